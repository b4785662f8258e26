// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Thread safety as documented: one compiled system shared read-only by several states that
// step in parallel threads gives bit-identical results to the same runs done serially.
//
// Two shared systems (the double pendulum in minimal coordinates and as a two-rod DAE), a
// const user-force context shared by all threads, and JOBS jobs that differ in initial state
// and method. The jobs run serially first (the reference), then all at once in JOBS threads
// released together by a barrier, twice; every recording of (t, q, qdot, lambda) and the
// step statistics must match the serial ones bit for bit. A library with hidden mutable
// state (a global workspace, a shared SUNDIALS context, a static buffer) fails this test, or
// trips ThreadSanitizer/ASan in the sanitizer build.
#define _POSIX_C_SOURCE 200809L // pthread_barrier_t
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "scenes_rel.h"

#define JOBS 6
#define CAP 20000

typedef struct job {
  const dal_system *sys;
  int dae;
  dal_method method;
  dal_formulation form;
  double th1;
  pthread_barrier_t *barrier;
  rel_rec rec;
  dal_stats stats;
  int rc;
  char err[256];
} job;

static void *run_job(void *arg) {
  job *j = arg;
  dal_state *st = NULL;
  j->rec.len = 0;
  j->rc = dal_state_create(j->sys, &st);
  if (j->barrier) pthread_barrier_wait(j->barrier);
  if (!j->rc) j->rc = rel_set(j->sys, st, j->dae, j->th1, -0.5, 0.0, 1.0);
  dal_solve_opts o = dal_default_solve_opts();
  o.method = j->method;
  o.form = j->form;
  o.rtol = 1e-8;
  o.atol = 1e-10;
  o.fixed_step = 2e-3;
  if (!j->rc) j->rc = dal_evolve(j->sys, st, &o, 1.5, 0.05, rel_record, &j->rec);
  if (st) {
    snprintf(j->err, sizeof j->err, "%s", dal_state_errmsg(st));
    dal_state_stats(st, &j->stats);
  }
  dal_state_destroy(st);
  return NULL;
}

int main(void) {
  dal_system *ode = rel_double_pendulum(0), *dae = rel_double_pendulum(1);
  CHECK(ode != NULL && dae != NULL);
  if (!ode || !dae) return check_summary("test_threads");
  const dal_method methods[] = {DAL_METHOD_DOPRI5, DAL_METHOD_BS,         DAL_METHOD_BDF,
                                DAL_METHOD_ADAMS,  DAL_METHOD_FEHLBERG78, DAL_METHOD_RK4};
  job ref[JOBS], par[JOBS];
  for (int i = 0; i < JOBS; ++i) {
    memset(&ref[i], 0, sizeof ref[i]);
    // odd jobs share the DAE system (GGL through IDA), even ones the ODE system
    ref[i].dae = i % 2;
    ref[i].sys = ref[i].dae ? dae : ode;
    ref[i].method = ref[i].dae ? DAL_METHOD_AUTO : methods[i % 6];
    ref[i].form = DAL_FORM_AUTO;
    ref[i].th1 = 0.5 + 0.3 * i;
    ref[i].rec.cap = CAP;
    ref[i].rec.buf = malloc(CAP * sizeof(double));
    CHECK(ref[i].rec.buf != NULL);
    par[i] = ref[i];
    par[i].rec.buf = malloc(CAP * sizeof(double));
    CHECK(par[i].rec.buf != NULL);
  }
  // serial reference
  for (int i = 0; i < JOBS; ++i) {
    run_job(&ref[i]);
    CHECK_MSG(ref[i].rc == DAL_OK, "job %d: %s: %s", i, dal_status_name(ref[i].rc), ref[i].err);
    CHECK(ref[i].rec.len > 0);
  }
  // parallel rounds
  for (int round = 0; round < 2; ++round) {
    pthread_barrier_t barrier;
    CHECK(pthread_barrier_init(&barrier, NULL, JOBS) == 0);
    pthread_t tid[JOBS];
    for (int i = 0; i < JOBS; ++i) {
      par[i].barrier = &barrier;
      CHECK(pthread_create(&tid[i], NULL, run_job, &par[i]) == 0);
    }
    for (int i = 0; i < JOBS; ++i)
      pthread_join(tid[i], NULL);
    pthread_barrier_destroy(&barrier);
    for (int i = 0; i < JOBS; ++i) {
      const job *a = &ref[i], *b = &par[i];
      int same = a->rc == b->rc && a->rec.len == b->rec.len &&
                 memcmp(a->rec.buf, b->rec.buf, a->rec.len * sizeof(double)) == 0 &&
                 a->stats.steps == b->stats.steps && a->stats.rhs_evals == b->stats.rhs_evals;
      CHECK_MSG(same, "round %d, job %d (%s, %s): the threaded run differs from the serial one",
                round, i, a->dae ? "dae" : "ode", dal_method_name(a->method));
    }
  }
  for (int i = 0; i < JOBS; ++i) {
    printf("job %d: %s %-10s %s, %zu values, %ld steps\n", i, ref[i].dae ? "dae" : "ode",
           dal_method_name(ref[i].method), dal_status_name(ref[i].rc), ref[i].rec.len,
           ref[i].stats.steps);
    free(ref[i].rec.buf);
    free(par[i].rec.buf);
  }
  dal_system_destroy(ode);
  dal_system_destroy(dae);
  return check_summary("test_threads");
}
