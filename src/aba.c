// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The articulated-body recursion for trees of placements, and the m x m loop system on top.
//
// Featherstone's articulated-body algorithm (R. Featherstone, Rigid Body Dynamics Algorithms,
// Springer 2008, ch. 7) specialised to point masses placed by primitives. Placement k moves
// its particle by dr_k = Lp_k dr_p + Lc_k dq_k (Lp_k: d x d parent block, the identity for a
// translating parent; Lc_k: d x nc coordinate columns), both kept by kinematics.c. To solve
// M x = tau, give each particle the acceleration a_k = Lp_k a_p + Lc_k x_k that x causes and
// let f_k = sum over k's subtree of (dr_i/dr_k)' m_i a_i. Once the subtree's own coordinate
// equations Lc_c' f_c = tau_c hold, f_k = IA_k a_k + pA_k with a d x d articulated inertia
// IA_k and a bias force pA_k:
//   backward, leaves first:  D_k = Lc_k' IA_k Lc_k = L_k L_k' (nc x nc),  W_k = IA_k Lc_k L_k^-T,
//                            IA_p += Lp_k' (IA_k - W_k W_k') Lp_k          (factor: q and t only)
//                            z_k = L_k^-1 (tau_k - Lc_k' pA_k),  pA_p += Lp_k' (pA_k + W_k z_k)
//   forward, roots first:    x_k = L_k^-T (z_k - W_k' Lp_k a_p),  a_k = Lp_k a_p + Lc_k x_k
// with IA_k starting at m_k I and pA_k at 0. Accelerations are x for tau = Q - c (the same Q
// and c the dense route uses). The pivots of the D_k are those of an LDL' factorization of M
// that eliminates leaves first: the same relative test as the dense Cholesky names a
// degenerate coordinate. Cost O(N (d^3 + d nc^2 + nc^3)) instead of O(n^3).
//
// Constraints on top of the tree (closed loops): the KKT system [A G'; G 0] with A = M or I
// is solved through its Schur complement: Y = A^-1 G' (m recursion solves with unit loads),
// S = G Y (m x m, symmetric positive definite when G has full rank), then
// A x = a + G' y, G x = b  give  x0 = A^-1 a,  y = S^-1 (b - G x0),  x = x0 + Y y.
// Compact G comes from the local blocks (kinematics.c), so no global Jacobian is formed.
// All storage is allocated once per state (dal__aba_create).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dae_internal.h"
#include "linalg.h"

struct dal_aba {
  int *doff, *woff;  // per particle: offsets of its factor L (nc x nc) and W (d x nc); [N] total
  unsigned char *tr; // per particle: the parent link is a translation (Lp = I)
  double *IA;        // articulated inertias (N x d x d, row-major)
  double *Lf;        // Cholesky factors of D_k (row-major lower; the diagonal holds 1 / L_ii)
  double *W;         // W_k = IA_k Lc_k L_k^-T (d x nc, row-major)
  double *piv;       // pivot of each coordinate (n)
  double *pA, *acc;  // bias forces and accelerations (N x d)
  double *z;         // L_k^-1 (tau_k - Lc_k' pA_k) per coordinate (n)
  double pmax;       // largest pivot of the last factorization (the scale of M)
  // the loop system (m > 0)
  int metric;     // factorization held: -1 none, DAL_KKT_IDENTITY or DAL_KKT_MASS
  double *Y;      // A^-1 G' (n x m, column r contiguous)
  double *S;      // Cholesky factor of G A^-1 G' (m x m, row-major lower, 1 / L_ii diagonal)
  double *x0, *r; // scratch (n) and (m)
};

