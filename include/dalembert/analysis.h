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

#include <stddef.h>

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
/// integrator opts->method (AUTO: DOPRI5 down to rtol 1e-12, BS below; FEHLBERG78, BS and RK4
/// too; the implicit and structure-preserving ones are DAL_E_UNSUPPORTED), whose error control with
/// opts->rtol and atol covers Phi and S as well as the trajectory. opts may be NULL (defaults).
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
  int frozen;            ///< 1: the system depends on time explicitly and these are the modes
                         ///< of the linearization frozen at the state's t
                         ///< (dal_normal_modes_frozen); 0 otherwise
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
/// Time dependence is never frozen silently: on a scene whose equations depend on time
/// explicitly (dal_time_dependence) the modes are given only where the motion through the
/// state is steady for its linearization (its eigenvalues at t + 0.37, 1.9 and 4.3 along the
/// motion, followed by dal_advance at rtol 1e-10, agree with those at t within 1e-6 of their
/// size or tau: the bottom of a turning circle in Cartesian coordinates, a relative
/// equilibrium carried by a turning constraint); elsewhere (a driven pendulum's bottom) it is
/// DAL_E_UNSUPPORTED naming the dependence, dal_floquet and dal_normal_modes_frozen.
/// Statuses of dal_linearize; DAL_E_SINGULAR if LAPACK fails (named in the message);
/// DAL_E_UNSUPPORTED when k = 0 (the constraint rows fix every coordinate: no modes, no
/// verdict), or see above.
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
  int frozen_time; ///< 1: accept an equilibrium of the equations frozen at the state's t for
                   ///< an explicitly time-dependent system (dal_time_dependence), and let
                   ///< dal_continue classify it by dal_normal_modes_frozen; 0 (default)
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

// ---------------------------------------------------------------------------------------------
// periodic motion: explicit time dependence, Floquet multipliers, periodic orbits

/// Whether the equations of motion of sys depend on time explicitly (a drive, a moving pivot,
/// a potential or constraint in t) in its coordinates. Decided on the exact df/dt of the
/// vector field (dal_vector_field_jacobian's ft, from jets) at the state and at five
/// pseudo-random points around it (t moved by up to 7 time units, q and qdot by up to 30% of
/// 1 + |.|; with constraint rows each point is made consistent first): dependent when
/// |df/dt| > 1e-9 ||A|| (|f| + ||A|| |y|) at one of them. This covers user jet callbacks
/// alike; a dependence confined to a region no probe reaches (a drive that switches on
/// later than t + 7) is missed. A scene that moves steadily in its own coordinates (a bead
/// measured in a uniformly turning ring) is not dependent: its equations are those of the
/// co-rotating frame, where equilibria and modes mean what they say (relative equilibria).
///  what (len bytes, nullable): the finding in words, naming what moves with t (placements
///    with dr/dt != 0 at fixed q, constraints with dphi/dt != 0) at the state.
/// The state is left as given, evaluated. Returns 1 (dependent), 0 (not), or a negative
/// status of dal_vector_field_jacobian at the state (the tangent must cover the system).
DAL_API int dal_time_dependence(const dal_system *sys, dal_state *st, char *what, size_t len);

/// dal_normal_modes of the linearization frozen at the state's time, asked for by name for
/// an explicitly time-dependent system (dal_normal_modes refuses one): out->frozen is then 1.
/// The verdict describes the frozen equations only, not the driven motion (use dal_floquet).
DAL_API int dal_normal_modes_frozen(const dal_system *sys, dal_state *st, double *omega2,
                                    double *shapes, double *lambda_re, double *lambda_im,
                                    dal_modes *out);

