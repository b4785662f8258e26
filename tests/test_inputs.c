// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Linearization with inputs (dal_linearize_inputs): the pendulum on a cart with a horizontal
// force F on the cart, hanging and upright, against the textbook linearization
//   (Mc + m) x'' + m l th'' cos th0 = F,   m l x'' cos th0 + m l^2 th'' + m g l cos th0 th = 0
// (th from the downward vertical; cos th0 = +1 hanging, -1 upright), i.e. with s = cos th0
//   x'' = (F + m g th) / Mc,   th'' = -s (F + (Mc + m) g th) / (Mc l);
// in minimal coordinates (a whole-system map) entry by entry, and written in Cartesian
// coordinates (cart on a line, bob on a rod) through the coordinate-free Markov parameters
// c A^j b of the output x (the cart position); plus a parameter input (the bob's mass) against
// central differences of the accelerations, and the refusal of a primitive parameter.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

static const double MC = 1.7, MB = 0.4, L = 0.8, G0 = SCN_G;

// cart at (x, 0), bob at (x + l sin th, -l cos th)
static int cart_map(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx) {
  (void)t;
  (void)ctx;
  r[0] = q[0];
  r[1] = dal_const(0.0);
  r[2] = dal_add(q[0], dal_scale(dal_sin(q[1]), L));
  r[3] = dal_scale(dal_cos(q[1]), -L);
  return 0;
}

static dal_system *cart_minimal(void) {
  dal_builder *b = NULL;
  int c, p, rc = dal_builder_create(2, &b);
  double g[2] = {0.0, -G0};
  if (!rc) rc = dal_builder_add_coord(b, "x", &c);
  if (!rc) rc = dal_builder_add_coord(b, "th", &c);
  if (!rc) rc = dal_builder_add_particle(b, "cart", MC, &p);
  if (!rc) rc = dal_builder_add_particle(b, "bob", MB, &p);
  if (!rc) rc = dal_builder_set_map(b, cart_map, NULL);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  return scn_finish(b, rc);
}

static dal_system *cart_cartesian(void) {
  dal_builder *b = NULL;
  int p[2], rc = scn_builder(NULL, 2, &b);
  if (!rc) rc = scn_add_xy(b, "cart", MC, "xc", "yc", &p[0]);
  if (!rc) rc = scn_add_xy(b, "bob", MB, "xb", "yb", &p[1]);
  dal_constraint_def rail = dal_default_constraint_def();
  rail.name = "rail";
  rail.prim = &dal_con_line2; // the x axis
  rail.parts = &p[0];
  rail.nparts = 1;
  if (!rc) rc = dal_builder_add_constraint_def(b, &rail, NULL);
  if (!rc) rc = scn_add_rod(b, "rod", p[0], p[1], L, NULL);
  return scn_finish(b, rc);
}

// the textbook first-order A (4 x 4) and b (4) in x = (x, th, x', th')
static void textbook(double s, double *A, double *b) {
  memset(A, 0, 16 * sizeof(double));
  memset(b, 0, 4 * sizeof(double));
  A[2 * 4 + 0] = A[3 * 4 + 1] = 1.0;
  A[1 * 4 + 2] = MB * G0 / MC;                   // dx''/dth
  A[1 * 4 + 3] = -s * (MC + MB) * G0 / (MC * L); // dth''/dth
  b[2] = 1.0 / MC;
  b[3] = -s / (MC * L);
}

