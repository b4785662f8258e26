// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A prescribed coordinate q_i = q0 + f(t), f a user jet function of time (rheonomic driving).
#include <math.h>
#include <stddef.h>

#include "dalembert/primitives.h"

static int prescribed(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  const dal_prescribed *pr = ctx;
  dal_jet f = dal_const(0.0);
  if (pr && pr->fn) {
    int rc = pr->fn(t, &f, pr->ctx);
    if (rc) return rc;
  }
  out[0] = dal_sub(in[0], dal_addc(f, p[0]));
  return 0;
}

static const char *const prescribed_names[] = {"q0"};
static const double prescribed_defaults[] = {0.0};
const dal_primitive dal_con_prescribed = {
    .name = "prescribed",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 1,
    .nout = 1,
    .nparam = 1,
    .eval = prescribed,
    .doc = "in (q); param (q0); ctx NULL or dal_prescribed; out q - (q0 + f(t))",
    .flags = 0,
    .param_names = prescribed_names,
    .param_defaults = prescribed_defaults,
};
