// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// One integrator interface: the formulation and method resolved from the method rows, and the
// three families behind one handle (dal_integ): the ODE methods on a formulation's problem, IDA
// on the DAE forms, and the ODE methods on a plain first-order problem (the analyses').
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "form/form.h"
#include "integrate.h"

// ---------------------------------------------------------------------------------------------
// the ODE family: an ODE method on a dal_ode_problem

// the ODE method to tout, the hook called after every accepted step
static int ode_run(dal_integ *it, double tout, int (*hook)(void *ctx), void *ctx) {
  dal_ode_integ *ig = it->impl;
  ig->hook = hook;
  ig->hook_ctx = ctx;
  ig->dense = hook && it->dense_steps;
  int rc = dal__ode_advance(ig, tout);
  ig->hook = NULL;
  return rc;
}

static int ode_advance(dal_integ *it, double tout, int (*hook)(void *ctx), void *ctx) {
  int rc = ode_run(it, tout, hook, ctx);
  if (rc) return rc;
  // the state at tout, evaluated there
  dal_ode_integ *ig = it->impl;
  dal__ode_to_state(ig, ig->t, ig->y);
  return dal__public_status(dal__eval(it->sys, it->st, DAL_P_ALL));
}

static void ode_window(const dal_integ *it, double *t0, double *t1) {
  const dal_ode_integ *ig = it->impl;
  *t0 = ig->tprev;
  *t1 = ig->t;
}

static int ode_place(dal_integ *it, double t) { return dal__ode_place(it->impl, t); }

static int ode_place_end(dal_integ *it) {
  dal_ode_integ *ig = it->impl;
  dal__ode_to_state(ig, ig->t, ig->y);
  dal__state_moved(it->st);
  return DAL_OK;
}

static void ode_new_output(dal_integ *it) {
  dal_ode_integ *ig = it->impl;
  ig->ncall = 0; // opts.max_steps per output
}

static void ode_destroy(dal_integ *it) {
  dal__ode_destroy(it->impl);
  free(it->yi);
}

static const dal_integ_ops ode_ops = {ode_advance,    ode_window,  ode_place, ode_place_end,
                                      ode_new_output, ode_destroy, NULL};

// ---------------------------------------------------------------------------------------------
// the first-order family: an ODE method on a plain first-order problem (dal_first_order)

// to tout within the caller's budget it->opts.max_steps; the work state follows the trajectory
// part of y there (not evaluated: F evaluates what it needs)
static int fo_advance(dal_integ *it, double tout, int (*hook)(void *ctx), void *ctx) {
  dal_ode_integ *ig = it->impl;
  ig->opts.max_steps = it->opts.max_steps;
  int rc = ode_run(it, tout, hook, ctx);
  if (rc == DAL__HOOK_STOP) return rc;
  if (rc) return dal__public_status(rc);
  dal__ode_to_state(ig, ig->t, ig->y);
  return DAL_OK;
}

static int fo_change_y(dal_integ *it, int i0, const double *y) {
  dal_ode_integ *ig = it->impl;
  if (!dal__ode_can_change_y(ig)) return 0;
  memcpy(ig->y + i0, y + i0, (size_t)(ig->ny - i0) * sizeof(double));
  return dal__ode_changed_y(ig, i0);
}

static const dal_integ_ops fo_ops = {fo_advance,     ode_window,  ode_place,  ode_place_end,
                                     ode_new_output, ode_destroy, fo_change_y};

// ---------------------------------------------------------------------------------------------
// the DAE family: IDA on the GGL, index-3 and index-1 forms

static void ida_window(const dal_integ *it, double *t0, double *t1) {
  dal__ida_window(it->impl, t0, t1);
}

static int ida_place(dal_integ *it, double t) { return dal__ida_place(it->impl, t); }

static int ida_place_end(dal_integ *it) {
  double a = 0, b = 0;
  ida_window(it, &a, &b);
  return ida_place(it, b);
}

static void ida_new_output(dal_integ *it) { it->nsteps = 0; }

static void ida_destroy(dal_integ *it) { dal__ida_free(it->impl); }

