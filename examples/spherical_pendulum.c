// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Spherical pendulum: conical motion, conserved E and L_z, and the chart's pole.
//
// Problem: a bob of mass m = 1 on a rod of length l = 1 about a fixed pivot in 3D, gravity
// g = 9.81 along -z. Coordinates: polar angle theta from the downward vertical and azimuth phi
// (dal_map_spherical). Formulation: minimal-coordinate ODE by particles, and the Lagrangian
// L = m l^2/2 (theta'^2 + sin^2(theta) phi'^2) + m g l cos(theta); dal_advance (automatic
// method) at rtol 1e-11.
// Hand equations: theta'' = sin cos phi'^2 - (g/l) sin, phi'' = -2 cot(theta) theta' phi'.
// The conical pendulum keeps theta = theta0 when phi'^2 = g / (l cos theta0). E and the vertical
// angular momentum L_z = m l^2 sin^2(theta) phi' are conserved. At theta = 0 the chart is
// singular (phi moves no mass): the library refuses with DAL_E_SINGULAR naming 'phi' and
// suggests redundant coordinates.
// Checks (--check: one revolution and a 3 s run; full mode: 5 revolutions and 20 s):
//  1. particles, Lagrangian and the hand equations agree at sample states;
//  2. the conical motion keeps theta = theta0 and phi = phi' t;
//  3. in a generic run E and L_z are conserved;
//  4. dal_forward at the pole returns DAL_E_SINGULAR naming 'phi'.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "example_util.h"

static const double mass = 1.0, len = 1.0, grav = 9.81, rtol = 1e-11;
#define PI 3.14159265358979323846

static int lagrangian(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet T = dal_add(dal_sq(v[0]), dal_mul(dal_sq(dal_sin(q[0])), dal_sq(v[1])));
  *L = dal_add(dal_scale(T, 0.5 * mass * len * len), dal_scale(dal_cos(q[0]), mass * grav * len));
  return 0;
}

static dal_system *build(int lagrange) {
  dal_builder *b = NULL;
  int q[2], p, rc = dal_builder_create(3, &b);
  double g[3] = {0, 0, -grav};
  if (!rc) rc = dal_builder_add_coord(b, "theta", &q[0]);
  if (!rc) rc = dal_builder_add_coord(b, "phi", &q[1]);
  if (lagrange) {
    if (!rc) rc = dal_builder_set_lagrangian(b, lagrangian, NULL);
  } else {
    if (!rc) rc = dal_builder_add_particle(b, "bob", mass, &p);
    dal_place_def pd = dal_default_place_def(); // pivot at the origin
    pd.prim = &dal_map_spherical;
    pd.coords = q;
    pd.ncoords = 2;
    pd.param[DAL_SPHERICAL_L] = len;
    if (!rc) rc = dal_builder_place_def(b, p, &pd);
    if (!rc) rc = dal_builder_set_gravity(b, g);
  }
  return ex_compile(b, rc);
}

