// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Reliability, second pass (issue 16): one row per defect an outside audit found, each with
// the exact status, the culprit the message must name (and words it must not contain), and
// checks that the state holds its last good values. Every row failed before its fix.
//
// References: closed forms (free flight x = x0 + v t, rest tension m g, a^n by libm's pow),
// a second formulation or method of the same scene (the index-1 ODE against IDA, DOPRI5
// against RK4), and counts that bound the work (a zero-progress loop took 1e6 steps).
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"

#define MSG_LEN 512

typedef struct rel_row {
  const char *name;
  int expect;          // the exact status
  const char *culprit; // substrings the message must contain (NULL: none)
  const char *culprit2;
  const char *never; // a substring the message must not contain (a wrong culprit; NULL: none)
  int (*run)(char *msg);
} rel_row;

static void copy_msg(char *msg, const char *s) { snprintf(msg, MSG_LEN, "%s", s ? s : ""); }

// ---------------------------------------------------------------- scenes
static const double g2[2] = {0.0, -9.81}, g3[3] = {0.0, 0.0, -9.81};

typedef struct scene {
  dal_builder *b;
  dal_system *sys;
  dal_state *st;
} scene;

static void scene_free(scene *s) {
  dal_state_destroy(s->st);
  dal_system_destroy(s->sys);
  dal_builder_destroy(s->b);
  memset(s, 0, sizeof *s);
}

// finish a scene: compile, create the state, set it
static int scene_finish(scene *s, double t, const double *q, const double *qd) {
  int rc = dal_builder_compile(s->b, &s->sys);
  if (!rc) rc = dal_state_create(s->sys, &s->st);
  if (!rc) rc = dal_state_set(s->sys, s->st, t, q, qd);
  return rc;
}

// 'bob' (mass m) free in the plane, coordinates 'x', 'y'
static int free2(scene *s, double m, int gravity) {
  int c[2], bob;
  memset(s, 0, sizeof *s);
  int rc = dal_builder_create(2, &s->b);
  if (!rc) rc = dal_builder_add_coord(s->b, "x", &c[0]);
  if (!rc) rc = dal_builder_add_coord(s->b, "y", &c[1]);
  if (!rc) rc = dal_builder_add_particle(s->b, "bob", m, &bob);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_cartesian2;
  pd.coords = c;
  pd.ncoords = 2;
  if (!rc) rc = dal_builder_place_def(s->b, bob, &pd);
  if (!rc && gravity) rc = dal_builder_set_gravity(s->b, g2);
  return rc;
}

// the planar pendulum 'bob' (1 kg, 1 m) on coordinate 'theta'
static int pendulum(scene *s, double th) {
  int c, bob;
  double qd = 0.0;
  memset(s, 0, sizeof *s);
  int rc = dal_builder_create(2, &s->b);
  if (!rc) rc = dal_builder_add_coord(s->b, "theta", &c);
  if (!rc) rc = dal_builder_add_particle(s->b, "bob", 1.0, &bob);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_pendulum;
  pd.coords = &c;
  pd.ncoords = 1;
  pd.param[DAL_PENDULUM_L] = 1.0;
  if (!rc) rc = dal_builder_place_def(s->b, bob, &pd);
  if (!rc) rc = dal_builder_set_gravity(s->b, g2);
  if (!rc) rc = scene_finish(s, 0.0, &th, &qd);
  return rc;
}

// the Cartesian pendulum: 'bob' (2 kg) at (x, y) on the rod 'rod' of 1 m from the origin
static int cart_pendulum(scene *s, double th, dal_force_fn *force, void *fctx) {
  double q[2] = {sin(th), -cos(th)}, qd[2] = {0.0, 0.0};
  int rc = free2(s, 2.0, 1), bob = 0;
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = "rod";
  cd.prim = &dal_con_anchor2;
  cd.parts = &bob;
  cd.nparts = 1;
  cd.param[DAL_ANCHOR_L] = 1.0;
  if (!rc) rc = dal_builder_add_constraint_def(s->b, &cd, NULL);
  if (!rc && force) rc = dal_builder_add_force(s->b, force, fctx);
  if (!rc) rc = scene_finish(s, 0.0, q, qd);
  return rc;
}

static dal_solve_opts opts_for(dal_method m) {
  dal_solve_opts o = dal_default_solve_opts();
  o.method = m;
  return o;
}

static long steps_of(const dal_state *st) {
  dal_stats s;
  CHECK_OK(dal_state_stats(st, &s));
  return s.steps;
}

static long evals_of(const dal_state *st) {
  dal_stats s;
  CHECK_OK(dal_state_stats(st, &s));
  return s.rhs_evals;
}

// ---------------------------------------------------------------- 1. csv monitor
// the state of a smaller system handed to dal_csv_monitor with a larger one: refused by name
// (it read past the state's arrays and wrote garbage with DAL_OK), nothing written
static int row_csv_foreign(char *msg) {
  scene small, big;
  CHECK_OK(pendulum(&small, 0.3));
  double q[2] = {0.1, 0.2}, qd[2] = {0.0, 0.0};
  CHECK_OK(free2(&big, 1.0, 1));
  CHECK_OK(scene_finish(&big, 0.0, q, qd));
  CHECK_OK(dal_forward(small.sys, small.st));
  FILE *fp = tmpfile();
  CHECK(fp != NULL);
  dal_csv csv = {fp, 0, 0};
  int rc = dal_csv_monitor(big.sys, small.st, &csv);
  copy_msg(msg, dal_state_errmsg(small.st));
  CHECK(ftell(fp) == 0 && csv.header_done == 0);
  // its own system: a header and one row (t, theta, theta_dot, E, h)
  CHECK_OK(dal_csv_monitor(small.sys, small.st, &csv));
  rewind(fp);
  char line[256];
  CHECK(fgets(line, sizeof line, fp) && strcmp(line, "t,theta,theta_dot,E,h\n") == 0);
  double t, th, thd, E, h;
  CHECK(fscanf(fp, "%lf,%lf,%lf,%lf,%lf", &t, &th, &thd, &E, &h) == 5);
  CHECK(t == 0.0 && th == 0.3 && thd == 0.0);
  CHECK_CLOSE(E, -9.81 * cos(0.3), 1e-14); // U = m g y, y = -cos theta, at rest
  fclose(fp);
  scene_free(&small);
  scene_free(&big);
  return rc;
}

