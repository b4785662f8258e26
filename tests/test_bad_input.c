// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Bad-input suite: every row provokes one failure and checks the exact status, that the
// error message names the culprit, that the object survives holding its last good state,
// and that fixing the cause lets the user continue. Leaks are caught by the sanitizer build
// (LeakSanitizer) and scripts/valgrind.sh.
//
// A row is a function that sets up a scene, makes the failing call, copies the message,
// checks survival and recovery itself, frees everything, and returns the failing call's
// status; the table says which status and which culprit names the message must contain.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"

#define MSG_LEN 512

typedef struct bad_row {
  const char *name;
  int expect;          // the exact status
  const char *culprit; // substrings the message must contain (NULL: none)
  const char *culprit2;
  int (*run)(char *msg);
} bad_row;

static void copy_msg(char *msg, const char *s) { snprintf(msg, MSG_LEN, "%s", s ? s : ""); }

// ---------------------------------------------------------------- scenes
static const double g2[2] = {0.0, -9.81}, g3[3] = {0.0, 0.0, -9.81};

// planar pendulum in minimal coordinates: coordinate 'theta', particle 'bob' (1 kg, 1 m)
static int pendulum(dal_builder **b, dal_system **sys, dal_state **st) {
  int th, bob;
  double par[7] = {1.0, 0, 0, 0, 0, 0, 0};
  int rc = dal_builder_create(2, b);
  if (!rc) rc = dal_builder_add_coord(*b, "theta", &th);
  if (!rc) rc = dal_builder_add_particle(*b, "bob", 1.0, &bob);
  if (!rc) rc = dal_builder_place(*b, bob, &dal_map_pendulum, -1, 1, &th, 7, par, NULL);
  if (!rc) rc = dal_builder_set_gravity(*b, g2);
  if (!rc && sys) rc = dal_builder_compile(*b, sys);
  if (!rc && st) rc = dal_state_create(*sys, st);
  return rc;
}

// a free particle 'bob' in the plane, coordinates 'x', 'y' (the identity map)
static int free2(dal_builder **b, int *bob) {
  int c[2];
  int rc = dal_builder_create(2, b);
  if (!rc) rc = dal_builder_add_coord(*b, "x", &c[0]);
  if (!rc) rc = dal_builder_add_coord(*b, "y", &c[1]);
  if (!rc) rc = dal_builder_add_particle(*b, "bob", 2.0, bob);
  if (!rc) rc = dal_builder_place(*b, *bob, &dal_map_cartesian2, -1, 2, c, 0, NULL, NULL);
  return rc;
}

static void destroy_all(dal_builder *b, dal_system *sys, dal_state *st) {
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
}

// compile and evaluate a builder's model at q = qd = 0.1: the "continue" step of a row
static int compiles_and_runs(dal_builder *b) {
  dal_system *sys = NULL;
  dal_state *st = NULL;
  int rc = dal_builder_compile(b, &sys);
  if (!rc) rc = dal_state_create(sys, &st);
  double q[8], qd[8];
  for (int i = 0; i < 8; ++i) q[i] = qd[i] = 0.1 * (i + 1);
  if (!rc) rc = dal_state_set(sys, st, 0.0, q, qd);
  if (!rc) rc = dal_forward(sys, st);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  return rc;
}

// ---------------------------------------------------------------- builder rows
static int row_dim(char *msg) {
  dal_builder *b = (dal_builder *)&msg; // must be overwritten with NULL
  int rc = dal_builder_create(4, &b);
  copy_msg(msg, "");
  CHECK(b == NULL);
  CHECK_OK(dal_builder_create(3, &b));
  dal_builder_destroy(b);
  return rc;
}

// add_particle with a bad mass; the failed call must not consume an index
static int mass_row(char *msg, double mass) {
  dal_builder *b = NULL;
  int th, idx = -7;
  double par[7] = {1.0, 0, 0, 0, 0, 0, 0};
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "theta", &th));
  int rc = dal_builder_add_particle(b, "bob", mass, &idx);
  copy_msg(msg, dal_builder_errmsg(b));
  CHECK(idx == -7);
  CHECK_OK(dal_builder_add_particle(b, "bob", 1.0, &idx));
  CHECK(idx == 0);
  CHECK_OK(dal_builder_place(b, idx, &dal_map_pendulum, -1, 1, &th, 7, par, NULL));
  CHECK_OK(compiles_and_runs(b));
  dal_builder_destroy(b);
  return rc;
}
static int row_mass_nan(char *msg) { return mass_row(msg, NAN); }
static int row_mass_inf(char *msg) { return mass_row(msg, INFINITY); }
static int row_mass_zero(char *msg) { return mass_row(msg, 0.0); }
static int row_mass_negative(char *msg) { return mass_row(msg, -1.0); }

