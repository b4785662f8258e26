// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Distance (rod) constraints: between two particles, and from a particle to a fixed or moving
// point.
#include <math.h>
#include <stddef.h>

#include "dalembert/primitives.h"

// |b - a| - L over d components, a and b given as jet arrays
static dal_jet rod(const dal_jet *a, const dal_jet *b, double L, int d) {
  dal_jet e[3];
  for (int i = 0; i < d; ++i)
    e[i] = dal_sub(b[i], a[i]);
  return dal_addc(dal_norm(e, d), -L);
}

static int distance2(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  out[0] = rod(in, in + 2, p[0], 2);
  return 0;
}

static int distance3(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  out[0] = rod(in, in + 3, p[0], 3);
  return 0;
}

// the anchor x0 + x(t) (x = 0 without a moving-point context) as jets
static int anchor_point(dal_jet t, const double *x0, void *ctx, dal_jet *x, int d) {
  const dal_moving_point *mp = ctx;
  for (int i = 0; i < d; ++i)
    x[i] = dal_const(0.0);
  if (mp && mp->fn) {
    int rc = mp->fn(t, x, mp->ctx);
    if (rc) return rc;
  }
  for (int i = 0; i < d; ++i)
    x[i] = dal_addc(x[i], x0[i]);
  return 0;
}

static int anchor(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx, int d) {
  dal_jet x[3];
  int rc = anchor_point(t, p + 1, ctx, x, d);
  if (rc) return rc;
  out[0] = rod(x, in, p[0], d);
  return 0;
}

static int anchor2(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  return anchor(in, t, p, out, ctx, 2);
}

static int anchor3(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  return anchor(in, t, p, out, ctx, 3);
}

static const char *const distance2_names[] = {"L"};
static const double distance2_defaults[] = {NAN};
const dal_primitive dal_con_distance2 = {
    .name = "distance2",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 4,
    .nout = 1,
    .nparam = 1,
    .eval = distance2,
    .doc = "in (xa, ya, xb, yb); param (L); out |b - a| - L",
    .flags = 0,
    .param_names = distance2_names,
    .param_defaults = distance2_defaults,
};
static const char *const distance3_names[] = {"L"};
static const double distance3_defaults[] = {NAN};
const dal_primitive dal_con_distance3 = {
    .name = "distance3",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 6,
    .nout = 1,
    .nparam = 1,
    .eval = distance3,
    .doc = "in (xa, ya, za, xb, yb, zb); param (L); out |b - a| - L",
    .flags = 0,
    .param_names = distance3_names,
    .param_defaults = distance3_defaults,
};
static const char *const anchor2_names[] = {"L", "x0", "y0"};
static const double anchor2_defaults[] = {NAN, 0.0, 0.0};
const dal_primitive dal_con_anchor2 = {
    .name = "anchor2",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 2,
    .nout = 1,
    .nparam = 3,
    .eval = anchor2,
    .doc = "in (x, y); param (L, x0, y0); ctx NULL or dal_moving_point; out |r - (x0 + x(t))| - L",
    .flags = 0,
    .param_names = anchor2_names,
    .param_defaults = anchor2_defaults,
};
static const char *const anchor3_names[] = {"L", "x0", "y0", "z0"};
static const double anchor3_defaults[] = {NAN, 0.0, 0.0, 0.0};
const dal_primitive dal_con_anchor3 = {
    .name = "anchor3",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 3,
    .nout = 1,
    .nparam = 4,
    .eval = anchor3,
    .doc = "in (x, y, z); param (L, x0, y0, z0); ctx NULL or dal_moving_point; "
           "out |r - (x0 + x(t))| - L",
    .flags = 0,
    .param_names = anchor3_names,
    .param_defaults = anchor3_defaults,
};
