// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The integration layer's face: one integrator interface (dal_integ, integ.c) over the ODE
// methods and IDA, the method table, and the services the ODE methods share.
#ifndef DAL_INTEGRATE_INTEGRATE_H
#define DAL_INTEGRATE_INTEGRATE_H

#include "form/form.h"

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

/// An ODE integrator run on a dal_ode_problem (arkode.c, cvode.c, bs.c,
/// rk4.c). The common part lives here; `impl` holds the method's own memory. Everything a
/// step needs is allocated by the method's create function.
typedef struct dal_ode_integ dal_ode_integ;
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

/// the after-step hook asked the integration to stop (a terminal event, a monitor's stop)
#define DAL__HOOK_STOP 1000

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

/// A first-order problem y' = F(t, y) of any size that is not a formulation of the system:
/// the tangent (Lyapunov) and variational integrations of analysis/ run on the library's ODE
/// methods through it, behind the integrator handle (dal__integ_create_fo; GSL's
/// gsl_odeiv2_system). y starts with the trajectory (q, qdot) of the system (the state follows
/// it in messages and on failure); the rest is the problem's own (tangent vectors,
/// sensitivities). A constrained tangent plugs in with its own rhs and, where it has a
/// manifold, a projection.
typedef struct dal_first_order {
  int ny;           ///< size of y (>= 2n)
  const double *y0; ///< y at the start (ny; read at creation)
  /// f = F(t, y) (ny each); 0, a retry code (DAL__RECOVERABLE, DAL__RETRY_*) or a negative
  /// status with the work state's message set; may use the work state as scratch
  int (*rhs)(void *ctx, dal_state *st, double t, const double *y, double *f);
  /// project y onto the problem's invariant manifold at t, in place (0 or a status); NULL: none
  int (*project)(void *ctx, dal_state *st, double t, double *y);
  void *ctx; ///< passed to rhs and project
  /// factor on the method's local tolerance for this problem (as dal_ode_problem's); 0: 1
  double tol_factor;
  dal_ode_problem prob; ///< filled by dal__ode_create_fo (the problem the integrator runs)
} dal_first_order;
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

/// the bit of formulation f in a method row's formulation sets
#define DAL__FORM_BIT(f) (1u << (unsigned)(f))
/// the formulations that are first-order ODE problems (dal_ode_problem)
#define DAL__ODE_FORMS (DAL__FORM_BIT(DAL_FORM_ODE) | DAL__FORM_BIT(DAL_FORM_INDEX1))
/// the formulations that are DAEs in IDA's residual form
#define DAL__DAE_FORMS                                                                             \
  (DAL__FORM_BIT(DAL_FORM_GGL) | DAL__FORM_BIT(DAL_FORM_INDEX3) | DAL__FORM_BIT(DAL_FORM_INDEX1))

