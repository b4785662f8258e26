// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Every registered primitive (maps and constraints) against central finite differences.
//
// One loop over the registry (dal_primitive_count/get), so primitives added later are covered
// without touching this file (unless they need a context it does not know: then it fails and
// says so). At random inputs u, parameters and times t, with exact-in-double curve arguments:
//  1. prim->eval directly: the Jacobian columns (inputs along e_i), the time derivatives
//     (t along 1), and first and second derivatives along a random direction (w, 1) with input
//     curvature z (the curvature term gamma) match central differences of the value function
//     to their estimated error (fd.h); constant inputs give zero derivatives.
//  2. through a system, for every primitive with 2 or 3 outputs placed as a map (all inputs as
//     coordinates, and again with its first d inputs from a curved parent particle):
//     dal_state_jacobian, dal_state_gamma, dal_state_drdt, positions, velocities and
//     accelerations match finite differences of the composite position r(q, t);
//  3. through a system, every primitive as a constraint (inputs from curved particles, then
//     coordinates): phi, phidot = G qdot + dphi/dt, and G qddot + gamma_phi = 0 along the
//     computed motion, against finite differences of phi(q, t).
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "fd.h"

#define MAXIO 16
#define NSAMPLE 12
#define ULPS 64.0  // rounding of one primitive value, in ulps of SCALE
#define SCALE 10.0 // size of intermediate quantities (inputs, parameters and outputs are O(1))

static unsigned long long seed = 0x853c49e6748fea9bULL;
static double grid(double lo, double hi, int bits) {
  return fd_grid(check_rand(&seed, lo, hi), bits);
}

// ---------------------------------------------------------------------------------------------
// contexts for primitives that take one: a moving curve, a moving point, a drive
static int curve2_fn(dal_jet s, dal_jet t, dal_jet *p, void *ctx) {
  (void)ctx;
  p[0] = dal_add(dal_cos(s), dal_scale(dal_mul(dal_sin(t), s), 0.3));
  p[1] = dal_add(dal_sin(dal_scale(s, 2.0)), dal_scale(dal_mul(t, dal_sq(s)), 0.2));
  return 0;
}
static int curve3_fn(dal_jet s, dal_jet t, dal_jet *p, void *ctx) {
  curve2_fn(s, t, p, ctx);
  p[2] = dal_scale(dal_mul(s, dal_cos(t)), 0.5);
  return 0;
}
static int motion2_fn(dal_jet t, dal_jet *x, void *ctx) {
  (void)ctx;
  x[0] = dal_scale(dal_cos(dal_scale(t, 1.3)), 0.3);
  x[1] = dal_scale(dal_sin(dal_scale(t, 0.7)), 0.2);
  return 0;
}
static int motion3_fn(dal_jet t, dal_jet *x, void *ctx) {
  motion2_fn(t, x, ctx);
  x[2] = dal_scale(dal_sq(t), 0.1);
  return 0;
}
static int drive_fn(dal_jet t, dal_jet *f, void *ctx) {
  (void)ctx;
  *f = dal_add(dal_scale(dal_sin(dal_scale(t, 1.1)), 0.4), dal_scale(dal_sq(t), 0.05));
  return 0;
}

static dal_curve ctx_curve2 = {curve2_fn, NULL}, ctx_curve3 = {curve3_fn, NULL};
static dal_moving_point ctx_motion2 = {motion2_fn, NULL}, ctx_motion3 = {motion3_fn, NULL};
static dal_prescribed ctx_drive = {drive_fn, NULL};

// the context this test knows for a primitive (NULL if none)
static void *known_ctx(const dal_primitive *p) {
  static const struct {
    const char *name;
    void *ctx;
  } table[] = {{"curve2", &ctx_curve2},
               {"curve3", &ctx_curve3},
               {"anchor2", &ctx_motion2},
               {"anchor3", &ctx_motion3},
               {"prescribed", &ctx_drive}};
  for (size_t i = 0; i < sizeof table / sizeof table[0]; ++i)
    if (strcmp(p->name, table[i].name) == 0) return table[i].ctx;
  return NULL;
}

