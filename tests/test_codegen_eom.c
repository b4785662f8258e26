// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Compiled equations of motion (dal_codegen_attach_eom) against the general path.
//
// The bound, stated in dalembert/codegen.h: |qddot - qddot_general|_i <= 2^-45 (|qddot_i| +
// sum_j |(M^-1)_ij| (|Q_j| + |c_j|)), M, Q, c and qddot_general from dal_forward (which always
// runs the general path), M^-1 by Gauss-Jordan here.
// 1. Every example scene (all have minimal coordinates): at 100 random (t, q, qdot); with a
//    mass and gravity overridden per trajectory; and the whole run (t1 = 2) against the run
//    without them, final q and qdot within 1e-8.
// 2. 200 random models: 1-3 particles in 2-D or 3-D, 1-3 coordinates, placements by random
//    formulas of the coordinates, t and parameters (some relative to a parent), random gravity
//    and a random potential U(q): at 20 random states each.
// 3. The fallback, with its note: a spring, a constraint (not in reach), a formula too large
//    for the algebra (DAL_E_TOO_LARGE), no compiler (DAL_E_UNSUPPORTED): nothing attached, the
//    general path runs; at a state where M is singular the compiled function declines.
#define _POSIX_C_SOURCE 200809L
#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "check.h"
#include "codegen/codegen.h"
#include "dalembert/dalembert.h"
#include "scene/scene.h"
#include "test_codegen.h"

static unsigned long long seed = 0x51ed2701f00dULL;
static double rnd(double lo, double hi) { return check_rand(&seed, lo, hi); }

#define MAXN 8

// the compiled qddot against the general path's at the state's (t, q, qdot); the worst ratio
// of the difference to its bound
static double compare(const dal_system *sys, dal_state *st) {
  int n = dal_system_ncoords(sys);
  double fast[MAXN], A[MAXN][2 * MAXN];
  CHECK(n <= MAXN);
  CHECK_OK(dal_forward(sys, st));
  int rc = dal__eom_qddot(sys, st, dal_state_time(st), dal_state_q(st), dal_state_qdot(st), fast);
  CHECK_MSG(rc == 0, "the compiled equations declined at a regular state");
  const double *M = dal_state_mass_matrix(st), *Q = dal_state_genforces(st),
               *c = dal_state_bias(st), *a = dal_state_qddot(st);
  CHECK(M && Q && c && a);
  if (!M || !Q || !c || !a) return 1e9;
  // M^-1 by Gauss-Jordan with partial pivoting
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j)
      A[i][j] = j < n ? M[(size_t)j * n + i] : (j - n == i);
  for (int p = 0; p < n; ++p) {
    int best = p;
    for (int i = p + 1; i < n; ++i)
      if (fabs(A[i][p]) > fabs(A[best][p])) best = i;
    for (int j = 0; j < 2 * n; ++j) {
      double t = A[p][j];
      A[p][j] = A[best][j];
      A[best][j] = t;
    }
    double d = A[p][p];
    for (int j = 0; j < 2 * n; ++j)
      A[p][j] /= d;
    for (int i = 0; i < n; ++i)
      if (i != p) {
        double f = A[i][p];
        for (int j = 0; j < 2 * n; ++j)
          A[i][j] -= f * A[p][j];
      }
  }
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    double s = fabs(a[i]);
    for (int j = 0; j < n; ++j)
      s += fabs(A[i][n + j]) * (fabs(Q[j]) + fabs(c[j]));
    double r = fabs(fast[i] - a[i]) / (ldexp(1.0, -45) * s);
    if (!(r <= worst)) worst = r; // NaN counts as the worst
  }
  return worst;
}

// at k random states
static double compare_random(const dal_system *sys, dal_state *st, int k) {
  int n = dal_system_ncoords(sys);
  double q[MAXN], qd[MAXN], worst = 0.0;
  for (int r = 0; r < k; ++r) {
    for (int i = 0; i < n; ++i) {
      q[i] = rnd(-3, 3);
      qd[i] = rnd(-3, 3);
    }
    CHECK_OK(dal_state_set(sys, st, rnd(0, 5), q, qd));
    double w = compare(sys, st);
    if (!(w <= worst)) worst = w;
  }
  return worst;
}

