// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Double pendulum: equations of motion, normal modes, and energy in a chaotic run.
//
// Problem: two bobs of mass m1 = m2 = 1 on rods l1 = l2 = 1, the first about a fixed pivot, the
// second hanging from the first, gravity g = 9.81. Coordinates: theta1, theta2 from the
// downward vertical (dal_map_pendulum, then dal_map_hanging with bob 1 as parent).
// Formulation: minimal-coordinate ODE by particles; the Lagrangian
// L = (m1+m2)/2 l1^2 w1^2 + m2/2 l2^2 w2^2 + m2 l1 l2 w1 w2 cos(th1 - th2)
//     + (m1+m2) g l1 cos(th1) + m2 g l2 cos(th2)
// for comparison; dal_evolve / dal_advance (automatic method) at rtol 1e-11.
// Hand equations: M qdd = Q - c with M = [(m1+m2) l1^2, m2 l1 l2 c12; m2 l1 l2 c12, m2 l2^2],
// c = m2 l1 l2 s12 (w2^2, -w1^2), Q = -g ((m1+m2) l1 sin th1, m2 l2 sin th2).
// Normal modes (m1 = m2, l1 = l2 = l): w^2 = (g/l)(2 -+ sqrt 2) with shapes (1, +-sqrt 2).
// Checks (--check: both modes and a 3 s chaotic run; full mode: 20 s):
//  1. particles, Lagrangian and the hand equations agree at sample states (and M, Q, c);
//  2. a small-amplitude (1e-5) mode returns to its start after one period and is reversed
//     after half of it;
//  3. in a chaotic run (released at theta1 = theta2 = 2) the energy is conserved.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "example_util.h"

static const double m1 = 1.0, m2 = 1.0, l1 = 1.0, l2 = 1.0, grav = 9.81, rtol = 1e-11;
#define PI 3.14159265358979323846

static int lagrangian(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet T = dal_scale(dal_sq(v[0]), 0.5 * (m1 + m2) * l1 * l1);
  T = dal_add(T, dal_scale(dal_sq(v[1]), 0.5 * m2 * l2 * l2));
  T = dal_add(T,
              dal_scale(dal_mul(dal_mul(v[0], v[1]), dal_cos(dal_sub(q[0], q[1]))), m2 * l1 * l2));
  dal_jet V = dal_add(dal_scale(dal_cos(q[0]), (m1 + m2) * grav * l1),
                      dal_scale(dal_cos(q[1]), m2 * grav * l2));
  *L = dal_add(T, V);
  return 0;
}

static dal_system *build(int lagrange) {
  dal_builder *b = NULL;
  int q[2], p1, p2, rc = dal_builder_create(2, &b);
  double g[2] = {0, -grav};
  if (!rc) rc = dal_builder_add_coord(b, "theta1", &q[0]);
  if (!rc) rc = dal_builder_add_coord(b, "theta2", &q[1]);
  if (lagrange) {
    if (!rc) rc = dal_builder_set_lagrangian(b, lagrangian, NULL);
  } else {
    if (!rc) rc = dal_builder_add_particle(b, "bob1", m1, &p1);
    if (!rc) rc = dal_builder_add_particle(b, "bob2", m2, &p2);
    dal_place_def pd = dal_default_place_def(); // pivot fixed at the origin
    pd.prim = &dal_map_pendulum;
    pd.coords = &q[0];
    pd.ncoords = 1;
    pd.param[DAL_PENDULUM_L] = l1;
    if (!rc) rc = dal_builder_place_def(b, p1, &pd);
    pd = dal_default_place_def(); // bob2 hangs from bob1
    pd.prim = &dal_map_hanging;
    pd.parent = p1;
    pd.coords = &q[1];
    pd.ncoords = 1;
    pd.param[DAL_HANGING_L] = l2;
    if (!rc) rc = dal_builder_place_def(b, p2, &pd);
    if (!rc) rc = dal_builder_set_gravity(b, g);
  }
  return ex_compile(b, rc);
}

