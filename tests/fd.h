// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Finite-difference oracle for tests: central differences with an honest error estimate.
//
// The first and second derivative of g at 0 by central differences at step h = 2^-13 (~1.2e-4)
// carry truncation errors h^2/6 g''' and h^2/12 g'''' and rounding errors ~noise/h and
// ~4 noise/h^2, where noise bounds the rounding in one value of g. The third and fourth
// derivatives are estimated by coarse stencils at H = 2^-6 and 2^-7 (the larger of the two,
// doubled, bounds them near 0). Callers pass curves whose arguments are exact in double
// (grid values, power-of-two steps), so the noise is a few ulps of |g|.
#ifndef DAL_TEST_FD_H
#define DAL_TEST_FD_H

#include <float.h>
#include <math.h>

/// a scalar function of the step s
typedef double fd_fn(double s, const void *ctx);

/// estimated derivatives and the bounds on their errors
typedef struct fd_est {
  double d1, d2;     // central first and second differences at h
  double tol1, tol2; // error bounds (truncation + rounding, with a safety factor 2)
  double h;          // the step used
  int valid;         // 0: no trustworthy bound (a singularity or the domain's edge is too near)
} fd_est;

/// FD derivatives of g at 0; one value of g carries at most `ulps` ulps of rounding relative
/// to max(|g|) + `scale` (scale: the size of the intermediate quantities when g cancels).
/// The bounds on g''' and g'''' come from coarse stencils at H and H/2, starting at H = 2^-6
/// and halving H until both are finite and agree to 25% (or to their own rounding level):
/// then the Taylor series converges on the stencil and twice the larger estimate bounds the
/// derivative near 0. If that never happens down to H = 2h, the estimate is not valid.
static inline fd_est fd_estimate(fd_fn *g, const void *ctx, double ulps, double scale) {
  fd_est e;
  const double h = ldexp(1.0, -13);
  double g0 = g(0.0, ctx), gp = g(h, ctx), gm = g(-h, ctx);
  e.h = h;
  e.d1 = (gp - gm) / (2.0 * h);
  e.d2 = (gp - 2.0 * g0 + gm) / (h * h);
  e.tol1 = e.tol2 = INFINITY;
  e.valid = 0;
  if (!isfinite(g0) || !isfinite(gp) || !isfinite(gm)) return e;
  for (int k = 6; k <= 12 && !e.valid; ++k) {
    double e3[2], e4[2], G = fmax(fabs(g0), fmax(fabs(gp), fabs(gm)));
    int ok = 1;
    for (int j = 0; j < 2; ++j) {
      double H = ldexp(1.0, -k - j);
      double g1 = g(H, ctx), gm1 = g(-H, ctx), g2 = g(2.0 * H, ctx), gm2 = g(-2.0 * H, ctx);
      if (!isfinite(g1) || !isfinite(gm1) || !isfinite(g2) || !isfinite(gm2)) ok = 0;
      e3[j] = (g2 - 2.0 * g1 + 2.0 * gm1 - gm2) / (2.0 * H * H * H);
      e4[j] = (g2 - 4.0 * g1 + 6.0 * g0 - 4.0 * gm1 + gm2) / (H * H * H * H);
      G = fmax(G, fmax(fmax(fabs(g1), fabs(gm1)), fmax(fabs(g2), fabs(gm2))));
    }
    if (!ok) continue;
    double noise = ulps * DBL_EPSILON * (G + scale), Hs = ldexp(1.0, -k - 1);
    double r3 = 3.0 * noise / (Hs * Hs * Hs), r4 = 16.0 * noise / (Hs * Hs * Hs * Hs);
    if (fabs(e3[0] - e3[1]) > 0.25 * fmax(fabs(e3[0]), fabs(e3[1])) + 2.0 * r3) continue;
    if (fabs(e4[0] - e4[1]) > 0.25 * fmax(fabs(e4[0]), fabs(e4[1])) + 2.0 * r4) continue;
    double B3 = 2.0 * fmax(fabs(e3[0]), fabs(e3[1])) + 2.0 * r3;
    double B4 = 2.0 * fmax(fabs(e4[0]), fabs(e4[1])) + 2.0 * r4;
    e.tol1 = 2.0 * (h * h / 6.0 * B3 + noise / h) + 1e-300;
    e.tol2 = 2.0 * (h * h / 12.0 * B4 + 4.0 * noise / (h * h)) + 1e-300;
    e.valid = 1;
  }
  return e;
}

/// third derivative of g at 0 by the central stencil D(h) = (g(2h) - 2 g(h) + 2 g(-h) -
/// g(-2h)) / (2 h^3) = g3 + h^2/4 g5 + ... (gk: k-th derivative), Richardson-extrapolated from
/// h/2 and h/4. The estimate is trusted when D(h) - D(h/2) and D(h/2) - D(h/4) shrink like
/// h^2 (ratio 1/4 +- 0.1, or at the rounding level); its error bound is then twice
/// |D(h/2) - D(h/4)| (3 times the error of D(h/4) alone, far above the extrapolated error) plus
/// four times the rounding (ulps of max |g| + scale, as in fd_estimate).
typedef struct fd3_est {
  double d3, tol;
  int valid;
} fd3_est;

static inline fd3_est fd3_estimate(fd_fn *g, const void *ctx, double ulps, double scale) {
  fd3_est e = {NAN, INFINITY, 0};
  for (int k = 4; k <= 9 && !e.valid; ++k) {
    double D[3], G = 0.0;
    int ok = 1;
    for (int j = 0; j < 3; ++j) {
      double h = ldexp(1.0, -k - j);
      double g1 = g(h, ctx), gm1 = g(-h, ctx), g2 = g(2.0 * h, ctx), gm2 = g(-2.0 * h, ctx);
      if (!isfinite(g1) || !isfinite(gm1) || !isfinite(g2) || !isfinite(gm2)) ok = 0;
      G = fmax(G, fmax(fmax(fabs(g1), fabs(gm1)), fmax(fabs(g2), fabs(gm2))));
      D[j] = (g2 - 2.0 * g1 + 2.0 * gm1 - gm2) / (2.0 * h * h * h);
    }
    if (!ok) continue;
    double hs = ldexp(1.0, -k - 2), r = 3.0 * ulps * DBL_EPSILON * (G + scale) / (hs * hs * hs);
    double d01 = fabs(D[0] - D[1]), d12 = fabs(D[1] - D[2]);
    if (fabs(d12 - 0.25 * d01) > 0.1 * d01 + 4.0 * r) continue; // not yet in the h^2 regime
    e.d3 = D[2] + (D[2] - D[1]) / 3.0;
    e.tol = 2.0 * (d12 + 2.0 * r) + 1e-300;
    e.valid = 1;
  }
  return e;
}

/// a random number in [lo, hi) rounded to the grid 2^-bits (exact sums along test curves)
static inline double fd_grid(double x, int bits) { return ldexp(nearbyint(ldexp(x, bits)), -bits); }

#endif
