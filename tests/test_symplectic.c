// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Symplectic methods against independent references; compensated summation in RK4 and BS.
//
// References: the discrete maps written out by hand (the midpoint variational integrator on a
// linear oscillator is the Cayley transform of its matrix, rotation by 2 atan(w h / 2);
// Stormer-Verlet is the three-term recurrence q_{n+1} - 2 q_n + q_{n-1} = -(w h)^2 q_n), run
// in long double; the large-amplitude pendulum by Jacobi elliptic functions (ref_elliptic.h);
// a second formulation (minimal coordinates by Bulirsch-Stoer at 1e-13 for a moving pivot);
// finite differences with Richardson extrapolation as the oracle of the one-step map's
// Jacobian (J' Omega J = Omega); Noether's conserved L_z; the same RK4 recurrence in long
// double with compensated summation for the round-off of the library's RK4.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "ref_elliptic.h"
#include "scenes.h"

#define PI 3.14159265358979323846
#define EPS 2.220446049250313e-16

static const dal_method var_m[3] = {DAL_METHOD_VARIATIONAL, DAL_METHOD_VARIATIONAL4,
                                    DAL_METHOD_VARIATIONAL6};
static const dal_method rat_m[3] = {DAL_METHOD_RATTLE, DAL_METHOD_RATTLE4, DAL_METHOD_RATTLE6};
static const int orders[3] = {2, 4, 6};

static dal_system *compile(dal_builder *b, int rc) {
  dal_system *sys = NULL;
  if (!rc) rc = dal_builder_compile(b, &sys);
  if (rc) fprintf(stderr, "build failed: %s\n", dal_builder_errmsg(b));
  CHECK_OK(rc);
  dal_builder_destroy(b);
  return sys;
}

// a standard scene, checked as compile() checks the scenes built here
static dal_system *built(dal_system *sys) {
  CHECK(sys != NULL);
  return sys;
}

static dal_solve_opts fixed(dal_method m, double h) {
  dal_solve_opts o = dal_default_solve_opts();
  o.method = m;
  o.fixed_step = h;
  o.max_steps = 100000000;
  return o;
}

// ---------------------------------------------------------------------------------------------
// scenes

// simple pendulum l = 1, g = 9.8 by a coordinate map, or as the Lagrangian v^2/2 + g cos th
static int pend_lag(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)t;
  (void)ctx;
  *L = dal_add(dal_scale(dal_sq(v[0]), 0.5), dal_scale(dal_cos(q[0]), 9.8));
  return 0;
}

static dal_system *make_pendulum(int lagrangian) {
  if (!lagrangian) {
    scn_knobs k = scn_default();
    k.g = 9.8;
    return built(scn_pendulum(&k));
  }
  dal_builder *b = NULL;
  int th, rc = dal_builder_create(2, &b);
  if (!rc) rc = dal_builder_add_coord(b, "theta", &th);
  if (!rc) rc = dal_builder_set_lagrangian(b, pend_lag, NULL);
  return compile(b, rc);
}

// linear oscillator in the plane, mass m, U = k/2 |q|^2, optional damping Q = -c qdot; by a
// particle (SICM's oscillator: m = 2, k = 1) or by the Lagrangian m/2 |v|^2 - k/2 |q|^2
typedef struct osc_par {
  double m, k, c;
} osc_par;

static int osc_pot(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  const osc_par *p = ctx;
  *U = dal_scale(dal_add(dal_sq(q[0]), dal_sq(q[1])), 0.5 * p->k);
  return 0;
}

static int osc_lag(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)t;
  const osc_par *p = ctx;
  dal_jet T = dal_scale(dal_add(dal_sq(v[0]), dal_sq(v[1])), 0.5 * p->m);
  *L = dal_sub(T, dal_scale(dal_add(dal_sq(q[0]), dal_sq(q[1])), 0.5 * p->k));
  return 0;
}

static int osc_damp(double t, const double *q, const double *qd, double *Q, void *ctx) {
  (void)t;
  (void)q;
  const osc_par *p = ctx;
  Q[0] -= p->c * qd[0];
  Q[1] -= p->c * qd[1];
  return 0;
}

static dal_system *make_oscillator(osc_par *p, int lagrangian) {
  dal_builder *b = NULL;
  scn_knobs free = scn_weightless();
  int c[2], k, rc = scn_builder(&free, 2, &b);
  if (lagrangian) {
    if (!rc) rc = dal_builder_add_coord(b, "x", &c[0]);
    if (!rc) rc = dal_builder_add_coord(b, "y", &c[1]);
    if (!rc) rc = dal_builder_set_lagrangian(b, osc_lag, p);
  } else {
    if (!rc) rc = scn_add_xy(b, "m", p->m, "x", "y", &k);
    if (!rc) rc = dal_builder_add_potential_q(b, osc_pot, p);
  }
  if (!rc && p->c > 0) rc = dal_builder_add_genforce(b, osc_damp, p);
  return compile(b, rc);
}

// Cartesian pendulum (l = 1, g = 9.8) on a rod to the origin or to a pivot moving as
// (a cos(w t), 0)
typedef struct pivot {
  double a, w;
} pivot;

static int pivot_path(dal_jet t, dal_jet *x, void *ctx) {
  const pivot *p = ctx;
  x[0] = dal_scale(dal_cos(dal_scale(t, p->w)), p->a);
  x[1] = dal_const(0.0);
  return 0;
}

static dal_system *make_cart_pendulum(dal_moving_point *mp) {
  scn_knobs k = scn_default();
  k.g = 9.8;
  k.pivot = mp;
  return built(scn_cart_pendulum(&k));
}

// the same driven pendulum in minimal coordinates: pivot (a cos(w t), 0)
static dal_system *make_driven_minimal(const pivot *pv) {
  scn_knobs k = scn_default();
  k.g = 9.8;
  k.ax = pv->a;
  k.w = pv->w;
  return built(scn_pendulum(&k));
}

// double pendulum m1 = 1, m2 = 0.5, l1 = 1, l2 = 0.7, g = 9.81: minimal or Cartesian
static dal_system *make_double(int cartesian) {
  scn_knobs k = scn_default();
  k.m2 = 0.5;
  k.l2 = 0.7;
  return built(cartesian ? scn_cart_double_pendulum(&k) : scn_double_pendulum(&k));
}

