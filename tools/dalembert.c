// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The dalembert command line: run a scene file (CSV, a gnuplot chart), show its equations,
// write it back normalized, and the analyses (cli.h lists the commands and options).
//
// The command table below: one row per command (its function and options table live in its
// own file and are declared in cli.h). Exit status: cli.h's table. Messages name the scene file
// and line.
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

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

const cli_opt cli_run_opts[] = {
    CLI_OPT_OUTPUT("the CSV of the run"),
    {"chart", 0, CLI_TEXT, "FILE.png", "a chart of the coordinates against t (gnuplot; needs -o)",
     0},
    {"events", 0, CLI_TEXT, "FILE.csv", "the log of the scene's events", 0},
    CLI_OPT_WRAP,
    CLI_OPT_T1,
    {"columns", 0, CLI_TEXT, "LIST",
     "named columns, e.g. 't,x:*,y:*,lambda:*' (docs/guide.md: Seeing the motion)", 0},
    CLI_END,
};

int cli_run(cli *c) {
  const char *png = cli_text(c, "chart"), *evpath = cli_text(c, "events");
  if (png && !cli_text(c, "output")) return cli_error(c, CLI_USAGE, "--chart needs -o FILE.csv");
  FILE *fp = cli_out(c);
  if (!fp) return DAL_E_IO;
  dal_events *ev = NULL;
  int rc = dal_scene_events(c->sc, &ev);
  double dt;
  dal_scene_opts(c->sc, NULL, NULL, &dt);
  if (!rc) rc = cli_evolve(c, fp, ev, dt, "run: t");
  if (rc >= 0 && evpath) {
    cli_file ef;
    int er = cli_open(c, evpath, &ef);
    if (!er && dal_events_write_csv(ev, ef.fp, -1, 0)) er = DAL_E_IO;
    er = cli_commit(c, &ef, er);
    if (er < 0) rc = er;
  }
  dal_events_destroy(ev);
  rc = cli_close(c, rc);
  if (rc >= 0 && png) rc = chart(c->sc, cli_text(c, "output"), png);
  return rc;
}

const cli_opt cli_show_opts[] = {
    {"text", 0, CLI_FLAG, NULL, "as plain text (the default)", 0},
    {"latex", 0, CLI_FLAG, NULL, "as LaTeX", 0},
    {"scheme", 0, CLI_FLAG, NULL, "as Scheme (SICM's notation)", 0},
    CLI_END,
};

int cli_show(cli *c) {
  int n = cli_given(c, "text") + cli_given(c, "latex") + cli_given(c, "scheme");
  if (n > 1) return cli_error(c, CLI_USAGE, "one of --text, --latex, --scheme");
  dal_expr_format fmt = cli_given(c, "latex")    ? DAL_EXPR_LATEX
                        : cli_given(c, "scheme") ? DAL_EXPR_SCHEME
                                                 : DAL_EXPR_TEXT;
  return cli_fail(c, dal_scene_show(c->sc, stdout, fmt, c->msg, sizeof c->msg), c->msg);
}

const cli_opt cli_write_opts[] = {CLI_END};

int cli_write(cli *c) { return dal_scene_write(c->sc, stdout); }

// one row per command: the order of the help
static const cli_cmd commands[] = {
    {"run", cli_run, cli_run_opts, "SCENE", "run the scene: a CSV row every dt from t0 to t1"},
    {"show", cli_show, cli_show_opts, "SCENE",
     "the scene's equations: T, U, L, the mass matrix, forces, accelerations"},
    {"write", cli_write, cli_write_opts, "SCENE", "the scene written back, normalized"},
    {"modes", cli_modes, cli_modes_opts, "SCENE",
     "normal modes at the equilibrium Newton finds from the initial q"},
    {"equilibria", cli_equilibria, cli_equilibria_opts, "SCENE",
     "equilibria from the initial q (and scanned starts), their stability"},
    {"lyapunov", cli_lyapunov, cli_lyapunov_opts, "SCENE",
     "Lyapunov exponents with 95% half-widths"},
    {"section", cli_section, cli_section_opts, "SCENE",
     "the scene's Poincare section (stroboscopic or a surface)"},
    {"sweep", cli_sweep, cli_sweep_opts, "SCENE",
     "final states over a grid of a scene parameter (threads or MPI)"},
    {"floquet", cli_floquet, cli_floquet_opts, "SCENE",
     "Floquet multipliers of the initial state over a period (the scene's strobe period)"},
    {"orbit", cli_orbit, cli_orbit_opts, "SCENE",
     "a periodic orbit by shooting from the initial state, its multipliers and branch"},
    {"view", cli_view, cli_view_opts, "SCENE",
     "the motion as one self-contained HTML page (scene, trails, linked plots)"},
    {"picture", cli_picture, cli_picture_opts, "SCENE",
     "a multi-exposure SVG of the configurations at chosen times"},
    {"compile", cli_compile, cli_compile_opts, "SCENE",
     "the scene's formulas as a standalone C source (dalembert/codegen.h)"},
    {NULL, NULL, NULL, NULL, NULL},
};

int main(int argc, char **argv) {
  cli c;
  memset(&c, 0, sizeof c);
  const char *ci = getenv("CI");
  c.progress = isatty(2) && !(ci && *ci);
  int done, rc = cli_parse(&c, commands, argc, argv, &done);
  if (!done) {
    cli_catch_interrupt();
    c.text = cli_read_text(&c, c.path);
    rc = c.text ? dal_scene_parse(c.text, c.path, &c.sc, c.msg, sizeof c.msg) : DAL_E_IO;
    if (rc && c.text) cli_fail(&c, rc, c.msg);
    if (!rc && (rc = cli_set_params(&c, c.sc, c.msg, sizeof c.msg)) < 0) cli_fail(&c, rc, c.msg);
    if (!rc && c.native && c.msg[0])
      fprintf(stderr, "dalembert %s: note: %s\n", c.cmd->name, c.msg);
    if (!rc) rc = c.cmd->fn(&c);
    dal_scene_destroy(c.sc);
    free(c.text);
    rc = rc == CLI_USAGE ? rc : cli_exit(rc);
  }
  // standard output too: a result that could not be written is a failure
  cli_file out = {stdout, NULL, NULL, 0};
  if (cli_commit(&c, &out, DAL_OK) < 0 && rc == 0) rc = cli_exit(DAL_E_IO);
  if (cli_interrupted() && rc != CLI_USAGE) rc = CLI_INTERRUPTED;
  free(c.sets);
  return rc;
}
