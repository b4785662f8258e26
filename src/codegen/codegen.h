// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The code generator's face: C source from compiled expressions, and its native code compiled,
// cached and attached at run time.
#ifndef DAL_CODEGEN_CODEGEN_H
#define DAL_CODEGEN_CODEGEN_H

#include <stddef.h>

#include "dalembert/codegen.h"
#include "expr/expr.h"

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

#endif
