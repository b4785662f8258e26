// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Consistent initialization and manifold projection of redundant coordinates.
//
// Positions: minimum-norm Gauss-Newton dq = -G'(G G')^-1 phi; velocities: M-orthogonal
// projection dv = -M^-1 G'(G M^-1 G')^-1 (G v + dphi/dt); both through the KKT system
// (Hairer, Lubich and Wanner, Geometric Numerical Integration, 2nd ed., IV.4 and VII.1;
// Hairer and Wanner, Solving ODEs II, VII.2). Index-1 with Baumgarte terms: Baumgarte,
// Comput. Methods Appl. Mech. Eng. 1, 1972.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "form.h"

/// position iterations of the consistent initialization
#define INIT_MAXIT 50

double dal__max_abs(const double *x, int n, int *at) {
  double mx = 0.0;
  if (at) *at = n > 0 ? 0 : -1;
  for (int i = 0; i < n; ++i)
    if (fabs(x[i]) > mx || isnan(x[i])) {
      mx = fabs(x[i]);
      if (at) *at = i;
      if (isnan(mx)) break;
    }
  return mx;
}

// positions onto phi = 0: damped minimum-norm Gauss-Newton
// residuals above tol left on two or more constraints where Gauss-Newton stalled: each step
// that reduces one increases another, so they conflict (at least near this guess); names them
// all (DAL_E_CONSTRAINT), or 0 when fewer than two constraints are left
static int conflicting_constraints(const dal_system *sys, dal_state *st, double tol) {
  char names[256] = "", qs[256];
  int nbad = 0, last = -1;
  size_t used = 0;
  for (int r = 0; r < sys->m; ++r) {
    int ci = sys->row_con[r];
    if (!(fabs(st->phi[r]) > tol) || ci == last) continue;
    last = ci;
    if (nbad++ < 4 && used < sizeof names)
      used += (size_t)snprintf(names + used, sizeof names - used, "%s'%s' (%.3g)",
                               nbad > 1 ? " and " : "", sys->con[ci].name, st->phi[r]);
  }
  if (nbad < 2) return DAL_OK;
  dal__fmt_q(sys, st->q, qs, sizeof qs);
  return DAL_FAIL(st, DAL_E_CONSTRAINT,
                  "constraints %s%s conflict: Gauss-Newton stalls at t=%.17g, %s with "
                  "these residuals > %.3g (a step that reduces one increases another, or "
                  "their gradients become dependent); no "
                  "position near this guess satisfies them together: fix their parameters, "
                  "or start from a guess near a common solution",
                  names, nbad > 4 ? " and others" : "", st->t, qs, tol);
}

