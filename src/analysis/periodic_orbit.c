// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Periodic orbits by Newton shooting on the exact state-transition matrix (single shooting):
// y(T; y0) - y0 = 0 with the Jacobian Phi - I, and for an autonomous scene the period as an
// unknown with the phase condition f(y0) . dy0 = 0 (Keller 1968; Seydel, Practical Bifurcation
// and Stability Analysis, 2010, sec. 7.3); on the constraint manifold the correction lives in
// its tangent space and the start is projected back after each step.
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis.h"
#include "dalembert/dae.h"

#define DAL_ORBIT_COOKIE 0x0eb17a11

dal_orbit_opts dal_default_orbit_opts(void) {
  dal_orbit_opts d;
  memset(&d, 0, sizeof d);
  d.cookie = DAL_ORBIT_COOKIE;
  d.period = 0.0;
  d.free_period = 0;
  d.xtol = 1e-9;
  d.max_iter = 30;
  d.solve = dal_default_solve_opts();
  d.solve.rtol = 1e-11;
  return d;
}

// indices of the multipliers nearest +1 (the trivial ones of an autonomous orbit)
static int nearest_one(int k2, const double *re, const double *im, int skip) {
  int best = -1;
  double bd = INFINITY;
  for (int i = 0; i < k2; ++i)
    if (i != skip && hypot(re[i] - 1.0, im[i]) < bd) {
      bd = hypot(re[i] - 1.0, im[i]);
      best = i;
    }
  return best;
}