// the Cartesian double pendulum's state for angles th (from the downward vertical), at rest
static void double_state(const double *th, double *q) {
  q[0] = sin(th[0]);
  q[1] = -cos(th[0]);
  q[2] = q[0] + 0.7 * sin(th[1]);
  q[3] = q[1] - 0.7 * cos(th[1]);
}

// a charged particle in a non-uniform magnetic field with an anharmonic potential: a
// Lagrangian with a gyroscopic term, L = |v|^2/2 + A(q) . v - U(q), canonical p = v + A(q)
static void mag_A(const double *q, double *A) {
  A[0] = -0.5 * q[1] * (1.0 + q[0] * q[0]);
  A[1] = 0.5 * q[0] * exp(0.3 * q[1]);
}

static int mag_lag(dal_jet t, const dal_jet *q, const dal_jet *v, dal_jet *L, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet x = q[0], y = q[1];
  dal_jet T = dal_scale(dal_add(dal_sq(v[0]), dal_sq(v[1])), 0.5);
  dal_jet Ax = dal_scale(dal_mul(y, dal_addc(dal_sq(x), 1.0)), -0.5);
  dal_jet Ay = dal_scale(dal_mul(x, dal_exp(dal_scale(y, 0.3))), 0.5);
  dal_jet U =
      dal_add(dal_scale(dal_add(dal_sq(x), dal_sq(y)), 0.5), dal_scale(dal_mul(dal_sq(x), y), 0.3));
  *L = dal_sub(dal_add(T, dal_add(dal_mul(Ax, v[0]), dal_mul(Ay, v[1]))), U);
  return 0;
}

static dal_system *make_magnetic(void) {
  dal_builder *b = NULL;
  int c, rc = dal_builder_create(2, &b);
  if (!rc) rc = dal_builder_add_coord(b, "x", &c);
  if (!rc) rc = dal_builder_add_coord(b, "y", &c);
  if (!rc) rc = dal_builder_set_lagrangian(b, mag_lag, NULL);
  return compile(b, rc);
}

// Henon-Heiles: a Cartesian particle of unit mass in U = (x^2 + y^2)/2 + x^2 y - y^3/3
static int hh_pot(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet x = q[0], y = q[1];
  dal_jet quad = dal_scale(dal_add(dal_sq(x), dal_sq(y)), 0.5);
  *U = dal_add(quad, dal_sub(dal_mul(dal_sq(x), y), dal_scale(dal_powi(y, 3), 1.0 / 3.0)));
  return 0;
}

static dal_system *make_henon_heiles(void) {
  dal_builder *b = NULL;
  scn_knobs free = scn_weightless();
  int p, rc = scn_builder(&free, 2, &b);
  if (!rc) rc = scn_add_xy(b, "star", 1.0, "x", "y", &p);
  if (!rc) rc = dal_builder_add_potential_q(b, hh_pot, NULL);
  return compile(b, rc);
}

// spherical pendulum (l = 1, m = 1, g = 9.81): minimal (theta, phi) or Cartesian on a rod
static dal_system *make_spherical(int cartesian) {
  return built(cartesian ? scn_cart_spherical(NULL) : scn_spherical(NULL));
}

// bead on a ring of radius 1 turning at w about the vertical: minimal (dal_map_ring) or
// Cartesian on dal_con_turning_circle
static dal_system *make_ring(double w, int cartesian) {
  scn_knobs k = scn_default();
  k.spin = w;
  return built(cartesian ? scn_cart_bead(&k) : scn_bead(&k));
}

// ---------------------------------------------------------------------------------------------
// 1. the discrete maps written out by hand

// one step of the midpoint variational integrator with midpoint forcing on m q'' = -k q - c q',
// per component: m a / h + (h/4) k a + (c/2) a = p0 - (h/2) k q0 with a = q1 - q0
static void midpoint_map(const osc_par *o, long double h, long double *q, long double *p) {
  long double a = (*p - 0.5L * h * o->k * *q) / (o->m / h + 0.25L * h * o->k + 0.5L * o->c);
  long double q1 = *q + a;
  *p = *p - h * o->k * (*q + 0.5L * a) - o->c * a;
  *q = q1;
}

