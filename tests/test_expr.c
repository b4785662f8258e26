// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Expressions: the built-in primitives written again as formulas, against their C jets.
//
// 1. Every built-in primitive with a closed formula (all but line3, whose normal pair is chosen
//    by a discrete rule, and the context-driven curves) written as expressions over the same
//    named parameters: at random inputs, parameters and times, evaluated along a coordinate
//    direction (the Jacobian column), along t (the time derivative) and along a random curve
//    with curvature (the curvature term, and the third derivative), the outputs equal the C
//    jets' to rounding. A table per primitive gives the largest difference in units of the
//    tolerance 2e-14 (1 + |coefficients|).
// 2. Errors: an unknown symbol, a bad token, an unknown function, a name given twice, and
//    nesting too deep are refused with messages naming the formula, the column and the culprit;
//    dal_expr_check names the function outside its domain.
// 3. Systems: the driven pendulum (dal_map_pendulum with a moving pivot) and the bead on the
//    turning ring (dal_map_ring) placed by expressions run to t = 10 like the C primitives, and
//    a per-trajectory override of the expression's parameter moves it like the C one; the
//    harmonic oscillator as a Lagrangian expression matches its closed form cos(w t).
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"

static unsigned long long seed = 0x2545f4914f6cdd1dULL;
static double rnd(double lo, double hi) { return check_rand(&seed, lo, hi); }

typedef struct case_ {
  const dal_primitive *prim;
  int nin;
  const char *inputs[8];
  const char *formulas[3];
} case_;

#define TOLF 2e-14

// largest |expr - C| / (TOLF (1 + |C coefficients|)) over outputs and the four coefficients
static double compare(const dal_primitive *prim, const dal_expr *e, const dal_jet *in, dal_jet t,
                      const double *param, double worst[4]) {
  dal_jet a[8], b[8];
  CHECK(prim->eval(in, t, param, a, NULL) == 0);
  CHECK_OK(dal_expr_eval(e, in, t, param, b));
  double w = 0.0;
  for (int k = 0; k < prim->nout; ++k) {
    double ca[4] = {a[k].v, a[k].d, a[k].dd, a[k].d3}, cb[4] = {b[k].v, b[k].d, b[k].dd, b[k].d3};
    double s = 1.0 + fabs(ca[0]) + fabs(ca[1]) + fabs(ca[2]) + fabs(ca[3]);
    for (int j = 0; j < 4; ++j) {
      double r = fabs(ca[j] - cb[j]) / (TOLF * s);
      if (!(r <= worst[j])) worst[j] = r;
      if (!(r <= w)) w = r;
    }
  }
  return w;
}

