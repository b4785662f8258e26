// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Time dependence never frozen silently, and Floquet multipliers of the driven pendulum against
// the test's own long-double integration of the Mathieu equation, Liouville (det = 1), the
// Cartesian (constrained) pendulum's 2(n - m) multipliers, and Kapitza's stabilization of the
// inverted pendulum against the Mathieu chart's series (Abramowitz & Stegun 20.2.25).
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "dalembert/scene.h"
#include "scenes.h"

static const double PI = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// reference: the linearized pendulum on a vertically driven pivot y = a cos(w t),
//   x'' + s (g - a w^2 cos(w t)) / l x = 0   (s = +1 at the bottom, -1 at the top),
// its 2 x 2 monodromy over 2 pi / w by classical RK4 in long double with 40000 steps

static void mathieu_rhs(long double t, const long double *y, long double *f, long double s,
                        long double g, long double l, long double a, long double w) {
  long double k = s * (g - a * w * w * cosl(w * t)) / l;
  f[0] = y[1];
  f[1] = -k * y[0];
  f[2] = y[3];
  f[3] = -k * y[2];
}

// the monodromy [x1 x2; x1' x2'] (column-major 2 x 2) into M
static void mathieu_monodromy(double s, double g, double l, double a, double w, double *M) {
  const int steps = 40000;
  long double T = 2.0L * 3.14159265358979323846264338327950288L / w, h = T / steps;
  long double y[4] = {1, 0, 0, 1}, k1[4], k2[4], k3[4], k4[4], z[4];
  for (int i = 0; i < steps; ++i) {
    long double t = i * h;
    mathieu_rhs(t, y, k1, s, g, l, a, w);
    for (int j = 0; j < 4; ++j)
      z[j] = y[j] + h / 2 * k1[j];
    mathieu_rhs(t + h / 2, z, k2, s, g, l, a, w);
    for (int j = 0; j < 4; ++j)
      z[j] = y[j] + h / 2 * k2[j];
    mathieu_rhs(t + h / 2, z, k3, s, g, l, a, w);
    for (int j = 0; j < 4; ++j)
      z[j] = y[j] + h * k3[j];
    mathieu_rhs(t + h, z, k4, s, g, l, a, w);
    for (int j = 0; j < 4; ++j)
      y[j] += h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
  }
  M[0] = (double)y[0];
  M[1] = (double)y[1];
  M[2] = (double)y[2];
  M[3] = (double)y[3];
}

// the driven pendulum in its angle (scn_pendulum: pivot (0, a cos wt))
static dal_system *driven(double g, double a, double w) {
  scn_knobs k = scn_default();
  k.g = g;
  k.ay = a;
  k.w = w;
  return scn_pendulum(&k);
}

static dal_state *at(const dal_system *sys, double theta, double rate) {
  dal_state *st = NULL;
  if (dal_state_create(sys, &st)) return NULL;
  if (dal_state_set(sys, st, 0.0, &theta, &rate)) {
    dal_state_destroy(st);
    return NULL;
  }
  return st;
}

// ---------------------------------------------------------------------------------------------
// 1. time dependence is never frozen silently

