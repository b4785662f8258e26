// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Jets: order-2 truncated Taylor numbers along one direction, for exact derivatives.
//
// A jet x = (v, d, dd) stands for the function s -> x(s) near s = 0 with x(0) = v,
// x'(0) = d and x''(0) = dd. Every smooth user function (coordinate map, constraint,
// potential, Lagrangian, path) is written once over jets; evaluating it along a chosen
// direction gives the directional first and second derivative exactly up to rounding.
//
// Domain errors are not trapped here: sqrt or log of a negative number, a derivative of
// sqrt at 0, division by zero, asin outside [-1, 1] all produce NaN or inf in the jet.
// The library checks every output of a user or primitive jet function and reports the
// object that produced a non-finite value (status DAL_E_DOMAIN) at the call that made it.
#ifndef DAL_JET_H
#define DAL_JET_H

#include <math.h>

#include "dalembert/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Order-2 jet: value v, first directional derivative d, second directional derivative dd.
typedef struct dal_jet {
  double v;  ///< value
  double d;  ///< first derivative along the direction
  double dd; ///< second derivative along the direction
} dal_jet;

/// A constant: (c, 0, 0).
static inline dal_jet dal_const(double c) {
  dal_jet r = {c, 0.0, 0.0};
  return r;
}

/// An independent variable x moving with rate `dir` along the direction: (x, dir, 0).
static inline dal_jet dal_var(double x, double dir) {
  dal_jet r = {x, dir, 0.0};
  return r;
}

/// Full constructor (value, first, second derivative).
static inline dal_jet dal_jet_make(double v, double d, double dd) {
  dal_jet r = {v, d, dd};
  return r;
}

/// 1 when value and both derivatives are finite, else 0.
static inline int dal_jet_isfinite(dal_jet a) {
  return isfinite(a.v) && isfinite(a.d) && isfinite(a.dd);
}

/// Chain rule for a scalar function f with f(a) = f0, f'(a) = f1, f''(a) = f2.
static inline dal_jet dal_jet_chain(dal_jet a, double f0, double f1, double f2) {
  dal_jet r = {f0, f1 * a.d, f1 * a.dd + f2 * a.d * a.d};
  return r;
}

/// a + b
static inline dal_jet dal_add(dal_jet a, dal_jet b) {
  dal_jet r = {a.v + b.v, a.d + b.d, a.dd + b.dd};
  return r;
}

/// a - b
static inline dal_jet dal_sub(dal_jet a, dal_jet b) {
  dal_jet r = {a.v - b.v, a.d - b.d, a.dd - b.dd};
  return r;
}

/// -a
static inline dal_jet dal_neg(dal_jet a) {
  dal_jet r = {-a.v, -a.d, -a.dd};
  return r;
}

/// s * a for a real s
static inline dal_jet dal_scale(dal_jet a, double s) {
  dal_jet r = {s * a.v, s * a.d, s * a.dd};
  return r;
}

/// a + c for a real c
static inline dal_jet dal_addc(dal_jet a, double c) {
  dal_jet r = {a.v + c, a.d, a.dd};
  return r;
}

/// a * b
static inline dal_jet dal_mul(dal_jet a, dal_jet b) {
  dal_jet r = {a.v * b.v, a.d * b.v + a.v * b.d, a.dd * b.v + 2.0 * a.d * b.d + a.v * b.dd};
  return r;
}

/// a / b (inf or NaN when b = 0)
static inline dal_jet dal_div(dal_jet a, dal_jet b) {
  double q = a.v / b.v;
  double qd = (a.d - q * b.d) / b.v;
  dal_jet r = {q, qd, (a.dd - 2.0 * qd * b.d - q * b.dd) / b.v};
  return r;
}

/// a * a
static inline dal_jet dal_sq(dal_jet a) {
  dal_jet r = {a.v * a.v, 2.0 * a.v * a.d, 2.0 * (a.d * a.d + a.v * a.dd)};
  return r;
}

/// sqrt(a); NaN for a < 0; at a = 0 the derivatives are inf/NaN unless a is constant.
static inline dal_jet dal_sqrt(dal_jet a) {
  double s = sqrt(a.v);
  if (a.d == 0.0 && a.dd == 0.0) return dal_jet_make(s, 0.0, 0.0);
  double d = a.d / (2.0 * s);
  dal_jet r = {s, d, (a.dd - 2.0 * d * d) / (2.0 * s)};
  return r;
}

/// a^p for a real exponent p (a > 0 unless p is an integer; see dal_powi).
static inline dal_jet dal_pow(dal_jet a, double p) {
  if (p == 0.0) return dal_const(1.0);
  double f0 = pow(a.v, p);
  double f1 = p * pow(a.v, p - 1.0);
  double f2 = p * (p - 1.0) * pow(a.v, p - 2.0);
  return dal_jet_chain(a, f0, f1, f2);
}

