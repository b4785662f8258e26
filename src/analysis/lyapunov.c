// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Lyapunov exponents: trajectory and exact tangent vectors integrated together, QR
// reorthonormalization (Benettin, Galgani, Giorgilli, Strelcyn, Meccanica 15, 1980).
//
// The augmented system is Y = (y, V) with y' = f(t, y) and V' = (df/dy) V, V = 2n x p. It runs
// on the library's own integrators (integrate.h: a first-order problem of size 2n (1 + p)),
// with dal_advance's tolerance calibration and progress guards. A Runge-Kutta step of the
// augmented system applies the method's own derivative to V, so V is the exact tangent of the
// numerical flow.
//
// The error estimate: the exponents of nblocks equal blocks of the averaging time are the
// samples; the reported error is a 95% confidence half-width of their mean, Student's t with
// nblocks - 1 degrees of freedom times the standard error, and never below the half-range of
// the block exponents divided by sqrt(nblocks) (blocks that stick to a regular island for
// part of the run are not independent samples; see dal_lyapunov in analysis.h).
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis.h"

#define DAL_LYAP_COOKIE 0x01a9e0f7

dal_lyapunov_opts dal_default_lyapunov_opts(void) {
  dal_lyapunov_opts d, *o = &d;
  memset(o, 0, sizeof *o);
  o->cookie = DAL_LYAP_COOKIE;
  o->nexp = 0;
  o->t_end = NAN;
  o->transient = 0.0;
  o->renorm = 1.0;
  o->method = DAL_METHOD_AUTO;
  o->rtol = 1e-10;
  o->atol = 1e-10;
  o->h = 1e-3;
  o->y0 = NULL;
  o->nblocks = 4;
  o->max_steps = 10000000;
  return d;
}

/// the run: system, work state, tangent workspace, the augmented problem and its integrator
typedef struct lyap {
  const dal_system *sys;
  dal_state *st; // work state: the integrators run on it
  dal_tangent *tg;
  const dal_lyapunov_opts *o;
  int n, ny, p, m;      // coordinates, 2n, tangent vectors, augmented size 2n (1 + p)
  double *Z;            // n x p scratch
  double *Y;            // current (y, V)
  double *tau, *qrwork; // QR
  lapack_int lwork;
  dal_first_order fo; // Y' = F(t, Y) for the library's integrators
  dal_solve_opts so;  // their options (tolerances as for dal_advance; the method resolved)
  dal_integ *it;      // the integrator handle, kept between segments while it can go on
  double h;           // the last full step of the previous segment (the next one's first)
  long steps;         // accepted steps (counted in the work state's statistics)
  int ymoved;         // the projection moved the trajectory at the last QR (constraint rows)
  // constraint rows: the full-space KKT tangent A (2n x 2n), and the basis N, Yb (n x k) of
  // the manifold's tangent space where the vectors start and are projected back at every QR
  double *A, *N, *Yb;
  // the averages: sums of log |R_jj| after the transient, their blocking, the last QR's logs,
  // the running estimates (p each)
  double *sum, *lg, *est;
  struct lyap_blocking *bk;
} lyap;

/// levels of the blocking analysis: blocks of 1, 2, 4, ... segments
#define LYAP_LEVELS 48
/// Flyvbjerg-Petersen blocking of the local exponents of one tangent vector, online: level k
/// holds blocks of 2^k consecutive segments (their exponent: sum of log |R_jj| over the sum of
/// their lengths), the pending partial block and the sums of the completed ones
typedef struct lyap_blocking {
  double pl[LYAP_LEVELS], pd[LYAP_LEVELS]; // pending block: sum of logs, of lengths
  int pc[LYAP_LEVELS];                     // blocks of the level below in it
  long n[LYAP_LEVELS];                     // completed blocks
  double s1[LYAP_LEVELS], s2[LYAP_LEVELS]; // sums of their exponents and squares
} lyap_blocking;