static void test_time_dependence(void) {
  char what[512];
  // the driven pendulum depends on t (its pivot); the undriven and the bead on a uniformly
  // turning ring (measured in the ring: the co-rotating frame) do not
  dal_system *dp = driven(9.8, 0.1, 2 * sqrt(9.8)), *free_ = driven(9.8, 0.0, 0.0);
  scn_knobs kb = scn_default();
  kb.spin = 5.0;
  dal_system *bead = scn_bead(&kb);
  CHECK(dp && free_ && bead);
  if (!dp || !free_ || !bead) return;
  dal_state *s1 = at(dp, 0.0, 0.0), *s2 = at(free_, 0.3, 0.0), *s3 = NULL;
  double th = 1.0, v = 0.0;
  CHECK_OK(dal_state_create(bead, &s3));
  CHECK_OK(dal_state_set(bead, s3, 0.0, &th, &v));
  CHECK(dal_time_dependence(dp, s1, what, sizeof what) == 1);
  CHECK_MSG(strstr(what, "'bob'") != NULL, "%s", what);
  CHECK(dal_time_dependence(free_, s2, what, sizeof what) == 0);
  CHECK(dal_time_dependence(bead, s3, what, sizeof what) == 0);
  CHECK_MSG(strstr(what, "steadily") && strstr(what, "'bead'"), "%s", what);
  CHECK(dal_state_time(s1) == 0.0 && dal_state_q(s1)[0] == 0.0); // the state as given

  // modes refuse the driven pendulum, naming the dependence and the call that fits
  dal_modes md;
  double w2[1];
  int rc = dal_normal_modes(dp, s1, w2, NULL, NULL, NULL, &md);
  CHECK(rc == DAL_E_UNSUPPORTED);
  CHECK_MSG(strstr(dal_state_errmsg(s1), "dal_floquet") && strstr(dal_state_errmsg(s1), "frozen") &&
                strstr(dal_state_errmsg(s1), "'bob'"),
            "%s", dal_state_errmsg(s1));
  // ... and give the frozen ones by name, saying so; the bead's modes are not frozen
  CHECK_OK(dal_normal_modes_frozen(dp, s1, w2, NULL, NULL, NULL, &md));
  CHECK(md.frozen == 1 && md.verdict == DAL_NEUTRAL);
  CHECK_CLOSE(w2[0], 9.8 - 0.1 * 4 * 9.8, 1e-12); // frozen at t = 0: g - a w^2 (l = 1)
  CHECK_OK(dal_equilibrium(bead, s3, NULL, NULL));
  CHECK_OK(dal_normal_modes(bead, s3, w2, NULL, NULL, NULL, &md));
  CHECK(md.frozen == 0);

  // the bottom of the driven pendulum is an equilibrium at every time: found
  th = 0.2;
  CHECK_OK(dal_state_set(dp, s1, 0.0, &th, &v));
  CHECK_OK(dal_equilibrium(dp, s1, NULL, NULL));
  CHECK(fabs(dal_state_q(s1)[0]) < 1e-12);
  // a horizontally driven pivot: the frozen point at t = 0 is refused unless asked for
  scn_knobs kh = scn_default();
  kh.ax = 0.1;
  kh.w = 5.0;
  dal_system *hp = scn_pendulum(&kh);
  dal_state *s4 = hp ? at(hp, 0.2, 0.0) : NULL;
  CHECK(s4 != NULL);
  if (s4) {
    rc = dal_equilibrium(hp, s4, NULL, NULL);
    CHECK(rc == DAL_E_UNSUPPORTED);
    CHECK_MSG(strstr(dal_state_errmsg(s4), "frozen_time") &&
                  strstr(dal_state_errmsg(s4), "dal_periodic_orbit"),
              "%s", dal_state_errmsg(s4));
    dal_equilibrium_opts eo = dal_default_equilibrium_opts();
    eo.frozen_time = 1;
    th = 0.2;
    CHECK_OK(dal_state_set(hp, s4, 0.0, &th, &v));
    CHECK_OK(dal_equilibrium(hp, s4, &eo, NULL));
    // frozen at t = 0 the pivot accelerates by -a w^2 in x: tan theta = a w^2 / g
    CHECK_CLOSE(dal_state_q(s4)[0], atan(0.1 * 25.0 / SCN_G), 1e-10);
  }
  dal_state_destroy(s1);
  dal_state_destroy(s2);
  dal_state_destroy(s3);
  dal_state_destroy(s4);
  dal_system_destroy(dp);
  dal_system_destroy(free_);
  dal_system_destroy(bead);
  dal_system_destroy(hp);
}

// the regression of issue 31: the scene file's driven pendulum, modes refused with the remedy
static void test_scene_regression(void) {
  dal_scene *sc = NULL;
  char msg[512];
  CHECK_OK(dal_scene_read(SCENE_DIR "/driven_pendulum.scene", &sc, msg, sizeof msg));
  if (!sc) return;
  const dal_system *sys = dal_scene_system(sc);
  dal_state *st = NULL;
  CHECK_OK(dal_scene_state(sc, &st));
  double th = 0.0, v = 0.0;
  CHECK_OK(dal_state_set(sys, st, 0.0, &th, &v));
  dal_modes md;
  CHECK(dal_normal_modes(sys, st, NULL, NULL, NULL, NULL, &md) == DAL_E_UNSUPPORTED);
  // its bottom over the strobe period (the scene declares it): unstable, trace -2.0986 (issue
  // 31's figure) from the Mathieu reference
  double T = dal_scene_strobe(sc), M[4], mr[2], mi[2];
  CHECK_CLOSE(T, 2 * PI / 6.2609903369994111, 1e-15);
  mathieu_monodromy(1.0, 9.8, 1.0, 0.1, 6.2609903369994111, M);
  dal_floquet_report rep;
  CHECK_OK(dal_floquet(sys, st, NULL, T, mr, mi, NULL, &rep));
  CHECK_CLOSE(rep.trace, M[0] + M[3], 1e-8);
  CHECK_CLOSE(rep.trace, -2.0986, 1e-4);
  CHECK(rep.verdict == DAL_UNSTABLE);
  CHECK_MSG(rep.accuracy < 1e-7, "accuracy %g", rep.accuracy);
  CHECK_CLOSE(rep.det, 1.0, 1e-8); // Liouville
  dal_state_destroy(st);
  dal_scene_destroy(sc);
}

