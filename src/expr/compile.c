// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Expression trees to register programs over doubles (parameters, constants) and jets.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "expr.h"

// operand kinds of a binary jet instruction
enum { M_JJ, M_JS, M_SJ, M_JK, M_KJ };
// kinds of a jet power: integer constant, real constant, scalar register, jet exponent
enum { P_INT = 8, P_K, P_S, P_GEN, P_SBASE };

#define SREGS 512
#define JREGS 256

typedef struct alloc {
  unsigned short free[SREGS];
  int nfree, used, cap;
} alloc;

static int take(alloc *a) {
  if (a->nfree) return a->free[--a->nfree];
  if (a->used >= a->cap) return -1;
  return a->used++;
}

static void give(alloc *a, int r) { a->free[a->nfree++] = (unsigned short)r; }

void dal__xprog_free(dal_xprog *p) {
  if (!p) return;
  free(p->ins);
  free(p->out);
  free(p->out_jet);
  memset(p, 0, sizeof *p);
}

static int is_int_const(const dal_xnode *x) {
  return x->op == X_NUM && x->c == floor(x->c) && fabs(x->c) <= 1024.0;
}

// 1 when child c of node i is a constant folded into i's jet instruction (arithmetic operands,
// power exponents), so it needs no register
static int folds(const dal_xtree *tr, const unsigned char *jet, int i, int c) {
  const dal_xnode *x = &tr->node[i];
  if (!jet[i] || tr->node[c].op != X_NUM) return 0;
  if (x->op == X_POW) return c == x->b;
  return x->op == X_ADD || x->op == X_SUB || x->op == X_MUL || x->op == X_DIV;
}

// which nodes are jets (depend on inputs or t), which the outputs reach (a constant operand
// of a jet instruction is folded into it), their emission order (scalar nodes, then jet
// nodes) and the last use of each value
static void plan(const dal_xtree *tr, const int *roots, int nout, unsigned char *jet,
                 unsigned char *reach, int *pos, int *last) {
  int n = tr->n;
  // which nodes depend on inputs or t (jets), in pool order (children first)
  for (int i = 0; i < n; ++i) {
    const dal_xnode *x = &tr->node[i];
    jet[i] =
        x->op == X_IN || x->op == X_TIME || (x->a >= 0 && jet[x->a]) || (x->b >= 0 && jet[x->b]);
  }
  // what the outputs reach; a constant operand of a jet instruction is folded into it
  for (int k = 0; k < nout; ++k)
    reach[roots[k]] = 1;
  for (int i = n - 1; i >= 0; --i) {
    if (!reach[i]) continue;
    const dal_xnode *x = &tr->node[i];
    if (x->a >= 0 && !folds(tr, jet, i, x->a)) reach[x->a] = 1;
    if (x->b >= 0 && !folds(tr, jet, i, x->b)) reach[x->b] = 1;
  }
  // emission order: scalar nodes, then jet nodes; last use of each value
  int np = 0;
  for (int pass = 0; pass < 2; ++pass)
    for (int i = 0; i < n; ++i)
      if (reach[i] && jet[i] == pass) pos[i] = np++;
  for (int i = 0; i < n; ++i)
    last[i] = -1;
  for (int i = 0; i < n; ++i) {
    if (!reach[i]) continue;
    const dal_xnode *x = &tr->node[i];
    if (x->a >= 0 && !folds(tr, jet, i, x->a) && last[x->a] < pos[i]) last[x->a] = pos[i];
    if (x->b >= 0 && !folds(tr, jet, i, x->b) && last[x->b] < pos[i]) last[x->b] = pos[i];
  }
  for (int k = 0; k < nout; ++k)
    last[roots[k]] = np + 1; // outputs stay live to the end
}

