// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The KKT system of constrained dynamics [A G'; G 0]: dense (LAPACKE dsytrf) or sparse (KLU).
//
// Solves A x = a + G' y, G x = b with A = M (dynamics, M-orthogonal velocity projection) or
// A = I (minimum-norm position steps). Small systems factor the dense symmetric indefinite
// matrix by Bunch-Kaufman (LAPACK dsytrf) and estimate its condition (dsycon); large or sparse
// ones (no dense M, or order >= 200 and <= 5% non-zeros) assemble the matrix in compressed
// columns from the compact particle Jacobians and constraint rows and factor it by KLU (Davis
// and Palamadai Natarajan, ACM TOMS 37, 2010), reusing the symbolic analysis and, while its
// pivots stay good, the numeric factorization.
// All storage is allocated once per state.
#include <klu.h>
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "eval.h"
#include "linalg/linalg.h"

struct dal_kkt {
  int n, m, nk, sparse;
  int cur;         // metric of the current factorization (-1: none)
  double *scratch; // 4 vectors of nk
  double *rhs;     // nk
  // dense
  double *K; // nk x nk, lower triangle
  lapack_int *ipiv, *iwork;
  double *work;
  lapack_int lwork;
  // sparse
  int nnz;
  dal_csc pat; // the pattern (Kp, Ki alias its arrays)
  int *Kp, *Ki;
  double *Kx;
  int *mpos_off, *mpos; // per particle: ndk x ndk positions of its M contributions
  int *gpos;            // per compact G entry: positions in the G and G' blocks (2 each)
  int *dpos;            // positions of the diagonal (j, j), j < n
  klu_symbolic *sym;
  klu_numeric *num[2];
  klu_common common;
};

// sparse pattern of [M G'; G 0] (+ the diagonal of M), symbolic analysis and position maps
static int sparse_setup(const dal_system *sys, struct dal_kkt *k) {
  int n = sys->n, nk = k->nk;
  size_t cap = (size_t)n;
  for (int p = 0; p < sys->N; ++p) {
    size_t nd = (size_t)(sys->pdep_off[p + 1] - sys->pdep_off[p]);
    cap += nd * nd;
  }
  cap += 2 * (size_t)sys->g_total;
  long long *key = malloc((cap + 1) * sizeof(long long));
  if (!key) return -1;
  size_t nt = 0;
  for (int j = 0; j < n; ++j)
    key[nt++] = dal__csc_key(nk, j, j);
  for (int p = 0; p < sys->N; ++p) {
    const int *dp = sys->pdep + sys->pdep_off[p];
    int nd = sys->pdep_off[p + 1] - sys->pdep_off[p];
    for (int a = 0; a < nd; ++a)
      for (int b = 0; b < nd; ++b)
        key[nt++] = dal__csc_key(nk, dp[a], dp[b]);
  }
  for (int ci = 0; ci < sys->ncon; ++ci) {
    const dal_con *c = &sys->con[ci];
    const int *dc = sys->cdep + c->dep_off;
    for (int r = 0; r < c->prim->nout; ++r)
      for (int j = 0; j < c->ndep; ++j) {
        int row = n + c->row + r;
        key[nt++] = dal__csc_key(nk, row, dc[j]); // G block (row, col dc[j])
        key[nt++] = dal__csc_key(nk, dc[j], row); // G' block
      }
  }
  int brc = dal__csc_build(&k->pat, nk, key, nt);
  free(key);
  if (brc) return -1;
  k->nnz = k->pat.nnz;
  k->Kp = k->pat.colptr;
  k->Ki = k->pat.rowind;
  k->Kx = malloc((size_t)k->nnz * sizeof(double) + 1);
  k->dpos = malloc(((size_t)n + 1) * sizeof(int));
  k->mpos_off = malloc(((size_t)sys->N + 1) * sizeof(int));
  k->gpos = malloc((2 * (size_t)sys->g_total + 1) * sizeof(int));
  if (!k->Kx || !k->dpos || !k->mpos_off || !k->gpos) return -1;
  // position maps
  for (int j = 0; j < n; ++j)
    k->dpos[j] = dal__csc_find(&k->pat, j, j);
  k->mpos_off[0] = 0;
  for (int p = 0; p < sys->N; ++p) {
    int nd = sys->pdep_off[p + 1] - sys->pdep_off[p];
    k->mpos_off[p + 1] = k->mpos_off[p] + nd * nd;
  }
  k->mpos = malloc(((size_t)k->mpos_off[sys->N] + 1) * sizeof(int));
  if (!k->mpos) return -1;
  for (int p = 0; p < sys->N; ++p) {
    const int *dp = sys->pdep + sys->pdep_off[p];
    int nd = sys->pdep_off[p + 1] - sys->pdep_off[p];
    int *mp = k->mpos + k->mpos_off[p];
    for (int a = 0; a < nd; ++a)
      for (int b = 0; b < nd; ++b)
        mp[a * nd + b] = dal__csc_find(&k->pat, dp[a], dp[b]);
  }
  for (int ci = 0; ci < sys->ncon; ++ci) {
    const dal_con *c = &sys->con[ci];
    const int *dc = sys->cdep + c->dep_off;
    for (int r = 0; r < c->prim->nout; ++r)
      for (int j = 0; j < c->ndep; ++j) {
        int e = c->g_off + r * c->ndep + j, row = n + c->row + r;
        k->gpos[2 * e] = dal__csc_find(&k->pat, row, dc[j]);
        k->gpos[2 * e + 1] = dal__csc_find(&k->pat, dc[j], row);
      }
  }
  klu_defaults(&k->common);
  k->sym = klu_analyze(nk, k->Kp, k->Ki, &k->common);
  return k->sym ? 0 : -1;
}

