// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Ensemble benchmark: sweep speed-up over threads / MPI ranks, machinery overhead, schedules.
//
// The sweep: 256 trajectories of the driven pendulum (dal_map_pendulum, drive amplitude and
// frequency overridden per trajectory over a 16 x 16 grid), DOPRI5 at rtol 1e-8 to t = 20.
// Rows (CSV on stdout, one row per measurement; times are wall-clock seconds of the whole
// sweep, `reps` repetitions interleaved so that a change of machine load hits every
// configuration alike; min and median reported):
//   threads   1 and 2 threads (dynamic schedule, chunk 1)
//   overhead  a plain loop (one state: dal_state_set_param, dal_state_set, dal_advance) vs
//             dal_sweep_run on 1 thread, for the 256 trajectories above and for 256 short
//             ones (t = 0.01, a few steps: the machinery's cost per trajectory shows)
//   uneven    64 trajectories ten times longer than the other 192, placed first: static
//             (contiguous blocks) vs dynamic schedule on 2 threads
// Built with -DDAL_BENCH_MPI (target dal_bench_ensemble_mpi): the sweep over MPI ranks
// (dal_sweep_run_mpi, 1 thread per rank), timed on rank 0 between barriers; run it under
// mpirun -np 1 and -np 2 (bench/ensemble.sh).
// Usage: dal_bench_ensemble [reps] | dal_bench_ensemble loop|sweep <t1> [threads] (one pass: for
// callgrind and for whole-process timings paired run by run) | dal_bench_ensemble split <t1>
// <threads> (one sweep: each worker's thread CPU time, i.e. how evenly the pool splits the work)
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "dalembert/dalembert.h"
#include "support/scenes.h"
#ifdef DAL_BENCH_MPI
#include "dalembert/mpi.h"
#endif

enum { NT = 256 };

static dal_system *driven(void) {
  scn_knobs k = scn_default(); // a drive of zero amplitude at w = 1
  k.w = 1.0;
  return scn_pendulum(&k);
}

static int keep(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx) {
  (void)sys;
  (void)ctx;
  tr->result[0] = dal_state_q(st)[0];
  return 0;
}

