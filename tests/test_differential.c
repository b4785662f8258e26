// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Differential test: seeded random planar trees of particles on rods (with gravity and a
// spring), built twice: in minimal coordinates (an angle per rod: dal_map_pendulum at the
// root, dal_map_hanging below) and in Cartesian coordinates tied by rods (dal_con_anchor2,
// dal_con_distance2). Every method and formulation integrates each scene to t = T; the
// particle positions are compared with a tight reference of the other kind: Bulirsch-Stoer at
// rtol 1e-12 in minimal coordinates (its own error is measured against the Cartesian form
// below). The table is printed.
//
// Bounds, and where they come from:
//  - adaptive methods: the documented one (solve.h, README "What a tolerance buys"): the
//    error stays within 16 x rtol (positions of order 1 m: 16 rtol max(1, |r|)). Two
//    formulations are documented to exceed it and are held to their documented figures
//    instead, printed as such: index-1 in IDA (no stabilization: "drifts: 47 to 1e-9") and
//    index-3 in IDA ("2e2 - 2e4 to 1e-9, kept to show where it fails");
//  - fixed-step methods (RK4, the variational and RATTLE compositions of order p): 16 x the
//    Richardson estimate |x_h - x_{h/2}| 2^p / (2^p - 1) of the error of the h run, which is
//    independent of the reference; the reference then checks the estimate.
// A DAL_OK beyond its bound fails the test; so does any status other than DAL_OK.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

#define MAXN 4
#define T_END 2.0
#define BOUND 16.0

typedef struct tree {
  int N;
  int parent[MAXN]; // -1: hung from the pivot
  double L[MAXN], m[MAXN], th[MAXN], om[MAXN], pivot[2], k, Ls;
} tree;

static const double grav[2] = {0.0, -9.81};

static tree random_tree(unsigned long long seed) {
  tree t;
  memset(&t, 0, sizeof t);
  unsigned long long s = seed * 0x9e3779b97f4a7c15ULL + 1;
  t.N = 2 + (int)check_rand(&s, 0, 3); // 2 ... 4 particles
  if (t.N > MAXN) t.N = MAXN;
  t.pivot[0] = check_rand(&s, -0.5, 0.5);
  t.pivot[1] = check_rand(&s, -0.5, 0.5);
  for (int k = 0; k < t.N; ++k) {
    t.parent[k] = k == 0 ? -1 : (int)check_rand(&s, -1, k); // a root or an earlier particle
    if (t.parent[k] >= k) t.parent[k] = k - 1;
    t.L[k] = check_rand(&s, 0.5, 1.5);
    t.m[k] = check_rand(&s, 0.5, 2.0);
    t.th[k] = check_rand(&s, -1.0, 1.0);
    t.om[k] = check_rand(&s, -1.0, 1.0);
  }
  t.k = check_rand(&s, 0.5, 5.0); // a spring between the first and the last particle
  t.Ls = check_rand(&s, 0.2, 1.0);
  return t;
}

// absolute positions and velocities of the tree's particles from the angles
static void tree_rv(const tree *t, double *r, double *v) {
  for (int k = 0; k < t->N; ++k) {
    int p = t->parent[k];
    double px = p < 0 ? t->pivot[0] : r[2 * p], py = p < 0 ? t->pivot[1] : r[2 * p + 1];
    double vx = p < 0 ? 0.0 : v[2 * p], vy = p < 0 ? 0.0 : v[2 * p + 1];
    double s = sin(t->th[k]), c = cos(t->th[k]);
    r[2 * k] = px + t->L[k] * s;
    r[2 * k + 1] = py - t->L[k] * c;
    v[2 * k] = vx + t->L[k] * c * t->om[k];
    v[2 * k + 1] = vy + t->L[k] * s * t->om[k];
  }
}

static int add_spring(dal_builder *b, const tree *t) {
  dal_spring_def sd = dal_default_spring_def();
  sd.a = 0;
  sd.b = t->N - 1;
  sd.k = t->k;
  sd.length = t->Ls;
  return dal_builder_add_spring_def(b, &sd);
}

// the scene library's knobs with the tree's pivot (the anchor of its roots)
static scn_knobs pivot_knobs(const tree *t) {
  scn_knobs k = scn_default();
  k.x0 = t->pivot[0];
  k.y0 = t->pivot[1];
  return k;
}

