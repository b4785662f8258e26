// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// White box: the library's serial-vector kernels (src/integrate/nvec.c) against SUNDIALS' own
// serial vector operations on random vectors (the reference), including the fused and vector-array
// forms against their definitions through SUNDIALS' single operations, and aliasing.
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sundials/sundials_context.h>

#include "check.h"
#include "integrate/nvec.h"

#define LEN 37
#define NV 7

static unsigned seed = 12345u;
static double urand(void) {
  seed = seed * 1103515245u + 12345u;
  return ((seed >> 8) & 0xffffff) / 16777215.0 - 0.5;
}

// worst |a - b| / (|b| + tiny scale) over n values (0 when both are equal, NaN-safe)
static double rel(const double *a, const double *b, int n, double scale) {
  double w = 0.0;
  for (int i = 0; i < n; ++i) {
    if (a[i] == b[i]) continue;
    double e = fabs(a[i] - b[i]) / (fabs(b[i]) + scale);
    if (!(e <= w)) w = e;
  }
  return w;
}

static double rel1(double a, double b) { return a == b ? 0.0 : fabs(a - b) / fabs(b); }

// vector pairs: f uses the library's kernels, s SUNDIALS' own, same contents
typedef struct pair {
  N_Vector f, s;
} pair;

// worst |z_f - z_s| / (|a x| + |b y|) of a linear sum (rounding against the terms' size: SUNDIALS
// sums some cases as a (x + y))
static double lsum_err(pair z, double a, const double *x, double b, const double *y) {
  const double *zf = N_VGetArrayPointer(z.f), *zs = N_VGetArrayPointer(z.s);
  double w = 0.0;
  for (int i = 0; i < LEN; ++i) {
    double s = fabs(a * x[i]) + fabs(b * y[i]);
    double e = zf[i] == zs[i] ? 0.0 : fabs(zf[i] - zs[i]) / s;
    if (!(e <= w)) w = e;
  }
  return w;
}

static pair pnew(SUNContext ctx) {
  pair p = {N_VNew_Serial(LEN, ctx), N_VNew_Serial(LEN, ctx)};
  CHECK(p.f && p.s);
  CHECK(dal__nvec_fast(p.f) == 0);
  return p;
}

static void pfill(pair p, double lo_zero) {
  double *a = N_VGetArrayPointer(p.f), *b = N_VGetArrayPointer(p.s);
  for (int i = 0; i < LEN; ++i) {
    double x = 10.0 * urand();
    if (lo_zero > 0 && fabs(x) < lo_zero) x = 0.0; // some exact zeros
    a[i] = b[i] = x;
  }
}

static double pcmp(pair p) {
  return rel(N_VGetArrayPointer(p.f), N_VGetArrayPointer(p.s), LEN, 1e-300);
}

static void pfree(pair p) {
  N_VDestroy(p.f);
  N_VDestroy(p.s);
}

