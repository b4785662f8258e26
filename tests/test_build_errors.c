// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Builder and evaluation errors of the minimal-coordinate API: exact status, culprit named.
//
// Every bad call (masses 0, negative, NaN, inf; indices out of range; dimension 4; a primitive
// given the wrong number of inputs, outputs or parameters; NaN parameters; NaN states; failing
// callbacks) must return its exact status code, leave a message that names the culprit (the
// particle, coordinate, primitive or callback, checked with strstr), change nothing, and leave
// the builder or state usable: after the errors the same builder compiles a pendulum whose
// acceleration is -g/l sin(theta).
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

// rc must equal code and msg must contain every name (NULL-terminated list)
static void expect_err(const char *what, int rc, int code, const char *msg, const char *n1,
                       const char *n2, const char *n3) {
  CHECK_MSG(rc == code, "%s: returned %s (%d), expected %s: %s", what, dal_status_name(rc), rc,
            dal_status_name(code), msg ? msg : "");
  const char *names[3] = {n1, n2, n3};
  for (int i = 0; i < 3; ++i)
    if (names[i])
      CHECK_MSG(msg && strstr(msg, names[i]), "%s: message does not name '%s': \"%s\"", what,
                names[i], msg ? msg : "");
}

#define EXPECT_B(call, code, n1, n2, n3)                                                           \
  expect_err(#call, (call), (code), dal_builder_errmsg(b), (n1), (n2), (n3))
#define EXPECT_S(call, code, n1, n2, n3)                                                           \
  expect_err(#call, (call), (code), dal_state_errmsg(st), (n1), (n2), (n3))

static void test_dimension(void) {
  dal_builder *b = (dal_builder *)&b; // must be reset to NULL on failure
  CHECK(dal_builder_create(4, &b) == DAL_E_ARG && b == NULL);
  b = (dal_builder *)&b;
  CHECK(dal_builder_create(1, &b) == DAL_E_ARG && b == NULL);
  CHECK(dal_builder_create(-3, &b) == DAL_E_ARG && b == NULL);
  CHECK(dal_builder_create(2, NULL) == DAL_E_ARG);
  CHECK_OK(dal_builder_create(3, &b));
  // a 2D map in a 3D scene: wrong number of outputs
  int th, p;
  CHECK_OK(dal_builder_add_coord(b, "theta", &th));
  CHECK_OK(dal_builder_add_particle(b, "bob", 1.0, &p));
  EXPECT_B(scn_place_swing(b, NULL, p, -1, 1.0, th), DAL_E_ARG, "bob", "'pendulum'", "3D");
  // a 3D gravity vector with NaN in z is caught in 3D only
  double g[3] = {0, 0, NAN};
  EXPECT_B(dal_builder_set_gravity(b, g), DAL_E_NONFINITE, "gravity", "2", NULL);
  EXPECT_B(dal_builder_set_gravity(b, NULL), DAL_E_ARG, "gravity", NULL, NULL);
  dal_builder_destroy(b);
  dal_builder_destroy(NULL); // no-op
}

// a pendulum builder after errors: must still compile and give theta'' = -g/l sin(theta)
static void check_recovers(dal_builder *b, int th, int p, double l) {
  double g[2] = {0, -9.81};
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_pendulum;
  pd.coords = &th;
  pd.ncoords = 1;
  pd.param[DAL_PENDULUM_L] = l;
  CHECK_OK(dal_builder_place_def(b, p, &pd));
  CHECK_OK(dal_builder_set_gravity(b, g));
  dal_system *sys = NULL;
  dal_state *st = NULL;
  int rc = dal_builder_compile(b, &sys);
  CHECK_MSG(rc == 0, "compile after errors: %s", dal_builder_errmsg(b));
  if (rc) return;
  CHECK(dal_system_nparticles(sys) == 1 && dal_system_ncoords(sys) == 1);
  CHECK(dal_system_mass(sys, 0) == 2.0);
  CHECK(strcmp(dal_system_particle_name(sys, 0), "bob") == 0);
  CHECK(strcmp(dal_system_coord_name(sys, 0), "theta") == 0);
  CHECK_OK(dal_state_create(sys, &st));
  double q = 0.8, qd = -0.3;
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &qd));
  CHECK_OK(dal_forward(sys, st));
  CHECK_CLOSE(dal_state_qddot(st)[0], -9.81 / l * sin(0.8), 1e-14);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

static void test_masses_and_indices(void) {
  dal_builder *b = NULL;
  CHECK_OK(dal_builder_create(2, &b));
  int th = -1, p = -1, idx = -7;
  CHECK_OK(dal_builder_add_coord(b, "theta", &th));
  // bad masses: nothing is added
  EXPECT_B(dal_builder_add_particle(b, "zero", 0.0, &idx), DAL_E_ARG, "zero", "mass", NULL);
  EXPECT_B(dal_builder_add_particle(b, "neg", -1.5, &idx), DAL_E_ARG, "neg", "mass", NULL);
  EXPECT_B(dal_builder_add_particle(b, "nan", NAN, &idx), DAL_E_NONFINITE, "nan", "mass", NULL);
  EXPECT_B(dal_builder_add_particle(b, "inf", INFINITY, &idx), DAL_E_NONFINITE, "inf", "mass",
           NULL);
  EXPECT_B(dal_builder_add_particle(b, "minf", -INFINITY, &idx), DAL_E_NONFINITE, "minf", "mass",
           NULL);
  CHECK(idx == -7);
  CHECK_OK(dal_builder_add_particle(b, "bob", 2.0, &p));
  CHECK(p == 0); // the rejected particles took no index
  // bad indices in place: e is the good def pd with one field spoiled
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_pendulum;
  pd.coords = &th;
  pd.ncoords = 1;
  pd.param[DAL_PENDULUM_L] = 1.0;
  dal_place_def e = pd;
  int badc = 3;
  EXPECT_B(dal_builder_place_def(b, 5, &pd), DAL_E_ARG, "5", NULL, NULL);
  EXPECT_B(dal_builder_place_def(b, -1, &pd), DAL_E_ARG, "-1", NULL, NULL);
  e.coords = &badc;
  EXPECT_B(dal_builder_place_def(b, p, &e), DAL_E_ARG, "bob", "coordinate index 3", NULL);
  e.coords = NULL;
  EXPECT_B(dal_builder_place_def(b, p, &e), DAL_E_ARG, "bob", NULL, NULL);
  e = pd;
  e.prim = NULL;
  EXPECT_B(dal_builder_place_def(b, p, &e), DAL_E_ARG, "bob", NULL, NULL);
  // parents: itself, out of range, not placed, added after the child
  e = pd;
  e.prim = &dal_map_hanging; // its one parameter, the length, is index 0: 1.0
  e.parent = p;
  EXPECT_B(dal_builder_place_def(b, p, &e), DAL_E_ARG, "bob", "parent", NULL);
  e.parent = 9;
  EXPECT_B(dal_builder_place_def(b, p, &e), DAL_E_ARG, "bob", "parent", NULL);
  // wrong number of inputs
  int two[2] = {th, th};
  e = pd;
  e.coords = two;
  e.ncoords = 2;
  EXPECT_B(dal_builder_place_def(b, p, &e), DAL_E_ARG, "bob", "'pendulum'", "inputs");
  e.coords = NULL;
  e.ncoords = 0;
  EXPECT_B(dal_builder_place_def(b, p, &e), DAL_E_ARG, "bob", "'pendulum'", "inputs");
  // a parameter list's own checks: more parameters than the primitive has, none given
  double par[8] = {1.0, 0, 0, 0, 0, 0, 0, 0};
  e = dal_default_place_def();
  e.prim = &dal_map_pendulum;
  e.coords = &th;
  e.ncoords = 1;
  e.param_list = par;
  e.nparam_list = 8;
  EXPECT_B(dal_builder_place_def(b, p, &e), DAL_E_ARG, "bob", "'pendulum'", "parameters");
  e.param_list = NULL;
  e.nparam_list = 7;
  EXPECT_B(dal_builder_place_def(b, p, &e), DAL_E_ARG, "bob", "'pendulum'", "parameters");
  // NaN and infinite parameters
  for (int i = 0; i < DAL_PENDULUM_NPARAM; ++i) {
    e = pd;
    e.param[i] = i % 2 ? NAN : INFINITY;
    char idxs[32];
    snprintf(idxs, sizeof idxs, "(index %d)", i);
    EXPECT_B(dal_builder_place_def(b, p, &e), DAL_E_NONFINITE, "bob", "'pendulum'", idxs);
  }
  // springs and dampers: bad indices, NaN or negative coefficients (b = -1: the anchor point,
  // at the origin by default)
  dal_spring_def sd = dal_default_spring_def();
  sd.a = p;
  sd.b = 4;
  sd.k = 1.0;
  sd.length = 1.0;
  EXPECT_B(dal_builder_add_spring_def(b, &sd), DAL_E_ARG, "spring", "4", NULL);
  sd.b = p;
  EXPECT_B(dal_builder_add_spring_def(b, &sd), DAL_E_ARG, "spring", NULL, NULL);
  sd.a = 8;
  EXPECT_B(dal_builder_add_spring_def(b, &sd), DAL_E_ARG, "spring", "8", NULL);
  sd.a = p;
  sd.b = -1;
  sd.k = NAN;
  EXPECT_B(dal_builder_add_spring_def(b, &sd), DAL_E_NONFINITE, "spring", "bob", NULL);
  sd.k = -1.0;
  EXPECT_B(dal_builder_add_spring_def(b, &sd), DAL_E_ARG, "spring", "bob", NULL);
  sd.k = 1.0;
  sd.length = -1.0;
  EXPECT_B(dal_builder_add_spring_def(b, &sd), DAL_E_ARG, "spring", "bob", NULL);
  sd.length = 1.0;
  sd.anchor[1] = NAN;
  EXPECT_B(dal_builder_add_spring_def(b, &sd), DAL_E_NONFINITE, "spring", "bob", NULL);
  dal_damper_def dd = dal_default_damper_def();
  dd.a = p;
  dd.b = 3;
  dd.c = 1.0;
  EXPECT_B(dal_builder_add_damper_def(b, &dd), DAL_E_ARG, "damper", "3", NULL);
  dd.b = -1;
  dd.c = INFINITY;
  EXPECT_B(dal_builder_add_damper_def(b, &dd), DAL_E_NONFINITE, "damper", "bob", NULL);
  dd.c = -0.5;
  EXPECT_B(dal_builder_add_damper_def(b, &dd), DAL_E_ARG, "damper", "bob", NULL);
  // NULL callbacks
  EXPECT_B(dal_builder_add_potential_r(b, NULL, NULL), DAL_E_ARG, "U(r,t)", NULL, NULL);
  EXPECT_B(dal_builder_add_potential_q(b, NULL, NULL), DAL_E_ARG, "U(q,t)", NULL, NULL);
  EXPECT_B(dal_builder_add_force(b, NULL, NULL), DAL_E_ARG, "force", NULL, NULL);
  EXPECT_B(dal_builder_add_genforce(b, NULL, NULL), DAL_E_ARG, "generalized force", NULL, NULL);
  EXPECT_B(dal_builder_set_map(b, NULL, NULL), DAL_E_ARG, "map", NULL, NULL);
  EXPECT_B(dal_builder_set_lagrangian(b, NULL, NULL), DAL_E_ARG, "Lagrangian", NULL, NULL);
  // the builder still works
  check_recovers(b, th, p, 1.5);
  // placing twice
  EXPECT_B(dal_builder_place_def(b, p, &pd), DAL_E_ARG, "bob", "already placed", NULL);
  dal_builder_destroy(b);
}

static int dummy_lag(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)t;
  (void)q;
  (void)ctx;
  *L = dal_scale(dal_sq(v[0]), 0.5);
  return 0;
}

