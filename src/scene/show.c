// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A scene's equations: positions as formulas, T, U, L, M, F and the state derivative.
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"

// the formulas of the built-in maps: $name is a parameter, $0 $1 the coordinates, $px $py $pz
// the parent's position
typedef struct tmpl {
  const char *prim;
  const char *f[3];
} tmpl;

static const tmpl maps[] = {
    {"pendulum",
     {"$x0 + $ax*cos($w*t + $ph) + $l*sin($0)", "$y0 + $ay*cos($w*t + $ph) - $l*cos($0)"}},
    {"hanging", {"$px + $l*sin($0)", "$py - $l*cos($0)"}},
    {"ring", {"$R*sin($0)*cos($w*t + $phi0)", "$R*sin($0)*sin($w*t + $phi0)", "-$R*cos($0)"}},
    {"spherical", {"$x0 + $l*sin($0)*cos($1)", "$y0 + $l*sin($0)*sin($1)", "$z0 - $l*cos($0)"}},
    {"sphere", {"$cx + $R*sin($0)*cos($1)", "$cy + $R*sin($0)*sin($1)", "$cz + $R*cos($0)"}},
    {"cartesian2", {"$0", "$1"}},
    {"cartesian3", {"$0", "$1", "$2"}},
    {"fixed2", {"$x", "$y"}},
    {"fixed3", {"$x", "$y", "$z"}},
};

typedef struct str {
  char *s;
  size_t n, cap;
} str;

static int add(str *b, const char *s, size_t n) {
  if (b->n + n + 1 > b->cap) {
    size_t cap = b->cap ? b->cap : 128;
    while (cap < b->n + n + 1)
      cap *= 2;
    char *v = realloc(b->s, cap);
    if (!v) return -1;
    b->s = v;
    b->cap = cap;
  }
  memcpy(b->s + b->n, s, n);
  b->n += n;
  b->s[b->n] = 0;
  return 0;
}

static int adds(str *b, const char *s) { return add(b, s, strlen(s)); }

// replace whole identifiers `from[i]` by "(to[i])" in text
static char *subst(const char *text, char *const *from, char *const *to, int n) {
  str b = {0};
  adds(&b, "");
  for (const char *s = text; *s;) {
    if (isalpha((unsigned char)*s) || *s == '_') {
      size_t k = 0;
      while (isalnum((unsigned char)s[k]) || s[k] == '_')
        k++;
      int j = -1;
      for (int i = 0; i < n; ++i)
        if (strlen(from[i]) == k && !strncmp(from[i], s, k)) j = i;
      if (j >= 0) {
        adds(&b, "(");
        adds(&b, to[j]);
        adds(&b, ")");
      } else {
        add(&b, s, k);
      }
      s += k;
    } else {
      add(&b, s, 1);
      s++;
    }
  }
  return b.s;
}

// a built-in map's template filled in: parameters from the line (formulas) or defaults
static char *fill(const char *t, const dal_primitive *prim, const sline *l, const char *const *cn,
                  int nc, char *const *parent) {
  str b = {0};
  adds(&b, "");
  for (const char *s = t; *s;) {
    if (*s != '$') {
      add(&b, s, 1);
      s++;
      continue;
    }
    s++;
    size_t k = 0;
    while (isalnum((unsigned char)s[k]) || s[k] == '_')
      k++;
    char key[32];
    snprintf(key, sizeof key, "%.*s", (int)(k < 31 ? k : 31), s);
    s += k;
    adds(&b, "(");
    if (isdigit((unsigned char)key[0])) {
      int i = atoi(key);
      adds(&b, i < nc ? cn[i] : "?");
    } else if (key[0] == 'p' && key[1] && strchr("xyz", key[1]) && !key[2] && parent) {
      adds(&b, parent[key[1] - 'x']);
    } else {
      const char *v = dal__scene_kv(l, 3, key);
      char num[40] = "0";
      if (!v)
        for (int i = 0; i < prim->nparam && prim->param_names; ++i)
          if (!strcmp(prim->param_names[i], key) && prim->param_defaults)
            snprintf(num, sizeof num, "%.17g", prim->param_defaults[i]);
      adds(&b, v ? v : num);
    }
    adds(&b, ")");
  }
  return b.s;
}

