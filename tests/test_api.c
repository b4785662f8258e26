// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The user-facing API: element defs and their defaults, named parameters, table versions, the
// moving-point convention, and each papercut of issue 11 against an independent reference.
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "headers.h"
#include "scenes.h"

#define G 9.81

static int has(const char *msg, const char *what) { return msg && strstr(msg, what) != NULL; }

// a planar pendulum by a def: only l set; pivot at the origin and no drive by default
static dal_system *pendulum_def(double l, double m) {
  dal_builder *b = NULL;
  int th, bob;
  dal_system *sys = NULL;
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "theta", &th));
  CHECK_OK(dal_builder_add_particle(b, "bob", m, &bob));
  dal_place_def d = dal_default_place_def();
  d.prim = &dal_map_pendulum;
  d.coords = &th;
  d.ncoords = 1;
  d.param[DAL_PENDULUM_L] = l;
  CHECK_OK(dal_builder_place_def(b, bob, &d));
  double g[2] = {0, -G};
  CHECK_OK(dal_builder_set_gravity(b, g));
  CHECK_OK(dal_builder_compile(b, &sys));
  dal_builder_destroy(b);
  return sys;
}

static void test_place_def(void) {
  // theta'' = -g/l sin theta (closed form of the pendulum equation)
  dal_system *sys = pendulum_def(0.7, 2.0);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q = 0.9, v = 0.4;
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &v));
  CHECK_OK(dal_forward(sys, st));
  CHECK_CLOSE(dal_state_qddot(st)[0], -G / 0.7 * sin(0.9), 1e-14);
  // pivot at the origin by default: the bob is at l (sin th, -cos th)
  CHECK_CLOSE(dal_state_positions(st)[0], 0.7 * sin(0.9), 1e-15);
  CHECK_CLOSE(dal_state_positions(st)[1], -0.7 * cos(0.9), 1e-15);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

static void test_def_errors(void) {
  dal_builder *b = NULL;
  int th, bob, c2[2];
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "theta", &th));
  CHECK_OK(dal_builder_add_coord(b, "x", &c2[0]));
  CHECK_OK(dal_builder_add_coord(b, "y", &c2[1]));
  CHECK_OK(dal_builder_add_particle(b, "bob", 1.0, &bob));
  // an uninitialized def (not from dal_default_place_def) is caught by its cookie
  dal_place_def raw;
  memset(&raw, 0, sizeof raw);
  raw.prim = &dal_map_pendulum;
  raw.coords = &th;
  raw.ncoords = 1;
  raw.param[DAL_PENDULUM_L] = 1.0;
  CHECK(dal_builder_place_def(b, bob, &raw) == DAL_E_ARG);
  CHECK(has(dal_builder_errmsg(b), "dal_default_place_def"));
  CHECK(dal_builder_place_def(b, bob, NULL) == DAL_E_ARG);
  // a required parameter left unset is named
  dal_place_def d = dal_default_place_def();
  d.prim = &dal_map_pendulum;
  d.coords = &th;
  d.ncoords = 1;
  CHECK(dal_builder_place_def(b, bob, &d) == DAL_E_ARG);
  CHECK(has(dal_builder_errmsg(b), "parameter 'l' of 'pendulum'"));
  CHECK(has(dal_builder_errmsg(b), "'bob'"));
  // a non-finite parameter is named
  d.param[DAL_PENDULUM_L] = 1.0;
  d.param[DAL_PENDULUM_W] = NAN;
  CHECK(dal_builder_place_def(b, bob, &d) == DAL_E_NONFINITE);
  CHECK(has(dal_builder_errmsg(b), "parameter 'w' of 'pendulum'"));
  // an index beyond the primitive's parameters (a wrong enum) is caught
  d = dal_default_place_def();
  d.prim = &dal_map_hanging;
  d.param[DAL_PENDULUM_W] = 2.0;
  CHECK(dal_builder_place_def(b, bob, &d) == DAL_E_ARG);
  CHECK(has(dal_builder_errmsg(b), "param[5]"));
  // constraint, spring, damper defs: cookie and required fields
  dal_constraint_def cd;
  memset(&cd, 0, sizeof cd);
  CHECK(dal_builder_add_constraint_def(b, &cd, NULL) == DAL_E_ARG);
  CHECK(has(dal_builder_errmsg(b), "dal_default_constraint_def"));
  cd = dal_default_constraint_def();
  cd.name = "ring";
  cd.prim = &dal_con_circle2;
  cd.coords = c2;
  cd.ncoords = 2; // coordinates of nobody: inputs must be particle positions here
  cd.parts = &bob;
  cd.nparts = 1;
  CHECK(dal_builder_add_constraint_def(b, &cd, NULL) == DAL_E_ARG);
  CHECK(has(dal_builder_errmsg(b), "inputs"));
  cd.ncoords = 0;
  CHECK(dal_builder_add_constraint_def(b, &cd, NULL) == DAL_E_ARG);
  CHECK(has(dal_builder_errmsg(b), "parameter 'R' of 'on_circle2'"));
  CHECK(has(dal_builder_errmsg(b), "'ring'"));
  dal_spring_def sd = dal_default_spring_def();
  CHECK(dal_builder_add_spring_def(b, &sd) == DAL_E_ARG); // a not set
  sd.a = bob;
  sd.k = -1.0;
  CHECK(dal_builder_add_spring_def(b, &sd) == DAL_E_ARG);
  CHECK(has(dal_builder_errmsg(b), "'bob'"));
  dal_damper_def dd;
  memset(&dd, 0, sizeof dd);
  CHECK(dal_builder_add_damper_def(b, &dd) == DAL_E_ARG);
  CHECK(has(dal_builder_errmsg(b), "dal_default_damper_def"));
  dal_builder_destroy(b);
}