static int dummy_map(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx) {
  (void)t;
  (void)ctx;
  r[0] = q[0];
  r[1] = dal_const(0.0);
  return 0;
}

static void test_model_errors(void) {
  dal_system *sys = NULL;
  // no coordinates, no particles
  dal_builder *b = NULL;
  CHECK_OK(dal_builder_create(2, &b));
  EXPECT_B(dal_builder_compile(b, &sys), DAL_E_ARG, "coordinates", NULL, NULL);
  CHECK(sys == NULL);
  int th, p, q2;
  // a pendulum on theta (l = 1), and a link hanging from `upper` on theta2
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_pendulum;
  pd.coords = &th;
  pd.ncoords = 1;
  pd.param[DAL_PENDULUM_L] = 1.0;
  dal_place_def hd = dal_default_place_def();
  hd.prim = &dal_map_hanging;
  hd.coords = &q2;
  hd.ncoords = 1;
  hd.param[DAL_HANGING_L] = 1.0;
  CHECK_OK(dal_builder_add_coord(b, "theta", &th));
  EXPECT_B(dal_builder_compile(b, &sys), DAL_E_ARG, "particles", NULL, NULL);
  // a particle without a position
  CHECK_OK(dal_builder_add_particle(b, "bob", 2.0, &p));
  EXPECT_B(dal_builder_compile(b, &sys), DAL_E_ARG, "bob", "position", NULL);
  CHECK(sys == NULL);
  // a Lagrangian excludes particles, and a map excludes placements
  EXPECT_B(dal_builder_set_lagrangian(b, dummy_lag, NULL), DAL_E_ARG, "particles", NULL, NULL);
  CHECK_OK(dal_builder_place_def(b, p, &pd));
  EXPECT_B(dal_builder_set_map(b, dummy_map, NULL), DAL_E_ARG, "bob", "placed", NULL);
  dal_builder_destroy(b);

  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "x", &th));
  CHECK_OK(dal_builder_set_lagrangian(b, dummy_lag, NULL));
  EXPECT_B(dal_builder_add_particle(b, "late", 1.0, &p), DAL_E_ARG, "late", "Lagrangian", NULL);
  dal_builder_destroy(b);

  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "x", &th));
  CHECK_OK(dal_builder_add_particle(b, "bead", 1.0, &p));
  CHECK_OK(dal_builder_set_map(b, dummy_map, NULL));
  EXPECT_B(dal_builder_place_def(b, p, &pd), DAL_E_ARG, "bead", "map", NULL);
  dal_builder_destroy(b);

  // a parent added after its child, and a parent not yet placed
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "theta1", &th));
  CHECK_OK(dal_builder_add_coord(b, "theta2", &q2));
  int lower, upper;
  CHECK_OK(dal_builder_add_particle(b, "lower", 1.0, &lower));
  CHECK_OK(dal_builder_add_particle(b, "upper", 1.0, &upper));
  hd.parent = upper;
  EXPECT_B(dal_builder_place_def(b, lower, &hd), DAL_E_ARG, "lower", "upper", "placed");
  CHECK_OK(dal_builder_place_def(b, upper, &pd));
  EXPECT_B(dal_builder_place_def(b, lower, &hd), DAL_E_ARG, "lower", "upper", "added before");
  dal_builder_destroy(b);

  // constraints: bad particle index, wrong input count (the constraint is named)
  CHECK_OK(dal_builder_create(2, &b));
  int xy[2];
  CHECK_OK(dal_builder_add_coord(b, "x", &xy[0]));
  CHECK_OK(dal_builder_add_coord(b, "y", &xy[1]));
  CHECK_OK(dal_builder_add_particle(b, "bead", 1.0, &p));
  pd = dal_default_place_def();
  pd.prim = &dal_map_cartesian2;
  pd.coords = xy;
  pd.ncoords = 2;
  CHECK_OK(dal_builder_place_def(b, p, &pd));
  int parts_bad[2] = {p, 6}, parts_one[1] = {p};
  dal_constraint_def cd = dal_default_constraint_def(); // a map used as a constraint
  cd.name = "rod";
  cd.prim = &dal_map_pendulum;
  cd.parts = parts_bad;
  cd.nparts = 2;
  cd.param[DAL_PENDULUM_L] = 1.0;
  EXPECT_B(dal_builder_add_constraint_def(b, &cd, NULL), DAL_E_ARG, "rod", "6", NULL);
  cd.parts = parts_one;
  cd.nparts = 1;
  EXPECT_B(dal_builder_add_constraint_def(b, &cd, NULL), DAL_E_ARG, "rod", "'pendulum'", "inputs");
  dal_builder_destroy(b);
}

