// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Jets: every operation against hand derivatives and finite differences, identities, domains.
//
// Every operation of jet.h is applied to input jets x = (v, d, dd, d3), i.e. to curves
// x(s) = v + d s + dd s^2 / 2 + d3 s^3 / 6, at random points and directions. References:
//  - hand-written partial derivatives f_i, f_ij, f_ijk of each operation: the output jet must
//    be (f, sum f_i d_i, sum f_i dd_i + sum f_ij d_i d_j, sum f_i d3_i + 3 sum f_ij d_i dd_j +
//    sum f_ijk d_i d_j d_k) to ~1e-14 relative to its terms;
//  - central finite differences of the value along the curve, to their estimated truncation
//    and rounding error (fd.h for the first two derivatives; a Richardson-extrapolated third
//    difference with its own bound for the third, fd3_estimate; curve arguments are exact in
//    double);
//  - the lower coefficients never read d3 (bit-identical with d3 = NaN), and the order-2
//    constructors dal_jet_make / dal_jet_chain mark d3 unknown (NaN);
//  - identities (sin^2 + cos^2 = 1 with zero derivatives, exp(log x) = x, ...) and chain
//    rule through 3-4 nested functions against hand-differentiated closed forms;
//  - domain errors give non-finite jets, and the library reports them where they arise
//    (DAL_E_DOMAIN naming the primitive, particle, potential or Lagrangian).
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "fd.h"

#define NSAMPLE 300
#define TOL_AN 1e-14
#define PI 3.14159265358979323846

static unsigned long long seed = 0x9e3779b97f4a7c15ULL;

// ---------------------------------------------------------------------------------------------
// the operations under test, each with hand-written value, gradient and Hessian
typedef dal_jet op_jet_fn(const dal_jet *x, double p);
typedef void op_hand_fn(const double *x, double p, double *f, double *g, double *H);
/// third partial derivatives f_ijk into T[i * 4 + j * 2 + k] (zeroed by the caller)
typedef void op_hand3_fn(const double *x, double p, double *T);

typedef struct op {
  const char *name;
  int arity;           // 1 or 2 jet arguments
  double lo[2], hi[2]; // sampling box of the arguments
  double excl;         // resample when the argument (arity 1) or (x0, x1) is nearer 0
  double plo, phi;     // range of the real parameter p
  int pint;            // p is an integer
  op_jet_fn *jet;
  op_hand_fn *hand;
  op_hand3_fn *hand3; // NULL: the operation leaves d3 unknown (NaN)
} op;

static void zero_gh(double *g, double *H) {
  g[0] = g[1] = 0.0;
  H[0] = H[1] = H[2] = H[3] = 0.0;
}

// x^n by repeated multiplication (independent of dal_powi's squaring)
static double ipow(double x, int n) {
  double r = 1.0;
  for (int i = 0; i < (n < 0 ? -n : n); ++i)
    r *= x;
  return n < 0 ? 1.0 / r : r;
}

