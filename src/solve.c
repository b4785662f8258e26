// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Integration driver: options, method dispatch, advance and evolve.
#include <string.h>

#include "internal.h"

void dal_solve_default_opts(dal_solve_opts *o) {
  if (!o) return;
  memset(o, 0, sizeof *o);
  o->magic = DAL_OPTS_MAGIC;
  o->method = DAL_METHOD_AUTO;
  o->form = DAL_FORM_AUTO;
  o->linsol = DAL_LINSOL_AUTO;
  o->rtol = 1e-8;
  o->atol = 1e-10;
  o->fixed_step = 1e-3;
  o->max_steps = 1000000;
  o->sparse_threshold = 200;
}

void dal__integ_reset(dal_state *st) {
  if (st->integ && st->integ_free) st->integ_free(st->integ);
  st->integ = NULL;
  st->integ_free = NULL;
}