// the instruction of node i: its operands' registers, or the constants folded into it, and
// for a jet instruction which operands are jets
static dal_xins encode(const dal_xtree *tr, const unsigned char *jet, const int *reg, int i,
                       int pass) {
  const dal_xnode *x = &tr->node[i];
  dal_xins in = {(unsigned char)x->op, 0, 0, 0, 0, i, 0.0};
  int a = x->a, b = x->b;
  if (!pass) {
    // scalar: operands are scalar registers
    if (x->op == X_NUM) in.k = x->c;
    if (x->op == X_PAR) in.a = (unsigned short)x->idx;
    if (a >= 0) in.a = (unsigned short)reg[a];
    if (b >= 0) in.b = (unsigned short)reg[b];
  } else if (x->op == X_IN) {
    in.a = (unsigned short)x->idx;
  } else if (x->op == X_POW) {
    const dal_xnode *e = &tr->node[b];
    in.a = (unsigned short)reg[a];
    if (!jet[a]) {
      in.mode = P_SBASE; // scalar base, jet exponent: exp(b log a)
      in.b = (unsigned short)reg[b];
    } else if (is_int_const(e)) {
      in.mode = P_INT;
      in.k = e->c;
    } else if (e->op == X_NUM) {
      in.mode = P_K;
      in.k = e->c;
    } else if (!jet[b]) {
      in.mode = P_S;
      in.b = (unsigned short)reg[b];
    } else {
      in.mode = P_GEN;
      in.b = (unsigned short)reg[b];
    }
  } else if (b >= 0) {
    // binary jet op: which operands are jets, scalars, folded constants
    int ka = folds(tr, jet, i, a), kb = folds(tr, jet, i, b);
    if (jet[a] && jet[b])
      in.mode = M_JJ;
    else if (jet[a])
      in.mode = kb ? M_JK : M_JS;
    else
      in.mode = ka ? M_KJ : M_SJ;
    if (in.mode == M_JK) in.k = tr->node[b].c;
    if (in.mode == M_KJ) in.k = tr->node[a].c;
    if (in.mode != M_KJ) in.a = (unsigned short)reg[a];
    if (in.mode != M_JK) in.b = (unsigned short)reg[b];
  } else if (a >= 0) {
    in.a = (unsigned short)reg[a];
  }
  return in;
}

int dal__xcompile(const dal_xtree *tr, const int *roots, int nout, dal_xprog *p, char *msg,
                  size_t msglen) {
  memset(p, 0, sizeof *p);
  int n = tr->n, rc = DAL_E_NOMEM;
  unsigned char *jet = calloc((size_t)n + 1, 1), *reach = calloc((size_t)n + 1, 1);
  int *pos = malloc(((size_t)n + 1) * sizeof *pos), *last = malloc(((size_t)n + 1) * sizeof *last);
  int *reg = malloc(((size_t)n + 1) * sizeof *reg);
  alloc *sa = calloc(1, sizeof *sa), *ja = calloc(1, sizeof *ja);
  p->out = malloc((size_t)nout * sizeof *p->out);
  p->out_jet = malloc((size_t)nout);
  p->ins = malloc(((size_t)n + 1) * sizeof *p->ins);
  if (!jet || !reach || !pos || !last || !reg || !sa || !ja || !p->out || !p->out_jet || !p->ins)
    goto done;
  p->nout = nout;
  plan(tr, roots, nout, jet, reach, pos, last);
  sa->cap = SREGS;
  ja->cap = JREGS;
  // emit
  int ni = 0;
  for (int pass = 0; pass < 2; ++pass)
    for (int i = 0; i < n; ++i) {
      if (!reach[i] || jet[i] != pass) continue;
      const dal_xnode *x = &tr->node[i];
      dal_xins in = encode(tr, jet, reg, i, pass);
      int a = x->a, b = x->b;
      // free operands at their last use, then take the result's register
      if (a >= 0 && reach[a] && !folds(tr, jet, i, a) && last[a] == pos[i])
        give(jet[a] ? ja : sa, reg[a]);
      if (b >= 0 && b != a && reach[b] && !folds(tr, jet, i, b) && last[b] == pos[i])
        give(jet[b] ? ja : sa, reg[b]);
      int r = take(pass ? ja : sa);
      if (r < 0) {
        if (msg && msglen)
          snprintf(msg, msglen,
                   "formula too large: more than %d live %s values (split it into several)",
                   pass ? JREGS : SREGS, pass ? "jet" : "scalar");
        rc = DAL_E_ARG;
        goto done;
      }
      reg[i] = r;
      in.dst = (unsigned short)r;
      if (last[i] < 0) give(pass ? ja : sa, r); // never read (cannot happen for reached nodes)
      p->ins[ni++] = in;
      if (!pass) p->nscalar = ni;
    }
  p->njet = ni - p->nscalar;
  for (int k = 0; k < nout; ++k) {
    p->out[k] = (unsigned short)reg[roots[k]];
    p->out_jet[k] = jet[roots[k]];
  }
  p->nsreg = sa->used;
  p->njreg = ja->used;
  rc = DAL_OK;
done:
  if (rc == DAL_E_NOMEM && msg && msglen) snprintf(msg, msglen, "out of memory compiling");
  if (rc) dal__xprog_free(p);
  free(jet);
  free(reach);
  free(pos);
  free(last);
  free(reg);
  free(sa);
  free(ja);
  return rc;
}

