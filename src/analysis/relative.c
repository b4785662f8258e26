// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Relative equilibria of scenes in Cartesian coordinates that turn uniformly about an axis (a
// conical pendulum, a bead on a turning circle): the motion q(t) = exp(P (t - t0)) q*, with P
// the rotation generator on every particle's (x, y, z), is a fixed point of the co-rotating
// field g(y) = f(t0, y) - diag(P, P) y on the constraint manifold (Arnold, Mathematical
// Methods of Classical Mechanics, app. 5; Marsden & Ratiu, Introduction to Mechanics and
// Symmetry, ch. 9). Newton (minimum norm, the rotation family being one direction) on g = 0 in
// the manifold's tangent space, and the eigenvalues of Dg = A - diag(P, P) there: the small
// oscillations seen from the turning frame.
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis.h"
#include "dalembert/dae.h"
#include "dalembert/primitives.h"

// the generator P (n x n, column-major) of the rotation at `rate` about the unit axis e on
// every particle's Cartesian coordinates; 0 or DAL_E_UNSUPPORTED naming a particle that is not
// placed by dal_map_cartesian3 or a coordinate no particle places
static int generator(const dal_system *sys, dal_state *st, const double *e, double rate,
                     double *P) {
  int n = sys->n;
  memset(P, 0, (size_t)n * (size_t)n * sizeof(double));
  int *seen = calloc((size_t)n + 1, sizeof(int));
  if (!seen) return DAL_FAIL(st, DAL_E_NOMEM, "relative_equilibrium: out of memory");
  // S x = rate e x x
  double S[9] = {
      0, rate * e[2], -rate * e[1], -rate * e[2], 0, rate * e[0], rate * e[1], -rate * e[0], 0};
  for (int k = 0; k < sys->N; ++k) {
    const dal_place *pl = sys->place ? &sys->place[k] : NULL;
    if (!pl || pl->prim != &dal_map_cartesian3 || pl->parent >= 0 || pl->ncoord != 3) {
      free(seen);
      return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                      "relative_equilibrium: particle '%s' is not placed by its own Cartesian "
                      "(x, y, z) (dal_map_cartesian3): the turning frame acts on Cartesian "
                      "coordinates only; write the scene in the co-rotating frame and use "
                      "dal_equilibrium and dal_normal_modes there",
                      sys->part_names[k]);
    }
    const int *c = sys->ipool + pl->coord_off;
    for (int a = 0; a < 3; ++a) {
      seen[c[a]] = 1;
      for (int b = 0; b < 3; ++b)
        P[(size_t)c[b] * n + c[a]] += S[b * 3 + a];
    }
  }
  for (int i = 0; i < n; ++i)
    if (!seen[i]) {
      free(seen);
      return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                      "relative_equilibrium: coordinate '%s' places no particle: the turning "
                      "frame acts on Cartesian particle coordinates only",
                      sys->coord_names[i]);
    }
  free(seen);
  return DAL_OK;
}

