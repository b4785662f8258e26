// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Scene files: one element per line, interpreted into a builder; written back; run; shown.
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"

// a placement and a constraint from their parts, through the defs
static int place_by(dal_builder *b, int p, const dal_primitive *prim, int parent, int nc,
                    const int *coords, int np, const double *param, void *ctx) {
  dal_place_def d = dal_default_place_def();
  d.prim = prim;
  d.parent = parent;
  d.coords = coords;
  d.ncoords = nc;
  d.param_list = param;
  d.nparam_list = np;
  d.ctx = ctx;
  return dal_builder_place_def(b, p, &d);
}

static int constrain_by(dal_builder *b, const char *name, const dal_primitive *prim, int np,
                        const int *parts, int nc, const int *coords, int npar, const double *param,
                        void *ctx) {
  dal_constraint_def d = dal_default_constraint_def();
  d.name = name;
  d.prim = prim;
  d.parts = parts;
  d.nparts = np;
  d.coords = coords;
  d.ncoords = nc;
  d.param_list = param;
  d.nparam_list = npar;
  d.ctx = ctx;
  return dal_builder_add_constraint_def(b, &d, NULL);
}

static char *dup(const char *s) {
  size_t n = strlen(s) + 1;
  char *r = malloc(n);
  if (r) memcpy(r, s, n);
  return r;
}

static char *dupn(const char *s, size_t n) {
  char *r = malloc(n + 1);
  if (r) {
    memcpy(r, s, n);
    r[n] = 0;
  }
  return r;
}

static int err(const dal_scene *sc, int line, char *msg, size_t len, int rc, const char *fmt, ...) {
  if (msg && len) {
    int k = snprintf(msg, len, "%s:%d: ", sc->name, line);
    if (k < 0) k = 0;
    if ((size_t)k < len) {
      va_list ap;
      va_start(ap, fmt);
      vsnprintf(msg + k, len - (size_t)k, fmt, ap);
      va_end(ap);
    }
  }
  return rc;
}

static void free_line(sline *l) {
  for (int i = 0; i < l->ntok; ++i)
    free(l->tok[i]);
  for (int i = 0; i < l->nf; ++i)
    free(l->f[i]);
}

// what a build made; the lines and parameters stay
static void unbuild(dal_scene *sc) {
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
  sc->strobe = 0;
}

void dal_scene_destroy(dal_scene *sc) {
  if (!sc) return;
  unbuild(sc);
  for (int i = 0; i < sc->nlines; ++i)
    free_line(&sc->lines[i]);
  free(sc->lines);
  for (int i = 0; i < sc->nparam; ++i)
    free(sc->pname[i]);
  free(sc->pname);
  free(sc->pval);
  free(sc->name);
  free(sc);
}

// split one line (comment removed) into words and formulas
static int split_line(dal_scene *sc, const char *s, size_t n, int lineno, sline *out, char *msg,
                      size_t len) {
  memset(out, 0, sizeof *out);
  out->line = lineno;
  size_t i = 0;
  while (i < n) {
    while (i < n && isspace((unsigned char)s[i]))
      i++;
    if (i >= n) break;
    if (s[i] == '=' && (i + 1 >= n || s[i + 1] != '=')) {
      // formulas: the rest of the line, split at ';'
      i++;
      while (i <= n) {
        size_t j = i;
        while (j < n && s[j] != ';')
          j++;
        size_t a = i, z = j;
        while (a < z && isspace((unsigned char)s[a]))
          a++;
        while (z > a && isspace((unsigned char)s[z - 1]))
          z--;
        if (out->nf == 3)
          return err(sc, lineno, msg, len, DAL_E_ARG, "more than 3 formulas after '='");
        out->f[out->nf] = dupn(s + a, z - a);
        if (!out->f[out->nf++]) return DAL_E_NOMEM;
        if (j >= n) break;
        i = j + 1;
      }
      break;
    }
    size_t j = i;
    while (j < n && !isspace((unsigned char)s[j]))
      j++;
    if (out->ntok == MAXTOK) return err(sc, lineno, msg, len, DAL_E_ARG, "too many words");
    out->tok[out->ntok] = dupn(s + i, j - i);
    if (!out->tok[out->ntok++]) return DAL_E_NOMEM;
    i = j;
  }
  return DAL_OK;
}

int dal__scene_find(char *const *names, int n, const char *s) {
  for (int i = 0; i < n; ++i)
    if (!strcmp(names[i], s)) return i;
  return -1;
}

static int keep_expr(dal_scene *sc, dal_expr *e) {
  if (sc->nex == sc->capex) {
    int cap = sc->capex ? 2 * sc->capex : 16;
    dal_expr **v = realloc(sc->ex, (size_t)cap * sizeof *v);
    if (!v) {
      dal_expr_destroy(e);
      return DAL_E_NOMEM;
    }
    sc->ex = v;
    sc->capex = cap;
  }
  sc->ex[sc->nex++] = e;
  return DAL_OK;
}

