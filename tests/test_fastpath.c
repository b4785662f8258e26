// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// White box: the hand-coded fast paths of kinematics.c (particles placed by their own
// Cartesian coordinates, particles hanging from their parent by dal_map_hanging; rods
// dal_con_distance2/3 and fixed dal_con_anchor2/3) against the jet
// path they replace. The same scene is built twice, once with the built-in primitives and once
// with copies of their tables (another address, so the library evaluates them by jets); every
// kinematic and constraint product, the accelerations and multipliers, the DAE residual and
// the Newton matrix must agree bit for bit, and a zero-length rod must fail alike.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "form/form.h"

static unsigned seed = 2024u;
static double urand(void) {
  seed = seed * 1103515245u + 12345u;
  return ((seed >> 8) & 0xffffff) / 16777215.0 - 0.5;
}

// a moving anchor (the jet path in both builds)
static int wobble(dal_jet t, dal_jet *x, void *ctx) {
  (void)ctx;
  x[0] = dal_scale(dal_sin(dal_scale(t, 3.0)), 0.3);
  x[1] = dal_scale(dal_cos(dal_scale(t, 2.0)), 0.2);
  x[2] = dal_scale(t, 0.1);
  return 0;
}
static dal_moving_point mover = {wobble, NULL};

// the jet-path twins: same tables at other addresses
static dal_primitive cart2, cart3, dist2, dist3, anch2, anch3, hang2;