/// What dal_floquet found. The verdict uses dal_stability with these meanings (names by
/// dal_floquet_verdict_name): DAL_UNSTABLE a multiplier |mu| > 1 + accuracy; DAL_ASYMPTOTIC
/// every |mu| < 1 - accuracy; DAL_MARGINAL ("boundary") some |mu| within the accuracy of 1 and
/// within twice it of +1 or -1, where a pair can leave the unit circle (a fold or
/// period-doubling boundary: the linearization cannot decide); DAL_NEUTRAL ("stable") the
/// rest: multipliers on the unit circle away from +-1 (Hamiltonian scenes) or inside it.
/// (Pairs colliding on the circle away from +-1, Krein collisions, are not examined.)
typedef struct dal_floquet_report {
  dal_stability verdict; ///< see above
  int count;             ///< multipliers: 2n, or 2(n - m) with m constraint rows
  double period;         ///< the period T used (time)
  double max_abs;        ///< the largest |mu|
  double accuracy;       ///< the multipliers' error estimate: the largest distance between
                         ///< them at rtol and at 10 rtol (matched nearest first), at least
                         ///< 1000 ulps of ||monodromy||
  double det;            ///< product of the multipliers: exp(int_0^T tr A dt), 1 for a scene
                         ///< without damping (Liouville)
  double trace;          ///< trace of the monodromy (sum of the multipliers)
  double gap;            ///< max_i |y_i(T) - y_i(0)| / (1 + |y_i(0)|): how far the state is
                         ///< from returning (0 on a T-periodic solution)
} dal_floquet_report;

/// Floquet analysis of the T-periodic solution through the state (an equilibrium of a
/// periodically driven scene such as the driven pendulum's bottom, or a periodic orbit from
/// dal_periodic_orbit): the monodromy matrix Phi(t + T, t) by dal_state_transition (exact
/// variational equations), its eigenvalues mu (Floquet multipliers; the exponents are
/// log(mu) / T, real part the growth rate in 1/time, imaginary part defined modulo 2 pi / T),
/// computed twice (opts->rtol and 10 rtol) for their accuracy, and the verdict.
///  opts: the integrator (an explicit method, see dal_state_transition); NULL: the defaults
///    with rtol 1e-10.
///  period: T > 0, e.g. the drive's period 2 pi / omega or a multiple of it.
///  mu_re, mu_im (count each, nullable): the multipliers by decreasing |mu|, then argument.
///  monodromy (count x count, column-major, nullable): the monodromy at opts->rtol, in
///    (q, qdot) without constraints; with m constraint rows reduced to the manifold's
///    tangent space in the coordinates (xi, eta) of dal_linearize (dq = N xi,
///    dqdot = N eta + Y xi, N at the state): count = 2(n - m).
///  rep (nullable): verdict, accuracy, det, trace, gap.
/// The state must lie on a T-periodic solution: a state that does not return within
/// 1e-6 + 1000 rtol (relative) is DAL_E_ARG naming the coordinate that misses most. With
/// constraint rows it must be consistent. On return the state is back at its start,
/// evaluated. Returns DAL_OK; DAL_E_ARG; DAL_E_UNSUPPORTED (no degrees of freedom, or see
/// dal_state_transition); the statuses of dal_state_transition; DAL_E_SINGULAR (LAPACK).
DAL_API int dal_floquet(const dal_system *sys, dal_state *st, const dal_solve_opts *opts,
                        double period, double *mu_re, double *mu_im, double *monodromy,
                        dal_floquet_report *rep);

/// The name of a Floquet verdict: "unstable", "boundary", "stable", "asymptotically stable".
DAL_API const char *dal_floquet_verdict_name(dal_stability s);

/// Options of dal_periodic_orbit. Always start from dal_default_orbit_opts().
typedef struct dal_orbit_opts {
  int cookie;           ///< set by dal_default_orbit_opts; do not touch
  double period;        ///< the period T (> 0, required): k times the drive period for a
                        ///< driven scene, or the first guess of a free period
  int free_period;      ///< 1: an autonomous scene whose period is an unknown, fixed by the
                        ///< phase condition f(y0) . dy0 = 0; 0 (default): T fixed
  double xtol;          ///< converged when max_i |y_i(T) - y_i(0)| / (1 + |y_i(0)|) <= xtol;
                        ///< 1e-9 (above the integration error at solve.rtol)
  int max_iter;         ///< Newton iterations at most; 30
  dal_solve_opts solve; ///< the integrator of the arcs and of the multipliers (an explicit
                        ///< method, see dal_state_transition); defaults with rtol 1e-11
} dal_orbit_opts;

