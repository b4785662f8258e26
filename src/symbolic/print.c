// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Printing canonical expressions for people: plain text, LaTeX, and SICM's prefix notation.
//
// Sums are printed with their terms in alphabetical order of their factors (constant last),
// products with their numeric coefficient first, then the factors in alphabetical order, and
// negative powers as a denominator; numbers are exact rationals p/q (q <= 64) when they are,
// else the shortest decimal that reads back to the same double.
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "symbolic.h"

enum { F_TEXT = DAL_XFMT_TEXT, F_LATEX = DAL_XFMT_LATEX, F_SCHEME = DAL_XFMT_SCHEME };

typedef struct sb {
  char *s;
  size_t n, cap;
  int fail; // 1: out of memory, 2: too large
} sb;

// bounds of one print (DAL_E_TOO_LARGE beyond): the text, and the bytes of every sort key made
// or copied on the way (keys of keys of a deep tree shared many times over)
#define MAX_TEXT (1u << 18)
#define MAX_KEY_BYTES (1u << 22)

static void put(sb *b, const char *fmt, ...) {
  if (b->fail) return;
  if (b->n > MAX_TEXT) {
    b->fail = 2;
    return;
  }
  va_list ap;
  va_start(ap, fmt);
  char tmp[256];
  int k = vsnprintf(tmp, sizeof tmp, fmt, ap);
  va_end(ap);
  if (k < 0) {
    b->fail = 1;
    return;
  }
  const char *src = tmp;
  char *big = NULL;
  if ((size_t)k >= sizeof tmp) {
    big = malloc((size_t)k + 1);
    if (!big) {
      b->fail = 1;
      return;
    }
    va_start(ap, fmt);
    vsnprintf(big, (size_t)k + 1, fmt, ap);
    va_end(ap);
    src = big;
  }
  if (b->n + (size_t)k + 1 > b->cap) {
    size_t cap = b->cap ? b->cap : 256;
    while (cap < b->n + (size_t)k + 1)
      cap *= 2;
    char *s = realloc(b->s, cap);
    if (!s) {
      b->fail = 1;
      free(big);
      return;
    }
    b->s = s;
    b->cap = cap;
  }
  memcpy(b->s + b->n, src, (size_t)k + 1);
  b->n += (size_t)k;
  free(big);
}

typedef struct pr {
  const dal_xtree *tr;
  int fmt;
  char **cache;  // text of each node once printed (sort keys), shared by nested printers
  size_t *spent; // bytes of sort keys made or copied so far (MAX_KEY_BYTES)
} pr;

static const dal_xnode *N(const pr *p, int x) { return &p->tr->node[x]; }

// a number: integer, exact rational p/q with q <= 64, or the shortest round-trip decimal
static void number(sb *b, double c, int fmt) {
  if (c == floor(c) && fabs(c) < 1e15) {
    put(b, "%.0f", c);
    return;
  }
  for (int q = 2; q <= 64; ++q) {
    double pq = c * q;
    if (pq == floor(pq) && fabs(pq) < 1e15 && pq / q == c) {
      if (fmt == F_LATEX)
        put(b, "%s\\frac{%.0f}{%d}", pq < 0 ? "-" : "", fabs(pq), q);
      else
        put(b, "%.0f/%d", pq, q);
      return;
    }
  }
  for (int prec = 15; prec <= 17; ++prec) {
    char tmp[40];
    snprintf(tmp, sizeof tmp, "%.*g", prec, c);
    if (strtod(tmp, NULL) == c || prec == 17) {
      char *e = strchr(tmp, 'e');
      if (e && fmt == F_LATEX)
        put(b, "%.*s \\cdot 10^{%d}", (int)(e - tmp), tmp, atoi(e + 1));
      else
        put(b, "%s", tmp);
      return;
    }
  }
}

static const char *const greek[] = {"alpha", "beta",  "gamma", "delta",  "epsilon", "zeta",   "eta",
                                    "theta", "iota",  "kappa", "lambda", "mu",      "nu",     "xi",
                                    "pi",    "rho",   "sigma", "tau",    "upsilon", "phi",    "chi",
                                    "psi",   "omega", "Gamma", "Delta",  "Theta",   "Lambda", "Xi",
                                    "Pi",    "Sigma", "Phi",   "Psi",    "Omega"};

