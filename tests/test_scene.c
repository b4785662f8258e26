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
#include <time.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "dalembert/scene.h"
#include "scenes.h"

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
  CHECK_OK(scn_place_by(b, p, prim, -1, 1, &th, np, param, NULL));
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
  // a built-in constraint primitive without formulas (on_line3: its normal pair is chosen by a
  // branch on the direction) is not shown, and it says so
  dal_scene *sc;
  char msg[512];
  CHECK_OK(dal_scene_parse("dim 3\ncoord x\ncoord y\ncoord z\nparticle b mass=1\n"
                           "place b = x; y; z\nconstraint c on_line3 parts=b\n",
                           "c.scene", &sc, msg, sizeof msg));
  FILE *fp = tmpfile();
  CHECK(sc && dal_scene_show(sc, fp, DAL_EXPR_TEXT, msg, sizeof msg) == DAL_E_UNSUPPORTED &&
        strstr(msg, "c.scene:7: constraint c: the primitive 'on_line3' has no formulas"));
  fclose(fp);
  dal_scene_destroy(sc);
}

// the state of a scene's own run at T, or NaN when it does not read
static void run_text(const char *text, double T, double *y, int n) {
  dal_scene *sc = NULL;
  char msg[1024];
  int rc = dal_scene_parse(text, "run.scene", &sc, msg, sizeof msg);
  CHECK_MSG(rc == 0, "%s", msg);
  for (int i = 0; i < 2 * n; ++i)
    y[i] = NAN;
  if (sc) run_scene(sc, T, y);
  dal_scene_destroy(sc);
}

// 1. lists of any length: an anchor= and a parts= list past 511 characters build the model
// they say, bit for bit the one of the short list (before: cut at 511 characters, another
// model with DAL_OK: the anchor's y lost, the second part taken for a particle named by the
// first 210 letters of its name)
static void long_lists(void) {
  char zeros[700] = "", a300[301], b300[301], b210[211];
  for (int i = 0; i < 300; ++i)
    strcat(zeros, "0+");
  memset(a300, 'a', 300), a300[300] = 0;
  memset(b300, 'b', 300), b300[300] = 0;
  memset(b210, 'b', 210), b210[210] = 0;
  const char *fmt = "dim 2\ncoord x q=1\ncoord y q=0\nparticle b mass=1\nplace b = x; y\n"
                    "spring b anchor=%s1,2 k=3\ngravity 0 -1\n";
  char shortt[512], *longt = malloc(4096);
  snprintf(shortt, sizeof shortt, fmt, "");
  snprintf(longt, 4096, fmt, zeros);
  double y1[4], y2[4];
  run_text(shortt, 2.0, y1, 2);
  run_text(longt, 2.0, y2, 2);
  CHECK_MSG(!memcmp(y1, y2, sizeof y1), "long anchor list: (%g, %g) against (%g, %g)", y2[0], y2[1],
            y1[0], y1[1]);
  const char *pf = "dim 2\ncoord x q=0.6\ncoord y q=-0.8\ncoord z q=3\n"
                   "particle %s mass=1\nplace %s fixed2 x=0 y=0\nparticle %s mass=1\n"
                   "place %s = x; y\nparticle %s mass=1\nplace %s = z; 0\n"
                   "constraint c distance2 parts=%s,%s L=1\ngravity 0 -9.8\n";
  snprintf(longt, 4096, pf, a300, a300, b300, b300, b210, b210, a300, b300);
  snprintf(shortt, sizeof shortt, pf, "a", "a", "b", "b", "c", "c", "a", "b");
  double y3[6], y4[6];
  run_text(shortt, 1.0, y3, 3);
  run_text(longt, 1.0, y4, 3);
  CHECK_MSG(!memcmp(y3, y4, sizeof y3), "long parts list: x = %g against %g", y4[0], y3[0]);
  free(longt);
  refused("dim 2\ncoord x\nparticle b mass=1\nplace b = x; 0\nspring b anchor=1,2,3 k=1\n",
          "bad.scene:5: spring b", "anchor of 3 components for dimension 2");
  refused("dim 2\ncoord x\nparticle b mass=1\nplace b = x; 0\nspring b k=1 c=2\n",
          "bad.scene:5: spring b", "unknown word 'c=2'");
}

