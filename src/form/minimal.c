// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The minimal-coordinate ODE: y = (q, qdot), f = (qdot, qddot) from M qddot = Q - c.
#include <string.h>

#include "codegen/codegen.h"
#include "form.h"

int dal__qv_size(const dal_system *sys) { return 2 * sys->n; }

void dal__qv_to_state(const dal_system *sys, dal_state *st, double t, const double *y) {
  size_t n = (size_t)sys->n;
  st->t = t;
  memcpy(st->q, y, n * sizeof(double));
  memcpy(st->qdot, y + n, n * sizeof(double));
  dal__state_moved(st);
}

void dal__qv_from_state(const dal_system *sys, const dal_state *st, double *y) {
  size_t n = (size_t)sys->n;
  memcpy(y, st->q, n * sizeof(double));
  memcpy(y + n, st->qdot, n * sizeof(double));
}

static int minimal_rhs(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t,
                       const double *y, double *ydot, unsigned need) {
  (void)opts;
  int n = sys->n;
  dal__qv_to_state(sys, st, t, y);
  // compiled equations of motion (src/codegen/eom.c) when qddot alone is asked for; where they
  // decline, the general path runs and names the cause
  if (sys->eom && need == DAL_P_ACC && !dal__eom_qddot(sys, st, t, y, y + n, ydot + n)) {
    memcpy(ydot, y + n, (size_t)n * sizeof(double));
    return DAL_OK;
  }
  int rc = dal__eval(sys, st, need | DAL_P_ACC);
  if (rc) return rc;
  // (the accelerations are finite: dal__eval gives a retry otherwise)
  for (int i = 0; i < n; ++i) {
    ydot[i] = y[n + i];
    ydot[n + i] = st->qddot[i];
  }
  return DAL_OK;
}

const dal_ode_problem dal__problem_minimal = {
    .name = "minimal",
    .size = dal__qv_size,
    .rhs = minimal_rhs,
    .project = NULL,
    .from_state = dal__qv_from_state,
    .to_state = dal__qv_to_state,
    .tol_factor = 1.0,
    .state_layout = 1,
};
