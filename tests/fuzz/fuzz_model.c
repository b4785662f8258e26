// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// libFuzzer target: random models built through the public API must never crash or leak.
//
// The fuzz bytes drive everything: dimension, coordinates (<= 12), particles (<= 6), their
// placements by registry primitives or small user primitives (with wrong counts and indices
// now and then), constraints, springs, dampers, gravity, user callbacks that return NaN or
// error codes, parameters including NaN, inf, 0, huge and tiny values, then compile, set a
// state, forward, a Lagrange residual, and a short bounded advance/evolve with random
// method, formulation and tolerances. Invariants checked after every call (a violation
// aborts, which is how a fuzz target reports a finding):
//   - every status is one of DAL_STATUS_LIST (0 or a listed negative code);
//   - every failure of a builder or state call leaves a non-empty error message;
//   - after advance/evolve the state's t, q, qdot are finite and t lies in [t0, t1]
//     (t == t1 on success): a failure keeps the last accepted step;
//   - a failed state can be reset and evaluated again.
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dalembert/dalembert.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define FZ_MAX_COORDS 12
#define FZ_MAX_PARTS 6
#define FZ_MAX_PARAM 8

// ---------------------------------------------------------------- byte reader
typedef struct fz {
  const uint8_t *p;
  size_t n, i;
} fz;

static unsigned fz_u8(fz *f) { return f->i < f->n ? f->p[f->i++] : 0u; }

// uniform-ish integer in [0, k)
static int fz_pick(fz *f, int k) { return k > 0 ? (int)(fz_u8(f) % (unsigned)k) : 0; }

