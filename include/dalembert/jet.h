// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Jets: order-3 truncated Taylor numbers along one direction, for exact derivatives.
///
/// A jet x = (v, d, dd, d3) stands for the function s -> x(s) near s = 0 with x(0) = v,
/// x'(0) = d, x''(0) = dd and x'''(0) = d3. Every smooth user function (coordinate map,
/// constraint, potential, Lagrangian, path) is written once over jets; evaluating it along a
/// chosen direction gives the directional derivatives exactly up to rounding.
///
/// Orders: the equations of motion read v, d and dd; the third coefficient d3 serves the exact
/// tangent (linearization, normal modes, equilibria, Lyapunov exponents: analysis.h), which
/// needs the derivative of the curvature terms gamma along a tangent direction. The lower
/// coefficients never read d3, so a function is exact to order 2 whatever its d3 holds.
///
/// Third derivatives of user functions (version 2 of this header appended d3): a function
/// written with the operations below (dal_add ... dal_norm, dal_const, dal_var) is exact to
/// order 3 without change. Jets built from explicit derivative values with the order-2
/// constructors dal_jet_make and dal_jet_chain carry d3 = NaN ("unknown"): ordinary evaluation
/// is unaffected, and the tangent routines report the function (DAL_E_DOMAIN) instead of
/// using a wrong third derivative; use dal_jet_make3 / dal_jet_chain3 to give it. A jet built
/// by a struct initializer with three values, {v, d, dd}, has d3 = 0 by the C rules: correct
/// only when the third derivative really is 0 (GCC and clang warn about it under -Wextra,
/// -Wmissing-field-initializers).
///
/// Domain errors are not trapped here: sqrt or log of a negative number, a derivative of
/// sqrt at 0, division by zero, asin outside [-1, 1] all produce NaN or inf in the jet.
/// The library checks every output of a user or primitive jet function and reports the
/// object that produced a non-finite value (status DAL_E_DOMAIN) at the call that made it.
#ifndef DAL_JET_H
#define DAL_JET_H

#include <math.h>

#include "dalembert/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Version of the jet layout: 1 = (v, d, dd); 2 = (v, d, dd, d3), d3 appended.
#define DAL_JET_VERSION 2

/// Order-3 jet: value v and the first, second and third directional derivatives.
typedef struct dal_jet {
  double v;  ///< value
  double d;  ///< first derivative along the direction
  double dd; ///< second derivative along the direction
  double d3; ///< third derivative along the direction (NaN: not known; see above)
} dal_jet;

/// A constant: (c, 0, 0, 0).
static inline dal_jet dal_const(double c) {
  dal_jet r = {c, 0.0, 0.0, 0.0};
  return r;
}

/// An independent variable x moving with rate `dir` along the direction: (x, dir, 0, 0).
static inline dal_jet dal_var(double x, double dir) {
  dal_jet r = {x, dir, 0.0, 0.0};
  return r;
}

/// Order-2 constructor (value, first, second derivative); the third derivative is unknown
/// (d3 = NaN). Use dal_jet_make3 when it is known.
static inline dal_jet dal_jet_make(double v, double d, double dd) {
  dal_jet r = {v, d, dd, NAN};
  return r;
}

/// Full constructor (value, first, second and third derivative).
static inline dal_jet dal_jet_make3(double v, double d, double dd, double d3) {
  dal_jet r = {v, d, dd, d3};
  return r;
}

/// 1 when the value and the first two derivatives are finite, else 0 (d3 is not looked at:
/// the equations of motion do not read it).
static inline int dal_jet_isfinite(dal_jet a) {
  return isfinite(a.v) && isfinite(a.d) && isfinite(a.dd);
}

/// 1 when all four coefficients, the third derivative included, are finite, else 0.
static inline int dal_jet_isfinite3(dal_jet a) {
  return isfinite(a.v) && isfinite(a.d) && isfinite(a.dd) && isfinite(a.d3);
}

