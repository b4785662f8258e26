// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Scene files built: each element line into the builder through its def; the parameters, the
// name tables and the expressions the lines compile.
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "expr/expr.h"
#include "model/model.h"
#include "scene.h"

int dal__scene_part(const dal_scene *sc, const char *name) {
  return dal__tab_get(&sc->parts, name);
}

static int coord_index(const dal_scene *sc, const char *name) {
  return dal__tab_get(&sc->coords, name);
}

static int keep_expr(dal_scene *sc, dal_expr *e) {
  dal_expr **v = dal__scene_grow(sc->ex, sc->nex, &sc->capex, sizeof *v, 16);
  if (!v) {
    dal_expr_destroy(e);
    return DAL_E_NOMEM;
  }
  sc->ex = v;
  sc->ex[sc->nex++] = e;
  return DAL_OK;
}

static int cmp_int(const void *a, const void *b) {
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

// the indices of the parameters the formulas name, in the order of the file (malloc'd)
static int used_params(const dal_scene *sc, const char *const *f, int nf, int **idx, int *n) {
  int cap = 16, m = 0;
  int *v = malloc((size_t)cap * sizeof *v);
  if (!v) return DAL_E_NOMEM;
  for (int k = 0; k < nf; ++k)
    for (const char *s = f[k]; s && *s;) {
      if (!(isalnum((unsigned char)*s) || *s == '_')) {
        s++;
        continue;
      }
      size_t w = 0;
      while (isalnum((unsigned char)s[w]) || s[w] == '_')
        w++;
      if (!isdigit((unsigned char)*s)) { // a number's exponent is no name
        char *name = dal__scene_dupn(s, w);
        int j = name ? dal__tab_get(&sc->ptab, name) : -1;
        free(name);
        if (j >= 0 && j < sc->nparam) {
          if (m == cap) {
            int *nv = realloc(v, (size_t)(cap *= 2) * sizeof *nv);
            if (!nv) {
              free(v);
              return DAL_E_NOMEM;
            }
            v = nv;
          }
          v[m++] = j;
        }
      }
      s += w;
    }
  qsort(v, (size_t)m, sizeof *v, cmp_int);
  int u = 0;
  for (int i = 0; i < m; ++i)
    if (!u || v[u - 1] != v[i]) v[u++] = v[i];
  *idx = v;
  *n = u;
  return DAL_OK;
}

int dal__scene_params(const dal_scene *sc, const char *const *f, int nf, const char ***names,
                      double **values, int *n) {
  int *idx = NULL, np = 0;
  int rc = used_params(sc, f, nf, &idx, &np);
  if (rc) return rc;
  *names = malloc(((size_t)np + 1) * sizeof **names);
  *values = malloc(((size_t)np + 1) * sizeof **values);
  if (!*names || !*values) rc = DAL_E_NOMEM;
  for (int i = 0; i < np && !rc; ++i) {
    (*names)[i] = sc->pname[idx[i]];
    (*values)[i] = sc->pval[idx[i]];
  }
  free(idx);
  *n = np;
  return rc;
}

int dal__scene_expr(const dal_scene *sc, const char *name, const char *const *f, int nf,
                    const char *const *in, int nin, int vel, dal_expr **e, char *msg, size_t len) {
  const char **pn = NULL;
  double *pv = NULL;
  int np = 0, rc = dal__scene_params(sc, f, nf, &pn, &pv, &np);
  if (!rc) {
    dal_expr_def d = dal_default_expr_def();
    d.name = name;
    d.formulas = f;
    d.nout = nf;
    d.inputs = in;
    d.nin = nin;
    d.velocities = vel;
    d.params = pn;
    d.values = pv;
    d.nparam = np;
    rc = dal_expr_create(&d, e, msg, len);
  }
  free(pn);
  free(pv);
  return rc;
}

// compile formulas over the named inputs and the parameters; the scene keeps the expression
static int mkexpr(dal_scene *sc, const sline *l, const char *what, const char *const *f, int nf,
                  const char *const *in, int nin, int vel, dal_expr **out, char *msg, size_t len) {
  int k = 0;
  if (msg && len) {
    k = snprintf(msg, len, "%s:%d: ", sc->name, l->line);
    if (k < 0 || (size_t)k >= len) k = 0;
  }
  int rc = dal__scene_expr(sc, what, f, nf, in, nin, vel, out, msg ? msg + k : NULL,
                           msg ? len - (size_t)k : 0);
  if (rc) return rc;
  return keep_expr(sc, *out);
}

// the value of a constant formula of the parameters (a plain number read directly)
static int constval(dal_scene *sc, const sline *l, const char *what, const char *text, double *v,
                    char *msg, size_t len) {
  char *end = NULL;
  errno = 0;
  *v = strtod(text, &end);
  if (end != text && !*end && isfinite(*v) && !isspace((unsigned char)text[0])) return DAL_OK;
  dal_expr *e;
  int rc = mkexpr(sc, l, what, &text, 1, NULL, 0, 0, &e, msg, len);
  if (rc) return rc;
  dal_jet out;
  dal_expr_eval(e, NULL, dal_const(0.0), NULL, &out);
  *v = out.v;
  if (!isfinite(*v))
    return dal__scene_err(sc, l->line, msg, len, DAL_E_NONFINITE, "%s: '%s' is not finite (%g)",
                          what, text, *v);
  return DAL_OK;
}

static int builder(dal_scene *sc, const sline *l, char *msg, size_t len) {
  if (sc->b) return DAL_OK;
  int rc = dal_builder_create(sc->dim, &sc->b);
  if (rc) return dal__scene_err(sc, l->line, msg, len, rc, "dim %d: no builder", sc->dim);
  return DAL_OK;
}

static int bcheck(dal_scene *sc, const sline *l, int rc, char *msg, size_t len) {
  if (rc) return dal__scene_err(sc, l->line, msg, len, rc, "%s", dal_builder_errmsg(sc->b));
  return DAL_OK;
}

// a name into table t (the line that gives it); a name given before is refused on the later
// of the two lines, naming the other
static int claim(dal_scene *sc, dal_tab *t, const sline *l, const char *name, int made, char *msg,
                 size_t len) {
  int other = dal__tab_get(t, name);
  if (other >= 0) {
    int a = other < l->line ? other : l->line, z = other < l->line ? l->line : other;
    return dal__scene_err(
        sc, z, msg, len, DAL_E_ARG, "%s %s: the name '%s' is given twice (line %d and %s)",
        l->tok[0], l->ntok > 1 ? l->tok[1] : "", name, a, z == l->line ? "here" : "this line");
  }
  const char *key = name;
  if (made) { // a made name (a rate, x_<p>): the scene keeps it
    char **v = dal__scene_grow(sc->symkeys, sc->nsymkeys, &sc->capsymkeys, sizeof *v, 16);
    if (!v) return DAL_E_NOMEM;
    sc->symkeys = v;
    char *k = dal__scene_dup(name);
    if (!k) return DAL_E_NOMEM;
    sc->symkeys[sc->nsymkeys++] = k;
    key = k;
  }
  return dal__tab_put(t, key, l->line);
}

// a symbol a formula may use, and the made ones with it (prefix + name + suffix)
static int claim_sym(dal_scene *sc, const sline *l, const char *pre, const char *name,
                     const char *suf, char *msg, size_t len) {
  if (!*pre && !*suf) return claim(sc, &sc->syms, l, name, 0, msg, len);
  char *s = dal__scene_strf("%s%s%s", pre, name, suf);
  if (!s) return DAL_E_NOMEM;
  int rc = claim(sc, &sc->syms, l, s, 1, msg, len);
  free(s);
  return rc;
}

// a comma-separated list: its n items (malloc'd copies in *items, the caller frees them)
static int split_list(const char *list, char ***items, int *n) {
  int m = 1;
  for (const char *s = list; *s; ++s)
    m += *s == ',';
  char **v = calloc((size_t)m, sizeof *v);
  if (!v) return DAL_E_NOMEM;
  int k = 0;
  for (const char *s = list;; ++k) {
    const char *e = strchr(s, ',');
    size_t w = e ? (size_t)(e - s) : strlen(s);
    v[k] = dal__scene_dupn(s, w);
    if (!v[k]) {
      for (int i = 0; i < k; ++i)
        free(v[i]);
      free(v);
      return DAL_E_NOMEM;
    }
    if (!e) break;
    s = e + 1;
  }
  *items = v;
  *n = m;
  return DAL_OK;
}

static void free_list(char **items, int n) {
  for (int i = 0; i < n; ++i)
    free(items[i]);
  free(items);
}

// a comma-separated list of particle names into indices (*idx malloc'd)
static int part_list(dal_scene *sc, const sline *l, const char *list, int **idx, int *n, char *msg,
                     size_t len) {
  char **it;
  int m, rc = split_list(list, &it, &m);
  if (rc) return rc;
  *idx = malloc((size_t)m * sizeof **idx);
  if (!*idx) rc = DAL_E_NOMEM;
  for (int i = 0; i < m && !rc; ++i)
    if (((*idx)[i] = dal__scene_part(sc, it[i])) < 0)
      rc = dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                          "%s %s: particle '%s' is not defined above", l->tok[0], l->tok[1], it[i]);
  free_list(it, m);
  *n = m;
  return rc;
}