static double Lz(const dal_state *st) {
  double s = sin(dal_state_q(st)[0]);
  return mass * len * len * s * s * dal_state_qdot(st)[1];
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0, bad = 0;
  dal_system *sys = build(0), *lag = build(1);
  dal_state *st = NULL, *stl = NULL;
  if (ex_two_states(sys, lag, &st, &stl)) return 1;
  printf("spherical pendulum: m = %g, l = %g, g = %g (3D, n = %d)\n", mass, len, grav,
         dal_system_ncoords(sys));

  // 1. equations of motion at sample states
  double worst = 0;
  for (int i = 0; i < 6; ++i) {
    double q[2] = {0.3 + 0.45 * i, -2 + i}, v[2] = {1.2 - 0.5 * i, 0.8 + 0.3 * i};
    if (dal_state_set(sys, st, 0, q, v) || dal_forward(sys, st) ||
        dal_state_set(lag, stl, 0, q, v) || dal_forward(lag, stl)) {
      bad = 1;
      break;
    }
    double s = sin(q[0]), c = cos(q[0]);
    double ref[2] = {s * c * v[1] * v[1] - grav / len * s, -2 * c / s * v[0] * v[1]};
    double sc = grav / len + (v[0] * v[0] + v[1] * v[1]) / s;
    for (int j = 0; j < 2; ++j) {
      worst = fmax(worst, fabs(dal_state_qddot(st)[j] - ref[j]) / sc);
      worst = fmax(worst, fabs(dal_state_qddot(stl)[j] - ref[j]) / sc);
    }
  }
  printf("  particles / Lagrangian / hand equations: max rel difference %.1e\n", worst);
  bad |= !(worst <= 1e-13);

  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = o.atol = rtol;

  // 2. conical pendulum
  double th0 = 0.6, wphi = sqrt(grav / (len * cos(th0))), Trev = 2 * PI / wphi;
  double q[2] = {th0, 0.0}, v[2] = {0.0, wphi};
  int revs = check ? 1 : 5, rc = dal_state_set(sys, st, 0.0, q, v);
  double dth = 0, dphi = 0;
  for (int i = 1; !rc && i <= 4 * revs; ++i) {
    rc = dal_advance(sys, st, &o, i * Trev / 4);
    if (rc) break;
    dth = fmax(dth, fabs(dal_state_q(st)[0] - th0));
    dphi = fmax(dphi, fabs(dal_state_q(st)[1] - wphi * i * Trev / 4));
  }
  if (rc) printf("  integration failed: %s\n", dal_state_errmsg(st));
  printf("  conical motion at theta0 = %g, phi' = %.12f, %d revolution(s) of %.10f s: max "
         "|theta - theta0| = %.1e, max |phi - phi' t| = %.1e\n",
         th0, wphi, revs, Trev, dth, dphi);
  bad |= rc != 0 || !(dth <= 1e-8) || !(dphi <= 1e-7 * revs);

  // 3. a generic run: E and L_z conserved
  double qg[2] = {1.0, 0.0}, vg[2] = {0.5, 2.0}, tend = check ? 3.0 : 20.0;
  double E0 = 0, L0 = 0, dE = 0, dL = 0, thmin = 10, thmax = -10;
  rc = dal_state_set(sys, st, 0.0, qg, vg);
  if (!rc) rc = dal_forward(sys, st);
  for (int i = 0; !rc && i <= (int)(tend / 0.1 + 0.5); ++i) {
    if (i) rc = dal_advance(sys, st, &o, 0.1 * i);
    if (rc) break;
    dal_energies e;
    dal_state_energies(st, &e);
    if (i == 0) {
      E0 = e.E;
      L0 = Lz(st);
    }
    dE = fmax(dE, fabs(e.E - E0));
    dL = fmax(dL, fabs(Lz(st) - L0));
    thmin = fmin(thmin, dal_state_q(st)[0]);
    thmax = fmax(thmax, dal_state_q(st)[0]);
    if (!check && i % 20 == 0)
      printf("    t = %5.1f  theta = %.8f  phi = %+12.8f  E = %.12f  L_z = %.12f\n", 0.1 * i,
             dal_state_q(st)[0], dal_state_q(st)[1], e.E, Lz(st));
  }
  if (rc) printf("  integration failed: %s\n", dal_state_errmsg(st));
  printf("  generic run to t = %g: theta in [%.6f, %.6f]; drift of E %.1e, of L_z %.1e\n", tend,
         thmin, thmax, dE, dL);
  bad |= rc != 0 || !(dE <= 1000 * rtol * mass * grav * len) || !(dL <= 1000 * rtol * L0);

  // 4. the pole of the chart
  double qp[2] = {0.0, 0.3}, vp[2] = {1.0, 0.0};
  rc = dal_state_set(sys, st, 0.0, qp, vp);
  if (!rc) rc = dal_forward(sys, st);
  printf("  at theta = 0: %s: %s\n", dal_status_name(rc), dal_state_errmsg(st));
  bad |= rc != DAL_E_SINGULAR || !strstr(dal_state_errmsg(st), "'phi'");

  dal_state_destroy(st);
  dal_state_destroy(stl);
  dal_system_destroy(sys);
  dal_system_destroy(lag);
  return ex_verdict(bad, "ok");
}
