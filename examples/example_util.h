// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// What several examples share besides the library: the command line (--check, --out DIR), the
// output folder, the chart drawn by gnuplot and the builder's last step. Header only, so an
// example still builds alone: cc example.c -ldalembert -lm (the compiler finds this header
// beside the example).
#ifndef DAL_EXAMPLES_EXAMPLE_UTIL_H
#define DAL_EXAMPLES_EXAMPLE_UTIL_H

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "dalembert/dalembert.h"

// --check (the short mode ctest runs) and --out DIR (where the full mode writes; *dir keeps its
// default without it): returns 1 for --check
static inline int ex_args(int argc, char **argv, const char **dir) {
  int check = 0;
  for (int i = 1; i < argc; ++i) {
    if (strcmp(argv[i], "--check") == 0)
      check = 1;
    else if (strcmp(argv[i], "--out") == 0 && i + 1 < argc)
      *dir = argv[++i];
  }
  return check;
}

// the whole number after the option `name` (e.g. --threads 4), or def without it
static inline int ex_int_opt(int argc, char **argv, const char *name, int def) {
  for (int i = 1; i + 1 < argc; ++i)
    if (strcmp(argv[i], name) == 0) return atoi(argv[i + 1]);
  return def;
}

// creates the output folder (an existing one is fine): 0, or 1 with the reason on stderr
static inline int ex_make_dir(const char *dir) {
  if (mkdir(dir, 0777) == 0 || errno == EEXIST) return 0;
  fprintf(stderr, "cannot create %s: %s\n", dir, strerror(errno));
  return 1;
}

// runs gnuplot on the script gp, which draws png; says where the chart is, or why it is not
static inline void ex_gnuplot(const char *gp, const char *png) {
  if (system("command -v gnuplot >/dev/null 2>&1") != 0) {
    printf("gnuplot not found: chart skipped (script left in %s)\n", gp);
    return;
  }
  char cmd[1100];
  snprintf(cmd, sizeof cmd, "gnuplot '%s'", gp);
  if (system(cmd) == 0)
    printf("chart: %s\n", png);
  else
    printf("gnuplot failed: chart skipped (script in %s)\n", gp);
}

// the builder's last step: rc is the first failure of the calls before (0: none); returns the
// compiled system, or NULL with the builder's message on stderr; the builder is destroyed
static inline dal_system *ex_compile(dal_builder *b, int rc) {
  dal_system *sys = NULL;
  if (!rc) rc = dal_builder_compile(b, &sys);
  if (rc) fprintf(stderr, "build failed: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return rc ? NULL : sys;
}

// n free particles in dim = 2 or 3 dimensions, each placed by its Cartesian coordinates
// (dal_map_cartesian2 or 3): particle k is named pname[k], has mass m[k] and the coordinates
// cname[dim k ...]; their ids are written to p[k] and c[dim k ...]. Returns the first failure
static inline int ex_cartesian_particles(dal_builder *b, int dim, int n, const char *const *pname,
                                         const double *m, const char *const *cname, int *c,
                                         int *p) {
  int rc = 0;
  for (int i = 0; i < dim * n; ++i)
    if (!rc) rc = dal_builder_add_coord(b, cname[i], &c[i]);
  for (int k = 0; k < n; ++k)
    if (!rc) rc = dal_builder_add_particle(b, pname[k], m[k], &p[k]);
  for (int k = 0; k < n; ++k) {
    dal_place_def d = dal_default_place_def();
    d.prim = dim == 2 ? &dal_map_cartesian2 : &dal_map_cartesian3;
    d.coords = c + dim * k;
    d.ncoords = dim;
    if (!rc) rc = dal_builder_place_def(b, p[k], &d);
  }
  return rc;
}

// a pendulum in 2D: "bob" (mass m) on a rod l about the origin, in the angle "theta" from the
// downward vertical, the pivot driven along (ax, ay) cos(w t) (dal_map_pendulum), gravity g
// along -y; the compiled system, or NULL as ex_compile
static inline dal_system *ex_pendulum(double m, double l, double g, double ax, double ay,
                                      double w) {
  dal_builder *b = NULL;
  int th, bob, rc = dal_builder_create(2, &b);
  double grav[2] = {0, -g};
  if (!rc) rc = dal_builder_add_coord(b, "theta", &th);
  if (!rc) rc = dal_builder_add_particle(b, "bob", m, &bob);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_pendulum;
  pd.coords = &th;
  pd.ncoords = 1;
  pd.param[DAL_PENDULUM_L] = l;
  pd.param[DAL_PENDULUM_AX] = ax;
  pd.param[DAL_PENDULUM_AY] = ay;
  pd.param[DAL_PENDULUM_W] = w;
  if (!rc) rc = dal_builder_place_def(b, bob, &pd);
  if (!rc) rc = dal_builder_set_gravity(b, grav);
  return ex_compile(b, rc);
}

// Likharev's bead: "bead" (mass m) on a ring of radius R turning at w about the vertical, in the
// polar angle "theta" from the ring's bottom (dal_map_ring, 3D), gravity g along -z; the
// compiled system, or NULL as ex_compile
static inline dal_system *ex_ring_bead(double m, double R, double w, double g) {
  dal_builder *b = NULL;
  int th, bead, rc = dal_builder_create(3, &b);
  double grav[3] = {0, 0, -g};
  if (!rc) rc = dal_builder_add_coord(b, "theta", &th);
  if (!rc) rc = dal_builder_add_particle(b, "bead", m, &bead);
  dal_place_def pd = dal_default_place_def(); // the ring's plane starts at angle 0
  pd.prim = &dal_map_ring;
  pd.coords = &th;
  pd.ncoords = 1;
  pd.param[DAL_RING_R] = R;
  pd.param[DAL_RING_W] = w;
  if (!rc) rc = dal_builder_place_def(b, bead, &pd);
  if (!rc) rc = dal_builder_set_gravity(b, grav);
  return ex_compile(b, rc);
}

// opens dir/name for writing (its path in path[size]): the file, or NULL with a message
static inline FILE *ex_open(const char *dir, const char *name, char *path, size_t size) {
  snprintf(path, size, "%s/%s", dir, name);
  FILE *f = fopen(path, "w");
  if (!f) fprintf(stderr, "cannot write %s\n", path);
  return f;
}

// a state for each of the two routes to one scene (sys from particles, lag from its Lagrangian):
// 0, or 1 with FAILED printed and everything destroyed
static inline int ex_two_states(dal_system *sys, dal_system *lag, dal_state **st, dal_state **stl) {
  if (sys && lag && !dal_state_create(sys, st) && !dal_state_create(lag, stl)) return 0;
  printf("FAILED\n");
  dal_state_destroy(*st);
  dal_system_destroy(sys);
  dal_system_destroy(lag);
  return 1;
}

// one check of an example: 0 when ok holds, else 1 with "FAILED: " and the message printed
static inline int ex_expect(int ok, const char *fmt, ...) {
  if (ok) return 0;
  va_list ap;
  va_start(ap, fmt);
  printf("FAILED: ");
  vprintf(fmt, ap);
  printf("\n");
  va_end(ap);
  return 1;
}

// an example's verdict after fails failed checks: prints FAILED or the word ok ("ok" or "OK"),
// returns the exit status (1 or 0)
static inline int ex_verdict(int fails, const char *ok) {
  printf("%s\n", fails ? "FAILED" : ok);
  return fails ? 1 : 0;
}

#endif