/// The defaults (see the fields); period must still be set.
DAL_API dal_orbit_opts dal_default_orbit_opts(void);

/// What dal_periodic_orbit found.
typedef struct dal_orbit_report {
  int iterations;             ///< Newton steps taken
  double period;              ///< the orbit's period (the fixed one, or the one found)
  double residual;            ///< the final return gap max_i |y_i(T) - y_i(0)| / (1 + |y_i(0)|)
  dal_floquet_report floquet; ///< the orbit's multipliers' report (dal_floquet); with a free
                              ///< period the trivial multiplier along the orbit (and its
                              ///< partner when det = 1, the neighbouring orbits of other
                              ///< energy) is left out of the verdict
} dal_orbit_report;

/// A periodic orbit through (near) the state by Newton shooting on the exact
/// state-transition matrix (single shooting): y(t + T; y0) = y0, Newton matrix Phi - I from
/// dal_state_transition, with the free period as one more unknown and the phase condition
/// f(y0) . dy0 = 0 for an autonomous scene. With m constraint rows the correction lies in the
/// tangent space of the manifold (the basis of dal_floquet) and the start is made consistent
/// after each step (dal_make_consistent). The start time is the state's t (the drive's phase).
///  mu_re, mu_im (2(n - m) each, nullable): the orbit's Floquet multipliers (dal_floquet).
///  rep (nullable): iterations, period, residual, multipliers' report.
/// On success the state holds the orbit's start (t, q, qdot), evaluated; on failure the state
/// as given. An orbit whose arc is too unstable for one shot (|mu| ~ 1/rtol) needs a start
/// close to it (multiple shooting is not offered).
/// Returns DAL_OK; DAL_E_ARG (options); DAL_E_CONV (no convergence in max_iter steps: the
/// message gives the gap, start and period); DAL_E_SINGULAR (Phi - I singular: a multiplier at
/// 1); the statuses of dal_state_transition, dal_make_consistent and dal_floquet.
DAL_API int dal_periodic_orbit(const dal_system *sys, dal_state *st, const dal_orbit_opts *o,
                               double *mu_re, double *mu_im, dal_orbit_report *rep);

/// What dal_relative_equilibrium found.
typedef struct dal_relative_report {
  int iterations;  ///< Newton steps taken
  double residual; ///< max |g(y)| / max(|qddot|, |P qdot|) at the solution (g: the
                   ///< co-rotating field, zero at a relative equilibrium)
} dal_relative_report;

/// A relative equilibrium of a scene in Cartesian coordinates turning uniformly at `rate`
/// (rad/time) about the axis through the origin along `axis` (3 values, any length > 0): the
/// motion q(t) = exp(P (t - t0)) q*, qdot = P q, with P the rotation generator acting on every
/// particle's (x, y, z) (a conical pendulum, a bead on a turning circle, in Cartesian
/// coordinates). Found by Newton's method (minimum-norm steps: the relative equilibria of a
/// symmetric scene form a circle) on the co-rotating field g(y) = f(t0, y) - diag(P, P) y in
/// the constraint manifold's tangent space, starting from the state's q (its qdot is replaced
/// by P q). The scene must be equivariant under the rotation (gravity along the axis,
/// constraints symmetric about it or turning with the frame).
///  lambda_re, lambda_im (2(n - m) each, nullable): the eigenvalues of Dg on the manifold's
///    tangent space, sorted by decreasing real part: the small oscillations seen from the
///    turning frame (+-i omega; zeros for the directions along the family).
///  rep (nullable): iterations and residual.
/// Every particle must be placed by dal_map_cartesian3 on three coordinates of its own (no
/// parent); else DAL_E_UNSUPPORTED (a scene in co-rotating coordinates is steady:
/// dal_equilibrium and dal_normal_modes apply there). On success the state holds (t0, q*, P q*),
/// evaluated; on failure the state as given.
/// Returns DAL_OK; DAL_E_ARG (not 3D, axis, rate); DAL_E_UNSUPPORTED; DAL_E_CONV (no convergence
/// in 50 steps); DAL_E_SINGULAR (LAPACK); the statuses of dal_make_consistent and
/// dal_vector_field_jacobian.
DAL_API int dal_relative_equilibrium(const dal_system *sys, dal_state *st, const double *axis,
                                     double rate, double *lambda_re, double *lambda_im,
                                     dal_relative_report *rep);