// ---------------------------------------------------------------------------------------------
// 1. the primitive's eval directly

// one evaluation point: u (nin), param, t, and a curve (u + s w + s^2/2 z, t + s dt)
typedef struct point {
  const dal_primitive *prim;
  void *ctx;
  double u[MAXIO], w[MAXIO], z[MAXIO], param[MAXIO], t, dt;
  int out; // output component for fd_fn
} point;

// evaluate with jets along (w, dt) with input curvature z; rc of eval or -99 if non-finite
static int eval_jet(const point *P, const double *w, const double *z, double dt, dal_jet *out) {
  dal_jet in[MAXIO];
  for (int i = 0; i < P->prim->nin; ++i)
    in[i] = dal_jet_make(P->u[i], w[i], z[i]);
  int rc = P->prim->eval(in, dal_jet_make(P->t, dt, 0.0), P->param, out, P->ctx);
  if (rc) return rc;
  for (int a = 0; a < P->prim->nout; ++a)
    if (!dal_jet_isfinite(out[a])) return -99;
  return 0;
}

// value of output P->out along the curve (u + s w + s^2/2 z, t + s dt)
static double value_along(double s, const void *ctx) {
  const point *P = ctx;
  dal_jet in[MAXIO], out[MAXIO];
  for (int i = 0; i < P->prim->nin; ++i)
    in[i] = dal_const(P->u[i] + P->w[i] * s + 0.5 * P->z[i] * (s * s));
  if (P->prim->eval(in, dal_const(P->t + P->dt * s), P->param, out, P->ctx)) return NAN;
  return out[P->out].v;
}

// compare a jet's d and dd with FD along the point's curve, for every output
static int fd_compare(const char *what, point *P, const dal_jet *jet, int check_dd) {
  int ok = 1;
  for (int a = 0; a < P->prim->nout; ++a) {
    P->out = a;
    fd_est e = fd_estimate(value_along, P, ULPS, SCALE);
    CHECK_MSG(e.valid, "%s '%s' output %d: FD bound not available", what, P->prim->name, a);
    if (!e.valid) continue;
    double d1 = fabs(jet[a].d - e.d1), d2 = fabs(jet[a].dd - e.d2);
    CHECK_MSG(d1 <= e.tol1, "%s '%s' output %d: first derivative %.17g vs FD %.17g (tol %g)", what,
              P->prim->name, a, jet[a].d, e.d1, e.tol1);
    if (check_dd)
      CHECK_MSG(d2 <= e.tol2, "%s '%s' output %d: second derivative %.17g vs FD %.17g (tol %g)",
                what, P->prim->name, a, jet[a].dd, e.d2, e.tol2);
    ok &= d1 <= e.tol1 && (!check_dd || d2 <= e.tol2);
  }
  return ok;
}

// random point where the primitive evaluates finitely along every direction used; 0 if none
static int random_point(point *P) {
  const dal_primitive *p = P->prim;
  for (int tries = 0; tries < 50; ++tries) {
    for (int i = 0; i < p->nin; ++i) {
      P->u[i] = grid(-1.5, 1.5, 20);
      P->w[i] = grid(-1, 1, 10);
      P->z[i] = grid(-1, 1, 10);
    }
    for (int i = 0; i < p->nparam; ++i)
      P->param[i] = check_rand(&seed, 0.5, 1.5);
    P->t = grid(-3, 3, 20);
    dal_jet out[MAXIO];
    if (eval_jet(P, P->w, P->z, 1.0, out) == 0) return 1;
  }
  return 0;
}

