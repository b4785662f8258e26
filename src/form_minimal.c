// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The minimal-coordinate ODE: y = (q, qdot), f = (qdot, qddot) from M qddot = Q - c.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "solve_internal.h"

static int minimal_size(const dal_system *sys) { return 2 * sys->n; }

static void minimal_to_state(const dal_system *sys, dal_state *st, double t, const double *y) {
  size_t n = (size_t)sys->n;
  st->t = t;
  memcpy(st->q, y, n * sizeof(double));
  memcpy(st->qdot, y + n, n * sizeof(double));
  dal__state_moved(st);
}

static void minimal_from_state(const dal_system *sys, const dal_state *st, double *y) {
  size_t n = (size_t)sys->n;
  memcpy(y, st->q, n * sizeof(double));
  memcpy(y + n, st->qdot, n * sizeof(double));
}

// The acceleration of coordinate i is not finite although the Cholesky factorization of M
// passed: with a nearly singular M (its pivots spread over more than DAL_NEAR_SINGULAR, a
// chart singularity) the cause is the chart, otherwise the forces are too large for the
// inertia (or overflowed themselves). Either is a retry whose cause names the coordinate.
static int minimal_nonfinite(const dal_system *sys, dal_state *st, int i, double t) {
  int n = sys->n;
  double pmin = INFINITY, pmax = 0.0;
  for (int j = 0; j < n; ++j) {
    double p = st->L[(size_t)j * n + j] * st->L[(size_t)j * n + j];
    pmin = fmin(pmin, p);
    pmax = fmax(pmax, p);
  }
  char qs[256];
  dal__fmt_q(sys, st->q, qs, sizeof qs);
  if (!(pmin > DAL_NEAR_SINGULAR * pmax))
    return DAL_FAIL(st, DAL__RETRY_SINGULAR,
                    "mass matrix nearly singular at t=%.17g, %s: the acceleration of coordinate "
                    "'%s' is %g (pivot ratio %.3g; it moves almost no mass there, e.g. a chart "
                    "singularity such as a spherical pendulum's pole); use redundant coordinates "
                    "with constraints, or another chart",
                    t, qs, sys->coord_names[i], st->qddot[i], pmin / pmax);
  return DAL_FAIL(st, DAL__RETRY_NONFINITE,
                  "acceleration of coordinate '%s' is %g at t=%.17g, %s: the forces are too large "
                  "for the masses they move (or overflow themselves); the state has left the "
                  "range the model can represent, or the units are badly scaled",
                  sys->coord_names[i], st->qddot[i], t, qs);
}

static int minimal_rhs(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t,
                       const double *y, double *ydot, unsigned need) {
  (void)opts;
  int n = sys->n;
  minimal_to_state(sys, st, t, y);
  int rc = dal__eval(sys, st, need | DAL_P_ACC);
  if (rc) return rc;
  for (int i = 0; i < n; ++i) {
    // a non-finite acceleration at a trial point: a smaller step may avoid it
    if (!isfinite(st->qddot[i])) return minimal_nonfinite(sys, st, i, t);
    ydot[i] = y[n + i];
    ydot[n + i] = st->qddot[i];
  }
  return DAL_OK;
}

const dal_ode_problem dal__problem_minimal = {"minimal", minimal_size,       minimal_rhs,
                                              NULL,      minimal_from_state, minimal_to_state};

