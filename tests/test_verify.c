// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The verification kit passes every built-in and catches deliberately wrong derivatives.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

static int has(const char *msg, const char *what) { return msg && strstr(msg, what) != NULL; }

// contexts the built-ins with a context take
static int curve2(dal_jet s, dal_jet t, dal_jet *p, void *ctx) {
  (void)ctx;
  p[0] = dal_add(dal_cos(s), dal_scale(t, 0.1));
  p[1] = dal_mul(dal_sin(dal_scale(s, 2.0)), dal_addc(dal_scale(t, 0.2), 1.0));
  return 0;
}
static int curve3(dal_jet s, dal_jet t, dal_jet *p, void *ctx) {
  (void)ctx;
  p[0] = dal_cos(s);
  p[1] = dal_sin(s);
  p[2] = dal_mul(s, t);
  return 0;
}
static int mover(dal_jet t, dal_jet *x, void *ctx) {
  (void)ctx;
  x[0] = dal_scale(dal_sin(t), 0.3);
  x[1] = dal_scale(dal_mul(t, t), 0.2);
  x[2] = dal_cos(t);
  return 0;
}
static int drive(dal_jet t, dal_jet *f, void *ctx) {
  (void)ctx;
  *f = dal_sin(dal_scale(t, 3.0));
  return 0;
}

static void *ctx_for(const dal_primitive *p) {
  static const dal_curve c2 = {curve2, NULL}, c3 = {curve3, NULL};
  static const dal_moving_point mp = {mover, NULL};
  static const dal_prescribed pr = {drive, NULL};
  if (p == &dal_map_curve2) return (void *)&c2;
  if (p == &dal_map_curve3) return (void *)&c3;
  if (p == &dal_con_anchor2 || p == &dal_con_anchor3) return (void *)&mp;
  if (p == &dal_con_prescribed) return (void *)&pr;
  return NULL;
}

static void test_builtins_pass(void) {
  for (int i = 0; i < dal_primitive_count(); ++i) {
    const dal_primitive *p = dal_primitive_get(i);
    double param[16];
    for (int k = 0; k < p->nparam; ++k)
      param[k] = 0.5 + 0.15 * k;
    dal_verify_report rep;
    int rc = dal_verify_primitive(p, param, ctx_for(p), NULL, &rep);
    CHECK_MSG(rc == DAL_OK, "%s (status %d)", rep.msg, rc);
    CHECK(rep.samples == 16 && rep.checks == 32 * p->nout && rep.failures == 0);
    CHECK(rep.worst <= 10.0);
  }
}

// sin(u) with a wrong first derivative (1.001 cos u), and one without the curvature term
static int bad_first(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)p;
  (void)ctx;
  double s = sin(in[0].v), c = cos(in[0].v);
  out[0] = dal_jet_chain(in[0], s, 1.001 * c, -s);
  return 0;
}
static int bad_second(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)p;
  (void)ctx;
  // u^2 t: the mixed term 2 (2u) du dt of the second derivative is left out
  dal_jet u2 = dal_mul(in[0], in[0]);
  out[0] = dal_jet_make(u2.v * t.v, u2.d * t.v + u2.v * t.d, u2.dd * t.v + u2.v * t.dd);
  return 0;
}
static int good_prod(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)p;
  (void)ctx;
  out[0] = dal_mul(dal_mul(in[0], in[0]), t);
  return 0;
}

