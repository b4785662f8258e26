// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A closed loop: the four-bar linkage, in Cartesian coordinates with three rods.
//
// Problem: ground pivots A = (0, 0) and D = (2, 0); crank A-B (length 1), coupler B-C (length
// 2), rocker C-D (length 1.5); point masses m_B = 1 at B and m_C = 2 at C, gravity g down.
// Coordinates: (xB, yB, xC, yC). Constraints: rod 'crank' (B to the fixed point A),
// 'coupler' (B-C), 'rocker' (C to the fixed point D). Formulation: GGL DAE (IDA).
// Checks (--check): (1) statics: with B also held at its x by a prescribed coordinate, the
// linkage is a structure; at rest the multipliers are the rod forces, compared with the
// equilibrium of joints C and B solved by hand (2 x 2 systems, Cramer's rule); (2) dynamics:
// released, the linkage moves on its one degree of freedom with rod residuals at the solver's
// tolerance and the energy conserved to rtol.
#include <dalembert/dalembert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "example_util.h"

#define G 9.81

static const double A[2] = {0, 0}, D[2] = {2, 0}, LAB = 1.0, LBC = 2.0, LCD = 1.5;
static const double MB = 1.0, MC = 2.0;

// a rod from particle p to a fixed point x0
static void anchor_rod(dal_builder *b, const char *name, int p, const double *x0, double L) {
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = name;
  cd.prim = &dal_con_anchor2;
  cd.parts = &p;
  cd.nparts = 1;
  cd.param[DAL_ANCHOR_L] = L;
  cd.param[DAL_ANCHOR_X0] = x0[0];
  cd.param[DAL_ANCHOR_Y0] = x0[1];
  dal_builder_add_constraint_def(b, &cd, NULL);
}

static dal_system *build(int hold, double xB) {
  dal_builder *b = NULL;
  int c[4], pB, pC;
  dal_builder_create(2, &b);
  const char *names[4] = {"xB", "yB", "xC", "yC"};
  for (int i = 0; i < 4; ++i)
    dal_builder_add_coord(b, names[i], &c[i]);
  dal_builder_add_particle(b, "B", MB, &pB);
  dal_builder_add_particle(b, "C", MC, &pC);
  dal_place_def d = dal_default_place_def();
  d.prim = &dal_map_cartesian2;
  d.ncoords = 2;
  d.coords = c;
  dal_builder_place_def(b, pB, &d);
  d.coords = c + 2;
  dal_builder_place_def(b, pC, &d);
  anchor_rod(b, "crank", pB, A, LAB);
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = "coupler";
  cd.prim = &dal_con_distance2;
  int bc[2] = {pB, pC};
  cd.parts = bc;
  cd.nparts = 2;
  cd.param[DAL_DISTANCE_L] = LBC;
  dal_builder_add_constraint_def(b, &cd, NULL);
  anchor_rod(b, "rocker", pC, D, LCD);
  if (hold) {
    // xB = xB0: a prescribed coordinate (no motion f(t)) makes the linkage a structure
    cd = dal_default_constraint_def();
    cd.name = "hold_xB";
    cd.prim = &dal_con_prescribed;
    cd.coords = &c[0];
    cd.ncoords = 1;
    cd.param[DAL_PRESCRIBED_Q0] = xB;
    dal_builder_add_constraint_def(b, &cd, NULL);
  }
  double g[2] = {0, -G};
  dal_builder_set_gravity(b, g);
  return ex_compile(b, 0);
}

