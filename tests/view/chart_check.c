// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The analyses' --chart (tools/chart.c) read back: every dot of the section's chart is a point of
// the section's CSV, the Lyapunov chart's end dots and error bars are the exponents and their 95%
// half-widths, the sweep's dots are the final coordinates against the parameter, all through
// the panel's declared data -> px map; a chart that cannot be written leaves no file at all.
//   chart_check DALEMBERT SCENES_DIR WORK_DIR
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "../check.h"

static char cli[1024], scenes[1024], work[1024];

// run `dalembert ARGS` in the work folder; its exit status
static int run(const char *args) {
  char cmd[8192];
  snprintf(cmd, sizeof cmd, "cd '%s' && '%s' %s 2> err.txt", work, cli, args);
  int rc = system(cmd);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

static char *slurp(const char *name) {
  char path[2048];
  snprintf(path, sizeof path, "%s/%s", work, name);
  FILE *fp = fopen(path, "rb");
  if (!fp) return NULL;
  fseek(fp, 0, SEEK_END);
  long n = ftell(fp);
  rewind(fp);
  char *s = calloc((size_t)n + 1, 1);
  if (s && fread(s, 1, (size_t)n, fp) != (size_t)n) s[0] = 0;
  fclose(fp);
  return s;
}

static int exists(const char *name) {
  char path[2048];
  struct stat sb;
  snprintf(path, sizeof path, "%s/%s", work, name);
  return stat(path, &sb) == 0;
}

// panel k's map [ax, bx, ay, by] and the text of the panel (up to the next one)
static const char *panel(const char *svg, int k, double *A, const char **end) {
  const char *p = svg;
  for (int i = 0; i <= k && p; ++i)
    p = strstr(p + 1, "<g class=\"panel\"");
  if (!p) return NULL;
  const char *t = strstr(p, "data-transform=\"[");
  if (!t || sscanf(t, "data-transform=\"[%lf,%lf,%lf,%lf]", &A[0], &A[1], &A[2], &A[3]) != 4)
    return NULL;
  *end = strstr(p + 1, "<g class=\"panel\"");
  if (!*end) *end = p + strlen(p);
  return p;
}

// the dots of a panel's text [p, end): their centres (at most max)
static int dots(const char *p, const char *end, double *xy, int max) {
  int n = 0;
  while ((p = strstr(p, "<circle cx=")) && p < end && n < max) {
    if (sscanf(p, "<circle cx=\"%lf\" cy=\"%lf\"", &xy[2 * n], &xy[2 * n + 1]) == 2) ++n;
    ++p;
  }
  return n;
}

// the numbers of CSV line `line` (0: the header) from column `col` on
static int csv_row(const char *csv, int line, double *x, int max) {
  const char *p = csv;
  for (int i = 0; i < line && p; ++i)
    p = strchr(p, '\n'), p = p ? p + 1 : NULL;
  if (!p || !*p) return 0;
  int n = 0;
  while (n < max && *p && *p != '\n') {
    char *e;
    double v = strtod(p, &e);
    x[n++] = e == p ? NAN : v;
    p = e + strcspn(e, ",\n");
    if (*p == ',') ++p;
  }
  return n;
}

// run `dalembert ARGS` and read the chart and the CSV it wrote (NULL, both freed, when either
// is missing or the chart has no panel);
// the first panel's map into A and its text [return, *end)
static const char *charted(const char *args, const char *svg_name, const char *csv_name, char **svg,
                           char **csv, double *A, const char **end) {
  CHECK(run(args) == 0);
  *svg = slurp(svg_name), *csv = slurp(csv_name);
  CHECK(*svg && *csv);
  const char *p = *svg && *csv ? panel(*svg, 0, A, end) : NULL;
  CHECK(p != NULL);
  if (!p) free(*svg), free(*csv); // nothing to read
  return p;
}

// the section of the driven pendulum: each dot one CSV point (theta, theta_dot), in order
static void section(void) {
  char args[2048];
  snprintf(args, sizeof args,
           "section '%s/driven_pendulum.scene' --wrap --t1 60 -o sec.csv --chart sec.svg", scenes);
  char *svg, *csv;
  double A[4], xy[2 * 200], r[8], worst = 0;
  const char *end, *p = charted(args, "sec.svg", "sec.csv", &svg, &csv, A, &end);
  if (!p) return;
  int n = dots(p, end, xy, 200), rows = 0;
  while (csv_row(csv, rows + 1, r, 8) >= 3)
    ++rows;
  CHECK_MSG(n == rows && n > 50, "the chart has %d dots, the CSV %d points", n, rows);
  for (int i = 0; i < n && i < rows; ++i) {
    csv_row(csv, i + 1, r, 8); // t, theta, theta_dot, ...
    double e = hypot(xy[2 * i] - (A[0] + A[1] * r[1]), xy[2 * i + 1] - (A[2] + A[3] * r[2]));
    worst = fmax(worst, e);
  }
  CHECK_MSG(worst <= 1e-3, "a section dot is %.3g px from its CSV point", worst);
  CHECK(panel(svg, 1, A, &end) == NULL); // one coordinate, one panel
  printf("section: %d dots, each within %.1e px of its CSV point\n", n, worst);
  free(svg);
  free(csv);
}

// the exponents at the end: dots at t1 with bars of +-error95
static void lyapunov(void) {
  char args[2048];
  snprintf(args, sizeof args, "lyapunov '%s/driven_pendulum.scene' --t1 40 --chart ly.svg > ly.csv",
           scenes);
  char *svg, *csv;
  double A[4], xy[8], r[4], worst = 0;
  const char *end, *p = charted(args, "ly.svg", "ly.csv", &svg, &csv, A, &end);
  if (!p) return;
  int n = dots(p, end, xy, 4);
  CHECK_MSG(n == 2, "%d end dots for the pendulum's 2 exponents", n);
  const char *bar = p;
  for (int i = 0; i < n; ++i) {
    CHECK(csv_row(csv, i + 2, r, 4) == 3); // # comment, header, then exponent,value,error95
    worst =
        fmax(worst, hypot(xy[2 * i] - (A[0] + A[1] * 40), xy[2 * i + 1] - (A[2] + A[3] * r[1])));
    double x1, y1, x2, y2;
    bar = strstr(bar + 1, "<line class=\"err\"");
    CHECK(bar && sscanf(bar, "<line class=\"err\" x1=\"%lf\" y1=\"%lf\" x2=\"%lf\" y2=\"%lf\"", &x1,
                        &y1, &x2, &y2) == 4);
    if (!bar) break;
    worst = fmax(worst, fabs(y1 - (A[2] + A[3] * (r[1] - r[2]))));
    worst = fmax(worst, fabs(y2 - (A[2] + A[3] * (r[1] + r[2]))));
    worst = fmax(worst, fabs(x1 - xy[2 * i]) + fabs(x2 - xy[2 * i]));
  }
  CHECK_MSG(worst <= 1e-3, "an exponent or its bar is drawn %.3g px from the CSV's", worst);
  CHECK(strstr(p, "<polyline") != NULL); // the running estimates
  printf("lyapunov: 2 exponents and their bars within %.1e px of the CSV's\n", worst);
  free(svg);
  free(csv);
}

// the sweep over the drive amplitude (the driven pendulum's runs cut to t1 = 5 by
// short.scene): a dot per run, (a, theta at the end)
static void sweep(void) {
  char args[2048];
  snprintf(args, sizeof args,
           "sed 's/ t1=100 / t1=5 /' '%s/driven_pendulum.scene' > short.scene && grep -q t1=5 "
           "short.scene",
           scenes);
  char cmd[4096];
  snprintf(cmd, sizeof cmd, "cd '%s' && %s", work, args);
  CHECK(system(cmd) == 0);
  snprintf(args, sizeof args, "sweep short.scene --param a=0:0.1:11 -o sw.csv --chart sw.svg");
  char *svg, *csv;
  double A[4], xy[2 * 16], r[8], worst = 0;
  const char *end, *p = charted(args, "sw.svg", "sw.csv", &svg, &csv, A, &end);
  if (!p) return;
  int n = dots(p, end, xy, 16);
  CHECK_MSG(n == 11, "%d dots for 11 runs", n);
  for (int i = 0; i < n; ++i) {
    CHECK(csv_row(csv, i + 1, r, 8) >= 5); // index, a, status, theta, theta_dot, message
    worst =
        fmax(worst, hypot(xy[2 * i] - (A[0] + A[1] * r[1]), xy[2 * i + 1] - (A[2] + A[3] * r[3])));
  }
  CHECK_MSG(worst <= 1e-3, "a sweep dot is %.3g px from its CSV row", worst);
  printf("sweep: 11 dots within %.1e px of the CSV's rows\n", worst);
  free(svg);
  free(csv);
}

// a chart that cannot be written: a non-zero exit naming it, and neither file left
static void unwritable(void) {
  static const char *const cmds[] = {
      "section '%s/driven_pendulum.scene' -o bad1.csv --chart nodir/x.svg",
      "lyapunov '%s/driven_pendulum.scene' --t1 5 --chart nodir/x.svg > bad2.csv",
      "sweep short.scene --param a=0:0.1:3 -o bad3.csv --chart nodir/x.svg",
  };
  for (int i = 0; i < 3; ++i) {
    char args[2048], name[16];
    snprintf(args, sizeof args, cmds[i], scenes); // (the sweep's: no scene folder)
    CHECK_MSG(run(args) != 0, "'%s' succeeded", args);
    char *err = slurp("err.txt");
    CHECK_MSG(err && strstr(err, "nodir/x.svg"), "the message does not name the chart: %s",
              err ? err : "");
    free(err);
    snprintf(name, sizeof name, "bad%d.csv", i + 1);
    if (i != 1) CHECK_MSG(!exists(name), "%s was left behind", name); // 2: the shell's file
  }
}

int main(int argc, char **argv) {
  if (argc < 4) {
    fprintf(stderr, "usage: chart_check DALEMBERT SCENES_DIR WORK_DIR\n");
    return 2;
  }
  snprintf(cli, sizeof cli, "%s", argv[1]);
  snprintf(scenes, sizeof scenes, "%s", argv[2]);
  snprintf(work, sizeof work, "%s", argv[3]);
  char cmd[2200];
  snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s'", work, work);
  if (system(cmd)) return 1;
  section();
  lyapunov();
  sweep();
  unwritable();
  return check_summary("chart_check");
}
