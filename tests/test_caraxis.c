// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The car axis problem of the Bari IVP test set (Schiehlen's multibody benchmark: an index-3
// DAE with 10 unknowns) built as a scene: two particles of mass K = eps^2 M / 2 in the plane in
// Cartesian coordinates, gravity, a spring (stiffness 1, rest length 1/2) from the left one to
// the origin and one from the right one to the road point (x_b(t), y_b(t)) = (sqrt(L^2 - y_b^2),
// r sin(w t)) (a moving anchor), the constraint x_l x_b + y_l y_b = 0 and the axis
// |p_l - p_r|^2 - L^2 = 0, written as the test set writes them, so the multipliers are the test
// set's lambda_1, lambda_2. At t = 3, the significant correct digits
// scd = -log10(max_i |y_i - ref_i| / |ref_i|) over all 10 unknowns (positions, velocities,
// multipliers), as the test set defines them, against this library's own 25-digit reference
// (tests/ref_caraxis.h, computed in __float128 by a second, hand-derived formulation), itself
// checked against the test set's published values.
//
// Measured (docs/dae.md, "The car axis"): GGL in IDA reaches 7.5 digits at rtol 1e-9, 8.36 at
// 1e-10 and 9.32 from 1e-11 (IDA runs below its floor 1e-12 down to the local tolerance
// 1e-14 while its steps succeed; with the floor applied from the start it stayed at 7.6); AUTO's
// route for tight tolerances (index-1 + projection + Bulirsch-Stoer) 12.25 at 1e-12 and 12.5 at
// 1e-13. The bounds sit 0.2 digits under the measurement (the 9-digit target of issue 31 from
// rtol 1e-11: at 9.0).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "ref_caraxis.h"

// the test set's parameters: eps, M, L, L0, r, w, g
#define CA_K (0.5 * 1e-2 * 1e-2 * 10.0)
#define CA_L 1.0
#define CA_L0 0.5
#define CA_R 0.1
#define CA_W 10.0
#define CA_G 1.0

// the road point (x_b, y_b) under the right wheel, over jets in t
static void road(dal_jet t, dal_jet *xb, dal_jet *yb) {
  *yb = dal_scale(dal_sin(dal_scale(t, CA_W)), CA_R);
  *xb = dal_sqrt(dal_sub(dal_const(CA_L * CA_L), dal_sq(*yb)));
}

static int road_path(dal_jet t, dal_jet *x, void *ctx) {
  (void)ctx;
  road(t, &x[0], &x[1]);
  return 0;
}

// phi_1 = x_l x_b(t) + y_l y_b(t): the left particle stays square to the road direction
static int con_left(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)p;
  (void)ctx;
  dal_jet xb, yb;
  road(t, &xb, &yb);
  out[0] = dal_add(dal_mul(in[0], xb), dal_mul(in[1], yb));
  return 0;
}
static const dal_primitive prim_left = {.name = "caraxis_left",
                                        .version = 1,
                                        .nin = 2,
                                        .nout = 1,
                                        .nparam = 0,
                                        .eval = con_left,
                                        .doc = "x_l x_b(t) + y_l y_b(t)"};

// phi_2 = |p_l - p_r|^2 - L^2: the axis keeps its length
static int con_axis(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)p;
  (void)ctx;
  out[0] =
      dal_addc(dal_add(dal_sq(dal_sub(in[0], in[2])), dal_sq(dal_sub(in[1], in[3]))), -CA_L * CA_L);
  return 0;
}
static const dal_primitive prim_axis = {.name = "caraxis_axis",
                                        .version = 1,
                                        .nin = 4,
                                        .nout = 1,
                                        .nparam = 0,
                                        .eval = con_axis,
                                        .doc = "|p_l - p_r|^2 - L^2"};

