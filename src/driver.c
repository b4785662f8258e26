// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Integration driver: the integrator kept in the state, advance and evolve, monitors.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dae_internal.h"
#include "form_dae.h"
#include "solve_internal.h"
#include "symplectic.h"

// ---------------------------------------------------------------------------------------------
// integrator handle kept in the state

enum { KIND_ODE = 1, KIND_IDA = 2 };

typedef struct dal_integ_handle {
  int kind;
  dal_ode_integ *ode;
  void *ida;
  double t;   // time of the state when last handed back
  double *qq; // (q, qdot) handed back, to notice changes made outside the integrator
} dal_integ_handle;

static void handle_free(void *p) {
  dal_integ_handle *h = p;
  if (!h) return;
  if (h->ode) dal__ode_destroy(h->ode);
  if (h->ida) dal__ida_free(h->ida);
  free(h->qq);
  free(h);
}

// resolve formulation and method; *prob is NULL for the IDA route; *tight is set when AUTO
// chose the index-1 form with projection because IDA cannot honour the tolerance (solve.h)
static int resolve(const dal_system *sys, dal_state *st, const dal_solve_opts *o, dal_method *meth,
                   const dal_ode_problem **prob, int *tight) {
  dal_formulation form = o->form;
  dal_method m = o->method;
  *tight = 0;
  if (o->work && sys->lag)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "opts.work: a Lagrangian-only system has no forces or constraints whose work "
                    "could be tracked; its energy function is dal_energies.h (unset opts.work)");
  if (dal__symplectic_method(m)) {
    if (o->work)
      return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                      "opts.work is not supported by the fixed-step method '%s' (its energy "
                      "error is bounded by construction); use an adaptive method to track W",
                      dal_method_name(m));
    *meth = m;
    return dal__symplectic_resolve(sys, st, o, m, prob);
  }
  if (form == DAL_FORM_AUTO && sys->m && m == DAL_METHOD_AUTO &&
      dal__dae_tol_factor(DAL_FORM_GGL) * o->rtol < DAL_IDA_TOL_FLOOR) {
    // IDA would be clamped at its floor: index-1 with projection and Bulirsch-Stoer honours
    // such tolerances (measured 5.7 x rtol at 1e-12 on the Cartesian pendulum)
    *tight = 1;
    *meth = DAL_METHOD_BS;
    *prob = &dal__problem_index1;
    return DAL_OK;
  }
  if (form == DAL_FORM_AUTO) form = sys->m ? DAL_FORM_GGL : DAL_FORM_ODE;
  if (form == DAL_FORM_INDEX1 && sys->m == 0) form = DAL_FORM_ODE;
  if (form == DAL_FORM_ODE && sys->m > 0)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "formulation 'ode' needs minimal coordinates, but the system has %d "
                    "constraint rows (first: '%s'); use DAL_FORM_GGL or DAL_FORM_INDEX1",
                    sys->m, sys->con[0].name);
  if (form == DAL_FORM_GGL || form == DAL_FORM_INDEX3 ||
      (form == DAL_FORM_INDEX1 && m == DAL_METHOD_BDF)) {
    if (m != DAL_METHOD_AUTO && m != DAL_METHOD_BDF)
      return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                      "formulation '%s' runs only with DAL_METHOD_BDF (IDA), not '%s'; use "
                      "DAL_METHOD_BDF or DAL_METHOD_AUTO, or DAL_FORM_INDEX1 for explicit "
                      "methods",
                      dal_formulation_name(form), dal_method_name(m));
    *meth = DAL_METHOD_BDF;
    *prob = NULL;
    return DAL_OK;
  }
  if (m == DAL_METHOD_AUTO) m = dal__auto_method(o->rtol);
  *meth = m;
  *prob = form == DAL_FORM_INDEX1 ? &dal__problem_index1 : &dal__problem_minimal;
  return DAL_OK;
}

// remember what the state looked like when the integrator handed it back
static void handle_sync(const dal_system *sys, dal_state *st, dal_integ_handle *h) {
  size_t n = (size_t)sys->n;
  h->t = st->t;
  memcpy(h->qq, st->q, n * sizeof(double));
  memcpy(h->qq + n, st->qdot, n * sizeof(double));
}

// the state's (t, q, qdot) still are where the integrator left them
static int handle_current(const dal_system *sys, const dal_state *st, const dal_integ_handle *h) {
  size_t n = (size_t)sys->n;
  return h->t == st->t && memcmp(h->qq, st->q, n * sizeof(double)) == 0 &&
         memcmp(h->qq + n, st->qdot, n * sizeof(double)) == 0;
}