// inputs of a formula element: positions of particles `parts` (x_<p>, ...), then the
// coordinates it uses; the expression compiled over them
static int element_expr(dal_scene *sc, const sline *l, const char *what, const int *parts,
                        int nparts, dal_expr **e, int *coords, int *ncoords, char *msg,
                        size_t len) {
  int d = sc->dim, nin = nparts * d + sc->ncoord;
  char **in = calloc((size_t)nin + 1, sizeof *in);
  if (!in) return DAL_E_NOMEM;
  int rc = DAL_OK;
  for (int k = 0; k < nparts && !rc; ++k)
    for (int i = 0; i < d && !rc; ++i)
      if (!(in[k * d + i] = dal__scene_strf("%c_%s", "xyz"[i], sc -> partname[parts[k]])))
        rc = DAL_E_NOMEM;
  for (int j = 0; j < sc->ncoord && !rc; ++j)
    in[nparts * d + j] = sc->cname[j];
  dal_expr *all = NULL;
  if (!rc)
    rc = mkexpr(sc, l, what, (const char *const *)l->f, l->nf, (const char *const *)in, nin, 0,
                &all, msg, len);
  if (!rc) {
    // keep only the coordinates the formulas use
    int m = 0;
    for (int j = 0; j < sc->ncoord; ++j)
      if (dal_expr_depends(all, nparts * d + j)) {
        coords[m] = j;
        in[nparts * d + m] = sc->cname[j];
        m++;
      }
    *ncoords = m;
    if (m == sc->ncoord)
      *e = all;
    else
      rc = mkexpr(sc, l, what, (const char *const *)l->f, l->nf, (const char *const *)in,
                  nparts * d + m, 0, e, msg, len);
  }
  for (int k = 0; k < nparts * d; ++k)
    free(in[k]);
  free(in);
  return rc;
}

