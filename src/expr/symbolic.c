// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Equations shown: printing, derivatives, T, U and L of a particle model, Lagrange's equations.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "expr.h"

// the public formats are the printer's (dal__xprint takes them as they are)
_Static_assert((int)DAL_EXPR_TEXT == (int)DAL_XFMT_TEXT &&
                   (int)DAL_EXPR_LATEX == (int)DAL_XFMT_LATEX &&
                   (int)DAL_EXPR_SCHEME == (int)DAL_XFMT_SCHEME,
               "dal_expr_format and the printer's formats differ");

#define MODEL_COOKIE 0x0e7a3d19

// a scratch tree with the symbols of `from` (names borrowed) for algebra on a const expression
static int scratch(dal_xtree *s, const dal_xtree *from) {
  if (dal__xtree_init(s)) return DAL_E_NOMEM;
  s->nin = from->nin;
  s->nparam = from->nparam;
  s->names = from->names;
  return DAL_OK;
}

static void scratch_free(dal_xtree *s) {
  s->names = NULL;
  dal__xtree_free(s);
}

// the message of a session past its bounds
static void too_large(char *msg, size_t msglen, const char *name, const dal_alg *g) {
  if (msg && msglen)
    snprintf(msg, msglen,
             "%s: too large to show (the symbolic algebra stopped at %ld operations and %d nodes; "
             "bounds %ld and %d): simplify the formulas or show fewer coordinates",
             name, g->work, g->tr->n, (long)DAL_ALG_MAX_WORK, DAL_ALG_MAX_NODES);
}

int dal_expr_print(const dal_expr *e, int k, dal_expr_format fmt, char *buf, size_t len) {
  if (buf && len) buf[0] = 0;
  if (!e || k < 0 || k >= e->nout || (!buf && len) ||
      (fmt != DAL_EXPR_TEXT && fmt != DAL_EXPR_LATEX && fmt != DAL_EXPR_SCHEME))
    return DAL_E_ARG;
  dal_xtree s;
  if (scratch(&s, &e->tree)) return DAL_E_NOMEM;
  dal_alg g;
  dal__alg_init(&g, &s);
  int r = dal__ximport(&s, &e->tree, e->roots[k]);
  r = dal__alg_factor(&g, dal__alg_simplify(&g, r));
  int n = r >= 0        ? dal__xprint(&s, r, (int)fmt, buf, len)
          : g.too_large ? DAL_E_TOO_LARGE
                        : DAL_E_NOMEM;
  dal__alg_free(&g);
  scratch_free(&s);
  return n;
}

int dal_expr_derivative(const dal_expr *e, int k, int j, dal_expr **out, char *msg, size_t msglen) {
  if (msg && msglen) msg[0] = 0;
  if (!out) return DAL_E_ARG;
  *out = NULL;
  if (!e || k < 0 || k >= e->nout || j < -1 || j >= e->tree.nin) {
    if (msg && msglen)
      snprintf(msg, msglen, "dal_expr_derivative: no formula %d or input %d", k + 1, j);
    return DAL_E_ARG;
  }
  dal_xtree s;
  if (scratch(&s, &e->tree)) return DAL_E_NOMEM;
  dal_alg g;
  dal__alg_init(&g, &s);
  int r = dal__alg_diff(&g, dal__ximport(&s, &e->tree, e->roots[k]), j);
  char name[160];
  snprintf(name, sizeof name, "d%s/d%s", e->name, j < 0 ? "t" : e->tree.names[j]);
  if (r < 0 && g.too_large) too_large(msg, msglen, e->name, &g);
  int rc = r < 0 ? (g.too_large ? DAL_E_TOO_LARGE : DAL_E_NOMEM)
                 : dal__expr_from_tree(name, &s, &r, 1, e->nin_named, e->velocities, e->values, out,
                                       msg, msglen);
  dal__alg_free(&g);
  scratch_free(&s);
  return rc;
}

int dal__expr_lagrange_parts(const dal_expr *e, dal_expr **out, char *msg, size_t msglen) {
  *out = NULL;
  if (!e || e->nout != 1 || !e->velocities) return DAL_E_ARG;
  int n = e->nin_named, *r = malloc(2 * (size_t)n * sizeof *r);
  dal_xtree s;
  if (!r || scratch(&s, &e->tree)) {
    free(r);
    return DAL_E_NOMEM;
  }
  dal_alg g;
  dal__alg_init(&g, &s);
  int L = dal__ximport(&s, &e->tree, e->roots[0]), ok = L >= 0;
  for (int i = 0; i < n && ok; ++i) {
    r[i] = dal__alg_diff(&g, L, n + i); // dL/dqdot_i: input n + i is qdot_i
    r[n + i] = dal__alg_diff(&g, L, i);
    ok = r[i] >= 0 && r[n + i] >= 0;
  }
  char name[160];
  snprintf(name, sizeof name, "%s: dL/dqdot, dL/dq", e->name);
  int rc = !ok ? (g.too_large ? DAL_E_TOO_LARGE : DAL_E_NOMEM)
               : dal__expr_from_tree(name, &s, r, 2 * n, n, 1, e->values, out, msg, msglen);
  dal__alg_free(&g);
  scratch_free(&s);
  free(r);
  return rc;
}

