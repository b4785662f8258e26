// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The code generator's face: C source from compiled expressions, and its native code compiled,
// cached and attached at run time.
#ifndef DAL_CODEGEN_CODEGEN_H
#define DAL_CODEGEN_CODEGEN_H

#include <stddef.h>

#include "base/base.h"
#include "dalembert/codegen.h"
#include "expr/expr.h"

/// dal_codegen_opts.cookie (native.c)
#define DAL_CODEGEN_COOKIE 0x0c0de6e4

/// a growing text; oom set when an append failed (the text is then incomplete)
typedef struct dal_cgbuf {
  char *s;
  size_t n, cap;
  int oom;
} dal_cgbuf;

void dal__cg_printf(dal_cgbuf *b, const char *fmt, ...);
void dal__cg_free(dal_cgbuf *b);

/// the text of dalembert/jet.h without its include of base.h: the generated code's arithmetic
void dal__cg_preamble(dal_cgbuf *b);
/// the program of e as a C function
/// `static void <fname>(const dal_jet *in, const dal_jet *in2, int split, dal_jet t,
/// const double *param, dal_jet *out)` (the arguments of dal__xrun), constants folded
void dal__cg_function(dal_cgbuf *b, const dal_expr *e, const char *fname);

/// compile src (or find it in the cache, native.c) and load it: *handle (dlclose it) and *fn
/// the address of its symbol `sym`; on failure msg says why (dal_codegen_attach's codes)
int dal__cg_load(const dal_cgbuf *src, const dal_codegen_opts *o, const char *sym, void **handle,
                 void **fn, char *msg, size_t msglen);

/// the generated C of the compiled equations of motion of sys (eom.c): one function
/// `int <fname>(double t, const double *q, const double *qd, const double *P,
/// const double *const *X, const double *m, const double *g, double *qdd)`; DAL_E_UNSUPPORTED
/// (with msg) for a system outside their reach, DAL_E_TOO_LARGE past the algebra's bounds
int dal__eom_source(const dal_system *sys, dal_cgbuf *b, const char *fname, char *msg,
                    size_t msglen);
/// attach the loaded function fn of dal__eom_source's code to sys (which then owns the dlopen
/// handle; a handle opened again by each caller); DAL_E_NOMEM
int dal__eom_attach(dal_system *sys, void *handle, void *fn);
/// qddot (n) at (t, q, qdot) with st's parameters by sys's compiled equations of motion (eom.c);
/// nonzero when the general path must run instead (a pivot not positive, a value not finite)
int dal__eom_qddot(const dal_system *sys, const dal_state *st, double t, const double *q,
                   const double *qd, double *qdd);
/// free a system's compiled equations of motion (NULL: nothing)
void dal__eom_free(struct dal_eom *e);

#endif