// ---------------------------------------------------------------------------------------------
// 2. Floquet multipliers

// the bottom and the top of the driven pendulum over a grid of drives, minimal coordinates
// against the Mathieu reference: trace, multipliers, det = 1, the verdict
static void test_mathieu(void) {
  const double g = SCN_G,
               drives[][2] = {
                   {0.1, 6.0}, {0.1, 2 * sqrt(SCN_G)}, {0.05, 30.0}, {0.2, 20.0}, {0.02, 4.0}};
  for (int d = 0; d < 5; ++d) {
    double a = drives[d][0], w = drives[d][1], T = 2 * PI / w;
    dal_system *sys = driven(g, a, w);
    for (int top = 0; top < 2 && sys; ++top) {
      dal_state *st = at(sys, top ? PI : 0.0, 0.0);
      double M[4], mr[2], mi[2], mono[4];
      mathieu_monodromy(top ? -1.0 : 1.0, g, 1.0, a, w, M);
      double tr = M[0] + M[3];
      dal_floquet_report rep;
      CHECK_OK(dal_floquet(sys, st, NULL, T, mr, mi, mono, &rep));
      CHECK_CLOSE(rep.trace, tr, 1e-8);
      CHECK_CLOSE(mono[0], M[0], 1e-8);
      CHECK_CLOSE(mono[1], M[1], 1e-8 * (1 + fabs(M[1])));
      CHECK_CLOSE(mono[2], M[2], 1e-8);
      CHECK_CLOSE(rep.det, 1.0, 1e-8);
      CHECK(rep.count == 2);
      // multipliers of the reference: roots of mu^2 - tr mu + 1
      double disc = tr * tr - 4, big = disc > 0 ? (fabs(tr) + sqrt(disc)) / 2 : 1.0;
      CHECK_CLOSE(rep.max_abs, big, 1e-7);
      CHECK_CLOSE(hypot(mr[0], mi[0]), big, 1e-7);
      dal_stability want = fabs(tr) > 2 + 1e-6   ? DAL_UNSTABLE
                           : fabs(tr) < 2 - 1e-6 ? DAL_NEUTRAL
                                                 : DAL_MARGINAL;
      CHECK_MSG(rep.verdict == want, "a %g w %g top %d: tr %.10g verdict %s", a, w, top, tr,
                dal_floquet_verdict_name(rep.verdict));
      CHECK(dal_state_time(st) == 0.0); // back at the start
      dal_state_destroy(st);
    }
    dal_system_destroy(sys);
  }
}

static int pivot_path(dal_jet t, dal_jet *x, void *ctx) {
  const double *aw = ctx;
  x[0] = dal_const(0.0);
  x[1] = dal_scale(dal_cos(dal_scale(t, aw[1])), aw[0]);
  return 0;
}

