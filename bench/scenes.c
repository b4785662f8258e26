// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The benchmark's scenes: builds through the public API, hand-written twins, references.
#include "scenes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ref.h"
#include "support/scenes.h"
#include "util.h"

#define PI 3.14159265358979323846

// scene constants
#define G_STD 9.81
#define HO_M 2.0
#define HO_K 1.0
#define PEND_TH0 (5.0 * PI / 6.0) // 150 degrees
#define RING_R 1.0
#define RING_TH0 1.0
#define DRV_L 1.0
#define DRV_A 0.1
#define DRV_G 9.8
#define DBL_TH1 (2.0 * PI / 3.0)
#define DBL_TH2 (PI / 3.0)
#define CHAIN_TH0 (PI / 4.0)
// references: two integrators at this tolerance must agree
#define REF_RTOL 1e-14
#define REF_ATOL 1e-16

static double ring_w(void) { return 2.0 * sqrt(G_STD / RING_R); }
static double drv_w(void) { return 2.0 * sqrt(DRV_G); }

void scene_init(bench_scene *sc, scene_kind kind, int N, double t1) {
  memset(sc, 0, sizeof *sc);
  sc->kind = kind;
  sc->N = 1;
  double def = 10.0;
  switch (kind) {
  case SC_HO2D:
    snprintf(sc->name, sizeof sc->name, "ho2d");
    break;
  case SC_PENDULUM:
    snprintf(sc->name, sizeof sc->name, "pendulum");
    break;
  case SC_RING:
    snprintf(sc->name, sizeof sc->name, "ring");
    break;
  case SC_DRIVEN:
    snprintf(sc->name, sizeof sc->name, "driven");
    def = 5.0;
    break;
  case SC_DOUBLE:
    snprintf(sc->name, sizeof sc->name, "double");
    sc->N = 2;
    def = 5.0;
    break;
  case SC_CHAIN:
    snprintf(sc->name, sizeof sc->name, "chain%d", N);
    sc->N = N;
    def = N <= 8 ? 10.0 : N <= 32 ? 5.0 : N <= 256 ? 1.0 : 0.25;
    break;
  }
  sc->t1 = t1 > 0 ? t1 : def;
}

int scene_np(const bench_scene *sc) {
  return (sc->kind == SC_DOUBLE || sc->kind == SC_CHAIN) ? sc->N : 1;
}

int scene_dim(const bench_scene *sc) { return sc->kind == SC_RING ? 3 : 2; }

int scene_has_hand(const bench_scene *sc) {
  return sc->kind == SC_PENDULUM || sc->kind == SC_DOUBLE || sc->kind == SC_CHAIN;
}

// initial angles of the chain-like scenes
static double chain_th0(const bench_scene *sc, int i) {
  if (sc->kind == SC_PENDULUM) return PEND_TH0;
  if (sc->kind == SC_DOUBLE) return i == 0 ? DBL_TH1 : DBL_TH2;
  return CHAIN_TH0;
}

hand_chain *scene_hand_chain(const bench_scene *sc, double *y0) {
  hand_chain *ch = hand_chain_create(sc->N, G_STD);
  if (!ch) return NULL;
  for (int i = 0; i < sc->N; ++i) {
    y0[i] = chain_th0(sc, i);
    y0[sc->N + i] = 0.0;
  }
  return ch;
}

// U = k/2 |r|^2 for the oscillator
static int ho_potential(const dal_jet *r, dal_jet t, dal_jet *U, void *ctx) {
  (void)t;
  (void)ctx;
  *U = dal_scale(dal_add(dal_sq(r[0]), dal_sq(r[1])), 0.5 * HO_K);
  return 0;
}

// allocate the model arrays for n coordinates
static int model_alloc(bench_model *m, int n) {
  m->n = n;
  m->q0 = calloc((size_t)n, sizeof(double));
  m->qd0 = calloc((size_t)n, sizeof(double));
  return m->q0 && m->qd0 ? DAL_OK : DAL_E_NOMEM;
}

