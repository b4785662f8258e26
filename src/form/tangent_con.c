// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The exact tangent on the constraint manifold: the full-space tangent of the index-1 vector
// field from the KKT system, a basis of the manifold's tangent space and the reduced Jacobian.
//
// With constraint rows phi(q, t) = 0 the accelerations and multipliers solve
//   M a - G' lambda = Q - c,   G a = -gamma_phi.
// Along a tangent direction z = (dq, dqdot, dt) at fixed (a, lambda) the first equation's
// residual R - G' lambda changes by dR[z] (tangent.c: the second derivatives of
// W = sum r . w + V - lambda . phi, which bring in the constraint curvature sum lambda_i
// Hess phi_i) and the second by dA[z] = D(G a + gamma_phi)[z], the derivative of the
// order-2 coefficient of phi along the state's curve (the constraint curvature's derivative
// along z, from the order-3 coefficient like the particles' dA); so
//   [M G'; G 0] (da; -dlambda) = -(dR[z]; dA[z]).
// The state manifold {phi = 0, G v + phi_t = 0} is invariant under this vector field, and its
// tangent space at the state is {(dq, dv): G dq = 0, G dv + P dq = 0}, P = d(G v + phi_t)/dq:
// with N an orthonormal basis of null(G) (an SVD of G) its vectors are
//   (N xi, Y xi + N eta),   Y = -G^+ P N,
// and since N' G^+ = 0, diag(N', N') recovers (xi, eta): the frozen reduced Jacobian
// diag(N', N') A Z is [0 I; A21 A22] (xi' = eta).
// The basis is carried along the motion (xi = N(t)' dq, eta = xi'), not frozen: where G
// changes along the motion (moving constraints, or qdot != 0) a frozen N turns against the
// motion and its eigenvalues are not the tangent flow's (the bead on a turning circle at its
// bottom: g/R frozen, g/R - w^2 carried). With the minimal-rotation transport
// Ndot = -G^+ Gdot N (G N and N' N stay constant; Gdot = P, the same jets) xi' = N' dv = eta
// still, and eta' = N' da + Ndot' dv adds N' P' (G G')^-1 P N to A21.
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "form.h"

int dal__tangent_kkt(const dal_system *sys, dal_state *st, dal_tangent *tg, double *A, double *ft,
                     double *dlam) {
  int n = tg->n, m = tg->m, nk = n + m, ncol = 2 * n + (ft ? 1 : 0);
  size_t snk = (size_t)nk, n2 = 2 * (size_t)n;
  double *K = tg->kkt; // allocated with the workspace: nothing is allocated here
  lapack_int *ipiv = tg->kpiv;
  double *B = K + snk * snk;
  // [M G'; G 0]
  for (int j = 0; j < nk; ++j)
    for (int i = 0; i < nk; ++i) {
      double x = 0.0;
      if (i < n && j < n)
        x = tg->M[(size_t)j * n + i];
      else if (i < n && j >= n)
        x = tg->G[(size_t)i * m + (j - n)];
      else if (i >= n && j < n)
        x = tg->G[(size_t)j * m + (i - n)];
      K[(size_t)j * snk + i] = x;
    }
  // right-hand sides -(dR[z]; dA[z]) for z = e_i in q, in qdot, and t
  for (int c = 0; c < ncol; ++c) {
    double *b = B + (size_t)c * snk;
    const double *top = c < n       ? tg->Rq + (size_t)c * n
                        : c < 2 * n ? tg->Ru + (size_t)(c - n) * n
                                    : tg->Rt;
    const double *bot = c < n       ? tg->Aq + (size_t)c * m
                        : c < 2 * n ? tg->Av + (size_t)(c - n) * m
                                    : tg->At;
    for (int i = 0; i < n; ++i)
      b[i] = -top[i];
    for (int r = 0; r < m; ++r)
      b[n + r] = -bot[r];
  }
  lapack_int info = LAPACKE_dgesv_work(LAPACK_COL_MAJOR, nk, ncol, K, nk, ipiv, B, nk);
  if (info != 0) {
    return DAL_FAIL(st, DAL_E_SINGULAR,
                    "tangent: the KKT matrix [M G'; G 0] is singular at t=%.17g, %s (pivot %d): "
                    "the constraint rows are dependent there or M is singular on their null "
                    "space; check the constraints with dal_check_constraints",
                    st->t, dal__qtext(sys, st->q).s, (int)info);
  }
  if (A) {
    memset(A, 0, n2 * n2 * sizeof(double));
    for (int i = 0; i < n; ++i)
      A[((size_t)n + i) * n2 + i] = 1.0;
    for (int c = 0; c < 2 * n; ++c)
      memcpy(A + (size_t)c * n2 + n, B + (size_t)c * snk, (size_t)n * sizeof(double));
  }
  if (ft) {
    for (int i = 0; i < n; ++i) {
      ft[i] = 0.0;
      ft[n + i] = B[(size_t)2 * n * snk + i];
    }
  }
  if (dlam)
    for (int c = 0; c < ncol; ++c)
      for (int r = 0; r < m; ++r)
        dlam[(size_t)c * m + r] = -B[(size_t)c * snk + n + r];
  return DAL_OK;
}

