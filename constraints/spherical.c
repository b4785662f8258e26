// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Spherical pendulum about a fixed pivot (polar angle from the downward vertical).
#include "dalembert/primitives.h"

static int spherical(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  (void)t;
  double l = p[0];
  dal_jet st = dal_sin(in[0]);
  out[0] = dal_addc(dal_scale(dal_mul(st, dal_cos(in[1])), l), p[1]);
  out[1] = dal_addc(dal_scale(dal_mul(st, dal_sin(in[1])), l), p[2]);
  out[2] = dal_addc(dal_scale(dal_cos(in[0]), -l), p[3]);
  return 0;
}

const dal_primitive dal_map_spherical = {
    "spherical", 1, 2, 3, 4, spherical,
    "in (theta, phi); param (l, x0, y0, z0); out pivot + l (s cos ph, s sin ph, -cos th)", 0};