static dal_jet j_add(const dal_jet *x, double p) {
  (void)p;
  return dal_add(x[0], x[1]);
}
static void h_add(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  *f = x[0] + x[1];
  g[0] = g[1] = 1.0;
}
static dal_jet j_sub(const dal_jet *x, double p) {
  (void)p;
  return dal_sub(x[0], x[1]);
}
static void h_sub(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  *f = x[0] - x[1];
  g[0] = 1.0;
  g[1] = -1.0;
}
static dal_jet j_mul(const dal_jet *x, double p) {
  (void)p;
  return dal_mul(x[0], x[1]);
}
static void h_mul(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  *f = x[0] * x[1];
  g[0] = x[1];
  g[1] = x[0];
  H[1] = H[2] = 1.0;
}
static dal_jet j_div(const dal_jet *x, double p) {
  (void)p;
  return dal_div(x[0], x[1]);
}
static void h_div(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  double a = x[0], b = x[1];
  *f = a / b;
  g[0] = 1.0 / b;
  g[1] = -a / (b * b);
  H[0] = 0.0;
  H[1] = H[2] = -1.0 / (b * b);
  H[3] = 2.0 * a / (b * b * b);
}
static dal_jet j_neg(const dal_jet *x, double p) {
  (void)p;
  return dal_neg(x[0]);
}
static void h_neg(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  *f = -x[0];
  g[0] = -1.0;
}
static dal_jet j_scale(const dal_jet *x, double p) { return dal_scale(x[0], p); }
static void h_scale(const double *x, double p, double *f, double *g, double *H) {
  zero_gh(g, H);
  *f = p * x[0];
  g[0] = p;
}
static dal_jet j_addc(const dal_jet *x, double p) { return dal_addc(x[0], p); }
static void h_addc(const double *x, double p, double *f, double *g, double *H) {
  zero_gh(g, H);
  *f = x[0] + p;
  g[0] = 1.0;
}
static dal_jet j_sq(const dal_jet *x, double p) {
  (void)p;
  return dal_sq(x[0]);
}
static void h_sq(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  *f = x[0] * x[0];
  g[0] = 2.0 * x[0];
  H[0] = 2.0;
}
static dal_jet j_sqrt(const dal_jet *x, double p) {
  (void)p;
  return dal_sqrt(x[0]);
}
static void h_sqrt(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  *f = sqrt(x[0]);
  g[0] = 0.5 / *f;
  H[0] = -0.25 / (x[0] * *f);
}
static dal_jet j_pow(const dal_jet *x, double p) { return dal_pow(x[0], p); }
static void h_pow(const double *x, double p, double *f, double *g, double *H) {
  zero_gh(g, H);
  // x > 0 and real p: exp(p log x); negative bases only with integer p: repeated products
  *f = x[0] > 0 ? exp(p * log(x[0])) : ipow(x[0], (int)p);
  g[0] = p * *f / x[0];
  H[0] = p * (p - 1.0) * *f / (x[0] * x[0]);
}
static dal_jet j_powi(const dal_jet *x, double p) { return dal_powi(x[0], (int)p); }
static void h_powi(const double *x, double p, double *f, double *g, double *H) {
  zero_gh(g, H);
  int n = (int)p;
  *f = ipow(x[0], n);
  g[0] = n * ipow(x[0], n - 1);
  H[0] = n * (n - 1.0) * ipow(x[0], n - 2);
}
static dal_jet j_exp(const dal_jet *x, double p) {
  (void)p;
  return dal_exp(x[0]);
}
static void h_exp(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  *f = g[0] = H[0] = exp(x[0]);
}
static dal_jet j_log(const dal_jet *x, double p) {
  (void)p;
  return dal_log(x[0]);
}
static void h_log(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  *f = log(x[0]);
  g[0] = 1.0 / x[0];
  H[0] = -1.0 / (x[0] * x[0]);
}
static dal_jet j_sin(const dal_jet *x, double p) {
  (void)p;
  return dal_sin(x[0]);
}
static void h_sin(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  *f = sin(x[0]);
  g[0] = cos(x[0]);
  H[0] = -sin(x[0]);
}
static dal_jet j_cos(const dal_jet *x, double p) {
  (void)p;
  return dal_cos(x[0]);
}
static void h_cos(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  *f = cos(x[0]);
  g[0] = -sin(x[0]);
  H[0] = -cos(x[0]);
}
static dal_jet j_tan(const dal_jet *x, double p) {
  (void)p;
  return dal_tan(x[0]);
}
static void h_tan(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  double c = cos(x[0]);
  *f = tan(x[0]);
  g[0] = 1.0 / (c * c);                 // sec^2
  H[0] = 2.0 * sin(x[0]) / (c * c * c); // 2 sec^2 tan
}
static dal_jet j_asin(const dal_jet *x, double p) {
  (void)p;
  return dal_asin(x[0]);
}
static void h_asin(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  double w = (1.0 - x[0]) * (1.0 + x[0]);
  *f = asin(x[0]);
  g[0] = 1.0 / sqrt(w);
  H[0] = x[0] / (w * sqrt(w));
}
static dal_jet j_acos(const dal_jet *x, double p) {
  (void)p;
  return dal_acos(x[0]);
}
static void h_acos(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  double w = (1.0 - x[0]) * (1.0 + x[0]);
  *f = acos(x[0]);
  g[0] = -1.0 / sqrt(w);
  H[0] = -x[0] / (w * sqrt(w));
}
static dal_jet j_atan(const dal_jet *x, double p) {
  (void)p;
  return dal_atan(x[0]);
}
static void h_atan(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  double u = 1.0 + x[0] * x[0];
  *f = atan(x[0]);
  g[0] = 1.0 / u;
  H[0] = -2.0 * x[0] / (u * u);
}
// atan2(y, x): argument 0 is y, argument 1 is x
static dal_jet j_atan2(const dal_jet *x, double p) {
  (void)p;
  return dal_atan2(x[0], x[1]);
}
static void h_atan2(const double *a, double p, double *f, double *g, double *H) {
  (void)p;
  double y = a[0], x = a[1], r2 = x * x + y * y, r4 = r2 * r2;
  // value by quadrant from atan (independent of atan2)
  double base = atan(y / x);
  *f = x > 0 ? base : (y >= 0 ? base + PI : base - PI);
  g[0] = x / r2;
  g[1] = -y / r2;
  H[0] = -2.0 * x * y / r4;
  H[1] = H[2] = (y * y - x * x) / r4;
  H[3] = 2.0 * x * y / r4;
}
static dal_jet j_sinh(const dal_jet *x, double p) {
  (void)p;
  return dal_sinh(x[0]);
}
static void h_sinh(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  *f = H[0] = sinh(x[0]);
  g[0] = cosh(x[0]);
}
static dal_jet j_cosh(const dal_jet *x, double p) {
  (void)p;
  return dal_cosh(x[0]);
}
static void h_cosh(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  *f = H[0] = cosh(x[0]);
  g[0] = sinh(x[0]);
}
static dal_jet j_tanh(const dal_jet *x, double p) {
  (void)p;
  return dal_tanh(x[0]);
}
static void h_tanh(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  double c = cosh(x[0]);
  *f = tanh(x[0]);
  g[0] = 1.0 / (c * c);                   // sech^2
  H[0] = -2.0 * sinh(x[0]) / (c * c * c); // -2 sech^2 tanh
}
static dal_jet j_hypot(const dal_jet *x, double p) {
  (void)p;
  return dal_hypot(x[0], x[1]);
}
static void h_hypot(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  double a = x[0], b = x[1], r = sqrt(a * a + b * b), r3 = r * r * r;
  *f = r;
  g[0] = a / r;
  g[1] = b / r;
  H[0] = b * b / r3;
  H[1] = H[2] = -a * b / r3;
  H[3] = a * a / r3;
}
// the library's own chain helper with f = x^3 (f' = 3x^2, f'' = 6x)
static dal_jet j_chain(const dal_jet *x, double p) {
  (void)p;
  double v = x[0].v;
  return dal_jet_chain(x[0], v * v * v, 3.0 * v * v, 6.0 * v);
}
static void h_chain(const double *x, double p, double *f, double *g, double *H) {
  (void)p;
  zero_gh(g, H);
  *f = x[0] * x[0] * x[0];
  g[0] = 3.0 * x[0] * x[0];
  H[0] = 6.0 * x[0];
}
// ---------------------------------------------------------------------------------------------
// third partial derivatives f_ijk of each operation, by hand (T zeroed by the caller)
static void h3_zero(const double *x, double p, double *T) {
  (void)x;
  (void)p;
  (void)T;
}
static void h3_div(const double *x, double p, double *T) {
  (void)p;
  double a = x[0], b = x[1], b3 = b * b * b;
  // f = a / b: f_abb = 2 / b^3, f_bbb = -6 a / b^4, the others 0
  T[0 * 4 + 1 * 2 + 1] = T[1 * 4 + 0 * 2 + 1] = T[1 * 4 + 1 * 2 + 0] = 2.0 / b3;
  T[7] = -6.0 * a / (b3 * b);
}
static void h3_sqrt(const double *x, double p, double *T) {
  (void)p;
  T[0] = 0.375 / (x[0] * x[0] * sqrt(x[0])); // 3/8 x^-5/2
}
static void h3_pow(const double *x, double p, double *T) {
  double f = x[0] > 0 ? exp(p * log(x[0])) : ipow(x[0], (int)p);
  T[0] = p * (p - 1.0) * (p - 2.0) * f / (x[0] * x[0] * x[0]);
}
static void h3_powi(const double *x, double p, double *T) {
  int n = (int)p;
  T[0] = n * (n - 1.0) * (n - 2.0) * ipow(x[0], n - 3);
}
static void h3_exp(const double *x, double p, double *T) {
  (void)p;
  T[0] = exp(x[0]);
}
static void h3_log(const double *x, double p, double *T) {
  (void)p;
  T[0] = 2.0 / (x[0] * x[0] * x[0]);
}
static void h3_sin(const double *x, double p, double *T) {
  (void)p;
  T[0] = -cos(x[0]);
}
static void h3_cos(const double *x, double p, double *T) {
  (void)p;
  T[0] = sin(x[0]);
}
static void h3_tan(const double *x, double p, double *T) {
  (void)p;
  double c = cos(x[0]), sec2 = 1.0 / (c * c), t = sin(x[0]) / c;
  T[0] = 2.0 * sec2 * sec2 + 4.0 * t * t * sec2; // d/dx (2 tan sec^2)
}
static void h3_asin(const double *x, double p, double *T) {
  (void)p;
  double w = (1.0 - x[0]) * (1.0 + x[0]);
  T[0] = (1.0 + 2.0 * x[0] * x[0]) / (w * w * sqrt(w));
}
static void h3_acos(const double *x, double p, double *T) {
  h3_asin(x, p, T);
  T[0] = -T[0];
}
static void h3_atan(const double *x, double p, double *T) {
  (void)p;
  double u = 1.0 + x[0] * x[0];
  T[0] = (6.0 * x[0] * x[0] - 2.0) / (u * u * u);
}
// atan2(y, x): argument 0 is y, argument 1 is x; f is harmonic: f_xxy = -f_yyy, f_xyy = -f_xxx
static void h3_atan2(const double *a, double p, double *T) {
  (void)p;
  double y = a[0], x = a[1], r2 = x * x + y * y, r6 = r2 * r2 * r2;
  double fyyy = (6.0 * x * y * y - 2.0 * x * x * x) / r6;
  double fxxx = (2.0 * y * y * y - 6.0 * x * x * y) / r6;
  T[0] = fyyy;                // yyy
  T[1] = T[2] = T[4] = -fxxx; // yyx
  T[3] = T[5] = T[6] = -fyyy; // yxx
  T[7] = fxxx;                // xxx
}
static void h3_sinh(const double *x, double p, double *T) {
  (void)p;
  T[0] = cosh(x[0]);
}
static void h3_cosh(const double *x, double p, double *T) {
  (void)p;
  T[0] = sinh(x[0]);
}
static void h3_tanh(const double *x, double p, double *T) {
  (void)p;
  double c = cosh(x[0]), s2 = 1.0 / (c * c), t = sinh(x[0]) / c;
  T[0] = -2.0 * s2 * s2 + 4.0 * t * t * s2; // d/dx (-2 tanh sech^2)
}
static void h3_hypot(const double *x, double p, double *T) {
  (void)p;
  double a = x[0], b = x[1], r = sqrt(a * a + b * b), r5 = r * r * r * r * r;
  T[0] = -3.0 * a * b * b / r5;                            // aaa
  T[1] = T[2] = T[4] = (2.0 * a * a * b - b * b * b) / r5; // aab
  T[3] = T[5] = T[6] = (2.0 * a * b * b - a * a * a) / r5; // abb
  T[7] = -3.0 * a * a * b / r5;                            // bbb
}
static void h3_chain3(const double *x, double p, double *T) {
  (void)x;
  (void)p;
  T[0] = 6.0;
}
// the order-3 chain helper with f = x^3 (f' = 3x^2, f'' = 6x, f''' = 6)
static dal_jet j_chain3(const dal_jet *x, double p) {
  (void)p;
  double v = x[0].v;
  return dal_jet_chain3(x[0], v * v * v, 3.0 * v * v, 6.0 * v, 6.0);
}
// dal_norm of (x0, x1): same function as hypot, through the vector routine
static dal_jet j_norm(const dal_jet *x, double p) {
  (void)p;
  return dal_norm(x, 2);
}

