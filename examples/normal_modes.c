// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Normal modes from the exact linearization, confirmed by integrating the motion.
//
// Scenes (minimal coordinates, g = 9.81):
//  1. double pendulum, equal masses m = 1 and lengths l = 1 (dal_map_pendulum + dal_map_hanging):
//     omega^2 = (g/l)(2 -+ sqrt 2), shapes (1, +-sqrt 2) (Goldstein, Classical Mechanics, 6.4);
//  2. a hanging chain of 4 pendulums (unit masses, lengths 1, 0.8, 0.6, 0.5): no closed form;
//  3. a trap U = (k1 x'^2 + k2 y'^2)/2 turning at w = 1 with its frame (x', y'), seen in the
//     rotating frame (a user map r = Rot(w t)(x, y) and a jet potential U(r, t)): the Coriolis
//     terms give C = 2 m w [0 -1; 1 0]; with k1 = 0.5, k2 = 0.2 the stiffness K = diag(k1 - w^2,
//     k2 - w^2) is negative definite, yet the eigenvalues of the first-order Jacobian are
//     imaginary (gyroscopic stabilization, from lambda^4 + (a + b + 4 w^2) lambda^2 + a b = 0);
//     with k1 = 3, k2 = 0.5 rotation does not help (a b < 0).
// What is computed: dal_normal_modes at the equilibrium (exact K, C, M by jets; dsygv for the
// modes, dgeev of the vector-field Jacobian for the verdict).
// Checks (--check and full mode alike):
//  - scene 1 against the closed form (1e-13);
//  - every mode of scenes 1 and 2 by integration: started from 1e-6 times its shape at rest, the
//    chain is back at its start after one period 2 pi / omega and at minus it after half a
//    period (Bulirsch-Stoer, rtol 1e-12), to 1e-6 of the amplitude: the modes are the motion's;
//  - scene 3: the verdicts (neutral, unstable), the eigenvalues against the quartic (1e-12), and
//    30 s of motion from 1e-3 off the centre that stays within 10x (stabilized) or grows past
//    100x (unstable).
// Full mode also prints the chain's frequencies and mode shapes.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "example_util.h"

#define PI 3.14159265358979323846
static const double grav = 9.81;

// a chain of n pendulums (masses 1) with the given lengths; n = 2 with l = 1, 1 is scene 1
static dal_system *chain(int n, const double *len) {
  dal_builder *b = NULL;
  double g[2] = {0, -grav};
  int rc = dal_builder_create(2, &b), prev = -1;
  for (int k = 0; k < n && !rc; ++k) {
    char name[16];
    int q, p;
    snprintf(name, sizeof name, "theta%d", k + 1);
    rc = dal_builder_add_coord(b, name, &q);
    snprintf(name, sizeof name, "bob%d", k + 1);
    if (!rc) rc = dal_builder_add_particle(b, name, 1.0, &p);
    // the first bob swings about the fixed pivot at the origin, the others hang from it
    dal_place_def pd = dal_default_place_def();
    pd.coords = &q;
    pd.ncoords = 1;
    if (k == 0) {
      pd.prim = &dal_map_pendulum;
      pd.param[DAL_PENDULUM_L] = len[k];
    } else {
      pd.prim = &dal_map_hanging;
      pd.parent = prev;
      pd.param[DAL_HANGING_L] = len[k];
    }
    if (!rc) rc = dal_builder_place_def(b, p, &pd);
    prev = p;
  }
  if (!rc) rc = dal_builder_set_gravity(b, g);
  return ex_compile(b, rc);
}

