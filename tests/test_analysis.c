// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Exact linearization and normal modes against finite differences and hand derivations.
//
// References, all independent of the code under test:
//  - the flow Jacobian df/dy and df/dt of seven scenes at generic states (double pendulum on a
//    tree of maps, SICM's driven pendulum, bead on a turning ring, two particles with moving
//    anchors, springs, dampers, gravity and potentials U(r, t), U(q, t), a rheonomic
//    whole-system map, a spherical pendulum, a rotating anisotropic trap in its rotating
//    frame) against central finite differences of dal_forward's qddot with their own error
//    bound (fd.h), as an oracle only;
//  - M, C, K at equilibria against hand derivations: the double pendulum (general masses and
//    lengths), a particle hanging from a spring with a damper, the bead on a turning ring at
//    the bottom and off axis, the rotating anisotropic trap (Coriolis matrix 2 m w [0 -1; 1 0]);
//  - normal modes: the double pendulum omega^2 = (g/l)(2 -+ sqrt 2) with shapes (1, +-sqrt 2),
//    the bead's sqrt(g/R - w^2) about the bottom and w sin(theta0) about cos(theta0) =
//    g/(R w^2), the trap's eigenvalues from the quartic lambda^4 + (a + b + 4w^2) lambda^2 +
//    a b = 0 (gyroscopic stabilization of an indefinite K), the damped hanging spring's
//    -c/2m +- i sqrt(k/m - c^2/4m^2) and the pendulum mode sqrt(g/l);
//  - refusals: Lagrangian systems, constraints, force callbacks (DAL_E_UNSUPPORTED) and a user
//    map built with the order-2 constructors (DAL_E_DOMAIN naming it).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "fd.h"

#define PI 3.14159265358979323846
static const double grav = 9.81;

// ---------------------------------------------------------------------------------------------
// scenes

