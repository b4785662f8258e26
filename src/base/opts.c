// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Integration options: defaults, validation, comparison, names; statistics.
#include <math.h>
#include <string.h>

#include "base.h"

dal_solve_opts dal_default_solve_opts(void) {
  dal_solve_opts d, *o = &d;
  memset(o, 0, sizeof *o);
  o->cookie = DAL_OPTS_COOKIE;
  o->method = DAL_METHOD_AUTO;
  o->form = DAL_FORM_AUTO;
  o->linsol = DAL_LINSOL_AUTO;
  o->rtol = 1e-8;
  o->atol = 0.0; // follows rtol: DAL_ATOL_PER_RTOL * rtol
  o->init_max_move = 0.0;
  o->fixed_step = 1e-3;
  o->max_steps = 1000000;
  o->sparse_threshold = DAL_SPARSE_THRESHOLD;
  o->fixed_erk = 0;
  return d;
}

const char *dal_formulation_name(dal_formulation f) {
  switch (f) {
  case DAL_FORM_AUTO:
    return "auto";
  case DAL_FORM_ODE:
    return "ode";
  case DAL_FORM_GGL:
    return "ggl";
  case DAL_FORM_INDEX1:
    return "index1";
  case DAL_FORM_INDEX3:
    return "index3";
  }
  return "unknown";
}

int dal_state_stats(const dal_state *st, dal_stats *out) {
  if (!st) return DAL_E_ARG;
  if (!out) return DAL_FAIL_C(st, DAL_E_ARG, "state_stats: out is NULL");
  *out = st->stats;
  return DAL_OK;
}

// validate options; a message names the field and the remedy
int dal__check_opts(dal_state *st, const dal_solve_opts *o) {
  if (!o) return DAL_FAIL(st, DAL_E_ARG, "solve options are NULL; pass dal_default_solve_opts()");
  if (o->cookie != DAL_OPTS_COOKIE)
    return DAL_FAIL(st, DAL_E_ARG,
                    "solve options were not initialized: call dal_default_solve_opts() "
                    "before setting fields");
  if ((int)o->method < DAL_METHOD_AUTO || (int)o->method > DAL_METHOD_RATTLE6)
    return DAL_FAIL(st, DAL_E_ARG, "opts.method = %d is not a dal_method", (int)o->method);
  if ((int)o->form < DAL_FORM_AUTO || (int)o->form > DAL_FORM_INDEX3)
    return DAL_FAIL(st, DAL_E_ARG, "opts.form = %d is not a dal_formulation", (int)o->form);
  if ((int)o->linsol < DAL_LINSOL_AUTO || (int)o->linsol > DAL_LINSOL_KLU)
    return DAL_FAIL(st, DAL_E_ARG, "opts.linsol = %d is not a dal_linsol", (int)o->linsol);
  // NaN or inf in any real option is a non-finite input, as everywhere in the library
  const double *reals[8] = {&o->rtol, &o->atol, &o->fixed_step,      &o->h0,
                            &o->hmin, &o->hmax, &o->baumgarte_alpha, &o->baumgarte_beta};
  const char *rnames[8] = {"rtol", "atol", "fixed_step",      "h0",
                           "hmin", "hmax", "baumgarte_alpha", "baumgarte_beta"};
  for (int i = 0; i < 8; ++i)
    if (!isfinite(*reals[i]))
      return DAL_FAIL(st, DAL_E_NONFINITE, "opts.%s = %g is not finite; give a finite value",
                      rnames[i], *reals[i]);
  if (!(o->rtol > 0) || !isfinite(o->rtol))
    return DAL_FAIL(st, DAL_E_ARG, "opts.rtol = %g must be positive and finite (e.g. 1e-8)",
                    o->rtol);
  if (o->rtol >= 1.0)
    return DAL_FAIL(st, DAL_E_ARG,
                    "opts.rtol = %g asks for no accuracy (a relative error of 100%% or more); use "
                    "a value below 1, e.g. 1e-6",
                    o->rtol);
  if (o->rtol < 1e-15)
    return DAL_FAIL(st, DAL_E_ARG,
                    "opts.rtol = %g is below what double precision can deliver; use >= 1e-15",
                    o->rtol);
  if (!(o->atol >= 0) || !isfinite(o->atol))
    return DAL_FAIL(st, DAL_E_ARG,
                    "opts.atol = %g must be positive and finite (e.g. 1e-10), or 0 to follow "
                    "rtol",
                    o->atol);
  if (!(o->init_max_move >= 0) || !isfinite(o->init_max_move))
    return DAL_FAIL(st, DAL_E_ARG, "opts.init_max_move = %g must be >= 0 and finite (0: no limit)",
                    o->init_max_move);
  // the integrators weight errors by 1 / (atol + rtol |y|): it must stay finite
  if (o->atol > 0 && o->atol < 1e-300)
    return DAL_FAIL(st, DAL_E_ARG,
                    "opts.atol = %g is too small for double precision (its error weights "
                    "overflow); use >= 1e-300, e.g. 1e-10",
                    o->atol);
  if (!(o->fixed_step > 0) || !isfinite(o->fixed_step))
    return DAL_FAIL(st, DAL_E_ARG, "opts.fixed_step = %g must be positive and finite",
                    o->fixed_step);
  const double *hs[3] = {&o->h0, &o->hmin, &o->hmax};
  const char *hn[3] = {"h0", "hmin", "hmax"};
  for (int i = 0; i < 3; ++i)
    if (!(*hs[i] >= 0) || !isfinite(*hs[i]))
      return DAL_FAIL(st, DAL_E_ARG, "opts.%s = %g must be >= 0 and finite (0: automatic)", hn[i],
                      *hs[i]);
  if (o->hmax > 0 && o->hmin > o->hmax)
    return DAL_FAIL(st, DAL_E_ARG, "opts.hmin = %g exceeds opts.hmax = %g", o->hmin, o->hmax);
  if (o->max_steps <= 0)
    return DAL_FAIL(st, DAL_E_ARG, "opts.max_steps = %ld must be positive", o->max_steps);
  if (o->baumgarte_alpha < 0 || o->baumgarte_beta < 0)
    return DAL_FAIL(st, DAL_E_ARG,
                    "opts.baumgarte_alpha = %g and opts.baumgarte_beta = %g must be >= 0 (0: off)",
                    o->baumgarte_alpha, o->baumgarte_beta);
  // the terms 2 alpha phidot and beta^2 phi must be representable for residuals of order 1
  if (!isfinite(2.0 * o->baumgarte_alpha) || !isfinite(o->baumgarte_beta * o->baumgarte_beta))
    return DAL_FAIL(st, DAL_E_ARG,
                    "opts.baumgarte_%s = %g overflows its term (%s); use rates near the motion's "
                    "own frequencies (1/s)",
                    isfinite(2.0 * o->baumgarte_alpha) ? "beta" : "alpha",
                    isfinite(2.0 * o->baumgarte_alpha) ? o->baumgarte_beta : o->baumgarte_alpha,
                    isfinite(2.0 * o->baumgarte_alpha) ? "beta^2 phi" : "2 alpha phidot");
  return DAL_OK;
}

