// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief State of one trajectory: (t, q, qdot), the computed physics, and the evaluation pipeline.
///
/// A state belongs to one system and is used by one thread at a time; the system may be
/// shared. Pointers returned by accessors are borrowed views into the state, valid until the
/// next call that changes the state, and NULL when the quantity does not exist for the system
/// or is not current: a product is handed out only while it was evaluated at the state's
/// (t, q, qdot), so it is NULL before the first dal_forward (or integration), after
/// dal_state_set, and after an evaluation that failed before producing it. The status calls
/// (dal_state_energies, dal_state_jacobian, dal_constraint_forces ...) answer DAL_E_STATE with a
/// message then. Every (system, state) call refuses a state of another system (or a NULL
/// system) with DAL_E_STATE and a message; the state keeps its message, which a const accessor
/// may update too (the text is not part of the state's value).
#ifndef DAL_STATE_H
#define DAL_STATE_H

#include "dalembert/base.h"
#include "dalembert/jet.h"
#include "dalembert/system.h"

#ifdef __cplusplus
extern "C" {
#endif

/// One trajectory's state and workspace.
typedef struct dal_state dal_state;

/// Energies of a state (after dal_forward).
///
/// What each field means for each kind of system:
/// - particles placed in minimal coordinates: T, U, E = T + U; h = T2 - T0 + U is the energy
///   function (Jacobi integral) qdot . dL/dqdot - L, conserved when L has no explicit t (a ring
///   turning at a constant rate) and no non-conservative force acts, while E then is not.
/// - redundant coordinates with constraints: the same, except that h is NaN when a constraint
///   depends explicitly on t (a moving pivot, a turning circle): its time dependence is not in
///   L, so h is not conserved there. Use E - W (below) instead.
/// - a Lagrangian-only system (dal_builder_set_lagrangian): h = qdot . dL/dqdot - L, and T, U,
///   T2, T1, T0 read off L (system.h).
///
/// W is the work done on the system since the last dal_state_set by non-conservative forces
/// (dampers, force callbacks), explicitly time-dependent potentials (moving spring anchors,
/// U(r, t), U(q, t)) and moving constraints (the power sum_k N_k . dr_k/dt of the reactions of
/// moving maps, and -lambda . dphi/dt of moving constraints), integrated with the motion when
/// opts.work is set (0 otherwise). E - W is then an invariant to the tolerance in every
/// formulation.
typedef struct dal_energies {
  double T;  ///< kinetic energy, 1/2 sum m_k |v_k|^2
  double U;  ///< potential energy (gravity, springs, user potentials)
  double E;  ///< total energy T + U
  double h;  ///< energy function (Jacobi integral) qdot . dL/dqdot - L = T2 - T0 + U (see above)
  double T2; ///< 1/2 qdot' M qdot
  double T1; ///< b' qdot, b = sum m_k J_k' dr_k/dt
  double T0; ///< 1/2 sum m_k |dr_k/dt|^2
  double W;  ///< work done on the system since dal_state_set (opts.work; see above)
} dal_energies;

/// Create a state for `sys` (borrowed; must outlive the state), at t = 0 with q = qdot = 0.
DAL_API int dal_state_create(const dal_system *sys, dal_state **out);

/// Free a state (NULL is a no-op).
DAL_API void dal_state_destroy(dal_state *st);

/// The state's last error message ("" if none): names the culprit and a remedy.
DAL_API const char *dal_state_errmsg(const dal_state *st);

/// Set time, coordinates q (n) and velocities qdot (n) (copied). Any integrator history is
/// discarded. Rejects non-finite values (DAL_E_NONFINITE naming the coordinate); on failure
/// the state is unchanged.
DAL_API int dal_state_set(const dal_system *sys, dal_state *st, double t, const double *q,
                          const double *qdot);

/// Evaluate the physics at the current (t, q, qdot): positions, velocities, Jacobians,
/// curvature terms, M, Q, c, accelerations qddot (Cholesky of M; for constrained systems the
/// KKT system, which also gives the multipliers), energies and reaction forces.
/// Errors: DAL_E_SINGULAR names the degenerate coordinate(s), t and q; DAL_E_DOMAIN names
/// the primitive that produced NaN/inf; DAL_E_CALLBACK for a user callback failure (also one
/// that returns > 0: there is no step to shrink here); DAL_E_NONFINITE when a product
/// overflows (forces, accelerations, velocity terms: the state lies beyond double range);
/// DAL_E_STATE for a state of another system. No product is handed out non-finite.
DAL_API int dal_forward(const dal_system *sys, dal_state *st);

/// Current time.
DAL_API double dal_state_time(const dal_state *st);
/// Coordinates q (n).
DAL_API const double *dal_state_q(const dal_state *st);
/// Velocities qdot (n).
DAL_API const double *dal_state_qdot(const dal_state *st);
/// Accelerations qddot (n), after dal_forward.
DAL_API const double *dal_state_qddot(const dal_state *st);
/// Particle positions r (N x d, row-major), after dal_forward.
DAL_API const double *dal_state_positions(const dal_state *st);
/// Particle velocities v (N x d), after dal_forward.
DAL_API const double *dal_state_velocities(const dal_state *st);
/// Particle accelerations a_k = J_k qddot + gamma_k (N x d), after dal_forward.
DAL_API const double *dal_state_accelerations(const dal_state *st);
/// Explicit time derivatives dr_k/dt (N x d), after dal_forward.
DAL_API const double *dal_state_drdt(const dal_state *st);
/// Curvature terms gamma_k (N x d): the acceleration at qddot = 0, after dal_forward.
DAL_API const double *dal_state_gamma(const dal_state *st);
/// Jacobian of particle k, J_k = dr_k/dq, written densely into J (d x n, row-major,
/// caller-owned). Returns DAL_E_ARG for a bad k or a NULL J (message in the state),
/// DAL_E_STATE for a state of another system or one not evaluated at its (t, q, qdot).
DAL_API int dal_state_jacobian(const dal_system *sys, const dal_state *st, int k, double *J);
/// Mass matrix M (n x n, column-major, symmetric), after dal_forward; NULL when the system
/// stores M only implicitly (more than 512 coordinates with constraints or on the recursive
/// route, solve.h; use dal_state_jacobian).
DAL_API const double *dal_state_mass_matrix(const dal_state *st);
/// Generalized applied forces Q = sum_k J_k' F_k + Q_user - dU(q)/dq (n).
DAL_API const double *dal_state_genforces(const dal_state *st);
/// Velocity-product (Coriolis, centrifugal, moving-frame) terms c = sum_k m_k J_k' gamma_k (n);
/// NULL for a Lagrangian system (the terms are inside L).
DAL_API const double *dal_state_bias(const dal_state *st);
/// Applied Cartesian forces F_k (N x d), after dal_forward.
DAL_API const double *dal_state_forces(const dal_state *st);
/// Constraint (reaction) forces N_k = m_k a_k - F_k on each particle (N x d): the force the
/// constraints (built into the map, and explicit ones) exert on particle k.
DAL_API const double *dal_state_reactions(const dal_state *st);
/// Joint forces: F (N x d, row-major, caller-owned, force units, world frame) receives for each
/// particle k the force its own placement exerts on it: the joint tying it to its parent
/// particle, or to the world (a fixed or moving support) for a placement without parent. For a
/// pendulum on a pivot it is the rod's pull, m (g cos theta + l thetadot^2) along the rod
/// towards the pivot; for a particle placed in Cartesian coordinates (dal_map_cartesian2/3,
/// nothing held) it is zero to rounding. Where dal_state_reactions gives the whole reaction
/// N_k = m_k a_k - F_k (every joint and constraint touching k), this splits it by Newton's
/// third law through the tree of placements (massless joints, point masses):
/// J_k = N_k - C_k + sum over the children c of k of Lp_c' J_c, with C_k the explicit
/// constraints' force on k (dal_constraint_forces) and Lp_c = dr_c/dr_k the child's parent
/// block (the identity for a translating map). Forces that act on the placement's coordinates
/// rather than on particles (a dal_con_prescribed row's drive, dal_builder_add_genforce, a
/// potential U(q, t)) act through the joint and are part of its force.
/// The state is only read (a monitor may call it). Returns DAL_E_ARG for a NULL st or F,
/// DAL_E_STATE for a state of another system or one not evaluated at its (t, q, qdot) (as
/// dal_constraint_forces), DAL_E_UNSUPPORTED for a system without placements (a Lagrangian,
/// or one map r(q, t) for all particles: dal_state_reactions has the reactions there).
DAL_API int dal_joint_forces(const dal_system *sys, const dal_state *st, double *F);
/// Multipliers lambda (m), one per constraint row, after dal_forward or a DAE step; the
/// generalized constraint force is G' lambda (NULL when m = 0).
DAL_API const double *dal_state_lambda(const dal_state *st);
/// Constraint residuals phi (m) at position level (NULL when m = 0).
DAL_API const double *dal_state_phi(const dal_state *st);
/// Constraint residuals G qdot + dphi/dt (m) at velocity level (NULL when m = 0).
DAL_API const double *dal_state_phidot(const dal_state *st);
/// Energies of the state (after dal_forward). Returns DAL_E_ARG for a NULL argument,
/// DAL_E_STATE when the state is not evaluated at its (t, q, qdot) (before dal_forward, after
/// dal_state_set), DAL_E_NONFINITE when they overflow; *out is written only on DAL_OK.
DAL_API int dal_state_energies(const dal_state *st, dal_energies *out);

/// Print the state to fp (like MuJoCo's mj_printData): t; per coordinate q, qdot, qddot, Q, c;
/// the mass matrix M; per constraint row lambda, phi and phidot; particle positions;
/// energies; the last consistent start's report. Quantities that need dal_forward are printed
/// only when the state is evaluated. %.17g throughout. Returns DAL_OK, DAL_E_ARG (a NULL
/// argument), DAL_E_STATE (a state of another system, with a message) or DAL_E_IO.
DAL_API int dal_state_print(const dal_system *sys, const dal_state *st, FILE *fp);

/// A proposed path q(t) over jets: write q[0..n-1] as jets in t (its first and second
/// derivatives are the path's velocity and acceleration).
typedef int dal_path_q_fn(dal_jet t, dal_jet *q, void *ctx);

/// Lagrange-equation residual of a proposed path at time t:
/// res = d/dt dL/dqdot - dL/dq - Q_nc (n), equal to M qddot + c - Q for particle systems.
/// Zero (to rounding) exactly when the path is realizable. Uses st as workspace: its
/// (t, q, qdot) become the path's values at t. `ctx` is passed to path. DAL_E_NONFINITE when
/// t is not finite or the residual overflows (a path too fast for double precision);
/// DAL_E_DOMAIN when the path leaves its own domain.
DAL_API int dal_lagrange_residual(const dal_system *sys, dal_state *st, dal_path_q_fn *path,
                                  double t, double *res, void *ctx);

#ifdef __cplusplus
}
#endif
#endif
