// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// dal_bench: work-precision, library overhead, cost growth and failure studies -> CSV files.
//
// Usage: dal_bench [--quick | --full] [--out DIR] [experiment ...]
// Experiments: smoke wp overhead cost loops drift energy daetol stiff singular (default: all
// but smoke); and single runs for instruction counting: ir, irloop, irroute (see below).
// Every CSV goes to DIR (default bench/results). Wall times are medians of repeated runs on
// the monotonic clock; each run starts from a fresh integrator (state reset).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "hand.h"
#include "ref.h"
#include "scenes.h"
#include "support/scenes.h"
#include "util.h"

#define PI 3.14159265358979323846

// run-wide settings
typedef struct bench_cfg {
  int quick;       // quick mode: fewer tolerances, sizes and repeats
  const char *out; // output directory
  double budget;   // seconds of repeated runs per configuration
  int min_reps;    // repeats at least this often (unless a run is long)
  int max_reps;    // and at most this often
  double long_run; // a single run longer than this is not repeated
  long max_steps;  // step budget of one run (a run that needs more is reported failed)
  double slow_run; // after a run this slow (s), tighter tolerances of its combination are skipped
  FILE *failures;  // failures.csv
} bench_cfg;

// the outcome of one configuration
typedef struct run_res {
  int status;
  double wall; // median wall time (s)
  long rhs, steps;
  double err;
  char msg[200];
} run_res;

// ---------------------------------------------------------------- small helpers

// a message safe for one CSV field: commas and quotes replaced, newlines cut
static void csv_clean(char *s) {
  for (char *p = s; *p; ++p) {
    if (*p == ',' || *p == '"') *p = ';';
    if (*p == '\n' || *p == '\r') *p = ' ';
  }
}

static void log_failure(const bench_cfg *cfg, const char *experiment, const char *scene,
                        const char *form, const char *method, double rtol, const run_res *r) {
  char msg[sizeof r->msg];
  snprintf(msg, sizeof msg, "%s", r->msg);
  csv_clean(msg);
  if (cfg->failures)
    fprintf(cfg->failures, "%s,%s,%s,%s,%.0e,%s,%s\n", experiment, scene, form, method, rtol,
            dal_status_name(r->status), msg);
  fprintf(stderr, "  [%s %s %s %s rtol %.0e] %s: %s\n", experiment, scene, form, method, rtol,
          dal_status_name(r->status), msg);
}

// how often to repeat a configuration whose first run took w seconds
static int reps_for(const bench_cfg *cfg, double w) {
  if (w > cfg->long_run) return 1;
  int n = w > 0 ? (int)(cfg->budget / w) : cfg->max_reps;
  if (n < cfg->min_reps) n = cfg->min_reps;
  if (n > cfg->max_reps) n = cfg->max_reps;
  return n;
}

// ---------------------------------------------------------------- one library run

// reset the model, advance to t1 under the clock; positions of the compared particles to r
static int lib_once(bench_model *m, const dal_solve_opts *o, double t1, double *r, int npd,
                    run_res *res) {
  double t0 = bench_now();
  int rc = scene_model_reset(m);
  if (!rc) rc = dal_advance(m->sys, m->st, o, t1);
  res->wall = bench_now() - t0;
  dal_stats s;
  memset(&s, 0, sizeof s);
  dal_state_stats(m->st, &s);
  res->rhs = s.rhs_evals;
  res->steps = s.steps;
  res->status = rc;
  if (rc)
    snprintf(res->msg, sizeof res->msg, "%s", dal_state_errmsg(m->st));
  else
    res->msg[0] = 0;
  const double *pos = dal_state_positions(m->st);
  for (int i = 0; i < npd; ++i)
    r[i] = rc ? NAN : pos[i];
  return rc;
}

// a library configuration: median of repeated runs, error against ref (npd values)
static void lib_measure(const bench_cfg *cfg, bench_model *m, const dal_solve_opts *o, double t1,
                        const double *ref, int npd, run_res *res) {
  double *r = malloc((size_t)npd * sizeof(double)), walls[64];
  if (!r) {
    res->status = DAL_E_NOMEM;
    return;
  }
  lib_once(m, o, t1, r, npd, res);
  res->err = res->status ? NAN : bench_maxdiff(r, ref, npd);
  walls[0] = res->wall;
  int n = res->status ? 1 : reps_for(cfg, res->wall);
  for (int i = 1; i < n; ++i) {
    run_res tmp;
    lib_once(m, o, t1, r, npd, &tmp);
    walls[i] = tmp.wall;
  }
  res->wall = bench_median(walls, n);
  free(r);
}

// the tolerance the library hands to SUNDIALS for a requested rtol: it scales the request
// per method so that the achieved global error tracks it (the method rows of
// src/integrate/methods.c, mirrored here so that both sides take the same steps; overhead.csv
// checks the rhs counts)
static double hand_tol(dal_method m, double rtol) {
  double c = m == DAL_METHOD_DOPRI5       ? 0.01
             : m == DAL_METHOD_FEHLBERG78 ? 0.01
             : m == DAL_METHOD_ADAMS      ? 0.001
             : m == DAL_METHOD_BDF        ? 0.0001
                                          : 1.0;
  return fmax(c * rtol, 1e-15);
}

// one hand-written run from y0 (2N); positions to r
static int hand_once(hand_chain *ch, const double *y0, double *y, dal_method meth, double rtol,
                     double t1, double *r, run_res *res) {
  const long max_steps = 5000000;
  int n = 2 * ch->N;
  hand_stats hs;
  double t0 = bench_now();
  memcpy(y, y0, (size_t)n * sizeof(double));
  double tol = hand_tol(meth, rtol);
  int rc = hand_integrate(hand_chain_rhs_dense, ch, n, y, 0.0, t1, meth, tol, tol, max_steps, &hs);
  res->wall = bench_now() - t0;
  res->rhs = hs.rhs_evals;
  res->steps = hs.steps;
  res->status = rc ? DAL_E_SOLVER : DAL_OK;
  if (rc)
    snprintf(res->msg, sizeof res->msg, "SUNDIALS returned %d", rc);
  else
    res->msg[0] = 0;
  hand_chain_positions(ch, y, r);
  return rc;
}

static void hand_measure(const bench_cfg *cfg, hand_chain *ch, const double *y0, dal_method meth,
                         double rtol, double t1, const double *ref, run_res *res) {
  int n = 2 * ch->N;
  double *y = malloc((size_t)n * sizeof(double)), *r = malloc((size_t)n * sizeof(double));
  double walls[64];
  if (!y || !r) {
    free(y);
    free(r);
    res->status = DAL_E_NOMEM;
    return;
  }
  hand_once(ch, y0, y, meth, rtol, t1, r, res);
  res->err = res->status ? NAN : bench_maxdiff(r, ref, n);
  walls[0] = res->wall;
  int reps = res->status ? 1 : reps_for(cfg, res->wall);
  for (int i = 1; i < reps; ++i) {
    run_res tmp;
    hand_once(ch, y0, y, meth, rtol, t1, r, &tmp);
    walls[i] = tmp.wall;
  }
  res->wall = bench_median(walls, reps);
  free(y);
  free(r);
}

// ---------------------------------------------------------------- work-precision

static const dal_method ode_methods[] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_BS,
                                         DAL_METHOD_ADAMS,  DAL_METHOD_BDF,        DAL_METHOD_RK4};
static const dal_method hand_methods[] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78,
                                          DAL_METHOD_ADAMS, DAL_METHOD_BDF};
#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

