// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Scene files: the seed scenes against the numbers of the C examples, write-back bit for bit,
// and messages that name the line.
//
// 1. examples/scenes/sicm_oscillator.scene: the state at t = 10 against the closed form
//    q0 cos(w t) + qdot0/w sin(w t) to 100 rtol (examples/sicm_oscillator.c's check).
// 2. driven_pendulum.scene: to t = 10 equal to the C route (dal_map_pendulum with a moving
//    pivot, examples/sicm_driven_pendulum.c's model) to 1e-10 (rounding amplified by the flow).
// 3. bead_ring_below/above.scene: equal to the C route (dal_map_ring) at t = 20; the Jacobi
//    integral h conserved; released 1e-4 from the equilibrium (0 below, acos(g/(R w^2)) above,
//    by dal_scene_set_param), the bead is back after one period 2 pi / Omega of the closed-form
//    small-oscillation frequency (examples/bead_ring.c's check 2).
// 4. Every seed scene written back and read again runs to the same state bit for bit, and
//    writes the same text.
// 5. Bad scenes are refused with the line and the culprit named.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "dalembert/scene.h"

// a placement and a constraint from their parts, through the defs
static int place_by(dal_builder *b, int p, const dal_primitive *prim, int parent, int nc,
                    const int *coords, int np, const double *param, void *ctx) {
  dal_place_def d = dal_default_place_def();
  d.prim = prim;
  d.parent = parent;
  d.coords = coords;
  d.ncoords = nc;
  d.param_list = param;
  d.nparam_list = np;
  d.ctx = ctx;
  return dal_builder_place_def(b, p, &d);
}

#define PI 3.14159265358979323846

static dal_scene *load(const char *name) {
  char path[512], msg[1024];
  snprintf(path, sizeof path, "%s/%s", SCENE_DIR, name);
  dal_scene *sc = NULL;
  int rc = dal_scene_read(path, &sc, msg, sizeof msg);
  CHECK_MSG(rc == 0, "%s: %s", name, msg);
  return sc;
}

// run the scene's own run to time T (its method and tolerances); y = (q, qdot)
static void run_scene(const dal_scene *sc, double T, double *y) {
  const dal_system *sys = dal_scene_system(sc);
  dal_state *st;
  CHECK_OK(dal_scene_state(sc, &st));
  CHECK_OK(dal_advance(sys, st, dal_scene_opts(sc, NULL, NULL, NULL), T));
  int n = dal_system_ncoords(sys);
  for (int i = 0; i < n; ++i) {
    y[i] = dal_state_q(st)[i];
    y[n + i] = dal_state_qdot(st)[i];
  }
  dal_state_destroy(st);
}

static void oscillator(void) {
  dal_scene *sc = load("sicm_oscillator.scene");
  if (!sc) return;
  double y[4], w = sqrt(1.0 / 2.0), q0[2] = {1, 2}, v0[2] = {3, 4};
  run_scene(sc, 10.0, y);
  for (int i = 0; i < 2; ++i) {
    CHECK_CLOSE(y[i], q0[i] * cos(w * 10) + v0[i] / w * sin(w * 10), 100 * 1e-12);
    CHECK_CLOSE(y[2 + i], -q0[i] * w * sin(w * 10) + v0[i] * cos(w * 10), 100 * 1e-12);
  }
  printf("oscillator at t = 10: (%.12f, %.12f), closed form (%.12f, %.12f)\n", y[0], y[1],
         q0[0] * cos(w * 10) + v0[0] / w * sin(w * 10),
         q0[1] * cos(w * 10) + v0[1] / w * sin(w * 10));
  dal_scene_destroy(sc);
}