// a name in LaTeX: trailing "dot"s as accents, trailing digits as a subscript, Greek letters
static void latex_name(sb *b, const char *name) {
  char base[64];
  snprintf(base, sizeof base, "%s", name);
  int dots = 0;
  size_t n = strlen(base);
  while (n > 3 && !strcmp(base + n - 3, "dot") && dots < 2) {
    base[n - 3] = 0;
    n -= 3;
    dots++;
  }
  size_t k = n;
  while (k > 1 && base[k - 1] >= '0' && base[k - 1] <= '9')
    k--;
  char sub[64] = "";
  if (k < n) {
    snprintf(sub, sizeof sub, "%s", base + k);
    base[k] = 0;
  }
  if (dots) put(b, dots == 1 ? "\\dot{" : "\\ddot{");
  int gr = 0;
  for (size_t i = 0; i < sizeof greek / sizeof greek[0]; ++i)
    if (!strcmp(base, greek[i])) gr = 1;
  if (gr)
    put(b, "\\%s", base);
  else if (strlen(base) == 1)
    put(b, "%s", base);
  else {
    put(b, "\\mathrm{");
    for (const char *c = base; *c; ++c)
      put(b, *c == '_' ? "\\_" : "%c", *c);
    put(b, "}");
  }
  if (dots) put(b, "}");
  if (sub[0]) put(b, "_{%s}", sub);
}

static void expr(const pr *p, sb *b, int x, int prec);

// the factors of a product, split into coefficient, numerator and denominator (bases with
// their positive exponents), each in display order
typedef struct fact {
  int base;
  double e; // numeric exponent (positive), or NaN: symbolic exponent, node `ex`
  int ex;
  char *key;
} fact;

// the text of node x (a sort key), computed once per node: without the cache, keys of keys
// would make printing exponential in the nesting depth
static char *text_of(const pr *p, int x) {
  if (*p->spent > MAX_KEY_BYTES) return NULL;
  if (p->cache && p->cache[x]) {
    size_t n = strlen(p->cache[x]) + 1;
    *p->spent += n;
    char *r = malloc(n);
    if (r) memcpy(r, p->cache[x], n);
    return r;
  }
  sb b = {0};
  pr q = {p->tr, F_TEXT, p->cache, p->spent};
  expr(&q, &b, x, 0);
  *p->spent += b.n;
  if (b.fail) {
    if (b.fail == 2) *p->spent = (size_t)MAX_KEY_BYTES + 1;
    free(b.s);
    return NULL;
  }
  char *r = b.s ? b.s : calloc(1, 1);
  if (r && p->cache) {
    size_t n = strlen(r) + 1;
    p->cache[x] = malloc(n);
    if (p->cache[x]) memcpy(p->cache[x], r, n);
  }
  return r;
}

static int fact_cmp(const void *a, const void *b) {
  const fact *x = a, *y = b;
  int c = strcmp(x->key ? x->key : "", y->key ? y->key : "");
  if (c) return c;
  return (x->e > y->e) - (x->e < y->e);
}

static void flatten_mul(const pr *p, int x, double *coef, fact **nf, int *nn, fact **df, int *nd) {
  *coef = 1.0;
  int cap = 8;
  fact *num = malloc((size_t)cap * sizeof *num), *den = malloc((size_t)cap * sizeof *den);
  *nn = *nd = 0;
  int stack[512], sp = 0;
  stack[sp++] = x;
  while (sp && num && den) {
    int y = stack[--sp];
    const dal_xnode *n = N(p, y);
    if (n->op == X_MUL && sp < 510) {
      stack[sp++] = n->b;
      stack[sp++] = n->a;
      continue;
    }
    if (n->op == X_NUM) {
      *coef *= n->c;
      continue;
    }
    fact f = {y, 1.0, -1, NULL};
    if (n->op == X_POW) {
      f.base = n->a;
      if (N(p, n->b)->op == X_NUM)
        f.e = N(p, n->b)->c;
      else {
        f.e = NAN;
        f.ex = n->b;
      }
    }
    int isden = f.e < 0;
    if (isden) f.e = -f.e;
    // display order: symbols and numbers, then functions, then sums (rank letter first)
    const dal_xnode *bn = N(p, f.base);
    char rank = bn->op <= X_TIME ? 'a' : dal__xop_unary_fn(bn->op) ? 'b' : 'c';
    char *tx = text_of(p, f.base);
    f.key = tx ? malloc(strlen(tx) + 2) : NULL;
    if (f.key) {
      f.key[0] = rank;
      strcpy(f.key + 1, tx);
    }
    free(tx);
    if ((isden ? *nd : *nn) == cap) {
      cap *= 2;
      fact *a = realloc(num, (size_t)cap * sizeof *a), *c = realloc(den, (size_t)cap * sizeof *c);
      if (a) num = a;
      if (c) den = c;
      if (!a || !c) break;
    }
    if (isden)
      den[(*nd)++] = f;
    else
      num[(*nn)++] = f;
  }
  qsort(num, (size_t)*nn, sizeof *num, fact_cmp);
  qsort(den, (size_t)*nd, sizeof *den, fact_cmp);
  *nf = num;
  *df = den;
}

