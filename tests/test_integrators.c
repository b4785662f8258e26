// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Integrators against closed forms: tolerance honesty, convergence orders, evolve, failures.
//
// References: the large-amplitude pendulum by Jacobi elliptic functions (ref_elliptic.h,
// itself checked against A&S and the ODE by finite differences), the 2D harmonic oscillator
// in closed form, Richardson order estimates from fixed-step runs (no reference needed), and
// a chirp whose frequency 1/(1 - t) diverges at t = 1, where every integrator must stop.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "ref_elliptic.h"
#include "scenes.h"

#define PI 3.14159265358979323846
#define G 9.8

static const dal_method adaptive[] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_BS,
                                      DAL_METHOD_ADAMS, DAL_METHOD_BDF};
#define NADAPT 5

// ---------------------------------------------------------------------------------------------
// systems

// simple pendulum, l = 1, g = 9.8: theta'' = -g sin theta
static dal_system *make_pendulum(void) {
  scn_knobs k = scn_default();
  k.g = G;
  dal_system *sys = scn_pendulum(&k);
  CHECK(sys != NULL);
  return sys;
}

// U = k/2 |q|^2 with k = 1
static int spring_pot(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  *U = dal_scale(dal_add(dal_sq(q[0]), dal_sq(q[1])), 0.5);
  return 0;
}

// an optional extra callback on the oscillator (domain checks, failures)
typedef struct osc_cb {
  int mode; // 0 none, 1 recoverable outside the energy shell, 2 stop after t_fail
  double E0, tfail;
  long fails, calls;
} osc_cb;

static int osc_force(double t, const double *q, const double *qd, double *Q, void *ctx) {
  (void)Q;
  osc_cb *c = ctx;
  c->calls++;
  if (c->mode == 1) {
    double E = (qd[0] * qd[0] + qd[1] * qd[1]) + 0.5 * (q[0] * q[0] + q[1] * q[1]);
    if (E > 1.001 * c->E0) {
      c->fails++;
      return 1;
    }
  } else if (c->mode == 2 && t > c->tfail) {
    c->fails++;
    return -1;
  }
  return 0;
}

// SICM's oscillator: particle of mass 2 in the plane, k = 1
static dal_system *make_oscillator(osc_cb *cb) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  int c[2], p;
  int rc = dal_builder_create(2, &b);
  if (!rc) rc = dal_builder_add_coord(b, "x", &c[0]);
  if (!rc) rc = dal_builder_add_coord(b, "y", &c[1]);
  if (!rc) rc = dal_builder_add_particle(b, "m", 2.0, &p);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_cartesian2;
  pd.coords = c;
  pd.ncoords = 2;
  if (!rc) rc = dal_builder_place_def(b, p, &pd);
  if (!rc) rc = dal_builder_add_potential_q(b, spring_pot, NULL);
  if (!rc && cb) rc = dal_builder_add_genforce(b, osc_force, cb);
  if (!rc) rc = dal_builder_compile(b, &sys);
  CHECK_OK(rc);
  dal_builder_destroy(b);
  return sys;
}

static const double osc_q0[2] = {1, 2}, osc_v0[2] = {3, 4};

// closed form: q = q0 cos(w t) + v0/w sin(w t), w = sqrt(k/m)
static void osc_exact(double t, double *y) {
  double w = sqrt(0.5);
  for (int i = 0; i < 2; ++i) {
    y[i] = osc_q0[i] * cos(w * t) + osc_v0[i] / w * sin(w * t);
    y[2 + i] = -osc_q0[i] * w * sin(w * t) + osc_v0[i] * cos(w * t);
  }
}

// x'' = -x / (1 - t)^2, y'' = 0: x stays bounded (|x| <= 1) but oscillates ever faster,
// infinitely often before t = 1; no step size resolves it once 1 - t nears rounding of t
static int chirp_force(double t, const double *q, const double *qd, double *Q, void *ctx) {
  (void)qd;
  (void)ctx;
  double w = 1.0 / fmax(fabs(1.0 - t), 1e-150);
  Q[0] -= w * w * q[0];
  return 0;
}

