// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The constraint Jacobian as a dense matrix, and its rank by rank-revealing QR: the named
// diagnosis of redundant constraints used by the KKT factorization, the recursion's loop
// system and dal_check_constraints.
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "eval.h"

void dal__dense_G(const dal_system *sys, const dal_state *st, double *G, int ld) {
  for (int j = 0; j < sys->n; ++j)
    memset(G + (size_t)j * ld, 0, (size_t)sys->m * sizeof(double));
  for (int ci = 0; ci < sys->ncon; ++ci) {
    const dal_con *c = &sys->con[ci];
    const int *dc = sys->cdep + c->dep_off;
    const double *Gc = st->G + c->g_off;
    for (int r = 0; r < c->prim->nout; ++r)
      for (int k = 0; k < c->ndep; ++k)
        G[(size_t)dc[k] * ld + c->row + r] = Gc[r * c->ndep + k];
  }
}

// The QR factorization with column pivoting (Businger and Golub, Numer. Math. 7, 1965;
// LAPACK dgeqp3, Quintana-Orti, Sun and Bischof, SIAM J. Sci. Comput. 19, 1998) of G' moves
// the most independent constraint rows first; a trailing pivot |R_kk| <= DAL_RANK_RTOL |R_11|
// marks row k as a combination of the rows before it, and R_11^-1 R_12 gives the combination,
// hence the names of the constraints involved.

// append "'name'" list of the constraints owning rows[0..nrows) to buf (unique, in order)
static void name_list(const dal_system *sys, const int *rows, int nrows, char *buf, size_t len,
                      int *ncon_out) {
  int seen[8], ns = 0;
  for (int i = 0; i < nrows; ++i) {
    int c = sys->row_con[rows[i]], dup = 0;
    for (int j = 0; j < ns; ++j)
      dup |= seen[j] == c;
    if (!dup && ns < 8) seen[ns++] = c;
  }
  // sort by constraint index so the message reads in model order
  for (int i = 1; i < ns; ++i)
    for (int j = i; j > 0 && seen[j - 1] > seen[j]; --j) {
      int t = seen[j];
      seen[j] = seen[j - 1];
      seen[j - 1] = t;
    }
  size_t used = 0;
  buf[0] = 0;
  for (int i = 0; i < ns && used < len; ++i) {
    const char *sep = i == 0 ? "" : (i == ns - 1 ? " and " : ", ");
    used += (size_t)snprintf(buf + used, len - used, "%s'%s'", sep, sys->con[seen[i]].name);
  }
  *ncon_out = ns;
}

// the first dependent row after the pivoted QR A (n x m, pivots jpvt) of numerical rank
// `rank` < m and the rows it combines (R_11 z = R(0:rank, rank); z, rows: m scratch), into the
// report and a DAL_E_CONSTRAINT naming them
static int report_dependent(const dal_system *sys, dal_state *st, const double *A,
                            const lapack_int *jpvt, double *z, int *rows, int rank,
                            dal_constraint_report *rep) {
  int n = sys->n, m = sys->m;
  int dep = (int)jpvt[rank] - 1, nrows = 0;
  rows[nrows++] = dep;
  double zmax = 0.0;
  for (int i = rank - 1; i >= 0; --i) {
    double s = A[(size_t)rank * n + i];
    for (int j = i + 1; j < rank; ++j)
      s -= A[(size_t)j * n + i] * z[j];
    z[i] = s / A[(size_t)i * n + i];
    if (fabs(z[i]) > zmax) zmax = fabs(z[i]);
  }
  for (int i = 0; i < rank; ++i)
    if (fabs(z[i]) > 1e-8 * zmax) rows[nrows++] = (int)jpvt[i] - 1;
  rep->ndependent = nrows;
  for (int i = 0; i < nrows && i < 8; ++i)
    rep->rows[i] = rows[i];
  char names[320], qs[256];
  int ncon = 0;
  name_list(sys, rows, nrows, names, sizeof names, &ncon);
  dal__fmt_q(sys, st->q, qs, sizeof qs);
  if (rank == 0 && nrows == 1)
    return DAL_FAIL(st, DAL_E_CONSTRAINT,
                    "constraint %s does not depend on the coordinates at t=%.17g, %s (rank 0 of "
                    "%d): its gradient vanishes; check its inputs or reformulate it",
                    names, st->t, qs, m);
  if (ncon == 1)
    return DAL_FAIL(st, DAL_E_CONSTRAINT,
                    "constraint %s has dependent rows (rank %d of %d) at t=%.17g, %s: its rows "
                    "restrict the same motion there (a singular configuration of the primitive)",
                    names, rank, m, st->t, qs);
  return DAL_FAIL(st, DAL_E_CONSTRAINT,
                  "constraints %s are redundant (rank %d of %d) at t=%.17g, %s: one of them "
                  "restricts nothing the others do not; remove one (or, if they disagree, they "
                  "conflict: fix their parameters)",
                  names, rank, m, st->t, qs);
}

