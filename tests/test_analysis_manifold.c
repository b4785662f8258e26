// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The analysis tools on the constraint manifold, each against an independent reference:
//  - Cartesian pendulum (x, y, rod): omega^2 = g/l (closed form) to 1e-12; equilibrium from an
//    inconsistent start and its rod tension m g (statics by hand);
//  - Cartesian double pendulum (four coordinates, two rods), equal masses and lengths:
//    omega^2 = (g/l)(2 -+ sqrt 2) to 1e-12; static tensions (m1 + m2) g and m2 g;
//  - the reduced linearization equals N' K_full N at a static equilibrium and the full-space
//    vector-field Jacobian against central differences of the KKT accelerations (oracle);
//  - the reduced linearization of the Cartesian pendulum at a moving state against the minimal
//    pendulum's -g cos(theta) / l (the basis carried along the motion);
//  - four-bar linkage (crank and rocker pivots fixed, particles at the two moving joints, three
//    rods): its one mode about the stable equilibrium against a model in the crank angle alone
//    written here by hand (coupler and rocker joint solved in closed form; U'' / M(theta)
//    by jets of that closed form), to 1e-10;
//  - bead on a circle turning at w as a Cartesian particle (dal_con_turning_circle): the
//    trivial branch's Omega^2 = g/R - w^2 and the pitchfork at w = sqrt(g/R) located by
//    continuation;
//  - the Lyapunov spectrum of the chaotic Cartesian double pendulum (2(n - m) = 4 exponents):
//    +- pairs and a zero sum (Hamiltonian), the largest against the same orbit in its angles
//    (the minimal-coordinate route) within the estimates' stated errors.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

static const double G0 = SCN_G;

// -------------------------------------------------------------------------------------------
// the Cartesian pendulum

