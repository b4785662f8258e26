// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Sweep: the bead on a rotating ring, every equilibrium and its stability over the ring's rate.
//
// Problem: a bead (m = 1) on a ring of radius R = 1 turning about its vertical diameter at the
// rate w, gravity g = 9.81. Coordinate: theta, the polar angle from the ring's bottom measured
// in the turning ring (dal_map_ring), so the equilibria are relative equilibria, steady in the
// ring's frame. Equation: theta'' = sin(theta) (w^2 cos(theta) - g/R).
// Closed form (Goldstein 2.7; Likharev, Essential Graduate Physics, CM sec. 2.1): theta = 0 is
// an equilibrium for every w, stable below w_c = sqrt(g/R) with Omega^2 = g/R - w^2 and
// unstable above; theta = pi (the top) is always unstable, Omega^2 = -(g/R + w^2); above w_c
// the pair cos(theta*) = g/(R w^2) appears, stable, Omega^2 = w^2 sin^2(theta*): a
// supercritical pitchfork at w = w_c.
// Method: ONE compiled system; the sweep (dal_sweep_run, 2 threads) overrides the ring's rate
// (parameter 1 of dal_map_ring, "place:bead:1") per trajectory. The reducer finds the
// equilibria of its rate with the analysis API: dal_equilibrium (Newton with the exact
// stiffness K) from 16 starts spread over the circle, the distinct solutions kept, and
// dal_normal_modes classifies each (verdict from the eigenvalues of the exact vector-field
// Jacobian, Omega^2 from K x = Omega^2 M x). No time integration at all.
// Checks (--check: 20 rates over [0, 2.5 w_c] and 4 within 1% of w_c; full mode: 250 rates
// over [0, 2.5 w_c], CSV + PNG chart):
//  1. the set of equilibria of every rate is the closed-form set ({0, pi} below w_c,
//     {-theta*, 0, theta*, pi} above), each within 1e-10 rad, steady (d qddot/dt = 0);
//  2. verdicts: 0 neutral below w_c and unstable above, pi unstable, +-theta* neutral;
//  3. Omega^2 against the closed forms above, within 1e-9 g/R;
//  4. the pitchfork: the count of equilibria changes from 2 to 4 and the bottom's verdict
//     from neutral to unstable in the grid interval that contains w_c, and nowhere else;
//  5. the sweep on 2 threads equals a plain loop of the same reducer on one state, bit for bit.
// Usage: sweep_bead [--check] [--out DIR]   (full mode writes DIR/sweep_bead.csv, the sweep's
// own CSV, DIR/sweep_bead_chart.csv, one row per equilibrium, and with gnuplot
// DIR/sweep_bead.png)
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "example_util.h"

static const double R = 1.0, grav = 9.81, PI = 3.14159265358979323846;

enum {
  NSTART = 16, // Newton starts per rate
  MAXEQ = 6,   // equilibria kept per rate (4 expected)
  NRES = 1 + 3 * MAXEQ
};

static dal_system *build(void) { return ex_ring_bead(1.0, R, 0.0, grav); }

// theta wrapped into (-pi, pi]
static double wrap(double th) {
  double x = remainder(th, 2 * PI);
  return x <= -PI ? x + 2 * PI : x;
}

