// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Dense output against closed forms, for every method: dal_evolve's states between steps
// (output times that are no step's end) against the elliptic pendulum and the Cartesian
// pendulum, within the method's tolerance; outputs do not change the trajectory; tight
// tolerances over [0, 20] at irregular times by events and by dal_advance loops.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "ref_elliptic.h"
#include "scenes.h"

#define G0 SCN_G

// the worst deviation from the closed form over the outputs, and their count (th0, cart: the
// pendulum's)
typedef struct cmp {
  double th0, err;
  int cart, n;
} cmp;

static int mon(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  cmp *c = ctx;
  double th, thd, t = dal_state_time(st);
  ref_pendulum(c->th0, sqrt(G0), t, &th, &thd);
  const double *q = dal_state_q(st), *v = dal_state_qdot(st);
  double e;
  if (c->cart)
    e = fmax(fmax(fabs(q[0] - sin(th)), fabs(q[1] + cos(th))),
             fmax(fabs(v[0] - thd * cos(th)), fabs(v[1] - thd * sin(th))) / sqrt(G0));
  else
    e = fmax(fabs(q[0] - th), fabs(v[0] - thd) / sqrt(G0));
  c->err = fmax(c->err, e);
  c->n++;
  return 0;
}

// one run: evolve to t1 with outputs every dt; returns the worst error at the outputs and the
// error at t1 (the step points' accuracy)
static double run(const dal_system *s, dal_state *st, const dal_solve_opts *o, int cart, double dt,
                  double *end_err, long *steps) {
  const double th0 = 2.0, t1 = 10.0;
  if (cart) {
    double x[2] = {sin(th0), -cos(th0)}, v[2] = {0, 0};
    CHECK_OK(dal_state_set(s, st, 0.0, x, v));
  } else {
    double q = th0, qd = 0;
    CHECK_OK(dal_state_set(s, st, 0.0, &q, &qd));
  }
  cmp c = {th0, 0, cart, 0};
  int rc = dal_evolve(s, st, o, t1, dt, mon, &c);
  CHECK_MSG(rc == DAL_OK, "%s: %s", dal_method_name(o->method), dal_state_errmsg(st));
  cmp e = {th0, 0, cart, 0};
  mon(s, st, &e);
  *end_err = e.err;
  dal_stats sts;
  dal_state_stats(st, &sts);
  *steps = sts.steps;
  return c.err;
}

// the pendulum (0) and its Cartesian twin (1), the standard scenes, each with a state
typedef struct twins {
  dal_system *s[2];
  dal_state *st[2];
} twins;

static twins twins_make(void) {
  twins t = {{scn_pendulum(NULL), scn_cart_pendulum(NULL)}, {NULL, NULL}};
  for (int i = 0; i < 2; ++i)
    CHECK_OK(dal_state_create(t.s[i], &t.st[i]));
  return t;
}

static void twins_free(twins *t) {
  for (int i = 0; i < 2; ++i) {
    dal_state_destroy(t->st[i]);
    dal_system_destroy(t->s[i]);
  }
}

