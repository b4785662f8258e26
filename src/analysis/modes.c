// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Normal modes (K x = omega^2 M x by LAPACK dsygv) and the stability verdict (eigenvalues of
// the first-order Jacobian by LAPACK dgeev).
#include <float.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis.h"

const char *dal_stability_name(dal_stability s) {
  switch (s) {
  case DAL_UNSTABLE:
    return "unstable";
  case DAL_MARGINAL:
    return "marginal";
  case DAL_NEUTRAL:
    return "neutral";
  case DAL_ASYMPTOTIC:
    return "asymptotic";
  }
  return "unknown";
}

// Frobenius norm of the n x n block of A (ld lda) starting at a
static double block_norm(const double *a, int n, size_t lda) {
  double s = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      s += a[(size_t)j * lda + i] * a[(size_t)j * lda + i];
  return sqrt(s);
}

// the verdict from eigenvalues (wr, wi) of df/dy with tolerance tau (see analysis.h)
static dal_stability classify(int m, const double *wr, const double *wi, double tau,
                              double *max_real) {
  double mr = -INFINITY, minabs = INFINITY;
  int on_axis = 0;
  for (int i = 0; i < m; ++i) {
    mr = fmax(mr, wr[i]);
    minabs = fmin(minabs, hypot(wr[i], wi[i]));
    on_axis |= fabs(wr[i]) <= tau;
  }
  *max_real = mr;
  if (mr > tau) return DAL_UNSTABLE;
  if (minabs <= tau) return DAL_MARGINAL;
  return on_axis ? DAL_NEUTRAL : DAL_ASYMPTOTIC;
}

// sort eigenvalue pairs by decreasing real part, then increasing imaginary part (insertion)
static void sort_eigs(int m, double *wr, double *wi) {
  for (int i = 1; i < m; ++i) {
    double r = wr[i], im = wi[i];
    int j = i - 1;
    while (j >= 0 && (wr[j] < r || (wr[j] == r && wi[j] > im))) {
      wr[j + 1] = wr[j];
      wi[j + 1] = wi[j];
      --j;
    }
    wr[j + 1] = r;
    wi[j + 1] = im;
  }
}

// the workspace of dal_normal_modes: k independent coordinates (n without constraints, n - m
// on the manifold), the first-order Jacobian A (2k x 2k), the k x k mass, stiffness and
// damping matrices with their rounding scales, the symmetric part Ks, the basis N (n x k)
typedef struct modes_work {
  int n, k;
  double *A, *Ks, *Mc, *w, *wr, *wi, *Km, *Cm, *Ka, *Ca, *N;
  // norms: K, K's asymmetry, C, M, the largest acceleration, the rounding scales of K and C
  double kn, ka, cn, mn, acc, kabs, cabs;
} modes_work;

// the tangent at the evaluated state into the workspace: reduced to the manifold with
// constraint rows (with the rounding scales |N|' Kabs |N|, |N|' Cabs |N|)
static int modes_tangent(const dal_system *sys, dal_state *st, dal_tangent *tg, modes_work *W) {
  int n = W->n, k = W->k, rc;
  size_t sk = (size_t)k;
  if ((rc = dal__tangent_eval(sys, st, tg, 0)) != 0) return rc;
  if (sys->m == 0) {
    if ((rc = dal__tangent_factor(sys, st, tg)) != 0) return rc;
    memcpy(W->Mc, tg->M, sk * sk * sizeof(double));
    memcpy(W->Km, tg->Rq, sk * sk * sizeof(double));
    memcpy(W->Cm, tg->Ru, sk * sk * sizeof(double));
    memcpy(W->Ka, tg->Kabs, sk * sk * sizeof(double));
    memcpy(W->Ca, tg->Cabs, sk * sk * sizeof(double));
    dal__tangent_flow(tg, W->A, NULL);
    return DAL_OK;
  }
  if ((rc = dal__tangent_on_manifold(sys, st, tg, "normal_modes")) != 0) return rc;
  if ((rc = dal__tangent_reduced(sys, st, tg, W->N, W->A, W->Mc, W->Cm, W->Km)) != 0) return rc;
  const double *N = W->N;
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      double ka = 0.0, ca = 0.0;
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          double nn = fabs(N[(size_t)i * n + a] * N[(size_t)j * n + b]);
          ka += nn * tg->Kabs[(size_t)b * n + a];
          ca += nn * tg->Cabs[(size_t)b * n + a];
        }
      W->Ka[(size_t)j * k + i] = ka;
      W->Ca[(size_t)j * k + i] = ca;
    }
  return DAL_OK;
}