// the C route of a one-coordinate scene: a particle placed by a built-in map
static void c_route(const dal_primitive *prim, int dim, const double *param, int np,
                    const double *g, const dal_solve_opts *o, double q0, double T, double *y) {
  dal_builder *b;
  dal_system *sys;
  int th, p;
  dal_builder_create(dim, &b);
  dal_builder_add_coord(b, "theta", &th);
  dal_builder_add_particle(b, "p", 1.0, &p);
  CHECK_OK(place_by(b, p, prim, -1, 1, &th, np, param, NULL));
  dal_builder_set_gravity(b, g);
  CHECK_OK(dal_builder_compile(b, &sys));
  dal_builder_destroy(b);
  dal_state *st;
  dal_state_create(sys, &st);
  double v0 = 0;
  dal_state_set(sys, st, 0, &q0, &v0);
  CHECK_OK(dal_advance(sys, st, o, T));
  y[0] = dal_state_q(st)[0];
  y[1] = dal_state_qdot(st)[0];
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

static void driven(void) {
  dal_scene *sc = load("driven_pendulum.scene");
  if (!sc) return;
  double y[2], yc[2];
  run_scene(sc, 10.0, y);
  double param[7] = {1, 0, 0, 0, 0.1, 2 * sqrt(9.8), 0}, g[2] = {0, -9.8};
  c_route(&dal_map_pendulum, 2, param, 7, g, dal_scene_opts(sc, NULL, NULL, NULL), 1.0, 10.0, yc);
  printf("driven pendulum at t = 10: scene %.15f %.15f, C route %.15f %.15f\n", y[0], y[1], yc[0],
         yc[1]);
  CHECK_CLOSE(y[0], yc[0], 1e-10);
  CHECK_CLOSE(y[1], yc[1], 1e-10);
  dal_scene_destroy(sc);
}

static void bead(const char *file, double w) {
  dal_scene *sc = load(file);
  if (!sc) return;
  const double R = 1, g = 9.81;
  double y[2], yc[2], param[3] = {R, w, 0}, gv[3] = {0, 0, -g};
  run_scene(sc, 20.0, y);
  c_route(&dal_map_ring, 3, param, 3, gv, dal_scene_opts(sc, NULL, NULL, NULL), 0.5, 20.0, yc);
  CHECK_CLOSE(y[0], yc[0], 1e-9);
  CHECK_CLOSE(y[1], yc[1], 1e-9);
  // the Jacobi integral over the scene's own run
  const dal_system *sys = dal_scene_system(sc);
  dal_state *st;
  CHECK_OK(dal_scene_state(sc, &st));
  CHECK_OK(dal_forward(sys, st));
  dal_energies e0, e1;
  dal_state_energies(st, &e0);
  CHECK_OK(dal_advance(sys, st, dal_scene_opts(sc, NULL, NULL, NULL), 20.0));
  CHECK_OK(dal_forward(sys, st));
  dal_state_energies(st, &e1);
  CHECK_CLOSE(e1.h, e0.h, 1e-9 * fabs(e0.h) + 1e-12);
  CHECK(fabs(e1.E - e0.E) > 1e-3); // the energy is not conserved (the ring does work)
  dal_state_destroy(st);
  // small oscillations about the equilibrium at the closed-form frequency
  double ts = w * w > g / R ? acos(g / (R * w * w)) : 0.0;
  double Om = w * w > g / R ? w * sin(ts) : sqrt(g / R - w * w);
  char msg[512];
  CHECK_OK(dal_scene_set_param(sc, "theta0", ts + 1e-4, msg, sizeof msg));
  sys = dal_scene_system(sc);
  run_scene(sc, 2 * PI / Om, y);
  printf("%s: h(0) = %.12f, h(20) = %.12f; after one period 2 pi/Omega = %.6f s the bead is "
         "%.3g rad from its start (amplitude 1e-4)\n",
         file, e0.h, e1.h, 2 * PI / Om, y[0] - (ts + 1e-4));
  CHECK(fabs(y[0] - (ts + 1e-4)) < 1e-10); // the period shifts by O(amplitude^2)
  CHECK(fabs(y[1]) < 1e-6);
  dal_scene_destroy(sc);
}

// written back and read again: the same text, the same state bit for bit
static void write_back(const char *file) {
  dal_scene *sc = load(file), *sc2 = NULL;
  if (!sc) return;
  char *t1 = NULL, *t2 = NULL;
  size_t n1 = 0, n2 = 0;
  FILE *fp = open_memstream(&t1, &n1);
  CHECK_OK(dal_scene_write(sc, fp));
  fclose(fp);
  char msg[512];
  CHECK_OK(dal_scene_parse(t1, "written", &sc2, msg, sizeof msg));
  if (sc2) {
    fp = open_memstream(&t2, &n2);
    dal_scene_write(sc2, fp);
    fclose(fp);
    const char *b1 = strchr(t1, '\n'), *b2 = strchr(t2, '\n'); // after the header line
    CHECK(b1 && b2 && !strcmp(b1, b2));
    double y1[8], y2[8];
    run_scene(sc, 3.0, y1);
    run_scene(sc2, 3.0, y2);
    int n = dal_system_ncoords(dal_scene_system(sc));
    CHECK_MSG(!memcmp(y1, y2, 2 * (size_t)n * sizeof *y1), "%s: written back, not bit for bit",
              file);
  }
  free(t1);
  free(t2);
  dal_scene_destroy(sc2);
  dal_scene_destroy(sc);
}

static void refused(const char *text, const char *f1, const char *f2) {
  static int marker;
  dal_scene *sc = (dal_scene *)&marker;
  char msg[1024] = "";
  int rc = dal_scene_parse(text, "bad.scene", &sc, msg, sizeof msg);
  CHECK_MSG(rc != 0 && sc == NULL, "accepted: %s", text);
  CHECK_MSG(strstr(msg, f1) && strstr(msg, f2), "message '%s' lacks '%s' or '%s'", msg, f1, f2);
}

static void errors(void) {
  refused("dim 2\ncoord th\nparticle b mass=1\nplace b = l*sin(th); -cos(th)\n",
          "bad.scene:4: place b: formula 1 'l*sin(th)', column 1", "unknown symbol 'l'");
  refused("dim 2\ncoord th\nparticle b mass=1\nplace c = sin(th); -cos(th)\n", "bad.scene:4",
          "particle 'c' is not defined above");
  refused("dim 2\n# comment\ncoord th\nwobble 3\n", "bad.scene:4", "unknown element 'wobble'");
  refused("param g = nine\n", "bad.scene:1: param g: formula 1 'nine'", "unknown symbol 'nine'");
  refused("param g = 1/0\n", "bad.scene:1: param g", "is not finite");
  refused("dim 2\ncoord th\nparticle b mass=1\nplace b = sin(th)\n", "bad.scene:4",
          "1 formulas for dimension 2");
  refused("dim 2\ncoord th\nparticle b mass=1\nplace b pendulum th\n", "bad.scene:4",
          "parameter 'l' of 'pendulum' is required");
  refused("dim 2\ncoord th\nparticle b mass=m\n", "bad.scene:3: particle mass",
          "unknown symbol 'm'");
  refused("dim 2\ncoord th\nparticle b mass=1\nplace b = sin(th); -cos(th)\nrun method=euler\n",
          "bad.scene:5", "unknown method 'euler'");
  refused("dim 2\ncoord th\nparticle b mass=1\n", "bad.scene", "'b'"); // never placed
  // event and section lines after a pendulum's 4 lines: the line added, its message's parts
  static const char *const bad_events[][3] = {
      {"event e = thdot + x\n", "bad.scene:5: event e: formula 1 'thdot + x'",
       "unknown symbol 'x'"},
      {"event e upward = th\n", "bad.scene:5", "unknown word 'upward'"},
      {"section s terminal = th\n", "bad.scene:5", "unknown word 'terminal'"},
      {"section s period=-1\n", "bad.scene:5", "period -1 is not positive"},
      {"section s period=1\nsection s2 period=2\n", "bad.scene:6", "a second stroboscopic"},
      {"event e = th; thdot\n", "bad.scene:5", "one formula after '='"},
  };
  for (size_t i = 0; i < sizeof bad_events / sizeof *bad_events; ++i) {
    char text[512];
    snprintf(text, sizeof text,
             "dim 2\ncoord th q=1\nparticle b mass=1\n"
             "place b = sin(th); -cos(th)\n%s",
             bad_events[i][0]);
    refused(text, bad_events[i][1], bad_events[i][2]);
  }
  refused("event e = t\n", "bad.scene:1", "after the coordinates");
  // a built-in constraint primitive has no formulas to show, and it says so
  dal_scene *sc;
  char msg[512];
  CHECK_OK(dal_scene_parse("dim 2\ncoord x\ncoord y\nparticle b mass=1\nplace b = x; y\n"
                           "particle a mass=1\nplace a fixed2 x=0 y=0\n"
                           "constraint c distance2 parts=a,b L=1\n",
                           "c.scene", &sc, msg, sizeof msg));
  FILE *fp = tmpfile();
  CHECK(sc && dal_scene_show(sc, fp, DAL_EXPR_TEXT, msg, sizeof msg) == DAL_E_UNSUPPORTED &&
        strstr(msg, "c.scene:8: constraint c: the primitive 'distance2' has no formulas"));
  fclose(fp);
  dal_scene_destroy(sc);
}

// the value of the formula `lhs = ...` that show printed (in text), over the scene's
// coordinates with rates and its parameters, at the state's (t, q, qdot)
static double shown(const char *out, const char *lhs, const dal_scene *sc, const dal_state *st) {
  char key[80];
  snprintf(key, sizeof key, "\n%s = ", lhs);
  const char *at = strstr(out, key);
  CHECK_MSG(at != NULL, "show printed no '%s'", lhs);
  if (!at) return NAN;
  at += strlen(key);
  size_t n = strcspn(at, "\n");
  char *f = malloc(n + 1);
  memcpy(f, at, n);
  f[n] = 0;
  const dal_system *sys = dal_scene_system(sc);
  int nq = dal_system_ncoords(sys);
  const char *in[8], *pn[] = {"g", "c"};
  double pv[] = {9.8, 0.3};
  for (int i = 0; i < nq; ++i)
    in[i] = dal_system_coord_name(sys, i);
  dal_expr_def d = dal_default_expr_def();
  d.formulas = (const char *const *)&f;
  d.nout = 1;
  d.inputs = in;
  d.nin = nq;
  d.velocities = 1;
  d.params = pn;
  d.values = pv;
  d.nparam = 2;
  dal_expr *e = NULL;
  char msg[512];
  CHECK_OK(dal_expr_create(&d, &e, msg, sizeof msg));
  dal_jet x[16], r = dal_const(NAN);
  for (int i = 0; i < nq; ++i) {
    x[i] = dal_const(dal_state_q(st)[i]);
    x[nq + i] = dal_const(dal_state_qdot(st)[i]);
  }
  if (e) dal_expr_eval(e, x, dal_const(dal_state_time(st)), NULL, &r);
  dal_expr_destroy(e);
  free(f);
  return r.v;
}

// show of a damped double pendulum (two coordinates: the accelerations by Cramer's rule, the
// damper's forces from Rayleigh's D) against the library's numeric accelerations at the
// initial state, and of a constrained particle: phi and G = dphi/dq in closed form
static void show_more(void) {
  const char *texts[2] = {
      "dim 2\nparam g = 9.8\nparam c = 0.3\ncoord a q=0.4 v=0.1\ncoord b q=-0.2 v=0.3\n"
      "particle p1 mass=1\nparticle p2 mass=2\nplace p1 = sin(a); -cos(a)\n"
      "place p2 parent=p1 = x_p1 + sin(b); y_p1 - cos(b)\ngravity 0 -g\n"
      "damper p2 anchor=0,0 c=c\n",
      "dim 2\nparam g = 9.8\ncoord x q=0.6 v=0\ncoord y q=-0.8 v=0\nparticle b mass=1\n"
      "place b = x; y\nconstraint rod parts=b = sqrt(x_b^2 + y_b^2) - 1\ngravity 0 -g\n"};
  for (int k = 0; k < 2; ++k) {
    dal_scene *sc = NULL;
    dal_state *st = NULL;
    char msg[512], *out = NULL;
    size_t n = 0;
    CHECK_OK(dal_scene_parse(texts[k], "more.scene", &sc, msg, sizeof msg));
    if (!sc) continue;
    FILE *fp = open_memstream(&out, &n);
    fputc('\n', fp);
    CHECK_OK(dal_scene_show(sc, fp, DAL_EXPR_TEXT, msg, sizeof msg));
    fclose(fp);
    CHECK_OK(dal_scene_state(sc, &st));
    CHECK_OK(dal_forward(dal_scene_system(sc), st));
    if (k == 0) {
      double aa = shown(out, "addot", sc, st), bb = shown(out, "bddot", sc, st);
      printf("damped double pendulum: shown qddot (%.15f, %.15f), numeric (%.15f, %.15f)\n", aa, bb,
             dal_state_qddot(st)[0], dal_state_qddot(st)[1]);
      CHECK_CLOSE(aa, dal_state_qddot(st)[0], 1e-13);
      CHECK_CLOSE(bb, dal_state_qddot(st)[1], 1e-13);
      CHECK(strstr(out, "\nD = ") && strstr(out, "\nM qddot = F + Q\n"));
    } else {
      CHECK_CLOSE(shown(out, "phi_rod", sc, st), 0.0, 1e-15);
      CHECK_CLOSE(shown(out, "G_rod,x", sc, st), 0.6, 1e-15);
      CHECK_CLOSE(shown(out, "G_rod,y", sc, st), -0.8, 1e-15);
      CHECK(strstr(out, "\nM qddot = F + G' lambda, phi = 0\n") != NULL);
    }
    free(out);
    dal_state_destroy(st);
    dal_scene_destroy(sc);
  }
}

// a terminal event of a scene file stops the run where the pendulum released at rest from
// theta0 first passes the bottom: a quarter period, 4 sqrt(l/g) K(sin^2(theta0/2)) / 4
// (K by the arithmetic-geometric mean: K(m) = pi / (2 AGM(1, sqrt(1 - m))))
static void terminal_event(void) {
  dal_scene *sc;
  char msg[512];
  CHECK_OK(dal_scene_parse("dim 2\nparam g = 9.8\ncoord th q=1\nparticle b mass=1\n"
                           "place b = sin(th); -cos(th)\ngravity 0 -g\n"
                           "run method=bs rtol=1e-12 t1=10 dt=0.5\n"
                           "event bottom falling terminal = th\nsection top rising = thdot\n",
                           "ev.scene", &sc, msg, sizeof msg));
  if (!sc) return;
  dal_events *ev;
  dal_state *st;
  CHECK_OK(dal_scene_events(sc, &ev));
  CHECK(dal_events_size(ev) == 2 && dal_scene_event_is_section(sc, 0) == 0 &&
        dal_scene_event_is_section(sc, 1) == 1 && dal_scene_event_is_section(sc, 2) == -1);
  CHECK(dal_scene_strobe(sc) == 0);
  int rc = dal_scene_run_events(sc, NULL, ev, &st, msg, sizeof msg);
  CHECK_MSG(rc == DAL_EVENT, "run: %d %s", rc, msg);
  double a = 1, b = sqrt(1 - pow(sin(0.5), 2));
  for (int i = 0; i < 40; ++i) {
    double an = (a + b) / 2;
    b = sqrt(a * b);
    a = an;
  }
  double quarter = sqrt(1 / 9.8) * PI / (2 * a);
  CHECK(st && fabs(dal_state_time(st) - quarter) < 1e-10);
  CHECK(dal_events_count(ev) == 1);
  printf("terminal event 'bottom' at t = %.15f, quarter period %.15f\n",
         st ? dal_state_time(st) : NAN, quarter);
  dal_state_destroy(st);
  dal_events_destroy(ev);
  dal_scene_destroy(sc);
}

int main(void) {
  terminal_event();
  show_more();
  oscillator();
  driven();
  bead("bead_ring_below.scene", 2.0);
  bead("bead_ring_above.scene", 5.0);
  const char *seeds[] = {"sicm_oscillator.scene", "driven_pendulum.scene", "bead_ring_below.scene",
                         "bead_ring_above.scene"};
  for (int i = 0; i < 4; ++i)
    write_back(seeds[i]);
  errors();
  return check_summary("test_scene");
}