int dal__check_rank(const dal_system *sys, dal_state *st, dal_constraint_report *rep) {
  int n = sys->n, m = sys->m;
  dal_constraint_report local;
  if (!rep) rep = &local;
  memset(rep, 0, sizeof *rep);
  rep->m = m;
  rep->rmin = 1.0;
  rep->rank = m;
  if (m == 0) return DAL_OK;
  if (m > DAL_RANK_MAX_ROWS || (double)n * (double)m > DAL_RANK_MAX_ENTRIES) {
    rep->rank = -1;
    return DAL_OK;
  }
  double *A = malloc((size_t)n * (size_t)m * sizeof(double) + sizeof(double));
  double *G = malloc((size_t)n * (size_t)m * sizeof(double) + sizeof(double));
  double *tau = malloc(((size_t)(n < m ? n : m) + 1) * sizeof(double));
  double *z = malloc(((size_t)m + 1) * sizeof(double));
  lapack_int *jpvt = calloc((size_t)m + 1, sizeof(lapack_int));
  int *rows = malloc(((size_t)m + 1) * sizeof(int));
  int rc = DAL_OK;
  if (!A || !G || !tau || !z || !jpvt || !rows) {
    rc = DAL_FAIL(st, DAL_E_NOMEM, "constraint check: out of memory (%d x %d)", m, n);
    goto done;
  }
  // A = G' (n x m): column r is the gradient of row r
  dal__dense_G(sys, st, G, m);
  for (int r = 0; r < m; ++r)
    for (int j = 0; j < n; ++j)
      A[(size_t)r * n + j] = G[(size_t)j * m + r];
  lapack_int info = LAPACKE_dgeqp3(LAPACK_COL_MAJOR, n, m, A, n, jpvt, tau);
  if (info != 0) {
    rc = DAL_FAIL(st, DAL_E_NOMEM, "constraint check: QR of G' failed (LAPACK info %d)", (int)info);
    goto done;
  }
  int kmax = n < m ? n : m, rank = 0;
  double r11 = fabs(A[0]);
  for (int k = 0; k < kmax; ++k) {
    double rkk = fabs(A[(size_t)k * n + k]);
    if (r11 > 0.0 && rkk > DAL_RANK_RTOL * r11) {
      rank = k + 1;
      rep->rmin = rkk / r11;
    } else {
      break;
    }
  }
  rep->rank = rank;
  if (rank == m) goto done;
  rc = report_dependent(sys, st, A, jpvt, z, rows, rank, rep);
done:
  DAL_FREE(A, G, tau, z, jpvt, rows);
  return rc;
}

int dal__blame_rank(const dal_system *sys, dal_state *st, const char *what) {
  if (dal__check_rank(sys, st, NULL) != DAL_E_CONSTRAINT) return 0;
  char saved[DAL_ERRMSG_LEN];
  memcpy(saved, st->err, sizeof saved);
  return DAL_FAIL(st, DAL_E_CONSTRAINT, "%s: %s", what, saved);
}