struct dal_kkt *dal__kkt_create(const dal_system *sys) {
  struct dal_kkt *k = calloc(1, sizeof *k);
  if (!k) return NULL;
  k->n = sys->n;
  k->m = sys->m;
  k->nk = sys->n + sys->m;
  // sparse without a dense M, with an M that couples few coordinates (Cartesian particles:
  // KLU wins at every order, base/bounds.h), or when the KKT matrix is large and at most 5%
  // full
  double nnz = 2.0 * sys->g_total + sys->n;
  for (int p = 0; p < sys->N; ++p) {
    double nd = sys->pdep_off[p + 1] - sys->pdep_off[p];
    nnz += nd * nd;
  }
  k->sparse = !sys->dense_M || sys->kkt_local ||
              (k->nk >= DAL_KKT_SPARSE_MIN && nnz <= DAL_KKT_SPARSE_FILL * k->nk * (double)k->nk);
  k->cur = -1;
  size_t nk = (size_t)k->nk;
  k->scratch = calloc(4 * nk + 1, sizeof(double));
  k->rhs = calloc(nk + 1, sizeof(double));
  int ok = k->scratch && k->rhs;
  if (sys->aba) {
    // a recursive system solves through the m x m loop system (aba.c): scratch only
  } else if (ok && !k->sparse) {
    k->lwork = (lapack_int)(64 * nk + 64);
    k->K = malloc(nk * nk * sizeof(double));
    k->ipiv = malloc(nk * sizeof(lapack_int));
    k->iwork = malloc(nk * sizeof(lapack_int));
    k->work = malloc((size_t)k->lwork * sizeof(double));
    ok = k->K && k->ipiv && k->iwork && k->work;
  } else if (ok) {
    ok = sparse_setup(sys, k) == 0;
  }
  if (!ok) {
    dal__kkt_free(k);
    return NULL;
  }
  return k;
}

void dal__kkt_reset(struct dal_kkt *k) {
  if (!k) return;
  for (int i = 0; i < 2; ++i)
    if (k->num[i]) klu_free_numeric(&k->num[i], &k->common);
  k->cur = -1;
}

void dal__kkt_free(struct dal_kkt *k) {
  if (!k) return;
  for (int i = 0; i < 2; ++i)
    if (k->num[i]) klu_free_numeric(&k->num[i], &k->common);
  if (k->sym) klu_free_symbolic(&k->sym, &k->common);
  dal__csc_free(&k->pat);
  DAL_FREE(k->scratch, k->rhs, k->K, k->ipiv, k->iwork, k->work, k->Kx, k->mpos_off, k->mpos,
           k->gpos, k->dpos, k);
}

