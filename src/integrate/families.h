// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The integrator families under the handle (private to integrate/): the IDA level (ida.c) and
// the ODE level (ode.c, its methods, the first-order problems of first_order.c). Only integ.c
// and the families themselves include it; the layers above see integrate.h alone (dal_integ).
#ifndef DAL_INTEGRATE_FAMILIES_H
#define DAL_INTEGRATE_FAMILIES_H

#include "integrate.h"

/// DAE integration through SUNDIALS IDA for the GGL, index-3 and BDF index-1 forms
/// (ida.c). create: allocate and initialize from the state's consistent (q, qdot);
/// advance: integrate to tout, leaving the state at tout (or at the last accepted step on
/// failure, with its error message naming time and dominating variable).
int dal__ida_create(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, void **mem);
int dal__ida_advance(const dal_system *sys, dal_state *st, void *mem, double tout);
void dal__ida_free(void *mem);
/// dense output of the IDA route: with a hook set, advance takes one step at a time and calls
/// hook(ctx) after each (0: go on, DAL__HOOK_STOP: stop, negative: fail); window gives the
/// step just taken; place puts the state's (t, q, qdot, W) at t in that window from IDA's
/// interpolating polynomial (no evaluation)
void dal__ida_set_hook(void *mem, int (*hook)(void *ctx), void *ctx);
void dal__ida_window(const void *mem, double *t0, double *t1);
int dal__ida_place(void *mem, double t);
/// after a run that retreated from below DAL_IDA_TOL_FLOOR to it: the note for the state's
/// message ("note: ..."), else ""
const char *dal__ida_note(const void *mem);

/// The operations of an ODE method (GSL's gsl_odeiv2_step_type): one const table per method,
/// which its create function sets into ig->ops with ig->impl.
typedef struct dal_ode_ops {
  /// integrate from t to tout (> t); on failure call dal__ode_fail. Returns 0 at tout, a
  /// negative status, or DAL__HOOK_STOP when the after-step hook stopped the run (the state
  /// then holds what the hook left in it; the integrator's own (t, y) is the accepted step).
  /// Callers go through dal__ode_advance.
  int (*advance)(dal_ode_integ *ig, double tout);
  /// free ig->impl
  void (*free_impl)(void *impl);
  /// y at any t in [tprev, t] into yout (ny) from the method's own interpolant, accurate to
  /// the method's tolerance; NULL: the cubic Hermite of ode_hermite (ode.c) is used.
  /// Returns 0 or a negative status. Must not change the integration (no state of the method
  /// is touched); may use ig->st as workspace.
  int (*interp)(dal_ode_integ *ig, double t, double *yout);
  /// the method's slope f(t, y) at the end of the last step, when it has it for free (the
  /// last stage of an FSAL method); NULL: evaluated
  int (*end_slope)(dal_ode_integ *ig, double *f);
  /// the caller changed ig->y[i0 .. ny) at ig->t between advance calls (a reorthonormalized
  /// tangent): go on from there, the rest of the method's memory kept (the compensation of the
  /// unchanged components, the step size); NULL: the caller makes a fresh integrator instead
  /// (dal__ode_changed_y)
  void (*changed_y)(dal_ode_integ *ig, int i0);
} dal_ode_ops;
/// An ODE integrator run on a dal_ode_problem (arkode.c, cvode.c, bs.c,
/// rk4.c). The common part lives here; `impl` holds the method's own memory. Everything a
/// step needs is allocated by the method's create function.
struct dal_ode_integ {
  const dal_ode_problem *prob;
  const dal_system *sys;
  dal_state *st;
  dal_solve_opts opts; ///< copy of the options the integrator was created with
  double rtol, atol;   ///< local tolerances of the error control (dal__tol_factor applied)
  dal_method method;   ///< resolved method (never AUTO)
  int ny;              ///< size of y
  double t;            ///< time of the last accepted step
  double tout;         ///< target of the current advance call
  long ncall;          ///< steps accepted in the current advance call (for opts.max_steps)
  double *y;           ///< solution at the last accepted step (ny)
  double *ydot;        ///< scratch (ny) for the final evaluation
  double *ewt;         ///< scratch (ny): error weights or scaled local errors of the last try
  int rhs_rc;          ///< return code of the last right-hand-side call
  int rhs_fatal;       ///< first negative right-hand-side code of this advance call (0: none)
  int ntiny;           ///< consecutive accepted steps of a few ulps of t (step size collapse)
  double tiny_t;       ///< time of the last step dal__ode_collapsed counted
  int nrecov;          ///< recoverable right-hand-side failures in this advance call
  double recov_t;      ///< time of the last of them
  int recov_rc;        ///< its retry code (DAL__RECOVERABLE, DAL__RETRY_*): the cause
  char rhs_err[DAL_ERRMSG_LEN]; ///< message of the last failing right-hand-side call
  char sun_err[DAL_ERRMSG_LEN]; ///< last message of the SUNDIALS error handler
  void *impl;                   ///< method memory
  const dal_ode_ops *ops;       ///< the method's operations (set by its create function)
  // dense output (driver.c): after every accepted step from tprev to t, dal__ode_accept calls
  // hook(hook_ctx); the hook reads the solution anywhere in [tprev, t] through interp
  double tprev;  ///< start of the last accepted step (= t before the first step)
  double *yprev; ///< y at tprev (ny): kept by dal__ode_accept for the Hermite fallback
  /// after-step hook (NULL: none): 0 to go on, DAL__HOOK_STOP to stop, negative to fail
  int (*hook)(void *ctx);
  void *hook_ctx;
  /// the hook reads the steps' dense output (outputs, events, a stored trajectory); 0 when it
  /// only asks the caller's cancel hook, which must not change the steps (Bulirsch-Stoer's
  /// dense mode would)
  int dense;
  /// where dal__ode_place writes y (borrowed): the state's (q, qdot) block itself when
  /// place_direct (the problem has the state's layout, dal_ode_problem.state_layout, and no
  /// work W is integrated), else a scratch of ny that the problem's to_state copies
  double *yplace;
  int place_direct;
  double *hf0, *hf1; ///< Hermite fallback: f at tprev and t (ny each)
  double *hc;        ///< Hermite fallback: the step's cubic, 4 coefficients per component
  /// bit 0: hf0 is current for this step, bit 1: hf1, bit 2: hc, bit 3: hc with place_direct
  /// (dal__ode_place's fast path)
  int hvalid;
};

