// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Integration driver: options, method dispatch, advance and evolve, the minimal-coordinate ODE.
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "solve_internal.h"

void dal_solve_default_opts(dal_solve_opts *o) {
  if (!o) return;
  memset(o, 0, sizeof *o);
  o->magic = DAL_OPTS_MAGIC;
  o->method = DAL_METHOD_AUTO;
  o->form = DAL_FORM_AUTO;
  o->linsol = DAL_LINSOL_AUTO;
  o->rtol = 1e-8;
  o->atol = 0.0; // follows rtol: DAL_ATOL_PER_RTOL * rtol
  o->init_max_move = 0.0;
  o->fixed_step = 1e-3;
  o->max_steps = 1000000;
  o->sparse_threshold = 200;
  o->fixed_erk = 0;
}

const char *dal_method_name(dal_method m) {
  switch (m) {
  case DAL_METHOD_AUTO:
    return "auto";
  case DAL_METHOD_DOPRI5:
    return "dopri5";
  case DAL_METHOD_FEHLBERG78:
    return "fehlberg78";
  case DAL_METHOD_BS:
    return "bs";
  case DAL_METHOD_RK4:
    return "rk4";
  case DAL_METHOD_ADAMS:
    return "adams";
  case DAL_METHOD_BDF:
    return "bdf";
  }
  return "unknown";
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
  if (!st || !out) return DAL_E_ARG;
  *out = st->stats;
  return DAL_OK;
}

// ---------------------------------------------------------------------------------------------
// minimal coordinates: y = (q, qdot), f = (qdot, qddot)

static int minimal_size(const dal_system *sys) { return 2 * sys->n; }

static void minimal_to_state(const dal_system *sys, dal_state *st, double t, const double *y) {
  size_t n = (size_t)sys->n;
  st->t = t;
  memcpy(st->q, y, n * sizeof(double));
  memcpy(st->qdot, y + n, n * sizeof(double));
  st->evaluated = 0;
}

static void minimal_from_state(const dal_system *sys, const dal_state *st, double *y) {
  size_t n = (size_t)sys->n;
  memcpy(y, st->q, n * sizeof(double));
  memcpy(y + n, st->qdot, n * sizeof(double));
}

static int minimal_rhs(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t,
                       const double *y, double *ydot) {
  (void)opts;
  int n = sys->n;
  minimal_to_state(sys, st, t, y);
  int rc = dal__forward(sys, st);
  if (rc) return rc;
  for (int i = 0; i < n; ++i) {
    // a non-finite acceleration at a trial point usually means the step was too long
    if (!isfinite(st->qddot[i])) {
      DAL_FAIL(st, DAL__RECOVERABLE,
               "acceleration of coordinate '%s' is %g at t=%.17g; the state may have left the "
               "model's domain",
               sys->coord_names[i], st->qddot[i], t);
      return DAL__RECOVERABLE;
    }
    ydot[i] = y[n + i];
    ydot[n + i] = st->qddot[i];
  }
  return DAL_OK;
}

const dal_ode_problem dal__problem_minimal = {"minimal", minimal_size,       minimal_rhs,
                                              NULL,      minimal_from_state, minimal_to_state};

// ---------------------------------------------------------------------------------------------
// services for the ODE integrators

int dal__ode_rhs(dal_ode_integ *ig, double t, const double *y, double *ydot) {
  dal_state *st = ig->st;
  // after an unrecoverable failure nothing more is evaluated in this call: the integrator
  // stops at its last accepted step (some retry a failing right-hand side)
  if (ig->rhs_fatal) return ig->rhs_rc = ig->rhs_fatal;
  st->stats.rhs_evals++;
  // the integrator needs only qddot: outputs are evaluated where the state stops
  st->lean = 1;
  int rc = ig->prob->rhs(ig->sys, st, &ig->opts, t, y, ydot);
  st->lean = 0;
  ig->rhs_rc = rc;
  if (rc) memcpy(ig->rhs_err, st->err, sizeof ig->rhs_err);
  if (rc < 0) ig->rhs_fatal = rc;
  if (rc == DAL__RECOVERABLE) {
    ig->nrecov++;
    ig->recov_t = t;
  }
  return rc;
}

