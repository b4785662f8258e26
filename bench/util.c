// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Benchmark utilities: monotonic clock, medians, CSV files, names of methods/formulations.
#define _POSIX_C_SOURCE 200809L
#include "util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

double bench_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

double bench_median(double *v, int n) {
  if (n <= 0) return NAN;
  qsort(v, (size_t)n, sizeof(double), cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

FILE *bench_csv_open(const char *dir, const char *name, const char *header) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *fp = fopen(path, "w");
  if (!fp) {
    fprintf(stderr, "dal_bench: cannot write %s\n", path);
    return NULL;
  }
  fprintf(fp, "%s\n", header);
  return fp;
}

double bench_maxdiff(const double *a, const double *b, int n) {
  double m = 0.0;
  for (int i = 0; i < n; ++i) {
    double d = fabs(a[i] - b[i]);
    if (isnan(d)) return NAN;
    if (d > m) m = d;
  }
  return m;
}

const char *bench_form_name(bench_form f) {
  static const char *names[BF_COUNT] = {"ode",         "ggl",    "index1",     "index1-baumgarte",
                                        "index1-proj", "index3", "handwritten"};
  return f >= 0 && f < BF_COUNT ? names[f] : "?";
}

void bench_opts(dal_solve_opts *o, bench_form f, dal_method m, double rtol) {
  *o = dal_default_solve_opts();
  o->method = m;
  o->rtol = rtol;
  o->atol = rtol;
  o->fixed_step = 0.5 * pow(rtol, 0.25);
  o->max_steps = 5000000;
  switch (f) {
  case BF_ODE:
    o->form = DAL_FORM_ODE;
    break;
  case BF_GGL:
    o->form = DAL_FORM_GGL;
    break;
  case BF_INDEX3:
    o->form = DAL_FORM_INDEX3;
    break;
  case BF_INDEX1:
    o->form = DAL_FORM_INDEX1;
    break;
  case BF_INDEX1_BAUMGARTE:
    o->form = DAL_FORM_INDEX1;
    o->baumgarte_alpha = 20.0;
    o->baumgarte_beta = 100.0;
    break;
  case BF_INDEX1_PROJ:
    o->form = DAL_FORM_INDEX1;
    o->project = 1;
    break;
  default:
    o->form = DAL_FORM_AUTO;
  }
}