static dal_system *make_chirp(void) {
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  int c[2], p;
  int rc = dal_builder_create(2, &b);
  if (!rc) rc = dal_builder_add_coord(b, "x", &c[0]);
  if (!rc) rc = dal_builder_add_coord(b, "y", &c[1]);
  if (!rc) rc = dal_builder_add_particle(b, "m", 1.0, &p);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_cartesian2;
  pd.coords = c;
  pd.ncoords = 2;
  if (!rc) rc = dal_builder_place_def(b, p, &pd);
  if (!rc) rc = dal_builder_add_genforce(b, chirp_force, NULL);
  if (!rc) rc = dal_builder_compile(b, &sys);
  CHECK_OK(rc);
  dal_builder_destroy(b);
  return sys;
}

// a run to t1 from the problem's initial state; returns rc, fills y (2n) and stats
typedef struct run_out {
  int rc;
  double t, y[4];
  dal_stats s;
} run_out;

static run_out run(const dal_system *sys, const double *q0, const double *v0,
                   const dal_solve_opts *o, double t1) {
  run_out r;
  memset(&r, 0, sizeof r);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  int n = dal_system_ncoords(sys);
  CHECK_OK(dal_state_set(sys, st, 0.0, q0, v0));
  r.rc = dal_advance(sys, st, o, t1);
  r.t = dal_state_time(st);
  for (int i = 0; i < n; ++i) {
    r.y[i] = dal_state_q(st)[i];
    r.y[n + i] = dal_state_qdot(st)[i];
  }
  dal_state_stats(st, &r.s);
  if (r.rc) printf("  run failed (%d): %s\n", r.rc, dal_state_errmsg(st));
  dal_state_destroy(st);
  return r;
}

// max |y - ref| / max(1, max |ref|)
static double rel_err(const double *y, const double *ref, int ny) {
  double e = 0, s = 1;
  for (int i = 0; i < ny; ++i) {
    e = fmax(e, fabs(y[i] - ref[i]));
    s = fmax(s, fabs(ref[i]));
  }
  return e / s;
}

// ---------------------------------------------------------------------------------------------
// the elliptic reference itself

static void test_elliptic_reference(void) {
  // K(m = 1/2) = 1.854074677301371918... (Abramowitz & Stegun, Table 17.1)
  CHECK_CLOSE(ref_ellip_K(0.5), 1.8540746773013719, 2e-16);
  // K(0) = pi/2; sn(K | m) = 1, cn(K) = 0
  CHECK_CLOSE(ref_ellip_K(0.0), PI / 2, 1e-16);
  double sn, cn, dn;
  ref_ellip_sncndn(ref_ellip_K(0.7), 0.7, &sn, &cn, &dn);
  CHECK_CLOSE(sn, 1.0, 1e-15);
  CHECK_CLOSE(cn, 0.0, 1e-7); // cn near K: loses digits as sqrt(eps)
  // d/du sn = cn dn by central differences (oracle)
  for (double u = -3.0; u < 3.0; u += 0.37) {
    double h = 1e-5, sp, sm, c, d, s;
    ref_ellip_sncndn(u + h, 0.9, &sp, &c, &d);
    ref_ellip_sncndn(u - h, 0.9, &sm, &c, &d);
    ref_ellip_sncndn(u, 0.9, &s, &c, &d);
    CHECK_CLOSE((sp - sm) / (2 * h), c * d, 1e-9);
    CHECK_CLOSE(s * s + c * c, 1.0, 1e-15);
  }
  // the pendulum solution satisfies theta'' = -g sin theta and conserves energy, and is
  // periodic with period 4 K / w0; small amplitude: theta0 cos(w0 t)
  double w0 = sqrt(G);
  const double amps[3] = {60, 120, 170};
  for (int a = 0; a < 3; ++a) {
    double th0 = amps[a] * PI / 180, E0 = -G * cos(th0);
    for (double t = 0.1; t < 10; t += 0.731) {
      double h = 1e-4, thp, thm, th, thd, d;
      ref_pendulum(th0, w0, t + h, &thp, &d);
      ref_pendulum(th0, w0, t - h, &thm, &d);
      ref_pendulum(th0, w0, t, &th, &thd);
      CHECK_CLOSE((thp - 2 * th + thm) / (h * h), -G * sin(th), 2e-6);
      CHECK_CLOSE((thp - thm) / (2 * h), thd, 1e-7);
      CHECK_CLOSE(0.5 * thd * thd - G * cos(th), E0, 1e-13);
    }
    double k = sin(th0 / 2), T = 4 * ref_ellip_K(k * k) / w0, th, thd;
    ref_pendulum(th0, w0, 3 * T, &th, &thd);
    CHECK_CLOSE(th, th0, 1e-13);
  }
  double th, thd;
  ref_pendulum(1e-4, w0, 2.345, &th, &thd);
  CHECK_CLOSE(th, 1e-4 * cos(w0 * 2.345), 1e-12);
}