// ---------------------------------------------------------------------------------------------
// evaluation errors: NaN states, failing callbacks, non-finite forces, degenerate springs
static int force_fail(double t, const double *r, const double *v, double *F, void *ctx) {
  (void)t;
  (void)r;
  (void)v;
  const int *mode = ctx;
  if (*mode == 1) return -2;
  if (*mode == 2) return 3;
  if (*mode == 3) F[1] += NAN;
  return 0;
}

static int gen_nan(double t, const double *q, const double *qd, double *Q, void *ctx) {
  (void)t;
  (void)q;
  (void)qd;
  const int *mode = ctx;
  if (*mode == 4) Q[0] += INFINITY;
  return 0;
}

static void test_state_errors(void) {
  int mode = 0;
  dal_builder *b = NULL;
  CHECK_OK(dal_builder_create(2, &b));
  int th, p, s2;
  double g[2] = {0, -9.81};
  CHECK_OK(dal_builder_add_coord(b, "theta", &th));
  CHECK_OK(dal_builder_add_particle(b, "bob", 2.0, &p));
  CHECK_OK(dal_builder_add_particle(b, "twin", 1.0, &s2));
  CHECK_OK(scn_place_swing(b, NULL, p, -1, 1.2, th));
  CHECK_OK(scn_place_swing(b, NULL, s2, -1, 1.2, th));
  CHECK_OK(dal_builder_set_gravity(b, g));
  dal_spring_def sd = dal_default_spring_def(); // bob and twin coincide: zero length
  sd.a = p;
  sd.b = s2;
  sd.k = 1.0;
  sd.length = 0.5;
  CHECK_OK(dal_builder_add_spring_def(b, &sd));
  CHECK_OK(dal_builder_add_force(b, force_fail, &mode));
  CHECK_OK(dal_builder_add_genforce(b, gen_nan, &mode));
  dal_system *sys = NULL, *other = NULL;
  CHECK_OK(dal_builder_compile(b, &sys));
  CHECK_OK(dal_builder_compile(b, &other));
  dal_builder_destroy(b);
  dal_state *st = NULL;
  if (!sys || dal_state_create(sys, &st)) {
    dal_system_destroy(sys);
    dal_system_destroy(other);
    return;
  }
  double q = 0.4, qd = 0.1, bad = NAN;
  CHECK_OK(dal_state_set(sys, st, 1.0, &q, &qd));
  EXPECT_S(dal_state_set(sys, st, 2.0, &bad, &qd), DAL_E_NONFINITE, "theta", NULL, NULL);
  EXPECT_S(dal_state_set(sys, st, 2.0, &q, &bad), DAL_E_NONFINITE, "theta", "velocity", NULL);
  double inf = INFINITY;
  EXPECT_S(dal_state_set(sys, st, 2.0, &inf, &qd), DAL_E_NONFINITE, "theta", NULL, NULL);
  EXPECT_S(dal_state_set(sys, st, NAN, &q, &qd), DAL_E_NONFINITE, "time", NULL, NULL);
  EXPECT_S(dal_state_set(sys, st, 2.0, NULL, &qd), DAL_E_ARG, NULL, NULL, NULL);
  EXPECT_S(dal_state_set(other, st, 2.0, &q, &qd), DAL_E_STATE, "another system", NULL, NULL);
  EXPECT_S(dal_forward(other, st), DAL_E_STATE, "another system", NULL, NULL);
  // the state is unchanged by the failures
  CHECK(dal_state_time(st) == 1.0 && dal_state_q(st)[0] == 0.4 && dal_state_qdot(st)[0] == 0.1);
  // the spring between two coinciding particles has no direction
  EXPECT_S(dal_forward(sys, st), DAL_E_DOMAIN, "spring", "bob", "t=1");
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_system_destroy(other);

  // callbacks: a fresh system without the degenerate spring
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "theta", &th));
  CHECK_OK(dal_builder_add_particle(b, "bob", 2.0, &p));
  CHECK_OK(scn_place_swing(b, NULL, p, -1, 1.2, th));
  CHECK_OK(dal_builder_set_gravity(b, g));
  CHECK_OK(dal_builder_add_force(b, force_fail, &mode));
  CHECK_OK(dal_builder_add_genforce(b, gen_nan, &mode));
  CHECK_OK(dal_builder_compile(b, &sys));
  dal_builder_destroy(b);
  if (!sys || dal_state_create(sys, &st)) {
    dal_system_destroy(sys);
    return;
  }
  CHECK_OK(dal_state_set(sys, st, 1.5, &q, &qd));
  mode = 1;
  EXPECT_S(dal_forward(sys, st), DAL_E_CALLBACK, "force callback", "t=1.5", NULL);
  mode = 2; // a recoverable request has no step to shrink in dal_forward
  EXPECT_S(dal_forward(sys, st), DAL_E_CALLBACK, "force callback", NULL, NULL);
  mode = 3;
  EXPECT_S(dal_forward(sys, st), DAL_E_NONFINITE, "bob", "force", NULL);
  mode = 4;
  EXPECT_S(dal_forward(sys, st), DAL_E_NONFINITE, "theta", "generalized force", NULL);
  mode = 0;
  CHECK_OK(dal_forward(sys, st));
  CHECK_CLOSE(dal_state_qddot(st)[0], -9.81 / 1.2 * sin(0.4), 1e-14);
  // Jacobian accessor: bad particle index
  double J[2];
  CHECK(dal_state_jacobian(sys, st, 1, J) == DAL_E_ARG);
  CHECK(dal_state_jacobian(sys, st, -1, J) == DAL_E_ARG);
  CHECK(dal_state_jacobian(sys, st, 0, NULL) == DAL_E_ARG);
  CHECK(dal_system_coord_name(sys, 1) == NULL && dal_system_particle_name(sys, -1) == NULL);
  CHECK(isnan(dal_system_mass(sys, 3)));
  dal_state_destroy(st);
  dal_state_destroy(NULL);
  dal_system_destroy(sys);
  dal_system_destroy(NULL);
}

