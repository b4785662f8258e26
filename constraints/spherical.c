// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Spherical pendulum about a fixed pivot (polar angle from the downward vertical).
#include <math.h>

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

static const char *const spherical_names[] = {"l", "x0", "y0", "z0"};
static const double spherical_defaults[] = {NAN, 0.0, 0.0, 0.0};
const dal_primitive dal_map_spherical = {
    .name = "spherical",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 2,
    .nout = 3,
    .nparam = 4,
    .eval = spherical,
    .doc = "in (theta, phi); param (l, x0, y0, z0); out pivot + l (s cos ph, s sin ph, -cos th)",
    .flags = 0,
    .param_names = spherical_names,
    .param_defaults = spherical_defaults,
};
