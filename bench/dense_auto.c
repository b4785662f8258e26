// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// dal_bench_dense_auto: the work-precision table behind AUTO's choice for a run with outputs
// (dal_evolve with a monitor) on three and more coordinates, in instructions.
//
// Usage: dal_bench_dense_auto N [N ...]
//   the N-link chain of the scene library released at 0.3 rad per joint, to t = 10 with an
//   output every 0.001 (a monitor reading q), by DOPRI5, Fehlberg 7(8), Bulirsch-Stoer and
//   Adams at rtol 1e-5 ... 1e-9 (default atol), each inside dense_auto_region(); the error is
//   the max-norm of q at t = 10 against Bulirsch-Stoer at rtol 1e-13 (computed first, outside
//   the region). One CSV row per run (row, N, method, rtol, status, err, rhs); under
//   valgrind --tool=callgrind --toggle-collect='dense_auto_region*' each run is followed by a
//   dump of its counts (rowK), joined by bench/cg_rows.sh.
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

static BENCH_NOINLINE int dense_auto_region(const dal_system *s, dal_state *st,
                                            const dal_solve_opts *o, double *acc) {
  return dal_evolve(s, st, o, 10.0, 0.001, scn_sum_q0, acc);
}

int main(int argc, char **argv) {
  static const dal_method ms[] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_BS,
                                  DAL_METHOD_ADAMS};
  static const double tols[] = {1e-5, 1e-6, 1e-7, 1e-8, 1e-9};
  if (argc < 2) {
    fprintf(stderr, "usage: dal_bench_dense_auto N [N ...]\n");
    return 2;
  }
  int row = 0;
  printf("row,N,method,rtol,status,err,rhs\n");
  for (int a = 1; a < argc; ++a) {
    scn_knobs k = scn_default();
    k.N = atoi(argv[a]);
    dal_system *s = scn_chain(&k);
    dal_state *st = NULL;
    if (!s || dal_state_create(s, &st)) return 1;
    int n = dal_system_ncoords(s);
    double *q0 = calloc((size_t)n, sizeof *q0), *v0 = calloc((size_t)n, sizeof *v0);
    double *ref = calloc((size_t)n, sizeof *ref);
    if (!q0 || !v0 || !ref) return 1;
    for (int i = 0; i < n; ++i)
      q0[i] = 0.3;
    dal_solve_opts o = dal_default_solve_opts();
    o.method = DAL_METHOD_BS;
    o.rtol = 1e-13;
    if (dal_state_set(s, st, 0, q0, v0) || dal_advance(s, st, &o, 10.0)) return 1;
    memcpy(ref, dal_state_q(st), (size_t)n * sizeof *ref);
    for (size_t mi = 0; mi < sizeof ms / sizeof ms[0]; ++mi)
      for (size_t ti = 0; ti < sizeof tols / sizeof tols[0]; ++ti) {
        o = dal_default_solve_opts();
        o.method = ms[mi];
        o.rtol = tols[ti];
        double acc = 0, e = 0;
        dal_state_set(s, st, 0, q0, v0);
        int rc = dense_auto_region(s, st, &o, &acc);
        for (int i = 0; i < n; ++i)
          e = fmax(e, fabs(dal_state_q(st)[i] - ref[i]));
        dal_stats sts;
        dal_state_stats(st, &sts);
        printf("%d,%d,%s,%.0e,%s,%.3e,%ld\n", row, k.N, dal_method_name(ms[mi]), tols[ti],
               dal_status_name(rc), rc ? NAN : e, sts.rhs_evals);
        fflush(stdout);
        char label[32];
        snprintf(label, sizeof label, "row%d", row++);
        CALLGRIND_DUMP_STATS_AT(label);
      }
    free(q0);
    free(v0);
    free(ref);
    dal_state_destroy(st);
    dal_system_destroy(s);
  }
  return 0;
}