/// a^n for an integer n (any sign of a; a = 0 with n < 0 gives inf). Defined for every int n,
/// INT_MIN included (|n| is formed in unsigned arithmetic).
static inline dal_jet dal_powi(dal_jet a, int n) {
  if (n == 0) return dal_const(1.0);
  if (n == 1) return a;
  double f0 = 1.0, f1, f2;
  unsigned m = n < 0 ? 0u - (unsigned)n : (unsigned)n; // |n| without overflow at INT_MIN
  double pm2 = 1.0; // a^(m-2) by repeated squaring when m >= 2
  if (m >= 2) {
    double base = a.v;
    unsigned e = m - 2;
    while (e) {
      if (e & 1) pm2 *= base;
      base *= base;
      e >>= 1;
    }
  }
  if (n > 0) {
    double pm1 = m >= 2 ? pm2 * a.v : 1.0;
    f0 = pm1 * a.v;
    f1 = (double)n * pm1;
    f2 = m >= 2 ? (double)n * ((double)n - 1.0) * pm2 : 0.0;
  } else {
    double pm = (m >= 2 ? pm2 * a.v * a.v : a.v); // a^m
    f0 = 1.0 / pm;
    f1 = (double)n * f0 / a.v;
    f2 = (double)n * ((double)n - 1.0) * f0 / (a.v * a.v);
  }
  return dal_jet_chain(a, f0, f1, f2);
}

/// exp(a)
static inline dal_jet dal_exp(dal_jet a) {
  double e = exp(a.v);
  return dal_jet_chain(a, e, e, e);
}

/// log(a); -inf at 0 and NaN for a < 0.
static inline dal_jet dal_log(dal_jet a) {
  return dal_jet_chain(a, log(a.v), 1.0 / a.v, -1.0 / (a.v * a.v));
}

/// sin(a)
static inline dal_jet dal_sin(dal_jet a) {
  double s = sin(a.v), c = cos(a.v);
  return dal_jet_chain(a, s, c, -s);
}

/// cos(a)
static inline dal_jet dal_cos(dal_jet a) {
  double s = sin(a.v), c = cos(a.v);
  return dal_jet_chain(a, c, -s, -c);
}

/// sin(a) and cos(a) together, from one evaluation of each function's value.
static inline void dal_sincos(dal_jet a, dal_jet *s, dal_jet *c) {
  double sv = sin(a.v), cv = cos(a.v);
  *s = dal_jet_chain(a, sv, cv, -sv);
  *c = dal_jet_chain(a, cv, -sv, -cv);
}

/// tan(a)
static inline dal_jet dal_tan(dal_jet a) {
  double t = tan(a.v), u = 1.0 + t * t;
  return dal_jet_chain(a, t, u, 2.0 * t * u);
}

/// asin(a); NaN outside [-1, 1], inf derivatives at +-1.
static inline dal_jet dal_asin(dal_jet a) {
  double w = (1.0 - a.v) * (1.0 + a.v), f1 = 1.0 / sqrt(w); // 1 - a^2 accurate near +-1
  return dal_jet_chain(a, asin(a.v), f1, a.v * f1 / w);
}

/// acos(a); NaN outside [-1, 1], inf derivatives at +-1.
static inline dal_jet dal_acos(dal_jet a) {
  double w = (1.0 - a.v) * (1.0 + a.v), f1 = 1.0 / sqrt(w); // 1 - a^2 accurate near +-1
  return dal_jet_chain(a, acos(a.v), -f1, -a.v * f1 / w);
}

/// atan(a)
static inline dal_jet dal_atan(dal_jet a) {
  double u = 1.0 / (1.0 + a.v * a.v);
  return dal_jet_chain(a, atan(a.v), u, -2.0 * a.v * u * u);
}

/// atan2(y, x), the angle of the point (x, y); derivatives are inf/NaN at the origin.
static inline dal_jet dal_atan2(dal_jet y, dal_jet x) {
  double r2 = x.v * x.v + y.v * y.v;
  double num = x.v * y.d - y.v * x.d;
  double d = num / r2;
  double numd = x.v * y.dd - y.v * x.dd;
  double r2d = 2.0 * (x.v * x.d + y.v * y.d);
  dal_jet r = {atan2(y.v, x.v), d, (numd - d * r2d) / r2};
  return r;
}

/// sinh(a)
static inline dal_jet dal_sinh(dal_jet a) {
  double s = sinh(a.v), c = cosh(a.v);
  return dal_jet_chain(a, s, c, s);
}

/// cosh(a)
static inline dal_jet dal_cosh(dal_jet a) {
  double s = sinh(a.v), c = cosh(a.v);
  return dal_jet_chain(a, c, s, c);
}

/// tanh(a)
static inline dal_jet dal_tanh(dal_jet a) {
  double c = cosh(a.v), t = tanh(a.v), u = 1.0 / (c * c); // sech^2, not 1 - t^2 (cancels)
  return dal_jet_chain(a, t, u, -2.0 * t * u);
}

/// hypot(a, b) = sqrt(a^2 + b^2) without overflow; derivatives inf/NaN at the origin
/// unless both arguments are constant.
static inline dal_jet dal_hypot(dal_jet a, dal_jet b) {
  double h = hypot(a.v, b.v);
  if (a.d == 0.0 && a.dd == 0.0 && b.d == 0.0 && b.dd == 0.0) return dal_const(h);
  double d = (a.v * a.d + b.v * b.d) / h;
  dal_jet r = {h, d, (a.d * a.d + a.v * a.dd + b.d * b.d + b.v * b.dd - d * d) / h};
  return r;
}

/// Euclidean norm of a jet vector x(n); same domain rules as dal_hypot.
static inline dal_jet dal_norm(const dal_jet *x, int n) {
  dal_jet s = dal_const(0.0);
  for (int i = 0; i < n; ++i) s = dal_add(s, dal_sq(x[i]));
  return dal_sqrt(s);
}

#ifdef __cplusplus
}
#endif
#endif
