// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The trustworthy core: what a tolerance buys in every method and formulation (against closed
// forms), no stall at tight tolerances, the minimal-coordinate route through IDA, and h only
// where it is the conserved energy function.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "ref_elliptic.h"
#include "scenes.h"

#define G0 SCN_G
#define PI 3.14159265358979323846

// minimal pendulum (l = 1), or the double pendulum (pendulum + hanging) when two is set
static dal_system *pendulum(int two) {
  return two ? scn_double_pendulum(NULL) : scn_pendulum(NULL);
}

// 2D isotropic oscillator: a unit mass on a zero-length spring (k = 1) to the origin
static dal_system *oscillator(void) { return scn_oscillator(NULL); }

static int pivot_path(dal_jet t, dal_jet *x, void *ctx) {
  (void)ctx;
  x[0] = dal_scale(dal_cos(dal_scale(t, 7.0)), 0.1);
  x[1] = dal_scale(dal_sin(dal_scale(t, 5.0)), 0.05);
  return 0;
}
static dal_moving_point pivot = {pivot_path, NULL};

// Cartesian pendulum (l = 1) on a fixed or moving pivot
static dal_system *cart_pendulum(int moving) {
  scn_knobs k = scn_default();
  k.pivot = moving ? &pivot : NULL;
  return scn_cart_pendulum(&k);
}

// Likharev's bead on a ring (R = 1) turning at w about the vertical
static dal_system *bead(double w) {
  scn_knobs k = scn_default();
  k.spin = w;
  return scn_bead(&k);
}

// Cartesian bead on the turning circle (three coordinates, two constraint rows)
static dal_system *cart_bead(double w) {
  scn_knobs k = scn_default();
  k.spin = w;
  return scn_cart_bead(&k);
}

// finding 1: minimal coordinates forced into IDA agree with Bulirsch-Stoer
static void test_minimal_in_ida(void) {
  dal_system *s = pendulum(1);
  dal_state *a = NULL, *b = NULL;
  CHECK_OK(dal_state_create(s, &a));
  CHECK_OK(dal_state_create(s, &b));
  double q[2] = {1.0, -0.5}, qd[2] = {0.0, 0.3}, tol = 1e-8;
  dal_formulation forms[2] = {DAL_FORM_GGL, DAL_FORM_INDEX3};
  CHECK_OK(dal_state_set(s, a, 0.0, q, qd));
  dal_solve_opts ob = scn_opts(DAL_FORM_AUTO, DAL_METHOD_BS, 1e-13);
  CHECK_OK(dal_advance(s, a, &ob, 2.0));
  for (int i = 0; i < 2; ++i) {
    CHECK_OK(dal_state_set(s, b, 0.0, q, qd));
    dal_solve_opts o = scn_opts(forms[i], DAL_METHOD_BDF, tol);
    CHECK_OK(dal_advance(s, b, &o, 2.0));
    double e = fmax(fabs(dal_state_q(a)[0] - dal_state_q(b)[0]),
                    fabs(dal_state_q(a)[1] - dal_state_q(b)[1]));
    printf("  double pendulum, minimal coordinates in IDA (%s): %.1e from BS (%.1f x rtol)\n",
           dal_formulation_name(forms[i]), e, e / tol);
    // (index-3 keeps only q in the error test: measured 30 x rtol here, exempt from 16 x)
    CHECK_MSG(e < (i ? 100 : 16) * tol, "%s: %g", dal_formulation_name(forms[i]), e);
  }
  dal_state_destroy(a);
  dal_state_destroy(b);
  dal_system_destroy(s);
}

