// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The command line's periodic motion: Floquet multipliers of the scene's initial state over a
// period (`floquet`) and periodic orbits by shooting, with their branch in a parameter
// (`orbit`), as CSV or JSON (the schemas: docs/analysis.md, "Periodic motion").
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "json.h"

#define CLI_OPT_PERIOD                                                                             \
  { "period", 0, CLI_POSITIVE, "T", "the period (default: the scene's strobe period)", 0 }

const cli_opt cli_floquet_opts[] = {
    CLI_OPT_PERIOD,
    CLI_OPT_FORMAT,
    CLI_END,
};

const cli_opt cli_orbit_opts[] = {
    CLI_OPT_PERIOD,
    {"free", 0, CLI_FLAG, NULL, "an autonomous scene: the period is an unknown (--period guesses)",
     0},
    {"continue", 0, CLI_TEXT, "NAME=LO:HI:N", "follow the orbit's branch in parameter NAME", 0},
    CLI_OPT_FORMAT,
    CLI_END,
};

// the period: --period, else the scene's stroboscopic section (its drive period); < 0: none
static double period_of(cli *c) {
  double T = cli_num(c, "period", -1.0);
  if (T > 0) return T;
  T = dal_scene_strobe(c->sc);
  return T > 0 ? T : -1.0;
}

static void json_coords(cli_json *j, const char *key, const dal_system *sys, const double *x) {
  cli_json_object(j, key);
  for (int i = 0; i < dal_system_ncoords(sys); ++i)
    cli_json_num(j, dal_system_coord_name(sys, i), x[i]);
  cli_json_end(j);
}

// the multipliers and the report: members of an open JSON object, or CSV lines
static void write_report(cli_json *j, FILE *fp, const dal_floquet_report *r, const double *re,
                         const double *im) {
  double T = r->period;
  if (j) {
    cli_json_num(j, "period", T);
    cli_json_str(j, "verdict", dal_floquet_verdict_name(r->verdict));
    cli_json_num(j, "accuracy", r->accuracy);
    cli_json_num(j, "trace", r->trace);
    cli_json_num(j, "det", r->det);
    cli_json_num(j, "max_abs", r->max_abs);
    cli_json_num(j, "gap", r->gap);
    cli_json_array(j, "multipliers");
    for (int i = 0; i < r->count; ++i) {
      double a = hypot(re[i], im[i]);
      cli_json_object(j, NULL);
      cli_json_num(j, "re", re[i]);
      cli_json_num(j, "im", im[i]);
      cli_json_num(j, "abs", a);
      cli_json_num(j, "exp_re", log(a) / T);
      cli_json_num(j, "exp_im", atan2(im[i], re[i]) / T);
      cli_json_end(j);
    }
    cli_json_end(j);
    return;
  }
  fprintf(fp, "# verdict: %s (largest |mu| %.12g, accuracy %.3g; trace %.12g, det %.12g)\n",
          dal_floquet_verdict_name(r->verdict), r->max_abs, r->accuracy, r->trace, r->det);
  fprintf(fp, "multiplier,re,im,abs,exponent_re,exponent_im\n");
  for (int i = 0; i < r->count; ++i) {
    double a = hypot(re[i], im[i]);
    fprintf(fp, "%d,%.17g,%.17g,%.17g,%.17g,%.17g\n", i + 1, re[i], im[i], a, log(a) / T,
            atan2(im[i], re[i]) / T);
  }
}