// a real number: mostly moderate, sometimes special (NaN, inf, 0, huge, tiny) or raw bits
static double fz_num(fz *f) {
  static const double pal[] = {0.0,     -0.0,    1.0,    -1.0,     0.5,    2.0,    10.0,
                               1e-3,    1e-8,    1e-12,  1e-300,   1e300,  -1e300, DBL_MAX,
                               DBL_MIN, 4.9e-324, NAN,   INFINITY, -INFINITY, 3.141592653589793,
                               1.5707963267948966, 1e6, -1e6,     1e-100};
  unsigned c = fz_u8(f);
  if (c < 176) return ((double)c - 88.0) / 16.0; // -5.5 .. 5.4375
  c -= 176;
  if (c < sizeof pal / sizeof pal[0]) return pal[c];
  uint64_t bits = 0;
  for (int k = 0; k < 8; ++k) bits = (bits << 8) | fz_u8(f);
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

// ---------------------------------------------------------------- invariants
// FZ_TRACE=1 in the environment prints each stage's status (to see what inputs reach)
static void fz_trace(const char *stage, int rc, const char *msg) {
  static int on = -1; // read once; the value never changes during a run
  if (on < 0) on = getenv("FZ_TRACE") != NULL;
  if (on) fprintf(stderr, "fz %-8s %-18s %.400s\n", stage, dal_status_name(rc), msg ? msg : "");
}

static void fz_die(const char *what, int rc, const char *msg) {
  fprintf(stderr, "fuzz_model: invariant violated: %s (status %d %s) msg='%s'\n", what, rc,
          dal_status_name(rc), msg ? msg : "");
  abort();
}

static void fz_status(const char *call, int rc) {
  // DAL_STOPPED (> 0) is evolve's status for a monitor that asked to stop
  if ((rc > 0 && (rc != DAL_STOPPED || strcmp(call, "evolve") != 0)) ||
      strcmp(dal_status_name(rc), "DAL_UNKNOWN") == 0)
    fz_die(call, rc, NULL);
}

static int fz_b(const dal_builder *b, const char *call, int rc) {
  fz_status(call, rc);
  if (rc && b && !dal_builder_errmsg(b)[0]) fz_die(call, rc, "(empty builder message)");
  return rc;
}

static int fz_s(const dal_state *st, const char *call, int rc) {
  fz_status(call, rc);
  if (rc && st && !dal_state_errmsg(st)[0]) fz_die(call, rc, "(empty state message)");
  return rc;
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
  for (int i = 0; i < c->n; ++i) Q[i] += fz_mode_val(c, -c->scale * sin(q[i]) - qdot[i] * t);
  return rc;
}

static int fz_pot_r(const dal_jet *r, dal_jet t, dal_jet *U, void *ctx) {
  fz_cb *c = ctx;
  int rc = fz_mode_rc(c);
  // an attracting point at the origin, ~ 1/|r|, plus a weak time-dependent field
  dal_jet s = dal_const(0.0);
  for (int i = 0; i < c->N * c->d; ++i) s = dal_add(s, dal_sq(r[i]));
  dal_jet inv = dal_div(dal_const(-c->scale), dal_sqrt(dal_addc(s, 1e-3)));
  *U = dal_add(inv, dal_scale(dal_sin(t), 0.01));
  if (c->mode == 1 && c->calls > 1) *U = dal_sqrt(dal_const(-1.0));
  return rc;
}

static int fz_pot_q(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  fz_cb *c = ctx;
  int rc = fz_mode_rc(c);
  dal_jet s = dal_const(0.0);
  for (int i = 0; i < c->n; ++i) s = dal_add(s, dal_cos(q[i]));
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
    {.name = "u_circle2", .version = 1, .nin = 2, .nout = 1, .nparam = 1, .eval = u_circle2,
     .doc = "x^2 + y^2 - R^2", .flags = 0},
    {.name = "u_dist2", .version = 1, .nin = 4, .nout = 1, .nparam = 1, .eval = u_dist2,
     .doc = "|b - a| - L (2D)", .flags = 0},
    {.name = "u_dist3", .version = 1, .nin = 6, .nout = 1, .nparam = 1, .eval = u_dist3,
     .doc = "|b - a| - L (3D)", .flags = 0},
    {.name = "u_lin", .version = 1, .nin = 1, .nout = 1, .nparam = 2, .eval = u_lin,
     .doc = "a u - b sin t", .flags = 0},
    {.name = "u_pair", .version = 1, .nin = 2, .nout = 2, .nparam = 0, .eval = u_pair,
     .doc = "(u0 - u1, u0 + sin u1)", .flags = 0},
    {.name = "u_callback", .version = 1, .nin = 1, .nout = 2, .nparam = 0, .eval = u_callback,
     .doc = "(u^2 + ct, sin u), may fail", .flags = 0},
    {.name = "u_broken", .version = 1, .nin = 1, .nout = 2, .nparam = 0, .eval = NULL,
     .doc = "no eval function", .flags = 0},
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
  int next_coord; // next coordinate handed out by fz_coords
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
  c->scale = fz_u8(f) < 200 ? 0.5 + fz_pick(f, 8) : fz_num(f);
  c->calls = 0;
  c->d = m->dim;
  c->N = m->N;
  c->n = m->n;
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
  if (!prim || fz_pick(f, 8) == 7) return NULL;
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
    if (m->n == 0) out[i] = c < 30 ? 0 : -1;
    else if (c < 24) out[i] = m->next_coord++ % m->n;
    else out[i] = c < 30 ? c % m->n : (c == 30 ? -1 : m->n + 3);
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
static void fz_place(fz *f, dal_builder *b, fz_model *m, int k) {
  const dal_primitive *prim = fz_map_prim(f, m->dim);
  int parent = -1;
  if (k > 0 && fz_pick(f, 3) == 2) parent = fz_pick(f, k + 1) - (fz_pick(f, 8) == 7);
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
  int rc = dal_builder_place(b, pk, prim, parent, nc, fz_pick(f, 20) != 19 ? coords : NULL, np,
                             fz_pick(f, 20) != 19 ? par : NULL, ctx);
  fz_b(b, "place", rc);
  if (!rc && pk == k) m->placed[k] = 1;
  // mostly fall back to a valid placement so that the model compiles
  if (!m->placed[k] && fz_pick(f, 8) && m->n > 0) {
    int d = m->dim, cc[3];
    for (int a = 0; a < d; ++a) cc[a] = (k * d + a) % m->n;
    rc = dal_builder_place(b, k, d == 2 ? &dal_map_cartesian2 : &dal_map_cartesian3, -1, d,
                           cc, 0, NULL, NULL);
    fz_b(b, "place (fallback)", rc);
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
  int rc = dal_builder_add_constraint(b, fz_pick(f, 8) ? name : NULL, prim, nparts, parts, nc,
                                      coords, np, par, fz_ctx(f, m, prim), &row);
  fz_b(b, "add_constraint", rc);
}

// build the model from the bytes; returns a compiled system or NULL
static dal_system *fz_build(fz *f, fz_model *m, dal_builder **bout) {
  int dim = 2 + fz_pick(f, 2);
  if (fz_pick(f, 64) == 63) dim = fz_pick(f, 5); // invalid dimension now and then
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
    fz_b(b, "add_coord", dal_builder_add_coord(b, fz_pick(f, 4) ? name : NULL, &idx));
  }
  if (kind == 14) {
    fz_cb *c = fz_new_cb(f, m);
    c->n = m->n;
    fz_b(b, "set_lagrangian", dal_builder_set_lagrangian(b, fz_lagr, c));
  }
  m->N = nparts;
  for (int k = 0; k < m->N; ++k) {
    char name[16];
    snprintf(name, sizeof name, "p%d", k);
    int idx = -1;
    double mass = fz_pos(f, 1.0);
    if (fz_b(b, "add_particle", dal_builder_add_particle(b, name, mass, &idx))) {
      // a rejected particle: add a sane one so indices stay aligned
      fz_b(b, "add_particle", dal_builder_add_particle(b, name, 1.0, &idx));
    }
  }
  if (kind == 15 && m->N > 0) {
    fz_cb *c = fz_new_cb(f, m);
    c->N = m->N;
    c->n = m->n;
    fz_b(b, "set_map", dal_builder_set_map(b, fz_map, c));
  } else {
    for (int k = 0; k < m->N; ++k)
      if (fz_pick(f, 32) != 31) fz_place(f, b, m, k);
  }
  int ncon = fz_pick(f, 4);
  for (int i = 0; i < ncon; ++i) fz_constraint(f, b, m, i);
  // forces
  int nforce = fz_pick(f, 6);
  for (int i = 0; i < nforce; ++i) {
    int what = fz_pick(f, 9);
    double x0[3] = {fz_num(f), fz_num(f), fz_num(f)};
    int pa = m->N ? fz_pick(f, m->N + 1) : 0, pb = m->N ? fz_pick(f, m->N + 1) : 0;
    fz_cb *c = NULL;
    if (what >= 4) {
      c = fz_new_cb(f, m);
      c->N = m->N;
      c->n = m->n;
    }
    switch (what) {
    case 0: {
      double g[3] = {fz_num(f), fz_num(f), fz_num(f)};
      fz_b(b, "set_gravity", dal_builder_set_gravity(b, g));
      break;
    }
    case 1:
      fz_b(b, "add_spring", dal_builder_add_spring(b, pa, pb, fz_pos(f, 10.0), fz_pos(f, 1.0)));
      break;
    case 2:
      fz_b(b, "add_damper", dal_builder_add_damper(b, pa, pb, fz_pos(f, 0.5)));
      break;
    case 3:
      fz_b(b, "add_anchor_spring",
           dal_builder_add_anchor_spring(b, pa, fz_pick(f, 8) != 7 ? x0 : NULL, NULL, NULL,
                                         fz_pos(f, 5.0), fz_pos(f, 0.5)));
      break;
    case 4:
      fz_b(b, "add_anchor_damper",
           dal_builder_add_anchor_damper(b, pa, x0, fz_pick(f, 2) ? fz_path : NULL, c,
                                         fz_pos(f, 0.5)));
      break;
    case 5:
      fz_b(b, "add_force", dal_builder_add_force(b, fz_pick(f, 16) != 15 ? fz_force : NULL, c));
      break;
    case 6:
      fz_b(b, "add_genforce", dal_builder_add_genforce(b, fz_genforce, c));
      break;
    case 7:
      fz_b(b, "add_potential_r", dal_builder_add_potential_r(b, fz_pot_r, c));
      break;
    default:
      fz_b(b, "add_potential_q", dal_builder_add_potential_q(b, fz_pot_q, c));
      break;
    }
  }
  dal_system *sys = NULL;
  rc = fz_b(b, "compile", dal_builder_compile(b, &sys));
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
  }
  return sys;
}

// ---------------------------------------------------------------- solving
typedef struct fz_path_ctx {
  int n;
  double a[FZ_MAX_COORDS], w;
} fz_path_ctx;

static int fz_qpath(dal_jet t, dal_jet *q, void *ctx) {
  const fz_path_ctx *p = ctx;
  for (int i = 0; i < p->n; ++i) q[i] = dal_addc(dal_scale(dal_sin(dal_scale(t, p->w)), 0.1),
                                                  p->a[i]);
  return 0;
}

typedef struct fz_mon {
  double t0, t1;
  int calls, stop_at, stopped;
} fz_mon;

static int fz_monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  fz_mon *mo = ctx;
  double t = dal_state_time(st);
  if (!(t >= mo->t0 && t <= mo->t1)) fz_die("monitor time outside [t0, t1]", 0, NULL);
  const double *q = dal_state_q(st);
  for (int i = 0; i < dal_system_ncoords(sys); ++i)
    if (!isfinite(q[i])) fz_die("monitor sees a non-finite q", 0, NULL);
  // stop at the chosen call (alternately as success or as failure), and after 64 calls
  // whatever dt was (a tiny dt means countless output times)
  if (++mo->calls != mo->stop_at && mo->calls < 64) return 0;
  mo->stopped = 1;
  return mo->calls % 2 || mo->calls >= 64 ? 1 : -1;
}