struct dal_aba *dal__aba_create(const dal_system *sys) {
  int N = sys->N, d = sys->dim;
  size_t n = (size_t)sys->n, m = (size_t)sys->m, Nd = (size_t)N * (size_t)d;
  struct dal_aba *w = calloc(1, sizeof *w);
  if (!w) return NULL;
  w->doff = calloc((size_t)N + 1, sizeof(int));
  w->woff = calloc((size_t)N + 1, sizeof(int));
  w->tr = calloc((size_t)N + 1, 1);
  if (!w->doff || !w->woff || !w->tr) {
    dal__aba_free(w);
    return NULL;
  }
  for (int k = 0; k < N; ++k) {
    const dal_place *pl = &sys->place[k];
    w->doff[k + 1] = w->doff[k] + pl->ncoord * pl->ncoord;
    w->woff[k + 1] = w->woff[k] + d * pl->ncoord;
    w->tr[k] = pl->parent >= 0 && (pl->prim->flags & DAL_PRIM_TRANSLATES);
  }
  w->IA = calloc(Nd * (size_t)d + 1, sizeof(double));
  w->Lf = calloc((size_t)w->doff[N] + 1, sizeof(double));
  w->W = calloc((size_t)w->woff[N] + 1, sizeof(double));
  w->piv = calloc(n + 1, sizeof(double));
  w->pA = calloc(Nd + 1, sizeof(double));
  w->acc = calloc(Nd + 1, sizeof(double));
  w->z = calloc(n + 1, sizeof(double));
  w->metric = -1;
  if (m) {
    w->Y = calloc(n * m, sizeof(double));
    w->S = calloc(m * m, sizeof(double));
    w->x0 = calloc(n, sizeof(double));
    w->r = calloc(m, sizeof(double));
  }
  if (!w->IA || !w->Lf || !w->W || !w->piv || !w->pA || !w->acc || !w->z ||
      (m && (!w->Y || !w->S || !w->x0 || !w->r))) {
    dal__aba_free(w);
    return NULL;
  }
  return w;
}

void dal__aba_free(struct dal_aba *w) {
  if (!w) return;
  free(w->doff);
  free(w->woff);
  free(w->tr);
  double *p[] = {w->IA, w->Lf, w->W, w->piv, w->pA, w->acc, w->z, w->Y, w->S, w->x0, w->r};
  for (size_t i = 0; i < sizeof p / sizeof p[0]; ++i)
    free(p[i]);
  free(w);
}

// the dense route's message (dynamics.c), word for word, optionally prefixed by the caller
static int singular_coord(const dal_system *sys, dal_state *st, int bad, const char *what) {
  char qs[256];
  dal__fmt_q(sys, st->q, qs, sizeof qs);
  return DAL_FAIL(st, DAL_E_SINGULAR,
                  "%s%smass matrix singular or not positive definite at t=%.17g, %s: coordinate "
                  "'%s' is degenerate (it moves no mass there, e.g. a chart singularity such "
                  "as a spherical pendulum's pole); use redundant coordinates with "
                  "constraints, or another chart",
                  what ? what : "", what ? ": " : "", st->t, qs, sys->coord_names[bad]);
}

// In-place Cholesky of the symmetric n x n block A (row-major, lower triangle read) into L
// with 1 / L_ii on the diagonal; pivot i (the Schur complement's diagonal) into piv[idx[i]]
// (or piv[i] when idx is NULL). A non-positive pivot is recorded and its direction dropped
// (1 / L_ii = 0) so that the pass stays finite; the caller judges the pivots afterwards.
static void chol_small(double *A, int n, double *piv, const int *idx) {
  for (int i = 0; i < n; ++i) {
    double *Ai = A + (size_t)i * n;
    for (int j = 0; j < i; ++j) {
      const double *Aj = A + (size_t)j * n;
      double s = Ai[j];
      for (int l = 0; l < j; ++l)
        s -= Ai[l] * Aj[l];
      Ai[j] = s * Aj[j];
    }
    double p = Ai[i];
    for (int l = 0; l < i; ++l)
      p -= Ai[l] * Ai[l];
    piv[idx ? idx[i] : i] = p;
    Ai[i] = p > 0.0 && isfinite(p) ? 1.0 / sqrt(p) : 0.0;
  }
}

