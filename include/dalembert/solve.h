// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Integrating the motion: methods, formulations, options, advance/evolve, statistics.
//
// A system without constraints runs as the ODE y = (q, qdot); a system with constraints runs
// as a DAE (index-2 stabilized GGL through SUNDIALS IDA by default). After any failure the
// state holds the last accepted step and dal_state_errmsg says what failed, when and why.
#ifndef DAL_SOLVE_H
#define DAL_SOLVE_H

#include <stdio.h>

#include "dalembert/base.h"
#include "dalembert/state.h"
#include "dalembert/system.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Integration methods.
///
/// DAL_METHOD_AUTO picks, for the ODE and index-1 forms, by opts.rtol:
///   rtol > 1e-6: DOPRI5;  1e-12 <= rtol <= 1e-6: Adams;  rtol < 1e-12: Bulirsch-Stoer;
/// and BDF (IDA) for the GGL and index-3 forms. Measured wall time to t = 10 on a 6-link
/// pendulum chain (ms, same run): rtol 1e-4: dopri5 2.9, adams 3.0, fehlberg78 7.7, bs 9.8;
/// 1e-8: bs 18, adams 23, fehlberg78 24, dopri5 30; 1e-12: adams 47, bs 48, fehlberg78 88,
/// dopri5 255. Below 1e-12 Adams' local tolerance nears rounding and BS is the robust choice
/// (on a single pendulum BS is fastest from 1e-5 down).
///
/// Tolerances are targets for the global error: each method runs its local error control at
/// c * rtol, c * atol with c = 0.1 (DOPRI5), 0.03 (Fehlberg), 0.005 (BS), 0.01 (Adams),
/// 0.001 (BDF), measured so that on the pendulum released at 60, 120 and 170 degrees (vs the
/// Jacobi-elliptic solution) and the 2D harmonic oscillator the error at t = 10 stays below
/// 16 x rtol for rtol = 1e-4 ... 1e-12 (worst factors 12, 7, 6, 11, 15; tests allow 100).
/// Ill-conditioned problems (chaos, near-separatrix motion) amplify local errors further.
typedef enum dal_method {
  DAL_METHOD_AUTO = 0,   ///< pick by formulation and tolerance (rule above)
  DAL_METHOD_DOPRI5,     ///< Dormand-Prince 5(4), adaptive explicit RK (ARKODE ERKStep)
  DAL_METHOD_FEHLBERG78, ///< Fehlberg 7(8), adaptive explicit RK of order 8 (ARKODE ERKStep)
  DAL_METHOD_BS,         ///< Gragg-Bulirsch-Stoer extrapolation with order/step control
  DAL_METHOD_RK4,        ///< classical RK4 at the fixed step opts.fixed_step
  DAL_METHOD_ADAMS,      ///< variable-order Adams-Moulton (CVODE, fixed-point iteration)
  DAL_METHOD_BDF,        ///< variable-order BDF (CVODE for ODEs, IDA for DAEs), stiff scenes
} dal_method;

/// Formulations of the equations of motion.
typedef enum dal_formulation {
  DAL_FORM_AUTO = 0, ///< ODE without constraints, GGL with constraints
  DAL_FORM_ODE,      ///< minimal coordinates, y = (q, qdot); requires m = 0
  DAL_FORM_GGL,      ///< index-2 stabilized (Gear-Gupta-Leimkuhler) DAE in IDA
  DAL_FORM_INDEX1,   ///< acceleration level; Baumgarte and/or projection optional
  DAL_FORM_INDEX3,   ///< index-3 DAE as written (for comparison: q only in the error test;
                     ///< global error measured 1e4-1e6 x rtol on a pendulum)
} dal_formulation;

/// Linear solver for implicit methods.
typedef enum dal_linsol {
  DAL_LINSOL_AUTO = 0, ///< dense below opts.sparse_threshold unknowns, KLU above
  DAL_LINSOL_DENSE,    ///< dense LU
  DAL_LINSOL_KLU,      ///< sparse KLU with a library-assembled Jacobian (DAE forms)
} dal_linsol;

