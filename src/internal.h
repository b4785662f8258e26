// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Private data structures of builder, system and state, and the internal pipeline calls.
#ifndef DAL_INTERNAL_H
#define DAL_INTERNAL_H

#include <stddef.h>

#include "dalembert/dalembert.h"

#define DAL_ERRMSG_LEN 512
#define DAL_OPTS_MAGIC 0x0da1e3b7
/// internal: a user callback asked for a smaller step (never returned to the user)
#define DAL__RECOVERABLE 1

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
  int *pj_off; // offset of particle k's compact J (d x ndep_k, row-major); pj_off[N] = total
  // constraints
  int ncon;
  dal_con *con;
  int *cdep;
  int g_total;   // total size of compact G storage
  int *row_con;  // constraint index owning each row (m)
  // forces
  int has_gravity;
  double g[3];
  int nspring, ndamper, npotr, npotq, nforce, ngenforce;
  dal_link *springs, *dampers;
  dal_cb *potr, *potq, *forces, *genforces;
  // sizes
  int max_in, max_out; // largest local input/output count of any primitive instance or map
  // tree assembly (placements only): subtree masses and local coordinate columns
  double *mu;   // mu[k] = sum of the masses of particle k and all particles it carries
  int *ploc_off; // offset of particle k's local coordinate columns (d x ncoord) in st->Lc
  int dense_M;         // M is assembled densely (n x n)
};

/// workspace and outputs of one trajectory
struct dal_state {
  const dal_system *sys;
  double t;
  double *q, *qdot, *qddot; // n
  double *r, *v, *a, *drdt, *gamma, *F, *N; // N x d
  double *J;                // compact per particle
  double *M;                // n x n (dense_M) or NULL
  double *L;                // Cholesky / scratch n x n (dense_M) or NULL
  double *Q, *c;            // n
  double *lambda, *phi, *phidot, *gphi, *G; // constraint outputs (m, m, m, m, compact)
  dal_energies en;
  // jet scratch
  dal_jet *jin, *jout; // max_in, max_out
  double *loc;          // local Jacobian, max_out x max_in
  dal_jet *jq, *jv;     // n
  dal_jet *jr;          // N x d
  double *work;         // n-sized scratch (x 4)
  double *Lc;           // local coordinate columns of each placement (sys->ploc_off)
  double *cf;           // subtree sums of F and m gamma (2 x N x d)
  int tree;             // every parent link is a translation: tree assembly applies
  int need_J;           // compact J is formed on every evaluation (sticky once a link is
                        // found that is not a translation, or when m > 0)
  int J_valid;          // compact J is current (else dal_state_jacobian rebuilds it from Lc)
  int lean;             // inside an integrator's right-hand side: skip particle accelerations
                        // and reactions (dal__finish), which only outputs need
  struct dal_kkt *kkt;  // KKT factorization workspace (kkt.c), NULL when m = 0
  int evaluated;        // dal_forward outputs are current
  // integrator (owned by solve.c)
  void *integ;
  void (*integ_free)(void *);
  dal_solve_opts integ_opts;
  dal_stats stats;
  dal_init_report init_rep; // the last consistent start's report (init.c)
  int init_rep_valid;       // init_rep holds a report
  char err[DAL_ERRMSG_LEN];
};

// errors
int dal__set_err(char *buf, int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
#define DAL_FAIL(st, code, ...) dal__set_err((st)->err, (code), __VA_ARGS__)

/// format "(q0=..., q1=...)" of the state's coordinates into buf
void dal__fmt_q(const dal_system *sys, const double *q, char *buf, size_t len);

/// check a user callback's return: 0 ok, >0 recoverable, <0 stop; name the culprit
int dal__cb_status(dal_state *st, int rc, const char *what);

// pipeline (kinematics.c, dynamics.c, lagrangian.c)
/// particle r, v, gamma, J (compact), drdt at the state's (t, q, qdot)
int dal__kinematics(const dal_system *sys, dal_state *st);
/// constraint phi, phidot, gamma_phi and compact G (requires kinematics)
int dal__constraints(const dal_system *sys, dal_state *st);
/// applied forces F, energies' U, Q, c and (dense) M (requires kinematics)
int dal__dynamics(const dal_system *sys, dal_state *st);
/// generalized terms from user callbacks over q: Q += Q_user - dU/dq, *U += U(q)
int dal__genforces(const dal_system *sys, dal_state *st, double *U);
/// qddot from M qddot = Q - c by Cholesky (m = 0); names degenerate coordinates
int dal__solve_unconstrained(const dal_system *sys, dal_state *st);
/// particle accelerations, reactions and energies from qddot
void dal__finish(const dal_system *sys, dal_state *st);
/// Lagrangian route: A = d2L/dqdot2 (n x n col-major into A), rhs = dL/dq - X + Q_nc
int dal__lagrangian_terms(const dal_system *sys, dal_state *st, double *A, double *rhs,
                          double *h_out);

/// M x for the state's current J (works with or without dense M): y (n) = M x
void dal__mass_apply(const dal_system *sys, const dal_state *st, const double *x, double *y);

/// The KKT solve of constrained systems: qddot and lambda from
/// [M G'; G 0] [qddot; -lambda] = [Q - c; -gamma_phi]  (kkt.c)
int dal__solve_kkt(const dal_system *sys, dal_state *st);

/// KKT workspace of a constrained system (kkt.c): create (NULL on failure) and free
struct dal_kkt *dal__kkt_create(const dal_system *sys);
void dal__kkt_free(struct dal_kkt *k);

/// full evaluation at the state's (t, q, qdot): kinematics, constraints, dynamics, qddot
int dal__forward(const dal_system *sys, dal_state *st);

/// drop integrator memory (called by dal_state_set and dal_state_destroy)
void dal__integ_reset(dal_state *st);

// primitives' table versions and parameter names (builder.c)
/// name of parameter i of prim: its param_names entry, else "p<i>" written into buf
const char *dal__param_name(const dal_primitive *prim, int i, char *buf, size_t len);
/// DAL_OK when prim->version is one this library reads, else DAL_E_ARG with a message in err
int dal__prim_version_ok(const dal_primitive *prim, char *err, const char *what);

#endif
