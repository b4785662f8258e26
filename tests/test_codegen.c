// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Generated code (dalembert/codegen.h) against the bytecode it replaces, and its cache.
//
// 1. Every example scene (examples/scenes/): each expression it makes, with native code
//    attached, equals the bytecode to the last bit (values and the three jet coefficients) at
//    random inputs, directions, times and parameters; the scene run writes the same CSV bytes.
// 2. 200 random expression models (formulas of + - * / ^, the twelve functions, atan2, hypot
//    over inputs, parameters, t and constants; 1-3 outputs): native equals bytecode bit for bit
//    at random jets, NaN where the bytecode has NaN.
// 3. The cache: a second attach loads the same object without compiling (its file unchanged);
//    an object changed after it was written, or put there without its sum file, is refused
//    and compiled again; a directory others may write to is refused (nothing attached); a
//    missing compiler (opts and the CC variable) leaves the bytecode running, with a message;
//    four processes compiling one entry at once all attach.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "expr/expr.h"
#include "scene/scene.h"
#include "test_codegen.h"

static unsigned long long seed = 0x9e3779b97f4a7c15ULL;
static double rnd(double lo, double hi) { return check_rand(&seed, lo, hi); }

// the same bits, or NaN in both
static int same(double a, double b) {
  if (isnan(a) || isnan(b)) return isnan(a) && isnan(b);
  return memcmp(&a, &b, sizeof a) == 0;
}

// native (e) against bytecode (ref) at k random points; returns the mismatches
static int compare(const dal_expr *e, const dal_expr *ref, int k, double lo, double hi) {
  int nin = e->tree.nin, np = e->tree.nparam, bad = 0;
  dal_jet in[64], a[16], b[16];
  double p[64];
  for (int r = 0; r < k; ++r) {
    for (int i = 0; i < nin && i < 64; ++i)
      in[i] = dal_jet_make3(rnd(lo, hi), rnd(-1, 1), rnd(-1, 1), rnd(-1, 1));
    for (int i = 0; i < np && i < 64; ++i)
      p[i] = r ? rnd(0.2, 2.0) : e->values[i];
    dal_jet t = dal_jet_make3(rnd(0, 5), r % 2 ? 1.0 : 0.0, 0.0, 0.0);
    CHECK(e->native != NULL);
    CHECK_OK(dal_expr_eval(e, in, t, p, a));
    CHECK_OK(dal_expr_eval(ref, in, t, p, b));
    for (int o = 0; o < e->nout; ++o)
      if (!same(a[o].v, b[o].v) || !same(a[o].d, b[o].d) || !same(a[o].dd, b[o].dd) ||
          !same(a[o].d3, b[o].d3)) {
        if (!bad)
          fprintf(stderr,
                  "%s output %d: native (%.17g %.17g %.17g %.17g) bytecode (%.17g %.17g "
                  "%.17g %.17g)\n",
                  e->name, o, a[o].v, a[o].d, a[o].dd, a[o].d3, b[o].v, b[o].d, b[o].dd, b[o].d3);
        ++bad;
      }
  }
  return bad;
}

// run a scene to its CSV in memory (a temporary file read back)
static char *run_csv(const dal_scene *sc, size_t *n) {
  FILE *f = tmpfile();
  CHECK(f != NULL);
  dal_state *st = NULL;
  char m[300];
  CHECK_OK(dal_scene_run(sc, f, &st, m, sizeof m));
  dal_state_destroy(st);
  long len = ftell(f);
  rewind(f);
  char *s = malloc((size_t)len + 1);
  *n = fread(s, 1, (size_t)len, f);
  fclose(f);
  return s;
}

