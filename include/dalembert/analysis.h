// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Analysis: exact linearization (with inputs), normal modes and stability, equilibria
/// and their continuation in one parameter, the state-transition matrix and parameter
/// sensitivities, Lyapunov exponents; in minimal coordinates and on the constraint manifold
/// (docs/analysis.md).
///
/// The state derivative of a system in minimal coordinates is f(t, y) = (qdot, qddot) with
/// y = (q, qdot) and qddot from M qddot = Q - c. Everything here rests on its exact tangent:
/// the equations of motion are written R(t, q, qdot, qddot) = M qddot + c - Q = 0, and
///   K = dR/dq,  C = dR/dqdot  (at fixed qddot),  M = dR/dqddot,
/// so a small variation obeys M dq'' + C dq' + K dq = 0 (with coefficients that depend on time
/// away from a steady state), and df/dy = [0, I; -M^-1 K, -M^-1 C]. No finite differences:
/// K and C come from jets. Their derivatives of M, Q and c need second derivatives of the maps
/// and potentials (by polarization of order-2 coefficients along sums of directions) and the
/// derivative of the curvature terms gamma, a third derivative D^3 r[dq, w, w] with
/// w = (qdot, 1) (by polarization of the order-3 coefficient d3 of dal_jet along the curves
/// s -> (q + s (qdot +- dq) + s^2/2 (qddot +- 2 dqdot), t + s (1 +- dt)); see jet.h).
///
/// What the tangent covers: particle systems placed by primitives or a whole-system map, in
/// minimal coordinates or with constraint rows phi(q, t) = 0 (redundant coordinates, loops
/// closed by constraints, moving constraints), with gravity, springs, dampers and jet
/// potentials U(r, t), U(q, t), rheonomic maps and moving anchors included; and systems given
/// by a Lagrangian L(t, q, qdot) (with U(q, t)) in minimal coordinates, whose tangent needs third
/// partials of L, taken the same way (polarization of d3 along curves in (q, qdot, t)).
///
/// With m constraint rows (G = dphi/dq of full rank m) the motion lives on the manifold
/// phi = 0, G qdot + dphi/dt = 0 of dimension 2k, k = n - m. The tangent is exact there too:
/// the residual becomes R - G' lambda (its q-derivative gains the constraint curvature
/// -sum lambda_i Hess phi_i, by polarization of the constraints' order-2 coefficients), and the
/// acceleration-level rows G qddot + gamma_phi = 0 are differentiated along each tangent
/// direction through their order-3 coefficient (the derivative of the constraint curvature).
/// The reduced quantities (dal_linearize, dal_normal_modes) are in independent coordinates
/// xi and velocities eta along an orthonormal basis N (n x k) of the null space of G:
/// dq = N xi, dqdot = N eta + Y xi with Y = -G^+ d(G qdot + dphi/dt)/dq (docs/analysis.md).
/// The state handed to them must be on the manifold (dal_make_consistent); an inconsistent
/// one is DAL_E_ARG naming the row.
///
/// It refuses, with DAL_E_UNSUPPORTED and a message naming the cause:
///  - a Lagrangian together with constraint rows;
///  - force callbacks given as plain doubles (dal_builder_add_force, dal_builder_add_genforce):
///    they have no exact derivative; write the force as a potential over jets if it has one.
/// A user jet function built with the order-2 constructors dal_jet_make / dal_jet_chain has no
/// third derivative: the tangent reports it (DAL_E_DOMAIN naming the function).
///
/// Every function takes the system and a state; it evaluates the state (as dal_forward does)
/// and reports failures in dal_state_errmsg(st). Matrices are column-major; n = number of
/// coordinates.
#ifndef DAL_ANALYSIS_H
#define DAL_ANALYSIS_H

#include "dalembert/base.h"
#include "dalembert/solve.h"
#include "dalembert/state.h"
#include "dalembert/system.h"

