// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// libFuzzer target: random models built through the public API must never crash or leak,
// and every answer the library gives must hold up.
//
// The fuzz bytes drive everything: dimension, coordinates (<= 12), particles (<= 6), their
// placements by registry primitives or small user primitives (with wrong counts and indices
// now and then), constraints, springs, dampers, gravity, user callbacks that return NaN or
// error codes, parameters including NaN, inf, 0, huge, tiny and subnormal values; or a long
// chain of 67..270 particles on rods (the sparse KKT and KLU paths). Then two states of the
// system and one of a foreign system go through a byte-chosen sequence of the whole public
// API: set, forward, advance, evolve (with the CSV monitor too), make_consistent,
// check_constraints, constraint forces, accessors, Jacobians, Lagrange residuals, foreign
// calls, with options from the defaults or not, short runs and long ones.
//
// Every byte is read in a statement of its own (never two reads in one function call,
// initializer or operator), so the decoding does not depend on the compiler's evaluation
// order: an input decodes to the same scene under gcc and clang (FZ_DIGEST=1 prints a digest
// of everything an input did, compared by scripts/fuzz_decode_check.sh).
//
// Invariants checked after every call (a violation aborts, which is how a fuzz target reports
// a finding):
//   - every status is one of DAL_STATUS_LIST; every failure of a builder or state call leaves
//     a non-empty message; a state of another system is DAL_E_STATE, always;
//   - the state's t, q, qdot are finite after every call; after advance/evolve t lies in
//     [t0, t1], t == t1 on success, and DAL_E_MAXSTEPS means t moved (no zero-progress loop);
//   - after DAL_OK from forward, advance, evolve or make_consistent every product is there and
//     finite (qddot, positions, ..., lambda, phi, energies, Jacobians, constraint and joint
//     forces);
//     products are handed out only while current (NULL or DAL_E_STATE otherwise);
//   - make_consistent leaves max |phi| within its tolerance; check_constraints reports a rank
//     consistent with its status; a monitor sees evaluated states at increasing times;
//   - two states of the same (pure) system given the same inputs end bit-identical;
//   - a failed state can be reset and evaluated again;
//   - per-trajectory parameters: a value is accepted only when finite, normal and (a mass)
//     positive, and then read back exactly; a refused one leaves the state's value;
//   - analysis: dal_equilibrium's DAL_OK is a point at rest with a consistent report, inside
//     the neighbourhood it promises; normal modes and Lyapunov exponents are finite on DAL_OK,
//     and a Lyapunov run takes no more segments than its span allows (no zero-progress loop);
//   - dal_evolve_at with byte-chosen output times: a refused list leaves the state where it
//     was; a trajectory recorded during a run spans part of it, is finite inside its span and
//     refuses times beyond it and NaN;
//   - symplectic methods (any of the six, any step) and every integration: DAL_E_ARG leaves
//     the state's time where it was; a monitor that calls dal_state_set or dal_advance on its
//     own state gets DAL_E_STATE with a message, and the run goes on.
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "dalembert/dalembert.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define FZ_MAX_COORDS 12
#define FZ_MAX_PARTS 6
#define FZ_MAX_PARAM 8
#define FZ_CHAIN_MAX 270 // particles of the longest chain

// ---------------------------------------------------------------- byte reader
typedef struct fz {
  const uint8_t *p;
  size_t n, i;
  uint64_t digest; // FNV-1a over every status, message and final value of this input
} fz;

static unsigned fz_u8(fz *f) { return f->i < f->n ? f->p[f->i++] : 0u; }

// uniform-ish integer in [0, k)
static int fz_pick(fz *f, int k) {
  unsigned c = fz_u8(f);
  return k > 0 ? (int)(c % (unsigned)k) : 0;
}

// a real number: mostly moderate, sometimes special (NaN, inf, 0, huge, tiny) or raw bits
static double fz_num(fz *f) {
  static const double pal[] = {0.0,
                               -0.0,
                               1.0,
                               -1.0,
                               0.5,
                               2.0,
                               10.0,
                               1e-3,
                               1e-8,
                               1e-12,
                               1e-300,
                               1e300,
                               -1e300,
                               DBL_MAX,
                               DBL_MIN,
                               4.9e-324,
                               NAN,
                               INFINITY,
                               -INFINITY,
                               3.141592653589793,
                               1.5707963267948966,
                               1e6,
                               -1e6,
                               1e-100};
  unsigned c = fz_u8(f);
  if (c < 176) return ((double)c - 88.0) / 16.0; // -5.5 .. 5.4375
  c -= 176;
  if (c < sizeof pal / sizeof pal[0]) return pal[c];
  uint64_t bits = 0;
  for (int k = 0; k < 8; ++k) {
    unsigned byte = fz_u8(f);
    bits = (bits << 8) | byte;
  }
  double x;
  memcpy(&x, &bits, sizeof x);
  return x;
}

// a positive quantity (mass, length, tolerance) that is sensible most of the time
static double fz_pos(fz *f, double typical) {
  unsigned c = fz_u8(f);
  if (c < 200) return typical * (0.25 + (double)c / 50.0);
  return fz_num(f);
}

// ---------------------------------------------------------------- digest
static void fz_hash(fz *f, const void *data, size_t len) {
  const unsigned char *b = data;
  for (size_t i = 0; i < len; ++i)
    f->digest = (f->digest ^ b[i]) * 1099511628211ULL;
}

// a message into the digest; the sign of a NaN it prints is left out (compilers differ in the
// sign of the NaN an invalid operation in the harness's own callbacks gives)
static void fz_hash_str(fz *f, const char *s) {
  for (; *s; ++s)
    if (!(s[0] == '-' && strncmp(s + 1, "nan", 3) == 0)) fz_hash(f, s, 1);
  fz_hash(f, "", 1);
}

// ---------------------------------------------------------------- invariants
// FZ_TRACE=1 in the environment prints each stage's status (to see what inputs reach)
static void fz_trace(const char *stage, int rc, const char *msg) {
  static int on = -1; // read once; the value never changes during a run
  if (on < 0) on = getenv("FZ_TRACE") != NULL;
  if (on)
    fprintf(stderr, "fz %8.3f %-12s %-18s %.400s\n", (double)clock() / CLOCKS_PER_SEC, stage,
            dal_status_name(rc), msg ? msg : "");
}

static void fz_die(const char *what, int rc, const char *msg) {
  fprintf(stderr, "fuzz_model: invariant violated: %s (status %d %s) msg='%s'\n", what, rc,
          dal_status_name(rc), msg ? msg : "");
  abort();
}

static void fz_status(const char *call, int rc) {
  // DAL_STOPPED (> 0) is evolve's status for a monitor that asked to stop
  if ((rc > 0 && (rc != DAL_STOPPED || strncmp(call, "evolve", 6) != 0)) ||
      strcmp(dal_status_name(rc), "DAL_UNKNOWN") == 0)
    fz_die(call, rc, NULL);
}

static int fz_b(fz *f, const dal_builder *b, const char *call, int rc) {
  fz_status(call, rc);
  if (rc && b && !dal_builder_errmsg(b)[0]) fz_die(call, rc, "(empty builder message)");
  fz_hash_str(f, call);
  fz_hash(f, &rc, sizeof rc);
  if (b) fz_hash_str(f, dal_builder_errmsg(b));
  return rc;
}

static int fz_s(fz *f, const dal_state *st, const char *call, int rc) {
  fz_status(call, rc);
  if (rc && st && !dal_state_errmsg(st)[0]) fz_die(call, rc, "(empty state message)");
  fz_hash_str(f, call);
  fz_hash(f, &rc, sizeof rc);
  if (st && rc) fz_hash_str(f, dal_state_errmsg(st));
  fz_trace(call, rc, st && rc ? dal_state_errmsg(st) : "");
  return rc;
}

// every entry of x (n) is finite
static int fz_finite(const double *x, int n) {
  for (int i = 0; i < n; ++i)
    if (!isfinite(x[i])) return 0;
  return 1;
}

// ---------------------------------------------------------------- user callbacks
// behaviour of a callback: 0 fine, 1 NaN, 2 recoverable once, 3 always recoverable, 4 stop,
// 5 huge values
typedef struct fz_cb {
  int mode;
  int calls;
  double scale;
  int N, d, n;
} fz_cb;

static int fz_mode_rc(fz_cb *c) {
  c->calls++;
  switch (c->mode) {
  case 2:
    return c->calls == 3 ? 1 : 0;
  case 3:
    return c->calls > 2 ? 1 : 0;
  case 4:
    return c->calls > 2 ? -3 : 0;
  default:
    return 0;
  }
}

static double fz_mode_val(const fz_cb *c, double x) {
  if (c->mode == 1 && c->calls > 1) return NAN;
  if (c->mode == 5) return 1e300 * x;
  return x;
}

static int fz_force(double t, const double *r, const double *v, double *F, void *ctx) {
  fz_cb *c = ctx;
  int rc = fz_mode_rc(c);
  for (int i = 0; i < c->N * c->d; ++i)
    F[i] += fz_mode_val(c, -c->scale * r[i] - 0.1 * v[i] + 0.01 * sin(t));
  return rc;
}

static int fz_genforce(double t, const double *q, const double *qdot, double *Q, void *ctx) {
  fz_cb *c = ctx;
  int rc = fz_mode_rc(c);
  for (int i = 0; i < c->n; ++i)
    Q[i] += fz_mode_val(c, -c->scale * sin(q[i]) - qdot[i] * t);
  return rc;
}

static int fz_pot_r(const dal_jet *r, dal_jet t, dal_jet *U, void *ctx) {
  fz_cb *c = ctx;
  int rc = fz_mode_rc(c);
  // an attracting point at the origin, ~ 1/|r|, plus a weak time-dependent field
  dal_jet s = dal_const(0.0);
  for (int i = 0; i < c->N * c->d; ++i)
    s = dal_add(s, dal_sq(r[i]));
  dal_jet inv = dal_div(dal_const(-c->scale), dal_sqrt(dal_addc(s, 1e-3)));
  *U = dal_add(inv, dal_scale(dal_sin(t), 0.01));
  if (c->mode == 1 && c->calls > 1) *U = dal_sqrt(dal_const(-1.0));
  return rc;
}

