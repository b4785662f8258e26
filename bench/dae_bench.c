// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The planar N-link chain in Cartesian coordinates (DAE forms) against minimal coordinates.
//
// Modes (bench/dae_ir.sh and bench/dae_configs.sh run them):
//   dal_bench_dae ir cart|min|hand N rtol t1 [form] [linsol] [method] [--err]
//       one run of the chain inside ir_region() for callgrind (--toggle-collect=ir_region);
//       cart: Cartesian particles with rods (form ggl, index1proj or auto; linsol klu, dense or
//       auto; method bdf, dopri5, ... or auto); min: minimal coordinates (the library's
//       automatic route, the articulated-body recursion; form ode, Adams unless a method is
//       given); hand: the hand-written O(N) chain by CVODE Adams at the library's own local
//       tolerance for rtol (the same steps as min). Prints the statistics, and
//       with --err the max position error at t1 against the hand-written O(N) chain by
//       Fehlberg 7(8) at rtol 1e-12 (computed outside the region).
//   dal_bench_dae scaling RTOL T1 [N ...]
//       the Cartesian chain in GGL with KLU (BDF) at each N (default 256 362 512 724 1024 1448
//       2048 2896 4096, steps of sqrt 2) to t = T1, one run inside ir_region() each: one CSV
//       row per run (row,N,rtol,t1,steps,nonlin_iters,jac_evals,rejected,status), each followed
//       by a callgrind dump of its counts (rowK) when run under valgrind --tool=callgrind
//       --toggle-collect=ir_region (bench/dae_scaling.sh joins and tabulates them).
//   dal_bench_dae configs [--quick|--full] [--out DIR]
//       the 32-link chain at rtol 1e-3 ... 1e-10: the default configuration (dal_solve_default
//       _opts, only rtol set) beside every forced one (GGL with dense LU or KLU; index-1 with
//       projection by each explicit method), runs interleaved in one process; writes
//       dae_configs.csv and prints the ratio default / best per rtol.
// The chain: pivot at the origin, unit masses and lengths, released from rest as a straight
// rod at 45 degrees from the downward vertical, gravity 9.81 (bench/scenes.c's chain).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <valgrind/callgrind.h>

#include "dalembert/dalembert.h"
#include "hand.h"
#include "support/scenes.h"
#include "util.h"

#define PI 3.14159265358979323846
#define G_STD 9.81
#define CHAIN_TH0 (PI / 4.0)

#if defined(__GNUC__)
#define BENCH_NOINLINE __attribute__((noinline))
#else
#define BENCH_NOINLINE
#endif

typedef struct chain_model {
  dal_system *sys;
  dal_state *st;
  int N, cart;
  double *q0, *qd0;
} chain_model;

static void chain_free(chain_model *m) {
  dal_state_destroy(m->st);
  dal_system_destroy(m->sys);
  free(m->q0);
  free(m->qd0);
  memset(m, 0, sizeof *m);
}

static int chain_reset(chain_model *m) { return dal_state_set(m->sys, m->st, 0.0, m->q0, m->qd0); }

// the chain of the scene library (scn_cart_chain, scn_chain) and its initial state
static int chain_build(int N, int cart, chain_model *m) {
  memset(m, 0, sizeof *m);
  m->N = N;
  m->cart = cart;
  size_t n = (size_t)(cart ? 2 * N : N);
  m->q0 = calloc(n, sizeof(double));
  m->qd0 = calloc(n, sizeof(double));
  int rc = m->q0 && m->qd0 ? DAL_OK : DAL_E_NOMEM;
  double x = 0.0, y = 0.0;
  for (int i = 0; i < N && !rc; ++i) {
    x += sin(CHAIN_TH0);
    y -= cos(CHAIN_TH0);
    if (cart)
      m->q0[2 * i] = x, m->q0[2 * i + 1] = y;
    else
      m->q0[i] = CHAIN_TH0;
  }
  scn_knobs k = scn_default();
  k.g = G_STD;
  k.N = N;
  if (!rc) m->sys = cart ? scn_cart_chain(&k) : scn_chain(&k);
  if (!rc && !m->sys) rc = DAL_E_ARG; // the builder's message is on stderr
  if (!rc) rc = dal_state_create(m->sys, &m->st);
  if (!rc) rc = chain_reset(m);
  if (rc) chain_free(m);
  return rc;
}

