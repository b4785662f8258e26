// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A particle on a circle: fixed in 2D or 3D, and a circle turning about the vertical axis.
#include <math.h>

#include "dalembert/primitives.h"

// |r - c| - R in the plane
static int circle2(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet e[2] = {dal_addc(in[0], -p[1]), dal_addc(in[1], -p[2])};
  out[0] = dal_addc(dal_norm(e, 2), -p[0]);
  return 0;
}

// rows: n.(r - c) (out of the circle's plane) and |in-plane part of r - c| - R
static int circle3(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  double nn = sqrt(p[4] * p[4] + p[5] * p[5] + p[6] * p[6]);
  double n[3] = {p[4] / nn, p[5] / nn, p[6] / nn};
  dal_jet e[3], h = dal_const(0.0);
  for (int i = 0; i < 3; ++i) {
    e[i] = dal_addc(in[i], -p[1 + i]);
    h = dal_add(h, dal_scale(e[i], n[i]));
  }
  for (int i = 0; i < 3; ++i)
    e[i] = dal_sub(e[i], dal_scale(h, n[i]));
  out[0] = h;
  out[1] = dal_addc(dal_norm(e, 3), -p[0]);
  return 0;
}

// the circle's plane contains the vertical through c and the direction (cos a, sin a, 0),
// a = w t + phi0; rows: n(t).(r - c) with n = (-sin a, cos a, 0), and |r - c| - R
static int turning_circle(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  dal_jet a = dal_addc(dal_scale(t, p[1]), p[2]);
  dal_jet e[3];
  for (int i = 0; i < 3; ++i)
    e[i] = dal_addc(in[i], -p[3 + i]);
  out[0] = dal_sub(dal_mul(e[1], dal_cos(a)), dal_mul(e[0], dal_sin(a)));
  out[1] = dal_addc(dal_norm(e, 3), -p[0]);
  return 0;
}

static const char *const circle2_names[] = {"R", "cx", "cy"};
static const double circle2_defaults[] = {NAN, 0.0, 0.0};
const dal_primitive dal_con_circle2 = {
    .name = "on_circle2",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 2,
    .nout = 1,
    .nparam = 3,
    .eval = circle2,
    .doc = "in (x, y); param (R, cx, cy); out |r - c| - R",
    .flags = 0,
    .param_names = circle2_names,
    .param_defaults = circle2_defaults,
};
static const char *const circle3_names[] = {"R", "cx", "cy", "cz", "nx", "ny", "nz"};
static const double circle3_defaults[] = {NAN, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0};
const dal_primitive dal_con_circle3 = {
    .name = "on_circle3",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 3,
    .nout = 2,
    .nparam = 7,
    .eval = circle3,
    .doc = "in (x, y, z); param (R, cx, cy, cz, nx, ny, nz); out (n.(r - c), |(r - c)_plane| - R)",
    .flags = 0,
    .param_names = circle3_names,
    .param_defaults = circle3_defaults,
};
static const char *const turning_circle_names[] = {"R", "w", "phi0", "cx", "cy", "cz"};
static const double turning_circle_defaults[] = {NAN, 0.0, 0.0, 0.0, 0.0, 0.0};
const dal_primitive dal_con_turning_circle = {
    .name = "turning_circle",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 3,
    .nout = 2,
    .nparam = 6,
    .eval = turning_circle,
    .doc = "in (x, y, z); param (R, w, phi0, cx, cy, cz); out (n(t).(r - c), |r - c| - R), "
           "n(t) = (-sin(w t + phi0), cos(w t + phi0), 0)",
    .flags = 0,
    .param_names = turning_circle_names,
    .param_defaults = turning_circle_defaults,
};
