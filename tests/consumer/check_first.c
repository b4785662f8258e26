// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Checks the README's first program's answer (read on stdin) against the exact pendulum.
//
// The program releases a pendulum (g/l = 9.81) at 1 rad from rest and prints
// "theta(10) = <x>" after integrating at rtol 1e-10. The reference is the Jacobi-elliptic
// closed form (tests/ref_elliptic.h); the README promises the error within 16 x rtol, i.e.
// 1.6e-9 rad here. Exit status 0 when the line is there and within the bound.
#include <math.h>
#include <stdio.h>

#include "ref_elliptic.h"

int main(void) {
  char line[256];
  double x = NAN;
  int found = 0;
  while (fgets(line, sizeof line, stdin)) {
    fputs(line, stdout);
    if (sscanf(line, "theta(10) = %lf", &x) == 1) found = 1;
  }
  double ref, refdot;
  ref_pendulum(1.0, sqrt(9.81), 10.0, &ref, &refdot);
  double err = fabs(x - ref), bound = 16.0 * 1e-10;
  if (!found || !(err <= bound)) {
    printf("first program: %s; exact theta(10) = %.12f, error %.3g rad, bound %.3g\n",
           found ? "wrong answer" : "no 'theta(10) = ' line", ref, err, bound);
    return 1;
  }
  printf("first program: theta(10) agrees with the exact %.12f to %.2g rad (bound %.2g: 16 x "
         "rtol)\n",
         ref, err, bound);
  return 0;
}
