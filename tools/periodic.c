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

int cli_orbit(cli *c) {
  const dal_system *sys = dal_scene_system(c->sc);
  double T = period_of(c);
  if (T <= 0) {
    snprintf(c->msg, sizeof c->msg, "orbit: %s declares no period: give --period T", c->path);
    return cli_fail(DAL_E_ARG, c->msg);
  }
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