static int set_method(dal_scene *sc, const sline *l, const char *v, char *msg, size_t len) {
  for (int m = DAL_METHOD_AUTO; m <= DAL_METHOD_RATTLE6; ++m)
    if (!strcmp(dal_method_name((dal_method)m), v)) {
      sc->opts.method = (dal_method)m;
      return DAL_OK;
    }
  return dal__scene_err(
      sc, l->line, msg, len, DAL_E_ARG,
      "run: unknown method '%s' (auto dopri5 fehlberg78 bs rk4 adams bdf variational "
      "variational4 variational6 rattle rattle4 rattle6)",
      v);
}

static int number(dal_scene *sc, const sline *l, const char *key, const char *v, double *out,
                  char *msg, size_t len) {
  char *what = dal__scene_strf("%s %s", l->tok[0], key);
  if (!what) return DAL_E_NOMEM;
  int rc = constval(sc, l, what, v, out, msg, len);
  free(what);
  return rc;
}

static int add_name(char ***names, int n, const char *s) {
  char **v = realloc(*names, ((size_t)n + 1) * sizeof *v);
  if (!v) return DAL_E_NOMEM;
  *names = v;
  v[n] = dal__scene_dup(s);
  return v[n] ? DAL_OK : DAL_E_NOMEM;
}

// param NAME = FORMULA (of the parameters above it); a value set by dal_scene_set_param wins
int dal__scene_param(dal_scene *sc, const sline *l, char *msg, size_t len) {
  if (l->ntok != 2 || l->nf != 1)
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                          "param: 'param <name> = <formula of the parameters above>'");
  int j = sc->nparam, rc;
  if ((rc = claim_sym(sc, l, "", l->tok[1], "", msg, len))) return rc;
  double v = sc->overval[j];
  if (!sc->over[j] && (rc = number(sc, l, l->tok[1], l->f[0], &v, msg, len))) return rc;
  sc->pname[j] = l->tok[1];
  sc->pval[j] = v;
  sc->nparam++;
  return dal__tab_put(&sc->ptab, l->tok[1], j);
}

int dal__scene_dim(dal_scene *sc, const sline *l, char *msg, size_t len) {
  if (l->ntok != 2 || sc->b ||
      (strcmp(l->tok[1], "0") && strcmp(l->tok[1], "2") && strcmp(l->tok[1], "3")))
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                          "dim: one of 0, 2, 3, before every coordinate and particle");
  sc->dim = atoi(l->tok[1]);
  return DAL_OK;
}