// the articulated inertias; a degenerate pivot names its coordinate (what: caller, nullable)
static int factor(const dal_system *sys, dal_state *st, const char *what) {
  struct dal_aba *w = st->aba;
  int d = sys->dim, dd = d * d, N = sys->N, n = sys->n;
  DAL_NEED(st, DAL_P_KIN);
  // every articulated inertia starts as its particle's mass
  memset(w->IA, 0, (size_t)N * (size_t)dd * sizeof(double));
  for (int k = 0; k < N; ++k)
    for (int a = 0; a < d; ++a)
      w->IA[k * dd + a * d + a] = sys->mass[k];
  for (int k = N - 1; k >= 0; --k) {
    const dal_place *pl = &sys->place[k];
    int nc = pl->ncoord, p = pl->parent;
    const double *Lc = st->Lc + sys->ploc_off[k];
    double *I = w->IA + k * dd, *L = w->Lf + w->doff[k], *W = w->W + w->woff[k];
    if (nc == 1) {
      // one coordinate (chains, pendulums): D is a number
      double u[3], D = 0.0;
      for (int a = 0; a < d; ++a) {
        double s = 0.0;
        for (int b = 0; b < d; ++b)
          s += I[a * d + b] * Lc[b];
        u[a] = s;
        D += Lc[a] * s;
      }
      int j = sys->ipool[pl->coord_off];
      w->piv[j] = D;
      double inv = D > 0.0 && isfinite(D) ? 1.0 / sqrt(D) : 0.0;
      L[0] = inv;
      for (int a = 0; a < d; ++a)
        W[a] = u[a] * inv;
    } else if (nc > 1) {
      // U = IA Lc into W, D = Lc' U into L, D = L L', then W = U L^-T row by row
      for (int a = 0; a < d; ++a)
        for (int i = 0; i < nc; ++i) {
          double s = 0.0;
          for (int b = 0; b < d; ++b)
            s += I[a * d + b] * Lc[b * nc + i];
          W[a * nc + i] = s;
        }
      for (int i = 0; i < nc; ++i)
        for (int j = 0; j <= i; ++j) {
          double s = 0.0;
          for (int a = 0; a < d; ++a)
            s += Lc[a * nc + i] * W[a * nc + j];
          L[i * nc + j] = s;
        }
      chol_small(L, nc, w->piv, sys->ipool + pl->coord_off);
      for (int a = 0; a < d; ++a)
        for (int i = 0; i < nc; ++i) {
          double s = W[a * nc + i];
          for (int l = 0; l < i; ++l)
            s -= W[a * nc + l] * L[i * nc + l];
          W[a * nc + i] = s * L[i * nc + i];
        }
    }
    if (p < 0) continue;
    // what the parent sees: IA - W W' through Lp
    for (int a = 0; a < d; ++a)
      for (int b = 0; b < d; ++b) {
        double s = 0.0;
        for (int i = 0; i < nc; ++i)
          s -= W[a * nc + i] * W[b * nc + i];
        I[a * d + b] += s;
      }
    double *Ip = w->IA + p * dd;
    if (w->tr[k]) {
      for (int e = 0; e < dd; ++e)
        Ip[e] += I[e];
    } else {
      const double *Lp = st->Lp + (size_t)k * dd;
      double T[9];
      for (int a = 0; a < d; ++a)
        for (int b = 0; b < d; ++b) {
          double s = 0.0;
          for (int c = 0; c < d; ++c)
            s += I[a * d + c] * Lp[c * d + b];
          T[a * d + b] = s;
        }
      for (int a = 0; a < d; ++a)
        for (int b = 0; b < d; ++b) {
          double s = 0.0;
          for (int c = 0; c < d; ++c)
            s += Lp[c * d + a] * T[c * d + b];
          Ip[a * d + b] += s;
        }
    }
  }
  // the dense Cholesky's test: a pivot at most DAL_CHOL_RTOL times the largest is degenerate
  double pmax = 0.0;
  for (int j = 0; j < n; ++j)
    if (w->piv[j] > pmax) pmax = w->piv[j];
  w->pmax = pmax;
  for (int j = 0; j < n; ++j)
    if (!(w->piv[j] > DAL_CHOL_RTOL * pmax)) return singular_coord(sys, st, j, what);
  return DAL_OK;
}