// moving pivot of the driven pendulum: (0, a cos(w t))
static int driven_pivot(dal_jet t, dal_jet *x, void *ctx) {
  (void)ctx;
  x[0] = dal_const(0.0);
  x[1] = dal_scale(dal_cos(dal_scale(t, drv_w())), DRV_A);
  return 0;
}

static const dal_moving_point driven_point = {driven_pivot, NULL};

// the 2D oscillator: "m" in (x, y) in the potential U(r) of ho_potential, no gravity
static dal_system *build_ho2d(const scn_knobs *k) {
  scn_knobs free = *k;
  free.g = 0.0;
  dal_builder *b = NULL;
  int p, rc = scn_builder(&free, 2, &b);
  if (!rc) rc = scn_add_xy(b, "m", HO_M, "x", "y", &p);
  if (!rc) rc = dal_builder_add_potential_r(b, ho_potential, NULL);
  return scn_finish(b, rc);
}

// minimal coordinates, from the scene library: the scene as the user of the map primitives
// writes it (the pendulum and the double pendulum are chains of 1 and 2 links)
static dal_system *build_minimal(const bench_scene *sc, scn_knobs *k, bench_model *m) {
  switch (sc->kind) {
  case SC_HO2D:
    m->q0[0] = 1.0;
    m->q0[1] = 2.0;
    m->qd0[0] = 3.0;
    m->qd0[1] = 4.0;
    return build_ho2d(k);
  case SC_RING: // the ring's plane at angle 0 at t = 0
    m->q0[0] = RING_TH0;
    return scn_bead(k);
  case SC_DRIVEN: // pivot (0, a cos(w t))
    k->ay = DRV_A;
    k->w = drv_w();
    m->q0[0] = 1.0;
    return scn_pendulum(k);
  default:
    break;
  }
  // chain-like: pendulum about the origin, then links hanging from the previous particle
  for (int i = 0; i < sc->N; ++i)
    m->q0[i] = chain_th0(sc, i);
  return scn_chain(k);
}

// redundant Cartesian coordinates tied by rods, from the scene library: every particle has its
// own (x, y[, z])
static dal_system *build_redundant(const bench_scene *sc, scn_knobs *k, bench_model *m) {
  switch (sc->kind) {
  case SC_RING:
    // bead held on the turning circle; starts on the ring at rest relative to it
    m->q0[0] = RING_R * sin(RING_TH0);
    m->q0[2] = -RING_R * cos(RING_TH0);
    m->qd0[1] = ring_w() * RING_R * sin(RING_TH0);
    return scn_cart_bead(k);
  case SC_DRIVEN:
    // rod to the moving pivot (0, a cos(w t)), which starts at (0, a) at rest
    k->pivot = &driven_point;
    m->q0[0] = DRV_L * sin(1.0);
    m->q0[1] = DRV_A - DRV_L * cos(1.0);
    return scn_cart_pendulum(k);
  default:
    break;
  }
  // chain-like: rod to the pivot, then rods between neighbours; released from rest
  double x = 0.0, y = 0.0;
  for (int i = 0; i < sc->N; ++i) {
    x += sin(chain_th0(sc, i));
    y -= cos(chain_th0(sc, i));
    m->q0[2 * i] = x;
    m->q0[2 * i + 1] = y;
  }
  return scn_cart_chain(k);
}

int scene_model(const bench_scene *sc, int redundant, bench_model *m, char *err, size_t len) {
  return scene_model_route(sc, redundant, DAL_DYNAMICS_AUTO, m, err, len);
}