int cli_floquet(cli *c) {
  const dal_system *sys = dal_scene_system(c->sc);
  double T = period_of(c);
  if (T <= 0)
    return cli_error(c, DAL_E_ARG,
                     "%s declares no period (a 'section NAME period=T' line): "
                     "give --period T",
                     c->path);
  dal_state *st;
  int rc = dal_scene_state(c->sc, &st);
  if (rc) return cli_fail(c, rc, "the scene's initial state was refused");
  int k2 = 2 * (dal_system_ncoords(sys) - dal_system_nconstraints(sys));
  double *re = calloc((size_t)k2 + 1, sizeof *re), *im = calloc((size_t)k2 + 1, sizeof *im);
  dal_floquet_report r;
  double t0 = dal_state_time(st);
  FILE *fp = cli_out(c);
  rc = !fp ? DAL_E_IO : re && im ? dal_floquet(sys, st, NULL, T, re, im, NULL, &r) : DAL_E_NOMEM;
  if (rc && fp) {
    snprintf(c->msg, sizeof c->msg, "%s: %s", c->path, dal_state_errmsg(st));
  } else if (!rc && cli_json_asked(c)) {
    cli_json j = cli_json_start(fp);
    cli_json_str(&j, "command", "floquet");
    cli_json_str(&j, "scene", c->path);
    cli_json_num(&j, "t0", t0);
    write_report(&j, fp, &r, re, im);
    cli_json_finish(&j);
  } else if (!rc) {
    fprintf(fp, "# Floquet multipliers of %s over T = %.17g from t = %.17g\n", c->path, T, t0);
    write_report(NULL, fp, &r, re, im);
  }
  free(re);
  free(im);
  dal_state_destroy(st);
  if (rc != DAL_E_IO) cli_fail(c, rc, c->msg);
  return cli_close(c, rc);
}

