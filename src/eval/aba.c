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
// and c the dense route uses); when every force acts on the particles (no generalized force,
// no potential over q) they come instead from tau = 0 with pA_k starting at the particle load
// m_k gamma_k - F_k, Featherstone's bias form: the same equations (Q - c = sum J_k' (F_k -
// m_k gamma_k)) without forming Q and c, so an integrator's right-hand side skips them
// (pipeline.c). The pivots of the D_k are those of an LDL' factorization of M
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

#include "eval.h"
#include "linalg/linalg.h"

// one placement as the recursion reads it
typedef struct aba_node {
  int parent;    // -1 for a root
  int nc;        // its coordinates
  int tr;        // the parent link is a translation (Lp = I)
  int j;         // its first coordinate
  const int *ck; // its coordinates (the system's index pool)
  int lc;        // offset of its columns Lc in st->Lc
  int fo, wo;    // offsets of its factor in Lf and of W
} aba_node;

struct dal_aba {
  aba_node *node;   // the N placements
  double *IA;       // articulated inertias (N x d x d, row-major)
  double *Lf;       // Cholesky factors of D_k (row-major lower, the diagonal holds 1 / L_ii);
                    // one coordinate: 1 / D_k (an LDL' step, no square root)
  double *W;        // W_k = IA_k Lc_k L_k^-T (d x nc, row-major); one coordinate: IA_k Lc_k
  double *piv;      // pivot of each coordinate (n)
  double *pA, *acc; // bias forces and accelerations (N x d)
  double *z;        // L_k^-1 (tau_k - Lc_k' pA_k) per coordinate (n)
  double *zero;     // a zero load on the coordinates (n)
  double pmax;      // largest pivot of the last factorization (the scale of M)
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
  w->node = calloc((size_t)N + 1, sizeof(aba_node));
  if (!w->node) {
    dal__aba_free(w);
    return NULL;
  }
  int fo = 0, wo = 0;
  for (int k = 0; k < N; ++k) {
    const dal_place *pl = &sys->place[k];
    aba_node *nd = &w->node[k];
    nd->parent = pl->parent;
    nd->nc = pl->ncoord;
    nd->tr = pl->parent >= 0 && (pl->prim->flags & DAL_PRIM_TRANSLATES);
    nd->ck = sys->ipool + pl->coord_off;
    nd->j = pl->ncoord ? nd->ck[0] : -1;
    nd->lc = sys->ploc_off[k];
    nd->fo = fo;
    nd->wo = wo;
    fo += pl->ncoord * pl->ncoord;
    wo += d * pl->ncoord;
  }
  w->IA = calloc(Nd * (size_t)d + 1, sizeof(double));
  w->Lf = calloc((size_t)fo + 1, sizeof(double));
  w->W = calloc((size_t)wo + 1, sizeof(double));
  w->piv = calloc(n + 1, sizeof(double));
  w->pA = calloc(Nd + 1, sizeof(double));
  w->acc = calloc(Nd + 1, sizeof(double));
  w->z = calloc(n + 1, sizeof(double));
  w->zero = calloc(n + 1, sizeof(double));
  w->metric = -1;
  if (m) {
    w->Y = calloc(n * m, sizeof(double));
    w->S = calloc(m * m, sizeof(double));
    w->x0 = calloc(n, sizeof(double));
    w->r = calloc(m, sizeof(double));
  }
  if (!w->IA || !w->Lf || !w->W || !w->piv || !w->pA || !w->acc || !w->z || !w->zero ||
      (m && (!w->Y || !w->S || !w->x0 || !w->r))) {
    dal__aba_free(w);
    return NULL;
  }
  return w;
}

