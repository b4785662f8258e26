// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Equilibria by Newton's method with the exact stiffness K, and their natural-parameter
// continuation with stability and located critical points (sign changes of det K).
#include <float.h>
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis.h"

#define DAL_EQ_COOKIE 0x0e9c1b05
/// Newton's neighbourhood: an iterate farther than this many times (1 + max |q0_i|) from the
/// start q0 has left any basin the start could be meant for (a nearly singular K sent it there)
#define DAL_EQ_REACH 1e4
/// the scaled residual below which a point whose last step met xtol is an equilibrium:
/// max(xtol, this many ulps)
#define DAL_EQ_RES_ULPS 1024.0
#define DAL_CONT_COOKIE 0x0c0a71e5

dal_equilibrium_opts dal_default_equilibrium_opts(void) {
  dal_equilibrium_opts d, *o = &d;
  memset(o, 0, sizeof *o);
  o->cookie = DAL_EQ_COOKIE;
  o->xtol = 1e-12;
  o->max_iter = 50;
  o->max_step = 0.0;
  return d;
}

dal_continuation_opts dal_default_continuation_opts(void) {
  dal_continuation_opts d, *o = &d;
  memset(o, 0, sizeof *o);
  o->cookie = DAL_CONT_COOKIE;
  o->p0 = 0.0;
  o->p1 = 1.0;
  o->npoints = 41;
  o->t = 0.0;
  o->locate = 1;
  o->ptol = 0.0;
  o->newton = dal_default_equilibrium_opts();
  return d;
}

static int check_eq_opts(const dal_equilibrium_opts *o, char *err, size_t len) {
  if (o->cookie != DAL_EQ_COOKIE) {
    snprintf(err, len, "equilibrium options not initialized: call dal_default_equilibrium_opts");
    return DAL_E_ARG;
  }
  if (!(o->xtol > 0) || !isfinite(o->xtol) || o->max_iter < 1 || !(o->max_step >= 0) ||
      !isfinite(o->max_step)) {
    snprintf(err, len,
             "equilibrium options: xtol = %g must be finite and > 0, max_iter = %d >= 1, "
             "max_step = %g finite and >= 0",
             o->xtol, o->max_iter, o->max_step);
    return DAL_E_ARG;
  }
  return DAL_OK;
}

// scratch of one Newton solve: n x n K and the pivots, n-vectors
typedef struct newton_ws {
  dal_tangent *tg;
  double *K, *x, *q, *zero;
  lapack_int *ipiv;
} newton_ws;

static void newton_free(newton_ws *w) {
  dal__tangent_free(w->tg);
  DAL_FREE(w->K, w->x, w->q, w->zero, w->ipiv);
  memset(w, 0, sizeof *w);
}

static int newton_alloc(const dal_system *sys, newton_ws *w) {
  size_t n = (size_t)sys->n + 1;
  memset(w, 0, sizeof *w);
  int rc = dal__tangent_create(sys, &w->tg);
  w->K = calloc(n * n, sizeof(double));
  w->x = calloc(n, sizeof(double));
  w->q = calloc(n, sizeof(double));
  w->zero = calloc(n, sizeof(double));
  w->ipiv = calloc(n, sizeof(lapack_int));
  if (rc || !w->K || !w->x || !w->q || !w->zero || !w->ipiv) {
    newton_free(w);
    return DAL_E_NOMEM;
  }
  return DAL_OK;
}

// the residual R = M qddot (= Q - c at qdot = 0, in w->x) scaled per coordinate by the size of
// the forces that make it: |Q_j| <= sqrt(M_jj) sum_k |F_k| / sqrt(m_k) bounds the particle
// forces' part (|J_kj|^2 m_k <= M_jj), sum_i |K_ji| the part that changes by a unit move
static double scaled_residual(const dal_system *sys, const dal_state *st, const newton_ws *w) {
  int n = sys->n;
  double fs = dal__force_scale(sys, st), worst = 0.0;
  for (int j = 0; j < n; ++j) {
    double s = sqrt(fabs(w->tg->M[(size_t)j * n + j])) * fs;
    for (int i = 0; i < n; ++i)
      s += fabs(w->tg->Rq[(size_t)i * n + j]);
    double r = fabs(w->x[j]);
    if (r > 0) worst = fmax(worst, s > 0 ? r / s : INFINITY);
    if (!isfinite(r)) worst = INFINITY;
  }
  return worst;
}

