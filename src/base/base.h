// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Private data structures of builder, system and state, and the internal pipeline calls.
#ifndef DAL_INTERNAL_H
#define DAL_INTERNAL_H

#include <math.h>
#include <stddef.h>

#include "bounds.h"
#include "dalembert/dalembert.h"

#define DAL_ERRMSG_LEN 512
#define DAL_OPTS_COOKIE 0x0da1e3b7
/// Internal codes > 0 (never returned to the user): a trial point failed in a way that a
/// smaller step may avoid. Each carries the public status it becomes when no smaller step
/// helps or there is no step to shrink (dal__public_status):
/// a user callback asked for a smaller step (-> DAL_E_CALLBACK)
#define DAL__RECOVERABLE 1
/// a trial value is not finite: t, q, qdot handed to the model, or accelerations or jets that
/// overflowed at a trial point reached by too long a step (-> DAL_E_NONFINITE)
#define DAL__RETRY_NONFINITE 2
/// the mass or KKT matrix is nearly singular at the trial point: accelerations overflow
/// although the forces are finite (-> DAL_E_SINGULAR)
#define DAL__RETRY_SINGULAR 3

/// programmer bugs only (broken invariants); never physics failures
#ifdef NDEBUG
#define DAL_ASSERT(c) ((void)0)
#else
#include <assert.h>
#define DAL_ASSERT(c) assert(c)
#endif

/// a particle placement: r_k = prim(parent position, q[coords], t; param)
typedef struct dal_place {
  const dal_primitive *prim;
  void *ctx;
  int parent;    // -1 for none
  int ncoord;    // coordinates used
  int coord_off; // into ipool
  int param_off; // into ppool
} dal_place;

/// a constraint block of prim->nout rows
typedef struct dal_con {
  char *name;
  const dal_primitive *prim;
  void *ctx;
  int npart, part_off;   // particle inputs, into ipool
  int ncoord, coord_off; // coordinate inputs, into ipool
  int param_off;         // into ppool
  int row;               // first row in phi
  int dep_off, ndep;     // dependency coordinates (sorted), into sys->cdep
  int g_off;             // offset of its compact G block (nout x ndep, row-major)
} dal_con;

/// a spring or damper between particles (b >= 0) or from particle a to an anchor (b < 0)
typedef struct dal_link {
  int a, b;
  double k, L; // stiffness and rest length (spring) or damping c in k (damper)
  double x0[3];
  dal_path_fn *fn;
  void *ctx;
} dal_link;

/// a user callback with its context
typedef struct dal_cb {
  union {
    dal_potential_r_fn *potr;
    dal_potential_q_fn *potq;
    dal_force_fn *force;
    dal_genforce_fn *gen;
  } fn;
  void *ctx;
} dal_cb;

/// growable array helper state
typedef struct dal_vec {
  void *data;
  int len, cap;
} dal_vec;

struct dal_builder {
  int dim;
  dal_vec coords;    // char *
  dal_vec parts;     // char *
  dal_vec masses;    // double
  dal_vec places;    // dal_place (indexed by particle; prim NULL = unplaced)
  dal_vec cons;      // dal_con
  dal_vec ipool;     // int
  dal_vec ppool;     // double
  dal_vec springs;   // dal_link
  dal_vec dampers;   // dal_link
  dal_vec potr;      // dal_cb
  dal_vec potq;      // dal_cb
  dal_vec forces;    // dal_cb
  dal_vec genforces; // dal_cb
  dal_map_fn *map;
  void *map_ctx;
  dal_lagrangian_fn *lag;
  void *lag_ctx;
  int has_gravity;
  double g[3];
  dal_dynamics dynamics; // dal_builder_set_dynamics
  char err[DAL_ERRMSG_LEN];
};

