// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Bulirsch-Stoer's rounding floor: a tighter request never gives a worse answer.
//
// 1. SICM's harmonic oscillator (m = 2, k = 1, q = (1, 2), v = (3, 4), to t = 10) against its
//    closed form (evaluated in long double): every rtol from 3e-13 to 1e-15 ends within
//    1.5e-14, the seed system's floor (7.8e-15 ... 1.4e-14) (before the fix: 4e-14 ... 1.7e-13 at
//    14 steps: the harmonic step-number sequence amplifies the midpoint rule's rounding by sum
//    |c_j| = 119 in column 8).
// 2. SICM's driven pendulum (l = 1, g = 9.8, pivot y = 0.1 cos(2 sqrt(g) t), from theta = 1,
//    thetadot = 0) at t = 50 against a 30th-order Taylor series solution in long double
//    computed here (its own recurrences, 5000 steps of 0.01; the same method in binary128
//    with 2500 ... 20000 steps agrees to 1e-26 and gives theta(50) = 1.72984182498573860491,
//    thetadot(50) = -3.05471806600551615968). The flow amplifies a 1e-16 change of theta(0) to
//    3.3e-10 at t = 50, so rounding decides at tight tolerances. The median error over nine
//    rtol within a factor 2^(1/2) of 1e-12, 1e-13, 1e-14 must not grow as rtol shrinks, and
//    at 1e-13 stays below 5e-8 (before: 1.8e-7 at 1e-13, 2.6e-7 at 1e-14).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

static const double g_earth = 9.8, drive_a = 0.1;

static int spring(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  *U = dal_scale(dal_add(dal_sq(q[0]), dal_sq(q[1])), 0.5);
  return 0;
}