// compile formulas over the named inputs and every parameter; the scene keeps the expression
static int mkexpr(dal_scene *sc, const sline *l, const char *what, const char *const *f, int nf,
                  const char *const *in, int nin, int vel, dal_expr **out, char *msg, size_t len) {
  dal_expr_def d = dal_default_expr_def();
  d.name = what;
  d.formulas = f;
  d.nout = nf;
  d.inputs = in;
  d.nin = nin;
  d.velocities = vel;
  d.params = (const char *const *)sc->pname;
  d.values = sc->pval;
  d.nparam = sc->nparam;
  char m[600];
  int rc = dal_expr_create(&d, out, m, sizeof m);
  if (rc) return err(sc, l->line, msg, len, rc, "%s", m);
  return keep_expr(sc, *out);
}

// the value of a constant formula of the parameters
static int constval(dal_scene *sc, const sline *l, const char *what, const char *text, double *v,
                    char *msg, size_t len) {
  dal_expr *e;
  int rc = mkexpr(sc, l, what, &text, 1, NULL, 0, 0, &e, msg, len);
  if (rc) return rc;
  dal_jet out;
  dal_expr_eval(e, NULL, dal_const(0.0), NULL, &out);
  *v = out.v;
  if (!isfinite(*v))
    return err(sc, l->line, msg, len, DAL_E_NONFINITE, "%s: '%s' is not finite (%g)", what, text,
               *v);
  return DAL_OK;
}

// key=value words: the value of `key` (NULL if absent)
const char *dal__scene_kv(const sline *l, int from, const char *key) {
  size_t n = strlen(key);
  for (int i = from; i < l->ntok; ++i)
    if (!strncmp(l->tok[i], key, n) && l->tok[i][n] == '=') return l->tok[i] + n + 1;
  return NULL;
}

static int builder(dal_scene *sc, const sline *l, char *msg, size_t len) {
  if (sc->b) return DAL_OK;
  int rc = dal_builder_create(sc->dim, &sc->b);
  if (rc) return err(sc, l->line, msg, len, rc, "dim %d: no builder", sc->dim);
  return DAL_OK;
}

static int bcheck(dal_scene *sc, const sline *l, int rc, char *msg, size_t len) {
  if (rc) return err(sc, l->line, msg, len, rc, "%s", dal_builder_errmsg(sc->b));
  return DAL_OK;
}

// a comma-separated list of particle names into indices
static int part_list(dal_scene *sc, const sline *l, const char *list, int *idx, int max, int *n,
                     char *msg, size_t len) {
  *n = 0;
  char buf[512];
  snprintf(buf, sizeof buf, "%s", list);
  for (char *sv = NULL, *s = strtok_r(buf, ",", &sv); s; s = strtok_r(NULL, ",", &sv)) {
    int k = dal__scene_find(sc->partname, sc->npart, s);
    if (k < 0)
      return err(sc, l->line, msg, len, DAL_E_ARG, "particle '%s' is not defined above", s);
    if (*n == max) return err(sc, l->line, msg, len, DAL_E_ARG, "more than %d particles", max);
    idx[(*n)++] = k;
  }
  return DAL_OK;
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
    for (int i = 0; i < d && !rc; ++i) {
      char nm[80];
      snprintf(nm, sizeof nm, "%c_%s", "xyz"[i], sc -> partname[parts[k]]);
      in[k * d + i] = dup(nm);
      if (!in[k * d + i]) rc = DAL_E_NOMEM;
    }
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
  return err(sc, l->line, msg, len, DAL_E_ARG,
             "run: unknown method '%s' (auto dopri5 fehlberg78 bs rk4 adams bdf variational "
             "variational4 variational6 rattle rattle4 rattle6)",
             v);
}

static int number(dal_scene *sc, const sline *l, const char *key, const char *v, double *out,
                  char *msg, size_t len) {
  char what[64];
  snprintf(what, sizeof what, "%s %s", l->tok[0], key);
  return constval(sc, l, what, v, out, msg, len);
}

static int add_name(char ***names, int n, const char *s) {
  char **v = realloc(*names, ((size_t)n + 1) * sizeof *v);
  if (!v) return DAL_E_NOMEM;
  *names = v;
  v[n] = dup(s);
  return v[n] ? DAL_OK : DAL_E_NOMEM;
}

static int el_param(dal_scene *sc, const sline *l, char *msg, size_t len) {
  (void)sc, (void)l, (void)msg, (void)len;
  return DAL_OK; // taken before the build
}

static int el_dim(dal_scene *sc, const sline *l, char *msg, size_t len) {
  if (l->ntok != 2 || sc->b ||
      (strcmp(l->tok[1], "0") && strcmp(l->tok[1], "2") && strcmp(l->tok[1], "3")))
    return err(sc, l->line, msg, len, DAL_E_ARG,
               "dim: one of 0, 2, 3, before every coordinate and particle");
  sc->dim = atoi(l->tok[1]);
  return DAL_OK;
}

