// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The cancel hook (dal_solve_opts.cancel): every method and route stops at an accepted step.
//
// Reference: the same run without a hook. A cancelled run ends at one of that run's accepted
// steps, so its state there must agree with a plain run to the same time (the methods whose
// steps do not depend on the end time reach it to rounding; the others within the tolerance),
// every output time up to the cancel has been served and none after, and a second call from
// the cancelled state reaches the end time.
#include "check.h"
#include "support/scenes.h"

#include <string.h>

typedef struct counter {
  int calls, stop_at;
} counter;

static int cancel_after(void *ctx) {
  counter *c = ctx;
  return ++c->calls >= c->stop_at;
}

typedef struct outputs {
  int n;
  double last;
} outputs;

static int count_outputs(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  outputs *o = ctx;
  o->n++;
  o->last = dal_state_time(st);
  return 0;
}

// one route: cancel after 5 steps, then compare with a plain run to the same time
static void one(const char *what, dal_system *sys, const double *q0, const double *qd0,
                dal_formulation f, dal_method m, double tol) {
  int n = dal_system_ncoords(sys);
  dal_state *st = NULL, *ref = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_create(sys, &ref));
  CHECK_OK(dal_state_set(sys, st, 0.0, q0, qd0));
  CHECK_OK(dal_state_set(sys, ref, 0.0, q0, qd0));
  dal_solve_opts o = scn_opts(f, m, 1e-9);
  o.fixed_step = 1e-2;
  counter c = {0, 5};
  o.cancel = cancel_after;
  o.cancel_ctx = &c;
  // advance: stops after the fifth accepted step
  int rc = dal_advance(sys, st, &o, 10.0);
  double tc = dal_state_time(st);
  CHECK_MSG(rc == DAL_CANCELLED, "%s: advance returned %d (%s)", what, rc, dal_state_errmsg(st));
  CHECK_MSG(c.calls == 5, "%s: the hook was asked %d times", what, c.calls);
  CHECK_MSG(tc > 0.0 && tc < 10.0, "%s: stopped at t=%g", what, tc);
  CHECK_MSG(strstr(dal_state_errmsg(st), "cancelled") != NULL, "%s: message '%s'", what,
            dal_state_errmsg(st));
  // the state holds an accepted step: a plain run to that time agrees
  dal_solve_opts plain = o;
  plain.cancel = NULL;
  CHECK_OK(dal_advance(sys, ref, &plain, tc));
  for (int i = 0; i < n; i++) {
    CHECK_CLOSE(dal_state_q(st)[i], dal_state_q(ref)[i], tol);
    CHECK_CLOSE(dal_state_qdot(st)[i], dal_state_qdot(ref)[i], tol);
  }
  // the state is evaluated there (its energies are those of its (q, qdot))
  dal_energies e;
  CHECK_OK(dal_state_energies(st, &e));
  CHECK(isfinite(e.E));
  // a second call without the hook goes on to the end
  CHECK_OK(dal_advance(sys, st, &plain, 1.0 > tc ? 1.0 : tc + 0.5));
  // evolve: every output up to the cancel served, none after
  CHECK_OK(dal_state_set(sys, st, 0.0, q0, qd0));
  c.calls = 0;
  outputs out = {0, -1.0};
  rc = dal_evolve(sys, st, &o, 10.0, 1e-3, count_outputs, &out);
  tc = dal_state_time(st);
  CHECK_MSG(rc == DAL_CANCELLED, "%s: evolve returned %d (%s)", what, rc, dal_state_errmsg(st));
  CHECK_MSG(out.n == (int)floor(tc / 1e-3 + 1e-9) + 1, "%s: %d outputs up to t=%.17g", what, out.n,
            tc);
  CHECK(out.last <= tc);
  dal_state_destroy(st);
  dal_state_destroy(ref);
}

int main(void) {
  scn_knobs k = scn_default();
  dal_system *pend = scn_pendulum(&k);
  double q = 1.0, qd = 0.0;
  // steps independent of the end time: to rounding (the plain run clips its last step at tc);
  // CVODE and BS end a step at tout: within the tolerance
  one("dopri5", pend, &q, &qd, DAL_FORM_ODE, DAL_METHOD_DOPRI5, 1e-13);
  one("fehlberg78", pend, &q, &qd, DAL_FORM_ODE, DAL_METHOD_FEHLBERG78, 1e-13);
  one("rk4", pend, &q, &qd, DAL_FORM_ODE, DAL_METHOD_RK4, 1e-13);
  one("bs", pend, &q, &qd, DAL_FORM_ODE, DAL_METHOD_BS, 1e-7);
  one("adams", pend, &q, &qd, DAL_FORM_ODE, DAL_METHOD_ADAMS, 1e-7);
  one("bdf", pend, &q, &qd, DAL_FORM_ODE, DAL_METHOD_BDF, 1e-7);
  one("variational", pend, &q, &qd, DAL_FORM_ODE, DAL_METHOD_VARIATIONAL, 1e-13);
  dal_system_destroy(pend);
  // redundant coordinates: IDA's GGL form
  dal_system *cart = scn_cart_pendulum(&k);
  double qc[2] = {sin(1.0), -cos(1.0)}, qdc[2] = {0, 0};
  one("ggl", cart, qc, qdc, DAL_FORM_GGL, DAL_METHOD_BDF, 1e-7);
  one("index1-bs", cart, qc, qdc, DAL_FORM_INDEX1, DAL_METHOD_BS, 1e-7);
  dal_system_destroy(cart);
  return check_summary("test_cancel");
}