// dal_builder_place with one thing wrong, then the right call
typedef struct place_case {
  int particle, ncoords, coord0, nparam;
  double l;
  const dal_primitive *prim;
} place_case;

static int place_row(char *msg, place_case pc) {
  dal_builder *b = NULL;
  int th, bob;
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "theta", &th));
  CHECK_OK(dal_builder_add_particle(b, "bob", 1.0, &bob));
  double par[8] = {pc.l, 0, 0, 0, 0, 0, 0, 0};
  int coords[2] = {pc.coord0, th};
  int rc = dal_builder_place(b, pc.particle, pc.prim, -1, pc.ncoords, coords, pc.nparam, par,
                             NULL);
  copy_msg(msg, dal_builder_errmsg(b));
  // the failed placement left no trace: the particle can still be placed, once
  par[0] = 1.0;
  CHECK_OK(dal_builder_place(b, bob, &dal_map_pendulum, -1, 1, &th, 7, par, NULL));
  CHECK(dal_builder_place(b, bob, &dal_map_pendulum, -1, 1, &th, 7, par, NULL) == DAL_E_ARG);
  CHECK_OK(compiles_and_runs(b));
  dal_builder_destroy(b);
  return rc;
}
static int row_place_particle_index(char *msg) {
  return place_row(msg, (place_case){5, 1, 0, 7, 1.0, &dal_map_pendulum});
}
static int row_place_coord_index(char *msg) {
  return place_row(msg, (place_case){0, 1, 3, 7, 1.0, &dal_map_pendulum});
}
static int row_place_negative_coord(char *msg) {
  return place_row(msg, (place_case){0, 1, -1, 7, 1.0, &dal_map_pendulum});
}
static int row_place_ninputs(char *msg) {
  return place_row(msg, (place_case){0, 2, 0, 7, 1.0, &dal_map_pendulum});
}
static int row_place_nparams(char *msg) {
  return place_row(msg, (place_case){0, 1, 0, 3, 1.0, &dal_map_pendulum});
}
static int row_place_nan_param(char *msg) {
  return place_row(msg, (place_case){0, 1, 0, 7, NAN, &dal_map_pendulum});
}
static int row_place_inf_param(char *msg) {
  return place_row(msg, (place_case){0, 1, 0, 7, -INFINITY, &dal_map_pendulum});
}
static int row_place_wrong_dim(char *msg) {
  return place_row(msg, (place_case){0, 2, 0, 4, 1.0, &dal_map_spherical});
}
static int row_place_null_prim(char *msg) {
  return place_row(msg, (place_case){0, 1, 0, 7, 1.0, NULL});
}

static int row_place_parent_order(char *msg) {
  dal_builder *b = NULL;
  int th[2], p[2];
  double par[7] = {1.0, 0, 0, 0, 0, 0, 0}, l = 1.0;
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "th1", &th[0]));
  CHECK_OK(dal_builder_add_coord(b, "th2", &th[1]));
  CHECK_OK(dal_builder_add_particle(b, "upper", 1.0, &p[0]));
  CHECK_OK(dal_builder_add_particle(b, "lower", 1.0, &p[1]));
  // the lower bob hangs from the upper one, which is not placed yet
  int rc = dal_builder_place(b, p[1], &dal_map_hanging, p[0], 1, &th[1], 1, &l, NULL);
  copy_msg(msg, dal_builder_errmsg(b));
  CHECK_OK(dal_builder_place(b, p[0], &dal_map_pendulum, -1, 1, &th[0], 7, par, NULL));
  CHECK_OK(dal_builder_place(b, p[1], &dal_map_hanging, p[0], 1, &th[1], 1, &l, NULL));
  CHECK_OK(compiles_and_runs(b));
  dal_builder_destroy(b);
  return rc;
}

// a user constraint primitive: |r_b - r_a| - L in 2D (inputs: both particles)
static int rod2(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  out[0] = dal_addc(dal_hypot(dal_sub(in[2], in[0]), dal_sub(in[3], in[1])), -p[0]);
  return 0;
}
static const dal_primitive user_rod2 = {"user_rod2", 1, 4, 1, 1, rod2, "|b - a| - L (2D)"};

// two free particles 'a' and 'b' in the plane (coordinates xa, ya, xb, yb)
static int two_free(dal_builder **b, int *pa, int *pb) {
  int c[4];
  const char *names[4] = {"xa", "ya", "xb", "yb"};
  int rc = dal_builder_create(2, b);
  for (int i = 0; i < 4 && !rc; ++i) rc = dal_builder_add_coord(*b, names[i], &c[i]);
  if (!rc) rc = dal_builder_add_particle(*b, "a", 1.0, pa);
  if (!rc) rc = dal_builder_add_particle(*b, "b", 1.0, pb);
  if (!rc) rc = dal_builder_place(*b, *pa, &dal_map_cartesian2, -1, 2, c, 0, NULL, NULL);
  if (!rc) rc = dal_builder_place(*b, *pb, &dal_map_cartesian2, -1, 2, c + 2, 0, NULL, NULL);
  return rc;
}