int dal__scene_coord(dal_scene *sc, const sline *l, char *msg, size_t len) {
  if (l->ntok < 2)
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG, "coord: a name is missing");
  int rc = builder(sc, l, msg, len);
  if (rc) return rc;
  double q = 0, v = 0;
  const char *s;
  if ((s = dal__scene_kv(l, 2, "q")) && (rc = number(sc, l, "q", s, &q, msg, len))) return rc;
  if ((s = dal__scene_kv(l, 2, "v")) && (rc = number(sc, l, "v", s, &v, msg, len))) return rc;
  for (int i = 2; i < l->ntok; ++i)
    if (strncmp(l->tok[i], "q=", 2) && strncmp(l->tok[i], "v=", 2))
      return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                            "coord %s: unknown word '%s' (q=, v=)", l->tok[1], l->tok[i]);
  if ((rc = claim_sym(sc, l, "", l->tok[1], "", msg, len)) ||
      (rc = claim_sym(sc, l, "", l->tok[1], "dot", msg, len)))
    return rc;
  if ((rc = bcheck(sc, l, dal_builder_add_coord(sc->b, l->tok[1], NULL), msg, len))) return rc;
  double *nq = realloc(sc->q0, ((size_t)sc->ncoord + 1) * sizeof *nq);
  if (nq) sc->q0 = nq;
  double *nv = realloc(sc->v0, ((size_t)sc->ncoord + 1) * sizeof *nv);
  if (nv) sc->v0 = nv;
  if (!nq || !nv || add_name(&sc->cname, sc->ncoord, l->tok[1])) return DAL_E_NOMEM;
  if (dal__tab_put(&sc->coords, sc->cname[sc->ncoord], sc->ncoord)) return DAL_E_NOMEM;
  sc->q0[sc->ncoord] = q;
  sc->v0[sc->ncoord++] = v;
  return DAL_OK;
}

int dal__scene_particle(dal_scene *sc, const sline *l, char *msg, size_t len) {
  const char *m = dal__scene_kv(l, 2, "mass");
  if (l->ntok != 3 || !m)
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                          "particle: 'particle <name> mass=<formula>'");
  int rc = builder(sc, l, msg, len);
  if (rc) return rc;
  double mv;
  if ((rc = number(sc, l, "mass", m, &mv, msg, len))) return rc;
  if (dal__scene_part(sc, l->tok[1]) >= 0) { // its first line is the one of x_<name>
    char *xs = dal__scene_strf("x_%s", l->tok[1]);
    int other = xs ? dal__tab_get(&sc->syms, xs) : -1;
    free(xs);
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                          "particle %s: the name '%s' is given twice (line %d and here)", l->tok[1],
                          l->tok[1], other);
  }
  for (int c = 0; c < 3 && !rc; ++c)
    rc = claim_sym(sc, l, c == 0 ? "x_" : c == 1 ? "y_" : "z_", l->tok[1], "", msg, len);
  if (rc) return rc;
  if ((rc = bcheck(sc, l, dal_builder_add_particle(sc->b, l->tok[1], mv, NULL), msg, len)))
    return rc;
  if (add_name(&sc->partname, sc->npart, l->tok[1])) return DAL_E_NOMEM;
  if (dal__tab_put(&sc->parts, sc->partname[sc->npart], sc->npart)) return DAL_E_NOMEM;
  sc->npart++;
  return DAL_OK;
}

// the built-in primitive named by word 2 and its words from word 3 on: coordinates and
// name=formula parameters (parent= and parts= belong to the element); every parameter without
// a default given. coords (ntok ints) and param (prim->nparam values) are the caller's.
static int prim_args(dal_scene *sc, const sline *l, const dal_primitive **pp, int *coords, int *nc,
                     double **param, char *msg, size_t len) {
  const char *k = l->tok[0], *nm = l->tok[1];
  *param = NULL;
  if (l->ntok < 3)
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG, "%s %s: '= formulas' or a primitive", k,
                          nm);
  const dal_primitive *prim = *pp = dal_primitive_find(l->tok[2]);
  if (!prim)
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG, "%s %s: unknown primitive '%s'", k, nm,
                          l->tok[2]);
  double *p = *param = malloc(((size_t)prim->nparam + 1) * sizeof *p);
  if (!p) return DAL_E_NOMEM;
  for (int i = 0; i < prim->nparam; ++i)
    p[i] = prim->param_defaults ? prim->param_defaults[i] : NAN;
  *nc = 0;
  for (int i = 3; i < l->ntok; ++i) {
    const char *w = l->tok[i], *eq = strchr(w, '=');
    if (!strncmp(w, "parent=", 7) || !strncmp(w, "parts=", 6)) continue;
    if (!eq) {
      int c = coord_index(sc, w);
      if (c < 0)
        return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                              "%s %s: '%s' is not a coordinate defined above", k, nm, w);
      coords[(*nc)++] = c;
      continue;
    }
    int j = -1;
    for (int q = 0; q < prim->nparam && prim->param_names; ++q)
      if (strlen(prim->param_names[q]) == (size_t)(eq - w) &&
          !strncmp(prim->param_names[q], w, (size_t)(eq - w)))
        j = q;
    if (j < 0)
      return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG, "%s %s: '%s' has no parameter '%.*s'",
                            k, nm, prim->name, (int)(eq - w), w);
    int rc = number(sc, l, prim->param_names[j], eq + 1, &p[j], msg, len);
    if (rc) return rc;
  }
  for (int i = 0; i < prim->nparam; ++i)
    if (p[i] != p[i])
      return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                            "%s %s: parameter '%s' of '%s' is required", k, nm,
                            prim->param_names ? prim->param_names[i] : "?", prim->name);
  return DAL_OK;
}

