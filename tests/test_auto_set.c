// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The default options against a differential set (issue 31): seeded random planar trees of
// 3 ... 6 pendulums in minimal coordinates with a spring between two children of one pendulum
// (a third of them with equal sibling rods and starts that make the siblings pass near each
// other, where the spring's direction turns fast: near-singular passes), run to t = 2.
//
// Reference: a much tighter run by another method (Bulirsch-Stoer at rtol 1e-13, or Adams at
// 1e-12 where the method under test is Bulirsch-Stoer); the two references are checked against
// each other. Each scene's amplification A is measured from a start perturbation (1e-7 on every
// q and qdot, the reference method on both starts): |dy(2)| / |dy(0)|.
// Bound: a DAL_OK run whose error max_i |y_i - ref_i| / max(1, |ref_i|) exceeds 16 rtol
// max(1, A) is a wrong answer the default must never give.
//
//   test_auto_set            ctest: the default options (AUTO) on all 300 trees at rtol
//                            1e-4 ... 1e-10, and the named methods at 1e-8 on the first 40
//   test_auto_set --full     the full set: 300 trees x 7 tolerances, the default options and
//                            every adaptive ODE method, one table row per method and rtol
//                            (the worst ratio error / (rtol max(1, A)), the count beyond 16);
//                            AUTO's rule (src/integrate/methods.c) is read off this table
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

#define MAXN 6
#define T_END 2.0
#define BOUND 16.0
#define NRTOL 7

typedef struct tree {
  int N;
  int parent[MAXN]; // -1: on the pivot
  double L[MAXN], m[MAXN], th[MAXN], om[MAXN];
  int sa, sb;   // the spring's siblings
  double k, Ls; // its stiffness and rest length
  int near;     // built for a near-singular pass
} tree;

static tree random_tree(unsigned long long seed) {
  tree t;
  memset(&t, 0, sizeof t);
  unsigned long long s = seed * 0x9e3779b97f4a7c15ULL + 7;
  t.N = 3 + (int)check_rand(&s, 0, 4); // 3 ... 6
  if (t.N > MAXN) t.N = MAXN;
  for (int k = 0; k < t.N; ++k) {
    t.parent[k] = k == 0 ? -1 : (int)check_rand(&s, -1, k);
    if (t.parent[k] >= k) t.parent[k] = k - 1;
    t.L[k] = check_rand(&s, 0.5, 1.5);
    t.m[k] = check_rand(&s, 0.5, 2.0);
    t.th[k] = check_rand(&s, -1.0, 1.0);
    t.om[k] = check_rand(&s, -1.5, 1.5);
  }
  // two children of one pendulum: the last two hang from the same parent
  int p = (int)check_rand(&s, -1, t.N - 2);
  if (p > t.N - 3) p = t.N - 3;
  t.sa = t.N - 2;
  t.sb = t.N - 1;
  t.parent[t.sa] = t.parent[t.sb] = p;
  t.k = check_rand(&s, 2.0, 40.0);
  t.Ls = check_rand(&s, 0.1, 0.8);
  t.near = seed % 3 == 0;
  if (t.near) {
    // rods within 2 ... 6 % of each other, swinging towards each other: the siblings pass at
    // about that difference (a few cm), where the spring's direction turns fast
    t.L[t.sb] = t.L[t.sa] * (1.0 + check_rand(&s, 0.02, 0.06));
    t.m[t.sb] = t.m[t.sa];
    t.th[t.sa] = check_rand(&s, 0.2, 0.6);
    t.th[t.sb] = -t.th[t.sa] + check_rand(&s, -0.01, 0.01);
    t.om[t.sa] = -check_rand(&s, 1.0, 3.0);
    t.om[t.sb] = -t.om[t.sa];
    t.Ls = check_rand(&s, 0.02, 0.2);
  } else if (fabs(t.L[t.sb] - t.L[t.sa]) < 0.02) {
    // siblings never meet (at equal rods they could pass through each other, where the
    // spring's force is not smooth: no method's error estimate holds there)
    t.L[t.sb] = t.L[t.sa] + 0.02;
  }
  return t;
}

