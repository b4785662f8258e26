// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Lyapunov exponents against exact and independent references.
//
//  1. Linear dynamics (a trajectory resting at an equilibrium, whose tangent dynamics is the
//     linearization): the exponents are the real parts of the eigenvalues, known in closed
//     form (a rotating saddle: lambda^4 + (a + b + 4 w^2) lambda^2 + a b = 0; a damped
//     spring: -c/2m twice and 0 twice). Finite-time estimates carry a bias bounded by
//     (log of the eigenvector condition) / T, a few units over T.
//  2. The sum of all exponents is the time average of div f = -tr(M^-1 C): exactly -c/m for
//     the damped spring, and for a conservative scene in minimal coordinates
//     -(log det M(t_end) - log det M(t_a)) / (t_end - t_a) (Liouville: tr(M^-1 C) =
//     d/dt log det M). Both hold to the integration tolerance at any T.
//  3. A Hamiltonian (chaotic double pendulum): pairs +-lambda and a zero exponent (autonomous
//     flow direction), within the estimates' block errors plus a 2/T bias.
//  4. SICM's driven pendulum: the tangent vector equals the difference of two orbits started
//     1e-8 apart divided by 1e-8, both integrated by the library's RK4 at the same fixed step
//     (the RK step applied to the variational equations is the exact derivative of the
//     numerical flow), to the rounding of the difference and the orbits' O(|dy|)
//     nonlinearity; and the exponent over the time before the orbits separate equals the slope
//     of log |dtheta| of two Bulirsch-Stoer orbits (least squares) within 0.05, the
//     oscillation of log |dtheta| about its trend.
//  5. A quasi-periodic small-amplitude driven pendulum (drive off the parametric resonances):
//     lambda_1 <= (1 + log T) / T, and it decreases between T = 100 and 400 (a chaotic orbit's
//     does not).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

// a standard scene, checked as built
static dal_system *built(dal_system *sys) {
  CHECK(sys != NULL);
  return sys;
}

// vertically driven pendulum (l = 1, m = 1, g = 9.8), pivot y = a cos(w t)
static dal_system *driven(double a, double w) {
  scn_knobs k = scn_default();
  k.g = 9.8;
  k.ay = a;
  k.w = w;
  return built(scn_pendulum(&k));
}

static dal_system *double_pendulum(void) { return built(scn_double_pendulum(NULL)); }

// rotating frame r = Rot(w t) (x, y) and a trap U = (k1 x'^2 + k2 y'^2)/2 turning with it
typedef scn_trap trap;

static dal_system *rotating_trap(const trap *tr) { return built(scn_rotating_trap(tr, 1.0)); }

// run dal_lyapunov from (t0, q, qdot); returns its status
static int run(const dal_system *sys, dal_state *st, double t0, const double *q, const double *qd,
               dal_lyapunov_opts *o, double *ex, double *er) {
  CHECK_OK(dal_state_set(sys, st, t0, q, qd));
  int rc = dal_lyapunov(sys, st, o, ex, er, NULL, NULL);
  CHECK_MSG(rc == 0, "lyapunov: %s (%s)", dal_status_name(rc), dal_state_errmsg(st));
  return rc;
}