static void test_discrete_maps(void) {
  const double q0[2] = {1, 2}, v0[2] = {3, 4}, T = 10.0;
  osc_par pars[2] = {{2.0, 1.0, 0.0}, {2.0, 1.0, 0.3}}; // SICM's oscillator, undamped and damped
  for (int damped = 0; damped < 2; ++damped)
    for (int lag = 0; lag < 2; ++lag) {
      osc_par *o = &pars[damped];
      dal_system *sys = make_oscillator(o, lag);
      dal_state *st = NULL;
      CHECK_OK(dal_state_create(sys, &st));
      for (int hi = 0; hi < 2; ++hi) {
        double h = hi ? 0.05 : 0.1;
        int N = (int)lround(T / h);
        dal_solve_opts op = fixed(DAL_METHOD_VARIATIONAL, h);
        CHECK_OK(dal_state_set(sys, st, 0.0, q0, v0));
        CHECK_OK(dal_advance(sys, st, &op, T));
        double err = 0.0, errc = 0.0;
        for (int i = 0; i < 2; ++i) {
          long double q = q0[i], p = o->m * v0[i];
          for (int k = 0; k < N; ++k)
            midpoint_map(o, h, &q, &p);
          err = fmax(err, fabs(dal_state_q(st)[i] - (double)q));
          err = fmax(err, fabs(dal_state_qdot(st)[i] - (double)(p / o->m)));
          if (!damped) {
            // the recurrence itself against its closed form: rotation by 2 atan(w h / 2)
            double w = sqrt(o->k / o->m), th = 2.0 * atan(0.5 * w * h);
            double qc = q0[i] * cos(N * th) + v0[i] / w * sin(N * th);
            errc = fmax(errc, fabs(qc - (double)q));
          }
        }
        CHECK_MSG(err <= 1e-13, "variational (%s, damping %g) vs the midpoint map: %.3g",
                  lag ? "Lagrangian" : "particle", o->c, err);
        CHECK_MSG(errc <= 1e-12, "midpoint map vs its closed form: %.3g", errc);
      }
      dal_state_destroy(st);
      dal_system_destroy(sys);
    }
  // RATTLE without constraints is Stormer-Verlet: q_{n+1} - 2 q_n + q_{n-1} = -(w h)^2 q_n
  osc_par o = {1.0, 4.0, 0.0};
  dal_system *sys = make_oscillator(&o, 0);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double h = 0.1, w = 2.0;
  dal_solve_opts op = fixed(DAL_METHOD_RATTLE, h);
  CHECK_OK(dal_state_set(sys, st, 0.0, q0, v0));
  CHECK_OK(dal_advance(sys, st, &op, T));
  double err = 0.0, errc = 0.0, th = acos(1.0 - 0.5 * (w * h) * (w * h));
  for (int i = 0; i < 2; ++i) {
    long double q = q0[i], v = v0[i], q1 = 0;
    for (int k = 0; k < 100; ++k) {
      long double vh = v - 0.5L * h * w * w * q;
      q = q + h * vh;
      v = vh - 0.5L * h * w * w * q;
      if (k == 0) q1 = q;
    }
    err = fmax(err,
               fmax(fabs(dal_state_q(st)[i] - (double)q), fabs(dal_state_qdot(st)[i] - (double)v)));
    // the recurrence's closed form: q_n = q0 cos(n th) + (q1 - q0 cos th) / sin th sin(n th)
    double qc = q0[i] * cos(100 * th) + ((double)q1 - q0[i] * cos(th)) / sin(th) * sin(100 * th);
    errc = fmax(errc, fabs(qc - (double)q));
  }
  CHECK_MSG(err <= 1e-13, "RATTLE (no constraints) vs Stormer-Verlet: %.3g", err);
  CHECK_MSG(errc <= 1e-12, "Stormer-Verlet vs its closed form: %.3g", errc);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// ---------------------------------------------------------------------------------------------
// 2. measured orders

// error of the pendulum released at 2.0 rad after T against the elliptic solution
static double pendulum_error(dal_system *sys, dal_state *st, int cartesian, dal_method m, double h,
                             double T) {
  double th0 = 2.0, th, thd;
  if (cartesian) {
    double q[2] = {sin(th0), -cos(th0)}, v[2] = {0, 0};
    CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
  } else {
    double v = 0.0;
    CHECK_OK(dal_state_set(sys, st, 0.0, &th0, &v));
  }
  dal_solve_opts o = fixed(m, h);
  int rc = dal_advance(sys, st, &o, T);
  CHECK_OK(rc);
  if (rc) return NAN;
  ref_pendulum(th0, sqrt(9.8), T, &th, &thd);
  const double *q = dal_state_q(st), *v = dal_state_qdot(st);
  if (!cartesian) return fmax(fabs(q[0] - th), fabs(v[0] - thd));
  double e = fmax(fabs(q[0] - sin(th)), fabs(q[1] + cos(th)));
  return fmax(e, fmax(fabs(v[0] - cos(th) * thd), fabs(v[1] - sin(th) * thd)));
}

static void test_orders(void) {
  // variational on the elliptic pendulum, by its coordinate map and by its Lagrangian
  for (int lag = 0; lag < 2; ++lag) {
    dal_system *sys = make_pendulum(lag);
    dal_state *st = NULL;
    CHECK_OK(dal_state_create(sys, &st));
    for (int k = 0; k < 3; ++k) {
      double e1 = pendulum_error(sys, st, 0, var_m[k], 0.05, 10.0);
      double e2 = pendulum_error(sys, st, 0, var_m[k], 0.025, 10.0);
      double p = log2(e1 / e2);
      CHECK_MSG(p > orders[k] - 0.15 && p < orders[k] + 0.3,
                "%s (%s): measured order %.3f (errors %.3g, %.3g)", dal_method_name(var_m[k]),
                lag ? "Lagrangian" : "particles", p, e1, e2);
    }
    dal_state_destroy(st);
    dal_system_destroy(sys);
  }
  // variational on SICM's oscillator against the closed form
  osc_par o = {2.0, 1.0, 0.0};
  dal_system *sys = make_oscillator(&o, 0);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  const double q0[2] = {1, 2}, v0[2] = {3, 4}, w = sqrt(0.5), T = 10.0;
  for (int k = 0; k < 3; ++k) {
    double e[2];
    for (int j = 0; j < 2; ++j) {
      dal_solve_opts op = fixed(var_m[k], j ? 0.1 : 0.2);
      CHECK_OK(dal_state_set(sys, st, 0.0, q0, v0));
      CHECK_OK(dal_advance(sys, st, &op, T));
      e[j] = 0.0;
      for (int i = 0; i < 2; ++i) {
        double q = q0[i] * cos(w * T) + v0[i] / w * sin(w * T);
        double v = -q0[i] * w * sin(w * T) + v0[i] * cos(w * T);
        e[j] = fmax(e[j], fmax(fabs(dal_state_q(st)[i] - q), fabs(dal_state_qdot(st)[i] - v)));
      }
    }
    double p = log2(e[0] / e[1]);
    CHECK_MSG(p > orders[k] - 0.15 && p < orders[k] + 0.3,
              "%s on the oscillator: measured order %.3f (errors %.3g, %.3g)",
              dal_method_name(var_m[k]), p, e[0], e[1]);
  }
  dal_state_destroy(st);
  dal_system_destroy(sys);
  // RATTLE on the Cartesian pendulum
  sys = make_cart_pendulum(NULL);
  CHECK_OK(dal_state_create(sys, &st));
  for (int k = 0; k < 3; ++k) {
    double e1 = pendulum_error(sys, st, 1, rat_m[k], 0.025, 5.0);
    double e2 = pendulum_error(sys, st, 1, rat_m[k], 0.0125, 5.0);
    double p = log2(e1 / e2);
    CHECK_MSG(p > orders[k] - 0.15 && p < orders[k] + 0.3,
              "%s on the Cartesian pendulum: measured order %.3f (errors %.3g, %.3g)",
              dal_method_name(rat_m[k]), p, e1, e2);
  }
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// RATTLE with a rheonomic constraint (rod to a moving pivot) against the same pendulum in
// minimal coordinates by Bulirsch-Stoer: second order, residuals at rounding
static void test_rheonomic(void) {
  pivot pv = {0.2, 5.0};
  dal_moving_point mp = {pivot_path, &pv};
  dal_system *cs = make_cart_pendulum(&mp), *ms = make_driven_minimal(&pv);
  dal_state *a = NULL, *b = NULL;
  CHECK_OK(dal_state_create(ms, &a));
  CHECK_OK(dal_state_create(cs, &b));
  double th0 = 1.0, thd0 = 0.0, T = 3.0;
  dal_solve_opts om = dal_default_solve_opts();
  om.method = DAL_METHOD_BS;
  om.rtol = om.atol = 1e-13;
  CHECK_OK(dal_state_set(ms, a, 0.0, &th0, &thd0));
  CHECK_OK(dal_advance(ms, a, &om, T));
  const double *r = dal_state_positions(a), *rv = dal_state_velocities(a);
  double e[2];
  for (int j = 0; j < 2; ++j) {
    double q[2] = {pv.a + sin(th0), -cos(th0)}, v[2] = {0, 0};
    dal_solve_opts o = fixed(DAL_METHOD_RATTLE, j ? 0.005 : 0.01);
    CHECK_OK(dal_state_set(cs, b, 0.0, q, v));
    CHECK_OK(dal_advance(cs, b, &o, T));
    const double *x = dal_state_q(b), *xv = dal_state_qdot(b);
    e[j] = 0.0;
    for (int i = 0; i < 2; ++i)
      e[j] = fmax(e[j], fmax(fabs(x[i] - r[i]), fabs(xv[i] - rv[i])));
    dal_stats s;
    dal_state_stats(b, &s);
    CHECK_MSG(s.max_phi <= 32 * EPS * 2 && s.max_phidot <= 32 * EPS * 4,
              "moving pivot: residuals %.3g, %.3g", s.max_phi, s.max_phidot);
  }
  double p = log2(e[0] / e[1]);
  CHECK_MSG(p > 1.85 && p < 2.3, "RATTLE with a moving pivot: order %.3f (errors %.3g, %.3g)", p,
            e[0], e[1]);
  dal_state_destroy(a);
  dal_state_destroy(b);
  dal_system_destroy(cs);
  dal_system_destroy(ms);
}

// ---------------------------------------------------------------------------------------------
// 3. symplecticity of the one-step map: J' Omega J = Omega (finite differences as the oracle)

typedef enum { SC_DOUBLE, SC_MAGNETIC, SC_HENON } sympl_scene;

// (q, p) -> (q, qdot) and back, through each scene's own Legendre transform
static void to_qdot(dal_system *sys, dal_state *st, sympl_scene sc, const double *z, double *qd) {
  if (sc == SC_MAGNETIC) {
    double A[2];
    mag_A(z, A);
    qd[0] = z[2] - A[0];
    qd[1] = z[3] - A[1];
  } else if (sc == SC_HENON) {
    qd[0] = z[2];
    qd[1] = z[3];
  } else {
    double zero[2] = {0, 0};
    CHECK_OK(dal_state_set(sys, st, 0, z, zero));
    CHECK_OK(dal_forward(sys, st));
    const double *M = dal_state_mass_matrix(st);
    double det = M[0] * M[3] - M[1] * M[2];
    qd[0] = (M[3] * z[2] - M[2] * z[3]) / det;
    qd[1] = (-M[1] * z[2] + M[0] * z[3]) / det;
  }
}

static void to_momenta(dal_system *sys, dal_state *st, sympl_scene sc, const double *q,
                       const double *qd, double *p) {
  if (sc == SC_MAGNETIC) {
    double A[2];
    mag_A(q, A);
    p[0] = qd[0] + A[0];
    p[1] = qd[1] + A[1];
  } else if (sc == SC_HENON) {
    p[0] = qd[0];
    p[1] = qd[1];
  } else {
    CHECK_OK(dal_state_set(sys, st, 0, q, qd));
    CHECK_OK(dal_forward(sys, st));
    const double *M = dal_state_mass_matrix(st);
    p[0] = M[0] * qd[0] + M[2] * qd[1];
    p[1] = M[1] * qd[0] + M[3] * qd[1];
  }
}

static void one_step(dal_system *sys, dal_state *st, sympl_scene sc, dal_method m, double h,
                     const double *z, double *z1) {
  double qd[2], q1[2], v1[2];
  to_qdot(sys, st, sc, z, qd);
  CHECK_OK(dal_state_set(sys, st, 0, z, qd));
  dal_solve_opts o = fixed(m, h);
  CHECK_OK(dal_advance(sys, st, &o, h));
  memcpy(q1, dal_state_q(st), sizeof q1);
  memcpy(v1, dal_state_qdot(st), sizeof v1);
  z1[0] = q1[0];
  z1[1] = q1[1];
  to_momenta(sys, st, sc, q1, v1, z1 + 2);
}

// max |J' Omega J - Omega| with J by central differences extrapolated (Richardson, O(d^4))
static double symplectic_defect(dal_system *sys, dal_state *st, sympl_scene sc, dal_method m,
                                double h, const double *z0) {
  double J[4][4];
  for (int j = 0; j < 4; ++j) {
    double col[2][4];
    for (int r = 0; r < 2; ++r) {
      double d = r ? 1e-3 : 2e-3, zp[4], zm[4], a[4], b[4];
      memcpy(zp, z0, sizeof zp);
      memcpy(zm, z0, sizeof zm);
      zp[j] += d;
      zm[j] -= d;
      one_step(sys, st, sc, m, h, zp, a);
      one_step(sys, st, sc, m, h, zm, b);
      for (int i = 0; i < 4; ++i)
        col[r][i] = (a[i] - b[i]) / (2 * d);
    }
    for (int i = 0; i < 4; ++i)
      J[i][j] = (4 * col[1][i] - col[0][i]) / 3;
  }
  double mx = 0.0;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      double s = 0.0;
      for (int i = 0; i < 2; ++i)
        s += J[i][a] * J[i + 2][b] - J[i + 2][a] * J[i][b];
      double om = (a < 2 && b == a + 2) ? 1.0 : (a >= 2 && b == a - 2) ? -1.0 : 0.0;
      mx = fmax(mx, fabs(s - om));
    }
  return mx;
}

static void test_symplecticity(void) {
  struct {
    sympl_scene sc;
    dal_method m;
    double z0[4];
    const char *what;
  } cases[] = {
      {SC_DOUBLE, DAL_METHOD_VARIATIONAL, {1.2, -0.7, 0.8, -0.3}, "double pendulum (particles)"},
      {SC_DOUBLE, DAL_METHOD_VARIATIONAL4, {1.2, -0.7, 0.8, -0.3}, "double pendulum, order 4"},
      {SC_MAGNETIC, DAL_METHOD_VARIATIONAL, {0.4, -0.3, 0.5, 0.2}, "magnetic (Lagrangian)"},
      {SC_MAGNETIC, DAL_METHOD_VARIATIONAL6, {0.4, -0.3, 0.5, 0.2}, "magnetic, order 6"},
      {SC_HENON, DAL_METHOD_RATTLE, {0.3, -0.2, 0.25, 0.3}, "Henon-Heiles (RATTLE)"},
      {SC_HENON, DAL_METHOD_RATTLE4, {0.3, -0.2, 0.25, 0.3}, "Henon-Heiles, order 4"},
  };
  double rk4[3] = {0, 0, 0};
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
    dal_system *sys = cases[c].sc == SC_DOUBLE     ? make_double(0)
                      : cases[c].sc == SC_MAGNETIC ? make_magnetic()
                                                   : make_henon_heiles();
    dal_state *st = NULL;
    CHECK_OK(dal_state_create(sys, &st));
    double d = symplectic_defect(sys, st, cases[c].sc, cases[c].m, 0.2, cases[c].z0);
    CHECK_MSG(d <= 2e-11, "%s: |J' Omega J - Omega| = %.3g", cases[c].what, d);
    if (rk4[cases[c].sc] == 0.0)
      rk4[cases[c].sc] = symplectic_defect(sys, st, cases[c].sc, DAL_METHOD_RK4, 0.2, cases[c].z0);
    dal_state_destroy(st);
    dal_system_destroy(sys);
  }
  // the oracle can tell: RK4 (not symplectic) at the same step misses by far more
  for (int s = 0; s < 3; ++s)
    CHECK_MSG(rk4[s] > 1e-7, "RK4's defect on scene %d is only %.3g", s, rk4[s]);
}

