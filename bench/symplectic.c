// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Long runs: symplectic vs adaptive methods (energy, phase, crossover), failures, round-off.
//
// Usage: dal_bench_symplectic [--quick | --full] [--out DIR] [--only SECTION]  (CSV files and
// sym_summary.md; --only stiff|drive|separatrix|rounding runs one section, summary to stdout)
// Charts: gnuplot -e "dir='DIR'" bench/symplectic.gp            (bench/symplectic.sh)
//
// Scenes: the pendulum released at 120 degrees (minimal coordinates, exact solution by Jacobi
// elliptic functions), the bead on a ring turning at 0.7 turns/s (minimal coordinates:
// Jacobi integral h; Cartesian on a turning circle: E - w L_z, a rheonomic constraint), the
// Cartesian double pendulum (two rods). Every symplectic run and its adaptive rivals are
// measured side by side in one process; "matched cost" picks the adaptive tolerance whose
// CPU time per simulated second, measured on a pilot stretch, is closest to the symplectic
// run's. Errors are sampled at log-spaced times (the adaptive drivers step exactly to each
// output, so dense sampling would change them); the running maximum over the samples is the
// envelope reported.
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "dalembert/dalembert.h"
#include "ref_elliptic.h"
#include "support/scenes.h"
#include "util.h"

#define PI 3.14159265358979323846

static int quick = 1;

// CPU seconds of this process: less sensitive than wall time to the other jobs of a shared
// machine (the library is single-threaded)
static double cpu_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
static const char *outdir = "bench/results";
// --only SECTION (stiff, drive, separatrix, rounding): run that section alone, its summary
// to stdout (sym_summary.md is left as it is)
static const char *only = NULL;

// ---------------------------------------------------------------------------------------------
// scenes

typedef enum { INV_E, INV_JACOBI, INV_E_WLZ } inv_kind;

typedef struct scene {
  const char *name;
  dal_system *sys;
  int n;
  double q0[8], v0[8];
  inv_kind inv;
  double w;     // ring rate (INV_E_WLZ)
  double unit;  // period: the time unit of horizons
  double scale; // energy scale of relative errors
  int exact;    // 1: the pendulum's elliptic solution is the reference of theta
} scene;