// every option field: the integrator is reused only while all of them are unchanged
// clang-format off
#define DAL_OPTS_FIELDS(X)                                                                         \
  X(cookie) X(method) X(form) X(linsol) X(rtol) X(atol) X(h0) X(hmin) X(hmax) X(fixed_step)      \
  X(max_steps) X(baumgarte_alpha) X(baumgarte_beta) X(project) X(sparse_threshold) X(fixed_erk)   \
  X(work) X(init_max_move) X(no_fallback)
// clang-format on
#define DAL_OPTS_SIZE(f) +sizeof(((dal_solve_opts *)0)->f)
// a new field changes the size: add it to DAL_OPTS_FIELDS, then update this check
// (4 bytes of padding follow no_fallback). The cancel hook and its context are read by each
// run from its own options, so a changed hook keeps the integrator: they are not listed
_Static_assert(0 DAL_OPTS_FIELDS(DAL_OPTS_SIZE) + 4 + sizeof(dal_cancel_fn *) + sizeof(void *) ==
                       136 &&
                   sizeof(dal_solve_opts) == 136,
               "dal_solve_opts changed: list every field in DAL_OPTS_FIELDS");

dal_solve_opts dal__effective_opts(const dal_solve_opts *o) {
  dal_solve_opts e = *o;
  if (e.atol == 0.0) e.atol = DAL_ATOL_PER_RTOL * e.rtol;
  return e;
}

int dal__same_opts(const dal_solve_opts *a, const dal_solve_opts *b) {
#define DAL_OPTS_EQ(f) &&a->f == b->f
  return 1 DAL_OPTS_FIELDS(DAL_OPTS_EQ);
#undef DAL_OPTS_EQ
}