static void primitives_as_expressions(void) {
  static const case_ cases[] = {
      {&dal_map_cartesian2, 2, {"x", "y"}, {"x", "y"}},
      {&dal_map_cartesian3, 3, {"x", "y", "z"}, {"x", "y", "z"}},
      {&dal_map_fixed2, 0, {0}, {"x", "y"}},
      {&dal_map_fixed3, 0, {0}, {"x", "y", "z"}},
      {&dal_map_pendulum,
       1,
       {"theta"},
       {"x0 + ax*cos(w*t + ph) + l*sin(theta)", "y0 + ay*cos(w*t + ph) - l*cos(theta)"}},
      {&dal_map_hanging, 3, {"xp", "yp", "theta"}, {"xp + l*sin(theta)", "yp - l*cos(theta)"}},
      {&dal_map_spherical,
       2,
       {"theta", "phi"},
       {"x0 + l*sin(theta)*cos(phi)", "y0 + l*sin(theta)*sin(phi)", "z0 - l*cos(theta)"}},
      {&dal_map_ring,
       1,
       {"theta"},
       {"R*sin(theta)*cos(w*t + phi0)", "R*sin(theta)*sin(w*t + phi0)", "-R*cos(theta)"}},
      {&dal_map_sphere,
       2,
       {"theta", "phi"},
       {"cx + R*sin(theta)*cos(phi)", "cy + R*sin(theta)*sin(phi)", "cz + R*cos(theta)"}},
      {&dal_con_distance2, 4, {"xa", "ya", "xb", "yb"}, {"sqrt((xb - xa)^2 + (yb - ya)^2) - L"}},
      {&dal_con_distance3,
       6,
       {"xa", "ya", "za", "xb", "yb", "zb"},
       {"sqrt((xb - xa)^2 + (yb - ya)^2 + (zb - za)^2) - L"}},
      {&dal_con_anchor2, 2, {"x", "y"}, {"hypot(x - x0, y - y0) - L"}},
      {&dal_con_anchor3, 3, {"x", "y", "z"}, {"sqrt((x - x0)^2 + (y - y0)^2 + (z - z0)^2) - L"}},
      {&dal_con_circle2, 2, {"x", "y"}, {"sqrt((x - cx)^2 + (y - cy)^2) - R"}},
      {&dal_con_circle3,
       3,
       {"x", "y", "z"},
       {"(nx*(x - cx) + ny*(y - cy) + nz*(z - cz))/sqrt(nx^2 + ny^2 + nz^2)",
        "sqrt((x - cx - (nx*(x - cx) + ny*(y - cy) + nz*(z - cz))*nx/(nx^2 + ny^2 + nz^2))^2"
        " + (y - cy - (nx*(x - cx) + ny*(y - cy) + nz*(z - cz))*ny/(nx^2 + ny^2 + nz^2))^2"
        " + (z - cz - (nx*(x - cx) + ny*(y - cy) + nz*(z - cz))*nz/(nx^2 + ny^2 + nz^2))^2) - R"}},
      {&dal_con_turning_circle,
       3,
       {"x", "y", "z"},
       {"(y - cy)*cos(w*t + phi0) - (x - cx)*sin(w*t + phi0)",
        "sqrt((x - cx)^2 + (y - cy)^2 + (z - cz)^2) - R"}},
      {&dal_con_sphere, 3, {"x", "y", "z"}, {"sqrt((x - cx)^2 + (y - cy)^2 + (z - cz)^2) - R"}},
      {&dal_con_plane,
       3,
       {"x", "y", "z"},
       {"(nx*(x - cx) + ny*(y - cy) + nz*(z - cz))/sqrt(nx^2 + ny^2 + nz^2)"}},
      {&dal_con_line2, 2, {"x", "y"}, {"(ax*(y - cy) - ay*(x - cx))/hypot(ax, ay)"}},
      {&dal_con_turning_line2,
       2,
       {"x", "y"},
       {"(y - cy)*cos(w*t + phi0) - (x - cx)*sin(w*t + phi0)"}},
      {&dal_con_prescribed, 1, {"q"}, {"q - q0"}},
  };
  int ncase = (int)(sizeof cases / sizeof cases[0]);
  printf("%-16s %6s | largest difference / tolerance (2e-14 (1 + |C jet|))\n", "primitive",
         "instr");
  printf("%-16s %6s | %9s %9s %9s %9s %9s\n", "", "", "value", "jacobian", "d/dt", "curvature",
         "third");
  for (int c = 0; c < ncase; ++c) {
    const case_ *cs = &cases[c];
    const dal_primitive *prim = cs->prim;
    CHECK(prim->nin == cs->nin);
    dal_expr_def d = dal_default_expr_def();
    d.name = prim->name;
    d.formulas = cs->formulas;
    d.nout = prim->nout;
    d.inputs = cs->inputs;
    d.nin = cs->nin;
    d.params = prim->param_names;
    d.nparam = prim->nparam;
    dal_expr *e = NULL;
    char msg[512];
    int rc = dal_expr_create(&d, &e, msg, sizeof msg);
    CHECK_MSG(rc == 0, "%s: %s", prim->name, msg);
    if (rc) continue;
    CHECK(dal_expr_nout(e) == prim->nout && dal_expr_nin(e) == prim->nin &&
          dal_expr_nparam(e) == prim->nparam);
    double worst[5] = {0, 0, 0, 0, 0};
    for (int s = 0; s < 40; ++s) {
      double param[16];
      for (int i = 0; i < prim->nparam; ++i)
        param[i] = rnd(0.5, 2.0) * (rnd(0, 1) < 0.3 ? -1.0 : 1.0);
      if (prim->nparam) param[0] = rnd(0.5, 2.0); // lengths and radii > 0
      dal_jet in[8], t;
      double u[8];
      for (int i = 0; i < prim->nin; ++i)
        u[i] = rnd(-2.0, 2.0);
      double tv = rnd(-3.0, 3.0);
      double wv[4];
      // value and Jacobian columns
      for (int j = 0; j < prim->nin; ++j) {
        for (int i = 0; i < prim->nin; ++i)
          in[i] = dal_var(u[i], i == j ? 1.0 : 0.0);
        wv[0] = wv[1] = wv[2] = wv[3] = 0;
        compare(prim, e, in, dal_const(tv), param, wv);
        if (wv[0] > worst[0]) worst[0] = wv[0];
        if (wv[1] > worst[1]) worst[1] = wv[1];
      }
      // the time derivative
      for (int i = 0; i < prim->nin; ++i)
        in[i] = dal_const(u[i]);
      wv[0] = wv[1] = wv[2] = wv[3] = 0;
      compare(prim, e, in, dal_var(tv, 1.0), param, wv);
      if (wv[1] > worst[2]) worst[2] = wv[1];
      // a curve with curvature: second and third derivatives
      for (int i = 0; i < prim->nin; ++i)
        in[i] = dal_jet_make3(u[i], rnd(-1, 1), rnd(-1, 1), rnd(-1, 1));
      t = dal_jet_make3(tv, 1.0, 0.0, 0.0);
      wv[0] = wv[1] = wv[2] = wv[3] = 0;
      compare(prim, e, in, t, param, wv);
      for (int j = 0; j < 2; ++j)
        if (wv[2 + j] > worst[3 + j]) worst[3 + j] = wv[2 + j];
    }
    printf("%-16s %6d | %9.3f %9.3f %9.3f %9.3f %9.3f\n", prim->name, dal_expr_ninstructions(e),
           worst[0], worst[1], worst[2], worst[3], worst[4]);
    for (int j = 0; j < 5; ++j)
      CHECK_MSG(worst[j] <= 1.0, "%s: coefficient %d differs by %.3g tolerances", prim->name, j,
                worst[j]);
    dal_expr_destroy(e);
  }
}

