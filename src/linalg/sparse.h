// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Compressed-column sparsity patterns from (row, col) lists: the KKT matrix and the IDA
// Newton matrix are built by the same helper (private).
#ifndef DAL_LINALG_SPARSE_H
#define DAL_LINALG_SPARSE_H

#include <stddef.h>

/// A square pattern of order n in compressed columns (row indices sorted in each column).
typedef struct dal_csc {
  int n, nnz;
  int *colptr; ///< n + 1
  int *rowind; ///< nnz
} dal_csc;

/// key of entry (row, col) in an order-n matrix
static inline long long dal__csc_key(int n, int row, int col) { return (long long)col * n + row; }

/// Build the pattern from nkeys keys (dal__csc_key; duplicates allowed; keys is sorted in
/// place). Returns 0 or -1 (out of memory; A is then empty).
int dal__csc_build(dal_csc *A, int n, long long *keys, size_t nkeys);

/// Position of (row, col) in A's arrays, or -1 when it is not in the pattern.
int dal__csc_find(const dal_csc *A, int row, int col);

/// Free A's arrays (A itself is the caller's).
void dal__csc_free(dal_csc *A);

#endif