int dal__ode_recov_blocked(const dal_ode_integ *ig) {
  return ig->nrecov > 0 && ig->recov_t >= ig->t && ig->rhs_err[0];
}

int dal__ode_recov_fail(dal_ode_integ *ig, double h) {
  char cause[DAL_ERRMSG_LEN];
  memcpy(cause, ig->rhs_err, sizeof cause);
  return dal__ode_fail(ig, DAL_E_CALLBACK,
                       "%s; the step was shrunk to h=%.3g and it still fails (%d times in this "
                       "call): a failure that persists is not recoverable; fix the callback, or "
                       "return < 0 from it to stop at once; stopped at t=%.17g (last accepted "
                       "step) before the target t=%.17g",
                       cause, h, ig->nrecov, ig->t, ig->tout);
}

int dal__ode_collapsed(dal_ode_integ *ig, double t) {
  if (t - ig->t > 8 * 2.220446049250313e-16 * fmax(1.0, fabs(t))) {
    ig->ntiny = 0;
    return 0;
  }
  return ++ig->ntiny >= 5;
}

int dal__ode_accept(dal_ode_integ *ig, double t, const double *y, int *projected) {
  dal_state *st = ig->st;
  if (projected) *projected = 0;
  if (ig->prob->project && ig->opts.project) {
    // project a copy so that the last accepted step survives a failing projection
    memcpy(ig->ydot, y, (size_t)ig->ny * sizeof(double));
    int rc = ig->prob->project(ig->sys, st, &ig->opts, t, ig->ydot);
    if (rc) {
      char msg[DAL_ERRMSG_LEN];
      memcpy(msg, st->err, sizeof msg);
      return dal__ode_fail(ig, rc < 0 ? rc : DAL_E_CONV,
                           "projection onto the constraint manifold failed after the step to "
                           "t=%.17g: %s; the state holds the step before (t=%.17g)",
                           t, msg, ig->t);
    }
    st->stats.projections++;
    memcpy(ig->y, ig->ydot, (size_t)ig->ny * sizeof(double));
    if (projected) *projected = 1;
  } else {
    memcpy(ig->y, y, (size_t)ig->ny * sizeof(double));
  }
  st->stats.steps++;
  st->stats.last_h = t - ig->t;
  ig->t = t;
  ig->ncall++;
  if (ig->t < ig->tout && ig->ncall >= ig->opts.max_steps) {
    // the variable that limits the steps: the fastest-changing one relative to its
    // tolerance, |y_i'| / (atol + rtol |y_i|), at the last accepted step
    char var[128] = "(not evaluated)";
    if (ig->prob->rhs(ig->sys, st, &ig->opts, ig->t, ig->y, ig->ydot) == 0) {
      for (int i = 0; i < ig->ny; ++i)
        ig->ewt[i] = ig->ydot[i] / (ig->atol + ig->rtol * fabs(ig->y[i]));
      dal__ode_var_name(ig, dal__ode_argmax(ig->ewt, ig->ny), var, sizeof var);
    }
    return dal__ode_fail(ig, DAL_E_MAXSTEPS,
                         "%ld steps taken at t=%.17g before the target t=%.17g "
                         "(opts.max_steps); the fastest-changing variable (relative to its "
                         "tolerance) is %s; raise max_steps, loosen the tolerances, or use "
                         "DAL_METHOD_BDF if the problem is stiff",
                         ig->ncall, ig->t, ig->tout, var);
  }
  return DAL_OK;
}