static void example_scenes(void) {
  const char *files[] = {"driven_pendulum", "bead_ring_above", "bead_ring_below",
                         "sicm_oscillator"};
  for (size_t f = 0; f < sizeof files / sizeof *files; ++f) {
    char path[512], m[400];
    snprintf(path, sizeof path, "%s/examples/scenes/%s.scene", DAL_SOURCE_DIR, files[f]);
    dal_scene *a = NULL, *b = NULL;
    CHECK_OK(dal_scene_read(path, &a, m, sizeof m));
    CHECK_OK(dal_scene_read(path, &b, m, sizeof m));
    if (!a || !b) continue;
    // short runs: t1 cut to 2 (the CSV compare below); the formulas alone (the compiled
    // equations of motion agree to rounding only: tests/test_codegen_eom.c)
    dal_codegen_opts o = opts();
    o.eom = 0;
    int rc = dal_scene_native(b, &o, m, sizeof m);
    CHECK_MSG(rc == DAL_OK, "%s: %s", files[f], m);
    CHECK(a->nex == b->nex && a->nex > 0);
    int bad = 0;
    for (int i = 0; i < a->nex && i < b->nex; ++i)
      bad += compare(b->ex[i], a->ex[i], 200, -3.0, 3.0);
    CHECK_MSG(bad == 0, "%s: %d mismatches", files[f], bad);
    // the whole run: the same bytes (after a rebuild, which attaches again)
    CHECK_OK(dal_scene_set_param(a, a->pname[0], a->pval[0], m, sizeof m));
    CHECK_OK(dal_scene_set_param(b, b->pname[0], b->pval[0], m, sizeof m));
    CHECK(dal_codegen_attached(b->ex[b->nex - 1]) == 1);
    a->t1 = b->t1 = 2.0;
    size_t na, nb;
    char *ca = run_csv(a, &na), *cb = run_csv(b, &nb);
    CHECK_MSG(na == nb && na > 100 && !memcmp(ca, cb, na), "%s: CSV differs", files[f]);
    printf("%-16s %d expressions, native = bytecode bit for bit; run CSV %zu bytes identical\n",
           files[f], b->nex, na);
    free(ca);
    free(cb);
    dal_scene_destroy(a);
    dal_scene_destroy(b);
  }
}

// a random formula over x0..x3, p0, p1, t, depth at most d
static void formula(char *s, size_t len, int d) {
  static const char *const fn[] = {"sin",  "cos",  "tan",  "asin", "acos", "atan",
                                   "sinh", "cosh", "tanh", "exp",  "log",  "sqrt"};
  static const char *const leaf[] = {"x0", "x1", "x2", "x3", "p0", "p1", "t", "2", "0.5", "pi"};
  int k = d <= 0 ? 0 : (int)rnd(0, 10);
  char a[4096], b[4096];
  if (k < 2) {
    put(s, len, "%s", leaf[(int)rnd(0, 10)]);
  } else if (k < 6) {
    formula(a, sizeof a, d - 1);
    formula(b, sizeof b, d - 1);
    put(s, len, "(%s %c %s)", a, "+-*/"[k - 2], b);
  } else if (k < 7) {
    formula(a, sizeof a, d - 1);
    double e = (double)(int)rnd(-3, 4);
    if (rnd(0, 1) < 0.3) e = rnd(-2, 2);
    if (rnd(0, 1) < 0.2)
      put(s, len, "(%s)^p1", a);
    else if (rnd(0, 1) < 0.1)
      put(s, len, "p0^(%s)", a);
    else
      put(s, len, "(%s)^(%.3g)", a, e);
  } else if (k < 9) {
    formula(a, sizeof a, d - 1);
    put(s, len, "%s(%s)", fn[(int)rnd(0, 12)], a);
  } else {
    formula(a, sizeof a, d - 1);
    formula(b, sizeof b, d - 1);
    put(s, len, "%s(%s, %s)", rnd(0, 1) < 0.5 ? "atan2" : "hypot", a, b);
  }
}

#define NRAND 200