// A placement by formulas that are dal_map_hanging's, x_P + l*sin(q); y_P - l*cos(q) with l the
// expression's one parameter (a planar chain's link), takes that primitive: its closed form
// (kinematics.c) and the recursion's translating link, as the C route does, instead of two
// evaluations of the formulas per right-hand side. Its parameter list is the expression's
// ([l]); a per-trajectory parameter of the placement is named "place:P:l" by hanging's name.
static const dal_primitive *hanging_prim(const dal_scene *sc, const dal_expr *e) {
  return sc->dim == 2 && dal__expr_hanging(e) ? &dal_map_hanging : NULL;
}

// a placement (p >= 0) or a constraint (p < 0) by formulas (after '=') or by a built-in
// primitive: parts are the particles whose positions the formulas may use (the parent, the
// constraint's parts)
static int element(dal_scene *sc, const sline *l, int p, const int *parts, int np, char *msg,
                   size_t len) {
  dal_expr *e = NULL;
  const dal_primitive *prim = NULL;
  double *param = NULL;
  int nc = 0, nparam = 0, rc;
  int *cs = malloc(((size_t)sc->ncoord + (size_t)l->ntok + 1) * sizeof *cs);
  char *what = dal__scene_strf("%s %s", l->tok[0], l->tok[1]);
  if (!cs || !what) {
    rc = DAL_E_NOMEM;
  } else if (l->nf) {
    rc = element_expr(sc, l, what, parts, np, &e, cs, &nc, msg, len);
    if (!rc) {
      prim = dal_expr_primitive(e);
      param = (double *)dal_expr_values(e);
      nparam = dal_expr_nparam(e);
    }
  } else {
    rc = prim_args(sc, l, &prim, cs, &nc, &param, msg, len);
    nparam = prim ? prim->nparam : 0;
  }
  if (!rc && p >= 0) {
    const dal_primitive *h = e && np && nc == 1 ? hanging_prim(sc, e) : NULL;
    dal_place_def pd = dal_default_place_def();
    pd.prim = h ? h : prim;
    pd.parent = np ? parts[0] : -1;
    pd.coords = cs;
    pd.ncoords = nc;
    pd.param_list = param;
    pd.nparam_list = nparam;
    pd.ctx = e;
    rc = bcheck(sc, l, dal_builder_place_def(sc->b, p, &pd), msg, len);
  } else if (!rc) {
    dal_constraint_def cd = dal_default_constraint_def();
    cd.name = l->tok[1];
    cd.prim = prim;
    cd.parts = parts;
    cd.nparts = np;
    cd.coords = cs;
    cd.ncoords = nc;
    cd.param_list = param;
    cd.nparam_list = nparam;
    cd.ctx = e;
    rc = bcheck(sc, l, dal_builder_add_constraint_def(sc->b, &cd, NULL), msg, len);
  }
  if (!e) free(param);
  free(cs);
  free(what);
  return rc;
}

int dal__scene_place(dal_scene *sc, const sline *l, char *msg, size_t len) {
  if (l->ntok < 2 || !sc->b)
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                          "place: 'place <particle> ...' after it");
  int p = dal__scene_part(sc, l->tok[1]), parent = -1;
  if (p < 0)
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                          "place: particle '%s' is not defined above", l->tok[1]);
  const char *ps = dal__scene_kv(l, 2, "parent");
  if (ps && (parent = dal__scene_part(sc, ps)) < 0)
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                          "place %s: parent '%s' is not defined above", l->tok[1], ps);
  if (l->nf) {
    if (l->nf != sc->dim)
      return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                            "place %s: %d formulas for dimension %d (separate them with ';')",
                            l->tok[1], l->nf, sc->dim);
    for (int i = 2; i < l->ntok; ++i)
      if (strncmp(l->tok[i], "parent=", 7))
        return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                              "place %s: unknown word '%s' before '='", l->tok[1], l->tok[i]);
  }
  return element(sc, l, p, &parent, parent >= 0, msg, len);
}

