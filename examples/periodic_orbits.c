// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Periodic orbits by shooting (dal_periodic_orbit) and a relative equilibrium in the turning
// frame (dal_relative_equilibrium).
//
// Problem 1: a pendulum (l = 1, g = 9.81) whose pivot moves horizontally, x = a cos(w t),
// a = 0.05, w = 2: in its angle theta it swings in step with the drive. Newton shooting on the
// exact state-transition matrix finds the period-1 orbit from the linear response
// theta = a w^2 / (g - w^2) cos(w t); checked: the orbit returns after 2 pi / w (integrated
// independently by dal_advance at rtol 1e-12), its amplitude lies within 5% of the linear one,
// and its multipliers lie on the unit circle (det 1).
//
// Problem 2: a spherical pendulum in Cartesian coordinates (x, y, z) with a rod to the origin,
// turning steadily at W = 5 rad/s about the vertical: the conical pendulum. Found in the turning
// frame; checked: cos th0 = g / (l W^2) and the wobble about the cone omega^2 = W^2 (1 + 3
// cos^2 th0), to 1e-9.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <dalembert/dalembert.h>

#include "example_util.h"

#define G 9.81
#define PI 3.14159265358979323846

static int forced(void) {
  const double a = 0.05, w = 2.0;
  dal_state *st;
  dal_system *sys = ex_pendulum(1.0, 1.0, G, a, 0.0, w);
  if (!sys) return 1;
  dal_state_create(sys, &st);
  double lin = a * w * w / (G - w * w), v = 0.0, re[2], im[2];
  dal_state_set(sys, st, 0.0, &lin, &v);
  dal_orbit_opts o = dal_default_orbit_opts();
  o.period = 2 * PI / w;
  dal_orbit_report rep;
  if (dal_periodic_orbit(sys, st, &o, re, im, &rep)) {
    puts(dal_state_errmsg(st));
    return 1;
  }
  double th0 = dal_state_q(st)[0], v0 = dal_state_qdot(st)[0];
  printf("forced pendulum: period-1 orbit theta(0) = %.12f (linear %.12f), theta'(0) = %.3g, "
         "%d Newton steps; multipliers %.9f %+.9fi, %.9f %+.9fi: %s\n",
         th0, lin, v0, rep.iterations, re[0], im[0], re[1], im[1],
         dal_floquet_verdict_name(rep.floquet.verdict));
  // an independent check of the return: one period by dal_advance
  dal_solve_opts so = dal_default_solve_opts();
  so.rtol = 1e-12;
  so.method = DAL_METHOD_BS;
  int bad = dal_advance(sys, st, &so, o.period) != DAL_OK;
  double gap = fabs(dal_state_q(st)[0] - th0) + fabs(dal_state_qdot(st)[0] - v0);
  printf("  return after 2 pi / w by dal_advance: %.3g\n", gap);
  bad |= gap > 1e-8 || fabs(th0 / lin - 1) > 0.05 || fabs(rep.floquet.det - 1) > 1e-8;
  bad |= fabs(hypot(re[0], im[0]) - 1) > 1e-8;
  dal_state_destroy(st);
  dal_system_destroy(sys);
  return bad;
}

static int conical(void) {
  const double l = 1.0, W = 5.0;
  dal_builder *b;
  dal_system *sys;
  dal_state *st;
  int c[3], bob;
  dal_builder_create(3, &b);
  dal_builder_add_coord(b, "x", &c[0]);
  dal_builder_add_coord(b, "y", &c[1]);
  dal_builder_add_coord(b, "z", &c[2]);
  dal_builder_add_particle(b, "bob", 1.0, &bob);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_cartesian3;
  pd.coords = c;
  pd.ncoords = 3;
  dal_builder_place_def(b, bob, &pd);
  double g[3] = {0, 0, -G};
  dal_builder_set_gravity(b, g);
  dal_constraint_def rod = dal_default_constraint_def();
  rod.name = "rod";
  rod.prim = &dal_con_anchor3;
  rod.parts = &bob;
  rod.nparts = 1;
  rod.param[DAL_ANCHOR_L] = l;
  dal_builder_add_constraint_def(b, &rod, NULL);
  if (dal_builder_compile(b, &sys)) {
    puts(dal_builder_errmsg(b));
    return 1;
  }
  dal_builder_destroy(b);
  dal_state_create(sys, &st);
  double q[3] = {0.8, 0.0, -0.6}, v[3] = {0, 0, 0}, axis[3] = {0, 0, 1}, re[4], im[4];
  dal_state_set(sys, st, 0.0, q, v);
  if (dal_relative_equilibrium(sys, st, axis, W, re, im, NULL)) {
    puts(dal_state_errmsg(st));
    return 1;
  }
  const double *qs = dal_state_q(st);
  double c0 = -qs[2] / l, wob = 0.0;
  for (int i = 0; i < 4; ++i)
    wob = fmax(wob, fabs(im[i]));
  double c_ref = G / (l * W * W), w_ref = W * sqrt(1 + 3 * c_ref * c_ref);
  printf("conical pendulum at W = %g: cos th0 = %.12f (g / (l W^2) = %.12f), wobble %.12f "
         "(W sqrt(1 + 3 cos^2 th0) = %.12f)\n",
         W, c0, c_ref, wob, w_ref);
  int bad = fabs(c0 - c_ref) > 1e-9 || fabs(wob - w_ref) > 1e-9 * w_ref;
  dal_state_destroy(st);
  dal_system_destroy(sys);
  return bad;
}

int main(void) {
  int bad = forced();
  bad |= conical();
  if (bad) puts("CHECK FAILED");
  return bad;
}
