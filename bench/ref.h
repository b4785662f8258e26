// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Closed-form references of the benchmark: Jacobi elliptic pendulum, harmonic oscillator.
//
// Jacobi functions by the arithmetic-geometric mean and descending Landen transformation
// (Abramowitz & Stegun 16.4 and 17.6); the argument is first reduced modulo the period 4K so
// that the backward recursion does not amplify rounding.
#ifndef DAL_BENCH_REF_H
#define DAL_BENCH_REF_H

#include <math.h>

/// sn, cn, dn of (u | m), parameter m = k^2 in [0, 1).
static inline void ref_jacobi(double u, double m, double *sn, double *cn, double *dn) {
  double a[16], c[16], phi;
  double b = sqrt(1.0 - m);
  int n = 0;
  a[0] = 1.0;
  c[0] = sqrt(m);
  while (n < 15 && fabs(c[n]) > 1e-17) {
    double an = a[n];
    a[n + 1] = 0.5 * (an + b);
    c[n + 1] = 0.5 * (an - b);
    b = sqrt(an * b);
    ++n;
  }
  // quarter period K = pi / (2 a_N); reduce u into [0, 4K)
  double K4 = 6.283185307179586477 / a[n];
  u = fmod(u, K4);
  if (u < 0) u += K4;
  phi = ldexp(a[n] * u, n);
  double phi1 = phi;
  for (int i = n; i > 0; --i) {
    phi1 = phi;
    phi = 0.5 * (phi + asin(c[i] / a[i] * sin(phi)));
  }
  *sn = sin(phi);
  *cn = cos(phi);
  *dn = n > 0 ? *cn / cos(phi1 - phi) : 1.0;
}

/// Simple pendulum of length l under gravity g released from rest at amplitude th0
/// (|th0| < pi): theta(t) and thetadot(t), from sin(theta/2) = k cd(w t | k^2), k = sin(th0/2).
static inline void ref_pendulum(double th0, double l, double g, double t, double *th, double *thd) {
  double k = sin(0.5 * th0), w = sqrt(g / l), sn, cn, dn;
  ref_jacobi(w * t, k * k, &sn, &cn, &dn);
  // cd = cn/dn; d/du cd = -(1 - m) sn / dn^2
  double cd = cn / dn, x = k * cd;
  *th = 2.0 * asin(x);
  double dcd = -(1.0 - k * k) * sn / (dn * dn);
  *thd = 2.0 * k * w * dcd / sqrt(1.0 - x * x);
}

/// Isotropic 2D harmonic oscillator m r'' = -k r: position at t from (r0, v0).
static inline void ref_oscillator(double m, double k, const double *r0, const double *v0, double t,
                                  double *r) {
  double w = sqrt(k / m);
  for (int i = 0; i < 2; ++i)
    r[i] = r0[i] * cos(w * t) + v0[i] / w * sin(w * t);
}

#endif
