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
// non-finite real is DAL_E_NONFINITE; destroy(NULL) does nothing;
// accessors answer NULL (pointers), NaN (reals) or 0 (counts) to a NULL object.
#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "headers.h"
#include "scenes.h"

// ---------------------------------------------------------------- fixtures
// A: Cartesian pendulum 'bob' on rod 'rod' (2 coordinates, 1 constraint row), evaluated;
// B: a planar pendulum in minimal coordinates (1 coordinate), evaluated. stA, stB their
// states; bld a builder that stays valid throughout.
typedef struct fix {
  dal_builder *bld;
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
  double q[2] = {0.6, -0.8}, qd[2] = {0.0, 0.0}, th0 = 0.3, thd = 0.0, v = 0.0;
  F.A = scn_cart_pendulum(NULL); // the standard scenes (tests/support/scenes.h)
  F.B = scn_pendulum(NULL);
  CHECK(F.A != NULL && F.B != NULL);
  if (!F.A || !F.B) return;
  // the names, sizes and values the rows rely on
  CHECK(dal_system_ncoords(F.A) == 2 && dal_system_nconstraints(F.A) == 1);
  CHECK(dal_system_ncoords(F.B) == 1 && dal_system_nconstraints(F.B) == 0);
  CHECK(strcmp(dal_system_coord_name(F.A, 0), "x") == 0);
  CHECK(strcmp(dal_system_coord_name(F.A, 1), "y") == 0);
  CHECK(strcmp(dal_system_coord_name(F.B, 0), "theta") == 0);
  CHECK(strcmp(dal_system_particle_name(F.A, 0), "bob") == 0);
  CHECK(strcmp(dal_system_particle_name(F.B, 0), "bob") == 0);
  CHECK(strcmp(dal_system_constraint_name(F.A, 0), "rod") == 0);
  CHECK(dal_system_mass(F.A, 0) == 1.0 && dal_system_mass(F.B, 0) == 1.0);
  CHECK(dal_system_param(F.A, &(dal_param_ref){DAL_PARAM_CONSTRAINT, 0, 0}, &v) == 0 && v == 1.0);
  CHECK(dal_system_param(F.B, &(dal_param_ref){DAL_PARAM_PLACE, 0, DAL_PENDULUM_L}, &v) == 0 &&
        v == 1.0);
  CHECK(dal_system_param(F.A, &(dal_param_ref){DAL_PARAM_GRAVITY, 0, 1}, &v) == 0 && v == -9.81);
  CHECK(dal_system_param(F.B, &(dal_param_ref){DAL_PARAM_GRAVITY, 0, 1}, &v) == 0 && v == -9.81);
  CHECK(dal_system_param(F.A, &(dal_param_ref){DAL_PARAM_GRAVITY, 0, 0}, &v) == 0 && v == 0.0);
  CHECK_OK(dal_state_create(F.A, &F.stA));
  CHECK_OK(dal_state_set(F.A, F.stA, 0.0, q, qd));
  CHECK_OK(dal_forward(F.A, F.stA));
  CHECK_OK(dal_state_create(F.B, &F.stB));
  CHECK_OK(dal_state_set(F.B, F.stB, 0.0, &th0, &thd));
  CHECK_OK(dal_forward(F.B, F.stB));
  CHECK_OK(dal_builder_create(2, &F.bld));
  CHECK_OK(dal_builder_add_coord(F.bld, "u", NULL));
  CHECK_OK(dal_builder_add_coord(F.bld, "w", NULL));
  CHECK_OK(dal_builder_add_particle(F.bld, "p", 1.0, NULL));
  F.o = dal_default_solve_opts();
}