// 2. a name given twice is refused on the later line, naming the earlier
static void names_twice(void) {
  static const char *const rows[][3] = {
      {"dim 2\ncoord th\ncoord th\nparticle b mass=1\nplace b = sin(th); -cos(th)\n",
       "bad.scene:3: coord th", "'th' is given twice (line 2 and here)"},
      {"dim 2\ncoord th\nparticle b mass=1\nparticle b mass=2\nplace b = sin(th); 0\n",
       "bad.scene:4: particle b", "'b' is given twice (line 3 and here)"},
      {"dim 2\ncoord th\nparam th = 1\nparticle b mass=1\nplace b = sin(th); 0\n",
       "bad.scene:3: ", "'th' is given twice (line 2 and this line)"},
      {"dim 2\nparam thdot = 1\ncoord th\nparticle b mass=1\nplace b = sin(th); 0\n",
       "bad.scene:3: coord th", "'thdot' is given twice (line 2 and here)"},
      {"dim 2\ncoord x_b\nparticle b mass=1\nplace b = x_b; 0\n", "bad.scene:3: particle b",
       "'x_b' is given twice (line 2 and here)"},
      {"dim 2\ncoord th\nparticle b mass=1\nplace b = sin(th); -cos(th)\nconstraint c = th\n"
       "constraint c = th - 1\n",
       "bad.scene:6: constraint c", "'c' is given twice (line 5 and here)"},
      {"dim 2\ncoord th\nparticle b mass=1\nplace b = sin(th); -cos(th)\nevent e = th\n"
       "section e = thdot\n",
       "bad.scene:6: section e", "'e' is given twice (line 5 and here)"},
      {"param g = 1\ndim 2\nparam g = 2\n", "bad.scene:3: param g",
       "'g' is given twice (line 1 and here)"},
  };
  for (size_t i = 0; i < sizeof rows / sizeof *rows; ++i)
    refused(rows[i][0], rows[i][1], rows[i][2]);
}

// 3. formulas wherever a number is taken: a param of the parameters above (its value follows
// them through dal_scene_set_param; a value set on it wins), spaces after key=
static void param_formulas(void) {
  const char *derived = "dim 2\nparam g = 9.8\nparam omega = 2 * sqrt(g)\nparam a = 0.1\n"
                        "coord th q=1 v=0.5 * omega - 3\nparticle b mass=1\n"
                        "place b = sin(th); a*cos(omega*t) - cos(th)\ngravity 0 -g\n";
  char plain[512];
  snprintf(plain, sizeof plain,
           "dim 2\nparam g = 9.8\nparam omega = %.17g\nparam a = 0.1\n"
           "coord th q=1 v=%.17g\nparticle b mass=1\n"
           "place b = sin(th); a*cos(omega*t) - cos(th)\ngravity 0 -g\n",
           2 * sqrt(9.8), 0.5 * (2 * sqrt(9.8)) - 3);
  double y1[2], y2[2];
  run_text(derived, 2.0, y1, 1);
  run_text(plain, 2.0, y2, 1);
  CHECK_MSG(!memcmp(y1, y2, sizeof y1), "param omega = 2*sqrt(g): theta %.17g against %.17g", y1[0],
            y2[0]);
  // g = 4 through set_param: omega becomes 4, as the scene written with those numbers
  dal_scene *sc = NULL;
  char msg[512];
  CHECK_OK(dal_scene_parse(derived, "d.scene", &sc, msg, sizeof msg));
  if (!sc) return;
  CHECK_OK(dal_scene_set_param(sc, "g", 4.0, msg, sizeof msg));
  run_scene(sc, 2.0, y1);
  snprintf(plain, sizeof plain,
           "dim 2\nparam g = 4\nparam omega = 4\nparam a = 0.1\ncoord th q=1 v=%.17g\n"
           "particle b mass=1\nplace b = sin(th); a*cos(omega*t) - cos(th)\ngravity 0 -g\n",
           0.5 * 4.0 - 3);
  run_text(plain, 2.0, y2, 1);
  CHECK_MSG(!memcmp(y1, y2, sizeof y1), "g = 4: theta %.17g against %.17g", y1[0], y2[0]);
  // a value set on the derived parameter wins, and the scene writes it back as that number
  CHECK_OK(dal_scene_set_param(sc, "omega", 5.0, msg, sizeof msg));
  char *w = NULL;
  size_t wn = 0;
  FILE *fp = open_memstream(&w, &wn);
  dal_scene_write(sc, fp);
  fclose(fp);
  CHECK_MSG(strstr(w, "\nparam g = 4\nparam omega = 5\n") &&
                strstr(w, "\ncoord th q=1 v=0.5 * omega - 3\n"),
            "written: %s", w);
  free(w);
  dal_scene_destroy(sc);
  refused("param a = b + 1\nparam b = 2\n", "bad.scene:1: param a", "unknown symbol 'b'");
}

