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

const dal_primitive dal_con_circle2 = {
    "on_circle2", 1, 2, 1, 3, circle2, "in (x, y); param (R, cx, cy); out |r - c| - R", 0};
const dal_primitive dal_con_circle3 = {
    "on_circle3",
    1,
    3,
    2,
    7,
    circle3,
    "in (x, y, z); param (R, cx, cy, cz, nx, ny, nz); out (n.(r - c), |(r - c)_plane| - R)", 0};
const dal_primitive dal_con_turning_circle = {
    "turning_circle",
    1,
    3,
    2,
    6,
    turning_circle,
    "in (x, y, z); param (R, w, phi0, cx, cy, cz); out (n(t).(r - c), |r - c| - R), "
    "n(t) = (-sin(w t + phi0), cos(w t + phi0), 0)", 0};
