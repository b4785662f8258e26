// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// White box: scene files take the C route's fast paths (issue 36). (1) Particles hanging from
// their parents: a planar chain written with `parent=` takes the recursion and the closed-form
// links of dal_map_hanging (scene/build.c recognises its formulas), checked against the C route
// (the same accelerations and run, bit for bit), the non-recursive route (the same chain by
// absolute formulas, dense M) and links not of that form. (2) A scene file's Lagrangian runs by
// its parts dL/dqdot and dL/dq, derived symbolically (eval/lagrangian.c), checked against the
// particle route of the same mechanics (independent of L) and L's polarization.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/base.h"
#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

#define NL 16
#define LINK 0.1

static double q0_of(int i) { return 0.3 + 0.02 * i; }

// text of a chain of n links: `parent=` lines (flat = 0) or absolute formulas (flat = 1); link
// `odd` (>= 1, 0: none) is written in another form: r = r_p + l (cos q, sin q) (not hanging's)
static char *chain_text(int n, int flat, int odd, const char *lname) {
  size_t cap = 64000, k = 0;
  char *s = malloc(cap);
  if (!s) return NULL;
  k += (size_t)snprintf(s + k, cap - k, "dim 2\nparam %s = %.17g\nparam g = 9.81\n", lname, LINK);
  for (int i = 0; i < n; ++i)
    k += (size_t)snprintf(s + k, cap - k, "coord q%d q=%.17g v=0\n", i, q0_of(i));
  for (int i = 0; i < n; ++i) {
    k += (size_t)snprintf(s + k, cap - k, "particle p%d mass=1\n", i);
    if (i == 0) {
      k += (size_t)snprintf(s + k, cap - k, "place p0 = %s*sin(q0); -%s*cos(q0)\n", lname, lname);
    } else if (!flat) {
      int o = i == odd;
      k += (size_t)snprintf(s + k, cap - k,
                            "place p%d parent=p%d = x_p%d + %s*%s(q%d); y_p%d %s %s*%s(q%d)\n", i,
                            i - 1, i - 1, lname, o ? "cos" : "sin", i, i - 1, o ? "+" : "-", lname,
                            o ? "sin" : "cos", i);
    } else {
      k += (size_t)snprintf(s + k, cap - k, "place p%d = 0", i);
      for (int j = 0; j <= i; ++j)
        k += (size_t)snprintf(s + k, cap - k, " + %s*%s(q%d)", lname,
                              odd && j == odd ? "cos" : "sin", j);
      k += (size_t)snprintf(s + k, cap - k, "; 0");
      for (int j = 0; j <= i; ++j)
        k += (size_t)snprintf(s + k, cap - k, " %s %s*%s(q%d)", odd && j == odd ? "+" : "-", lname,
                              odd && j == odd ? "sin" : "cos", j);
      k += (size_t)snprintf(s + k, cap - k, "\n");
    }
  }
  snprintf(s + k, cap - k, "gravity 0 -g\n");
  return s;
}

static dal_scene *scene(int n, int flat, int odd, const char *lname) {
  char *t = chain_text(n, flat, odd, lname), msg[512];
  dal_scene *sc = NULL;
  int rc = t ? dal_scene_parse(t, "chain", &sc, msg, sizeof msg) : DAL_E_NOMEM;
  CHECK_MSG(rc == DAL_OK, "%s", msg);
  free(t);
  return sc;
}

// the C route: dal_map_pendulum about the origin, then dal_map_hanging links (the scene
// library's chain)
static dal_system *c_chain(int n) {
  scn_knobs k = scn_default();
  k.N = n;
  k.l = LINK;
  k.g = 9.81;
  return scn_chain(&k);
}

// largest |qddot_a - qddot_b| / max(1, |qddot_b|) over random states and times; *bits: all
// equal bit for bit
static double qddot_gap(const dal_system *a, const dal_system *b, int n, int *bits) {
  dal_state *sa = NULL, *sb = NULL;
  CHECK_OK(dal_state_create(a, &sa));
  CHECK_OK(dal_state_create(b, &sb));
  unsigned long long seed = 36;
  double q[NL], v[NL], gap = 0.0;
  *bits = 1;
  for (int trial = 0; trial < 20 && sa && sb; ++trial) {
    double t = check_rand(&seed, 0.0, 10.0);
    for (int i = 0; i < n; ++i) {
      q[i] = check_rand(&seed, -3.0, 3.0);
      v[i] = check_rand(&seed, -5.0, 5.0);
    }
    CHECK_OK(dal_state_set(a, sa, t, q, v));
    CHECK_OK(dal_state_set(b, sb, t, q, v));
    CHECK_OK(dal_forward(a, sa));
    CHECK_OK(dal_forward(b, sb));
    const double *x = dal_state_qddot(sa), *y = dal_state_qddot(sb);
    for (int i = 0; i < n; ++i) {
      gap = fmax(gap, fabs(x[i] - y[i]) / fmax(1.0, fabs(y[i])));
      *bits &= x[i] == y[i];
    }
  }
  dal_state_destroy(sa);
  dal_state_destroy(sb);
  return gap;
}

