// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The flow map's derivatives (dal_state_transition) against independent references:
//  - Phi(t1, t0) of a double pendulum in its angles against central differences of the flow
//    (oracle; Richardson-extrapolated, the flow by Bulirsch-Stoer at rtol 1e-13) to 1e-7;
//  - det Phi against Liouville: the flow preserves phase volume in (q, p), p = M qdot, so in
//    (q, qdot) det Phi = det M(t0) / det M(t1) for a conservative scene;
//  - dy(t1)/dp for a mass, a gravity component, a spring's k and L and a damper's c (a scene
//    with an anchored spring and damper) against central differences in the parameter;
//  - the Cartesian double pendulum (constraint rows): Phi z for z in the tangent space of the
//    manifold and dy/dp against central differences of the constrained flow (starts made
//    consistent, index-1 form with projection), to 1e-7;
//  - refusals: a primitive parameter, an implicit method.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

// double pendulum in angles (th1, th2), bob 1 on l1 about the origin, bob 2 on l2 from bob 1;
// with_links: an anchored spring on bob 2 and a damper from bob 1 to an anchor
static dal_system *dp_angles(int with_links) {
  dal_builder *b = NULL;
  int p[2], rc = scn_builder(NULL, 2, &b);
  if (!rc) rc = scn_add_swing(b, NULL, "b1", 1.3, -1, 0.9, "th1", &p[0]);
  if (!rc) rc = scn_add_swing(b, NULL, "b2", 0.7, p[0], 0.6, "th2", &p[1]);
  if (with_links) {
    dal_spring_def s = dal_default_spring_def();
    s.a = p[1];
    s.k = 14.0;
    s.length = 0.4;
    s.anchor[0] = 0.8;
    s.anchor[1] = -1.2;
    if (!rc) rc = dal_builder_add_spring_def(b, &s);
    dal_damper_def dm = dal_default_damper_def();
    dm.a = p[0];
    dm.c = 0.9;
    dm.anchor[0] = -0.7;
    dm.anchor[1] = -0.3;
    if (!rc) rc = dal_builder_add_damper_def(b, &dm);
  }
  return scn_finish(b, rc);
}

// the flow y(t1) from (t0, q, v) with the state's parameters, by BS at rtol 1e-13 (index-1
// form with projection when constrained)
static void flow(const dal_system *sys, dal_state *st, double t0, const double *q, const double *v,
                 double t1, double *y) {
  int n = dal_system_ncoords(sys);
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_BS;
  o.rtol = 1e-13;
  if (dal_system_nconstraints(sys) > 0) {
    o.form = DAL_FORM_INDEX1;
    o.project = 1;
  }
  CHECK_OK(dal_state_set(sys, st, t0, q, v));
  if (dal_system_nconstraints(sys) > 0) CHECK_OK(dal_make_consistent(sys, st, 1e-15, NULL));
  int rc = dal_advance(sys, st, &o, t1);
  CHECK_MSG(rc == 0, "advance: %s", dal_state_errmsg(st));
  memcpy(y, dal_state_q(st), (size_t)n * sizeof(double));
  memcpy(y + n, dal_state_qdot(st), (size_t)n * sizeof(double));
}

// central difference of the flow along z (2n), Richardson-extrapolated from h and h/2
static void flow_fd(const dal_system *sys, dal_state *st, double t0, const double *y0,
                    const double *z, double t1, double h, double *out) {
  int n = dal_system_ncoords(sys), n2 = 2 * n;
  double yp[16], ym[16], yy[16], d[2][16];
  for (int pass = 0; pass < 2; ++pass) {
    double hh = pass ? h / 2 : h;
    for (int i = 0; i < n2; ++i)
      yy[i] = y0[i] + hh * z[i];
    flow(sys, st, t0, yy, yy + n, t1, yp);
    for (int i = 0; i < n2; ++i)
      yy[i] = y0[i] - hh * z[i];
    flow(sys, st, t0, yy, yy + n, t1, ym);
    for (int i = 0; i < n2; ++i)
      d[pass][i] = (yp[i] - ym[i]) / (2 * hh);
  }
  for (int i = 0; i < n2; ++i)
    out[i] = (4 * d[1][i] - d[0][i]) / 3;
}

