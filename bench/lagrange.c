// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// dal_bench_lagrange: the Lagrangian route (dal_builder_set_lagrangian) against the particle
// route for the same scene, in instructions.
//
// Usage: dal_bench_lagrange [ROW]   (ROW: run only that one, without dumps, for profiles)
//   SICM's harmonic oscillator (2D, m = 2, k = 1, to t = 10) and driven pendulum (pivot
//   driven along y by a cos(w t), a = 0.1, w = 2 sqrt(g/l), g = 9.8, to t = 10), each stated as
//   particles (a Cartesian particle with a spring; a pendulum map with a moving support) and as
//   a Lagrangian L(t, q, qdot) over jets, advanced by DOPRI5 and Bulirsch-Stoer at rtol 1e-8
//   inside lagrange_region(). One CSV row per run on stdout (scene, route, method, rhs, steps,
//   max |q - q_particle| at the end); under valgrind --tool=callgrind
//   --toggle-collect='lagrange_region*' each run is followed by a dump of its counts (rowK),
//   joined by bench/cg_rows.sh.
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

#define GRAV 9.8
#define HO_MASS 2.0
#define HO_K 1.0
#define DR_A 0.1
#define DR_W (2.0 * 3.1304951684997055) // 2 sqrt(g): the bench scene "driven"

// the oscillator: L = m/2 |v|^2 - k/2 |q|^2
static int ho_lagrangian(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet T = dal_scale(dal_add(dal_sq(v[0]), dal_sq(v[1])), 0.5 * HO_MASS);
  dal_jet U = dal_scale(dal_add(dal_sq(q[0]), dal_sq(q[1])), 0.5 * HO_K);
  *L = dal_sub(T, U);
  return 0;
}

// the driven pendulum (unit mass and length), support at (0, a cos(w t)) (SICM 1.6.2)
static int dr_lagrangian(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)ctx;
  dal_jet ys = dal_scale(dal_cos(dal_scale(t, DR_W)), DR_A);
  dal_jet ysd = dal_scale(dal_sin(dal_scale(t, DR_W)), -DR_A * DR_W);
  dal_jet T = dal_add(dal_sq(v[0]), dal_scale(dal_mul(dal_mul(ysd, v[0]), dal_sin(q[0])), 2.0));
  T = dal_scale(dal_add(T, dal_sq(ysd)), 0.5);
  dal_jet U = dal_scale(dal_sub(ys, dal_cos(q[0])), GRAV);
  *L = dal_sub(T, U);
  return 0;
}

static dal_system *build(int driven, int lagrange) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  int c[2], p, nc = driven ? 1 : 2, rc = dal_builder_create(2, &b);
  for (int i = 0; i < nc && !rc; ++i)
    rc = dal_builder_add_coord(b, i ? "y" : "x", &c[i]);
  if (lagrange) {
    if (!rc) rc = dal_builder_set_lagrangian(b, driven ? dr_lagrangian : ho_lagrangian, NULL);
  } else {
    if (!rc) rc = dal_builder_add_particle(b, "p", driven ? 1.0 : HO_MASS, &p);
    dal_place_def pd = dal_default_place_def();
    pd.coords = c;
    pd.ncoords = nc;
    if (driven) {
      pd.prim = &dal_map_pendulum;
      pd.param[DAL_PENDULUM_L] = 1.0;
      pd.param[DAL_PENDULUM_AY] = DR_A;
      pd.param[DAL_PENDULUM_W] = DR_W;
    } else {
      pd.prim = &dal_map_cartesian2;
    }
    if (!rc) rc = dal_builder_place_def(b, p, &pd);
    if (driven) {
      double g[2] = {0, -GRAV};
      if (!rc) rc = dal_builder_set_gravity(b, g);
    } else {
      dal_spring_def sd = dal_default_spring_def(); // anchored at the origin, rest length 0
      sd.a = p;
      sd.k = HO_K;
      if (!rc) rc = dal_builder_add_spring_def(b, &sd);
    }
  }
  if (!rc) rc = dal_builder_compile(b, &sys);
  if (rc) fprintf(stderr, "build failed: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return sys;
}

// the measured region: callgrind counts instructions only in here
static BENCH_NOINLINE int lagrange_region(dal_system *sys, dal_state *st, const dal_solve_opts *o,
                                          double t1) {
  return dal_advance(sys, st, o, t1);
}

int main(int argc, char **argv) {
  static const dal_method meths[] = {DAL_METHOD_DOPRI5, DAL_METHOD_BS};
  int row = 0, only = argc > 1 ? atoi(argv[1]) : -1;
  printf("row,scene,route,method,rhs,steps,diff\n");
  for (int driven = 0; driven < 2; ++driven)
    for (size_t mi = 0; mi < sizeof meths / sizeof meths[0]; ++mi) {
      double qend[2][2] = {{0}};
      for (int lag = 0; lag < 2; ++lag, ++row) {
        if (only >= 0 && row != only) continue;
        dal_system *sys = build(driven, lag);
        dal_state *st = NULL;
        if (!sys || dal_state_create(sys, &st)) return 1;
        double q0[2] = {1, 2}, v0[2] = {3, 4}, p0 = 0.2, w0 = 0.0;
        if (driven ? dal_state_set(sys, st, 0.0, &p0, &w0) : dal_state_set(sys, st, 0.0, q0, v0))
          return 1;
        dal_solve_opts o = dal_default_solve_opts();
        o.method = meths[mi];
        o.rtol = 1e-8;
        int rc = lagrange_region(sys, st, &o, 10.0);
        dal_stats s;
        dal_state_stats(st, &s);
        int n = driven ? 1 : 2;
        memcpy(qend[lag], dal_state_q(st), (size_t)n * sizeof(double));
        double d = 0.0;
        for (int i = 0; lag && i < n; ++i)
          d = fmax(d, fabs(qend[1][i] - qend[0][i]));
        printf("%d,%s,%s,%s,%ld,%ld,%.3e%s\n", row, driven ? "driven" : "oscillator",
               lag ? "lagrangian" : "particle", dal_method_name(meths[mi]), s.rhs_evals, s.steps, d,
               rc ? ",FAILED" : "");
        fflush(stdout);
        char label[32];
        snprintf(label, sizeof label, "row%d", row);
        if (only < 0) CALLGRIND_DUMP_STATS_AT(label);
        dal_state_destroy(st);
        dal_system_destroy(sys);
      }
    }
  return 0;
}
