// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A first-order problem y' = F(t, y) of any size run by the library's ODE methods (behind the
// integrator handle: dal__integ_create_fo): the tangent and variational integrations of the
// analysis layer use the same integrators, step control, progress guards and failure naming as
// dal_advance.
#include <string.h>

#include "integrate.h"

// (the size is the problem's ny, set per run by dal__ode_create_fo)
static int fo_size(const dal_system *sys) { return 2 * sys->n; }

// the state follows the trajectory part of y (messages, the last accepted step on failure)
static void fo_to_state(const dal_system *sys, dal_state *st, double t, const double *y) {
  size_t n = (size_t)sys->n;
  st->t = t;
  memcpy(st->q, y, n * sizeof(double));
  memcpy(st->qdot, y + n, n * sizeof(double));
  dal__state_moved(st);
}

static void fo_from_state(const dal_system *sys, const dal_state *st, double *y) {
  (void)sys;
  memcpy(y, st->fo->y0, (size_t)st->fo->ny * sizeof(double));
}

static int fo_rhs(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t,
                  const double *y, double *ydot, unsigned need) {
  (void)sys;
  (void)opts;
  (void)need; // F evaluates the state at the trajectory point fully
  return st->fo->rhs(st->fo->ctx, st, t, y, ydot);
}

static int fo_project(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t,
                      double *y) {
  (void)sys;
  (void)opts;
  return st->fo->project ? st->fo->project(st->fo->ctx, st, t, y) : DAL_OK;
}

const dal_ode_problem dal__problem_first_order = {
    .name = "first-order",
    .size = fo_size,
    .rhs = fo_rhs,
    .project = fo_project,
    .from_state = fo_from_state,
    .to_state = fo_to_state,
    .tol_factor = 1.0,
};

int dal__ode_create_fo(const dal_system *sys, dal_state *st, const dal_solve_opts *opts,
                       dal_method meth, dal_first_order *fo, dal_ode_integ **out) {
  *out = NULL;
  if (fo->ny < 2 * sys->n)
    return DAL_FAIL(st, DAL_E_ARG, "first-order problem of size %d below 2n = %d", fo->ny,
                    2 * sys->n);
  dal_solve_opts o = *opts;
  o.form = DAL_FORM_ODE;
  o.work = 0;
  o.project = fo->project != NULL;
  st->fo = fo;
  fo->prob = dal__problem_first_order;
  fo->prob.ny = fo->ny;
  if (fo->tol_factor > 0) fo->prob.tol_factor = fo->tol_factor;
  return dal__ode_create(sys, st, &o, meth, &fo->prob, out);
}
