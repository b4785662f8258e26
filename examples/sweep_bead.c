// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Sweep: the bead on a rotating ring, equilibria over the ring's rate (pitchfork at w_c).
//
// Problem: a bead (m = 1) on a ring of radius R = 1 turning about its vertical diameter at the
// rate w, gravity g = 9.81, with a light viscous drag Q = -b theta' (b = 1) so that every
// trajectory settles on a stable equilibrium. Coordinate: theta from the ring's bottom
// (dal_map_ring). Equation: theta'' = sin(theta) (w^2 cos(theta) - g/R) - b theta'.
// Closed form (Goldstein 2.7): below w_c = sqrt(g/R) the bottom theta = 0 is the only stable
// equilibrium; above it the bottom is unstable and the bead settles at cos(theta*) = g/(R w^2)
// on either side (a supercritical pitchfork at w = w_c). Linearized frequency squared:
// Omega^2 = g/R - w^2 at the bottom, w^2 sin^2(theta*) on the side branches (> 0: stable).
// Method: ONE compiled system; the sweep (dal_sweep_run, 2 threads) overrides the ring's rate
// (parameter 1 of dal_map_ring, "place:bead:1") per trajectory, starts each rate from
// theta = +0.05 and -0.05 (just off the bottom), advances to t = 60 (DOPRI5, rtol 1e-10) and
// keeps the final theta, theta' as the reducer's result: the long damped run finds the stable
// equilibrium the closed form predicts. (The analysis API's equilibria and their stability
// will replace the long runs; the closed form stays the check.)
// Checks (--check: 16 rates; full mode: 161 rates, CSV + PNG chart into the output dir):
//  1. every trajectory settles (|theta'| < 1e-8) on the closed-form stable equilibrium within
//     1e-7 wherever |Omega^2| >= 0.5 (away from the critical slowing-down at w_c);
//  2. the pitchfork: below w_c both starts end at 0; above it they split to +theta*, -theta*;
//  3. the sweep's results are identical to a plain loop of dal_advance (bit for bit).
// Usage: sweep_bead [--check] [--out DIR]   (full mode writes DIR/sweep_bead.csv
// and, when gnuplot is installed, DIR/sweep_bead.png)
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dalembert/dalembert.h"

static const double R = 1.0, grav = 9.81, drag = 1.0, T_END = 60.0;

static int damping(double t, const double *q, const double *qdot, double *Q, void *ctx) {
  (void)t;
  (void)q;
  Q[0] -= *(const double *)ctx * qdot[0];
  return 0;
}