static void example_scenes(void) {
  const char *files[] = {"driven_pendulum", "driven_pendulum_bottom", "bead_ring_above",
                         "bead_ring_below", "sicm_oscillator"};
  for (size_t f = 0; f < sizeof files / sizeof *files; ++f) {
    char path[512], m[400];
    snprintf(path, sizeof path, "%s/examples/scenes/%s.scene", DAL_SOURCE_DIR, files[f]);
    dal_scene *a = NULL, *b = NULL;
    CHECK_OK(dal_scene_read(path, &a, m, sizeof m));
    CHECK_OK(dal_scene_read(path, &b, m, sizeof m));
    if (!a || !b) continue;
    dal_codegen_opts o = opts();
    CHECK_OK(dal_scene_native(b, &o, m, sizeof m));
    const dal_system *sys = dal_scene_system(b);
    CHECK_MSG(dal_codegen_eom_attached(sys) == 1, "%s: %s", files[f], m);
    if (!dal_codegen_eom_attached(sys)) continue;
    dal_state *st;
    CHECK_OK(dal_state_create(sys, &st));
    double w = compare_random(sys, st, 100);
    // per-trajectory parameters: a heavier particle, another gravity
    double g[3] = {0.3, -7.0, -2.0};
    CHECK_OK(dal_state_set_mass(sys, st, 0, 2.5));
    CHECK_OK(dal_state_set_gravity(sys, st, g));
    double w2 = compare_random(sys, st, 20);
    CHECK_MSG(w <= 1.0 && w2 <= 1.0, "%s: worst |difference| / bound %g, %g", files[f], w, w2);
    dal_state_destroy(st);
    // after a rebuild (dal_scene_set_param) the equations are compiled again; the whole run
    CHECK_OK(dal_scene_set_param(b, b->pname[0], b->pval[0], m, sizeof m));
    CHECK(dal_codegen_eom_attached(dal_scene_system(b)) == 1);
    a->t1 = b->t1 = 2.0;
    dal_state *sa = NULL, *sb = NULL;
    CHECK_OK(dal_scene_run(a, NULL, &sa, m, sizeof m));
    CHECK_OK(dal_scene_run(b, NULL, &sb, m, sizeof m));
    double d = 0.0;
    int n = dal_system_ncoords(dal_scene_system(b));
    for (int i = 0; sa && sb && i < n; ++i)
      d = fmax(d, fmax(fabs(dal_state_q(sa)[i] - dal_state_q(sb)[i]),
                       fabs(dal_state_qdot(sa)[i] - dal_state_qdot(sb)[i])));
    CHECK_MSG(d <= 1e-8, "%s: runs differ by %g", files[f], d);
    printf("%-22s compiled qddot within %.3g of the bound (%.3g with parameters overridden); "
           "run to t=2 differs by %.2g\n",
           files[f], w, w2, d);
    dal_state_destroy(sa);
    dal_state_destroy(sb);
    dal_scene_destroy(a);
    dal_scene_destroy(b);
  }
}

// a smooth random term of the coordinates q0..q(n-1), t and the parameters p0, p1
static void term(char *s, size_t len, int n) {
  static const char *const fn[] = {"sin", "cos", "atan", "tanh", "exp"};
  int i = (int)rnd(0, n), j = (int)rnd(0, n), k = (int)rnd(0, 6);
  double a = rnd(-1, 1), b = rnd(-1, 1);
  switch (k) {
  case 0:
    put(s, len, "%.3f*%s(%.3f*q%d + p0*t)", a, fn[(int)rnd(0, 4)], b, i);
    break;
  case 1:
    put(s, len, "%.3f*q%d*cos(q%d)", a, i, j);
    break;
  case 2:
    put(s, len, "%.3f*p1*q%d^2", 0.3 * a, i);
    break;
  case 3:
    put(s, len, "%.3f*exp(%.3f*q%d)*sin(t)", 0.5 * a, 0.3 * b, i);
    break;
  case 4:
    put(s, len, "%.3f*sqrt(1 + q%d^2)", a, i);
    break;
  default:
    put(s, len, "%.3f*hypot(q%d, 1 + p1)/(2 + cos(q%d))", a, i, j);
  }
}

#define NRAND 200

