// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The articulated-body recursion against the dense assembly, and closed loops on top of it.
//
// Each random model is built twice from one seed, once with DAL_DYNAMICS_RECURSIVE and once
// with DAL_DYNAMICS_DENSE (M assembled and factored by Cholesky, the KKT matrix with
// constraints): accelerations, particle accelerations, reactions and multipliers must agree to
// 1e-12 relative, and the recursion's accelerations must solve the dense M qddot = Q - c (and
// the KKT system) to a backward error of 1e-14. Trees of 1 ... 200 particles in 2D and 3D mix
// translating parents (hanging, flagged and unflagged), parents that are not translations
// (user maps r = s(t) p + c R(q) p + ..., Lp != I), one- and multi-coordinate placements,
// rheonomic maps (moving pivots, a turning ring, time-dependent lengths), springs, dampers,
// moving anchors, force callbacks, U(q) and generalized forces. Singular cases must give the
// dense route's status and message. The four-bar linkage and a 64-link chain with both ends
// held, as a tree plus loop-closure rows, must agree with the same scenes in Cartesian
// coordinates (GGL) to the tolerance.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

#define PI 3.14159265358979323846
#define MAXN 256

// ---------------------------------------------------------------- test primitives

// 3D particle hanging from its parent at length l(t) = l0 (1 + e sin(w t)), polar angle a from
// the downward vertical and azimuth b. in (px, py, pz, a, b), param (l0, e, w). Translating.
static int hang3(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  dal_jet l = dal_scale(dal_addc(dal_scale(dal_sin(dal_scale(t, p[2])), p[1]), 1.0), p[0]);
  dal_jet sa, ca, sb, cb;
  dal_sincos(in[3], &sa, &ca);
  dal_sincos(in[4], &sb, &cb);
  out[0] = dal_add(in[0], dal_mul(l, dal_mul(sa, cb)));
  out[1] = dal_add(in[1], dal_mul(l, dal_mul(sa, sb)));
  out[2] = dal_sub(in[2], dal_mul(l, ca));
  return 0;
}
static const dal_primitive prim_hang3 = {.name = "hang3",
                                         .version = 1,
                                         .nin = 5,
                                         .nout = 3,
                                         .nparam = 3,
                                         .eval = hang3,
                                         .doc = "test",
                                         .flags = DAL_PRIM_TRANSLATES};

// the built-in hanging map without the translation hint: the library must find Lp = I itself
static int hang2u(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  return dal_map_hanging.eval(in, t, p, out, ctx);
}
static const dal_primitive prim_hang2u = {.name = "hang2u",
                                          .version = 1,
                                          .nin = 3,
                                          .nout = 2,
                                          .nparam = 1,
                                          .eval = hang2u,
                                          .doc = "test",
                                          .flags = 0};

// 2D, not a translation: r = p + c R(q) p + l(t) (sin q, -cos q), l(t) = l0 (1 + e sin(w t)).
// in (px, py, q), param (l0, c, e, w)
static int twist2(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  dal_jet l = dal_scale(dal_addc(dal_scale(dal_sin(dal_scale(t, p[3])), p[2]), 1.0), p[0]);
  dal_jet s, c;
  dal_sincos(in[2], &s, &c);
  dal_jet rx = dal_sub(dal_mul(c, in[0]), dal_mul(s, in[1]));
  dal_jet ry = dal_add(dal_mul(s, in[0]), dal_mul(c, in[1]));
  out[0] = dal_add(dal_add(in[0], dal_scale(rx, p[1])), dal_mul(l, s));
  out[1] = dal_sub(dal_add(in[1], dal_scale(ry, p[1])), dal_mul(l, c));
  return 0;
}
static const dal_primitive prim_twist2 = {.name = "twist2",
                                          .version = 1,
                                          .nin = 3,
                                          .nout = 2,
                                          .nparam = 4,
                                          .eval = twist2,
                                          .doc = "test",
                                          .flags = 0};

// 3D, not a translation: r = p + c Rz(q) p + l (sin q, cos q / 2, -cos q). in (p, q),
// param (l, c)
static int twist3(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  (void)t;
  dal_jet s, c;
  dal_sincos(in[3], &s, &c);
  dal_jet rx = dal_sub(dal_mul(c, in[0]), dal_mul(s, in[1]));
  dal_jet ry = dal_add(dal_mul(s, in[0]), dal_mul(c, in[1]));
  out[0] = dal_add(dal_add(in[0], dal_scale(rx, p[1])), dal_scale(s, p[0]));
  out[1] = dal_add(dal_add(in[1], dal_scale(ry, p[1])), dal_scale(c, 0.5 * p[0]));
  out[2] = dal_sub(dal_add(in[2], dal_scale(in[2], p[1])), dal_scale(c, p[0]));
  return 0;
}
static const dal_primitive prim_twist3 = {.name = "twist3",
                                          .version = 1,
                                          .nin = 4,
                                          .nout = 3,
                                          .nparam = 2,
                                          .eval = twist3,
                                          .doc = "test",
                                          .flags = 0};

