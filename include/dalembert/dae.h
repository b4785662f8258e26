// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Redundant coordinates: consistent initialization, constraint diagnostics, constraint
/// forces.
///
/// A system with constraints phi(q, t) = 0 (m rows, G = dphi/dq, m x n) moves by
///   M qddot = Q - c + G' lambda,   phi(q, t) = 0,
/// so G' lambda (n) is the generalized force the constraints exert and lambda (m) holds one
/// multiplier per row. Sign: a row pushes along +grad phi when its multiplier is positive. For
/// a rod |r_b - r_a| - L the force on b is lambda e (e the unit vector from a to b): a rod in
/// tension T has lambda = -T, a strut in compression C has lambda = +C. Forces are in the
/// world frame of the particle positions.
///
/// dal_advance/dal_evolve run such a system as a DAE in SUNDIALS IDA (index-2 GGL by default,
/// see solve.h for the formulations). They first check the constraints (dal_check_constraints)
/// and make the state consistent (dal_make_consistent); users may call both themselves to see
/// the report. After every DAE step the state's lambda, qddot and reactions are those of the
/// KKT system at the step's (t, q, qdot), and dal_state_phi / dal_state_phidot give the
/// position- and velocity-level residuals there.
///
/// Baumgarte terms of the index-1 form (opts.baumgarte_alpha = alpha in 1/s,
/// opts.baumgarte_beta = beta in 1/s): the acceleration-level constraint becomes
///   G qddot + gamma_phi + 2 alpha (G qdot + dphi/dt) + beta^2 phi = 0,
/// i.e. the residual obeys phi'' + 2 alpha phi' + beta^2 phi = 0 (critically damped for
/// alpha = beta). Both 0 (the default) is the unstabilized index-1 form, which drifts.
///
/// What a tolerance buys (Cartesian pendulum released at 120 degrees, 10 s, against the exact
/// elliptic solution; measured, see tests/test_dae.c and examples/cartesian_pendulum.c):
///  - GGL in IDA: global error at most 4 x rtol for rtol = 1e-4 ... 1e-9 (IDA's local error
///    control runs at 0.001 x rtol; the table in solve.h, printed by tests/test_core.c); below
///    1e-9 IDA's clamp shows (23 x rtol at 1e-10, solve.h); the residuals phi and
///    G v + dphi/dt stay below rtol (Newton level);
///  - index-1 in IDA without stabilization: the residuals drift (phi ~ t^2, phidot ~ t) and the
///    error grows to 1e3-1e4 x rtol; Baumgarte terms bound the drift;
///  - index-3 in IDA: only q is in the error test; 1e4-1e6 x rtol;
///  - index-1 as an ODE with projection under Bulirsch-Stoer: within 10 x rtol down to 1e-12
///    (DOPRI5 with projection ~13 x at 1e-12). Use it when accuracy matters more than cost;
///    projection needs an ODE method (BDF in IDA takes Baumgarte terms instead).
/// Large systems (no dense M: n > 512 with constraints) use a sparse KKT factorization by KLU
/// and the KLU solver in IDA with a Newton matrix assembled from M, G and the constraints'
/// geometric stiffness; cost per step grows about linearly in the number of particles.
#ifndef DAL_DAE_H
#define DAL_DAE_H

#include "dalembert/base.h"
#include "dalembert/state.h"
#include "dalembert/system.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Relative threshold of the rank decision: a pivot |R_kk| <= DAL_RANK_RTOL |R_11| of the
/// column-pivoted QR of G' counts as zero (the row depends on the others).
#define DAL_RANK_RTOL 1e-9

/// What dal_make_consistent changed, and by how much.
typedef struct dal_init_report {
  double phi_before;    ///< max |phi| at the given state (length units)
  double phi_after;     ///< max |phi| after the position projection
  int phi_row;          ///< row of the largest given position residual (-1 if m = 0)
  double phidot_before; ///< max |G qdot + dphi/dt| at the given state (length/time)
  double phidot_after;  ///< max |G qdot + dphi/dt| after the velocity projection
  int phidot_row;       ///< row of the largest given velocity residual (-1 if m = 0)
  double dq_max;        ///< max |delta q_i| applied to the coordinates
  int dq_coord;         ///< coordinate changed most (-1 if none)
  double dqdot_max;     ///< max |delta qdot_i| applied to the velocities
  int dqdot_coord;      ///< velocity changed most (-1 if none)
  int iterations;       ///< Gauss-Newton iterations of the position projection
  double tol;           ///< position tolerance used (length units)
} dal_init_report;

