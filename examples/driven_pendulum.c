// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Pendulum with a vertically driven support (SICM 1.6.2), and Kapitza's inverted pendulum.
//
// Problem: a bob of mass m = 1 on a rod of length l = 1 whose support moves vertically as
// y_s(t) = a cos(w t), gravity g = 9.81. Coordinate: theta from the downward vertical
// (dal_map_pendulum with the support motion in its parameters). Formulation: minimal ODE by
// particles (the moving support is a time-dependent coordinate map), and SICM's Lagrangian
// L = m/2 (l^2 theta'^2 + 2 l y_s' theta' sin(theta) + y_s'^2) - m g (y_s - l cos(theta));
// dal_advance (automatic method) at rtol 1e-9.
// Equation of motion: theta'' = -(g + y_s'') sin(theta) / l, y_s'' = -a w^2 cos(w t).
// Kapitza (Landau & Lifshitz, Mechanics sec. 30): a fast drive stabilizes the inverted position
// when a^2 w^2 > 2 g l; the slow motion about theta = pi then has the frequency
// Omega^2 = a^2 w^2 / (2 l^2) - g / l.
// Checks (--check integrates 3 s, the full mode 6 s):
//  1. both routes give the equation of motion at sample states (t enters through the drive);
//  2. h = T2 - T0 + U and E = T + U match their hand formulas;
//  3. started 0.2 rad from upright, the pendulum stays within 0.5 rad of upright under a fast
//     drive (a = 0.1, w = 100: a^2 w^2 = 100 > 2 g l), and falls under a slow one (w = 10);
//  4. the slow oscillation about upright under the fast drive has the period 2 pi / Omega
//     within 10% (the averaging is exact only as w -> infinity).
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "example_util.h"

static const double mass = 1.0, len = 1.0, grav = 9.81;
#define PI 3.14159265358979323846

typedef struct drive {
  double a, w;
} drive;

static int lagrangian(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  const drive *D = ctx;
  dal_jet ys = dal_scale(dal_cos(dal_scale(t, D->w)), D->a);
  dal_jet ysd = dal_scale(dal_sin(dal_scale(t, D->w)), -D->a * D->w);
  dal_jet T = dal_add(dal_scale(dal_sq(v[0]), len * len),
                      dal_scale(dal_mul(dal_mul(ysd, v[0]), dal_sin(q[0])), 2 * len));
  T = dal_scale(dal_add(T, dal_sq(ysd)), 0.5 * mass);
  dal_jet U = dal_scale(dal_sub(ys, dal_scale(dal_cos(q[0]), len)), mass * grav);
  *L = dal_sub(T, U);
  return 0;
}

static dal_system *build(drive *D, int lagrange) {
  // support p(t) = (0, a cos(w t)): the pivot at the origin driven along y
  if (!lagrange) return ex_pendulum(mass, len, grav, 0.0, D->a, D->w);
  dal_builder *b = NULL;
  int th, rc = dal_builder_create(2, &b);
  if (!rc) rc = dal_builder_add_coord(b, "theta", &th);
  if (!rc) rc = dal_builder_set_lagrangian(b, lagrangian, D);
  return ex_compile(b, rc);
}