static int fz_pot_q(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  fz_cb *c = ctx;
  int rc = fz_mode_rc(c);
  dal_jet s = dal_const(0.0);
  for (int i = 0; i < c->n; ++i)
    s = dal_add(s, dal_cos(q[i]));
  *U = dal_add(dal_scale(s, -c->scale), dal_scale(t, 0.0));
  if (c->mode == 1 && c->calls > 1) *U = dal_log(dal_const(-1.0));
  return rc;
}

static int fz_path(dal_jet t, dal_jet *x, void *ctx) {
  fz_cb *c = ctx;
  int rc = fz_mode_rc(c);
  x[0] = dal_scale(dal_cos(t), c->scale);
  x[1] = dal_scale(dal_sin(t), c->scale);
  if (c->d == 3) x[2] = dal_scale(t, fz_mode_val(c, 0.1));
  return rc;
}

static int fz_curve(dal_jet s, dal_jet t, dal_jet *p, void *ctx) {
  fz_cb *c = ctx;
  int rc = fz_mode_rc(c);
  // an ellipse (2D) or a helix (3D) whose size breathes slowly with time
  dal_jet a = dal_addc(dal_scale(dal_sin(t), 0.1), 1.0);
  p[0] = dal_mul(a, dal_cos(s));
  p[1] = dal_scale(dal_mul(a, dal_sin(s)), c->scale);
  if (c->d == 3) p[2] = dal_scale(s, 0.2);
  if (c->mode == 1 && c->calls > 1) p[0] = dal_sqrt(dal_addc(s, -1e9));
  return rc;
}

static int fz_map(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx) {
  fz_cb *c = ctx;
  int rc = fz_mode_rc(c);
  // particle k, axis a: a smooth mix of the coordinates
  for (int k = 0; k < c->N; ++k)
    for (int a = 0; a < c->d; ++a) {
      dal_jet s = dal_scale(t, 0.01 * a);
      for (int j = 0; j < c->n; ++j) {
        dal_jet term = ((j + k + a) % 3 == 0) ? q[j] : dal_sin(q[j]);
        s = dal_add(s, dal_scale(term, (j % (c->d + k + 1) == a ? 1.0 : 0.25)));
      }
      r[k * c->d + a] = dal_scale(s, fz_mode_val(c, 1.0));
    }
  return rc;
}

static int fz_lagr(dal_jet t, const dal_jet *q, const dal_jet *qdot, dal_jet *L, void *ctx) {
  fz_cb *c = ctx;
  int rc = fz_mode_rc(c);
  dal_jet T = dal_const(0.0), U = dal_const(0.0);
  for (int i = 0; i < c->n; ++i) {
    T = dal_add(T, dal_scale(dal_sq(qdot[i]), 0.5 * (1.0 + i)));
    U = dal_add(U, dal_scale(dal_cos(q[i]), -c->scale));
  }
  *L = dal_add(dal_sub(T, U), dal_scale(t, 0.0));
  if (c->mode == 1 && c->calls > 1) *L = dal_div(*L, dal_const(0.0));
  return rc;
}

// ---------------------------------------------------------------- user primitives
static int u_circle2(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  out[0] = dal_addc(dal_add(dal_sq(in[0]), dal_sq(in[1])), -p[0] * p[0]);
  return 0;
}

static int u_dist2(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  out[0] = dal_addc(dal_hypot(dal_sub(in[2], in[0]), dal_sub(in[3], in[1])), -p[0]);
  return 0;
}

static int u_dist3(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet d[3] = {dal_sub(in[3], in[0]), dal_sub(in[4], in[1]), dal_sub(in[5], in[2])};
  out[0] = dal_addc(dal_norm(d, 3), -p[0]);
  return 0;
}

static int u_lin(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  out[0] = dal_sub(dal_scale(in[0], p[0]), dal_scale(dal_sin(t), p[1]));
  return 0;
}

static int u_pair(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)p;
  (void)ctx;
  out[0] = dal_sub(in[0], in[1]);
  out[1] = dal_add(in[0], dal_sin(in[1]));
  return 0;
}

static int u_callback(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)p;
  fz_cb *c = ctx;
  int rc = c ? fz_mode_rc(c) : -1;
  out[0] = dal_add(dal_sq(in[0]), dal_scale(t, c ? fz_mode_val(c, 0.01) : 0.0));
  out[1] = dal_sin(in[0]);
  return rc;
}

static const dal_primitive u_prims[] = {
    {.name = "u_circle2",
     .version = 1,
     .nin = 2,
     .nout = 1,
     .nparam = 1,
     .eval = u_circle2,
     .doc = "x^2 + y^2 - R^2",
     .flags = 0},
    {.name = "u_dist2",
     .version = 1,
     .nin = 4,
     .nout = 1,
     .nparam = 1,
     .eval = u_dist2,
     .doc = "|b - a| - L (2D)",
     .flags = 0},
    {.name = "u_dist3",
     .version = 1,
     .nin = 6,
     .nout = 1,
     .nparam = 1,
     .eval = u_dist3,
     .doc = "|b - a| - L (3D)",
     .flags = 0},
    {.name = "u_lin",
     .version = 1,
     .nin = 1,
     .nout = 1,
     .nparam = 2,
     .eval = u_lin,
     .doc = "a u - b sin t",
     .flags = 0},
    {.name = "u_pair",
     .version = 1,
     .nin = 2,
     .nout = 2,
     .nparam = 0,
     .eval = u_pair,
     .doc = "(u0 - u1, u0 + sin u1)",
     .flags = 0},
    {.name = "u_callback",
     .version = 1,
     .nin = 1,
     .nout = 2,
     .nparam = 0,
     .eval = u_callback,
     .doc = "(u^2 + ct, sin u), may fail",
     .flags = 0},
    {.name = "u_broken",
     .version = 1,
     .nin = 1,
     .nout = 2,
     .nparam = 0,
     .eval = NULL,
     .doc = "no eval function",
     .flags = 0},
};
#define FZ_NUPRIM ((int)(sizeof u_prims / sizeof u_prims[0]))

// a primitive: from the registry, a user one, or NULL
static const dal_primitive *fz_prim(fz *f) {
  int nreg = dal_primitive_count();
  int i = fz_pick(f, nreg + FZ_NUPRIM + 1);
  if (i < nreg) return dal_primitive_get(i);
  if (i < nreg + FZ_NUPRIM) return &u_prims[i - nreg];
  return NULL;
}

// ---------------------------------------------------------------- the model
#define FZ_MAX_CTX 8

// typed contexts of primitive instances
typedef union fz_ctx_slot {
  dal_curve curve;
  dal_moving_point point;
  dal_prescribed presc;
} fz_ctx_slot;

typedef struct fz_model {
  int dim, n, N, placed[FZ_MAX_PARTS];
  int chain;      // a long chain of particles on rods (N up to FZ_CHAIN_MAX)
  int next_coord; // next coordinate handed out by fz_coords
  int impure;     // some callback's answer depends on how often it was called
  fz_cb cbs[24];
  int ncb;
  fz_ctx_slot ctxs[FZ_MAX_CTX];
  int nctx;
} fz_model;

static fz_cb *fz_new_cb(fz *f, fz_model *m) {
  if (m->ncb >= (int)(sizeof m->cbs / sizeof m->cbs[0])) return &m->cbs[0];
  fz_cb *c = &m->cbs[m->ncb++];
  unsigned c0 = fz_u8(f);
  c->mode = c0 < 160 ? 0 : (int)(c0 % 6u);
  unsigned c1 = fz_u8(f);
  if (c1 < 200) {
    int k = fz_pick(f, 8);
    c->scale = 0.5 + k;
  } else {
    c->scale = fz_num(f);
  }
  c->calls = 0;
  c->d = m->dim;
  c->N = m->N;
  c->n = m->n;
  if (c->mode >= 1 && c->mode <= 4) m->impure = 1;
  return c;
}

static int fz_time(dal_jet t, dal_jet *f, void *ctx) {
  fz_cb *c = ctx;
  int rc = fz_mode_rc(c);
  *f = dal_scale(dal_sin(dal_scale(t, 3.0)), fz_mode_val(c, c->scale));
  return rc;
}

// the context for a primitive instance, of the type its documentation asks for: a dal_curve
// for curve primitives, a dal_moving_point for anchors, a dal_prescribed for prescribed
// motions, a callback context for the user primitive that reads one; NULL now and then
static void *fz_ctx(fz *f, fz_model *m, const dal_primitive *prim) {
  if (!prim) return NULL;
  if (fz_pick(f, 8) == 7) return NULL;
  if (m->nctx >= FZ_MAX_CTX) return NULL;
  fz_ctx_slot *s = &m->ctxs[m->nctx++];
  fz_cb *c = fz_new_cb(f, m);
  c->d = prim->nout;
  if (strncmp(prim->name, "curve", 5) == 0) {
    s->curve.fn = fz_curve;
    s->curve.ctx = c;
    return &s->curve;
  }
  if (strncmp(prim->name, "anchor", 6) == 0) {
    c->d = prim->nin; // the anchor point has the particle's dimension
    s->point.fn = fz_path;
    s->point.ctx = c;
    return &s->point;
  }
  if (strcmp(prim->name, "prescribed") == 0) {
    s->presc.fn = fz_time;
    s->presc.ctx = c;
    return &s->presc;
  }
  if (strcmp(prim->name, "u_callback") == 0) return c;
  return NULL;
}

