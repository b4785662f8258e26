// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Exact linearization and normal modes against finite differences and hand derivations.
//
// References, all independent of the code under test:
//  - the vector-field Jacobian df/dy and df/dt of seven scenes at generic states (double pendulum
//  on a
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
#include "scenes.h"

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
// a standard scene, checked as compile() checks the scenes built here
static dal_system *built(dal_system *sys) {
  CHECK(sys != NULL);
  return sys;
}

static dal_system *double_pendulum(double m1, double m2, double l1, double l2) {
  scn_knobs k = scn_default();
  k.g = grav;
  k.m = m1;
  k.m2 = m2;
  k.l = l1;
  k.l2 = l2;
  return built(scn_double_pendulum(&k));
}

// SICM's driven pendulum: pivot y = a cos(w t), a = 0.1, w = 2 sqrt(g), l = 1, m = 1, g = 9.8
static dal_system *driven_pendulum(void) {
  scn_knobs k = scn_default();
  k.g = 9.8;
  k.ay = 0.1;
  k.w = 2 * sqrt(9.8);
  return built(scn_pendulum(&k));
}

// bead (mass m) on a ring of radius R turning at w about the vertical axis
static dal_system *ring(double m, double R, double w) {
  scn_knobs k = scn_default();
  k.g = grav;
  k.m = m;
  k.R = R;
  k.spin = w;
  k.phi0 = 0.2;
  return built(scn_bead(&k));
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
  scn_knobs k = scn_default();
  k.g = grav;
  double x0[2] = {-0.5, 0.8};
  int p[2], rc = scn_builder(&k, 2, &b);
  if (!rc) rc = scn_add_xy(b, "a", 1.3, "x1", "y1", &p[0]);
  if (!rc) rc = scn_add_xy(b, "b", 0.6, "x2", "y2", &p[1]);
  dal_spring_def sd = dal_default_spring_def();
  sd.a = p[0];
  sd.path = circle_path;
  sd.k = 30.0;
  sd.length = 0.4;
  if (!rc) rc = dal_builder_add_spring_def(b, &sd);
  sd = dal_default_spring_def();
  sd.a = p[1];
  memcpy(sd.anchor, x0, sizeof x0);
  sd.k = 12.0;
  if (!rc) rc = dal_builder_add_spring_def(b, &sd);
  sd = dal_default_spring_def();
  sd.a = p[0];
  sd.b = p[1];
  sd.k = 20.0;
  sd.length = 0.5;
  if (!rc) rc = dal_builder_add_spring_def(b, &sd);
  dal_damper_def dd = dal_default_damper_def();
  dd.a = p[0];
  dd.path = circle_path;
  dd.c = 0.7;
  if (!rc) rc = dal_builder_add_damper_def(b, &dd);
  dd = dal_default_damper_def();
  dd.a = p[1];
  memcpy(dd.anchor, x0, sizeof x0);
  dd.c = 0.3;
  if (!rc) rc = dal_builder_add_damper_def(b, &dd);
  dd = dal_default_damper_def();
  dd.a = p[0];
  dd.b = p[1];
  dd.c = 0.9;
  if (!rc) rc = dal_builder_add_damper_def(b, &dd);
  if (!rc) rc = dal_builder_add_potential_r(b, pot_r, NULL);
  if (!rc) rc = dal_builder_add_potential_q(b, pot_q, NULL);
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
  scn_knobs k = scn_default();
  k.g = grav;
  k.m = 0.9;
  k.l = 1.2;
  k.x0 = 0.1;
  k.y0 = -0.2;
  k.z0 = 0.3;
  return built(scn_spherical(&k));
}

// an ion in an anisotropic trap turning with the frame (scenes.h)
typedef scn_trap trap;

static dal_system *rotating_trap(const trap *tr, double m) {
  return built(scn_rotating_trap(tr, m));
}

