// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The flow map's derivatives: the state-transition matrix of a double pendulum and the
// sensitivity of its end state to the lower bob's mass and to gravity.
//
// Problem: double pendulum in its angles (th1, th2) from the downward vertical, bobs of 1.3
// and 0.7 kg on rods of 0.9 and 0.6 m, released from (0.9, -0.5) rad with rates (1.2, 0.4)
// rad/s; integrated to t1 = 1.5 s. dal_state_transition carries Phi = dy(t1)/dy(0) and
// S = dy(t1)/d(m2, g_y) with the trajectory through DOPRI5 at rtol 1e-12.
// Checks (--check): (1) Liouville: det Phi = det M(0) / det M(t1) (volume is kept in (q, p),
// p = M qdot); (2) one column of Phi and of S against central differences of two runs each.
#include <dalembert/dalembert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "example_util.h"

static dal_system *build(void) {
  dal_builder *b = NULL;
  int c[2], p[2];
  double g[2] = {0.0, -9.81};
  dal_builder_create(2, &b);
  dal_builder_add_coord(b, "th1", &c[0]);
  dal_builder_add_coord(b, "th2", &c[1]);
  dal_builder_add_particle(b, "b1", 1.3, &p[0]);
  dal_builder_add_particle(b, "b2", 0.7, &p[1]);
  dal_place_def d1 = dal_default_place_def();
  d1.prim = &dal_map_pendulum;
  d1.coords = &c[0];
  d1.ncoords = 1;
  d1.param[DAL_PENDULUM_L] = 0.9;
  dal_builder_place_def(b, p[0], &d1);
  dal_place_def d2 = dal_default_place_def();
  d2.prim = &dal_map_hanging;
  d2.parent = p[0];
  d2.coords = &c[1];
  d2.ncoords = 1;
  d2.param[0] = 0.6; // rod length
  dal_builder_place_def(b, p[1], &d2);
  dal_builder_set_gravity(b, g);
  return ex_compile(b, 0);
}

static double det(int n, const double *A) { // Gaussian elimination with partial pivoting
  double a[16], d = 1.0;
  memcpy(a, A, (size_t)(n * n) * sizeof(double));
  for (int k = 0; k < n; ++k) {
    int p = k;
    for (int i = k + 1; i < n; ++i)
      if (fabs(a[k * n + i]) > fabs(a[k * n + p])) p = i;
    if (p != k) {
      for (int j = 0; j < n; ++j) {
        double t = a[j * n + k];
        a[j * n + k] = a[j * n + p];
        a[j * n + p] = t;
      }
      d = -d;
    }
    d *= a[k * n + k];
    for (int i = k + 1; i < n; ++i)
      for (int j = k + 1; j < n; ++j)
        a[j * n + i] -= a[k * n + i] / a[k * n + k] * a[j * n + k];
  }
  return d;
}

// y(t1) from y0 with the state's parameters (Bulirsch-Stoer, rtol 1e-13)
static void run(const dal_system *sys, dal_state *st, const double *y0, double t1, double *y) {
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_BS;
  o.rtol = 1e-13;
  dal_state_set(sys, st, 0.0, y0, y0 + 2);
  dal_advance(sys, st, &o, t1);
  memcpy(y, dal_state_q(st), 2 * sizeof(double));
  memcpy(y + 2, dal_state_qdot(st), 2 * sizeof(double));
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0, bad = 0;
  dal_system *sys = build();
  dal_state *st = NULL;
  if (!sys || dal_state_create(sys, &st)) return 1;
  const double y0[4] = {0.9, -0.5, 1.2, 0.4}, t1 = 1.5;
  const char *params[2] = {"mass:b2", "gravity:1"};
  double M0[4], M1[4], Phi[16], S[8];
  dal_state_set(sys, st, 0.0, y0, y0 + 2);
  dal_linearize(sys, st, M0, NULL, NULL);
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-12;
  if (dal_state_transition(sys, st, &o, t1, Phi, 2, params, S)) {
    printf("state_transition: %s\n", dal_state_errmsg(st));
    return 1;
  }
  dal_linearize(sys, st, M1, NULL, NULL);
  printf("Phi(%.1f, 0) (rows: th1, th2, th1', th2'):\n", t1);
  for (int i = 0; i < 4; ++i)
    printf("  %12.6f %12.6f %12.6f %12.6f\n", Phi[i], Phi[4 + i], Phi[8 + i], Phi[12 + i]);
  printf("dy/d(m2):  %12.6f %12.6f %12.6f %12.6f\n", S[0], S[1], S[2], S[3]);
  printf("dy/d(g_y): %12.6f %12.6f %12.6f %12.6f\n", S[4], S[5], S[6], S[7]);
  double dP = det(4, Phi), lv = det(2, M0) / det(2, M1);
  printf("det Phi = %.12f, det M(0) / det M(t1) = %.12f\n", dP, lv);
  bad |= fabs(dP - lv) > 1e-9 * fabs(lv);
  // one column of each against central differences (oracle)
  dal_state *s2 = NULL;
  dal_state_create(sys, &s2);
  double yp[4], ym[4], yy[4], h = 1e-5;
  memcpy(yy, y0, sizeof yy);
  yy[2] += h;
  run(sys, s2, yy, t1, yp);
  yy[2] -= 2 * h;
  run(sys, s2, yy, t1, ym);
  double e1 = 0.0, e2 = 0.0;
  for (int i = 0; i < 4; ++i)
    e1 = fmax(e1, fabs((yp[i] - ym[i]) / (2 * h) - Phi[8 + i]));
  dal_state_set_param_named(sys, s2, "mass:b2", 0.7 + h);
  run(sys, s2, y0, t1, yp);
  dal_state_set_param_named(sys, s2, "mass:b2", 0.7 - h);
  run(sys, s2, y0, t1, ym);
  for (int i = 0; i < 4; ++i)
    e2 = fmax(e2, fabs((yp[i] - ym[i]) / (2 * h) - S[i]));
  printf("central differences: Phi column th1' off by %.2e, dy/d(m2) off by %.2e\n", e1, e2);
  bad |= e1 > 1e-6 || e2 > 1e-6;
  dal_state_destroy(s2);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  if (check) printf(bad ? "CHECK FAILED\n" : "check passed\n");
  return bad;
}