dal_expr_model_def dal_default_expr_model_def(void) {
  dal_expr_model_def d;
  memset(&d, 0, sizeof d);
  d.name = "model";
  d.cookie = MODEL_COOKIE;
  return d;
}

// parse one formula of a model, labelled for messages
static int parse_one(dal_xtree *tr, const char *text, const char *label, int *root, char *msg,
                     size_t msglen, const char *name) {
  if (!text) {
    if (msg && msglen) snprintf(msg, msglen, "%s: %s is NULL", name, label);
    return DAL_E_ARG;
  }
  char m[400];
  int rc = dal__xparse(tr, text, -1, label, root, m, sizeof m);
  if (rc && msg && msglen) snprintf(msg, msglen, "%s: %s", name, m);
  return rc;
}

static int in_node(dal_xtree *tr, int i) { return dal__xnode(tr, X_IN, -1, -1, i, 0.0); }

// v = sum_j dr/dq_j qdot_j + dr/dt of position node r over n coordinates; -1: out of memory
static int velocity_of(dal_alg *g, dal_xtree *s, int r, int n) {
  int vt[64], nv = 0, *vbig = n + 1 > 64 ? malloc(((size_t)n + 1) * sizeof *vbig) : vt;
  if (!vbig) return -1;
  for (int j = 0; j < n; ++j) {
    int f[2] = {dal__alg_diff(g, r, j), in_node(s, n + j)};
    vbig[nv++] = dal__alg_mul(g, f, 2);
  }
  vbig[nv++] = dal__alg_diff(g, r, -1);
  int v = dal__alg_add(g, vbig, nv);
  if (vbig != vt) free(vbig);
  return v;
}

// particle k's terms: 1/2 m v_i^2 into T's terms, -m g_i r_i into U's
static int particle_energy(dal_alg *g, dal_xtree *s, const dal_expr_model_def *d, int k,
                           const int *grav, int *terms, int *nt, int *uterms, int *nu, char *msg,
                           size_t msglen) {
  const char *name = d->name ? d->name : "model";
  char label[64];
  int m, dim = d->dim;
  snprintf(label, sizeof label, "mass of particle %d", k + 1);
  int rc = parse_one(s, d->masses[k], label, &m, msg, msglen, name);
  if (rc) return rc;
  m = dal__alg_canon(g, m);
  for (int i = 0; i < dim; ++i) {
    int r;
    snprintf(label, sizeof label, "position %c of particle %d", "xyz"[i], k + 1);
    rc = parse_one(s, d->positions[k * dim + i], label, &r, msg, msglen, name);
    if (rc) return rc;
    r = dal__alg_canon(g, r);
    int v = velocity_of(g, s, r, d->ncoords);
    if (v < 0) return DAL_E_NOMEM;
    int half[3] = {dal__xnum(s, 0.5), m, dal__alg_pow(g, v, dal__xnum(s, 2.0))};
    terms[(*nt)++] = dal__alg_mul(g, half, 3);
    if (grav[i] >= 0) {
      int f[4] = {dal__xnum(s, -1.0), m, grav[i], r};
      uterms[(*nu)++] = dal__alg_mul(g, f, 4);
    }
  }
  return DAL_OK;
}

// a model def from dal_default_expr_model_def with counts and arrays that match
static int model_def_ok(const dal_expr_model_def *d) {
  return !(!d || d->cookie != MODEL_COOKIE || d->dim < 1 || d->dim > 3 || d->ncoords < 1 ||
           !d->coords || d->nparticles < 1 || !d->masses || !d->positions || d->nparam < 0 ||
           (d->nparam && !d->params) || d->ncoords > 10000 || d->nparticles > 10000);
}

