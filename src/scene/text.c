// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Scene files' words and names: strings, the name tables, messages that name the line, the
// key=value words of a line (what the reader, the builder and the shower all use).
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

void *dal__scene_grow(void *v, int n, int *cap, size_t sz, int first) {
  if (n < *cap) return v;
  int c = *cap ? 2 * *cap : first;
  void *p = realloc(v, (size_t)c * sz);
  if (p) *cap = c;
  return p;
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

// key=value words: the value of `key` (NULL if absent)
const char *dal__scene_kv(const sline *l, int from, const char *key) {
  size_t n = strlen(key);
  for (int i = from; i < l->ntok; ++i)
    if (!strncmp(l->tok[i], key, n) && l->tok[i][n] == '=') return l->tok[i] + n + 1;
  return NULL;
}
