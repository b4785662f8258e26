// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// dalembert view SCENE [-o FILE.html]: the motion as one self-contained HTML page
// (dal_view_write), and dalembert picture SCENE -o FILE.svg: a multi-exposure
// (dal_picture_write); each written under a temporary name, renamed when complete.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

const cli_opt cli_view_opts[] = {
    {"output", 'o', CLI_TEXT, "FILE.html", "the page (default: the scene's name with .html)", 0},
    CLI_OPT_T1,
    {"fps", 0, CLI_POSITIVE, "F", "frames per second of motion time (default 60)", 0},
    CLI_END,
};

int cli_view(cli *c) {
  const dal_system *sys = dal_scene_system(c->sc);
  double t0, t1;
  dal_solve_opts so = *dal_scene_opts(c->sc, &t0, &t1, NULL);
  so.cancel = cli_cancel; // Ctrl-C: the page ends where the motion stopped
  dal_view_opts o = dal_default_view_opts();
  o.t1 = cli_num(c, "t1", t1); // an end time, as every command's --t1
  o.fps = cli_num(c, "fps", o.fps);
  o.solve = &so;
  o.title = c->path;
  o.strobe = dal_scene_strobe(c->sc);
  // the page's name: -o, else the scene's with .html
  char name[4096];
  const char *out = cli_text(c, "output");
  if (!out) {
    snprintf(name, sizeof name - 8, "%s", c->path);
    char *dot = strrchr(name, '.'), *slash = strrchr(name, '/');
    if (dot && (!slash || dot > slash)) *dot = 0;
    strcat(name, ".html");
    out = name;
  }
  dal_state *st = NULL;
  dal_events *ev = NULL;
  cli_file f;
  int rc = dal_scene_state(c->sc, &st);
  if (rc) return cli_fail(c, rc, "the scene's initial state was refused");
  rc = dal_scene_events(c->sc, &ev);
  // the section lines' crossings are section points, the other events' are not
  int nev = ev ? dal_events_size(ev) : 0, *sections = calloc((size_t)nev + 1, sizeof *sections);
  for (int i = 0; i < nev && sections; ++i)
    sections[i] = dal_scene_event_is_section(c->sc, i) == 1;
  o.sections = sections;
  if (!rc && !sections) rc = cli_error(c, DAL_E_NOMEM, "out of memory");
  if (!rc) rc = cli_open(c, out, &f);
  if (!rc) {
    rc = dal_view_write(sys, st, &o, ev, f.fp);
    if (rc < 0) cli_error(c, rc, "%s: %s", c->path, dal_state_errmsg(st));
    if (rc == DAL_CANCELLED)
      cli_error(c, 0, "interrupted at t = %.17g: the page ends there", dal_state_time(st));
    rc = cli_commit(c, &f, rc);
  }
  if (rc >= 0)
    fprintf(stderr, "dalembert view: wrote %s (%s#t=1.25 opens it at t = 1.25)\n", out, out);
  free(sections);
  dal_events_destroy(ev);
  dal_state_destroy(st);
  return rc;
}

const cli_opt cli_picture_opts[] = {
    {"output", 'o', CLI_TEXT, "FILE.svg", "the picture (required)", 0},
    {"times", 0, CLI_TEXT, "T1,T2,...",
     "the times drawn (default: 9 from t0 to --t1, or over the first 2 s)", 0},
    CLI_OPT_T1,
    CLI_END,
};

int cli_picture(cli *c) {
  const char *out = cli_text(c, "output"), *list = cli_text(c, "times");
  if (!out) return cli_error(c, CLI_USAGE, "picture needs -o FILE.svg");
  const dal_system *sys = dal_scene_system(c->sc);
  double t0, t1;
  dal_solve_opts so = *dal_scene_opts(c->sc, &t0, &t1, NULL);
  so.cancel = cli_cancel;
  // the times: --times, else 9 from t0 to --t1 (default: the first 2 s of the run)
  double times[1000];
  size_t n = 0;
  if (list) {
    for (const char *p = list; *p && n < 1000; ++n) {
      char *end;
      times[n] = strtod(p, &end);
      if (end == p || (*end && *end != ','))
        return cli_error(c, CLI_USAGE, "--times '%s': not a comma-separated list of numbers", list);
      p = *end ? end + 1 : end;
    }
  } else {
    double span = cli_num(c, "t1", t1 - t0 < 2 ? t1 : t0 + 2) - t0;
    for (n = 0; n < 9; ++n)
      times[n] = t0 + span * (double)n / 8;
  }
  dal_state *st = NULL;
  cli_file f;
  int rc = dal_scene_state(c->sc, &st);
  if (rc) return cli_fail(c, rc, "the scene's initial state was refused");
  rc = cli_open(c, out, &f);
  if (!rc) {
    rc = dal_picture_write(sys, st, times, n, &so, f.fp);
    if (rc < 0) cli_error(c, rc, "%s: %s", c->path, dal_state_errmsg(st));
    if (rc == DAL_CANCELLED) rc = cli_error(c, DAL_E_ARG, "interrupted: no picture");
    rc = cli_commit(c, &f, rc);
  }
  dal_state_destroy(st);
  return rc;
}
