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

// one comparison over random states (q, qdot and t drawn from the ranges) of the minimal
// scene: its joint forces J against what `ref` derives from the twin evaluated at the same
// motion; `ref` may also give `alt`, another force whose distance to the reference is
// reported (a rule that must differ, or a second reference). Returns the worst |J - ref| and
// sets *alt_worst, both relative to `scale`
typedef void ref_fn(const twins *w, double *ref, double *alt);
typedef struct sweep_spec {
  double qmax, vmax, tmax, scale;
  unsigned long long seed;
  const char *what, *alt_what; // printed: the reference, and alt (NULL: none)
  double alt_bound;            // alt within it of the reference, or (< 0) farther than -alt_bound
} sweep_spec;

static double sweep(const twins *w, const sweep_spec *sp, ref_fn *ref, double *alt_worst) {
  int n = dal_system_ncoords(w->s);
  int nd = dal_system_nparticles(w->s) * dal_system_dim(w->s);
  unsigned long long seed = sp->seed;
  double worst = 0;
  *alt_worst = 0;
  for (int i = 0; i < 200; ++i) {
    double q[2], v[2], t = sp->tmax > 0 ? check_rand(&seed, 0, sp->tmax) : 0.0;
    for (int j = 0; j < n; ++j) {
      q[j] = check_rand(&seed, -sp->qmax, sp->qmax);
      v[j] = check_rand(&seed, -sp->vmax, sp->vmax);
    }
    CHECK_OK(dal_state_set(w->s, w->st, t, q, v));
    CHECK_OK(dal_forward(w->s, w->st));
    double J[6], r[6], alt[6];
    CHECK_OK(dal_joint_forces(w->s, w->st, J));
    twin(w->s, w->st, w->c, w->sc);
    memcpy(alt, J, sizeof alt);
    ref(w, r, alt);
    worst = fmax(worst, worst_rel(J, r, nd, sp->scale));
    *alt_worst = fmax(*alt_worst, worst_rel(alt, r, nd, sp->scale));
  }
  return worst;
}

// a sweep printed and checked: J within 1e-14 (relative) of the reference, alt as the spec says
static void run_case(const twins *w, const sweep_spec *sp, ref_fn *ref) {
  double alt = 0, worst = sweep(w, sp, ref, &alt);
  printf("%s: %.2g", sp->what, worst);
  if (sp->alt_what) printf("; %s: %.2g", sp->alt_what, alt);
  printf(" (relative to %g)\n", sp->scale);
  CHECK_MSG(worst <= 1e-14, "%s: %.3g", sp->what, worst);
  if (sp->alt_what)
    CHECK_MSG(sp->alt_bound > 0 ? alt <= sp->alt_bound : alt > -sp->alt_bound, "%s: %.3g",
              sp->alt_what, alt);
}

// the pendulum (m 1.7, l 0.8): the rod's tension T = m (g cos th + l thd^2) along the rod
// towards the pivot, r = l (sin th, -cos th); alt: the Cartesian rod's force from its
// multiplier. There the particle's own placement (Cartesian coordinates) holds nothing
#define PEND_M 1.7
#define PEND_L 0.8
static void pendulum_ref(const twins *w, double *ref, double *alt) {
  double th = dal_state_q(w->st)[0], thd = dal_state_qdot(w->st)[0];
  double T = PEND_M * (SCN_G * cos(th) + PEND_L * thd * thd), Jc[2];
  ref[0] = -T * sin(th);
  ref[1] = T * cos(th);
  CHECK_OK(dal_constraint_forces(w->c, w->sc, alt));
  CHECK_OK(dal_joint_forces(w->c, w->sc, Jc));
  CHECK(fabs(Jc[0]) + fabs(Jc[1]) <= 1e-14 * PEND_M * (SCN_G + 36.0 * PEND_L));
}

