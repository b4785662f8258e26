// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The face of eval/: the evaluation pipeline at a state's (t, q, qdot) (kinematics, forces,
// accelerations by Cholesky, KKT or the articulated-body recursion) and the KKT solves,
// projections and rank test that the formulations above build on.
#ifndef DAL_EVAL_EVAL_H
#define DAL_EVAL_EVAL_H

#include "base/base.h"
#include "dalembert/dae.h"
#include "linalg/linalg.h"

/// Products of an evaluation at the state's (t, q, qdot). A caller asks dal__eval for the set
/// it needs; st->have holds the set that is current. Anything that moves the state clears it
/// (dal__state_moved), and a consumer asserts the bits it reads (DAL_NEED).
enum {
  DAL_P_KIN = 1u << 0,  ///< r, v, gamma, drdt, local columns Lc / Lp and st->tree
  DAL_P_J = 1u << 1,    ///< compact particle Jacobians J
  DAL_P_CON = 1u << 2,  ///< phi, phidot, gphi, compact G, local constraint Jacobians Gl
  DAL_P_DYN = 1u << 3,  ///< F, Q, c and the energies' T, U, E, T2, T1, T0, h
  DAL_P_MLOW = 1u << 4, ///< lower triangle of the dense M (dense_M systems)
  DAL_P_M = 1u << 5,    ///< the whole dense M (symmetric)
  DAL_P_ACC = 1u << 6,  ///< qddot, and lambda when m > 0
  DAL_P_OUT = 1u << 7,  ///< particle accelerations a and reactions N; phit; h (NaN when a
                        ///< constraint depends on t explicitly)
  DAL_P_PW = 1u << 8,   ///< st->pw: the forces' share of dE/dt (non-conservative power,
                        ///< explicit dU/dt), formed with DAL_P_DYN
  DAL_P_POW = 1u << 9,  ///< st->power = dE/dt from the forces and the moving constraints
  /// what a user reads after dal_forward: everything the system has
  DAL_P_ALL = DAL_P_KIN | DAL_P_J | DAL_P_CON | DAL_P_DYN | DAL_P_M | DAL_P_ACC | DAL_P_OUT |
              DAL_P_PW | DAL_P_POW,
};
/// a consumer reads product bits `p`: they must be current (debug builds check)
#define DAL_NEED(st, p) DAL_ASSERT(((st)->have & (p)) == (p))

// evaluation pipeline (pipeline.c -> kinematics.c, dynamics.c, lagrangian.c, kkt.c)
/// Evaluate at the state's (t, q, qdot) what `need` (DAL_P_* bits) asks for, and what that
/// depends on; st->have becomes the set computed. Returns 0, DAL__RECOVERABLE or a negative
/// status with the state's message naming the culprit.
int dal__eval(const dal_system *sys, dal_state *st, unsigned need);
/// Kinematics and constraint rows at the state's (t, q, qdot) (no dynamics).
int dal__eval_constraints(const dal_system *sys, dal_state *st);

/// one primitive instance: a particle's placement (owner k >= 0) or a constraint (-1 - c)
typedef struct dal_inst {
  const dal_primitive *prim;
  const double *param;
  void *ctx;
  int npart, ncoord;
  const int *parts, *coords;
} dal_inst;
/// largest |v|, |d|, |dd| over n jets (to tell an overflow from a domain error)
static inline double dal__jets_max(const dal_jet *x, int n) {
  double m = 0.0;
  for (int i = 0; i < n; ++i) {
    double a = fabs(x[i].v), b = fabs(x[i].d), c = fabs(x[i].dd);
    m = a > m ? a : m;
    m = b > m ? b : m;
    m = c > m ? c : m;
  }
  return m;
}

/// the instance of an owner (particle k >= 0, constraint -1 - c), with the state's parameters
dal_inst dal__inst(const dal_system *sys, const dal_state *st, int owner);
/// Evaluate a primitive instance with its inputs u (particle positions, then coordinates) at
/// their values plus the curve s -> u + s d1 + s^2/2 d2 (d1, d2 local (nin); NULL = 0) and
/// time t + s tdot: st->jout receives value, first and second derivative along it. Checks the
/// callback's return and the outputs' finiteness, naming the owner.
int dal__prim_eval(const dal_system *sys, dal_state *st, int owner, const double *d1,
                   const double *d2, double tdot);

