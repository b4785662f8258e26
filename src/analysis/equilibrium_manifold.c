// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Equilibria of constrained systems by Newton's method on the manifold: the static KKT system
//   c(q, 0) - Q(q) - G(q)' lambda = 0,   phi(q, t) = 0
// in (q, lambda) with its exact Jacobian [K - sum lambda_i Hess phi_i, -G'; G, 0] from the
// tangent (jets), the multipliers at the solution being the static loads.
#include <float.h>
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis.h"

// the residual (R - G' lambda; phi) at qdot = qddot = 0 scaled as dal_equilibrium scales its
// own (equilibrium.c): each coordinate's by the forces that make it (sqrt(M_jj) sum_k |F_k| /
// sqrt(m_k), the change of a unit move sum_i |K_ji|, the constraint forces sum_r |G_rj lambda_r|),
// each constraint row's by the change of a unit move sum_j |G_rj| (1 + max |q|)
static double scaled_residual(const dal_system *sys, const dal_state *st, const dal_tangent *tg,
                              const double *lam) {
  int n = sys->n, m = sys->m, d = sys->dim;
  double fs = 0.0, worst = 0.0, qmax = 0.0;
  for (int k = 0; k < sys->N; ++k) {
    double f2 = 0.0, mk = st->prm.mass[k];
    for (int a = 0; a < d; ++a)
      f2 += st->F[k * d + a] * st->F[k * d + a];
    if (mk > 0) fs += sqrt(f2 / mk);
  }
  for (int j = 0; j < n; ++j) {
    double sc = sqrt(fabs(tg->M[(size_t)j * n + j])) * fs;
    for (int i = 0; i < n; ++i)
      sc += fabs(tg->Rq[(size_t)i * n + j]);
    for (int r = 0; r < m; ++r)
      sc += fabs(tg->G[(size_t)j * m + r] * lam[r]);
    double x = fabs(tg->res[j]);
    if (x > 0) worst = fmax(worst, sc > 0 ? x / sc : INFINITY);
    if (!isfinite(x)) worst = INFINITY;
    qmax = fmax(qmax, fabs(st->q[j]));
  }
  for (int r = 0; r < m; ++r) {
    double sc = 0.0, x = fabs(tg->cres[r]);
    for (int j = 0; j < n; ++j)
      sc += fabs(tg->G[(size_t)j * m + r]);
    sc *= 1.0 + qmax;
    if (x > 0) worst = fmax(worst, sc > 0 ? x / sc : INFINITY);
    if (!isfinite(x)) worst = INFINITY;
  }
  return worst;
}

