// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The DAE formulations of redundant coordinates (GGL, index-3, index-1) behind one interface:
// sizes, residual, error-test mask and Newton-matrix entries (private; dae.c), and the
// other formulations of form/: minimal coordinates, index-1 with projection, the tangent
// (linearized) problems and the consistent start.
#ifndef DAL_FORM_FORM_H
#define DAL_FORM_FORM_H

#include "model/model.h"

/// max |x_i| over n entries (NaN counts as largest); *at (nullable) receives its index
/// (init.c)
double dal__max_abs(const double *x, int n, int *at);

/// A DAE formulation on a system and a state (the state is its workspace).
/// Unknowns y = (q, v, lambda[, mu][, W]).
typedef struct dal_dae {
  const dal_system *sys;
  dal_state *st;
  dal_formulation form; ///< DAL_FORM_GGL, DAL_FORM_INDEX3 or DAL_FORM_INDEX1
  double alpha, beta;   ///< index-1 Baumgarte terms
  int n, m, neq;
  int off_l, off_mu; ///< offsets of lambda and mu in y (mu: -1 unless GGL)
  int off_w;         ///< offset of the work W (last unknown; -1 unless opts.work)
  dal_csc pat;       ///< pattern of the Newton matrix (after dal__dae_pattern)
  int *pos;          ///< position in pat's values of each Newton-matrix entry, in assembly
                     ///< order (after dal__dae_pattern; the sparse sink's addresses)
  size_t npos;       ///< number of entries assembled (with repetitions)
  // geometric-stiffness scratch (max_in, max_out, largest constraint dependency count)
  double *H, *hv, *Ju, *tmp, *Hq, *dir, *udot, *g0;
} dal_dae;

/// Where Newton-matrix entries go: counted, recorded as keys, their positions in the pattern
/// recorded (these three build the pattern), summed into a sparse value array of the pattern
/// (through f->pos: the entries come in the same order every time), or into a dense
/// column-major matrix (leading dimension neq).
typedef struct dal_dae_sink {
  int mode; ///< DAL_SINK_COUNT, DAL_SINK_KEYS, DAL_SINK_POS, DAL_SINK_SPARSE, DAL_SINK_DENSE
  size_t n; ///< entries so far (start at 0)
  long long *keys;
  double *val;
} dal_dae_sink;
enum { DAL_SINK_COUNT, DAL_SINK_KEYS, DAL_SINK_POS, DAL_SINK_SPARSE, DAL_SINK_DENSE };

/// Set up form f (sizes, scratch). Returns 0 or DAL_E_NOMEM.
int dal__dae_init(dal_dae *f, const dal_system *sys, dal_state *st, dal_formulation form,
                  double alpha, double beta, int work);
void dal__dae_free(dal_dae *f);
/// The Newton matrix's pattern (f->pat) and the position of every assembled entry in it
/// (f->pos). Returns 0 or -1 (out of memory).
int dal__dae_pattern(dal_dae *f);
/// Evaluate the state at (t, q, v) from y: kinematics, constraint rows, forces (M through J).
int dal__dae_eval(dal_dae *f, double t, const double *y);
/// Residual F (neq) at (t, y, y'); evaluates the state there.
int dal__dae_residual(dal_dae *f, double t, const double *y, const double *yp, double *F);
/// Local tolerance factor of a DAE form in IDA (calibrated like the ODE methods' factors).
double dal__dae_tol_factor(dal_formulation form);
/// How far one unit of each multiplier moves the differential unknowns per unit of step size,
/// at the state's current kinematics: sl[r] = max_j |G_rj| / M_jj (v moves by h sl[r] per unit
/// of lambda_r, from M v' = ... + G' lambda) and smu[r] = max_j |G_rj| (q moves by h smu[r]
/// per unit of mu_r, from q' = v - G' mu). Both (m); 0 for a row with a zero gradient.
/// Returns 0 or DAL_E_NOMEM.
int dal__dae_row_scales(dal_dae *f, double *sl, double *smu);
/// Error-test mask id (neq): 1 for variables in the error test (q and v; index-3: q only),
/// 0 for the algebraic ones (lambda, mu).
void dal__dae_mask(const dal_dae *f, double *id);
/// Newton matrix dF/dy + cj dF/dy' at (t, y) into the sink, from exact pieces: M, G, G', the
/// constraints' geometric stiffness sum_i w_i Hess(phi_i) (jets, by polarization) and the
/// derivative of G v + phi_t. Left out: the curvature of non-Cartesian particle maps
/// (dM/dq v') and the derivatives of applied forces. Evaluates the state at (t, y).
int dal__dae_newton(dal_dae *f, double t, double cj, const double *y, dal_dae_sink *out);
/// true when dal__dae_newton's matrix is the whole Jacobian of the residual (Cartesian
/// particles, no forces but gravity): then no difference quotients are needed anywhere.
int dal__dae_newton_exact(const dal_system *sys);

