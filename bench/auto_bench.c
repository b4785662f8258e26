// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// dal_bench_auto: the work-precision table behind DAL_METHOD_AUTO and the default atol.
//
// Usage:
//   dal_bench_auto refs OUT.csv [--quick]
//       the reference positions of every scene at its final time (two independent
//       computations; written once, natively: they are not what is measured)
//   dal_bench_auto sweep REFS.csv [--quick] [--method NAME] [--rtol R]
//       for every scene, method (auto, dopri5, fehlberg78, bs, adams), atol rule (atol =
//       DAL_ATOL_PER_RTOL rtol, the default, or atol = 1e-2 rtol) and rtol 1e-2 ... 1e-13
//       (decades):
//       one dal_advance from the initial state inside auto_region(), then one CSV row on stdout
//       (scene, N, method, atol rule, rtol, status, error, rhs, steps, wall). Run under
//       valgrind --tool=callgrind --toggle-collect=auto_region: after each run the program asks
//       callgrind to dump its counts (CALLGRIND_DUMP_STATS_AT, labelled with the row number),
//       so the instructions of run k are in the k-th dump (bench/auto.sh joins them).
//   dal_bench_auto table SWEEP.csv
//       the AUTO table from a joined sweep (the columns above plus ir): for each scene, N and
//       error band 1e-4, 1e-8, 1e-11 the cheapest configuration (method, atol rule, rtol
//       interpolated) and AUTO's cost over it, as markdown on stdout.
//   dal_bench_auto rules SWEEP.csv
//       the rule search: for each number of coordinates that several scenes share, and for
//       n <= 2 and n >= 3, the rule
//       keyed on rtol (a method and atol rule per decade, at most three switches; every such rule
//       is replayed from the named methods' rows) with the smallest worst AUTO / best, beside
//       the worst of AUTO's own rows, as markdown on stdout; then the library's rule against the
//       best of what AUTO may run (no Fehlberg 7(8), the default atol) beside the best of every
//       configuration, and the best rule of what AUTO may run.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <valgrind/callgrind.h>

#include "dalembert/dalembert.h"
#include "scenes.h"
#include "util.h"

#if defined(__GNUC__)
#define BENCH_NOINLINE __attribute__((noinline))
#else
#define BENCH_NOINLINE
#endif
#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

// the scenes of the table: the seed scenes at their default horizons, then the chain
typedef struct auto_scene {
  scene_kind kind;
  int N;
} auto_scene;

static const auto_scene scenes_full[] = {
    {SC_PENDULUM, 1}, {SC_RING, 1},   {SC_DRIVEN, 1},  {SC_DOUBLE, 2},  {SC_HO2D, 1},
    {SC_CHAIN, 1},    {SC_CHAIN, 2},  {SC_CHAIN, 4},   {SC_CHAIN, 8},   {SC_CHAIN, 16},
    {SC_CHAIN, 32},   {SC_CHAIN, 64}, {SC_CHAIN, 128}, {SC_CHAIN, 256},
};
static const auto_scene scenes_quick[] = {
    {SC_PENDULUM, 1},
    {SC_DOUBLE, 2},
    {SC_CHAIN, 4},
    {SC_CHAIN, 32},
};

static const dal_method methods[] = {DAL_METHOD_AUTO, DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78,
                                     DAL_METHOD_BS, DAL_METHOD_ADAMS};
#define NMETH COUNT(methods)

// the error bands of the table; a configuration needs no tighter rtol once its error is
// below the tightest band by this factor
static const double bands[] = {1e-4, 1e-8, 1e-11};
#define NBAND COUNT(bands)
#define ERR_FLOOR 1e-12

static int scene_list(int quick, const auto_scene **out) {
  *out = quick ? scenes_quick : scenes_full;
  return quick ? COUNT(scenes_quick) : COUNT(scenes_full);
}

// ---------------------------------------------------------------- references

