// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Symbolic algebra on expression trees: a canonical form, expansion, derivatives, factoring.
//
// Canonical form (every node built by the c_* constructors below):
//   a sum is a left-nested chain ADD(ADD(t1, t2), t3) of terms sorted by node index, like terms
//   collected (c x + d x = (c + d) x), at most one constant term, and c X sin(u)^2 + c X
//   cos(u)^2 merged into c X;
//   a term or product is MUL(coefficient, rest) or rest, rest a chain of factors sorted by
//   node index, equal bases merged by adding exponents (x^a x^b = x^(a + b));
//   a power POW(base, exponent) has an exponent other than 0 and 1, and integer powers are
//   distributed over products ((a b)^n = a^n b^n, (a^m)^n = a^(m n));
//   no SUB, DIV, NEG or SQRT (a - b = a + (-1) b, a / b = a b^-1, sqrt(a) = a^(1/2));
//   numbers are folded in double arithmetic.
// Since nodes are hash-consed, two canonical forms are equal exactly when their node indices
// are; sorting by index is what makes them unique (the printer sorts again for people).
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "symbolic.h"

#define MAX_TERMS 64 // expansion gives up beyond this many terms (the product stays)

typedef struct ivec {
  int *v;
  int n, cap;
} ivec;

static int spend(dal_alg *g, long n);

static int push(dal_alg *g, ivec *a, int x) {
  if (x < 0 || spend(g, 1)) {
    g->fail = 1;
    return -1;
  }
  if (a->n == a->cap) {
    int cap = a->cap ? 2 * a->cap : 16;
    int *v = realloc(a->v, (size_t)cap * sizeof *v);
    if (!v) {
      g->fail = 1;
      return -1;
    }
    a->v = v;
    a->cap = cap;
  }
  a->v[a->n++] = x;
  return 0;
}

static const dal_xnode *N(const dal_alg *g, int i) { return &g->tr->node[i]; }

// count n units of work; past the session's bounds every later call fails (too large)
static int spend(dal_alg *g, long n) {
  g->work += n;
  if (g->work > DAL_ALG_MAX_WORK || g->tr->n > DAL_ALG_MAX_NODES) {
    g->fail = 1;
    g->too_large = 1;
  }
  return g->fail;
}

static int num(dal_alg *g, double c) {
  if (spend(g, 1)) return -1;
  int r = dal__xnum(g->tr, c);
  if (r < 0) g->fail = 1;
  return r;
}

static int node(dal_alg *g, int op, int a, int b) {
  if (a < -1 || b < -1 || spend(g, 1)) {
    g->fail = 1;
    return -1;
  }
  int r = dal__xnode(g->tr, op, a, b, 0, 0.0);
  if (r < 0) g->fail = 1;
  return r;
}

int dal__alg_isnum(const dal_alg *g, int x, double c) {
  return x >= 0 && N(g, x)->op == X_NUM && N(g, x)->c == c;
}