// the modes of a chain at rest, each confirmed by integrating one period
static int chain_modes(const dal_system *sys, const char *name, int verbose, double *w2) {
  int n = dal_system_ncoords(sys), bad = 0;
  dal_state *st = NULL;
  double z[8] = {0}, X[64], q0[8];
  dal_modes md;
  if (dal_state_create(sys, &st) || dal_state_set(sys, st, 0.0, z, z) ||
      dal_normal_modes(sys, st, w2, X, NULL, NULL, &md)) {
    fprintf(stderr, "%s: %s\n", name, dal_state_errmsg(st));
    dal_state_destroy(st);
    return 1;
  }
  printf("%s: %s at rest (max Re lambda %.1e)\n", name, dal_stability_name(md.verdict),
         md.max_real);
  bad |= md.verdict != DAL_NEUTRAL;
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_BS;
  o.rtol = o.atol = 1e-12;
  for (int i = 0; i < n; ++i) {
    double w = sqrt(w2[i]), T = 2 * PI / w, amp = 0.0, eh = 0.0, ef = 0.0;
    for (int j = 0; j < n; ++j) {
      q0[j] = 1e-6 * X[i * n + j];
      amp = fmax(amp, fabs(q0[j]));
    }
    int rc = dal_state_set(sys, st, 0.0, q0, z);
    if (!rc) rc = dal_advance(sys, st, &o, T / 2);
    for (int j = 0; j < n && !rc; ++j)
      eh = fmax(eh, fabs(dal_state_q(st)[j] + q0[j]));
    if (!rc) rc = dal_advance(sys, st, &o, T);
    for (int j = 0; j < n && !rc; ++j)
      ef = fmax(ef, fabs(dal_state_q(st)[j] - q0[j]));
    if (rc) {
      fprintf(stderr, "%s mode %d: %s\n", name, i + 1, dal_state_errmsg(st));
      bad = 1;
      continue;
    }
    printf("  mode %d: omega = %.10f rad/s; after T/2 |q + q0| = %.1e, after T |q - q0| = %.1e "
           "(amplitude %.0e)\n",
           i + 1, w, eh, ef, amp);
    if (verbose) {
      printf("          shape");
      for (int j = 0; j < n; ++j)
        printf(" %+.6f", X[i * n + j]);
      printf("\n");
    }
    bad |= !(eh <= 1e-6 * amp && ef <= 1e-6 * amp);
  }
  dal_state_destroy(st);
  return bad;
}

// rotating frame r = Rot(w t)(x, y) and a trap turning with it
static int rotating(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  dal_jet s, c;
  dal_sincos(dal_scale(t, p[0]), &s, &c);
  out[0] = dal_sub(dal_mul(in[0], c), dal_mul(in[1], s));
  out[1] = dal_add(dal_mul(in[0], s), dal_mul(in[1], c));
  return 0;
}
static const dal_primitive prim_rotating = {.name = "rotating",
                                            .version = 1,
                                            .nin = 2,
                                            .nout = 2,
                                            .nparam = 1,
                                            .eval = rotating,
                                            .doc = "in (x, y); param (w); out Rot(w t) (x, y)"};
typedef struct trap {
  double w, k1, k2;
} trap;
static int trap_pot(const dal_jet *r, dal_jet t, dal_jet *U, void *ctx) {
  const trap *tr = ctx;
  dal_jet s, c;
  dal_sincos(dal_scale(t, tr->w), &s, &c);
  dal_jet xp = dal_add(dal_mul(r[0], c), dal_mul(r[1], s));
  dal_jet yp = dal_sub(dal_mul(r[1], c), dal_mul(r[0], s));
  *U = dal_add(dal_scale(dal_sq(xp), 0.5 * tr->k1), dal_scale(dal_sq(yp), 0.5 * tr->k2));
  return 0;
}

