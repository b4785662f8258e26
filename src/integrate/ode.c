// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Services shared by the ODE integrators: counted right-hand sides, accepted steps, progress
// and failure handling (the state always keeps the last accepted step), creation.
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "families.h"
#include "integrate.h"

int dal__ode_eval(dal_ode_integ *ig, double t, const double *y, double *ydot, unsigned need) {
  dal_state *st = ig->st;
  int work = ig->opts.work != 0;
  int rc = ig->prob->rhs(ig->sys, st, &ig->opts, t, y, ydot, need | (work ? DAL_P_POW : 0u));
  if (rc == 0 && work) {
    // W' = dE/dt from the forces and moving constraints (the last component of y)
    st->W = y[ig->ny - 1];
    ydot[ig->ny - 1] = st->power;
  }
  return rc;
}

void dal__ode_to_state(dal_ode_integ *ig, double t, const double *y) {
  ig->prob->to_state(ig->sys, ig->st, t, y);
  if (ig->opts.work) ig->st->W = y[ig->ny - 1];
}

int dal__ode_rhs(dal_ode_integ *ig, double t, const double *y, double *ydot) {
  dal_state *st = ig->st;
  // after an unrecoverable failure nothing more is evaluated in this call: the integrator
  // stops at its last accepted step (some retry a failing right-hand side)
  if (ig->rhs_fatal) return ig->rhs_rc = ig->rhs_fatal;
  st->stats.rhs_evals++;
  int rc = dal__ode_eval(ig, t, y, ydot, DAL_P_ACC);
  ig->rhs_rc = rc;
  if (rc) memcpy(ig->rhs_err, st->err, sizeof ig->rhs_err);
  if (rc < 0) ig->rhs_fatal = rc;
  if (dal__is_retry(rc)) {
    ig->nrecov++;
    ig->recov_t = t;
    ig->recov_rc = rc;
  }
  return rc;
}

int dal__ode_recov_blocked(const dal_ode_integ *ig) {
  return ig->nrecov > 0 && ig->recov_t >= ig->t && ig->rhs_err[0];
}

int dal__ode_recov_fail(dal_ode_integ *ig, double h) {
  char cause[DAL_ERRMSG_LEN];
  memcpy(cause, ig->rhs_err, sizeof cause);
  int code = ig->recov_rc ? ig->recov_rc : DAL__RECOVERABLE;
  const char *remedy = code == DAL__RECOVERABLE
                           ? "a failure that persists is not recoverable; fix the callback, or "
                             "return < 0 from it to stop at once"
                           : "no smaller step avoids it";
  return dal__ode_fail(ig, code,
                       "%s; the step was shrunk to h=%.3g and it still fails (%d times in this "
                       "call): %s; stopped at t=%.17g (last accepted step) before the target "
                       "t=%.17g",
                       cause, h, ig->nrecov, remedy, ig->t, ig->tout);
}

int dal__ode_collapsed(dal_ode_integ *ig, double t) {
  if (ig->ntiny > 0 && t == ig->tiny_t) return ig->ntiny >= DAL_TINY_STEP_COUNT;
  ig->tiny_t = t;
  if (t - ig->t > DAL_TINY_STEP(t)) {
    ig->ntiny = 0;
    return 0;
  }
  return ++ig->ntiny >= DAL_TINY_STEP_COUNT;
}

// The progress guard: the step from ig->t to t (result y) must advance t, not be one of a
// run of steps of a few ulps, and hold finite values. Otherwise fail with the cause: a retry
// that kept failing there, else a step size collapse (DAL_E_STEP) or an overflow.
static int ode_progress(dal_ode_integ *ig, double t, const double *y) {
  char var[128];
  int bad = -1;
  for (int i = 0; i < ig->ny && bad < 0; ++i)
    if (!isfinite(y[i])) bad = i;
  if (bad >= 0)
    return dal__ode_fail(ig, DAL_E_NONFINITE,
                         "the step from t=%.17g to t=%.17g (%s) overflowed: %s is %g; the state "
                         "holds the step before; the solution leaves the range of doubles there, "
                         "or the step is too long for the method (a smaller opts.fixed_step or "
                         "opts.hmax)",
                         ig->t, t, dal_method_name(ig->method),
                         dal__ode_var_name(ig, bad, var, sizeof var), y[bad]);
  int stalled = !(t > ig->t);
  if (!stalled && !dal__ode_collapsed(ig, t)) return DAL_OK;
  return dal__ode_stall(ig, t - ig->t,
                        stalled ? "the step does not advance t" : "steps of a few ulps of t");
}