static dal_system *build(void) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  const char *names[4] = {"x_l", "y_l", "x_r", "y_r"};
  int rc = dal_builder_create(2, &b), c[4], part[2];
  double g[2] = {0.0, -CA_G};
  if (!rc) rc = dal_builder_set_gravity(b, g);
  for (int i = 0; i < 4 && !rc; ++i)
    rc = dal_builder_add_coord(b, names[i], &c[i]);
  for (int k = 0; k < 2 && !rc; ++k) {
    rc = dal_builder_add_particle(b, k ? "right" : "left", CA_K, &part[k]);
    dal_place_def pd = dal_default_place_def();
    pd.prim = &dal_map_cartesian2;
    pd.coords = &c[2 * k];
    pd.ncoords = 2;
    if (!rc) rc = dal_builder_place_def(b, part[k], &pd);
    dal_spring_def sd = dal_default_spring_def();
    sd.a = part[k];
    sd.k = 1.0;
    sd.length = CA_L0;
    sd.path = k ? road_path : NULL;
    if (!rc) rc = dal_builder_add_spring_def(b, &sd);
  }
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = "left";
  cd.prim = &prim_left;
  cd.parts = &part[0];
  cd.nparts = 1;
  if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
  cd.name = "axis";
  cd.prim = &prim_axis;
  cd.parts = part;
  cd.nparts = 2;
  if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
  if (!rc) rc = dal_builder_compile(b, &sys);
  if (rc) fprintf(stderr, "build: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return sys;
}

// scd of y (10 values) against the reference; *pos: over the positions only
static double scd(const double *y, const double *ref, double *pos) {
  double e = 0.0, ep = 0.0;
  for (int i = 0; i < 10; ++i) {
    double r = fabs(y[i] - ref[i]) / fabs(ref[i]);
    e = fmax(e, r);
    if (i < 4) ep = fmax(ep, r);
  }
  if (pos) *pos = -log10(ep);
  return -log10(e);
}

typedef struct run {
  double scd, scd_pos, rtol_used;
  long steps;
  char msg[512]; // the state's message after the run (notes)
  dal_formulation form;
  dal_method method;
} run;

// the test set's consistent start, integrated to t = 3 with options o
static int solve(const dal_system *sys, const dal_solve_opts *o, const double *ref, run *r) {
  dal_state *st = NULL;
  double q[4] = {0.0, 0.5, 1.0, 0.5}, v[4] = {-0.5, 0.0, -0.5, 0.0}, y[10];
  int rc = dal_state_create(sys, &st);
  if (!rc) rc = dal_state_set(sys, st, 0.0, q, v);
  if (!rc) rc = dal_advance(sys, st, o, 3.0);
  if (!rc) rc = dal_forward(sys, st);
  if (rc) {
    fprintf(stderr, "car axis rtol %g: status %d: %s\n", o->rtol, rc, dal_state_errmsg(st));
  } else {
    memcpy(y, dal_state_q(st), 4 * sizeof(double));
    memcpy(y + 4, dal_state_qdot(st), 4 * sizeof(double));
    memcpy(y + 8, dal_state_lambda(st), 2 * sizeof(double));
    r->scd = scd(y, ref, &r->scd_pos);
    dal_stats s;
    dal_state_stats(st, &s);
    r->steps = s.steps;
    r->rtol_used = s.rtol_used;
    snprintf(r->msg, sizeof r->msg, "%s", dal_state_errmsg(st));
    r->form = s.form_used;
    r->method = s.method_used;
  }
  dal_state_destroy(st);
  return rc;
}