// make sure st->integ is an integrator for these options at the state's current point
static int ensure_integ(const dal_system *sys, dal_state *st, const dal_solve_opts *o) {
  dal_integ_handle *h = st->integ;
  if (h && dal__same_opts(o, &st->integ_opts) && handle_current(sys, st, h)) return DAL_OK;
  dal__integ_reset(st);
  dal_method meth = DAL_METHOD_AUTO;
  const dal_ode_problem *prob = NULL;
  int tight = 0;
  int rc = resolve(sys, st, o, &meth, &prob, &tight);
  if (rc) return rc;
  dal_solve_opts oc = *o;
  if (tight) {
    // the index-1 form starts from a consistent state too, and projects after every step
    oc.form = DAL_FORM_INDEX1;
    oc.project = 1;
    if ((rc = dal__public_status(dal__dae_start(sys, st, o->init_max_move, NULL))) != 0) return rc;
    o = &oc;
  }
  h = calloc(1, sizeof *h);
  if (!h) return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the integrator");
  h->qq = calloc(2 * (size_t)sys->n + 1, sizeof(double));
  if (!h->qq) {
    free(h);
    return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the integrator");
  }
  if (prob) {
    h->kind = KIND_ODE;
    rc = dal__ode_create(sys, st, o, meth, prob, &h->ode);
  } else {
    h->kind = KIND_IDA;
    rc = dal__public_status(dal__ida_create(sys, st, o, &h->ida));
  }
  if (rc) {
    handle_free(h);
    return rc;
  }
  handle_sync(sys, st, h);
  st->integ = h;
  st->integ_free = handle_free;
  st->integ_opts = *o;
  return DAL_OK;
}

// evaluate the state where it stands (outputs valid); a recoverable request is a failure here
static int evaluate_here(const dal_system *sys, dal_state *st) {
  return dal__public_status(dal__eval(sys, st, DAL_P_ALL));
}

// advance to t1 >= st->t with validated arguments
static int advance_to(const dal_system *sys, dal_state *st, const dal_solve_opts *o, double t1) {
  int rc = ensure_integ(sys, st, o);
  if (rc) return rc;
  dal_integ_handle *h = st->integ;
  if (t1 == st->t) return evaluate_here(sys, st);
  if (t1 - st->t <= DAL_TINY_STEP(st->t)) {
    // an interval of a few ulps: the solution does not change at double precision; restart
    // the integrator at the new time rather than asking it for a step it cannot take
    dal__integ_reset(st);
    st->t = t1;
    return evaluate_here(sys, st);
  }
  if (h->kind == KIND_ODE) {
    dal_ode_integ *ig = h->ode;
    ig->tout = t1;
    ig->ncall = 0;
    ig->rhs_fatal = 0;
    ig->ntiny = 0;
    ig->nrecov = 0;
    rc = ig->advance(ig, t1);
    if (!rc) {
      // the state at t1, evaluated there
      dal__ode_to_state(ig, ig->t, ig->y);
      rc = dal__public_status(dal__ode_eval(ig, ig->t, ig->y, ig->ydot, DAL_P_ALL));
    }
  } else {
    rc = dal__public_status(dal__ida_advance(sys, st, h->ida, t1));
  }
  if (rc) {
    // the state holds the last accepted step; the next call restarts the integrator there
    dal__integ_reset(st);
    return rc;
  }
  st->err[0] = 0;
  handle_sync(sys, st, h);
  return DAL_OK;
}

