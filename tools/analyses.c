// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The command line's analyses of one scene: modes, equilibria, Lyapunov exponents, sections
// (CSV, or JSON with --format json: docs/cli.md), and cli_evolve, the run under them.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "json.h"

#define PI 3.14159265358979323846

static double grid_at(double lo, double hi, int n, int k) {
  return n == 1 ? lo : lo + (hi - lo) * k / (n - 1);
}

// the coordinates of a state as a comment: "theta = 0.5, x = 1"
static void print_q(FILE *fp, const dal_system *sys, const double *q) {
  for (int i = 0; i < dal_system_ncoords(sys); ++i)
    fprintf(fp, "%s%s = %.17g", i ? ", " : "", dal_system_coord_name(sys, i), q[i]);
}

// an angle wrapped into [-pi, pi)
static double wrap_pi(double x) { return x - 2 * PI * floor(x / (2 * PI) + 0.5); }

// a JSON member `key`: {"name": value, ...} over the coordinates (wrapped when wrap is set)
static void json_coords(cli_json *j, const char *key, const dal_system *sys, const double *v,
                        int wrap) {
  cli_json_object(j, key);
  for (int i = 0; i < dal_system_ncoords(sys); ++i)
    cli_json_num(j, dal_system_coord_name(sys, i), wrap ? wrap_pi(v[i]) : v[i]);
  cli_json_end(j);
}

// a status that refuses the request itself (the same for every start), not a start that failed
static int refused(int rc) { return rc == DAL_E_UNSUPPORTED || rc == DAL_E_ARG; }

// points kept for a chart: rows of t and w numbers
typedef struct points {
  double *v;
  size_t count, cap;
  int w;
} points;

// a row: t, x (nx, angles wrapped into [-pi, pi) when wrap is set), y (the rest of the row)
static int keep(points *p, double t, const double *x, int nx, const double *y, int wrap) {
  size_t w = 1 + (size_t)p->w;
  if (p->count == p->cap) {
    size_t cap = p->cap ? 2 * p->cap : 64;
    double *v = realloc(p->v, cap * w * sizeof *v);
    if (!v) return DAL_E_NOMEM;
    p->v = v, p->cap = cap;
  }
  double *r = p->v + p->count++ * w;
  r[0] = t;
  for (int i = 0; i < p->w; ++i)
    r[1 + i] = i >= nx ? y[i - nx] : wrap ? wrap_pi(x[i]) : x[i];
  return DAL_OK;
}

const cli_opt cli_modes_opts[] = {
    {"here", 0, CLI_FLAG, NULL, "at the initial q (no Newton search)", 0},
    CLI_OPT_FROZEN,
    CLI_OPT_FORMAT,
    CLI_END,
};

