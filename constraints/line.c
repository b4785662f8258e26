// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A particle on a straight line: fixed in 2D or 3D, and a 2D line turning about a point.
#include <math.h>

#include "dalembert/primitives.h"

// 2D: distance from the line through c with direction a, positive to the left of a
static int line2(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  double na = hypot(p[2], p[3]);
  dal_jet ex = dal_addc(in[0], -p[0]), ey = dal_addc(in[1], -p[1]);
  out[0] = dal_add(dal_scale(ey, p[2] / na), dal_scale(ex, -p[3] / na));
  return 0;
}

// 3D: the two components of r - c along an orthonormal pair (e1, e2) normal to a
static int line3(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  double na = sqrt(p[3] * p[3] + p[4] * p[4] + p[5] * p[5]);
  double a[3] = {p[3] / na, p[4] / na, p[5] / na};
  // e1: a crossed with the coordinate axis least aligned with a; e2 = a x e1
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (fabs(a[i]) < fabs(a[k])) k = i;
  double u[3] = {0.0, 0.0, 0.0};
  u[k] = 1.0;
  double e1[3] = {a[1] * u[2] - a[2] * u[1], a[2] * u[0] - a[0] * u[2], a[0] * u[1] - a[1] * u[0]};
  double n1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  for (int i = 0; i < 3; ++i)
    e1[i] /= n1;
  double e2[3] = {a[1] * e1[2] - a[2] * e1[1], a[2] * e1[0] - a[0] * e1[2],
                  a[0] * e1[1] - a[1] * e1[0]};
  dal_jet h1 = dal_const(0.0), h2 = dal_const(0.0);
  for (int i = 0; i < 3; ++i) {
    dal_jet e = dal_addc(in[i], -p[i]);
    h1 = dal_add(h1, dal_scale(e, e1[i]));
    h2 = dal_add(h2, dal_scale(e, e2[i]));
  }
  out[0] = h1;
  out[1] = h2;
  return 0;
}

// 2D line through c at angle a(t) = w t + phi0 from the x axis:
// -(x - cx) sin a + (y - cy) cos a
static int turning_line2(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  dal_jet a = dal_addc(dal_scale(t, p[2]), p[3]);
  dal_jet ex = dal_addc(in[0], -p[0]), ey = dal_addc(in[1], -p[1]);
  out[0] = dal_sub(dal_mul(ey, dal_cos(a)), dal_mul(ex, dal_sin(a)));
  return 0;
}

static const char *const line2_names[] = {"cx", "cy", "ax", "ay"};
static const double line2_defaults[] = {0.0, 0.0, 1.0, 0.0};
const dal_primitive dal_con_line2 = {
    .name = "on_line2",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 2,
    .nout = 1,
    .nparam = 4,
    .eval = line2,
    .doc = "in (x, y); param (cx, cy, ax, ay); out signed distance from the line c + s a",
    .flags = 0,
    .param_names = line2_names,
    .param_defaults = line2_defaults,
};
static const char *const line3_names[] = {"cx", "cy", "cz", "ax", "ay", "az"};
static const double line3_defaults[] = {0.0, 0.0, 0.0, 1.0, 0.0, 0.0};
const dal_primitive dal_con_line3 = {
    .name = "on_line3",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 3,
    .nout = 2,
    .nparam = 6,
    .eval = line3,
    .doc = "in (x, y, z); param (cx, cy, cz, ax, ay, az); out (e1.(r - c), e2.(r - c)), e1, e2 "
           "orthonormal and normal to a",
    .flags = 0,
    .param_names = line3_names,
    .param_defaults = line3_defaults,
};
static const char *const turning_line2_names[] = {"cx", "cy", "w", "phi0"};
static const double turning_line2_defaults[] = {0.0, 0.0, 0.0, 0.0};
const dal_primitive dal_con_turning_line2 = {
    .name = "turning_line2",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 2,
    .nout = 1,
    .nparam = 4,
    .eval = turning_line2,
    .doc = "in (x, y); param (cx, cy, w, phi0); out -(x - cx) sin a + (y - cy) cos a, "
           "a = w t + phi0",
    .flags = 0,
    .param_names = turning_line2_names,
    .param_defaults = turning_line2_defaults,
};