int dal__scene_constraint(dal_scene *sc, const sline *l, char *msg, size_t len) {
  if (l->ntok < 2 || !sc->b)
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG, "constraint: 'constraint <name> ...'");
  int *parts = NULL, np = 0, rc = claim(sc, &sc->elems, l, l->tok[1], 0, msg, len);
  const char *pl = dal__scene_kv(l, 2, "parts");
  if (!rc && pl) rc = part_list(sc, l, pl, &parts, &np, msg, len);
  if (!rc) rc = element(sc, l, -1, parts, np, msg, len);
  free(parts);
  return rc;
}

// spring a b ... / spring a anchor=x,y ...: the other end (-1: an anchor) and the anchor
static int ends(dal_scene *sc, const sline *l, int *a, int *b, int *from, double *anchor, char *msg,
                size_t len) {
  const char *k = l->tok[0];
  if (l->ntok < 3 || !sc->b)
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                          "%s: '%s <a> <b> ...' or '%s <a> anchor=x,y ...'", k, k, k);
  *a = dal__scene_part(sc, l->tok[1]);
  if (*a < 0)
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                          "%s: particle '%s' is not defined above", k, l->tok[1]);
  *b = -1;
  *from = 2;
  if (!strchr(l->tok[2], '=')) {
    *b = dal__scene_part(sc, l->tok[2]);
    if (*b < 0)
      return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                            "%s: particle '%s' is not defined above", k, l->tok[2]);
    *from = 3;
  }
  const char *an = dal__scene_kv(l, *from, "anchor");
  if (!an) return DAL_OK;
  char **it;
  int n, rc = split_list(an, &it, &n);
  if (rc) return rc;
  if (n > sc->dim)
    rc =
        dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                       "%s %s: anchor of %d components for dimension %d", k, l->tok[1], n, sc->dim);
  for (int i = 0; i < n && !rc; ++i)
    rc = number(sc, l, "anchor", it[i], &anchor[i], msg, len);
  free_list(it, n);
  return rc;
}

int dal__scene_spring(dal_scene *sc, const sline *l, char *msg, size_t len) {
  int spring = l->tok[0][0] == 's', a = -1, bb = -1, from = 2, rc;
  double anchor[3] = {0, 0, 0}, kk = 0, LL = 0;
  if ((rc = ends(sc, l, &a, &bb, &from, anchor, msg, len))) return rc;
  for (int i = from; i < l->ntok; ++i)
    if (strncmp(l->tok[i], "anchor=", 7) && strncmp(l->tok[i], spring ? "k=" : "c=", 2) &&
        (!spring || strncmp(l->tok[i], "L=", 2)))
      return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG, "%s %s: unknown word '%s' (%s)",
                            l->tok[0], l->tok[1], l->tok[i],
                            spring ? "anchor= k= L=" : "anchor= c=");
  const char *s;
  if ((s = dal__scene_kv(l, from, spring ? "k" : "c")) &&
      (rc = number(sc, l, spring ? "k" : "c", s, &kk, msg, len)))
    return rc;
  if (spring && (s = dal__scene_kv(l, from, "L")) && (rc = number(sc, l, "L", s, &LL, msg, len)))
    return rc;
  if (spring) {
    dal_spring_def d = dal_default_spring_def();
    d.a = a;
    d.b = bb;
    d.k = kk;
    d.length = LL;
    memcpy(d.anchor, anchor, sizeof anchor);
    return bcheck(sc, l, dal_builder_add_spring_def(sc->b, &d), msg, len);
  }
  dal_damper_def d = dal_default_damper_def();
  d.a = a;
  d.b = bb;
  d.c = kk;
  memcpy(d.anchor, anchor, sizeof anchor);
  return bcheck(sc, l, dal_builder_add_damper_def(sc->b, &d), msg, len);
}

int dal__scene_gravity(dal_scene *sc, const sline *l, char *msg, size_t len) {
  if (!sc->b || l->ntok != 1 + sc->dim)
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG, "gravity: %d components (formulas)",
                          sc->dim);
  double g[3];
  for (int i = 0; i < sc->dim; ++i) {
    int rc = number(sc, l, "component", l->tok[1 + i], &g[i], msg, len);
    if (rc) return rc;
  }
  return bcheck(sc, l, dal_builder_set_gravity(sc->b, g), msg, len);
}