// adaptive methods: outputs between the steps within 16 x rtol (the library's promise for
// the step points, solve.h), and the step count independent of the outputs
static void test_adaptive(void) {
  twins P = twins_make();
  const struct {
    dal_method m;
    dal_formulation f;
  } cases[] = {
      {DAL_METHOD_DOPRI5, DAL_FORM_AUTO}, {DAL_METHOD_FEHLBERG78, DAL_FORM_AUTO},
      {DAL_METHOD_BS, DAL_FORM_AUTO},     {DAL_METHOD_ADAMS, DAL_FORM_AUTO},
      {DAL_METHOD_BDF, DAL_FORM_AUTO},    {DAL_METHOD_BDF, DAL_FORM_GGL},
      {DAL_METHOD_BS, DAL_FORM_INDEX1},   {DAL_METHOD_DOPRI5, DAL_FORM_INDEX1},
  };
  const double tols[] = {1e-5, 1e-8, 1e-11};
  printf("dense output: worst error at outputs every 0.0137 / rtol (error at t = 10 / rtol)\n");
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
    int cart = cases[k].f != DAL_FORM_AUTO;
    printf("  %-7s %-10s", cart ? dal_formulation_name(cases[k].f) : "minimal",
           dal_method_name(cases[k].m));
    for (size_t j = 0; j < sizeof tols / sizeof tols[0]; ++j) {
      dal_solve_opts o = dal_default_solve_opts();
      o.method = cases[k].m;
      o.form = cases[k].f;
      o.project = cases[k].f == DAL_FORM_INDEX1;
      o.rtol = tols[j];
      if (cases[k].f == DAL_FORM_GGL && o.rtol < 1e-9) o.rtol = 1e-9; // IDA's floor (solve.h)
      double end_dense = 0, end_coarse = 0;
      long st_dense = 0, st_coarse = 0;
      double e = run(P.s[cart], P.st[cart], &o, cart, 0.0137, &end_dense, &st_dense);
      run(P.s[cart], P.st[cart], &o, cart, 10.0, &end_coarse, &st_coarse);
      printf("  %6.2f (%5.2f)", e / o.rtol, end_dense / o.rtol);
      CHECK_MSG(e <= 16.0 * o.rtol, "%s %s rtol %g: dense error %g = %.1f x rtol",
                dal_formulation_name(cases[k].f), dal_method_name(o.method), o.rtol, e, e / o.rtol);
      // the local tolerance the method runs at is reported (solve.h: factor x rtol, floored)
      dal_stats ss;
      CHECK_OK(dal_state_stats(P.st[cart], &ss));
      CHECK_MSG(ss.rtol_used > 0 && ss.rtol_used <= o.rtol, "%s: rtol_used %g",
                dal_method_name(o.method), ss.rtol_used);
      // the outputs do not steer the steps: the same steps with and without them
      CHECK_MSG(st_dense == st_coarse && end_dense == end_coarse,
                "%s: %ld steps with outputs, %ld without", dal_method_name(o.method), st_dense,
                st_coarse);
    }
    printf("\n");
  }
  twins_free(&P);
}

// fixed-step methods: outputs between grid points as accurate as the grid points themselves
// (RK4's cubic Hermite and the symplectic methods' partial composed step are of the method's
// order), and the grid trajectory untouched by the outputs
static void test_fixed(void) {
  twins P = twins_make();
  const struct {
    dal_method m;
    double h;
    int cart;
  } cases[] = {
      {DAL_METHOD_RK4, 1e-3, 0},          {DAL_METHOD_VARIATIONAL, 1e-3, 0},
      {DAL_METHOD_VARIATIONAL4, 1e-2, 0}, {DAL_METHOD_VARIATIONAL6, 1e-2, 0},
      {DAL_METHOD_RATTLE, 1e-3, 1},       {DAL_METHOD_RATTLE4, 1e-2, 1},
  };
  printf("fixed-step dense output: worst error at outputs every 0.0137 and on the grid (0.1)\n");
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
    dal_solve_opts o = dal_default_solve_opts();
    o.method = cases[k].m;
    o.fixed_step = cases[k].h;
    int cart = cases[k].cart;
    double end_a = 0, end_b = 0;
    long sa = 0, sb = 0;
    double off = run(P.s[cart], P.st[cart], &o, cart, 0.0137, &end_a, &sa);
    double on = run(P.s[cart], P.st[cart], &o, cart, 0.1, &end_b, &sb);
    printf("  %-12s h = %g: off the grid %.2e, on the grid %.2e\n", dal_method_name(o.method),
           o.fixed_step, off, on);
    CHECK_MSG(off <= 1.5 * on + 1e-12, "%s: off-grid outputs %g, grid %g",
              dal_method_name(o.method), off, on);
    CHECK_MSG(end_a == end_b && sa == sb, "%s: the outputs changed the trajectory",
              dal_method_name(o.method));
  }
  twins_free(&P);
}

