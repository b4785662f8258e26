// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Redundant-constraint diagnostics for users: dal_check_constraints evaluates the constraint
// rows and runs the rank test of kkt.c (rank-revealing QR of G').
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "form.h"

int dal_check_constraints(const dal_system *sys, dal_state *st, dal_constraint_report *rep) {
  int pair = dal__check_pair(sys, st, "check_constraints");
  if (pair) return pair;
  if (rep) {
    memset(rep, 0, sizeof *rep);
    rep->m = sys->m;
    rep->rank = sys->m;
    rep->rmin = 1.0;
  }
  if (sys->m == 0) return DAL_OK;
  int rc = dal__eval_constraints(sys, st);
  rc = dal__public_status(rc);
  if (rc) return rc;
  return dal__check_rank(sys, st, rep);
}