// ---------------------------------------------------------------------------------------------
// 4. invariants: Noether's L_z, bounded energy and Jacobi integral

typedef struct inv_mon {
  int kind; // 0: L_z from the particle, 1: energy E, 2: Jacobi integral h, 3: E - w L_z
  double w, T, ref, win[10];
  int started;
} inv_mon;

static int inv_monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  inv_mon *m = ctx;
  dal_energies e;
  dal_state_energies(st, &e);
  const double *r = dal_state_positions(st), *v = dal_state_velocities(st);
  double lz = r[0] * v[1] - r[1] * v[0];
  double val = m->kind == 0 ? lz : m->kind == 1 ? e.E : m->kind == 2 ? e.h : e.E - m->w * lz;
  if (!m->started) {
    m->ref = val;
    m->started = 1;
  }
  int w = (int)(dal_state_time(st) / m->T * 10);
  if (w > 9) w = 9;
  m->win[w] = fmax(m->win[w], fabs(val - m->ref));
  return 0;
}

static double run_invariant(dal_system *sys, const double *q, const double *qd, int kind, double w,
                            dal_solve_opts *o, double T, double dt, inv_mon *m) {
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  memset(m, 0, sizeof *m);
  m->kind = kind;
  m->w = w;
  m->T = T;
  CHECK_OK(dal_state_set(sys, st, 0.0, q, qd));
  int rc = 0;
  if (o->method == DAL_METHOD_DOPRI5) {
    // DOPRI5 measured at its own steps (dal_advance lands a step on each output time):
    // between steps its cubic dense output adds an interpolation error of its own, larger
    // than the energy drift this test looks for at rtol 1e-6 (docs/events.md)
    CHECK_OK(dal_forward(sys, st));
    inv_monitor(sys, st, m);
    for (long k = 1; !rc && (double)k * dt <= T; ++k)
      if ((rc = dal_advance(sys, st, o, (double)k * dt)) == 0) rc = inv_monitor(sys, st, m);
  } else {
    rc = dal_evolve(sys, st, o, T, dt, inv_monitor, m);
  }
  if (rc) fprintf(stderr, "evolve: %s\n", dal_state_errmsg(st));
  CHECK_OK(rc);
  dal_state_destroy(st);
  double mx = 0.0;
  for (int i = 0; i < 10; ++i)
    mx = fmax(mx, m->win[i]);
  return mx;
}