// a state never evaluated has no energies: the monitor refuses instead of writing stale ones
static int row_csv_unevaluated(char *msg) {
  scene s;
  CHECK_OK(pendulum(&s, 0.3));
  FILE *fp = tmpfile();
  dal_csv csv = {fp, 0, 0};
  int rc = dal_csv_monitor(s.sys, s.st, &csv);
  copy_msg(msg, dal_state_errmsg(s.st));
  CHECK(ftell(fp) == 0);
  // through dal_evolve every row is evaluated: 11 rows for t = 0, 0.1, ..., 1
  dal_solve_opts o = opts_for(DAL_METHOD_DOPRI5);
  CHECK_OK(dal_evolve(s.sys, s.st, &o, 1.0, 0.1, dal_csv_monitor, &csv));
  rewind(fp);
  int lines = 0;
  for (int ch; (ch = fgetc(fp)) != EOF;)
    lines += ch == '\n';
  CHECK(lines == 12);
  fclose(fp);
  scene_free(&s);
  return rc;
}

// ---------------------------------------------------------------- 2. RK4 overflow
// x'' = 0 from x = 0 at v = 1e308: each RK4 stage is finite and so is the solution
// x = v t (1e306 at t = 0.01), but the sum k1 + 2 k2 + 2 k3 + k4 overflowed and the step
// was accepted with x = inf
static int row_rk4_stage_sum(char *msg) {
  scene s;
  double q[2] = {0.0, 0.0}, qd[2] = {1e308, 0.0};
  CHECK_OK(free2(&s, 1.0, 0));
  CHECK_OK(scene_finish(&s, 0.0, q, qd));
  dal_solve_opts o = opts_for(DAL_METHOD_RK4);
  o.fixed_step = 1e-3;
  int rc = dal_advance(s.sys, s.st, &o, 0.01);
  copy_msg(msg, dal_state_errmsg(s.st));
  CHECK(dal_state_time(s.st) == 0.01);
  CHECK_CLOSE(dal_state_q(s.st)[0] / 1e306, 1.0, 1e-13);
  CHECK(dal_state_qdot(s.st)[0] == 1e308);
  scene_free(&s);
  return rc;
}

// x = 1.7e308 + 1e308 t leaves double range at t = 0.0797...: RK4 stops with the state at
// its last accepted step, finite and on the trajectory, naming the coordinate
static int row_rk4_overflow(char *msg) {
  scene s;
  double q[2] = {1.7e308, 0.0}, qd[2] = {1e308, 0.0};
  CHECK_OK(free2(&s, 1.0, 0));
  CHECK_OK(scene_finish(&s, 0.0, q, qd));
  dal_solve_opts o = opts_for(DAL_METHOD_RK4);
  o.fixed_step = 1e-3;
  int rc = dal_advance(s.sys, s.st, &o, 1.0);
  copy_msg(msg, dal_state_errmsg(s.st));
  double t = dal_state_time(s.st), x = dal_state_q(s.st)[0];
  double tmax = (DBL_MAX - 1.7e308) / 1e308;
  CHECK_MSG(t > tmax - 2e-3 && t <= tmax, "stopped at t=%.17g (overflow at %.17g)", t, tmax);
  CHECK(isfinite(x) && isfinite(dal_state_qdot(s.st)[0]));
  CHECK_CLOSE(x / 1e308, 1.7 + t, 1e-13);
  CHECK(evals_of(s.st) < 2000);
  scene_free(&s);
  return rc;
}

// ---------------------------------------------------------------- 3. dal_powi(x, INT_MIN)
// -INT_MIN overflowed (undefined behaviour; in practice a^INT_MIN came out as 1/a)
static int row_powi_int_min(char *msg) {
  const double as[] = {2.0, -1.0, 1.0, 1.0 + 1e-9, 0.5, -0.999999999};
  int n = INT_MIN;
  for (size_t i = 0; i < sizeof as / sizeof as[0]; ++i) {
    double a = as[i], ref = pow(a, (double)n);
    dal_jet r = dal_powi(dal_var(a, 1.0), n);
    CHECK_MSG(r.v == ref || fabs(r.v - ref) <= 1e-6 * fabs(ref), "a=%g: %g vs pow %g", a, r.v, ref);
    // the derivative n a^(n-1) (both underflow or overflow together)
    double dref = (double)n * pow(a, (double)n - 1.0);
    CHECK_MSG(r.d == dref || fabs(r.d - dref) <= 1e-6 * fabs(dref), "a=%g: d %g vs %g", a, r.d,
              dref);
  }
  // INT_MAX and INT_MIN + 1 on |a| = 1 (exact)
  CHECK(dal_powi(dal_const(-1.0), INT_MAX).v == -1.0);
  CHECK(dal_powi(dal_const(-1.0), INT_MIN + 1).v == -1.0);
  copy_msg(msg, "");
  return DAL_OK;
}

