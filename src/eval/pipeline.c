// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The evaluation pipeline: a caller asks for the products it needs at the state's (t, q, qdot)
// and gets those and what they depend on, each marked current (MuJoCo's staged forward).
//
// Stages: kinematics (r, v, gamma, drdt; J when asked or needed) -> constraint rows ->
// forces, Q, c and energies (and M when asked or needed) -> accelerations (Cholesky of M, or
// the KKT system with multipliers; for trees the articulated-body recursion of aba.c, with
// the m x m loop system for multipliers) -> outputs (particle accelerations and reactions).
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "eval.h"
#include "linalg/linalg.h"

static int first_nonfinite(const double *x, int n);
static int accel_nonfinite(const dal_system *sys, dal_state *st, int i, int mult);

// a Lagrangian system: A = d2L/dqdot2 in st->M, qddot, and h = E unless only the
// accelerations are asked for (an integrator's right-hand side)
static int eval_lagrangian(const dal_system *sys, dal_state *st, unsigned need) {
  double h;
  int energies = (need & ~(DAL_P_KIN | DAL_P_ACC)) != 0;
  int rc = dal__lagrangian_terms(sys, st, st->M, st->qddot, &h, energies);
  if (rc) return rc;
  st->have |= DAL_P_M | DAL_P_MLOW | (energies ? DAL_P_DYN : 0u);
  int bad = -1;
  if (dal__chol_solve(sys->n, st->M, st->L, st->qddot, &bad)) {
    return DAL_FAIL(st, DAL_E_SINGULAR,
                    "d2L/dqdot2 singular or not positive definite at t=%.17g, %s: coordinate "
                    "'%s' is degenerate; use another chart",
                    st->t, dal__qtext(sys, st->q).s, sys->coord_names[bad]);
  }
  int i = first_nonfinite(st->qddot, sys->n);
  if (i >= 0) return accel_nonfinite(sys, st, i, 0);
  st->have |= DAL_P_ACC | DAL_P_KIN | DAL_P_J | DAL_P_CON;
  if (!energies) return DAL_OK;
  // T, U, T2, T1, T0 come from dal__lagrangian_terms (read off L, system.h)
  st->en.E = st->en.T + st->en.U;
  st->en.h = h;
  st->have |= DAL_P_OUT;
  return DAL_OK;
}

// A non-finite point is never handed to the model: it comes from an integrator whose trial
// step overflowed (or whose step size did), so it is a retry for that integrator, not a
// domain error of the first map that would see it.
static int check_point(const dal_system *sys, dal_state *st) {
  int bad = -1, vel = 0;
  for (int i = 0; i < sys->n && bad < 0; ++i)
    if (!isfinite(st->q[i]))
      bad = i;
    else if (!isfinite(st->qdot[i]))
      bad = i, vel = 1;
  if (isfinite(st->t) && bad < 0) return DAL_OK;
  double x = bad < 0 ? st->t : vel ? st->qdot[bad] : st->q[bad];
  DAL_FAIL(st, DAL__RETRY_NONFINITE,
           "the integrator's trial point is not finite (%s%s%s = %g at t=%g): a step overflowed, "
           "or its step size did (velocities or accelerations too large for its error control); "
           "rescale the model's units, or bound the step with opts.h0/opts.hmax",
           bad < 0 ? "time"
           : vel   ? "velocity of '"
                   : "coordinate '",
           bad < 0 ? "" : sys->coord_names[bad], bad < 0 ? "" : "'", x, st->t);
  return DAL__RETRY_NONFINITE;
}

// index of the first non-finite entry of x (n), or -1
static int first_nonfinite(const double *x, int n) {
  for (int i = 0; i < n; ++i)
    if (!isfinite(x[i])) return i;
  return -1;
}