int dal__aba_factor(const dal_system *sys, dal_state *st) { return factor(sys, st, NULL); }

void dal__aba_solve(const dal_system *sys, dal_state *st, const double *tau, double *x) {
  struct dal_aba *w = st->aba;
  int d = sys->dim, dd = d * d, N = sys->N;
  double *pA = w->pA, *acc = w->acc, *z = w->z;
  memset(pA, 0, (size_t)N * (size_t)d * sizeof(double));
  // backward: the loads the subtrees pass to their parents
  for (int k = N - 1; k >= 0; --k) {
    const dal_place *pl = &sys->place[k];
    int nc = pl->ncoord, p = pl->parent;
    const int *ck = sys->ipool + pl->coord_off;
    const double *Lc = st->Lc + sys->ploc_off[k], *L = w->Lf + w->doff[k];
    const double *W = w->W + w->woff[k];
    double *f = pA + k * d;
    for (int i = 0; i < nc; ++i) {
      double s = tau[ck[i]];
      for (int a = 0; a < d; ++a)
        s -= Lc[a * nc + i] * f[a];
      for (int l = 0; l < i; ++l)
        s -= L[i * nc + l] * z[ck[l]];
      z[ck[i]] = s * L[i * nc + i];
    }
    if (p < 0) continue;
    for (int a = 0; a < d; ++a) {
      double s = 0.0;
      for (int i = 0; i < nc; ++i)
        s += W[a * nc + i] * z[ck[i]];
      f[a] += s;
    }
    double *fp = pA + p * d;
    if (w->tr[k]) {
      for (int a = 0; a < d; ++a)
        fp[a] += f[a];
    } else {
      const double *Lp = st->Lp + (size_t)k * dd;
      for (int a = 0; a < d; ++a)
        for (int b = 0; b < d; ++b)
          fp[a] += Lp[b * d + a] * f[b];
    }
  }
  // forward: coordinates and accelerations from the roots out
  for (int k = 0; k < N; ++k) {
    const dal_place *pl = &sys->place[k];
    int nc = pl->ncoord, p = pl->parent;
    const int *ck = sys->ipool + pl->coord_off;
    const double *Lc = st->Lc + sys->ploc_off[k], *L = w->Lf + w->doff[k];
    const double *W = w->W + w->woff[k];
    double ap[3] = {0.0, 0.0, 0.0}, *a = acc + k * d;
    if (p >= 0 && w->tr[k]) {
      for (int b = 0; b < d; ++b)
        ap[b] = acc[p * d + b];
    } else if (p >= 0) {
      const double *Lp = st->Lp + (size_t)k * dd;
      for (int b = 0; b < d; ++b)
        for (int c = 0; c < d; ++c)
          ap[b] += Lp[b * d + c] * acc[p * d + c];
    }
    // y = z - W' ap in x, then x = L^-T y from the last coordinate back
    for (int i = 0; i < nc; ++i) {
      double s = z[ck[i]];
      for (int b = 0; b < d; ++b)
        s -= W[b * nc + i] * ap[b];
      x[ck[i]] = s;
    }
    for (int i = nc - 1; i >= 0; --i) {
      double s = x[ck[i]];
      for (int l = i + 1; l < nc; ++l)
        s -= L[l * nc + i] * x[ck[l]];
      x[ck[i]] = s * L[i * nc + i];
    }
    for (int b = 0; b < d; ++b) {
      double s = ap[b];
      for (int i = 0; i < nc; ++i)
        s += Lc[b * nc + i] * x[ck[i]];
      a[b] = s;
    }
  }
}

int dal__aba_accel(const dal_system *sys, dal_state *st) {
  DAL_NEED(st, DAL_P_KIN | DAL_P_DYN);
  int rc = factor(sys, st, NULL);
  if (rc) return rc;
  for (int j = 0; j < sys->n; ++j)
    st->qddot[j] = st->Q[j] - st->c[j];
  dal__aba_solve(sys, st, st->qddot, st->qddot);
  return DAL_OK;
}