int dal_periodic_orbit(const dal_system *sys, dal_state *st, const dal_orbit_opts *o, double *mu_re,
                       double *mu_im, dal_orbit_report *rep) {
  int rc = dal__check_pair(sys, st, "periodic_orbit");
  if (rc) return rc;
  if (!o || o->cookie != DAL_ORBIT_COOKIE)
    return DAL_FAIL(st, DAL_E_ARG,
                    "periodic_orbit: options not initialized: call dal_default_orbit_opts");
  if (!isfinite(o->period) || !(o->period > 0) || !(o->xtol > 0) || o->max_iter < 1)
    return DAL_FAIL(st, DAL_E_ARG,
                    "periodic_orbit: period = %g must be finite and > 0 (k times the drive's, "
                    "or a guess of a free period), xtol = %g > 0, max_iter = %d >= 1",
                    o->period, o->xtol, o->max_iter);
  int n = sys->n, k = n - sys->m, fp = o->free_period != 0;
  if (k <= 0)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED, "periodic_orbit: the system has no degrees of freedom");
  size_t sn = (size_t)n, sk = (size_t)k, n2 = 2 * sn, k2 = 2 * sk;
  size_t rows = n2 + (size_t)fp, cols = k2 + (size_t)fp;
  double *buf = calloc(n2 * n2 + 2 * n2 * k2 + rows * cols + 6 * n2 + 2 * rows + 8, sizeof(double));
  dal_tangent *tg = NULL;
  if (!buf || dal__tangent_create(sys, &tg)) {
    free(buf);
    return DAL_FAIL(st, DAL_E_NOMEM, "periodic_orbit: out of memory");
  }
  double *Phi = buf, *Z = Phi + n2 * n2, *PZ = Z + n2 * k2, *J = PZ + n2 * k2;
  double *y0 = J + rows * cols, *yT = y0 + n2;
  double *f0 = yT + n2, *f1 = f0 + n2, *keep = f1 + n2, *b = keep + n2, *sv = b + rows;
  double t0 = st->t, T = o->period, res = INFINITY;
  memcpy(keep, st->q, sn * sizeof(double));
  memcpy(keep + sn, st->qdot, sn * sizeof(double));
  memcpy(y0, keep, n2 * sizeof(double));
  int it = 0;
  for (;; ++it) {
    // the start on the manifold, its tangent basis and f(y0)
    if ((rc = dal_state_set(sys, st, t0, y0, y0 + sn)) != 0) break;
    if (sys->m > 0 && (rc = dal_make_consistent(sys, st, 0.0, NULL)) != 0) break;
    if ((rc = dal_forward(sys, st)) != 0) break;
    memcpy(y0, st->q, sn * sizeof(double));
    memcpy(y0 + sn, st->qdot, sn * sizeof(double));
    memcpy(f0, st->qdot, sn * sizeof(double));
    memcpy(f0 + sn, st->qddot, sn * sizeof(double));
    if (sys->m > 0 && (rc = dal__tangent_eval(sys, st, tg, 0)) != 0) break;
    if ((rc = dal__tangent_manifold(sys, st, tg, Z, NULL)) != 0) break;
    // one arc: y(T), Phi and f(y(T))
    if ((rc = dal_state_transition(sys, st, &o->solve, t0 + T, Phi, 0, NULL, NULL)) != 0) break;
    memcpy(yT, st->q, sn * sizeof(double));
    memcpy(yT + sn, st->qdot, sn * sizeof(double));
    memcpy(f1, st->qdot, sn * sizeof(double));
    memcpy(f1 + sn, st->qddot, sn * sizeof(double));
    res = 0.0;
    for (size_t i = 0; i < n2; ++i)
      res = fmax(res, fabs(yT[i] - y0[i]) / (1.0 + fabs(y0[i])));
    if (!(res <= INFINITY)) res = INFINITY;
    if (res <= o->xtol) break;
    if (it >= o->max_iter || !isfinite(res)) {
      rc = DAL_FAIL(st, DAL_E_CONV,
                    "periodic_orbit: Newton shooting did not converge in %d iterations (return "
                    "gap %.3g against xtol %.3g, start %s, period %.17g); start nearer an orbit "
                    "(a few periods of a run, or a stroboscopic section point), or shorten the "
                    "period",
                    it, res, o->xtol, dal__qtext(sys, y0).s, T);
      break;
    }
    // the Newton system [(Phi - I) Z, f1; f0' Z, 0] (dxi; dT) = (y0 - yT; 0), least squares
    for (size_t j = 0; j < k2; ++j)
      for (size_t i = 0; i < n2; ++i) {
        double s = -Z[j * n2 + i];
        for (size_t l = 0; l < n2; ++l)
          s += Phi[l * n2 + i] * Z[j * n2 + l];
        J[j * rows + i] = s;
      }
    if (fp) {
      for (size_t i = 0; i < n2; ++i)
        J[k2 * rows + i] = f1[i];
      for (size_t j = 0; j < k2; ++j) {
        double s = 0.0;
        for (size_t l = 0; l < n2; ++l)
          s += f0[l] * Z[j * n2 + l];
        J[j * rows + n2] = s;
      }
      J[k2 * rows + n2] = 0.0;
      b[n2] = 0.0;
    }
    for (size_t i = 0; i < n2; ++i)
      b[i] = y0[i] - yT[i];
    // minimum norm by SVD: a conservative autonomous orbit lies in a family (energy), whose
    // direction Phi - I leaves singular even with the phase condition
    lapack_int rank = 0;
    lapack_int info = LAPACKE_dgelsd(LAPACK_COL_MAJOR, (lapack_int)rows, (lapack_int)cols, 1, J,
                                     (lapack_int)rows, b, (lapack_int)rows, sv, 1e-10, &rank);
    if (info != 0 || (!fp && rank < (lapack_int)cols)) {
      rc = DAL_FAIL(st, DAL_E_SINGULAR,
                    "periodic_orbit: the shooting matrix Phi - I is singular (rank %d of %d, "
                    "LAPACK dgelsd info %d) at iteration %d: a multiplier is 1 (a fold, or an "
                    "autonomous scene: set free_period)",
                    (int)rank, (int)cols, (int)info, it);
      break;
    }
    for (size_t i = 0; i < n2; ++i) {
      double s = 0.0;
      for (size_t j = 0; j < k2; ++j)
        s += Z[j * n2 + i] * b[j];
      y0[i] += s;
    }
    if (fp) {
      T += b[k2];
      if (!(T > 0) || !isfinite(T)) {
        rc = DAL_FAIL(st, DAL_E_CONV,
                      "periodic_orbit: the period went to %g at iteration %d: start nearer "
                      "an orbit",
                      T, it);
        break;
      }
    }
  }
  dal__tangent_free(tg);
  if (rc) {
    rc = dal__restore_state(sys, st, t0, keep, rc);
    free(buf);
    return rc;
  }
  // the orbit's multipliers (the state back at the start of the orbit)
  double *re = Phi, *im = Phi + k2; // Phi is free now
  dal_floquet_report fr;
  rc = dal__restore_state(sys, st, t0, y0, DAL_OK);
  if (!rc) rc = dal_floquet(sys, st, &o->solve, T, re, im, NULL, &fr);
  if (!rc && fp) {
    // the trivial multiplier along the orbit, and its partner of the energy family when the
    // flow preserves volume, leave the verdict
    int i1 = nearest_one((int)k2, re, im, -1), i2 = -1;
    if (fabs(fr.det - 1.0) <= 10 * fr.accuracy + 1e-9) i2 = nearest_one((int)k2, re, im, i1);
    fr.verdict = dal__floquet_verdict((int)k2, re, im, fr.accuracy, i1, i2, &fr.max_abs);
  }
  if (!rc) {
    if (mu_re) memcpy(mu_re, re, k2 * sizeof(double));
    if (mu_im) memcpy(mu_im, im, k2 * sizeof(double));
    if (rep) {
      rep->iterations = it;
      rep->period = T;
      rep->residual = res;
      rep->floquet = fr;
    }
  }
  free(buf);
  return rc;
}
