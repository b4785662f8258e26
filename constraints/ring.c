// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Bead on a ring turning about the vertical axis at rate w (Likharev 2.1, Fig. 2.1).
#include <math.h>

#include "dalembert/primitives.h"

// r = (R sin th cos(w t + phi0), R sin th sin(w t + phi0), -R cos th)
static int ring(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  double R = p[0], w = p[1], phi0 = p[2];
  dal_jet ph = dal_addc(dal_scale(t, w), phi0);
  dal_jet s = dal_scale(dal_sin(in[0]), R);
  out[0] = dal_mul(s, dal_cos(ph));
  out[1] = dal_mul(s, dal_sin(ph));
  out[2] = dal_scale(dal_cos(in[0]), -R);
  return 0;
}

static const char *const ring_names[] = {"R", "w", "phi0"};
static const double ring_defaults[] = {NAN, 0.0, 0.0};
const dal_primitive dal_map_ring = {
    .name = "ring",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 1,
    .nout = 3,
    .nparam = 3,
    .eval = ring,
    .doc = "in (theta); param (R, w, phi0); out (R s cos(wt+phi0), R s sin(wt+phi0), -R cos th)",
    .flags = 0,
    .param_names = ring_names,
    .param_defaults = ring_defaults,
};
