// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Sweep: largest Lyapunov exponent of the driven damped pendulum over (amplitude, frequency).
//
// Problem: a pendulum (m = 1, l = 1, g = 1, so the small-oscillation frequency is 1) whose
// support moves horizontally as x_s(t) = a cos(w t), with a viscous drag Q = -b theta'
// (b = 0.5). Coordinate: theta from the downward vertical (dal_map_pendulum, drive in its
// parameters 3 (ax) and 5 (w)). Equation:
//   theta'' = -sin(theta) + a w^2 cos(w t) cos(theta) - b theta'.
// Method: ONE compiled system; the sweep (dal_sweep_run, 2 threads) overrides (a, w) per
// trajectory ("place:bob:3", "place:bob:5"). The reducer estimates the largest Lyapunov
// exponent by the classic two-trajectory method (Benettin et al. 1976; Wolf et al. 1985):
// after a transient of 100 it follows the reference orbit and a second orbit started
// d0 = 1e-7 away in phase space (theta, theta') - the second state is per-worker data -
// and every tau = 1 time unit adds log(d / d0) and pulls the second orbit back to distance
// d0 along the current separation. lambda = sum / T. This is a stand-in: the analysis API
// (exact tangent dynamics) will replace it; the reducer is the only part to change.
// Checks (--check: 3 trajectories averaged over T = 2000; full mode: a 48 x 40 grid, T = 400,
// CSV + PNG heat map):
//  1. no drive (a = 0): the orbit rests at the bottom and lambda = -b/2 (the damped linear
//     oscillator's exponent, closed form) within 0.01;
//  2. a chaotic point of the map (a = 2.625, w = 1.1923, in the red region of the chart):
//     lambda > 0.1, and within 0.03 of an independent estimate from the variational
//     (tangent-linear) equations integrated by a hand-written RK4 from the same start;
//  3. a periodic point (a = 0.5, w = 0.8): lambda < 0 and within 0.01 of the same reference.
// Usage: lyapunov_map [--check] [--out DIR] [--threads N]
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dalembert/dalembert.h"

static const double drag = 0.5, D0 = 1e-7, TAU = 1.0, T_TRANS = 100.0;

static int damping(double t, const double *q, const double *qdot, double *Q, void *ctx) {
  (void)t;
  (void)q;
  Q[0] -= *(const double *)ctx * qdot[0];
  return 0;
}