void dal__tree_mass_apply(const dal_system *sys, const dal_state *st, const double *x, double *y) {
  struct dal_aba *w = st->aba;
  int d = sys->dim, dd = d * d, N = sys->N;
  DAL_NEED(st, DAL_P_KIN);
  DAL_ASSERT(w);
  double *acc = w->acc, *f = w->pA;
  // forward: a_k = Lp_k a_p + Lc_k x_k (the accelerations J x)
  for (int k = 0; k < N; ++k) {
    const dal_place *pl = &sys->place[k];
    const int *ck = sys->ipool + pl->coord_off;
    const double *Lc = st->Lc + sys->ploc_off[k], *Lp = st->Lp + (size_t)k * dd;
    int nc = pl->ncoord, p = pl->parent;
    for (int a = 0; a < d; ++a) {
      double s = 0.0;
      for (int b = 0; b < d && p >= 0; ++b)
        s += Lp[a * d + b] * acc[p * d + b];
      for (int i = 0; i < nc; ++i)
        s += Lc[a * nc + i] * x[ck[i]];
      acc[k * d + a] = s;
    }
  }
  // backward: f_k = m_k a_k + sum over children Lp_c' f_c, and (M x)_k = Lc_k' f_k
  memset(f, 0, (size_t)N * (size_t)d * sizeof(double));
  for (int k = N - 1; k >= 0; --k) {
    const dal_place *pl = &sys->place[k];
    const int *ck = sys->ipool + pl->coord_off;
    const double *Lc = st->Lc + sys->ploc_off[k], *Lp = st->Lp + (size_t)k * dd;
    int nc = pl->ncoord, p = pl->parent;
    for (int a = 0; a < d; ++a)
      f[k * d + a] += sys->mass[k] * acc[k * d + a];
    for (int i = 0; i < nc; ++i) {
      double s = 0.0;
      for (int a = 0; a < d; ++a)
        s += Lc[a * nc + i] * f[k * d + a];
      y[ck[i]] = s;
    }
    for (int a = 0; a < d && p >= 0; ++a)
      for (int b = 0; b < d; ++b)
        f[p * d + a] += Lp[b * d + a] * f[k * d + b];
  }
}

// ---------------------------------------------------------------------------------------
// the m x m loop system