// d coordinates relative to a parent seen through a breathing frame, not a translation:
// r = (1 + e sin(w t)) p + u + 0.1 (u_2 u_3, u_1 u_3, u_1 u_2) (3D; 2D: + 0.1 (u_2^2, u_1 u_2)).
// in (p, u), param (e, w)
static int frame(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, int d) {
  dal_jet s = dal_addc(dal_scale(dal_sin(dal_scale(t, p[1])), p[0]), 1.0);
  const dal_jet *u = in + d;
  for (int a = 0; a < d; ++a)
    out[a] = dal_add(dal_mul(s, in[a]), u[a]);
  if (d == 3) {
    out[0] = dal_add(out[0], dal_scale(dal_mul(u[1], u[2]), 0.1));
    out[1] = dal_add(out[1], dal_scale(dal_mul(u[0], u[2]), 0.1));
    out[2] = dal_add(out[2], dal_scale(dal_mul(u[0], u[1]), 0.1));
  } else {
    out[0] = dal_add(out[0], dal_scale(dal_sq(u[1]), 0.1));
    out[1] = dal_add(out[1], dal_scale(dal_mul(u[0], u[1]), 0.1));
  }
  return 0;
}
static int frame2(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  return frame(in, t, p, out, 2);
}
static int frame3(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  return frame(in, t, p, out, 3);
}
static const dal_primitive prim_frame2 = {.name = "frame2",
                                          .version = 1,
                                          .nin = 4,
                                          .nout = 2,
                                          .nparam = 2,
                                          .eval = frame2,
                                          .doc = "test",
                                          .flags = 0};
static const dal_primitive prim_frame3 = {.name = "frame3",
                                          .version = 1,
                                          .nin = 6,
                                          .nout = 3,
                                          .nparam = 2,
                                          .eval = frame3,
                                          .doc = "test",
                                          .flags = 0};

// ---------------------------------------------------------------- forces

// an anchor moving on a small circle
static int moving_anchor(dal_jet t, dal_jet *x, void *ctx) {
  (void)ctx;
  x[0] = dal_scale(dal_cos(dal_scale(t, 1.3)), 0.2);
  x[1] = dal_scale(dal_sin(dal_scale(t, 1.3)), 0.2);
  x[2] = dal_const(0.1);
  return 0;
}

typedef struct force_ctx {
  int N, d;
} force_ctx;

// drag and a swirl: F_k += -0.1 v_k + 0.05 (r_y, -r_x, 0)
static int swirl_force(double t, const double *r, const double *v, double *F, void *ctx) {
  const force_ctx *c = ctx;
  (void)t;
  for (int k = 0; k < c->N; ++k) {
    for (int a = 0; a < c->d; ++a)
      F[k * c->d + a] -= 0.1 * v[k * c->d + a];
    F[k * c->d] += 0.05 * r[k * c->d + 1];
    F[k * c->d + 1] -= 0.05 * r[k * c->d];
  }
  return 0;
}

typedef struct qforce_ctx {
  int n;
} qforce_ctx;

// U(q) = sum (0.3 + 0.01 j) q_j^2 / 2
static int quad_potential(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  const qforce_ctx *c = ctx;
  (void)t;
  *U = dal_const(0.0);
  for (int j = 0; j < c->n; ++j)
    *U = dal_add(*U, dal_scale(dal_sq(q[j]), 0.5 * (0.3 + 0.01 * j)));
  return 0;
}

// Q_j += 0.2 sin(t + j) - 0.05 qdot_j
static int gen_force(double t, const double *q, const double *qdot, double *Q, void *ctx) {
  const qforce_ctx *c = ctx;
  (void)q;
  for (int j = 0; j < c->n; ++j)
    Q[j] += 0.2 * sin(t + j) - 0.05 * qdot[j];
  return 0;
}

// ---------------------------------------------------------------- random models

static unsigned long long rng_state;
static double urand(void) {
  rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(rng_state >> 11) * (1.0 / 9007199254740992.0);
}
static double urange(double a, double b) { return a + (b - a) * urand(); }
static int irand(int n) { return (int)(urand() * n) % n; }

typedef struct model {
  dal_system *sys;
  dal_state *st;
  int n, N, d, m;
  force_ctx fc;
  qforce_ctx qc;
} model;

static void model_free(model *md) {
  dal_state_destroy(md->st);
  dal_system_destroy(md->sys);
  md->st = NULL;
  md->sys = NULL;
}

