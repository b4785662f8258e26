// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Integrating the motion: methods, formulations, options, advance/evolve, statistics.
///
/// A system without constraints runs as the ODE y = (q, qdot); a system with constraints runs
/// as a DAE (index-2 stabilized GGL through SUNDIALS IDA by default). After any failure the
/// state holds the last accepted step and dal_state_errmsg says what failed, when and why.
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
/// DAL_METHOD_AUTO picks, for the ODE and index-1 forms, by opts.rtol and the number of
/// coordinates n (never a symplectic method, see below):
///   rtol >= 1e-3: DOPRI5;
///   rtol < 1e-3, n <= 2: Bulirsch-Stoer;
///   rtol < 1e-3, n >= 3: DOPRI5 down to rtol 1e-5, Bulirsch-Stoer below,
/// and BDF (IDA) for the GGL and index-3 forms. The choice is made when the integrator is
/// created, and kept while the options stay the same. AUTO takes a method only where its
/// error estimate holds on a differential set (tests/test_auto_set.c: 300 random planar trees
/// of 3 ... 6 pendulums with a spring between two siblings, a third of them passing each other
/// within a few cm, to t = 2, against Bulirsch-Stoer at 1e-13 or Adams at 1e-12, which agree
/// to 2.3e-11): the default options stay within 16 x rtol times the scene's amplification of
/// a start perturbation at every rtol 1e-4 ... 1e-10 (the test checks every run). Fehlberg
/// 7(8), the cheapest on the seed scenes at 1e-5 ... 1e-8 and AUTO's choice there before,
/// reached 22.8 ... 117 x on that set (`test_auto_set --full` prints the table for every
/// method); it is there by name only. Among the others the rule is read off the
/// work-precision tables (bench/auto.sh and bench/dense_auto.sh, docs/performance.md "AUTO"):
/// the instructions each method needs to reach a position error of 1e-4, 1e-8 and 1e-11 on
/// the pendulum, the bead on the turning ring, SICM's driven pendulum, the double pendulum,
/// the 2D oscillator and the N-link chain (N = 1 ... 256), with the default atol, and with
/// outputs every 0.001 on the chain (N = 1 ... 64), where DOPRI5 costs 1.3-2.7x the cheapest
/// method at errors 1e-8 ... 1e-10 and Bulirsch-Stoer at most 1.2x there and 1.44x at 1e-7.
/// Adams (CVODE) is never the cheapest by more than a few percent there: its per-step
/// overhead outweighs its fewer evaluations. Stiff problems
/// want DAL_METHOD_BDF, which AUTO does not detect.
///
/// Tolerances are targets for the global error: each method runs its local error control at
/// c * rtol, c * atol, calibrated so that the error at t = 10 on the closed-form scenes (the
/// pendulum released at 60, 120 and 170 degrees vs the Jacobi-elliptic solution, the 2D
/// harmonic oscillator; the Cartesian pendulum for the DAE forms) stays below 16 x rtol for
/// rtol = 1e-4 ... 1e-12, and the Jacobi integral of the bead on the turning ring drifts less
/// than 20 x rtol over 1000 periods (tests/test_core.c prints the table):
///
/// | method / form            | c       | worst error / rtol (t = 10) | bead, 1000 periods |
/// |--------------------------|---------|-----------------------------|--------------------|
/// | DOPRI5                   | 0.01    | 1.0                         | 12.1               |
/// | Fehlberg 7(8)            | 0.01    | 2.4                         | 10.3               |
/// | Bulirsch-Stoer           | 0.005   | 9.0                         | 5.2                |
/// | Adams (CVODE)            | 0.001   | 1.2                         | 1.4                |
/// | BDF (CVODE)              | 0.0001  | 2.2 to 1e-11; clamped below | 0.9                |
/// | GGL (IDA)                | 0.001   | 2.4 to 1e-9; 12.9 at 1e-10  | 16.5 (to 1e-8)     |
/// | index-1 + projection     | x 0.2   | 1.0 (BS), 2.1 (DOPRI5)      |                    |
/// | index-1 in IDA           | 0.0002  | drifts: 47 to 1e-9, 778 at 1e-10 (no stabilization)|
/// | index-3 in IDA           | 0.001   | 2e2 - 2e4 to 1e-9 (kept to show where it fails)    |
///
/// (The last two rows are that table's loop with those forms as rows, not in tests/test_core.c:
/// their errors exceed its bound; tests/test_differential.c holds them to these figures.)
///
/// Adams and BDF are calibrated over [0, 20] with outputs at 986 irregular times (the pendulum
/// at 2.5 rad, by events at the times and by a dal_advance loop; tests/test_dense.c): the
/// factors 0.005 and 0.0005 calibrated at t = 10 gave up to 27 x and 107 x there. CVODE's BDF
/// honours rtol >= 1e-11 (its local tolerance would pass the floor 1e-15 below): a tighter
/// request runs as 1e-11, atol scaled alike, never silently: DAL_OK with a note in the state's
/// message ("rtol ... is below what bdf can honour") and the clamp in dal_stats.rtol_used.
/// Floors, stated and enforced (issue 31): below them a method's error stops falling and grew
/// again (rounding). DOPRI5, Fehlberg 7(8) and Adams honour rtol >= 1e-12, Bulirsch-Stoer
/// >= 1e-13, BDF >= 1e-11; a tighter request runs as the floor itself (the same run, atol
/// scaled alike), DAL_OK with a note in the state's message ("rtol ... is below what ... can
/// honour") and the local tolerance in dal_stats.rtol_used. So a tighter request is never
/// worse: tests/test_dense.c (test_tighter) prints each method's error on the pendulum at
/// 2.5 rad (t = 20) and 1 rad (t = 10) for rtol 1e-6 ... 1e-14 and checks that the error at a
/// tighter rtol is not above the looser one's unless it is within 16 x its own rtol.
/// A dal_advance call without events or monitor lets CVODE step on past its target and
/// takes the state there from CVODE's interpolating polynomial (forcing a step to end at every
/// target broke the multistep history: 113 x rtol for Adams in a loop of 986 calls); the model
/// may then be evaluated up to one step beyond the target.
///
/// IDA's floor is the local tolerance 1e-12 (DAL_IDA_TOL_FLOOR, base/bounds.h): below it, on
/// some scenes, the rounding of the constraint rows, amplified into the multipliers' Newton
/// corrections, fails IDA's convergence test (docs/dae.md has the measurements). A tighter
/// request runs below it, down to the local tolerance 1e-14, while its steps succeed; a failed
/// step there goes on from the last accepted step at 1e-12, with a note in the state's message
/// ("IDA's step failed at t=... it continued from there at the floor") and dal_stats.rtol_used
/// = 1e-12. Below 1e-14 a request is clamped, atol scaled alike, with the note "rtol ... is
/// below what IDA can honour" (GGL measures 2.3 x rtol at 1e-10, 0.3 x at 1e-11, 3.2 x at 1e-12
/// on the Cartesian pendulum). With DAL_FORM_AUTO and DAL_METHOD_AUTO, a constrained
/// system asked for rtol < 1e-9 runs the index-1 form with projection and Bulirsch-Stoer instead
/// (from a consistent start), which honours it (row "auto (constrained)" of the table in
/// tests/test_core.c). With the defaults, an IDA failure by convergence or step collapse falls
/// back to that route from the last accepted step (opts.no_fallback; dal_stats.fallbacks;
/// tests/test_dae_grid.c: 0 failures over 390 starts and random rod trees at rtol 1e-4 ...
/// 1e-10). On the car axis of the Bari test set (tests/test_caraxis.c, docs/dae.md) GGL reaches
/// 7.5 significant correct digits at rtol 1e-9, 8.36 at 1e-10 and 9.32 below, AUTO's route 12.25
/// at 1e-12 and 12.5 at 1e-13. Ill-conditioned problems (chaos,
/// near-separatrix motion) amplify local errors further.
///
/// Structure-preserving methods (AUTO never picks them: ask for them by name). They take the
/// fixed step opts.fixed_step on their own grid t0 + k h and ignore rtol/atol; an output time
/// between grid points (dal_advance's target, dal_evolve's monitor times) is served by one
/// extra step from the last grid point into a copy, so outputs never change the trajectory
/// (bit for bit). The state is summed with compensation. A callback asking for a smaller step
/// stops them (DAL_E_CALLBACK): a fixed step cannot shrink.
///  - DAL_METHOD_VARIATIONAL: minimal coordinates (particles by maps, or a Lagrangian), the
///    discrete Euler-Lagrange equations of the midpoint discrete Lagrangian h L((q0+q1)/2,
///    (q1-q0)/h, t+h/2) in position-momentum form (Marsden-West 2001), solved by Newton; the
///    state's qdot is the inverse Legendre transform of the discrete momentum. Symplectic and
///    momentum-preserving for any Lagrangian (gyroscopic ones too): J' Omega J = Omega to 1e-13
///    (finite-difference oracle), L_z of the spherical pendulum to 1.6e-15 over 10^4 steps.
///    Non-conservative forces (dampers, callbacks) enter by the discrete Lagrange-d'Alembert
///    principle at the midpoint; then nothing is conserved, by design. Needs m = 0.
///  - DAL_METHOD_RATTLE: Cartesian particles (dal_map_cartesian2/3, fixed points) with
///    constraints and potential forces only (gravity, springs, potentials; a damper or force
///    callback is DAL_E_UNSUPPORTED). Symplectic and symmetric; at every step max |phi| <= 16
///    ulps of max(1, |q|) and G v + dphi/dt at rounding (dal_stats.max_phi, max_phidot), by a
///    simplified Newton iteration through the KKT factorization (KLU on large systems: O(N)
///    per step on chains). Rheonomic constraints are imposed at t_{n+1} (phi(q, t_{n+1}) = 0,
///    G v + dphi/dt = 0 there): RATTLE of the extended phase space with t as a coordinate,
///    symplectic there; the energy then changes by the moving constraint's work and what the
///    extended system conserves stays bounded (a uniformly turning ring: E - w L_z bounded,
///    no drift over 10^4 periods). The state is made consistent first (dal_make_consistent).
///  - ..4 and ..6: symmetric compositions of order 4 (Yoshida's triple jump, 3 steps) and 6
///    (Kahan-Li, 9 steps); measured orders 4.0 and 6.0.
/// What they buy (bench/symplectic.c, bench/results/sym_summary.md, docs/symplectic.md): an
/// energy (or Jacobi integral) error that oscillates with a bounded amplitude where every
/// adaptive method's grows about linearly (pendulum, 10^5 periods at matched CPU time:
/// variational4 3.5e-5 m g l throughout; DOPRI5 2.5e-2 -> 1.4, BS 2.6e-6 -> 3.5e-4), and a
/// phase error growing like t instead of t^2.
/// What they cost: each variational step is implicit (Newton, about 3 iterations), RATTLE's
/// needs a few constraint iterations. The crossover (the horizon after which they are the
/// cheaper route to a given energy accuracy) against DOPRI5 lies at 20-2500 periods for targets
/// 1e-8..1e-6 (2.5e4-9e4 at 1e-4), against IDA's GGL at 0-45 periods; against the library's
/// Bulirsch-Stoer (compensated, energy drift ~2.5e-13 m g l per period at 1e-10) at 2e4 to
/// beyond 1e9 periods: for smooth low-dimensional scenes BS stays the cheaper route to an
/// accuracy, the symplectic methods give what no tolerance gives (no growth at all, exact
/// momenta, a symplectic map for sections).
/// Where they fail:
///  - a stiff spring: RATTLE (explicit Stormer-Verlet) is unstable for h w_fast > 2 (the
///    state overflows, then DAL_E_DOMAIN); the variational method stays bounded (implicit
///    midpoint) but turns the fast oscillation by 2 atan(w h / 2) per step, not w h: the fast
///    motion is not resolved beyond w h ~ 1; an adaptive stiff method (BDF) is cheaper;
///  - steps too long for the motion: Newton (variational, h w > ~1 on nonlinear scenes) or
///    RATTLE's constraint iteration (h |v| / l > ~1 for a constraint of length scale l) stop
///    converging: DAL_E_CONV naming the coordinate or constraint, state at the last grid point;
///  - a drive with energy input: nothing is conserved, so the bounded-energy argument is void;
///    on SICM's driven pendulum the variational method (h = 0.01) leaves the reference (0.1 rad)
///    at 18.9 s, BS at the same cost (rtol 1e-12) at 79.6 s;
///  - near a separatrix the period depends without bound on the energy: the O(h^2) shift of
///    the conserved modified energy becomes a large period error (released 1e-3 rad below the
///    top: 3.6 rad after 400 s at h = 0.05, BS at 1e-10: 1.4e-4), and beyond h w0 ~ 0.5 the
///    discrete map's chaotic layer reaches the orbit, which goes over the top (h = 0.2).
typedef enum dal_method {
  DAL_METHOD_AUTO = 0,     ///< pick by formulation and tolerance (rule above)
  DAL_METHOD_DOPRI5,       ///< Dormand-Prince 5(4), adaptive explicit RK (ARKODE ERKStep)
  DAL_METHOD_FEHLBERG78,   ///< Fehlberg 7(8), adaptive explicit RK of order 8 (ARKODE ERKStep)
  DAL_METHOD_BS,           ///< Gragg-Bulirsch-Stoer extrapolation with order/step control
  DAL_METHOD_RK4,          ///< classical RK4 at the fixed step opts.fixed_step
  DAL_METHOD_ADAMS,        ///< variable-order Adams-Moulton (CVODE, fixed-point iteration)
  DAL_METHOD_BDF,          ///< variable-order BDF (CVODE for ODEs, IDA for DAEs), stiff scenes
  DAL_METHOD_VARIATIONAL,  ///< variational midpoint integrator, minimal coordinates, order 2
                           ///< (symplectic, fixed step opts.fixed_step; see below)
  DAL_METHOD_VARIATIONAL4, ///< its symmetric composition of order 4 (Yoshida triple jump)
  DAL_METHOD_VARIATIONAL6, ///< its symmetric composition of order 6 (Kahan-Li, 9 stages)
  DAL_METHOD_RATTLE,       ///< RATTLE, Cartesian particles with constraints, order 2
                           ///< (symplectic, fixed step opts.fixed_step; see below)
  DAL_METHOD_RATTLE4,      ///< RATTLE composed to order 4 (triple jump)
  DAL_METHOD_RATTLE6,      ///< RATTLE composed to order 6 (Kahan-Li, 9 stages)
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

// Dynamics routes (dal_builder_set_dynamics in system.h). Accelerations come from
// M qddot = Q - c, and with constraints from the KKT system [M G'; G 0] [qddot; -lambda] =
// [Q - c; -gamma_phi]. Two routes solve them:
//
// - DAL_DYNAMICS_RECURSIVE, the articulated-body recursion (Featherstone's, for point masses:
//   a d x d articulated inertia and a bias force per particle, one sweep from the leaves and
//   one from the roots), O(N) per evaluation. It applies to any tree of placements in which
//   every coordinate moves exactly one placement: translating parents (r_k = r_parent +
//   f(q_k, t), the composite-mass case) and others (through the local parent block dr_k /
//   dr_parent), several coordinates per placement, rheonomic maps, every force. With
//   constraints (loops closed on the tree, a few Cartesian rods) the multipliers come from
//   the m x m system G M^-1 G' lambda = ..., built from m recursion solves with unit loads;
//   the dense or sparse KKT matrix in all coordinates is not formed. M is assembled only when
//   asked for (dal_forward, dal_state_mass_matrix), and not at all above 512 coordinates; the
//   global Jacobians are never stored in an evaluated state of a recursive system
//   (dal_state_jacobian forms them from the local blocks on request).
// - DAL_DYNAMICS_DENSE: M assembled (composite masses for translating trees, J'MJ otherwise)
//   and factored by LAPACK Cholesky; the KKT matrix dense (dsytrf) or sparse (KLU).
//
// DAL_DYNAMICS_AUTO takes the recursion wherever it applies and the system has at most
// DAL_LOOP_ROWS_MAX = 32 constraint rows; otherwise the dense route. Measured in callgrind
// instructions (bench/overhead_ir.sh; README): the planar chain at N = 1 ... 32 costs 0.41 ...
// 0.80 of the dense route with DOPRI5 and Adams at rtol 1e-8, already at N = 1 (no LAPACK
// call), and from N = 128 to 4096 one evaluation costs N^0.99 (the dense route's wall time grows
// as N^2.4 from 16 to 128). The four-bar linkage and a 64-link chain held at both ends, a tree
// plus one loop row each, run 2.5x and 9.7x cheaper than the same trees through the KKT matrix
// and 7.1x and 8.4x cheaper than the Cartesian scenes in GGL (DOPRI5 with projection at rtol
// 1e-6 against GGL at 1e-8, similar errors). With more rows the KKT matrix wins once KLU
// factors it (the Cartesian chain: the loop system costs 0.47 of the dense KKT matrix at m =
// 32, 3.7x KLU at m = 72). The recursion needs a regular M: where M is singular but the KKT
// matrix is not (a coordinate at a chart singularity held by a constraint), DAL_E_SINGULAR
// names the coordinate and DAL_DYNAMICS_DENSE is the remedy. Both routes give the same
// accelerations, multipliers and reactions to rounding (tests/test_aba.c: below 1e-13 relative
// on random trees of up to 200 particles) and the same DAL_E_SINGULAR message for a degenerate
// coordinate.

/// Linear solver for implicit methods.
typedef enum dal_linsol {
  DAL_LINSOL_AUTO = 0, ///< dense below opts.sparse_threshold unknowns, KLU above
  DAL_LINSOL_DENSE,    ///< dense LU
  DAL_LINSOL_KLU,      ///< sparse KLU with a library-assembled Jacobian (DAE forms)
} dal_linsol;

/// Cancel hook of a run (dal_solve_opts.cancel): called with opts.cancel_ctx once after every
/// accepted step of dal_advance, dal_evolve and dal_evolve_at (and of the analyses that run
/// them). Return 0 to go on, nonzero to stop there: the run returns DAL_CANCELLED (a positive
/// status, not an error), the state holds that last accepted step, evaluated, every output time
/// up to it has been served to the monitor, and dal_state_errmsg says where it stopped. It must
/// be cheap and must not touch the state; a flag set by a signal handler or another thread (read
/// as volatile or atomic) is the intended use (the command line's Ctrl-C, Python's
/// KeyboardInterrupt). A hook that never cancels leaves the steps as they are: DOPRI5,
/// Fehlberg 7(8), Bulirsch-Stoer and RK4 end bit for bit where they end without it; CVODE
/// (Adams, BDF) and IDA then take their steps one at a time, as with a monitor, and end within
/// the tolerance of the run without it (tests/test_cancel.c).
typedef int dal_cancel_fn(void *ctx);

/// Options for advance/evolve. Always start from dal_default_solve_opts().
typedef struct dal_solve_opts {
  int cookie;             ///< set by dal_default_solve_opts; do not touch
  dal_method method;      ///< integration method
  dal_formulation form;   ///< formulation
  dal_linsol linsol;      ///< linear solver for implicit methods
  double rtol;            ///< relative tolerance, 1e-15 <= rtol < 1, default 1e-8
  double atol;            ///< absolute tolerance (> 0, units of q); 0 (default) follows
                          ///< rtol: atol = DAL_ATOL_PER_RTOL * rtol (1e-8 at the default
                          ///< rtol), so setting only rtol tightens both. Set it yourself
                          ///< when coordinates are far from unit scale.
  double h0;              ///< initial step (0: automatic)
  double hmin;            ///< minimum step (0: none)
  double hmax;            ///< maximum step (0: none)
  double fixed_step;      ///< step of DAL_METHOD_RK4 and of the symplectic methods (> 0,
                          ///< and it must move t: a step below the resolution of t is
                          ///< DAL_E_ARG), default 1e-3
  long max_steps;         ///< maximum steps per advance call, default 1000000
  double baumgarte_alpha; ///< INDEX1: damping of G v + dphi/dt (1/s), default 0 (off)
  double baumgarte_beta;  ///< INDEX1: frequency on phi (1/s; term beta^2 phi, dae.h), 0
                          ///< (both >= 0, with 2 alpha and beta^2 finite)
  int project;            ///< INDEX1: project q and v onto the manifold after each step
                          ///< (ODE methods; with BDF/IDA: DAL_E_UNSUPPORTED)
  int sparse_threshold;   ///< DAL_LINSOL_AUTO switches to KLU at this many unknowns (12)
  int work;               ///< if nonzero, integrate the work W done by non-conservative
                          ///< forces, time-dependent potentials and moving constraints
                          ///< with the motion (dal_energies.W; E - W is then conserved);
                          ///< default 0. Adaptive methods and IDA; not the fixed-step
                          ///< structure-preserving ones
  int fixed_erk;          ///< DOPRI5/FEHLBERG78: if nonzero, take fixed steps of
                          ///< opts.fixed_step without error control (order studies); 0
  double init_max_move;   ///< DAE start: the largest change |delta q_i| (units of q) the
                          ///< consistent initialization may apply; a larger one fails with
                          ///< DAL_E_INIT naming the coordinate and the state is unchanged.
                          ///< 0 (default): no limit, but a move beyond atol + rtol |q_i|
                          ///< leaves a note in the state's message after DAL_OK (naming the
                          ///< coordinate, the move and the constraint). Either way the report
                          ///< of the move is kept (dal_state_init_report in dae.h).
  int no_fallback;        ///< DAE route: if nonzero, a failure of IDA is returned as it is;
                          ///< 0 (default): with DAL_FORM_AUTO and DAL_METHOD_AUTO, a
                          ///< convergence failure or step collapse in IDA (DAL_E_CONV,
                          ///< DAL_E_STEP) restarts from the last accepted step in the index-1
                          ///< form with projection and Bulirsch-Stoer (the fallback ladder of
                          ///< docs/dae.md), recorded in dal_stats and in the state's message.
                          ///< An explicit formulation or method is honoured as asked: its
                          ///< failure message names this fallback as the remedy.
  dal_cancel_fn *cancel;  ///< cancel hook (dal_cancel_fn), or NULL (default): asked after every
                          ///< accepted step; nonzero stops the run with DAL_CANCELLED
  void *cancel_ctx;       ///< passed to cancel (borrowed), default NULL
} dal_solve_opts;

/// atol = DAL_ATOL_PER_RTOL * rtol when opts.atol is 0 (the default). atol = rtol reaches a
/// given position error with fewer instructions than atol = 1e-2 rtol (the rule before) on
/// coordinates of unit scale: 0.73 - 1.13 of the cost, median 0.95, over the scenes of the
/// AUTO table (bench/auto.sh); the tolerance calibration above was measured with atol = rtol.
#define DAL_ATOL_PER_RTOL 1.0

/// Fill *o with the defaults: AUTO method, AUTO formulation, rtol 1e-8, atol 0 (follows rtol:
/// 1e-8), no limit on the consistent start's move.
DAL_API dal_solve_opts dal_default_solve_opts(void);

/// Short name of a method ("dopri5", "fehlberg78", "bs", "rk4", "adams", "bdf", "variational",
/// "variational4", "variational6", "rattle", "rattle4", "rattle6", "auto").
DAL_API const char *dal_method_name(dal_method m);
/// Short name of a formulation ("ode", "ggl", "index1", "index3", "auto").
DAL_API const char *dal_formulation_name(dal_formulation f);

/// Integration statistics accumulated since the last dal_state_set.
typedef struct dal_stats {
  long steps;             ///< accepted steps
  long rejected;          ///< rejected steps (error test and convergence failures)
  long rhs_evals;         ///< right-hand-side or residual evaluations
  long jac_evals;         ///< Jacobian evaluations
  long nonlin_iters;      ///< nonlinear (Newton) iterations
  long projections;       ///< manifold projections (INDEX1 with project)
  double last_h;          ///< last step size taken
  int foreign_code;       ///< last raw return code of the underlying solver (0 if none)
  double rtol_used;       ///< local relative tolerance the integrator runs at: the calibrated
                          ///< factor times opts.rtol, raised to the method's floor when the
                          ///< request is tighter than it can honour (the clamp is visible here)
  double max_phi;         ///< RATTLE: largest position residual max |phi| at an accepted step
                          ///< (length units; 0 for the other methods)
  double max_phidot;      ///< RATTLE: largest velocity residual max |G v + dphi/dt| at an accepted
                          ///< step (length/time; 0 for the other methods)
  dal_method method_used; ///< the method that ran last (AUTO resolved; DAL_METHOD_BDF for IDA)
  dal_formulation form_used; ///< the formulation that ran last (AUTO resolved)
  int fallbacks;             ///< switches of the DAE route to the fallback (opts.no_fallback)
  double fallback_t;         ///< time of the last switch (the last step IDA accepted)
  int fallback_cause;        ///< status of IDA's failure that caused it (DAL_E_CONV, DAL_E_STEP)
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

/// Monitor called by dal_evolve at every output time with the state there (its products are
/// evaluated on first read: dal_forward's outputs are valid through the accessors). Return 0
/// to continue, > 0 to stop early (dal_evolve then returns DAL_STOPPED, a positive status that
/// is not an error: the state holds that time and dal_state_errmsg says where it stopped),
/// < 0 to report a failure (dal_evolve returns DAL_E_CALLBACK).
typedef int dal_monitor_fn(const dal_system *sys, const dal_state *st, void *ctx);

/// Evolve from the current time t0 to t1, calling `monitor` (may be NULL) at t0 and at
/// every t0 + k dt <= t1 (dt > 0), and at t1. Returns DAL_OK when it reached t1, DAL_STOPPED
/// when the monitor stopped it before t1 (not an error), DAL_EVENT when a terminal event
/// stopped it (events.h), or a negative status.
///
/// Dense output: the integrator takes its own steps towards t1 and the states at the output
/// times come from the method's interpolant of each step (SUNDIALS' own for CVODE, ARKODE's
/// DOPRI5 and IDA; Hairer-Norsett-Wanner's extrapolated dense output for Bulirsch-Stoer; for
/// Fehlberg 7(8) a Hermite interpolant of degree 7 or 9 built once per step, docs/performance.md;
/// a cubic Hermite for RK4; a partial composed step
/// for the symplectic methods), accurate to the method's tolerance. tests/test_dense.c
/// (test_routes) holds every route to it: the pendulum at 2.5 rad over [0, 20] against the
/// elliptic solution, atol = rtol, at 500 irregular times by dal_evolve_at, at the same times
/// from the stored trajectory of a dal_advance run, and on dal_evolve's grid (dt = 0.04); it
/// prints the worst error / rtol of the three routes (they agree to 0.4) and checks 16 x rtol
/// except in the two cells marked:
///
/// | method        | 1e-6 | 1e-8 | 1e-10 | 1e-11 | 1e-12                                  |
/// |---------------|------|------|-------|-------|----------------------------------------|
/// | DOPRI5        | 2.7  | 2.6  | 7.1   | 8.4   | 24.9 (checked: 32; the step ends too)  |
/// | Fehlberg 7(8) | 6.7  | 9.3  | 4.8   | 3.5   | 1.9                                    |
/// | BS            | 1.9  | 0.4  | 0.6   | 0.3   | 0.2                                    |
/// | Adams         | 0.4  | 4.0  | 1.1   | 2.0   | 9.3                                    |
/// | BDF           | 0.4  | 3.9  | 2.2   | 3.1   | 31.3 (runs as 1e-11: 3.1 x that)       |
///
/// So the outputs do not change the steps:
/// the trajectory, its end state and the statistics are the same for any dt. opts.max_steps
/// counts the steps between two outputs. A run with a monitor is not the same run as one
/// without (monitor NULL, which is dal_advance's run bit for bit): Bulirsch-Stoer then runs its
/// dense mode, whose interpolation error control changes its steps, and CVODE's Adams and BDF
/// end in the last digits elsewhere; their end states agree within the tolerance, not bit for
/// bit, and a chaotic scene magnifies the difference (the double pendulum from (2, 2) rad at
/// rtol 1e-10, t = 30, Bulirsch-Stoer: q[0] = -5.607 without a monitor, -11.15 with one).
/// DOPRI5 and Fehlberg 7(8) take the same steps either way.
///
/// The monitor gets the state at the output time with (t, q, qdot) set; everything else
/// (positions, reactions, multipliers, energies, M ...) is evaluated on its first read through
/// the accessors, so a monitor that reads only q costs no model evaluation. Where that
/// evaluation fails (a point between steps the integrator never evaluated, outside a map's
/// domain, say), the monitor reads NULL products and evolve then fails there with the
/// evaluation's status and message. dt NaN or inf is
/// DAL_E_NONFINITE, dt <= 0 or below the resolution of t DAL_E_ARG. A monitor returning < 0
/// stops evolve with DAL_E_CALLBACK; a message the monitor left in the state (dal_csv_monitor
/// does) is quoted. On any early end the state is at that time, evaluated.
DAL_API int dal_evolve(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t1,
                       double dt, dal_monitor_fn *monitor, void *ctx);

/// Evolve from the current time to times[n - 1], calling `monitor` (may be NULL) at every
/// output time times[0 .. n) (n >= 1, caller-owned, read during the call only; seconds), like
/// solve_ivp's t_eval. The times must be finite, not before the current time and
/// non-decreasing (integration runs forward; equal times are each served); the monitor is
/// called at the current time only when times[0] equals it. The outputs are served exactly as
/// dal_evolve serves its grid: from the method's dense output after each accepted step, so the
/// steps, the end state and the statistics are bit for bit those of dal_evolve with a monitor
/// to the same end time, whatever the list (tests/test_evolve_at.c). opts.max_steps counts the
/// steps between two outputs. Returns DAL_OK at times[n - 1], DAL_STOPPED, DAL_EVENT or a
/// negative status as dal_evolve does; a bad list is refused before any step with a message
/// naming the index: times NULL or n = 0 DAL_E_ARG, a time NaN or inf DAL_E_NONFINITE,
/// times[i] < times[i - 1] DAL_E_ARG, times[0] before the current time DAL_E_TIME.
DAL_API int dal_evolve_at(const dal_system *sys, dal_state *st, const dal_solve_opts *opts,
                          const double *times, size_t n, dal_monitor_fn *monitor, void *ctx);

/// A stored dense trajectory (solve_ivp's dense_output): recorded during dal_advance,
/// dal_evolve and dal_evolve_at on a state it is attached to (dal_state_set_trajectory), and
/// evaluable at any time of the covered span after the run (dal_trajectory_eval).
///
/// What is stored: after every accepted step [a, b] the method's own dense output (the one
/// dal_evolve's outputs come from: see dal_evolve) is sampled at the 9 Chebyshev-Lobatto points
/// of the step (a, b and 7 between; b is the accepted step itself), q and qdot, as one record;
/// dal_trajectory_eval interpolates a record by the polynomial of degree 8 through its points
/// (barycentric form). Bulirsch-Stoer's long steps carry an interpolant of degree up to
/// 2 kappa + 1 and are stored as 4 records of a quarter step each. Where the method's
/// interpolant is a polynomial of degree <= 8 in t (RK4's cubic Hermite, DOPRI5's, CVODE's BDF
/// and IDA's of order <= 5) it is reproduced to rounding; for Adams (order up to 12),
/// Bulirsch-Stoer, Fehlberg 7(8) (a Hermite of degree 9 or 7) and the symplectic methods the
/// degree-8 interpolation error over a record is added. Measured (tests/test_trajectory.c prints
/// the table) against the elliptic pendulum released at 2 rad, at 2000 irregular times over [0,
/// 10], as the worst of |q - q_ref| and |qdot - qdot_ref| / w0, over rtol:
///
/// | method (form)  | rtol 1e-6 | rtol 1e-9 | rtol 1e-12 | distance to the dense output   |
/// |----------------|-----------|-----------|------------|--------------------------------|
/// | DOPRI5         | 1.14      | 4.99      |            | <= 5.3e-15 (rounding)          |
/// | Fehlberg 7(8)  | 1.56      | 0.99      |            | <= 1.0e-10 (interpolation)     |
/// | Bulirsch-Stoer | 0.41      | 0.04      | 0.04       | <= 6.4e-13 (interpolation)     |
/// | Adams (CVODE)  | 0.03      | 0.26      | 0.80       | <= 5.2e-15                     |
/// | BDF (CVODE)    | 0.02      | 0.41      |            | <= 4.7e-15                     |
/// | GGL (IDA; Cartesian pendulum) | 1.84 | 2.30 at 1e-8 |  | <= 1.0e-14                     |
///
/// and for the fixed-step methods at h = 0.01 (RK4, variational4; RATTLE4 on the Cartesian
/// pendulum) the distance to their dense output is <= 1.1e-14 (the error against the closed
/// form is then the method's own: 9.9e-8, 3.5e-7, 9.2e-5 rad),
///
/// so the stored trajectory is as accurate as the method's dense output (within the 16 x rtol
/// that dal_evolve promises for the adaptive methods).
///
/// What it costs: 8 evaluations of the dense output per record (each method interpolates from
/// data it holds for the step: Fehlberg's Hermite is built once per step), and memory: 3 + 18 n
/// doubles per record (n coordinates; 168 bytes for the pendulum), one record per accepted step (4
/// for Bulirsch-Stoer), grown by doubling (about log2(records) allocations over a run: a recorded
/// run allocates, an unrecorded one does not). A recorded run takes the steps of a run with
/// dense output (those of dal_evolve with a monitor: the same end state bit for bit; without
/// monitor or events dal_advance may take other steps, within the tolerance), and recording
/// changes neither the steps nor the outputs of dal_evolve / dal_evolve_at (bit for bit, every
/// method of the table; tests/test_trajectory.c). Not thread-safe:
/// one trajectory per state, read after the run (dal_trajectory_eval keeps its message in the
/// trajectory).
typedef struct dal_trajectory dal_trajectory;

/// Create an empty trajectory for `sys` (borrowed; must outlive it). *out is NULL on failure.
/// Returns DAL_OK, DAL_E_ARG (NULL argument), DAL_E_NOMEM.
DAL_API int dal_trajectory_create(const dal_system *sys, dal_trajectory **out);

/// Free the trajectory (NULL is fine). Detach it from its state first
/// (dal_state_set_trajectory(st, NULL)).
DAL_API void dal_trajectory_destroy(dal_trajectory *tr);

/// Attach `tr` (borrowed; must stay alive while attached) to the state, or detach with NULL.
/// Every later dal_advance / dal_evolve / dal_evolve_at on the state appends its accepted
/// steps. A run must start where the trajectory ends (or the trajectory is empty): a run from
/// another time (after dal_state_set, say) is refused with DAL_E_ARG naming both times. A run
/// stopped inside a step (a terminal event, a monitor) leaves the trajectory ending at the stop.
/// If storing a step fails for memory the run stops there with DAL_E_NOMEM (the state at that
/// step). Returns DAL_E_ARG (NULL st), DAL_E_STATE (tr of another system, or the state is
/// running), else DAL_OK.
DAL_API int dal_state_set_trajectory(dal_state *st, dal_trajectory *tr);

/// Evaluate the trajectory at time t of its span: q and qdot (n each, caller-owned; either may
/// be NULL). Accuracy: see dal_trajectory above. Returns DAL_OK; DAL_E_ARG for a NULL tr, an
/// empty trajectory, or t outside the span [t0, t1] (the message names the span and t);
/// DAL_E_NONFINITE for t NaN or inf. The message is kept in the trajectory
/// (dal_trajectory_errmsg).
DAL_API int dal_trajectory_eval(dal_trajectory *tr, double t, double *q, double *qdot);

/// The span [*t0, *t1] covered so far (seconds; each pointer may be NULL). Returns the number
/// of stored records (one per accepted step, four per Bulirsch-Stoer step; 0 for an empty
/// trajectory, whose span is NaN), or DAL_E_ARG for a NULL tr.
DAL_API long dal_trajectory_span(const dal_trajectory *tr, double *t0, double *t1);

/// Message of the last failing call on the trajectory ("" if none; "" for NULL).
DAL_API const char *dal_trajectory_errmsg(const dal_trajectory *tr);

/// CSV writer for monitors: a monitor context writing t, q..., qdot..., E, h per row, or the
/// columns of a selection (output.h). Zero it, then set fp (and columns).
typedef struct dal_csv {
  FILE *fp;        ///< output stream (borrowed)
  int header_done; ///< set after the header row is written
  int wrap_angles; ///< if nonzero, write q wrapped to [-pi, pi) (principal value)
  /// the columns to write (borrowed; output.h: dal_columns_create), NULL for the default
  /// t, q..., qdot..., E, h; the header is then the columns' names
  const struct dal_columns *columns;
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