static void fix_free(void) {
  dal_state_destroy(F.stA);
  dal_state_destroy(F.stB);
  dal_system_destroy(F.A);
  dal_system_destroy(F.B);
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
// the three rows every (system, state, ...) call shares: no state (DAL_E_ARG, no message), no
// system, and a system `other` the state does not belong to (DAL_E_STATE, a message in st)
#define ST_OWNER(fn, own, other, st, ...)                                                          \
  do {                                                                                             \
    ST(fn(own, NULL, __VA_ARGS__), DAL_E_ARG, NULL);                                               \
    ST(fn(NULL, st, __VA_ARGS__), DAL_E_STATE, st);                                                \
    ST(fn(other, st, __VA_ARGS__), DAL_E_STATE, st);                                               \
  } while (0)
#define ST_OWNER2(fn, own, other, st)                                                              \
  do {                                                                                             \
    ST(fn(own, NULL), DAL_E_ARG, NULL);                                                            \
    ST(fn(NULL, st), DAL_E_STATE, st);                                                             \
    ST(fn(other, st), DAL_E_STATE, st);                                                            \
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

static dal_builder *scratch(int placed); // a builder for calls that succeed (below)

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
  CHECK(strcmp(dal_status_name(4), "DAL_UNKNOWN") == 0);
  CHECK(strcmp(dal_status_name(3), "DAL_CANCELLED") == 0);
  CHECK(strcmp(dal_status_name(1), "DAL_STOPPED") == 0); // the positive statuses
  CHECK(strcmp(dal_status_name(2), "DAL_EVENT") == 0);
  CHECK(strcmp(dal_status_name(INT_MAX), "DAL_UNKNOWN") == 0);
  CHECK(strcmp(dal_status_name(DAL_E_STATE), "DAL_E_STATE") == 0);
}
static void sw_dal_version(void) { CHECK(dal_version() != NULL && dal_version()[0] != 0); }

// ---------------------------------------------------------------- rows: dae.h
static void sw_dal_make_consistent(void) {
  dal_init_report rep;
  ST_OWNER(dal_make_consistent, F.A, F.B, F.stA, 0.0, &rep);
  ST(dal_make_consistent(F.A, F.stA, NAN, &rep), DAL_E_NONFINITE, F.stA);
  ST(dal_make_consistent(F.A, F.stA, INFINITY, NULL), DAL_E_NONFINITE, F.stA);
  st_intact();
  ST(dal_make_consistent(F.A, F.stA, 0.0, NULL), DAL_OK, F.stA);
}
static void sw_dal_check_constraints(void) {
  dal_constraint_report rep;
  ST_OWNER(dal_check_constraints, F.A, F.B, F.stA, &rep);
  ST(dal_check_constraints(F.A, F.stA, NULL), DAL_OK, F.stA);
}
// a (system, const state, out) reader: NULL state, NULL or foreign system, NULL out, then ok
typedef int state_reader_fn(const dal_system *sys, const dal_state *st, double *out);
static void reader_rows(state_reader_fn *fn, const dal_system *own, dal_state *st,
                        const dal_system *other, double *out) {
  ST(fn(own, NULL, out), DAL_E_ARG, NULL);
  ST(fn(NULL, st, out), DAL_E_STATE, st);
  ST(fn(other, st, out), DAL_E_STATE, st);
  ST(fn(own, st, NULL), DAL_E_ARG, st);
  ST(fn(own, st, out), DAL_OK, st);
}
static void sw_dal_joint_forces(void) {
  double Fo[2];
  CHECK_OK(dal_forward(F.B, F.stB));
  reader_rows(dal_joint_forces, F.B, F.stB, F.A, Fo);
  CHECK(isfinite(Fo[0]) && isfinite(Fo[1]) && Fo[1] > 0); // the rod holds the bob up
  st_intact();
}
static void sw_dal_constraint_forces(void) {
  double Fo[2];
  CHECK_OK(dal_forward(F.A, F.stA));
  reader_rows(dal_constraint_forces, F.A, F.stA, F.B, Fo);
  // the minimal system has no explicit constraints: zero forces, DAL_OK
  double Fb[2] = {7, 7};
  ST(dal_constraint_forces(F.B, F.stB, Fb), DAL_OK, F.stB);
  CHECK(Fb[0] == 0.0 && Fb[1] == 0.0);
}
static void sw_dal_constraint_genforces(void) {
  double Q[2];
  reader_rows(dal_constraint_genforces, F.A, F.stA, F.B, Q);
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
static void sw_dal_default_solve_opts(void) {
  dal_solve_opts o;
  memset(&o, 0xff, sizeof o);
  o = dal_default_solve_opts(); // every field written, the cookie too
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
  ST_OWNER(dal_advance, F.A, F.B, F.stA, &F.o, 1.0);
  ST(dal_advance(F.A, F.stA, NULL, 1.0), DAL_E_ARG, F.stA);
  ST(dal_advance(F.A, F.stA, &bad, 1.0), DAL_E_ARG, F.stA);
  ST(dal_advance(F.A, F.stA, &F.o, NAN), DAL_E_NONFINITE, F.stA);
  ST(dal_advance(F.A, F.stA, &F.o, -INFINITY), DAL_E_NONFINITE, F.stA);
  ST(dal_advance(F.A, F.stA, &F.o, -1.0), DAL_E_TIME, F.stA);
  st_intact();
}
static void sw_dal_evolve(void) {
  ST_OWNER(dal_evolve, F.A, F.B, F.stA, &F.o, 1.0, 0.1, NULL, NULL);
  ST(dal_evolve(F.A, F.stA, NULL, 1.0, 0.1, NULL, NULL), DAL_E_ARG, F.stA);
  ST(dal_evolve(F.A, F.stA, &F.o, NAN, 0.1, NULL, NULL), DAL_E_NONFINITE, F.stA);
  ST(dal_evolve(F.A, F.stA, &F.o, 1.0, NAN, NULL, NULL), DAL_E_NONFINITE, F.stA);
  ST(dal_evolve(F.A, F.stA, &F.o, 1.0, INFINITY, NULL, NULL), DAL_E_NONFINITE, F.stA);
  ST(dal_evolve(F.A, F.stA, &F.o, 1.0, 0.0, NULL, NULL), DAL_E_ARG, F.stA);
  ST(dal_evolve(F.A, F.stA, &F.o, 1.0, -0.1, NULL, NULL), DAL_E_ARG, F.stA);
  st_intact();
}
static void sw_dal_evolve_at(void) {
  const double ts[2] = {0.5, 1.0}, dec[3] = {0.5, 1.0, 0.7}, nan2[2] = {0.5, NAN};
  const double back[2] = {-1.0, 1.0};
  ST_OWNER(dal_evolve_at, F.A, F.B, F.stA, &F.o, ts, 2, NULL, NULL);
  ST(dal_evolve_at(F.A, F.stA, NULL, ts, 2, NULL, NULL), DAL_E_ARG, F.stA);
  ST(dal_evolve_at(F.A, F.stA, &F.o, NULL, 2, NULL, NULL), DAL_E_ARG, F.stA);
  ST(dal_evolve_at(F.A, F.stA, &F.o, ts, 0, NULL, NULL), DAL_E_ARG, F.stA);
  ST(dal_evolve_at(F.A, F.stA, &F.o, dec, 3, NULL, NULL), DAL_E_ARG, F.stA);
  ST(dal_evolve_at(F.A, F.stA, &F.o, nan2, 2, NULL, NULL), DAL_E_NONFINITE, F.stA);
  ST(dal_evolve_at(F.A, F.stA, &F.o, back, 2, NULL, NULL), DAL_E_TIME, F.stA);
  st_intact();
}
static void sw_dal_csv_monitor(void) {
  dal_csv none = {NULL, 0, 0, NULL};
  FILE *fp = tmpfile();
  dal_csv ok = {fp, 0, 0, NULL};
  ST_OWNER(dal_csv_monitor, F.A, F.B, F.stA, &ok);
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
  ST_OWNER(dal_state_set, F.A, F.B, F.stA, 0.0, q, qd);
  ST(dal_state_set(F.A, F.stA, 0.0, NULL, qd), DAL_E_ARG, F.stA);
  ST(dal_state_set(F.A, F.stA, 0.0, q, NULL), DAL_E_ARG, F.stA);
  ST(dal_state_set(F.A, F.stA, NAN, q, qd), DAL_E_NONFINITE, F.stA);
  ST(dal_state_set(F.A, F.stA, 0.0, qn, qd), DAL_E_NONFINITE, F.stA);
  ST(dal_state_set(F.A, F.stA, 0.0, qd, qn), DAL_E_NONFINITE, F.stA);
  st_intact();
}
static void sw_dal_forward(void) {
  ST_OWNER2(dal_forward, F.A, F.B, F.stA);
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
  ST_OWNER(dal_state_jacobian, F.A, F.B, F.stA, 0, J);
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
  ST_OWNER(dal_lagrange_residual, F.A, F.B, F.stA, path_q, 0.0, res, NULL);
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
static void sw_dal_builder_set_map(void) {
  BL(dal_builder_set_map(NULL, map_fn, NULL), DAL_E_ARG, NULL);
  BL(dal_builder_set_map(F.bld, NULL, NULL), DAL_E_ARG, F.bld);
}
static void sw_dal_builder_set_lagrangian(void) {
  BL(dal_builder_set_lagrangian(NULL, lag_fn, NULL), DAL_E_ARG, NULL);
  BL(dal_builder_set_lagrangian(F.bld, NULL, NULL), DAL_E_ARG, F.bld);
  BL(dal_builder_set_lagrangian(F.bld, lag_fn, NULL), DAL_E_ARG, F.bld); // has a particle
}
static void sw_dal_builder_set_gravity(void) {
  double g[3] = {0.0, -9.81, 0.0}, gn[3] = {0.0, NAN, 0.0};
  BL(dal_builder_set_gravity(NULL, g), DAL_E_ARG, NULL);
  BL(dal_builder_set_gravity(F.bld, NULL), DAL_E_ARG, F.bld);
  BL(dal_builder_set_gravity(F.bld, gn), DAL_E_NONFINITE, F.bld);
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

// ---------------------------------------------------------------- helpers of the new rows
// a scratch builder for calls that succeed (F.bld must keep its one unplaced particle): 2-D,
// coordinates x, y, particle 's' (placed by dal_map_cartesian2 when `placed`)
static dal_builder *scratch(int placed) {
  dal_builder *b = NULL;
  int c[2] = {0, 1};
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "x", NULL));
  CHECK_OK(dal_builder_add_coord(b, "y", NULL));
  CHECK_OK(dal_builder_add_particle(b, "s", 1.0, NULL));
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_cartesian2;
  pd.coords = c;
  pd.ncoords = 2;
  if (placed) CHECK_OK(dal_builder_place_def(b, 0, &pd));
  return b;
}

// a fresh state of B at theta = 0.3 at rest, evaluated (for calls that move their state)
static dal_state *state_b(void) {
  dal_state *st = NULL;
  double th0 = 0.3, thd = 0.0;
  CHECK_OK(dal_state_create(F.B, &st));
  CHECK_OK(dal_state_set(F.B, st, 0.0, &th0, &thd));
  CHECK_OK(dal_forward(F.B, st));
  return st;
}

// the status of a call whose message goes into a caller's buffer (msg NULL: no message)
static void m_expect(const char *call, int rc, int want, const char *msg) {
  CHECK_MSG(rc == want, "%s: %s, expected %s", call, dal_status_name(rc), dal_status_name(want));
  if (msg && want != DAL_OK)
    CHECK_MSG(msg[0] != 0 && strcmp(msg, "stale") != 0, "%s: %s without a message of its own", call,
              dal_status_name(rc));
}
#define MS(call, want, msg)                                                                        \
  do {                                                                                             \
    if (msg) snprintf(msg, 8, "stale");                                                            \
    m_expect(#call, (int)(call), (want), (msg));                                                   \
  } while (0)

// stA after the rows that override its parameters: back to the system's values, evaluated
static void stA_restore(void) {
  double q[2] = {0.6, -0.8}, qd[2] = {0.0, 0.0};
  CHECK_OK(dal_state_reset_params(F.A, F.stA));
  CHECK_OK(dal_state_set(F.A, F.stA, 0.0, q, qd));
  CHECK_OK(dal_forward(F.A, F.stA));
}

// ---------------------------------------------------------------- rows: ensemble.h
static void sw_dal_default_sweep_opts(void) {
  dal_sweep_opts o;
  memset(&o, 0xff, sizeof o);
  o = dal_default_sweep_opts(); // every field written, the cookie too
  CHECK(o.nthreads == 1 && o.schedule == DAL_SCHEDULE_DYNAMIC && o.chunk == 1);
  CHECK(o.progress == NULL && o.part == 0 && o.nparts == 1 && o.part_block == 1);
}
static void sw_dal_sweep_part_of(void) {
  // one part, a negative index: part 0; block < 1 counts as 1
  CHECK(dal_sweep_part_of(5, 1, 1) == 0 && dal_sweep_part_of(5, 0, 1) == 0);
  CHECK(dal_sweep_part_of(5, INT_MIN, 1) == 0 && dal_sweep_part_of(-1, 3, 1) == 0);
  CHECK(dal_sweep_part_of(LONG_MIN, 3, 1) == 0 && dal_sweep_part_of(5, 3, 0) == 2);
  CHECK(dal_sweep_part_of(5, 3, INT_MIN) == 2 && dal_sweep_part_of(LONG_MAX, 2, INT_MAX) >= 0);
  // blocks of 2 dealt round-robin over 3 parts: 0 0 1 1 2 2 0 0 ...
  CHECK(dal_sweep_part_of(4, 3, 1) == 1 && dal_sweep_part_of(5, 3, 2) == 2);
  CHECK(dal_sweep_part_of(6, 3, 2) == 0);
}

static int reduce_q_mass(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx) {
  (void)ctx;
  dal_param_ref m = {DAL_PARAM_MASS, 0, 0};
  tr->result[0] = dal_state_q(st)[0];
  return dal_state_param(sys, st, &m, &tr->result[1]);
}

// a sweep of B over the mass of 'bob' (1 and 2), reducing to (theta, mass)
typedef struct sweep_fix {
  dal_param_ref ref;
  double values[2], q0, qd0, results[4];
  int status[2];
  char msgs[2 * 64];
  dal_sweep sw;
  dal_sweep_opts o;
  dal_sweep_out out;
} sweep_fix;

static void sweep_make(sweep_fix *s) {
  memset(s, 0, sizeof *s);
  s->ref = (dal_param_ref){DAL_PARAM_MASS, 0, 0};
  s->values[0] = 1.0;
  s->values[1] = 2.0;
  s->q0 = 0.3;
  s->sw = (dal_sweep){.ntraj = 2,
                      .nparam = 1,
                      .params = &s->ref,
                      .values = s->values,
                      .q0 = &s->q0,
                      .qdot0 = &s->qd0,
                      .nresult = 2,
                      .reduce = reduce_q_mass};
  s->o = dal_default_sweep_opts();
  s->out =
      (dal_sweep_out){.results = s->results, .status = s->status, .msgs = s->msgs, .msg_len = 64};
}

static void sw_dal_sweep_run(void) {
  sweep_fix s;
  sweep_make(&s);
  char err[256], *e = err;
  dal_sweep bad = s.sw;
  dal_sweep_opts raw;
  memset(&raw, 0, sizeof raw);
  MS(dal_sweep_run(NULL, &s.sw, &s.o, &s.out, e, sizeof err), DAL_E_ARG, e);
  MS(dal_sweep_run(F.B, NULL, &s.o, &s.out, e, sizeof err), DAL_E_ARG, e);
  MS(dal_sweep_run(F.B, &s.sw, NULL, &s.out, e, sizeof err), DAL_E_ARG, e);
  MS(dal_sweep_run(F.B, &s.sw, &s.o, NULL, e, sizeof err), DAL_E_ARG, e);
  MS(dal_sweep_run(F.B, &s.sw, &raw, &s.out, e, sizeof err), DAL_E_ARG, e);
  MS(dal_sweep_run(F.B, &s.sw, &s.o, &s.out, NULL, 0), DAL_OK, NULL);
  // a parameter of another system (A's constraint 'rod': B has none)
  bad.params = &(dal_param_ref){DAL_PARAM_CONSTRAINT, 0, 0};
  MS(dal_sweep_run(F.B, &bad, &s.o, &s.out, e, sizeof err), DAL_E_ARG, e);
  bad = s.sw;
  bad.ntraj = 0;
  MS(dal_sweep_run(F.B, &bad, &s.o, &s.out, e, sizeof err), DAL_E_ARG, e);
  bad = s.sw;
  bad.q0 = NULL;
  MS(dal_sweep_run(F.B, &bad, &s.o, &s.out, e, sizeof err), DAL_E_ARG, e);
  bad = s.sw;
  bad.state_stride = 2; // n = 1
  MS(dal_sweep_run(F.B, &bad, &s.o, &s.out, e, sizeof err), DAL_E_ARG, e);
  bad = s.sw;
  bad.solve = &F.o;
  bad.t1 = NAN;
  // NOTE: header says DAL_E_ARG for an invalid sweep (DAL_E_NONFINITE is not in its list)
  MS(dal_sweep_run(F.B, &bad, &s.o, &s.out, e, sizeof err), DAL_E_NONFINITE, e);
  dal_sweep_opts o2 = s.o;
  o2.part = 1; // of 1 part
  MS(dal_sweep_run(F.B, &s.sw, &o2, &s.out, e, sizeof err), DAL_E_ARG, e);
  o2 = s.o;
  o2.nthreads = -1;
  MS(dal_sweep_run(F.B, &s.sw, &o2, &s.out, e, sizeof err), DAL_E_ARG, e);
  dal_sweep_out o3 = s.out;
  o3.status = NULL;
  MS(dal_sweep_run(F.B, &s.sw, &s.o, &o3, e, sizeof err), DAL_E_ARG, e);
  // the valid sweep: each trajectory starts at q0 with its own mass (the values table)
  for (int i = 0; i < 4; ++i)
    s.results[i] = -1.0;
  MS(dal_sweep_run(F.B, &s.sw, &s.o, &s.out, e, sizeof err), DAL_OK, e);
  CHECK(s.out.nrun == 2 && s.out.nfailed == 0 && s.status[0] == 0 && s.status[1] == 0);
  CHECK(s.results[0] == 0.3 && s.results[1] == 1.0 && s.results[2] == 0.3 && s.results[3] == 2.0);
}
static void sw_dal_sweep_grid(void) {
  int count[2] = {2, 3}, zero[2] = {2, 0};
  double lo[2] = {0.0, 0.0}, hi[2] = {1.0, 2.0}, nan2[2] = {0.0, NAN}, v[12];
  CHECK(dal_sweep_grid(0, count, lo, hi, v) == DAL_E_ARG);
  CHECK(dal_sweep_grid(INT_MIN, count, lo, hi, v) == DAL_E_ARG);
  CHECK(dal_sweep_grid(2, NULL, lo, hi, v) == DAL_E_ARG);
  CHECK(dal_sweep_grid(2, count, NULL, hi, v) == DAL_E_ARG);
  CHECK(dal_sweep_grid(2, count, lo, NULL, v) == DAL_E_ARG);
  CHECK(dal_sweep_grid(2, count, lo, hi, NULL) == DAL_E_ARG);
  CHECK(dal_sweep_grid(2, zero, lo, hi, v) == DAL_E_ARG);
  CHECK(dal_sweep_grid(2, count, nan2, hi, v) == DAL_E_ARG);
  CHECK(dal_sweep_grid(2, count, lo, (double[2]){1.0, INFINITY}, v) == DAL_E_ARG);
  // rows (0,0) (0,1) (0,2) (1,0) (1,1) (1,2): the last axis fastest
  CHECK(dal_sweep_grid(2, count, lo, hi, v) == 6);
  CHECK(v[0] == 0.0 && v[1] == 0.0 && v[3] == 1.0 && v[5] == 2.0 && v[6] == 1.0 && v[11] == 2.0);
}
static void sw_dal_sweep_write_csv(void) {
  sweep_fix s;
  sweep_make(&s);
  CHECK_OK(dal_sweep_run(F.B, &s.sw, &s.o, &s.out, NULL, 0));
  FILE *fp = tmpfile(), *ro = fopen("/dev/null", "r");
  CHECK(fp != NULL && ro != NULL);
  if (!fp || !ro) return;
  dal_sweep bad = s.sw;
  bad.params = &(dal_param_ref){DAL_PARAM_SPRING_K, 0, 0}; // B has no spring
  dal_sweep_out o3 = s.out;
  o3.results = NULL;
  CHECK(dal_sweep_write_csv(NULL, F.B, &s.sw, &s.out, NULL) == DAL_E_ARG);
  CHECK(dal_sweep_write_csv(fp, NULL, &s.sw, &s.out, NULL) == DAL_E_ARG);
  CHECK(dal_sweep_write_csv(fp, F.B, NULL, &s.out, NULL) == DAL_E_ARG);
  CHECK(dal_sweep_write_csv(fp, F.B, &s.sw, NULL, NULL) == DAL_E_ARG);
  CHECK(dal_sweep_write_csv(fp, F.B, &s.sw, &o3, NULL) == DAL_E_ARG);
  CHECK(dal_sweep_write_csv(fp, F.B, &bad, &s.out, NULL) == DAL_E_ARG);
  CHECK(dal_sweep_write_csv(ro, F.B, &s.sw, &s.out, NULL) == DAL_E_IO);
  rewind(fp);
  CHECK(dal_sweep_write_csv(fp, F.B, &s.sw, &s.out, NULL) == DAL_OK);
  char head[64] = "";
  rewind(fp);
  CHECK(fgets(head, sizeof head, fp) != NULL);
  CHECK(strcmp(head, "index,mass:bob,status,r0,r1,message\n") == 0);
  fclose(fp);
  fclose(ro);
}

// ---------------------------------------------------------------- rows: params.h
static void sw_dal_param_find(void) {
  dal_param_ref r = {DAL_PARAM_NONE, 0, 0};
  char msg[256], *m = msg;
  MS(dal_param_find(NULL, "mass:bob", &r, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_find(F.A, NULL, &r, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_find(F.A, "mass:bob", NULL, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_find(F.A, "", &r, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_find(F.A, "mass:nobody", &r, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_find(F.A, "mass:1", &r, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_find(F.A, "con:rod:3", &r, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_find(F.A, "con:rod:-1", &r, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_find(F.A, "gravity:2", &r, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_find(F.A, "place:bob:0", &r, m, sizeof msg), DAL_E_ARG, m); // cartesian2: none
  MS(dal_param_find(F.A, "spring:0:k", &r, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_find(F.B, "con:rod:0", &r, m, sizeof msg), DAL_E_ARG, m); // A's constraint
  MS(dal_param_find(F.A, "mass:bob:0:1", &r, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_find(F.A, "nonsense", &r, NULL, 0), DAL_E_ARG, NULL);
  CHECK(r.kind == DAL_PARAM_NONE); // untouched on failure
  MS(dal_param_find(F.A, "con:rod:0", &r, m, sizeof msg), DAL_OK, m);
  CHECK(r.kind == DAL_PARAM_CONSTRAINT && r.target == 0 && r.index == 0);
  MS(dal_param_find(F.B, "place:bob:5", &r, m, sizeof msg), DAL_OK, m);
  CHECK(r.kind == DAL_PARAM_PLACE && r.target == 0 && r.index == 5);
}
static void sw_dal_param_check(void) {
  char msg[256], *m = msg;
  dal_param_ref mass = {DAL_PARAM_MASS, 0, 0};
  MS(dal_param_check(NULL, &mass, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_check(F.A, NULL, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_check(F.A, &(dal_param_ref){DAL_PARAM_NONE, 0, 0}, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_check(F.A, &(dal_param_ref){(dal_param_kind)99, 0, 0}, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_check(F.A, &(dal_param_ref){DAL_PARAM_MASS, -1, 0}, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_check(F.A, &(dal_param_ref){DAL_PARAM_MASS, 1, 0}, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_check(F.A, &(dal_param_ref){DAL_PARAM_MASS, INT_MIN, 0}, m, sizeof msg), DAL_E_ARG,
     m);
  MS(dal_param_check(F.B, &(dal_param_ref){DAL_PARAM_PLACE, 0, 7}, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_check(F.B, &(dal_param_ref){DAL_PARAM_PLACE, 0, -1}, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_check(F.B, &(dal_param_ref){DAL_PARAM_CONSTRAINT, 0, 0}, m, sizeof msg), DAL_E_ARG,
     m);
  MS(dal_param_check(F.A, &(dal_param_ref){DAL_PARAM_CONSTRAINT, 0, INT_MAX}, m, sizeof msg),
     DAL_E_ARG, m);
  MS(dal_param_check(F.A, &(dal_param_ref){DAL_PARAM_GRAVITY, 0, 2}, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_check(F.A, &(dal_param_ref){DAL_PARAM_SPRING_L, 0, 0}, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_check(F.A, &(dal_param_ref){DAL_PARAM_DAMPER_C, 0, 0}, m, sizeof msg), DAL_E_ARG, m);
  MS(dal_param_check(F.A, &(dal_param_ref){DAL_PARAM_SPRING_K, 0, 0}, NULL, 0), DAL_E_ARG, NULL);
  MS(dal_param_check(F.A, &mass, m, sizeof msg), DAL_OK, m);
  MS(dal_param_check(F.B, &(dal_param_ref){DAL_PARAM_PLACE, 0, 6}, m, sizeof msg), DAL_OK, m);
}
static void sw_dal_param_name(void) {
  char buf[64];
  dal_param_ref rod = {DAL_PARAM_CONSTRAINT, 0, 0};
  CHECK(dal_param_name(NULL, &rod, buf, sizeof buf) == DAL_E_ARG);
  CHECK(dal_param_name(F.A, NULL, buf, sizeof buf) == DAL_E_ARG);
  CHECK(dal_param_name(F.A, &rod, NULL, sizeof buf) == DAL_E_ARG);
  CHECK(dal_param_name(F.A, &rod, buf, 0) == DAL_E_ARG);
  CHECK(dal_param_name(F.B, &rod, buf, sizeof buf) == DAL_E_ARG); // B has no constraint
  CHECK(dal_param_name(F.A, &(dal_param_ref){DAL_PARAM_NONE, 0, 0}, buf, sizeof buf) == DAL_E_ARG);
  CHECK(dal_param_name(F.A, &rod, buf, sizeof buf) == DAL_OK && strcmp(buf, "con:rod:0") == 0);
  CHECK(dal_param_name(F.A, &rod, buf, 4) == DAL_OK && strcmp(buf, "con") == 0); // truncated
}
static void sw_dal_system_param(void) {
  double v = -1.0;
  dal_param_ref rod = {DAL_PARAM_CONSTRAINT, 0, 0}, g1 = {DAL_PARAM_GRAVITY, 0, 1};
  CHECK(dal_system_param(NULL, &rod, &v) == DAL_E_ARG);
  CHECK(dal_system_param(F.A, NULL, &v) == DAL_E_ARG);
  CHECK(dal_system_param(F.A, &rod, NULL) == DAL_E_ARG);
  CHECK(dal_system_param(F.B, &rod, &v) == DAL_E_ARG);
  CHECK(dal_system_param(F.A, &(dal_param_ref){DAL_PARAM_GRAVITY, 0, -1}, &v) == DAL_E_ARG);
  CHECK(v == -1.0);
  // the values given to the builders in fix_make
  CHECK(dal_system_param(F.A, &rod, &v) == DAL_OK && v == 1.0);
  CHECK(dal_system_param(F.B, &g1, &v) == DAL_OK && v == -9.81);
}
static void sw_dal_state_param(void) {
  double v = -1.0;
  dal_param_ref rod = {DAL_PARAM_CONSTRAINT, 0, 0};
  // the state is const: no message can be kept
  ST(dal_state_param(F.A, NULL, &rod, &v), DAL_E_ARG, NULL);
  ST(dal_state_param(NULL, F.stA, &rod, &v), DAL_E_STATE, NULL);
  ST(dal_state_param(F.B, F.stA, &rod, &v), DAL_E_STATE, NULL);
  ST(dal_state_param(F.A, F.stA, NULL, &v), DAL_E_ARG, NULL);
  ST(dal_state_param(F.A, F.stA, &rod, NULL), DAL_E_ARG, NULL);
  ST(dal_state_param(F.A, F.stA, &(dal_param_ref){DAL_PARAM_MASS, 3, 0}, &v), DAL_E_ARG, NULL);
  CHECK(v == -1.0);
  ST(dal_state_param(F.A, F.stA, &rod, &v), DAL_OK, NULL);
  CHECK(v == 1.0);
}
static void sw_dal_state_set_param(void) {
  dal_param_ref mass = {DAL_PARAM_MASS, 0, 0}, g0 = {DAL_PARAM_GRAVITY, 0, 0};
  dal_param_ref sp = {DAL_PARAM_SPRING_K, 0, 0};
  ST_OWNER(dal_state_set_param, F.A, F.B, F.stA, &mass, 2.0);
  ST(dal_state_set_param(F.A, F.stA, NULL, 2.0), DAL_E_ARG, F.stA);
  ST(dal_state_set_param(F.A, F.stA, &sp, 2.0), DAL_E_ARG, F.stA);
  ST(dal_state_set_param(F.A, F.stA, &mass, NAN), DAL_E_NONFINITE, F.stA);
  ST(dal_state_set_param(F.A, F.stA, &mass, INFINITY), DAL_E_NONFINITE, F.stA);
  ST(dal_state_set_param(F.A, F.stA, &mass, 0.0), DAL_E_ARG, F.stA);
  ST(dal_state_set_param(F.A, F.stA, &mass, -1.0), DAL_E_ARG, F.stA);
  ST(dal_state_set_param(F.A, F.stA, &g0, -INFINITY), DAL_E_NONFINITE, F.stA);
  st_intact();
  double v = 0.0;
  ST(dal_state_set_param(F.A, F.stA, &mass, 2.0), DAL_OK, F.stA);
  CHECK(dal_state_param(F.A, F.stA, &mass, &v) == DAL_OK && v == 2.0);
  CHECK(dal_system_param(F.A, &mass, &v) == DAL_OK && v == 1.0); // the system is untouched
  stA_restore();
}
static void sw_dal_state_set_param_named(void) {
  dal_param_ref rod = {DAL_PARAM_CONSTRAINT, 0, 0};
  ST_OWNER(dal_state_set_param_named, F.A, F.B, F.stA, "con:rod:0", 1.5);
  ST(dal_state_set_param_named(F.A, F.stA, NULL, 1.5), DAL_E_ARG, F.stA);
  ST(dal_state_set_param_named(F.A, F.stA, "con:nothing:0", 1.5), DAL_E_ARG, F.stA);
  ST(dal_state_set_param_named(F.A, F.stA, "con:rod:9", 1.5), DAL_E_ARG, F.stA);
  ST(dal_state_set_param_named(F.A, F.stA, "con:rod:0", NAN), DAL_E_NONFINITE, F.stA);
  st_intact();
  double v = 0.0;
  ST(dal_state_set_param_named(F.A, F.stA, "con:rod:0", 1.5), DAL_OK, F.stA);
  CHECK(dal_state_param(F.A, F.stA, &rod, &v) == DAL_OK && v == 1.5);
  stA_restore();
}
static void sw_dal_state_set_mass(void) {
  dal_param_ref mass = {DAL_PARAM_MASS, 0, 0};
  ST_OWNER(dal_state_set_mass, F.A, F.B, F.stA, 0, 2.0);
  ST(dal_state_set_mass(F.A, F.stA, -1, 2.0), DAL_E_ARG, F.stA);
  ST(dal_state_set_mass(F.A, F.stA, 1, 2.0), DAL_E_ARG, F.stA);
  ST(dal_state_set_mass(F.A, F.stA, INT_MAX, 2.0), DAL_E_ARG, F.stA);
  ST(dal_state_set_mass(F.A, F.stA, 0, NAN), DAL_E_NONFINITE, F.stA);
  ST(dal_state_set_mass(F.A, F.stA, 0, -INFINITY), DAL_E_NONFINITE, F.stA);
  ST(dal_state_set_mass(F.A, F.stA, 0, 0.0), DAL_E_ARG, F.stA);
  st_intact();
  double v = 0.0;
  ST(dal_state_set_mass(F.A, F.stA, 0, 3.0), DAL_OK, F.stA);
  CHECK(dal_state_param(F.A, F.stA, &mass, &v) == DAL_OK && v == 3.0);
  stA_restore();
}
static void sw_dal_state_set_gravity(void) {
  double g[2] = {0.0, -1.62}, gn[2] = {NAN, 0.0}, gi[2] = {0.0, INFINITY}, v = 0.0;
  dal_param_ref g1 = {DAL_PARAM_GRAVITY, 0, 1};
  ST_OWNER(dal_state_set_gravity, F.A, F.B, F.stA, g);
  ST(dal_state_set_gravity(F.A, F.stA, NULL), DAL_E_ARG, F.stA);
  ST(dal_state_set_gravity(F.A, F.stA, gn), DAL_E_NONFINITE, F.stA);
  ST(dal_state_set_gravity(F.A, F.stA, gi), DAL_E_NONFINITE, F.stA);
  st_intact();
  CHECK(dal_state_param(F.A, F.stA, &g1, &v) == DAL_OK && v == -9.81); // unchanged
  ST(dal_state_set_gravity(F.A, F.stA, g), DAL_OK, F.stA);
  CHECK(dal_state_param(F.A, F.stA, &g1, &v) == DAL_OK && v == -1.62);
  stA_restore();
}
static void sw_dal_state_reset_params(void) {
  dal_param_ref mass = {DAL_PARAM_MASS, 0, 0};
  double v = 0.0;
  ST_OWNER2(dal_state_reset_params, F.A, F.B, F.stA);
  st_intact();
  CHECK_OK(dal_state_set_mass(F.A, F.stA, 0, 4.0));
  ST(dal_state_reset_params(F.A, F.stA), DAL_OK, F.stA);
  CHECK(dal_state_param(F.A, F.stA, &mass, &v) == DAL_OK && v == 1.0);
  stA_restore();
}
static void sw_dal_state_copy_params(void) {
  dal_param_ref mass = {DAL_PARAM_MASS, 0, 0};
  dal_state *st2 = NULL;
  double v = 0.0;
  CHECK_OK(dal_state_create(F.A, &st2));
  ST(dal_state_copy_params(F.A, NULL, F.stA), DAL_E_ARG, NULL);
  // dst is given but keeps no message for a NULL src (the header promises only the status)
  ST(dal_state_copy_params(F.A, F.stA, NULL), DAL_E_ARG, NULL);
  ST(dal_state_copy_params(NULL, F.stA, st2), DAL_E_STATE, F.stA);
  ST(dal_state_copy_params(F.B, F.stA, st2), DAL_E_STATE, F.stA);
  ST(dal_state_copy_params(F.A, F.stB, F.stA), DAL_E_STATE, F.stB); // dst of another system
  ST(dal_state_copy_params(F.A, F.stA, F.stB), DAL_E_STATE, F.stA); // src of another system
  st_intact();
  CHECK_OK(dal_state_set_mass(F.A, F.stA, 0, 5.0));
  ST(dal_state_copy_params(F.A, F.stA, F.stA), DAL_OK, F.stA);
  ST(dal_state_copy_params(F.A, st2, F.stA), DAL_OK, NULL);
  CHECK(dal_state_param(F.A, st2, &mass, &v) == DAL_OK && v == 5.0);
  dal_state_destroy(st2);
  stA_restore();
}

// ---------------------------------------------------------------- rows: verify.h
static void sw_dal_default_verify_opts(void) {
  dal_verify_opts o;
  memset(&o, 0xff, sizeof o);
  o = dal_default_verify_opts(); // every field written, the cookie too
  CHECK(o.nsamples == 16 && o.lo == -1.0 && o.hi == 1.0 && o.in_lo == NULL && o.in_hi == NULL);
  CHECK(o.t_lo == 0.0 && o.t_hi == 1.0 && o.h == 1e-3 && o.tol_factor == 10.0 && o.seed == 1);
}
// options every jet check refuses (DAL_E_ARG with the report's message)
static void verify_bad_opts(dal_verify_opts *few, dal_verify_opts *nan_lo, dal_verify_opts *inf_t,
                            dal_verify_opts *zero_h) {
  *few = dal_default_verify_opts();
  few->nsamples = 0;
  *nan_lo = dal_default_verify_opts();
  nan_lo->lo = NAN;
  *inf_t = dal_default_verify_opts();
  inf_t->t_hi = INFINITY;
  *zero_h = dal_default_verify_opts();
  zero_h->h = 0.0;
}
static void sw_dal_verify_primitive(void) {
  dal_verify_report rep;
  dal_verify_opts few, nan_lo, inf_t, zero_h;
  verify_bad_opts(&few, &nan_lo, &inf_t, &zero_h);
  dal_primitive noeval = dal_map_cartesian2, badver = dal_map_cartesian2;
  noeval.eval = NULL;
  badver.version = 99;
  char *m = rep.msg;
  CHECK(dal_verify_primitive(NULL, NULL, NULL, NULL, &rep) == DAL_E_ARG);
  CHECK(dal_verify_primitive(&noeval, NULL, NULL, NULL, &rep) == DAL_E_ARG);
  CHECK(dal_verify_primitive(&badver, NULL, NULL, NULL, &rep) == DAL_E_ARG);
  // the pendulum's length is required: no defaults to fall back on
  CHECK(dal_verify_primitive(&dal_map_pendulum, NULL, NULL, NULL, &rep) == DAL_E_ARG);
  // non-finite options: verify.h documents DAL_E_ARG for options (not DAL_E_NONFINITE)
  MS(dal_verify_primitive(&dal_map_cartesian2, NULL, NULL, &few, &rep), DAL_E_ARG, m);
  MS(dal_verify_primitive(&dal_map_cartesian2, NULL, NULL, &nan_lo, &rep), DAL_E_ARG, m);
  MS(dal_verify_primitive(&dal_map_cartesian2, NULL, NULL, &inf_t, &rep), DAL_E_ARG, m);
  MS(dal_verify_primitive(&dal_map_cartesian2, NULL, NULL, &zero_h, NULL), DAL_E_ARG, NULL);
  dal_verify_opts raw; // not from dal_default_verify_opts: refused by its cookie
  memset(&raw, 0, sizeof raw);
  MS(dal_verify_primitive(&dal_map_cartesian2, NULL, NULL, &raw, &rep), DAL_E_ARG, m);
  CHECK(strstr(m, "dal_default_verify_opts") != NULL);
  double pend[7] = {1.0, 0, 0, 0, 0, 0, 0};
  MS(dal_verify_primitive(&dal_map_pendulum, pend, NULL, NULL, &rep), DAL_OK, m);
  CHECK(rep.samples == 16 && rep.checks > 0 && rep.failures == 0);
  MS(dal_verify_primitive(&dal_map_cartesian2, NULL, NULL, NULL, NULL), DAL_OK, NULL);
}
static void sw_dal_verify_map(void) {
  dal_verify_report rep;
  dal_verify_opts few, nan_lo, inf_t, zero_h;
  verify_bad_opts(&few, &nan_lo, &inf_t, &zero_h);
  char *m = rep.msg;
  CHECK(dal_verify_map(NULL, 2, 1, 2, NULL, &rep, NULL) == DAL_E_ARG);
  CHECK(dal_verify_map(map_fn, 0, 1, 2, NULL, &rep, NULL) == DAL_E_ARG);
  CHECK(dal_verify_map(map_fn, 2, 0, 2, NULL, &rep, NULL) == DAL_E_ARG);
  CHECK(dal_verify_map(map_fn, 2, INT_MIN, 2, NULL, &rep, NULL) == DAL_E_ARG);
  CHECK(dal_verify_map(map_fn, 2, 1, 1, NULL, &rep, NULL) == DAL_E_ARG);
  CHECK(dal_verify_map(map_fn, 2, 1, 4, NULL, &rep, NULL) == DAL_E_ARG);
  MS(dal_verify_map(map_fn, 2, 1, 2, &few, &rep, NULL), DAL_E_ARG, m);
  MS(dal_verify_map(map_fn, 2, 1, 2, &nan_lo, &rep, NULL), DAL_E_ARG, m);
  MS(dal_verify_map(map_fn, 2, 1, 2, &inf_t, &rep, NULL), DAL_E_ARG, m);
  MS(dal_verify_map(map_fn, 2, 1, 2, NULL, &rep, NULL), DAL_OK, m);
  CHECK(rep.checks > 0 && rep.failures == 0);
}
static void sw_dal_verify_potential_r(void) {
  dal_verify_report rep;
  dal_verify_opts few, nan_lo, inf_t, zero_h;
  verify_bad_opts(&few, &nan_lo, &inf_t, &zero_h);
  char *m = rep.msg;
  CHECK(dal_verify_potential_r(NULL, 1, 2, NULL, &rep, NULL) == DAL_E_ARG);
  CHECK(dal_verify_potential_r(pot_r, 0, 2, NULL, &rep, NULL) == DAL_E_ARG);
  CHECK(dal_verify_potential_r(pot_r, -1, 2, NULL, &rep, NULL) == DAL_E_ARG);
  CHECK(dal_verify_potential_r(pot_r, 1, 0, NULL, &rep, NULL) == DAL_E_ARG);
  CHECK(dal_verify_potential_r(pot_r, 1, INT_MAX, NULL, &rep, NULL) == DAL_E_ARG);
  MS(dal_verify_potential_r(pot_r, 1, 2, &few, &rep, NULL), DAL_E_ARG, m);
  MS(dal_verify_potential_r(pot_r, 1, 2, &nan_lo, &rep, NULL), DAL_E_ARG, m);
  MS(dal_verify_potential_r(pot_r, 1, 2, &zero_h, &rep, NULL), DAL_E_ARG, m);
  MS(dal_verify_potential_r(pot_r, 1, 2, NULL, &rep, NULL), DAL_OK, m);
  CHECK(rep.checks > 0 && rep.failures == 0);
}
static void sw_dal_verify_potential_q(void) {
  dal_verify_report rep;
  dal_verify_opts few, nan_lo, inf_t, zero_h;
  verify_bad_opts(&few, &nan_lo, &inf_t, &zero_h);
  char *m = rep.msg;
  CHECK(dal_verify_potential_q(NULL, 1, NULL, &rep, NULL) == DAL_E_ARG);
  CHECK(dal_verify_potential_q(pot_q, 0, NULL, &rep, NULL) == DAL_E_ARG);
  CHECK(dal_verify_potential_q(pot_q, INT_MIN, NULL, &rep, NULL) == DAL_E_ARG);
  MS(dal_verify_potential_q(pot_q, 1, &few, &rep, NULL), DAL_E_ARG, m);
  MS(dal_verify_potential_q(pot_q, 1, &inf_t, &rep, NULL), DAL_E_ARG, m);
  MS(dal_verify_potential_q(pot_q, 1, NULL, &rep, NULL), DAL_OK, m);
  CHECK(rep.checks > 0 && rep.failures == 0);
}
static void sw_dal_verify_lagrangian(void) {
  dal_verify_report rep;
  dal_verify_opts few, nan_lo, inf_t, zero_h;
  verify_bad_opts(&few, &nan_lo, &inf_t, &zero_h);
  char *m = rep.msg;
  CHECK(dal_verify_lagrangian(NULL, 1, NULL, &rep, NULL) == DAL_E_ARG);
  CHECK(dal_verify_lagrangian(lag_fn, 0, NULL, &rep, NULL) == DAL_E_ARG);
  CHECK(dal_verify_lagrangian(lag_fn, -1, NULL, &rep, NULL) == DAL_E_ARG);
  MS(dal_verify_lagrangian(lag_fn, 1, &few, &rep, NULL), DAL_E_ARG, m);
  MS(dal_verify_lagrangian(lag_fn, 1, &nan_lo, &rep, NULL), DAL_E_ARG, m);
  MS(dal_verify_lagrangian(lag_fn, 1, NULL, &rep, NULL), DAL_OK, m);
  CHECK(rep.checks > 0 && rep.failures == 0);
}
static void sw_dal_verify_model(void) {
  dal_model_report rep;
  // the (system, state) convention of state.h: a NULL system is DAL_E_STATE with a message in
  // the state (and in the report), a NULL state DAL_E_ARG with the message in the report
  ST(dal_verify_model(NULL, F.stB, NULL, &rep), DAL_E_STATE, F.stB);
  CHECK(strstr(rep.msg, "the system is NULL") != NULL && rep.passed == 0);
  ST(dal_verify_model(F.B, NULL, NULL, &rep), DAL_E_ARG, NULL);
  CHECK(strstr(rep.msg, "state is NULL") != NULL && rep.passed == 0);
  ST(dal_verify_model(F.A, F.stB, NULL, &rep), DAL_E_STATE, F.stB);
  CHECK(strstr(rep.msg, "another system") != NULL && rep.passed == 0);
  st_intact();
  ST(dal_verify_model(F.B, F.stB, NULL, &rep), DAL_OK, F.stB);
  CHECK(rep.passed == 1 && rep.mass_checked == 1 && rep.path_checked == 1 && rep.m == 0);
  ST(dal_verify_model(F.B, F.stB, NULL, NULL), DAL_OK, F.stB);
  dal_verify_opts raw; // not from dal_default_verify_opts: refused by its cookie
  memset(&raw, 0, sizeof raw);
  CHECK(dal_verify_model(F.B, F.stB, &raw, &rep) == DAL_E_ARG);
  CHECK(strstr(rep.msg, "dal_default_verify_opts") != NULL && rep.passed == 0);
  st_intact();
}

// ---------------------------------------------------------------- rows: analysis.h
// At theta = 0.3 at rest, B (unit mass on a unit rod, g = 9.81) has M = 1, C = 0 and
// K = d2U/dtheta2 = 9.81 cos(0.3) (U = -9.81 cos theta; M is constant, so no M' qddot term).
static void sw_dal_linearize(void) {
  double M[1] = {0}, C[1] = {1}, K[1] = {0};
  ST_OWNER(dal_linearize, F.B, F.A, F.stB, M, C, K);
  // A on its manifold (one independent coordinate along the circle at sin theta = 0.6, at rest):
  // the reduced K is the minimal pendulum's g cos theta = 9.81 x 0.8
  ST(dal_linearize(F.A, F.stA, NULL, NULL, NULL), DAL_OK, F.stA);
  ST(dal_linearize(F.A, F.stA, M, C, K), DAL_OK, F.stA);
  CHECK_CLOSE(M[0], 1.0, 1e-14);
  CHECK_CLOSE(C[0], 0.0, 1e-14);
  CHECK_CLOSE(K[0], 9.81 * 0.8, 1e-13);
  st_intact();
  ST(dal_linearize(F.B, F.stB, NULL, NULL, NULL), DAL_OK, F.stB);
  ST(dal_linearize(F.B, F.stB, M, C, K), DAL_OK, F.stB);
  CHECK_CLOSE(M[0], 1.0, 1e-14);
  CHECK_CLOSE(C[0], 0.0, 1e-14);
  CHECK_CLOSE(K[0], 9.81 * cos(0.3), 1e-13);
}
// The full-space matrices of A at rest: M = I, C = 0, G the rod's unit row (0.6, -0.8), N the
// tangent (0.8, 0.6) up to sign; B has N = 1 and leaves G alone.
static void sw_dal_linearize_full(void) {
  double M[4], C[4], K[4], G[2], N[2];
  ST_OWNER(dal_linearize_full, F.A, F.B, F.stA, M, C, K, G, N);
  ST(dal_linearize_full(F.A, F.stA, NULL, NULL, NULL, NULL, NULL), DAL_OK, F.stA);
  ST(dal_linearize_full(F.A, F.stA, M, C, K, G, N), DAL_OK, F.stA);
  CHECK(M[0] == 1.0 && M[1] == 0.0 && M[2] == 0.0 && M[3] == 1.0);
  CHECK(C[0] == 0.0 && C[1] == 0.0 && C[2] == 0.0 && C[3] == 0.0);
  CHECK_CLOSE(G[0], 0.6, 1e-15);
  CHECK_CLOSE(G[1], -0.8, 1e-15);
  CHECK_CLOSE(fabs(N[0]), 0.8, 1e-15);
  CHECK_CLOSE(N[1] / N[0], 0.75, 1e-15);
  double g1 = 7.0, n1 = 0.0;
  ST(dal_linearize_full(F.B, F.stB, M, C, K, &g1, &n1), DAL_OK, F.stB);
  CHECK(g1 == 7.0 && n1 == 1.0);
  st_intact();
}
static void sw_dal_vector_field_jacobian(void) {
  double A[4] = {0}, ft[2] = {1, 1};
  ST_OWNER(dal_vector_field_jacobian, F.B, F.A, F.stB, A, ft);
  ST(dal_vector_field_jacobian(F.B, F.stB, NULL, ft), DAL_E_ARG, F.stB);
  double A4[16];
  ST(dal_vector_field_jacobian(F.A, F.stA, A4, NULL), DAL_OK, F.stA); // full space, 4 x 4
  CHECK(A4[8] == 1.0 && A4[13] == 1.0 && A4[0] == 0.0 && A4[12] == 0.0);
  st_intact();
  ST(dal_vector_field_jacobian(F.B, F.stB, A, NULL), DAL_OK, F.stB);
  ST(dal_vector_field_jacobian(F.B, F.stB, A, ft), DAL_OK, F.stB);
  // df/dy = [0 1; -K/M 0] column-major; autonomous: df/dt = 0
  CHECK(A[0] == 0.0 && A[2] == 1.0 && A[3] == 0.0);
  CHECK_CLOSE(A[1], -9.81 * cos(0.3), 1e-13);
  CHECK(ft[0] == 0.0 && ft[1] == 0.0);
}
// B at theta = 0.3 at rest with a force on theta: B = 1, Bf = (0, 1/M) = (0, 1)
static void sw_dal_linearize_inputs(void) {
  const char *in[1] = {"force:theta"}, *bad[1] = {"place:bob:0"}, *none[1] = {"force:zz"};
  double B[1] = {0}, Af[4], Bf[2];
  ST_OWNER(dal_linearize_inputs, F.B, F.A, F.stB, 1, in, B, Af, Bf);
  ST(dal_linearize_inputs(F.B, F.stB, 1, NULL, B, Af, Bf), DAL_E_ARG, F.stB);
  ST(dal_linearize_inputs(F.B, F.stB, -1, in, B, Af, Bf), DAL_E_ARG, F.stB);
  ST(dal_linearize_inputs(F.B, F.stB, 1, none, B, Af, Bf), DAL_E_ARG, F.stB);
  ST(dal_linearize_inputs(F.B, F.stB, 1, bad, B, Af, Bf), DAL_E_UNSUPPORTED, F.stB);
  ST(dal_linearize_inputs(F.B, F.stB, 0, NULL, NULL, NULL, NULL), DAL_OK, F.stB);
  ST(dal_linearize_inputs(F.B, F.stB, 1, in, B, Af, Bf), DAL_OK, F.stB);
  CHECK(B[0] == 1.0 && Bf[0] == 0.0);
  CHECK_CLOSE(Bf[1], 1.0, 1e-14);
  CHECK_CLOSE(Af[1], -9.81 * cos(0.3), 1e-13);
  st_intact();
}
// from theta = 0.3 at rest to t = 0.5 (a fresh state: the call moves it)
static void sw_dal_state_transition(void) {
  double Phi[4], S[2];
  const char *in[1] = {"gravity:1"}, *bad[1] = {"place:bob:0"};
  dal_solve_opts o = dal_default_solve_opts();
  ST_OWNER(dal_state_transition, F.B, F.A, F.stB, NULL, 0.5, Phi, 0, NULL, NULL);
  ST(dal_state_transition(F.B, F.stB, NULL, 0.5, NULL, 0, NULL, NULL), DAL_E_ARG, F.stB);
  ST(dal_state_transition(F.B, F.stB, NULL, 0.0, Phi, 0, NULL, NULL), DAL_E_ARG, F.stB);
  ST(dal_state_transition(F.B, F.stB, NULL, NAN, Phi, 0, NULL, NULL), DAL_E_ARG, F.stB);
  ST(dal_state_transition(F.B, F.stB, NULL, 0.5, Phi, 1, NULL, S), DAL_E_ARG, F.stB);
  ST(dal_state_transition(F.B, F.stB, NULL, 0.5, Phi, 1, bad, S), DAL_E_UNSUPPORTED, F.stB);
  o.method = DAL_METHOD_BDF;
  ST(dal_state_transition(F.B, F.stB, &o, 0.5, Phi, 0, NULL, NULL), DAL_E_UNSUPPORTED, F.stB);
  st_intact();
  dal_state *st = state_b();
  ST(dal_state_transition(F.B, st, NULL, 0.5, Phi, 1, in, S), DAL_OK, NULL);
  CHECK(dal_state_time(st) == 0.5 && Phi[0] != 0.0 && S[0] != 0.0);
  dal_state_destroy(st);
}
// periodic motion (floquet.c, periodic_orbit.c): the pendulum B is autonomous; at rest at the
// bottom it is T-periodic for any T, at 0.3 it does not return after 0.5
static void sw_dal_time_dependence(void) {
  char what[256];
  ST_OWNER(dal_time_dependence, F.B, F.A, F.stB, what, sizeof what);
  CHECK(dal_time_dependence(F.B, F.stB, NULL, 0) == 0);
  CHECK(dal_time_dependence(F.B, F.stB, what, 1) == 0 && what[0] == 0);
  st_intact();
}
static void sw_dal_normal_modes_frozen(void) {
  double w2[1] = {0};
  dal_modes md;
  ST(dal_normal_modes_frozen(F.B, NULL, w2, NULL, NULL, NULL, &md), DAL_E_ARG, NULL);
  ST(dal_normal_modes_frozen(F.A, F.stB, w2, NULL, NULL, NULL, &md), DAL_E_STATE, F.stB);
  ST(dal_normal_modes_frozen(F.B, F.stB, w2, NULL, NULL, NULL, &md), DAL_OK, F.stB);
  CHECK(md.frozen == 0); // autonomous: nothing frozen
  st_intact();
}
static void sw_dal_floquet(void) {
  double re[2], im[2], mono[4];
  dal_floquet_report r;
  ST_OWNER(dal_floquet, F.B, F.A, F.stB, NULL, 1.0, re, im, mono, &r);
  ST(dal_floquet(F.B, F.stB, NULL, 0.0, re, im, mono, &r), DAL_E_ARG, F.stB);
  ST(dal_floquet(F.B, F.stB, NULL, NAN, re, im, mono, &r), DAL_E_ARG, F.stB);
  ST(dal_floquet(F.B, F.stB, NULL, INFINITY, re, im, mono, &r), DAL_E_ARG, F.stB);
  ST(dal_floquet(F.B, F.stB, NULL, 0.5, re, im, mono, &r), DAL_E_ARG, F.stB); // no return
  st_intact();
  dal_state *st = state_b();
  double z = 0.0;
  CHECK_OK(dal_state_set(F.B, st, 0.0, &z, &z));
  ST(dal_floquet(F.B, st, NULL, 0.5, NULL, NULL, NULL, NULL), DAL_OK, NULL);
  ST(dal_floquet(F.B, st, NULL, 0.5, re, im, mono, &r), DAL_OK, NULL);
  // the bottom: mu = exp(+-i sqrt(g) T) on the unit circle
  CHECK(r.count == 2 && r.verdict == DAL_NEUTRAL);
  CHECK_CLOSE(r.trace, 2 * cos(sqrt(9.81) * 0.5), 1e-9);
  CHECK(dal_state_time(st) == 0.0);
  dal_state_destroy(st);
}
static void sw_dal_floquet_verdict_name(void) {
  CHECK(strcmp(dal_floquet_verdict_name((dal_stability)7), "unknown") == 0);
  CHECK(strcmp(dal_floquet_verdict_name(DAL_MARGINAL), "boundary") == 0);
  CHECK(strcmp(dal_floquet_verdict_name(DAL_NEUTRAL), "stable") == 0);
  CHECK(strcmp(dal_floquet_verdict_name(DAL_UNSTABLE), "unstable") == 0);
}
static void sw_dal_default_orbit_opts(void) {
  dal_orbit_opts o;
  memset(&o, 0xff, sizeof o);
  o = dal_default_orbit_opts();
  CHECK(o.period == 0.0 && o.free_period == 0 && o.xtol == 1e-9 && o.max_iter == 30);
  CHECK(o.solve.rtol == 1e-11);
}
static void sw_dal_periodic_orbit(void) {
  dal_orbit_opts o = dal_default_orbit_opts(), raw;
  memset(&raw, 0, sizeof raw);
  double re[2], im[2];
  dal_orbit_report r;
  o.period = 0.5;
  ST_OWNER(dal_periodic_orbit, F.B, F.A, F.stB, &o, re, im, &r);
  ST(dal_periodic_orbit(F.B, F.stB, NULL, re, im, &r), DAL_E_ARG, F.stB);
  ST(dal_periodic_orbit(F.B, F.stB, &raw, re, im, &r), DAL_E_ARG, F.stB);
  o.period = NAN;
  ST(dal_periodic_orbit(F.B, F.stB, &o, re, im, &r), DAL_E_ARG, F.stB);
  o.period = 0.5;
  o.max_iter = 0;
  ST(dal_periodic_orbit(F.B, F.stB, &o, re, im, &r), DAL_E_ARG, F.stB);
  st_intact();
  // a fixed period of the autonomous pendulum from 0.3: Newton lands on the bottom
  dal_state *st = state_b();
  o.max_iter = 30;
  ST(dal_periodic_orbit(F.B, st, &o, re, im, &r), DAL_OK, NULL);
  CHECK(fabs(dal_state_q(st)[0]) < 1e-9 && r.period == 0.5);
  dal_state_destroy(st);
}
static void sw_dal_relative_equilibrium(void) {
  double axis[3] = {0, 0, 1}, zero[3] = {0, 0, 0}, re[2], im[2];
  dal_relative_report r;
  ST_OWNER(dal_relative_equilibrium, F.B, F.A, F.stB, axis, 1.0, re, im, &r);
  ST(dal_relative_equilibrium(F.B, F.stB, axis, 1.0, re, im, &r), DAL_E_ARG, F.stB); // 2D
  ST(dal_relative_equilibrium(F.B, F.stB, NULL, 1.0, re, im, &r), DAL_E_ARG, F.stB);
  ST(dal_relative_equilibrium(F.B, F.stB, zero, 1.0, re, im, &r), DAL_E_ARG, F.stB);
  ST(dal_relative_equilibrium(F.B, F.stB, axis, NAN, re, im, &r), DAL_E_ARG, F.stB);
  st_intact();
}
static int sw_orbit_rebuild(double p, dal_system **out, void *ctx) {
  (void)p;
  (void)ctx;
  *out = NULL;
  return 1; // refuses: the continuation must stop with its message
}
static void sw_dal_default_orbit_continuation_opts(void) {
  dal_orbit_continuation_opts o;
  memset(&o, 0xff, sizeof o);
  o = dal_default_orbit_continuation_opts();
  CHECK(o.p0 == 0.0 && o.p1 == 1.0 && o.npoints == 41 && o.locate == 1 && o.ptol == 0.0);
  CHECK(o.orbit.max_iter == 30 && o.orbit.period == 0.0);
}
static void sw_dal_orbit_continue(void) {
  dal_orbit_continuation_opts o = dal_default_orbit_continuation_opts(), raw;
  memset(&raw, 0, sizeof raw);
  dal_continuation_report r;
  double y0[2] = {0, 0};
  CHECK(dal_orbit_continue(NULL, y0, &o, NULL, &r, NULL) == DAL_E_ARG && r.msg[0]);
  CHECK(dal_orbit_continue(sw_orbit_rebuild, NULL, &o, NULL, &r, NULL) == DAL_E_ARG);
  CHECK(dal_orbit_continue(sw_orbit_rebuild, y0, NULL, NULL, &r, NULL) == DAL_E_ARG);
  CHECK(dal_orbit_continue(sw_orbit_rebuild, y0, &raw, NULL, NULL, NULL) == DAL_E_ARG);
  o.p1 = NAN;
  CHECK(dal_orbit_continue(sw_orbit_rebuild, y0, &o, NULL, &r, NULL) == DAL_E_ARG);
  o.p1 = 1.0;
  CHECK(dal_orbit_continue(sw_orbit_rebuild, y0, &o, NULL, &r, NULL) == DAL_E_CALLBACK);
  CHECK(strstr(r.msg, "rebuild") != NULL);
}
static void sw_dal_stability_name(void) {
  CHECK(strcmp(dal_stability_name((dal_stability)7), "unknown") == 0);
  CHECK(strcmp(dal_stability_name((dal_stability)-2), "unknown") == 0);
  CHECK(strcmp(dal_stability_name(DAL_NEUTRAL), "neutral") == 0);
  CHECK(strcmp(dal_stability_name(DAL_UNSTABLE), "unstable") == 0);
}
static void sw_dal_normal_modes(void) {
  double w2[1] = {0}, x[1] = {0}, re[2], im[2];
  dal_modes md;
  ST_OWNER(dal_normal_modes, F.B, F.A, F.stB, w2, x, re, im, &md);
  double xa[2];
  ST(dal_normal_modes(F.A, F.stA, w2, xa, re, im, &md), DAL_OK, F.stA); // on the manifold
  CHECK_CLOSE(w2[0], 9.81 * 0.8, 1e-13);
  st_intact();
  ST(dal_normal_modes(F.B, F.stB, NULL, NULL, NULL, NULL, NULL), DAL_OK, F.stB);
  ST(dal_normal_modes(F.B, F.stB, w2, x, re, im, &md), DAL_OK, F.stB);
  // omega^2 = K / M, shape M-normalized to 1; eigenvalues of df/dy +- i omega
  CHECK_CLOSE(w2[0], 9.81 * cos(0.3), 1e-13);
  CHECK_CLOSE(x[0], 1.0, 1e-14);
  CHECK_CLOSE(im[1], sqrt(9.81 * cos(0.3)), 1e-12);
  CHECK(md.verdict == DAL_NEUTRAL);
}
static void sw_dal_default_equilibrium_opts(void) {
  dal_equilibrium_opts o;
  memset(&o, 0xff, sizeof o);
  o = dal_default_equilibrium_opts(); // every field written, the cookie too
  CHECK(o.xtol == 1e-12 && o.max_iter == 50 && o.max_step == 0.0);
}
static void sw_dal_equilibrium(void) {
  dal_equilibrium_opts o, raw, nan_tol, no_iter;
  dal_equilibrium_report rep;
  o = dal_default_equilibrium_opts();
  memset(&raw, 0, sizeof raw);
  nan_tol = no_iter = o;
  nan_tol.xtol = NAN;
  no_iter.max_iter = 0;
  ST_OWNER(dal_equilibrium, F.B, F.A, F.stB, &o, &rep);
  ST(dal_equilibrium(F.B, F.stB, &raw, &rep), DAL_E_ARG, F.stB);
  ST(dal_equilibrium(F.B, F.stB, &nan_tol, &rep), DAL_E_ARG, F.stB);
  ST(dal_equilibrium(F.B, F.stB, &no_iter, &rep), DAL_E_ARG, F.stB);
  // A on its manifold (a fresh state: this one moves): hanging, the rod's lambda = -m g
  dal_state *sa = NULL;
  CHECK_OK(dal_state_create(F.A, &sa));
  double qa[2] = {0.6, -0.8}, va[2] = {0.0, 0.0};
  CHECK_OK(dal_state_set(F.A, sa, 0.0, qa, va));
  ST(dal_equilibrium(F.A, sa, NULL, &rep), DAL_OK, NULL);
  CHECK(fabs(dal_state_q(sa)[0]) < 1e-12 && fabs(dal_state_q(sa)[1] + 1.0) < 1e-12);
  CHECK(fabs(dal_state_lambda(sa)[0] + 9.81) < 1e-12);
  dal_state_destroy(sa);
  st_intact();
  // the hanging pendulum: theta* = 0 from theta = 0.3 (a fresh state: this one moves)
  dal_state *st = state_b();
  ST(dal_equilibrium(F.B, st, &o, &rep), DAL_OK, NULL);
  CHECK(fabs(dal_state_q(st)[0]) < 1e-12 && rep.iterations >= 1 && rep.unsteady == 0.0);
  CHECK(dal_state_qdot(st)[0] == 0.0);
  dal_state_destroy(st);
}
static void sw_dal_default_continuation_opts(void) {
  dal_continuation_opts o;
  memset(&o, 0xff, sizeof o);
  o = dal_default_continuation_opts(); // every field written, the cookie too
  CHECK(o.p0 == 0.0 && o.p1 == 1.0 && o.npoints == 41 && o.t == 0.0 && o.locate == 1);
  CHECK(o.newton.xtol == 1e-12 && o.newton.max_iter == 50);
}

// B with gravity 9.81 + p; ctx: the branch record (fail: rebuild refuses)
typedef struct branch_rec {
  int fail, points, bad;
} branch_rec;
static int rebuild_pend(double p, dal_system **out, void *ctx) {
  if (((branch_rec *)ctx)->fail) return 1;
  scn_knobs k = scn_default();
  k.g = 9.81 + p;
  *out = scn_pendulum(&k);
  return *out ? DAL_OK : DAL_E_ARG;
}
static int branch_point(double p, const dal_system *sys, const dal_state *st, dal_stability v,
                        dal_branch_kind kind, void *ctx) {
  (void)p;
  (void)sys;
  branch_rec *r = ctx;
  ++r->points;
  if (fabs(dal_state_q(st)[0]) > 1e-12 || v != DAL_NEUTRAL || kind != DAL_BRANCH_REGULAR) ++r->bad;
  return 0;
}
static void sw_dal_continue(void) {
  dal_continuation_opts o, raw, same, nan_p, one, bad_newton;
  dal_continuation_report rep;
  char *m = rep.msg;
  double q0 = 0.3;
  branch_rec rec = {0, 0, 0};
  o = dal_default_continuation_opts();
  o.npoints = 3;
  memset(&raw, 0, sizeof raw);
  same = nan_p = one = bad_newton = o;
  same.p1 = same.p0;
  nan_p.p1 = NAN;
  one.npoints = 1;
  bad_newton.newton.xtol = -1.0;
  MS(dal_continue(NULL, &q0, &o, branch_point, &rep, &rec), DAL_E_ARG, m);
  MS(dal_continue(rebuild_pend, NULL, &o, branch_point, &rep, &rec), DAL_E_ARG, m);
  MS(dal_continue(rebuild_pend, &q0, NULL, branch_point, &rep, &rec), DAL_E_ARG, m);
  MS(dal_continue(rebuild_pend, &q0, &raw, branch_point, &rep, &rec), DAL_E_ARG, m);
  MS(dal_continue(rebuild_pend, &q0, &same, branch_point, &rep, &rec), DAL_E_ARG, m);
  MS(dal_continue(rebuild_pend, &q0, &nan_p, branch_point, &rep, &rec), DAL_E_ARG, m);
  MS(dal_continue(rebuild_pend, &q0, &one, branch_point, &rep, &rec), DAL_E_ARG, m);
  MS(dal_continue(rebuild_pend, &q0, &bad_newton, branch_point, &rep, &rec), DAL_E_ARG, m);
  MS(dal_continue(rebuild_pend, &q0, &o, branch_point, NULL, &rec), DAL_OK, NULL);
  CHECK(rec.points == 3 && rec.bad == 0);
  rec.fail = 1;
  MS(dal_continue(rebuild_pend, &q0, &o, branch_point, &rep, &rec), DAL_E_CALLBACK, m);
  CHECK(rec.points == 3);
  rec = (branch_rec){0, 0, 0};
  MS(dal_continue(rebuild_pend, &q0, &o, branch_point, &rep, &rec), DAL_OK, m);
  CHECK(rec.points == 3 && rec.bad == 0 && rep.npoints == 3 && rep.ncritical == 0);
  CHECK(rep.p_end == 1.0 && rep.msg[0] == 0);
}
static void sw_dal_default_lyapunov_opts(void) {
  dal_lyapunov_opts o;
  memset(&o, 0xff, sizeof o);
  o = dal_default_lyapunov_opts(); // every field written, the cookie too
  CHECK(isnan(o.t_end) && o.nexp == 0 && o.renorm == 1.0 && o.method == DAL_METHOD_AUTO);
  CHECK(o.rtol == 1e-10 && o.atol == 1e-10 && o.y0 == NULL && o.nblocks == 4);
}
static void sw_dal_lyapunov(void) {
  dal_lyapunov_opts o, raw, no_end, behind, bs, many, no_renorm, nan_y0;
  double ex[2] = {0, 0}, err[2], y0n[4] = {1, 0, NAN, 1};
  o = dal_default_lyapunov_opts();
  o.t_end = 0.05;
  o.renorm = 0.01;
  o.nblocks = 2;
  memset(&raw, 0, sizeof raw);
  no_end = behind = bs = many = no_renorm = nan_y0 = o;
  no_end.t_end = NAN;
  behind.t_end = -1.0;
  bs.method = DAL_METHOD_VARIATIONAL; // structure-preserving: not for the tangent
  many.nexp = 3;                      // 2n = 2
  no_renorm.renorm = 0.0;
  nan_y0.y0 = y0n;
  ST_OWNER(dal_lyapunov, F.B, F.A, F.stB, &o, ex, err, NULL, NULL);
  ST(dal_lyapunov(F.B, F.stB, &o, NULL, err, NULL, NULL), DAL_E_ARG, F.stB);
  ST(dal_lyapunov(F.B, F.stB, NULL, ex, err, NULL, NULL), DAL_E_ARG, F.stB);
  ST(dal_lyapunov(F.B, F.stB, &raw, ex, err, NULL, NULL), DAL_E_ARG, F.stB);
  ST(dal_lyapunov(F.B, F.stB, &no_end, ex, err, NULL, NULL), DAL_E_ARG, F.stB);
  ST(dal_lyapunov(F.B, F.stB, &behind, ex, err, NULL, NULL), DAL_E_ARG, F.stB);
  ST(dal_lyapunov(F.B, F.stB, &bs, ex, err, NULL, NULL), DAL_E_UNSUPPORTED, F.stB);
  ST(dal_lyapunov(F.B, F.stB, &many, ex, err, NULL, NULL), DAL_E_ARG, F.stB);
  ST(dal_lyapunov(F.B, F.stB, &no_renorm, ex, err, NULL, NULL), DAL_E_ARG, F.stB);
  ST(dal_lyapunov(F.B, F.stB, &nan_y0, ex, err, NULL, NULL), DAL_E_NONFINITE, F.stB);
  dal_lyapunov_opts with_y0 = o;
  double y0a[4] = {1, 0, 0, 0};
  with_y0.nexp = 1;
  with_y0.y0 = y0a; // constrained: the vectors start on the manifold's tangent space
  ST(dal_lyapunov(F.A, F.stA, &with_y0, ex, err, NULL, NULL), DAL_E_UNSUPPORTED, F.stA);
  ST(dal_lyapunov(F.A, F.stA, &many, ex, err, NULL, NULL), DAL_E_ARG, F.stA); // 2(n - m) = 2
  st_intact();
  // a short run on a fresh state (it moves to t_end): the flow preserves phase-space volume
  // (trace df/dy = 0), so the two exponents sum to 0 up to the integration tolerance
  dal_state *st = state_b();
  ST(dal_lyapunov(F.B, st, &o, ex, NULL, NULL, NULL), DAL_OK, NULL);
  CHECK(isfinite(ex[0]) && isfinite(ex[1]) && ex[0] >= ex[1]);
  CHECK_CLOSE(ex[0] + ex[1], 0.0, 1e-6);
  CHECK_CLOSE(dal_state_time(st), 0.05, 1e-14);
  dal_state_destroy(st);
}

// ---------------------------------------------------------------- rows: system.h (defs)
static void sw_dal_default_place_def(void) {
  dal_place_def d = dal_default_place_def();
  CHECK(d.prim == NULL && d.parent == -1 && d.coords == NULL && d.ncoords == 0 && d.ctx == NULL);
}
static void sw_dal_default_constraint_def(void) {
  dal_constraint_def d = dal_default_constraint_def();
  CHECK(d.name == NULL && d.prim == NULL && d.parts == NULL && d.nparts == 0);
  CHECK(d.coords == NULL && d.ncoords == 0 && d.ctx == NULL);
}
// the name-checked setters: a name of the def's primitive sets that entry only; an unknown
// name, a name of another primitive, a missing primitive or NULL set nothing
static void sw_dal_place_def_set(void) {
  dal_place_def d = dal_default_place_def();
  double before[DAL_MAX_PARAM];
  CHECK(dal_place_def_set(&d, "l", 1.0) == DAL_E_ARG); // no primitive yet
  d.prim = &dal_map_pendulum;
  memcpy(before, d.param, sizeof before);
  CHECK(dal_place_def_set(NULL, "l", 1.0) == DAL_E_ARG);
  CHECK(dal_place_def_set(&d, NULL, 1.0) == DAL_E_ARG);
  CHECK(dal_place_def_set(&d, "R", 1.0) == DAL_E_ARG); // the ring's radius: not a pendulum's
  CHECK(dal_place_def_set(&d, "", 1.0) == DAL_E_ARG);
  CHECK(dal_place_def_set(&d, "7", 1.0) == DAL_E_ARG); // the pendulum has 7 parameters
  CHECK(memcmp(before, d.param, sizeof before) == 0);
  CHECK(dal_place_def_set(&d, "w", 2.5) == DAL_OK && d.param[DAL_PENDULUM_W] == 2.5);
  CHECK(dal_place_def_set(&d, "0", 0.5) == DAL_OK && d.param[DAL_PENDULUM_L] == 0.5);
}
static void sw_dal_constraint_def_set(void) {
  dal_constraint_def d = dal_default_constraint_def();
  CHECK(dal_constraint_def_set(&d, "L", 1.0) == DAL_E_ARG);
  d.prim = &dal_con_anchor2;
  CHECK(dal_constraint_def_set(NULL, "L", 1.0) == DAL_E_ARG);
  CHECK(dal_constraint_def_set(&d, NULL, 1.0) == DAL_E_ARG);
  CHECK(dal_constraint_def_set(&d, "z0", 1.0) == DAL_E_ARG); // anchor2 is planar
  CHECK(dal_constraint_def_set(&d, "y0", -0.5) == DAL_OK && d.param[DAL_ANCHOR_Y0] == -0.5);
}
static void sw_dal_default_spring_def(void) {
  dal_spring_def d = dal_default_spring_def();
  CHECK(d.a == -1 && d.b == -1 && d.k == 0.0 && d.length == 0.0 && d.path == NULL);
  CHECK(d.anchor[0] == 0.0 && d.anchor[1] == 0.0 && d.anchor[2] == 0.0 && d.ctx == NULL);
}
static void sw_dal_default_damper_def(void) {
  dal_damper_def d = dal_default_damper_def();
  CHECK(d.a == -1 && d.b == -1 && d.c == 0.0 && d.path == NULL && d.ctx == NULL);
  CHECK(d.anchor[0] == 0.0 && d.anchor[1] == 0.0 && d.anchor[2] == 0.0);
}
static void sw_dal_builder_place_def(void) {
  int c[2] = {0, 1}, bad[2] = {0, 7};
  dal_place_def d = dal_default_place_def(), raw, e;
  memset(&raw, 0, sizeof raw);
  d.prim = &dal_map_cartesian2;
  d.coords = c;
  d.ncoords = 2;
  BL(dal_builder_place_def(NULL, 0, &d), DAL_E_ARG, NULL);
  BL(dal_builder_place_def(F.bld, 0, NULL), DAL_E_ARG, F.bld);
  BL(dal_builder_place_def(F.bld, 0, &raw), DAL_E_ARG, F.bld); // no cookie
  BL(dal_builder_place_def(F.bld, -1, &d), DAL_E_ARG, F.bld);
  BL(dal_builder_place_def(F.bld, 1, &d), DAL_E_ARG, F.bld);
  BL(dal_builder_place_def(F.bld, INT_MIN, &d), DAL_E_ARG, F.bld);
  e = d;
  e.prim = NULL;
  BL(dal_builder_place_def(F.bld, 0, &e), DAL_E_ARG, F.bld);
  e = d;
  e.coords = bad;
  BL(dal_builder_place_def(F.bld, 0, &e), DAL_E_ARG, F.bld);
  e = d;
  e.coords = NULL;
  BL(dal_builder_place_def(F.bld, 0, &e), DAL_E_ARG, F.bld);
  e = d;
  e.parent = 5;
  BL(dal_builder_place_def(F.bld, 0, &e), DAL_E_ARG, F.bld);
  e = d;
  e.param[0] = 1.0; // cartesian2 takes no parameters
  BL(dal_builder_place_def(F.bld, 0, &e), DAL_E_ARG, F.bld);
  e = dal_default_place_def();
  e.prim = &dal_map_pendulum;
  e.coords = c;
  e.ncoords = 1;
  BL(dal_builder_place_def(F.bld, 0, &e), DAL_E_ARG, F.bld); // the length is required
  e.param[DAL_PENDULUM_L] = NAN;
  BL(dal_builder_place_def(F.bld, 0, &e), DAL_E_NONFINITE, F.bld);
  e.param[DAL_PENDULUM_L] = 1.0;
  e.param[DAL_PENDULUM_W] = INFINITY;
  BL(dal_builder_place_def(F.bld, 0, &e), DAL_E_NONFINITE, F.bld);
  // the parameter list: longer than the primitive's count, NULL with a count, a negative
  // count, beside a set param[] entry, a non-finite value in it
  double list[8] = {1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0}, nan1 = NAN;
  e = dal_default_place_def();
  e.prim = &dal_map_pendulum;
  e.coords = c;
  e.ncoords = 1;
  e.param_list = list;
  e.nparam_list = 8;
  BL(dal_builder_place_def(F.bld, 0, &e), DAL_E_ARG, F.bld);
  e.param_list = NULL;
  e.nparam_list = 1;
  BL(dal_builder_place_def(F.bld, 0, &e), DAL_E_ARG, F.bld);
  e.param_list = list;
  e.nparam_list = -1;
  BL(dal_builder_place_def(F.bld, 0, &e), DAL_E_ARG, F.bld);
  e.nparam_list = 1;
  e.param[DAL_PENDULUM_W] = 1.0;
  BL(dal_builder_place_def(F.bld, 0, &e), DAL_E_ARG, F.bld);
  e.param[DAL_PENDULUM_W] = d.param[DAL_PENDULUM_W]; // unset again
  e.param_list = &nan1;
  BL(dal_builder_place_def(F.bld, 0, &e), DAL_E_NONFINITE, F.bld);
  dal_builder *b = scratch(0);
  BL(dal_builder_place_def(b, 0, &d), DAL_OK, b);
  BL(dal_builder_place_def(b, 0, &d), DAL_E_ARG, b); // placed once
  dal_system *s = NULL;
  CHECK_OK(dal_builder_compile(b, &s));
  dal_system_destroy(s);
  dal_builder_destroy(b);
}
static void sw_dal_builder_add_constraint_def(void) {
  int p[1] = {0}, pbad[1] = {5}, idx = -1;
  dal_constraint_def d = dal_default_constraint_def(), raw, e;
  memset(&raw, 0, sizeof raw);
  d.name = "rod";
  d.prim = &dal_con_anchor2;
  d.parts = p;
  d.nparts = 1;
  d.param[0] = 1.0;
  BL(dal_builder_add_constraint_def(NULL, &d, &idx), DAL_E_ARG, NULL);
  BL(dal_builder_add_constraint_def(F.bld, NULL, &idx), DAL_E_ARG, F.bld);
  BL(dal_builder_add_constraint_def(F.bld, &raw, &idx), DAL_E_ARG, F.bld);
  e = d;
  e.prim = NULL;
  BL(dal_builder_add_constraint_def(F.bld, &e, &idx), DAL_E_ARG, F.bld);
  e = d;
  e.parts = NULL;
  BL(dal_builder_add_constraint_def(F.bld, &e, &idx), DAL_E_ARG, F.bld);
  e = d;
  e.parts = pbad;
  BL(dal_builder_add_constraint_def(F.bld, &e, &idx), DAL_E_ARG, F.bld);
  e = d;
  e.nparts = -1;
  BL(dal_builder_add_constraint_def(F.bld, &e, &idx), DAL_E_ARG, F.bld);
  e = d;
  e.ncoords = 1; // no coords array, and the input count no longer matches
  BL(dal_builder_add_constraint_def(F.bld, &e, &idx), DAL_E_ARG, F.bld);
  e = d;
  e.param[0] = NAN;
  BL(dal_builder_add_constraint_def(F.bld, &e, &idx), DAL_E_NONFINITE, F.bld);
  e = d;
  e.param[DAL_MAX_PARAM - 1] = 1.0; // beyond the primitive's parameters
  BL(dal_builder_add_constraint_def(F.bld, &e, &idx), DAL_E_ARG, F.bld);
  e = d;
  double four[4] = {1.0, 0.0, 0.0, 0.0};
  e.param[0] = e.param[1]; // unset: the list gives the parameters, one too many for anchor2
  e.param_list = four;
  e.nparam_list = 4;
  BL(dal_builder_add_constraint_def(F.bld, &e, &idx), DAL_E_ARG, F.bld);
  CHECK(idx == -1);
  dal_builder *b = scratch(1);
  e = d;
  e.name = NULL; // documented: gives "c<i>"
  BL(dal_builder_add_constraint_def(b, &e, &idx), DAL_OK, b);
  CHECK(idx == 0);
  BL(dal_builder_add_constraint_def(b, &d, NULL), DAL_OK, b);
  dal_system *s = NULL;
  CHECK_OK(dal_builder_compile(b, &s));
  CHECK(dal_system_nconstraints(s) == 2 && strcmp(dal_system_constraint_name(s, 0), "c0") == 0);
  CHECK(strcmp(dal_system_constraint_name(s, 1), "rod") == 0);
  dal_system_destroy(s);
  dal_builder_destroy(b);
}
static void sw_dal_builder_add_spring_def(void) {
  dal_spring_def d = dal_default_spring_def(), raw, e;
  memset(&raw, 0, sizeof raw);
  d.a = 0;
  d.k = 2.0;
  d.length = 0.5;
  BL(dal_builder_add_spring_def(NULL, &d), DAL_E_ARG, NULL);
  BL(dal_builder_add_spring_def(F.bld, NULL), DAL_E_ARG, F.bld);
  BL(dal_builder_add_spring_def(F.bld, &raw), DAL_E_ARG, F.bld);
  e = dal_default_spring_def(); // a = -1 must be set
  BL(dal_builder_add_spring_def(F.bld, &e), DAL_E_ARG, F.bld);
  e = d;
  e.a = 1;
  BL(dal_builder_add_spring_def(F.bld, &e), DAL_E_ARG, F.bld);
  e = d;
  e.b = -2;
  BL(dal_builder_add_spring_def(F.bld, &e), DAL_E_ARG, F.bld);
  e = d;
  e.b = 0; // a spring from a particle to itself
  BL(dal_builder_add_spring_def(F.bld, &e), DAL_E_ARG, F.bld);
  e = d;
  e.k = -1.0;
  BL(dal_builder_add_spring_def(F.bld, &e), DAL_E_ARG, F.bld);
  e = d;
  e.length = -1.0;
  BL(dal_builder_add_spring_def(F.bld, &e), DAL_E_ARG, F.bld);
  e = d;
  e.k = NAN;
  BL(dal_builder_add_spring_def(F.bld, &e), DAL_E_NONFINITE, F.bld);
  e = d;
  e.length = INFINITY;
  BL(dal_builder_add_spring_def(F.bld, &e), DAL_E_NONFINITE, F.bld);
  e = d;
  e.anchor[1] = NAN;
  BL(dal_builder_add_spring_def(F.bld, &e), DAL_E_NONFINITE, F.bld);
  dal_builder *b = scratch(1);
  BL(dal_builder_add_spring_def(b, &d), DAL_OK, b);
  dal_system *s = NULL;
  dal_param_ref k = {DAL_PARAM_SPRING_K, 0, 0};
  double v = 0.0;
  CHECK_OK(dal_builder_compile(b, &s));
  CHECK(dal_system_param(s, &k, &v) == DAL_OK && v == 2.0);
  dal_system_destroy(s);
  dal_builder_destroy(b);
}
static void sw_dal_builder_add_damper_def(void) {
  dal_damper_def d = dal_default_damper_def(), raw, e;
  memset(&raw, 0, sizeof raw);
  d.a = 0;
  d.c = 0.5;
  BL(dal_builder_add_damper_def(NULL, &d), DAL_E_ARG, NULL);
  BL(dal_builder_add_damper_def(F.bld, NULL), DAL_E_ARG, F.bld);
  BL(dal_builder_add_damper_def(F.bld, &raw), DAL_E_ARG, F.bld);
  e = dal_default_damper_def();
  BL(dal_builder_add_damper_def(F.bld, &e), DAL_E_ARG, F.bld);
  e = d;
  e.a = INT_MAX;
  BL(dal_builder_add_damper_def(F.bld, &e), DAL_E_ARG, F.bld);
  e = d;
  e.b = INT_MIN;
  BL(dal_builder_add_damper_def(F.bld, &e), DAL_E_ARG, F.bld);
  e = d;
  e.c = -0.5;
  BL(dal_builder_add_damper_def(F.bld, &e), DAL_E_ARG, F.bld);
  e = d;
  e.c = -INFINITY;
  BL(dal_builder_add_damper_def(F.bld, &e), DAL_E_NONFINITE, F.bld);
  e = d;
  e.anchor[0] = INFINITY;
  BL(dal_builder_add_damper_def(F.bld, &e), DAL_E_NONFINITE, F.bld);
  dal_builder *b = scratch(1);
  BL(dal_builder_add_damper_def(b, &d), DAL_OK, b);
  dal_system *s = NULL;
  dal_param_ref c = {DAL_PARAM_DAMPER_C, 0, 0};
  double v = 0.0;
  CHECK_OK(dal_builder_compile(b, &s));
  CHECK(dal_system_param(s, &c, &v) == DAL_OK && v == 0.5);
  dal_system_destroy(s);
  dal_builder_destroy(b);
}
static void sw_dal_builder_set_dynamics(void) {
  BL(dal_builder_set_dynamics(NULL, DAL_DYNAMICS_DENSE), DAL_E_ARG, NULL);
  BL(dal_builder_set_dynamics(F.bld, (dal_dynamics)7), DAL_E_ARG, F.bld);
  BL(dal_builder_set_dynamics(F.bld, (dal_dynamics)-1), DAL_E_ARG, F.bld);
  dal_builder *b = scratch(1);
  BL(dal_builder_set_dynamics(b, DAL_DYNAMICS_DENSE), DAL_OK, b);
  dal_system *s = NULL;
  CHECK_OK(dal_builder_compile(b, &s));
  CHECK(dal_system_dynamics(s) == DAL_DYNAMICS_DENSE);
  dal_system_destroy(s);
  dal_builder_destroy(b);
}
static void sw_dal_system_dynamics(void) {
  CHECK(dal_system_dynamics(NULL) == DAL_DYNAMICS_AUTO);
  // AUTO is resolved at compile time
  CHECK(dal_system_dynamics(F.A) == DAL_DYNAMICS_DENSE ||
        dal_system_dynamics(F.A) == DAL_DYNAMICS_RECURSIVE);
  CHECK(dal_system_dynamics(F.B) == DAL_DYNAMICS_DENSE ||
        dal_system_dynamics(F.B) == DAL_DYNAMICS_RECURSIVE);
}
static void sw_dal_system_print(void) {
  FILE *fp = tmpfile(), *ro = fopen("/dev/null", "r");
  CHECK(fp != NULL && ro != NULL);
  if (!fp || !ro) return;
  CHECK(dal_system_print(NULL, fp) == DAL_E_ARG);
  CHECK(dal_system_print(F.A, NULL) == DAL_E_ARG);
  CHECK(ftell(fp) == 0);
  CHECK(dal_system_print(F.A, ro) == DAL_E_IO);
  CHECK(dal_system_print(F.A, fp) == DAL_OK && ftell(fp) > 0);
  fclose(fp);
  fclose(ro);
}

// ---------------------------------------------------------------- rows: state.h, dae.h (more)
static void sw_dal_state_print(void) {
  FILE *fp = tmpfile(), *ro = fopen("/dev/null", "r");
  CHECK(fp != NULL && ro != NULL);
  if (!fp || !ro) return;
  // the state is const: no message can be kept; the header documents DAL_E_ARG for a state of
  // another system (the README convention would be DAL_E_STATE)
  ST(dal_state_print(NULL, F.stA, fp), DAL_E_STATE, F.stA);
  ST(dal_state_print(F.A, NULL, fp), DAL_E_ARG, NULL);
  ST(dal_state_print(F.A, F.stA, NULL), DAL_E_ARG, F.stA);
  ST(dal_state_print(F.B, F.stA, fp), DAL_E_STATE, F.stA);
  CHECK(ftell(fp) == 0);
  ST(dal_state_print(F.A, F.stA, ro), DAL_E_IO, NULL);
  ST(dal_state_print(F.A, F.stA, fp), DAL_OK, NULL);
  CHECK(ftell(fp) > 0);
  fclose(fp);
  fclose(ro);
}
static void sw_dal_state_init_report(void) {
  dal_init_report rep;
  ST(dal_state_init_report(NULL, &rep), DAL_E_ARG, NULL);
  ST(dal_state_init_report(F.stA, NULL), DAL_E_ARG, NULL);
  // no consistent start yet on a fresh state: DAL_E_STATE, the report zeroed with rows -1
  dal_state *st = state_b();
  memset(&rep, 0x55, sizeof rep);
  ST(dal_state_init_report(st, &rep), DAL_E_STATE, NULL);
  CHECK(rep.phi_row == -1 && rep.phidot_row == -1 && rep.dq_coord == -1 && rep.dqdot_coord == -1);
  dal_state_destroy(st);
  CHECK_OK(dal_make_consistent(F.A, F.stA, 0.0, NULL));
  ST(dal_state_init_report(F.stA, &rep), DAL_OK, NULL);
}

// ---------------------------------------------------------------- the table
// ---------------------------------------------------------------- rows: events.h
static double ev_theta(double t, const double *q, const double *qd, void *ctx) {
  (void)t;
  (void)qd;
  (void)ctx;
  return q[0];
}
static void sw_dal_default_event_def(void) {
  dal_event_def d = dal_default_event_def();
  CHECK(d.g == NULL && d.g_state == NULL && d.constraint == NULL && d.terminal == 0);
  CHECK(d.direction == DAL_EVENT_BOTH && d.name != NULL);
}
static void sw_dal_events_create(void) {
  dal_events *ev = (dal_events *)&F; // overwritten with NULL on failure
  CHECK(dal_events_create(NULL, &ev) == DAL_E_ARG && ev == NULL);
  CHECK(dal_events_create(F.A, NULL) == DAL_E_ARG);
  CHECK(dal_events_create(F.A, &ev) == DAL_OK && ev != NULL);
  dal_events_destroy(ev);
}
static void sw_dal_events_destroy(void) { dal_events_destroy(NULL); }
static void sw_dal_events_add(void) {
  dal_events *ev = NULL;
  CHECK_OK(dal_events_create(F.A, &ev));
  dal_event_def d = dal_default_event_def();
  CHECK(dal_events_add(NULL, &d) == DAL_E_ARG);
  CHECK(dal_events_add(ev, NULL) == DAL_E_ARG);
  CHECK(dal_events_add(ev, &d) == DAL_E_ARG); // no function
  CHECK(strstr(dal_events_errmsg(ev), "exactly one") != NULL);
  dal_event_def raw;
  memset(&raw, 0, sizeof raw);
  raw.g = ev_theta;
  CHECK(dal_events_add(ev, &raw) == DAL_E_ARG); // no cookie
  d.g = ev_theta;
  d.constraint = "rod";
  CHECK(dal_events_add(ev, &d) == DAL_E_ARG); // two kinds
  d.g = NULL;
  d.constraint = "rope";
  CHECK(dal_events_add(ev, &d) == DAL_E_ARG); // unknown constraint, named with the known ones
  CHECK(strstr(dal_events_errmsg(ev), "'rope'") && strstr(dal_events_errmsg(ev), "'rod'"));
  d.constraint = "rod";
  d.row = 1;
  CHECK(dal_events_add(ev, &d) == DAL_E_ARG); // a scalar constraint has row 0 only
  d.row = 0;
  d.direction = (dal_event_direction)3;
  CHECK(dal_events_add(ev, &d) == DAL_E_ARG);
  d.direction = DAL_EVENT_FALLING;
  CHECK(dal_events_add(ev, &d) == 0);
  CHECK(dal_events_size(ev) == 1);
  dal_events_destroy(ev);
}
static void sw_dal_events_errmsg(void) { CHECK(strcmp(dal_events_errmsg(NULL), "") == 0); }
static void sw_dal_events_size(void) { CHECK(dal_events_size(NULL) == 0); }
static void sw_dal_events_name(void) {
  dal_events *ev = NULL;
  CHECK_OK(dal_events_create(F.B, &ev));
  dal_event_def d = dal_default_event_def();
  d.g = ev_theta;
  d.name = "zero";
  CHECK(dal_events_add(ev, &d) == 0);
  CHECK(strcmp(dal_events_name(ev, 0), "zero") == 0);
  CHECK(dal_events_name(ev, 1) == NULL && dal_events_name(ev, -1) == NULL);
  CHECK(dal_events_name(NULL, 0) == NULL);
  dal_events_destroy(ev);
}
static void sw_dal_state_set_events(void) {
  dal_events *ev = NULL;
  CHECK_OK(dal_events_create(F.A, &ev));
  CHECK(dal_state_set_events(NULL, ev) == DAL_E_ARG);
  ST(dal_state_set_events(F.stB, ev), DAL_E_STATE, F.stB); // a set of another system
  CHECK(dal_state_set_events(F.stA, NULL) == DAL_OK);
  dal_events_destroy(ev);
}
static void sw_dal_trajectory_create(void) {
  dal_trajectory *tr = (dal_trajectory *)&F; // overwritten with NULL on failure
  CHECK(dal_trajectory_create(NULL, &tr) == DAL_E_ARG && tr == NULL);
  CHECK(dal_trajectory_create(F.B, NULL) == DAL_E_ARG);
  CHECK(dal_trajectory_create(F.B, &tr) == DAL_OK && tr != NULL);
  dal_trajectory_destroy(tr);
}
static void sw_dal_trajectory_destroy(void) { dal_trajectory_destroy(NULL); }
static void sw_dal_trajectory_errmsg(void) { CHECK(strcmp(dal_trajectory_errmsg(NULL), "") == 0); }
static void sw_dal_state_set_trajectory(void) {
  dal_trajectory *tr = NULL;
  CHECK_OK(dal_trajectory_create(F.A, &tr));
  CHECK(dal_state_set_trajectory(NULL, tr) == DAL_E_ARG);
  ST(dal_state_set_trajectory(F.stB, tr), DAL_E_STATE, F.stB); // another system's
  CHECK(dal_state_set_trajectory(F.stA, NULL) == DAL_OK);
  dal_trajectory_destroy(tr);
}
static void sw_dal_trajectory_span(void) {
  dal_trajectory *tr = NULL;
  double t0 = 0, t1 = 0;
  CHECK(dal_trajectory_span(NULL, &t0, &t1) == DAL_E_ARG);
  CHECK_OK(dal_trajectory_create(F.B, &tr));
  CHECK(dal_trajectory_span(tr, &t0, &t1) == 0 && isnan(t0) && isnan(t1));
  CHECK(dal_trajectory_span(tr, NULL, NULL) == 0);
  dal_trajectory_destroy(tr);
}
static void sw_dal_trajectory_eval(void) {
  dal_trajectory *tr = NULL;
  dal_state *st = NULL;
  double q = 0.3, qd = 0, qo, vo;
  CHECK(dal_trajectory_eval(NULL, 0.0, &qo, &vo) == DAL_E_ARG);
  CHECK_OK(dal_trajectory_create(F.B, &tr));
  CHECK(dal_trajectory_eval(tr, 0.0, &qo, &vo) == DAL_E_ARG && dal_trajectory_errmsg(tr)[0]);
  CHECK_OK(dal_state_create(F.B, &st));
  CHECK_OK(dal_state_set(F.B, st, 0.0, &q, &qd));
  CHECK_OK(dal_state_set_trajectory(st, tr));
  CHECK_OK(dal_advance(F.B, st, &F.o, 0.5));
  CHECK(dal_trajectory_eval(tr, NAN, &qo, &vo) == DAL_E_NONFINITE && dal_trajectory_errmsg(tr)[0]);
  CHECK(dal_trajectory_eval(tr, INFINITY, &qo, &vo) == DAL_E_NONFINITE);
  CHECK(dal_trajectory_eval(tr, 0.6, &qo, &vo) == DAL_E_ARG && dal_trajectory_errmsg(tr)[0]);
  CHECK(dal_trajectory_eval(tr, -0.1, &qo, &vo) == DAL_E_ARG);
  CHECK(dal_trajectory_eval(tr, 0.25, NULL, NULL) == DAL_OK);
  CHECK(dal_trajectory_eval(tr, 0.5, &qo, NULL) == DAL_OK && qo == dal_state_q(st)[0]);
  CHECK(dal_trajectory_errmsg(tr)[0] == 0);
  dal_state_destroy(st);
  dal_trajectory_destroy(tr);
}
static void sw_dal_events_count(void) { CHECK(dal_events_count(NULL) == 0); }
static void sw_dal_events_get(void) {
  dal_events *ev = NULL;
  dal_event_record r;
  CHECK_OK(dal_events_create(F.B, &ev));
  CHECK(dal_events_get(NULL, 0, &r, NULL, NULL) == DAL_E_ARG);
  CHECK(dal_events_get(ev, 0, &r, NULL, NULL) == DAL_E_ARG); // empty log
  CHECK(dal_events_get(ev, -1, &r, NULL, NULL) == DAL_E_ARG);
  dal_events_destroy(ev);
}
static void sw_dal_events_clear(void) { dal_events_clear(NULL); }
static void sw_dal_events_write_csv(void) {
  dal_events *ev = NULL;
  CHECK_OK(dal_events_create(F.B, &ev));
  CHECK(dal_events_write_csv(NULL, stdout, -1, 0) == DAL_E_ARG);
  CHECK(dal_events_write_csv(ev, NULL, -1, 0) == DAL_E_ARG);
  CHECK(dal_events_write_csv(ev, stdout, 0, 0) == DAL_E_ARG); // no event 0
  CHECK(dal_events_write_csv(ev, stdout, -2, 0) == DAL_E_ARG);
  dal_events_destroy(ev);
}

// ---------------------------------------------------------------- expressions and scenes
static dal_expr *sweep_expr(int velocities) {
  const char *f = "l*sin(x)", *in = "x", *pn = "l";
  double v = 1.0;
  dal_expr_def d = dal_default_expr_def();
  d.formulas = &f;
  d.nout = 1;
  d.inputs = &in;
  d.nin = 1;
  d.velocities = velocities;
  d.params = &pn;
  d.values = &v;
  d.nparam = 1;
  dal_expr *e = NULL;
  CHECK_OK(dal_expr_create(&d, &e, NULL, 0));
  return e;
}
static const char *sweep_scene_text = "dim 2\nparam l = 1\ncoord th q=1\nparticle b mass=1\n"
                                      "place b = l*sin(th); -l*cos(th)\ngravity 0 -9.8\n"
                                      "run t1=0.1 dt=0.05\n";
static void sw_dal_default_expr_def(void) { CHECK(dal_default_expr_def().nout == 0); }
static void sw_dal_expr_create(void) {
  dal_expr *e = (dal_expr *)&F;
  dal_expr_def d = dal_default_expr_def();
  char msg[256];
  CHECK(dal_expr_create(NULL, &e, msg, sizeof msg) == DAL_E_ARG && e == NULL && msg[0]);
  CHECK(dal_expr_create(&d, NULL, msg, sizeof msg) == DAL_E_ARG);
  CHECK(dal_expr_create(&d, &e, msg, sizeof msg) == DAL_E_ARG && msg[0]); // no formulas
  const char *f = "x";
  d.formulas = &f;
  d.nout = 1;
  d.nin = 1; // inputs NULL
  CHECK(dal_expr_create(&d, &e, msg, sizeof msg) == DAL_E_ARG && msg[0]);
  double nan = NAN;
  const char *pn = "p";
  d.nin = 0;
  d.formulas = &pn;
  d.params = &pn;
  d.values = &nan;
  d.nparam = 1;
  CHECK(dal_expr_create(&d, &e, msg, sizeof msg) == DAL_E_NONFINITE && msg[0]);
  CHECK(dal_expr_create(&d, &e, NULL, 0) == DAL_E_NONFINITE);
}
static void sw_dal_expr_destroy(void) { dal_expr_destroy(NULL); }
static void sw_dal_expr_nout(void) { CHECK(dal_expr_nout(NULL) == 0); }
static void sw_dal_expr_nin(void) { CHECK(dal_expr_nin(NULL) == 0); }
static void sw_dal_expr_nparam(void) { CHECK(dal_expr_nparam(NULL) == 0); }
static void sw_dal_expr_symbol(void) {
  dal_expr *e = sweep_expr(0);
  CHECK(dal_expr_symbol(NULL, 0) == NULL);
  CHECK(dal_expr_symbol(e, -1) == NULL && dal_expr_symbol(e, 2) == NULL);
  CHECK(!strcmp(dal_expr_symbol(e, 1), "l"));
  dal_expr_destroy(e);
}
static void sw_dal_expr_values(void) { CHECK(dal_expr_values(NULL) == NULL); }
static void sw_dal_expr_depends(void) {
  dal_expr *e = sweep_expr(0);
  CHECK(dal_expr_depends(NULL, 0) == 0 && dal_expr_depends(e, 5) == 0 &&
        dal_expr_depends(e, -2) == 0 && dal_expr_depends(e, -1) == 0 &&
        dal_expr_depends(e, 0) == 1);
  dal_expr_destroy(e);
}
static void sw_dal_expr_ninstructions(void) { CHECK(dal_expr_ninstructions(NULL) == 0); }
static void sw_dal_expr_eval(void) {
  dal_expr *e = sweep_expr(0);
  dal_jet in = dal_const(1), out;
  CHECK(dal_expr_eval(NULL, &in, in, NULL, &out) == DAL_E_ARG);
  CHECK(dal_expr_eval(e, NULL, in, NULL, &out) == DAL_E_ARG);
  CHECK(dal_expr_eval(e, &in, in, NULL, NULL) == DAL_E_ARG);
  dal_expr_destroy(e);
}
static void sw_dal_expr_check(void) {
  dal_expr *e = sweep_expr(0);
  dal_jet in = dal_const(1), out;
  char msg[64];
  CHECK(dal_expr_check(NULL, &in, in, NULL, &out, msg, sizeof msg) == DAL_E_ARG);
  CHECK(dal_expr_check(e, NULL, in, NULL, &out, msg, sizeof msg) == DAL_E_ARG);
  CHECK(dal_expr_check(e, &in, in, NULL, NULL, NULL, 0) == DAL_E_ARG);
  in = dal_const(NAN);
  CHECK(dal_expr_check(e, &in, in, NULL, &out, msg, sizeof msg) == DAL_E_DOMAIN && msg[0]);
  dal_expr_destroy(e);
}
static void sw_dal_expr_primitive(void) { CHECK(dal_expr_primitive(NULL) == NULL); }
static void sw_dal_expr_place_def(void) {
  dal_expr *e = sweep_expr(0);
  dal_place_def d = dal_default_place_def();
  CHECK(dal_expr_place_def(NULL, &d) == DAL_E_ARG && dal_expr_place_def(e, NULL) == DAL_E_ARG);
  dal_expr_destroy(e);
}
static void sw_dal_expr_constraint_def(void) {
  dal_expr *e = sweep_expr(0);
  dal_constraint_def d = dal_default_constraint_def();
  CHECK(dal_expr_constraint_def(NULL, &d) == DAL_E_ARG &&
        dal_expr_constraint_def(e, NULL) == DAL_E_ARG);
  dal_expr_destroy(e);
}
static void sw_dal_expr_map(void) {
  dal_jet q = dal_const(0), r;
  CHECK(dal_expr_map(&q, q, &r, NULL) < 0);
}
static void sw_dal_expr_potential_r(void) {
  dal_jet q = dal_const(0), r;
  CHECK(dal_expr_potential_r(&q, q, &r, NULL) < 0);
}
static void sw_dal_expr_potential_q(void) {
  dal_jet q = dal_const(0), r;
  CHECK(dal_expr_potential_q(&q, q, &r, NULL) < 0);
}
static void sw_dal_expr_lagrangian(void) {
  dal_expr *e = sweep_expr(0); // no velocities: not a Lagrangian
  dal_jet q = dal_const(0), L;
  CHECK(dal_expr_lagrangian(q, &q, &q, &L, NULL) < 0);
  CHECK(dal_expr_lagrangian(q, &q, &q, &L, e) < 0);
  dal_expr_destroy(e);
}
static void sw_dal_expr_path(void) {
  dal_jet x;
  CHECK(dal_expr_path(dal_const(0), &x, NULL) < 0);
}
static void sw_dal_expr_time(void) {
  dal_jet x;
  CHECK(dal_expr_time(dal_const(0), &x, NULL) < 0);
}
static void sw_dal_expr_event(void) {
  double q = 0;
  dal_expr *e = sweep_expr(0);
  CHECK(isnan(dal_expr_event(0, &q, &q, NULL)) && isnan(dal_expr_event(0, &q, &q, e)));
  dal_expr_destroy(e);
}
static void sw_dal_expr_print(void) {
  dal_expr *e = sweep_expr(0);
  char buf[64];
  CHECK(dal_expr_print(NULL, 0, DAL_EXPR_TEXT, buf, sizeof buf) == DAL_E_ARG);
  CHECK(dal_expr_print(e, 1, DAL_EXPR_TEXT, buf, sizeof buf) == DAL_E_ARG);
  CHECK(dal_expr_print(e, -1, DAL_EXPR_TEXT, buf, sizeof buf) == DAL_E_ARG);
  CHECK(dal_expr_print(e, 0, (dal_expr_format)7, buf, sizeof buf) == DAL_E_ARG);
  CHECK(dal_expr_print(e, 0, DAL_EXPR_TEXT, NULL, 4) == DAL_E_ARG);
  CHECK(dal_expr_print(e, 0, DAL_EXPR_TEXT, NULL, 0) == (int)strlen("l*sin(x)"));
  dal_expr_destroy(e);
}
static void sw_dal_expr_derivative(void) {
  dal_expr *e = sweep_expr(0), *d = (dal_expr *)&F;
  char msg[128];
  CHECK(dal_expr_derivative(NULL, 0, 0, &d, msg, sizeof msg) == DAL_E_ARG && d == NULL);
  CHECK(dal_expr_derivative(e, 0, 0, NULL, msg, sizeof msg) == DAL_E_ARG);
  CHECK(dal_expr_derivative(e, 1, 0, &d, msg, sizeof msg) == DAL_E_ARG && msg[0]);
  CHECK(dal_expr_derivative(e, 0, 1, &d, msg, sizeof msg) == DAL_E_ARG && msg[0]);
  CHECK(dal_expr_derivative(e, 0, -2, &d, NULL, 0) == DAL_E_ARG);
  dal_expr_destroy(e);
}
static void sw_dal_default_expr_model_def(void) { CHECK(dal_default_expr_model_def().dim == 0); }
static void sw_dal_expr_model_energies(void) {
  dal_expr *T = (dal_expr *)&F;
  char msg[256];
  dal_expr_model_def d = dal_default_expr_model_def();
  CHECK(dal_expr_model_energies(NULL, &T, NULL, NULL, msg, sizeof msg) == DAL_E_ARG && !T &&
        msg[0]);
  CHECK(dal_expr_model_energies(&d, &T, NULL, NULL, msg, sizeof msg) == DAL_E_ARG && msg[0]);
  const char *c = "q", *m = "1", *pos = "q";
  d.dim = 1;
  d.coords = &c;
  d.ncoords = 1;
  d.masses = &m;
  d.nparticles = 1;
  d.positions = &pos;
  CHECK_OK(dal_expr_model_energies(&d, NULL, NULL, NULL, NULL, 0));
  pos = "q +";
  CHECK(dal_expr_model_energies(&d, &T, NULL, NULL, msg, sizeof msg) == DAL_E_ARG &&
        strstr(msg, "position x of particle 1"));
}
static void sw_dal_expr_lagrange(void) {
  dal_expr *e = sweep_expr(0);
  dal_expr_equations eq;
  char msg[256];
  CHECK(dal_expr_lagrange(NULL, &eq, msg, sizeof msg) == DAL_E_ARG && msg[0]);
  CHECK(dal_expr_lagrange(e, NULL, msg, sizeof msg) == DAL_E_ARG);
  CHECK(dal_expr_lagrange(e, &eq, msg, sizeof msg) == DAL_E_ARG && msg[0] && !eq.mass);
  dal_expr_destroy(e);
  e = sweep_expr(1);
  CHECK_OK(dal_expr_lagrange(e, &eq, NULL, 0));
  dal_expr_equations_destroy(&eq);
  dal_expr_destroy(e);
}
static void sw_dal_expr_equations_destroy(void) { dal_expr_equations_destroy(NULL); }
static void sw_dal_scene_parse(void) {
  dal_scene *sc = (dal_scene *)&F;
  char msg[256];
  CHECK(dal_scene_parse(NULL, "x", &sc, msg, sizeof msg) == DAL_E_ARG && sc == NULL);
  CHECK(dal_scene_parse(sweep_scene_text, "x", NULL, msg, sizeof msg) == DAL_E_ARG);
  CHECK(dal_scene_parse("dim 7\n", NULL, &sc, msg, sizeof msg) == DAL_E_ARG && msg[0]);
  CHECK(dal_scene_parse("", NULL, &sc, NULL, 0) == DAL_E_ARG);
}
static void sw_dal_scene_read(void) {
  dal_scene *sc = (dal_scene *)&F;
  char msg[256];
  CHECK(dal_scene_read(NULL, &sc, msg, sizeof msg) == DAL_E_ARG && sc == NULL);
  CHECK(dal_scene_read("/nonexistent/x.scene", NULL, msg, sizeof msg) == DAL_E_ARG);
  CHECK(dal_scene_read("/nonexistent/x.scene", &sc, msg, sizeof msg) == DAL_E_IO && msg[0]);
}
static void sw_dal_scene_destroy(void) { dal_scene_destroy(NULL); }
static dal_scene *sweep_scene(void) {
  dal_scene *sc = NULL;
  CHECK_OK(dal_scene_parse(sweep_scene_text, "sweep", &sc, NULL, 0));
  return sc;
}
static void sw_dal_scene_write(void) {
  dal_scene *sc = sweep_scene();
  CHECK(dal_scene_write(NULL, stdout) == DAL_E_ARG && dal_scene_write(sc, NULL) == DAL_E_ARG);
  dal_scene_destroy(sc);
}
static void sw_dal_scene_set_param(void) {
  dal_scene *sc = sweep_scene();
  char msg[128];
  CHECK(dal_scene_set_param(NULL, "l", 1, msg, sizeof msg) == DAL_E_ARG);
  CHECK(dal_scene_set_param(sc, NULL, 1, msg, sizeof msg) == DAL_E_ARG);
  CHECK(dal_scene_set_param(sc, "zz", 1, msg, sizeof msg) == DAL_E_ARG && msg[0]);
  CHECK(dal_scene_set_param(sc, "l", NAN, msg, sizeof msg) == DAL_E_NONFINITE);
  CHECK_OK(dal_scene_set_param(sc, "l", 2, msg, sizeof msg));
  CHECK(dal_scene_system(sc) != NULL);
  dal_scene_destroy(sc);
}
static void sw_dal_scene_system(void) { CHECK(dal_scene_system(NULL) == NULL); }
static void sw_dal_scene_opts(void) { CHECK(dal_scene_opts(NULL, NULL, NULL, NULL) == NULL); }
static void sw_dal_scene_state(void) {
  dal_scene *sc = sweep_scene();
  dal_state *st;
  CHECK(dal_scene_state(NULL, &st) == DAL_E_ARG && dal_scene_state(sc, NULL) == DAL_E_ARG);
  dal_scene_destroy(sc);
}
static void sw_dal_scene_run(void) {
  dal_scene *sc = sweep_scene();
  dal_state *st = (dal_state *)&F;
  CHECK(dal_scene_run(NULL, NULL, &st, NULL, 0) == DAL_E_ARG && st == NULL);
  CHECK_OK(dal_scene_run(sc, NULL, NULL, NULL, 0));
  dal_scene_destroy(sc);
}
static void sw_dal_scene_events(void) {
  dal_scene *sc = sweep_scene();
  dal_events *ev = (dal_events *)&F;
  CHECK(dal_scene_events(NULL, &ev) == DAL_E_ARG && ev == NULL);
  CHECK(dal_scene_events(sc, NULL) == DAL_E_ARG);
  CHECK_OK(dal_scene_events(sc, &ev));
  CHECK(ev && dal_events_size(ev) == 0);
  dal_events_destroy(ev);
  dal_scene_destroy(sc);
}
static void sw_dal_scene_event_is_section(void) {
  dal_scene *sc = sweep_scene();
  CHECK(dal_scene_event_is_section(NULL, 0) == -1 && dal_scene_event_is_section(sc, 0) == -1 &&
        dal_scene_event_is_section(sc, -1) == -1);
  dal_scene_destroy(sc);
}
static void sw_dal_scene_strobe(void) {
  dal_scene *sc = sweep_scene();
  CHECK(dal_scene_strobe(NULL) == 0 && dal_scene_strobe(sc) == 0);
  dal_scene_destroy(sc);
}
static void sw_dal_scene_help(void) {
  CHECK(dal_scene_help(NULL) == DAL_E_ARG);
  FILE *fp = tmpfile();
  char out[4096] = "";
  CHECK_OK(dal_scene_help(fp));
  rewind(fp);
  size_t n = fread(out, 1, sizeof out - 1, fp);
  out[n] = 0;
  fclose(fp);
  CHECK(strstr(out, "  force COORD = ") && strstr(out, "  param NAME = FORMULA"));
}
static void sw_dal_scene_run_events(void) {
  dal_scene *sc = sweep_scene(), *other = sweep_scene();
  dal_state *st = (dal_state *)&F;
  dal_events *ev = NULL;
  char msg[256];
  CHECK(dal_scene_run_events(NULL, NULL, NULL, &st, NULL, 0) == DAL_E_ARG && st == NULL);
  // an event set of another scene's system is foreign
  CHECK_OK(dal_scene_events(other, &ev));
  CHECK(dal_scene_run_events(sc, NULL, ev, NULL, msg, sizeof msg) == DAL_E_STATE && msg[0]);
  dal_events_destroy(ev);
  CHECK_OK(dal_scene_run_events(sc, NULL, NULL, NULL, NULL, 0));
  dal_scene_destroy(other);
  dal_scene_destroy(sc);
}
static void sw_dal_scene_show(void) {
  dal_scene *sc = sweep_scene();
  CHECK(dal_scene_show(NULL, stdout, DAL_EXPR_TEXT, NULL, 0) == DAL_E_ARG);
  CHECK(dal_scene_show(sc, NULL, DAL_EXPR_TEXT, NULL, 0) == DAL_E_ARG);
  dal_scene_destroy(sc);
}
static void sw_dal_scene_native(void) {
  dal_scene *sc = sweep_scene();
  dal_codegen_opts o;
  memset(&o, 0, sizeof o); // not from dal_codegen_default_opts
  char msg[256];
  CHECK(dal_scene_native(NULL, NULL, msg, sizeof msg) == DAL_E_ARG);
  CHECK(dal_scene_native(sc, &o, msg, sizeof msg) == DAL_E_ARG && msg[0]);
  CHECK(dal_codegen_attached(dal_scene_expr(sc, 0)) == 0);
  dal_scene_destroy(sc);
}
static void sw_dal_scene_nexprs(void) { CHECK(dal_scene_nexprs(NULL) == 0); }
static void sw_dal_scene_expr(void) {
  dal_scene *sc = sweep_scene();
  int n = dal_scene_nexprs(sc);
  CHECK(n > 0 && dal_scene_expr(sc, 0) != NULL);
  CHECK(dal_scene_expr(NULL, 0) == NULL && dal_scene_expr(sc, -1) == NULL &&
        dal_scene_expr(sc, n) == NULL);
  dal_scene_destroy(sc);
}
static void sw_dal_scene_write_c(void) {
  dal_scene *sc = sweep_scene();
  CHECK(dal_scene_write_c(NULL, "m", stdout) == DAL_E_ARG);
  CHECK(dal_scene_write_c(sc, "m", NULL) == DAL_E_ARG);
  CHECK(dal_scene_write_c(sc, NULL, stdout) == DAL_E_ARG);
  CHECK(dal_scene_write_c(sc, "1m", stdout) == DAL_E_ARG);
  CHECK(dal_scene_write_c(sc, "a-b", stdout) == DAL_E_ARG);
  dal_scene_destroy(sc);
}
static void sw_dal_codegen_default_opts(void) {
  dal_codegen_opts o = dal_codegen_default_opts();
  CHECK(o.cc == NULL && o.cache_dir == NULL && o.cookie != 0);
}
static void sw_dal_codegen_write(void) {
  dal_scene *sc = sweep_scene();
  dal_expr *e = (dal_expr *)dal_scene_expr(sc, 0), *none[1] = {NULL};
  CHECK(dal_codegen_write(NULL, 1, "m", stdout) == DAL_E_ARG);
  CHECK(dal_codegen_write(none, 1, "m", stdout) == DAL_E_ARG);
  CHECK(dal_codegen_write(&e, -1, "m", stdout) == DAL_E_ARG);
  CHECK(dal_codegen_write(&e, 1, "m", NULL) == DAL_E_ARG);
  CHECK(dal_codegen_write(&e, 1, "", stdout) == DAL_E_ARG);
  dal_scene_destroy(sc);
}
static void sw_dal_codegen_attach(void) {
  dal_scene *sc = sweep_scene();
  dal_expr *e = (dal_expr *)dal_scene_expr(sc, 0), *none[1] = {NULL};
  dal_codegen_opts o;
  memset(&o, 0, sizeof o);
  char msg[256];
  CHECK(dal_codegen_attach(NULL, 1, NULL, msg, sizeof msg) == DAL_E_ARG && msg[0]);
  CHECK(dal_codegen_attach(&e, 0, NULL, msg, sizeof msg) == DAL_E_ARG && msg[0]);
  CHECK(dal_codegen_attach(none, 1, NULL, msg, sizeof msg) == DAL_E_ARG && msg[0]);
  CHECK(dal_codegen_attach(&e, 1, &o, msg, sizeof msg) == DAL_E_ARG && msg[0]);
  CHECK(dal_codegen_attached(e) == 0);
  dal_scene_destroy(sc);
}
static void sw_dal_codegen_attached(void) { CHECK(dal_codegen_attached(NULL) == 0); }
static void sw_dal_codegen_attach_eom(void) {
  dal_codegen_opts o;
  memset(&o, 0, sizeof o);
  char msg[256];
  CHECK(dal_codegen_attach_eom(NULL, NULL, msg, sizeof msg) == DAL_E_ARG && msg[0]);
  CHECK(dal_codegen_attach_eom(F.B, &o, msg, sizeof msg) == DAL_E_ARG && msg[0]);
  // out of reach: a constraint (A), a placement by a C primitive (B); nothing attached
  CHECK(dal_codegen_attach_eom(F.A, NULL, msg, sizeof msg) == DAL_E_UNSUPPORTED &&
        strstr(msg, "constraints"));
  CHECK(dal_codegen_attach_eom(F.B, NULL, msg, sizeof msg) == DAL_E_UNSUPPORTED &&
        strstr(msg, "not placed by formulas"));
  CHECK(dal_codegen_eom_attached(F.A) == 0 && dal_codegen_eom_attached(F.B) == 0);
}
static void sw_dal_codegen_eom_attached(void) { CHECK(dal_codegen_eom_attached(NULL) == 0); }

typedef struct sweep_row {
  const char *name;
  void (*run)(void);
} sweep_row;

// ---------------------------------------------------------------- rows: output.h
static void sw_dal_columns_create(void) {
  char buf[256], *msg = buf;
  dal_columns *c = (dal_columns *)&F; // reset to NULL on failure
  MS(dal_columns_create(NULL, "t", &c, msg, sizeof buf), DAL_E_ARG, msg);
  CHECK(c == NULL);
  MS(dal_columns_create(F.A, "t", NULL, msg, sizeof buf), DAL_E_ARG, msg);
  MS(dal_columns_create(F.A, "x:nobody", &c, msg, sizeof buf), DAL_E_ARG, msg);
  MS(dal_columns_create(F.A, "t", &c, NULL, 0), DAL_OK, NULL);
  CHECK(dal_columns_count(c) == 1);
  dal_columns_destroy(c);
}
static void sw_dal_columns_destroy(void) { dal_columns_destroy(NULL); }
static void sw_dal_columns_count(void) { CHECK(dal_columns_count(NULL) == 0); }
static void sw_dal_columns_name(void) {
  dal_columns *c = NULL;
  CHECK_OK(dal_columns_create(F.A, NULL, &c, NULL, 0));
  CHECK(dal_columns_name(NULL, 0) == NULL);
  CHECK(dal_columns_name(c, -1) == NULL && dal_columns_name(c, 99) == NULL);
  CHECK(strcmp(dal_columns_name(c, 0), "t") == 0);
  dal_columns_destroy(c);
}
static void sw_dal_columns_need_work(void) { CHECK(dal_columns_need_work(NULL) == 0); }
static void sw_dal_columns_eval(void) {
  dal_columns *c = NULL;
  double row[16];
  CHECK_OK(dal_columns_create(F.A, "t,lambda:rod", &c, NULL, 0));
  ST_OWNER(dal_columns_eval, F.A, F.B, F.stA, c, row);
  ST(dal_columns_eval(F.A, F.stA, NULL, row), DAL_E_ARG, F.stA);
  ST(dal_columns_eval(F.A, F.stA, c, NULL), DAL_E_ARG, F.stA);
  ST(dal_columns_eval(F.B, F.stB, c, row), DAL_E_ARG, F.stB); // made for another system
  ST(dal_columns_eval(F.A, F.stA, c, row), DAL_OK, F.stA);
  dal_columns_destroy(c);
  st_intact();
}
static void sw_dal_columns_write_header(void) {
  dal_columns *c = NULL;
  CHECK_OK(dal_columns_create(F.A, NULL, &c, NULL, 0));
  CHECK(dal_columns_write_header(NULL, stdout) == DAL_E_ARG);
  CHECK(dal_columns_write_header(c, NULL) == DAL_E_ARG);
  dal_columns_destroy(c);
}
static void sw_dal_default_view_opts(void) {
  dal_view_opts o = dal_default_view_opts();
  CHECK(o.fps == 60 && o.t1 == 10 && o.solve == NULL);
}
static void sw_dal_view_write(void) {
  dal_view_opts o = dal_default_view_opts();
  FILE *fp = tmpfile();
  ST_OWNER(dal_view_write, F.A, F.B, F.stA, &o, NULL, fp);
  ST(dal_view_write(F.A, F.stA, &o, NULL, NULL), DAL_E_ARG, F.stA);
  o.fps = -1;
  ST(dal_view_write(F.A, F.stA, &o, NULL, fp), DAL_E_ARG, F.stA);
  o.fps = NAN;
  ST(dal_view_write(F.A, F.stA, &o, NULL, fp), DAL_E_NONFINITE, F.stA);
  o.fps = 60, o.t1 = -1;
  ST(dal_view_write(F.A, F.stA, &o, NULL, fp), DAL_E_ARG, F.stA);
  o.t1 = 1e9;
  ST(dal_view_write(F.A, F.stA, &o, NULL, fp), DAL_E_ARG, F.stA); // too many frames
  CHECK(ftell(fp) == 0);
  fclose(fp);
  st_intact();
}
static void sw_dal_picture_write(void) {
  double ts[2] = {0.1, 0.2};
  FILE *fp = tmpfile();
  ST_OWNER(dal_picture_write, F.A, F.B, F.stA, ts, 2, NULL, fp);
  ST(dal_picture_write(F.A, F.stA, NULL, 2, NULL, fp), DAL_E_ARG, F.stA);
  ST(dal_picture_write(F.A, F.stA, ts, 0, NULL, fp), DAL_E_ARG, F.stA);
  ST(dal_picture_write(F.A, F.stA, ts, 2, NULL, NULL), DAL_E_ARG, F.stA);
  CHECK(ftell(fp) == 0);
  fclose(fp);
  st_intact();
}

#define ROW(f)                                                                                     \
  { #f, sw_##f }
static const sweep_row rows[] = {
    ROW(dal_default_expr_def),
    ROW(dal_expr_create),
    ROW(dal_expr_destroy),
    ROW(dal_expr_nout),
    ROW(dal_expr_nin),
    ROW(dal_expr_nparam),
    ROW(dal_expr_symbol),
    ROW(dal_expr_values),
    ROW(dal_expr_depends),
    ROW(dal_expr_ninstructions),
    ROW(dal_expr_eval),
    ROW(dal_expr_check),
    ROW(dal_expr_primitive),
    ROW(dal_expr_place_def),
    ROW(dal_expr_constraint_def),
    ROW(dal_expr_map),
    ROW(dal_expr_potential_r),
    ROW(dal_expr_potential_q),
    ROW(dal_expr_lagrangian),
    ROW(dal_expr_path),
    ROW(dal_expr_time),
    ROW(dal_expr_event),
    ROW(dal_expr_print),
    ROW(dal_expr_derivative),
    ROW(dal_default_expr_model_def),
    ROW(dal_expr_model_energies),
    ROW(dal_expr_lagrange),
    ROW(dal_expr_equations_destroy),
    ROW(dal_scene_parse),
    ROW(dal_scene_read),
    ROW(dal_scene_destroy),
    ROW(dal_scene_write),
    ROW(dal_scene_set_param),
    ROW(dal_scene_system),
    ROW(dal_scene_opts),
    ROW(dal_scene_state),
    ROW(dal_scene_run),
    ROW(dal_scene_show),
    ROW(dal_scene_native),
    ROW(dal_scene_help),
    ROW(dal_scene_nexprs),
    ROW(dal_scene_expr),
    ROW(dal_scene_write_c),
    ROW(dal_codegen_default_opts),
    ROW(dal_codegen_write),
    ROW(dal_codegen_attach),
    ROW(dal_codegen_attached),
    ROW(dal_codegen_attach_eom),
    ROW(dal_codegen_eom_attached),
    ROW(dal_scene_events),
    ROW(dal_scene_event_is_section),
    ROW(dal_scene_strobe),
    ROW(dal_scene_run_events),
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
    ROW(dal_default_solve_opts),
    ROW(dal_method_name),
    ROW(dal_formulation_name),
    ROW(dal_state_stats),
    ROW(dal_advance),
    ROW(dal_evolve),
    ROW(dal_evolve_at),
    ROW(dal_csv_monitor),
    ROW(dal_columns_create),
    ROW(dal_columns_destroy),
    ROW(dal_columns_count),
    ROW(dal_columns_name),
    ROW(dal_columns_need_work),
    ROW(dal_columns_eval),
    ROW(dal_columns_write_header),
    ROW(dal_default_view_opts),
    ROW(dal_view_write),
    ROW(dal_picture_write),
    ROW(dal_trajectory_create),
    ROW(dal_trajectory_destroy),
    ROW(dal_state_set_trajectory),
    ROW(dal_trajectory_eval),
    ROW(dal_trajectory_span),
    ROW(dal_trajectory_errmsg),
    ROW(dal_default_event_def),
    ROW(dal_events_create),
    ROW(dal_events_destroy),
    ROW(dal_events_add),
    ROW(dal_events_errmsg),
    ROW(dal_events_size),
    ROW(dal_events_name),
    ROW(dal_state_set_events),
    ROW(dal_events_count),
    ROW(dal_events_get),
    ROW(dal_events_clear),
    ROW(dal_events_write_csv),
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
    ROW(dal_joint_forces),
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
    ROW(dal_builder_set_map),
    ROW(dal_builder_set_lagrangian),
    ROW(dal_builder_set_gravity),
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
    ROW(dal_default_sweep_opts),
    ROW(dal_sweep_part_of),
    ROW(dal_sweep_run),
    ROW(dal_sweep_grid),
    ROW(dal_sweep_write_csv),
    ROW(dal_param_find),
    ROW(dal_param_check),
    ROW(dal_param_name),
    ROW(dal_system_param),
    ROW(dal_state_param),
    ROW(dal_state_set_param),
    ROW(dal_state_set_param_named),
    ROW(dal_state_set_mass),
    ROW(dal_state_set_gravity),
    ROW(dal_state_reset_params),
    ROW(dal_state_copy_params),
    ROW(dal_default_verify_opts),
    ROW(dal_verify_primitive),
    ROW(dal_verify_map),
    ROW(dal_verify_potential_r),
    ROW(dal_verify_potential_q),
    ROW(dal_verify_lagrangian),
    ROW(dal_verify_model),
    ROW(dal_state_print),
    ROW(dal_state_init_report),
    ROW(dal_linearize),
    ROW(dal_linearize_full),
    ROW(dal_linearize_inputs),
    ROW(dal_state_transition),
    ROW(dal_vector_field_jacobian),
    ROW(dal_stability_name),
    ROW(dal_time_dependence),
    ROW(dal_normal_modes_frozen),
    ROW(dal_floquet),
    ROW(dal_floquet_verdict_name),
    ROW(dal_default_orbit_opts),
    ROW(dal_periodic_orbit),
    ROW(dal_relative_equilibrium),
    ROW(dal_default_orbit_continuation_opts),
    ROW(dal_orbit_continue),
    ROW(dal_normal_modes),
    ROW(dal_default_equilibrium_opts),
    ROW(dal_equilibrium),
    ROW(dal_default_continuation_opts),
    ROW(dal_continue),
    ROW(dal_default_lyapunov_opts),
    ROW(dal_lyapunov),
    ROW(dal_default_place_def),
    ROW(dal_place_def_set),
    ROW(dal_constraint_def_set),
    ROW(dal_default_constraint_def),
    ROW(dal_default_spring_def),
    ROW(dal_default_damper_def),
    ROW(dal_builder_place_def),
    ROW(dal_builder_add_constraint_def),
    ROW(dal_builder_add_spring_def),
    ROW(dal_builder_add_damper_def),
    ROW(dal_builder_set_dynamics),
    ROW(dal_system_dynamics),
    ROW(dal_system_print),
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

// the public functions of every header in dir; -1 when the directory cannot be read
typedef struct api_names {
  char (*names)[64];
  int n;
} api_names;
static void scan_one(char *text, const char *name, void *ctx) {
  api_names *a = ctx;
  // mpi.h declares dal_sweep_run_mpi of the separate library dalembert_mpi, which this test
  // does not link (and <mpi.h> is not on its include path): tests/test_ensemble_mpi.c covers it
  if (strcmp(name, "mpi.h") != 0) a->n = scan_header(text, a->names, a->n);
}
static int scan_headers(const char *dir, char names[][64]) {
  api_names a = {names, 0};
  return for_each_header(dir, scan_one, &a) > 0 ? a.n : -1;
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
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_cartesian2;
  pd.coords = c;
  pd.ncoords = 2;
  CHECK_OK(dal_builder_place_def(F.bld, 0, &pd));
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
