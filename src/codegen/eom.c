// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Compiled equations of motion of a minimal-coordinate system: the closed form of the positions
// differentiated by the symbolic layer (J, gamma, dU/dq), M and Q - c assembled and solved by
// an unrolled LDL' in straight-line C, compiled through the native cache.
#define _POSIX_C_SOURCE 200809L
#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "codegen.h"

/// the largest system compiled (the unrolled solve grows as n^3)
#define EOM_MAX_N 24
/// a potential's parameter symbol: EOM_XPAR + (potential << 12) + index (below: ppool index)
#define EOM_XPAR (1 << 24)

typedef int eom_raw(double t, const double *q, const double *qd, const double *P,
                    const double *const *X, const double *m, const double *g, double *qdd);

struct dal_eom {
  void *handle;
  eom_raw *fn;
  const double **x; // the potentials' parameter values (their expressions own them)
};

// the derivation: one tree, one algebra session
typedef struct eb {
  const dal_system *sys;
  dal_xtree tr;
  dal_alg g;
  int n, N, d, np;
  int *pos;  // N x d
  int *J;    // (N d) x n
  int *gam;  // N d
  int *dU;   // n
  int *have; // N: position made
  const dal_expr **pot;
  int npot;
} eb;

static int say(char *msg, size_t len, int rc, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static int say(char *msg, size_t len, int rc, const char *fmt, ...) {
  if (msg && len) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, len, fmt, ap);
    va_end(ap);
  }
  return rc;
}

// the expression of a primitive instance (prim, ctx), or NULL when it is not one
static const dal_expr *expr_of(const dal_primitive *prim, const void *ctx) {
  if (!ctx || !prim) return NULL;
  uintptr_t e = (uintptr_t)prim - offsetof(dal_expr, prim);
  return e == (uintptr_t)ctx ? (const dal_expr *)ctx : NULL;
}

// formula `root` of e in our tree, its inputs replaced by the nodes in[], its parameters by
// the symbols par0 + index; canonical; -1 on failure
static int import(eb *b, const dal_expr *e, int root, const int *in, int nin, int par0) {
  const dal_xtree *t = &e->tree;
  int *map = malloc(((size_t)root + 1) * sizeof *map);
  char *reach = calloc((size_t)root + 1, 1);
  int r = -1;
  if (!map || !reach) goto done;
  reach[root] = 1;
  for (int i = root; i >= 0; --i)
    if (reach[i]) {
      if (t->node[i].a >= 0) reach[t->node[i].a] = 1;
      if (t->node[i].b >= 0) reach[t->node[i].b] = 1;
    }
  for (int i = 0; i <= root; ++i) {
    if (!reach[i]) continue;
    const dal_xnode *x = &t->node[i];
    switch (x->op) {
    case X_NUM:
      map[i] = dal__xnum(&b->tr, x->c);
      break;
    case X_IN:
      map[i] = x->idx < nin ? in[x->idx] : -1;
      break;
    case X_PAR:
      map[i] = dal__xnode(&b->tr, X_PAR, -1, -1, par0 + x->idx, 0.0);
      break;
    case X_TIME:
      map[i] = dal__xnode(&b->tr, X_TIME, -1, -1, 0, 0.0);
      break;
    default:
      map[i] =
          dal__xnode(&b->tr, x->op, x->a >= 0 ? map[x->a] : -1, x->b >= 0 ? map[x->b] : -1, 0, 0.0);
    }
    if (map[i] < 0) goto done;
  }
  r = dal__alg_canon(&b->g, map[root]);
done:
  free(map);
  free(reach);
  if (r < 0) b->g.fail = 1;
  return r;
}

static int qnode(eb *b, int j) { return dal__xnode(&b->tr, X_IN, -1, -1, j, 0.0); }

// a link by dal_map_hanging (a scene file's chain link, recognised by the scene's builder):
// x_P + l*sin(q), y_P - l*cos(q), l the placement's parameter
static int is_hanging(const dal_place *pl, int d) {
  return pl->prim == &dal_map_hanging && pl->parent >= 0 && pl->ncoord == 1 && d == 2;
}