// one segment of length dt with log growth lg
static void blocking_add(lyap_blocking *b, double lg, double dt) {
  for (int k = 0; k < LYAP_LEVELS; ++k) {
    b->pl[k] += lg;
    b->pd[k] += dt;
    if (++b->pc[k] < (k == 0 ? 1 : 2)) return;
    double e = b->pl[k] / b->pd[k];
    b->n[k]++;
    b->s1[k] += e;
    b->s2[k] += e * e;
    lg = b->pl[k];
    dt = b->pd[k];
    b->pl[k] = b->pd[k] = 0.0;
    b->pc[k] = 0;
  }
}

// two-sided 95% quantile of Student's t with nu degrees of freedom (Cornish-Fisher expansion
// about the normal quantile 1.96; within 0.5% of the tables for nu >= 3, 2% at nu = 2)
static double student95(long nu) {
  const double z = 1.959963984540054, z3 = z * z * z, z5 = z3 * z * z;
  double v = (double)nu;
  return z + (z3 + z) / (4 * v) + (5 * z5 + 16 * z3 + 3 * z) / (96 * v * v) +
         (3 * z5 * z * z + 19 * z5 + 17 * z3 - 15 * z) / (384 * v * v * v);
}

// the error of the mean exponent: the largest 95% half-width t * s / sqrt(n) over the
// blockings that keep at least nmin blocks (the standard error grows with the block length
// while the blocks are correlated, and levels off once they are not)
static double blocking_error(const lyap_blocking *b, int nmin) {
  double err = -1.0;
  for (int k = 0; k < LYAP_LEVELS; ++k) {
    long n = b->n[k];
    if (n < nmin || n < 2) continue;
    double mean = b->s1[k] / n, var = fmax(0.0, (b->s2[k] - n * mean * mean) / (n - 1));
    err = fmax(err, student95(n - 1) * sqrt(var / n));
  }
  return err >= 0 ? err : INFINITY;
}

// with constraint rows: F = (f, A V) with the full-space tangent of the index-1 field (the
// state evaluated, its tangent taken)
static int aug_rhs_manifold(lyap *L, const double *Y, double *F) {
  int n = L->n, ny = L->ny, rc = dal__tangent_kkt(L->sys, L->st, L->tg, L->A, NULL, NULL);
  if (rc) return rc;
  const double *qdd = dal_state_qddot(L->st);
  for (int i = 0; i < n; ++i) {
    F[i] = Y[n + i];
    F[n + i] = qdd[i];
  }
  for (int j = 0; j < L->p; ++j) {
    const double *v = Y + (size_t)ny * (1 + j);
    double *f = F + (size_t)ny * (1 + j);
    for (int i = 0; i < ny; ++i) {
      double x = 0.0;
      for (int c = 0; c < ny; ++c)
        x += L->A[(size_t)c * ny + i] * v[c];
      f[i] = x;
    }
  }
  return DAL_OK;
}