int dal__ode_fail(dal_ode_integ *ig, int status, const char *fmt, ...) {
  char msg[DAL_ERRMSG_LEN];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  dal_state *st = ig->st;
  // back to the last accepted step, evaluated there
  ig->prob->to_state(ig->sys, st, ig->t, ig->y);
  int rc = ig->prob->rhs(ig->sys, st, &ig->opts, ig->t, ig->y, ig->ydot);
  // the same failure again (e.g. a singular start, where the last accepted step is the start
  // itself): one message, not the cause twice
  if (rc && strncmp(msg, st->err, strlen(st->err)) == 0) rc = 0;
  if (rc) {
    char again[DAL_ERRMSG_LEN];
    memcpy(again, st->err, sizeof again);
    snprintf(st->err, sizeof st->err,
             "%.300s (re-evaluating the last accepted step failed too: "
             "%.140s)",
             msg, again);
  } else {
    memcpy(st->err, msg, sizeof msg);
  }
  if (status == DAL__RECOVERABLE) status = DAL_E_CALLBACK;
  return status;
}

const char *dal__ode_var_name(const dal_ode_integ *ig, int i, char *buf, size_t len) {
  int n = ig->sys->n;
  if (i >= 0 && i < n)
    snprintf(buf, len, "coordinate '%s'", ig->sys->coord_names[i]);
  else if (i >= n && i < 2 * n)
    snprintf(buf, len, "velocity of '%s'", ig->sys->coord_names[i - n]);
  else
    snprintf(buf, len, "component %d of the ODE state", i);
  return buf;
}

void dal__ode_sun_err(int code, const char *module, const char *function, char *msg, void *ud) {
  dal_ode_integ *ig = ud;
  snprintf(ig->sun_err, sizeof ig->sun_err, "%s %s (%d): %s", module, function, code, msg);
}

int dal__ode_argmax(const double *w, int n) {
  int best = 0;
  for (int i = 1; i < n; ++i)
    if (fabs(w[i]) > fabs(w[best])) best = i;
  return best;
}

static void ode_destroy(void *p) {
  dal_ode_integ *ig = p;
  if (!ig) return;
  if (ig->free_impl) ig->free_impl(ig->impl);
  free(ig->y);
  free(ig->ydot);
  free(ig->ewt);
  free(ig);
}

// ---------------------------------------------------------------------------------------------
// integrator handle kept in the state

enum { KIND_ODE = 1, KIND_IDA = 2 };

typedef struct dal_integ_handle {
  int kind;
  dal_ode_integ *ode;
  void *ida;
  double t;   // time of the state when last handed back
  double *qq; // (q, qdot) handed back, to notice changes made outside the integrator
} dal_integ_handle;

static void handle_free(void *p) {
  dal_integ_handle *h = p;
  if (!h) return;
  if (h->ode) ode_destroy(h->ode);
  if (h->ida) dal__ida_free(h->ida);
  free(h->qq);
  free(h);
}

void dal__integ_reset(dal_state *st) {
  if (st->integ && st->integ_free) st->integ_free(st->integ);
  st->integ = NULL;
  st->integ_free = NULL;
}