// after every step IDA takes: the caller's hook, then opts.max_steps counted from the last
// output (IDA's own count runs per advance call)
static int ida_after_step(void *p) {
  dal_integ *it = p;
  it->nsteps++;
  int rc = it->hook(it->hook_ctx);
  if (rc) return rc;
  double a = 0, b = 0;
  ida_window(it, &a, &b);
  if (it->nsteps < it->opts.max_steps || !(b < it->tout)) return DAL_OK;
  dal_state *st = it->st;
  if ((rc = ida_place(it, b)) != 0) return rc;
  DAL_FAIL(st, DAL_E_MAXSTEPS,
           "%ld steps taken at t=%.17g before the next output or the target t=%.17g "
           "(opts.max_steps); raise max_steps or loosen the tolerances",
           it->nsteps, b, it->tout);
  // the state where the run stops, evaluated there, with this message
  char msg[DAL_ERRMSG_LEN];
  memcpy(msg, st->err, sizeof msg);
  if ((rc = dal__public_status(dal__eval(it->sys, st, DAL_P_ALL))) != 0) return rc;
  memcpy(st->err, msg, sizeof msg);
  return DAL_E_MAXSTEPS;
}

static int ida_advance(dal_integ *it, double tout, int (*hook)(void *ctx), void *ctx) {
  it->hook = hook;
  it->hook_ctx = ctx;
  it->nsteps = 0;
  it->tout = tout;
  dal__ida_set_hook(it->impl, hook ? ida_after_step : NULL, it);
  int rc = dal__ida_advance(it->sys, it->st, it->impl, tout);
  if (rc != DAL__HOOK_STOP) rc = dal__public_status(rc);
  snprintf(it->run_note, sizeof it->run_note, "%s", dal__ida_note(it->impl));
  dal__ida_set_hook(it->impl, NULL, NULL);
  return rc;
}

static const dal_integ_ops ida_ops = {ida_advance,    ida_window,  ida_place, ida_place_end,
                                      ida_new_output, ida_destroy, NULL};

// ---------------------------------------------------------------------------------------------
// resolution and creation

dal_solve_opts dal__fallback_opts(const dal_solve_opts *o) {
  dal_solve_opts f = *o;
  f.form = DAL_FORM_INDEX1;
  f.project = 1;
  f.method = DAL_METHOD_BS;
  return f;
}

int dal__fallback_start(const dal_system *sys, dal_state *st, const dal_solve_opts *o) {
  return dal__public_status(dal__dae_start(sys, st, o->init_max_move, NULL));
}

// resolve formulation and method from the rows; *prob is NULL for a DAE form; *tight is set
// when AUTO chose the index-1 form with projection because IDA cannot honour the tolerance
// (solve.h)
static int resolve(const dal_system *sys, dal_state *st, const dal_solve_opts *o, int dense,
                   dal_method *meth, const dal_ode_problem **prob, int *tight) {
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
    // IDA would be clamped at its floor: the fallback formulation honours such tolerances
    // (measured 5.7 x rtol at 1e-12 on the Cartesian pendulum)
    *tight = 1;
    *meth = dal__fallback_opts(o).method;
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
  const dal_method_row *row = dal__method_row(m);
  unsigned fb = DAL__FORM_BIT(form);
  if (!row) return DAL_FAIL(st, DAL_E_UNSUPPORTED, "no integrator for method %d", (int)m);
  if (!(row->ode_forms & fb)) {
    // a DAE form: the method that runs it in IDA
    if (!(row->dae_forms & fb))
      return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                      "formulation '%s' runs only with DAL_METHOD_BDF (IDA), not '%s'; use "
                      "DAL_METHOD_BDF or DAL_METHOD_AUTO, or DAL_FORM_INDEX1 for explicit "
                      "methods",
                      dal_formulation_name(form), dal_method_name(m));
    *meth = dal__dae_method(form);
    *prob = NULL;
    return DAL_OK;
  }
  if (m == DAL_METHOD_AUTO) m = dal__auto_method(o->rtol, sys->n, dense);
  *meth = m;
  *prob = form == DAL_FORM_INDEX1 ? &dal__problem_index1 : &dal__problem_minimal;
  return DAL_OK;
}

// the ODE family's memory, and its note when the method ran at a floor of its own (CVODE's BDF)
static int create_ode(dal_integ *it, const dal_ode_problem *prob) {
  dal_state *st = it->st;
  const dal_solve_opts *o = &it->opts;
  dal_ode_integ *ig = NULL;
  int rc = dal__ode_create(it->sys, st, o, it->method, prob, &ig);
  if (rc) return rc;
  it->ops = &ode_ops;
  it->impl = ig;
  if (!(it->yi = calloc((size_t)ig->ny + 1, sizeof(double))))
    return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the integrator");
  // dense output straight into the state's (q, qdot) where y has its layout
  ig->place_direct = prob->state_layout && !o->work;
  ig->yplace = ig->place_direct ? st->q : it->yi;
  const dal_method_row *mr = dal__method_row(it->method);
  if (mr && o->rtol < mr->min_rtol)
    snprintf(it->note, sizeof it->note,
             "note: rtol %g is below what %s can honour (its error stops falling there): it "
             "ran as rtol %g, atol scaled alike (dal_stats.rtol_used has the local "
             "tolerance), so expect errors above rtol%s",
             o->rtol, mr->name, mr->min_rtol,
             it->method != DAL_METHOD_BS && o->rtol >= dal__method_row(DAL_METHOD_BS)->min_rtol
                 ? "; DAL_METHOD_BS (AUTO's choice there) honours it"
                 : "");
  return DAL_OK;
}