int dal__equilibrium_manifold(const dal_system *sys, dal_state *st, const dal_equilibrium_opts *o,
                              dal_equilibrium_report *rep) {
  int n = sys->n, m = sys->m, nk = n + m, rc;
  size_t sn = (size_t)n, snk = (size_t)nk;
  double t = st->t, step = INFINITY, reach = 0.0, res = INFINITY;
  dal_tangent *tg = NULL;
  double *buf = calloc(snk * snk + 2 * snk + 2 * sn + 2 * (size_t)m + 1, sizeof(double));
  lapack_int *ipiv = calloc(snk, sizeof(lapack_int));
  if (!buf || !ipiv || dal__tangent_create(sys, &tg)) {
    free(buf);
    free(ipiv);
    return DAL_FAIL(st, DAL_E_NOMEM, "equilibrium: out of memory for the Newton workspace");
  }
  double *J = buf, *x = J + snk * snk, *q = x + snk, *zero = q + sn, *lam = zero + sn;
  double *ftbuf = NULL; // 2n: df/dt at the solution
  memcpy(q, st->q, sn * sizeof(double));
  // the same neighbourhood and residual test as dal_equilibrium (equilibrium.c)
  for (int i = 0; i < n; ++i)
    reach = fmax(reach, fabs(q[i]));
  reach = 1e4 * (1.0 + reach);
  double res_tol = fmax(o->xtol, 1024.0 * DBL_EPSILON);
  dal_equilibrium_report r = {0, 0.0, 0.0, 0.0};
  // the multipliers start from the KKT solution at (q, 0)
  if ((rc = dal__analysis_eval(sys, st, t, q, zero)) != 0) goto done;
  memcpy(lam, st->lambda, (size_t)m * sizeof(double));
  tg->acc = zero;
  tg->lam = lam;
  for (int it = 1;; ++it) {
    if (it > 1 && (rc = dal__analysis_eval(sys, st, t, q, zero)) != 0) goto done;
    if ((rc = dal__tangent_eval(sys, st, tg, 0)) != 0) goto done;
    // converged: the last step was below xtol and the scaled residual is small here
    res = scaled_residual(sys, st, tg, lam);
    if (step <= 0.0 && res <= res_tol) break;
    if (it > o->max_iter) {
      char qs[256];
      dal__fmt_q(sys, st->q, qs, sizeof qs);
      rc = DAL_FAIL(st, DAL_E_CONV,
                    "equilibrium: Newton on the constraint manifold did not converge in %d "
                    "iterations at t=%.17g (last step %.3g, scaled residual %.3g against %.3g, "
                    "now at %s); start closer to the equilibrium, bound the step (max_step) or "
                    "raise max_iter",
                    o->max_iter, t, r.step, res, res_tol, qs);
      goto done;
    }
    // [K_full -G'; G 0] (dq; dlambda) = -(R - G' lambda; phi) at qdot = 0, qddot = 0
    for (int j = 0; j < nk; ++j)
      for (int i = 0; i < nk; ++i) {
        double v = 0.0;
        if (i < n && j < n)
          v = tg->Rq[(size_t)j * n + i];
        else if (i < n)
          v = -tg->G[(size_t)i * m + (j - n)];
        else if (j < n)
          v = tg->G[(size_t)j * m + (i - n)];
        J[(size_t)j * snk + i] = v;
      }
    for (int i = 0; i < n; ++i)
      x[i] = -tg->res[i];
    for (int i = 0; i < m; ++i)
      x[n + i] = -tg->cres[i];
    lapack_int info = LAPACKE_dgesv_work(LAPACK_COL_MAJOR, nk, 1, J, nk, ipiv, x, nk);
    if (info != 0) {
      char qs[256];
      dal__fmt_q(sys, st->q, qs, sizeof qs);
      int piv = info > 0 ? (int)info - 1 : 0;
      rc = DAL_FAIL(st, DAL_E_SINGULAR,
                    "equilibrium: the Newton matrix on the constraint manifold [K -G'; G 0] is "
                    "singular at t=%.17g, %s (pivot of %s '%s'): a bifurcation point, a "
                    "direction with no restoring force, or dependent constraint rows; move the "
                    "parameter off the critical value or drop a redundant constraint",
                    t, qs, piv < n ? "coordinate" : "constraint",
                    piv < n ? sys->coord_names[piv] : sys->con[sys->row_con[piv - n]].name);
      goto done;
    }
    double big = 0.0, conv = 0.0;
    for (int i = 0; i < n; ++i) {
      big = fmax(big, fabs(x[i]));
      if (!isfinite(x[i])) big = INFINITY;
    }
    for (int i = 0; i < m; ++i)
      if (!isfinite(x[n + i])) big = INFINITY;
    if (!isfinite(big)) {
      rc = DAL_FAIL(st, DAL_E_CONV, "equilibrium: non-finite Newton step at t=%.17g", t);
      goto done;
    }
    double f = o->max_step > 0 && big > o->max_step ? o->max_step / big : 1.0;
    // a step that leaves the start's neighbourhood lands on no equilibrium the start was
    // meant for (the Newton matrix is nearly singular there)
    for (int i = 0; i < n; ++i)
      if (!(fabs(q[i] + f * x[i]) <= reach)) {
        char qs[256];
        dal__fmt_q(sys, st->q, qs, sizeof qs);
        rc = DAL_FAIL(st, DAL_E_CONV,
                      "equilibrium: the Newton step at t=%.17g from %s sends coordinate '%s' to "
                      "%.3g, beyond %.3g (1e4 (1 + max |q0|)), far from the start: the Newton "
                      "matrix on the constraint manifold is nearly singular there; start closer "
                      "to the equilibrium or bound the step (max_step)",
                      t, qs, sys->coord_names[i], q[i] + f * x[i], reach);
        goto done;
      }
    for (int i = 0; i < n; ++i) {
      q[i] += f * x[i];
      conv = fmax(conv, fabs(f * x[i]) / (1.0 + fabs(q[i])));
    }
    for (int i = 0; i < m; ++i)
      lam[i] += f * x[n + i];
    r.iterations = it;
    r.step = f * big;
    step = conv <= o->xtol && f == 1.0 ? 0.0 : conv;
  }
  // a moving constraint whose motion carries the point (dphi/dt != 0): qdot = 0 is not on
  // the manifold there, and the point is no equilibrium of these coordinates
  for (int i = 0; i < m; ++i) {
    double gn = 0.0;
    for (int j = 0; j < n; ++j)
      gn += fabs(tg->G[(size_t)j * m + i]);
    if (!(fabs(st->phit[i]) <= 1e-10 * (1.0 + gn))) {
      char qs[256];
      dal__fmt_q(sys, st->q, qs, sizeof qs);
      rc = DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "equilibrium: at t=%.17g, %s the moving constraint '%s' carries the point "
                    "(dphi/dt = %.3g): a relative equilibrium, which redundant coordinates do "
                    "not cover yet; describe the moving part by a coordinate map in its frame "
                    "(dal_map_ring for a turning ring)",
                    t, qs, sys->con[sys->row_con[i]].name, st->phit[i]);
      goto done;
    }
  }
  // the solution, evaluated with its KKT accelerations and multipliers (the static loads),
  // and its time dependence d qddot/dt
  tg->acc = NULL;
  tg->lam = NULL;
  ftbuf = malloc(2 * sn * sizeof(double));
  if (!ftbuf) {
    rc = DAL_FAIL(st, DAL_E_NOMEM, "equilibrium: out of memory");
    goto done;
  }
  if ((rc = dal__tangent_eval(sys, st, tg, 1)) != 0) goto done;
  if ((rc = dal__tangent_kkt(sys, st, tg, NULL, ftbuf, NULL)) != 0) goto done;
  for (int i = 0; i < n; ++i) {
    r.accel = fmax(r.accel, fabs(st->qddot[i]));
    r.unsteady = fmax(r.unsteady, fabs(ftbuf[n + i]));
  }
  if (rep) *rep = r;
done:
  free(ftbuf);
  free(buf);
  free(ipiv);
  dal__tangent_free(tg);
  return rc;
}