// the equilibrium solve on a prepared workspace; on success the state is at (t, q*, 0),
// evaluated, with the tangent (and dR/dt) of the solution in w->tg
// the Newton step K dq = R (R in w->x) taken from w->q, scaled down to max_step and kept
// within reach of the start; *step: the largest relative change of q (0 when below xtol with
// the full step), *length: the step's length
static int newton_step(const dal_system *sys, dal_state *st, const dal_equilibrium_opts *o,
                       newton_ws *w, double reach, double *step, double *length) {
  int n = sys->n;
  double t = st->t;
  memcpy(w->K, w->tg->Rq, (size_t)n * (size_t)n * sizeof(double));
  lapack_int info = LAPACKE_dgesv_work(LAPACK_COL_MAJOR, n, 1, w->K, n, w->ipiv, w->x, n);
  if (info != 0) {
    return DAL_FAIL(st, DAL_E_SINGULAR,
                    "equilibrium: the stiffness K is singular at t=%.17g, %s (pivot of "
                    "coordinate '%s'): a bifurcation point, or a direction with no restoring "
                    "force (a free or cyclic coordinate); fix that coordinate or move the "
                    "parameter off the critical value",
                    t, dal__qtext(sys, st->q).s, sys->coord_names[info > 0 ? (int)info - 1 : 0]);
  }
  double big = 0.0, conv = 0.0;
  int far = -1;
  double f = dal__newton_scale(w->x, n, 0, w->q, o->max_step, reach, &big, &far);
  int rc = dal__newton_apply(sys, st, w->x, w->q, f, big, far, reach,
                             "the stiffness K is nearly singular there (a turning point of the "
                             "potential)",
                             &conv);
  if (rc) return rc;
  *length = f * big;
  *step = conv <= o->xtol && f == 1.0 ? 0.0 : conv;
  return DAL_OK;
}

static int solve(const dal_system *sys, dal_state *st, const dal_equilibrium_opts *o, newton_ws *w,
                 dal_equilibrium_report *rep) {
  int n = sys->n, rc;
  double t = st->t, step = INFINITY, reach = 0.0, res = INFINITY;
  memcpy(w->q, st->q, (size_t)n * sizeof(double));
  for (int i = 0; i < n; ++i)
    reach = fmax(reach, fabs(w->q[i]));
  reach = DAL_EQ_REACH * (1.0 + reach);
  double res_tol = fmax(o->xtol, DAL_EQ_RES_ULPS * DBL_EPSILON);
  dal_equilibrium_report r = {0, 0.0, 0.0, 0.0};
  for (int it = 1;; ++it) {
    if ((rc = dal__analysis_eval(sys, st, t, w->q, w->zero)) != 0) return rc;
    if ((rc = dal__tangent_eval(sys, st, w->tg, 0)) != 0) return rc;
    // the residual R = M qddot (= Q - c at qdot = 0), scaled by the forces that make it
    for (int i = 0; i < n; ++i) {
      double s = 0.0;
      for (int j = 0; j < n; ++j)
        s += w->tg->M[(size_t)j * n + i] * st->qddot[j];
      w->x[i] = s;
    }
    res = scaled_residual(sys, st, w);
    // converged: the last step was below xtol and the residual is small here (a step that
    // cannot move q, at |q| where the spacing of doubles exceeds it, is not convergence)
    if (step <= 0.0 && res <= res_tol) break;
    if (it > o->max_iter) {
      return DAL_FAIL(st, DAL_E_CONV,
                      "equilibrium: Newton did not converge in %d iterations at t=%.17g (last "
                      "step %.3g, scaled residual %.3g against %.3g, now at %s); start closer to "
                      "the equilibrium, bound the step (max_step) or raise max_iter",
                      o->max_iter, t, r.step, res, res_tol, dal__qtext(sys, st->q).s);
    }
    if ((rc = newton_step(sys, st, o, w, reach, &step, &r.step)) != 0) return rc;
    r.iterations = it;
  }
  // the solution: residual and time dependence d qddot/dt = -M^-1 dR/dt
  if ((rc = dal__tangent_eval(sys, st, w->tg, 1)) != 0) return rc;
  if ((rc = dal__tangent_factor(sys, st, w->tg)) != 0) return rc;
  memcpy(w->x, w->tg->Rt, (size_t)n * sizeof(double));
  dal__tangent_msolve(w->tg, 1, w->x);
  for (int i = 0; i < n; ++i) {
    r.accel = fmax(r.accel, fabs(st->qddot[i]));
    r.unsteady = fmax(r.unsteady, fabs(w->x[i]));
  }
  if (rep) *rep = r;
  return DAL_OK;
}