void dal__tangent_kkt_solve(dal_tangent *tg, int nrhs, double *b) {
  int nk = tg->n + tg->m;
  if (nrhs > 0)
    LAPACKE_dgetrs_work(LAPACK_COL_MAJOR, 'N', nk, nrhs, tg->kkt, nk, (lapack_int *)tg->kpiv, b,
                        nk);
}

int dal__tangent_basis(const dal_system *sys, dal_state *st, dal_tangent *tg, double *N, double *Y,
                       double *W) {
  int n = tg->n, m = tg->m, k = n - m;
  size_t sn = (size_t)n, sm = (size_t)m;
  // G = U S V' (full V: its last k columns span null(G))
  double *buf =
      malloc((sm * sn + sm * sm + sn * sn + 3 * sm + sm * (size_t)(k + 1)) * sizeof(double));
  if (!buf) return DAL_FAIL(st, DAL_E_NOMEM, "tangent: out of memory for the null-space basis");
  double *Gc = buf, *U = Gc + sm * sn, *Vt = U + sm * sm, *s = Vt + sn * sn, *sup = s + sm;
  double *zz = sup + sm, *T = zz + sm;
  memcpy(Gc, tg->G, sm * sn * sizeof(double));
  lapack_int info = LAPACKE_dgesvd(LAPACK_COL_MAJOR, 'A', 'A', m, n, Gc, m, s, U, m, Vt, n, sup);
  if (info != 0) {
    free(buf);
    return DAL_FAIL(st, DAL_E_SINGULAR, "tangent: the SVD of G failed (info %d) at t=%.17g",
                    (int)info, st->t);
  }
  // rank: every singular value above n eps s_max
  double tol = (double)n * 2.220446049250313e-16 * (m > 0 ? s[0] : 0.0);
  if (m > 0 && !(s[m - 1] > tol)) {
    int row = 0; // the row that leans most on the weakest singular direction
    for (int r = 1; r < m; ++r)
      if (fabs(U[(size_t)(m - 1) * m + r]) > fabs(U[(size_t)(m - 1) * m + row])) row = r;
    double smin = s[m - 1], smax = s[0];
    free(buf);
    return DAL_FAIL(st, DAL_E_SINGULAR,
                    "tangent: the constraint Jacobian G has rank below %d at t=%.17g, %s "
                    "(singular values %.3g ... %.3g; row %d of constraint '%s' is dependent): "
                    "drop a redundant constraint or move off the singular configuration",
                    m, st->t, dal__qtext(sys, st->q).s, smax, smin, row,
                    sys->con[sys->row_con[row]].name);
  }
  // N: rows m .. n-1 of V' transposed
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < n; ++i)
      N[(size_t)j * n + i] = Vt[(size_t)i * n + (m + j)];
  if (Y || W) {
    // T = P N (m x k); W = S^-1 U' T (m x k); Y = -V_1 W (n x k)
    dal__gemm('N', 'N', m, k, n, tg->Pq, m, N, n, T, m);
    for (int j = 0; j < k; ++j) {
      // zz = S^-1 U' T e_j
      for (int l = 0; l < m; ++l) {
        double x = 0.0;
        for (int r = 0; r < m; ++r)
          x += U[(size_t)l * m + r] * T[(size_t)j * m + r];
        zz[l] = x / s[l];
        if (W) W[(size_t)j * m + l] = zz[l];
      }
      for (int i = 0; Y && i < n; ++i) {
        double x = 0.0;
        for (int l = 0; l < m; ++l)
          x += Vt[(size_t)i * n + l] * zz[l];
        Y[(size_t)j * n + i] = -x;
      }
    }
  }
  free(buf);
  return DAL_OK;
}