static int el_coord(dal_scene *sc, const sline *l, char *msg, size_t len) {
  if (l->ntok < 2) return err(sc, l->line, msg, len, DAL_E_ARG, "coord: a name is missing");
  int rc = builder(sc, l, msg, len);
  if (rc) return rc;
  double q = 0, v = 0;
  const char *s;
  if ((s = dal__scene_kv(l, 2, "q")) && (rc = number(sc, l, "q", s, &q, msg, len))) return rc;
  if ((s = dal__scene_kv(l, 2, "v")) && (rc = number(sc, l, "v", s, &v, msg, len))) return rc;
  for (int i = 2; i < l->ntok; ++i)
    if (strncmp(l->tok[i], "q=", 2) && strncmp(l->tok[i], "v=", 2))
      return err(sc, l->line, msg, len, DAL_E_ARG, "coord %s: unknown word '%s' (q=, v=)",
                 l->tok[1], l->tok[i]);
  if ((rc = bcheck(sc, l, dal_builder_add_coord(sc->b, l->tok[1], NULL), msg, len))) return rc;
  double *nq = realloc(sc->q0, ((size_t)sc->ncoord + 1) * sizeof *nq);
  if (nq) sc->q0 = nq;
  double *nv = realloc(sc->v0, ((size_t)sc->ncoord + 1) * sizeof *nv);
  if (nv) sc->v0 = nv;
  if (!nq || !nv || add_name(&sc->cname, sc->ncoord, l->tok[1])) return DAL_E_NOMEM;
  sc->q0[sc->ncoord] = q;
  sc->v0[sc->ncoord++] = v;
  return DAL_OK;
}

static int el_particle(dal_scene *sc, const sline *l, char *msg, size_t len) {
  const char *m = dal__scene_kv(l, 2, "mass");
  if (l->ntok != 3 || !m)
    return err(sc, l->line, msg, len, DAL_E_ARG, "particle: 'particle <name> mass=<formula>'");
  int rc = builder(sc, l, msg, len);
  if (rc) return rc;
  double mv;
  if ((rc = number(sc, l, "mass", m, &mv, msg, len))) return rc;
  if ((rc = bcheck(sc, l, dal_builder_add_particle(sc->b, l->tok[1], mv, NULL), msg, len)))
    return rc;
  if (add_name(&sc->partname, sc->npart, l->tok[1])) return DAL_E_NOMEM;
  sc->npart++;
  return DAL_OK;
}