// list of k coordinate indices: mostly the next unused ones (so that most coordinates move
// some mass), sometimes any, now and then out of range
static void fz_coords(fz *f, fz_model *m, int k, int *out) {
  for (int i = 0; i < k; ++i) {
    int c = fz_pick(f, 32);
    if (m->n == 0)
      out[i] = c < 30 ? 0 : -1;
    else if (c < 24)
      out[i] = m->next_coord++ % m->n;
    else
      out[i] = c < 30 ? c % m->n : (c == 30 ? -1 : m->n + 3);
  }
}

static void fz_params(fz *f, int k, double *out) {
  for (int i = 0; i < k && i < FZ_MAX_PARAM; ++i) {
    unsigned c = fz_u8(f);
    out[i] = c < 220 ? 0.2 + (double)(c % 40) / 10.0 : fz_num(f);
  }
}

// a coordinate map for a d-dimensional scene (nout == d), or now and then any primitive
static const dal_primitive *fz_map_prim(fz *f, int d) {
  if (fz_pick(f, 8) == 7) return fz_prim(f);
  const dal_primitive *fit[32];
  int nfit = 0;
  for (int i = 0; i < dal_primitive_count() && nfit < 32; ++i) {
    const dal_primitive *p = dal_primitive_get(i);
    if (p->nout == d && p->nin <= FZ_MAX_COORDS + d) fit[nfit++] = p;
  }
  return nfit ? fit[fz_pick(f, nfit)] : NULL;
}

// place particle k; counts derived from the primitive, sometimes deliberately wrong
// the builder's defs filled from positional arguments (the harness draws them in this order)
static int fz_place_def(dal_builder *b, int particle, const dal_primitive *prim, int parent, int nc,
                        const int *coords, int np, const double *par, void *ctx) {
  dal_place_def d = dal_default_place_def();
  d.prim = prim;
  d.parent = parent;
  d.ncoords = nc;
  d.coords = coords;
  d.param_list = par;
  d.nparam_list = np;
  d.ctx = ctx;
  return dal_builder_place_def(b, particle, &d);
}

static int fz_add_constraint(dal_builder *b, const char *name, const dal_primitive *prim,
                             int nparts, const int *parts, int nc, const int *coords, int np,
                             const double *par, void *ctx, int *row) {
  dal_constraint_def d = dal_default_constraint_def();
  d.name = name;
  d.prim = prim;
  d.nparts = nparts;
  d.parts = parts;
  d.ncoords = nc;
  d.coords = coords;
  d.param_list = par;
  d.nparam_list = np;
  d.ctx = ctx;
  return dal_builder_add_constraint_def(b, &d, row);
}

// a spring (k, L) or damper (k as c, L unused) between pa and pb, or to x0 + path(t) if pb < 0
static int fz_link(dal_builder *b, int damper, int pa, int pb, const double *x0, dal_path_fn *path,
                   void *ctx, double k, double L) {
  if (damper) {
    dal_damper_def dd = dal_default_damper_def();
    dd.a = pa;
    dd.b = pb;
    for (int i = 0; x0 && i < 3; ++i) // the builder reads d of them
      dd.anchor[i] = x0[i];
    dd.path = path;
    dd.ctx = ctx;
    dd.c = k;
    return dal_builder_add_damper_def(b, &dd);
  }
  dal_spring_def sd = dal_default_spring_def();
  sd.a = pa;
  sd.b = pb;
  for (int i = 0; x0 && i < 3; ++i) // the builder reads d of them
    sd.anchor[i] = x0[i];
  sd.path = path;
  sd.ctx = ctx;
  sd.k = k;
  sd.length = L;
  return dal_builder_add_spring_def(b, &sd);
}

static void fz_place(fz *f, dal_builder *b, fz_model *m, int k) {
  const dal_primitive *prim = fz_map_prim(f, m->dim);
  int parent = -1;
  if (k > 0 && fz_pick(f, 3) == 2) {
    int p = fz_pick(f, k + 1);
    int minus = fz_pick(f, 8) == 7;
    parent = p - minus;
  }
  int fixed = parent >= 0 ? m->dim : 0;
  int nc = prim ? prim->nin - fixed : 1;
  int np = prim ? prim->nparam : 0;
  if (fz_pick(f, 16) == 15) nc += fz_pick(f, 3) - 1;
  if (fz_pick(f, 16) == 15) np += fz_pick(f, 3) - 1;
  if (nc < 0) nc = fz_pick(f, 2) ? 0 : -1;
  if (nc > FZ_MAX_COORDS) nc = FZ_MAX_COORDS;
  if (np < 0) np = 0;
  if (np > FZ_MAX_PARAM) np = FZ_MAX_PARAM;
  int coords[FZ_MAX_COORDS] = {0};
  double par[FZ_MAX_PARAM] = {0};
  fz_coords(f, m, nc > 0 ? nc : 0, coords);
  fz_params(f, np, par);
  void *ctx = fz_ctx(f, m, prim);
  int pk = fz_pick(f, 24) == 23 ? k + FZ_MAX_PARTS : k;
  int with_coords = fz_pick(f, 20) != 19;
  int with_par = fz_pick(f, 20) != 19;
  int rc = fz_place_def(b, pk, prim, parent, nc, with_coords ? coords : NULL, np,
                        with_par ? par : NULL, ctx);
  fz_b(f, b, "place", rc);
  if (!rc && pk == k) m->placed[k] = 1;
  // mostly fall back to a valid placement so that the model compiles
  if (!m->placed[k] && fz_pick(f, 8) && m->n > 0) {
    int d = m->dim, cc[3];
    for (int a = 0; a < d; ++a)
      cc[a] = (k * d + a) % m->n;
    rc = fz_place_def(b, k, d == 2 ? &dal_map_cartesian2 : &dal_map_cartesian3, -1, d, cc, 0, NULL,
                      NULL);
    fz_b(f, b, "place (fallback)", rc);
    if (!rc) m->placed[k] = 1;
  }
}

static void fz_constraint(fz *f, dal_builder *b, fz_model *m, int i) {
  const dal_primitive *prim = fz_prim(f);
  int nparts = 0, parts[4] = {0};
  if (prim && m->N > 0) {
    int maxp = prim->nin / m->dim;
    nparts = maxp > 0 ? fz_pick(f, (maxp < 4 ? maxp : 4) + 1) : 0;
  }
  for (int a = 0; a < nparts; ++a) {
    int p = fz_pick(f, 16);
    parts[a] = p < 14 ? (m->N ? p % m->N : 0) : (p == 14 ? -2 : m->N);
  }
  int nc = prim ? prim->nin - nparts * m->dim : 1;
  int np = prim ? prim->nparam : 0;
  if (fz_pick(f, 16) == 15) nc += fz_pick(f, 3) - 1;
  if (nc < 0) nc = 0;
  if (nc > FZ_MAX_COORDS) nc = FZ_MAX_COORDS;
  if (np > FZ_MAX_PARAM) np = FZ_MAX_PARAM;
  int coords[FZ_MAX_COORDS] = {0};
  double par[FZ_MAX_PARAM] = {0};
  fz_coords(f, m, nc, coords);
  fz_params(f, np, par);
  char name[16];
  snprintf(name, sizeof name, "c%d", i);
  int row = -1;
  int named = fz_pick(f, 8);
  void *ctx = fz_ctx(f, m, prim);
  int rc = fz_add_constraint(b, named ? name : NULL, prim, nparts, parts, nc, coords, np, par, ctx,
                             &row);
  fz_b(f, b, "add_constraint", rc);
}

// forces of a particle model: gravity, springs, dampers, potentials, force callbacks
static void fz_forces(fz *f, dal_builder *b, fz_model *m) {
  int nforce = fz_pick(f, 6);
  for (int i = 0; i < nforce; ++i) {
    int what = fz_pick(f, 9);
    double x0[3];
    for (int a = 0; a < 3; ++a)
      x0[a] = fz_num(f);
    int pa = m->N ? fz_pick(f, m->N + 1) : 0;
    int pb = m->N ? fz_pick(f, m->N + 1) : 0;
    fz_cb *c = NULL;
    if (what >= 4) {
      c = fz_new_cb(f, m);
      c->N = m->N;
      c->n = m->n;
    }
    switch (what) {
    case 0: {
      double g[3];
      for (int a = 0; a < 3; ++a)
        g[a] = fz_num(f);
      fz_b(f, b, "set_gravity", dal_builder_set_gravity(b, g));
      break;
    }
    case 1: {
      double k = fz_pos(f, 10.0);
      double L = fz_pos(f, 1.0);
      fz_b(f, b, "add_spring", fz_link(b, 0, pa, pb, NULL, NULL, NULL, k, L));
      break;
    }
    case 2: {
      double cd = fz_pos(f, 0.5);
      fz_b(f, b, "add_damper", fz_link(b, 1, pa, pb, NULL, NULL, NULL, cd, 0.0));
      break;
    }
    case 3: {
      int with_x0 = fz_pick(f, 8) != 7;
      double k = fz_pos(f, 5.0);
      double L = fz_pos(f, 0.5);
      fz_b(f, b, "add_anchor_spring", fz_link(b, 0, pa, -1, with_x0 ? x0 : NULL, NULL, NULL, k, L));
      break;
    }
    case 4: {
      int moving = fz_pick(f, 2);
      double cd = fz_pos(f, 0.5);
      fz_b(f, b, "add_anchor_damper",
           fz_link(b, 1, pa, -1, x0, moving ? fz_path : NULL, c, cd, 0.0));
      break;
    }
    case 5: {
      int with_fn = fz_pick(f, 16) != 15;
      fz_b(f, b, "add_force", dal_builder_add_force(b, with_fn ? fz_force : NULL, c));
      break;
    }
    case 6:
      fz_b(f, b, "add_genforce", dal_builder_add_genforce(b, fz_genforce, c));
      break;
    case 7:
      fz_b(f, b, "add_potential_r", dal_builder_add_potential_r(b, fz_pot_r, c));
      break;
    default:
      fz_b(f, b, "add_potential_q", dal_builder_add_potential_q(b, fz_pot_q, c));
      break;
    }
  }
}