// which methods a redundant formulation is run with
static int dae_methods(bench_form f, dal_method *out) {
  int n = 0;
  switch (f) {
  case BF_GGL:
  case BF_INDEX3:
    out[n++] = DAL_METHOD_BDF;
    break;
  case BF_INDEX1:
    out[n++] = DAL_METHOD_BDF;
    out[n++] = DAL_METHOD_DOPRI5;
    break;
  case BF_INDEX1_BAUMGARTE:
    out[n++] = DAL_METHOD_DOPRI5;
    out[n++] = DAL_METHOD_ADAMS;
    break;
  case BF_INDEX1_PROJ:
    out[n++] = DAL_METHOD_DOPRI5;
    out[n++] = DAL_METHOD_FEHLBERG78;
    out[n++] = DAL_METHOD_BS;
    out[n++] = DAL_METHOD_ADAMS;
    break;
  default:
    break;
  }
  return n;
}

static void wp_row(FILE *fp, const char *scene, const char *form, const char *meth, double rtol,
                   const run_res *r) {
  fprintf(fp, "%s,%s,%s,%.0e,%.6e,%ld,%ld,%.6e\n", scene, form, meth, rtol, r->wall, r->rhs,
          r->steps, r->err);
  fflush(fp);
}

static void wp_scene(const bench_cfg *cfg, const bench_scene *sc, FILE *fp, FILE *refs) {
  int npd = scene_np(sc) * scene_dim(sc);
  double *ref = malloc((size_t)npd * sizeof(double)), agree;
  char how[160], err[400];
  if (!ref) return;
  double t0 = bench_now();
  int rc = scene_reference(sc, ref, &agree, how, sizeof how);
  fprintf(stderr, "wp %s: reference (%s) in %.1f s, agreement %.2e\n", sc->name, how,
          bench_now() - t0, agree);
  fprintf(refs, "%s,%g,%.3e,%s\n", sc->name, sc->t1, agree, how);
  if (rc) {
    free(ref);
    return;
  }
  static const double quick_tols[] = {1e-3, 1e-6, 1e-9, 1e-12};
  static const double full_tols[] = {1e-3, 1e-4,  1e-5,  1e-6,  1e-7, 1e-8,
                                     1e-9, 1e-10, 1e-11, 1e-12, 1e-13};
  const double *tols = cfg->quick ? quick_tols : full_tols;
  int ntol = cfg->quick ? COUNT(quick_tols) : COUNT(full_tols);
  // minimal coordinates through the library
  bench_model m;
  rc = scene_model(sc, 0, &m, err, sizeof err);
  if (rc) fprintf(stderr, "  cannot build %s: %s\n", sc->name, err);
  for (int mi = 0; !rc && mi < COUNT(ode_methods); ++mi)
    for (int ti = 0; ti < ntol; ++ti) {
      dal_solve_opts o;
      bench_opts(&o, BF_ODE, ode_methods[mi], tols[ti]);
      o.max_steps = cfg->max_steps;
      run_res r;
      lib_measure(cfg, &m, &o, sc->t1, ref, npd, &r);
      if (r.status == DAL_E_UNSUPPORTED) break;
      if (r.status)
        log_failure(cfg, "wp", sc->name, "ode", dal_method_name(o.method), tols[ti], &r);
      wp_row(fp, sc->name, "ode", dal_method_name(o.method), tols[ti], &r);
      // tighter tolerances would cost more still
      if (r.status == DAL_E_MAXSTEPS || r.wall > cfg->slow_run) break;
    }
  if (!rc) scene_model_free(&m);
  // the hand-written twin
  if (scene_has_hand(sc)) {
    double *y0 = malloc(2 * (size_t)sc->N * sizeof(double));
    hand_chain *ch = y0 ? scene_hand_chain(sc, y0) : NULL;
    for (int mi = 0; ch && mi < COUNT(hand_methods); ++mi)
      for (int ti = 0; ti < ntol; ++ti) {
        run_res r;
        hand_measure(cfg, ch, y0, hand_methods[mi], tols[ti], sc->t1, ref, &r);
        if (r.status)
          log_failure(cfg, "wp", sc->name, "handwritten", dal_method_name(hand_methods[mi]),
                      tols[ti], &r);
        wp_row(fp, sc->name, "handwritten", dal_method_name(hand_methods[mi]), tols[ti], &r);
      }
    hand_chain_destroy(ch);
    free(y0);
  }
  // redundant coordinates
  rc = scene_model(sc, 1, &m, err, sizeof err);
  if (rc && rc != DAL_E_UNSUPPORTED)
    fprintf(stderr, "  cannot build redundant %s: %s\n", sc->name, err);
  for (int f = BF_GGL; !rc && f <= BF_INDEX3; ++f) {
    dal_method meths[4];
    int nm = dae_methods((bench_form)f, meths);
    for (int mi = 0; mi < nm; ++mi)
      for (int ti = 0; ti < ntol; ++ti) {
        dal_solve_opts o;
        bench_opts(&o, (bench_form)f, meths[mi], tols[ti]);
        o.max_steps = cfg->max_steps;
        run_res r;
        lib_measure(cfg, &m, &o, sc->t1, ref, npd, &r);
        if (r.status)
          log_failure(cfg, "wp", sc->name, bench_form_name((bench_form)f),
                      dal_method_name(meths[mi]), tols[ti], &r);
        if (r.status == DAL_E_UNSUPPORTED) break;
        wp_row(fp, sc->name, bench_form_name((bench_form)f), dal_method_name(meths[mi]), tols[ti],
               &r);
        if (r.status == DAL_E_MAXSTEPS || r.wall > cfg->slow_run) break;
      }
  }
  if (!rc) scene_model_free(&m);
  free(ref);
}

static void exp_wp(const bench_cfg *cfg) {
  FILE *fp = bench_csv_open(cfg->out, "work_precision.csv",
                            "scene,formulation,method,rtol,wall_s,rhs_evals,steps,err");
  FILE *refs = bench_csv_open(cfg->out, "references.csv", "scene,t1,agreement,reference");
  if (!fp || !refs) {
    if (fp) fclose(fp);
    if (refs) fclose(refs);
    return;
  }
  bench_scene sc;
  scene_kind kinds[] = {SC_HO2D, SC_PENDULUM, SC_RING, SC_DRIVEN, SC_DOUBLE};
  for (int i = 0; i < COUNT(kinds); ++i) {
    scene_init(&sc, kinds[i], 1, 0);
    wp_scene(cfg, &sc, fp, refs);
  }
  int chains_quick[] = {8}, chains_full[] = {4, 8, 32};
  int nch = cfg->quick ? COUNT(chains_quick) : COUNT(chains_full);
  for (int i = 0; i < nch; ++i) {
    scene_init(&sc, SC_CHAIN, cfg->quick ? chains_quick[i] : chains_full[i], 0);
    wp_scene(cfg, &sc, fp, refs);
  }
  fclose(fp);
  fclose(refs);
}

// ---------------------------------------------------------------- overhead vs hand-written