// a def's param_list with omitted trailing parameters = the def's param[] with the defaults
// (bit-identical); a list longer than the primitive's count, or a list beside a set param[],
// is refused by name
static void test_param_list_defaults(void) {
  dal_builder *b = NULL;
  int th, bob;
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "theta", &th));
  CHECK_OK(dal_builder_add_particle(b, "bob", 1.0, &bob));
  double l = 1.3, g[2] = {0, -G};
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_pendulum;
  pd.coords = &th;
  pd.ncoords = 1;
  pd.param_list = &l;
  pd.nparam_list = 1;
  CHECK_OK(dal_builder_place_def(b, bob, &pd));
  CHECK_OK(dal_builder_set_gravity(b, g));
  dal_system *s1 = NULL, *s2 = pendulum_def(1.3, 1.0);
  CHECK_OK(dal_builder_compile(b, &s1));
  dal_state *a = NULL, *c = NULL;
  CHECK_OK(dal_state_create(s1, &a));
  CHECK_OK(dal_state_create(s2, &c));
  double q = 2.0, v = -1.0;
  CHECK_OK(dal_state_set(s1, a, 0.0, &q, &v));
  CHECK_OK(dal_state_set(s2, c, 0.0, &q, &v));
  dal_solve_opts o = dal_default_solve_opts();
  CHECK_OK(dal_advance(s1, a, &o, 1.0));
  CHECK_OK(dal_advance(s2, c, &o, 1.0));
  CHECK(dal_state_q(a)[0] == dal_state_q(c)[0]);
  // too many parameters is still an error
  double many[8] = {1, 0, 0, 0, 0, 0, 0, 0};
  dal_builder_destroy(b);
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "theta", &th));
  CHECK_OK(dal_builder_add_particle(b, "bob", 1.0, &bob));
  pd.param_list = many;
  pd.nparam_list = 8;
  CHECK(dal_builder_place_def(b, bob, &pd) == DAL_E_ARG);
  CHECK(has(dal_builder_errmsg(b), "takes 7 parameters"));
  // a list beside a set param[] entry: which one is meant is not guessed
  pd.nparam_list = 1;
  pd.param[DAL_PENDULUM_L] = 1.3;
  CHECK(dal_builder_place_def(b, bob, &pd) == DAL_E_ARG);
  CHECK(has(dal_builder_errmsg(b), "both param[0] and a param_list"));
  dal_state_destroy(a);
  dal_state_destroy(c);
  dal_system_destroy(s1);
  dal_system_destroy(s2);
  dal_builder_destroy(b);
}

// a primitive with more parameters than param[] holds (20): its parameters come through
// param_list, the inline array refuses it naming the list; r = p[19] (sin th, -cos th), a
// pendulum of length p[19], checked against that closed form
#define WIDE_NPARAM 20
static int wide_eval(const dal_jet *in, dal_jet t, const double *param, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  out[0] = dal_scale(dal_sin(in[0]), param[WIDE_NPARAM - 1]);
  out[1] = dal_scale(dal_cos(in[0]), -param[WIDE_NPARAM - 1]);
  return 0;
}
static const dal_primitive wide_prim = {.name = "wide",
                                        .version = DAL_PRIMITIVE_VERSION,
                                        .nin = 1,
                                        .nout = 2,
                                        .nparam = WIDE_NPARAM,
                                        .eval = wide_eval};

static void test_param_list_wide(void) {
  dal_builder *b = NULL;
  int th, bob;
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "theta", &th));
  CHECK_OK(dal_builder_add_particle(b, "bob", 1.0, &bob));
  dal_place_def pd = dal_default_place_def();
  pd.prim = &wide_prim;
  pd.coords = &th;
  pd.ncoords = 1;
  CHECK(dal_builder_place_def(b, bob, &pd) == DAL_E_ARG);
  CHECK(has(dal_builder_errmsg(b), "param_list"));
  double par[WIDE_NPARAM];
  for (int i = 0; i < WIDE_NPARAM; ++i)
    par[i] = 0.1 * (i + 1); // the last, the length, is 2.0
  pd.param_list = par;
  pd.nparam_list = WIDE_NPARAM;
  CHECK_OK(dal_builder_place_def(b, bob, &pd));
  dal_system *sys = NULL;
  CHECK_OK(dal_builder_compile(b, &sys));
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q = 0.7, v = 0.0;
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &v));
  CHECK_OK(dal_forward(sys, st));
  const double *r = dal_state_positions(st);
  CHECK(r != NULL);
  if (r) {
    CHECK_CLOSE(r[0], 2.0 * sin(0.7), 1e-15);
    CHECK_CLOSE(r[1], -2.0 * cos(0.7), 1e-15);
  }
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
}

// parameters given through param_list build exactly what param[] builds: one scene with its
// placements and its constraint through each, compared by the printed model (every parameter
// with %.17g) and by the accelerations, multipliers and forces at a state, bit for bit
static int wobble(dal_jet t, dal_jet *x, void *ctx) {
  (void)ctx;
  x[0] = dal_scale(dal_sin(t), 0.2);
  x[1] = dal_scale(t, -0.1);
  return 0;
}
static const dal_moving_point wobble_point = {wobble, NULL};

