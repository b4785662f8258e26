// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A user's program that calls libm (sin, pow) beside the library: built by
// scripts/readme_install.sh with the README's link lines and the guide's CMake block verbatim,
// it must link (-lm comes with them) and print sin(x) equal to its Taylor series.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "dalembert/dalembert.h"

int main(int argc, char **argv) {
  double x = argc > 1 ? atof(argv[1]) : 0.5; // read at run time: the compiler cannot fold sin
  double s = sin(x), series = 0, term = x;
  for (int k = 1; k < 20; ++k) { // x - x^3/3! + x^5/5! - ...
    series += term;
    term *= -x * x / ((2.0 * k) * (2.0 * k + 1));
  }
  printf("sin(%g) = %.15f, its series %.15f, dalembert %s\n", x, s, series, dal_version());
  return fabs(s - series) <= 1e-15 ? 0 : 1;
}