static void test_linear(void) {
  int fails0 = check_failures;
  double z[2] = {0, 0}, ex[4], er[4];
  dal_lyapunov_opts o = dal_default_lyapunov_opts();
  const double T = 200.0;
  o.t_end = T;
  // rotating saddle a b < 0: real pair +-sqrt(mu1) and an imaginary pair
  trap tr = {1.0, 3.0, 0.5};
  dal_system *sys = rotating_trap(&tr);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double a = tr.k1 - tr.w * tr.w, b = tr.k2 - tr.w * tr.w, B = a + b + 4 * tr.w * tr.w;
  double mu1 = (-B + sqrt(B * B - 4 * a * b)) / 2, l1 = sqrt(mu1);
  double ref[4] = {l1, 0, 0, -l1};
  if (!run(sys, st, 0.0, z, z, &o, ex, er)) {
    for (int i = 0; i < 4; ++i)
      CHECK_MSG(fabs(ex[i] - ref[i]) <= 4.0 / T, "saddle exponent %d: %.6f vs %.6f", i, ex[i],
                ref[i]);
    double s = ex[0] + ex[1] + ex[2] + ex[3];
    CHECK_MSG(fabs(s) <= 1e-8, "saddle: sum of exponents %.3g (div f = 0)", s);
    printf("  %-34s %.5f %.5f %.5f %.5f (exact %.5f 0 0 %.5f)\n", "rotating saddle", ex[0], ex[1],
           ex[2], ex[3], l1, -l1);
  }
  CHECK(dal_state_time(st) == T && dal_state_q(st)[0] == 0.0); // the state ends at t_end
  dal_state_destroy(st);
  dal_system_destroy(sys);
  // damped spring at rest: real parts 0, 0, -c/2m, -c/2m; the sum is exactly -c/m
  const double m = 0.7, k = 40.0, L = 0.5, c = 0.3, ell = L + m * 9.81 / k;
  scn_knobs kn = scn_default(); // hanging from a spring (k, rest L) with a damper c
  kn.m = m, kn.k = k, kn.l = L, kn.c = c;
  sys = built(scn_hanging_spring(&kn));
  CHECK_OK(dal_state_create(sys, &st));
  double q[2] = {0, -ell};
  if (!run(sys, st, 0.0, q, z, &o, ex, er)) {
    double r2[4] = {0, 0, -c / (2 * m), -c / (2 * m)};
    for (int i = 0; i < 4; ++i)
      CHECK_MSG(fabs(ex[i] - r2[i]) <= 4.0 / T, "damped spring exponent %d: %.6f vs %.6f", i, ex[i],
                r2[i]);
    double s = ex[0] + ex[1] + ex[2] + ex[3];
    CHECK_MSG(fabs(s + c / m) <= 1e-8, "damped spring: sum %.12f vs -c/m = %.12f", s, -c / m);
    printf("  %-34s %.5f %.5f %.5f %.5f (exact 0 0 %.5f %.5f)\n", "damped spring", ex[0], ex[1],
           ex[2], ex[3], -c / (2 * m), -c / (2 * m));
  }
  dal_state_destroy(st);
  dal_system_destroy(sys);
  printf("  %-34s %s\n", "linear: exponents = Re(eigenvalues)",
         check_failures > fails0 ? "FAILED" : "ok");
}

// log det M of a 2 x 2 mass matrix at the state (after dal_forward)
static double logdetM(const dal_state *st) {
  const double *M = dal_state_mass_matrix(st);
  return log(M[0] * M[3] - M[1] * M[2]);
}