// A d-dimensional scene of np particles: the first placed by Cartesian coordinates, every
// third hanging from its predecessor by a pendulum-like map (not Cartesian: exercises the
// chained G), rods between neighbours, a fixed anchor on particle 0 and a moving one on the
// last; jets = 1 builds with the twins.
static dal_system *scene(int d, int np, int jets) {
  const dal_primitive *cart =
      jets ? (d == 2 ? &cart2 : &cart3) : (d == 2 ? &dal_map_cartesian2 : &dal_map_cartesian3);
  const dal_primitive *dist =
      jets ? (d == 2 ? &dist2 : &dist3) : (d == 2 ? &dal_con_distance2 : &dal_con_distance3);
  const dal_primitive *anch =
      jets ? (d == 2 ? &anch2 : &anch3) : (d == 2 ? &dal_con_anchor2 : &dal_con_anchor3);
  dal_builder *b = NULL;
  dal_system *s = NULL;
  int rc = dal_builder_create(d, &b);
  double g[3] = {0.0, -9.81, 0.0};
  int rodq[6], nrodq = 0; // coordinates of particles 0 and 3 (a rod given on coordinates)
  if (d == 3) g[1] = 0.0, g[2] = -9.81;
  if (!rc) rc = dal_builder_set_gravity(b, g);
  for (int k = 0; k < np && !rc; ++k) {
    char name[32];
    int p, c[3];
    snprintf(name, sizeof name, "p%d", k);
    rc = dal_builder_add_particle(b, name, 0.5 + k * 0.25, &p);
    int hang = k % 3 == 2;
    for (int a = 0; a < (hang ? 1 : d) && !rc; ++a) {
      snprintf(name, sizeof name, "q%d_%d", k, a);
      rc = dal_builder_add_coord(b, name, &c[a]);
    }
    dal_place_def pd = dal_default_place_def();
    if (hang) {
      pd.prim = jets ? &hang2 : &dal_map_hanging;
      pd.parent = p - 1;
      pd.param[DAL_HANGING_L] = 0.8;
      pd.coords = c;
      pd.ncoords = 1;
      if (d == 3) {
        // hanging is planar; in 3D place it by Cartesian coordinates as well
        pd = dal_default_place_def();
        pd.prim = cart;
        for (int a = 1; a < d && !rc; ++a) {
          snprintf(name, sizeof name, "q%d_%d", k, a);
          rc = dal_builder_add_coord(b, name, &c[a]);
        }
        pd.coords = c;
        pd.ncoords = d;
      }
    } else {
      pd.prim = cart;
      pd.coords = c;
      pd.ncoords = d;
    }
    if (!rc) rc = dal_builder_place_def(b, p, &pd);
    for (int a = 0; a < d && (k == 0 || k == 3) && !hang; ++a)
      rodq[nrodq++] = c[a];
    dal_constraint_def cd = dal_default_constraint_def();
    int ends[2] = {p - 1, p};
    snprintf(name, sizeof name, "rod%d", k);
    cd.name = name;
    if (k == 0) {
      cd.prim = anch;
      cd.parts = &ends[1];
      cd.nparts = 1;
      cd.param[DAL_ANCHOR_L] = 1.1;
      cd.param[DAL_ANCHOR_X0] = 0.2;
      cd.param[DAL_ANCHOR_Y0] = -0.1;
    } else if (!hang) {
      cd.prim = dist;
      cd.parts = ends;
      cd.nparts = 2;
      cd.param[DAL_DISTANCE_L] = 0.9;
    }
    if (!rc && cd.prim) rc = dal_builder_add_constraint_def(b, &cd, NULL);
  }
  // a moving anchor on the last particle
  dal_constraint_def cd = dal_default_constraint_def();
  int last = np - 1;
  cd.name = "moving";
  cd.prim = anch;
  cd.parts = &last;
  cd.nparts = 1;
  cd.param[DAL_ANCHOR_L] = 2.0;
  cd.ctx = &mover;
  if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
  // a rod whose inputs are coordinates, not particles (the jet path in both builds)
  if (nrodq == 2 * d) {
    cd = dal_default_constraint_def();
    cd.name = "on-coordinates";
    cd.prim = dist;
    cd.coords = rodq;
    cd.ncoords = 2 * d;
    cd.param[DAL_DISTANCE_L] = 1.7;
    if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
  }
  if (!rc) rc = dal_builder_set_dynamics(b, DAL_DYNAMICS_DENSE);
  if (!rc) rc = dal_builder_compile(b, &s);
  if (rc) fprintf(stderr, "scene: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return s;
}

static int same(const double *a, const double *b, size_t n, const char *what, int d) {
  for (size_t i = 0; i < n; ++i)
    if (!(a[i] == b[i]) && !(isnan(a[i]) && isnan(b[i]))) {
      fprintf(stderr, "d=%d %s[%zu]: fast %.17g, jets %.17g\n", d, what, i, a[i], b[i]);
      return 0;
    }
  return 1;
}

static void compare(int d, int np) {
  dal_system *fs = scene(d, np, 0), *js = scene(d, np, 1);
  CHECK(fs && js);
  if (!fs || !js) return;
  dal_state *fst = NULL, *jst = NULL;
  CHECK_OK(dal_state_create(fs, &fst));
  CHECK_OK(dal_state_create(js, &jst));
  int n = fs->n, m = fs->m, Nd = fs->N * d;
  double *q = malloc((size_t)n * sizeof(double)), *qd = malloc((size_t)n * sizeof(double));
  for (int i = 0; i < n; ++i) {
    q[i] = 2.0 * urand();
    qd[i] = 3.0 * urand();
  }
  CHECK_OK(dal_state_set(fs, fst, 0.3, q, qd));
  CHECK_OK(dal_state_set(js, jst, 0.3, q, qd));
  // dal_forward: kinematics, constraint rows, dynamics, the KKT solve, outputs
  CHECK_OK(dal_forward(fs, fst));
  CHECK_OK(dal_forward(js, jst));
  CHECK(same(fst->r, jst->r, Nd, "r", d));
  CHECK(same(fst->v, jst->v, Nd, "v", d));
  CHECK(same(fst->gamma, jst->gamma, Nd, "gamma", d));
  CHECK(same(fst->drdt, jst->drdt, Nd, "drdt", d));
  CHECK(same(fst->J, jst->J, fs->pj_off[fs->N], "J", d));
  CHECK(same(fst->Lc, jst->Lc, fs->ploc_off[fs->N], "Lc", d));
  CHECK(same(fst->phi, jst->phi, m, "phi", d));
  CHECK(same(fst->phidot, jst->phidot, m, "phidot", d));
  CHECK(same(fst->gphi, jst->gphi, m, "gamma_phi", d));
  CHECK(same(fst->G, jst->G, fs->g_total, "G", d));
  CHECK(same(fst->Gl, jst->Gl, fs->con_loff[fs->ncon], "G local", d));
  CHECK(same(fst->qddot, jst->qddot, n, "qddot", d));
  CHECK(same(fst->lambda, jst->lambda, m, "lambda", d));
  CHECK(same(fst->a, jst->a, Nd, "a", d));
  // the GGL residual and its Newton matrix (the Jacobian reads the constraint rows too)
  dal_dae ff, jf;
  CHECK(dal__dae_init(&ff, fs, fst, DAL_FORM_GGL, 0.0, 0.0, 0) == 0);
  CHECK(dal__dae_init(&jf, js, jst, DAL_FORM_GGL, 0.0, 0.0, 0) == 0);
  int neq = ff.neq;
  double *y = malloc((size_t)neq * sizeof(double)), *yp = malloc((size_t)neq * sizeof(double));
  double *F1 = malloc((size_t)neq * sizeof(double)), *F2 = malloc((size_t)neq * sizeof(double));
  double *A1 = calloc((size_t)neq * neq, sizeof(double));
  double *A2 = calloc((size_t)neq * neq, sizeof(double));
  for (int i = 0; i < neq; ++i) {
    y[i] = i < 2 * n ? (i < n ? q[i] : qd[i - n]) : urand();
    yp[i] = urand();
  }
  CHECK(dal__dae_residual(&ff, 0.7, y, yp, F1) == 0);
  CHECK(dal__dae_residual(&jf, 0.7, y, yp, F2) == 0);
  CHECK(same(F1, F2, neq, "GGL residual", d));
  dal_dae_sink s1 = {DAL_SINK_DENSE, 0, NULL, A1}, s2 = {DAL_SINK_DENSE, 0, NULL, A2};
  CHECK(dal__dae_newton(&ff, 0.7, 13.0, y, &s1) == 0);
  CHECK(dal__dae_newton(&jf, 0.7, 13.0, y, &s2) == 0);
  CHECK(same(A1, A2, (size_t)neq * neq, "Newton matrix", d));
  // a zero-length rod: the fast path hands over to the jet path, which names it
  memcpy(q + d, q, (size_t)d * sizeof(double)); // particle 1 on particle 0 (rod1)
  CHECK_OK(dal_state_set(fs, fst, 0.3, q, qd));
  CHECK_OK(dal_state_set(js, jst, 0.3, q, qd));
  int r1 = dal_forward(fs, fst), r2 = dal_forward(js, jst);
  CHECK(r1 == DAL_E_DOMAIN && r2 == r1);
  CHECK_MSG(strcmp(dal_state_errmsg(fst), dal_state_errmsg(jst)) == 0 &&
                strstr(dal_state_errmsg(fst), "'rod1'"),
            "fast: %s\njets: %s", dal_state_errmsg(fst), dal_state_errmsg(jst));
  printf("  d = %d, %d particles, %d coordinates, %d rods: fast path == jet path (bit for bit)\n",
         d, np, n, m);
  free(q);
  free(qd);
  free(y);
  free(yp);
  free(F1);
  free(F2);
  free(A1);
  free(A2);
  dal__dae_free(&ff);
  dal__dae_free(&jf);
  dal_state_destroy(fst);
  dal_state_destroy(jst);
  dal_system_destroy(fs);
  dal_system_destroy(js);
}

// a planar pendulum chain in minimal coordinates (links hanging from links; the recursion)
static dal_system *chain(int N, int jets) {
  dal_builder *b = NULL;
  dal_system *s = NULL;
  int rc = dal_builder_create(2, &b);
  double g[2] = {0.0, -9.81};
  for (int k = 0; k < N && !rc; ++k) {
    char name[32];
    int p, c;
    snprintf(name, sizeof name, "th%d", k);
    rc = dal_builder_add_coord(b, name, &c);
    snprintf(name, sizeof name, "p%d", k);
    if (!rc) rc = dal_builder_add_particle(b, name, 1.0 + 0.1 * k, &p);
    dal_place_def pd = dal_default_place_def();
    pd.coords = &c;
    pd.ncoords = 1;
    if (k == 0) {
      pd.prim = &dal_map_pendulum;
      pd.param[DAL_PENDULUM_L] = 1.2;
    } else {
      pd.prim = jets ? &hang2 : &dal_map_hanging;
      pd.parent = p - 1;
      pd.param[DAL_HANGING_L] = 0.5 + 0.1 * k;
    }
    if (!rc) rc = dal_builder_place_def(b, p, &pd);
  }
  if (!rc) rc = dal_builder_set_gravity(b, g);
  if (!rc) rc = dal_builder_compile(b, &s);
  if (rc) fprintf(stderr, "chain: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return s;
}

static void compare_chain(int N) {
  dal_system *fs = chain(N, 0), *js = chain(N, 1);
  CHECK(fs && js);
  if (!fs || !js) return;
  dal_state *fst = NULL, *jst = NULL;
  CHECK_OK(dal_state_create(fs, &fst));
  CHECK_OK(dal_state_create(js, &jst));
  double q[16], qd[16];
  for (int i = 0; i < N; ++i) {
    q[i] = 3.0 * urand();
    qd[i] = 4.0 * urand();
  }
  CHECK_OK(dal_state_set(fs, fst, 0.1, q, qd));
  CHECK_OK(dal_state_set(js, jst, 0.1, q, qd));
  CHECK_OK(dal_forward(fs, fst));
  CHECK_OK(dal_forward(js, jst));
  int Nd = 2 * N;
  CHECK(same(fst->r, jst->r, Nd, "chain r", 2));
  CHECK(same(fst->v, jst->v, Nd, "chain v", 2));
  CHECK(same(fst->gamma, jst->gamma, Nd, "chain gamma", 2));
  CHECK(same(fst->drdt, jst->drdt, Nd, "chain drdt", 2));
  CHECK(same(fst->Lc, jst->Lc, fs->ploc_off[N], "chain Lc", 2));
  CHECK(same(fst->Lp, jst->Lp, 4 * (size_t)N, "chain Lp", 2));
  CHECK(same(fst->qddot, jst->qddot, N, "chain qddot", 2));
  CHECK(same(fst->a, jst->a, Nd, "chain a", 2));
  CHECK(same(fst->N, jst->N, Nd, "chain reactions", 2));
  CHECK(fst->en.E == jst->en.E && fst->en.h == jst->en.h);
  printf("  pendulum chain of %d links (the recursion): fast path == jet path (bit for bit)\n", N);
  dal_state_destroy(fst);
  dal_state_destroy(jst);
  dal_system_destroy(fs);
  dal_system_destroy(js);
}

int main(void) {
  cart2 = dal_map_cartesian2, cart3 = dal_map_cartesian3;
  dist2 = dal_con_distance2, dist3 = dal_con_distance3;
  anch2 = dal_con_anchor2, anch3 = dal_con_anchor3, hang2 = dal_map_hanging;
  for (int d = 2; d <= 3; ++d) {
    compare(d, 2);
    compare(d, 7);
  }
  compare_chain(2);
  compare_chain(9);
  return check_summary("test_fastpath");
}