static int cmd_refs(const char *path, int quick) {
  FILE *fp = fopen(path, "w");
  if (!fp) {
    perror(path);
    return 1;
  }
  fprintf(fp, "scene,t1,agreement,values...\n");
  const auto_scene *list;
  int ns = scene_list(quick, &list);
  for (int i = 0; i < ns; ++i) {
    bench_scene sc;
    scene_init(&sc, list[i].kind, list[i].N, 0);
    int npd = scene_np(&sc) * scene_dim(&sc);
    double *r = malloc((size_t)npd * sizeof(double)), agree = 0;
    char how[160];
    if (!r) return 1;
    double t0 = bench_now();
    int rc = scene_reference(&sc, r, &agree, how, sizeof how);
    fprintf(stderr, "refs %s: %s, agreement %.2e, %.1f s\n", sc.name, how, agree, bench_now() - t0);
    if (rc) {
      fprintf(stderr, "refs %s: failed (%s)\n", sc.name, dal_status_name(rc));
      free(r);
      fclose(fp);
      return 1;
    }
    fprintf(fp, "%s,%.17g,%.3e", sc.name, sc.t1, agree);
    for (int k = 0; k < npd; ++k)
      fprintf(fp, ",%.17g", r[k]);
    fprintf(fp, "\n");
    free(r);
  }
  fclose(fp);
  return 0;
}

// the reference of a scene from the file written by `refs` (npd values)
static int read_ref(const char *path, const char *name, double *r, int npd) {
  FILE *fp = fopen(path, "r");
  if (!fp) return 1;
  size_t cap = 1 << 20;
  char *line = malloc(cap);
  int found = 0;
  while (line && !found && fgets(line, (int)cap, fp)) {
    char *c = strchr(line, ',');
    if (!c || (size_t)(c - line) != strlen(name) || strncmp(line, name, strlen(name)) != 0)
      continue;
    // skip t1 and the agreement
    c = strchr(c + 1, ',');
    c = c ? strchr(c + 1, ',') : NULL;
    int k = 0;
    while (c && k < npd) {
      r[k++] = strtod(c + 1, NULL);
      c = strchr(c + 1, ',');
    }
    found = k == npd;
  }
  free(line);
  fclose(fp);
  return !found;
}

// ---------------------------------------------------------------- the sweep

// the measured region: callgrind counts instructions only in here
static BENCH_NOINLINE int auto_region(bench_model *m, const dal_solve_opts *o, double t1) {
  return dal_advance(m->sys, m->st, o, t1);
}

static int cmd_sweep(const char *refs, int quick, const char *only, double only_rtol) {
  static const double tols[] = {1e-2, 1e-3, 1e-4,  1e-5,  1e-6,  1e-7,
                                1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13};
  const auto_scene *list;
  int ns = scene_list(quick, &list), row = 0;
  printf("row,scene,N,method,atol_rule,rtol,status,err,rhs,steps,wall_s\n");
  for (int i = 0; i < ns; ++i) {
    bench_scene sc;
    scene_init(&sc, list[i].kind, list[i].N, 0);
    int npd = scene_np(&sc) * scene_dim(&sc);
    double *ref = malloc((size_t)npd * sizeof(double));
    char err[400];
    if (!ref || read_ref(refs, sc.name, ref, npd)) {
      fprintf(stderr, "sweep %s: no reference in %s (run `refs` first)\n", sc.name, refs);
      free(ref);
      return 1;
    }
    bench_model m;
    if (scene_model(&sc, 0, &m, err, sizeof err)) {
      fprintf(stderr, "sweep %s: %s\n", sc.name, err);
      free(ref);
      return 1;
    }
    for (int mi = 0; mi < NMETH; ++mi)
      for (int rule = 0; rule < 2; ++rule) {
        // AUTO is measured as a user gets it: the default atol
        if (methods[mi] == DAL_METHOD_AUTO && rule == 1) continue;
        if (only && strcmp(only, dal_method_name(methods[mi])) != 0) continue;
        for (int ti = 0; ti < COUNT(tols); ++ti) {
          if (only_rtol > 0 && tols[ti] != only_rtol) continue;
          dal_solve_opts o = dal_default_solve_opts();
          o.method = methods[mi];
          o.form = DAL_FORM_ODE;
          o.rtol = tols[ti];
          o.atol = rule ? 1e-2 * tols[ti] : 0.0;
          o.max_steps = 2000000;
          int rc = scene_model_reset(&m);
          double t0 = bench_now();
          if (!rc) rc = auto_region(&m, &o, sc.t1);
          double wall = bench_now() - t0;
          dal_stats s;
          memset(&s, 0, sizeof s);
          dal_state_stats(m.st, &s);
          double e = rc ? NAN : bench_maxdiff(dal_state_positions(m.st), ref, npd);
          printf("%d,%s,%d,%s,%s,%.0e,%s,%.4e,%ld,%ld,%.4e\n", row, sc.name, sc.N,
                 dal_method_name(methods[mi]), rule ? "0.01rtol" : "default", tols[ti],
                 dal_status_name(rc), e, s.rhs_evals, s.steps, wall);
          fflush(stdout);
          char label[32];
          snprintf(label, sizeof label, "row%d", row++);
          CALLGRIND_DUMP_STATS_AT(label);
          // tighter tolerances cost more and add nothing to the bands
          if (rc || e < ERR_FLOOR) break;
        }
      }
    scene_model_free(&m);
    free(ref);
  }
  return 0;
}

