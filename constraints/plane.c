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

const dal_primitive dal_con_plane = {"on_plane",
                                     1,
                                     3,
                                     1,
                                     6,
                                     on_plane,
                                     "in (x, y, z); param (cx, cy, cz, nx, ny, nz); "
                                     "out n.(r - c) / |n|", 0};