static int cmp_int(const void *a, const void *b) {
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

// ---------------------------------------------------------------------------------------------
// flattening

void dal__alg_terms(const dal_alg *g, int x, int **out, int *n) {
  // a canonical sum chain: ADD(ADD(t1, t2), t3); walk down the left spine
  int k = 0, y = x;
  while (N(g, y)->op == X_ADD) {
    k++;
    y = N(g, y)->a;
  }
  *n = k + 1;
  *out = malloc((size_t)(k + 1) * sizeof **out);
  if (!*out) {
    *n = 0;
    return;
  }
  y = x;
  for (int i = k; i > 0; --i) {
    (*out)[i] = N(g, y)->b;
    y = N(g, y)->a;
  }
  (*out)[0] = y;
}

// split a canonical term into coefficient and rest (-1: the term is a number)
static double split(const dal_alg *g, int x, int *rest) {
  const dal_xnode *n = N(g, x);
  if (n->op == X_NUM) {
    *rest = -1;
    return n->c;
  }
  if (n->op == X_MUL && N(g, n->a)->op == X_NUM) {
    *rest = n->b;
    return N(g, n->a)->c;
  }
  *rest = x;
  return 1.0;
}

// the factors of a coefficient-free product chain
static void factors(dal_alg *g, int x, ivec *out) {
  if (N(g, x)->op == X_MUL) {
    factors(g, N(g, x)->a, out);
    push(g, out, N(g, x)->b);
  } else {
    push(g, out, x);
  }
}

static void base_exp(dal_alg *g, int f, int *base, int *ex) {
  if (N(g, f)->op == X_POW) {
    *base = N(g, f)->a;
    *ex = N(g, f)->b;
  } else {
    *base = f;
    *ex = num(g, 1.0);
  }
}

// ---------------------------------------------------------------------------------------------
// constructors of canonical forms

static int chain(dal_alg *g, int op, const int *v, int n) {
  int r = v[0];
  for (int i = 1; i < n; ++i)
    r = node(g, op, r, v[i]);
  return r;
}

static int term(dal_alg *g, double c, int rest) {
  if (rest < 0 || c == 0.0) return num(g, c);
  if (c == 1.0) return rest;
  return node(g, X_MUL, num(g, c), rest);
}

int dal__alg_mul(dal_alg *g, const int *f, int n);
int dal__alg_pow(dal_alg *g, int b, int e);

static int trig_merge(dal_alg *g, double *coef, int *rest, int n);

int dal__alg_add(dal_alg *g, const int *t, int n) {
  if (g->fail) return -1;
  ivec all = {0};
  for (int i = 0; i < n; ++i) {
    if (t[i] < 0) {
      g->fail = 1;
      break;
    }
    int *ts, nt;
    dal__alg_terms(g, t[i], &ts, &nt);
    for (int j = 0; j < nt; ++j)
      push(g, &all, ts[j]);
    free(ts);
  }
  double *coef = malloc(((size_t)all.n + 1) * sizeof *coef);
  int *rest = malloc(((size_t)all.n + 1) * sizeof *rest);
  int r = -1;
  if (!coef || !rest || g->fail) {
    g->fail = 1;
    goto done;
  }
  for (int i = 0; i < all.n; ++i)
    coef[i] = split(g, all.v[i], &rest[i]);
  int m = all.n;
  if (spend(g, (long)m * m)) goto done;
  // collect like terms (quadratic in the number of terms, sums are short); then the
  // sin^2 + cos^2 pairs, which may make new like terms
  for (int pass = 0; pass < 8; ++pass) {
    for (int i = 0; i < m; ++i)
      for (int j = i + 1; j < m; ++j)
        if (rest[j] == rest[i]) {
          coef[i] += coef[j];
          coef[j] = coef[m - 1];
          rest[j] = rest[m - 1];
          m--;
          j--;
        }
    if (!trig_merge(g, coef, rest, m)) break;
  }
  ivec out = {0};
  for (int i = 0; i < m; ++i)
    if (coef[i] != 0.0) push(g, &out, term(g, coef[i], rest[i]));
  if (!out.n) {
    r = num(g, 0.0);
  } else {
    qsort(out.v, (size_t)out.n, sizeof *out.v, cmp_int);
    r = chain(g, X_ADD, out.v, out.n);
  }
  free(out.v);
done:
  free(all.v);
  free(coef);
  free(rest);
  return g->fail ? -1 : r;
}

// c X sin(u)^p + c X sin(u)^(p-2) cos(u)^2 -> c X sin(u)^(p-2); returns 1 if one was merged
static int trig_merge(dal_alg *g, double *coef, int *rest, int m) {
  if (spend(g, m)) return 0;
  for (int i = 0; i < m; ++i) {
    if (rest[i] < 0 || coef[i] == 0.0) continue;
    ivec f = {0};
    factors(g, rest[i], &f);
    for (int k = 0; k < f.n; ++k) {
      int b, e;
      base_exp(g, f.v[k], &b, &e);
      if (g->fail || N(g, b)->op != X_SIN || N(g, e)->op != X_NUM || N(g, e)->c < 2.0) continue;
      int cs = node(g, X_COS, N(g, b)->a, -1);
      int two = num(g, 2.0), mtwo = num(g, -2.0);
      int pr[3] = {rest[i], dal__alg_pow(g, b, mtwo), dal__alg_pow(g, cs, two)};
      int want = dal__alg_mul(g, pr, 3);
      for (int j = 0; j < m; ++j)
        if (j != i && rest[j] == want && coef[j] == coef[i]) {
          int nr = dal__alg_mul(g, pr, 2);
          double c;
          int rr;
          c = split(g, nr, &rr); // nr may be a number (X = 1)
          coef[i] *= c;
          rest[i] = rr;
          coef[j] = 0.0;
          free(f.v);
          return 1;
        }
    }
    free(f.v);
  }
  return 0;
}

// merge equal bases of m factors base^ex (exponents add); returns the number left
static int merge_bases(dal_alg *g, int *base, int *ex, int m) {
  for (int i = 0; i < m; ++i)
    for (int j = i + 1; j < m; ++j)
      if (base[j] == base[i]) {
        int pair[2] = {ex[i], ex[j]};
        ex[i] = dal__alg_add(g, pair, 2);
        base[j] = base[m - 1];
        ex[j] = ex[m - 1];
        m--;
        j--;
      }
  return m;
}

// 1 when two neighbours of the sorted factors have the same base
static int repeats_base(dal_alg *g, const ivec *out) {
  int again = 0;
  for (int i = 0; i + 1 < out->n; ++i) {
    int b1, e1, b2, e2;
    base_exp(g, out->v[i], &b1, &e1);
    base_exp(g, out->v[i + 1], &b2, &e2);
    if (b1 == b2) again = 1;
  }
  return again;
}

int dal__alg_mul(dal_alg *g, const int *f, int n) {
  if (g->fail) return -1;
  double c = 1.0;
  ivec fs = {0};
  for (int i = 0; i < n; ++i) {
    if (f[i] < 0) {
      g->fail = 1;
      break;
    }
    int rest;
    c *= split(g, f[i], &rest);
    if (rest >= 0) factors(g, rest, &fs);
  }
  int r = -1;
  int *base = malloc(((size_t)fs.n + 1) * sizeof *base),
      *ex = malloc(((size_t)fs.n + 1) * sizeof *ex);
  ivec out = {0};
  if (!base || !ex || g->fail) {
    g->fail = 1;
    goto done;
  }
  if (c == 0.0) {
    r = num(g, 0.0);
    goto done;
  }
  if (spend(g, (long)fs.n * fs.n)) goto done;
  for (int i = 0; i < fs.n; ++i)
    base_exp(g, fs.v[i], &base[i], &ex[i]);
  int m = merge_bases(g, base, ex, fs.n);
  for (int i = 0; i < m; ++i) {
    int p = dal__alg_pow(g, base[i], ex[i]);
    if (p < 0) break;
    int rest;
    double pc = split(g, p, &rest);
    c *= pc;
    if (rest >= 0) {
      // a power that came apart (integer power of a product) gives several factors
      ivec sub = {0};
      factors(g, rest, &sub);
      for (int k = 0; k < sub.n; ++k)
        push(g, &out, sub.v[k]);
      free(sub.v);
    }
  }
  if (g->fail) goto done;
  if (c == 0.0) {
    r = num(g, 0.0);
    goto done;
  }
  // factors that came apart may repeat a base: merge again when so
  if (out.n > 1) qsort(out.v, (size_t)out.n, sizeof *out.v, cmp_int);
  int again = repeats_base(g, &out);
  if (again && out.n < n + fs.n + 64) {
    int cnum = num(g, c);
    push(g, &out, cnum);
    // one more round is enough: the merged powers no longer come apart
    int *copy = malloc((size_t)out.n * sizeof *copy);
    if (!copy) {
      g->fail = 1;
      goto done;
    }
    memcpy(copy, out.v, (size_t)out.n * sizeof *copy);
    int nn = out.n;
    free(out.v);
    out.v = NULL;
    out.n = out.cap = 0;
    r = dal__alg_mul(g, copy, nn);
    free(copy);
    goto done;
  }
  r = out.n ? term(g, c, chain(g, X_MUL, out.v, out.n)) : num(g, c);
done:
  free(fs.v);
  free(out.v);
  free(base);
  free(ex);
  return g->fail ? -1 : r;
}

static int is_int(const dal_alg *g, int x) {
  return N(g, x)->op == X_NUM && N(g, x)->c == floor(N(g, x)->c) && fabs(N(g, x)->c) <= 1e6;
}

int dal__alg_pow(dal_alg *g, int b, int e) {
  if (b < 0 || e < 0 || g->fail) {
    g->fail = 1;
    return -1;
  }
  if (dal__alg_isnum(g, e, 0.0)) return num(g, 1.0);
  if (dal__alg_isnum(g, e, 1.0)) return b;
  const dal_xnode *B = N(g, b), *E = N(g, e);
  if (B->op == X_NUM && E->op == X_NUM) {
    double v = pow(B->c, E->c);
    if (isfinite(v) && (B->c > 0.0 || is_int(g, e))) return num(g, v);
  }
  if (dal__alg_isnum(g, b, 1.0)) return num(g, 1.0);
  if (B->op == X_POW && is_int(g, e)) {
    int pr[2] = {B->b, e};
    return dal__alg_pow(g, B->a, dal__alg_mul(g, pr, 2));
  }
  if (B->op == X_MUL && is_int(g, e)) {
    int rest;
    double c = split(g, b, &rest);
    ivec f = {0};
    if (rest >= 0) factors(g, rest, &f);
    ivec p = {0};
    push(g, &p, num(g, pow(c, E->c)));
    for (int i = 0; i < f.n; ++i)
      push(g, &p, dal__alg_pow(g, f.v[i], e));
    int r = g->fail ? -1 : dal__alg_mul(g, p.v, p.n);
    free(f.v);
    free(p.v);
    return r;
  }
  return node(g, X_POW, b, e);
}

// a term with a negative coefficient: the term negated, else -1
static int negated(dal_alg *g, int x) {
  int rest;
  double c = split(g, x, &rest);
  if (c >= 0.0) return -1;
  return term(g, -c, rest < 0 ? -1 : rest);
}

int dal__alg_fn(dal_alg *g, int op, int a) {
  if (a < 0 || g->fail) {
    g->fail = 1;
    return -1;
  }
  // exact values at 0 and 1
  if (dal__alg_isnum(g, a, 0.0)) {
    switch (op) {
    case X_SIN:
    case X_TAN:
    case X_ASIN:
    case X_ATAN:
    case X_SINH:
    case X_TANH:
      return num(g, 0.0);
    case X_COS:
    case X_COSH:
    case X_EXP:
      return num(g, 1.0);
    default:
      break;
    }
  }
  if (op == X_LOG && dal__alg_isnum(g, a, 1.0)) return num(g, 0.0);
  if (op == X_SQRT) return dal__alg_pow(g, a, num(g, 0.5));
  if (op == X_LOG && N(g, a)->op == X_EXP) return N(g, a)->a;
  // parity: f(-u) = -f(u) for odd f, f(-u) = f(u) for even f
  int na = N(g, a)->op == X_MUL ? negated(g, a) : -1;
  if (na >= 0) {
    int odd =
        op == X_SIN || op == X_TAN || op == X_ASIN || op == X_ATAN || op == X_SINH || op == X_TANH;
    int even = op == X_COS || op == X_COSH;
    if (odd) {
      int f[2] = {num(g, -1.0), node(g, op, na, -1)};
      return dal__alg_mul(g, f, 2);
    }
    if (even) return node(g, op, na, -1);
  }
  return node(g, op, a, -1);
}

// ---------------------------------------------------------------------------------------------
// memo tables indexed by node, grown as the tree grows

static int *memo_get(dal_alg *g, int **m, int *cap, int x) {
  if (x >= *cap) {
    int nc = g->tr->n > x ? g->tr->n + 64 : x + 64;
    int *v = realloc(*m, (size_t)nc * sizeof *v);
    if (!v) {
      g->fail = 1;
      return NULL;
    }
    for (int i = *cap; i < nc; ++i)
      v[i] = -1;
    *m = v;
    *cap = nc;
  }
  return &(*m)[x];
}

// the memo of x in table m: its value (>= 0); -1 on a failure (x failed, the session failed, no
// memory); -2 when x has none yet
static int memo_find(dal_alg *g, int **m, int *cap, int x) {
  if (x < 0 || g->fail) return -1;
  int *slot = memo_get(g, m, cap, x);
  return !slot ? -1 : *slot >= 0 ? *slot : -2;
}

// remember r as the memo of x (the table may have grown since memo_find); 0 on a failure
static int memo_put(dal_alg *g, int **m, int *cap, int x, int r) {
  if (g->fail) return 0;
  int *slot = memo_get(g, m, cap, x);
  if (!slot) return 0;
  *slot = r;
  return 1;
}

int dal__alg_canon(dal_alg *g, int x) {
  int memo = memo_find(g, &g->canon, &g->ncanon, x);
  if (memo != -2) return memo;
  const dal_xnode n = *N(g, x);
  int a = n.a >= 0 ? dal__alg_canon(g, n.a) : -1;
  int b = n.b >= 0 ? dal__alg_canon(g, n.b) : -1;
  int r;
  switch (n.op) {
  case X_NUM:
  case X_IN:
  case X_PAR:
  case X_TIME:
    r = x;
    break;
  case X_ADD: {
    int t[2] = {a, b};
    r = dal__alg_add(g, t, 2);
    break;
  }
  case X_SUB: {
    int nb[2] = {num(g, -1.0), b};
    int t[2] = {a, dal__alg_mul(g, nb, 2)};
    r = dal__alg_add(g, t, 2);
    break;
  }
  case X_MUL: {
    int f[2] = {a, b};
    r = dal__alg_mul(g, f, 2);
    break;
  }
  case X_DIV: {
    int f[2] = {a, dal__alg_pow(g, b, num(g, -1.0))};
    r = dal__alg_mul(g, f, 2);
    break;
  }
  case X_NEG: {
    int f[2] = {num(g, -1.0), a};
    r = dal__alg_mul(g, f, 2);
    break;
  }
  case X_POW:
    r = dal__alg_pow(g, a, b);
    break;
  case X_ATAN2:
  case X_HYPOT:
    r = node(g, n.op, a, b);
    break;
  default:
    r = dal__alg_fn(g, n.op, a);
  }
  if (!memo_put(g, &g->canon, &g->ncanon, x, r)) return -1;
  int *self = memo_get(g, &g->canon, &g->ncanon, r);
  if (self && *self < 0) *self = r; // a canonical node is its own canonical form
  return r;
}

// ---------------------------------------------------------------------------------------------
// expansion: products of sums and small integer powers of sums multiplied out

static int distribute(dal_alg *g, const int *f, int n) {
  ivec acc = {0}, nxt = {0};
  push(g, &acc, num(g, 1.0));
  for (int i = 0; i < n && !g->fail; ++i) {
    int *ts, nt;
    if (N(g, f[i])->op == X_ADD) {
      dal__alg_terms(g, f[i], &ts, &nt);
    } else {
      nt = 1;
      ts = malloc(sizeof *ts);
      if (ts) ts[0] = f[i];
    }
    if (!ts) {
      g->fail = 1;
      break;
    }
    if ((long)acc.n * nt > MAX_TERMS) {
      // too many terms: keep this factor unexpanded
      for (int k = 0; k < acc.n; ++k) {
        int pr[2] = {acc.v[k], f[i]};
        acc.v[k] = dal__alg_mul(g, pr, 2);
      }
      free(ts);
      continue;
    }
    nxt.n = 0;
    for (int k = 0; k < acc.n; ++k)
      for (int j = 0; j < nt; ++j) {
        int pr[2] = {acc.v[k], ts[j]};
        push(g, &nxt, dal__alg_mul(g, pr, 2));
      }
    free(ts);
    ivec tmp = acc;
    acc = nxt;
    nxt = tmp;
  }
  int r = g->fail ? -1 : dal__alg_add(g, acc.v, acc.n);
  free(acc.v);
  free(nxt.v);
  return r;
}

int dal__alg_expand(dal_alg *g, int x) {
  int memo = memo_find(g, &g->expand, &g->nexpand, x);
  if (memo != -2) return memo;
  const dal_xnode n = *N(g, x);
  int r;
  switch (n.op) {
  case X_NUM:
  case X_IN:
  case X_PAR:
  case X_TIME:
    r = x;
    break;
  case X_ADD: {
    int *ts, nt;
    dal__alg_terms(g, x, &ts, &nt);
    if (!ts) {
      g->fail = 1;
      return -1;
    }
    for (int i = 0; i < nt; ++i)
      ts[i] = dal__alg_expand(g, ts[i]);
    r = g->fail ? -1 : dal__alg_add(g, ts, nt);
    free(ts);
    break;
  }
  case X_MUL: {
    int pair[2] = {dal__alg_expand(g, n.a), dal__alg_expand(g, n.b)};
    r = g->fail ? -1 : distribute(g, pair, 2);
    break;
  }
  case X_POW: {
    int b = dal__alg_expand(g, n.a), e = dal__alg_expand(g, n.b);
    if (!g->fail && N(g, b)->op == X_ADD && is_int(g, e) && N(g, e)->c >= 2 && N(g, e)->c <= 8) {
      int k = (int)N(g, e)->c, f[8];
      for (int i = 0; i < k; ++i)
        f[i] = b;
      r = distribute(g, f, k);
    } else {
      r = dal__alg_pow(g, b, e);
    }
    break;
  }
  case X_ATAN2:
  case X_HYPOT:
    r = node(g, n.op, dal__alg_expand(g, n.a), dal__alg_expand(g, n.b));
    break;
  default:
    r = dal__alg_fn(g, n.op, dal__alg_expand(g, n.a));
  }
  return memo_put(g, &g->expand, &g->nexpand, x, r) ? r : -1;
}

int dal__alg_simplify(dal_alg *g, int x) { return dal__alg_expand(g, dal__alg_canon(g, x)); }

// ---------------------------------------------------------------------------------------------
// derivatives of canonical forms, along input `var` (or t when var < 0)

static int deriv(dal_alg *g, int x, int var);

static int prod(dal_alg *g, int a, int b) {
  int f[2] = {a, b};
  return dal__alg_mul(g, f, 2);
}
static int prod3(dal_alg *g, int a, int b, int c) {
  int f[3] = {a, b, c};
  return dal__alg_mul(g, f, 3);
}
static int sum(dal_alg *g, int a, int b) {
  int t[2] = {a, b};
  return dal__alg_add(g, t, 2);
}
static int powk(dal_alg *g, int a, double k) { return dal__alg_pow(g, a, num(g, k)); }

// f'(u) of a one-argument function f (node x = f(u)); -1 for one that is not canonical
static int outer(dal_alg *g, int op, int u, int x) {
  switch (op) {
  case X_SIN:
    return dal__alg_fn(g, X_COS, u);
  case X_COS:
    return prod(g, num(g, -1.0), dal__alg_fn(g, X_SIN, u));
  case X_TAN:
    return powk(g, dal__alg_fn(g, X_COS, u), -2);
  case X_ASIN:
    return powk(g, sum(g, num(g, 1.0), prod(g, num(g, -1.0), powk(g, u, 2))), -0.5);
  case X_ACOS:
    return prod(g, num(g, -1.0),
                powk(g, sum(g, num(g, 1.0), prod(g, num(g, -1.0), powk(g, u, 2))), -0.5));
  case X_ATAN:
    return powk(g, sum(g, num(g, 1.0), powk(g, u, 2)), -1);
  case X_SINH:
    return dal__alg_fn(g, X_COSH, u);
  case X_COSH:
    return dal__alg_fn(g, X_SINH, u);
  case X_TANH:
    return powk(g, dal__alg_fn(g, X_COSH, u), -2);
  case X_EXP:
    return x;
  case X_LOG:
    return powk(g, u, -1);
  default:
    g->fail = 1;
    return -1; // SQRT, SUB, DIV, NEG are not canonical
  }
}

static int deriv_node(dal_alg *g, int x, int var) {
  const dal_xnode n = *N(g, x);
  switch (n.op) {
  case X_NUM:
  case X_PAR:
    return num(g, 0.0);
  case X_IN:
    return num(g, var >= 0 && n.idx == var ? 1.0 : 0.0);
  case X_TIME:
    return num(g, var < 0 ? 1.0 : 0.0);
  case X_ADD:
    return sum(g, deriv(g, n.a, var), deriv(g, n.b, var));
  case X_MUL:
    return sum(g, prod(g, deriv(g, n.a, var), n.b), prod(g, n.a, deriv(g, n.b, var)));
  case X_POW: {
    int db = deriv(g, n.a, var), de = deriv(g, n.b, var);
    if (g->fail) return -1;
    // e b^(e-1) b' + b^e log(b) e'
    int r = prod3(g, n.b, dal__alg_pow(g, n.a, sum(g, n.b, num(g, -1.0))), db);
    if (!dal__alg_isnum(g, de, 0.0)) r = sum(g, r, prod3(g, x, dal__alg_fn(g, X_LOG, n.a), de));
    return r;
  }
  case X_ATAN2: {
    // (x y' - y x') / (x^2 + y^2) for atan2(y, x)
    int y = n.a, xx = n.b, dy = deriv(g, y, var), dx = deriv(g, xx, var);
    int num_ = sum(g, prod(g, xx, dy), prod3(g, num(g, -1.0), y, dx));
    return prod(g, num_, powk(g, sum(g, powk(g, xx, 2), powk(g, y, 2)), -1));
  }
  case X_HYPOT: {
    int a = n.a, b = n.b, da = deriv(g, a, var), db = deriv(g, b, var);
    return prod(g, sum(g, prod(g, a, da), prod(g, b, db)), powk(g, x, -1));
  }
  default:
    break;
  }
  // one-argument functions: f'(u) u'
  int u = n.a, du = deriv(g, u, var);
  if (g->fail) return -1;
  if (dal__alg_isnum(g, du, 0.0)) return du;
  int f1 = outer(g, n.op, u, x);
  return prod(g, f1, du);
}

static int deriv(dal_alg *g, int x, int var) {
  int memo = memo_find(g, &g->deriv, &g->nderiv, x);
  if (memo != -2) return memo;
  int r = deriv_node(g, x, var);
  return memo_put(g, &g->deriv, &g->nderiv, x, r) ? r : -1;
}

int dal__alg_diff(dal_alg *g, int x, int var) {
  x = dal__alg_canon(g, x);
  if (x < 0) return -1;
  if (g->deriv_var != var) {
    // a new variable: forget the derivatives taken along the last one
    for (int i = 0; i < g->nderiv; ++i)
      g->deriv[i] = -1;
    g->deriv_var = var;
  }
  return dal__alg_expand(g, deriv(g, x, var));
}

// ---------------------------------------------------------------------------------------------
// factoring for display: common factors of a sum's terms taken out (powers of one base with
// exponents of one sign, the smallest in size; the integer coefficients' gcd; a common sign)

static long gcdl(long a, long b) {
  while (b) {
    long t = a % b;
    a = b;
    b = t;
  }
  return a < 0 ? -a : a;
}

// the coefficient that comes out of a sum of nt terms: with rational coefficients p_i/q over
// one denominator q <= 64 their gcd(p_i)/q, negative when every coefficient is; else 1 or -1
static double common_coef(dal_alg *g, const int *ts, int nt) {
  long gc = 0, q = 0;
  int allneg = 1, allint = 1;
  for (long qq = 1; qq <= 64 && !q; ++qq) {
    int ok = 1;
    for (int i = 0; i < nt && ok; ++i) {
      int rr;
      double c = split(g, ts[i], &rr) * (double)qq;
      ok = c == floor(c) && fabs(c) <= 1e9;
    }
    if (ok) q = qq;
  }
  for (int i = 0; i < nt; ++i) {
    int rr;
    double c = split(g, ts[i], &rr);
    if (c >= 0) allneg = 0;
    if (!q)
      allint = 0;
    else
      gc = gcdl(gc, (long)(c * (double)q));
  }
  double cf = allint && gc > 0 && gc != q ? (double)gc / (double)q : 1.0;
  return allneg ? -cf : cf;
}

// 1 when base b appears with a numeric exponent of the sign of *emin in terms 1 .. nt-1 too;
// *emin becomes the exponent of smallest magnitude
static int everywhere(dal_alg *g, const int *ts, int nt, int b, double *emin) {
  double sg = *emin > 0 ? 1.0 : -1.0;
  for (int i = 1; i < nt; ++i) {
    int rr;
    split(g, ts[i], &rr);
    ivec fi = {0};
    if (rr >= 0) factors(g, rr, &fi);
    int found = 0;
    for (int j = 0; j < fi.n; ++j) {
      int bj, ej;
      base_exp(g, fi.v[j], &bj, &ej);
      if (bj == b && N(g, ej)->op == X_NUM && N(g, ej)->c * sg > 0) {
        found = 1;
        if (N(g, ej)->c * sg < *emin * sg) *emin = N(g, ej)->c;
      }
    }
    free(fi.v);
    if (!found) return 0;
  }
  return 1;
}

int dal__alg_factor(dal_alg *g, int x) {
  if (x < 0 || g->fail) return -1;
  const dal_xnode n = *N(g, x);
  switch (n.op) {
  case X_NUM:
  case X_IN:
  case X_PAR:
  case X_TIME:
    return x;
  case X_MUL:
    return prod(g, dal__alg_factor(g, n.a), dal__alg_factor(g, n.b));
  case X_POW:
    return dal__alg_pow(g, dal__alg_factor(g, n.a), n.b);
  case X_ATAN2:
  case X_HYPOT:
    return node(g, n.op, dal__alg_factor(g, n.a), dal__alg_factor(g, n.b));
  case X_ADD:
    break;
  default:
    return dal__alg_fn(g, n.op, dal__alg_factor(g, n.a));
  }
  int *ts, nt;
  dal__alg_terms(g, x, &ts, &nt);
  if (!ts) {
    g->fail = 1;
    return -1;
  }
  for (int i = 0; i < nt; ++i)
    ts[i] = dal__alg_factor(g, ts[i]);
  if (g->fail) { // a term failed (memory, or past the session's bounds)
    free(ts);
    return -1;
  }
  // common bases with positive numeric exponents (the smallest), and the coefficients' gcd
  ivec common = {0}, f0 = {0};
  int rest0;
  double c0 = split(g, ts[0], &rest0);
  if (rest0 >= 0) factors(g, rest0, &f0);
  double cf = common_coef(g, ts, nt);
  (void)c0;
  for (int k = 0; k < f0.n && !g->fail; ++k) {
    int b, e;
    base_exp(g, f0.v[k], &b, &e);
    if (N(g, e)->op != X_NUM || N(g, e)->c == 0) continue;
    double emin = N(g, e)->c;
    if (everywhere(g, ts, nt, b, &emin)) push(g, &common, powk(g, b, emin));
  }
  int r;
  if (!common.n && cf == 1.0) {
    r = g->fail ? -1 : dal__alg_add(g, ts, nt);
  } else {
    int cm = common.n ? dal__alg_mul(g, common.v, common.n) : num(g, 1.0);
    int inv = prod(g, num(g, 1.0 / cf), powk(g, cm, -1));
    for (int i = 0; i < nt; ++i)
      ts[i] = prod(g, ts[i], inv);
    int inner = dal__alg_add(g, ts, nt);
    // the product keeps the sum whole: build it without distributing
    r = prod3(g, num(g, cf), cm, inner);
  }
  free(ts);
  free(common.v);
  free(f0.v);
  return g->fail ? -1 : r;
}

void dal__alg_init(dal_alg *g, dal_xtree *tr) {
  memset(g, 0, sizeof *g);
  g->tr = tr;
  g->deriv_var = -2;
}

void dal__alg_free(dal_alg *g) {
  free(g->canon);
  free(g->expand);
  free(g->deriv);
  memset(g, 0, sizeof *g);
}