// particle positions (N x 2) of the model's state
static void chain_positions(const chain_model *m, double *r) {
  memcpy(r, dal_state_positions(m->st), 2 * (size_t)m->N * sizeof(double));
}

// the reference positions at t1: the hand-written O(N) chain by Fehlberg 7(8) at rtol 1e-12
static int chain_reference(int N, double t1, double *r) {
  double *y = malloc(2 * (size_t)N * sizeof(double));
  hand_chain *ch = y ? hand_chain_create(N, G_STD) : NULL;
  int rc = -1;
  if (ch) {
    for (int i = 0; i < N; ++i) {
      y[i] = CHAIN_TH0;
      y[N + i] = 0.0;
    }
    rc = hand_integrate(hand_chain_rhs_tridiag, ch, 2 * N, y, 0.0, t1, DAL_METHOD_FEHLBERG78, 1e-12,
                        1e-14, 100000000, NULL);
    hand_chain_positions(ch, y, r);
  }
  hand_chain_destroy(ch);
  free(y);
  return rc;
}

// ---------------------------------------------------------------- configurations

typedef struct dae_config {
  const char *name;
  int dflt; // the default configuration: only rtol set
  dal_formulation form;
  int project;
  dal_linsol linsol;
  dal_method method;
} dae_config;

static const dae_config configs[] = {
    {"default", 1, DAL_FORM_AUTO, 0, DAL_LINSOL_AUTO, DAL_METHOD_AUTO},
    {"ggl/bdf/dense", 0, DAL_FORM_GGL, 0, DAL_LINSOL_DENSE, DAL_METHOD_BDF},
    {"ggl/bdf/klu", 0, DAL_FORM_GGL, 0, DAL_LINSOL_KLU, DAL_METHOD_BDF},
    {"index1-proj/dopri5", 0, DAL_FORM_INDEX1, 1, DAL_LINSOL_AUTO, DAL_METHOD_DOPRI5},
    {"index1-proj/fehlberg78", 0, DAL_FORM_INDEX1, 1, DAL_LINSOL_AUTO, DAL_METHOD_FEHLBERG78},
    {"index1-proj/bs", 0, DAL_FORM_INDEX1, 1, DAL_LINSOL_AUTO, DAL_METHOD_BS},
    {"index1-proj/adams", 0, DAL_FORM_INDEX1, 1, DAL_LINSOL_AUTO, DAL_METHOD_ADAMS},
};
#define NCONF ((int)(sizeof configs / sizeof configs[0]))

static const dae_config *config_find(const char *form, const char *linsol, const char *method) {
  static dae_config c;
  c.name = "custom";
  c.dflt = strcmp(form, "auto") == 0 && strcmp(linsol, "auto") == 0 && strcmp(method, "auto") == 0;
  c.form = strcmp(form, "ggl") == 0          ? DAL_FORM_GGL
           : strcmp(form, "index1proj") == 0 ? DAL_FORM_INDEX1
           : strcmp(form, "ode") == 0        ? DAL_FORM_ODE
                                             : DAL_FORM_AUTO;
  c.project = c.form == DAL_FORM_INDEX1;
  c.linsol = strcmp(linsol, "klu") == 0     ? DAL_LINSOL_KLU
             : strcmp(linsol, "dense") == 0 ? DAL_LINSOL_DENSE
                                            : DAL_LINSOL_AUTO;
  c.method = DAL_METHOD_AUTO;
  for (int k = DAL_METHOD_DOPRI5; k <= DAL_METHOD_BDF; ++k)
    if (strcmp(method, dal_method_name((dal_method)k)) == 0) c.method = (dal_method)k;
  return &c;
}

