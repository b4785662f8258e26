// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Linearization with an input: the inverted pendulum on a cart, pushed by a horizontal force.
//
// Problem: a cart of 1.7 kg on a horizontal rail and a bob of 0.4 kg on a massless rod of
// 0.8 m pivoted on it, written in Cartesian coordinates (xc, yc, xb, yb) with the constraints
// 'rail' (yc = 0) and 'rod'; the input is a force F on xc ("force:xc"). dal_linearize_inputs
// at the upright rest state gives the reduced first-order (A, B) in two independent
// coordinates, ready for a controller design.
// Checks (--check): the open loop has one unstable pole at sqrt((Mc + m) g / (Mc l)) (the
// textbook linearization), and the transfer function from F to the cart position agrees with
// the textbook one through its Markov parameters c A^j B, j = 0..7.
#include <dalembert/dalembert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "example_util.h"

static const double MC = 1.7, MB = 0.4, L = 0.8, G = 9.81;

static dal_system *build(void) {
  dal_builder *b = NULL;
  int c[4], p[2];
  double g[2] = {0.0, -G};
  const char *nm[4] = {"xc", "yc", "xb", "yb"}, *pn[2] = {"cart", "bob"};
  const double m[2] = {MC, MB};
  dal_builder_create(2, &b);
  ex_cartesian_particles(b, 2, 2, pn, m, nm, c, p);
  dal_builder_set_gravity(b, g);
  dal_constraint_def rail = dal_default_constraint_def();
  rail.name = "rail";
  rail.prim = &dal_con_line2; // through the origin along x
  rail.parts = &p[0];
  rail.nparts = 1;
  dal_builder_add_constraint_def(b, &rail, NULL);
  dal_constraint_def rod = dal_default_constraint_def();
  rod.name = "rod";
  rod.prim = &dal_con_distance2;
  rod.parts = p;
  rod.nparts = 2;
  rod.param[DAL_DISTANCE_L] = L;
  dal_builder_add_constraint_def(b, &rod, NULL);
  return ex_compile(b, 0);
}

static void markov(const double *A, const double *b, const double *c, double *out) {
  double v[4], w[4];
  memcpy(v, b, sizeof v);
  for (int j = 0; j < 8; ++j) {
    out[j] = c[0] * v[0] + c[1] * v[1] + c[2] * v[2] + c[3] * v[3];
    for (int i = 0; i < 4; ++i)
      w[i] = A[i] * v[0] + A[4 + i] * v[1] + A[8 + i] * v[2] + A[12 + i] * v[3];
    memcpy(v, w, sizeof v);
  }
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0, bad = 0;
  dal_system *sys = build();
  dal_state *st = NULL;
  if (!sys || dal_state_create(sys, &st)) return 1;
  double q[4] = {0.0, 0.0, 0.0, L}, v[4] = {0}; // upright at rest
  dal_state_set(sys, st, 0.0, q, v);
  const char *in[1] = {"force:xc"};
  double A[16], B[4], N[8], re[4], im[4];
  if (dal_linearize_inputs(sys, st, 1, in, NULL, A, B) ||
      dal_linearize_full(sys, st, NULL, NULL, NULL, NULL, N) ||
      dal_normal_modes(sys, st, NULL, NULL, re, im, NULL)) {
    printf("%s\n", dal_state_errmsg(st));
    return 1;
  }
  printf("reduced A (x = (xi, eta), dq = N xi):\n");
  for (int i = 0; i < 4; ++i)
    printf("  %10.5f %10.5f %10.5f %10.5f   B %10.5f\n", A[i], A[4 + i], A[8 + i], A[12 + i], B[i]);
  double pole = sqrt((MC + MB) * G / (MC * L));
  printf("open-loop poles: %.10f %.10f %.10f %.10f (textbook +-%.10f and a double zero)\n", re[0],
         re[1], re[2], re[3], pole);
  bad |= fabs(re[0] - pole) > 1e-10 * pole || fabs(re[3] + pole) > 1e-10 * pole;
  // the textbook (x, th, x', th') with th from the upward vertical: x'' = (F - m g th) / Mc,
  // th'' = ((Mc + m) g th - F) / (Mc l)
  double At[16] = {0}, bt[4] = {0, 0, 1 / MC, -1 / (MC * L)}, ct[4] = {1, 0, 0, 0};
  At[8] = At[13] = 1.0;
  At[6] = -MB * G / MC;
  At[7] = (MC + MB) * G / (MC * L);
  double cr[4] = {N[0], N[4], 0, 0}, mr[8], mt[8];
  markov(A, B, cr, mr);
  markov(At, bt, ct, mt);
  double worst = 0.0;
  for (int j = 0; j < 8; ++j)
    worst = fmax(worst, fabs(mr[j] - mt[j]) / fmax(1.0, fabs(mt[j])));
  printf("transfer F -> x: Markov parameters agree with the textbook to %.2e\n", worst);
  bad |= worst > 1e-12;
  dal_state_destroy(st);
  dal_system_destroy(sys);
  if (check) printf(bad ? "CHECK FAILED\n" : "check passed\n");
  return bad;
}