// --continue: every point of the branch is a fresh scene (--set values and the parameter
// applied); the continuation borrows its system, all are destroyed at the end
typedef struct branch {
  cli *c;
  FILE *fp;
  cli_json *j; // NULL: CSV
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
  dal_scene *sc = NULL;
  char msg[512];
  int rc = dal_scene_parse(b->c->text, b->c->path, &sc, msg, sizeof msg);
  if (!rc) rc = cli_set_params(b->c, sc, msg, sizeof msg);
  if (!rc) rc = dal_scene_set_param(sc, b->name, p, msg, sizeof msg);
  if (rc) {
    cli_error(b->c, rc, "--continue at %s = %.17g: %s", b->name, p, msg);
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
  const char *k = kind == DAL_ORBIT_FOLD              ? "fold"
                  : kind == DAL_ORBIT_PERIOD_DOUBLING ? "period-doubling"
                                                      : "regular";
  const dal_floquet_report *f = &rep->floquet;
  if (b->j) {
    cli_json_object(b->j, NULL);
    cli_json_num(b->j, "p", p);
    cli_json_str(b->j, "kind", k);
    cli_json_str(b->j, "verdict", dal_floquet_verdict_name(f->verdict));
    cli_json_num(b->j, "max_abs", f->max_abs);
    cli_json_num(b->j, "trace", f->trace);
    cli_json_num(b->j, "period", rep->period);
    json_coords(b->j, "q", sys, q);
    json_coords(b->j, "qdot", sys, v);
    cli_json_end(b->j);
  } else {
    if (!b->rows) {
      fprintf(b->fp, "%s,kind,verdict,max_abs,trace,period", b->name);
      for (int i = 0; i < n; ++i)
        fprintf(b->fp, ",%s,%s_dot", dal_system_coord_name(sys, i), dal_system_coord_name(sys, i));
      fprintf(b->fp, "\n");
    }
    fprintf(b->fp, "%.17g,%s,%s,%.17g,%.17g,%.17g", p, k, dal_floquet_verdict_name(f->verdict),
            f->max_abs, f->trace, rep->period);
    for (int i = 0; i < n; ++i)
      fprintf(b->fp, ",%.17g,%.17g", q[i], v[i]);
    fprintf(b->fp, "\n");
  }
  ++b->rows;
  return cli_interrupted();
}

static int orbit_branch(cli *c, FILE *fp, dal_state *st, double T) {
  branch b = {c, fp, NULL, "", NULL, 0, 0, 0};
  double lo, hi;
  int npts,
      rc = cli_grid(c, "continue", cli_text(c, "continue"), b.name, sizeof b.name, &lo, &hi, &npts);
  if (rc) return rc;
  if (npts < 2) return cli_error(c, CLI_USAGE, "--continue: N must be at least 2");
  int n = dal_system_ncoords(dal_scene_system(c->sc));
  double *y0 = calloc(2 * (size_t)n + 1, sizeof *y0);
  if (!y0) return DAL_E_NOMEM;
  memcpy(y0, dal_state_q(st), (size_t)n * sizeof *y0);
  memcpy(y0 + n, dal_state_qdot(st), (size_t)n * sizeof *y0);
  dal_orbit_continuation_opts o = dal_default_orbit_continuation_opts();
  o.p0 = lo;
  o.p1 = hi;
  o.npoints = npts;
  o.t = dal_state_time(st);
  o.borrowed = 1;
  o.orbit.period = T;
  o.orbit.free_period = cli_given(c, "free") > 0;
  dal_continuation_report rep;
  cli_json j;
  if (cli_json_asked(c)) {
    j = cli_json_start(fp);
    cli_json_str(&j, "command", "orbit");
    cli_json_str(&j, "scene", c->path);
    cli_json_str(&j, "parameter", b.name);
    cli_json_array(&j, "branch");
    b.j = &j;
  }
  rc = dal_orbit_continue(branch_rebuild, y0, &o, branch_point, &rep, &b);
  if (b.j) {
    cli_json_end(&j);
    cli_json_finish(&j);
  }
  if (rc) snprintf(c->msg, sizeof c->msg, "%s: --continue: %s", c->path, rep.msg);
  for (int i = 0; i < b.count; ++i)
    dal_scene_destroy(b.scenes[i]);
  free(b.scenes);
  free(y0);
  return rc;
}

int cli_orbit(cli *c) {
  const dal_system *sys = dal_scene_system(c->sc);
  double T = period_of(c);
  if (T <= 0) return cli_error(c, DAL_E_ARG, "%s declares no period: give --period T", c->path);
  dal_state *st;
  int rc = dal_scene_state(c->sc, &st);
  if (rc) return cli_fail(c, rc, "the scene's initial state was refused");
  FILE *fp = cli_out(c);
  if (!fp) {
    dal_state_destroy(st);
    return cli_close(c, DAL_E_IO);
  }
  if (cli_given(c, "continue")) {
    rc = orbit_branch(c, fp, st, T);
    dal_state_destroy(st);
    if (rc < 0 && rc != DAL_E_IO && c->msg[0]) cli_fail(c, rc, c->msg);
    return cli_close(c, rc);
  }
  int n = dal_system_ncoords(sys), k2 = 2 * (n - dal_system_nconstraints(sys));
  double *re = calloc((size_t)k2 + 1, sizeof *re), *im = calloc((size_t)k2 + 1, sizeof *im);
  dal_orbit_opts o = dal_default_orbit_opts();
  o.period = T;
  o.free_period = cli_given(c, "free") > 0;
  dal_orbit_report r;
  double t0 = dal_state_time(st);
  rc = re && im ? dal_periodic_orbit(sys, st, &o, re, im, &r) : DAL_E_NOMEM;
  const double *q = dal_state_q(st), *v = dal_state_qdot(st);
  if (rc) {
    snprintf(c->msg, sizeof c->msg, "%s: %s", c->path, dal_state_errmsg(st));
  } else if (cli_json_asked(c)) {
    cli_json j = cli_json_start(fp);
    cli_json_str(&j, "command", "orbit");
    cli_json_str(&j, "scene", c->path);
    cli_json_num(&j, "t0", t0);
    write_report(&j, fp, &r.floquet, re, im);
    cli_json_object(&j, "orbit");
    cli_json_int(&j, "iterations", r.iterations);
    cli_json_num(&j, "residual", r.residual);
    json_coords(&j, "q", sys, q);
    json_coords(&j, "qdot", sys, v);
    cli_json_end(&j);
    cli_json_finish(&j);
  } else {
    fprintf(fp,
            "# periodic orbit of %s, period %.17g, from t = %.17g (%d Newton steps, return "
            "gap %.3g):",
            c->path, r.period, t0, r.iterations, r.residual);
    for (int i = 0; i < n; ++i)
      fprintf(fp, " %s = %.17g, %s' = %.17g", dal_system_coord_name(sys, i), q[i],
              dal_system_coord_name(sys, i), v[i]);
    fprintf(fp, "\n");
    write_report(NULL, fp, &r.floquet, re, im);
  }
  free(re);
  free(im);
  dal_state_destroy(st);
  if (rc) cli_fail(c, rc, c->msg);
  return cli_close(c, rc);
}