static void pendulum(void) {
  scn_knobs k = scn_default();
  k.m = PEND_M;
  k.l = PEND_L;
  twins w = twins_open(scn_pendulum(&k), scn_cart_pendulum(&k));
  const sweep_spec sp = {3.1,
                         6,
                         0,
                         PEND_M * (SCN_G + 36.0 * PEND_L),
                         11,
                         "pendulum: joint force vs m (g cos th + l thd^2)",
                         "the Cartesian rod's multiplier vs it",
                         1e-14};
  run_case(&w, &sp, pendulum_ref);
  // refusals: not evaluated, a foreign state, NULL output
  double th = 0.3, thd = 0, J[2];
  CHECK_OK(dal_state_set(w.s, w.st, 0.0, &th, &thd));
  CHECK(dal_joint_forces(w.s, w.st, J) == DAL_E_STATE &&
        strstr(dal_state_errmsg(w.st), "dal_forward"));
  CHECK(dal_joint_forces(w.c, w.st, J) == DAL_E_STATE);
  CHECK(dal_joint_forces(w.s, w.st, NULL) == DAL_E_ARG);
  CHECK(dal_joint_forces(w.s, NULL, J) == DAL_E_ARG);
  twins_close(&w);
}

// the double pendulum: the lower joint is rod2's pull, the upper one rod1's alone; in the
// Cartesian twin each rod is a row, so rod1's force on the upper particle is the sum of the
// constraint forces on both (rod2's pulls on them cancel). alt: the whole reaction on the
// upper particle (rod1's pull plus rod2's), which is not its joint force
static void double_ref(const twins *w, double *ref, double *alt) {
  double Fc[4];
  CHECK_OK(dal_constraint_forces(w->c, w->sc, Fc));
  for (int a = 0; a < 2; ++a) {
    ref[a] = Fc[a] + Fc[2 + a];
    ref[2 + a] = Fc[2 + a];
    alt[a] = dal_state_reactions(w->st)[a];
  }
}

static void double_pendulum(void) {
  scn_knobs k = scn_default();
  k.m = 1.3;
  k.m2 = 0.6;
  k.l2 = 0.7;
  twins w = twins_open(scn_double_pendulum(&k), scn_cart_double_pendulum(&k));
  const sweep_spec sp = {3,
                         4,
                         0,
                         (k.m + k.m2) * (k.g + 16.0 * 2),
                         5,
                         "double pendulum: joint forces vs the Cartesian rods' multipliers",
                         "the upper reaction vs its joint force (must differ)",
                         -1e-2};
  run_case(&w, &sp, double_ref);
  twins_close(&w);
}

// the bead on a ring turning about the vertical (3D, a rheonomic map) against the Cartesian bead
// on the turning circle: the ring's force on the bead from the two constraint rows
static void bead_ref(const twins *w, double *ref, double *alt) {
  (void)alt;
  CHECK_OK(dal_constraint_forces(w->c, w->sc, ref));
}

static void bead(void) {
  scn_knobs k = scn_default();
  k.R = 0.6;
  k.spin = 5.0;
  twins w = twins_open(scn_bead(&k), scn_cart_bead(&k));
  const sweep_spec sp = {3,    5,
                         2,    k.m * (k.g + k.R * 100.0),
                         3,    "bead on the turning ring: joint force vs the ring constraint's",
                         NULL, 0};
  run_case(&w, &sp, bead_ref);
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

// the first rod (row 0) on the upper particle: lambda times the unit vector from the origin;
// only the lever rod acts on the lower particle. alt: the child's force handed up unscaled (a
// translation's rule), wrong here
static void lever_ref(const twins *w, double *ref, double *alt) {
  double Fc[4];
  CHECK_OK(dal_constraint_forces(w->c, w->sc, Fc));
  const double *r = dal_state_positions(w->sc), lam = dal_state_lambda(w->sc)[0];
  double len = hypot(r[0], r[1]);
  ref[0] = lam * r[0] / len;
  ref[1] = lam * r[1] / len;
  ref[2] = Fc[2];
  ref[3] = Fc[3];
  const double *N = dal_state_reactions(w->st);
  alt[0] = N[0] + alt[2];
  alt[1] = N[1] + alt[3];
}

static void lever_test(void) {
  twins w = twins_open(lever(0), lever(1));
  if (!w.s || !w.c) return;
  const sweep_spec sp = {
      3,
      3,
      0,
      2.0 * (SCN_G + 9.0 * 2.5),
      23,
      "lever (parent block 1.5 I): joint forces vs the Cartesian rows' multipliers",
      "the translation's rule (must differ)",
      -1e-2};
  run_case(&w, &sp, lever_ref);
  twins_close(&w);
}

int main(void) {
  pendulum();
  double_pendulum();
  bead();
  lever_test();
  return check_summary("test_joint_forces");
}
