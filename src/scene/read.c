// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Scene files read: the words and formulas of each line, the grammar (one table: the
// element handlers, their pass, their forms for the help), a scene from text or a file.
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"

char *dal__scene_dup(const char *s) {
  size_t n = strlen(s) + 1;
  char *r = malloc(n);
  if (r) memcpy(r, s, n);
  return r;
}

char *dal__scene_dupn(const char *s, size_t n) {
  char *r = malloc(n + 1);
  if (r) {
    memcpy(r, s, n);
    r[n] = 0;
  }
  return r;
}

// a formatted string of any length (malloc'd; NULL when out of memory)
char *dal__scene_strf(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  char *s = n >= 0 ? malloc((size_t)n + 1) : NULL;
  if (s) {
    va_start(ap, fmt);
    vsnprintf(s, (size_t)n + 1, fmt, ap);
    va_end(ap);
  }
  return s;
}

// ---- name tables (FNV-1a, open addressing, at most half full)

static uint32_t hash(const char *s) {
  uint32_t h = 2166136261u;
  for (; *s; ++s)
    h = (h ^ (unsigned char)*s) * 16777619u;
  return h;
}

int dal__tab_get(const dal_tab *t, const char *key) {
  if (!t->cap) return -1;
  for (uint32_t i = hash(key) & (uint32_t)(t->cap - 1);; i = (i + 1) & (uint32_t)(t->cap - 1)) {
    if (!t->key[i]) return -1;
    if (!strcmp(t->key[i], key)) return t->val[i];
  }
}

int dal__tab_put(dal_tab *t, const char *key, int v) {
  if (2 * (t->n + 1) > t->cap) {
    dal_tab g = {NULL, NULL, t->cap ? 2 * t->cap : 64, 0};
    g.key = calloc((size_t)g.cap, sizeof *g.key);
    g.val = calloc((size_t)g.cap, sizeof *g.val);
    if (!g.key || !g.val) {
      free(g.key);
      free(g.val);
      return DAL_E_NOMEM;
    }
    for (int i = 0; i < t->cap; ++i)
      if (t->key[i]) dal__tab_put(&g, t->key[i], t->val[i]);
    dal__tab_free(t);
    *t = g;
  }
  uint32_t i = hash(key) & (uint32_t)(t->cap - 1);
  while (t->key[i] && strcmp(t->key[i], key))
    i = (i + 1) & (uint32_t)(t->cap - 1);
  if (!t->key[i]) t->n++;
  t->key[i] = key;
  t->val[i] = v;
  return DAL_OK;
}

void dal__tab_free(dal_tab *t) {
  free(t->key);
  free(t->val);
  memset(t, 0, sizeof *t);
}

int dal__scene_err(const dal_scene *sc, int line, char *msg, size_t len, int rc, const char *fmt,
                   ...) {
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

void dal__scene_free_line(sline *l) {
  for (int i = 0; i < l->ntok; ++i)
    free(l->tok[i]);
  free(l->tok);
  for (int i = 0; i < l->nf; ++i)
    free(l->f[i]);
}

void dal_scene_destroy(dal_scene *sc) {
  if (!sc) return;
  dal__scene_unbuild(sc);
  for (int i = 0; i < sc->nlines; ++i)
    dal__scene_free_line(&sc->lines[i]);
  free(sc->lines);
  free(sc->over);
  free(sc->overval);
  free(sc->name);
  free(sc);
}

static int push_word(sline *out, char *w) {
  if (!w) return DAL_E_NOMEM;
  if (out->ntok == out->captok) {
    int cap = out->captok ? 2 * out->captok : 8;
    char **v = realloc(out->tok, (size_t)cap * sizeof *v);
    if (!v) {
      free(w);
      return DAL_E_NOMEM;
    }
    out->tok = v;
    out->captok = cap;
  }
  out->tok[out->ntok++] = w;
  return DAL_OK;
}

// 1 when w is key=value with an identifier key
static int keyed(const char *w) {
  if (!(isalpha((unsigned char)w[0]) || w[0] == '_')) return 0;
  size_t k = 1;
  while (isalnum((unsigned char)w[k]) || w[k] == '_')
    k++;
  return w[k] == '=' && w[k + 1] != '=';
}

// a formula value goes on over the next word when it is not complete: open parentheses, an
// operator at its end, or the next word starting with an operator ("q=2 * a", "v=sin( t )")
static int goes_on(const char *v, size_t n, const char *next, size_t m) {
  int depth = 0;
  for (size_t i = 0; i < n; ++i)
    depth += v[i] == '(' ? 1 : v[i] == ')' ? -1 : 0;
  if (depth > 0) return 1;
  if (n && strchr("+-*/^(,", v[n - 1])) return 1;
  return m && strchr("+-*/^),", next[0]);
}

// split one line (comment removed) into words and formulas
static int split_line(dal_scene *sc, const char *s, size_t n, int lineno, sline *out, char *msg,
                      size_t len) {
  memset(out, 0, sizeof *out);
  out->line = lineno;
  size_t i = 0;
  int joinable = 0; // the last word is key=value: a formula that may go on
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
          return dal__scene_err(sc, lineno, msg, len, DAL_E_ARG, "more than 3 formulas after '='");
        out->f[out->nf] = dal__scene_dupn(s + a, z - a);
        if (!out->f[out->nf++]) return DAL_E_NOMEM;
        if (j >= n) break;
        i = j + 1;
      }
      break;
    }
    size_t j = i;
    while (j < n && !isspace((unsigned char)s[j]))
      j++;
    char *last = out->ntok ? out->tok[out->ntok - 1] : NULL;
    if (joinable && goes_on(last, strlen(last), s + i, j - i) && !keyed(s + i)) {
      char *w = dal__scene_strf("%s %.*s", last, (int)(j - i), s + i);
      if (!w) return DAL_E_NOMEM;
      free(last);
      out->tok[out->ntok - 1] = w;
    } else {
      int rc = push_word(out, dal__scene_dupn(s + i, j - i));
      if (rc) return rc;
      joinable = out->ntok > 1 && keyed(out->tok[out->ntok - 1]);
    }
    i = j;
  }
  return DAL_OK;
}