static void test_noether(void) {
  // spherical pendulum: L_z = m (x vy - y vx) by the variational method (minimal, particles)
  // and by RATTLE (Cartesian on a rod), against an adaptive method
  inv_mon m;
  dal_system *sys = make_spherical(0);
  double q[2] = {1.0, 0.3}, qd[2] = {0.5, 2.0}, Lz = 2.0 * pow(sin(1.0), 2);
  dal_solve_opts o = fixed(DAL_METHOD_VARIATIONAL, 0.01);
  double d = run_invariant(sys, q, qd, 0, 0, &o, 50.0, 0.5, &m);
  CHECK_MSG(d <= 1e-14 * Lz, "spherical pendulum, variational: L_z drifts by %.3g", d);
  dal_solve_opts oa = dal_default_solve_opts();
  oa.method = DAL_METHOD_DOPRI5;
  double da = run_invariant(sys, q, qd, 0, 0, &oa, 50.0, 0.5, &m);
  CHECK_MSG(da > 1e-10, "DOPRI5 keeps L_z to %.3g: the check cannot tell", da);
  dal_system_destroy(sys);
  sys = make_spherical(1);
  double s1 = sin(1.0), c1 = cos(1.0), x[3] = {s1 * cos(0.3), s1 * sin(0.3), -c1};
  // velocity of theta' = 0.5, phi' = 2 at (theta, phi) = (1, 0.3)
  double v[3] = {0.5 * c1 * cos(0.3) - 2.0 * s1 * sin(0.3),
                 0.5 * c1 * sin(0.3) + 2.0 * s1 * cos(0.3), 0.5 * s1};
  o = fixed(DAL_METHOD_RATTLE, 0.005);
  d = run_invariant(sys, x, v, 0, 0, &o, 20.0, 0.5, &m);
  CHECK_MSG(d <= 1e-14 * Lz, "spherical pendulum, RATTLE: L_z drifts by %.3g", d);
  dal_system_destroy(sys);
}