void dal__tangent_reduce(int n, int k, const double *A, const double *N, const double *Y,
                         double *Ar) {
  size_t n2 = 2 * (size_t)n, k2 = 2 * (size_t)k;
  // column c of Z: (N e_c, Y e_c) for c < k, (0, N e_(c-k)) after
  for (size_t c = 0; c < k2; ++c) {
    const double *zq = c < (size_t)k ? N + c * n : NULL;
    const double *zv = c < (size_t)k ? Y + c * n : N + (c - k) * n;
    for (size_t row = 0; row < k2; ++row) {
      const double *w = N + (row < (size_t)k ? row : row - k) * n;
      size_t off = row < (size_t)k ? 0 : (size_t)n; // rows of A: q block or v block
      double x = 0.0;
      for (int i = 0; i < n; ++i) {
        double az = 0.0; // (A z)_{off + i}
        for (int j = 0; j < n; ++j) {
          if (zq) az += A[(size_t)j * n2 + off + i] * zq[j];
          az += A[((size_t)n + j) * n2 + off + i] * zv[j];
        }
        x += w[i] * az;
      }
      Ar[c * k2 + row] = x;
    }
  }
}

int dal__tangent_manifold(const dal_system *sys, dal_state *st, dal_tangent *tg, double *Z,
                          double *P) {
  int n = sys->n, k = n - sys->m, rc;
  size_t sn = (size_t)n, sk = (size_t)k, n2 = 2 * sn, k2 = 2 * sk;
  memset(Z, 0, n2 * k2 * sizeof(double));
  if (P) memset(P, 0, k2 * n2 * sizeof(double));
  if (sys->m == 0) {
    for (size_t i = 0; i < n2; ++i) {
      Z[i * n2 + i] = 1.0;
      if (P) P[i * k2 + i] = 1.0;
    }
    return DAL_OK;
  }
  double *N = malloc((2 * sn * sk + sk * sk + 1) * sizeof(double));
  if (!N) return DAL_FAIL(st, DAL_E_NOMEM, "tangent: out of memory for the manifold's basis");
  double *Y = N + sn * sk, *NY = Y + sn * sk;
  if ((rc = dal__tangent_basis(sys, st, tg, N, Y, NULL)) != 0) {
    free(N);
    return rc;
  }
  dal__gemm('T', 'N', k, k, n, N, n, Y, n, NY, k); // NY = N' Y (k x k)
  for (size_t j = 0; j < sk; ++j)
    for (size_t i = 0; i < sn; ++i) {
      Z[j * n2 + i] = N[j * sn + i];             // (N xi, Y xi)
      Z[j * n2 + sn + i] = Y[j * sn + i];        //
      Z[(sk + j) * n2 + sn + i] = N[j * sn + i]; // (0, N eta)
      if (!P) continue;
      P[i * k2 + j] = N[j * sn + i];             // xi = N' dq
      P[(sn + i) * k2 + sk + j] = N[j * sn + i]; // eta = N' dv - N'Y N' dq
      double s = 0.0;
      for (size_t l = 0; l < sk; ++l)
        s += NY[l * sk + j] * N[l * sn + i];
      P[i * k2 + sk + j] = -s;
    }
  free(N);
  return DAL_OK;
}