typedef struct con_case {
  int part1, nparts, ncoords, nparam;
  double L;
} con_case;

static int constraint_row(char *msg, con_case cc) {
  dal_builder *b = NULL;
  int pa, pb, row = -5, coord = 0;
  CHECK_OK(two_free(&b, &pa, &pb));
  int parts[2] = {pa, cc.part1};
  double L = cc.L;
  int rc = dal_builder_add_constraint(b, "rod", &user_rod2, cc.nparts, parts, cc.ncoords,
                                      &coord, cc.nparam, &L, NULL, &row);
  copy_msg(msg, dal_builder_errmsg(b));
  CHECK(row == -5);
  parts[1] = pb;
  L = 1.0;
  CHECK_OK(dal_builder_add_constraint(b, "rod", &user_rod2, 2, parts, 0, NULL, 1, &L, NULL,
                                      &row));
  CHECK(row == 0); // the failed call added no rows
  dal_system *sys = NULL;
  CHECK_OK(dal_builder_compile(b, &sys));
  CHECK(dal_system_nconstraints(sys) == 1);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
  return rc;
}
static int row_con_particle_index(char *msg) {
  return constraint_row(msg, (con_case){9, 2, 0, 1, 1.0});
}
static int row_con_ninputs(char *msg) {
  return constraint_row(msg, (con_case){1, 2, 1, 1, 1.0});
}
static int row_con_nan_param(char *msg) {
  return constraint_row(msg, (con_case){1, 2, 0, 1, NAN});
}
static int row_con_nparams(char *msg) {
  return constraint_row(msg, (con_case){1, 2, 0, 0, 1.0});
}

static int row_gravity_nan(char *msg) {
  dal_builder *b = NULL;
  CHECK_OK(pendulum(&b, NULL, NULL));
  double g[2] = {0.0, NAN};
  int rc = dal_builder_set_gravity(b, g);
  copy_msg(msg, dal_builder_errmsg(b));
  CHECK_OK(compiles_and_runs(b));
  dal_builder_destroy(b);
  return rc;
}

// springs and dampers: bad coefficient, length, index or anchor
typedef struct link_case {
  int kind; // 0 spring, 1 anchor spring, 2 damper
  int pb;
  double k, L, x0;
} link_case;

static int link_row(char *msg, link_case lc) {
  dal_builder *b = NULL;
  int pa, pb;
  CHECK_OK(two_free(&b, &pa, &pb));
  double x0[2] = {lc.x0, 0.0};
  int rc = lc.kind == 0   ? dal_builder_add_spring(b, pa, lc.pb, lc.k, lc.L)
           : lc.kind == 1 ? dal_builder_add_anchor_spring(b, pa, x0, NULL, NULL, lc.k, lc.L)
                          : dal_builder_add_damper(b, pa, lc.pb, lc.k);
  copy_msg(msg, dal_builder_errmsg(b));
  CHECK_OK(dal_builder_add_spring(b, pa, pb, 10.0, 1.0));
  CHECK_OK(compiles_and_runs(b));
  dal_builder_destroy(b);
  return rc;
}
static int row_spring_negative_k(char *msg) {
  return link_row(msg, (link_case){0, 1, -3.0, 1.0, 0.0});
}
static int row_spring_nan_length(char *msg) {
  return link_row(msg, (link_case){0, 1, 3.0, NAN, 0.0});
}
static int row_spring_self(char *msg) { return link_row(msg, (link_case){0, 0, 3.0, 1.0, 0.0}); }
static int row_anchor_inf(char *msg) {
  return link_row(msg, (link_case){1, -1, 3.0, 1.0, INFINITY});
}
static int row_damper_index(char *msg) {
  return link_row(msg, (link_case){2, 7, 0.5, 0.0, 0.0});
}
static int row_damper_inf(char *msg) {
  return link_row(msg, (link_case){2, 1, INFINITY, 0.0, 0.0});
}

static int row_compile_unplaced(char *msg) {
  dal_builder *b = NULL;
  dal_system *sys = (dal_system *)&msg; // must be overwritten with NULL
  int th, bob, extra;
  double par[7] = {1.0, 0, 0, 0, 0, 0, 0};
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "theta", &th));
  CHECK_OK(dal_builder_add_particle(b, "bob", 1.0, &bob));
  CHECK_OK(dal_builder_add_particle(b, "stray", 1.0, &extra));
  CHECK_OK(dal_builder_place(b, bob, &dal_map_pendulum, -1, 1, &th, 7, par, NULL));
  int rc = dal_builder_compile(b, &sys);
  copy_msg(msg, dal_builder_errmsg(b));
  CHECK(sys == NULL);
  par[2] = -1.0;
  CHECK_OK(dal_builder_place(b, extra, &dal_map_pendulum, -1, 1, &th, 7, par, NULL));
  CHECK_OK(compiles_and_runs(b));
  dal_builder_destroy(b);
  return rc;
}