// diagnostics: asymmetry of K, size of C, acceleration at the state; Ks = (K + K') / 2
static void modes_norms(const dal_state *st, modes_work *W) {
  int n = W->n, k = W->k;
  W->kn = W->ka = W->cn = W->mn = W->acc = W->kabs = W->cabs = 0.0;
  for (int j = 0; j < n; ++j)
    W->acc = fmax(W->acc, fabs(st->qddot[j]));
  for (int j = 0; j < k; ++j) {
    for (int i = 0; i < k; ++i) {
      size_t ji = (size_t)j * k + i;
      W->kabs += W->Ka[ji] * W->Ka[ji];
      W->cabs += W->Ca[ji] * W->Ca[ji];
      double kij = W->Km[ji], kt = W->Km[(size_t)i * k + j];
      W->kn += kij * kij;
      W->ka += (kij - kt) * (kij - kt);
      W->cn += W->Cm[ji] * W->Cm[ji];
      W->mn += W->Mc[ji] * W->Mc[ji];
      W->Ks[ji] = 0.5 * (kij + kt);
    }
  }
  W->kn = sqrt(W->kn);
}

// undamped modes: Ks x = omega^2 M x (x' M x = 1), largest component of each shape positive
static int modes_undamped(const dal_system *sys, dal_state *st, modes_work *W, double *omega2,
                          double *shapes) {
  int n = W->n, k = W->k;
  lapack_int info =
      LAPACKE_dsygv(LAPACK_COL_MAJOR, 1, shapes ? 'V' : 'N', 'L', k, W->Ks, k, W->Mc, k, W->w);
  if (info != 0)
    return DAL_FAIL(st, DAL_E_SINGULAR,
                    "normal_modes: LAPACK dsygv failed (info %d) at t=%.17g: %s", (int)info, st->t,
                    info > k ? "the mass matrix is not positive definite"
                             : "the eigenvalue iteration did not converge");
  if (omega2) memcpy(omega2, W->w, (size_t)k * sizeof(double));
  if (!shapes) return DAL_OK;
  // with constraints the shape in the coordinates is N xi (still M-orthonormal)
  for (int j = 0; j < k; ++j) {
    const double *xi = W->Ks + (size_t)j * k;
    double *x = shapes + (size_t)j * n, big = 0.0;
    for (int i = 0; i < n; ++i) {
      double v = xi[i < k ? i : 0];
      if (sys->m > 0) {
        v = 0.0;
        for (int l = 0; l < k; ++l)
          v += W->N[(size_t)l * n + i] * xi[l];
      }
      x[i] = v;
      if (fabs(v) > fabs(big)) big = v;
    }
    if (big < 0)
      for (int i = 0; i < n; ++i)
        x[i] = -x[i];
  }
  return DAL_OK;
}