/// the state's (t, q, qdot, W) at t in [ig->tprev, ig->t] (not evaluated): the accepted values
/// at the step's ends, inside it the method's interpolant or the cubic Hermite fallback (two
/// right-hand sides per step, evaluated on first use; its coefficients once per step), through
/// ig->yplace; 0 or a negative status (ode.c)
int dal__ode_place(dal_ode_integ *ig, double t);
/// the slope f(tprev, yprev) at the start of the last step into ig->hf0, evaluated once per
/// step (the Hermite fallback and Fehlberg's partial step share it); 0 or a public status
int dal__ode_start_slope(dal_ode_integ *ig);
/// integrate ig to tout (> ig->t) with its method, the per-call target and progress guard's
/// counters (opts.max_steps, step size collapse, recoverable failures) reset: returns as
/// dal_ode_ops.advance
int dal__ode_advance(dal_ode_integ *ig, double tout);
/// the caller changed ig->y[i0 .. ny) at ig->t: 1 when the method goes on from there with the
/// rest of its memory kept, 0 when it cannot (make a fresh integrator; nothing was done)
int dal__ode_changed_y(dal_ode_integ *ig, int i0);
/// 1 when dal__ode_changed_y can go on (the method has the operation)
int dal__ode_can_change_y(const dal_ode_integ *ig);
/// the slope f(t, y) at the end of the last step into ig->hf1, once per step: the method's own
/// (end_slope) unless a projection moved y, else evaluated; 0 or a public status
int dal__ode_end_slope(dal_ode_integ *ig);

/// the problem that runs st->fo (first_order.c; its ny is set per run)
extern const dal_ode_problem dal__problem_first_order;
/// The ODE level under dal__integ_create_fo: a fresh ODE integrator for the resolved method
/// meth on fo at time st->t (first_order.c; st->fo = fo while it lives, fo's prob filled). opts:
/// tolerances (a global target, the method's calibrated factor applied as for dal_advance), h0,
/// hmax, fixed_step, max_steps; the formulation, work and projection options are ignored
/// (fo->project runs when set). Destroying the integrator (dal__ode_destroy) lets go of the
/// work state's st->fo.
int dal__ode_create_fo(const dal_system *sys, dal_state *st, const dal_solve_opts *opts,
                       dal_method meth, dal_first_order *fo, dal_ode_integ **out);

/// a fresh ODE integrator for method meth on problem prob at the state's (t, q, qdot), and
/// its destruction (ode.c)
int dal__ode_create(const dal_system *sys, dal_state *st, const dal_solve_opts *o, dal_method meth,
                    const dal_ode_problem *prob, dal_ode_integ **out);
void dal__ode_destroy(void *ig);

/// A SUNDIALS integrator returned at its stop time tout while its own time tn lies more than
/// a few ulps before it: it takes a stop time within 100 ulps of t as reached and extrapolates
/// there, which at large |t| is seconds of motion that did not happen. Fails (DAL_E_STEP,
/// naming the resolution of t and the remedy) with the state at the last accepted step; 0 when
/// tn is tout to a few ulps, or nothing moves over the gap beyond the tolerances.
int dal__ode_tstop_gap(dal_ode_integ *ig, double tn, double tout);
/// The failure of a SUNDIALS step stopped by the right-hand side: the status of its fatal code
/// (else of its last recoverable one), its message, the last accepted step and the target.
int dal__ode_rhs_fail(dal_ode_integ *ig);
/// The same after a SUNDIALS step that returned at tret (at_tstop: at the stop time tout) with
/// its own time tn and last step hlast: the time moved by the step integrated is tn, or
/// t + hlast where the library snapped its time to the stop time (CVODE and ERKStep take a
/// stop time within 100 ulps of t as reached).
int dal__ode_step_gap(dal_ode_integ *ig, double tret, double tn, double hlast, int at_tstop,
                      double tout);

