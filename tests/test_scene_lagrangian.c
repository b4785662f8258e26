// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// White box: a scene file's Lagrangian runs by its parts dL/dqdot and dL/dq, derived
// symbolically (scene/build.c, eval/lagrangian.c), instead of L's polarization. Checked against
// the particle route of the same mechanics (the driven pendulum and the double pendulum by
// built-in primitives: independent of L) and against the polarization of the same formula
// (the scene's L through dal_builder_set_lagrangian alone), at random states and over a run.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/base.h"
#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

#define G 9.8
#define A_DR 0.1
#define W_DR 6.2609903369994111

static const char *driven_text =
    "dim 0\nparam l = 1\nparam g = 9.8\nparam a = 0.1\nparam w = 6.2609903369994111\n"
    "coord th q=1 v=0\n"
    "lagrangian = 1/2*((l*cos(th)*thdot)^2 + (-a*w*sin(w*t) + l*sin(th)*thdot)^2) - "
    "g*(a*cos(w*t) - l*cos(th))\n";

static const char *double_text =
    "dim 0\nparam g = 9.8\ncoord a q=0.7 v=0\ncoord b q=-0.4 v=0.3\n"
    "lagrangian = adot^2 + 1/2*bdot^2 + adot*bdot*cos(a - b) + 2*g*cos(a) + g*cos(b)\n";

// the particle route (the scene library): the driven pendulum (n = 1) or the double pendulum
static dal_system *particles(int n) {
  scn_knobs k = scn_default();
  k.g = G;
  if (n == 1) {
    k.ay = A_DR;
    k.w = W_DR;
    return scn_pendulum(&k);
  }
  return scn_double_pendulum(&k);
}

// the scene's own Lagrangian expression by polarization alone (no parts)
static dal_system *polarized(const dal_scene *sc, int n) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  CHECK_OK(dal_builder_create(2, &b));
  for (int i = 0; i < n; ++i) {
    char nm[8];
    snprintf(nm, sizeof nm, "q%d", i);
    CHECK_OK(dal_builder_add_coord(b, nm, NULL));
  }
  const dal_expr *L = NULL;
  for (int i = 0; i < dal_scene_nexprs(sc) && !L; ++i) // the first expression over velocities
    if (dal_expr_nin(dal_scene_expr(sc, i)) == 2 * n && dal_expr_nout(dal_scene_expr(sc, i)) == 1)
      L = dal_scene_expr(sc, i);
  CHECK(L != NULL);
  CHECK_OK(dal_builder_set_lagrangian(b, dal_expr_lagrangian, (void *)L));
  CHECK_OK(dal_builder_compile(b, &sys));
  dal_builder_destroy(b);
  return sys;
}

// largest relative qddot difference over random states and times
static double gap(const dal_system *a, const dal_system *b, int n) {
  dal_state *sa = NULL, *sb = NULL;
  CHECK_OK(dal_state_create(a, &sa));
  CHECK_OK(dal_state_create(b, &sb));
  unsigned long long seed = 7;
  double q[2], v[2], worst = 0.0;
  for (int k = 0; k < 50 && sa && sb; ++k) {
    double t = check_rand(&seed, 0.0, 10.0);
    for (int i = 0; i < n; ++i) {
      q[i] = check_rand(&seed, -3.0, 3.0);
      v[i] = check_rand(&seed, -4.0, 4.0);
    }
    CHECK_OK(dal_state_set(a, sa, t, q, v));
    CHECK_OK(dal_state_set(b, sb, t, q, v));
    CHECK_OK(dal_forward(a, sa));
    CHECK_OK(dal_forward(b, sb));
    for (int i = 0; i < n; ++i) {
      double x = dal_state_qddot(sa)[i], y = dal_state_qddot(sb)[i];
      worst = fmax(worst, fabs(x - y) / fmax(1.0, fabs(y)));
    }
  }
  dal_state_destroy(sa);
  dal_state_destroy(sb);
  return worst;
}

// q at t = 5 by DOPRI5 at rtol 1e-10 from (q0, v0)
static void run(const dal_system *sys, const double *q0, const double *v0, double *q, int n) {
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_set(sys, st, 0.0, q0, v0));
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_DOPRI5;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  CHECK_OK(dal_advance(sys, st, &o, 5.0));
  memcpy(q, dal_state_q(st), (size_t)n * sizeof(double));
  dal_state_destroy(st);
}

static void check_scene(const char *name, const char *text, int n) {
  dal_scene *sc = NULL;
  char msg[512];
  CHECK_MSG(dal_scene_parse(text, name, &sc, msg, sizeof msg) == DAL_OK, "%s", msg);
  if (!sc) return;
  const dal_system *s = dal_scene_system(sc);
  CHECK(s->lag_parts != NULL); // the parts were derived and given to the system
  dal_system *pr = particles(n), *pol = polarized(sc, n);
  CHECK(pol && pol->lag_parts == NULL);
  double gp = gap(s, pr, n), gl = gap(s, pol, n);
  printf("%s: qddot against the particle route %.3g, against L's polarization %.3g\n", name, gp,
         gl);
  CHECK(gp < 1e-13);
  CHECK(gl < 1e-13);
  double q0[2] = {1.0, -0.4}, v0[2] = {0.2, 0.3}, a[2], b[2], c[2];
  run(s, q0, v0, a, n);
  run(pr, q0, v0, b, n);
  run(pol, q0, v0, c, n);
  double d1 = 0, d2 = 0;
  for (int i = 0; i < n; ++i) {
    d1 = fmax(d1, fabs(a[i] - b[i]));
    d2 = fmax(d2, fabs(a[i] - c[i]));
  }
  printf("%s: q(5) against the particle route %.3g, against the polarization %.3g\n", name, d1, d2);
  CHECK(d1 < 1e-9);
  CHECK(d2 < 1e-9);
  // the energy function still comes from L: constant for the double pendulum (no t in L)
  if (n == 2) {
    dal_state *st = NULL;
    CHECK_OK(dal_state_create(s, &st));
    CHECK_OK(dal_state_set(s, st, 0.0, q0, v0));
    dal_energies e0, e1;
    CHECK_OK(dal_forward(s, st));
    CHECK_OK(dal_state_energies(st, &e0));
    dal_solve_opts o = dal_default_solve_opts();
    o.rtol = 1e-10;
    CHECK_OK(dal_advance(s, st, &o, 5.0));
    CHECK_OK(dal_state_energies(st, &e1));
    CHECK_CLOSE(e1.h, e0.h, 1e-8);
    dal_state_destroy(st);
  }
  dal_system_destroy(pr);
  dal_system_destroy(pol);
  dal_scene_destroy(sc);
}

int main(void) {
  check_scene("driven pendulum", driven_text, 1);
  check_scene("double pendulum", double_text, 2);
  return check_summary("test_scene_lagrangian");
}
