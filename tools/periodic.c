// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The command line's periodic motion: Floquet multipliers of the scene's initial state over a
// period (`floquet`) and periodic orbits by shooting (`orbit`), as text or JSON.
//
// JSON of `floquet` (and of `orbit`, which adds "orbit"):
//   {"scene": PATH, "t0": T0, "period": T, "verdict": "unstable|boundary|stable|asymptotically
//    stable", "accuracy": A, "trace": TR, "det": D, "max_abs": M, "gap": G,
//    "multipliers": [{"re": R, "im": I, "abs": |mu|, "exp_re": log|mu|/T, "exp_im": arg/T}],
//    "orbit": {"iterations": K, "residual": R, "q": {NAME: V, ...}, "qdot": {NAME: V, ...}}}
// `orbit --continue NAME=LO:HI:N` prints one CSV row per orbit of the branch (text), or a JSON
// array of {"p": P, "kind": "regular|fold|period-doubling", "verdict": V, "max_abs": M,
// "trace": TR, "period": T, "q": {...}, "qdot": {...}}.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

// the period: --period, else the scene's stroboscopic section (its drive period)
static double period_of(cli *c) {
  if (c->period > 0) return c->period;
  double T = dal_scene_strobe(c->sc);
  return T > 0 ? T : -1.0;
}

static void print_multipliers(int json, int k2, const double *re, const double *im, double T) {
  if (!json) printf("multiplier,re,im,abs,exponent_re,exponent_im\n");
  for (int i = 0; i < k2; ++i) {
    double a = hypot(re[i], im[i]), er = log(a) / T, ei = atan2(im[i], re[i]) / T;
    if (json)
      printf("%s{\"re\": %.17g, \"im\": %.17g, \"abs\": %.17g, \"exp_re\": %.17g, "
             "\"exp_im\": %.17g}",
             i ? ", " : "", re[i], im[i], a, er, ei);
    else
      printf("%d,%.17g,%.17g,%.17g,%.17g,%.17g\n", i + 1, re[i], im[i], a, er, ei);
  }
}

static void print_report(cli *c, int json, double t0, const dal_floquet_report *r,
                         const double *re, const double *im) {
  if (json) {
    printf("{\"scene\": \"%s\", \"t0\": %.17g, \"period\": %.17g, \"verdict\": \"%s\", "
           "\"accuracy\": %.3g, \"trace\": %.17g, \"det\": %.17g, \"max_abs\": %.17g, "
           "\"gap\": %.3g, \"multipliers\": [",
           c->path, t0, r->period, dal_floquet_verdict_name(r->verdict), r->accuracy, r->trace,
           r->det, r->max_abs, r->gap);
    print_multipliers(1, r->count, re, im, r->period);
    printf("]");
    return;
  }
  printf("# Floquet multipliers of %s over T = %.17g from t = %.17g\n", c->path, r->period, t0);
  printf("# verdict: %s (largest |mu| %.12g, accuracy %.3g; trace %.12g, det %.12g)\n",
         dal_floquet_verdict_name(r->verdict), r->max_abs, r->accuracy, r->trace, r->det);
  print_multipliers(0, r->count, re, im, r->period);
}

int cli_floquet(cli *c) {
  const dal_system *sys = dal_scene_system(c->sc);
  double T = period_of(c);
  if (T <= 0) {
    snprintf(c->msg, sizeof c->msg,
             "floquet: %s declares no period (a 'section NAME period=T' line): give --period T",
             c->path);
    return cli_fail(DAL_E_ARG, c->msg);
  }
  dal_state *st;
  int rc = dal_scene_state(c->sc, &st);
  if (rc) return cli_fail(rc, "floquet: the scene's initial state was refused");
  int k2 = 2 * (dal_system_ncoords(sys) - dal_system_nconstraints(sys));
  double *re = calloc((size_t)k2 + 1, sizeof *re), *im = calloc((size_t)k2 + 1, sizeof *im);
  dal_floquet_report r;
  double t0 = dal_state_time(st);
  rc = re && im ? dal_floquet(sys, st, NULL, T, re, im, NULL, &r) : DAL_E_NOMEM;
  if (rc) {
    snprintf(c->msg, sizeof c->msg, "%s: %s", c->path, dal_state_errmsg(st));
  } else {
    print_report(c, c->json, t0, &r, re, im);
    if (c->json) printf("}\n");
  }
  free(re);
  free(im);
  dal_state_destroy(st);
  return cli_fail(rc, c->msg);
}

