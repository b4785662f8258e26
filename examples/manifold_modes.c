// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Analysis on the constraint manifold: the four-bar linkage's equilibrium, static loads and
// mode, and the pitchfork of a bead on a turning circle, both in Cartesian coordinates.
//
// Problem 1: ground pivots A = (0, 0) and D = (1.5, 0); crank A-B (1), coupler B-C (1.2),
// rocker C-D (0.9); masses m_B = 1, m_C = 2; gravity g down. Coordinates (xB, yB, xC, yC),
// constraints 'crank', 'coupler', 'rocker' (one degree of freedom). dal_equilibrium finds the
// hanging configuration by Newton on the manifold from a rough guess and leaves the rod
// multipliers (the static loads) in the state; dal_linearize_full gives the full-space M, K,
// G and the null-space basis N; dal_normal_modes the one mode.
// Problem 2: a bead (unit mass) on a circle of radius R turning at w about the vertical,
// Cartesian (x, y, z) with dal_con_turning_circle (two rows); dal_continue in w follows the
// bottom point and locates the pitchfork.
// Checks (--check): (1) statics: the vertical forces of the two ground rods carry the whole
// weight (m_B + m_C) g; (2) the reduced stiffness equals N' K N at the equilibrium; (3) the
// mode against a crank-angle model with the coupler and rocker solved in closed form
// (U''(theta) / M(theta) by jets of that closed form); (4) the pitchfork at sqrt(g/R).
#include <dalembert/dalembert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "example_util.h"

#define G 9.81
static const double LA = 1.0, LB = 1.2, LC = 0.9, DX = 1.5, MB = 1.0, MC = 2.0, R = 0.6;

static dal_constraint_def rod(const char *name, const dal_primitive *prim, int *parts, int np,
                              double L, double x0) {
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = name;
  cd.prim = prim;
  cd.parts = parts;
  cd.nparts = np;
  cd.param[DAL_ANCHOR_L] = L; // DAL_DISTANCE_L is the same first slot
  if (prim == &dal_con_anchor2) cd.param[DAL_ANCHOR_X0] = x0;
  return cd;
}

static dal_system *fourbar(void) {
  dal_builder *b = NULL;
  int c[4], p[2];
  double g[2] = {0.0, -G};
  const char *names[4] = {"xB", "yB", "xC", "yC"}, *pn[2] = {"B", "C"};
  const double m[2] = {MB, MC};
  dal_builder_create(2, &b);
  ex_cartesian_particles(b, 2, 2, pn, m, names, c, p);
  dal_builder_set_gravity(b, g);
  dal_constraint_def k1 = rod("crank", &dal_con_anchor2, &p[0], 1, LA, 0.0);
  dal_constraint_def k2 = rod("coupler", &dal_con_distance2, p, 2, LB, 0.0);
  dal_constraint_def k3 = rod("rocker", &dal_con_anchor2, &p[1], 1, LC, DX);
  dal_builder_add_constraint_def(b, &k1, NULL);
  dal_builder_add_constraint_def(b, &k2, NULL);
  dal_builder_add_constraint_def(b, &k3, NULL);
  return ex_compile(b, 0);
}

// the crank-angle model: U'(th), U''(th) and M(th) by jets of the closed-form joint C
static void crank_model(double th, double *Up, double *Upp, double *Mth) {
  dal_jet t = dal_var(th, 1.0);
  dal_jet bx = dal_scale(dal_cos(t), LA), by = dal_scale(dal_sin(t), LA);
  dal_jet px = dal_sub(dal_const(DX), bx), py = dal_scale(by, -1.0);
  dal_jet L2 = dal_add(dal_sq(px), dal_sq(py)), L = dal_sqrt(L2);
  dal_jet x = dal_div(dal_addc(L2, LB * LB - LC * LC), dal_scale(L, 2.0));
  dal_jet h = dal_sqrt(dal_sub(dal_const(LB * LB), dal_sq(x)));
  dal_jet cx = dal_add(bx, dal_div(dal_add(dal_mul(x, px), dal_mul(h, py)), L));
  dal_jet cy = dal_add(by, dal_div(dal_sub(dal_mul(x, py), dal_mul(h, px)), L));
  dal_jet U = dal_scale(dal_add(dal_scale(by, MB), dal_scale(cy, MC)), G);
  *Up = U.d;
  *Upp = U.dd;
  *Mth = MB * (bx.d * bx.d + by.d * by.d) + MC * (cx.d * cx.d + cy.d * cy.d);
}

static dal_system *bead(double w) {
  dal_builder *b = NULL;
  int c[3], p;
  double g[3] = {0.0, 0.0, -G};
  const char *names[3] = {"x", "y", "z"};
  dal_builder_create(3, &b);
  for (int i = 0; i < 3; ++i)
    dal_builder_add_coord(b, names[i], &c[i]);
  dal_builder_add_particle(b, "bead", 1.0, &p);
  dal_place_def d = dal_default_place_def();
  d.prim = &dal_map_cartesian3;
  d.coords = c;
  d.ncoords = 3;
  dal_builder_place_def(b, p, &d);
  dal_builder_set_gravity(b, g);
  dal_constraint_def k = dal_default_constraint_def();
  k.name = "ring";
  k.prim = &dal_con_turning_circle;
  k.parts = &p;
  k.nparts = 1;
  k.param[DAL_TURNING_CIRCLE_R] = R;
  k.param[DAL_TURNING_CIRCLE_W] = w;
  dal_builder_add_constraint_def(b, &k, NULL);
  return ex_compile(b, 0);
}

