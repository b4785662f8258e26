// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A user's verification program, registered by dalembert_add_verify_test: a primitive of
// one's own (a point on an ellipse turning at rate w) must agree with finite differences.
#include <dalembert/dalembert.h>
#include <stdio.h>

static int ellipse(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)ctx;
  dal_jet a = dal_add(in[0], dal_scale(t, p[2]));
  out[0] = dal_scale(dal_cos(a), p[0]);
  out[1] = dal_scale(dal_sin(a), p[1]);
  return 0;
}

static const char *const names[] = {"a", "b", "w"};
static const double defaults[] = {1.0, 0.5, 0.0};
static const dal_primitive my_ellipse = {.name = "my_ellipse",
                                         .version = DAL_PRIMITIVE_VERSION,
                                         .nin = 1,
                                         .nout = 2,
                                         .nparam = 3,
                                         .eval = ellipse,
                                         .doc = "in (s); param (a, b, w)",
                                         .param_names = names,
                                         .param_defaults = defaults};

int main(void) {
  double p[3] = {2.0, 0.7, 1.3};
  dal_verify_report rep;
  int rc = dal_verify_primitive(&my_ellipse, p, NULL, NULL, &rep);
  printf("%s\n", rep.msg);
  return rc == DAL_OK ? 0 : 1;
}
