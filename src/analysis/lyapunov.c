// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Lyapunov exponents: trajectory and exact tangent vectors integrated together, QR
// reorthonormalization (Benettin, Galgani, Giorgilli, Strelcyn, Meccanica 15, 1980).
//
// The augmented system is Y = (y, V) with y' = f(t, y) and V' = (df/dy) V, V = 2n x p. Its
// integrator is this file's own: classical RK4 at a fixed step, or Dormand-Prince 5(4) with
// the step control of Hairer-Norsett-Wanner, Solving ODEs I, sec. II.4 (coefficients of
// Table 5.2). A Runge-Kutta step of the augmented system applies the method's own derivative
// to V, so V is the exact tangent of the numerical flow.
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
  o->method = DAL_METHOD_DOPRI5;
  o->rtol = 1e-10;
  o->atol = 1e-10;
  o->h = 1e-3;
  o->y0 = NULL;
  o->nblocks = 10;
  o->max_steps = 10000000;
  return d;
}

/// the run: system, scratch state, tangent workspace and integrator memory
typedef struct lyap {
  const dal_system *sys;
  dal_state *st;
  dal_tangent *tg;
  const dal_lyapunov_opts *o;
  int n, ny, p, m;            // coordinates, 2n, tangent vectors, augmented size 2n (1 + p)
  double *Z;                  // n x p scratch
  double *k[7], *yt, *y1, *Y; // integrator stages, trial state, result, current state
  double *kc;                 // RK4: compensation of the trajectory's sum (ny; Kahan, as the
                              // library's RK4, so both follow the same orbit to the bit)
  double *tau, *qrwork;       // QR
  lapack_int lwork;
  double h;   // DOPRI5 step carried between segments
  long steps; // accepted steps
  // constraint rows: the full-space KKT tangent A (2n x 2n), and the basis N, Yb (n x k) of
  // the manifold's tangent space where the vectors start and are projected back at every QR
  double *A, *N, *Yb;
} lyap;

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
  memset(L->kc, 0, (size_t)ny * sizeof(double)); // RK4's compensation belongs to the old y
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
static int aug_rhs(lyap *L, double t, const double *Y, double *F) {
  int n = L->n, ny = L->ny, rc;
  if ((rc = dal__analysis_eval(L->sys, L->st, t, Y, Y + n)) != 0) return rc;
  if ((rc = dal__tangent_eval(L->sys, L->st, L->tg, 0)) != 0) return rc;
  if (L->sys->m > 0) return aug_rhs_manifold(L, Y, F);
  if ((rc = dal__tangent_factor(L->sys, L->st, L->tg)) != 0) return rc;
  const double *qdd = dal_state_qddot(L->st);
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

// classical RK4 from t over [t, t1] in steps of at most h (the last one shortened)
static int rk4_segment(lyap *L, double *t, double t1) {
  int m = L->m, rc;
  double *y = L->Y, *yt = L->yt, **k = L->k;
  while (*t < t1) {
    double h = L->o->h;
    if (*t + h > t1 - 1e-9 * h) h = t1 - *t;
    if ((rc = aug_rhs(L, *t, y, k[0])) != 0) return rc;
    for (int i = 0; i < m; ++i)
      yt[i] = y[i] + 0.5 * h * k[0][i];
    if ((rc = aug_rhs(L, *t + 0.5 * h, yt, k[1])) != 0) return rc;
    for (int i = 0; i < m; ++i)
      yt[i] = y[i] + 0.5 * h * k[1][i];
    if ((rc = aug_rhs(L, *t + 0.5 * h, yt, k[2])) != 0) return rc;
    for (int i = 0; i < m; ++i)
      yt[i] = y[i] + h * k[2][i];
    if ((rc = aug_rhs(L, *t + h, yt, k[3])) != 0) return rc;
    for (int i = 0; i < m; ++i) {
      double d = h * (k[0][i] / 6.0 + k[1][i] / 3.0 + k[2][i] / 3.0 + k[3][i] / 6.0);
      if (i < L->ny) {
        dal__ksum(&y[i], &L->kc[i], d); // the trajectory compensated, like ode_rk4.c
      } else {
        y[i] += d;
      }
    }
    *t = h == t1 - *t ? t1 : *t + h;
    if (++L->steps > L->o->max_steps) return DAL_E_MAXSTEPS;
  }
  return DAL_OK;
}

// Dormand-Prince 5(4) tableau
static const double dp_c[7] = {0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1, 1};
static const double dp_a[7][6] = {
    {0},
    {1.0 / 5},
    {3.0 / 40, 9.0 / 40},
    {44.0 / 45, -56.0 / 15, 32.0 / 9},
    {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729},
    {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656},
    {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84}};
// error coefficients: 5th-order weights minus the embedded 4th-order ones
static const double dp_e[7] = {71.0 / 57600,      0,          -71.0 / 16695, 71.0 / 1920,
                               -17253.0 / 339200, 22.0 / 525, -1.0 / 40};

// DOPRI5 over [t, t1]: steps under error control, the last one landing on t1
static int dopri_segment(lyap *L, double *t, double t1) {
  int m = L->m, rc;
  const dal_lyapunov_opts *o = L->o;
  double *y = L->Y, *yt = L->yt, *y1 = L->y1, **k = L->k;
  if ((rc = aug_rhs(L, *t, y, k[0])) != 0) return rc;
  if (L->h <= 0) {
    // starting step from the sizes of y and f (Hairer-Norsett-Wanner II.4)
    double d0 = 0, d1 = 0;
    for (int i = 0; i < m; ++i) {
      double sc = o->atol + o->rtol * fabs(y[i]);
      d0 += (y[i] / sc) * (y[i] / sc);
      d1 += (k[0][i] / sc) * (k[0][i] / sc);
    }
    d0 = sqrt(d0 / m);
    d1 = sqrt(d1 / m);
    L->h = d0 > 1e-5 && d1 > 1e-5 ? 0.01 * d0 / d1 : 1e-6;
  }
  while (*t < t1) {
    double h = fmin(L->h, t1 - *t);
    int last = h == t1 - *t;
    if (h <= 1e-14 * fmax(1.0, fabs(*t))) {
      char qs[256];
      dal__fmt_q(L->sys, L->Y, qs, sizeof qs);
      return DAL_FAIL(L->st, DAL_E_STEP,
                      "lyapunov: DOPRI5 step size underflow (h = %.3g) at t=%.17g, %s; loosen "
                      "rtol/atol or use RK4 with a fixed step",
                      h, *t, qs);
    }
    for (int s = 1; s < 7; ++s) {
      for (int i = 0; i < m; ++i) {
        double acc = 0.0;
        for (int j = 0; j < s; ++j)
          acc += dp_a[s][j] * k[j][i];
        (s == 6 ? y1 : yt)[i] = y[i] + h * acc;
      }
      if ((rc = aug_rhs(L, *t + dp_c[s] * h, s == 6 ? y1 : yt, k[s])) != 0) return rc;
    }
    double err = 0.0;
    for (int i = 0; i < m; ++i) {
      double e = 0.0;
      for (int s = 0; s < 7; ++s)
        e += dp_e[s] * k[s][i];
      double sc = o->atol + o->rtol * fmax(fabs(y[i]), fabs(y1[i]));
      err += (h * e / sc) * (h * e / sc);
    }
    err = sqrt(err / m);
    double fac = err > 0 ? 0.9 * pow(err, -0.2) : 10.0;
    fac = fmin(10.0, fmax(0.2, fac));
    if (err <= 1.0) {
      memcpy(y, y1, (size_t)m * sizeof(double));
      memcpy(k[0], k[6], (size_t)m * sizeof(double)); // first same as last
      *t = last ? t1 : *t + h;
      if (++L->steps > o->max_steps) return DAL_E_MAXSTEPS;
      if (!last || fac < 1.0) L->h = h * fac;
    } else {
      L->h = h * fmin(1.0, fac);
    }
  }
  return DAL_OK;
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
  for (int i = 0; i < 7; ++i)
    free(L->k[i]);
  free(L->yt);
  free(L->kc);
  free(L->y1);
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

static int check_opts(const dal_system *sys, dal_state *st, const dal_lyapunov_opts *o) {
  int ny = 2 * (sys->n - sys->m); // the manifold's dimension with constraint rows
  if (!o || o->cookie != DAL_LYAP_COOKIE)
    return DAL_FAIL(st, DAL_E_ARG,
                    "lyapunov: options not initialized: call "
                    "dal_default_lyapunov_opts");
  if (o->method != DAL_METHOD_DOPRI5 && o->method != DAL_METHOD_RK4)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "lyapunov: method '%s' is not available for the variational equations; use "
                    "DAL_METHOD_DOPRI5 or DAL_METHOD_RK4",
                    dal_method_name(o->method));
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
  if (o->method == DAL_METHOD_RK4 && (!(o->h > 0) || !isfinite(o->h)))
    return DAL_FAIL(st, DAL_E_ARG, "lyapunov: RK4 step h = %g must be finite and > 0", o->h);
  // the progress guard: a segment or step of a few ulps of t cannot advance t
  double tmax = fmax(fabs(st->t), fabs(o->t_end)), tiny = DAL_TINY_STEP(tmax);
  if (o->renorm <= tiny || (o->method == DAL_METHOD_RK4 && o->h <= tiny))
    return DAL_FAIL(st, DAL_E_ARG,
                    "lyapunov: %s = %g is below the floating-point resolution of t near %g (%g, "
                    "a few ulps): t would not advance; use a larger value or restart the clock "
                    "near 0",
                    o->renorm <= tiny ? "renorm" : "RK4 step h",
                    o->renorm <= tiny ? o->renorm : o->h, tmax, tiny);
  if (o->method == DAL_METHOD_DOPRI5 &&
      (!(o->rtol > 0) || !(o->atol > 0) || !isfinite(o->rtol) || !isfinite(o->atol)))
    return DAL_FAIL(st, DAL_E_ARG, "lyapunov: rtol = %g and atol = %g must be finite and > 0",
                    o->rtol, o->atol);
  if (o->y0)
    for (int i = 0; i < ny * (o->nexp ? o->nexp : ny); ++i)
      if (!isfinite(o->y0[i]))
        return DAL_FAIL(st, DAL_E_NONFINITE, "lyapunov: y0[%d] (vector %d, component %d) is %g", i,
                        i / ny, i % ny, o->y0[i]);
  return DAL_OK;
}

int dal_lyapunov(const dal_system *sys, dal_state *st, const dal_lyapunov_opts *o,
                 double *exponents, double *errors, dal_lyapunov_fn *monitor, void *ctx) {
  if (!st) return DAL_E_ARG;
  if (!sys || st->sys != sys)
    return DAL_FAIL(st, DAL_E_STATE, "lyapunov: the state belongs to another system");
  if (dal__check_idle(st, "lyapunov")) return DAL_E_STATE;
  if (!exponents) return DAL_FAIL(st, DAL_E_ARG, "lyapunov: exponents is NULL");
  int rc = check_opts(sys, st, o);
  if (!rc) rc = dal__tangent_supported(sys, st, "lyapunov");
  if (rc) return rc;

  lyap L;
  memset(&L, 0, sizeof L);
  L.sys = sys;
  L.o = o;
  L.n = sys->n;
  L.ny = 2 * sys->n;
  L.p = o->nexp ? o->nexp : 2 * (sys->n - sys->m);
  L.m = L.ny * (1 + L.p);
  int nb = o->nblocks, ny = L.ny, p = L.p;
  double *sum = NULL, *blk = NULL, *lg = NULL, *est = NULL;
  size_t m = (size_t)L.m;
  // the work state carries the state's parameter overrides (a sweep's per-trajectory values)
  int ok = dal_state_create(sys, &L.st) == 0 && dal_state_copy_params(sys, L.st, st) == 0 &&
           dal__tangent_create(sys, &L.tg) == 0;
  for (int i = 0; i < 7 && ok; ++i)
    ok = (L.k[i] = calloc(m, sizeof(double))) != NULL;
  ok = ok && (L.yt = calloc(m, sizeof(double))) && (L.y1 = calloc(m, sizeof(double))) &&
       (L.kc = calloc(m, sizeof(double))) && (L.Y = calloc(m, sizeof(double))) &&
       (L.Z = calloc((size_t)L.n * p + 2 * (size_t)L.n + 1, sizeof(double))) &&
       (L.tau = calloc((size_t)p, sizeof(double))) && (sum = calloc((size_t)p, sizeof(double))) &&
       (blk = calloc((size_t)p * nb, sizeof(double))) && (lg = calloc((size_t)p, sizeof(double))) &&
       (est = calloc((size_t)p, sizeof(double)));
  if (ok && sys->m > 0)
    ok = (L.A = calloc((size_t)ny * ny, sizeof(double))) &&
         (L.N = calloc((size_t)L.n * L.n + 1, sizeof(double))) &&
         (L.Yb = calloc((size_t)L.n * L.n + 1, sizeof(double)));
  if (ok) {
    // workspace of the QR factorization and of forming Q
    double q1 = 0.0, q2 = 0.0;
    ok = LAPACKE_dgeqrf_work(LAPACK_COL_MAJOR, ny, p, L.Y + ny, ny, L.tau, &q1, -1) == 0 &&
         LAPACKE_dorgqr_work(LAPACK_COL_MAJOR, ny, p, p, L.Y + ny, ny, L.tau, &q2, -1) == 0;
    L.lwork = (lapack_int)fmax(fmax(q1, q2), 1.0);
    ok = ok && (L.qrwork = calloc((size_t)L.lwork, sizeof(double)));
  }
  if (!ok) {
    rc = DAL_FAIL(st, DAL_E_NOMEM, "lyapunov: out of memory for %d tangent vectors", p);
    goto done;
  }

  // the start: trajectory from the state, tangent vectors orthonormalized
  double t = st->t;
  memcpy(L.Y, st->q, (size_t)L.n * sizeof(double));
  memcpy(L.Y + L.n, st->qdot, (size_t)L.n * sizeof(double));
  for (int j = 0; j < p; ++j)
    for (int i = 0; i < ny; ++i)
      L.Y[(size_t)ny * (1 + j) + i] = o->y0 ? o->y0[(size_t)j * ny + i] : (i == j ? 1.0 : 0.0);
  if (sys->m > 0) { // a consistent start, the vectors on the manifold's tangent space
    if ((rc = dal__analysis_eval(sys, L.st, t, L.Y, L.Y + L.n)) != 0 ||
        (rc = dal__tangent_eval(sys, L.st, L.tg, 0)) != 0 ||
        (rc = dal__tangent_on_manifold(sys, L.st, L.tg, "lyapunov")) != 0 ||
        (rc = manifold_project(&L, t, 1)) != 0) {
      memcpy(st->err, L.st->err, sizeof st->err);
      goto done;
    }
  }
  if (orthonormalize(&L, lg) != 0) {
    rc = DAL_FAIL(st, DAL_E_ARG, "lyapunov: the initial tangent vectors could not be factored");
    goto done;
  }
  for (int j = 0; j < p; ++j)
    if (!(lg[j] > log(1e-12)) || !isfinite(lg[j])) {
      rc = DAL_FAIL(st, DAL_E_ARG,
                    "lyapunov: initial tangent vector %d depends on the previous ones (|R_%d%d| "
                    "= %.3g); give linearly independent vectors",
                    j, j, j, exp(lg[j]));
      goto done;
    }

  // segments: QR every `renorm` and at the block boundaries of the averaging window
  double ta = t + o->transient, span = o->t_end - ta;
  int block = 0;
  while (t < o->t_end) {
    int averaging = t >= ta;
    double bound = averaging ? ta + span * (block + 1) / nb : ta;
    if (averaging && block == nb - 1) bound = o->t_end;
    double t1 = fmin(t + o->renorm, bound);
    if (bound - t1 < 1e-9 * o->renorm) t1 = bound;
    double t_seg = t;
    rc = o->method == DAL_METHOD_RK4 ? rk4_segment(&L, &t, t1) : dopri_segment(&L, &t, t1);
    if (!rc && !(t > t_seg))
      rc = DAL_FAIL(L.st, DAL_E_STEP, "lyapunov: no progress at t=%.17g (segment to %.17g)", t, t1);
    if (rc == DAL_E_MAXSTEPS)
      rc = DAL_FAIL(L.st, DAL_E_MAXSTEPS, "lyapunov: more than %ld steps before t=%.17g",
                    o->max_steps, o->t_end);
    if (!rc && sys->m > 0) rc = manifold_project(&L, t, 0);
    if (rc) {
      memcpy(st->err, L.st->err, sizeof st->err);
      goto done;
    }
    if (orthonormalize(&L, lg) != 0) {
      rc = DAL_FAIL(st, DAL_E_SINGULAR, "lyapunov: QR factorization failed at t=%.17g", t);
      goto done;
    }
    if (!averaging) continue;
    for (int j = 0; j < p; ++j) {
      if (!isfinite(lg[j])) {
        rc = DAL_FAIL(st, DAL_E_SINGULAR,
                      "lyapunov: tangent vector %d collapsed at t=%.17g (|R| = %g); shorten "
                      "renorm",
                      j, t, exp(lg[j]));
        goto done;
      }
      sum[j] += lg[j];
      blk[(size_t)block * p + j] += lg[j];
      est[j] = sum[j] / (t - ta);
    }
    if (t >= bound && block < nb - 1) ++block;
    if (monitor && monitor(t, est, p, ctx)) break;
  }
  for (int j = 0; j < p; ++j) {
    exponents[j] = t > ta ? sum[j] / (t - ta) : NAN;
    if (errors) {
      // standard error of the block means (blocks of equal length span / nb)
      double mean = 0.0, var = 0.0, bl = span / nb;
      int nfull = t >= o->t_end ? nb : block;
      for (int b = 0; b < nfull; ++b)
        mean += blk[(size_t)b * p + j] / bl;
      mean /= nfull > 0 ? nfull : 1;
      for (int b = 0; b < nfull; ++b) {
        double x = blk[(size_t)b * p + j] / bl - mean;
        var += x * x;
      }
      errors[j] = nfull > 1 ? sqrt(var / (nfull - 1) / nfull) : INFINITY;
    }
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
  // leave the user's state at the end of the trajectory, evaluated
  rc = dal__analysis_eval(sys, st, t, L.Y, L.Y + L.n);
done:
  free(sum);
  free(blk);
  free(lg);
  free(est);
  lyap_free(&L);
  return rc;
}
