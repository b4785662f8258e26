// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Equilibria in one parameter: the pitchfork of a bead on a turning ring.
//
// Bead of mass m on a ring of radius R turning about the vertical at rate w (dal_map_ring).
// Reference (closed form, e.g. Likharev, Essential Graduate Physics, CM 2.1): the equilibria in
// the ring are theta = 0 for every w, stable for w < w_c = sqrt(g/R) with small-oscillation
// frequency sqrt(g/R - w^2) and unstable above; and for w > w_c the pair
// cos(theta0) = g/(R w^2), stable with frequency w sin(theta0). The pitchfork sits at w_c.
// Checks: the trivial branch across w_c (theta = 0, verdict neutral below and unstable above,
// one critical point located at w_c to the bisection tolerance), both off-axis branches from
// 2 w_c down to 1.01 w_c (theta against acos, verdict neutral, frequencies), the equilibrium
// solver's singular-K report at w_c exactly, and option and callback errors.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

static const double grav = 9.81, R = 0.4, mass = 0.25;

static int build_ring(double w, dal_system **out, void *ctx) {
  (void)ctx;
  scn_knobs k = scn_default();
  k.g = grav;
  k.R = R;
  k.m = mass;
  k.spin = w;
  *out = scn_bead(&k);
  return *out ? DAL_OK : DAL_E_ARG;
}

typedef struct branch {
  int n, ncrit;
  double p[64], q[64], w2[64], pc[4];
  dal_stability v[64];
  dal_branch_kind kind[64];
} branch;

static int record(double p, const dal_system *sys, const dal_state *st, dal_stability v,
                  dal_branch_kind kind, void *ctx) {
  branch *br = ctx;
  (void)sys;
  if (kind == DAL_BRANCH_CRITICAL) {
    if (br->ncrit < 4) br->pc[br->ncrit] = p;
    br->ncrit++;
    return 0;
  }
  if (br->n >= 64) return 1;
  br->p[br->n] = p;
  br->q[br->n] = dal_state_q(st)[0];
  br->v[br->n] = v;
  CHECK(dal_state_qdot(st)[0] == 0.0 && fabs(dal_state_qddot(st)[0]) <= 1e-12);
  br->n++;
  return 0;
}

