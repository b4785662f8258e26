// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The method table: one constant row per integration method, and the automatic choice.
#include <stddef.h>
#include <stdio.h>

#include "integrate.h"
#include "symplectic.h"

// the formulation sets of the rows: the ODE problems; minimal coordinates only (BDF, whose
// index-1 form runs in IDA); the DAE-only forms AUTO hands to the DAE method
#define ODE_FORMS DAL__ODE_FORMS
#define ODE_ONLY DAL__FORM_BIT(DAL_FORM_ODE)
#define DAE_ONLY (DAL__FORM_BIT(DAL_FORM_GGL) | DAL__FORM_BIT(DAL_FORM_INDEX3))

// what callers ask of the rows: the adaptive explicit methods, the CVODE ones, the
// structure-preserving ones
#define EXPL (DAL__CAP_FIRST_ORDER | DAL__CAP_EXPLICIT)
#define IMPL DAL__CAP_FIRST_ORDER
#define SYMP DAL__CAP_SYMPLECTIC

static const dal_method_row rows[] = {
    {DAL_METHOD_AUTO, "auto", 1.0, NULL, ODE_FORMS, DAE_ONLY, 0, 0, 0, 0},
    // floors (issue 31: a tighter request is never worse): below them the error stops falling
    // (rounding) and grew again (tests/test_dense.c, test_tighter): DOPRI5, Fehlberg 7(8) and
    // Adams honour 1e-12, Bulirsch-Stoer 1e-13; a tighter request runs at the floor, with a note
    {DAL_METHOD_DOPRI5, "dopri5", 0.01, dal__erk_create, ODE_FORMS, 0, 1e-12, 2, EXPL, 1},
    {DAL_METHOD_FEHLBERG78, "fehlberg78", 0.01, dal__erk_create, ODE_FORMS, 0, 1e-12, 2, EXPL, 1},
    {DAL_METHOD_BS, "bs", 0.005, dal__bs_create, ODE_FORMS, 0, 1e-13, 0, EXPL, 4},
    {DAL_METHOD_RK4, "rk4", 1.0, dal__rk4_create, ODE_FORMS, 0, 0, 1, EXPL, 1},
    {DAL_METHOD_ADAMS, "adams", 0.001, dal__cvode_create, ODE_FORMS, 0, 1e-12, 0, IMPL, 1},
    // BDF: below rtol 1e-11 its local tolerance 1e-4 rtol would pass DAL_TOL_FLOOR; over
    // [0, 20] on the pendulum at 2.5 rad a request of 1e-12 gave 62 ... 190 x rtol, so it runs
    // as 1e-11: tests/test_dense.c
    {DAL_METHOD_BDF, "bdf", 0.0001, dal__cvode_create, ODE_ONLY, DAL__DAE_FORMS, 1e-11, 0, IMPL, 1},
    // fixed-step structure-preserving methods (symplectic.c): no error control
    {DAL_METHOD_VARIATIONAL, "variational", 1.0, dal__symplectic_create, 0, 0, 0, 1, SYMP, 1},
    {DAL_METHOD_VARIATIONAL4, "variational4", 1.0, dal__symplectic_create, 0, 0, 0, 1, SYMP, 1},
    {DAL_METHOD_VARIATIONAL6, "variational6", 1.0, dal__symplectic_create, 0, 0, 0, 1, SYMP, 1},
    {DAL_METHOD_RATTLE, "rattle", 1.0, dal__symplectic_create, 0, 0, 0, 1, SYMP, 1},
    {DAL_METHOD_RATTLE4, "rattle4", 1.0, dal__symplectic_create, 0, 0, 0, 1, SYMP, 1},
    {DAL_METHOD_RATTLE6, "rattle6", 1.0, dal__symplectic_create, 0, 0, 0, 1, SYMP, 1},
};

const dal_method_row *dal__method_row(dal_method m) {
  for (size_t i = 0; i < sizeof rows / sizeof rows[0]; ++i)
    if (rows[i].id == m) return &rows[i];
  return NULL;
}

int dal__method_fixed(dal_method m, const dal_solve_opts *o) {
  const dal_method_row *r = dal__method_row(m);
  return r && (r->fixed == 1 || (r->fixed == 2 && o->fixed_erk));
}

int dal__method_can(dal_method m, unsigned caps) {
  const dal_method_row *r = dal__method_row(m);
  return r && (r->caps & caps) == caps;
}