// Tight tolerances over [0, 20]: the pendulum at 2.5 rad against the elliptic solution at 986
// irregular times (gaps 0.005 ... 0.035), by both routes a user has: one event per time
// (g = t - t_k, rising: the state at the crossing comes from the dense output) in one
// dal_advance to 20, and a loop of dal_advance to each time. Every method within 16 x the
// request it honours (BDF honours 1e-11 at most: a tighter request runs as 1e-11, shown in
// rtol_used). Before: Adams 113 x and BDF 125 x by the loop, Adams 27.5 x by the events.
static double at_time(double t, const double *q, const double *qd, void *ctx) {
  (void)q;
  (void)qd;
  return t - *(const double *)ctx;
}

static double pend_err(double th0, double t, const double *q, const double *v) {
  double th, thd;
  ref_pendulum(th0, sqrt(G0), t, &th, &thd);
  return fmax(fabs(q[0] - th), fabs(v[0] - thd) / sqrt(G0));
}

static void test_tight_irregular(void) {
  const double th0 = 2.5, T = 20.0;
  static double tk[1200];
  int nk = 0;
  unsigned long long seed = 12345;
  for (double t = 0;;) {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    t += 0.005 + 0.03 * (double)(seed >> 11) / 9007199254740992.0;
    if (t >= T) break;
    tk[nk++] = t;
  }
  tk[nk++] = T;
  dal_system *s = scn_pendulum(NULL);
  dal_state *st = NULL;
  dal_events *ev = NULL;
  CHECK_OK(dal_state_create(s, &st));
  CHECK_OK(dal_events_create(s, &ev));
  for (int k = 0; k + 1 < nk; ++k) {
    dal_event_def d = dal_default_event_def();
    d.g = at_time;
    d.ctx = &tk[k];
    d.direction = DAL_EVENT_RISING;
    CHECK(dal_events_add(ev, &d) == k);
  }
  const dal_method ms[] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_BS,
                           DAL_METHOD_ADAMS, DAL_METHOD_BDF};
  const double tols[] = {1e-6, 1e-8, 1e-10, 1e-11, 1e-12};
  printf("pendulum at 2.5 rad, %d irregular times in [0, 20]: worst error / rtol by events | "
         "by a dal_advance loop\n  rtol      ",
         nk);
  for (size_t j = 0; j < sizeof tols / sizeof tols[0]; ++j)
    printf("  %-11.0e", tols[j]);
  printf("\n");
  for (size_t mi = 0; mi < sizeof ms / sizeof ms[0]; ++mi) {
    printf("  %-10s", dal_method_name(ms[mi]));
    for (size_t j = 0; j < sizeof tols / sizeof tols[0]; ++j) {
      dal_solve_opts o = dal_default_solve_opts();
      o.method = ms[mi];
      o.rtol = tols[j];
      // the bound below was set with atol = 1e-2 rtol (the default until the AUTO table of
      // docs/performance.md); with atol = rtol DOPRI5's dense output measures 25 x at 1e-12
      o.atol = 1e-2 * o.rtol;
      double q = th0, qd = 0, ea = 0, eb = 0;
      // the request honoured: BDF runs a tighter one as 1e-11, and says so in rtol_used
      double honoured = ms[mi] == DAL_METHOD_BDF ? fmax(o.rtol, 1e-11) : o.rtol;
      // events at the times, one call
      CHECK_OK(dal_state_set(s, st, 0.0, &q, &qd));
      CHECK_OK(dal_state_set_events(st, ev));
      CHECK_OK(dal_advance(s, st, &o, T));
      CHECK_MSG(dal_events_count(ev) == nk - 1, "%s: %ld events of %d", dal_method_name(o.method),
                dal_events_count(ev), nk - 1);
      for (long i = 0; i < dal_events_count(ev); ++i) {
        dal_event_record r;
        double qq, vv;
        CHECK_OK(dal_events_get(ev, i, &r, &qq, &vv));
        ea = fmax(ea, pend_err(th0, r.t, &qq, &vv));
      }
      dal_stats ss;
      CHECK_OK(dal_state_stats(st, &ss));
      if (honoured > o.rtol)
        CHECK_MSG(ss.rtol_used >= 1e-15 && ss.rtol_used > 1e-4 * o.rtol,
                  "%s at %g: the clamp does not show (rtol_used %g)", dal_method_name(o.method),
                  o.rtol, ss.rtol_used);
      CHECK_OK(dal_state_set_events(st, NULL));
      dal_events_clear(ev);
      // a loop of dal_advance
      CHECK_OK(dal_state_set(s, st, 0.0, &q, &qd));
      for (int k = 0; k < nk; ++k) {
        int rc = dal_advance(s, st, &o, tk[k]);
        CHECK_MSG(rc == DAL_OK, "%s: %s", dal_method_name(o.method), dal_state_errmsg(st));
        if (rc) break;
        eb = fmax(eb, pend_err(th0, tk[k], dal_state_q(st), dal_state_qdot(st)));
      }
      printf("  %5.1f|%5.1f", ea / o.rtol, eb / o.rtol);
      CHECK_MSG(ea <= 16.0 * honoured && eb <= 16.0 * honoured,
                "%s rtol %g: events %.1f x, loop %.1f x the honoured rtol %g",
                dal_method_name(o.method), o.rtol, ea / honoured, eb / honoured, honoured);
    }
    printf("\n");
  }
  dal_events_destroy(ev);
  dal_state_destroy(st);
  dal_system_destroy(s);
}