// key=value words: the value of `key` (NULL if absent)
const char *dal__scene_kv(const sline *l, int from, const char *key) {
  size_t n = strlen(key);
  for (int i = from; i < l->ntok; ++i)
    if (!strncmp(l->tok[i], key, n) && l->tok[i][n] == '=') return l->tok[i] + n + 1;
  return NULL;
}

// the grammar: the elements of a scene file by their first word, the pass that reads them
// (parameters first, so every formula may use every parameter) and their forms
static const struct {
  const char *key;
  dal_scene_element_fn *fn;
  int pass;
  const char *form;
} elements[] = {
    {"param", dal__scene_param, 0, "param NAME = FORMULA        (of the parameters above)"},
    {"dim", dal__scene_dim, 1, "dim 2|3|0                   (0: a Lagrangian only; first)"},
    {"coord", dal__scene_coord, 1, "coord NAME [q=F] [v=F]      (initial value and rate)"},
    {"particle", dal__scene_particle, 1, "particle NAME mass=F"},
    {"place", dal__scene_place, 1,
     "place P [parent=Q] = F1; F2[; F3]  |  place P PRIMITIVE COORDS... [NAME=F]..."},
    {"constraint", dal__scene_constraint, 1,
     "constraint NAME [parts=A,B,...] = F1[; F2; F3]  |  constraint NAME PRIMITIVE "
     "[parts=..] [COORDS...] [NAME=F]..."},
    {"spring", dal__scene_spring, 1, "spring A B|anchor=F,F[,F] k=F [L=F]"},
    {"damper", dal__scene_spring, 1, "damper A B|anchor=F,F[,F] c=F"},
    {"force", dal__scene_force, 1, "force COORD = F(t, q, qdot)  (a generalized force on COORD)"},
    {"gravity", dal__scene_gravity, 1, "gravity F F [F]"},
    {"potential", dal__scene_potential, 1, "potential = U(q, t)"},
    {"lagrangian", dal__scene_potential, 1, "lagrangian = L(t, q, qdot)"},
    {"run", dal__scene_run, 1, "run [method=M] [rtol=F] [atol=F] [step=F] [t0=F] [t1=F] [dt=F]"},
    {"event", dal__scene_event, 1, "event NAME [rising|falling|both] [terminal] = g(t, q, qdot)"},
    {"section", dal__scene_event, 1,
     "section NAME [rising|falling|both] = g(t, q, qdot)  |  section NAME period=F"},
};

enum { NELEMENTS = sizeof elements / sizeof *elements };

int dal_scene_help(FILE *fp) {
  if (!fp) return DAL_E_ARG;
  fprintf(fp, "scene file: one element per line, '#' starts a comment, F a formula (a value after "
              "key= may hold spaces):\n");
  for (int i = 0; i < NELEMENTS; ++i)
    fprintf(fp, "  %s\n", elements[i].form);
  return ferror(fp) ? DAL_E_IO : DAL_OK;
}

int dal__scene_line(dal_scene *sc, const sline *l, int pass, char *msg, size_t len) {
  for (int i = 0; i < NELEMENTS; ++i)
    if (!strcmp(l->tok[0], elements[i].key))
      return elements[i].pass == pass ? elements[i].fn(sc, l, msg, len) : DAL_OK;
  if (pass) return DAL_OK;
  char known[256] = "";
  for (int i = 0; i < NELEMENTS; ++i)
    snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", i ? " " : "",
             elements[i].key);
  return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG, "unknown element '%s' (%s)", l->tok[0],
                        known);
}

int dal_scene_parse(const char *text, const char *name, dal_scene **out, char *msg, size_t msglen) {
  if (msg && msglen) msg[0] = 0;
  if (!out) return DAL_E_ARG;
  *out = NULL;
  if (!text) return DAL_E_ARG;
  dal_scene *sc = calloc(1, sizeof *sc);
  if (!sc) return DAL_E_NOMEM;
  sc->name = dal__scene_dup(name ? name : "scene");
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
    if (!rc && l.ntok == 0 && l.nf)
      rc = dal__scene_err(sc, lineno, msg, msglen, DAL_E_ARG, "a line starts with '='");
    if (!rc && l.ntok > 0 && sc->nlines == cap) {
      cap = cap ? 2 * cap : 32;
      sline *v = realloc(sc->lines, (size_t)cap * sizeof *v);
      if (v)
        sc->lines = v;
      else
        rc = DAL_E_NOMEM;
    }
    if (!rc && l.ntok > 0) {
      sc->nparamlines += !strcmp(l.tok[0], "param");
      sc->lines[sc->nlines++] = l;
    } else {
      dal__scene_free_line(&l);
    }
    s = e ? e + 1 : s + n;
  }
  if (!rc) {
    sc->over = calloc((size_t)sc->nparamlines + 1, 1);
    sc->overval = calloc((size_t)sc->nparamlines + 1, sizeof *sc->overval);
    if (!sc->over || !sc->overval) rc = DAL_E_NOMEM;
  }
  if (!rc) rc = dal__scene_build(sc, msg, msglen);
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
