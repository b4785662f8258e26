// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Sweep: largest Lyapunov exponent of the driven damped pendulum over (amplitude, frequency).
//
// Problem: a pendulum (bob m = 1, l = 1, g = 1: small-oscillation frequency 1 rad per time
// unit) whose support moves horizontally as x_s(t) = a cos(w t), damped by a rotary dashpot:
// a light rack (mass m_r = 1e-3) meshing with a pinion of radius rho = 1 on the pendulum's
// axle slides along a horizontal rail as x_r = rho theta, and a linear damper (c = b / rho^2,
// b = 0.5) pulls it back toward a point far along the rail. Along the rail the damper's line
// of action is the rail itself, so its generalized force is exactly -b theta' (the tangent
// dynamics of the analysis API take dampers, not force callbacks; this is how a viscous drag
// on one coordinate is built from them). Coordinate: theta from the downward vertical
// (dal_map_pendulum for the bob, drive in its parameters 3 (ax) and 5 (w); dal_map_curve2 for
// the rack). With I = m l^2 + m_r rho^2 = 1.001:
//   I theta'' = -sin(theta) + a w^2 cos(w t) cos(theta) - b theta'.
// Method: ONE compiled system; the sweep (dal_sweep_run, 2 threads) overrides (a, w) per
// trajectory ("place:bob:3", "place:bob:5") and the reducer calls dal_lyapunov: the orbit
// and a tangent vector integrated together with the exact tangent dynamics (no finite
// differences, no second orbit), QR-renormalized every time unit (Benettin et al. 1980),
// averaged after a transient of 100 from theta = 0.1, theta' = 0.
// Checks (--check, 6 trajectories; full mode: a 48 x 40 grid averaged over 400, CSV + PNG):
//  1. no drive (a = 0): the orbit comes to rest at the bottom, a damped linear oscillator
//     whose two exponents are both -b/(2 I) (closed form, complex pair of I s^2 + b s + 1);
//     within 0.003 each, over 2000;
//  2. the same with the damper's coefficient overridden per trajectory ("damper:0:c" = 0.3):
//     both -0.3/(2 I) within 0.003;
//  3. a chaotic point (a = 2.625, w = 1.1923, in the red region of the map): lambda_1 > 0.1
//     and within 0.03 of an independent estimate (the variational equations written out by
//     hand for this scene and integrated by a hand-written RK4 over the same 2000);
//  4. Liouville: the flow contracts phase area at the constant rate b/I (trace of df/dy), so
//     lambda_1 + lambda_2 = -b/I for every drive; checked to 1e-7 at the chaotic point;
//  5. a periodic point (a = 0.5, w = 0.8): lambda_1 < 0 and within 0.01 of the same hand-
//     written reference;
//  6. the per-trajectory override equals a system compiled with those drive values, bit for
//     bit (a = 1.5, w = 0.9 over 50).
// Usage: lyapunov_map [--check] [--out DIR] [--threads N]
//   full mode writes DIR/lyapunov_map.csv and, with gnuplot, DIR/lyapunov_map.png, and prints
//   the CPU cost of the trajectories and how evenly MPI parts of the map would share it
//   (round-robin vs contiguous blocks; docs/ensembles.md, load balance)
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "dalembert/dalembert.h"
#include "example_util.h"

static const double drag = 0.5, rho = 1.0, m_rack = 1e-3, T_TRANS = 100.0;
// moment of inertia about the axle: bob m l^2 = 1 plus the rack's m_r rho^2
#define INERTIA (1.0 + m_rack * rho * rho)

// the rail: x = rho s, y = -2 (below the pendulum; horizontal, so gravity does no work on it)
static int rail(dal_jet s, dal_jet t, dal_jet *p, void *ctx) {
  (void)t;
  p[0] = dal_scale(s, *(const double *)ctx);
  p[1] = dal_const(-2.0);
  return 0;
}