// ---------------------------------------------------------------------------------------------
// the vector-field Jacobian against central differences of dal_forward's qddot

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
  if (pr->col < 2 * pr->n)
    y[pr->col] += s;
  else
    t += s;
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
  int rc = dal_vector_field_jacobian(sys, st, A, ft);
  CHECK_MSG(rc == 0, "%s: vector_field_jacobian %s: %s", name, dal_status_name(rc),
            dal_state_errmsg(st));
  if (rc) goto done;
  // the state is left evaluated at (t, q, qdot); the upper rows are exactly [0 I] and 0
  CHECK(dal_state_time(st) == t && dal_state_q(st)[0] == q[0]);
  for (int c = 0; c < 2 * n; ++c)
    for (int j = 0; j < n; ++j)
      CHECK(A[c * 2 * n + j] == (c == n + j ? 1.0 : 0.0));
  for (int j = 0; j < n; ++j)
    CHECK(ft[j] == 0.0);
  // the mass matrix from the tangent's particle Jacobians against dal_forward's assembly
  double M[16], Mn = 0.0;
  CHECK_OK(dal_linearize(sys, st, M, NULL, NULL));
  const double *Mf = dal_state_mass_matrix(st);
  for (int i = 0; i < n * n; ++i)
    Mn = fmax(Mn, fabs(Mf[i]));
  for (int i = 0; i < n * n; ++i)
    CHECK_MSG(fabs(M[i] - Mf[i]) <= 1e-14 * Mn, "%s: M[%d] = %.17g, forward %.17g", name, i, M[i],
              Mf[i]);
  double scale = 0.0;
  const double *bias = dal_state_bias(st); // NULL for a Lagrangian system (no particles)
  for (int j = 0; j < n; ++j)
    scale += fabs(dal_state_qddot(st)[j]) + fabs(dal_state_genforces(st)[j]) +
             (bias ? fabs(bias[j]) : 0.0);
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
      CHECK_MSG(fabs(ex - e.d1) <= e.tol1,
                "%s: d qddot[%d] / d y[%d]: exact %.15g, FD %.15g (tol %.2g)", name, j, c, ex, e.d1,
                e.tol1);
    }
  CHECK_MSG(nvalid >= n * (2 * n + 1) - 1, "%s: FD oracle valid for %d of %d entries", name, nvalid,
            n * (2 * n + 1));
  printf("  %-22s vector-field Jacobian vs FD: %2d entries, worst |exact - FD| / bound %.3f%s\n",
         name, nvalid, worst, check_failures > fails0 ? "  FAILED" : "");
done:
  dal_state_destroy(st);
  dal_state_destroy(aux);
}

// the double pendulum by its Lagrangian (masses m1, m2, lengths l1, l2)
static const double lg_m1 = 1.0, lg_m2 = 0.5, lg_l1 = 1.0, lg_l2 = 0.7;
static int lag_double(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet T = dal_scale(dal_sq(v[0]), 0.5 * (lg_m1 + lg_m2) * lg_l1 * lg_l1);
  T = dal_add(T, dal_scale(dal_sq(v[1]), 0.5 * lg_m2 * lg_l2 * lg_l2));
  T = dal_add(T, dal_scale(dal_mul(dal_mul(v[0], v[1]), dal_cos(dal_sub(q[0], q[1]))),
                           lg_m2 * lg_l1 * lg_l2));
  dal_jet V = dal_add(dal_scale(dal_cos(q[0]), (lg_m1 + lg_m2) * grav * lg_l1),
                      dal_scale(dal_cos(q[1]), lg_m2 * grav * lg_l2));
  *L = dal_add(T, V);
  return 0;
}

// SICM's driven pendulum by its Lagrangian: pivot y_s = a cos(w t), m = l = 1, g = 9.8
static int lag_driven(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)ctx;
  const double a = 0.1, w = 2 * sqrt(9.8);
  dal_jet s, c, ys = dal_scale(dal_cos(dal_scale(t, w)), a);
  dal_jet yd = dal_scale(dal_sin(dal_scale(t, w)), -a * w);
  dal_sincos(q[0], &s, &c);
  dal_jet T = dal_scale(
      dal_add(dal_add(dal_sq(v[0]), dal_sq(yd)), dal_scale(dal_mul(dal_mul(s, v[0]), yd), 2.0)),
      0.5);
  *L = dal_sub(T, dal_scale(dal_sub(ys, c), 9.8));
  return 0;
}

// a velocity-dependent Lagrangian (charge in a magnetic field B z, harmonic trap) plus U(q, t)
static int lag_magnetic(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)t;
  (void)ctx;
  const double B = 0.7;
  dal_jet T = dal_scale(dal_add(dal_sq(v[0]), dal_sq(v[1])), 0.5);
  dal_jet A = dal_scale(dal_sub(dal_mul(q[0], v[1]), dal_mul(q[1], v[0])), 0.5 * B);
  dal_jet U = dal_scale(dal_add(dal_sq(q[0]), dal_scale(dal_sq(q[1]), 2.0)), 0.5);
  *L = dal_sub(dal_add(T, A), U);
  return 0;
}

static dal_system *lagrangian_system(dal_lagrangian_fn *fn, int n, int with_potq) {
  dal_builder *b = NULL;
  int rc = dal_builder_create(2, &b);
  for (int i = 0; i < n && !rc; ++i)
    rc = dal_builder_add_coord(b, NULL, NULL);
  if (!rc) rc = dal_builder_set_lagrangian(b, fn, NULL);
  if (!rc && with_potq) rc = dal_builder_add_potential_q(b, pot_q, NULL);
  return compile(b, rc);
}

static void test_flow_fd(void) {
  printf("vector-field Jacobian df/dy, df/dt against central differences (oracle):\n");
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
  s = lagrangian_system(lag_double, 2, 0);
  q[0] = 0.7, q[1] = -0.4, qd[0] = 0.3, qd[1] = 1.1;
  check_flow_fd("Lagrangian dbl pend.", s, 0.0, q, qd);
  dal_system_destroy(s);
  s = lagrangian_system(lag_driven, 1, 0);
  q[0] = 1.0, qd[0] = 0.5;
  check_flow_fd("Lagrangian driven", s, 0.37, q, qd);
  dal_system_destroy(s);
  s = lagrangian_system(lag_magnetic, 2, 1);
  q[0] = 0.4, q[1] = -0.3, qd[0] = 0.8, qd[1] = 0.2;
  check_flow_fd("Lagrangian + U(q,t)", s, 0.9, q, qd);
  dal_system_destroy(s);
}