int dal__scene_potential(dal_scene *sc, const sline *l, char *msg, size_t len) {
  const char *k = l->tok[0];
  int lag = k[0] == 'l';
  if (!sc->b || l->nf != 1 || l->ntok != 1)
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                          "%s: '%s = <formula>' after the coordinates", k, k);
  dal_expr *e;
  int rc = mkexpr(sc, l, k, (const char *const *)l->f, 1, (const char *const *)sc->cname,
                  sc->ncoord, lag, &e, msg, len);
  if (rc) return rc;
  if (!lag)
    return bcheck(sc, l, dal_builder_add_potential_q(sc->b, dal_expr_potential_q, e), msg, len);
  if ((rc = bcheck(sc, l, dal_builder_set_lagrangian(sc->b, dal_expr_lagrangian, e), msg, len)))
    return rc;
  // its parts dL/dqdot and dL/dq, derived once: the accelerations in n + 1 evaluations of them
  // instead of n (n + 3) / 2 + 1 of L (eval/lagrangian.c); past the algebra's bounds L alone
  dal_expr *parts = NULL;
  rc = dal__expr_lagrange_parts(e, &parts, NULL, 0);
  if (rc == DAL_E_NOMEM || (!rc && (rc = keep_expr(sc, parts)))) return DAL_E_NOMEM;
  if (rc) return DAL_OK;
  return bcheck(sc, l,
                dal__builder_set_lagrangian_parts(sc->b, dal__expr_lagrange_parts_eval, parts), msg,
                len);
}

// the generalized force of a force line, added to Q_i
static int force_q(double t, const double *q, const double *qdot, double *Q, void *ctx) {
  const scene_force *f = ctx;
  double v = dal_expr_event(t, q, qdot, f->e);
  if (!isfinite(v)) return -1;
  Q[f->coord] += v;
  return 0;
}

// force COORD = Q(t, q, qdot): a generalized force on one coordinate
int dal__scene_force(dal_scene *sc, const sline *l, char *msg, size_t len) {
  if (!sc->b || l->ntok != 2 || l->nf != 1)
    return dal__scene_err(
        sc, l->line, msg, len, DAL_E_ARG,
        "force: 'force <coordinate> = <formula of t, q, qdot>' after the coordinates");
  int i = coord_index(sc, l->tok[1]);
  if (i < 0)
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                          "force %s: '%s' is not a coordinate defined above", l->tok[1], l->tok[1]);
  if (sc->ncoord > DAL_EXPR_EVENT_MAXN)
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG, "force %s: more than %d coordinates",
                          l->tok[1], DAL_EXPR_EVENT_MAXN);
  scene_force **v = realloc(sc->gf, ((size_t)sc->ngf + 1) * sizeof *v);
  if (!v) return DAL_E_NOMEM;
  sc->gf = v;
  scene_force *f = sc->gf[sc->ngf] = calloc(1, sizeof *f);
  if (!f) return DAL_E_NOMEM;
  sc->ngf++;
  char *what = dal__scene_strf("force %s", l->tok[1]);
  int rc = what ? mkexpr(sc, l, what, (const char *const *)l->f, 1, (const char *const *)sc->cname,
                         sc->ncoord, 1, &f->e, msg, len)
                : DAL_E_NOMEM;
  free(what);
  f->coord = i;
  return rc ? rc : bcheck(sc, l, dal_builder_add_genforce(sc->b, force_q, f), msg, len);
}

// one key=value word of a run line
static int run_key(dal_scene *sc, const sline *l, const char *w, char *msg, size_t len) {
  const char *eq = strchr(w, '=');
  if (!eq) return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG, "run: '%s' is not key=value", w);
  size_t n = (size_t)(eq - w);
  if (n == 6 && !strncmp(w, "method", 6)) return set_method(sc, l, eq + 1, msg, len);
  static const char *const keys[] = {"rtol", "atol", "step", "t0", "t1", "dt"};
  double *dst[] = {&sc->opts.rtol, &sc->opts.atol, &sc->opts.fixed_step, &sc->t0, &sc->t1, &sc->dt};
  for (int i = 0; i < 6; ++i)
    if (strlen(keys[i]) == n && !strncmp(w, keys[i], n))
      return number(sc, l, keys[i], eq + 1, dst[i], msg, len);
  return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                        "run: unknown key '%.*s' (method rtol atol step t0 t1 dt)", (int)n, w);
}

int dal__scene_run(dal_scene *sc, const sline *l, char *msg, size_t len) {
  sc->has_run = 1;
  for (int i = 1; i < l->ntok; ++i) {
    int rc = run_key(sc, l, l->tok[i], msg, len);
    if (rc) return rc;
  }
  return DAL_OK;
}