static dal_system *list_scene(int listed) {
  // a: Cartesian (x, y) on a rod to the moving point (0.3, 0.1) + x(t); b: pendulum (theta)
  // about a driven pivot; c hanging from b (phi); springs a-b and c-anchor, dampers a-c and
  // b-anchor (moving anchors x0 + x(t))
  dal_builder *b = NULL;
  int q[4], a, pb, c;
  double g[2] = {0, -G}, x0[2] = {0.5, -1.0};
  CHECK_OK(dal_builder_create(2, &b));
  const char *names[4] = {"x", "y", "theta", "phi"};
  for (int i = 0; i < 4; ++i)
    CHECK_OK(dal_builder_add_coord(b, names[i], &q[i]));
  CHECK_OK(dal_builder_add_particle(b, "a", 1.5, &a));
  CHECK_OK(dal_builder_add_particle(b, "b", 0.8, &pb));
  CHECK_OK(dal_builder_add_particle(b, "c", 0.6, &c));
  CHECK_OK(dal_builder_set_gravity(b, g));
  if (listed) {
    double rod[3] = {1.2, 0.3, 0.1}, pend[6] = {0.9, -0.5, 0.2, 0.1, 0.05, 2.0}, hang = 0.7;
    dal_place_def pd = dal_default_place_def();
    pd.prim = &dal_map_cartesian2;
    pd.coords = q;
    pd.ncoords = 2;
    CHECK_OK(dal_builder_place_def(b, a, &pd));
    pd.prim = &dal_map_pendulum;
    pd.coords = &q[2];
    pd.ncoords = 1;
    pd.param_list = pend;
    pd.nparam_list = 6;
    CHECK_OK(dal_builder_place_def(b, pb, &pd));
    pd.prim = &dal_map_hanging;
    pd.parent = pb;
    pd.coords = &q[3];
    pd.param_list = &hang;
    pd.nparam_list = 1;
    CHECK_OK(dal_builder_place_def(b, c, &pd));
    dal_constraint_def cd = dal_default_constraint_def();
    cd.name = "rod";
    cd.prim = &dal_con_anchor2;
    cd.parts = &a;
    cd.nparts = 1;
    cd.param_list = rod;
    cd.nparam_list = 3;
    cd.ctx = (void *)&wobble_point;
    CHECK_OK(dal_builder_add_constraint_def(b, &cd, NULL));
  } else {
    dal_place_def pd = dal_default_place_def();
    pd.prim = &dal_map_cartesian2;
    pd.coords = q;
    pd.ncoords = 2;
    CHECK_OK(dal_builder_place_def(b, a, &pd));
    pd = dal_default_place_def(); // the phase DAL_PENDULUM_PH keeps its default 0
    pd.prim = &dal_map_pendulum;
    pd.coords = &q[2];
    pd.ncoords = 1;
    pd.param[DAL_PENDULUM_L] = 0.9;
    pd.param[DAL_PENDULUM_X0] = -0.5;
    pd.param[DAL_PENDULUM_Y0] = 0.2;
    pd.param[DAL_PENDULUM_AX] = 0.1;
    pd.param[DAL_PENDULUM_AY] = 0.05;
    pd.param[DAL_PENDULUM_W] = 2.0;
    CHECK_OK(dal_builder_place_def(b, pb, &pd));
    pd = dal_default_place_def();
    pd.prim = &dal_map_hanging;
    pd.parent = pb;
    pd.coords = &q[3];
    pd.ncoords = 1;
    pd.param[DAL_HANGING_L] = 0.7;
    CHECK_OK(dal_builder_place_def(b, c, &pd));
    scn_knobs k = scn_default(); // the rod to (0.3, 0.1) moving by wobble_point
    k.x0 = 0.3;
    k.y0 = 0.1;
    k.pivot = &wobble_point;
    CHECK_OK(scn_add_rod(b, "rod", a, -1, 1.2, &k));
  }
  dal_spring_def sd = dal_default_spring_def();
  sd.a = a;
  sd.b = pb;
  sd.k = 20.0;
  sd.length = 0.4;
  CHECK_OK(dal_builder_add_spring_def(b, &sd));
  sd = dal_default_spring_def();
  sd.a = c;
  sd.anchor[0] = x0[0];
  sd.anchor[1] = x0[1];
  sd.path = wobble;
  sd.k = 15.0;
  sd.length = 0.3;
  CHECK_OK(dal_builder_add_spring_def(b, &sd));
  dal_damper_def dd = dal_default_damper_def();
  dd.a = a;
  dd.b = c;
  dd.c = 0.3;
  CHECK_OK(dal_builder_add_damper_def(b, &dd));
  dd = dal_default_damper_def();
  dd.a = pb;
  dd.anchor[0] = x0[0];
  dd.anchor[1] = x0[1];
  dd.path = wobble;
  dd.c = 0.2;
  CHECK_OK(dal_builder_add_damper_def(b, &dd));
  dal_system *sys = NULL;
  CHECK_OK(dal_builder_compile(b, &sys));
  dal_builder_destroy(b);
  return sys;
}

// the printed model as a string (caller frees)
static char *printed(const dal_system *sys) {
  FILE *fp = tmpfile();
  if (!fp) return NULL;
  CHECK_OK(dal_system_print(sys, fp));
  long len = ftell(fp);
  char *s = len > 0 ? malloc((size_t)len + 1) : NULL;
  rewind(fp);
  if (s && fread(s, 1, (size_t)len, fp) != (size_t)len) len = 0;
  if (s) s[len > 0 ? len : 0] = 0;
  fclose(fp);
  return s;
}