// Accelerations (or multipliers) that are not finite although the factorization passed:
// with a dense M whose Cholesky pivots spread over more than DAL_NEAR_SINGULAR the chart is
// nearly singular there (DAL__RETRY_SINGULAR), otherwise the forces are too large for the
// masses they move (DAL__RETRY_NONFINITE). A retry for an integrator, a failure in
// dal_forward: no product is handed out non-finite.
static int accel_nonfinite(const dal_system *sys, dal_state *st, int i, int mult) {
  int n = sys->n;
  if (!sys->m && st->L && !sys->aba) { // the Cholesky route's pivots (the recursion has none)
    double pmin = INFINITY, pmax = 0.0;
    for (int j = 0; j < n; ++j) {
      double p = st->L[(size_t)j * n + j] * st->L[(size_t)j * n + j];
      pmin = fmin(pmin, p);
      pmax = fmax(pmax, p);
    }
    if (!(pmin > DAL_NEAR_SINGULAR * pmax))
      return DAL_FAIL(st, DAL__RETRY_SINGULAR,
                      "mass matrix nearly singular at t=%.17g, %s: the acceleration of "
                      "coordinate '%s' is %g (pivot ratio %.3g; it moves almost no mass there, "
                      "e.g. a chart singularity such as a spherical pendulum's pole); use "
                      "redundant coordinates with constraints, or another chart",
                      st->t, dal__qtext(sys, st->q).s, sys->coord_names[i], st->qddot[i],
                      pmin / pmax);
  }
  if (mult)
    return DAL_FAIL(st, DAL__RETRY_NONFINITE,
                    "multiplier of constraint '%s' (row %d) is %g at t=%.17g, %s: the constraint "
                    "forces overflow (forces too large for the masses, or near-redundant "
                    "constraints)",
                    sys->con[sys->row_con[i]].name, i, st->lambda[i], st->t,
                    dal__qtext(sys, st->q).s);
  return DAL_FAIL(st, DAL__RETRY_NONFINITE,
                  "acceleration of coordinate '%s' is %g at t=%.17g, %s: the forces are too large "
                  "for the masses they move (or overflow themselves); the state has left the "
                  "range the model can represent, or the units are badly scaled",
                  sys->coord_names[i], st->qddot[i], st->t, dal__qtext(sys, st->q).s);
}

// Products of the dynamics stage that must be finite: c and the assembled part of M (a sum
// of finite terms may still overflow). A retry naming the entry.
static int check_dynamics(const dal_system *sys, dal_state *st) {
  int n = sys->n, i = first_nonfinite(st->c, n);
  if (i >= 0)
    return DAL_FAIL(st, DAL__RETRY_NONFINITE,
                    "velocity-product term c of coordinate '%s' is %g at t=%.17g: the velocities "
                    "are too large for double precision there",
                    sys->coord_names[i], st->c[i], st->t);
  if (st->have & DAL_P_MLOW)
    for (int j = 0; j < n; ++j)
      if ((i = first_nonfinite(st->M + (size_t)j * n + j, n - j)) >= 0)
        return DAL_FAIL(st, DAL__RETRY_NONFINITE,
                        "mass matrix entry ('%s', '%s') is %g at t=%.17g: the masses or the "
                        "coordinate map's derivatives are too large for double precision",
                        sys->coord_names[j + i], sys->coord_names[j], st->M[(size_t)j * n + j + i],
                        st->t);
  return DAL_OK;
}

void dal__power(const dal_system *sys, dal_state *st) {
  DAL_NEED(st, DAL_P_OUT | DAL_P_PW);
  // reactions of moving maps and multipliers of moving constraints do work; fixed ones do not
  double p = st->pw[0] + st->pw[1];
  for (int i = 0; i < sys->N * sys->dim; ++i)
    p += st->N[i] * st->drdt[i];
  for (int r = 0; r < sys->m; ++r)
    p -= st->lambda[r] * st->phit[r];
  st->power = p;
  st->have |= DAL_P_POW;
}