static void test_pitchfork(void) {
  int fails0 = check_failures;
  const double wc = sqrt(grav / R);
  dal_continuation_opts o = dal_default_continuation_opts();
  dal_continuation_report rep;
  // the trivial branch from 0.5 w_c to 2 w_c (w_c is not a grid point)
  static branch tb;
  double q0 = 0.0;
  o.p0 = 0.5 * wc;
  o.p1 = 2.0 * wc;
  o.npoints = 32;
  o.t = 0.3;
  int rc = dal_continue(build_ring, &q0, &o, record, &rep, &tb);
  CHECK_MSG(rc == 0, "trivial branch: %s (%s)", dal_status_name(rc), rep.msg);
  CHECK(tb.n == 32 && rep.npoints == 32 && rep.ncritical == 1 && tb.ncrit == 1);
  CHECK(rep.p_end == o.p1 && rep.msg[0] == 0);
  for (int i = 0; i < tb.n; ++i) {
    CHECK(tb.q[i] == 0.0);
    dal_stability want = tb.p[i] < wc ? DAL_NEUTRAL : DAL_UNSTABLE;
    CHECK_MSG(tb.v[i] == want, "trivial branch at w = %g: %s", tb.p[i],
              dal_stability_name(tb.v[i]));
  }
  double ptol = 1e-10 * (o.p1 - o.p0);
  CHECK_MSG(fabs(tb.pc[0] - wc) <= ptol + 1e-14 * wc, "critical point %.15g vs w_c %.15g", tb.pc[0],
            wc);
  printf("  %-34s %d points, critical point at %.12f (w_c %.12f)\n", "trivial branch", tb.n,
         tb.pc[0], wc);

  // the off-axis branches from 2 w_c down to 1.01 w_c: theta0 = +-acos(g/(R w^2)), stable
  for (int sgn = -1; sgn <= 1; sgn += 2) {
    static branch ob;
    memset(&ob, 0, sizeof ob);
    double g0 = sgn * 1.0;
    o.p0 = 2.0 * wc;
    o.p1 = 1.01 * wc;
    o.npoints = 25;
    rc = dal_continue(build_ring, &g0, &o, record, &rep, &ob);
    CHECK_MSG(rc == 0, "off-axis branch: %s (%s)", dal_status_name(rc), rep.msg);
    CHECK(ob.n == 25 && ob.ncrit == 0);
    double worst = 0.0;
    for (int i = 0; i < ob.n; ++i) {
      double th0 = sgn * acos(grav / (R * ob.p[i] * ob.p[i]));
      worst = fmax(worst, fabs(ob.q[i] - th0));
      CHECK_MSG(fabs(ob.q[i] - th0) <= 1e-12, "branch at w = %.6f: %.15f vs %.15f", ob.p[i],
                ob.q[i], th0);
      CHECK(ob.v[i] == DAL_NEUTRAL);
    }
    printf("  %-34s %d points, worst |theta - acos(g/(R w^2))| %.1e\n",
           sgn > 0 ? "off-axis branch theta > 0" : "off-axis branch theta < 0", ob.n, worst);
  }

  // the frequency on both sides of the fork: sqrt(g/R - w^2) below, w sin(theta0) above
  dal_system *sys = NULL;
  dal_state *st = NULL;
  double w2, z = 0.0, wl = 0.8 * wc, wh = 1.3 * wc;
  CHECK_OK(build_ring(wl, &sys, NULL));
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_set(sys, st, 0.0, &z, &z));
  CHECK_OK(dal_normal_modes(sys, st, &w2, NULL, NULL, NULL, NULL));
  CHECK_CLOSE(sqrt(w2), sqrt(grav / R - wl * wl), 1e-13);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  CHECK_OK(build_ring(wh, &sys, NULL));
  CHECK_OK(dal_state_create(sys, &st));
  double th = 1.0;
  CHECK_OK(dal_state_set(sys, st, 0.0, &th, &z));
  CHECK_OK(dal_equilibrium(sys, st, NULL, NULL));
  CHECK_OK(dal_normal_modes(sys, st, &w2, NULL, NULL, NULL, NULL));
  CHECK_CLOSE(sqrt(w2), wh * sin(acos(grav / (R * wh * wh))), 1e-13);
  dal_state_destroy(st);
  dal_system_destroy(sys);

  // exactly at the fork K = 0: the solver says so, naming the coordinate
  CHECK_OK(build_ring(wc, &sys, NULL));
  CHECK_OK(dal_state_create(sys, &st));
  th = 0.01;
  CHECK_OK(dal_state_set(sys, st, 0.0, &th, &z));
  dal_equilibrium_report er;
  rc = dal_equilibrium(sys, st, NULL, &er);
  // qddot ~ -w_c^2 theta^3 / 2 near 0 at the fork: a triple root, where Newton converges only
  // linearly (theta -> 2 theta / 3 per step) and the root is determined to eps^(1/3) ~ 6e-6
  // only: the residual sinks below rounding near theta ~ 1e-8, after ~ log(1e-6)/log(2/3) = 34
  // steps
  CHECK_MSG(rc == 0 && fabs(dal_state_q(st)[0]) < 1e-5 && er.iterations > 25 && er.iterations < 50,
            "at the fork: %s (%s), theta %g after %d steps", dal_status_name(rc),
            dal_state_errmsg(st), dal_state_q(st)[0], er.iterations);
  double zero = 0.0, K;
  CHECK_OK(dal_state_set(sys, st, 0.0, &zero, &z));
  CHECK_OK(dal_linearize(sys, st, NULL, NULL, &K));
  CHECK_MSG(fabs(K) <= 1e-15 * mass * grav * R, "K at the fork %g", K);
  dal_modes md;
  CHECK_OK(dal_normal_modes(sys, st, &w2, NULL, NULL, NULL, &md));
  CHECK_MSG(md.verdict == DAL_MARGINAL, "verdict at the fork %s", dal_stability_name(md.verdict));
  dal_state_destroy(st);
  dal_system_destroy(sys);
  printf("  %-34s %s\n", "pitchfork of the turning ring",
         check_failures > fails0 ? "FAILED" : "ok");
}

