// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Scene files read: the words and formulas of each line, a scene from text or a file (built by
// the grammar's table, grammar.c).
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
  char **v = dal__scene_grow(out->tok, out->ntok, &out->captok, sizeof *v, 8);
  if (!v) {
    free(w);
    return DAL_E_NOMEM;
  }
  out->tok = v;
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
    if (!rc && l.ntok > 0) {
      sline *v = dal__scene_grow(sc->lines, sc->nlines, &cap, sizeof *v, 32);
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