// ---------------------------------------------------------------------------------------------
// tolerance honesty

static void test_tolerance_honesty(void) {
  dal_system *pend = make_pendulum(), *osc = make_oscillator(NULL);
  double w0 = sqrt(G), T = 10.0;
  printf("tolerance honesty: max (global error at t=10) / rtol over rtol = 1e-4..1e-12\n");
  for (int mi = 0; mi < NADAPT; ++mi) {
    double worst = 0;
    for (int p = 0; p < 4; ++p) {
      const dal_system *sys = p < 3 ? pend : osc;
      double th0 = (p == 0 ? 60 : p == 1 ? 120 : 170) * PI / 180;
      double ref[4], q0 = th0, v0 = 0;
      int ny = p < 3 ? 2 : 4;
      if (p < 3)
        ref_pendulum(th0, w0, T, &ref[0], &ref[1]);
      else
        osc_exact(T, ref);
      double prev = INFINITY;
      for (int e = 4; e <= 12; e += 2) {
        dal_solve_opts o = dal_default_solve_opts();
        o.method = adaptive[mi];
        o.rtol = o.atol = pow(10.0, -e);
        run_out r = p < 3 ? run(sys, &q0, &v0, &o, T) : run(sys, osc_q0, osc_v0, &o, T);
        CHECK_OK(r.rc);
        double err = rel_err(r.y, ref, ny), f = err / o.rtol;
        worst = fmax(worst, f);
        CHECK_MSG(f <= 100, "%s problem %d rtol 1e-%d: error %.3g = %.1f x rtol",
                  dal_method_name(o.method), p, e, err, f);
        // the error decreases with the tolerance (until it reaches rounding)
        CHECK_MSG(err < prev || err < 1e-13, "%s problem %d rtol 1e-%d: error %.3g >= %.3g",
                  dal_method_name(o.method), p, e, err, prev);
        prev = err;
      }
    }
    printf("  %-10s worst factor %6.2f\n", dal_method_name(adaptive[mi]), worst);
  }
  // the same through evolve with outputs every 0.1 (steps land on each output time)
  for (int mi = 0; mi < NADAPT; ++mi) {
    double th0 = 120 * PI / 180, ref[2];
    ref_pendulum(th0, w0, T, &ref[0], &ref[1]);
    for (int e = 5; e <= 11; e += 3) {
      dal_state *st = NULL;
      CHECK_OK(dal_state_create(pend, &st));
      double q0 = th0, v0 = 0;
      CHECK_OK(dal_state_set(pend, st, 0, &q0, &v0));
      dal_solve_opts o = dal_default_solve_opts();
      o.method = adaptive[mi];
      o.rtol = o.atol = pow(10.0, -e);
      CHECK_OK(dal_evolve(pend, st, &o, T, 0.1, NULL, NULL));
      double y[2] = {dal_state_q(st)[0], dal_state_qdot(st)[0]};
      double f = rel_err(y, ref, 2) / o.rtol;
      CHECK_MSG(f <= 100, "evolve %s rtol 1e-%d: %.1f x rtol", dal_method_name(o.method), e, f);
      dal_state_destroy(st);
    }
  }
  dal_system_destroy(pend);
  dal_system_destroy(osc);
}

// ---------------------------------------------------------------------------------------------
// convergence orders at fixed steps

// Richardson estimate of the order from runs at h, h/2, h/4 (no reference needed)
static double richardson_order(const dal_system *sys, const double *q0, const double *v0,
                               dal_method m, double h, double T) {
  double y[3][4];
  int ny = 2 * dal_system_ncoords(sys);
  for (int i = 0; i < 3; ++i) {
    dal_solve_opts o = dal_default_solve_opts();
    o.method = m;
    o.fixed_erk = 1;
    o.fixed_step = h / (1 << i);
    run_out r = run(sys, q0, v0, &o, T);
    CHECK_OK(r.rc);
    memcpy(y[i], r.y, sizeof y[i]);
  }
  double d1 = 0, d2 = 0;
  for (int i = 0; i < ny; ++i) {
    d1 = fmax(d1, fabs(y[0][i] - y[1][i]));
    d2 = fmax(d2, fabs(y[1][i] - y[2][i]));
  }
  return log2(d1 / d2);
}