static void config_opts(const dae_config *c, double rtol, dal_solve_opts *o) {
  *o = dal_default_solve_opts();
  o->rtol = rtol;
  o->max_steps = 2000000;
  if (c->dflt) return;
  o->form = c->form;
  o->project = c->project;
  o->linsol = c->linsol;
  o->method = c->method;
}

// the measured region: callgrind counts instructions only in here (the library's run, or with
// ch set the hand-written O(N) chain from y by Adams at the tolerance tol)
static BENCH_NOINLINE int ir_region(chain_model *m, const dal_solve_opts *o, double t1,
                                    hand_chain *ch, double *y, double tol, hand_stats *hs) {
  if (ch)
    return hand_integrate(hand_chain_rhs_tridiag, ch, 2 * ch->N, y, 0.0, t1, DAL_METHOD_ADAMS, tol,
                          tol, 5000000, hs);
  int rc = chain_reset(m);
  return rc ? rc : dal_advance(m->sys, m->st, o, t1);
}

// dal_bench_dae ir hand N rtol t1: the hand-written O(N) chain (rod tensions from a
// tridiagonal system, bench/hand.c) by CVODE Adams at the tolerance the library's minimal
// route runs at for this request (from a library run before the region), so that both sides
// take the same steps
static int mode_ir_hand(int N, double rtol, double t1) {
  chain_model m;
  if (chain_build(N, 0, &m)) return 1;
  dal_solve_opts o = dal_default_solve_opts();
  o.form = DAL_FORM_ODE;
  o.method = DAL_METHOD_ADAMS;
  o.rtol = o.atol = rtol;
  o.max_steps = 5000000;
  int rc = dal_advance(m.sys, m.st, &o, t1);
  dal_stats s;
  dal_state_stats(m.st, &s);
  chain_free(&m);
  double *y = malloc(2 * (size_t)N * sizeof(double));
  hand_chain *ch = y && !rc ? hand_chain_create(N, G_STD) : NULL;
  if (!ch) {
    free(y);
    return 1;
  }
  for (int i = 0; i < N; ++i) {
    y[i] = CHAIN_TH0;
    y[N + i] = 0.0;
  }
  // the ODE integrators leave dal_stats.rtol_used at 0: then the factor of Adams in the method
  // table (src/integrate/methods.c), mirrored; the equal right-hand-side counts printed check it
  double tol = s.rtol_used > 0 ? s.rtol_used : 0.005 * rtol;
  hand_stats hs;
  rc = ir_region(NULL, NULL, t1, ch, y, tol, &hs);
  printf("rhs_evals=%ld steps=%ld status=%d tol=%.3g (library: rhs_evals=%ld steps=%ld)\n",
         hs.rhs_evals, hs.steps, rc, tol, s.rhs_evals, s.steps);
  hand_chain_destroy(ch);
  free(y);
  return rc ? 1 : 0;
}

// dal_bench_dae ir cart|min|hand N rtol t1 [form] [linsol] [method] [--err]
static int mode_ir(int argc, char **argv) {
  int want_err = argc > 0 && strcmp(argv[argc - 1], "--err") == 0;
  if (want_err) --argc;
  if (argc < 4 || argc > 7) {
    fprintf(stderr, "usage: dal_bench_dae ir cart|min|hand N rtol t1 [form] [linsol] [method] "
                    "[--err]\n");
    return 2;
  }
  int cart = strcmp(argv[0], "cart") == 0, N = atoi(argv[1]);
  double rtol = atof(argv[2]), t1 = atof(argv[3]);
  if (N < 1 || !(rtol > 0) || !(t1 > 0)) return 2;
  if (strcmp(argv[0], "hand") == 0) return mode_ir_hand(N, rtol, t1);
  const dae_config *c = config_find(argc > 4 ? argv[4] : (cart ? "auto" : "ode"),
                                    argc > 5 ? argv[5] : "auto", argc > 6 ? argv[6] : "auto");
  dal_solve_opts o;
  config_opts(c, rtol, &o);
  if (!cart) {
    o.form = DAL_FORM_ODE;
    o.atol = rtol;
    if (o.method == DAL_METHOD_AUTO) o.method = DAL_METHOD_ADAMS;
  }
  chain_model m;
  int rc = chain_build(N, cart, &m);
  if (rc) return 1;
  double w0 = bench_now();
  rc = ir_region(&m, &o, t1, NULL, NULL, 0.0, NULL);
  double wall = bench_now() - w0;
  dal_stats s;
  dal_state_stats(m.st, &s);
  printf("rhs_evals=%ld steps=%ld jac_evals=%ld nonlin_iters=%ld rejected=%ld status=%d "
         "wall=%.4g",
         s.rhs_evals, s.steps, s.jac_evals, s.nonlin_iters, s.rejected, rc, wall);
  if (rc) printf(" msg=\"%s\"", dal_state_errmsg(m.st));
  if (want_err && !rc) {
    double *r = malloc(4 * (size_t)N * sizeof(double));
    if (r && chain_reference(N, t1, r + 2 * N) == 0) {
      chain_positions(&m, r);
      printf(" err=%.3g", bench_maxdiff(r, r + 2 * N, 2 * N));
    }
    free(r);
  }
  printf("\n");
  chain_free(&m);
  return rc ? 1 : 0;
}