// A random tree of N particles in d dimensions with nloop constraint rows on top (distance
// rods between random particles, a rod to an anchor, a prescribed coordinate), all drawn from
// `seed`: the same seed gives the same model whatever the route. Returns the compile status.
static int build_tree(unsigned long long seed, int d, int N, int nloop, dal_dynamics how,
                      model *md) {
  dal_builder *b = NULL;
  memset(md, 0, sizeof *md);
  rng_state = seed;
  int rc = dal_builder_create(d, &b), coord[4];
  char name[32];
  md->d = d;
  md->N = N;
  for (int k = 0; k < N && !rc; ++k) {
    int p = k == 0 || urand() < 0.08 ? -1 : irand(k), part, kind = irand(5), nc;
    const dal_primitive *prim;
    double par[8] = {0};
    int npar = 0;
    if (p < 0) {
      // roots: a pendulum with a moving pivot or Cartesian (2D); Cartesian, a spherical
      // pendulum or a turning ring (3D)
      if (d == 2 && kind < 3) {
        prim = &dal_map_pendulum;
        nc = 1;
        double pp[7] = {urange(0.5, 1.5), urange(-1, 1), urange(-1, 1), 0.1, 0.2, 2.0, 0.3};
        memcpy(par, pp, sizeof pp);
        npar = 7;
      } else if (d == 2) {
        prim = &dal_map_cartesian2;
        nc = 2;
      } else if (kind < 2) {
        prim = &dal_map_cartesian3;
        nc = 3;
      } else if (kind < 4) {
        prim = &dal_map_spherical;
        nc = 2;
        double pp[4] = {urange(0.5, 1.5), urange(-1, 1), urange(-1, 1), urange(-1, 1)};
        memcpy(par, pp, sizeof pp);
        npar = 4;
      } else {
        prim = &dal_map_ring;
        nc = 1;
        double pp[3] = {urange(0.5, 1.5), urange(0.5, 2.0), urange(0, 1)};
        memcpy(par, pp, sizeof pp);
        npar = 3;
      }
    } else if (d == 2) {
      // children: translating (flagged or not), twisting, or a breathing frame
      if (kind < 2) {
        prim = kind == 0 ? &dal_map_hanging : &prim_hang2u;
        nc = 1;
        par[0] = urange(0.5, 1.5);
        npar = 1;
      } else if (kind < 4) {
        prim = &prim_twist2;
        nc = 1;
        double pp[4] = {urange(0.5, 1.5), 0.15, 0.1, urange(0.5, 2)};
        memcpy(par, pp, sizeof pp);
        npar = 4;
      } else {
        prim = &prim_frame2;
        nc = 2;
        par[0] = 0.05;
        par[1] = urange(0.5, 2);
        npar = 2;
      }
    } else {
      if (kind < 2) {
        prim = &prim_hang3;
        nc = 2;
        double pp[3] = {urange(0.5, 1.5), 0.1, urange(0.5, 2)};
        memcpy(par, pp, sizeof pp);
        npar = 3;
      } else if (kind < 4) {
        prim = &prim_twist3;
        nc = 1;
        par[0] = urange(0.5, 1.5);
        par[1] = 0.15;
        npar = 2;
      } else {
        prim = &prim_frame3;
        nc = 3;
        par[0] = 0.05;
        par[1] = urange(0.5, 2);
        npar = 2;
      }
    }
    for (int i = 0; i < nc && !rc; ++i) {
      snprintf(name, sizeof name, "q%d_%d", k, i);
      rc = dal_builder_add_coord(b, name, &coord[i]);
    }
    snprintf(name, sizeof name, "p%d", k);
    if (!rc) rc = dal_builder_add_particle(b, name, urange(0.5, 2.0), &part);
    dal_place_def pd = dal_default_place_def();
    pd.prim = prim;
    pd.parent = p;
    pd.coords = coord;
    pd.ncoords = nc;
    for (int i = 0; i < npar; ++i)
      pd.param[i] = par[i]; // the rest take the primitive's defaults
    if (!rc) rc = dal_builder_place_def(b, part, &pd);
    md->n += nc;
  }
  // forces
  double g[3] = {0.1, -9.81, 0.0};
  if (d == 3) g[1] = 0.2, g[2] = -9.81;
  if (!rc) rc = dal_builder_set_gravity(b, g);
  for (int i = 0; i < N / 3 + 1 && !rc && N > 1; ++i) {
    int a = irand(N), c = irand(N);
    if (a == c) continue;
    dal_spring_def sd = dal_default_spring_def();
    sd.a = a;
    sd.b = c;
    sd.length = urange(0.5, 2); // drawn before k, as the compiler evaluated the former call
    sd.k = urange(1, 10);
    rc = dal_builder_add_spring_def(b, &sd);
    if (rc || i % 2 == 0) continue;
    dal_damper_def dd = dal_default_damper_def();
    dd.a = a;
    dd.b = c;
    dd.c = urange(0.1, 1);
    rc = dal_builder_add_damper_def(b, &dd);
  }
  double x0[3] = {0.3, 0.4, 0.5};
  dal_spring_def sd = dal_default_spring_def();
  sd.a = irand(N);
  memcpy(sd.anchor, x0, sizeof x0);
  sd.path = moving_anchor;
  sd.k = 3.0;
  sd.length = 0.5;
  if (!rc) rc = dal_builder_add_spring_def(b, &sd);
  dal_damper_def dd = dal_default_damper_def();
  dd.a = irand(N);
  memcpy(dd.anchor, x0, sizeof x0);
  dd.c = 0.4;
  if (!rc) rc = dal_builder_add_damper_def(b, &dd);
  md->fc.N = N;
  md->fc.d = d;
  md->qc.n = md->n;
  if (!rc) rc = dal_builder_add_force(b, swirl_force, &md->fc);
  if (!rc) rc = dal_builder_add_potential_q(b, quad_potential, &md->qc);
  if (!rc) rc = dal_builder_add_genforce(b, gen_force, &md->qc);
  // loop-closure rows: rods between particles, a rod to an anchor, a prescribed coordinate
  for (int i = 0; i < nloop && !rc; ++i) {
    int parts[2] = {irand(N), irand(N)};
    snprintf(name, sizeof name, "loop%d", i);
    if (i % 3 == 1) {
      dal_constraint_def cd = dal_default_constraint_def(); // a unit rod to (0.1, 0.2[, 0.3])
      cd.name = name;
      cd.prim = d == 2 ? &dal_con_anchor2 : &dal_con_anchor3;
      cd.parts = parts;
      cd.nparts = 1;
      cd.param[DAL_ANCHOR_L] = 1.0;
      cd.param[DAL_ANCHOR_X0] = 0.1;
      cd.param[DAL_ANCHOR_Y0] = 0.2;
      if (d == 3) cd.param[DAL_ANCHOR_Z0] = 0.3;
      rc = dal_builder_add_constraint_def(b, &cd, NULL);
    } else if (i % 3 == 2) {
      int j = irand(md->n);
      double q0 = 0.2;
      dal_constraint_def cd = dal_default_constraint_def();
      cd.name = name;
      cd.prim = &dal_con_prescribed;
      cd.coords = &j;
      cd.ncoords = 1;
      cd.param[DAL_PRESCRIBED_Q0] = q0;
      rc = dal_builder_add_constraint_def(b, &cd, NULL);
    } else {
      if (parts[0] == parts[1]) parts[1] = (parts[0] + 1) % N;
      dal_constraint_def cd = dal_default_constraint_def();
      cd.name = name;
      cd.prim = d == 2 ? &dal_con_distance2 : &dal_con_distance3;
      cd.parts = parts;
      cd.nparts = 2;
      cd.param[DAL_DISTANCE_L] = 1.0;
      rc = dal_builder_add_constraint_def(b, &cd, NULL);
    }
  }
  if (!rc) rc = dal_builder_set_dynamics(b, how);
  if (!rc) rc = dal_builder_compile(b, &md->sys);
  if (rc) fprintf(stderr, "build_tree: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  if (!rc) rc = dal_state_create(md->sys, &md->st);
  if (!rc) md->m = dal_system_nconstraints(md->sys);
  return rc;
}

// a random state (drawn after the model, so the same for both routes)
static void random_state(model *md, double *q, double *qd, double *t) {
  for (int j = 0; j < md->n; ++j) {
    q[j] = urange(0.4, 2.6); // away from the spherical charts' poles
    qd[j] = urange(-1.5, 1.5);
  }
  *t = urange(0, 3);
}

static double max_abs(const double *x, int n) {
  double s = 0.0;
  for (int i = 0; i < n; ++i)
    s = fmax(s, fabs(x[i]));
  return s;
}

// max |x - y| / max(1, max |y|)
static double rel_diff(const double *x, const double *y, int n) {
  double s = 0.0;
  for (int i = 0; i < n; ++i)
    s = fmax(s, fabs(x[i] - y[i]));
  return s / fmax(1.0, max_abs(y, n));
}

static double worst_acc = 0.0, worst_out = 0.0, worst_lam = 0.0, worst_bwd = 0.0;

// the recursion's qddot (and lambda) solve the dense system: backward error of
// M x - G' lambda = Q - c (and of G x = -gamma_phi through the constraint reactions' balance)
static double backward_error(const model *md, const dal_state *st) {
  int n = md->n;
  const double *M = dal_state_mass_matrix(st), *x = dal_state_qddot(st);
  const double *Q = dal_state_genforces(st), *c = dal_state_bias(st);
  double *res = calloc((size_t)n, sizeof(double)), *Qc = calloc((size_t)n, sizeof(double));
  double mnorm = 0.0, err = 0.0;
  if (!res || !Qc || !M) {
    free(res);
    free(Qc);
    return INFINITY;
  }
  if (md->m) dal_constraint_genforces(md->sys, st, Qc);
  for (int i = 0; i < n; ++i) {
    double s = 0.0, row = 0.0;
    for (int j = 0; j < n; ++j) {
      s += M[(size_t)j * n + i] * x[j];
      row += fabs(M[(size_t)j * n + i]);
    }
    res[i] = s - (Q[i] - c[i]) - Qc[i];
    mnorm = fmax(mnorm, row);
  }
  double scale = mnorm * max_abs(x, n) + max_abs(Q, n) + max_abs(c, n) + max_abs(Qc, n);
  err = max_abs(res, n) / scale;
  free(res);
  free(Qc);
  return err;
}

// one random model through both routes at a few random states
static void compare_routes(unsigned long long seed, int d, int N, int nloop, int nstates) {
  model rec, den;
  int rc1 = build_tree(seed, d, N, nloop, DAL_DYNAMICS_RECURSIVE, &rec);
  int rc2 = build_tree(seed, d, N, nloop, DAL_DYNAMICS_DENSE, &den);
  CHECK_MSG(rc1 == 0 && rc2 == 0, "build d=%d N=%d loops=%d: %d %d", d, N, nloop, rc1, rc2);
  if (rc1 || rc2) {
    model_free(&rec);
    model_free(&den);
    return;
  }
  CHECK(dal_system_dynamics(rec.sys) == DAL_DYNAMICS_RECURSIVE);
  CHECK(dal_system_dynamics(den.sys) == DAL_DYNAMICS_DENSE);
  int n = rec.n, Nd = N * d, m = rec.m;
  double *q = malloc((size_t)n * sizeof(double)), *qd = malloc((size_t)n * sizeof(double)), t;
  rng_state = seed ^ 0x9e3779b97f4a7c15ULL;
  for (int s = 0; s < nstates && q && qd; ++s) {
    random_state(&rec, q, qd, &t);
    CHECK_OK(dal_state_set(rec.sys, rec.st, t, q, qd));
    CHECK_OK(dal_state_set(den.sys, den.st, t, q, qd));
    int a = dal_forward(rec.sys, rec.st), b = dal_forward(den.sys, den.st);
    CHECK_MSG(a == b, "d=%d N=%d: forward %d (%s) vs %d (%s)", d, N, a, dal_state_errmsg(rec.st), b,
              dal_state_errmsg(den.st));
    if (a || b) continue;
    double e1 = rel_diff(dal_state_qddot(rec.st), dal_state_qddot(den.st), n);
    double e2 = fmax(rel_diff(dal_state_accelerations(rec.st), dal_state_accelerations(den.st), Nd),
                     rel_diff(dal_state_reactions(rec.st), dal_state_reactions(den.st), Nd));
    double e3 = m ? rel_diff(dal_state_lambda(rec.st), dal_state_lambda(den.st), m) : 0.0;
    double e4 = backward_error(&rec, rec.st);
    // the same Q, c and M (one assembly for both)
    CHECK(rel_diff(dal_state_genforces(rec.st), dal_state_genforces(den.st), n) < 1e-14);
    CHECK(rel_diff(dal_state_bias(rec.st), dal_state_bias(den.st), n) < 1e-14);
    worst_acc = fmax(worst_acc, e1);
    worst_out = fmax(worst_out, e2);
    worst_lam = fmax(worst_lam, e3);
    worst_bwd = fmax(worst_bwd, e4);
    CHECK_MSG(e1 < 1e-12, "d=%d N=%d loops=%d: qddot differs by %.3g", d, N, nloop, e1);
    CHECK_MSG(e2 < 1e-12, "d=%d N=%d loops=%d: a or reactions differ by %.3g", d, N, nloop, e2);
    CHECK_MSG(e3 < 1e-12, "d=%d N=%d loops=%d: lambda differs by %.3g", d, N, nloop, e3);
    CHECK_MSG(e4 < 1e-14, "d=%d N=%d loops=%d: backward error %.3g", d, N, nloop, e4);
  }
  free(q);
  free(qd);
  model_free(&rec);
  model_free(&den);
}

static void test_random_trees(void) {
  static const int sizes[] = {1, 2, 3, 5, 8, 13, 30, 60, 120, 200};
  for (int d = 2; d <= 3; ++d)
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; ++i)
      for (int rep = 0; rep < 2; ++rep)
        compare_routes(1000ULL * d + 17ULL * sizes[i] + (unsigned long long)rep, d, sizes[i], 0, 3);
  printf("  random trees (1 ... 200 particles, 2D and 3D): qddot %.2e, a and N %.2e, backward "
         "error %.2e (relative)\n",
         worst_acc, worst_out, worst_bwd);
}