// q at t1 by DOPRI5 at rtol 1e-10 from (q0, v0); NULL q0: the chain's start, at rest
static void run(const dal_system *sys, int n, const double *q0, const double *v0, double t1,
                double *q) {
  dal_state *st = NULL;
  double c0[NL], z[NL] = {0};
  for (int i = 0; i < n; ++i)
    c0[i] = q0_of(i);
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_set(sys, st, 0.0, q0 ? q0 : c0, v0 ? v0 : z));
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_DOPRI5;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  CHECK_OK(dal_advance(sys, st, &o, t1));
  memcpy(q, dal_state_q(st), (size_t)n * sizeof(double));
  dal_state_destroy(st);
}

static double max_diff(const double *a, const double *b, int n) {
  double d = 0.0;
  for (int i = 0; i < n; ++i)
    d = fmax(d, fabs(a[i] - b[i]));
  return d;
}

// the chain by parent= against the C route and against the absolute formulas
static void test_chain(void) {
  dal_scene *tree = scene(NL, 0, 0, "len"), *flat = scene(NL, 1, 0, "len");
  dal_system *c = c_chain(NL);
  if (!tree || !flat || !c) return;
  const dal_system *ts = dal_scene_system(tree), *fs = dal_scene_system(flat);
  CHECK(dal_system_dynamics(ts) == DAL_DYNAMICS_RECURSIVE);
  CHECK(dal_system_dynamics(fs) == DAL_DYNAMICS_DENSE); // a coordinate moves many particles
  // the links took hanging's primitive: their parameter carries hanging's name, not the scene's
  dal_param_ref ref;
  CHECK(dal_param_find(ts, "place:p5:l", &ref, NULL, 0) == DAL_OK);
  // the same accelerations as the C route (bit for bit: hanging's closed form, and the root's
  // formulas are dal_map_pendulum's operations) and as the dense route (to rounding)
  int bits;
  double gc = qddot_gap(ts, c, NL, &bits);
  printf("chain16 by parent=: qddot against the C route %.3g (bit for bit: %d)\n", gc, bits);
  CHECK(bits);
  int bits_f;
  double gf = qddot_gap(ts, fs, NL, &bits_f);
  printf("chain16 by parent=: qddot against the dense route %.3g\n", gf);
  CHECK(gf < 1e-11);
  // the same runs: bit for bit with C, within the tolerance of the dense route
  double qt[NL], qc[NL], qf[NL];
  run(ts, NL, NULL, NULL, 1.0, qt);
  run(c, NL, NULL, NULL, 1.0, qc);
  run(fs, NL, NULL, NULL, 1.0, qf);
  printf("q(1): scene - C %.3g, scene - dense %.3g\n", max_diff(qt, qc, NL), max_diff(qt, qf, NL));
  CHECK(max_diff(qt, qc, NL) == 0.0);
  CHECK(max_diff(qt, qf, NL) < 1e-8);
  // a per-trajectory link length reads as in the C route
  dal_state *a = NULL, *b = NULL;
  CHECK_OK(dal_state_create(ts, &a));
  CHECK_OK(dal_state_create(c, &b));
  CHECK_OK(dal_state_set_param_named(ts, a, "place:p7:l", 0.25));
  CHECK_OK(dal_state_set_param_named(c, b, "place:p7:l", 0.25));
  double q[NL], v[NL];
  for (int i = 0; i < NL; ++i) {
    q[i] = q0_of(i);
    v[i] = 0.1 * i;
  }
  CHECK_OK(dal_state_set(ts, a, 0.0, q, v));
  CHECK_OK(dal_state_set(c, b, 0.0, q, v));
  CHECK_OK(dal_forward(ts, a));
  CHECK_OK(dal_forward(c, b));
  CHECK(max_diff(dal_state_qddot(a), dal_state_qddot(b), NL) == 0.0);
  dal_state_destroy(a);
  dal_state_destroy(b);
  dal_system_destroy(c);
  dal_scene_destroy(tree);
  dal_scene_destroy(flat);
}

// links of another form (r_p + l (cos q, sin q)) or another parameter name stay formulas and
// still agree with the dense route; the recognised ones keep working beside them
static void test_other_forms(void) {
  dal_scene *tree = scene(6, 0, 3, "len"), *flat = scene(6, 1, 3, "len");
  if (!tree || !flat) return;
  const dal_system *ts = dal_scene_system(tree), *fs = dal_scene_system(flat);
  CHECK(dal_system_dynamics(ts) == DAL_DYNAMICS_RECURSIVE);
  dal_param_ref ref;
  CHECK(dal_param_find(ts, "place:p3:len", &ref, NULL, 0) == DAL_OK); // link 3: formulas
  CHECK(dal_param_find(ts, "place:p2:l", &ref, NULL, 0) == DAL_OK);   // link 2: hanging
  int bits;
  double g = qddot_gap(ts, fs, 6, &bits);
  printf("6 links, link 3 in another form: qddot against the dense route %.3g\n", g);
  CHECK(g < 1e-11);
  double qt[6], qf[6];
  run(ts, 6, NULL, NULL, 1.0, qt);
  run(fs, 6, NULL, NULL, 1.0, qf);
  CHECK(max_diff(qt, qf, 6) < 1e-8);
  dal_scene_destroy(tree);
  dal_scene_destroy(flat);
}