// validate options; a message names the field and the remedy
static int check_opts(dal_state *st, const dal_solve_opts *o) {
  if (!o) return DAL_FAIL(st, DAL_E_ARG, "solve options are NULL; pass dal_solve_default_opts()");
  if (o->magic != DAL_OPTS_MAGIC)
    return DAL_FAIL(st, DAL_E_ARG,
                    "solve options were not initialized: call dal_solve_default_opts(&opts) "
                    "before setting fields");
  if ((int)o->method < DAL_METHOD_AUTO || (int)o->method > DAL_METHOD_BDF)
    return DAL_FAIL(st, DAL_E_ARG, "opts.method = %d is not a dal_method", (int)o->method);
  if ((int)o->form < DAL_FORM_AUTO || (int)o->form > DAL_FORM_INDEX3)
    return DAL_FAIL(st, DAL_E_ARG, "opts.form = %d is not a dal_formulation", (int)o->form);
  if ((int)o->linsol < DAL_LINSOL_AUTO || (int)o->linsol > DAL_LINSOL_KLU)
    return DAL_FAIL(st, DAL_E_ARG, "opts.linsol = %d is not a dal_linsol", (int)o->linsol);
  // NaN or inf in any real option is a non-finite input, as everywhere in the library
  const double *reals[8] = {&o->rtol, &o->atol, &o->fixed_step, &o->h0,
                            &o->hmin, &o->hmax, &o->baumgarte_alpha, &o->baumgarte_beta};
  const char *rnames[8] = {"rtol", "atol", "fixed_step", "h0",
                           "hmin", "hmax", "baumgarte_alpha", "baumgarte_beta"};
  for (int i = 0; i < 8; ++i)
    if (!isfinite(*reals[i]))
      return DAL_FAIL(st, DAL_E_NONFINITE, "opts.%s = %g is not finite; give a finite value",
                      rnames[i], *reals[i]);
  if (!(o->rtol > 0) || !isfinite(o->rtol))
    return DAL_FAIL(st, DAL_E_ARG, "opts.rtol = %g must be positive and finite (e.g. 1e-8)",
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
  if (!isfinite(o->baumgarte_alpha) || !isfinite(o->baumgarte_beta) || o->baumgarte_alpha < 0 ||
      o->baumgarte_beta < 0)
    return DAL_FAIL(st, DAL_E_ARG, "opts.baumgarte_alpha/beta must be >= 0 and finite");
  return DAL_OK;
}

// the options an integrator depends on are the same
static int same_opts(const dal_solve_opts *a, const dal_solve_opts *b) {
  return a->method == b->method && a->form == b->form && a->linsol == b->linsol &&
         a->rtol == b->rtol && a->atol == b->atol && a->h0 == b->h0 && a->hmin == b->hmin &&
         a->hmax == b->hmax && a->fixed_step == b->fixed_step && a->max_steps == b->max_steps &&
         a->baumgarte_alpha == b->baumgarte_alpha && a->baumgarte_beta == b->baumgarte_beta &&
         a->project == b->project && a->sparse_threshold == b->sparse_threshold &&
         a->fixed_erk == b->fixed_erk;
}

/// The automatic method for an ODE formulation, by relative tolerance (documented in solve.h):
/// rtol > 1e-6: DOPRI5; 1e-12 <= rtol <= 1e-6: Adams; rtol < 1e-12: Bulirsch-Stoer.
static dal_method auto_method(double rtol) {
  if (rtol > 1e-6) return DAL_METHOD_DOPRI5;
  if (rtol >= 1e-12) return DAL_METHOD_ADAMS;
  return DAL_METHOD_BS;
}

// resolve formulation and method; *prob is NULL for the IDA route
static int resolve(const dal_system *sys, dal_state *st, const dal_solve_opts *o, dal_method *meth,
                   const dal_ode_problem **prob) {
  dal_formulation form = o->form;
  dal_method m = o->method;
  if (form == DAL_FORM_AUTO) form = sys->m ? DAL_FORM_GGL : DAL_FORM_ODE;
  if (form == DAL_FORM_INDEX1 && sys->m == 0) form = DAL_FORM_ODE;
  if (form == DAL_FORM_ODE && sys->m > 0)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "formulation 'ode' needs minimal coordinates, but the system has %d "
                    "constraint rows (first: '%s'); use DAL_FORM_GGL or DAL_FORM_INDEX1",
                    sys->m, sys->con[0].name);
  if (form == DAL_FORM_GGL || form == DAL_FORM_INDEX3 ||
      (form == DAL_FORM_INDEX1 && m == DAL_METHOD_BDF)) {
    if (m != DAL_METHOD_AUTO && m != DAL_METHOD_BDF)
      return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                      "formulation '%s' runs only with DAL_METHOD_BDF (IDA), not '%s'; use "
                      "DAL_METHOD_BDF or DAL_METHOD_AUTO, or DAL_FORM_INDEX1 for explicit "
                      "methods",
                      dal_formulation_name(form), dal_method_name(m));
    *meth = DAL_METHOD_BDF;
    *prob = NULL;
    return DAL_OK;
  }
  if (m == DAL_METHOD_AUTO) m = auto_method(o->rtol);
  *meth = m;
  *prob = form == DAL_FORM_INDEX1 ? &dal__problem_index1 : &dal__problem_minimal;
  return DAL_OK;
}