int dal__eval(const dal_system *sys, dal_state *st, unsigned need) {
  int m = sys->m, rc;
  st->have = 0;
  if ((rc = check_point(sys, st)) != 0) return rc;
  if (sys->lag) return eval_lagrangian(sys, st, need);
  // accelerations alone on the recursion, with every force on the particles: the forces F are
  // all it reads (aba.c), so Q, c and the energies are skipped (an integrator's right-hand side)
  int lean = sys->aba && m == 0 && !sys->npotq && !sys->ngenforce &&
             (need & ~(DAL_P_KIN | DAL_P_ACC)) == 0 && (need & DAL_P_ACC);
  if (need & DAL_P_POW) need |= DAL_P_OUT | DAL_P_PW;
  if (need & DAL_P_PW) need |= DAL_P_DYN;
  // what each product needs: outputs need accelerations; accelerations need forces and M
  // (Cholesky when m = 0, or the KKT system, whose dense form reads the lower M and whose
  // sparse form reads J); constraint rows need J
  // (the recursion needs neither M nor J: its constraint rows come from the local blocks);
  // large recursive trees store no J at all
  if (need & DAL_P_OUT) need |= DAL_P_ACC;
  if (need & DAL_P_ACC) {
    need |= DAL_P_DYN | (m ? DAL_P_CON : 0u);
    if (sys->dense_M && !sys->aba) need |= DAL_P_MLOW;
  }
  if ((need & DAL_P_CON) && !sys->aba) need |= DAL_P_J;
  if (need & DAL_P_M) need |= DAL_P_MLOW;
  if (need & DAL_P_MLOW) need |= DAL_P_DYN;
  // the recursion reads no global Jacobian: for an evaluated state (all products) they are left
  // to dal_state_jacobian, which forms them from the local blocks (O(N^2) storage and work
  // otherwise for a chain, once per output); callers that read J ask for it alone
  if (!sys->store_J || (sys->aba && (need & DAL_P_ALL) == DAL_P_ALL)) need &= ~DAL_P_J;
  if ((rc = dal__kinematics(sys, st, (need & DAL_P_J) != 0)) != 0) return rc;
  // M of a tree with a link that is not a translation is assembled through J
  if ((need & DAL_P_MLOW) && sys->dense_M && !st->tree && !(st->have & DAL_P_J))
    dal__jacobians(sys, st);
  if ((need & DAL_P_CON) && m && (rc = dal__constraints(sys, st)) != 0) return rc;
  if (need & DAL_P_CON) st->have |= DAL_P_CON;
  if (lean) {
    // (a failing force is reported as dal__dynamics reports it)
    if ((rc = dal__forces(sys, st)) != 0)
      return rc == DAL_E_NONFINITE ? dal__blame_forces(sys, st) : rc;
    if (dal__aba_accel(sys, st) == DAL_OK && first_nonfinite(st->qddot, sys->n) < 0) {
      st->have |= DAL_P_ACC;
      return DAL_OK;
    }
    // a degenerate coordinate or accelerations that overflow: the whole evaluation below
    // names the cause, as it always has
    st->have &= DAL_P_KIN | DAL_P_J | DAL_P_CON;
  }
  if (need & DAL_P_DYN) {
    int want_M = (need & DAL_P_M) ? 2 : (need & DAL_P_MLOW) ? 1 : 0;
    st->pw[0] = st->pw[1] = 0.0;
    // a non-finite force sum: name the built-in force that overflowed (blame.c)
    if ((rc = dal__dynamics(sys, st, want_M, (need & DAL_P_PW) ? st->pw : NULL)) != 0)
      return rc == DAL_E_NONFINITE ? dal__blame_forces(sys, st) : rc;
    if ((rc = check_dynamics(sys, st)) != 0) {
      st->have &= ~(DAL_P_DYN | DAL_P_M | DAL_P_MLOW);
      return rc;
    }
    if (need & DAL_P_PW) st->have |= DAL_P_PW;
  }
  if (need & DAL_P_ACC) {
    rc = m          ? dal__solve_kkt(sys, st)
         : sys->aba ? dal__aba_accel(sys, st)
                    : dal__solve_unconstrained(sys, st);
    if (rc) return rc;
    int i = first_nonfinite(st->qddot, sys->n), l = i < 0 ? first_nonfinite(st->lambda, m) : -1;
    if (i >= 0 || l >= 0) return accel_nonfinite(sys, st, i >= 0 ? i : l, i < 0);
    st->have |= DAL_P_ACC;
  }
  if (need & DAL_P_OUT) {
    if ((rc = dal__finish(sys, st)) != 0) return rc;
    int d = sys->dim, k = first_nonfinite(st->a, sys->N * d);
    if (k < 0) k = first_nonfinite(st->N, sys->N * d);
    if (k >= 0) {
      st->have &= ~DAL_P_OUT;
      return DAL_FAIL(st, DAL__RETRY_NONFINITE,
                      "acceleration or reaction force of particle '%s' overflows at t=%.17g "
                      "(component %d): the coordinate map's derivatives or the masses are too "
                      "large for double precision there",
                      sys->part_names[k / d], st->t, k % d);
    }
  }
  if (need & DAL_P_POW) dal__power(sys, st);
  return DAL_OK;
}

int dal__eval_constraints(const dal_system *sys, dal_state *st) {
  dal__state_moved(st);
  return dal__eval(sys, st, DAL_P_CON);
}