// dal_bench_dae scaling RTOL T1 [N ...]: GGL + KLU over the sizes, one callgrind dump per run
static int mode_scaling(int argc, char **argv) {
  static const int dflt[] = {256, 362, 512, 724, 1024, 1448, 2048, 2896, 4096};
  if (argc < 2) {
    fprintf(stderr, "usage: dal_bench_dae scaling RTOL T1 [N ...]\n");
    return 2;
  }
  double rtol = atof(argv[0]), t1 = atof(argv[1]);
  int nn = argc > 2 ? argc - 2 : (int)(sizeof dflt / sizeof dflt[0]);
  if (!(rtol > 0) || !(t1 > 0)) return 2;
  const dae_config *c = config_find("ggl", "klu", "bdf");
  dal_solve_opts o;
  config_opts(c, rtol, &o);
  printf("row,N,rtol,t1,steps,nonlin_iters,jac_evals,rejected,status\n");
  int bad = 0;
  for (int k = 0; k < nn; ++k) {
    int N = argc > 2 ? atoi(argv[2 + k]) : dflt[k];
    chain_model m;
    if (N < 1 || chain_build(N, 1, &m)) return 1;
    int rc = ir_region(&m, &o, t1, NULL, NULL, 0.0, NULL);
    dal_stats s;
    dal_state_stats(m.st, &s);
    printf("%d,%d,%.0e,%g,%ld,%ld,%ld,%ld,%s\n", k, N, rtol, t1, s.steps, s.nonlin_iters,
           s.jac_evals, s.rejected, dal_status_name(rc));
    fflush(stdout);
    char label[32];
    snprintf(label, sizeof label, "row%d", k);
    CALLGRIND_DUMP_STATS_AT(label);
    bad |= rc != 0;
    chain_free(&m);
  }
  return bad;
}

