// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The reference of tests/ref_caraxis.h, recomputed in __float128: the car axis problem (Bari
// IVP test set) in the index-1 form, the accelerations and multipliers from the 2 x 2 system
// G K^-1 G' lambda = -gamma - G K^-1 f derived by hand (no jets, no library code), integrated
// by Gragg-Bulirsch-Stoer extrapolation at a fixed step. Usage: ref_caraxis [steps columns];
// without arguments it checks its result against ref_caraxis.h to 1e-22 (relative).
#include <quadmath.h>
#include <stdio.h>
#include <stdlib.h>

#include "ref_caraxis.h"

typedef __float128 real;
#define NV 8
#define KMAX 16
static const real K = 5e-4Q, L = 1, L0 = 0.5Q, R0 = 0.1Q, W = 10, G0 = 1;

// the road under the right wheel: (x_b, y_b) and its first two time derivatives
static void road(real t, real *b, real *bd, real *bdd) {
  real yb = R0 * sinq(W * t), ybd = R0 * W * cosq(W * t), ybdd = -W * W * yb;
  real xb = sqrtq(L * L - yb * yb), xbd = -yb * ybd / xb;
  b[0] = xb, b[1] = yb, bd[0] = xbd, bd[1] = ybd;
  bdd[0] = -(xbd * xbd + ybd * ybd + yb * ybdd) / xb, bdd[1] = ybdd;
}

// accelerations a (4) and multipliers lam (2) at (t, p, u)
static void accel(real t, const real *z, real *a, real *lam) {
  const real *p = z, *u = z + 4;
  real b[2], bd[2], bdd[2], f[4];
  road(t, b, bd, bdd);
  // springs (stiffness 1, rest length L0) to the origin and to the road point; gravity K g
  real ll = sqrtq(p[0] * p[0] + p[1] * p[1]);
  f[0] = (L0 - ll) * p[0] / ll;
  f[1] = (L0 - ll) * p[1] / ll - K * G0;
  real ex = p[2] - b[0], ey = p[3] - b[1], lr = sqrtq(ex * ex + ey * ey);
  f[2] = (L0 - lr) * ex / lr;
  f[3] = (L0 - lr) * ey / lr - K * G0;
  // phi_1 = x_l x_b + y_l y_b, phi_2 = |p_l - p_r|^2 - L^2: gradients and curvature terms
  real dx = p[0] - p[2], dy = p[1] - p[3], du = u[0] - u[2], dv = u[1] - u[3];
  real g[2][4] = {{b[0], b[1], 0, 0}, {2 * dx, 2 * dy, -2 * dx, -2 * dy}};
  real gam[2] = {2 * (u[0] * bd[0] + u[1] * bd[1]) + p[0] * bdd[0] + p[1] * bdd[1],
                 2 * (du * du + dv * dv)};
  real s[2][2] = {{0, 0}, {0, 0}}, r[2];
  for (int i = 0; i < 2; ++i) {
    r[i] = -gam[i];
    for (int k = 0; k < 4; ++k)
      r[i] -= g[i][k] * f[k] / K;
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 4; ++k)
        s[i][j] += g[i][k] * g[j][k] / K;
  }
  real det = s[0][0] * s[1][1] - s[0][1] * s[1][0];
  lam[0] = (r[0] * s[1][1] - s[0][1] * r[1]) / det;
  lam[1] = (s[0][0] * r[1] - s[1][0] * r[0]) / det;
  for (int k = 0; k < 4; ++k)
    a[k] = (f[k] + g[0][k] * lam[0] + g[1][k] * lam[1]) / K;
}

static void rhs(real t, const real *z, real *zd) {
  real lam[2];
  for (int k = 0; k < 4; ++k)
    zd[k] = z[4 + k];
  accel(t, z, zd + 4, lam);
}

// one Gragg-Bulirsch-Stoer step of size H: modified midpoint with n_j = 2, 4, ..., 2 kc
// substeps, extrapolated to h = 0 by Aitken-Neville in h^2
static void gbs(real t, real *z, real H, int kc) {
  real tab[KMAX][NV];
  for (int j = 0; j < kc; ++j) {
    int nj = 2 * (j + 1);
    real h = H / nj, z0[NV], z1[NV], f[NV];
    rhs(t, z, f);
    for (int i = 0; i < NV; ++i)
      z0[i] = z[i], z1[i] = z[i] + h * f[i];
    for (int s = 1; s < nj; ++s) {
      rhs(t + s * h, z1, f);
      for (int i = 0; i < NV; ++i) {
        real z2 = z0[i] + 2 * h * f[i];
        z0[i] = z1[i], z1[i] = z2;
      }
    }
    rhs(t + H, z1, f);
    for (int i = 0; i < NV; ++i)
      tab[j][i] = (z1[i] + z0[i] + h * f[i]) / 2;
    for (int k = j - 1; k >= 0; --k) {
      real ratio = (real)nj / (2 * (k + 1)), c = 1 / (ratio * ratio - 1);
      for (int i = 0; i < NV; ++i)
        tab[k][i] = tab[k + 1][i] + (tab[k + 1][i] - tab[k][i]) * c;
    }
  }
  for (int i = 0; i < NV; ++i)
    z[i] = tab[0][i];
}

int main(int argc, char **argv) {
  int nsteps = argc > 2 ? atoi(argv[1]) : 600, kc = argc > 2 ? atoi(argv[2]) : 14;
  if (nsteps < 1 || kc < 1 || kc > KMAX) return 2;
  // the test set's consistent start
  real z[NV] = {0, 0.5Q, 1, 0.5Q, -0.5Q, 0, -0.5Q, 0}, H = (real)3 / nsteps, a[4], y[10];
  for (int s = 0; s < nsteps; ++s)
    gbs(s * H, z, H, kc);
  accel(3, z, a, y + 8);
  for (int i = 0; i < NV; ++i)
    y[i] = z[i];
  int bad = 0;
  for (int i = 0; i < 10; ++i) {
    char buf[64];
    quadmath_snprintf(buf, sizeof buf, "%+.24Qe", y[i]);
    real ref = strtoflt128(caraxis_ref[i], NULL), e = fabsq(y[i] - ref) / fabsq(ref);
    printf("y%-2d %s  rel. diff. to ref_caraxis.h %.1e\n", i + 1, buf, (double)e);
    if (argc <= 2 && !(e <= 1e-22Q)) bad = 1;
  }
  return bad;
}
