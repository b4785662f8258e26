// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Exact large-amplitude pendulum by Jacobi elliptic functions (header-only reference).
//
// theta'' = -w0^2 sin theta, theta(0) = theta0 (|theta0| < pi), theta'(0) = 0, w0 = sqrt(g/l):
//   k = sin(theta0 / 2), u = K(k) - w0 t,
//   sin(theta/2) = k sn(u, k),  theta = 2 asin(k sn u),  theta' = -2 k w0 cn u
// (Lawden, Elliptic Functions and Applications, sec. 5.2; the period is 4 K / w0).
// K by the arithmetic-geometric mean, K = pi / (2 AGM(1, sqrt(1 - k^2))), and sn, cn, dn by
// the AGM with the descending Landen transformation (Abramowitz & Stegun 16.4.1-16.4.3,
// 17.6.1). The argument is reduced modulo the period 4K first.
#ifndef DAL_REF_ELLIPTIC_H
#define DAL_REF_ELLIPTIC_H

#include <math.h>

/// scratch size of the AGM sequence (converges quadratically: < 8 terms for m < 1 - 1e-12)
#define REF_AGM_MAX 24

/// AGM sequences a_n, c_n for parameter m = k^2 in [0, 1); returns N (last index).
static inline int ref_agm(double m, double *a, double *c) {
  double b = sqrt(1.0 - m);
  int n = 0;
  a[0] = 1.0;
  c[0] = sqrt(m);
  while (n < REF_AGM_MAX - 1 && fabs(c[n]) > 2.2e-16 * a[n]) {
    double an = a[n];
    a[n + 1] = 0.5 * (an + b);
    c[n + 1] = 0.5 * (an - b);
    b = sqrt(an * b);
    ++n;
  }
  return n;
}

/// complete elliptic integral of the first kind K(m), m = k^2 in [0, 1)
static inline double ref_ellip_K(double m) {
  double a[REF_AGM_MAX], c[REF_AGM_MAX];
  int n = ref_agm(m, a, c);
  return 3.14159265358979323846 / (2.0 * a[n]);
}

/// Jacobi sn, cn, dn of (u | m), m = k^2 in [0, 1)
static inline void ref_ellip_sncndn(double u, double m, double *sn, double *cn, double *dn) {
  double a[REF_AGM_MAX], c[REF_AGM_MAX];
  int n = ref_agm(m, a, c);
  // reduce u modulo the period 4K = 2 pi / a_N
  double P = 6.28318530717958647692 / a[n];
  u = fmod(u, P);
  if (u < 0) u += P;
  // phi_N = 2^N a_N u, then phi_{n-1} = (phi_n + asin(c_n / a_n sin phi_n)) / 2
  double phi = ldexp(a[n] * u, n);
  for (int i = n; i > 0; --i)
    phi = 0.5 * (phi + asin(c[i] / a[i] * sin(phi)));
  *sn = sin(phi);
  *cn = cos(phi);
  *dn = sqrt(1.0 - m * *sn * *sn);
}

/// exact pendulum released from rest at theta0: theta(t) and theta'(t), w0 = sqrt(g/l)
static inline void ref_pendulum(double theta0, double w0, double t, double *theta,
                                double *thetadot) {
  double k = sin(0.5 * theta0), m = k * k, sn, cn, dn;
  ref_ellip_sncndn(ref_ellip_K(m) - w0 * t, m, &sn, &cn, &dn);
  *theta = 2.0 * asin(k * sn);
  *thetadot = -2.0 * k * w0 * cn;
}

/// the start of the pendulum of length 1 released from rest at theta0: in its angle (cart 0:
/// q = theta0) or in Cartesian coordinates about a pivot at the origin (cart 1: q = (x, y));
/// qdot = 0 (q, qdot: 1 or 2 entries)
static inline void ref_pendulum_start(double theta0, int cart, double *q, double *qdot) {
  q[0] = cart ? sin(theta0) : theta0;
  qdot[0] = 0.0;
  if (cart) {
    q[1] = -cos(theta0);
    qdot[1] = 0.0;
  }
}

/// the deviation of (q, qdot) at t from that pendulum's exact motion (length 1, w0 = sqrt(g)):
/// the worst of the coordinates' errors and the velocities' errors / w0
static inline double ref_pendulum_error(double theta0, double w0, int cart, double t,
                                        const double *q, const double *v) {
  double th, thd;
  ref_pendulum(theta0, w0, t, &th, &thd);
  if (cart)
    return fmax(fmax(fabs(q[0] - sin(th)), fabs(q[1] + cos(th))),
                fmax(fabs(v[0] - thd * cos(th)), fabs(v[1] - thd * sin(th))) / w0);
  return fmax(fabs(q[0] - th), fabs(v[0] - thd) / w0);
}

#endif