// Dense output by every route (issue 31): the pendulum at 2.5 rad over [0, 20] against the
// elliptic solution, with the default atol (= rtol), at 500 irregular times through
// dal_evolve_at, through the stored trajectory (dal_trajectory_eval at the same times after a
// dal_advance that recorded it), and on dal_evolve's grid (dt = 0.04, no step's end); worst
// error / rtol printed per method, rtol and route. The bound is 16 x rtol except where the
// table below says otherwise (solve.h quotes this table: the bounds are what this test checks).
typedef struct route_bound {
  dal_method m;
  double rtol; // the bound holds from this rtol up (0: every rtol)
  double bound;
} route_bound;

// the measured exceptions to 16 x rtol, stated in solve.h (dense output): DOPRI5 at rtol
// 1e-12, where its local tolerance 1e-14 meets rounding (the step ends too: the grid route
// measures the same); BDF below 1e-11 runs as 1e-11 (clamped, with a note): 16 x that
static const route_bound route_bounds[] = {
    {DAL_METHOD_DOPRI5, 1e-12, 32.0},
    {DAL_METHOD_BDF, 1e-12, 160.0},
};

static double route_bound_of(dal_method m, double rtol) {
  for (size_t i = 0; i < sizeof route_bounds / sizeof route_bounds[0]; ++i)
    if (route_bounds[i].m == m && rtol <= route_bounds[i].rtol) return route_bounds[i].bound;
  return 16.0;
}

typedef struct route_ctx {
  double th0, err;
} route_ctx;

static int route_mon(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  route_ctx *c = ctx;
  c->err = fmax(c->err, pend_err(c->th0, dal_state_time(st), dal_state_q(st), dal_state_qdot(st)));
  return 0;
}