static void random_models(void) {
  static const char *const in[] = {"x0", "x1", "x2", "x3"}, *const pn[] = {"p0", "p1"};
  static char text[NRAND][3][4096];
  dal_expr *e[NRAND], *ref[NRAND];
  double pv[2] = {0.7, 1.3};
  char m[400];
  int made = 0;
  for (int i = 0; i < NRAND; ++i) {
    int nout = 1 + (int)rnd(0, 3);
    const char *f[3];
    for (int k = 0; k < nout; ++k) {
      formula(text[i][k], sizeof text[i][k], 1 + (int)rnd(0, 5));
      f[k] = text[i][k];
    }
    dal_expr_def d = dal_default_expr_def();
    d.name = "random";
    d.formulas = f;
    d.nout = nout;
    d.inputs = in;
    d.nin = 4;
    d.params = pn;
    d.nparam = 2;
    d.values = pv;
    CHECK_OK(dal_expr_create(&d, &e[i], m, sizeof m));
    CHECK_OK(dal_expr_create(&d, &ref[i], m, sizeof m));
    made += e[i] && ref[i];
  }
  CHECK(made == NRAND);
  if (made != NRAND) return;
  dal_codegen_opts o = opts();
  int rc = dal_codegen_attach(e, NRAND, &o, m, sizeof m);
  CHECK_MSG(rc == DAL_OK, "%s", m);
  int bad = 0;
  for (int i = 0; i < NRAND && !rc; ++i) {
    int b = compare(e[i], ref[i], 50, -2.0, 2.0);
    if (b) fprintf(stderr, "model %d: %s\n", i, text[i][0]);
    bad += b;
  }
  CHECK_MSG(bad == 0, "%d mismatches", bad);
  printf("%d random models: native = bytecode bit for bit at 50 points each\n", NRAND);
  for (int i = 0; i < NRAND; ++i) {
    dal_expr_destroy(e[i]);
    dal_expr_destroy(ref[i]);
  }
}

// one small expression and its cache entry's paths (found by listing the directory)
static dal_expr *small(void) {
  const char *f[] = {"sin(x)*l"}, *in[] = {"x"}, *pn[] = {"l"};
  double v[] = {2.0};
  dal_expr_def d = dal_default_expr_def();
  d.formulas = f;
  d.nout = 1;
  d.inputs = in;
  d.nin = 1;
  d.params = pn;
  d.nparam = 1;
  d.values = v;
  dal_expr *e = NULL;
  CHECK_OK(dal_expr_create(&d, &e, NULL, 0));
  return e;
}

static int value_ok(const dal_expr *e) {
  dal_jet x = dal_var(0.5, 1.0), y;
  dal_expr_eval(e, &x, dal_const(0.0), NULL, &y);
  return y.v == 2.0 * sin(0.5) && y.d == 2.0 * cos(0.5);
}

