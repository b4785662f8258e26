// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// White box: what callers read off the method rows (src/integrate/methods.c) against the rules
// the public headers document, the integrator handle on a first-order problem against the closed
// form, and the handle's key: AUTO's tight case (the
// fallback formulation, solve.h) keeps its integrator over dal_advance calls exactly as the
// same formulation asked for by name does.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "integrate/integrate.h"
#include "scenes.h"

// the capabilities each method has by solve.h and analysis.h: the adaptive explicit ones and
// RK4 run every first-order problem, Adams and BDF (CVODE) the implicit way, the six
// structure-preserving ones none
static void test_caps(void) {
  static const struct {
    dal_method m;
    int first_order, explicit_, symplectic, pieces;
  } want[] = {
      {DAL_METHOD_DOPRI5, 1, 1, 0, 1},       {DAL_METHOD_FEHLBERG78, 1, 1, 0, 1},
      {DAL_METHOD_BS, 1, 1, 0, 4},           {DAL_METHOD_RK4, 1, 1, 0, 1},
      {DAL_METHOD_ADAMS, 1, 0, 0, 1},        {DAL_METHOD_BDF, 1, 0, 0, 1},
      {DAL_METHOD_VARIATIONAL, 0, 0, 1, 1},  {DAL_METHOD_VARIATIONAL4, 0, 0, 1, 1},
      {DAL_METHOD_VARIATIONAL6, 0, 0, 1, 1}, {DAL_METHOD_RATTLE, 0, 0, 1, 1},
      {DAL_METHOD_RATTLE4, 0, 0, 1, 1},      {DAL_METHOD_RATTLE6, 0, 0, 1, 1},
  };
  for (size_t i = 0; i < sizeof want / sizeof want[0]; ++i) {
    dal_method m = want[i].m;
    CHECK_MSG(dal__method_can(m, DAL__CAP_FIRST_ORDER) == want[i].first_order, "%s",
              dal_method_name(m));
    CHECK_MSG(dal__method_can(m, DAL__CAP_EXPLICIT) == want[i].explicit_, "%s", dal_method_name(m));
    CHECK_MSG(dal__method_can(m, DAL__CAP_SYMPLECTIC) == want[i].symplectic, "%s",
              dal_method_name(m));
    CHECK_MSG(dal__method_row(m)->traj_pieces == want[i].pieces, "%s", dal_method_name(m));
  }
  // AUTO has no capability of its own; an unknown method none
  CHECK(!dal__method_can(DAL_METHOD_AUTO, DAL__CAP_FIRST_ORDER));
  CHECK(!dal__method_can((dal_method)999, 0));
  char buf[128];
  CHECK(strcmp(dal__methods_that_can(DAL__CAP_FIRST_ORDER | DAL__CAP_EXPLICIT, buf, sizeof buf),
               "dopri5, fehlberg78, bs, rk4") == 0);
  CHECK(strcmp(dal__methods_that_can(DAL__CAP_SYMPLECTIC, buf, sizeof buf),
               "variational, variational4, variational6, rattle, rattle4, rattle6") == 0);
  // a short buffer ends at a whole name
  CHECK(strcmp(dal__methods_that_can(DAL__CAP_FIRST_ORDER, buf, 12), "dopri5") == 0);
}

// AUTO on first-order problems: analysis.h's rule for dal_lyapunov (DOPRI5 above rtol 1e-6,
// Adams down to 1e-12, Bulirsch-Stoer below) and, among the explicit methods, the one
// dal_state_transition documents (DOPRI5 down to 1e-12, Bulirsch-Stoer below)
static void test_auto_fo(void) {
  const unsigned fo = DAL__CAP_FIRST_ORDER, ex = DAL__CAP_FIRST_ORDER | DAL__CAP_EXPLICIT;
  static const struct {
    double rtol;
    dal_method any, expl;
  } rule[] = {
      {1e-3, DAL_METHOD_DOPRI5, DAL_METHOD_DOPRI5}, {2e-6, DAL_METHOD_DOPRI5, DAL_METHOD_DOPRI5},
      {1e-6, DAL_METHOD_ADAMS, DAL_METHOD_DOPRI5},  {1e-10, DAL_METHOD_ADAMS, DAL_METHOD_DOPRI5},
      {1e-12, DAL_METHOD_ADAMS, DAL_METHOD_DOPRI5}, {9e-13, DAL_METHOD_BS, DAL_METHOD_BS},
      {1e-14, DAL_METHOD_BS, DAL_METHOD_BS},
  };
  for (size_t i = 0; i < sizeof rule / sizeof rule[0]; ++i) {
    CHECK_MSG(dal__auto_method_fo(rule[i].rtol, fo) == rule[i].any, "rtol %g: %s", rule[i].rtol,
              dal_method_name(dal__auto_method_fo(rule[i].rtol, fo)));
    CHECK_MSG(dal__auto_method_fo(rule[i].rtol, ex) == rule[i].expl, "rtol %g: %s", rule[i].rtol,
              dal_method_name(dal__auto_method_fo(rule[i].rtol, ex)));
  }
  // nothing has every capability: no method
  CHECK(dal__auto_method_fo(1e-8, DAL__CAP_FIRST_ORDER | DAL__CAP_SYMPLECTIC) == DAL_METHOD_AUTO);
}

