// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// SICM's harmonic oscillator: advance a state and compare with the closed form.
//
// Problem (Sussman & Wisdom, SICM sec. 1.7): a particle of mass m = 2 in the plane on a
// spring of stiffness k = 1 to the origin, L = m/2 |v|^2 - k/2 |q|^2. Coordinates (x, y)
// (dal_map_cartesian2, potential k/2 |q|^2 over q). Formulation: ODE; method Bulirsch-Stoer
// (SICM's default) and the automatic choice, both at rtol = atol = 1e-12.
// From t = 0, q = (1, 2), qdot = (3, 4) to t = 10 (SICM's state-advancer example); the closed
// form is q(t) = q0 cos(w t) + qdot0 / w sin(w t), w = sqrt(k/m).
// --check: the state at t = 10 agrees with the closed form to 100 x rtol and the energy is
// conserved to the same. Full mode (--out DIR, default ./demo-output) also writes the orbit
// over one period to CSV and draws it (gnuplot) against the closed-form ellipse.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "example_util.h"

static const double mass = 2.0, k = 1.0;
static const double q0[2] = {1, 2}, v0[2] = {3, 4};

static int spring(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  *U = dal_scale(dal_add(dal_sq(q[0]), dal_sq(q[1])), 0.5 * k);
  return 0;
}

static dal_system *build(void) {
  dal_builder *b = NULL;
  const char *xy[2] = {"x", "y"}, *name = "particle";
  int c[2], p, rc = dal_builder_create(2, &b);
  if (!rc) rc = ex_cartesian_particles(b, 2, 1, &name, &mass, xy, c, &p);
  if (!rc) rc = dal_builder_add_potential_q(b, spring, NULL);
  return ex_compile(b, rc);
}

static void exact(double t, double *q, double *v) {
  double w = sqrt(k / mass);
  for (int i = 0; i < 2; ++i) {
    q[i] = q0[i] * cos(w * t) + v0[i] / w * sin(w * t);
    v[i] = -q0[i] * w * sin(w * t) + v0[i] * cos(w * t);
  }
}

// advance to t = 10 with method m; print the state SICM-style; nonzero when a check fails
static int advance_and_compare(const dal_system *sys, dal_method m) {
  dal_state *st = NULL;
  int rc = dal_state_create(sys, &st);
  if (!rc) rc = dal_state_set(sys, st, 0.0, q0, v0);
  dal_solve_opts o = dal_default_solve_opts();
  o.method = m;
  o.rtol = o.atol = 1e-12;
  double E0 = 0;
  if (!rc) rc = dal_forward(sys, st);
  dal_energies en;
  dal_state_energies(st, &en);
  E0 = en.E;
  if (!rc) rc = dal_advance(sys, st, &o, 10.0);
  if (rc) {
    fprintf(stderr, "advance failed (%d): %s\n", rc, st ? dal_state_errmsg(st) : "");
    dal_state_destroy(st);
    return 1;
  }
  const double *q = dal_state_q(st), *v = dal_state_qdot(st);
  double qe[2], ve[2], err = 0;
  exact(10.0, qe, ve);
  for (int i = 0; i < 2; ++i)
    err = fmax(err, fmax(fabs(q[i] - qe[i]), fabs(v[i] - ve[i])));
  dal_state_energies(st, &en);
  dal_stats s;
  dal_state_stats(st, &s);
  printf("%-6s (up %.17g (up %.17g %.17g) (up %.17g %.17g))\n", dal_method_name(m),
         dal_state_time(st), q[0], q[1], v[0], v[1]);
  printf("closed (up 10 (up %.17g %.17g) (up %.17g %.17g))\n", qe[0], qe[1], ve[0], ve[1]);
  printf("       error %.2e, energy drift %.2e, %ld steps, %ld evaluations\n", err, fabs(en.E - E0),
         s.steps, s.rhs_evals);
  int bad = !(err < 100 * o.rtol * 6) || !(fabs(en.E - E0) < 100 * o.rtol * fabs(E0));
  dal_state_destroy(st);
  return bad;
}

// ten periods of the orbit to CSV and a chart of the error against the closed form over time
static int full_mode(const dal_system *sys, const char *dir) {
  if (ex_make_dir(dir)) return 1;
  char path[1024], gp[1024], png[1024];
  snprintf(gp, sizeof gp, "%s/oscillator.gp", dir);
  snprintf(png, sizeof png, "%s/oscillator.png", dir);
  FILE *fp = ex_open(dir, "oscillator.csv", path, sizeof path);
  if (!fp) return 1;
  dal_state *st = NULL;
  int rc = dal_state_create(sys, &st);
  if (!rc) rc = dal_state_set(sys, st, 0.0, q0, v0);
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_BS;
  o.rtol = o.atol = 1e-12;
  dal_csv csv = {fp, 0, 0, NULL};
  double period = 2 * 3.14159265358979323846 * sqrt(mass / k);
  if (!rc) rc = dal_evolve(sys, st, &o, 10 * period, period / 50, dal_csv_monitor, &csv);
  fclose(fp);
  dal_state_destroy(st);
  if (rc) return 1;
  printf("wrote %s\n", path);
  FILE *gf = fopen(gp, "w");
  if (gf) {
    double w = sqrt(k / mass);
    fprintf(gf,
            "set terminal pngcairo size 1000,600\nset output '%s'\nset datafile separator ','\n"
            "set logscale y\nset format y '10^{%%L}'\nset grid\nset key outside\n"
            "set xlabel 't (s)'\nset ylabel 'position error (m)'\nset xrange [0:%.17g]\n"
            "set title 'SICM oscillator (m = %g kg, k = %g N/m), ten periods to t = %.1f s: "
            "BS at rtol 1e-12 vs the closed form'\n"
            "w = %.17g\n"
            "ex(t, a, b) = a * cos(w * t) + b / w * sin(w * t)\n"
            "err(t, x, y) = sqrt((x - ex(t, %g, %g))**2 + (y - ex(t, %g, %g))**2)\n"
            "plot '%s' using 1:(e = err($1, $2, $3), e > 0 ? e : 1/0) every ::1 with linespoints "
            "pt 7 ps 0.5 pi 10 lc rgb '#1f77b4' title '|q - q_{exact}|', 1e-12 with lines dt 2 "
            "lc rgb 'black' title 'rtol', 16e-12 with lines dt 3 lc rgb 'gray40' title "
            "'16 x rtol'\n",
            png, 10 * period, mass, k, 10 * period, w, q0[0], v0[0], q0[1], v0[1], path);
    fclose(gf);
  }
  ex_gnuplot(gp, png);
  return 0;
}

int main(int argc, char **argv) {
  const char *dir = "demo-output";
  int check = ex_args(argc, argv, &dir);
  dal_system *sys = build();
  int bad = sys == NULL;
  printf("SICM harmonic oscillator: m=%g k=%g, q(0)=(1,2), qdot(0)=(3,4), to t=10 at 1e-12\n", mass,
         k);
  if (!bad) bad |= advance_and_compare(sys, DAL_METHOD_BS);
  if (!bad) bad |= advance_and_compare(sys, DAL_METHOD_AUTO);
  if (!bad && !check) bad |= full_mode(sys, dir);
  dal_system_destroy(sys);
  if (check) printf("%s\n", bad ? "FAILED" : "ok");
  return bad;
}