static void test_routes(void) {
  const double th0 = 2.5, T = 20.0;
  enum { NT = 500 };
  static double tk[NT];
  unsigned long long seed = 777;
  // 500 irregular times in (0, 20], the last 20
  double acc = 0, gaps[NT];
  for (int k = 0; k < NT; ++k) {
    gaps[k] = check_rand(&seed, 0.2, 1.8);
    acc += gaps[k];
  }
  double t = 0;
  for (int k = 0; k < NT; ++k) {
    t += gaps[k] * T / acc;
    tk[k] = t;
  }
  tk[NT - 1] = T;
  dal_system *s = scn_pendulum(NULL);
  dal_state *st = NULL;
  dal_trajectory *tr = NULL;
  CHECK_OK(dal_state_create(s, &st));
  const dal_method ms[] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_BS,
                           DAL_METHOD_ADAMS, DAL_METHOD_BDF};
  const double tols[] = {1e-6, 1e-8, 1e-10, 1e-11, 1e-12};
  printf("pendulum at 2.5 rad over [0, 20], atol = rtol: worst error / rtol by dal_evolve_at "
         "(500 irregular times) | stored trajectory (same times) | dal_evolve (dt = 0.04)\n"
         "  rtol      ");
  for (size_t j = 0; j < sizeof tols / sizeof tols[0]; ++j)
    printf("  %-17.0e", tols[j]);
  printf("\n");
  for (size_t mi = 0; mi < sizeof ms / sizeof ms[0]; ++mi) {
    printf("  %-10s", dal_method_name(ms[mi]));
    for (size_t j = 0; j < sizeof tols / sizeof tols[0]; ++j) {
      dal_solve_opts o = dal_default_solve_opts();
      o.method = ms[mi];
      o.rtol = o.atol = tols[j];
      double q = th0, qd = 0, e[3] = {0, 0, 0};
      // dal_evolve_at
      route_ctx c = {th0, 0};
      CHECK_OK(dal_state_set(s, st, 0.0, &q, &qd));
      CHECK_OK(dal_evolve_at(s, st, &o, tk, NT, route_mon, &c));
      e[0] = c.err;
      // the stored trajectory of a dal_advance run
      CHECK_OK(dal_state_set(s, st, 0.0, &q, &qd));
      CHECK_OK(dal_trajectory_create(s, &tr));
      CHECK_OK(dal_state_set_trajectory(st, tr));
      CHECK_OK(dal_advance(s, st, &o, T));
      CHECK_OK(dal_state_set_trajectory(st, NULL));
      for (int k = 0; k < NT; ++k) {
        double qq, vv;
        CHECK_OK(dal_trajectory_eval(tr, tk[k], &qq, &vv));
        e[1] = fmax(e[1], pend_err(th0, tk[k], &qq, &vv));
      }
      dal_trajectory_destroy(tr);
      tr = NULL;
      // dal_evolve's grid
      route_ctx g = {th0, 0};
      CHECK_OK(dal_state_set(s, st, 0.0, &q, &qd));
      CHECK_OK(dal_evolve(s, st, &o, T, 0.04, route_mon, &g));
      e[2] = g.err;
      double b = route_bound_of(ms[mi], o.rtol);
      printf("  %5.1f|%5.1f|%5.1f", e[0] / o.rtol, e[1] / o.rtol, e[2] / o.rtol);
      CHECK_MSG(e[0] <= b * o.rtol && e[1] <= b * o.rtol && e[2] <= b * o.rtol,
                "%s rtol %g: evolve_at %.1f x, trajectory %.1f x, evolve %.1f x rtol (bound %g)",
                dal_method_name(o.method), o.rtol, e[0] / o.rtol, e[1] / o.rtol, e[2] / o.rtol, b);
    }
    printf("\n");
  }
  dal_state_destroy(st);
  dal_system_destroy(s);
}