int dal_relative_equilibrium(const dal_system *sys, dal_state *st, const double *axis, double rate,
                             double *lambda_re, double *lambda_im, dal_relative_report *rep) {
  int rc = dal__check_pair(sys, st, "relative_equilibrium");
  if (rc) return rc;
  double an = axis ? sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]) : 0.0;
  if (sys->dim != 3 || !(an > 0) || !isfinite(an) || !isfinite(rate))
    return DAL_FAIL(st, DAL_E_ARG,
                    "relative_equilibrium: needs a 3D scene (dim %d), a finite non-zero axis "
                    "and a finite rate (%g)",
                    sys->dim, rate);
  int n = sys->n, k = n - sys->m;
  if (k <= 0)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "relative_equilibrium: the system has no degrees of freedom");
  size_t sn = (size_t)n, sk = (size_t)k, n2 = 2 * sn, k2 = 2 * sk;
  double e[3] = {axis[0] / an, axis[1] / an, axis[2] / an};
  double *buf = calloc(sn * sn + 3 * n2 * n2 + 3 * n2 * k2 + k2 * k2 + 8 * n2 + 8, sizeof(double));
  dal_tangent *tg = NULL;
  if (!buf || dal__tangent_create(sys, &tg)) {
    free(buf);
    return DAL_FAIL(st, DAL_E_NOMEM, "relative_equilibrium: out of memory");
  }
  double *P = buf, *A = P + sn * sn, *J = A + n2 * n2, *Z = J + 2 * n2 * n2, *L = Z + n2 * k2;
  double *Ar = L + n2 * k2, *y = Ar + k2 * k2;
  double *r = y + n2, *keep = r + n2, *sv = keep + n2, *wr = sv + n2, *wi = wr + n2;
  double *tmp = J + n2 * n2; // n2 x k2 after J: inside the 3 n2 x n2 block
  double t0 = st->t, res = INFINITY;
  memcpy(keep, st->q, sn * sizeof(double));
  memcpy(keep + sn, st->qdot, sn * sizeof(double));
  memcpy(y, st->q, sn * sizeof(double));
  int it = 0;
  if ((rc = generator(sys, st, e, rate, P)) != 0) goto done;
  for (;; ++it) {
    // the start turning with the frame: v = P q, made consistent
    for (size_t i = 0; i < sn; ++i) {
      double s = 0.0;
      for (size_t j = 0; j < sn; ++j)
        s += P[j * sn + i] * y[j];
      y[sn + i] = s;
    }
    if ((rc = dal_state_set(sys, st, t0, y, y + sn)) != 0) break;
    if (sys->m > 0 && (rc = dal_make_consistent(sys, st, 0.0, NULL)) != 0) break;
    if ((rc = dal_vector_field_jacobian(sys, st, A, NULL)) != 0) break;
    memcpy(y, st->q, sn * sizeof(double));
    memcpy(y + sn, st->qdot, sn * sizeof(double));
    // g(y) = f(y) - diag(P, P) y and Dg = A - diag(P, P)
    double ys = 0.0, fs = 0.0;
    res = 0.0;
    for (size_t i = 0; i < sn; ++i) {
      double pq = 0.0, pv = 0.0;
      for (size_t j = 0; j < sn; ++j) {
        pq += P[j * sn + i] * y[j];
        pv += P[j * sn + i] * y[sn + j];
      }
      r[i] = st->qdot[i] - pq;
      r[sn + i] = st->qddot[i] - pv;
      fs = fmax(fs, fmax(fabs(st->qddot[i]), fabs(pv)));
      ys = fmax(ys, fabs(y[i]));
    }
    for (size_t i = 0; i < n2; ++i)
      res = fmax(res, fabs(r[i]));
    res /= fs + 1e-300;
    for (size_t j = 0; j < n2; ++j)
      for (size_t i = 0; i < n2; ++i) {
        size_t a = i % sn, b = j % sn;
        double p = (i < sn) == (j < sn) ? P[b * sn + a] : 0.0;
        J[j * n2 + i] = A[j * n2 + i] - p;
      }
    // the tangent basis Z (2n x k2) and its left inverse L (k2 x 2n)
    if (sys->m > 0 && (rc = dal__tangent_eval(sys, st, tg, 0)) != 0) break;
    if ((rc = dal__tangent_manifold(sys, st, tg, Z, L)) != 0) break;
    if (res <= 1e-12) break;
    if (it >= 50) {
      rc = DAL_FAIL(st, DAL_E_CONV,
                    "relative_equilibrium: Newton did not converge in 50 iterations (scaled "
                    "residual %.3g, at %s); start nearer a steady turning state",
                    res, dal__qtext(sys, y).s);
      break;
    }
    // (Dg Z) delta = -g, minimum norm
    dal__gemm('N', 'N', (int)n2, (int)k2, (int)n2, J, (int)n2, Z, (int)n2, tmp, (int)n2);
    for (size_t i = 0; i < n2; ++i)
      r[i] = -r[i];
    lapack_int rank;
    lapack_int info = LAPACKE_dgelsd(LAPACK_COL_MAJOR, (lapack_int)n2, (lapack_int)k2, 1, tmp,
                                     (lapack_int)n2, r, (lapack_int)n2, sv, 1e-12, &rank);
    if (info != 0) {
      rc = DAL_FAIL(st, DAL_E_SINGULAR, "relative_equilibrium: LAPACK dgelsd failed (info %d)",
                    (int)info);
      break;
    }
    for (size_t i = 0; i < sn; ++i) {
      double s = 0.0;
      for (size_t j = 0; j < k2; ++j)
        s += Z[j * n2 + i] * r[j];
      y[i] += s;
    }
    (void)ys;
  }
  if (!rc) {
    // the co-rotating linearization on the manifold: Ar = L Dg Z, its eigenvalues
    dal__gemm('N', 'N', (int)n2, (int)k2, (int)n2, J, (int)n2, Z, (int)n2, tmp, (int)n2);
    dal__gemm('N', 'N', (int)k2, (int)k2, (int)n2, L, (int)k2, tmp, (int)n2, Ar, (int)k2);
    lapack_int info = LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', (lapack_int)k2, Ar, (lapack_int)k2,
                                    wr, wi, NULL, 1, NULL, 1);
    if (info != 0)
      rc = DAL_FAIL(st, DAL_E_SINGULAR, "relative_equilibrium: LAPACK dgeev failed (info %d)",
                    (int)info);
  }
  if (!rc) {
    // sorted by decreasing real part, then increasing imaginary part
    for (size_t i = 1; i < k2; ++i) {
      double a = wr[i], b = wi[i];
      size_t j = i;
      while (j > 0 && (wr[j - 1] < a || (wr[j - 1] == a && wi[j - 1] > b))) {
        wr[j] = wr[j - 1];
        wi[j] = wi[j - 1];
        --j;
      }
      wr[j] = a;
      wi[j] = b;
    }
    if (lambda_re) memcpy(lambda_re, wr, k2 * sizeof(double));
    if (lambda_im) memcpy(lambda_im, wi, k2 * sizeof(double));
    if (rep) {
      rep->iterations = it;
      rep->residual = res;
    }
  }
done:
  dal__tangent_free(tg);
  if (rc) {
    rc = dal__restore_state(sys, st, t0, keep, rc);
  } else {
    rc = dal__restore_state(sys, st, t0, y, DAL_OK);
  }
  free(buf);
  return rc;
}