/// Chain rule to order 3 for a scalar function f with f(a) = f0, f'(a) = f1, f''(a) = f2,
/// f'''(a) = f3: (f o a)''' = f3 a'^3 + 3 f2 a' a'' + f1 a'''.
static inline dal_jet dal_jet_chain3(dal_jet a, double f0, double f1, double f2, double f3) {
  dal_jet r = {f0, f1 * a.d, f1 * a.dd + f2 * a.d * a.d,
               f1 * a.d3 + a.d * (3.0 * f2 * a.dd + f3 * a.d * a.d)};
  return r;
}

/// Order-2 chain rule (f0, f1, f2 as in dal_jet_chain3); the third derivative is unknown
/// (d3 = NaN). Use dal_jet_chain3 when f''' is known.
static inline dal_jet dal_jet_chain(dal_jet a, double f0, double f1, double f2) {
  return dal_jet_chain3(a, f0, f1, f2, NAN);
}

/// a + b
static inline dal_jet dal_add(dal_jet a, dal_jet b) {
  dal_jet r = {a.v + b.v, a.d + b.d, a.dd + b.dd, a.d3 + b.d3};
  return r;
}

/// a - b
static inline dal_jet dal_sub(dal_jet a, dal_jet b) {
  dal_jet r = {a.v - b.v, a.d - b.d, a.dd - b.dd, a.d3 - b.d3};
  return r;
}

/// -a
static inline dal_jet dal_neg(dal_jet a) {
  dal_jet r = {-a.v, -a.d, -a.dd, -a.d3};
  return r;
}

/// s * a for a real s
static inline dal_jet dal_scale(dal_jet a, double s) {
  dal_jet r = {s * a.v, s * a.d, s * a.dd, s * a.d3};
  return r;
}

/// a + c for a real c
static inline dal_jet dal_addc(dal_jet a, double c) {
  dal_jet r = {a.v + c, a.d, a.dd, a.d3};
  return r;
}

/// a * b
static inline dal_jet dal_mul(dal_jet a, dal_jet b) {
  dal_jet r = {a.v * b.v, a.d * b.v + a.v * b.d, a.dd * b.v + 2.0 * a.d * b.d + a.v * b.dd,
               a.d3 * b.v + 3.0 * (a.dd * b.d + a.d * b.dd) + a.v * b.d3};
  return r;
}

/// a / b (inf or NaN when b = 0)
static inline dal_jet dal_div(dal_jet a, dal_jet b) {
  double q = a.v / b.v;
  double qd = (a.d - q * b.d) / b.v;
  double qdd = (a.dd - 2.0 * qd * b.d - q * b.dd) / b.v;
  dal_jet r = {q, qd, qdd, (a.d3 - 3.0 * (qdd * b.d + qd * b.dd) - q * b.d3) / b.v};
  return r;
}

/// a * a
static inline dal_jet dal_sq(dal_jet a) {
  dal_jet r = {a.v * a.v, 2.0 * a.v * a.d, 2.0 * (a.d * a.d + a.v * a.dd),
               2.0 * (a.v * a.d3 + 3.0 * a.d * a.dd)};
  return r;
}

/// sqrt(a); NaN for a < 0; at a = 0 the derivatives are inf/NaN unless a is constant.
static inline dal_jet dal_sqrt(dal_jet a) {
  double s = sqrt(a.v);
  if (a.d == 0.0 && a.dd == 0.0)
    return dal_jet_make3(s, 0.0, 0.0, a.d3 == 0.0 ? 0.0 : a.d3 / (2.0 * s));
  double d = a.d / (2.0 * s);
  double dd = (a.dd - 2.0 * d * d) / (2.0 * s);
  dal_jet r = {s, d, dd, (a.d3 - 6.0 * d * dd) / (2.0 * s)};
  return r;
}