// event NAME [rising|falling|both] [terminal] = g(t, q, qdot)
// section NAME [rising|falling|both] = g(t, q, qdot)    (a surface section: logged crossings)
// section NAME period=T                                  (stroboscopic: the state every T)
int dal__scene_event(dal_scene *sc, const sline *l, char *msg, size_t len) {
  const char *k = l->tok[0];
  int section = k[0] == 's', dir = DAL_EVENT_BOTH, terminal = 0, rc;
  if (l->ntok < 2 || !sc->b || !sc->ncoord)
    return dal__scene_err(
        sc, l->line, msg, len, DAL_E_ARG,
        section ? "section: 'section <name> [rising|falling] = <formula>' or "
                  "'section <name> period=<formula>', after the coordinates"
                : "event: 'event <name> [rising|falling] [terminal] = <formula>', after "
                  "the coordinates");
  if ((rc = claim(sc, &sc->elems, l, l->tok[1], 0, msg, len))) return rc;
  const char *per = dal__scene_kv(l, 2, "period");
  if (section && per) {
    if (l->ntok != 3 || l->nf)
      return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                            "section %s: 'period=<formula>' alone", l->tok[1]);
    if (sc->strobe > 0)
      return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                            "section %s: a second stroboscopic section", l->tok[1]);
    double T;
    if ((rc = number(sc, l, "period", per, &T, msg, len))) return rc;
    if (!(T > 0))
      return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                            "section %s: period %g is not positive", l->tok[1], T);
    sc->strobe = T;
    return DAL_OK;
  }
  for (int i = 2; i < l->ntok; ++i) {
    const char *w = l->tok[i];
    if (!strcmp(w, "rising"))
      dir = DAL_EVENT_RISING;
    else if (!strcmp(w, "falling"))
      dir = DAL_EVENT_FALLING;
    else if (!strcmp(w, "both"))
      dir = DAL_EVENT_BOTH;
    else if (!section && !strcmp(w, "terminal"))
      terminal = 1;
    else
      return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG,
                            "%s %s: unknown word '%s' (rising falling both%s)", k, l->tok[1], w,
                            section ? " period=" : " terminal");
  }
  if (l->nf != 1)
    return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG, "%s %s: one formula after '='", k,
                          l->tok[1]);
  scene_event *v = realloc(sc->ev, ((size_t)sc->nev + 1) * sizeof *v);
  if (!v) return DAL_E_NOMEM;
  sc->ev = v;
  char *what = dal__scene_strf("%s %s", k, l->tok[1]);
  scene_event *ev = &sc->ev[sc->nev];
  rc = what ? mkexpr(sc, l, what, (const char *const *)l->f, 1, (const char *const *)sc->cname,
                     sc->ncoord, 1, &ev->e, msg, len)
            : DAL_E_NOMEM;
  free(what);
  if (rc) return rc;
  ev->name = l->tok[1];
  ev->direction = dir;
  ev->terminal = terminal;
  ev->section = section;
  sc->nev++;
  return DAL_OK;
}

// what a build made; the lines and the parameters' overrides stay
void dal__scene_unbuild(dal_scene *sc) {
  dal_system_destroy(sc->sys);
  dal_builder_destroy(sc->b);
  sc->sys = NULL;
  sc->b = NULL;
  for (int i = 0; i < sc->nex; ++i)
    dal_expr_destroy(sc->ex[i]);
  free(sc->ex);
  sc->ex = NULL;
  sc->nex = sc->capex = 0;
  for (int i = 0; i < sc->ncoord; ++i)
    free(sc->cname[i]);
  free(sc->cname);
  free(sc->q0);
  free(sc->v0);
  sc->cname = NULL;
  sc->q0 = sc->v0 = NULL;
  sc->ncoord = 0;
  for (int i = 0; i < sc->npart; ++i)
    free(sc->partname[i]);
  free(sc->partname);
  sc->partname = NULL;
  sc->npart = 0;
  free(sc->ev);
  sc->ev = NULL;
  sc->nev = 0;
  for (int i = 0; i < sc->ngf; ++i)
    free(sc->gf[i]);
  free(sc->gf);
  sc->gf = NULL;
  sc->ngf = 0;
  sc->strobe = 0;
  free(sc->pname);
  free(sc->pval);
  sc->pname = NULL;
  sc->pval = NULL;
  sc->nparam = 0;
  dal__tab_free(&sc->ptab);
  dal__tab_free(&sc->syms);
  dal__tab_free(&sc->parts);
  dal__tab_free(&sc->coords);
  dal__tab_free(&sc->elems);
  for (int i = 0; i < sc->nsymkeys; ++i)
    free(sc->symkeys[i]);
  free(sc->symkeys);
  sc->symkeys = NULL;
  sc->nsymkeys = sc->capsymkeys = 0;
}