int scene_model_route(const bench_scene *sc, int redundant, dal_dynamics how, bench_model *m,
                      char *err, size_t len) {
  memset(m, 0, sizeof *m);
  err[0] = 0;
  if (redundant && sc->kind == SC_HO2D) return DAL_E_UNSUPPORTED;
  // the scene's knobs: unit masses and lengths, standard gravity (the driven pendulum's own)
  scn_knobs k = scn_default();
  k.g = sc->kind == SC_DRIVEN ? DRV_G : G_STD;
  k.l = sc->kind == SC_DRIVEN ? DRV_L : 1.0;
  k.R = RING_R;
  k.spin = ring_w();
  k.N = sc->N;
  k.dynamics = how;
  int n = sc->kind == SC_HO2D ? 2 : sc->kind == SC_RING || sc->kind == SC_DRIVEN ? 1 : sc->N;
  int rc = model_alloc(m, redundant ? scene_dim(sc) * n : n);
  if (!rc) {
    m->sys = redundant ? build_redundant(sc, &k, m) : build_minimal(sc, &k, m);
    if (!m->sys) {
      snprintf(err, len, "%s: cannot be built (message on stderr)", sc->name);
      rc = DAL_E_ARG;
    }
  }
  if (!rc) rc = dal_state_create(m->sys, &m->st);
  if (!rc) rc = scene_model_reset(m);
  if (rc) scene_model_free(m);
  return rc;
}

void scene_model_free(bench_model *m) {
  dal_state_destroy(m->st);
  dal_system_destroy(m->sys);
  free(m->q0);
  free(m->qd0);
  memset(m, 0, sizeof *m);
}

int scene_model_reset(bench_model *m) { return dal_state_set(m->sys, m->st, 0.0, m->q0, m->qd0); }

// integrate a hand-written scene by two methods into ya and yb; ya is the reference
static int two_methods(hand_rhs_fn *f1, hand_rhs_fn *f2, void *ctx, int n, const double *y0,
                       double t1, double *ya, double *yb) {
  memcpy(ya, y0, (size_t)n * sizeof(double));
  memcpy(yb, y0, (size_t)n * sizeof(double));
  int rc = hand_integrate(f1, ctx, n, ya, 0.0, t1, DAL_METHOD_FEHLBERG78, REF_RTOL, REF_ATOL,
                          100000000, NULL);
  if (!rc)
    rc = hand_integrate(f2, ctx, n, yb, 0.0, t1, DAL_METHOD_DOPRI5, REF_RTOL, REF_ATOL, 100000000,
                        NULL);
  return rc ? DAL_E_SOLVER : DAL_OK;
}

