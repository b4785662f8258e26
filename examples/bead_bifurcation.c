// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Bifurcation diagram of a bead on a turning ring: the pitchfork at w = sqrt(g/R).
//
// Problem: a bead of mass m = 0.1 on a ring of radius R = 0.5 turning about the vertical at a
// constant rate w; g = 9.81. Coordinate: theta, the polar angle from the ring's bottom measured
// in the turning ring (dal_map_ring), so the equilibria are relative equilibria, steady in the
// ring's frame. Analysis: dal_continue follows a branch of equilibria in the parameter w
// (every point a Newton solve with the exact stiffness, rebuilt system per w) and classifies
// each by the eigenvalues of the exact vector-field Jacobian; det K changing sign between grid
// points is bisected to the critical rate.
// Closed form (Likharev, Essential Graduate Physics, CM sec. 2.1): theta = 0 for all w, stable
// below w_c = sqrt(g/R) with frequency sqrt(g/R - w^2), unstable above; for w > w_c the pair
// cos(theta0) = g/(R w^2), stable, frequency w sin(theta0).
//
// Full mode (default; --out DIR, default ./demo-output): writes bead_bifurcation.csv
// (branch, w, theta, verdict, small-oscillation frequency; the located fork as branch "fork",
// frequency 0) and draws bead_bifurcation.png
// (stable branches solid, unstable dashed, the located fork marked) with gnuplot.
// --check (ctest): every point against the closed form (theta to 1e-12, frequency to 1e-10,
// verdict neutral/unstable as above) and the located fork against sqrt(g/R) to 1e-9.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "example_util.h"

static const double g = 9.81, R = 0.5, mass = 0.1;

static int build_ring(double w, dal_system **out, void *ctx) {
  (void)ctx;
  *out = ex_ring_bead(mass, R, w, g);
  return !*out;
}

// what each reported point is checked against and written as
typedef struct diagram {
  FILE *csv;          // may be NULL
  const char *branch; // "trivial", "upper", "lower"
  int bad, points;    // failed checks, points seen
  double fork;        // located critical rate (NAN if none)
  double worst_theta; // largest |theta - closed form|
  double worst_freq;  // largest relative frequency error
} diagram;

static int on_point(double w, const dal_system *sys, const dal_state *st, dal_stability v,
                    dal_branch_kind kind, void *ctx) {
  diagram *dg = ctx;
  const double wc = sqrt(g / R), th = dal_state_q(st)[0];
  if (kind == DAL_BRANCH_CRITICAL) {
    dg->fork = w;
    printf("  %-8s critical point (det K = 0) at w = %.12f, sqrt(g/R) = %.12f\n", dg->branch, w,
           wc);
    if (dg->csv) fprintf(dg->csv, "fork,%.12g,%.15g,%s,0\n", w, th, dal_stability_name(v));
    return 0;
  }
  // the small-oscillation frequency from the normal modes at this equilibrium
  double w2;
  dal_state *tmp = NULL;
  int rc = dal_state_create(sys, &tmp);
  double z = 0.0;
  if (!rc) rc = dal_state_set(sys, tmp, dal_state_time(st), &th, &z);
  if (!rc) rc = dal_normal_modes(sys, tmp, &w2, NULL, NULL, NULL, NULL);
  dal_state_destroy(tmp);
  if (rc) return 1;
  double freq = w2 >= 0 ? sqrt(w2) : -sqrt(-w2); // negative: growth rate of an unstable point
  // the closed form
  int trivial = strcmp(dg->branch, "trivial") == 0;
  double th_ref = trivial ? 0.0 : (th > 0 ? 1 : -1) * acos(g / (R * w * w));
  double f_ref =
      trivial ? (w < wc ? sqrt(g / R - w * w) : -sqrt(w * w - g / R)) : w * sin(fabs(th_ref));
  dal_stability v_ref = trivial && w > wc ? DAL_UNSTABLE : DAL_NEUTRAL;
  double et = fabs(th - th_ref), ef = fabs(freq - f_ref) / fabs(f_ref);
  dg->worst_theta = fmax(dg->worst_theta, et);
  dg->worst_freq = fmax(dg->worst_freq, ef);
  if (et > 1e-12 || ef > 1e-10 || v != v_ref) {
    fprintf(stderr, "%s branch at w = %.6f: theta %.15f (%.15f), frequency %.12f (%.12f), %s\n",
            dg->branch, w, th, th_ref, freq, f_ref, dal_stability_name(v));
    dg->bad++;
  }
  dg->points++;
  if (dg->csv)
    fprintf(dg->csv, "%s,%.12g,%.15g,%s,%.12g\n", dg->branch, w, th, dal_stability_name(v), freq);
  return 0;
}

