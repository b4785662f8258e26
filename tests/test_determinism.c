// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Determinism: the same inputs give bit-identical trajectories, whatever the heap layout,
// whether the system is compiled afresh or a state is reused, and in another process.
//
// Scenes: a chaotic double pendulum with drag in minimal coordinates (every ODE method) and
// the same pendulum in Cartesian coordinates held by two rods (the DAE formulations). Each
// configuration is evolved three times in this process -- fresh system and state; a second,
// separately compiled system with the heap perturbed by live allocations of odd sizes; the
// first state reset by dal_state_set and run again -- and the recordings of (t, q, qdot,
// lambda) at every output time are compared with memcmp, as are the step statistics.
// A child process (this program with --hash) recomputes every recording under a different
// address-space layout; its FNV-1a hashes must equal ours.
#define _POSIX_C_SOURCE 200809L // popen
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "scenes_rel.h"

#define T_END 2.0
#define DT 0.05
#define CAP 20000

typedef struct config {
  const char *name;
  int dae;
  dal_method method;
  dal_formulation form;
  double rtol;
} config;

static const config configs[] = {
    {"ode dopri5", 0, DAL_METHOD_DOPRI5, DAL_FORM_ODE, 1e-9},
    {"ode fehlberg78", 0, DAL_METHOD_FEHLBERG78, DAL_FORM_ODE, 1e-10},
    {"ode bs", 0, DAL_METHOD_BS, DAL_FORM_ODE, 1e-10},
    {"ode rk4", 0, DAL_METHOD_RK4, DAL_FORM_ODE, 1e-8},
    {"ode adams", 0, DAL_METHOD_ADAMS, DAL_FORM_ODE, 1e-9},
    {"ode bdf", 0, DAL_METHOD_BDF, DAL_FORM_ODE, 1e-8},
    {"dae ggl (auto)", 1, DAL_METHOD_AUTO, DAL_FORM_AUTO, 1e-8},
    {"dae index1 + projection", 1, DAL_METHOD_DOPRI5, DAL_FORM_INDEX1, 1e-6},
    {"dae index1 bs", 1, DAL_METHOD_BS, DAL_FORM_INDEX1, 1e-8},
};
#define NCONFIG ((int)(sizeof configs / sizeof configs[0]))

typedef struct run {
  rel_rec rec;
  dal_stats stats;
  int rc;
} run;

static void run_free(run *r) { free(r->rec.buf); }

// evolve the configuration from a fixed initial state on st, recording every output
static run evolve(const config *c, const dal_system *sys, dal_state *st) {
  run r;
  memset(&r, 0, sizeof r);
  r.rec.cap = CAP;
  r.rec.buf = malloc(CAP * sizeof(double));
  r.rc = r.rec.buf ? rel_set(sys, st, c->dae, 2.0, -1.0, 0.5, 0.0) : DAL_E_NOMEM;
  dal_solve_opts o = dal_default_solve_opts();
  o.method = c->method;
  o.form = c->form;
  o.rtol = c->rtol;
  o.atol = c->rtol * 1e-2;
  o.fixed_step = 2e-3;
  o.project = 1;
  if (!r.rc) r.rc = dal_evolve(sys, st, &o, T_END, DT, rel_record, &r.rec);
  if (r.rc) fprintf(stderr, "%s: %s: %s\n", c->name, dal_status_name(r.rc), dal_state_errmsg(st));
  dal_state_stats(st, &r.stats);
  return r;
}

static run evolve_fresh(const config *c) {
  run r;
  memset(&r, 0, sizeof r);
  dal_system *sys = rel_double_pendulum(c->dae);
  dal_state *st = NULL;
  r.rc = sys ? dal_state_create(sys, &st) : DAL_E_ARG;
  if (!r.rc) r = evolve(c, sys, st);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  return r;
}

static uint64_t fnv1a(const void *p, size_t len) {
  const unsigned char *b = p;
  uint64_t h = 1469598103934665603ULL;
  for (size_t i = 0; i < len; ++i)
    h = (h ^ b[i]) * 1099511628211ULL;
  return h;
}

