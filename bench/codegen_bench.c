// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Generated code against the peers: one scene integrated by DOPRI5 (rtol 1e-8, atol 1e-10)
// from t = 0 to T by each route, for instruction counts per integrated second.
//
//   dal_bench_codegen SCENE ROUTE T
//     SCENE: pendulum (driven) | bead | double | spherical | chain8 | chain16
//     ROUTE: c      the built-in C jet primitives (dal_map_pendulum, dal_map_ring,
//                   dal_map_hanging, dal_map_spherical)
//            scene  the scene file (examples/scenes/, or the text below), formulas by bytecode
//            native the scene with native formulas (dal_scene_native, opts.eom = 0)
//            eom    the scene with native formulas and compiled equations of motion
//                   (dal_scene_native's default; compiled beforehand)
//            sympy  SymPy's equations printed as C (bench/sympy_eom.py) through the same ARKODE
//                   Dormand-Prince at the same tolerances (bench/hand.c)
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
int sympy_chain2(double t, const double *y, double *ydot, void *ctx);
int sympy_chain8(double t, const double *y, double *ydot, void *ctx);
int sympy_chain16(double t, const double *y, double *ydot, void *ctx);
int sympy_spherical(double t, const double *y, double *ydot, void *ctx);

#define RTOL 1e-8
#define ATOL 1e-10
#define MAXN 16

static void die(const char *what, const char *msg) {
  fprintf(stderr, "dal_bench_codegen: %s: %s\n", what, msg);
  exit(1);
}

// the scenes: kind 0 driven pendulum, 1 bead, 2 chain of N links (the double pendulum is N = 2),
// 3 spherical pendulum
typedef struct scene {
  const char *name;
  int kind, n;
} scene;

static const scene scenes[] = {{"pendulum", 0, 1},  {"bead", 1, 1},   {"double", 2, 2},
                               {"spherical", 3, 2}, {"chain8", 2, 8}, {"chain16", 2, 16}};