/// y' = f(t, y) through the problem with at least the products `need`, and W' = dE/dt as the
/// last component when opts.work is set (not counted; no failure bookkeeping)
int dal__ode_eval(dal_ode_integ *ig, double t, const double *y, double *ydot, unsigned need);
/// the state's (t, q, qdot) and W from y (does not evaluate)
void dal__ode_to_state(dal_ode_integ *ig, double t, const double *y);
/// y' = f(t, y) through the problem, counting evaluations and keeping the failure message;
/// returns 0, a retry code (DAL__RECOVERABLE, DAL__RETRY_*) or a negative status (ode.c)
int dal__ode_rhs(dal_ode_integ *ig, double t, const double *y, double *ydot);
/// true when the step just taken from ig->t to t is a few ulps of t, several times in a row:
/// the integrator makes no progress (step size collapse). Counts each step once (asking again
/// about the same t gives the same answer).
int dal__ode_collapsed(dal_ode_integ *ig, double t);
/// record an accepted step (t, y): copies y into ig->y, counts the step and, when the problem
/// has a projection and opts.project is set, projects ig->y in place (*projected = 1 then;
/// projected may be NULL). The progress guard of every ODE method: a step that does not
/// advance t, a step size collapse (dal__ode_collapsed) or a non-finite y is a failure with
/// the status of its cause (a retry that kept failing, else DAL_E_STEP or DAL_E_NONFINITE).
/// Returns 0 or a negative status (the state then holds the step before).
int dal__ode_accept(dal_ode_integ *ig, double t, const double *y, int *projected);
/// stop with the state at the last accepted step (ig->t, ig->y), re-evaluated there, and the
/// message fmt... (prefixed to nothing; name time and culprit in it). Returns status.
int dal__ode_fail(dal_ode_integ *ig, int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/// name of component i of y ("coordinate 'x'", "velocity of 'x'") into buf
const char *dal__ode_var_name(const dal_ode_integ *ig, int i, char *buf, size_t len);
/// index of the largest |w[i]| (the dominating variable of an error estimate)
int dal__ode_argmax(const double *w, int n);
/// SUNDIALS error handler of the ODE drivers (ud is the dal_ode_integ): keeps the message in
/// ig->sun_err instead of printing it
void dal__ode_sun_err(int code, const char *module, const char *function, char *msg, void *ud);
/// true when recoverable right-hand-side failures after the last accepted step are what
/// keeps the integrator from advancing (a step collapse is then the callback's doing)
int dal__ode_recov_blocked(const dal_ode_integ *ig);
/// A step size collapse at ig->t (h the step that does not make progress, `what` says how):
/// the status of a retry that kept failing there (dal__ode_recov_fail), else DAL_E_STEP naming
/// the fastest-changing variable. The state goes back to the last accepted step.
int dal__ode_stall(dal_ode_integ *ig, double h, const char *what);
/// the status and message of a step collapse caused by a retry that kept failing (a callback
/// that keeps asking for a smaller step, an overflow, a near-singular matrix; see
/// dal__ode_recov_blocked): the status of that cause; h is the last step size tried
int dal__ode_recov_fail(dal_ode_integ *ig, double h);

/// method constructors: fill ig->impl and ig->ops from ig->y at ig->t
int dal__erk_create(dal_ode_integ *ig);   ///< DOPRI5, FEHLBERG78 (arkode.c)
int dal__cvode_create(dal_ode_integ *ig); ///< ADAMS, BDF (cvode.c)
int dal__bs_create(dal_ode_integ *ig);    ///< Gragg-Bulirsch-Stoer (bs.c)
int dal__rk4_create(dal_ode_integ *ig);   ///< classical RK4, fixed step (rk4.c)
/// CVODE's own dense output for a CVODE integrator ig: CVodeGetDky(t, k) into out (ny), the
/// k-th derivative of the last step's polynomial at t; returns CVODE's code (0: success).
/// For tests: ig->ops->interp reads the same polynomial without a call per output
int dal__cvode_dky(dal_ode_integ *ig, double t, int k, double *out);
/// the outputs of a CVODE integrator that ig->ops->interp served without a CVodeGetDky call (with
/// the Nordsieck columns read by the step's first output)
long dal__cvode_fast_outputs(const dal_ode_integ *ig);
/// for tests: every further output of a CVODE integrator by a CVodeGetDky call (the path taken
/// when CVODE hands over columns of another form than the fast path assumes)
void dal__cvode_slow_dense(dal_ode_integ *ig);

#endif