// ---------------------------------------------------------------- 4. OK with NaN or stale
// before any evaluation, after dal_state_set and after a failed evaluation nothing hands out
// values: the status calls say DAL_E_STATE by name, the accessors give NULL
static int row_unevaluated_products(char *msg) {
  scene s;
  CHECK_OK(cart_pendulum(&s, 0.0, NULL, NULL));
  double F[2] = {7, 7}, Qc[2] = {7, 7}, J[4];
  dal_energies en;
  int rc = dal_constraint_forces(s.sys, s.st, F);
  copy_msg(msg, dal_state_errmsg(s.st));
  CHECK(dal_constraint_genforces(s.sys, s.st, Qc) == DAL_E_STATE);
  CHECK(strstr(dal_state_errmsg(s.st), "constraint_genforces") != NULL);
  CHECK(dal_state_jacobian(s.sys, s.st, 0, J) == DAL_E_STATE);
  CHECK(strstr(dal_state_errmsg(s.st), "state_jacobian") != NULL);
  CHECK(dal_state_energies(s.st, &en) == DAL_E_STATE);
  CHECK(dal_state_qddot(s.st) == NULL && dal_state_positions(s.st) == NULL);
  CHECK(dal_state_lambda(s.st) == NULL && dal_state_phi(s.st) == NULL);
  CHECK(dal_state_mass_matrix(s.st) == NULL && dal_state_reactions(s.st) == NULL);
  CHECK(dal_state_q(s.st) != NULL && dal_state_qdot(s.st) != NULL);
  // evaluated: the bob hangs at rest, the rod holds it with m g = 19.62 N upwards
  CHECK_OK(dal_forward(s.sys, s.st));
  CHECK_OK(dal_constraint_forces(s.sys, s.st, F));
  CHECK_CLOSE(F[0], 0.0, 1e-13);
  CHECK_CLOSE(F[1], 2.0 * 9.81, 1e-13);
  CHECK_OK(dal_constraint_genforces(s.sys, s.st, Qc)); // Cartesian: G' lambda is the force
  CHECK(Qc[0] == F[0] && Qc[1] == F[1]);
  CHECK_OK(dal_state_jacobian(s.sys, s.st, 0, J));
  CHECK(J[0] == 1.0 && J[1] == 0.0 && J[2] == 0.0 && J[3] == 1.0);
  CHECK_OK(dal_state_energies(s.st, &en));
  CHECK_CLOSE(en.E, -2.0 * 9.81, 1e-13);
  CHECK(dal_state_qddot(s.st) != NULL && dal_state_mass_matrix(s.st) != NULL);
  // moved: the products of the old point are stale, not handed out
  double q[2] = {0.6, -0.8}, qd[2] = {0.0, 0.0};
  CHECK_OK(dal_state_set(s.sys, s.st, 0.0, q, qd));
  CHECK(dal_constraint_forces(s.sys, s.st, F) == DAL_E_STATE);
  CHECK(dal_state_energies(s.st, &en) == DAL_E_STATE);
  CHECK(dal_state_qddot(s.st) == NULL && dal_state_accelerations(s.st) == NULL);
  scene_free(&s);
  return rc;
}

// a failed evaluation (the spherical pendulum at its pole) leaves no products either
static int row_failed_evaluation(char *msg) {
  scene s;
  int c[2], bob;
  double q[2] = {0.5, 0.3}, qd[2] = {1.0, 0.0};
  memset(&s, 0, sizeof s);
  CHECK_OK(dal_builder_create(3, &s.b));
  CHECK_OK(dal_builder_add_coord(s.b, "theta", &c[0]));
  CHECK_OK(dal_builder_add_coord(s.b, "phi", &c[1]));
  CHECK_OK(dal_builder_add_particle(s.b, "bob", 1.0, &bob));
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_spherical;
  pd.coords = c;
  pd.ncoords = 2;
  pd.param[DAL_SPHERICAL_L] = 1.0;
  CHECK_OK(dal_builder_place_def(s.b, bob, &pd));
  CHECK_OK(dal_builder_set_gravity(s.b, g3));
  CHECK_OK(scene_finish(&s, 0.0, q, qd));
  CHECK_OK(dal_forward(s.sys, s.st));
  CHECK(dal_state_qddot(s.st) != NULL);
  q[0] = 0.0;
  CHECK_OK(dal_state_set(s.sys, s.st, 0.0, q, qd));
  CHECK(dal_forward(s.sys, s.st) == DAL_E_SINGULAR);
  dal_energies en;
  // the energies come before the solve and are current: T = 1/2 theta'^2 (l = 1, m = 1),
  // U = m g z = -9.81 at the pole
  int rc = dal_state_energies(s.st, &en);
  CHECK(rc == DAL_OK);
  CHECK_CLOSE(en.E, 0.5 - 9.81, 1e-14);
  CHECK(dal_state_qddot(s.st) == NULL && dal_state_accelerations(s.st) == NULL);
  rc = dal_forward(s.sys, s.st);
  copy_msg(msg, dal_state_errmsg(s.st));
  scene_free(&s);
  return rc;
}

// ---------------------------------------------------------------- 5. inexact parameters
// a subnormal mass gave an acceleration 6% wrong with DAL_OK; 1e-300 is exact
static int row_subnormal_mass(char *msg) {
  scene s;
  int rc = free2(&s, 4.9e-324, 1);
  copy_msg(msg, dal_builder_errmsg(s.b));
  scene_free(&s);
  double q[2] = {0.0, 0.0}, qd[2] = {0.0, 0.0};
  CHECK_OK(free2(&s, 1e-300, 1));
  CHECK_OK(scene_finish(&s, 0.0, q, qd));
  CHECK_OK(dal_forward(s.sys, s.st));
  CHECK_CLOSE(dal_state_qddot(s.st)[1], -9.81, 1e-15);
  scene_free(&s);
  return rc;
}