// ---------------------------------------------------------------------------------------------
// every registered primitive: the third derivative along a cubic curve of inputs and time
// against the third-difference oracle (fd3_estimate), so the tangent has exact d3 to work with

static int reg_curve2(dal_jet s, dal_jet t, dal_jet *p, void *ctx) {
  (void)ctx;
  p[0] = dal_add(dal_cos(s), dal_scale(dal_mul(dal_sin(t), s), 0.3));
  p[1] = dal_add(dal_sin(dal_scale(s, 2.0)), dal_scale(dal_mul(t, dal_sq(s)), 0.2));
  return 0;
}
static int reg_curve3(dal_jet s, dal_jet t, dal_jet *p, void *ctx) {
  reg_curve2(s, t, p, ctx);
  p[2] = dal_scale(dal_mul(s, dal_cos(t)), 0.5);
  return 0;
}
static int reg_motion2(dal_jet t, dal_jet *x, void *ctx) {
  (void)ctx;
  x[0] = dal_scale(dal_cos(dal_scale(t, 1.3)), 0.3);
  x[1] = dal_scale(dal_sin(dal_scale(t, 0.7)), 0.2);
  return 0;
}
static int reg_motion3(dal_jet t, dal_jet *x, void *ctx) {
  reg_motion2(t, x, ctx);
  x[2] = dal_scale(dal_sq(t), 0.1);
  return 0;
}
static int reg_drive(dal_jet t, dal_jet *f, void *ctx) {
  (void)ctx;
  *f = dal_add(dal_scale(dal_sin(dal_scale(t, 1.1)), 0.4), dal_scale(dal_powi(t, 3), 0.05));
  return 0;
}
static dal_curve reg_c2 = {reg_curve2, NULL}, reg_c3 = {reg_curve3, NULL};
static dal_moving_point reg_m2 = {reg_motion2, NULL}, reg_m3 = {reg_motion3, NULL};
static dal_prescribed reg_dr = {reg_drive, NULL};

static void *reg_ctx(const dal_primitive *p) {
  if (!strcmp(p->name, "curve2")) return &reg_c2;
  if (!strcmp(p->name, "curve3")) return &reg_c3;
  if (!strcmp(p->name, "anchor2")) return &reg_m2;
  if (!strcmp(p->name, "anchor3")) return &reg_m3;
  if (!strcmp(p->name, "prescribed")) return &reg_dr;
  return NULL;
}

// a primitive at inputs u + s w + s^2/2 z + s^3 c3 and time t + s dt (exact in double)
typedef struct reg_point {
  const dal_primitive *prim;
  void *ctx;
  double u[16], w[16], z[16], c3[16], param[16], t, dt;
  int out;
} reg_point;

static double reg_along(double s, const void *ctx) {
  const reg_point *P = ctx;
  dal_jet in[16], out[16];
  for (int i = 0; i < P->prim->nin; ++i)
    in[i] = dal_const(P->u[i] + P->w[i] * s + 0.5 * P->z[i] * (s * s) + P->c3[i] * (s * s * s));
  if (P->prim->eval(in, dal_const(P->t + P->dt * s), P->param, out, P->ctx)) return NAN;
  return out[P->out].v;
}

static void test_registry_d3(void) {
  int fails0 = check_failures, total = 0, valid = 0;
  double worst = 0.0;
  unsigned long long seed = 0x2545f4914f6cdd1dULL;
  for (int r = 0; r < dal_primitive_count(); ++r) {
    const dal_primitive *p = dal_primitive_get(r);
    reg_point P;
    memset(&P, 0, sizeof P);
    P.prim = p;
    P.ctx = reg_ctx(p);
    int done = 0;
    for (int tries = 0; tries < 200 && done < 6; ++tries) {
      for (int i = 0; i < p->nin; ++i) {
        P.u[i] = fd_grid(check_rand(&seed, -1.5, 1.5), 20);
        P.w[i] = fd_grid(check_rand(&seed, -1, 1), 10);
        P.z[i] = fd_grid(check_rand(&seed, -1, 1), 10);
        P.c3[i] = fd_grid(check_rand(&seed, -1, 1), 10) / 8.0;
      }
      for (int i = 0; i < p->nparam; ++i)
        P.param[i] = fd_grid(check_rand(&seed, 0.5, 1.5), 10);
      P.t = fd_grid(check_rand(&seed, -2, 2), 20);
      P.dt = 1.0;
      dal_jet in[16], out[16];
      for (int i = 0; i < p->nin; ++i)
        in[i] = dal_jet_make3(P.u[i], P.w[i], P.z[i], 6 * P.c3[i]);
      if (p->eval(in, dal_jet_make3(P.t, P.dt, 0.0, 0.0), P.param, out, P.ctx)) continue;
      int finite = 1;
      for (int a = 0; a < p->nout; ++a)
        finite &= dal_jet_isfinite3(out[a]);
      if (!finite) continue;
      ++done;
      for (int a = 0; a < p->nout; ++a) {
        P.out = a;
        fd3_est e = fd3_estimate(reg_along, &P, 64.0, 10.0);
        ++total;
        if (!e.valid) continue;
        ++valid;
        worst = fmax(worst, fabs(out[a].d3 - e.d3) / e.tol);
        CHECK_MSG(fabs(out[a].d3 - e.d3) <= e.tol,
                  "'%s' output %d: d3 %.15g vs FD %.15g (tol %.2g)", p->name, a, out[a].d3, e.d3,
                  e.tol);
      }
    }
    CHECK_MSG(done == 6, "'%s': only %d evaluable points", p->name, done);
  }
  CHECK_MSG(valid >= total * 9 / 10, "registry d3: FD oracle valid at %d of %d", valid, total);
  printf("  %-22s %d primitives, d3 vs FD at %d/%d outputs, worst |d3 - FD| / bound %.3f%s\n",
         "registry", dal_primitive_count(), valid, total, worst,
         check_failures > fails0 ? "  FAILED" : "");
}