static dal_system *finish(dal_builder *b, int rc) {
  dal_system *sys = NULL;
  if (!rc) rc = dal_builder_compile(b, &sys);
  if (rc) fprintf(stderr, "build failed: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return sys;
}

static dal_system *oscillator(void) {
  dal_builder *b;
  int p, rc = dal_builder_create(2, &b);
  if (!rc) rc = scn_add_xy(b, "p", 2.0, "x", "y", &p);
  if (!rc) rc = dal_builder_add_potential_q(b, spring, NULL);
  return finish(b, rc);
}

static dal_system *driven(void) {
  scn_knobs k = scn_default();
  k.g = g_earth;
  k.ay = drive_a;
  k.w = 2 * sqrt(g_earth);
  return scn_pendulum(&k);
}

// theta'' = -(g - a w^2 cos(w t)) sin(theta) (pivot y = a cos(w t)), by a Taylor series of
// order K per step: theta_k from the series of sin(theta), cos(theta) (s' = c theta',
// c' = -s theta') times the forcing's series; parameters are the doubles the scene uses
#define TAYLOR_K 30
static void taylor_reference(double T, long nstep, long double *th, long double *thd) {
  long double g = g_earth, a = drive_a, w = 2 * sqrt(g_earth), h = (long double)T / nstep;
  long double x = 1, xd = 0, X[TAYLOR_K + 1], S[TAYLOR_K + 1], C[TAYLOR_K + 1], F[TAYLOR_K + 1];
  for (long st = 0; st < nstep; ++st) {
    long double t0 = (long double)T * st / nstep, cw = cosl(w * t0), sw = sinl(w * t0), wk = 1;
    // forcing g - a w^2 cos(w (t0 + tau)) in powers of tau
    for (int k = 0; k <= TAYLOR_K; ++k) {
      if (k) wk *= w / k;
      int m = k % 4;
      long double cc = m == 0 ? 1 : m == 2 ? -1 : 0, ss = m == 1 ? 1 : m == 3 ? -1 : 0;
      F[k] = (k == 0 ? g : 0) - a * w * w * wk * (cw * cc - sw * ss);
    }
    X[0] = x;
    X[1] = xd;
    S[0] = sinl(x);
    C[0] = cosl(x);
    for (int k = 0; k + 2 <= TAYLOR_K; ++k) {
      if (k > 0) {
        long double s = 0, c = 0;
        for (int j = 1; j <= k; ++j) {
          s += j * X[j] * C[k - j];
          c -= j * X[j] * S[k - j];
        }
        S[k] = s / k;
        C[k] = c / k;
      }
      long double p = 0;
      for (int j = 0; j <= k; ++j)
        p += F[j] * S[k - j];
      X[k + 2] = -p / ((long double)(k + 1) * (k + 2));
    }
    long double nx = 0, nv = 0;
    for (int k = TAYLOR_K; k >= 0; --k)
      nx = nx * h + X[k];
    for (int k = TAYLOR_K; k >= 1; --k)
      nv = nv * h + k * X[k];
    x = nx;
    xd = nv;
  }
  *th = x;
  *thd = xd;
}

static dal_solve_opts bs_opts(double rtol) {
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_BS;
  o.rtol = o.atol = rtol;
  return o;
}

static void test_oscillator_floor(void) {
  dal_system *sys = oscillator();
  CHECK(sys != NULL);
  if (!sys) return;
  const double q0[2] = {1, 2}, v0[2] = {3, 4}, T = 10;
  const long double w = sqrtl(0.5L);
  printf("SICM harmonic oscillator, Bulirsch-Stoer, t = 10, max |error| of (q, v) against the "
         "closed form\n  rtol      error     steps\n");
  const double rtols[] = {3e-13, 1e-13, 3e-14, 1e-14, 3e-15, 1e-15};
  for (size_t r = 0; r < sizeof rtols / sizeof rtols[0]; ++r) {
    dal_state *st = NULL;
    CHECK_OK(dal_state_create(sys, &st));
    CHECK_OK(dal_state_set(sys, st, 0, q0, v0));
    dal_solve_opts o = bs_opts(rtols[r]);
    CHECK_OK(dal_advance(sys, st, &o, T));
    long double err = 0;
    for (int k = 0; k < 2; ++k) {
      long double qe = q0[k] * cosl(w * T) + v0[k] / w * sinl(w * T);
      long double ve = -q0[k] * w * sinl(w * T) + v0[k] * cosl(w * T);
      err = fmaxl(err, fmaxl(fabsl(dal_state_q(st)[k] - qe), fabsl(dal_state_qdot(st)[k] - ve)));
    }
    dal_stats s;
    dal_state_stats(st, &s);
    printf("  %.0e  %.2Le  %ld\n", rtols[r], err, s.steps);
    CHECK_MSG(err <= 1.5e-14, "rtol %g: error %.3Lg above the floor 1.5e-14", rtols[r], err);
    dal_state_destroy(st);
  }
  dal_system_destroy(sys);
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static void test_driven_monotone(void) {
  dal_system *sys = driven();
  CHECK(sys != NULL);
  if (!sys) return;
  long double th_ref, thd_ref;
  taylor_reference(50.0, 5000, &th_ref, &thd_ref);
  // the reference against its binary128 value (see the header): long double keeps 1e-12
  CHECK(fabsl(th_ref - 1.72984182498573860491L) < 1e-11L);
  CHECK(fabsl(thd_ref + 3.05471806600551615968L) < 1e-11L);
  printf("SICM driven pendulum, Bulirsch-Stoer, t = 50, error against a long double Taylor "
         "solution: median and range over 9 rtol in [rtol/sqrt2, rtol sqrt2]\n"
         "  rtol    median     min        max\n");
  const double bases[] = {1e-12, 1e-13, 1e-14};
  double med[3];
  for (int bi = 0; bi < 3; ++bi) {
    double e[9];
    for (int i = 0; i < 9; ++i) {
      dal_state *st = NULL;
      double th = 1, thd = 0;
      CHECK_OK(dal_state_create(sys, &st));
      CHECK_OK(dal_state_set(sys, st, 0, &th, &thd));
      dal_solve_opts o = bs_opts(bases[bi] * pow(2.0, (i - 4) / 8.0));
      CHECK_OK(dal_advance(sys, st, &o, 50.0));
      e[i] =
          (double)fmaxl(fabsl(dal_state_q(st)[0] - th_ref), fabsl(dal_state_qdot(st)[0] - thd_ref));
      dal_state_destroy(st);
    }
    qsort(e, 9, sizeof e[0], cmp_double);
    med[bi] = e[4];
    printf("  %.0e  %.2e  %.2e  %.2e\n", bases[bi], e[4], e[0], e[8]);
  }
  CHECK_MSG(med[1] <= med[0], "median at 1e-13 %.3g above the one at 1e-12 %.3g", med[1], med[0]);
  CHECK_MSG(med[2] <= med[1], "median at 1e-14 %.3g above the one at 1e-13 %.3g", med[2], med[1]);
  CHECK_MSG(med[1] <= 5e-8, "median at 1e-13: %.3g", med[1]);
  dal_system_destroy(sys);
}

int main(void) {
  test_oscillator_floor();
  test_driven_monotone();
  return check_summary("test_rounding");
}