static const op ops[] = {
    {"add", 2, {-5, -5}, {5, 5}, 0, 0, 0, 0, j_add, h_add, h3_zero},
    {"sub", 2, {-5, -5}, {5, 5}, 0, 0, 0, 0, j_sub, h_sub, h3_zero},
    {"mul", 2, {-5, -5}, {5, 5}, 0, 0, 0, 0, j_mul, h_mul, h3_zero},
    {"div", 2, {-5, -3}, {5, 3}, 0.4, 0, 0, 0, j_div, h_div, h3_div},
    {"neg", 1, {-5, 0}, {5, 0}, 0, 0, 0, 0, j_neg, h_neg, h3_zero},
    {"scale", 1, {-5, 0}, {5, 0}, 0, -3, 3, 0, j_scale, h_scale, h3_zero},
    {"addc", 1, {-5, 0}, {5, 0}, 0, -3, 3, 0, j_addc, h_addc, h3_zero},
    {"sq", 1, {-5, 0}, {5, 0}, 0, 0, 0, 0, j_sq, h_sq, h3_zero},
    {"sqrt", 1, {0.2, 0}, {9, 0}, 0, 0, 0, 0, j_sqrt, h_sqrt, h3_sqrt},
    {"pow(real p)", 1, {0.2, 0}, {4, 0}, 0, -2.5, 3.5, 0, j_pow, h_pow, h3_pow},
    {"pow(integer p, any sign of base)", 1, {-3, 0}, {3, 0}, 0.4, -4, 5, 1, j_pow, h_pow, h3_pow},
    {"pow(p = 0)", 1, {0.2, 0}, {4, 0}, 0, 0, 0, 0, j_pow, h_pow, h3_pow},
    {"powi(n in -5..6, any sign of base)",
     1,
     {-3, 0},
     {3, 0},
     0.4,
     -5,
     6,
     1,
     j_powi,
     h_powi,
     h3_powi},
    {"exp", 1, {-3, 0}, {3, 0}, 0, 0, 0, 0, j_exp, h_exp, h3_exp},
    {"log", 1, {0.2, 0}, {10, 0}, 0, 0, 0, 0, j_log, h_log, h3_log},
    {"sin", 1, {-7, 0}, {7, 0}, 0, 0, 0, 0, j_sin, h_sin, h3_sin},
    {"cos", 1, {-7, 0}, {7, 0}, 0, 0, 0, 0, j_cos, h_cos, h3_cos},
    {"tan", 1, {-1.3, 0}, {1.3, 0}, 0, 0, 0, 0, j_tan, h_tan, h3_tan},
    {"asin", 1, {-0.9995, 0}, {0.9995, 0}, 0, 0, 0, 0, j_asin, h_asin, h3_asin},
    {"acos", 1, {-0.9995, 0}, {0.9995, 0}, 0, 0, 0, 0, j_acos, h_acos, h3_acos},
    {"atan", 1, {-50, 0}, {50, 0}, 0, 0, 0, 0, j_atan, h_atan, h3_atan},
    {"atan2", 2, {-3, -3}, {3, 3}, 0.4, 0, 0, 0, j_atan2, h_atan2, h3_atan2},
    {"sinh", 1, {-3, 0}, {3, 0}, 0, 0, 0, 0, j_sinh, h_sinh, h3_sinh},
    {"cosh", 1, {-3, 0}, {3, 0}, 0, 0, 0, 0, j_cosh, h_cosh, h3_cosh},
    {"tanh", 1, {-12, 0}, {12, 0}, 0, 0, 0, 0, j_tanh, h_tanh, h3_tanh},
    {"hypot", 2, {-3, -3}, {3, 3}, 0.4, 0, 0, 0, j_hypot, h_hypot, h3_hypot},
    {"norm", 2, {-3, -3}, {3, 3}, 0.4, 0, 0, 0, j_norm, h_hypot, h3_hypot},
    {"jet_chain", 1, {-3, 0}, {3, 0}, 0, 0, 0, 0, j_chain, h_chain, NULL},
    {"jet_chain3", 1, {-3, 0}, {3, 0}, 0, 0, 0, 0, j_chain3, h_chain, h3_chain3},
};

// ---------------------------------------------------------------------------------------------
// one sample: argument curves x_i(s) = v_i + d_i s + dd_i s^2 / 2 + c3_i s^3 (exact in
// double; the third derivative is d3_i = 6 c3_i)
typedef struct sample {
  const op *o;
  double v[2], d[2], dd[2], c3[2], p;
} sample;

static double curve_arg(const sample *sm, int i, double s) {
  return sm->v[i] + sm->d[i] * s + 0.5 * sm->dd[i] * (s * s) + sm->c3[i] * (s * s * s);
}

// value of the operation along the curve, through the jet's own value path
static double op_along(double s, const void *ctx) {
  const sample *sm = ctx;
  dal_jet x[2];
  for (int i = 0; i < sm->o->arity; ++i)
    x[i] = dal_const(curve_arg(sm, i, s));
  return sm->o->jet(x, sm->p).v;
}

