// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Planar pendulums: about a (possibly oscillating) pivot, and hanging from another particle.
#include <math.h>

#include "dalembert/primitives.h"

// r = p(t) + l (sin th, -cos th), p(t) = (x0 + ax cos(w t + ph), y0 + ay cos(w t + ph))
static int pendulum(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  double l = p[0], x0 = p[1], y0 = p[2], ax = p[3], ay = p[4], w = p[5], ph = p[6];
  dal_jet drive = dal_cos(dal_addc(dal_scale(t, w), ph)), s, c;
  dal_sincos(in[0], &s, &c);
  out[0] = dal_add(dal_addc(dal_scale(drive, ax), x0), dal_scale(s, l));
  out[1] = dal_sub(dal_addc(dal_scale(drive, ay), y0), dal_scale(c, l));
  return 0;
}

// r = parent + l (sin th, -cos th)
static int hanging(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  (void)t;
  dal_jet s, c;
  dal_sincos(in[2], &s, &c);
  out[0] = dal_add(in[0], dal_scale(s, p[0]));
  out[1] = dal_sub(in[1], dal_scale(c, p[0]));
  return 0;
}

static const char *const pendulum_names[] = {"l", "x0", "y0", "ax", "ay", "w", "ph"};
static const double pendulum_defaults[] = {NAN, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
const dal_primitive dal_map_pendulum = {
    .name = "pendulum",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 1,
    .nout = 2,
    .nparam = 7,
    .eval = pendulum,
    .doc = "in (theta); param (l, x0, y0, ax, ay, w, ph); out p(t) + l (sin th, -cos th)",
    .flags = 0,
    .param_names = pendulum_names,
    .param_defaults = pendulum_defaults,
};
static const char *const hanging_names[] = {"l"};
static const double hanging_defaults[] = {NAN};
const dal_primitive dal_map_hanging = {
    .name = "hanging",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 3,
    .nout = 2,
    .nparam = 1,
    .eval = hanging,
    .doc = "in (x_parent, y_parent, theta); param (l); out parent + l (sin th, -cos th)",
    .flags = DAL_PRIM_TRANSLATES,
    .param_names = hanging_names,
    .param_defaults = hanging_defaults,
};