static void free_facts(fact *f, int n) {
  for (int i = 0; i < n; ++i)
    free(f[i].key);
  free(f);
}

// the exponent of a factor in the prefix and LaTeX forms: its number, or its expression
static void exponent(const pr *p, sb *b, const fact *f, int fmt) {
  if (f->e == f->e)
    number(b, f->e, fmt);
  else
    expr(p, b, f->ex, 0);
}

// base^e for one factor (e > 0 or symbolic)
static void power(const pr *p, sb *b, const fact *f) {
  int base = f->base;
  const dal_xnode *bn = N(p, base);
  int atom = bn->op == X_IN || bn->op == X_PAR || bn->op == X_TIME ||
             (bn->op == X_NUM && bn->c >= 0 && bn->c == floor(bn->c));
  if (f->e == 1.0) {
    expr(p, b, base, 3);
    return;
  }
  if (f->e == 0.5) {
    put(b, p->fmt == F_LATEX ? "\\sqrt{" : p->fmt == F_SCHEME ? "(sqrt " : "sqrt(");
    expr(p, b, base, 0);
    put(b, p->fmt == F_LATEX ? "}" : ")");
    return;
  }
  if (p->fmt == F_SCHEME) {
    put(b, "(expt ");
    expr(p, b, base, 0);
    put(b, " ");
    exponent(p, b, f, F_SCHEME);
    put(b, ")");
    return;
  }
  if (p->fmt == F_LATEX) {
    int fn = dal__xop_unary_fn(bn->op) && bn->op != X_SQRT;
    if (fn && f->e == f->e && f->e == floor(f->e)) {
      // sin^{2}(u)
      static const char *const lf[] = {"\\sin",    "\\cos",    "\\tan",  "\\arcsin",
                                       "\\arccos", "\\arctan", "\\sinh", "\\cosh",
                                       "\\tanh",   "\\exp",    "\\log"};
      put(b, "%s^{%.0f}\\left(", lf[bn->op - X_SIN], f->e);
      expr(p, b, bn->a, 0);
      put(b, "\\right)");
      return;
    }
    if (atom)
      expr(p, b, base, 4);
    else {
      put(b, "\\left(");
      expr(p, b, base, 0);
      put(b, "\\right)");
    }
    put(b, "^{");
    exponent(p, b, f, F_LATEX);
    put(b, "}");
    return;
  }
  expr(p, b, base, atom || dal__xop_unary_fn(bn->op) ? 4 : 5);
  put(b, "^");
  if (f->e == f->e) {
    if (f->e == floor(f->e))
      number(b, f->e, F_TEXT);
    else {
      put(b, "(");
      number(b, f->e, F_TEXT);
      put(b, ")");
    }
  } else {
    expr(p, b, f->ex, 4);
  }
}

static void factors_out(const pr *p, sb *b, const fact *f, int n) {
  const char *sep = p->fmt == F_TEXT ? "*" : " ";
  if (p->fmt == F_SCHEME && n > 1) put(b, "(* ");
  for (int i = 0; i < n; ++i) {
    if (i) put(b, "%s", sep);
    power(p, b, &f[i]);
  }
  if (p->fmt == F_SCHEME && n > 1) put(b, ")");
}

static void product(const pr *p, sb *b, int x, int prec) {
  double c;
  fact *nf, *df;
  int nn, nd;
  flatten_mul(p, x, &c, &nf, &nn, &df, &nd);
  if (!nf || !df) {
    b->fail = 1;
    free(nf);
    free(df);
    return;
  }
  if (p->fmt == F_SCHEME) {
    if (nd) put(b, "(/ ");
    int nitems = nn + (c != 1.0);
    if (nitems > 1) put(b, "(* ");
    if (c != 1.0) {
      number(b, c, F_SCHEME);
      if (nn) put(b, " ");
    }
    if (!nn && c == 1.0) put(b, "1");
    for (int i = 0; i < nn; ++i) {
      if (i) put(b, " ");
      power(p, b, &nf[i]);
    }
    if (nitems > 1) put(b, ")");
    if (nd) {
      put(b, " ");
      factors_out(p, b, df, nd);
      put(b, ")");
    }
  } else {
    int neg = c < 0;
    double ac = fabs(c);
    int paren = prec > 2 || (neg && prec > 1);
    if (paren) put(b, p->fmt == F_LATEX ? "\\left(" : "(");
    if (neg) put(b, "-");
    if (p->fmt == F_LATEX && nd) {
      put(b, "\\frac{");
      if (ac != 1.0 || !nn) number(b, ac, F_TEXT);
      if (ac != 1.0 && nn) put(b, " ");
      factors_out(p, b, nf, nn);
      put(b, "}{");
      factors_out(p, b, df, nd);
      put(b, "}");
    } else {
      if (ac != 1.0 || !nn) {
        number(b, ac, p->fmt);
        if (nn) put(b, p->fmt == F_TEXT ? "*" : " ");
      }
      factors_out(p, b, nf, nn);
      if (nd) {
        put(b, "/");
        if (nd > 1 || (df[0].e != 1.0 && df[0].e != 0.5)) put(b, "(");
        factors_out(p, b, df, nd);
        if (nd > 1 || (df[0].e != 1.0 && df[0].e != 0.5)) put(b, ")");
      }
    }
    if (paren) put(b, p->fmt == F_LATEX ? "\\right)" : ")");
  }
  free_facts(nf, nn);
  free_facts(df, nd);
}