// library and hand-written chain side by side, runs interleaved so that both see the same
// machine load; the ratio of medians is the library's modelling overhead
static void exp_overhead(const bench_cfg *cfg) {
  FILE *fp = bench_csv_open(cfg->out, "overhead.csv",
                            "N,method,rtol,wall_lib_s,wall_hand_s,ratio,rhs_lib,rhs_hand,"
                            "steps_lib,steps_hand,err_lib,err_hand,ratio_per_rhs,pairs,"
                            "ratio_min,ratio_max");
  if (!fp) return;
  static const double quick_tols[] = {1e-8}, full_tols[] = {1e-6, 1e-8, 1e-10};
  const double *tols = cfg->quick ? quick_tols : full_tols;
  int ntol = cfg->quick ? COUNT(quick_tols) : COUNT(full_tols);
  const double t1 = 2.0;
  for (int N = 1; N <= 32; N *= 2) {
    bench_scene sc;
    scene_init(&sc, SC_CHAIN, N, t1);
    int npd = 2 * N;
    double *ref = malloc((size_t)npd * sizeof(double)), agree;
    double *y0 = malloc((size_t)npd * sizeof(double)), *y = malloc((size_t)npd * sizeof(double));
    double *r = malloc((size_t)npd * sizeof(double));
    char how[160], err[400];
    bench_model m;
    hand_chain *ch = y0 ? scene_hand_chain(&sc, y0) : NULL;
    int rc =
        (ref && y && r && ch) ? scene_reference(&sc, ref, &agree, how, sizeof how) : DAL_E_NOMEM;
    if (!rc) rc = scene_model(&sc, 0, &m, err, sizeof err);
    for (int mi = 0; !rc && mi < COUNT(hand_methods); ++mi)
      for (int ti = 0; ti < ntol; ++ti) {
        dal_solve_opts o;
        bench_opts(&o, BF_ODE, hand_methods[mi], tols[ti]);
        run_res rl, rh;
        double wl[64], wh[64];
        lib_once(&m, &o, t1, r, npd, &rl);
        rl.err = rl.status ? NAN : bench_maxdiff(r, ref, npd);
        // the comparison holds only at the same local tolerance (the same steps): the
        // library's calibration factors (integrate/methods.c) and hand_tol must agree
        dal_stats used;
        dal_state_stats(m.st, &used);
        if (!rl.status &&
            fabs(used.rtol_used - hand_tol(o.method, tols[ti])) > 1e-12 * used.rtol_used) {
          fprintf(stderr,
                  "overhead: %s runs at local tolerance %g, the hand-written chain at %g: "
                  "update hand_tol in bench/bench.c\n",
                  dal_method_name(o.method), used.rtol_used, hand_tol(o.method, tols[ti]));
          exit(1);
        }
        hand_once(ch, y0, y, hand_methods[mi], tols[ti], t1, r, &rh);
        rh.err = rh.status ? NAN : bench_maxdiff(r, ref, npd);
        if (rl.status) {
          log_failure(cfg, "overhead", sc.name, "ode", dal_method_name(o.method), tols[ti], &rl);
          continue;
        }
        // interleaved repeats, at least 5 pairs
        int reps = reps_for(cfg, rl.wall + rh.wall);
        if (reps < 5) reps = 5;
        for (int i = 0; i < reps; ++i) {
          run_res tmp;
          lib_once(&m, &o, t1, r, npd, &tmp);
          wl[i] = tmp.wall;
          hand_once(ch, y0, y, hand_methods[mi], tols[ti], t1, r, &tmp);
          wh[i] = tmp.wall;
        }
        // the spread: the ratio of each interleaved pair (both runs saw the same load)
        double lo = INFINITY, hi = 0;
        for (int i = 0; i < reps; ++i) {
          double q = wl[i] / wh[i];
          lo = q < lo ? q : lo;
          hi = q > hi ? q : hi;
        }
        double a = bench_median(wl, reps), b = bench_median(wh, reps);
        fprintf(fp, "%d,%s,%.0e,%.6e,%.6e,%.4f,%ld,%ld,%ld,%ld,%.3e,%.3e,%.4f,%d,%.4f,%.4f\n", N,
                dal_method_name(o.method), tols[ti], a, b, a / b, rl.rhs, rh.rhs, rl.steps,
                rh.steps, rl.err, rh.err, (a / (double)rl.rhs) / (b / (double)rh.rhs), reps, lo,
                hi);
        fflush(fp);
        fprintf(stderr,
                "overhead N=%d %s rtol %.0e: lib %.3g s hand %.3g s ratio %.2f "
                "(rhs %ld vs %ld)\n",
                N, dal_method_name(o.method), tols[ti], a, b, a / b, rl.rhs, rh.rhs);
      }
    if (!rc) scene_model_free(&m);
    hand_chain_destroy(ch);
    free(ref);
    free(y0);
    free(y);
    free(r);
  }
  fclose(fp);
}

// ---------------------------------------------------------------- cost growth

typedef struct cost_pt {
  int N;
  double w;
} cost_pt;

// least-squares slope of log w against log N over points with N >= nmin
static double fit_exponent(const cost_pt *p, int n, int nmin, int *used) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int k = 0;
  for (int i = 0; i < n; ++i) {
    if (p[i].N < nmin || !(p[i].w > 0)) continue;
    double x = log((double)p[i].N), yv = log(p[i].w);
    sx += x;
    sy += yv;
    sxx += x * x;
    sxy += x * yv;
    ++k;
  }
  *used = k;
  if (k < 2) return NAN;
  return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

// horizon of the cost-growth runs (the same for every formulation at a given N)
static double cost_t1(int N) {
  return N <= 16 ? 2.0 : N <= 128 ? 0.5 : N <= 512 ? 0.2 : N <= 1024 ? 0.1 : 0.05;
}