// T = the sum of its terms, U likewise (0 without any), L = T - U, each expanded
static int sum_up(dal_alg *g, dal_xtree *s, int *terms, int nt, int *uterms, int nu, int *Tn,
                  int *Un, int *Ln) {
  *Tn = dal__alg_expand(g, dal__alg_add(g, terms, nt));
  *Un = nu ? dal__alg_expand(g, dal__alg_add(g, uterms, nu)) : dal__xnum(s, 0.0);
  int f[2] = {dal__xnum(s, -1.0), *Un};
  int l[2] = {*Tn, dal__alg_mul(g, f, 2)};
  *Ln = dal__alg_expand(g, dal__alg_add(g, l, 2));
  return g->fail || *Tn < 0 || *Un < 0 || *Ln < 0 ? DAL_E_NOMEM : DAL_OK;
}

// T, U or L of the model as an expression named "<model>.<which>"
static int energy_expr(const char *name, char which, dal_xtree *s, int root, int n,
                       const double *values, dal_expr **out, char *msg, size_t msglen) {
  char nm[160];
  snprintf(nm, sizeof nm, "%s.%c", name, which);
  return dal__expr_from_tree(nm, s, &root, 1, n, 1, values, out, msg, msglen);
}

int dal_expr_model_energies(const dal_expr_model_def *d, dal_expr **T, dal_expr **U, dal_expr **L,
                            char *msg, size_t msglen) {
  if (msg && msglen) msg[0] = 0;
  if (T) *T = NULL;
  if (U) *U = NULL;
  if (L) *L = NULL;
  const char *name = d && d->name ? d->name : "model";
  if (!model_def_ok(d)) {
    if (msg && msglen)
      snprintf(msg, msglen,
               "%s: the model def is NULL, not from dal_default_expr_model_def(), or its "
               "counts and arrays do not match (dim 1..3, ncoords >= 1, nparticles >= 1)",
               name);
    return DAL_E_ARG;
  }
  // the symbols: checked and named by an expression made of them
  dal_expr_def ed = dal_default_expr_def();
  const char *zero = "0";
  ed.name = name;
  ed.formulas = &zero;
  ed.nout = 1;
  ed.inputs = d->coords;
  ed.nin = d->ncoords;
  ed.velocities = 1;
  ed.params = d->params;
  ed.values = d->values;
  ed.nparam = d->nparam;
  dal_expr *sym;
  int rc = dal_expr_create(&ed, &sym, msg, msglen);
  if (rc) return rc;
  dal_xtree s;
  if (scratch(&s, &sym->tree)) {
    dal_expr_destroy(sym);
    return DAL_E_NOMEM;
  }
  dal_alg g;
  dal__alg_init(&g, &s);
  int n = d->ncoords, dim = d->dim, Tn = -1, Un = -1, Ln = -1;
  int *terms = malloc(((size_t)d->nparticles * (size_t)dim * 2 + 2) * sizeof *terms);
  int *uterms = malloc(((size_t)d->nparticles * (size_t)dim + 2) * sizeof *uterms);
  int nt = 0, nu = 0;
  rc = terms && uterms ? DAL_OK : DAL_E_NOMEM;
  // gravity components
  int grav[3] = {-1, -1, -1};
  for (int i = 0; i < dim && d->gravity && !rc; ++i) {
    char label[48];
    snprintf(label, sizeof label, "gravity component %d", i + 1);
    rc = parse_one(&s, d->gravity[i], label, &grav[i], msg, msglen, name);
    if (!rc) grav[i] = dal__alg_canon(&g, grav[i]);
  }
  for (int k = 0; k < d->nparticles && !rc; ++k)
    rc = particle_energy(&g, &s, d, k, grav, terms, &nt, uterms, &nu, msg, msglen);
  if (!rc && d->potential) {
    int p;
    rc = parse_one(&s, d->potential, "potential", &p, msg, msglen, name);
    if (!rc) uterms[nu++] = dal__alg_canon(&g, p);
  }
  if (!rc) rc = sum_up(&g, &s, terms, nt, uterms, nu, &Tn, &Un, &Ln);
  const int roots[3] = {Tn, Un, Ln};
  dal_expr **outs[3] = {T, U, L};
  for (int k = 0; k < 3 && !rc; ++k)
    if (outs[k])
      rc = energy_expr(name, "TUL"[k], &s, roots[k], n, d -> values, outs[k], msg, msglen);
  if (rc && g.too_large) {
    rc = DAL_E_TOO_LARGE;
    too_large(msg, msglen, name, &g);
  }
  if (rc) {
    if (rc == DAL_E_NOMEM && msg && msglen) snprintf(msg, msglen, "%s: out of memory", name);
    if (T) dal_expr_destroy(*T), *T = NULL;
    if (U) dal_expr_destroy(*U), *U = NULL;
    if (L) dal_expr_destroy(*L), *L = NULL;
  }
  free(terms);
  free(uterms);
  dal__alg_free(&g);
  scratch_free(&s);
  dal_expr_destroy(sym);
  return rc;
}

