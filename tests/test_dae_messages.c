// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// IDA's failure messages tell the truth (issue 20, item 5). A failure at a regular point does
// not send the user to the constraints: the message reports dal_check_constraints' verdict
// (the oracle here: the same check run by the test on the returned state) and names the
// unknown that dominated the last Newton correction. A real constraint defect is named as one:
// a rail x = 0.5 + t crossing the unit circle becomes tangent to it at t = 0.5, where the two
// constraints become dependent (their gradients' smallest pivot ratio is |y| = sqrt(1 - x^2),
// closed form); the bead into a cusp, where a gradient vanishes, is in test_bad_input.c. The
// time in the message is the state's (it named the step IDA tried, t = 1e15 + 1.75, before).
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

// the rail x = 0.5 + t
static int rail(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)p;
  (void)ctx;
  out[0] = dal_sub(in[0], dal_addc(t, 0.5));
  return 0;
}
static const dal_primitive prim_rail = {
    .name = "rail", .version = 1, .nin = 2, .nout = 1, .eval = rail, .doc = "x - 0.5 - t"};

// a bead (m = 1) in the plane under gravity, on a unit rod to the origin and on the rail
static dal_system *rail_scene(void) {
  dal_builder *b = NULL;
  int c[2], p, rc = dal_builder_create(2, &b);
  double g[2] = {0.0, -9.81};
  if (!rc) rc = dal_builder_set_gravity(b, g);
  if (!rc) rc = dal_builder_add_coord(b, "x", &c[0]);
  if (!rc) rc = dal_builder_add_coord(b, "y", &c[1]);
  if (!rc) rc = dal_builder_add_particle(b, "bead", 1.0, &p);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_cartesian2, pd.coords = c, pd.ncoords = 2;
  if (!rc) rc = dal_builder_place_def(b, p, &pd);
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = "rod", cd.prim = &dal_con_anchor2, cd.parts = &p, cd.nparts = 1;
  cd.param[DAL_ANCHOR_L] = 1.0;
  if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
  cd = dal_default_constraint_def();
  cd.name = "rail", cd.prim = &prim_rail, cd.parts = &p, cd.nparts = 1;
  if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
  return scn_finish(b, rc);
}

static int has(const char *msg, const char *s) { return strstr(msg, s) != NULL; }

// run from (t0, q, v) to t1; returns the status, the message in msg
static int run(const dal_system *sys, dal_state *st, double t0, const double *q, const double *v,
               const dal_solve_opts *o, double t1, char *msg, size_t len) {
  CHECK_OK(dal_state_set(sys, st, t0, q, v));
  int rc = dal_advance(sys, st, o, t1);
  snprintf(msg, len, "%s", dal_state_errmsg(st));
  printf("%s: %s\n\n", dal_status_name(rc), msg);
  return rc;
}

// the oracle: dal_check_constraints on the returned state (its last accepted step)
static void check_oracle(const dal_system *sys, dal_state *st, int *rank, double *rmin) {
  dal_constraint_report rep;
  CHECK_OK(dal_check_constraints(sys, st, &rep));
  *rank = rep.rank;
  *rmin = rep.rmin;
}

// 1. regular points: the pendulum with an absurd minimum step (Newton cannot converge at
// h = 0.3), and far from t = 0 (t0 = 1e15, where 3 s is 24 ulps of t)
static void regular(void) {
  dal_system *sys = scn_cart_pendulum(NULL);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q[2] = {0.8, -0.6}, v[2] = {1.8, 2.4};
  char msg[1024], want[128];
  dal_solve_opts o = dal_default_solve_opts();
  o.form = DAL_FORM_GGL;
  o.hmin = o.h0 = 0.3;
  CHECK(run(sys, st, 0.0, q, v, &o, 2.0, msg, sizeof msg) == DAL_E_CONV);
  int rank;
  double rmin;
  check_oracle(sys, st, &rank, &rmin);
  CHECK(rank == 1 && rmin == 1.0);
  CHECK(dal_state_time(st) == 0.0);
  CHECK_MSG(has(msg, "at t=0 (last accepted step), h=0.3") &&
                has(msg, "pass dal_check_constraints here (rank 1 of 1") &&
                has(msg, "not their defect") && !has(msg, "check the constraints") &&
                has(msg, "correction dominated by") && has(msg, "index-1 form with projection"),
            "%s", msg);
  // at t0 = 1e15: the message names the state's time, t0, and the step's resolution
  double t0 = 1e15;
  o = dal_default_solve_opts();
  o.form = DAL_FORM_GGL;
  int rc = run(sys, st, t0, q, v, &o, t0 + 3.0, msg, sizeof msg);
  CHECK(rc == DAL_E_CONV && dal_state_time(st) == t0);
  snprintf(want, sizeof want, "at t=%.17g (last accepted step)", t0);
  CHECK_MSG(has(msg, want) && has(msg, "ulps of t (restart the clock") &&
                !has(msg, "check the constraints"),
            "%s", msg);
  // too many steps: no verdict on the constraints, the local error's variable
  o = dal_default_solve_opts();
  o.form = DAL_FORM_GGL;
  o.max_steps = 5;
  CHECK(run(sys, st, 0.0, q, v, &o, 2.0, msg, sizeof msg) == DAL_E_MAXSTEPS);
  CHECK_MSG(has(msg, "error dominated by") && !has(msg, "dal_check_constraints"), "%s", msg);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// 2. a constraint defect: the rail becoming tangent to the rod's circle
static void defects(void) {
  dal_system *sys = rail_scene();
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double y0 = -sqrt(0.75), q[2] = {0.5, y0}, v[2] = {1.0, 0.5 / -y0};
  char msg[1024], want[128];
  dal_solve_opts o = dal_default_solve_opts();
  o.form = DAL_FORM_GGL;
  CHECK(run(sys, st, 0.0, q, v, &o, 1.0, msg, sizeof msg) == DAL_E_CONV);
  double t = dal_state_time(st), x = 0.5 + t;
  CHECK(t > 0.49 && t < 0.5);
  // the pivot ratios the message quotes: |y| at the start and at the state (closed form)
  int rank;
  double rmin;
  check_oracle(sys, st, &rank, &rmin);
  CHECK(rank == 2);
  CHECK_CLOSE(rmin, sqrt(1.0 - x * x), 1e-6);
  snprintf(want, sizeof want, "fell from %.3g at the start to %.3g here", -y0, sqrt(1.0 - x * x));
  CHECK_MSG(has(msg, "the constraints become dependent") && has(msg, want) &&
                has(msg, "check the constraints") && !has(msg, "not their defect"),
            "%s", msg);
  // the rail's multiplier grows like 1/|y| there: it dominates the last Newton correction
  CHECK_MSG(has(msg, "lambda[1] (multiplier of constraint 'rail')"), "%s", msg);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

int main(void) {
  regular();
  defects();
  return check_summary("test_dae_messages");
}