static int row_compile_no_coords(char *msg) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  int bob;
  double x[2] = {0.0, 1.0};
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_particle(b, "bob", 1.0, &bob));
  CHECK_OK(dal_builder_place(b, bob, &dal_map_fixed2, -1, 0, NULL, 2, x, NULL));
  int rc = dal_builder_compile(b, &sys);
  copy_msg(msg, dal_builder_errmsg(b));
  CHECK(sys == NULL);
  dal_builder_destroy(b);
  return rc;
}

static int lag_free(dal_jet t, const dal_jet *q, const dal_jet *qd, dal_jet *L, void *ctx) {
  (void)t;
  (void)q;
  (void)ctx;
  *L = dal_scale(dal_sq(qd[0]), 0.5); // no kinetic term for q[1]: d2L/dqdot2 singular
  return 0;
}

static int row_lagrangian_particle(char *msg) {
  dal_builder *b = NULL;
  int x, p = -3;
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "x", &x));
  CHECK_OK(dal_builder_set_lagrangian(b, lag_free, NULL));
  int rc = dal_builder_add_particle(b, "bob", 1.0, &p);
  copy_msg(msg, dal_builder_errmsg(b));
  CHECK(p == -3);
  CHECK_OK(compiles_and_runs(b));
  dal_builder_destroy(b);
  return rc;
}

// ---------------------------------------------------------------- state rows
// dal_state_set with one bad value: the state keeps its previous (t, q, qdot)
static int set_row(char *msg, double t, double q, double qd) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  CHECK_OK(pendulum(&b, &sys, &st));
  double q0 = 0.4, qd0 = -0.2;
  CHECK_OK(dal_state_set(sys, st, 1.5, &q0, &qd0));
  CHECK_OK(dal_forward(sys, st));
  double acc = dal_state_qddot(st)[0];
  int rc = dal_state_set(sys, st, t, &q, &qd);
  copy_msg(msg, dal_state_errmsg(st));
  CHECK(dal_state_time(st) == 1.5 && dal_state_q(st)[0] == q0 && dal_state_qdot(st)[0] == qd0);
  // evaluating again gives the same physics as before the failed call
  CHECK_OK(dal_forward(sys, st));
  CHECK(dal_state_qddot(st)[0] == acc);
  CHECK_CLOSE(acc, -9.81 * sin(q0), 1e-13);
  destroy_all(b, sys, st);
  return rc;
}
static int row_set_nan_q(char *msg) { return set_row(msg, 0.0, NAN, 0.0); }
static int row_set_inf_qdot(char *msg) { return set_row(msg, 0.0, 0.1, -INFINITY); }
static int row_set_nan_t(char *msg) { return set_row(msg, NAN, 0.1, 0.0); }

static int row_foreign_state(char *msg) {
  dal_builder *b1 = NULL, *b2 = NULL;
  dal_system *s1 = NULL, *s2 = NULL;
  dal_state *st = NULL;
  CHECK_OK(pendulum(&b1, &s1, &st));
  CHECK_OK(pendulum(&b2, &s2, NULL));
  double q = 0.3, qd = 0.0;
  CHECK_OK(dal_state_set(s1, st, 0.0, &q, &qd));
  int rc = dal_forward(s2, st);
  copy_msg(msg, dal_state_errmsg(st));
  CHECK(dal_state_set(s2, st, 0.0, &q, &qd) == DAL_E_STATE);
  CHECK(dal_state_q(st)[0] == q);
  CHECK_OK(dal_forward(s1, st));
  destroy_all(b1, s1, st);
  destroy_all(b2, s2, NULL);
  return rc;
}

// spherical pendulum in minimal coordinates at its pole: phi moves no mass
static int spherical(dal_builder **b, dal_system **sys, dal_state **st) {
  int c[2], bob;
  double par[4] = {1.0, 0, 0, 0};
  int rc = dal_builder_create(3, b);
  if (!rc) rc = dal_builder_add_coord(*b, "theta", &c[0]);
  if (!rc) rc = dal_builder_add_coord(*b, "phi", &c[1]);
  if (!rc) rc = dal_builder_add_particle(*b, "bob", 1.0, &bob);
  if (!rc) rc = dal_builder_place(*b, bob, &dal_map_spherical, -1, 2, c, 4, par, NULL);
  if (!rc) rc = dal_builder_set_gravity(*b, g3);
  if (!rc) rc = dal_builder_compile(*b, sys);
  if (!rc) rc = dal_state_create(*sys, st);
  return rc;
}