int dal__tangent_on_manifold(const dal_system *sys, dal_state *st, dal_tangent *tg,
                             const char *what) {
  int n = tg->n, m = tg->m;
  for (int r = 0; r < m; ++r) {
    // scales: |q| |G row| for phi, |G row| |v| + |phi_t| for the velocity row
    double gn = 0.0, qn = 0.0, vn = 0.0;
    for (int i = 0; i < n; ++i) {
      gn += fabs(tg->G[(size_t)i * m + r]);
      qn = fmax(qn, fabs(st->q[i]));
      vn = fmax(vn, fabs(st->qdot[i]));
    }
    double pos = fabs(tg->cres[r]), vel = fabs(tg->cres[m + r]);
    double ptol = 1e-8 * (1.0 + gn * qn), vtol = 1e-8 * (1.0 + gn * vn + fabs(st->phit[r]));
    if (!(pos <= ptol) || !(vel <= vtol))
      return DAL_FAIL(st, DAL_E_ARG,
                      "%s: the state is off the constraint manifold at t=%.17g: row %d of "
                      "constraint '%s' has phi = %.3g, G qdot + dphi/dt = %.3g (tolerances "
                      "%.3g, %.3g); the tangent on the manifold needs a consistent state: "
                      "project it first (dal_make_consistent)",
                      what, st->t, r, sys->con[sys->row_con[r]].name, tg->cres[r], tg->cres[m + r],
                      ptol, vtol);
  }
  return DAL_OK;
}

int dal__tangent_reduced(const dal_system *sys, dal_state *st, dal_tangent *tg, double *N,
                         double *Ar, double *Mr, double *Cr, double *Kr) {
  int n = tg->n, k = n - tg->m;
  size_t sn = (size_t)n, sk = (size_t)k, n2 = 2 * sn, k2 = 2 * sk;
  size_t sm = (size_t)tg->m;
  double *buf = malloc((n2 * n2 + 2 * sn * sk + k2 * k2 + sn * sk + sm * sk + 1) * sizeof(double));
  if (!buf) return DAL_FAIL(st, DAL_E_NOMEM, "tangent: out of memory for the reduction");
  double *A = buf, *Nb = A + n2 * n2, *Y = Nb + sn * sk, *R = Y + sn * sk, *MN = R + k2 * k2;
  double *W = MN + sn * sk;
  int rc = dal__tangent_kkt(sys, st, tg, A, NULL, NULL);
  if (!rc) rc = dal__tangent_basis(sys, st, tg, Nb, Y, W);
  if (rc) {
    free(buf);
    return rc;
  }
  dal__tangent_reduce(n, k, A, Nb, Y, R);
  // the basis carried along the motion (minimal rotation, Ndot = -G^+ Gdot N, Gdot = P):
  // eta' = N' dv' + Ndot' dv adds N' P' (G G')^-1 P N = W' W to A21; zero where G is steady
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      double x = 0.0;
      for (size_t r = 0; r < sm; ++r)
        x += W[(size_t)i * sm + r] * W[(size_t)j * sm + r];
      R[(size_t)j * k2 + k + i] += x;
    }
  if (N) memcpy(N, Nb, sn * sk * sizeof(double));
  if (Ar) memcpy(Ar, R, k2 * k2 * sizeof(double));
  // M_r = N' M N; then C_r = -M_r A22, K_r = -M_r A21 (M_r xi'' + C_r xi' + K_r xi = 0)
  dal__gemm('N', 'N', n, k, n, tg->M, n, Nb, n, MN, n);
  double *mr = Y; // N' M N into the Y storage (no longer needed)
  dal__gemm('T', 'N', k, k, n, Nb, n, MN, n, mr, k);
  for (int j = 0; j < k; ++j) // symmetric to rounding: mirror the lower triangle
    for (int i = 0; i < j; ++i)
      mr[(size_t)j * k + i] = mr[(size_t)i * k + j];
  if (Mr) memcpy(Mr, mr, sk * sk * sizeof(double));
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      double c = 0.0, kk = 0.0;
      for (int l = 0; l < k; ++l) {
        c -= mr[(size_t)l * k + i] * R[((size_t)k + j) * k2 + k + l];
        kk -= mr[(size_t)l * k + i] * R[(size_t)j * k2 + k + l];
      }
      if (Cr) Cr[(size_t)j * k + i] = c;
      if (Kr) Kr[(size_t)j * k + i] = kk;
    }
  free(buf);
  return DAL_OK;
}