#define G 9.8
#define A_DR 0.1
#define W_DR 6.2609903369994111

static const char *driven_text =
    "dim 0\nparam l = 1\nparam g = 9.8\nparam a = 0.1\nparam w = 6.2609903369994111\n"
    "coord th q=1 v=0\n"
    "lagrangian = 1/2*((l*cos(th)*thdot)^2 + (-a*w*sin(w*t) + l*sin(th)*thdot)^2) - "
    "g*(a*cos(w*t) - l*cos(th))\n";

static const char *double_text =
    "dim 0\nparam g = 9.8\ncoord a q=0.7 v=0\ncoord b q=-0.4 v=0.3\n"
    "lagrangian = adot^2 + 1/2*bdot^2 + adot*bdot*cos(a - b) + 2*g*cos(a) + g*cos(b)\n";

// the particle route (the scene library): the driven pendulum (n = 1) or the double pendulum
static dal_system *particles(int n) {
  scn_knobs k = scn_default();
  k.g = G;
  if (n == 1) {
    k.ay = A_DR;
    k.w = W_DR;
    return scn_pendulum(&k);
  }
  return scn_double_pendulum(&k);
}

// the scene's own Lagrangian expression by polarization alone (no parts)
static dal_system *polarized(const dal_scene *sc, int n) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  CHECK_OK(dal_builder_create(2, &b));
  for (int i = 0; i < n; ++i) {
    char nm[16];
    snprintf(nm, sizeof nm, "q%d", i);
    CHECK_OK(dal_builder_add_coord(b, nm, NULL));
  }
  const dal_expr *L = NULL;
  for (int i = 0; i < dal_scene_nexprs(sc) && !L; ++i) // the first expression over velocities
    if (dal_expr_nin(dal_scene_expr(sc, i)) == 2 * n && dal_expr_nout(dal_scene_expr(sc, i)) == 1)
      L = dal_scene_expr(sc, i);
  CHECK(L != NULL);
  CHECK_OK(dal_builder_set_lagrangian(b, dal_expr_lagrangian, (void *)L));
  CHECK_OK(dal_builder_compile(b, &sys));
  dal_builder_destroy(b);
  return sys;
}

static void check_lagrangian(const char *name, const char *text, int n) {
  dal_scene *sc = NULL;
  char msg[512];
  CHECK_MSG(dal_scene_parse(text, name, &sc, msg, sizeof msg) == DAL_OK, "%s", msg);
  if (!sc) return;
  const dal_system *s = dal_scene_system(sc);
  CHECK(s->lag_parts != NULL); // the parts were derived and given to the system
  dal_system *pr = particles(n), *pol = polarized(sc, n);
  CHECK(pol && pol->lag_parts == NULL);
  int bits;
  double gp = qddot_gap(s, pr, n, &bits), gl = qddot_gap(s, pol, n, &bits);
  printf("%s: qddot against the particle route %.3g, against L's polarization %.3g\n", name, gp,
         gl);
  CHECK(gp < 1e-13);
  CHECK(gl < 1e-13);
  double q0[2] = {1.0, -0.4}, v0[2] = {0.2, 0.3}, a[2], b[2], c[2];
  run(s, n, q0, v0, 5.0, a);
  run(pr, n, q0, v0, 5.0, b);
  run(pol, n, q0, v0, 5.0, c);
  double d1 = 0, d2 = 0;
  for (int i = 0; i < n; ++i) {
    d1 = fmax(d1, fabs(a[i] - b[i]));
    d2 = fmax(d2, fabs(a[i] - c[i]));
  }
  printf("%s: q(5) against the particle route %.3g, against the polarization %.3g\n", name, d1, d2);
  CHECK(d1 < 1e-9);
  CHECK(d2 < 1e-9);
  // the energy function still comes from L: constant for the double pendulum (no t in L)
  if (n == 2) {
    dal_state *st = NULL;
    CHECK_OK(dal_state_create(s, &st));
    CHECK_OK(dal_state_set(s, st, 0.0, q0, v0));
    dal_energies e0, e1;
    CHECK_OK(dal_forward(s, st));
    CHECK_OK(dal_state_energies(st, &e0));
    dal_solve_opts o = dal_default_solve_opts();
    o.rtol = 1e-10;
    CHECK_OK(dal_advance(s, st, &o, 5.0));
    CHECK_OK(dal_state_energies(st, &e1));
    CHECK_CLOSE(e1.h, e0.h, 1e-8);
    dal_state_destroy(st);
  }
  dal_system_destroy(pr);
  dal_system_destroy(pol);
  dal_scene_destroy(sc);
}

int main(void) {
  test_chain();
  test_other_forms();
  check_lagrangian("driven pendulum", driven_text, 1);
  check_lagrangian("double pendulum", double_text, 2);
  return check_summary("test_scene_routes");
}