static int place_hanging(eb *b, int k, const dal_place *pl) {
  int q = qnode(b, b->sys->ipool[pl->coord_off]);
  int l = dal__xnode(&b->tr, X_PAR, -1, -1, pl->param_off + DAL_HANGING_L, 0.0);
  int s = dal__xnode(&b->tr, X_MUL, l, dal__xnode(&b->tr, X_SIN, q, -1, 0, 0.0), 0, 0.0);
  int c = dal__xnode(&b->tr, X_MUL, l, dal__xnode(&b->tr, X_COS, q, -1, 0, 0.0), 0, 0.0);
  int x = dal__xnode(&b->tr, X_ADD, b->pos[pl->parent * 2], s, 0, 0.0);
  int y = dal__xnode(&b->tr, X_SUB, b->pos[pl->parent * 2 + 1], c, 0, 0.0);
  b->pos[k * 2] = dal__alg_canon(&b->g, x);
  b->pos[k * 2 + 1] = dal__alg_canon(&b->g, y);
  if (b->pos[k * 2] < 0 || b->pos[k * 2 + 1] < 0) b->g.fail = 1;
  b->have[k] = 1;
  return b->g.fail ? -1 : 0;
}

// the position of particle k (its parent's first)
static int place(eb *b, int k, int depth) {
  if (b->have[k]) return b->g.fail ? -1 : 0;
  const dal_place *pl = &b->sys->place[k];
  const dal_expr *e = expr_of(pl->prim, pl->ctx);
  if ((!e && !is_hanging(pl, b->d)) || depth > b->N) return -1;
  if (!e) return place(b, pl->parent, depth + 1) ? -1 : place_hanging(b, k, pl);
  int in[64], d = b->d, k0 = 0;
  if (pl->parent >= 0) {
    if (place(b, pl->parent, depth + 1)) return -1;
    for (int c = 0; c < d; ++c)
      in[k0++] = b->pos[pl->parent * d + c];
  }
  if (k0 + pl->ncoord > 64 || e->tree.nin != k0 + pl->ncoord || e->nout != d) return -1;
  for (int i = 0; i < pl->ncoord; ++i)
    in[k0 + i] = qnode(b, b->sys->ipool[pl->coord_off + i]);
  for (int c = 0; c < d; ++c)
    b->pos[k * d + c] = import(b, e, e->roots[c], in, k0 + pl->ncoord, pl->param_off);
  b->have[k] = 1;
  return b->g.fail ? -1 : 0;
}

// sum_j a_j qd_j + extra over the derivatives a_j = d x / d q_j
static int along(eb *b, const int *dx, int extra) {
  int *t = malloc(((size_t)b->n + 1) * sizeof *t), nt = 0;
  if (!t) {
    b->g.fail = 1;
    return -1;
  }
  for (int j = 0; j < b->n; ++j)
    if (!dal__alg_isnum(&b->g, dx[j], 0.0)) {
      int f[2] = {dx[j], qnode(b, b->n + j)};
      t[nt++] = dal__alg_mul(&b->g, f, 2);
    }
  t[nt++] = extra;
  int r = dal__alg_add(&b->g, t, nt);
  free(t);
  return r;
}

// why sys is out of reach (NULL: it is not)
static const char *unsupported(const dal_system *sys, char *why, size_t len) {
  if (sys->m || sys->ncon) return "it has constraints (the DAE forms run)";
  if (sys->map || sys->lag) return "it is given by a global map or a Lagrangian";
  if (sys->n > EOM_MAX_N) {
    snprintf(why, len, "it has %d coordinates (at most %d)", sys->n, EOM_MAX_N);
    return why;
  }
  if (sys->nspring || sys->ndamper) return "it has springs or dampers";
  if (sys->nforce || sys->ngenforce) return "it has force callbacks";
  for (int i = 0; i < sys->npotq; ++i)
    if (sys->potq[i].fn.potq != dal_expr_potential_q) return "a potential is a C callback";
  for (int i = 0; i < sys->npotr; ++i)
    if (sys->potr[i].fn.potr != dal_expr_potential_r) return "a potential is a C callback";
  for (int k = 0; k < sys->N; ++k)
    if (!sys->place || (!expr_of(sys->place[k].prim, sys->place[k].ctx) &&
                        !is_hanging(&sys->place[k], sys->dim))) {
      snprintf(why, len, "particle '%s' is not placed by formulas", sys->part_names[k]);
      return why;
    }
  return NULL;
}

