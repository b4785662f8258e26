// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// SICM's periodically driven pendulum: sensitive dependence on initial conditions.
//
// Problem (Sussman & Wisdom, Structure and Interpretation of Classical Mechanics, sec. 1.7):
// a bob of mass m = 1 on a rod l = 1 whose pivot moves vertically, y_s(t) = a cos(omega t),
// a = 0.1, omega = 2 sqrt(g), g = 9.8, released at theta = 1 (from the downward vertical)
// with thetadot = 0, integrated to t = 100 with output every 0.01, and again with
// thetadot = 1e-10. Coordinates: theta (minimal, dal_map_pendulum with a moving pivot).
// Formulation: ODE y = (theta, thetadot); method Bulirsch-Stoer (SICM's default), rtol 1e-12.
//
// Full mode (default; --out DIR, default ./demo-output) writes both orbits to CSV with theta
// as principal value in [-pi, pi), reports when they separate (|dtheta| > 0.1 rad) and draws
// theta(t) with gnuplot when it is installed.
// --check (ctest): over t in [0, 10] Bulirsch-Stoer and Adams agree while the motion is
// predictable, and the energy bookkeeping closes: E(t) - E(0) equals the work done by the
// rod's force on the bob, the integral of N . v (N = m a - F, from dal_state_reactions),
// integrated independently by Simpson's rule.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "example_util.h"

#define PI 3.14159265358979323846

static const double g = 9.8, a = 0.1, l = 1.0, mass = 1.0;

static double wrap(double x) {
  double r = x - 2 * PI * floor((x + PI) / (2 * PI));
  return r >= PI ? r - 2 * PI : r;
}

// monitor: record theta (unwrapped) and the power N . v, optionally write a CSV row
typedef struct orbit {
  long n, cap;
  double *theta, *power, *E;
  dal_csv *csv;
} orbit;

static int record(const dal_system *sys, const dal_state *st, void *ctx) {
  orbit *o = ctx;
  if (o->n >= o->cap) return -1;
  const double *N = dal_state_reactions(st), *v = dal_state_velocities(st);
  dal_energies en;
  dal_state_energies(st, &en);
  o->theta[o->n] = dal_state_q(st)[0];
  o->power[o->n] = N[0] * v[0] + N[1] * v[1];
  o->E[o->n] = en.E;
  o->n++;
  return o->csv ? dal_csv_monitor(sys, st, o->csv) : 0;
}

// evolve from (theta0, thetadot0) to T with output every dt into o
static int run(const dal_system *sys, dal_method m, double theta0, double thetadot0, double T,
               double dt, orbit *o) {
  dal_state *st = NULL;
  int rc = dal_state_create(sys, &st);
  if (!rc) rc = dal_state_set(sys, st, 0.0, &theta0, &thetadot0);
  dal_solve_opts opts = dal_default_solve_opts();
  opts.method = m;
  opts.rtol = opts.atol = 1e-12;
  if (!rc) rc = dal_evolve(sys, st, &opts, T, dt, record, o);
  if (rc) fprintf(stderr, "integration failed (%d): %s\n", rc, dal_state_errmsg(st));
  dal_stats s;
  dal_state_stats(st, &s);
  printf("  %s from thetadot0 = %g: %ld steps, %ld rejected, %ld evaluations\n", dal_method_name(m),
         thetadot0, s.steps, s.rejected, s.rhs_evals);
  dal_state_destroy(st);
  return rc;
}

static int alloc_orbit(orbit *o, long cap) {
  memset(o, 0, sizeof *o);
  o->cap = cap;
  o->theta = calloc((size_t)cap, sizeof(double));
  o->power = calloc((size_t)cap, sizeof(double));
  o->E = calloc((size_t)cap, sizeof(double));
  return o->theta && o->power && o->E ? 0 : -1;
}

static void free_orbit(orbit *o) {
  free(o->theta);
  free(o->power);
  free(o->E);
}

// first output time where the orbits differ by more than 0.1 rad (mod 2 pi); -1 if never
static double separation(const orbit *o1, const orbit *o2, double dt) {
  long n = o1->n < o2->n ? o1->n : o2->n;
  for (long k = 0; k < n; ++k)
    if (fabs(wrap(o1->theta[k] - o2->theta[k])) > 0.1) return (double)k * dt;
  return -1;
}