/// One row per integration method (GSL's gsl_odeiv2_step_type): adding a method is one row
/// in methods.c and one file. `tol_factor`: the method's local error control runs at
/// tol_factor * rtol, tol_factor * atol (not below DAL_TOL_FLOOR), so that the global error
/// tracks the requested tolerance (measurements in solve.h; like RADAU5's tolerance
/// transformation, Hairer-Wanner, Solving ODEs II, sec. IV.8). `ode_create` runs the method
/// on an ODE problem (NULL: none). `ode_forms`: the formulations (DAL__FORM_BIT) the method
/// runs as an ODE problem; `dae_forms`: those it runs as a DAE in IDA (AUTO: those it hands to
/// the DAE method). `min_rtol`: the tightest request the method honours on an ODE problem (0:
/// down to DAL_TOL_FLOOR / tol_factor); a tighter one runs as min_rtol, atol scaled alike, and
/// the clamp shows in dal_stats.rtol_used. `fixed`: the method takes opts.fixed_step (1), or
/// does with opts.fixed_erk (2), or not (0). `caps`: what a caller may ask of it (DAL__CAP_*).
/// `traj_pieces`: records per accepted step of a stored trajectory (dal_trajectory: degree 8
/// each; Bulirsch-Stoer's long steps take 4).
typedef struct dal_method_row {
  dal_method id;
  const char *name;
  double tol_factor;
  int (*ode_create)(dal_ode_integ *ig);
  unsigned ode_forms, dae_forms;
  double min_rtol;
  int fixed;
  unsigned caps;
  int traj_pieces;
} dal_method_row;
/// The capabilities of a method row:
enum {
  /// runs a plain first-order problem y' = F(t, y) (dal__integ_create_fo): tangent vectors,
  /// variational equations
  DAL__CAP_FIRST_ORDER = 1u << 0,
  /// explicit: no Newton or fixed-point iteration per step (the variational equations of
  /// dal_state_transition ask for one: an implicit method would iterate on all of Phi and S)
  DAL__CAP_EXPLICIT = 1u << 1,
  /// structure-preserving fixed-step method (symplectic.c): no error control, no work
  /// tracking, its own formulation (dal__symplectic_resolve)
  DAL__CAP_SYMPLECTIC = 1u << 2,
};
/// the row of a method (AUTO has a row too, with no create function)
const dal_method_row *dal__method_row(dal_method m);
/// 1 when method m takes a fixed step with options o (its row's `fixed`: always, or with
/// o->fixed_erk), else 0
int dal__method_fixed(dal_method m, const dal_solve_opts *o);
/// 1 when method m's row has every capability in caps (DAL__CAP_*); 0 for an unknown method
int dal__method_can(dal_method m, unsigned caps);
/// The methods whose rows have every capability in caps, as "DOPRI5, Fehlberg 7(8), ..." for a
/// message (the rows' order; AUTO not listed) into buf; returns buf
const char *dal__methods_that_can(unsigned caps, char *buf, size_t len);
/// AUTO on a plain first-order problem (tangent vectors, variational equations) by relative
/// tolerance, among the methods with the capabilities caps (DAL__CAP_FIRST_ORDER at least):
/// DOPRI5 above rtol 1e-6, Adams down to 1e-12, Bulirsch-Stoer below; a method without caps
/// gives way to the next one that has them (validated on the tangent system of
/// tests/test_analysis_lyapunov.c, not on plain trajectories as dal__auto_method)
dal_method dal__auto_method_fo(double rtol, unsigned caps);
/// The method that runs a first-order problem asking the capabilities caps (DAL__CAP_FIRST_ORDER
/// is always asked; DAL__CAP_EXPLICIT for the variational equations) under the request m at
/// relative tolerance rtol: m itself, or for AUTO dal__auto_method_fo's choice, into *out. 0, or
/// DAL_E_UNSUPPORTED with st's message naming m, what the problem asks and the methods that
/// can (prefixed "what: " when what is not NULL)
int dal__fo_method(dal_state *st, dal_method m, double rtol, unsigned caps, const char *what,
                   dal_method *out);
/// the method that runs formulation form as a DAE (the first row other than AUTO whose
/// dae_forms holds it), or DAL_METHOD_AUTO when none does
dal_method dal__dae_method(dal_formulation form);
/// local tolerance factor of a method (its row's tol_factor)
double dal__tol_factor(dal_method m);

/// The fallback formulation (solve.h), written once: index-1 with projection after every step
/// and Bulirsch-Stoer. AUTO runs it where IDA cannot honour the tolerance (integ.c), and the
/// driver goes on with it where IDA stopped (dal_stats.fallbacks). The options that run it,
/// from the caller's o (integ.c).
dal_solve_opts dal__fallback_opts(const dal_solve_opts *o);
/// its consistent start at the state's (t, q, qdot) (within o->init_max_move): 0 or a public
/// status with the state's message set (integ.c)
int dal__fallback_start(const dal_system *sys, dal_state *st, const dal_solve_opts *o);

/// the automatic method for an ODE formulation by relative tolerance and number of
/// coordinates n, and whether a monitor reads dense outputs (rule in solve.h)
dal_method dal__auto_method(double rtol, int n, int dense);
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