static void test_eval(const dal_primitive *p, void *ctx, const char *ctxname) {
  int f0 = check_failures, n = 0;
  point P;
  memset(&P, 0, sizeof P);
  P.prim = p;
  P.ctx = ctx;
  for (int it = 0; it < NSAMPLE; ++it) {
    if (!random_point(&P)) break;
    ++n;
    dal_jet out[MAXIO];
    double zero[MAXIO] = {0}, w[MAXIO], z[MAXIO];
    memcpy(w, P.w, sizeof w);
    memcpy(z, P.z, sizeof z);
    // constant inputs and time: zero derivatives
    CHECK_OK(eval_jet(&P, zero, zero, 0.0, out));
    for (int a = 0; a < p->nout; ++a)
      CHECK_MSG(out[a].d == 0 && out[a].dd == 0, "'%s': constant inputs give (d, dd) = (%g, %g)",
                p->name, out[a].d, out[a].dd);
    // Jacobian columns: input i along e_i (and its second derivative)
    double J[MAXIO][MAXIO], Jt[MAXIO];
    for (int i = 0; i < p->nin; ++i) {
      double e[MAXIO] = {0};
      e[i] = 1.0;
      CHECK_OK(eval_jet(&P, e, zero, 0.0, out));
      for (int a = 0; a < p->nout; ++a)
        J[a][i] = out[a].d;
      memcpy(P.w, e, sizeof e);
      memset(P.z, 0, sizeof P.z);
      P.dt = 0.0;
      fd_compare("Jacobian column", &P, out, 1);
    }
    // time derivatives
    CHECK_OK(eval_jet(&P, zero, zero, 1.0, out));
    for (int a = 0; a < p->nout; ++a)
      Jt[a] = out[a].d;
    memset(P.w, 0, sizeof P.w);
    memset(P.z, 0, sizeof P.z);
    P.dt = 1.0;
    fd_compare("time derivative", &P, out, 1);
    // random direction (w, 1) with input curvature z: velocity and curvature term
    memcpy(P.w, w, sizeof w);
    memcpy(P.z, z, sizeof z);
    CHECK_OK(eval_jet(&P, w, z, 1.0, out));
    fd_compare("direction (w, 1) with curvature z", &P, out, 1);
    // the first derivative along (w, 1) is J w + df/dt
    for (int a = 0; a < p->nout; ++a) {
      double s = Jt[a], sc = fabs(Jt[a]);
      for (int i = 0; i < p->nin; ++i) {
        s += J[a][i] * w[i];
        sc += fabs(J[a][i] * w[i]);
      }
      CHECK_MSG(fabs(out[a].d - s) <= 1e-13 * (sc + 1),
                "'%s': d along (w,1) %.17g vs J w + ft %.17g", p->name, out[a].d, s);
    }
  }
  CHECK_MSG(n == NSAMPLE, "'%s' (%s): found only %d evaluable random points", p->name, ctxname, n);
  printf("  %-16s %-12s eval: Jacobian, time derivatives, curvature vs FD %s\n", p->name, ctxname,
         check_failures > f0 ? "FAILED" : "ok");
}

// ---------------------------------------------------------------------------------------------
// 2./3. through a system

// test map "slider": out = (u, 0[, 0]) gives each coordinate its own mass (M positive definite)
static int slider_eval(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)p;
  (void)ctx;
  out[0] = in[0];
  out[1] = out[2] = dal_const(0.0);
  return 0;
}
static const dal_primitive slider2 = {.name = "slider2",
                                      .version = 1,
                                      .nin = 1,
                                      .nout = 2,
                                      .nparam = 0,
                                      .eval = slider_eval,
                                      .doc = "test helper",
                                      .flags = 0};
static const dal_primitive slider3 = {.name = "slider3",
                                      .version = 1,
                                      .nin = 1,
                                      .nout = 3,
                                      .nparam = 0,
                                      .eval = slider_eval,
                                      .doc = "test helper",
                                      .flags = 0};

