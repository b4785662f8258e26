// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// NULL / foreign / out-of-range argument sweep of every public function, one row each.
//
// usage: test_api_sweep INCLUDE_DIR (the directory holding dalembert/*.h)
// The headers are parsed at run time for DAL_API function declarations: a public function
// without a row here, or a row naming a function that no longer exists, fails the test, so a
// new function cannot be added without its row. A row calls its function with each pointer
// argument NULL in turn, with a state of another system, with indices out of range and
// non-finite reals, and checks the exact status, that the object that could keep a message
// keeps one, and that nothing crashes (the sanitizer build and valgrind watch the memory).
//
// Conventions checked (README, errors section): a NULL object that could hold a message is
// DAL_E_ARG without one; any other bad argument is reported with a message in the object
// given; a state of another system (or a NULL system with a state) is DAL_E_STATE; a
// non-finite real is DAL_E_NONFINITE; destroy(NULL) and default_opts(NULL) do nothing;
// accessors answer NULL (pointers), NaN (reals) or 0 (counts) to a NULL object.
#include <ctype.h>
#include <dirent.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"

// ---------------------------------------------------------------- fixtures
// A: Cartesian pendulum 'bob' on rod 'rod' (2 coordinates, 1 constraint row), evaluated;
// B: a planar pendulum in minimal coordinates (1 coordinate), evaluated. stA, stB their
// states; bld a builder that stays valid throughout.
typedef struct fix {
  dal_builder *bld, *ba, *bb;
  dal_system *A, *B;
  dal_state *stA, *stB;
  dal_solve_opts o;
} fix;

static fix F;

static int path_q(dal_jet t, dal_jet *q, void *ctx) {
  (void)ctx;
  q[0] = dal_sin(t);
  q[1] = dal_scale(dal_cos(t), -1.0);
  return 0;
}

static int force_cb(double t, const double *r, const double *v, double *Fo, void *ctx) {
  (void)t;
  (void)r;
  (void)v;
  (void)Fo;
  (void)ctx;
  return 0;
}

static int genforce_cb(double t, const double *q, const double *qd, double *Q, void *ctx) {
  (void)t;
  (void)q;
  (void)qd;
  (void)Q;
  (void)ctx;
  return 0;
}

static int pot_r(const dal_jet *r, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  *U = r[0];
  return 0;
}

static int pot_q(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  *U = q[0];
  return 0;
}

static int map_fn(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx) {
  (void)t;
  (void)ctx;
  r[0] = q[0];
  r[1] = q[1];
  return 0;
}

static int lag_fn(dal_jet t, const dal_jet *q, const dal_jet *qd, dal_jet *L, void *ctx) {
  (void)t;
  (void)q;
  (void)ctx;
  *L = dal_scale(dal_sq(qd[0]), 0.5);
  return 0;
}

static void fix_make(void) {
  static const double g2[2] = {0.0, -9.81};
  int c[2], bob, th;
  double rod[3] = {1.0, 0.0, 0.0}, pend[7] = {1.0, 0, 0, 0, 0, 0, 0};
  double q[2] = {0.6, -0.8}, qd[2] = {0.0, 0.0}, th0 = 0.3, thd = 0.0;
  CHECK_OK(dal_builder_create(2, &F.ba));
  CHECK_OK(dal_builder_add_coord(F.ba, "x", &c[0]));
  CHECK_OK(dal_builder_add_coord(F.ba, "y", &c[1]));
  CHECK_OK(dal_builder_add_particle(F.ba, "bob", 1.0, &bob));
  CHECK_OK(dal_builder_place(F.ba, bob, &dal_map_cartesian2, -1, 2, c, 0, NULL, NULL));
  CHECK_OK(dal_builder_set_gravity(F.ba, g2));
  CHECK_OK(dal_builder_add_constraint(F.ba, "rod", &dal_con_anchor2, 1, &bob, 0, NULL, 3, rod, NULL,
                                      NULL));
  CHECK_OK(dal_builder_compile(F.ba, &F.A));
  CHECK_OK(dal_state_create(F.A, &F.stA));
  CHECK_OK(dal_state_set(F.A, F.stA, 0.0, q, qd));
  CHECK_OK(dal_forward(F.A, F.stA));
  CHECK_OK(dal_builder_create(2, &F.bb));
  CHECK_OK(dal_builder_add_coord(F.bb, "theta", &th));
  CHECK_OK(dal_builder_add_particle(F.bb, "bob", 1.0, &bob));
  CHECK_OK(dal_builder_place(F.bb, bob, &dal_map_pendulum, -1, 1, &th, 7, pend, NULL));
  CHECK_OK(dal_builder_set_gravity(F.bb, g2));
  CHECK_OK(dal_builder_compile(F.bb, &F.B));
  CHECK_OK(dal_state_create(F.B, &F.stB));
  CHECK_OK(dal_state_set(F.B, F.stB, 0.0, &th0, &thd));
  CHECK_OK(dal_forward(F.B, F.stB));
  CHECK_OK(dal_builder_create(2, &F.bld));
  CHECK_OK(dal_builder_add_coord(F.bld, "u", NULL));
  CHECK_OK(dal_builder_add_coord(F.bld, "w", NULL));
  CHECK_OK(dal_builder_add_particle(F.bld, "p", 1.0, NULL));
  dal_solve_default_opts(&F.o);
}

static void fix_free(void) {
  dal_state_destroy(F.stA);
  dal_state_destroy(F.stB);
  dal_system_destroy(F.A);
  dal_system_destroy(F.B);
  dal_builder_destroy(F.ba);
  dal_builder_destroy(F.bb);
  dal_builder_destroy(F.bld);
}

