// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Compressed-column sparsity patterns from (row, col) lists: sort, merge duplicates, compress.
#include "sparse.h"

#include <stdlib.h>
#include <string.h>

static int cmp_ll(const void *x, const void *y) {
  long long a = *(const long long *)x, b = *(const long long *)y;
  return (a > b) - (a < b);
}

int dal__csc_build(dal_csc *A, int n, long long *keys, size_t nkeys) {
  memset(A, 0, sizeof *A);
  qsort(keys, nkeys, sizeof(long long), cmp_ll);
  size_t nu = 0;
  for (size_t i = 0; i < nkeys; ++i)
    if (nu == 0 || keys[nu - 1] != keys[i]) keys[nu++] = keys[i];
  A->colptr = calloc((size_t)n + 1, sizeof(int));
  A->rowind = malloc((nu + 1) * sizeof(int));
  if (!A->colptr || !A->rowind) {
    dal__csc_free(A);
    return -1;
  }
  A->n = n;
  A->nnz = (int)nu;
  for (size_t i = 0; i < nu; ++i) {
    A->rowind[i] = (int)(keys[i] % n);
    A->colptr[keys[i] / n + 1]++;
  }
  for (int j = 0; j < n; ++j)
    A->colptr[j + 1] += A->colptr[j];
  return 0;
}

int dal__csc_find(const dal_csc *A, int row, int col) {
  int lo = A->colptr[col], hi = A->colptr[col + 1] - 1;
  while (lo <= hi) {
    int mid = (lo + hi) / 2;
    if (A->rowind[mid] == row) return mid;
    if (A->rowind[mid] < row)
      lo = mid + 1;
    else
      hi = mid - 1;
  }
  return -1;
}

void dal__csc_free(dal_csc *A) {
  free(A->colptr);
  free(A->rowind);
  A->colptr = A->rowind = NULL;
  A->nnz = 0;
}