/// Make the state consistent with its constraints at its time t, in three steps:
/// 1. positions: minimum-norm Gauss-Newton q <- q - G'(G G')^-1 phi until max |phi| <= tol;
/// 2. velocities: M-orthogonal projection qdot <- qdot - M^-1 G' (G M^-1 G')^-1 (G qdot +
///    dphi/dt), the smallest change in kinetic-energy norm that satisfies the velocity
///    constraint;
/// 3. accelerations and multipliers from the KKT system (the state is left evaluated, as
///    after dal_forward).
/// `tol` is the position tolerance in length units; tol <= 0 selects 1e-12 max(1, max|q_i|);
/// a NaN or infinite tol is DAL_E_NONFINITE.
/// `rep` (nullable) receives the report. A system without constraints is only evaluated.
/// Any integrator history is discarded. Errors: DAL_E_INIT when the positions cannot be
/// brought onto phi = 0 (a guess too far away; the message names the constraint with the
/// largest residual) — the state is then unchanged; DAL_E_CONSTRAINT when G is rank deficient
/// (the message names the dependent constraints) or when the projection stalls with
/// residuals left on two or more constraints (they conflict near the guess; the message names
/// them); the errors of dal_forward.
DAL_API int dal_make_consistent(const dal_system *sys, dal_state *st, double tol,
                                dal_init_report *rep);

/// The report of the last consistent start on this state (dal_make_consistent, or the one
/// dal_advance / dal_evolve run before a DAE integration, including one refused because it
/// moved more than opts.init_max_move) into *out. Read it to see whether the library moved
/// your initial state onto the constraints, and by how much. Returns DAL_OK, DAL_E_ARG for
/// NULL arguments, DAL_E_STATE when no consistent start has run on this state (*out is then
/// zeroed with rows and coordinates -1).
DAL_API int dal_state_init_report(const dal_state *st, dal_init_report *out);

/// Result of a constraint check.
typedef struct dal_constraint_report {
  int m;          ///< constraint rows
  int rank;       ///< numerical rank of G at the state; -1 if not checked (see below)
  double rmin;    ///< smallest pivot ratio |R_kk| / |R_11| among the kept rows (1 if m = 0)
  int ndependent; ///< rows in the first dependent set found (0 if full rank)
  int rows[8];    ///< those rows (the first 8)
} dal_constraint_report;

/// Detect redundant or conflicting constraints at the state's (t, q): the column-pivoted
/// (rank-revealing) QR of G' through LAPACKE dgeqp3. When the rank r is below m the state's
/// error message names the constraints of the first dependent set, e.g. "constraints 'rod2'
/// and 'rod5' are redundant (rank 5 of 6) at t=0 ...", and DAL_E_CONSTRAINT is returned.
/// Systems with more than 512 rows or n m > 1e6 are not checked by QR (rank = -1, DAL_OK):
/// their singular KKT or Jacobian factorizations are reported when they occur.
/// `rep` is nullable. Uses the state as workspace (its kinematics become current).
DAL_API int dal_check_constraints(const dal_system *sys, dal_state *st, dal_constraint_report *rep);

/// Force exerted by the explicit constraints on each particle, from the state's current
/// multipliers (after dal_forward, dal_make_consistent or a step): F (N x d, row-major,
/// caller-owned) receives F_k = sum over the rows touching particle k of
/// (dphi_row / dr_k)' lambda_row, world frame, force units. Rows on coordinates (e.g.
/// dal_con_prescribed) act on coordinates, not on particles, and are left out; see
/// dal_constraint_genforces for the whole generalized force. The state is only read, so a
/// monitor (which sees a const state) may call it. Returns DAL_E_ARG for bad arguments and
/// DAL_E_STATE for a state of another system or one whose multipliers are not evaluated at its
/// (t, q, qdot) (before dal_forward, after dal_state_set, after a failed evaluation; no message
/// is kept, the state being const); a system without constraints gives zero forces.
DAL_API int dal_constraint_forces(const dal_system *sys, const dal_state *st, double *F);

/// Generalized constraint force G' lambda (n, caller-owned) at the state's current G and
/// lambda. Returns DAL_E_ARG for a NULL Qc, DAL_E_STATE as dal_constraint_forces does.
DAL_API int dal_constraint_genforces(const dal_system *sys, const dal_state *st, double *Qc);

#ifdef __cplusplus
}
#endif
#endif