int dal__ode_rhs_fail(dal_ode_integ *ig) {
  return dal__ode_fail(ig,
                       ig->rhs_fatal  ? ig->rhs_fatal
                       : ig->recov_rc ? ig->recov_rc
                                      : DAL__RECOVERABLE,
                       "%s; stopped at t=%.17g (last accepted step) before the target t=%.17g",
                       ig->rhs_err, ig->t, ig->tout);
}

int dal__ode_step_gap(dal_ode_integ *ig, double tret, double tn, double hlast, int at_tstop,
                      double tout) {
  if (at_tstop || tn > tret) tn = ig->t + hlast;
  return dal__ode_tstop_gap(ig, tn, at_tstop ? tout : tret);
}

int dal__ode_tstop_gap(dal_ode_integ *ig, double tn, double tout) {
  double gap = tout - tn;
  if (!(gap > DAL_TINY_STEP(tout))) return DAL_OK;
  // a gap over which nothing moves beyond the tolerances (the last step of a fixed-step run
  // that fell a few ulps short) is closed honestly by the snap
  if (dal__ode_eval(ig, ig->t, ig->y, ig->ydot, DAL_P_ACC) == 0) {
    int moves = 0;
    for (int i = 0; i < ig->ny && !moves; ++i)
      moves = !(fabs(ig->ydot[i]) * gap <= ig->atol + ig->rtol * fabs(ig->y[i]));
    if (!moves) return DAL_OK;
  }
  return dal__ode_fail(ig, DAL_E_STEP,
                       "%s stopped at t=%.17g, %.3g before the target t=%.17g, and would "
                       "extrapolate the rest: an interval of %.0f x DBL_EPSILON |t| is below its "
                       "resolution of time at this magnitude (it takes a stop time within 100 "
                       "ulps of t as reached); restart the clock near 0 (shift the time origin); "
                       "the state holds the last accepted step t=%.17g",
                       dal_method_name(ig->method), tn, tout - tn, tout,
                       (tout - tn) / (DBL_EPSILON * fabs(tout)), ig->t);
}

int dal__ode_stall(dal_ode_integ *ig, double h, const char *what) {
  char var[128];
  if (dal__ode_recov_blocked(ig)) return dal__ode_recov_fail(ig, h);
  // the variable that changes fastest relative to its tolerance at the last accepted step
  snprintf(var, sizeof var, "(not evaluated)");
  if (ig->prob->rhs(ig->sys, ig->st, &ig->opts, ig->t, ig->y, ig->ydot, DAL_P_ACC) == 0) {
    for (int i = 0; i < ig->ny; ++i)
      ig->ewt[i] = ig->ydot[i] / (ig->atol + ig->rtol * fabs(ig->y[i]));
    dal__ode_var_name(ig, dal__ode_argmax(ig->ewt, ig->ny), var, sizeof var);
  }
  return dal__ode_fail(ig, DAL_E_STEP,
                       "step size collapse at t=%.17g (%s): %s (h=%.3g); the fastest-changing "
                       "variable (relative to its tolerance) is %s; the solution may be "
                       "singular there, or the tolerances too tight for its scale (atol is "
                       "absolute), or the step too small for t's precision: loosen rtol/atol, "
                       "give opts.h0, check the model near this time, or restart the clock near 0",
                       ig->t, dal_method_name(ig->method), what, h, var);
}

