// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A motor-driven four-bar linkage: the motor torque is the multiplier of the drive's row.
//
// Problem: ground pivots A = (0, 0) and D = (2, 0); crank A-B (length 1), coupler B-C (length
// 2), rocker C-D (length 1.5); point masses m_B = 1 kg at B and m_C = 2 kg at C, gravity g
// down. A motor turns the crank at a constant rate: theta = theta0 + w t, w = 2 rad/s.
// Coordinates: the crank angle theta (B placed by dal_map_pendulum about A) and (xC, yC).
// Constraints: 'coupler' (B-C, so theta enters it), 'rocker' (C to the fixed point D) and
// 'motor', a dal_con_prescribed row on theta. Formulation: index-1 with projection,
// Bulirsch-Stoer (rtol 1e-10).
//
// The motor's torque is the multiplier of its own row, lambda_motor (the row is
// theta - theta0 - w t, its gradient is 1 on theta). It is NOT the theta entry of
// dal_constraint_genforces: that entry, (G' lambda)_theta, also holds the coupler's pull on the
// crank, lambda_coupler d|B - C|/dtheta. Check (--check), independent of the multipliers: the
// power balance. The rods are fixed in time and do no work, so the motor's power
// tau * thetadot integrated over the run (Simpson's rule on the output grid) must equal the
// change of T + U (written out by hand from the coordinates); the same integral of
// (G' lambda)_theta * thetadot must not. Writes driven_four_bar.csv without --check.
#include <dalembert/dalembert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "example_util.h"

#define G 9.81
#define W 2.0 // crank rate (rad/s)

static const double LAB = 1.0, LBC = 2.0, LCD = 1.5, DX = 2.0, MB = 1.0, MC = 2.0;

static int crank_motion(dal_jet t, dal_jet *f, void *ctx) {
  (void)ctx;
  *f = dal_scale(t, W);
  return 0;
}
static const dal_prescribed motor_motion = {crank_motion, NULL};

static dal_system *build(int *motor_row) {
  dal_builder *b = NULL;
  int th, c[2], pB, pC;
  dal_builder_create(2, &b);
  dal_builder_add_coord(b, "theta", &th);
  dal_builder_add_coord(b, "xC", &c[0]);
  dal_builder_add_coord(b, "yC", &c[1]);
  dal_builder_add_particle(b, "B", MB, &pB);
  dal_builder_add_particle(b, "C", MC, &pC);
  dal_place_def d = dal_default_place_def(); // B on the crank about A = (0, 0)
  d.prim = &dal_map_pendulum;
  d.coords = &th;
  d.ncoords = 1;
  dal_place_def_set(&d, "l", LAB);
  dal_builder_place_def(b, pB, &d);
  d = dal_default_place_def(); // C free in the plane, held by the rods
  d.prim = &dal_map_cartesian2;
  d.coords = c;
  d.ncoords = 2;
  dal_builder_place_def(b, pC, &d);
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = "coupler";
  cd.prim = &dal_con_distance2;
  int bc[2] = {pB, pC};
  cd.parts = bc;
  cd.nparts = 2;
  dal_constraint_def_set(&cd, "L", LBC);
  dal_builder_add_constraint_def(b, &cd, NULL);
  cd = dal_default_constraint_def();
  cd.name = "rocker";
  cd.prim = &dal_con_anchor2;
  cd.parts = &pC;
  cd.nparts = 1;
  dal_constraint_def_set(&cd, "L", LCD);
  dal_constraint_def_set(&cd, "x0", DX);
  dal_builder_add_constraint_def(b, &cd, NULL);
  cd = dal_default_constraint_def();
  cd.name = "motor";
  cd.prim = &dal_con_prescribed;
  cd.coords = &th;
  cd.ncoords = 1;
  dal_constraint_def_set(&cd, "q0", 0.0);
  cd.ctx = (void *)&motor_motion;
  dal_builder_add_constraint_def(b, &cd, motor_row);
  double g[2] = {0, -G};
  dal_builder_set_gravity(b, g);
  return ex_compile(b, 0);
}

typedef struct power {
  int row, k;               // the motor's row; samples so far
  double dt;                // output interval
  double p[2][2], work[2];  // Simpson: last two samples and the integrals of
                            // [0] tau thetadot and [1] (G' lambda)_theta thetadot
  double tau_max, diff_max; // largest |tau| and |(G' lambda)_theta - tau|
  FILE *csv;                // t, theta, tau, (G' lambda)_theta, E (NULL: none)
} power;