// the C jets route: the same scene by built-in primitives
static dal_system *c_system(const scene *sc) {
  dal_builder *b;
  dal_system *sys;
  int q[MAXN], p[MAXN];
  dal_builder_create(sc->kind == 1 || sc->kind == 3 ? 3 : 2, &b);
  for (int i = 0; i < sc->n; ++i) {
    char nm[16];
    snprintf(nm, sizeof nm, "q%d", i);
    dal_builder_add_coord(b, nm, &q[i]);
  }
  double pend[7] = {1, 0, 0, 0, 0.1, 6.2609903369994111, 0}, ring[3] = {1, 2, 0};
  double still[7] = {1, 0, 0, 0, 0, 0, 0}, l[1] = {1}, sph[4] = {1, 0, 0, 0};
  for (int k = 0; k < (sc->kind == 2 ? sc->n : 1); ++k) {
    char nm[16];
    snprintf(nm, sizeof nm, "b%d", k);
    dal_builder_add_particle(b, nm, 1.0, &p[k]);
    dal_place_def d = dal_default_place_def();
    d.coords = sc->kind == 3 ? q : &q[k];
    d.ncoords = sc->kind == 3 ? 2 : 1;
    if (sc->kind == 0) d.prim = &dal_map_pendulum, d.param_list = pend, d.nparam_list = 7;
    if (sc->kind == 1) d.prim = &dal_map_ring, d.param_list = ring, d.nparam_list = 3;
    if (sc->kind == 3) d.prim = &dal_map_spherical, d.param_list = sph, d.nparam_list = 4;
    if (sc->kind == 2 && k == 0)
      d.prim = &dal_map_pendulum, d.param_list = still, d.nparam_list = 7;
    if (sc->kind == 2 && k > 0)
      d.prim = &dal_map_hanging, d.param_list = l, d.nparam_list = 1, d.parent = p[k - 1];
    if (dal_builder_place_def(b, p[k], &d)) die("place", dal_builder_errmsg(b));
  }
  double g3[3] = {0, 0, -9.81}, g2[2] = {0, sc->kind == 0 ? -9.8 : -9.81};
  dal_builder_set_gravity(b, sc->kind == 1 || sc->kind == 3 ? g3 : g2);
  if (dal_builder_compile(b, &sys)) die("compile", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return sys;
}

// the scene file of a chain or the spherical pendulum (the same model as c_system), malloc'd
static char *scene_text(const scene *sc) {
  size_t cap = 8192;
  char *s = malloc(cap);
  int k = 0;
  if (sc->kind == 3) {
    k = snprintf(s, cap,
                 "dim 3\nparam m = 1\nparam l = 1\nparam g = 9.81\ncoord q0\ncoord q1\n"
                 "particle b0 mass=m\n"
                 "place b0 = l*sin(q0)*cos(q1); l*sin(q0)*sin(q1); -l*cos(q0)\n"
                 "gravity 0 0 -g\n");
    return s;
  }
  k += snprintf(s + k, cap - (size_t)k, "dim 2\nparam m = 1\nparam l = 1\nparam g = 9.81\n");
  for (int i = 0; i < sc->n; ++i)
    k += snprintf(s + k, cap - (size_t)k, "coord q%d\nparticle b%d mass=m\n", i, i);
  k += snprintf(s + k, cap - (size_t)k, "place b0 = l*sin(q0); -l*cos(q0)\n");
  for (int i = 1; i < sc->n; ++i)
    k += snprintf(s + k, cap - (size_t)k,
                  "place b%d parent=b%d = x_b%d + l*sin(q%d); y_b%d - l*cos(q%d)\n", i, i - 1,
                  i - 1, i, i - 1, i);
  snprintf(s + k, cap - (size_t)k, "gravity 0 -g\n");
  return s;
}

int main(int argc, char **argv) {
  const scene *sc = NULL;
  for (size_t i = 0; argc == 4 && i < sizeof scenes / sizeof *scenes; ++i)
    if (!strcmp(argv[1], scenes[i].name)) sc = &scenes[i];
  if (!sc) {
    fprintf(stderr, "usage: dal_bench_codegen pendulum|bead|double|spherical|chain8|chain16 "
                    "c|scene|native|eom|sympy T\n");
    return 64;
  }
  const char *route = argv[2];
  int n = sc->n;
  double T = atof(argv[3]), y[2 * MAXN] = {0};
  // the start: the pendulum at 1 rad, the bead at 0.5, the chains at 0.3 rad per link (not
  // chaotic: every route takes the same steps), the spherical pendulum at 1 rad turning
  for (int i = 0; i < n; ++i)
    y[i] = sc->kind == 0 ? 1.0 : sc->kind == 1 ? 0.5 : 0.3;
  if (sc->kind == 3) y[0] = 1.0, y[1] = 0.0, y[2] = 0.0, y[3] = 1.5;
  if (!strcmp(route, "sympy")) {
    // the library's local tolerances (its calibration factor on rtol and atol): the same steps
    dal_system *cs = c_system(sc);
    dal_state *cst;
    dal_state_create(cs, &cst);
    dal_state_set(cs, cst, 0.0, y, y + n);
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
    // p: (m, l, g, a, w), (m, R, g, w), (m, l, g): the values of the scenes
    double pd[5] = {1, 1, 9.8, 0.1, 6.2609903369994111}, pb[4] = {1, 1, 9.81, 2},
           pc[3] = {1, 1, 9.81};
    int (*fn)(double, const double *, double *, void *) = sc->kind == 0   ? sympy_driven
                                                          : sc->kind == 1 ? sympy_bead
                                                          : sc->kind == 3 ? sympy_spherical
                                                          : n == 2        ? sympy_chain2
                                                          : n == 8        ? sympy_chain8
                                                                          : sympy_chain16;
    hand_stats hs;
    int rc =
        hand_integrate(fn,
                       sc->kind == 0   ? pd
                       : sc->kind == 1 ? pb
                                       : pc,
                       2 * n, y, 0.0, T, DAL_METHOD_DOPRI5, f * RTOL, f * ATOL, 100000000, &hs);
    if (rc) die("sympy", "integration failed (or SymPy was capped: bench/sympy_eom.py)");
    printf("%s sympy T=%g q0 %.12f qd0 %.12f steps %ld rhs %ld\n", sc->name, T, y[0], y[n],
           hs.steps, hs.rhs_evals);
    return 0;
  }
  dal_scene *ss = NULL;
  dal_system *own = NULL;
  const dal_system *sys;
  char msg[600];
  if (!strcmp(route, "c")) {
    sys = own = c_system(sc);
  } else {
    if (sc->kind <= 1) {
      char path[600];
      snprintf(path, sizeof path, "%s/examples/scenes/%s.scene", DAL_SOURCE_DIR,
               sc->kind ? "bead_ring_below" : "driven_pendulum");
      if (dal_scene_read(path, &ss, msg, sizeof msg)) die(path, msg);
    } else {
      char *text = scene_text(sc);
      if (dal_scene_parse(text, sc->name, &ss, msg, sizeof msg)) die(sc->name, msg);
      free(text);
    }
    int eom = !strcmp(route, "eom");
    if (eom || !strcmp(route, "native")) {
      dal_codegen_opts o = dal_codegen_default_opts();
      o.eom = eom;
      if (dal_scene_native(ss, &o, msg, sizeof msg)) die("native", msg);
      if (eom && !dal_codegen_eom_attached(dal_scene_system(ss)))
        fprintf(stderr, "dal_bench_codegen: %s\n", msg);
    }
    sys = dal_scene_system(ss);
  }
  dal_state *st;
  dal_state_create(sys, &st);
  dal_state_set(sys, st, 0.0, y, y + n);
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_DOPRI5;
  o.rtol = RTOL;
  o.atol = ATOL;
  o.max_steps = 100000000;
  if (dal_advance(sys, st, &o, T)) die("advance", dal_state_errmsg(st));
  dal_stats s;
  dal_state_stats(st, &s);
  printf("%s %s T=%g q0 %.12f qd0 %.12f steps %ld rhs %ld\n", sc->name, route, T,
         dal_state_q(st)[0], dal_state_qdot(st)[0], s.steps, s.rhs_evals);
  dal_state_destroy(st);
  dal_system_destroy(own);
  dal_scene_destroy(ss);
  return 0;
}
