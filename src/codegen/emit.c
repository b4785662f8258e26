// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Straight-line C from an expression's register program: one local per instruction, constants
// folded, the jet arithmetic of dalembert/jet.h, so the results equal the bytecode's bit for bit.
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <dal_jet_text.h>

#include "codegen.h"

void dal__cg_printf(dal_cgbuf *b, const char *fmt, ...) {
  if (b->oom) return;
  for (;;) {
    va_list ap;
    va_start(ap, fmt);
    size_t room = b->cap - b->n;
    int k = vsnprintf(b->s ? b->s + b->n : NULL, b->s ? room : 0, fmt, ap);
    va_end(ap);
    if (k < 0) {
      b->oom = 1;
      return;
    }
    if (b->s && (size_t)k < room) {
      b->n += (size_t)k;
      return;
    }
    size_t cap = b->cap ? 2 * b->cap : 4096;
    while (cap < b->n + (size_t)k + 1)
      cap *= 2;
    char *s = realloc(b->s, cap);
    if (!s) {
      b->oom = 1;
      return;
    }
    b->s = s;
    b->cap = cap;
  }
}

void dal__cg_free(dal_cgbuf *b) {
  free(b->s);
  memset(b, 0, sizeof *b);
}

void dal__cg_preamble(dal_cgbuf *b) {
  // jet.h verbatim but for its include of base.h (the export macro, unused here)
  const char *p = dal__jet_text;
  while (*p) {
    const char *e = strchr(p, '\n');
    size_t n = e ? (size_t)(e - p) + 1 : strlen(p);
    if (strncmp(p, "#include \"dalembert/", 20)) dal__cg_printf(b, "%.*s", (int)n, p);
    p += n;
  }
  // a power with an exponent known only at run time (compile.c's jpow)
  dal__cg_printf(b, "\n#ifndef DAL_CG_JPOW\n#define DAL_CG_JPOW\n"
                    "static inline dal_jet dal_cg_jpow(dal_jet a, double k) {\n"
                    "  if (k == floor(k) && fabs(k) <= 1e9) return k == 2.0 ? dal_sq(a) : "
                    "dal_powi(a, (int)k);\n"
                    "  if (k == 0.5) return dal_sqrt(a);\n"
                    "  return dal_pow(a, k);\n}\n#endif\n");
}

// operand kinds of compile.c (M_*: binary jet ops; P_*: powers)
enum { M_JJ, M_JS, M_SJ, M_JK, M_KJ };
enum { P_INT = 8, P_K, P_S, P_GEN, P_SBASE };

static const char *const fname1[] = {"sin",  "cos",  "tan",  "asin", "acos", "atan",
                                     "sinh", "cosh", "tanh", "exp",  "log",  "sqrt"};

// a double as an exact C literal (hexadecimal), in parentheses
typedef struct lit {
  char s[48];
} lit;

static lit literal(double v) {
  lit l;
  if (isnan(v))
    snprintf(l.s, sizeof l.s, "(NAN)");
  else if (isinf(v))
    snprintf(l.s, sizeof l.s, "(%sINFINITY)", v < 0 ? "-" : "");
  else
    snprintf(l.s, sizeof l.s, "(%a)", v);
  return l;
}

// what a register holds now: a folded constant or the local of the instruction that wrote it
typedef struct sval {
  int known;
  double c;
  int var;
} sval;

static lit sname(const sval *s) {
  if (s->known) return literal(s->c);
  lit l;
  snprintf(l.s, sizeof l.s, "s%d", s->var);
  return l;
}