// T + U written out by hand from (theta, xC, yC) and their rates, not read from the library
static double energy(const double *q, const double *v) {
  double vB2 = LAB * LAB * v[0] * v[0], yB = -LAB * cos(q[0]);
  return 0.5 * MB * vB2 + 0.5 * MC * (v[1] * v[1] + v[2] * v[2]) + G * (MB * yB + MC * q[2]);
}

static int monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  power *pw = ctx;
  double Qc[3];
  if (dal_constraint_genforces(sys, st, Qc)) return -1;
  double tau = dal_state_lambda(st)[pw->row], thd = dal_state_qdot(st)[0];
  double P[2] = {tau * thd, Qc[0] * thd};
  for (int j = 0; j < 2; ++j) {
    if (pw->k == 0)
      pw->p[j][0] = P[j];
    else if (pw->k % 2 == 1)
      pw->p[j][1] = P[j];
    else {
      pw->work[j] += pw->dt / 3.0 * (pw->p[j][0] + 4.0 * pw->p[j][1] + P[j]);
      pw->p[j][0] = P[j];
    }
  }
  pw->k++;
  pw->tau_max = fmax(pw->tau_max, fabs(tau));
  pw->diff_max = fmax(pw->diff_max, fabs(Qc[0] - tau));
  if (pw->csv)
    fprintf(pw->csv, "%.6f,%.10f,%.10f,%.10f,%.10f\n", dal_state_time(st), dal_state_q(st)[0], tau,
            Qc[0], energy(dal_state_q(st), dal_state_qdot(st)));
  return 0;
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0;
  int row = -1;
  dal_system *sys = build(&row);
  if (!sys) return 1;
  dal_state *st = NULL;
  dal_state_create(sys, &st);
  // start: crank straight down (theta = 0, B = (0, -1)); C where the coupler and rocker
  // circles meet above the ground line (closed form), moving as the consistent start says
  double B[2] = {0.0, -LAB}, dx = DX - B[0], dy = 0.0 - B[1], dd = hypot(dx, dy);
  double a = (LBC * LBC - LCD * LCD + dd * dd) / (2 * dd), h = sqrt(LBC * LBC - a * a);
  double q[3] = {0.0, B[0] + a * dx / dd - h * dy / dd, B[1] + a * dy / dd + h * dx / dd};
  double v[3] = {W, 0.0, 0.0};
  dal_state_set(sys, st, 0.0, q, v);
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-10;
  o.form = DAL_FORM_INDEX1;
  o.project = 1;
  o.method = DAL_METHOD_BS;
  if (dal_make_consistent(sys, st, 0.0, NULL)) {
    fprintf(stderr, "%s\n", dal_state_errmsg(st));
    return 1;
  }
  double E0 = energy(dal_state_q(st), dal_state_qdot(st));
  const double T = 2 * acos(-1.0) / W; // one turn of the crank
  power pw = {row, 0, T / 2000, {{0, 0}, {0, 0}}, {0, 0}, 0, 0, NULL};
  if (!check) pw.csv = fopen("driven_four_bar.csv", "w");
  if (pw.csv) fprintf(pw.csv, "t,theta,tau_motor,genforce_theta,E\n");
  int rc = dal_evolve(sys, st, &o, 0.5 * T, pw.dt, monitor, &pw);
  if (pw.csv) fclose(pw.csv);
  double dE = energy(dal_state_q(st), dal_state_qdot(st)) - E0;
  printf("half a turn of the crank (t = %.4f s): E(t) - E(0) = %.9f J\n", 0.5 * T, dE);
  printf("  motor torque = lambda of row 'motor': work %.9f J (difference %.1e J)\n", pw.work[0],
         pw.work[0] - dE);
  printf("  (G' lambda)_theta: work %.9f J; it differs from the torque by up to %.2f N m "
         "(largest torque %.2f N m)\n",
         pw.work[1], pw.diff_max, pw.tau_max);
  int bad = rc != DAL_OK || !(fabs(pw.work[0] - dE) < 1e-6) || !(fabs(dE) > 1.0) ||
            !(fabs(pw.work[1] - dE) > 1.0) || !(pw.diff_max > 1.0);
  if (check) printf("driven_four_bar: %s\n", bad ? "FAILED" : "ok");
  dal_state_destroy(st);
  dal_system_destroy(sys);
  return bad;
}
