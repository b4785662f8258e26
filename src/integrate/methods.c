// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The method table: one constant row per integration method, and the automatic choice.
#include <stddef.h>

#include "integrate.h"
#include "symplectic.h"

// the formulation sets of the rows: the ODE problems; minimal coordinates only (BDF, whose
// index-1 form runs in IDA); the DAE-only forms AUTO hands to the DAE method
#define ODE_FORMS DAL__ODE_FORMS
#define ODE_ONLY DAL__FORM_BIT(DAL_FORM_ODE)
#define DAE_ONLY (DAL__FORM_BIT(DAL_FORM_GGL) | DAL__FORM_BIT(DAL_FORM_INDEX3))

static const dal_method_row rows[] = {
    {DAL_METHOD_AUTO, "auto", 1.0, NULL, ODE_FORMS, DAE_ONLY, 0, 0},
    // floors (issue 31: a tighter request is never worse): below them the error stops falling
    // (rounding) and grew again (tests/test_dense.c, test_tighter): DOPRI5, Fehlberg 7(8) and
    // Adams honour 1e-12, Bulirsch-Stoer 1e-13; a tighter request runs at the floor, with a note
    {DAL_METHOD_DOPRI5, "dopri5", 0.01, dal__erk_create, ODE_FORMS, 0, 1e-12, 2},
    {DAL_METHOD_FEHLBERG78, "fehlberg78", 0.01, dal__erk_create, ODE_FORMS, 0, 1e-12, 2},
    {DAL_METHOD_BS, "bs", 0.005, dal__bs_create, ODE_FORMS, 0, 1e-13, 0},
    {DAL_METHOD_RK4, "rk4", 1.0, dal__rk4_create, ODE_FORMS, 0, 0, 1},
    {DAL_METHOD_ADAMS, "adams", 0.001, dal__cvode_create, ODE_FORMS, 0, 1e-12, 0},
    // BDF: below rtol 1e-11 its local tolerance 1e-4 rtol would pass DAL_TOL_FLOOR; over
    // [0, 20] on the pendulum at 2.5 rad a request of 1e-12 gave 62 ... 190 x rtol, so it runs
    // as 1e-11: tests/test_dense.c
    {DAL_METHOD_BDF, "bdf", 0.0001, dal__cvode_create, ODE_ONLY, DAL__DAE_FORMS, 1e-11, 0},
    // fixed-step structure-preserving methods (symplectic.c): no error control
    {DAL_METHOD_VARIATIONAL, "variational", 1.0, dal__symplectic_create, 0, 0, 0, 1},
    {DAL_METHOD_VARIATIONAL4, "variational4", 1.0, dal__symplectic_create, 0, 0, 0, 1},
    {DAL_METHOD_VARIATIONAL6, "variational6", 1.0, dal__symplectic_create, 0, 0, 0, 1},
    {DAL_METHOD_RATTLE, "rattle", 1.0, dal__symplectic_create, 0, 0, 0, 1},
    {DAL_METHOD_RATTLE4, "rattle4", 1.0, dal__symplectic_create, 0, 0, 0, 1},
    {DAL_METHOD_RATTLE6, "rattle6", 1.0, dal__symplectic_create, 0, 0, 0, 1},
};

const dal_method_row *dal__method_row(dal_method m) {
  for (size_t i = 0; i < sizeof rows / sizeof rows[0]; ++i)
    if (rows[i].id == m) return &rows[i];
  return NULL;
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