/// particle r, v, gamma, drdt, local columns (and compact J when want_J) (DAL_P_KIN [| J])
int dal__kinematics(const dal_system *sys, dal_state *st, int want_J);
/// constraint phi, phidot, gamma_phi, compact G and local Jacobians (requires KIN and J)
int dal__constraints(const dal_system *sys, dal_state *st);
/// applied forces F, energies, Q, c and, when want_M, the dense M (lower triangle; mirrored
/// when want_M > 1) (requires KIN, and J unless st->tree). pw (nullable, 2): pw[0] += power of
/// the non-conservative forces, pw[1] += explicit time derivative of the potential energy
int dal__dynamics(const dal_system *sys, dal_state *st, int want_M, double *pw);
/// generalized terms from user callbacks over q: Q += Q_user - dU/dq, *U += U(q); pw as above
int dal__genforces(const dal_system *sys, dal_state *st, double *U, double *pw);
/// The applied forces F on the particles alone (no Q, c, energies): what the recursion's
/// accelerations need when no force acts on the coordinates (pipeline.c). 0, or as dal__dynamics.
int dal__forces(const dal_system *sys, dal_state *st);
/// After dal__dynamics failed with DAL_E_NONFINITE: when a built-in force (gravity, a spring, a
/// damper) or the sum of finite ones overflowed rather than a force callback, rewrite the
/// message to name it (blame.c). Returns DAL_E_NONFINITE.
int dal__blame_forces(const dal_system *sys, dal_state *st);
/// qddot from M qddot = Q - c by Cholesky (m = 0); names degenerate coordinates
int dal__solve_unconstrained(const dal_system *sys, dal_state *st);
/// DAL_E_SINGULAR naming coordinate `bad` of a mass matrix that is singular or not positive
/// definite (the dense route's and the recursion's one message), prefixed "<what>: " when what
/// is not NULL (blame.c).
int dal__fail_degenerate(const dal_system *sys, dal_state *st, int bad, const char *what);
/// particle accelerations and reactions from qddot, and the constraints' explicit time
/// derivatives phit (h becomes NaN when one is non-zero) (requires KIN, ACC; J unless a tree)
int dal__finish(const dal_system *sys, dal_state *st);
/// st->power = dE/dt = pw[0] + pw[1] + sum_k N_k . drdt_k - lambda . phit (requires OUT, PW)
void dal__power(const dal_system *sys, dal_state *st);
/// Lagrangian route: A = d2L/dqdot2 (n x n col-major into A), rhs = dL/dq - X + Q_nc; with
/// energies, also h (*h_out) and st->en's T, U, T2, T1, T0 (two more evaluations of L;
/// otherwise *h_out is NaN and st->en is left alone)
int dal__lagrangian_terms(const dal_system *sys, dal_state *st, double *A, double *rhs,
                          double *h_out, int energies);

/// M x through the particle Jacobians (requires DAL_P_J) or the dense M (DAL_P_M): y (n) = M x
void dal__mass_apply(const dal_system *sys, const dal_state *st, const double *x, double *y);
/// the diagonal of M (n), the same numbers as dal__mass_apply on each unit vector, in O(n)
/// from the particle Jacobians or the dense M (through dal__mass_apply otherwise)
void dal__mass_diag(const dal_system *sys, const dal_state *st, double *md);

/// The KKT solve of constrained systems: qddot and lambda from
/// [M G'; G 0] [qddot; -lambda] = [Q - c; -gamma_phi]  (kkt.c)
int dal__solve_kkt(const dal_system *sys, dal_state *st);

/// KKT workspace of a constrained system (kkt.c): create (NULL on failure) and free
struct dal_kkt *dal__kkt_create(const dal_system *sys);
void dal__kkt_free(struct dal_kkt *k);
/// forget the reusable numeric factorizations (KLU refactors with the pivots of an earlier
/// factorization, so results would depend on the state's history): called wherever integrator
/// history is discarded, so that the same inputs give bit-identical outputs
void dal__kkt_reset(struct dal_kkt *k);