// ---------------------------------------------------------------------------------------------
// hand-derived linearizations and normal modes

static void check_mat(const char *what, const double *A, const double *B, int n, double tol) {
  double s = 0.0;
  for (int i = 0; i < n * n; ++i)
    s = fmax(s, fabs(B[i]));
  for (int i = 0; i < n * n; ++i)
    CHECK_MSG(fabs(A[i] - B[i]) <= tol * (s > 0 ? s : 1.0), "%s[%d,%d] = %.17g, expected %.17g",
              what, i % n, i / n, A[i], B[i]);
}

// eigenvalues (re, im) contain the expected ones (each matched once) to tol
static void check_eigs(const char *what, const double *re, const double *im, int m,
                       const double *ere, const double *eim, double tol) {
  int used[8] = {0};
  for (int i = 0; i < m; ++i) {
    int found = -1;
    for (int j = 0; j < m && found < 0; ++j)
      if (!used[j] && hypot(re[j] - ere[i], im[j] - eim[i]) <= tol) found = j;
    CHECK_MSG(found >= 0, "%s: eigenvalue %.15g%+.15gi not found", what, ere[i], eim[i]);
    if (found >= 0) used[found] = 1;
  }
}

static void test_double_pendulum_modes(void) {
  int fails0 = check_failures;
  // general masses and lengths at the hanging equilibrium: M, K by hand, C = 0
  const double m1 = 1.3, m2 = 0.6, l1 = 0.9, l2 = 1.4;
  dal_system *sys = double_pendulum(m1, m2, l1, l2);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double z[2] = {0, 0}, M[4], C[4], K[4];
  CHECK_OK(dal_state_set(sys, st, 0.0, z, z));
  CHECK_OK(dal_linearize(sys, st, M, C, K));
  double Mh[4] = {(m1 + m2) * l1 * l1, m2 * l1 * l2, m2 * l1 * l2, m2 * l2 * l2};
  double Kh[4] = {(m1 + m2) * grav * l1, 0, 0, m2 * grav * l2}, Ch[4] = {0, 0, 0, 0};
  check_mat("double pendulum M", M, Mh, 2, 1e-15);
  check_mat("double pendulum K", K, Kh, 2, 1e-14);
  check_mat("double pendulum C", C, Ch, 2, 1e-14);
  dal_state_destroy(st);
  dal_system_destroy(sys);

  // equal masses and lengths: omega^2 = (g/l)(2 -+ sqrt 2), shapes (1, +-sqrt 2)
  const double l = 0.8;
  sys = double_pendulum(1.0, 1.0, l, l);
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_set(sys, st, 0.0, z, z));
  double w2[2], X[4], lr[4], li[4];
  dal_modes md;
  CHECK_OK(dal_normal_modes(sys, st, w2, X, lr, li, &md));
  double e1 = grav / l * (2 - sqrt(2.0)), e2 = grav / l * (2 + sqrt(2.0));
  CHECK_CLOSE(w2[0], e1, 1e-14);
  CHECK_CLOSE(w2[1], e2, 1e-14);
  CHECK_CLOSE(X[1] / X[0], sqrt(2.0), 1e-13);
  CHECK_CLOSE(X[3] / X[2], -sqrt(2.0), 1e-13);
  // M-orthonormal: x_i' M x_j = delta_ij, with M = m l^2 [2 1; 1 1]
  double Me[4] = {2 * l * l, l * l, l * l, l * l};
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      double s = 0;
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
          s += X[i * 2 + a] * Me[b * 2 + a] * X[j * 2 + b];
      CHECK_CLOSE(s, i == j ? 1.0 : 0.0, 1e-14);
    }
  double ere[4] = {0, 0, 0, 0}, eim[4] = {sqrt(e1), -sqrt(e1), sqrt(e2), -sqrt(e2)};
  check_eigs("double pendulum", lr, li, 4, ere, eim, 1e-12 * sqrt(e2));
  CHECK_MSG(md.verdict == DAL_NEUTRAL, "double pendulum verdict %s",
            dal_stability_name(md.verdict));
  CHECK(md.asymmetry <= 1e-15 && md.gyroscopic <= 1e-15 && md.accel == 0.0);
  // upside down (theta = pi, pi): both omega^2 negative, unstable
  double up[2] = {PI, PI};
  CHECK_OK(dal_state_set(sys, st, 0.0, up, z));
  CHECK_OK(dal_normal_modes(sys, st, w2, NULL, NULL, NULL, &md));
  CHECK_CLOSE(w2[0], -e2, 1e-13);
  CHECK_CLOSE(w2[1], -e1, 1e-13);
  CHECK(md.verdict == DAL_UNSTABLE);
  CHECK_CLOSE(md.max_real, sqrt(e2), 1e-12);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  printf("  %-40s %s\n", "double pendulum: M, C, K, modes, verdicts",
         check_failures > fails0 ? "FAILED" : "ok");
}