// the analysis calls refuse what the rows say a method cannot run, naming those that can
static void test_refusals(void) {
  dal_system *sys = scn_pendulum(NULL);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q = 1.0, v = 0.0, Phi[4];
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &v));
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_ADAMS;
  CHECK(dal_state_transition(sys, st, &o, 1.0, Phi, 0, NULL, NULL) == DAL_E_UNSUPPORTED);
  CHECK(strstr(dal_state_errmsg(st), "(dopri5, fehlberg78, bs, rk4)") != NULL);
  // through the handle, a first-order run honours opts.max_steps like dal_advance (the
  // variational run went without its per-call target and never counted)
  o = dal_default_solve_opts();
  o.max_steps = 5;
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &v));
  CHECK(dal_state_transition(sys, st, &o, 10.0, Phi, 0, NULL, NULL) == DAL_E_MAXSTEPS);
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &v));
  dal_lyapunov_opts lo = dal_default_lyapunov_opts();
  lo.t_end = 10.0;
  lo.method = DAL_METHOD_RATTLE;
  double lambda[2];
  CHECK(dal_lyapunov(sys, st, &lo, lambda, NULL, NULL, NULL) == DAL_E_UNSUPPORTED);
  CHECK(strstr(dal_state_errmsg(st), "(dopri5, fehlberg78, bs, rk4, adams, bdf)") != NULL);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// the first-order problem of test_fo_handle: two harmonic oscillators, y = (q, v, x, w),
// q' = v, v' = -q, x' = w, w' = -x (the rhs ignores the pendulum: a first-order problem says
// its own F)
static int two_oscillators(void *ctx, dal_state *st, double t, const double *y, double *f) {
  (void)ctx;
  (void)st;
  (void)t;
  f[0] = y[1];
  f[1] = -y[0];
  f[2] = y[3];
  f[3] = -y[2];
  return DAL_OK;
}

// after every step of a hooked run: the work state placed at the middle of the step just taken,
// against q = cos t
typedef struct dense_probe {
  dal_integ *it;
  int steps;
  double err;
} dense_probe;

static int probe_mid(void *ctx) {
  dense_probe *pr = ctx;
  double a = 0, b = 0;
  pr->it->ops->window(pr->it, &a, &b);
  double tm = 0.5 * (a + b);
  int rc = pr->it->ops->place(pr->it, tm);
  if (rc) return rc;
  const dal_state *st = pr->it->st;
  pr->err = fmax(pr->err, st->t == tm && b > a ? fabs(dal_state_q(st)[0] - cos(tm)) : INFINITY);
  pr->steps++;
  return DAL_OK;
}