// with constraint rows, at a QR time: the trajectory back onto the manifold (its drift is the
// integrator's error) and the tangent vectors onto the tangent space there,
// v = (vq, vv) -> (N N' vq, Yb N' vq + N N' vv) (the manifold's tangent space in the basis of
// dal__tangent_basis); also the start's vectors (init: the first p columns of that basis)
static int manifold_project(lyap *L, double t, int init) {
  int n = L->n, ny = L->ny, k = n - L->sys->m, rc;
  double *Y = L->Y;
  if ((rc = dal__analysis_eval(L->sys, L->st, t, Y, Y + n)) != 0) return rc;
  if ((rc = dal__project_state(L->sys, L->st, 1e-13, 20, NULL)) != 0) return rc;
  if ((rc = dal_forward(L->sys, L->st)) != 0) return rc;
  memcpy(Y, L->st->q, (size_t)n * sizeof(double));
  memcpy(Y + n, L->st->qdot, (size_t)n * sizeof(double));
  L->ymoved = 1; // the integrator's y changed in full
  if ((rc = dal__tangent_eval(L->sys, L->st, L->tg, 0)) != 0) return rc;
  if ((rc = dal__tangent_basis(L->sys, L->st, L->tg, L->N, L->Yb, NULL)) != 0) return rc;
  for (int j = 0; j < L->p; ++j) {
    double *v = Y + (size_t)ny * (1 + j), *xi = L->Z, *eta = L->Z + k;
    for (int a = 0; a < k; ++a) {
      double x = 0.0, e = 0.0;
      for (int i = 0; i < n; ++i) {
        x += L->N[(size_t)a * n + i] * v[i];
        e += L->N[(size_t)a * n + i] * v[n + i];
      }
      xi[a] = init ? (j == a) : x;
      eta[a] = init ? (j == k + a) : e;
    }
    for (int i = 0; i < n; ++i) {
      double vq = 0.0, vv = 0.0;
      for (int a = 0; a < k; ++a) {
        vq += L->N[(size_t)a * n + i] * xi[a];
        vv += L->Yb[(size_t)a * n + i] * xi[a] + L->N[(size_t)a * n + i] * eta[a];
      }
      v[i] = vq;
      v[n + i] = vv;
    }
  }
  return DAL_OK;
}

// augmented right-hand side F = (f(t, y), (df/dy) V)
static int aug_rhs(void *ctx, dal_state *st, double t, const double *Y, double *F) {
  lyap *L = ctx;
  int n = L->n, ny = L->ny, rc;
  if (L->sys->m > 0) {
    if ((rc = dal__analysis_eval(L->sys, st, t, Y, Y + n)) != 0) return rc;
    if ((rc = dal__tangent_eval(L->sys, st, L->tg, 0)) != 0) return rc;
    return aug_rhs_manifold(L, Y, F);
  }
  // the trajectory point, evaluated (no validation or reset of a public dal_state_set: the
  // integrator's values are finite, its progress guard checks them)
  st->t = t;
  memcpy(st->q, Y, (size_t)n * sizeof(double));
  memcpy(st->qdot, Y + n, (size_t)n * sizeof(double));
  dal__state_moved(st);
  if ((rc = dal__eval(L->sys, st, DAL_P_ALL)) != 0) return rc;
  if ((rc = dal__tangent_eval(L->sys, st, L->tg, 0)) != 0) return rc;
  if ((rc = dal__tangent_factor(L->sys, st, L->tg)) != 0) return rc;
  const double *qdd = dal_state_qddot(st);
  for (int i = 0; i < n; ++i) {
    F[i] = Y[n + i];
    F[n + i] = qdd[i];
  }
  // each tangent vector v = (vq, vu): (vu, -M^-1 (K vq + C vu))
  for (int j = 0; j < L->p; ++j) {
    const double *v = Y + (size_t)ny * (1 + j);
    double *z = L->Z + (size_t)n * j;
    for (int i = 0; i < n; ++i) {
      double s = 0.0;
      for (int c = 0; c < n; ++c)
        s += L->tg->Rq[(size_t)c * n + i] * v[c] + L->tg->Ru[(size_t)c * n + i] * v[n + c];
      z[i] = -s;
    }
  }
  dal__tangent_msolve(L->tg, L->p, L->Z);
  for (int j = 0; j < L->p; ++j) {
    const double *v = Y + (size_t)ny * (1 + j);
    double *f = F + (size_t)ny * (1 + j);
    for (int i = 0; i < n; ++i) {
      f[i] = v[n + i];
      f[n + i] = L->Z[(size_t)n * j + i];
    }
  }
  return DAL_OK;
}