static int same_run(const run *a, const run *b) {
  return a->rc == b->rc && a->rec.len == b->rec.len &&
         memcmp(a->rec.buf, b->rec.buf, a->rec.len * sizeof(double)) == 0 &&
         a->stats.steps == b->stats.steps && a->stats.rhs_evals == b->stats.rhs_evals &&
         a->stats.rejected == b->stats.rejected;
}

int main(int argc, char **argv) {
  // child mode: print one hash per configuration
  if (argc > 1 && strcmp(argv[1], "--hash") == 0) {
    for (int i = 0; i < NCONFIG; ++i) {
      run r = evolve_fresh(&configs[i]);
      printf("%016" PRIx64 "\n", fnv1a(r.rec.buf, r.rec.len * sizeof(double)));
      run_free(&r);
    }
    return 0;
  }
  uint64_t hash[NCONFIG];
  for (int i = 0; i < NCONFIG; ++i) {
    const config *c = &configs[i];
    // run 1: fresh system and state
    dal_system *sys = rel_double_pendulum(c->dae);
    dal_state *st = NULL;
    CHECK(sys != NULL);
    CHECK_OK(dal_state_create(sys, &st));
    run r1 = evolve(c, sys, st);
    CHECK_MSG(r1.rc == DAL_OK, "%s: %s", c->name, dal_status_name(r1.rc));
    size_t rows = (size_t)(T_END / DT + 0.5) + 1;
    size_t width = 1 + 2 * (size_t)dal_system_ncoords(sys) + (size_t)dal_system_nconstraints(sys);
    CHECK_MSG(r1.rec.len == rows * width, "%s: %zu values recorded, expected %zu", c->name,
              r1.rec.len, rows * width);
    // the pendulum did move: the recording is not trivially constant
    if (r1.rec.len >= 2 * width)
      CHECK(memcmp(r1.rec.buf + 1, r1.rec.buf + r1.rec.len - width + 1,
                   (width - 1) * sizeof(double)) != 0);
    // run 2: another compiled system, the heap perturbed by live blocks of odd sizes
    void *junk[16];
    for (int k = 0; k < 16; ++k)
      junk[k] = malloc((size_t)(17 * k + 3 + 40 * i));
    run r2 = evolve_fresh(c);
    for (int k = 0; k < 16; ++k)
      free(junk[k]);
    // run 3: the first state reset and reused
    run r3 = evolve(c, sys, st);
    CHECK_MSG(same_run(&r1, &r2), "%s: a second system gives a different trajectory", c->name);
    CHECK_MSG(same_run(&r1, &r3), "%s: a reused state gives a different trajectory", c->name);
    hash[i] = fnv1a(r1.rec.buf, r1.rec.len * sizeof(double));
    printf("%-24s %s  %zu values, %ld steps, hash %016" PRIx64 "\n", c->name,
           dal_status_name(r1.rc), r1.rec.len, r1.stats.steps, hash[i]);
    run_free(&r1);
    run_free(&r2);
    run_free(&r3);
    dal_state_destroy(st);
    dal_system_destroy(sys);
  }
  // another process (another address-space layout) computes the same bits
  char cmd[4096];
  snprintf(cmd, sizeof cmd, "'%s' --hash", argv[0]);
  FILE *child = popen(cmd, "r");
  CHECK(child != NULL);
  if (child) {
    for (int i = 0; i < NCONFIG; ++i) {
      char line[64] = "";
      char mine[32];
      snprintf(mine, sizeof mine, "%016" PRIx64, hash[i]);
      CHECK_MSG(fgets(line, sizeof line, child) && strncmp(line, mine, 16) == 0,
                "%s: the child process computed hash %.16s, this one %s", configs[i].name, line,
                mine);
    }
    CHECK(pclose(child) == 0);
  }
  return check_summary("test_determinism");
}