int main(void) {
  SUNContext ctx = NULL;
  CHECK(SUNContext_Create(NULL, &ctx) == 0);
  const double tol = 4.0 * 2.2e-16; // one rounding per term at most
  pair x = pnew(ctx), y = pnew(ctx), z = pnew(ctx), w = pnew(ctx), id = pnew(ctx);
  pfill(x, 0.3);
  pfill(y, 0.0);
  pfill(w, 0.0);
  pfill(z, 0.0);
  {
    double *a = N_VGetArrayPointer(id.f), *b = N_VGetArrayPointer(id.s);
    for (int i = 0; i < LEN; ++i)
      a[i] = b[i] = i % 3 ? 1.0 : 0.0;
  }
  // a clone inherits the kernels
  N_Vector cl = N_VClone(x.f);
  CHECK(cl && cl->ops->nvlinearsum == x.f->ops->nvlinearsum);
  CHECK(x.f->ops->nvlinearsum != x.s->ops->nvlinearsum);
  N_VDestroy(cl);

  // element-wise operations (the scalars include SUNDIALS' special cases 1, -1, a == b)
  const double coef[][2] = {{0.7, -1.3}, {1.0, 1.0},  {1.0, -1.0}, {-1.0, 1.0},
                            {2.5, 2.5},  {2.5, -2.5}, {0.0, 3.0},  {1.0, 0.4}};
  double zk[LEN];
  for (size_t k = 0; k < sizeof coef / sizeof coef[0]; ++k) {
    double a = coef[k][0], b = coef[k][1], e;
    N_VLinearSum(a, x.f, b, y.f, z.f);
    N_VLinearSum(a, x.s, b, y.s, z.s);
    e = lsum_err(z, a, N_VGetArrayPointer(x.s), b, N_VGetArrayPointer(y.s));
    CHECK_MSG(e <= tol, "linear sum (%g, %g): %.2e", a, b, e);
    // aliased: z = a x + b z
    pfill(z, 0.0);
    memcpy(zk, N_VGetArrayPointer(z.s), sizeof zk);
    N_VLinearSum(a, x.f, b, z.f, z.f);
    N_VLinearSum(a, x.s, b, z.s, z.s);
    e = lsum_err(z, a, N_VGetArrayPointer(x.s), b, zk);
    CHECK_MSG(e <= tol, "aliased linear sum (%g, %g): %.2e", a, b, e);
  }
  N_VConst(0.25, z.f);
  N_VConst(0.25, z.s);
  CHECK(pcmp(z) == 0.0);
  N_VProd(x.f, y.f, z.f);
  N_VProd(x.s, y.s, z.s);
  CHECK(pcmp(z) == 0.0);
  N_VDiv(y.f, w.f, z.f);
  N_VDiv(y.s, w.s, z.s);
  CHECK(pcmp(z) == 0.0);
  N_VScale(-3.5, x.f, z.f);
  N_VScale(-3.5, x.s, z.s);
  CHECK(pcmp(z) == 0.0);
  N_VAbs(x.f, z.f);
  N_VAbs(x.s, z.s);
  CHECK(pcmp(z) == 0.0);
  N_VInv(w.f, z.f);
  N_VInv(w.s, z.s);
  CHECK(pcmp(z) == 0.0);
  N_VAddConst(x.f, 1.5, z.f);
  N_VAddConst(x.s, 1.5, z.s);
  CHECK(pcmp(z) == 0.0);
  N_VCompare(2.0, x.f, z.f);
  N_VCompare(2.0, x.s, z.s);
  CHECK(pcmp(z) == 0.0);
  // x has exact zeros: both report them and agree on the rest
  pfill(z, 0.0);
  CHECK(N_VInvTest(x.f, z.f) == N_VInvTest(x.s, z.s));
  CHECK(pcmp(z) == 0.0);
  CHECK(N_VInvTest(w.f, z.f) == N_VInvTest(w.s, z.s));
  CHECK(pcmp(z) == 0.0);

  // reductions (summed in index order by both)
  CHECK(rel1(N_VDotProd(x.f, y.f), N_VDotProd(x.s, y.s)) <= LEN * tol);
  CHECK(N_VMaxNorm(x.f) == N_VMaxNorm(x.s));
  CHECK(rel1(N_VWrmsNorm(x.f, w.f), N_VWrmsNorm(x.s, w.s)) <= LEN * tol);
  CHECK(rel1(N_VWrmsNormMask(x.f, w.f, id.f), N_VWrmsNormMask(x.s, w.s, id.s)) <= LEN * tol);
  CHECK(N_VMin(x.f) == N_VMin(x.s));
  CHECK(rel1(N_VWL2Norm(x.f, w.f), N_VWL2Norm(x.s, w.s)) <= LEN * tol);
  CHECK(rel1(N_VL1Norm(x.f), N_VL1Norm(x.s)) <= LEN * tol);
  CHECK(N_VMinQuotient(y.f, x.f) == N_VMinQuotient(y.s, x.s));
  N_VConst(0.0, z.f);
  N_VConst(0.0, z.s);
  CHECK(N_VMinQuotient(y.f, z.f) == N_VMinQuotient(y.s, z.s)); // every denominator 0
  CHECK(rel1(N_VWSqrSumLocal(x.f, w.f), N_VWSqrSumLocal(x.s, w.s)) <= LEN * tol);
  CHECK(rel1(N_VWSqrSumMaskLocal(x.f, w.f, id.f), N_VWSqrSumMaskLocal(x.s, w.s, id.s)) <=
        LEN * tol);

  // fused and vector-array forms against their definitions by single SUNDIALS operations
  pair X[NV], Y[NV], Z[NV];
  N_Vector Xf[NV], Xs[NV], Yf[NV], Ys[NV], Zf[NV], Zs[NV];
  double c[NV], nf[NV], ns[NV];
  for (int k = 0; k < NV; ++k) {
    X[k] = pnew(ctx), Y[k] = pnew(ctx), Z[k] = pnew(ctx);
    pfill(X[k], 0.0);
    pfill(Y[k], 0.0);
    Xf[k] = X[k].f, Xs[k] = X[k].s, Yf[k] = Y[k].f, Ys[k] = Y[k].s;
    Zf[k] = Z[k].f, Zs[k] = Z[k].s;
    c[k] = 2.0 * urand();
  }
  for (int nv = 1; nv <= NV; ++nv) {
    // linear combination: z = c0 X0 + c1 X1 + ...; also into X0 itself
    for (int into_x0 = 0; into_x0 < 2; ++into_x0) {
      if (into_x0) pfill(X[0], 0.0);
      N_Vector zf = into_x0 ? X[0].f : z.f, zs = into_x0 ? X[0].s : z.s;
      CHECK(N_VLinearCombination(nv, c, Xf, zf) == 0);
      N_VScale(c[0], Xs[0], zs);
      for (int k = 1; k < nv; ++k)
        N_VLinearSum(c[k], Xs[k], 1.0, zs, zs);
      double e = rel(N_VGetArrayPointer(zf), N_VGetArrayPointer(zs), LEN, 1e-300);
      CHECK_MSG(e <= tol, "linear combination of %d%s: %.2e", nv, into_x0 ? " into X0" : "", e);
    }
    CHECK(N_VScaleAddMulti(nv, c, x.f, Yf, Zf) == 0);
    for (int k = 0; k < nv; ++k) {
      N_VLinearSum(c[k], x.s, 1.0, Ys[k], Zs[k]);
      CHECK(pcmp(Z[k]) <= tol);
    }
    CHECK(N_VDotProdMulti(nv, x.f, Yf, nf) == 0);
    for (int k = 0; k < nv; ++k)
      CHECK(rel1(nf[k], N_VDotProd(x.s, Ys[k])) <= LEN * tol);
    CHECK(N_VLinearSumVectorArray(nv, 0.3, Xf, -1.7, Yf, Zf) == 0);
    for (int k = 0; k < nv; ++k) {
      N_VLinearSum(0.3, Xs[k], -1.7, Ys[k], Zs[k]);
      CHECK(pcmp(Z[k]) <= tol);
    }
    CHECK(N_VScaleVectorArray(nv, c, Xf, Zf) == 0);
    for (int k = 0; k < nv; ++k) {
      N_VScale(c[k], Xs[k], Zs[k]);
      CHECK(pcmp(Z[k]) == 0.0);
    }
    CHECK(N_VConstVectorArray(nv, -2.0, Zf) == 0);
    for (int k = 0; k < nv; ++k) {
      N_VConst(-2.0, Zs[k]);
      CHECK(pcmp(Z[k]) == 0.0);
    }
    CHECK(N_VWrmsNormVectorArray(nv, Xf, Yf, nf) == 0);
    CHECK(N_VWrmsNormMaskVectorArray(nv, Xf, Yf, id.f, ns) == 0);
    for (int k = 0; k < nv; ++k) {
      CHECK(rel1(nf[k], N_VWrmsNorm(Xs[k], Ys[k])) <= LEN * tol);
      CHECK(rel1(ns[k], N_VWrmsNormMask(Xs[k], Ys[k], id.s)) <= LEN * tol);
    }
  }
  for (int k = 0; k < NV; ++k) {
    pfree(X[k]);
    pfree(Y[k]);
    pfree(Z[k]);
  }
  pfree(x);
  pfree(y);
  pfree(z);
  pfree(w);
  pfree(id);
  // not a serial vector: refused, unchanged
  CHECK(dal__nvec_fast(NULL) == -1);
  SUNContext_Free(&ctx);
  return check_summary("test_nvec");
}
