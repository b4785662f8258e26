// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Bead on a rotating ring: equilibria, small-oscillation frequencies, Jacobi integral, reaction.
//
// Problem: a bead of mass m = 1 slides without friction on a ring of radius R = 1 turning about
// its vertical diameter at the constant rate w, gravity g = 9.81 (Goldstein sec. 2.7; Likharev
// CM 2.1). Coordinate: theta, the polar angle from the ring's bottom (dal_map_ring, 3D).
// Equation of motion (convention of dal_map_ring): theta'' = sin(theta) (w^2 cos(theta) - g/R).
// Below w_c = sqrt(g/R) the bottom is the stable equilibrium, with small oscillations at
// Omega^2 = g/R - w^2; above it the bead settles at cos(theta*) = g/(R w^2) and oscillates at
// Omega^2 = w^2 sin^2(theta*). The ring holds the bead with the force
// N = -m (R (theta'^2 + w^2 sin^2) + g cos) n + 2 m w R cos(theta) theta' e_phi, where n is the
// outward normal in the ring's plane and e_phi the direction of the ring's motion; N has no
// component along the ring.
// Formulation: minimal-coordinate ODE (particle route) and the Lagrangian
// L = m R^2/2 (theta'^2 + w^2 sin^2 theta) + m g R cos theta; dal_advance at rtol 1e-11.
// Checks (both modes; the full mode prints more w):
//  1. both routes give the equation of motion at sample states; theta'' = 0 at the equilibria;
//  2. a small oscillation (amplitude 1e-4) returns after one period 2 pi / Omega;
//  3. over a large-amplitude run the Jacobi integral h is conserved while E is not, and the
//     reaction force matches the closed form at every output time.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "example_util.h"

static const double mass = 1.0, R = 1.0, grav = 9.81, rtol = 1e-11;
#define PI 3.14159265358979323846

typedef struct ring {
  double w;
  dal_system *sys, *lag;
  dal_state *st, *stl;
} ring;

static int lagrangian(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)t;
  double w = *(const double *)ctx;
  dal_jet s = dal_sin(q[0]);
  dal_jet T = dal_scale(dal_add(dal_sq(v[0]), dal_scale(dal_sq(s), w * w)), 0.5 * mass * R * R);
  *L = dal_add(T, dal_scale(dal_cos(q[0]), mass * grav * R));
  return 0;
}

static int build(ring *r) {
  r->sys = ex_ring_bead(mass, R, r->w, grav); // the built-in map
  dal_builder *b = NULL;                      // the same bead from its Lagrangian
  int rc = dal_builder_create(3, &b);
  if (!rc) rc = dal_builder_add_coord(b, "theta", NULL);
  if (!rc) rc = dal_builder_set_lagrangian(b, lagrangian, &r->w);
  r->lag = ex_compile(b, rc);
  if (!r->sys || !r->lag) return 1;
  rc = dal_state_create(r->sys, &r->st);
  if (!rc) rc = dal_state_create(r->lag, &r->stl);
  return rc;
}

static void destroy(ring *r) {
  dal_state_destroy(r->st);
  dal_state_destroy(r->stl);
  dal_system_destroy(r->sys);
  dal_system_destroy(r->lag);
}

// theta'' from both routes at (t, theta, thetadot); returns the worst error against the hand EOM
static double eom_err(ring *r, double t, double th, double thd) {
  if (dal_state_set(r->sys, r->st, t, &th, &thd) || dal_forward(r->sys, r->st) ||
      dal_state_set(r->lag, r->stl, t, &th, &thd) || dal_forward(r->lag, r->stl))
    return INFINITY;
  double ref = sin(th) * (r->w * r->w * cos(th) - grav / R);
  return fmax(fabs(dal_state_qddot(r->st)[0] - ref), fabs(dal_state_qddot(r->stl)[0] - ref));
}

// reaction force error against the closed form at the state's current evaluation
static double reaction_err(const ring *r) {
  double t = dal_state_time(r->st), th = dal_state_q(r->st)[0], thd = dal_state_qdot(r->st)[0];
  double w = r->w, sn = sin(th), cs = cos(th), ph = w * t, cp = cos(ph), sp = sin(ph);
  double n[3] = {sn * cp, sn * sp, -cs}, ef[3] = {-sp, cp, 0}, tg[3] = {cs * cp, cs * sp, sn};
  double Nn = -mass * (R * (thd * thd + w * w * sn * sn) + grav * cs);
  double Nf = 2 * mass * w * R * cs * thd;
  const double *N = dal_state_reactions(r->st);
  double err = 0, along = 0;
  for (int a = 0; a < 3; ++a) {
    err = fmax(err, fabs(N[a] - (Nn * n[a] + Nf * ef[a])));
    along += N[a] * tg[a];
  }
  return fmax(err, fabs(along));
}