// the sort key of a term: its text without the coefficient; constants last
typedef struct tkey {
  int x;
  char *key;
} tkey;

static int tkey_cmp(const void *a, const void *b) {
  const tkey *x = a, *y = b;
  return strcmp(x->key ? x->key : "", y->key ? y->key : "");
}

static void sum(const pr *p, sb *b, int x, int prec) {
  int n = 0;
  for (int y = x; N(p, y)->op == X_ADD; y = N(p, y)->a)
    n++;
  n++;
  tkey *t = calloc((size_t)n, sizeof *t);
  if (!t) {
    b->fail = 1;
    return;
  }
  int y = x;
  for (int i = n - 1; i > 0; --i, y = N(p, y)->a)
    t[i].x = N(p, y)->b;
  t[0].x = y;
  for (int i = 0; i < n; ++i) {
    const dal_xnode *tn = N(p, t[i].x);
    int rest = tn->op == X_MUL && N(p, tn->a)->op == X_NUM ? tn->b : t[i].x;
    if (tn->op == X_NUM) {
      t[i].key = malloc(2);
      if (t[i].key) strcpy(t[i].key, "~"); // after letters
    } else {
      t[i].key = text_of(p, rest);
    }
  }
  qsort(t, (size_t)n, sizeof *t, tkey_cmp);
  if (p->fmt == F_SCHEME) {
    put(b, "(+");
    for (int i = 0; i < n; ++i) {
      put(b, " ");
      expr(p, b, t[i].x, 0);
    }
    put(b, ")");
  } else {
    if (prec > 1) put(b, p->fmt == F_LATEX ? "\\left(" : "(");
    for (int i = 0; i < n; ++i) {
      const dal_xnode *tn = N(p, t[i].x);
      double c = tn->op == X_NUM                               ? tn->c
                 : tn->op == X_MUL && N(p, tn->a)->op == X_NUM ? N(p, tn->a)->c
                                                               : 1.0;
      if (i && c < 0) {
        // a - b: print b's negation
        put(b, " - ");
        sb tmp = {0};
        expr(p, &tmp, t[i].x, 1);
        put(b, "%s", tmp.s && tmp.s[0] == '-' ? tmp.s + 1 : tmp.s ? tmp.s : "");
        if (tmp.fail) b->fail = 1;
        free(tmp.s);
      } else {
        if (i) put(b, " + ");
        expr(p, b, t[i].x, 1);
      }
    }
    if (prec > 1) put(b, p->fmt == F_LATEX ? "\\right)" : ")");
  }
  for (int i = 0; i < n; ++i)
    free(t[i].key);
  free(t);
}

// prec: 0 top or argument, 1 term of a sum, 2 factor, 3 base of a power, 4 atom required
// a number: in parentheses where a sign or a fraction would bind wrongly
static void print_number(const pr *p, sb *b, double c, int prec) {
  if (c < 0 && prec > 1 && p->fmt != F_SCHEME) {
    put(b, p->fmt == F_LATEX ? "\\left(" : "(");
    number(b, c, p->fmt);
    put(b, p->fmt == F_LATEX ? "\\right)" : ")");
  } else if (prec >= 3 && c != floor(c) && p->fmt == F_TEXT) {
    put(b, "(");
    number(b, c, p->fmt);
    put(b, ")");
  } else {
    number(b, c, p->fmt);
  }
}

