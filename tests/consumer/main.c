// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Consumer check: a program built outside the source tree against the installed library.
//
// It includes only <dalembert/dalembert.h>, checks that the library it runs with has the
// version its build system found (DAL_EXPECT_VERSION), differentiates with jets, and builds
// and evaluates a pendulum, comparing theta'' with -g/l sin(theta). Exit status 0 on success.
#include <dalembert/dalembert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#ifndef DAL_EXPECT_VERSION
#define DAL_EXPECT_VERSION ""
#endif

int main(void) {
  int bad = 0;
  printf("consumer: dalembert %s (build system found %s)\n", dal_version(), DAL_EXPECT_VERSION);
  if (strcmp(dal_version(), DAL_EXPECT_VERSION) != 0) {
    printf("consumer: version mismatch\n");
    bad = 1;
  }
  // jets: d/ds and d2/ds2 of exp(sin(x + s)) at s = 0
  dal_jet x = dal_var(0.4, 1.0), f = dal_exp(dal_sin(x));
  double e = exp(sin(0.4)), c = cos(0.4), s = sin(0.4);
  if (fabs(f.d - e * c) > 1e-14 || fabs(f.dd - e * (c * c - s)) > 1e-14) {
    printf("consumer: jet derivatives wrong (%.17g, %.17g)\n", f.d, f.dd);
    bad = 1;
  }
  // a pendulum: theta'' = -g/l sin(theta)
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  int th, bob, rc = dal_builder_create(2, &b);
  double g[2] = {0, -9.81}, q = 1.1, qd = 0.3;
  if (!rc) rc = dal_builder_add_coord(b, "theta", &th);
  if (!rc) rc = dal_builder_add_particle(b, "bob", 1.5, &bob);
  dal_place_def pd = dal_default_place_def(); // pivot fixed at the origin
  pd.prim = &dal_map_pendulum;
  pd.coords = &th;
  pd.ncoords = 1;
  pd.param[DAL_PENDULUM_L] = 0.75;
  if (!rc) rc = dal_builder_place_def(b, bob, &pd);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  if (!rc) rc = dal_builder_compile(b, &sys);
  if (rc) printf("consumer: build failed: %s: %s\n", dal_status_name(rc), dal_builder_errmsg(b));
  if (!rc) rc = dal_state_create(sys, &st);
  if (!rc) rc = dal_state_set(sys, st, 0.0, &q, &qd);
  if (!rc) rc = dal_forward(sys, st);
  if (!rc) {
    double a = dal_state_qddot(st)[0], ref = -9.81 / 0.75 * sin(1.1);
    printf("consumer: pendulum theta'' = %.15g (closed form %.15g)\n", a, ref);
    if (fabs(a - ref) > 1e-13 * fabs(ref)) bad = 1;
  } else if (st) {
    printf("consumer: forward failed: %s\n", dal_state_errmsg(st));
  }
  bad |= rc != 0;
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
  printf("consumer: %s\n", bad ? "FAILED" : "ok");
  return bad;
}