static int excluded(const op *o, const double *v) {
  if (o->excl <= 0) return 0;
  if (o->arity == 1) return fabs(v[0]) < o->excl;
  if (o->jet == j_div) return fabs(v[1]) < o->excl;
  // atan2: away from the origin and from the branch cut x < 0, y = 0
  if (o->jet == j_atan2 && v[1] < 0 && fabs(v[0]) < 0.1) return 1;
  return hypot(v[0], v[1]) < o->excl;
}

static void test_op(const op *o) {
  int fails0 = check_failures, quadrant[4] = {0, 0, 0, 0}, nvalid = 0, nvalid3 = 0;
  double worst_an = 0.0, worst_fd = 0.0, worst_an3 = 0.0, worst_fd3 = 0.0;
  for (int it = 0; it < NSAMPLE; ++it) {
    sample sm = {o, {0, 0}, {0, 0}, {0, 0}, {0, 0}, 0.0};
    do {
      for (int i = 0; i < o->arity; ++i)
        sm.v[i] = fd_grid(check_rand(&seed, o->lo[i], o->hi[i]), 20);
    } while (excluded(o, sm.v));
    for (int i = 0; i < o->arity; ++i) {
      sm.d[i] = fd_grid(check_rand(&seed, -1, 1), 10);
      sm.dd[i] = fd_grid(check_rand(&seed, -1, 1), 10);
      sm.c3[i] = fd_grid(check_rand(&seed, -1, 1), 10) / 8.0;
    }
    sm.p = check_rand(&seed, o->plo, o->phi);
    if (o->pint) sm.p = floor(sm.p + 0.5);
    if (o->jet == j_atan2) quadrant[(sm.v[1] < 0) * 2 + (sm.v[0] < 0)]++;

    // the jet
    dal_jet x[2];
    for (int i = 0; i < o->arity; ++i)
      x[i] = dal_jet_make3(sm.v[i], sm.d[i], sm.dd[i], 6.0 * sm.c3[i]);
    dal_jet r = o->jet(x, sm.p);

    // the lower coefficients do not read d3: bit-identical with an unknown (NaN) d3
    dal_jet xn[2];
    for (int i = 0; i < o->arity; ++i)
      xn[i] = dal_jet_make(sm.v[i], sm.d[i], sm.dd[i]);
    dal_jet rn = o->jet(xn, sm.p);
    int constant = (o->jet == j_pow || o->jet == j_powi) && sm.p == 0.0; // x^0 = 1: d3 = 0
    CHECK_MSG(rn.v == r.v && rn.d == r.d && rn.dd == r.dd && (constant || !isfinite(rn.d3)),
              "%s: value or derivatives depend on d3, or d3 = NaN is lost", o->name);

    // hand derivatives: g' = sum f_i d_i, g'' = sum f_i dd_i + sum f_ij d_i d_j
    double f, g[2] = {0, 0}, H[4] = {0, 0, 0, 0};
    o->hand(sm.v, sm.p, &f, g, H);
    double e1 = 0, s1 = 0, e2 = 0, s2 = 0;
    for (int i = 0; i < o->arity; ++i) {
      e1 += g[i] * sm.d[i];
      s1 += fabs(g[i] * sm.d[i]);
      e2 += g[i] * sm.dd[i];
      s2 += fabs(g[i] * sm.dd[i]);
      for (int j = 0; j < o->arity; ++j) {
        e2 += H[i * 2 + j] * sm.d[i] * sm.d[j];
        s2 += fabs(H[i * 2 + j] * sm.d[i] * sm.d[j]);
      }
    }
    double err_v = fabs(r.v - f) / (fabs(f) + 1e-300);
    double err_d = fabs(r.d - e1) / (s1 + 1e-300);
    double err_dd = fabs(r.dd - e2) / (s2 + 1e-300);
    worst_an = fmax(worst_an, fmax(err_v * (f != 0), fmax(err_d * (s1 > 0), err_dd * (s2 > 0))));
    CHECK_MSG(fabs(r.v - f) <= TOL_AN * fabs(f), "%s value at (%g, %g) p=%g: %.17g vs %.17g",
              o->name, sm.v[0], sm.v[1], sm.p, r.v, f);
    CHECK_MSG(fabs(r.d - e1) <= TOL_AN * s1, "%s first derivative at (%g, %g) p=%g: %.17g vs %.17g",
              o->name, sm.v[0], sm.v[1], sm.p, r.d, e1);
    CHECK_MSG(fabs(r.dd - e2) <= TOL_AN * s2,
              "%s second derivative at (%g, %g) p=%g: %.17g vs %.17g", o->name, sm.v[0], sm.v[1],
              sm.p, r.dd, e2);

    // third derivative: sum f_i d3_i + 3 sum f_ij d_i dd_j + sum f_ijk d_i d_j d_k
    if (o->hand3) {
      double T[8] = {0, 0, 0, 0, 0, 0, 0, 0}, e3 = 0, s3 = 0;
      o->hand3(sm.v, sm.p, T);
      for (int i = 0; i < o->arity; ++i) {
        double t1 = g[i] * 6.0 * sm.c3[i];
        e3 += t1;
        s3 += fabs(t1);
        for (int j = 0; j < o->arity; ++j) {
          double t2 = 3.0 * H[i * 2 + j] * sm.d[i] * sm.dd[j];
          e3 += t2;
          s3 += fabs(t2);
          for (int k = 0; k < o->arity; ++k) {
            double t3 = T[i * 4 + j * 2 + k] * sm.d[i] * sm.d[j] * sm.d[k];
            e3 += t3;
            s3 += fabs(t3);
          }
        }
      }
      if (s3 > 0) worst_an3 = fmax(worst_an3, fabs(r.d3 - e3) / s3);
      CHECK_MSG(fabs(r.d3 - e3) <= TOL_AN * s3,
                "%s third derivative at (%g, %g) p=%g: %.17g vs %.17g", o->name, sm.v[0], sm.v[1],
                sm.p, r.d3, e3);
      fd3_est f3 = fd3_estimate(op_along, &sm, 8.0, 0.0);
      if (f3.valid) {
        nvalid3++;
        worst_fd3 = fmax(worst_fd3, fabs(r.d3 - f3.d3) / f3.tol);
        CHECK_MSG(fabs(r.d3 - f3.d3) <= f3.tol, "%s d3 vs FD at (%g, %g): %.17g vs %.17g (tol %g)",
                  o->name, sm.v[0], sm.v[1], r.d3, f3.d3, f3.tol);
      }
    } else {
      CHECK_MSG(isnan(r.d3), "%s: order-2 helper must leave d3 unknown (NaN), got %g", o->name,
                r.d3);
    }

    // finite differences along the curve (where their error bound is trustworthy)
    fd_est fd = fd_estimate(op_along, &sm, 8.0, 0.0);
    if (!fd.valid) continue;
    nvalid++;
    worst_fd = fmax(worst_fd, fmax(fabs(r.d - fd.d1) / fd.tol1, fabs(r.dd - fd.d2) / fd.tol2));
    CHECK_MSG(fabs(r.d - fd.d1) <= fd.tol1, "%s d vs FD at (%g, %g): %.17g vs %.17g (tol %g)",
              o->name, sm.v[0], sm.v[1], r.d, fd.d1, fd.tol1);
    CHECK_MSG(fabs(r.dd - fd.d2) <= fd.tol2, "%s dd vs FD at (%g, %g): %.17g vs %.17g (tol %g)",
              o->name, sm.v[0], sm.v[1], r.dd, fd.d2, fd.tol2);
  }
  // the FD oracle must have covered most samples (it only gives up near a singularity)
  CHECK_MSG(nvalid >= NSAMPLE * 9 / 10, "%s: FD bound valid at only %d of %d samples", o->name,
            nvalid, NSAMPLE);
  if (o->jet == j_atan2)
    for (int qd = 0; qd < 4; ++qd)
      CHECK_MSG(quadrant[qd] > 20, "atan2 quadrant %d sampled %d times", qd, quadrant[qd]);
  if (o->hand3)
    CHECK_MSG(nvalid3 >= NSAMPLE * 8 / 10, "%s: third-derivative FD bound valid at only %d of %d",
              o->name, nvalid3, NSAMPLE);
  printf("  %-36s worst hand rel %.1e, FD at %3d/%d points, worst |jet - FD| / bound %.2f%s\n",
         o->name, worst_an, nvalid, NSAMPLE, worst_fd, check_failures > fails0 ? "  FAILED" : "");
  if (o->hand3)
    printf("  %-36s   order 3: worst hand rel %.1e, FD at %3d/%d, worst |d3 - FD| / bound %.2f\n",
           "", worst_an3, nvalid3, NSAMPLE, worst_fd3);
}