// test map "warp": a curved particle position from d coordinates (a parent with gamma != 0)
static int warp_eval(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)p;
  const int *d = ctx;
  out[0] = dal_add(in[0], dal_scale(dal_sin(dal_add(in[1], t)), 0.3));
  out[1] = dal_add(in[1], dal_scale(dal_sq(in[0]), 0.2));
  if (*d == 3) out[2] = dal_add(in[2], dal_scale(dal_mul(in[0], in[1]), 0.1));
  return 0;
}
static int dim2 = 2, dim3 = 3;
static const dal_primitive warp2 = {.name = "warp2",
                                    .version = 1,
                                    .nin = 2,
                                    .nout = 2,
                                    .nparam = 0,
                                    .eval = warp_eval,
                                    .doc = "test helper",
                                    .flags = 0};
static const dal_primitive warp3 = {.name = "warp3",
                                    .version = 1,
                                    .nin = 3,
                                    .nout = 3,
                                    .nparam = 0,
                                    .eval = warp_eval,
                                    .doc = "test helper",
                                    .flags = 0};

// the scene under test: coordinates q (n), `npart` warp particles on the first npart * d
// coordinates, then the primitive's remaining inputs on the following coordinates
typedef struct scene {
  const dal_primitive *prim;
  void *ctx;
  int d, npart, n;
  double param[MAXIO];
  double q[MAXIO], qd[MAXIO], qdd[MAXIO], t;
  int self;              // index of the particle under test (map scenes)
  int out;               // output component for fd
  int accel;             // fd along (q + s qd + s^2/2 qdd, t + s) instead of (q + s qd, t + s)
  double dq[MAXIO], dtt; // direction of the FD curve (when not along the motion)
} scene;

// the primitive's value at (q, t): warp particles, then prim
static int composite(const scene *S, const double *q, double t, double *val) {
  dal_jet in[MAXIO], out[MAXIO], tt = dal_const(t);
  int k = 0;
  for (int a = 0; a < S->npart; ++a) {
    dal_jet wq[3], wr[3];
    for (int b = 0; b < S->d; ++b)
      wq[b] = dal_const(q[a * S->d + b]);
    warp_eval(wq, tt, NULL, wr, S->d == 3 ? &dim3 : &dim2);
    for (int b = 0; b < S->d; ++b)
      in[k++] = wr[b];
  }
  for (int i = S->npart * S->d; i < S->prim->nin; ++i)
    in[k++] = dal_const(q[i]);
  if (S->prim->eval(in, tt, S->param, out, S->ctx)) return -1;
  for (int a = 0; a < S->prim->nout; ++a)
    val[a] = out[a].v;
  return 0;
}

static double scene_along(double s, const void *ctx) {
  const scene *S = ctx;
  double q[MAXIO], val[MAXIO];
  for (int i = 0; i < S->n; ++i)
    q[i] = S->q[i] + s * S->dq[i] + (S->accel ? 0.5 * (s * s) * S->qdd[i] : 0.0);
  if (composite(S, q, S->t + s * S->dtt, val)) return NAN;
  return val[S->out];
}

// FD of output a along direction (dq, dtt) [+ acceleration]
static fd_est scene_fd(scene *S, int a, const double *dq, double dtt, int accel) {
  S->out = a;
  memcpy(S->dq, dq, sizeof S->dq);
  S->dtt = dtt;
  S->accel = accel;
  return fd_estimate(scene_along, S, ULPS, SCALE);
}