static int run_branches(FILE *csv, int npoints, int *bad) {
  const double wc = sqrt(g / R);
  dal_continuation_opts o = dal_default_continuation_opts();
  dal_continuation_report rep;
  struct {
    const char *name;
    double q0, p0, p1;
  } br[3] = {{"trivial", 0.0, 0.2 * wc, 2.5 * wc},
             {"upper", 1.2, 2.5 * wc, 1.005 * wc},
             {"lower", -1.2, 2.5 * wc, 1.005 * wc}};
  double fork = NAN;
  for (int i = 0; i < 3; ++i) {
    diagram dg = {csv, br[i].name, 0, 0, NAN, 0.0, 0.0};
    o.p0 = br[i].p0;
    o.p1 = br[i].p1;
    o.npoints = npoints;
    int rc = dal_continue(build_ring, &br[i].q0, &o, on_point, &rep, &dg);
    if (rc) {
      fprintf(stderr, "%s branch: %s (%s)\n", br[i].name, dal_status_name(rc), rep.msg);
      return 1;
    }
    printf("  %-8s %d points from w = %.4f to %.4f, %d critical; worst |theta - closed form| "
           "%.1e, frequency rel. error %.1e\n",
           br[i].name, rep.npoints, o.p0, o.p1, rep.ncritical, dg.worst_theta, dg.worst_freq);
    *bad += dg.bad;
    if (i == 0) fork = dg.fork;
    // only the trivial branch crosses the fork; the others stay on one side of it
    if ((i == 0) != (rep.ncritical == 1) || (i > 0 && rep.ncritical != 0)) *bad += 1;
  }
  if (!(fabs(fork - wc) <= 1e-9 * wc)) {
    fprintf(stderr, "fork located at %.15g, expected %.15g\n", fork, wc);
    *bad += 1;
  }
  return 0;
}

static void chart(const char *dir, const char *csvpath) {
  char gp[1024], png[1024];
  snprintf(gp, sizeof gp, "%s/bead_bifurcation.gp", dir);
  snprintf(png, sizeof png, "%s/bead_bifurcation.png", dir);
  FILE *f = fopen(gp, "w");
  if (!f) return;
  double wc = sqrt(g / R);
  fprintf(
      f,
      "set terminal pngcairo size 1000,650\nset output '%s'\nset datafile separator ','\n"
      "set xlabel 'ring rate w (rad/s)'\nset ylabel 'equilibrium theta (rad, from the bottom)'\n"
      "set title 'Bead on a turning ring (R = 0.5 m, g = 9.81 m/s^2): pitchfork at w = sqrt(g/R) = "
      "%.4f rad/s'\n"
      "set key top left\nset grid\nset samples 2000\n"
      "set arrow from %g,-pi/2 to %g,pi/2 nohead dt 3 lc rgb 'gray50'\n"
      "stable(s) = (s eq 'neutral' || s eq 'asymptotic') ? 1 : 0\n"
      "plot '%s' using ($2):((stable(strcol(4)) && strcol(1) eq 'trivial') ? $3 : 1/0) "
      "with lines lw 3 lc rgb '#1f77b4' title 'theta = 0, stable', "
      "'' using ($2):((!stable(strcol(4)) && strcol(1) eq 'trivial') ? $3 : 1/0) with lines "
      "lw 3 dt 2 lc rgb '#d62728' title 'theta = 0, unstable', "
      "'' using ($2):((strcol(1) eq 'upper' || strcol(1) eq 'lower') ? $3 : 1/0) with points "
      "pt 7 ps 0.6 lc rgb '#2ca02c' title 'cos theta = g/(R w^2) (stable, computed)', "
      "'' using ($2):((strcol(1) eq 'fork') ? $3 : 1/0) with points pt 6 ps 2.5 lw 2 "
      "lc rgb 'black' title 'located fork (det K = 0, bisection)', "
      "acos(%g/(%g*x*x)) * (x > %g ? 1 : 1/0) with lines lc rgb 'black' title 'closed form', "
      "-acos(%g/(%g*x*x)) * (x > %g ? 1 : 1/0) with lines lc rgb 'black' notitle\n",
      png, wc, wc, wc, csvpath, g, R, wc, g, R, wc);
  fclose(f);
  ex_gnuplot(gp, png);
}

int main(int argc, char **argv) {
  const char *dir = "demo-output";
  int check = ex_args(argc, argv, &dir);
  printf("bead on a turning ring: m=%g R=%g g=%g, w_c = sqrt(g/R) = %.6f\n", mass, R, g,
         sqrt(g / R));
  int bad = 0;
  if (check) {
    if (run_branches(NULL, 31, &bad)) bad++;
    printf("%s\n", bad ? "FAILED" : "ok");
    return bad != 0;
  }
  if (ex_make_dir(dir)) return 1;
  char csvpath[1024];
  FILE *csv = ex_open(dir, "bead_bifurcation.csv", csvpath, sizeof csvpath);
  if (!csv) return 1;
  fprintf(csv, "branch,w,theta,verdict,frequency\n");
  int rc = run_branches(csv, 121, &bad);
  fclose(csv);
  if (rc) return 1;
  printf("wrote %s%s\n", csvpath, bad ? " (some points disagree with the closed form)" : "");
  chart(dir, csvpath);
  return bad != 0;
}
