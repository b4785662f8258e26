// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// dal_joint_forces: the pendulum's rod pull against the closed form m (g cos th + l thd^2)
// along the rod; the same pull from the multiplier of the Cartesian pendulum's rod; the double
// pendulum's two joints against the Cartesian double pendulum's rod rows (the upper rod's force
// alone, which dal_state_reactions cannot give); the bead on a turning ring against its
// Cartesian twin's ring constraint; a lever (a parent block that is not the identity) against
// its Cartesian twin's rows; zero for Cartesian placements; the refusals.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

// the Cartesian twin at the minimal state's positions and velocities, evaluated
static void twin(const dal_system *s, const dal_state *st, const dal_system *c, dal_state *sc) {
  int nc = dal_system_ncoords(c);
  double q[6], v[6];
  memcpy(q, dal_state_positions(st), (size_t)nc * sizeof(double));
  memcpy(v, dal_state_velocities(st), (size_t)nc * sizeof(double));
  (void)s;
  CHECK_OK(dal_state_set(c, sc, dal_state_time(st), q, v));
  CHECK_OK(dal_forward(c, sc));
}

// a scene in minimal coordinates and its Cartesian twin, with a state each
typedef struct twins {
  dal_system *s, *c;
  dal_state *st, *sc;
} twins;

static twins twins_open(dal_system *s, dal_system *c) {
  twins w = {s, c, NULL, NULL};
  CHECK(s && c);
  CHECK_OK(dal_state_create(s, &w.st));
  CHECK_OK(dal_state_create(c, &w.sc));
  return w;
}

static void twins_close(twins *w) {
  dal_state_destroy(w->st);
  dal_state_destroy(w->sc);
  dal_system_destroy(w->s);
  dal_system_destroy(w->c);
}

static double worst_rel(const double *a, const double *b, int n, double scale) {
  double w = 0;
  for (int i = 0; i < n; ++i)
    w = fmax(w, fabs(a[i] - b[i]) / scale);
  return w;
}

static void pendulum(void) {
  scn_knobs k = scn_default();
  k.m = 1.7;
  k.l = 0.8;
  twins w = twins_open(scn_pendulum(&k), scn_cart_pendulum(&k));
  dal_system *s = w.s, *c = w.c;
  dal_state *st = w.st, *sc = w.sc;
  unsigned long long seed = 11;
  double w_closed = 0, w_cart = 0, w_zero = 0;
  for (int i = 0; i < 200; ++i) {
    double th = check_rand(&seed, -3.1, 3.1), thd = check_rand(&seed, -6, 6);
    CHECK_OK(dal_state_set(s, st, 0.0, &th, &thd));
    CHECK_OK(dal_forward(s, st));
    double J[2], Jc[2], Fc[2], Z[2];
    CHECK_OK(dal_joint_forces(s, st, J));
    // closed form: tension T along the rod towards the pivot, r = l (sin th, -cos th)
    double T = k.m * (k.g * cos(th) + k.l * thd * thd);
    double ref[2] = {-T * sin(th), T * cos(th)};
    double scale = k.m * (k.g + k.l * 36.0);
    w_closed = fmax(w_closed, worst_rel(J, ref, 2, scale));
    // the Cartesian pendulum: the rod's force from its multiplier
    twin(s, st, c, sc);
    CHECK_OK(dal_constraint_forces(c, sc, Fc));
    w_cart = fmax(w_cart, worst_rel(J, Fc, 2, scale));
    // there the particle's own placement (Cartesian coordinates) holds nothing
    CHECK_OK(dal_joint_forces(c, sc, Jc));
    Z[0] = Z[1] = 0;
    w_zero = fmax(w_zero, worst_rel(Jc, Z, 2, scale));
  }
  printf("pendulum: joint force vs m (g cos th + l thd^2): %.2g; vs the Cartesian rod's "
         "multiplier: %.2g; Cartesian placement: %.2g (relative to m (g + l thd_max^2))\n",
         w_closed, w_cart, w_zero);
  CHECK(w_closed <= 1e-14);
  CHECK(w_cart <= 1e-12);
  CHECK(w_zero <= 1e-14);
  // refusals: not evaluated, a foreign state, NULL output
  double th = 0.3, thd = 0, J[2];
  CHECK_OK(dal_state_set(s, st, 0.0, &th, &thd));
  CHECK(dal_joint_forces(s, st, J) == DAL_E_STATE && strstr(dal_state_errmsg(st), "dal_forward"));
  CHECK(dal_joint_forces(c, st, J) == DAL_E_STATE);
  CHECK(dal_joint_forces(s, st, NULL) == DAL_E_ARG);
  CHECK(dal_joint_forces(s, NULL, J) == DAL_E_ARG);
  twins_close(&w);
}