// the same pendulum in Cartesian coordinates on the moving pivot: 2 (n - m) = 2 multipliers,
// the angle's
static void test_manifold(void) {
  double aw[2] = {0.1, 6.0};
  dal_moving_point mp = {pivot_path, aw};
  scn_knobs k = scn_default();
  k.pivot = &mp;
  dal_system *sys = scn_cart_pendulum(&k);
  CHECK(sys != NULL);
  if (!sys) return;
  dal_state *st = NULL;
  double q[2] = {0.0, 0.1 - 1.0}, v[2] = {0.0, 0.0}, M[4], mr[2], mi[2];
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
  char what[512];
  CHECK(dal_time_dependence(sys, st, what, sizeof what) == 1);
  CHECK_MSG(strstr(what, "constraint 'rod'"), "%s", what);
  dal_floquet_report rep;
  mathieu_monodromy(1.0, SCN_G, 1.0, aw[0], aw[1], M);
  CHECK_OK(dal_floquet(sys, st, NULL, 2 * PI / aw[1], mr, mi, NULL, &rep));
  CHECK(rep.count == 2);
  CHECK_CLOSE(rep.trace, M[0] + M[3], 1e-7);
  CHECK_CLOSE(rep.det, 1.0, 1e-7);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// a state on no periodic solution is refused, naming the coordinate
static void test_not_periodic(void) {
  dal_system *sys = driven(SCN_G, 0.1, 6.0);
  dal_state *st = sys ? at(sys, 0.5, 0.0) : NULL;
  CHECK(st != NULL);
  if (!st) return;
  int rc = dal_floquet(sys, st, NULL, 2 * PI / 6.0, NULL, NULL, NULL, NULL);
  CHECK(rc == DAL_E_ARG);
  CHECK_MSG(strstr(dal_state_errmsg(st), "'theta'") &&
                strstr(dal_state_errmsg(st), "dal_periodic_orbit"),
            "%s", dal_state_errmsg(st));
  CHECK(dal_floquet(sys, st, NULL, -1.0, NULL, NULL, NULL, NULL) == DAL_E_ARG);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// ---------------------------------------------------------------------------------------------
// 3. Kapitza: the inverted pendulum stands above a critical drive frequency. In Mathieu's form
// y'' + (A - 2 Q cos 2s) y = 0 (s = w t / 2) the top has A = -4 g / (l w^2), Q = 2 a / l; it is
// stable for A > a0(Q), a0(Q) = -Q^2/2 + 7 Q^4/128 - 29 Q^6/2304 + 68687 Q^8/18874368 - ...
// (Abramowitz & Stegun 20.2.25), where the multiplier pair leaves the circle at +1.

// trace - 2 of the top's monodromy at drive frequency w (amplitude a, l = 1)
static double top_trace(double a, double w, int *ok) {
  dal_system *sys = driven(SCN_G, a, w);
  dal_state *st = sys ? at(sys, PI, 0.0) : NULL;
  dal_floquet_report rep;
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-12;
  int rc = st ? dal_floquet(sys, st, &o, 2 * PI / w, NULL, NULL, NULL, &rep) : DAL_E_NOMEM;
  *ok &= rc == DAL_OK;
  dal_state_destroy(st);
  dal_system_destroy(sys);
  return rc ? NAN : rep.trace - 2.0;
}

static void test_kapitza(void) {
  const double a = 0.05, Q = 2 * a;
  double a0 =
      -Q * Q / 2 + 7 * pow(Q, 4) / 128 - 29 * pow(Q, 6) / 2304 + 68687 * pow(Q, 8) / 18874368;
  double w_series = sqrt(-4 * SCN_G / a0);
  // the library's boundary by bisection on the sign of tr - 2 (unstable below, stable above)
  int ok = 1;
  double lo = 0.9 * w_series, hi = 1.1 * w_series;
  double flo = top_trace(a, lo, &ok), fhi = top_trace(a, hi, &ok);
  CHECK(ok && flo > 0 && fhi < 0);
  for (int i = 0; i < 40 && ok; ++i) {
    double mid = 0.5 * (lo + hi), f = top_trace(a, mid, &ok);
    if (f > 0)
      lo = mid;
    else
      hi = mid;
  }
  double w_lib = 0.5 * (lo + hi);
  CHECK_MSG(fabs(w_lib - w_series) < 1e-7 * w_series, "w_lib %.12g series %.12g", w_lib, w_series);
  // the verdicts on both sides: unstable 1% below, stable 1% above (Kapitza's criterion
  // a^2 w^2 > 2 g l to first order)
  dal_system *s1 = driven(SCN_G, a, 0.99 * w_lib), *s2 = driven(SCN_G, a, 1.01 * w_lib);
  dal_state *t1 = at(s1, PI, 0.0), *t2 = at(s2, PI, 0.0);
  dal_floquet_report r1, r2;
  CHECK_OK(dal_floquet(s1, t1, NULL, 2 * PI / (0.99 * w_lib), NULL, NULL, NULL, &r1));
  CHECK_OK(dal_floquet(s2, t2, NULL, 2 * PI / (1.01 * w_lib), NULL, NULL, NULL, &r2));
  CHECK(r1.verdict == DAL_UNSTABLE && r2.verdict == DAL_NEUTRAL);
  CHECK(a * a * w_lib * w_lib > 2 * SCN_G && a * a * w_lib * w_lib < 2.1 * SCN_G);
  dal_state_destroy(t1);
  dal_state_destroy(t2);
  dal_system_destroy(s1);
  dal_system_destroy(s2);
}

int main(void) {
  test_time_dependence();
  test_scene_regression();
  test_mathieu();
  test_manifold();
  test_not_periodic();
  test_kapitza();
  return check_summary("test_floquet");
}
