// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Dense linear algebra through LAPACKE (private).
#ifndef DAL_LINALG_LINALG_H
#define DAL_LINALG_LINALG_H

#include <stddef.h>

/// Relative pivot threshold below which a Cholesky pivot counts as degenerate.
#define DAL_CHOL_RTOL 2.2e-13

/// Largest order factored by the library's own unblocked Cholesky; larger ones go to LAPACK.
/// OpenBLAS' dpotrf/dpotrs cost about 4000 instructions per call in locks, buffer allocation
/// and dispatch whatever the order (callgrind, bench/lagrange.c: 8 of the 15 million
/// instructions of the driven pendulum's Lagrangian route at n = 1).
#ifndef DAL_CHOL_UNBLOCKED_MAX
#define DAL_CHOL_UNBLOCKED_MAX 32
#endif

/// Solve A x = b for symmetric positive definite A (n x n, column-major, not modified) by
/// Cholesky into the scratch L (n x n). b (n) is overwritten by x. Returns 0, or -1 with
/// *bad = index of the first degenerate pivot (not positive definite, or a pivot squared
/// below DAL_CHOL_RTOL times the largest).
int dal__chol_solve(int n, const double *A, double *L, double *b, int *bad);

/// the largest distance |a_i - b_j| between two sets of k2 complex numbers (ar + i ai, br + i bi)
/// matched greedily, each a_i to the nearest unused b_j; used: scratch (k2)
double dal__match_distance(int k2, const double *ar, const double *ai, const double *br,
                           const double *bi, int *used);

/// C = op(A) op(B) for column-major matrices, as BLAS dgemm with alpha = 1 and beta = 0: op(X)
/// is X ('N') or its transpose ('T'); C is m x n, the inner dimension k; lda, ldb, ldc are the
/// leading dimensions. Each element is the plain sum over l = 0 .. k-1 in that order, so the
/// result is the triple loop's to the bit. C must not overlap A or B. A row-major product
/// C = A B is the column-major C' = B' A': dal__gemm('N', 'N', n, m, k, B, ldb, A, lda, C, ldc).
static inline void dal__gemm(char ta, char tb, int m, int n, int k, const double *A, int lda,
                             const double *B, int ldb, double *C, int ldc) {
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i) {
      double s = 0.0;
      for (int l = 0; l < k; ++l)
        s += (ta == 'N' ? A[(size_t)l * lda + i] : A[(size_t)i * lda + l]) *
             (tb == 'N' ? B[(size_t)j * ldb + l] : B[(size_t)l * ldb + j]);
      C[(size_t)j * ldc + i] = s;
    }
}

#include "sparse.h"

#endif
