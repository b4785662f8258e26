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
#include "support/scenes.h"

#if defined(__GNUC__)
#define BENCH_NOINLINE __attribute__((noinline))
#else
#define BENCH_NOINLINE
#endif

// the pendulum (1 link) and the double pendulum (2) of the scene library
static dal_system *chain(int links) {
  scn_knobs k = scn_default();
  k.N = links;
  return scn_chain(&k);
}

// the measured region: mode 0 advance, 1 evolve reading q, 2 evolve reading the energies
static BENCH_NOINLINE int dense_region(const dal_system *s, dal_state *st, const dal_solve_opts *o,
                                       int mode, double *acc) {
  return mode == 0   ? dal_advance(s, st, o, 10.0)
         : mode == 1 ? dal_evolve(s, st, o, 10.0, 0.001, scn_sum_q0, acc)
                     : dal_evolve(s, st, o, 10.0, 0.001, scn_sum_energy, acc);
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
