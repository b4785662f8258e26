// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The command line's analyses of one scene: modes, equilibria, Lyapunov exponents, sections.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static double grid_at(double lo, double hi, int n, int k) {
  return n == 1 ? lo : lo + (hi - lo) * k / (n - 1);
}

// the coordinates of a state as a comment: "theta = 0.5, x = 1"
static void print_q(const dal_system *sys, const double *q) {
  for (int i = 0; i < dal_system_ncoords(sys); ++i)
    printf("%s%s = %.17g", i ? ", " : "", dal_system_coord_name(sys, i), q[i]);
}

// normal modes at the state: "mode,omega2,omega,period" rows and the verdict
static int print_modes(const dal_system *sys, dal_state *st, int frozen, char *msg, size_t len) {
  int n = dal_system_ncoords(sys), k = n - dal_system_nconstraints(sys);
  double *w2 = calloc((size_t)k + 1, sizeof *w2), *lre = calloc(2 * (size_t)k + 1, sizeof *lre),
         *lim = calloc(2 * (size_t)k + 1, sizeof *lim);
  dal_modes m;
  int rc = w2 && lre && lim ? (frozen ? dal_normal_modes_frozen : dal_normal_modes)(
                                   sys, st, w2, NULL, lre, lim, &m)
                             : DAL_E_NOMEM;
  if (rc) {
    snprintf(msg, len, "modes: %s", dal_state_errmsg(st));
  } else {
    if (m.frozen)
      printf("# frozen at t = %.17g (--frozen): the scene depends on time; these modes are not "
             "the driven motion's (dalembert floquet)\n",
             dal_state_time(st));
    printf("# verdict: %s (largest real part %.3g, tolerance %.3g, acceleration %.3g)\n",
           dal_stability_name(m.verdict), m.max_real, m.tau, m.accel);
    printf("mode,omega2,omega,period\n");
    for (int i = 0; i < k; ++i) {
      double w = sqrt(fabs(w2[i]));
      // a negative omega^2 is a growth rate, not a frequency: no period
      printf("%d,%.17g,%.17g,%.17g\n", i + 1, w2[i], w2[i] >= 0 ? w : -w,
             w2[i] > 0 ? 2 * 3.14159265358979323846 / w : INFINITY);
    }
  }
  free(w2);
  free(lre);
  free(lim);
  return rc;
}

int cli_modes(cli *c) {
  const dal_system *sys = dal_scene_system(c->sc);
  dal_state *st;
  int rc = dal_scene_state(c->sc, &st);
  if (rc) return cli_fail(rc, "modes: the scene's initial state was refused");
  dal_equilibrium_report rep;
  dal_equilibrium_opts eo = dal_default_equilibrium_opts();
  eo.frozen_time = c->frozen;
  if (!c->here && (rc = dal_equilibrium(sys, st, &eo, &rep))) {
    snprintf(c->msg, sizeof c->msg,
             "%s: no equilibrium from the initial q (%s); start nearer one, or --here for the "
             "modes at the initial q",
             c->path, dal_state_errmsg(st));
  } else {
    printf("# normal modes of %s at t = %.17g, ", c->path, dal_state_time(st));
    print_q(sys, dal_state_q(st));
    printf("%s\n", c->here ? "" : " (the equilibrium found from the initial q)");
    rc = print_modes(sys, st, c->frozen, c->msg, sizeof c->msg);
  }
  dal_state_destroy(st);
  return cli_fail(rc, c->msg);
}

// the equilibria found so far, as the particles' positions (np each): two coordinate vectors
// that place every particle alike (an angle and the angle + 2 pi) are one equilibrium
typedef struct found {
  double *r;
  int count, cap;
} found;

static int seen(const found *f, const double *r, int np) {
  for (int j = 0; j < f->count; ++j) {
    int same = 1;
    for (int i = 0; i < np && same; ++i)
      same = fabs(f->r[j * np + i] - r[i]) <= 1e-8 * (1 + fabs(r[i]));
    if (same) return 1;
  }
  return 0;
}