double *dal__kkt_scratch(dal_state *st, int i) {
  return st->kkt->scratch + (size_t)i * st->kkt->nk;
}

void dal__gt_apply(const dal_system *sys, const dal_state *st, const double *lambda, double *y) {
  memset(y, 0, (size_t)sys->n * sizeof(double));
  for (int ci = 0; ci < sys->ncon; ++ci) {
    const dal_con *c = &sys->con[ci];
    const int *dc = sys->cdep + c->dep_off;
    const double *Gc = st->G + c->g_off;
    for (int r = 0; r < c->prim->nout; ++r) {
      double l = lambda[c->row + r];
      for (int k = 0; k < c->ndep; ++k)
        y[dc[k]] += Gc[r * c->ndep + k] * l;
    }
  }
}

// name the failure: a rank-deficient G is reported by name, otherwise a degenerate M
static int kkt_singular(const dal_system *sys, dal_state *st, const char *what, double rcond) {
  int rc = dal__blame_rank(sys, st, what);
  if (rc) return rc;
  return DAL_FAIL(st, DAL_E_SINGULAR,
                  "%s: the KKT matrix [M G'; G 0] is singular at t=%.17g, %s (reciprocal "
                  "condition %.3g): some motion allowed by the constraints moves no mass, or "
                  "constraints are redundant; check the masses and the constraint list",
                  what, st->t, dal__qtext(sys, st->q).s, rcond);
}

static int factor_dense(const dal_system *sys, dal_state *st, int metric, const char *what) {
  struct dal_kkt *k = st->kkt;
  int n = k->n, nk = k->nk;
  double *K = k->K;
  // lower triangle: A, then G below it; the (2,2) block is zero
  for (int j = 0; j < nk; ++j)
    memset(K + (size_t)j * nk, 0, (size_t)nk * sizeof(double));
  if (metric == DAL_KKT_MASS) DAL_NEED(st, DAL_P_MLOW);
  if (metric == DAL_KKT_MASS)
    for (int j = 0; j < n; ++j)
      memcpy(K + (size_t)j * nk + j, st->M + (size_t)j * n + j, (size_t)(n - j) * sizeof(double));
  else
    for (int j = 0; j < n; ++j)
      K[(size_t)j * nk + j] = 1.0;
  dal__dense_G(sys, st, K + n, nk);
  double anorm = LAPACKE_dlansy_work(LAPACK_COL_MAJOR, '1', 'L', nk, K, nk, k->work);
  lapack_int info =
      LAPACKE_dsytrf_work(LAPACK_COL_MAJOR, 'L', nk, K, nk, k->ipiv, k->work, k->lwork);
  double rcond = 0.0;
  if (info == 0)
    info = LAPACKE_dsycon_work(LAPACK_COL_MAJOR, 'L', nk, K, nk, k->ipiv, anorm, &rcond, k->work,
                               k->iwork);
  if (info != 0 || !(rcond >= DAL_KKT_RCOND_MIN)) return kkt_singular(sys, st, what, rcond);
  return DAL_OK;
}