static int print_eq(FILE *fp, const char *lhs, const dal_expr *e, int k, dal_expr_format fmt) {
  int n = dal_expr_print(e, k, fmt, NULL, 0);
  if (n < 0) return n;
  char *buf = malloc((size_t)n + 1);
  if (!buf) return DAL_E_NOMEM;
  dal_expr_print(e, k, fmt, buf, (size_t)n + 1);
  if (fmt == DAL_EXPR_LATEX)
    fprintf(fp, "$$%s = %s$$\n", lhs, buf);
  else
    fprintf(fp, "%s = %s\n", lhs, buf);
  free(buf);
  return DAL_OK;
}

// a coordinate's name in LaTeX (Greek letters, accents), through a one-symbol expression
static void latex_sym(const char *name, char *out, size_t len) {
  snprintf(out, len, "%s", name);
  dal_expr_def d = dal_default_expr_def();
  d.formulas = &name;
  d.nout = 1;
  d.inputs = &name;
  d.nin = 1;
  dal_expr *e;
  if (!dal_expr_create(&d, &e, NULL, 0)) {
    dal_expr_print(e, 0, DAL_EXPR_LATEX, out, len);
    dal_expr_destroy(e);
  }
}

static int show_equations(const dal_scene *sc, FILE *fp, dal_expr_format fmt, dal_expr *T,
                          dal_expr *U, dal_expr *L, char *msg, size_t msglen) {
  int rc = DAL_OK;
  if (T) rc = print_eq(fp, "T", T, 0, fmt);
  if (!rc && U) rc = print_eq(fp, "U", U, 0, fmt);
  if (!rc) rc = print_eq(fp, "L", L, 0, fmt);
  dal_expr_equations eq;
  if (!rc) rc = dal_expr_lagrange(L, &eq, msg, msglen);
  if (rc) return rc;
  int n = eq.n;
  char lhs[160];
  for (int i = 0; i < n && !rc; ++i) {
    char nm[96];
    latex_sym(sc->cname[i], nm, sizeof nm);
    snprintf(lhs, sizeof lhs, fmt == DAL_EXPR_LATEX ? "p_{%s}" : "p_%s",
             fmt == DAL_EXPR_LATEX ? nm : sc->cname[i]);
    rc = print_eq(fp, lhs, eq.momentum, i, fmt);
  }
  for (int i = 0; i < n * n && !rc; ++i) {
    snprintf(lhs, sizeof lhs, fmt == DAL_EXPR_LATEX ? "M_{%d%d}" : "M_%d%d", i / n + 1, i % n + 1);
    rc = print_eq(fp, lhs, eq.mass, i, fmt);
  }
  for (int i = 0; i < n && !rc; ++i) {
    char nm[96];
    latex_sym(sc->cname[i], nm, sizeof nm);
    snprintf(lhs, sizeof lhs, fmt == DAL_EXPR_LATEX ? "F_{%s}" : "F_%s",
             fmt == DAL_EXPR_LATEX ? nm : sc->cname[i]);
    rc = print_eq(fp, lhs, eq.force, i, fmt);
  }
  if (!rc && n > 1)
    fprintf(fp, "%s", fmt == DAL_EXPR_LATEX ? "$$M \\ddot{q} = F$$\n" : "M qddot = F\n");
  if (!rc && eq.accel) {
    if (fmt == DAL_EXPR_SCHEME) {
      int k = dal_expr_print(eq.accel, 0, fmt, NULL, 0);
      char *buf = k >= 0 ? malloc((size_t)k + 1) : NULL;
      if (buf) {
        dal_expr_print(eq.accel, 0, fmt, buf, (size_t)k + 1);
        fprintf(fp, "state derivative = (up 1 %sdot %s)\n", sc->cname[0], buf);
        free(buf);
      } else {
        rc = DAL_E_NOMEM;
      }
    } else {
      snprintf(lhs, sizeof lhs, fmt == DAL_EXPR_LATEX ? "\\ddot{%s}" : "%sddot", sc->cname[0]);
      if (fmt == DAL_EXPR_LATEX) {
        char nm[96];
        latex_sym(sc->cname[0], nm, sizeof nm);
        snprintf(lhs, sizeof lhs, "\\ddot{%s}", nm);
      }
      rc = print_eq(fp, lhs, eq.accel, 0, fmt);
    }
  }
  dal_expr_equations_destroy(&eq);
  return rc;
}