// A chain of N particles in Cartesian coordinates hanging from the origin on rods of length
// ~1 (an anchor rod, then a rod between neighbours), under gravity: n = d N coordinates and N
// constraint rows, so the KKT system is large and sparse (KLU from N = 67 on) and above
// N = 256 (2D) no dense M exists at all.
static void fz_chain(fz *f, dal_builder *b, fz_model *m) {
  int d = m->dim, N = m->N;
  for (int k = 0; k < N; ++k) {
    char name[24];
    int c[3], p = -1;
    for (int a = 0; a < d; ++a) {
      snprintf(name, sizeof name, "%c%d", "xyz"[a], k);
      fz_b(f, b, "add_coord", dal_builder_add_coord(b, name, &c[a]));
    }
    snprintf(name, sizeof name, "p%d", k);
    double mass = k % 16 == 0 ? fz_pos(f, 1.0) : 1.0;
    if (fz_b(f, b, "add_particle", dal_builder_add_particle(b, name, mass, &p)))
      fz_b(f, b, "add_particle", dal_builder_add_particle(b, name, 1.0, &p));
    fz_b(f, b, "place",
         fz_place_def(b, p, d == 2 ? &dal_map_cartesian2 : &dal_map_cartesian3, -1, d, c, 0, NULL,
                      NULL));
  }
  double g[3] = {0.0, 0.0, 0.0};
  g[d - 1] = -9.81;
  fz_b(f, b, "set_gravity", dal_builder_set_gravity(b, g));
  for (int k = 0; k < N; ++k) {
    char name[24];
    snprintf(name, sizeof name, "rod%d", k);
    double L = k % 8 == 0 ? fz_pos(f, 1.0) : 1.0;
    if (k == 0) {
      double par[4] = {L, 0.0, 0.0, 0.0};
      fz_b(f, b, "add_constraint",
           fz_add_constraint(b, name, d == 2 ? &dal_con_anchor2 : &dal_con_anchor3, 1, &k, 0, NULL,
                             d + 1, par, NULL, NULL));
    } else {
      int parts[2] = {k - 1, k};
      fz_b(f, b, "add_constraint",
           fz_add_constraint(b, name, d == 2 ? &dal_con_distance2 : &dal_con_distance3, 2, parts, 0,
                             NULL, 1, &L, NULL, NULL));
    }
  }
  // now and then a damper along the chain or a force callback on it
  int extra = fz_pick(f, 4);
  if (extra == 1) {
    double cd = fz_pos(f, 0.5);
    fz_b(f, b, "add_damper", fz_link(b, 1, 0, N - 1, NULL, NULL, NULL, cd, 0.0));
  } else if (extra == 2) {
    fz_cb *c = fz_new_cb(f, m);
    c->N = N;
    c->n = m->n;
    fz_b(f, b, "add_force", dal_builder_add_force(b, fz_force, c));
  }
}

// build the model from the bytes; returns a compiled system or NULL
static dal_system *fz_build(fz *f, fz_model *m, dal_builder **bout) {
  int dim = 2 + fz_pick(f, 2);
  if (fz_pick(f, 64) == 63) {
    // invalid dimensions now and then; 4 and 5 select the chain in 2D and 3D
    dim = fz_pick(f, 6);
    if (dim >= 4) {
      m->chain = 1;
      dim -= 2;
    }
  }
  dal_builder *b = NULL;
  int rc = dal_builder_create(dim, &b);
  fz_status("builder_create", rc);
  if (rc) {
    if (b) fz_die("builder_create returned an object on failure", rc, NULL);
    return NULL;
  }
  if (dim == 0) {
    // dim 0 is a Lagrangian-only builder: particles are refused by name
    if (dal_builder_add_particle(b, "p", 1.0, NULL) != DAL_E_ARG)
      fz_die("a dim-0 builder accepted a particle", 0, NULL);
    dal_builder_destroy(b);
    return NULL;
  }
  *bout = b;
  m->dim = dim;
  if (m->chain) {
    int big = fz_pick(f, 8) == 7;
    int extra = fz_pick(f, 44);
    // 67..110 particles (sparse KKT with a dense M), or beyond 512 coordinates (no dense M)
    m->N = big ? (dim == 2 ? 257 : 171) + extra % 14 : 67 + extra;
    m->n = dim * m->N;
    fz_chain(f, b, m);
  } else {
    // particles first, then about as many coordinates as they can use (unused coordinates
    // only make the mass matrix singular)
    int kind = fz_pick(f, 16); // 14: Lagrangian, 15: whole-system map, else particles
    int nparts = kind == 14 ? 0 : 1 + fz_pick(f, FZ_MAX_PARTS);
    if (fz_pick(f, 32) == 31) nparts = 0;
    int ncmax = nparts ? dim * nparts : FZ_MAX_COORDS;
    m->n = 1 + fz_pick(f, ncmax < FZ_MAX_COORDS ? ncmax : FZ_MAX_COORDS);
    if (fz_pick(f, 8) == 7) m->n = fz_pick(f, FZ_MAX_COORDS + 1);
    for (int i = 0; i < m->n; ++i) {
      char name[16];
      snprintf(name, sizeof name, "q%d", i);
      int idx = -1;
      int named = fz_pick(f, 4);
      fz_b(f, b, "add_coord", dal_builder_add_coord(b, named ? name : NULL, &idx));
    }
    if (kind == 14) {
      fz_cb *c = fz_new_cb(f, m);
      c->n = m->n;
      fz_b(f, b, "set_lagrangian", dal_builder_set_lagrangian(b, fz_lagr, c));
    }
    m->N = nparts;
    for (int k = 0; k < m->N; ++k) {
      char name[16];
      snprintf(name, sizeof name, "p%d", k);
      int idx = -1;
      double mass = fz_pos(f, 1.0);
      if (fz_b(f, b, "add_particle", dal_builder_add_particle(b, name, mass, &idx))) {
        // a rejected particle: add a sane one so indices stay aligned
        fz_b(f, b, "add_particle", dal_builder_add_particle(b, name, 1.0, &idx));
      }
    }
    if (kind == 15 && m->N > 0) {
      fz_cb *c = fz_new_cb(f, m);
      c->N = m->N;
      c->n = m->n;
      fz_b(f, b, "set_map", dal_builder_set_map(b, fz_map, c));
    } else {
      for (int k = 0; k < m->N; ++k)
        if (fz_pick(f, 32) != 31) fz_place(f, b, m, k);
    }
    int ncon = fz_pick(f, 4);
    for (int i = 0; i < ncon; ++i)
      fz_constraint(f, b, m, i);
    fz_forces(f, b, m);
  }
  dal_system *sys = NULL;
  rc = fz_b(f, b, "compile", dal_builder_compile(b, &sys));
  fz_trace("compile", rc, dal_builder_errmsg(b));
  if (rc && sys) fz_die("compile returned a system on failure", rc, NULL);
  if (!rc) {
    if (dal_system_ncoords(sys) != m->n || dal_system_dim(sys) != m->dim)
      fz_die("compiled sizes differ from the builder's", rc, NULL);
    // every name accessor answers in range and NULL out of range
    for (int i = -1; i <= m->n; ++i)
      if ((dal_system_coord_name(sys, i) != NULL) != (i >= 0 && i < m->n))
        fz_die("coord_name range", i, NULL);
    int mc = dal_system_nconstraints(sys);
    for (int i = -1; i <= mc; ++i)
      if ((dal_system_constraint_name(sys, i) != NULL) != (i >= 0 && i < mc))
        fz_die("constraint_name range", i, NULL);
    int N = dal_system_nparticles(sys);
    for (int k = -1; k <= N; ++k)
      if ((isnan(dal_system_mass(sys, k)) != !(k >= 0 && k < N)) ||
          ((dal_system_particle_name(sys, k) != NULL) != (k >= 0 && k < N)))
        fz_die("particle accessor range", k, NULL);
  }
  return sys;
}

// ---------------------------------------------------------------- checks of a state
#define FZ_NQ (3 * FZ_CHAIN_MAX) // largest n

typedef struct fz_run_ctx {
  const dal_system *sys;
  fz_model *m;
  int n, N, d, mc, lag;
  dal_state *st[2];       // two states of sys
  const dal_system *fsys; // a foreign system and its state
  dal_state *fst;
  FILE *devnull; // the CSV monitor's stream (opened when first needed)
} fz_run_ctx;

// the state's t, q, qdot are finite (after any call)
static void fz_finite_state(const fz_run_ctx *r, const dal_state *st, int rc, const char *call) {
  if (!isfinite(dal_state_time(st)) || !fz_finite(dal_state_q(st), r->n) ||
      !fz_finite(dal_state_qdot(st), r->n))
    fz_die(call, rc, "non-finite t, q or qdot kept");
}

