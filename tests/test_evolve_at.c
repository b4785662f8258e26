// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// dal_evolve_at (a list of output times, solve_ivp's t_eval): the states at irregular times
// against the elliptic pendulum (and the Cartesian pendulum in IDA) for every adaptive method;
// the list does not change the steps (end state, statistics and the states at shared times
// bit for bit equal for different lists and for dal_evolve's grid); bad lists are refused
// naming the index, before any step.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "ref_elliptic.h"
#include "scenes.h"

#define TH0 2.0
#define NT 300
#define NREC 400

// what the monitor saw
typedef struct rec {
  int cart, n;
  double t[NREC], q[NREC][2], v[NREC][2];
  double err; // worst deviation from the closed form (rad, and rad / w0 for rates)
} rec;

static int mon(const dal_system *sys, const dal_state *st, void *ctx) {
  rec *r = ctx;
  int n = dal_system_ncoords(sys);
  if (r->n >= NREC) return -1;
  const double *q = dal_state_q(st), *v = dal_state_qdot(st);
  double t = dal_state_time(st);
  r->t[r->n] = t;
  for (int i = 0; i < n; ++i) {
    r->q[r->n][i] = q[i];
    r->v[r->n][i] = v[i];
  }
  r->n++;
  r->err = fmax(r->err, ref_pendulum_error(TH0, sqrt(SCN_G), r->cart, t, q, v));
  return 0;
}

static void start(const dal_system *s, dal_state *st, int cart) {
  double q[2], v[2];
  ref_pendulum_start(TH0, cart, q, v);
  CHECK_OK(dal_state_set(s, st, 0.0, q, v));
}

// irregular sorted times in [0, 10]: a few duplicates, the start and the end included
static void make_times(double *t, int n, unsigned long long seed) {
  for (int i = 0; i < n; ++i)
    t[i] = check_rand(&seed, 0.0, 10.0);
  for (int i = 1; i < n; ++i) // insertion sort
    for (int j = i; j > 0 && t[j] < t[j - 1]; --j) {
      double x = t[j];
      t[j] = t[j - 1];
      t[j - 1] = x;
    }
  t[0] = 0.0;
  t[7] = t[6]; // a duplicate: served twice
  t[n - 1] = 10.0;
}

// a method against the closed form at the listed times, and the bit-identity of its steps
static void method_row(const dal_system *s, dal_state *st, int cart, dal_method m, double rtol) {
  dal_solve_opts o = dal_default_solve_opts();
  o.method = m;
  o.rtol = rtol;
  static double ta[NT], tb[NT / 3];
  make_times(ta, NT, 7);
  // list b: every third time of list a (shared times), ending at 10 as well
  for (int i = 0; i < NT / 3; ++i)
    tb[i] = ta[3 * i];
  tb[NT / 3 - 1] = 10.0;
  static rec ra, rb, rg;
  memset(&ra, 0, sizeof ra);
  memset(&rb, 0, sizeof rb);
  memset(&rg, 0, sizeof rg);
  ra.cart = rb.cart = rg.cart = cart;
  dal_stats sa, sb, sg;
  double qa[2], qb[2], qg[2], va[2], vb[2], vg[2];
  int n = dal_system_ncoords(s);

  start(s, st, cart);
  int rc = dal_evolve_at(s, st, &o, ta, NT, mon, &ra);
  CHECK_MSG(rc == DAL_OK, "%s: %s", dal_method_name(m), dal_state_errmsg(st));
  dal_state_stats(st, &sa);
  memcpy(qa, dal_state_q(st), (size_t)n * sizeof(double));
  memcpy(va, dal_state_qdot(st), (size_t)n * sizeof(double));

  start(s, st, cart);
  CHECK_OK(dal_evolve_at(s, st, &o, tb, NT / 3, mon, &rb));
  dal_state_stats(st, &sb);
  memcpy(qb, dal_state_q(st), (size_t)n * sizeof(double));
  memcpy(vb, dal_state_qdot(st), (size_t)n * sizeof(double));

  start(s, st, cart);
  CHECK_OK(dal_evolve(s, st, &o, 10.0, 0.37, mon, &rg));
  dal_state_stats(st, &sg);
  memcpy(qg, dal_state_q(st), (size_t)n * sizeof(double));
  memcpy(vg, dal_state_qdot(st), (size_t)n * sizeof(double));

  // every listed time served once, at exactly that time
  CHECK_MSG(ra.n == NT && rb.n == NT / 3, "%s: %d and %d outputs", dal_method_name(m), ra.n, rb.n);
  int exact = 1;
  for (int i = 0; i < ra.n && i < NT; ++i)
    exact &= ra.t[i] == ta[i];
  CHECK_MSG(exact, "%s: an output at another time than listed", dal_method_name(m));
  // the same steps whatever the outputs (bit for bit)
  CHECK_MSG(memcmp(qa, qb, (size_t)n * sizeof(double)) == 0 &&
                memcmp(va, vb, (size_t)n * sizeof(double)) == 0 &&
                memcmp(qa, qg, (size_t)n * sizeof(double)) == 0 &&
                memcmp(va, vg, (size_t)n * sizeof(double)) == 0,
            "%s: end states differ between output lists", dal_method_name(m));
  // (the right-hand sides differ: a dense output may evaluate some, Fehlberg's partial step)
  CHECK_MSG(sa.steps == sb.steps && sa.steps == sg.steps && sa.rejected == sb.rejected &&
                sa.rejected == sg.rejected && sa.last_h == sg.last_h,
            "%s: steps %ld / %ld / %ld, rejected %ld / %ld / %ld", dal_method_name(m), sa.steps,
            sb.steps, sg.steps, sa.rejected, sb.rejected, sg.rejected);
  // the states at the shared times are the same numbers (the same interpolant of the same step)
  int same = 1;
  for (int i = 0; i < NT / 3 - 1 && i < rb.n; ++i)
    same &= memcmp(ra.q[3 * i], rb.q[i], (size_t)n * sizeof(double)) == 0 &&
            memcmp(ra.v[3 * i], rb.v[i], (size_t)n * sizeof(double)) == 0;
  CHECK_MSG(same, "%s: states at shared output times differ", dal_method_name(m));
  // against the closed form: within the dense output's 16 x rtol (solve.h)
  printf("%-10s %-6s rtol %.0e: %3d outputs, worst error %.3g = %5.2f x rtol, %ld steps\n",
         dal_method_name(m), cart ? "ggl" : "ode", rtol, ra.n, ra.err, ra.err / rtol, sa.steps);
  CHECK_MSG(ra.err <= 16 * rtol, "%s: error %.3g at rtol %g", dal_method_name(m), ra.err, rtol);
}

