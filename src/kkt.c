// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The KKT system of constrained dynamics: M qddot - G' lambda = Q - c, G qddot = -gamma_phi.
#include <lapacke.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

// dense G (m x n, column-major) from the compact per-constraint blocks
static void dense_G(const dal_system *sys, const dal_state *st, double *G) {
  int m = sys->m;
  memset(G, 0, (size_t)m * (size_t)sys->n * sizeof(double));
  for (int ci = 0; ci < sys->ncon; ++ci) {
    const dal_con *c = &sys->con[ci];
    const int *dc = sys->cdep + c->dep_off;
    const double *Gc = st->G + c->g_off;
    for (int r = 0; r < c->prim->nout; ++r)
      for (int k = 0; k < c->ndep; ++k) G[(size_t)dc[k] * m + c->row + r] = Gc[r * c->ndep + k];
  }
}

int dal__solve_kkt(const dal_system *sys, dal_state *st) {
  int n = sys->n, m = sys->m, nk = n + m;
  if (!st->M)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "forward: the system has %d coordinates and is stored without a dense mass "
                    "matrix; evaluate it through the DAE integrator", n);
  double *K = malloc((size_t)nk * (size_t)nk * sizeof(double));
  double *G = malloc((size_t)m * (size_t)n * sizeof(double) + 1);
  double *x = malloc((size_t)nk * sizeof(double));
  lapack_int *piv = malloc((size_t)nk * sizeof(lapack_int));
  if (!K || !G || !x || !piv) {
    free(K);
    free(G);
    free(x);
    free(piv);
    return DAL_FAIL(st, DAL_E_NOMEM, "forward: out of memory for the KKT system");
  }
  dense_G(sys, st, G);
  // K = [M G'; G 0], unknowns (qddot, -lambda)
  memset(K, 0, (size_t)nk * (size_t)nk * sizeof(double));
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) K[(size_t)j * nk + i] = st->M[(size_t)j * n + i];
    for (int r = 0; r < m; ++r) {
      K[(size_t)j * nk + n + r] = G[(size_t)j * m + r];
      K[(size_t)(n + r) * nk + j] = G[(size_t)j * m + r];
    }
  }
  for (int i = 0; i < n; ++i) x[i] = st->Q[i] - st->c[i];
  for (int r = 0; r < m; ++r) x[n + r] = -st->gphi[r];
  lapack_int info = LAPACKE_dsysv(LAPACK_COL_MAJOR, 'L', nk, 1, K, nk, piv, x, nk);
  int rc = DAL_OK;
  if (info != 0) {
    int bad = info > 0 ? (int)info - 1 : 0;
    rc = DAL_FAIL(st, DAL_E_CONSTRAINT,
                  "forward: the KKT matrix [M G'; G 0] is singular at t=%.17g (pivot %d, %s "
                  "'%s'): constraints are redundant or the mass matrix is degenerate",
                  st->t, bad, bad < n ? "coordinate" : "constraint",
                  bad < n ? sys->coord_names[bad] : sys->con[sys->row_con[bad - n]].name);
  } else {
    memcpy(st->qddot, x, (size_t)n * sizeof(double));
    for (int r = 0; r < m; ++r) st->lambda[r] = -x[n + r];
  }
  free(K);
  free(G);
  free(x);
  free(piv);
  return rc;
}
