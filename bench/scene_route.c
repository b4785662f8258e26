// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Scene files against the C route: one scene integrated by DOPRI5 (rtol 1e-8, atol 1e-10) from
// t = 0 to T, for instruction counts per integrated second.
//
//   dal_bench_scene_route SCENE ROUTE T
//     SCENE: pendulum    SICM's driven pendulum (examples/scenes/driven_pendulum.scene)
//            bead        the bead on the turning ring (examples/scenes/bead_ring_below.scene)
//            chain16     16 links of length 0.1 hanging from the origin, released at 0.3 +
//                        0.02 i rad
//            oscillator  SICM's oscillator (a particle on a spring to the origin, m = 2, k = 1)
//     ROUTE: c       built-in C jet primitives (pendulum, ring, hanging; cartesian2 + spring)
//            scene   the scene file, particles placed by formulas (chain16: parent=)
//            native  the same with native code (dal_scene_native; compiled beforehand)
//            flat    chain16 only: every particle placed by absolute formulas (no parent=)
//            lag     the scene file's Lagrangian (`lagrangian = T - U`, dim 0)
//            lagn    the same with native code
//            lagc    the Lagrangian written in C over jets (dal_builder_set_lagrangian)
//
// bench/scene_route.sh runs each under callgrind at two T and divides the difference of the
// instruction counts by the difference of T: instructions per integrated second, set-up (and
// the compiler run or the cache load) removed. Every run prints its end state: the routes of
// one scene agree to the tolerance.
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dalembert/dalembert.h"

#define RTOL 1e-8
#define ATOL 1e-10
#define CHAIN 16
#define LINK 0.1
#define DR_L 1.0
#define DR_A 0.1
#define DR_W 6.2609903369994111
#define DR_G 9.8

static void die(const char *what, const char *msg) {
  fprintf(stderr, "dal_bench_scene_route: %s: %s\n", what, msg);
  exit(1);
}

static double chain_q0(int i) { return 0.3 + 0.02 * i; }

// the C Lagrangians: the driven pendulum (support at (0, a cos(w t)), SICM 1.6.2) and the
// oscillator L = m/2 |v|^2 - k/2 |q|^2 (m = 2, k = 1)
static int lag_driven(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)ctx;
  dal_jet ysd = dal_scale(dal_sin(dal_scale(t, DR_W)), -DR_A * DR_W);
  dal_jet ys = dal_scale(dal_cos(dal_scale(t, DR_W)), DR_A);
  dal_jet vx = dal_scale(dal_mul(dal_cos(q[0]), v[0]), DR_L);
  dal_jet vy = dal_add(ysd, dal_scale(dal_mul(dal_sin(q[0]), v[0]), DR_L));
  dal_jet T = dal_scale(dal_add(dal_sq(vx), dal_sq(vy)), 0.5);
  dal_jet U = dal_scale(dal_sub(ys, dal_scale(dal_cos(q[0]), DR_L)), DR_G);
  *L = dal_sub(T, U);
  return 0;
}

static int lag_osc(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet T = dal_add(dal_sq(v[0]), dal_sq(v[1]));
  dal_jet U = dal_scale(dal_add(dal_sq(q[0]), dal_sq(q[1])), 0.5);
  *L = dal_sub(T, U);
  return 0;
}