// ---------------------------------------------------------------------------------------------
// identities
static dal_jet rand_jet(double lo, double hi) {
  return dal_jet_make(check_rand(&seed, lo, hi), check_rand(&seed, -1, 1),
                      check_rand(&seed, -1, 1));
}

static void check_jet_eq(const char *what, dal_jet a, dal_jet b, double sv, double sd, double sdd) {
  CHECK_MSG(fabs(a.v - b.v) <= 1e-14 * sv, "%s value %.17g vs %.17g", what, a.v, b.v);
  CHECK_MSG(fabs(a.d - b.d) <= 1e-14 * sd, "%s d %.17g vs %.17g", what, a.d, b.d);
  CHECK_MSG(fabs(a.dd - b.dd) <= 1e-14 * sdd, "%s dd %.17g vs %.17g", what, a.dd, b.dd);
}

static void test_identities(void) {
  int fails0 = check_failures;
  for (int it = 0; it < NSAMPLE; ++it) {
    dal_jet a = rand_jet(-4, 4);
    double sd = fabs(a.d), sdd = fabs(a.dd) + a.d * a.d;
    // sin^2 + cos^2 = 1 with zero derivatives
    dal_jet one = dal_add(dal_sq(dal_sin(a)), dal_sq(dal_cos(a)));
    check_jet_eq("sin^2+cos^2", one, dal_const(1.0), 1.0, sd, sdd);
    // cosh^2 - sinh^2 = 1 (rounding scales with cosh^2)
    double c2 = cosh(a.v) * cosh(a.v);
    dal_jet hyp = dal_sub(dal_sq(dal_cosh(a)), dal_sq(dal_sinh(a)));
    check_jet_eq("cosh^2-sinh^2", hyp, dal_const(1.0), 2 * c2, 2 * c2 * sd, 4 * c2 * sdd);
    // tan = sin / cos, tanh = sinh / cosh (away from the poles of tan)
    if (fabs(cos(a.v)) > 0.2) {
      double sc = 1.0 / (cos(a.v) * cos(a.v));
      check_jet_eq("tan=sin/cos", dal_tan(a), dal_div(dal_sin(a), dal_cos(a)), 2 * sc, 4 * sc * sd,
                   20 * sc * sc * sdd);
    }
    check_jet_eq("tanh=sinh/cosh", dal_tanh(a), dal_div(dal_sinh(a), dal_cosh(a)), 2, 4 * sd,
                 8 * sdd);
    // atan2(sin a, cos a) = a for a in (-pi, pi)
    dal_jet ang = dal_jet_make(check_rand(&seed, -3.1, 3.1), a.d, a.dd);
    check_jet_eq("atan2(sin a, cos a)", dal_atan2(dal_sin(ang), dal_cos(ang)), ang, 4, 4 * sd,
                 4 * sdd);
    // atan2 is invariant under scaling both arguments by a positive jet
    dal_jet ls = dal_exp(rand_jet(-1, 1));
    dal_jet q = dal_atan2(dal_mul(ls, dal_sin(ang)), dal_mul(ls, dal_cos(ang)));
    check_jet_eq("atan2(l sin a, l cos a)", q, ang, 4, 10 * (sd + 1), 40 * (sdd + 1));
    // asin(sin a) = a, atan(tan a) = a on (-pi/2, pi/2); acos(cos a) = a on (0, pi)
    dal_jet hp = dal_jet_make(check_rand(&seed, -1.4, 1.4), a.d, a.dd);
    double sec = 1.0 / cos(hp.v);
    check_jet_eq("asin(sin a)", dal_asin(dal_sin(hp)), hp, 2, 4 * sd * sec, 8 * sdd * sec * sec);
    check_jet_eq("atan(tan a)", dal_atan(dal_tan(hp)), hp, 2, 4 * sd * sec * sec,
                 8 * sdd * sec * sec * sec * sec);
    dal_jet pp = dal_jet_make(check_rand(&seed, 0.15, 3.0), a.d, a.dd);
    double csc = 1.0 / sin(pp.v);
    check_jet_eq("acos(cos a)", dal_acos(dal_cos(pp)), pp, 4, 4 * sd * csc, 8 * sdd * csc * csc);
    // exp(log x) = x and log(exp a) = a, sqrt(x)^2 = x, x^p x^-p = 1, x^0.5 = sqrt x
    dal_jet x = rand_jet(0.1, 5);
    double sx = fabs(x.v), sxd = fabs(x.d), sxdd = fabs(x.dd) + x.d * x.d / x.v;
    check_jet_eq("exp(log x)", dal_exp(dal_log(x)), x, 2 * sx, 4 * sxd, 8 * sxdd);
    check_jet_eq("log(exp a)", dal_log(dal_exp(a)), a, 2 * fabs(a.v) + 1, 4 * sd, 8 * sdd);
    check_jet_eq("sqrt(x)^2", dal_sq(dal_sqrt(x)), x, 2 * sx, 4 * sxd, 8 * sxdd);
    check_jet_eq("pow(x, 0.5)", dal_pow(x, 0.5), dal_sqrt(x), 2 * sqrt(sx), 4 * sxd / sqrt(sx),
                 8 * sxdd / sqrt(sx));
    double p = check_rand(&seed, -3, 3);
    double sp = fabs(p) + 1, lx = fabs(log(x.v)) + 1;
    check_jet_eq("x^p x^-p", dal_mul(dal_pow(x, p), dal_pow(x, -p)), dal_const(1.0), 8 * sp * lx,
                 16 * sp * sp * lx * sxd / sx, 64 * sp * sp * sp * lx * sxdd / sx / sx);
    // powi against repeated multiplication, including negative bases and n <= 0
    dal_jet y = rand_jet(-3, 3);
    if (fabs(y.v) > 0.3) {
      dal_jet prod = dal_const(1.0);
      for (int n = 0; n <= 6; ++n) {
        double sy = pow(fabs(y.v), n) + 1e-300, dy = fabs(y.d) / fabs(y.v),
               ddy = fabs(y.dd) / fabs(y.v) + dy * dy;
        check_jet_eq("powi(y, n) = y*...*y", dal_powi(y, n), prod, 8 * sy, 8 * n * sy * dy + 1e-300,
                     16 * (n * n + 1) * sy * ddy + 1e-300);
        dal_jet inv = dal_div(dal_const(1.0), prod);
        check_jet_eq("powi(y, -n) = 1/(y*...*y)", dal_powi(y, -n), inv, 8 / sy,
                     8 * n * dy / sy + 1e-300, 16 * (n * n + 1) * ddy / sy + 1e-300);
        prod = dal_mul(prod, y);
      }
    }
    // div(mul(a, b), b) = a; hypot(a, b)^2 = a^2 + b^2
    dal_jet b = rand_jet(0.5, 3);
    check_jet_eq("(a b) / b", dal_div(dal_mul(a, b), b), a, 4 * fabs(a.v) + 1e-300,
                 8 * (sd + fabs(a.v)), 16 * (sdd + fabs(a.v) + sd));
    dal_jet hy = dal_hypot(a, b);
    double sa = a.v * a.v + b.v * b.v;
    check_jet_eq("hypot^2", dal_sq(hy), dal_add(dal_sq(a), dal_sq(b)), 4 * sa, 8 * sa, 16 * sa);
  }
  printf("  %-36s %s\n", "identities", check_failures > fails0 ? "FAILED" : "ok");
}

