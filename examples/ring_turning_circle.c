// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Bead on a rotating ring as a free particle held on a turning circle (time-dependent DAE).
//
// Problem (Likharev, Essential Graduate Physics CM 2.1; Goldstein 2.7): a bead of mass m = 1
// on a ring of radius R = 1 turning about its vertical diameter at omega = 5 rad/s (above the
// critical rate sqrt(g/R), g = 9.8), released at theta0 = 0.3 from the bottom at rest relative
// to the ring. Coordinates: the bead's Cartesian (x, y, z); constraint: the turning circle
// dal_con_turning_circle (2 rows: in the ring's turning plane, at distance R from the centre),
// explicit in time. Formulation: GGL in IDA at rtol 1e-10. References: the same scene in the
// minimal coordinate theta (dal_map_ring) by Bulirsch-Stoer at 1e-13, and the Jacobi
// integral of the rotating ring written in Cartesian terms, h = E - omega L_z (the energy in
// the ring's frame), which is conserved while E = T + U is not (the drive does work).
//
// Checks (both modes): positions agree with the minimal run to 1000 x rtol on [0, 2]; h is
// conserved to 1000 x rtol while E changes by more than 1e6 times as much; the bead oscillates
// about the off-centre equilibrium theta* = acos(g / (R omega^2)) (theta stays on one side of 0 and
// its extremes straddle theta*); the residuals stay below rtol. --check runs 2 s, the full mode 10
// s with a table.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "example_util.h"

static const double g = 9.8, R = 1.0, mass = 1.0, omega = 5.0;

static int build(int cartesian, dal_system **sys) {
  dal_builder *b = NULL;
  int bead, rc = dal_builder_create(3, &b);
  double grav[3] = {0, 0, -g};
  if (!rc) rc = dal_builder_add_particle(b, "bead", mass, &bead);
  if (!rc) rc = dal_builder_set_gravity(b, grav);
  if (cartesian) {
    int c[3];
    const char *names[3] = {"x", "y", "z"};
    for (int i = 0; i < 3 && !rc; ++i)
      rc = dal_builder_add_coord(b, names[i], &c[i]);
    dal_place_def pd = dal_default_place_def();
    pd.prim = &dal_map_cartesian3;
    pd.coords = c;
    pd.ncoords = 3;
    if (!rc) rc = dal_builder_place_def(b, bead, &pd);
    dal_constraint_def cd = dal_default_constraint_def(); // centred at the origin, angle 0 at t = 0
    cd.name = "ring";
    cd.prim = &dal_con_turning_circle;
    cd.parts = &bead;
    cd.nparts = 1;
    cd.param[DAL_TURNING_CIRCLE_R] = R;
    cd.param[DAL_TURNING_CIRCLE_W] = omega;
    if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
  } else {
    int th;
    if (!rc) rc = dal_builder_add_coord(b, "theta", &th);
    dal_place_def pd = dal_default_place_def(); // the same ring: plane at angle 0 at t = 0
    pd.prim = &dal_map_ring;
    pd.coords = &th;
    pd.ncoords = 1;
    pd.param[DAL_RING_R] = R;
    pd.param[DAL_RING_W] = omega;
    if (!rc) rc = dal_builder_place_def(b, bead, &pd);
  }
  *sys = ex_compile(b, rc);
  return !*sys;
}