static int check_mode(const dal_system *sys) {
  int bad = 0;
  double T = 10.0, dt = 1e-3;
  long cap = (long)(T / dt) + 3;
  orbit bs, ad, pert;
  if (alloc_orbit(&bs, cap) || alloc_orbit(&ad, cap) || alloc_orbit(&pert, cap)) return 1;
  bad |= run(sys, DAL_METHOD_BS, 1.0, 0.0, T, dt, &bs) != 0;
  bad |= run(sys, DAL_METHOD_ADAMS, 1.0, 0.0, T, dt, &ad) != 0;
  bad |= run(sys, DAL_METHOD_BS, 1.0, 1e-10, T, dt, &pert) != 0;
  if (bad) return 1;
  // two methods agree over the predictable horizon
  double dmax = 0, dpert = 0;
  for (long k = 0; k < bs.n; ++k) {
    dmax = fmax(dmax, fabs(bs.theta[k] - ad.theta[k]));
    dpert = fmax(dpert, fabs(bs.theta[k] - pert.theta[k]));
  }
  printf("max |theta_bs - theta_adams| on [0, %g]: %.3e\n", T, dmax);
  printf("max |theta(0) - theta(1e-10)| on [0, %g]: %.3e (from 1e-10 at t = 0)\n", T, dpert);
  bad |= !(dmax < 1e-7);
  // energy bookkeeping: E(T) - E(0) = int_0^T N . v dt (Simpson, n even)
  long n = bs.n - 1;
  if (n % 2) --n;
  double work = bs.power[0] + bs.power[n];
  for (long k = 1; k < n; ++k)
    work += (k % 2 ? 4.0 : 2.0) * bs.power[k];
  work *= dt / 3.0;
  double dE = bs.E[n] - bs.E[0];
  printf("energy bookkeeping to t=%g: E(t) - E(0) = %.12f, work of the rod = %.12f (diff %.2e)\n",
         (double)n * dt, dE, work, fabs(dE - work));
  bad |= !(fabs(dE - work) < 1e-7 * fmax(1.0, fabs(dE)));
  bad |= !(fabs(dE) > 1e-3); // the drive does change the energy
  free_orbit(&bs);
  free_orbit(&ad);
  free_orbit(&pert);
  return bad;
}