// a consistent configuration for crank angle phi: B on the crank circle, C where the coupler
// and rocker circles meet (upper intersection)
static void configure(double phi, double *q) {
  double B[2] = {A[0] + LAB * cos(phi), A[1] + LAB * sin(phi)};
  double dx = D[0] - B[0], dy = D[1] - B[1], dd = hypot(dx, dy);
  double a = (LBC * LBC - LCD * LCD + dd * dd) / (2 * dd), h = sqrt(LBC * LBC - a * a);
  q[0] = B[0];
  q[1] = B[1];
  q[2] = B[0] + a * dx / dd - h * dy / dd;
  q[3] = B[1] + a * dy / dd + h * dx / dd;
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0, bad = 0;
  double q[4], v[4] = {0, 0, 0, 0};
  configure(1.1, q);
  // 1. statics
  dal_system *sys = build(1, q[0]);
  dal_state *st = NULL;
  if (!sys || dal_state_create(sys, &st)) return 1;
  dal_state_set(sys, st, 0, q, v);
  if (dal_make_consistent(sys, st, 0, NULL)) {
    fprintf(stderr, "%s\n", dal_state_errmsg(st));
    return 1;
  }
  const double *lam = dal_state_lambda(st);
  // unit vectors: e1 from A to B, e2 from B to C, e3 from D to C
  double e1[2] = {(q[0] - A[0]) / LAB, (q[1] - A[1]) / LAB};
  double e2[2] = {(q[2] - q[0]) / LBC, (q[3] - q[1]) / LBC};
  double e3[2] = {(q[2] - D[0]) / LCD, (q[3] - D[1]) / LCD};
  // joint C: -T2 e2 - T3 e3 + (0, -MC g) = 0 (a rod in tension T pulls each end inwards)
  double det = -e2[0] * (-e3[1]) - (-e3[0]) * (-e2[1]);
  double T2 = (0 * (-e3[1]) - (-e3[0]) * (MC * G)) / det;
  double T3 = ((-e2[0]) * (MC * G) - 0 * (-e2[1])) / det;
  // joint B: -T1 e1 + T2 e2 + (Hx, 0) + (0, -MB g) = 0 -> y row gives T1, x row gives Hx
  double T1 = (T2 * e2[1] - MB * G) / e1[1];
  double Hx = T1 * e1[0] - T2 * e2[0];
  // a rod row's multiplier is -T; the prescribed row's multiplier is the holding force
  double err =
      fmax(fmax(fabs(lam[0] + T1), fabs(lam[1] + T2)), fmax(fabs(lam[2] + T3), fabs(lam[3] - Hx)));
  printf("statics at crank angle 1.1: rod tensions crank %.12f coupler %.12f rocker %.12f, "
         "holding force %.12f N\n",
         -lam[0], -lam[1], -lam[2], lam[3]);
  printf("hand-solved statics:                 crank %.12f coupler %.12f rocker %.12f, "
         "holding force %.12f N (max difference %.2g)\n",
         T1, T2, T3, Hx, err);
  if (err > 1e-10 || fabs(dal_state_qddot(st)[2]) > 1e-12) bad = 1;
  dal_state_destroy(st);
  dal_system_destroy(sys);
  // 2. released: one degree of freedom, residuals and energy
  sys = build(0, 0);
  dal_state_create(sys, &st);
  dal_state_set(sys, st, 0, q, v);
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-9;
  dal_energies en0, en1;
  dal_make_consistent(sys, st, 0, NULL);
  dal_state_energies(st, &en0);
  if (dal_advance(sys, st, &o, 3.0)) {
    fprintf(stderr, "%s\n", dal_state_errmsg(st));
    return 1;
  }
  dal_state_energies(st, &en1);
  double phimax = 0.0;
  for (int r = 0; r < 3; ++r)
    phimax = fmax(phimax, fabs(dal_state_phi(st)[r]));
  printf("released: t=3, B at (%.6f, %.6f), max |phi| %.2g m, energy change %.2g J of %.4g\n",
         dal_state_q(st)[0], dal_state_q(st)[1], phimax, en1.E - en0.E, en0.E);
  if (phimax > 1e-8 || fabs(en1.E - en0.E) > 1e-5 * fabs(en0.E)) bad = 1;
  dal_state_destroy(st);
  dal_system_destroy(sys);
  if (check) printf("four_bar: %s\n", bad ? "FAILED" : "ok");
  return bad;
}