// the double pendulum: the lower joint is rod2's pull, the upper one rod1's alone; in the
// Cartesian twin each rod is a row, so rod1's force on the upper particle is the sum of the
// constraint forces on both (rod2's pulls on them cancel)
static void double_pendulum(void) {
  scn_knobs k = scn_default();
  k.m = 1.3;
  k.m2 = 0.6;
  k.l2 = 0.7;
  twins w = twins_open(scn_double_pendulum(&k), scn_cart_double_pendulum(&k));
  dal_system *s = w.s, *c = w.c;
  dal_state *st = w.st, *sc = w.sc;
  unsigned long long seed = 5;
  double worst = 0, split = 0;
  for (int i = 0; i < 200; ++i) {
    double q[2], v[2];
    for (int j = 0; j < 2; ++j) {
      q[j] = check_rand(&seed, -3, 3);
      v[j] = check_rand(&seed, -4, 4);
    }
    CHECK_OK(dal_state_set(s, st, 0.0, q, v));
    CHECK_OK(dal_forward(s, st));
    double J[4], Fc[4], ref[4];
    CHECK_OK(dal_joint_forces(s, st, J));
    twin(s, st, c, sc);
    CHECK_OK(dal_constraint_forces(c, sc, Fc));
    for (int a = 0; a < 2; ++a) {
      ref[a] = Fc[a] + Fc[2 + a]; // rod1 on the upper particle
      ref[2 + a] = Fc[2 + a];     // rod2 on the lower
    }
    double scale = (k.m + k.m2) * (k.g + 16.0 * 2);
    worst = fmax(worst, worst_rel(J, ref, 4, scale));
    // the whole reaction on the upper particle is rod1's pull plus rod2's: not the joint force
    const double *N = dal_state_reactions(st);
    split = fmax(split, worst_rel(N, J, 2, scale));
  }
  printf("double pendulum: joint forces vs the Cartesian rods' multipliers: %.2g (the upper "
         "reaction differs from its joint force by up to %.2g)\n",
         worst, split);
  CHECK(worst <= 1e-12);
  CHECK(split > 1e-2);
  twins_close(&w);
}

// the bead on a ring turning about the vertical (3D, a rheonomic map) against the Cartesian bead
// on the turning circle: the ring's force on the bead from the two constraint rows
static void bead(void) {
  scn_knobs k = scn_default();
  k.R = 0.6;
  k.spin = 5.0;
  twins w = twins_open(scn_bead(&k), scn_cart_bead(&k));
  dal_system *s = w.s, *c = w.c;
  dal_state *st = w.st, *sc = w.sc;
  unsigned long long seed = 3;
  double worst = 0;
  for (int i = 0; i < 100; ++i) {
    double th = check_rand(&seed, -3, 3), thd = check_rand(&seed, -5, 5);
    double t = check_rand(&seed, 0, 2);
    CHECK_OK(dal_state_set(s, st, t, &th, &thd));
    CHECK_OK(dal_forward(s, st));
    double J[3], Fc[3];
    CHECK_OK(dal_joint_forces(s, st, J));
    twin(s, st, c, sc);
    CHECK_OK(dal_constraint_forces(c, sc, Fc));
    worst = fmax(worst, worst_rel(J, Fc, 3, k.m * (k.g + k.R * 100.0)));
  }
  printf("bead on the turning ring: joint force vs the ring constraint's: %.2g\n", worst);
  CHECK(worst <= 1e-12);
  twins_close(&w);
}

// a lever: the second particle hangs on a rod from a point that is not its parent's position
// but s times it, r_k = s r_p + l (sin th, -cos th), so its parent block is s I and the joint
// hands s J_k to the parent (not J_k). In Cartesian coordinates the same scene holds p by a rod
// to the origin and k by |r_k - s r_p| = l: the upper joint is the first rod's multiplier alone
#define LEVER_S 1.5
#define LEVER_L 0.7
static int lever_map(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet sn, cs;
  dal_sincos(in[2], &sn, &cs);
  out[0] = dal_add(dal_scale(in[0], p[0]), dal_scale(sn, p[1]));
  out[1] = dal_sub(dal_scale(in[1], p[0]), dal_scale(cs, p[1]));
  return 0;
}
static int lever_rod(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet e[2] = {dal_sub(in[2], dal_scale(in[0], p[0])), dal_sub(in[3], dal_scale(in[1], p[0]))};
  out[0] = dal_addc(dal_norm(e, 2), -p[1]);
  return 0;
}
static const dal_primitive lever_map_prim = {
    .name = "lever", .version = 1, .nin = 3, .nout = 2, .nparam = 2, .eval = lever_map};
