// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The dalembert command line: run a scene file (CSV, a gnuplot chart), show its equations,
// write it back normalized, and the analyses (cli.h lists the commands and options).
//
// Exit status: 0 on success (a run a terminal event stopped early included), else minus the
// library's status (DAL_E_ARG -> 1, DAL_E_DOMAIN -> 4, DAL_E_CONV -> 11, DAL_E_UNSUPPORTED ->
// 15, DAL_E_IO -> 16, ...: the list in dalembert/base.h), 64 for a command line it does not
// understand. Messages name the scene file and line.
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

int cli_usage(void) {
  fprintf(
      stderr,
      "usage: dalembert run SCENE [-o FILE.csv] [--chart FILE.png] [--events FILE.csv] [--wrap]\n"
      "       dalembert show SCENE [--text | --latex | --scheme]\n"
      "       dalembert write SCENE\n"
      "       dalembert modes SCENE [--here]\n"
      "       dalembert equilibria SCENE [--scan COORD=LO:HI:N]\n"
      "       dalembert lyapunov SCENE [--t1 T] [--transient T] [--renorm T] [--nexp K]\n"
      "                          [--method M] [--h H]\n"
      "       dalembert section SCENE [-o FILE.csv] [--surface] [--wrap]\n"
      "       dalembert sweep SCENE --param NAME=LO:HI:N [--threads K] [--mpi] [-o FILE.csv]\n"
      "       dalembert floquet SCENE [--period T] [--format json]\n"
      "       dalembert orbit SCENE [--period T] [--free] [--continue NAME=LO:HI:N]\n"
      "                       [--format json]\n"
      "modes, equilibria: [--frozen] (the linearization frozen at t0, by name)\n"
      "every command: [--set NAME=VALUE]... [--progress | --no-progress]\n");
  return 64;
}

// a chart of the coordinates against t from the CSV, by gnuplot when it is installed
static int chart(const dal_scene *sc, const char *csv, const char *png) {
  const dal_system *sys = dal_scene_system(sc);
  FILE *gp = popen("gnuplot 2>/dev/null", "w");
  if (!gp) {
    fprintf(stderr, "dalembert: gnuplot not found; no chart\n");
    return DAL_E_IO;
  }
  fprintf(gp,
          "set terminal pngcairo size 900,500\nset output '%s'\nset datafile separator ','\n"
          "set key autotitle columnhead\nset xlabel 't'\nplot ",
          png);
  int n = dal_system_ncoords(sys);
  for (int i = 0; i < n; ++i)
    fprintf(gp, "%s'%s' using 1:%d with lines", i ? ", " : "", csv, i + 2);
  fprintf(gp, "\n");
  int rc = pclose(gp);
  if (rc) fprintf(stderr, "dalembert: gnuplot failed (status %d); no chart\n", rc);
  return rc ? DAL_E_IO : DAL_OK;
}

static int cmd_run(cli *c) {
  if (c->png && !c->out) {
    fprintf(stderr, "dalembert: --chart needs -o FILE.csv\n");
    return DAL_E_ARG;
  }
  FILE *fp = cli_out(c);
  if (!fp) return DAL_E_IO;
  dal_events *ev = NULL;
  int rc = dal_scene_events(c->sc, &ev);
  double dt;
  dal_scene_opts(c->sc, NULL, NULL, &dt);
  if (!rc) rc = cli_evolve(c, fp, ev, dt, "run: t");
  if (rc >= 0 && c->events) {
    FILE *ef = fopen(c->events, "w");
    if (!ef || dal_events_write_csv(ev, ef, -1, 0)) {
      fprintf(stderr, "dalembert: cannot write %s\n", c->events);
      rc = DAL_E_IO;
    }
    if (ef && fclose(ef)) rc = DAL_E_IO;
  }
  dal_events_destroy(ev);
  rc = cli_close(c, fp, rc);
  if (rc >= 0 && c->png) rc = chart(c->sc, c->out, c->png);
  return rc;
}

// one NAME=VALUE of --set
static int set_one(cli *c, char *arg) {
  char *eq = strchr(arg, '='), *end;
  if (!eq) return 64;
  *eq = 0;
  double v = strtod(eq + 1, &end);
  if (end == eq + 1 || *end) {
    fprintf(stderr, "dalembert: --set %s: '%s' is not a number\n", arg, eq + 1);
    return DAL_E_ARG;
  }
  return cli_fail(dal_scene_set_param(c->sc, arg, v, c->msg, sizeof c->msg), c->msg);
}

// the value after option argv[*i] as a number
static int num_arg(int argc, char **argv, int *i, double *v) {
  char *end;
  if (*i + 1 >= argc) return 64;
  *v = strtod(argv[++*i], &end);
  if (end == argv[*i] || *end) {
    fprintf(stderr, "dalembert: %s: '%s' is not a number\n", argv[*i - 1], argv[*i]);
    return DAL_E_ARG;
  }
  return DAL_OK;
}