// bad lists: refused before any step, naming the index; the state unchanged
static void refusals(const dal_system *s, dal_state *st) {
  dal_solve_opts o = dal_default_solve_opts();
  start(s, st, 0);
  double q0 = dal_state_q(st)[0];
  double bad1[4] = {0.5, 1.0, 0.75, 2.0}, bad2[3] = {0.5, NAN, 1.0}, bad3[2] = {-1.0, 1.0};
  rec r;
  memset(&r, 0, sizeof r);
  int rc = dal_evolve_at(s, st, &o, bad1, 4, mon, &r);
  CHECK(rc == DAL_E_ARG && strstr(dal_state_errmsg(st), "times[2]") != NULL);
  rc = dal_evolve_at(s, st, &o, bad2, 3, mon, &r);
  CHECK(rc == DAL_E_NONFINITE && strstr(dal_state_errmsg(st), "times[1]") != NULL);
  rc = dal_evolve_at(s, st, &o, bad3, 2, mon, &r);
  CHECK(rc == DAL_E_TIME && strstr(dal_state_errmsg(st), "times[0]") != NULL);
  CHECK(dal_evolve_at(s, st, &o, bad3, 0, mon, &r) == DAL_E_ARG);
  CHECK(dal_evolve_at(s, st, &o, NULL, 3, mon, &r) == DAL_E_ARG);
  CHECK(r.n == 0 && dal_state_time(st) == 0.0 && dal_state_q(st)[0] == q0);
  // a later start: the monitor is called at the start only when it is listed
  double later[2] = {0.25, 0.5};
  CHECK_OK(dal_evolve_at(s, st, &o, later, 2, mon, &r));
  CHECK(r.n == 2 && r.t[0] == 0.25 && dal_state_time(st) == 0.5);
  // the end state is the closed form's at the last listed time
  double ref_th, ref_thd;
  ref_pendulum(TH0, sqrt(SCN_G), 0.5, &ref_th, &ref_thd);
  CHECK_CLOSE(dal_state_q(st)[0], ref_th, 16 * o.rtol);
}

int main(void) {
  dal_system *sys[2] = {scn_pendulum(NULL), scn_cart_pendulum(NULL)};
  CHECK(sys[0] && sys[1]);
  if (!sys[0] || !sys[1]) return 1;
  // every adaptive ODE method at two tolerances, and IDA (GGL) on the Cartesian pendulum
  static const struct {
    int cart;
    dal_method m;
    double rtol;
  } rows[] = {{0, DAL_METHOD_DOPRI5, 1e-6},     {0, DAL_METHOD_FEHLBERG78, 1e-6},
              {0, DAL_METHOD_BS, 1e-6},         {0, DAL_METHOD_ADAMS, 1e-6},
              {0, DAL_METHOD_BDF, 1e-6},        {0, DAL_METHOD_DOPRI5, 1e-9},
              {0, DAL_METHOD_FEHLBERG78, 1e-9}, {0, DAL_METHOD_BS, 1e-9},
              {0, DAL_METHOD_ADAMS, 1e-9},      {0, DAL_METHOD_BDF, 1e-9},
              {1, DAL_METHOD_BDF, 1e-6},        {1, DAL_METHOD_BDF, 1e-8}};
  for (size_t i = 0; i < sizeof rows / sizeof rows[0]; ++i) {
    dal_state *st = NULL;
    CHECK_OK(dal_state_create(sys[rows[i].cart], &st));
    method_row(sys[rows[i].cart], st, rows[i].cart, rows[i].m, rows[i].rtol);
    if (i == 0) refusals(sys[0], st);
    dal_state_destroy(st);
  }
  dal_system_destroy(sys[0]);
  dal_system_destroy(sys[1]);
  return check_summary("test_evolve_at");
}