static void minimal(void) {
  dal_system *sys = cart_minimal();
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  const char *in[2] = {"force:x", "mass:bob"};
  for (int up = 0; up < 2; ++up) {
    double q[2] = {0.3, up ? 3.14159265358979323846 : 0.0}, v[2] = {0.0, 0.0};
    CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
    double B[4], Af[16], Bf[8], At[16], bt[4];
    int rc = dal_linearize_inputs(sys, st, 2, in, B, Af, Bf);
    CHECK_MSG(rc == 0, "linearize_inputs: %s", dal_state_errmsg(st));
    textbook(up ? -1.0 : 1.0, At, bt);
    double worst = 0.0;
    for (int i = 0; i < 16; ++i) {
      CHECK_CLOSE(Af[i], At[i], 1e-13);
      worst = fmax(worst, fabs(Af[i] - At[i]));
    }
    for (int i = 0; i < 4; ++i) {
      CHECK_CLOSE(Bf[i], bt[i], 1e-14);
      worst = fmax(worst, fabs(Bf[i] - bt[i]));
    }
    CHECK(B[0] == 1.0 && B[1] == 0.0); // the force acts on x
    printf("cart-pendulum (%s, minimal): A, B vs textbook worst %.3g\n", up ? "upright" : "hanging",
           worst);
    // the mass input against central differences of the accelerations (oracle)
    double acc[2][2];
    for (int sgn = 0; sgn < 2; ++sgn) {
      dal_state *sp = NULL;
      CHECK_OK(dal_state_create(sys, &sp));
      CHECK_OK(dal_state_set_param_named(sys, sp, "mass:bob", MB + (sgn ? -1e-5 : 1e-5)));
      CHECK_OK(dal_state_set(sys, sp, 0.0, q, v));
      CHECK_OK(dal_forward(sys, sp));
      memcpy(acc[sgn], dal_state_qddot(sp), sizeof acc[sgn]);
      dal_state_destroy(sp);
    }
    for (int i = 0; i < 2; ++i)
      CHECK_CLOSE(Bf[4 + 2 + i], (acc[0][i] - acc[1][i]) / 2e-5, 1e-8);
  }
  const char *bad[1] = {"force:nope"};
  CHECK(dal_linearize_inputs(sys, st, 1, bad, NULL, NULL, NULL) == DAL_E_ARG);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// the Markov parameters c A^j b (j = 0..7, which fix the transfer function of a 4-state
// system) of the output x from an (A, b, c) of size 2k
static void markov(int k2, const double *A, const double *b, const double *c, double *out) {
  double v[8], w[8];
  memcpy(v, b, (size_t)k2 * sizeof(double));
  for (int j = 0; j < 8; ++j) {
    double s = 0.0;
    for (int i = 0; i < k2; ++i)
      s += c[i] * v[i];
    out[j] = s;
    for (int i = 0; i < k2; ++i) {
      w[i] = 0.0;
      for (int l = 0; l < k2; ++l)
        w[i] += A[l * k2 + i] * v[l];
    }
    memcpy(v, w, (size_t)k2 * sizeof(double));
  }
}

static void cartesian(void) {
  dal_system *sys = cart_cartesian();
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  const char *in[1] = {"force:xc"};
  for (int up = 0; up < 2; ++up) {
    double q[4] = {0.3, 0.0, 0.3, up ? L : -L}, v[4] = {0};
    CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
    double Af[16], Bf[4], N[8], At[16], bt[4];
    int rc = dal_linearize_inputs(sys, st, 1, in, NULL, Af, Bf);
    CHECK_MSG(rc == 0, "linearize_inputs: %s", dal_state_errmsg(st));
    CHECK_OK(dal_linearize_full(sys, st, NULL, NULL, NULL, NULL, N));
    textbook(up ? -1.0 : 1.0, At, bt);
    // output x = xc: (N xi)_0 in the reduced coordinates, x in the textbook ones
    double cr[4] = {N[0], N[4], 0.0, 0.0}, ct[4] = {1.0, 0.0, 0.0, 0.0}, mr[8], mt[8];
    markov(4, Af, Bf, cr, mr);
    markov(4, At, bt, ct, mt);
    printf("cart-pendulum (%s, Cartesian): Markov parameters %.15g %.15g %.15g %.15g, textbook "
           "%.15g %.15g %.15g %.15g\n",
           up ? "upright" : "hanging", mr[0], mr[1], mr[2], mr[3], mt[0], mt[1], mt[2], mt[3]);
    for (int j = 0; j < 8; ++j)
      CHECK(fabs(mr[j] - mt[j]) <= 1e-12 * fmax(1.0, fabs(mt[j])));
    printf("  c A^7 b = %.15g (textbook %.15g)\n", mr[7], mt[7]);
  }
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

int main(void) {
  minimal();
  cartesian();
  printf("%d checks, %d failures\n", check_count, check_failures);
  return check_failures != 0;
}