// the derivation: positions, J, gamma, dU/dq
static int derive(eb *b) {
  const dal_system *sys = b->sys;
  int n = b->n, nd = b->N * b->d, *in = NULL;
  for (int k = 0; k < b->N; ++k)
    if (place(b, k, 0)) return -1;
  // potentials: U(q, t) and U(r, t), their sum
  int *terms = malloc(((size_t)sys->npotq + (size_t)sys->npotr + 1) * sizeof *terms), nt = 0;
  in = malloc(((size_t)nd + (size_t)n + 1) * sizeof *in);
  b->pot = malloc(((size_t)sys->npotq + (size_t)sys->npotr + 1) * sizeof *b->pot);
  if (!terms || !in || !b->pot) goto fail;
  for (int j = 0; j < n; ++j)
    in[j] = qnode(b, j);
  for (int i = 0; i < sys->npotq + sys->npotr; ++i) {
    int isq = i < sys->npotq;
    const dal_expr *e = isq ? sys->potq[i].ctx : sys->potr[i - sys->npotq].ctx;
    if (!e || e->nout != 1 || e->tree.nin != (isq ? n : nd)) goto fail;
    b->pot[b->npot] = e;
    terms[nt++] =
        import(b, e, e->roots[0], isq ? in : b->pos, isq ? n : nd, EOM_XPAR + (b->npot << 12));
    b->npot++;
  }
  int U = nt ? dal__alg_add(&b->g, terms, nt) : -1;
  // J, dU/dq (one variable at a time: the algebra's memo holds one)
  int *rt = malloc(((size_t)nd * 3 + 1) * sizeof *rt), *v = rt + nd, *tmp = rt + 2 * nd;
  int *dv = malloc(((size_t)nd * (size_t)n + 1) * sizeof *dv);
  if (!rt || !dv) {
    free(rt);
    free(dv);
    goto fail;
  }
  for (int j = 0; j < n; ++j) {
    for (int r = 0; r < nd; ++r)
      b->J[r * n + j] = dal__alg_diff(&b->g, b->pos[r], j);
    b->dU[j] = U >= 0 ? dal__alg_diff(&b->g, U, j) : dal__xnum(&b->tr, 0.0);
  }
  for (int r = 0; r < nd; ++r)
    rt[r] = dal__alg_diff(&b->g, b->pos[r], -1);
  // v = J qd + dr/dt; gamma = (dv/dq) qd + dv/dt at fixed qd
  for (int r = 0; r < nd; ++r)
    v[r] = along(b, b->J + (size_t)r * n, rt[r]);
  for (int j = 0; j < n; ++j)
    for (int r = 0; r < nd; ++r)
      dv[r * n + j] = dal__alg_diff(&b->g, v[r], j);
  for (int r = 0; r < nd; ++r)
    tmp[r] = dal__alg_diff(&b->g, v[r], -1);
  for (int r = 0; r < nd; ++r)
    b->gam[r] = along(b, dv + (size_t)r * n, tmp[r]);
  free(rt);
  free(dv);
  free(terms);
  free(in);
  return b->g.fail ? -1 : 0;
fail:
  b->g.fail = 1;
  free(terms);
  free(in);
  return -1;
}

// ---------------------------------------------------------------------------------------------
// emission

static const dal_xnode *nd_(const eb *b, int i) { return &b->tr.node[i]; }

// a power with a small exponent written out: 1 when x^e has one (k: the form)
static int small_pow(double e) {
  return e == 0.5 || e == -0.5 || e == 1.5 || e == -1.5 ||
         (e == floor(e) && fabs(e) <= 8.0 && e != 0.0);
}