// the articulated-body recursion for trees of placements (aba.c)
/// recursion workspace of a system with sys->aba: create (NULL on failure) and free
struct dal_aba *dal__aba_create(const dal_system *sys);
void dal__aba_free(struct dal_aba *w);
/// Articulated inertias at the state's kinematics (the q- and t-dependent part: a leaf-first
/// factorization of M). DAL_E_SINGULAR names a degenerate coordinate (requires DAL_P_KIN).
int dal__aba_factor(const dal_system *sys, dal_state *st);
/// x (n) = M^-1 tau (n) with the last dal__aba_factor, in O(N); x may alias tau.
void dal__aba_solve(const dal_system *sys, dal_state *st, const double *tau, double *x);
/// qddot from M qddot = Q - c by the recursion (requires DAL_P_KIN | DAL_P_DYN)
int dal__aba_accel(const dal_system *sys, dal_state *st);
/// y (n) = M x from the local blocks in O(N) (requires DAL_P_KIN; no J, no M)
void dal__tree_mass_apply(const dal_system *sys, const dal_state *st, const double *x, double *y);
/// The KKT solves of a recursive system with constraints through the m x m loop system:
/// factor A = I or M (metric DAL_KKT_IDENTITY or DAL_KKT_MASS) and S = G A^-1 G'; then solve
/// A x = a + G' y, G x = b (x may alias a, y may alias b). Same contract as dal__kkt_factor
/// and dal__kkt_solve, which dispatch here.
int dal__loop_factor(const dal_system *sys, dal_state *st, int metric, const char *what);
void dal__loop_solve(const dal_system *sys, dal_state *st, const double *a, const double *b,
                     double *x, double *y);

/// global compact Jacobians J_k = Lp_k J_parent + Lc_k from the local blocks (DAL_P_J)
void dal__jacobians(const dal_system *sys, dal_state *st);

/// KKT metric: the (1,1) block is the identity (minimum-norm position steps) or M.
enum { DAL_KKT_IDENTITY = 0, DAL_KKT_MASS = 1 };

/// Factor K = [A G'; G 0] at the state's current kinematics and constraint rows (A = I or M;
/// M is the dense st->M or, for large systems, assembled sparse from the particle Jacobians).
/// `what` names the caller in the error message. Returns 0 or DAL_E_CONSTRAINT /
/// DAL_E_SINGULAR / DAL_E_NOMEM with the state's message naming the culprit.
int dal__kkt_factor(const dal_system *sys, dal_state *st, int metric, const char *what);

/// 1 when dal__kkt_factor with the mass metric reads the dense st->M (the dense KKT matrix),
/// 0 when it does not (the loop system of a tree, or the sparse KKT matrix assembled from the
/// particle Jacobians): a caller then need not ask for DAL_P_MLOW, an O(n^2) assembly.
int dal__kkt_reads_M(const dal_system *sys, const dal_state *st);

/// Solve A x = a + G' y, G x = b with the last factorization: a (n), b (m) -> x (n), y (m).
/// x may alias a and y may alias b. No allocation.
void dal__kkt_solve(const dal_system *sys, dal_state *st, const double *a, const double *b,
                    double *x, double *y);

/// Scratch vector i (0..3) of n + m doubles owned by the state's KKT workspace.
double *dal__kkt_scratch(dal_state *st, int i);

/// Dense G (m x n, column-major, leading dimension ld >= m) from the compact blocks.
void dal__dense_G(const dal_system *sys, const dal_state *st, double *G, int ld);

/// y (n) = G' lambda for the state's current G (compact blocks).
void dal__gt_apply(const dal_system *sys, const dal_state *st, const double *lambda, double *y);
/// The same products for compact blocks G of the system's layout (st->G or a copy of it):
/// y (n) = G' lambda, and y (m) = G x.
void dal__gt_mul(const dal_system *sys, const double *G, const double *lambda, double *y);
void dal__g_mul(const dal_system *sys, const double *G, const double *x, double *y);

/// Rank check (rank.c): writes the named message into the state when G is rank
/// deficient. Returns DAL_OK, DAL_E_CONSTRAINT or DAL_E_NOMEM; rep is nullable.
int dal__check_rank(const dal_system *sys, dal_state *st, dal_constraint_report *rep);
/// A failed solve's first suspect: when G is rank deficient, DAL_E_CONSTRAINT with
/// "<what>: <the rank check's message naming the constraints>"; 0 otherwise (the caller then
/// names its own failure).
int dal__blame_rank(const dal_system *sys, dal_state *st, const char *what);

#endif