void dal_expr_equations_destroy(dal_expr_equations *eq) {
  if (!eq) return;
  dal_expr_destroy(eq->momentum);
  dal_expr_destroy(eq->mass);
  dal_expr_destroy(eq->force);
  dal_expr_destroy(eq->accel);
  memset(eq, 0, sizeof *eq);
}

int dal_expr_lagrange(const dal_expr *Lx, dal_expr_equations *eq, char *msg, size_t msglen) {
  if (msg && msglen) msg[0] = 0;
  if (!eq) return DAL_E_ARG;
  memset(eq, 0, sizeof *eq);
  if (!Lx || Lx->nout != 1 || !Lx->velocities) {
    if (msg && msglen)
      snprintf(msg, msglen,
               "dal_expr_lagrange: %s is not a Lagrangian (one formula over coordinates with "
               "velocities = 1)",
               Lx ? Lx->name : "NULL");
    return DAL_E_ARG;
  }
  int n = Lx->nin_named, rc = DAL_E_NOMEM;
  dal_xtree s;
  if (scratch(&s, &Lx->tree)) return DAL_E_NOMEM;
  dal_alg g;
  dal__alg_init(&g, &s);
  int *p = malloc((size_t)n * sizeof *p), *M = malloc((size_t)n * (size_t)n * sizeof *M);
  int *F = malloc((size_t)n * sizeof *F), *t = malloc(((size_t)n + 2) * sizeof *t);
  if (!p || !M || !F || !t) goto done;
  int L = dal__alg_simplify(&g, dal__ximport(&s, &Lx->tree, Lx->roots[0]));
  for (int i = 0; i < n; ++i) {
    p[i] = dal__alg_diff(&g, L, n + i);
    for (int j = 0; j < n; ++j)
      M[i * n + j] = dal__alg_diff(&g, p[i], n + j);
    // F_i = dL/dq_i - sum_j dp_i/dq_j qdot_j - dp_i/dt
    int nt = 0;
    t[nt++] = dal__alg_diff(&g, L, i);
    for (int j = 0; j < n; ++j) {
      int f[3] = {dal__xnum(&s, -1.0), dal__alg_diff(&g, p[i], j), in_node(&s, n + j)};
      t[nt++] = dal__alg_mul(&g, f, 3);
    }
    int f[2] = {dal__xnum(&s, -1.0), dal__alg_diff(&g, p[i], -1)};
    t[nt++] = dal__alg_mul(&g, f, 2);
    F[i] = dal__alg_expand(&g, dal__alg_add(&g, t, nt));
  }
  if (g.fail) {
    if (g.too_large) rc = DAL_E_TOO_LARGE, too_large(msg, msglen, Lx->name, &g);
    goto done;
  }
  char nm[160];
  snprintf(nm, sizeof nm, "%s.momentum", Lx->name);
  rc = dal__expr_from_tree(nm, &s, p, n, n, 1, Lx->values, &eq->momentum, msg, msglen);
  snprintf(nm, sizeof nm, "%s.mass", Lx->name);
  if (!rc) rc = dal__expr_from_tree(nm, &s, M, n * n, n, 1, Lx->values, &eq->mass, msg, msglen);
  snprintf(nm, sizeof nm, "%s.force", Lx->name);
  if (!rc) rc = dal__expr_from_tree(nm, &s, F, n, n, 1, Lx->values, &eq->force, msg, msglen);
  if (!rc && n == 1) {
    // qddot = F / M with the common factors of both cancelled
    int a[2] = {dal__alg_factor(&g, F[0]),
                dal__alg_pow(&g, dal__alg_factor(&g, M[0]), dal__xnum(&s, -1.0))};
    int acc = dal__alg_mul(&g, a, 2);
    snprintf(nm, sizeof nm, "%s.accel", Lx->name);
    if (acc < 0 && g.too_large) too_large(msg, msglen, Lx->name, &g);
    rc = acc < 0 ? (g.too_large ? DAL_E_TOO_LARGE : DAL_E_NOMEM)
                 : dal__expr_from_tree(nm, &s, &acc, 1, n, 1, Lx->values, &eq->accel, msg, msglen);
  }
  eq->n = n;
done:
  if (rc) {
    if (rc == DAL_E_NOMEM && msg && msglen) snprintf(msg, msglen, "%s: out of memory", Lx->name);
    dal_expr_equations_destroy(eq);
  }
  free(p);
  free(M);
  free(F);
  free(t);
  dal__alg_free(&g);
  scratch_free(&s);
  return rc;
}