// the nodes node i's code reads (a product by x^-1 reads x: it divides)
static int operands(const eb *b, int i, int *o) {
  const dal_xnode *x = nd_(b, i);
  int k = 0;
  switch (x->op) {
  case X_NUM:
  case X_IN:
  case X_PAR:
  case X_TIME:
    return 0;
  case X_MUL: {
    const dal_xnode *B = nd_(b, x->b);
    if (nd_(b, x->a)->op != X_NUM) o[k++] = x->a;
    if (B->op == X_POW && nd_(b, B->b)->op == X_NUM && nd_(b, B->b)->c == -1.0)
      o[k++] = B->a;
    else if (B->op != X_NUM)
      o[k++] = x->b;
    return k;
  }
  case X_POW:
    o[k++] = x->a;
    if (nd_(b, x->b)->op != X_NUM) o[k++] = x->b;
    return k;
  default:
    if (x->a >= 0 && nd_(b, x->a)->op != X_NUM) o[k++] = x->a;
    if (x->b >= 0 && nd_(b, x->b)->op != X_NUM) o[k++] = x->b;
    return k;
  }
}

// a node as an operand: a literal or its local
typedef struct ref {
  char s[48];
} ref;

static ref R(const eb *b, int i) {
  ref r;
  const dal_xnode *x = nd_(b, i);
  if (x->op == X_NUM)
    snprintf(r.s, sizeof r.s, "(%a)", x->c);
  else
    snprintf(r.s, sizeof r.s, "x%d", i);
  return r;
}

static const char *const fn1[] = {"sin",  "cos",  "tan",  "asin", "acos", "atan",
                                  "sinh", "cosh", "tanh", "exp",  "log",  "sqrt"};

static void emit_node(dal_cgbuf *o, const eb *b, int i) {
  const dal_xnode *x = nd_(b, i);
  dal__cg_printf(o, "  const double x%d = ", i);
  switch (x->op) {
  case X_IN:
    if (x->idx < b->n)
      dal__cg_printf(o, "q[%d];\n", x->idx);
    else
      dal__cg_printf(o, "qd[%d];\n", x->idx - b->n);
    return;
  case X_PAR:
    if (x->idx >= EOM_XPAR)
      dal__cg_printf(o, "X[%d][%d];\n", (x->idx - EOM_XPAR) >> 12, (x->idx - EOM_XPAR) & 4095);
    else
      dal__cg_printf(o, "P[%d];\n", x->idx);
    return;
  case X_TIME:
    dal__cg_printf(o, "t;\n");
    return;
  case X_ADD:
    dal__cg_printf(o, "%s + %s;\n", R(b, x->a).s, R(b, x->b).s);
    return;
  case X_MUL: {
    const dal_xnode *A = nd_(b, x->a), *B = nd_(b, x->b);
    if (B->op == X_POW && nd_(b, B->b)->op == X_NUM && nd_(b, B->b)->c == -1.0)
      dal__cg_printf(o, "%s / %s;\n", R(b, x->a).s, R(b, B->a).s);
    else if (A->op == X_NUM && A->c == -1.0)
      dal__cg_printf(o, "-%s;\n", R(b, x->b).s);
    else
      dal__cg_printf(o, "%s * %s;\n", R(b, x->a).s, R(b, x->b).s);
    return;
  }
  case X_POW: {
    const dal_xnode *E = nd_(b, x->b);
    ref a = R(b, x->a);
    if (E->op != X_NUM || !small_pow(E->c)) {
      dal__cg_printf(o, "pow(%s, %s);\n", a.s, R(b, x->b).s);
      return;
    }
    double e = fabs(E->c), k = floor(e);
    const char *inv = E->c < 0 ? "1.0 / (" : "(";
    dal__cg_printf(o, "%s", inv);
    int first = 1;
    for (int p = 0; p < (int)k; ++p, first = 0)
      dal__cg_printf(o, "%s%s", first ? "" : " * ", a.s);
    if (e != k) dal__cg_printf(o, "%ssqrt(%s)", first ? "" : " * ", a.s);
    dal__cg_printf(o, ");\n");
    return;
  }
  case X_ATAN2:
  case X_HYPOT:
    dal__cg_printf(o, "%s(%s, %s);\n", x->op == X_ATAN2 ? "atan2" : "hypot", R(b, x->a).s,
                   R(b, x->b).s);
    return;
  case X_SUB:
    dal__cg_printf(o, "%s - %s;\n", R(b, x->a).s, R(b, x->b).s);
    return;
  case X_DIV:
    dal__cg_printf(o, "%s / %s;\n", R(b, x->a).s, R(b, x->b).s);
    return;
  case X_NEG:
    dal__cg_printf(o, "-%s;\n", R(b, x->a).s);
    return;
  default:
    if (x->op >= X_SIN && x->op <= X_SQRT)
      dal__cg_printf(o, "%s(%s);\n", fn1[x->op - X_SIN], R(b, x->a).s);
    else
      dal__cg_printf(o, "NAN;\n");
  }
}