static void random_models(void) {
  static const char *const cn[] = {"q0", "q1", "q2"}, *const pn[] = {"p0", "p1"};
  int attached = 0;
  double worst = 0.0;
  static dal_system *sys[NRAND];
  static dal_expr *ex[NRAND][4];
  dal_cgbuf src = {0};
  for (int r = 0; r < NRAND; ++r) {
    int d = rnd(0, 1) < 0.5 ? 2 : 3, n = 1 + (int)rnd(0, 3), N = 1 + (int)rnd(0, 3);
    if (N * d < n) N = 2; // rows enough for every coordinate
    dal_builder *b;
    CHECK_OK(dal_builder_create(d, &b));
    int q[3], p[3];
    for (int i = 0; i < n; ++i)
      CHECK_OK(dal_builder_add_coord(b, cn[i], &q[i]));
    dal_expr *e[4] = {NULL, NULL, NULL, NULL};
    char f[3][600], m[400];
    for (int k = 0; k < N; ++k) {
      char name[16];
      snprintf(name, sizeof name, "p%d", k);
      CHECK_OK(dal_builder_add_particle(b, name, rnd(0.5, 2.0), &p[k]));
      // x_c = sum_j a_cj q_j (full rank over the particles) + smooth terms; a parent's position
      // x_c + (its coordinates)
      int parent = k > 0 && rnd(0, 1) < 0.4 ? k - 1 : -1;
      const char *in[8];
      static const char *const pin[] = {"px", "py", "pz"};
      int nin = 0;
      for (int c = 0; parent >= 0 && c < d; ++c)
        in[nin++] = pin[c];
      for (int i = 0; i < n; ++i)
        in[nin++] = cn[i];
      const char *fs[3];
      for (int c = 0; c < d; ++c) {
        char t1[200], t2[200] = "0";
        term(t1, sizeof t1, n);
        if (c == 0) term(t2, sizeof t2, n);
        int i = (k * d + c) % n;
        put(f[c], sizeof f[c], "%s%s%.3f*q%d + %.3f*q%d + %s + %s", parent >= 0 ? pin[c] : "",
            parent >= 0 ? " + " : "", rnd(1.5, 2.5), i, rnd(-0.5, 0.5), (i + 1) % n, t1, t2);
        fs[c] = f[c];
      }
      dal_expr_def ed = dal_default_expr_def();
      ed.name = "random place";
      ed.formulas = fs;
      ed.nout = d;
      ed.inputs = in;
      ed.nin = nin;
      ed.params = pn;
      ed.nparam = 2;
      double pv[2] = {rnd(0.2, 1.5), rnd(0.2, 1.5)};
      ed.values = pv;
      CHECK_OK(dal_expr_create(&ed, &e[k], m, sizeof m));
      dal_place_def pd = dal_default_place_def();
      CHECK_OK(dal_expr_place_def(e[k], &pd));
      pd.parent = parent;
      pd.coords = q;
      pd.ncoords = n;
      CHECK_OK(dal_builder_place_def(b, p[k], &pd));
    }
    double g[3] = {rnd(-1, 1), rnd(-10, 0), rnd(-3, 3)};
    CHECK_OK(dal_builder_set_gravity(b, g));
    if (rnd(0, 1) < 0.5) {
      char u[600], t1[200];
      term(t1, sizeof t1, n);
      put(u, sizeof u, "0.5*q0^2 + %s*t", t1);
      const char *us = u;
      dal_expr_def ud = dal_default_expr_def();
      ud.name = "U";
      ud.formulas = &us;
      ud.nout = 1;
      ud.inputs = cn;
      ud.nin = n;
      ud.params = pn;
      ud.nparam = 2;
      double pv[2] = {0.7, 1.1};
      ud.values = pv;
      CHECK_OK(dal_expr_create(&ud, &e[3], m, sizeof m));
      CHECK_OK(dal_builder_add_potential_q(b, dal_expr_potential_q, e[3]));
    }
    CHECK_OK(dal_builder_compile(b, &sys[r]));
    dal_builder_destroy(b);
    // one source for all (one compiler run): model r's function is eom_<r>
    char fname[32];
    snprintf(fname, sizeof fname, "eom_%d", r);
    CHECK_OK(sys[r] ? dal__eom_source(sys[r], &src, fname, m, sizeof m) : -1);
    memcpy(ex[r], e, sizeof e);
  }
  dal_codegen_opts o = opts();
  char m[400];
  // one compiler run and one object; each system borrows its function (the handle is closed
  // after the last system)
  void *hd = NULL, *fn0 = NULL;
  int rc = dal__cg_load(&src, &o, "eom_0", &hd, &fn0, m, sizeof m);
  CHECK_MSG(rc == DAL_OK, "the random models' source: %s", m);
  for (int r = 0; r < NRAND; ++r) {
    char fname[32];
    snprintf(fname, sizeof fname, "eom_%d", r);
    void *fn = hd ? dlsym(hd, fname) : NULL;
    CHECK_MSG(fn != NULL, "random model %d: no %s", r, fname);
    if (fn) CHECK_OK(dal__eom_attach(sys[r], NULL, fn));
    if (!rc && dal_codegen_eom_attached(sys[r])) {
      attached++;
      dal_state *st;
      CHECK_OK(dal_state_create(sys[r], &st));
      double w = compare_random(sys[r], st, 20);
      CHECK_MSG(w <= 1.0, "random model %d: |difference| / bound %g", r, w);
      if (!(w <= worst)) worst = w;
      dal_state_destroy(st);
    }
    dal_system_destroy(sys[r]);
    for (int k = 0; k < 4; ++k)
      dal_expr_destroy(ex[r][k]);
  }
  dal__cg_free(&src);
  if (hd) dlclose(hd);
  printf("%d random models: compiled qddot within %.3g of the bound\n", attached, worst);
}