void dal__aba_free(struct dal_aba *w) {
  if (!w) return;
  free(w->node);
  DAL_FREE(w->IA, w->Lf, w->W, w->piv, w->pA, w->acc, w->z, w->zero, w->Y, w->S, w->x0, w->r, w);
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

// several coordinates in one placement: U = IA Lc into W, D = Lc' U into L, D = L L', then
// W = U L^-T row by row
static void node_factor_multi(const aba_node *nd, int d, const double *I, const double *Lc,
                              double *L, double *W, double *piv) {
  int nc = nd->nc;
  dal__gemm('N', 'N', nc, d, d, Lc, nc, I, d, W, nc); // row-major W = I Lc
  for (int i = 0; i < nc; ++i)
    for (int j = 0; j <= i; ++j) {
      double s = 0.0;
      for (int a = 0; a < d; ++a)
        s += Lc[a * nc + i] * W[a * nc + j];
      L[i * nc + j] = s;
    }
  chol_small(L, nc, piv, nd->ck);
  for (int a = 0; a < d; ++a)
    for (int i = 0; i < nc; ++i) {
      double s = W[a * nc + i];
      for (int l = 0; l < i; ++l)
        s -= W[a * nc + l] * L[i * nc + l];
      W[a * nc + i] = s * L[i * nc + i];
    }
}

// the bias step of placement k for the load tau: z_k = L^-1 (tau_k - Lc' f) and, unless it
// is a root, f += W z (the load its parent sees before Lp)
static inline void node_bias(const aba_node *nd, const int d, const double *Lc, const double *W,
                             const double *L, const double *tau, double *f, double *z) {
  int nc = nd->nc;
  if (nc == 1) {
    double u = tau[nd->j];
    for (int a = 0; a < d; ++a)
      u -= Lc[a] * f[a];
    z[nd->j] = u;
    if (nd->parent < 0) return;
    u *= L[0];
    for (int a = 0; a < d; ++a)
      f[a] += W[a] * u;
    return;
  }
  const int *ck = nd->ck;
  for (int i = 0; i < nc; ++i) {
    double s = tau[ck[i]];
    for (int a = 0; a < d; ++a)
      s -= Lc[a * nc + i] * f[a];
    for (int l = 0; l < i; ++l)
      s -= L[i * nc + l] * z[ck[l]];
    z[ck[i]] = s * L[i * nc + i];
  }
  if (nd->parent < 0) return;
  for (int a = 0; a < d; ++a)
    for (int i = 0; i < nc; ++i)
      f[a] += W[a * nc + i] * z[ck[i]];
}

// a d-vector passed to the parent: fp += Lp' f (f itself for a translation)
static inline void pass_up(const aba_node *nd, const int d, const double *Lp, const double *f,
                           double *fp) {
  if (nd->tr) {
    for (int a = 0; a < d; ++a)
      fp[a] += f[a];
    return;
  }
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b)
      fp[a] += Lp[b * d + a] * f[b];
}

// The backward pass for d = 2 or 3 (a constant once inlined): articulated inertias and, for a
// load tau on the coordinates (nullable), the bias forces in the same sweep, starting from the
// particle loads m gamma - F when `loads` is set, else from 0.
// the articulated inertia I (d x d) of a node as its parent sees it, added to the parent's
// Ip: I itself across a translating link, else Lp' I Lp
static inline void add_to_parent(double *restrict Ip, const double *restrict I, const double *Lp,
                                 const int d, int tr) {
  if (tr) {
    for (int e = 0; e < d * d; ++e)
      Ip[e] += I[e];
    return;
  }
  double T[9];
  dal__gemm('N', 'N', d, d, d, Lp, d, I, d, T, d); // row-major T = I Lp
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b) {
      double s = 0.0;
      for (int c = 0; c < d; ++c)
        s += Lp[c * d + a] * T[c * d + b];
      Ip[a * d + b] += s;
    }
}