// the same class: every real input of the builder that multiplies (stiffness, primitive
// parameter, gravity, anchor) is refused when subnormal, naming it
static int row_subnormal_inputs(char *msg) {
  scene s;
  int bob = 0, rc0;
  CHECK_OK(free2(&s, 1.0, 0));
  dal_spring_def sd = dal_default_spring_def();
  sd.a = bob;
  memcpy(sd.anchor, g2, sizeof g2);
  sd.k = 1e-310;
  sd.length = 1.0;
  rc0 = dal_builder_add_spring_def(s.b, &sd);
  copy_msg(msg, dal_builder_errmsg(s.b));
  double gs[2] = {0.0, -1e-310};
  CHECK(dal_builder_set_gravity(s.b, gs) == DAL_E_ARG);
  CHECK(strstr(dal_builder_errmsg(s.b), "gravity component 1") != NULL);
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = "rod";
  cd.prim = &dal_con_anchor2;
  cd.parts = &bob;
  cd.nparts = 1;
  cd.param[DAL_ANCHOR_L] = 1.0;
  cd.param[DAL_ANCHOR_X0] = 2e-320;
  CHECK(dal_builder_add_constraint_def(s.b, &cd, NULL) == DAL_E_ARG);
  CHECK(strstr(dal_builder_errmsg(s.b), "index 1") != NULL);
  dal_damper_def dd = dal_default_damper_def();
  dd.a = bob;
  memcpy(dd.anchor, g2, sizeof g2);
  dd.c = 1e-320;
  CHECK(dal_builder_add_damper_def(s.b, &dd) == DAL_E_ARG);
  CHECK(strstr(dal_builder_errmsg(s.b), "subnormal") != NULL);
  const double x0[2] = {1e-315, 0.0};
  dd = dal_default_damper_def();
  dd.a = bob;
  memcpy(dd.anchor, x0, sizeof x0);
  dd.c = 1.0;
  CHECK(dal_builder_add_damper_def(s.b, &dd) == DAL_E_ARG);
  CHECK(strstr(dal_builder_errmsg(s.b), "anchor component 0") != NULL);
  // normal values pass, and the model runs
  sd = dal_default_spring_def();
  sd.a = bob;
  memcpy(sd.anchor, g2, sizeof g2);
  sd.k = 1e-300;
  sd.length = 1.0;
  CHECK_OK(dal_builder_add_spring_def(s.b, &sd));
  CHECK(dal_builder_errmsg(s.b)[0] == 0);
  scene_free(&s);
  return rc0;
}

// ---------------------------------------------------------------- 6. zero progress
// Bulirsch-Stoer with a collapsed first-step estimate (velocity 1e150 on a coordinate at 0,
// atol 1e-300) took 1e6 zero-length steps and reported "raise max_steps"
static int row_bs_zero_steps(char *msg) {
  scene s;
  double q[2] = {0.0, 0.0}, qd[2] = {1e150, 0.0};
  CHECK_OK(free2(&s, 1.0, 1));
  CHECK_OK(scene_finish(&s, 0.0, q, qd));
  dal_solve_opts o = opts_for(DAL_METHOD_BS);
  o.rtol = 1e-15;
  o.atol = 1e-300;
  int rc = dal_advance(s.sys, s.st, &o, 1.0);
  copy_msg(msg, dal_state_errmsg(s.st));
  CHECK(dal_state_time(s.st) == 0.0 && dal_state_qdot(s.st)[0] == 1e150);
  CHECK(steps_of(s.st) == 0 && evals_of(s.st) < 100);
  scene_free(&s);
  return rc;
}

// RK4 at a fixed step below the resolution of t (1e-20 at t = 1): refused at once, as hmax is
static int rk4_unresolvable(char *msg, double t0, double h) {
  scene s;
  double q[2] = {0.0, 0.0}, qd[2] = {1.0, 0.0};
  CHECK_OK(free2(&s, 1.0, 1));
  CHECK_OK(scene_finish(&s, t0, q, qd));
  dal_solve_opts o = opts_for(DAL_METHOD_RK4);
  o.fixed_step = h;
  int rc = dal_advance(s.sys, s.st, &o, t0 == 1.0 ? 2.0 : 1.5e308);
  copy_msg(msg, dal_state_errmsg(s.st));
  CHECK(dal_state_time(s.st) == t0 && evals_of(s.st) == 0);
  scene_free(&s);
  return rc;
}
static int row_rk4_step_below_resolution(char *msg) { return rk4_unresolvable(msg, 1.0, 1e-20); }
static int row_rk4_at_1e308(char *msg) { return rk4_unresolvable(msg, 1e308, 1e-3); }

// a force callback that returns > 0 from t = t_fail on, forever
typedef struct gate {
  double t_fail;
  long calls;
} gate;

static int force_gate(double t, const double *r, const double *v, double *F, void *ctx) {
  gate *g = ctx;
  (void)r;
  (void)v;
  (void)F;
  g->calls++;
  return t >= g->t_fail ? 1 : 0;
}

// RK4 halving below the resolution of t (t near 1e8) in front of such a callback: it took
// zero-length steps; now the callback is named at once
static int row_rk4_halving_stall(char *msg) {
  scene s;
  gate g = {1e8 + 0.5, 0};
  double q[2] = {0.0, 0.0}, qd[2] = {1.0, 0.0};
  CHECK_OK(free2(&s, 1.0, 1));
  CHECK_OK(dal_builder_add_force(s.b, force_gate, &g));
  CHECK_OK(scene_finish(&s, 1e8, q, qd));
  dal_solve_opts o = opts_for(DAL_METHOD_RK4);
  int rc = dal_advance(s.sys, s.st, &o, 1e8 + 2.0);
  copy_msg(msg, dal_state_errmsg(s.st));
  double t = dal_state_time(s.st);
  CHECK(t > 1e8 + 0.49 && t < 1e8 + 0.5);
  CHECK(g.calls < 5000);
  scene_free(&s);
  return rc;
}

