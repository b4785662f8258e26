// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The index-1 ODE of redundant coordinates: y = (q, v), y' = (v, qddot) with qddot and lambda
// from the KKT system at acceleration level, optional Baumgarte terms (Baumgarte, Comput.
// Methods Appl. Mech. Eng. 1, 1972) and optional projection onto the manifold after each step.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "form.h"

/// position iterations of a projection after a step
#define PROJECT_MAXIT 10

// ---------------------------------------------------------------------------------------
// the index-1 ODE y = (q, v), y' = (v, qddot) with optional Baumgarte terms and projection

// The acceleration of coordinate i is not finite at a trial point: name what overflowed, the
// Baumgarte terms or the forces (or, both finite, the accelerations themselves). A retry.
static int index1_nonfinite(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, int i,
                            double t) {
  double al = opts->baumgarte_alpha, be = opts->baumgarte_beta;
  int forces_ok = 1, baum_ok = 1;
  for (int j = 0; j < sys->n; ++j)
    forces_ok &= isfinite(st->Q[j] - st->c[j]);
  for (int r = 0; r < sys->m; ++r) {
    double bt = 2.0 * al * st->phidot[r] + be * be * st->phi[r];
    baum_ok &= isfinite(bt) && isfinite(st->gphi[r] + bt);
  }
  if (!baum_ok)
    return DAL_FAIL(st, DAL__RETRY_NONFINITE,
                    "index-1: the Baumgarte terms 2 alpha (G v + dphi/dt) + beta^2 phi overflow at "
                    "t=%.17g, %s (opts.baumgarte_alpha = %g, opts.baumgarte_beta = %g): the "
                    "acceleration of coordinate '%s' is %g; use rates near the motion's own "
                    "frequencies",
                    t, dal__qtext(sys, st->q).s, al, be, sys->coord_names[i], st->qddot[i]);
  return DAL_FAIL(st, DAL__RETRY_NONFINITE,
                  "index-1: acceleration of coordinate '%s' is %g at t=%.17g, %s: %s",
                  sys->coord_names[i], st->qddot[i], t, dal__qtext(sys, st->q).s,
                  forces_ok ? "the forces are too large for the masses they move, or the KKT "
                              "matrix is nearly singular there (near-redundant constraints)"
                            : "the generalized forces overflow there");
}

static int index1_rhs(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t,
                      const double *y, double *ydot, unsigned need) {
  int n = sys->n, m = sys->m, rc;
  dal__qv_to_state(sys, st, t, y);
  if (m == 0) {
    rc = dal__eval(sys, st, need | DAL_P_ACC);
  } else {
    // G qddot = -(gamma_phi + 2 alpha (G v + dphi/dt) + beta^2 phi)
    // (the dense KKT matrix reads the lower M; the loop system of aba.c and the sparse KKT
    // matrix, assembled from the particle Jacobians, need none: its dense assembly was the
    // O(n^2) per right-hand side of bench/cliff.sh up to DAL_DENSE_M_MAX coordinates)
    unsigned late = DAL_P_ACC | DAL_P_OUT | DAL_P_POW; // formed here, after the KKT solve
    unsigned mass = dal__kkt_reads_M(sys, st) ? DAL_P_MLOW : 0u;
    rc = dal__eval(sys, st,
                   (need & ~late) | ((need & DAL_P_POW) ? DAL_P_PW : 0u) | DAL_P_CON | DAL_P_DYN |
                       mass);
    double al = opts->baumgarte_alpha, be = opts->baumgarte_beta;
    double *a = dal__kkt_scratch(st, 0), *b = dal__kkt_scratch(st, 1);
    if (rc == 0) rc = dal__kkt_factor(sys, st, DAL_KKT_MASS, "index-1 right-hand side");
    if (rc == 0) {
      for (int i = 0; i < n; ++i)
        a[i] = st->Q[i] - st->c[i];
      for (int r = 0; r < m; ++r)
        b[r] = -(st->gphi[r] + 2.0 * al * st->phidot[r] + be * be * st->phi[r]);
      dal__kkt_solve(sys, st, a, b, st->qddot, st->lambda);
      st->have |= DAL_P_ACC;
      if (need & (DAL_P_OUT | DAL_P_POW)) rc = dal__finish(sys, st);
      if (rc == 0 && (need & DAL_P_POW)) dal__power(sys, st);
    }
  }
  if (rc) return rc;
  for (int i = 0; i < n; ++i)
    if (!isfinite(st->qddot[i])) return index1_nonfinite(sys, st, opts, i, t);
  memcpy(ydot, st->qdot, (size_t)n * sizeof(double));
  memcpy(ydot + n, st->qddot, (size_t)n * sizeof(double));
  return DAL_OK;
}

static int index1_project(const dal_system *sys, dal_state *st, const dal_solve_opts *opts,
                          double t, double *y) {
  dal__qv_to_state(sys, st, t, y);
  // well below the integrator's absolute tolerance, above the rounding floor
  double tol = fmax(1e-2 * opts->atol, 4e-16 * fmax(1.0, dal__max_abs(st->q, sys->n, NULL)));
  int rc = dal__project_state(sys, st, tol, PROJECT_MAXIT, NULL);
  if (rc) return rc;
  dal__qv_from_state(sys, st, y);
  return DAL_OK;
}

const dal_ode_problem dal__problem_index1 = {
    .name = "index1",
    .size = dal__qv_size,
    .rhs = index1_rhs,
    .project = index1_project,
    .from_state = dal__qv_from_state,
    .to_state = dal__qv_to_state,
    .tol_factor = 0.2,
    .state_layout = 1,
};