// Y from t to t1 by the library's integrator. A method that can go on after the QR changed V
// (change_y: RK4, Bulirsch-Stoer) keeps its integrator, compensation and step; the others get
// a fresh one per segment, its first step the last full one before. On failure Y and t hold
// the last accepted step and the work state's message says what failed.
static int segment(lyap *L, double *t, double t1) {
  if (L->steps >= L->o->max_steps) return DAL_E_MAXSTEPS;
  dal_integ *it = L->it;
  // the vectors changed, and the trajectory too when it was projected
  if (it && !it->ops->change_y(it, L->ymoved ? 0 : L->ny, L->Y)) {
    dal__integ_destroy(it);
    it = L->it = NULL;
  }
  if (!it) {
    dal_solve_opts so = L->so;
    if (L->h > 0 && !dal__method_fixed(so.method, &so)) so.h0 = fmin(L->h, t1 - *t);
    L->st->t = *t;
    L->fo.y0 = L->Y;
    int rc = dal__integ_create_fo(L->sys, L->st, &so, &L->fo, &L->it);
    if (rc) return rc;
    it = L->it;
  }
  L->ymoved = 0;
  it->opts.max_steps = L->o->max_steps - L->steps;
  long before = L->st->stats.steps;
  int rc = it->ops->advance(it, t1, NULL, NULL);
  memcpy(L->Y, it->y, (size_t)L->m * sizeof(double));
  double a = 0, b = 0;
  it->ops->window(it, &a, &b);
  *t = b;
  long taken = L->st->stats.steps - before;
  L->steps += taken;
  // the step before a landing step shortened to t1 is the natural one
  if (taken > 1 || b - a > L->h) L->h = b - a;
  return rc;
}

// V = Q R: V becomes Q, logs of |R_ii| into lg (p)
static int orthonormalize(lyap *L, double *lg) {
  int ny = L->ny, p = L->p;
  double *V = L->Y + ny;
  lapack_int info =
      LAPACKE_dgeqrf_work(LAPACK_COL_MAJOR, ny, p, V, ny, L->tau, L->qrwork, L->lwork);
  if (info != 0) return DAL_E_SINGULAR;
  for (int j = 0; j < p; ++j)
    lg[j] = log(fabs(V[(size_t)j * ny + j]));
  info = LAPACKE_dorgqr_work(LAPACK_COL_MAJOR, ny, p, p, V, ny, L->tau, L->qrwork, L->lwork);
  return info != 0 ? DAL_E_SINGULAR : DAL_OK;
}

static void lyap_free(lyap *L) {
  dal__integ_destroy(L->it);
  free(L->sum);
  free(L->lg);
  free(L->est);
  free(L->bk);
  free(L->Y);
  free(L->Z);
  free(L->tau);
  free(L->qrwork);
  free(L->A);
  free(L->N);
  free(L->Yb);
  dal__tangent_free(L->tg);
  dal_state_destroy(L->st);
}

