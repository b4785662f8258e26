// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// dalembert view SCENE [-o FILE.html] [--t1 T] [--fps F]: the motion as one self-contained
// HTML page (output.h: dal_view_write), written to a temporary file renamed when complete.
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

int cli_view(cli *c) {
  const dal_system *sys = dal_scene_system(c->sc);
  double t0, t1;
  const dal_solve_opts *so = dal_scene_opts(c->sc, &t0, &t1, NULL);
  dal_view_opts o = dal_default_view_opts();
  o.t1 = c->t1 > 0 ? t0 + c->t1 : t1;
  if (c->fps > 0) o.fps = c->fps;
  o.solve = so;
  o.title = c->path;
  o.strobe = dal_scene_strobe(c->sc);
  // the page's name: -o, else the scene's with .html
  char out[1024], tmp[1100];
  if (c->out)
    snprintf(out, sizeof out, "%s", c->out);
  else {
    snprintf(out, sizeof out, "%s", c->path);
    char *dot = strrchr(out, '.'), *slash = strrchr(out, '/');
    if (dot && (!slash || dot > slash)) *dot = 0;
    strncat(out, ".html", sizeof out - strlen(out) - 1);
  }
  snprintf(tmp, sizeof tmp, "%s.part", out);
  dal_state *st = NULL;
  dal_events *ev = NULL;
  int rc = dal_scene_state(c->sc, &st);
  if (rc) return cli_fail(rc, "the scene's initial state was refused");
  rc = dal_scene_events(c->sc, &ev);
  FILE *fp = rc ? NULL : fopen(tmp, "w");
  if (!rc && !fp) {
    snprintf(c->msg, sizeof c->msg, "cannot write %.1000s", tmp);
    rc = DAL_E_IO;
  }
  if (fp) {
    rc = dal_view_write(sys, st, &o, ev, fp);
    if (rc) snprintf(c->msg, sizeof c->msg, "%s: %s", c->path, dal_state_errmsg(st));
    if (fclose(fp) && !rc) {
      snprintf(c->msg, sizeof c->msg, "writing %.1000s failed", tmp);
      rc = DAL_E_IO;
    }
    // only a complete page takes the name
    if (!rc && rename(tmp, out)) {
      snprintf(c->msg, sizeof c->msg, "cannot rename %.900s to %.900s", tmp, out);
      rc = DAL_E_IO;
    }
    if (rc) remove(tmp);
  }
  if (!rc) fprintf(stderr, "dalembert: wrote %s (open it in a browser; %s#t=1.25 opens at t = 1.25)\n", out, out);
  dal_events_destroy(ev);
  dal_state_destroy(st);
  return cli_fail(rc, c->msg);
}

int cli_picture(cli *c) {
  if (!c->out) {
    fprintf(stderr, "dalembert: picture needs -o FILE.svg\n");
    return DAL_E_ARG;
  }
  const dal_system *sys = dal_scene_system(c->sc);
  double t0, t1;
  const dal_solve_opts *so = dal_scene_opts(c->sc, &t0, &t1, NULL);
  // the times: --times, else 9 over the first 2 s (or --t1 T) of the run
  double times[1000];
  size_t n = 0;
  if (c->times) {
    const char *p = c->times;
    while (*p && n < 1000) {
      char *end;
      times[n] = strtod(p, &end);
      if (end == p || (*end && *end != ',')) {
        fprintf(stderr, "dalembert: --times '%s': not a comma-separated list of numbers\n",
                c->times);
        return DAL_E_ARG;
      }
      ++n;
      p = *end ? end + 1 : end;
    }
  } else {
    double span = c->t1 > 0 ? c->t1 : (t1 - t0 < 2 ? t1 - t0 : 2);
    for (n = 0; n < 9; ++n)
      times[n] = t0 + span * (double)n / 8;
  }
  char tmp[1100];
  snprintf(tmp, sizeof tmp, "%.1000s.part", c->out);
  dal_state *st = NULL;
  int rc = dal_scene_state(c->sc, &st);
  if (rc) return cli_fail(rc, "the scene's initial state was refused");
  FILE *fp = fopen(tmp, "w");
  if (!fp) {
    snprintf(c->msg, sizeof c->msg, "cannot write %.1000s", tmp);
    rc = DAL_E_IO;
  } else {
    rc = dal_picture_write(sys, st, times, n, so, fp);
    if (rc) snprintf(c->msg, sizeof c->msg, "%.1000s: %.900s", c->path, dal_state_errmsg(st));
    if (fclose(fp) && !rc) {
      snprintf(c->msg, sizeof c->msg, "writing %.1000s failed", tmp);
      rc = DAL_E_IO;
    }
    if (!rc && rename(tmp, c->out)) {
      snprintf(c->msg, sizeof c->msg, "cannot rename %.1000s", tmp);
      rc = DAL_E_IO;
    }
    if (rc) remove(tmp);
  }
  dal_state_destroy(st);
  return cli_fail(rc, c->msg);
}
