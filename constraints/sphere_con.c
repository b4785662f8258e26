// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A particle on a sphere of radius R centred at a fixed point (constraint form).
#include <math.h>

#include "dalembert/primitives.h"

static int on_sphere(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet e[3];
  for (int i = 0; i < 3; ++i)
    e[i] = dal_addc(in[i], -p[1 + i]);
  out[0] = dal_addc(dal_norm(e, 3), -p[0]);
  return 0;
}

static const char *const sphere_names[] = {"R", "cx", "cy", "cz"};
static const double sphere_defaults[] = {NAN, 0.0, 0.0, 0.0};
const dal_primitive dal_con_sphere = {
    .name = "on_sphere",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 3,
    .nout = 1,
    .nparam = 4,
    .eval = on_sphere,
    .doc = "in (x, y, z); param (R, cx, cy, cz); out |r - c| - R",
    .flags = 0,
    .param_names = sphere_names,
    .param_defaults = sphere_defaults,
};