// chain rule through nested functions against hand-differentiated formulas
static void test_chain_rule(void) {
  int fails0 = check_failures;
  for (int it = 0; it < NSAMPLE; ++it) {
    double d = check_rand(&seed, -1, 1), dd = check_rand(&seed, -1, 1);
    // (1) g(x) = log(1 + exp(sin(x^2))): u = x^2, v = sin u, w = exp v, s = w / (1 + w):
    //     g' = s v', g'' = s (1 - s) v'^2 + s v'', v' = 2x cos u, v'' = 2 cos u - 4x^2 sin u
    double x = check_rand(&seed, -2, 2);
    dal_jet J = dal_log(dal_addc(dal_exp(dal_sin(dal_sq(dal_jet_make(x, d, dd)))), 1.0));
    double u = x * x, w = exp(sin(u)), s = w / (1 + w);
    double v1 = 2 * x * cos(u), v2 = 2 * cos(u) - 4 * x * x * sin(u);
    double g1 = s * v1, g2 = s * (1 - s) * v1 * v1 + s * v2;
    check_jet_eq("log(1+exp(sin(x^2)))", J, dal_jet_make(log(1 + w), g1 * d, g1 * dd + g2 * d * d),
                 2 * fabs(log(1 + w)), 8 * fabs(g1 * d) + 1e-15,
                 8 * (fabs(g1 * dd) + fabs(g2) * d * d) + 1e-15);
    // (2) atan(sinh(log y)) = 2 atan(y) - pi/2 (Gudermannian of log y):
    //     h' = 2 / (1 + y^2), h'' = -4y / (1 + y^2)^2
    double y = check_rand(&seed, 0.2, 5);
    J = dal_atan(dal_sinh(dal_log(dal_jet_make(y, d, dd))));
    double q = 1 + y * y, h1 = 2 / q, h2 = -4 * y / (q * q);
    check_jet_eq("atan(sinh(log y))", J,
                 dal_jet_make(2 * atan(y) - PI / 2, h1 * d, h1 * dd + h2 * d * d), 4,
                 8 * fabs(h1 * d), 8 * (fabs(h1 * dd) + fabs(h2) * d * d));
    // (3) f(x) = sqrt(cosh(tan(x / 2))): u = tan(x/2), u' = (1 + u^2)/2, u'' = u (1 + u^2)/2,
    //     c = cosh u, c' = sinh u u', c'' = cosh u u'^2 + sinh u u'',
    //     f' = c' / (2 sqrt c), f'' = c'' / (2 sqrt c) - c'^2 / (4 c^1.5)
    x = check_rand(&seed, -2.5, 2.5);
    J = dal_sqrt(dal_cosh(dal_tan(dal_scale(dal_jet_make(x, d, dd), 0.5))));
    u = tan(x / 2);
    double u1 = (1 + u * u) / 2, u2 = u * (1 + u * u) / 2;
    double c = cosh(u), c1 = sinh(u) * u1, c2 = cosh(u) * u1 * u1 + sinh(u) * u2;
    double f1 = c1 / (2 * sqrt(c)), f2 = c2 / (2 * sqrt(c)) - c1 * c1 / (4 * c * sqrt(c));
    check_jet_eq("sqrt(cosh(tan(x/2)))", J, dal_jet_make(sqrt(c), f1 * d, f1 * dd + f2 * d * d),
                 4 * sqrt(c), 16 * (fabs(f1 * d) + 1e-15),
                 16 * (fabs(f1 * dd) + fabs(c2 / (2 * sqrt(c))) * d * d + 1e-15));
    // (4) the same composite along two different parametrizations of one curve agrees:
    //     x(s) along (d, dd) equals x(2 s') along (d/2, dd/4) -> derivatives scale by 1/2, 1/4
    dal_jet Jh = dal_sqrt(dal_cosh(dal_tan(dal_scale(dal_jet_make(x, d / 2, dd / 4), 0.5))));
    CHECK_CLOSE(Jh.d * 2, J.d, 1e-14);
    CHECK_CLOSE(Jh.dd * 4, J.dd, 1e-14);
  }
  printf("  %-36s %s\n", "chain rule (3-4 nested functions)",
         check_failures > fails0 ? "FAILED" : "ok");
}

// third derivatives through the same nested functions, against the FD oracle along the
// cubic curve x(s) = x0 + d s + dd s^2 / 2 + c3 s^3
typedef struct nested {
  int which;
  double x0, d, dd, c3;
} nested;

static dal_jet nested_eval(int which, dal_jet x) {
  if (which == 0) return dal_log(dal_addc(dal_exp(dal_sin(dal_sq(x))), 1.0));
  if (which == 1) return dal_atan(dal_sinh(dal_log(x)));
  return dal_sqrt(dal_cosh(dal_tan(dal_scale(x, 0.5))));
}

static double nested_along(double s, const void *ctx) {
  const nested *n = ctx;
  return nested_eval(n->which,
                     dal_const(n->x0 + n->d * s + 0.5 * n->dd * (s * s) + n->c3 * (s * s * s)))
      .v;
}

