// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// dal_bench_cliff: the cost of one step of the N-link chain against N, in every formulation,
// to show where a switch of route (recursion or KKT matrix, dense or sparse) changes it.
//
// Usage: dal_bench_cliff [--fixed-h H] FORM ROUTE N [N ...]
//   FORM: ode (minimal coordinates, DOPRI5), ggl (Cartesian, IDA BDF), index1 (Cartesian,
//   IDA BDF), index3 (Cartesian, IDA BDF), index1-proj (Cartesian, DOPRI5 with projection),
//   index1-baumgarte (Cartesian, DOPRI5 with Baumgarte terms); ROUTE: auto, dense or
//   recursive (dal_builder_set_dynamics). For each N: the chain from bench/scenes.c (unit
//   masses and lengths, released at 45 degrees), advanced at rtol 1e-6 to t = 0.05 s (the
//   setup: consistent start, patterns, first factorizations), then from there to 0.25 s inside
//   cliff_region(). One CSV row per N on stdout (form, route, N, unknowns, steps, rhs,
//   status); under valgrind --tool=callgrind --toggle-collect='cliff_region*' the program asks
//   callgrind to dump its counts after each region (labelled rowK), so bench/cliff.sh can
//   divide the region's instructions by its steps.
//   --fixed-h H: every step of length H (h0 = hmin = hmax = H). IDA's adaptive runs vary from
//   one N to the next in Newton iterations per step (1.2 ... 2.9 residuals) and in how often the
//   Jacobian is refreshed; at a fixed step the work per step is the same at every N, so the
//   cost per step shows the code paths' own growth (bench/cliff.sh runs the IDA forms so too).
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <valgrind/callgrind.h>

#include "dalembert/dalembert.h"
#include "scenes.h"
#include "util.h"

#if defined(__GNUC__)
#define BENCH_NOINLINE __attribute__((noinline))
#else
#define BENCH_NOINLINE
#endif

#define T_SETUP 0.05
#define T_END 0.25

// the measured region: callgrind counts instructions only in here
static BENCH_NOINLINE int cliff_region(bench_model *m, const dal_solve_opts *o) {
  return dal_advance(m->sys, m->st, o, T_END);
}

static int form_opts(const char *form, dal_solve_opts *o) {
  static const struct {
    const char *name;
    bench_form f;
    dal_method m;
  } forms[] = {{"ode", BF_ODE, DAL_METHOD_DOPRI5},
               {"ggl", BF_GGL, DAL_METHOD_BDF},
               {"index1", BF_INDEX1, DAL_METHOD_BDF},
               {"index3", BF_INDEX3, DAL_METHOD_BDF},
               {"index1-proj", BF_INDEX1_PROJ, DAL_METHOD_DOPRI5},
               {"index1-baumgarte", BF_INDEX1_BAUMGARTE, DAL_METHOD_DOPRI5}};
  for (size_t i = 0; i < sizeof forms / sizeof forms[0]; ++i)
    if (strcmp(form, forms[i].name) == 0) {
      bench_opts(o, forms[i].f, forms[i].m, 1e-6);
      return forms[i].f == BF_ODE ? 0 : 1;
    }
  return -1;
}

int main(int argc, char **argv) {
  dal_solve_opts o;
  double fixed_h = 0;
  if (argc >= 3 && strcmp(argv[1], "--fixed-h") == 0) {
    fixed_h = atof(argv[2]);
    argv += 2;
    argc -= 2;
  }
  int redundant = argc >= 4 ? form_opts(argv[1], &o) : -1;
  dal_dynamics how = DAL_DYNAMICS_AUTO;
  if (argc >= 4 && strcmp(argv[2], "dense") == 0) how = DAL_DYNAMICS_DENSE;
  if (argc >= 4 && strcmp(argv[2], "recursive") == 0) how = DAL_DYNAMICS_RECURSIVE;
  if (redundant < 0) {
    fprintf(
        stderr,
        "usage: dal_bench_cliff [--fixed-h H] ode|ggl|index1|index3|index1-proj|index1-baumgarte "
        "auto|dense|recursive N [N ...]\n");
    return 2;
  }
  if (fixed_h > 0) o.h0 = o.hmax = fixed_h;
  printf("row,form,route,N,unknowns,steps,rhs,status\n");
  for (int a = 3; a < argc; ++a) {
    int N = atoi(argv[a]);
    bench_scene sc;
    scene_init(&sc, SC_CHAIN, N, T_END);
    bench_model m;
    char err[400];
    int rc = scene_model_route(&sc, redundant, how, &m, err, sizeof err);
    if (rc) {
      fprintf(stderr, "cliff %s N=%d: %s\n", argv[1], N, err);
      return 1;
    }
    rc = scene_model_reset(&m);
    if (!rc) rc = dal_advance(m.sys, m.st, &o, T_SETUP);
    dal_stats s0, s1;
    memset(&s0, 0, sizeof s0);
    memset(&s1, 0, sizeof s1);
    dal_state_stats(m.st, &s0);
    if (!rc) rc = cliff_region(&m, &o);
    dal_state_stats(m.st, &s1);
    int nc = dal_system_ncoords(m.sys), nr = dal_system_nconstraints(m.sys);
    printf("%d,%s,%s,%d,%d,%ld,%ld,%s\n", a - 3, argv[1], argv[2], N, nc + nr, s1.steps - s0.steps,
           s1.rhs_evals - s0.rhs_evals, dal_status_name(rc));
    fflush(stdout);
    char label[32];
    snprintf(label, sizeof label, "row%d", a - 3);
    CALLGRIND_DUMP_STATS_AT(label);
    scene_model_free(&m);
  }
  return 0;
}