static int rebuild(double w, dal_system **out, void *ctx) {
  (void)ctx;
  *out = bead(w);
  return *out ? 0 : 1;
}

static int on_point(double w, const dal_system *sys, const dal_state *st, dal_stability v,
                    dal_branch_kind kind, void *ctx) {
  (void)sys;
  (void)st;
  printf("  w = %.10f  %-10s%s\n", w, dal_stability_name(v),
         kind == DAL_BRANCH_CRITICAL ? "  <- critical" : "");
  if (kind == DAL_BRANCH_CRITICAL) *(double *)ctx = w;
  return 0;
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0, bad = 0;
  dal_system *sys = fourbar();
  dal_state *st = NULL;
  if (!sys || dal_state_create(sys, &st)) return 1;
  // a rough guess below the pivots, not on the manifold
  double q[4] = {0.2, -1.0, 1.2, -1.0}, v[4] = {0};
  dal_state_set(sys, st, 0.0, q, v);
  dal_equilibrium_report rep;
  if (dal_equilibrium(sys, st, NULL, &rep)) {
    printf("equilibrium: %s\n", dal_state_errmsg(st));
    return 1;
  }
  const double *qs = dal_state_q(st), *lam = dal_state_lambda(st);
  printf("four-bar equilibrium in %d Newton steps: B = (%.6f, %.6f), C = (%.6f, %.6f)\n",
         rep.iterations, qs[0], qs[1], qs[2], qs[3]);
  printf("static loads (lambda = -tension): crank %.6f, coupler %.6f, rocker %.6f N\n", lam[0],
         lam[1], lam[2]);
  // (1) the ground rods hold the weight: rod forces on B and C along their unit vectors
  double eB[2] = {qs[0] / LA, qs[1] / LA}, eC[2] = {(qs[2] - DX) / LC, qs[3] / LC};
  double lift = lam[0] * eB[1] + lam[2] * eC[1]; // a row pulls its particle by lambda e
  printf("vertical load on the ground pivots %.12f N, weight %.12f N\n", lift, (MB + MC) * G);
  bad |= fabs(lift - (MB + MC) * G) > 1e-10;

  // (2) reduced vs full-space matrices
  double M[16], K[16], Gm[12], N[4], Mr[1], Kr[1];
  dal_linearize_full(sys, st, M, NULL, K, Gm, N);
  dal_linearize(sys, st, Mr, NULL, Kr);
  double nkn = 0.0, nmn = 0.0;
  for (int a = 0; a < 4; ++a)
    for (int b2 = 0; b2 < 4; ++b2) {
      nkn += N[a] * K[b2 * 4 + a] * N[b2];
      nmn += N[a] * M[b2 * 4 + a] * N[b2];
    }
  printf("reduced M_r = %.12f (N'MN %.12f), K_r = %.12f (N'KN %.12f)\n", Mr[0], nmn, Kr[0], nkn);
  bad |= fabs(Kr[0] - nkn) > 1e-10 * fabs(nkn) || fabs(Mr[0] - nmn) > 1e-12 * nmn;

  // (3) the mode against the crank-angle model at the same crank angle
  double w2[1];
  dal_modes md;
  dal_normal_modes(sys, st, w2, NULL, NULL, NULL, &md);
  double th = atan2(qs[1], qs[0]), up, upp, mth;
  crank_model(th, &up, &upp, &mth);
  printf("mode: omega^2 = %.12f (%s); crank-angle model U''/M = %.12f (U' = %.1e)\n", w2[0],
         dal_stability_name(md.verdict), upp / mth, up);
  bad |= fabs(w2[0] - upp / mth) > 1e-10 * w2[0] || md.verdict != DAL_NEUTRAL;
  dal_state_destroy(st);
  dal_system_destroy(sys);

  // (4) the turning bead's pitchfork by continuation along the bottom point
  double wc = sqrt(G / R), found = 0.0, q0[3] = {0.0, 0.0, -R};
  dal_continuation_opts o = dal_default_continuation_opts();
  o.p0 = 0.5 * wc;
  o.p1 = 1.5 * wc;
  o.npoints = check ? 6 : 21;
  dal_continuation_report crep;
  printf("Cartesian bead on a turning circle, bottom branch:\n");
  if (dal_continue(rebuild, q0, &o, on_point, &crep, &found)) printf("continue: %s\n", crep.msg);
  printf("pitchfork at w = %.12f, sqrt(g/R) = %.12f\n", found, wc);
  bad |= fabs(found - wc) > 1e-9 * wc;
  if (check) printf(bad ? "CHECK FAILED\n" : "check passed\n");
  return bad;
}
