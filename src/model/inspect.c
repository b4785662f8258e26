// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Read-only views of a state kept for the user: the last consistent start's report.
#include <string.h>

#include "base/base.h"

int dal_state_init_report(const dal_state *st, dal_init_report *out) {
  if (!st || !out) return DAL_E_ARG;
  if (!st->init_rep_valid) {
    memset(out, 0, sizeof *out);
    out->phi_row = out->phidot_row = out->dq_coord = out->dqdot_coord = -1;
    return DAL_E_STATE;
  }
  *out = st->init_rep;
  return DAL_OK;
}