static int row_forward_pole(char *msg) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  CHECK_OK(spherical(&b, &sys, &st));
  double q[2] = {0.0, 0.3}, qd[2] = {1.0, 0.0};
  CHECK_OK(dal_state_set(sys, st, 0.25, q, qd));
  int rc = dal_forward(sys, st);
  copy_msg(msg, dal_state_errmsg(st));
  CHECK(dal_state_time(st) == 0.25 && dal_state_q(st)[0] == 0.0 && dal_state_q(st)[1] == 0.3);
  // off the pole the chart is fine: theta'' = -g/l sin theta + sin theta cos theta phidot^2
  q[0] = 0.5;
  CHECK_OK(dal_state_set(sys, st, 0.25, q, qd));
  CHECK_OK(dal_forward(sys, st));
  CHECK_CLOSE(dal_state_qddot(st)[0], -9.81 * sin(0.5), 1e-13);
  destroy_all(b, sys, st);
  return rc;
}

// a force callback whose behaviour the row controls
typedef struct force_ctx {
  int mode;       // 0 fine, 1 NaN, 2 recoverable (> 0), 3 stop (< 0)
  double t_fail;  // misbehave only at t >= t_fail
  int n_fail;     // misbehave at most this many times (-1: always)
  int calls, fails;
} force_ctx;

static int force_cb(double t, const double *r, const double *v, double *F, void *ctx) {
  force_ctx *c = ctx;
  (void)v;
  c->calls++;
  F[0] += -4.0 * r[0]; // a spring to the origin along x
  if (c->mode == 0 || t < c->t_fail || (c->n_fail >= 0 && c->fails >= c->n_fail)) return 0;
  c->fails++;
  if (c->mode == 1) {
    F[1] = NAN;
    return 0;
  }
  return c->mode == 2 ? 1 : -2;
}

// free particle with the force callback; forward fails, then the fixed callback works
static int force_row(char *msg, int mode) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  int bob;
  force_ctx fc = {mode, 0.0, -1, 0, 0};
  CHECK_OK(free2(&b, &bob));
  CHECK_OK(dal_builder_add_force(b, force_cb, &fc));
  CHECK_OK(dal_builder_compile(b, &sys));
  CHECK_OK(dal_state_create(sys, &st));
  double q[2] = {0.5, 0.0}, qd[2] = {0.0, 0.0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, qd));
  int rc = dal_forward(sys, st);
  copy_msg(msg, dal_state_errmsg(st));
  CHECK(dal_state_q(st)[0] == 0.5 && dal_state_time(st) == 0.0);
  fc.mode = 0;
  CHECK_OK(dal_forward(sys, st));
  CHECK_CLOSE(dal_state_qddot(st)[0], -4.0 * 0.5 / 2.0, 1e-15);
  destroy_all(b, sys, st);
  return rc;
}
static int row_force_nan(char *msg) { return force_row(msg, 1); }
static int row_force_recoverable_forward(char *msg) { return force_row(msg, 2); }
static int row_force_stop(char *msg) { return force_row(msg, 3); }

// U(r) = -1/|r|: its gradient is not finite at the origin
static int pot_kepler(const dal_jet *r, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  *U = dal_div(dal_const(-1.0), dal_hypot(r[0], r[1]));
  return 0;
}

static int row_potential_r_domain(char *msg) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  int bob;
  CHECK_OK(free2(&b, &bob));
  CHECK_OK(dal_builder_add_potential_r(b, pot_kepler, NULL));
  CHECK_OK(dal_builder_compile(b, &sys));
  CHECK_OK(dal_state_create(sys, &st));
  double q[2] = {0.0, 0.0}, qd[2] = {0.0, 0.0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, qd));
  int rc = dal_forward(sys, st);
  copy_msg(msg, dal_state_errmsg(st));
  q[0] = 2.0;
  CHECK_OK(dal_state_set(sys, st, 0.0, q, qd));
  CHECK_OK(dal_forward(sys, st));
  CHECK_CLOSE(dal_state_qddot(st)[0], -1.0 / 4.0 / 2.0, 1e-15); // -1/r^2 / m
  destroy_all(b, sys, st);
  return rc;
}

// U(q) = -log(x): not finite for x <= 0
static int pot_log(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  *U = dal_neg(dal_log(q[0]));
  return 0;
}