// the first-order Jacobian's eigenvalues decide stability (damping, gyroscopic terms)
static int modes_stability(dal_state *st, modes_work *W, double *lambda_re, double *lambda_im,
                           dal_modes *out) {
  int k = W->k, k2 = 2 * k;
  double *A = W->A, *wr = W->wr, *wi = W->wi;
  double scale = fmax(sqrt(block_norm(A + k, k, (size_t)k2)),
                      block_norm(A + (size_t)k * k2 + k, k, (size_t)k2));
  lapack_int info = LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', k2, A, k2, wr, wi, NULL, 1, NULL, 1);
  if (info != 0)
    return DAL_FAIL(st, DAL_E_SINGULAR,
                    "normal_modes: LAPACK dgeev did not converge (info %d) at t=%.17g", (int)info,
                    st->t);
  sort_eigs(k2, wr, wi);
  double lmax = 0.0;
  for (int i = 0; i < k2; ++i)
    lmax = fmax(lmax, hypot(wr[i], wi[i]));
  // relative tolerance, and the rounding floor of K and C: a perturbation dK of K moves a
  // zero eigenvalue by sqrt(|dK| / |M|), dC by |dC| / |M| (64 ulps of the terms' magnitudes)
  double mf = sqrt(W->mn), ek = 64 * DBL_EPSILON * sqrt(W->kabs) / mf;
  double ec = 64 * DBL_EPSILON * sqrt(W->cabs) / mf;
  double tau = fmax(1e-6 * fmax(lmax, scale), fmax(sqrt(ek), ec)) + 1e-300, mr;
  dal_stability v = classify(k2, wr, wi, tau, &mr);
  if (lambda_re) memcpy(lambda_re, wr, (size_t)k2 * sizeof(double));
  if (lambda_im) memcpy(lambda_im, wi, (size_t)k2 * sizeof(double));
  if (out) {
    double kn = W->kn, mn = W->mn, cn = W->cn;
    out->verdict = v;
    out->max_real = mr;
    out->tau = tau;
    out->asymmetry = kn > 0 ? sqrt(W->ka) / kn : 0.0;
    out->gyroscopic = kn > 0 && mn > 0 ? sqrt(cn) / sqrt(kn * sqrt(mn)) : sqrt(cn);
    out->accel = W->acc;
  }
  return DAL_OK;
}

// the modes at the state; frozen: 1 to accept an explicitly time-dependent system (its
// frozen linearization), 0 to refuse one
static int normal_modes(const dal_system *sys, dal_state *st, double *omega2, double *shapes,
                        double *lambda_re, double *lambda_im, dal_modes *out, int frozen) {
  if (!st) return DAL_E_ARG;
  if (!sys || st->sys != sys)
    return DAL_FAIL(st, DAL_E_STATE, "normal_modes: the state belongs to another system");
  int rc = dal__tangent_supported(sys, st, "normal_modes");
  if (!rc) rc = dal_forward(sys, st);
  if (rc) return rc;
  // k independent coordinates: n without constraints, n - m on the manifold
  int n = sys->n, k = n - sys->m, k2 = 2 * k;
  if (k <= 0)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "normal_modes: the system has no degrees of freedom (%d constraint row(s) "
                    "on %d coordinate(s), first '%s'): nothing can oscillate, so there are no "
                    "modes and no verdict; if some rows repeat others, remove them",
                    sys->m, n, sys->m ? sys->con[0].name : "");
  // time dependence is never frozen silently: on a time-dependent scene the modes hold only
  // where the motion through the state is steady for its linearization (a relative
  // equilibrium of a turning constraint); else refused unless asked for by name
  char why[512];
  int td = dal_time_dependence(sys, st, why, sizeof why);
  if (td < 0) return td;
  if (td == 1 && !frozen) {
    double worst = 0.0;
    int steady = dal__steady_modes(sys, st, &worst);
    if (steady < 0) return steady;
    if (steady) {
      td = 0; // the modes of a steady motion are not frozen ones
    } else {
      return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                      "normal_modes: %s, and the linearization changes along the motion "
                      "(eigenvalues %.3g apart, relative, within t + 4.3): a linearization "
                      "frozen at t=%.6g says nothing about the motion; for a periodic drive use "
                      "dal_floquet (dalembert floquet) over its period; dal_normal_modes_frozen "
                      "(dalembert modes --frozen) gives the frozen modes by name",
                      why, worst, st->t);
    }
  }
  size_t sn = (size_t)n, sk = (size_t)k;
  dal_tangent *tg = NULL;
  double *buf = NULL;
  if (dal__tangent_create(sys, &tg) ||
      !(buf = malloc(((size_t)k2 * k2 + 6 * sk * sk + sn * sk + 3 * (size_t)k2 + 1) *
                     sizeof(double)))) {
    dal__tangent_free(tg);
    return DAL_FAIL(st, DAL_E_NOMEM, "normal_modes: out of memory");
  }
  modes_work W = {.n = n, .k = k, .A = buf};
  W.Ks = W.A + (size_t)k2 * k2;
  W.Mc = W.Ks + sk * sk;
  W.w = W.Mc + sk * sk;
  W.wr = W.w + k2;
  W.wi = W.wr + k2;
  W.Km = W.wi + k2;
  W.Cm = W.Km + sk * sk;
  W.Ka = W.Cm + sk * sk;
  W.N = W.Ka + sk * sk;
  W.Ca = W.N + sn * sk;
  if ((rc = modes_tangent(sys, st, tg, &W)) == 0) {
    modes_norms(st, &W);
    rc = modes_undamped(sys, st, &W, omega2, shapes);
    if (!rc) rc = modes_stability(st, &W, lambda_re, lambda_im, out);
  }
  if (!rc && out) out->frozen = td == 1;
  free(buf);
  dal__tangent_free(tg);
  return rc;
}