// normal modes at the state: "mode,omega2,omega,period" rows and the verdict (or JSON)
static int print_modes(cli *c, FILE *fp, const dal_system *sys, dal_state *st) {
  int n = dal_system_ncoords(sys), k = n - dal_system_nconstraints(sys),
      here = cli_given(c, "here");
  double *w2 = calloc((size_t)k + 1, sizeof *w2), *lre = calloc(2 * (size_t)k + 1, sizeof *lre),
         *lim = calloc(2 * (size_t)k + 1, sizeof *lim);
  dal_modes m;
  int rc = w2 && lre && lim ? (cli_given(c, "frozen") ? dal_normal_modes_frozen : dal_normal_modes)(
                                  sys, st, w2, NULL, lre, lim, &m)
                            : DAL_E_NOMEM;
  if (rc) {
    snprintf(c->msg, sizeof c->msg, "%s: %s", c->path, dal_state_errmsg(st));
  } else if (cli_json_asked(c)) {
    cli_json j = cli_json_start(fp);
    cli_json_str(&j, "command", "modes");
    cli_json_str(&j, "scene", c->path);
    cli_json_num(&j, "t", dal_state_time(st));
    cli_json_str(&j, "at", here ? "initial" : "equilibrium");
    json_coords(&j, "q", sys, dal_state_q(st), 0);
    cli_json_str(&j, "verdict", dal_stability_name(m.verdict));
    cli_json_num(&j, "max_real", m.max_real);
    cli_json_num(&j, "tolerance", m.tau);
    cli_json_num(&j, "acceleration", m.accel);
    if (m.frozen) cli_json_bool(&j, "frozen", 1); // asked for by --frozen on a driven scene
    cli_json_array(&j, "modes");
    for (int i = 0; i < k; ++i) {
      double w = sqrt(fabs(w2[i]));
      cli_json_object(&j, NULL);
      cli_json_int(&j, "mode", i + 1);
      cli_json_num(&j, "omega2", w2[i]);
      cli_json_num(&j, "omega", w2[i] >= 0 ? w : -w);
      cli_json_num(&j, "period", w2[i] > 0 ? 2 * PI / w : INFINITY);
      cli_json_end(&j);
    }
    cli_json_finish(&j);
  } else {
    fprintf(fp, "# normal modes of %s at t = %.17g, ", c->path, dal_state_time(st));
    print_q(fp, sys, dal_state_q(st));
    fprintf(fp, "%s\n", here ? "" : " (the equilibrium found from the initial q)");
    if (m.frozen)
      fprintf(fp,
              "# frozen at t = %.17g (--frozen): the scene depends on time; these modes are not "
              "the driven motion's (dalembert floquet)\n",
              dal_state_time(st));
    fprintf(fp, "# verdict: %s (largest real part %.3g, tolerance %.3g, acceleration %.3g)\n",
            dal_stability_name(m.verdict), m.max_real, m.tau, m.accel);
    fprintf(fp, "mode,omega2,omega,period\n");
    for (int i = 0; i < k; ++i) {
      double w = sqrt(fabs(w2[i]));
      // a negative omega^2 is a growth rate, not a frequency: no period
      fprintf(fp, "%d,%.17g,%.17g,%.17g\n", i + 1, w2[i], w2[i] >= 0 ? w : -w,
              w2[i] > 0 ? 2 * PI / w : INFINITY);
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
  if (rc) return cli_fail(c, rc, "the scene's initial state was refused");
  FILE *fp = cli_out(c);
  dal_equilibrium_report rep;
  dal_equilibrium_opts eo = dal_default_equilibrium_opts();
  eo.frozen_time = cli_given(c, "frozen") > 0;
  if (!fp)
    rc = DAL_E_IO;
  else if (!cli_given(c, "here") && (rc = dal_equilibrium(sys, st, &eo, &rep)))
    // a refusal (a request the analysis cannot honour) is said as the library says it
    snprintf(c->msg, sizeof c->msg, "%s: %s%s%s", c->path,
             refused(rc) ? "" : "no equilibrium from the initial q: ", dal_state_errmsg(st),
             refused(rc) ? "" : "; start nearer one, or --here for the modes at the initial q");
  else if (!(rc = print_modes(c, fp, sys, st)))
    cli_note(c, st);
  dal_state_destroy(st);
  if (rc != DAL_E_IO) cli_fail(c, rc, c->msg);
  return cli_close(c, rc);
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

// where equilibria go: CSV rows to fp, or objects of the JSON array "equilibria"
typedef struct eq_out {
  FILE *fp;
  cli_json *j; // NULL: CSV
} eq_out;

// Newton from q; a new equilibrium is written as a CSV row or a JSON object
static int one_start(cli *c, dal_state *st, const double *q, double *zero, found *f, eq_out *o) {
  const dal_system *sys = dal_scene_system(c->sc);
  int n = dal_system_ncoords(sys);
  double t0;
  dal_scene_opts(c->sc, &t0, NULL, NULL);
  dal_equilibrium_report rep;
  dal_equilibrium_opts eo = dal_default_equilibrium_opts();
  eo.frozen_time = cli_given(c, "frozen") > 0;
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
  int mr = (cli_given(c, "frozen") ? dal_normal_modes_frozen : dal_normal_modes)(sys, st, w2, NULL,
                                                                                 NULL, NULL, &m);
  const char *verdict = mr ? "unknown" : dal_stability_name(m.verdict);
  // a driven scene's equilibrium has no frozen verdict unless asked for: say which call fits
  char why[512];
  snprintf(why, sizeof why, "%s", dal_state_errmsg(st));
  if (mr == DAL_E_UNSUPPORTED && dal_time_dependence(sys, st, NULL, 0) == 1) {
    verdict = "driven";
    cli_error(c, 0, "%s", why);
  } else if (!mr && m.frozen) {
    verdict = m.verdict == DAL_UNSTABLE   ? "unstable-frozen"
              : m.verdict == DAL_NEUTRAL  ? "neutral-frozen"
              : m.verdict == DAL_MARGINAL ? "marginal-frozen"
                                          : "asymptotic-frozen";
  }
  if (o->j) {
    cli_json_object(o->j, NULL);
    json_coords(o->j, "q", sys, qs, 0);
    cli_json_str(o->j, "stability", verdict);
    cli_json_num(o->j, "omega2_min", mr ? NAN : w2[0]);
    cli_json_num(o->j, "accel", rep.accel);
    cli_json_num(o->j, "unsteady", rep.unsteady);
    cli_json_end(o->j);
  } else {
    for (int i = 0; i < n; ++i)
      fprintf(o->fp, "%.17g,", qs[i]);
    fprintf(o->fp, "%s,%.17g,%.3g,%.3g\n", verdict, mr ? NAN : w2[0], rep.accel, rep.unsteady);
  }
  free(w2);
  return DAL_OK;
}

const cli_opt cli_equilibria_opts[] = {
    {"scan", 0, CLI_TEXT, "COORD=LO:HI:N", "also Newton from N starts of coordinate COORD", 0},
    CLI_OPT_FROZEN,
    CLI_OPT_FORMAT,
    CLI_END,
};

int cli_equilibria(cli *c) {
  const dal_system *sys = dal_scene_system(c->sc);
  int n = dal_system_ncoords(sys), npts = 0, coord = -1, failed = 0, last = DAL_OK, s;
  double lo = 0, hi = 0;
  char name[256];
  const char *scan = cli_text(c, "scan");
  if (scan) {
    int rc = cli_grid(c, "scan", scan, name, sizeof name, &lo, &hi, &npts);
    for (int i = 0; i < n && !rc; ++i)
      if (!strcmp(dal_system_coord_name(sys, i), name)) coord = i;
    if (rc) return rc;
    if (coord < 0)
      return cli_error(c, DAL_E_ARG, "--scan: %s has no coordinate '%s'", c->path, name);
  }
  dal_state *st;
  int rc = dal_scene_state(c->sc, &st);
  if (rc) return cli_fail(c, rc, "the scene's initial state was refused");
  FILE *fp = cli_out(c);
  double *q = malloc(2 * (size_t)n * sizeof *q);
  found f = {0};
  cli_json j;
  eq_out o = {fp, NULL};
  if (!fp) rc = DAL_E_IO;
  if (!q && !rc) rc = DAL_E_NOMEM;
  if (!rc && cli_json_asked(c)) {
    j = cli_json_start(fp);
    o.j = &j;
    cli_json_str(&j, "command", "equilibria");
    cli_json_str(&j, "scene", c->path);
    cli_json_array(&j, "equilibria");
  } else if (!rc) {
    fprintf(fp, "# equilibria of %s (Newton from the initial q%s)\n", c->path,
            scan ? " and the scanned starts" : "");
    for (int i = 0; i < n; ++i)
      fprintf(fp, "%s,", dal_system_coord_name(sys, i));
    fprintf(fp, "stability,omega2_min,accel,unsteady\n");
  }
  for (s = -1; s < npts && !rc && !cli_interrupted(); ++s) {
    const double *q0 = dal_state_q(st);
    if (s == -1) memcpy(q, q0, (size_t)n * sizeof *q);
    if (s >= 0) q[coord] = grid_at(lo, hi, npts, s);
    memset(q + n, 0, (size_t)n * sizeof *q);
    int r = one_start(c, st, q, q + n, &f, &o);
    if (r == DAL_E_NOMEM) rc = r;
    if (refused(r)) rc = cli_error(c, r, "%s: %s", c->path, dal_state_errmsg(st));
    if (r) failed++, last = r;
    cli_progress(c, "equilibria: starts", s + 2, npts + 1, NULL);
  }
  if (o.j) {
    cli_json_end(&j);
    cli_json_int(&j, "starts", s + 1);
    cli_json_int(&j, "failed", failed);
    cli_json_bool(&j, "complete", s == npts);
    cli_json_finish(&j);
  }
  if (s < npts && !rc) cli_error(c, 0, "interrupted after %d of %d starts", s + 1, npts + 1);
  if (failed && !rc) cli_error(c, 0, "%d of %d starts did not converge", failed, s + 1);
  if (!rc && !f.count && !cli_interrupted())
    rc = cli_error(c, last, "%s: no equilibrium found (the last start: %s)", c->path,
                   dal_state_errmsg(st));
  free(q);
  free(f.r);
  dal_state_destroy(st);
  return cli_close(c, rc);
}

static int method_named(const cli *c, const char *name, dal_method *m) {
  for (int k = DAL_METHOD_AUTO; k <= DAL_METHOD_RATTLE6; ++k)
    if (!strcmp(dal_method_name((dal_method)k), name)) {
      *m = (dal_method)k;
      return DAL_OK;
    }
  return cli_error(c, CLI_USAGE, "--method: unknown method '%s'", name);
}

typedef struct lyap_ctx {
  const cli *c;
  double t1, t; // the end, the last renormalization
  points *kept; // nullable: the running estimates (rows t, exponents) for the chart
} lyap_ctx;

static int lyap_progress(double t, const double *ex, int nexp, void *ctx) {
  lyap_ctx *l = ctx;
  char extra[64];
  l->t = t;
  if (l->kept && nexp == l->kept->w && keep(l->kept, t, ex, nexp, NULL, 0)) return 1;
  snprintf(extra, sizeof extra, "lambda_1 %.4f", nexp ? ex[0] : NAN);
  cli_progress(l->c, "lyapunov: t", t, l->t1, extra);
  return cli_interrupted();
}

const cli_opt cli_lyapunov_opts[] = {
    CLI_OPT_T1,
    {"transient", 0, CLI_NONNEG, "T", "time discarded before the average", 0},
    {"renorm", 0, CLI_POSITIVE, "T", "time between renormalizations", 0},
    {"nexp", 0, CLI_COUNT, "K", "the K largest exponents (default 0: all)", 1 << 20},
    {"method", 0, CLI_TEXT, "M", "the integration method (dal_method_name; default: the scene's)",
     0},
    {"h", 0, CLI_POSITIVE, "H", "the step of a fixed-step method", 0},
    CLI_OPT_FORMAT,
    CLI_OPT_CHART("the running estimates against t, and the exponents with their 95% half-widths"),
    CLI_END,
};

// the running estimates (rows t, k exponents, every renormalization: at most 2000 drawn) and
// the exponents with their half-widths at the end
static int lyapunov_chart(cli *c, cli_file *f, const points *p, int k, double tend,
                          const double *ex, const double *er) {
  cli_series *se = calloc((size_t)k + 1, sizeof *se);
  double *at = calloc((size_t)k + 1, sizeof *at);
  char(*names)[48] = calloc((size_t)k + 1, sizeof *names), title[400];
  int rc = se && at && names ? DAL_OK : DAL_E_NOMEM;
  size_t every = p->count / 2000 + 1, w = 1 + (size_t)p->w;
  for (int i = 0; i < k && !rc; ++i) {
    snprintf(names[i], sizeof names[i], "running, column %d", i + 1);
    se[i] = (cli_series){names[i],  p->v, p->v + 1 + i, NULL, (p->count + every - 1) / every,
                         every * w, 1};
    at[i] = tend;
  }
  if (!rc) {
    se[k] = (cli_series){"exponents at the end, 95% half-widths", at, ex, er, (size_t)k, 1, 0};
    snprintf(title, sizeof title, "%s: Lyapunov exponents", c->path);
    cli_panel pan = {title, "t", "exponent (1/time)", se, k + 1};
    rc = cli_chart(c, f, &pan, 1);
  }
  free(se), free(at), free(names);
  return rc;
}

static void print_exponents(cli *c, FILE *fp, const dal_lyapunov_opts *o, double t0, double tend,
                            const double *ex, const double *er, int k) {
  double sum = 0;
  for (int i = 0; i < k; ++i)
    sum += ex[i];
  if (cli_json_asked(c)) {
    cli_json j = cli_json_start(fp);
    cli_json_str(&j, "command", "lyapunov");
    cli_json_str(&j, "scene", c->path);
    cli_json_num(&j, "t0", t0);
    cli_json_num(&j, "t1", tend);
    cli_json_num(&j, "transient", o->transient);
    cli_json_num(&j, "renorm", o->renorm);
    cli_json_str(&j, "method", dal_method_name(o->method));
    cli_json_num(&j, "rtol", o->rtol);
    cli_json_num(&j, "atol", o->atol);
    cli_json_array(&j, "exponents");
    for (int i = 0; i < k; ++i) {
      cli_json_object(&j, NULL);
      cli_json_int(&j, "index", i + 1);
      cli_json_num(&j, "value", ex[i]);
      cli_json_num(&j, "error95", er[i]);
      cli_json_end(&j);
    }
    cli_json_end(&j);
    cli_json_num(&j, "sum", sum);
    cli_json_bool(&j, "complete", tend >= o->t_end);
    cli_json_finish(&j);
    return;
  }
  fprintf(fp,
          "# Lyapunov exponents of %s from t = %g to %g (transient %g, renormalized every %g, "
          "%s, rtol %g, atol %g), 1/time, with 95%% half-widths\n",
          c->path, t0, tend, o->transient, o->renorm, dal_method_name(o->method), o->rtol, o->atol);
  fprintf(fp, "exponent,value,error95\n");
  for (int i = 0; i < k; ++i)
    fprintf(fp, "%d,%.17g,%.17g\n", i + 1, ex[i], er[i]);
  fprintf(fp, "# sum %.3g\n", sum);
}

int cli_lyapunov(cli *c) {
  const dal_system *sys = dal_scene_system(c->sc);
  double t0, t1;
  const dal_solve_opts *so = dal_scene_opts(c->sc, &t0, &t1, NULL);
  dal_lyapunov_opts o = dal_default_lyapunov_opts();
  o.t_end = cli_num(c, "t1", t1);
  o.transient = cli_num(c, "transient", o.transient);
  o.renorm = cli_num(c, "renorm", o.renorm);
  o.h = cli_num(c, "h", o.h);
  o.nexp = (int)cli_num(c, "nexp", 0);
  o.method = so->method;
  o.rtol = so->rtol;
  // the scene's atol, or what a run of the scene takes when it states none (solve.h)
  o.atol = so->atol > 0 ? so->atol : DAL_ATOL_PER_RTOL * so->rtol;
  const char *method = cli_text(c, "method");
  int rc = DAL_OK;
  if (method && (rc = method_named(c, method, &o.method))) return rc;
  int k = 2 * (dal_system_ncoords(sys) - dal_system_nconstraints(sys));
  if (o.nexp > 0 && o.nexp < k) k = o.nexp;
  dal_state *st;
  rc = dal_scene_state(c->sc, &st);
  if (rc) return cli_fail(c, rc, "the scene's initial state was refused");
  // the chart's file first: one that cannot be written stops the command before it runs
  const char *chart = cli_text(c, "chart");
  cli_file cf = {0};
  if (chart && cli_open(c, chart, &cf)) {
    dal_state_destroy(st);
    return DAL_E_IO;
  }
  double *ex = calloc((size_t)k + 1, sizeof *ex), *er = calloc((size_t)k + 1, sizeof *er);
  points kept = {NULL, 0, 0, k}; // the running estimates (k: the monitor's count)
  lyap_ctx lc = {c, o.t_end, NAN, chart ? &kept : NULL};
  FILE *fp = cli_out(c);
  rc = !fp        ? DAL_E_IO
       : ex && er ? dal_lyapunov(sys, st, &o, ex, er, lyap_progress, &lc)
                  : DAL_E_NOMEM;
  int stopped = !rc && cli_interrupted();
  if (rc) {
    if (rc != DAL_E_IO) cli_error(c, rc, "%s: %s", c->path, dal_state_errmsg(st));
  } else {
    print_exponents(c, fp, &o, t0, stopped ? lc.t : o.t_end, ex, er, k);
    if (stopped)
      cli_error(c, 0, "interrupted at t = %.17g: the estimates up to there", lc.t);
    else
      cli_note(c, st);
    if (chart) rc = lyapunov_chart(c, &cf, &kept, k, stopped ? lc.t : o.t_end, ex, er);
  }
  free(ex);
  free(er);
  free(kept.v);
  dal_state_destroy(st);
  // the chart, then the exponents: when either fails neither is left
  if (chart) rc = cli_commit(c, &cf, rc);
  int done = cli_close(c, rc);
  if (chart && done < 0 && rc >= 0) remove(chart);
  return done;
}

// the monitor of a run: the progress line, the interruption, and a row (CSV or JSON)
typedef struct rows {
  cli *c;
  dal_csv csv;     // csv.fp NULL: no CSV rows
  cli_json *json;  // nullable: objects into its open array
  double t1, last; // the end, the time of the last row written (NaN: none)
  const char *what;
  points *kept; // nullable: every row's t, q, qdot kept (for a chart)
} rows;

static int row(const dal_system *sys, const dal_state *st, void *ctx) {
  rows *r = ctx;
  if (cli_interrupted()) return 1; // stop before this row: the rows written are whole
  cli_progress(r->c, r->what, dal_state_time(st), r->t1, NULL);
  FILE *fp = r->json ? r->json->fp : r->csv.fp;
  if (fp && ferror(fp)) return -1; // a row not written: cli_commit says why
  r->last = dal_state_time(st);
  if (r->kept && keep(r->kept, r->last, dal_state_q(st), dal_system_ncoords(sys),
                      dal_state_qdot(st), r->csv.wrap_angles))
    return -1;
  if (r->json) {
    cli_json_object(r->json, NULL);
    cli_json_num(r->json, "t", dal_state_time(st));
    json_coords(r->json, "q", sys, dal_state_q(st), r->csv.wrap_angles);
    json_coords(r->json, "qdot", sys, dal_state_qdot(st), 0);
    cli_json_end(r->json);
    return ferror(r->json->fp) ? -1 : 0;
  }
  return r->csv.fp ? dal_csv_monitor(sys, st, &r->csv) : DAL_OK;
}

// run the scene with the monitor's rows r
static int evolve(cli *c, rows *r, dal_events *ev, double dt) {
  const dal_system *sys = dal_scene_system(c->sc);
  double t1;
  dal_solve_opts so = *dal_scene_opts(c->sc, NULL, &t1, NULL);
  so.cancel = cli_cancel; // Ctrl-C: the run stops at its next step, outputs up to it served
  r->t1 = t1 = cli_num(c, "t1", t1);
  dal_state *st;
  int rc = dal_scene_state(c->sc, &st);
  if (rc) return cli_fail(c, rc, "the scene's initial state was refused");
  if (ev) rc = dal_state_set_events(st, ev);
  if (dal_columns_need_work(r->csv.columns)) so.work = 1; // W is integrated only when asked for
  if (!rc) rc = dal_evolve(sys, st, &so, t1, dt, row, r);
  FILE *fp = r->json ? r->json->fp : r->csv.fp;
  if (rc < 0 && fp && ferror(fp)) {
    rc = DAL_E_IO; // the output's failure, said by cli_commit
  } else if (rc < 0) {
    snprintf(c->msg, sizeof c->msg, "%s: %s", c->path, dal_state_errmsg(st));
    cli_fail(c, rc, c->msg);
  } else if (cli_interrupted()) {
    cli_error(c, 0, "interrupted at t = %.17g: the rows written end at t = %.17g",
              dal_state_time(st), r->last);
  } else {
    cli_note(c, st);
  }
  dal_state_set_events(st, NULL);
  dal_state_destroy(st);
  return rc;
}

int cli_evolve(cli *c, FILE *fp, dal_events *ev, double dt, const char *what) {
  // --columns: a selection checked before the first row (a bad name: the output is removed)
  dal_columns *cols = NULL;
  const char *spec = cli_text(c, "columns");
  if (spec) {
    int rc = dal_columns_create(dal_scene_system(c->sc), spec, &cols, c->msg, sizeof c->msg);
    if (rc) return cli_fail(c, rc, c->msg);
  }
  rows r = {c, {fp, 0, cli_given(c, "wrap"), cols}, NULL, 0, NAN, what, NULL};
  int rc = evolve(c, &r, ev, dt);
  dal_columns_destroy(cols);
  return rc;
}

// the crossings of the surface sections: "t,section,<q>,<qdot>" or JSON objects (and kept,
// when kept is not NULL)
static int write_crossings(cli *c, const dal_events *ev, FILE *fp, cli_json *j, points *kept) {
  const dal_system *sys = dal_scene_system(c->sc);
  int n = dal_system_ncoords(sys), wrap = cli_given(c, "wrap");
  double *q = malloc(2 * (size_t)n * sizeof *q);
  if (!q) return DAL_E_NOMEM;
  if (!j) {
    fprintf(fp, "t,section");
    for (int i = 0; i < n; ++i)
      fprintf(fp, ",%s", dal_system_coord_name(sys, i));
    for (int i = 0; i < n; ++i)
      fprintf(fp, ",%s_dot", dal_system_coord_name(sys, i));
    fputc('\n', fp);
  }
  for (long k = 0; k < dal_events_count(ev); ++k) {
    dal_event_record r;
    dal_events_get(ev, k, &r, q, q + n);
    if (dal_scene_event_is_section(c->sc, r.event) != 1) continue;
    for (int i = 0; wrap && i < n; ++i)
      q[i] = wrap_pi(q[i]);
    if (kept && keep(kept, r.t, q, 2 * n, NULL, 0)) {
      free(q);
      return DAL_E_NOMEM;
    }
    if (j) {
      cli_json_object(j, NULL);
      cli_json_num(j, "t", r.t);
      cli_json_str(j, "section", dal_events_name(ev, r.event));
      json_coords(j, "q", sys, q, 0);
      json_coords(j, "qdot", sys, q + n, 0);
      cli_json_end(j);
      continue;
    }
    fprintf(fp, "%.17g,%s", r.t, dal_events_name(ev, r.event));
    for (int i = 0; i < 2 * n; ++i)
      fprintf(fp, ",%.17g", q[i]);
    fputc('\n', fp);
  }
  free(q);
  return ferror(fp) ? DAL_E_IO : DAL_OK;
}

// the section's chart: a panel per coordinate, qdot_i against q_i at the section's points
static int section_chart(cli *c, cli_file *f, const points *p) {
  const dal_system *sys = dal_scene_system(c->sc);
  int n = p->w / 2;
  cli_panel *pan = calloc((size_t)n, sizeof *pan);
  cli_series *se = calloc((size_t)n, sizeof *se);
  char(*title)[320] = calloc((size_t)n, sizeof *title),
  (*ylab)[300] = calloc((size_t)n, sizeof *ylab);
  int rc = pan && se && title && ylab ? DAL_OK : DAL_E_NOMEM;
  for (int i = 0; i < n && !rc; ++i) {
    const char *name = dal_system_coord_name(sys, i);
    snprintf(title[i], sizeof title[i], "%s: section of %s (%zu points)", c->path, name, p->count);
    snprintf(ylab[i], sizeof ylab[i], "%s_dot", name);
    se[i] =
        (cli_series){NULL, p->v + 1 + i, p->v + 1 + n + i, NULL, p->count, 1 + 2 * (size_t)n, 0};
    pan[i] = (cli_panel){title[i], name, ylab[i], &se[i], 1};
  }
  if (!rc) rc = cli_chart(c, f, pan, n);
  free(pan), free(se), free(title), free(ylab);
  return rc;
}

const cli_opt cli_section_opts[] = {
    CLI_OPT_OUTPUT("the section's points"),
    CLI_OPT_CHART("the section's points, qdot against q for each coordinate"),
    {"surface", 0, CLI_FLAG, NULL, "the surface section (a 'section ... rising =' line)", 0},
    CLI_OPT_WRAP,
    CLI_OPT_T1,
    CLI_OPT_FORMAT,
    CLI_END,
};

int cli_section(cli *c) {
  int nsurf = 0, surface = cli_given(c, "surface");
  for (int i = 0; dal_scene_event_is_section(c->sc, i) >= 0; ++i)
    nsurf += dal_scene_event_is_section(c->sc, i);
  int strobo = dal_scene_strobe(c->sc) > 0 && !surface;
  if (!strobo && !nsurf)
    return cli_error(c, DAL_E_ARG,
                     "%s has no %ssection line ('section <name> period=<T>' or 'section <name> "
                     "rising = <formula>')",
                     c->path, surface ? "surface " : "");
  // the chart's file first: one that cannot be written stops the command before it runs
  const char *chart = cli_text(c, "chart");
  cli_file cf = {0};
  if (chart && cli_open(c, chart, &cf)) return DAL_E_IO;
  FILE *fp = cli_out(c);
  if (!fp) {
    if (chart) cli_commit(c, &cf, DAL_E_IO);
    return DAL_E_IO;
  }
  dal_events *ev = NULL;
  points kept = {NULL, 0, 0, 2 * dal_system_ncoords(dal_scene_system(c->sc))};
  double dt;
  dal_scene_opts(c->sc, NULL, NULL, &dt);
  cli_json j, *jp = NULL;
  if (cli_json_asked(c)) {
    j = cli_json_start(fp);
    jp = &j;
    cli_json_str(&j, "command", "section");
    cli_json_str(&j, "scene", c->path);
    cli_json_str(&j, "kind", strobo ? "stroboscopic" : "surface");
    cli_json_num(&j, "period", strobo ? dal_scene_strobe(c->sc) : NAN);
    cli_json_array(&j, "points");
  }
  int rc = strobo ? DAL_OK : dal_scene_events(c->sc, &ev);
  rows r = {c,
            {strobo && !jp ? fp : NULL, 0, cli_given(c, "wrap"), NULL},
            strobo ? jp : NULL,
            0,
            NAN,
            "section: t",
            strobo && chart ? &kept : NULL};
  if (!rc) rc = evolve(c, &r, ev, strobo ? dal_scene_strobe(c->sc) : dt);
  if (!strobo && rc >= 0) rc = write_crossings(c, ev, fp, jp, chart ? &kept : NULL);
  if (jp) {
    cli_json_end(&j);
    cli_json_bool(&j, "complete", rc >= 0 && !cli_interrupted());
    cli_json_finish(&j);
  }
  dal_events_destroy(ev);
  // the chart, then the points: when either fails neither is left
  if (chart && rc >= 0) rc = section_chart(c, &cf, &kept);
  free(kept.v);
  if (chart) rc = cli_commit(c, &cf, rc);
  int done = cli_close(c, rc);
  if (chart && done < 0 && rc >= 0) remove(chart);
  return done;
}