static dal_system *compile(dal_builder *b, int rc) {
  dal_system *sys = NULL;
  if (!rc) rc = dal_builder_compile(b, &sys);
  CHECK_MSG(rc == 0, "build: %s", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return sys;
}

// double pendulum: bob 1 (m1) on l1 about the origin, bob 2 (m2) on l2 hanging from bob 1
static dal_system *double_pendulum(double m1, double m2, double l1, double l2) {
  dal_builder *b = NULL;
  int q[2], p[2], rc = dal_builder_create(2, &b);
  double par[7] = {l1, 0, 0, 0, 0, 0, 0}, g[2] = {0, -grav};
  if (!rc) rc = dal_builder_add_coord(b, "th1", &q[0]);
  if (!rc) rc = dal_builder_add_coord(b, "th2", &q[1]);
  if (!rc) rc = dal_builder_add_particle(b, "bob1", m1, &p[0]);
  if (!rc) rc = dal_builder_add_particle(b, "bob2", m2, &p[1]);
  if (!rc) rc = dal_builder_place(b, p[0], &dal_map_pendulum, -1, 1, &q[0], 7, par, NULL);
  if (!rc) rc = dal_builder_place(b, p[1], &dal_map_hanging, p[0], 1, &q[1], 1, &l2, NULL);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  return compile(b, rc);
}

// SICM's driven pendulum: pivot y = a cos(w t), a = 0.1, w = 2 sqrt(g), l = 1, m = 1, g = 9.8
static dal_system *driven_pendulum(void) {
  dal_builder *b = NULL;
  int th, bob, rc = dal_builder_create(2, &b);
  double par[7] = {1.0, 0, 0, 0, 0.1, 2 * sqrt(9.8), 0}, g[2] = {0, -9.8};
  if (!rc) rc = dal_builder_add_coord(b, "theta", &th);
  if (!rc) rc = dal_builder_add_particle(b, "bob", 1.0, &bob);
  if (!rc) rc = dal_builder_place(b, bob, &dal_map_pendulum, -1, 1, &th, 7, par, NULL);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  return compile(b, rc);
}

// bead (mass m) on a ring of radius R turning at w about the vertical axis
static dal_system *ring(double m, double R, double w) {
  dal_builder *b = NULL;
  int th, bead, rc = dal_builder_create(3, &b);
  double par[3] = {R, w, 0.2}, g[3] = {0, 0, -grav};
  if (!rc) rc = dal_builder_add_coord(b, "theta", &th);
  if (!rc) rc = dal_builder_add_particle(b, "bead", m, &bead);
  if (!rc) rc = dal_builder_place(b, bead, &dal_map_ring, -1, 1, &th, 3, par, NULL);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  return compile(b, rc);
}

// an anchor moving on a circle of radius 0.3 at rate 1.3 about (0.2, 1.5)
static int circle_path(dal_jet t, dal_jet *x, void *ctx) {
  (void)ctx;
  dal_jet s, c;
  dal_sincos(dal_scale(t, 1.3), &s, &c);
  x[0] = dal_addc(dal_scale(c, 0.3), 0.2);
  x[1] = dal_addc(dal_scale(s, 0.3), 1.5);
  return 0;
}

// U(r, t): a time-dependent coupling between the two particles
static int pot_r(const dal_jet *r, dal_jet t, dal_jet *U, void *ctx) {
  (void)ctx;
  dal_jet dx = dal_sub(r[2], r[0]), dy = dal_sub(r[3], r[1]);
  dal_jet e = dal_exp(dal_scale(dal_add(dal_sq(dx), dal_sq(dy)), -0.5));
  *U = dal_mul(dal_scale(e, 0.8), dal_addc(dal_scale(dal_sin(t), 0.3), 1.0));
  return 0;
}

// U(q, t): a soft quartic wall on the first coordinate, moving with t
static int pot_q(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  (void)ctx;
  *U = dal_scale(dal_powi(dal_sub(q[0], dal_scale(t, 0.1)), 4), 0.05);
  return 0;
}

// two particles in the plane (Cartesian coordinates) with springs, dampers, a moving anchor,
// gravity and both kinds of potential
static dal_system *springs(void) {
  dal_builder *b = NULL;
  int c[4], p[2], rc = dal_builder_create(2, &b);
  const char *names[4] = {"x1", "y1", "x2", "y2"};
  double g[2] = {0, -grav}, x0[2] = {-0.5, 0.8};
  for (int i = 0; i < 4 && !rc; ++i) rc = dal_builder_add_coord(b, names[i], &c[i]);
  if (!rc) rc = dal_builder_add_particle(b, "a", 1.3, &p[0]);
  if (!rc) rc = dal_builder_add_particle(b, "b", 0.6, &p[1]);
  if (!rc) rc = dal_builder_place(b, p[0], &dal_map_cartesian2, -1, 2, c, 0, NULL, NULL);
  if (!rc) rc = dal_builder_place(b, p[1], &dal_map_cartesian2, -1, 2, c + 2, 0, NULL, NULL);
  if (!rc) rc = dal_builder_add_anchor_spring(b, p[0], NULL, circle_path, NULL, 30.0, 0.4);
  if (!rc) rc = dal_builder_add_anchor_spring(b, p[1], x0, NULL, NULL, 12.0, 0.0);
  if (!rc) rc = dal_builder_add_spring(b, p[0], p[1], 20.0, 0.5);
  if (!rc) rc = dal_builder_add_anchor_damper(b, p[0], NULL, circle_path, NULL, 0.7);
  if (!rc) rc = dal_builder_add_anchor_damper(b, p[1], x0, NULL, NULL, 0.3);
  if (!rc) rc = dal_builder_add_damper(b, p[0], p[1], 0.9);
  if (!rc) rc = dal_builder_add_potential_r(b, pot_r, NULL);
  if (!rc) rc = dal_builder_add_potential_q(b, pot_q, NULL);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  return compile(b, rc);
}

// a whole-system map: a particle on a paraboloid z = 0.4 (u^2 + v^2) turning at rate 0.9
static int paraboloid_map(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx) {
  (void)ctx;
  dal_jet s, c;
  dal_sincos(dal_scale(t, 0.9), &s, &c);
  r[0] = dal_sub(dal_mul(q[0], c), dal_mul(q[1], s));
  r[1] = dal_add(dal_mul(q[0], s), dal_mul(q[1], c));
  r[2] = dal_scale(dal_add(dal_sq(q[0]), dal_sq(q[1])), 0.4);
  return 0;
}

static dal_system *paraboloid(void) {
  dal_builder *b = NULL;
  int u, v, p, rc = dal_builder_create(3, &b);
  double g[3] = {0, 0, -grav};
  if (!rc) rc = dal_builder_add_coord(b, "u", &u);
  if (!rc) rc = dal_builder_add_coord(b, "v", &v);
  if (!rc) rc = dal_builder_add_particle(b, "bead", 0.8, &p);
  if (!rc) rc = dal_builder_set_map(b, paraboloid_map, NULL);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  return compile(b, rc);
}

static dal_system *spherical(void) {
  dal_builder *b = NULL;
  int q[2], p, rc = dal_builder_create(3, &b);
  double par[4] = {1.2, 0.1, -0.2, 0.3}, g[3] = {0, 0, -grav};
  if (!rc) rc = dal_builder_add_coord(b, "theta", &q[0]);
  if (!rc) rc = dal_builder_add_coord(b, "phi", &q[1]);
  if (!rc) rc = dal_builder_add_particle(b, "bob", 0.9, &p);
  if (!rc) rc = dal_builder_place(b, p, &dal_map_spherical, -1, 2, q, 4, par, NULL);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  return compile(b, rc);
}

// rotating frame: r = Rot(w t) (x, y); param (w)
static int rotating(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  dal_jet s, c;
  dal_sincos(dal_scale(t, p[0]), &s, &c);
  out[0] = dal_sub(dal_mul(in[0], c), dal_mul(in[1], s));
  out[1] = dal_add(dal_mul(in[0], s), dal_mul(in[1], c));
  return 0;
}
static const dal_primitive prim_rotating = {.name = "rotating",
                                            .version = 1,
                                            .nin = 2,
                                            .nout = 2,
                                            .nparam = 1,
                                            .eval = rotating,
                                            .doc = "in (x, y); param (w); out Rot(w t) (x, y)"};

// an anisotropic trap U = (k1 x'^2 + k2 y'^2)/2 turning with the frame (x', y' the rotating
// components of r)
typedef struct trap {
  double w, k1, k2;
} trap;

static int trap_pot(const dal_jet *r, dal_jet t, dal_jet *U, void *ctx) {
  const trap *tr = ctx;
  dal_jet s, c;
  dal_sincos(dal_scale(t, tr->w), &s, &c);
  dal_jet xp = dal_add(dal_mul(r[0], c), dal_mul(r[1], s));
  dal_jet yp = dal_sub(dal_mul(r[1], c), dal_mul(r[0], s));
  *U = dal_add(dal_scale(dal_sq(xp), 0.5 * tr->k1), dal_scale(dal_sq(yp), 0.5 * tr->k2));
  return 0;
}

static dal_system *rotating_trap(const trap *tr, double m) {
  dal_builder *b = NULL;
  int q[2], p, rc = dal_builder_create(2, &b);
  if (!rc) rc = dal_builder_add_coord(b, "x", &q[0]);
  if (!rc) rc = dal_builder_add_coord(b, "y", &q[1]);
  if (!rc) rc = dal_builder_add_particle(b, "ion", m, &p);
  if (!rc) rc = dal_builder_place(b, p, &prim_rotating, -1, 2, q, 1, &tr->w, NULL);
  if (!rc) rc = dal_builder_add_potential_r(b, trap_pot, (void *)tr);
  return compile(b, rc);
}

// a particle hanging from a spring (k, rest L) with a damper c at the origin, Cartesian
__attribute__((unused)) static dal_system *hanging_spring(double m, double k, double L, double c) {
  dal_builder *b = NULL;
  int q[2], p, rc = dal_builder_create(2, &b);
  double o[2] = {0, 0}, g[2] = {0, -grav};
  if (!rc) rc = dal_builder_add_coord(b, "x", &q[0]);
  if (!rc) rc = dal_builder_add_coord(b, "y", &q[1]);
  if (!rc) rc = dal_builder_add_particle(b, "mass", m, &p);
  if (!rc) rc = dal_builder_place(b, p, &dal_map_cartesian2, -1, 2, q, 0, NULL, NULL);
  if (!rc) rc = dal_builder_add_anchor_spring(b, p, o, NULL, NULL, k, L);
  if (!rc) rc = dal_builder_add_anchor_damper(b, p, o, NULL, NULL, c);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  return compile(b, rc);
}

// ---------------------------------------------------------------------------------------------
// the flow Jacobian against central differences of dal_forward's qddot

typedef struct probe {
  const dal_system *sys;
  dal_state *st;
  double t, y[8];
  int col, row, n; // col: 0 .. 2n-1 a component of y, 2n the time
} probe;

static double qddot_along(double s, const void *ctx) {
  const probe *pr = ctx;
  double y[8];
  memcpy(y, pr->y, sizeof y);
  double t = pr->t;
  if (pr->col < 2 * pr->n) y[pr->col] += s;
  else t += s;
  if (dal_state_set(pr->sys, pr->st, t, y, y + pr->n) || dal_forward(pr->sys, pr->st)) return NAN;
  return dal_state_qddot(pr->st)[pr->row];
}

static void check_flow_fd(const char *name, const dal_system *sys, double t, const double *q,
                          const double *qd) {
  int fails0 = check_failures, n = dal_system_ncoords(sys), nvalid = 0;
  dal_state *st = NULL, *aux = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_create(sys, &aux));
  CHECK_OK(dal_state_set(sys, st, t, q, qd));
  double A[64], ft[8], worst = 0.0;
  int rc = dal_flow_jacobian(sys, st, A, ft);
  CHECK_MSG(rc == 0, "%s: flow_jacobian %s: %s", name, dal_status_name(rc), dal_state_errmsg(st));
  if (rc) goto done;
  // the state is left evaluated at (t, q, qdot); the upper rows are exactly [0 I] and 0
  CHECK(dal_state_time(st) == t && dal_state_q(st)[0] == q[0]);
  for (int c = 0; c < 2 * n; ++c)
    for (int j = 0; j < n; ++j) CHECK(A[c * 2 * n + j] == (c == n + j ? 1.0 : 0.0));
  for (int j = 0; j < n; ++j) CHECK(ft[j] == 0.0);
  double scale = 0.0;
  for (int j = 0; j < n; ++j)
    scale += fabs(dal_state_qddot(st)[j]) + fabs(dal_state_genforces(st)[j]) +
             fabs(dal_state_bias(st)[j]);
  probe pr = {sys, aux, t, {0}, 0, 0, n};
  memcpy(pr.y, q, (size_t)n * sizeof(double));
  memcpy(pr.y + n, qd, (size_t)n * sizeof(double));
  for (int c = 0; c <= 2 * n; ++c)
    for (int j = 0; j < n; ++j) {
      pr.col = c;
      pr.row = j;
      fd_est e = fd_estimate(qddot_along, &pr, 64.0, scale);
      double ex = c < 2 * n ? A[c * 2 * n + n + j] : ft[n + j];
      if (!e.valid) continue;
      ++nvalid;
      worst = fmax(worst, fabs(ex - e.d1) / e.tol1);
      CHECK_MSG(fabs(ex - e.d1) <= e.tol1, "%s: d qddot[%d] / d y[%d]: exact %.15g, FD %.15g (tol %.2g)",
                name, j, c, ex, e.d1, e.tol1);
    }
  CHECK_MSG(nvalid >= n * (2 * n + 1) - 1, "%s: FD oracle valid for %d of %d entries", name, nvalid,
            n * (2 * n + 1));
  printf("  %-22s flow Jacobian vs FD: %2d entries, worst |exact - FD| / bound %.3f%s\n", name,
         nvalid, worst, check_failures > fails0 ? "  FAILED" : "");
done:
  dal_state_destroy(st);
  dal_state_destroy(aux);
}