// cost growth of the chain: wall time per simulated second against N. The requested
// tolerances differ per formulation so that the achieved errors are alike (about 1e-8 to
// 1e-7; IDA's error is 100-1000x its tolerance, the library's ODE path tightens its own).
static void exp_cost(const bench_cfg *cfg) {
  FILE *fp =
      bench_csv_open(cfg->out, "cost_growth.csv", "formulation,method,N,rtol,wall_s_per_sim_s,err");
  FILE *fit = bench_csv_open(cfg->out, "cost_fit.csv",
                             "formulation,method,rtol,exponent,n_points,N_min,N_max");
  if (!fp || !fit) {
    if (fp) fclose(fp);
    if (fit) fclose(fit);
    return;
  }
  int nmax_dense = cfg->quick ? 128 : 1024, nmax_sparse = cfg->quick ? 1024 : 8192;
  int nmax_tri = cfg->quick ? 4096 : 16384;
  // ode: the library's automatic route (the articulated-body recursion for the chain);
  // ode-dense: the same system forced to assemble M and factor it (the route before)
  enum { C_ODE, C_ODED, C_GGL, C_HAND, C_TRI, C_NUM };
  const char *fname[C_NUM] = {"ode", "ode-dense", "ggl", "handwritten", "handwritten-tridiag"};
  dal_method fmeth[C_NUM] = {DAL_METHOD_ADAMS, DAL_METHOD_ADAMS, DAL_METHOD_BDF, DAL_METHOD_ADAMS,
                             DAL_METHOD_ADAMS};
  double frtol[C_NUM] = {1e-6, 1e-6, 1e-8, 1e-6, 1e-6};
  int fmax[C_NUM] = {nmax_tri, nmax_dense, nmax_sparse, nmax_dense, nmax_tri};
  cost_pt pts[C_NUM][20];
  int npts[C_NUM] = {0, 0, 0, 0, 0};
  for (int N = 1; N <= nmax_tri; N *= 2) {
    bench_scene sc;
    double t1 = cost_t1(N);
    scene_init(&sc, SC_CHAIN, N, t1);
    int npd = 2 * N;
    double *ref = malloc((size_t)npd * sizeof(double)), agree;
    char how[160], err[400];
    if (!ref) break;
    double tr = bench_now();
    agree = NAN;
    int rc = N <= 64 ? scene_reference(&sc, ref, &agree, how, sizeof how)
                     : scene_reference_fast(&sc, ref);
    fprintf(stderr, "cost N=%d t1=%g: reference in %.1f s (agreement %.1e)\n", N, t1,
            bench_now() - tr, agree);
    for (int f = 0; !rc && f < C_NUM; ++f) {
      if (N > fmax[f]) continue;
      run_res r;
      memset(&r, 0, sizeof r);
      if (f == C_ODE || f == C_ODED || f == C_GGL) {
        bench_model m;
        int brc =
            scene_model_route(&sc, f == C_GGL, f == C_ODED ? DAL_DYNAMICS_DENSE : DAL_DYNAMICS_AUTO,
                              &m, err, sizeof err);
        if (brc) {
          if (brc != DAL_E_UNSUPPORTED) fprintf(stderr, "  cannot build: %s\n", err);
          continue;
        }
        dal_solve_opts o;
        bench_opts(&o, f == C_GGL ? BF_GGL : BF_ODE, fmeth[f], frtol[f]);
        if (f == C_GGL) o.linsol = DAL_LINSOL_KLU;
        o.max_steps = cfg->max_steps;
        lib_measure(cfg, &m, &o, t1, ref, npd, &r);
        scene_model_free(&m);
      } else {
        double *y0 = malloc((size_t)npd * sizeof(double));
        hand_chain *ch = y0 ? scene_hand_chain(&sc, y0) : NULL;
        if (!ch) {
          free(y0);
          continue;
        }
        if (f == C_HAND) {
          hand_measure(cfg, ch, y0, fmeth[f], frtol[f], t1, ref, &r);
        } else {
          // the O(N) tension form
          double *y = malloc((size_t)npd * sizeof(double)),
                 *rr = malloc((size_t)npd * sizeof(double));
          double walls[64];
          int reps = 0;
          for (; y && rr && reps < cfg->max_reps; ++reps) {
            hand_stats hs;
            memcpy(y, y0, (size_t)npd * sizeof(double));
            double t0 = bench_now();
            double tol = hand_tol(fmeth[f], frtol[f]);
            r.status = hand_integrate(hand_chain_rhs_tridiag, ch, npd, y, 0.0, t1, fmeth[f], tol,
                                      tol, 5000000, &hs);
            walls[reps] = bench_now() - t0;
            r.rhs = hs.rhs_evals;
            r.steps = hs.steps;
            if (reps + 1 >= reps_for(cfg, walls[0])) {
              ++reps;
              break;
            }
          }
          if (y && rr) {
            hand_chain_positions(ch, y, rr);
            r.err = r.status ? NAN : bench_maxdiff(rr, ref, npd);
            r.wall = bench_median(walls, reps);
          }
          free(y);
          free(rr);
        }
        hand_chain_destroy(ch);
        free(y0);
      }
      if (r.status) {
        log_failure(cfg, "cost", sc.name, fname[f], dal_method_name(fmeth[f]), frtol[f], &r);
        continue;
      }
      fprintf(fp, "%s,%s,%d,%.0e,%.6e,%.3e\n", fname[f], dal_method_name(fmeth[f]), N, frtol[f],
              r.wall / t1, r.err);
      fflush(fp);
      fprintf(stderr, "  %-20s N=%5d: %.3e s per simulated s, err %.2e, %ld steps\n", fname[f], N,
              r.wall / t1, r.err, r.steps);
      pts[f][npts[f]].N = N;
      pts[f][npts[f]].w = r.wall / t1;
      ++npts[f];
    }
    free(ref);
  }
  // fitted exponents over N >= 16 and over N >= 128 (the range of the O(N) target)
  for (int f = 0; f < C_NUM; ++f)
    for (int r = 0; r < 2; ++r) {
      int used, nmin = r ? 128 : 16;
      double e = fit_exponent(pts[f], npts[f], nmin, &used);
      if (r && used < 2) continue;
      fprintf(fit, "%s,%s,%.0e,%.3f,%d,%d,%d\n", fname[f], dal_method_name(fmeth[f]), frtol[f], e,
              used, nmin, npts[f] ? pts[f][npts[f] - 1].N : 0);
    }
  // crossovers (log interpolation): the first N from which the first of a pair is cheaper than
  // the second: the sparse DAE than the library's ODE, the recursion than the dense assembly
  // (NaN: not in the measured range)
  int pairs[2][2] = {{C_GGL, C_ODE}, {C_ODE, C_ODED}};
  const char *pname[2] = {"ggl-vs-ode", "ode-vs-ode-dense"};
  for (int q = 0; q < 2; ++q) {
    int a = pairs[q][0], b = pairs[q][1];
    double cross = NAN;
    for (int i = 1; i < npts[b]; ++i) {
      int N0 = pts[b][i - 1].N, N1 = pts[b][i].N;
      double d0 = NAN, d1 = NAN;
      for (int j = 0; j < npts[a]; ++j) {
        if (pts[a][j].N == N0) d0 = log(pts[a][j].w / pts[b][i - 1].w);
        if (pts[a][j].N == N1) d1 = log(pts[a][j].w / pts[b][i].w);
      }
      if (i == 1 && d0 <= 0) {
        cross = N0;
        break;
      }
      if (d0 > 0 && d1 <= 0) {
        double x = log((double)N0) + (log((double)N1) - log((double)N0)) * d0 / (d0 - d1);
        cross = exp(x);
        break;
      }
    }
    fprintf(fit, "crossover,%s,0,%.1f,0,0,0\n", pname[q], cross);
  }
  fclose(fp);
  fclose(fit);
}

// ---------------------------------------------------------------- long runs: drift, energy

typedef struct mon_ctx {
  FILE *fp;
  const char *form, *meth;
  double rtol, E0;
  int energy; // 1: energy rows, 0: drift rows
  int first;
  double runmax; // largest |phi| so far
} mon_ctx;

static int long_monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  mon_ctx *c = ctx;
  dal_energies en;
  dal_state_energies(st, &en);
  if (c->first) {
    c->E0 = en.E;
    c->first = 0;
  }
  double t = dal_state_time(st);
  if (c->energy) {
    fprintf(c->fp, "%s,%s,%.0e,%.6g,%.6e\n", c->form, c->meth, c->rtol, t,
            fabs(en.E - c->E0) / fabs(c->E0));
  } else {
    int mrows = dal_system_nconstraints(sys);
    const double *phi = dal_state_phi(st), *phid = dal_state_phidot(st);
    double a = 0, b = 0;
    for (int i = 0; i < mrows; ++i) {
      if (fabs(phi[i]) > a) a = fabs(phi[i]);
      if (fabs(phid[i]) > b) b = fabs(phid[i]);
    }
    if (a > c->runmax) c->runmax = a;
    fprintf(c->fp, "%s,%s,%.0e,%.6g,%.6e,%.6e,%.6e\n", c->form, c->meth, c->rtol, t, a, b,
            c->runmax);
  }
  return 0;
}

// evolve one long run with a monitor; logs a failure
static void long_run(const bench_cfg *cfg, const char *what, bench_model *m, bench_form f,
                     dal_method meth, double rtol, double t1, double dt, FILE *fp, int energy) {
  dal_solve_opts o;
  bench_opts(&o, f, meth, rtol);
  if (meth == DAL_METHOD_RK4) o.fixed_step = 1e-3;
  o.max_steps = cfg->max_steps;
  mon_ctx c = {fp, bench_form_name(f), dal_method_name(meth), rtol, 0.0, energy, 1, 0.0};
  double t0 = bench_now();
  int rc = scene_model_reset(m);
  if (!rc) rc = dal_evolve(m->sys, m->st, &o, t1, dt, long_monitor, &c);
  fprintf(stderr, "%s %s/%s: %.2f s%s\n", what, c.form, c.meth, bench_now() - t0,
          rc ? " (failed)" : "");
  if (rc) {
    run_res r;
    memset(&r, 0, sizeof r);
    r.status = rc;
    snprintf(r.msg, sizeof r.msg, "%s", dal_state_errmsg(m->st));
    log_failure(cfg, what, "double", c.form, c.meth, rtol, &r);
  }
  fflush(fp);
}