/// solve options reach the forms through the first-order problem
#include "dalembert/solve.h"

/// A first-order ODE y' = f(t, y) built on a system and a state, optionally with a projection
/// onto an invariant manifold after each accepted step.
typedef struct dal_ode_problem {
  const char *name; ///< "minimal", "index1"
  /// size of y for this system
  int (*size)(const dal_system *sys);
  /// ydot = f(t, y); uses st as workspace (its q, qdot, t are overwritten) and evaluates at
  /// least the products `need` (DAL_P_ACC inside an integrator, DAL_P_ALL where the state
  /// stops). Returns 0, a retry code (DAL__RECOVERABLE, DAL__RETRY_*), or a negative status
  /// with the state's message set.
  int (*rhs)(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t,
             const double *y, double *ydot, unsigned need);
  /// project y (in place) onto the invariant manifold at t; NULL if none
  int (*project)(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t,
                 double *y);
  /// y from the state's (q, qdot)
  void (*from_state)(const dal_system *sys, const dal_state *st, double *y);
  /// the state's (t, q, qdot) from y (does not evaluate)
  void (*to_state)(const dal_system *sys, dal_state *st, double t, const double *y);
  /// size of y when > 0 (a problem built at run time, e.g. the variational equations, whose
  /// size depends on the request); 0: size(sys)
  int ny;
  /// factor on the method's local tolerance for this problem (the projection of the index-1
  /// form adds its own error: measured 30 x rtol with DOPRI5's factor alone, 0.2 brings it
  /// under 16)
  double tol_factor;
  /// 1: y is (q, qdot) exactly as the state holds them (its one block q, qdot = q + n) and
  /// to_state only copies t and y and marks the state moved; dense output may then write
  /// straight into st->q
  int state_layout;
} dal_ode_problem;
/// minimal coordinates: y = (q, qdot), f = (qdot, qddot) (minimal.c)
extern const dal_ode_problem dal__problem_minimal;
/// The layout y = (q, qdot) of a first-order state (2n; minimal.c), which the minimal and the
/// index-1 problems share: its size, y from the state, and the state put at (t, y), moved.
int dal__qv_size(const dal_system *sys);
void dal__qv_from_state(const dal_system *sys, const dal_state *st, double *y);
void dal__qv_to_state(const dal_system *sys, dal_state *st, double t, const double *y);
/// index-1 redundant coordinates: y = (q, v), f = (v, qddot from the KKT system with optional
/// Baumgarte terms), projection onto phi = 0, G v + dphi/dt = 0 when opts->project (init.c)
extern const dal_ode_problem dal__problem_index1;

/// consistent initialization (init.c)
/// Project the state's q onto phi = 0 (minimum-norm Gauss-Newton, at most maxit iterations,
/// max |phi| <= tol) then qdot onto G qdot + dphi/dt = 0 (M-orthogonal). Leaves kinematics,
/// constraint rows and (when the velocity was projected) dynamics current. *iters receives the
/// position iterations (nullable). No allocation.
int dal__project_state(const dal_system *sys, dal_state *st, double tol, int maxit, int *iters);
/// Start of a DAE run (init.c): rank check, then the consistent initialization (positions,
/// velocities, KKT accelerations and multipliers) at the state's time; rep is nullable.
int dal__dae_start(const dal_system *sys, dal_state *st, double max_move, dal_init_report *rep);
/// dal__dae_start that also hands back the rank check's report (crep, nullable): the IDA glue
/// compares the constraints' conditioning at a failure with the start's.
int dal__dae_start_checked(const dal_system *sys, dal_state *st, double max_move,
                           dal_init_report *rep, dal_constraint_report *crep);