static void test_param_list_scene(void) {
  dal_system *sp = list_scene(1), *sd = list_scene(0);
  if (!sp || !sd) {
    dal_system_destroy(sp);
    dal_system_destroy(sd);
    return;
  }
  char *tp = printed(sp), *td = printed(sd);
  CHECK_MSG(tp && td && strcmp(tp, td) == 0, "param_list model:\n%s\nparam[] model:\n%s",
            tp ? tp : "", td ? td : "");
  // the moving anchors and springs are in it (a print that omitted them could agree)
  CHECK(tp && has(tp, "rod") && has(tp, "l=0.69999999999999996") && has(tp, "k=15"));
  free(tp);
  free(td);
  dal_state *a = NULL, *c = NULL;
  CHECK_OK(dal_state_create(sp, &a));
  CHECK_OK(dal_state_create(sd, &c));
  double q[4] = {0.4, -0.95, 0.6, -0.3}, v[4] = {0.2, 0.1, -0.4, 0.7};
  CHECK_OK(dal_state_set(sp, a, 0.7, q, v));
  CHECK_OK(dal_state_set(sd, c, 0.7, q, v));
  CHECK_OK(dal_forward(sp, a));
  CHECK_OK(dal_forward(sd, c));
  int same = 1;
  for (int i = 0; i < 4; ++i)
    same &= dal_state_qddot(a)[i] == dal_state_qddot(c)[i];
  same &= dal_state_lambda(a)[0] == dal_state_lambda(c)[0];
  for (int i = 0; i < 6; ++i)
    same &= dal_state_forces(a)[i] == dal_state_forces(c)[i];
  CHECK_MSG(same, "param_list and param[] scenes differ at a state");
  CHECK(dal_state_qddot(a)[0] != 0.0 && dal_state_lambda(a)[0] != 0.0);
  dal_state_destroy(a);
  dal_state_destroy(c);
  dal_system_destroy(sp);
  dal_system_destroy(sd);
}

// every built-in names all its parameters; defaults are NaN (required) or finite
static void test_registry_names(void) {
  for (int i = 0; i < dal_primitive_count(); ++i) {
    const dal_primitive *p = dal_primitive_get(i);
    CHECK_MSG(p->version == DAL_PRIMITIVE_VERSION, "'%s' version %d", p->name, p->version);
    CHECK_MSG(p->nparam == 0 || (p->param_names && p->param_defaults), "'%s' unnamed", p->name);
    for (int k = 0; k < p->nparam && p->param_names; ++k) {
      CHECK_MSG(p->param_names[k] && p->param_names[k][0], "'%s' param %d", p->name, k);
      for (int j = 0; j < k; ++j)
        CHECK_MSG(strcmp(p->param_names[j], p->param_names[k]), "'%s' duplicate", p->name);
    }
  }
  // the enums agree with the tables
  CHECK(dal_map_pendulum.nparam == DAL_PENDULUM_NPARAM);
  CHECK(strcmp(dal_map_pendulum.param_names[DAL_PENDULUM_PH], "ph") == 0);
  CHECK(dal_con_anchor2.nparam == DAL_ANCHOR2_NPARAM && dal_con_anchor3.nparam == 4);
  CHECK(dal_con_circle3.nparam == DAL_CIRCLE3_NPARAM && dal_con_circle2.nparam == 3);
  CHECK(dal_con_circle3.param_defaults[DAL_CIRCLE_NZ] == 1.0);
  CHECK(dal_con_plane.nparam == DAL_PLANE_NPARAM && dal_con_line3.nparam == DAL_LINE3_NPARAM);
  CHECK(dal_con_line2.nparam == DAL_LINE2_NPARAM && dal_map_ring.nparam == DAL_RING_NPARAM);
  CHECK(dal_con_turning_circle.nparam == DAL_TURNING_CIRCLE_NPARAM);
  CHECK(dal_con_turning_line2.nparam == DAL_TURNING_LINE2_NPARAM);
  CHECK(dal_con_prescribed.nparam == DAL_PRESCRIBED_NPARAM);
  CHECK(dal_map_sphere.nparam == DAL_SPHERE_NPARAM && dal_con_sphere.nparam == DAL_SPHERE_NPARAM);
  CHECK(dal_map_spherical.nparam == DAL_SPHERICAL_NPARAM);
  CHECK(dal_map_fixed3.nparam == DAL_FIXED3_NPARAM && dal_map_hanging.nparam == 1);
  CHECK(dal_con_distance3.nparam == DAL_DISTANCE_NPARAM);
}

static int lin_eval(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  out[0] = dal_scale(in[0], p[0]);
  out[1] = dal_const(0.0);
  return 0;
}

