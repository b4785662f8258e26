// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The integrator memory kept in a state: dropping it, with the factorization history it holds.
#include "base/base.h"

void dal__integ_reset(dal_state *st) {
  if (st->integ && st->integ_free) st->integ_free(st->integ);
  st->integ = NULL;
  st->integ_free = NULL;
  dal__kkt_reset(st->kkt);
}