static dal_system *build(const tree *t) {
  scn_knobs kn = scn_default();
  dal_builder *b = NULL;
  int rc = scn_builder(&kn, 2, &b), p[MAXN];
  for (int k = 0; k < t->N && !rc; ++k) {
    char name[16], coord[16];
    snprintf(name, sizeof name, "p%d", k);
    snprintf(coord, sizeof coord, "th%d", k);
    rc = scn_add_swing(b, &kn, name, t->m[k], t->parent[k] < 0 ? -1 : p[t->parent[k]], t->L[k],
                       coord, &p[k]);
  }
  dal_spring_def sd = dal_default_spring_def();
  sd.a = p[t->sa];
  sd.b = p[t->sb];
  sd.k = t->k;
  sd.length = t->Ls;
  if (!rc) rc = dal_builder_add_spring_def(b, &sd);
  return scn_finish(b, rc);
}

// run from y0 (q then qdot) to T_END; y gets the end state; the status
static int run(const dal_system *sys, const double *y0, const dal_solve_opts *o, double *y,
               dal_method *used) {
  int n = dal_system_ncoords(sys);
  dal_state *st = NULL;
  int rc = dal_state_create(sys, &st);
  if (!rc) rc = dal_state_set(sys, st, 0.0, y0, y0 + n);
  if (!rc) rc = dal_advance(sys, st, o, T_END);
  if (st) {
    memcpy(y, dal_state_q(st), (size_t)n * sizeof(double));
    memcpy(y + n, dal_state_qdot(st), (size_t)n * sizeof(double));
    dal_stats s;
    dal_state_stats(st, &s);
    if (used) *used = s.method_used;
  }
  dal_state_destroy(st);
  return rc;
}

static dal_solve_opts opts(dal_method m, double rtol) {
  dal_solve_opts o = dal_default_solve_opts();
  o.method = m;
  o.rtol = rtol;
  o.atol = rtol;
  o.max_steps = 1000000;
  return o;
}

static double dist(const double *a, const double *b, int ny) {
  double e = 0.0;
  for (int i = 0; i < ny; ++i) {
    double d = fabs(a[i] - b[i]) / fmax(1.0, fabs(b[i]));
    if (!(d <= e)) e = d;
  }
  return e;
}

// a scene with its references and amplification
typedef struct scene {
  dal_system *sys;
  int ny;
  double y0[2 * MAXN], ref_bs[2 * MAXN], ref_ad[2 * MAXN], amp, refgap;
} scene;

static int scene_make(unsigned long long seed, scene *sc) {
  tree t = random_tree(seed);
  memset(sc, 0, sizeof *sc);
  if (!(sc->sys = build(&t))) return -1;
  int n = t.N;
  sc->ny = 2 * n;
  for (int k = 0; k < n; ++k) {
    sc->y0[k] = t.th[k];
    sc->y0[n + k] = t.om[k];
  }
  dal_solve_opts rb = opts(DAL_METHOD_BS, 1e-13), rd = opts(DAL_METHOD_ADAMS, 1e-12);
  int rc = run(sc->sys, sc->y0, &rb, sc->ref_bs, NULL);
  if (!rc) rc = run(sc->sys, sc->y0, &rd, sc->ref_ad, NULL);
  if (rc) return rc;
  sc->refgap = dist(sc->ref_ad, sc->ref_bs, sc->ny);
  // amplification of a start perturbation of 1e-7 (alternating signs)
  double yp[2 * MAXN], yend[2 * MAXN];
  for (int i = 0; i < sc->ny; ++i)
    yp[i] = sc->y0[i] + (i % 2 ? -1e-7 : 1e-7);
  dal_solve_opts ra = opts(DAL_METHOD_BS, 1e-11); // its error: 1e-4 of the perturbation's
  if ((rc = run(sc->sys, yp, &ra, yend, NULL)) != 0) return rc;
  sc->amp = dist(yend, sc->ref_bs, sc->ny) / 1e-7;
  return 0;
}

typedef struct tally {
  double worst;
  long beyond, failed, runs;
  unsigned long long worst_seed;
} tally;

