// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// dal_bench_dense_ir: what output every 0.001 costs in dal_evolve against one dal_advance, in
// instructions, for every adaptive method (the wall-time twin is bench/dense.c).
//
// Usage: dal_bench_dense_ir [METHOD [SCENE]]   (only that method's rows, e.g. fehlberg78, or
//   every method's: all; only that scene's: oscillator, pendulum or double)
//   the pendulum and the double pendulum of bench/dense.c (released at 2 and 1 rad, to t = 10)
//   and the 2D oscillator of the scene library (m = k = 1, from (1, 0) at velocity (0, 0.5):
//   the cheap scene, whose plain advance takes 8 - 600 steps) by DOPRI5, Fehlberg 7(8),
//   Bulirsch-Stoer and Adams at rtol 1e-6 and 1e-10: one plain dal_advance, dal_evolve with a
//   monitor reading q only, and one reading the energies, each inside dense_region(). One CSV row
//   per run (scene, method, rtol, mode, steps, rhs); under valgrind --tool=callgrind
//   --toggle-collect='dense_region*' each run is followed by a dump of its counts (rowK), joined by
//   bench/cg_rows.sh (bench/dense_ir.sh).
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

// the pendulum (1 link) and the double pendulum (2) of the scene library, or (0) its oscillator
static dal_system *scene(int links) {
  scn_knobs k = scn_default();
  k.N = links;
  return links ? scn_chain(&k) : scn_oscillator(&k);
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
  static const char *names[] = {"oscillator", "pendulum", "double"};
  for (int links = 1; links <= 3; ++links) {
    if (argc > 2 && strcmp(argv[2], names[links % 3]) != 0) continue;
    dal_system *s = scene(links % 3);
    dal_state *st = NULL;
    if (!s || dal_state_create(s, &st)) return 1;
    for (size_t mi = 0; mi < sizeof ms / sizeof ms[0]; ++mi)
      for (size_t ti = 0; ti < sizeof tols / sizeof tols[0]; ++ti)
        for (int mode = 0; mode < 3; ++mode) {
          if (argc > 1 && strcmp(argv[1], "all") != 0 &&
              strcmp(argv[1], dal_method_name(ms[mi])) != 0)
            continue;
          dal_solve_opts o = dal_default_solve_opts();
          o.method = ms[mi];
          o.rtol = tols[ti];
          double q[2] = {2.0, 1.0}, qd[2] = {0, 0}, acc = 0;
          if (links == 3) q[0] = 1.0, q[1] = 0.0, qd[1] = 0.5;
          dal_state_set(s, st, 0.0, q, qd);
          int rc = dense_region(s, st, &o, mode, &acc);
          dal_stats sts;
          dal_state_stats(st, &sts);
          printf("%d,%s,%s,%.0e,%s,%ld,%ld,%s\n", row, names[links % 3], dal_method_name(ms[mi]),
                 tols[ti], modes[mode], sts.steps, sts.rhs_evals, dal_status_name(rc));
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
