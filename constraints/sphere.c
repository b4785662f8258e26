// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Point on a sphere of radius R centred at c (polar angle from +z), as a coordinate map.
#include <math.h>

#include "dalembert/primitives.h"

static int sphere(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  (void)t;
  double R = p[0];
  dal_jet st = dal_sin(in[0]);
  out[0] = dal_addc(dal_scale(dal_mul(st, dal_cos(in[1])), R), p[1]);
  out[1] = dal_addc(dal_scale(dal_mul(st, dal_sin(in[1])), R), p[2]);
  out[2] = dal_addc(dal_scale(dal_cos(in[0]), R), p[3]);
  return 0;
}

static const char *const sphere_names[] = {"R", "cx", "cy", "cz"};
static const double sphere_defaults[] = {NAN, 0.0, 0.0, 0.0};
const dal_primitive dal_map_sphere = {
    .name = "sphere",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 2,
    .nout = 3,
    .nparam = 4,
    .eval = sphere,
    .doc = "in (theta, phi); param (R, cx, cy, cz); out c + R (s cos ph, s sin ph, cos th)",
    .flags = 0,
    .param_names = sphere_names,
    .param_defaults = sphere_defaults,
};
