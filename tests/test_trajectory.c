// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The stored dense trajectory (dal_trajectory): recorded during dal_advance, evaluated after
// the run at 2000 irregular times against the elliptic pendulum (and the Cartesian pendulum in
// IDA) for every adaptive method, printed as a table of worst error / rtol, with the distance
// to the method's own dense output at the same times (dal_evolve_at); the recorded run's end
// state is dal_evolve's bit for bit and the trajectory ends on it; a run stopped by a terminal
// event ends the record there and the next run continues it; the refusals name span and t.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "ref_elliptic.h"
#include "scenes.h"

#define TH0 2.0
#define NE 2000

static double times[NE];

// the closed form's error at t of (q, qdot) (minimal: theta; Cartesian: x, y)
static double ref_err(int cart, double t, const double *q, const double *v) {
  return ref_pendulum_error(TH0, sqrt(SCN_G), cart, t, q, v);
}

static void start(const dal_system *s, dal_state *st, int cart) {
  double q[2], v[2];
  ref_pendulum_start(TH0, cart, q, v);
  CHECK_OK(dal_state_set(s, st, 0.0, q, v));
}

// the dense output at the listed times, compared with the trajectory there
typedef struct dense_cmp {
  dal_trajectory *tr;
  int n;
  double diff;   // worst |trajectory - dense output| over q and qdot / w0
  double *seen;  // the outputs' (q, qdot) (2n each), kept by a first run ...
  int compare;   // ... and compared bit for bit by a second one
  int different; // outputs of the second run that differ
} dense_cmp;

static int dense_mon(const dal_system *sys, const dal_state *st, void *ctx) {
  dense_cmp *c = ctx;
  int n = dal_system_ncoords(sys);
  double q[2], v[2];
  double *seen = c->seen + (size_t)c->n * 2 * (size_t)n;
  if (c->compare) {
    c->different += memcmp(seen, dal_state_q(st), (size_t)n * sizeof(double)) != 0 ||
                    memcmp(seen + n, dal_state_qdot(st), (size_t)n * sizeof(double)) != 0;
    c->n++;
    return 0;
  }
  memcpy(seen, dal_state_q(st), (size_t)n * sizeof(double));
  memcpy(seen + n, dal_state_qdot(st), (size_t)n * sizeof(double));
  if (dal_trajectory_eval(c->tr, dal_state_time(st), q, v)) return -1;
  for (int i = 0; i < n; ++i)
    c->diff = fmax(c->diff, fmax(fabs(q[i] - dal_state_q(st)[i]),
                                 fabs(v[i] - dal_state_qdot(st)[i]) / sqrt(SCN_G)));
  c->n++;
  return 0;
}

