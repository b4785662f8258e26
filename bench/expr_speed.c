// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Expressions against C jets: the same scene placed by built-in primitives and by formulas,
// N right-hand sides (dal_forward at varying states) of each.
//
//   dal_bench_expr SCENE ROUTE N     SCENE: pendulum | bead | chain32; ROUTE: c | expr | native
//                                    (native: the expressions with dal_codegen_attach)
//
// Run under `valgrind --tool=cachegrind` at two N and take the difference of the instruction
// counts over the difference of N: instructions per right-hand side with the set-up removed
// (bench/expr_speed.sh does this and prints the table of docs/expressions.md).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "support/scenes.h"

static dal_expr *keep[64];
static int nkeep;

static dal_expr *mk(const char *const *f, int nout, const char *const *in, int nin,
                    const char *const *pn, const double *pv, int np) {
  dal_expr_def d = dal_default_expr_def();
  d.formulas = f;
  d.nout = nout;
  d.inputs = in;
  d.nin = nin;
  d.params = pn;
  d.values = pv;
  d.nparam = np;
  dal_expr *e;
  char msg[512];
  if (dal_expr_create(&d, &e, msg, sizeof msg)) {
    fprintf(stderr, "%s\n", msg);
    exit(1);
  }
  keep[nkeep++] = e;
  return e;
}

static dal_system *build(const char *scene, int expr) {
  dal_builder *b;
  dal_system *sys;
  int n = !strcmp(scene, "chain32") ? 32 : 1, dim = !strcmp(scene, "bead") ? 3 : 2;
  dal_builder_create(dim, &b);
  int q[32], p[32];
  for (int i = 0; i < n; ++i) {
    char nm[16];
    snprintf(nm, sizeof nm, "q%d", i);
    dal_builder_add_coord(b, nm, &q[i]);
    snprintf(nm, sizeof nm, "p%d", i);
    dal_builder_add_particle(b, nm, 1.0, &p[i]);
  }
  if (!strcmp(scene, "pendulum")) {
    double par[7] = {1, 0, 0, 0, 0.1, 6.26, 0};
    if (expr) {
      const char *f[] = {"l*sin(theta)", "a*cos(w*t) - l*cos(theta)"}, *in[] = {"theta"},
                 *pn[] = {"l", "a", "w"};
      double pv[] = {1, 0.1, 6.26};
      dal_expr *e = mk(f, 2, in, 1, pn, pv, 3);
      scn_place_by(b, p[0], dal_expr_primitive(e), -1, 1, q, 3, pv, e);
    } else {
      scn_place_by(b, p[0], &dal_map_pendulum, -1, 1, q, 7, par, NULL);
    }
  } else if (!strcmp(scene, "bead")) {
    double par[3] = {1, 5, 0};
    if (expr) {
      const char *f[] = {"R*sin(theta)*cos(w*t)", "R*sin(theta)*sin(w*t)", "-R*cos(theta)"},
                 *in[] = {"theta"}, *pn[] = {"R", "w"};
      dal_expr *e = mk(f, 3, in, 1, pn, par, 2);
      scn_place_by(b, p[0], dal_expr_primitive(e), -1, 1, q, 2, par, e);
    } else {
      scn_place_by(b, p[0], &dal_map_ring, -1, 1, q, 3, par, NULL);
    }
  } else {
    // a chain of 32 links of length 0.1: the first about the origin, each next from its parent
    double l = 0.1;
    const char *f0[] = {"l*sin(th)", "-l*cos(th)"}, *in0[] = {"th"}, *pn[] = {"l"};
    const char *f1[] = {"x + l*sin(th)", "y - l*cos(th)"}, *in1[] = {"x", "y", "th"};
    dal_expr *e0 = expr ? mk(f0, 2, in0, 1, pn, &l, 1) : NULL;
    dal_expr *e1 = expr ? mk(f1, 2, in1, 3, pn, &l, 1) : NULL;
    double par[7] = {l, 0, 0, 0, 0, 0, 0};
    for (int i = 0; i < n; ++i) {
      if (i == 0)
        scn_place_by(b, p[0], expr ? dal_expr_primitive(e0) : &dal_map_pendulum, -1, 1, q,
                     expr ? 1 : 7, par, e0);
      else
        scn_place_by(b, p[i], expr ? dal_expr_primitive(e1) : &dal_map_hanging, p[i - 1], 1, &q[i],
                     1, &l, e1);
    }
  }
  double g3[3] = {0, 0, -9.81}, g2[2] = {0, -9.81};
  dal_builder_set_gravity(b, dim == 3 ? g3 : g2);
  if (dal_builder_compile(b, &sys)) {
    fprintf(stderr, "%s\n", dal_builder_errmsg(b));
    exit(1);
  }
  dal_builder_destroy(b);
  return sys;
}

int main(int argc, char **argv) {
  if (argc != 4) {
    fprintf(stderr, "usage: dal_bench_expr pendulum|bead|chain32 c|expr N\n");
    return 64;
  }
  int native = !strcmp(argv[2], "native");
  dal_system *sys = build(argv[1], !strcmp(argv[2], "expr") || native);
  char msg[600];
  if (native && dal_codegen_attach(keep, nkeep, NULL, msg, sizeof msg)) {
    fprintf(stderr, "%s\n", msg);
    return 1;
  }
  long N = atol(argv[3]);
  int n = dal_system_ncoords(sys);
  dal_state *st;
  dal_state_create(sys, &st);
  double q[32], v[32], sum = 0;
  for (long k = 0; k < N; ++k) {
    for (int i = 0; i < n; ++i) {
      q[i] = 0.3 + 0.001 * (double)k + 0.01 * i;
      v[i] = -0.2 + 0.002 * (double)i;
    }
    dal_state_set(sys, st, 0.01 * (double)k, q, v);
    dal_forward(sys, st);
    sum += dal_state_qddot(st)[n - 1];
  }
  printf("%s %s N=%ld checksum %.17g\n", argv[1], argv[2], N, sum);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  for (int i = 0; i < nkeep; ++i)
    dal_expr_destroy(keep[i]);
  return 0;
}