// the tree in its angles
static int build_minimal(const tree *t, dal_system **sys, dal_state **st) {
  dal_builder *b;
  scn_knobs kp = pivot_knobs(t);
  int rc = dal_builder_create(2, &b), c[MAXN], p[MAXN];
  char nm[16];
  for (int k = 0; k < t->N && !rc; ++k) {
    snprintf(nm, sizeof nm, "th%d", k);
    rc = dal_builder_add_coord(b, nm, &c[k]);
    snprintf(nm, sizeof nm, "p%d", k);
    if (!rc) rc = dal_builder_add_particle(b, nm, t->m[k], &p[k]);
    int parent = t->parent[k] < 0 ? -1 : p[t->parent[k]];
    if (!rc) rc = scn_place_swing(b, &kp, p[k], parent, t->L[k], c[k]);
  }
  if (!rc) rc = dal_builder_set_gravity(b, grav);
  if (!rc) rc = add_spring(b, t);
  if (!rc) rc = dal_builder_compile(b, sys);
  if (rc) fprintf(stderr, "minimal build: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  if (!rc) rc = dal_state_create(*sys, st);
  if (!rc) rc = dal_state_set(*sys, *st, 0.0, t->th, t->om);
  return rc;
}

// the tree in Cartesian coordinates with rods
static int build_cartesian(const tree *t, dal_system **sys, dal_state **st) {
  dal_builder *b;
  scn_knobs kp = pivot_knobs(t);
  int rc = dal_builder_create(2, &b), p[MAXN];
  char nm[16];
  for (int k = 0; k < t->N && !rc; ++k) {
    char x[16], y[16];
    snprintf(x, sizeof x, "x%d", k);
    snprintf(y, sizeof y, "y%d", k);
    snprintf(nm, sizeof nm, "p%d", k);
    rc = scn_add_xy(b, nm, t->m[k], x, y, &p[k]);
    snprintf(nm, sizeof nm, "rod%d", k);
    int parent = t->parent[k] < 0 ? -1 : p[t->parent[k]];
    if (!rc) rc = scn_add_rod(b, nm, p[k], parent, t->L[k], &kp);
  }
  if (!rc) rc = dal_builder_set_gravity(b, grav);
  if (!rc) rc = add_spring(b, t);
  if (!rc) rc = dal_builder_compile(b, sys);
  if (rc) fprintf(stderr, "cartesian build: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  double r[2 * MAXN], v[2 * MAXN];
  tree_rv(t, r, v);
  if (!rc) rc = dal_state_create(*sys, st);
  if (!rc) rc = dal_state_set(*sys, *st, 0.0, r, v);
  return rc;
}

// a configuration: coordinates, method, formulation, fixed step (0: adaptive) and its order
typedef struct config {
  int cart;
  dal_method method;
  dal_formulation form;
  double h;
  int order;
  double documented; // a documented bound other than 16 x rtol (0: none)
  int may_refuse;    // documented to fail (index-3): a refusal with a status is not an error
} config;

static const config configs[] = {
    {0, DAL_METHOD_AUTO, DAL_FORM_AUTO, 0, 0, 0, 0},
    {0, DAL_METHOD_DOPRI5, DAL_FORM_ODE, 0, 0, 0, 0},
    {0, DAL_METHOD_FEHLBERG78, DAL_FORM_ODE, 0, 0, 0, 0},
    {0, DAL_METHOD_BS, DAL_FORM_ODE, 0, 0, 0, 0},
    {0, DAL_METHOD_ADAMS, DAL_FORM_ODE, 0, 0, 0, 0},
    {0, DAL_METHOD_BDF, DAL_FORM_ODE, 0, 0, 0, 0},
    {0, DAL_METHOD_RK4, DAL_FORM_ODE, 2e-3, 4, 0, 0},
    {0, DAL_METHOD_VARIATIONAL, DAL_FORM_ODE, 1e-3, 2, 0, 0},
    {0, DAL_METHOD_VARIATIONAL4, DAL_FORM_ODE, 4e-3, 4, 0, 0},
    {0, DAL_METHOD_VARIATIONAL6, DAL_FORM_ODE, 1e-2, 6, 0, 0},
    {1, DAL_METHOD_AUTO, DAL_FORM_AUTO, 0, 0, 0, 0},
    {1, DAL_METHOD_BDF, DAL_FORM_GGL, 0, 0, 0, 0},
    {1, DAL_METHOD_DOPRI5, DAL_FORM_INDEX1, 0, 0, 0, 0},
    {1, DAL_METHOD_FEHLBERG78, DAL_FORM_INDEX1, 0, 0, 0, 0},
    {1, DAL_METHOD_BS, DAL_FORM_INDEX1, 0, 0, 0, 0},
    {1, DAL_METHOD_ADAMS, DAL_FORM_INDEX1, 0, 0, 0, 0},
    {1, DAL_METHOD_BDF, DAL_FORM_INDEX1, 0, 0, 47.0,
     0}, // solve.h: "drifts: 47 to 1e-9, 778 at 1e-10"
    {1, DAL_METHOD_RK4, DAL_FORM_INDEX1, 2e-3, 4, 0, 0},
    {1, DAL_METHOD_BDF, DAL_FORM_INDEX3, 0, 0, 2.2e4, 1}, // solve.h: "2e2 - 2e4 to 1e-9 (kept
                                                          // to show where it fails)"
    {1, DAL_METHOD_RATTLE, DAL_FORM_AUTO, 1e-3, 2, 0, 0},
    {1, DAL_METHOD_RATTLE4, DAL_FORM_AUTO, 4e-3, 4, 0, 0},
    {1, DAL_METHOD_RATTLE6, DAL_FORM_AUTO, 1e-2, 6, 0, 0},
};

// integrate one configuration of one tree at rtol (adaptive) or step h (fixed) to T_END;
// positions into r (2N); status returned
static int run(const tree *t, const config *c, double rtol, double h, double *r, char *msg,
               size_t len) {
  dal_system *sys = NULL;
  dal_state *st = NULL;
  int rc = c->cart ? build_cartesian(t, &sys, &st) : build_minimal(t, &sys, &st);
  if (!rc) {
    dal_solve_opts o = dal_default_solve_opts();
    o.method = c->method;
    o.form = c->form;
    o.rtol = rtol;
    if (h > 0) o.fixed_step = h;
    // index-1 with an explicit method: projection onto the rods (the documented use)
    if (c->form == DAL_FORM_INDEX1 && c->method != DAL_METHOD_BDF) o.project = 1;
    rc = dal_advance(sys, st, &o, T_END);
    if (!rc) memcpy(r, dal_state_positions(st), 2 * (size_t)t->N * sizeof(double));
    snprintf(msg, len, "%s", dal_state_errmsg(st));
  } else {
    snprintf(msg, len, "build failed");
  }
  dal_state_destroy(st);
  dal_system_destroy(sys);
  return rc;
}

static double max_dist(int N, const double *a, const double *b) {
  double e = 0.0;
  for (int k = 0; k < N; ++k)
    e = fmax(e, hypot(a[2 * k] - b[2 * k], a[2 * k + 1] - b[2 * k + 1]));
  return e;
}

int main(void) {
  const int nscenes = 8;
  const double rtols[2] = {1e-6, 1e-9};
  int nconf = (int)(sizeof configs / sizeof configs[0]), over = 0, documented_over = 0;
  char msg[512];
  double worst[sizeof configs / sizeof configs[0]] = {0}; // worst error / (rtol scale) or / bound
  int refused[sizeof configs / sizeof configs[0]] = {0};
  printf("%-6s %-3s %-10s %-8s %-9s %9s %9s %9s  %s\n", "scene", "N", "coords", "form", "method",
         "rtol/h", "error", "bound", "verdict");
  for (int sc = 0; sc < nscenes; ++sc) {
    tree t = random_tree(1000 + (unsigned long long)sc);
    double ref[2 * MAXN], cref[2 * MAXN], scale = 1.0;
    config rc_ref = {0, DAL_METHOD_BS, DAL_FORM_ODE, 0, 0, 0, 0};
    CHECK_OK(run(&t, &rc_ref, 1e-12, 0.0, ref, msg, sizeof msg));
    for (int i = 0; i < 2 * t.N; ++i)
      scale = fmax(scale, fabs(ref[i]));
    // the reference against the other kind at the same tolerance: both within 16e-12
    config cc = {1, DAL_METHOD_BS, DAL_FORM_INDEX1, 0, 0, 0, 0};
    CHECK_OK(run(&t, &cc, 1e-12, 0.0, cref, msg, sizeof msg));
    double eref = max_dist(t.N, ref, cref);
    CHECK_MSG(eref <= 2 * BOUND * 1e-12 * scale, "scene %d: the two references differ by %.3g", sc,
              eref);
    printf("%-6d %-3d %-10s %-8s %-9s %9.1e %9.2e %9.2e  %s\n", sc, t.N, "both", "ode/idx1", "bs",
           1e-12, eref, 2 * BOUND * 1e-12 * scale, "reference");
    for (int ci = 0; ci < nconf; ++ci) {
      const config *c = &configs[ci];
      int nrun = c->h > 0 ? 1 : 2;
      for (int ri = 0; ri < nrun; ++ri) {
        double r[2 * MAXN], rh[2 * MAXN], err, bound;
        double rtol = rtols[ri];
        int rc = run(&t, c, rtol, c->h, r, msg, sizeof msg);
        if (rc == DAL_OK && c->h > 0) {
          // Richardson: the run at h/2 estimates the error of the run at h
          rc = run(&t, c, rtol, 0.5 * c->h, rh, msg, sizeof msg);
          double p2 = pow(2.0, c->order);
          bound = BOUND * max_dist(t.N, r, rh) * p2 / (p2 - 1.0);
          bound = fmax(bound, BOUND * 1e-12 * scale); // the reference's own error
        } else {
          bound = (c->documented > 0 ? c->documented : BOUND) * rtol * scale;
        }
        err = rc == DAL_OK ? max_dist(t.N, r, ref) : NAN;
        const char *verdict = "ok";
        if (rc != DAL_OK && c->may_refuse) {
          verdict = "refused (documented to fail)";
          refused[ci]++;
        } else if (rc != DAL_OK) {
          verdict = "FAILED";
          CHECK_MSG(0, "scene %d %s %s %s: %s (%s)", sc, c->cart ? "cartesian" : "minimal",
                    dal_formulation_name(c->form), dal_method_name(c->method), dal_status_name(rc),
                    msg);
        } else if (!(err <= bound)) {
          verdict = "OVER";
          over++;
          CHECK_MSG(0, "scene %d %s %s %s rtol %g: DAL_OK with error %.3g beyond the bound %.3g",
                    sc, c->cart ? "cartesian" : "minimal", dal_formulation_name(c->form),
                    dal_method_name(c->method), rtol, err, bound);
        } else if (c->documented > 0 && err > BOUND * rtol * scale) {
          verdict = "ok (documented exception: beyond 16 x rtol)";
          documented_over++;
        }
        if (rc == DAL_OK)
          worst[ci] = fmax(worst[ci], c->h > 0 ? err / bound * BOUND : err / (rtol * scale));
        printf("%-6d %-3d %-10s %-8s %-9s %9.1e %9.2e %9.2e  %s\n", sc, t.N,
               c->cart ? "cartesian" : "minimal", dal_formulation_name(c->form),
               dal_method_name(c->method), c->h > 0 ? c->h : rtol, err, bound, verdict);
      }
    }
  }
  // the summary: adaptive rows as worst error / (rtol max(1, |r|)) (bound 16), fixed-step rows
  // as worst error / Richardson estimate (bound 16)
  printf("\nsummary over %d scenes (adaptive: rtol 1e-6 and 1e-9)\n", nscenes);
  printf("%-10s %-8s %-13s %-32s %s\n", "coords", "form", "method", "worst error / (rtol scale)",
         "refused");
  for (int ci = 0; ci < nconf; ++ci) {
    const config *c = &configs[ci];
    printf("%-10s %-8s %-13s %-32.3g %d%s\n", c->cart ? "cartesian" : "minimal",
           dal_formulation_name(c->form), dal_method_name(c->method), worst[ci], refused[ci],
           c->h > 0 ? "  (fixed step: error / Richardson estimate)" : "");
  }
  printf("DAL_OK beyond the bound: %d; documented exceptions beyond 16 x rtol: %d\n", over,
         documented_over);
  return check_summary("test_differential");
}