/// Kind of a point reported along a branch of periodic orbits.
typedef enum dal_orbit_kind {
  DAL_ORBIT_REGULAR = 0,         ///< a point of the parameter grid
  DAL_ORBIT_FOLD = 1,            ///< located: a real multiplier crosses +1 (prod (mu - 1)
                                 ///< changes sign: a fold, or a branch point of orbits)
  DAL_ORBIT_PERIOD_DOUBLING = 2, ///< located: a real multiplier crosses -1 (prod (mu + 1)
                                 ///< changes sign): orbits of twice the period branch off
} dal_orbit_kind;

/// Called at every point of a branch of orbits: the parameter, the system and the state at
/// the orbit's start, the orbit's report and its multipliers (2(n - m) each), the point's kind.
/// All valid during the call only. Return 0 to continue, non-zero to stop.
typedef int dal_orbit_branch_fn(double p, const dal_system *sys, const dal_state *st,
                                const dal_orbit_report *rep, const double *mu_re,
                                const double *mu_im, dal_orbit_kind kind, void *ctx);

/// Options of dal_orbit_continue. Always start from dal_default_orbit_continuation_opts().
typedef struct dal_orbit_continuation_opts {
  int cookie;           ///< set by dal_default_orbit_continuation_opts; do not touch
  double p0;            ///< the first parameter value; 0
  double p1;            ///< the last parameter value (may be below p0); 1
  int npoints;          ///< grid points, both ends included (>= 2); 41
  double t;             ///< the orbits' start time (the drive's phase); 0
  int locate;           ///< locate folds and period doublings by bisection; 1
  double ptol;          ///< their parameter tolerance; 0: 1e-10 |p1 - p0|
  dal_orbit_opts orbit; ///< the shooting at every point (period, free_period, xtol, solve)
  int borrowed;         ///< 1: the systems rebuild gives stay the caller's, valid until
                        ///< dal_orbit_continue returns (a scene's); 0 (default): the
                        ///< continuation destroys each with dal_system_destroy
} dal_orbit_continuation_opts;

/// The defaults (see the fields); orbit.period must still be set.
DAL_API dal_orbit_continuation_opts dal_default_orbit_continuation_opts(void);

/// Natural-parameter continuation of one branch of periodic orbits: for p on the grid from p0
/// to p1 build the system (rebuild, as for dal_continue), find the orbit by dal_periodic_orbit
/// from the previous one's start (y0 = (q, qdot), 2n values, at the first point), and report
/// it. Between grid points where prod (mu_i - 1) or prod (mu_i + 1) changes sign the crossing
/// is located by bisection (every trial an orbit solve) and reported as DAL_ORBIT_FOLD or
/// DAL_ORBIT_PERIOD_DOUBLING before the grid point. Past a fold the branch turns back in p:
/// the next solve fails or jumps to another branch (the message says where it stopped); no
/// pseudo-arclength continuation is offered.
/// Returns DAL_OK (p1 reached); DAL_E_ARG; DAL_E_CALLBACK (rebuild failed or point asked to
/// stop); the statuses of dal_periodic_orbit (rep->msg names the parameter). rep nullable.
DAL_API int dal_orbit_continue(dal_rebuild_fn *rebuild, const double *y0,
                               const dal_orbit_continuation_opts *o, dal_orbit_branch_fn *point,
                               dal_continuation_report *rep, void *ctx);

#ifdef __cplusplus
}
#endif
#endif