// reducer: result = (count, then per equilibrium in ascending theta: theta, verdict, Omega^2);
// the largest |d qddot/dt| of the solutions goes into the message when it is not ~0
static int equilibria(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx) {
  (void)ctx;
  dal_equilibrium_opts eo = dal_default_equilibrium_opts();
  eo.max_step = 0.25; // stay in the basin of the nearest solution
  double found[NSTART];
  int nf = 0, rc = DAL_OK, last = DAL_OK;
  for (int k = 0; k < NSTART; ++k) {
    double th = -PI + 2 * PI * k / NSTART, z = 0.0; // a grid over the circle, 0 and pi on it
    dal_equilibrium_report rep;
    if ((rc = dal_state_set(sys, st, 0.0, &th, &z)) != 0) return rc;
    if ((rc = dal_equilibrium(sys, st, &eo, &rep)) != 0) {
      last = rc; // a start at a singular K or without convergence: the others cover it
      continue;
    }
    if (!(fabs(rep.unsteady) <= 1e-12)) {
      snprintf(tr->msg, DAL_SWEEP_MSG_LEN, "equilibrium at theta=%.17g is not steady (%g)",
               dal_state_q(st)[0], rep.unsteady);
      return DAL_E_CALLBACK;
    }
    double q = wrap(dal_state_q(st)[0]);
    if (q < -PI + 1e-6) q += 2 * PI; // the top as +pi, whichever side Newton came from
    int dup = 0;
    for (int j = 0; j < nf; ++j)
      dup |= fabs(wrap(q - found[j])) <= 1e-8;
    if (!dup) found[nf++] = q;
  }
  if (nf == 0) return last ? last : DAL_E_CONV;
  if (nf > MAXEQ) {
    snprintf(tr->msg, DAL_SWEEP_MSG_LEN, "%d distinct equilibria, more than %d", nf, MAXEQ);
    return DAL_E_CALLBACK;
  }
  for (int i = 1; i < nf; ++i) // ascending
    for (int j = i; j > 0 && found[j] < found[j - 1]; --j) {
      double x = found[j];
      found[j] = found[j - 1];
      found[j - 1] = x;
    }
  tr->result[0] = nf;
  for (int j = 0; j < nf; ++j) {
    double z = 0.0, w2;
    dal_modes m;
    if ((rc = dal_state_set(sys, st, 0.0, &found[j], &z)) != 0 ||
        (rc = dal_normal_modes(sys, st, &w2, NULL, NULL, NULL, &m)) != 0)
      return rc;
    tr->result[1 + 3 * j] = found[j];
    tr->result[2 + 3 * j] = (double)m.verdict;
    tr->result[3 + 3 * j] = w2;
  }
  return 0;
}

// the closed-form equilibria of rate w, ascending in (-pi, pi], with verdicts and Omega^2
static int closed_form(double w, double *th, dal_stability *v, double *om2) {
  double wc2 = grav / R, w2 = w * w;
  int n = 0;
  if (w2 > wc2) {
    double ts = acos(wc2 / w2);
    th[n] = -ts, v[n] = DAL_NEUTRAL, om2[n++] = w2 * sin(ts) * sin(ts);
  }
  th[n] = 0.0, v[n] = w2 < wc2 ? DAL_NEUTRAL : DAL_UNSTABLE, om2[n++] = wc2 - w2;
  if (w2 > wc2) {
    double ts = acos(wc2 / w2);
    th[n] = ts, v[n] = DAL_NEUTRAL, om2[n++] = w2 * sin(ts) * sin(ts);
  }
  th[n] = PI, v[n] = DAL_UNSTABLE, om2[n++] = -(wc2 + w2);
  return n;
}

static int chart(const char *dir, const char *csv) {
  char gp[1024], png[1024];
  snprintf(gp, sizeof gp, "%s/sweep_bead.gp", dir);
  snprintf(png, sizeof png, "%s/sweep_bead.png", dir);
  FILE *fp = fopen(gp, "w");
  if (!fp) return 1;
  double wc = sqrt(grav / R);
  fprintf(fp,
          "set terminal pngcairo size 950,640 font ',11'\nset output '%s'\n"
          "set datafile separator ','\nset key inside bottom left opaque box\n"
          "set grid\nset title \"Bead on a ring turning at rate w (R = 1, g = 9.81): equilibria "
          "and their stability\\none compiled system, 250 rates, dal\\\\_equilibrium + "
          "dal\\\\_normal\\\\_modes per rate; pitchfork at w_c = sqrt(g/R) = %.3f rad/s\"\n"
          "set xlabel 'ring rate w (rad/s)'\n"
          "set ylabel 'equilibrium angle theta from the bottom (rad)'\n"
          "set xrange [0:%g]\nset yrange [-3.5:3.8]\n"
          "set ytics ('-pi' -pi, '-pi/2' -pi/2, '0' 0, 'pi/2' pi/2, 'pi' pi)\n"
          "set samples 3000\nwc = %.17g\nth(x) = acos(wc * wc / (x * x))\n"
          "set arrow from wc, graph 0 to wc, graph 1 nohead dt 3 lw 1.5 lc rgb 'gray40'\n"
          "set label 'w_c = sqrt(g/R)' at wc, 3.55 offset 0.6, 0 tc rgb 'gray30'\n"
          "plot (x > wc ? th(x) : 1/0) w l lw 1 lc rgb 'black' t 'closed form cos(theta*) = "
          "g/(R w^2)', \\\n"
          "     (x > wc ? -th(x) : 1/0) w l lw 1 lc rgb 'black' notitle, \\\n"
          "     '%s' u 1:($3 == 1 ? $2 : 1/0) every ::1 w p pt 7 ps 0.55 lc rgb '#1f77b4' "
          "t 'stable (neutral: Omega^2 > 0)', \\\n"
          "     '%s' u 1:($3 == 0 ? $2 : 1/0) every ::1 w p pt 6 ps 0.6 lc rgb '#d62728' "
          "t 'unstable (Omega^2 < 0)'\n",
          png, wc, 2.5 * wc, wc, csv, csv);
  fclose(fp);
  char cmd[2200];
  snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", gp);
  return system(cmd) != 0;
}