// the error table: every method and formulation against closed forms, rtol 1e-4 ... 1e-12
static void test_tolerance_table(void) {
  dal_system *pend = pendulum(0), *osc = oscillator(), *cart = cart_pendulum(0);
  dal_state *sp = NULL, *so = NULL, *sc = NULL;
  CHECK_OK(dal_state_create(pend, &sp));
  CHECK_OK(dal_state_create(osc, &so));
  CHECK_OK(dal_state_create(cart, &sc));
  struct {
    const char *name;
    dal_formulation f;
    dal_method m;
    int project;
  } rows[] = {{"dopri5", DAL_FORM_ODE, DAL_METHOD_DOPRI5, 0},
              {"fehlberg78", DAL_FORM_ODE, DAL_METHOD_FEHLBERG78, 0},
              {"bs", DAL_FORM_ODE, DAL_METHOD_BS, 0},
              {"adams", DAL_FORM_ODE, DAL_METHOD_ADAMS, 0},
              {"bdf (cvode)", DAL_FORM_ODE, DAL_METHOD_BDF, 0},
              {"ggl (ida)", DAL_FORM_GGL, DAL_METHOD_BDF, 0},
              {"index1+proj bs", DAL_FORM_INDEX1, DAL_METHOD_BS, 1},
              {"auto (constrained)", DAL_FORM_AUTO, DAL_METHOD_AUTO, 0},
              {"index1+proj dopri5", DAL_FORM_INDEX1, DAL_METHOD_DOPRI5, 1}};
  double th0s[3] = {PI / 3, 2 * PI / 3, 170 * PI / 180}, T = 10.0;
  printf("  worst error at t = 10 / rtol (pendulum 60/120/170 deg vs elliptic, oscillator vs "
         "cos/sin; DAE rows: Cartesian pendulum)\n  %-20s",
         "method");
  for (int k = 4; k <= 12; ++k)
    printf(" 1e-%-3d", k);
  printf("\n");
  for (size_t r = 0; r < sizeof rows / sizeof rows[0]; ++r) {
    printf("  %-20s", rows[r].name);
    int dae = rows[r].f != DAL_FORM_ODE; // AUTO runs the Cartesian pendulum (constrained)
    for (int k = 4; k <= 12; ++k) {
      double tol = pow(10.0, -k), worst = 0.0;
      int bad = 0;
      dal_solve_opts o = scn_opts(rows[r].f, rows[r].m, tol);
      o.project = rows[r].project;
      for (int i = 0; i < 4; ++i) {
        double err;
        if (i < 3) {
          double th, thd, th0 = th0s[i];
          ref_pendulum(th0, sqrt(G0), T, &th, &thd);
          if (dae) {
            double q[2] = {sin(th0), -cos(th0)}, qd[2] = {0, 0};
            CHECK_OK(dal_state_set(cart, sc, 0.0, q, qd));
            bad |= dal_advance(cart, sc, &o, T) != 0;
            err = hypot(dal_state_q(sc)[0] - sin(th), dal_state_q(sc)[1] + cos(th));
          } else {
            double q = th0, qd = 0.0;
            CHECK_OK(dal_state_set(pend, sp, 0.0, &q, &qd));
            bad |= dal_advance(pend, sp, &o, T) != 0;
            err = fabs(dal_state_q(sp)[0] - th);
          }
        } else {
          if (dae) break;
          double q[2] = {1.0, 0.0}, qd[2] = {0.0, 0.5};
          CHECK_OK(dal_state_set(osc, so, 0.0, q, qd));
          bad |= dal_advance(osc, so, &o, T) != 0;
          err = hypot(dal_state_q(so)[0] - cos(T), dal_state_q(so)[1] - 0.5 * sin(T));
        }
        worst = fmax(worst, err / tol);
      }
      printf(" %6.1f", worst);
      CHECK_MSG(!bad, "%s at rtol %g failed", rows[r].name, tol);
      // IDA's clamp: below rtol 1e-11 it runs at its smallest local tolerance 1e-14,
      // reported in the statistics, and honours 16 x that (measured 3.2 x rtol at 1e-12)
      if (dae && rows[r].m == DAL_METHOD_BDF && 0.001 * tol < 1e-14) {
        dal_stats ss;
        dal_state_stats(sc, &ss);
        CHECK_MSG(ss.rtol_used > 0.005 * tol, "clamp not reported: %g", ss.rtol_used);
        CHECK_MSG(worst * tol < 16.0 * ss.rtol_used / 0.001, "%s at rtol %g: %g x rtol",
                  rows[r].name, tol, worst);
      } else if (!dae && rows[r].m == DAL_METHOD_BDF && tol < 1e-11) {
        // CVODE's BDF honours 1e-11 at most: a tighter request runs as 1e-11 (solve.h), and
        // the clamp shows in rtol_used (1e-15 instead of 1e-4 x rtol)
        dal_stats ss;
        dal_state_stats(so, &ss);
        CHECK_MSG(ss.rtol_used > 1e-4 * tol, "clamp not reported: %g", ss.rtol_used);
        CHECK_MSG(worst * tol < 16.0 * 1e-11, "%s at rtol %g: %g x rtol", rows[r].name, tol, worst);
      } else {
        CHECK_MSG(worst < 16.0, "%s at rtol %g: %g x rtol", rows[r].name, tol, worst);
      }
    }
    printf("\n");
  }
  dal_state_destroy(sp);
  dal_state_destroy(so);
  dal_state_destroy(sc);
  dal_system_destroy(pend);
  dal_system_destroy(osc);
  dal_system_destroy(cart);
}