static void test_orders(void) {
  dal_system *pend = make_pendulum(), *osc = make_oscillator(NULL);
  double th0 = 120 * PI / 180, v0 = 0;
  // every offered explicit RK table shows its order on the nonlinear pendulum
  double p5 = richardson_order(pend, &th0, &v0, DAL_METHOD_DOPRI5, 0.025, 2.0);
  double p8 = richardson_order(pend, &th0, &v0, DAL_METHOD_FEHLBERG78, 0.4, 2.0);
  double p4 = richardson_order(pend, &th0, &v0, DAL_METHOD_RK4, 0.1, 2.0);
  printf("fixed-step orders on the 120 deg pendulum: dopri5 %.2f, fehlberg78 %.2f, rk4 %.2f\n", p5,
         p8, p4);
  CHECK_MSG(fabs(p5 - 5) < 0.5, "dopri5 order %.2f", p5);
  CHECK_MSG(fabs(p8 - 8) < 0.6, "fehlberg78 order %.2f", p8);
  CHECK_MSG(fabs(p4 - 4) < 0.5, "rk4 order %.2f", p4);
  // RK4: error ratio ~16 when the step halves, against the oscillator's closed form
  double ref[4], e[3];
  osc_exact(10.0, ref);
  for (int i = 0; i < 3; ++i) {
    dal_solve_opts o = dal_default_solve_opts();
    o.method = DAL_METHOD_RK4;
    o.fixed_step = 0.1 / (1 << i);
    run_out r = run(osc, osc_q0, osc_v0, &o, 10.0);
    CHECK_OK(r.rc);
    CHECK(r.s.steps == 100L << i);
    CHECK(r.s.rhs_evals == 4 * (100L << i));
    e[i] = rel_err(r.y, ref, 4);
  }
  printf("rk4 on the oscillator: error ratios %.2f %.2f when the step halves\n", e[0] / e[1],
         e[1] / e[2]);
  CHECK(e[0] / e[1] > 15 && e[0] / e[1] < 17);
  CHECK(e[1] / e[2] > 15 && e[1] / e[2] < 17);
  dal_system_destroy(pend);
  dal_system_destroy(osc);
}

// Bulirsch-Stoer reaches 1e-12 on the oscillator with fewer evaluations than DOPRI5
static void test_bs_vs_dopri(void) {
  dal_system *osc = make_oscillator(NULL);
  double ref[4];
  osc_exact(10.0, ref);
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = o.atol = 1e-12;
  o.method = DAL_METHOD_BS;
  run_out bs = run(osc, osc_q0, osc_v0, &o, 10.0);
  o.method = DAL_METHOD_DOPRI5;
  run_out dp = run(osc, osc_q0, osc_v0, &o, 10.0);
  double ebs = rel_err(bs.y, ref, 4), edp = rel_err(dp.y, ref, 4);
  printf("oscillator at 1e-12: bs error %.2e with %ld evaluations, dopri5 %.2e with %ld\n", ebs,
         bs.s.rhs_evals, edp, dp.s.rhs_evals);
  CHECK(ebs <= 1e-12);
  CHECK(edp <= 1e-11);
  CHECK(bs.s.rhs_evals < dp.s.rhs_evals);
  dal_system_destroy(osc);
}

// ---------------------------------------------------------------------------------------------
// evolve and its monitor

typedef struct mon_rec {
  int n, stop_at;
  double t[64], err;
} mon_rec;

static int record(const dal_system *sys, const dal_state *st, void *ctx) {
  mon_rec *m = ctx;
  double y[4], ex[4];
  if (m->n < 64) m->t[m->n] = dal_state_time(st);
  m->n++;
  // the monitor sees the solution at its time, evaluated there (qddot = -q / 2)
  osc_exact(dal_state_time(st), ex);
  for (int i = 0; i < 2; ++i) {
    y[i] = dal_state_q(st)[i];
    y[2 + i] = dal_state_qdot(st)[i];
    CHECK_CLOSE(dal_state_qddot(st)[i], -0.5 * y[i], 1e-14);
  }
  m->err = fmax(m->err, rel_err(y, ex, 4));
  (void)sys;
  if (m->stop_at && m->n == m->stop_at) return 1;
  return 0;
}

