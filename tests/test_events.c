// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Events against closed forms: the pendulum's period from its zero crossings, the bead's
// turning points from the Jacobi integral, a particle leaving a circle (reaction and
// multiplier events), terminal stops and restarts, and events fed by every method.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "ref_elliptic.h"
#include "scenes.h"

#define G0 SCN_G

// the standard scenes at a given length (radius) and turning rate
static dal_system *pendulum(double l) {
  scn_knobs k = scn_default();
  k.l = l;
  return scn_pendulum(&k);
}
static dal_system *cart_pendulum(double l) {
  scn_knobs k = scn_default();
  k.l = l;
  return scn_cart_pendulum(&k);
}
static dal_system *bead(double R, double w) {
  scn_knobs k = scn_default();
  k.R = R;
  k.spin = w;
  return scn_bead(&k);
}
#define PI 3.14159265358979323846

static double g_q0(double t, const double *q, const double *qd, void *ctx) {
  (void)t;
  (void)qd;
  (void)ctx;
  return q[0];
}
static double g_qd0(double t, const double *q, const double *qd, void *ctx) {
  (void)t;
  (void)q;
  (void)ctx;
  return qd[0];
}

// the events of s with the one event d (its index 0), watched by the state st
static dal_events *one_event(const dal_system *s, dal_state *st, const dal_event_def *d) {
  dal_events *ev = NULL;
  CHECK_OK(dal_events_create(s, &ev));
  CHECK(dal_events_add(ev, d) == 0);
  CHECK_OK(dal_state_set_events(st, ev));
  return ev;
}

// 1. the period from successive upward zero crossings against 4 K(m) / w0, m = sin^2(th0/2)
static void test_period(void) {
  const double l = 1.0, th0 = 2.0, w0 = sqrt(G0 / l);
  const double T = 4.0 * ref_ellip_K(sin(0.5 * th0) * sin(0.5 * th0)) / w0;
  dal_system *s = pendulum(l);
  dal_state *st = NULL;
  dal_events *ev = NULL;
  CHECK_OK(dal_state_create(s, &st));
  dal_event_def d = dal_default_event_def();
  d.name = "theta=0 upwards";
  d.g = g_q0;
  d.direction = DAL_EVENT_RISING;
  ev = one_event(s, st, &d);
  const struct {
    dal_method m;
    double rtol, bound; // bound on |T_measured - T| / T
  } cases[] = {
      {DAL_METHOD_AUTO, 1e-12, 1e-12}, // Adams at 1e-12 (AUTO's rule)
      {DAL_METHOD_BS, 1e-12, 1e-12},         {DAL_METHOD_DOPRI5, 1e-12, 1e-12},
      {DAL_METHOD_FEHLBERG78, 1e-12, 1e-12}, {DAL_METHOD_AUTO, 1e-8, 2e-8},
  };
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
    double q = th0, qd = 0.0;
    CHECK_OK(dal_state_set(s, st, 0.0, &q, &qd));
    dal_events_clear(ev);
    dal_solve_opts o = dal_default_solve_opts();
    o.method = cases[c].m;
    o.rtol = cases[c].rtol;
    CHECK_OK(dal_advance(s, st, &o, 5.2 * T));
    long n = dal_events_count(ev);
    CHECK_MSG(n == 5, "%ld crossings in 5.2 periods", n);
    double worst = 0.0, first = 0;
    for (long i = 0; i < n; ++i) {
      dal_event_record r;
      double qq, qv;
      CHECK_OK(dal_events_get(ev, i, &r, &qq, &qv));
      CHECK(r.event == 0 && r.direction == 1 && qv > 0);
      // the state logged at the crossing is on the crossing: |theta| ~ |theta'| dt
      CHECK_MSG(fabs(qq) < 1e-9, "theta at the crossing %g", qq);
      if (i == 0) {
        first = r.t;
        CHECK_CLOSE(r.t, 0.75 * T, 10 * cases[c].bound); // the first upward pass: 3T/4
      } else {
        worst = fmax(worst, fabs((r.t - first) / i - T) / T);
      }
    }
    dal_stats sts;
    CHECK_OK(dal_state_stats(st, &sts));
    printf("  period from crossings, %-10s rtol %.0e: relative error %.2e (%ld steps)\n",
           dal_method_name(o.method), o.rtol, worst, sts.steps);
    CHECK_MSG(worst <= cases[c].bound, "%s at %g: period error %.3g", dal_method_name(o.method),
              o.rtol, worst);
  }
  dal_state_set_events(st, NULL);
  dal_events_destroy(ev);
  dal_state_destroy(st);
  dal_system_destroy(s);
}