// --continue: every point of the branch is a fresh scene with the parameter set (the
// continuation borrows its system; all are destroyed at the end)
typedef struct branch {
  cli *c;
  char name[256];
  dal_scene **scenes;
  int count, cap, rows;
} branch;

static int branch_rebuild(double p, dal_system **out, void *ctx) {
  branch *b = ctx;
  *out = NULL;
  if (b->count == b->cap) {
    int cap = b->cap ? 2 * b->cap : 64;
    dal_scene **v = realloc(b->scenes, (size_t)cap * sizeof *v);
    if (!v) return 1;
    b->scenes = v;
    b->cap = cap;
  }
  // the scene as given, --set values included (written normalized, read back), at p
  dal_scene *sc = NULL;
  char msg[512] = "out of memory";
  char *text = NULL;
  size_t len = 0;
  FILE *mem = open_memstream(&text, &len);
  int rc = !mem || dal_scene_write(b->c->sc, mem);
  if (mem && fclose(mem)) rc = 1;
  if (!rc) rc = dal_scene_parse(text, b->c->path, &sc, msg, sizeof msg);
  free(text);
  if (rc || dal_scene_set_param(sc, b->name, p, msg, sizeof msg)) {
    fprintf(stderr, "dalembert: %s\n", msg);
    dal_scene_destroy(sc);
    return 1;
  }
  b->scenes[b->count++] = sc;
  *out = (dal_system *)dal_scene_system(sc); // borrowed (opts.borrowed)
  return 0;
}

static int branch_point(double p, const dal_system *sys, const dal_state *st,
                        const dal_orbit_report *rep, const double *re, const double *im,
                        dal_orbit_kind kind, void *ctx) {
  branch *b = ctx;
  (void)re;
  (void)im;
  int n = dal_system_ncoords(sys);
  const double *q = dal_state_q(st), *v = dal_state_qdot(st);
  const char *k = kind == DAL_ORBIT_FOLD                ? "fold"
                  : kind == DAL_ORBIT_PERIOD_DOUBLING ? "period-doubling"
                                                      : "regular";
  const dal_floquet_report *f = &rep->floquet;
  if (b->c->json) {
    printf("%s{\"p\": %.17g, \"kind\": \"%s\", \"verdict\": \"%s\", \"max_abs\": %.17g, "
           "\"trace\": %.17g, \"period\": %.17g, \"q\": {",
           b->rows ? ",\n " : "", p, k, dal_floquet_verdict_name(f->verdict), f->max_abs,
           f->trace, rep->period);
    for (int i = 0; i < n; ++i)
      printf("%s\"%s\": %.17g", i ? ", " : "", dal_system_coord_name(sys, i), q[i]);
    printf("}, \"qdot\": {");
    for (int i = 0; i < n; ++i)
      printf("%s\"%s\": %.17g", i ? ", " : "", dal_system_coord_name(sys, i), v[i]);
    printf("}}");
  } else {
    if (!b->rows) {
      printf("%s,kind,verdict,max_abs,trace,period", b->name);
      for (int i = 0; i < n; ++i)
        printf(",%s,%s_dot", dal_system_coord_name(sys, i), dal_system_coord_name(sys, i));
      printf("\n");
    }
    printf("%.17g,%s,%s,%.17g,%.17g,%.17g", p, k, dal_floquet_verdict_name(f->verdict),
           f->max_abs, f->trace, rep->period);
    for (int i = 0; i < n; ++i)
      printf(",%.17g,%.17g", q[i], v[i]);
    printf("\n");
  }
  ++b->rows;
  return 0;
}