static void test_hamiltonian(void) {
  int fails0 = check_failures;
  dal_system *sys = double_pendulum();
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q[2] = {2.0, 2.0}, z[2] = {0, 0}, ex[4], er[4];
  dal_lyapunov_opts o = dal_default_lyapunov_opts();
  o.t_end = 200.0;
  CHECK_OK(dal_state_set(sys, st, 0.0, q, z));
  CHECK_OK(dal_forward(sys, st));
  double ld0 = logdetM(st);
  if (!run(sys, st, 0.0, q, z, &o, ex, er)) {
    double T = o.t_end - o.transient, ld1 = logdetM(st), sum = ex[0] + ex[1] + ex[2] + ex[3];
    double liouville = -(ld1 - ld0) / T;
    printf("  %-34s %.4f(%.4f) %.4f(%.4f) %.4f(%.4f) %.4f(%.4f)\n", "double pendulum", ex[0], er[0],
           ex[1], er[1], ex[2], er[2], ex[3], er[3]);
    printf("  %-34s sum %.3e, Liouville -d(log det M)/T %.3e\n", "", sum, liouville);
    CHECK_MSG(fabs(sum - liouville) <= 1e-6, "sum %.9g vs Liouville %.9g", sum, liouville);
    // the errors are 95% half-widths (analysis.h)
    CHECK(ex[0] > 1.0 && er[0] < 0.2 * ex[0]);
    CHECK_MSG(fabs(ex[0] + ex[3]) <= hypot(er[0], er[3]) + 2.0 / T, "pair 1: %.4f %.4f", ex[0],
              ex[3]);
    CHECK_MSG(fabs(ex[1] + ex[2]) <= hypot(er[1], er[2]) + 2.0 / T, "pair 2: %.4f %.4f", ex[1],
              ex[2]);
    CHECK_MSG(fabs(ex[1]) <= er[1] + 2.0 / T, "zero exponent: %.4f +- %.4f", ex[1], er[1]);
  }
  dal_state_destroy(st);
  dal_system_destroy(sys);
  printf("  %-34s %s\n", "Hamiltonian: +-pairs, zero, sum",
         check_failures > fails0 ? "FAILED" : "ok");
}

// ---------------------------------------------------------------------------------------------
// SICM's driven pendulum: the tangent against two orbits

typedef struct track {
  int n;
  double t[4096], lg[4096];
} track;

// monitor: log |V(t)| = exponent * (t - t_a) for one vector started as a unit vector
static int record(double t, const double *ex, int nexp, void *ctx) {
  track *tk = ctx;
  (void)nexp;
  if (tk->n < 4096) {
    tk->t[tk->n] = t;
    tk->lg[tk->n] = ex[0] * t;
    tk->n++;
  }
  return 0;
}

// least-squares slope of y(x) over n points
static double slope(const double *x, const double *y, int n) {
  double mx = 0, my = 0, sxy = 0, sxx = 0;
  for (int i = 0; i < n; ++i)
    mx += x[i] / n, my += y[i] / n;
  for (int i = 0; i < n; ++i)
    sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
  return sxy / sxx;
}