static void fz_opts(fz *f, dal_solve_opts *o) {
  dal_solve_default_opts(o);
  o->method = (dal_method)fz_pick(f, 7);
  o->form = (dal_formulation)fz_pick(f, 5);
  o->linsol = (dal_linsol)fz_pick(f, 3);
  if (fz_pick(f, 32) == 31) o->method = (dal_method)(7 + fz_pick(f, 3));
  if (fz_pick(f, 32) == 31) o->form = (dal_formulation)(5 + fz_pick(f, 3));
  o->rtol = fz_u8(f) < 220 ? pow(10.0, -2.0 - fz_pick(f, 11)) : fz_num(f);
  o->atol = fz_u8(f) < 220 ? pow(10.0, -3.0 - fz_pick(f, 11)) : fz_num(f);
  if (fz_pick(f, 8) == 7) o->h0 = fz_u8(f) < 128 ? 1e-4 : fz_num(f);
  if (fz_pick(f, 8) == 7) o->hmin = fz_u8(f) < 128 ? 1e-12 : fz_num(f);
  if (fz_pick(f, 8) == 7) o->hmax = fz_u8(f) < 128 ? 1e-2 : fz_num(f);
  o->fixed_step = fz_u8(f) < 220 ? 1e-3 * (1 + fz_pick(f, 10)) : fz_num(f);
  o->max_steps = 1 + fz_pick(f, 200);
  if (fz_pick(f, 32) == 31) o->max_steps = -fz_pick(f, 3);
  if (fz_pick(f, 4) == 3) {
    o->baumgarte_alpha = fz_u8(f) < 200 ? fz_pick(f, 20) : fz_num(f);
    o->baumgarte_beta = fz_u8(f) < 200 ? fz_pick(f, 20) : fz_num(f);
  }
  o->project = fz_pick(f, 2);
  o->sparse_threshold = fz_pick(f, 2) ? 200 : fz_pick(f, 40);
}

