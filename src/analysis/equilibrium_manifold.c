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

double dal__force_scale(const dal_system *sys, const dal_state *st) {
  int d = sys->dim;
  double fs = 0.0;
  for (int k = 0; k < sys->N; ++k) {
    double f2 = 0.0, m = st->prm.mass[k];
    for (int a = 0; a < d; ++a)
      f2 += st->F[k * d + a] * st->F[k * d + a];
    if (m > 0) fs += sqrt(f2 / m);
  }
  return fs;
}

// the residual (R - G' lambda; phi) at qdot = qddot = 0 scaled as dal_equilibrium scales its
// own (equilibrium.c): each coordinate's by the forces that make it (sqrt(M_jj) sum_k |F_k| /
// sqrt(m_k), the change of a unit move sum_i |K_ji|, the constraint forces sum_r |G_rj lambda_r|),
// each constraint row's by the change of a unit move sum_j |G_rj| (1 + max |q|)
static double scaled_residual(const dal_system *sys, const dal_state *st, const dal_tangent *tg,
                              const double *lam) {
  int n = sys->n, m = sys->m;
  double fs = dal__force_scale(sys, st), worst = 0.0, qmax = 0.0;
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

double dal__newton_scale(const double *x, int n, int m, const double *q, double max_step,
                         double reach, double *big, int *far) {
  *big = 0.0;
  *far = -1;
  for (int i = 0; i < n; ++i) {
    *big = fmax(*big, fabs(x[i]));
    if (!isfinite(x[i])) *big = INFINITY;
  }
  for (int i = 0; i < m; ++i)
    if (!isfinite(x[n + i])) *big = INFINITY;
  if (!isfinite(*big)) return 1.0;
  double f = max_step > 0 && *big > max_step ? max_step / *big : 1.0;
  for (int i = 0; i < n && *far < 0; ++i)
    if (!(fabs(q[i] + f * x[i]) <= reach)) *far = i;
  return f;
}

int dal__newton_apply(const dal_system *sys, dal_state *st, const double *x, double *q, double f,
                      double big, int far, double reach, const char *singular, double *conv) {
  if (!isfinite(big))
    return DAL_FAIL(st, DAL_E_CONV, "equilibrium: non-finite Newton step at t=%.17g", st->t);
  // a step that leaves the start's neighbourhood lands on no equilibrium the start was meant
  // for (|q0| <= reach / 1e4)
  if (far >= 0) {
    return DAL_FAIL(st, DAL_E_CONV,
                    "equilibrium: the Newton step at t=%.17g from %s sends coordinate '%s' to "
                    "%.3g, beyond %.3g (1e4 (1 + max |q0|)), far from the start: %s; start "
                    "closer to the equilibrium or bound the step (max_step)",
                    st->t, dal__qtext(sys, st->q).s, sys->coord_names[far], q[far] + f * x[far],
                    reach, singular);
  }
  *conv = 0.0;
  for (int i = 0; i < sys->n; ++i) {
    q[i] += f * x[i];
    *conv = fmax(*conv, fabs(f * x[i]) / (1.0 + fabs(q[i])));
  }
  return DAL_OK;
}

// the Newton workspace on the manifold: the KKT matrix J (nk x nk), the step x (nk), the
// coordinates q, the zero velocity, the multipliers lam; reach bounds |q_i|
typedef struct mf_ws {
  int n, m, nk;
  double *J, *x, *q, *zero, *lam;
  lapack_int *ipiv;
  double reach;
} mf_ws;

// the Newton step: [K_full -G'; G 0] (dq; dlambda) = -(R - G' lambda; phi) at qdot = 0,
// qddot = 0, into w->x; 0 or DAL_E_SINGULAR naming the pivot
static int mf_solve(const dal_system *sys, dal_state *st, const dal_tangent *tg, mf_ws *w) {
  int n = w->n, m = w->m, nk = w->nk;
  size_t snk = (size_t)nk;
  for (int j = 0; j < nk; ++j)
    for (int i = 0; i < nk; ++i) {
      double v = 0.0;
      if (i < n && j < n)
        v = tg->Rq[(size_t)j * n + i];
      else if (i < n)
        v = -tg->G[(size_t)i * m + (j - n)];
      else if (j < n)
        v = tg->G[(size_t)j * m + (i - n)];
      w->J[(size_t)j * snk + i] = v;
    }
  for (int i = 0; i < n; ++i)
    w->x[i] = -tg->res[i];
  for (int i = 0; i < m; ++i)
    w->x[n + i] = -tg->cres[i];
  lapack_int info = LAPACKE_dgesv_work(LAPACK_COL_MAJOR, nk, 1, w->J, nk, w->ipiv, w->x, nk);
  if (info == 0) return DAL_OK;
  int piv = info > 0 ? (int)info - 1 : 0;
  return DAL_FAIL(st, DAL_E_SINGULAR,
                  "equilibrium: the Newton matrix on the constraint manifold [K -G'; G 0] is "
                  "singular at t=%.17g, %s (pivot of %s '%s'): a bifurcation point, a "
                  "direction with no restoring force, or dependent constraint rows; move the "
                  "parameter off the critical value or drop a redundant constraint",
                  st->t, dal__qtext(sys, st->q).s, piv < n ? "coordinate" : "constraint",
                  piv < n ? sys->coord_names[piv] : sys->con[sys->row_con[piv - n]].name);
}

// take the step w->x (scaled down to max_step), within the start's neighbourhood; *conv: the
// largest relative change of q, r: iterations and step length
static int mf_step(const dal_system *sys, dal_state *st, const dal_equilibrium_opts *o, mf_ws *w,
                   int it, double *conv, dal_equilibrium_report *r) {
  int n = w->n, m = w->m;
  double *x = w->x, *q = w->q, big = 0.0;
  int far = -1;
  double f = dal__newton_scale(x, n, m, q, o->max_step, w->reach, &big, &far);
  int rc = dal__newton_apply(sys, st, x, q, f, big, far, w->reach,
                             "the Newton matrix on the constraint manifold is nearly singular "
                             "there",
                             conv);
  if (rc) return rc;
  for (int i = 0; i < m; ++i)
    w->lam[i] += f * x[n + i];
  r->iterations = it;
  r->step = f * big;
  return f == 1.0 ? DAL_OK : 1; // 1: a shortened step (not converged)
}

// a moving constraint whose motion carries the point (dphi/dt != 0): qdot = 0 is not on
// the manifold there, and the point is no equilibrium of these coordinates
static int mf_not_carried(const dal_system *sys, dal_state *st, const dal_tangent *tg) {
  int n = sys->n, m = sys->m;
  for (int i = 0; i < m; ++i) {
    double gn = 0.0;
    for (int j = 0; j < n; ++j)
      gn += fabs(tg->G[(size_t)j * m + i]);
    if (!(fabs(st->phit[i]) <= 1e-10 * (1.0 + gn))) {
      return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                      "equilibrium: at t=%.17g, %s the moving constraint '%s' carries the point "
                      "(dphi/dt = %.3g): a relative equilibrium, which redundant coordinates do "
                      "not cover yet; describe the moving part by a coordinate map in its frame "
                      "(dal_map_ring for a turning ring)",
                      st->t, dal__qtext(sys, st->q).s, sys->con[sys->row_con[i]].name, st->phit[i]);
    }
  }
  return DAL_OK;
}

