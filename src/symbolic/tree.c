// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Hash-consed expression nodes: each (op, children, index, constant) exists once in a pool.
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "symbolic.h"

static const char *const op_names[X_NOPS] = {
    "number", "input", "parameter", "t",   "+",   "-",    "*",     "/",
    "^",      "-",     "sin",       "cos", "tan", "asin", "acos",  "atan",
    "sinh",   "cosh",  "tanh",      "exp", "log", "sqrt", "atan2", "hypot"};

const char *dal__xop_name(int op) { return op >= 0 && op < X_NOPS ? op_names[op] : "?"; }

int dal__xop_unary_fn(int op) { return op >= X_SIN && op <= X_SQRT; }

int dal__xtree_init(dal_xtree *tr) {
  memset(tr, 0, sizeof *tr);
  tr->hcap = 64;
  tr->hash = malloc((size_t)tr->hcap * sizeof *tr->hash);
  if (!tr->hash) return DAL_E_NOMEM;
  for (int i = 0; i < tr->hcap; ++i)
    tr->hash[i] = -1;
  return DAL_OK;
}

void dal__xtree_free(dal_xtree *tr) {
  if (!tr) return;
  free(tr->node);
  free(tr->hash);
  if (tr->names)
    for (int i = 0; i < tr->nin + tr->nparam; ++i)
      free(tr->names[i]);
  free(tr->names);
  memset(tr, 0, sizeof *tr);
}

static uint64_t mix(uint64_t h, uint64_t x) {
  h ^= x + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
  return h * 0xff51afd7ed558ccdull;
}

static uint64_t node_hash(int op, int a, int b, int idx, double c) {
  uint64_t cb;
  if (c == 0.0) c = 0.0; // -0 and +0 are one constant
  memcpy(&cb, &c, sizeof cb);
  uint64_t h = mix(mix(mix(mix((uint64_t)op, (uint64_t)(uint32_t)a), (uint64_t)(uint32_t)b),
                       (uint64_t)(uint32_t)idx),
                   cb);
  return h ^ (h >> 29);
}

static int same(const dal_xnode *x, int op, int a, int b, int idx, double c) {
  return x->op == op && x->a == a && x->b == b && x->idx == idx &&
         (x->c == c || (x->c != x->c && c != c));
}

// grow the hash table to twice its size and reinsert every node
static int rehash(dal_xtree *tr) {
  int cap = tr->hcap * 2;
  int *h = malloc((size_t)cap * sizeof *h);
  if (!h) return DAL_E_NOMEM;
  for (int i = 0; i < cap; ++i)
    h[i] = -1;
  for (int i = 0; i < tr->n; ++i) {
    const dal_xnode *x = &tr->node[i];
    size_t s = (size_t)(node_hash(x->op, x->a, x->b, x->idx, x->c) & (uint64_t)(cap - 1));
    while (h[s] >= 0)
      s = (s + 1) & (size_t)(cap - 1);
    h[s] = i;
  }
  free(tr->hash);
  tr->hash = h;
  tr->hcap = cap;
  return DAL_OK;
}

int dal__xnode(dal_xtree *tr, int op, int a, int b, int idx, double c) {
  if (a < -1 || b < -1) return -1; // a failed child propagates
  if (op != X_NUM) c = 0.0;
  if (c == 0.0) c = 0.0;
  size_t s = (size_t)(node_hash(op, a, b, idx, c) & (uint64_t)(tr->hcap - 1));
  while (tr->hash[s] >= 0) {
    if (same(&tr->node[tr->hash[s]], op, a, b, idx, c)) return tr->hash[s];
    s = (s + 1) & (size_t)(tr->hcap - 1);
  }
  // a new node
  if (tr->n == tr->cap) {
    int cap = tr->cap ? 2 * tr->cap : 64;
    dal_xnode *nn = realloc(tr->node, (size_t)cap * sizeof *nn);
    if (!nn) return -1;
    tr->node = nn;
    tr->cap = cap;
  }
  dal_xnode *x = &tr->node[tr->n];
  x->op = op;
  x->a = a;
  x->b = b;
  x->idx = idx;
  x->c = c;
  x->col = 0;
  x->src = -1;
  tr->hash[s] = tr->n++;
  if (2 * tr->n > tr->hcap && rehash(tr)) return -1;
  return tr->n - 1;
}

int dal__xnum(dal_xtree *tr, double c) { return dal__xnode(tr, X_NUM, -1, -1, 0, c); }

int dal__ximport(dal_xtree *to, const dal_xtree *from, int root) {
  if (root < 0 || root >= from->n) return -1;
  int *map = malloc((size_t)(root + 1) * sizeof *map);
  if (!map) return -1;
  // mark what root reaches (children precede parents), then copy in pool order
  for (int i = 0; i <= root; ++i)
    map[i] = -2;
  map[root] = -1;
  for (int i = root; i >= 0; --i) {
    if (map[i] == -2) continue;
    if (from->node[i].a >= 0) map[from->node[i].a] = -1;
    if (from->node[i].b >= 0) map[from->node[i].b] = -1;
  }
  int y = -1;
  for (int i = 0; i <= root; ++i) {
    if (map[i] == -2) continue;
    const dal_xnode *x = &from->node[i];
    y = dal__xnode(to, x->op, x->a >= 0 ? map[x->a] : -1, x->b >= 0 ? map[x->b] : -1, x->idx, x->c);
    if (y < 0) break;
    if (to->node[y].src < 0 && x->src >= 0) {
      to->node[y].src = x->src;
      to->node[y].col = x->col;
    }
    map[i] = y;
  }
  free(map);
  return y;
}