static void test_spring_damper(void) {
  int fails0 = check_failures;
  const double m = 0.7, k = 40.0, L = 0.5, c = 1.1;
  // a particle hanging from a spring (k, rest L) with a damper c at the origin, Cartesian
  scn_knobs kn = scn_default();
  kn.m = m, kn.k = k, kn.l = L, kn.c = c;
  dal_system *sys = built(scn_hanging_spring(&kn));
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  // the equilibrium from a nearby start: y* = -(L + m g / k)
  double ell = L + m * grav / k, q[2] = {0.02, -0.6}, z[2] = {0, 0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, z));
  dal_equilibrium_report er;
  int rc = dal_equilibrium(sys, st, NULL, &er);
  CHECK_MSG(rc == 0, "spring equilibrium: %s", dal_state_errmsg(st));
  CHECK_CLOSE(dal_state_q(st)[0], 0.0, 1e-15);
  CHECK_CLOSE(dal_state_q(st)[1], -ell, 1e-15);
  CHECK(er.unsteady == 0.0 && er.accel <= 1e-14 && er.iterations <= 8);
  // K = diag(m g / ell, k) (tension over length sideways, the spring along), C = diag(0, c)
  double M[4], C[4], K[4];
  CHECK_OK(dal_linearize(sys, st, M, C, K));
  double Mh[4] = {m, 0, 0, m}, Kh[4] = {m * grav / ell, 0, 0, k}, Ch[4] = {0, 0, 0, c};
  check_mat("spring M", M, Mh, 2, 1e-15);
  check_mat("spring K", K, Kh, 2, 1e-14);
  check_mat("spring C", C, Ch, 2, 1e-14);
  // eigenvalues: +-i sqrt(g/ell) and -c/2m +- i sqrt(k/m - c^2/4m^2); verdict neutral
  double lr[4], li[4], w2[2];
  dal_modes md;
  CHECK_OK(dal_normal_modes(sys, st, w2, NULL, lr, li, &md));
  double wd = sqrt(k / m - c * c / (4 * m * m)), wp = sqrt(grav / ell);
  double ere[4] = {0, 0, -c / (2 * m), -c / (2 * m)}, eim[4] = {wp, -wp, wd, -wd};
  check_eigs("spring-damper", lr, li, 4, ere, eim, 1e-12 * wd);
  CHECK_CLOSE(w2[0], grav / ell, 1e-14);
  CHECK_CLOSE(w2[1], k / m, 1e-14);
  CHECK_MSG(md.verdict == DAL_NEUTRAL, "spring verdict %s", dal_stability_name(md.verdict));
  // sorted by decreasing real part: the undamped pair first, +i before -i... by imaginary part
  CHECK(fabs(lr[0]) <= 1e-12 && li[0] < 0 && li[1] > 0 && lr[2] < 0);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  printf("  %-40s %s\n", "spring and damper: equilibrium, M, C, K",
         check_failures > fails0 ? "FAILED" : "ok");
}