// 4. show of the built-in constraints: each row shown as a formula, evaluated at a point off
// the constraint, equals the primitive's own jet function there
static void show_builtin(void) {
  static const struct {
    const char *prim, *args;
    int d, nparts;
  } rows[] = {
      {"distance2", "L=1.3", 2, 2},
      {"distance3", "L=1.3", 3, 2},
      {"anchor2", "L=1.3 x0=0.2 y0=-0.1", 2, 1},
      {"anchor3", "L=1.3 x0=0.2 y0=-0.1 z0=0.3", 3, 1},
      {"on_circle2", "R=0.9 cx=0.1 cy=0.2", 2, 1},
      {"on_circle3", "R=0.9 cx=0.1 cy=0.2 cz=-0.3 nx=0.3 ny=-0.5 nz=0.8", 3, 1},
      {"turning_circle", "R=0.9 w=1.7 phi0=0.3 cx=0.1 cy=0.2 cz=-0.3", 3, 1},
      {"on_sphere", "R=0.9 cx=0.1 cy=0.2 cz=-0.3", 3, 1},
      {"on_plane", "cx=0.1 cy=0.2 cz=-0.3 nx=0.3 ny=-0.5 nz=0.8", 3, 1},
      {"on_line2", "cx=0.1 cy=0.2 ax=0.6 ay=-0.8", 2, 1},
      {"turning_line2", "cx=0.1 cy=0.2 w=1.3 phi0=0.4", 2, 1},
      {"prescribed", "th q0=0.25", 2, 0},
  };
  const char *names[] = {"x1", "y1", "z1", "x2", "y2", "z2", "th"};
  const double at[] = {0.31, -0.72, 0.55, -0.4, 0.93, 0.18, 0.61}, t = 0.37;
  for (size_t r = 0; r < sizeof rows / sizeof *rows; ++r) {
    const dal_primitive *prim = dal_primitive_find(rows[r].prim);
    int d = rows[r].d;
    char text[1024], *out = NULL, msg[512];
    snprintf(text, sizeof text,
             "dim %d\ncoord x1\ncoord y1\n%scoord x2\ncoord y2\n%scoord th\n"
             "particle a mass=1\nplace a = x1; y1%s\nparticle b mass=1\nplace b = x2; y2%s\n"
             "particle c mass=1\nplace c = th; 0%s\nconstraint k %s%s %s\n",
             d, d == 3 ? "coord z1\n" : "", d == 3 ? "coord z2\n" : "", d == 3 ? "; z1" : "",
             d == 3 ? "; z2" : "", d == 3 ? "; 0" : "", rows[r].prim,
             rows[r].nparts == 2   ? " parts=a,b"
             : rows[r].nparts == 1 ? " parts=a"
                                   : "",
             rows[r].args);
    dal_scene *sc = NULL;
    CHECK_MSG(prim && !dal_scene_parse(text, "k.scene", &sc, msg, sizeof msg), "%s: %s",
              rows[r].prim, msg);
    if (!sc || !prim) continue;
    size_t n = 0;
    FILE *fp = open_memstream(&out, &n);
    int rc = dal_scene_show(sc, fp, DAL_EXPR_TEXT, msg, sizeof msg);
    fclose(fp);
    CHECK_MSG(rc == 0, "%s: show: %s", rows[r].prim, msg);
    // the primitive at the point: inputs the parts' positions, then the coordinates
    double param[16];
    for (int i = 0; i < prim->nparam; ++i)
      param[i] = prim->param_defaults ? prim->param_defaults[i] : NAN;
    for (const char *w = rows[r].args; w && *w;) {
      const char *eq = strchr(w, '='), *sp = strchr(w, ' ');
      if (eq && (!sp || eq < sp))
        for (int i = 0; i < prim->nparam; ++i)
          if (strlen(prim->param_names[i]) == (size_t)(eq - w) &&
              !strncmp(prim->param_names[i], w, (size_t)(eq - w)))
            param[i] = atof(eq + 1);
      w = sp ? sp + 1 : NULL;
    }
    dal_jet in[8], phi[2];
    int k = 0;
    for (int p = 0; p < rows[r].nparts; ++p)
      for (int c = 0; c < d; ++c)
        in[k++] = dal_const(at[3 * p + c]);
    if (!rows[r].nparts) in[k++] = dal_const(at[6]);
    prim->eval(in, dal_const(t), param, phi, NULL);
    for (int row = 0; row < prim->nout && out; ++row) {
      char key[32];
      snprintf(key, sizeof key, prim->nout > 1 ? "\nphi_k%d = " : "\nphi_k = ", row + 1);
      const char *f = strstr(out, key);
      CHECK_MSG(f != NULL, "%s: no row %d shown", rows[r].prim, row + 1);
      if (!f) continue;
      f += strlen(key);
      char *line = strndup(f, strcspn(f, "\n"));
      dal_expr_def ed = dal_default_expr_def();
      ed.formulas = (const char *const *)&line;
      ed.nout = 1;
      ed.inputs = names;
      ed.nin = 7;
      dal_expr *e = NULL;
      CHECK_OK(dal_expr_create(&ed, &e, msg, sizeof msg));
      dal_jet x[7], v = dal_const(NAN);
      for (int i = 0; i < 7; ++i)
        x[i] = dal_const(i == 6 ? at[6] : at[i]);
      if (e) dal_expr_eval(e, x, dal_const(t), NULL, &v);
      CHECK_MSG(fabs(v.v - phi[row].v) < 1e-13, "%s row %d: shown %.17g, primitive %.17g",
                rows[r].prim, row + 1, v.v, phi[row].v);
      dal_expr_destroy(e);
      free(line);
    }
    free(out);
    dal_scene_destroy(sc);
  }
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

// 5. damper and force lines against closed forms: the damped oscillator m x'' = -k x - c x'
// (a spring and a damper anchored far off on the x axis, or a force line -c*xdot: both exact
// along the axis), x(t) = e^(-g t) (cos(wd t) + g/wd sin(wd t)), g = c/(2m), wd^2 = k/m - g^2;
// a constant generalized force F: x = x0 + v0 t + F t^2/(2m)
static void damper_force(void) {
  const double m = 2, k = 3, c = 0.4, T = 5, g = c / (2 * m), wd = sqrt(k / m - g * g);
  const double xs = exp(-g * T) * (cos(wd * T) + g / wd * sin(wd * T));
  const double vs = -exp(-g * T) * (k / m) / wd * sin(wd * T);
  const char *head = "dim 2\nparam m = 2\nparam k = 3\nparam c = 0.4\ncoord x q=1 v=0\n"
                     "coord y q=0\nparticle b mass=m\nplace b = x; y\n"
                     "spring b anchor=-100,0 k=k L=100\nrun method=bs rtol=1e-12 atol=1e-14\n";
  const char *tails[] = {"damper b anchor=-1000,0 c=c\n", "force x = -c*xdot\n"};
  for (int i = 0; i < 2; ++i) {
    char text[1024];
    snprintf(text, sizeof text, "%s%s", head, tails[i]);
    double y[4];
    run_text(text, T, y, 2);
    printf("damped oscillator by %s: x(5) = %.15f (closed form %.15f), v(5) = %.15f (%.15f)\n",
           i ? "a force line" : "a damper", y[0], xs, y[2], vs);
    CHECK_CLOSE(y[0], xs, 1e-10);
    CHECK_CLOSE(y[2], vs, 1e-10);
  }
  double y[2];
  run_text("dim 2\nparam F = 0.7\ncoord x q=0.5 v=-1\nparticle b mass=2\nplace b = x; 0\n"
           "force x = F\nrun method=bs rtol=1e-12\n",
           3.0, y, 1);
  CHECK_CLOSE(y[0], 0.5 - 3.0 + 0.7 * 9.0 / 4.0, 1e-12);
  CHECK_CLOSE(y[1], -1.0 + 0.7 * 3.0 / 2.0, 1e-12);
  // show: the force line joins Q, and the shown acceleration is the library's
  dal_scene *sc = NULL;
  dal_state *st = NULL;
  char msg[512], *out = NULL;
  size_t n = 0;
  CHECK_OK(dal_scene_parse("dim 2\nparam g = 9.8\nparam c = 0.3\ncoord a q=0.4 v=0.7\n"
                           "particle p mass=1\nplace p = sin(a); -cos(a)\ngravity 0 -g\n"
                           "force a = -c*adot + sin(t)\n",
                           "f.scene", &sc, msg, sizeof msg));
  if (!sc) return;
  FILE *fp = open_memstream(&out, &n);
  fputc('\n', fp);
  CHECK_OK(dal_scene_show(sc, fp, DAL_EXPR_TEXT, msg, sizeof msg));
  fclose(fp);
  CHECK_OK(dal_scene_state(sc, &st));
  CHECK_OK(dal_forward(dal_scene_system(sc), st));
  double shown_a = shown(out, "addot", sc, st);
  CHECK_CLOSE(shown_a, dal_state_qddot(st)[0], 1e-14);
  CHECK(strstr(out, "\nM qddot = F + Q\n") != NULL);
  free(out);
  dal_state_destroy(st);
  dal_scene_destroy(sc);
  refused("dim 2\ncoord x\nparticle b mass=1\nplace b = x; 0\nforce z = 1\n", "bad.scene:5",
          "'z' is not a coordinate defined above");
}

// 6. parsing is linear in the scene's size: 10^5 parameters read (and written) in a moment
// (before: quadratic, 4 10^4 took 67 s)
static void many_params(void) {
  const int n = 100000;
  char *text = malloc((size_t)n * 32 + 256), *w = text;
  w += sprintf(w, "dim 2\n");
  for (int i = 0; i < n; ++i)
    w += sprintf(w, "param p%d = %d\n", i, i + 1);
  sprintf(w, "coord th q=p5 / 10\nparticle b mass=p7\nplace b = sin(th); -cos(th)\n"
             "gravity 0 -p99999\n");
  struct timespec a, b;
  clock_gettime(CLOCK_MONOTONIC, &a);
  dal_scene *sc = NULL;
  char msg[512];
  CHECK_OK(dal_scene_parse(text, "many.scene", &sc, msg, sizeof msg));
  clock_gettime(CLOCK_MONOTONIC, &b);
  double s = (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
  printf("10^5 parameters read in %.3f s\n", s);
  CHECK(s < 10.0);
  CHECK(sc && dal_scene_opts(sc, NULL, NULL, NULL) != NULL);
  dal_scene_destroy(sc);
  free(text);
}

// 7. the symbolic printer is bounded: a 435-character formula found by fuzzing (10 s to print
// before) is too large to show, said at once; show of a scene holding it says so too
static void print_bounded(void) {
  const char *f =
      "((((((((p+(((y)^5-(p*0.5)))^5))^4*sqrt(tan(cos(y))))*((1+(((ydot-atan(2)))/(((ydot+p)-p)))"
      "^p)+tan((2-2)))))^p*((((((log(atan(xdot))*(p-(ydot*0.5)))*ydot)*((((x+ydot)-(xdot)^-2)-1)*"
      "((1+(t*y))+(cos(1)-log(2)))))-((((y*x)+0.5)-(((1-xdot)-sin(x))+(t)^3))+((((x*xdot)-atan("
      "xdot))+((2*1))^-2)*(((0.5*t))^-1+y)))))^5*(((((sin(sin(ydot))*(exp(xdot))/((t+y)))+(sin(("
      "y*ydot))*((0.5+1)+0.5)))*p)*sin(2))*(t+((((2*atan(p)))^5)^-1)^5))))-exp(2)))^2";
  const char *in[] = {"x", "y"}, *pn[] = {"p"};
  double pv[] = {0.7};
  dal_expr_def d = dal_default_expr_def();
  d.formulas = &f;
  d.nout = 1;
  d.inputs = in;
  d.nin = 2;
  d.velocities = 1;
  d.params = pn;
  d.values = pv;
  d.nparam = 1;
  dal_expr *e = NULL;
  char msg[1024];
  CHECK_OK(dal_expr_create(&d, &e, msg, sizeof msg));
  struct timespec a, b;
  clock_gettime(CLOCK_MONOTONIC, &a);
  int rc = e ? dal_expr_print(e, 0, DAL_EXPR_TEXT, NULL, 0) : 0;
  clock_gettime(CLOCK_MONOTONIC, &b);
  double s = (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
  printf("a 435-character formula: dal_expr_print %d (%s) in %.3f s\n", rc, dal_status_string(rc),
         s);
  CHECK(rc == DAL_E_TOO_LARGE);
  dal_expr_destroy(e);
  char *text = malloc(strlen(f) + 256);
  sprintf(text, "dim 0\nparam p = 0.7\ncoord x\ncoord y\nlagrangian = %s\n", f);
  dal_scene *sc = NULL;
  CHECK_OK(dal_scene_parse(text, "big.scene", &sc, msg, sizeof msg));
  FILE *fp = tmpfile();
  rc = sc ? dal_scene_show(sc, fp, DAL_EXPR_TEXT, msg, sizeof msg) : 0;
  CHECK_MSG(rc == DAL_E_TOO_LARGE && strstr(msg, "big.scene") && strstr(msg, "too large to show"),
            "show: %d '%s'", rc, msg);
  fclose(fp);
  dal_scene_destroy(sc);
  free(text);
}

int main(void) {
  long_lists();
  names_twice();
  param_formulas();
  show_builtin();
  damper_force();
  many_params();
  print_bounded();
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