typedef struct scene {
  dal_curve rail; // the rack's rail (must outlive the system)
  double rho;
} scene;

static dal_system *build(scene *sc, double a, double w) {
  dal_builder *b = NULL;
  int th, bob, rack, rc = dal_builder_create(2, &b);
  double g[2] = {0, -1.0};
  sc->rho = rho;
  sc->rail.fn = rail;
  sc->rail.ctx = &sc->rho;
  if (!rc) rc = dal_builder_add_coord(b, "theta", &th);
  if (!rc) rc = dal_builder_add_particle(b, "bob", 1.0, &bob);
  if (!rc) rc = dal_builder_add_particle(b, "rack", m_rack, &rack);
  dal_place_def pd = dal_default_place_def(); // the pivot driven along x
  pd.prim = &dal_map_pendulum;
  pd.coords = &th;
  pd.ncoords = 1;
  pd.param[DAL_PENDULUM_L] = 1.0;
  pd.param[DAL_PENDULUM_AX] = a;
  pd.param[DAL_PENDULUM_W] = w;
  if (!rc) rc = dal_builder_place_def(b, bob, &pd);
  pd = dal_default_place_def();
  pd.prim = &dal_map_curve2;
  pd.coords = &th;
  pd.ncoords = 1;
  pd.ctx = &sc->rail;
  if (!rc) rc = dal_builder_place_def(b, rack, &pd);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  // the dashpot on the rack, anchored 1e6 along the rail: its line of action is the rail
  dal_damper_def dd = dal_default_damper_def();
  dd.a = rack;
  dd.anchor[0] = -1e6;
  dd.anchor[1] = -2.0;
  dd.c = drag / (rho * rho);
  if (!rc) rc = dal_builder_add_damper_def(b, &dd);
  return ex_compile(b, rc);
}

typedef struct lyap_cfg {
  double T;     // averaging time after the transient
  int nexp;     // exponents per trajectory (1 for the map; 2 in the checks)
  double rtol;  // DOPRI5 tolerance
  double *cost; // nullable: thread CPU seconds of trajectory i (slot i, written by its worker)
} lyap_cfg;