static int zero(const eb *b, int i) { return dal__alg_isnum(&b->g, i, 0.0); }

// sums over sets of particles, each emitted once: a set's sum is its first member plus the sum
// of the rest (a suffix shared, as the sets of a chain are: the masses beyond a link)
typedef struct sums {
  int n, cap;
  char **key; // "kind c k1 k2 ..."
} sums;

// the local holding sum_{k in set} m[k] (c < 0) or a<k>_<c>; its name into out
static void setsum(dal_cgbuf *o, sums *S, const int *set, int ns, int c, char *out, size_t len) {
  if (ns == 1) {
    if (c < 0)
      snprintf(out, len, "m[%d]", set[0]);
    else
      snprintf(out, len, "a%d_%d", set[0], c);
    return;
  }
  char key[2048];
  int k = snprintf(key, sizeof key, "%d", c);
  for (int i = 0; i < ns && k < (int)sizeof key - 16; ++i)
    k += snprintf(key + k, sizeof key - (size_t)k, " %d", set[i]);
  for (int i = 0; i < S->n; ++i)
    if (!strcmp(S->key[i], key)) {
      snprintf(out, len, "S%d", i);
      return;
    }
  char rest[32];
  setsum(o, S, set + 1, ns - 1, c, rest, sizeof rest);
  if (S->n == S->cap) {
    int cap = S->cap ? 2 * S->cap : 64;
    char **v = realloc(S->key, (size_t)cap * sizeof *v);
    if (!v) {
      o->oom = 1;
      snprintf(out, len, "0");
      return;
    }
    S->key = v;
    S->cap = cap;
  }
  char *dup = malloc(strlen(key) + 1);
  if (!dup) {
    o->oom = 1;
    snprintf(out, len, "0");
    return;
  }
  strcpy(dup, key);
  S->key[S->n] = dup;
  if (c < 0)
    dal__cg_printf(o, "  const double S%d = m[%d] + %s;\n", S->n, set[0], rest);
  else
    dal__cg_printf(o, "  const double S%d = a%d_%d + %s;\n", S->n, set[0], c, rest);
  snprintf(out, len, "S%d", S->n++);
}

// 1 when particles k and l have the same Jacobian entries in columns i and j (nodes)
static int same_cols(const eb *b, int k, int l, int i, int j) {
  int n = b->n, d = b->d;
  for (int c = 0; c < d; ++c) {
    int r = k * d + c, s = l * d + c;
    if (b->J[r * n + i] != b->J[s * n + i] || b->J[r * n + j] != b->J[s * n + j]) return 0;
  }
  return 1;
}

// the particles with a component nonzero in both columns i and j, grouped by equal columns:
// grp[k] the group's first member (-1: k does not contribute)
static void group(const eb *b, int i, int j, int *grp) {
  int n = b->n, d = b->d;
  for (int k = 0; k < b->N; ++k) {
    grp[k] = -1;
    for (int c = 0; c < d; ++c) {
      int r = k * d + c;
      if (!zero(b, b->J[r * n + i]) && !zero(b, b->J[r * n + j])) grp[k] = k;
    }
    for (int l = 0; l < k && grp[k] >= 0; ++l)
      if (grp[l] == l && same_cols(b, k, l, i, j)) grp[k] = l;
  }
}