static void test_random_loops(void) {
  static const int sizes[] = {2, 4, 9, 25, 80, 200};
  static const int loops[] = {1, 3, 5};
  worst_acc = worst_out = worst_lam = worst_bwd = 0.0;
  for (int d = 2; d <= 3; ++d)
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; ++i)
      for (size_t l = 0; l < sizeof loops / sizeof loops[0]; ++l)
        compare_routes(77ULL + 1000ULL * d + 31ULL * sizes[i] + l, d, sizes[i], loops[l], 2);
  printf("  random trees with 1, 3, 5 loop rows: qddot %.2e, a and N %.2e, lambda %.2e, "
         "backward error %.2e\n",
         worst_acc, worst_out, worst_lam, worst_bwd);
}

// ---------------------------------------------------------------- singular cases

// a spherical pendulum at its pole, and a chain with a link of zero length: same status and
// the same message from both routes
static int singular_model(int which, dal_dynamics how, dal_system **sys) {
  dal_builder *b = NULL;
  int rc = dal_builder_create(which == 0 ? 3 : 2, &b), c[3], p[3];
  if (which == 0) {
    rc = rc ? rc : dal_builder_add_coord(b, "theta", &c[0]);
    rc = rc ? rc : dal_builder_add_coord(b, "phi", &c[1]);
    rc = rc ? rc : dal_builder_add_particle(b, "bob", 1.0, &p[0]);
    dal_place_def pd = dal_default_place_def();
    pd.prim = &dal_map_spherical;
    pd.coords = c;
    pd.ncoords = 2;
    pd.param[DAL_SPHERICAL_L] = 1.0;
    rc = rc ? rc : dal_builder_place_def(b, p[0], &pd);
  } else {
    double l0 = 0.0, l1 = 1.0;
    rc = rc ? rc : dal_builder_add_coord(b, "a", &c[0]);
    rc = rc ? rc : dal_builder_add_coord(b, "b", &c[1]);
    rc = rc ? rc : dal_builder_add_coord(b, "c", &c[2]);
    for (int k = 0; k < 3 && !rc; ++k)
      rc = dal_builder_add_particle(b, NULL, 1.0, &p[k]);
    rc = rc ? rc : scn_place_swing(b, NULL, p[0], -1, 1.0, c[0]);
    rc = rc ? rc : scn_place_swing(b, NULL, p[1], p[0], l0, c[1]);
    rc = rc ? rc : scn_place_swing(b, NULL, p[2], p[1], l1, c[2]);
  }
  double g[3] = {0, 0, -9.81};
  rc = rc ? rc : dal_builder_set_gravity(b, g);
  rc = rc ? rc : dal_builder_set_dynamics(b, how);
  rc = rc ? rc : dal_builder_compile(b, sys);
  dal_builder_destroy(b);
  return rc;
}

