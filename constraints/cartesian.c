// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Identity maps r = (x, y[, z]): Cartesian (redundant) coordinates.
#include "dalembert/primitives.h"

static int cartesian(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, int d) {
  (void)t;
  (void)p;
  for (int i = 0; i < d; ++i) out[i] = in[i];
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

const dal_primitive dal_map_cartesian2 = {"cartesian2", 1, 2, 2, 0, cartesian2,
                                          "in (x, y); out (x, y)", 0};
const dal_primitive dal_map_cartesian3 = {"cartesian3", 1, 3, 3, 0, cartesian3,
                                          "in (x, y, z); out (x, y, z)", 0};