/// One integrator behind one interface, whatever its family (an ODE method on a formulation's
/// dal_ode_problem, IDA on a DAE form, an ODE method on a plain first-order problem): the
/// driver, the events, the stored trajectory and the analyses talk to nothing else (GSL's evolve
/// object over its step types). Created from the method rows by dal__integ_create and
/// dal__integ_create_fo.
typedef struct dal_integ dal_integ;
typedef struct dal_integ_ops {
  /// integrate from the state's time to tout (> it); after every accepted step hook(ctx) when
  /// hook is set (0: go on, DAL__HOOK_STOP: stop, negative: fail). Returns 0 with the state at
  /// tout, evaluated; DAL__HOOK_STOP (the state is what the hook left); or a negative public
  /// status with the state at the last accepted step, evaluated, its message naming the cause.
  /// A first-order problem's: the work state's (t, q, qdot) at tout, not evaluated (F evaluates
  /// what it needs); its budget is it->opts.max_steps steps per call, read at every call
  int (*advance)(dal_integ *it, double tout, int (*hook)(void *ctx), void *ctx);
  /// the step just taken, [*t0, *t1] (both the start before the first step); after an advance
  /// without hook a method that steps past tout and interpolates back (CVODE) gives [tout, tout]
  void (*window)(const dal_integ *it, double *t0, double *t1);
  /// the state's (t, q, qdot, W) at t in the step just taken from the method's dense output
  /// (not evaluated); 0 or a negative status
  int (*place)(dal_integ *it, double t);
  /// the state's (t, q, qdot, W) at the end of the step just taken: the accepted step itself,
  /// not its interpolant (not evaluated); 0 or a negative status
  int (*place_end)(dal_integ *it);
  /// an output was served inside the step: opts.max_steps counts from here
  void (*new_output)(dal_integ *it);
  void (*destroy)(dal_integ *it);
  /// a first-order problem's y[i0 .. ny) replaced by y[i0 .. ny) at the time of the last
  /// accepted step (a reorthonormalized tangent): 1 when the method goes on from there with the
  /// rest of its memory kept (the compensation of the unchanged components, the step size), 0
  /// when it cannot (nothing changed: create a fresh integrator there). NULL for the
  /// formulations' families
  int (*change_y)(dal_integ *it, int i0, const double *y);
} dal_integ_ops;
struct dal_integ {
  const dal_integ_ops *ops;
  const dal_system *sys;
  dal_state *st;
  dal_solve_opts opts;  ///< the options it runs with (the automatic choice's form set)
  dal_method method;    ///< resolved method (never AUTO)
  dal_formulation form; ///< resolved formulation (never AUTO; a first-order problem: ODE)
  /// a failure of the Newton iteration or a step size collapse may be retried from the last
  /// accepted step in another formulation (the fallback ladder, docs/dae.md)
  int can_fall_back;
  /// records per accepted step of a stored trajectory (dal_trajectory: degree 8 each); a
  /// method whose interpolant has a higher degree over its long steps takes more (BS: 4)
  int traj_pieces;
  /// set by the driver before advance: the hook reads the steps' dense output (0: the hook, if
  /// any, only asks the cancel hook)
  int dense_steps;
  /// what creation did not honour as asked (a tolerance raised to a floor): "note: ..." for the
  /// state's message on success, or empty
  char note[DAL_ERRMSG_LEN];
  /// what a run did not honour as asked after creation (IDA's local tolerance raised to its
  /// floor after a failed step below it): "note: ..." for the state's message, or empty
  char run_note[DAL_ERRMSG_LEN];
  /// a first-order problem's y at the last accepted step (ny; borrowed, valid while the
  /// integrator lives); NULL for the formulations' families
  const double *y;
  int ny;
  void *impl; ///< the family's memory (dal_ode_integ, IDA's)
  // after-step hook of the current advance call and the steps since the last output (the
  // families that do not count opts.max_steps themselves)
  int (*hook)(void *ctx);
  void *hook_ctx;
  long nsteps;
  double tout;
  double *yi; ///< dense output scratch of the ODE families (ny)
};
/// Resolve formulation and method for options o from the method rows (dense: a monitor reads
/// outputs between the steps, which AUTO takes into account) and create the integrator at the
/// state's current point. Where AUTO runs the index-1 form with projection because IDA cannot
/// honour the tolerance, the consistent start is made first (it->opts says so). 0 or a
/// negative public status with the state's message set (integ.c)
int dal__integ_create(const dal_system *sys, dal_state *st, const dal_solve_opts *o, int dense,
                      dal_integ **out);
/// An integrator on the first-order problem fo at time st->t, behind the same handle: st is a
/// work state the integrator owns while it lives (fo must outlive it). The method is
/// o->method, or for AUTO the rule of the first-order problems (dal__fo_method); a method that
/// does not run one is refused (DAL_E_UNSUPPORTED naming those that do). o: tolerances (a
/// global target, the method's calibrated factor applied as for dal_advance), h0, hmax,
/// fixed_step, max_steps; the formulation, work and projection options are ignored (fo->project
/// runs when set). The solution is read at it->y, the last step from window; dense output of
/// the trajectory part through place. 0 or a negative public status with st's message set
/// (integ.c)
int dal__integ_create_fo(const dal_system *sys, dal_state *st, const dal_solve_opts *o,
                         dal_first_order *fo, dal_integ **out);
/// destroy an integrator (NULL: nothing)
void dal__integ_destroy(dal_integ *it);

#include "symplectic.h"

#endif