// h = E - omega L_z from the Cartesian state
static double jacobi(const dal_state *st) {
  const double *r = dal_state_q(st), *v = dal_state_qdot(st);
  dal_energies e;
  dal_state_energies(st, &e);
  return e.E - omega * mass * (r[0] * v[1] - r[1] * v[0]);
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0;
  double T = check ? 2.0 : 10.0, dt = 0.05, tol = 1e-10;
  dal_system *ms = NULL, *cs = NULL;
  dal_state *a = NULL, *b = NULL;
  if (build(0, &ms) || build(1, &cs) || dal_state_create(ms, &a) || dal_state_create(cs, &b))
    return 1;
  double th0 = 0.3, thd0 = 0.0, q[3], qd[3];
  if (dal_state_set(ms, a, 0.0, &th0, &thd0) || dal_forward(ms, a)) return 1;
  memcpy(q, dal_state_positions(a), sizeof q);
  memcpy(qd, dal_state_velocities(a), sizeof qd);
  if (dal_state_set(cs, b, 0.0, q, qd) || dal_forward(cs, b)) return 1;
  double h0 = jacobi(b), E0, thmin = th0, thmax = th0, pmax = 0, hmax = 0, Emax = 0, rmax = 0;
  dal_energies e;
  dal_state_energies(b, &e);
  E0 = e.E;
  dal_solve_opts om, od;
  om = dal_default_solve_opts();
  om.method = DAL_METHOD_BS;
  om.rtol = om.atol = 1e-13;
  od = dal_default_solve_opts();
  od.rtol = od.atol = tol;
  if (!check) printf("    t     theta    |r - r_min|  h - h0      E - E0    |phi|\n");
  int steps = (int)(T / dt + 0.5);
  for (int k = 1; k <= steps; ++k) {
    double t = k * dt;
    if (dal_advance(ms, a, &om, t) || dal_advance(cs, b, &od, t)) {
      printf("advance failed: %s %s\n", dal_state_errmsg(a), dal_state_errmsg(b));
      return 1;
    }
    const double *r = dal_state_positions(a), *x = dal_state_q(b);
    double dp = 0;
    for (int i = 0; i < 3; ++i)
      dp = fmax(dp, fabs(x[i] - r[i]));
    double th = atan2(hypot(x[0], x[1]), -x[2]); // polar angle from the bottom, >= 0
    // the sign of theta: the side of the axis along the ring's horizontal direction
    if (x[0] * cos(omega * t) + x[1] * sin(omega * t) < 0) th = -th;
    thmin = fmin(thmin, th);
    thmax = fmax(thmax, th);
    dal_state_energies(b, &e);
    double dh = jacobi(b) - h0, dE = e.E - E0;
    double res = 0;
    for (int i = 0; i < 2; ++i)
      res = fmax(res, fmax(fabs(dal_state_phi(b)[i]), fabs(dal_state_phidot(b)[i])));
    if (t <= 2.0 + 1e-12) pmax = fmax(pmax, dp); // the global error grows with time
    hmax = fmax(hmax, fabs(dh));
    Emax = fmax(Emax, fabs(dE));
    rmax = fmax(rmax, res);
    if (!check && k % 10 == 0)
      printf("  %5.2f  %8.5f  %9.2e  %10.2e  %10.3e  %8.1e\n", t, th, dp, dh, dE, res);
  }
  double thstar = acos(g / (R * omega * omega));
  printf("positions vs minimal on [0, 2] %.2e (%.0f x rtol); Jacobi integral h drifts %.1e while E "
         "varies "
         "%.3g; theta in [%.4f, %.4f] about theta* = %.4f; residuals %.1e\n",
         pmax, pmax / tol, hmax, Emax, thmin, thmax, thstar, rmax);
  int fails = 0;
  fails += ex_expect(pmax <= 1e3 * tol, "positions differ by %g", pmax);
  fails += ex_expect(hmax <= 1e3 * tol, "h drifts by %g", hmax);
  fails += ex_expect(Emax > 1e6 * hmax, "E should vary, by %g only", Emax);
  fails += ex_expect(thmin > 0 && thmin < thstar && thmax > thstar,
                     "theta range [%g, %g] does not straddle %g", thmin, thmax, thstar);
  fails += ex_expect(rmax <= tol, "residual %g", rmax);
  dal_state_destroy(a);
  dal_state_destroy(b);
  dal_system_destroy(ms);
  dal_system_destroy(cs);
  return ex_verdict(fails, "OK");
}