static int project_positions(const dal_system *sys, dal_state *st, double tol, int maxit,
                             int *iters) {
  int n = sys->n, m = sys->m, worst = 0, it = 0, rc, stalled = 0;
  double *zero = dal__kkt_scratch(st, 0), *b = dal__kkt_scratch(st, 1);
  double *q0 = dal__kkt_scratch(st, 2), *dq = dal__kkt_scratch(st, 3);
  memset(zero, 0, (size_t)n * sizeof(double));
  double res = dal__max_abs(st->phi, m, &worst);
  for (; it < maxit && !(res <= tol); ++it) {
    if (!isfinite(res)) break;
    rc = dal__kkt_factor(sys, st, DAL_KKT_IDENTITY, "projection onto the constraints");
    if (rc == DAL_E_SINGULAR && it > 0) {
      // the iteration ran into a point where the constraint gradients vanish or become
      // dependent, with residuals left: a stationary point of |phi|, no solution near it
      stalled = 2;
      break;
    }
    if (rc) return rc;
    for (int r = 0; r < m; ++r)
      b[r] = -st->phi[r];
    dal__kkt_solve(sys, st, zero, b, dq, b);
    memcpy(q0, st->q, (size_t)n * sizeof(double));
    // backtrack while the residual grows (far guesses); accept the full step otherwise
    double s = 1.0, nres = INFINITY;
    for (int k = 0; k < 8; ++k, s *= 0.5) {
      for (int j = 0; j < n; ++j)
        st->q[j] = q0[j] + s * dq[j];
      rc = dal__eval_constraints(sys, st);
      if (rc < 0 && rc != DAL_E_DOMAIN) return rc;
      nres = rc ? INFINITY : dal__max_abs(st->phi, m, &worst);
      if (nres < res || nres <= tol) break;
    }
    if (!(nres < res) && !(nres <= tol)) {
      // no decrease along the Gauss-Newton direction: stalled (conflicting constraints)
      memcpy(st->q, q0, (size_t)n * sizeof(double));
      rc = dal__eval_constraints(sys, st);
      if (rc) return rc;
      res = dal__max_abs(st->phi, m, &worst);
      ++it;
      stalled = 1;
      break;
    }
    res = nres;
  }
  if (iters) *iters = it;
  // stalled with residuals left on two or more constraints: they conflict
  if (!(res <= tol) && stalled && (rc = conflicting_constraints(sys, st, tol)) != 0) return rc;
  if (!(res <= tol)) {
    return DAL_FAIL(st, DAL_E_INIT,
                    "positions cannot be brought onto the constraints at t=%.17g: after %d "
                    "Gauss-Newton iterations constraint '%s' (row %d) still has residual %.3g "
                    "> %.3g at %s%s; the constraints conflict (no position satisfies them all) "
                    "or the initial guess is too far from the constraint manifold",
                    st->t, it, sys->con[sys->row_con[worst]].name, worst, res, tol,
                    dal__qtext(sys, st->q).s,
                    stalled == 2 ? ", where the constraint gradients vanish (the residual is "
                                   "stationary there)"
                                 : "");
  }
  return DAL_OK;
}

// velocities onto G v + dphi/dt = 0, M-orthogonally (kinematics at q current)
static int project_velocities(const dal_system *sys, dal_state *st) {
  int n = sys->n, m = sys->m, rc;
  double *zero = dal__kkt_scratch(st, 0), *b = dal__kkt_scratch(st, 1);
  double *dv = dal__kkt_scratch(st, 3);
  if (dal__max_abs(st->phidot, m, NULL) == 0.0) return DAL_OK;
  // M at q (dense systems assemble it in dynamics; M depends on q and t only) where the KKT
  // matrix reads it (the recursion of aba.c and the sparse KKT matrix need no dense M)
  unsigned mass = dal__kkt_reads_M(sys, st) ? DAL_P_MLOW : 0u;
  if (sys->dense_M && !sys->aba && (rc = dal__eval(sys, st, DAL_P_CON | mass)) != 0) return rc;
  rc = dal__kkt_factor(sys, st, DAL_KKT_MASS, "velocity projection");
  if (rc) return rc;
  memset(zero, 0, (size_t)n * sizeof(double));
  for (int r = 0; r < m; ++r)
    b[r] = -st->phidot[r];
  dal__kkt_solve(sys, st, zero, b, dv, b);
  for (int j = 0; j < n; ++j)
    st->qdot[j] += dv[j];
  return dal__eval_constraints(sys, st);
}

int dal__project_state(const dal_system *sys, dal_state *st, double tol, int maxit, int *iters) {
  if (iters) *iters = 0;
  if (sys->m == 0) return DAL_OK;
  int rc = dal__eval_constraints(sys, st);
  if (rc) return rc;
  rc = project_positions(sys, st, tol, maxit, iters);
  if (rc) return rc;
  return project_velocities(sys, st);
}