// 2. the bead's turning points (theta' = 0) against the Jacobi integral's prediction
static void test_bead_turning(void) {
  const double R = 0.5, w = 6.0; // above the critical rate sqrt(g/R) = 4.43: off-axis minimum
  dal_system *s = bead(R, w);
  dal_state *st = NULL;
  dal_events *ev = NULL;
  CHECK_OK(dal_state_create(s, &st));
  dal_event_def d = dal_default_event_def();
  d.name = "turn";
  d.g = g_qd0;
  ev = one_event(s, st, &d);
  double q = 0.2, qd = 0.0; // released at 0.2 rad: it swings through the off-axis minimum
  CHECK_OK(dal_state_set(s, st, 0.0, &q, &qd));
  // Jacobi integral per unit mass: h = R^2 th'^2 / 2 - R^2 w^2 sin^2 th / 2 - g R cos th, so
  // at a turning point c = cos th solves (R^2 w^2 / 2) c^2 - g R c - R^2 w^2 / 2 - h = 0
  double A = 0.5 * R * R * w * w, h = -A * sin(q) * sin(q) - G0 * R * cos(q);
  double disc = G0 * G0 * R * R + 4.0 * A * (A + h);
  double c1 = (G0 * R + sqrt(disc)) / (2.0 * A), c2 = (G0 * R - sqrt(disc)) / (2.0 * A);
  double th_a = acos(fmin(c1, 1.0)), th_b = acos(c2); // the two turning angles (th_a = 0.2)
  CHECK_CLOSE(th_a, 0.2, 1e-12);
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-10;
  CHECK_OK(dal_advance(s, st, &o, 10.0));
  long n = dal_events_count(ev);
  CHECK_MSG(n >= 10, "%ld turning points", n);
  double worst = 0.0;
  for (long i = 0; i < n; ++i) {
    dal_event_record r;
    double qq, qv;
    CHECK_OK(dal_events_get(ev, i, &r, &qq, &qv));
    // alternately the far side (th_b, where theta' turns from + to -) and the near side
    double want = i % 2 == 0 ? th_b : th_a;
    CHECK(r.direction == (i % 2 == 0 ? -1 : 1));
    worst = fmax(worst, fabs(qq - want));
  }
  printf("  bead turning points: %ld, worst |theta - Jacobi prediction| %.2e rad (%.3f, %.3f)\n", n,
         worst, th_a, th_b);
  // at a turning point theta is quadratic in time: an error eps in t moves it by ~theta'' eps^2
  CHECK_MSG(worst < 1e-8, "turning points off by %g", worst);
  dal_state_set_events(st, NULL);
  dal_events_destroy(ev);
  dal_state_destroy(st);
  dal_system_destroy(s);
}

// radial component of the reaction on the particle (outward from the centre)
static double g_reaction(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  (void)ctx;
  const double *N = dal_state_reactions(st), *r = dal_state_positions(st);
  if (!N || !r) return NAN;
  return (N[0] * r[0] + N[1] * r[1]) / hypot(r[0], r[1]);
}