// time dependence is never frozen silently: a point found for an explicitly time-dependent
// system must be an equilibrium at every time (the driven pendulum's bottom), unless the frozen
// one is asked for by name
static int steady(const dal_system *sys, dal_state *st, const dal_equilibrium_opts *o) {
  if (o->frozen_time) return DAL_OK;
  char why[512];
  int td = dal_time_dependence(sys, st, why, sizeof why);
  if (td <= 0) return td;
  double worst, when;
  int all = dal__equilibrium_all_times(sys, st, &worst, &when);
  if (all < 0) return all;
  if (all) return DAL_OK;
  return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                  "equilibrium: %s, and the point found at t=%.6g, %s, is no equilibrium at "
                  "t=%.6g (scaled residual %.3g): it holds for the equations frozen at t=%.6g "
                  "only; for a periodic drive look for a periodic orbit (dal_periodic_orbit, "
                  "dalembert orbit), or ask for the frozen one by name (opts.frozen_time, "
                  "dalembert equilibria --frozen)",
                  why, st->t, dal__qtext(sys, st->q).s, when, worst, st->t);
}

int dal_equilibrium(const dal_system *sys, dal_state *st, const dal_equilibrium_opts *o,
                    dal_equilibrium_report *rep) {
  if (!st) return DAL_E_ARG;
  if (!sys || st->sys != sys)
    return DAL_FAIL(st, DAL_E_STATE, "equilibrium: the state belongs to another system");
  if (dal__check_idle(st, "equilibrium")) return DAL_E_STATE;
  dal_equilibrium_opts def;
  if (!o) {
    def = dal_default_equilibrium_opts();
    o = &def;
  }
  char err[256];
  int rc = check_eq_opts(o, err, sizeof err);
  if (rc) return DAL_FAIL(st, rc, "%s", err);
  if ((rc = dal__tangent_supported(sys, st, "equilibrium")) != 0) return rc;
  if (sys->m > 0) {
    rc = dal__equilibrium_manifold(sys, st, o, rep);
  } else {
    newton_ws w;
    if (newton_alloc(sys, &w))
      return DAL_FAIL(st, DAL_E_NOMEM, "equilibrium: out of memory for the Newton workspace");
    rc = solve(sys, st, o, &w, rep);
    newton_free(&w);
  }
  return rc ? rc : steady(sys, st, o);
}

// ---------------------------------------------------------------------------------------------
// continuation

// sign of det K from an LU factorization of a copy (0 when exactly singular)
static int det_sign(int n, const double *K, double *work, lapack_int *ipiv) {
  memcpy(work, K, (size_t)n * (size_t)n * sizeof(double));
  lapack_int info = LAPACKE_dgetrf_work(LAPACK_COL_MAJOR, n, n, work, n, ipiv);
  if (info > 0) return 0;
  int s = 1;
  for (int i = 0; i < n; ++i) {
    if (work[(size_t)i * n + i] < 0) s = -s;
    if (ipiv[i] != i + 1) s = -s;
  }
  return s;
}

// one point of a branch: a system at p, its equilibrium from the guess q (n), the verdict
// and the sign of det K; the system and state stay alive for the caller
typedef struct cont_point {
  dal_system *sys;
  dal_state *st;
  dal_stability verdict;
  int sign;
} cont_point;

static void point_free(cont_point *pt) {
  dal_state_destroy(pt->st);
  dal_system_destroy(pt->sys);
  pt->st = NULL;
  pt->sys = NULL;
}