static int failing_monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  (void)ctx;
  return dal_state_time(st) > 0.5 ? -7 : 0;
}

static void test_evolve(void) {
  dal_system *osc = make_oscillator(NULL);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(osc, &st));
  const dal_method ms[6] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_BS,
                            DAL_METHOD_ADAMS,  DAL_METHOD_BDF,        DAL_METHOD_RK4};
  for (int mi = 0; mi < 6; ++mi) {
    // outputs at exactly t0 + k dt, then at t1; the solution there is accurate
    double qa[2], va[2], ex[4];
    osc_exact(0.3, ex);
    memcpy(qa, ex, sizeof qa);
    memcpy(va, ex + 2, sizeof va);
    CHECK_OK(dal_state_set(osc, st, 0.3, qa, va));
    dal_solve_opts o = dal_default_solve_opts();
    o.method = ms[mi];
    o.rtol = o.atol = 1e-9;
    o.fixed_step = 1e-3;
    mon_rec m;
    memset(&m, 0, sizeof m);
    CHECK_OK(dal_evolve(osc, st, &o, 1.05, 0.1, record, &m));
    CHECK(m.n == 9);
    for (int k = 0; k < 8 && k < m.n; ++k)
      CHECK_MSG(m.t[k] == 0.3 + (double)k * 0.1, "%s output %d at %.17g", dal_method_name(o.method),
                k, m.t[k]);
    CHECK(m.n < 9 || m.t[8] == 1.05);
    CHECK_MSG(m.err < 1e-7, "%s monitor error %.3g", dal_method_name(o.method), m.err);
    // a positive monitor return stops evolve where it stood, with DAL_STOPPED (not an error)
    CHECK_OK(dal_state_set(osc, st, 0.0, osc_q0, osc_v0));
    memset(&m, 0, sizeof m);
    m.stop_at = 4;
    CHECK(dal_evolve(osc, st, &o, 5.0, 0.25, record, &m) == DAL_STOPPED);
    CHECK(m.n == 4 && dal_state_time(st) == 0.75);
  }
  // a negative monitor return is a callback failure naming the time
  dal_solve_opts o = dal_default_solve_opts();
  CHECK_OK(dal_state_set(osc, st, 0.0, osc_q0, osc_v0));
  int rc = dal_evolve(osc, st, &o, 2.0, 0.25, failing_monitor, NULL);
  CHECK(rc == DAL_E_CALLBACK);
  CHECK(dal_state_time(st) == 0.75);
  CHECK(strstr(dal_state_errmsg(st), "monitor returned -7") != NULL);
  // dt that does not divide the interval: the last output is t1 itself
  mon_rec m;
  memset(&m, 0, sizeof m);
  CHECK_OK(dal_state_set(osc, st, 0.0, osc_q0, osc_v0));
  CHECK_OK(dal_evolve(osc, st, &o, 0.3, 0.1, record, &m));
  CHECK(m.n == 4 && m.t[3] == 0.3);
  dal_state_destroy(st);
  dal_system_destroy(osc);
}

// ---------------------------------------------------------------------------------------------
// callback failures

static void test_recoverable(void) {
  osc_cb cb = {1, 0, 0, 0, 0};
  cb.E0 = (osc_v0[0] * osc_v0[0] + osc_v0[1] * osc_v0[1]) +
          0.5 * (osc_q0[0] * osc_q0[0] + osc_q0[1] * osc_q0[1]);
  dal_system *osc = make_oscillator(&cb);
  double ref[4];
  osc_exact(10.0, ref);
  const dal_method ms[6] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_BS,
                            DAL_METHOD_ADAMS,  DAL_METHOD_BDF,        DAL_METHOD_RK4};
  for (int mi = 0; mi < 6; ++mi) {
    dal_solve_opts o = dal_default_solve_opts();
    o.method = ms[mi];
    o.rtol = o.atol = 1e-8;
    o.h0 = 3.0;         // a first step far too long: trial states leave the energy shell
    o.fixed_step = 1.0; // RK4: every full step has to be halved
    cb.fails = cb.calls = 0;
    run_out r = run(osc, osc_q0, osc_v0, &o, 10.0);
    CHECK_MSG(r.rc == 0, "%s: rc %d", dal_method_name(o.method), r.rc);
    CHECK_MSG(cb.fails > 0, "%s: the callback never refused a state", dal_method_name(o.method));
    CHECK_MSG(r.s.rejected > 0, "%s: no rejected step", dal_method_name(o.method));
    double err = rel_err(r.y, ref, 4);
    CHECK_MSG(err < (ms[mi] == DAL_METHOD_RK4 ? 1e-2 : 1e-6), "%s: error %.3g",
              dal_method_name(o.method), err);
  }
  dal_system_destroy(osc);
}

