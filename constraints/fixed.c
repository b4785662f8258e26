// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Fixed points: a particle held at a given position (no inputs).
#include <math.h>

#include "dalembert/primitives.h"

static int fixed(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, int d) {
  (void)in;
  (void)t;
  for (int i = 0; i < d; ++i)
    out[i] = dal_const(p[i]);
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

static const char *const fixed2_names[] = {"x", "y"};
static const double fixed2_defaults[] = {0.0, 0.0};
const dal_primitive dal_map_fixed2 = {
    .name = "fixed2",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 0,
    .nout = 2,
    .nparam = 2,
    .eval = fixed2,
    .doc = "param (x, y); out (x, y)",
    .flags = 0,
    .param_names = fixed2_names,
    .param_defaults = fixed2_defaults,
};
static const char *const fixed3_names[] = {"x", "y", "z"};
static const double fixed3_defaults[] = {0.0, 0.0, 0.0};
const dal_primitive dal_map_fixed3 = {
    .name = "fixed3",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 0,
    .nout = 3,
    .nparam = 3,
    .eval = fixed3,
    .doc = "param (x, y, z); out (x, y, z)",
    .flags = 0,
    .param_names = fixed3_names,
    .param_defaults = fixed3_defaults,
};