/// a^p for a real exponent p (a > 0 unless p is an integer; see dal_powi).
static inline dal_jet dal_pow(dal_jet a, double p) {
  if (p == 0.0) return dal_const(1.0);
  double f0 = pow(a.v, p);
  double f1 = p * pow(a.v, p - 1.0);
  double f2 = p * (p - 1.0) * pow(a.v, p - 2.0);
  double c3 = p * (p - 1.0) * (p - 2.0); // 0 for p = 1, 2: no pow(0, < 0) then
  double f3 = c3 == 0.0 ? 0.0 : c3 * pow(a.v, p - 3.0);
  return dal_jet_chain3(a, f0, f1, f2, f3);
}

/// a^n for an integer n (any sign of a; a = 0 with n < 0 gives inf). Defined for every int n,
/// INT_MIN included (|n| is formed in unsigned arithmetic).
static inline dal_jet dal_powi(dal_jet a, int n) {
  if (n == 0) return dal_const(1.0);
  if (n == 1) return a;
  double f0 = 1.0, f1, f2, f3;
  unsigned m = n < 0 ? 0u - (unsigned)n : (unsigned)n; // |n| without overflow at INT_MIN
  double pm2 = 1.0;                                    // a^(m-2) by repeated squaring when m >= 2
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
    f3 = 0.0;
    if (m >= 3) {
      double pm3 = 1.0, base = a.v; // a^(m-3), also by squaring (finite at a = 0)
      for (unsigned e = m - 3; e; e >>= 1) {
        if (e & 1) pm3 *= base;
        base *= base;
      }
      f3 = (double)n * ((double)n - 1.0) * ((double)n - 2.0) * pm3;
    }
  } else {
    double pm = (m >= 2 ? pm2 * a.v * a.v : a.v); // a^m
    f0 = 1.0 / pm;
    f1 = (double)n * f0 / a.v;
    f2 = (double)n * ((double)n - 1.0) * f0 / (a.v * a.v);
    f3 = (double)n * ((double)n - 1.0) * ((double)n - 2.0) * f0 / (a.v * a.v * a.v);
  }
  return dal_jet_chain3(a, f0, f1, f2, f3);
}

/// exp(a)
static inline dal_jet dal_exp(dal_jet a) {
  double e = exp(a.v);
  return dal_jet_chain3(a, e, e, e, e);
}

/// log(a); -inf at 0 and NaN for a < 0.
static inline dal_jet dal_log(dal_jet a) {
  double a2 = a.v * a.v;
  return dal_jet_chain3(a, log(a.v), 1.0 / a.v, -1.0 / a2, 2.0 / (a2 * a.v));
}

/// sin(a)
static inline dal_jet dal_sin(dal_jet a) {
  double s = sin(a.v), c = cos(a.v);
  return dal_jet_chain3(a, s, c, -s, -c);
}

/// cos(a)
static inline dal_jet dal_cos(dal_jet a) {
  double s = sin(a.v), c = cos(a.v);
  return dal_jet_chain3(a, c, -s, -c, s);
}

/// sin(a) and cos(a) together, from one evaluation of each function's value.
static inline void dal_sincos(dal_jet a, dal_jet *s, dal_jet *c) {
  double sv = sin(a.v), cv = cos(a.v);
  *s = dal_jet_chain3(a, sv, cv, -sv, -cv);
  *c = dal_jet_chain3(a, cv, -sv, -cv, sv);
}

/// tan(a)
static inline dal_jet dal_tan(dal_jet a) {
  double t = tan(a.v), u = 1.0 + t * t;
  return dal_jet_chain3(a, t, u, 2.0 * t * u, 2.0 * u * (u + 2.0 * t * t));
}

/// asin(a); NaN outside [-1, 1], inf derivatives at +-1.
static inline dal_jet dal_asin(dal_jet a) {
  double w = (1.0 - a.v) * (1.0 + a.v), f1 = 1.0 / sqrt(w); // 1 - a^2 accurate near +-1
  return dal_jet_chain3(a, asin(a.v), f1, a.v * f1 / w, (1.0 + 2.0 * a.v * a.v) * f1 / (w * w));
}