static void test_driven(void) {
  int fails0 = check_failures;
  const double delta = 1e-10, w = 2 * sqrt(9.8);
  dal_system *sys = driven(0.1, w);
  dal_state *st = NULL, *s1 = NULL, *s2 = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_state_create(sys, &s1));
  CHECK_OK(dal_state_create(sys, &s2));
  double q = 1.0, z = 0.0, dz = delta, ex[2], y0[2] = {0.0, 1.0};
  static track tk;

  // (a) RK4 at h = 2^-8: tangent vector = (orbit 2 - orbit 1) / delta
  dal_lyapunov_opts o = dal_default_lyapunov_opts();
  o.method = DAL_METHOD_RK4;
  o.h = ldexp(1.0, -8);
  o.nexp = 1;
  o.y0 = y0;
  o.renorm = 1.0;
  o.t_end = 40.0;
  tk.n = 0;
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &z));
  int rc = dal_lyapunov(sys, st, &o, ex, NULL, record, &tk);
  CHECK_MSG(rc == 0, "driven RK4: %s", dal_state_errmsg(st));
  dal_solve_opts so = dal_default_solve_opts();
  so.method = DAL_METHOD_RK4;
  so.fixed_step = o.h;
  const double d8 = 1e-8; // a larger offset than the demo's: rounding matters less
  double dz8 = d8, ymax = 0.0, dmin = d8;
  CHECK_OK(dal_state_set(sys, s1, 0.0, &q, &z));
  CHECK_OK(dal_state_set(sys, s2, 0.0, &q, &dz8));
  double worst = 0.0;
  int compared = 0;
  for (int i = 0; i < tk.n; ++i) {
    CHECK_OK(dal_advance(sys, s1, &so, tk.t[i]));
    CHECK_OK(dal_advance(sys, s2, &so, tk.t[i]));
    double dq = dal_state_q(s2)[0] - dal_state_q(s1)[0];
    double dv = dal_state_qdot(s2)[0] - dal_state_qdot(s1)[0], dy = hypot(dq, dv);
    if (dy > 1e-5) break;
    // the two orbits' rounding (a few ulps of |y| per step, independent, amplified like dy:
    // relative to dy at most sqrt(steps) ulps of |y| over the smallest |dy| so far) and the
    // O(|dy|) nonlinearity of the difference
    ymax = fmax(ymax, fabs(dal_state_q(s1)[0]) + fabs(dal_state_qdot(s1)[0]));
    dmin = fmin(dmin, dy);
    double tol = 4 * 2.2e-16 * ymax * sqrt(tk.t[i] / o.h) / dmin + 100 * dy;
    double err = fabs(tk.lg[i] - log(dy / d8));
    worst = fmax(worst, err / tol);
    CHECK_MSG(err <= tol, "t=%g: log|V| %.12f vs log(|dy|/d) %.12f (tol %.2g)", tk.t[i], tk.lg[i],
              log(dy / d8), tol);
    ++compared;
  }
  CHECK_MSG(compared >= 20, "only %d times compared", compared);
  printf("  %-34s %d times, worst error / bound %.3f (bound at the end %.1e)\n",
         "RK4 tangent = orbit difference", compared, worst,
         4 * 2.2e-16 * ymax * sqrt(o.t_end / o.h) / dmin);

  // (b) Bulirsch-Stoer orbits 1e-10 apart: slope of log |dtheta| until they separate
  dal_solve_opts bs = dal_default_solve_opts();
  bs.method = DAL_METHOD_BS;
  bs.rtol = bs.atol = 1e-12;
  CHECK_OK(dal_state_set(sys, s1, 0.0, &q, &z));
  CHECK_OK(dal_state_set(sys, s2, 0.0, &q, &dz));
  static double ts[4096], ldth[4096];
  int np = 0;
  double tsep = 0.0;
  for (int i = 1; i < 4096; ++i) {
    double t = 0.25 * i;
    CHECK_OK(dal_advance(sys, s1, &bs, t));
    CHECK_OK(dal_advance(sys, s2, &bs, t));
    double dth = fabs(dal_state_q(s2)[0] - dal_state_q(s1)[0]);
    if (dth > 0.1) {
      tsep = t;
      break;
    }
    ts[np] = t;
    ldth[np++] = log(dth);
  }
  CHECK_MSG(tsep > 30, "orbits separate at t = %g", tsep);
  double sl = slope(ts, ldth, np);
  // the finite-time exponent of the same window from the same perturbation direction
  o.method = DAL_METHOD_DOPRI5;
  o.rtol = o.atol = 1e-12;
  o.t_end = ts[np - 1];
  o.renorm = 0.25;
  tk.n = 0;
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &z));
  rc = dal_lyapunov(sys, st, &o, ex, NULL, record, &tk);
  CHECK_MSG(rc == 0, "driven DOPRI5: %s", dal_state_errmsg(st));
  double slv = slope(tk.t, tk.lg, tk.n);
  CHECK_MSG(fabs(ex[0] - sl) <= 0.05, "finite-time exponent %.4f vs slope of log|dtheta| %.4f",
            ex[0], sl);
  CHECK_MSG(fabs(slv - sl) <= 0.05, "slope of log|V| %.4f vs slope of log|dtheta| %.4f", slv, sl);
  printf("  %-34s separate at t=%g: slope log|dtheta| %.4f, exponent over [0, %g] %.4f\n",
         "BS orbits 1e-10 apart", tsep, sl, o.t_end, ex[0]);
  dal_state_destroy(st);
  dal_state_destroy(s1);
  dal_state_destroy(s2);
  dal_system_destroy(sys);

  // (c) small amplitude, drive off the parametric resonances: quasi-periodic, lambda -> 0
  sys = driven(0.1, 2.5 * sqrt(9.8));
  CHECK_OK(dal_state_create(sys, &st));
  double q0 = 0.05, e100[2], e400[2];
  o = dal_default_lyapunov_opts();
  o.t_end = 100.0;
  run(sys, st, 0.0, &q0, &z, &o, e100, NULL);
  o.t_end = 400.0;
  run(sys, st, 0.0, &q0, &z, &o, e400, NULL);
  CHECK_MSG(e400[0] <= (1 + log(400.0)) / 400.0, "quasi-periodic lambda %.5f", e400[0]);
  CHECK_MSG(e400[0] < 0.7 * e100[0], "quasi-periodic lambda does not decay: %.5f -> %.5f", e100[0],
            e400[0]);
  CHECK(fabs(e400[0] + e400[1]) <= 1e-8);
  printf("  %-34s lambda_1(100) %.5f, lambda_1(400) %.5f (bound %.5f)\n", "quasi-periodic", e100[0],
         e400[0], (1 + log(400.0)) / 400.0);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  printf("  %-34s %s\n", "driven pendulum", check_failures > fails0 ? "FAILED" : "ok");
}

