// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Benchmark utilities: monotonic clock, medians, CSV files, names of methods/formulations.
#ifndef DAL_BENCH_UTIL_H
#define DAL_BENCH_UTIL_H

#include <stdio.h>

#include "dalembert/solve.h"

/// Seconds on the monotonic clock.
double bench_now(void);

/// Median of v (n values; v is sorted in place).
double bench_median(double *v, int n);

/// Open dir/name for writing and write the header line; NULL (with a message) on failure.
FILE *bench_csv_open(const char *dir, const char *name, const char *header);

/// Max-norm of a - b over n values (NaN if any value is NaN).
double bench_maxdiff(const double *a, const double *b, int n);

/// Benchmark formulations: the library's plus the variants of index-1 and the baseline.
typedef enum bench_form {
  BF_ODE,
  BF_GGL,
  BF_INDEX1,
  BF_INDEX1_BAUMGARTE,
  BF_INDEX1_PROJ,
  BF_INDEX3,
  BF_HAND,
  BF_COUNT
} bench_form;

/// CSV name of a formulation: ode, ggl, index1, index1-baumgarte, index1-proj, index3,
/// handwritten.
const char *bench_form_name(bench_form f);

/// Fill library options for a formulation, method and tolerance (atol = rtol; Baumgarte
/// alpha = 20 /s, beta = 100 /s^2, i.e. critically damped at 10 rad/s). RK4 uses the fixed
/// step h = 0.5 rtol^(1/4).
void bench_opts(dal_solve_opts *o, bench_form f, dal_method m, double rtol);

/// The exact pendulum of tests/ref_elliptic.h (written independently of bench/ref.h):
/// theta(t), thetadot(t) released from rest at th0, w0 = sqrt(g/l).
void bench_tests_pendulum(double th0, double w0, double t, double *th, double *thd);

#endif