/// acos(a); NaN outside [-1, 1], inf derivatives at +-1.
static inline dal_jet dal_acos(dal_jet a) {
  double w = (1.0 - a.v) * (1.0 + a.v), f1 = 1.0 / sqrt(w); // 1 - a^2 accurate near +-1
  return dal_jet_chain3(a, acos(a.v), -f1, -a.v * f1 / w, -(1.0 + 2.0 * a.v * a.v) * f1 / (w * w));
}

/// atan(a)
static inline dal_jet dal_atan(dal_jet a) {
  double u = 1.0 / (1.0 + a.v * a.v);
  return dal_jet_chain3(a, atan(a.v), u, -2.0 * a.v * u * u, (6.0 * a.v * a.v - 2.0) * u * u * u);
}

/// atan2(y, x), the angle of the point (x, y); derivatives are inf/NaN at the origin.
static inline dal_jet dal_atan2(dal_jet y, dal_jet x) {
  // angle' r2 = num with r2 = x^2 + y^2, num = x y' - y x'; differentiated twice
  double r2 = x.v * x.v + y.v * y.v;
  double num = x.v * y.d - y.v * x.d;
  double d = num / r2;
  double numd = x.v * y.dd - y.v * x.dd;
  double r2d = 2.0 * (x.v * x.d + y.v * y.d);
  double dd = (numd - d * r2d) / r2;
  double numdd = x.d * y.dd - y.d * x.dd + x.v * y.d3 - y.v * x.d3;
  double r2dd = 2.0 * (x.d * x.d + x.v * x.dd + y.d * y.d + y.v * y.dd);
  dal_jet r = {atan2(y.v, x.v), d, dd, (numdd - 2.0 * dd * r2d - d * r2dd) / r2};
  return r;
}

/// sinh(a)
static inline dal_jet dal_sinh(dal_jet a) {
  double s = sinh(a.v), c = cosh(a.v);
  return dal_jet_chain3(a, s, c, s, c);
}

/// cosh(a)
static inline dal_jet dal_cosh(dal_jet a) {
  double s = sinh(a.v), c = cosh(a.v);
  return dal_jet_chain3(a, c, s, c, s);
}

/// tanh(a)
static inline dal_jet dal_tanh(dal_jet a) {
  double c = cosh(a.v), t = tanh(a.v), u = 1.0 / (c * c); // sech^2, not 1 - t^2 (cancels)
  return dal_jet_chain3(a, t, u, -2.0 * t * u, u * (4.0 * t * t - 2.0 * u));
}

/// hypot(a, b) = sqrt(a^2 + b^2) without overflow; derivatives inf/NaN at the origin
/// unless both arguments are constant.
static inline dal_jet dal_hypot(dal_jet a, dal_jet b) {
  double h = hypot(a.v, b.v);
  if (a.d == 0.0 && a.dd == 0.0 && b.d == 0.0 && b.dd == 0.0)
    return dal_jet_make3(h, 0.0, 0.0,
                         a.d3 == 0.0 && b.d3 == 0.0 ? 0.0 : (a.v * a.d3 + b.v * b.d3) / h);
  // h h' = a a' + b b', differentiated twice
  double d = (a.v * a.d + b.v * b.d) / h;
  double dd = (a.d * a.d + a.v * a.dd + b.d * b.d + b.v * b.dd - d * d) / h;
  double p2 = 3.0 * (a.d * a.dd + b.d * b.dd) + a.v * a.d3 + b.v * b.d3;
  dal_jet r = {h, d, dd, (p2 - 3.0 * d * dd) / h};
  return r;
}

/// Euclidean norm of a jet vector x(n); same domain rules as dal_hypot.
static inline dal_jet dal_norm(const dal_jet *x, int n) {
  dal_jet s = dal_const(0.0);
  for (int i = 0; i < n; ++i)
    s = dal_add(s, dal_sq(x[i]));
  return dal_sqrt(s);
}

#ifdef __cplusplus
}
#endif
#endif