static void test_singular(void) {
  // a link of zero length (the second model) is now refused by the builder, which names the
  // parameter: the degenerate coordinate never reaches either route
  {
    dal_system *z = NULL;
    CHECK(singular_model(1, DAL_DYNAMICS_AUTO, &z) == DAL_E_ARG);
    dal_system_destroy(z);
  }
  for (int which = 0; which < 1; ++which) {
    dal_system *s[2] = {NULL, NULL};
    dal_state *st[2] = {NULL, NULL};
    int status[2];
    for (int r = 0; r < 2; ++r) {
      CHECK_OK(singular_model(which, r ? DAL_DYNAMICS_DENSE : DAL_DYNAMICS_RECURSIVE, &s[r]));
      CHECK_OK(dal_state_create(s[r], &st[r]));
      double q[3] = {0.0, 0.3, 0.2}, qd[3] = {1.0, 0.5, 0.1};
      CHECK_OK(dal_state_set(s[r], st[r], 0.5, q, qd));
      status[r] = dal_forward(s[r], st[r]);
    }
    CHECK(status[0] == DAL_E_SINGULAR && status[1] == DAL_E_SINGULAR);
    CHECK_MSG(strcmp(dal_state_errmsg(st[0]), dal_state_errmsg(st[1])) == 0,
              "messages differ:\n    %s\n    %s", dal_state_errmsg(st[0]), dal_state_errmsg(st[1]));
    CHECK(strstr(dal_state_errmsg(st[0]), which == 0 ? "'phi'" : "'b'") != NULL);
    printf("  %s: %s / %s (%s)\n", which == 0 ? "pole" : "massless", dal_status_name(status[0]),
           dal_status_name(status[1]), dal_state_errmsg(st[0]));
    for (int r = 0; r < 2; ++r) {
      dal_state_destroy(st[r]);
      dal_system_destroy(s[r]);
    }
  }
  // redundant loop rows: both routes name the constraints
  for (int r = 0; r < 2; ++r) {
    dal_builder *b = NULL;
    dal_system *s = NULL;
    dal_state *st = NULL;
    int c[2], p[2];
    double l = 1.0;
    CHECK_OK(dal_builder_create(2, &b));
    CHECK_OK(dal_builder_add_coord(b, "a", &c[0]));
    CHECK_OK(dal_builder_add_coord(b, "b", &c[1]));
    CHECK_OK(dal_builder_add_particle(b, "p", 1.0, &p[0]));
    CHECK_OK(dal_builder_add_particle(b, "tip", 1.0, &p[1]));
    CHECK_OK(scn_place_swing(b, NULL, p[0], -1, 1.0, c[0]));
    CHECK_OK(scn_place_swing(b, NULL, p[1], p[0], l, c[1]));
    CHECK_OK(scn_add_rod(b, "held", p[1], -1, 2.0, NULL));
    CHECK_OK(scn_add_rod(b, "held_again", p[1], -1, 2.0, NULL));
    CHECK_OK(dal_builder_set_dynamics(b, r ? DAL_DYNAMICS_DENSE : DAL_DYNAMICS_RECURSIVE));
    CHECK_OK(dal_builder_compile(b, &s));
    dal_builder_destroy(b);
    CHECK_OK(dal_state_create(s, &st));
    double q[2] = {0.7, 1.1}, qd[2] = {0.2, -0.4};
    CHECK_OK(dal_state_set(s, st, 0.0, q, qd));
    int rc = dal_forward(s, st);
    CHECK_MSG(rc == DAL_E_CONSTRAINT, "route %d: %s", r, dal_state_errmsg(st));
    CHECK(strstr(dal_state_errmsg(st), "'held'") && strstr(dal_state_errmsg(st), "'held_again'"));
    dal_state_destroy(st);
    dal_system_destroy(s);
  }
}

