// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Symbolic algebra over one expression tree (canonical forms, expansion, derivatives, factoring)
// and the printers; every function returns a node of the same tree, -1 on failure (g->fail).
#ifndef DAL_EXPR_ALGEBRA_H
#define DAL_EXPR_ALGEBRA_H

#include "expr.h"

/// an algebra session on a tree: memo tables of canonical forms, expansions and derivatives
typedef struct dal_alg {
  dal_xtree *tr;
  int *canon, ncanon;
  int *expand, nexpand;
  int *deriv, nderiv, deriv_var;
  int fail;      // set by any allocation failure or bound; every later call returns -1
  int too_large; // the bound was reached (the tree or the work of one session)
  long work;     // operations so far (nodes made or looked up, pairs of terms compared)
} dal_alg;

/// bounds of one algebra session: beyond them it fails with too_large (DAL_E_TOO_LARGE)
#define DAL_ALG_MAX_NODES (1 << 19)
#define DAL_ALG_MAX_WORK (1L << 22)

void dal__alg_init(dal_alg *g, dal_xtree *tr);
void dal__alg_free(dal_alg *g);
/// canonical form of any node (parsed or built)
int dal__alg_canon(dal_alg *g, int x);
/// canonical form with products of sums and small powers of sums multiplied out
int dal__alg_simplify(dal_alg *g, int x);
/// expansion of a canonical form
int dal__alg_expand(dal_alg *g, int x);
/// derivative of x along input var (t when var < 0), simplified
int dal__alg_diff(dal_alg *g, int x, int var);
/// common factors of sums taken out (for display; the result is canonical but not expanded)
int dal__alg_factor(dal_alg *g, int x);
/// canonical sum, product, power and one-argument function of canonical operands
int dal__alg_add(dal_alg *g, const int *t, int n);
int dal__alg_mul(dal_alg *g, const int *f, int n);
int dal__alg_pow(dal_alg *g, int b, int e);
int dal__alg_fn(dal_alg *g, int op, int a);
/// 1 when x is the number c
int dal__alg_isnum(const dal_alg *g, int x, double c);
/// the terms of a canonical sum (one term when x is not a sum); *out malloc'd (NULL: no memory)
void dal__alg_terms(const dal_alg *g, int x, int **out, int *n);

/// print node x of tr in format fmt (dal_expr_format) into buf (snprintf-like: returns the
/// length the whole text needs); names from tr->names, "t" for the time
int dal__xprint(const dal_xtree *tr, int x, int fmt, char *buf, size_t len);

#endif