static int row_potential_q_domain(char *msg) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  int bob;
  CHECK_OK(free2(&b, &bob));
  CHECK_OK(dal_builder_add_potential_q(b, pot_log, NULL));
  CHECK_OK(dal_builder_compile(b, &sys));
  CHECK_OK(dal_state_create(sys, &st));
  double q[2] = {-1.0, 0.0}, qd[2] = {0.0, 0.0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, qd));
  int rc = dal_forward(sys, st);
  copy_msg(msg, dal_state_errmsg(st));
  q[0] = 0.5;
  CHECK_OK(dal_state_set(sys, st, 0.0, q, qd));
  CHECK_OK(dal_forward(sys, st));
  CHECK_CLOSE(dal_state_qddot(st)[0], 1.0 / 0.5 / 2.0, 1e-15); // Q = 1/x, m = 2
  destroy_all(b, sys, st);
  return rc;
}

// generalized force returning NaN on the second coordinate
static int gen_nan(double t, const double *q, const double *qd, double *Q, void *ctx) {
  (void)t;
  (void)qd;
  const int *on = ctx;
  Q[0] -= q[0];
  if (*on) Q[1] = NAN;
  return 0;
}

static int row_genforce_nan(char *msg) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  int bob, on = 1;
  CHECK_OK(free2(&b, &bob));
  CHECK_OK(dal_builder_add_genforce(b, gen_nan, &on));
  CHECK_OK(dal_builder_compile(b, &sys));
  CHECK_OK(dal_state_create(sys, &st));
  double q[2] = {1.0, 0.0}, qd[2] = {0.0, 0.0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, qd));
  int rc = dal_forward(sys, st);
  copy_msg(msg, dal_state_errmsg(st));
  on = 0;
  CHECK_OK(dal_forward(sys, st));
  CHECK_CLOSE(dal_state_qddot(st)[0], -0.5, 1e-15);
  destroy_all(b, sys, st);
  return rc;
}

// a coordinate map with a domain: r = (sqrt(s), 0), undefined for s < 0
static int sqrt_map(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)p;
  (void)ctx;
  out[0] = dal_sqrt(in[0]);
  out[1] = dal_const(0.0);
  return 0;
}
static const dal_primitive user_sqrt = {"sqrtmap", 1, 1, 2, 0, sqrt_map, "(sqrt s, 0)"};

static int row_map_domain(char *msg) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  int s, bob;
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "s", &s));
  CHECK_OK(dal_builder_add_particle(b, "bob", 1.0, &bob));
  CHECK_OK(dal_builder_place(b, bob, &user_sqrt, -1, 1, &s, 0, NULL, NULL));
  CHECK_OK(dal_builder_compile(b, &sys));
  CHECK_OK(dal_state_create(sys, &st));
  double q = -0.5, qd = 0.0;
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &qd));
  int rc = dal_forward(sys, st);
  copy_msg(msg, dal_state_errmsg(st));
  CHECK(dal_state_q(st)[0] == -0.5);
  q = 4.0;
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &qd));
  CHECK_OK(dal_forward(sys, st));
  CHECK_CLOSE(dal_state_positions(st)[0], 2.0, 1e-15);
  destroy_all(b, sys, st);
  return rc;
}

// the curve primitive without its dal_curve context: its eval reports failure
static int circle_curve(dal_jet s, dal_jet t, dal_jet *p, void *ctx) {
  (void)t;
  (void)ctx;
  p[0] = dal_cos(s);
  p[1] = dal_sin(s);
  return 0;
}

static int row_curve_no_ctx(char *msg) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  int s, bob;
  dal_curve cv = {circle_curve, NULL};
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "s", &s));
  CHECK_OK(dal_builder_add_particle(b, "bead", 1.0, &bob));
  CHECK_OK(dal_builder_place(b, bob, &dal_map_curve2, -1, 1, &s, 0, NULL, NULL));
  CHECK_OK(dal_builder_compile(b, &sys));
  CHECK_OK(dal_state_create(sys, &st));
  double q = 0.5, qd = 1.0;
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &qd));
  int rc = dal_forward(sys, st);
  copy_msg(msg, dal_state_errmsg(st));
  // the fix: give the curve; a bead on a unit circle at unit speed has |a| = 1
  destroy_all(NULL, sys, st);
  dal_builder_destroy(b);
  b = NULL;
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "s", &s));
  CHECK_OK(dal_builder_add_particle(b, "bead", 1.0, &bob));
  CHECK_OK(dal_builder_place(b, bob, &dal_map_curve2, -1, 1, &s, 0, NULL, &cv));
  CHECK_OK(dal_builder_compile(b, &sys));
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &qd));
  CHECK_OK(dal_forward(sys, st));
  const double *a = dal_state_accelerations(st);
  CHECK_CLOSE(hypot(a[0], a[1]), 1.0, 1e-14);
  destroy_all(b, sys, st);
  return rc;
}