struct dal_system {
  int dim, n, N, m;
  char **coord_names, **part_names;
  double *mass;
  dal_place *place; // N entries (NULL with a global map)
  dal_map_fn *map;
  void *map_ctx;
  dal_lagrangian_fn *lag;
  void *lag_ctx;
  int *ipool;
  double *ppool;
  // per-particle dependency coordinates (sorted): pdep[pdep_off[k] .. pdep_off[k+1])
  int *pdep_off, *pdep;
  int *pj_off;   // offset of particle k's compact J (d x ndep_k, row-major); pj_off[N] = total
  int *con_loff; // offset of constraint c's local Jacobian (nout x nin) in st->Gl; [ncon] total
  // constraints
  int ncon;
  dal_con *con;
  int *cdep;
  int g_total;  // total size of compact G storage
  int *row_con; // constraint index owning each row (m)
  // forces
  int has_gravity;
  double g[3];
  int nspring, ndamper, npotr, npotq, nforce, ngenforce;
  dal_link *springs, *dampers;
  dal_cb *potr, *potq, *forces, *genforces;
  // sizes
  int max_in, max_out; // largest local input/output count of any primitive instance or map
  // tree assembly (placements only): subtree masses and local coordinate columns
  double *mu;    // mu[k] = sum of the masses of particle k and all particles it carries
  int *ploc_off; // offset of particle k's local coordinate columns (d x ncoord) in st->Lc
  int dense_M;   // M is assembled densely (n x n)
  // the articulated-body recursion (aba.c): accelerations without M, and with constraints the
  // m x m loop system instead of the KKT matrix; chosen at compile time (system.c)
  int aba;
  int store_J; // compact particle Jacobians are stored (all but large recursive trees)
  // M couples few coordinates (sum over particles of (coordinates it depends on)^2 at most
  // DAL_KKT_LOCAL_COUPLING n: Cartesian particles): its KKT matrix goes to KLU at any order
  int kkt_local;
};

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
/// compensated summation x += d with compensation c (Kahan 1965): c holds the negated
/// rounding error of the running sum and is fed back into the next addition
static inline void dal__ksum(double *x, double *c, double d) {
  double y = d - *c, s = *x + y;
  *c = (s - *x) - y;
  *x = s;
}

/// a consumer reads product bits `p`: they must be current (debug builds check)
#define DAL_NEED(st, p) DAL_ASSERT(((st)->have & (p)) == (p))
/// per-trajectory parameters (params.c): read pointers that point at the system's arrays
/// until the first override copies that array into the state (copy-on-write); the
/// evaluation reads masses, primitive parameters, gravity and link constants through them
typedef struct dal_params {
  const double *mass, *mu, *ppool, *g; // N, N (subtree masses), the parameter pool, 3
  const dal_link *springs, *dampers;   // nspring, ndamper
  int has_gravity;
  double *own_mass, *own_mu, *own_ppool; // owned copies (NULL until overridden)
  dal_link *own_springs, *own_dampers;
  double own_g[3];
} dal_params;

/// workspace and outputs of one trajectory
struct dal_state {
  const dal_system *sys;
  dal_params prm; // per-trajectory parameters (params.c)
  double t;
  double *q, *qdot, *qddot;                 // n; q and qdot one block (qdot = q + n)
  double *r, *v, *a, *drdt, *gamma, *F, *N; // N x d
  double *J;                                // compact per particle
  double *M;                                // n x n (dense_M) or NULL
  double *L;                                // Cholesky / scratch n x n (dense_M) or NULL
  double *Q, *c;                            // n
  double *lambda, *phi, *phidot, *gphi, *G; // constraint outputs (m, m, m, m, compact)
  double *Gl;   // local constraint Jacobians (nout x nin per constraint, con_loff)
  double *phit; // explicit time derivatives of the constraint rows (m)
  double pw[2]; // (DAL_P_PW) non-conservative power, explicit dU/dt
  double power; // (DAL_P_POW) dE/dt = P_nc + dU/dt|explicit + sum N_k . drdt_k
                // - lambda . phi_t: the power of everything that makes E change
  double W;     // work of that power since dal_state_set (opts.work runs)
  dal_energies en;
  unsigned have; // products current for (t, q, qdot): DAL_P_* bits
  int tree;      // (DAL_P_KIN) every parent link is a translation at this point
  // jet scratch
  dal_jet *jin, *jout; // max_in, max_out
  double *loc;         // local Jacobian, max_out x max_in
  double *dir;         // local direction scratch (2 x max_in)
  dal_jet *jq, *jv;    // n
  dal_jet *jr;         // N x d
  double *work;        // n-sized scratch (x 4)
  double *Lc;          // local coordinate columns of each placement (sys->ploc_off)
  double *Lp;          // local parent block of each placement (d x d per particle)
  double *cf;          // subtree sums of F and m gamma (2 x N x d)
  struct dal_kkt *kkt; // KKT factorization workspace (kkt.c), NULL when m = 0
  struct dal_aba *aba; // recursion workspace (aba.c), NULL unless sys->aba
  // integrator (owned by the driver)
  void *integ;
  void (*integ_free)(void *);
  dal_solve_opts integ_opts;
  dal_stats stats;
  dal_init_report init_rep;         // the last consistent start's report (init.c)
  int init_rep_valid;               // init_rep holds a report
  struct dal_events *events;        // attached event set (borrowed; events.h)
  struct dal_trajectory *traj;      // attached dense trajectory record (borrowed; solve.h)
  const struct dal_first_order *fo; // a first-order problem run on this work state by the
                                    // integrators (integrate.h: dal__ode_create_fo), or NULL
  int lazy;    // a callback holds the state at an output time, not yet evaluated: the public
               // accessors evaluate it on first use (dal__lazy_eval)
  int lazy_rc; // status of that evaluation when it failed (the driver then stops the run)
  int busy;    // dal_advance / dal_evolve is running on this state (its callbacks see it)
  char err[DAL_ERRMSG_LEN];
};

