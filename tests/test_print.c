// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The model and state printers name every element and print the values the accessors give.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

// print into a buffer through a temporary file
static char *capture(const dal_system *sys, const dal_state *st) {
  FILE *fp = tmpfile();
  if (!fp) return NULL;
  int rc = st ? dal_state_print(sys, st, fp) : dal_system_print(sys, fp);
  CHECK_OK(rc);
  long len = ftell(fp);
  char *buf = calloc((size_t)len + 1, 1);
  rewind(fp);
  if (buf && fread(buf, 1, (size_t)len, fp) != (size_t)len) buf[0] = 0;
  fclose(fp);
  return buf;
}

static int has(const char *s, const char *what) { return s && strstr(s, what) != NULL; }

// the printout holds "label=<value as %.17g>"
static int has_value(const char *s, const char *label, double x) {
  char want[96];
  snprintf(want, sizeof want, "%s=%.17g", label, x);
  return has(s, want);
}

// L = v^2 / 2 - k q^2 / 2 with k = 4 (a unit-mass oscillator)
static int osc_lagrangian(dal_jet t, const dal_jet *q, const dal_jet *qdot, dal_jet *L, void *ctx) {
  (void)t, (void)ctx;
  *L = dal_sub(dal_scale(dal_sq(qdot[0]), 0.5), dal_scale(dal_sq(q[0]), 2.0));
  return 0;
}

// the number printed after "label=" (NaN if none)
static double value_of(const char *s, const char *label) {
  const char *p = s ? strstr(s, label) : NULL;
  return p ? strtod(p + strlen(label), NULL) : NAN;
}

// a Lagrangian system has no separate Q and c: the printer shows A qddot, which the closed
// form gives (A = 1, qddot = -k q), and the forces from outside L (none here)
static void test_lagrangian(void) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  int x;
  CHECK_OK(dal_builder_create(0, &b));
  CHECK_OK(dal_builder_add_coord(b, "x", &x));
  CHECK_OK(dal_builder_set_lagrangian(b, osc_lagrangian, NULL));
  CHECK_OK(dal_builder_compile(b, &sys));
  CHECK_OK(dal_state_create(sys, &st));
  double q = 0.3, v = 0.2;
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &v));
  CHECK_OK(dal_forward(sys, st));
  char *txt = capture(sys, st);
  CHECK(has(txt, "Lagrangian system") && !has(txt, " c=") && !has(txt, " Q="));
  double aq = value_of(txt, "Aqddot="), qdd = value_of(txt, "qddot="), qe = value_of(txt, "Q_ext=");
  CHECK_MSG(fabs(aq - (-4.0 * q)) <= 1e-14 && fabs(qdd - (-4.0 * q)) <= 1e-14 && qe == 0.0,
            "Lagrangian printout: Aqddot=%g qddot=%g Q_ext=%g (want -1.2, -1.2, 0)", aq, qdd, qe);
  free(txt);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
}