int scene_reference(const bench_scene *sc, double *r, double *agree, char *how, size_t len) {
  double t = sc->t1;
  *agree = 0.0;
  switch (sc->kind) {
  case SC_HO2D: {
    double r0[2] = {1.0, 2.0}, v0[2] = {3.0, 4.0};
    ref_oscillator(HO_M, HO_K, r0, v0, t, r);
    snprintf(how, len, "closed form");
    return DAL_OK;
  }
  case SC_PENDULUM: {
    double th, thd;
    ref_pendulum(PEND_TH0, 1.0, G_STD, t, &th, &thd);
    r[0] = sin(th);
    r[1] = -cos(th);
    snprintf(how, len, "Jacobi elliptic closed form");
    return DAL_OK;
  }
  case SC_RING: {
    double p[3] = {RING_R, ring_w(), G_STD}, y0[2] = {RING_TH0, 0.0}, y[4], rb[3];
    int rc = two_methods(hand_ring_rhs, hand_ring_rhs, p, 2, y0, t, y, y + 2);
    for (int k = 0; k < 2; ++k) {
      double *out = k ? rb : r, s = RING_R * sin(y[2 * k]);
      out[0] = s * cos(ring_w() * t);
      out[1] = s * sin(ring_w() * t);
      out[2] = -RING_R * cos(y[2 * k]);
    }
    *agree = bench_maxdiff(r, rb, 3);
    snprintf(how, len, "hand-written ODE: fehlberg78 vs dopri5 at rtol 1e-14");
    return rc;
  }
  case SC_DRIVEN: {
    double p[4] = {DRV_L, DRV_A, drv_w(), DRV_G}, y0[2] = {1.0, 0.0}, y[4], rb[2];
    int rc = two_methods(hand_driven_rhs, hand_driven_rhs, p, 2, y0, t, y, y + 2);
    for (int k = 0; k < 2; ++k) {
      double *out = k ? rb : r;
      out[0] = DRV_L * sin(y[2 * k]);
      out[1] = DRV_A * cos(drv_w() * t) - DRV_L * cos(y[2 * k]);
    }
    *agree = bench_maxdiff(r, rb, 2);
    snprintf(how, len, "hand-written ODE: fehlberg78 vs dopri5 at rtol 1e-14");
    return rc;
  }
  default:
    break;
  }
  // chain-like: O(N) tension form by Fehlberg 7(8) against the dense form by Dormand-Prince
  int N = sc->N;
  size_t n2 = 2 * (size_t)N;
  double *y0 = malloc(n2 * sizeof(double)), *y = malloc(2 * n2 * sizeof(double));
  double *rb = malloc(n2 * sizeof(double));
  hand_chain *ch = y0 ? scene_hand_chain(sc, y0) : NULL;
  int rc = DAL_E_NOMEM;
  if (ch && y && rb) {
    hand_rhs_fn *second = N <= 256 ? hand_chain_rhs_dense : hand_chain_rhs_tridiag;
    rc = two_methods(hand_chain_rhs_tridiag, second, ch, 2 * N, y0, t, y, y + n2);
    hand_chain_positions(ch, y, r);
    hand_chain_positions(ch, y + n2, rb);
    *agree = bench_maxdiff(r, rb, 2 * N);
    snprintf(how, len,
             "hand-written chain: O(N) form by fehlberg78 vs %s form by dopri5 at "
             "rtol 1e-14",
             N <= 256 ? "dense" : "O(N)");
  }
  hand_chain_destroy(ch);
  free(y0);
  free(y);
  free(rb);
  return rc;
}

int scene_reference_fast(const bench_scene *sc, double *r) {
  if (sc->kind != SC_CHAIN) return DAL_E_UNSUPPORTED;
  size_t n2 = 2 * (size_t)sc->N;
  double *y = malloc(n2 * sizeof(double));
  hand_chain *ch = y ? scene_hand_chain(sc, y) : NULL;
  int rc = DAL_E_NOMEM;
  if (ch) {
    rc = hand_integrate(hand_chain_rhs_tridiag, ch, (int)n2, y, 0.0, sc->t1, DAL_METHOD_FEHLBERG78,
                        1e-12, 1e-14, 100000000, NULL);
    rc = rc ? DAL_E_SOLVER : DAL_OK;
    hand_chain_positions(ch, y, r);
  }
  hand_chain_destroy(ch);
  free(y);
  return rc;
}

// ---------------------------------------------------------------- closed loops on a tree

int loop_np(int which, int NL) { return which == LOOP_FOURBAR ? 2 : NL - 1; }

int loop_model(int which, int NL, int cart, dal_dynamics how, bench_model *m, char *err,
               size_t len) {
  // the four-bar (crank at 0.4 rad turning at 3 rad/s) and the held chain of the scene library
  memset(m, 0, sizeof *m);
  err[0] = 0;
  scn_knobs k = scn_default();
  k.g = G_STD;
  k.dynamics = how;
  k.N = NL;
  int rc = model_alloc(m, which == LOOP_FOURBAR ? (cart ? 4 : 2) : (cart ? 2 : 1) * (NL - 1));
  if (!rc) {
    m->sys = which == LOOP_FOURBAR ? scn_fourbar(&k, cart, 0.4, 3.0, m->q0, m->qd0)
                                   : scn_held_chain(&k, cart, m->q0, m->qd0);
    if (!m->sys) {
      snprintf(err, len, "loop scene %d: cannot be built (message on stderr)", which);
      rc = DAL_E_ARG;
    }
  }
  if (!rc) rc = dal_state_create(m->sys, &m->st);
  if (!rc) rc = scene_model_reset(m);
  if (rc) scene_model_free(m);
  return rc;
}