/// principal value of an angle in [-pi, pi) (CSV writers)
static inline double dal__wrap_pi(double x) {
  const double pi = 3.14159265358979323846, twopi = 6.28318530717958647692;
  double r = x - twopi * floor((x + pi) / twopi);
  if (r >= pi) r -= twopi;
  if (r < -pi) r += twopi;
  return r;
}

/// A state handed to a monitor or event function at a dense-output time is evaluated only
/// when the callback reads a product (st->lazy): reading q alone costs nothing; the public
/// readers call this first (state.c; nothing happens unless st->lazy)
void dal__lazy_eval(const dal_state *st);
/// the same for the products p only (DAL_P_*): a reader evaluates what it reads
void dal__lazy_eval_for(const dal_state *st, unsigned p);
/// End a callback's hold on a lazily evaluated state: 0, or the status of an evaluation that
/// failed while the callback read it, with the message "<who> at t=...: evaluating the state
/// failed: ..." (state.c)
int dal__lazy_end(dal_state *st, const char *who);

// errors
int dal__set_err(char *buf, int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
#define DAL_FAIL(st, code, ...) dal__set_err((st)->err, (code), __VA_ARGS__)
/// DAL_FAIL for a state passed as const (an accessor): the error text is not part of the
/// state's value (as sqlite3_errmsg), and no state is a const object (dal_state_create)
#define DAL_FAIL_C(st, code, ...) dal__set_err(((dal_state *)(st))->err, (code), __VA_ARGS__)
/// The checks of every (system, state) call: a NULL state is DAL_E_ARG (no message can be
/// kept); a NULL system or a state of another system is DAL_E_STATE with the message
/// "<what>: the state belongs to another system ...". Returns 0 when they match.
int dal__check_pair(const dal_system *sys, const dal_state *st, const char *what);
/// Calls that move a state or replace its integrator refuse a state that dal_advance or
/// dal_evolve is integrating (a monitor or event function that cast away const): DAL_E_STATE
/// with "<what>: ..."; 0 when the state is idle.
int dal__check_idle(dal_state *st, const char *what);

/// format "(q0=..., q1=...)" of the state's coordinates into buf
void dal__fmt_q(const dal_system *sys, const double *q, char *buf, size_t len);

/// check a user callback's return: 0 ok, >0 recoverable, <0 stop; name the culprit
int dal__cb_status(dal_state *st, int rc, const char *what);

/// The one conversion of an internal code to a public status: a retry code (a trial point
/// failed where there is no step left to shrink) becomes the status of its cause
/// (DAL__RECOVERABLE: DAL_E_CALLBACK, DAL__RETRY_NONFINITE: DAL_E_NONFINITE,
/// DAL__RETRY_SINGULAR: DAL_E_SINGULAR), any other positive (foreign) code DAL_E_SOLVER;
/// statuses pass through.
int dal__public_status(int rc);
/// true for the internal retry codes (a smaller step may help)
static inline int dal__is_retry(int rc) {
  return rc >= DAL__RECOVERABLE && rc <= DAL__RETRY_SINGULAR;
}

/// Domain check of a built-in primitive's parameters (constraints/registry.c): NULL when they
/// are fine (or prim is not a built-in), else the name of the offending quantity ("rod length
/// L", "normal n") with *bad its first parameter index and *rule what it must be.
const char *dal__builtin_param_check(const dal_primitive *prim, const double *param, int *bad,
                                     const char **rule);

// evaluation pipeline (eval.c -> kinematics.c, dynamics.c, lagrangian.c, kkt.c)
/// Evaluate at the state's (t, q, qdot) what `need` (DAL_P_* bits) asks for, and what that
/// depends on; st->have becomes the set computed. Returns 0, DAL__RECOVERABLE or a negative
/// status with the state's message naming the culprit.
int dal__eval(const dal_system *sys, dal_state *st, unsigned need);
/// Kinematics and constraint rows at the state's (t, q, qdot) (no dynamics).
int dal__eval_constraints(const dal_system *sys, dal_state *st);
/// a path kept out of line, so that the fast path that calls it saves no registers (COLD: a
/// rare one, also optimized for size)
#if defined(__GNUC__)
#define DAL__NOINLINE __attribute__((noinline))
#define DAL__COLD __attribute__((cold, noinline))
#else
#define DAL__NOINLINE
#define DAL__COLD
#endif
/// the state's (t, q, qdot) changed: no product is current any more
static inline void dal__state_moved(dal_state *st) { st->have = 0; }

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
/// accelerations need when no force acts on the coordinates (eval.c). 0, or as dal__dynamics.
int dal__forces(const dal_system *sys, dal_state *st);
/// After dal__dynamics failed with DAL_E_NONFINITE: when a built-in force (gravity, a spring, a
/// damper) or the sum of finite ones overflowed rather than a force callback, rewrite the
/// message to name it (blame.c). Returns DAL_E_NONFINITE.
int dal__blame_forces(const dal_system *sys, dal_state *st);
/// qddot from M qddot = Q - c by Cholesky (m = 0); names degenerate coordinates
int dal__solve_unconstrained(const dal_system *sys, dal_state *st);
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
/// factor A = I or M (metric as in dae_internal.h) and S = G A^-1 G'; then solve
/// A x = a + G' y, G x = b (x may alias a, y may alias b). Same contract as dal__kkt_factor
/// and dal__kkt_solve, which dispatch here.
int dal__loop_factor(const dal_system *sys, dal_state *st, int metric, const char *what);
void dal__loop_solve(const dal_system *sys, dal_state *st, const double *a, const double *b,
                     double *x, double *y);

/// global compact Jacobians J_k = Lp_k J_parent + Lc_k from the local blocks (DAL_P_J)
void dal__jacobians(const dal_system *sys, dal_state *st);

/// drop integrator memory (dal_state_set, dal_state_destroy, parameter changes); the KKT
/// factorization's history goes with it, so that results do not depend on a state's past
/// (integ.c)
void dal__integ_reset(dal_state *st);

/// per-trajectory parameters (params.c): point at the system's arrays / free owned copies
void dal__params_init(dal_state *st);
void dal__params_free(dal_state *st);
/// restore the system's values into the state's owned copies (keeps the buffers: no allocation)
void dal__params_rewind(dal_state *st);
// primitives' table versions and parameter names (builder.c)
/// name of parameter i of prim: its param_names entry, else "p<i>" written into buf
const char *dal__param_name(const dal_primitive *prim, int i, char *buf, size_t len);
/// DAL_OK when prim->version is one this library reads, else DAL_E_ARG with a message in err
int dal__prim_version_ok(const dal_primitive *prim, char *err, const char *what);

/// solve options (opts.c)
/// validate options; the state's message names the field and the remedy (opts.c)
int dal__check_opts(dal_state *st, const dal_solve_opts *o);
/// the options as the integrators read them: atol = 0 follows rtol (solve.h) (opts.c)
dal_solve_opts dal__effective_opts(const dal_solve_opts *o);
/// every option is the same in a and b (opts.c; a new field cannot be forgotten)
int dal__same_opts(const dal_solve_opts *a, const dal_solve_opts *b);

#endif