int dal__ode_accept(dal_ode_integ *ig, double t, const double *y, int *projected) {
  dal_state *st = ig->st;
  if (projected) *projected = 0;
  int rc = ode_progress(ig, t, y);
  if (rc) return rc;
  if (ig->prob->project && ig->opts.project) {
    // project a copy so that the last accepted step survives a failing projection
    memcpy(ig->ydot, y, (size_t)ig->ny * sizeof(double));
    rc = ig->prob->project(ig->sys, st, &ig->opts, t, ig->ydot);
    if (rc) {
      char msg[DAL_ERRMSG_LEN];
      memcpy(msg, st->err, sizeof msg);
      return dal__ode_fail(ig, rc < 0 ? rc : DAL_E_CONV,
                           "projection onto the constraint manifold failed after the step to "
                           "t=%.17g: %s; the state holds the step before (t=%.17g)",
                           t, msg, ig->t);
    }
    st->stats.projections++;
    if (ig->hook) memcpy(ig->yprev, ig->y, (size_t)ig->ny * sizeof(double));
    memcpy(ig->y, ig->ydot, (size_t)ig->ny * sizeof(double));
    if (projected) *projected = 1;
  } else {
    if (ig->hook) memcpy(ig->yprev, ig->y, (size_t)ig->ny * sizeof(double));
    memcpy(ig->y, y, (size_t)ig->ny * sizeof(double));
  }
  st->stats.steps++;
  st->stats.last_h = t - ig->t;
  ig->tprev = ig->t;
  ig->t = t;
  ig->ncall++;
  if (ig->hook) {
    // dense output and events of the step just accepted (driver.c); the Hermite fallback's
    // slope at the end of the last step is the slope at the start of this one
    if (ig->hvalid & 2) {
      double *sw = ig->hf0;
      ig->hf0 = ig->hf1;
      ig->hf1 = sw;
      ig->hvalid = 1;
    } else {
      ig->hvalid = 0;
    }
    if ((rc = ig->hook(ig->hook_ctx)) != 0) return rc;
  }
  if (ig->t < ig->tout && ig->ncall >= ig->opts.max_steps) {
    // the variable that limits the steps: the fastest-changing one relative to its
    // tolerance, |y_i'| / (atol + rtol |y_i|), at the last accepted step
    char var[128] = "(not evaluated)";
    if (dal__ode_eval(ig, ig->t, ig->y, ig->ydot, DAL_P_ACC) == 0) {
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
  dal__ode_to_state(ig, ig->t, ig->y);
  int rc = dal__ode_eval(ig, ig->t, ig->y, ig->ydot, DAL_P_ALL);
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
  return dal__public_status(status);
}

const char *dal__ode_var_name(const dal_ode_integ *ig, int i, char *buf, size_t len) {
  int n = ig->sys->n;
  if (i >= 0 && i < n)
    snprintf(buf, len, "coordinate '%s'", ig->sys->coord_names[i]);
  else if (i >= n && i < 2 * n)
    snprintf(buf, len, "velocity of '%s'", ig->sys->coord_names[i - n]);
  else if (ig->opts.work && i == ig->ny - 1)
    snprintf(buf, len, "the work W of the forces and moving constraints (opts.work)");
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

int dal__ode_advance(dal_ode_integ *ig, double tout) {
  ig->tout = tout;
  ig->ncall = 0;
  ig->rhs_fatal = 0;
  ig->ntiny = 0;
  ig->nrecov = 0;
  return ig->ops->advance(ig, tout);
}

int dal__ode_changed_y(dal_ode_integ *ig, int i0) {
  if (!ig->ops->changed_y) return 0;
  ig->ops->changed_y(ig, i0);
  return 1;
}

int dal__ode_can_change_y(const dal_ode_integ *ig) { return ig->ops->changed_y != NULL; }

void dal__ode_destroy(void *p) {
  dal_ode_integ *ig = p;
  if (!ig) return;
  // a first-order problem's integrator lets go of the work state (dal__ode_create_fo)
  if (ig->st && ig->st->fo && ig->prob == &ig->st->fo->prob) ig->st->fo = NULL;
  if (ig->ops && ig->ops->free_impl) ig->ops->free_impl(ig->impl);
  free(ig->y);
  free(ig->ydot);
  free(ig->ewt);
  free(ig->yprev);
  free(ig->hf0);
  free(ig->hf1);
  free(ig->hc);
  free(ig);
}

// a fresh ODE integrator at the state's (t, q, qdot)
int dal__ode_create(const dal_system *sys, dal_state *st, const dal_solve_opts *o, dal_method meth,
                    const dal_ode_problem *prob, dal_ode_integ **out) {
  *out = NULL;
  dal_ode_integ *ig = calloc(1, sizeof *ig);
  if (!ig) return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the integrator");
  ig->prob = prob;
  ig->sys = sys;
  ig->st = st;
  ig->opts = *o;
  ig->method = meth;
  // with opts.work the work W of the forces and moving constraints is integrated as the last
  // component of y, under the same error control
  ig->ny = (prob->ny > 0 ? prob->ny : prob->size(sys)) + (o->work ? 1 : 0);
  // the local tolerances: a request below the method's min_rtol runs as min_rtol (atol raised
  // in proportion, the requested ratio atol / rtol kept, as for IDA); rtol not below the floor
  const dal_method_row *mrow = dal__method_row(meth);
  double c = dal__tol_factor(meth) * prob->tol_factor, rt = o->rtol, at = o->atol;
  if (mrow && o->rtol < mrow->min_rtol) {
    // the clamped run is the run at min_rtol itself (atol = rtol stays exactly so): a tighter
    // request is never worse than the floor (tests/test_dense.c, test_tighter)
    rt = mrow->min_rtol;
    at = o->atol == o->rtol ? rt : o->atol * (rt / o->rtol);
  }
  ig->rtol = fmax(c * rt, DAL_TOL_FLOOR);
  ig->atol = c * at;
  st->stats.rtol_used = ig->rtol; // the local tolerance, floor included (solve.h)
  ig->t = st->t;
  size_t ny = (size_t)ig->ny + 1;
  ig->y = calloc(ny, sizeof(double));
  ig->ydot = calloc(ny, sizeof(double));
  ig->ewt = calloc(ny, sizeof(double));
  ig->yprev = calloc(ny, sizeof(double));
  ig->hf0 = calloc(ny, sizeof(double));
  ig->hf1 = calloc(ny, sizeof(double));
  ig->hc = calloc(4 * ny, sizeof(double));
  ig->tprev = ig->t;
  if (!ig->y || !ig->ydot || !ig->ewt || !ig->yprev || !ig->hf0 || !ig->hf1 || !ig->hc) {
    dal__ode_destroy(ig);
    return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the integrator");
  }
  prob->from_state(sys, st, ig->y);
  if (o->work) ig->y[ig->ny - 1] = st->W;
  memcpy(ig->yprev, ig->y, (size_t)ig->ny * sizeof(double));
  const dal_method_row *row = dal__method_row(meth);
  int rc = row && row->ode_create
               ? row->ode_create(ig)
               : DAL_FAIL(st, DAL_E_UNSUPPORTED, "no ODE integrator for method '%s'",
                          dal_method_name(meth));
  if (rc) {
    if (rc > 0) rc = DAL_E_SOLVER;
    dal__ode_destroy(ig);
    return rc;
  }
  *out = ig;
  return DAL_OK;
}

// Cubic Hermite interpolation on [tprev, t] from y and f = y' at both ends (Hairer-Norsett-
// Wanner I, sec. II.6, (6.7)): the dense output of RK4 and DOPRI5. The slopes are evaluated on
// first use in a step and kept; the end slope of one step is the start slope of the next, so
// a run with outputs in every step pays one right-hand side per step (none for DOPRI5, whose
// last stage is that slope). Once per step the coefficients, then a few flops per output:
// measured 10x cheaper per output than ARKODE's own interpolation call.
int dal__ode_start_slope(dal_ode_integ *ig) {
  if (ig->hvalid & 1) return DAL_OK;
  int rc = dal__ode_eval(ig, ig->tprev, ig->yprev, ig->hf0, DAL_P_ACC);
  if (rc) return dal__public_status(rc);
  ig->st->stats.rhs_evals++;
  ig->hvalid |= 1;
  return DAL_OK;
}

int dal__ode_end_slope(dal_ode_integ *ig) {
  if (ig->hvalid & 2) return DAL_OK;
  // the method's own slope at the step's end when it has one (no projection moved y)
  int own = ig->ops->end_slope && !(ig->prob->project && ig->opts.project);
  int rc =
      own ? ig->ops->end_slope(ig, ig->hf1) : dal__ode_eval(ig, ig->t, ig->y, ig->hf1, DAL_P_ACC);
  if (rc) return dal__public_status(rc);
  if (!own) ig->st->stats.rhs_evals++;
  ig->hvalid |= 2;
  return DAL_OK;
}

// the cubic in s = (t - tprev) / h, once per step: with d = y1 - y0, a = h f0, b = h f1,
// y(s) = y0 + s (a + s ((3 d - 2 a - b) + s (a + b - 2 d))), coefficients interleaved per
// component (hc[4 i .. 4 i + 3])
static int hermite_coeffs(dal_ode_integ *ig) {
  int rc = dal__ode_start_slope(ig);
  if (!rc) rc = dal__ode_end_slope(ig);
  if (rc) return rc;
  double h = ig->t - ig->tprev;
  for (int i = 0; i < ig->ny; ++i) {
    double y0 = ig->yprev[i], d = ig->y[i] - y0, a = h * ig->hf0[i], b = h * ig->hf1[i];
    double *c = ig->hc + 4 * (size_t)i;
    c[0] = y0;
    c[1] = a;
    c[2] = 3.0 * d - 2.0 * a - b;
    c[3] = a + b - 2.0 * d;
  }
  ig->hvalid |= ig->place_direct ? 4 | 8 : 4;
  return DAL_OK;
}

// the step's cubic at t (hermite_coeffs done): Horner per output
static inline void hermite_horner(const dal_ode_integ *ig, double t, double *yout) {
  double s = (t - ig->tprev) / (ig->t - ig->tprev);
  const double *c = ig->hc;
  for (int i = 0; i < ig->ny; ++i, c += 4)
    yout[i] = c[0] + s * (c[1] + s * (c[2] + s * c[3]));
}

static int ode_hermite(dal_ode_integ *ig, double t, double *yout) {
  if (!(ig->hvalid & 4)) {
    int rc = hermite_coeffs(ig);
    if (rc) return rc;
  }
  hermite_horner(ig, t, yout);
  return DAL_OK;
}

// y at t in [tprev, t] into yout
static int ode_interp(dal_ode_integ *ig, double t, double *yout) {
  // the step's ends are the accepted values themselves (projected where the form projects)
  if (t >= ig->t || ig->t == ig->tprev) {
    memcpy(yout, ig->y, (size_t)ig->ny * sizeof(double));
    return DAL_OK;
  }
  if (t <= ig->tprev) {
    memcpy(yout, ig->yprev, (size_t)ig->ny * sizeof(double));
    return DAL_OK;
  }
  return ig->ops->interp ? ig->ops->interp(ig, t, yout) : ode_hermite(ig, t, yout);
}

// dal__ode_place where the fast path does not apply: an end of the step, the method's own
// interpolant, the step's first Hermite output, or y copied by the problem
static DAL__NOINLINE int ode_place_slow(dal_ode_integ *ig, double t) {
  int rc = ode_interp(ig, t, ig->yplace);
  if (rc) return rc;
  // y is in the state's (q, qdot) already, or copied there by the problem
  dal_state *st = ig->st;
  if (ig->place_direct)
    st->t = t;
  else
    dal__ode_to_state(ig, t, ig->yplace);
  dal__state_moved(st);
  return DAL_OK;
}

// inside the step of a method with its own interpolant, y in the state's layout: straight into
// the state's (q, qdot); else the slow path
static int ode_place_own(dal_ode_integ *ig, double t) {
  if (!(ig->place_direct && ig->ops->interp && t > ig->tprev && t < ig->t))
    return ode_place_slow(ig, t);
  int rc = ig->ops->interp(ig, t, ig->yplace);
  if (rc) return rc;
  ig->st->t = t;
  dal__state_moved(ig->st);
  return DAL_OK;
}

int dal__ode_place(dal_ode_integ *ig, double t) {
  if ((ig->hvalid & 8) && t > ig->tprev && t < ig->t) {
    // inside the step, its Hermite cubic built: straight into the state's (q, qdot)
    hermite_horner(ig, t, ig->yplace);
    ig->st->t = t;
    dal__state_moved(ig->st);
    return DAL_OK;
  }
  return ode_place_own(ig, t);
}
