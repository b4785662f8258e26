// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The standard scenes of the tests and benchmarks (scenes.h).
#include "scenes.h"

#include <stdio.h>

scn_knobs scn_default(void) {
  scn_knobs k = {0};
  k.g = SCN_G;
  k.m = k.m2 = 1.0;
  k.l = k.l2 = 1.0;
  k.R = 1.0;
  k.k = 1.0;
  k.N = 4;
  k.dynamics = DAL_DYNAMICS_AUTO;
  return k;
}

// NULL knobs: the defaults
#define KNOBS(k)                                                                                   \
  scn_knobs dflt_ = scn_default();                                                                 \
  if (!(k)) (k) = &dflt_

dal_system *scn_finish(dal_builder *b, int rc) {
  dal_system *s = NULL;
  if (!rc) rc = dal_builder_compile(b, &s);
  if (rc) fprintf(stderr, "scene: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return rc ? NULL : s;
}

int scn_builder(const scn_knobs *k, int d, dal_builder **b) {
  KNOBS(k);
  int rc = dal_builder_create(d, b);
  double g[3] = {0.0, 0.0, 0.0};
  g[d - 1] = -k->g;
  if (!rc && k->g != 0.0) rc = dal_builder_set_gravity(*b, g);
  if (!rc) rc = dal_builder_set_dynamics(*b, k->dynamics);
  return rc;
}

int scn_add_swing(dal_builder *b, const scn_knobs *k, const char *name, double m, int parent,
                  double l, const char *coord, int *p) {
  KNOBS(k);
  int c, rc = dal_builder_add_coord(b, coord, &c);
  if (!rc) rc = dal_builder_add_particle(b, name, m, p);
  dal_place_def pd = dal_default_place_def();
  pd.coords = &c;
  pd.ncoords = 1;
  if (parent < 0) {
    pd.prim = &dal_map_pendulum;
    pd.param[DAL_PENDULUM_L] = l;
    pd.param[DAL_PENDULUM_AX] = k->ax;
    pd.param[DAL_PENDULUM_AY] = k->ay;
    pd.param[DAL_PENDULUM_W] = k->w;
    pd.param[DAL_PENDULUM_PH] = k->ph;
    pd.param[DAL_PENDULUM_X0] = k->x0;
    pd.param[DAL_PENDULUM_Y0] = k->y0;
  } else {
    pd.prim = &dal_map_hanging;
    pd.parent = parent;
    pd.param[DAL_HANGING_L] = l;
  }
  if (!rc) rc = dal_builder_place_def(b, *p, &pd);
  return rc;
}

int scn_add_xy(dal_builder *b, const char *name, double m, const char *xname, const char *yname,
               int *p) {
  int c[2], rc = dal_builder_add_coord(b, xname, &c[0]);
  if (!rc) rc = dal_builder_add_coord(b, yname, &c[1]);
  if (!rc) rc = dal_builder_add_particle(b, name, m, p);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_cartesian2;
  pd.coords = c;
  pd.ncoords = 2;
  if (!rc) rc = dal_builder_place_def(b, *p, &pd);
  return rc;
}

int scn_add_rod(dal_builder *b, const char *name, int a, int b2, double l, const scn_knobs *k) {
  KNOBS(k);
  int parts[2] = {a, b2};
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = name;
  cd.parts = parts;
  if (b2 < 0) {
    cd.prim = &dal_con_anchor2;
    cd.nparts = 1;
    cd.param[DAL_ANCHOR_L] = l;
    cd.param[DAL_ANCHOR_X0] = k->x0;
    cd.param[DAL_ANCHOR_Y0] = k->y0;
    cd.ctx = (void *)k->pivot;
  } else {
    cd.prim = &dal_con_distance2;
    cd.nparts = 2;
    cd.param[DAL_DISTANCE_L] = l;
  }
  return dal_builder_add_constraint_def(b, &cd, NULL);
}

dal_system *scn_pendulum(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int p, rc = scn_builder(k, 2, &b);
  if (!rc) rc = scn_add_swing(b, k, "bob", k->m, -1, k->l, "theta", &p);
  return scn_finish(b, rc);
}

dal_system *scn_cart_pendulum(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int p, rc = scn_builder(k, 2, &b);
  if (!rc) rc = scn_add_xy(b, "bob", k->m, "x", "y", &p);
  if (!rc) rc = scn_add_rod(b, "rod", p, -1, k->l, k);
  return scn_finish(b, rc);
}

dal_system *scn_double_pendulum(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int p[2], rc = scn_builder(k, 2, &b);
  if (!rc) rc = scn_add_swing(b, k, "upper", k->m, -1, k->l, "theta1", &p[0]);
  if (!rc) rc = scn_add_swing(b, k, "lower", k->m2, p[0], k->l2, "theta2", &p[1]);
  return scn_finish(b, rc);
}

dal_system *scn_cart_double_pendulum(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int p[2], rc = scn_builder(k, 2, &b);
  if (!rc) rc = scn_add_xy(b, "upper", k->m, "x1", "y1", &p[0]);
  if (!rc) rc = scn_add_xy(b, "lower", k->m2, "x2", "y2", &p[1]);
  if (!rc) rc = scn_add_rod(b, "rod1", p[0], -1, k->l, k);
  if (!rc) rc = scn_add_rod(b, "rod2", p[0], p[1], k->l2, k);
  return scn_finish(b, rc);
}

dal_system *scn_bead(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int c, p, rc = scn_builder(k, 3, &b);
  if (!rc) rc = dal_builder_add_coord(b, "theta", &c);
  if (!rc) rc = dal_builder_add_particle(b, "bead", k->m, &p);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_ring;
  pd.coords = &c;
  pd.ncoords = 1;
  pd.param[DAL_RING_R] = k->R;
  pd.param[DAL_RING_W] = k->spin;
  if (!rc) rc = dal_builder_place_def(b, p, &pd);
  return scn_finish(b, rc);
}

dal_system *scn_cart_bead(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int c[3], p, rc = scn_builder(k, 3, &b);
  const char *nm[3] = {"x", "y", "z"};
  for (int i = 0; i < 3 && !rc; ++i)
    rc = dal_builder_add_coord(b, nm[i], &c[i]);
  if (!rc) rc = dal_builder_add_particle(b, "bead", k->m, &p);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_cartesian3;
  pd.coords = c;
  pd.ncoords = 3;
  if (!rc) rc = dal_builder_place_def(b, p, &pd);
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = "ring";
  cd.prim = &dal_con_turning_circle;
  cd.parts = &p;
  cd.nparts = 1;
  cd.param[DAL_TURNING_CIRCLE_R] = k->R;
  cd.param[DAL_TURNING_CIRCLE_W] = k->spin;
  if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
  return scn_finish(b, rc);
}

dal_system *scn_oscillator(const scn_knobs *k) {
  KNOBS(k);
  scn_knobs free = *k;
  free.g = 0.0;
  dal_builder *b = NULL;
  int p, rc = scn_builder(&free, 2, &b);
  if (!rc) rc = scn_add_xy(b, "bob", k->m, "x", "y", &p);
  dal_spring_def sd = dal_default_spring_def(); // zero length, to the origin
  sd.a = p;
  sd.k = k->k;
  if (!rc) rc = dal_builder_add_spring_def(b, &sd);
  return scn_finish(b, rc);
}

dal_system *scn_hanging_spring(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int p, rc = scn_builder(k, 2, &b);
  if (!rc) rc = scn_add_xy(b, "bob", k->m, "x", "y", &p);
  dal_spring_def sd = dal_default_spring_def();
  sd.a = p;
  sd.k = k->k;
  sd.length = k->l;
  if (!rc) rc = dal_builder_add_spring_def(b, &sd);
  dal_damper_def dd = dal_default_damper_def();
  dd.a = p;
  dd.c = k->c;
  if (!rc) rc = dal_builder_add_damper_def(b, &dd);
  return scn_finish(b, rc);
}

dal_system *scn_chain(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int p = -1, rc = scn_builder(k, 2, &b);
  for (int i = 0; i < k->N && !rc; ++i) {
    char name[16], coord[16];
    snprintf(name, sizeof name, "p%d", i);
    snprintf(coord, sizeof coord, "th%d", i);
    rc = scn_add_swing(b, k, name, k->m, p, k->l, coord, &p);
  }
  return scn_finish(b, rc);
}

dal_system *scn_cart_chain(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int prev = -1, rc = scn_builder(k, 2, &b);
  for (int i = 0; i < k->N && !rc; ++i) {
    char name[16], x[16], y[16], r[16];
    snprintf(name, sizeof name, "p%d", i);
    snprintf(x, sizeof x, "x%d", i);
    snprintf(y, sizeof y, "y%d", i);
    snprintf(r, sizeof r, "rod%d", i);
    int p;
    rc = scn_add_xy(b, name, k->m, x, y, &p);
    if (!rc) rc = scn_add_rod(b, r, i == 0 ? p : prev, i == 0 ? -1 : p, k->l, k);
    prev = p;
  }
  return scn_finish(b, rc);
}