static void test_chain_rule3(void) {
  int fails0 = check_failures, nvalid = 0, total = 0;
  double worst = 0.0;
  for (int it = 0; it < NSAMPLE; ++it)
    for (int which = 0; which < 3; ++which) {
      double lo[3] = {-2, 0.2, -2.5}, hi[3] = {2, 5, 2.5};
      nested n = {which, fd_grid(check_rand(&seed, lo[which], hi[which]), 20),
                  fd_grid(check_rand(&seed, -1, 1), 10), fd_grid(check_rand(&seed, -1, 1), 10),
                  fd_grid(check_rand(&seed, -1, 1), 10) / 8.0};
      dal_jet J = nested_eval(which, dal_jet_make3(n.x0, n.d, n.dd, 6.0 * n.c3));
      fd3_est f3 = fd3_estimate(nested_along, &n, 16.0, 0.0);
      ++total;
      if (!f3.valid) continue;
      ++nvalid;
      worst = fmax(worst, fabs(J.d3 - f3.d3) / f3.tol);
      CHECK_MSG(fabs(J.d3 - f3.d3) <= f3.tol, "nested %d at %g: d3 %.17g vs FD %.17g (tol %g)",
                which, n.x0, J.d3, f3.d3, f3.tol);
    }
  CHECK_MSG(nvalid >= total * 8 / 10, "nested d3: FD valid at only %d of %d", nvalid, total);
  printf("  %-36s FD at %d/%d, worst |d3 - FD| / bound %.2f %s\n", "chain rule, order 3", nvalid,
         total, worst, check_failures > fails0 ? "FAILED" : "ok");
}

// accuracy near the edges of the domains: asin/acos at 1 - 2^-k, tanh at large |x|
static void test_edges(void) {
  int fails0 = check_failures;
  for (int k = 4; k <= 40; ++k)
    for (int sg = -1; sg <= 1; sg += 2) {
      double v = sg * (1.0 - ldexp(1.0, -k));
      double w = ldexp(2.0 - ldexp(1.0, -k), -k); // 1 - v^2, exact
      double f1 = 1.0 / sqrt(w), f2 = v / (w * sqrt(w));
      dal_jet a = dal_asin(dal_jet_make(v, 1.0, 0.5)), c = dal_acos(dal_jet_make(v, 1.0, 0.5));
      CHECK_MSG(fabs(a.d - f1) <= 1e-14 * f1, "asin'(%.17g) = %.17g vs %.17g", v, a.d, f1);
      CHECK_MSG(fabs(a.dd - (0.5 * f1 + f2)) <= 1e-14 * (0.5 * f1 + fabs(f2)),
                "asin''(%.17g) = %.17g vs %.17g", v, a.dd, 0.5 * f1 + f2);
      CHECK_MSG(fabs(c.d + f1) <= 1e-14 * f1, "acos'(%.17g) = %.17g vs %.17g", v, c.d, -f1);
      CHECK_MSG(fabs(c.dd + (0.5 * f1 + f2)) <= 1e-14 * (0.5 * f1 + fabs(f2)),
                "acos''(%.17g) = %.17g vs %.17g", v, c.dd, -(0.5 * f1 + f2));
    }
  for (double x = 5.0; x <= 320.0; x *= 1.5)
    for (int sg = -1; sg <= 1; sg += 2) {
      // sech^2 x = 4 e^{-2|x|} / (1 + e^{-2|x|})^2, tanh'' = -2 tanh sech^2
      double e = exp(-2.0 * x), s2 = 4.0 * e / ((1.0 + e) * (1.0 + e));
      dal_jet t = dal_tanh(dal_var(sg * x, 1.0));
      CHECK_MSG(fabs(t.d - s2) <= 1e-14 * s2, "tanh'(%g) = %.17g vs %.17g", sg * x, t.d, s2);
      CHECK_MSG(fabs(t.dd + 2.0 * sg * tanh(x) * s2) <= 1e-14 * 2.0 * s2, "tanh''(%g) = %.17g",
                sg * x, t.dd);
    }
  printf("  %-36s %s\n", "accuracy near domain edges", check_failures > fails0 ? "FAILED" : "ok");
}

// ---------------------------------------------------------------------------------------------
// domain errors: non-finite jets
static void test_domain_jets(void) {
  int fails0 = check_failures;
  dal_jet x1 = dal_var(-1.0, 1.0), z = dal_var(0.0, 1.0), zc = dal_const(0.0);
  CHECK(!dal_jet_isfinite(dal_sqrt(x1)));
  CHECK(!dal_jet_isfinite(dal_sqrt(dal_const(-1.0))));
  CHECK(!dal_jet_isfinite(dal_sqrt(z)));                           // derivative of sqrt at 0
  CHECK(!dal_jet_isfinite(dal_sqrt(dal_jet_make(0.0, 0.0, 1.0)))); // curvature only
  CHECK(dal_jet_isfinite(dal_sqrt(zc)));                           // constant 0 is fine
  CHECK(dal_sqrt(zc).v == 0.0 && dal_sqrt(zc).d == 0.0 && dal_sqrt(zc).dd == 0.0);
  CHECK(!dal_jet_isfinite(dal_log(zc)));
  CHECK(!dal_jet_isfinite(dal_log(z)));
  CHECK(!dal_jet_isfinite(dal_log(dal_const(-1.0))));
  CHECK(!dal_jet_isfinite(dal_log(x1)));
  CHECK(!dal_jet_isfinite(dal_asin(dal_const(2.0))));
  CHECK(!dal_jet_isfinite(dal_asin(dal_var(2.0, 1.0))));
  CHECK(!dal_jet_isfinite(dal_acos(dal_var(-1.5, 1.0))));
  CHECK(!dal_jet_isfinite(dal_asin(dal_var(1.0, 1.0)))); // infinite slope at the end point
  CHECK(!dal_jet_isfinite(dal_div(dal_const(1.0), zc)));
  CHECK(!dal_jet_isfinite(dal_powi(zc, -1)));
  CHECK(!dal_jet_isfinite(dal_pow(dal_var(-2.0, 1.0), 0.5)));
  CHECK(!dal_jet_isfinite(dal_atan2(z, z)));
  CHECK(!dal_jet_isfinite(dal_hypot(z, zc)));
  CHECK(dal_jet_isfinite(dal_hypot(zc, zc)));
  dal_jet v0[3] = {z, zc, zc};
  CHECK(!dal_jet_isfinite(dal_norm(v0, 3)));
  CHECK(!dal_jet_isfinite(dal_jet_make(NAN, 0, 0)));
  CHECK(!dal_jet_isfinite(dal_jet_make(0, INFINITY, 0)));
  CHECK(!dal_jet_isfinite(dal_jet_make(0, 0, -INFINITY)));
  CHECK(dal_jet_isfinite(dal_jet_make(1, 2, 3)));
  // constructors: constants and variables are exact to order 3; the order-2 constructors
  // leave d3 unknown (NaN), which dal_jet_isfinite ignores and dal_jet_isfinite3 reports
  dal_jet c = dal_const(2.5), v = dal_var(1.5, -0.5), m2 = dal_jet_make(1, 2, 3);
  dal_jet m3 = dal_jet_make3(1, 2, 3, 4);
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
  dal_jet lit = {1, 2, 3}; // a version-1 initializer still compiles (d3 = 0 by C's rules)
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
  CHECK(c.v == 2.5 && c.d == 0 && c.dd == 0 && c.d3 == 0);
  CHECK(v.v == 1.5 && v.d == -0.5 && v.dd == 0 && v.d3 == 0);
  CHECK(m2.v == 1 && m2.d == 2 && m2.dd == 3 && isnan(m2.d3));
  CHECK(dal_jet_isfinite(m2) && !dal_jet_isfinite3(m2));
  CHECK(m3.d3 == 4 && dal_jet_isfinite3(m3) && lit.d3 == 0);
  CHECK(!dal_jet_isfinite3(dal_jet_make3(1, 2, 3, INFINITY)));
  CHECK(isnan(dal_jet_chain(v, 1, 2, 3).d3) && dal_jet_chain3(v, 1, 2, 3, 4).d3 == 4 * -0.125);
  // an unknown d3 stays unknown through every operation (never silently becomes a number)
  dal_jet u = dal_jet_make(0.7, 0.3, -0.2);
  CHECK(isnan(dal_mul(u, dal_const(0.0)).d3) && isnan(dal_sin(dal_add(u, v)).d3));
  CHECK(isnan(dal_atan2(u, dal_const(1.0)).d3) && isnan(dal_hypot(dal_const(1.0), u).d3));
  printf("  %-36s %s\n", "domain errors give non-finite jets",
         check_failures > fails0 ? "FAILED" : "ok");
}