// the members of the group led by k into set[]; their count
static int members(const int *grp, int k, int N, int *set) {
  int ns = 0;
  for (int l = k; l < N; ++l)
    if (grp[l] == k) set[ns++] = l;
  return ns;
}

// M, Q - c and the unrolled LDL' solve. M_ij = sum_k m_k J_k,i . J_k,j and b_i = sum_k J_k,i .
// a_k, a_k = m_k (g - gamma_k), with the particles whose columns are the same nodes taken
// together (a chain's links beyond i: their masses and a's summed first)
static void emit_solve(dal_cgbuf *o, const eb *b) {
  int n = b->n, N = b->N, d = b->d;
  for (int k = 0; k < N; ++k)
    for (int c = 0; c < d; ++c)
      dal__cg_printf(o, "  const double a%d_%d = m[%d] * (g[%d] - %s);\n", k, c, k, c,
                     R(b, b->gam[k * d + c]).s);
  // nz: the entries of M (then L) not known zero
  char *nz = calloc((size_t)n * (size_t)n + 1, 1);
  int *grp = malloc(((size_t)N + 1) * sizeof *grp), *set = malloc(((size_t)N + 1) * sizeof *set);
  sums S = {0};
  if (!nz || !grp || !set) {
    o->oom = 1;
    goto done;
  }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) {
      group(b, i, j, grp);
      // the line apart: the set sums it names are emitted before it
      dal_cgbuf ln = {0};
      int terms = 0;
      for (int k = 0; k < N; ++k) {
        if (grp[k] != k) continue;
        int ns = members(grp, k, N, set);
        char mass[32];
        setsum(o, &S, set, ns, -1, mass, sizeof mass);
        dal__cg_printf(&ln, "%s%s * (", terms ? " + " : "", mass);
        for (int c = 0, any = 0; c < d; ++c) {
          int r = k * d + c, ji = b->J[r * n + i], jj = b->J[r * n + j];
          if (zero(b, ji) || zero(b, jj)) continue;
          dal__cg_printf(&ln, "%s%s * %s", any ? " + " : "", R(b, ji).s, R(b, jj).s);
          any = 1;
        }
        dal__cg_printf(&ln, ")");
        terms++;
      }
      if (terms || i == j) {
        dal__cg_printf(o, "  const double M%d_%d = %s;\n", i, j, terms ? ln.s : "0.0");
        nz[i * n + j] = 1;
      }
      if (ln.oom) o->oom = 1;
      dal__cg_free(&ln);
    }
  for (int i = 0; i < n; ++i) {
    group(b, i, i, grp);
    dal_cgbuf ln = {0};
    int terms = 0;
    for (int k = 0; k < N; ++k) {
      if (grp[k] != k) continue;
      int ns = members(grp, k, N, set);
      for (int c = 0; c < d; ++c) {
        int ji = b->J[(k * d + c) * n + i];
        if (zero(b, ji)) continue;
        char a[32];
        setsum(o, &S, set, ns, c, a, sizeof a);
        dal__cg_printf(&ln, "%s%s * %s", terms ? " + " : "", R(b, ji).s, a);
        terms++;
      }
    }
    if (!zero(b, b->dU[i])) dal__cg_printf(&ln, "%s%s", terms ? " - " : "-", R(b, b->dU[i]).s);
    dal__cg_printf(o, "  const double b%d = %s;\n", i, ln.n ? ln.s : "0.0");
    if (ln.oom) o->oom = 1;
    dal__cg_free(&ln);
  }
  // LDL': W_ip = M_ip - sum_r<p W_ir L_pr, L_ip = W_ip / D_p, D_i = M_ii - sum_p<i W_ip L_ip
  for (int i = 0; i < n; ++i) {
    for (int p = 0; p < i; ++p) {
      int any = nz[i * n + p];
      for (int r = 0; r < p && !any; ++r)
        any = nz[i * n + r] && nz[p * n + r];
      if (!any) continue;
      dal__cg_printf(o, "  const double W%d_%d = %s", i, p, nz[i * n + p] ? "" : "0.0");
      if (nz[i * n + p]) dal__cg_printf(o, "M%d_%d", i, p);
      for (int r = 0; r < p; ++r)
        if (nz[i * n + r] && nz[p * n + r]) dal__cg_printf(o, " - W%d_%d * L%d_%d", i, r, p, r);
      dal__cg_printf(o, ";\n  const double L%d_%d = W%d_%d * e%d;\n", i, p, i, p, p);
      nz[i * n + p] = 1;
    }
    dal__cg_printf(o, "  const double D%d = M%d_%d", i, i, i);
    for (int p = 0; p < i; ++p)
      if (nz[i * n + p]) dal__cg_printf(o, " - W%d_%d * L%d_%d", i, p, i, p);
    dal__cg_printf(o, ";\n  if (!(D%d > 0.0)) return 1;\n  const double e%d = 1.0 / D%d;\n", i, i,
                   i);
  }
  // L z = b, then L' x = D^-1 z
  for (int i = 0; i < n; ++i) {
    dal__cg_printf(o, "  const double z%d = b%d", i, i);
    for (int p = 0; p < i; ++p)
      if (nz[i * n + p]) dal__cg_printf(o, " - L%d_%d * z%d", i, p, p);
    dal__cg_printf(o, ";\n");
  }
  for (int i = n - 1; i >= 0; --i) {
    dal__cg_printf(o, "  const double y%d = z%d * e%d", i, i, i);
    for (int p = i + 1; p < n; ++p)
      if (nz[p * n + i]) dal__cg_printf(o, " - L%d_%d * y%d", p, i, p);
    dal__cg_printf(o, ";\n");
  }
  dal__cg_printf(o, "  double s = 0.0;\n");
  for (int i = 0; i < n; ++i)
    dal__cg_printf(o, "  qdd[%d] = y%d;\n  s += y%d;\n", i, i, i);
  dal__cg_printf(o, "  return !isfinite(s);\n}\n");
