// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The expression layer's face: the parser, the compiler to jet programs, the compiled
// expression (the trees and their algebra are symbolic/symbolic.h's).
#ifndef DAL_EXPR_EXPR_H
#define DAL_EXPR_EXPR_H

#include <stddef.h>

#include "dalembert/expr.h"
#include "symbolic/symbolic.h"

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

/// 1 when e places a particle hanging from its parent in the plane exactly as dal_map_hanging
/// does: outputs (x + P sin(q), y - P cos(q)) over inputs (x, y, q), P its only parameter, no t
int dal__expr_hanging(const dal_expr *e);

/// The parts of a Lagrangian e (one formula over q and qdot, dal_expr_lagrangian) its equations
/// read: dL/dqdot_i and dL/dq_i (i < n), derived symbolically, as one expression of 2n outputs
/// (in that order) over e's inputs and parameters (*out; the caller destroys it). Returns
/// DAL_OK, DAL_E_ARG (not a Lagrangian), DAL_E_NOMEM, DAL_E_TOO_LARGE (symbolic.c).
int dal__expr_lagrange_parts(const dal_expr *e, dal_expr **out, char *msg, size_t msglen);
/// the parts' program at (t, q, qdot) into out (2n jets); ctx: the parts' expression (a
/// dal__lagrangian_parts_fn of base.h; expr.c)
int dal__expr_lagrange_parts_eval(dal_jet t, const dal_jet *q, const dal_jet *qdot, dal_jet *out,
                                  void *ctx);

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
/// a scalar instruction of a program: op (X_ADD .. X_HYPOT) of a and b (b unused by one-argument
/// operations) in doubles, as the program's scalar part and the generated code's folding
/// compute it
double dal__xscalar(int op, double a, double b);
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
  dal_xnative_fn *native;         // NULL: the bytecode runs (src/codegen/ sets it)
  void (*native_release)(void *); // called on native_ctx by dal_expr_destroy (nullable)
  void *native_ctx;
};

#endif