static void exp_drift(const bench_cfg *cfg) {
  FILE *fp = bench_csv_open(cfg->out, "drift.csv",
                            "formulation,method,rtol,t,phi_max,phidot_max,phi_max_so_far");
  if (!fp) return;
  bench_scene sc;
  scene_init(&sc, SC_DOUBLE, 2, 0);
  bench_model m;
  char err[400];
  int rc = scene_model(&sc, 1, &m, err, sizeof err);
  if (rc) {
    fprintf(stderr, "drift: no redundant double pendulum (%s)\n", dal_status_name(rc));
    fclose(fp);
    return;
  }
  double t1 = cfg->quick ? 100.0 : 1000.0, dt = cfg->quick ? 1.0 : 5.0, rtol = 1e-6;
  long_run(cfg, "drift", &m, BF_INDEX1, DAL_METHOD_DOPRI5, rtol, t1, dt, fp, 0);
  long_run(cfg, "drift", &m, BF_INDEX1_BAUMGARTE, DAL_METHOD_DOPRI5, rtol, t1, dt, fp, 0);
  long_run(cfg, "drift", &m, BF_INDEX1_PROJ, DAL_METHOD_DOPRI5, rtol, t1, dt, fp, 0);
  long_run(cfg, "drift", &m, BF_GGL, DAL_METHOD_BDF, rtol, t1, dt, fp, 0);
  scene_model_free(&m);
  fclose(fp);
}

static void exp_energy(const bench_cfg *cfg) {
  FILE *fp = bench_csv_open(cfg->out, "energy.csv", "formulation,method,rtol,t,energy_err");
  if (!fp) return;
  bench_scene sc;
  scene_init(&sc, SC_DOUBLE, 2, 0);
  bench_model m;
  char err[400];
  double t1 = cfg->quick ? 100.0 : 1000.0, dt = cfg->quick ? 1.0 : 5.0, rtol = 1e-8;
  if (!scene_model(&sc, 0, &m, err, sizeof err)) {
    for (int mi = 0; mi < COUNT(ode_methods); ++mi)
      long_run(cfg, "energy", &m, BF_ODE, ode_methods[mi], rtol, t1, dt, fp, 1);
    scene_model_free(&m);
  }
  if (!scene_model(&sc, 1, &m, err, sizeof err)) {
    long_run(cfg, "energy", &m, BF_GGL, DAL_METHOD_BDF, rtol, t1, dt, fp, 1);
    long_run(cfg, "energy", &m, BF_INDEX1_PROJ, DAL_METHOD_DOPRI5, rtol, t1, dt, fp, 1);
    scene_model_free(&m);
  }
  fclose(fp);
}

// ---------------------------------------------------------------- DAE tolerance sweep

static void exp_daetol(const bench_cfg *cfg) {
  FILE *fp = bench_csv_open(cfg->out, "dae_tolerance.csv",
                            "formulation,method,rtol,status,wall_s,rhs_evals,steps,err");
  if (!fp) return;
  bench_scene sc;
  scene_init(&sc, SC_DOUBLE, 2, 0);
  int npd = 4;
  double ref[4], agree;
  char how[160], err[400];
  bench_model m;
  if (scene_reference(&sc, ref, &agree, how, sizeof how) ||
      scene_model(&sc, 1, &m, err, sizeof err)) {
    fprintf(stderr, "daetol: no redundant double pendulum\n");
    fclose(fp);
    return;
  }
  bench_form forms[] = {BF_GGL, BF_INDEX3, BF_INDEX1};
  for (int fi = 0; fi < COUNT(forms); ++fi)
    for (int e = 2; e <= 14; ++e) {
      double rtol = pow(10.0, -e);
      dal_solve_opts o;
      bench_opts(&o, forms[fi], DAL_METHOD_BDF, rtol);
      o.max_steps = cfg->max_steps;
      run_res r;
      lib_measure(cfg, &m, &o, sc.t1, ref, npd, &r);
      if (r.status)
        log_failure(cfg, "daetol", sc.name, bench_form_name(forms[fi]), "bdf", rtol, &r);
      fprintf(fp, "%s,bdf,%.0e,%s,%.6e,%ld,%ld,%.6e\n", bench_form_name(forms[fi]), rtol,
              dal_status_name(r.status), r.wall, r.rhs, r.steps, r.err);
      fflush(fp);
    }
  scene_model_free(&m);
  fclose(fp);
}

// ---------------------------------------------------------------- stiff spring pendulum

static void exp_stiff(const bench_cfg *cfg) {
  FILE *fp =
      bench_csv_open(cfg->out, "stiff.csv", "k,method,rtol,status,wall_s,rhs_evals,steps,err");
  if (!fp) return;
  const double t1 = 1.0, rtols[2] = {1e-3, 1e-6}, th0 = PI / 4;
  double th, thd, ref[2];
  ref_pendulum(th0, 1.0, 9.81, t1, &th, &thd);
  ref[0] = sin(th);
  ref[1] = -cos(th);
  double ks_quick[] = {1e2, 1e4, 1e6, 1e8}, ks_full[] = {1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8};
  double *ks = cfg->quick ? ks_quick : ks_full;
  int nk = cfg->quick ? COUNT(ks_quick) : COUNT(ks_full);
  dal_method meths[] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_ADAMS, DAL_METHOD_BDF};
  for (int ki = 0; ki < nk; ++ki) {
    // a bob on a very stiff spring of rest length 1 to the origin, in Cartesian coordinates
    bench_model m;
    memset(&m, 0, sizeof m);
    scn_knobs kn = scn_default(); // anchored at the origin, no damper
    kn.g = 9.81;
    kn.k = ks[ki];
    kn.l = 1.0;
    m.sys = scn_hanging_spring(&kn);
    int rc = m.sys ? DAL_OK : DAL_E_ARG;
    if (!rc) rc = dal_state_create(m.sys, &m.st);
    m.n = 2;
    // released from rest at the static stretch, so that the fast radial mode is not excited
    // and the solution is smooth: the stiffness limits explicit steps, not the accuracy
    double len = 1.0 + 9.81 * cos(th0) / ks[ki];
    double q0[2] = {len * sin(th0), -len * cos(th0)}, qd0[2] = {0.0, 0.0};
    m.q0 = q0;
    m.qd0 = qd0;
    for (int ri = 0; ri < 2; ++ri)
      for (int mi = 0; !rc && mi < COUNT(meths); ++mi) {
        double rtol = rtols[ri];
        dal_solve_opts o;
        bench_opts(&o, BF_ODE, meths[mi], rtol);
        o.max_steps = cfg->max_steps;
        run_res r;
        lib_measure(cfg, &m, &o, t1, ref, 2, &r);
        if (r.status)
          log_failure(cfg, "stiff", "spring", "ode", dal_method_name(meths[mi]), rtol, &r);
        fprintf(fp, "%.0e,%s,%.0e,%s,%.6e,%ld,%ld,%.6e\n", ks[ki], dal_method_name(meths[mi]), rtol,
                dal_status_name(r.status), r.wall, r.rhs, r.steps, r.err);
        fflush(fp);
        fprintf(stderr, "stiff k=%.0e %s rtol %.0e: %s %.3g s, %ld rhs\n", ks[ki],
                dal_method_name(meths[mi]), rtol, dal_status_name(r.status), r.wall, r.rhs);
      }
    dal_state_destroy(m.st);
    dal_system_destroy(m.sys);
  }
  fclose(fp);
}

// ---------------------------------------------------------------- coordinate singularity

// the spherical pendulum in minimal (theta, phi) or redundant (x, y, z + rod) coordinates
static int spherical_model(int redundant, double th0, double thd0, double phd0, bench_model *m) {
  memset(m, 0, sizeof *m);
  // unit length and mass, pivot at the origin (the scene library's)
  m->sys = redundant ? scn_cart_spherical(NULL) : scn_spherical(NULL);
  int rc = m->sys ? DAL_OK : DAL_E_ARG;
  if (!rc) rc = dal_state_create(m->sys, &m->st);
  int n = m->sys ? dal_system_ncoords(m->sys) : 0;
  m->n = n;
  m->q0 = calloc((size_t)n + 1, sizeof(double));
  m->qd0 = calloc((size_t)n + 1, sizeof(double));
  if (!rc && (!m->q0 || !m->qd0)) rc = DAL_E_NOMEM;
  if (!rc && !redundant) {
    m->q0[0] = th0;
    m->qd0[0] = thd0;
    m->qd0[1] = phd0;
  } else if (!rc) {
    // r = (sin th, 0, -cos th), v = thd (cos th, 0, sin th) + phd sin th (0, 1, 0)
    m->q0[0] = sin(th0);
    m->q0[2] = -cos(th0);
    m->qd0[0] = thd0 * cos(th0);
    m->qd0[1] = phd0 * sin(th0);
    m->qd0[2] = thd0 * sin(th0);
  }
  if (!rc) rc = scene_model_reset(m);
  if (rc) scene_model_free(m);
  return rc;
}