static dal_system *build(void) {
  dal_builder *b = NULL;
  dal_system *s = NULL;
  int th, p, rc = dal_builder_create(2, &b);
  double par[7] = {1.0, 0, 0, 0.0, 0, 1.0, 0}, g[2] = {0, -1.0};
  if (!rc) rc = dal_builder_add_coord(b, "theta", &th);
  if (!rc) rc = dal_builder_add_particle(b, "bob", 1.0, &p);
  if (!rc) rc = dal_builder_place(b, p, &dal_map_pendulum, -1, 1, &th, 7, par, NULL);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  if (!rc) rc = dal_builder_add_genforce(b, damping, (void *)&drag);
  if (!rc) rc = dal_builder_compile(b, &s);
  if (rc) fprintf(stderr, "build: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return s;
}

typedef struct lyap_cfg {
  double T; // averaging time after the transient
  dal_solve_opts so;
} lyap_cfg;

static int make_state(const dal_system *sys, int id, void *ctx, void **data) {
  (void)id;
  (void)ctx;
  dal_state *st = NULL;
  int rc = dal_state_create(sys, &st);
  *data = st;
  return rc;
}

static void free_state(void *data, void *ctx) {
  (void)ctx;
  dal_state_destroy(data);
}

// the two-trajectory estimate; result: lambda, lambda over the first and the second half
static int lyapunov(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx) {
  const lyap_cfg *c = ctx;
  dal_state *nb = tr->worker;
  int rc = dal_advance(sys, st, &c->so, T_TRANS);
  if (!rc) rc = dal_state_copy_params(sys, nb, st);
  if (rc) return rc;
  // the neighbour starts d0 away along (1, 1) / sqrt(2)
  double t = dal_state_time(st), th = dal_state_q(st)[0], om = dal_state_qdot(st)[0];
  double thn = th + D0 / sqrt(2.0), omn = om + D0 / sqrt(2.0);
  if ((rc = dal_state_set(sys, nb, t, &thn, &omn)) != 0) return rc;
  long nsteps = (long)floor(c->T / TAU + 0.5), half = nsteps / 2;
  double sum = 0, sum1 = 0;
  for (long k = 1; k <= nsteps; ++k) {
    double tk = T_TRANS + k * TAU;
    if ((rc = dal_advance(sys, st, &c->so, tk)) || (rc = dal_advance(sys, nb, &c->so, tk))) {
      // report the failing state's message through the reference state
      if (dal_state_errmsg(nb)[0])
        snprintf(tr->msg, DAL_SWEEP_MSG_LEN, "neighbour orbit: %s", dal_state_errmsg(nb));
      return rc;
    }
    th = dal_state_q(st)[0];
    om = dal_state_qdot(st)[0];
    double dth = dal_state_q(nb)[0] - th, dom = dal_state_qdot(nb)[0] - om;
    double d = hypot(dth, dom);
    sum += log(d / D0);
    if (k == half) sum1 = sum;
    thn = th + dth * (D0 / d);
    omn = om + dom * (D0 / d);
    if ((rc = dal_state_set(sys, nb, tk, &thn, &omn)) != 0) return rc;
  }
  tr->result[0] = sum / (nsteps * TAU);
  tr->result[1] = sum1 / (half * TAU);
  tr->result[2] = (sum - sum1) / ((nsteps - half) * TAU);
  return 0;
}

// independent reference: the variational equations by a hand-written fixed-step RK4
static void vf(double t, const double *y, double a, double w, double *f) {
  double s = sin(y[0]), c = cos(y[0]), dr = a * w * w * cos(w * t);
  f[0] = y[1];
  f[1] = -s + dr * c - drag * y[1];
  f[2] = y[3];
  f[3] = (-c - dr * s) * y[2] - drag * y[3];
}

static double lyap_reference(double a, double w, double T) {
  double y[4] = {0.1, 0.0, 1.0 / sqrt(2.0), 1.0 / sqrt(2.0)}, t = 0, h = 1.0 / 400;
  double sum = 0;
  long per = (long)(TAU / h + 0.5), ntr = (long)(T_TRANS / TAU + 0.5), n = (long)(T / TAU + 0.5);
  for (long k = 0; k < ntr + n; ++k) {
    for (long i = 0; i < per; ++i) {
      double k1[4], k2[4], k3[4], k4[4], z[4];
      vf(t, y, a, w, k1);
      for (int j = 0; j < 4; ++j)
        z[j] = y[j] + 0.5 * h * k1[j];
      vf(t + 0.5 * h, z, a, w, k2);
      for (int j = 0; j < 4; ++j)
        z[j] = y[j] + 0.5 * h * k2[j];
      vf(t + 0.5 * h, z, a, w, k3);
      for (int j = 0; j < 4; ++j)
        z[j] = y[j] + h * k3[j];
      vf(t + h, z, a, w, k4);
      for (int j = 0; j < 4; ++j)
        y[j] += h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
      t = (double)(k * per + i + 1) * h;
    }
    double d = hypot(y[2], y[3]);
    if (k >= ntr) sum += log(d);
    y[2] /= d;
    y[3] /= d;
  }
  return sum / (n * TAU);
}

static int chart(const char *dir, const char *csv, double amax, double wmin, double wmax) {
  char gp[1024], png[1024];
  snprintf(gp, sizeof gp, "%s/lyapunov_map.gp", dir);
  snprintf(png, sizeof png, "%s/lyapunov_map.png", dir);
  FILE *fp = fopen(gp, "w");
  if (!fp) return 1;
  fprintf(fp,
          "set terminal pngcairo size 950,700 font ',11'\nset output '%s'\n"
          "set datafile separator ','\n"
          "set title \"Driven damped pendulum (b = 0.5): largest Lyapunov exponent\\n"
          "support x = a cos(w t); two-trajectory estimate, T = 400 after a transient of 100\"\n"
          "set xlabel 'drive frequency w (units of the small-oscillation frequency)'\n"
          "set ylabel 'drive amplitude a (units of l)'\n"
          "set cblabel 'lambda'\nset xrange [%g:%g]\nset yrange [0:%g]\n"
          "set palette defined (-0.3 '#08306b', -0.1 '#6baed6', 0 '#f7f7f7', 0.1 '#fc9272', "
          "0.3 '#a50f15')\nset cbrange [-0.3:0.3]\n"
          "set view map\n"
          "set key bottom left opaque box\n"
          "plot '%s' u 3:2:5 every ::1 w image notitle, \\\n"
          "     '%s' u 3:($5 > 0.01 ? $2 : 1/0) every ::1 w p pt 7 ps 0.3 lc rgb 'black' "
          "t 'lambda > 0.01 (chaotic)'\n",
          png, wmin, wmax, amax, csv, csv);
  fclose(fp);
  char cmd[2200];
  snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", gp);
  return system(cmd) != 0;
}

int main(int argc, char **argv) {
  int check = 0, threads = 2;
  const char *dir = ".";
  for (int i = 1; i < argc; ++i) {
    if (!strcmp(argv[i], "--check"))
      check = 1;
    else if (!strcmp(argv[i], "--out") && i + 1 < argc)
      dir = argv[++i];
    else if (!strcmp(argv[i], "--threads") && i + 1 < argc)
      threads = atoi(argv[++i]);
  }
  dal_system *sys = build();
  if (!sys) return 1;
  lyap_cfg cfg;
  cfg.T = check ? 2000.0 : 400.0; // check: long enough for a 0.03 agreement on chaos
  dal_solve_default_opts(&cfg.so);
  cfg.so.method = DAL_METHOD_DOPRI5;
  cfg.so.rtol = 1e-10;
  cfg.so.atol = 1e-12;
  int na = check ? 1 : 48, nw = check ? 3 : 40;
  long nt = (long)na * nw;
  double amax = 3.0, wmin = 0.3, wmax = 1.5;
  double *values = malloc((size_t)nt * 2 * sizeof(double));
  double *res = malloc((size_t)nt * 3 * sizeof(double));
  int *status = malloc((size_t)nt * sizeof(int));
  char *msgs = malloc((size_t)nt * 200);
  if (!values || !res || !status || !msgs) return 1;
  if (check) {
    // (a, w): no drive, the chaotic point, a periodic point
    const double pts[6] = {0.0, 1.0, 2.625, 0.3 + 1.2 * 29 / 39, 0.5, 0.8};
    memcpy(values, pts, sizeof pts);
  } else {
    int count[2] = {na, nw};
    double lo[2] = {amax / na, wmin}, hi[2] = {amax, wmax};
    dal_sweep_grid(2, count, lo, hi, values);
  }
  dal_param_ref par[2];
  if (dal_param_find(sys, "place:bob:3", &par[0], NULL, 0) ||
      dal_param_find(sys, "place:bob:5", &par[1], NULL, 0))
    return 1;
  double q0 = 0.1, v0 = 0.0;
  dal_sweep sw = {.ntraj = nt,
                  .nparam = 2,
                  .params = par,
                  .values = values,
                  .q0 = &q0,
                  .qdot0 = &v0,
                  .nresult = 3,
                  .reduce = lyapunov,
                  .ctx = &cfg};
  dal_sweep_out out = {res, status, msgs, 200, 0, 0};
  dal_sweep_opts o;
  dal_sweep_default_opts(&o);
  o.nthreads = threads;
  o.worker_create = make_state;
  o.worker_destroy = free_state;
  char err[256];
  if (dal_sweep_run(sys, &sw, &o, &out, err, sizeof err)) {
    fprintf(stderr, "sweep: %s\n", err);
    return 1;
  }
  int bad = out.nfailed != 0;
  for (long i = 0; i < nt; ++i)
    if (status[i]) printf("trajectory %ld failed: %s\n", i, msgs + i * 200);
  if (check) {
    double ref_c = lyap_reference(values[2], values[3], cfg.T),
           ref_p = lyap_reference(0.5, 0.8, cfg.T);
    printf("lyapunov: a = 0: lambda = %.5f (closed form -b/2 = %.5f)\n", res[0], -drag / 2);
    printf("  chaotic a = 2.625, w = 1.1923: lambda = %.5f (halves %.4f, %.4f); variational RK4 "
           "reference %.5f\n",
           res[3], res[4], res[5], ref_c);
    printf("  periodic a = 0.5, w = 0.8: lambda = %.5f; variational RK4 reference %.5f\n", res[6],
           ref_p);
    bad |= !(fabs(res[0] + drag / 2) <= 0.01);
    bad |= !(res[3] > 0.1) || !(fabs(res[3] - ref_c) <= 0.03);
    bad |= !(res[6] < 0) || !(fabs(res[6] - ref_p) <= 0.01);
  } else {
    long pos = 0;
    for (long i = 0; i < nt; ++i)
      pos += !status[i] && res[3 * i] > 0.01;
    printf("lyapunov map: %ld trajectories, %ld failed, %ld with lambda > 0.01\n", nt, out.nfailed,
           pos);
    char csv[1024];
    snprintf(csv, sizeof csv, "%s/lyapunov_map.csv", dir);
    FILE *fp = fopen(csv, "w");
    const char *names[3] = {"lambda", "lambda_first_half", "lambda_second_half"};
    if (!fp || dal_sweep_write_csv(fp, sys, &sw, &out, names)) bad = 1;
    if (fp) fclose(fp);
    if (chart(dir, csv, amax, wmin, wmax))
      printf("  (gnuplot not available: no chart)\n");
    else
      printf("  chart: %s/lyapunov_map.png\n", dir);
  }
  free(values);
  free(res);
  free(status);
  free(msgs);
  dal_system_destroy(sys);
  printf("%s\n", bad ? "FAILED" : "OK");
  return bad;
}