int main(void) {
  test_lagrangian();
  // a double pendulum hanging from a spring-mounted cart, plus a rod to a wall point
  dal_builder *b = NULL;
  int xc, th1, th2, cart, b1, b2;
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, "x_cart", &xc));
  CHECK_OK(dal_builder_add_coord(b, "theta1", &th1));
  CHECK_OK(dal_builder_add_coord(b, "theta2", &th2));
  CHECK_OK(dal_builder_add_particle(b, "cart", 3.0, &cart));
  CHECK_OK(dal_builder_add_particle(b, "bob1", 1.25, &b1));
  CHECK_OK(dal_builder_add_particle(b, "bob2", 0.75, &b2));
  dal_place_def d = dal_default_place_def();
  d.prim = &dal_map_pendulum;
  d.coords = &xc;
  d.ncoords = 1;
  d.param[DAL_PENDULUM_L] = 0.5; // the cart swings on a short pendulum from (0, 1)
  d.param[DAL_PENDULUM_Y0] = 1.0;
  CHECK_OK(dal_builder_place_def(b, cart, &d));
  d = dal_default_place_def();
  d.prim = &dal_map_hanging;
  d.parent = cart;
  d.coords = &th1;
  d.ncoords = 1;
  d.param[DAL_HANGING_L] = 0.8;
  CHECK_OK(dal_builder_place_def(b, b1, &d));
  d.parent = b1;
  d.coords = &th2;
  d.param[DAL_HANGING_L] = 0.6;
  CHECK_OK(dal_builder_place_def(b, b2, &d));
  dal_spring_def sd = dal_default_spring_def();
  sd.a = b2;
  sd.k = 12.5;
  sd.length = 0.3;
  sd.anchor[0] = 1.5;
  CHECK_OK(dal_builder_add_spring_def(b, &sd));
  double g[2] = {0, -9.81};
  CHECK_OK(dal_builder_set_gravity(b, g));
  dal_system *sys = NULL;
  CHECK_OK(dal_builder_compile(b, &sys));
  char *txt = capture(sys, NULL);
  CHECK(txt != NULL);
  for (int i = 0; i < dal_system_ncoords(sys); ++i)
    CHECK(has(txt, dal_system_coord_name(sys, i)));
  for (int k = 0; k < dal_system_nparticles(sys); ++k) {
    CHECK(has(txt, dal_system_particle_name(sys, k)));
    CHECK(has_value(txt, "mass", dal_system_mass(sys, k)));
  }
  CHECK(has(txt, "'pendulum'") && has(txt, "'hanging'") && has(txt, "on parent 'bob1'"));
  CHECK(has_value(txt, "l", 0.5) && has_value(txt, "y0", 1.0) && has_value(txt, "l", 0.6));
  CHECK(has_value(txt, "k", 12.5) && has_value(txt, "length", 0.3) && has(txt, "gravity"));
  free(txt);

  // the state: values equal the accessors'
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q[3] = {0.2, -0.4, 0.9}, v[3] = {0.1, 0.3, -0.2};
  CHECK_OK(dal_state_set(sys, st, 0.5, q, v));
  txt = capture(sys, st);
  CHECK(has(txt, "not evaluated"));
  free(txt);
  CHECK_OK(dal_forward(sys, st));
  txt = capture(sys, st);
  int n = dal_system_ncoords(sys);
  for (int i = 0; i < n; ++i) {
    CHECK(has_value(txt, "q", dal_state_q(st)[i]));
    CHECK(has_value(txt, "qddot", dal_state_qddot(st)[i]));
    CHECK(has_value(txt, "Q", dal_state_genforces(st)[i]));
    CHECK(has_value(txt, "c", dal_state_bias(st)[i]));
    for (int j = 0; j < n; ++j) {
      char want[64];
      snprintf(want, sizeof want, " %.17g", dal_state_mass_matrix(st)[j * n + i]);
      CHECK(has(txt, want));
    }
  }
  dal_energies en;
  CHECK_OK(dal_state_energies(st, &en));
  CHECK(has_value(txt, "T", en.T) && has_value(txt, "U", en.U) && has_value(txt, "h", en.h));
  free(txt);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_builder_destroy(b);

  // a constrained system prints its rows, multipliers and residuals
  scn_knobs k = scn_default(); // the Cartesian pendulum of the scene library: 'bob' on 'rod'
  k.m = 2.0;
  k.l = 1.5;
  k.y0 = 0.25;
  sys = scn_cart_pendulum(&k);
  b = NULL;
  CHECK(sys != NULL);
  txt = capture(sys, NULL);
  CHECK(has(txt, "'rod' by 'anchor2' on particles ('bob')"));
  CHECK(has_value(txt, "L", 1.5));
  CHECK(has_value(txt, "y0", 0.25));
  CHECK(has_value(txt, "x0", 0.0));
  CHECK(has(txt, "2 coordinates, 1 particles, 1 constraint rows"));
  CHECK(has(txt, "'bob' mass=2 placed by 'cartesian2' of ('x', 'y')"));
  CHECK(has(txt, "gravity (0, -9.81"));
  CHECK(has(txt, "[0] 'x'") && has(txt, "[1] 'y'"));
  free(txt);
  CHECK_OK(dal_state_create(sys, &st));
  double qc[2] = {1.5 * sin(0.3), 0.25 - 1.5 * cos(0.3)}, vc[2] = {0, 0};
  CHECK_OK(dal_state_set(sys, st, 0.0, qc, vc));
  CHECK_OK(dal_make_consistent(sys, st, 0.0, NULL));
  txt = capture(sys, st);
  CHECK(has(txt, "'rod'"));
  CHECK(has_value(txt, "lambda", dal_state_lambda(st)[0]));
  CHECK(has_value(txt, "phi", dal_state_phi(st)[0]));
  CHECK(has(txt, "last consistent start"));
  free(txt);
  CHECK(dal_system_print(NULL, stdout) == DAL_E_ARG);
  CHECK(dal_state_print(sys, NULL, stdout) == DAL_E_ARG);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
  return check_summary("test_print");
}