static void exp_singular(const bench_cfg *cfg) {
  FILE *fp = bench_csv_open(cfg->out, "singular.csv",
                            "case,phidot0,formulation,method,rtol,status,wall_s,rhs_evals,steps,"
                            "err,case_id");
  if (!fp) return;
  const double t1 = 3.0, rtol = 1e-8, g = 9.81;
  struct {
    const char *name;
    double th0, thd0, phd0;
  } cases[] = {{"start-at-pole", 0.0, 2.0, 0.0}, {"near-pole", PI / 3, 0.0, 1e-1},
               {"near-pole", PI / 3, 0.0, 1e-3}, {"near-pole", PI / 3, 0.0, 1e-5},
               {"near-pole", PI / 3, 0.0, 1e-7}, {"through-pole", PI / 3, 0.0, 0.0}};
  for (int ci = 0; ci < COUNT(cases); ++ci) {
    // reference: the hand-written Cartesian equations, two methods
    double th0 = cases[ci].th0, y0[6] = {sin(th0),
                                         0.0,
                                         -cos(th0),
                                         cases[ci].thd0 * cos(th0),
                                         cases[ci].phd0 * sin(th0),
                                         cases[ci].thd0 * sin(th0)};
    double ya[6], yb[6], gg = g;
    memcpy(ya, y0, sizeof ya);
    memcpy(yb, y0, sizeof yb);
    hand_integrate(hand_spherical_rhs, &gg, 6, ya, 0.0, t1, DAL_METHOD_FEHLBERG78, 1e-14, 1e-16,
                   100000000, NULL);
    hand_integrate(hand_spherical_rhs, &gg, 6, yb, 0.0, t1, DAL_METHOD_DOPRI5, 1e-14, 1e-16,
                   100000000, NULL);
    fprintf(stderr, "singular %s phd0=%g: reference agreement %.2e\n", cases[ci].name,
            cases[ci].phd0, bench_maxdiff(ya, yb, 3));
    for (int red = 0; red <= 1; ++red) {
      bench_model m;
      int rc = spherical_model(red, th0, cases[ci].thd0, cases[ci].phd0, &m);
      if (rc) {
        if (rc != DAL_E_UNSUPPORTED) fprintf(stderr, "  cannot build spherical (%d)\n", rc);
        continue;
      }
      struct {
        bench_form f;
        dal_method meth;
      } runs[2] = {{BF_ODE, DAL_METHOD_DOPRI5}, {BF_ODE, DAL_METHOD_ADAMS}};
      if (red) {
        runs[0].f = BF_GGL;
        runs[0].meth = DAL_METHOD_BDF;
        runs[1].f = BF_INDEX1_PROJ;
        runs[1].meth = DAL_METHOD_DOPRI5;
      }
      for (int ri = 0; ri < 2; ++ri) {
        dal_solve_opts o;
        bench_opts(&o, runs[ri].f, runs[ri].meth, rtol);
        o.max_steps = cfg->max_steps;
        run_res r;
        lib_measure(cfg, &m, &o, t1, ya, 3, &r);
        if (r.status)
          log_failure(cfg, "singular", cases[ci].name, bench_form_name(runs[ri].f),
                      dal_method_name(runs[ri].meth), rtol, &r);
        fprintf(fp, "%s,%.0e,%s,%s,%.0e,%s,%.6e,%ld,%ld,%.6e,%d\n", cases[ci].name, cases[ci].phd0,
                bench_form_name(runs[ri].f), dal_method_name(runs[ri].meth), rtol,
                dal_status_name(r.status), r.wall, r.rhs, r.steps, r.err, ci);
        fflush(fp);
      }
      scene_model_free(&m);
    }
  }
  fclose(fp);
}

// ---------------------------------------------------------------- smoke self-check

// library accelerations against both hand-written forms, and one short integration
static int exp_smoke(void) {
  int bad = 0;
  bench_scene sc;
  scene_init(&sc, SC_CHAIN, 5, 1.0);
  bench_model m;
  char err[400];
  if (scene_model(&sc, 0, &m, err, sizeof err)) {
    fprintf(stderr, "smoke: cannot build the chain: %s\n", err);
    return 1;
  }
  double y[10], f1[10], f2[10];
  hand_chain *ch = scene_hand_chain(&sc, y);
  srand(7);
  for (int trial = 0; ch && trial < 20; ++trial) {
    for (int i = 0; i < 10; ++i)
      y[i] = 4.0 * rand() / RAND_MAX - 2.0;
    hand_chain_rhs_dense(0.0, y, f1, ch);
    hand_chain_rhs_tridiag(0.0, y, f2, ch);
    dal_state_set(m.sys, m.st, 0.0, y, y + 5);
    if (dal_forward(m.sys, m.st)) {
      fprintf(stderr, "smoke: forward failed: %s\n", dal_state_errmsg(m.st));
      bad = 1;
      break;
    }
    const double *a = dal_state_qddot(m.st);
    for (int i = 0; i < 5; ++i) {
      double s = 1.0 + fabs(f1[5 + i]);
      if (fabs(a[i] - f1[5 + i]) > 1e-12 * s || fabs(f2[5 + i] - f1[5 + i]) > 1e-12 * s) {
        fprintf(stderr, "smoke: thdd[%d]: library %.17g, dense %.17g, O(N) %.17g\n", i, a[i],
                f1[5 + i], f2[5 + i]);
        bad = 1;
      }
    }
  }
  hand_chain_destroy(ch);
  scene_model_free(&m);
  // the benchmark's elliptic reference against the tests' independent one
  double worst = 0.0;
  for (int i = 0; i <= 40; ++i) {
    double t = 0.25 * i, a, ad, b, bd;
    ref_pendulum(5.0 * PI / 6.0, 1.0, 9.81, t, &a, &ad);
    bench_tests_pendulum(5.0 * PI / 6.0, sqrt(9.81), t, &b, &bd);
    worst = fmax(worst, fmax(fabs(a - b), fabs(ad - bd) / 10.0));
  }
  fprintf(stderr, "smoke: bench/ref.h vs tests/ref_elliptic.h (150 deg, t in [0, 10]): %.2e\n",
          worst);
  if (!(worst < 1e-12)) bad = 1;
  // the pendulum at 1e-8 against the Jacobi elliptic solution
  scene_init(&sc, SC_PENDULUM, 1, 0);
  double ref[2], agree, r[2];
  char how[160];
  scene_reference(&sc, ref, &agree, how, sizeof how);
  if (!scene_model(&sc, 0, &m, err, sizeof err)) {
    dal_solve_opts o;
    bench_opts(&o, BF_ODE, DAL_METHOD_DOPRI5, 1e-8);
    run_res rr;
    lib_once(&m, &o, sc.t1, r, 2, &rr);
    double e = rr.status ? NAN : bench_maxdiff(r, ref, 2);
    fprintf(stderr, "smoke: pendulum dopri5 rtol 1e-8: %s, err %.2e, %ld rhs\n",
            dal_status_name(rr.status), e, rr.rhs);
    if (!(e < 1e-5)) bad = 1;
    scene_model_free(&m);
  }
  fprintf(stderr, "smoke: %s\n", bad ? "FAILED" : "ok");
  return bad;
}

