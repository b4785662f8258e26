// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// dal_bench_dense_ir: what output every 0.001 costs in dal_evolve against one dal_advance, in
// instructions, for every adaptive method (the wall-time twin is bench/dense.c).
//
// Usage: dal_bench_dense_ir [METHOD]   (METHOD: only that method's rows, e.g. fehlberg78)
//   the pendulum and the double pendulum of bench/dense.c (released at 2 and 1 rad, to t = 10)
//   by DOPRI5, Fehlberg 7(8), Bulirsch-Stoer and Adams at rtol 1e-6 and 1e-10: one plain
//   dal_advance, dal_evolve with a monitor reading q only, and one reading the energies, each
//   inside dense_region(). One CSV row per run (scene, method, rtol, mode, steps, rhs); under
//   valgrind --tool=callgrind --toggle-collect='dense_region*' each run is followed by a dump
//   of its counts (rowK), joined by bench/cg_rows.sh (bench/dense_ir.sh).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <valgrind/callgrind.h>

#include "dalembert/dalembert.h"

#if defined(__GNUC__)
#define BENCH_NOINLINE __attribute__((noinline))
#else
#define BENCH_NOINLINE
#endif

static dal_system *chain(int links) {
  dal_builder *b = NULL;
  dal_system *s = NULL;
  int rc = dal_builder_create(2, &b), prev = -1;
  double g[2] = {0.0, -9.81};
  for (int i = 0; i < links && !rc; ++i) {
    int c, p;
    char name[16];
    snprintf(name, sizeof name, "th%d", i + 1);
    rc = dal_builder_add_coord(b, name, &c);
    snprintf(name, sizeof name, "bob%d", i + 1);
    if (!rc) rc = dal_builder_add_particle(b, name, 1.0, &p);
    dal_place_def d = dal_default_place_def();
    d.coords = &c;
    d.ncoords = 1;
    if (prev < 0) {
      d.prim = &dal_map_pendulum;
      d.param[DAL_PENDULUM_L] = 1.0;
    } else {
      d.prim = &dal_map_hanging;
      d.parent = prev;
      d.param[DAL_HANGING_L] = 1.0;
    }
    if (!rc) rc = dal_builder_place_def(b, p, &d);
    prev = p;
  }
  if (!rc) rc = dal_builder_set_gravity(b, g);
  if (!rc) rc = dal_builder_compile(b, &s);
  if (rc) fprintf(stderr, "build: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return s;
}

static int read_q(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  *(double *)ctx += dal_state_q(st)[0];
  return 0;
}
static int read_energy(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  dal_energies e;
  if (dal_state_energies(st, &e)) return -1;
  *(double *)ctx += e.E;
  return 0;
}

// the measured region: mode 0 advance, 1 evolve reading q, 2 evolve reading the energies
static BENCH_NOINLINE int dense_region(const dal_system *s, dal_state *st, const dal_solve_opts *o,
                                       int mode, double *acc) {
  return mode == 0   ? dal_advance(s, st, o, 10.0)
         : mode == 1 ? dal_evolve(s, st, o, 10.0, 0.001, read_q, acc)
                     : dal_evolve(s, st, o, 10.0, 0.001, read_energy, acc);
}

int main(int argc, char **argv) {
  static const dal_method ms[] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_BS,
                                  DAL_METHOD_ADAMS};
  static const double tols[] = {1e-6, 1e-10};
  static const char *modes[] = {"advance", "evolve-q", "evolve-energies"};
  int row = 0;
  printf("row,scene,method,rtol,mode,steps,rhs,status\n");
  for (int links = 1; links <= 2; ++links) {
    dal_system *s = chain(links);
    dal_state *st = NULL;
    if (!s || dal_state_create(s, &st)) return 1;
    for (size_t mi = 0; mi < sizeof ms / sizeof ms[0]; ++mi)
      for (size_t ti = 0; ti < sizeof tols / sizeof tols[0]; ++ti)
        for (int mode = 0; mode < 3; ++mode) {
          if (argc > 1 && strcmp(argv[1], dal_method_name(ms[mi])) != 0) continue;
          dal_solve_opts o = dal_default_solve_opts();
          o.method = ms[mi];
          o.rtol = tols[ti];
          double q[2] = {2.0, 1.0}, qd[2] = {0, 0}, acc = 0;
          dal_state_set(s, st, 0.0, q, qd);
          int rc = dense_region(s, st, &o, mode, &acc);
          dal_stats sts;
          dal_state_stats(st, &sts);
          printf("%d,%s,%s,%.0e,%s,%ld,%ld,%s\n", row, links == 1 ? "pendulum" : "double",
                 dal_method_name(ms[mi]), tols[ti], modes[mode], sts.steps, sts.rhs_evals,
                 dal_status_name(rc));
          fflush(stdout);
          char label[32];
          snprintf(label, sizeof label, "row%d", row++);
          CALLGRIND_DUMP_STATS_AT(label);
        }
    dal_state_destroy(st);
    dal_system_destroy(s);
  }
  return 0;
}