static void test_ring_modes(void) {
  int fails0 = check_failures;
  const double m = 0.3, R = 0.5, wc = sqrt(grav / R);
  double z = 0.0, th;
  dal_modes md;
  double w2, M, C, K, lr[2], li[2];
  // below the critical rate: the bottom is stable with omega^2 = g/R - w^2
  double w = 0.6 * wc;
  dal_system *sys = ring(m, R, w);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_set(sys, st, 0.7, &z, &z));
  CHECK_OK(dal_linearize(sys, st, &M, &C, &K));
  CHECK_CLOSE(M, m * R * R, 1e-15);
  CHECK_CLOSE(K, m * R * R * (grav / R - w * w), 1e-14);
  CHECK(fabs(C) <= 1e-15);
  CHECK_OK(dal_normal_modes(sys, st, &w2, NULL, lr, li, &md));
  CHECK_CLOSE(w2, grav / R - w * w, 1e-14);
  CHECK(md.verdict == DAL_NEUTRAL);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  // above it: the bottom is unstable, the off-axis equilibrium cos(theta0) = g/(R w^2) is
  // stable with frequency w sin(theta0); found by Newton from theta = 1, at any time
  w = 1.7 * wc;
  double th0 = acos(grav / (R * w * w));
  sys = ring(m, R, w);
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_set(sys, st, 0.0, &z, &z));
  CHECK_OK(dal_normal_modes(sys, st, &w2, NULL, lr, li, &md));
  CHECK_CLOSE(w2, grav / R - w * w, 1e-14);
  CHECK(md.verdict == DAL_UNSTABLE);
  CHECK_CLOSE(lr[0], sqrt(w * w - grav / R), 1e-12);
  th = 1.0;
  CHECK_OK(dal_state_set(sys, st, 2.3, &th, &z));
  dal_equilibrium_report er;
  int rc = dal_equilibrium(sys, st, NULL, &er);
  CHECK_MSG(rc == 0, "ring equilibrium: %s", dal_state_errmsg(st));
  CHECK_CLOSE(dal_state_q(st)[0], th0, 1e-14);
  CHECK_MSG(er.unsteady <= 1e-14, "ring relative equilibrium unsteady %g", er.unsteady);
  CHECK(dal_state_time(st) == 2.3 && dal_state_qdot(st)[0] == 0.0);
  CHECK_OK(dal_linearize(sys, st, &M, &C, &K));
  CHECK_CLOSE(K, m * R * R * w * w * sin(th0) * sin(th0), 1e-13);
  CHECK_OK(dal_normal_modes(sys, st, &w2, NULL, lr, li, &md));
  CHECK_CLOSE(sqrt(w2), w * sin(th0), 1e-13);
  CHECK_CLOSE(fabs(li[0]), w * sin(th0), 1e-12);
  CHECK(md.verdict == DAL_NEUTRAL);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  printf("  %-40s %s\n", "bead on a turning ring: modes, verdicts",
         check_failures > fails0 ? "FAILED" : "ok");
}

// roots lambda of lambda^4 + (a + b + 4 w^2) lambda^2 + a b = 0 (unit mass), as (re, im)
static void trap_roots(double a, double b, double w, double *re, double *im) {
  double B = a + b + 4 * w * w, D = B * B - 4 * a * b;
  for (int s = 0; s < 2; ++s) {
    double mu_re, mu_im;
    if (D >= 0) {
      mu_re = (-B + (s ? -1 : 1) * sqrt(D)) / 2;
      mu_im = 0;
    } else {
      mu_re = -B / 2;
      mu_im = (s ? -1 : 1) * sqrt(-D) / 2;
    }
    // lambda = +- sqrt(mu), principal root of the complex number mu
    double r = hypot(mu_re, mu_im), sr = sqrt((r + mu_re) / 2),
           si = copysign(sqrt((r - mu_re) / 2), mu_im);
    re[2 * s] = sr, im[2 * s] = si;
    re[2 * s + 1] = -sr, im[2 * s + 1] = -si;
  }
}

static void test_rotating_trap(void) {
  int fails0 = check_failures;
  double z[2] = {0, 0};
  // gyroscopic stabilization: K negative definite, yet every eigenvalue on the imaginary axis
  trap tr = {1.0, 0.5, 0.2};
  dal_system *sys = rotating_trap(&tr, 1.0);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_set(sys, st, 0.4, z, z));
  double M[4], C[4], K[4], w2[2], lr[4], li[4], ere[4], eim[4];
  CHECK_OK(dal_linearize(sys, st, M, C, K));
  double a = tr.k1 - tr.w * tr.w, b = tr.k2 - tr.w * tr.w;
  double Mh[4] = {1, 0, 0, 1}, Ch[4] = {0, 2 * tr.w, -2 * tr.w, 0}, Kh[4] = {a, 0, 0, b};
  check_mat("trap M", M, Mh, 2, 1e-15);
  check_mat("trap C", C, Ch, 2, 1e-14);
  check_mat("trap K", K, Kh, 2, 1e-14);
  dal_modes md;
  CHECK_OK(dal_normal_modes(sys, st, w2, NULL, lr, li, &md));
  CHECK_CLOSE(w2[0], b, 1e-14);
  CHECK_CLOSE(w2[1], a, 1e-14);
  trap_roots(a, b, tr.w, ere, eim);
  check_eigs("stabilized trap", lr, li, 4, ere, eim, 1e-12);
  CHECK_MSG(md.verdict == DAL_NEUTRAL, "stabilized trap verdict %s",
            dal_stability_name(md.verdict));
  CHECK_CLOSE(md.gyroscopic, 2 * sqrt(2.0) / sqrt(sqrt(a * a + b * b) * sqrt(2.0)), 1e-14);
  // the equilibrium at the origin is steady in the rotating frame
  double q[2] = {0.1, -0.05};
  CHECK_OK(dal_state_set(sys, st, 1.1, q, z));
  dal_equilibrium_report er;
  CHECK_OK(dal_equilibrium(sys, st, NULL, &er));
  CHECK(fabs(dal_state_q(st)[0]) <= 1e-15 && fabs(dal_state_q(st)[1]) <= 1e-15);
  CHECK(er.unsteady <= 1e-15);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  // a saddle that rotation does not save (a b < 0): a real pair
  trap tu = {1.0, 3.0, 0.5};
  sys = rotating_trap(&tu, 1.0);
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_set(sys, st, 0.0, z, z));
  CHECK_OK(dal_normal_modes(sys, st, w2, NULL, lr, li, &md));
  trap_roots(tu.k1 - 1.0, tu.k2 - 1.0, tu.w, ere, eim);
  check_eigs("unstable trap", lr, li, 4, ere, eim, 1e-12);
  CHECK(md.verdict == DAL_UNSTABLE && md.max_real > 0.1);
  CHECK_CLOSE(md.max_real, ere[0], 1e-12);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  printf("  %-40s %s\n", "rotating trap: Coriolis C, stabilization",
         check_failures > fails0 ? "FAILED" : "ok");
}