// table versions: 1 still works (no names), 0 and newer-than-library are refused by name
static void test_versions(void) {
  dal_primitive v1 = {.name = "lin1",
                      .version = 1,
                      .nin = 1,
                      .nout = 2,
                      .nparam = 1,
                      .eval = lin_eval,
                      .doc = "(a x, 0)",
                      .flags = 0};
  dal_builder *b = NULL;
  int x, p;
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "x", &x));
  CHECK_OK(dal_builder_add_particle(b, "p", 1.0, &p));
  dal_place_def d = dal_default_place_def();
  d.prim = &v1;
  d.coords = &x;
  d.ncoords = 1;
  CHECK(dal_builder_place_def(b, p, &d) == DAL_E_ARG); // version 1: no defaults, p0 required
  CHECK(has(dal_builder_errmsg(b), "parameter 'p0' of 'lin1'"));
  v1.version = 0;
  d.param[0] = 2.0;
  CHECK(dal_builder_place_def(b, p, &d) == DAL_E_ARG);
  CHECK(has(dal_builder_errmsg(b), "table version 0"));
  v1.version = DAL_PRIMITIVE_VERSION + 1;
  CHECK(dal_builder_place_def(b, p, &d) == DAL_E_ARG);
  CHECK(has(dal_builder_errmsg(b), "newer than this library"));
  v1.version = 1;
  CHECK_OK(dal_builder_place_def(b, p, &d));
  // a table changed after placement is caught at compile
  v1.version = 7;
  dal_system *sys = NULL;
  CHECK(dal_builder_compile(b, &sys) == DAL_E_ARG && sys == NULL);
  CHECK(has(dal_builder_errmsg(b), "'lin1'"));
  v1.version = 1;
  CHECK_OK(dal_builder_compile(b, &sys));
  dal_system_destroy(sys);
  dal_builder_destroy(b);
}

// a moving anchor point x0 + x(t): the spring and damper force against the hand formula
static int anchor_path(dal_jet t, dal_jet *x, void *ctx) {
  (void)ctx;
  x[0] = dal_scale(dal_sin(t), 0.5);
  x[1] = dal_scale(t, 0.25);
  return 0;
}

static void test_anchor_convention(void) {
  dal_builder *b = NULL;
  int c[2], p;
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "x", &c[0]));
  CHECK_OK(dal_builder_add_coord(b, "y", &c[1]));
  CHECK_OK(dal_builder_add_particle(b, "p", 2.0, &p));
  dal_place_def d = dal_default_place_def();
  d.prim = &dal_map_cartesian2;
  d.coords = c;
  d.ncoords = 2;
  CHECK_OK(dal_builder_place_def(b, p, &d));
  dal_spring_def sd = dal_default_spring_def();
  sd.a = p;
  sd.k = 3.0;
  sd.length = 0.4;
  sd.anchor[0] = 1.0;
  sd.anchor[1] = -2.0;
  sd.path = anchor_path;
  CHECK_OK(dal_builder_add_spring_def(b, &sd));
  dal_damper_def dd = dal_default_damper_def();
  dd.a = p;
  dd.c = 0.7;
  dd.anchor[0] = 1.0;
  dd.anchor[1] = -2.0;
  dd.path = anchor_path;
  CHECK_OK(dal_builder_add_damper_def(b, &dd));
  dal_system *sys = NULL;
  CHECK_OK(dal_builder_compile(b, &sys));
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double t = 0.8, q[2] = {0.3, 0.9}, v[2] = {-0.2, 0.5};
  CHECK_OK(dal_state_set(sys, st, t, q, v));
  CHECK_OK(dal_forward(sys, st));
  // hand formula: anchor X = x0 + x(t), Xdot = x'(t); spring -k (|r - X| - L) e, damper
  // -c ((v - Xdot) . e) e with e = (r - X)/|r - X|
  double X[2] = {1.0 + 0.5 * sin(t), -2.0 + 0.25 * t}, Xd[2] = {0.5 * cos(t), 0.25};
  double e[2] = {q[0] - X[0], q[1] - X[1]}, len = hypot(e[0], e[1]);
  e[0] /= len;
  e[1] /= len;
  double vr = (v[0] - Xd[0]) * e[0] + (v[1] - Xd[1]) * e[1];
  for (int i = 0; i < 2; ++i)
    CHECK_CLOSE(dal_state_forces(st)[i], -3.0 * (len - 0.4) * e[i] - 0.7 * vr * e[i], 1e-14);
  dal_energies en;
  CHECK_OK(dal_state_energies(st, &en));
  CHECK_CLOSE(en.U, 1.5 * (len - 0.4) * (len - 0.4), 1e-14);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
}

// Cartesian pendulum (x, y) with a rod to the origin: a DAE system
static dal_system *cart_pendulum(double l) {
  scn_knobs k = scn_default(); // the scene library's: 'bob' (1.5 kg) on the rod 'rod'
  k.m = 1.5;
  k.l = l;
  k.g = G;
  dal_system *sys = scn_cart_pendulum(&k);
  CHECK(sys != NULL);
  if (!sys) return NULL;
  // the names, sizes and values the callers rely on
  double v = 0.0;
  CHECK(dal_system_ncoords(sys) == 2 && dal_system_nconstraints(sys) == 1);
  CHECK(strcmp(dal_system_coord_name(sys, 0), "x") == 0);
  CHECK(strcmp(dal_system_coord_name(sys, 1), "y") == 0);
  CHECK(strcmp(dal_system_particle_name(sys, 0), "bob") == 0);
  CHECK(strcmp(dal_system_constraint_name(sys, 0), "rod") == 0);
  CHECK(dal_system_mass(sys, 0) == 1.5);
  CHECK(dal_system_param(sys, &(dal_param_ref){DAL_PARAM_CONSTRAINT, 0, DAL_ANCHOR_L}, &v) == 0 &&
        v == l);
  CHECK(dal_system_param(sys, &(dal_param_ref){DAL_PARAM_GRAVITY, 0, 1}, &v) == 0 && v == -G);
  return sys;
}

typedef struct mon_ctx {
  int calls, stop_at, bad;
  double maxdiff;
} mon_ctx;

// from a monitor (const state): rod force = reaction m a - F, an independent route
static int rod_monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  mon_ctx *m = ctx;
  double F[2];
  if (dal_constraint_forces(sys, st, F)) m->bad = 1;
  const double *N = dal_state_reactions(st);
  for (int i = 0; i < 2; ++i)
    m->maxdiff = fmax(m->maxdiff, fabs(F[i] - N[i]));
  return ++m->calls == m->stop_at;
}