// build: as a map (as_con = 0; placed on particle 0) or as a constraint (as_con = 1)
static dal_system *scene_build(scene *S, int as_con) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  int d = S->d, rc = dal_builder_create(d, &b), coords[MAXIO], parts[MAXIO], idx;
  for (int i = 0; i < S->n && !rc; ++i)
    rc = dal_builder_add_coord(b, NULL, &coords[i]);
  // warp particles, then the particle under test (map; after its parent), then one slider per
  // coordinate
  int self = -1;
  for (int a = 0; a < S->npart && !rc; ++a) {
    rc = dal_builder_add_particle(b, NULL, 0.7, &parts[a]);
    dal_place_def pd = dal_default_place_def();
    pd.prim = d == 3 ? &warp3 : &warp2;
    pd.coords = coords + a * d;
    pd.ncoords = d;
    pd.ctx = d == 3 ? &dim3 : &dim2;
    if (!rc) rc = dal_builder_place_def(b, parts[a], &pd);
  }
  if (!rc && !as_con) rc = dal_builder_add_particle(b, "self", 1.3, &self);
  S->self = self;
  for (int i = 0; i < S->n && !rc; ++i) {
    rc = dal_builder_add_particle(b, NULL, 0.9, &idx);
    dal_place_def pd = dal_default_place_def();
    pd.prim = d == 3 ? &slider3 : &slider2;
    pd.coords = &coords[i];
    pd.ncoords = 1;
    if (!rc) rc = dal_builder_place_def(b, idx, &pd);
  }
  // the primitive under test with all its parameters (by index: any primitive of the registry)
  int nrest = S->prim->nin - S->npart * d;
  if (!rc && !as_con) {
    dal_place_def pd = dal_default_place_def();
    pd.prim = S->prim;
    pd.parent = S->npart ? parts[0] : -1;
    pd.coords = coords + S->npart * d;
    pd.ncoords = nrest;
    for (int i = 0; i < S->prim->nparam; ++i)
      pd.param[i] = S->param[i];
    pd.ctx = S->ctx;
    rc = dal_builder_place_def(b, self, &pd);
  }
  if (!rc && as_con) {
    dal_constraint_def cd = dal_default_constraint_def();
    cd.name = S->prim->name;
    cd.prim = S->prim;
    cd.parts = parts;
    cd.nparts = S->npart;
    cd.coords = coords + S->npart * d;
    cd.ncoords = nrest;
    for (int i = 0; i < S->prim->nparam; ++i)
      cd.param[i] = S->param[i];
    cd.ctx = S->ctx;
    rc = dal_builder_add_constraint_def(b, &cd, NULL);
  }
  if (!rc) rc = dal_builder_compile(b, &sys);
  CHECK_MSG(rc == 0, "'%s': building the %s scene: %s", S->prim->name,
            as_con ? "constraint" : "map", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return sys;
}

// random state where the primitive is finite; 0 if none found
static int scene_point(scene *S) {
  for (int tries = 0; tries < 50; ++tries) {
    for (int i = 0; i < S->n; ++i) {
      S->q[i] = grid(-1.5, 1.5, 20);
      S->qd[i] = grid(-1, 1, 10);
    }
    for (int i = 0; i < S->prim->nparam; ++i)
      S->param[i] = check_rand(&seed, 0.5, 1.5);
    S->t = grid(-3, 3, 20);
    double val[MAXIO];
    if (composite(S, S->q, S->t, val) == 0) {
      int ok = 1;
      for (int a = 0; a < S->prim->nout; ++a)
        ok &= isfinite(val[a]);
      if (ok) return 1;
    }
  }
  return 0;
}

static void fd_check(const char *what, const scene *S, int a, double x, fd_est e, int second) {
  CHECK_MSG(e.valid, "%s '%s'[%d]: FD bound not available", what, S->prim->name, a);
  if (!e.valid) return;
  double ref = second ? e.d2 : e.d1, tol = second ? e.tol2 : e.tol1;
  CHECK_MSG(fabs(x - ref) <= tol, "%s '%s'[%d]: %.17g vs FD %.17g (tol %g)", what, S->prim->name, a,
            x, ref, tol);
}