int dal__loop_factor(const dal_system *sys, dal_state *st, int metric, const char *what) {
  struct dal_aba *w = st->aba;
  int n = sys->n, m = sys->m, rc;
  DAL_NEED(st, DAL_P_CON);
  DAL_ASSERT(w && m > 0);
  w->metric = -1;
  if (metric == DAL_KKT_MASS && (rc = factor(sys, st, what)) != 0) return rc;
  // Y = A^-1 G': the columns of G' from the compact rows, then one solve each
  memset(w->Y, 0, (size_t)n * (size_t)m * sizeof(double));
  for (int ci = 0; ci < sys->ncon; ++ci) {
    const dal_con *c = &sys->con[ci];
    const int *dc = sys->cdep + c->dep_off;
    const double *G = st->G + c->g_off;
    for (int r = 0; r < c->prim->nout; ++r) {
      double *col = w->Y + (size_t)(c->row + r) * n;
      for (int k = 0; k < c->ndep; ++k)
        col[dc[k]] += G[r * c->ndep + k];
    }
  }
  if (metric == DAL_KKT_MASS)
    for (int r = 0; r < m; ++r)
      dal__aba_solve(sys, st, w->Y + (size_t)r * n, w->Y + (size_t)r * n);
  // S = G Y (lower triangle), then its Cholesky factor
  double smax = 0.0;
  for (int ci = 0; ci < sys->ncon; ++ci) {
    const dal_con *c = &sys->con[ci];
    const int *dc = sys->cdep + c->dep_off;
    const double *G = st->G + c->g_off;
    for (int r = 0; r < c->prim->nout; ++r) {
      int i = c->row + r;
      for (int s = 0; s <= i; ++s) {
        const double *col = w->Y + (size_t)s * n;
        double v = 0.0;
        for (int k = 0; k < c->ndep; ++k)
          v += G[r * c->ndep + k] * col[dc[k]];
        w->S[i * m + s] = v;
      }
      if (w->S[i * m + i] > smax) smax = w->S[i * m + i];
    }
  }
  chol_small(w->S, m, w->r, NULL);
  // degenerate: a pivot small against the largest (dependent rows), or against the scale the
  // dense route's condition estimate of [A G'; G 0] sees (a gradient that vanishes): for
  // A = a I and one row g that estimate is |g|^2 / a, the pivot here
  double gn = 0.0, an = metric == DAL_KKT_MASS ? w->pmax : 1.0;
  for (int ci = 0; ci < sys->ncon; ++ci) {
    const dal_con *c = &sys->con[ci];
    for (int r = 0; r < c->prim->nout; ++r) {
      double s = 0.0;
      for (int k = 0; k < c->ndep; ++k)
        s += fabs(st->G[c->g_off + r * c->ndep + k]);
      gn = fmax(gn, s);
    }
  }
  double kn = fmax(an, gn), floor = DAL_KKT_RCOND_MIN * kn * kn / an;
  for (int i = 0; i < m; ++i)
    if (!(w->r[i] > DAL_CHOL_RTOL * smax) || !(w->r[i] > floor)) {
      // a rank-deficient G is reported by name; otherwise the loop system is degenerate
      char saved[DAL_ERRMSG_LEN];
      rc = dal__check_rank(sys, st, NULL);
      if (rc == DAL_E_CONSTRAINT) {
        memcpy(saved, st->err, sizeof saved);
        return DAL_FAIL(st, DAL_E_CONSTRAINT, "%s: %s", what, saved);
      }
      char qs[256];
      dal__fmt_q(sys, st->q, qs, sizeof qs);
      return DAL_FAIL(st, DAL_E_SINGULAR,
                      "%s: the loop system G M^-1 G' is singular at t=%.17g, %s (constraint "
                      "'%s', pivot %.3g of %.3g): the constraints are redundant or their "
                      "gradients vanish there; check the constraint list",
                      what, st->t, qs, sys->con[sys->row_con[i]].name, w->r[i], smax);
    }
  w->metric = metric;
  return DAL_OK;
}

void dal__loop_solve(const dal_system *sys, dal_state *st, const double *a, const double *b,
                     double *x, double *y) {
  struct dal_aba *w = st->aba;
  int n = sys->n, m = sys->m;
  DAL_ASSERT(w && w->metric >= 0);
  double *x0 = w->x0, *r = w->r;
  // x0 = A^-1 a
  if (w->metric == DAL_KKT_MASS)
    dal__aba_solve(sys, st, a, x0);
  else
    memcpy(x0, a, (size_t)n * sizeof(double));
  // r = b - G x0
  for (int ci = 0; ci < sys->ncon; ++ci) {
    const dal_con *c = &sys->con[ci];
    const int *dc = sys->cdep + c->dep_off;
    const double *G = st->G + c->g_off;
    for (int k = 0; k < c->prim->nout; ++k) {
      double s = b[c->row + k];
      for (int j = 0; j < c->ndep; ++j)
        s -= G[k * c->ndep + j] * x0[dc[j]];
      r[c->row + k] = s;
    }
  }
  // y = S^-1 r by the factor L L' (diagonal stored inverted)
  const double *S = w->S;
  for (int i = 0; i < m; ++i) {
    double s = r[i];
    for (int l = 0; l < i; ++l)
      s -= S[i * m + l] * r[l];
    r[i] = s * S[i * m + i];
  }
  for (int i = m - 1; i >= 0; --i) {
    double s = r[i];
    for (int l = i + 1; l < m; ++l)
      s -= S[l * m + i] * r[l];
    r[i] = s * S[i * m + i];
  }
  // x = x0 + Y y
  for (int j = 0; j < n; ++j) {
    double s = x0[j];
    for (int i = 0; i < m; ++i)
      s += w->Y[(size_t)i * n + j] * r[i];
    x[j] = s;
  }
  memcpy(y, r, (size_t)m * sizeof(double));
}