static int fail_build(double p, dal_system **out, void *ctx) {
  (void)ctx;
  if (p > 1.5) return -3;
  return build_ring(p, out, NULL);
}

static int stop_after(double p, const dal_system *sys, const dal_state *st, dal_stability v,
                      dal_branch_kind kind, void *ctx) {
  (void)p, (void)sys, (void)st, (void)v, (void)kind;
  int *count = ctx;
  return ++*count >= 3;
}

static void test_errors(void) {
  dal_continuation_opts o = dal_default_continuation_opts();
  dal_continuation_report rep;
  double q0 = 0.0;
  o.p0 = o.p1 = 1.0;
  CHECK(dal_continue(build_ring, &q0, &o, NULL, &rep, NULL) == DAL_E_ARG);
  CHECK(strstr(rep.msg, "p0") != NULL);
  o.p1 = 2.0;
  o.npoints = 1;
  CHECK(dal_continue(build_ring, &q0, &o, NULL, &rep, NULL) == DAL_E_ARG);
  o.npoints = 5;
  o.newton.xtol = -1;
  CHECK(dal_continue(build_ring, &q0, &o, NULL, &rep, NULL) == DAL_E_ARG);
  CHECK(strstr(rep.msg, "xtol") != NULL);
  o = dal_default_continuation_opts();
  o.cookie = 1;
  CHECK(dal_continue(build_ring, &q0, &o, NULL, &rep, NULL) == DAL_E_ARG);
  o = dal_default_continuation_opts();
  o.p0 = 1.0;
  o.p1 = 2.0;
  o.npoints = 5;
  // the rebuild callback fails past 1.5: the points before are reported, then it stops
  int count = 0;
  int rc = dal_continue(fail_build, &q0, &o, NULL, &rep, &count);
  CHECK(rc == DAL_E_CALLBACK && rep.npoints == 3 && rep.p_end == 1.5);
  CHECK_MSG(strstr(rep.msg, "rebuild returned -3") != NULL, "%s", rep.msg);
  // the point callback stops the branch
  count = 0;
  rc = dal_continue(build_ring, &q0, &o, stop_after, &rep, &count);
  CHECK(rc == DAL_E_CALLBACK && rep.npoints == 3 && count == 3);
  // equilibrium options
  dal_system *sys = NULL;
  dal_state *st = NULL;
  CHECK_OK(build_ring(1.0, &sys, NULL));
  CHECK_OK(dal_state_create(sys, &st));
  dal_equilibrium_opts eo = dal_default_equilibrium_opts();
  eo.max_iter = 0;
  CHECK(dal_equilibrium(sys, st, &eo, NULL) == DAL_E_ARG);
  // too few iterations from far away: DAL_E_CONV naming the iteration count
  eo = dal_default_equilibrium_opts();
  eo.max_iter = 1;
  double th = 1.0, z = 0.0;
  CHECK_OK(dal_state_set(sys, st, 0.0, &th, &z));
  rc = dal_equilibrium(sys, st, &eo, NULL);
  CHECK_MSG(rc == DAL_E_CONV && strstr(dal_state_errmsg(st), "1 iterations"), "%s: %s",
            dal_status_name(rc), dal_state_errmsg(st));
  // a step bound slows Newton down but it still converges
  eo = dal_default_equilibrium_opts();
  eo.max_step = 0.1;
  dal_equilibrium_report er;
  CHECK_OK(dal_state_set(sys, st, 0.0, &th, &z));
  CHECK_OK(dal_equilibrium(sys, st, &eo, &er));
  CHECK(fabs(dal_state_q(st)[0]) <= 1e-14 && er.iterations >= 10);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

int main(void) {
  printf("equilibria and continuation:\n");
  test_pitchfork();
  test_errors();
  return check_summary("test_analysis_branch");
}