// ---------------------------------------------------------------- the table

typedef struct pt {
  char scene[32], meth[16], rule[16];
  int N, ok;
  long rhs, steps;
  double rtol, err, ir;
} pt;

// the cost for a configuration (points of one scene, method and rule, loosest rtol first) to
// reach an error <= band: the first rtol that reaches it, interpolated log-log against the
// rtol before it (errors between decades of rtol); INFINITY when none does. *rt: the rtol
// (interpolated alike) at which it does.
static double cost_at(const pt *p, int n, double band, double *rt) {
  for (int i = 0; i < n; ++i) {
    if (!p[i].ok || !(p[i].err <= band)) continue;
    *rt = p[i].rtol;
    if (i == 0 || !p[i - 1].ok || !(p[i - 1].err > band) || p[i].err <= 0) return p[i].ir;
    double x0 = log(p[i - 1].err), x1 = log(p[i].err), x = log(band);
    double s = (x - x0) / (x1 - x0);
    *rt = exp(log(p[i - 1].rtol) + s * (log(p[i].rtol) - log(p[i - 1].rtol)));
    return exp(log(p[i - 1].ir) + s * (log(p[i].ir) - log(p[i - 1].ir)));
  }
  return INFINITY;
}

// the rows of a joined sweep (row,scene,N,method,atol_rule,rtol,status,err,rhs,steps,wall_s,ir),
// in file order; NULL when it cannot be read
static pt *load_sweep(const char *path, int *count) {
  FILE *fp = fopen(path, "r");
  if (!fp) {
    perror(path);
    return NULL;
  }
  int cap = 4096, n = 0;
  pt *p = malloc((size_t)cap * sizeof *p);
  char line[512];
  if (!p || !fgets(line, sizeof line, fp)) {
    fclose(fp);
    free(p);
    return NULL;
  }
  while (fgets(line, sizeof line, fp)) {
    if (n == cap) {
      pt *q = realloc(p, (size_t)(cap *= 2) * sizeof *p);
      if (!q) break;
      p = q;
    }
    char status[32];
    int row;
    double wall;
    pt *x = &p[n];
    if (sscanf(line, "%d,%31[^,],%d,%15[^,],%15[^,],%lf,%31[^,],%lf,%ld,%ld,%lf,%lf", &row,
               x->scene, &x->N, x->meth, x->rule, &x->rtol, status, &x->err, &x->rhs, &x->steps,
               &wall, &x->ir) != 12)
      continue;
    x->ok = strcmp(status, "DAL_OK") == 0 && isfinite(x->err) && x->ir > 0;
    ++n;
  }
  fclose(fp);
  *count = n;
  return p;
}