// the bead's Jacobi integral over 1000 periods of the ring, every method
static void test_bead_invariant(void) {
  double w = 2.0 * sqrt(G0), T = 1000.0 * 2.0 * PI / w;
  dal_system *s = bead(w), *c = cart_bead(w);
  dal_state *st = NULL, *sc = NULL;
  CHECK_OK(dal_state_create(s, &st));
  CHECK_OK(dal_state_create(c, &sc));
  dal_method ms[5] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_BS, DAL_METHOD_ADAMS,
                      DAL_METHOD_BDF};
  printf(
      "  bead on the ring turning at w = 2 sqrt(g/R), 1000 periods: |h(T) - h(0)| / |h0| / rtol\n");
  for (int k = 6; k <= 10; k += 2) {
    double tol = pow(10.0, -k);
    printf("  rtol 1e-%d:", k);
    // (GGL at 1e-10 asks IDA for 1e-13, below its floor: clamped, and the 1000-period run
    // fails there; measured in the note of issue 10, left out here)
    for (int i = 0; i < (k < 10 ? 6 : 5); ++i) {
      double drift, h0;
      dal_energies e;
      if (i < 5) {
        double q = 0.3, qd = 0.0;
        CHECK_OK(dal_state_set(s, st, 0.0, &q, &qd));
        CHECK_OK(dal_forward(s, st));
        dal_state_energies(st, &e);
        h0 = e.h;
        dal_solve_opts o = scn_opts(DAL_FORM_ODE, ms[i], tol);
        o.max_steps = 100000000;
        CHECK_OK(dal_advance(s, st, &o, T));
        dal_state_energies(st, &e);
        drift = fabs(e.h - h0) / fabs(h0);
        printf(" %s %.1f", dal_method_name(ms[i]), drift / tol);
      } else {
        // the Cartesian bead in GGL: the Jacobi integral E - w L_z from the state itself
        double q[3] = {sin(0.3), 0.0, -cos(0.3)}, qd[3] = {0.0, w * sin(0.3), 0.0};
        CHECK_OK(dal_state_set(c, sc, 0.0, q, qd));
        dal_solve_opts o = scn_opts(DAL_FORM_GGL, DAL_METHOD_BDF, tol);
        o.max_steps = 100000000;
        double jac[2];
        for (int pass = 0; pass < 2; ++pass) {
          if (pass)
            CHECK_OK(dal_advance(c, sc, &o, T));
          else
            CHECK_OK(dal_forward(c, sc));
          const double *x = dal_state_q(sc), *v = dal_state_qdot(sc);
          double E = 0.5 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + G0 * x[2];
          jac[pass] = E - w * (x[0] * v[1] - x[1] * v[0]);
        }
        h0 = jac[0];
        drift = fabs(jac[1] - jac[0]) / fabs(h0);
        printf(" ggl %.1f", drift / tol);
      }
      CHECK_MSG(drift < 20.0 * tol, "method %d at rtol %g: drift %g", i, tol, drift);
    }
    printf("\n");
  }
  dal_state_destroy(st);
  dal_state_destroy(sc);
  dal_system_destroy(s);
  dal_system_destroy(c);
}

