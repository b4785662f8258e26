// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The dalembert command line: run a scene file (CSV, a gnuplot chart), show its equations,
// write it back normalized.
//
//   dalembert run SCENE [-o FILE.csv] [--chart FILE.png] [--set NAME=VALUE]... [--quiet]
//   dalembert show SCENE [--text | --latex | --scheme] [--set NAME=VALUE]...
//   dalembert write SCENE [--set NAME=VALUE]...
//
// Exit status: 0 on success (a run a monitor or a terminal event stopped early included),
// else minus the library's status (DAL_E_ARG -> 1, DAL_E_DOMAIN -> 4, DAL_E_IO -> 16, ...: the
// list in dalembert/base.h), 64 for a command line it does not understand. Messages name the
// scene file and line.
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dalembert/dalembert.h"
#include "dalembert/scene.h"

static int usage(void) {
  fprintf(stderr,
          "usage: dalembert run SCENE [-o FILE.csv] [--chart FILE.png] [--set NAME=VALUE]...\n"
          "       dalembert show SCENE [--text | --latex | --scheme] [--set NAME=VALUE]...\n"
          "       dalembert write SCENE [--set NAME=VALUE]...\n");
  return 64;
}

static int status_exit(int rc) { return rc < 0 ? -rc : 0; }

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

int main(int argc, char **argv) {
  if (argc < 3) return usage();
  const char *cmd = argv[1], *path = argv[2], *out = NULL, *png = NULL;
  dal_expr_format fmt = DAL_EXPR_TEXT;
  char msg[2048];
  dal_scene *sc;
  int rc = dal_scene_read(path, &sc, msg, sizeof msg);
  if (rc) {
    fprintf(stderr, "dalembert: %s\n", msg);
    return status_exit(rc);
  }
  for (int i = 3; i < argc && !rc; ++i) {
    if (!strcmp(argv[i], "-o") && i + 1 < argc) {
      out = argv[++i];
    } else if (!strcmp(argv[i], "--chart") && i + 1 < argc) {
      png = argv[++i];
    } else if (!strcmp(argv[i], "--text")) {
      fmt = DAL_EXPR_TEXT;
    } else if (!strcmp(argv[i], "--latex")) {
      fmt = DAL_EXPR_LATEX;
    } else if (!strcmp(argv[i], "--scheme")) {
      fmt = DAL_EXPR_SCHEME;
    } else if (!strcmp(argv[i], "--set") && i + 1 < argc) {
      char *eq = strchr(argv[++i], '='), *end;
      if (!eq) {
        dal_scene_destroy(sc);
        return usage();
      }
      *eq = 0;
      double v = strtod(eq + 1, &end);
      if (end == eq + 1 || *end) {
        fprintf(stderr, "dalembert: --set %s: '%s' is not a number\n", argv[i], eq + 1);
        dal_scene_destroy(sc);
        return status_exit(DAL_E_ARG);
      }
      rc = dal_scene_set_param(sc, argv[i], v, msg, sizeof msg);
      if (rc) fprintf(stderr, "dalembert: %s\n", msg);
    } else {
      dal_scene_destroy(sc);
      return usage();
    }
  }
  if (!rc && !strcmp(cmd, "run")) {
    if (png && !out) {
      fprintf(stderr, "dalembert: --chart needs -o FILE.csv\n");
      dal_scene_destroy(sc);
      return usage();
    }
    FILE *fp = out ? fopen(out, "w") : stdout;
    if (!fp) {
      fprintf(stderr, "dalembert: cannot write %s\n", out);
      rc = DAL_E_IO;
    } else {
      rc = dal_scene_run(sc, fp, NULL, msg, sizeof msg);
      if (rc < 0) fprintf(stderr, "dalembert: %s\n", msg);
      if (out && fclose(fp)) rc = rc ? rc : DAL_E_IO;
      if (rc >= 0 && png) rc = chart(sc, out, png);
    }
  } else if (!rc && !strcmp(cmd, "show")) {
    rc = dal_scene_show(sc, stdout, fmt, msg, sizeof msg);
    if (rc) fprintf(stderr, "dalembert: %s\n", msg);
  } else if (!rc && !strcmp(cmd, "write")) {
    rc = dal_scene_write(sc, stdout);
  } else if (!rc) {
    dal_scene_destroy(sc);
    return usage();
  }
  dal_scene_destroy(sc);
  return status_exit(rc);
}