static int cmd_table(const char *path) {
  int n = 0;
  pt *p = load_sweep(path, &n);
  if (!p) return 1;
  printf("| scene | N | band | best: method, atol rule, rtol | AUTO: method at that band, rtol "
         "| AUTO / best | best with atol = 1e-2 rtol / best with the default atol |\n");
  printf("|---|---:|---:|---|---|---:|---:|\n");
  double worst = 0, worst_atol = 0;
  for (int i = 0; i < n;) {
    int j = i;
    while (j < n && strcmp(p[j].scene, p[i].scene) == 0)
      ++j;
    // [i, j) is one scene; configurations are runs of equal (method, rule)
    for (int b = 0; b < NBAND; ++b) {
      double best = INFINITY, best_rt = 0, autoc = INFINITY, auto_rt = 0;
      double best_rule[2] = {INFINITY, INFINITY};
      const char *bm = "-", *br = "-", *am = "-";
      for (int k = i; k < j;) {
        int l = k;
        while (l < j && strcmp(p[l].meth, p[k].meth) == 0 && strcmp(p[l].rule, p[k].rule) == 0)
          ++l;
        double rt = 0, c = cost_at(p + k, l - k, bands[b], &rt);
        if (strcmp(p[k].meth, "auto") == 0) {
          autoc = c;
          auto_rt = rt;
          // AUTO's runs are runs of a named method: a configuration too
          if (c < best) {
            best = c;
            best_rt = rt;
            bm = "auto";
            br = p[k].rule;
          }
        } else {
          int r = strcmp(p[k].rule, "0.01rtol") == 0;
          if (c < best_rule[r]) best_rule[r] = c;
          if (c < best) {
            best = c;
            best_rt = rt;
            bm = p[k].meth;
            br = p[k].rule;
          }
        }
        k = l;
      }
      if (!isfinite(best)) continue;
      // the method AUTO ran at the first rtol that reached the band: the configuration with
      // the default atol and the same rtol, steps and right-hand sides
      for (int k = i; k < j; ++k) {
        if (strcmp(p[k].meth, "auto") != 0 || !p[k].ok || !(p[k].err <= bands[b])) continue;
        for (int l = i; l < j; ++l)
          if (l != k && strcmp(p[l].rule, "default") == 0 && p[l].rtol == p[k].rtol &&
              p[l].rhs == p[k].rhs && p[l].steps == p[k].steps)
            am = p[l].meth;
        break;
      }
      double ratio = autoc / best, ar = best_rule[1] / best_rule[0];
      if (ratio > worst) worst = ratio;
      if (ar > worst_atol) worst_atol = ar;
      printf("| %s | %d | %.0e | %s, %s, %.1e | %s, %.1e | %.2f | %.2f |\n", p[i].scene, p[i].N,
             bands[b], bm, br, best_rt, am, auto_rt, ratio, ar);
    }
    i = j;
  }
  printf("\nLargest AUTO / best: %.2f.\n", worst);
  (void)worst_atol;
  free(p);
  return 0;
}

// ---------------------------------------------------------------- the rule search

#define RMAX 16 // decades of rtol in a sweep
#define NCONF 8 // configurations a rule may pick: four methods x two atol rules
static const char *conf_meth[] = {"dopri5", "fehlberg78", "bs", "adams"};
static const char *conf_rule[] = {"default", "0.01rtol"};

typedef struct rscene {
  const char *name;
  int n;                     // coordinates
  const pt *at[NCONF][RMAX]; // the run of each configuration at each rtol (NULL: none)
  double best[NBAND];        // the cheapest of all configurations at each band
  double now[NBAND];         // AUTO's own runs (the rule the library has)
} rscene;

// the number of coordinates of a scene of the sweep (built once, not integrated)
static int scene_ncoords(const char *name) {
  for (int i = 0; i < COUNT(scenes_full); ++i) {
    bench_scene sc;
    scene_init(&sc, scenes_full[i].kind, scenes_full[i].N, 0);
    if (strcmp(sc.name, name) != 0) continue;
    bench_model m;
    char err[200];
    if (scene_model(&sc, 0, &m, err, sizeof err)) return -1;
    int n = dal_system_ncoords(m.sys);
    scene_model_free(&m);
    return n;
  }
  return -1;
}

