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

// the rows of the built-in constraints as formulas: #ax #ay #az the position of the first part,
// #bx ... of the second (the symbols x_<part>), $name a parameter, $0 the first coordinate
static const struct {
  const char *prim;
  const char *f[2];
} cons[] = {
    {"distance2", {"sqrt((#bx - #ax)^2 + (#by - #ay)^2) - $L"}},
    {"distance3", {"sqrt((#bx - #ax)^2 + (#by - #ay)^2 + (#bz - #az)^2) - $L"}},
    {"anchor2", {"sqrt((#ax - $x0)^2 + (#ay - $y0)^2) - $L"}},
    {"anchor3", {"sqrt((#ax - $x0)^2 + (#ay - $y0)^2 + (#az - $z0)^2) - $L"}},
    {"on_circle2", {"sqrt((#ax - $cx)^2 + (#ay - $cy)^2) - $R"}},
    {"on_circle3",
     {"($nx*(#ax - $cx) + $ny*(#ay - $cy) + $nz*(#az - $cz))/sqrt($nx^2 + $ny^2 + $nz^2)",
      "sqrt((#ax - $cx)^2 + (#ay - $cy)^2 + (#az - $cz)^2 - ($nx*(#ax - $cx) + $ny*(#ay - $cy) + "
      "$nz*(#az - $cz))^2/($nx^2 + $ny^2 + $nz^2)) - $R"}},
    {"turning_circle",
     {"(#ay - $cy)*cos($w*t + $phi0) - (#ax - $cx)*sin($w*t + $phi0)",
      "sqrt((#ax - $cx)^2 + (#ay - $cy)^2 + (#az - $cz)^2) - $R"}},
    {"on_sphere", {"sqrt((#ax - $cx)^2 + (#ay - $cy)^2 + (#az - $cz)^2) - $R"}},
    {"on_plane",
     {"($nx*(#ax - $cx) + $ny*(#ay - $cy) + $nz*(#az - $cz))/sqrt($nx^2 + $ny^2 + $nz^2)"}},
    {"on_line2", {"($ax*(#ay - $cy) - $ay*(#ax - $cx))/sqrt($ax^2 + $ay^2)"}},
    {"turning_line2", {"(#ay - $cy)*cos($w*t + $phi0) - (#ax - $cx)*sin($w*t + $phi0)"}},
    {"prescribed", {"$0 - $q0"}},
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
                  int nc, char *const *parent, char *const *parts, int np) {
  str b = {0};
  adds(&b, "");
  for (const char *s = t; *s;) {
    if (*s == '#' && (s[1] == 'a' || s[1] == 'b') && s[2] && strchr("xyz", s[2])) {
      int k = s[1] - 'a';
      adds(&b, s[2] == 'x' ? "x_" : s[2] == 'y' ? "y_" : "z_");
      adds(&b, k < np ? parts[k] : "?");
      s += 3;
      continue;
    }
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

// formula k of e as text that reads back (malloc'd; NULL when out of memory)
static char *text_of(const dal_expr *e, int k) {
  int n = dal_expr_print(e, k, DAL_EXPR_TEXT, NULL, 0);
  char *buf = n >= 0 ? malloc((size_t)n + 1) : NULL;
  if (buf) dal_expr_print(e, k, DAL_EXPR_TEXT, buf, (size_t)n + 1);
  return buf;
}

// a formula over the coordinates (and their rates when vel), t and the parameters
static int compile(const dal_scene *sc, const char *name, const char *f, int vel, dal_expr **e,
                   char *msg, size_t msglen) {
  return dal__scene_expr(sc, name, &f, 1, (const char *const *)sc->cname, sc->ncoord, vel, e, msg,
                         msglen);
}

// what the lines give beyond T and U: the damping forces (Rayleigh's D) and the constraints
typedef struct extras {
  str D;    // D(q, qdot, t) = sum 1/2 c |v_a - v_b|^2 ("" when no damper)
  str *phi; // the constraint rows as formulas of q and t
  char **name;
  int nphi;
  str *gq;    // the force lines' sum per coordinate (ncoord; "" when none)
  int forced; // some force line
} extras;

// the generalized forces of the dampers, -dD/dqdot_i, into Q (n formulas as text)
static int damping(const dal_scene *sc, const extras *x, char **Q, char *msg, size_t msglen) {
  dal_expr *D = NULL;
  int rc = compile(sc, "D", x->D.s, 1, &D, msg, msglen);
  for (int i = 0; i < sc->ncoord && !rc; ++i) {
    dal_expr *dD;
    rc = dal_expr_derivative(D, 0, sc->ncoord + i, &dD, msg, msglen);
    if (rc) break;
    char *t = text_of(dD, 0);
    str q = {0};
    if (t && !adds(&q, "-(") && !adds(&q, t) && !adds(&q, ")"))
      Q[i] = q.s;
    else
      rc = DAL_E_NOMEM, free(q.s);
    free(t);
    dal_expr_destroy(dD);
  }
  dal_expr_destroy(D);
  return rc;
}

// the cofactor expansion of det of the k x k submatrix of M (texts, row-major n x n) with
// rows r[0..k-1] and columns c[0..k-1]; column `col` replaced by the texts b when b is set
static int det(char **M, int n, const int *r, const int *c, int k, int col, char **b, str *out) {
  if (k == 1) {
    adds(out, "(");
    adds(out, c[0] == col ? b[r[0]] : M[r[0] * n + c[0]]);
    return adds(out, ")");
  }
  adds(out, "(");
  for (int j = 0; j < k; ++j) {
    int cc[3], m = 0;
    for (int i = 0; i < k; ++i)
      if (i != j) cc[m++] = c[i];
    adds(out, j ? (j % 2 ? " - " : " + ") : "");
    adds(out, "(");
    adds(out, c[j] == col ? b[r[0]] : M[r[0] * n + c[j]]);
    adds(out, ")*");
    det(M, n, r + 1, cc, k - 1, col, b, out);
  }
  return adds(out, ")");
}

// qddot_i = det(M with column i replaced by F) / det(M) (Cramer's rule, n <= 3), printed
static int accel_cramer(const dal_scene *sc, FILE *fp, dal_expr_format fmt,
                        const dal_expr_equations *eq, char **Q, char *msg, size_t msglen) {
  int n = eq->n, rc = DAL_OK, idx[3] = {0, 1, 2};
  char *M[9] = {0}, *F[3] = {0};
  for (int i = 0; i < n * n && !rc; ++i)
    if (!(M[i] = text_of(eq->mass, i))) rc = DAL_E_NOMEM;
  for (int i = 0; i < n && !rc; ++i) {
    char *f = text_of(eq->force, i);
    str s = {0};
    if (f && !adds(&s, f) && (!Q || (!adds(&s, " + ") && !adds(&s, Q[i]))))
      F[i] = s.s;
    else
      rc = DAL_E_NOMEM, free(s.s);
    free(f);
  }
  for (int i = 0; i < n && !rc; ++i) {
    str a = {0};
    adds(&a, "");
    det(M, n, idx, idx, n, i, F, &a);
    adds(&a, "/");
    det(M, n, idx, idx, n, -1, F, &a);
    dal_expr *e = NULL;
    rc = a.s ? compile(sc, "qddot", a.s, 1, &e, msg, msglen) : DAL_E_NOMEM;
    free(a.s);
    char lhs[160], nm[96];
    latex_sym(sc->cname[i], nm, sizeof nm);
    snprintf(lhs, sizeof lhs, fmt == DAL_EXPR_LATEX ? "\\ddot{%s}" : "%sddot",
             fmt == DAL_EXPR_LATEX ? nm : sc->cname[i]);
    if (!rc) rc = print_eq(fp, lhs, e, 0, fmt);
    dal_expr_destroy(e);
  }
  for (int i = 0; i < 9; ++i)
    free(M[i]);
  for (int i = 0; i < 3; ++i)
    free(F[i]);
  return rc;
}

// the state derivative of one coordinate as SICM prints it, or qddot = ...
static int accel_one(const dal_scene *sc, FILE *fp, dal_expr_format fmt, const dal_expr *accel) {
  char lhs[160];
  if (fmt == DAL_EXPR_SCHEME) {
    int k = dal_expr_print(accel, 0, fmt, NULL, 0);
    char *s = k >= 0 ? malloc((size_t)k + 1) : NULL;
    if (!s) return DAL_E_NOMEM;
    dal_expr_print(accel, 0, fmt, s, (size_t)k + 1);
    fprintf(fp, "state derivative = (up 1 %sdot %s)\n", sc->cname[0], s);
    free(s);
    return DAL_OK;
  }
  char nm[96];
  latex_sym(sc->cname[0], nm, sizeof nm);
  snprintf(lhs, sizeof lhs, fmt == DAL_EXPR_LATEX ? "\\ddot{%s}" : "%sddot",
           fmt == DAL_EXPR_LATEX ? nm : sc->cname[0]);
  return print_eq(fp, lhs, accel, 0, fmt);
}

// p_i, M_ij and F_i of Lagrange's equations
static int show_pmf(const dal_scene *sc, FILE *fp, dal_expr_format fmt,
                    const dal_expr_equations *eq) {
  int n = eq->n, rc = DAL_OK;
  char lhs[160], nm[96];
  for (int i = 0; i < n && !rc; ++i) {
    latex_sym(sc->cname[i], nm, sizeof nm);
    snprintf(lhs, sizeof lhs, fmt == DAL_EXPR_LATEX ? "p_{%s}" : "p_%s",
             fmt == DAL_EXPR_LATEX ? nm : sc->cname[i]);
    rc = print_eq(fp, lhs, eq->momentum, i, fmt);
  }
  for (int i = 0; i < n * n && !rc; ++i) {
    snprintf(lhs, sizeof lhs, fmt == DAL_EXPR_LATEX ? "M_{%d%d}" : "M_%d%d", i / n + 1, i % n + 1);
    rc = print_eq(fp, lhs, eq->mass, i, fmt);
  }
  for (int i = 0; i < n && !rc; ++i) {
    latex_sym(sc->cname[i], nm, sizeof nm);
    snprintf(lhs, sizeof lhs, fmt == DAL_EXPR_LATEX ? "F_{%s}" : "F_%s",
             fmt == DAL_EXPR_LATEX ? nm : sc->cname[i]);
    rc = print_eq(fp, lhs, eq->force, i, fmt);
  }
  return rc;
}

// a formula of q and t printed under the name lhs
static int print_text(const dal_scene *sc, FILE *fp, dal_expr_format fmt, const char *lhs,
                      const char *f, int vel, char *msg, size_t msglen) {
  dal_expr *e = NULL;
  int rc = compile(sc, lhs, f, vel, &e, msg, msglen);
  if (!rc) rc = print_eq(fp, lhs, e, 0, fmt);
  dal_expr_destroy(e);
  return rc;
}

// the constraint rows phi and their Jacobian G = dphi/dq
static int show_constraints(const dal_scene *sc, FILE *fp, dal_expr_format fmt, const extras *x,
                            char *msg, size_t msglen) {
  int rc = DAL_OK;
  char lhs[200];
  for (int r = 0; r < x->nphi && !rc; ++r) {
    snprintf(lhs, sizeof lhs, fmt == DAL_EXPR_LATEX ? "\\phi_{\\mathrm{%s}}" : "phi_%s",
             x->name[r]);
    rc = print_text(sc, fp, fmt, lhs, x->phi[r].s, 0, msg, msglen);
    dal_expr *e = NULL;
    if (!rc) rc = compile(sc, lhs, x->phi[r].s, 0, &e, msg, msglen);
    for (int j = 0; j < sc->ncoord && !rc; ++j) {
      dal_expr *g = NULL;
      rc = dal_expr_derivative(e, 0, j, &g, msg, msglen);
      snprintf(lhs, sizeof lhs, fmt == DAL_EXPR_LATEX ? "G_{\\mathrm{%s},%s}" : "G_%s,%s",
               x->name[r], sc->cname[j]);
      if (!rc) rc = print_eq(fp, lhs, g, 0, fmt);
      dal_expr_destroy(g);
    }
    dal_expr_destroy(e);
  }
  if (!rc)
    fprintf(fp, "%s",
            fmt == DAL_EXPR_LATEX ? "$$M \\ddot{q} = F + G^T \\lambda, \\quad \\phi = 0$$\n"
                                  : "M qddot = F + G' lambda, phi = 0\n");
  return rc;
}

static int show_equations(const dal_scene *sc, FILE *fp, dal_expr_format fmt, dal_expr *T,
                          dal_expr *U, dal_expr *L, const extras *x, char *msg, size_t msglen) {
  int rc = DAL_OK, damped = x && x->D.n;
  if (T) rc = print_eq(fp, "T", T, 0, fmt);
  if (!rc && U) rc = print_eq(fp, "U", U, 0, fmt);
  if (!rc) rc = print_eq(fp, "L", L, 0, fmt);
  if (!rc && damped) rc = print_text(sc, fp, fmt, "D", x->D.s, 1, msg, msglen);
  dal_expr_equations eq;
  if (!rc) rc = dal_expr_lagrange(L, &eq, msg, msglen);
  if (rc) return rc;
  int n = eq.n;
  char **Q = calloc((size_t)n + 1, sizeof *Q), lhs[160];
  rc = Q ? show_pmf(sc, fp, fmt, &eq) : DAL_E_NOMEM;
  if (!rc && damped) rc = damping(sc, x, Q, msg, msglen);
  // the force lines' generalized forces join the dampers' Q
  for (int i = 0; i < n && x && x->forced && !rc; ++i) {
    str q = {0};
    if (adds(&q, Q[i] ? Q[i] : "0") || adds(&q, " + (") ||
        adds(&q, x->gq[i].n ? x->gq[i].s : "0") || adds(&q, ")"))
      rc = DAL_E_NOMEM;
    free(Q[i]);
    Q[i] = q.s;
  }
  damped = damped || (x && x->forced);
  for (int i = 0; i < n && damped && !rc; ++i) {
    snprintf(lhs, sizeof lhs, fmt == DAL_EXPR_LATEX ? "Q_{%s}" : "Q_%s", sc->cname[i]);
    rc = print_text(sc, fp, fmt, lhs, Q[i], 1, msg, msglen);
  }
  if (!rc && x && x->nphi) {
    rc = show_constraints(sc, fp, fmt, x, msg, msglen);
  } else if (!rc) {
    if (n > 1 || damped)
      fprintf(fp, "%s",
              fmt == DAL_EXPR_LATEX
                  ? (damped ? "$$M \\ddot{q} = F + Q$$\n" : "$$M \\ddot{q} = F$$\n")
                  : (damped ? "M qddot = F + Q\n" : "M qddot = F\n"));
    if (eq.accel && !damped)
      rc = accel_one(sc, fp, fmt, eq.accel);
    else if (n <= 3)
      rc = accel_cramer(sc, fp, fmt, &eq, damped ? Q : NULL, msg, msglen);
  }
  for (int i = 0; Q && i < n; ++i)
    free(Q[i]);
  free(Q);
  dal_expr_equations_destroy(&eq);
  return rc;
}

// the positions, masses, gravity and potential the lines give (formulas as text)
typedef struct model {
  int np, d;
  char **pos;  // np x d
  char **mass; // np, borrowed from the lines
  char *grav[3];
  str pot;
} model;

// a placement: by formulas (the parent's x_<p> replaced by its position) or a built-in map
static int collect_place(const dal_scene *sc, const sline *l, model *m, char *msg, size_t len) {
  int d = m->d, p = dal__scene_part(sc, l->tok[1]);
  const char *ps = dal__scene_kv(l, 2, "parent");
  int parent = ps ? dal__scene_part(sc, ps) : -1;
  char *par[3] = {NULL, NULL, NULL};
  if (parent >= 0)
    for (int c = 0; c < d; ++c)
      par[c] = m->pos[parent * d + c];
  if (l->nf) {
    char *from[3], *to[3], nm[3][80];
    for (int c = 0; c < d; ++c) {
      snprintf(nm[c], sizeof nm[c], "%c_%s", "xyz"[c], parent >= 0 ? ps : "");
      from[c] = nm[c];
      to[c] = par[c] ? par[c] : "0";
    }
    for (int c = 0; c < d; ++c)
      m->pos[p * d + c] = subst(l->f[c], from, to, parent >= 0 ? d : 0);
    return DAL_OK;
  }
  const tmpl *t = NULL;
  for (size_t j = 0; j < sizeof maps / sizeof maps[0]; ++j)
    if (!strcmp(maps[j].prim, l->tok[2])) t = &maps[j];
  if (!t) {
    if (msg && len)
      snprintf(msg, len, "%s:%d: place %s: the primitive '%s' has no formulas to show", sc->name,
               l->line, l->tok[1], l->tok[2]);
    return DAL_E_UNSUPPORTED;
  }
  const char *cn[8];
  int nc = 0;
  for (int j = 3; j < l->ntok && nc < 8; ++j)
    if (!strchr(l->tok[j], '=')) cn[nc++] = l->tok[j];
  for (int c = 0; c < d; ++c)
    m->pos[p * d + c] = fill(t->f[c], dal_primitive_find(l->tok[2]), l, cn, nc, par, NULL, 0);
  return DAL_OK;
}

// spring a b ... / spring a anchor=..: the other end's position (a particle's or the anchor)
static void other_end(const sline *l, const model *m, const dal_scene *sc, int c, char **anc,
                      const char **end) {
  int b = strchr(l->tok[2], '=') ? -1 : dal__scene_part(sc, l->tok[2]);
  *end = b >= 0 ? (m->pos[b * m->d + c] ? m->pos[b * m->d + c] : "0") : anc[c] ? anc[c] : "0";
}

// the anchor's components as texts (malloc'd; NULL: 0)
static void anchor_of(const sline *l, char **anc) {
  const char *an = dal__scene_kv(l, 2, "anchor");
  for (int c = 0; c < 3; ++c)
    anc[c] = NULL;
  for (int c = 0; an && c < 3; ++c) {
    size_t w = strcspn(an, ",");
    str t = {0};
    add(&t, an, w);
    anc[c] = t.s;
    an = an[w] ? an + w + 1 : NULL;
  }
}

// a spring's potential 1/2 k (|r_a - r_b| - L)^2 added to U
static void collect_spring(const dal_scene *sc, const sline *l, model *m) {
  int a = dal__scene_part(sc, l->tok[1]);
  const char *kk = dal__scene_kv(l, 2, "k"), *LL = dal__scene_kv(l, 2, "L"), *end;
  char *anc[3];
  anchor_of(l, anc);
  adds(&m->pot, m->pot.n ? " + 1/2*(" : "1/2*(");
  adds(&m->pot, kk ? kk : "0");
  adds(&m->pot, ")*(sqrt(");
  for (int c = 0; c < m->d; ++c) {
    other_end(l, m, sc, c, anc, &end);
    adds(&m->pot, c ? " + ((" : "((");
    adds(&m->pot, m->pos[a * m->d + c] ? m->pos[a * m->d + c] : "0");
    adds(&m->pot, ") - (");
    adds(&m->pot, end);
    adds(&m->pot, "))^2");
  }
  adds(&m->pot, ") - (");
  adds(&m->pot, LL ? LL : "0");
  adds(&m->pot, "))^2");
  for (int c = 0; c < 3; ++c)
    free(anc[c]);
}

// the velocity of position formula r: sum_j dr/dq_j qdot_j + dr/dt, as text (into v)
static int velocity(const dal_scene *sc, const char *r, str *v, char *msg, size_t len) {
  dal_expr *e = NULL;
  int rc = compile(sc, "v", r, 0, &e, msg, len);
  adds(v, "(0");
  for (int j = -1; j < sc->ncoord && !rc; ++j) {
    dal_expr *dr = NULL;
    rc = dal_expr_derivative(e, 0, j, &dr, msg, len);
    char *t = rc ? NULL : text_of(dr, 0);
    if (!rc && !t) rc = DAL_E_NOMEM;
    if (!rc) {
      adds(v, " + (");
      adds(v, t);
      adds(v, j >= 0 ? ")*" : ")");
      if (j >= 0) adds(v, sc->cname[j]), adds(v, "dot");
    }
    free(t);
    dal_expr_destroy(dr);
  }
  dal_expr_destroy(e);
  return rc ? rc : adds(v, ")") ? DAL_E_NOMEM : DAL_OK;
}

// a damper's Rayleigh function along its axis, 1/2 c ((r_a - r_b) . (v_a - v_b))^2 / |r_a - r_b|^2
// (the library's damper force -c ((v_a - v_b) . e) e), added to D
static int collect_damper(const dal_scene *sc, const sline *l, const model *m, extras *x, char *msg,
                          size_t len) {
  int a = dal__scene_part(sc, l->tok[1]), rc = DAL_OK, d = m->d;
  int b = strchr(l->tok[2], '=') ? -1 : dal__scene_part(sc, l->tok[2]);
  const char *c = dal__scene_kv(l, 2, "c"), *end;
  char *anc[3];
  anchor_of(l, anc);
  str dr = {0}, dist = {0};
  adds(&dist, "(0");
  for (int k = 0; k < d; ++k) {
    other_end(l, m, sc, k, anc, &end);
    const char *ra = m->pos[a * d + k] ? m->pos[a * d + k] : "0";
    free(dr.s);
    dr = (str){0};
    adds(&dr, "((");
    adds(&dr, ra);
    adds(&dr, ") - (");
    adds(&dr, end);
    adds(&dr, "))");
    adds(&dist, " + ");
    adds(&dist, dr.s);
    adds(&dist, "^2");
  }
  adds(&dist, ")");
  adds(&x->D, x->D.n ? " + 1/2*(" : "1/2*(");
  adds(&x->D, c ? c : "0");
  adds(&x->D, ")*(0");
  for (int k = 0; k < d && !rc; ++k) {
    other_end(l, m, sc, k, anc, &end);
    const char *ra = m->pos[a * d + k] ? m->pos[a * d + k] : "0";
    adds(&x->D, " + ((");
    adds(&x->D, ra);
    adds(&x->D, ") - (");
    adds(&x->D, end);
    adds(&x->D, "))*(");
    rc = velocity(sc, ra, &x->D, msg, len);
    adds(&x->D, " - ");
    if (!rc && b >= 0)
      rc = velocity(sc, end, &x->D, msg, len);
    else
      adds(&x->D, "0");
    adds(&x->D, ")");
  }
  adds(&x->D, ")^2/");
  int bad = adds(&x->D, dist.s ? dist.s : "1");
  free(dr.s);
  free(dist.s);
  for (int k = 0; k < 3; ++k)
    free(anc[k]);
  return rc ? rc : bad || !dist.s ? DAL_E_NOMEM : DAL_OK;
}

// a constraint by formulas or a built-in constraint's rows: the parts' positions x_<p>, y_<p>,
// z_<p> replaced by theirs
static int collect_constraint(const dal_scene *sc, const sline *l, const model *m, extras *x,
                              char *msg, size_t len) {
  int rows = l->nf, t = -1;
  if (!l->nf) {
    for (size_t j = 0; l->ntok > 2 && j < sizeof cons / sizeof *cons; ++j)
      if (!strcmp(cons[j].prim, l->tok[2])) t = (int)j;
    if (t < 0) {
      if (msg && len)
        snprintf(msg, len, "%s:%d: constraint %s: the primitive '%s' has no formulas to show",
                 sc->name, l->line, l->tok[1], l->ntok > 2 ? l->tok[2] : "?");
      return DAL_E_UNSUPPORTED;
    }
    rows = cons[t].f[1] ? 2 : 1;
  }
  // the parts, each name once in the list
  const char *pl = dal__scene_kv(l, 2, "parts");
  int np = 0, d = m->d, rc = DAL_OK;
  for (const char *s = pl; s && *s; ++s)
    np += *s == ',';
  np += pl ? 1 : 0;
  char **pn = calloc((size_t)np + 1, sizeof *pn), **from = calloc((size_t)np * 3 + 1, sizeof *from);
  char **to = calloc((size_t)np * 3 + 1, sizeof *to);
  if (!pn || !from || !to) rc = DAL_E_NOMEM;
  const char *s = pl;
  for (int k = 0; k < np && !rc; ++k) {
    const char *e = strchr(s, ',');
    size_t w = e ? (size_t)(e - s) : strlen(s);
    str nm = {0};
    if (add(&nm, s, w)) rc = DAL_E_NOMEM;
    pn[k] = nm.s;
    int p = pn[k] ? dal__scene_part(sc, pn[k]) : -1;
    for (int c = 0; c < d && !rc; ++c) {
      str f = {0};
      if (adds(&f, c == 0 ? "x_" : c == 1 ? "y_" : "z_") || adds(&f, pn[k])) rc = DAL_E_NOMEM;
      from[k * d + c] = f.s;
      to[k * d + c] = p >= 0 && m->pos[p * d + c] ? m->pos[p * d + c] : "0";
    }
    s = e ? e + 1 : s + w;
  }
  const char *cn[8];
  int nc = 0;
  for (int j = 3; t >= 0 && j < l->ntok && nc < 8; ++j)
    if (!strchr(l->tok[j], '=')) cn[nc++] = l->tok[j];
  str *phi = rc ? NULL : realloc(x->phi, ((size_t)x->nphi + (size_t)rows) * sizeof *phi);
  char **names = phi ? realloc(x->name, ((size_t)x->nphi + (size_t)rows) * sizeof *names) : NULL;
  if (phi) x->phi = phi;
  if (names) x->name = names;
  if (!rc && (!phi || !names)) rc = DAL_E_NOMEM;
  for (int r = 0; r < rows && !rc; ++r) {
    char *row =
        t >= 0 ? fill(cons[t].f[r], dal_primitive_find(l->tok[2]), l, cn, nc, NULL, pn, np) : NULL;
    char *f = subst(t >= 0 ? row : l->f[r], from, to, np * d);
    str nm = {0};
    x->phi[x->nphi] = (str){0};
    if (!f || adds(&x->phi[x->nphi], f) || adds(&nm, l->tok[1])) rc = DAL_E_NOMEM;
    if (!rc && rows > 1) {
      char k[16];
      snprintf(k, sizeof k, "%d", r + 1);
      rc = adds(&nm, k) ? DAL_E_NOMEM : DAL_OK;
    }
    x->name[x->nphi++] = nm.s;
    free(f);
    free(row);
  }
  for (int k = 0; k < np && pn; ++k)
    free(pn[k]);
  for (int k = 0; k < np * d && from; ++k)
    free(from[k]);
  free(pn);
  free(from);
  free(to);
  return rc;
}

// a force line: Q_i += its formula
static int collect_force(const dal_scene *sc, const sline *l, extras *x) {
  int i = -1;
  for (int j = 0; j < sc->ncoord; ++j)
    if (!strcmp(sc->cname[j], l->tok[1])) i = j;
  if (i < 0) return DAL_E_ARG;
  x->forced = 1;
  if (adds(&x->gq[i], x->gq[i].n ? " + (" : "(") || adds(&x->gq[i], l->f[0]) ||
      adds(&x->gq[i], ")"))
    return DAL_E_NOMEM;
  return DAL_OK;
}

// one line's part of the model; dampers and constraints after every placement (second pass)
static int collect(const dal_scene *sc, const sline *l, model *m, extras *x, int pass, int *k,
                   char *msg, size_t len) {
  const char *kw = l->tok[0];
  if (pass == 1) {
    if (!strcmp(kw, "damper")) return collect_damper(sc, l, m, x, msg, len);
    if (!strcmp(kw, "constraint")) return collect_constraint(sc, l, m, x, msg, len);
    if (!strcmp(kw, "force")) return collect_force(sc, l, x);
    return DAL_OK;
  }
  if (!strcmp(kw, "particle")) m->mass[(*k)++] = (char *)dal__scene_kv(l, 2, "mass");
  if (!strcmp(kw, "place")) return collect_place(sc, l, m, msg, len);
  if (!strcmp(kw, "gravity"))
    for (int c = 0; c < m->d; ++c)
      m->grav[c] = l->tok[1 + c];
  if (!strcmp(kw, "potential")) {
    adds(&m->pot, m->pot.n ? " + " : "");
    adds(&m->pot, l->f[0]);
  }
  if (!strcmp(kw, "spring")) collect_spring(sc, l, m);
  return DAL_OK;
}

// a Lagrangian scene: L as written
static int show_lagrangian(const dal_scene *sc, const sline *l, FILE *fp, dal_expr_format fmt,
                           char *msg, size_t msglen) {
  dal_expr *L = NULL;
  int rc = compile(sc, "L", l->f[0], 1, &L, msg, msglen);
  if (!rc) rc = show_equations(sc, fp, fmt, NULL, NULL, L, NULL, msg, msglen);
  dal_expr_destroy(L);
  return rc;
}

// the positions, simplified (a name with '_' in LaTeX text mode is left as it is)
static int show_positions(const dal_scene *sc, const model *m, FILE *fp, dal_expr_format fmt,
                          char *msg, size_t msglen) {
  int rc = DAL_OK;
  for (int p = 0; p < m->np && !rc; ++p)
    for (int c = 0; c < m->d && !rc; ++c) {
      char lhs[96];
      snprintf(lhs, sizeof lhs, fmt == DAL_EXPR_LATEX ? "%c_{\\mathrm{%s}}" : "%c_%s", "xyz"[c],
               sc -> partname[p]);
      dal_expr *e = NULL;
      rc = compile(sc, sc->partname[p], m->pos[p * m->d + c], 0, &e, msg, msglen);
      if (!rc) rc = print_eq(fp, lhs, e, 0, fmt);
      dal_expr_destroy(e);
    }
  return rc;
}

static int show_model(const dal_scene *sc, const model *m, const extras *x, FILE *fp,
                      dal_expr_format fmt, char *msg, size_t msglen) {
  int rc = show_positions(sc, m, fp, fmt, msg, msglen);
  if (rc) return rc;
  dal_expr_model_def md = dal_default_expr_model_def();
  md.name = sc->name;
  md.dim = m->d;
  md.coords = (const char *const *)sc->cname;
  md.ncoords = sc->ncoord;
  md.masses = (const char *const *)m->mass;
  md.nparticles = m->np;
  md.positions = (const char *const *)m->pos;
  md.gravity = m->grav[0] ? (const char *const *)m->grav : NULL;
  md.potential = m->pot.n ? m->pot.s : NULL;
  // the parameters the model's formulas name
  int nt = 0, np = 0;
  const char **texts = malloc(((size_t)m->np * (size_t)(m->d + 1) + 4) * sizeof *texts);
  const char **pn = NULL;
  double *pv = NULL;
  if (!texts) return DAL_E_NOMEM;
  for (int i = 0; i < m->np * m->d; ++i)
    texts[nt++] = m->pos[i];
  for (int i = 0; i < m->np; ++i)
    texts[nt++] = m->mass[i];
  for (int c = 0; c < 3; ++c)
    if (m->grav[c]) texts[nt++] = m->grav[c];
  if (m->pot.n) texts[nt++] = m->pot.s;
  rc = dal__scene_params(sc, texts, nt, &pn, &pv, &np);
  free(texts);
  md.params = pn;
  md.values = pv;
  md.nparam = np;
  dal_expr *T = NULL, *U = NULL, *L = NULL;
  if (!rc) rc = dal_expr_model_energies(&md, &T, &U, &L, msg, msglen);
  free(pn);
  free(pv);
  if (!rc) rc = show_equations(sc, fp, fmt, T, U, L, x, msg, msglen);
  dal_expr_destroy(T);
  dal_expr_destroy(U);
  dal_expr_destroy(L);
  return rc;
}

static int show_scene(const dal_scene *sc, FILE *fp, dal_expr_format fmt, char *msg,
                      size_t msglen) {
  for (int i = 0; i < sc->nlines; ++i)
    if (!strcmp(sc->lines[i].tok[0], "lagrangian"))
      return show_lagrangian(sc, &sc->lines[i], fp, fmt, msg, msglen);
  model m = {sc->npart, sc->dim, NULL, NULL, {NULL, NULL, NULL}, {0}};
  extras x;
  memset(&x, 0, sizeof x);
  m.pos = calloc((size_t)m.np * (size_t)m.d + 1, sizeof *m.pos);
  m.mass = calloc((size_t)m.np + 1, sizeof *m.mass);
  x.gq = calloc((size_t)sc->ncoord + 1, sizeof *x.gq);
  adds(&m.pot, "");
  int rc = m.pos && m.mass && m.pot.s && x.gq ? DAL_OK : DAL_E_NOMEM, k = 0;
  for (int pass = 0; pass < 2; ++pass)
    for (int i = 0; i < sc->nlines && !rc; ++i)
      rc = collect(sc, &sc->lines[i], &m, &x, pass, &k, msg, msglen);
  for (int i = 0; i < m.np * m.d && !rc; ++i)
    if (!m.pos[i]) {
      rc = DAL_E_UNSUPPORTED;
      if (msg && msglen)
        snprintf(msg, msglen, "%s: particle '%s' is not placed by formulas", sc->name,
                 sc->partname[i / m.d]);
    }
  if (!rc) rc = show_model(sc, &m, &x, fp, fmt, msg, msglen);
  for (int i = 0; m.pos && i < m.np * m.d; ++i)
    free(m.pos[i]);
  free(m.pos);
  free(m.mass);
  free(m.pot.s);
  free(x.D.s);
  for (int r = 0; r < x.nphi; ++r) {
    free(x.phi[r].s);
    free(x.name[r]);
  }
  free(x.phi);
  free(x.name);
  for (int i = 0; x.gq && i < sc->ncoord; ++i)
    free(x.gq[i].s);
  free(x.gq);
  if (!rc && ferror(fp)) rc = DAL_E_IO;
  return rc;
}

int dal_scene_show(const dal_scene *sc, FILE *fp, dal_expr_format fmt, char *msg, size_t msglen) {
  if (msg && msglen) msg[0] = 0;
  if (!sc || !fp) return DAL_E_ARG;
  int rc = show_scene(sc, fp, fmt, msg, msglen);
  if (rc == DAL_E_TOO_LARGE && msg && msglen) {
    // the scene's name first, then what the algebra said (or the printer's bound)
    char *inner = msg[0] ? strdup(msg) : NULL;
    snprintf(msg, msglen, "%s: an equation is too large to show%s%s", sc->name,
             inner ? ": "
                   : " (more than 256 KiB of text or 2^21 operations of the algebra); "
                     "simplify the formulas or show fewer coordinates",
             inner ? inner : "");
    free(inner);
  }
  return rc;
}