static int trap_scene(const trap *tr, dal_stability expect) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  int q[2], p, bad = 0, rc = dal_builder_create(2, &b);
  if (!rc) rc = dal_builder_add_coord(b, "x", &q[0]);
  if (!rc) rc = dal_builder_add_coord(b, "y", &q[1]);
  if (!rc) rc = dal_builder_add_particle(b, "ion", 1.0, &p);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &prim_rotating;
  pd.coords = q;
  pd.ncoords = 2;
  pd.param[0] = tr->w; // the frame's rate w, the primitive's one parameter
  if (!rc) rc = dal_builder_place_def(b, p, &pd);
  if (!rc) rc = dal_builder_add_potential_r(b, trap_pot, (void *)tr);
  if (!rc) rc = dal_builder_compile(b, &sys);
  dal_builder_destroy(b);
  double z[2] = {0, 0}, w2[2], lr[4], li[4], K[4];
  dal_modes md;
  if (!rc) rc = dal_state_create(sys, &st);
  if (!rc) rc = dal_state_set(sys, st, 0.0, z, z);
  if (!rc) rc = dal_linearize(sys, st, NULL, NULL, K);
  if (!rc) rc = dal_normal_modes(sys, st, w2, NULL, lr, li, &md);
  if (rc) {
    fprintf(stderr, "trap: %s\n", st ? dal_state_errmsg(st) : "build failed");
    dal_state_destroy(st);
    dal_system_destroy(sys);
    return 1;
  }
  printf("rotating trap k1 = %g, k2 = %g, w = %g: K = diag(%g, %g), omega^2 = %g, %g -> %s\n",
         tr->k1, tr->k2, tr->w, K[0], K[3], w2[0], w2[1], dal_stability_name(md.verdict));
  bad |= md.verdict != expect;
  // eigenvalues against the quartic lambda^4 + B lambda^2 + a b = 0 (unit mass)
  double a = tr->k1 - tr->w * tr->w, bb = tr->k2 - tr->w * tr->w, B = a + bb + 4 * tr->w * tr->w;
  double D = B * B - 4 * a * bb;
  for (int s = 0; s < 2; ++s) {
    double mu = (-B + (s ? -1 : 1) * sqrt(D)) / 2; // D > 0 for both parameter sets here
    double er = mu >= 0 ? sqrt(mu) : 0.0, ei = mu < 0 ? sqrt(-mu) : 0.0;
    int found = 0;
    for (int i = 0; i < 4; ++i)
      found |= hypot(fabs(lr[i]) - er, fabs(li[i]) - ei) <= 1e-12;
    printf("  lambda = +-(%.10f + %.10fi) %s\n", er, ei, found ? "found" : "MISSING");
    bad |= !found;
  }
  // 30 s of motion from 1e-3 off the centre
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = o.atol = 1e-10;
  double q0[2] = {1e-3, 0.0}, big = 0.0;
  rc = dal_state_set(sys, st, 0.0, q0, z);
  for (int k = 1; k <= 300 && !rc; ++k) {
    rc = dal_advance(sys, st, &o, 0.1 * k);
    big = fmax(big, hypot(dal_state_q(st)[0], dal_state_q(st)[1]));
  }
  printf("  30 s from 1e-3 off the centre: max distance %.3g\n", big);
  bad |= rc != 0 || (expect == DAL_NEUTRAL ? !(big < 1e-2) : !(big > 1e-1));
  dal_state_destroy(st);
  dal_system_destroy(sys);
  return bad;
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0, bad = 0;
  // 1. double pendulum against the closed form
  double l2[2] = {1.0, 1.0}, w2[4];
  dal_system *sys = chain(2, l2);
  if (!sys) return 1;
  bad |= chain_modes(sys, "double pendulum", !check, w2);
  double e1 = grav * (2 - sqrt(2.0)), e2 = grav * (2 + sqrt(2.0));
  printf("  closed form omega^2 = (g/l)(2 -+ sqrt 2) = %.12f, %.12f; computed %.12f, %.12f\n", e1,
         e2, w2[0], w2[1]);
  bad |= !(fabs(w2[0] - e1) <= 1e-13 * e2 && fabs(w2[1] - e2) <= 1e-13 * e2);
  dal_system_destroy(sys);
  // 2. a chain of four
  double l4[4] = {1.0, 0.8, 0.6, 0.5};
  sys = chain(4, l4);
  if (!sys) return 1;
  bad |= chain_modes(sys, "chain of 4 pendulums", !check, w2);
  dal_system_destroy(sys);
  // 3. rotating traps
  trap stab = {1.0, 0.5, 0.2}, unst = {1.0, 3.0, 0.5};
  bad |= trap_scene(&stab, DAL_NEUTRAL);
  bad |= trap_scene(&unst, DAL_UNSTABLE);
  return ex_verdict(bad, "ok");
}