int dal_scene_show(const dal_scene *sc, FILE *fp, dal_expr_format fmt, char *msg, size_t msglen) {
  if (msg && msglen) msg[0] = 0;
  if (!sc || !fp) return DAL_E_ARG;
  int rc = DAL_OK, d = sc->dim;
  // a Lagrangian scene: L as written
  for (int i = 0; i < sc->nlines; ++i) {
    const sline *l = &sc->lines[i];
    if (!strcmp(l->tok[0], "lagrangian")) {
      dal_expr_def ed = dal_default_expr_def();
      ed.name = "L";
      ed.formulas = (const char *const *)l->f;
      ed.nout = 1;
      ed.inputs = (const char *const *)sc->cname;
      ed.nin = sc->ncoord;
      ed.velocities = 1;
      ed.params = (const char *const *)sc->pname;
      ed.values = sc->pval;
      ed.nparam = sc->nparam;
      dal_expr *L;
      rc = dal_expr_create(&ed, &L, msg, msglen);
      if (!rc) rc = show_equations(sc, fp, fmt, NULL, NULL, L, msg, msglen);
      dal_expr_destroy(L);
      return rc;
    }
  }
  // particles: positions as formulas, masses, gravity, potentials (springs included)
  int np = sc->npart;
  char **pos = calloc((size_t)np * (size_t)d + 1, sizeof *pos);
  char **mass = calloc((size_t)np + 1, sizeof *mass);
  char *grav[3] = {NULL, NULL, NULL};
  str pot = {0};
  adds(&pot, "");
  if (!pos || !mass) rc = DAL_E_NOMEM;
  int k = 0;
  for (int i = 0; i < sc->nlines && !rc; ++i) {
    const sline *l = &sc->lines[i];
    const char *kw = l->tok[0];
    if (!strcmp(kw, "particle")) {
      mass[k++] = (char *)dal__scene_kv(l, 2, "mass");
    } else if (!strcmp(kw, "place")) {
      int p = dal__scene_find(sc->partname, sc->npart, l->tok[1]);
      const char *ps = dal__scene_kv(l, 2, "parent");
      int parent = ps ? dal__scene_find(sc->partname, sc->npart, ps) : -1;
      char *par[3] = {NULL, NULL, NULL};
      if (parent >= 0)
        for (int c = 0; c < d; ++c)
          par[c] = pos[parent * d + c];
      if (l->nf) {
        // the formulas, the parent's x_<p> replaced by its position
        char *from[3], *to[3];
        char nm[3][80];
        for (int c = 0; c < d; ++c) {
          snprintf(nm[c], sizeof nm[c], "%c_%s", "xyz"[c], parent >= 0 ? ps : "");
          from[c] = nm[c];
          to[c] = par[c] ? par[c] : "0";
        }
        for (int c = 0; c < d; ++c)
          pos[p * d + c] = subst(l->f[c], from, to, parent >= 0 ? d : 0);
      } else {
        const tmpl *t = NULL;
        for (size_t j = 0; j < sizeof maps / sizeof maps[0]; ++j)
          if (!strcmp(maps[j].prim, l->tok[2])) t = &maps[j];
        if (!t) {
          rc = DAL_E_UNSUPPORTED;
          if (msg && msglen)
            snprintf(msg, msglen, "%s:%d: place %s: the primitive '%s' has no formulas to show",
                     sc->name, l->line, l->tok[1], l->tok[2]);
          break;
        }
        const char *cn[8];
        int nc = 0;
        for (int j = 3; j < l->ntok && nc < 8; ++j)
          if (!strchr(l->tok[j], '=')) cn[nc++] = l->tok[j];
        for (int c = 0; c < d; ++c)
          pos[p * d + c] = fill(t->f[c], dal_primitive_find(l->tok[2]), l, cn, nc, par);
      }
    } else if (!strcmp(kw, "gravity")) {
      for (int c = 0; c < d; ++c)
        grav[c] = l->tok[1 + c];
    } else if (!strcmp(kw, "potential")) {
      adds(&pot, pot.n ? " + " : "");
      adds(&pot, l->f[0]);
    } else if (!strcmp(kw, "spring")) {
      int a = dal__scene_find(sc->partname, sc->npart, l->tok[1]);
      int b = strchr(l->tok[2], '=') ? -1 : dal__scene_find(sc->partname, sc->npart, l->tok[2]);
      const char *kk = dal__scene_kv(l, 2, "k"), *LL = dal__scene_kv(l, 2, "L");
      const char *an = dal__scene_kv(l, 2, "anchor");
      char anc[3][128] = {"0", "0", "0"};
      if (an) {
        char buf[512];
        snprintf(buf, sizeof buf, "%s", an);
        int c = 0;
        for (char *sv = NULL, *s = strtok_r(buf, ",", &sv); s && c < 3;
             s = strtok_r(NULL, ",", &sv), ++c)
          snprintf(anc[c], sizeof anc[c], "%s", s);
      }
      adds(&pot, pot.n ? " + 1/2*(" : "1/2*(");
      adds(&pot, kk ? kk : "0");
      adds(&pot, ")*(sqrt(");
      for (int c = 0; c < d; ++c) {
        adds(&pot, c ? " + ((" : "((");
        adds(&pot, pos[a * d + c] ? pos[a * d + c] : "0");
        adds(&pot, ") - (");
        adds(&pot, b >= 0 ? (pos[b * d + c] ? pos[b * d + c] : "0") : anc[c]);
        adds(&pot, "))^2");
      }
      adds(&pot, ") - (");
      adds(&pot, LL ? LL : "0");
      adds(&pot, "))^2");
    } else if (!strcmp(kw, "constraint") || !strcmp(kw, "damper")) {
      rc = DAL_E_UNSUPPORTED;
      if (msg && msglen)
        snprintf(msg, msglen,
                 "%s:%d: %s %s: the equations of scenes with constraints or dampers are not "
                 "shown (minimal coordinates and conservative forces only)",
                 sc->name, l->line, kw, l->tok[1]);
    }
  }
  for (int i = 0; i < np * d && !rc; ++i)
    if (!pos[i]) {
      rc = DAL_E_UNSUPPORTED;
      if (msg && msglen)
        snprintf(msg, msglen, "%s: particle '%s' is not placed by formulas", sc->name,
                 sc->partname[i / d]);
    }
  if (!rc) {
    // the positions, simplified (a name with '_' in LaTeX text mode is left as it is)
    for (int p = 0; p < np && !rc; ++p)
      for (int c = 0; c < d && !rc; ++c) {
        dal_expr_def ed = dal_default_expr_def();
        ed.name = sc->partname[p];
        ed.formulas = (const char *const *)&pos[p * d + c];
        ed.nout = 1;
        ed.inputs = (const char *const *)sc->cname;
        ed.nin = sc->ncoord;
        ed.params = (const char *const *)sc->pname;
        ed.values = sc->pval;
        ed.nparam = sc->nparam;
        dal_expr *e;
        rc = dal_expr_create(&ed, &e, msg, msglen);
        char lhs[96];
        snprintf(lhs, sizeof lhs, fmt == DAL_EXPR_LATEX ? "%c_{\\mathrm{%s}}" : "%c_%s", "xyz"[c],
                 sc -> partname[p]);
        if (!rc) rc = print_eq(fp, lhs, e, 0, fmt);
        dal_expr_destroy(e);
      }
  }
  if (!rc) {
    dal_expr_model_def md = dal_default_expr_model_def();
    md.name = sc->name;
    md.dim = d;
    md.coords = (const char *const *)sc->cname;
    md.ncoords = sc->ncoord;
    md.masses = (const char *const *)mass;
    md.nparticles = np;
    md.positions = (const char *const *)pos;
    md.gravity = grav[0] ? (const char *const *)grav : NULL;
    md.potential = pot.n ? pot.s : NULL;
    md.params = (const char *const *)sc->pname;
    md.values = sc->pval;
    md.nparam = sc->nparam;
    dal_expr *T, *U, *L;
    rc = dal_expr_model_energies(&md, &T, &U, &L, msg, msglen);
    if (!rc) rc = show_equations(sc, fp, fmt, T, U, L, msg, msglen);
    dal_expr_destroy(T);
    dal_expr_destroy(U);
    dal_expr_destroy(L);
  }
  if (pos)
    for (int i = 0; i < np * d; ++i)
      free(pos[i]);
  free(pos);
  free(mass);
  free(pot.s);
  if (!rc && ferror(fp)) rc = DAL_E_IO;
  return rc;
}