static inline void factor_pass(struct dal_aba *w, const dal_state *st, const double *mass, int N,
                               const int d, const double *tau, int loads) {
  const int dd = d * d;
  double *restrict IA = w->IA, *restrict pA = w->pA;
  const double *gam = st->gamma, *F = st->F;
  // every articulated inertia starts as its particle's mass, every bias force at its load
  for (int k = 0; k < N; ++k)
    for (int a = 0; a < d; ++a) {
      for (int b = 0; b < d; ++b)
        IA[k * dd + a * d + b] = a == b ? mass[k] : 0.0;
      pA[k * d + a] = loads ? mass[k] * gam[k * d + a] - F[k * d + a] : 0.0;
    }
  for (int k = N - 1; k >= 0; --k) {
    const aba_node *nd = &w->node[k];
    const double *restrict Lc = st->Lc + nd->lc, *Lp = st->Lp + (size_t)k * dd;
    double *restrict I = IA + k * dd, *restrict W = w->W + nd->wo, *L = w->Lf + nd->fo;
    int p = nd->parent, tau_done = 0;
    if (nd->nc == 1) {
      // one coordinate (chains, pendulums): an LDL' step, D = Lc' IA Lc a number
      double D = 0.0;
      for (int a = 0; a < d; ++a) {
        double s = 0.0;
        for (int b = 0; b < d; ++b)
          s += I[a * d + b] * Lc[b];
        W[a] = s;
        D += Lc[a] * s;
      }
      w->piv[nd->j] = D;
      double inv = D > 0.0 && D < INFINITY ? 1.0 / D : 0.0;
      L[0] = inv;
      if (tau) node_bias(nd, d, Lc, W, L, tau, pA + k * d, w->z);
      if (p >= 0 && nd->tr) {
        // a translating link (chains): the parent adds IA - U U' / D and pA + U z / D
        double *restrict Ip = IA + p * dd;
        for (int a = 0; a < d; ++a)
          for (int b = 0; b < d; ++b)
            Ip[a * d + b] += I[a * d + b] - W[a] * W[b] * inv;
        if (tau)
          for (int a = 0; a < d; ++a)
            pA[p * d + a] += pA[k * d + a];
        continue;
      }
      if (p >= 0)
        for (int a = 0; a < d; ++a)
          for (int b = 0; b < d; ++b)
            I[a * d + b] -= W[a] * W[b] * inv;
      if (tau) {
        if (p >= 0) pass_up(nd, d, Lp, pA + k * d, pA + p * d);
        tau_done = 1;
      }
    } else {
      if (nd->nc > 1) node_factor_multi(nd, d, I, Lc, L, W, w->piv);
      for (int a = 0; a < d && p >= 0; ++a)
        for (int b = 0; b < d; ++b) {
          double s = 0.0;
          for (int i = 0; i < nd->nc; ++i)
            s += W[a * nd->nc + i] * W[b * nd->nc + i];
          I[a * d + b] -= s;
        }
    }
    if (tau && !tau_done) {
      node_bias(nd, d, Lc, W, L, tau, pA + k * d, w->z);
      if (p >= 0) pass_up(nd, d, Lp, pA + k * d, pA + p * d);
    }
    if (p < 0) continue;
    // what the parent sees: Lp' (IA - W W') Lp, and Lp' (pA + W z)
    add_to_parent(IA + p * dd, I, Lp, d, nd->tr);
  }
}

// the dense Cholesky's test on the pivots: at most DAL_CHOL_RTOL times the largest is
// degenerate (what: caller, nullable)
static int check_pivots(const dal_system *sys, dal_state *st, const char *what) {
  struct dal_aba *w = st->aba;
  int n = sys->n;
  double pmax = 0.0;
  for (int j = 0; j < n; ++j)
    if (w->piv[j] > pmax) pmax = w->piv[j];
  w->pmax = pmax;
  for (int j = 0; j < n; ++j)
    if (!(w->piv[j] > DAL_CHOL_RTOL * pmax)) return dal__fail_degenerate(sys, st, j, what);
  return DAL_OK;
}

// the articulated inertias; a degenerate pivot names its coordinate (what: caller, nullable)
static int factor(const dal_system *sys, dal_state *st, const char *what) {
  DAL_NEED(st, DAL_P_KIN);
  if (sys->dim == 2)
    factor_pass(st->aba, st, st->prm.mass, sys->N, 2, NULL, 0);
  else
    factor_pass(st->aba, st, st->prm.mass, sys->N, 3, NULL, 0);
  return check_pivots(sys, st, what);
}

int dal__aba_factor(const dal_system *sys, dal_state *st) { return factor(sys, st, NULL); }

