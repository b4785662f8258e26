// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Generated code against the peers: one scene integrated by DOPRI5 (rtol 1e-8, atol 1e-10)
// from t = 0 to T by each route, for instruction counts per integrated second.
//
//   dal_bench_codegen SCENE ROUTE T    SCENE: pendulum | bead
//     ROUTE: c      the built-in C jet primitives (dal_map_pendulum, dal_map_ring)
//            scene  the scene file (examples/scenes/), its formulas by the bytecode
//            native the scene file with native code (dal_scene_native; compiled beforehand)
//            sympy  SymPy's closed-form acceleration printed as C (bench/sympy_eom.py) through
//                   the same ARKODE Dormand-Prince at the same tolerances (bench/hand.c)
//
// bench/codegen.sh runs each under callgrind at two T and divides the difference of the
// instruction counts by the difference of T: instructions per integrated second, set-up (and
// the compiler run or the cache load) removed.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "hand.h"

int sympy_driven(double t, const double *y, double *ydot, void *ctx);
int sympy_bead(double t, const double *y, double *ydot, void *ctx);

#define RTOL 1e-8
#define ATOL 1e-10

static void die(const char *what, const char *msg) {
  fprintf(stderr, "dal_bench_codegen: %s: %s\n", what, msg);
  exit(1);
}

// the C jets route: the same scene by built-in primitives
static dal_system *c_system(int bead) {
  dal_builder *b;
  dal_system *sys;
  int q, p;
  dal_builder_create(bead ? 3 : 2, &b);
  dal_builder_add_coord(b, "theta", &q);
  dal_builder_add_particle(b, "bob", 1.0, &p);
  dal_place_def d = dal_default_place_def();
  double pend[7] = {1, 0, 0, 0, 0.1, 6.2609903369994111, 0}, ring[3] = {1, 2, 0};
  d.prim = bead ? &dal_map_ring : &dal_map_pendulum;
  d.coords = &q;
  d.ncoords = 1;
  d.param_list = bead ? ring : pend;
  d.nparam_list = bead ? 3 : 7;
  if (dal_builder_place_def(b, p, &d)) die("place", dal_builder_errmsg(b));
  double g3[3] = {0, 0, -9.81}, g2[2] = {0, -9.8};
  dal_builder_set_gravity(b, bead ? g3 : g2);
  if (dal_builder_compile(b, &sys)) die("compile", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return sys;
}

int main(int argc, char **argv) {
  if (argc != 4) {
    fprintf(stderr, "usage: dal_bench_codegen pendulum|bead c|scene|native|sympy T\n");
    return 64;
  }
  int bead = !strcmp(argv[1], "bead");
  const char *route = argv[2];
  double T = atof(argv[3]), y[2] = {bead ? 0.5 : 1.0, 0.0};
  if (!strcmp(route, "sympy")) {
    // the library's local tolerances (its calibration factor on rtol and atol): the same steps
    dal_system *cs = c_system(bead);
    dal_state *cst;
    dal_state_create(cs, &cst);
    dal_state_set(cs, cst, 0.0, &y[0], &y[1]);
    dal_solve_opts o = dal_default_solve_opts();
    o.method = DAL_METHOD_DOPRI5;
    o.rtol = RTOL;
    o.atol = ATOL;
    dal_advance(cs, cst, &o, 1e-3);
    dal_stats s;
    dal_state_stats(cst, &s);
    double f = s.rtol_used / RTOL;
    dal_state_destroy(cst);
    dal_system_destroy(cs);
    // p: (m, l, g, a, w) and (m, R, g, w), the values of the scene files
    double pd[5] = {1, 1, 9.8, 0.1, 6.2609903369994111}, pb[4] = {1, 1, 9.81, 2};
    hand_stats hs;
    int rc = hand_integrate(bead ? sympy_bead : sympy_driven, bead ? pb : pd, 2, y, 0.0, T,
                            DAL_METHOD_DOPRI5, f * RTOL, f * ATOL, 100000000, &hs);
    if (rc) die("sympy", "integration failed");
    printf("%s sympy T=%g theta %.12f thetadot %.12f steps %ld rhs %ld\n", argv[1], T, y[0], y[1],
           hs.steps, hs.rhs_evals);
    return 0;
  }
  dal_scene *sc = NULL;
  dal_system *own = NULL;
  const dal_system *sys;
  char msg[600];
  if (!strcmp(route, "c")) {
    sys = own = c_system(bead);
  } else {
    char path[600];
    snprintf(path, sizeof path, "%s/examples/scenes/%s.scene", DAL_SOURCE_DIR,
             bead ? "bead_ring_below" : "driven_pendulum");
    if (dal_scene_read(path, &sc, msg, sizeof msg)) die(path, msg);
    if (!strcmp(route, "native") && dal_scene_native(sc, NULL, msg, sizeof msg))
      die("native", msg);
    sys = dal_scene_system(sc);
  }
  dal_state *st;
  dal_state_create(sys, &st);
  dal_state_set(sys, st, 0.0, &y[0], &y[1]);
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_DOPRI5;
  o.rtol = RTOL;
  o.atol = ATOL;
  o.max_steps = 100000000;
  if (dal_advance(sys, st, &o, T)) die("advance", dal_state_errmsg(st));
  dal_stats s;
  dal_state_stats(st, &s);
  printf("%s %s T=%g theta %.12f thetadot %.12f steps %ld rhs %ld\n", argv[1], route, T,
         dal_state_q(st)[0], dal_state_qdot(st)[0], s.steps, s.rhs_evals);
  dal_state_destroy(st);
  dal_system_destroy(own);
  dal_scene_destroy(sc);
  return 0;
}