// the message of a refused def contains every expected fragment
static void refused(const char *formula, const char *f1, const char *f2) {
  const char *inputs[] = {"theta"};
  const char *params[] = {"l"};
  dal_expr_def d = dal_default_expr_def();
  d.name = "bob";
  d.formulas = &formula;
  d.nout = 1;
  d.inputs = inputs;
  d.nin = 1;
  d.params = params;
  d.nparam = 1;
  dal_expr *e = (dal_expr *)&d; // must be reset to NULL
  char msg[512];
  int rc = dal_expr_create(&d, &e, msg, sizeof msg);
  CHECK_MSG(rc == DAL_E_ARG && e == NULL, "'%s' accepted", formula);
  CHECK_MSG(strstr(msg, f1) && strstr(msg, f2), "'%s': message '%s' lacks '%s' or '%s'", formula,
            msg, f1, f2);
}

static void errors(void) {
  refused("l*sin(thet)", "column 7", "unknown symbol 'thet'");
  refused("l*sin(theta", "column 12", "')' closing sin( of column 3");
  refused("l*sinus(theta)", "column 3", "unknown function 'sinus'");
  refused("l*sin(theta) +", "column 15", "end of the formula");
  refused("2 l", "column 3", "an operator expected, found 'l'");
  refused("l # 2", "column 3", "found '#'");
  refused("atan2(theta)", "column 12", "atan2 takes 2 arguments");
  refused("", "bob: formula 1", "column 1");
  char deep[1000];
  memset(deep, '(', 500);
  strcpy(deep + 500, "theta");
  refused(deep, "nested more than 200", "column");
  // names: twice, not a name, the time
  const char *in2[] = {"x", "x"};
  const char *f = "x";
  dal_expr_def d = dal_default_expr_def();
  d.formulas = &f;
  d.nout = 1;
  d.inputs = in2;
  d.nin = 2;
  dal_expr *e = NULL;
  char msg[512];
  CHECK(dal_expr_create(&d, &e, msg, sizeof msg) == DAL_E_ARG && strstr(msg, "'x' is given twice"));
  const char *in3[] = {"t"};
  d.inputs = in3;
  d.nin = 1;
  CHECK(dal_expr_create(&d, &e, msg, sizeof msg) == DAL_E_ARG && strstr(msg, "'t' is the time"));
  const char *in4[] = {"2x"};
  d.inputs = in4;
  CHECK(dal_expr_create(&d, &e, msg, sizeof msg) == DAL_E_ARG && strstr(msg, "not a name"));
  dal_expr_def bad;
  memset(&bad, 0, sizeof bad);
  CHECK(dal_expr_create(&bad, &e, msg, sizeof msg) == DAL_E_ARG &&
        strstr(msg, "dal_default_expr_def"));
  // a domain error at run time, named by dal_expr_check
  const char *g = "sqrt(l) + log(x - 1)";
  const char *in1[] = {"x"};
  const char *par[] = {"l"};
  double val = 2.0;
  d.inputs = in1;
  d.formulas = &g;
  d.params = par;
  d.values = &val;
  d.nparam = 1;
  d.name = "logger";
  CHECK_OK(dal_expr_create(&d, &e, msg, sizeof msg));
  dal_jet x = dal_var(0.5, 1.0), out;
  CHECK(dal_expr_check(e, &x, dal_const(0), NULL, &out, msg, sizeof msg) == DAL_E_DOMAIN);
  CHECK_MSG(strstr(msg, "logger: formula 1") && strstr(msg, "column 11") && strstr(msg, "'log'"),
            "%s", msg);
  x = dal_var(1.5, 1.0);
  CHECK(dal_expr_check(e, &x, dal_const(0), NULL, &out, msg, sizeof msg) == DAL_OK);
  CHECK_CLOSE(out.v, sqrt(2.0) + log(0.5), 1e-15);
  CHECK_CLOSE(out.d, 2.0, 1e-15);
  // numbers, powers, signs: against the same arithmetic in C
  const char *h = "-x^2 + 2^-1*x**3 - 1.5e-1/x + pow(x, 0.5) + x^l + (-x)^3";
  d.formulas = &h;
  dal_expr_destroy(e);
  CHECK_OK(dal_expr_create(&d, &e, msg, sizeof msg));
  x = dal_var(1.7, 1.0);
  CHECK_OK(dal_expr_eval(e, &x, dal_const(0), NULL, &out));
  double xv = 1.7;
  CHECK_CLOSE(out.v, -xv * xv + 0.5 * xv * xv * xv - 0.15 / xv + sqrt(xv) + xv * xv - xv * xv * xv,
              1e-14);
  CHECK_CLOSE(out.d,
              -2 * xv + 1.5 * xv * xv + 0.15 / (xv * xv) + 0.5 / sqrt(xv) + 2 * xv - 3 * xv * xv,
              1e-14);
  dal_expr_destroy(e);
}