double dal__xscalar(int op, double a, double b) {
  switch (op) {
  case X_ADD:
    return a + b;
  case X_SUB:
    return a - b;
  case X_MUL:
    return a * b;
  case X_DIV:
    return a / b;
  case X_POW:
    return pow(a, b);
  case X_NEG:
    return -a;
  case X_SIN:
    return sin(a);
  case X_COS:
    return cos(a);
  case X_TAN:
    return tan(a);
  case X_ASIN:
    return asin(a);
  case X_ACOS:
    return acos(a);
  case X_ATAN:
    return atan(a);
  case X_SINH:
    return sinh(a);
  case X_COSH:
    return cosh(a);
  case X_TANH:
    return tanh(a);
  case X_EXP:
    return exp(a);
  case X_LOG:
    return log(a);
  case X_SQRT:
    return sqrt(a);
  case X_ATAN2:
    return atan2(a, b);
  case X_HYPOT:
    return hypot(a, b);
  default:
    return NAN;
  }
}

static dal_jet jfn1(int op, dal_jet a) {
  switch (op) {
  case X_NEG:
    return dal_neg(a);
  case X_SIN:
    return dal_sin(a);
  case X_COS:
    return dal_cos(a);
  case X_TAN:
    return dal_tan(a);
  case X_ASIN:
    return dal_asin(a);
  case X_ACOS:
    return dal_acos(a);
  case X_ATAN:
    return dal_atan(a);
  case X_SINH:
    return dal_sinh(a);
  case X_COSH:
    return dal_cosh(a);
  case X_TANH:
    return dal_tanh(a);
  case X_EXP:
    return dal_exp(a);
  case X_LOG:
    return dal_log(a);
  case X_SQRT:
    return dal_sqrt(a);
  default:
    return dal_const(NAN);
  }
}

static dal_jet jpow(dal_jet a, double k) {
  if (k == floor(k) && fabs(k) <= 1e9) return k == 2.0 ? dal_sq(a) : dal_powi(a, (int)k);
  if (k == 0.5) return dal_sqrt(a);
  return dal_pow(a, k);
}