// the options checked, and the method that runs them (*meth: AUTO resolved by the method rows)
static int check_opts(const dal_system *sys, dal_state *st, const dal_lyapunov_opts *o,
                      dal_method *meth) {
  int ny = 2 * (sys->n - sys->m); // the manifold's dimension with constraint rows
  if (!o || o->cookie != DAL_LYAP_COOKIE)
    return DAL_FAIL(st, DAL_E_ARG,
                    "lyapunov: options not initialized: call "
                    "dal_default_lyapunov_opts");
  // AUTO: the rule of the first-order problems (methods.c), validated on this tangent system
  int rc = dal__fo_method(st, o->method, o->rtol, 0, "lyapunov", meth);
  if (rc) return rc;
  if (o->nexp < 0 || o->nexp > ny)
    return DAL_FAIL(st, DAL_E_ARG, "lyapunov: nexp = %d must lie in 0 .. 2(n - m) = %d", o->nexp,
                    ny);
  if (o->y0 && sys->m > 0)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "lyapunov: initial vectors y0 with constraint rows: the vectors start on the "
                    "manifold's tangent space; leave y0 NULL");

  if (!isfinite(o->t_end) || !(o->t_end > st->t))
    return DAL_FAIL(st, DAL_E_ARG, "lyapunov: t_end = %g must be finite and after t = %.17g",
                    o->t_end, st->t);
  if (!(o->transient >= 0) || !(o->transient < o->t_end - st->t))
    return DAL_FAIL(st, DAL_E_ARG,
                    "lyapunov: transient = %g must be >= 0 and shorter than t_end - t = %g",
                    o->transient, o->t_end - st->t);
  if (!(o->renorm > 0) || !isfinite(o->renorm) || o->nblocks < 2 || o->max_steps < 1)
    return DAL_FAIL(st, DAL_E_ARG,
                    "lyapunov: renorm = %g must be finite and > 0, nblocks = %d >= 2, max_steps "
                    "= %ld >= 1",
                    o->renorm, o->nblocks, o->max_steps);
  // a fixed-step method (its row: RK4) takes the step h and no tolerances
  int fixed = dal__method_row(*meth)->fixed == 1;
  if (fixed && (!(o->h > 0) || !isfinite(o->h)))
    return DAL_FAIL(st, DAL_E_ARG, "lyapunov: RK4 step h = %g must be finite and > 0", o->h);
  // the progress guard: a segment or step of a few ulps of t cannot advance t
  double tmax = fmax(fabs(st->t), fabs(o->t_end)), tiny = DAL_TINY_STEP(tmax);
  if (o->renorm <= tiny || (fixed && o->h <= tiny))
    return DAL_FAIL(st, DAL_E_ARG,
                    "lyapunov: %s = %g is below the floating-point resolution of t near %g (%g, "
                    "a few ulps): t would not advance; use a larger value or restart the clock "
                    "near 0",
                    o->renorm <= tiny ? "renorm" : "RK4 step h",
                    o->renorm <= tiny ? o->renorm : o->h, tmax, tiny);
  if (!fixed && (!(o->rtol > 0) || !(o->atol > 0) || !isfinite(o->rtol) || !isfinite(o->atol)))
    return DAL_FAIL(st, DAL_E_ARG, "lyapunov: rtol = %g and atol = %g must be finite and > 0",
                    o->rtol, o->atol);
  if (o->y0)
    for (int i = 0; i < ny * (o->nexp ? o->nexp : ny); ++i)
      if (!isfinite(o->y0[i]))
        return DAL_FAIL(st, DAL_E_NONFINITE, "lyapunov: y0[%d] (vector %d, component %d) is %g", i,
                        i / ny, i % ny, o->y0[i]);
  return DAL_OK;
}

// the work state, the augmented (y, V) and the workspaces of L for options o (sizes set), and
// the integrator's options; 0 or a status with the caller's state message set
static int lyap_alloc(lyap *L, const dal_system *sys, dal_state *st, const dal_lyapunov_opts *o,
                      dal_method meth) {
  memset(L, 0, sizeof *L);
  L->sys = sys;
  L->o = o;
  L->n = sys->n;
  L->ny = 2 * sys->n;
  L->p = o->nexp ? o->nexp : 2 * (sys->n - sys->m);
  L->m = L->ny * (1 + L->p);
  int ny = L->ny, p = L->p;
  size_t m = (size_t)L->m;
  // the work state carries the state's parameter overrides (a sweep's per-trajectory values)
  int ok = dal_state_create(sys, &L->st) == 0 && dal_state_copy_params(sys, L->st, st) == 0 &&
           dal__tangent_create(sys, &L->tg) == 0;
  ok = ok && (L->Y = calloc(m, sizeof(double))) &&
       (L->Z = calloc((size_t)L->n * p + 2 * (size_t)L->n + 1, sizeof(double))) &&
       (L->tau = calloc((size_t)p, sizeof(double))) &&
       (L->sum = calloc((size_t)p, sizeof(double))) && (L->bk = calloc((size_t)p, sizeof *L->bk)) &&
       (L->lg = calloc((size_t)p, sizeof(double))) && (L->est = calloc((size_t)p, sizeof(double)));
  if (ok && sys->m > 0)
    ok = (L->A = calloc((size_t)ny * ny, sizeof(double))) &&
         (L->N = calloc((size_t)L->n * L->n + 1, sizeof(double))) &&
         (L->Yb = calloc((size_t)L->n * L->n + 1, sizeof(double)));
  if (ok) {
    // workspace of the QR factorization and of forming Q
    double q1 = 0.0, q2 = 0.0;
    ok = LAPACKE_dgeqrf_work(LAPACK_COL_MAJOR, ny, p, L->Y + ny, ny, L->tau, &q1, -1) == 0 &&
         LAPACKE_dorgqr_work(LAPACK_COL_MAJOR, ny, p, p, L->Y + ny, ny, L->tau, &q2, -1) == 0;
    L->lwork = (lapack_int)fmax(fmax(q1, q2), 1.0);
    ok = ok && (L->qrwork = calloc((size_t)L->lwork, sizeof(double)));
  }
  if (!ok) return DAL_FAIL(st, DAL_E_NOMEM, "lyapunov: out of memory for %d tangent vectors", p);

  // the integrator: the library's, on the augmented problem, with dal_advance's tolerances
  L->fo.ny = L->m;
  L->fo.rhs = aug_rhs;
  L->fo.ctx = L;
  L->so = dal_default_solve_opts();
  L->so.method = meth;
  L->so.rtol = o->rtol;
  L->so.atol = o->atol;
  L->so.fixed_step = o->h;
  return DAL_OK;
}