// ---------------------------------------------------------------- compile-time detection

static void test_detection(void) {
  // a coordinate shared by two placements: AUTO falls back to the dense route, RECURSIVE names it
  for (int how = 0; how < 2; ++how) {
    dal_builder *b = NULL;
    dal_system *s = NULL;
    int c, p[2];
    double l = 1.0;
    CHECK_OK(dal_builder_create(2, &b));
    CHECK_OK(dal_builder_add_coord(b, "theta", &c));
    CHECK_OK(dal_builder_add_particle(b, "p0", 1.0, &p[0]));
    CHECK_OK(dal_builder_add_particle(b, "p1", 1.0, &p[1]));
    dal_place_def pd = dal_default_place_def();
    pd.prim = &dal_map_pendulum;
    pd.coords = &c;
    pd.ncoords = 1;
    pd.param[DAL_PENDULUM_L] = 1.0;
    CHECK_OK(dal_builder_place_def(b, p[0], &pd));
    pd = dal_default_place_def();
    pd.prim = &dal_map_hanging;
    pd.parent = p[0];
    pd.coords = &c;
    pd.ncoords = 1;
    pd.param[DAL_HANGING_L] = l;
    CHECK_OK(dal_builder_place_def(b, p[1], &pd));
    CHECK_OK(dal_builder_set_dynamics(b, how ? DAL_DYNAMICS_RECURSIVE : DAL_DYNAMICS_AUTO));
    int rc = dal_builder_compile(b, &s);
    if (how == 0) {
      CHECK(rc == DAL_OK && dal_system_dynamics(s) == DAL_DYNAMICS_DENSE);
    } else {
      CHECK(rc == DAL_E_UNSUPPORTED);
      CHECK(strstr(dal_builder_errmsg(b), "'theta'") && strstr(dal_builder_errmsg(b), "'p1'"));
    }
    dal_system_destroy(s);
    dal_builder_destroy(b);
  }
  // a coordinate that moves nothing; an unknown route
  dal_builder *b = NULL;
  dal_system *s = NULL;
  int c[2], p;
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "theta", &c[0]));
  CHECK_OK(dal_builder_add_coord(b, "idle", &c[1]));
  CHECK_OK(dal_builder_add_particle(b, "bob", 1.0, &p));
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_pendulum;
  pd.coords = &c[0];
  pd.ncoords = 1;
  pd.param[DAL_PENDULUM_L] = 1.0;
  CHECK_OK(dal_builder_place_def(b, p, &pd));
  CHECK(dal_builder_set_dynamics(b, (dal_dynamics)7) == DAL_E_ARG);
  CHECK_OK(dal_builder_set_dynamics(b, DAL_DYNAMICS_RECURSIVE));
  CHECK(dal_builder_compile(b, &s) == DAL_E_UNSUPPORTED);
  CHECK(strstr(dal_builder_errmsg(b), "'idle'") != NULL);
  dal_builder_destroy(b);
  // the default chain is recursive
  model md;
  CHECK_OK(build_tree(5, 2, 10, 0, DAL_DYNAMICS_AUTO, &md));
  CHECK(dal_system_dynamics(md.sys) == DAL_DYNAMICS_RECURSIVE);
  model_free(&md);
}