// the sensitivities S (np x n, row j: dy/dp_j at t1 from y0 at t = 0) against
// Richardson-extrapolated central differences of the flow in each parameter names[j], on the
// scratch state sp; each component to 1e-7 relative; returns the worst relative difference
static double param_fd(const dal_system *sys, dal_state *sp, int n, const double *y0, double t1,
                       int np, const char *const *names, const double *S) {
  double worst = 0.0;
  for (int j = 0; j < np; ++j) {
    dal_param_ref ref;
    double p0, d[2][8];
    CHECK_OK(dal_param_find(sys, names[j], &ref, NULL, 0));
    CHECK_OK(dal_system_param(sys, &ref, &p0));
    double h = 1e-4 * fmax(1.0, fabs(p0));
    for (int pass = 0; pass < 2; ++pass) {
      double hh = pass ? h / 2 : h, yp[8], ym[8];
      CHECK_OK(dal_state_set_param(sys, sp, &ref, p0 + hh));
      flow(sys, sp, 0.0, y0, y0 + n / 2, t1, yp);
      CHECK_OK(dal_state_set_param(sys, sp, &ref, p0 - hh));
      flow(sys, sp, 0.0, y0, y0 + n / 2, t1, ym);
      for (int i = 0; i < n; ++i)
        d[pass][i] = (yp[i] - ym[i]) / (2 * hh);
    }
    CHECK_OK(dal_state_reset_params(sys, sp));
    for (int i = 0; i < n; ++i) {
      double fd = (4 * d[1][i] - d[0][i]) / 3, e = fabs(S[j * n + i] - fd) / fmax(1.0, fabs(fd));
      worst = fmax(worst, e);
      CHECK_MSG(e <= 1e-7, "dy%d/d%s = %.12g, FD %.12g", i, names[j], S[j * n + i], fd);
    }
  }
  return worst;
}

static double det(int n, const double *A) {
  double a[64], dv = 1.0;
  memcpy(a, A, (size_t)n * n * sizeof(double));
  for (int k = 0; k < n; ++k) {
    int p = k;
    for (int i = k + 1; i < n; ++i)
      if (fabs(a[k * n + i]) > fabs(a[k * n + p])) p = i;
    if (p != k) {
      for (int j = 0; j < n; ++j) {
        double t = a[j * n + k];
        a[j * n + k] = a[j * n + p];
        a[j * n + p] = t;
      }
      dv = -dv;
    }
    dv *= a[k * n + k];
    for (int i = k + 1; i < n; ++i) {
      double f = a[k * n + i] / a[k * n + k];
      for (int j = k; j < n; ++j)
        a[j * n + i] -= f * a[j * n + k];
    }
  }
  return dv;
}