// IDA crept towards t = 0.5 for 1e6 steps (8 million residuals) where the callback returns
// > 0 forever; the ODE forms stopped at once with DAL_E_CALLBACK, and so does IDA now
static int row_ida_callback_forever(char *msg) {
  scene s;
  gate g = {0.5, 0};
  CHECK_OK(cart_pendulum(&s, 0.5, force_gate, &g));
  dal_solve_opts o = opts_for(DAL_METHOD_AUTO); // GGL in IDA
  int rc = dal_advance(s.sys, s.st, &o, 2.0);
  copy_msg(msg, dal_state_errmsg(s.st));
  double t = dal_state_time(s.st), x = dal_state_q(s.st)[0], y = dal_state_q(s.st)[1];
  CHECK(t > 0.49 && t < 0.5);
  CHECK_CLOSE(hypot(x, y), 1.0, 1e-8);
  CHECK(steps_of(s.st) < 2000 && g.calls < 20000);
  // the index-1 ODE form of the same scene stops with the same status
  double q[2] = {sin(0.5), -cos(0.5)}, qd[2] = {0.0, 0.0};
  CHECK_OK(dal_state_set(s.sys, s.st, 0.0, q, qd));
  o.form = DAL_FORM_INDEX1;
  o.method = DAL_METHOD_DOPRI5;
  CHECK(dal_advance(s.sys, s.st, &o, 2.0) == rc);
  scene_free(&s);
  return rc;
}

// a particle held on the unit circle and on the line y = t: no position satisfies both
// after t = 1 (the line leaves the circle), where the gradients become parallel. IDA crept
// towards t = 1 for 1e6 steps (14 million residuals); it now stops at once with the status
// the index-1 ODE form gives (a step size collapse)
static int lift(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)p;
  (void)ctx;
  out[0] = dal_sub(in[1], t);
  return 0;
}
static const dal_primitive prim_lift = {.name = "lift",
                                        .version = 1,
                                        .nin = 2,
                                        .nout = 1,
                                        .nparam = 0,
                                        .eval = lift,
                                        .doc = "y - t",
                                        .flags = 0};

static int row_ida_unsatisfiable(char *msg) {
  scene s;
  double q[2] = {1.0, 0.0}, qd[2] = {0.0, 1.0};
  int bob = 0;
  CHECK_OK(free2(&s, 1.0, 0));
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = "circle";
  cd.prim = &dal_con_circle2;
  cd.parts = &bob;
  cd.nparts = 1;
  cd.param[DAL_CIRCLE_R] = 1.0;
  CHECK_OK(dal_builder_add_constraint_def(s.b, &cd, NULL));
  cd = dal_default_constraint_def();
  cd.name = "lift";
  cd.prim = &prim_lift;
  cd.parts = &bob;
  cd.nparts = 1;
  CHECK_OK(dal_builder_add_constraint_def(s.b, &cd, NULL));
  CHECK_OK(scene_finish(&s, 0.0, q, qd));
  dal_solve_opts o = opts_for(DAL_METHOD_AUTO);
  int rc = dal_advance(s.sys, s.st, &o, 2.0);
  copy_msg(msg, dal_state_errmsg(s.st));
  double t = dal_state_time(s.st), x = dal_state_q(s.st)[0], y = dal_state_q(s.st)[1];
  CHECK_MSG(t > 1.0 - 1e-5 && t < 1.0, "t = %.17g", t);
  CHECK_CLOSE(y, t, 1e-8); // on the exact motion (x, y) = (sqrt(1 - t^2), t)
  CHECK_CLOSE(x, sqrt(1.0 - t * t), 1e-4);
  // (IDA at its calibrated tolerance: 12934 steps measured; the creep it replaces took 1e6)
  CHECK_MSG(steps_of(s.st) < 30000, "%ld steps", steps_of(s.st));
  CHECK_OK(dal_state_set(s.sys, s.st, 0.0, q, qd));
  o.form = DAL_FORM_INDEX1;
  o.method = DAL_METHOD_DOPRI5;
  CHECK(dal_advance(s.sys, s.st, &o, 2.0) == rc);
  scene_free(&s);
  return rc;
}

// ---------------------------------------------------------------- 7. wrong culprits
// a whole-system map (u, w) -> (sin u, w) with velocities 1e300: the curvature term
// overflows. It was "the map produced a non-finite value at t=-nan" (the integrators had
// evaluated it at t = NaN); it is an overflow of the motion, for every method
static int umap(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx) {
  (void)t;
  (void)ctx;
  r[0] = dal_sin(q[0]);
  r[1] = q[1];
  return 0;
}

static int row_huge_velocity_map(char *msg) {
  int rc0 = 0;
  for (int m = DAL_METHOD_DOPRI5; m <= DAL_METHOD_BDF; ++m) {
    scene s;
    int c[2], bob;
    double q[2] = {0.1, 0.0}, qd[2] = {1e300, 1e300};
    memset(&s, 0, sizeof s);
    CHECK_OK(dal_builder_create(2, &s.b));
    CHECK_OK(dal_builder_add_coord(s.b, "u", &c[0]));
    CHECK_OK(dal_builder_add_coord(s.b, "w", &c[1]));
    CHECK_OK(dal_builder_add_particle(s.b, "bob", 1.0, &bob));
    CHECK_OK(dal_builder_set_map(s.b, umap, NULL));
    CHECK_OK(scene_finish(&s, 0.0, q, qd));
    dal_solve_opts o = opts_for((dal_method)m);
    int rc = dal_advance(s.sys, s.st, &o, 1.0);
    if (m == DAL_METHOD_DOPRI5) {
      rc0 = rc;
      copy_msg(msg, dal_state_errmsg(s.st));
    }
    CHECK_MSG(rc == rc0, "%s: %s: %s", dal_method_name((dal_method)m), dal_status_name(rc),
              dal_state_errmsg(s.st));
    CHECK(strstr(dal_state_errmsg(s.st), "nan") == NULL);
    CHECK(dal_state_time(s.st) == 0.0 && dal_state_qdot(s.st)[0] == 1e300);
    scene_free(&s);
  }
  return rc0;
}