static void test_errors(void) {
  dal_system *sys = driven(0.1, 1.0);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q = 0.3, z = 0.0, ex[2];
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &z));
  dal_lyapunov_opts o = dal_default_lyapunov_opts();
  CHECK(dal_lyapunov(sys, st, &o, ex, NULL, NULL, NULL) == DAL_E_ARG); // t_end unset
  CHECK(strstr(dal_state_errmsg(st), "t_end") != NULL);
  o.t_end = 1.0;
  o.method = DAL_METHOD_VARIATIONAL; // a structure-preserving method: not for the tangent
  CHECK(dal_lyapunov(sys, st, &o, ex, NULL, NULL, NULL) == DAL_E_UNSUPPORTED);
  o.method = DAL_METHOD_DOPRI5;
  o.nexp = 3;
  CHECK(dal_lyapunov(sys, st, &o, ex, NULL, NULL, NULL) == DAL_E_ARG);
  o.nexp = 2;
  double dep[4] = {1, 0, 2, 0};
  o.y0 = dep;
  CHECK(dal_lyapunov(sys, st, &o, ex, NULL, NULL, NULL) == DAL_E_ARG);
  CHECK(strstr(dal_state_errmsg(st), "independent") != NULL);
  dep[2] = NAN;
  CHECK(dal_lyapunov(sys, st, &o, ex, NULL, NULL, NULL) == DAL_E_NONFINITE);
  CHECK(strstr(dal_state_errmsg(st), "y0[2]") != NULL);
  o.y0 = NULL;
  o.transient = 2.0;
  CHECK(dal_lyapunov(sys, st, &o, ex, NULL, NULL, NULL) == DAL_E_ARG);
  dal_lyapunov_opts bad = o;
  bad.cookie = 0;
  CHECK(dal_lyapunov(sys, st, &bad, ex, NULL, NULL, NULL) == DAL_E_ARG);
  CHECK(dal_state_time(st) == 0.0 && dal_state_q(st)[0] == q); // untouched by refusals
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// SICM's driven pendulum over 1000 s from seven nearby starts (theta0 = 1 + 0.001 k): the
// reported errors against the spread of the seven estimates, and the same Benettin loop written
// on dal_advance (two orbits 1e-8 apart, renormalized every second: an independent second
// route) with its CPU time. Before (private DOPRI5, errors = standard error of 10 block means):
// 0.146 ... 0.614 with errors 0.04 ... 0.08.
static double cpu_s(void) { return (double)clock() / CLOCKS_PER_SEC; }

