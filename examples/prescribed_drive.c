// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A prescribed drive: the work the drive does equals the change of the energy.
//
// Problem: a bead (0.4 kg) on a rod turning in a vertical plane; the rod's angle phi is
// driven, phi = phi0 + 0.6 sin(2 t) (dal_con_prescribed with a dal_prescribed motion), and
// the bead slides along it, held towards the hub by a spring (k = 30 N/m, rest 0.5 m) and
// pulled down by gravity. Coordinates: (rho, phi), the bead at rho (cos phi, sin phi): a user
// map r(q, t). Constraint: 'drive' on phi. Formulation: GGL DAE (IDA) and index-1 + projection.
// Check (--check): the generalized constraint force on phi, (G' lambda)_phi, is the torque the
// drive applies; its power times phidot, integrated alongside (Simpson's rule on the monitor
// grid), equals E(t) - E(0).
#include <dalembert/dalembert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "example_util.h"

static int motion(dal_jet t, dal_jet *f, void *ctx) {
  (void)ctx;
  *f = dal_scale(dal_sin(dal_scale(t, 2.0)), 0.6);
  return 0;
}

static int rod_map(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx) {
  (void)t;
  (void)ctx;
  r[0] = dal_mul(q[0], dal_cos(q[1]));
  r[1] = dal_mul(q[0], dal_sin(q[1]));
  return 0;
}

static const dal_prescribed drive = {motion, NULL};

static dal_system *build(void) {
  dal_builder *b = NULL;
  int rho, phi, bead;
  dal_builder_create(2, &b);
  dal_builder_add_coord(b, "rho", &rho);
  dal_builder_add_coord(b, "phi", &phi);
  dal_builder_add_particle(b, "bead", 0.4, &bead);
  dal_builder_set_map(b, rod_map, NULL);
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = "drive";
  cd.prim = &dal_con_prescribed;
  cd.coords = &phi;
  cd.ncoords = 1;
  cd.param[DAL_PRESCRIBED_Q0] = 0.3;
  cd.ctx = (void *)&drive;
  dal_builder_add_constraint_def(b, &cd, NULL);
  dal_spring_def s = dal_default_spring_def(); // to the hub at the origin
  s.a = bead;
  s.k = 30.0;
  s.length = 0.5;
  dal_builder_add_spring_def(b, &s);
  double g[2] = {0, -9.81};
  dal_builder_set_gravity(b, g);
  return ex_compile(b, 0);
}

typedef struct work {
  double p[2], W, dt;
  int k;
} work;

// drive power P = (G' lambda)_phi phidot; Simpson over pairs of intervals
static int monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  work *w = ctx;
  double Qc[2];
  dal_constraint_genforces(sys, st, Qc);
  double P = Qc[1] * dal_state_qdot(st)[1];
  if (w->k == 0)
    w->p[0] = P;
  else if (w->k % 2 == 1)
    w->p[1] = P;
  else {
    w->W += w->dt / 3.0 * (w->p[0] + 4.0 * w->p[1] + P);
    w->p[0] = P;
  }
  w->k++;
  return 0;
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0, bad = 0;
  dal_system *sys = build();
  if (!sys) return 1;
  for (int f = 0; f < 2; ++f) {
    dal_state *st = NULL;
    dal_state_create(sys, &st);
    double q[2] = {0.7, 0.3}, v[2] = {0.0, 1.2}; // phidot = f'(0) = 1.2 rad/s
    dal_state_set(sys, st, 0, q, v);
    dal_solve_opts o = dal_default_solve_opts();
    o.rtol = 1e-10;
    if (f == 1) {
      o.form = DAL_FORM_INDEX1;
      o.project = 1;
      o.method = DAL_METHOD_BS;
    }
    dal_make_consistent(sys, st, 0, NULL);
    dal_energies e0, e1;
    dal_state_energies(st, &e0);
    work w = {{0, 0}, 0.0, 2e-3, 0};
    int rc = dal_evolve(sys, st, &o, 3.0, w.dt, monitor, &w);
    dal_state_energies(st, &e1);
    double dE = e1.E - e0.E;
    printf("%s: E(3) - E(0) = %.10f J, drive work %.10f J (difference %.2g)\n",
           f ? "index1-proj/bs" : "ggl/bdf", dE, w.W, dE - w.W);
    if (rc || fabs(dE - w.W) > (f ? 1e-7 : 1e-5) || fabs(w.W) < 0.1) bad = 1;
    dal_state_destroy(st);
  }
  dal_system_destroy(sys);
  if (check) printf("prescribed_drive: %s\n", bad ? "FAILED" : "ok");
  return bad;
}