// the forward pass for d = 2 or 3: coordinates x and accelerations from the roots out
static inline void forward_pass(struct dal_aba *w, const dal_state *st, int N, const int d,
                                double *x) {
  const int dd = d * d;
  double *restrict acc = w->acc;
  const double *restrict z = w->z;
  for (int k = 0; k < N; ++k) {
    const aba_node *nd = &w->node[k];
    const double *restrict Lc = st->Lc + nd->lc, *restrict W = w->W + nd->wo;
    const double *L = w->Lf + nd->fo;
    double ap[3] = {0.0, 0.0, 0.0}, *restrict a = acc + k * d;
    int p = nd->parent, nc = nd->nc;
    if (p >= 0 && nd->tr) {
      for (int b = 0; b < d; ++b)
        ap[b] = acc[p * d + b];
    } else if (p >= 0) {
      const double *Lp = st->Lp + (size_t)k * dd;
      for (int b = 0; b < d; ++b)
        for (int c = 0; c < d; ++c)
          ap[b] += Lp[b * d + c] * acc[p * d + c];
    }
    if (nc == 1) {
      // x = (z - U' ap) / D
      double y = z[nd->j];
      for (int b = 0; b < d; ++b)
        y -= W[b] * ap[b];
      y *= L[0];
      x[nd->j] = y;
      for (int b = 0; b < d; ++b)
        a[b] = ap[b] + Lc[b] * y;
      continue;
    }
    // y = z - W' ap in x, then x = L^-T y from the last coordinate back
    const int *ck = nd->ck;
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

// x = M^-1 tau with the articulated inertias held, for d = 2 or 3; x may alias tau
static inline void solve_pass(struct dal_aba *w, const dal_state *st, int N, const int d,
                              const double *tau, double *x) {
  double *restrict pA = w->pA;
  for (int e = 0; e < N * d; ++e)
    pA[e] = 0.0;
  // backward: the loads the subtrees pass to their parents
  for (int k = N - 1; k >= 0; --k) {
    const aba_node *nd = &w->node[k];
    node_bias(nd, d, st->Lc + nd->lc, w->W + nd->wo, w->Lf + nd->fo, tau, pA + k * d, w->z);
    if (nd->parent >= 0)
      pass_up(nd, d, st->Lp + (size_t)k * d * d, pA + k * d, pA + nd->parent * d);
  }
  forward_pass(w, st, N, d, x);
}

void dal__aba_solve(const dal_system *sys, dal_state *st, const double *tau, double *x) {
  if (sys->dim == 2)
    solve_pass(st->aba, st, sys->N, 2, tau, x);
  else
    solve_pass(st->aba, st, sys->N, 3, tau, x);
}

int dal__aba_accel(const dal_system *sys, dal_state *st) {
  DAL_NEED(st, DAL_P_KIN);
  struct dal_aba *w = st->aba;
  int N = sys->N, d = sys->dim;
  // every force on the particles: the bias forces start at the particle loads m gamma - F
  // (Featherstone's form; no Q and c needed, so the right-hand side can skip them); with
  // generalized forces too, tau = Q - c (dal__dynamics)
  int loads = !sys->npotq && !sys->ngenforce;
  const double *tau = w->zero;
  if (!loads) {
    DAL_NEED(st, DAL_P_DYN);
    for (int j = 0; j < sys->n; ++j)
      st->qddot[j] = st->Q[j] - st->c[j];
    tau = st->qddot;
  }
  // one backward sweep (inertias and biases) and one forward sweep
  if (d == 2)
    factor_pass(w, st, st->prm.mass, N, 2, tau, loads);
  else
    factor_pass(w, st, st->prm.mass, N, 3, tau, loads);
  int rc = check_pivots(sys, st, NULL);
  if (rc) return rc;
  if (d == 2)
    forward_pass(w, st, N, 2, st->qddot);
  else
    forward_pass(w, st, N, 3, st->qddot);
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
      f[k * d + a] += st->prm.mass[k] * acc[k * d + a];
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
      if ((rc = dal__blame_rank(sys, st, what)) != 0) return rc;
      return DAL_FAIL(st, DAL_E_SINGULAR,
                      "%s: the loop system G M^-1 G' is singular at t=%.17g, %s (constraint "
                      "'%s', pivot %.3g of %.3g): the constraints are redundant or their "
                      "gradients vanish there; check the constraint list",
                      what, st->t, dal__qtext(sys, st->q).s, sys->con[sys->row_con[i]].name,
                      w->r[i], smax);
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