static void minimal_phi(void) {
  dal_system *sys = dp_angles(0);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  const double t1 = 1.5, y0[4] = {0.9, -0.5, 1.2, 0.4};
  CHECK_OK(dal_state_set(sys, st, 0.0, y0, y0 + 2));
  double M0[4], M1[4];
  CHECK_OK(dal_linearize(sys, st, M0, NULL, NULL));
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-12;
  double Phi[16];
  int rc = dal_state_transition(sys, st, &o, t1, Phi, 0, NULL, NULL);
  CHECK_MSG(rc == 0, "state_transition: %s", dal_state_errmsg(st));
  CHECK(dal_state_time(st) == t1);
  CHECK_OK(dal_linearize(sys, st, M1, NULL, NULL));
  double worst = 0.0;
  for (int j = 0; j < 4; ++j) {
    double z[4] = {0}, fd[4];
    z[j] = 1.0;
    flow_fd(sys, st, 0.0, y0, z, t1, 1e-4, fd);
    for (int i = 0; i < 4; ++i) {
      double e = fabs(Phi[j * 4 + i] - fd[i]) / fmax(1.0, fabs(fd[i]));
      worst = fmax(worst, e);
      CHECK_MSG(e <= 1e-7, "Phi[%d][%d] = %.12g, FD %.12g", i, j, Phi[j * 4 + i], fd[i]);
    }
  }
  double dP = det(4, Phi), lv = det(2, M0) / det(2, M1);
  printf("double pendulum (angles): Phi vs central differences worst %.3g; det Phi = %.15f, "
         "det M(t0)/det M(t1) = %.15f\n",
         worst, dP, lv);
  CHECK(fabs(dP - lv) <= 1e-9 * fabs(lv));
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

static void minimal_params(void) {
  dal_system *sys = dp_angles(1);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  const double t1 = 1.2, y0[4] = {0.6, -0.3, 0.8, 1.1};
  const char *names[5] = {"mass:b1", "gravity:1", "spring:0:k", "spring:0:L", "damper:0:c"};
  CHECK_OK(dal_state_set(sys, st, 0.0, y0, y0 + 2));
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-12;
  double Phi[16], S[20];
  int rc = dal_state_transition(sys, st, &o, t1, Phi, 5, names, S);
  CHECK_MSG(rc == 0, "state_transition: %s", dal_state_errmsg(st));
  dal_state *sp = NULL;
  CHECK_OK(dal_state_create(sys, &sp));
  double worst = param_fd(sys, sp, 4, y0, t1, 5, names, S);
  printf("sensitivities to mass, gravity, spring k and L, damper c: worst vs central differences "
         "%.3g\n",
         worst);
  // refusals
  const char *bad[1] = {"place:b1:0"};
  CHECK_OK(dal_state_set(sys, st, 0.0, y0, y0 + 2));
  CHECK(dal_state_transition(sys, st, NULL, 1.0, NULL, 1, bad, S) == DAL_E_UNSUPPORTED);
  CHECK(strstr(dal_state_errmsg(st), "place:b1:0") != NULL);
  o.method = DAL_METHOD_BDF;
  CHECK(dal_state_transition(sys, st, &o, 1.0, Phi, 0, NULL, NULL) == DAL_E_UNSUPPORTED);
  dal_state_destroy(sp);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// Cartesian double pendulum (p1 on a rod to the origin, p2 on a rod to p1)
static dal_system *dp_cartesian(void) {
  dal_builder *b = NULL;
  int p[2], rc = scn_builder(NULL, 2, &b);
  if (!rc) rc = scn_add_xy(b, "p1", 1.3, "x1", "y1", &p[0]);
  if (!rc) rc = scn_add_xy(b, "p2", 0.7, "x2", "y2", &p[1]);
  if (!rc) rc = scn_add_rod(b, "rod1", p[0], -1, 0.9, NULL);
  if (!rc) rc = scn_add_rod(b, "rod2", p[0], p[1], 0.6, NULL);
  return scn_finish(b, rc);
}

static void redundant_phi(void) {
  dal_system *sys = dp_cartesian();
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double a1 = 0.9, a2 = -0.5, w1 = 1.2, w2 = 0.4;
  double y0[8] = {0.9 * sin(a1),
                  -0.9 * cos(a1),
                  0.9 * sin(a1) + 0.6 * sin(a2),
                  -0.9 * cos(a1) - 0.6 * cos(a2),
                  0.9 * cos(a1) * w1,
                  0.9 * sin(a1) * w1,
                  0.9 * cos(a1) * w1 + 0.6 * cos(a2) * w2,
                  0.9 * sin(a1) * w1 + 0.6 * sin(a2) * w2};
  const double t1 = 1.5;
  // tangent directions of the state manifold: the angle variations mapped to (dq, dv)
  double Z[4][8];
  for (int j = 0; j < 4; ++j) {
    double da1 = j == 0, da2 = j == 1, dw1 = j == 2, dw2 = j == 3;
    double z[8] = {
        0.9 * cos(a1) * da1,
        0.9 * sin(a1) * da1,
        0.9 * cos(a1) * da1 + 0.6 * cos(a2) * da2,
        0.9 * sin(a1) * da1 + 0.6 * sin(a2) * da2,
        0.9 * (cos(a1) * dw1 - sin(a1) * w1 * da1),
        0.9 * (sin(a1) * dw1 + cos(a1) * w1 * da1),
        0.9 * (cos(a1) * dw1 - sin(a1) * w1 * da1) + 0.6 * (cos(a2) * dw2 - sin(a2) * w2 * da2),
        0.9 * (sin(a1) * dw1 + cos(a1) * w1 * da1) + 0.6 * (sin(a2) * dw2 + cos(a2) * w2 * da2)};
    memcpy(Z[j], z, sizeof z);
  }
  CHECK_OK(dal_state_set(sys, st, 0.0, y0, y0 + 4));
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-12;
  double Phi[64], S[16];
  const char *names[2] = {"mass:p2", "gravity:1"};
  int rc = dal_state_transition(sys, st, &o, t1, Phi, 2, names, S);
  CHECK_MSG(rc == 0, "state_transition: %s", dal_state_errmsg(st));
  double worst = 0.0;
  for (int j = 0; j < 4; ++j) {
    double fd[8], pz[8] = {0};
    flow_fd(sys, st, 0.0, y0, Z[j], t1, 1e-4, fd);
    for (int i = 0; i < 8; ++i)
      for (int l = 0; l < 8; ++l)
        pz[i] += Phi[l * 8 + i] * Z[j][l];
    for (int i = 0; i < 8; ++i) {
      double e = fabs(pz[i] - fd[i]) / fmax(1.0, fabs(fd[i]));
      worst = fmax(worst, e);
      CHECK_MSG(e <= 1e-7, "(Phi z%d)[%d] = %.12g, FD %.12g", j, i, pz[i], fd[i]);
    }
  }
  dal_state *sp = NULL;
  CHECK_OK(dal_state_create(sys, &sp));
  worst = fmax(worst, param_fd(sys, sp, 8, y0, t1, 2, names, S));
  printf("Cartesian double pendulum: Phi on the tangent space and dy/dp vs central differences "
         "of the constrained flow: worst %.3g\n",
         worst);
  dal_state_destroy(sp);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

int main(void) {
  minimal_phi();
  minimal_params();
  redundant_phi();
  printf("%d checks, %d failures\n", check_count, check_failures);
  return check_failures != 0;
}