// after DAL_OK from an evaluating call: every product exists and is finite
static void fz_products(fz *f, const fz_run_ctx *r, dal_state *st, const char *call) {
  int n = r->n, Nd = r->N * r->d;
  const double *x;
  if (!(x = dal_state_qddot(st)) || !fz_finite(x, n))
    fz_die(call, 0, "qddot missing or not finite");
  const double *(*nd[])(const dal_state *) = {
      dal_state_positions, dal_state_velocities, dal_state_accelerations, dal_state_drdt,
      dal_state_gamma,     dal_state_forces,     dal_state_reactions};
  for (size_t i = 0; i < sizeof nd / sizeof nd[0]; ++i)
    if (!(x = nd[i](st)) || !fz_finite(x, Nd))
      fz_die(call, (int)i, "particle product missing or not finite");
  if (!(x = dal_state_genforces(st)) || !fz_finite(x, n))
    fz_die(call, 0, "Q missing or not finite");
  x = dal_state_bias(st);
  if (r->lag ? x != NULL : (!x || !fz_finite(x, n))) fz_die(call, 0, "c missing or not finite");
  if ((x = dal_state_mass_matrix(st)) != NULL && n <= 256 && !fz_finite(x, n * n))
    fz_die(call, 0, "M not finite");
  if (r->mc > 0) {
    const double *(*mr[])(const dal_state *) = {dal_state_lambda, dal_state_phi, dal_state_phidot};
    for (int i = 0; i < 3; ++i)
      if (!(x = mr[i](st)) || !fz_finite(x, r->mc))
        fz_die(call, i, "lambda/phi/phidot missing or not finite");
  }
  dal_energies e;
  int rc = dal_state_energies(st, &e);
  fz_s(f, st, "state_energies", rc);
  if (rc != DAL_OK && rc != DAL_E_NONFINITE) fz_die(call, rc, "energies of an evaluated state");
  // h is NaN by definition where a constraint depends on t (state.h), never inf
  if (rc == DAL_OK && (!isfinite(e.E) || !(isfinite(e.h) || (isnan(e.h) && r->mc > 0)) ||
                       (!r->lag && !isfinite(e.T))))
    fz_die(call, rc, "energies not finite after DAL_OK");
  static double buf[3 * FZ_NQ];
  for (int k = 0; k < r->N && k < 2; ++k) {
    int kk = k ? r->N - 1 : 0;
    rc = fz_s(f, st, "state_jacobian", dal_state_jacobian(r->sys, st, kk, buf));
    if (rc || !fz_finite(buf, r->d * n)) fz_die(call, rc, "jacobian of an evaluated state");
  }
  rc = fz_s(f, st, "constraint_forces", dal_constraint_forces(r->sys, st, buf));
  if (rc || !fz_finite(buf, Nd)) fz_die(call, rc, "constraint forces of an evaluated state");
  rc = fz_s(f, st, "constraint_genforces", dal_constraint_genforces(r->sys, st, buf));
  if (rc || !fz_finite(buf, n)) fz_die(call, rc, "generalized constraint forces");
  // joint forces: finite wherever there are placements (a Lagrangian or one global map has none)
  rc = fz_s(f, st, "joint_forces", dal_joint_forces(r->sys, st, buf));
  if (rc == DAL_OK ? !fz_finite(buf, Nd) : rc != DAL_E_UNSUPPORTED)
    fz_die(call, rc, "joint forces of an evaluated state");
}

// after an advance or evolve from ta towards t1: the state is at a time in [ta, t1], t1 on
// success, and a run that hit max_steps moved t
static void fz_progress(fz *f, const fz_run_ctx *r, dal_state *st, double ta, double t1, int rc,
                        const char *call, int stopped) {
  double t = dal_state_time(st);
  fz_finite_state(r, st, rc, call);
  if (isfinite(t1) && t1 >= ta && !(t >= ta && t <= t1))
    fz_die("state time left [t0, t1]", rc, dal_state_errmsg(st));
  if (rc == DAL_OK && isfinite(t1) && t1 >= ta && !stopped && t != t1)
    fz_die(call, rc, "success but the state is not at t1");
  if (rc == DAL_E_MAXSTEPS && !(t > ta)) fz_die(call, rc, "max_steps taken without progress in t");
  if (rc == DAL_E_ARG && t != ta) fz_die(call, rc, "a refused run moved the state's time");
  if (rc == DAL_OK) fz_products(f, r, st, call);
}

// a trajectory recorded during a run from ta: detached, its span inside [ta, the state's time],
// every evaluation inside the span finite (its records come from accepted steps), outside it
// DAL_E_ARG, at NaN DAL_E_NONFINITE (or DAL_E_ARG when empty); then destroyed
static void fz_trajectory(fz *f, dal_state *st, dal_trajectory *tr, double ta, int n) {
  if (dal_state_set_trajectory(st, NULL) != DAL_OK) fz_die("detaching a trajectory", 0, NULL);
  double s0 = NAN, s1 = NAN, q[FZ_NQ], qd[FZ_NQ];
  long nrec = dal_trajectory_span(tr, &s0, &s1);
  fz_hash(f, &nrec, sizeof nrec);
  if (nrec < 0) fz_die("trajectory span", (int)nrec, dal_trajectory_errmsg(tr));
  if (nrec > 0) {
    if (!(s0 >= ta && s1 >= s0 && s1 <= dal_state_time(st)))
      fz_die("a trajectory's span outside its run", 0, dal_trajectory_errmsg(tr));
    for (int k = 0; k <= 4; ++k) {
      int rc = dal_trajectory_eval(tr, s0 + 0.25 * k * (s1 - s0), q, qd);
      if (rc != DAL_OK || !fz_finite(q, n) || !fz_finite(qd, n))
        fz_die("a trajectory inside its span", rc, dal_trajectory_errmsg(tr));
      fz_hash(f, q, (size_t)n * sizeof *q);
    }
    if (dal_trajectory_eval(tr, s1 + 1.0 + fabs(s1), q, qd) != DAL_E_ARG)
      fz_die("a trajectory evaluated beyond its span", 0, dal_trajectory_errmsg(tr));
  }
  int rn = dal_trajectory_eval(tr, NAN, q, qd);
  if (!(rn == DAL_E_NONFINITE || (nrec == 0 && rn == DAL_E_ARG)) || !dal_trajectory_errmsg(tr)[0])
    fz_die("a trajectory at NaN", 0, dal_trajectory_errmsg(tr));
  dal_trajectory_destroy(tr);
}

// ---------------------------------------------------------------- solving
typedef struct fz_path_ctx {
  int n;
  double a[FZ_NQ], w;
} fz_path_ctx;

static int fz_qpath(dal_jet t, dal_jet *q, void *ctx) {
  const fz_path_ctx *p = ctx;
  for (int i = 0; i < p->n; ++i)
    q[i] = dal_addc(dal_scale(dal_sin(dal_scale(t, p->w)), 0.1), p->a[i]);
  return 0;
}

typedef struct fz_mon {
  double t0, t1, last;
  int calls, stop_at, stopped, n, csv;
  int unevaluated; // the state could not be evaluated at an output time (evolve must fail)
  int repeats;     // output times may repeat (a list for dal_evolve_at)
  int reenter;     // 1, 2: the monitor calls dal_state_set / dal_advance on its own state
  dal_csv out;
} fz_mon;

static int fz_monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  fz_mon *mo = ctx;
  double t = dal_state_time(st);
  if (!(t >= mo->t0 && t <= mo->t1)) fz_die("monitor time outside [t0, t1]", 0, NULL);
  if (mo->calls && !(t > mo->last || (mo->repeats && t == mo->last)))
    fz_die("monitor times do not increase", 0, NULL);
  mo->last = t;
  const double *q = dal_state_q(st), *qdd = dal_state_qddot(st);
  if (!fz_finite(q, mo->n)) fz_die("monitor sees a non-finite q", 0, NULL);
  // products are evaluated on first read; where that evaluation fails (a point between steps
  // outside the model's domain) they are NULL and evolve must fail there
  if (!qdd) {
    mo->unevaluated = 1;
    return 0;
  }
  if (!fz_finite(qdd, mo->n)) fz_die("monitor sees a non-finite qddot", 0, NULL);
  if (mo->reenter) {
    // the state belongs to the run: a call that would move it is refused, by name
    dal_state *w = (dal_state *)st; // what a careless monitor does
    dal_solve_opts o = dal_default_solve_opts();
    int rc = mo->reenter == 1 ? dal_state_set(sys, w, t, q, dal_state_qdot(st))
                              : dal_advance(sys, w, &o, t + 1.0);
    if (rc != DAL_E_STATE || !dal_state_errmsg(st)[0])
      fz_die("a monitor moved the state under its run", rc, dal_state_errmsg(st));
    if (dal_state_time(st) != t) fz_die("a refused re-entrant call moved the state", rc, NULL);
  }
  if (mo->csv) {
    int rc = dal_csv_monitor(sys, st, &mo->out);
    if (rc != DAL_OK && rc != DAL_E_STATE) fz_die("csv monitor", rc, dal_state_errmsg(st));
    if (rc) return rc;
  }
  // stop at the chosen call (alternately as success or as failure), and after 64 calls
  // whatever dt was (a tiny dt means countless output times)
  if (++mo->calls != mo->stop_at && mo->calls < 64) return 0;
  mo->stopped = 1;
  return mo->calls % 2 || mo->calls >= 64 ? 1 : -1;
}

static void fz_opts(fz *f, dal_solve_opts *o) {
  *o = dal_default_solve_opts();
  o->method = (dal_method)fz_pick(f, 7);
  o->form = (dal_formulation)fz_pick(f, 5);
  o->linsol = (dal_linsol)fz_pick(f, 3);
  if (fz_pick(f, 8) == 7) o->method = (dal_method)(7 + fz_pick(f, 6)); // the symplectic six
  if (fz_pick(f, 32) == 31) o->form = (dal_formulation)(5 + fz_pick(f, 3));
  if (fz_u8(f) < 220) {
    int e = fz_pick(f, 11);
    o->rtol = pow(10.0, -2.0 - e);
  } else {
    o->rtol = fz_num(f);
  }
  if (fz_u8(f) < 220) {
    int e = fz_pick(f, 11);
    o->atol = pow(10.0, -3.0 - e);
  } else {
    o->atol = fz_num(f);
  }
  if (fz_pick(f, 8) == 7) o->h0 = fz_u8(f) < 128 ? 1e-4 : fz_num(f);
  if (fz_pick(f, 8) == 7) o->hmin = fz_u8(f) < 128 ? 1e-12 : fz_num(f);
  if (fz_pick(f, 8) == 7) o->hmax = fz_u8(f) < 128 ? 1e-2 : fz_num(f);
  if (fz_u8(f) < 220) {
    int k = fz_pick(f, 10);
    o->fixed_step = 1e-3 * (1 + k);
  } else {
    o->fixed_step = fz_num(f);
  }
  o->max_steps = 1 + fz_pick(f, 200);
  if (fz_pick(f, 32) == 31) o->max_steps = -fz_pick(f, 3);
  if (fz_pick(f, 4) == 3) {
    o->baumgarte_alpha = fz_u8(f) < 200 ? fz_pick(f, 20) : fz_num(f);
    o->baumgarte_beta = fz_u8(f) < 200 ? fz_pick(f, 20) : fz_num(f);
  }
  o->project = fz_pick(f, 2);
  o->sparse_threshold = fz_pick(f, 2) ? 200 : fz_pick(f, 40);
  // options not only from the defaults: raw bytes (refused by the cookie check, or with the
  // cookie kept, by the field checks), fixed-step explicit RK, long runs
  int mode = fz_pick(f, 32);
  if (mode == 31) {
    int cookie = o->cookie, keep = fz_pick(f, 2);
    unsigned char raw[sizeof *o];
    for (size_t i = 0; i < sizeof raw; ++i)
      raw[i] = (unsigned char)fz_u8(f);
    memcpy(o, raw, sizeof raw);
    if (keep) o->cookie = cookie;
  } else if (mode == 30) {
    o->fixed_erk = 1;
  } else if (mode == 29) {
    int k = fz_pick(f, 6);
    o->max_steps = 1000 + 500 * k;
  }
}