// ---------------------------------------------------------------------------------------------
// systems: the same scene through a C primitive and through an expression

static dal_system *pendulum_system(const dal_expr *e, double l, double a, double w) {
  dal_builder *b;
  dal_system *sys = NULL;
  int th, bob;
  dal_builder_create(2, &b);
  dal_builder_add_coord(b, "theta", &th);
  dal_builder_add_particle(b, "bob", 1.0, &bob);
  dal_place_def pd = dal_default_place_def();
  if (e) {
    CHECK_OK(dal_expr_place_def(e, &pd));
  } else {
    pd.prim = &dal_map_pendulum;
    pd.param[DAL_PENDULUM_L] = l;
    pd.param[DAL_PENDULUM_AY] = a;
    pd.param[DAL_PENDULUM_W] = w;
  }
  pd.coords = &th;
  pd.ncoords = 1;
  CHECK_OK(dal_builder_place_def(b, bob, &pd));
  double g[2] = {0, -9.8};
  dal_builder_set_gravity(b, g);
  int rc = dal_builder_compile(b, &sys);
  CHECK_MSG(rc == 0, "%s", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return sys;
}

static void run_to(const dal_system *sys, const char *override, double value, double q0, double T,
                   double *q) {
  dal_state *st;
  dal_state_create(sys, &st);
  if (override) CHECK_OK(dal_state_set_param_named(sys, st, override, value));
  double v0 = 0.0;
  CHECK_OK(dal_state_set(sys, st, 0.0, &q0, &v0));
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_BS;
  o.rtol = 1e-12;
  CHECK_OK(dal_advance(sys, st, &o, T));
  int n = dal_system_ncoords(sys);
  for (int i = 0; i < n; ++i) {
    q[i] = dal_state_q(st)[i];
    q[n + i] = dal_state_qdot(st)[i];
  }
  dal_state_destroy(st);
}

static void systems(void) {
  double g = 9.8, a = 0.1, w = 2 * sqrt(g);
  const char *inputs[] = {"theta"};
  const char *pf[] = {"l*sin(theta)", "a*cos(omega*t) - l*cos(theta)"};
  const char *pp[] = {"l", "a", "omega"};
  double pv[] = {1.0, a, w};
  dal_expr_def d = dal_default_expr_def();
  d.name = "driven";
  d.formulas = pf;
  d.nout = 2;
  d.inputs = inputs;
  d.nin = 1;
  d.params = pp;
  d.values = pv;
  d.nparam = 3;
  dal_expr *e;
  char msg[512];
  CHECK_OK(dal_expr_create(&d, &e, msg, sizeof msg));
  dal_system *sc = pendulum_system(NULL, 1.0, a, w), *se = pendulum_system(e, 0, 0, 0);
  // the same state, the same Jacobian and curvature term
  dal_state *s1, *s2;
  dal_state_create(sc, &s1);
  dal_state_create(se, &s2);
  double q = 0.7, v = -1.3;
  dal_state_set(sc, s1, 0.4, &q, &v);
  dal_state_set(se, s2, 0.4, &q, &v);
  CHECK_OK(dal_forward(sc, s1));
  CHECK_OK(dal_forward(se, s2));
  double J1[2], J2[2];
  CHECK_OK(dal_state_jacobian(sc, s1, 0, J1));
  CHECK_OK(dal_state_jacobian(se, s2, 0, J2));
  for (int i = 0; i < 2; ++i) {
    CHECK_CLOSE(dal_state_positions(s2)[i], dal_state_positions(s1)[i], 4e-16);
    CHECK_CLOSE(dal_state_velocities(s2)[i], dal_state_velocities(s1)[i], 4e-15);
    CHECK_CLOSE(J2[i], J1[i], 4e-16);
    CHECK_CLOSE(dal_state_gamma(s2)[i], dal_state_gamma(s1)[i], 4e-15);
  }
  CHECK_CLOSE(dal_state_qddot(s2)[0], dal_state_qddot(s1)[0], 4e-15);
  dal_state_destroy(s1);
  dal_state_destroy(s2);
  // trajectories to t = 10 (rtol 1e-12); the two routes differ by rounding only, which the
  // flow amplifies by at most ~e^(0.5 t) before t = 10 (the orbits part near t = 70)
  double y1[2], y2[2];
  run_to(sc, NULL, 0, 1.0, 10.0, y1);
  run_to(se, NULL, 0, 1.0, 10.0, y2);
  printf("driven pendulum at t = 10: C %.15f %.15f, expression %.15f %.15f\n", y1[0], y1[1], y2[0],
         y2[1]);
  CHECK_CLOSE(y2[0], y1[0], 1e-10);
  CHECK_CLOSE(y2[1], y1[1], 1e-10);
  // a per-trajectory override: the pivot amplitude (C parameter ay = 4, expression a = 1)
  run_to(sc, "place:bob:4", 0.2, 1.0, 3.0, y1);
  run_to(se, "place:bob:1", 0.2, 1.0, 3.0, y2);
  CHECK_CLOSE(y2[0], y1[0], 1e-10);
  double y0[2];
  run_to(se, NULL, 0, 1.0, 3.0, y0);
  CHECK(fabs(y0[0] - y2[0]) > 1e-3); // the override changed the motion
  dal_system_destroy(sc);
  dal_system_destroy(se);
  dal_expr_destroy(e);

  // the harmonic oscillator as a Lagrangian expression: x(t) = cos(w t), w^2 = k/m
  const char *lf = "1/2*m*xdot^2 - 1/2*k*x^2";
  const char *li[] = {"x"};
  const char *lp[] = {"m", "k"};
  double lv[] = {2.0, 8.0};
  d = dal_default_expr_def();
  d.name = "oscillator";
  d.formulas = &lf;
  d.nout = 1;
  d.inputs = li;
  d.nin = 1;
  d.velocities = 1;
  d.params = lp;
  d.values = lv;
  d.nparam = 2;
  CHECK_OK(dal_expr_create(&d, &e, msg, sizeof msg));
  dal_builder *b;
  dal_builder_create(0, &b);
  dal_builder_add_coord(b, "x", NULL);
  CHECK_OK(dal_builder_set_lagrangian(b, dal_expr_lagrangian, e));
  dal_system *sl;
  CHECK_OK(dal_builder_compile(b, &sl));
  dal_builder_destroy(b);
  run_to(sl, NULL, 0, 1.0, 10.0, y1);
  CHECK_CLOSE(y1[0], cos(2.0 * 10.0), 1e-10);
  CHECK_CLOSE(y1[1], -2.0 * sin(2.0 * 10.0), 1e-10);
  dal_system_destroy(sl);
  dal_expr_destroy(e);
}

int main(void) {
  primitives_as_expressions();
  errors();
  systems();
  return check_summary("test_expr");
}