// common argument checks of advance and evolve
static int check_call(const dal_system *sys, dal_state *st, const dal_solve_opts *o, double t1,
                      const char *what) {
  int pair = dal__check_pair(sys, st, what);
  if (pair) return pair;
  int rc = dal__check_opts(st, o);
  if (rc) return rc;
  if (!isfinite(t1))
    return DAL_FAIL(st, DAL_E_NONFINITE, "%s: target time is %g; give a finite time", what, t1);
  // a step bound below the spacing of doubles at t cannot move t (the fixed step counts for
  // the methods that take it: RK4, and DOPRI5/Fehlberg with fixed_erk)
  int fixed =
      o->method == DAL_METHOD_RK4 ||
      (o->fixed_erk && (o->method == DAL_METHOD_DOPRI5 || o->method == DAL_METHOD_FEHLBERG78));
  const double hs[4] = {o->h0, o->hmin, o->hmax, fixed ? o->fixed_step : 0.0};
  const char *hn[4] = {"h0", "hmin", "hmax", "fixed_step"};
  for (int i = 0; i < 4; ++i)
    if (hs[i] > 0 && (st->t + hs[i] == st->t || t1 + hs[i] == t1))
      return DAL_FAIL(st, DAL_E_ARG,
                      "%s: opts.%s = %g is below the floating-point resolution of t between %g "
                      "and %g; use a larger value or 0 (automatic)",
                      what, hn[i], hs[i], st->t, t1);
  if (t1 < st->t)
    return DAL_FAIL(st, DAL_E_TIME,
                    "%s: target time %.17g lies behind the current time %.17g; integration runs "
                    "forward only (reset the state with dal_state_set to go back)",
                    what, t1, st->t);
  return DAL_OK;
}

int dal_advance(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t1) {
  int rc = check_call(sys, st, opts, t1, "advance");
  if (rc) return rc;
  dal_solve_opts eff = dal__effective_opts(opts);
  return advance_to(sys, st, &eff, t1);
}

// run the monitor at the state's time; 1 = stop requested (ok), negative = failure
static int call_monitor(const dal_system *sys, dal_state *st, dal_monitor_fn *monitor, void *ctx) {
  if (!monitor) return 0;
  st->err[0] = 0; // a monitor of the library (dal_csv_monitor) leaves its reason here
  int mr = monitor(sys, st, ctx);
  if (mr > 0) {
    // not a failure; the message says where and why the run ended
    DAL_FAIL(st, DAL_STOPPED, "monitor returned %d at t=%.17g: evolve stopped there as asked", mr,
             st->t);
    return 1;
  }
  if (mr < 0) {
    char why[DAL_ERRMSG_LEN];
    memcpy(why, st->err, sizeof why);
    return DAL_FAIL(st, DAL_E_CALLBACK,
                    "monitor returned %d (%s) at t=%.17g%s%.300s; evolve stopped there (the state "
                    "holds that time)",
                    mr, dal_status_name(mr), st->t, why[0] ? ": " : "", why);
  }
  return 0;
}

int dal_evolve(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t1,
               double dt, dal_monitor_fn *monitor, void *ctx) {
  int rc = check_call(sys, st, opts, t1, "evolve");
  if (rc) return rc;
  if (!isfinite(dt))
    return DAL_FAIL(st, DAL_E_NONFINITE,
                    "evolve: output interval dt = %g is not finite; give a positive finite dt", dt);
  if (!(dt > 0))
    return DAL_FAIL(st, DAL_E_ARG, "evolve: output interval dt = %g must be positive", dt);
  double t0 = st->t, span = (t1 - t0) / dt;
  // a dt below the floating-point spacing of t would give output times that never advance
  if (t0 + dt == t0 || t1 + dt == t1)
    return DAL_FAIL(st, DAL_E_ARG,
                    "evolve: output interval dt = %g is below the floating-point resolution of "
                    "t between %g and %g; use a larger dt or restart the clock near 0",
                    dt, t0, t1);
  if (span > 1e12)
    return DAL_FAIL(st, DAL_E_ARG,
                    "evolve: %.3g output times between %g and %g (dt = %g); use a larger dt", span,
                    t0, t1, dt);
  dal_solve_opts eff = dal__effective_opts(opts);
  opts = &eff;
  // K = number of whole output intervals: t0 + K dt <= t1 in floating point
  long K = (long)floor(span);
  while (K > 0 && t0 + (double)K * dt > t1)
    --K;
  while (t0 + (double)(K + 1) * dt <= t1)
    ++K;
  for (long k = 0; k <= K; ++k) {
    double tk = t0 + (double)k * dt;
    // a grid time within rounding of t1 is t1 itself (no near-duplicate output)
    if (k == K && t1 - tk <= 1e-9 * dt) tk = t1;
    if ((rc = advance_to(sys, st, opts, tk)) != 0) return rc;
    if ((rc = call_monitor(sys, st, monitor, ctx)) != 0) return rc > 0 ? DAL_STOPPED : rc;
  }
  if (st->t < t1) {
    if ((rc = advance_to(sys, st, opts, t1)) != 0) return rc;
    if ((rc = call_monitor(sys, st, monitor, ctx)) != 0) return rc > 0 ? DAL_STOPPED : rc;
  }
  return DAL_OK;
}
