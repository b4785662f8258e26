// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Compiled expressions: creation from a def, evaluation, and the primitive and callback faces.
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "expr.h"

#define EXPR_COOKIE 0x0e7a2d25

static void face(dal_expr *e);

// the program of e: its native code when attached, else the bytecode
static inline void xrun(const dal_expr *e, const dal_jet *in, const dal_jet *in2, int split,
                        dal_jet t, const double *param, dal_jet *out) {
  if (e->native)
    e->native(in, in2, split, t, param, out);
  else
    dal__xrun(&e->prog, in, in2, split, t, param, out, NULL);
}

dal_expr_def dal_default_expr_def(void) {
  dal_expr_def d;
  memset(&d, 0, sizeof d);
  d.name = "expr";
  d.cookie = EXPR_COOKIE;
  return d;
}

static int say(char *msg, size_t len, int rc, const char *fmt, const char *a, const char *b) {
  if (msg && len) snprintf(msg, len, fmt, a, b);
  return rc;
}

static char *dup(const char *s) {
  size_t n = strlen(s) + 1;
  char *r = malloc(n);
  if (r) memcpy(r, s, n);
  return r;
}

static int ident(const char *s) {
  if (!s || !(isalpha((unsigned char)*s) || *s == '_')) return 0;
  size_t n = 0;
  for (; s[n]; ++n)
    if (!(isalnum((unsigned char)s[n]) || s[n] == '_')) return 0;
  return n < 60;
}

// the primitive's eval: ctx is the expression
static int prim_eval(const dal_jet *in, dal_jet t, const double *param, dal_jet *out, void *ctx) {
  const dal_expr *e = ctx;
  if (!e) return -1; // placed without its ctx: dal_expr_place_def sets it
  xrun(e, in, NULL, e->tree.nin, t, param, out);
  return 0;
}