double dal__tol_factor(dal_method m) {
  switch (m) {
  case DAL_METHOD_DOPRI5:
    return 0.1;
  case DAL_METHOD_FEHLBERG78:
    return 0.03;
  case DAL_METHOD_BS:
    return 0.005;
  case DAL_METHOD_ADAMS:
    return 0.01;
  case DAL_METHOD_BDF:
    return 0.001;
  default:
    return 1.0;
  }
}

// a fresh ODE integrator at the state's (t, q, qdot)
static int ode_create(const dal_system *sys, dal_state *st, const dal_solve_opts *o,
                      dal_method meth, const dal_ode_problem *prob, dal_ode_integ **out) {
  *out = NULL;
  dal_ode_integ *ig = calloc(1, sizeof *ig);
  if (!ig) return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the integrator");
  ig->prob = prob;
  ig->sys = sys;
  ig->st = st;
  ig->opts = *o;
  ig->method = meth;
  ig->ny = prob->size(sys);
  double c = dal__tol_factor(meth);
  ig->rtol = fmax(c * o->rtol, DAL_TOL_FLOOR);
  ig->atol = c * o->atol;
  ig->t = st->t;
  size_t ny = (size_t)ig->ny + 1;
  ig->y = calloc(ny, sizeof(double));
  ig->ydot = calloc(ny, sizeof(double));
  ig->ewt = calloc(ny, sizeof(double));
  if (!ig->y || !ig->ydot || !ig->ewt) {
    ode_destroy(ig);
    return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the integrator");
  }
  prob->from_state(sys, st, ig->y);
  int rc;
  switch (meth) {
  case DAL_METHOD_DOPRI5:
  case DAL_METHOD_FEHLBERG78:
    rc = dal__erk_create(ig);
    break;
  case DAL_METHOD_ADAMS:
  case DAL_METHOD_BDF:
    rc = dal__cvode_create(ig);
    break;
  case DAL_METHOD_BS:
    rc = dal__bs_create(ig);
    break;
  case DAL_METHOD_RK4:
    rc = dal__rk4_create(ig);
    break;
  default:
    rc =
        DAL_FAIL(st, DAL_E_UNSUPPORTED, "no ODE integrator for method '%s'", dal_method_name(meth));
  }
  if (rc) {
    if (rc > 0) rc = DAL_E_SOLVER;
    ode_destroy(ig);
    return rc;
  }
  *out = ig;
  return DAL_OK;
}

// remember what the state looked like when the integrator handed it back
static void handle_sync(const dal_system *sys, dal_state *st, dal_integ_handle *h) {
  size_t n = (size_t)sys->n;
  h->t = st->t;
  memcpy(h->qq, st->q, n * sizeof(double));
  memcpy(h->qq + n, st->qdot, n * sizeof(double));
}

// the state's (t, q, qdot) still are where the integrator left them
static int handle_current(const dal_system *sys, const dal_state *st, const dal_integ_handle *h) {
  size_t n = (size_t)sys->n;
  return h->t == st->t && memcmp(h->qq, st->q, n * sizeof(double)) == 0 &&
         memcmp(h->qq + n, st->qdot, n * sizeof(double)) == 0;
}