done:
  for (int i = 0; i < S.n; ++i)
    free(S.key[i]);
  free(S.key);
  free(nz);
  free(grp);
  free(set);
}

static void emit(dal_cgbuf *o, eb *b, const char *fname) {
  int nn = b->tr.n, nd = b->N * b->d, n = b->n;
  char *need = calloc((size_t)nn + 1, 1);
  if (!need) {
    o->oom = 1;
    return;
  }
  // the nodes the solve reads, and theirs (children precede parents in the pool)
  for (int r = 0; r < nd; ++r) {
    need[b->gam[r]] = 1;
    for (int j = 0; j < n; ++j)
      need[b->J[r * n + j]] = 1;
  }
  for (int j = 0; j < n; ++j)
    need[b->dU[j]] = 1;
  for (int i = nn - 1; i >= 0; --i)
    if (need[i]) {
      int op[2], k = operands(b, i, op);
      for (int z = 0; z < k; ++z)
        need[op[z]] = 1;
    }
  dal__cg_printf(o,
                 "// Generated by dalembert (codegen/eom.c): the equations of motion of a "
                 "system of %d coordinates\n#include <math.h>\n"
                 "int %s(double t, const double *q, const double *qd, const double *P,\n"
                 "    const double *const *X, const double *m, const double *g, double *qdd);\n"
                 "int %s(double t, const double *q, const double *qd, const double *P,\n"
                 "    const double *const *X, const double *m, const double *g, double *qdd) {\n"
                 "  (void)t; (void)q; (void)qd; (void)P; (void)X;\n",
                 n, fname, fname);
  for (int i = 0; i < nn; ++i)
    if (need[i] && nd_(b, i)->op != X_NUM) emit_node(o, b, i);
  free(need);
  emit_solve(o, b);
}