static int full_mode(const dal_system *sys, const char *dir) {
  double T = 100.0, dt = 0.01;
  long cap = (long)(T / dt) + 3;
  if (ex_make_dir(dir)) return 1;
  char p1[1024], p2[1024], gp[1024], png[1024];
  snprintf(p1, sizeof p1, "%s/driven_pendulum_a.csv", dir);
  snprintf(p2, sizeof p2, "%s/driven_pendulum_b.csv", dir);
  snprintf(gp, sizeof gp, "%s/driven_pendulum.gp", dir);
  snprintf(png, sizeof png, "%s/driven_pendulum.png", dir);
  FILE *f1 = fopen(p1, "w"), *f2 = fopen(p2, "w");
  orbit o1, o2;
  if (!f1 || !f2 || alloc_orbit(&o1, cap) || alloc_orbit(&o2, cap)) {
    fprintf(stderr, "cannot write %s\n", dir);
    return 1;
  }
  dal_csv c1 = {f1, 0, 1, NULL}, c2 = {f2, 0, 1, NULL};
  o1.csv = &c1;
  o2.csv = &c2;
  int rc = run(sys, DAL_METHOD_BS, 1.0, 0.0, T, dt, &o1);
  if (!rc) rc = run(sys, DAL_METHOD_BS, 1.0, 1e-10, T, dt, &o2);
  fclose(f1);
  fclose(f2);
  if (rc) return 1;
  double tsep = separation(&o1, &o2, dt);
  if (tsep >= 0)
    printf("the orbits from thetadot0 = 0 and 1e-10 separate (|dtheta| > 0.1 rad) at t = %.2f\n",
           tsep);
  else
    printf("the orbits stay within 0.1 rad up to t = %g\n", T);
  // the same pair by a second method: the separation time is a property of the orbits
  orbit a1, a2;
  if (alloc_orbit(&a1, cap) || alloc_orbit(&a2, cap)) return 1;
  if (!run(sys, DAL_METHOD_ADAMS, 1.0, 0.0, T, dt, &a1) &&
      !run(sys, DAL_METHOD_ADAMS, 1.0, 1e-10, T, dt, &a2))
    printf("cross-check with Adams: separation at t = %.2f\n", separation(&a1, &a2, dt));
  free_orbit(&a1);
  free_orbit(&a2);
  printf("wrote %s and %s\n", p1, p2);
  // |delta theta|(t) of the two orbits, and the slope of log |delta theta| fitted by least
  // squares while they are close (t in [5, tsep - 5]): the rate at which they diverge
  char p3[1024];
  snprintf(p3, sizeof p3, "%s/driven_pendulum_delta.csv", dir);
  FILE *f3 = fopen(p3, "w");
  double sx = 0, sy = 0, sxx = 0, sxy = 0, slope = NAN, icpt = NAN;
  long nfit = 0, np = o1.n < o2.n ? o1.n : o2.n;
  double tfit1 = tsep >= 0 ? tsep - 5.0 : T;
  if (f3) fprintf(f3, "t,abs_dtheta\n");
  for (long k = 0; k < np; ++k) {
    double t = k * dt, d = fabs(o2.theta[k] - o1.theta[k]);
    if (f3 && d > 0) fprintf(f3, "%.17g,%.17g\n", t, d);
    if (d > 0 && t >= 5.0 && t <= tfit1) {
      double y = log(d);
      sx += t, sy += y, sxx += t * t, sxy += t * y, ++nfit;
    }
  }
  if (f3) fclose(f3);
  if (nfit > 2) {
    slope = (nfit * sxy - sx * sy) / (nfit * sxx - sx * sx);
    icpt = (sy - slope * sx) / nfit;
    printf("slope of log|dtheta| on [5, %.1f]: %.4f 1/s (the finite-time divergence rate)\n", tfit1,
           slope);
  }
  // the chart: the orbits, then log |delta theta| with its fitted line
  FILE *gf = fopen(gp, "w");
  if (gf) {
    fprintf(gf,
            "set terminal pngcairo size 1200,900\nset output '%s'\nset datafile separator ','\n"
            "set multiplot layout 2,1\nset key outside\nset grid\nset xlabel 't (s)'\n"
            "set ylabel 'theta (rad, principal value)'\nset yrange [-pi:pi]\n"
            "set title 'SICM driven pendulum, l = 1 m, pivot 0.1 cos(2 sqrt(g) t) m: two orbits "
            "from theta = 1 rad, thetadot = 0 and 1e-10 rad/s'\n",
            png);
    if (tsep >= 0)
      fprintf(gf, "set arrow 1 from %g,-pi to %g,pi nohead dt 2 lc rgb 'gray40'\n", tsep, tsep);
    fprintf(gf,
            "plot '%s' using 1:2 every ::1 with points pt 7 ps 0.25 lc rgb '#1f77b4' title "
            "'thetadot0 = 0', '%s' using 1:2 every ::1 with points pt 6 ps 0.35 lc rgb '#d62728' "
            "title 'thetadot0 = 1e-10'\n"
            "unset arrow 1\nset autoscale y\nset logscale y\nset format y '10^{%%L}'\n"
            "set ylabel '|delta theta| (rad)'\n"
            "set title 'log |delta theta| grows as a line of slope %.3f 1/s until the orbits "
            "part%s'\n",
            p1, p2, slope, tsep >= 0 ? " (dashed: 0.1 rad apart)" : "");
    if (tsep >= 0)
      fprintf(gf, "set arrow 2 from %g, graph 0 to %g, graph 1 nohead dt 2 lc rgb 'gray40'\n", tsep,
              tsep);
    fprintf(gf,
            "plot '%s' using 1:2 every ::1 with linespoints pt 7 ps 0.5 pi 200 lw 1 lc rgb "
            "'#9467bd' title '|theta_b - theta_a|'",
            p3);
    if (isfinite(slope))
      fprintf(gf,
              ", (x >= 5 && x <= %g) ? exp(%.17g + %.17g * x) : 1/0 with lines lw 3 dt 2 lc "
              "rgb 'black' title 'fit: slope %.3f 1/s'",
              tfit1, icpt, slope, slope);
    fprintf(gf, "\nunset multiplot\n");
    fclose(gf);
  }
  ex_gnuplot(gp, png);
  free_orbit(&o1);
  free_orbit(&o2);
  return 0;
}

int main(int argc, char **argv) {
  const char *dir = "demo-output";
  int check = ex_args(argc, argv, &dir);
  dal_system *sys = ex_pendulum(mass, l, g, 0.0, a, 2 * sqrt(g)); // pivot y = a cos(omega t)
  int bad = sys == NULL;
  printf("SICM driven pendulum: m=%g l=%g g=%g a=%g omega=2 sqrt(g), theta0=1\n", mass, l, g, a);
  if (!bad) bad = check ? check_mode(sys) : full_mode(sys, dir);
  dal_system_destroy(sys);
  if (check) printf("%s\n", bad ? "FAILED" : "ok");
  return bad;
}
