// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The standard scenes of the tests and benchmarks (scenes.h).
#include "scenes.h"

#include <math.h>
#include <stdio.h>

#define PI 3.14159265358979323846

scn_knobs scn_default(void) {
  scn_knobs k = {0};
  k.g = SCN_G;
  k.m = k.m2 = 1.0;
  k.l = k.l2 = 1.0;
  k.R = 1.0;
  k.k = 1.0;
  k.N = 4;
  k.dynamics = DAL_DYNAMICS_AUTO;
  return k;
}

scn_knobs scn_weightless(void) {
  scn_knobs k = scn_default();
  k.g = 0.0;
  return k;
}

// NULL knobs: the defaults
#define KNOBS(k)                                                                                   \
  scn_knobs dflt_ = scn_default();                                                                 \
  if (!(k)) (k) = &dflt_

dal_system *scn_finish(dal_builder *b, int rc) {
  dal_system *s = NULL;
  if (!rc) rc = dal_builder_compile(b, &s);
  if (rc) fprintf(stderr, "scene: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return rc ? NULL : s;
}

int scn_builder(const scn_knobs *k, int d, dal_builder **b) {
  KNOBS(k);
  int rc = dal_builder_create(d, b);
  double g[3] = {0.0, 0.0, 0.0};
  g[d - 1] = -k->g;
  if (!rc && k->g != 0.0) rc = dal_builder_set_gravity(*b, g);
  if (!rc) rc = dal_builder_set_dynamics(*b, k->dynamics);
  return rc;
}

int scn_place_swing(dal_builder *b, const scn_knobs *k, int p, int parent, double l, int coord) {
  KNOBS(k);
  dal_place_def pd = dal_default_place_def();
  pd.coords = &coord;
  pd.ncoords = 1;
  if (parent < 0) {
    pd.prim = &dal_map_pendulum;
    pd.param[DAL_PENDULUM_L] = l;
    pd.param[DAL_PENDULUM_AX] = k->ax;
    pd.param[DAL_PENDULUM_AY] = k->ay;
    pd.param[DAL_PENDULUM_W] = k->w;
    pd.param[DAL_PENDULUM_PH] = k->ph;
    pd.param[DAL_PENDULUM_X0] = k->x0;
    pd.param[DAL_PENDULUM_Y0] = k->y0;
  } else {
    pd.prim = &dal_map_hanging;
    pd.parent = parent;
    pd.param[DAL_HANGING_L] = l;
  }
  return dal_builder_place_def(b, p, &pd);
}

int scn_add_swing(dal_builder *b, const scn_knobs *k, const char *name, double m, int parent,
                  double l, const char *coord, int *p) {
  int c, rc = dal_builder_add_coord(b, coord, &c);
  if (!rc) rc = dal_builder_add_particle(b, name, m, p);
  return rc ? rc : scn_place_swing(b, k, *p, parent, l, c);
}

// particle `name` (mass m) in its own d Cartesian coordinates named nm[0 .. d)
static int add_cartesian(dal_builder *b, const char *name, double m, const char *const *nm, int d,
                         int *p) {
  int c[3], rc = DAL_OK;
  for (int i = 0; i < d && !rc; ++i)
    rc = dal_builder_add_coord(b, nm[i], &c[i]);
  if (!rc) rc = dal_builder_add_particle(b, name, m, p);
  dal_place_def pd = dal_default_place_def();
  pd.prim = d == 2 ? &dal_map_cartesian2 : &dal_map_cartesian3;
  pd.coords = c;
  pd.ncoords = d;
  if (!rc) rc = dal_builder_place_def(b, *p, &pd);
  return rc;
}

int scn_add_xy(dal_builder *b, const char *name, double m, const char *xname, const char *yname,
               int *p) {
  const char *nm[2] = {xname, yname};
  return add_cartesian(b, name, m, nm, 2, p);
}

int scn_add_xyz(dal_builder *b, const char *name, double m, int *p) {
  static const char *const nm[3] = {"x", "y", "z"};
  return add_cartesian(b, name, m, nm, 3, p);
}

int scn_add_rod(dal_builder *b, const char *name, int a, int b2, double l, const scn_knobs *k) {
  KNOBS(k);
  int parts[2] = {a, b2};
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = name;
  cd.parts = parts;
  if (b2 < 0) {
    cd.prim = &dal_con_anchor2;
    cd.nparts = 1;
    cd.param[DAL_ANCHOR_L] = l;
    cd.param[DAL_ANCHOR_X0] = k->x0;
    cd.param[DAL_ANCHOR_Y0] = k->y0;
    cd.ctx = (void *)k->pivot;
  } else {
    cd.prim = &dal_con_distance2;
    cd.nparts = 2;
    cd.param[DAL_DISTANCE_L] = l;
  }
  return dal_builder_add_constraint_def(b, &cd, NULL);
}

dal_system *scn_pendulum(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int p, rc = scn_builder(k, 2, &b);
  if (!rc) rc = scn_add_swing(b, k, "bob", k->m, -1, k->l, "theta", &p);
  return scn_finish(b, rc);
}

dal_system *scn_cart_pendulum(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int p, rc = scn_builder(k, 2, &b);
  if (!rc) rc = scn_add_xy(b, "bob", k->m, "x", "y", &p);
  if (!rc) rc = scn_add_rod(b, "rod", p, -1, k->l, k);
  return scn_finish(b, rc);
}

dal_system *scn_double_pendulum(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int p[2], rc = scn_builder(k, 2, &b);
  if (!rc) rc = scn_add_swing(b, k, "upper", k->m, -1, k->l, "theta1", &p[0]);
  if (!rc) rc = scn_add_swing(b, k, "lower", k->m2, p[0], k->l2, "theta2", &p[1]);
  return scn_finish(b, rc);
}

dal_system *scn_cart_double_pendulum(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int p[2], rc = scn_builder(k, 2, &b);
  if (!rc) rc = scn_add_xy(b, "upper", k->m, "x1", "y1", &p[0]);
  if (!rc) rc = scn_add_xy(b, "lower", k->m2, "x2", "y2", &p[1]);
  if (!rc) rc = scn_add_rod(b, "rod1", p[0], -1, k->l, k);
  if (!rc) rc = scn_add_rod(b, "rod2", p[0], p[1], k->l2, k);
  return scn_finish(b, rc);
}

dal_system *scn_bead(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int c, p, rc = scn_builder(k, 3, &b);
  if (!rc) rc = dal_builder_add_coord(b, "theta", &c);
  if (!rc) rc = dal_builder_add_particle(b, "bead", k->m, &p);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_ring;
  pd.coords = &c;
  pd.ncoords = 1;
  pd.param[DAL_RING_R] = k->R;
  pd.param[DAL_RING_W] = k->spin;
  pd.param[DAL_RING_PHI0] = k->phi0;
  if (!rc) rc = dal_builder_place_def(b, p, &pd);
  return scn_finish(b, rc);
}

// one particle in (x, y, z) under gravity held by one constraint: the spherical pendulum's rod
// "rod" (anchor3: l to (x0, y0, z0)) on "bob", or the bead's turning circle "ring" (R, spin)
static dal_system *cart3(const scn_knobs *k, int rod) {
  dal_builder *b = NULL;
  int p, rc = scn_builder(k, 3, &b);
  if (!rc) rc = scn_add_xyz(b, rod ? "bob" : "bead", k->m, &p);
  dal_constraint_def cd = dal_default_constraint_def();
  cd.parts = &p;
  cd.nparts = 1;
  if (rod) {
    cd.name = "rod";
    cd.prim = &dal_con_anchor3;
    cd.param[DAL_ANCHOR_L] = k->l;
    cd.param[DAL_ANCHOR_X0] = k->x0;
    cd.param[DAL_ANCHOR_Y0] = k->y0;
    cd.param[DAL_ANCHOR_Z0] = k->z0;
  } else {
    cd.name = "ring";
    cd.prim = &dal_con_turning_circle;
    cd.param[DAL_TURNING_CIRCLE_R] = k->R;
    cd.param[DAL_TURNING_CIRCLE_W] = k->spin;
  }
  if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
  return scn_finish(b, rc);
}

dal_system *scn_cart_bead(const scn_knobs *k) {
  KNOBS(k);
  return cart3(k, 0);
}

int scn_add_spherical(dal_builder *b, const scn_knobs *k, int *p) {
  KNOBS(k);
  int c[2], rc = dal_builder_add_coord(b, "theta", &c[0]);
  if (!rc) rc = dal_builder_add_coord(b, "phi", &c[1]);
  if (!rc) rc = dal_builder_add_particle(b, "bob", k->m, p);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_spherical;
  pd.coords = c;
  pd.ncoords = 2;
  pd.param[DAL_SPHERICAL_L] = k->l;
  pd.param[DAL_SPHERICAL_X0] = k->x0;
  pd.param[DAL_SPHERICAL_Y0] = k->y0;
  pd.param[DAL_SPHERICAL_Z0] = k->z0;
  if (!rc) rc = dal_builder_place_def(b, *p, &pd);
  return rc;
}

dal_system *scn_spherical(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int p, rc = scn_builder(k, 3, &b);
  if (!rc) rc = scn_add_spherical(b, k, &p);
  return scn_finish(b, rc);
}

dal_system *scn_cart_spherical(const scn_knobs *k) {
  KNOBS(k);
  return cart3(k, 1);
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

// the trap's potential in the turning components of r
static int trap_pot(const dal_jet *r, dal_jet t, dal_jet *U, void *ctx) {
  const scn_trap *tr = ctx;
  dal_jet s, c;
  dal_sincos(dal_scale(t, tr->w), &s, &c);
  dal_jet xp = dal_add(dal_mul(r[0], c), dal_mul(r[1], s));
  dal_jet yp = dal_sub(dal_mul(r[1], c), dal_mul(r[0], s));
  *U = dal_add(dal_scale(dal_sq(xp), 0.5 * tr->k1), dal_scale(dal_sq(yp), 0.5 * tr->k2));
  return 0;
}

dal_system *scn_rotating_trap(const scn_trap *tr, double m) {
  scn_knobs free = scn_weightless();
  dal_builder *b = NULL;
  int q[2], p, rc = scn_builder(&free, 2, &b);
  if (!rc) rc = dal_builder_add_coord(b, "x", &q[0]);
  if (!rc) rc = dal_builder_add_coord(b, "y", &q[1]);
  if (!rc) rc = dal_builder_add_particle(b, "ion", m, &p);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &prim_rotating;
  pd.coords = q;
  pd.ncoords = 2;
  pd.param[0] = tr->w;
  if (!rc) rc = dal_builder_place_def(b, p, &pd);
  if (!rc) rc = dal_builder_add_potential_r(b, trap_pot, (void *)tr);
  return scn_finish(b, rc);
}

// "bob" in (x, y) on a spring of stiffness k to the origin: of zero length without gravity
// (the oscillator), or hanging (rest length l, gravity, a damper c unless c = 0)
static dal_system *spring_bob(const scn_knobs *k, int hanging) {
  scn_knobs kk = *k;
  if (!hanging) kk.g = 0.0;
  dal_builder *b = NULL;
  int p, rc = scn_builder(&kk, 2, &b);
  if (!rc) rc = scn_add_xy(b, "bob", k->m, "x", "y", &p);
  dal_spring_def sd = dal_default_spring_def();
  sd.a = p;
  sd.k = k->k;
  if (hanging) sd.length = k->l;
  if (!rc) rc = dal_builder_add_spring_def(b, &sd);
  dal_damper_def dd = dal_default_damper_def();
  dd.a = p;
  dd.c = k->c;
  if (!rc && hanging && k->c != 0.0) rc = dal_builder_add_damper_def(b, &dd);
  return scn_finish(b, rc);
}

dal_system *scn_oscillator(const scn_knobs *k) {
  KNOBS(k);
  return spring_bob(k, 0);
}

dal_system *scn_hanging_spring(const scn_knobs *k) {
  KNOBS(k);
  return spring_bob(k, 1);
}

dal_system *scn_chain(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int p = -1, rc = scn_builder(k, 2, &b);
  for (int i = 0; i < k->N && !rc; ++i) {
    char name[16], coord[16];
    snprintf(name, sizeof name, "p%d", i);
    snprintf(coord, sizeof coord, "th%d", i);
    rc = scn_add_swing(b, k, name, k->m, p, k->l, coord, &p);
  }
  return scn_finish(b, rc);
}

dal_system *scn_cart_chain(const scn_knobs *k) {
  KNOBS(k);
  dal_builder *b = NULL;
  int prev = -1, rc = scn_builder(k, 2, &b);
  for (int i = 0; i < k->N && !rc; ++i) {
    char name[16], x[16], y[16], r[16];
    snprintf(name, sizeof name, "p%d", i);
    snprintf(x, sizeof x, "x%d", i);
    snprintf(y, sizeof y, "y%d", i);
    snprintf(r, sizeof r, "rod%d", i);
    int p;
    rc = scn_add_xy(b, name, k->m, x, y, &p);
    if (!rc) rc = scn_add_rod(b, r, i == 0 ? p : prev, i == 0 ? -1 : p, k->l, k);
    prev = p;
  }
  return scn_finish(b, rc);
}

dal_system *scn_fourbar(const scn_knobs *k, int cart, double th1, double w1, double *q,
                        double *qd) {
  KNOBS(k);
  const double a = 1.0, bl = 3.5, c = 2.0, Dx = 3.0;
  double B[2] = {a * sin(th1), -a * cos(th1)};
  // C on circle(B, bl) and circle(D, c), the lower intersection
  double dx = Dx - B[0], dy = -B[1], dd = sqrt(dx * dx + dy * dy);
  double al = (bl * bl - c * c + dd * dd) / (2 * dd), h = sqrt(bl * bl - al * al);
  double C[2] = {B[0] + al * dx / dd + h * dy / dd, B[1] + al * dy / dd - h * dx / dd};
  double th2 = atan2(C[0] - B[0], -(C[1] - B[1]));
  // closure (C - D) . Cdot = 0 gives the coupler rate
  double e1[2] = {cos(th1), sin(th1)}, e2[2] = {cos(th2), sin(th2)};
  double CD[2] = {C[0] - Dx, C[1]};
  double w2 = -a * w1 * (CD[0] * e1[0] + CD[1] * e1[1]) / (bl * (CD[0] * e2[0] + CD[1] * e2[1]));
  double Bd[2] = {a * w1 * e1[0], a * w1 * e1[1]};
  double Cd[2] = {Bd[0] + bl * w2 * e2[0], Bd[1] + bl * w2 * e2[1]};
  // the ground pivots: A at the origin, D at (Dx, 0)
  scn_knobs ground = *k;
  ground.x0 = ground.y0 = ground.ax = ground.ay = 0.0;
  ground.pivot = NULL;
  dal_builder *b = NULL;
  int p[2], rc = scn_builder(k, 2, &b);
  if (!cart) {
    if (!rc) rc = scn_add_swing(b, &ground, "B", 1.0, -1, a, "crank", &p[0]);
    if (!rc) rc = scn_add_swing(b, &ground, "C", 2.0, p[0], bl, "coupler", &p[1]);
    q[0] = th1, q[1] = th2, qd[0] = w1, qd[1] = w2;
  } else {
    if (!rc) rc = scn_add_xy(b, "B", 1.0, "xB", "yB", &p[0]);
    if (!rc) rc = scn_add_xy(b, "C", 2.0, "xC", "yC", &p[1]);
    if (!rc) rc = scn_add_rod(b, "AB", p[0], -1, a, &ground);
    if (!rc) rc = scn_add_rod(b, "BC", p[0], p[1], bl, &ground);
    q[0] = B[0], q[1] = B[1], q[2] = C[0], q[3] = C[1];
    qd[0] = Bd[0], qd[1] = Bd[1], qd[2] = Cd[0], qd[3] = Cd[1];
  }
  ground.x0 = Dx;
  if (!rc) rc = scn_add_rod(b, "CD", p[1], -1, c, &ground);
  return scn_finish(b, rc);
}

dal_system *scn_held_chain(const scn_knobs *k, int cart, double *q, double *qd) {
  KNOBS(k);
  const int NL = k->N;
  const double al = PI / 3.0;
  double span = NL * sin(al), x = 0.0, y = 0.0;
  scn_knobs ground = *k;
  ground.x0 = ground.y0 = ground.ax = ground.ay = 0.0;
  ground.pivot = NULL;
  dal_builder *b = NULL;
  int rc = scn_builder(k, 2, &b), prev = -1;
  for (int i = 0; i < NL - 1 && !rc; ++i) {
    double th = i < NL / 2 ? al : PI - al;
    char name[16], cx[16], cy[16];
    int p;
    x += sin(th);
    y -= cos(th);
    snprintf(name, sizeof name, "p%d", i);
    if (!cart) {
      // unit links: a pendulum about A at the origin, then each hanging from the previous
      snprintf(cx, sizeof cx, "th%d", i);
      rc = scn_add_swing(b, &ground, name, 1.0, prev, 1.0, cx, &p);
      q[i] = th;
      qd[i] = 0.0;
    } else {
      // unit rods: the first to A at the origin, then between neighbours
      snprintf(cx, sizeof cx, "x%d", i);
      snprintf(cy, sizeof cy, "y%d", i);
      rc = scn_add_xy(b, name, 1.0, cx, cy, &p);
      if (!rc) rc = scn_add_rod(b, NULL, i == 0 ? p : prev, i == 0 ? -1 : p, 1.0, &ground);
      q[2 * i] = x, q[2 * i + 1] = y;
      qd[2 * i] = qd[2 * i + 1] = 0.0;
    }
    prev = p;
  }
  ground.x0 = span; // the last unit rod to B = (span, 0)
  if (!rc) rc = scn_add_rod(b, "held", prev, -1, 1.0, &ground);
  return scn_finish(b, rc);
}

dal_system *scn_closed_loop(const scn_knobs *k, double link) {
  KNOBS(k);
  dal_builder *b = NULL;
  int p[2], rc = scn_builder(k, 2, &b);
  if (!rc) rc = scn_add_xy(b, "p", k->m, NULL, NULL, &p[0]);
  if (!rc) rc = scn_add_xy(b, "s", k->m2, NULL, NULL, &p[1]);
  if (!rc) rc = scn_add_rod(b, "rod", p[0], -1, k->l, k);
  dal_constraint_def cd = dal_default_constraint_def();
  cd.name = "ring";
  cd.prim = &dal_con_circle2;
  cd.parts = &p[1];
  cd.nparts = 1;
  cd.param[DAL_CIRCLE_R] = k->R;
  if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
  if (!rc) rc = scn_add_rod(b, "link", p[0], p[1], link, k);
  return scn_finish(b, rc);
}

void scn_rk4_replica(const double *y0, double T, double H, int naive, double *out) {
  long double y[4] = {y0[0], y0[1], y0[2], y0[3]}, c[4] = {0, 0, 0, 0};
  double yd[4] = {y0[0], y0[1], y0[2], y0[3]}, t = 0.0;
  while (t < T) {
    double tend = t + H;
    if (tend > T - 1e-9 * H) tend = T;
    double hd = tend - t;
    if (naive) {
      // in double, the update summed directly
      double k[4][4], yt[4];
      for (int s = 0; s < 4; ++s) {
        double a = s == 0 ? 0.0 : s == 3 ? hd : 0.5 * hd;
        for (int i = 0; i < 4; ++i)
          yt[i] = s ? yd[i] + a * k[s - 1][i] : yd[i];
        k[s][0] = yt[2], k[s][1] = yt[3], k[s][2] = -yt[0], k[s][3] = -yt[1];
      }
      for (int i = 0; i < 4; ++i)
        yd[i] = yd[i] + hd / 6.0 * (k[0][i] + 2.0 * (k[1][i] + k[2][i]) + k[3][i]);
    } else {
      // in long double, the update added with Kahan's compensation
      long double h = hd, k[4][4], yt[4];
      for (int s = 0; s < 4; ++s) {
        long double a = s == 0 ? 0.0L : s == 3 ? h : 0.5L * h;
        for (int i = 0; i < 4; ++i)
          yt[i] = s ? y[i] + a * k[s - 1][i] : y[i];
        k[s][0] = yt[2], k[s][1] = yt[3], k[s][2] = -yt[0], k[s][3] = -yt[1];
      }
      for (int i = 0; i < 4; ++i) {
        long double d = h * (k[0][i] + 2 * (k[1][i] + k[2][i]) + k[3][i]) / 6 - c[i];
        long double s = y[i] + d;
        c[i] = (s - y[i]) - d;
        y[i] = s;
      }
    }
    t = tend;
  }
  for (int i = 0; i < 4; ++i)
    out[i] = naive ? yd[i] : (double)y[i];
}

dal_solve_opts scn_opts(dal_formulation f, dal_method m, double tol) {
  dal_solve_opts o = dal_default_solve_opts();
  o.form = f;
  o.method = m;
  o.rtol = o.atol = tol;
  return o;
}

int scn_sum_q0(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  *(double *)ctx += dal_state_q(st)[0];
  return 0;
}

int scn_sum_energy(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  dal_energies e;
  if (dal_state_energies(st, &e)) return -1;
  *(double *)ctx += e.E;
  return 0;
}