/// the exact tangent of the vector field (tangent.c, tangent_lagrangian.c)
#include "dalembert/analysis.h"
/// Workspace of the exact tangent of one system (all arrays allocated by dal__tangent_create;
/// nothing is allocated by an evaluation). n coordinates, nd = N d particle components.
typedef struct dal_tangent {
  int n, nd;
  dal_jet *jq;           // n: coordinate jets of the current curve
  dal_jet *jv;           // n: velocity jets (Lagrangian systems)
  dal_jet *jr;           // nd: particle jets along the current curve
  dal_jet *jin;          // max_in: inputs of one primitive instance
  dal_jet *jout;         // max_out
  dal_jet *cp, *cm;      // nd: particle jets along the curves lambda = +1 and -1
  double *d3diag;        // (n + 1) x nd: third derivatives along e_i (i = n: the time direction)
  double *J;             // n x nd: J[i * nd + c] = d r_c / d q_i
  double *r, *v, *A, *w; // nd: positions, velocities, accelerations, frozen weights m A - F_d
  double *Fd;            // nd: damper forces at the state
  double *dr, *dv, *da, *dF; // nd: derivatives along one tangent direction
  double *H;          // (n + 1)^2, column-major: second derivatives of W = sum r . w + V in (q, t)
  double *res;        // n: R = dW/dq at the state (zero up to rounding when qddot is current)
  double *M;          // n x n mass matrix, from the particle Jacobians
  double *Rq, *Ru;    // n x n: K = dR/dq, C = dR/dqdot
  double *Rt;         // n: dR/dt
  double *Habs;       // (n + 1)^2: sums of the magnitudes behind H (rounding scale)
  double *Kabs;       // n x n: sums of the magnitudes of the terms of K (rounding scale)
  double *Cabs;       // n x n: the same for C
  double *HL, *HLabs; // (2n + 1)^2: Hessian of L in (q, qdot, t) (Lagrangian systems)
  double *L;          // n x n Cholesky factor of M
  double *link;       // per spring and damper: anchor x, x', x'' (3 x 3)
  // constraint rows (m > 0; tangent_con.c): the residual is R - G' lambda, W gains
  // -lambda . phi, and the constraints' own derivatives along each direction are kept
  int m;              // constraint rows
  const double *acc;  // accelerations the weights use (n); NULL: the state's qddot
  const double *lam;  // multipliers the weights use (m); NULL: the state's lambda
  dal_jet *jc;        // m: constraint jets along the current curve
  dal_jet *ccp, *ccm; // m: constraint jets along the curves lambda = +1 and -1
  double *c3diag;     // (n + 1) x m: third derivatives of phi along e_i (i = n: time)
  double *G;          // m x n column-major: G = dphi/dq
  double *phit;       // m: dphi/dt (when want_t)
  double *cres;       // 3 x m: phi, G v + phi_t, G a + gamma_phi at the state
  double *Pq;         // m x n: d(G v + phi_t)/dq
  double *Aq, *Av;    // m x n: d(G a + gamma_phi)/dq, /dqdot at fixed a
  double *At;         // m: d(G a + gamma_phi)/dt at fixed a
  double *kkt;        // (n + m)^2 LU factors of [M G'; G 0] after dal__tangent_kkt, then
                      // (n + m) x (2n + 1) right-hand sides
  void *kpiv;         // (n + m) pivots (lapack_int)
} dal_tangent;
/// Allocate the workspace of sys. Returns DAL_OK or DAL_E_NOMEM (*out NULL then).
int dal__tangent_create(const dal_system *sys, dal_tangent **out);
/// Free (NULL is a no-op).
void dal__tangent_free(dal_tangent *tg);
/// DAL_OK if the exact tangent covers sys, else DAL_E_UNSUPPORTED with the reason in st's
/// message, prefixed by `what` (the public function's name).
int dal__tangent_supported(const dal_system *sys, dal_state *st, const char *what);
/// The tangent at the state's (t, q, qdot) with its current qddot (call dal_forward first):
/// tg->M, Rq, Ru, and Rt when want_t. Returns DAL_OK, DAL_E_DOMAIN, DAL_E_CALLBACK.
int dal__tangent_eval(const dal_system *sys, dal_state *st, dal_tangent *tg, int want_t);
/// The same for a system given by a Lagrangian (tangent_lagrangian.c).
int dal__tangent_lagrangian(const dal_system *sys, dal_state *st, dal_tangent *tg, int want_t);
/// Factor tg->M into tg->L (Cholesky). Returns DAL_OK or DAL_E_SINGULAR (message set).
int dal__tangent_factor(const dal_system *sys, dal_state *st, dal_tangent *tg);
/// B (n x k, column-major) = M^-1 B with the factor of dal__tangent_factor.
void dal__tangent_msolve(dal_tangent *tg, int k, double *B);
/// The vector-field Jacobian A = df/dy (2n x 2n) and ft = df/dt (2n; NULL to skip) from the last
/// evaluation (factor first). Uses tg->dr.. as no scratch; A, ft caller-owned.
void dal__tangent_flow(dal_tangent *tg, double *A, double *ft);
/// Constrained systems (tangent_con.c). The tangent of the index-1 vector field
/// f(q, v) = (v, a) with (a, lambda) from the KKT system [M G'; G 0] (a; -lambda) =
/// (Q - c; -gamma_phi), from the last dal__tangent_eval: A (2n x 2n) and ft (2n; NULL to
/// skip), caller-owned; dlam (m x (2n + 1), NULL to skip): the multipliers' derivatives along
/// q, qdot and t (the t column only with ft). Returns DAL_OK, DAL_E_SINGULAR (message set:
/// the KKT matrix is singular) or DAL_E_NOMEM.
int dal__tangent_kkt(const dal_system *sys, dal_state *st, dal_tangent *tg, double *A, double *ft,
                     double *dlam);