// a whole-system map that stops (returns < 0) when asked
static int map_stop(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx) {
  (void)t;
  r[0] = q[0];
  r[1] = dal_sin(q[0]);
  return *(const int *)ctx ? -4 : 0;
}

static int row_map_callback_stop(char *msg) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  int x, bob, stop = 1;
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "x", &x));
  CHECK_OK(dal_builder_add_particle(b, "bob", 1.0, &bob));
  CHECK_OK(dal_builder_set_map(b, map_stop, &stop));
  CHECK_OK(dal_builder_compile(b, &sys));
  CHECK_OK(dal_state_create(sys, &st));
  double q = 0.0, qd = 1.0;
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &qd));
  int rc = dal_forward(sys, st);
  copy_msg(msg, dal_state_errmsg(st));
  stop = 0;
  CHECK_OK(dal_forward(sys, st));
  // y = sin x, free (no forces): M = 1 + cos^2 x, c = cos x (-sin x) xdot^2 -> at x = 0, 0
  CHECK_CLOSE(dal_state_qddot(st)[0], 0.0, 1e-15);
  destroy_all(b, sys, st);
  return rc;
}

static int row_lagrangian_singular(char *msg) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  int c[2];
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "x", &c[0]));
  CHECK_OK(dal_builder_add_coord(b, "y", &c[1]));
  CHECK_OK(dal_builder_set_lagrangian(b, lag_free, NULL));
  CHECK_OK(dal_builder_compile(b, &sys));
  CHECK_OK(dal_state_create(sys, &st));
  double q[2] = {0.1, 0.2}, qd[2] = {0.3, 0.4};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, qd));
  int rc = dal_forward(sys, st);
  copy_msg(msg, dal_state_errmsg(st));
  CHECK(dal_state_q(st)[1] == 0.2 && dal_state_qdot(st)[1] == 0.4);
  destroy_all(b, sys, st);
  return rc;
}

// a proposed path that leaves its domain: theta(t) = sqrt(t - 1)
static int path_sqrt(dal_jet t, dal_jet *q, void *ctx) {
  (void)ctx;
  q[0] = dal_sqrt(dal_addc(t, -1.0));
  return 0;
}

static int row_path_domain(char *msg) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  CHECK_OK(pendulum(&b, &sys, &st));
  double res = -1.0;
  int rc = dal_lagrange_residual(sys, st, path_sqrt, NULL, 0.5, &res);
  copy_msg(msg, dal_state_errmsg(st));
  CHECK(res == -1.0);
  // in the domain: the residual of theta = sqrt(t - 1) at t = 2 is M qddot + c - Q
  CHECK_OK(dal_lagrange_residual(sys, st, path_sqrt, NULL, 2.0, &res));
  double th = 1.0, thdd = -0.25; // d2/dt2 sqrt(t - 1) at t = 2
  CHECK_CLOSE(res, thdd + 9.81 * sin(th), 1e-12);
  destroy_all(b, sys, st);
  return rc;
}

