// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The lowest face: the private data structures of builder, system and state that every layer
// shares, the internal status codes and their conversion, the error helpers and the options'
// checks. What a folder above defines is declared in that folder's face (eval/eval.h, ...).
#ifndef DAL_BASE_BASE_H
#define DAL_BASE_BASE_H

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

/// The parts of a Lagrangian its equations read, over jets: out[i] = dL/dqdot_i and
/// out[n + i] = dL/dq_i (i < n) at (t, q, qdot); 0 ok, as dal_lagrangian_fn otherwise. Given
/// beside L (model/builder.c), the accelerations take n + 1 evaluations of it instead of the
/// polarization's n (n + 3) / 2 + 1 of L (eval/lagrangian.c).
typedef int dal__lagrangian_parts_fn(dal_jet t, const dal_jet *q, const dal_jet *qdot, dal_jet *out,
                                     void *ctx);

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
  dal__lagrangian_parts_fn *lag_parts; // nullable (model/builder.c)
  void *lag_parts_ctx;
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
  dal__lagrangian_parts_fn *lag_parts; // dL/dqdot and dL/dq as one program (NULL: by L alone)
  void *lag_parts_ctx;
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
  // compiled equations of motion (src/codegen/eom.c; NULL: none): the minimal-coordinate
  // right-hand side's qddot in one call
  struct dal_eom *eom;
};

/// compensated summation x += d with compensation c (Kahan 1965): c holds the negated
/// rounding error of the running sum and is fed back into the next addition
static inline void dal__ksum(double *x, double *c, double d) {
  double y = d - *c, s = *x + y;
  *c = (s - *x) - y;
  *x = s;
}

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
  unsigned have; // products current for (t, q, qdot): DAL_P_* bits (eval/eval.h)
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

/// free each pointer listed (any may be NULL): the buffers a structure owns, then the
/// structure, in one statement, DAL_FREE(w->K, w->x, w)
#define DAL_FREE(...)                                                                              \
  dal__free_all((void *[]){__VA_ARGS__}, sizeof((void *[]){__VA_ARGS__}) / sizeof(void *))
void dal__free_all(void *const *p, size_t n);

/// format "(q0=..., q1=...)" of the state's coordinates into buf
void dal__fmt_q(const dal_system *sys, const double *q, char *buf, size_t len);
/// coordinates q as dal__fmt_q's text, returned by value so that a message names them in place:
/// DAL_FAIL(st, code, "... at %s", dal__qtext(sys, st->q).s) (the text lives to the end of the
/// statement)
typedef struct dal_qtext {
  char s[256];
} dal_qtext;
dal_qtext dal__qtext(const dal_system *sys, const double *q);

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

/// solve options (opts.c)
/// validate options; the state's message names the field and the remedy (opts.c)
int dal__check_opts(dal_state *st, const dal_solve_opts *o);
/// the options as the integrators read them: atol = 0 follows rtol (solve.h) (opts.c)
dal_solve_opts dal__effective_opts(const dal_solve_opts *o);
/// every option is the same in a and b (opts.c; a new field cannot be forgotten)
int dal__same_opts(const dal_solve_opts *a, const dal_solve_opts *b);

#endif