static void test_unrecoverable(void) {
  osc_cb cb = {2, 0, 3.3, 0, 0};
  dal_system *osc = make_oscillator(&cb);
  const dal_method ms[6] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_BS,
                            DAL_METHOD_ADAMS,  DAL_METHOD_BDF,        DAL_METHOD_RK4};
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(osc, &st));
  for (int mi = 0; mi < 6; ++mi) {
    dal_solve_opts o = dal_default_solve_opts();
    o.method = ms[mi];
    o.rtol = o.atol = 1e-10;
    o.fixed_step = 0.01;
    cb.mode = 2;
    CHECK_OK(dal_state_set(osc, st, 0.0, osc_q0, osc_v0));
    int rc = dal_advance(osc, st, &o, 10.0);
    double ts = dal_state_time(st);
    const char *msg = dal_state_errmsg(st);
    CHECK_MSG(rc == DAL_E_CALLBACK, "%s: rc %d", dal_method_name(o.method), rc);
    // (Bulirsch-Stoer's steps at this tolerance are 1.5 s long)
    CHECK_MSG(ts > (ms[mi] == DAL_METHOD_BS ? 1.5 : 2.0) && ts < 3.6, "%s: stopped at t=%g",
              dal_method_name(o.method), ts);
    CHECK(strstr(msg, "generalized force callback") != NULL);
    CHECK(strstr(msg, "last accepted step") != NULL);
    // the state is evaluated at the accepted step
    for (int i = 0; i < 2; ++i)
      CHECK_CLOSE(dal_state_qddot(st)[i], -0.5 * dal_state_q(st)[i], 1e-14);
    // and equals a reference run stopped at that time
    double y[4] = {dal_state_q(st)[0], dal_state_q(st)[1], dal_state_qdot(st)[0],
                   dal_state_qdot(st)[1]};
    cb.mode = 0;
    run_out r = run(osc, osc_q0, osc_v0, &o, ts);
    CHECK_OK(r.rc);
    double d = rel_err(y, r.y, 4);
    CHECK_MSG(d < (ms[mi] == DAL_METHOD_RK4 ? 1e-12 : 1e-8), "%s: state differs by %.3g",
              dal_method_name(o.method), d);
    // the next call restarts from there and goes on once the callback allows it
    CHECK_OK(dal_advance(osc, st, &o, 10.0));
    CHECK(dal_state_time(st) == 10.0);
  }
  dal_state_destroy(st);
  dal_system_destroy(osc);
}

// a singularity: step size collapse names time and the dominating coordinate
static void test_step_failure(void) {
  dal_system *sys = make_chirp();
  double q0[2] = {1, 0}, v0[2] = {0, 0};
  for (int mi = 0; mi < NADAPT; ++mi) {
    dal_state *st = NULL;
    CHECK_OK(dal_state_create(sys, &st));
    CHECK_OK(dal_state_set(sys, st, 0, q0, v0));
    dal_solve_opts o = dal_default_solve_opts();
    o.method = adaptive[mi];
    int rc = dal_advance(sys, st, &o, 2.0);
    const char *msg = dal_state_errmsg(st);
    CHECK_MSG(rc == DAL_E_STEP || rc == DAL_E_CONV || rc == DAL_E_MAXSTEPS, "%s: rc %d (%s)",
              dal_method_name(o.method), rc, msg);
    double t = dal_state_time(st), x = dal_state_q(st)[0];
    CHECK(t > 0.999 && t < 1.0);
    CHECK_MSG(strstr(msg, "'x'") != NULL && strstr(msg, "'y'") == NULL && strstr(msg, "t=") != NULL,
              "%s: %s", dal_method_name(o.method), msg);
    // the state is a point of the trajectory: bounded, and y untouched
    CHECK(fabs(x) <= 1.0 && dal_state_q(st)[1] == 0.0);
    CHECK_CLOSE(dal_state_qddot(st)[0], -x / ((1 - t) * (1 - t)), 1e-12);
    printf("  %-10s stops at t=%.9f: %.160s\n", dal_method_name(o.method), t, msg);
    dal_state_destroy(st);
  }
  dal_system_destroy(sys);
}

