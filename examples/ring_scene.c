// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Bead on a ring turning about the vertical axis: the Jacobi integral is conserved, E is not.
//
// Problem (Likharev, Essential Graduate Physics CM 2.1; Goldstein sec. 2.7): a bead of mass
// m = 1 slides without friction on a circle of radius R = 1 that turns about its vertical
// diameter at the constant rate omega, under gravity g = 9.8. Coordinate: the polar angle
// theta from the ring's bottom (dal_map_ring). Formulation: ODE; method AUTO at rtol 1e-10.
// L = m R^2/2 (thetadot^2 + omega^2 sin^2 theta) + m g R cos theta has no explicit t, so
// h = m R^2/2 thetadot^2 - m R^2/2 omega^2 sin^2 theta - m g R cos theta is conserved, while
// the ring's drive does work and E = T + U changes. Below omega_c = sqrt(g/R) the bead
// oscillates about theta = 0; above it about theta* = acos(g / (R omega^2)).
//
// Checks (both modes): h from the library equals the formula above and stays constant to the
// tolerance while E varies by orders of magnitude more; the observed extremes of theta match
// the turning points V(theta) = V(theta0) of the effective potential V = -m R^2/2 omega^2
// sin^2 theta - m g R cos theta found independently by bisection; the motion is symmetric
// about 0 below omega_c, and about theta* lies strictly inside the range above it.
// Full mode (--out DIR, default ./demo-output) writes both runs to CSV and draws theta(t).
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "example_util.h"

static const double g = 9.8, R = 1.0, mass = 1.0;

static dal_system *build(double omega) { return ex_ring_bead(mass, R, omega, g); }

// effective potential (per the Jacobi integral)
static double V(double omega, double th) {
  double s = sin(th);
  return -0.5 * mass * R * R * omega * omega * s * s - mass * g * R * cos(th);
}

