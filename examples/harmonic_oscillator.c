// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// 2D harmonic oscillator (SICM's m = 2, k = 1) from a particle and a spring, and from L.
//
// Problem: a particle of mass m = 2 in the plane, tied to the origin by a spring of stiffness
// k = 1 and rest length 0, so U = k/2 |r|^2 (Sussman & Wisdom, SICM sec. 1.6).
// Coordinates: Cartesian (x, y) (dal_map_cartesian2). Two formulations of the same system:
// particles + an anchor spring (d'Alembert's principle), and the Lagrangian
// L = m/2 |v|^2 - k/2 |q|^2 written over jets (dal_builder_set_lagrangian).
// Integration: minimal-coordinate ODE, dal_evolve with the automatic method at rtol 1e-10.
// Checks (--check runs 2 periods, the full mode 10):
//  1. at sample states both routes give qddot = -k/m q;
//  2. the Lagrange residual of the closed-form solution q(t) = q0 cos wt + v0/w sin wt,
//     w = sqrt(k/m), vanishes, and that of a path with the wrong frequency w' equals
//     (k - m w'^2) q(t), for both routes;
//  3. the integrated motion follows the closed form at every output time, and E is conserved.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "example_util.h"

static const double mass = 2.0, k = 1.0, rtol = 1e-10;
static const double q0[2] = {1, 2}, v0[2] = {3, 4};
#define PI 3.14159265358979323846

static int lagrangian(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet T = dal_scale(dal_add(dal_sq(v[0]), dal_sq(v[1])), 0.5 * mass);
  dal_jet U = dal_scale(dal_add(dal_sq(q[0]), dal_sq(q[1])), 0.5 * k);
  *L = dal_sub(T, U);
  return 0;
}

// the closed-form motion with frequency w (ctx: w), as a path over jets
static int path(dal_jet t, dal_jet *q, void *ctx) {
  double w = *(const double *)ctx;
  dal_jet c = dal_cos(dal_scale(t, w)), s = dal_sin(dal_scale(t, w));
  for (int i = 0; i < 2; ++i)
    q[i] = dal_add(dal_scale(c, q0[i]), dal_scale(s, v0[i] / w));
  return 0;
}

static void exact(double t, double *q, double *v) {
  double w = sqrt(k / mass);
  for (int i = 0; i < 2; ++i) {
    q[i] = q0[i] * cos(w * t) + v0[i] / w * sin(w * t);
    v[i] = -q0[i] * w * sin(w * t) + v0[i] * cos(w * t);
  }
}

static dal_system *build(int lagrange) {
  dal_builder *b = NULL;
  int c[2], p, rc = dal_builder_create(2, &b);
  if (!rc) rc = dal_builder_add_coord(b, "x", &c[0]);
  if (!rc) rc = dal_builder_add_coord(b, "y", &c[1]);
  if (lagrange) {
    if (!rc) rc = dal_builder_set_lagrangian(b, lagrangian, NULL);
  } else {
    if (!rc) rc = dal_builder_add_particle(b, "particle", mass, &p);
    dal_place_def pd = dal_default_place_def();
    pd.prim = &dal_map_cartesian2;
    pd.coords = c;
    pd.ncoords = 2;
    if (!rc) rc = dal_builder_place_def(b, p, &pd);
    dal_spring_def sd = dal_default_spring_def(); // anchored at the origin, rest length 0
    sd.a = p;
    sd.k = k;
    if (!rc) rc = dal_builder_add_spring_def(b, &sd);
  }
  return ex_compile(b, rc);
}

// monitor: error against the closed form and energy drift
typedef struct track {
  double E0, maxerr, maxdE;
  int rows, every;
} track;