// the C route of each scene
static dal_system *c_system(const char *scene, int lagrangian) {
  int bead = !strcmp(scene, "bead"), chain = !strcmp(scene, "chain16");
  int osc = !strcmp(scene, "oscillator");
  int nq = chain ? CHAIN : osc ? 2 : 1, q[CHAIN], p[CHAIN];
  dal_builder *b;
  dal_system *sys;
  if (dal_builder_create(bead ? 3 : 2, &b)) die("builder", "out of memory");
  for (int i = 0; i < nq; ++i) {
    char nm[16];
    snprintf(nm, sizeof nm, "q%d", i);
    if (dal_builder_add_coord(b, nm, &q[i])) die("coord", dal_builder_errmsg(b));
  }
  if (lagrangian) {
    if (dal_builder_set_lagrangian(b, osc ? lag_osc : lag_driven, NULL))
      die("lagrangian", dal_builder_errmsg(b));
  } else {
    for (int i = 0; i < (chain ? CHAIN : 1); ++i) {
      char nm[16];
      snprintf(nm, sizeof nm, "p%d", i);
      if (dal_builder_add_particle(b, nm, osc ? 2.0 : 1.0, &p[i]))
        die("particle", dal_builder_errmsg(b));
      dal_place_def d = dal_default_place_def();
      d.coords = q + i;
      d.ncoords = 1;
      if (bead) {
        d.prim = &dal_map_ring;
        d.param[DAL_RING_R] = 1.0;
        d.param[DAL_RING_W] = 2.0;
      } else if (osc) {
        d.prim = &dal_map_cartesian2;
        d.ncoords = 2;
      } else if (chain && i > 0) {
        d.prim = &dal_map_hanging;
        d.parent = p[i - 1];
        d.param[DAL_HANGING_L] = LINK;
      } else {
        d.prim = &dal_map_pendulum;
        d.param[DAL_PENDULUM_L] = chain ? LINK : DR_L;
        d.param[DAL_PENDULUM_AY] = chain ? 0.0 : DR_A;
        d.param[DAL_PENDULUM_W] = chain ? 0.0 : DR_W;
      }
      if (dal_builder_place_def(b, p[i], &d)) die("place", dal_builder_errmsg(b));
    }
    if (osc) {
      dal_spring_def sd = dal_default_spring_def(); // to the origin, rest length 0
      sd.a = p[0];
      sd.k = 1.0;
      if (dal_builder_add_spring_def(b, &sd)) die("spring", dal_builder_errmsg(b));
    }
    double g3[3] = {0, 0, -9.81}, g2[2] = {0, chain ? -9.81 : -DR_G};
    if (!osc) dal_builder_set_gravity(b, bead ? g3 : g2);
  }
  if (dal_builder_compile(b, &sys)) die("compile", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return sys;
}

// append to a growing text
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static void
cat(char **s, size_t *len, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int k = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  char *r = realloc(*s, *len + (size_t)k + 1);
  if (!r) die("text", "out of memory");
  va_start(ap, fmt);
  vsnprintf(r + *len, (size_t)k + 1, fmt, ap);
  va_end(ap);
  *s = r;
  *len += (size_t)k;
}

// the scene file's text of each route
static char *scene_text(const char *scene, const char *route) {
  char *s = NULL;
  size_t n = 0;
  int lag = !strncmp(route, "lag", 3);
  if (!strcmp(scene, "chain16")) {
    cat(&s, &n, "dim 2\nparam l = %.17g\nparam g = 9.81\n", LINK);
    for (int i = 0; i < CHAIN; ++i)
      cat(&s, &n, "coord q%d q=%.17g v=0\n", i, chain_q0(i));
    for (int i = 0; i < CHAIN; ++i) {
      cat(&s, &n, "particle p%d mass=1\n", i);
      if (i == 0) {
        cat(&s, &n, "place p0 = l*sin(q0); -l*cos(q0)\n");
      } else if (!strcmp(route, "flat")) {
        cat(&s, &n, "place p%d = l*sin(q0)", i);
        for (int j = 1; j <= i; ++j)
          cat(&s, &n, " + l*sin(q%d)", j);
        cat(&s, &n, "; -l*cos(q0)");
        for (int j = 1; j <= i; ++j)
          cat(&s, &n, " - l*cos(q%d)", j);
        cat(&s, &n, "\n");
      } else {
        cat(&s, &n, "place p%d parent=p%d = x_p%d + l*sin(q%d); y_p%d - l*cos(q%d)\n", i, i - 1,
            i - 1, i, i - 1, i);
      }
    }
    cat(&s, &n, "gravity 0 -g\n");
  } else if (!strcmp(scene, "oscillator")) {
    cat(&s, &n, "dim %d\nparam m = 2\nparam k = 1\ncoord x q=1 v=3\ncoord y q=2 v=4\n",
        lag ? 0 : 2);
    if (lag)
      cat(&s, &n, "lagrangian = 1/2*m*(xdot^2 + ydot^2) - 1/2*k*(x^2 + y^2)\n");
    else
      cat(&s, &n, "particle p mass=m\nplace p = x; y\npotential = 1/2*k*(x^2 + y^2)\n");
  } else if (!strcmp(scene, "pendulum") && lag) {
    // T and U of the pendulum with the moving support, as a person writes them
    cat(&s, &n,
        "dim 0\nparam m = 1\nparam l = %.17g\nparam g = %.17g\nparam a = %.17g\n"
        "param omega = %.17g\ncoord theta q=1 v=0\n"
        "lagrangian = 1/2*m*((l*cos(theta)*thetadot)^2 + (-a*omega*sin(omega*t) + "
        "l*sin(theta)*thetadot)^2) - m*g*(a*cos(omega*t) - l*cos(theta))\n",
        DR_L, DR_G, DR_A, DR_W);
  } else {
    char path[600];
    snprintf(path, sizeof path, "%s/examples/scenes/%s.scene", DAL_SOURCE_DIR,
             !strcmp(scene, "bead") ? "bead_ring_below" : "driven_pendulum");
    FILE *f = fopen(path, "r");
    if (!f) die(path, "cannot open");
    char buf[4096];
    size_t k;
    while ((k = fread(buf, 1, sizeof buf - 1, f)) > 0) {
      buf[k] = 0;
      cat(&s, &n, "%s", buf);
    }
    fclose(f);
  }
  return s;
}

int main(int argc, char **argv) {
  if (argc != 4) {
    fprintf(stderr, "usage: dal_bench_scene_route pendulum|bead|chain16|oscillator "
                    "c|scene|native|flat|lag|lagn|lagc T\n");
    return 64;
  }
  const char *scene = argv[1], *route = argv[2];
  double T = atof(argv[3]);
  int chain = !strcmp(scene, "chain16"), osc = !strcmp(scene, "oscillator");
  int n = chain ? CHAIN : osc ? 2 : 1;
  double q0[CHAIN], v0[CHAIN];
  for (int i = 0; i < n; ++i) {
    q0[i] = chain ? chain_q0(i) : osc ? 1.0 + i : !strcmp(scene, "bead") ? 0.5 : 1.0;
    v0[i] = osc ? 3.0 + i : 0.0;
  }
  dal_scene *sc = NULL;
  dal_system *own = NULL;
  const dal_system *sys;
  char msg[600];
  if (!strcmp(route, "c") || !strcmp(route, "lagc")) {
    sys = own = c_system(scene, !strcmp(route, "lagc"));
  } else {
    char *text = scene_text(scene, route);
    if (dal_scene_parse(text, scene, &sc, msg, sizeof msg)) die(scene, msg);
    free(text);
    if ((!strcmp(route, "native") || !strcmp(route, "lagn")) &&
        dal_scene_native(sc, NULL, msg, sizeof msg))
      die("native", msg);
    sys = dal_scene_system(sc);
  }
  dal_state *st;
  if (dal_state_create(sys, &st)) die("state", "out of memory");
  if (dal_state_set(sys, st, 0.0, q0, v0)) die("state", dal_state_errmsg(st));
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_DOPRI5;
  o.rtol = RTOL;
  o.atol = ATOL;
  o.max_steps = 100000000;
  if (dal_advance(sys, st, &o, T)) die("advance", dal_state_errmsg(st));
  dal_stats s;
  dal_state_stats(st, &s);
  printf("%s %s T=%g route=%s q_last %.12f qdot_last %.12f steps %ld rhs %ld\n", scene, route, T,
         dal_system_dynamics(sys) == DAL_DYNAMICS_RECURSIVE ? "recursive" : "dense",
         dal_state_q(st)[n - 1], dal_state_qdot(st)[n - 1], s.steps, s.rhs_evals);
  dal_state_destroy(st);
  dal_system_destroy(own);
  dal_scene_destroy(sc);
  return 0;
}