static int solve_point(dal_rebuild_fn *rebuild, double p, const double *guess, int *n,
                       const dal_continuation_opts *o, cont_point *pt, dal_continuation_report *r,
                       void *ctx) {
  memset(pt, 0, sizeof *pt);
  int rc = rebuild(p, &pt->sys, ctx);
  if (rc || !pt->sys) {
    snprintf(r->msg, sizeof r->msg, "rebuild returned %d (system %s) at p=%.17g", rc,
             pt->sys ? "built" : "NULL", p);
    dal_system_destroy(pt->sys);
    pt->sys = NULL;
    return DAL_E_CALLBACK;
  }
  if (*n < 0) *n = pt->sys->n;
  if (pt->sys->n != *n) {
    snprintf(r->msg, sizeof r->msg,
             "rebuild at p=%.17g gave a system with %d coordinates, the branch has %d", p,
             pt->sys->n, *n);
    point_free(pt);
    return DAL_E_ARG;
  }
  if ((rc = dal_state_create(pt->sys, &pt->st)) != 0) {
    snprintf(r->msg, sizeof r->msg, "out of memory for a state at p=%.17g", p);
    point_free(pt);
    return rc;
  }
  double zero[64] = {0};
  double *z = *n <= 64 ? zero : calloc((size_t)*n, sizeof(double));
  rc = z ? dal_state_set(pt->sys, pt->st, o->t, guess, z) : DAL_E_NOMEM;
  if (z != zero) free(z);
  if (!rc) rc = dal_equilibrium(pt->sys, pt->st, &o->newton, NULL);
  dal_modes md;
  if (!rc)
    rc = (o->newton.frozen_time ? dal_normal_modes_frozen
                                : dal_normal_modes)(pt->sys, pt->st, NULL, NULL, NULL, NULL, &md);
  if (rc) {
    snprintf(r->msg, sizeof r->msg, "at p=%.17g: %s", p, dal_state_errmsg(pt->st));
    point_free(pt);
    return rc;
  }
  pt->verdict = md.verdict;
  return DAL_OK;
}

// det K sign at the point's solution (the state is evaluated at the equilibrium)
static int point_sign(cont_point *pt, double *work, lapack_int *ipiv) {
  int n = pt->sys->n - pt->sys->m; // K is k x k on the constraint manifold
  double *K = work + (size_t)n * n;
  int rc = dal_linearize(pt->sys, pt->st, NULL, NULL, K);
  if (rc) return rc;
  pt->sign = det_sign(n, K, work, ipiv);
  return DAL_OK;
}

// the arguments of dal_continue; 0 or DAL_E_ARG with the report's message set
static int check_cont_args(dal_rebuild_fn *rebuild, const double *q0,
                           const dal_continuation_opts *o, dal_continuation_report *r) {
  if (!rebuild || !q0 || !o) {
    snprintf(r->msg, sizeof r->msg, "continue: rebuild, q0 and options are required");
    return DAL_E_ARG;
  }
  if (o->cookie != DAL_CONT_COOKIE) {
    snprintf(r->msg, sizeof r->msg,
             "continuation options not initialized: call dal_default_continuation_opts");
    return DAL_E_ARG;
  }
  if (!isfinite(o->p0) || !isfinite(o->p1) || o->p0 == o->p1 || o->npoints < 2 || !isfinite(o->t) ||
      !(o->ptol >= 0)) {
    snprintf(r->msg, sizeof r->msg,
             "continuation options: p0 = %g and p1 = %g must be finite and differ, npoints = %d "
             ">= 2, t = %g finite, ptol = %g >= 0",
             o->p0, o->p1, o->npoints, o->t, o->ptol);
    return DAL_E_ARG;
  }
  return check_eq_opts(&o->newton, r->msg, sizeof r->msg);
}

// what a continuation run shares with its bisections
typedef struct cont_run {
  dal_rebuild_fn *rebuild;
  const dal_continuation_opts *o;
  dal_branch_fn *point;
  void *ctx;
  dal_continuation_report *r;
  int n;            // coordinates (-1 until the first point is solved)
  double ptol;      // the bisection's parameter tolerance
  double *work;     // (2 n^2) sign of det K
  lapack_int *ipiv; // (n)
} cont_run;