// options that take a string
static int str_opt(cli *c, const char *o, const char *v) {
  static const char *const names[] = {"-o",      "--chart",  "--events", "--scan",
                                      "--param", "--method", "--format", "--continue"};
  const char **dst[] = {&c->out,   &c->png,    &c->events, &c->scan,
                        &c->param, &c->method, &c->format, &c->cont};
  for (int k = 0; k < 8; ++k)
    if (!strcmp(o, names[k])) {
      *dst[k] = v;
      return 1;
    }
  return 0;
}

// options that take a number
static double *num_opt(cli *c, const char *o) {
  static const char *const names[] = {"--t1", "--transient", "--renorm",
                                      "--h",  "--nexp",      "--threads", "--period"};
  double *dst[] = {&c->t1, &c->transient, &c->renorm, &c->h, &c->nexp, &c->threads, &c->period};
  for (int k = 0; k < 7; ++k)
    if (!strcmp(o, names[k])) return dst[k];
  return NULL;
}

// flags
static int flag_opt(cli *c, const char *o) {
  static const char *const names[] = {"--here", "--surface", "--wrap",
                                      "--mpi",  "--frozen",  "--free"};
  int *dst[] = {&c->here, &c->surface, &c->wrap, &c->mpi, &c->frozen, &c->free_period};
  for (int k = 0; k < 6; ++k)
    if (!strcmp(o, names[k])) {
      *dst[k] = 1;
      return 1;
    }
  if (!strcmp(o, "--progress"))
    c->progress = 1;
  else if (!strcmp(o, "--no-progress"))
    c->progress = 0;
  else if (!strcmp(o, "--text"))
    c->fmt = DAL_EXPR_TEXT;
  else if (!strcmp(o, "--latex"))
    c->fmt = DAL_EXPR_LATEX;
  else if (!strcmp(o, "--scheme"))
    c->fmt = DAL_EXPR_SCHEME;
  else
    return 0;
  return 1;
}

static int parse(cli *c, int argc, char **argv) {
  for (int i = 3; i < argc; ++i) {
    double *d;
    int rc = DAL_OK;
    if (flag_opt(c, argv[i])) continue;
    if (!strcmp(argv[i], "--set") && i + 1 < argc)
      rc = set_one(c, argv[++i]);
    else if (i + 1 < argc && str_opt(c, argv[i], argv[i + 1]))
      ++i;
    else if ((d = num_opt(c, argv[i])))
      rc = num_arg(argc, argv, &i, d);
    else
      rc = 64;
    if (rc) return rc;
  }
  return DAL_OK;
}

typedef int command_fn(cli *c);

static int cmd_show(cli *c) {
  return cli_fail(dal_scene_show(c->sc, stdout, c->fmt, c->msg, sizeof c->msg), c->msg);
}

static int cmd_write(cli *c) { return dal_scene_write(c->sc, stdout); }

static const struct {
  const char *name;
  command_fn *fn;
} commands[] = {
    {"run", cmd_run},
    {"show", cmd_show},
    {"write", cmd_write},
    {"modes", cli_modes},
    {"equilibria", cli_equilibria},
    {"lyapunov", cli_lyapunov},
    {"section", cli_section},
    {"sweep", cli_sweep},
    {"floquet", cli_floquet},
    {"orbit", cli_orbit},
};

int main(int argc, char **argv) {
  if (argc < 3) return cli_usage();
  command_fn *fn = NULL;
  for (size_t k = 0; k < sizeof commands / sizeof *commands; ++k)
    if (!strcmp(argv[1], commands[k].name)) fn = commands[k].fn;
  if (!fn) return cli_usage();
  cli c;
  memset(&c, 0, sizeof c);
  c.path = argv[2];
  c.fmt = DAL_EXPR_TEXT;
  c.nexp = 0;
  c.threads = 1;
  c.t1 = c.transient = c.renorm = c.h = -1;
  const char *ci = getenv("CI");
  c.progress = isatty(2) && !(ci && *ci);
  c.argc = argc;
  c.argv = argv;
  int rc = dal_scene_read(c.path, &c.sc, c.msg, sizeof c.msg);
  if (rc) {
    fprintf(stderr, "dalembert: %s\n", c.msg);
    return cli_status_exit(rc);
  }
  c.period = -1;
  rc = parse(&c, argc, argv);
  if (!rc && c.format) {
    c.json = !strcmp(c.format, "json");
    if (!c.json && strcmp(c.format, "text")) {
      fprintf(stderr, "dalembert: --format %s: 'json' or 'text'\n", c.format);
      rc = DAL_E_ARG;
    }
  }
  if (!rc) rc = fn(&c);
  dal_scene_destroy(c.sc);
  return rc == 64 ? cli_usage() : cli_status_exit(rc);
}