static void test_wrong_caught(void) {
  const dal_primitive b1 = {
      .name = "bad_first", .version = 1, .nin = 1, .nout = 1, .eval = bad_first};
  const dal_primitive b2 = {
      .name = "bad_second", .version = 1, .nin = 1, .nout = 1, .eval = bad_second};
  const dal_primitive g2 = {
      .name = "good_prod", .version = 1, .nin = 1, .nout = 1, .eval = good_prod};
  dal_verify_report rep;
  CHECK(dal_verify_primitive(&b1, NULL, NULL, NULL, &rep) == DAL_E_VERIFY);
  CHECK(rep.failures > 0 && rep.worst_order == 1 && rep.worst > 10.0);
  CHECK(has(rep.msg, "'bad_first'") && has(rep.msg, "DISAGREE"));
  // the error of the wrong derivative is 0.001 cos u: far above the derived bound
  CHECK_CLOSE(rep.worst_jet - rep.worst_fd, 0.001 * rep.worst_fd / 1.001, 1e-6);
  CHECK(dal_verify_primitive(&b2, NULL, NULL, NULL, &rep) == DAL_E_VERIFY);
  CHECK(rep.worst_order == 2 && has(rep.msg, "second"));
  CHECK_OK(dal_verify_primitive(&g2, NULL, NULL, NULL, &rep));
  // a required parameter without a value is an argument error
  CHECK(dal_verify_primitive(&dal_map_pendulum, NULL, NULL, NULL, &rep) == DAL_E_ARG);
  // outside the domain: sqrt of negative inputs is reported as such
}

// a map, potentials and a Lagrangian: right ones pass, wrong ones are caught
static int ring_map(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx) {
  double w = *(const double *)ctx;
  dal_jet a = dal_scale(t, w), s = dal_sin(q[0]);
  r[0] = dal_mul(s, dal_cos(a));
  r[1] = dal_mul(s, dal_sin(a));
  r[2] = dal_neg(dal_cos(q[0]));
  return 0;
}
static int coulomb(const dal_jet *r, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet d[2] = {dal_addc(r[0], 3.0), dal_addc(r[1], -0.5)};
  *U = dal_div(dal_const(1.0), dal_norm(d, 2));
  return 0;
}
static int wrong_quartic(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  // q^4 / 4 with the derivative of q^3 / 3 (a typo a user makes)
  double x = q[0].v;
  *U = dal_jet_chain(q[0], 0.25 * x * x * x * x, x * x, 2 * x);
  return 0;
}
static int lag_ok(dal_jet t, const dal_jet *q, const dal_jet *qd, dal_jet *L, void *ctx) {
  (void)ctx;
  *L = dal_sub(dal_scale(dal_mul(qd[0], qd[0]), 0.5), dal_mul(dal_cos(q[0]), dal_addc(t, 1.0)));
  *L = dal_add(*L, dal_mul(qd[1], dal_mul(q[0], qd[0])));
  return 0;
}

static void test_functions(void) {
  dal_verify_report rep;
  double w = 2.5;
  CHECK_OK(dal_verify_map(ring_map, 1, 1, 3, NULL, &rep, &w));
  CHECK(rep.checks == 2 * 3 * 16);
  CHECK_OK(dal_verify_potential_r(coulomb, 1, 2, NULL, &rep, NULL));
  CHECK(dal_verify_potential_q(wrong_quartic, 1, NULL, &rep, NULL) == DAL_E_VERIFY);
  CHECK(has(rep.msg, "potential U(q, t)"));
  CHECK_OK(dal_verify_lagrangian(lag_ok, 2, NULL, &rep, NULL));
  CHECK(dal_verify_map(ring_map, 1, 1, 4, NULL, &rep, &w) == DAL_E_ARG);
}

// model checks ----------------------------------------------------------------------------

static int quartic_ok(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet q2 = dal_mul(q[0], q[0]);
  *U = dal_scale(dal_mul(q2, q2), 0.25);
  return 0;
}