// the DAE family's memory, and its note when IDA ran at its tolerance floor
static int create_ida(dal_integ *it) {
  dal_state *st = it->st;
  const dal_solve_opts *o = &it->opts;
  int rc = dal__public_status(dal__ida_create(it->sys, st, o, &it->impl));
  if (rc) return rc;
  it->ops = &ida_ops;
  it->can_fall_back = 1;
  if (st->stats.rtol_used > o->rtol * dal__dae_tol_factor(o->form))
    snprintf(it->note, sizeof it->note,
             "note: rtol %g is below what IDA can honour: it ran at the local tolerance %g "
             "(the smallest it is tried at, dal_stats.rtol_used), so expect errors above rtol; "
             "DAL_FORM_AUTO with "
             "DAL_METHOD_AUTO runs the index-1 form with projection and Bulirsch-Stoer there",
             o->rtol, st->stats.rtol_used);
  return DAL_OK;
}

// a handle of method meth in formulation form for options o, its family's memory not made yet;
// NULL with the state's message set when out of memory
static dal_integ *integ_alloc(const dal_system *sys, dal_state *st, const dal_solve_opts *o,
                              dal_method meth, dal_formulation form) {
  dal_integ *it = calloc(1, sizeof *it);
  if (!it) {
    DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the integrator");
    return NULL;
  }
  it->sys = sys;
  it->st = st;
  it->opts = *o;
  it->method = meth;
  it->form = form;
  it->traj_pieces = dal__method_row(meth)->traj_pieces;
  return it;
}

// the end of a creation with status rc: the handle into *out, or destroyed
static int integ_done(dal_integ *it, int rc, dal_integ **out) {
  if (rc) {
    dal__integ_destroy(it);
    return rc;
  }
  *out = it;
  return DAL_OK;
}

int dal__integ_create(const dal_system *sys, dal_state *st, const dal_solve_opts *o, int dense,
                      dal_integ **out) {
  *out = NULL;
  dal_method meth = DAL_METHOD_AUTO;
  const dal_ode_problem *prob = NULL;
  int tight = 0;
  int rc = resolve(sys, st, o, dense, &meth, &prob, &tight);
  if (rc) return rc;
  dal_formulation form = prob == &dal__problem_index1 ? DAL_FORM_INDEX1
                         : prob                       ? DAL_FORM_ODE
                         : o->form == DAL_FORM_AUTO   ? DAL_FORM_GGL
                                                      : o->form;
  dal_integ *it = integ_alloc(sys, st, o, meth, form);
  if (!it) return DAL_E_NOMEM;
  if (tight) {
    // the fallback formulation starts from a consistent state too
    it->opts = dal__fallback_opts(o);
    rc = dal__fallback_start(sys, st, o);
  }
  if (!rc) rc = prob ? create_ode(it, prob) : create_ida(it);
  return integ_done(it, rc, out);
}

int dal__integ_create_fo(const dal_system *sys, dal_state *st, const dal_solve_opts *o,
                         dal_first_order *fo, dal_integ **out) {
  *out = NULL;
  dal_method meth = DAL_METHOD_AUTO;
  int rc = dal__fo_method(st, o->method, o->rtol, DAL__CAP_FIRST_ORDER, NULL, &meth);
  if (rc) return rc;
  dal_integ *it = integ_alloc(sys, st, o, meth, DAL_FORM_ODE);
  if (!it) return DAL_E_NOMEM;
  it->opts.method = meth;
  dal_ode_integ *ig = NULL;
  if ((rc = dal__ode_create_fo(sys, st, &it->opts, meth, fo, &ig)) == 0) {
    it->ops = &fo_ops;
    it->impl = ig;
    it->y = ig->y;
    it->ny = ig->ny;
    // dense output of y into a scratch, the trajectory part copied into the state
    if (!(it->yi = calloc((size_t)ig->ny + 1, sizeof(double))))
      rc = DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the integrator");
    ig->yplace = it->yi;
  }
  return integ_done(it, rc, out);
}

void dal__integ_destroy(dal_integ *it) {
  if (!it) return;
  if (it->ops) it->ops->destroy(it);
  free(it);
}
