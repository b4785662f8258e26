// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// dal_joint_forces: the pendulum's rod pull against the closed form m (g cos th + l thd^2)
// along the rod; the same pull from the multiplier of the Cartesian pendulum's rod; the double
// pendulum's two joints against the Cartesian double pendulum's rod rows (the upper rod's force
// alone, which dal_state_reactions cannot give); the bead on a turning ring against its
// Cartesian twin's ring constraint; zero for Cartesian placements; the refusals.
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

int main(void) {
  pendulum();
  double_pendulum();
  bead();
  return check_summary("test_joint_forces");
}
