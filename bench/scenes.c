// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The benchmark's scenes: builds through the public API, hand-written twins, references.
#include "scenes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ref.h"
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

// minimal coordinates: the scene as the user of the map primitives writes it
static int build_minimal(const bench_scene *sc, dal_builder *b, bench_model *m) {
  int rc = DAL_OK, p, c;
  double g2[2] = {0.0, -G_STD}, g3[3] = {0.0, 0.0, -G_STD};
  switch (sc->kind) {
  case SC_HO2D: {
    int xy[2];
    if (!rc) rc = dal_builder_add_coord(b, "x", &xy[0]);
    if (!rc) rc = dal_builder_add_coord(b, "y", &xy[1]);
    if (!rc) rc = dal_builder_add_particle(b, "m", HO_M, &p);
    dal_place_def pd = dal_default_place_def();
    pd.prim = &dal_map_cartesian2;
    pd.coords = xy;
    pd.ncoords = 2;
    if (!rc) rc = dal_builder_place_def(b, p, &pd);
    if (!rc) rc = dal_builder_add_potential_r(b, ho_potential, NULL);
    if (!rc) rc = model_alloc(m, 2);
    if (!rc) {
      m->q0[0] = 1.0;
      m->q0[1] = 2.0;
      m->qd0[0] = 3.0;
      m->qd0[1] = 4.0;
    }
    return rc;
  }
  case SC_RING: {
    if (!rc) rc = dal_builder_add_coord(b, "theta", &c);
    if (!rc) rc = dal_builder_add_particle(b, "bead", 1.0, &p);
    dal_place_def pd = dal_default_place_def(); // the ring's plane at angle 0 at t = 0
    pd.prim = &dal_map_ring;
    pd.coords = &c;
    pd.ncoords = 1;
    pd.param[DAL_RING_R] = RING_R;
    pd.param[DAL_RING_W] = ring_w();
    if (!rc) rc = dal_builder_place_def(b, p, &pd);
    if (!rc) rc = dal_builder_set_gravity(b, g3);
    if (!rc) rc = model_alloc(m, 1);
    if (!rc) m->q0[0] = RING_TH0;
    return rc;
  }
  case SC_DRIVEN: {
    double gd[2] = {0.0, -DRV_G};
    if (!rc) rc = dal_builder_add_coord(b, "theta", &c);
    if (!rc) rc = dal_builder_add_particle(b, "bob", 1.0, &p);
    dal_place_def pd = dal_default_place_def(); // pivot (0, a cos(w t))
    pd.prim = &dal_map_pendulum;
    pd.coords = &c;
    pd.ncoords = 1;
    pd.param[DAL_PENDULUM_L] = DRV_L;
    pd.param[DAL_PENDULUM_AY] = DRV_A;
    pd.param[DAL_PENDULUM_W] = drv_w();
    if (!rc) rc = dal_builder_place_def(b, p, &pd);
    if (!rc) rc = dal_builder_set_gravity(b, gd);
    if (!rc) rc = model_alloc(m, 1);
    if (!rc) m->q0[0] = 1.0;
    return rc;
  }
  default:
    break;
  }
  // chain-like: pendulum about the origin, then links hanging from the previous particle
  int N = sc->N;
  rc = model_alloc(m, N);
  for (int i = 0; i < N && !rc; ++i) {
    char name[32];
    snprintf(name, sizeof name, "th%d", i);
    rc = dal_builder_add_coord(b, name, &c);
    snprintf(name, sizeof name, "p%d", i);
    if (!rc) rc = dal_builder_add_particle(b, name, 1.0, &p);
    dal_place_def pd = dal_default_place_def();
    pd.coords = &c;
    pd.ncoords = 1;
    if (i == 0) {
      pd.prim = &dal_map_pendulum;
      pd.param[DAL_PENDULUM_L] = 1.0;
    } else {
      pd.prim = &dal_map_hanging;
      pd.parent = p - 1;
      pd.param[DAL_HANGING_L] = 1.0;
    }
    if (!rc) rc = dal_builder_place_def(b, p, &pd);
    m->q0[i] = chain_th0(sc, i);
  }
  if (!rc) rc = dal_builder_set_gravity(b, g2);
  return rc;
}

// moving pivot of the driven pendulum: (0, a cos(w t))
static int driven_pivot(dal_jet t, dal_jet *x, void *ctx) {
  (void)ctx;
  x[0] = dal_const(0.0);
  x[1] = dal_scale(dal_cos(dal_scale(t, drv_w())), DRV_A);
  return 0;
}

static const dal_moving_point driven_point = {driven_pivot, NULL};