int dal__eom_source(const dal_system *sys, dal_cgbuf *o, const char *fname, char *msg,
                    size_t msglen) {
  char why[200];
  const char *no = unsupported(sys, why, sizeof why);
  if (no)
    return say(msg, msglen, DAL_E_UNSUPPORTED,
               "equations of motion not compiled: %s; the general path runs", no);
  eb b;
  memset(&b, 0, sizeof b);
  b.sys = sys;
  b.n = sys->n;
  b.N = sys->N;
  b.d = sys->dim;
  int rc = dal__xtree_init(&b.tr);
  if (rc) return rc;
  dal__alg_init(&b.g, &b.tr);
  size_t nd = (size_t)b.N * (size_t)b.d;
  b.pos = malloc((nd + 1) * sizeof *b.pos);
  b.J = malloc((nd * (size_t)b.n + 1) * sizeof *b.J);
  b.gam = malloc((nd + 1) * sizeof *b.gam);
  b.dU = malloc(((size_t)b.n + 1) * sizeof *b.dU);
  b.have = calloc((size_t)b.N + 1, sizeof *b.have);
  if (!b.pos || !b.J || !b.gam || !b.dU || !b.have) {
    rc = DAL_E_NOMEM;
  } else if (derive(&b)) {
    rc = b.g.too_large         ? say(msg, msglen, DAL_E_TOO_LARGE,
                                     "equations of motion not compiled: their closed form is too large "
                                             "(more than 2^19 nodes or 2^21 operations of the algebra); the "
                                             "general path runs")
         : b.g.fail && !b.tr.n ? DAL_E_NOMEM
                               : say(msg, msglen, DAL_E_UNSUPPORTED,
                                     "equations of motion not compiled: a formula is outside "
                                     "the symbolic layer's reach; the general path runs");
  } else {
    emit(o, &b, fname);
    rc = o->oom ? DAL_E_NOMEM : DAL_OK;
  }
  free(b.pos);
  free(b.J);
  free(b.gam);
  free(b.dU);
  free(b.have);
  free(b.pot);
  dal__alg_free(&b.g);
  dal__xtree_free(&b.tr);
  return rc;
}

void dal__eom_free(struct dal_eom *e) {
  if (!e) return;
  if (e->handle) dlclose(e->handle);
  free(e->x);
  free(e);
}

int dal__eom_qddot(const dal_system *sys, const dal_state *st, double t, const double *q,
                   const double *qd, double *qdd) {
  static const double g0[3] = {0.0, 0.0, 0.0};
  const struct dal_eom *e = sys->eom;
  return e->fn(t, q, qd, st->prm.ppool, e->x, st->prm.mass, st->prm.has_gravity ? st->prm.g : g0,
               qdd);
}

int dal__eom_attach(dal_system *sys, void *handle, void *fn) {
  struct dal_eom *e = calloc(1, sizeof *e);
  int np = sys->npotq + sys->npotr;
  if (e) e->x = calloc((size_t)np + 1, sizeof *e->x);
  if (!e || !e->x) {
    free(e);
    return DAL_E_NOMEM;
  }
  // the potentials' parameters in the order the derivation numbered them
  for (int i = 0; i < np; ++i) {
    const dal_expr *x = i < sys->npotq ? sys->potq[i].ctx : sys->potr[i - sys->npotq].ctx;
    e->x[i] = x->values;
  }
  e->handle = handle;
  memcpy(&e->fn, &fn, sizeof fn);
  dal__eom_free(sys->eom);
  sys->eom = e;
  return DAL_OK;
}

int dal_codegen_attach_eom(dal_system *sys, const dal_codegen_opts *o, char *msg, size_t msglen) {
  if (msg && msglen) msg[0] = 0;
  dal_codegen_opts def = dal_codegen_default_opts();
  if (!o) o = &def;
  if (!sys || o->cookie != DAL_CODEGEN_COOKIE)
    return say(msg, msglen, DAL_E_ARG,
               "dal_codegen_attach_eom: no system, or opts not from dal_codegen_default_opts()");
  dal_cgbuf src = {0};
  void *hd = NULL, *fn = NULL;
  int rc = dal__eom_source(sys, &src, "dal_eom_run", msg, msglen);
  if (!rc) rc = dal__cg_load(&src, o, "dal_eom_run", &hd, &fn, msg, msglen);
  dal__cg_free(&src);
  if (!rc) rc = dal__eom_attach(sys, hd, fn);
  if (rc && hd) dlclose(hd);
  return rc;
}

int dal_codegen_eom_attached(const dal_system *sys) { return sys && sys->eom ? 1 : 0; }