// 3. a particle sliding off the top of a circle leaves it where the reaction vanishes:
//    cos(phi) = (2 + v0^2 / (g R)) / 3, phi from the top (energy and the radial equation)
static void test_leaving_circle(void) {
  const double R = 1.0, v0 = 0.5;
  const double phi_ref = acos((2.0 + v0 * v0 / (G0 * R)) / 3.0);
  // minimal coordinates: the pendulum map's reaction (theta = pi at the top)
  dal_system *s = pendulum(R);
  dal_state *st = NULL;
  dal_events *ev = NULL;
  CHECK_OK(dal_state_create(s, &st));
  dal_event_def d = dal_default_event_def();
  d.name = "leaves the circle";
  d.g_state = g_reaction;
  d.direction = DAL_EVENT_FALLING;
  d.terminal = 1;
  ev = one_event(s, st, &d);
  double q = PI, qd = v0 / R;
  CHECK_OK(dal_state_set(s, st, 0.0, &q, &qd));
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-10;
  int rc = dal_advance(s, st, &o, 5.0);
  CHECK_MSG(rc == DAL_EVENT, "status %s: %s", dal_status_name(rc), dal_state_errmsg(st));
  CHECK(strstr(dal_state_errmsg(st), "leaves the circle") != NULL);
  double phi = dal_state_q(st)[0] - PI;
  printf("  leaves the circle (minimal, reaction event) at phi = %.12f, closed form %.12f\n", phi,
         phi_ref);
  CHECK_CLOSE(phi, phi_ref, 1e-8);
  // the state is delivered evaluated at the event: the reaction there is zero to rounding
  CHECK(fabs(g_reaction(s, st, NULL)) < 1e-6 * G0);
  CHECK(dal_events_count(ev) == 1);
  // continuing does not find the same crossing again (the reaction stays negative after it)
  double t_event = dal_state_time(st);
  rc = dal_advance(s, st, &o, t_event + 0.01);
  CHECK_MSG(rc == DAL_OK, "restart: %s", dal_state_errmsg(st));
  CHECK(dal_events_count(ev) == 1);
  dal_state_set_events(st, NULL);
  dal_events_destroy(ev);
  dal_state_destroy(st);
  dal_system_destroy(s);

  // Cartesian coordinates in GGL (IDA): the rod's multiplier changes sign there
  s = cart_pendulum(R);
  CHECK_OK(dal_state_create(s, &st));
  d = dal_default_event_def();
  d.name = "rod slack";
  d.constraint = "rod";
  d.terminal = 1;
  ev = one_event(s, st, &d);
  const dal_formulation forms[2] = {DAL_FORM_GGL, DAL_FORM_INDEX1};
  for (int f = 0; f < 2; ++f) {
    double x[2] = {0.0, R}, v[2] = {v0, 0.0};
    CHECK_OK(dal_state_set(s, st, 0.0, x, v));
    dal_events_clear(ev);
    o = dal_default_solve_opts();
    o.form = forms[f];
    o.project = 1;
    o.rtol = 1e-9;
    rc = dal_advance(s, st, &o, 5.0);
    CHECK_MSG(rc == DAL_EVENT, "%s: status %s: %s", dal_formulation_name(forms[f]),
              dal_status_name(rc), dal_state_errmsg(st));
    const double *r = dal_state_positions(st);
    double phi_c = atan2(r[0], r[1]);
    printf("  leaves the circle (Cartesian %s, multiplier event) at phi = %.12f\n",
           dal_formulation_name(forms[f]), phi_c);
    CHECK_CLOSE(phi_c, phi_ref, 1e-7);
    CHECK(fabs(dal_state_lambda(st)[0]) < 1e-6 * G0);
  }
  dal_state_set_events(st, NULL);
  dal_events_destroy(ev);
  dal_state_destroy(st);
  dal_system_destroy(s);
}

typedef struct count_ctx {
  int calls;
  double tlast;
} count_ctx;
static int mon_count(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  count_ctx *c = ctx;
  c->calls++;
  c->tlast = dal_state_time(st);
  return 0;
}

// 4. events with every method and in evolve: same crossings, monitor order kept, a terminal
//    event ends evolve with DAL_EVENT and the state there
static void test_every_method(void) {
  const double l = 1.0, th0 = 1.0, w0 = sqrt(G0 / l);
  const double T = 4.0 * ref_ellip_K(sin(0.5 * th0) * sin(0.5 * th0)) / w0;
  dal_system *s = pendulum(l);
  dal_state *st = NULL;
  dal_events *ev = NULL;
  CHECK_OK(dal_state_create(s, &st));
  CHECK_OK(dal_events_create(s, &ev));
  dal_event_def d = dal_default_event_def();
  d.g = g_q0;
  d.name = "down";
  d.direction = DAL_EVENT_FALLING;
  CHECK(dal_events_add(ev, &d) == 0);
  d.name = "third up";
  d.direction = DAL_EVENT_RISING;
  CHECK(dal_events_add(ev, &d) == 1);
  CHECK_OK(dal_state_set_events(st, ev));
  const dal_method ms[] = {
      DAL_METHOD_DOPRI5,      DAL_METHOD_FEHLBERG78,   DAL_METHOD_BS,
      DAL_METHOD_RK4,         DAL_METHOD_ADAMS,        DAL_METHOD_BDF,
      DAL_METHOD_VARIATIONAL, DAL_METHOD_VARIATIONAL4, DAL_METHOD_VARIATIONAL6};
  for (size_t k = 0; k < sizeof ms / sizeof ms[0]; ++k) {
    double q = th0, qd = 0.0;
    CHECK_OK(dal_state_set(s, st, 0.0, &q, &qd));
    dal_events_clear(ev);
    dal_solve_opts o = dal_default_solve_opts();
    o.method = ms[k];
    o.rtol = 1e-9;
    o.fixed_step = 1e-3;
    count_ctx cc = {0, 0};
    int rc = dal_evolve(s, st, &o, 3.0 * T, 0.1, mon_count, &cc);
    CHECK_MSG(rc == DAL_OK, "%s: %s", dal_method_name(ms[k]), dal_state_errmsg(st));
    CHECK(cc.calls == (int)floor(3.0 * T / 0.1) + 2 && cc.tlast == 3.0 * T);
    // falling crossings at T/4, 5T/4, 9T/4; rising at 3T/4, 7T/4, 11T/4
    long n = dal_events_count(ev);
    CHECK_MSG(n == 6, "%s: %ld events", dal_method_name(ms[k]), n);
    double worst = 0;
    for (long i = 0; i < n; ++i) {
      dal_event_record r;
      CHECK_OK(dal_events_get(ev, i, &r, NULL, NULL));
      CHECK(r.event == (int)(i % 2) && r.direction == (i % 2 ? 1 : -1));
      worst = fmax(worst, fabs(r.t - (0.25 + 0.5 * (double)i) * T));
    }
    // the order-2 variational method at h = 1e-3 has its own phase error, about
    // t (h w0)^2 / 24 = 2.4e-6 s at t = 6 (the others' errors at this h are below 1e-10 s)
    double bound = ms[k] == DAL_METHOD_VARIATIONAL ? 1e-5 : 1e-7;
    printf("  %-12s: 6 crossings, worst time error %.2e s\n", dal_method_name(ms[k]), worst);
    CHECK_MSG(worst < bound, "%s: crossing times off by %g", dal_method_name(ms[k]), worst);
    // a terminal event inside evolve: stops there; the monitor saw only earlier times
    dal_events_destroy(ev);
    d.name = "stop";
    d.direction = DAL_EVENT_RISING;
    d.terminal = 1;
    ev = one_event(s, st, &d);
    CHECK_OK(dal_state_set(s, st, 0.0, &q, &qd));
    cc.calls = 0;
    rc = dal_evolve(s, st, &o, 3.0 * T, 0.1, mon_count, &cc);
    CHECK_MSG(rc == DAL_EVENT, "%s: %s", dal_method_name(ms[k]), dal_status_name(rc));
    CHECK(fabs(dal_state_time(st) - 0.75 * T) < bound && cc.tlast < dal_state_time(st));
    CHECK(dal_state_qddot(st) != NULL); // evaluated there
    // rebuild the two-event set for the next method
    dal_events_destroy(ev);
    CHECK_OK(dal_events_create(s, &ev));
    d.terminal = 0;
    d.name = "down";
    d.direction = DAL_EVENT_FALLING;
    CHECK(dal_events_add(ev, &d) == 0);
    d.name = "third up";
    d.direction = DAL_EVENT_RISING;
    CHECK(dal_events_add(ev, &d) == 1);
    CHECK_OK(dal_state_set_events(st, ev));
  }
  dal_state_set_events(st, NULL);
  dal_events_destroy(ev);
  dal_state_destroy(st);
  dal_system_destroy(s);
}

