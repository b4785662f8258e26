// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Dense linear algebra: Cholesky solves with degenerate-pivot detection (small orders
// unblocked, larger ones through LAPACKE).
#include <lapacke.h>
#include <math.h>
#include <string.h>

#include "linalg.h"

// the lower Cholesky factor of A (column-major, lower triangle read) into L, unblocked
// (Golub-Van Loan, algorithm 4.2.1, column by column); 0, or j + 1 when pivot j is not positive
static int chol_small(int n, const double *A, double *L) {
  for (int j = 0; j < n; ++j) {
    double *lj = L + (size_t)j * n;
    for (int i = j; i < n; ++i)
      lj[i] = A[(size_t)j * n + i];
    // subtract the columns left of j: L(j:n, j) -= L(j:n, k) L(j, k)
    for (int k = 0; k < j; ++k) {
      const double *lk = L + (size_t)k * n;
      double ljk = lk[j];
      for (int i = j; i < n; ++i)
        lj[i] -= lk[i] * ljk;
    }
    if (!(lj[j] > 0.0)) return j + 1;
    double d = sqrt(lj[j]), r = 1.0 / d;
    lj[j] = d;
    for (int i = j + 1; i < n; ++i)
      lj[i] *= r;
  }
  return 0;
}

// b := L^-T L^-1 b for the lower factor L
static void chol_small_solve(int n, const double *L, double *b) {
  for (int j = 0; j < n; ++j) {
    const double *lj = L + (size_t)j * n;
    double x = b[j] / lj[j];
    b[j] = x;
    for (int i = j + 1; i < n; ++i)
      b[i] -= lj[i] * x;
  }
  for (int j = n - 1; j >= 0; --j) {
    const double *lj = L + (size_t)j * n;
    double x = b[j];
    for (int i = j + 1; i < n; ++i)
      x -= lj[i] * b[i];
    b[j] = x / lj[j];
  }
}

int dal__chol_solve(int n, const double *A, double *L, double *b, int *bad) {
  int small = n <= DAL_CHOL_UNBLOCKED_MAX;
  lapack_int info;
  if (small) {
    info = chol_small(n, A, L);
  } else {
    memcpy(L, A, (size_t)n * (size_t)n * sizeof(double));
    // the _work variants skip LAPACKE's NaN scan: inputs were checked finite upstream
    info = LAPACKE_dpotrf_work(LAPACK_COL_MAJOR, 'L', n, L, n);
  }
  if (info != 0) {
    *bad = info > 0 ? (int)info - 1 : 0;
    return -1;
  }
  // pivots L_ii^2 measure what column i adds beyond the others: tiny means degenerate
  double pmax = 0.0;
  for (int i = 0; i < n; ++i) {
    double p = L[(size_t)i * n + i] * L[(size_t)i * n + i];
    if (p > pmax) pmax = p;
  }
  for (int i = 0; i < n; ++i) {
    double p = L[(size_t)i * n + i] * L[(size_t)i * n + i];
    if (!(p > DAL_CHOL_RTOL * pmax)) {
      *bad = i;
      return -1;
    }
  }
  if (small) {
    chol_small_solve(n, L, b);
    return 0;
  }
  info = LAPACKE_dpotrs_work(LAPACK_COL_MAJOR, 'L', n, 1, L, n, b, n);
  if (info != 0) {
    *bad = 0;
    return -1;
  }
  return 0;
}

// the largest distance between two sets of complex numbers (multipliers, eigenvalues), each
// matched greedily to its nearest unused partner
double dal__match_distance(int k2, const double *ar, const double *ai, const double *br,
                           const double *bi, int *used) {
  double worst = 0.0;
  memset(used, 0, (size_t)k2 * sizeof(int));
  for (int i = 0; i < k2; ++i) {
    int best = -1;
    double bd = INFINITY;
    for (int j = 0; j < k2; ++j)
      if (!used[j] && hypot(ar[i] - br[j], ai[i] - bi[j]) < bd) {
        bd = hypot(ar[i] - br[j], ai[i] - bi[j]);
        best = j;
      }
    if (best >= 0) used[best] = 1;
    worst = fmax(worst, bd);
  }
  return worst;
}