const char *dal__methods_that_can(unsigned caps, char *buf, size_t len) {
  size_t at = 0;
  buf[0] = 0;
  for (size_t i = 0; i < sizeof rows / sizeof rows[0]; ++i) {
    if (rows[i].id == DAL_METHOD_AUTO || (rows[i].caps & caps) != caps) continue;
    int k = snprintf(buf + at, len - at, "%s%s", at ? ", " : "", rows[i].name);
    if (k < 0 || (size_t)k >= len - at) {
      buf[at] = 0; // whole names only
      break;
    }
    at += (size_t)k;
  }
  return buf;
}

// AUTO on a first-order problem: the method of the first rtol range that holds the request
static const struct {
  double from; // the range holds rtol > from (strict) or rtol >= from
  int strict;
  dal_method method;
} fo_auto[] = {{1e-6, 1, DAL_METHOD_DOPRI5}, {1e-12, 0, DAL_METHOD_ADAMS}, {0.0, 0, DAL_METHOD_BS}};

dal_method dal__auto_method_fo(double rtol, unsigned caps) {
  dal_method looser = DAL_METHOD_AUTO; // the method with caps of the last looser range
  for (size_t i = 0; i < sizeof fo_auto / sizeof fo_auto[0]; ++i) {
    int holds = fo_auto[i].strict ? rtol > fo_auto[i].from : rtol >= fo_auto[i].from;
    int can = dal__method_can(fo_auto[i].method, caps);
    if (holds && can) return fo_auto[i].method;
    if (holds && looser != DAL_METHOD_AUTO) return looser;
    if (can) looser = fo_auto[i].method;
  }
  return looser;
}

int dal__fo_method(dal_state *st, dal_method m, double rtol, unsigned caps, const char *what,
                   dal_method *out) {
  caps |= DAL__CAP_FIRST_ORDER;
  *out = m == DAL_METHOD_AUTO ? dal__auto_method_fo(rtol, caps) : m;
  if (dal__method_can(*out, caps)) return DAL_OK;
  char can[128];
  return DAL_FAIL(
      st, DAL_E_UNSUPPORTED, "%s%smethod '%s' cannot run %s; use auto or one that can (%s)",
      what ? what : "", what ? ": " : "", dal_method_name(m),
      caps & DAL__CAP_EXPLICIT ? "this first-order problem, which asks for an explicit method (no "
                                 "iteration per step)"
                               : "a first-order problem y' = F(t, y)",
      dal__methods_that_can(caps, can, sizeof can));
}

dal_method dal__dae_method(dal_formulation form) {
  for (size_t i = 0; i < sizeof rows / sizeof rows[0]; ++i)
    if (rows[i].id != DAL_METHOD_AUTO && (rows[i].dae_forms & DAL__FORM_BIT(form)))
      return rows[i].id;
  return DAL_METHOD_AUTO;
}

double dal__tol_factor(dal_method m) {
  const dal_method_row *r = dal__method_row(m);
  return r ? r->tol_factor : 1.0;
}

const char *dal_method_name(dal_method m) {
  const dal_method_row *r = dal__method_row(m);
  return r ? r->name : "unknown";
}

/// The automatic method for an ODE formulation, by relative tolerance and number of
/// coordinates (documented in solve.h; derived from bench/auto.sh's and bench/dense_auto.sh's
/// work-precision tables among the methods whose error estimate holds on the differential set
/// of tests/test_auto_set.c): rtol >= 1e-3: DOPRI5; below, n <= 2: Bulirsch-Stoer; otherwise
/// DOPRI5 down to DAL_AUTO_MID_RTOL and Bulirsch-Stoer below, dense output or not (Fehlberg
/// 7(8)'s estimate misses that set: issue 31).
dal_method dal__auto_method(double rtol, int n, int dense) {
  (void)dense; // one rule since issue 31 (it was Fehlberg 7(8) at 1e-5 ... 1e-8 without)
  if (rtol >= DAL_AUTO_LOOSE_RTOL) return DAL_METHOD_DOPRI5;
  if (n <= DAL_AUTO_SMALL_N) return DAL_METHOD_BS;
  return rtol >= DAL_AUTO_MID_RTOL ? DAL_METHOD_DOPRI5 : DAL_METHOD_BS;
}