int main(int argc, char **argv) {
  const char *dir = ".";
  int check = ex_args(argc, argv, &dir);
  dal_system *sys = build();
  if (!sys) return 1;
  // w_c = 2.5 w_c j / (ngrid - 1) has no integer j: w_c is not on the grid; --check adds four
  // rates within 1e-3 and 1e-2 of w_c (small theta*, nearly singular K) to the 20 of the grid
  const int ngrid = check ? 20 : 250, nnear = check ? 4 : 0, nw = ngrid + nnear;
  double wc = sqrt(grav / R), wmax = 2.5 * wc;
  double *rates = malloc((size_t)nw * sizeof(double));
  double *res = malloc((size_t)nw * NRES * sizeof(double));
  double *res2 = malloc((size_t)nw * NRES * sizeof(double));
  int *status = malloc((size_t)nw * sizeof(int));
  char *msgs = malloc((size_t)nw * DAL_SWEEP_MSG_LEN);
  if (!rates || !res || !res2 || !status || !msgs) return 1;
  int count = ngrid;
  double lo = 0.0;
  dal_sweep_grid(1, &count, &lo, &wmax, rates);
  const double near[4] = {0.99 * wc, 0.999 * wc, 1.001 * wc, 1.01 * wc};
  for (int k = 0; k < nnear; ++k) { // insert, keeping the rates ascending
    int j = ngrid + k;
    for (; j > 0 && rates[j - 1] > near[k]; --j)
      rates[j] = rates[j - 1];
    rates[j] = near[k];
  }
  dal_param_ref rate;
  char err[256];
  if (dal_param_find(sys, "place:bead:1", &rate, err, sizeof err)) {
    fprintf(stderr, "%s\n", err);
    return 1;
  }
  double q0 = 0.0, v0 = 0.0;
  dal_sweep sw = {.ntraj = nw,
                  .nparam = 1,
                  .params = &rate,
                  .values = rates,
                  .q0 = &q0,
                  .qdot0 = &v0,
                  .nresult = NRES,
                  .reduce = equilibria};
  dal_sweep_out out = {res, status, msgs, DAL_SWEEP_MSG_LEN, 0, 0};
  dal_sweep_opts o = dal_default_sweep_opts();
  o.nthreads = 2;
  if (dal_sweep_run(sys, &sw, &o, &out, err, sizeof err)) {
    fprintf(stderr, "sweep: %s\n", err);
    return 1;
  }
  // checks 1-4 against the closed form
  int bad = out.nfailed != 0, forks = 0, fork_ok = 0;
  double worst_th = 0, worst_om = 0;
  for (long i = 0; i < nw; ++i) {
    const double w = rates[i], *r = res + i * NRES;
    if (status[i]) {
      printf("w = %g failed: %s (%s)\n", w, dal_status_name(status[i]),
             msgs + i * DAL_SWEEP_MSG_LEN);
      continue;
    }
    double th[4], om2[4];
    dal_stability v[4];
    int n = closed_form(w, th, v, om2);
    if ((int)r[0] != n) {
      printf("w = %g: %d equilibria, expected %d\n", w, (int)r[0], n);
      bad = 1;
      continue;
    }
    for (int j = 0; j < n; ++j) {
      double et = fabs(wrap(r[1 + 3 * j] - th[j])), eo = fabs(r[3 + 3 * j] - om2[j]) / (grav / R);
      worst_th = fmax(worst_th, et);
      worst_om = fmax(worst_om, eo);
      if (!(et <= 1e-10) || !(eo <= 1e-9) || (int)r[2 + 3 * j] != (int)v[j]) {
        printf("w = %g: theta %.15g (%.15g), Omega^2 %.12g (%.12g), %s (%s)\n", w, r[1 + 3 * j],
               th[j], r[3 + 3 * j], om2[j], dal_stability_name((dal_stability)r[2 + 3 * j]),
               dal_stability_name(v[j]));
        bad = 1;
      }
    }
    // the pitchfork between rates i-1 and i: count and the bottom's verdict change together
    if (i > 0 && !status[i - 1] && res[(i - 1) * NRES] != r[0]) {
      ++forks;
      fork_ok = rates[i - 1] < wc && wc < w && res[(i - 1) * NRES] == 2 && r[0] == 4;
      printf("  pitchfork between w = %.6f and %.6f (w_c = sqrt(g/R) = %.6f)\n", rates[i - 1], w,
             wc);
    }
  }
  bad |= forks != 1 || !fork_ok;
  printf("bead sweep: %d rates over w in [0, 2.5 w_c], %ld failed; equilibria vs closed form: "
         "max |theta error| %.1e rad, max |Omega^2 error| %.1e g/R\n",
         nw, out.nfailed, worst_th, worst_om);
  // 5. the sweep against a plain loop of the same reducer on one state
  int same = 1;
  dal_state *st = NULL;
  if (dal_state_create(sys, &st)) return 1;
  for (long i = 0; i < nw; ++i) {
    char m[DAL_SWEEP_MSG_LEN] = "";
    dal_traj tr = {i, &rates[i], res2 + i * NRES, NRES, NULL, 0, m};
    for (int k = 0; k < NRES; ++k)
      res2[i * NRES + k] = NAN;
    int rc = dal_state_reset_params(sys, st);
    if (!rc) rc = dal_state_set_param(sys, st, &rate, rates[i]);
    if (!rc) rc = dal_state_set(sys, st, 0.0, &q0, &v0);
    if (!rc) rc = equilibria(sys, st, &tr, NULL);
    same &= rc == status[i];
  }
  dal_state_destroy(st);
  same &= memcmp(res, res2, (size_t)nw * NRES * sizeof(double)) == 0;
  printf("  sweep on 2 threads vs a plain loop on one state: %s\n",
         same ? "bit-identical" : "DIFFERENT");
  bad |= !same;
  if (!check) {
    char csv[1024];
    snprintf(csv, sizeof csv, "%s/sweep_bead.csv", dir);
    FILE *fp = fopen(csv, "w");
    const char *names[NRES] = {"n_eq"};
    char namebuf[3 * MAXEQ][24];
    for (int j = 0; j < MAXEQ; ++j) {
      snprintf(namebuf[3 * j], 24, "theta%d", j + 1);
      snprintf(namebuf[3 * j + 1], 24, "verdict%d", j + 1);
      snprintf(namebuf[3 * j + 2], 24, "Omega2_%d", j + 1);
      for (int k = 0; k < 3; ++k)
        names[1 + 3 * j + k] = namebuf[3 * j + k];
    }
    // the sweep's own CSV: index, place:bead:1 (= w), status, n_eq, theta1, verdict1, ...
    if (!fp || dal_sweep_write_csv(fp, sys, &sw, &out, names)) bad = 1;
    if (fp) fclose(fp);
    // the chart's table: one row per equilibrium
    char csv2[1024];
    snprintf(csv2, sizeof csv2, "%s/sweep_bead_chart.csv", dir);
    fp = fopen(csv2, "w");
    if (fp) {
      fprintf(fp, "w,theta,stable,verdict,Omega2\n");
      for (long i = 0; i < nw; ++i)
        for (int j = 0; !status[i] && j < (int)res[i * NRES]; ++j) {
          const double *e = res + i * NRES + 1 + 3 * j;
          dal_stability v = (dal_stability)e[1];
          fprintf(fp, "%.17g,%.17g,%d,%s,%.17g\n", rates[i], e[0],
                  v == DAL_NEUTRAL || v == DAL_ASYMPTOTIC, dal_stability_name(v), e[2]);
        }
      fclose(fp);
      if (chart(dir, csv2))
        printf("  (gnuplot not available: no chart)\n");
      else
        printf("  chart: %s/sweep_bead.png\n", dir);
    }
  }
  free(rates);
  free(res);
  free(res2);
  free(status);
  free(msgs);
  dal_system_destroy(sys);
  return ex_verdict(bad, "OK");
}