// the start: trajectory from the state, tangent vectors (given or the unit vectors) on the
// manifold's tangent space and orthonormalized; 0 or a status with st's message set
static int lyap_start(lyap *L, dal_state *st) {
  const dal_system *sys = L->sys;
  const dal_lyapunov_opts *o = L->o;
  int ny = L->ny, p = L->p, rc;
  double t = st->t, *lg = L->lg;
  memcpy(L->Y, st->q, (size_t)L->n * sizeof(double));
  memcpy(L->Y + L->n, st->qdot, (size_t)L->n * sizeof(double));
  for (int j = 0; j < p; ++j)
    for (int i = 0; i < ny; ++i)
      L->Y[(size_t)ny * (1 + j) + i] = o->y0 ? o->y0[(size_t)j * ny + i] : (i == j ? 1.0 : 0.0);
  if (sys->m > 0) { // a consistent start, the vectors on the manifold's tangent space
    if ((rc = dal__analysis_eval(sys, L->st, t, L->Y, L->Y + L->n)) != 0 ||
        (rc = dal__tangent_eval(sys, L->st, L->tg, 0)) != 0 ||
        (rc = dal__tangent_on_manifold(sys, L->st, L->tg, "lyapunov")) != 0 ||
        (rc = manifold_project(L, t, 1)) != 0) {
      memcpy(st->err, L->st->err, sizeof st->err);
      return rc;
    }
  }
  if (orthonormalize(L, lg) != 0)
    return DAL_FAIL(st, DAL_E_ARG, "lyapunov: the initial tangent vectors could not be factored");
  for (int j = 0; j < p; ++j)
    if (!(lg[j] > log(1e-12)) || !isfinite(lg[j]))
      return DAL_FAIL(st, DAL_E_ARG,
                      "lyapunov: initial tangent vector %d depends on the previous ones (|R_%d%d| "
                      "= %.3g); give linearly independent vectors",
                      j, j, j, exp(lg[j]));
  return DAL_OK;
}