static const dal_primitive lever_rod_prim = {
    .name = "lever_rod", .version = 1, .nin = 4, .nout = 1, .nparam = 2, .eval = lever_rod};

static dal_system *lever(int cart) {
  static const double g2[2] = {0.0, -SCN_G}, par[2] = {LEVER_S, LEVER_L};
  dal_builder *b = NULL;
  int c[4], p[2], rc = dal_builder_create(2, &b);
  const char *names[4] = {"x1", "y1", "x2", "y2"};
  for (int i = 0; i < (cart ? 4 : 2) && !rc; ++i)
    rc = dal_builder_add_coord(b, cart ? names[i] : i ? "theta2" : "theta1", &c[i]);
  if (!rc) rc = dal_builder_add_particle(b, "upper", 1.2, &p[0]);
  if (!rc) rc = dal_builder_add_particle(b, "lower", 0.8, &p[1]);
  for (int k = 0; k < 2 && !rc; ++k) {
    dal_place_def pd = dal_default_place_def();
    pd.prim = cart ? &dal_map_cartesian2 : k ? &lever_map_prim : &dal_map_pendulum;
    pd.coords = c + (cart ? 2 * k : k);
    pd.ncoords = cart ? 2 : 1;
    pd.parent = cart || !k ? -1 : p[0];
    if (!cart && !k) pd.param[DAL_PENDULUM_L] = 1.0;
    if (!cart && k) {
      pd.param_list = par;
      pd.nparam_list = 2;
    }
    rc = dal_builder_place_def(b, p[k], &pd);
  }
  if (!rc) rc = dal_builder_set_gravity(b, g2);
  if (cart && !rc) {
    dal_constraint_def cd = dal_default_constraint_def();
    cd.name = "rod1";
    cd.prim = &dal_con_anchor2;
    cd.parts = p;
    cd.nparts = 1;
    cd.param[DAL_ANCHOR_L] = 1.0;
    rc = dal_builder_add_constraint_def(b, &cd, NULL);
    cd = dal_default_constraint_def();
    cd.name = "lever rod";
    cd.prim = &lever_rod_prim;
    cd.parts = p;
    cd.nparts = 2;
    cd.param_list = par;
    cd.nparam_list = 2;
    if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
  }
  return scn_finish(b, rc);
}

static void lever_test(void) {
  twins w = twins_open(lever(0), lever(1));
  if (!w.s || !w.c) return;
  unsigned long long seed = 23;
  double worst = 0, naive = 0;
  for (int i = 0; i < 100; ++i) {
    double q[2], v[2];
    for (int j = 0; j < 2; ++j) {
      q[j] = check_rand(&seed, -3, 3);
      v[j] = check_rand(&seed, -3, 3);
    }
    CHECK_OK(dal_state_set(w.s, w.st, 0.0, q, v));
    CHECK_OK(dal_forward(w.s, w.st));
    double J[4], Fc[4], ref[4];
    CHECK_OK(dal_joint_forces(w.s, w.st, J));
    twin(w.s, w.st, w.c, w.sc);
    CHECK_OK(dal_constraint_forces(w.c, w.sc, Fc));
    // the first rod (row 0) on the upper particle: lambda times the unit vector from the origin
    const double *r = dal_state_positions(w.sc), lam = dal_state_lambda(w.sc)[0];
    double len = hypot(r[0], r[1]);
    ref[0] = lam * r[0] / len;
    ref[1] = lam * r[1] / len;
    ref[2] = Fc[2]; // only the lever rod acts on the lower particle
    ref[3] = Fc[3];
    double scale = 2.0 * (SCN_G + 9.0 * 2.5);
    worst = fmax(worst, worst_rel(J, ref, 4, scale));
    // handing J_k up unscaled (a translation's rule) would be wrong here
    const double *N = dal_state_reactions(w.st);
    double plain[2] = {N[0] + J[2], N[1] + J[3]};
    naive = fmax(naive, worst_rel(plain, ref, 2, scale));
  }
  printf("lever (parent block 1.5 I): joint forces vs the Cartesian rows' multipliers: %.2g (the "
         "translation's rule would be off by %.2g)\n",
         worst, naive);
  CHECK(worst <= 1e-12);
  CHECK(naive > 1e-2);
  twins_close(&w);
}

int main(void) {
  pendulum();
  double_pendulum();
  bead();
  lever_test();
  return check_summary("test_joint_forces");
}