/// Solve [M G'; G 0] x = b for nrhs columns b (n + m each, in place) with the LU factors of the
/// last dal__tangent_kkt.
void dal__tangent_kkt_solve(dal_tangent *tg, int nrhs, double *b);
/// Orthonormal basis N (n x k, k = n - m) of the null space of G and the velocity part
/// Y = -G^+ Pq N (n x k) of the tangent space of the state manifold
/// {phi = 0, G v + phi_t = 0}: its vectors are (N xi, Y xi + N eta). Y may be
/// NULL; W (m x k, nullable) = S^-1 U' P N from the SVD G = U S V', so W' W =
/// N' P' (G G')^-1 P N. From the last dal__tangent_eval (by an SVD of G). Returns DAL_OK,
/// DAL_E_SINGULAR (rank of G below m, message naming the row) or DAL_E_NOMEM.
int dal__tangent_basis(const dal_system *sys, dal_state *st, dal_tangent *tg, double *N, double *Y,
                       double *W);
/// The reduced first-order Jacobian Ar (2k x 2k) = [0 I; A21 A22] of the full A on the
/// tangent space (basis N, Y of dal__tangent_basis): Ar = diag(N', N') A Z.
void dal__tangent_reduce(int n, int k, const double *A, const double *N, const double *Y,
                         double *Ar);
/// The tangent space of the state manifold at the last dal__tangent_eval, as the basis
/// Z (2n x 2k) = [N 0; Y N] of dal__tangent_basis and, P nullable, its left inverse
/// P (2k x 2n) = [N' 0; -N'Y N' N'] (P Z = I), which takes (dq, dv) to (xi, eta): a 2n x 2n
/// matrix A on the manifold is P A Z. Both are the identity when m = 0 (tg is not read then).
/// Returns DAL_OK, DAL_E_SINGULAR (rank of G) or DAL_E_NOMEM.
int dal__tangent_manifold(const dal_system *sys, dal_state *st, dal_tangent *tg, double *Z,
                          double *P);
/// The reduced linearization on the constraint manifold from the last dal__tangent_eval:
/// N (n x k), Ar (2k x 2k) in xi = N' dq, eta = xi' with N carried along the motion by
/// minimal rotation (tangent_con.c), and M_r = N' M N, C_r, K_r (k x k) with
/// M_r xi'' + C_r xi' + K_r xi = 0 the second-order form of Ar; each output nullable.
int dal__tangent_reduced(const dal_system *sys, dal_state *st, dal_tangent *tg, double *N,
                         double *Ar, double *Mr, double *Cr, double *Kr);
/// The manifold check of the tangent: the state must satisfy phi = 0 and G v + phi_t = 0
/// (relative to the scale of the rows); DAL_E_ARG naming the row otherwise.
int dal__tangent_on_manifold(const dal_system *sys, dal_state *st, dal_tangent *tg,
                             const char *what);
/// Evaluate sys at (t, q, qdot) into st (state set and forward; the integrator memory of st
/// is dropped). Returns the status of dal_state_set / dal_forward.
int dal__analysis_eval(const dal_system *sys, dal_state *st, double t, const double *q,
                       const double *qdot);

#endif
