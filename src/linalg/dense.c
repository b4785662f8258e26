// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Dense linear algebra through LAPACKE: Cholesky solves with degenerate-pivot detection.
#include <lapacke.h>
#include <string.h>

#include "linalg.h"

int dal__chol_solve(int n, const double *A, double *L, double *b, int *bad) {
  memcpy(L, A, (size_t)n * (size_t)n * sizeof(double));
  // the _work variants skip LAPACKE's NaN scan: inputs were checked finite upstream
  lapack_int info = LAPACKE_dpotrf_work(LAPACK_COL_MAJOR, 'L', n, L, n);
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
  info = LAPACKE_dpotrs_work(LAPACK_COL_MAJOR, 'L', n, 1, L, n, b, n);
  if (info != 0) {
    *bad = 0;
    return -1;
  }
  return 0;
}