// ---------------------------------------------------------------------------------------------
// redundant coordinates, index-1 form: the ODE methods with projection onto the constraints

static void test_index1(void) {
  scn_knobs k = scn_default(); // the Cartesian pendulum of the scene library, g = G
  k.g = G;
  dal_system *sys = scn_cart_pendulum(&k);
  CHECK(sys != NULL);
  if (!sys) return;
  double th0 = 120 * PI / 180, ex, exd;
  ref_pendulum(th0, sqrt(G), 10.0, &ex, &exd);
  const dal_method ms[5] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_BS,
                            DAL_METHOD_ADAMS, DAL_METHOD_RK4};
  for (int mi = 0; mi < 5; ++mi) {
    double q0[2] = {sin(th0), -cos(th0)}, v0[2] = {0, 0}, drift[2];
    for (int proj = 0; proj < 2; ++proj) {
      dal_solve_opts o = dal_default_solve_opts();
      o.method = ms[mi];
      o.form = DAL_FORM_INDEX1;
      o.project = proj;
      o.rtol = o.atol = 1e-8;
      run_out r = run(sys, q0, v0, &o, 10.0);
      CHECK_OK(r.rc);
      // the bob's angle against the elliptic solution; the distance to the pivot
      double th = atan2(r.y[0], -r.y[1]);
      drift[proj] = fabs(hypot(r.y[0], r.y[1]) - 1.0);
      CHECK_MSG(fabs(th - ex) < 100 * o.rtol, "index1 %s project %d: theta error %.3g",
                dal_method_name(o.method), proj, th - ex);
      CHECK(proj ? r.s.projections == r.s.steps && r.s.steps > 0 : r.s.projections == 0);
    }
    CHECK_MSG(drift[1] < 1e-9 && (drift[0] < 1e-9 || drift[1] < drift[0]),
              "index1 %s: drift %.3g projected, %.3g not", dal_method_name(ms[mi]), drift[1],
              drift[0]);
  }
  dal_system_destroy(sys);
}

// ---------------------------------------------------------------------------------------------
// options, determinism, CSV

static void test_options(void) {
  dal_system *osc = make_oscillator(NULL);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(osc, &st));
  CHECK_OK(dal_state_set(osc, st, 0.0, osc_q0, osc_v0));
  dal_solve_opts o;
  memset(&o, 0, sizeof o);
  CHECK(dal_advance(osc, st, &o, 1.0) == DAL_E_ARG);
  CHECK(strstr(dal_state_errmsg(st), "dal_default_solve_opts") != NULL);
  CHECK(dal_advance(osc, st, NULL, 1.0) == DAL_E_ARG);
  struct {
    double *field;
    double bad;
    const char *name;
    int code;
  } cases[] = {{&o.rtol, 0.0, "rtol", DAL_E_ARG},
               {&o.rtol, NAN, "rtol", DAL_E_NONFINITE},
               {&o.atol, -1.0, "atol", DAL_E_ARG},
               {&o.atol, INFINITY, "atol", DAL_E_NONFINITE},
               {&o.fixed_step, 0.0, "fixed_step", DAL_E_ARG},
               {&o.hmax, -1.0, "hmax", DAL_E_ARG}};
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    o = dal_default_solve_opts();
    *cases[i].field = cases[i].bad;
    CHECK(dal_advance(osc, st, &o, 1.0) == cases[i].code);
    CHECK_MSG(strstr(dal_state_errmsg(st), cases[i].name) != NULL, "%s", dal_state_errmsg(st));
  }
  o = dal_default_solve_opts();
  o.method = (dal_method)42;
  CHECK(dal_advance(osc, st, &o, 1.0) == DAL_E_ARG);
  o = dal_default_solve_opts();
  CHECK(dal_advance(osc, st, &o, -1.0) == DAL_E_TIME);
  CHECK(strstr(dal_state_errmsg(st), "behind") != NULL);
  CHECK(dal_advance(osc, st, &o, NAN) == DAL_E_NONFINITE);
  CHECK(dal_evolve(osc, st, &o, 1.0, 0.0, NULL, NULL) == DAL_E_ARG);
  CHECK(dal_evolve(osc, st, &o, 1.0, -0.1, NULL, NULL) == DAL_E_ARG);
  CHECK(dal_state_time(st) == 0.0);
  // names
  CHECK(strcmp(dal_method_name(DAL_METHOD_BS), "bs") == 0);
  CHECK(strcmp(dal_method_name(DAL_METHOD_FEHLBERG78), "fehlberg78") == 0);
  CHECK(strcmp(dal_formulation_name(DAL_FORM_GGL), "ggl") == 0);
  // advancing to the current time evaluates the state there
  CHECK_OK(dal_advance(osc, st, &o, 0.0));
  CHECK_CLOSE(dal_state_qddot(st)[1], -1.0, 1e-15);
  // changing options between calls continues from the current state
  CHECK_OK(dal_advance(osc, st, &o, 1.0));
  o.method = DAL_METHOD_BS;
  CHECK_OK(dal_advance(osc, st, &o, 2.0));
  double ex[4],
      y[4] = {dal_state_q(st)[0], dal_state_q(st)[1], dal_state_qdot(st)[0], dal_state_qdot(st)[1]};
  osc_exact(2.0, ex);
  CHECK(rel_err(y, ex, 4) < 1e-6);
  // so does a state changed between calls (dal_state_set restarts the integrator)
  CHECK_OK(dal_state_set(osc, st, 0.0, osc_q0, osc_v0));
  CHECK_OK(dal_advance(osc, st, &o, 2.0));
  y[0] = dal_state_q(st)[0];
  CHECK_CLOSE(y[0], ex[0], 1e-6);
  dal_stats s;
  CHECK_OK(dal_state_stats(st, &s));
  CHECK(s.steps > 0 && s.rhs_evals > s.steps && s.last_h > 0);
  dal_state_destroy(st);
  dal_system_destroy(osc);
}