// dal_bench_dae configs: every configuration side by side on the 32-link chain
static int mode_configs(int argc, char **argv) {
  int quick = 1, N = 32;
  const char *out = "bench/results";
  for (int i = 0; i < argc; ++i) {
    if (strcmp(argv[i], "--quick") == 0)
      quick = 1;
    else if (strcmp(argv[i], "--full") == 0)
      quick = 0;
    else if (strcmp(argv[i], "--out") == 0 && i + 1 < argc)
      out = argv[++i];
    else {
      fprintf(stderr, "usage: dal_bench_dae configs [--quick|--full] [--out DIR]\n");
      return 2;
    }
  }
  const double t1 = 1.0, tols[] = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
  const int ntol = (int)(sizeof tols / sizeof tols[0]), reps = quick ? 3 : 7;
  const double slow = quick ? 5.0 : 20.0; // a configuration slower than this runs once
  FILE *fp = bench_csv_open(out, "dae_configs.csv",
                            "N,t1,rtol,config,what,status,wall_s,steps,rhs,jac,err,ratio_to_best");
  chain_model m;
  double *ref = malloc(2 * (size_t)N * sizeof(double)), *r = malloc(2 * (size_t)N * sizeof(double));
  if (!fp || !ref || !r || chain_build(N, 1, &m)) {
    if (fp) fclose(fp);
    free(ref);
    free(r);
    return 1;
  }
  int rc = chain_reference(N, t1, ref);
  if (rc) fprintf(stderr, "dal_bench_dae: the reference failed (%d)\n", rc);
  printf("%-8s %-24s %10s %8s %8s %6s %9s %7s\n", "rtol", "config", "wall (s)", "steps", "rhs",
         "jac", "error", "/best");
  for (int ti = 0; ti < ntol && !rc; ++ti) {
    double walls[NCONF][16], err[NCONF], med[NCONF];
    dal_stats stats[NCONF];
    int status[NCONF], nrun[NCONF];
    char what[NCONF][64];
    memset(nrun, 0, sizeof nrun);
    // interleaved: repetition k of every configuration before repetition k + 1 of any
    for (int k = 0; k < reps; ++k)
      for (int c = 0; c < NCONF; ++c) {
        if (k > 0 && (status[c] || walls[c][0] > slow)) continue;
        dal_solve_opts o;
        config_opts(&configs[c], tols[ti], &o);
        int s = chain_reset(&m);
        double w0 = bench_now();
        if (!s) s = dal_advance(m.sys, m.st, &o, t1);
        walls[c][nrun[c]++] = bench_now() - w0;
        if (k == 0) {
          status[c] = s;
          dal_state_stats(m.st, &stats[c]);
          chain_positions(&m, r);
          err[c] = s ? NAN : bench_maxdiff(r, ref, 2 * N);
          snprintf(what[c], sizeof what[c], "%s", configs[c].name);
        }
      }
    // what the default ran as: the forced configuration with the same statistics and error
    snprintf(what[0], sizeof what[0], "?");
    for (int c = 1; c < NCONF; ++c)
      if (!status[c] && !status[0] && stats[c].steps == stats[0].steps &&
          stats[c].rhs_evals == stats[0].rhs_evals && stats[c].jac_evals == stats[0].jac_evals &&
          stats[c].rejected == stats[0].rejected && err[c] == err[0]) {
        snprintf(what[0], sizeof what[0], "%s", configs[c].name);
        break;
      }
    double best = INFINITY;
    int ib = -1;
    for (int c = 0; c < NCONF; ++c) {
      med[c] = bench_median(walls[c], nrun[c]);
      if (!configs[c].dflt && !status[c] && med[c] < best) best = med[c], ib = c;
    }
    for (int c = 0; c < NCONF; ++c) {
      printf("%-8.0e %-24s %10.4g %8ld %8ld %6ld %9.2e %7.2f%s\n", tols[ti], configs[c].name,
             med[c], stats[c].steps, stats[c].rhs_evals, stats[c].jac_evals, err[c], med[c] / best,
             status[c] ? " FAILED" : "");
      fprintf(fp, "%d,%g,%g,%s,%s,%d,%.6g,%ld,%ld,%ld,%.3g,%.4f\n", N, t1, tols[ti],
              configs[c].name, what[c], status[c], med[c], stats[c].steps, stats[c].rhs_evals,
              stats[c].jac_evals, err[c], med[c] / best);
    }
    printf("rtol %.0e: default (runs as %s) / best (%s) = %.2f\n\n", tols[ti], what[0],
           ib >= 0 ? configs[ib].name : "-", med[0] / best);
    fflush(stdout);
  }
  chain_free(&m);
  free(ref);
  free(r);
  fclose(fp);
  return rc ? 1 : 0;
}

int main(int argc, char **argv) {
  if (argc > 1 && strcmp(argv[1], "ir") == 0) return mode_ir(argc - 2, argv + 2);
  if (argc > 1 && strcmp(argv[1], "configs") == 0) return mode_configs(argc - 2, argv + 2);
  if (argc > 1 && strcmp(argv[1], "scaling") == 0) return mode_scaling(argc - 2, argv + 2);
  fprintf(stderr, "usage: dal_bench_dae ir ... | configs ... | scaling ...\n");
  return 2;
}