// atan2(a, b), hypot(a, b)
static void two_args(const pr *p, sb *b, const dal_xnode *n) {
  if (p->fmt == F_SCHEME) {
    put(b, n->op == X_ATAN2 ? "(atan " : "(hypot ");
    expr(p, b, n->a, 0);
    put(b, " ");
    expr(p, b, n->b, 0);
    put(b, ")");
  } else {
    put(b, p->fmt == F_LATEX ? "\\operatorname{%s}\\left(" : "%s(", dal__xop_name(n->op));
    expr(p, b, n->a, 0);
    put(b, ", ");
    expr(p, b, n->b, 0);
    put(b, p->fmt == F_LATEX ? "\\right)" : ")");
  }
}

// a - b, a/b, -a: not canonical (printing a parsed tree as it is)
static void difference(const pr *p, sb *b, const dal_xnode *n, int prec) {
  int lp = n->op == X_SUB ? 1 : 2;
  if (p->fmt == F_SCHEME) {
    put(b, n->op == X_DIV ? "(/ " : "(- ");
    expr(p, b, n->a, 0);
    if (n->op != X_NEG) {
      put(b, " ");
      expr(p, b, n->b, 0);
    }
    put(b, ")");
    return;
  }
  if (prec > lp) put(b, "(");
  if (n->op == X_NEG) {
    put(b, "-");
    expr(p, b, n->a, 3);
  } else {
    expr(p, b, n->a, lp);
    put(b, n->op == X_SUB ? " - " : "/");
    expr(p, b, n->b, lp + 1);
  }
  if (prec > lp) put(b, ")");
}

// one-argument functions
static void function(const pr *p, sb *b, const dal_xnode *n) {
  if (p->fmt == F_SCHEME) {
    put(b, "(%s ", dal__xop_name(n->op));
    expr(p, b, n->a, 0);
    put(b, ")");
  } else if (p->fmt == F_LATEX) {
    static const char *const lf[] = {"\\sin",    "\\cos",    "\\tan",  "\\arcsin",
                                     "\\arccos", "\\arctan", "\\sinh", "\\cosh",
                                     "\\tanh",   "\\exp",    "\\log"};
    if (n->op == X_SQRT) {
      put(b, "\\sqrt{");
      expr(p, b, n->a, 0);
      put(b, "}");
    } else {
      put(b, "%s\\left(", lf[n->op - X_SIN]);
      expr(p, b, n->a, 0);
      put(b, "\\right)");
    }
  } else {
    put(b, "%s(", dal__xop_name(n->op));
    expr(p, b, n->a, 0);
    put(b, ")");
  }
}

static void expr(const pr *p, sb *b, int x, int prec) {
  if (b->fail || *p->spent > MAX_KEY_BYTES) { // over a bound: no more walking
    if (!b->fail) b->fail = 2;
    return;
  }
  const dal_xnode *n = N(p, x);
  switch (n->op) {
  case X_NUM:
    print_number(p, b, n->c, prec);
    return;
  case X_IN:
  case X_PAR: {
    const char *name = p->tr->names[n->op == X_IN ? n->idx : p->tr->nin + n->idx];
    if (p->fmt == F_LATEX)
      latex_name(b, name);
    else
      put(b, "%s", name);
    return;
  }
  case X_TIME:
    put(b, "t");
    return;
  case X_ADD:
    sum(p, b, x, prec);
    return;
  case X_MUL:
  case X_POW:
    product(p, b, x, prec);
    return;
  case X_ATAN2:
  case X_HYPOT:
    two_args(p, b, n);
    return;
  case X_SUB:
  case X_DIV:
  case X_NEG:
    difference(p, b, n, prec);
    return;
  default:
    function(p, b, n);
  }
}

int dal__xprint(const dal_xtree *tr, int x, int fmt, char *buf, size_t len) {
  sb b = {0};
  size_t spent = 0;
  pr p = {tr, fmt, calloc((size_t)tr->n + 1, sizeof(char *)), &spent};
  if (x >= 0 && p.cache) expr(&p, &b, x, 0);
  if (p.cache)
    for (int i = 0; i < tr->n; ++i)
      free(p.cache[i]);
  int nocache = !p.cache;
  free(p.cache);
  if (b.fail || x < 0 || nocache || spent > MAX_KEY_BYTES) {
    free(b.s);
    if (buf && len) buf[0] = 0;
    return b.fail == 2 || spent > MAX_KEY_BYTES ? DAL_E_TOO_LARGE : DAL_E_NOMEM;
  }
  int n = (int)b.n;
  if (buf && len) {
    size_t k = b.n < len - 1 ? b.n : len - 1;
    if (b.s) memcpy(buf, b.s, k);
    buf[k] = 0;
  }
  free(b.s);
  return n;
}