// root of V(th) = V0 in [lo, hi] by bisection (V - V0 changes sign there)
static double turning_point(double omega, double V0, double lo, double hi) {
  double flo = V(omega, lo) - V0;
  for (int i = 0; i < 200; ++i) {
    double mid = 0.5 * (lo + hi), fm = V(omega, mid) - V0;
    if ((fm < 0) == (flo < 0)) {
      lo = mid;
      flo = fm;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

typedef struct watch {
  double h0, E0, dh, dE, thmin, thmax;
  dal_csv *csv;
} watch;

static int monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  watch *w = ctx;
  dal_energies en;
  dal_state_energies(st, &en);
  double th = dal_state_q(st)[0];
  if (dal_state_time(st) == 0.0) {
    w->h0 = en.h;
    w->E0 = en.E;
    w->thmin = w->thmax = th;
  }
  w->dh = fmax(w->dh, fabs(en.h - w->h0));
  w->dE = fmax(w->dE, fabs(en.E - w->E0));
  w->thmin = fmin(w->thmin, th);
  w->thmax = fmax(w->thmax, th);
  return w->csv ? dal_csv_monitor(sys, st, w->csv) : 0;
}

// one run; returns nonzero when a check fails
static int scene(double omega, double theta0, double T, double dt, FILE *csvfp, double *hdrift,
                 double *Evar) {
  dal_system *sys = build(omega);
  dal_state *st = NULL;
  int bad = sys == NULL;
  double zero = 0.0;
  if (!bad) bad = dal_state_create(sys, &st) || dal_state_set(sys, st, 0.0, &theta0, &zero);
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = o.atol = 1e-10;
  dal_csv csv = {csvfp, 0, 0, NULL};
  watch w;
  memset(&w, 0, sizeof w);
  w.csv = csvfp ? &csv : NULL;
  if (!bad) {
    int rc = dal_evolve(sys, st, &o, T, dt, monitor, &w);
    if (rc) fprintf(stderr, "integration failed (%d): %s\n", rc, dal_state_errmsg(st));
    bad = rc != 0;
  }
  if (bad) goto done;
  // h of the library against the formula, at the final state
  dal_energies en;
  dal_state_energies(st, &en);
  double th = dal_state_q(st)[0], thd = dal_state_qdot(st)[0];
  double hf = 0.5 * mass * R * R * thd * thd + V(omega, th);
  // turning points of V(theta) = V(theta0), independently of the integration
  double wc = sqrt(g / R), V0 = V(omega, theta0), lo, hi, centre;
  if (omega < wc) {
    centre = 0.0; // V is even: the motion is symmetric about 0
    lo = -theta0;
    hi = theta0;
  } else {
    centre = acos(g / (R * omega * omega));
    double other = turning_point(omega, V0, theta0 < centre ? centre : 0.0,
                                 theta0 < centre ? 3.14159265 : centre);
    lo = fmin(theta0, other);
    hi = fmax(theta0, other);
  }
  double mid = 0.5 * (w.thmin + w.thmax);
  printf("omega = %.3f omega_c: theta in [%.6f, %.6f] (turning points [%.6f, %.6f]), "
         "mid-range %.6f, centre %s = %.6f\n",
         omega / wc, w.thmin, w.thmax, lo, hi, mid, omega < wc ? "0" : "acos(g/(R w^2))", centre);
  printf("  Jacobi integral h = %.12f drifts by %.2e; E = T + U varies by %.4f; h vs formula "
         "%.1e\n",
         w.h0, w.dh, w.dE, fabs(en.h - hf));
  bad |= !(fabs(en.h - hf) < 1e-12 * fmax(1.0, fabs(hf)));
  bad |= !(w.dh < 100 * o.rtol * fmax(1.0, fabs(w.h0)));
  bad |= !(w.dE > 1e4 * w.dh && w.dE > 1e-2);
  // the extremes sampled every dt lie within dt^2 |theta''| of the turning points
  bad |= !(fabs(w.thmin - lo) < 1e-3 && fabs(w.thmax - hi) < 1e-3);
  bad |= !(lo < centre && centre < hi);
  if (omega < wc) bad |= !(fabs(mid) < 1e-3);
  *hdrift = w.dh;
  *Evar = w.dE;
done:
  dal_state_destroy(st);
  dal_system_destroy(sys);
  return bad;
}

int main(int argc, char **argv) {
  const char *dir = "demo-output";
  int check = ex_args(argc, argv, &dir);
  double wc = sqrt(g / R), T = check ? 10.0 : 20.0, dt = 1e-3, hd, ev;
  double w_lo = 0.7 * wc, w_hi = 1.5 * wc, th0 = 0.3;
  printf("bead on a rotating ring: R=%g g=%g, omega_c = sqrt(g/R) = %.4f, theta0 = %g\n", R, g, wc,
         th0);
  int bad = 0;
  if (check) {
    bad |= scene(w_lo, th0, T, dt, NULL, &hd, &ev);
    bad |= scene(w_hi, th0, T, dt, NULL, &hd, &ev);
    printf("%s\n", bad ? "FAILED" : "ok");
    return bad;
  }
  if (ex_make_dir(dir)) return 1;
  char p1[1024], p2[1024], gp[1024], png[1024];
  snprintf(p1, sizeof p1, "%s/ring_below.csv", dir);
  snprintf(p2, sizeof p2, "%s/ring_above.csv", dir);
  snprintf(gp, sizeof gp, "%s/ring.gp", dir);
  snprintf(png, sizeof png, "%s/ring.png", dir);
  FILE *f1 = fopen(p1, "w"), *f2 = fopen(p2, "w");
  if (!f1 || !f2) {
    fprintf(stderr, "cannot write in %s\n", dir);
    return 1;
  }
  bad |= scene(w_lo, th0, T, 0.01, f1, &hd, &ev);
  bad |= scene(w_hi, th0, T, 0.01, f2, &hd, &ev);
  fclose(f1);
  fclose(f2);
  printf("wrote %s and %s\n", p1, p2);
  FILE *gf = fopen(gp, "w");
  if (gf) {
    // top: theta; middle: E relative to its start (omega = 1.5 omega_c: the ring does work on
    // the bead); bottom: h relative to its start on its own scale, its real (integration) drift
    fprintf(
        gf,
        "set terminal pngcairo size 1200,1200\nset output '%s'\nset datafile separator ','\n"
        "set multiplot layout 3,1\nset key outside\nset grid\n"
        "set xlabel 't (s)'\nset ylabel 'theta (rad)'\n"
        "set title 'Bead on a turning ring (R = %g m, g = %g m/s^2, theta(0) = %g rad): about 0 "
        "below omega_c = sqrt(g/R), off-axis above'\n"
        "plot '%s' using 1:2 with lines lw 2 title 'omega = 0.7 omega_c', "
        "'%s' using 1:2 with lines lw 2 title 'omega = 1.5 omega_c', "
        "0 with lines dt 2 lc rgb 'gray40' title 'theta = 0', "
        "%.17g with lines dt 2 lc rgb 'black' title 'acos(g/(R omega^2))'\n"
        "set ylabel 'E - E(0) (J; m = 1 kg)'\n"
        "set title 'omega = 1.5 omega_c: the energy E changes (the turning ring does work on "
        "the bead)'\n"
        "stats '%s' every ::1::1 using 4 nooutput name 'E0'\n"
        "stats '%s' every ::1::1 using 5 nooutput name 'H0'\n"
        "plot '%s' using 1:($4 - E0_mean) every ::1 with lines lw 2 lc rgb '#d62728' "
        "title 'E - E(0)'\n"
        "set ylabel 'h - h(0) (J)'\nset format y '%%.1e'\n"
        "set title 'the Jacobi integral h is conserved: its drift, on its own scale, is the "
        "integration error'\n"
        "plot '%s' using 1:($5 - H0_mean) every ::1 with lines lw 1 lc rgb '#2ca02c' "
        "title 'h - h(0)'\n"
        "unset multiplot\n",
        png, R, g, th0, p1, p2, acos(g / (R * w_hi * w_hi)), p2, p2, p2, p2);
    fclose(gf);
  }
  ex_gnuplot(gp, png);
  return bad;
}