// the energy error of a symplectic method oscillates with a bounded amplitude; an adaptive
// method's grows with time
static void test_bounded_energy(void) {
  inv_mon m;
  dal_system *sys = make_pendulum(0);
  double th = 2.0 * PI / 3.0, thd = 0.0, T = 1500.0; // about 550 periods
  dal_solve_opts o = fixed(DAL_METHOD_VARIATIONAL, 0.05);
  run_invariant(sys, &th, &thd, 1, 0, &o, T, 0.5, &m);
  CHECK_MSG(m.win[9] <= 1.05 * m.win[0] && m.win[9] > 0,
            "variational pendulum: energy error %.3g in the first tenth, %.3g in the last",
            m.win[0], m.win[9]);
  dal_solve_opts oa = dal_default_solve_opts();
  oa.method = DAL_METHOD_DOPRI5;
  oa.rtol = oa.atol = 1e-6;
  run_invariant(sys, &th, &thd, 1, 0, &oa, T, 0.5, &m);
  CHECK_MSG(m.win[9] >= 5.0 * m.win[0],
            "DOPRI5 pendulum: energy error %.3g in the first tenth, %.3g in the last (expected "
            "secular growth)",
            m.win[0], m.win[9]);
  dal_system_destroy(sys);
  // the Jacobi integral of the bead on the turning ring: minimal (variational) and Cartesian
  // on a turning circle (RATTLE, rheonomic), where it is E - w L_z
  double w = 2.0 * PI * 0.7, q = 2.0, qd = 0.0;
  sys = make_ring(w, 0);
  o = fixed(DAL_METHOD_VARIATIONAL, 0.01);
  run_invariant(sys, &q, &qd, 2, w, &o, 300.0, 0.5, &m);
  CHECK_MSG(m.win[9] <= 1.05 * m.win[0] && m.win[9] > 0,
            "ring, variational: Jacobi integral error %.3g first, %.3g last", m.win[0], m.win[9]);
  dal_system_destroy(sys);
  sys = make_ring(w, 1);
  double x[3] = {sin(2.0), 0, -cos(2.0)}, v[3] = {0, w * sin(2.0), 0};
  o = fixed(DAL_METHOD_RATTLE, 0.01);
  run_invariant(sys, x, v, 3, w, &o, 300.0, 0.5, &m);
  CHECK_MSG(m.win[9] <= 1.05 * m.win[0] && m.win[9] > 0,
            "turning circle, RATTLE: E - w L_z error %.3g first, %.3g last", m.win[0], m.win[9]);
  dal_system_destroy(sys);
}

// ---------------------------------------------------------------------------------------------
// 5. RATTLE's residuals at every step; outputs do not perturb the trajectory

typedef struct res_mon {
  double phi, phidot;
  long n;
} res_mon;

static int res_monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  res_mon *m = ctx;
  int mrows = dal_system_nconstraints(sys), n = dal_system_ncoords(sys);
  double qmax = 1.0, vmax = 1.0, p = 0.0, pd = 0.0;
  for (int i = 0; i < n; ++i) {
    qmax = fmax(qmax, fabs(dal_state_q(st)[i]));
    vmax = fmax(vmax, fabs(dal_state_qdot(st)[i]));
  }
  for (int r = 0; r < mrows; ++r) {
    p = fmax(p, fabs(dal_state_phi(st)[r]));
    pd = fmax(pd, fabs(dal_state_phidot(st)[r]));
  }
  // each step's residuals, relative to the state's scale
  m->phi = fmax(m->phi, p / qmax);
  m->phidot = fmax(m->phidot, pd / vmax);
  m->n++;
  return 0;
}