// map scene: particle 0 is the primitive; parent: first d inputs from a warp particle
static void test_map_scene(const dal_primitive *p, void *ctx, int parent) {
  int f0 = check_failures, d = p->nout;
  scene S;
  memset(&S, 0, sizeof S);
  S.prim = p;
  S.ctx = ctx;
  S.d = d;
  S.npart = parent;
  S.n = p->nin > 0 ? p->nin : 1; // a scene needs one coordinate (for fixed points)
  double zero[MAXIO] = {0};
  for (int it = 0; it < NSAMPLE; ++it) {
    if (!scene_point(&S)) {
      CHECK_MSG(0, "'%s': no evaluable scene state", p->name);
      break;
    }
    dal_system *sys = scene_build(&S, 0);
    dal_state *st = NULL;
    if (!sys || dal_state_create(sys, &st)) {
      dal_system_destroy(sys);
      break;
    }
    int rc = dal_state_set(sys, st, S.t, S.q, S.qd);
    if (!rc) rc = dal_forward(sys, st);
    CHECK_MSG(rc == 0, "'%s' map scene: %s", p->name, dal_state_errmsg(st));
    if (!rc) {
      memcpy(S.qdd, dal_state_qddot(st), (size_t)S.n * sizeof(double));
      double J[3 * MAXIO], val[3];
      CHECK_OK(dal_state_jacobian(sys, st, S.self, J));
      composite(&S, S.q, S.t, val);
      const double *r = dal_state_positions(st) + S.self * d;
      const double *v = dal_state_velocities(st) + S.self * d;
      const double *acc = dal_state_accelerations(st) + S.self * d;
      const double *gam = dal_state_gamma(st) + S.self * d, *drdt = dal_state_drdt(st) + S.self * d;
      for (int a = 0; a < d; ++a) {
        CHECK_MSG(fabs(r[a] - val[a]) <= 1e-14 * SCALE, "'%s' position %d: %.17g vs %.17g", p->name,
                  a, r[a], val[a]);
        for (int j = 0; j < S.n; ++j) {
          double e[MAXIO] = {0};
          e[j] = 1.0;
          fd_check("system Jacobian", &S, a, J[a * S.n + j], scene_fd(&S, a, e, 0.0, 0), 0);
        }
        fd_check("system dr/dt", &S, a, drdt[a], scene_fd(&S, a, zero, 1.0, 0), 0);
        fd_est e = scene_fd(&S, a, S.qd, 1.0, 0);
        fd_check("system velocity", &S, a, v[a], e, 0);
        fd_check("system gamma", &S, a, gam[a], e, 1);
        fd_check("system acceleration", &S, a, acc[a], scene_fd(&S, a, S.qd, 1.0, 1), 1);
      }
    }
    dal_state_destroy(st);
    dal_system_destroy(sys);
  }
  printf("  %-16s %-12s as a map%s: J, dr/dt, v, gamma, a vs FD %s\n", p->name,
         ctx ? "(with ctx)" : "", parent ? " under a curved parent" : "",
         check_failures > f0 ? "FAILED" : "ok");
}

// constraint scene: phi, phidot and G qddot + gamma_phi = 0
static void test_constraint_scene(const dal_primitive *p, void *ctx) {
  int f0 = check_failures;
  scene S;
  memset(&S, 0, sizeof S);
  S.prim = p;
  S.ctx = ctx;
  S.d = (p->nin >= 3 && p->nin % 3 == 0) ? 3 : 2;
  S.npart = p->nin / S.d;
  S.n = p->nin > 0 ? p->nin : 1;
  for (int it = 0; it < NSAMPLE; ++it) {
    if (!scene_point(&S)) {
      CHECK_MSG(0, "'%s': no evaluable scene state", p->name);
      break;
    }
    dal_system *sys = scene_build(&S, 1);
    dal_state *st = NULL;
    if (!sys || dal_state_create(sys, &st)) {
      dal_system_destroy(sys);
      break;
    }
    CHECK(dal_system_nconstraints(sys) == p->nout);
    int rc = dal_state_set(sys, st, S.t, S.q, S.qd);
    if (!rc) rc = dal_forward(sys, st);
    CHECK_MSG(rc == 0, "'%s' constraint scene: %s", p->name, dal_state_errmsg(st));
    const double *phi = dal_state_phi(st), *phid = dal_state_phidot(st);
    if (!rc && phi && phid) {
      memcpy(S.qdd, dal_state_qddot(st), (size_t)S.n * sizeof(double));
      double val[MAXIO];
      composite(&S, S.q, S.t, val);
      for (int a = 0; a < p->nout; ++a) {
        CHECK_MSG(fabs(phi[a] - val[a]) <= 1e-14 * SCALE, "'%s' phi[%d]: %.17g vs %.17g", p->name,
                  a, phi[a], val[a]);
        fd_check("constraint phidot", &S, a, phid[a], scene_fd(&S, a, S.qd, 1.0, 0), 0);
        // along the computed motion the constraint's second derivative vanishes
        fd_check("constraint G qdd + gamma_phi", &S, a, 0.0, scene_fd(&S, a, S.qd, 1.0, 1), 1);
      }
    }
    dal_state_destroy(st);
    dal_system_destroy(sys);
  }
  printf("  %-16s %-12s as a constraint (%d particle inputs): phi, phidot, acceleration level %s\n",
         p->name, ctx ? "(with ctx)" : "", S.npart, check_failures > f0 ? "FAILED" : "ok");
}

