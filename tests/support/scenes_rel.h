// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Scenes shared by the determinism and thread tests: a chaotic double pendulum in minimal
// coordinates (ODE) and a Cartesian double pendulum held by two rods (DAE), built on the scene
// library (scenes.h), and a monitor that records every output state into a flat buffer so runs
// can be compared bit for bit.
#ifndef DAL_TEST_SCENES_REL_H
#define DAL_TEST_SCENES_REL_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "scenes.h"

/// |r - anchor| - L for one particle (inputs its d = 2 position; param (L, ax, ay))
static inline int rel_rod_fixed(const dal_jet *in, dal_jet t, const double *p, dal_jet *out,
                                void *ctx) {
  (void)t;
  (void)ctx;
  out[0] = dal_addc(dal_hypot(dal_addc(in[0], -p[1]), dal_addc(in[1], -p[2])), -p[0]);
  return 0;
}

/// |r_b - r_a| - L for two particles (inputs 2 + 2 positions; param (L))
static inline int rel_rod_pair(const dal_jet *in, dal_jet t, const double *p, dal_jet *out,
                               void *ctx) {
  (void)t;
  (void)ctx;
  out[0] = dal_addc(dal_hypot(dal_sub(in[2], in[0]), dal_sub(in[3], in[1])), -p[0]);
  return 0;
}

static const dal_primitive rel_prim_rod_fixed = {.name = "rel_rod_fixed",
                                                 .version = 1,
                                                 .nin = 2,
                                                 .nout = 1,
                                                 .nparam = 3,
                                                 .eval = rel_rod_fixed,
                                                 .doc = "|r - a| - L",
                                                 .flags = 0};
static const dal_primitive rel_prim_rod_pair = {.name = "rel_rod_pair",
                                                .version = 1,
                                                .nin = 4,
                                                .nout = 1,
                                                .nparam = 1,
                                                .eval = rel_rod_pair,
                                                .doc = "|r_b - r_a| - L",
                                                .flags = 0};

/// a weak velocity-dependent force read from a const context (shared read-only by threads)
typedef struct rel_drag {
  double c;
} rel_drag;

static inline int rel_drag_force(double t, const double *r, const double *v, double *F, void *ctx) {
  const rel_drag *d = ctx;
  (void)r;
  for (int i = 0; i < 4; ++i)
    F[i] -= d->c * v[i] * (1.0 + 0.1 * sin(t));
  return 0;
}

static const rel_drag rel_drag_ctx = {0.05};

/// double pendulum (l1 = 1, l2 = 0.7, m1 = 1, m2 = 0.5) with drag; minimal (ODE) when
/// dae == 0, Cartesian with two rods (DAE) otherwise. Returns the compiled system or NULL.
static inline dal_system *rel_double_pendulum(int dae) {
  dal_builder *b = NULL;
  int rc = scn_builder(NULL, 2, &b), p[2] = {0, 0};
  if (!dae) {
    if (!rc) rc = scn_add_swing(b, NULL, "upper", 1.0, -1, 1.0, "th1", &p[0]);
    if (!rc) rc = scn_add_swing(b, NULL, "lower", 0.5, p[0], 0.7, "th2", &p[1]);
  } else {
    // the rods as user primitives (read-only contexts shared by threads)
    double rod1[3] = {1.0, 0.0, 0.0}, rod2 = 0.7;
    if (!rc) rc = scn_add_xy(b, "upper", 1.0, "x1", "y1", &p[0]);
    if (!rc) rc = scn_add_xy(b, "lower", 0.5, "x2", "y2", &p[1]);
    dal_constraint_def cd = dal_default_constraint_def();
    cd.name = "rod1";
    cd.prim = &rel_prim_rod_fixed;
    cd.parts = &p[0];
    cd.nparts = 1;
    cd.param_list = rod1;
    cd.nparam_list = 3;
    if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
    cd.name = "rod2";
    cd.prim = &rel_prim_rod_pair;
    cd.parts = p;
    cd.nparts = 2;
    cd.param_list = &rod2;
    cd.nparam_list = 1;
    if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
  }
  if (!rc) rc = dal_builder_add_force(b, rel_drag_force, (void *)&rel_drag_ctx);
  return scn_finish(b, rc);
}

/// a consistent initial state from the two angles and their rates
static inline int rel_set(const dal_system *sys, dal_state *st, int dae, double th1, double th2,
                          double w1, double w2) {
  if (!dae) {
    double q[2] = {th1, th2}, qd[2] = {w1, w2};
    return dal_state_set(sys, st, 0.0, q, qd);
  }
  double l2 = 0.7;
  double q[4] = {sin(th1), -cos(th1), sin(th1) + l2 * sin(th2), -cos(th1) - l2 * cos(th2)};
  double qd[4] = {cos(th1) * w1, sin(th1) * w1, cos(th1) * w1 + l2 * cos(th2) * w2,
                  sin(th1) * w1 + l2 * sin(th2) * w2};
  return dal_state_set(sys, st, 0.0, q, qd);
}

/// a recording of (t, q, qdot, lambda) at every output time
typedef struct rel_rec {
  double *buf;
  size_t len, cap;
} rel_rec;

static inline int rel_record(const dal_system *sys, const dal_state *st, void *ctx) {
  rel_rec *r = ctx;
  int n = dal_system_ncoords(sys), m = dal_system_nconstraints(sys);
  size_t need = 1 + 2 * (size_t)n + (size_t)m;
  if (r->len + need > r->cap) return -1; // the caller sized the buffer
  r->buf[r->len++] = dal_state_time(st);
  memcpy(r->buf + r->len, dal_state_q(st), (size_t)n * sizeof(double));
  r->len += (size_t)n;
  memcpy(r->buf + r->len, dal_state_qdot(st), (size_t)n * sizeof(double));
  r->len += (size_t)n;
  if (m) {
    memcpy(r->buf + r->len, dal_state_lambda(st), (size_t)m * sizeof(double));
    r->len += (size_t)m;
  }
  return 0;
}

#endif