// Newton from q; a new equilibrium is printed as a CSV row
static int one_start(cli *c, dal_state *st, const double *q, double *zero, found *f) {
  const dal_system *sys = dal_scene_system(c->sc);
  int n = dal_system_ncoords(sys);
  double t0;
  dal_scene_opts(c->sc, &t0, NULL, NULL);
  dal_equilibrium_report rep;
  dal_equilibrium_opts eo = dal_default_equilibrium_opts();
  eo.frozen_time = c->frozen;
  int rc = dal_state_set(sys, st, t0, q, zero);
  if (!rc) rc = dal_equilibrium(sys, st, &eo, &rep);
  if (rc) return rc;
  const double *qs = dal_state_q(st), *r = dal_state_positions(st);
  int np = dal_system_nparticles(sys) * dal_system_dim(sys);
  if (!r) return DAL_E_STATE;
  if (seen(f, r, np)) return DAL_OK;
  if (f->count == f->cap) {
    int cap = f->cap ? 2 * f->cap : 8;
    double *v = realloc(f->r, (size_t)cap * (size_t)np * sizeof *v);
    if (!v) return DAL_E_NOMEM;
    f->r = v;
    f->cap = cap;
  }
  memcpy(f->r + (size_t)f->count++ * (size_t)np, r, (size_t)np * sizeof *r);
  dal_modes m;
  int k = n - dal_system_nconstraints(sys);
  double *w2 = calloc((size_t)k + 1, sizeof *w2);
  if (!w2) return DAL_E_NOMEM;
  int mr = (c->frozen ? dal_normal_modes_frozen : dal_normal_modes)(sys, st, w2, NULL, NULL,
                                                                    NULL, &m);
  // a driven scene's equilibrium has no frozen verdict unless asked for: say which call fits
  const char *verdict = mr ? "unknown" : dal_stability_name(m.verdict);
  char why[512];
  snprintf(why, sizeof why, "%s", dal_state_errmsg(st));
  if (mr == DAL_E_UNSUPPORTED && dal_time_dependence(sys, st, NULL, 0) == 1) {
    verdict = "driven";
    fprintf(stderr, "dalembert: %s\n", why);
  } else if (!mr && m.frozen) {
    verdict = m.verdict == DAL_UNSTABLE   ? "unstable-frozen"
              : m.verdict == DAL_NEUTRAL  ? "neutral-frozen"
              : m.verdict == DAL_MARGINAL ? "marginal-frozen"
                                          : "asymptotic-frozen";
  }
  for (int i = 0; i < n; ++i)
    printf("%.17g,", qs[i]);
  printf("%s,%.17g,%.3g,%.3g\n", verdict, mr ? NAN : w2[0], rep.accel, rep.unsteady);
  free(w2);
  return DAL_OK;
}

int cli_equilibria(cli *c) {
  const dal_system *sys = dal_scene_system(c->sc);
  int n = dal_system_ncoords(sys), npts = 0, coord = -1, failed = 0, last = DAL_OK;
  double lo = 0, hi = 0;
  char name[256];
  if (c->scan) {
    int rc = cli_grid(c->scan, name, sizeof name, &lo, &hi, &npts);
    for (int i = 0; i < n && !rc; ++i)
      if (!strcmp(dal_system_coord_name(sys, i), name)) coord = i;
    if (rc || coord < 0) {
      if (!rc) fprintf(stderr, "dalembert: --scan: no coordinate '%s'\n", name);
      return DAL_E_ARG;
    }
  }
  dal_state *st;
  int rc = dal_scene_state(c->sc, &st);
  if (rc) return cli_fail(rc, "equilibria: the scene's initial state was refused");
  double *q = malloc(2 * (size_t)n * sizeof *q);
  found f = {0};
  if (!q) rc = DAL_E_NOMEM;
  printf("# equilibria of %s (Newton from the initial q%s)\n", c->path,
         c->scan ? " and the scanned starts" : "");
  for (int i = 0; i < n; ++i)
    printf("%s,", dal_system_coord_name(sys, i));
  printf("stability,omega2_min,accel,unsteady\n");
  for (int s = -1; s < npts && !rc; ++s) {
    const double *q0 = dal_state_q(st);
    if (s == -1) memcpy(q, q0, (size_t)n * sizeof *q);
    if (s >= 0) q[coord] = grid_at(lo, hi, npts, s);
    memset(q + n, 0, (size_t)n * sizeof *q);
    int r = one_start(c, st, q, q + n, &f);
    if (r == DAL_E_NOMEM) rc = r;
    if (r) failed++, last = r;
    cli_progress(c, "equilibria: starts", s + 2, npts + 1, NULL);
  }
  if (failed) fprintf(stderr, "dalembert: %d of %d starts did not converge\n", failed, npts + 1);
  if (!rc && !f.count) {
    fprintf(stderr, "dalembert: %s: no equilibrium found (%s)\n", c->path, dal_status_string(last));
    rc = last;
  }
  free(q);
  free(f.r);
  dal_state_destroy(st);
  return rc;
}

