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

int dal_normal_modes(const dal_system *sys, dal_state *st, double *omega2, double *shapes,
                     double *lambda_re, double *lambda_im, dal_modes *out) {
  if (!st) return DAL_E_ARG;
  if (!sys || st->sys != sys)
    return DAL_FAIL(st, DAL_E_STATE, "normal_modes: the state belongs to another system");
  int rc = dal__tangent_supported(sys, st, "normal_modes");
  if (!rc) rc = dal_forward(sys, st);
  if (rc) return rc;
  // k independent coordinates: n without constraints, n - m on the manifold
  int n = sys->n, k = n - sys->m, k2 = 2 * k;
  size_t sn = (size_t)n, sk = (size_t)k;
  dal_tangent *tg = NULL;
  double *buf = NULL;
  if (dal__tangent_create(sys, &tg) ||
      !(buf = malloc(((size_t)k2 * k2 + 6 * sk * sk + sn * sk + 3 * (size_t)k2 + 1) *
                     sizeof(double)))) {
    dal__tangent_free(tg);
    return DAL_FAIL(st, DAL_E_NOMEM, "normal_modes: out of memory");
  }
  double *A = buf, *Ks = A + (size_t)k2 * k2, *Mc = Ks + sk * sk, *w = Mc + sk * sk;
  double *wr = w + k2, *wi = wr + k2, *Km = wi + k2, *Cm = Km + sk * sk, *Ka = Cm + sk * sk;
  double *N = Ka + sk * sk, *Ca = N + sn * sk;
  if ((rc = dal__tangent_eval(sys, st, tg, 0)) != 0) goto done;
  if (sys->m > 0) {
    // the reduced tangent on the manifold, and the rounding scales |N|' Kabs |N|, |N|' Cabs |N|
    if ((rc = dal__tangent_on_manifold(sys, st, tg, "normal_modes")) != 0) goto done;
    if ((rc = dal__tangent_reduced(sys, st, tg, N, A, Mc, Cm, Km)) != 0) goto done;
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) {
        double ka = 0.0, ca = 0.0;
        for (int a = 0; a < n; ++a)
          for (int b = 0; b < n; ++b) {
            double nn = fabs(N[(size_t)i * n + a] * N[(size_t)j * n + b]);
            ka += nn * tg->Kabs[(size_t)b * n + a];
            ca += nn * tg->Cabs[(size_t)b * n + a];
          }
        Ka[(size_t)j * k + i] = ka;
        Ca[(size_t)j * k + i] = ca;
      }
  } else {
    if ((rc = dal__tangent_factor(sys, st, tg)) != 0) goto done;
    memcpy(Mc, tg->M, sk * sk * sizeof(double));
    memcpy(Km, tg->Rq, sk * sk * sizeof(double));
    memcpy(Cm, tg->Ru, sk * sk * sizeof(double));
    memcpy(Ka, tg->Kabs, sk * sk * sizeof(double));
    memcpy(Ca, tg->Cabs, sk * sk * sizeof(double));
    dal__tangent_flow(tg, A, NULL);
  }

  // diagnostics: asymmetry of K, size of C, acceleration at the state
  double kn = 0.0, ka = 0.0, cn = 0.0, mn = 0.0, acc = 0.0, kabs = 0.0, cabs = 0.0;
  for (int j = 0; j < n; ++j)
    acc = fmax(acc, fabs(st->qddot[j]));
  for (int j = 0; j < k; ++j) {
    for (int i = 0; i < k; ++i) {
      kabs += Ka[(size_t)j * k + i] * Ka[(size_t)j * k + i];
      cabs += Ca[(size_t)j * k + i] * Ca[(size_t)j * k + i];
      double kij = Km[(size_t)j * k + i], kt = Km[(size_t)i * k + j];
      kn += kij * kij;
      ka += (kij - kt) * (kij - kt);
      cn += Cm[(size_t)j * k + i] * Cm[(size_t)j * k + i];
      mn += Mc[(size_t)j * k + i] * Mc[(size_t)j * k + i];
      Ks[(size_t)j * k + i] = 0.5 * (kij + kt);
    }
  }
  kn = sqrt(kn);

  // undamped modes: Ks x = omega^2 M x (x' M x = 1), largest component of each shape positive
  lapack_int info = LAPACKE_dsygv(LAPACK_COL_MAJOR, 1, shapes ? 'V' : 'N', 'L', k, Ks, k, Mc, k, w);
  if (info != 0) {
    rc = DAL_FAIL(st, DAL_E_SINGULAR, "normal_modes: LAPACK dsygv failed (info %d) at t=%.17g: %s",
                  (int)info, st->t,
                  info > k ? "the mass matrix is not positive definite"
                           : "the eigenvalue iteration did not converge");
    goto done;
  }
  if (omega2) memcpy(omega2, w, sk * sizeof(double));
  if (shapes) {
    // with constraints the shape in the coordinates is N xi (still M-orthonormal)
    for (int j = 0; j < k; ++j) {
      const double *xi = Ks + (size_t)j * k;
      double *x = shapes + (size_t)j * n, big = 0.0;
      for (int i = 0; i < n; ++i) {
        double v = xi[i < k ? i : 0];
        if (sys->m > 0) {
          v = 0.0;
          for (int l = 0; l < k; ++l)
            v += N[(size_t)l * n + i] * xi[l];
        }
        x[i] = v;
        if (fabs(v) > fabs(big)) big = v;
      }
      if (big < 0)
        for (int i = 0; i < n; ++i)
          x[i] = -x[i];
    }
  }

  // the first-order Jacobian's eigenvalues decide stability (damping, gyroscopic terms)
  double scale = fmax(sqrt(block_norm(A + k, k, (size_t)k2)),
                      block_norm(A + (size_t)k * k2 + k, k, (size_t)k2));
  info = LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', k2, A, k2, wr, wi, NULL, 1, NULL, 1);
  if (info != 0) {
    rc = DAL_FAIL(st, DAL_E_SINGULAR,
                  "normal_modes: LAPACK dgeev did not converge (info %d) at t=%.17g", (int)info,
                  st->t);
    goto done;
  }
  sort_eigs(k2, wr, wi);
  double lmax = 0.0;
  for (int i = 0; i < k2; ++i)
    lmax = fmax(lmax, hypot(wr[i], wi[i]));
  // relative tolerance, and the rounding floor of K and C: a perturbation dK of K moves a
  // zero eigenvalue by sqrt(|dK| / |M|), dC by |dC| / |M| (64 ulps of the terms' magnitudes)
  double mf = sqrt(mn), ek = 64 * DBL_EPSILON * sqrt(kabs) / mf;
  double ec = 64 * DBL_EPSILON * sqrt(cabs) / mf;
  double tau = fmax(1e-6 * fmax(lmax, scale), fmax(sqrt(ek), ec)) + 1e-300, mr;
  dal_stability v = classify(k2, wr, wi, tau, &mr);
  if (lambda_re) memcpy(lambda_re, wr, (size_t)k2 * sizeof(double));
  if (lambda_im) memcpy(lambda_im, wi, (size_t)k2 * sizeof(double));
  if (out) {
    out->verdict = v;
    out->max_real = mr;
    out->tau = tau;
    out->asymmetry = kn > 0 ? sqrt(ka) / kn : 0.0;
    out->gyroscopic = kn > 0 && mn > 0 ? sqrt(cn) / sqrt(kn * sqrt(mn)) : sqrt(cn);
    out->accel = acc;
  }
done:
  free(buf);
  dal__tangent_free(tg);
  return rc;
}