// the library reports domain errors where they arise --------------------------------------------
// custom primitive "root": out = (sqrt(u), u)
static int root_eval(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)p;
  (void)ctx;
  out[0] = dal_sqrt(in[0]);
  out[1] = in[0];
  return 0;
}
static const dal_primitive prim_root = {.name = "root",
                                        .version = 1,
                                        .nin = 1,
                                        .nout = 2,
                                        .nparam = 0,
                                        .eval = root_eval,
                                        .doc = "in (u); out (sqrt u, u)",
                                        .flags = 0};

// whole-system map: particle 'bead' at (sqrt(1 - q0^2), q0) (unit circle arc)
static int arc_map(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx) {
  (void)t;
  (void)ctx;
  r[0] = dal_sqrt(dal_addc(dal_neg(dal_sq(q[0])), 1.0));
  r[1] = q[0];
  return 0;
}

static int logpot(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  *U = dal_log(q[0]);
  return 0;
}

static int sqrtlag(dal_jet t, const dal_jet *q, const dal_jet *qd, dal_jet *L, void *ctx) {
  (void)t;
  (void)ctx;
  *L = dal_sub(dal_scale(dal_sq(qd[0]), 0.5), dal_sqrt(q[0]));
  return 0;
}

// build a small 2D system; which: 0 primitive "root", 1 whole-system map, 2 U(q) on a
// Cartesian particle (coordinates u, w), 3 Lagrangian
static dal_system *build_domain_system(int which) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  int q[2], p = 0, rc = dal_builder_create(2, &b);
  if (!rc) rc = dal_builder_add_coord(b, "u", &q[0]);
  if (!rc && which == 2) rc = dal_builder_add_coord(b, "w", &q[1]);
  if (!rc && which != 3) rc = dal_builder_add_particle(b, "bead", 1.0, &p);
  // 0: the bead placed by prim_root(u); 2: Cartesian (u, w)
  dal_place_def pd = dal_default_place_def();
  pd.prim = which == 0 ? &prim_root : &dal_map_cartesian2;
  pd.coords = q;
  pd.ncoords = which == 0 ? 1 : 2;
  if (!rc && which == 0) rc = dal_builder_place_def(b, p, &pd);
  if (!rc && which == 1) rc = dal_builder_set_map(b, arc_map, NULL);
  if (!rc && which == 2) rc = dal_builder_place_def(b, p, &pd);
  if (!rc && which == 2) rc = dal_builder_add_potential_q(b, logpot, NULL);
  if (!rc && which == 3) rc = dal_builder_set_lagrangian(b, sqrtlag, NULL);
  if (!rc) rc = dal_builder_compile(b, &sys);
  CHECK_MSG(rc == 0, "building domain test system %d: %s", which, dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return sys;
}

static void expect_domain(int which, double u, const char *const *names, int nnames) {
  dal_system *sys = build_domain_system(which);
  dal_state *st = NULL;
  if (!sys || dal_state_create(sys, &st)) {
    CHECK(0);
    dal_system_destroy(sys);
    return;
  }
  double q[2] = {u, 0.3}, qd[2] = {0.7, 0.1};
  CHECK_OK(dal_state_set(sys, st, 1.25, q, qd));
  int rc = dal_forward(sys, st);
  const char *msg = dal_state_errmsg(st);
  CHECK_MSG(rc == DAL_E_DOMAIN, "system %d at u=%g: forward returned %s (%s)", which, u,
            dal_status_name(rc), msg);
  for (int i = 0; i < nnames; ++i)
    CHECK_MSG(strstr(msg, names[i]) != NULL, "system %d: message lacks '%s': %s", which, names[i],
              msg);
  CHECK_MSG(strstr(msg, "t=1.25") != NULL, "system %d: message lacks the time: %s", which, msg);
  // the state keeps its (t, q, qdot)
  CHECK(dal_state_time(st) == 1.25 && dal_state_q(st)[0] == u && dal_state_qdot(st)[0] == 0.7);
  // and a valid state of the same system evaluates
  double qok[2] = {0.5, 0.3};
  CHECK_OK(dal_state_set(sys, st, 1.25, qok, qd));
  rc = dal_forward(sys, st);
  CHECK_MSG(rc == 0, "system %d at u=0.5: %s", which, dal_state_errmsg(st));
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

static void test_domain_reported(void) {
  int fails0 = check_failures;
  const char *prim_names[] = {"root", "bead"};
  expect_domain(0, -1.0, prim_names, 2); // sqrt of a negative number
  expect_domain(0, 0.0, prim_names, 2);  // derivative of sqrt at 0
  const char *map_names[] = {"map", "bead"};
  expect_domain(1, 1.5, map_names, 2); // sqrt(1 - q^2) with |q| > 1
  expect_domain(1, 1.0, map_names, 2); // derivative of sqrt at 0
  const char *pot_names[] = {"U(q,t)", "'u'"};
  expect_domain(2, -1.0, pot_names, 2); // log of a negative number
  expect_domain(2, 0.0, pot_names, 2);  // log 0
  const char *lag_names[] = {"Lagrangian", "u="};
  expect_domain(3, -2.0, lag_names, 2); // sqrt of a negative number
  printf("  %-36s %s\n", "domain errors reported by the library",
         check_failures > fails0 ? "FAILED" : "ok");
}

// dal_sincos gives exactly the jets of dal_sin and dal_cos (same formulas, one call)
static void test_sincos(void) {
  unsigned long long sc_seed = 0x5eed51c05ULL;
  for (int i = 0; i < NSAMPLE; ++i) {
    dal_jet a = dal_jet_make(check_rand(&sc_seed, -10, 10), check_rand(&sc_seed, -3, 3),
                             check_rand(&sc_seed, -3, 3));
    dal_jet s, c, s1 = dal_sin(a), c1 = dal_cos(a);
    dal_sincos(a, &s, &c);
    CHECK(s.v == s1.v && s.d == s1.d && s.dd == s1.dd);
    CHECK(c.v == c1.v && c.d == c1.d && c.dd == c1.dd);
  }
}

int main(void) {
  printf("jet operations at %d random points along random directions:\n", NSAMPLE);
  for (size_t i = 0; i < sizeof ops / sizeof ops[0]; ++i)
    test_op(&ops[i]);
  test_identities();
  test_chain_rule();
  test_chain_rule3();
  test_edges();
  test_domain_jets();
  test_domain_reported();
  test_sincos();
  return check_summary("test_jet");
}