/// Options for advance/evolve. Always start from dal_solve_default_opts().
typedef struct dal_solve_opts {
  int magic;                  ///< set by dal_solve_default_opts; do not touch
  dal_method method;          ///< integration method
  dal_formulation form;       ///< formulation
  dal_linsol linsol;          ///< linear solver for implicit methods
  double rtol;                ///< relative tolerance, 1e-15 <= rtol < 1, default 1e-8
  double atol;                ///< absolute tolerance (> 0, units of q), default 1e-10
  double h0;                  ///< initial step (0: automatic)
  double hmin;                ///< minimum step (0: none)
  double hmax;                ///< maximum step (0: none)
  double fixed_step;          ///< step of DAL_METHOD_RK4 (> 0, and it must move t: a step
                              ///< below the resolution of t is DAL_E_ARG), default 1e-3
  long max_steps;             ///< maximum steps per advance call, default 1000000
  double baumgarte_alpha;     ///< INDEX1: damping of G v + dphi/dt (1/s), default 0 (off)
  double baumgarte_beta;      ///< INDEX1: frequency on phi (1/s; term beta^2 phi, dae.h), 0
                              ///< (both >= 0, with 2 alpha and beta^2 finite)
  int project;                ///< INDEX1: project q and v onto the manifold after each step
                              ///< (ODE methods; with BDF/IDA: DAL_E_UNSUPPORTED)
  int sparse_threshold;       ///< DAL_LINSOL_AUTO switches to KLU at this many unknowns (200)
  int fixed_erk;              ///< DOPRI5/FEHLBERG78: if nonzero, take fixed steps of
                              ///< opts.fixed_step without error control (order studies); 0
} dal_solve_opts;

/// Fill *o with the defaults: AUTO method, AUTO formulation, rtol 1e-8, atol 1e-10.
DAL_API void dal_solve_default_opts(dal_solve_opts *o);

/// Short name of a method ("dopri5", "fehlberg78", "bs", "rk4", "adams", "bdf", "auto").
DAL_API const char *dal_method_name(dal_method m);
/// Short name of a formulation ("ode", "ggl", "index1", "index3", "auto").
DAL_API const char *dal_formulation_name(dal_formulation f);

/// Integration statistics accumulated since the last dal_state_set.
typedef struct dal_stats {
  long steps;        ///< accepted steps
  long rejected;     ///< rejected steps (error test and convergence failures)
  long rhs_evals;    ///< right-hand-side or residual evaluations
  long jac_evals;    ///< Jacobian evaluations
  long nonlin_iters; ///< nonlinear (Newton) iterations
  long projections;  ///< manifold projections (INDEX1 with project)
  double last_h;     ///< last step size taken
  int foreign_code;  ///< last raw return code of the underlying solver (0 if none)
} dal_stats;

/// Statistics of the state's integration so far.
DAL_API int dal_state_stats(const dal_state *st, dal_stats *out);

/// Advance the state to time t1 (>= current time) with the given options (SICM's
/// state-advancer). On success the state holds the exact-to-tolerance solution at t1,
/// with dal_forward outputs evaluated there. On failure it holds the last accepted step.
/// Changing opts between calls restarts the integrator from the current state.
/// Every method has a progress guard: a step that does not advance t (or a run of steps of a
/// few ulps of t) stops the run at once with the status of its cause (a callback that keeps
/// asking for a smaller step: DAL_E_CALLBACK; an overflow: DAL_E_NONFINITE; a chart
/// singularity: DAL_E_SINGULAR; otherwise DAL_E_STEP), never a million-step loop; a step whose
/// result is not finite is never accepted.
DAL_API int dal_advance(const dal_system *sys, dal_state *st, const dal_solve_opts *opts,
                        double t1);

/// Monitor called by dal_evolve at every output time with the state evaluated there
/// (dal_forward outputs valid). Return 0 to continue, non-zero to stop (evolve returns it
/// as DAL_E_CALLBACK if negative, DAL_OK if positive).
typedef int dal_monitor_fn(const dal_system *sys, const dal_state *st, void *ctx);

/// Evolve from the current time t0 to t1, calling `monitor` (may be NULL) at t0 and at
/// every t0 + k dt <= t1 (dt > 0), and at t1. The monitor sees the state at exactly those
/// times (the integrator steps to each output time). dt NaN or inf is DAL_E_NONFINITE, dt <= 0
/// or below the resolution of t DAL_E_ARG. A monitor returning < 0 stops evolve with
/// DAL_E_CALLBACK; a message the monitor left in the state (dal_csv_monitor does) is quoted.
DAL_API int dal_evolve(const dal_system *sys, dal_state *st, const dal_solve_opts *opts,
                       double t1, double dt, dal_monitor_fn *monitor, void *ctx);

/// CSV writer for monitors: a monitor context writing t, q..., qdot..., E, h per row.
typedef struct dal_csv {
  FILE *fp;         ///< output stream (borrowed)
  int header_done;  ///< set after the header row is written
  int wrap_angles;  ///< if nonzero, write q wrapped to [-pi, pi) (principal value)
} dal_csv;

/// Monitor that writes one CSV row (and the header first); ctx is a dal_csv *. Returns
/// DAL_E_ARG (ctx NULL or without a stream), DAL_E_STATE (a state of another system, or one
/// not evaluated at its (t, q, qdot): its energies would be stale; dal_evolve always passes
/// evaluated states), DAL_E_IO (the stream failed), each with a message in the state; nothing
/// is written on failure.
DAL_API int dal_csv_monitor(const dal_system *sys, const dal_state *st, void *ctx);

#ifdef __cplusplus
}
#endif
#endif