static void test_determinism(void) {
  dal_system *pend = make_pendulum();
  double th0 = 2.9, v0 = 0.1;
  for (int mi = 0; mi < NADAPT; ++mi) {
    dal_solve_opts o = dal_default_solve_opts();
    o.method = adaptive[mi];
    run_out a = run(pend, &th0, &v0, &o, 7.3), b = run(pend, &th0, &v0, &o, 7.3);
    CHECK(memcmp(a.y, b.y, sizeof a.y) == 0);
    CHECK(a.s.steps == b.s.steps && a.s.rhs_evals == b.s.rhs_evals);
  }
  dal_system_destroy(pend);
}

static void test_csv(void) {
  dal_system *pend = make_pendulum();
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(pend, &st));
  double th0 = 3.0, v0 = 3.0; // goes over the top: theta grows past pi
  CHECK_OK(dal_state_set(pend, st, 0, &th0, &v0));
  FILE *fp = tmpfile();
  CHECK(fp != NULL);
  if (!fp) return;
  dal_csv csv = {fp, 0, 1, NULL};
  dal_solve_opts o = dal_default_solve_opts();
  CHECK_OK(dal_evolve(pend, st, &o, 2.0, 0.5, dal_csv_monitor, &csv));
  double last_q = dal_state_q(st)[0];
  dal_energies en;
  dal_state_energies(st, &en);
  rewind(fp);
  char line[512];
  CHECK(fgets(line, sizeof line, fp) && strcmp(line, "t,theta,theta_dot,E,h\n") == 0);
  int rows = 0;
  double t = 0, q = 0, qd = 0, E = 0, h = 0;
  while (fgets(line, sizeof line, fp)) {
    CHECK(sscanf(line, "%lf,%lf,%lf,%lf,%lf", &t, &q, &qd, &E, &h) == 5);
    CHECK(q >= -PI && q < PI);
    ++rows;
  }
  CHECK(rows == 5 && t == 2.0);
  CHECK(last_q > PI); // the state itself is not wrapped
  CHECK_CLOSE(q, last_q - 2 * PI * floor((last_q + PI) / (2 * PI)), 1e-15);
  CHECK(qd == dal_state_qdot(st)[0] && E == en.E && h == en.h);
  fclose(fp);
  dal_state_destroy(st);
  dal_system_destroy(pend);
}

int main(void) {
  test_elliptic_reference();
  test_tolerance_honesty();
  test_orders();
  test_bs_vs_dopri();
  test_evolve();
  test_recoverable();
  test_unrecoverable();
  test_step_failure();
  test_index1();
  test_options();
  test_determinism();
  test_csv();
  return check_summary("test_integrators");
}