// A tighter request is never worse (issue 31), for every adaptive ODE method: the pendulum
// against the elliptic solution (2.5 rad to t = 20, 1 rad to t = 10), atol = rtol, rtol 1e-6
// ... 1e-14 by decades: the error at a tighter rtol is not above the looser one's unless it is
// within 16 x its own rtol (an adaptive method's error moves within its tolerance band: BS
// went 3.3e-7 -> 5.7e-7 from 1e-6 to 1e-7). Below a method's floor (DOPRI5, Fehlberg 7(8) and
// Adams 1e-12, BS 1e-13, BDF 1e-11: the method rows) the request runs at the floor, with a
// note, and the error is the floor's: before the floors Adams went 4.1e-12 -> 5.3e-12 from
// 1e-12 to 1e-13 here, and on SICM's driven pendulum DOPRI5 and Fehlberg 7(8) grew from 1e-12
// to 1e-13 (issue 31); BDF's clamped runs differed by the rounding of the scaled atol.
static void test_tighter(void) {
  dal_system *s = scn_pendulum(NULL);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(s, &st));
  const dal_method ms[] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_BS,
                           DAL_METHOD_ADAMS, DAL_METHOD_BDF};
  const double th0s[2] = {2.5, 1.0}, Ts[2] = {20.0, 10.0};
  printf("tighter never worse: pendulum error at the end, rtol 1e-6 ... 1e-14\n");
  for (int sc = 0; sc < 2; ++sc)
    for (size_t mi = 0; mi < sizeof ms / sizeof ms[0]; ++mi) {
      printf("  %.1f rad %-10s", th0s[sc], dal_method_name(ms[mi]));
      double prev = INFINITY, prev_rtol = 0;
      const double rs[] = {1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14};
      for (size_t ri = 0; ri < sizeof rs / sizeof rs[0]; ++ri) {
        double r = rs[ri];
        dal_solve_opts o = dal_default_solve_opts();
        o.method = ms[mi];
        o.rtol = o.atol = r;
        o.max_steps = 10000000;
        double q = th0s[sc], qd = 0;
        CHECK_OK(dal_state_set(s, st, 0.0, &q, &qd));
        int rc = dal_advance(s, st, &o, Ts[sc]);
        CHECK_MSG(rc == DAL_OK, "%s at %g: %s", dal_method_name(o.method), r, dal_state_errmsg(st));
        double e = pend_err(th0s[sc], Ts[sc], dal_state_q(st), dal_state_qdot(st));
        printf(" %8.2e", e);
        // never worse than the looser request, unless within 16 x its own rtol (where an
        // adaptive method's error moves within the band of its tolerance)
        CHECK_MSG(e <= fmax(prev, 16.0 * r),
                  "%.1f rad, %s: error %.3g at rtol %g, worse than %.3g at %g and above 16 rtol",
                  th0s[sc], dal_method_name(o.method), e, r, prev, prev_rtol);
        prev = e;
        prev_rtol = r;
      }
      printf("\n");
    }
  dal_state_destroy(st);
  dal_system_destroy(s);
}

static int reads_nothing(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  (void)st;
  (void)ctx;
  return 0;
}

// a run with a monitor against one without (solve.h, dal_evolve): without a monitor evolve is
// dal_advance's run bit for bit; DOPRI5 and Fehlberg 7(8) take the same steps with one;
// Bulirsch-Stoer (dense mode) and CVODE's methods end within the tolerance of it
static void test_monitor_or_not(void) {
  const dal_method ms[] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_BS,
                           DAL_METHOD_ADAMS, DAL_METHOD_BDF};
  const double rtol = 1e-9;
  dal_system *s = scn_pendulum(NULL);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(s, &st));
  for (size_t k = 0; k < sizeof ms / sizeof ms[0]; ++k) {
    double q[3], v[3];
    long steps[3];
    for (int r = 0; r < 3; ++r) {
      double q0 = 2.0, v0 = 0.0;
      CHECK_OK(dal_state_set(s, st, 0.0, &q0, &v0));
      dal_solve_opts o = dal_default_solve_opts();
      o.method = ms[k];
      o.rtol = o.atol = rtol;
      int rc = r == 0   ? dal_advance(s, st, &o, 10.0)
               : r == 1 ? dal_evolve(s, st, &o, 10.0, 0.1, NULL, NULL)
                        : dal_evolve(s, st, &o, 10.0, 0.1, reads_nothing, NULL);
      CHECK_MSG(rc == DAL_OK, "%s run %d: %s", dal_method_name(ms[k]), r, dal_state_errmsg(st));
      q[r] = dal_state_q(st)[0];
      v[r] = dal_state_qdot(st)[0];
      dal_stats sts;
      dal_state_stats(st, &sts);
      steps[r] = sts.steps;
    }
    CHECK_MSG(q[1] == q[0] && v[1] == v[0] && steps[1] == steps[0],
              "%s: evolve without a monitor is not dal_advance's run", dal_method_name(ms[k]));
    int same = ms[k] == DAL_METHOD_DOPRI5 || ms[k] == DAL_METHOD_FEHLBERG78;
    if (same)
      CHECK_MSG(q[2] == q[0] && v[2] == v[0] && steps[2] == steps[0],
                "%s: a monitor changed the steps", dal_method_name(ms[k]));
    else
      CHECK_MSG(fabs(q[2] - q[0]) <= 16 * rtol * (1 + fabs(q[0])),
                "%s: with a monitor %.17g, without %.17g", dal_method_name(ms[k]), q[2], q[0]);
    printf("monitor or not, %-12s steps %ld / %ld, |dq| %.2g\n", dal_method_name(ms[k]), steps[0],
           steps[2], fabs(q[2] - q[0]));
  }
  dal_state_destroy(st);
  dal_system_destroy(s);
}

