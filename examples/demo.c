// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Flagship demo (stand-in): library version, a jet self-check, and a pendulum's acceleration.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dalembert/dalembert.h"

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0;
  printf("dalembert %s\n", dal_version());
  // jet self-check: d/ds sin(x + s)^2 + cos(x + s)^2 = 0
  dal_jet x = dal_var(0.7, 1.0);
  dal_jet one = dal_add(dal_sq(dal_sin(x)), dal_sq(dal_cos(x)));
  printf("jet check: sin^2+cos^2 = %.17g (d %.3g, dd %.3g)\n", one.v, one.d, one.dd);
  int bad = fabs(one.v - 1) > 1e-15 || fabs(one.d) > 1e-15 || fabs(one.dd) > 1e-14;

  // a simple pendulum built from the pendulum primitive: theta'' = -g/l sin theta
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  int th, bob, rc = dal_builder_create(2, &b);
  double g[2] = {0, -9.81}, par[7] = {1.0, 0, 0, 0, 0, 0, 0}, q = 1.0, qd = 0.0;
  if (!rc) rc = dal_builder_add_coord(b, "theta", &th);
  if (!rc) rc = dal_builder_add_particle(b, "bob", 1.0, &bob);
  if (!rc) rc = dal_builder_place(b, bob, &dal_map_pendulum, -1, 1, &th, 7, par, NULL);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  if (!rc) rc = dal_builder_compile(b, &sys);
  if (rc) printf("build failed: %s\n", dal_builder_errmsg(b));
  if (!rc) rc = dal_state_create(sys, &st);
  if (!rc) rc = dal_state_set(sys, st, 0.0, &q, &qd);
  if (!rc) rc = dal_forward(sys, st);
  if (!rc) {
    double a = dal_state_qddot(st)[0], ref = -9.81 * sin(1.0);
    printf("pendulum at theta=1: theta'' = %.17g (closed form %.17g)\n", a, ref);
    bad |= fabs(a - ref) > 1e-13;
  } else if (st) {
    printf("forward failed: %s\n", dal_state_errmsg(st));
  }
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
  bad |= rc != 0;
  if (check) printf("%s\n", bad ? "FAILED" : "ok");
  return bad;
}