static void test_status_strings(void) {
  // every status has a distinct name and a description; unknown codes are named as such
  const int codes[] = {DAL_OK,       DAL_E_ARG,      DAL_E_NOMEM,    DAL_E_NONFINITE,
                       DAL_E_DOMAIN, DAL_E_SINGULAR, DAL_E_CALLBACK, DAL_E_CONSTRAINT,
                       DAL_E_INIT,   DAL_E_STEP,     DAL_E_MAXSTEPS, DAL_E_CONV,
                       DAL_E_SOLVER, DAL_E_TIME,     DAL_E_STATE,    DAL_E_UNSUPPORTED,
                       DAL_E_IO};
  int n = (int)(sizeof codes / sizeof codes[0]);
  for (int i = 0; i < n; ++i) {
    CHECK(strcmp(dal_status_string(codes[i]), "unknown status") != 0);
    CHECK(strncmp(dal_status_name(codes[i]), "DAL_", 4) == 0);
    for (int j = 0; j < i; ++j)
      CHECK(strcmp(dal_status_name(codes[i]), dal_status_name(codes[j])));
  }
  CHECK(strcmp(dal_status_name(DAL_E_SINGULAR), "DAL_E_SINGULAR") == 0);
  CHECK(strcmp(dal_status_string(12345), "unknown status") == 0);
  CHECK(strcmp(dal_status_name(-999), "DAL_UNKNOWN") == 0);
}

int main(void) {
  test_dimension();
  test_masses_and_indices();
  test_model_errors();
  test_state_errors();
  test_status_strings();
  return check_summary("test_build_errors");
}