// the same velocities on a placed particle (the identity map): the step-size control
// collapses; no method evaluates the model at t = NaN or blames the map
static int row_huge_velocity_placed(char *msg) {
  int rc0 = 0;
  for (int m = DAL_METHOD_DOPRI5; m <= DAL_METHOD_ADAMS; ++m) {
    scene s;
    double q[2] = {0.0, 0.0}, qd[2] = {1e300, 1e300};
    CHECK_OK(free2(&s, 1.0, 1));
    CHECK_OK(scene_finish(&s, 0.0, q, qd));
    dal_solve_opts o = opts_for((dal_method)m);
    int rc = dal_advance(s.sys, s.st, &o, 1.0);
    if (m == DAL_METHOD_DOPRI5) {
      rc0 = rc;
      copy_msg(msg, dal_state_errmsg(s.st));
    }
    if (m != DAL_METHOD_RK4) { // RK4 has no error control: it integrates x = 1e300 t
      CHECK_MSG(rc == rc0, "%s: %s: %s", dal_method_name((dal_method)m), dal_status_name(rc),
                dal_state_errmsg(s.st));
    } else {
      CHECK_MSG(rc == DAL_OK, "rk4: %s: %s", dal_status_name(rc), dal_state_errmsg(s.st));
      CHECK_CLOSE(dal_state_q(s.st)[0] / 1e300, 1.0, 1e-12);
    }
    CHECK(strstr(dal_state_errmsg(s.st), "nan") == NULL);
    CHECK(strstr(dal_state_errmsg(s.st), "domain") == NULL);
    scene_free(&s);
  }
  return rc0;
}

// a spring that overflows, in a scene without force callbacks: the spring is named
static int row_spring_overflow(char *msg) {
  scene s;
  int c[4], a, b;
  double q[4] = {0.0, 0.0, 1e10, 0.0}, qd[4] = {0.0, 0.0, 0.0, 0.0};
  memset(&s, 0, sizeof s);
  CHECK_OK(dal_builder_create(2, &s.b));
  for (int i = 0; i < 4; ++i)
    CHECK_OK(dal_builder_add_coord(s.b, NULL, &c[i]));
  CHECK_OK(dal_builder_add_particle(s.b, "a", 1.0, &a));
  CHECK_OK(dal_builder_add_particle(s.b, "b", 1.0, &b));
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_cartesian2;
  pd.coords = c;
  pd.ncoords = 2;
  CHECK_OK(dal_builder_place_def(s.b, a, &pd));
  pd.coords = c + 2;
  CHECK_OK(dal_builder_place_def(s.b, b, &pd));
  dal_spring_def sd = dal_default_spring_def();
  sd.a = a;
  sd.b = b;
  sd.k = 1e300;
  sd.length = 1.0;
  CHECK_OK(dal_builder_add_spring_def(s.b, &sd));
  CHECK_OK(scene_finish(&s, 0.0, q, qd));
  int rc = dal_forward(s.sys, s.st);
  copy_msg(msg, dal_state_errmsg(s.st));
  // a meter apart the same spring is fine: F = k (d - L) = 0 at its rest length
  q[2] = 1.0;
  CHECK_OK(dal_state_set(s.sys, s.st, 0.0, q, qd));
  CHECK_OK(dal_forward(s.sys, s.st));
  CHECK(dal_state_qddot(s.st)[0] == 0.0);
  scene_free(&s);
  return rc;
}

// Baumgarte rates of 1e300: beta^2 overflows, refused by name (it ran 1e6 steps or gave
// DAL_E_CALLBACK with no callback in the scene)
static int row_baumgarte_huge(char *msg) {
  scene s;
  CHECK_OK(cart_pendulum(&s, 0.5, NULL, NULL));
  dal_solve_opts o = opts_for(DAL_METHOD_DOPRI5);
  o.form = DAL_FORM_INDEX1;
  o.baumgarte_alpha = 1e300;
  o.baumgarte_beta = 1e300;
  int rc = dal_advance(s.sys, s.st, &o, 1.0);
  copy_msg(msg, dal_state_errmsg(s.st));
  CHECK(dal_state_time(s.st) == 0.0 && evals_of(s.st) == 0);
  // alpha alone of 1e300 is representable but stiffer than any explicit step: the run stops
  // early, naming an overflow, never a callback
  o.baumgarte_beta = 0.0;
  int rc2 = dal_advance(s.sys, s.st, &o, 1.0);
  CHECK_MSG(rc2 == DAL_E_NONFINITE || rc2 == DAL_E_STEP, "%s: %s", dal_status_name(rc2),
            dal_state_errmsg(s.st));
  CHECK(strstr(dal_state_errmsg(s.st), "callback") == NULL);
  CHECK_CLOSE(hypot(dal_state_q(s.st)[0], dal_state_q(s.st)[1]), 1.0, 1e-8);
  scene_free(&s);
  return rc;
}

// 'bob' of 1e-300 kg pushed by a force callback with 1e10 N (returning 0: it is fine): the
// acceleration 1e310 overflows. RK4 reported this as a callback failure ("fix the callback");
// every method now names the acceleration that overflows, with DAL_E_NONFINITE
static int force_push(double t, const double *r, const double *v, double *F, void *ctx) {
  (void)t;
  (void)r;
  (void)v;
  (void)ctx;
  F[0] += 1e10;
  return 0;
}