static int cmp_name(const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

// the symbol table: inputs, their velocities, parameters; every name an identifier, once
static int names(dal_expr *e, const dal_expr_def *d, char *msg, size_t len) {
  int nin = d->nin * (d->velocities ? 2 : 1), nn = nin + d->nparam;
  e->tree.names = calloc((size_t)nn + 1, sizeof *e->tree.names);
  if (!e->tree.names) return DAL_E_NOMEM;
  for (int i = 0; i < nn; ++i) {
    const char *s = i < d->nin ? d->inputs[i]
                    : i < nin  ? d->inputs[i - d->nin]
                               : d->params[i - nin];
    if (!ident(s))
      return say(msg, len, DAL_E_ARG,
                 "%s: symbol '%s' is not a name (a letter or '_', then letters, digits, '_'; "
                 "at most 59)",
                 e->name, s ? s : "(null)");
    char buf[64];
    snprintf(buf, sizeof buf, "%s%s", s, i >= d->nin && i < nin ? "dot" : "");
    if (!strcmp(buf, "t"))
      return say(msg, len, DAL_E_ARG, "%s: symbol '%s' is the time; choose another name", e->name,
                 buf);
    e->tree.names[i] = dup(buf);
    if (!e->tree.names[i]) return DAL_E_NOMEM;
    e->tree.nin = i < nin ? i + 1 : nin;
    e->tree.nparam = i < nin ? 0 : i - nin + 1;
  }
  // a name given twice: neighbours in sorted order (n log n: scenes of 10^5 parameters)
  char **by = malloc(((size_t)nn + 1) * sizeof *by);
  if (!by) return DAL_E_NOMEM;
  memcpy(by, e->tree.names, (size_t)nn * sizeof *by);
  qsort(by, (size_t)nn, sizeof *by, cmp_name);
  for (int i = 1; i < nn; ++i)
    if (!strcmp(by[i - 1], by[i])) {
      int rc = say(msg, len, DAL_E_ARG, "%s: symbol '%s' is given twice", e->name, by[i]);
      free(by);
      return rc;
    }
  free(by);
  return DAL_OK;
}

// the end of both constructors: with rc = DAL_OK compile the roots and hand e out; on a
// failure (rc, or the compiler's) name it and destroy e
static int finish(dal_expr *e, int rc, const char *name, char *msg, size_t len, dal_expr **out) {
  if (!rc) {
    char m[300];
    rc = dal__xcompile(&e->tree, e->roots, e->nout, &e->prog, m, sizeof m);
    if (rc) say(msg, len, rc, "%s: %s", name, m);
  }
  if (!rc) {
    face(e);
    *out = e;
    return DAL_OK;
  }
  if (rc == DAL_E_NOMEM) say(msg, len, rc, "%s: out of memory%s", name, "");
  dal_expr_destroy(e);
  return rc;
}

int dal_expr_create(const dal_expr_def *d, dal_expr **out, char *msg, size_t len) {
  if (msg && len) msg[0] = 0;
  if (!out) return say(msg, len, DAL_E_ARG, "dal_expr_create: out is NULL%s%s", "", "");
  *out = NULL;
  if (!d || d->cookie != EXPR_COOKIE)
    return say(msg, len, DAL_E_ARG,
               "dal_expr_create: the def is NULL or not from dal_default_expr_def()%s%s", "", "");
  const char *name = d->name ? d->name : "expr";
  if (d->nout < 1 || !d->formulas || d->nin < 0 || (d->nin && !d->inputs) || d->nparam < 0 ||
      (d->nparam && !d->params) || d->nin > 100000 || d->nparam > 100000 || d->nout > 100000)
    return say(msg, len, DAL_E_ARG,
               "%s: counts and arrays do not match (nout >= 1 formulas; nin inputs, nparam "
               "parameters, each array given when its count is > 0)%s",
               name, "");
  for (int i = 0; i < d->nparam && d->values; ++i)
    if (!isfinite(d->values[i]))
      return say(msg, len, DAL_E_NONFINITE, "%s: the value of parameter '%s' is not finite", name,
                 d->params[i] ? d->params[i] : "(null)");
  dal_expr *e = calloc(1, sizeof *e);
  if (!e) return DAL_E_NOMEM;
  int rc = DAL_E_NOMEM;
  e->name = dup(name);
  e->nout = d->nout;
  e->nin_named = d->nin;
  e->velocities = d->velocities ? 1 : 0;
  e->roots = calloc((size_t)d->nout, sizeof *e->roots);
  e->formulas = calloc((size_t)d->nout, sizeof *e->formulas);
  e->values = calloc((size_t)d->nparam + 1, sizeof *e->values);
  if (!e->name || !e->roots || !e->formulas || !e->values || dal__xtree_init(&e->tree)) goto fail;
  rc = names(e, d, msg, len);
  if (rc) goto fail;
  for (int i = 0; i < d->nparam; ++i)
    e->values[i] = d->values ? d->values[i] : 0.0;
  // parse each formula, then compile them together (shared subexpressions once)
  for (int k = 0; k < d->nout; ++k) {
    if (!d->formulas[k]) {
      char num[16];
      snprintf(num, sizeof num, "%d", k + 1);
      rc = say(msg, len, DAL_E_ARG, "%s: formula %s is NULL", name, num);
      goto fail;
    }
    if (strlen(d->formulas[k]) > DAL_EXPR_MAX_LEN) {
      char num[16];
      snprintf(num, sizeof num, "%d", k + 1);
      rc = say(msg, len, DAL_E_ARG, "%s: formula %s is longer than 65536 characters", name, num);
      goto fail;
    }
    e->formulas[k] = dup(d->formulas[k]);
    if (!e->formulas[k]) {
      rc = DAL_E_NOMEM;
      goto fail;
    }
    char m[400];
    rc = dal__xparse(&e->tree, d->formulas[k], k, NULL, &e->roots[k], m, sizeof m);
    if (rc) {
      say(msg, len, rc, "%s: %s", name, m);
      goto fail;
    }
  }
  return finish(e, DAL_OK, name, msg, len, out);
fail:
  return finish(e, rc, name, msg, len, out);
}

// DAL_PRIM_TRANSLATES when output k = input k + f(the other inputs) for every output: the
// derivative of output k along input j < nout is exactly 1 (j = k) or 0, found symbolically
static unsigned translates(const dal_expr *e) {
  if (e->tree.nin <= e->nout || e->tree.n > 4000) return 0;
  dal_xtree s;
  if (dal__xtree_init(&s)) return 0;
  s.nin = e->tree.nin;
  s.nparam = e->tree.nparam;
  dal_alg g;
  dal__alg_init(&g, &s);
  int ok = 1;
  for (int k = 0; k < e->nout && ok; ++k) {
    int r = dal__ximport(&s, &e->tree, e->roots[k]);
    for (int j = 0; j < e->nout && ok; ++j)
      ok = dal__alg_isnum(&g, dal__alg_diff(&g, r, j), j == k ? 1.0 : 0.0);
  }
  dal__alg_free(&g);
  dal__xtree_free(&s);
  return ok ? DAL_PRIM_TRANSLATES : 0u;
}

// 1 when e is dal_map_hanging's formula: outputs (x + P sin(q), y - P cos(q)) over the inputs
// (x, y, q) with P its only parameter and no t, found symbolically (the difference of each
// output from that form is canonically 0)
int dal__expr_hanging(const dal_expr *e) {
  if (!e || e->nout != 2 || e->tree.nin != 3 || e->tree.nparam != 1 || e->velocities ||
      !(e->prim.flags & DAL_PRIM_TRANSLATES) || e->tree.n > 4000)
    return 0;
  dal_xtree s;
  if (dal__xtree_init(&s)) return 0;
  s.nin = 3;
  s.nparam = 1;
  dal_alg g;
  dal__alg_init(&g, &s);
  int q = dal__xnode(&s, X_IN, -1, -1, 2, 0.0), P = dal__xnode(&s, X_PAR, -1, -1, 0, 0.0);
  int ok = q >= 0 && P >= 0;
  for (int k = 0; k < 2 && ok; ++k) {
    int r = dal__ximport(&s, &e->tree, e->roots[k]), x = dal__xnode(&s, X_IN, -1, -1, k, 0.0);
    int f = dal__xnode(&s, k ? X_COS : X_SIN, q, -1, 0, 0.0);
    int off = f >= 0 ? dal__xnode(&s, X_MUL, P, f, 0, 0.0) : -1;
    int want = off >= 0 && x >= 0 ? dal__xnode(&s, k ? X_SUB : X_ADD, x, off, 0, 0.0) : -1;
    int diff = want >= 0 && r >= 0 ? dal__xnode(&s, X_SUB, r, want, 0, 0.0) : -1;
    ok = diff >= 0 && dal__alg_isnum(&g, dal__alg_simplify(&g, diff), 0.0);
  }
  dal__alg_free(&g);
  dal__xtree_free(&s);
  return ok;
}

// the primitive face
static void face(dal_expr *e) {
  e->prim.name = e->name;
  e->prim.version = DAL_PRIMITIVE_VERSION;
  e->prim.nin = e->tree.nin;
  e->prim.nout = e->nout;
  e->prim.nparam = e->tree.nparam;
  e->prim.eval = prim_eval;
  e->prim.doc = "an expression (dalembert/expr.h)";
  e->prim.flags = translates(e);
  e->prim.param_names = e->tree.nparam ? (const char *const *)(e->tree.names + e->tree.nin) : NULL;
  e->prim.param_defaults = e->values;
}

int dal__expr_from_tree(const char *name, const dal_xtree *tr, const int *roots, int nout,
                        int nin_named, int velocities, const double *values, dal_expr **out,
                        char *msg, size_t len) {
  *out = NULL;
  dal_expr *e = calloc(1, sizeof *e);
  if (!e) return DAL_E_NOMEM;
  int rc = DAL_E_NOMEM, nn = tr->nin + tr->nparam;
  e->name = dup(name);
  e->nout = nout;
  e->nin_named = nin_named;
  e->velocities = velocities;
  e->roots = calloc((size_t)nout, sizeof *e->roots);
  e->formulas = calloc((size_t)nout, sizeof *e->formulas);
  e->values = calloc((size_t)tr->nparam + 1, sizeof *e->values);
  if (!e->name || !e->roots || !e->formulas || !e->values || dal__xtree_init(&e->tree)) goto fail;
  e->tree.names = calloc((size_t)nn + 1, sizeof *e->tree.names);
  if (!e->tree.names) goto fail;
  for (int i = 0; i < nn; ++i) {
    e->tree.names[i] = dup(tr->names[i]);
    if (!e->tree.names[i]) goto fail;
  }
  e->tree.nin = tr->nin;
  e->tree.nparam = tr->nparam;
  for (int i = 0; i < tr->nparam; ++i)
    e->values[i] = values ? values[i] : 0.0;
  for (int k = 0; k < nout; ++k) {
    e->roots[k] = dal__ximport(&e->tree, tr, roots[k]);
    if (e->roots[k] < 0) goto fail;
  }
  // derived formulas have no source text (dal_expr_print shows them): nodes forget theirs
  for (int i = 0; i < e->tree.n; ++i) {
    e->tree.node[i].src = -1;
    e->tree.node[i].col = 0;
  }
  for (int k = 0; k < nout; ++k) {
    e->formulas[k] = dup("(derived)");
    if (!e->formulas[k]) goto fail;
  }
  return finish(e, DAL_OK, name, msg, len, out);
fail:
  return finish(e, rc, name, msg, len, out);
}

void dal_expr_destroy(dal_expr *e) {
  if (!e) return;
  if (e->native_release) e->native_release(e->native_ctx);
  dal__xtree_free(&e->tree);
  dal__xprog_free(&e->prog);
  if (e->formulas)
    for (int k = 0; k < e->nout; ++k)
      free(e->formulas[k]);
  free(e->formulas);
  free(e->roots);
  free(e->values);
  free(e->name);
  free(e);
}

int dal_expr_nout(const dal_expr *e) { return e ? e->nout : 0; }
int dal_expr_nin(const dal_expr *e) { return e ? e->tree.nin : 0; }
int dal_expr_nparam(const dal_expr *e) { return e ? e->tree.nparam : 0; }
const double *dal_expr_values(const dal_expr *e) { return e ? e->values : NULL; }
int dal_expr_ninstructions(const dal_expr *e) { return e ? e->prog.nscalar + e->prog.njet : 0; }

int dal_expr_depends(const dal_expr *e, int i) {
  if (!e || i < -1 || i >= e->tree.nin) return 0;
  for (int k = 0; k < e->prog.nscalar + e->prog.njet; ++k) {
    const dal_xins *x = &e->prog.ins[k];
    if (k >= e->prog.nscalar &&
        ((i < 0 && x->op == X_TIME) || (i >= 0 && x->op == X_IN && x->a == i)))
      return 1;
  }
  return 0;
}

const char *dal_expr_symbol(const dal_expr *e, int i) {
  if (!e || i < 0 || i >= e->tree.nin + e->tree.nparam) return NULL;
  return e->tree.names[i];
}

int dal_expr_eval(const dal_expr *e, const dal_jet *in, dal_jet t, const double *param,
                  dal_jet *out) {
  if (!e || !out || (!in && e->tree.nin)) return DAL_E_ARG;
  xrun(e, in, NULL, e->tree.nin, t, param ? param : e->values, out);
  return DAL_OK;
}

int dal_expr_check(const dal_expr *e, const dal_jet *in, dal_jet t, const double *param,
                   dal_jet *out, char *msg, size_t msglen) {
  if (msg && msglen) msg[0] = 0;
  if (!e || !out || (!in && e->tree.nin)) return DAL_E_ARG;
  int bad;
  dal__xrun(&e->prog, in, NULL, e->tree.nin, t, param ? param : e->values, out, &bad);
  if (bad < 0) return DAL_OK;
  const dal_xnode *x = &e->tree.node[e->prog.ins[bad].node];
  if (msg && msglen) {
    if (x->src >= 0)
      snprintf(msg, msglen, "%s: formula %d '%.60s', column %d: '%s' is not finite there", e->name,
               x->src + 1, e->formulas[x->src], x->col, dal__xop_name(x->op));
    else
      snprintf(msg, msglen, "%s: '%s' is not finite there", e->name, dal__xop_name(x->op));
  }
  return DAL_E_DOMAIN;
}

const dal_primitive *dal_expr_primitive(const dal_expr *e) { return e ? &e->prim : NULL; }

int dal_expr_place_def(const dal_expr *e, dal_place_def *def) {
  if (!e || !def || e->tree.nparam > DAL_MAX_PARAM) return DAL_E_ARG;
  def->prim = &e->prim;
  def->ctx = (void *)e;
  return DAL_OK;
}

int dal_expr_constraint_def(const dal_expr *e, dal_constraint_def *def) {
  if (!e || !def || e->tree.nparam > DAL_MAX_PARAM) return DAL_E_ARG;
  def->prim = &e->prim;
  def->ctx = (void *)e;
  if (!def->name) def->name = e->name;
  return DAL_OK;
}

int dal_expr_map(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx) {
  const dal_expr *e = ctx;
  if (!e) return -1;
  xrun(e, q, NULL, e->tree.nin, t, e->values, r);
  return 0;
}

int dal_expr_potential_r(const dal_jet *r, dal_jet t, dal_jet *U, void *ctx) {
  return dal_expr_map(r, t, U, ctx);
}

int dal_expr_potential_q(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  return dal_expr_map(q, t, U, ctx);
}

int dal_expr_lagrangian(dal_jet t, const dal_jet *q, const dal_jet *qdot, dal_jet *L, void *ctx) {
  const dal_expr *e = ctx;
  if (!e || !e->velocities) return -1;
  xrun(e, q, qdot, e->nin_named, t, e->values, L);
  return 0;
}

int dal__expr_lagrange_parts_eval(dal_jet t, const dal_jet *q, const dal_jet *qdot, dal_jet *out,
                                  void *ctx) {
  const dal_expr *e = ctx;
  xrun(e, q, qdot, e->nin_named, t, e->values, out);
  return 0;
}

int dal_expr_path(dal_jet t, dal_jet *x, void *ctx) { return dal_expr_map(NULL, t, x, ctx); }

int dal_expr_time(dal_jet t, dal_jet *f, void *ctx) { return dal_expr_map(NULL, t, f, ctx); }

double dal_expr_event(double t, const double *q, const double *qdot, void *ctx) {
  const dal_expr *e = ctx;
  if (!e || !e->velocities) return NAN;
  int n = e->nin_named;
  if (n > DAL_EXPR_EVENT_MAXN) return NAN;
  dal_jet in[2 * DAL_EXPR_EVENT_MAXN], g;
  for (int i = 0; i < n; ++i) {
    in[i] = dal_const(q[i]);
    in[n + i] = dal_const(qdot[i]);
  }
  xrun(e, in, NULL, 2 * n, dal_const(t), e->values, &g);
  return g.v;
}