// ---------------------------------------------------------------- a large chain (n > 512)

static int chain_path(dal_jet t, dal_jet *q, void *ctx) {
  int n = *(const int *)ctx;
  for (int j = 0; j < n; ++j)
    q[j] = dal_addc(dal_scale(dal_sin(dal_addc(t, 0.1 * j)), 0.3), 0.5);
  return 0;
}

static void test_large_chain(void) {
  int N = 600;
  dal_system *s[2] = {NULL, NULL};
  dal_state *st[2] = {NULL, NULL};
  double *q = malloc(N * sizeof(double)), *qd = malloc(N * sizeof(double));
  double *res0 = malloc(N * sizeof(double)), *res1 = malloc(N * sizeof(double));
  double *J = malloc(2 * (size_t)N * sizeof(double));
  for (int r = 0; r < 2; ++r) {
    dal_builder *b = NULL;
    double g[2] = {0, -9.81};
    CHECK_OK(dal_builder_create(2, &b));
    for (int k = 0; k < N; ++k) {
      int c, p;
      CHECK_OK(dal_builder_add_coord(b, NULL, &c));
      CHECK_OK(dal_builder_add_particle(b, NULL, 1.0 + 0.001 * k, &p));
      // unit links: a pendulum about the origin, then each hanging from the previous
      dal_place_def pd = dal_default_place_def();
      pd.coords = &c;
      pd.ncoords = 1;
      if (k == 0) {
        pd.prim = &dal_map_pendulum;
        pd.param[DAL_PENDULUM_L] = 1.0;
      } else {
        pd.prim = &dal_map_hanging;
        pd.parent = p - 1;
        pd.param[DAL_HANGING_L] = 1.0;
      }
      CHECK_OK(dal_builder_place_def(b, p, &pd));
    }
    CHECK_OK(dal_builder_set_gravity(b, g));
    CHECK_OK(dal_builder_set_dynamics(b, r ? DAL_DYNAMICS_DENSE : DAL_DYNAMICS_AUTO));
    CHECK_OK(dal_builder_compile(b, &s[r]));
    dal_builder_destroy(b);
    CHECK_OK(dal_state_create(s[r], &st[r]));
    for (int j = 0; j < N; ++j) {
      q[j] = 0.3 * sin(0.1 * j);
      qd[j] = 0.2 * cos(0.07 * j);
    }
    CHECK_OK(dal_state_set(s[r], st[r], 0.0, q, qd));
    CHECK_OK(dal_forward(s[r], st[r]));
  }
  // the recursive system keeps neither M nor global Jacobians, and agrees with the dense one
  CHECK(dal_state_mass_matrix(st[0]) == NULL && dal_state_mass_matrix(st[1]) != NULL);
  double e = rel_diff(dal_state_qddot(st[0]), dal_state_qddot(st[1]), N);
  CHECK_MSG(e < 1e-12, "N=600 chain: qddot differs by %.3g", e);
  CHECK(rel_diff(dal_state_reactions(st[0]), dal_state_reactions(st[1]), 2 * N) < 1e-12);
  CHECK_OK(dal_state_jacobian(s[0], st[0], N - 1, J));
  CHECK_CLOSE(J[0], cos(q[0]), 1e-15);
  CHECK_CLOSE(J[N + N - 1], sin(q[N - 1]), 1e-15);
  // M applied through the local blocks (Lagrange residual of a path) vs the dense M
  int n = N;
  CHECK_OK(dal_lagrange_residual(s[0], st[0], chain_path, 0.7, res0, &n));
  CHECK_OK(dal_lagrange_residual(s[1], st[1], chain_path, 0.7, res1, &n));
  double er = rel_diff(res0, res1, N);
  CHECK_MSG(er < 1e-12, "Lagrange residual differs by %.3g", er);
  printf("  600-link chain without M or J: qddot %.2e, Lagrange residual %.2e\n", e, er);
  for (int r = 0; r < 2; ++r) {
    dal_state_destroy(st[r]);
    dal_system_destroy(s[r]);
  }
  free(q);
  free(qd);
  free(res0);
  free(res1);
  free(J);
}

// ---------------------------------------------------------------- integration

static void test_integration(void) {
  model a, b;
  CHECK_OK(build_tree(4242, 2, 8, 0, DAL_DYNAMICS_RECURSIVE, &a));
  CHECK_OK(build_tree(4242, 2, 8, 0, DAL_DYNAMICS_DENSE, &b));
  double q[64], qd[64], t;
  rng_state = 99;
  random_state(&a, q, qd, &t);
  for (int j = 0; j < a.n; ++j)
    qd[j] *= 0.3;
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_DOPRI5;
  o.rtol = 1e-10;
  o.atol = 1e-10;
  CHECK_OK(dal_state_set(a.sys, a.st, 0.0, q, qd));
  CHECK_OK(dal_state_set(b.sys, b.st, 0.0, q, qd));
  CHECK_OK(dal_advance(a.sys, a.st, &o, 1.0));
  CHECK_OK(dal_advance(b.sys, b.st, &o, 1.0));
  double e = rel_diff(dal_state_q(a.st), dal_state_q(b.st), a.n);
  CHECK_MSG(e < 1e-9, "integrated 8-particle tree: routes differ by %.3g", e);
  printf("  8-particle tree, DOPRI5 to t = 1 at 1e-10: routes differ by %.2e\n", e);
  model_free(&a);
  model_free(&b);
}

