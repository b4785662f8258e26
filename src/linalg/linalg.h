// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Dense linear algebra through LAPACKE (private).
#ifndef DAL_LINALG_LINALG_H
#define DAL_LINALG_LINALG_H

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

#include "sparse.h"

#endif