// the built-in primitive named by word 2 and its words from word 3 on: coordinates and
// name=formula parameters
// (parent= and parts= belong to the element); every parameter without a default given
static int prim_args(dal_scene *sc, const sline *l, const dal_primitive **pp, int *coords, int *nc,
                     double *param, char *msg, size_t len) {
  const char *k = l->tok[0], *nm = l->tok[1];
  if (l->ntok < 3)
    return err(sc, l->line, msg, len, DAL_E_ARG, "%s %s: '= formulas' or a primitive", k, nm);
  const dal_primitive *prim = *pp = dal_primitive_find(l->tok[2]);
  if (!prim)
    return err(sc, l->line, msg, len, DAL_E_ARG, "%s %s: unknown primitive '%s'", k, nm, l->tok[2]);
  if (prim->nparam > 64)
    return err(sc, l->line, msg, len, DAL_E_ARG, "%s %s: '%s' has more than 64 parameters", k, nm,
               prim->name);
  for (int i = 0; i < prim->nparam; ++i)
    param[i] = prim->param_defaults ? prim->param_defaults[i] : NAN;
  *nc = 0;
  for (int i = 3; i < l->ntok; ++i) {
    const char *w = l->tok[i], *eq = strchr(w, '=');
    if (!strncmp(w, "parent=", 7) || !strncmp(w, "parts=", 6)) continue;
    if (!eq) {
      int c = dal__scene_find(sc->cname, sc->ncoord, w);
      if (c < 0)
        return err(sc, l->line, msg, len, DAL_E_ARG,
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
      return err(sc, l->line, msg, len, DAL_E_ARG, "%s %s: '%s' has no parameter '%.*s'", k, nm,
                 prim->name, (int)(eq - w), w);
    int rc = number(sc, l, prim->param_names[j], eq + 1, &param[j], msg, len);
    if (rc) return rc;
  }
  for (int i = 0; i < prim->nparam; ++i)
    if (param[i] != param[i])
      return err(sc, l->line, msg, len, DAL_E_ARG, "%s %s: parameter '%s' of '%s' is required", k,
                 nm, prim->param_names ? prim->param_names[i] : "?", prim->name);
  return DAL_OK;
}

// a placement or a constraint by formulas (after '='): parts are the particles whose
// positions the formulas may use (the parent, the constraint's parts)
static int formula_element(dal_scene *sc, const sline *l, int p, const int *parts, int np,
                           char *msg, size_t len) {
  dal_expr *e = NULL;
  char what[80];
  snprintf(what, sizeof what, "%s %s", l->tok[0], l->tok[1]);
  int nc = 0, *cs = malloc(((size_t)sc->ncoord + 1) * sizeof *cs);
  if (!cs) return DAL_E_NOMEM;
  int rc = element_expr(sc, l, what, parts, np, &e, cs, &nc, msg, len);
  if (!rc && p >= 0) {
    dal_place_def pd = dal_default_place_def();
    pd.prim = dal_expr_primitive(e);
    pd.parent = np ? parts[0] : -1;
    pd.coords = cs;
    pd.ncoords = nc;
    pd.param_list = dal_expr_values(e);
    pd.nparam_list = dal_expr_nparam(e);
    pd.ctx = e;
    rc = bcheck(sc, l, dal_builder_place_def(sc->b, p, &pd), msg, len);
  } else if (!rc) {
    dal_constraint_def cd = dal_default_constraint_def();
    cd.name = l->tok[1];
    cd.prim = dal_expr_primitive(e);
    cd.parts = parts;
    cd.nparts = np;
    cd.coords = cs;
    cd.ncoords = nc;
    cd.param_list = dal_expr_values(e);
    cd.nparam_list = dal_expr_nparam(e);
    cd.ctx = e;
    rc = bcheck(sc, l, dal_builder_add_constraint_def(sc->b, &cd, NULL), msg, len);
  }
  free(cs);
  return rc;
}

static int el_place(dal_scene *sc, const sline *l, char *msg, size_t len) {
  if (l->ntok < 2 || !sc->b)
    return err(sc, l->line, msg, len, DAL_E_ARG, "place: 'place <particle> ...' after it");
  int p = dal__scene_find(sc->partname, sc->npart, l->tok[1]), parent = -1;
  if (p < 0)
    return err(sc, l->line, msg, len, DAL_E_ARG, "place: particle '%s' is not defined above",
               l->tok[1]);
  const char *ps = dal__scene_kv(l, 2, "parent");
  if (ps && (parent = dal__scene_find(sc->partname, sc->npart, ps)) < 0)
    return err(sc, l->line, msg, len, DAL_E_ARG, "place %s: parent '%s' is not defined above",
               l->tok[1], ps);
  if (l->nf) {
    if (l->nf != sc->dim)
      return err(sc, l->line, msg, len, DAL_E_ARG,
                 "place %s: %d formulas for dimension %d (separate them with ';')", l->tok[1],
                 l->nf, sc->dim);
    for (int i = 2; i < l->ntok; ++i)
      if (strncmp(l->tok[i], "parent=", 7))
        return err(sc, l->line, msg, len, DAL_E_ARG, "place %s: unknown word '%s' before '='",
                   l->tok[1], l->tok[i]);
    return formula_element(sc, l, p, &parent, parent >= 0, msg, len);
  }
  // by a built-in primitive: its name, coordinates, parameters
  const dal_primitive *prim = NULL;
  double param[64];
  int coords[MAXTOK], nc = 0, rc = prim_args(sc, l, &prim, coords, &nc, param, msg, len);
  if (rc) return rc;
  return bcheck(sc, l, place_by(sc->b, p, prim, parent, nc, coords, prim->nparam, param, NULL), msg,
                len);
}

static int el_constraint(dal_scene *sc, const sline *l, char *msg, size_t len) {
  if (l->ntok < 2 || !sc->b)
    return err(sc, l->line, msg, len, DAL_E_ARG, "constraint: 'constraint <name> ...'");
  int parts[16], np = 0, rc;
  const char *pl = dal__scene_kv(l, 2, "parts");
  if (pl && (rc = part_list(sc, l, pl, parts, 16, &np, msg, len))) return rc;
  if (l->nf) return formula_element(sc, l, -1, parts, np, msg, len);
  const dal_primitive *prim = NULL;
  double param[64];
  int coords[MAXTOK], nc = 0;
  if ((rc = prim_args(sc, l, &prim, coords, &nc, param, msg, len))) return rc;
  return bcheck(
      sc, l, constrain_by(sc->b, l->tok[1], prim, np, parts, nc, coords, prim->nparam, param, NULL),
      msg, len);
}

// spring a b ... / spring a anchor=x,y ...: the other end (-1: an anchor) and the anchor
static int ends(dal_scene *sc, const sline *l, int *a, int *b, int *from, double *anchor, char *msg,
                size_t len) {
  const char *k = l->tok[0];
  if (l->ntok < 3 || !sc->b)
    return err(sc, l->line, msg, len, DAL_E_ARG, "%s: '%s <a> <b> ...' or '%s <a> anchor=x,y ...'",
               k, k, k);
  *a = dal__scene_find(sc->partname, sc->npart, l->tok[1]);
  if (*a < 0)
    return err(sc, l->line, msg, len, DAL_E_ARG, "%s: particle '%s' is not defined above", k,
               l->tok[1]);
  *b = -1;
  *from = 2;
  if (!strchr(l->tok[2], '=')) {
    *b = dal__scene_find(sc->partname, sc->npart, l->tok[2]);
    if (*b < 0)
      return err(sc, l->line, msg, len, DAL_E_ARG, "%s: particle '%s' is not defined above", k,
                 l->tok[2]);
    *from = 3;
  }
  const char *an = dal__scene_kv(l, *from, "anchor");
  if (an) {
    char buf[512];
    snprintf(buf, sizeof buf, "%s", an);
    int i = 0, rc;
    for (char *sv = NULL, *s = strtok_r(buf, ",", &sv); s && i < 3;
         s = strtok_r(NULL, ",", &sv), ++i)
      if ((rc = number(sc, l, "anchor", s, &anchor[i], msg, len))) return rc;
  }
  return DAL_OK;
}

static int el_spring(dal_scene *sc, const sline *l, char *msg, size_t len) {
  int spring = l->tok[0][0] == 's', a = -1, bb = -1, from = 2, rc;
  double anchor[3] = {0, 0, 0}, kk = 0, LL = 0;
  if ((rc = ends(sc, l, &a, &bb, &from, anchor, msg, len))) return rc;
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

static int el_gravity(dal_scene *sc, const sline *l, char *msg, size_t len) {
  if (!sc->b || l->ntok != 1 + sc->dim)
    return err(sc, l->line, msg, len, DAL_E_ARG, "gravity: %d components (formulas)", sc->dim);
  double g[3];
  for (int i = 0; i < sc->dim; ++i) {
    int rc = number(sc, l, "component", l->tok[1 + i], &g[i], msg, len);
    if (rc) return rc;
  }
  return bcheck(sc, l, dal_builder_set_gravity(sc->b, g), msg, len);
}

static int el_potential(dal_scene *sc, const sline *l, char *msg, size_t len) {
  const char *k = l->tok[0];
  int lag = k[0] == 'l';
  if (!sc->b || l->nf != 1 || l->ntok != 1)
    return err(sc, l->line, msg, len, DAL_E_ARG, "%s: '%s = <formula>' after the coordinates", k,
               k);
  dal_expr *e;
  int rc = mkexpr(sc, l, k, (const char *const *)l->f, 1, (const char *const *)sc->cname,
                  sc->ncoord, lag, &e, msg, len);
  if (rc) return rc;
  return bcheck(sc, l,
                lag ? dal_builder_set_lagrangian(sc->b, dal_expr_lagrangian, e)
                    : dal_builder_add_potential_q(sc->b, dal_expr_potential_q, e),
                msg, len);
}

// one key=value word of a run line
static int run_key(dal_scene *sc, const sline *l, const char *w, char *msg, size_t len) {
  const char *eq = strchr(w, '=');
  if (!eq) return err(sc, l->line, msg, len, DAL_E_ARG, "run: '%s' is not key=value", w);
  size_t n = (size_t)(eq - w);
  char key[32];
  snprintf(key, sizeof key, "%.*s", (int)(n < 31 ? n : 31), w);
  if (!strcmp(key, "method")) return set_method(sc, l, eq + 1, msg, len);
  static const char *const keys[] = {"rtol", "atol", "step", "t0", "t1", "dt"};
  double *dst[] = {&sc->opts.rtol, &sc->opts.atol, &sc->opts.fixed_step, &sc->t0, &sc->t1, &sc->dt};
  for (int i = 0; i < 6; ++i)
    if (!strcmp(key, keys[i])) return number(sc, l, key, eq + 1, dst[i], msg, len);
  return err(sc, l->line, msg, len, DAL_E_ARG,
             "run: unknown key '%s' (method rtol atol step t0 t1 dt)", key);
}

static int el_run(dal_scene *sc, const sline *l, char *msg, size_t len) {
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
static int el_event(dal_scene *sc, const sline *l, char *msg, size_t len) {
  const char *k = l->tok[0];
  int section = k[0] == 's', dir = DAL_EVENT_BOTH, terminal = 0, rc;
  if (l->ntok < 2 || !sc->b || !sc->ncoord)
    return err(sc, l->line, msg, len, DAL_E_ARG,
               section ? "section: 'section <name> [rising|falling] = <formula>' or "
                         "'section <name> period=<formula>', after the coordinates"
                       : "event: 'event <name> [rising|falling] [terminal] = <formula>', after "
                         "the coordinates");
  const char *per = dal__scene_kv(l, 2, "period");
  if (section && per) {
    if (l->ntok != 3 || l->nf)
      return err(sc, l->line, msg, len, DAL_E_ARG, "section %s: 'period=<formula>' alone",
                 l->tok[1]);
    if (sc->strobe > 0)
      return err(sc, l->line, msg, len, DAL_E_ARG, "section %s: a second stroboscopic section",
                 l->tok[1]);
    double T;
    if ((rc = number(sc, l, "period", per, &T, msg, len))) return rc;
    if (!(T > 0))
      return err(sc, l->line, msg, len, DAL_E_ARG, "section %s: period %g is not positive",
                 l->tok[1], T);
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
      return err(sc, l->line, msg, len, DAL_E_ARG,
                 "%s %s: unknown word '%s' (rising falling both%s)", k, l->tok[1], w,
                 section ? " period=" : " terminal");
  }
  if (l->nf != 1)
    return err(sc, l->line, msg, len, DAL_E_ARG, "%s %s: one formula after '='", k, l->tok[1]);
  scene_event *v = realloc(sc->ev, ((size_t)sc->nev + 1) * sizeof *v);
  if (!v) return DAL_E_NOMEM;
  sc->ev = v;
  char what[80];
  snprintf(what, sizeof what, "%s %s", k, l->tok[1]);
  scene_event *ev = &sc->ev[sc->nev];
  rc = mkexpr(sc, l, what, (const char *const *)l->f, 1, (const char *const *)sc->cname, sc->ncoord,
              1, &ev->e, msg, len);
  if (rc) return rc;
  ev->name = l->tok[1];
  ev->direction = dir;
  ev->terminal = terminal;
  ev->section = section;
  sc->nev++;
  return DAL_OK;
}

typedef int element_fn(dal_scene *sc, const sline *l, char *msg, size_t len);

// the elements of a scene file, by their first word
static const struct {
  const char *key;
  element_fn *fn;
} elements[] = {
    {"param", el_param},          {"dim", el_dim},
    {"coord", el_coord},          {"particle", el_particle},
    {"place", el_place},          {"constraint", el_constraint},
    {"spring", el_spring},        {"damper", el_spring},
    {"gravity", el_gravity},      {"potential", el_potential},
    {"lagrangian", el_potential}, {"run", el_run},
    {"event", el_event},          {"section", el_event},
};

static int one_line(dal_scene *sc, const sline *l, char *msg, size_t len) {
  for (size_t i = 0; i < sizeof elements / sizeof *elements; ++i)
    if (!strcmp(l->tok[0], elements[i].key)) return elements[i].fn(sc, l, msg, len);
  return err(sc, l->line, msg, len, DAL_E_ARG,
             "unknown element '%s' (dim param coord particle place constraint spring damper "
             "gravity potential lagrangian run event section)",
             l->tok[0]);
}

static int build(dal_scene *sc, char *msg, size_t len) {
  unbuild(sc);
  sc->dim = 2;
  sc->opts = dal_default_solve_opts();
  sc->t0 = 0;
  sc->t1 = 10;
  sc->dt = 0.01;
  sc->has_run = 0;
  int rc = DAL_OK;
  for (int i = 0; i < sc->nlines && !rc; ++i)
    rc = one_line(sc, &sc->lines[i], msg, len);
  if (!rc && !sc->b)
    rc = err(sc, sc->nlines ? sc->lines[sc->nlines - 1].line : 0, msg, len, DAL_E_ARG,
             "no coordinates or particles");
  if (!rc) {
    rc = dal_builder_compile(sc->b, &sc->sys);
    if (rc && msg && len) snprintf(msg, len, "%s: %s", sc->name, dal_builder_errmsg(sc->b));
  }
  // native code again for the new expressions (the cache has it)
  if (!rc && sc->native && sc->nex)
    rc = dal_codegen_attach(sc->ex, sc->nex, &sc->native_opts, msg, len);
  return rc;
}

int dal_scene_native(dal_scene *sc, const dal_codegen_opts *o, char *msg, size_t msglen) {
  if (msg && msglen) msg[0] = 0;
  if (!sc) return DAL_E_ARG;
  if (!sc->nex) return DAL_OK;
  int rc = dal_codegen_attach(sc->ex, sc->nex, o, msg, msglen);
  if (rc) return rc;
  sc->native = 1;
  sc->native_opts = o ? *o : dal_codegen_default_opts();
  return DAL_OK;
}

int dal_scene_nexprs(const dal_scene *sc) { return sc ? sc->nex : 0; }

const dal_expr *dal_scene_expr(const dal_scene *sc, int i) {
  return sc && i >= 0 && i < sc->nex ? sc->ex[i] : NULL;
}

int dal_scene_write_c(const dal_scene *sc, const char *prefix, FILE *fp) {
  if (!sc) return DAL_E_ARG;
  return dal_codegen_write(sc->ex, sc->nex, prefix, fp);
}

int dal_scene_parse(const char *text, const char *name, dal_scene **out, char *msg, size_t msglen) {
  if (msg && msglen) msg[0] = 0;
  if (!out) return DAL_E_ARG;
  *out = NULL;
  if (!text) return DAL_E_ARG;
  dal_scene *sc = calloc(1, sizeof *sc);
  if (!sc) return DAL_E_NOMEM;
  sc->name = dup(name ? name : "scene");
  int rc = sc->name ? DAL_OK : DAL_E_NOMEM, lineno = 0, cap = 0;
  const char *s = text;
  while (!rc && *s) {
    lineno++;
    const char *e = strchr(s, '\n');
    size_t n = e ? (size_t)(e - s) : strlen(s);
    const char *hash = memchr(s, '#', n);
    size_t m = hash ? (size_t)(hash - s) : n;
    sline l;
    rc = split_line(sc, s, m, lineno, &l, msg, msglen);
    if (rc) {
      free_line(&l);
    } else if (l.ntok == 0 && l.nf == 0) {
      free_line(&l);
    } else if (!rc && l.ntok == 0) {
      free_line(&l);
      rc = err(sc, lineno, msg, msglen, DAL_E_ARG, "a line starts with '='");
    } else if (!rc && !strcmp(l.tok[0], "param")) {
      // param <name> = <number>
      double v = 0;
      char *end = NULL;
      if (l.ntok != 2 || l.nf != 1) {
        rc = err(sc, lineno, msg, msglen, DAL_E_ARG, "param: 'param <name> = <number>'");
      } else {
        errno = 0;
        v = strtod(l.f[0], &end);
        if (end == l.f[0] || *end || !isfinite(v))
          rc = err(sc, lineno, msg, msglen, DAL_E_ARG, "param %s: '%s' is not a finite number",
                   l.tok[1], l.f[0]);
        else if (dal__scene_find(sc->pname, sc->nparam, l.tok[1]) >= 0)
          rc = err(sc, lineno, msg, msglen, DAL_E_ARG, "param %s is given twice", l.tok[1]);
      }
      if (!rc) {
        double *pv = realloc(sc->pval, ((size_t)sc->nparam + 1) * sizeof *pv);
        if (pv) sc->pval = pv;
        if (!pv || add_name(&sc->pname, sc->nparam, l.tok[1]))
          rc = DAL_E_NOMEM;
        else
          sc->pval[sc->nparam++] = v;
      }
      if (rc) free_line(&l);
    }
    if (!rc && l.ntok > 0) {
      if (sc->nlines == cap) {
        cap = cap ? 2 * cap : 32;
        sline *v = realloc(sc->lines, (size_t)cap * sizeof *v);
        if (!v) {
          free_line(&l);
          rc = DAL_E_NOMEM;
          break;
        }
        sc->lines = v;
      }
      sc->lines[sc->nlines++] = l;
    }
    s = e ? e + 1 : s + n;
  }
  if (!rc) rc = build(sc, msg, msglen);
  if (rc) {
    if (rc == DAL_E_NOMEM && msg && msglen) snprintf(msg, msglen, "out of memory");
    dal_scene_destroy(sc);
    return rc;
  }
  *out = sc;
  return DAL_OK;
}

int dal_scene_read(const char *path, dal_scene **out, char *msg, size_t msglen) {
  if (out) *out = NULL;
  if (!path || !out) return DAL_E_ARG;
  FILE *fp = fopen(path, "rb");
  if (!fp) {
    if (msg && msglen) snprintf(msg, msglen, "%s: cannot open (%s)", path, strerror(errno));
    return DAL_E_IO;
  }
  size_t cap = 4096, n = 0;
  char *buf = malloc(cap);
  while (buf) {
    size_t k = fread(buf + n, 1, cap - n - 1, fp);
    n += k;
    if (n < cap - 1) break;
    if (cap > ((size_t)1 << 26)) {
      free(buf);
      buf = NULL;
      break;
    }
    char *nb = realloc(buf, cap * 2);
    if (!nb) {
      free(buf);
      buf = NULL;
      break;
    }
    buf = nb;
    cap *= 2;
  }
  int bad = ferror(fp);
  fclose(fp);
  if (!buf || bad) {
    free(buf);
    if (msg && msglen) snprintf(msg, msglen, "%s: cannot read (or larger than 64 MiB)", path);
    return buf ? DAL_E_IO : DAL_E_NOMEM;
  }
  buf[n] = 0;
  if (strlen(buf) != n) {
    free(buf);
    if (msg && msglen) snprintf(msg, msglen, "%s: a NUL byte in the file", path);
    return DAL_E_ARG;
  }
  int rc = dal_scene_parse(buf, path, out, msg, msglen);
  free(buf);
  return rc;
}

int dal_scene_write(const dal_scene *sc, FILE *fp) {
  if (!sc || !fp) return DAL_E_ARG;
  fprintf(fp, "# %s, written by dalembert %s\n", sc->name, dal_version());
  for (int i = 0; i < sc->nlines; ++i) {
    const sline *l = &sc->lines[i];
    if (!strcmp(l->tok[0], "param")) {
      int j = dal__scene_find(sc->pname, sc->nparam, l->tok[1]);
      char num[40];
      for (int prec = 15; prec <= 17; ++prec) {
        snprintf(num, sizeof num, "%.*g", prec, sc->pval[j]);
        if (strtod(num, NULL) == sc->pval[j]) break;
      }
      fprintf(fp, "param %s = %s\n", l->tok[1], num);
      continue;
    }
    for (int k = 0; k < l->ntok; ++k)
      fprintf(fp, "%s%s", k ? " " : "", l->tok[k]);
    for (int k = 0; k < l->nf; ++k)
      fprintf(fp, "%s%s", k ? "; " : " = ", l->f[k]);
    fputc('\n', fp);
  }
  return ferror(fp) ? DAL_E_IO : DAL_OK;
}

int dal_scene_set_param(dal_scene *sc, const char *name, double value, char *msg, size_t msglen) {
  if (msg && msglen) msg[0] = 0;
  if (!sc || !name) return DAL_E_ARG;
  int j = dal__scene_find(sc->pname, sc->nparam, name);
  if (j < 0) {
    if (msg && msglen) snprintf(msg, msglen, "%s: no parameter '%s'", sc->name, name);
    return DAL_E_ARG;
  }
  if (!isfinite(value)) {
    if (msg && msglen) snprintf(msg, msglen, "%s: parameter '%s' is not finite", sc->name, name);
    return DAL_E_NONFINITE;
  }
  // a value the model refuses leaves the scene as it was
  double old = sc->pval[j];
  sc->pval[j] = value;
  int rc = build(sc, msg, msglen);
  if (rc) {
    sc->pval[j] = old;
    build(sc, NULL, 0);
  }
  return rc;
}

const dal_system *dal_scene_system(const dal_scene *sc) { return sc ? sc->sys : NULL; }

const dal_solve_opts *dal_scene_opts(const dal_scene *sc, double *t0, double *t1, double *dt) {
  if (!sc) return NULL;
  if (t0) *t0 = sc->t0;
  if (t1) *t1 = sc->t1;
  if (dt) *dt = sc->dt;
  return &sc->opts;
}

int dal_scene_state(const dal_scene *sc, dal_state **out) {
  if (!sc || !out) return DAL_E_ARG;
  int rc = dal_state_create(sc->sys, out);
  if (rc) return rc;
  rc = dal_state_set(sc->sys, *out, sc->t0, sc->q0, sc->v0);
  if (rc) {
    dal_state_destroy(*out);
    *out = NULL;
  }
  return rc;
}

int dal_scene_events(const dal_scene *sc, dal_events **out) {
  if (out) *out = NULL;
  if (!sc || !out) return DAL_E_ARG;
  int rc = dal_events_create(sc->sys, out);
  for (int i = 0; i < sc->nev && !rc; ++i) {
    dal_event_def d = dal_default_event_def();
    d.name = sc->ev[i].name;
    d.g = dal_expr_event;
    d.ctx = sc->ev[i].e;
    d.direction = (dal_event_direction)sc->ev[i].direction;
    d.terminal = sc->ev[i].terminal;
    int k = dal_events_add(*out, &d);
    if (k < 0) rc = k;
  }
  if (rc) {
    dal_events_destroy(*out);
    *out = NULL;
  }
  return rc;
}

int dal_scene_event_is_section(const dal_scene *sc, int i) {
  return sc && i >= 0 && i < sc->nev ? sc->ev[i].section : -1;
}

double dal_scene_strobe(const dal_scene *sc) { return sc ? sc->strobe : 0.0; }

int dal_scene_run_events(const dal_scene *sc, FILE *csv, dal_events *ev, dal_state **stp, char *msg,
                         size_t msglen) {
  if (msg && msglen) msg[0] = 0;
  if (stp) *stp = NULL;
  if (!sc) return DAL_E_ARG;
  dal_events *own = NULL;
  dal_state *st;
  int rc = ev || !sc->nev ? DAL_OK : dal_scene_events(sc, &own);
  if (!rc) rc = dal_scene_state(sc, &st);
  if (rc) {
    if (msg && msglen)
      snprintf(msg, msglen, "%s: the initial state: %s", sc->name, dal_status_string(rc));
    dal_events_destroy(own);
    return rc;
  }
  dal_events *use = ev ? ev : own;
  if (use) rc = dal_state_set_events(st, use);
  dal_csv c = {csv, 0, 0};
  if (!rc)
    rc = dal_evolve(sc->sys, st, &sc->opts, sc->t1, sc->dt, csv ? dal_csv_monitor : NULL,
                    csv ? &c : NULL);
  if (rc && msg && msglen) snprintf(msg, msglen, "%s: %s", sc->name, dal_state_errmsg(st));
  dal_state_set_events(st, NULL);
  dal_events_destroy(own);
  if (stp)
    *stp = st;
  else
    dal_state_destroy(st);
  return rc;
}

int dal_scene_run(const dal_scene *sc, FILE *csv, dal_state **stp, char *msg, size_t msglen) {
  return dal_scene_run_events(sc, csv, NULL, stp, msg, msglen);
}