static void test_rattle_residuals(void) {
  double th[2] = {2.0, 2.5}, q[4], v[4] = {0, 0, 0, 0};
  double_state(th, q);
  dal_system *sys = make_double(1);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  for (int k = 0; k < 3; ++k) {
    res_mon m = {0, 0, 0};
    dal_solve_opts o = fixed(rat_m[k], 0.01);
    CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
    CHECK_OK(dal_evolve(sys, st, &o, 3.0, 0.01, res_monitor, &m));
    dal_stats s;
    dal_state_stats(st, &s);
    CHECK(m.n == 301 && s.steps == 300);
    CHECK_MSG(m.phi <= 32 * EPS && m.phidot <= 32 * EPS,
              "%s: residuals at the steps %.3g (phi), %.3g (phidot)", dal_method_name(rat_m[k]),
              m.phi, m.phidot);
    CHECK_MSG(s.max_phi <= 32 * EPS * 1.7 && s.max_phidot <= 32 * EPS * 10,
              "%s: stats residuals %.3g, %.3g", dal_method_name(rat_m[k]), s.max_phi, s.max_phidot);
  }
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// a run with outputs between grid points ends bit for bit where a run without them ends
static void test_outputs(void) {
  for (int c = 0; c < 3; ++c) {
    dal_system *sys = c == 0 ? make_pendulum(0) : c == 1 ? make_pendulum(1) : make_double(1);
    dal_state *a = NULL, *b = NULL;
    CHECK_OK(dal_state_create(sys, &a));
    CHECK_OK(dal_state_create(sys, &b));
    int n = dal_system_ncoords(sys);
    double q[4] = {2.0, 0, 0, 0}, v[4] = {0, 0, 0, 0}, th[2] = {2.0, 2.5};
    if (c == 2) double_state(th, q);
    dal_solve_opts o = fixed(c == 2 ? DAL_METHOD_RATTLE4 : DAL_METHOD_VARIATIONAL4, 0.02);
    CHECK_OK(dal_state_set(sys, a, 0.0, q, v));
    CHECK_OK(dal_state_set(sys, b, 0.0, q, v));
    CHECK_OK(dal_advance(sys, a, &o, 4.0));
    CHECK_OK(dal_evolve(sys, b, &o, 4.0, 0.0371, NULL, NULL));
    CHECK_MSG(memcmp(dal_state_q(a), dal_state_q(b), (size_t)n * sizeof(double)) == 0,
              "scene %d: outputs off the grid changed the trajectory (q %.17g vs %.17g)", c,
              dal_state_q(a)[0], dal_state_q(b)[0]);
    for (int i = 0; i < n; ++i)
      CHECK_CLOSE(dal_state_qdot(b)[i], dal_state_qdot(a)[i], 4 * EPS);
    dal_state_destroy(a);
    dal_state_destroy(b);
    dal_system_destroy(sys);
  }
  // an output between grid points is the composed step's value there: compare with the
  // elliptic solution at an off-grid time (order-4 accuracy, not a shortened grid)
  dal_system *sys = make_pendulum(0);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double th0 = 2.0, v0 = 0.0, th, thd;
  dal_solve_opts o = fixed(DAL_METHOD_VARIATIONAL4, 0.025);
  CHECK_OK(dal_state_set(sys, st, 0.0, &th0, &v0));
  CHECK_OK(dal_advance(sys, st, &o, 3.01234));
  ref_pendulum(th0, sqrt(9.8), 3.01234, &th, &thd);
  CHECK_MSG(fabs(dal_state_q(st)[0] - th) < 1e-5, "off-grid output: error %.3g",
            fabs(dal_state_q(st)[0] - th));
  CHECK_CLOSE(dal_state_time(st), 3.01234, 0.0);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// ---------------------------------------------------------------------------------------------
// 6. where they refuse or fail

static void test_failures(void) {
  char msg[512];
  // variational on a constrained system; RATTLE on a coordinate map, with a damper, with GGL
  dal_system *cs = make_cart_pendulum(NULL), *ps = make_pendulum(0);
  dal_state *a = NULL, *b = NULL;
  CHECK_OK(dal_state_create(cs, &a));
  CHECK_OK(dal_state_create(ps, &b));
  double q[2] = {sin(1.0), -cos(1.0)}, v[2] = {0, 0}, th = 1.0, thd = 0.0;
  CHECK_OK(dal_state_set(cs, a, 0, q, v));
  CHECK_OK(dal_state_set(ps, b, 0, &th, &thd));
  dal_solve_opts o = fixed(DAL_METHOD_VARIATIONAL, 0.01);
  CHECK(dal_advance(cs, a, &o, 1.0) == DAL_E_UNSUPPORTED);
  CHECK_MSG(strstr(dal_state_errmsg(a), "RATTLE") != NULL, "%s", dal_state_errmsg(a));
  o.method = DAL_METHOD_RATTLE;
  CHECK(dal_advance(ps, b, &o, 1.0) == DAL_E_UNSUPPORTED);
  snprintf(msg, sizeof msg, "%s", dal_state_errmsg(b));
  CHECK_MSG(strstr(msg, "'bob'") && strstr(msg, "'pendulum'"), "%s", msg);
  o.form = DAL_FORM_GGL;
  CHECK(dal_advance(cs, a, &o, 1.0) == DAL_E_UNSUPPORTED);
  CHECK(dal_state_time(a) == 0.0);
  dal_state_destroy(a);
  dal_state_destroy(b);
  dal_system_destroy(cs);
  dal_system_destroy(ps);
  {
    dal_builder *bb = NULL;
    scn_knobs free = scn_weightless();
    int p, rc = scn_builder(&free, 2, &bb);
    if (!rc) rc = scn_add_xy(bb, "m", 1.0, "x", "y", &p);
    dal_damper_def dd = dal_default_damper_def();
    dd.a = p;
    dd.c = 0.1;
    if (!rc) rc = dal_builder_add_damper_def(bb, &dd);
    dal_system *ds = compile(bb, rc);
    CHECK_OK(dal_state_create(ds, &a));
    double z[2] = {1, 0};
    CHECK_OK(dal_state_set(ds, a, 0, z, z));
    o = fixed(DAL_METHOD_RATTLE, 0.01);
    CHECK(dal_advance(ds, a, &o, 1.0) == DAL_E_UNSUPPORTED);
    CHECK_MSG(strstr(dal_state_errmsg(a), "damper") != NULL, "%s", dal_state_errmsg(a));
    dal_state_destroy(a);
    dal_system_destroy(ds);
  }
}

// a stiff spring bounds the step by its period: Stormer-Verlet (RATTLE) is stable exactly
// for w h < 2 (|cos theta| = |1 - (w h)^2/2| <= 1); the variational method (the implicit
// midpoint rule on a linear spring) stays bounded at any step, its energy exact, but turns
// the oscillation by 2 atan(w h / 2) per step instead of w h: beyond w h ~ 1 the fast motion
// is not resolved. On a nonlinear scene Newton's iteration fails at such steps: DAL_E_CONV,
// the state at the last accepted step.
static void test_stiff(void) {
  osc_par o = {1.0, 1e4, 0.0}; // w = 100
  dal_system *sys = make_oscillator(&o, 0);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q0[2] = {1e-3, 0}, v0[2] = {0, 0.1}; // amplitude 1e-3 in both directions
  for (int k = 0; k < 2; ++k) {
    double h = k ? 0.0205 : 0.0195; // w h = 2.05 and 1.95
    dal_solve_opts op = fixed(DAL_METHOD_RATTLE, h);
    CHECK_OK(dal_state_set(sys, st, 0.0, q0, v0));
    CHECK_OK(dal_advance(sys, st, &op, 500 * h));
    double amp = fmax(fabs(dal_state_q(st)[0]), fabs(dal_state_q(st)[1]));
    if (k)
      CHECK_MSG(amp > 1.0, "Verlet beyond w h = 2 should blow up; amplitude %.3g", amp);
    else
      CHECK_MSG(amp < 0.1, "Verlet below w h = 2 should stay bounded; amplitude %.3g", amp);
  }
  dal_solve_opts op = fixed(DAL_METHOD_VARIATIONAL, 0.05); // w h = 5
  CHECK_OK(dal_state_set(sys, st, 0.0, q0, v0));
  CHECK_OK(dal_advance(sys, st, &op, 1.0));
  CHECK_OK(dal_forward(sys, st));
  dal_energies e;
  dal_state_energies(st, &e);
  double E0 = 0.5 * 0.01 + 0.5 * 1e4 * 1e-6, w = 100.0;
  CHECK_MSG(fabs(e.E - E0) <= 1e-12 * E0, "variational at w h = 5: energy %.17g vs %.17g", e.E, E0);
  double xe = q0[0] * cos(w * 1.0), xerr = fabs(dal_state_q(st)[0] - xe);
  CHECK_MSG(xerr > 3e-4, "variational at w h = 5 should miss the phase; error only %.3g", xerr);
  dal_system *ps = make_pendulum(0);
  dal_state *pst = NULL;
  CHECK_OK(dal_state_create(ps, &pst));
  double th = 2.0, thd = 0.0;
  op = fixed(DAL_METHOD_VARIATIONAL, 1.8);
  CHECK_OK(dal_state_set(ps, pst, 0.0, &th, &thd));
  int rc = dal_advance(ps, pst, &op, 90.0);
  double tf = dal_state_time(pst);
  CHECK_MSG(rc == DAL_E_CONV, "variational pendulum at h = 1.8: status %d (%s)", rc,
            dal_state_errmsg(pst));
  CHECK(strstr(dal_state_errmsg(pst), "fixed_step") != NULL);
  CHECK_MSG(tf >= 0.0 && tf < 90.0 && fabs(tf / 1.8 - round(tf / 1.8)) < 1e-9,
            "the state should hold the last grid point, t = %.17g", tf);
  CHECK(isfinite(dal_state_q(pst)[0]) && isfinite(dal_state_qdot(pst)[0]));
  dal_state_destroy(pst);
  dal_system_destroy(ps);
  // opts.max_steps stops at a grid point, the state evaluated there
  op = fixed(DAL_METHOD_VARIATIONAL, 0.001);
  op.max_steps = 10;
  CHECK_OK(dal_state_set(sys, st, 0.0, q0, v0));
  CHECK(dal_advance(sys, st, &op, 1.0) == DAL_E_MAXSTEPS);
  CHECK_CLOSE(dal_state_time(st), 0.01, 1e-15);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  // a step below the floating-point resolution of t cannot advance the grid
  dal_system *ps2 = make_pendulum(0);
  dal_state *st2 = NULL;
  CHECK_OK(dal_state_create(ps2, &st2));
  double th2 = 1.0, thd2 = 0.0;
  op = fixed(DAL_METHOD_VARIATIONAL, 1e-12);
  CHECK_OK(dal_state_set(ps2, st2, 1e6, &th2, &thd2));
  CHECK(dal_advance(ps2, st2, &op, 1e6 + 1.0) == DAL_E_ARG);
  CHECK_MSG(strstr(dal_state_errmsg(st2), "fixed_step") != NULL, "%s", dal_state_errmsg(st2));
  CHECK(dal_state_time(st2) == 1e6);
  dal_state_destroy(st2);
  dal_system_destroy(ps2);
  CHECK(strcmp(dal_method_name(DAL_METHOD_RATTLE6), "rattle6") == 0);
  CHECK(strcmp(dal_method_name(DAL_METHOD_VARIATIONAL4), "variational4") == 0);
}

// ---------------------------------------------------------------------------------------------
// 7. compensated summation in RK4 and Bulirsch-Stoer

// RK4 for q'' = -q (unit mass and stiffness: the library's right-hand side is exact) on the
// library's own time grid, in long double with compensation (the exact-arithmetic trajectory
// to ~1e-19) or, with naive = 1, in double without compensation (the previous library code);
// the recurrence is the scene library's
static void rk4_replica(const double *q0, const double *v0, double T, double H, int naive,
                        double *out) {
  double y0[4] = {q0[0], q0[1], v0[0], v0[1]};
  scn_rk4_replica(y0, T, H, naive, out);
}

static void test_compensated(void) {
  osc_par o = {1.0, 1.0, 0.0};
  dal_system *sys = make_oscillator(&o, 0);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  const double q0[2][2] = {{1, 2}, {-0.7, 0.4}}, v0[2][2] = {{3, 4}, {2.5, -1.1}};
  double H = 1e-3, T = 100.0, worst = 0.0, worst_naive = 0.0;
  for (int c = 0; c < 2; ++c) {
    dal_solve_opts op = fixed(DAL_METHOD_RK4, H);
    CHECK_OK(dal_state_set(sys, st, 0.0, q0[c], v0[c]));
    CHECK_OK(dal_advance(sys, st, &op, T));
    double ref[4], nv[4];
    rk4_replica(q0[c], v0[c], T, H, 0, ref);
    rk4_replica(q0[c], v0[c], T, H, 1, nv);
    for (int i = 0; i < 2; ++i) {
      worst = fmax(
          worst, fmax(fabs(dal_state_q(st)[i] - ref[i]), fabs(dal_state_qdot(st)[i] - ref[2 + i])));
      worst_naive = fmax(worst_naive, fmax(fabs(nv[i] - ref[i]), fabs(nv[2 + i] - ref[2 + i])));
    }
  }
  // 1e5 steps, |y| ~ 5 (one ulp 8.9e-16): the compensated update stays within a few ulps
  // (measured <= 4.4e-16); the uncompensated (h/6) * (...) update of the previous code drifts
  // to ~1e-13 (measured 7.7e-14)
  CHECK_MSG(worst <= 3e-15, "RK4 round-off after 1e5 steps: %.3g", worst);
  CHECK_MSG(worst_naive > 1e-14, "naive summation gives only %.3g: the bound cannot tell",
            worst_naive);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  // Bulirsch-Stoer at tolerance 1e-12 on SICM's oscillator at t = 10 (was 2.2e-13 before
  // the increments were extrapolated and summed with compensation; SICM's BS: 1.3e-14)
  osc_par s = {2.0, 1.0, 0.0};
  sys = make_oscillator(&s, 0);
  CHECK_OK(dal_state_create(sys, &st));
  const double qs[2] = {1, 2}, vs[2] = {3, 4}, w = sqrt(0.5);
  dal_solve_opts op = dal_default_solve_opts();
  op.method = DAL_METHOD_BS;
  op.rtol = op.atol = 1e-12;
  CHECK_OK(dal_state_set(sys, st, 0.0, qs, vs));
  CHECK_OK(dal_advance(sys, st, &op, 10.0));
  double err = 0.0;
  for (int i = 0; i < 2; ++i) {
    double q = qs[i] * cos(w * 10) + vs[i] / w * sin(w * 10);
    double v = -qs[i] * w * sin(w * 10) + vs[i] * cos(w * 10);
    err = fmax(err, fmax(fabs(dal_state_q(st)[i] - q), fabs(dal_state_qdot(st)[i] - v)));
  }
  CHECK_MSG(err <= 5e-14, "BS at 1e-12 on SICM's oscillator: error %.3g at t = 10", err);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

int main(void) {
  test_discrete_maps();
  test_orders();
  test_rheonomic();
  test_symplecticity();
  test_noether();
  test_bounded_energy();
  test_rattle_residuals();
  test_outputs();
  test_failures();
  test_stiff();
  test_compensated();
  return check_summary("test_symplectic");
}