// ---------------------------------------------------------------- the table
static const bad_row rows[] = {
    {"builder dimension 4", DAL_E_ARG, NULL, NULL, row_dim},
    {"mass NaN", DAL_E_NONFINITE, "'bob'", "mass", row_mass_nan},
    {"mass inf", DAL_E_NONFINITE, "'bob'", "mass", row_mass_inf},
    {"mass zero", DAL_E_ARG, "'bob'", "mass", row_mass_zero},
    {"mass negative", DAL_E_ARG, "'bob'", "mass", row_mass_negative},
    {"place: particle index", DAL_E_ARG, "particle index 5", NULL, row_place_particle_index},
    {"place: coordinate index", DAL_E_ARG, "'bob'", "coordinate index 3",
     row_place_coord_index},
    {"place: negative coordinate index", DAL_E_ARG, "'bob'", "coordinate index -1",
     row_place_negative_coord},
    {"place: wrong number of inputs", DAL_E_ARG, "'bob'", "'pendulum' takes 1 inputs",
     row_place_ninputs},
    {"place: wrong number of parameters", DAL_E_ARG, "'bob'", "takes 7 parameters",
     row_place_nparams},
    {"place: NaN parameter", DAL_E_NONFINITE, "'bob'", "parameter 0 of primitive 'pendulum'",
     row_place_nan_param},
    {"place: inf parameter", DAL_E_NONFINITE, "'bob'", "parameter 0", row_place_inf_param},
    {"place: 3D primitive in 2D", DAL_E_ARG, "'bob'", "'spherical'", row_place_wrong_dim},
    {"place: NULL primitive", DAL_E_ARG, "'bob'", "primitive", row_place_null_prim},
    {"place: parent not placed", DAL_E_ARG, "'lower'", "'upper'", row_place_parent_order},
    {"constraint: particle index", DAL_E_ARG, "'rod'", "particle index 9",
     row_con_particle_index},
    {"constraint: wrong number of inputs", DAL_E_ARG, "'rod'", "'user_rod2' takes 4 inputs",
     row_con_ninputs},
    {"constraint: wrong number of parameters", DAL_E_ARG, "'rod'", "takes 1 parameters",
     row_con_nparams},
    {"constraint: NaN parameter", DAL_E_NONFINITE, "'rod'", "parameter 0", row_con_nan_param},
    {"gravity NaN", DAL_E_NONFINITE, "gravity", "component 1", row_gravity_nan},
    {"spring: negative stiffness", DAL_E_ARG, "spring", "'a'", row_spring_negative_k},
    {"spring: NaN rest length", DAL_E_NONFINITE, "spring", "'a'", row_spring_nan_length},
    {"spring: particle to itself", DAL_E_ARG, "spring", "index 0", row_spring_self},
    {"anchor spring: inf anchor", DAL_E_NONFINITE, "anchor spring", "'a'", row_anchor_inf},
    {"damper: particle index", DAL_E_ARG, "damper", "index 7", row_damper_index},
    {"damper: inf coefficient", DAL_E_NONFINITE, "damper", "'a'", row_damper_inf},
    {"compile: unplaced particle", DAL_E_ARG, "'stray'", "no position", row_compile_unplaced},
    {"compile: no coordinates", DAL_E_ARG, "no generalized coordinates", NULL,
     row_compile_no_coords},
    {"particle in a Lagrangian system", DAL_E_ARG, "'bob'", "Lagrangian",
     row_lagrangian_particle},
    {"state: NaN coordinate", DAL_E_NONFINITE, "'theta'", "nan", row_set_nan_q},
    {"state: inf velocity", DAL_E_NONFINITE, "velocity of coordinate 'theta'", "inf",
     row_set_inf_qdot},
    {"state: NaN time", DAL_E_NONFINITE, "time", "nan", row_set_nan_t},
    {"state of another system", DAL_E_STATE, "another system", NULL, row_foreign_state},
    {"forward: spherical pendulum at its pole", DAL_E_SINGULAR, "'phi'", "t=0.25",
     row_forward_pole},
    {"forward: force callback NaN", DAL_E_NONFINITE, "'bob'", "t=", row_force_nan},
    {"forward: force callback > 0", DAL_E_CALLBACK, "force callback", "t=",
     row_force_recoverable_forward},
    {"forward: force callback < 0", DAL_E_CALLBACK, "force callback", "t=", row_force_stop},
    {"forward: potential U(r) at its pole", DAL_E_DOMAIN, "U(r,t)", "'bob'",
     row_potential_r_domain},
    {"forward: potential U(q) outside its domain", DAL_E_DOMAIN, "U(q,t)", "'x'",
     row_potential_q_domain},
    {"forward: generalized force NaN", DAL_E_NONFINITE, "'y'", "t=", row_genforce_nan},
    {"forward: coordinate map outside its domain", DAL_E_DOMAIN, "'sqrtmap'", "'bob'",
     row_map_domain},
    {"forward: curve primitive without its curve", DAL_E_CALLBACK, "'curve2'", "'bead'",
     row_curve_no_ctx},
    {"forward: whole-system map stops", DAL_E_CALLBACK, "coordinate map", "t=",
     row_map_callback_stop},
    {"forward: Lagrangian with singular d2L/dqdot2", DAL_E_SINGULAR, "'y'", "t=",
     row_lagrangian_singular},
    {"lagrange_residual: path outside its domain", DAL_E_DOMAIN, "'theta'", "t=0.5",
     row_path_domain},
};

int main(void) {
  int nrows = (int)(sizeof rows / sizeof rows[0]);
  for (int i = 0; i < nrows; ++i) {
    const bad_row *r = &rows[i];
    char msg[MSG_LEN] = "";
    int before = check_failures;
    int rc = r->run(msg);
    CHECK_MSG(rc == r->expect, "row '%s': status %s, expected %s (message: %s)", r->name,
              dal_status_name(rc), dal_status_name(r->expect), msg);
    if (r->culprit)
      CHECK_MSG(strstr(msg, r->culprit) != NULL, "row '%s': message does not name '%s': %s",
                r->name, r->culprit, msg);
    if (r->culprit2)
      CHECK_MSG(strstr(msg, r->culprit2) != NULL, "row '%s': message does not name '%s': %s",
                r->name, r->culprit2, msg);
    // a failure always leaves a message where an object could keep one
    if (r->culprit) CHECK_MSG(msg[0] != 0, "row '%s': empty message", r->name);
    printf("%-48s %-16s %s | %s\n", r->name, dal_status_name(rc),
           check_failures == before ? "ok  " : "FAIL", msg);
  }
  return check_summary("test_bad_input");
}
