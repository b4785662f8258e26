// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The symbolic layer's face: hash-consed expression trees, the algebra over them (canonical
// forms, expansion, derivatives, factoring; every function returns a node of the same tree, -1
// on failure, g->fail) and the printers. The parser and the compiler sit above, in expr/.
#ifndef DAL_SYMBOLIC_SYMBOLIC_H
#define DAL_SYMBOLIC_SYMBOLIC_H

#include <stddef.h>

#include "dalembert/base.h"

/// node operations; the order of X_SIN .. X_SQRT is the order of the function names
enum dal_xop {
  X_NUM,  // constant c
  X_IN,   // input idx
  X_PAR,  // parameter idx
  X_TIME, // t
  X_ADD,  // a + b
  X_SUB,  // a - b
  X_MUL,  // a * b
  X_DIV,  // a / b
  X_POW,  // a ^ b
  X_NEG,  // -a
  X_SIN,  // one-argument functions, in this order
  X_COS,
  X_TAN,
  X_ASIN,
  X_ACOS,
  X_ATAN,
  X_SINH,
  X_COSH,
  X_TANH,
  X_EXP,
  X_LOG,
  X_SQRT,
  X_ATAN2, // atan2(a, b)
  X_HYPOT, // hypot(a, b)
  X_NOPS
};

/// one node: children a, b (-1 when absent) precede it in the pool, so the pool's order is a
/// topological order
typedef struct dal_xnode {
  int op;
  int a, b;
  int idx;  // input or parameter index
  double c; // constant
  int col;  // 1-based column in its formula (0: made by algebra), for messages
  int src;  // formula it was first parsed in (-1: made by algebra)
} dal_xnode;

/// a pool of hash-consed nodes with its symbol table
typedef struct dal_xtree {
  dal_xnode *node;
  int n, cap;
  int *hash; // open addressing, hcap slots, -1 empty
  int hcap;
  int nin, nparam;
  char **names; // nin + nparam names (inputs, then parameters)
} dal_xtree;

int dal__xtree_init(dal_xtree *tr);
void dal__xtree_free(dal_xtree *tr);
/// the node (op, a, b, idx, c), made once; -1 on allocation failure
int dal__xnode(dal_xtree *tr, int op, int a, int b, int idx, double c);
int dal__xnum(dal_xtree *tr, double c);
/// copy the subtree `root` of `from` into `to` (same symbol numbering); -1 on failure
int dal__ximport(dal_xtree *to, const dal_xtree *from, int root);

/// name of an operation for messages and printing ("+", "sin", ...)
const char *dal__xop_name(int op);
/// 1 when op is a one-argument function (X_SIN .. X_SQRT)
int dal__xop_unary_fn(int op);

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
#define DAL_ALG_MAX_WORK (1L << 21)

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

/// the printers' formats (expr/ hands its public dal_expr_format over as these, same values)
enum dal_xformat { DAL_XFMT_TEXT, DAL_XFMT_LATEX, DAL_XFMT_SCHEME };

/// print node x of tr in format fmt (enum dal_xformat) into buf (snprintf-like: returns the
/// length the whole text needs); names from tr->names, "t" for the time
int dal__xprint(const dal_xtree *tr, int x, int fmt, char *buf, size_t len);

#endif
