// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Springs, a damper-free user potential U(r, t), and a force callback with its dissipated work.
//
// Problem: two particles in the plane (Cartesian coordinates x1, y1, x2, y2), joined by a
// spring (k = 40 N/m, rest 0.5 m), the first tied to an anchor at (0, 1) by another spring
// (k = 25 N/m, rest 0.3 m), under gravity, and attracted to the origin by a user potential
// U(r) = -mu / sqrt(|r_2|^2 + 0.2^2) on the second particle. Formulation: minimal ODE (no
// constraints). Checks (--check): (1) the user potential's jets against finite differences
// (dal_verify_potential_r) and the model check (Q = -dU/dq, Lagrange residual of a path,
// dal_verify_model); (2) without damping E = T + U is conserved to rtol; (3) with a viscous
// force callback F = -c v on both particles, the energy lost equals the work dissipated,
// W(t) = integral of c |v|^2 dt integrated alongside by Simpson's rule on the monitor's grid.
#include <dalembert/dalembert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "example_util.h"

#define MU 0.8
#define CDAMP 0.35

static int attract(const dal_jet *r, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  // particle 2 is r[2], r[3]; softened at the origin by a core radius 0.2 m
  dal_jet s = dal_addc(dal_add(dal_mul(r[2], r[2]), dal_mul(r[3], r[3])), 0.04);
  *U = dal_div(dal_const(-MU), dal_sqrt(s));
  return 0;
}

// viscous damping on every particle: ADD -c v (the callback adds into F)
static int viscous(double t, const double *r, const double *v, double *F, void *ctx) {
  (void)t;
  (void)r;
  int nd = *(const int *)ctx;
  for (int i = 0; i < nd; ++i)
    F[i] -= CDAMP * v[i];
  return 0;
}

static dal_system *build(int damped) {
  static const int nd = 4;
  dal_builder *b = NULL;
  int c[4], p[2];
  dal_builder_create(2, &b);
  const char *names[4] = {"x1", "y1", "x2", "y2"}, *pn[2] = {"p1", "p2"};
  const double m[2] = {0.5, 0.3};
  ex_cartesian_particles(b, 2, 2, pn, m, names, c, p);
  dal_spring_def s = dal_default_spring_def();
  s.a = p[0];
  s.b = p[1];
  s.k = 40.0;
  s.length = 0.5;
  dal_builder_add_spring_def(b, &s);
  s = dal_default_spring_def(); // anchored, at (0, 1)
  s.a = p[0];
  s.k = 25.0;
  s.length = 0.3;
  s.anchor[1] = 1.0;
  dal_builder_add_spring_def(b, &s);
  dal_builder_add_potential_r(b, attract, NULL);
  if (damped) dal_builder_add_force(b, viscous, (void *)&nd);
  double g[2] = {0, -9.81};
  dal_builder_set_gravity(b, g);
  return ex_compile(b, 0);
}

// dissipated work by Simpson's rule over pairs of monitor intervals
typedef struct work {
  double p[3]; // c |v|^2 at the last three output times
  int k;
  double W, dt;
} work;

static int monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  work *w = ctx;
  const double *v = dal_state_velocities(st);
  double pw = 0.0;
  for (int i = 0; i < 2 * dal_system_nparticles(sys); ++i)
    pw += CDAMP * v[i] * v[i];
  if (w->k < 2) {
    w->p[w->k++] = pw;
    return 0;
  }
  w->p[2] = pw;
  w->W += w->dt / 3.0 * (w->p[0] + 4.0 * w->p[1] + w->p[2]);
  w->p[0] = pw;
  w->k = 1;
  return 0;
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0, bad = 0;
  // 1. the potential and the model
  dal_verify_report vr;
  dal_verify_opts vo = dal_default_verify_opts();
  if (dal_verify_potential_r(attract, 2, 2, &vo, &vr, NULL)) bad = 1;
  printf("%s\n", vr.msg);
  dal_system *sys = build(0);
  dal_state *st = NULL;
  if (!sys || dal_state_create(sys, &st)) return 1;
  double q0[4] = {0.2, 0.6, 0.9, 0.4}, v0[4] = {0.5, 0.0, -0.3, 0.8};
  dal_state_set(sys, st, 0, q0, v0);
  dal_model_report mr;
  if (dal_verify_model(sys, st, NULL, &mr)) bad = 1;
  printf("%s\n", mr.msg);
  // 2. conservation of E
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-10;
  dal_energies e0, e1;
  dal_forward(sys, st);
  dal_state_energies(st, &e0);
  if (dal_advance(sys, st, &o, 4.0)) return 1;
  dal_state_energies(st, &e1);
  printf("undamped: E(0) = %.12f J, E(4) = %.12f J (change %.2g)\n", e0.E, e1.E, e1.E - e0.E);
  if (fabs(e1.E - e0.E) > 1e-8) bad = 1;
  dal_state_destroy(st);
  dal_system_destroy(sys);
  // 3. damped: E(0) - E(t) = W(t)
  sys = build(1);
  dal_state_create(sys, &st);
  dal_state_set(sys, st, 0, q0, v0);
  work w = {{0, 0, 0}, 0, 0.0, 2e-3}; // Simpson error ~ (t/180) dt^4 max|P''''|, about 1e-9 here
  int rc = dal_evolve(sys, st, &o, 4.0, w.dt, monitor, &w);
  dal_state_energies(st, &e1);
  double loss = e0.E - e1.E;
  printf("damped: energy lost %.12f J, dissipated work %.12f J (difference %.2g)\n", loss, w.W,
         loss - w.W);
  if (rc || fabs(loss - w.W) > 1e-8 || loss < 0.1) bad = 1;
  dal_state_destroy(st);
  dal_system_destroy(sys);
  if (check) printf("springs_potential: %s\n", bad ? "FAILED" : "ok");
  return bad;
}