// ---------------------------------------------------------------- closed loops on a tree

// the forms a loop scene runs in: the tree of placements plus loop rows through the recursion
// and the m x m loop system (index-1 with projection), the same tree forced through the KKT
// matrix, and the Cartesian scene (every link a constraint) in GGL and index-1 with projection
typedef struct loop_form {
  const char *name;
  int cart;
  dal_dynamics how;
  bench_form form;
} loop_form;
static const loop_form loop_forms[] = {{"tree", 0, DAL_DYNAMICS_AUTO, BF_INDEX1_PROJ},
                                       {"tree-dense", 0, DAL_DYNAMICS_DENSE, BF_INDEX1_PROJ},
                                       {"cart-ggl", 1, DAL_DYNAMICS_AUTO, BF_GGL},
                                       {"cart-index1", 1, DAL_DYNAMICS_AUTO, BF_INDEX1_PROJ}};

static const loop_form *loop_form_find(const char *name) {
  for (int i = 0; i < COUNT(loop_forms); ++i)
    if (strcmp(loop_forms[i].name, name) == 0) return &loop_forms[i];
  return NULL;
}

// library options of a loop form (GGL with KLU: the dense default takes difference quotients)
static void loop_opts(dal_solve_opts *o, const loop_form *lf, dal_method meth, double rtol) {
  bench_opts(o, lf->form, meth, rtol);
  if (lf->form == BF_GGL) o->linsol = DAL_LINSOL_KLU;
}

// the four-bar linkage and a 64-link chain held at both ends in every form: wall time,
// evaluations and error against a reference computed twice (tree and Cartesian forms,
// Fehlberg 7(8) with projection at rtol 1e-12)
static void exp_loops(const bench_cfg *cfg) {
  FILE *fp = bench_csv_open(cfg->out, "loops.csv",
                            "scene,form,method,rtol,wall_s,rhs_evals,steps,err,ref_agreement");
  if (!fp) return;
  struct {
    const char *name;
    int which, NL;
    double t1;
  } scenes[] = {{"fourbar", LOOP_FOURBAR, 0, 2.0}, {"held64", LOOP_HELD, 64, 1.0}};
  for (int si = 0; si < COUNT(scenes); ++si) {
    int np = loop_np(scenes[si].which, scenes[si].NL), npd = 2 * np;
    double *ref = malloc((size_t)npd * sizeof(double)), *r2 = malloc((size_t)npd * sizeof(double));
    char err[400];
    bench_model m;
    double agree = NAN;
    int rc = ref && r2 ? DAL_OK : DAL_E_NOMEM;
    // the reference in two forms
    for (int c = 0; c < 2 && !rc; ++c) {
      rc = loop_model(scenes[si].which, scenes[si].NL, c, DAL_DYNAMICS_AUTO, &m, err, sizeof err);
      if (rc) break;
      dal_solve_opts o;
      bench_opts(&o, BF_INDEX1_PROJ, DAL_METHOD_FEHLBERG78, 1e-12);
      o.max_steps = 10000000;
      run_res rr;
      rc = lib_once(&m, &o, scenes[si].t1, c ? r2 : ref, npd, &rr);
      if (rc) fprintf(stderr, "loops %s: reference failed: %s\n", scenes[si].name, rr.msg);
      scene_model_free(&m);
    }
    if (!rc) agree = bench_maxdiff(ref, r2, npd);
    fprintf(stderr, "loops %s: reference agreement (tree vs Cartesian, rtol 1e-12) %.2e\n",
            scenes[si].name, agree);
    static const double tols[] = {1e-6, 1e-8};
    for (int fi = 0; !rc && fi < COUNT(loop_forms); ++fi) {
      const loop_form *lf = &loop_forms[fi];
      if (loop_model(scenes[si].which, scenes[si].NL, lf->cart, lf->how, &m, err, sizeof err)) {
        fprintf(stderr, "  cannot build: %s\n", err);
        continue;
      }
      dal_method meth = lf->form == BF_GGL ? DAL_METHOD_BDF : DAL_METHOD_DOPRI5;
      for (int ti = 0; ti < COUNT(tols); ++ti) {
        // GGL's error is 100-1000x its tolerance: ask it for two more digits
        double rtol = lf->form == BF_GGL ? 1e-2 * tols[ti] : tols[ti];
        dal_solve_opts o;
        loop_opts(&o, lf, meth, rtol);
        o.max_steps = cfg->max_steps;
        run_res r;
        lib_measure(cfg, &m, &o, scenes[si].t1, ref, npd, &r);
        if (r.status)
          log_failure(cfg, "loops", scenes[si].name, lf->name, dal_method_name(meth), rtol, &r);
        fprintf(fp, "%s,%s,%s,%.0e,%.6e,%ld,%ld,%.6e,%.3e\n", scenes[si].name, lf->name,
                dal_method_name(meth), rtol, r.wall, r.rhs, r.steps, r.err, agree);
        fflush(fp);
        fprintf(stderr, "  %-12s %-7s rtol %.0e: %.3g s, %ld rhs, err %.2e\n", lf->name,
                dal_method_name(meth), rtol, r.wall, r.rhs, r.err);
      }
      scene_model_free(&m);
    }
    free(ref);
    free(r2);
  }
  fclose(fp);
}

// ---------------------------------------------------------------- instruction counts

#if defined(__GNUC__)
#define BENCH_NOINLINE __attribute__((noinline))
#else
#define BENCH_NOINLINE
#endif

// the measured region of `dal_bench ir ...`: callgrind counts instructions only in here
// (valgrind --tool=callgrind --toggle-collect=ir_region)
static BENCH_NOINLINE int ir_region(bench_model *m, const dal_solve_opts *o, hand_chain *ch,
                                    int tri, const double *y0, double *y, dal_method meth,
                                    double rtol, double t1) {
  if (m) {
    int rc = scene_model_reset(m);
    return rc ? rc : dal_advance(m->sys, m->st, o, t1);
  }
  int n = 2 * ch->N;
  double tol = hand_tol(meth, rtol);
  memcpy(y, y0, (size_t)n * sizeof(double));
  return hand_integrate(tri ? hand_chain_rhs_tridiag : hand_chain_rhs_dense, ch, n, y, 0.0, t1,
                        meth, tol, tol, 5000000, NULL);
}

// dal_bench ir lib|dense|hand|tridiag N method rtol t1: one run of the chain, for instruction
// counting (lib: the library's automatic route; dense: the library forced to assemble and
// factor M; hand: the lean hand-written dense chain; tridiag: the hand-written O(N) chain)
static int exp_ir(int argc, char **argv) {
  if (argc != 5) {
    fprintf(stderr, "usage: dal_bench ir lib|dense|hand|tridiag N method rtol t1\n");
    return 2;
  }
  int dense = strcmp(argv[0], "dense") == 0, lib = dense || strcmp(argv[0], "lib") == 0;
  int tri = strcmp(argv[0], "tridiag") == 0, N = atoi(argv[1]);
  double rtol = atof(argv[3]), t1 = atof(argv[4]);
  dal_method meth = DAL_METHOD_AUTO;
  for (int k = DAL_METHOD_DOPRI5; k <= DAL_METHOD_BDF; ++k)
    if (strcmp(argv[2], dal_method_name((dal_method)k)) == 0) meth = (dal_method)k;
  if (N < 1 || meth == DAL_METHOD_AUTO || !(rtol > 0) || !(t1 > 0)) return 2;
  bench_scene sc;
  scene_init(&sc, SC_CHAIN, N, t1);
  bench_model m;
  char err[400];
  double *y0 = malloc(2 * (size_t)N * sizeof(double)), *y = malloc(2 * (size_t)N * sizeof(double));
  hand_chain *ch = y0 ? scene_hand_chain(&sc, y0) : NULL;
  int rc = ch && y ? DAL_OK : DAL_E_NOMEM;
  if (!rc && lib)
    rc = scene_model_route(&sc, 0, dense ? DAL_DYNAMICS_DENSE : DAL_DYNAMICS_AUTO, &m, err,
                           sizeof err);
  dal_solve_opts o;
  bench_opts(&o, BF_ODE, meth, rtol);
  if (!rc) rc = ir_region(lib ? &m : NULL, &o, ch, tri, y0, y, meth, rtol, t1);
  if (lib && ch && y) {
    dal_stats s;
    dal_state_stats(m.st, &s);
    printf("rhs_evals=%ld steps=%ld\n", s.rhs_evals, s.steps);
    scene_model_free(&m);
  } else {
    printf("rhs_evals=%ld\n", ch ? ch->nevals : 0L);
  }
  hand_chain_destroy(ch);
  free(y0);
  free(y);
  return rc ? 1 : 0;
}

