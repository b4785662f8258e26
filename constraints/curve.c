// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Point on a user parametric curve p(s, t); the instance's ctx is a dal_curve.
#include <math.h>

#include "dalembert/primitives.h"

static int curve(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)p;
  const dal_curve *c = ctx;
  if (!c || !c->fn) return -1;
  return c->fn(in[0], t, out, c->ctx);
}

const dal_primitive dal_map_curve2 = {
    .name = "curve2",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 1,
    .nout = 2,
    .nparam = 0,
    .eval = curve,
    .doc = "in (s); ctx dal_curve; out p(s, t) (2D)",
    .flags = 0,
};
const dal_primitive dal_map_curve3 = {
    .name = "curve3",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 1,
    .nout = 3,
    .nparam = 0,
    .eval = curve,
    .doc = "in (s); ctx dal_curve; out p(s, t) (3D)",
    .flags = 0,
};