static int row_acceleration_overflow(char *msg) {
  int rc0 = 0;
  const dal_method ms[3] = {DAL_METHOD_RK4, DAL_METHOD_DOPRI5, DAL_METHOD_BS};
  for (int i = 0; i < 3; ++i) {
    scene s;
    double q[2] = {0.0, 0.0}, qd[2] = {0.0, 0.0};
    CHECK_OK(free2(&s, 1e-300, 0));
    CHECK_OK(dal_builder_add_force(s.b, force_push, NULL));
    CHECK_OK(scene_finish(&s, 0.0, q, qd));
    dal_solve_opts o = opts_for(ms[i]);
    int rc = dal_advance(s.sys, s.st, &o, 1.0);
    if (i == 0) {
      rc0 = rc;
      copy_msg(msg, dal_state_errmsg(s.st));
    }
    CHECK_MSG(rc == rc0, "%s: %s: %s", dal_method_name(ms[i]), dal_status_name(rc),
              dal_state_errmsg(s.st));
    CHECK(strstr(dal_state_errmsg(s.st), "fix the callback") == NULL);
    CHECK(dal_state_time(s.st) == 0.0 && dal_state_q(s.st)[0] == 0.0);
    scene_free(&s);
  }
  return rc0;
}

// ---------------------------------------------------------------- 8. one code per situation
static int user_prim_eval(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)p;
  (void)ctx;
  out[0] = in[0];
  return 0;
}

// a state of another system: DAL_E_STATE with a message from every (system, state) call
// (some gave DAL_E_ARG without one)
static int row_foreign_state_everywhere(char *msg) {
  scene a, b;
  CHECK_OK(pendulum(&a, 0.3));
  CHECK_OK(pendulum(&b, 0.3));
  CHECK_OK(dal_forward(a.sys, a.st));
  double J[2], F[2], Q[2], res[1];
  dal_solve_opts o = opts_for(DAL_METHOD_AUTO);
  dal_csv csv = {stdout, 1, 0};
  int rcs[9] = {
      dal_state_jacobian(b.sys, a.st, 0, J),
      dal_constraint_forces(b.sys, a.st, F),
      dal_constraint_genforces(b.sys, a.st, Q),
      dal_csv_monitor(b.sys, a.st, &csv),
      dal_forward(b.sys, a.st),
      dal_advance(b.sys, a.st, &o, 1.0),
      dal_make_consistent(b.sys, a.st, 0.0, NULL),
      dal_check_constraints(b.sys, a.st, NULL),
      dal_lagrange_residual(b.sys, a.st, NULL, 0.0, res, NULL),
  };
  for (int i = 0; i < 9; ++i)
    CHECK_MSG(rcs[i] == DAL_E_STATE, "call %d: %s", i, dal_status_name(rcs[i]));
  int rc = dal_state_jacobian(b.sys, a.st, 0, J);
  copy_msg(msg, dal_state_errmsg(a.st));
  scene_free(&a);
  scene_free(&b);
  return rc;
}

// NaN where a tolerance or interval is expected: DAL_E_NONFINITE as the README promises
static int row_nan_dt(char *msg) {
  scene s;
  CHECK_OK(pendulum(&s, 0.3));
  dal_solve_opts o = opts_for(DAL_METHOD_AUTO);
  int rc = dal_evolve(s.sys, s.st, &o, 1.0, NAN, NULL, NULL);
  copy_msg(msg, dal_state_errmsg(s.st));
  scene_free(&s);
  return rc;
}

static int row_nan_tolerance(char *msg) {
  scene s;
  CHECK_OK(cart_pendulum(&s, 0.3, NULL, NULL));
  int rc = dal_make_consistent(s.sys, s.st, NAN, NULL);
  copy_msg(msg, dal_state_errmsg(s.st));
  CHECK_OK(dal_make_consistent(s.sys, s.st, 0.0, NULL));
  scene_free(&s);
  return rc;
}

// a user primitive declaring nparam = -1 (or nin < 0) was accepted
static int row_malformed_primitive(char *msg) {
  scene s;
  int bob = 0, x = 0;
  const dal_primitive neg_param = {.name = "neg_param",
                                   .version = 1,
                                   .nin = 1,
                                   .nout = 1,
                                   .nparam = -1,
                                   .eval = user_prim_eval,
                                   .doc = "",
                                   .flags = 0};
  const dal_primitive neg_in = {.name = "neg_in",
                                .version = 1,
                                .nin = -1,
                                .nout = 1,
                                .nparam = 0,
                                .eval = user_prim_eval,
                                .doc = "",
                                .flags = 0};
  CHECK_OK(free2(&s, 1.0, 0));
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = "c";
  cd.prim = &neg_param;
  cd.coords = &x;
  cd.ncoords = 1;
  int rc = dal_builder_add_constraint_def(s.b, &cd, NULL);
  copy_msg(msg, dal_builder_errmsg(s.b));
  cd = dal_default_constraint_def();
  cd.name = "c";
  cd.prim = &neg_in;
  CHECK(dal_builder_add_constraint_def(s.b, &cd, NULL) == DAL_E_ARG);
  CHECK(strstr(dal_builder_errmsg(s.b), "'neg_in'") != NULL);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &neg_param;
  pd.coords = &x;
  pd.ncoords = 1;
  CHECK(dal_builder_place_def(s.b, bob, &pd) == DAL_E_ARG);
  scene_free(&s);
  return rc;
}

