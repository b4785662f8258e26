// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Identity maps r = (x, y[, z]): Cartesian (redundant) coordinates.
#include <math.h>

#include "dalembert/primitives.h"

static int cartesian(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, int d) {
  (void)t;
  (void)p;
  for (int i = 0; i < d; ++i)
    out[i] = in[i];
  return 0;
}

static int cartesian2(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  return cartesian(in, t, p, out, 2);
}

static int cartesian3(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  return cartesian(in, t, p, out, 3);
}

const dal_primitive dal_map_cartesian2 = {
    .name = "cartesian2",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 2,
    .nout = 2,
    .nparam = 0,
    .eval = cartesian2,
    .doc = "in (x, y); out (x, y)",
    .flags = 0,
};
const dal_primitive dal_map_cartesian3 = {
    .name = "cartesian3",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 3,
    .nout = 3,
    .nparam = 0,
    .eval = cartesian3,
    .doc = "in (x, y, z); out (x, y, z)",
    .flags = 0,
};