static double advance_loop(const dal_system *sys, double th0, double T) {
  dal_state *a = NULL, *b = NULL;
  double d0 = 1e-8, z = 0, qb = th0 + d0, sum = 0;
  CHECK_OK(dal_state_create(sys, &a));
  CHECK_OK(dal_state_create(sys, &b));
  CHECK_OK(dal_state_set(sys, a, 0, &th0, &z));
  CHECK_OK(dal_state_set(sys, b, 0, &qb, &z));
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-10; // the Lyapunov default, the same automatic method (Adams)
  for (int k = 1; k <= (int)T; ++k) {
    CHECK_OK(dal_advance(sys, a, &o, k));
    CHECK_OK(dal_advance(sys, b, &o, k));
    double dq = dal_state_q(b)[0] - dal_state_q(a)[0];
    double dv = dal_state_qdot(b)[0] - dal_state_qdot(a)[0], d = hypot(dq, dv);
    sum += log(d / d0);
    double nq = dal_state_q(a)[0] + dq * d0 / d, nv = dal_state_qdot(a)[0] + dv * d0 / d;
    CHECK_OK(dal_state_set(sys, b, k, &nq, &nv));
  }
  dal_state_destroy(a);
  dal_state_destroy(b);
  return sum / T;
}

static int cmp_d(const void *x, const void *y) {
  double a = *(const double *)x, b = *(const double *)y;
  return (a > b) - (a < b);
}

static void test_sicm_seven(void) {
  dal_system *sys = driven(0.1, 2 * sqrt(9.8));
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  const double T = 1000.0;
  double lam[7], err[7], loop[7], cl = 0, ca = 0;
  printf("  SICM driven pendulum, 1000 s, seven starts (defaults: AUTO = Adams at rtol 1e-10)\n"
         "    theta0   lambda +- error (95%%)   dal_advance loop   CPU s: lyapunov / loop\n");
  for (int k = 0; k < 7; ++k) {
    double th0 = 1.0 + 1e-3 * k, z = 0.0;
    dal_lyapunov_opts o = dal_default_lyapunov_opts();
    o.t_end = T;
    o.nexp = 1;
    double c0 = cpu_s();
    if (run(sys, st, 0.0, &th0, &z, &o, &lam[k], &err[k])) break;
    double c1 = cpu_s();
    loop[k] = advance_loop(sys, th0, T);
    double c2 = cpu_s();
    cl += c1 - c0;
    ca += c2 - c1;
    printf("    %.3f    %.4f +- %.4f          %.4f             %.2f / %.2f\n", th0, lam[k], err[k],
           loop[k], c1 - c0, c2 - c1);
  }
  double mean = 0, var = 0, srt[7], esrt[7];
  for (int k = 0; k < 7; ++k)
    mean += lam[k] / 7;
  for (int k = 0; k < 7; ++k) {
    var += (lam[k] - mean) * (lam[k] - mean) / 6;
    srt[k] = lam[k];
    esrt[k] = err[k];
  }
  qsort(srt, 7, sizeof srt[0], cmp_d);
  qsort(esrt, 7, sizeof esrt[0], cmp_d);
  int cover = 0;
  for (int k = 0; k < 7; ++k)
    cover += fabs(lam[k] - srt[3]) <= err[k];
  printf("    spread: %.4f ... %.4f, standard deviation %.4f; reported errors %.4f ... %.4f "
         "(median %.4f); %d of 7 intervals hold the median %.4f; CPU %.1f s against %.1f s\n",
         srt[0], srt[6], sqrt(var), esrt[0], esrt[6], esrt[3], cover, srt[3], cl, ca);
  // the reported errors are of the size of the run-to-run scatter (before: 3 x smaller)
  CHECK_MSG(esrt[3] >= sqrt(var), "median error %.4f below the spread's deviation %.4f", esrt[3],
            sqrt(var));
  CHECK_MSG(cover >= 5, "%d of 7 intervals hold the median", cover);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

int main(void) {
  printf("Lyapunov exponents:\n");
  test_linear();
  test_hamiltonian();
  test_driven();
  test_errors();
  test_sicm_seven();
  return check_summary("test_analysis_lyapunov");
}
