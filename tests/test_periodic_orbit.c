// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Periodic orbits by shooting: a period-1 orbit of the forced pendulum against the test's own
// Newton shooting (long-double RK4 with its own variational equations), its multipliers against
// that shooting's monodromy; the same orbit in Cartesian coordinates (on the manifold); a free
// period of the autonomous pendulum against the elliptic period 4 K(sin(th_max / 2)) / sqrt(g).
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

static const long double LPI = 3.14159265358979323846264338327950288L;
static const double PI = 3.14159265358979323846;

// the pendulum (l = 1) on a pivot x = a cos(w t): th'' = -g sin th + a w^2 cos(w t) cos th,
// with its variational equations (columns (dth, dth')); y = (th, th', 2 x 2 Phi)
static void forced_rhs(long double t, const long double *y, long double *f, long double g,
                       long double a, long double w) {
  long double s = sinl(y[0]), c = cosl(y[0]), d = a * w * w * cosl(w * t);
  long double k = -g * c - d * s; // d th'' / d th
  f[0] = y[1];
  f[1] = -g * s + d * c;
  for (int j = 0; j < 2; ++j) {
    f[2 + 2 * j] = y[3 + 2 * j];
    f[3 + 2 * j] = k * y[2 + 2 * j];
  }
}

// y(T) from y (6 values) by RK4 in steps of T / 20000
static void forced_flow(long double *y, long double g, long double a, long double w) {
  const int steps = 20000;
  long double T = 2 * LPI / w, h = T / steps, k1[6], k2[6], k3[6], k4[6], z[6];
  for (int i = 0; i < steps; ++i) {
    long double t = i * h;
    forced_rhs(t, y, k1, g, a, w);
    for (int j = 0; j < 6; ++j)
      z[j] = y[j] + h / 2 * k1[j];
    forced_rhs(t + h / 2, z, k2, g, a, w);
    for (int j = 0; j < 6; ++j)
      z[j] = y[j] + h / 2 * k2[j];
    forced_rhs(t + h / 2, z, k3, g, a, w);
    for (int j = 0; j < 6; ++j)
      z[j] = y[j] + h * k3[j];
    forced_rhs(t + h, z, k4, g, a, w);
    for (int j = 0; j < 6; ++j)
      y[j] += h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
  }
}

// the test's own shooting: (th0, th0') of the period-1 orbit from a guess, and its monodromy
static void forced_orbit(long double g, long double a, long double w, long double *x,
                         long double *M) {
  for (int it = 0; it < 20; ++it) {
    long double y[6] = {x[0], x[1], 1, 0, 0, 1};
    forced_flow(y, g, a, w);
    long double r0 = y[0] - x[0], r1 = y[1] - x[1];
    long double a11 = y[2] - 1, a21 = y[3], a12 = y[4], a22 = y[5] - 1;
    long double det = a11 * a22 - a12 * a21;
    x[0] -= (a22 * r0 - a12 * r1) / det;
    x[1] -= (-a21 * r0 + a11 * r1) / det;
    for (int j = 0; j < 4; ++j)
      M[j] = y[2 + j];
  }
}

static void test_forced(void) {
  const double g = SCN_G, a = 0.1, w = 5.0;
  scn_knobs k = scn_default();
  k.ax = a;
  k.w = w;
  dal_system *sys = scn_pendulum(&k);
  CHECK(sys != NULL);
  if (!sys) return;
  // the linear response a w^2 / (g - w^2) cos(w t) as the guess
  double th = a * w * w / (g - w * w), v = 0.0;
  long double x[2] = {th, 0}, M[4];
  forced_orbit(g, a, w, x, M);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_set(sys, st, 0.0, &th, &v));
  dal_orbit_opts o = dal_default_orbit_opts();
  o.period = 2 * PI / w;
  dal_orbit_report rep;
  double mr[2], mi[2];
  CHECK_OK(dal_periodic_orbit(sys, st, &o, mr, mi, &rep));
  CHECK_CLOSE(dal_state_q(st)[0], (double)x[0], 1e-9);
  CHECK_CLOSE(dal_state_qdot(st)[0], (double)x[1], 1e-9);
  CHECK(fabsl(x[0] - th) > 1e-3); // the nonlinear orbit differs from the guess
  CHECK(rep.residual <= 1e-9 && rep.iterations >= 2);
  CHECK_CLOSE(rep.period, o.period, 0.0);
  CHECK_CLOSE(rep.floquet.trace, (double)(M[0] + M[3]), 1e-8);
  CHECK_CLOSE(rep.floquet.det, 1.0, 1e-8);
  CHECK_CLOSE(mr[0] + mr[1], (double)(M[0] + M[3]), 1e-8);
  CHECK(rep.floquet.verdict == (fabsl(M[0] + M[3]) < 2 ? DAL_NEUTRAL : DAL_UNSTABLE));
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