// the segments from *t to o->t_end: QR every `renorm` and at the block boundaries of the
// averaging window after the transient (which starts at ta); *t ends where the run stopped
static int lyap_run(lyap *L, dal_state *st, double *t, double ta, dal_lyapunov_fn *monitor,
                    void *ctx) {
  const dal_lyapunov_opts *o = L->o;
  int nb = o->nblocks, p = L->p, block = 0, rc;
  double span = o->t_end - ta, *lg = L->lg;
  while (*t < o->t_end) {
    int averaging = *t >= ta;
    double bound = averaging ? ta + span * (block + 1) / nb : ta;
    if (averaging && block == nb - 1) bound = o->t_end;
    double t1 = fmin(*t + o->renorm, bound);
    if (bound - t1 < 1e-9 * o->renorm) t1 = bound;
    double tprev = *t;
    rc = segment(L, t, t1);
    if (!rc && !(*t > tprev))
      rc = DAL_FAIL(L->st, DAL_E_STEP, "lyapunov: no progress at t=%.17g (segment to %.17g)", *t,
                    t1);
    if (rc == DAL_E_MAXSTEPS)
      rc = DAL_FAIL(L->st, DAL_E_MAXSTEPS, "lyapunov: more than %ld steps before t=%.17g",
                    o->max_steps, o->t_end);
    if (!rc && L->sys->m > 0) rc = manifold_project(L, *t, 0);
    if (rc) {
      memcpy(st->err, L->st->err, sizeof st->err);
      return rc;
    }
    if (orthonormalize(L, lg) != 0)
      return DAL_FAIL(st, DAL_E_SINGULAR, "lyapunov: QR factorization failed at t=%.17g", *t);
    if (!averaging) continue;
    for (int j = 0; j < p; ++j) {
      if (!isfinite(lg[j]))
        return DAL_FAIL(st, DAL_E_SINGULAR,
                        "lyapunov: tangent vector %d collapsed at t=%.17g (|R| = %g); shorten "
                        "renorm",
                        j, *t, exp(lg[j]));
      L->sum[j] += lg[j];
      blocking_add(&L->bk[j], lg[j], *t - tprev);
      L->est[j] = L->sum[j] / (*t - ta);
    }
    if (*t >= bound && block < nb - 1) ++block;
    if (monitor && monitor(*t, L->est, p, ctx)) break;
  }
  return DAL_OK;
}

// the exponents averaged over [ta, t] and their errors, largest first
static void lyap_results(const lyap *L, double t, double ta, double *exponents, double *errors) {
  int p = L->p;
  for (int j = 0; j < p; ++j) {
    exponents[j] = t > ta ? L->sum[j] / (t - ta) : NAN;
    if (errors) errors[j] = blocking_error(&L->bk[j], L->o->nblocks);
  }
  // largest first (decoupled invariant subspaces keep the QR columns in their initial order)
  for (int i = 1; i < p; ++i)
    for (int j = i; j > 0 && exponents[j] > exponents[j - 1]; --j) {
      double x = exponents[j];
      exponents[j] = exponents[j - 1];
      exponents[j - 1] = x;
      if (errors) {
        x = errors[j];
        errors[j] = errors[j - 1];
        errors[j - 1] = x;
      }
    }
}

int dal_lyapunov(const dal_system *sys, dal_state *st, const dal_lyapunov_opts *o,
                 double *exponents, double *errors, dal_lyapunov_fn *monitor, void *ctx) {
  if (!st) return DAL_E_ARG;
  if (!sys || st->sys != sys)
    return DAL_FAIL(st, DAL_E_STATE, "lyapunov: the state belongs to another system");
  if (dal__check_idle(st, "lyapunov")) return DAL_E_STATE;
  if (!exponents) return DAL_FAIL(st, DAL_E_ARG, "lyapunov: exponents is NULL");
  dal_method meth = DAL_METHOD_AUTO;
  int rc = check_opts(sys, st, o, &meth);
  if (!rc) rc = dal__tangent_supported(sys, st, "lyapunov");
  if (rc) return rc;
  lyap L;
  double t = st->t, ta = t + o->transient;
  if ((rc = lyap_alloc(&L, sys, st, o, meth)) == 0 && (rc = lyap_start(&L, st)) == 0 &&
      (rc = lyap_run(&L, st, &t, ta, monitor, ctx)) == 0) {
    lyap_results(&L, t, ta, exponents, errors);
    // leave the user's state at the end of the trajectory, evaluated
    rc = dal__analysis_eval(sys, st, t, L.Y, L.Y + L.n);
  }
  lyap_free(&L);
  return rc;
}