// add a particle with its own Cartesian coordinates (d of them)
static int add_cartesian(dal_builder *b, int d, int i, int *p) {
  char name[32];
  int c[3], rc = DAL_OK;
  for (int a = 0; a < d && !rc; ++a) {
    snprintf(name, sizeof name, "%c%d", "xyz"[a], i);
    rc = dal_builder_add_coord(b, name, &c[a]);
  }
  snprintf(name, sizeof name, "p%d", i);
  if (!rc) rc = dal_builder_add_particle(b, name, 1.0, p);
  dal_place_def pd = dal_default_place_def();
  pd.prim = d == 2 ? &dal_map_cartesian2 : &dal_map_cartesian3;
  pd.coords = c;
  pd.ncoords = d;
  if (!rc) rc = dal_builder_place_def(b, *p, &pd);
  return rc;
}

// redundant Cartesian coordinates tied by rods: every particle has its own (x, y[, z])
static int build_redundant(const bench_scene *sc, dal_builder *b, bench_model *m) {
  int rc = DAL_OK, p;
  double g2[2] = {0.0, -G_STD}, g3[3] = {0.0, 0.0, -G_STD};
  switch (sc->kind) {
  case SC_RING: {
    // bead held on the turning circle; starts on the ring at rest relative to it
    rc = add_cartesian(b, 3, 0, &p);
    dal_constraint_def cd = dal_default_constraint_def(); // centred at the origin
    cd.name = "ring";
    cd.prim = &dal_con_turning_circle;
    cd.parts = &p;
    cd.nparts = 1;
    cd.param[DAL_TURNING_CIRCLE_R] = RING_R;
    cd.param[DAL_TURNING_CIRCLE_W] = ring_w();
    if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
    if (!rc) rc = dal_builder_set_gravity(b, g3);
    if (!rc) rc = model_alloc(m, 3);
    if (!rc) {
      m->q0[0] = RING_R * sin(RING_TH0);
      m->q0[2] = -RING_R * cos(RING_TH0);
      m->qd0[1] = ring_w() * RING_R * sin(RING_TH0);
    }
    return rc;
  }
  case SC_DRIVEN: {
    // rod to the moving pivot (0, a cos(w t)), which starts at (0, a) at rest
    double gd[2] = {0.0, -DRV_G};
    rc = add_cartesian(b, 2, 0, &p);
    dal_constraint_def cd = dal_default_constraint_def(); // the point 0 + x(t)
    cd.name = "rod";
    cd.prim = &dal_con_anchor2;
    cd.parts = &p;
    cd.nparts = 1;
    cd.param[DAL_ANCHOR_L] = DRV_L;
    cd.ctx = (void *)&driven_point;
    if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
    if (!rc) rc = dal_builder_set_gravity(b, gd);
    if (!rc) rc = model_alloc(m, 2);
    if (!rc) {
      m->q0[0] = DRV_L * sin(1.0);
      m->q0[1] = DRV_A - DRV_L * cos(1.0);
    }
    return rc;
  }
  case SC_HO2D:
    return DAL_E_UNSUPPORTED;
  default:
    break;
  }
  // chain-like: rod to the pivot, then rods between neighbours; released from rest
  int N = sc->N;
  double x = 0.0, y = 0.0;
  rc = model_alloc(m, 2 * N);
  for (int i = 0; i < N && !rc; ++i) {
    char name[32];
    rc = add_cartesian(b, 2, i, &p);
    snprintf(name, sizeof name, "rod%d", i);
    // the first rod to the fixed pivot at the origin, the others between neighbours
    int ends[2];
    dal_constraint_def cd = dal_default_constraint_def();
    cd.name = name;
    if (i == 0) {
      cd.prim = &dal_con_anchor2;
      cd.parts = &p;
      cd.nparts = 1;
      cd.param[DAL_ANCHOR_L] = 1.0;
    } else {
      ends[0] = p - 1;
      ends[1] = p;
      cd.prim = &dal_con_distance2;
      cd.parts = ends;
      cd.nparts = 2;
      cd.param[DAL_DISTANCE_L] = 1.0;
    }
    if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
    x += sin(chain_th0(sc, i));
    y -= cos(chain_th0(sc, i));
    m->q0[2 * i] = x;
    m->q0[2 * i + 1] = y;
  }
  if (!rc) rc = dal_builder_set_gravity(b, g2);
  return rc;
}

int scene_model(const bench_scene *sc, int redundant, bench_model *m, char *err, size_t len) {
  return scene_model_route(sc, redundant, DAL_DYNAMICS_AUTO, m, err, len);
}