// ---------------------------------------------------------------------------------------------
static void test_registry_shape(void) {
  int n = dal_primitive_count();
  CHECK(n >= 11);
  CHECK(dal_primitive_get(-1) == NULL && dal_primitive_get(n) == NULL);
  CHECK(dal_primitive_find(NULL) == NULL && dal_primitive_find("no such primitive") == NULL);
  for (int i = 0; i < n; ++i) {
    const dal_primitive *p = dal_primitive_get(i);
    CHECK_MSG(p && p->name && p->eval && p->doc && p->doc[0], "registry entry %d incomplete", i);
    if (!p || !p->name) continue;
    CHECK_MSG(p->version >= 1 && p->nin >= 0 && p->nout >= 1 && p->nparam >= 0 && p->nin <= MAXIO &&
                  p->nout <= MAXIO && p->nparam <= MAXIO,
              "'%s': version %d, nin %d, nout %d, nparam %d", p->name, p->version, p->nin, p->nout,
              p->nparam);
    CHECK_MSG(dal_primitive_find(p->name) == p, "'%s' not found by name (duplicate?)", p->name);
  }
  // the maps of primitives.h are registered
  const dal_primitive *maps[] = {&dal_map_cartesian2, &dal_map_cartesian3, &dal_map_fixed2,
                                 &dal_map_fixed3,     &dal_map_pendulum,   &dal_map_hanging,
                                 &dal_map_spherical,  &dal_map_ring,       &dal_map_curve2,
                                 &dal_map_curve3,     &dal_map_sphere};
  for (size_t i = 0; i < sizeof maps / sizeof maps[0]; ++i)
    CHECK_MSG(dal_primitive_find(maps[i]->name) == maps[i], "'%s' not in the registry",
              maps[i]->name);
}

int main(void) {
  test_registry_shape();
  int n = dal_primitive_count();
  printf("%d registered primitives:\n", n);
  for (int i = 0; i < n; ++i) {
    const dal_primitive *p = dal_primitive_get(i);
    if (!p || !p->eval || p->nin > MAXIO || p->nout > MAXIO || p->nparam > MAXIO) continue;
    void *ctx = known_ctx(p);
    // without a context, unless the primitive needs one (then this test must know it)
    point P;
    memset(&P, 0, sizeof P);
    P.prim = p;
    int works_null = random_point(&P);
    CHECK_MSG(works_null || ctx,
              "primitive '%s' fails without a context and test_primitives.c knows none: add one "
              "to known_ctx()",
              p->name);
    for (int pass = 0; pass < 2; ++pass) {
      void *c = pass ? ctx : NULL;
      if ((pass == 0 && !works_null) || (pass == 1 && !ctx)) continue;
      test_eval(p, c, c ? "(with ctx)" : "");
      if (p->nout == 2 || p->nout == 3) {
        test_map_scene(p, c, 0);
        if (p->nin >= p->nout) test_map_scene(p, c, 1);
      }
      if (p->nin > 0 && p->nout <= p->nin) test_constraint_scene(p, c);
    }
  }
  return check_summary("test_primitives");
}