// a sign change of det K between a (solution qa, sign sa; qa is overwritten) and b: bisect
// for the critical parameter and report it to the point callback
static int locate_critical(cont_run *c, double a, double b, int sa, double *qa) {
  dal_continuation_report *r = c->r;
  cont_point mid = {0};
  int rc = DAL_OK;
  while (fabs(b - a) > c->ptol) {
    double pc = 0.5 * (a + b);
    point_free(&mid);
    rc = solve_point(c->rebuild, pc, qa, &c->n, c->o, &mid, r, c->ctx);
    if (!rc) rc = point_sign(&mid, c->work, c->ipiv);
    if (rc) break;
    if (mid.sign == sa) {
      a = pc;
      memcpy(qa, mid.st->q, (size_t)c->n * sizeof(double));
    } else {
      b = pc;
    }
    if (mid.sign == 0) { // det K is exactly zero at pc: the critical point itself
      a = pc;
      break;
    }
  }
  if (!rc) {
    double pc = 0.5 * (a + b);
    point_free(&mid);
    rc = solve_point(c->rebuild, pc, qa, &c->n, c->o, &mid, r, c->ctx);
    if (!rc) {
      r->ncritical++;
      if (c->point && c->point(pc, mid.sys, mid.st, mid.verdict, DAL_BRANCH_CRITICAL, c->ctx)) {
        snprintf(r->msg, sizeof r->msg, "the point callback stopped at p=%.17g", pc);
        rc = DAL_E_CALLBACK;
      }
    }
  }
  point_free(&mid);
  return rc;
}

int dal_continue(dal_rebuild_fn *rebuild, const double *q0, const dal_continuation_opts *o,
                 dal_branch_fn *point, dal_continuation_report *rep, void *ctx) {
  dal_continuation_report r;
  memset(&r, 0, sizeof r);
  int rc = check_cont_args(rebuild, q0, o, &r);
  if (rc) {
    if (rep) *rep = r;
    return rc;
  }
  cont_run c = {.rebuild = rebuild, .o = o, .point = point, .ctx = ctx, .r = &r, .n = -1};
  c.ptol = o->ptol > 0 ? o->ptol : 1e-10 * fabs(o->p1 - o->p0);
  cont_point cur = {0}, prev = {0};
  double *hist = NULL, *guess = NULL, pprev = o->p0;
  for (int k = 0; k < o->npoints; ++k) {
    int n = c.n;
    double p = k == o->npoints - 1 ? o->p1 : o->p0 + (o->p1 - o->p0) * k / (o->npoints - 1);
    // the guess: q0, the previous solution, or a secant through the two previous ones
    if (k == 0) {
      rc = solve_point(rebuild, p, q0, &c.n, o, &cur, &r, ctx);
      n = c.n;
      if (!rc) {
        hist = calloc(2 * (size_t)n + 1, sizeof(double));
        guess = calloc((size_t)n + 1, sizeof(double));
        c.work = calloc(2 * (size_t)n * n + 1, sizeof(double));
        c.ipiv = calloc((size_t)n + 1, sizeof(lapack_int));
        if (!hist || !guess || !c.work || !c.ipiv) {
          snprintf(r.msg, sizeof r.msg, "continue: out of memory");
          rc = DAL_E_NOMEM;
        }
      }
    } else {
      for (int i = 0; i < n; ++i)
        guess[i] = k == 1 ? hist[i] : hist[i] + (hist[i] - hist[n + i]);
      rc = solve_point(rebuild, p, guess, &c.n, o, &cur, &r, ctx);
    }
    if (!rc) rc = point_sign(&cur, c.work, c.ipiv);
    if (rc) {
      if (!r.msg[0]) snprintf(r.msg, sizeof r.msg, "at p=%.17g: %s", p, dal_state_errmsg(cur.st));
      break;
    }
    // a sign change of det K since the previous point: bisect for the critical parameter
    // (from the solution at the previous point, the guess for the midpoints)
    if (k > 0 && o->locate && cur.sign != prev.sign && cur.sign != 0 && prev.sign != 0) {
      memcpy(guess, prev.st->q, (size_t)n * sizeof(double));
      if ((rc = locate_critical(&c, pprev, p, prev.sign, guess)) != 0) break;
    }
    r.npoints++;
    r.p_end = p;
    if (point && point(p, cur.sys, cur.st, cur.verdict, DAL_BRANCH_REGULAR, ctx)) {
      snprintf(r.msg, sizeof r.msg, "the point callback stopped at p=%.17g", p);
      rc = DAL_E_CALLBACK;
      break;
    }
    // shift the history
    memcpy(hist + n, hist, (size_t)n * sizeof(double));
    memcpy(hist, cur.st->q, (size_t)n * sizeof(double));
    point_free(&prev);
    prev = cur;
    memset(&cur, 0, sizeof cur);
    pprev = p;
  }
  point_free(&cur);
  point_free(&prev);
  free(hist);
  free(guess);
  free(c.work);
  free(c.ipiv);
  if (rep) *rep = r;
  return rc;
}