int main(void) {
  double ref[10];
  for (int i = 0; i < 10; ++i)
    ref[i] = strtod(caraxis_ref[i], NULL);
  // the published values agree with ours to 9.2 digits (the accuracy the test set states)
  double pub = scd(caraxis_published, ref, NULL);
  printf("published reference against ours: scd %.2f\n", pub);
  CHECK(pub > 9.0 && pub < 9.5);
  dal_system *sys = build();
  CHECK(sys != NULL);
  if (!sys) return check_summary("test_caraxis");
  printf("%-6s %-7s %-22s %8s %8s %8s\n", "route", "rtol", "form, method used", "steps", "scd",
         "scd(q)");
  // rtol = atol; lower bounds of scd, 0.2 under the measurement (GGL in IDA, then AUTO)
  static const double rt[] = {1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13};
  static const double low[2][8] = {{4.9, 5.8, 6.5, 7.3, 8.16, 9.0, 9.0, 9.0},
                                   {4.9, 5.8, 6.5, 7.3, 10.2, 10.9, 12.0, 12.25}};
  for (int route = 0; route < 2; ++route)
    for (size_t k = 0; k < sizeof rt / sizeof rt[0]; ++k) {
      dal_solve_opts o = dal_default_solve_opts();
      o.rtol = rt[k];
      o.atol = rt[k];
      if (route == 0) o.form = DAL_FORM_GGL;
      run r = {0};
      int rc = solve(sys, &o, ref, &r);
      CHECK_OK(rc);
      if (rc) continue;
      printf("%-6s %-7.0e %-22s %8ld %8.2f %8.2f\n", route ? "AUTO" : "GGL", rt[k],
             r.form == DAL_FORM_GGL      ? "GGL, BDF (IDA)"
             : r.method == DAL_METHOD_BS ? "index-1+proj, BS"
                                         : "index-1+proj, other",
             r.steps, r.scd, r.scd_pos);
      CHECK_MSG(r.scd >= low[route][k], "%s rtol %g: scd %.2f below %.2f", route ? "AUTO" : "GGL",
                rt[k], r.scd, low[route][k]);
      // the route AUTO picks (solve.h): GGL in IDA down to rtol 1e-9, then index-1 + BS
      if (route) CHECK(r.form == (rt[k] >= 1e-9 ? DAL_FORM_GGL : DAL_FORM_INDEX1));
      // GGL runs at 0.001 rtol down to IDA's smallest local tolerance 1e-14, no step failed
      // (no retreat to the floor 1e-12, no note); below, the clamp to 1e-14 is noted
      if (!route) {
        CHECK_MSG(r.rtol_used == fmax(0.001 * rt[k], 1e-14), "rtol %g: rtol_used %g", rt[k],
                  r.rtol_used);
        CHECK_MSG((strstr(r.msg, "note:") != NULL) == (rt[k] < 1e-11), "rtol %g: '%s'", rt[k],
                  r.msg);
        CHECK(strstr(r.msg, "continued from there at the floor") == NULL);
      }
    }
  // a step that fails below the floor: atol 1e-14 at rtol 1e-11 (the local absolute tolerance
  // 1e-17) fails an error test at t = 0.138; IDA goes on from its last accepted step at the
  // floor 1e-12 and the message says when and from which tolerance. Measured 8.41 digits
  // (203164 steps); the floor from the start (before) gave 7.6
  dal_solve_opts o = dal_default_solve_opts();
  o.form = DAL_FORM_GGL;
  o.rtol = 1e-11;
  o.atol = 1e-14;
  run r = {0};
  CHECK_OK(solve(sys, &o, ref, &r));
  printf("GGL    rtol 1e-11, atol 1e-14: %ld steps, scd %.2f, rtol_used %g\n  %s\n", r.steps, r.scd,
         r.rtol_used, r.msg);
  CHECK_MSG(r.scd >= 8.2, "scd %.2f", r.scd);
  CHECK(r.rtol_used == 1e-12);
  const char *at = strstr(r.msg, "note: IDA's step failed at t=");
  CHECK_MSG(at != NULL && strstr(at, "at the local tolerance 1e-14 (below its floor 1e-12") &&
                strstr(at, "continued from there at the floor"),
            "'%s'", r.msg);
  // the time it names lies in (0, 3), where the failed step was
  double tf = at ? strtod(at + strlen("note: IDA's step failed at t="), NULL) : -1.0;
  CHECK_MSG(tf > 0.0 && tf < 3.0, "t = %g", tf);
  dal_system_destroy(sys);
  return check_summary("test_caraxis");
}