static int study(double w, int verbose) {
  ring r = {w, NULL, NULL, NULL, NULL};
  int bad = build(&r) != 0;
  if (bad) {
    destroy(&r);
    return 1;
  }
  double wc = sqrt(grav / R), thstar = w > wc ? acos(grav / (R * w * w)) : 0.0;
  double Om2 = w > wc ? w * w * sin(thstar) * sin(thstar) : grav / R - w * w;
  printf("w = %.3f w_c: equilibrium theta* = %.12f, small oscillations Omega = %.12f\n", w / wc,
         thstar, sqrt(Om2));
  // 1. equation of motion at sample states, and equilibria
  double worst = 0;
  for (int i = 0; i < 6; ++i)
    worst = fmax(worst, eom_err(&r, 0.3 * i, -2.5 + i, 1.5 - 0.6 * i));
  double eq = fabs(eom_err(&r, 0.7, thstar, 0.0));
  double eq_acc = fabs(dal_state_qddot(r.st)[0]);
  printf("  theta'' vs sin(theta)(w^2 cos(theta) - g/R), both routes: max error %.1e; at theta* "
         "theta'' = %.1e\n",
         worst, eq_acc);
  bad |= !(worst <= 1e-13) || !(eq <= 1e-13) || !(eq_acc <= 1e-13);

  // 2. a small oscillation returns after 2 pi / Omega
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = o.atol = rtol;
  double eps = 1e-4, th0 = thstar + eps, z = 0.0, T = 2 * PI / sqrt(Om2);
  int rc = dal_state_set(r.sys, r.st, 0.0, &th0, &z);
  if (!rc) rc = dal_advance(r.sys, r.st, &o, T / 2);
  double half = dal_state_q(r.st)[0] - thstar;
  if (!rc) rc = dal_advance(r.sys, r.st, &o, T);
  double full = dal_state_q(r.st)[0] - thstar;
  printf("  small oscillation (amplitude %.0e): theta - theta* = %.8e at T/2, %.8e at T = %.6f\n",
         eps, half, full, T);
  // nonlinear corrections are O(eps^2), integration errors O(rtol)
  bad |= rc != 0 || !(fabs(half + eps) <= 1e-3 * eps) || !(fabs(full - eps) <= 1e-3 * eps);

  // 3. a large-amplitude run: h conserved, E not; reaction force along the way
  double thL = thstar + 1.0, thdL = 0.5, h0 = 0, hmax = 0, Emin = 1e300, Emax = -1e300, Nerr = 0;
  rc = dal_state_set(r.sys, r.st, 0.0, &thL, &thdL);
  if (!rc) rc = dal_forward(r.sys, r.st);
  for (int i = 0; !rc && i <= 40; ++i) {
    if (i) rc = dal_advance(r.sys, r.st, &o, 0.05 * i);
    if (rc) break;
    dal_energies e;
    dal_state_energies(r.st, &e);
    double th = dal_state_q(r.st)[0], thd = dal_state_qdot(r.st)[0], sn = sin(th);
    double hh = 0.5 * mass * R * R * (thd * thd - w * w * sn * sn) - mass * grav * R * cos(th);
    if (i == 0) h0 = e.h;
    hmax = fmax(hmax, fmax(fabs(e.h - h0), fabs(e.h - hh)));
    Emin = fmin(Emin, e.E);
    Emax = fmax(Emax, e.E);
    Nerr = fmax(Nerr, reaction_err(&r));
    if (verbose && i % 10 == 0)
      printf("    t = %4.2f  theta = %10.6f  h = %.12f  E = %.9f\n", 0.05 * i, th, e.h, e.E);
  }
  if (rc) printf("  integration failed: %s\n", dal_state_errmsg(r.st));
  printf("  2 s from theta* + 1: h drift %.1e, E varies by %.3e; reaction force error %.1e\n", hmax,
         Emax - Emin, Nerr);
  bad |= rc != 0 || !(hmax <= 1e-8) || !(Nerr <= 1e-8 * (1 + w * w));
  if (w > 0.1 * wc) bad |= !(Emax - Emin > 1e4 * hmax); // the drive does work on the bead
  destroy(&r);
  return bad;
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0, bad = 0;
  double wc = sqrt(grav / R);
  printf("bead on a ring of radius %g turning at w about its vertical diameter (g = %g)\n", R,
         grav);
  const double ws_check[] = {0.5, 2.0};
  const double ws_full[] = {0.0, 0.5, 0.9, 1.1, 2.0, 4.0};
  const double *ws = check ? ws_check : ws_full;
  int n = check ? 2 : 6;
  for (int i = 0; i < n; ++i)
    bad |= study(ws[i] * wc, !check);
  return ex_verdict(bad, "ok");
}