// the worst AUTO / best over the scenes [s, s + ns) with coordinates in [nlo, nhi] when AUTO
// runs configuration seq[k] at rtol k (the replay: AUTO's run at an rtol is the run of the
// named method it resolves to, tests/test_defaults.c); *where: that scene and band
static double rule_worst(const rscene *sc, int ns, int nlo, int nhi, const int *seq, int L,
                         int *where) {
  double worst = 0;
  for (int i = 0; i < ns; ++i) {
    if (sc[i].n < nlo || sc[i].n > nhi) continue;
    pt curve[RMAX];
    for (int k = 0; k < L; ++k) {
      const pt *x = sc[i].at[seq[k]][k];
      if (x)
        curve[k] = *x;
      else
        memset(&curve[k], 0, sizeof curve[k]);
    }
    for (int b = 0; b < NBAND; ++b) {
      if (!isfinite(sc[i].best[b])) continue;
      double rt = 0, r = cost_at(curve, L, bands[b], &rt) / sc[i].best[b];
      if (r > worst) {
        worst = r;
        *where = i * NBAND + b;
      }
    }
  }
  return worst;
}

// a rule as text: runs of one configuration, loosest rtol first
static void rule_text(const int *seq, const double *rt, int L, char *out, size_t len) {
  size_t k = 0;
  out[0] = 0;
  for (int i = 0; i < L; ++i) {
    if (i > 0 && seq[i] == seq[i - 1]) continue;
    int c = seq[i];
    k += (size_t)snprintf(out + k, len > k ? len - k : 0, "%s%s%s from %.0e", i ? "; " : "",
                          conf_meth[c / 2], c % 2 ? " (atol 1e-2 rtol)" : "", rt[i]);
  }
}

// the best rule for one class of systems: a configuration per decade of rtol with at most
// RULE_SWITCHES switches (every such rule is replayed), the smallest worst AUTO / best first,
// fewer switches on a tie
#define RULE_SWITCHES 3
typedef struct rsearch {
  const rscene *sc;
  int ns, nlo, nhi, L;
  int seq[RMAX], best[RMAX], where;
  double worst;
} rsearch;

// a method the rule search may not pick (-1: none): fehlberg78, whose error estimate misses
// the differential set of tests/test_auto_set.c (issue 31)
static int rule_excluded = -1;
// with this set the rule search picks only the default atol (the configurations AUTO runs:
// it chooses a method, never the caller's atol)
static int rule_default_atol = 0;

static void rule_walk(rsearch *r, int k, int switches) {
  if (k == r->L) {
    int w = 0;
    double x = rule_worst(r->sc, r->ns, r->nlo, r->nhi, r->seq, r->L, &w);
    if (x < r->worst - 1e-12) {
      r->worst = x;
      r->where = w;
      memcpy(r->best, r->seq, sizeof r->seq);
    }
    return;
  }
  for (int c = 0; c < NCONF; ++c) {
    if (c / 2 == rule_excluded || (rule_default_atol && c % 2)) continue;
    int sw = k > 0 && c != r->seq[k - 1];
    if (switches + sw > RULE_SWITCHES) continue;
    r->seq[k] = c;
    rule_walk(r, k + 1, switches + sw);
  }
}