// run method m at rtol on sc: the ratio error / (rtol max(1, A)) into t
static void measure(const scene *sc, unsigned long long seed, dal_method m, double rtol, tally *t,
                    int must_hold) {
  dal_solve_opts o = opts(m, rtol);
  double y[2 * MAXN];
  dal_method used = m;
  int rc = run(sc->sys, sc->y0, &o, y, &used);
  t->runs++;
  if (rc != DAL_OK) {
    t->failed++;
    return;
  }
  const double *ref = used == DAL_METHOD_BS ? sc->ref_ad : sc->ref_bs;
  double ratio = dist(y, ref, sc->ny) / (rtol * fmax(1.0, sc->amp));
  if (ratio > t->worst) {
    t->worst = ratio;
    t->worst_seed = seed;
  }
  if (ratio > BOUND) {
    t->beyond++;
    if (must_hold)
      CHECK_MSG(0,
                "tree %llu, %s at rtol %g (ran %s): DAL_OK with %.3g x rtol max(1, A) (A = "
                "%.3g)",
                seed, dal_method_name(m), rtol, dal_method_name(used), ratio, sc->amp);
  }
}

int main(int argc, char **argv) {
  int full = argc > 1 && strcmp(argv[1], "--full") == 0;
  const int ntrees = 300, nnamed = full ? 300 : 40;
  const double rtols[NRTOL] = {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
  const dal_method named[4] = {DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_BS,
                               DAL_METHOD_ADAMS};
  tally dflt[NRTOL], meth[4][NRTOL];
  memset(dflt, 0, sizeof dflt);
  memset(meth, 0, sizeof meth);
  double amp_max = 0.0, gap_max = 0.0;
  for (int i = 0; i < ntrees; ++i) {
    scene sc;
    unsigned long long seed = (unsigned long long)i + 1;
    int rc = scene_make(seed, &sc);
    CHECK_MSG(rc == 0, "tree %llu: the scene or its reference failed (%d)", seed, rc);
    if (rc) {
      dal_system_destroy(sc.sys);
      continue;
    }
    // the references agree far below the tightest request (else the set proves nothing)
    CHECK_MSG(sc.refgap <= 1e-11 * fmax(1.0, sc.amp),
              "tree %llu: references differ by %.3g (A = %.3g)", seed, sc.refgap, sc.amp);
    if (sc.amp > amp_max) amp_max = sc.amp;
    if (sc.refgap > gap_max) gap_max = sc.refgap;
    for (int r = 0; r < NRTOL; ++r)
      measure(&sc, seed, DAL_METHOD_AUTO, rtols[r], &dflt[r], 1);
    if (i < nnamed)
      for (int j = 0; j < 4; ++j)
        for (int r = 0; r < NRTOL; ++r)
          if (full || rtols[r] == 1e-8) measure(&sc, seed, named[j], rtols[r], &meth[j][r], 0);
    dal_system_destroy(sc.sys);
  }
  printf("%d random trees (3 ... 6 pendulums, a spring between siblings, every third a "
         "near-singular pass) to t = 2; amplification up to %.3g, references within %.3g\n",
         ntrees, amp_max, gap_max);
  printf("%-12s %-7s %-22s %-9s %-6s\n", "method", "rtol", "worst err/(rtol A)", "beyond 16",
         "failed");
  for (int r = 0; r < NRTOL; ++r)
    printf("%-12s %-7.0e %-10.3g (tree %-4llu)  %-9ld %-6ld\n", "default", rtols[r], dflt[r].worst,
           dflt[r].worst_seed, dflt[r].beyond, dflt[r].failed);
  for (int j = 0; j < 4; ++j)
    for (int r = 0; r < NRTOL; ++r)
      if (meth[j][r].runs)
        printf("%-12s %-7.0e %-10.3g (tree %-4llu)  %-9ld %-6ld\n", dal_method_name(named[j]),
               rtols[r], meth[j][r].worst, meth[j][r].worst_seed, meth[j][r].beyond,
               meth[j][r].failed);
  // the defaults never fail on these smooth scenes
  for (int r = 0; r < NRTOL; ++r)
    CHECK_MSG(dflt[r].failed == 0, "default at rtol %g: %ld runs failed", rtols[r], dflt[r].failed);
  return check_summary("test_auto_set");
}
