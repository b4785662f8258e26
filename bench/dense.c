// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Benchmark: what output every 0.001 costs in dal_evolve (dense output) against one
// dal_advance to the end, for Bulirsch-Stoer, DOPRI5, Fehlberg 7(8) and Adams on a pendulum and
// a double pendulum.
//
// Each row runs both side by side, alternating, and keeps the median of the repeats; the
// ratio is evolve / advance, taken pair by pair (median and min-max over the repeats). Before dense
// output dal_evolve stepped to every output time (Bulirsch-Stoer: 47 steps to t = 10 alone, 10,000
// with output every 0.001, 30x the time). Two monitors: one reading q only (no model evaluation at
// the outputs), one reading the energies (one evaluation per output, like dal_csv_monitor). Usage:
// dal_bench_dense [repeats] (default 7); prints a table (markdown) and CSV rows.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "dalembert/dalembert.h"
#include "support/scenes.h"
#include "util.h"

// the pendulum (1 link) and the double pendulum (2) of the scene library
static dal_system *chain(int links) {
  scn_knobs k = scn_default();
  k.N = links;
  return scn_chain(&k);
}

// seconds for one run: mode 0 advance, 1 evolve reading q, 2 evolve reading the energies
static double one(const dal_system *s, dal_state *st, const dal_solve_opts *o, int mode,
                  long *steps, long *evals) {
  double q[2] = {2.0, 1.0}, qd[2] = {0, 0}, acc = 0, t1 = 10.0;
  dal_state_set(s, st, 0.0, q, qd);
  double t0 = bench_now();
  int rc = mode == 0   ? dal_advance(s, st, o, t1)
           : mode == 1 ? dal_evolve(s, st, o, t1, 0.001, scn_sum_q0, &acc)
                       : dal_evolve(s, st, o, t1, 0.001, scn_sum_energy, &acc);
  double dt = bench_now() - t0;
  if (rc) fprintf(stderr, "run failed: %s\n", dal_state_errmsg(st));
  dal_stats sts;
  dal_state_stats(st, &sts);
  *steps = sts.steps;
  *evals = sts.rhs_evals;
  return dt;
}

int main(int argc, char **argv) {
  int reps = argc > 1 ? atoi(argv[1]) : 7;
  if (reps < 1 || reps > 99) reps = 7;
  const dal_method ms[4] = {DAL_METHOD_BS, DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78,
                            DAL_METHOD_ADAMS};
  const double tols[2] = {1e-6, 1e-10};
  printf("| scene | method | rtol | steps | advance (ms) | evolve, q (ms) | ratio | evolve, "
         "energies (ms) | ratio |\n|---|---|---|---|---|---|---|---|---|\n");
  for (int links = 1; links <= 2; ++links) {
    dal_system *s = chain(links);
    dal_state *st = NULL;
    if (!s || dal_state_create(s, &st)) return 1;
    for (int mi = 0; mi < 4; ++mi)
      for (int ti = 0; ti < 2; ++ti) {
        dal_solve_opts o = dal_default_solve_opts();
        o.method = ms[mi];
        o.rtol = tols[ti];
        double t[3][99];
        long steps[3] = {0}, evals[3] = {0};
        for (int r = 0; r < reps; ++r)
          for (int mode = 0; mode < 3; ++mode)
            t[mode][r] = one(s, st, &o, mode, &steps[mode], &evals[mode]);
        double med[3], rq[99], re[99];
        for (int mode = 0; mode < 3; ++mode)
          med[mode] = bench_median(t[mode], reps);
        // the ratios pair by pair (adjacent runs share the machine's load), median (min-max)
        double lo[2] = {INFINITY, INFINITY}, hi[2] = {0, 0};
        for (int r = 0; r < reps; ++r) {
          rq[r] = t[1][r] / t[0][r];
          re[r] = t[2][r] / t[0][r];
          lo[0] = fmin(lo[0], rq[r]);
          hi[0] = fmax(hi[0], rq[r]);
          lo[1] = fmin(lo[1], re[r]);
          hi[1] = fmax(hi[1], re[r]);
        }
        double mq = bench_median(rq, reps), me = bench_median(re, reps);
        printf(
            "| %s | %s | %.0e | %ld | %.2f | %.2f | %.2f (%.2f-%.2f) | %.2f | %.2f (%.2f-%.2f) |\n",
            links == 1 ? "pendulum" : "double pendulum", dal_method_name(ms[mi]), tols[ti],
            steps[0], 1e3 * med[0], 1e3 * med[1], mq, lo[0], hi[0], 1e3 * med[2], me, lo[1], hi[1]);
        if (steps[1] != steps[0])
          printf("(steps differ: %ld with outputs, %ld without)\n", steps[1], steps[0]);
      }
    dal_state_destroy(st);
    dal_system_destroy(s);
  }
  return 0;
}