// the consistent initialization without touching integrator memory
static int make_consistent(const dal_system *sys, dal_state *st, double tol, double max_move,
                           dal_init_report *rep) {
  int n = sys->n, m = sys->m, rc;
  memset(rep, 0, sizeof *rep);
  rep->phi_row = rep->phidot_row = rep->dq_coord = rep->dqdot_coord = -1;
  if (!(tol > 0.0)) tol = 1e-12 * fmax(1.0, dal__max_abs(st->q, n, NULL));
  rep->tol = tol;
  if (m == 0) {
    rc = dal__eval(sys, st, DAL_P_ALL);
    return dal__public_status(rc);
  }
  double *save = malloc(2 * (size_t)n * sizeof(double));
  if (!save) return DAL_FAIL(st, DAL_E_NOMEM, "consistent initialization: out of memory");
  memcpy(save, st->q, (size_t)n * sizeof(double));
  memcpy(save + n, st->qdot, (size_t)n * sizeof(double));
  rc = dal__eval_constraints(sys, st);
  if (rc == 0) {
    rep->phi_before = dal__max_abs(st->phi, m, &rep->phi_row);
    rep->phidot_before = dal__max_abs(st->phidot, m, &rep->phidot_row);
    rc = project_positions(sys, st, tol, INIT_MAXIT, &rep->iterations);
  }
  if (rc == 0) {
    rep->phi_after = dal__max_abs(st->phi, m, NULL);
    rc = project_velocities(sys, st);
  }
  if (rc == 0) {
    rep->phidot_after = dal__max_abs(st->phidot, m, NULL);
    rc = dal__eval(sys, st, DAL_P_ALL);
  }
  if (rc) {
    // the state keeps what the caller gave
    memcpy(st->q, save, (size_t)n * sizeof(double));
    memcpy(st->qdot, save + n, (size_t)n * sizeof(double));
    dal__state_moved(st);
    free(save);
    return dal__public_status(rc);
  }
  for (int j = 0; j < n; ++j) {
    double dq = fabs(st->q[j] - save[j]), dv = fabs(st->qdot[j] - save[n + j]);
    if (dq > rep->dq_max) {
      rep->dq_max = dq;
      rep->dq_coord = j;
    }
    if (dv > rep->dqdot_max) {
      rep->dqdot_max = dv;
      rep->dqdot_coord = j;
    }
  }
  // keep the report in the state; a move beyond the caller's limit is refused
  st->init_rep = *rep;
  st->init_rep_valid = 1;
  if (max_move > 0 && rep->dq_max > max_move) {
    int j = rep->dq_coord;
    double qnew = st->q[j];
    memcpy(st->q, save, (size_t)n * sizeof(double));
    memcpy(st->qdot, save + n, (size_t)n * sizeof(double));
    dal__state_moved(st);
    rc = DAL_FAIL(st, DAL_E_INIT,
                  "consistent start at t=%.17g would move coordinate '%s' by %.3g (from %.9g to "
                  "%.9g), more than opts.init_max_move = %g; the largest constraint residual "
                  "was %.3g on '%s'. Start closer to the constraints or raise the limit; the "
                  "state is unchanged (dal_state_init_report has the full report)",
                  st->t, sys->coord_names[j], rep->dq_max, save[j], qnew, max_move, rep->phi_before,
                  rep->phi_row >= 0 ? sys->con[sys->row_con[rep->phi_row]].name : "-");
    free(save);
    return rc;
  }
  free(save);
  return DAL_OK;
}

int dal_make_consistent(const dal_system *sys, dal_state *st, double tol, dal_init_report *rep) {
  int pair = dal__check_pair(sys, st, "make_consistent");
  if (pair) return pair;
  if ((pair = dal__check_idle(st, "make_consistent")) != 0) return pair;
  if (!isfinite(tol))
    return DAL_FAIL(st, DAL_E_NONFINITE,
                    "make_consistent: tolerance %g is not finite; give a finite tolerance (<= 0: "
                    "automatic)",
                    tol);
  dal_init_report local;
  dal__integ_reset(st);
  return make_consistent(sys, st, tol, 0.0, rep ? rep : &local);
}

// used by the IDA driver: rank check (its report into *crep, nullable), then the consistent
// initialization
int dal__dae_start_checked(const dal_system *sys, dal_state *st, double max_move,
                           dal_init_report *rep, dal_constraint_report *crep) {
  dal_init_report local;
  int rc = dal__eval_constraints(sys, st);
  if (rc == 0) rc = dal__check_rank(sys, st, crep);
  if (rc == 0) rc = make_consistent(sys, st, 0.0, max_move, rep ? rep : &local);
  return dal__public_status(rc);
}

int dal__dae_start(const dal_system *sys, dal_state *st, double max_move, dal_init_report *rep) {
  return dal__dae_start_checked(sys, st, max_move, rep, NULL);
}
