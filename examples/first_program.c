// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The README's first program: a pendulum released at 1 rad, theta at t = 10 s.
#include <dalembert/dalembert.h>
#include <stdio.h>

int main(void) {
  dal_builder *b;
  dal_system *sys;
  dal_state *st;
  int th, bob;
  dal_builder_create(2, &b); /* a planar scene */
  dal_builder_add_coord(b, "theta", &th);
  dal_builder_add_particle(b, "bob", 1.0, &bob);
  dal_place_def pend = dal_default_place_def(); /* pivot at the origin, no drive */
  pend.prim = &dal_map_pendulum;
  pend.coords = &th;
  pend.ncoords = 1;
  pend.param[DAL_PENDULUM_L] = 1.0;
  dal_builder_place_def(b, bob, &pend);
  double g[2] = {0, -9.81};
  dal_builder_set_gravity(b, g);
  if (dal_builder_compile(b, &sys)) {
    puts(dal_builder_errmsg(b));
    return 1;
  }
  dal_state_create(sys, &st);
  double q = 1.0, qdot = 0.0;
  dal_state_set(sys, st, 0.0, &q, &qdot);
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-10; /* atol follows: 1e-10 */
  if (dal_advance(sys, st, &o, 10.0)) puts(dal_state_errmsg(st));
  printf("theta(10) = %.12f\n", dal_state_q(st)[0]);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
  return 0;
}