// finding 3: a sweep of 200 tolerances between 1e-14 and 1e-10 on the moving-pivot Cartesian
// pendulum either succeeds or refuses clearly, never stalls
static void test_no_stall(void) {
  dal_system *s = cart_pendulum(1);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(s, &st));
  int ok = 0, refused = 0, clamped = 0;
  clock_t c0 = clock();
  for (int i = 0; i < 200; ++i) {
    double tol = 1e-14 * pow(1e4, i / 199.0), q[2] = {0.6, -0.8}, qd[2] = {0.0, 0.0};
    CHECK_OK(dal_state_set(s, st, 0.0, q, qd));
    dal_solve_opts o = scn_opts(DAL_FORM_GGL, DAL_METHOD_BDF, tol);
    o.max_steps = 200000;
    int rc = dal_advance(s, st, &o, 2.0);
    dal_stats ss;
    dal_state_stats(st, &ss);
    if (rc == DAL_OK) {
      ok++;
      clamped += ss.rtol_used > 0.001 * tol * 1.0000001;
    } else {
      refused++;
      CHECK_MSG(rc == DAL_E_ARG, "rtol %g: %s (%s)", tol, dal_status_name(rc),
                dal_state_errmsg(st));
    }
  }
  double secs = (double)(clock() - c0) / CLOCKS_PER_SEC;
  printf("  moving pivot, 200 tolerances in [1e-14, 1e-10] to t = 2: %d ok (%d clamped to IDA's "
         "floor, reported in dal_stats.rtol_used), %d refused, %.1f s CPU\n",
         ok, clamped, refused, secs);
  CHECK(ok + refused == 200);
  dal_state_destroy(st);
  dal_system_destroy(s);
}

// ---------------------------------------------------------------------------------------------
// energy bookkeeping: E - W is an invariant in every formulation

static int wind(double t, const double *r, const double *v, double *F, void *ctx) {
  (void)r;
  (void)v;
  (void)ctx;
  F[0] += 0.3 * cos(2.0 * t); // a time-varying push on the bob (non-conservative)
  return 0;
}

static int drive_path(dal_jet t, dal_jet *x, void *ctx) {
  (void)ctx;
  x[0] = dal_scale(dal_cos(dal_scale(t, 3.0)), 0.2);
  x[1] = dal_scale(dal_sin(dal_scale(t, 2.0)), 0.1);
  return 0;
}
static dal_moving_point drive = {drive_path, NULL};

// a pendulum whose pivot moves (0.2 cos 3t, 0.1 sin 2t), damped towards a fixed point and
// pushed by a force callback: minimal (pendulum map with a moving pivot, a rheonomic map) or
// Cartesian (rod to a moving anchor, a rheonomic constraint)
static dal_system *forced_pendulum(int cartesian) {
  dal_builder *b = NULL;
  scn_knobs k = scn_default();
  int p, rc = scn_builder(&k, 2, &b);
  if (!cartesian) {
    // the built-in drive: pivot (ax cos(w t + ph), ay cos(w t + ph)); use the path through a
    // user map instead to match the Cartesian scene exactly
    k.ax = 0.2;
    k.w = 3.0;
    if (!rc) rc = scn_add_swing(b, &k, "bob", 1.0, -1, 1.0, "theta", &p);
  } else {
    k.pivot = &drive; // the rod to the moving point 0 + x(t)
    if (!rc) rc = scn_add_xy(b, "bob", 1.0, "x", "y", &p);
    if (!rc) rc = scn_add_rod(b, "rod", p, -1, 1.0, &k);
  }
  dal_damper_def dd = dal_default_damper_def();
  dd.a = p;
  dd.anchor[1] = -2.0; // at (0, -2)
  dd.c = 0.4;
  if (!rc) rc = dal_builder_add_damper_def(b, &dd);
  if (!rc) rc = dal_builder_add_force(b, wind, NULL);
  return scn_finish(b, rc);
}

// |E(T) - E(0) - W(T)| relative to the energies involved, over [0, T] at rtol tol
static double energy_balance(dal_system *s, const double *q, const double *qd, dal_solve_opts o,
                             double T, double *Wout) {
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(s, &st));
  CHECK_OK(dal_state_set(s, st, 0.0, q, qd));
  o.work = 1;
  dal_energies e0, e1;
  // a redundant start is first brought onto the constraints (that move changes E)
  if (dal_system_nconstraints(s)) CHECK_OK(dal_make_consistent(s, st, 0.0, NULL));
  CHECK_OK(dal_forward(s, st));
  dal_state_energies(st, &e0);
  CHECK(e0.W == 0.0);
  CHECK_OK(dal_advance(s, st, &o, T));
  dal_state_energies(st, &e1);
  double scale = fmax(1.0, fmax(fabs(e0.E), fabs(e1.W)));
  *Wout = e1.W;
  dal_state_destroy(st);
  return fabs(e1.E - e0.E - e1.W) / scale;
}