int dal_normal_modes(const dal_system *sys, dal_state *st, double *omega2, double *shapes,
                     double *lambda_re, double *lambda_im, dal_modes *out) {
  return normal_modes(sys, st, omega2, shapes, lambda_re, lambda_im, out, 0);
}

int dal_normal_modes_frozen(const dal_system *sys, dal_state *st, double *omega2, double *shapes,
                            double *lambda_re, double *lambda_im, dal_modes *out) {
  return normal_modes(sys, st, omega2, shapes, lambda_re, lambda_im, out, 1);
}

int dal__steady_modes(const dal_system *sys, dal_state *st, double *worst_out) {
  int k2 = 2 * (sys->n - sys->m), rc;
  double *b = calloc(4 * (size_t)k2 + 1, sizeof(double));
  int *used = calloc((size_t)k2 + 1, sizeof(int));
  dal_state *s2 = NULL;
  if (!b || !used || dal_state_create(sys, &s2) || dal_state_copy_params(sys, s2, st)) {
    free(b);
    free(used);
    dal_state_destroy(s2);
    return DAL_FAIL(st, DAL_E_NOMEM, "normal_modes: out of memory");
  }
  double *r0 = b, *i0 = r0 + k2, *r1 = i0 + k2, *i1 = r1 + k2, worst = 0.0, scale = 0.0;
  dal_modes md;
  rc = dal_normal_modes_frozen(sys, st, NULL, NULL, r0, i0, &md);
  // the scale: the eigenvalues' size, at least the verdict's tolerance tau (near a bifurcation
  // the eigenvalues vanish and the integration error decides)
  for (int i = 0; i < k2 && !rc; ++i)
    scale = fmax(scale, hypot(r0[i], i0[i]));
  double tol = rc ? 0.0 : fmax(1e-6 * scale, md.tau);
  // the motion through the state, followed to three later times by the integrator, on a
  // copy (parameters included); the linearization's eigenvalues there against those here
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-10;
  static const double when[3] = {0.37, 1.9, 4.3};
  if (!rc) rc = dal_state_set(sys, s2, st->t, st->q, st->qdot);
  for (int j = 0; j < 3 && !rc; ++j) {
    int arc = dal_advance(sys, s2, &o, st->t + when[j]);
    if (arc) { // the motion cannot be followed: not shown steady
      worst = INFINITY;
      break;
    }
    if (dal_normal_modes_frozen(sys, s2, NULL, NULL, r1, i1, NULL)) {
      worst = INFINITY;
      break;
    }
    worst = fmax(worst, dal__match_distance(k2, r0, i0, r1, i1, used));
  }
  dal_state_destroy(s2);
  free(b);
  free(used);
  if (rc) return rc;
  if (worst_out) *worst_out = scale > 0 ? worst / scale : worst;
  return worst <= tol;
}
