// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Fixed points: a particle held at a given position (no inputs).
#include "dalembert/primitives.h"

static int fixed(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, int d) {
  (void)in;
  (void)t;
  for (int i = 0; i < d; ++i) out[i] = dal_const(p[i]);
  return 0;
}

static int fixed2(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  return fixed(in, t, p, out, 2);
}

static int fixed3(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  return fixed(in, t, p, out, 3);
}

const dal_primitive dal_map_fixed2 = {"fixed2", 1, 0, 2, 2, fixed2, "param (x, y); out (x, y)", 0};
const dal_primitive dal_map_fixed3 = {"fixed3", 1, 0, 3, 3, fixed3,
                                      "param (x, y, z); out (x, y, z)", 0};