static double thread_cpu(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

// reducer: the largest exponent(s) and their convergence estimates (95% half-widths of the block
// means)
static int lyapunov(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx) {
  const lyap_cfg *c = ctx;
  dal_lyapunov_opts o = dal_default_lyapunov_opts();
  o.nexp = c->nexp;
  o.transient = T_TRANS;
  o.t_end = dal_state_time(st) + T_TRANS + c->T;
  o.rtol = o.atol = c->rtol;
  double ex[2], er[2], c0 = thread_cpu();
  int rc = dal_lyapunov(sys, st, &o, ex, er, NULL, NULL);
  if (c->cost) c->cost[tr->index] = thread_cpu() - c0; // kept apart: the CSV stays exact
  if (rc) return rc;
  for (int k = 0; k < c->nexp; ++k) {
    tr->result[2 * k] = ex[k];
    tr->result[2 * k + 1] = er[k];
  }
  return 0;
}

// independent reference: the variational equations of I theta'' = -sin theta + a w^2 cos(w t)
// cos theta - b theta', written out by hand and integrated by a fixed-step RK4
static void vf(double t, const double *y, double a, double w, double *f) {
  double s = sin(y[0]), c = cos(y[0]), dr = a * w * w * cos(w * t);
  f[0] = y[1];
  f[1] = (-s + dr * c - drag * y[1]) / INERTIA;
  f[2] = y[3];
  f[3] = ((-c - dr * s) * y[2] - drag * y[3]) / INERTIA;
}

static double lyap_reference(double a, double w, double T) {
  double y[4] = {0.1, 0.0, 1.0 / sqrt(2.0), 1.0 / sqrt(2.0)}, t = 0, h = 1.0 / 400;
  double sum = 0;
  long per = 400, ntr = (long)(T_TRANS + 0.5), n = (long)(T + 0.5);
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
  return sum / (double)n;
}

static int chart(const char *dir, const char *csv, double amax, double wmin, double wmax,
                 double T) {
  char gp[1024], png[1024];
  snprintf(gp, sizeof gp, "%s/lyapunov_map.gp", dir);
  snprintf(png, sizeof png, "%s/lyapunov_map.png", dir);
  FILE *fp = fopen(gp, "w");
  if (!fp) return 1;
  fprintf(fp,
          "set terminal pngcairo size 950,720 font ',11'\nset output '%s'\n"
          "set datafile separator ','\n"
          "set title \"Driven damped pendulum: largest Lyapunov exponent (exact tangent "
          "dynamics)\\nI theta'' = -sin theta + a w^2 cos(w t) cos theta - b theta', b = 0.5, "
          "I = 1.001; averaged over t = %g after %g\"\n"
          "set xlabel 'drive frequency w (rad per time unit; small-oscillation frequency = 1)'\n"
          "set ylabel 'support amplitude a (units of l)'\n"
          "set cblabel 'lambda_1 (1 / time unit)'\nset xrange [%g:%g]\nset yrange [0:%g]\n"
          "set palette defined (-0.3 '#08306b', -0.1 '#6baed6', 0 '#f7f7f7', 0.1 '#fc9272', "
          "0.3 '#a50f15')\nset cbrange [-0.3:0.3]\n"
          "set key bottom left opaque box\n"
          "plot '%s' u 3:2:5 every ::1 w image notitle, \\\n"
          "     '%s' u 3:($5 > 0.01 ? $2 : 1/0) every ::1 w p pt 7 ps 0.3 lc rgb 'black' "
          "t 'lambda_1 > 0.01 (chaotic)'\n",
          png, T, T_TRANS, wmin, wmax, amax, csv, csv);
  fclose(fp);
  char cmd[2200];
  snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", gp);
  return system(cmd) != 0;
}

// check 6: the sweep's per-trajectory override against a system compiled with the values
static int check_override(const dal_system *sys, const dal_param_ref *par, const lyap_cfg *cfg) {
  const double a = 1.5, w = 0.9, q0 = 0.1, v0 = 0.0;
  double vals[2] = {a, w}, res[4], ref[4];
  int status = -1;
  lyap_cfg c = *cfg;
  c.T = 50.0;
  dal_sweep sw = {.ntraj = 1,
                  .nparam = 2,
                  .params = par,
                  .values = vals,
                  .q0 = &q0,
                  .qdot0 = &v0,
                  .nresult = 2 * c.nexp,
                  .reduce = lyapunov,
                  .ctx = &c};
  dal_sweep_out out = {res, &status, NULL, 0, 0, 0};
  dal_sweep_opts o = dal_default_sweep_opts();
  if (dal_sweep_run(sys, &sw, &o, &out, NULL, 0) || status) return 1;
  scene sc;
  dal_system *own = build(&sc, a, w);
  dal_state *st = NULL;
  dal_traj tr = {0, vals, ref, 2 * c.nexp, NULL, 0, NULL};
  int rc = !own || dal_state_create(own, &st) || dal_state_set(own, st, 0.0, &q0, &v0) ||
           lyapunov(own, st, &tr, &c);
  dal_state_destroy(st);
  dal_system_destroy(own);
  int same = !rc && memcmp(res, ref, sizeof res) == 0;
  printf("  override (a, w) = (%g, %g) vs compiled with them, T = 50: lambda %.15f vs %.15f, "
         "%s\n",
         a, w, res[0], ref[0], same ? "bit-identical" : "DIFFERENT");
  return !same;
}

static int cmp_d(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

// the cost of the trajectories over the map, and how well MPI parts balance it: for P parts,
// the largest part's CPU over the mean part's (1 = perfect), round-robin (dal_sweep_part_of
// with block 1, the default) against contiguous blocks of ntraj / P
static void cost_report(const double *cost, const double *res, const int *status, long nt) {
  double *c = malloc((size_t)nt * sizeof(double)), tot = 0.0, chaos = 0.0, calm = 0.0;
  long nchaos = 0;
  if (!c) return;
  for (long i = 0; i < nt; ++i) {
    c[i] = cost[i];
    tot += cost[i];
    if (!status[i] && res[2 * i] > 0.01) {
      chaos += cost[i];
      ++nchaos;
    } else {
      calm += cost[i];
    }
  }
  qsort(c, (size_t)nt, sizeof(double), cmp_d);
  printf("  cost per trajectory (thread CPU s): min %.4f, median %.4f, max %.4f, total %.1f; "
         "mean where lambda_1 > 0.01: %.4f, elsewhere %.4f\n",
         c[0], c[nt / 2], c[nt - 1], tot, nchaos ? chaos / nchaos : 0.0,
         nt > nchaos ? calm / (nt - nchaos) : 0.0);
  const int parts[4] = {2, 8, 32, 128};
  for (int k = 0; k < 4; ++k) {
    int P = parts[k], block = (int)((nt + P - 1) / P);
    double rr[128] = {0}, cb[128] = {0}, mrr = 0, mcb = 0;
    for (long i = 0; i < nt; ++i) {
      rr[dal_sweep_part_of(i, P, 1)] += cost[i];
      cb[dal_sweep_part_of(i, P, block)] += cost[i];
    }
    for (int p = 0; p < P; ++p) {
      mrr = fmax(mrr, rr[p]);
      mcb = fmax(mcb, cb[p]);
    }
    printf("  %3d parts: largest / mean part CPU, round-robin %.3f, contiguous blocks %.3f\n", P,
           mrr * P / tot, mcb * P / tot);
  }
  free(c);
}

int main(int argc, char **argv) {
  const char *dir = ".";
  int check = ex_args(argc, argv, &dir), threads = ex_int_opt(argc, argv, "--threads", 2);
  scene sc;
  dal_system *sys = build(&sc, 0.0, 1.0);
  if (!sys) return 1;
  lyap_cfg cfg = {check ? 2000.0 : 400.0, check ? 2 : 1, check ? 1e-10 : 1e-8, NULL};
  int na = check ? 1 : 48, nw = check ? 4 : 40;
  long nt = (long)na * nw;
  double amax = 3.0, wmin = 0.3, wmax = 1.5;
  const int npar = check ? 3 : 2;
  double *values = malloc((size_t)nt * (size_t)npar * sizeof(double));
  double *res = malloc((size_t)nt * 4 * sizeof(double));
  int *status = malloc((size_t)nt * sizeof(int));
  char *msgs = malloc((size_t)nt * 200);
  double *cost = check ? NULL : calloc((size_t)nt, sizeof(double));
  if (!values || !res || !status || !msgs || (!check && !cost)) return 1;
  cfg.cost = cost;
  if (check) {
    // (a, w, damper c): no drive, no drive with c = 0.3, the chaotic point, a periodic point
    const double pts[12] = {0.0,  1.0, drag, 0.0, 1.0, 0.3, 2.625, 0.3 + 1.2 * 29 / 39,
                            drag, 0.5, 0.8,  drag};
    memcpy(values, pts, sizeof pts);
  } else {
    int count[2] = {na, nw};
    double lo[2] = {amax / na, wmin}, hi[2] = {amax, wmax};
    dal_sweep_grid(2, count, lo, hi, values);
  }
  dal_param_ref par[3];
  char err[256];
  if (dal_param_find(sys, "place:bob:3", &par[0], err, sizeof err) ||
      dal_param_find(sys, "place:bob:5", &par[1], err, sizeof err) ||
      dal_param_find(sys, "damper:0:c", &par[2], err, sizeof err)) {
    fprintf(stderr, "%s\n", err);
    return 1;
  }
  double q0 = 0.1, v0 = 0.0;
  dal_sweep sw = {.ntraj = nt,
                  .nparam = npar,
                  .params = par,
                  .values = values,
                  .q0 = &q0,
                  .qdot0 = &v0,
                  .nresult = 2 * cfg.nexp,
                  .reduce = lyapunov,
                  .ctx = &cfg};
  dal_sweep_out out = {res, status, msgs, 200, 0, 0};
  dal_sweep_opts o = dal_default_sweep_opts();
  o.nthreads = threads;
  if (dal_sweep_run(sys, &sw, &o, &out, err, sizeof err)) {
    fprintf(stderr, "sweep: %s\n", err);
    return 1;
  }
  int bad = out.nfailed != 0;
  for (long i = 0; i < nt; ++i)
    if (status[i]) printf("trajectory %ld failed: %s\n", i, msgs + i * 200);
  if (check) {
    const double I = INERTIA, T = cfg.T, *r = res;
    double l0 = -drag / (2 * I), l03 = -0.3 / (2 * I);
    double ref_c = lyap_reference(values[6], values[7], T), ref_p = lyap_reference(0.5, 0.8, T);
    printf("lyapunov map checks (exact tangent, DOPRI5 rtol %g, averaged over %g after %g):\n",
           cfg.rtol, T, T_TRANS);
    printf("  a = 0, b = 0.5: lambda = %.6f, %.6f (closed form -b/(2I) = %.6f)\n", r[0], r[2], l0);
    printf("  a = 0, damper c overridden to 0.3: lambda = %.6f, %.6f (closed form %.6f)\n", r[4],
           r[6], l03);
    printf("  chaotic a = 2.625, w = 1.1923: lambda_1 = %.5f +- %.5f; hand-written variational "
           "RK4 reference %.5f\n",
           r[8], r[9], ref_c);
    printf("  chaotic point: lambda_1 + lambda_2 = %.9f (Liouville: -b/I = %.9f)\n", r[8] + r[10],
           -drag / I);
    printf("  periodic a = 0.5, w = 0.8: lambda_1 = %.5f; hand-written reference %.5f\n", r[12],
           ref_p);
    bad |= !(fabs(r[0] - l0) <= 3e-3) || !(fabs(r[2] - l0) <= 3e-3);
    bad |= !(fabs(r[4] - l03) <= 3e-3) || !(fabs(r[6] - l03) <= 3e-3);
    bad |= !(r[8] > 0.1) || !(fabs(r[8] - ref_c) <= 0.03);
    bad |= !(fabs(r[8] + r[10] + drag / I) <= 1e-7);
    bad |= !(r[12] < 0) || !(fabs(r[12] - ref_p) <= 0.01);
    bad |= check_override(sys, par, &cfg);
  } else {
    long pos = 0;
    for (long i = 0; i < nt; ++i)
      pos += !status[i] && res[2 * i] > 0.01;
    printf("lyapunov map: %ld trajectories, %ld failed, %ld with lambda_1 > 0.01\n", nt,
           out.nfailed, pos);
    cost_report(cost, res, status, nt);
    char csv[1024];
    snprintf(csv, sizeof csv, "%s/lyapunov_map.csv", dir);
    FILE *fp = fopen(csv, "w");
    const char *names[2] = {"lambda1", "lambda1_stderr"};
    if (!fp || dal_sweep_write_csv(fp, sys, &sw, &out, names)) bad = 1;
    if (fp) fclose(fp);
    if (chart(dir, csv, amax, wmin, wmax, cfg.T))
      printf("  (gnuplot not available: no chart)\n");
    else
      printf("  chart: %s/lyapunov_map.png\n", dir);
  }
  free(values);
  free(cost);
  free(res);
  free(status);
  free(msgs);
  dal_system_destroy(sys);
  return ex_verdict(bad, "OK");
}
