// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The C side of bench/python_bench.py: a scene's run from its initial state to t1 with an
// output every dt collected into arrays (t, q, qdot, positions, energies: what the Python
// package's monitor collects), repeated; prints the fastest repetition in seconds.
//   python_overhead SCENE T1 DT REPS
#define _POSIX_C_SOURCE 200809L
#include <dalembert/dalembert.h>
#include <dalembert/scene.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct rows {
  long cap, len;
  int n, k;
  double *t, *q, *qdot, *pos, *energy;
} rows;

// one output row, as the Python package's monitor writes it
static int collect(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  rows *r = ctx;
  if (r->len >= r->cap) return -1;
  long i = r->len;
  size_t n = (size_t)r->n, k = (size_t)r->k;
  r->t[i] = dal_state_time(st);
  memcpy(r->q + i * n, dal_state_q(st), n * sizeof(double));
  memcpy(r->qdot + i * n, dal_state_qdot(st), n * sizeof(double));
  const double *p = dal_state_positions(st);
  if (!p) return -1;
  memcpy(r->pos + i * k, p, k * sizeof(double));
  dal_energies e;
  if (dal_state_energies(st, &e)) return -1;
  double *E = r->energy + 4 * i;
  E[0] = e.E, E[1] = e.T, E[2] = e.U, E[3] = e.h;
  r->len++;
  return 0;
}

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(int argc, char **argv) {
  if (argc != 5) {
    fprintf(stderr, "usage: python_overhead SCENE T1 DT REPS\n");
    return 64;
  }
  double t1 = atof(argv[2]), dt = atof(argv[3]);
  int reps = atoi(argv[4]);
  char msg[1024];
  dal_scene *sc;
  if (dal_scene_read(argv[1], &sc, msg, sizeof msg)) {
    fprintf(stderr, "%s\n", msg);
    return 1;
  }
  const dal_system *sys = dal_scene_system(sc);
  const dal_solve_opts *o = dal_scene_opts(sc, NULL, NULL, NULL);
  int n = dal_system_ncoords(sys), k = dal_system_nparticles(sys) * dal_system_dim(sys);
  double best = INFINITY;
  int rc = 0;
  for (int rep = 0; rep < reps && !rc; ++rep) {
    double t0 = now();
    // as the package does per call: the state, the buffers, the run
    dal_state *st;
    rc = dal_scene_state(sc, &st);
    long cap = (long)floor(t1 / dt) + 2;
    rows r = {cap,
              0,
              n,
              k,
              malloc((size_t)cap * sizeof(double)),
              malloc((size_t)cap * (size_t)n * sizeof(double)),
              malloc((size_t)cap * (size_t)n * sizeof(double)),
              malloc((size_t)cap * (size_t)k * sizeof(double)),
              malloc((size_t)cap * 4 * sizeof(double))};
    if (!rc) rc = dal_evolve(sys, st, o, t1, dt, collect, &r);
    dal_state_destroy(st);
    free(r.t), free(r.q), free(r.qdot), free(r.pos), free(r.energy);
    double el = now() - t0;
    if (el < best) best = el;
  }
  dal_scene_destroy(sc);
  if (rc) {
    fprintf(stderr, "run failed: %s\n", dal_status_string(rc));
    return 1;
  }
  printf("%.9f\n", best);
  return 0;
}