void dal__cg_function(dal_cgbuf *b, const dal_expr *e, const char *fname) {
  const dal_xprog *p = &e->prog;
  int ns = p->nsreg > 0 ? p->nsreg : 1, nj = p->njreg > 0 ? p->njreg : 1;
  sval *S = calloc((size_t)ns, sizeof *S);
  int *J = calloc((size_t)nj, sizeof *J);
  if (!S || !J) {
    b->oom = 1;
    free(S);
    free(J);
    return;
  }
  dal__cg_printf(b,
                 "\n// %s: %d outputs of %d inputs, %d parameters\n"
                 "static void %s(const dal_jet *in, const dal_jet *in2, int split, dal_jet t,\n"
                 "    const double *param, dal_jet *out) {\n"
                 "  (void)in; (void)in2; (void)split; (void)t; (void)param;\n",
                 e->name, e->nout, e->tree.nin, e->tree.nparam, fname);
  // the scalar part: parameters read, constants folded
  for (int i = 0; i < p->nscalar; ++i) {
    const dal_xins *x = &p->ins[i];
    // operands are registers but for a constant and a parameter (whose a is its index)
    sval *d = &S[x->dst], a = {0, 0.0, 0}, bb = {0, 0.0, 0};
    if (x->op != X_NUM && x->op != X_PAR) {
      a = S[x->a];
      bb = S[x->b];
    }
    sval r = {0, 0.0, i};
    if (x->op == X_NUM) {
      r.known = 1;
      r.c = x->k;
    } else if (x->op == X_PAR) {
      dal__cg_printf(b, "  const double s%d = param[%d];\n", i, x->a);
    } else {
      int binary = x->op <= X_POW || x->op == X_ATAN2 || x->op == X_HYPOT;
      if (a.known && (!binary || bb.known)) {
        r.known = 1;
        // folded as the bytecode's scalar part computes it
        r.c = dal__xscalar(x->op, a.c, bb.c);
      } else {
        lit la = sname(&a), lb = sname(&bb);
        if (x->op >= X_ADD && x->op <= X_DIV)
          dal__cg_printf(b, "  const double s%d = %s %c %s;\n", i, la.s, "+-*/"[x->op - X_ADD],
                         lb.s);
        else if (x->op == X_NEG)
          dal__cg_printf(b, "  const double s%d = -%s;\n", i, la.s);
        else if (binary)
          dal__cg_printf(b, "  const double s%d = %s(%s, %s);\n", i,
                         x->op == X_POW     ? "pow"
                         : x->op == X_ATAN2 ? "atan2"
                                            : "hypot",
                         la.s, lb.s);
        else
          dal__cg_printf(b, "  const double s%d = %s(%s);\n", i, fname1[x->op - X_SIN], la.s);
      }
    }
    *d = r;
  }
  // the jet part
  for (int i = p->nscalar; i < p->nscalar + p->njet; ++i) {
    const dal_xins *x = &p->ins[i];
    char ja[24], jb[24];
    // the jet operands' locals (a and b may be an input index or a scalar register instead:
    // read only in range, used only where they are jet registers)
    snprintf(ja, sizeof ja, "j%d", x->a < nj ? J[x->a] : -1);
    snprintf(jb, sizeof jb, "j%d", x->b < nj ? J[x->b] : -1);
    dal__cg_printf(b, "  const dal_jet j%d = ", i);
    switch (x->op) {
    case X_IN:
      dal__cg_printf(b, "%d < split ? in[%d] : in2[%d - split];\n", x->a, x->a, x->a);
      break;
    case X_TIME:
      dal__cg_printf(b, "t;\n");
      break;
    case X_ADD:
    case X_SUB:
    case X_MUL:
    case X_DIV:
      if (x->mode == M_JJ) {
        const char *f[] = {"dal_add", "dal_sub", "dal_mul", "dal_div"};
        dal__cg_printf(b, "%s(%s, %s);\n", f[x->op - X_ADD], ja, jb);
      } else if (x->mode == M_JS || x->mode == M_JK) {
        sval s = x->mode == M_JK ? (sval){1, x->k, 0} : S[x->b];
        lit l = sname(&s);
        if (x->op == X_ADD) dal__cg_printf(b, "dal_addc(%s, %s);\n", ja, l.s);
        if (x->op == X_MUL) dal__cg_printf(b, "dal_scale(%s, %s);\n", ja, l.s);
        if (x->op == X_SUB) {
          if (s.known)
            dal__cg_printf(b, "dal_addc(%s, %s);\n", ja, literal(-s.c).s);
          else
            dal__cg_printf(b, "dal_addc(%s, -%s);\n", ja, l.s);
        }
        if (x->op == X_DIV) {
          if (s.known)
            dal__cg_printf(b, "dal_scale(%s, %s);\n", ja, literal(1.0 / s.c).s);
          else
            dal__cg_printf(b, "dal_scale(%s, 1.0 / %s);\n", ja, l.s);
        }
      } else {
        sval s = x->mode == M_KJ ? (sval){1, x->k, 0} : S[x->a];
        lit l = sname(&s);
        const char *f = x->op == X_ADD   ? "dal_addc(%s, %s);\n"
                        : x->op == X_SUB ? "dal_addc(dal_neg(%s), %s);\n"
                        : x->op == X_MUL ? "dal_scale(%s, %s);\n"
                                         : NULL;
        if (f)
          dal__cg_printf(b, f, jb, l.s);
        else
          dal__cg_printf(b, "dal_div(dal_const(%s), %s);\n", l.s, jb);
      }
      break;
    case X_POW: {
      double k = x->k;
      int known = x->mode == P_INT || x->mode == P_K;
      if (x->mode == P_S && S[x->b].known) {
        known = 1;
        k = S[x->b].c;
      }
      if (known && x->mode == P_INT) {
        if (k == 2.0)
          dal__cg_printf(b, "dal_sq(%s);\n", ja);
        else
          dal__cg_printf(b, "dal_powi(%s, %d);\n", ja, (int)k);
      } else if (known) {
        // compile.c's jpow with its exponent known
        if (k == floor(k) && fabs(k) <= 1e9) {
          if (k == 2.0)
            dal__cg_printf(b, "dal_sq(%s);\n", ja);
          else
            dal__cg_printf(b, "dal_powi(%s, %d);\n", ja, (int)k);
        } else if (k == 0.5) {
          dal__cg_printf(b, "dal_sqrt(%s);\n", ja);
        } else {
          dal__cg_printf(b, "dal_pow(%s, %s);\n", ja, literal(k).s);
        }
      } else if (x->mode == P_S) {
        dal__cg_printf(b, "dal_cg_jpow(%s, %s);\n", ja, sname(&S[x->b]).s);
      } else if (x->mode == P_GEN) {
        dal__cg_printf(b, "dal_exp(dal_mul(%s, dal_log(%s)));\n", jb, ja);
      } else { // P_SBASE: scalar base
        const sval *s = &S[x->a];
        if (s->known)
          dal__cg_printf(b, "dal_exp(dal_scale(%s, %s));\n", jb, literal(log(s->c)).s);
        else
          dal__cg_printf(b, "dal_exp(dal_scale(%s, log(%s)));\n", jb, sname(s).s);
      }
      break;
    }
    case X_ATAN2:
    case X_HYPOT: {
      char ca[64], cb[64];
      if (x->mode == M_SJ)
        snprintf(ca, sizeof ca, "dal_const(%s)", sname(&S[x->a]).s);
      else
        snprintf(ca, sizeof ca, "%s", ja);
      if (x->mode == M_JS)
        snprintf(cb, sizeof cb, "dal_const(%s)", sname(&S[x->b]).s);
      else
        snprintf(cb, sizeof cb, "%s", jb);
      dal__cg_printf(b, "%s(%s, %s);\n", x->op == X_ATAN2 ? "dal_atan2" : "dal_hypot", ca, cb);
      break;
    }
    case X_NEG:
      dal__cg_printf(b, "dal_neg(%s);\n", ja);
      break;
    default:
      if (x->op >= X_SIN && x->op <= X_SQRT)
        dal__cg_printf(b, "dal_%s(%s);\n", fname1[x->op - X_SIN], ja);
      else
        dal__cg_printf(b, "dal_const(NAN);\n");
    }
    J[x->dst] = i;
  }
  // the outputs
  for (int k = 0; k < p->nout; ++k) {
    if (p->out_jet[k])
      dal__cg_printf(b, "  out[%d] = j%d;\n", k, J[p->out[k]]);
    else
      dal__cg_printf(b, "  out[%d] = dal_const(%s);\n", k, sname(&S[p->out[k]]).s);
  }
  dal__cg_printf(b, "}\n");
  free(S);
  free(J);
}
