// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The command line's services below its commands: exit status, messages, the progress line,
// the output file and grid specifications (cli.h).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

int cli_status_exit(int rc) { return rc < 0 ? -rc : 0; }

int cli_fail(int rc, const char *msg) {
  if (rc < 0) fprintf(stderr, "dalembert: %s\n", msg);
  return rc;
}

void cli_progress(const cli *c, const char *what, double done, double total, const char *extra) {
  static double last = -1; // the fraction shown last: a line every 0.5% (calls are serialized)
  if (!c->progress) return;
  double f = total > 0 ? done / total : 1;
  if (f < 1 && last >= 0 && f - last < 0.005 && f >= last) return;
  last = f >= 1 ? -1 : f;
  fprintf(stderr, "\r%s: %.4g / %.4g%s%s   ", what, done, total, extra ? " " : "",
          extra ? extra : "");
  if (done >= total) fputc('\n', stderr);
  fflush(stderr);
}

FILE *cli_out(const cli *c) {
  FILE *fp = c->out ? fopen(c->out, "w") : stdout;
  if (!fp) fprintf(stderr, "dalembert: cannot write %s\n", c->out);
  return fp;
}

int cli_close(const cli *c, FILE *fp, int rc) {
  if (fp && fp != stdout && fclose(fp) && rc >= 0) {
    fprintf(stderr, "dalembert: writing %s failed\n", c->out);
    return DAL_E_IO;
  }
  return rc;
}

int cli_grid(const char *spec, char *buf, size_t len, double *lo, double *hi, int *n) {
  snprintf(buf, len, "%s", spec ? spec : "");
  char *eq = strchr(buf, '=');
  if (!eq || sscanf(eq + 1, "%lf:%lf:%d", lo, hi, n) != 3 || *n < 1 || !isfinite(*lo) ||
      !isfinite(*hi)) {
    fprintf(stderr, "dalembert: '%s' is not NAME=LO:HI:N (N >= 1)\n", spec ? spec : "");
    return DAL_E_ARG;
  }
  *eq = 0;
  return DAL_OK;
}
