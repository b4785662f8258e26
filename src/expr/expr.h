// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The expression layer's face: hash-consed expression trees, the parser, the compiler to jet
// programs and the symbolic algebra (derivatives, simplification, printing).
#ifndef DAL_EXPR_EXPR_H
#define DAL_EXPR_EXPR_H

#include <stddef.h>

#include "dalembert/expr.h"

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

/// parse `text` (formula number `which`, called `label` in messages, NULL: "formula <which+1>")
/// into the tree; *root receives the node. Symbols: tr->names (inputs, then parameters), "t",
/// "pi". msg names the formula, column and token.
int dal__xparse(dal_xtree *tr, const char *text, int which, const char *label, int *root, char *msg,
                size_t msglen);

/// a new expression from roots (nout nodes) of tr, whose symbols are nin_named inputs (with
/// their velocities when `velocities`) and parameters with `values`; its formulas have no
/// source text ("(derived)"; dal_expr_print shows them). msg on failure.
int dal__expr_from_tree(const char *name, const dal_xtree *tr, const int *roots, int nout,
                        int nin_named, int velocities, const double *values, dal_expr **out,
                        char *msg, size_t msglen);

/// a compiled program: a scalar part (parameters and constants, doubles) and a jet part
typedef struct dal_xins {
  unsigned char op, mode; // mode: operand kinds for binary jet ops (see compile.c)
  unsigned short dst, a, b;
  int node; // the node it computes (messages)
  double k;
} dal_xins;

#define DAL_XREGS 255

typedef struct dal_xprog {
  dal_xins *ins;
  int nscalar, njet; // instructions: ins[0 .. nscalar-1] scalar, then njet jet ones
  int nout;
  unsigned short *out;    // register of output k
  unsigned char *out_jet; // 1: output k is a jet register, 0: a scalar one
  int nsreg, njreg;
} dal_xprog;

/// compile roots (nout nodes) of tr; msg on failure (too many registers)
int dal__xcompile(const dal_xtree *tr, const int *roots, int nout, dal_xprog *p, char *msg,
                  size_t msglen);
void dal__xprog_free(dal_xprog *p);
/// run p: input i is in[i] for i < split, else in2[i - split]; `bad` (nullable) receives the
/// index of the first instruction whose result is not finite (-1 none)
void dal__xrun(const dal_xprog *p, const dal_jet *in, const dal_jet *in2, int split, dal_jet t,
               const double *param, dal_jet *out, int *bad);

/// native code for a program (src/codegen/): the arguments and results of dal__xrun, `bad` aside
typedef void dal_xnative_fn(const dal_jet *in, const dal_jet *in2, int split, dal_jet t,
                            const double *param, dal_jet *out);

/// the compiled expression (public dal_expr)
struct dal_expr {
  char *name;
  dal_xtree tree;
  int nout, nin_named, velocities;
  int *roots; // nout nodes
  char **formulas;
  double *values;
  dal_xprog prog;
  dal_primitive prim;
  dal_xnative_fn *native;           // NULL: the bytecode runs (src/codegen/ sets it)
  void (*native_release)(void *);   // called on native_ctx by dal_expr_destroy (nullable)
  void *native_ctx;
};

#endif