// A particle driven by the generalized force Q(t) = (6 t - 4, -1.5 t) (unit mass, no gravity)
// moves on the cubics x = t^3 - 2 t^2 + t / 2 + 1, y = -t^3 / 4 + t: DOPRI5 (order 5) and RK4
// (order 4) step exactly to rounding, and the cubic Hermite through y and f at both ends of a
// step is the solution itself, so every output between the steps matches the closed form to
// rounding (a wrong coefficient, a slope from the wrong stage would be off by the step's
// error). With opts.work the outputs are copied into the state, without they are written
// straight into it: both placements are checked.
static int cubic_force(double t, const double *q, const double *qdot, double *Q, void *ctx) {
  (void)q, (void)qdot, (void)ctx;
  Q[0] = 6.0 * t - 4.0;
  Q[1] = -1.5 * t;
  return 0;
}

static int cubic_mon(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  cmp *c = ctx;
  double t = dal_state_time(st);
  const double x[4] = {((t - 2.0) * t + 0.5) * t + 1.0, (-0.25 * t * t + 1.0) * t,
                       (3.0 * t - 4.0) * t + 0.5, -0.75 * t * t + 1.0};
  const double *q = dal_state_q(st), *v = dal_state_qdot(st);
  const double got[4] = {q[0], q[1], v[0], v[1]};
  for (int i = 0; i < 4; ++i)
    c->err = fmax(c->err, fabs(got[i] - x[i]) / (1.0 + fabs(x[i])));
  c->n++;
  return 0;
}

static void test_cubic_exact(void) {
  scn_knobs k = scn_weightless();
  dal_builder *b = NULL;
  int p = -1, rc = scn_builder(&k, 2, &b);
  if (!rc) rc = scn_add_xy(b, "p", 1.0, "x", "y", &p);
  if (!rc) rc = dal_builder_add_genforce(b, cubic_force, NULL);
  dal_system *s = scn_finish(b, rc);
  dal_state *st = NULL;
  CHECK(s && dal_state_create(s, &st) == 0);
  if (!st) {
    dal_system_destroy(s);
    return;
  }
  static const dal_method ms[] = {DAL_METHOD_DOPRI5, DAL_METHOD_RK4};
  for (int mi = 0; mi < 2; ++mi)
    for (int work = 0; work < 2; ++work) {
      double q[2] = {1.0, 0.0}, v[2] = {0.5, 1.0};
      CHECK_OK(dal_state_set(s, st, 0.0, q, v));
      dal_solve_opts o = dal_default_solve_opts();
      o.method = ms[mi];
      o.work = work;
      o.fixed_step = 0.37; // RK4: outputs every 0.01 fall inside its steps
      cmp c = {0, 0, 0, 0};
      CHECK_OK(dal_evolve(s, st, &o, 3.0, 0.01, cubic_mon, &c));
      dal_stats sts;
      dal_state_stats(st, &sts);
      CHECK_MSG(c.n == 301 && c.err < 1e-14,
                "%s (work %d): %d outputs, largest relative deviation from the cubic %.3g",
                dal_method_name(ms[mi]), work, c.n, c.err);
      printf("cubic, %-6s work %d: %ld steps, %d outputs, relative deviation %.2g\n",
             dal_method_name(ms[mi]), work, sts.steps, c.n, c.err);
    }
  dal_state_destroy(st);
  dal_system_destroy(s);
}

int main(void) {
  test_cubic_exact();
  test_adaptive();
  test_fixed();
  test_tight_irregular();
  test_routes();
  test_tighter();
  test_monitor_or_not();
  return check_summary("test_dense");
}