// the state must hold finite values at a time in [t0, t1]
static void fz_check_state(const dal_system *sys, const dal_state *st, double t0, double t1,
                           int rc, const char *call) {
  double t = dal_state_time(st);
  if (!isfinite(t)) fz_die("state time is not finite after a step", rc, dal_state_errmsg(st));
  if (isfinite(t1) && t1 >= t0 && !(t >= t0 && t <= t1))
    fz_die("state time left [t0, t1]", rc, dal_state_errmsg(st));
  if (rc == DAL_OK && isfinite(t1) && t1 >= t0 && t != t1)
    fz_die(call, rc, "success but the state is not at t1");
  const double *q = dal_state_q(st), *qd = dal_state_qdot(st);
  for (int i = 0; i < dal_system_ncoords(sys); ++i)
    if (!isfinite(q[i]) || !isfinite(qd[i]))
      fz_die("non-finite q or qdot kept after a step", rc, dal_state_errmsg(st));
}

static void fz_run(fz *f, const dal_system *sys, fz_model *m) {
  dal_state *st = NULL;
  int rc = dal_state_create(sys, &st);
  fz_status("state_create", rc);
  if (rc) return;
  int n = m->n;
  double q[FZ_MAX_COORDS], qd[FZ_MAX_COORDS];
  for (int i = 0; i < n; ++i) {
    q[i] = fz_u8(f) < 230 ? ((double)fz_pick(f, 64) - 32.0) / 16.0 : fz_num(f);
    qd[i] = fz_u8(f) < 230 ? ((double)fz_pick(f, 64) - 32.0) / 32.0 : fz_num(f);
  }
  double t0 = fz_u8(f) < 230 ? 0.0 : fz_num(f);
  rc = fz_s(st, "state_set", dal_state_set(sys, st, t0, q, qd));
  if (rc) {
    for (int i = 0; i < n; ++i) q[i] = 0.1 * (i + 1), qd[i] = 0.0;
    t0 = 0.0;
    fz_s(st, "state_set", dal_state_set(sys, st, t0, q, qd));
  }
  rc = fz_s(st, "forward", dal_forward(sys, st));
  fz_trace("forward", rc, dal_state_errmsg(st));
  double J[3 * FZ_MAX_COORDS];
  fz_status("state_jacobian", dal_state_jacobian(sys, st, fz_pick(f, 8) - 1, J));
  dal_energies en;
  fz_status("state_energies", dal_state_energies(st, &en));

  // a Lagrange residual along a simple path
  if (fz_pick(f, 4) == 0) {
    fz_path_ctx pc = {.n = n, .w = fz_num(f)};
    for (int i = 0; i < n; ++i) pc.a[i] = q[i];
    double res[FZ_MAX_COORDS];
    fz_s(st, "lagrange_residual", dal_lagrange_residual(sys, st, fz_qpath, fz_num(f), res, &pc));
    fz_s(st, "state_set", dal_state_set(sys, st, t0, q, qd));
  }

  // short integrations with random options; the state must survive every failure
  int nrun = 1 + fz_pick(f, 3);
  for (int r = 0; r < nrun; ++r) {
    dal_solve_opts o;
    fz_opts(f, &o);
    double ta = dal_state_time(st);
    double hz = fz_u8(f) < 230 ? 1e-3 * (1 + fz_pick(f, 50)) : fz_num(f);
    double t1 = ta + hz;
    if (fz_pick(f, 3) == 0) {
      fz_mon mo = {ta, t1, 0, fz_pick(f, 6), 0};
      double dt = fz_u8(f) < 230 ? hz / (1 + fz_pick(f, 8)) : fz_num(f);
      rc = fz_s(st, "evolve", dal_evolve(sys, st, &o, t1, dt, fz_monitor, &mo));
      fz_trace("evolve", rc, dal_state_errmsg(st));
      if (rc == DAL_STOPPED && !mo.stopped) fz_die("DAL_STOPPED without a monitor stop", rc, NULL);
      // a monitor that stopped the run early leaves the state before t1
      fz_check_state(sys, st, ta, mo.stopped ? NAN : t1, rc, "evolve");
      if (rc == DAL_OK && mo.calls < 1 && isfinite(t1) && t1 >= ta)
        fz_die("evolve succeeded without calling the monitor", rc, NULL);
    } else {
      rc = fz_s(st, "advance", dal_advance(sys, st, &o, t1));
      fz_trace("advance", rc, dal_state_errmsg(st));
      fz_check_state(sys, st, ta, t1, rc, "advance");
    }
    dal_stats stats;
    fz_status("state_stats", dal_state_stats(st, &stats));
  }
  // the state is reusable: reset it to where it is and evaluate again
  double tn = dal_state_time(st);
  memcpy(q, dal_state_q(st), (size_t)n * sizeof(double));
  memcpy(qd, dal_state_qdot(st), (size_t)n * sizeof(double));
  fz_s(st, "state_set (again)", dal_state_set(sys, st, tn, q, qd));
  fz_s(st, "forward (again)", dal_forward(sys, st));
  dal_state_destroy(st);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fz f = {data, size, 0};
  fz_model m;
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
  return 0;
}
