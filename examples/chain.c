// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A hanging chain of N particles joined by rods: the sparse DAE (KLU), up to thousands of links.
//
// Problem: N unit masses in the plane, the first on a rod of length 1 to the origin, each next
// one on a rod of length 1 to the previous, gravity g = 9.81, released at rest from 45 degrees
// with the links aligned (the benchmark's chain). Coordinates: the particles' Cartesian (x, y),
// 2N of them; constraints: N rods (dal_con_anchor2, dal_con_distance2). Formulation: GGL in
// IDA; the linear solver is chosen by size (dense below opts.sparse_threshold unknowns, KLU
// with the library-assembled Newton matrix above), or forced by --klu / --dense.
//
// Usage: chain --check | chain [N [T [rtol]]] [--klu | --dense]   (defaults 1024, 1, 1e-6)
// The full mode prints the cost (wall time per simulated second, steps, residual and Jacobian
// evaluations), the largest residuals and the energy change, for the benchmark.
//
// Checks (--check): for N = 4 the chain agrees with the same chain in minimal coordinates (the
// link angles, dal_map_pendulum + dal_map_hanging, Bulirsch-Stoer at 1e-13) to 1000 x rtol
// over 1 s, and the dense and KLU runs agree; for N = 600 (no dense mass matrix: sparse KKT
// and KLU) over 0.05 s the residuals stay below rtol and the energy is conserved to 1e3 x rtol
// relative. Both modes fail when the residuals exceed rtol or the energy drifts.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "dalembert/dalembert.h"
#include "example_util.h"

static const double g = 9.81, PI = 3.14159265358979323846;

static int build(int N, int cartesian, dal_system **sys) {
  dal_builder *b = NULL;
  int rc = dal_builder_create(2, &b), prev = -1;
  double grav[2] = {0.0, -g};
  if (!rc) rc = dal_builder_set_gravity(b, grav);
  for (int k = 0; k < N && !rc; ++k) {
    char name[32];
    int p, c[2];
    snprintf(name, sizeof name, "m%d", k);
    rc = dal_builder_add_particle(b, name, 1.0, &p);
    if (cartesian) {
      snprintf(name, sizeof name, "x%d", k);
      if (!rc) rc = dal_builder_add_coord(b, name, &c[0]);
      snprintf(name, sizeof name, "y%d", k);
      if (!rc) rc = dal_builder_add_coord(b, name, &c[1]);
      dal_place_def pd = dal_default_place_def();
      pd.prim = &dal_map_cartesian2;
      pd.coords = c;
      pd.ncoords = 2;
      if (!rc) rc = dal_builder_place_def(b, p, &pd);
      snprintf(name, sizeof name, "rod%d", k);
      // the first rod to the fixed pivot at the origin, the others between neighbours
      int pp[2];
      dal_constraint_def cd = dal_default_constraint_def();
      cd.name = name;
      if (k == 0) {
        cd.prim = &dal_con_anchor2;
        cd.parts = &p;
        cd.nparts = 1;
        cd.param[DAL_ANCHOR_L] = 1.0;
      } else {
        pp[0] = prev;
        pp[1] = p;
        cd.prim = &dal_con_distance2;
        cd.parts = pp;
        cd.nparts = 2;
        cd.param[DAL_DISTANCE_L] = 1.0;
      }
      if (!rc) rc = dal_builder_add_constraint_def(b, &cd, NULL);
    } else {
      snprintf(name, sizeof name, "theta%d", k);
      if (!rc) rc = dal_builder_add_coord(b, name, &c[0]);
      // the first link swings about the fixed pivot at the origin, the others hang from it
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
    }
    prev = p;
  }
  *sys = ex_compile(b, rc);
  return !*sys;
}

// the Cartesian start: 45 degrees, aligned, at rest
static void start(int N, double *q, double *qd) {
  for (int k = 0; k < N; ++k) {
    q[2 * k] = (k + 1) * sin(PI / 4);
    q[2 * k + 1] = -(k + 1) * cos(PI / 4);
    qd[2 * k] = qd[2 * k + 1] = 0.0;
  }
}

typedef struct result {
  int rc;
  double wall, phi, phidot, dE; // seconds, max residuals, relative energy change
  dal_stats stats;
} result;

// run the Cartesian chain to T; q (2N) receives the final coordinates
static result run(const dal_system *sys, int N, double T, double rtol, dal_linsol ls, double *q) {
  result r;
  memset(&r, 0, sizeof r);
  dal_state *st = NULL;
  double *qd = malloc(2 * (size_t)N * sizeof(double));
  if (!qd || dal_state_create(sys, &st)) {
    free(qd);
    r.rc = DAL_E_NOMEM;
    return r;
  }
  start(N, q, qd);
  dal_energies e0, e1;
  clock_t c0 = clock();
  r.rc = dal_state_set(sys, st, 0.0, q, qd);
  if (!r.rc) r.rc = dal_forward(sys, st);
  dal_state_energies(st, &e0);
  dal_solve_opts o = dal_default_solve_opts(); // GGL in IDA
  o.rtol = o.atol = rtol;
  o.linsol = ls;
  if (!r.rc) r.rc = dal_advance(sys, st, &o, T);
  r.wall = (double)(clock() - c0) / CLOCKS_PER_SEC;
  if (r.rc) printf("advance failed: %s\n", dal_state_errmsg(st));
  dal_state_energies(st, &e1);
  dal_state_stats(st, &r.stats);
  for (int k = 0; k < N; ++k) {
    r.phi = fmax(r.phi, fabs(dal_state_phi(st)[k]));
    r.phidot = fmax(r.phidot, fabs(dal_state_phidot(st)[k]));
  }
  r.dE = fabs(e1.E - e0.E) / fabs(e0.E);
  memcpy(q, dal_state_q(st), 2 * (size_t)N * sizeof(double));
  dal_state_destroy(st);
  free(qd);
  return r;
}