static int orbit_branch(cli *c, double T) {
  branch b = {c, "", NULL, 0, 0, 0};
  double lo, hi;
  int npts;
  if (cli_grid(c->cont, b.name, sizeof b.name, &lo, &hi, &npts) || npts < 2) {
    fprintf(stderr, "dalembert: --continue %s: NAME=LO:HI:N with N >= 2\n", c->cont);
    return DAL_E_ARG;
  }
  const dal_system *sys = dal_scene_system(c->sc);
  dal_state *st;
  int rc = dal_scene_state(c->sc, &st);
  if (rc) return cli_fail(rc, "orbit: the scene's initial state was refused");
  int n = dal_system_ncoords(sys);
  double *y0 = calloc(2 * (size_t)n + 1, sizeof *y0);
  dal_orbit_continuation_opts o = dal_default_orbit_continuation_opts();
  o.p0 = lo;
  o.p1 = hi;
  o.npoints = npts;
  o.t = dal_state_time(st);
  o.borrowed = 1;
  o.orbit.period = T;
  o.orbit.free_period = c->free_period;
  dal_continuation_report rep;
  if (y0) {
    memcpy(y0, dal_state_q(st), (size_t)n * sizeof *y0);
    memcpy(y0 + n, dal_state_qdot(st), (size_t)n * sizeof *y0);
  }
  if (c->json) printf("[");
  rc = y0 ? dal_orbit_continue(branch_rebuild, y0, &o, branch_point, &rep, &b) : DAL_E_NOMEM;
  if (c->json) printf("]\n");
  if (rc) snprintf(c->msg, sizeof c->msg, "%s: orbit --continue: %s", c->path, rep.msg);
  for (int i = 0; i < b.count; ++i)
    dal_scene_destroy(b.scenes[i]);
  free(b.scenes);
  free(y0);
  dal_state_destroy(st);
  return cli_fail(rc, c->msg);
}

int cli_orbit(cli *c) {
  const dal_system *sys = dal_scene_system(c->sc);
  double T = period_of(c);
  if (T <= 0) {
    snprintf(c->msg, sizeof c->msg, "orbit: %s declares no period: give --period T", c->path);
    return cli_fail(DAL_E_ARG, c->msg);
  }
  if (c->cont) return orbit_branch(c, T);
  dal_state *st;
  int rc = dal_scene_state(c->sc, &st);
  if (rc) return cli_fail(rc, "orbit: the scene's initial state was refused");
  int n = dal_system_ncoords(sys), k2 = 2 * (n - dal_system_nconstraints(sys));
  double *re = calloc((size_t)k2 + 1, sizeof *re), *im = calloc((size_t)k2 + 1, sizeof *im);
  dal_orbit_opts o = dal_default_orbit_opts();
  o.period = T;
  o.free_period = c->free_period;
  dal_orbit_report r;
  double t0 = dal_state_time(st);
  rc = re && im ? dal_periodic_orbit(sys, st, &o, re, im, &r) : DAL_E_NOMEM;
  if (rc) {
    snprintf(c->msg, sizeof c->msg, "%s: %s", c->path, dal_state_errmsg(st));
  } else {
    const double *q = dal_state_q(st), *v = dal_state_qdot(st);
    print_report(c, c->json, t0, &r.floquet, re, im);
    if (c->json) {
      printf(", \"orbit\": {\"iterations\": %d, \"residual\": %.3g, \"q\": {", r.iterations,
             r.residual);
      for (int i = 0; i < n; ++i)
        printf("%s\"%s\": %.17g", i ? ", " : "", dal_system_coord_name(sys, i), q[i]);
      printf("}, \"qdot\": {");
      for (int i = 0; i < n; ++i)
        printf("%s\"%s\": %.17g", i ? ", " : "", dal_system_coord_name(sys, i), v[i]);
      printf("}}}\n");
    } else {
      printf("# orbit start at t = %.17g (%d Newton steps, return gap %.3g):", t0, r.iterations,
             r.residual);
      for (int i = 0; i < n; ++i)
        printf(" %s = %.17g, %s' = %.17g", dal_system_coord_name(sys, i), q[i],
               dal_system_coord_name(sys, i), v[i]);
      printf("\n");
    }
  }
  free(re);
  free(im);
  dal_state_destroy(st);
  return cli_fail(rc, c->msg);
}