static int monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  track *tr = ctx;
  double t = dal_state_time(st), qe[2], ve[2], err = 0;
  const double *q = dal_state_q(st), *v = dal_state_qdot(st);
  exact(t, qe, ve);
  for (int i = 0; i < 2; ++i)
    err = fmax(err, fmax(fabs(q[i] - qe[i]), fabs(v[i] - ve[i])));
  dal_energies e;
  dal_state_energies(st, &e);
  if (tr->rows == 0) tr->E0 = e.E;
  tr->maxerr = fmax(tr->maxerr, err);
  tr->maxdE = fmax(tr->maxdE, fabs(e.E - tr->E0));
  if (tr->rows++ % tr->every == 0)
    printf("  %7.3f  %12.8f %12.8f  %12.8f %12.8f  %9.2e  %.12f\n", t, q[0], q[1], v[0], v[1], err,
           e.E);
  return 0;
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0, bad = 0;
  double w = sqrt(k / mass), period = 2 * PI / w;
  dal_system *sys[2] = {build(0), build(1)};
  dal_state *st[2] = {NULL, NULL};
  const char *route[2] = {"particle + spring", "Lagrangian"};
  for (int r = 0; r < 2; ++r)
    if (!sys[r] || dal_state_create(sys[r], &st[r])) bad = 1;
  if (bad) goto out;
  printf("2D harmonic oscillator: m = %g, k = %g, w = %.15g, period %.15g\n", mass, k, w, period);

  // 1. accelerations at sample states
  printf("accelerations (hand: -k/m q):\n");
  for (int i = 0; i < 3; ++i) {
    double q[2] = {0.3 + i, -1.1 + 0.7 * i}, v[2] = {0.5 * i, -0.2};
    for (int r = 0; r < 2; ++r) {
      int rc = dal_state_set(sys[r], st[r], 0.1 * i, q, v);
      if (!rc) rc = dal_forward(sys[r], st[r]);
      if (rc) {
        printf("forward failed: %s\n", dal_state_errmsg(st[r]));
        bad = 1;
        continue;
      }
      const double *a = dal_state_qddot(st[r]);
      double ex = -k / mass * q[0], ey = -k / mass * q[1];
      double err = fmax(fabs(a[0] - ex), fabs(a[1] - ey));
      printf("  %-18s q = (%5.2f, %5.2f): qddot = (%.15g, %.15g), error %.1e\n", route[r], q[0],
             q[1], a[0], a[1], err);
      bad |= !(err <= 1e-14);
    }
  }

  // 2. Lagrange residual of the closed form and of a wrong-frequency path
  printf("Lagrange residual d/dt dL/dv - dL/dq along paths:\n");
  for (int r = 0; r < 2; ++r) {
    double res[2], worst = 0, wrong = 1.05 * w, worst_wrong = 0;
    for (int i = 0; i <= 20; ++i) {
      double t = 0.5 * i;
      if (dal_lagrange_residual(sys[r], st[r], path, t, res, &w)) bad = 1;
      worst = fmax(worst, fmax(fabs(res[0]), fabs(res[1])));
      if (dal_lagrange_residual(sys[r], st[r], path, t, res, &wrong)) bad = 1;
      double f = k - mass * wrong * wrong;
      for (int j = 0; j < 2; ++j) {
        double qj = q0[j] * cos(wrong * t) + v0[j] / wrong * sin(wrong * t);
        worst_wrong = fmax(worst_wrong, fabs(res[j] - f * qj));
      }
    }
    printf("  %-18s exact path: max |res| = %.1e; w' = 1.05 w: max |res - (k - m w'^2) q| = "
           "%.1e\n",
           route[r], worst, worst_wrong);
    bad |= !(worst <= 1e-13) || !(worst_wrong <= 1e-13);
  }

  // 3. integration against the closed form
  int periods = check ? 2 : 10;
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = rtol;
  o.atol = rtol;
  for (int r = 0; r < 2; ++r) {
    track tr = {0, 0, 0, 0, check ? 10 : 20};
    printf("integration (%s, %s), %d periods:\n       t            x            y           "
           "vx           vy      error  E\n",
           route[r], dal_method_name(o.method), periods);
    if (dal_state_set(sys[r], st[r], 0.0, q0, v0) ||
        dal_evolve(sys[r], st[r], &o, periods * period, period / 20, monitor, &tr)) {
      printf("integration failed: %s\n", dal_state_errmsg(st[r]));
      bad = 1;
      continue;
    }
    dal_stats s;
    dal_state_stats(st[r], &s);
    printf("  max error %.2e (rtol %.0e), energy drift %.2e, %ld steps\n", tr.maxerr, rtol,
           tr.maxdE, s.steps);
    // global error allowed: 100 x rtol x the size of the state (amplitude ~ 7)
    bad |= !(tr.maxerr <= 100 * rtol * 7) || !(tr.maxdE <= 100 * rtol * tr.E0);
  }
out:
  for (int r = 0; r < 2; ++r) {
    dal_state_destroy(st[r]);
    dal_system_destroy(sys[r]);
  }
  return ex_verdict(bad, "ok");
}
