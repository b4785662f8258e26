// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A particle on a sphere of radius R centred at a fixed point (constraint form).
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

const dal_primitive dal_con_sphere = {
    "on_sphere", 1, 3, 1, 4, on_sphere, "in (x, y, z); param (R, cx, cy, cz); out |r - c| - R", 0};
