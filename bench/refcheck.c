// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The tests' Jacobi-elliptic pendulum (tests/ref_elliptic.h), for the benchmark to check its
// own reference (bench/ref.h) against an independently written one.
#include "util.h"

#include "ref_elliptic.h"

void bench_tests_pendulum(double th0, double w0, double t, double *th, double *thd) {
  ref_pendulum(th0, w0, t, th, thd);
}