// make sure st->integ is an integrator for these options at the state's current point
static int ensure_integ(const dal_system *sys, dal_state *st, const dal_solve_opts *o) {
  dal_integ_handle *h = st->integ;
  if (h && same_opts(o, &st->integ_opts) && handle_current(sys, st, h)) return DAL_OK;
  dal__integ_reset(st);
  dal_method meth = DAL_METHOD_AUTO;
  const dal_ode_problem *prob = NULL;
  int rc = resolve(sys, st, o, &meth, &prob);
  if (rc) return rc;
  h = calloc(1, sizeof *h);
  if (!h) return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the integrator");
  h->qq = calloc(2 * (size_t)sys->n + 1, sizeof(double));
  if (!h->qq) {
    free(h);
    return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the integrator");
  }
  if (prob) {
    h->kind = KIND_ODE;
    rc = ode_create(sys, st, o, meth, prob, &h->ode);
  } else {
    h->kind = KIND_IDA;
    rc = dal__ida_create(sys, st, o, &h->ida);
    if (rc > 0) rc = DAL_E_SOLVER;
  }
  if (rc) {
    handle_free(h);
    return rc;
  }
  handle_sync(sys, st, h);
  st->integ = h;
  st->integ_free = handle_free;
  st->integ_opts = *o;
  return DAL_OK;
}

// evaluate the state where it stands (outputs valid); a recoverable request is a failure here
static int evaluate_here(const dal_system *sys, dal_state *st) {
  int rc = dal__forward(sys, st);
  if (rc == DAL__RECOVERABLE) rc = DAL_E_CALLBACK;
  return rc;
}

// advance to t1 >= st->t with validated arguments
static int advance_to(const dal_system *sys, dal_state *st, const dal_solve_opts *o, double t1) {
  int rc = ensure_integ(sys, st, o);
  if (rc) return rc;
  dal_integ_handle *h = st->integ;
  if (t1 == st->t) return evaluate_here(sys, st);
  if (t1 - st->t <= 8 * 2.220446049250313e-16 * fmax(1.0, fabs(st->t))) {
    // an interval of a few ulps: the solution does not change at double precision; restart
    // the integrator at the new time rather than asking it for a step it cannot take
    dal__integ_reset(st);
    st->t = t1;
    return evaluate_here(sys, st);
  }
  if (h->kind == KIND_ODE) {
    dal_ode_integ *ig = h->ode;
    ig->tout = t1;
    ig->ncall = 0;
    ig->rhs_fatal = 0;
    ig->ntiny = 0;
    ig->nrecov = 0;
    rc = ig->advance(ig, t1);
    if (!rc) {
      // the state at t1, evaluated there
      ig->prob->to_state(sys, st, ig->t, ig->y);
      rc = ig->prob->rhs(sys, st, &ig->opts, ig->t, ig->y, ig->ydot);
      if (rc == DAL__RECOVERABLE) rc = DAL_E_CALLBACK;
    }
  } else {
    rc = dal__ida_advance(sys, st, h->ida, t1);
    if (rc > 0) rc = DAL_E_SOLVER;
  }
  if (rc) {
    // the state holds the last accepted step; the next call restarts the integrator there
    dal__integ_reset(st);
    return rc;
  }
  st->err[0] = 0;
  handle_sync(sys, st, h);
  return DAL_OK;
}

// common argument checks of advance and evolve
static int check_call(const dal_system *sys, dal_state *st, const dal_solve_opts *o, double t1,
                      const char *what) {
  if (!st) return DAL_E_ARG;
  if (!sys || st->sys != sys)
    return DAL_FAIL(st, DAL_E_STATE, "%s: the state belongs to another system", what);
  int rc = check_opts(st, o);
  if (rc) return rc;
  if (!isfinite(t1))
    return DAL_FAIL(st, DAL_E_NONFINITE, "%s: target time is %g; give a finite time", what, t1);
  // a step bound below the spacing of doubles at t cannot move t
  const double hs[3] = {o->h0, o->hmin, o->hmax};
  const char *hn[3] = {"h0", "hmin", "hmax"};
  for (int i = 0; i < 3; ++i)
    if (hs[i] > 0 && (st->t + hs[i] == st->t || t1 + hs[i] == t1))
      return DAL_FAIL(st, DAL_E_ARG,
                      "%s: opts.%s = %g is below the floating-point resolution of t between %g "
                      "and %g; use a larger value or 0 (automatic)",
                      what, hn[i], hs[i], st->t, t1);
  if (t1 < st->t)
    return DAL_FAIL(st, DAL_E_TIME,
                    "%s: target time %.17g lies behind the current time %.17g; integration runs "
                    "forward only (reset the state with dal_state_set to go back)",
                    what, t1, st->t);
  return DAL_OK;
}