static int factor_sparse(const dal_system *sys, dal_state *st, int metric, const char *what) {
  struct dal_kkt *k = st->kkt;
  int d = sys->dim;
  memset(k->Kx, 0, (size_t)k->nnz * sizeof(double));
  if (metric == DAL_KKT_MASS) {
    for (int p = 0; p < sys->N; ++p) {
      int nd = sys->pdep_off[p + 1] - sys->pdep_off[p];
      const double *Jp = st->J + sys->pj_off[p];
      const int *mp = k->mpos + k->mpos_off[p];
      for (int a = 0; a < nd; ++a)
        for (int b = 0; b < nd; ++b) {
          double s = 0.0;
          for (int c = 0; c < d; ++c)
            s += Jp[c * nd + a] * Jp[c * nd + b];
          k->Kx[mp[a * nd + b]] += st->prm.mass[p] * s;
        }
    }
  } else {
    for (int j = 0; j < k->n; ++j)
      k->Kx[k->dpos[j]] = 1.0;
  }
  for (int e = 0; e < sys->g_total; ++e) {
    k->Kx[k->gpos[2 * e]] = st->G[e];
    k->Kx[k->gpos[2 * e + 1]] = st->G[e];
  }
  // reuse the numeric factorization while its pivots stay good, else factor afresh
  klu_numeric **num = &k->num[metric];
  int ok = 0;
  if (*num) {
    ok = klu_refactor(k->Kp, k->Ki, k->Kx, k->sym, *num, &k->common) &&
         klu_rcond(k->sym, *num, &k->common) && k->common.rcond >= DAL_KKT_RCOND_MIN;
    if (!ok) klu_free_numeric(num, &k->common);
  }
  if (!ok) {
    *num = klu_factor(k->Kp, k->Ki, k->Kx, k->sym, &k->common);
    if (!*num && k->common.status == KLU_OUT_OF_MEMORY)
      return DAL_FAIL(st, DAL_E_NOMEM, "%s: out of memory factoring the KKT matrix", what);
    ok = *num && klu_rcond(k->sym, *num, &k->common) && k->common.rcond >= DAL_KKT_RCOND_MIN;
    if (!ok) {
      double rc = *num ? k->common.rcond : 0.0;
      if (*num) klu_free_numeric(num, &k->common);
      return kkt_singular(sys, st, what, rc);
    }
  }
  return DAL_OK;
}

int dal__kkt_factor(const dal_system *sys, dal_state *st, int metric, const char *what) {
  struct dal_kkt *k = st->kkt;
  DAL_ASSERT(k && (metric == DAL_KKT_IDENTITY || metric == DAL_KKT_MASS));
  if (sys->aba) return dal__loop_factor(sys, st, metric, what);
  DAL_NEED(st, DAL_P_CON | DAL_P_J);
  k->cur = -1;
  int rc = k->sparse ? factor_sparse(sys, st, metric, what) : factor_dense(sys, st, metric, what);
  if (rc == DAL_OK) k->cur = metric;
  return rc;
}

int dal__kkt_reads_M(const dal_system *sys, const dal_state *st) {
  return !sys->aba && sys->dense_M && (!st->kkt || !st->kkt->sparse);
}

void dal__kkt_solve(const dal_system *sys, dal_state *st, const double *a, const double *b,
                    double *x, double *y) {
  struct dal_kkt *k = st->kkt;
  int n = k->n, m = k->m, nk = k->nk;
  if (sys->aba) {
    dal__loop_solve(sys, st, a, b, x, y);
    return;
  }
  memcpy(k->rhs, a, (size_t)n * sizeof(double));
  memcpy(k->rhs + n, b, (size_t)m * sizeof(double));
  if (k->sparse) {
    DAL_ASSERT(k->cur >= 0 && k->num[k->cur]);
    klu_solve(k->sym, k->num[k->cur], nk, 1, k->rhs, &k->common);
  } else {
    LAPACKE_dsytrs(LAPACK_COL_MAJOR, 'L', nk, 1, k->K, nk, k->ipiv, k->rhs, nk);
  }
  memcpy(x, k->rhs, (size_t)n * sizeof(double));
  for (int r = 0; r < m; ++r)
    y[r] = -k->rhs[n + r];
}

int dal__solve_kkt(const dal_system *sys, dal_state *st) {
  int n = sys->n, m = sys->m;
  int rc = dal__kkt_factor(sys, st, DAL_KKT_MASS, "forward");
  if (rc) return rc;
  double *a = dal__kkt_scratch(st, 0), *b = dal__kkt_scratch(st, 1);
  for (int i = 0; i < n; ++i)
    a[i] = st->Q[i] - st->c[i];
  for (int r = 0; r < m; ++r)
    b[r] = -st->gphi[r];
  dal__kkt_solve(sys, st, a, b, st->qddot, st->lambda);
  return DAL_OK;
}

// the multipliers and constraint rows are current at the state's (t, q, qdot)