// Long runs are for the small models; a chain stays short (each of its steps costs a sparse
// factorization of ~600 unknowns), and in IDA with the dense solver its difference-quotient
// Newton matrix of ~600 columns is legitimate but takes seconds under the sanitizers.
static void fz_cap(const fz_run_ctx *r, dal_solve_opts *o) {
  if (!r->m->chain) return;
  if (o->max_steps > 60) o->max_steps = 60;
  if (o->linsol == DAL_LINSOL_DENSE) o->linsol = DAL_LINSOL_AUTO;
}

// one advance or evolve of st with options from the bytes, and its invariants
static void fz_integrate(fz *f, fz_run_ctx *r, dal_state *st) {
  dal_solve_opts o;
  fz_opts(f, &o);
  double ta = dal_state_time(st);
  double hz;
  if (fz_u8(f) < 230) {
    int k = fz_pick(f, 50);
    hz = 1e-3 * (1 + k);
  } else {
    hz = fz_num(f);
  }
  fz_cap(r, &o);
  if (o.max_steps >= 1000) hz *= 10; // a long run
  double t1 = ta + hz;
  if (fz_pick(f, 3) == 0) {
    fz_mon mo;
    memset(&mo, 0, sizeof mo);
    mo.t0 = ta;
    mo.t1 = t1;
    mo.n = r->n;
    mo.stop_at = fz_pick(f, 6);
    mo.csv = fz_pick(f, 4) == 3;
    mo.reenter = fz_pick(f, 8) < 2 ? 1 + fz_pick(f, 2) : 0;
    if (mo.csv) {
      if (!r->devnull) r->devnull = fopen("/dev/null", "w");
      mo.out.fp = r->devnull;
      mo.csv = r->devnull != NULL;
    }
    double dt;
    if (fz_u8(f) < 230) {
      int k = fz_pick(f, 8);
      dt = hz / (1 + k);
    } else {
      dt = fz_num(f);
    }
    // now and then a list of output times instead of the grid (dal_evolve_at: sorted, or with
    // a byte-chosen value anywhere, NaN and decreasing ones included), and a trajectory
    // recorded during the run
    int at = fz_pick(f, 4) == 0;
    int record = fz_pick(f, 4) == 0;
    double times[8];
    int nt = 0, bad = 0; // bad: a list dal_evolve_at must refuse before any step
    if (at) {
      nt = 1 + fz_pick(f, 8);
      for (int i = 0; i < nt; ++i) {
        int raw = fz_u8(f) >= 240;
        times[i] = raw ? fz_num(f) : ta + hz * (i + 1) / nt;
        if (!isfinite(times[i]) || (i > 0 && times[i] < times[i - 1]) || times[i] < ta) bad = 1;
      }
      t1 = times[nt - 1];
      mo.t1 = t1;
      mo.repeats = 1;
    }
    dal_trajectory *tr = NULL;
    if (record && dal_trajectory_create(r->sys, &tr) == DAL_OK &&
        fz_s(f, st, "set_trajectory", dal_state_set_trajectory(st, tr)) != DAL_OK)
      fz_die("a fresh trajectory was refused by an idle state", 0, dal_state_errmsg(st));
    const char *call = at ? "evolve_at" : "evolve";
    int rc = fz_s(f, st, call,
                  at ? dal_evolve_at(r->sys, st, &o, times, (size_t)nt, fz_monitor, &mo)
                     : dal_evolve(r->sys, st, &o, t1, dt, fz_monitor, &mo));
    // a bad list is refused, and moves nothing
    if (bad && (rc >= 0 || dal_state_time(st) != ta || mo.calls))
      fz_die("a bad list of output times was not refused before any step", rc,
             dal_state_errmsg(st));
    if (tr) fz_trajectory(f, st, tr, ta, r->n);
    // a monitor that stopped the run early leaves the state before t1
    fz_progress(f, r, st, ta, t1, rc, call, mo.stopped);
    if (rc == DAL_OK && mo.calls < 1 && isfinite(t1) && t1 >= ta && !mo.unevaluated)
      fz_die("evolve succeeded without calling the monitor", rc, NULL);
    if (mo.unevaluated && rc >= 0)
      fz_die("the monitor saw a state that could not be evaluated, yet evolve went on", rc,
             dal_state_errmsg(st));
  } else {
    int rc = fz_s(f, st, "advance", dal_advance(r->sys, st, &o, t1));
    fz_progress(f, r, st, ta, t1, rc, "advance", 0);
  }
  dal_stats stats;
  fz_status("state_stats", dal_state_stats(st, &stats));
  if (stats.steps < 0 || stats.rhs_evals < 0) fz_die("negative statistics", 0, NULL);
  char what[160];
  snprintf(what, sizeof what, "n=%d %s/%s linsol %d max_steps %ld: %ld steps, %ld evaluations",
           r->n, dal_method_name(o.method), dal_formulation_name(o.form), (int)o.linsol,
           o.max_steps, stats.steps, stats.rhs_evals);
  fz_trace("stats", 0, what);
}

// the initial (q, qdot) of a chain: hanging from the origin, turned by an angle in the plane
// of the first and the vertical axis and turning rigidly (consistent with the rods), plus a
// small perturbation now and then (make_consistent's job)
static void fz_chain_state(fz *f, const fz_model *m, double *q, double *qd) {
  int d = m->dim, v = d - 1;
  double th = ((double)fz_pick(f, 64) - 32.0) / 32.0;
  double w = ((double)fz_pick(f, 64) - 32.0) / 16.0;
  double eps = fz_pick(f, 4) == 3 ? 1e-3 : 0.0;
  for (int k = 0; k < m->N; ++k) {
    double s = k + 1.0;
    for (int a = 0; a < d; ++a)
      q[k * d + a] = qd[k * d + a] = 0.0;
    q[k * d] = s * sin(th) + eps * (k % 3);
    q[k * d + v] = -s * cos(th);
    qd[k * d] = w * s * cos(th);
    qd[k * d + v] = w * s * sin(th);
  }
}

// a state of another system: every (system, state) call refuses it with DAL_E_STATE
static void fz_foreign(fz *f, fz_run_ctx *r, dal_state *st) {
  int which = fz_pick(f, 11), rc = 0;
  dal_state *fs = r->fst;
  double t0 = dal_state_time(fs), q0 = dal_state_q(fs)[0];
  static double buf[3 * FZ_NQ];
  dal_solve_opts o = dal_default_solve_opts();
  dal_csv csv = {r->devnull, 1, 0, NULL};
  switch (which) {
  case 0:
    rc = dal_state_jacobian(r->sys, fs, 0, buf);
    break;
  case 1:
    rc = dal_constraint_forces(r->sys, fs, buf);
    break;
  case 2:
    rc = dal_constraint_genforces(r->sys, fs, buf);
    break;
  case 3:
    rc = dal_csv_monitor(r->sys, fs, &csv);
    break;
  case 4:
    rc = dal_forward(r->sys, fs);
    break;
  case 5:
    rc = dal_advance(r->sys, fs, &o, t0 + 1.0);
    break;
  case 6:
    rc = dal_evolve(r->sys, fs, &o, t0 + 1.0, 0.1, NULL, NULL);
    break;
  case 7:
    rc = dal_make_consistent(r->sys, fs, 0.0, NULL);
    break;
  case 8:
    rc = dal_check_constraints(r->sys, fs, NULL);
    break;
  case 9:
    rc = dal_state_set(r->sys, fs, 0.0, buf, buf);
    break;
  default:
    // the other way round: this system's state with the foreign system
    rc = dal_forward(r->fsys, st);
    fz_s(f, st, "foreign forward", rc);
    if (rc != DAL_E_STATE) fz_die("foreign system accepted", rc, dal_state_errmsg(st));
    return;
  }
  fz_s(f, fs, "foreign call", rc);
  if (rc != DAL_E_STATE) fz_die("foreign state accepted", rc, dal_state_errmsg(fs));
  if (dal_state_time(fs) != t0 || dal_state_q(fs)[0] != q0)
    fz_die("foreign state changed", rc, NULL);
}