// the options as the integrators read them: atol = 0 follows rtol (solve.h)
static dal_solve_opts effective_opts(const dal_solve_opts *o) {
  dal_solve_opts e = *o;
  if (e.atol == 0.0) e.atol = DAL_ATOL_PER_RTOL * e.rtol;
  return e;
}

int dal_advance(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t1) {
  int rc = check_call(sys, st, opts, t1, "advance");
  if (rc) return rc;
  dal_solve_opts eff = effective_opts(opts);
  return advance_to(sys, st, &eff, t1);
}

// run the monitor at the state's time; 1 = stop requested (ok), negative = failure
static int call_monitor(const dal_system *sys, dal_state *st, dal_monitor_fn *monitor, void *ctx) {
  if (!monitor) return 0;
  int mr = monitor(sys, st, ctx);
  if (mr > 0) {
    // not a failure; the message says where and why the run ended
    DAL_FAIL(st, DAL_STOPPED, "monitor returned %d at t=%.17g: evolve stopped there as asked", mr,
             st->t);
    return 1;
  }
  if (mr < 0)
    return DAL_FAIL(st, DAL_E_CALLBACK,
                    "monitor returned %d (%s) at t=%.17g; evolve stopped there (the state holds "
                    "that time)",
                    mr, dal_status_name(mr), st->t);
  return 0;
}

int dal_evolve(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t1,
               double dt, dal_monitor_fn *monitor, void *ctx) {
  int rc = check_call(sys, st, opts, t1, "evolve");
  if (rc) return rc;
  if (!(dt > 0) || !isfinite(dt))
    return DAL_FAIL(st, DAL_E_ARG, "evolve: output interval dt = %g must be positive and finite",
                    dt);
  double t0 = st->t, span = (t1 - t0) / dt;
  // a dt below the floating-point spacing of t would give output times that never advance
  if (t0 + dt == t0 || t1 + dt == t1)
    return DAL_FAIL(st, DAL_E_ARG,
                    "evolve: output interval dt = %g is below the floating-point resolution of "
                    "t between %g and %g; use a larger dt or restart the clock near 0",
                    dt, t0, t1);
  if (span > 1e12)
    return DAL_FAIL(st, DAL_E_ARG,
                    "evolve: %.3g output times between %g and %g (dt = %g); use a larger dt", span,
                    t0, t1, dt);
  // K = number of whole output intervals: t0 + K dt <= t1 in floating point
  dal_solve_opts eff = effective_opts(opts);
  opts = &eff;
  long K = (long)floor(span);
  while (K > 0 && t0 + (double)K * dt > t1)
    --K;
  while (t0 + (double)(K + 1) * dt <= t1)
    ++K;
  for (long k = 0; k <= K; ++k) {
    double tk = t0 + (double)k * dt;
    // a grid time within rounding of t1 is t1 itself (no near-duplicate output)
    if (k == K && t1 - tk <= 1e-9 * dt) tk = t1;
    if ((rc = advance_to(sys, st, opts, tk)) != 0) return rc;
    if ((rc = call_monitor(sys, st, monitor, ctx)) != 0) return rc > 0 ? DAL_STOPPED : rc;
  }
  if (st->t < t1) {
    if ((rc = advance_to(sys, st, opts, t1)) != 0) return rc;
    if ((rc = call_monitor(sys, st, monitor, ctx)) != 0) return rc > 0 ? DAL_STOPPED : rc;
  }
  return DAL_OK;
}