static void report(int N, double T, double rtol, const char *ls, const result *r) {
  printf("N %5d  %-5s rtol %.0e  T %g: %.3f s wall (%.3f s per simulated s), %ld steps, %ld "
         "residuals, %ld Jacobians; |phi| %.1e |phidot| %.1e, energy change %.1e\n",
         N, ls, rtol, T, r->wall, r->wall / T, r->stats.steps, r->stats.rhs_evals,
         r->stats.jac_evals, r->phi, r->phidot, r->dE);
}

static int sound(const result *r, double rtol) {
  int ok = r->rc == 0 && r->phi <= rtol && r->phidot <= rtol && r->dE <= 1e3 * rtol;
  if (!ok) printf("FAILED: rc %d, residuals %g %g, energy %g\n", r->rc, r->phi, r->phidot, r->dE);
  return ok;
}

// --check: small chain vs minimal coordinates, dense vs KLU, and a large sparse chain
static int check(void) {
  enum { NS = 4, NL = 600 };
  double rtol = 1e-8, T = 1.0, qa[2 * NS], qb[2 * NS];
  int fails = 0;
  dal_system *cs = NULL, *ms = NULL, *ls = NULL;
  dal_state *st = NULL;
  if (build(NS, 1, &cs) || build(NS, 0, &ms) || dal_state_create(ms, &st)) return 1;
  result a = run(cs, NS, T, rtol, DAL_LINSOL_DENSE, qa);
  result b = run(cs, NS, T, rtol, DAL_LINSOL_KLU, qb);
  report(NS, T, rtol, "dense", &a);
  report(NS, T, rtol, "klu", &b);
  fails += !sound(&a, rtol) + !sound(&b, rtol);
  // minimal coordinates: link angles 45 degrees, at rest
  double th[NS], thd[NS];
  for (int k = 0; k < NS; ++k)
    th[k] = PI / 4, thd[k] = 0.0;
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_BS;
  o.rtol = o.atol = 1e-13;
  if (dal_state_set(ms, st, 0.0, th, thd) || dal_advance(ms, st, &o, T)) {
    printf("FAILED: minimal chain: %s\n", dal_state_errmsg(st));
    return 1;
  }
  const double *r = dal_state_positions(st);
  double dmin = 0, dlin = 0;
  for (int i = 0; i < 2 * NS; ++i) {
    dmin = fmax(dmin, fmax(fabs(qa[i] - r[i]), fabs(qb[i] - r[i])));
    dlin = fmax(dlin, fabs(qa[i] - qb[i]));
  }
  printf("N %d: Cartesian DAE vs minimal coordinates %.2e (%.0f x rtol); dense vs KLU %.2e\n", NS,
         dmin, dmin / rtol, dlin);
  fails += ex_expect(dmin <= 1e3 * rtol, "differs from the minimal chain");
  fails += ex_expect(dlin <= 1e3 * rtol, "dense and KLU differ");
  // a large chain: no dense mass matrix (sparse KKT), KLU chosen automatically
  double *q = malloc(2 * NL * sizeof(double));
  if (!q || build(NL, 1, &ls)) return 1;
  result c = run(ls, NL, 0.05, 1e-6, DAL_LINSOL_AUTO, q);
  report(NL, 0.05, 1e-6, "auto", &c);
  fails += !sound(&c, 1e-6);
  free(q);
  dal_state_destroy(st);
  dal_system_destroy(cs);
  dal_system_destroy(ms);
  dal_system_destroy(ls);
  return fails;
}

int main(int argc, char **argv) {
  int N = 1024, npos = 0, fails;
  double T = 1.0, rtol = 1e-6;
  dal_linsol ls = DAL_LINSOL_AUTO;
  if (argc > 1 && strcmp(argv[1], "--check") == 0) {
    fails = check();
  } else {
    for (int i = 1; i < argc; ++i) {
      if (strcmp(argv[i], "--klu") == 0)
        ls = DAL_LINSOL_KLU;
      else if (strcmp(argv[i], "--dense") == 0)
        ls = DAL_LINSOL_DENSE;
      else if (npos == 0 && ++npos)
        N = atoi(argv[i]);
      else if (npos == 1 && ++npos)
        T = atof(argv[i]);
      else if (npos == 2 && ++npos)
        rtol = atof(argv[i]);
    }
    if (N < 1 || !(T > 0) || !(rtol > 0)) {
      fprintf(stderr, "usage: chain --check | chain [N [T [rtol]]] [--klu | --dense]\n");
      return 2;
    }
    dal_system *sys = NULL;
    double *q = malloc(2 * (size_t)N * sizeof(double));
    if (!q || build(N, 1, &sys)) return 1;
    result r = run(sys, N, T, rtol, ls, q);
    report(N, T, rtol,
           ls == DAL_LINSOL_KLU     ? "klu"
           : ls == DAL_LINSOL_DENSE ? "dense"
                                    : "auto",
           &r);
    fails = !sound(&r, rtol);
    free(q);
    dal_system_destroy(sys);
  }
  return ex_verdict(fails, "OK");
}