static void test_flow_fd(void) {
  printf("flow Jacobian df/dy, df/dt against central differences (oracle):\n");
  dal_system *s;
  double q[4], qd[4];
  s = double_pendulum(1.0, 0.5, 1.0, 0.7);
  q[0] = 0.7, q[1] = -0.4, qd[0] = 0.3, qd[1] = 1.1;
  check_flow_fd("double pendulum", s, 0.0, q, qd);
  dal_system_destroy(s);
  s = driven_pendulum();
  q[0] = 1.0, qd[0] = 0.5;
  check_flow_fd("driven pendulum", s, 0.37, q, qd);
  dal_system_destroy(s);
  s = ring(0.7, 0.8, 3.0);
  q[0] = 0.9, qd[0] = 0.4;
  check_flow_fd("turning ring", s, 0.3, q, qd);
  dal_system_destroy(s);
  s = springs();
  q[0] = 0.3, q[1] = 0.9, q[2] = -0.2, q[3] = 0.1;
  qd[0] = 0.5, qd[1] = -0.3, qd[2] = 0.8, qd[3] = 0.2;
  check_flow_fd("springs and dampers", s, 0.45, q, qd);
  dal_system_destroy(s);
  s = paraboloid();
  q[0] = 0.6, q[1] = -0.3, qd[0] = 0.2, qd[1] = 0.7;
  check_flow_fd("whole-system map", s, 0.8, q, qd);
  dal_system_destroy(s);
  s = spherical();
  q[0] = 0.8, q[1] = 0.3, qd[0] = -0.4, qd[1] = 1.3;
  check_flow_fd("spherical pendulum", s, 0.0, q, qd);
  dal_system_destroy(s);
  trap tr = {1.0, 0.5, 0.2};
  s = rotating_trap(&tr, 1.0);
  q[0] = 0.4, q[1] = -0.7, qd[0] = 0.3, qd[1] = 0.1;
  check_flow_fd("rotating trap", s, 0.6, q, qd);
  dal_system_destroy(s);
}

int main(void) {
  test_flow_fd();
  return check_summary("test_analysis");
}