static void cart_pendulum(void) {
  const double l = 1.3;
  scn_knobs k = scn_default();
  k.l = l;
  dal_system *sys = scn_cart_pendulum(&k);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q[2] = {0.0, -l}, v[2] = {0.0, 0.0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
  double w2[1], x[2], re[2], im[2];
  dal_modes md;
  int rc = dal_normal_modes(sys, st, w2, x, re, im, &md);
  CHECK_MSG(rc == 0, "modes: %s", dal_state_errmsg(st));
  printf("Cartesian pendulum: omega^2 = %.17g, g/l = %.17g, diff %.3g\n", w2[0], G0 / l,
         w2[0] - G0 / l);
  CHECK_CLOSE(w2[0], G0 / l, 1e-12);
  CHECK(md.verdict == DAL_NEUTRAL);
  // the shape is along the tangent of the circle (x), M-normalized (m = 1)
  CHECK_CLOSE(x[0], 1.0, 1e-12);
  CHECK_CLOSE(x[1], 0.0, 1e-12);
  CHECK_CLOSE(im[1], sqrt(G0 / l), 1e-12);
  CHECK_CLOSE(re[0], 0.0, 1e-12);

  // the equilibrium from an inconsistent start: the bob below the pivot, tension m g
  double q0[2] = {0.4, -0.9 * l};
  CHECK_OK(dal_state_set(sys, st, 0.0, q0, v));
  dal_equilibrium_report rep;
  rc = dal_equilibrium(sys, st, NULL, &rep);
  CHECK_MSG(rc == 0, "equilibrium: %s", dal_state_errmsg(st));
  const double *qs = dal_state_q(st), *lam = dal_state_lambda(st);
  printf("  equilibrium (%.3g, %.17g) in %d iterations, lambda = %.17g (-m g = %.17g)\n", qs[0],
         qs[1], rep.iterations, lam[0], -G0);
  CHECK_CLOSE(qs[0], 0.0, 1e-13);
  CHECK_CLOSE(qs[1], -l, 1e-13);
  CHECK_CLOSE(lam[0], -G0, 1e-12); // lambda = -T for a rod in tension T = m g
  CHECK(rep.accel <= 1e-12 && rep.unsteady == 0.0);
  // too few iterations: DAL_E_CONV with the residual in the message, the state at the iterate
  dal_equilibrium_opts few = dal_default_equilibrium_opts();
  few.max_iter = 1;
  CHECK_OK(dal_state_set(sys, st, 0.0, q0, v));
  rc = dal_equilibrium(sys, st, &few, NULL);
  CHECK(rc == DAL_E_CONV && strstr(dal_state_errmsg(st), "scaled residual") != NULL);
  // the inverted equilibrium: unstable, omega^2 = -g/l, compression -m g (lambda = +m g)
  double q1[2] = {0.2, 0.8 * l};
  CHECK_OK(dal_state_set(sys, st, 0.0, q1, v));
  CHECK_OK(dal_equilibrium(sys, st, NULL, NULL));
  CHECK_CLOSE(dal_state_q(st)[1], l, 1e-13);
  CHECK_CLOSE(dal_state_lambda(st)[0], G0, 1e-12);
  CHECK_OK(dal_normal_modes(sys, st, w2, NULL, NULL, NULL, &md));
  CHECK_CLOSE(w2[0], -G0 / l, 1e-12);
  CHECK(md.verdict == DAL_UNSTABLE);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// -------------------------------------------------------------------------------------------
// the Cartesian double pendulum: p1 on a rod of length l to the origin, p2 on a rod to p1

static dal_system *double_pendulum(double m1, double m2, double l1, double l2) {
  dal_builder *b = NULL;
  int p[2], rc = scn_builder(NULL, 2, &b);
  if (!rc) rc = scn_add_xy(b, "p1", m1, "x1", "y1", &p[0]);
  if (!rc) rc = scn_add_xy(b, "p2", m2, "x2", "y2", &p[1]);
  if (!rc) rc = scn_add_rod(b, "rod1", p[0], -1, l1, NULL);
  if (!rc) rc = scn_add_rod(b, "rod2", p[0], p[1], l2, NULL);
  return scn_finish(b, rc);
}

static void cart_double_pendulum(void) {
  const double l = 0.7, m = 1.9;
  dal_system *sys = double_pendulum(m, m, l, l);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q[4] = {0.1, -0.6, -0.2, -1.3}, v[4] = {0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
  int rc = dal_equilibrium(sys, st, NULL, NULL);
  CHECK_MSG(rc == 0, "equilibrium: %s", dal_state_errmsg(st));
  const double *qs = dal_state_q(st), *lam = dal_state_lambda(st);
  CHECK_CLOSE(qs[0], 0.0, 1e-13);
  CHECK_CLOSE(qs[1], -l, 1e-13);
  CHECK_CLOSE(qs[2], 0.0, 1e-13);
  CHECK_CLOSE(qs[3], -2 * l, 1e-13);
  // statics: the upper rod carries both bobs, the lower one the lower bob (lambda = -T)
  printf("Cartesian double pendulum: lambda = (%.17g, %.17g), -(m1 + m2) g = %.17g, -m2 g = "
         "%.17g\n",
         lam[0], lam[1], -2 * m * G0, -m * G0);
  CHECK_CLOSE(lam[0], -2 * m * G0, 1e-12);
  CHECK_CLOSE(lam[1], -m * G0, 1e-12);
  double w2[2], x[8];
  dal_modes md;
  rc = dal_normal_modes(sys, st, w2, x, NULL, NULL, &md);
  CHECK_MSG(rc == 0, "modes: %s", dal_state_errmsg(st));
  double lo = G0 / l * (2 - sqrt(2.0)), hi = G0 / l * (2 + sqrt(2.0));
  printf("  omega^2 = %.17g, %.17g; closed form %.17g, %.17g (diff %.3g, %.3g)\n", w2[0], w2[1], lo,
         hi, w2[0] - lo, w2[1] - hi);
  CHECK_CLOSE(w2[0], lo, 1e-12);
  CHECK_CLOSE(w2[1], hi, 1e-12);
  CHECK(md.verdict == DAL_NEUTRAL);
  // shapes: horizontal motions only, angles theta2 = sqrt 2 theta1 (in phase), then -sqrt 2
  CHECK_CLOSE(x[1], 0.0, 1e-12);
  CHECK_CLOSE(x[3], 0.0, 1e-12);
  CHECK_CLOSE(x[2] / x[0], 1 + sqrt(2.0),
              1e-12); // x2 = l (theta1 + theta2), theta2 = +-sqrt 2 theta1
  CHECK_CLOSE(x[6] / x[4], 1 - sqrt(2.0), 1e-12);
  // at the static point the reduced matrices are N' M N and N' K_full N
  double M[16], K[16], N[8], Mr[4], Kr[4];
  CHECK_OK(dal_linearize_full(sys, st, M, NULL, K, NULL, N));
  CHECK_OK(dal_linearize(sys, st, Mr, NULL, Kr));
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      double sm = 0, sk = 0;
      for (int a = 0; a < 4; ++a)
        for (int b2 = 0; b2 < 4; ++b2) {
          sm += N[i * 4 + a] * M[b2 * 4 + a] * N[j * 4 + b2];
          sk += N[i * 4 + a] * K[b2 * 4 + a] * N[j * 4 + b2];
        }
      CHECK_CLOSE(Mr[j * 2 + i], sm, 1e-13);
      CHECK_CLOSE(Kr[j * 2 + i], sk, 1e-12);
    }
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// -------------------------------------------------------------------------------------------
// the full-space vector-field Jacobian against central differences of the KKT accelerations
// (oracle) at a moving, generic state of the double pendulum (unequal masses and lengths)

static void jacobian_vs_fd(void) {
  dal_system *sys = double_pendulum(1.3, 0.6, 0.9, 0.5);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double a1 = 0.7, a2 = -0.4, w1 = 1.1, wv2 = -2.3;
  double q[4] = {0.9 * sin(a1), -0.9 * cos(a1), 0.9 * sin(a1) + 0.5 * sin(a2),
                 -0.9 * cos(a1) - 0.5 * cos(a2)};
  double v[4] = {0.9 * cos(a1) * w1, 0.9 * sin(a1) * w1, 0.9 * cos(a1) * w1 + 0.5 * cos(a2) * wv2,
                 0.9 * sin(a1) * w1 + 0.5 * sin(a2) * wv2};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
  double A[64], ft[8];
  int rc = dal_vector_field_jacobian(sys, st, A, ft);
  CHECK_MSG(rc == 0, "jacobian: %s", dal_state_errmsg(st));
  double worst = 0.0;
  for (int c = 0; c < 8; ++c) {
    double h = 1e-5, ap[4], am[4], y[8];
    for (int s = 0; s < 2; ++s) {
      memcpy(y, q, sizeof q);
      memcpy(y + 4, v, sizeof v);
      y[c] += s ? -h : h;
      CHECK_OK(dal_state_set(sys, st, 0.0, y, y + 4));
      CHECK_OK(dal_forward(sys, st));
      memcpy(s ? am : ap, dal_state_qddot(st), sizeof ap);
    }
    for (int i = 0; i < 4; ++i) {
      double fd = (ap[i] - am[i]) / (2 * h), ex = A[c * 8 + 4 + i];
      worst = fmax(worst, fabs(fd - ex) / (1.0 + fabs(ex)));
      CHECK_CLOSE(ex, fd, 1e-7);
      CHECK(A[c * 8 + i] == (c == 4 + i ? 1.0 : 0.0));
    }
  }
  printf("full-space vector-field Jacobian vs central differences: worst %.3g\n", worst);
  for (int i = 0; i < 8; ++i)
    CHECK(ft[i] == 0.0 || fabs(ft[i]) < 1e-13);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// -------------------------------------------------------------------------------------------
// the Cartesian pendulum at a moving state: with the basis carried along the motion, the
// reduced tangent is the minimal pendulum's xi'' = -(g / l) cos(theta) xi (xi = l dtheta)

static void moving_pendulum(void) {
  const double l = 0.8, th = 0.9, w = 2.7;
  scn_knobs k = scn_default();
  k.l = l;
  dal_system *sys = scn_cart_pendulum(&k);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q[2] = {l * sin(th), -l * cos(th)}, v[2] = {l * cos(th) * w, l * sin(th) * w};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
  double M[1], C[1], K[1];
  int rc = dal_linearize(sys, st, M, C, K);
  CHECK_MSG(rc == 0, "linearize: %s", dal_state_errmsg(st));
  printf("moving Cartesian pendulum: K_r / M_r = %.17g, g cos(theta) / l = %.17g, C_r = %.3g\n",
         K[0] / M[0], G0 * cos(th) / l, C[0]);
  CHECK_CLOSE(M[0], 1.0, 1e-14);
  CHECK_CLOSE(K[0], G0 * cos(th) / l, 1e-12);
  CHECK_CLOSE(C[0], 0.0, 1e-12);
  // off the manifold: refused, naming the row
  double qb[2] = {q[0] * 1.01, q[1]};
  CHECK_OK(dal_state_set(sys, st, 0.0, qb, v));
  rc = dal_linearize(sys, st, M, C, K);
  CHECK(rc == DAL_E_ARG && strstr(dal_state_errmsg(st), "'rod'") != NULL);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// -------------------------------------------------------------------------------------------
// the four-bar linkage: ground pivots A = (0, 0) and D = (d, 0), crank AB (a), coupler BC (b),
// rocker DC (c); particles at B (mB) and C (mC) in Cartesian coordinates, gravity -y

static const double FB_A = 1.0, FB_B = 1.2, FB_C = 0.9, FB_D = 1.5, FB_MB = 1.0, FB_MC = 2.0;

static dal_system *fourbar(void) {
  dal_builder *b = NULL;
  scn_knobs k = scn_default();
  int p[2], rc = scn_builder(&k, 2, &b);
  if (!rc) rc = scn_add_xy(b, "B", FB_MB, "xB", "yB", &p[0]);
  if (!rc) rc = scn_add_xy(b, "C", FB_MC, "xC", "yC", &p[1]);
  if (!rc) rc = scn_add_rod(b, "crank", p[0], -1, FB_A, &k);
  if (!rc) rc = scn_add_rod(b, "coupler", p[0], p[1], FB_B, &k);
  k.x0 = FB_D;
  if (!rc) rc = scn_add_rod(b, "rocker", p[1], -1, FB_C, &k);
  return scn_finish(b, rc);
}

// the mechanism in the crank angle th by hand: B = a (cos th, sin th), C on the circles about
// B (radius b) and D (radius c), on the lower branch; jets along th give U', U'' and M(th)
static void fourbar_hand(double th, double *Up, double *Upp, double *Mth, double *pos) {
  dal_jet t = dal_var(th, 1.0);
  dal_jet bx = dal_scale(dal_cos(t), FB_A), by = dal_scale(dal_sin(t), FB_A);
  dal_jet px = dal_sub(dal_const(FB_D), bx), py = dal_scale(by, -1.0); // D - B
  dal_jet L2 = dal_add(dal_sq(px), dal_sq(py)), L = dal_sqrt(L2);
  dal_jet x = dal_div(dal_addc(L2, FB_B * FB_B - FB_C * FB_C), dal_scale(L, 2.0));
  dal_jet h = dal_sqrt(dal_sub(dal_const(FB_B * FB_B), dal_sq(x)));
  // C = B + (x p - h perp(p)) / L, perp(p) = (-py, px): the branch below the line BD
  dal_jet cx = dal_add(bx, dal_div(dal_add(dal_mul(x, px), dal_mul(h, py)), L));
  dal_jet cy = dal_add(by, dal_div(dal_sub(dal_mul(x, py), dal_mul(h, px)), L));
  dal_jet U = dal_scale(dal_add(dal_scale(by, FB_MB), dal_scale(cy, FB_MC)), G0);
  *Up = U.d;
  *Upp = U.dd;
  *Mth = FB_MB * (bx.d * bx.d + by.d * by.d) + FB_MC * (cx.d * cx.d + cy.d * cy.d);
  if (pos) {
    pos[0] = bx.v;
    pos[1] = by.v;
    pos[2] = cx.v;
    pos[3] = cy.v;
  }
}

static void fourbar_mode(void) {
  // the hand model's equilibrium: Newton on U'(th) = 0 with U'' from the jets
  double th = -1.3, up, upp, mth, pos[4];
  for (int i = 0; i < 50; ++i) {
    fourbar_hand(th, &up, &upp, &mth, NULL);
    th -= up / upp;
  }
  fourbar_hand(th, &up, &upp, &mth, pos);
  double w2hand = upp / mth;
  CHECK(fabs(up) < 1e-12 && upp > 0);
  // the constrained model from a nearby consistent configuration (the hand model at th + 0.2)
  dal_system *sys = fourbar();
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q0[4], v[4] = {0};
  fourbar_hand(th + 0.2, &up, &upp, &mth, q0);
  CHECK_OK(dal_state_set(sys, st, 0.0, q0, v));
  dal_equilibrium_report rep;
  int rc = dal_equilibrium(sys, st, NULL, &rep);
  CHECK_MSG(rc == 0, "equilibrium: %s", dal_state_errmsg(st));
  const double *q = dal_state_q(st);
  for (int i = 0; i < 4; ++i)
    CHECK_CLOSE(q[i], pos[i], 1e-12);
  double w2[1];
  dal_modes md;
  rc = dal_normal_modes(sys, st, w2, NULL, NULL, NULL, &md);
  CHECK_MSG(rc == 0, "modes: %s", dal_state_errmsg(st));
  printf("four-bar: crank angle %.15f, omega^2 = %.17g, hand model U''/M = %.17g (rel diff "
         "%.3g), %d Newton iterations\n",
         th, w2[0], w2hand, (w2[0] - w2hand) / w2hand, rep.iterations);
  CHECK(fabs(w2[0] - w2hand) <= 1e-10 * w2hand);
  CHECK(md.verdict == DAL_NEUTRAL);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// -------------------------------------------------------------------------------------------
// the bead on a circle of radius R turning at w about the vertical, as a Cartesian particle
// (x, y, z) with dal_con_turning_circle (two rows)

static const double BEAD_R = 0.6;

static dal_system *cart_bead(double w) {
  scn_knobs k = scn_default();
  k.R = BEAD_R;
  k.spin = w;
  return scn_cart_bead(&k);
}

static int bead_rebuild(double w, dal_system **out, void *ctx) {
  (void)ctx;
  *out = cart_bead(w);
  return *out ? 0 : 1;
}

typedef struct bead_branch {
  int regular, critical, bad;
  double pcrit;
} bead_branch;

static int bead_point(double w, const dal_system *sys, const dal_state *st, dal_stability verdict,
                      dal_branch_kind kind, void *ctx) {
  (void)sys;
  bead_branch *br = ctx;
  const double wc = sqrt(G0 / BEAD_R);
  if (kind == DAL_BRANCH_CRITICAL) {
    br->critical++;
    br->pcrit = w;
    return 0;
  }
  br->regular++;
  // the trivial branch: the bottom point, neutral below the critical rate, unstable above
  const double *q = dal_state_q(st);
  if (fabs(q[0]) > 1e-12 || fabs(q[1]) > 1e-12 || fabs(q[2] + BEAD_R) > 1e-12) br->bad++;
  if (w < wc - 1e-6 && verdict != DAL_NEUTRAL) br->bad++;
  if (w > wc + 1e-6 && verdict != DAL_UNSTABLE) br->bad++;
  return 0;
}

static void turning_bead(void) {
  const double wc = sqrt(G0 / BEAD_R);
  // below the critical rate: Omega^2 = g/R - w^2 about the bottom (a relative equilibrium of
  // the turning constraint whose point stays put)
  for (int pass = 0; pass < 2; ++pass) {
    double w = pass ? 1.3 * wc : 0.7 * wc;
    dal_system *sys = cart_bead(w);
    dal_state *st = NULL;
    CHECK_OK(dal_state_create(sys, &st));
    double q[3] = {0.0, 0.0, -BEAD_R}, v[3] = {0};
    CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
    double w2[1], re[2], im[2];
    dal_modes md;
    int rc = dal_normal_modes(sys, st, w2, NULL, re, im, &md);
    CHECK_MSG(rc == 0, "modes: %s", dal_state_errmsg(st));
    double ref = G0 / BEAD_R - w * w;
    printf("Cartesian bead at w = %.2f w_c: Omega^2 = %.17g, g/R - w^2 = %.17g\n", w / wc, w2[0],
           ref);
    CHECK_CLOSE(w2[0], ref, 1e-12);
    CHECK(md.verdict == (pass ? DAL_UNSTABLE : DAL_NEUTRAL));
    dal_state_destroy(st);
    dal_system_destroy(sys);
  }
  // continuation in w along the bottom branch: the pitchfork at sqrt(g/R)
  dal_continuation_opts o = dal_default_continuation_opts();
  o.p0 = 0.2 * wc;
  o.p1 = 1.8 * wc;
  o.npoints = 8; // no grid point on the critical rate
  double q0[3] = {0.0, 0.0, -BEAD_R};
  bead_branch br = {0, 0, 0, 0.0};
  dal_continuation_report rep;
  int rc = dal_continue(bead_rebuild, q0, &o, bead_point, &rep, &br);
  CHECK_MSG(rc == 0, "continue: %s", rep.msg);
  printf("  continuation: %d points, %d critical at w = %.15f (sqrt(g/R) = %.15f)\n", br.regular,
         br.critical, br.pcrit, wc);
  CHECK(br.regular == 8 && br.critical == 1 && br.bad == 0);
  CHECK(fabs(br.pcrit - wc) <= 2e-10 * (o.p1 - o.p0));

  // above the critical rate, at the relative equilibrium cos(theta*) = g / (R w^2) (closed
  // form; the particle circles the axis with the ring, qdot = w x r): the carried tangent's
  // mode is Omega = w sin(theta*). dal_equilibrium seeks static points (qdot = 0) only: from
  // theta* it finds a point on the axis, which the turning constraint leaves in place
  double w = 1.4 * wc, th = acos(G0 / (BEAD_R * w * w));
  dal_system *sys = cart_bead(w);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q[3] = {BEAD_R * sin(th), 0.0, -BEAD_R * cos(th)}, v[3] = {0.0, w * q[0], 0.0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
  double w2[1], re[2], im[2];
  dal_modes md;
  rc = dal_normal_modes(sys, st, w2, NULL, re, im, &md);
  CHECK_MSG(rc == 0, "modes: %s", dal_state_errmsg(st));
  double ref = w * w * sin(th) * sin(th);
  printf("  relative equilibrium theta* = %.6f at w = 1.4 w_c: Omega^2 = %.17g, (w sin theta*)^2 "
         "= %.17g; eigenvalues %.3g %+.17g i\n",
         th, w2[0], ref, re[0], im[0]);
  CHECK_CLOSE(w2[0], ref, 1e-12);
  CHECK_CLOSE(fabs(im[0]), sqrt(ref), 1e-12);
  CHECK(md.verdict == DAL_NEUTRAL);
  dal_equilibrium_report er;
  rc = dal_equilibrium(sys, st, NULL, &er);
  const double *qe = dal_state_q(st);
  printf("  dal_equilibrium from theta*: rc %d, (%.3g, %.3g, %.17g), accel %.3g\n", rc, qe[0],
         qe[1], qe[2], er.accel);
  CHECK(rc == 0 && fabs(qe[0]) < 1e-12 && fabs(qe[1]) < 1e-12 &&
        fabs(fabs(qe[2]) - BEAD_R) < 1e-12 && er.accel < 1e-12);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// -------------------------------------------------------------------------------------------
// Lyapunov spectrum on the manifold: the double pendulum (unit masses and rods) released at
// rest from (2, 2) rad, in Cartesian coordinates and in its angles

static void lyapunov_manifold(void) {
  const double T = 200.0;
  dal_lyapunov_opts o;
  o = dal_default_lyapunov_opts();
  o.t_end = T;
  double exc[4], erc[4], exm[4], erm[4];
  // Cartesian
  dal_system *sys = double_pendulum(1.0, 1.0, 1.0, 1.0);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q[4] = {sin(2.0), -cos(2.0), 2 * sin(2.0), -2 * cos(2.0)}, v[4] = {0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, v));
  int rc = dal_lyapunov(sys, st, &o, exc, erc, NULL, NULL);
  CHECK_MSG(rc == 0, "lyapunov (Cartesian): %s", dal_state_errmsg(st));
  // the end of the orbit is on the manifold (projected at every QR)
  double r1 = hypot(dal_state_q(st)[0], dal_state_q(st)[1]);
  CHECK(fabs(r1 - 1.0) < 1e-12);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  // minimal coordinates
  sys = scn_double_pendulum(NULL); // unit masses and rods, g = 9.81
  CHECK_OK(dal_state_create(sys, &st));
  double th[2] = {2.0, 2.0}, z[2] = {0, 0};
  CHECK_OK(dal_state_set(sys, st, 0.0, th, z));
  rc = dal_lyapunov(sys, st, &o, exm, erm, NULL, NULL);
  CHECK_MSG(rc == 0, "lyapunov (angles): %s", dal_state_errmsg(st));
  dal_state_destroy(st);
  dal_system_destroy(sys);
  printf("Lyapunov, double pendulum from (2, 2) rad, T = %g:\n  Cartesian %.4f(%.4f) %.4f(%.4f) "
         "%.4f(%.4f) %.4f(%.4f)\n  angles    %.4f(%.4f) %.4f(%.4f) %.4f(%.4f) %.4f(%.4f)\n",
         T, exc[0], erc[0], exc[1], erc[1], exc[2], erc[2], exc[3], erc[3], exm[0], erm[0], exm[1],
         erm[1], exm[2], erm[2], exm[3], erm[3]);
  // Hamiltonian: no phase-space contraction; the volume on the tangent space is measured in the
  // Euclidean metric of (q, qdot), a bounded factor off the invariant one: O(1/T)
  double sum = exc[0] + exc[1] + exc[2] + exc[3];
  CHECK_MSG(fabs(sum) <= 4.0 / T, "sum %.3g", sum);
  // the errors are 95% half-widths (analysis.h)
  CHECK(exc[0] > 1.0 && erc[0] < 0.2 * exc[0]);
  CHECK_MSG(fabs(exc[0] + exc[3]) <= hypot(erc[0], erc[3]) + 2.0 / T, "pair 1");
  CHECK_MSG(fabs(exc[1] + exc[2]) <= hypot(erc[1], erc[2]) + 2.0 / T, "pair 2");
  CHECK_MSG(fabs(exc[0] - exm[0]) <= hypot(erc[0], erm[0]) + 2.0 / T,
            "largest: Cartesian %.4f(%.4f) vs angles %.4f(%.4f)", exc[0], erc[0], exm[0], erm[0]);
}

// a truss: one particle held by two rods to two anchors (k = n - m = 0). The modes are refused
// by name (before: LAPACK's dsygv printed an illegal argument and the status said its
// iteration did not converge); the linearization is the empty 0 x 0 one, the equilibrium the
// apex, held by the rods with the force of statics
static void truss(void) {
  scn_knobs k = scn_default();
  dal_builder *b = NULL;
  int p = 0, rc = scn_builder(&k, 2, &b);
  if (!rc) rc = scn_add_xy(b, "P", 1.0, "x", "y", &p);
  if (!rc) rc = scn_add_rod(b, "left", p, -1, 1.0, &k);
  k.x0 = 1.0;
  if (!rc) rc = scn_add_rod(b, "right", p, -1, 1.0, &k);
  dal_system *s = scn_finish(b, rc);
  dal_state *st = NULL;
  CHECK(s && dal_state_create(s, &st) == DAL_OK);
  if (!st) return;
  double q[2] = {0.5, -sqrt(0.75)}, v[2] = {0, 0}, w2[2], M[4], C[4], K[4];
  CHECK_OK(dal_state_set(s, st, 0, q, v));
  dal_modes md;
  int r = dal_normal_modes(s, st, w2, NULL, NULL, NULL, &md);
  CHECK_MSG(r == DAL_E_UNSUPPORTED && strstr(dal_state_errmsg(st), "no degrees of freedom"),
            "truss modes: %s (%s)", dal_status_name(r), dal_state_errmsg(st));
  CHECK_OK(dal_linearize(s, st, M, C, K));
  dal_equilibrium_report rep;
  CHECK_OK(dal_equilibrium(s, st, NULL, &rep));
  const double *lam = dal_state_lambda(st), *qe = dal_state_q(st);
  CHECK(lam && fabs(qe[0] - 0.5) < 1e-12 && fabs(qe[1] + sqrt(0.75)) < 1e-12);
  // statics: the rods together hold the particle's weight, F = (0, m g), symmetrically
  double F[2] = {NAN, NAN};
  CHECK_OK(dal_constraint_forces(s, st, F));
  CHECK_CLOSE(F[0], 0.0, 1e-12);
  CHECK_CLOSE(F[1], k.g, 1e-12);
  if (lam) CHECK_CLOSE(lam[0], lam[1], 1e-12);
  printf("truss: modes refused (%s), rod forces (%.3g, %.15g) against (0, m g = %.15g)\n",
         dal_status_name(r), F[0], F[1], k.g);
  dal_state_destroy(st);
  dal_system_destroy(s);
}

int main(void) {
  cart_pendulum();
  cart_double_pendulum();
  jacobian_vs_fd();
  moving_pendulum();
  fourbar_mode();
  turning_bead();
  lyapunov_manifold();
  truss();
  printf("%d checks, %d failures\n", check_count, check_failures);
  return check_failures != 0;
}