// the same double pendulum by particles and by its Lagrangian: the same M, C, K
static void test_lagrangian_vs_particles(void) {
  int fails0 = check_failures;
  dal_system *sp = double_pendulum(lg_m1, lg_m2, lg_l1, lg_l2);
  dal_system *sl = lagrangian_system(lag_double, 2, 0);
  dal_state *a = NULL, *b = NULL;
  CHECK_OK(dal_state_create(sp, &a));
  CHECK_OK(dal_state_create(sl, &b));
  unsigned long long seed = 0x9e3779b97f4a7c15ULL;
  for (int it = 0; it < 20; ++it) {
    double q[2], qd[2], M1[4], C1[4], K1[4], M2[4], C2[4], K2[4];
    for (int i = 0; i < 2; ++i) {
      q[i] = check_rand(&seed, -3, 3);
      qd[i] = check_rand(&seed, -2, 2);
    }
    CHECK_OK(dal_state_set(sp, a, 0.0, q, qd));
    CHECK_OK(dal_state_set(sl, b, 0.0, q, qd));
    CHECK_OK(dal_linearize(sp, a, M1, C1, K1));
    CHECK_OK(dal_linearize(sl, b, M2, C2, K2));
    check_mat("Lagrangian M", M2, M1, 2, 1e-14);
    check_mat("Lagrangian C", C2, C1, 2, 1e-13);
    check_mat("Lagrangian K", K2, K1, 2, 1e-13);
  }
  dal_state_destroy(a);
  dal_state_destroy(b);
  dal_system_destroy(sp);
  dal_system_destroy(sl);
  printf("  %-40s %s\n", "Lagrangian = particles (M, C, K)",
         check_failures > fails0 ? "FAILED" : "ok");
}

// ---------------------------------------------------------------------------------------------
// refusals

static int lag_osc(dal_jet t, const dal_jet *q, const dal_jet *qd, dal_jet *L, void *ctx) {
  (void)t;
  (void)ctx;
  *L = dal_scale(dal_sub(dal_sq(qd[0]), dal_sq(q[0])), 0.5);
  return 0;
}

static int drag(double t, const double *r, const double *v, double *F, void *ctx) {
  (void)t, (void)r, (void)ctx;
  F[0] -= 0.1 * v[0];
  return 0;
}

static int gdrag(double t, const double *q, const double *qd, double *Q, void *ctx) {
  (void)t, (void)q, (void)ctx;
  Q[0] -= 0.1 * qd[0];
  return 0;
}

// a pendulum map written with hand derivatives through dal_jet_make (order 2 only)
static int hand_pendulum(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *c) {
  (void)t, (void)p, (void)c;
  double s = sin(in[0].v), co = cos(in[0].v);
  out[0] = dal_jet_make(s, co * in[0].d, co * in[0].dd - s * in[0].d * in[0].d);
  out[1] = dal_jet_make(-co, s * in[0].d, s * in[0].dd + co * in[0].d * in[0].d);
  return 0;
}
static const dal_primitive prim_hand = {.name = "hand_pendulum",
                                        .version = 1,
                                        .nin = 1,
                                        .nout = 2,
                                        .nparam = 0,
                                        .eval = hand_pendulum,
                                        .doc = "order-2 pendulum"};

static void expect_refusal(const char *what, dal_system *sys, int status, const char *needle) {
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q[2] = {0.3, 0.1}, z[2] = {0.2, 0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, z));
  double buf[16];
  int rc = dal_linearize(sys, st, buf, buf, buf);
  CHECK_MSG(rc == status && strstr(dal_state_errmsg(st), needle), "%s: %s (%s)", what,
            dal_status_name(rc), dal_state_errmsg(st));
  rc = dal_vector_field_jacobian(sys, st, buf, NULL);
  CHECK_MSG(rc == status, "%s: vector_field_jacobian %s", what, dal_status_name(rc));
  dal_lyapunov_opts lo = dal_default_lyapunov_opts();
  lo.t_end = 1.0;
  rc = dal_lyapunov(sys, st, &lo, buf, NULL, NULL, NULL);
  CHECK_MSG(rc == status, "%s: lyapunov %s", what, dal_status_name(rc));
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