static void cache_rules(void) {
  char sub[300], so[400], sum[400], m[400];
  snprintf(sub, sizeof sub, "%s/rules", cache);
  dal_codegen_opts o = dal_codegen_default_opts();
  o.cache_dir = sub;
  dal_expr *e = small();
  if (!e) return;
  CHECK_OK(dal_codegen_attach(&e, 1, &o, m, sizeof m));
  CHECK(dal_codegen_attached(e) && value_ok(e));
  // the entry: the only .so in the directory
  char cmd[700];
  snprintf(cmd, sizeof cmd, "ls %s/*.so", sub);
  FILE *p = popen(cmd, "r");
  CHECK(p && fgets(so, sizeof so, p));
  if (p) pclose(p);
  so[strcspn(so, "\n")] = 0;
  snprintf(sum, sizeof sum, "%.*s.sum", (int)(strlen(so) - 3), so);
  struct stat s0, s1;
  CHECK(stat(so, &s0) == 0);
  // a second attach loads it as it is
  CHECK_OK(dal_codegen_attach(&e, 1, &o, m, sizeof m));
  CHECK(stat(so, &s1) == 0 && s1.st_ino == s0.st_ino && s1.st_mtime == s0.st_mtime);
  // an object changed after it was written: refused, compiled again
  FILE *f = fopen(so, "ab");
  CHECK(f && fputc(0, f) == 0);
  if (f) fclose(f);
  CHECK(stat(so, &s1) == 0 && s1.st_size == s0.st_size + 1);
  CHECK_OK(dal_codegen_attach(&e, 1, &o, m, sizeof m));
  CHECK(stat(so, &s1) == 0 && s1.st_size == s0.st_size && value_ok(e));
  // a file it did not write (no sum beside it): refused, compiled again
  CHECK(unlink(sum) == 0);
  f = fopen(so, "wb");
  CHECK(f && fputs("not an object", f) >= 0);
  if (f) fclose(f);
  CHECK_OK(dal_codegen_attach(&e, 1, &o, m, sizeof m));
  CHECK(stat(so, &s1) == 0 && s1.st_size == s0.st_size && value_ok(e));
  dal_expr_destroy(e);
  // a directory others may write to: refused, nothing attached
  e = small();
  CHECK(chmod(sub, 0777) == 0);
  int rc = dal_codegen_attach(&e, 1, &o, m, sizeof m);
  CHECK(rc == DAL_E_IO && strstr(m, "refused") && !dal_codegen_attached(e) && value_ok(e));
  printf("refused: %s\n", m);
  CHECK(chmod(sub, 0700) == 0);
  // a group-writable object: refused, compiled again
  CHECK(chmod(so, 0664) == 0);
  CHECK_OK(dal_codegen_attach(&e, 1, &o, m, sizeof m));
  CHECK(stat(so, &s1) == 0 && (s1.st_mode & 022) == 0 && value_ok(e));
  dal_expr_destroy(e);
  // no compiler: the bytecode runs, the message says so (opts, then the CC variable)
  e = small();
  o.cc = "/nonexistent/dalembert-cc";
  rc = dal_codegen_attach(&e, 1, &o, m, sizeof m);
  CHECK(rc == DAL_E_UNSUPPORTED && strstr(m, "no compiler") && !dal_codegen_attached(e));
  printf("no compiler: %s\n", m);
  o.cc = NULL;
  CHECK(setenv("CC", "/nonexistent/dalembert-cc", 1) == 0);
  rc = dal_codegen_attach(&e, 1, &o, m, sizeof m);
  CHECK(rc == DAL_E_UNSUPPORTED && !dal_codegen_attached(e) && value_ok(e));
  dal_expr_destroy(e);
  // a scene without a compiler runs on the bytecode
  char path[512];
  snprintf(path, sizeof path, "%s/examples/scenes/driven_pendulum.scene", DAL_SOURCE_DIR);
  dal_scene *sc = NULL;
  CHECK_OK(dal_scene_read(path, &sc, m, sizeof m));
  if (sc) {
    dal_codegen_opts so2 = opts();
    CHECK(dal_scene_native(sc, &so2, m, sizeof m) == DAL_E_UNSUPPORTED);
    CHECK(!dal_codegen_attached(sc->ex[0]));
    sc->t1 = 1.0;
    size_t n;
    free(run_csv(sc, &n));
    CHECK(n > 100);
    dal_scene_destroy(sc);
  }
  CHECK(unsetenv("CC") == 0);
}

// four processes compiling the same entry into a fresh cache at once: every one attaches
static void concurrent(void) {
  char sub[300];
  snprintf(sub, sizeof sub, "%s/race", cache);
  pid_t pid[4];
  for (int k = 0; k < 4; ++k) {
    pid[k] = fork();
    if (pid[k] == 0) {
      dal_codegen_opts o = dal_codegen_default_opts();
      o.cache_dir = sub;
      dal_expr *e = small();
      char m[400];
      int rc = e ? dal_codegen_attach(&e, 1, &o, m, sizeof m) : -1;
      if (rc) fprintf(stderr, "process %d: %s\n", k, m);
      int ok = !rc && value_ok(e);
      dal_expr_destroy(e);
      _exit(ok ? 0 : 1);
    }
  }
  int good = 0;
  for (int k = 0; k < 4; ++k) {
    int st;
    good += pid[k] > 0 && waitpid(pid[k], &st, 0) == pid[k] && WIFEXITED(st) && !WEXITSTATUS(st);
  }
  CHECK_MSG(good == 4, "%d of 4 processes attached", good);
  printf("4 processes compiling one entry at once: %d attached\n", good);
}

int main(void) {
  // a fresh private cache for this run
  cache_make();
  example_scenes();
  random_models();
  cache_rules();
  concurrent();
  cache_remove();
  return check_summary("test_codegen");
}