// ---------------------------------------------------------------- expectations
// Before each call the object gets a known "sentinel" message from a failure no row provokes;
// a failing call must replace it with its own (a stale message would not count).
static char st_sentinel[512], b_sentinel[512];

static void st_mark(dal_state *st) {
  if (!st) return;
  double res[2];
  const dal_system *sys = st == F.stA ? F.A : F.B;
  CHECK(dal_lagrange_residual(sys, st, path_q, INFINITY, res, NULL) == DAL_E_NONFINITE);
  snprintf(st_sentinel, sizeof st_sentinel, "%s", dal_state_errmsg(st));
}

static void b_mark(dal_builder *b) {
  if (!b) return;
  CHECK(dal_builder_add_particle(b, "sentinel", -7.0, NULL) == DAL_E_ARG);
  snprintf(b_sentinel, sizeof b_sentinel, "%s", dal_builder_errmsg(b));
}

// the status of a state call, and the state's message (st may be NULL: no message)
static void st_expect(const char *call, int rc, int want, const dal_state *st) {
  CHECK_MSG(rc == want, "%s: %s, expected %s", call, dal_status_name(rc), dal_status_name(want));
  if (st && want != DAL_OK)
    CHECK_MSG(dal_state_errmsg(st)[0] != 0 && strcmp(dal_state_errmsg(st), st_sentinel) != 0,
              "%s: %s without a message of its own", call, dal_status_name(rc));
}
#define ST(call, want, st)                                                                         \
  do {                                                                                             \
    st_mark(st);                                                                                   \
    st_expect(#call, (call), (want), (st));                                                        \
  } while (0)

static void b_expect(const char *call, int rc, int want, const dal_builder *b) {
  CHECK_MSG(rc == want, "%s: %s, expected %s", call, dal_status_name(rc), dal_status_name(want));
  if (b && want != DAL_OK)
    CHECK_MSG(dal_builder_errmsg(b)[0] != 0 && strcmp(dal_builder_errmsg(b), b_sentinel) != 0,
              "%s: %s without a message of its own", call, dal_status_name(rc));
}
#define BL(call, want, b)                                                                          \
  do {                                                                                             \
    b_mark(b);                                                                                     \
    b_expect(#call, (call), (want), (b));                                                          \
  } while (0)

// a state survived a refused call: still at its point, still evaluated
static void st_intact(void) {
  CHECK(dal_state_time(F.stA) == 0.0 && dal_state_q(F.stA)[0] == 0.6);
  CHECK(dal_state_qddot(F.stA) != NULL && dal_state_time(F.stB) == 0.0);
}

// ---------------------------------------------------------------- rows: base.h
static void sw_dal_status_string(void) {
  CHECK(strcmp(dal_status_string(-9999), "unknown status") == 0);
  CHECK(strcmp(dal_status_string(INT_MIN), "unknown status") == 0);
  CHECK(strcmp(dal_status_string(DAL_OK), "ok") == 0);
}
static void sw_dal_status_name(void) {
  CHECK(strcmp(dal_status_name(1), "DAL_UNKNOWN") == 0);
  CHECK(strcmp(dal_status_name(INT_MAX), "DAL_UNKNOWN") == 0);
  CHECK(strcmp(dal_status_name(DAL_E_STATE), "DAL_E_STATE") == 0);
}
static void sw_dal_version(void) { CHECK(dal_version() != NULL && dal_version()[0] != 0); }

// ---------------------------------------------------------------- rows: dae.h
static void sw_dal_make_consistent(void) {
  dal_init_report rep;
  ST(dal_make_consistent(F.A, NULL, 0.0, &rep), DAL_E_ARG, NULL);
  ST(dal_make_consistent(NULL, F.stA, 0.0, &rep), DAL_E_STATE, F.stA);
  ST(dal_make_consistent(F.B, F.stA, 0.0, &rep), DAL_E_STATE, F.stA);
  ST(dal_make_consistent(F.A, F.stA, NAN, &rep), DAL_E_NONFINITE, F.stA);
  ST(dal_make_consistent(F.A, F.stA, INFINITY, NULL), DAL_E_NONFINITE, F.stA);
  st_intact();
  ST(dal_make_consistent(F.A, F.stA, 0.0, NULL), DAL_OK, F.stA);
}
static void sw_dal_check_constraints(void) {
  dal_constraint_report rep;
  ST(dal_check_constraints(F.A, NULL, &rep), DAL_E_ARG, NULL);
  ST(dal_check_constraints(NULL, F.stA, &rep), DAL_E_STATE, F.stA);
  ST(dal_check_constraints(F.B, F.stA, &rep), DAL_E_STATE, F.stA);
  ST(dal_check_constraints(F.A, F.stA, NULL), DAL_OK, F.stA);
}
static void sw_dal_constraint_forces(void) {
  double Fo[2];
  CHECK_OK(dal_forward(F.A, F.stA));
  ST(dal_constraint_forces(F.A, NULL, Fo), DAL_E_ARG, NULL);
  ST(dal_constraint_forces(NULL, F.stA, Fo), DAL_E_STATE, F.stA);
  ST(dal_constraint_forces(F.B, F.stA, Fo), DAL_E_STATE, F.stA);
  ST(dal_constraint_forces(F.A, F.stA, NULL), DAL_E_ARG, F.stA);
  ST(dal_constraint_forces(F.A, F.stA, Fo), DAL_OK, F.stA);
  // the minimal system has no explicit constraints: zero forces, DAL_OK
  double Fb[2] = {7, 7};
  ST(dal_constraint_forces(F.B, F.stB, Fb), DAL_OK, F.stB);
  CHECK(Fb[0] == 0.0 && Fb[1] == 0.0);
}
static void sw_dal_constraint_genforces(void) {
  double Q[2];
  ST(dal_constraint_genforces(F.A, NULL, Q), DAL_E_ARG, NULL);
  ST(dal_constraint_genforces(NULL, F.stA, Q), DAL_E_STATE, F.stA);
  ST(dal_constraint_genforces(F.B, F.stA, Q), DAL_E_STATE, F.stA);
  ST(dal_constraint_genforces(F.A, F.stA, NULL), DAL_E_ARG, F.stA);
  ST(dal_constraint_genforces(F.A, F.stA, Q), DAL_OK, F.stA);
}

// ---------------------------------------------------------------- rows: primitives.h
static void sw_dal_primitive_count(void) { CHECK(dal_primitive_count() >= 24); }
static void sw_dal_primitive_get(void) {
  CHECK(dal_primitive_get(-1) == NULL && dal_primitive_get(INT_MIN) == NULL);
  CHECK(dal_primitive_get(dal_primitive_count()) == NULL && dal_primitive_get(INT_MAX) == NULL);
  CHECK(dal_primitive_get(0) != NULL);
}
static void sw_dal_primitive_find(void) {
  CHECK(dal_primitive_find(NULL) == NULL && dal_primitive_find("") == NULL);
  CHECK(dal_primitive_find("no such primitive") == NULL);
  CHECK(dal_primitive_find("distance2") == &dal_con_distance2);
}

// ---------------------------------------------------------------- rows: solve.h
static void sw_dal_solve_default_opts(void) {
  dal_solve_default_opts(NULL); // a no-op
  dal_solve_opts o;
  memset(&o, 0xff, sizeof o);
  dal_solve_default_opts(&o);
  CHECK(o.rtol == 1e-8 && o.method == DAL_METHOD_AUTO);
}
static void sw_dal_method_name(void) {
  CHECK(strcmp(dal_method_name((dal_method)99), "unknown") == 0);
  CHECK(strcmp(dal_method_name((dal_method)-1), "unknown") == 0);
  CHECK(strcmp(dal_method_name(DAL_METHOD_BS), "bs") == 0);
}
static void sw_dal_formulation_name(void) {
  CHECK(strcmp(dal_formulation_name((dal_formulation)99), "unknown") == 0);
  CHECK(strcmp(dal_formulation_name(DAL_FORM_GGL), "ggl") == 0);
}
static void sw_dal_state_stats(void) {
  dal_stats s;
  ST(dal_state_stats(NULL, &s), DAL_E_ARG, NULL);
  ST(dal_state_stats(F.stA, NULL), DAL_E_ARG, F.stA);
  ST(dal_state_stats(F.stA, &s), DAL_OK, F.stA);
}
static void sw_dal_advance(void) {
  dal_solve_opts bad;
  memset(&bad, 0, sizeof bad);
  ST(dal_advance(F.A, NULL, &F.o, 1.0), DAL_E_ARG, NULL);
  ST(dal_advance(NULL, F.stA, &F.o, 1.0), DAL_E_STATE, F.stA);
  ST(dal_advance(F.B, F.stA, &F.o, 1.0), DAL_E_STATE, F.stA);
  ST(dal_advance(F.A, F.stA, NULL, 1.0), DAL_E_ARG, F.stA);
  ST(dal_advance(F.A, F.stA, &bad, 1.0), DAL_E_ARG, F.stA);
  ST(dal_advance(F.A, F.stA, &F.o, NAN), DAL_E_NONFINITE, F.stA);
  ST(dal_advance(F.A, F.stA, &F.o, -INFINITY), DAL_E_NONFINITE, F.stA);
  ST(dal_advance(F.A, F.stA, &F.o, -1.0), DAL_E_TIME, F.stA);
  st_intact();
}
static void sw_dal_evolve(void) {
  ST(dal_evolve(F.A, NULL, &F.o, 1.0, 0.1, NULL, NULL), DAL_E_ARG, NULL);
  ST(dal_evolve(NULL, F.stA, &F.o, 1.0, 0.1, NULL, NULL), DAL_E_STATE, F.stA);
  ST(dal_evolve(F.B, F.stA, &F.o, 1.0, 0.1, NULL, NULL), DAL_E_STATE, F.stA);
  ST(dal_evolve(F.A, F.stA, NULL, 1.0, 0.1, NULL, NULL), DAL_E_ARG, F.stA);
  ST(dal_evolve(F.A, F.stA, &F.o, NAN, 0.1, NULL, NULL), DAL_E_NONFINITE, F.stA);
  ST(dal_evolve(F.A, F.stA, &F.o, 1.0, NAN, NULL, NULL), DAL_E_NONFINITE, F.stA);
  ST(dal_evolve(F.A, F.stA, &F.o, 1.0, INFINITY, NULL, NULL), DAL_E_NONFINITE, F.stA);
  ST(dal_evolve(F.A, F.stA, &F.o, 1.0, 0.0, NULL, NULL), DAL_E_ARG, F.stA);
  ST(dal_evolve(F.A, F.stA, &F.o, 1.0, -0.1, NULL, NULL), DAL_E_ARG, F.stA);
  st_intact();
}
static void sw_dal_csv_monitor(void) {
  dal_csv none = {NULL, 0, 0};
  FILE *fp = tmpfile();
  dal_csv ok = {fp, 0, 0};
  ST(dal_csv_monitor(F.A, NULL, &ok), DAL_E_ARG, NULL);
  ST(dal_csv_monitor(NULL, F.stA, &ok), DAL_E_STATE, F.stA);
  ST(dal_csv_monitor(F.B, F.stA, &ok), DAL_E_STATE, F.stA);
  ST(dal_csv_monitor(F.A, F.stA, NULL), DAL_E_ARG, F.stA);
  ST(dal_csv_monitor(F.A, F.stA, &none), DAL_E_ARG, F.stA);
  CHECK(ftell(fp) == 0);
  ST(dal_csv_monitor(F.A, F.stA, &ok), DAL_OK, F.stA);
  CHECK(ftell(fp) > 0);
  fclose(fp);
}

// ---------------------------------------------------------------- rows: state.h
static void sw_dal_state_create(void) {
  dal_state *st = (dal_state *)&F; // a non-NULL value that must be overwritten
  ST(dal_state_create(NULL, &st), DAL_E_ARG, NULL);
  CHECK(st == NULL);
  ST(dal_state_create(F.A, NULL), DAL_E_ARG, NULL);
}
static void sw_dal_state_destroy(void) { dal_state_destroy(NULL); }
static void sw_dal_state_errmsg(void) {
  CHECK(dal_state_errmsg(NULL) != NULL && dal_state_errmsg(NULL)[0] == 0);
}
static void sw_dal_state_set(void) {
  double q[2] = {0.6, -0.8}, qd[2] = {0.0, 0.0}, qn[2] = {NAN, 0.0};
  ST(dal_state_set(F.A, NULL, 0.0, q, qd), DAL_E_ARG, NULL);
  ST(dal_state_set(NULL, F.stA, 0.0, q, qd), DAL_E_STATE, F.stA);
  ST(dal_state_set(F.B, F.stA, 0.0, q, qd), DAL_E_STATE, F.stA);
  ST(dal_state_set(F.A, F.stA, 0.0, NULL, qd), DAL_E_ARG, F.stA);
  ST(dal_state_set(F.A, F.stA, 0.0, q, NULL), DAL_E_ARG, F.stA);
  ST(dal_state_set(F.A, F.stA, NAN, q, qd), DAL_E_NONFINITE, F.stA);
  ST(dal_state_set(F.A, F.stA, 0.0, qn, qd), DAL_E_NONFINITE, F.stA);
  ST(dal_state_set(F.A, F.stA, 0.0, qd, qn), DAL_E_NONFINITE, F.stA);
  st_intact();
}
static void sw_dal_forward(void) {
  ST(dal_forward(F.A, NULL), DAL_E_ARG, NULL);
  ST(dal_forward(NULL, F.stA), DAL_E_STATE, F.stA);
  ST(dal_forward(F.B, F.stA), DAL_E_STATE, F.stA);
  st_intact();
  ST(dal_forward(F.A, F.stA), DAL_OK, F.stA);
}
static void sw_dal_state_time(void) { CHECK(isnan(dal_state_time(NULL))); }

// every pointer accessor: NULL for a NULL state; non-NULL for an evaluated state where the
// quantity exists (m > 0 for lambda, phi, phidot; NULL for the minimal system)
typedef const double *accessor_fn(const dal_state *);
static void accessor(accessor_fn *fn, int constrained_only) {
  CHECK(fn(NULL) == NULL);
  CHECK(fn(F.stA) != NULL);
  CHECK(constrained_only ? fn(F.stB) == NULL : fn(F.stB) != NULL);
}
static void sw_dal_state_q(void) { accessor(dal_state_q, 0); }
static void sw_dal_state_qdot(void) { accessor(dal_state_qdot, 0); }
static void sw_dal_state_qddot(void) { accessor(dal_state_qddot, 0); }
static void sw_dal_state_positions(void) { accessor(dal_state_positions, 0); }
static void sw_dal_state_velocities(void) { accessor(dal_state_velocities, 0); }
static void sw_dal_state_accelerations(void) { accessor(dal_state_accelerations, 0); }
static void sw_dal_state_drdt(void) { accessor(dal_state_drdt, 0); }
static void sw_dal_state_gamma(void) { accessor(dal_state_gamma, 0); }
static void sw_dal_state_mass_matrix(void) { accessor(dal_state_mass_matrix, 0); }
static void sw_dal_state_genforces(void) { accessor(dal_state_genforces, 0); }
static void sw_dal_state_bias(void) { accessor(dal_state_bias, 0); }
static void sw_dal_state_forces(void) { accessor(dal_state_forces, 0); }
static void sw_dal_state_reactions(void) { accessor(dal_state_reactions, 0); }
static void sw_dal_state_lambda(void) { accessor(dal_state_lambda, 1); }
static void sw_dal_state_phi(void) { accessor(dal_state_phi, 1); }
static void sw_dal_state_phidot(void) { accessor(dal_state_phidot, 1); }

static void sw_dal_state_jacobian(void) {
  double J[4];
  ST(dal_state_jacobian(F.A, NULL, 0, J), DAL_E_ARG, NULL);
  ST(dal_state_jacobian(NULL, F.stA, 0, J), DAL_E_STATE, F.stA);
  ST(dal_state_jacobian(F.B, F.stA, 0, J), DAL_E_STATE, F.stA);
  ST(dal_state_jacobian(F.A, F.stA, 0, NULL), DAL_E_ARG, F.stA);
  ST(dal_state_jacobian(F.A, F.stA, -1, J), DAL_E_ARG, F.stA);
  ST(dal_state_jacobian(F.A, F.stA, 1, J), DAL_E_ARG, F.stA);
  ST(dal_state_jacobian(F.A, F.stA, INT_MIN, J), DAL_E_ARG, F.stA);
  ST(dal_state_jacobian(F.A, F.stA, 0, J), DAL_OK, F.stA);
}
static void sw_dal_state_energies(void) {
  dal_energies e;
  ST(dal_state_energies(NULL, &e), DAL_E_ARG, NULL);
  ST(dal_state_energies(F.stA, NULL), DAL_E_ARG, F.stA);
  ST(dal_state_energies(F.stA, &e), DAL_OK, F.stA);
}
static void sw_dal_lagrange_residual(void) {
  double res[2];
  ST(dal_lagrange_residual(F.A, NULL, path_q, 0.0, res, NULL), DAL_E_ARG, NULL);
  ST(dal_lagrange_residual(NULL, F.stA, path_q, 0.0, res, NULL), DAL_E_STATE, F.stA);
  ST(dal_lagrange_residual(F.B, F.stA, path_q, 0.0, res, NULL), DAL_E_STATE, F.stA);
  ST(dal_lagrange_residual(F.A, F.stA, NULL, 0.0, res, NULL), DAL_E_ARG, F.stA);
  ST(dal_lagrange_residual(F.A, F.stA, path_q, 0.0, NULL, NULL), DAL_E_ARG, F.stA);
  ST(dal_lagrange_residual(F.A, F.stA, path_q, NAN, res, NULL), DAL_E_NONFINITE, F.stA);
  st_intact();
  // (the residual uses the state as workspace: restore the fixture afterwards)
  ST(dal_lagrange_residual(F.A, F.stA, path_q, 0.0, res, NULL), DAL_OK, F.stA);
  double q[2] = {0.6, -0.8}, qd[2] = {0.0, 0.0};
  CHECK_OK(dal_state_set(F.A, F.stA, 0.0, q, qd));
  CHECK_OK(dal_forward(F.A, F.stA));
}

// ---------------------------------------------------------------- rows: system.h
static void sw_dal_builder_create(void) {
  dal_builder *b = (dal_builder *)&F;
  BL(dal_builder_create(2, NULL), DAL_E_ARG, NULL);
  BL(dal_builder_create(4, &b), DAL_E_ARG, NULL);
  CHECK(b == NULL);
  BL(dal_builder_create(INT_MIN, &b), DAL_E_ARG, NULL);
  BL(dal_builder_create(1, &b), DAL_E_ARG, NULL);
}
static void sw_dal_builder_destroy(void) { dal_builder_destroy(NULL); }
static void sw_dal_builder_errmsg(void) {
  CHECK(dal_builder_errmsg(NULL) != NULL && dal_builder_errmsg(NULL)[0] == 0);
}
static void sw_dal_builder_add_coord(void) {
  BL(dal_builder_add_coord(NULL, "z", NULL), DAL_E_ARG, NULL);
}
static void sw_dal_builder_add_particle(void) {
  BL(dal_builder_add_particle(NULL, "q", 1.0, NULL), DAL_E_ARG, NULL);
  BL(dal_builder_add_particle(F.bld, NULL, NAN, NULL), DAL_E_NONFINITE, F.bld);
  BL(dal_builder_add_particle(F.bld, NULL, 0.0, NULL), DAL_E_ARG, F.bld);
  BL(dal_builder_add_particle(F.bld, NULL, -INFINITY, NULL), DAL_E_NONFINITE, F.bld);
}
static void sw_dal_builder_place(void) {
  int c[2] = {0, 1}, bad[2] = {0, 7};
  double par[1] = {1.0};
  BL(dal_builder_place(NULL, 0, &dal_map_cartesian2, -1, 2, c, 0, NULL, NULL), DAL_E_ARG, NULL);
  BL(dal_builder_place(F.bld, 0, NULL, -1, 2, c, 0, NULL, NULL), DAL_E_ARG, F.bld);
  BL(dal_builder_place(F.bld, -1, &dal_map_cartesian2, -1, 2, c, 0, NULL, NULL), DAL_E_ARG, F.bld);
  BL(dal_builder_place(F.bld, 9, &dal_map_cartesian2, -1, 2, c, 0, NULL, NULL), DAL_E_ARG, F.bld);
  BL(dal_builder_place(F.bld, 0, &dal_map_cartesian2, -1, 2, NULL, 0, NULL, NULL), DAL_E_ARG,
     F.bld);
  BL(dal_builder_place(F.bld, 0, &dal_map_cartesian2, -1, 2, bad, 0, NULL, NULL), DAL_E_ARG, F.bld);
  BL(dal_builder_place(F.bld, 0, &dal_map_cartesian2, -1, -1, c, 0, NULL, NULL), DAL_E_ARG, F.bld);
  BL(dal_builder_place(F.bld, 0, &dal_map_cartesian2, 0, 2, c, 0, NULL, NULL), DAL_E_ARG, F.bld);
  BL(dal_builder_place(F.bld, 0, &dal_map_hanging, 5, 1, c, 1, par, NULL), DAL_E_ARG, F.bld);
  BL(dal_builder_place(F.bld, 0, &dal_map_hanging, -1, 1, c, 1, NULL, NULL), DAL_E_ARG, F.bld);
  BL(dal_builder_place(F.bld, 0, &dal_map_cartesian2, -1, 2, c, -1, NULL, NULL), DAL_E_ARG, F.bld);
}
static void sw_dal_builder_set_map(void) {
  BL(dal_builder_set_map(NULL, map_fn, NULL), DAL_E_ARG, NULL);
  BL(dal_builder_set_map(F.bld, NULL, NULL), DAL_E_ARG, F.bld);
}
static void sw_dal_builder_set_lagrangian(void) {
  BL(dal_builder_set_lagrangian(NULL, lag_fn, NULL), DAL_E_ARG, NULL);
  BL(dal_builder_set_lagrangian(F.bld, NULL, NULL), DAL_E_ARG, F.bld);
  BL(dal_builder_set_lagrangian(F.bld, lag_fn, NULL), DAL_E_ARG, F.bld); // has a particle
}
static void sw_dal_builder_add_constraint(void) {
  int p[1] = {0}, pbad[1] = {5}, c[1] = {0};
  double par[3] = {1.0, 0.0, 0.0}, nan3[3] = {NAN, 0.0, 0.0};
  const dal_primitive *a2 = &dal_con_anchor2;
  BL(dal_builder_add_constraint(NULL, "r", a2, 1, p, 0, NULL, 3, par, NULL, NULL), DAL_E_ARG, NULL);
  BL(dal_builder_add_constraint(F.bld, "r", NULL, 1, p, 0, NULL, 3, par, NULL, NULL), DAL_E_ARG,
     F.bld);
  BL(dal_builder_add_constraint(F.bld, "r", a2, 1, NULL, 0, NULL, 3, par, NULL, NULL), DAL_E_ARG,
     F.bld);
  BL(dal_builder_add_constraint(F.bld, "r", a2, 1, pbad, 0, NULL, 3, par, NULL, NULL), DAL_E_ARG,
     F.bld);
  BL(dal_builder_add_constraint(F.bld, "r", a2, -1, p, 0, NULL, 3, par, NULL, NULL), DAL_E_ARG,
     F.bld);
  BL(dal_builder_add_constraint(F.bld, "r", a2, 1, p, 0, NULL, 3, NULL, NULL, NULL), DAL_E_ARG,
     F.bld);
  BL(dal_builder_add_constraint(F.bld, "r", a2, 1, p, 1, NULL, 3, par, NULL, NULL), DAL_E_ARG,
     F.bld);
  BL(dal_builder_add_constraint(F.bld, "r", a2, 1, p, 0, c, 3, nan3, NULL, NULL), DAL_E_NONFINITE,
     F.bld);
  BL(dal_builder_add_constraint(F.bld, NULL, a2, 1, p, 0, NULL, 2, par, NULL, NULL), DAL_E_ARG,
     F.bld);
}
static void sw_dal_builder_set_gravity(void) {
  double g[3] = {0.0, -9.81, 0.0}, gn[3] = {0.0, NAN, 0.0};
  BL(dal_builder_set_gravity(NULL, g), DAL_E_ARG, NULL);
  BL(dal_builder_set_gravity(F.bld, NULL), DAL_E_ARG, F.bld);
  BL(dal_builder_set_gravity(F.bld, gn), DAL_E_NONFINITE, F.bld);
}
static void sw_dal_builder_add_spring(void) {
  BL(dal_builder_add_spring(NULL, 0, 0, 1.0, 1.0), DAL_E_ARG, NULL);
  BL(dal_builder_add_spring(F.bld, -1, 0, 1.0, 1.0), DAL_E_ARG, F.bld);
  BL(dal_builder_add_spring(F.bld, 0, -1, 1.0, 1.0), DAL_E_ARG, F.bld);
  BL(dal_builder_add_spring(F.bld, 0, 9, 1.0, 1.0), DAL_E_ARG, F.bld);
  BL(dal_builder_add_spring(F.bld, 0, 0, 1.0, 1.0), DAL_E_ARG, F.bld);
}
static void sw_dal_builder_add_anchor_spring(void) {
  double x0[2] = {0.0, 0.0};
  BL(dal_builder_add_anchor_spring(NULL, 0, x0, NULL, NULL, 1.0, 1.0), DAL_E_ARG, NULL);
  BL(dal_builder_add_anchor_spring(F.bld, 0, NULL, NULL, NULL, 1.0, 1.0), DAL_E_ARG, F.bld);
  BL(dal_builder_add_anchor_spring(F.bld, 9, x0, NULL, NULL, 1.0, 1.0), DAL_E_ARG, F.bld);
  BL(dal_builder_add_anchor_spring(F.bld, 0, x0, NULL, NULL, NAN, 1.0), DAL_E_NONFINITE, F.bld);
  BL(dal_builder_add_anchor_spring(F.bld, 0, x0, NULL, NULL, -1.0, 1.0), DAL_E_ARG, F.bld);
}
static void sw_dal_builder_add_damper(void) {
  BL(dal_builder_add_damper(NULL, 0, 0, 1.0), DAL_E_ARG, NULL);
  BL(dal_builder_add_damper(F.bld, 0, -1, 1.0), DAL_E_ARG, F.bld);
  BL(dal_builder_add_damper(F.bld, INT_MAX, 0, 1.0), DAL_E_ARG, F.bld);
}
static void sw_dal_builder_add_anchor_damper(void) {
  double x0[2] = {0.0, 0.0};
  BL(dal_builder_add_anchor_damper(NULL, 0, x0, NULL, NULL, 1.0), DAL_E_ARG, NULL);
  BL(dal_builder_add_anchor_damper(F.bld, 0, NULL, NULL, NULL, 1.0), DAL_E_ARG, F.bld);
  BL(dal_builder_add_anchor_damper(F.bld, -5, x0, NULL, NULL, 1.0), DAL_E_ARG, F.bld);
  BL(dal_builder_add_anchor_damper(F.bld, 0, x0, NULL, NULL, INFINITY), DAL_E_NONFINITE, F.bld);
}
static void sw_dal_builder_add_potential_r(void) {
  BL(dal_builder_add_potential_r(NULL, pot_r, NULL), DAL_E_ARG, NULL);
  BL(dal_builder_add_potential_r(F.bld, NULL, NULL), DAL_E_ARG, F.bld);
}
static void sw_dal_builder_add_potential_q(void) {
  BL(dal_builder_add_potential_q(NULL, pot_q, NULL), DAL_E_ARG, NULL);
  BL(dal_builder_add_potential_q(F.bld, NULL, NULL), DAL_E_ARG, F.bld);
}
static void sw_dal_builder_add_force(void) {
  BL(dal_builder_add_force(NULL, force_cb, NULL), DAL_E_ARG, NULL);
  BL(dal_builder_add_force(F.bld, NULL, NULL), DAL_E_ARG, F.bld);
}
static void sw_dal_builder_add_genforce(void) {
  BL(dal_builder_add_genforce(NULL, genforce_cb, NULL), DAL_E_ARG, NULL);
  BL(dal_builder_add_genforce(F.bld, NULL, NULL), DAL_E_ARG, F.bld);
}
static void sw_dal_builder_compile(void) {
  dal_system *s = (dal_system *)&F;
  BL(dal_builder_compile(NULL, &s), DAL_E_ARG, NULL);
  BL(dal_builder_compile(F.bld, NULL), DAL_E_ARG, F.bld);
  // the particle of bld was never placed: refused by name, *out NULL
  BL(dal_builder_compile(F.bld, &s), DAL_E_ARG, F.bld);
  CHECK(s == NULL);
}
static void sw_dal_system_destroy(void) { dal_system_destroy(NULL); }
static void sw_dal_system_dim(void) {
  CHECK(dal_system_dim(NULL) == 0 && dal_system_dim(F.A) == 2);
}
static void sw_dal_system_ncoords(void) {
  CHECK(dal_system_ncoords(NULL) == 0 && dal_system_ncoords(F.A) == 2);
}
static void sw_dal_system_nparticles(void) {
  CHECK(dal_system_nparticles(NULL) == 0 && dal_system_nparticles(F.A) == 1);
}
static void sw_dal_system_nconstraints(void) {
  CHECK(dal_system_nconstraints(NULL) == 0 && dal_system_nconstraints(F.A) == 1);
}
typedef const char *name_fn(const dal_system *, int);
static void names(name_fn *fn, int count) {
  CHECK(fn(NULL, 0) == NULL && fn(F.A, -1) == NULL && fn(F.A, count) == NULL);
  CHECK(fn(F.A, INT_MIN) == NULL && fn(F.A, INT_MAX) == NULL && fn(F.A, 0) != NULL);
}
static void sw_dal_system_coord_name(void) { names(dal_system_coord_name, 2); }
static void sw_dal_system_particle_name(void) { names(dal_system_particle_name, 1); }
static void sw_dal_system_constraint_name(void) { names(dal_system_constraint_name, 1); }
static void sw_dal_system_mass(void) {
  CHECK(isnan(dal_system_mass(NULL, 0)) && isnan(dal_system_mass(F.A, -1)));
  CHECK(isnan(dal_system_mass(F.A, 1)) && dal_system_mass(F.A, 0) == 1.0);
}

// ---------------------------------------------------------------- the table
typedef struct sweep_row {
  const char *name;
  void (*run)(void);
} sweep_row;

#define ROW(f)                                                                                     \
  { #f, sw_##f }
static const sweep_row rows[] = {
    ROW(dal_status_string),
    ROW(dal_status_name),
    ROW(dal_version),
    ROW(dal_make_consistent),
    ROW(dal_check_constraints),
    ROW(dal_constraint_forces),
    ROW(dal_constraint_genforces),
    ROW(dal_primitive_count),
    ROW(dal_primitive_get),
    ROW(dal_primitive_find),
    ROW(dal_solve_default_opts),
    ROW(dal_method_name),
    ROW(dal_formulation_name),
    ROW(dal_state_stats),
    ROW(dal_advance),
    ROW(dal_evolve),
    ROW(dal_csv_monitor),
    ROW(dal_state_create),
    ROW(dal_state_destroy),
    ROW(dal_state_errmsg),
    ROW(dal_state_set),
    ROW(dal_forward),
    ROW(dal_state_time),
    ROW(dal_state_q),
    ROW(dal_state_qdot),
    ROW(dal_state_qddot),
    ROW(dal_state_positions),
    ROW(dal_state_velocities),
    ROW(dal_state_accelerations),
    ROW(dal_state_drdt),
    ROW(dal_state_gamma),
    ROW(dal_state_jacobian),
    ROW(dal_state_mass_matrix),
    ROW(dal_state_genforces),
    ROW(dal_state_bias),
    ROW(dal_state_forces),
    ROW(dal_state_reactions),
    ROW(dal_state_lambda),
    ROW(dal_state_phi),
    ROW(dal_state_phidot),
    ROW(dal_state_energies),
    ROW(dal_lagrange_residual),
    ROW(dal_builder_create),
    ROW(dal_builder_destroy),
    ROW(dal_builder_errmsg),
    ROW(dal_builder_add_coord),
    ROW(dal_builder_add_particle),
    ROW(dal_builder_place),
    ROW(dal_builder_set_map),
    ROW(dal_builder_set_lagrangian),
    ROW(dal_builder_add_constraint),
    ROW(dal_builder_set_gravity),
    ROW(dal_builder_add_spring),
    ROW(dal_builder_add_anchor_spring),
    ROW(dal_builder_add_damper),
    ROW(dal_builder_add_anchor_damper),
    ROW(dal_builder_add_potential_r),
    ROW(dal_builder_add_potential_q),
    ROW(dal_builder_add_force),
    ROW(dal_builder_add_genforce),
    ROW(dal_builder_compile),
    ROW(dal_system_destroy),
    ROW(dal_system_dim),
    ROW(dal_system_ncoords),
    ROW(dal_system_nparticles),
    ROW(dal_system_nconstraints),
    ROW(dal_system_coord_name),
    ROW(dal_system_particle_name),
    ROW(dal_system_constraint_name),
    ROW(dal_system_mass),
};
#define NROWS ((int)(sizeof rows / sizeof rows[0]))

// ---------------------------------------------------------------- header scan
#define MAX_API 512

// append the names of the DAL_API functions declared in text (not the DAL_API data objects:
// their declarations have no parameter list)
static int scan_header(const char *text, char names[][64], int n) {
  for (const char *p = strstr(text, "DAL_API"); p && n < MAX_API; p = strstr(p + 7, "DAL_API")) {
    // skip the macro's own definition lines (#define DAL_API ...)
    const char *line = p;
    while (line > text && line[-1] != '\n')
      --line;
    if (line[0] == '#') continue;
    const char *end = p + strcspn(p, ";{");
    const char *paren = memchr(p, '(', (size_t)(end - p));
    if (!paren) continue; // a data object
    const char *e = paren;
    while (e > p && isspace((unsigned char)e[-1]))
      --e;
    const char *b = e;
    while (b > p && (isalnum((unsigned char)b[-1]) || b[-1] == '_'))
      --b;
    if (e - b <= 0 || e - b >= 64) continue;
    memcpy(names[n], b, (size_t)(e - b));
    names[n][e - b] = 0;
    ++n;
  }
  return n;
}

static char *read_all(const char *path) {
  FILE *fp = fopen(path, "rb");
  if (!fp) return NULL;
  fseek(fp, 0, SEEK_END);
  long len = ftell(fp);
  rewind(fp);
  char *s = len >= 0 ? malloc((size_t)len + 1) : NULL;
  if (s && fread(s, 1, (size_t)len, fp) != (size_t)len) {
    free(s);
    s = NULL;
  }
  if (s) s[len] = 0;
  fclose(fp);
  return s;
}

// the public functions of every header in dir; -1 when the directory cannot be read
static int scan_headers(const char *dir, char names[][64]) {
  DIR *d = opendir(dir);
  if (!d) return -1;
  int n = 0, files = 0;
  for (struct dirent *e; (e = readdir(d)) != NULL;) {
    size_t len = strlen(e->d_name);
    if (len < 3 || strcmp(e->d_name + len - 2, ".h") != 0) continue;
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    char *text = read_all(path);
    if (!text) continue;
    n = scan_header(text, names, n);
    ++files;
    free(text);
  }
  closedir(d);
  return files ? n : -1;
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s INCLUDE_DIR/dalembert\n", argv[0]);
    return 2;
  }
  static char api[MAX_API][64];
  int napi = scan_headers(argv[1], api);
  CHECK_MSG(napi > 0, "no public functions found in %s", argv[1]);
  // every public function has a row, every row a public function
  for (int i = 0; i < napi; ++i) {
    int found = 0;
    for (int r = 0; r < NROWS && !found; ++r)
      found = strcmp(api[i], rows[r].name) == 0;
    CHECK_MSG(found,
              "public function %s has no row in tests/test_api_sweep.c: add one (NULL, "
              "foreign and out-of-range arguments)",
              api[i]);
  }
  for (int r = 0; r < NROWS; ++r) {
    int found = 0;
    for (int i = 0; i < napi && !found; ++i)
      found = strcmp(api[i], rows[r].name) == 0;
    CHECK_MSG(found, "row %s names no public function of %s", rows[r].name, argv[1]);
  }
  fix_make();
  for (int r = 0; r < NROWS; ++r) {
    int before = check_failures;
    rows[r].run();
    if (check_failures != before) fprintf(stderr, "row %s failed\n", rows[r].name);
  }
  // after the whole sweep the fixtures still work: the builder compiles once its particle is
  // placed, and both states integrate
  int c[2] = {0, 1};
  CHECK_OK(dal_builder_place(F.bld, 0, &dal_map_cartesian2, -1, 2, c, 0, NULL, NULL));
  dal_system *s = NULL;
  CHECK_OK(dal_builder_compile(F.bld, &s));
  CHECK(dal_system_ncoords(s) == 2 && dal_system_nparticles(s) == 1 &&
        dal_system_nconstraints(s) == 0);
  dal_system_destroy(s);
  CHECK_OK(dal_advance(F.A, F.stA, &F.o, 0.1));
  CHECK_OK(dal_advance(F.B, F.stB, &F.o, 0.1));
  fix_free();
  printf("test_api_sweep: %d public functions, %d rows\n", napi, NROWS);
  return check_summary("test_api_sweep");
}