static double g_nan(double t, const double *q, const double *qd, void *ctx) {
  (void)q;
  (void)qd;
  (void)ctx;
  return t > 0.5 ? NAN : 1.0;
}

// 5. a failing event function stops the run with DAL_E_CALLBACK naming it; a section to CSV
static void test_failures_and_csv(void) {
  dal_system *s = scn_pendulum(NULL);
  dal_state *st = NULL;
  dal_events *ev = NULL;
  CHECK_OK(dal_state_create(s, &st));
  dal_event_def d = dal_default_event_def();
  d.name = "broken";
  d.g = g_nan;
  ev = one_event(s, st, &d);
  double q = 1.0, qd = 0.0;
  CHECK_OK(dal_state_set(s, st, 0.0, &q, &qd));
  dal_solve_opts o = dal_default_solve_opts();
  int rc = dal_advance(s, st, &o, 2.0);
  CHECK(rc == DAL_E_CALLBACK && strstr(dal_state_errmsg(st), "'broken'") != NULL);
  CHECK(dal_state_time(st) > 0.5 && dal_state_time(st) < 2.0 && dal_state_qddot(st) != NULL);
  dal_events_destroy(ev);
  // a surface section written to CSV: one header, one row per crossing
  d = dal_default_event_def();
  d.name = "section";
  d.g = g_q0;
  d.direction = DAL_EVENT_RISING;
  ev = one_event(s, st, &d);
  CHECK_OK(dal_state_set(s, st, 0.0, &q, &qd));
  CHECK_OK(dal_advance(s, st, &o, 20.0));
  FILE *fp = tmpfile();
  CHECK(fp != NULL);
  if (fp) {
    CHECK_OK(dal_events_write_csv(ev, fp, -1, 1));
    rewind(fp);
    char line[512];
    int rows = 0;
    while (fgets(line, sizeof line, fp))
      ++rows;
    CHECK(rows == 1 + (int)dal_events_count(ev) && rows > 5);
    fclose(fp);
  }
  dal_state_set_events(st, NULL);
  dal_events_destroy(ev);
  dal_state_destroy(st);
  dal_system_destroy(s);
}

int main(void) {
  test_period();
  test_bead_turning();
  test_leaving_circle();
  test_every_method();
  test_failures_and_csv();
  return check_summary("test_events");
}