// ---------------------------------------------------------------- closed loops vs Cartesian

// positions (np x 2) of a scene in either form at t1
typedef struct loop_run {
  double r[2 * 64];
  int status;
  long rhs;
} loop_run;

static void run_scene(dal_system *s, const double *q, const double *qd, int n, dal_formulation form,
                      dal_method meth, double rtol, double t1, int np, loop_run *out) {
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(s, &st));
  CHECK_OK(dal_state_set(s, st, 0.0, q, qd));
  (void)n;
  dal_solve_opts o = dal_default_solve_opts();
  o.form = form;
  o.method = meth;
  o.rtol = o.atol = rtol;
  o.project = form == DAL_FORM_INDEX1;
  if (form == DAL_FORM_GGL) o.linsol = DAL_LINSOL_KLU;
  out->status = dal_advance(s, st, &o, t1);
  CHECK_MSG(out->status == 0, "%s", dal_state_errmsg(st));
  memcpy(out->r, dal_state_positions(st), (size_t)np * 2 * sizeof(double));
  dal_stats stt;
  dal_state_stats(st, &stt);
  out->rhs = stt.rhs_evals;
  dal_state_destroy(st);
}

// the four-bar linkage and the chain held at both ends (scenes.h), checked as built
static void fourbar(int cart, dal_dynamics how, double th1, double w1, dal_system **s, double *q,
                    double *qd) {
  scn_knobs k = scn_default();
  k.dynamics = how;
  *s = scn_fourbar(&k, cart, th1, w1, q, qd);
  CHECK_MSG(*s != NULL, "fourbar");
}

static void held_chain(int NL, int cart, dal_dynamics how, dal_system **s, double *q, double *qd) {
  scn_knobs k = scn_default();
  k.dynamics = how;
  k.N = NL;
  *s = scn_held_chain(&k, cart, q, qd);
  CHECK_MSG(*s != NULL, "held chain");
}

static void test_loops_vs_cartesian(void) {
  // the four-bar: tree + 1 loop row (recursive and dense routes) vs Cartesian GGL
  double q[128], qd[128];
  dal_system *s = NULL;
  loop_run rec, den, cart;
  const double tol = 1e-8, t1 = 2.0;
  fourbar(0, DAL_DYNAMICS_AUTO, 0.4, 3.0, &s, q, qd);
  CHECK(dal_system_dynamics(s) == DAL_DYNAMICS_RECURSIVE);
  run_scene(s, q, qd, 2, DAL_FORM_INDEX1, DAL_METHOD_DOPRI5, tol, t1, 2, &rec);
  dal_system_destroy(s);
  fourbar(0, DAL_DYNAMICS_DENSE, 0.4, 3.0, &s, q, qd);
  CHECK(dal_system_dynamics(s) == DAL_DYNAMICS_DENSE);
  run_scene(s, q, qd, 2, DAL_FORM_INDEX1, DAL_METHOD_DOPRI5, tol, t1, 2, &den);
  dal_system_destroy(s);
  fourbar(1, DAL_DYNAMICS_DENSE, 0.4, 3.0, &s, q, qd);
  run_scene(s, q, qd, 4, DAL_FORM_GGL, DAL_METHOD_BDF, tol, t1, 2,
            &cart); // IDA: calibrated (solve.h)
  dal_system_destroy(s);
  double e_cart = 0.0, e_den = 0.0;
  for (int i = 0; i < 4; ++i) {
    e_cart = fmax(e_cart, fabs(rec.r[i] - cart.r[i]));
    e_den = fmax(e_den, fabs(rec.r[i] - den.r[i]));
  }
  printf("  four-bar to t = %g: tree+loop (recursive) vs Cartesian GGL %.2e, vs tree+loop "
         "(dense KKT) %.3e (rtol %g)\n",
         t1, e_cart, e_den, tol);
  CHECK(e_cart < 20 * tol);
  CHECK(e_den < 20 * tol);
  // a 32-link chain held at both ends
  const int NL = 32;
  held_chain(NL, 0, DAL_DYNAMICS_AUTO, &s, q, qd);
  CHECK(dal_system_dynamics(s) == DAL_DYNAMICS_RECURSIVE);
  run_scene(s, q, qd, NL - 1, DAL_FORM_INDEX1, DAL_METHOD_DOPRI5, tol, 0.5, NL - 1, &rec);
  dal_system_destroy(s);
  held_chain(NL, 1, DAL_DYNAMICS_AUTO, &s, q, qd);
  run_scene(s, q, qd, 2 * (NL - 1), DAL_FORM_GGL, DAL_METHOD_BDF, tol, 0.5, NL - 1, &cart);
  dal_system_destroy(s);
  e_cart = 0.0;
  for (int i = 0; i < 2 * (NL - 1); ++i)
    e_cart = fmax(e_cart, fabs(rec.r[i] - cart.r[i]));
  printf("  %d-link chain held at both ends to t = 0.5: tree+loop vs Cartesian GGL %.2e\n", NL,
         e_cart);
  CHECK(e_cart < 20 * tol);
}

int main(void) {
  test_random_trees();
  test_random_loops();
  test_singular();
  test_detection();
  test_large_chain();
  test_integration();
  test_loops_vs_cartesian();
  return check_summary("test_aba");
}