// hand equations of motion: M, c, Q and qdd
static void hand(const double *th, const double *w, double *M, double *c, double *Q, double *qdd) {
  double c12 = cos(th[0] - th[1]), s12 = sin(th[0] - th[1]);
  M[0] = (m1 + m2) * l1 * l1;
  M[1] = M[2] = m2 * l1 * l2 * c12;
  M[3] = m2 * l2 * l2;
  c[0] = m2 * l1 * l2 * s12 * w[1] * w[1];
  c[1] = -m2 * l1 * l2 * s12 * w[0] * w[0];
  Q[0] = -(m1 + m2) * grav * l1 * sin(th[0]);
  Q[1] = -m2 * grav * l2 * sin(th[1]);
  double r0 = Q[0] - c[0], r1 = Q[1] - c[1], det = M[0] * M[3] - M[1] * M[2];
  qdd[0] = (r0 * M[3] - M[1] * r1) / det;
  qdd[1] = (M[0] * r1 - M[2] * r0) / det;
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0, bad = 0;
  dal_system *sys = build(0), *lag = build(1);
  dal_state *st = NULL, *stl = NULL;
  if (ex_two_states(sys, lag, &st, &stl)) return 1;
  printf("double pendulum: m1 = %g, m2 = %g, l1 = %g, l2 = %g, g = %g\n", m1, m2, l1, l2, grav);

  // 1. equations of motion at sample states
  double worst = 0;
  for (int i = 0; i < 6; ++i) {
    double th[2] = {-2.5 + i, 1.7 - 0.9 * i}, w[2] = {1.5 - 0.7 * i, 0.4 * i - 1};
    if (dal_state_set(sys, st, 0, th, w) || dal_forward(sys, st) ||
        dal_state_set(lag, stl, 0, th, w) || dal_forward(lag, stl)) {
      bad = 1;
      break;
    }
    double M[4], c[2], Q[2], qdd[2], sc = grav + w[0] * w[0] + w[1] * w[1];
    hand(th, w, M, c, Q, qdd);
    const double *Ml = dal_state_mass_matrix(st), *cl = dal_state_bias(st);
    const double *Ql = dal_state_genforces(st);
    for (int j = 0; j < 2; ++j) {
      worst = fmax(worst, fabs(dal_state_qddot(st)[j] - qdd[j]) / sc);
      worst = fmax(worst, fabs(dal_state_qddot(stl)[j] - qdd[j]) / sc);
      worst = fmax(worst, fabs(cl[j] - c[j]) / sc);
      worst = fmax(worst, fabs(Ql[j] - Q[j]) / sc);
    }
    for (int j = 0; j < 4; ++j)
      worst = fmax(worst, fabs(Ml[j] - M[j]));
    if (i < 2)
      printf("  th = (%5.2f, %5.2f) w = (%5.2f, %5.2f): qdd = (%.12f, %.12f), hand (%.12f, "
             "%.12f)\n",
             th[0], th[1], w[0], w[1], dal_state_qddot(st)[0], dal_state_qddot(st)[1], qdd[0],
             qdd[1]);
  }
  printf("  particles / Lagrangian / hand (qdd, M, c, Q): max rel difference %.1e\n", worst);
  bad |= !(worst <= 1e-13);

  // 2. normal modes
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = o.atol = rtol;
  for (int mode = 0; mode < 2; ++mode) {
    double sg = mode ? -1.0 : 1.0, eps = 1e-5;
    double om = sqrt(grav / l1 * (2 - sg * sqrt(2.0))), T = 2 * PI / om;
    double th[2] = {eps, sg * sqrt(2.0) * eps}, w[2] = {0, 0};
    int rc = dal_state_set(sys, st, 0.0, th, w);
    if (!rc) rc = dal_advance(sys, st, &o, T / 2);
    double h0 = dal_state_q(st)[0] / eps, h1 = dal_state_q(st)[1] / eps;
    if (!rc) rc = dal_advance(sys, st, &o, T);
    double f0 = dal_state_q(st)[0] / eps, f1 = dal_state_q(st)[1] / eps;
    printf("  mode (1, %+.4f): w = %.10f, T = %.10f; q/eps at T/2 = (%+.8f, %+.8f), at T = "
           "(%+.8f, %+.8f)\n",
           sg * sqrt(2.0), om, T, h0, h1, f0, f1);
    // nonlinear corrections are O(eps^2), integration errors O(rtol / eps)
    double tol = 1e-5;
    bad |= rc != 0 || !(fabs(h0 + 1) <= tol) || !(fabs(h1 + sg * sqrt(2.0)) <= tol) ||
           !(fabs(f0 - 1) <= tol) || !(fabs(f1 - sg * sqrt(2.0)) <= tol);
  }

  // 3. energy in a chaotic run
  double th[2] = {2.0, 2.0}, w[2] = {0, 0}, tend = check ? 3.0 : 20.0, E0 = 0, dEmax = 0;
  int rc = dal_state_set(sys, st, 0.0, th, w);
  if (!rc) rc = dal_forward(sys, st);
  for (int i = 0; !rc && i <= (int)(tend / 0.5 + 0.5); ++i) {
    if (i) rc = dal_advance(sys, st, &o, 0.5 * i);
    if (rc) break;
    dal_energies e;
    dal_state_energies(st, &e);
    if (i == 0) E0 = e.E;
    dEmax = fmax(dEmax, fabs(e.E - E0));
    if (!check || i % 2 == 0)
      printf("    t = %5.2f  theta1 = %+10.5f  theta2 = %+10.5f  E = %.12f\n", 0.5 * i,
             dal_state_q(st)[0], dal_state_q(st)[1], e.E);
  }
  dal_stats s;
  dal_state_stats(st, &s);
  if (rc) printf("  integration failed: %s\n", dal_state_errmsg(st));
  printf("  chaotic run to t = %g: energy drift %.1e (scale m g l = %g), %ld steps\n", tend, dEmax,
         m1 * grav * l1, s.steps);
  bad |= rc != 0 || !(dEmax <= 1000 * rtol * m1 * grav * l1);
  dal_state_destroy(st);
  dal_state_destroy(stl);
  dal_system_destroy(sys);
  dal_system_destroy(lag);
  return ex_verdict(bad, "ok");
}
