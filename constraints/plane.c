// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A particle on a fixed plane through c with normal n (signed distance, length units).
#include <math.h>

#include "dalembert/primitives.h"

static int on_plane(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  double nn = sqrt(p[3] * p[3] + p[4] * p[4] + p[5] * p[5]);
  dal_jet h = dal_const(0.0);
  for (int i = 0; i < 3; ++i)
    h = dal_add(h, dal_scale(dal_addc(in[i], -p[i]), p[3 + i] / nn));
  out[0] = h;
  return 0;
}

static const char *const plane_names[] = {"cx", "cy", "cz", "nx", "ny", "nz"};
static const double plane_defaults[] = {0.0, 0.0, 0.0, 0.0, 0.0, 1.0};
const dal_primitive dal_con_plane = {
    .name = "on_plane",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 3,
    .nout = 1,
    .nparam = 6,
    .eval = on_plane,
    .doc = "in (x, y, z); param (cx, cy, cz, nx, ny, nz); "
           "out n.(r - c) / |n|",
    .flags = 0,
    .param_names = plane_names,
    .param_defaults = plane_defaults,
};