static void test_energy_bookkeeping(void) {
  double tol = 1e-9, T = 10.0, W;
  // minimal coordinates, moving pivot (map), damper, force callback: three ODE methods
  dal_system *m = forced_pendulum(0), *c = forced_pendulum(1);
  double th = 0.8, thd = 0.0;
  dal_method ms[3] = {DAL_METHOD_DOPRI5, DAL_METHOD_BS, DAL_METHOD_ADAMS};
  for (int i = 0; i < 3; ++i) {
    double e = energy_balance(m, &th, &thd, scn_opts(DAL_FORM_ODE, ms[i], tol), T, &W);
    printf("  forced pendulum, minimal, %s: W = %.6f, |dE - W| = %.1e (%.1f x rtol)\n",
           dal_method_name(ms[i]), W, e, e / tol);
    CHECK_MSG(e < 20 * tol, "%s: %g", dal_method_name(ms[i]), e);
    CHECK(fabs(W) > 0.1); // the drive, the damper and the push do work
  }
  // Cartesian coordinates, moving anchor (constraint power -lambda . phi_t): GGL in IDA and
  // index-1 with projection
  double q[2] = {sin(0.8), -cos(0.8)}, qd[2] = {0, 0};
  dal_solve_opts og = scn_opts(DAL_FORM_GGL, DAL_METHOD_BDF, tol);
  double e = energy_balance(c, q, qd, og, T, &W);
  printf("  forced pendulum, Cartesian, GGL: W = %.6f, |dE - W| = %.1e (%.1f x rtol)\n", W, e,
         e / tol);
  CHECK_MSG(e < 20 * tol, "ggl: %g", e);
  dal_solve_opts oi = scn_opts(DAL_FORM_INDEX1, DAL_METHOD_BS, tol);
  oi.project = 1;
  e = energy_balance(c, q, qd, oi, T, &W);
  printf("  forced pendulum, Cartesian, index-1 + projection (BS): |dE - W| = %.1e\n", e);
  CHECK_MSG(e < 20 * tol, "index1: %g", e);
  dal_system_destroy(m);
  dal_system_destroy(c);

  // the Cartesian bead on the turning circle: h is not its Jacobi integral (NaN), and the
  // work of the turning ring is w times the change of L_z (E - w L_z is conserved)
  double w = 2.0 * sqrt(G0);
  dal_system *cb = cart_bead(w);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(cb, &st));
  double qb[3] = {sin(0.3), 0.0, -cos(0.3)}, vb[3] = {0.0, w * sin(0.3), 0.0};
  CHECK_OK(dal_state_set(cb, st, 0.0, qb, vb));
  CHECK_OK(dal_forward(cb, st));
  dal_energies en;
  dal_state_energies(st, &en);
  CHECK_MSG(isnan(en.h), "h of a redundant rheonomic scene is %g, not NaN", en.h);
  double Lz0 = qb[0] * vb[1] - qb[1] * vb[0], E0 = en.E;
  dal_solve_opts ob = scn_opts(DAL_FORM_GGL, DAL_METHOD_BDF, tol);
  ob.work = 1;
  CHECK_OK(dal_advance(cb, st, &ob, 3.0));
  dal_state_energies(st, &en);
  const double *x = dal_state_q(st), *v = dal_state_qdot(st);
  double dLz = x[0] * v[1] - x[1] * v[0] - Lz0;
  printf("  Cartesian bead: W = %.9f, w dLz = %.9f, E - E0 = %.9f\n", en.W, w * dLz, en.E - E0);
  CHECK_MSG(fabs(en.W - w * dLz) < 20 * tol * fmax(1.0, fabs(en.W)), "W %g vs w dLz %g", en.W,
            w * dLz);
  CHECK(fabs(en.W) > 0.1);
  dal_state_destroy(st);
  dal_system_destroy(cb);
  // a scleronomic Cartesian scene keeps h = E
  dal_system *cp = cart_pendulum(0);
  CHECK_OK(dal_state_create(cp, &st));
  CHECK_OK(dal_state_set(cp, st, 0.0, q, qd));
  CHECK_OK(dal_forward(cp, st));
  dal_state_energies(st, &en);
  CHECK(en.h == en.E);
  dal_state_destroy(st);
  dal_system_destroy(cp);
}

int main(void) {
  test_energy_bookkeeping();
  test_no_stall();
  test_minimal_in_ida();
  test_tolerance_table();
  test_bead_invariant();
  return check_summary("test_core");
}