// the solution, evaluated with its KKT accelerations and multipliers (the static loads),
// and its time dependence d qddot/dt into the report
static int mf_finish(const dal_system *sys, dal_state *st, dal_tangent *tg,
                     dal_equilibrium_report *r) {
  int n = sys->n, rc;
  tg->acc = NULL;
  tg->lam = NULL;
  double *ft = malloc(2 * (size_t)n * sizeof(double)); // df/dt at the solution
  if (!ft) return DAL_FAIL(st, DAL_E_NOMEM, "equilibrium: out of memory");
  if ((rc = dal__tangent_eval(sys, st, tg, 1)) == 0 &&
      (rc = dal__tangent_kkt(sys, st, tg, NULL, ft, NULL)) == 0)
    for (int i = 0; i < n; ++i) {
      r->accel = fmax(r->accel, fabs(st->qddot[i]));
      r->unsteady = fmax(r->unsteady, fabs(ft[n + i]));
    }
  free(ft);
  return rc;
}

int dal__equilibrium_manifold(const dal_system *sys, dal_state *st, const dal_equilibrium_opts *o,
                              dal_equilibrium_report *rep) {
  int n = sys->n, m = sys->m, nk = n + m, rc;
  size_t sn = (size_t)n, snk = (size_t)nk;
  double t = st->t, step = INFINITY, res = INFINITY;
  dal_tangent *tg = NULL;
  double *buf = calloc(snk * snk + 2 * snk + 2 * sn + 2 * (size_t)m + 1, sizeof(double));
  mf_ws w = {.n = n, .m = m, .nk = nk, .ipiv = calloc(snk, sizeof(lapack_int))};
  if (!buf || !w.ipiv || dal__tangent_create(sys, &tg)) {
    free(buf);
    free(w.ipiv);
    return DAL_FAIL(st, DAL_E_NOMEM, "equilibrium: out of memory for the Newton workspace");
  }
  w.J = buf;
  w.x = w.J + snk * snk;
  w.q = w.x + snk;
  w.zero = w.q + sn;
  w.lam = w.zero + sn;
  memcpy(w.q, st->q, sn * sizeof(double));
  // the same neighbourhood and residual test as dal_equilibrium (equilibrium.c)
  for (int i = 0; i < n; ++i)
    w.reach = fmax(w.reach, fabs(w.q[i]));
  w.reach = 1e4 * (1.0 + w.reach);
  double res_tol = fmax(o->xtol, 1024.0 * DBL_EPSILON);
  dal_equilibrium_report r = {0, 0.0, 0.0, 0.0};
  // the multipliers start from the KKT solution at (q, 0)
  if ((rc = dal__analysis_eval(sys, st, t, w.q, w.zero)) != 0) goto done;
  memcpy(w.lam, st->lambda, (size_t)m * sizeof(double));
  tg->acc = w.zero;
  tg->lam = w.lam;
  for (int it = 1;; ++it) {
    if (it > 1 && (rc = dal__analysis_eval(sys, st, t, w.q, w.zero)) != 0) goto done;
    if ((rc = dal__tangent_eval(sys, st, tg, 0)) != 0) goto done;
    // converged: the last step was below xtol and the scaled residual is small here
    res = scaled_residual(sys, st, tg, w.lam);
    if (step <= 0.0 && res <= res_tol) break;
    if (it > o->max_iter) {
      rc = DAL_FAIL(st, DAL_E_CONV,
                    "equilibrium: Newton on the constraint manifold did not converge in %d "
                    "iterations at t=%.17g (last step %.3g, scaled residual %.3g against %.3g, "
                    "now at %s); start closer to the equilibrium, bound the step (max_step) or "
                    "raise max_iter",
                    o->max_iter, t, r.step, res, res_tol, dal__qtext(sys, st->q).s);
      goto done;
    }
    double conv = 0.0;
    if ((rc = mf_solve(sys, st, tg, &w)) != 0) goto done;
    int shortened = mf_step(sys, st, o, &w, it, &conv, &r);
    if (shortened < 0) {
      rc = shortened;
      goto done;
    }
    step = conv <= o->xtol && !shortened ? 0.0 : conv;
  }
  if ((rc = mf_not_carried(sys, st, tg)) == 0 && (rc = mf_finish(sys, st, tg, &r)) == 0 && rep)
    *rep = r;
done:
  free(buf);
  free(w.ipiv);
  dal__tangent_free(tg);
  return rc;
}