// an arithmetic instruction: jet and jet, jet and scalar or constant, or the other way round
static inline dal_jet arith(const dal_xins *x, const double *S, const dal_jet *J) {
  dal_jet a, b;
  switch (x->mode) {
  case M_JS:
  case M_JK: {
    double s = x->mode == M_JK ? x->k : S[x->b];
    a = J[x->a];
    return x->op == X_ADD   ? dal_addc(a, s)
           : x->op == X_SUB ? dal_addc(a, -s)
           : x->op == X_MUL ? dal_scale(a, s)
                            : dal_scale(a, 1.0 / s);
  }
  case M_SJ:
  case M_KJ: {
    double s = x->mode == M_KJ ? x->k : S[x->a];
    b = J[x->b];
    return x->op == X_ADD   ? dal_addc(b, s)
           : x->op == X_SUB ? dal_addc(dal_neg(b), s)
           : x->op == X_MUL ? dal_scale(b, s)
                            : dal_div(dal_const(s), b);
  }
  default:
    a = J[x->a];
    b = J[x->b];
    return x->op == X_ADD   ? dal_add(a, b)
           : x->op == X_SUB ? dal_sub(a, b)
           : x->op == X_MUL ? dal_mul(a, b)
                            : dal_div(a, b);
  }
}

// a power: integer, constant or scalar exponent, jet exponent, or a scalar base
static inline dal_jet power(const dal_xins *x, const double *S, const dal_jet *J) {
  switch (x->mode) {
  case P_INT:
    return x->k == 2.0 ? dal_sq(J[x->a]) : dal_powi(J[x->a], (int)x->k);
  case P_K:
    return jpow(J[x->a], x->k);
  case P_S:
    return jpow(J[x->a], S[x->b]);
  case P_GEN:
    return dal_exp(dal_mul(J[x->b], dal_log(J[x->a])));
  default:
    return dal_exp(dal_scale(J[x->b], log(S[x->a]))); // P_SBASE
  }
}

static inline void run(const dal_xprog *p, const dal_jet *in, const dal_jet *in2, int split,
                       dal_jet t, const double *param, dal_jet *out, int check, int *bad) {
  double S[SREGS];
  dal_jet J[JREGS];
  const dal_xins *ins = p->ins;
  if (check) *bad = -1;
  // the scalar part: parameters and constants
  for (int i = 0; i < p->nscalar; ++i) {
    const dal_xins *x = &ins[i];
    double v;
    if (x->op == X_NUM)
      v = x->k;
    else if (x->op == X_PAR)
      v = param[x->a];
    else
      v = dal__xscalar(x->op, S[x->a], S[x->b]);
    S[x->dst] = v;
    if (check && *bad < 0 && !isfinite(v)) *bad = i;
  }
  // the jet part
  for (int i = p->nscalar; i < p->nscalar + p->njet; ++i) {
    const dal_xins *x = &ins[i];
    dal_jet r;
    switch (x->op) {
    case X_IN:
      r = x->a < split ? in[x->a] : in2[x->a - split];
      break;
    case X_TIME:
      r = t;
      break;
    case X_ADD:
    case X_SUB:
    case X_MUL:
    case X_DIV:
      r = arith(x, S, J);
      break;
    case X_POW:
      r = power(x, S, J);
      break;
    case X_ATAN2:
    case X_HYPOT: {
      dal_jet a = x->mode == M_SJ ? dal_const(S[x->a]) : J[x->a];
      dal_jet b = x->mode == M_JS ? dal_const(S[x->b]) : J[x->b];
      r = x->op == X_ATAN2 ? dal_atan2(a, b) : dal_hypot(a, b);
      break;
    }
    default:
      r = jfn1(x->op, J[x->a]);
    }
    J[x->dst] = r;
    if (check && *bad < 0 && !dal_jet_isfinite(r)) *bad = i;
  }
  for (int k = 0; k < p->nout; ++k)
    out[k] = p->out_jet[k] ? J[p->out[k]] : dal_const(S[p->out[k]]);
}

void dal__xrun(const dal_xprog *p, const dal_jet *in, const dal_jet *in2, int split, dal_jet t,
               const double *param, dal_jet *out, int *bad) {
  if (bad)
    run(p, in, in2, split, t, param, out, 1, bad);
  else
    run(p, in, in2, split, t, param, out, 0, NULL);
}