// integrate from near upright; report the largest distance from upright and the times at which
// theta - pi changes sign (slow oscillation)
static int upright_run(drive *D, double tend, double *maxdev, double *period, int verbose) {
  dal_system *sys = build(D, 0);
  dal_state *st = NULL;
  int rc = sys ? dal_state_create(sys, &st) : -1;
  double th0 = PI - 0.2, z = 0.0, dt = 0.002, last_cross = -1, first_cross = -1;
  int ncross = 0;
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = o.atol = 1e-9;
  if (!rc) rc = dal_state_set(sys, st, 0.0, &th0, &z);
  *maxdev = 0.0;
  double prev = -0.2;
  for (int i = 1; !rc && i * dt <= tend + 1e-12; ++i) {
    rc = dal_advance(sys, st, &o, i * dt);
    if (rc) break;
    double dev = dal_state_q(st)[0] - PI;
    *maxdev = fmax(*maxdev, fabs(dev));
    if (dev * prev < 0) {
      double tc = (i - 1) * dt + dt * prev / (prev - dev);
      // count a crossing only if it is well apart from the previous (ignore the fast ripple)
      if (last_cross < 0 || tc - last_cross > 0.1) {
        if (first_cross < 0) first_cross = tc;
        last_cross = tc;
        ++ncross;
      }
    }
    prev = dev;
    if (verbose && i % 250 == 0) printf("    t = %4.1f  theta - pi = %+9.5f\n", i * dt, dev);
    if (fabs(dev) > 3.0) break; // fell over
  }
  if (rc) printf("  integration failed: %s\n", st ? dal_state_errmsg(st) : "");
  // crossings are half periods apart
  *period = ncross >= 3 ? 2 * (last_cross - first_cross) / (ncross - 1) : NAN;
  dal_state_destroy(st);
  dal_system_destroy(sys);
  return rc;
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0, bad = 0;
  drive D = {0.1, 100.0};
  printf("pendulum with a vertically driven support: m = %g, l = %g, g = %g\n", mass, len, grav);

  // 1./2. equation of motion and energies at sample states, both routes
  dal_system *sys = build(&D, 0), *lag = build(&D, 1);
  dal_state *st = NULL, *stl = NULL;
  if (!sys || !lag || dal_state_create(sys, &st) || dal_state_create(lag, &stl)) bad = 1;
  double worst = 0, worst_l = 0, worst_e = 0;
  for (int i = 0; !bad && i < 8; ++i) {
    double t = 0.013 * i, th = -3 + 0.8 * i, thd = 2 - 0.5 * i;
    if (dal_state_set(sys, st, t, &th, &thd) || dal_forward(sys, st) ||
        dal_state_set(lag, stl, t, &th, &thd) || dal_forward(lag, stl)) {
      bad = 1;
      break;
    }
    double c = cos(D.w * t), s = sin(D.w * t), ysdd = -D.a * D.w * D.w * c;
    double ref = -(grav + ysdd) * sin(th) / len;
    worst = fmax(worst, fabs(dal_state_qddot(st)[0] - ref) / (grav + fabs(ysdd)));
    worst_l = fmax(worst_l, fabs(dal_state_qddot(stl)[0] - ref) / (grav + fabs(ysdd)));
    double ys = D.a * c, ysd = -D.a * D.w * s;
    double T2 = 0.5 * mass * len * len * thd * thd, T0 = 0.5 * mass * ysd * ysd;
    double T1 = mass * len * ysd * thd * sin(th), U = mass * grav * (ys - len * cos(th));
    dal_energies e, el;
    dal_state_energies(st, &e);
    dal_state_energies(stl, &el);
    double sc = T2 + T0 + fabs(T1) + fabs(U);
    worst_e = fmax(worst_e, fabs(e.E - (T2 + T1 + T0 + U)) / sc);
    worst_e = fmax(worst_e, fabs(e.h - (T2 - T0 + U)) / sc);
    worst_e = fmax(worst_e, fabs(el.h - (T2 - T0 + U)) / sc);
  }
  // the Lagrangian route takes second partials by polarization, which mixes in the large
  // d2/dt2 of the drive's kinetic energy (a^2 w^4 ~ 1e6): expect a few 1e-13 relative
  printf("  theta'' = -(g + y_s'') sin(theta)/l: max rel error %.1e (particles), %.1e "
         "(Lagrangian)\n",
         worst, worst_l);
  printf("  E = T + U and h = T2 - T0 + U vs hand formulas: max rel error %.1e\n", worst_e);
  bad |= !(worst <= 1e-13) || !(worst_l <= 1e-11) || !(worst_e <= 1e-13);
  dal_state_destroy(st);
  dal_state_destroy(stl);
  dal_system_destroy(sys);
  dal_system_destroy(lag);

  // 3./4. Kapitza's pendulum
  double tend = check ? 3.0 : 6.0, dev_fast, dev_slow, per_fast, per_slow;
  double Om = sqrt(D.a * D.a * D.w * D.w / (2 * len * len) - grav / len);
  printf("  fast drive a = %g, w = %g (a^2 w^2 = %g > 2 g l = %g), from theta = pi - 0.2:\n", D.a,
         D.w, D.a * D.a * D.w * D.w, 2 * grav * len);
  bad |= upright_run(&D, tend, &dev_fast, &per_fast, !check) != 0;
  drive slow = {0.1, 10.0};
  bad |= upright_run(&slow, tend, &dev_slow, &per_slow, 0) != 0;
  printf("  fast drive: max |theta - pi| = %.4f over %g s; slow period %.4f s (averaged theory "
         "2 pi / Omega = %.4f s)\n",
         dev_fast, tend, per_fast, 2 * PI / Om);
  printf("  slow drive a = %g, w = %g (a^2 w^2 = %g < 2 g l): max |theta - pi| = %.3f: it falls\n",
         slow.a, slow.w, slow.a * slow.a * slow.w * slow.w, dev_slow);
  bad |= !(dev_fast < 0.5) || !(dev_slow > 1.0);
  bad |= !(fabs(per_fast - 2 * PI / Om) <= 0.1 * 2 * PI / Om);
  return ex_verdict(bad, "ok");
}