static int cmp_d(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static void row(const char *name, const char *config, int reps, double *t, double base_min,
                double base_med) {
  qsort(t, (size_t)reps, sizeof(double), cmp_d);
  double mn = t[0], med = reps % 2 ? t[reps / 2] : 0.5 * (t[reps / 2 - 1] + t[reps / 2]);
  printf("%s,%s,%d,%.6f,%.6f,%.3f,%.3f\n", name, config, reps, mn, med,
         base_min > 0 ? base_min / mn : 1.0, base_med > 0 ? base_med / med : 1.0);
  fflush(stdout);
}

typedef struct setup {
  dal_system *sys;
  dal_param_ref par[2];
  double values[2 * NT], res[NT], q0, v0;
  int status[NT];
  dal_solve_opts so;
  dal_sweep sw;
} setup;

static int make(setup *s) {
  s->sys = driven();
  if (!s->sys) return 1;
  int count[2] = {16, 16};
  double lo[2] = {0.0, 2.0}, hi[2] = {0.3, 9.0};
  dal_sweep_grid(2, count, lo, hi, s->values);
  if (dal_param_find(s->sys, "place:bob:3", &s->par[0], NULL, 0) ||
      dal_param_find(s->sys, "place:bob:5", &s->par[1], NULL, 0))
    return 1;
  s->q0 = 0.4;
  s->v0 = 0.0;
  s->so = dal_default_solve_opts();
  s->so.method = DAL_METHOD_DOPRI5;
  s->so.rtol = 1e-8;
  dal_sweep sw = {.ntraj = NT,
                  .nparam = 2,
                  .params = s->par,
                  .values = s->values,
                  .q0 = &s->q0,
                  .qdot0 = &s->v0,
                  .solve = &s->so,
                  .t1 = 20.0,
                  .nresult = 1,
                  .reduce = keep};
  s->sw = sw;
  return 0;
}

#ifndef DAL_BENCH_MPI
static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

// uneven: the reducer advances trajectory i further, ten times as far for i < 64
static int uneven(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx) {
  const dal_solve_opts *so = ctx;
  int rc = dal_advance(sys, st, so, tr->index < 64 ? 20.0 : 2.0);
  tr->result[0] = dal_state_q(st)[0];
  return rc;
}

static double time_sweep(setup *s, const dal_sweep *sw, int threads, dal_schedule sched) {
  dal_sweep_out out = {s->res, s->status, NULL, 0, 0, 0};
  dal_sweep_opts o = dal_default_sweep_opts();
  o.nthreads = threads;
  o.schedule = sched;
  double t0 = now();
  int rc = dal_sweep_run(s->sys, sw, &o, &out, NULL, 0);
  double t = now() - t0;
  return rc || out.nfailed ? NAN : t;
}

// the CPU split of a threaded sweep: each worker's thread CPU time when it finished its last
// trajectory (load-independent: time a thread waits for a core is not CPU time)
static double thread_cpu(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

enum { MAXW = 64 };
typedef struct wclock {
  int id;
  long n;     // trajectories run
  double cpu; // thread CPU time after the last one
} wclock;
typedef struct split {
  double cpu[MAXW];
  long n[MAXW];
} split;

static int clock_create(const dal_system *sys, int id, void *ctx, void **data) {
  (void)sys;
  (void)ctx;
  wclock *c = calloc(1, sizeof *c);
  if (c) c->id = id;
  *data = c;
  return c ? 0 : DAL_E_NOMEM;
}

static void clock_destroy(void *data, void *ctx) {
  wclock *c = data;
  split *sp = ctx;
  if (c && c->id < MAXW) {
    sp->cpu[c->id] = c->cpu;
    sp->n[c->id] = c->n;
  }
  free(c);
}

static int keep_timed(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx) {
  wclock *c = tr->worker;
  c->cpu = thread_cpu();
  c->n++;
  return keep(sys, st, tr, ctx);
}

// one sweep on `threads` threads; prints each worker's CPU seconds and the speed-up that split
// allows on free cores (total / largest): the load balance, not a wall-clock speed-up
static int cpu_split(setup *s, double t1, int threads) {
  split sp;
  memset(&sp, 0, sizeof sp);
  dal_sweep sw = s->sw;
  sw.t1 = t1;
  sw.reduce = keep_timed;
  dal_sweep_out out = {s->res, s->status, NULL, 0, 0, 0};
  dal_sweep_opts o = dal_default_sweep_opts();
  o.nthreads = threads;
  o.worker_create = clock_create;
  o.worker_destroy = clock_destroy;
  o.worker_ctx = &sp;
  double c0 = thread_cpu(), w0 = now();
  int rc = dal_sweep_run(s->sys, &sw, &o, &out, NULL, 0);
  double wall = now() - w0;
  if (rc || out.nfailed) return 1;
  sp.cpu[0] -= c0; // worker 0 is this thread: its clock ran before the sweep
  double tot = 0.0, mx = 0.0;
  printf("split t1=%g threads=%d: worker CPU s (trajectories):", t1, threads);
  for (int w = 0; w < threads && w < MAXW; ++w) {
    printf(" %.3f (%ld)", sp.cpu[w], sp.n[w]);
    tot += sp.cpu[w];
    mx = fmax(mx, sp.cpu[w]);
  }
  printf("; total %.3f s, largest %.3f s: the split allows %.3fx on free cores; wall %.3f s\n", tot,
         mx, tot / mx, wall);
  return 0;
}

static double time_loop(setup *s, dal_state *st, double t1) {
  double t0 = now();
  for (int i = 0; i < NT; ++i) {
    dal_state_reset_params(s->sys, st);
    for (int j = 0; j < 2; ++j)
      dal_state_set_param(s->sys, st, &s->par[j], s->values[2 * i + j]);
    if (dal_state_set(s->sys, st, 0.0, &s->q0, &s->v0) || dal_advance(s->sys, st, &s->so, t1))
      return NAN;
    s->res[i] = dal_state_q(st)[0];
  }
  return now() - t0;
}

int main(int argc, char **argv) {
  int reps = argc > 1 ? atoi(argv[1]) : 7;
  if (reps < 1 || reps > 100) reps = 7;
  setup *s = calloc(1, sizeof *s);
  if (!s || make(s)) return 1;
  // one pass of the loop or the sweep to t1 (on `threads` threads, default 1): for instruction
  // counts under valgrind --tool=callgrind and for whole-process timings paired run by run
  // (bench/ensemble.sh): dal_bench_ensemble loop|sweep <t1> [threads]
  if (argc > 3 && !strcmp(argv[1], "split")) {
    int threads = atoi(argv[3]);
    int rc = threads < 1 || threads > MAXW || cpu_split(s, atof(argv[2]), threads);
    dal_system_destroy(s->sys);
    free(s);
    return rc;
  }
  if (argc > 2 && (!strcmp(argv[1], "loop") || !strcmp(argv[1], "sweep"))) {
    double t1 = atof(argv[2]);
    int threads = argc > 3 ? atoi(argv[3]) : 1;
    if (threads < 1 || threads > 64) threads = 1;
    dal_state *st1 = NULL;
    dal_sweep sw1 = s->sw;
    sw1.t1 = t1;
    int rc = dal_state_create(s->sys, &st1);
    double t = rc ? NAN
                  : (!strcmp(argv[1], "loop") ? time_loop(s, st1, t1)
                                              : time_sweep(s, &sw1, threads, DAL_SCHEDULE_DYNAMIC));
    printf("%s t1=%g threads=%d: %.6f s\n", argv[1], t1, threads, t);
    dal_state_destroy(st1);
    dal_system_destroy(s->sys);
    free(s);
    return isnan(t);
  }
  double *a = malloc((size_t)reps * 4 * sizeof(double));
  dal_state *st = NULL;
  if (!a || dal_state_create(s->sys, &st)) return 1;
  double *b = a + reps, *c = a + 2 * reps, *d = a + 3 * reps;
  printf("name,config,reps,min_s,median_s,speedup_min,speedup_median\n");
  // 1. threads: 1 and 2, interleaved
  for (int r = 0; r < reps; ++r) {
    a[r] = time_sweep(s, &s->sw, 1, DAL_SCHEDULE_DYNAMIC);
    b[r] = time_sweep(s, &s->sw, 2, DAL_SCHEDULE_DYNAMIC);
  }
  qsort(a, (size_t)reps, sizeof(double), cmp_d);
  double m1 = a[0], med1 = a[reps / 2];
  row("threads", "256 traj t=20 1 thread", reps, a, 0, 0);
  row("threads", "256 traj t=20 2 threads", reps, b, m1, med1);
  // 2. overhead: plain loop vs sweep on 1 thread, normal and short trajectories
  dal_sweep shortsw = s->sw;
  shortsw.t1 = 0.01;
  for (int r = 0; r < reps; ++r) {
    a[r] = time_loop(s, st, 20.0);
    b[r] = time_sweep(s, &s->sw, 1, DAL_SCHEDULE_DYNAMIC);
    c[r] = time_loop(s, st, 0.01);
    d[r] = time_sweep(s, &shortsw, 1, DAL_SCHEDULE_DYNAMIC);
  }
  qsort(a, (size_t)reps, sizeof(double), cmp_d);
  qsort(c, (size_t)reps, sizeof(double), cmp_d);
  double lm = a[0], lmed = a[reps / 2], sm = c[0], smed = c[reps / 2];
  row("overhead", "plain loop 256 traj t=20", reps, a, 0, 0);
  row("overhead", "sweep 1 thread 256 traj t=20", reps, b, lm, lmed);
  row("overhead", "plain loop 256 traj t=0.01", reps, c, 0, 0);
  row("overhead", "sweep 1 thread 256 traj t=0.01", reps, d, sm, smed);
  qsort(b, (size_t)reps, sizeof(double), cmp_d);
  qsort(d, (size_t)reps, sizeof(double), cmp_d);
  printf("# overhead per trajectory (sweep - loop) / 256, min and median: t=20: %.2f us, %.2f us;"
         " t=0.01: %.2f us, %.2f us\n",
         1e6 * (b[0] - lm) / NT, 1e6 * (b[reps / 2] - lmed) / NT, 1e6 * (d[0] - sm) / NT,
         1e6 * (d[reps / 2] - smed) / NT);
  // 3. uneven costs: static blocks vs dynamic on 2 threads (and 1 thread as the base)
  dal_sweep un = s->sw;
  un.solve = NULL;
  un.reduce = uneven;
  un.ctx = &s->so;
  for (int r = 0; r < reps; ++r) {
    a[r] = time_sweep(s, &un, 1, DAL_SCHEDULE_DYNAMIC);
    b[r] = time_sweep(s, &un, 2, DAL_SCHEDULE_STATIC);
    c[r] = time_sweep(s, &un, 2, DAL_SCHEDULE_DYNAMIC);
  }
  qsort(a, (size_t)reps, sizeof(double), cmp_d);
  m1 = a[0];
  med1 = a[reps / 2];
  row("uneven", "1 thread", reps, a, 0, 0);
  row("uneven", "2 threads static", reps, b, m1, med1);
  row("uneven", "2 threads dynamic", reps, c, m1, med1);
  dal_state_destroy(st);
  dal_system_destroy(s->sys);
  free(a);
  free(s);
  return 0;
}
#else
int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1, reps = argc > 1 ? atoi(argv[1]) : 7;
  if (reps < 1 || reps > 100) reps = 7;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  setup *s = calloc(1, sizeof *s);
  double *t = malloc((size_t)reps * sizeof(double));
  int bad = !s || !t || make(s);
  for (int r = 0; r < reps && !bad; ++r) {
    dal_sweep_out out = {s->res, s->status, NULL, 0, 0, 0};
    dal_sweep_opts o = dal_default_sweep_opts();
    MPI_Barrier(MPI_COMM_WORLD);
    double t0 = MPI_Wtime();
    bad |= dal_sweep_run_mpi(s->sys, &s->sw, &o, &out, MPI_COMM_WORLD, NULL, 0) != 0;
    MPI_Barrier(MPI_COMM_WORLD);
    t[r] = MPI_Wtime() - t0;
  }
  if (rank == 0 && !bad) {
    char cfg[64];
    snprintf(cfg, sizeof cfg, "256 traj t=20 %d rank%s 1 thread", size, size > 1 ? "s" : "");
    row("mpi", cfg, reps, t, 0, 0);
  }
  if (s) dal_system_destroy(s->sys);
  free(s);
  free(t);
  MPI_Finalize();
  return bad;
}
#endif