// one row of the table: record dal_advance over [0, 10], evaluate, compare
static void row(const dal_system *s, dal_state *st, int cart, dal_method m, double rtol) {
  dal_solve_opts o = dal_default_solve_opts();
  o.method = m;
  if (rtol > 0) o.rtol = rtol;
  o.fixed_step = 0.01; // RK4 and the symplectic methods (rtol 0 in the table)
  int n = dal_system_ncoords(s);
  dal_trajectory *tr = NULL;
  CHECK_OK(dal_trajectory_create(s, &tr));
  start(s, st, cart);
  CHECK_OK(dal_state_set_trajectory(st, tr));
  int rc = dal_advance(s, st, &o, 10.0);
  CHECK_MSG(rc == DAL_OK, "%s: %s", dal_method_name(m), dal_state_errmsg(st));
  CHECK_OK(dal_state_set_trajectory(st, NULL));
  double qe[2], ve[2], q[2], v[2], t0 = 0, t1 = 0;
  memcpy(qe, dal_state_q(st), (size_t)n * sizeof(double));
  memcpy(ve, dal_state_qdot(st), (size_t)n * sizeof(double));
  long steps = dal_trajectory_span(tr, &t0, &t1);
  CHECK(steps > 0 && t0 == 0.0 && t1 == 10.0);
  // the trajectory ends on the end state, bit for bit
  CHECK_OK(dal_trajectory_eval(tr, 10.0, q, v));
  CHECK_MSG(memcmp(q, qe, (size_t)n * sizeof(double)) == 0 &&
                memcmp(v, ve, (size_t)n * sizeof(double)) == 0,
            "%s: the trajectory's end is not the end state", dal_method_name(m));
  // against the closed form at irregular times
  double worst = 0;
  for (int i = 0; i < NE; ++i) {
    CHECK_OK(dal_trajectory_eval(tr, times[i], q, v));
    worst = fmax(worst, ref_err(cart, times[i], q, v));
  }
  // the same steps without recording: dal_evolve_at with a monitor (dense output) ends on the
  // same state bit for bit, and its outputs are what the trajectory interpolates
  static double seen[NE * 4];
  dense_cmp dc = {tr, 0, 0, seen, 0, 0};
  start(s, st, cart);
  CHECK_OK(dal_evolve_at(s, st, &o, times, NE, dense_mon, &dc));
  CHECK_MSG(memcmp(dal_state_q(st), qe, (size_t)n * sizeof(double)) == 0 &&
                memcmp(dal_state_qdot(st), ve, (size_t)n * sizeof(double)) == 0,
            "%s: the recorded run's end state differs from dal_evolve_at's", dal_method_name(m));
  CHECK(dc.n == NE);
  // recording does not change the outputs either: the same run recorded, bit for bit
  dal_trajectory *tr2 = NULL;
  dense_cmp d2 = {NULL, 0, 0, seen, 1, 0};
  CHECK_OK(dal_trajectory_create(s, &tr2));
  start(s, st, cart);
  CHECK_OK(dal_state_set_trajectory(st, tr2));
  CHECK_OK(dal_evolve_at(s, st, &o, times, NE, dense_mon, &d2));
  CHECK_OK(dal_state_set_trajectory(st, NULL));
  CHECK_MSG(d2.n == NE && d2.different == 0, "%s: %d of %d outputs change when recorded",
            dal_method_name(m), d2.different, d2.n);
  CHECK(memcmp(dal_state_q(st), qe, (size_t)n * sizeof(double)) == 0);
  dal_trajectory_destroy(tr2);
  size_t bytes = (size_t)steps * (3 + 18 * (size_t)n) * sizeof(double);
  if (rtol > 0)
    printf("| %-12s | %-4s | %5.0e | %6ld | %9.2f | %9.2e | %8zu |\n", dal_method_name(m),
           cart ? "cart" : "min", rtol, steps, worst / rtol, dc.diff, bytes);
  else // fixed step h = 0.01: the error itself
    printf("| %-12s | %-4s | h=.01 | %6ld | %9.2e | %9.2e | %8zu |\n", dal_method_name(m),
           cart ? "cart" : "min", steps, worst, dc.diff, bytes);
  if (rtol > 0)
    CHECK_MSG(worst <= 16 * rtol, "%s at %g: %.3g x rtol", dal_method_name(m), rtol, worst / rtol);
  // a polynomial interpolant of degree <= 8 is reproduced to rounding (solve.h)
  if (m == DAL_METHOD_DOPRI5 || m == DAL_METHOD_BDF || m == DAL_METHOD_RK4)
    CHECK_MSG(dc.diff <= 1e-13, "%s: %.3g from its dense output", dal_method_name(m), dc.diff);
  dal_trajectory_destroy(tr);
}

// a terminal event stops the recorded run inside a step: the record ends there; the next run
// continues it; a run from elsewhere is refused; evaluation outside the span names it
static double theta_zero(double t, const double *q, const double *qdot, void *ctx) {
  (void)t;
  (void)qdot;
  (void)ctx;
  return q[0];
}

static void stops_and_refusals(const dal_system *s, dal_state *st) {
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-9;
  dal_trajectory *tr = NULL;
  dal_events *ev = NULL;
  CHECK_OK(dal_trajectory_create(s, &tr));
  CHECK_OK(dal_events_create(s, &ev));
  dal_event_def ed = dal_default_event_def();
  ed.name = "bottom";
  ed.g = theta_zero;
  ed.terminal = 1;
  CHECK_OK(dal_events_add(ev, &ed));
  double q[1], v[1], t0, t1;
  // empty
  CHECK(dal_trajectory_eval(tr, 0.0, q, v) == DAL_E_ARG &&
        strstr(dal_trajectory_errmsg(tr), "empty") != NULL);
  CHECK(dal_trajectory_span(tr, &t0, &t1) == 0 && isnan(t0));
  start(s, st, 0);
  CHECK_OK(dal_state_set_trajectory(st, tr));
  CHECK_OK(dal_state_set_events(st, ev));
  CHECK(dal_advance(s, st, &o, 10.0) == DAL_EVENT);
  double te = dal_state_time(st);
  // a quarter period of the elliptic pendulum: K(k) / w0
  double Kq = ref_ellip_K(sin(0.5 * TH0) * sin(0.5 * TH0)) / sqrt(SCN_G);
  CHECK_CLOSE(te, Kq, 1e-8);
  CHECK(dal_trajectory_span(tr, &t0, &t1) > 0 && t0 == 0.0 && t1 == te);
  CHECK_OK(dal_trajectory_eval(tr, te, q, v));
  CHECK(fabs(q[0]) <= 1e-8);
  // beyond the stop: refused, naming span and t
  CHECK(dal_trajectory_eval(tr, te + 0.01, q, v) == DAL_E_ARG);
  char want[64];
  snprintf(want, sizeof want, "%.17g", te);
  CHECK(strstr(dal_trajectory_errmsg(tr), want) != NULL &&
        strstr(dal_trajectory_errmsg(tr), "outside the recorded span") != NULL);
  CHECK(dal_trajectory_eval(tr, -1.0, q, v) == DAL_E_ARG);
  CHECK(dal_trajectory_eval(tr, NAN, q, v) == DAL_E_NONFINITE);
  // the next run continues the record (the event no longer terminal)
  CHECK_OK(dal_state_set_events(st, NULL));
  CHECK_OK(dal_advance(s, st, &o, 3.0));
  CHECK(dal_trajectory_span(tr, &t0, &t1) > 0 && t1 == 3.0);
  double worst = 0;
  for (int i = 0; i < NE; ++i) {
    double t = 3.0 * i / (NE - 1);
    if (dal_trajectory_eval(tr, t, q, v)) {
      CHECK_MSG(0, "%s", dal_trajectory_errmsg(tr));
      break;
    }
    worst = fmax(worst, ref_err(0, t, q, v));
  }
  printf("stopped by an event at t = %.6f, continued to 3: worst error %.2f x rtol\n", te,
         worst / o.rtol);
  CHECK(worst <= 16 * o.rtol);
  // a run from another time is refused (the state untouched)
  start(s, st, 0);
  CHECK(dal_advance(s, st, &o, 1.0) == DAL_E_ARG && dal_state_time(st) == 0.0 &&
        strstr(dal_state_errmsg(st), "trajectory ends at t=3") != NULL);
  // a trajectory of another system cannot be attached
  dal_system *c = scn_cart_pendulum(NULL);
  dal_trajectory *tc = NULL;
  CHECK_OK(dal_trajectory_create(c, &tc));
  CHECK(dal_state_set_trajectory(st, tc) == DAL_E_STATE);
  CHECK_OK(dal_state_set_trajectory(st, NULL));
  dal_trajectory_destroy(tc);
  dal_system_destroy(c);
  dal_events_destroy(ev);
  dal_trajectory_destroy(tr);
}