static dal_system *build(void) {
  dal_builder *b = NULL;
  dal_system *s = NULL;
  int th, p, rc = dal_builder_create(3, &b);
  double par[3] = {R, 0.0, 0.0}, g[3] = {0, 0, -grav};
  if (!rc) rc = dal_builder_add_coord(b, "theta", &th);
  if (!rc) rc = dal_builder_add_particle(b, "bead", 1.0, &p);
  if (!rc) rc = dal_builder_place(b, p, &dal_map_ring, -1, 1, &th, 3, par, NULL);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  if (!rc) rc = dal_builder_add_genforce(b, damping, (void *)&drag);
  if (!rc) rc = dal_builder_compile(b, &s);
  if (rc) fprintf(stderr, "build: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return s;
}

// reducer: the settled state
static int settle(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx) {
  (void)sys;
  (void)ctx;
  tr->result[0] = dal_state_q(st)[0];
  tr->result[1] = dal_state_qdot(st)[0];
  return 0;
}

// closed-form stable equilibrium on the side of theta0, and Omega^2 there
static double stable_eq(double w, double th0, double *Om2) {
  double wc2 = grav / R;
  if (w * w <= wc2) {
    *Om2 = wc2 - w * w;
    return 0.0;
  }
  double ts = acos(wc2 / (w * w));
  *Om2 = w * w * sin(ts) * sin(ts);
  return th0 > 0 ? ts : -ts;
}

static int chart(const char *dir, const char *csv) {
  char gp[1024], png[1024];
  snprintf(gp, sizeof gp, "%s/sweep_bead.gp", dir);
  snprintf(png, sizeof png, "%s/sweep_bead.png", dir);
  FILE *fp = fopen(gp, "w");
  if (!fp) return 1;
  double wc = sqrt(grav / R);
  fprintf(fp,
          "set terminal pngcairo size 900,600 font ',11'\nset output '%s'\n"
          "set datafile separator ','\nset key top left\nset grid\n"
          "set title 'Bead on a rotating ring: equilibria over the rate (one compiled system, "
          "sweep of long damped runs)'\n"
          "set xlabel 'w / w_c   (w_c = sqrt(g/R))'\nset ylabel 'settled theta (rad)'\n"
          "set xrange [0:2.5]\nset yrange [-1.7:1.7]\nset samples 4000\nwc = %.17g\n"
          "th(x) = acos(1.0 / (x * x))\n"
          "set arrow from 1, graph 0 to 1, graph 1 nohead dt 3 lc rgb 'gray50'\n"
          "plot (x > 1 ? th(x) : 1/0) w l lw 2 lc rgb '#1f77b4' t 'closed form cos(theta*) = "
          "g/(R w^2), stable', \\\n"
          "     (x > 1 ? -th(x) : 1/0) w l lw 2 lc rgb '#1f77b4' notitle, \\\n"
          "     (x <= 1 ? 0 : 1/0) w l lw 2 lc rgb '#2ca02c' t 'theta = 0, stable (w < w_c)', \\\n"
          "     (x > 1 ? 0 : 1/0) w l lw 2 dt 2 lc rgb '#d62728' t 'theta = 0, unstable "
          "(w > w_c)', \\\n"
          "     '%s' u ($3 > 0 ? $2 / wc : 1/0):5 every ::1 w p pt 7 ps 0.7 lc rgb 'black' "
          "t 'sweep, start theta = +0.05', \\\n"
          "     '%s' u ($3 < 0 ? $2 / wc : 1/0):5 every ::1 w p pt 6 ps 1.0 lc rgb '#ff7f0e' "
          "t 'sweep, start theta = -0.05'\n",
          png, wc, csv, csv);
  fclose(fp);
  char cmd[2200];
  snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", gp);
  return system(cmd) != 0;
}

int main(int argc, char **argv) {
  int check = 0;
  const char *dir = ".";
  for (int i = 1; i < argc; ++i) {
    if (!strcmp(argv[i], "--check"))
      check = 1;
    else if (!strcmp(argv[i], "--out") && i + 1 < argc)
      dir = argv[++i];
  }
  dal_system *sys = build();
  if (!sys) return 1;
  int nw = check ? 16 : 161;
  long nt = 2L * nw;
  double wc = sqrt(grav / R), wmax = 2.5 * wc;
  // trajectory i: rate w_(i/2), started from theta = +0.05 (even i) or -0.05 (odd i)
  double *rates = malloc((size_t)nt * sizeof(double));
  double *q0 = malloc((size_t)nt * sizeof(double)), *v0 = calloc((size_t)nt, sizeof(double));
  double *res = malloc((size_t)nt * 2 * sizeof(double));
  int *status = malloc((size_t)nt * sizeof(int));
  char *msgs = malloc((size_t)nt * 200);
  if (!rates || !q0 || !v0 || !res || !status || !msgs) return 1;
  for (long i = 0; i < nt; ++i) {
    rates[i] = wmax * (double)(i / 2) / (nw - 1);
    q0[i] = i % 2 ? -0.05 : 0.05;
  }
  dal_param_ref rate;
  char err[256];
  if (dal_param_find(sys, "place:bead:1", &rate, err, sizeof err)) {
    fprintf(stderr, "%s\n", err);
    return 1;
  }
  dal_solve_opts so;
  dal_solve_default_opts(&so);
  so.method = DAL_METHOD_DOPRI5;
  so.rtol = 1e-10;
  so.atol = 1e-12;
  dal_sweep sw = {.ntraj = nt,
                  .nparam = 1,
                  .params = &rate,
                  .values = rates,
                  .q0 = q0,
                  .qdot0 = v0,
                  .state_stride = 1,
                  .solve = &so,
                  .t1 = T_END,
                  .nresult = 2,
                  .reduce = settle};
  dal_sweep_out out = {res, status, msgs, 200, 0, 0};
  dal_sweep_opts o;
  dal_sweep_default_opts(&o);
  o.nthreads = 2;
  int rc = dal_sweep_run(sys, &sw, &o, &out, err, sizeof err);
  if (rc) {
    fprintf(stderr, "sweep: %s\n", err);
    return 1;
  }
  // checks against the closed form
  int bad = out.nfailed != 0, checked = 0;
  double worst = 0;
  for (long i = 0; i < nt; ++i) {
    double Om2, eq = stable_eq(rates[i], q0[i], &Om2);
    if (status[i]) {
      printf("trajectory %ld failed: %s\n", i, msgs + i * 200);
      continue;
    }
    if (fabs(Om2) >= 0.5) {
      worst = fmax(worst, fabs(res[2 * i] - eq));
      bad |= !(fabs(res[2 * i] - eq) <= 1e-7) || !(fabs(res[2 * i + 1]) <= 1e-8);
      ++checked;
    }
    // the pitchfork: each start keeps its side above w_c and returns to 0 below
    if (rates[i] > 1.05 * wc && !(res[2 * i] * copysign(1.0, q0[i]) > 0.5 * fabs(eq))) {
      printf("  w = %g start %g: settled at %g, expected %g\n", rates[i], q0[i], res[2 * i], eq);
      bad = 1;
    }
    if (rates[i] < 0.95 * wc && !(fabs(res[2 * i]) < 1e-6)) {
      printf("  w = %g start %g: settled at %g, expected 0\n", rates[i], q0[i], res[2 * i]);
      bad = 1;
    }
  }
  printf("bead sweep: %ld trajectories over w in [0, 2.5 w_c] (w_c = %.6f), %ld failed\n", nt, wc,
         out.nfailed);
  printf("  settled theta vs closed form (|Omega^2| >= 0.5, %d trajectories): max error %.2e\n",
         checked, worst);
  // the sweep against a plain loop of dal_advance
  double maxdiff = 0;
  dal_state *st = NULL;
  if (dal_state_create(sys, &st)) return 1;
  for (long i = 0; i < nt; i += check ? 1 : 7) {
    double v = 0.0;
    if (dal_state_set_param(sys, st, &rate, rates[i]) || dal_state_set(sys, st, 0.0, &q0[i], &v) ||
        dal_advance(sys, st, &so, T_END)) {
      bad = 1;
      continue;
    }
    if (memcmp(dal_state_q(st), &res[2 * i], sizeof(double)) ||
        memcmp(dal_state_qdot(st), &res[2 * i + 1], sizeof(double)))
      maxdiff = 1;
  }
  dal_state_destroy(st);
  printf("  sweep vs plain loop of dal_advance: %s\n", maxdiff ? "DIFFERENT" : "bit-identical");
  bad |= maxdiff != 0;
  if (!check) {
    char csv[1024];
    snprintf(csv, sizeof csv, "%s/sweep_bead.csv", dir);
    FILE *fp = fopen(csv, "w");
    const char *names[2] = {"theta", "thetadot"};
    // the sweep's own CSV: index, place:bead:1 (= w), status, theta, thetadot, message
    if (!fp || dal_sweep_write_csv(fp, sys, &sw, &out, names)) bad = 1;
    if (fp) fclose(fp);
    // the chart's table: w, the start theta0 and the closed-form equilibrium beside theta
    char csv2[1024];
    snprintf(csv2, sizeof csv2, "%s/sweep_bead_chart.csv", dir);
    fp = fopen(csv2, "w");
    if (fp) {
      fprintf(fp, "index,w,theta0,closed_form,theta,thetadot\n");
      for (long i = 0; i < nt; ++i) {
        double Om2, eq = stable_eq(rates[i], q0[i], &Om2);
        fprintf(fp, "%ld,%.17g,%.17g,%.17g,%.17g,%.17g\n", i, rates[i], q0[i], eq, res[2 * i],
                res[2 * i + 1]);
      }
      fclose(fp);
      if (chart(dir, csv2))
        printf("  (gnuplot not available: no chart)\n");
      else
        printf("  chart: %s/sweep_bead.png\n", dir);
    }
  }
  free(rates);
  free(q0);
  free(v0);
  free(res);
  free(status);
  free(msgs);
  dal_system_destroy(sys);
  printf("%s\n", bad ? "FAILED" : "OK");
  return bad;
}