// a rod of length 0 was accepted, and the builder kept the message of an earlier failure
static int row_rod_length_zero(char *msg) {
  scene s;
  int c[4], a, b;
  memset(&s, 0, sizeof s);
  CHECK_OK(dal_builder_create(2, &s.b));
  for (int i = 0; i < 4; ++i)
    CHECK_OK(dal_builder_add_coord(s.b, NULL, &c[i]));
  CHECK_OK(dal_builder_add_particle(s.b, "a", 1.0, &a));
  CHECK_OK(dal_builder_add_particle(s.b, "b", 1.0, &b));
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_cartesian2;
  pd.coords = c;
  pd.ncoords = 2;
  CHECK_OK(dal_builder_place_def(s.b, a, &pd));
  pd.coords = c + 2;
  CHECK_OK(dal_builder_place_def(s.b, b, &pd));
  CHECK(dal_builder_add_particle(s.b, "bad", -1.0, NULL) == DAL_E_ARG);
  int parts[2] = {a, b};
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = "rod";
  cd.prim = &dal_con_distance2;
  cd.parts = parts;
  cd.nparts = 2;
  cd.param[DAL_DISTANCE_L] = 0.0;
  int rc = dal_builder_add_constraint_def(s.b, &cd, NULL);
  copy_msg(msg, dal_builder_errmsg(s.b));
  CHECK(strstr(msg, "'bad'") == NULL); // not the earlier failure's message
  cd.param[DAL_DISTANCE_L] = 1.0;
  CHECK_OK(dal_builder_add_constraint_def(s.b, &cd, NULL));
  CHECK(dal_builder_errmsg(s.b)[0] == 0); // a successful call leaves no message
  scene_free(&s);
  return rc;
}

// rtol = 100 was accepted silently
static int row_rtol_huge(char *msg) {
  scene s;
  CHECK_OK(pendulum(&s, 0.3));
  dal_solve_opts o = opts_for(DAL_METHOD_AUTO);
  o.rtol = 100.0;
  int rc = dal_advance(s.sys, s.st, &o, 1.0);
  copy_msg(msg, dal_state_errmsg(s.st));
  CHECK(dal_state_time(s.st) == 0.0);
  scene_free(&s);
  return rc;
}

// ---------------------------------------------------------------- the table
static const rel_row rows[] = {
    {"csv monitor: state of a smaller system", DAL_E_STATE, "csv_monitor", "another system", NULL,
     row_csv_foreign},
    {"csv monitor: state never evaluated", DAL_E_STATE, "csv_monitor", "not evaluated", NULL,
     row_csv_unevaluated},
    {"rk4: a stage sum that overflows, a solution that does not", DAL_OK, NULL, NULL, NULL,
     row_rk4_stage_sum},
    {"rk4: a solution that leaves double range", DAL_E_NONFINITE, "coordinate 'x'", "overflow",
     "callback", row_rk4_overflow},
    {"dal_powi(a, INT_MIN)", DAL_OK, NULL, NULL, NULL, row_powi_int_min},
    {"products before evaluation", DAL_E_STATE, "constraint_forces", "dal_forward", NULL,
     row_unevaluated_products},
    {"products after a failed evaluation", DAL_E_SINGULAR, "'phi'", "t=", NULL,
     row_failed_evaluation},
    {"subnormal mass", DAL_E_ARG, "'bob'", "subnormal", NULL, row_subnormal_mass},
    {"subnormal stiffness, gravity, parameter", DAL_E_ARG, "coefficient", "subnormal", NULL,
     row_subnormal_inputs},
    {"bs: collapsed first step", DAL_E_STEP, "t=0", "bs", "max_steps", row_bs_zero_steps},
    {"rk4: fixed step below the resolution of t", DAL_E_ARG, "fixed_step", "resolution", NULL,
     row_rk4_step_below_resolution},
    {"rk4: any step at t = 1e308", DAL_E_ARG, "fixed_step", "resolution", NULL, row_rk4_at_1e308},
    {"rk4: halving below the resolution of t", DAL_E_CALLBACK, "force callback", "t=", NULL,
     row_rk4_halving_stall},
    {"ida: callback > 0 forever", DAL_E_CALLBACK, "force callback", "t=", "max_steps",
     row_ida_callback_forever},
    {"ida: constraint that becomes unsatisfiable", DAL_E_STEP, "t=", "dominated by", "max_steps",
     row_ida_unsatisfiable},
    {"huge velocity, whole-system map (6 methods)", DAL_E_NONFINITE, "coordinate map", "overflows",
     "domain", row_huge_velocity_map},
    {"huge velocity, placed particle (5 methods)", DAL_E_STEP, "t=0", "collapse", "map",
     row_huge_velocity_placed},
    {"spring overflow without force callbacks", DAL_E_NONFINITE, "spring between 'a' and 'b'",
     "t=0", "callback", row_spring_overflow},
    {"baumgarte rates of 1e300", DAL_E_ARG, "baumgarte_beta", "1e+300", "callback",
     row_baumgarte_huge},
    {"accelerations that overflow (rk4, dopri5, bs)", DAL_E_NONFINITE,
     "acceleration of coordinate 'x'", "masses", "fix the callback", row_acceleration_overflow},
    {"foreign state, every (system, state) call", DAL_E_STATE, "state_jacobian", "another system",
     NULL, row_foreign_state_everywhere},
    {"evolve: dt NaN", DAL_E_NONFINITE, "dt", "nan", NULL, row_nan_dt},
    {"make_consistent: tolerance NaN", DAL_E_NONFINITE, "tolerance", "nan", NULL,
     row_nan_tolerance},
    {"primitive with nparam = -1", DAL_E_ARG, "'neg_param'", "nparam = -1", NULL,
     row_malformed_primitive},
    {"rod of length 0", DAL_E_ARG, "'rod'", "rod length L", "'bad'", row_rod_length_zero},
    {"rtol = 100", DAL_E_ARG, "rtol", "100", NULL, row_rtol_huge},
};

int main(void) {
  int nrows = (int)(sizeof rows / sizeof rows[0]);
  for (int i = 0; i < nrows; ++i) {
    const rel_row *r = &rows[i];
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
    if (r->never)
      CHECK_MSG(strstr(msg, r->never) == NULL, "row '%s': message names '%s' (wrong culprit): %s",
                r->name, r->never, msg);
    printf("%-55s %-16s %s | %.300s\n", r->name, dal_status_name(rc),
           check_failures == before ? "ok  " : "FAIL", msg);
  }
  return check_summary("test_reliability");
}