int scene_model_route(const bench_scene *sc, int redundant, dal_dynamics how, bench_model *m,
                      char *err, size_t len) {
  memset(m, 0, sizeof *m);
  err[0] = 0;
  dal_builder *b = NULL;
  int rc = dal_builder_create(scene_dim(sc), &b);
  if (!rc) rc = redundant ? build_redundant(sc, b, m) : build_minimal(sc, b, m);
  if (!rc) rc = dal_builder_set_dynamics(b, how);
  if (!rc) rc = dal_builder_compile(b, &m->sys);
  if (rc && rc != DAL_E_UNSUPPORTED && b)
    snprintf(err, len, "%s: %s", sc->name, dal_builder_errmsg(b));
  if (!rc) rc = dal_state_create(m->sys, &m->st);
  if (!rc) rc = scene_model_reset(m);
  dal_builder_destroy(b);
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

// four-bar linkage: ground pivots A = (0, 0), D = (3, 0); crank AB = 1, coupler BC = 3.5,
// rocker CD = 2, massless links, masses 1 at B and 2 at C, started with the crank at 0.4 rad
// turning at 3 rad/s (the coupler's rate from the closure). Tree: B pendulum about A, C
// hanging from B, loop row CD; Cartesian: B, C with rods AB, BC, CD.
static int build_fourbar(dal_builder *b, int cart, bench_model *m) {
  const double a = 1.0, bl = 3.5, c = 2.0, Dx = 3.0, th1 = 0.4, w1 = 3.0;
  double B[2] = {a * sin(th1), -a * cos(th1)};
  double dx = Dx - B[0], dy = -B[1], dd = sqrt(dx * dx + dy * dy);
  double al = (bl * bl - c * c + dd * dd) / (2 * dd), h = sqrt(bl * bl - al * al);
  double C[2] = {B[0] + al * dx / dd + h * dy / dd, B[1] + al * dy / dd - h * dx / dd};
  double th2 = atan2(C[0] - B[0], -(C[1] - B[1]));
  double e1[2] = {cos(th1), sin(th1)}, e2[2] = {cos(th2), sin(th2)}, CD[2] = {C[0] - Dx, C[1]};
  double w2 = -a * w1 * (CD[0] * e1[0] + CD[1] * e1[1]) / (bl * (CD[0] * e2[0] + CD[1] * e2[1]));
  double Bd[2] = {a * w1 * e1[0], a * w1 * e1[1]};
  double Cd[2] = {Bd[0] + bl * w2 * e2[0], Bd[1] + bl * w2 * e2[1]};
  int p[2], cs[4], rc = model_alloc(m, cart ? 4 : 2);
  if (!rc) rc = dal_builder_add_particle(b, "B", 1.0, &p[0]);
  if (!rc) rc = dal_builder_add_particle(b, "C", 2.0, &p[1]);
  dal_place_def pd = dal_default_place_def();
  dal_constraint_def cd = dal_default_constraint_def();
  if (!rc && !cart) {
    rc = dal_builder_add_coord(b, "crank", &cs[0]);
    if (!rc) rc = dal_builder_add_coord(b, "coupler", &cs[1]);
    pd.prim = &dal_map_pendulum; // B about A at the origin
    pd.coords = &cs[0];
    pd.ncoords = 1;
    pd.param[DAL_PENDULUM_L] = a;
    if (!rc) rc = dal_builder_place_def(b, p[0], &pd);
    pd = dal_default_place_def(); // C hanging from B
    pd.prim = &dal_map_hanging;
    pd.parent = p[0];
    pd.coords = &cs[1];
    pd.ncoords = 1;
    pd.param[DAL_HANGING_L] = bl;
    if (!rc) rc = dal_builder_place_def(b, p[1], &pd);
    if (!rc) {
      m->q0[0] = th1, m->q0[1] = th2, m->qd0[0] = w1, m->qd0[1] = w2;
    }
  } else if (!rc) {
    const char *nm[4] = {"xB", "yB", "xC", "yC"};
    for (int i = 0; i < 4 && !rc; ++i)
      rc = dal_builder_add_coord(b, nm[i], &cs[i]);
    pd.prim = &dal_map_cartesian2;
    pd.ncoords = 2;
    pd.coords = cs;
    if (!rc) rc = dal_builder_place_def(b, p[0], &pd);
    pd.coords = cs + 2;
    if (!rc) rc = dal_builder_place_def(b, p[1], &pd);
    cd.name = "AB"; // B to the ground pivot A at the origin
    cd.prim = &dal_con_anchor2;
    cd.parts = &p[0];
    cd.nparts = 1;
    cd.param[DAL_ANCHOR_L] = a;
    if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
    cd = dal_default_constraint_def();
    cd.name = "BC";
    cd.prim = &dal_con_distance2;
    cd.parts = p;
    cd.nparts = 2;
    cd.param[DAL_DISTANCE_L] = bl;
    if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
    if (!rc) {
      double q[4] = {B[0], B[1], C[0], C[1]}, qd[4] = {Bd[0], Bd[1], Cd[0], Cd[1]};
      memcpy(m->q0, q, sizeof q);
      memcpy(m->qd0, qd, sizeof qd);
    }
  }
  cd = dal_default_constraint_def(); // C to the ground pivot D = (Dx, 0)
  cd.name = "CD";
  cd.prim = &dal_con_anchor2;
  cd.parts = &p[1];
  cd.nparts = 1;
  cd.param[DAL_ANCHOR_L] = c;
  cd.param[DAL_ANCHOR_X0] = Dx;
  if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
  double g[2] = {0.0, -G_STD};
  if (!rc) rc = dal_builder_set_gravity(b, g);
  return rc;
}

// a chain of NL unit links and unit masses between A = (0, 0) and B = (NL sin 60deg, 0),
// released from rest as a V. Tree: NL - 1 particles (a pendulum, then hanging), loop row: the
// last rod to B; Cartesian: NL - 1 particles and NL rods.
static int build_held(dal_builder *b, int NL, int cart, bench_model *m) {
  const double al = PI / 3.0;
  double span = NL * sin(al), x = 0.0, y = 0.0;
  int rc = model_alloc(m, cart ? 2 * (NL - 1) : NL - 1), prev = -1;
  for (int k = 0; k < NL - 1 && !rc; ++k) {
    double th = k < NL / 2 ? al : PI - al;
    int p, c[2], pair[2];
    char name[32];
    x += sin(th);
    y -= cos(th);
    snprintf(name, sizeof name, "p%d", k);
    rc = dal_builder_add_particle(b, name, 1.0, &p);
    pair[0] = prev;
    pair[1] = p;
    if (!rc && !cart) {
      snprintf(name, sizeof name, "th%d", k);
      rc = dal_builder_add_coord(b, name, &c[0]);
      // unit links: a pendulum about A at the origin, then each hanging from the previous
      dal_place_def pd = dal_default_place_def();
      pd.coords = c;
      pd.ncoords = 1;
      if (k == 0) {
        pd.prim = &dal_map_pendulum;
        pd.param[DAL_PENDULUM_L] = 1.0;
      } else {
        pd.prim = &dal_map_hanging;
        pd.parent = prev;
        pd.param[DAL_HANGING_L] = 1.0;
      }
      if (!rc) rc = dal_builder_place_def(b, p, &pd);
      m->q0[k] = th;
    } else if (!rc) {
      snprintf(name, sizeof name, "x%d", k);
      rc = dal_builder_add_coord(b, name, &c[0]);
      snprintf(name, sizeof name, "y%d", k);
      if (!rc) rc = dal_builder_add_coord(b, name, &c[1]);
      dal_place_def pd = dal_default_place_def();
      pd.prim = &dal_map_cartesian2;
      pd.coords = c;
      pd.ncoords = 2;
      if (!rc) rc = dal_builder_place_def(b, p, &pd);
      // unit rods: the first to A at the origin, then between neighbours
      dal_constraint_def cd = dal_default_constraint_def();
      if (k == 0) {
        cd.prim = &dal_con_anchor2;
        cd.parts = &p;
        cd.nparts = 1;
        cd.param[DAL_ANCHOR_L] = 1.0;
      } else {
        cd.prim = &dal_con_distance2;
        cd.parts = pair;
        cd.nparts = 2;
        cd.param[DAL_DISTANCE_L] = 1.0;
      }
      if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
      m->q0[2 * k] = x;
      m->q0[2 * k + 1] = y;
    }
    prev = p;
  }
  dal_constraint_def cd = dal_default_constraint_def(); // the last unit rod to B = (span, 0)
  cd.name = "held";
  cd.prim = &dal_con_anchor2;
  cd.parts = &prev;
  cd.nparts = 1;
  cd.param[DAL_ANCHOR_L] = 1.0;
  cd.param[DAL_ANCHOR_X0] = span;
  if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
  double g[2] = {0.0, -G_STD};
  if (!rc) rc = dal_builder_set_gravity(b, g);
  return rc;
}

int loop_model(int which, int NL, int cart, dal_dynamics how, bench_model *m, char *err,
               size_t len) {
  memset(m, 0, sizeof *m);
  err[0] = 0;
  dal_builder *b = NULL;
  int rc = dal_builder_create(2, &b);
  if (!rc) rc = which == LOOP_FOURBAR ? build_fourbar(b, cart, m) : build_held(b, NL, cart, m);
  if (!rc) rc = dal_builder_set_dynamics(b, how);
  if (!rc) rc = dal_builder_compile(b, &m->sys);
  if (rc && b) snprintf(err, len, "loop scene %d: %s", which, dal_builder_errmsg(b));
  if (!rc) rc = dal_state_create(m->sys, &m->st);
  if (!rc) rc = scene_model_reset(m);
  dal_builder_destroy(b);
  if (rc) scene_model_free(m);
  return rc;
}
