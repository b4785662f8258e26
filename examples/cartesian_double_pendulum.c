// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Double pendulum in Cartesian coordinates (4 coordinates, 2 rods) against the minimal one.
//
// Problem: masses m1 = 1, m2 = 0.5 on massless rods l1 = 1 (to the origin) and l2 = 0.7
// (between the masses), gravity g = 9.81, released at theta1 = 2.0, theta2 = 2.5 (from the
// downward vertical) at rest: a large-amplitude, chaotic motion. Redundant coordinates
// (x1, y1, x2, y2) with the rods dal_con_anchor2 and dal_con_distance2, formulation GGL in
// IDA (the default) at rtol 1e-10. Reference: the same scene in minimal coordinates (theta1,
// theta2) by dal_map_pendulum and dal_map_hanging, integrated by Bulirsch-Stoer at 1e-13.
//
// Checks (both modes): positions agree with the minimal run to 1000 x rtol over the first
// 2 s (the motion is chaotic: the difference grows like the perturbation of an unstable orbit
// later); the rod forces dal_constraint_forces equal the minimal run's reactions N_k =
// m_k a_k - F_k; each rod's multiplier reproduces the rod tension; energy is conserved and
// the residuals stay below rtol (the level of IDA's Newton tolerance). --check runs 2 s, the
// full mode 10 s with a table.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "example_util.h"

static const double g = 9.81, l1 = 1.0, l2 = 0.7, m1 = 1.0, m2 = 0.5;