#ifdef __cplusplus
extern "C" {
#endif

// ---------------------------------------------------------------------------------------------
// linearization

/// Linearize the equations of motion at the state's (t, q, qdot): with qddot the state's
/// acceleration, a variation obeys M dq'' + C dq' + K dq = 0 to first order, where
/// M = mass matrix, C = dR/dqdot (damping and gyroscopic terms), K = dR/dq (stiffness,
/// including centrifugal terms and, away from an equilibrium, the derivative of M applied to
/// qddot), R = M qddot + c - Q. Each output is k x k column-major, caller-owned, and may be
/// NULL; k = n without constraints. At an equilibrium (qdot = qddot = 0) of a conservative
/// scene K is the Hessian of the (effective) potential and C the gyroscopic matrix
/// (antisymmetric).
/// With m constraint rows, k = n - m and the matrices are the reduced ones in the independent
/// coordinates xi (dq = N xi, N of dal_linearize_full): M_r = N' M N, and C_r, K_r such that
/// M_r xi'' + C_r xi' + K_r xi = 0 is the tangent on the manifold (at a static equilibrium of
/// scleronomic constraints K_r = N' (K - sum lambda_i Hess phi_i) N, C_r = N' C N).
/// Returns DAL_OK; DAL_E_UNSUPPORTED (see the file comment); the statuses of dal_forward;
/// DAL_E_DOMAIN when a jet function gives a non-finite or unknown third derivative;
/// DAL_E_NOMEM.
DAL_API int dal_linearize(const dal_system *sys, dal_state *st, double *M, double *C, double *K);

/// The full-space linearization and the basis that maps it to the reduced one (constraints):
/// M (n x n) the mass matrix, C = d(R - G' lambda)/dqdot, K = d(R - G' lambda)/dq at the
/// state's qddot and frozen multipliers lambda (K includes the constraint curvature
/// -sum lambda_i Hess phi_i), G = dphi/dq (m x n), and N (n x k, k = n - m) an orthonormal
/// basis of the null space of G (dq = N xi). A variation obeys M dq'' + C dq' + K dq = G' dlambda
/// with G dq = 0 to first order at fixed time; at a static equilibrium of scleronomic
/// constraints N' M N, N' C N, N' K N are dal_linearize's matrices. All outputs column-major,
/// caller-owned, nullable; without constraints G is untouched and N = I. Statuses of
/// dal_linearize, and DAL_E_SINGULAR when G has rank below m (the message names the row).
DAL_API int dal_linearize_full(const dal_system *sys, dal_state *st, double *M, double *C,
                               double *K, double *G, double *N);

/// Linearization with inputs u: M dq'' + C dq' + K dq = B du (the matrices of dal_linearize)
/// and the first-order x' = Af x + Bf u, x = (dq, dqdot), at the state. Inputs are named:
/// "force:<coordinate>" (a generalized force added to Q on that coordinate, by name or 0-based
/// index; units of Q) or a parameter with an exact derivative in the syntax of params.h
/// ("mass:<particle>", "gravity:<i>", "spring:<j>:k", "spring:<j>:L", "damper:<j>:c").
///  B (k x ninput), Af (2k x 2k), Bf (2k x ninput): column-major, caller-owned, nullable;
///  k = n without constraints (Af is dal_vector_field_jacobian's A), k = n - m with them: the
///  reduced coordinates of dal_linearize (x = (xi, eta), dq = N xi), B = N' b and
///  Bf = (0, N' da) with da the KKT response to the input.
/// Primitive and constraint parameters (a prescribed drive's amplitude) have no exact
/// derivative: DAL_E_UNSUPPORTED naming the input. Statuses of dal_linearize; DAL_E_ARG for
/// an unknown input.
DAL_API int dal_linearize_inputs(const dal_system *sys, dal_state *st, int ninput,
                                 const char *const *inputs, double *B, double *Af, double *Bf);

/// Jacobian of the vector field f(t, y) = (qdot, qddot), y = (q, qdot), at the state (not the
/// Jacobian of the flow map):
/// A = df/dy (2n x 2n, column-major, caller-owned) and, if ft is not NULL, ft = df/dt (2n):
/// the explicit time dependence (zero for an autonomous scene). With constraint rows, f is the
/// index-1 vector field (qddot and lambda from the KKT system) in the full space: the tangent
/// space of the manifold is invariant under A, whose other 2m eigenvalues are zero (the drift
/// off phi = 0). Same statuses as dal_linearize; DAL_E_SINGULAR for a singular KKT matrix.
DAL_API int dal_vector_field_jacobian(const dal_system *sys, dal_state *st, double *A, double *ft);

// ---------------------------------------------------------------------------------------------
// the flow map: state-transition matrix and parameter sensitivities

/// Integrate from the state's (t0, q, qdot) to t1 > t0 with the variational equations
/// Phi' = A Phi, Phi(t0) = I and S' = A S + df/dp, S(t0) = 0 (A = df/dy, the exact tangent of
/// dal_vector_field_jacobian) carried along as one first-order problem through the library's
/// integrator opts->method (DOPRI5 for AUTO; FEHLBERG78, BS and RK4 too; the implicit and
/// structure-preserving ones are DAL_E_UNSUPPORTED), whose error control with opts->rtol and
/// atol covers Phi and S as well as the trajectory. opts may be NULL (defaults).
///  Phi (2n x 2n, column-major, caller-owned, nullable): dy(t1)/dy(t0), y = (q, qdot).
///  params (nparam names in the syntax of params.h: "mass:bob", "gravity:1", "spring:0:k",
///    "spring:0:L", "damper:0:c"), S (2n x nparam, caller-owned): dy(t1)/dp, the derivative
///    with respect to each parameter at the state's values (nparam = 0 and S = NULL for none).
///    Primitive and constraint parameters ("place:...", "con:...") and Lagrangian systems have
///    no exact derivative: DAL_E_UNSUPPORTED.
/// With constraint rows the trajectory runs the index-1 vector field in the full space (no
/// Baumgarte terms) from a consistent state; Phi z for z in the tangent space of the manifold
/// (see dal_linearize_full's N) is the derivative of the constrained flow, and S stays in it;
/// Phi on other directions is that of the index-1 field (linear drift of phi).
/// On success the state holds (t1, q, qdot), evaluated; its integrator history is dropped.
/// Cost: 2n + nparam tangent columns (the full tangent at every stage).
/// Returns DAL_OK; DAL_E_ARG (sizes, t1, options, unknown parameter, a state off the
/// manifold); DAL_E_UNSUPPORTED (method, parameter, or see the file comment); the integrator's
/// statuses (DAL_E_STEP, DAL_E_MAXSTEPS, ...) and those of dal_vector_field_jacobian.
DAL_API int dal_state_transition(const dal_system *sys, dal_state *st, const dal_solve_opts *opts,
                                 double t1, double *Phi, int nparam, const char *const *params,
                                 double *S);

// ---------------------------------------------------------------------------------------------
// normal modes and stability

/// Stability verdict of a linearization, from the eigenvalues lambda of df/dy (LAPACK dgeev)
/// with the tolerance tau = max(1e-6 max(max |lambda|, ||M^-1 K||_F^1/2, ||M^-1 C||_F),
/// (e_K / ||M||_F)^1/2, e_C / ||M||_F), where e_K, e_C are 64 ulps of the summed magnitudes of
/// the terms that make up K and C (their rounding: a zero eigenvalue moves by sqrt(dK / M)):
typedef enum dal_stability {
  DAL_UNSTABLE = -1,  ///< an eigenvalue with real part > tau: perturbations grow
  DAL_MARGINAL = 0,   ///< no real part > tau but an eigenvalue |lambda| <= tau (a zero
                      ///< frequency, e.g. at a bifurcation): the linearization cannot decide
  DAL_NEUTRAL = 1,    ///< all real parts within tau of 0 or below -tau, no zero eigenvalue,
                      ///< some on the imaginary axis: oscillations neither grow nor decay
                      ///< (conservative scenes; nonlinear terms decide beyond)
  DAL_ASYMPTOTIC = 2, ///< every real part < -tau: perturbations decay
} dal_stability;

/// Short name of a verdict ("unstable", "marginal", "neutral", "asymptotic", "unknown").
DAL_API const char *dal_stability_name(dal_stability s);

/// Normal modes and stability at the state (meant for an equilibrium, see dal_equilibrium).
typedef struct dal_modes {
  dal_stability verdict; ///< from the eigenvalues of the full df/dy (C and K as they are)
  double max_real;       ///< largest real part of those eigenvalues (1/time)
  double tau;            ///< the tolerance of the verdict (1/time)
  double asymmetry;      ///< ||K - K'||_F / ||K||_F: 0 for a conservative equilibrium
  double gyroscopic;     ///< ||C||_F / (||K||_F ||M||_F)^1/2: 0 without damping or Coriolis
  double accel;          ///< max_i |qddot_i| at the state: 0 at an equilibrium
} dal_modes;

/// Normal modes at the state: the generalized symmetric eigenproblem
/// K_s x = omega^2 M x with K_s = (K + K')/2 (LAPACK dsygv), and the eigenvalues of the
/// first-order Jacobian df/dy for the verdict (which does account for C, gyroscopic
/// stabilization included).
///  omega2 (n, caller-owned, may be NULL): omega^2 ascending (1/time^2; negative = a direction
///    of exponential growth when C = 0); the frequencies are sqrt(omega2) in rad/time.
///  shapes (n x n, may be NULL): column i is the mode shape of omega2[i], M-orthonormal
///    (x_i' M x_j = delta_ij), its largest component positive.
///  lambda_re, lambda_im (2n each, may be NULL): eigenvalues of df/dy, sorted by decreasing
///    real part, then by increasing imaginary part.
///  out (may be NULL): verdict and diagnostics.
/// The modes describe small oscillations only where accel ~ 0 and qdot = 0 (an equilibrium or
/// a steady relative equilibrium); elsewhere they are those of the frozen linearization.
/// With m constraint rows the sizes are k = n - m: omega2 (k), lambda_re / lambda_im (2k),
/// from the reduced matrices of dal_linearize, and shapes (n x k) are mapped back to the
/// coordinates (x = N xi, still M-orthonormal); the state must be on the manifold.
/// Statuses of dal_linearize; DAL_E_SINGULAR if LAPACK fails (named in the message);
/// DAL_E_UNSUPPORTED when k = 0 (the constraint rows fix every coordinate: no modes, no
/// verdict).
DAL_API int dal_normal_modes(const dal_system *sys, dal_state *st, double *omega2, double *shapes,
                             double *lambda_re, double *lambda_im, dal_modes *out);

// ---------------------------------------------------------------------------------------------
// equilibria

/// Options of dal_equilibrium. Always start from dal_default_equilibrium_opts().
typedef struct dal_equilibrium_opts {
  int cookie;      ///< set by dal_default_equilibrium_opts; do not touch
  double xtol;     ///< converged when every Newton step |dq_i| <= xtol (1 + |q_i|); 1e-12
  int max_iter;    ///< Newton iterations at most; 50
  double max_step; ///< largest |dq_i| of one step (the step is scaled down to it); 0: none
} dal_equilibrium_opts;

/// Fill *o with the defaults (xtol 1e-12, 50 iterations, no step bound).
DAL_API dal_equilibrium_opts dal_default_equilibrium_opts(void);

/// What dal_equilibrium found.
typedef struct dal_equilibrium_report {
  int iterations;  ///< Newton iterations taken
  double step;     ///< max |dq_i| of the last step
  double accel;    ///< max |qddot_i| at the solution (1/time^2 x units of q)
  double unsteady; ///< max |d qddot_i / dt| at the solution: 0 when it is an equilibrium at
                   ///< every time (a static or a steady relative equilibrium), non-zero when
                   ///< it only holds at the state's t (a driven scene)
} dal_equilibrium_report;

/// Find an equilibrium qddot(t, q, 0) = 0 by Newton's method on q with the exact Jacobian K
/// (dq = K^-1 (Q - c), LAPACK dgesv), starting from the state's q at the state's time t with
/// qdot set to 0. For a rheonomic scene steady in its coordinates (a bead on a ring turning at
/// a constant rate, q measured in the ring) this is a relative equilibrium: the report's
/// `unsteady` tells whether it holds at all times. On success the state holds (t, q*, 0),
/// evaluated. `o` may be NULL (defaults); `rep` may be NULL.
/// With m constraint rows, Newton runs on (q, lambda) for the static KKT system
/// c - Q - G' lambda = 0, phi = 0 with the exact Jacobian [K - sum lambda_i Hess phi_i, -G';
/// G, 0] (the start need not be on the manifold); on success dal_state_lambda(st) holds the
/// multipliers at the equilibrium: the static loads (lambda = -T for a rod in tension T). Only
/// static points (qdot = 0) are sought: a moving constraint that leaves the point in place (a
/// turning ring's bottom) is fine, a converged point that it carries along (dphi/dt != 0) is
/// DAL_E_UNSUPPORTED, and relative equilibria carried by the constraint (a bead off the axis of
/// a turning ring in Cartesian coordinates) are not sought (use a map in the moving frame).
/// Returns DAL_OK; DAL_E_SINGULAR when K (or the KKT Newton matrix) is singular (a bifurcation
/// point or a neutral direction; the message names the coordinate); DAL_E_CONV after max_iter
/// iterations or a non-finite step (the state then holds the last iterate); DAL_E_ARG for bad
/// options; the statuses of dal_linearize.
DAL_API int dal_equilibrium(const dal_system *sys, dal_state *st, const dal_equilibrium_opts *o,
                            dal_equilibrium_report *rep);

/// Build the system for parameter value p (e.g. a ring's turning rate) into *out; the
/// continuation destroys it with dal_system_destroy when done. Return 0, or non-zero to stop
/// (the continuation then returns DAL_E_CALLBACK).
typedef int dal_rebuild_fn(double p, dal_system **out, void *ctx);

/// Kind of a point reported along a branch.
typedef enum dal_branch_kind {
  DAL_BRANCH_REGULAR = 0,  ///< a point of the parameter grid
  DAL_BRANCH_CRITICAL = 1, ///< a located point where a real eigenvalue of K crosses zero
                           ///< along the branch (det K changes sign: a pitchfork or
                           ///< transcritical bifurcation), between two grid points whose det K
                           ///< differ in sign. A fold (the branch turns back in p) is not one:
                           ///< it ends the continuation with DAL_E_CONV (see dal_continue)
} dal_branch_kind;

/// Called at every converged point of a branch with the state at the equilibrium
/// (t, q*, qdot = 0, evaluated), the verdict of dal_normal_modes there and the point's kind.
/// sys and st are valid during the call only. Return 0 to continue, non-zero to stop.
typedef int dal_branch_fn(double p, const dal_system *sys, const dal_state *st,
                          dal_stability verdict, dal_branch_kind kind, void *ctx);

/// Options of dal_continue. Always start from dal_default_continuation_opts().
typedef struct dal_continuation_opts {
  int cookie;                  ///< set by dal_default_continuation_opts; do not touch
  double p0;                   ///< first parameter value
  double p1;                   ///< last parameter value (may be below p0)
  int npoints;                 ///< grid points from p0 to p1, both included (>= 2); 41
  double t;                    ///< time at which the equilibria are sought; 0
  int locate;                  ///< locate the critical points (bisection on sign det K); 1
  double ptol;                 ///< parameter tolerance of the located points; 1e-10 |p1 - p0|
  dal_equilibrium_opts newton; ///< options of every Newton solve
} dal_continuation_opts;

/// Fill *o with the defaults (see the fields), p0 = 0, p1 = 1.
DAL_API dal_continuation_opts dal_default_continuation_opts(void);

/// Report of a continuation.
typedef struct dal_continuation_report {
  int npoints;   ///< grid points converged and reported
  int ncritical; ///< critical points located and reported
  double p_end;  ///< last parameter value reached
  char msg[512]; ///< why the branch ended early ("" when it reached p1)
} dal_continuation_report;

/// Natural-parameter continuation of one branch of equilibria: for p on the grid from p0 to p1
/// build the system (rebuild), solve for the equilibrium by dal_equilibrium starting from the
/// previous solution (from q0 (n values) at the first point; a secant predictor from the two
/// previous ones after that), classify it by dal_normal_modes and report it to `point`.
/// Between grid points where det K changes sign the critical parameter is located by
/// bisection (every trial point an exact Newton solve) and reported as DAL_BRANCH_CRITICAL.
/// With constraint rows q0 and the states hold all n coordinates and det K is that of the
/// reduced k x k stiffness of dal_linearize.
/// A branch that folds back (a turning point in p) cannot be followed past the fold: the
/// continuation then stops with DAL_E_CONV and says where. To follow another branch through a
/// pitchfork, start a second continuation from a point on it.
/// Returns DAL_OK when p1 was reached; DAL_E_CONV / DAL_E_SINGULAR (the branch ended, rep->msg
/// says where and why, the points before were reported); DAL_E_CALLBACK (rebuild or point
/// asked to stop or failed); DAL_E_ARG (bad options or sizes). rep may be NULL.
DAL_API int dal_continue(dal_rebuild_fn *rebuild, const double *q0, const dal_continuation_opts *o,
                         dal_branch_fn *point, dal_continuation_report *rep, void *ctx);

// ---------------------------------------------------------------------------------------------
// Lyapunov exponents

/// Options of dal_lyapunov. Always start from dal_default_lyapunov_opts().
typedef struct dal_lyapunov_opts {
  int cookie;        ///< set by dal_default_lyapunov_opts; do not touch
  int nexp;          ///< exponents wanted, 1 .. 2n (2(n - m) with constraint rows; the
                     ///< largest ones); 0 (default): all of them
  double t_end;      ///< integrate from the state's t to t_end (> t); required
  double transient;  ///< time discarded before the averages start (the tangent vectors align
                     ///< with the leading directions meanwhile); 0
  double renorm;     ///< time between QR reorthonormalizations (> 0); 1
  dal_method method; ///< the library's ODE integrator that runs trajectory and tangent
                     ///< vectors: DAL_METHOD_AUTO (default: its own rule, validated on the
                     ///< tangent system, not dal_advance's: DOPRI5 above rtol 1e-6, Adams
                     ///< down to 1e-12, Bulirsch-Stoer below; Adams at the default rtol),
                     ///< DOPRI5, FEHLBERG78, BS, ADAMS, BDF, or RK4 (fixed step `h`); the
                     ///< structure-preserving methods are DAL_E_UNSUPPORTED
  double rtol;       ///< relative tolerance, a global target as for dal_advance (the method's
                     ///< calibrated factor applies) on trajectory and tangent vectors; 1e-10
  double atol;       ///< absolute tolerance (> 0); 1e-10
  double h;          ///< RK4 step (> 0; the last step before a QR is shortened to land on it);
                     ///< 1e-3
  const double *y0;  ///< NULL (default): the tangent vectors start as the first nexp unit
                     ///< vectors of y = (q, qdot); else nexp initial vectors (2n each,
                     ///< column-major 2n x nexp), which must be linearly independent
  int nblocks;       ///< the error estimate uses blockings with at least this many blocks
                     ///< (>= 2); 4
  long max_steps;    ///< steps at most; 10000000
} dal_lyapunov_opts;

/// Fill *o with the defaults (see the fields); t_end must still be set.
DAL_API dal_lyapunov_opts dal_default_lyapunov_opts(void);

/// Called after every reorthonormalization that lies past the transient: time t and the
/// running estimates (nexp), in the order of the QR columns (decreasing once the tangent
/// vectors have aligned; only dal_lyapunov's final exponents are sorted largest first), valid
/// during the call. Return 0 to continue,
/// non-zero to stop (dal_lyapunov then returns DAL_OK with the estimates so far).
typedef int dal_lyapunov_fn(double t, const double *exponents, int nexp, void *ctx);

/// Lyapunov exponents by the method of Benettin, Galgani, Giorgilli and Strelcyn (Meccanica
/// 15, 1980): the trajectory y(t) and nexp tangent vectors Y' = (df/dy) Y (the exact tangent,
/// see dal_vector_field_jacobian) are integrated together; every `renorm` time units Y is
/// reorthonormalized by a QR factorization (LAPACK dgeqrf) and log |R_ii| accumulated; after
/// the transient, exponents[i] = (sum of log |R_ii|) / (elapsed time), largest first.
///  exponents (nexp, caller-owned): the estimates (1/time).
///  errors (nexp, may be NULL): a 95% half-width of each, from the scatter of the local
///    exponents (log |R_jj| over each renorm interval) by Flyvbjerg-Petersen blocking: the
///    intervals are grouped into blocks of 1, 2, 4, ... consecutive ones; for every blocking
///    with at least `nblocks` blocks, Student's t (blocks - 1 degrees of freedom, 95%) times
///    the standard error of the block exponents; the largest of these. Longer blocks catch
///    correlations over longer times (an orbit that sticks near a regular island). It
///    measures what this orbit shows: another orbit of a mixed phase space may have another
///    finite-time exponent (SICM's driven pendulum over 1000 s, seven starts 0.001 apart:
///    0.32 ... 0.66, standard deviation 0.12, errors 0.06 ... 0.21, five of seven intervals
///    hold the median; tests/test_analysis_lyapunov.c); run several starts to see that. Not
///    in it: a bias that decays like 1/time (the initial alignment; raise `transient`).
///  monitor (may be NULL): called after each reorthonormalization past the transient with
///    the running estimates in the order of the QR columns (decreasing once converged).
/// The augmented system (trajectory and tangent vectors) runs on the library's integrators,
/// with dal_advance's step control, progress guards and failure messages; a fresh integrator
/// per renorm interval (the QR changes the vectors), its first step the last one before.
/// With m constraint rows there are 2(n - m) exponents (nexp at most that; 0: all): the
/// trajectory runs the index-1 vector field with the full-space KKT tangent, the vectors start
/// as a basis of the manifold's tangent space, and at every reorthonormalization the trajectory
/// is projected back onto the manifold and the vectors onto its tangent space (y0 must be
/// NULL: DAL_E_UNSUPPORTED otherwise); the state must be consistent.
/// On success the state holds the end of the trajectory (evaluated; its integrator history is
/// dropped); on failure it is unchanged and its message says what failed and when. Units:
/// 1/time.
/// Returns DAL_OK; DAL_E_ARG (options, nexp, a dependent y0); DAL_E_NONFINITE (y0);
/// DAL_E_UNSUPPORTED (method, or see the file comment); the integrators' statuses
/// (DAL_E_STEP, DAL_E_MAXSTEPS for max_steps in all, ...); the statuses of
/// dal_vector_field_jacobian at the failing time.
DAL_API int dal_lyapunov(const dal_system *sys, dal_state *st, const dal_lyapunov_opts *o,
                         double *exponents, double *errors, dal_lyapunov_fn *monitor, void *ctx);

#ifdef __cplusplus
}
#endif
#endif