static void test_refusals(void) {
  int fails0 = check_failures;
  dal_builder *b = NULL;
  int q, p, rc;
  // a Lagrangian system with a generalized force callback
  rc = dal_builder_create(2, &b);
  if (!rc) rc = dal_builder_add_coord(b, "x", &q);
  if (!rc) rc = dal_builder_set_lagrangian(b, lag_osc, NULL);
  if (!rc) rc = dal_builder_add_genforce(b, gdrag, NULL);
  expect_refusal("Lagrangian with a callback", compile(b, rc), DAL_E_UNSUPPORTED,
                 "no exact derivative");
  // constraints: the Cartesian pendulum without gravity
  scn_knobs free = scn_default();
  free.g = 0.0;
  // constraints are covered by every tool (test_analysis_manifold); Lyapunov vectors start on
  // the manifold's tangent space, so initial vectors y0 are refused
  {
    dal_system *cs = built(scn_cart_pendulum(&free));
    dal_state *cst = NULL;
    double z[2] = {0.0, -1.0}, zv[2] = {0.0, 0.0}, ex[4], y0[4] = {1, 0, 0, 0};
    CHECK(cs && dal_state_create(cs, &cst) == 0 && dal_state_set(cs, cst, 0.0, z, zv) == 0);
    dal_lyapunov_opts lo = dal_default_lyapunov_opts();
    lo.t_end = 1.0;
    lo.nexp = 1;
    lo.y0 = y0;
    CHECK(cst && dal_lyapunov(cs, cst, &lo, ex, NULL, NULL, NULL) == DAL_E_UNSUPPORTED);
    CHECK(cst && strstr(dal_state_errmsg(cst), "y0") != NULL);
    lo.y0 = NULL;
    lo.nexp = 3; // 2 (n - m) = 2 exponents at most
    CHECK(cst && dal_lyapunov(cs, cst, &lo, ex, NULL, NULL, NULL) == DAL_E_ARG);
    lo.nexp = 0;
    CHECK(cst && dal_lyapunov(cs, cst, &lo, ex, NULL, NULL, NULL) == DAL_OK);
    dal_state_destroy(cst);
    dal_system_destroy(cs);
  }
  // force callbacks (Cartesian and generalized)
  for (int g = 0; g < 2; ++g) {
    rc = scn_builder(&free, 2, &b);
    if (!rc) rc = scn_add_xy(b, "bob", 1.0, "x", "y", &p);
    if (!rc)
      rc = g ? dal_builder_add_genforce(b, gdrag, NULL) : dal_builder_add_force(b, drag, NULL);
    expect_refusal("force callback", compile(b, rc), DAL_E_UNSUPPORTED, "no exact derivative");
  }
  // a user map without third derivatives: named, with the remedy
  double g[2] = {0, -grav};
  rc = dal_builder_create(2, &b);
  if (!rc) rc = dal_builder_add_coord(b, "th", &q);
  if (!rc) rc = dal_builder_add_particle(b, "bob", 1.0, &p);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &prim_hand;
  pd.coords = &q;
  pd.ncoords = 1;
  if (!rc) rc = dal_builder_place_def(b, p, &pd);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  dal_system *sys = compile(b, rc);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double th = 0.4, w = 0.1, K;
  CHECK_OK(dal_state_set(sys, st, 0.0, &th, &w));
  CHECK_OK(dal_forward(sys, st)); // the equations of motion do not need d3
  rc = dal_linearize(sys, st, NULL, NULL, &K);
  CHECK_MSG(rc == DAL_E_DOMAIN && strstr(dal_state_errmsg(st), "'hand_pendulum'") &&
                strstr(dal_state_errmsg(st), "'bob'") &&
                strstr(dal_state_errmsg(st), "dal_jet_make3"),
            "order-2 map: %s (%s)", dal_status_name(rc), dal_state_errmsg(st));
  // a state of another system
  dal_system *other = driven_pendulum();
  rc = dal_linearize(other, st, NULL, NULL, &K);
  CHECK(rc == DAL_E_STATE);
  CHECK(dal_linearize(other, NULL, NULL, NULL, &K) == DAL_E_ARG);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_system_destroy(other);
  printf("  %-40s %s\n", "refusals with named causes", check_failures > fails0 ? "FAILED" : "ok");
}

int main(void) {
  test_flow_fd();
  test_registry_d3();
  printf("hand-derived linearizations and modes:\n");
  test_double_pendulum_modes();
  test_spring_damper();
  test_ring_modes();
  test_rotating_trap();
  test_lagrangian_vs_particles();
  test_refusals();
  return check_summary("test_analysis");
}