static int method_named(const char *name, dal_method *m) {
  for (int k = DAL_METHOD_AUTO; k <= DAL_METHOD_RATTLE6; ++k)
    if (!strcmp(dal_method_name((dal_method)k), name)) {
      *m = (dal_method)k;
      return DAL_OK;
    }
  fprintf(stderr, "dalembert: --method: unknown method '%s'\n", name);
  return DAL_E_ARG;
}

static int lyap_progress(double t, const double *ex, int nexp, void *ctx) {
  const cli *c = ctx;
  char extra[64];
  snprintf(extra, sizeof extra, "lambda_1 %.4f", nexp ? ex[0] : NAN);
  cli_progress(c, "lyapunov: t", t, c->t1, extra);
  return 0;
}

int cli_lyapunov(cli *c) {
  const dal_system *sys = dal_scene_system(c->sc);
  double t0, t1;
  const dal_solve_opts *so = dal_scene_opts(c->sc, &t0, &t1, NULL);
  dal_lyapunov_opts o = dal_default_lyapunov_opts();
  o.t_end = c->t1 > 0 ? c->t1 : t1;
  c->t1 = o.t_end;
  if (c->transient >= 0) o.transient = c->transient;
  if (c->renorm > 0) o.renorm = c->renorm;
  if (c->h > 0) o.h = c->h;
  o.nexp = (int)c->nexp;
  o.method = so->method;
  o.rtol = so->rtol;
  if (so->atol > 0) o.atol = so->atol; // else dal_lyapunov's default (it needs one > 0)
  if (c->method && method_named(c->method, &o.method)) return DAL_E_ARG;
  int k = 2 * (dal_system_ncoords(sys) - dal_system_nconstraints(sys));
  if (o.nexp > 0 && o.nexp < k) k = o.nexp;
  dal_state *st;
  int rc = dal_scene_state(c->sc, &st);
  if (rc) return cli_fail(rc, "lyapunov: the scene's initial state was refused");
  double *ex = calloc((size_t)k + 1, sizeof *ex), *er = calloc((size_t)k + 1, sizeof *er);
  rc = ex && er ? dal_lyapunov(sys, st, &o, ex, er, lyap_progress, c) : DAL_E_NOMEM;
  if (rc) {
    snprintf(c->msg, sizeof c->msg, "%s: %s", c->path, dal_state_errmsg(st));
  } else {
    double sum = 0;
    printf("# Lyapunov exponents of %s from t = %g to %g (transient %g, renormalized every %g, "
           "%s), 1/time, with 95%% half-widths\n",
           c->path, t0, o.t_end, o.transient, o.renorm, dal_method_name(o.method));
    printf("exponent,value,error95\n");
    for (int i = 0; i < k; ++i) {
      printf("%d,%.17g,%.17g\n", i + 1, ex[i], er[i]);
      sum += ex[i];
    }
    printf("# sum %.3g\n", sum);
  }
  free(ex);
  free(er);
  dal_state_destroy(st);
  return cli_fail(rc, c->msg);
}