static dal_system *compile(dal_builder *b, int rc) {
  dal_system *sys = NULL;
  if (!rc) rc = dal_builder_compile(b, &sys);
  if (rc) fprintf(stderr, "build failed: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  if (!sys) exit(1);
  return sys;
}

// a standard scene (tests/support), or the end of the run when it cannot be built
static dal_system *built(dal_system *sys) {
  if (!sys) exit(1);
  return sys;
}

// a unit pendulum (g = 9.8) whose pivot is driven by (ax cos wt, ay cos wt)
static dal_system *build_pendulum(double ax, double ay, double w) {
  scn_knobs k = scn_default();
  k.g = 9.8;
  k.ax = ax;
  k.ay = ay;
  k.w = w;
  return built(scn_pendulum(&k));
}

static dal_system *build_ring(double w, int cartesian) {
  scn_knobs k = scn_default(); // unit radius, centred at the origin
  k.spin = w;
  return built(cartesian ? scn_cart_bead(&k) : scn_bead(&k));
}

static dal_system *build_double_cartesian(void) {
  scn_knobs k = scn_default(); // m2 = 0.5 on l2 = 0.7 below a unit rod to the origin
  k.m2 = 0.5;
  k.l2 = 0.7;
  return built(scn_cart_double_pendulum(&k));
}

// the period of the bead's oscillation on the ring, from the times theta' turns positive
static double ring_period(double w, double th0) {
  dal_system *sys = build_ring(w, 0);
  dal_state *st = NULL;
  dal_state_create(sys, &st);
  double v = 0.0, tprev = -1, first = -1, last = -1, pv = 0.0;
  int count = 0;
  dal_state_set(sys, st, 0.0, &th0, &v);
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_BS;
  o.rtol = o.atol = 1e-12;
  for (int k = 1; k <= 40000; ++k) {
    double t = 0.001 * k;
    if (dal_advance(sys, st, &o, t)) break;
    double qd = dal_state_qdot(st)[0];
    if (pv < 0 && qd >= 0) {
      double tc = t - 0.001 * qd / (qd - pv);
      if (first < 0) first = tc;
      last = tc;
      ++count;
    }
    pv = qd;
    tprev = t;
  }
  (void)tprev;
  dal_state_destroy(st);
  dal_system_destroy(sys);
  return count > 1 ? (last - first) / (count - 1) : 2 * PI / w;
}

static void scene_pendulum(scene *s) {
  memset(s, 0, sizeof *s);
  s->name = "pendulum";
  s->sys = build_pendulum(0, 0, 0);
  s->n = 1;
  s->q0[0] = 2.0 * PI / 3.0;
  s->inv = INV_E;
  s->unit = 4.0 * ref_ellip_K(0.75) / sqrt(9.8);
  s->scale = 9.8;
  s->exact = 1;
}

static void scene_ring(scene *s, int cartesian) {
  memset(s, 0, sizeof *s);
  double w = 2.0 * PI * 0.7, th0 = 2.0;
  s->name = cartesian ? "ring_cartesian" : "ring";
  s->sys = build_ring(w, cartesian);
  s->w = w;
  s->unit = ring_period(w, th0);
  s->scale = 9.81;
  if (cartesian) {
    s->n = 3;
    s->q0[0] = sin(th0);
    s->q0[2] = -cos(th0);
    s->v0[1] = w * sin(th0); // co-moving with the ring at rest on it
    s->inv = INV_E_WLZ;
  } else {
    s->n = 1;
    s->q0[0] = th0;
    s->inv = INV_JACOBI;
  }
}

static void scene_double(scene *s) {
  memset(s, 0, sizeof *s);
  double th[2] = {1.5, 2.0};
  s->name = "double_cartesian";
  s->sys = build_double_cartesian();
  s->n = 4;
  s->q0[0] = sin(th[0]);
  s->q0[1] = -cos(th[0]);
  s->q0[2] = s->q0[0] + 0.7 * sin(th[1]);
  s->q0[3] = s->q0[1] - 0.7 * cos(th[1]);
  s->inv = INV_E;
  s->unit = 2.0 * PI * sqrt(1.0 / 9.81);
  s->scale = 1.5 * 9.81;
}

static double invariant(const scene *s, const dal_state *st) {
  dal_energies e;
  dal_state_energies(st, &e);
  if (s->inv == INV_JACOBI) return e.h;
  if (s->inv == INV_E) return e.E;
  const double *r = dal_state_positions(st), *v = dal_state_velocities(st);
  return e.E - s->w * (r[0] * v[1] - r[1] * v[0]);
}

static double wrap(double x) {
  double r = x - 2 * PI * floor((x + PI) / (2 * PI));
  return r >= PI ? r - 2 * PI : r;
}

// ---------------------------------------------------------------------------------------------
// runs

typedef struct run_cfg {
  dal_method m;
  double param; // fixed step (symplectic) or rtol (adaptive)
  dal_formulation form;
  int project;
} run_cfg;

static int is_fixed(dal_method m) {
  return m == DAL_METHOD_VARIATIONAL || m == DAL_METHOD_VARIATIONAL4 ||
         m == DAL_METHOD_VARIATIONAL6 || m == DAL_METHOD_RATTLE || m == DAL_METHOD_RATTLE4 ||
         m == DAL_METHOD_RATTLE6 || m == DAL_METHOD_RK4;
}

static void cfg_opts(const run_cfg *c, dal_solve_opts *o) {
  *o = dal_default_solve_opts();
  o->method = c->m;
  o->form = c->form;
  o->project = c->project;
  o->max_steps = 2000000000L;
  if (is_fixed(c->m))
    o->fixed_step = c->param;
  else
    o->rtol = o->atol = c->param;
}

static const char *cfg_name(const run_cfg *c, char *buf, size_t len) {
  snprintf(buf, len, "%s%s", dal_method_name(c->m),
           c->project                ? "-proj"
           : c->form == DAL_FORM_GGL ? "-ggl"
                                     : "");
  return buf;
}

// the samples of one run: time, invariant error, its running max, theta error and its max
typedef struct samples {
  int n, cap;
  double *t, *dE, *dEmax, *dq, *dqmax;
  double wall;
  int rc;
} samples;

static void samples_free(samples *s) {
  free(s->t);
  free(s->dE);
  free(s->dEmax);
  free(s->dq);
  free(s->dqmax);
  memset(s, 0, sizeof *s);
}

// log-spaced sample times from one unit to the horizon, per decade
static int sample_times(double unit, double horizon, int per_decade, double **out) {
  int nd = (int)ceil(log10(horizon / unit) * per_decade) + 1;
  double *t = malloc((size_t)(nd + 2) * sizeof(double));
  int n = 0;
  for (int k = 0; k < nd; ++k) {
    double tk = unit * pow(10.0, (double)k / per_decade);
    if (tk >= horizon) break;
    t[n++] = tk;
  }
  t[n++] = horizon;
  *out = t;
  return n;
}

static int run(const scene *sc, const run_cfg *c, const double *times, int nt, samples *out) {
  dal_state *st = NULL;
  dal_solve_opts o;
  cfg_opts(c, &o);
  memset(out, 0, sizeof *out);
  out->t = calloc((size_t)nt, sizeof(double));
  out->dE = calloc((size_t)nt, sizeof(double));
  out->dEmax = calloc((size_t)nt, sizeof(double));
  out->dq = calloc((size_t)nt, sizeof(double));
  out->dqmax = calloc((size_t)nt, sizeof(double));
  dal_state_create(sc->sys, &st);
  dal_state_set(sc->sys, st, 0.0, sc->q0, sc->v0);
  int rc = dal_make_consistent(sc->sys, st, 0.0, NULL);
  double I0 = invariant(sc, st), emax = 0.0, qmax = 0.0, t0 = cpu_now();
  for (int k = 0; k < nt && !rc; ++k) {
    rc = dal_advance(sc->sys, st, &o, times[k]);
    if (rc) {
      fprintf(stderr, "  %s/%s: %s\n", sc->name, dal_method_name(c->m), dal_state_errmsg(st));
      break;
    }
    double dE = fabs(invariant(sc, st) - I0) / sc->scale, dq = NAN;
    emax = fmax(emax, dE);
    if (sc->exact) {
      double th, thd;
      ref_pendulum(sc->q0[0], sqrt(9.8), times[k], &th, &thd);
      dq = fabs(wrap(dal_state_q(st)[0] - th));
      qmax = fmax(qmax, dq);
    }
    out->t[out->n] = times[k];
    out->dE[out->n] = dE;
    out->dEmax[out->n] = emax;
    out->dq[out->n] = dq;
    out->dqmax[out->n] = sc->exact ? qmax : NAN;
    out->n++;
  }
  out->wall = cpu_now() - t0;
  out->rc = rc;
  dal_state_destroy(st);
  return rc;
}

// CPU seconds per simulated second over a pilot stretch (median of three)
static double cost_rate(const scene *sc, const run_cfg *c, double T) {
  double r[3];
  for (int i = 0; i < 3; ++i) {
    samples s;
    run(sc, c, &T, 1, &s);
    r[i] = s.rc ? INFINITY : s.wall / T;
    samples_free(&s);
  }
  return bench_median(r, 3);
}

// the adaptive tolerance (from a list) whose cost rate is closest to `target`
static double matched_rtol(const scene *sc, run_cfg c, double target, double T) {
  static const double tols[] = {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
  double best = tols[0], bd = INFINITY;
  for (size_t i = 0; i < sizeof tols / sizeof tols[0]; ++i) {
    c.param = tols[i];
    double r = cost_rate(sc, &c, T), d = fabs(log(r / target));
    if (d < bd) {
      bd = d;
      best = tols[i];
    }
    if (r > 3 * target) break;
  }
  return best;
}

// ---------------------------------------------------------------------------------------------
// 1. long runs at matched cost: energy envelope and phase error against time

static FILE *fp_long;

static void write_samples(const scene *sc, const run_cfg *c, const samples *s) {
  char nm[64];
  cfg_name(c, nm, sizeof nm);
  for (int k = 0; k < s->n; ++k)
    fprintf(fp_long, "%s,%s,%.6g,%.4f,%.9g,%.4e,%.4e,%.4e,%.4e\n", sc->name, nm, c->param, s->wall,
            s->t[k] / sc->unit, s->dE[k], s->dEmax[k], s->dq[k], s->dqmax[k]);
  fflush(fp_long);
}

// least-squares slope of log y against log t over the samples with t >= t_from (y > 0)
static double loglog_slope(const samples *s, const double *y, double t_from) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (int k = 0; k < s->n; ++k)
    if (s->t[k] >= t_from && y[k] > 0 && isfinite(y[k])) {
      double x = log(s->t[k]), v = log(y[k]);
      sx += x;
      sy += v;
      sxx += x * x;
      sxy += x * v;
      ++n;
    }
  return n > 2 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : NAN;
}

static FILE *fp_sum;

static void long_runs(scene *sc, const run_cfg *sym, int nsym, const run_cfg *ad, int nad,
                      double periods) {
  double horizon = periods * sc->unit, *times;
  int nt = sample_times(sc->unit, horizon, quick ? 40 : 60, &times);
  fprintf(fp_sum, "\n### %s: %.0f periods (period %.4g s), invariant error / %.3g\n\n", sc->name,
          periods, sc->unit, sc->scale);
  fprintf(fp_sum,
          "| method | step or rtol | CPU s | max error first 1%% | max error at the end "
          "| growth exponent of the error envelope%s |\n|---|---|---|---|---|---|%s\n",
          sc->exact ? " | theta error at the end | growth exponent of the theta error" : "",
          sc->exact ? "---|---|" : "");
  double pilot = fmax(20.0 * sc->unit, horizon / 200.0), rate0 = 0.0;
  for (int i = 0; i < nsym + nad; ++i) {
    run_cfg c = i < nsym ? sym[i] : ad[i - nsym];
    if (i >= nsym) {
      // matched cost: the tolerance whose pilot cost rate is nearest the first symplectic run
      c.param = matched_rtol(sc, c, rate0, pilot);
    }
    samples s;
    char nm[64];
    fprintf(stderr, "  %s: %s %g over %.3g s ...\n", sc->name, cfg_name(&c, nm, sizeof nm), c.param,
            horizon);
    run(sc, &c, times, nt, &s);
    if (i == 0) rate0 = s.wall / horizon;
    write_samples(sc, &c, &s);
    double e1 = 0.0;
    for (int k = 0; k < s.n && s.t[k] <= 0.01 * horizon; ++k)
      e1 = s.dEmax[k];
    double slope = loglog_slope(&s, s.dEmax, 0.01 * horizon);
    fprintf(fp_sum, "| %s | %g | %.2f | %.2e | %.2e | %.2f", nm, c.param, s.wall, e1,
            s.n ? s.dEmax[s.n - 1] : NAN, slope);
    if (sc->exact)
      fprintf(fp_sum, " | %.2e | %.2f", s.n ? s.dq[s.n - 1] : NAN,
              loglog_slope(&s, s.dqmax, 0.01 * horizon));
    fprintf(fp_sum, " |%s\n", s.rc ? " (failed)" : "");
    fflush(fp_sum);
    samples_free(&s);
  }
  free(times);
}

// ---------------------------------------------------------------------------------------------
// 2. crossover: the horizon after which the symplectic methods are the cheaper route to a given
// accuracy of the invariant. Each configuration runs once to the measured horizon; its cost is
// its CPU time per simulated second (linear in the horizon) and its accuracy at horizon T the
// envelope at T; cost_m(T, E*) = min over the configurations of method family m whose envelope
// at T is <= E* of rate * T. Beyond the measured horizon the envelopes are extrapolated: a
// symplectic one stays at its maximum, an adaptive one grows as (T / T_h)^s with s fitted on
// the last decade (reported as "extrapolated").

static FILE *fp_cross, *fp_ccost;

typedef struct cross_run {
  run_cfg c;
  int fam; // 0 symplectic, else the adaptive family (index into the labels)
  samples s;
  double rate, growth, env_end, env_max;
} cross_run;

// envelope of run r at time T (periods), measured or extrapolated
static double env_at(const cross_run *r, double T, double Th) {
  if (r->s.rc || r->s.n == 0) return INFINITY;
  if (T > Th) return r->fam == 0 ? r->env_max : r->env_end * pow(T / Th, fmax(r->growth, 0.0));
  double e = r->s.dEmax[0];
  for (int k = 0; k < r->s.n && r->s.t[k] <= T * (1 + 1e-12); ++k)
    e = r->s.dEmax[k];
  return e;
}

static double family_cost(const cross_run *r, int nc, int fam, double T, double Th, double E,
                          int *best) {
  double c = INFINITY;
  *best = -1;
  for (int i = 0; i < nc; ++i)
    if (r[i].fam == fam && env_at(&r[i], T, Th) <= E && r[i].rate * T < c) {
      c = r[i].rate * T;
      *best = i;
    }
  return c;
}

static void crossover(scene *sc, const run_cfg *cfgs, const int *fam, int nc, const char **labels,
                      int nfam, double periods) {
  double horizon = periods * sc->unit, *times;
  int nt = sample_times(sc->unit, horizon, 20, &times);
  cross_run *r = calloc((size_t)nc, sizeof *r);
  for (int i = 0; i < nc; ++i) {
    char nm[64];
    r[i].c = cfgs[i];
    r[i].fam = fam[i];
    fprintf(stderr, "  crossover %s: %s %g\n", sc->name, cfg_name(&cfgs[i], nm, sizeof nm),
            cfgs[i].param);
    run(sc, &cfgs[i], times, nt, &r[i].s);
    samples *s = &r[i].s;
    r[i].rate = s->rc ? INFINITY : s->wall / periods; // CPU s per period
    r[i].env_end = s->n ? s->dEmax[s->n - 1] : INFINITY;
    r[i].env_max = r[i].env_end;
    r[i].growth = loglog_slope(s, s->dEmax, 0.1 * horizon);
    for (int k = 0; k < s->n; ++k)
      fprintf(fp_cross, "%s,%s,%s,%.6g,%.4e,%.9g,%.4e\n", sc->name,
              fam[i] ? labels[fam[i]] : "symplectic", nm, cfgs[i].param, r[i].rate,
              s->t[k] / sc->unit, s->dEmax[k]);
  }
  fflush(fp_cross);
  fprintf(fp_sum, "\n#### crossover, %s (measured to %.0f periods; CPU s per period: ", sc->name,
          periods);
  for (int i = 0; i < nc; ++i) {
    char nm[64];
    fprintf(fp_sum, "%s%s %g: %.2e", i ? ", " : "", cfg_name(&r[i].c, nm, sizeof nm), r[i].c.param,
            r[i].rate);
  }
  fprintf(fp_sum, ")\n\n| target invariant error |");
  for (int f = 1; f < nfam; ++f)
    fprintf(fp_sum, " symplectic cheaper than %s after (periods) |", labels[f]);
  fprintf(fp_sum, "\n|---|");
  for (int f = 1; f < nfam; ++f)
    fprintf(fp_sum, "---|");
  fprintf(fp_sum, "\n");
  static const double targets[] = {1e-4, 1e-6, 1e-8};
  // the cheapest cost of each family against the horizon, for the charts
  for (size_t ti = 0; ti < sizeof targets / sizeof targets[0]; ++ti)
    for (int f = 0; f < nfam; ++f)
      for (int k = 0; k <= 9 * 20; ++k) {
        double T = pow(10.0, k / 20.0);
        int b;
        double c = family_cost(r, nc, f, T, periods, targets[ti], &b);
        if (isfinite(c))
          fprintf(fp_ccost, "%s,%.0e,%s,%.6g,%.4e,%d\n", sc->name, targets[ti], labels[f], T, c,
                  T > periods);
      }
  fflush(fp_ccost);
  for (size_t ti = 0; ti < sizeof targets / sizeof targets[0]; ++ti) {
    double E = targets[ti];
    fprintf(fp_sum, "| %.0e |", E);
    for (int f = 1; f < nfam; ++f) {
      // on a log grid of horizons from 1 to 1e9 periods: the last change of the winner
      double cross = NAN;
      int won_at_end = 0, sym_ever = 0, bs = -1, ba = -1;
      for (int k = 0; k <= 9 * 20; ++k) {
        double T = pow(10.0, k / 20.0);
        int is, ia;
        double cs = family_cost(r, nc, 0, T, periods, E, &is);
        double ca = family_cost(r, nc, f, T, periods, E, &ia);
        int win = isfinite(cs) && cs <= ca;
        if (win && !won_at_end) cross = T;
        won_at_end = win;
        sym_ever |= isfinite(cs);
        if (T <= periods * (1 + 1e-9)) bs = is, ba = ia;
      }
      char nm1[64] = "-", nm2[64] = "-";
      if (bs >= 0) cfg_name(&r[bs].c, nm1, sizeof nm1);
      if (ba >= 0) cfg_name(&r[ba].c, nm2, sizeof nm2);
      if (!sym_ever)
        fprintf(fp_sum, " no symplectic run reaches it |");
      else if (!won_at_end)
        fprintf(fp_sum, " not before 1e9 |");
      else if (cross <= 1.0)
        fprintf(fp_sum, " from the start (%s %g vs %s %g at %.0f) |", nm1,
                bs >= 0 ? r[bs].c.param : NAN, nm2, ba >= 0 ? r[ba].c.param : NAN, periods);
      else
        fprintf(fp_sum, " %.2g%s |", cross, cross > periods ? " (extrapolated)" : "");
    }
    fprintf(fp_sum, "\n");
  }
  fflush(fp_sum);
  for (int i = 0; i < nc; ++i)
    samples_free(&r[i].s);
  free(r);
  free(times);
}

// ---------------------------------------------------------------------------------------------
// 3. where they fail

// (a) a stiff spring: two unit masses on a line, a soft spring to the wall (w = 1) and a stiff
// one between them (w_fast = sqrt(2 k) = 100); error of the slow coordinate at T = 20
static int stiff_pot(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet soft = dal_scale(dal_sq(q[0]), 0.5);
  dal_jet stiff = dal_scale(dal_sq(dal_addc(dal_sub(q[2], q[0]), -1.0)), 0.5 * 5000.0);
  *U = dal_add(soft, stiff);
  return 0;
}

static dal_system *build_stiff(void) {
  dal_builder *b = NULL;
  scn_knobs free = scn_weightless();
  int p[2], rc = scn_builder(&free, 2, &b);
  if (!rc) rc = scn_add_xy(b, "m1", 1.0, "x1", "y1", &p[0]);
  if (!rc) rc = scn_add_xy(b, "m2", 1.0, "x2", "y2", &p[1]);
  if (!rc) rc = dal_builder_add_potential_q(b, stiff_pot, NULL);
  return compile(b, rc);
}

static void fail_stiff(void) {
  FILE *fp = bench_csv_open(outdir, "sym_stiff.csv", "method,param,cpu_s,steps,error,status");
  if (!fp) return;
  dal_system *sys = build_stiff();
  dal_state *st = NULL;
  dal_state_create(sys, &st);
  double q0[4] = {1.0, 0, 2.0 + 1e-3, 0}, v0[4] = {0, 0, 0, 0}, T = 20.0, ref[4];
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_BS;
  o.rtol = o.atol = 1e-13;
  o.max_steps = 100000000;
  dal_state_set(sys, st, 0, q0, v0);
  dal_advance(sys, st, &o, T);
  memcpy(ref, dal_state_q(st), sizeof ref);
  fprintf(fp_sum,
          "\n### failure: a stiff spring (w_slow ~ 0.7, w_fast = 100), error of x1 at "
          "t = 20\n\n| method | step or rtol | CPU s | error | status |\n|---|---|---|---|---|\n");
  const dal_method ms[5] = {DAL_METHOD_RATTLE, DAL_METHOD_VARIATIONAL, DAL_METHOD_BDF,
                            DAL_METHOD_DOPRI5, DAL_METHOD_BS};
  const double hs[] = {0.004, 0.01, 0.0195, 0.0205, 0.05, 0.1};
  const double tols[] = {1e-4, 1e-6, 1e-8};
  for (int mi = 0; mi < 5; ++mi) {
    int fixed = mi < 2, np = fixed ? 6 : 3;
    for (int k = 0; k < np; ++k) {
      run_cfg c = {ms[mi], fixed ? hs[k] : tols[k], DAL_FORM_AUTO, 0};
      cfg_opts(&c, &o);
      dal_state_set(sys, st, 0, q0, v0);
      double t0 = cpu_now();
      int rc = dal_advance(sys, st, &o, T);
      double wall = cpu_now() - t0, err = fabs(dal_state_q(st)[0] - ref[0]);
      dal_stats s;
      dal_state_stats(st, &s);
      const char *status = rc                            ? dal_status_name(rc)
                           : !isfinite(err) || err > 1.0 ? "blew up"
                                                         : "ok";
      fprintf(fp, "%s,%g,%.4f,%ld,%.4e,%s\n", dal_method_name(ms[mi]), c.param, wall, s.steps, err,
              status);
      fprintf(fp_sum, "| %s | %g | %.3f | %.2e | %s |\n", dal_method_name(ms[mi]), c.param, wall,
              err, status);
    }
  }
  fclose(fp);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// (b) a drive with energy input: SICM's driven pendulum (pivot a cos(w t) vertically, a = 0.1,
// w = 2 sqrt(g)), theta error against BS at 1e-13 over time, variational vs BS at matched cost
static void fail_drive(void) {
  FILE *fp = bench_csv_open(outdir, "sym_drive.csv", "method,param,t,error,energy_change");
  if (!fp) return;
  double g = 9.8, T = quick ? 30.0 : 100.0, h = 0.01;
  dal_system *sys = build_pendulum(0, 0.1, 2 * sqrt(g));
  dal_state *ref = NULL, *a = NULL, *b = NULL;
  dal_state_create(sys, &ref);
  dal_state_create(sys, &a);
  dal_state_create(sys, &b);
  double th = 1.0, thd = 0.0;
  dal_solve_opts orf, oa, ob;
  orf = dal_default_solve_opts();
  orf.method = DAL_METHOD_BS;
  orf.rtol = orf.atol = 1e-13;
  run_cfg cv = {DAL_METHOD_VARIATIONAL, h, DAL_FORM_AUTO, 0};
  cfg_opts(&cv, &oa);
  // matched cost for BS on a pilot stretch
  scene sc = {0};
  sc.name = "drive";
  sc.sys = sys;
  sc.n = 1;
  sc.q0[0] = th;
  sc.unit = 1.0;
  sc.scale = 9.8;
  run_cfg cb = {DAL_METHOD_BS, 0, DAL_FORM_AUTO, 0};
  cb.param = matched_rtol(&sc, cb, cost_rate(&sc, &cv, 10.0), 10.0);
  cfg_opts(&cb, &ob);
  dal_state_set(sys, ref, 0, &th, &thd);
  dal_state_set(sys, a, 0, &th, &thd);
  dal_state_set(sys, b, 0, &th, &thd);
  dal_forward(sys, ref);
  dal_energies e0, e;
  dal_state_energies(ref, &e0);
  double ea_max = 0, eb_max = 0, t_sep_a = NAN, t_sep_b = NAN;
  for (int k = 1; k <= (int)(T / 0.1 + 0.5); ++k) {
    double t = 0.1 * k;
    if (dal_advance(sys, ref, &orf, t) || dal_advance(sys, a, &oa, t) ||
        dal_advance(sys, b, &ob, t))
      break;
    double r = dal_state_q(ref)[0];
    double ea = fabs(wrap(dal_state_q(a)[0] - r)), eb = fabs(wrap(dal_state_q(b)[0] - r));
    dal_state_energies(ref, &e);
    fprintf(fp, "variational,%g,%.3f,%.4e,%.4e\n", h, t, ea, (e.E - e0.E) / 9.8);
    fprintf(fp, "bs,%g,%.3f,%.4e,%.4e\n", cb.param, t, eb, (e.E - e0.E) / 9.8);
    ea_max = fmax(ea_max, ea);
    eb_max = fmax(eb_max, eb);
    if (isnan(t_sep_a) && ea > 0.1) t_sep_a = t;
    if (isnan(t_sep_b) && eb > 0.1) t_sep_b = t;
  }
  char sa[64] = "never", sb[64] = "never";
  if (!isnan(t_sep_a)) snprintf(sa, sizeof sa, "t = %.1f", t_sep_a);
  if (!isnan(t_sep_b)) snprintf(sb, sizeof sb, "t = %.1f", t_sep_b);
  fprintf(fp_sum,
          "\n### failure: a drive with energy input (SICM's driven pendulum, %g s)\n\n"
          "variational h = %g against BS at matched cost (rtol %g), theta against BS at 1e-13: "
          "the error exceeds 0.1 rad at %s (variational; max %.2e) and %s (BS; max %.2e). The "
          "energy is not conserved (the drive does work), so the bounded-energy argument does "
          "not apply, and the motion's sensitivity amplifies the O(h^2) error of a fixed step.\n",
          T, h, cb.param, sa, ea_max, sb, eb_max);
  fclose(fp);
  dal_state_destroy(ref);
  dal_state_destroy(a);
  dal_state_destroy(b);
  dal_system_destroy(sys);
}

// (c) a near-separatrix orbit: the pendulum released 1e-3 rad below the top (its energy 5e-7
// m g l below the separatrix). The period depends on the energy without bound near the
// separatrix, so the O(h^2) error of a fixed step's modified energy becomes a large period
// error; and for h w0 beyond ~0.5 the discrete map's chaotic layer around the separatrix
// (exponentially thin in 1 / (h w0)) reaches the orbit, which then goes over the top.
static void fail_separatrix(void) {
  FILE *fp = bench_csv_open(outdir, "sym_separatrix.csv", "method,param,t,theta,theta_exact");
  if (!fp) return;
  dal_system *sys = build_pendulum(0, 0, 0);
  dal_state *st = NULL;
  dal_state_create(sys, &st);
  double th0 = PI - 1e-3, v = 0.0, T = quick ? 100.0 : 400.0;
  double P = 4.0 * ref_ellip_K(pow(sin(0.5 * th0), 2)) / sqrt(9.8);
  fprintf(fp_sum,
          "\n### failure: a near-separatrix orbit (released 1e-3 rad below the top, "
          "period %.3f s, w0 = 3.13/s)\n\n| method | step or rtol | CPU s | max theta "
          "error on [0, %g] | goes over the top (first time) |\n|---|---|---|---|---|\n",
          P, T);
  run_cfg cfgs[] = {{DAL_METHOD_VARIATIONAL, 0.01, DAL_FORM_AUTO, 0},
                    {DAL_METHOD_VARIATIONAL, 0.05, DAL_FORM_AUTO, 0},
                    {DAL_METHOD_VARIATIONAL, 0.2, DAL_FORM_AUTO, 0},
                    {DAL_METHOD_VARIATIONAL4, 0.05, DAL_FORM_AUTO, 0},
                    {DAL_METHOD_BS, 1e-8, DAL_FORM_AUTO, 0},
                    {DAL_METHOD_BS, 1e-10, DAL_FORM_AUTO, 0}};
  for (size_t i = 0; i < sizeof cfgs / sizeof cfgs[0]; ++i) {
    dal_solve_opts o;
    cfg_opts(&cfgs[i], &o);
    dal_state_set(sys, st, 0, &th0, &v);
    double emax = 0.0, tover = NAN, c0 = cpu_now();
    for (int k = 1; k <= (int)(T / 0.1 + 0.5); ++k) {
      double t = 0.1 * k, th, thd;
      if (dal_advance(sys, st, &o, t)) break;
      ref_pendulum(th0, sqrt(9.8), t, &th, &thd);
      double q = dal_state_q(st)[0];
      if (isnan(tover) && fabs(q) > PI) tover = t;
      emax = fmax(emax, fabs(q - th));
      // the CSV keeps the runs the chart draws (variational h = 0.05 and 0.2), every 0.2 s
      if (cfgs[i].m == DAL_METHOD_VARIATIONAL && cfgs[i].param >= 0.05 && k % 2 == 0)
        fprintf(fp, "%s,%g,%.3f,%.6f,%.6f\n", dal_method_name(cfgs[i].m), cfgs[i].param, t, q, th);
    }
    char over[64] = "no";
    if (!isnan(tover)) snprintf(over, sizeof over, "yes (t = %.1f)", tover);
    fprintf(fp_sum, "| %s | %g | %.2f | %.2e | %s |\n", dal_method_name(cfgs[i].m), cfgs[i].param,
            cpu_now() - c0, emax, over);
  }
  fclose(fp);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// ---------------------------------------------------------------------------------------------
// 4. round-off: RK4 on q'' = -q (unit mass and stiffness: the right-hand side is exact in
// floating point) against the same recurrence in long double with compensation, for the
// library (compensated update h * (...) / 6) and for a replica of the previous update
// y + (h / 6) * (...) without compensation; RMS over initial conditions, N = 1e3 .. 1e6 steps,
// h = 1e-3, 1e-2, 1e-1. Then Bulirsch-Stoer on SICM's oscillator against the closed form.

static int unit_pot(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  *U = dal_scale(dal_add(dal_sq(q[0]), dal_sq(q[1])), 0.5);
  return 0;
}

static int sicm_pot(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  *U = dal_scale(dal_add(dal_sq(q[0]), dal_sq(q[1])), 0.5);
  return 0;
}

static double fit_slope(const double *x, const double *y, int n) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int m = 0;
  for (int i = 0; i < n; ++i)
    if (y[i] > 0) {
      sx += log(x[i]), sy += log(y[i]), sxx += log(x[i]) * log(x[i]), sxy += log(x[i]) * log(y[i]);
      ++m;
    }
  return m > 2 ? (m * sxy - sx * sy) / (m * sxx - sx * sx) : NAN;
}

static void rounding(void) {
  FILE *fp = bench_csv_open(outdir, "sym_rounding.csv", "what,h,N,rms_error,rms_over_sqrtN");
  if (!fp) return;
  dal_builder *b = NULL;
  scn_knobs free = scn_weightless();
  int p, rc = scn_builder(&free, 2, &b);
  if (!rc) rc = scn_add_xy(b, "m", 1.0, "x", "y", &p);
  if (!rc) rc = dal_builder_add_potential_q(b, unit_pot, NULL);
  dal_system *sys = compile(b, rc);
  dal_state *st = NULL;
  dal_state_create(sys, &st);
  int nic = quick ? 4 : 8, nmax = quick ? 5 : 6;
  fprintf(fp_sum,
          "\n### round-off: RK4 on q'' = -q, RMS over %d initial conditions in [-2, 2] "
          "against the same recurrence in long double (compensated)\n\n| h | steps N | "
          "library (compensated) | uncompensated (h/6) update |\n|---|---|---|---|\n",
          nic);
  const double hs[3] = {1e-3, 1e-2, 1e-1};
  double slopes[3][2];
  for (int hi = 0; hi < 3; ++hi) {
    double H = hs[hi], xs[8], yl[8], yn[8];
    int nf = 0;
    for (int e = 3; e <= nmax; ++e) {
      double N = pow(10.0, e), T = N * H, sl = 0, sn = 0;
      unsigned long long seed = 12345;
      for (int ic = 0; ic < nic; ++ic) {
        double y0[4];
        for (int i = 0; i < 4; ++i) {
          seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
          y0[i] = -2.0 + 4.0 * (double)(seed >> 11) / 9007199254740992.0;
        }
        dal_solve_opts o = dal_default_solve_opts();
        o.method = DAL_METHOD_RK4;
        o.fixed_step = H;
        o.max_steps = 100000000;
        dal_state_set(sys, st, 0, y0, y0 + 2);
        dal_advance(sys, st, &o, T);
        double ref[4], nv[4];
        scn_rk4_replica(y0, T, H, 0, ref);
        scn_rk4_replica(y0, T, H, 1, nv);
        for (int i = 0; i < 2; ++i) {
          double dl = dal_state_q(st)[i] - ref[i], dv = dal_state_qdot(st)[i] - ref[2 + i];
          sl += dl * dl + dv * dv;
          dl = nv[i] - ref[i];
          dv = nv[2 + i] - ref[2 + i];
          sn += dl * dl + dv * dv;
        }
      }
      sl = sqrt(sl / (4 * nic));
      sn = sqrt(sn / (4 * nic));
      fprintf(fp, "compensated,%g,%.0f,%.4e,%.4e\nuncompensated,%g,%.0f,%.4e,%.4e\n", H, N, sl,
              sl / sqrt(N), H, N, sn, sn / sqrt(N));
      fprintf(fp_sum, "| %g | %.0f | %.2e | %.2e |\n", H, N, sl, sn);
      xs[nf] = N, yl[nf] = sl, yn[nf] = sn, ++nf;
    }
    slopes[hi][0] = fit_slope(xs, yl, nf);
    slopes[hi][1] = fit_slope(xs, yn, nf);
  }
  fprintf(fp_sum,
          "\nGrowth exponents of the RMS in N (Brouwer's law: 0.5, systematic rounding: 1): ");
  for (int hi = 0; hi < 3; ++hi)
    fprintf(fp_sum, "%sh = %g: compensated %.2f, uncompensated %.2f", hi ? "; " : "", hs[hi],
            slopes[hi][0], slopes[hi][1]);
  fprintf(fp_sum, ".\n");
  fclose(fp);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  // Bulirsch-Stoer on SICM's oscillator (mass 2, k = 1) at t = 10 against the closed form
  b = NULL;
  rc = scn_builder(&free, 2, &b);
  if (!rc) rc = scn_add_xy(b, "m", 2.0, "x", "y", &p);
  if (!rc) rc = dal_builder_add_potential_q(b, sicm_pot, NULL);
  sys = compile(b, rc);
  dal_state_create(sys, &st);
  fprintf(fp_sum, "\nBulirsch-Stoer on SICM's oscillator (q0 = (1, 2), v0 = (3, 4)), max error at "
                  "t = 10 against the closed form:");
  const double qs[2] = {1, 2}, vs[2] = {3, 4}, w = sqrt(0.5);
  for (int k = 10; k <= 13; ++k) {
    dal_solve_opts o = dal_default_solve_opts();
    o.method = DAL_METHOD_BS;
    o.rtol = o.atol = pow(10.0, -k);
    dal_state_set(sys, st, 0, qs, vs);
    dal_advance(sys, st, &o, 10.0);
    double err = 0;
    for (int i = 0; i < 2; ++i) {
      double q = qs[i] * cos(w * 10) + vs[i] / w * sin(w * 10);
      double v = -qs[i] * w * sin(w * 10) + vs[i] * cos(w * 10);
      err = fmax(err, fmax(fabs(dal_state_q(st)[i] - q), fabs(dal_state_qdot(st)[i] - v)));
    }
    fprintf(fp_sum, "%s tol 1e-%d: %.2e", k > 10 ? "," : "", k, err);
  }
  fprintf(fp_sum, ".\n");
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// ---------------------------------------------------------------------------------------------

int main(int argc, char **argv) {
  for (int i = 1; i < argc; ++i) {
    if (strcmp(argv[i], "--quick") == 0)
      quick = 1;
    else if (strcmp(argv[i], "--full") == 0)
      quick = 0;
    else if (strcmp(argv[i], "--only") == 0 && i + 1 < argc)
      only = argv[++i];
    else if (strcmp(argv[i], "--out") == 0 && i + 1 < argc)
      outdir = argv[++i];
    else {
      fprintf(stderr, "usage: dal_bench_symplectic [--quick | --full] [--out DIR] [--only "
                      "stiff|drive|separatrix|rounding]\n");
      return 2;
    }
  }
  if (mkdir(outdir, 0775) != 0 && errno != EEXIST) {
    fprintf(stderr, "cannot create %s\n", outdir);
    return 1;
  }
  if (only) {
    fp_sum = stdout;
    if (strcmp(only, "stiff") == 0)
      fail_stiff();
    else if (strcmp(only, "drive") == 0)
      fail_drive();
    else if (strcmp(only, "separatrix") == 0)
      fail_separatrix();
    else if (strcmp(only, "rounding") == 0)
      rounding();
    else {
      fprintf(stderr, "unknown section '%s'\n", only);
      return 2;
    }
    return 0;
  }
  char path[1024];
  snprintf(path, sizeof path, "%s/sym_summary.md", outdir);
  fp_sum = fopen(path, "w");
  fp_long = bench_csv_open(outdir, "sym_longrun.csv",
                           "scene,method,param,cpu_s,t_periods,dE,dE_max,dtheta,dtheta_max");
  fp_cross = bench_csv_open(outdir, "sym_crossover.csv",
                            "scene,family,method,param,rate_s_per_s,t_periods,dE_max");
  fp_ccost = bench_csv_open(outdir, "sym_crosscost.csv",
                            "scene,target,family,t_periods,cpu_s,extrapolated");
  if (!fp_sum || !fp_long || !fp_cross || !fp_ccost) return 1;
  double t_start = bench_now();
  fprintf(fp_sum,
          "## Structure-preserving integrators: long runs (%s mode)\n\n"
          "Generated by `dal_bench_symplectic %s`; invariant errors relative to the "
          "energy scale m g l.\n",
          quick ? "quick" : "full", quick ? "--quick" : "--full");

  scene pend, ring, cring, dbl;
  scene_pendulum(&pend);
  scene_ring(&ring, 0);
  scene_ring(&cring, 1);
  scene_double(&dbl);
  double P = pend.unit, Pr = ring.unit;
  const run_cfg dp5 = {DAL_METHOD_DOPRI5, 0, DAL_FORM_AUTO, 0}, bsm = {DAL_METHOD_BS, 0, 0, 0};
  const run_cfg ggl = {DAL_METHOD_BDF, 0, DAL_FORM_GGL, 0},
                bsp = {DAL_METHOD_BS, 0, DAL_FORM_INDEX1, 1};
  // long runs; the adaptive methods at the cost of the first symplectic run
  {
    run_cfg sym[] = {{DAL_METHOD_VARIATIONAL, P / 64, 0, 0},
                     {DAL_METHOD_VARIATIONAL4, P / 64, 0, 0}};
    run_cfg ad[] = {dp5, bsm};
    long_runs(&pend, sym, 2, ad, 2, quick ? 1e4 : 1e5);
  }
  {
    run_cfg sym[] = {{DAL_METHOD_VARIATIONAL, Pr / 64, 0, 0}};
    run_cfg ad[] = {dp5, bsm};
    long_runs(&ring, sym, 1, ad, 2, quick ? 1e3 : 1e4);
  }
  {
    run_cfg sym[] = {{DAL_METHOD_RATTLE, Pr / 64, 0, 0}, {DAL_METHOD_RATTLE4, Pr / 64, 0, 0}};
    run_cfg ad[] = {ggl, bsp};
    long_runs(&cring, sym, 2, ad, 2, quick ? 1e3 : 1e4);
  }
  {
    run_cfg sym[] = {{DAL_METHOD_RATTLE, 0.005, 0, 0}, {DAL_METHOD_RATTLE4, 0.01, 0, 0}};
    run_cfg ad[] = {ggl, bsp};
    long_runs(&dbl, sym, 2, ad, 2, quick ? 1e3 : 1e4);
  }
  // crossovers
  {
    const char *labels[] = {"symplectic", "dopri5", "bs"};
    run_cfg c[] = {{DAL_METHOD_VARIATIONAL, 1.0 / 64, 0, 0},
                   {DAL_METHOD_VARIATIONAL, 1.0 / 256, 0, 0},
                   {DAL_METHOD_VARIATIONAL4, 1.0 / 32, 0, 0},
                   {DAL_METHOD_VARIATIONAL4, 1.0 / 64, 0, 0},
                   {DAL_METHOD_VARIATIONAL4, 1.0 / 128, 0, 0},
                   {DAL_METHOD_VARIATIONAL6, 1.0 / 16, 0, 0},
                   {DAL_METHOD_VARIATIONAL6, 1.0 / 32, 0, 0},
                   {DAL_METHOD_VARIATIONAL6, 1.0 / 64, 0, 0},
                   {DAL_METHOD_DOPRI5, 1e-6, 0, 0},
                   {DAL_METHOD_DOPRI5, 1e-8, 0, 0},
                   {DAL_METHOD_DOPRI5, 1e-10, 0, 0},
                   {DAL_METHOD_BS, 1e-6, 0, 0},
                   {DAL_METHOD_BS, 1e-8, 0, 0},
                   {DAL_METHOD_BS, 1e-10, 0, 0},
                   {DAL_METHOD_BS, 1e-12, 0, 0}};
    int fam[] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 2, 2, 2, 2}, nc = 15;
    run_cfg cp[15], cr[15];
    for (int i = 0; i < nc; ++i) {
      cp[i] = cr[i] = c[i];
      if (fam[i] == 0) cp[i].param *= P, cr[i].param *= Pr;
    }
    crossover(&pend, cp, fam, nc, labels, 3, quick ? 1e3 : 1e4);
    crossover(&ring, cr, fam, nc, labels, 3, quick ? 1e3 : 1e4);
  }
  {
    const char *labels[] = {"symplectic", "bdf-ggl", "bs-proj"};
    run_cfg c[] = {
        {DAL_METHOD_RATTLE, Pr / 32, 0, 0},        {DAL_METHOD_RATTLE, Pr / 128, 0, 0},
        {DAL_METHOD_RATTLE, Pr / 512, 0, 0},       {DAL_METHOD_RATTLE4, Pr / 32, 0, 0},
        {DAL_METHOD_RATTLE4, Pr / 64, 0, 0},       {DAL_METHOD_RATTLE4, Pr / 128, 0, 0},
        {DAL_METHOD_RATTLE6, Pr / 32, 0, 0},       {DAL_METHOD_RATTLE6, Pr / 64, 0, 0},
        {DAL_METHOD_BDF, 1e-6, DAL_FORM_GGL, 0},   {DAL_METHOD_BDF, 1e-8, DAL_FORM_GGL, 0},
        {DAL_METHOD_BDF, 1e-10, DAL_FORM_GGL, 0},  {DAL_METHOD_BS, 1e-6, DAL_FORM_INDEX1, 1},
        {DAL_METHOD_BS, 1e-8, DAL_FORM_INDEX1, 1}, {DAL_METHOD_BS, 1e-10, DAL_FORM_INDEX1, 1}};
    int fam[] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 2, 2, 2};
    crossover(&cring, c, fam, 14, labels, 3, quick ? 1e2 : 1e3);
    const double hd[8] = {0.01, 0.0025, 0.000625, 0.02, 0.01, 0.005, 0.02, 0.01};
    for (int i = 0; i < 8; ++i)
      c[i].param = hd[i];
    crossover(&dbl, c, fam, 14, labels, 3, quick ? 1e2 : 1e3);
  }
  fail_stiff();
  fail_drive();
  fail_separatrix();
  rounding();
  fprintf(fp_sum, "\nTotal run time %.0f s.\n", bench_now() - t_start);
  fclose(fp_sum);
  fclose(fp_long);
  fclose(fp_cross);
  fclose(fp_ccost);
  dal_system_destroy(pend.sys);
  dal_system_destroy(ring.sys);
  dal_system_destroy(cring.sys);
  dal_system_destroy(dbl.sys);
  fprintf(stderr, "dal_bench_symplectic: results in %s (%.0f s)\n", outdir, bench_now() - t_start);
  return 0;
}