static int build(int cartesian, dal_system **sys) {
  dal_builder *b = NULL;
  int p[2], rc = dal_builder_create(2, &b);
  double grav[2] = {0.0, -g};
  if (!rc) rc = dal_builder_add_particle(b, "upper", m1, &p[0]);
  if (!rc) rc = dal_builder_add_particle(b, "lower", m2, &p[1]);
  if (!rc) rc = dal_builder_set_gravity(b, grav);
  if (cartesian) {
    int c[4];
    const char *names[4] = {"x1", "y1", "x2", "y2"};
    for (int i = 0; i < 4 && !rc; ++i)
      rc = dal_builder_add_coord(b, names[i], &c[i]);
    dal_place_def pd = dal_default_place_def();
    pd.prim = &dal_map_cartesian2;
    pd.ncoords = 2;
    pd.coords = c;
    if (!rc) rc = dal_builder_place_def(b, p[0], &pd);
    pd.coords = c + 2;
    if (!rc) rc = dal_builder_place_def(b, p[1], &pd);
    dal_constraint_def cd = dal_default_constraint_def(); // to the fixed pivot at the origin
    cd.name = "rod1";
    cd.prim = &dal_con_anchor2;
    cd.parts = &p[0];
    cd.nparts = 1;
    cd.param[DAL_ANCHOR_L] = l1;
    if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
    cd = dal_default_constraint_def();
    cd.name = "rod2";
    cd.prim = &dal_con_distance2;
    cd.parts = p;
    cd.nparts = 2;
    cd.param[DAL_DISTANCE_L] = l2;
    if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
  } else {
    int th[2];
    if (!rc) rc = dal_builder_add_coord(b, "theta1", &th[0]);
    if (!rc) rc = dal_builder_add_coord(b, "theta2", &th[1]);
    dal_place_def pd = dal_default_place_def(); // pivot fixed at the origin
    pd.prim = &dal_map_pendulum;
    pd.coords = &th[0];
    pd.ncoords = 1;
    pd.param[DAL_PENDULUM_L] = l1;
    if (!rc) rc = dal_builder_place_def(b, p[0], &pd);
    pd = dal_default_place_def();
    pd.prim = &dal_map_hanging;
    pd.parent = p[0];
    pd.coords = &th[1];
    pd.ncoords = 1;
    pd.param[DAL_HANGING_L] = l2;
    if (!rc) rc = dal_builder_place_def(b, p[1], &pd);
  }
  *sys = ex_compile(b, rc);
  return !*sys;
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0;
  double T = check ? 2.0 : 10.0, dt = check ? 0.25 : 0.5, tol = 1e-10;
  dal_system *ms = NULL, *cs = NULL;
  dal_state *a = NULL, *b = NULL;
  if (build(0, &ms) || build(1, &cs) || dal_state_create(ms, &a) || dal_state_create(cs, &b))
    return 1;
  // the same initial state: minimal angles -> particle positions and velocities
  double th[2] = {2.0, 2.5}, thd[2] = {0.0, 0.0}, q[4], qd[4];
  if (dal_state_set(ms, a, 0.0, th, thd) || dal_forward(ms, a)) return 1;
  memcpy(q, dal_state_positions(a), sizeof q);
  memcpy(qd, dal_state_velocities(a), sizeof qd);
  if (dal_state_set(cs, b, 0.0, q, qd) || dal_forward(cs, b)) return 1;
  dal_energies e0, e;
  dal_state_energies(b, &e0);
  dal_solve_opts om, od;
  om = dal_default_solve_opts();
  om.method = DAL_METHOD_BS;
  om.rtol = om.atol = 1e-13;
  od = dal_default_solve_opts(); // GGL in IDA
  od.rtol = od.atol = tol;
  double pmax = 0, fmaxd = 0, tmax = 0, rmax = 0, Emax = 0;
  if (!check)
    printf("    t    |r - r_min|  |F_c - N_min|  tension1  tension2   |phi|    |phidot|\n");
  for (int k = 1; k * dt <= T + 1e-12; ++k) {
    double t = k * dt;
    if (dal_advance(ms, a, &om, t) || dal_advance(cs, b, &od, t)) {
      printf("advance failed: %s %s\n", dal_state_errmsg(a), dal_state_errmsg(b));
      return 1;
    }
    const double *r = dal_state_positions(a), *x = dal_state_q(b), *N = dal_state_reactions(a);
    double F[4], dp = 0, df = 0;
    dal_constraint_forces(cs, b, F);
    for (int i = 0; i < 4; ++i) {
      dp = fmax(dp, fabs(x[i] - r[i]));
      df = fmax(df, fabs(F[i] - N[i]) / (m1 * g));
    }
    // tensions from the minimal run: the lower rod pulls the lower mass towards the upper
    // one with T2 = -N_2 . e2; the upper rod holds both: T1 = -(N_1 - T2 e2) . e1
    double e1[2] = {r[0] / l1, r[1] / l1}, e2[2] = {(r[2] - r[0]) / l2, (r[3] - r[1]) / l2};
    double T2 = -(N[2] * e2[0] + N[3] * e2[1]);
    double T1 = -((N[0] - T2 * e2[0]) * e1[0] + (N[1] - T2 * e2[1]) * e1[1]);
    const double *lam = dal_state_lambda(b);
    double dt12 = fmax(fabs(-lam[0] - T1), fabs(-lam[1] - T2)) / (m1 * g);
    double res = fmax(fmax(fabs(dal_state_phi(b)[0]), fabs(dal_state_phi(b)[1])),
                      fmax(fabs(dal_state_phidot(b)[0]), fabs(dal_state_phidot(b)[1])));
    dal_state_energies(b, &e);
    if (!check)
      printf("  %5.2f  %9.2e    %9.2e   %9.4f %9.4f  %8.1e  %8.1e\n", t, dp, df, -lam[0], -lam[1],
             fabs(dal_state_phi(b)[0]), fabs(dal_state_phidot(b)[0]));
    if (t <= 2.0 + 1e-12) {
      pmax = fmax(pmax, dp);
      fmaxd = fmax(fmaxd, df);
      tmax = fmax(tmax, dt12);
      Emax = fmax(Emax, fabs(e.E - e0.E) / (m1 * g * l1));
    }
    rmax = fmax(rmax, res);
  }
  printf("on [0, 2]: positions vs minimal %.2e (%.0f x rtol), constraint forces vs reactions "
         "%.2e, tensions %.2e, energy %.1e; residuals to t=%g %.1e\n",
         pmax, pmax / tol, fmaxd, tmax, Emax, T, rmax);
  int fails = 0;
  fails += ex_expect(pmax <= 1e3 * tol, "positions differ by %g", pmax);
  fails += ex_expect(fmaxd <= 1e4 * tol, "forces differ by %g m1 g", fmaxd);
  fails += ex_expect(tmax <= 1e4 * tol, "tensions differ by %g m1 g", tmax);
  fails += ex_expect(Emax <= 1e3 * tol, "energy drift %g", Emax);
  fails += ex_expect(rmax <= tol, "residual %g", rmax);
  dal_state_destroy(a);
  dal_state_destroy(b);
  dal_system_destroy(ms);
  dal_system_destroy(cs);
  return ex_verdict(fails, "OK");
}