// a first-order problem behind the integrator handle (dal__integ_create_fo), against the
// closed form: AUTO resolved by the rows, the solution at it->y, the work state following the
// trajectory part, dense output through place, change_y where the method keeps its memory, the
// budget it->opts.max_steps, a refused method naming those that run one
static void test_fo_handle(void) {
  dal_system *sys = scn_pendulum(NULL);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  const double y0[4] = {1.0, 0.0, 0.0, 1.0}; // q = cos t, v = -sin t, x = sin t, w = cos t
  dal_first_order fo = {.ny = 4, .y0 = y0, .rhs = two_oscillators};
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = o.atol = 1e-10;
  dal_integ *it = NULL;
  CHECK_OK(dal__integ_create_fo(sys, st, &o, &fo, &it));
  // AUTO on a first-order problem: Adams between rtol 1e-6 and 1e-12 (analysis.h)
  CHECK(it->method == DAL_METHOD_ADAMS && it->ny == 4 && it->ops->change_y);
  CHECK_OK(it->ops->advance(it, 1.0, NULL, NULL));
  double err = 0;
  CHECK(st->t == 1.0);
  const double ref[4] = {cos(1.0), -sin(1.0), sin(1.0), cos(1.0)};
  for (int i = 0; i < 4; ++i)
    err = fmax(err, fabs(it->y[i] - ref[i]));
  CHECK_MSG(err < 1e-10, "Adams at rtol 1e-10: error %.3g", err);
  CHECK(dal_state_q(st)[0] == it->y[0] && dal_state_qdot(st)[0] == it->y[1]);
  // dense output of the trajectory part inside every step of a hooked run
  dense_probe pr = {.it = it};
  it->dense_steps = 1;
  CHECK_OK(it->ops->advance(it, 2.0, probe_mid, &pr));
  CHECK_MSG(pr.steps > 5 && pr.err < 1e-10, "%d steps, dense output off by %.3g", pr.steps, pr.err);
  printf("first-order handle, Adams at rtol 1e-10: error %.3g at t = 1, dense output %.3g in %d "
         "steps\n",
         err, pr.err, pr.steps);
  // Adams cannot go on after y changed: nothing changed, the caller makes a fresh integrator
  const double moved[4] = {0.0, 0.0, 0.0, 2.0};
  double w1 = it->y[3];
  CHECK(it->ops->change_y(it, 2, moved) == 0 && it->y[3] == w1);
  // the step budget is read at every call
  it->opts.max_steps = 3;
  CHECK(it->ops->advance(it, 60.0, NULL, NULL) == DAL_E_MAXSTEPS);
  CHECK(strstr(dal_state_errmsg(st), "opts.max_steps") != NULL);
  dal__integ_destroy(it);

  // Bulirsch-Stoer goes on from the changed tangent part: x = 2 sin(t - 1) from t = 1
  o.method = DAL_METHOD_BS;
  st->t = 0.0;
  CHECK_OK(dal__integ_create_fo(sys, st, &o, &fo, &it));
  CHECK_OK(it->ops->advance(it, 1.0, NULL, NULL));
  CHECK(it->ops->change_y(it, 2, moved) == 1 && it->y[2] == 0.0 && it->y[3] == 2.0);
  CHECK_OK(it->ops->advance(it, 2.0, NULL, NULL));
  const double ref2[4] = {cos(2.0), -sin(2.0), 2.0 * sin(1.0), 2.0 * cos(1.0)};
  err = 0;
  for (int i = 0; i < 4; ++i)
    err = fmax(err, fabs(it->y[i] - ref2[i]));
  CHECK_MSG(err < 1e-10, "BS after change_y: error %.3g", err);
  printf("first-order handle, Bulirsch-Stoer through change_y: error %.3g at t = 2\n", err);
  dal__integ_destroy(it);

  // a structure-preserving method runs no first-order problem: refused, naming those that do
  o.method = DAL_METHOD_RATTLE;
  CHECK(dal__integ_create_fo(sys, st, &o, &fo, &it) == DAL_E_UNSUPPORTED && it == NULL);
  CHECK(strstr(dal_state_errmsg(st), "(dopri5, fehlberg78, bs, rk4, adams, bdf)") != NULL);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// AUTO below IDA's tolerance floor runs the fallback formulation; its integrator must be kept
// from one dal_advance call to the next like any other (it was rebuilt at every call: 200
// steps instead of 102 for 100 calls). Reference: the same formulation asked for by name.
static void test_tight_key(void) {
  dal_system *sys = scn_cart_pendulum(NULL);
  dal_stats s[2];
  double q[2][2];
  for (int named = 0; named < 2; ++named) {
    dal_state *st = NULL;
    CHECK_OK(dal_state_create(sys, &st));
    const double q0[2] = {1.0, 0.0}, v0[2] = {0.0, 0.0};
    CHECK_OK(dal_state_set(sys, st, 0.0, q0, v0));
    dal_solve_opts o = dal_default_solve_opts();
    o.rtol = o.atol = 1e-12;
    if (named) {
      o.form = DAL_FORM_INDEX1;
      o.project = 1;
      o.method = DAL_METHOD_BS;
    }
    int rc = 0;
    for (int k = 1; k <= 100 && !rc; ++k)
      rc = dal_advance(sys, st, &o, 0.1 * k);
    CHECK_MSG(rc == 0, "%s", dal_state_errmsg(st));
    CHECK_OK(dal_state_stats(st, &s[named]));
    memcpy(q[named], dal_state_q(st), sizeof q[named]);
    dal_state_destroy(st);
  }
  CHECK(s[0].method_used == DAL_METHOD_BS && s[0].form_used == DAL_FORM_INDEX1);
  CHECK_MSG(s[0].steps == s[1].steps && s[0].rhs_evals == s[1].rhs_evals,
            "AUTO: %ld steps, %ld evaluations; by name: %ld, %ld", s[0].steps, s[0].rhs_evals,
            s[1].steps, s[1].rhs_evals);
  CHECK(memcmp(q[0], q[1], sizeof q[0]) == 0);
  printf("AUTO's tight case over 100 dal_advance calls: %ld steps, %ld evaluations (by name: "
         "%ld, %ld)\n",
         s[0].steps, s[0].rhs_evals, s[1].steps, s[1].rhs_evals);
  dal_system_destroy(sys);
}

int main(void) {
  test_caps();
  test_auto_fo();
  test_refusals();
  test_fo_handle();
  test_tight_key();
  return check_summary("test_method_rows");
}