// AUTO picks for a recorded run what it picks for a plain dal_advance since issue 31 (one rule,
// solve.h): Bulirsch-Stoer on n >= 3 at rtol 1e-6 either way
static void auto_rule(void) {
  scn_knobs k = scn_default();
  k.N = 3;
  dal_system *s = scn_chain(&k);
  dal_state *st = NULL;
  dal_trajectory *tr = NULL;
  CHECK_OK(dal_state_create(s, &st));
  CHECK_OK(dal_trajectory_create(s, &tr));
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-6;
  double q[3] = {0.5, 0.2, -0.1}, v[3] = {0, 0, 0};
  dal_stats sp, sr;
  CHECK_OK(dal_state_set(s, st, 0.0, q, v));
  CHECK_OK(dal_advance(s, st, &o, 1.0));
  CHECK_OK(dal_state_stats(st, &sp));
  CHECK_OK(dal_state_set(s, st, 0.0, q, v));
  CHECK_OK(dal_state_set_trajectory(st, tr));
  CHECK_OK(dal_advance(s, st, &o, 1.0));
  CHECK_OK(dal_state_stats(st, &sr));
  CHECK(sp.method_used == DAL_METHOD_BS && sr.method_used == DAL_METHOD_BS);
  CHECK_OK(dal_state_set_trajectory(st, NULL));
  dal_trajectory_destroy(tr);
  dal_state_destroy(st);
  dal_system_destroy(s);
}

int main(void) {
  dal_system *s = scn_pendulum(NULL), *c = scn_cart_pendulum(NULL);
  dal_state *st, *sc;
  CHECK(s && c);
  if (!s || !c) return 1;
  CHECK_OK(dal_state_create(s, &st));
  CHECK_OK(dal_state_create(c, &sc));
  unsigned long long seed = 19;
  for (int i = 0; i < NE; ++i)
    times[i] = check_rand(&seed, 0.0, 10.0);
  for (int i = 1; i < NE; ++i) // sorted (dal_evolve_at needs them so)
    for (int j = i; j > 0 && times[j] < times[j - 1]; --j) {
      double x = times[j];
      times[j] = times[j - 1];
      times[j - 1] = x;
    }
  times[NE - 1] = 10.0;
  printf("stored trajectory vs the elliptic pendulum (2 rad) at %d times in [0, 10]:\n", NE);
  printf("| method       | q    | rtol  | records | err/rtol | vs dense  | bytes    |\n");
  const dal_method ms[] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_BS,
                           DAL_METHOD_ADAMS, DAL_METHOD_BDF};
  for (int i = 0; i < 5; ++i) {
    row(s, st, 0, ms[i], 1e-6);
    row(s, st, 0, ms[i], 1e-9);
  }
  row(s, st, 0, DAL_METHOD_BS, 1e-12);
  row(s, st, 0, DAL_METHOD_ADAMS, 1e-12);
  row(s, st, 0, DAL_METHOD_RK4, 0);
  row(s, st, 0, DAL_METHOD_VARIATIONAL4, 0);
  row(c, sc, 1, DAL_METHOD_RATTLE4, 0);
  row(c, sc, 1, DAL_METHOD_BDF, 1e-6);
  row(c, sc, 1, DAL_METHOD_BDF, 1e-8);
  stops_and_refusals(s, st);
  auto_rule();
  dal_state_destroy(st);
  dal_state_destroy(sc);
  dal_system_destroy(s);
  dal_system_destroy(c);
  return check_summary("test_trajectory");
}