// two states given the same inputs end bit-identical (pure models only: some callbacks count
// their calls)
static void fz_twins(fz *f, fz_run_ctx *r) {
  dal_state *a = r->st[0], *b = r->st[1];
  int n = r->n;
  static double q[FZ_NQ], qd[FZ_NQ];
  memcpy(q, dal_state_q(a), (size_t)n * sizeof(double));
  memcpy(qd, dal_state_qdot(a), (size_t)n * sizeof(double));
  double t = dal_state_time(a);
  dal_solve_opts o;
  fz_opts(f, &o);
  fz_cap(r, &o);
  int k = fz_pick(f, 20);
  double t1 = t + 1e-3 * (1 + k);
  // the same parameters too (fz_param may have set some on one of them)
  int rp = dal_state_copy_params(r->sys, b, a);
  if (rp && rp != DAL_E_NOMEM) fz_die("copy_params between states of one system", rp, NULL);
  int ra = dal_state_set(r->sys, a, t, q, qd), rb = dal_state_set(r->sys, b, t, q, qd);
  if (ra || rb) fz_die("state_set of a valid state", ra ? ra : rb, NULL);
  ra = fz_s(f, a, "advance (twin a)", dal_advance(r->sys, a, &o, t1));
  rb = fz_s(f, b, "advance (twin b)", dal_advance(r->sys, b, &o, t1));
  if (r->m->impure || rp) return;
  if (ra != rb || dal_state_time(a) != dal_state_time(b) ||
      memcmp(dal_state_q(a), dal_state_q(b), (size_t)n * sizeof(double)) ||
      memcmp(dal_state_qdot(a), dal_state_qdot(b), (size_t)n * sizeof(double)) ||
      strcmp(dal_state_errmsg(a), dal_state_errmsg(b)))
    fz_die("two states of one system given the same inputs differ", ra, dal_state_errmsg(a));
}

// ---------------------------------------------------------------- the newer surfaces
// a per-trajectory parameter set from the bytes: accepted only when finite, normal (and a
// mass positive), then read back exactly; a refused value leaves the state's value
static void fz_param(fz *f, fz_run_ctx *r, dal_state *st) {
  static const char *const names[] = {"mass:0",    "place:0:0",  "place:0:1",  "con:0:0",
                                      "gravity:1", "spring:0:k", "spring:0:L", "damper:0:c"};
  const char *name = names[fz_pick(f, 8)];
  double v;
  if (fz_u8(f) < 128) {
    int k = fz_pick(f, 64);
    v = ((double)k - 16.0) / 16.0;
  } else {
    v = fz_num(f);
  }
  dal_param_ref ref;
  char msg[512];
  double t = dal_state_time(st);
  if (dal_param_find(r->sys, name, &ref, msg, sizeof msg) != DAL_OK) {
    if (!msg[0]) fz_die("param_find failed without a message", 0, name);
    int rc = fz_s(f, st, "set_param_named", dal_state_set_param_named(r->sys, st, name, v));
    if (rc != DAL_E_ARG) fz_die("a parameter that does not exist was set", rc, name);
    return;
  }
  double before = NAN, after = NAN;
  fz_status("state_param", dal_state_param(r->sys, st, &ref, &before));
  int rc = fz_s(f, st, "set_param", dal_state_set_param(r->sys, st, &ref, v));
  fz_status("state_param", dal_state_param(r->sys, st, &ref, &after));
  if (rc == DAL_OK) {
    if (!isfinite(v) || (v != 0.0 && fabs(v) < DBL_MIN))
      fz_die("set_param accepted a non-finite or subnormal value", rc, name);
    if (ref.kind == DAL_PARAM_MASS && !(v > 0)) fz_die("set_param accepted a mass <= 0", rc, name);
    if (after != v) fz_die("an accepted parameter does not read back", rc, name);
  } else {
    if (rc != DAL_E_ARG && rc != DAL_E_NONFINITE && rc != DAL_E_NOMEM)
      fz_die("set_param failed with an unexpected status", rc, dal_state_errmsg(st));
    if (memcmp(&after, &before, sizeof after) != 0)
      fz_die("a refused parameter changed the state's value", rc, name);
  }
  if (dal_state_time(st) != t) fz_die("set_param moved the state's time", rc, name);
  rc = fz_s(f, st, "forward (param)", dal_forward(r->sys, st));
  fz_finite_state(r, st, rc, "forward (param)");
  if (rc == DAL_OK) fz_products(f, r, st, "forward (param)");
}

typedef struct fz_lyap {
  long segments, max_segments;
} fz_lyap;

static int fz_lyap_monitor(double t, const double *e, int p, void *ctx) {
  fz_lyap *l = ctx;
  if (!isfinite(t) || !fz_finite(e, p)) fz_die("lyapunov monitor sees non-finite values", p, NULL);
  if (++l->segments > l->max_segments)
    fz_die("lyapunov: more segments than its span allows", 0, NULL);
  return 0;
}

// equilibrium, normal modes or a short Lyapunov run (small models only)
static void fz_analysis(fz *f, fz_run_ctx *r, dal_state *st) {
  enum { NA = FZ_MAX_COORDS };
  static double w2[NA], shapes[NA * NA], lre[2 * NA], lim[2 * NA], ex[2 * NA], er[2 * NA];
  int which = fz_pick(f, 3), n = r->n, rc;
  if (r->m->chain || n > NA) return;
  if (which == 0) {
    dal_equilibrium_opts o = dal_default_equilibrium_opts();
    o.max_iter = 1 + fz_pick(f, 30);
    if (fz_pick(f, 4) == 3) o.max_step = fz_num(f);
    if (fz_pick(f, 8) == 7) o.xtol = fz_num(f);
    double q0 = 0.0;
    for (int i = 0; i < n; ++i)
      q0 = fmax(q0, fabs(dal_state_q(st)[i]));
    dal_equilibrium_report rep;
    rc = fz_s(f, st, "equilibrium", dal_equilibrium(r->sys, st, &o, &rep));
    fz_finite_state(r, st, rc, "equilibrium");
    if (rc != DAL_OK) return;
    fz_products(f, r, st, "equilibrium");
    double a = 0.0, qm = 0.0;
    for (int i = 0; i < n; ++i) {
      if (dal_state_qdot(st)[i] != 0.0) fz_die("equilibrium: DAL_OK with qdot != 0", rc, NULL);
      a = fmax(a, fabs(dal_state_qddot(st)[i]));
      qm = fmax(qm, fabs(dal_state_q(st)[i]));
    }
    if (!(rep.accel == a) || !isfinite(rep.unsteady) || !isfinite(rep.step) || rep.iterations < 1)
      fz_die("equilibrium: a report that does not match the state", rc, NULL);
    if (!(qm <= 1e4 * (1.0 + q0) * (1.0 + 1e-15)))
      fz_die("equilibrium: DAL_OK outside the neighbourhood of the start", rc, NULL);
  } else if (which == 1) {
    dal_modes md;
    rc = fz_s(f, st, "normal_modes", dal_normal_modes(r->sys, st, w2, shapes, lre, lim, &md));
    fz_finite_state(r, st, rc, "normal_modes");
    if (rc == DAL_OK &&
        (!fz_finite(w2, n) || !fz_finite(shapes, n * n) || !fz_finite(lre, 2 * n) ||
         !fz_finite(lim, 2 * n) || md.verdict < DAL_UNSTABLE || md.verdict > DAL_ASYMPTOTIC))
      fz_die("normal modes: DAL_OK with non-finite values or an unknown verdict", rc, NULL);
  } else {
    dal_lyapunov_opts o = dal_default_lyapunov_opts();
    double t = dal_state_time(st);
    o.t_end = t + 0.02 * (1 + fz_pick(f, 5));
    o.nexp = 1 + fz_pick(f, 2);
    if (o.nexp > 2 * n) o.nexp = 2 * n;
    if (fz_u8(f) < 200) {
      int k = fz_pick(f, 10);
      o.renorm = 0.005 * (1 + k);
    } else {
      o.renorm = fz_num(f);
    }
    if (fz_pick(f, 2)) {
      o.method = DAL_METHOD_RK4;
      if (fz_u8(f) < 200) {
        int k = fz_pick(f, 10);
        o.h = 1e-3 * (1 + k);
      } else {
        o.h = fz_num(f);
      }
    }
    o.max_steps = 2000;
    fz_lyap l = {0, 0};
    double span = o.t_end - t;
    l.max_segments = o.renorm > 0 && isfinite(o.renorm) ? (long)fmin(1e6, span / o.renorm) : 0;
    l.max_segments += o.nblocks + 4;
    rc = fz_s(f, st, "lyapunov", dal_lyapunov(r->sys, st, &o, ex, er, fz_lyap_monitor, &l));
    fz_finite_state(r, st, rc, "lyapunov");
    if (rc == DAL_OK && !fz_finite(ex, o.nexp))
      fz_die("lyapunov: DAL_OK, exponents not finite", rc, NULL);
  }
}