// the monitor of cli_evolve: the progress line and the CSV row
typedef struct rows {
  cli *c;
  dal_csv csv;
  double t1;
  const char *what;
} rows;

static int row(const dal_system *sys, const dal_state *st, void *ctx) {
  rows *r = ctx;
  cli_progress(r->c, r->what, dal_state_time(st), r->t1, NULL);
  return r->csv.fp ? dal_csv_monitor(sys, st, &r->csv) : DAL_OK;
}

int cli_evolve(cli *c, FILE *fp, dal_events *ev, double dt, const char *what) {
  const dal_system *sys = dal_scene_system(c->sc);
  double t1;
  const dal_solve_opts *so = dal_scene_opts(c->sc, NULL, &t1, NULL);
  dal_state *st;
  int rc = dal_scene_state(c->sc, &st);
  if (rc) return cli_fail(rc, "the scene's initial state was refused");
  if (ev) rc = dal_state_set_events(st, ev);
  rows r = {c, {fp, 0, c->wrap}, t1, what};
  if (!rc) rc = dal_evolve(sys, st, so, t1, dt, row, &r);
  if (rc < 0) snprintf(c->msg, sizeof c->msg, "%s: %s", c->path, dal_state_errmsg(st));
  dal_state_set_events(st, NULL);
  dal_state_destroy(st);
  return cli_fail(rc, c->msg);
}

// the crossings of the surface sections: "t,section,<q>,<qdot>"
static int write_crossings(cli *c, const dal_events *ev, FILE *fp) {
  const dal_system *sys = dal_scene_system(c->sc);
  int n = dal_system_ncoords(sys);
  double *q = malloc(2 * (size_t)n * sizeof *q);
  if (!q) return DAL_E_NOMEM;
  fprintf(fp, "t,section");
  for (int i = 0; i < n; ++i)
    fprintf(fp, ",%s", dal_system_coord_name(sys, i));
  for (int i = 0; i < n; ++i)
    fprintf(fp, ",%s_dot", dal_system_coord_name(sys, i));
  fputc('\n', fp);
  for (long j = 0; j < dal_events_count(ev); ++j) {
    dal_event_record r;
    dal_events_get(ev, j, &r, q, q + n);
    if (dal_scene_event_is_section(c->sc, r.event) != 1) continue;
    fprintf(fp, "%.17g,%s", r.t, dal_events_name(ev, r.event));
    for (int i = 0; i < 2 * n; ++i) {
      double x = q[i];
      if (c->wrap && i < n)
        x -= 2 * 3.14159265358979323846 * floor(x / (2 * 3.14159265358979323846) + 0.5);
      fprintf(fp, ",%.17g", x);
    }
    fputc('\n', fp);
  }
  free(q);
  return DAL_OK;
}

int cli_section(cli *c) {
  int nsurf = 0;
  for (int i = 0; dal_scene_event_is_section(c->sc, i) >= 0; ++i)
    nsurf += dal_scene_event_is_section(c->sc, i);
  int strobo = dal_scene_strobe(c->sc) > 0 && !c->surface;
  if (!strobo && !nsurf) {
    fprintf(stderr,
            "dalembert: %s has no %ssection line ('section <name> period=<T>' or 'section "
            "<name> rising = <formula>')\n",
            c->path, c->surface ? "surface " : "");
    return DAL_E_ARG;
  }
  FILE *fp = cli_out(c);
  if (!fp) return DAL_E_IO;
  dal_events *ev = NULL;
  double dt;
  dal_scene_opts(c->sc, NULL, NULL, &dt);
  int rc = strobo ? DAL_OK : dal_scene_events(c->sc, &ev);
  if (!rc)
    rc = cli_evolve(c, strobo ? fp : NULL, ev, strobo ? dal_scene_strobe(c->sc) : dt, "section: t");
  if (!strobo && rc >= 0) rc = write_crossings(c, ev, fp);
  dal_events_destroy(ev);
  return cli_close(c, fp, rc);
}