// dal_bench irloop fourbar|held<NL> tree|tree-dense|cart-ggl|cart-index1 method rtol t1: one
// run of a loop scene, for instruction counting
static int exp_irloop(int argc, char **argv) {
  if (argc != 5) {
    fprintf(stderr, "usage: dal_bench irloop fourbar|held<NL> form method rtol t1\n");
    return 2;
  }
  int which = strncmp(argv[0], "held", 4) == 0 ? LOOP_HELD : LOOP_FOURBAR;
  int NL = which == LOOP_HELD ? atoi(argv[0] + 4) : 0;
  const loop_form *lf = loop_form_find(argv[1]);
  double rtol = atof(argv[3]), t1 = atof(argv[4]);
  dal_method meth = DAL_METHOD_AUTO;
  for (int k = DAL_METHOD_DOPRI5; k <= DAL_METHOD_BDF; ++k)
    if (strcmp(argv[2], dal_method_name((dal_method)k)) == 0) meth = (dal_method)k;
  if (!lf || meth == DAL_METHOD_AUTO || (which == LOOP_HELD && NL < 2) || !(rtol > 0) || !(t1 > 0))
    return 2;
  bench_model m;
  char err[400];
  int rc = loop_model(which, NL, lf->cart, lf->how, &m, err, sizeof err);
  if (rc) {
    fprintf(stderr, "%s\n", err);
    return 1;
  }
  dal_solve_opts o;
  loop_opts(&o, lf, meth, rtol);
  rc = ir_region(&m, &o, NULL, 0, NULL, NULL, meth, rtol, t1);
  dal_stats st;
  dal_state_stats(m.st, &st);
  printf("rhs_evals=%ld steps=%ld status=%d\n", st.rhs_evals, st.steps, rc);
  scene_model_free(&m);
  return rc ? 1 : 0;
}

// dal_bench irroute N recursive|dense rtol t1: the N-link chain in Cartesian coordinates (N
// rods) as an index-1 ODE with projection (DOPRI5), through the m x m loop system or the KKT
// matrix: the measurement behind DAL_LOOP_ROWS_MAX
static int exp_irroute(int argc, char **argv) {
  if (argc != 4) {
    fprintf(stderr, "usage: dal_bench irroute N recursive|dense rtol t1\n");
    return 2;
  }
  int N = atoi(argv[0]);
  int dense = strcmp(argv[1], "dense") == 0;
  double rtol = atof(argv[2]), t1 = atof(argv[3]);
  if (N < 1 || !(rtol > 0) || !(t1 > 0)) return 2;
  bench_scene sc;
  scene_init(&sc, SC_CHAIN, N, t1);
  bench_model m;
  char err[400];
  int rc = scene_model_route(&sc, 1, dense ? DAL_DYNAMICS_DENSE : DAL_DYNAMICS_RECURSIVE, &m, err,
                             sizeof err);
  if (rc) {
    fprintf(stderr, "%s\n", err);
    return 1;
  }
  dal_solve_opts o;
  bench_opts(&o, BF_INDEX1_PROJ, DAL_METHOD_DOPRI5, rtol);
  rc = ir_region(&m, &o, NULL, 0, NULL, NULL, DAL_METHOD_DOPRI5, rtol, t1);
  dal_stats st;
  dal_state_stats(m.st, &st);
  printf("rhs_evals=%ld steps=%ld status=%d\n", st.rhs_evals, st.steps, rc);
  scene_model_free(&m);
  return rc ? 1 : 0;
}

// ---------------------------------------------------------------- main

int main(int argc, char **argv) {
  bench_cfg cfg = {1, "bench/results", 0.05, 3, 15, 0.1, 50000, 2.0, NULL};
  const char *exps[16];
  int nexp = 0;
  for (int i = 1; i < argc; ++i) {
    if (strcmp(argv[i], "--quick") == 0)
      cfg.quick = 1;
    else if (strcmp(argv[i], "--full") == 0)
      cfg.quick = 0;
    else if (strcmp(argv[i], "--out") == 0 && i + 1 < argc)
      cfg.out = argv[++i];
    else if (argv[i][0] != '-' && nexp < 16)
      exps[nexp++] = argv[i];
    else {
      fprintf(stderr, "usage: dal_bench [--quick|--full] [--out DIR] [smoke wp overhead cost "
                      "loops drift energy daetol stiff singular]\n");
      return 2;
    }
  }
  if (!cfg.quick) {
    cfg.budget = 0.3;
    cfg.min_reps = 3;
    cfg.max_reps = 31;
    cfg.long_run = 2.0;
    cfg.max_steps = 200000;
    cfg.slow_run = 10.0;
  }
  if (argc > 1 && strcmp(argv[1], "ir") == 0) return exp_ir(argc - 2, argv + 2);
  if (argc > 1 && strcmp(argv[1], "irloop") == 0) return exp_irloop(argc - 2, argv + 2);
  if (argc > 1 && strcmp(argv[1], "irroute") == 0) return exp_irroute(argc - 2, argv + 2);
  if (nexp == 1 && strcmp(exps[0], "smoke") == 0) return exp_smoke();
  static const char *all[] = {"wp",     "overhead", "cost",  "loops",   "drift",
                              "energy", "daetol",   "stiff", "singular"};
  if (nexp == 0) {
    for (int i = 0; i < COUNT(all); ++i)
      exps[i] = all[i];
    nexp = COUNT(all);
  }
  cfg.failures = bench_csv_open(cfg.out, "failures.csv",
                                "experiment,scene,formulation,method,rtol,status,message");
  if (!cfg.failures) return 1;
  for (int i = 0; i < nexp; ++i) {
    double t0 = bench_now();
    if (strcmp(exps[i], "wp") == 0)
      exp_wp(&cfg);
    else if (strcmp(exps[i], "overhead") == 0)
      exp_overhead(&cfg);
    else if (strcmp(exps[i], "cost") == 0)
      exp_cost(&cfg);
    else if (strcmp(exps[i], "loops") == 0)
      exp_loops(&cfg);
    else if (strcmp(exps[i], "drift") == 0)
      exp_drift(&cfg);
    else if (strcmp(exps[i], "energy") == 0)
      exp_energy(&cfg);
    else if (strcmp(exps[i], "daetol") == 0)
      exp_daetol(&cfg);
    else if (strcmp(exps[i], "stiff") == 0)
      exp_stiff(&cfg);
    else if (strcmp(exps[i], "singular") == 0)
      exp_singular(&cfg);
    else if (strcmp(exps[i], "smoke") == 0)
      exp_smoke();
    else
      fprintf(stderr, "dal_bench: unknown experiment '%s'\n", exps[i]);
    fprintf(stderr, "== %s: %.1f s\n", exps[i], bench_now() - t0);
  }
  fclose(cfg.failures);
  return 0;
}
