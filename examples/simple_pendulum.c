// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Simple pendulum at large amplitude against the elliptic-integral closed form.
//
// Problem: a bob of mass m = 1 on a massless rod of length l = 1 about a fixed pivot, gravity
// g = 9.81, released from rest at theta0. Coordinate: theta from the downward vertical
// (dal_map_pendulum). Formulation: minimal-coordinate ODE, dal_advance (automatic method)
// at rtol 1e-11.
// Closed form: with k = sin(theta0/2) and K(k) the complete elliptic integral of the first
// kind (here by the arithmetic-geometric mean, K = pi / (2 AGM(1, sqrt(1 - k^2)))), the
// period is T = 4 K sqrt(l/g); theta = 0 at T/4 with thetadot = -2 k sqrt(g/l), theta = -theta0
// at rest at T/2, and theta = theta0 again at T. At the bottom the rod pulls the bob up with
// the force m g (3 - 2 cos theta0).
// Checks (--check: theta0 = 2.0 and 3.0; full mode: a table over amplitudes):
//  1. theta'' = -g/l sin(theta) at sample states;
//  2. the states at T/4, T/2, T match the closed form; the rod force at T/4 matches;
//  3. energy is conserved.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "example_util.h"

static const double mass = 1.0, len = 1.0, grav = 9.81, rtol = 1e-11;
#define PI 3.14159265358979323846

// complete elliptic integral of the first kind K(k) by the arithmetic-geometric mean
static double ellipk(double k) {
  double a = 1.0, b = sqrt(1.0 - k * k);
  for (int i = 0; i < 40 && fabs(a - b) > 1e-16 * a; ++i) {
    double an = 0.5 * (a + b);
    b = sqrt(a * b);
    a = an;
  }
  return PI / (2.0 * a);
}

// advance to t and return the worst of the errors against (theta, thetadot)
static double advance_err(const dal_system *sys, dal_state *st, const dal_solve_opts *o, double t,
                          double th, double thd, int *bad) {
  if (dal_advance(sys, st, o, t)) {
    printf("advance failed: %s\n", dal_state_errmsg(st));
    *bad = 1;
    return INFINITY;
  }
  double e1 = fabs(dal_state_q(st)[0] - th), e2 = fabs(dal_state_qdot(st)[0] - thd);
  return fmax(e1, e2 / sqrt(grav / len));
}

static int run(const dal_system *sys, dal_state *st, double th0, int verbose) {
  int bad = 0;
  double kk = sin(th0 / 2), K = ellipk(kk), T = 4 * K * sqrt(len / grav), z = 0.0;
  double T0 = 2 * PI * sqrt(len / grav);
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = o.atol = rtol;
  if (dal_state_set(sys, st, 0.0, &th0, &z) || dal_forward(sys, st)) {
    printf("set failed: %s\n", dal_state_errmsg(st));
    return 1;
  }
  dal_energies e0, e1;
  dal_state_energies(st, &e0);
  double vb = -2 * kk * sqrt(grav / len);
  double err4 = advance_err(sys, st, &o, T / 4, 0.0, vb, &bad);
  // the rod force at the bottom: straight up, m g (3 - 2 cos theta0)
  const double *N = dal_state_reactions(st);
  double Nref = mass * grav * (3 - 2 * cos(th0));
  double errN = fabs(N[1] - Nref) + fabs(N[0]);
  double err2 = advance_err(sys, st, &o, T / 2, -th0, 0.0, &bad);
  double err1 = advance_err(sys, st, &o, T, th0, 0.0, &bad);
  dal_state_energies(st, &e1);
  double dE = fabs(e1.E - e0.E) / (mass * grav * len);
  double err = fmax(err4, fmax(err2, err1));
  if (verbose)
    printf("  %5.2f  %.12f  %8.5f  %8.1e  %8.1e  %10.6f  %8.1e\n", th0, T, T / T0, err, dE, Nref,
           errN / Nref);
  // the error grows like the period's sensitivity to theta0 near the separatrix
  double allow = 1000 * rtol / (1 - kk * kk);
  bad |= !(err <= allow) || !(dE <= 100 * rtol) || !(errN <= 1e-6 * Nref);
  return bad;
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0, bad = 0;
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  int th, bob, rc = dal_builder_create(2, &b);
  double g[2] = {0, -grav};
  if (!rc) rc = dal_builder_add_coord(b, "theta", &th);
  if (!rc) rc = dal_builder_add_particle(b, "bob", mass, &bob);
  dal_place_def pd = dal_default_place_def(); // pivot fixed at the origin
  pd.prim = &dal_map_pendulum;
  pd.coords = &th;
  pd.ncoords = 1;
  pd.param[DAL_PENDULUM_L] = len;
  if (!rc) rc = dal_builder_place_def(b, bob, &pd);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  if (!rc) rc = dal_builder_compile(b, &sys);
  if (rc) printf("build failed: %s\n", dal_builder_errmsg(b));
  if (!rc) rc = dal_state_create(sys, &st);
  bad = rc != 0;
  if (!bad) {
    printf("simple pendulum: m = %g, l = %g, g = %g (n = %d coordinate, %dD)\n", mass, len, grav,
           dal_system_ncoords(sys), dal_system_dim(sys));
    // 1. the equation of motion at sample states
    for (int i = 0; i < 4; ++i) {
      double q = -2.5 + 1.6 * i, qd = 1.0 - 0.5 * i;
      if (dal_state_set(sys, st, 0.0, &q, &qd) || dal_forward(sys, st)) {
        bad = 1;
        continue;
      }
      double a = dal_state_qddot(st)[0], ref = -grav / len * sin(q);
      printf("  theta = %5.2f: theta'' = %.15g (hand %.15g)\n", q, a, ref);
      bad |= !(fabs(a - ref) <= 1e-14 * grav);
    }
    // 2./3. the motion over one period against the closed form
    printf("  theta0  period T (closed form)  T/T_small  state err  energy err  rod force "
           "m g (3 - 2 cos)  rel err\n");
    const double amps_check[] = {2.0, 3.0};
    const double amps_full[] = {0.1, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.1};
    const double *amps = check ? amps_check : amps_full;
    int na = check ? 2 : 8;
    for (int i = 0; i < na; ++i)
      bad |= run(sys, st, amps[i], 1);
  }
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
  return ex_verdict(bad, "ok");
}
