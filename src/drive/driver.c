// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Integration driver: the integrator kept in the state, advance and evolve, monitors.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drive.h"
#include "eval/eval.h"
#include "form/form.h"
#include "integrate/integrate.h"

// ---------------------------------------------------------------------------------------------
// integrator handle kept in the state

typedef struct dal_integ_handle {
  dal_integ *it;             // the integrator (either family, one interface)
  double t;                  // time of the state when last handed back
  double *qq;                // (q, qdot) handed back, to notice changes made outside the integrator
  char note[DAL_ERRMSG_LEN]; // a fallback's note, left in the state's message on success
  char why[DAL_ERRMSG_LEN];  // IDA's failure message that caused the fallback
} dal_integ_handle;

static void handle_free(void *p) {
  dal_integ_handle *h = p;
  if (!h) return;
  dal__integ_destroy(h->it);
  free(h->qq);
  free(h);
}

// a handle for a fresh integrator of options o at the state's point (dense: outputs between
// the steps), or NULL with the state's message set (*rc)
static dal_integ_handle *handle_create(const dal_system *sys, dal_state *st,
                                       const dal_solve_opts *o, int dense, int *rc) {
  dal_integ_handle *h = calloc(1, sizeof *h);
  if (!h || !(h->qq = calloc(2 * (size_t)sys->n + 1, sizeof(double)))) {
    free(h);
    *rc = DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the integrator");
    return NULL;
  }
  if ((*rc = dal__integ_create(sys, st, o, dense, &h->it)) != 0) {
    handle_free(h);
    return NULL;
  }
  return h;
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

// the state keeps handle h, created for options o
static void handle_keep(const dal_system *sys, dal_state *st, dal_integ_handle *h,
                        const dal_solve_opts *o) {
  handle_sync(sys, st, h);
  st->integ = h;
  st->integ_free = handle_free;
  st->integ_opts = *o;
  st->stats.method_used = h->it->method;
  st->stats.form_used = h->it->form;
}

// notes for the state's message on success (issue: never silent where a request was not
// honoured as given): a consistent start that moved the coordinates by more than the
// tolerance asked for, and an IDA tolerance raised to its floor
static void start_notes(const dal_system *sys, dal_state *st, const dal_solve_opts *o,
                        dal_integ_handle *h, const dal_init_report *before, int before_valid) {
  size_t used = strlen(h->note);
  const dal_init_report *r = &st->init_rep;
  if (st->init_rep_valid && r->dq_coord >= 0 &&
      (!before_valid || memcmp(before, r, sizeof *r) != 0)) {
    int j = r->dq_coord;
    double scale = o->atol + o->rtol * fabs(st->q[j]);
    if (r->dq_max > scale && used < sizeof h->note)
      used += (size_t)snprintf(
          h->note + used, sizeof h->note - used,
          "%snote: the consistent start at t=%.17g moved coordinate '%s' by %.3g (largest "
          "constraint residual %.3g on '%s'); set opts.init_max_move to refuse such moves "
          "(dal_state_init_report has the report)",
          used ? "; " : "", st->t, sys->coord_names[j], r->dq_max, r->phi_before,
          r->phi_row >= 0 ? sys->con[sys->row_con[r->phi_row]].name : "-");
  }
  // what the integrator did not honour as asked (a tolerance floor)
  const char *parts[2] = {used ? "; " : "", h->it->note};
  for (int k = 0; k < 2 && h->it->note[0]; ++k) {
    size_t len = strlen(parts[k]);
    if (len > sizeof h->note - 1 - used) len = sizeof h->note - 1 - used;
    memcpy(h->note + used, parts[k], len);
    h->note[used += len] = 0;
  }
}

// make sure st->integ is an integrator for these options at the state's current point (dense:
// a monitor reads outputs between the steps, which AUTO takes into account when it creates one)
static int ensure_integ(const dal_system *sys, dal_state *st, const dal_solve_opts *o, int dense) {
  dal_integ_handle *h = st->integ;
  if (h && dal__same_opts(o, &st->integ_opts) && handle_current(sys, st, h)) return DAL_OK;
  dal__integ_reset(st);
  // the consistent start's report before this start (to notice a new one)
  dal_init_report before = st->init_rep;
  int before_valid = st->init_rep_valid;
  int rc = 0;
  if (!(h = handle_create(sys, st, o, dense, &rc))) return rc;
  start_notes(sys, st, &h->it->opts, h, &before, before_valid);
  // the caller's options are the key (the integrator may run others: AUTO's fallback form)
  handle_keep(sys, st, h, o);
  return DAL_OK;
}

// the fallback ladder's one rung (docs/dae.md): an IDA failure that another formulation can
// overcome (a Newton iteration that does not converge, a step size collapse at a regular
// point) restarts from the last accepted step in the index-1 form with projection and
// Bulirsch-Stoer; the caller's options stay the integrator's key, so that later calls with the
// same options continue on the fallback
static int can_fall_back(const dal_solve_opts *o, int rc) {
  return !o->no_fallback && o->form == DAL_FORM_AUTO && o->method == DAL_METHOD_AUTO &&
         (rc == DAL_E_CONV || rc == DAL_E_STEP);
}

static int fall_back(const dal_system *sys, dal_state *st, const dal_solve_opts *o, int cause) {
  char why[DAL_ERRMSG_LEN];
  memcpy(why, st->err, sizeof why);
  double t = st->t;
  dal__integ_reset(st);
  dal_solve_opts oc = dal__fallback_opts(o);
  int rc = dal__fallback_start(sys, st, o);
  if (rc) {
    // no consistent start there (a singular point): IDA's failure stands, with both reasons;
    // the state stays at IDA's last accepted step, evaluated
    // IDA's message up to a clause boundary, then the start's reason
    size_t cut = strlen(why);
    if (cut > 300) {
      cut = 300;
      while (cut > 0 && !(why[cut - 1] == ';' || why[cut - 1] == ':'))
        --cut;
      if (cut > 0) --cut;
    }
    char msg[2 * DAL_ERRMSG_LEN];
    snprintf(msg, sizeof msg, "%.*s; the fallback to the index-1 form could not start there: %s",
             (int)cut, why, st->err);
    (void)dal__eval(sys, st, DAL_P_ALL);
    msg[sizeof st->err - 1] = 0; // cut to the state's message length
    memcpy(st->err, msg, sizeof st->err);
    return cause;
  }
  dal_integ_handle *h = handle_create(sys, st, &oc, 0, &rc);
  if (!h) return rc;
  memcpy(h->why, why, sizeof why);
  handle_keep(sys, st, h, o);
  st->stats.fallbacks++;
  st->stats.fallback_t = t;
  st->stats.fallback_cause = cause;
  snprintf(h->note, sizeof h->note,
           "note: IDA's GGL form stopped at t=%.17g (%s); the run went on from there in the "
           "index-1 form with projection and Bulirsch-Stoer (dal_stats.fallbacks; "
           "opts.no_fallback turns this off). IDA said: %.300s",
           t, dal_status_name(cause), why);
  return DAL_OK;
}

// evaluate the state where it stands (outputs valid); a recoverable request is a failure here
static int evaluate_here(const dal_system *sys, dal_state *st) {
  return dal__public_status(dal__eval(sys, st, DAL_P_ALL));
}

// Over an interval [t, t1] of a few ulps of t no method can take a step. The state may stay
// where it is only when it does not move there beyond the tolerances (|qdot| h + |qddot| h^2/2
// and |qddot| h within atol + rtol |x|, at the evaluated state): at t = 1 a few ulps are
// 1e-15 s, at t = 1e15 they are seconds. Otherwise the interval is refused (never reported as
// motion that did not happen). 0 when the state may stay.
static int check_unresolved(const dal_system *sys, dal_state *st, const dal_solve_opts *o,
                            double t1, const char *what) {
  int rc = evaluate_here(sys, st);
  if (rc) return rc;
  double h = t1 - st->t, worst = 0.0;
  int bad = -1;
  for (int i = 0; i < sys->n; ++i) {
    double a = fabs(st->qddot[i]), dq = fabs(st->qdot[i]) * h + 0.5 * a * h * h, dv = a * h;
    double r = fmax(dq / (o->atol + o->rtol * fabs(st->q[i])),
                    dv / (o->atol + o->rtol * fabs(st->qdot[i])));
    if (!(r <= 1.0) && !(r <= worst)) {
      worst = r;
      bad = i;
    }
  }
  if (bad < 0) return DAL_OK;
  return DAL_FAIL(st, DAL_E_ARG,
                  "%s: the interval from t=%.17g to %.17g (%.3g) is a few ulps of t, below the "
                  "floating-point resolution of t at this magnitude: no step can be taken over "
                  "it, and coordinate '%s' moves there (%.3g times its tolerance); restart the "
                  "clock near 0 (shift the time origin) to integrate it",
                  what, st->t, t1, h, sys->coord_names[bad], worst);
}

// ---------------------------------------------------------------------------------------------
// a run of advance or evolve: the integrator steps freely towards the end time; after every
// accepted step the hook serves the output times and the events inside the step from the
// method's dense output (no step is shortened for an output)

typedef struct run {
  const dal_system *sys;
  dal_state *st;
  const dal_solve_opts *o;
  const char *what; // "advance" or "evolve" (messages)
  dal_integ_handle *h;
  int outputs;         // evolve: the output grid below is served
  double t0, dt, t1;   // output times t0 + k dt (k <= K), then t1
  long k, K;           // next output index
  const double *times; // evolve_at: the output times times[0 .. K] instead of the grid
  double last_out;     // time of the last output served
  double tnext;        // the next output time (out_time), +inf when all are served
  dal_monitor_fn *monitor;
  void *ctx;
  dal_events *ev; // attached events with at least one event, or NULL
  int status;     // why the hook stopped the run: DAL_STOPPED, DAL_EVENT, or a failure
} run;

// the next output time, or +inf when all are served
static inline double out_time(const run *r) {
  // the common case first: a grid time before the last (K = 0 without outputs)
  if (!r->times && r->k < r->K) return r->t0 + (double)r->k * r->dt;
  if (!r->outputs) return INFINITY;
  if (r->times) return r->k <= r->K ? r->times[r->k] : INFINITY;
  if (r->k == r->K) {
    double tk = r->t0 + (double)r->k * r->dt;
    // a later grid time within rounding of t1 is t1 itself (no near-duplicate output); the
    // first (t0) is always served, however large dt is against t1 - t0 (issue 31)
    return r->k > 0 && r->t1 - tk <= 1e-9 * r->dt ? r->t1 : tk;
  }
  return r->last_out < r->t1 ? r->t1 : INFINITY;
}

// the outcome of a monitor that returned mr != 0 or saw a failing evaluation (its message in
// the state); 1 = stop requested (ok), negative = failure
static DAL__COLD int monitor_outcome(dal_state *st, int mr) {
  // a state the monitor could not have evaluated (it saw NULL products) fails the run there
  int rc = dal__lazy_end(st, "the output time");
  if (rc) return rc;
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

// run the monitor at the state's time; 1 = stop requested (ok), negative = failure
static int call_monitor(const dal_system *sys, dal_state *st, dal_monitor_fn *monitor, void *ctx) {
  if (!monitor) return 0;
  st->err[0] = 0; // a monitor of the library (dal_csv_monitor) leaves its reason here
  st->lazy_rc = 0;
  int mr = monitor(sys, st, ctx);
  st->lazy = 0;
  return mr || st->lazy_rc ? monitor_outcome(st, mr) : 0;
}

// the state where the run stops, evaluated there; keeps the message already set
static int stop_here(run *r, int status) {
  char msg[DAL_ERRMSG_LEN];
  memcpy(msg, r->st->err, sizeof msg);
  int rc = evaluate_here(r->sys, r->st);
  if (rc && status < 0) {
    // already a failure (the evaluation at this time is what failed): keep its message
    memcpy(r->st->err, msg, sizeof msg);
    return r->status = status;
  }
  if (rc) return r->status = rc;
  memcpy(r->st->err, msg, sizeof msg);
  r->status = status;
  return DAL__HOOK_STOP;
}

// the output at time t is in the state (placed inside the step just taken, or the state's own
// time when at_state): the next output time, then the monitor
static inline int output_done(run *r, double t, int at_state) {
  dal_state *st = r->st;
  r->last_out = t;
  r->k++;
  r->tnext = out_time(r);
  // opts.max_steps per output (after_step tells the integrator once per step)
  if (at_state && r->h) r->h->it->ops->new_output(r->h->it);
  if (!r->monitor) return DAL_OK;
  // the monitor reads the state; products are evaluated on its first read (dal__lazy_eval)
  st->lazy = !at_state;
  int mr = call_monitor(r->sys, st, r->monitor, r->ctx);
  if (mr == 0) return DAL_OK;
  return stop_here(r, mr > 0 ? DAL_STOPPED : mr);
}

// serve the output at the state's own time
static int serve_output(run *r) { return output_done(r, r->st->t, 1); }

// serve the next output time, inside the step just taken
static int serve_next(run *r) {
  dal_integ *it = r->h->it;
  int rc = it->ops->place(it, r->tnext);
  if (rc) return r->status = rc;
  return output_done(r, r->tnext, 0);
}

// the cancel hook asked to stop after the step just taken: the state at its end, evaluated
static DAL__COLD int cancel_here(run *r) {
  dal_integ *it = r->h->it;
  int rc = it->ops->place_end(it);
  if (rc) return r->status = rc;
  DAL_FAIL(r->st, DAL_CANCELLED,
           "%s cancelled by the caller's cancel hook at t=%.17g (the last accepted step; the "
           "state holds it)",
           r->what, r->st->t);
  return stop_here(r, DAL_CANCELLED);
}

// after every accepted step [a, b]: the trajectory's records, then the outputs and event
// crossings inside it in time order, each served by the integrator handle (its window and dense
// output)
static int after_step(void *p) {
  run *r = p;
  dal_state *st = r->st;
  dal_integ *it = r->h->it;
  double a = 0, b = 0;
  it->ops->window(it, &a, &b);
  int rc, np = 0, kp = 0;
  if (st->traj && (rc = dal__traj_step(st->traj, it)) != 0) {
    // out of memory: the run stops at the step's end, evaluated
    char msg[DAL_ERRMSG_LEN];
    memcpy(msg, st->err, sizeof msg);
    if (it->ops->place_end(it) == 0 && evaluate_here(r->sys, st) == 0)
      memcpy(st->err, msg, sizeof msg);
    return r->status = rc;
  }
  if (r->ev) {
    if ((rc = dal__events_scan(r->ev, it)) != 0) {
      // a failing event function: the run stops at the step's end, evaluated
      char msg[DAL_ERRMSG_LEN];
      memcpy(msg, st->err, sizeof msg);
      if (it->ops->place(it, b) == 0 && evaluate_here(r->sys, st) == 0)
        memcpy(st->err, msg, sizeof msg);
      return r->status = rc;
    }
    np = dal__events_npending(r->ev);
  }
  long k0 = r->k;
  for (;;) {
    double te = kp < np ? dal__events_pending(r->ev, kp)->t : INFINITY, lim = te < b ? te : b;
    // the outputs up to the next event crossing (an output first at a tie) or the step's end
    while (r->tnext <= lim)
      if ((rc = serve_next(r)) != 0) return rc;
    if (!(te <= b)) break;
    const dal__pending *e = dal__events_pending(r->ev, kp++);
    if ((rc = it->ops->place(it, e->t)) != 0 ||
        (rc = dal__events_record(r->ev, st, e->event, e->dir)) != 0)
      return r->status = rc;
    if (dal__events_terminal(r->ev, e->event)) {
      DAL_FAIL(st, DAL_EVENT, "event '%s' (%s) at t=%.17g: stopped there as asked",
               dal__events_item_name(r->ev, e->event), e->dir > 0 ? "rising" : "falling", e->t);
      return stop_here(r, DAL_EVENT);
    }
  }
  // opts.max_steps counts from the last output
  if (r->k != k0) it->ops->new_output(it);
  // the caller's cancel hook: the run ends at this accepted step, evaluated
  if (r->o->cancel && r->o->cancel(r->o->cancel_ctx)) return cancel_here(r);
  return DAL_OK;
}

// advance the run to t1 >= st->t with validated arguments
static int run_steps(run *r, double t1) {
  const dal_system *sys = r->sys;
  dal_state *st = r->st;
  int rc = ensure_integ(sys, st, r->o, (r->outputs && r->monitor) || st->traj);
  if (rc) return rc;
again:;
  dal_integ_handle *h = st->integ;
  r->h = h;
  if (t1 == st->t) return evaluate_here(sys, st);
  if (t1 - st->t <= DAL_TINY_STEP(st->t)) {
    // an interval of a few ulps: no step can be taken over it. When the state does not move
    // there beyond the tolerances, restart the integrator at the new time; else refuse
    if ((rc = check_unresolved(sys, st, r->o, t1, r->what)) != 0) return rc;
    dal__integ_reset(st);
    r->h = NULL; // freed with it
    st->t = t1;
    return evaluate_here(sys, st);
  }
  // the hook only when someone looks: a monitor at output times, events, or a trajectory
  // (the cancel hook alone asks after every step but reads no dense output: same steps)
  int dense = (r->outputs && r->monitor) || r->ev || st->traj;
  int hooked = dense || r->o->cancel;
  if (r->ev && (rc = dal__events_begin(r->ev, st)) != 0) return rc;
  r->status = DAL_OK;
  h->it->dense_steps = dense;
  rc = h->it->ops->advance(h->it, t1, hooked ? after_step : NULL, r);
  if (rc == DAL__HOOK_STOP) {
    // the hook left the state where the run stops, evaluated; the integrator is elsewhere
    dal__integ_reset(st);
    r->h = NULL; // freed with it
    return r->status;
  }
  if (rc && h->it->can_fall_back && can_fall_back(r->o, rc) && st->t < t1) {
    // the fallback from the last accepted step (its own failure is returned as it is)
    r->h = NULL;
    int frc = fall_back(sys, st, r->o, rc);
    if (frc) return frc;
    goto again;
  }
  if (rc && h->why[0] && rc != DAL__HOOK_STOP) {
    // the fallback failed too: its reason, and IDA's before it
    char msg[2 * DAL_ERRMSG_LEN];
    snprintf(msg, sizeof msg,
             "%.300s; this run had fallen back from IDA's GGL form, which "
             "stopped with: %s",
             st->err, h->why);
    msg[sizeof st->err - 1] = 0; // cut to the state's message length
    memcpy(st->err, msg, sizeof st->err);
  }
  if (rc) {
    // the state holds the last accepted step (or the failing callback's time); the next
    // call restarts the integrator there
    dal__integ_reset(st);
    r->h = NULL; // freed with it
    return rc;
  }
  st->err[0] = 0;
  if (h->note[0]) memcpy(st->err, h->note, sizeof st->err);
  if (h->it->run_note[0]) {
    // a tolerance raised during the run (after the creation's notes)
    size_t used = strlen(st->err);
    snprintf(st->err + used, sizeof st->err - used, "%s%s", used ? "; " : "", h->it->run_note);
  }
  handle_sync(sys, st, h);
  return DAL_OK;
}

// run_steps, recorded into the state's trajectory when one is attached
static int run_to(run *r, double t1) {
  dal_trajectory *tr = r->st->traj;
  int rc = tr && t1 > r->st->t ? dal__traj_begin(tr, r->st) : DAL_OK;
  if (!rc) rc = run_steps(r, t1);
  if (tr) dal__traj_end(tr, r->st->t);
  return rc;
}

static dal_events *active_events(const dal_state *st) {
  return st->events && dal_events_size(st->events) > 0 ? st->events : NULL;
}

// common argument checks of advance and evolve
static int check_call(const dal_system *sys, dal_state *st, const dal_solve_opts *o, double t1,
                      const char *what) {
  int pair = dal__check_pair(sys, st, what);
  if (pair) return pair;
  if ((pair = dal__check_idle(st, what)) != 0) return pair;
  int rc = dal__check_opts(st, o);
  if (rc) return rc;
  if (!isfinite(t1))
    return DAL_FAIL(st, DAL_E_NONFINITE, "%s: target time is %g; give a finite time", what, t1);
  // a step bound below the spacing of doubles at t cannot move t (the fixed step counts for
  // the methods that take it: RK4, and DOPRI5/Fehlberg with fixed_erk)
  int fixed = dal__method_fixed(o->method, o);
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
  run r = {.sys = sys,
           .st = st,
           .o = &eff,
           .what = "advance",
           .t1 = t1,
           .tnext = INFINITY,
           .ev = active_events(st)};
  // the state (and its events) belong to the run until it returns (dal__check_idle refuses
  // its callbacks)
  st->busy = 1;
  if (r.ev) dal__events_hold(r.ev, 1);
  rc = run_to(&r, t1);
  if (r.ev) dal__events_hold(r.ev, 0);
  st->busy = 0;
  return rc;
}

// the output grid t0 + k dt of dal_evolve, checked, into r
static int grid_setup(run *r, double dt) {
  dal_state *st = r->st;
  if (!isfinite(dt))
    return DAL_FAIL(st, DAL_E_NONFINITE,
                    "evolve: output interval dt = %g is not finite; give a positive finite dt", dt);
  if (!(dt > 0))
    return DAL_FAIL(st, DAL_E_ARG, "evolve: output interval dt = %g must be positive", dt);
  double t0 = r->t0, t1 = r->t1, span = (t1 - t0) / dt;
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
  // K = number of whole output intervals: t0 + K dt <= t1 in floating point
  long K = (long)floor(span);
  while (K > 0 && t0 + (double)K * dt > t1)
    --K;
  while (t0 + (double)(K + 1) * dt <= t1)
    ++K;
  r->dt = dt;
  r->K = K;
  return DAL_OK;
}

// the output times of dal_evolve_at, checked (naming the index), into r
static int list_setup(run *r, const double *times, size_t n) {
  dal_state *st = r->st;
  if (!times || n == 0)
    return DAL_FAIL(st, DAL_E_ARG,
                    "evolve_at: no output times (times %s, n = %zu); give at least one time, the "
                    "last being the end of the run",
                    times ? "given" : "NULL", n);
  for (size_t i = 0; i < n; ++i) {
    if (!isfinite(times[i]))
      return DAL_FAIL(st, DAL_E_NONFINITE, "evolve_at: times[%zu] = %g is not finite", i, times[i]);
    if (i > 0 && times[i] < times[i - 1])
      return DAL_FAIL(st, DAL_E_ARG,
                      "evolve_at: times[%zu] = %.17g lies before times[%zu] = %.17g; the output "
                      "times must be non-decreasing (integration runs forward)",
                      i, times[i], i - 1, times[i - 1]);
  }
  if (times[0] < st->t)
    return DAL_FAIL(st, DAL_E_TIME,
                    "evolve_at: times[0] = %.17g lies behind the current time %.17g; integration "
                    "runs forward only (reset the state with dal_state_set to go back)",
                    times[0], st->t);
  r->times = times;
  r->K = (long)n - 1;
  return DAL_OK;
}

// the output times of a call: dal_evolve's grid of dt, or dal_evolve_at's list times[0 .. n)
typedef struct out_spec {
  int list;
  double dt;
  const double *times;
  size_t n;
} out_spec;

// dal_evolve and dal_evolve_at with checked (system, state, options, t1)
static int evolve(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t1,
                  const out_spec *os, dal_monitor_fn *monitor, void *ctx) {
  dal_solve_opts eff = dal__effective_opts(opts);
  double t0 = st->t;
  run r = {.sys = sys,
           .st = st,
           .o = &eff,
           .what = "evolve",
           .outputs = 1,
           .t0 = t0,
           .t1 = t1,
           .k = 0,
           .last_out = -INFINITY,
           .monitor = monitor,
           .ctx = ctx,
           .ev = active_events(st)};
  int rc = os->list ? list_setup(&r, os->times, os->n) : grid_setup(&r, os->dt);
  if (rc) return rc;
  if (!monitor) {
    // no one looks at the output times: dal_advance's run to t1 (solve.h), never a walk over
    // every output time (t1 = 1000, dt = 1e-9 took an hour; issue 31)
    run a = {
        .sys = sys, .st = st, .o = &eff, .what = r.what, .t1 = t1, .tnext = INFINITY, .ev = r.ev};
    return run_to(&a, t1);
  }
  r.tnext = out_time(&r);
  // the start (made consistent first in redundant coordinates), evaluated
  if ((rc = run_to(&r, t0)) != 0) return rc;
  // an interval of a few ulps that cannot be integrated is refused before any output
  if (t1 > t0 && t1 - t0 <= DAL_TINY_STEP(t0) &&
      (rc = check_unresolved(sys, st, &eff, t1, "evolve")))
    return rc;
  // the output times at the start (the grid's first), then the steps serve the others
  while (r.tnext <= st->t)
    if ((rc = serve_output(&r)) != 0) return rc == DAL__HOOK_STOP ? r.status : rc;
  if (t1 > st->t && (rc = run_to(&r, t1)) != 0) return rc;
  // outputs the steps did not reach (t1 itself after a step of a few ulps): the final state
  while (r.tnext <= t1)
    if ((rc = serve_output(&r)) != 0) return rc == DAL__HOOK_STOP ? r.status : rc;
  return DAL_OK;
}

// the public evolve calls: checks, then the state (and its events) belong to the run until it
// returns (dal__check_idle refuses its callbacks)
static int evolve_held(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t1,
                       const out_spec *os, dal_monitor_fn *monitor, void *ctx) {
  int rc = check_call(sys, st, opts, t1, os->list ? "evolve_at" : "evolve");
  if (rc) return rc;
  dal_events *ev = active_events(st);
  st->busy = 1;
  if (ev) dal__events_hold(ev, 1);
  rc = evolve(sys, st, opts, t1, os, monitor, ctx);
  if (ev) dal__events_hold(ev, 0);
  st->busy = 0;
  return rc;
}

int dal_evolve(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t1,
               double dt, dal_monitor_fn *monitor, void *ctx) {
  const out_spec os = {.dt = dt};
  return evolve_held(sys, st, opts, t1, &os, monitor, ctx);
}

int dal_evolve_at(const dal_system *sys, dal_state *st, const dal_solve_opts *opts,
                  const double *times, size_t n, dal_monitor_fn *monitor, void *ctx) {
  // the end time is the last output time; the list itself is checked later (naming the index)
  double t1 = st ? st->t : 0.0;
  if (st && times && n > 0 && isfinite(times[n - 1]) && times[n - 1] > t1) t1 = times[n - 1];
  const out_spec os = {.list = 1, .times = times, .n = n};
  return evolve_held(sys, st, opts, t1, &os, monitor, ctx);
}
