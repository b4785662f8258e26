// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Small scenes built from defs, shared by the dense-output and event tests: a pendulum in its
// angle, the same circle in Cartesian coordinates with a rod, the bead on a turning ring.
#ifndef DAL_TESTS_SCENES_DEF_H
#define DAL_TESTS_SCENES_DEF_H

#include <stdio.h>

#include "dalembert/dalembert.h"

/// gravity of these scenes (m/s^2)
#define SCENE_G 9.81

static inline dal_system *scene_finish(dal_builder *b, int rc) {
  dal_system *s = NULL;
  if (!rc) rc = dal_builder_compile(b, &s);
  if (rc) fprintf(stderr, "build: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return s;
}

/// a pendulum of length l, theta from the downward vertical
static inline dal_system *scene_pendulum(double l) {
  dal_builder *b = NULL;
  int c, p, rc = dal_builder_create(2, &b);
  double g[2] = {0.0, -SCENE_G};
  if (!rc) rc = dal_builder_add_coord(b, "theta", &c);
  if (!rc) rc = dal_builder_add_particle(b, "bob", 1.0, &p);
  dal_place_def d = dal_default_place_def();
  d.prim = &dal_map_pendulum;
  d.coords = &c;
  d.ncoords = 1;
  d.param[DAL_PENDULUM_L] = l;
  if (!rc) rc = dal_builder_place_def(b, p, &d);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  return scene_finish(b, rc);
}

/// the same circle of radius l in Cartesian coordinates (x, y), a rod "rod" to the origin
static inline dal_system *scene_cart_pendulum(double l) {
  dal_builder *b = NULL;
  int c[2], p, rc = dal_builder_create(2, &b);
  double g[2] = {0.0, -SCENE_G};
  if (!rc) rc = dal_builder_add_coord(b, "x", &c[0]);
  if (!rc) rc = dal_builder_add_coord(b, "y", &c[1]);
  if (!rc) rc = dal_builder_add_particle(b, "bob", 1.0, &p);
  dal_place_def d = dal_default_place_def();
  d.prim = &dal_map_cartesian2;
  d.coords = c;
  d.ncoords = 2;
  if (!rc) rc = dal_builder_place_def(b, p, &d);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  dal_constraint_def k = dal_default_constraint_def();
  k.name = "rod";
  k.prim = &dal_con_anchor2;
  k.parts = &p;
  k.nparts = 1;
  k.param[DAL_ANCHOR_L] = l;
  if (!rc) rc = dal_builder_add_constraint_def(b, &k, NULL);
  return scene_finish(b, rc);
}

/// Likharev's bead on a ring of radius R turning at w about the vertical
static inline dal_system *scene_bead(double R, double w) {
  dal_builder *b = NULL;
  int c, p, rc = dal_builder_create(3, &b);
  double g[3] = {0, 0, -SCENE_G};
  if (!rc) rc = dal_builder_add_coord(b, "theta", &c);
  if (!rc) rc = dal_builder_add_particle(b, "bead", 1.0, &p);
  dal_place_def d = dal_default_place_def();
  d.prim = &dal_map_ring;
  d.coords = &c;
  d.ncoords = 1;
  d.param[DAL_RING_R] = R;
  d.param[DAL_RING_W] = w;
  if (!rc) rc = dal_builder_place_def(b, p, &d);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  return scene_finish(b, rc);
}

#endif