// a scene the compiled equations decline: DAL_OK, a note, the general path
static void declined(const char *text, const char *note) {
  dal_scene *sc = NULL;
  char m[600];
  CHECK_OK(dal_scene_parse(text, "declined", &sc, m, sizeof m));
  if (!sc) return;
  dal_codegen_opts o = opts();
  CHECK_OK(dal_scene_native(sc, &o, m, sizeof m));
  CHECK(dal_codegen_eom_attached(dal_scene_system(sc)) == 0);
  CHECK_MSG(strstr(m, note) != NULL, "the note '%s' does not say '%s'", m, note);
  printf("declined: %s\n", m);
  sc->t1 = 0.5;
  CHECK_OK(dal_scene_run(sc, NULL, NULL, m, sizeof m));
  dal_scene_destroy(sc);
}

static void fallback(void) {
  declined("dim 2\ncoord x q=1 v=0\nparticle a mass=1\nplace a = x; 0\nspring a anchor=0,0 k=2 "
           "L=0.5\n",
           "springs");
  declined("dim 2\ncoord x q=1 v=0\ncoord y q=0 v=0\nparticle a mass=1\nplace a = x; y\n"
           "constraint rod parts=a = sqrt(x_a^2 + y_a^2) - 1\ngravity 0 -9.8\n",
           "constraints");
  // expansion of nested powers of sums beyond the algebra's bounds
  declined(
      "dim 2\ncoord x q=0.1 v=0\nparticle a mass=1\nplace a = x + (0.3*(0.3*(0.3*(0.3*(sin(x) + "
      "cos(x) + x + t))^8 + sin(2*x) + x^2 + t)^8 + sin(3*x) + t^3 + x)^8 + cos(x*t))^8; x\n",
      "too large");
  // at a state where M is singular (the spherical pendulum at its pole) the compiled function
  // declines, and the general path names the cause
  {
    dal_scene *sp = NULL;
    char msg[600];
    CHECK_OK(dal_scene_parse("dim 3\ncoord th\ncoord ph\nparticle b mass=1\n"
                             "place b = sin(th)*cos(ph); sin(th)*sin(ph); -cos(th)\n"
                             "gravity 0 0 -9.81\n",
                             "pole", &sp, msg, sizeof msg));
    dal_codegen_opts o = opts();
    CHECK_OK(sp ? dal_scene_native(sp, &o, msg, sizeof msg) : -1);
    const dal_system *sys = sp ? dal_scene_system(sp) : NULL;
    CHECK(dal_codegen_eom_attached(sys) == 1);
    dal_state *st = NULL;
    double q[2] = {0, 0}, qd[2] = {0.1, 0.2}, a[2];
    if (sys) CHECK_OK(dal_state_create(sys, &st));
    if (st) {
      CHECK_OK(dal_state_set(sys, st, 0.0, q, qd));
      CHECK(dal__eom_qddot(sys, st, 0.0, q, qd, a) != 0);
      int rc = dal_forward(sys, st);
      CHECK_MSG(rc == DAL_E_SINGULAR, "the general path at the pole: %d %s", rc,
                dal_state_errmsg(st));
      printf("declined at the pole; the general path: %s\n", dal_state_errmsg(st));
    }
    dal_state_destroy(st);
    dal_scene_destroy(sp);
  }
  // no compiler: the formulas stay on the bytecode, nothing is attached
  dal_scene *sc = NULL;
  char m[600];
  CHECK_OK(dal_scene_parse("dim 2\ncoord x q=1 v=0\nparticle a mass=1\nplace a = x; 0\n", "nocc",
                           &sc, m, sizeof m));
  dal_codegen_opts o = opts();
  o.cc = "/nonexistent/cc";
  dal_system *sys = sc ? (dal_system *)dal_scene_system(sc) : NULL;
  int rc = sys ? dal_codegen_attach_eom(sys, &o, m, sizeof m) : -1;
  CHECK_MSG(rc == DAL_E_UNSUPPORTED && strstr(m, "no compiler"), "no compiler: %d %s", rc, m);
  CHECK(dal_codegen_eom_attached(sys) == 0);
  dal_scene_destroy(sc);
}

int main(void) {
  cache_make();
  struct timespec t0, t1, t2, t3;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  example_scenes();
  clock_gettime(CLOCK_MONOTONIC, &t1);
  random_models();
  clock_gettime(CLOCK_MONOTONIC, &t2);
  fallback();
  clock_gettime(CLOCK_MONOTONIC, &t3);
  printf("seconds: scenes %.1f, random models %.1f, fallback %.1f\n",
         (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec),
         (double)(t2.tv_sec - t1.tv_sec) + 1e-9 * (double)(t2.tv_nsec - t1.tv_nsec),
         (double)(t3.tv_sec - t2.tv_sec) + 1e-9 * (double)(t3.tv_nsec - t2.tv_nsec));
  cache_remove();
  return check_summary("test_codegen_eom");
}