static int pivot_x(dal_jet t, dal_jet *x, void *ctx) {
  const double *aw = ctx;
  x[0] = dal_scale(dal_cos(dal_scale(t, aw[1])), aw[0]);
  x[1] = dal_const(0.0);
  return 0;
}

static void test_forced_cartesian(void) {
  const double g = SCN_G, a = 0.1, w = 5.0;
  double aw[2] = {a, w};
  dal_moving_point mp = {pivot_x, aw};
  scn_knobs k = scn_default();
  k.pivot = &mp;
  dal_system *sys = scn_cart_pendulum(&k);
  CHECK(sys != NULL);
  if (!sys) return;
  long double x[2] = {a * w * w / (g - w * w), 0}, M[4];
  forced_orbit(g, a, w, x, M);
  // a start near the orbit: the bob under the pivot (a, 0) displaced by the guess angle
  double th = (double)x[0] + 0.02, q[2] = {a + sin(th), -cos(th)}, v[2] = {0.0, 0.0};
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
  CHECK_OK(dal_make_consistent(sys, st, 0.0, NULL));
  dal_orbit_opts o = dal_default_orbit_opts();
  o.period = 2 * PI / w;
  dal_orbit_report rep;
  CHECK_OK(dal_periodic_orbit(sys, st, &o, NULL, NULL, &rep));
  const double *qs = dal_state_q(st), *vs = dal_state_qdot(st);
  // the angle and its rate from the bob relative to the pivot (a cos 0, 0) at t = 0
  double ang = atan2(qs[0] - a, -qs[1]), rate = vs[0] * cos(ang) + vs[1] * sin(ang);
  CHECK_CLOSE(ang, (double)x[0], 1e-8);
  CHECK_CLOSE(rate, (double)x[1], 1e-8);
  CHECK(rep.floquet.count == 2);
  CHECK_CLOSE(rep.floquet.trace, (double)(M[0] + M[3]), 1e-7);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// complete elliptic integral of the first kind by the arithmetic-geometric mean
static double ellip_k(double m) {
  double a = 1.0, b = sqrt(1.0 - m);
  for (int i = 0; i < 40; ++i) {
    double an = 0.5 * (a + b);
    b = sqrt(a * b);
    a = an;
  }
  return PI / (2 * a);
}

static void test_free_period(void) {
  dal_system *sys = scn_pendulum(NULL);
  CHECK(sys != NULL);
  if (!sys) return;
  double th = 1.0, v = 0.05;
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_set(sys, st, 0.0, &th, &v));
  dal_orbit_opts o = dal_default_orbit_opts();
  o.period = 2.14; // a guess: the small-amplitude period is 2.006, at 1 rad 2.14
  o.free_period = 1;
  dal_orbit_report rep;
  CHECK_OK(dal_periodic_orbit(sys, st, &o, NULL, NULL, &rep));
  // the period of the orbit it found, from its energy: cos th_max = cos th - th'^2 / (2 g)
  double q = dal_state_q(st)[0], qd = dal_state_qdot(st)[0];
  double cmax = cos(q) - qd * qd / (2 * SCN_G), s = sin(0.5 * acos(cmax));
  double T = 4 * ellip_k(s * s) / sqrt(SCN_G);
  CHECK_CLOSE(rep.period, T, 1e-9);
  // (the minimum-norm steps slide along the family of orbits: the amplitude found is not the
  // start's; at 0.03 rad the elliptic period still differs from 2 pi / sqrt(g) by 6e-5)
  CHECK_MSG(acos(cmax) > 0.01, "amplitude %g period %g", acos(cmax), rep.period);
  // trivial multipliers left out: the rest (none for one degree of freedom) is stable
  CHECK(rep.floquet.verdict == DAL_NEUTRAL);
  CHECK_CLOSE(rep.floquet.det, 1.0, 1e-7);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// options are checked; a start far from any orbit in few iterations fails naming the gap
static void test_errors(void) {
  dal_system *sys = scn_pendulum(NULL);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double th = 0.3, v = 0.0;
  CHECK_OK(dal_state_set(sys, st, 0.0, &th, &v));
  dal_orbit_opts o = dal_default_orbit_opts();
  CHECK(dal_periodic_orbit(sys, st, &o, NULL, NULL, NULL) == DAL_E_ARG); // no period
  o.period = 1.234;
  o.max_iter = 2;
  int rc = dal_periodic_orbit(sys, st, &o, NULL, NULL, NULL);
  CHECK(rc == DAL_E_CONV || rc == DAL_E_SINGULAR);
  CHECK_MSG(strstr(dal_state_errmsg(st), "periodic_orbit"), "%s", dal_state_errmsg(st));
  CHECK(dal_state_q(st)[0] == 0.3); // the state as given
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// ---------------------------------------------------------------------------------------------
// continuation: the bottom of the vertically driven pendulum in the amplitude a at fixed w
// (Mathieu A = 4 g / w^2 = 0.9) enters the first tongue, where a multiplier passes -1: the
// period doubling against the test's own long-double Mathieu monodromy (trace = -2, bisection)

static double vert_trace(long double a, long double w) {
  const int steps = 20000;
  long double T = 2 * LPI / w, h = T / steps, y[4] = {1, 0, 0, 1}, k[4][4], z[4];
  for (int i = 0; i < steps; ++i) {
    long double t = i * h;
    for (int s = 0; s < 4; ++s) {
      long double ts = t + (s == 0 ? 0 : s == 3 ? h : h / 2);
      for (int j = 0; j < 4; ++j)
        z[j] = y[j] + (s == 0 ? 0 : (s == 3 ? h : h / 2) * k[s - 1][j]);
      long double kk = (SCN_G - a * w * w * cosl(w * ts));
      k[s][0] = z[1];
      k[s][1] = -kk * z[0];
      k[s][2] = z[3];
      k[s][3] = -kk * z[2];
    }
    for (int j = 0; j < 4; ++j)
      y[j] += h / 6 * (k[0][j] + 2 * k[1][j] + 2 * k[2][j] + k[3][j]);
  }
  return (double)(y[0] + y[3]);
}

typedef struct vctx {
  double w;
  int pd, regular;
  double p_pd;
} vctx;

static int vrebuild(double a, dal_system **out, void *ctx) {
  const vctx *v = ctx;
  scn_knobs k = scn_default();
  k.ay = a;
  k.w = v->w;
  *out = scn_pendulum(&k);
  return *out ? 0 : 1;
}

static int vpoint(double p, const dal_system *sys, const dal_state *st, const dal_orbit_report *rep,
                  const double *re, const double *im, dal_orbit_kind kind, void *ctx) {
  vctx *v = ctx;
  (void)sys;
  (void)st;
  (void)re;
  (void)im;
  CHECK(rep->floquet.count == 2);
  if (kind == DAL_ORBIT_PERIOD_DOUBLING) {
    ++v->pd;
    v->p_pd = p;
    CHECK_CLOSE(rep->floquet.trace, -2.0, 1e-6);
  } else {
    CHECK(kind == DAL_ORBIT_REGULAR);
    ++v->regular;
  }
  return 0;
}

static void test_continue(void) {
  vctx v = {2 * sqrt(SCN_G / 0.9), 0, 0, 0.0};
  // the reference: trace(a) + 2 changes sign once on [0.01, 0.15]
  double lo = 0.01, hi = 0.15;
  CHECK(vert_trace(lo, v.w) > -2 && vert_trace(hi, v.w) < -2);
  for (int i = 0; i < 50; ++i) {
    double mid = 0.5 * (lo + hi);
    if (vert_trace(mid, v.w) > -2)
      lo = mid;
    else
      hi = mid;
  }
  double a_ref = 0.5 * (lo + hi);
  dal_orbit_continuation_opts o = dal_default_orbit_continuation_opts();
  o.p0 = 0.01;
  o.p1 = 0.15;
  o.npoints = 8;
  o.orbit.period = 2 * PI / v.w;
  double y0[2] = {0.0, 0.0};
  dal_continuation_report rep;
  CHECK_OK(dal_orbit_continue(vrebuild, y0, &o, vpoint, &rep, &v));
  CHECK(rep.npoints == 8 && rep.ncritical == 1 && v.pd == 1 && v.regular == 8);
  CHECK_MSG(fabs(v.p_pd - a_ref) < 1e-8, "period doubling at a = %.12g, reference %.12g", v.p_pd,
            a_ref);
  // Mathieu's series for the boundary b1(Q) = 1 - Q - Q^2/8 + Q^3/64 - Q^4/1536 = 0.9 (A&S
  // 20.2.25, Q = 2 a): within its truncation
  double Q = 2 * a_ref;
  CHECK(fabs(1 - Q - Q * Q / 8 + Q * Q * Q / 64 - pow(Q, 4) / 1536 - 0.9) < 1e-6);
  // bad options
  dal_orbit_continuation_opts bad = o;
  bad.npoints = 1;
  CHECK(dal_orbit_continue(vrebuild, y0, &bad, vpoint, &rep, &v) == DAL_E_ARG);
  CHECK(dal_orbit_continue(vrebuild, NULL, &o, vpoint, &rep, &v) == DAL_E_ARG);
}

int main(void) {
  test_forced();
  test_forced_cartesian();
  test_free_period();
  test_errors();
  test_continue();
  return check_summary("test_periodic_orbit");
}