static void test_monitor_papercuts(void) {
  dal_system *sys = cart_pendulum(1.0);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q[2] = {sin(1.0), -cos(1.0)}, v[2] = {0, 0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
  dal_solve_opts o = dal_default_solve_opts();
  mon_ctx m = {0, 5, 0, 0.0};
  int rc = dal_evolve(sys, st, &o, 2.0, 0.1, rod_monitor, &m);
  // stopped early: a distinct, non-error status, the state at the 5th output time
  CHECK(rc == DAL_STOPPED && rc > 0);
  CHECK(m.calls == 5 && fabs(dal_state_time(st) - 0.4) < 1e-12);
  CHECK(has(dal_state_errmsg(st), "stopped"));
  CHECK(strcmp(dal_status_name(DAL_STOPPED), "DAL_STOPPED") == 0);
  CHECK(m.bad == 0);
  CHECK_MSG(m.maxdiff < 1e-9, "rod force vs reaction: %.3g", m.maxdiff);
  // completing the run is DAL_OK
  m.stop_at = -1;
  CHECK(dal_evolve(sys, st, &o, 1.0, 0.1, rod_monitor, &m) == DAL_OK);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// setting only rtol: atol follows (= DAL_ATOL_PER_RTOL rtol), same steps as setting both
// explicitly, and the error against the closed form tracks rtol
static void test_atol_follows(void) {
  // 2D oscillator x'' = -x, y'' = -y: an anchor spring k = 1 to the origin, m = 1
  dal_builder *b = NULL;
  int xy[2], p;
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "x", &xy[0]));
  CHECK_OK(dal_builder_add_coord(b, "y", &xy[1]));
  CHECK_OK(dal_builder_add_particle(b, "p", 1.0, &p));
  dal_place_def d = dal_default_place_def();
  d.prim = &dal_map_cartesian2;
  d.coords = xy;
  d.ncoords = 2;
  CHECK_OK(dal_builder_place_def(b, p, &d));
  dal_spring_def sd = dal_default_spring_def();
  sd.a = p;
  sd.k = 1.0;
  CHECK_OK(dal_builder_add_spring_def(b, &sd));
  dal_system *sys = NULL;
  CHECK_OK(dal_builder_compile(b, &sys));
  dal_state *s1 = NULL, *s2 = NULL, *s3 = NULL;
  CHECK_OK(dal_state_create(sys, &s1));
  CHECK_OK(dal_state_create(sys, &s2));
  CHECK_OK(dal_state_create(sys, &s3));
  double q0[2] = {1e-3, 0}, v0[2] = {0, 1e-3}; // small amplitude: atol matters
  dal_solve_opts o1, o2, o3;
  o1 = dal_default_solve_opts();
  o1.rtol = 1e-11; // only rtol
  o2 = o1;
  o2.atol = DAL_ATOL_PER_RTOL * o1.rtol; // the documented rule, explicit
  o3 = o1;
  o3.atol = 1e-8; // a fixed atol far above the motion's scale times rtol
  CHECK(o1.atol == 0.0);
  CHECK_OK(dal_state_set(sys, s1, 0, q0, v0));
  CHECK_OK(dal_state_set(sys, s2, 0, q0, v0));
  CHECK_OK(dal_state_set(sys, s3, 0, q0, v0));
  CHECK_OK(dal_advance(sys, s1, &o1, 10.0));
  CHECK_OK(dal_advance(sys, s2, &o2, 10.0));
  CHECK_OK(dal_advance(sys, s3, &o3, 10.0));
  CHECK(dal_state_q(s1)[0] == dal_state_q(s2)[0] && dal_state_q(s1)[1] == dal_state_q(s2)[1]);
  double e1 = hypot(dal_state_q(s1)[0] - 1e-3 * cos(10.0), dal_state_q(s1)[1] - 1e-3 * sin(10.0));
  double e3 = hypot(dal_state_q(s3)[0] - 1e-3 * cos(10.0), dal_state_q(s3)[1] - 1e-3 * sin(10.0));
  CHECK_MSG(e1 < 100 * 1e-11 * 1e-3 + 1e-13 * 100, "error %.3g with only rtol", e1);
  CHECK_MSG(e3 > 10 * e1, "fixed atol 1e-8 %.3g vs following %.3g", e3, e1);
  dal_state_destroy(s1);
  dal_state_destroy(s2);
  dal_state_destroy(s3);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
}