static int cmd_rules(const char *path) {
  int n = 0;
  pt *p = load_sweep(path, &n);
  if (!p) return 1;
  // the decades of rtol, loosest first
  double rt[RMAX];
  int L = 0;
  for (int i = 0; i < n; ++i) {
    int k = 0;
    while (k < L && rt[k] != p[i].rtol)
      ++k;
    if (k == L && L < RMAX) rt[L++] = p[i].rtol;
  }
  for (int i = 1; i < L; ++i)
    for (int j = i; j > 0 && rt[j] > rt[j - 1]; --j) {
      double t = rt[j];
      rt[j] = rt[j - 1];
      rt[j - 1] = t;
    }
  rscene *sc = calloc(COUNT(scenes_full), sizeof *sc);
  int ns = 0;
  for (int i = 0; sc && i < n;) {
    int j = i;
    while (j < n && strcmp(p[j].scene, p[i].scene) == 0)
      ++j;
    rscene *x = &sc[ns++];
    x->name = p[i].scene;
    x->n = scene_ncoords(p[i].scene);
    for (int k = i; k < j; ++k)
      for (int c = 0; c < NCONF; ++c)
        for (int r = 0; r < L; ++r)
          if (strcmp(p[k].meth, conf_meth[c / 2]) == 0 &&
              strcmp(p[k].rule, conf_rule[c % 2]) == 0 && p[k].rtol == rt[r])
            x->at[c][r] = &p[k];
    for (int b = 0; b < NBAND; ++b) {
      x->best[b] = x->now[b] = INFINITY;
      for (int k = i; k < j;) {
        int l = k;
        while (l < j && strcmp(p[l].meth, p[k].meth) == 0 && strcmp(p[l].rule, p[k].rule) == 0)
          ++l;
        double r = 0, c = cost_at(p + k, l - k, bands[b], &r);
        if (strcmp(p[k].meth, "auto") == 0)
          x->now[b] = c;
        else if (c < x->best[b])
          x->best[b] = c;
        k = l;
      }
    }
    if (x->n < 0 || ns == COUNT(scenes_full)) break;
    i = j;
  }
  if (!sc || ns == 0 || sc[ns - 1].n < 0) {
    fprintf(stderr, "rules: a scene of %s is not one of this program's\n", path);
    free(sc);
    free(p);
    return 1;
  }
  // the classes: every number of coordinates that two or more scenes share (one scene alone is
  // fitted exactly by some rule, which says nothing), then n <= 2 and n >= 3 (the split of the
  // rule the library has)
  int lo[64], hi[64], nc = 0;
  for (int i = 0; i < ns; ++i) {
    int k = 0;
    while (k < nc && lo[k] != sc[i].n)
      ++k;
    int shared = 0;
    for (int j = 0; j < ns; ++j)
      shared += sc[j].n == sc[i].n;
    if (k == nc && shared > 1) lo[nc] = hi[nc] = sc[i].n, ++nc;
  }
  lo[nc] = 1, hi[nc++] = 2;
  lo[nc] = 3, hi[nc++] = 1 << 30;
  double lib_worst[2] = {0, 0}, safe_worst = 0;
  int lib_where[2] = {0, 0}, safe_where = 0;
  char safe_text[400] = "";
  printf("| coordinates | AUTO now: worst AUTO / best (scene, band) | best rule keyed on rtol "
         "alone (at most three switches) | its worst (scene, band) |\n|---|---|---|---|\n");
  for (int k = 0; k < nc; ++k) {
    double now = 0;
    int wn = -1;
    for (int i = 0; i < ns; ++i)
      for (int b = 0; b < NBAND; ++b)
        if (sc[i].n >= lo[k] && sc[i].n <= hi[k] && isfinite(sc[i].best[b]) &&
            sc[i].now[b] / sc[i].best[b] > now)
          now = sc[i].now[b] / sc[i].best[b], wn = i * NBAND + b;
    rsearch r = {.sc = sc, .ns = ns, .nlo = lo[k], .nhi = hi[k], .L = L, .worst = INFINITY};
    rule_walk(&r, 0, 0);
    char text[400], cls[32];
    rule_text(r.best, rt, L, text, sizeof text);
    // the library's rule since issue 31, replayed (n >= 3: DOPRI5 down to 1e-5, BS below;
    // n <= 2: DOPRI5 down to 1e-3, BS below), and the best rule without fehlberg78
    if (lo[k] == 1 && hi[k] == 2) {
      int seq[RMAX], wl = 0;
      for (int i = 0; i < L; ++i)
        seq[i] = rt[i] >= 1e-3 * (1 - 1e-9) ? 0 : 4;
      lib_worst[0] = rule_worst(sc, ns, 1, 2, seq, L, &wl), lib_where[0] = wl;
    } else if (lo[k] == 3 && hi[k] == 1 << 30) {
      int seq[RMAX], wl = 0;
      for (int i = 0; i < L; ++i)
        seq[i] = rt[i] >= 1e-5 * (1 - 1e-9) ? 0 : 4;
      lib_worst[1] = rule_worst(sc, ns, 3, 1 << 30, seq, L, &wl), lib_where[1] = wl;
      rule_excluded = 1;
      rsearch q = {.sc = sc, .ns = ns, .nlo = lo[k], .nhi = hi[k], .L = L, .worst = INFINITY};
      rule_walk(&q, 0, 0);
      rule_excluded = -1;
      safe_worst = q.worst;
      safe_where = q.where;
      rule_text(q.best, rt, L, safe_text, sizeof safe_text);
    }
    if (lo[k] == hi[k])
      snprintf(cls, sizeof cls, "%d", lo[k]);
    else if (hi[k] == 1 << 30)
      snprintf(cls, sizeof cls, "%d and more", lo[k]);
    else
      snprintf(cls, sizeof cls, "%d to %d", lo[k], hi[k]);
    if (wn < 0) continue;
    printf("| %s | %.3f (%s, %.0e) | %s | %.3f (%s, %.0e) |\n", cls, now, sc[wn / NBAND].name,
           bands[wn % NBAND], text, r.worst, sc[r.where / NBAND].name, bands[r.where % NBAND]);
  }
  printf("\nThe rule since issue 31 (no Fehlberg 7(8)), replayed: n <= 2 %.3f (%s, %.0e); n >= 3 "
         "%.3f (%s, %.0e). Best rule for n >= 3 without Fehlberg 7(8): %s, %.3f (%s, %.0e).\n",
         lib_worst[0], sc[lib_where[0] / NBAND].name, bands[lib_where[0] % NBAND], lib_worst[1],
         sc[lib_where[1] / NBAND].name, bands[lib_where[1] % NBAND], safe_text, safe_worst,
         sc[safe_where / NBAND].name, bands[safe_where % NBAND]);
  // what the atol rule does on its own: per method, cost with atol = 1e-2 rtol over cost with
  // atol = rtol at the same error band, over every scene and band
  printf("\n| method | atol = 1e-2 rtol over atol = rtol at equal error: median | min | max | "
         "cells |\n|---|---:|---:|---:|---:|\n");
  for (int c = 0; c < NCONF; c += 2) {
    double r[COUNT(scenes_full) * NBAND];
    int nr = 0;
    for (int i = 0; i < ns; ++i) {
      pt c0[RMAX], c1[RMAX];
      memset(c0, 0, sizeof c0);
      memset(c1, 0, sizeof c1);
      for (int k = 0; k < L; ++k) {
        if (sc[i].at[c][k]) c0[k] = *sc[i].at[c][k];
        if (sc[i].at[c + 1][k]) c1[k] = *sc[i].at[c + 1][k];
      }
      for (int b = 0; b < NBAND; ++b) {
        double r0 = 0, x = cost_at(c1, L, bands[b], &r0) / cost_at(c0, L, bands[b], &r0);
        if (isfinite(x)) r[nr++] = x;
      }
    }
    for (int a = 1; a < nr; ++a) // insertion sort: a few dozen cells
      for (int b = a; b > 0 && r[b] < r[b - 1]; --b) {
        double t = r[b];
        r[b] = r[b - 1];
        r[b - 1] = t;
      }
    if (nr > 0)
      printf("| %s | %.3f | %.2f | %.2f | %d |\n", conf_meth[c / 2],
             nr % 2 ? r[nr / 2] : 0.5 * (r[nr / 2 - 1] + r[nr / 2]), r[0], r[nr - 1], nr);
  }
  // what AUTO may run (issue 31: no Fehlberg 7(8); the caller's atol): the library's rule
  // against the best of those configurations, cell by cell, and the best rule of them
  printf("\n| coordinates | the library's rule: worst AUTO / best of every configuration | worst "
         "AUTO / best of what AUTO may run (DOPRI5, BS, Adams at the default atol) | cells above "
         "1.1 of either | best rule of what AUTO may run | its worst / best of every "
         "configuration |\n|---|---|---|---|---|---|\n");
  for (int cls = 0; cls < 2; ++cls) {
    int nlo = cls ? 3 : 1, nhi = cls ? 1 << 30 : 2, seq[RMAX], above = 0;
    for (int i = 0; i < L; ++i)
      seq[i] = rt[i] >= (cls ? 1e-5 : 1e-3) * (1 - 1e-9) ? 0 : 4;
    double w_all = 0, w_may = 0;
    int at_all = 0, at_may = 0;
    for (int i = 0; i < ns; ++i) {
      if (sc[i].n < nlo || sc[i].n > nhi) continue;
      pt curve[RMAX];
      for (int k = 0; k < L; ++k) {
        if (sc[i].at[seq[k]][k])
          curve[k] = *sc[i].at[seq[k]][k];
        else
          memset(&curve[k], 0, sizeof curve[k]);
      }
      for (int b = 0; b < NBAND; ++b) {
        double may = INFINITY, r0 = 0;
        for (int c = 0; c < NCONF; c += 2) {
          if (c / 2 == 1) continue; // fehlberg78
          pt cc[RMAX];
          for (int k = 0; k < L; ++k) {
            if (sc[i].at[c][k])
              cc[k] = *sc[i].at[c][k];
            else
              memset(&cc[k], 0, sizeof cc[k]);
          }
          may = fmin(may, cost_at(cc, L, bands[b], &r0));
        }
        double cost = cost_at(curve, L, bands[b], &r0), ra = cost / sc[i].best[b], rm = cost / may;
        if (!isfinite(ra) || !isfinite(rm)) continue;
        above += ra > 1.1 || rm > 1.1;
        if (ra > w_all) w_all = ra, at_all = i * NBAND + b;
        if (rm > w_may) w_may = rm, at_may = i * NBAND + b;
      }
    }
    rule_excluded = 1;
    rule_default_atol = 1;
    rsearch q = {.sc = sc, .ns = ns, .nlo = nlo, .nhi = nhi, .L = L, .worst = INFINITY};
    rule_walk(&q, 0, 0);
    rule_excluded = -1;
    rule_default_atol = 0;
    char text[400];
    rule_text(q.best, rt, L, text, sizeof text);
    printf("| %s | %.3f (%s, %.0e) | %.3f (%s, %.0e) | %d | %s | %.3f (%s, %.0e) |\n",
           cls ? "3 and more" : "1 to 2", w_all, sc[at_all / NBAND].name, bands[at_all % NBAND],
           w_may, sc[at_may / NBAND].name, bands[at_may % NBAND], above, text, q.worst,
           sc[q.where / NBAND].name, bands[q.where % NBAND]);
  }
  free(sc);
  free(p);
  return 0;
}

int main(int argc, char **argv) {
  int quick = 0;
  const char *only = NULL;
  double only_rtol = 0;
  for (int a = 3; a < argc; ++a) {
    if (strcmp(argv[a], "--quick") == 0) quick = 1;
    if (strcmp(argv[a], "--method") == 0 && a + 1 < argc) only = argv[++a];
    if (strcmp(argv[a], "--rtol") == 0 && a + 1 < argc) only_rtol = atof(argv[++a]);
  }
  if (argc >= 3 && strcmp(argv[1], "refs") == 0) return cmd_refs(argv[2], quick);
  if (argc >= 3 && strcmp(argv[1], "sweep") == 0) return cmd_sweep(argv[2], quick, only, only_rtol);
  if (argc >= 3 && strcmp(argv[1], "table") == 0) return cmd_table(argv[2]);
  if (argc >= 3 && strcmp(argv[1], "rules") == 0) return cmd_rules(argv[2]);
  fprintf(stderr, "usage: dal_bench_auto refs OUT.csv [--quick] | sweep REFS.csv [--quick] "
                  "[--method NAME] [--rtol R] | table SWEEP.csv | rules SWEEP.csv\n");
  return 2;
}