// a pendulum plus U(q); with a wrong potential the force check fails by name
static int model_pendulum(dal_potential_q_fn *pot) {
  dal_builder *b = NULL;
  int th, bob;
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "theta", &th));
  CHECK_OK(dal_builder_add_particle(b, "bob", 1.0, &bob));
  CHECK_OK(scn_place_swing(b, NULL, bob, -1, 1.0, th));
  double g[2] = {0, -9.81};
  CHECK_OK(dal_builder_set_gravity(b, g));
  CHECK_OK(dal_builder_add_potential_q(b, pot, NULL));
  dal_system *sys = NULL;
  CHECK_OK(dal_builder_compile(b, &sys));
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q = 0.7, v = 0.3;
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &v));
  dal_model_report rep;
  int rc = dal_verify_model(sys, st, NULL, &rep);
  if (pot == quartic_ok) {
    CHECK_MSG(rc == DAL_OK && rep.passed, "%s", rep.msg);
    CHECK(rep.mass_checked && rep.force_checked && rep.path_checked);
    CHECK(rep.path_residual < 1e-6);
  } else {
    CHECK(rc == DAL_E_VERIFY && !rep.passed);
    CHECK_MSG(has(rep.msg, "forces") && has(rep.msg, "'theta'"), "%s", rep.msg);
  }
  CHECK(dal_state_q(st)[0] == 0.7 && dal_state_time(st) == 0.0); // left where it was
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
  return rc;
}

// Cartesian double pendulum with rods (m = 2): the residual equals G' lambda; a third,
// redundant rod is caught by the rank check
static void test_model_constrained(int redundant) {
  dal_builder *b = NULL;
  int c[4], p[2];
  CHECK_OK(dal_builder_create(2, &b));
  const char *names[4] = {"x1", "y1", "x2", "y2"};
  for (int i = 0; i < 4; ++i)
    CHECK_OK(dal_builder_add_coord(b, names[i], &c[i]));
  CHECK_OK(dal_builder_add_particle(b, "a", 1.0, &p[0]));
  CHECK_OK(dal_builder_add_particle(b, "b", 2.0, &p[1]));
  for (int k = 0; k < 2; ++k) {
    dal_place_def d = dal_default_place_def();
    d.prim = &dal_map_cartesian2;
    d.coords = c + 2 * k;
    d.ncoords = 2;
    CHECK_OK(dal_builder_place_def(b, p[k], &d));
  }
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = "rod1";
  cd.prim = &dal_con_anchor2;
  cd.parts = &p[0];
  cd.nparts = 1;
  cd.param[DAL_ANCHOR_L] = 1.0;
  CHECK_OK(dal_builder_add_constraint_def(b, &cd, NULL));
  cd = dal_default_constraint_def();
  cd.name = "rod2";
  cd.prim = &dal_con_distance2;
  cd.parts = p;
  cd.nparts = 2;
  cd.param[DAL_DISTANCE_L] = 1.0;
  CHECK_OK(dal_builder_add_constraint_def(b, &cd, NULL));
  if (redundant) {
    cd.name = "rod2_again";
    CHECK_OK(dal_builder_add_constraint_def(b, &cd, NULL));
  }
  double g[2] = {0, -9.81};
  CHECK_OK(dal_builder_set_gravity(b, g));
  dal_system *sys = NULL;
  CHECK_OK(dal_builder_compile(b, &sys));
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q[4] = {sin(0.5), -cos(0.5), sin(0.5) + sin(1.0), -cos(0.5) - cos(1.0)};
  double v[4] = {0, 0, 0, 0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
  dal_model_report rep;
  int rc = dal_verify_model(sys, st, NULL, &rep);
  if (!redundant) {
    CHECK_MSG(rc == DAL_OK, "%s", rep.msg);
    CHECK(rep.rank == 2 && rep.m == 2 && rep.path_checked && rep.path_residual < 1e-6);
  } else {
    CHECK(rc == DAL_E_VERIFY || rc == DAL_E_CONSTRAINT);
    CHECK_MSG(has(rep.msg, "rod2") || has(dal_state_errmsg(st), "rod2"), "%s", rep.msg);
  }
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
}

int main(void) {
  test_builtins_pass();
  test_wrong_caught();
  test_functions();
  CHECK(model_pendulum(quartic_ok) == DAL_OK);
  CHECK(model_pendulum(wrong_quartic) == DAL_E_VERIFY);
  test_model_constrained(0);
  test_model_constrained(1);
  return check_summary("test_verify");
}
