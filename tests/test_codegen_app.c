// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// `dalembert compile` as a C program uses it: the sources the command wrote for the four
// example scenes (CMake runs it; the ctest codegen_standalone compiles each alone with
// -std=c11 -pedantic -Werror) are compiled into this program, and every function of their
// tables equals the library's expression (dal_scene_expr) to the last bit at random jets,
// times and parameters, with the default parameters when param is NULL.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"

#include "bead_ring_above.c"
#include "bead_ring_below.c"
#include "driven_pendulum.c"
#include "sicm_oscillator.c"

static unsigned long long seed = 0x51ed27c0ffee1234ULL;
static double rnd(double lo, double hi) { return check_rand(&seed, lo, hi); }

static int same(double a, double b) {
  if (isnan(a) || isnan(b)) return isnan(a) && isnan(b);
  return memcmp(&a, &b, sizeof a) == 0;
}

typedef int eval_fn(const dal_jet *in, dal_jet t, const double *param, dal_jet *out, void *ctx);

// entry i of a table: its counts and function, against expression i of the scene
static void check_one(const dal_expr *e, const char *name, int nin, int nout, int nparam,
                      eval_fn *fn) {
  CHECK(e != NULL && nin == dal_expr_nin(e) && nout == dal_expr_nout(e) &&
        nparam == dal_expr_nparam(e));
  if (!e || nin > 16 || nout > 16 || nparam > 32) return;
  dal_jet in[16], a[16], b[16];
  double p[32];
  int bad = 0;
  for (int r = 0; r < 100; ++r) {
    for (int i = 0; i < nin; ++i)
      in[i] = dal_jet_make3(rnd(-3, 3), rnd(-1, 1), rnd(-1, 1), rnd(-1, 1));
    for (int i = 0; i < nparam; ++i)
      p[i] = rnd(0.5, 2.0);
    dal_jet t = dal_jet_make3(rnd(0, 10), r % 2, 0, 0);
    const double *pp = r % 3 ? p : NULL; // NULL: the defaults on both sides
    CHECK(fn(in, t, pp, a, NULL) == 0);
    CHECK_OK(dal_expr_eval(e, in, t, pp, b));
    for (int k = 0; k < nout; ++k)
      bad += !same(a[k].v, b[k].v) || !same(a[k].d, b[k].d) || !same(a[k].dd, b[k].dd) ||
             !same(a[k].d3, b[k].d3);
  }
  CHECK_MSG(bad == 0, "%s: %d outputs differ", name, bad);
}

#define SCENE(file, prefix)                                                                        \
  do {                                                                                             \
    dal_scene *sc = NULL;                                                                          \
    char m[400];                                                                                   \
    CHECK_OK(dal_scene_read(DAL_SOURCE_DIR "/examples/scenes/" file ".scene", &sc, m, sizeof m));  \
    if (!sc) break;                                                                                \
    CHECK(prefix##_count == dal_scene_nexprs(sc));                                                 \
    for (int i = 0; i < prefix##_count; ++i)                                                       \
      check_one(dal_scene_expr(sc, i), prefix##_table[i].name, prefix##_table[i].nin,              \
                prefix##_table[i].nout, prefix##_table[i].nparam, prefix##_table[i].eval);         \
    printf("%-16s %d functions = the library's expressions bit for bit\n", file, prefix##_count); \
    dal_scene_destroy(sc);                                                                         \
  } while (0)

int main(void) {
  SCENE("driven_pendulum", driven_pendulum);
  SCENE("bead_ring_above", bead_ring_above);
  SCENE("bead_ring_below", bead_ring_below);
  SCENE("sicm_oscillator", sicm_oscillator);
  return check_summary("test_codegen_app");
}
