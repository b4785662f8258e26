// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The integration layer's face: one integrator interface (dal_integ, integ.c) over the ODE
// methods and IDA, the method table and the first-order problems. What lies below the handle
// (the ODE and IDA levels) is declared in the private header families.h.
#ifndef DAL_INTEGRATE_INTEGRATE_H
#define DAL_INTEGRATE_INTEGRATE_H

#include "form/form.h"

/// An ODE integrator, opaque here: the method rows name its constructors. The ODE level
/// (dal_ode_integ, dal_ode_ops, dal__ode_*) and the IDA level (dal__ida_*) are integrate/'s own,
/// declared in its private header families.h; the layers above reach both through dal_integ.
typedef struct dal_ode_integ dal_ode_integ;

/// the after-step hook asked the integration to stop (a terminal event, a monitor's stop)
#define DAL__HOOK_STOP 1000

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

#endif