// the consistent start: its report is kept; a move beyond the limit is refused by name
static void test_init_report(void) {
  dal_system *sys = cart_pendulum(1.0);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  dal_init_report rep;
  CHECK(dal_state_init_report(st, &rep) == DAL_E_STATE && rep.dq_coord == -1);
  // 5 % off the rod length: the projection moves the bob radially by 0.05
  double q[2] = {0.0, -1.05}, v[2] = {0.3, 0.0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
  dal_solve_opts o = dal_default_solve_opts();
  o.init_max_move = 0.01;
  int rc = dal_advance(sys, st, &o, 0.5);
  CHECK(rc == DAL_E_INIT);
  CHECK(has(dal_state_errmsg(st), "coordinate 'y'") && has(dal_state_errmsg(st), "init_max_move"));
  CHECK(dal_state_q(st)[1] == -1.05 && dal_state_time(st) == 0.0); // unchanged
  CHECK_OK(dal_state_init_report(st, &rep));
  CHECK_CLOSE(rep.dq_max, 0.05, 1e-12);
  CHECK(rep.dq_coord == 1);
  CHECK_CLOSE(rep.phi_before, 0.05, 1e-12);
  // without a limit the run goes on, and the report says what was moved
  o.init_max_move = 0.0;
  CHECK_OK(dal_advance(sys, st, &o, 0.5));
  CHECK_OK(dal_state_init_report(st, &rep));
  CHECK_CLOSE(rep.dq_max, 0.05, 1e-12);
  CHECK(rep.phi_after <= rep.tol);
  o.init_max_move = -1.0;
  CHECK(dal_advance(sys, st, &o, 1.0) == DAL_E_ARG);
  CHECK(has(dal_state_errmsg(st), "init_max_move"));
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// count occurrences of needle in s
static int count(const char *s, const char *needle) {
  int n = 0;
  for (const char *p = strstr(s, needle); p; p = strstr(p + 1, needle))
    ++n;
  return n;
}

// a singular start: one message, whole, not the cause twice and truncated
static void test_singular_start_message(void) {
  dal_builder *b = NULL;
  int c[2], p;
  CHECK_OK(dal_builder_create(3, &b));
  CHECK_OK(dal_builder_add_coord(b, "theta", &c[0]));
  CHECK_OK(dal_builder_add_coord(b, "phi", &c[1]));
  CHECK_OK(dal_builder_add_particle(b, "bob", 1.0, &p));
  dal_place_def d = dal_default_place_def();
  d.prim = &dal_map_spherical;
  d.coords = c;
  d.ncoords = 2;
  d.param[DAL_SPHERICAL_L] = 1.0;
  CHECK_OK(dal_builder_place_def(b, p, &d));
  dal_system *sys = NULL;
  CHECK_OK(dal_builder_compile(b, &sys));
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q[2] = {0, 0}, v[2] = {0, 0};
  const dal_method ms[] = {DAL_METHOD_DOPRI5, DAL_METHOD_BS, DAL_METHOD_ADAMS, DAL_METHOD_RK4};
  for (int i = 0; i < 4; ++i) {
    dal_solve_opts o = dal_default_solve_opts();
    o.method = ms[i];
    CHECK_OK(dal_state_set(sys, st, 0, q, v));
    CHECK(dal_advance(sys, st, &o, 1.0) == DAL_E_SINGULAR);
    const char *msg = dal_state_errmsg(st);
    CHECK_MSG(count(msg, "mass matrix singular") == 1 && !has(msg, "failed too"), "%s: %s",
              dal_method_name(ms[i]), msg);
    CHECK_MSG(has(msg, "'phi'") && has(msg, "redundant coordinates"), "%s", msg);
  }
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
}

// L = 1/2 m l^2 thd^2 + m g l cos th: energies read off L match the particle pendulum's
static int pend_lag(dal_jet t, const dal_jet *q, const dal_jet *qd, dal_jet *L, void *ctx) {
  (void)t;
  (void)ctx;
  const double m = 2.0, l = 0.7;
  *L = dal_add(dal_scale(dal_mul(qd[0], qd[0]), 0.5 * m * l * l),
               dal_scale(dal_cos(q[0]), m * G * l));
  return 0;
}

static void test_lagrangian_energies(void) {
  dal_builder *b = NULL;
  CHECK_OK(dal_builder_create(0, &b)); // dim is optional for a Lagrangian system
  int th, p;
  CHECK_OK(dal_builder_add_coord(b, "theta", &th));
  CHECK(dal_builder_add_particle(b, "p", 1.0, &p) == DAL_E_ARG);
  CHECK(has(dal_builder_errmsg(b), "dim 0"));
  CHECK_OK(dal_builder_set_lagrangian(b, pend_lag, NULL));
  dal_system *sl = NULL, *sp = pendulum_def(0.7, 2.0);
  CHECK_OK(dal_builder_compile(b, &sl));
  CHECK(dal_system_dim(sl) == 0);
  dal_state *a = NULL, *c = NULL;
  CHECK_OK(dal_state_create(sl, &a));
  CHECK_OK(dal_state_create(sp, &c));
  double q = 0.6, v = 1.1;
  CHECK_OK(dal_state_set(sl, a, 0, &q, &v));
  CHECK_OK(dal_state_set(sp, c, 0, &q, &v));
  CHECK_OK(dal_forward(sl, a));
  CHECK_OK(dal_forward(sp, c));
  dal_energies ea, ec;
  CHECK_OK(dal_state_energies(a, &ea));
  CHECK_OK(dal_state_energies(c, &ec));
  // particle pendulum: T = 1/2 m l^2 v^2, U = -m g l cos q (closed form)
  CHECK_CLOSE(ec.T, 0.5 * 2.0 * 0.49 * v * v, 1e-14);
  CHECK_CLOSE(ea.T, ec.T, 1e-14);
  CHECK_CLOSE(ea.U, ec.U, 1e-14);
  CHECK_CLOSE(ea.E, ec.E, 1e-14);
  CHECK_CLOSE(ea.h, ec.h, 1e-14);
  CHECK_CLOSE(ea.T2, ec.T, 1e-14);
  CHECK(isfinite(ea.T1) && fabs(ea.T1) < 1e-14 && ea.T0 == 0.0);
  // after integration too (the state is evaluated where it stops)
  dal_solve_opts o = dal_default_solve_opts();
  CHECK_OK(dal_advance(sl, a, &o, 1.0));
  CHECK_OK(dal_state_energies(a, &ea));
  CHECK(isfinite(ea.T) && isfinite(ea.U));
  CHECK_CLOSE(ea.E, ec.E, 1e-7);
  dal_state_destroy(a);
  dal_state_destroy(c);
  dal_system_destroy(sl);
  dal_system_destroy(sp);
  dal_builder_destroy(b);
}

// ---------------------------------------------------------------- context last (papercut)
// In every public function and callback type a user context `ctx` is the last parameter. The
// public headers (DAL_HEADER_DIR) are read at run time: comments and preprocessor lines are
// stripped, each declaration's parameter list is split at its top-level commas, and a `ctx`
// that is not the last parameter fails, except the documented exceptions below (each must
// still exist, so the list cannot rot).
static const char *const ctx_exceptions[][2] = {
    {"dal_verify_primitive", "ctx is the primitive instance's data (as param), not a callback's"},
    {"dal_worker_create_fn", "an out-parameter (data) follows the context"},
};
#define NEXC ((int)(sizeof ctx_exceptions / sizeof ctx_exceptions[0]))

// blank out comments and preprocessor lines (with their continuations) in place
static void strip_noise(char *s) {
  for (char *p = s; *p;) {
    if (p[0] == '/' && p[1] == '/') {
      while (*p && *p != '\n')
        *p++ = ' ';
    } else if (p[0] == '/' && p[1] == '*') {
      while (*p && !(p[0] == '*' && p[1] == '/'))
        *p++ = ' ';
      if (*p) p[0] = p[1] = ' ', p += 2;
    } else if (*p == '#' && (p == s || p[-1] == '\n')) {
      while (*p && !(*p == '\n' && p[-1] != '\\'))
        *p++ = ' ';
    } else {
      ++p;
    }
  }
}

static int is_ident(char c) { return isalnum((unsigned char)c) || c == '_'; }

// check the declarations in text; counts declarations with a ctx parameter and exceptions met
static void check_ctx_last(char *text, const char *file, int *nctx, int *met) {
  strip_noise(text);
  for (char *stmt = text; *stmt;) {
    size_t len = strcspn(stmt, ";{}");
    char *open = memchr(stmt, '(', len);
    if (open && open[1] != '*') {
      // the declared name precedes the parameter list
      char *e = open;
      while (e > stmt && isspace((unsigned char)e[-1]))
        --e;
      char *b = e;
      while (b > stmt && is_ident(b[-1]))
        --b;
      char name[64] = "";
      if (e - b > 0 && e - b < 64) memcpy(name, b, (size_t)(e - b)), name[e - b] = 0;
      // parameters: split at top-level commas up to the matching ')'
      int depth = 0, index = 0, ctx_index = -1;
      char *q = open;
      for (; q < stmt + len; ++q) {
        if (*q == '(') ++depth;
        if (*q == ')' && --depth == 0) break;
        if (*q == ',' && depth == 1) ++index;
        if (depth == 1 && q[0] == 'c' && q[1] == 't' && q[2] == 'x' && !is_ident(q[-1]) &&
            !is_ident(q[3]))
          ctx_index = index;
      }
      if (ctx_index >= 0) {
        ++*nctx;
        int exc = -1;
        for (int k = 0; k < NEXC; ++k)
          if (strcmp(name, ctx_exceptions[k][0]) == 0) exc = k;
        if (ctx_index != index && exc >= 0) met[exc] = 1;
        CHECK_MSG(ctx_index == index || exc >= 0,
                  "%s: %s takes ctx as parameter %d of %d; put the user context last", file, name,
                  ctx_index + 1, index + 1);
      }
    }
    stmt += len + (stmt[len] != 0);
  }
}

// the context-last check of one header; ctx: its tallies
typedef struct ctx_tally {
  int nctx, met[NEXC];
} ctx_tally;
static void ctx_last_of(char *text, const char *name, void *ctx) {
  ctx_tally *t = ctx;
  check_ctx_last(text, name, &t->nctx, t->met);
}

static void test_context_last(void) {
  ctx_tally t = {0, {0}};
  int files = for_each_header(DAL_HEADER_DIR, ctx_last_of, &t), nctx = t.nctx, *met = t.met;
  CHECK_MSG(files >= 0, "cannot read %s", DAL_HEADER_DIR);
  if (files < 0) return;
  // the scan saw the headers' callback types and functions (more than 20 take a ctx)
  CHECK_MSG(files >= 10 && nctx > 20, "%d headers, %d declarations with ctx", files, nctx);
  for (int k = 0; k < NEXC; ++k)
    CHECK_MSG(met[k], "exception %s (%s) no longer needed: remove it from the list",
              ctx_exceptions[k][0], ctx_exceptions[k][1]);
}

static void test_version(void) {
  char v[32];
  snprintf(v, sizeof v, "%d.%d.%d", DAL_VERSION_MAJOR, DAL_VERSION_MINOR, DAL_VERSION_PATCH);
  CHECK(strcmp(v, dal_version()) == 0);
  CHECK(DAL_VERSION_NUMBER ==
        DAL_VERSION_MAJOR * 10000 + DAL_VERSION_MINOR * 100 + DAL_VERSION_PATCH);
}

int main(void) {
  test_place_def();
  test_def_errors();
  test_param_list_defaults();
  test_param_list_wide();
  test_param_list_scene();
  test_registry_names();
  test_versions();
  test_anchor_convention();
  test_monitor_papercuts();
  test_atol_follows();
  test_init_report();
  test_singular_start_message();
  test_lagrangian_energies();
  test_version();
  test_context_last();
  return check_summary("test_api");
}