// a sequence of public calls chosen by the bytes, on the two states of the system
static void fz_ops(fz *f, fz_run_ctx *r) {
  int nops = fz_pick(f, 10), cur = 0;
  static double buf[3 * FZ_NQ], q[FZ_NQ], qd[FZ_NQ];
  for (int op = 0; op < nops; ++op) {
    int code = fz_pick(f, 14), rc;
    dal_state *st = r->st[cur];
    switch (code) {
    case 0: // switch state
      cur = fz_pick(f, 2);
      break;
    case 1: { // set near the current point, or anywhere
      int far = fz_pick(f, 4) == 3;
      for (int i = 0; i < r->n; ++i) {
        q[i] = dal_state_q(st)[i];
        qd[i] = dal_state_qdot(st)[i];
      }
      int i = r->n ? fz_pick(f, r->n) : 0;
      double x = far ? fz_num(f) : ((double)fz_pick(f, 64) - 32.0) / 256.0;
      if (r->n) q[i] = far ? x : q[i] + x;
      rc = fz_s(f, st, "state_set", dal_state_set(r->sys, st, dal_state_time(st), q, qd));
      fz_finite_state(r, st, rc, "state_set");
      if (rc == DAL_OK && (dal_state_qddot(st) || dal_state_positions(st)))
        fz_die("products handed out after state_set", rc, NULL);
      break;
    }
    case 2: // forward
      rc = fz_s(f, st, "forward", dal_forward(r->sys, st));
      fz_finite_state(r, st, rc, "forward");
      if (rc == DAL_OK)
        fz_products(f, r, st, "forward");
      else if (dal_state_qddot(st) && rc != DAL_E_NONFINITE)
        fz_die("qddot handed out after a failed forward", rc, dal_state_errmsg(st));
      break;
    case 3:
    case 4:
      fz_integrate(f, r, st);
      break;
    case 5: { // make_consistent
      unsigned c = fz_u8(f);
      double tol = c < 128 ? 0.0 : c < 250 ? 1e-8 * (1 + c % 100) : fz_num(f);
      dal_init_report rep;
      rc = fz_s(f, st, "make_consistent", dal_make_consistent(r->sys, st, tol, &rep));
      fz_finite_state(r, st, rc, "make_consistent");
      if (rc == DAL_OK) {
        fz_products(f, r, st, "make_consistent");
        if (r->mc > 0) {
          const double *phi = dal_state_phi(st);
          for (int i = 0; i < r->mc; ++i)
            if (!(fabs(phi[i]) <= rep.tol)) fz_die("make_consistent left |phi| > tol", rc, NULL);
        }
      }
      break;
    }
    case 6: { // check_constraints
      dal_constraint_report rep;
      rc = fz_s(f, st, "check_constraints", dal_check_constraints(r->sys, st, &rep));
      fz_finite_state(r, st, rc, "check_constraints");
      if (rc == DAL_OK && !(rep.rank == r->mc || rep.rank == -1))
        fz_die("check_constraints OK with a rank below m", rep.rank, NULL);
      if (rc == DAL_E_CONSTRAINT && !(rep.rank >= 0 && rep.rank < r->mc && rep.ndependent >= 1))
        fz_die("check_constraints failed with full rank", rep.rank, NULL);
      break;
    }
    case 7: { // constraint forces: only on an evaluated state, finite then
      int r1 = fz_s(f, st, "constraint_forces", dal_constraint_forces(r->sys, st, buf));
      if (r1 == DAL_OK && !fz_finite(buf, r->N * r->d)) fz_die("constraint forces", r1, NULL);
      int r2 = fz_s(f, st, "constraint_genforces", dal_constraint_genforces(r->sys, st, buf));
      if (r2 == DAL_OK && !fz_finite(buf, r->n)) fz_die("generalized constraint forces", r2, NULL);
      if ((r1 == DAL_OK) != (r2 == DAL_OK) || (r1 && r1 != DAL_E_STATE))
        fz_die("constraint forces and genforces disagree", r1, dal_state_errmsg(st));
      break;
    }
    case 8: { // accessors: all or none of an evaluation's products
      if (dal_state_qddot(st)) fz_products(f, r, st, "accessors");
      int k = fz_pick(f, r->N + 2) - 1;
      rc = fz_s(f, st, "state_jacobian", dal_state_jacobian(r->sys, st, k, buf));
      if (rc == DAL_OK && !fz_finite(buf, r->d * r->n)) fz_die("jacobian", rc, NULL);
      if (rc == DAL_OK && !dal_state_positions(st)) fz_die("jacobian without kinematics", rc, NULL);
      break;
    }
    case 9: { // the CSV monitor called directly
      if (!r->devnull) r->devnull = fopen("/dev/null", "w");
      if (!r->devnull) break;
      dal_csv csv = {r->devnull, 0, fz_pick(f, 2), NULL};
      dal_energies e;
      int evaluated = dal_state_energies(st, &e) != DAL_E_STATE;
      rc = fz_s(f, st, "csv_monitor", dal_csv_monitor(r->sys, st, &csv));
      if ((rc == DAL_OK) != evaluated) fz_die("csv monitor on an unevaluated state", rc, NULL);
      break;
    }
    case 10:
      fz_foreign(f, r, st);
      break;
    case 12:
      fz_param(f, r, st);
      break;
    case 13:
      fz_analysis(f, r, st);
      break;
    default:
      fz_twins(f, r);
      break;
    }
  }
}

// a small foreign system: a planar pendulum
static int fz_foreign_make(dal_builder **b, dal_system **sys, dal_state **st) {
  int th, bob;
  double par[7] = {1.0, 0, 0, 0, 0, 0, 0}, q = 0.1, qd = 0.0;
  int rc = dal_builder_create(2, b);
  if (!rc) rc = dal_builder_add_coord(*b, "theta", &th);
  if (!rc) rc = dal_builder_add_particle(*b, "bob", 1.0, &bob);
  if (!rc) rc = fz_place_def(*b, bob, &dal_map_pendulum, -1, 1, &th, 7, par, NULL);
  if (!rc) rc = dal_builder_compile(*b, sys);
  if (!rc) rc = dal_state_create(*sys, st);
  if (!rc) rc = dal_state_set(*sys, *st, 0.0, &q, &qd);
  return rc;
}

static void fz_run(fz *f, const dal_system *sys, fz_model *m) {
  fz_run_ctx r;
  memset(&r, 0, sizeof r);
  r.sys = sys;
  r.m = m;
  r.n = m->n;
  r.N = dal_system_nparticles(sys);
  r.d = m->dim;
  r.mc = dal_system_nconstraints(sys);
  r.lag = r.N == 0;
  int rc = dal_state_create(sys, &r.st[0]);
  fz_status("state_create", rc);
  if (rc) return;
  dal_state *st = r.st[0];
  int n = m->n;
  static double q[FZ_NQ], qd[FZ_NQ];
  if (m->chain) {
    fz_chain_state(f, m, q, qd);
  } else {
    for (int i = 0; i < n; ++i) {
      if (fz_u8(f) < 230) {
        int k = fz_pick(f, 64);
        q[i] = ((double)k - 32.0) / 16.0;
      } else {
        q[i] = fz_num(f);
      }
      if (fz_u8(f) < 230) {
        int k = fz_pick(f, 64);
        qd[i] = ((double)k - 32.0) / 32.0;
      } else {
        qd[i] = fz_num(f);
      }
    }
  }
  double t0 = fz_u8(f) < 230 ? 0.0 : fz_num(f);
  rc = fz_s(f, st, "state_set", dal_state_set(sys, st, t0, q, qd));
  if (rc) {
    for (int i = 0; i < n; ++i)
      q[i] = 0.1 * (i + 1), qd[i] = 0.0;
    t0 = 0.0;
    fz_s(f, st, "state_set", dal_state_set(sys, st, t0, q, qd));
  }
  rc = fz_s(f, st, "forward", dal_forward(sys, st));
  fz_finite_state(&r, st, rc, "forward");
  if (rc == DAL_OK) fz_products(f, &r, st, "forward");
  static double J[3 * FZ_NQ];
  int k = fz_pick(f, 8) - 1;
  fz_status("state_jacobian", dal_state_jacobian(sys, st, k, J));
  dal_energies en;
  fz_status("state_energies", dal_state_energies(st, &en));

  // a Lagrange residual along a simple path
  if (fz_pick(f, 4) == 0) {
    static fz_path_ctx pc;
    pc.n = n;
    pc.w = fz_num(f);
    for (int i = 0; i < n; ++i)
      pc.a[i] = q[i];
    static double res[FZ_NQ];
    double t = fz_num(f);
    rc = fz_s(f, st, "lagrange_residual", dal_lagrange_residual(sys, st, fz_qpath, t, res, &pc));
    if (rc == DAL_OK && !fz_finite(res, n)) fz_die("lagrange residual not finite", rc, NULL);
    fz_s(f, st, "state_set", dal_state_set(sys, st, t0, q, qd));
  }

  // short integrations with random options; the state must survive every failure
  int nrun = 1 + fz_pick(f, 3);
  for (int i = 0; i < nrun; ++i)
    fz_integrate(f, &r, st);
  // the state is reusable: reset it to where it is and evaluate again
  double tn = dal_state_time(st);
  memcpy(q, dal_state_q(st), (size_t)n * sizeof(double));
  memcpy(qd, dal_state_qdot(st), (size_t)n * sizeof(double));
  fz_s(f, st, "state_set (again)", dal_state_set(sys, st, tn, q, qd));
  rc = fz_s(f, st, "forward (again)", dal_forward(sys, st));
  if (rc == DAL_OK) fz_products(f, &r, st, "forward (again)");

  // the whole API on a second state of the system and against a foreign one
  dal_builder *fb = NULL;
  dal_system *fsys = NULL;
  rc = dal_state_create(sys, &r.st[1]);
  fz_status("state_create (second)", rc);
  if (!rc) rc = dal_state_set(sys, r.st[1], tn, q, qd);
  if (!rc && fz_foreign_make(&fb, &fsys, &r.fst) == DAL_OK) {
    r.fsys = fsys;
    fz_ops(f, &r);
  }
  // the digest of where the states ended
  for (int s = 0; s < 2 && r.st[s]; ++s) {
    double t = dal_state_time(r.st[s]);
    fz_hash(f, &t, sizeof t);
    fz_hash(f, dal_state_q(r.st[s]), (size_t)n * sizeof(double));
    fz_hash(f, dal_state_qdot(r.st[s]), (size_t)n * sizeof(double));
  }
  if (r.devnull) fclose(r.devnull);
  dal_state_destroy(r.fst);
  dal_system_destroy(fsys);
  dal_builder_destroy(fb);
  dal_state_destroy(r.st[1]);
  dal_state_destroy(st);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fz f = {data, size, 0, 14695981039346656037ULL};
  static fz_model m; // large (callback contexts); reset for every input
  memset(&m, 0, sizeof m);
  dal_builder *b = NULL;
  dal_system *sys = fz_build(&f, &m, &b);
  // the compiled system does not depend on its builder
  if (fz_pick(&f, 2)) {
    dal_builder_destroy(b);
    b = NULL;
  }
  if (sys) fz_run(&f, sys, &m);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
  if (getenv("FZ_DIGEST")) printf("fz-digest %016llx\n", (unsigned long long)f.digest);
  return 0;
}
