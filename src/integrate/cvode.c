// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Variable-order multistep methods through SUNDIALS CVODE: Adams-Moulton (orders 1-12) with
// fixed-point (functional) iteration, and BDF (orders 1-5) with Newton iteration on a dense
// difference-quotient Newton matrix (Hindmarsh et al., SUNDIALS, ACM TOMS 31, 2005; Hairer-Norsett-
// Wanner, Solving ODEs I, sec. III.1-III.7). One internal step per call.
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include "integrate.h"
#include "nvec.h"

/// CVODE's Newton convergence coefficient with the exact Newton matrix (default 0.1): the
/// exact matrix converges in fewer iterations, and CVODE's test then stops them while the
/// iterate still carries more error at rtol 1e-12 (the tolerance table's BDF column measured
/// 22.9 x rtol there; 0.1 x the default keeps it within the bound, see test_core)
#define NLS_COEF 0.01

/// CVODE's highest order (Adams; BDF stops at 5): the dense-output polynomial has at most
/// CV_QMAX + 1 coefficients per component
#define CV_QMAX 12

struct cv_mem;
/// the dense output's probe vector's content: a serial vector's (on the probe's sum), so that
/// every serial operation works on it, then the integrator memory its linear combination fills
typedef struct cv_probe_content {
  struct _N_VectorContent_Serial serial;
  struct cv_mem *m;
} cv_probe_content;

typedef struct cv_mem {
  void *cv;
  dal_sun_vecs v; // context and vectors
  SUNMatrix A;
  SUNLinearSolver LS;
  SUNNonlinearSolver NLS;
  long netf, nsf, nje, nni; // counters already added to the state's statistics
  dal_tangent *tg; // exact Newton matrix for BDF in minimal coordinates (NULL: differences)
  double *Af;      // its vector-field Jacobian (2n x 2n, column-major)
  int ahead;       // CVODE's time is beyond the state's (cv_advance_ahead)
  // dense output (cv_interp): CVodeGetDky(t, 0) sums the Nordsieck columns zn[q..0] with the
  // powers of s = (t - tn) / h by N_VLinearCombination on its output vector. Into `probe` (a
  // serial vector whose linear combination is cv_probe_sum) it hands the columns over: copied
  // once per step, they give every output of the step by Horner in s
  N_Vector probe;
  cv_probe_content pcontent;
  double *pout; // the probe's sum when the columns do not fit (ny)
  double *zc;   // the columns, component by component: zc[i (CV_QMAX + 1) + j] = zn[q - j]_i
  double pc[CV_QMAX + 1]; // the coefficients CVODE handed over
  int pn;                 // their number (q + 1); 0: not kept
  int ny;                 // the size of the vectors
  double ptn, ph;         // tn and h of the step, as CVodeGetDky reads them
  int pfast;   // zc holds this step's columns (a probed call in this step matched the form)
  int pbroken; // a probed call did not match the assumed form: CVodeGetDky every output
  long nfast;  // outputs served without a CVodeGetDky call (dal__cvode_fast_outputs)
} cv_mem;

static int cv_rhs(realtype t, N_Vector y, N_Vector ydot, void *ud) {
  dal_ode_integ *ig = ud;
  return dal__ode_rhs(ig, t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
}

// Newton matrix for BDF: difference quotients column by column, with CVODE's increments
// (inc_j = max(sqrt(uround) |y_j|, min_inc / w_j), min_inc from the step, size and |f|;
// Hindmarsh et al. 2005, sec. 2.1). Written here so that a step allocates nothing (CVODE's
// own dense difference quotient clones a vector per Jacobian).
// The exact Jacobian df/dy of f = (qdot, qddot) from the jets (form/tangent.c, the same tangent
// as dal_vector_field_jacobian); nonzero when it cannot be had at this point (a jet without a
// third derivative, a singular M): the caller falls back to differences
static int cv_jac_exact(dal_ode_integ *ig, cv_mem *m, double t, const double *y, SUNMatrix J) {
  dal_state *st = ig->st;
  int n = ig->sys->n, rc;
  char keep[DAL_ERRMSG_LEN];
  memcpy(keep, st->err, sizeof keep);
  dal__ode_to_state(ig, t, y);
  rc = dal__eval(ig->sys, st, DAL_P_ALL);
  if (!rc) rc = dal__tangent_eval(ig->sys, st, m->tg, 0);
  if (!rc) rc = dal__tangent_factor(ig->sys, st, m->tg);
  if (rc) {
    memcpy(st->err, keep, sizeof keep);
    return rc;
  }
  dal__tangent_flow(m->tg, m->Af, NULL);
  for (int j = 0; j < 2 * n; ++j)
    memcpy(SUNDenseMatrix_Column(J, j), m->Af + (size_t)j * 2 * n, 2 * (size_t)n * sizeof(double));
  return DAL_OK;
}

static int cv_jac(realtype t, N_Vector y, N_Vector fy, SUNMatrix J, void *ud, N_Vector tmp1,
                  N_Vector tmp2, N_Vector tmp3) {
  (void)tmp3;
  dal_ode_integ *ig = ud;
  cv_mem *m = ig->impl;
  if (m->tg && cv_jac_exact(ig, m, t, N_VGetArrayPointer(y), J) == DAL_OK) return 0;
  int n = ig->ny;
  double h = 0, *yp = N_VGetArrayPointer(tmp2), *fp = N_VGetArrayPointer(tmp1);
  const double *y0 = N_VGetArrayPointer(y), *f0 = N_VGetArrayPointer(fy);
  const double *w = N_VGetArrayPointer(m->v.ewt);
  CVodeGetCurrentStep(m->cv, &h);
  CVodeGetErrWeights(m->cv, m->v.ewt);
  double fnorm = 0, uround = DBL_EPSILON, srur = sqrt(uround);
  for (int i = 0; i < n; ++i)
    fnorm += (f0[i] * w[i]) * (f0[i] * w[i]);
  fnorm = sqrt(fnorm / n);
  double min_inc = fnorm != 0 ? 1000.0 * fabs(h) * uround * n * fnorm : 1.0;
  memcpy(yp, y0, (size_t)n * sizeof(double));
  for (int j = 0; j < n; ++j) {
    double inc = fmax(srur * fabs(y0[j]), min_inc / w[j]);
    yp[j] = y0[j] + inc;
    int rc = dal__ode_rhs(ig, t, yp, fp);
    yp[j] = y0[j];
    if (rc) return rc;
    double *col = SUNDenseMatrix_Column(J, j);
    for (int i = 0; i < n; ++i)
      col[i] = (fp[i] - f0[i]) / inc;
  }
  return 0;
}

static void cv_free(void *p) {
  cv_mem *m = p;
  if (!m) return;
  if (m->cv) CVodeFree(&m->cv);
  if (m->NLS) SUNNonlinSolFree(m->NLS);
  if (m->LS) SUNLinSolFree(m->LS);
  if (m->A) SUNMatDestroy(m->A);
  dal__sun_vecs_free(&m->v);
  if (m->tg) dal__tangent_free(m->tg);
  free(m->Af);
  if (m->probe) N_VFreeEmpty(m->probe);
  free(m->pout);
  free(m->zc);
  free(m);
}

// add the counters' growth since the last call to the statistics
static void cv_sync_stats(dal_ode_integ *ig, cv_mem *m) {
  long netf = 0, nsf = 0, nje = 0, nni = 0;
  CVodeGetNumErrTestFails(m->cv, &netf);
  CVodeGetNumStepSolveFails(m->cv, &nsf);
  CVodeGetNumNonlinSolvIters(m->cv, &nni);
  if (m->LS) CVodeGetNumJacEvals(m->cv, &nje);
  dal_stats *s = &ig->st->stats;
  s->rejected += (netf - m->netf) + (nsf - m->nsf);
  s->jac_evals += nje - m->nje;
  s->nonlin_iters += nni - m->nni;
  m->netf = netf;
  m->nsf = nsf;
  m->nje = nje;
  m->nni = nni;
}

// restart at the last accepted step (after a projection) with initial step h
static int cv_restart(dal_ode_integ *ig, cv_mem *m, double h) {
  cv_sync_stats(ig, m);
  memcpy(N_VGetArrayPointer(m->v.y), ig->y, (size_t)ig->ny * sizeof(double));
  int flag = CVodeSetInitStep(m->cv, h);
  if (flag == CV_SUCCESS) flag = CVodeReInit(m->cv, ig->t, m->v.y);
  m->netf = m->nsf = m->nje = m->nni = 0;
  m->pfast = 0; // new columns
  return flag;
}

// the failure message and status for a CVODE return code
static int cv_failure(dal_ode_integ *ig, cv_mem *m, int flag) {
  char var[128] = "(not estimated)";
  double h = 0;
  CVodeGetCurrentStep(m->cv, &h);
  ig->st->stats.foreign_code = flag;
  // an unrecoverable right-hand side decides, whatever the integrator made of it
  if (ig->rhs_fatal) flag = CV_RHSFUNC_FAIL;
  // dominating variable: the largest weighted local error estimate of the failed try (only
  // after error tests or Newton iterations: before, CVODE's vectors hold no values)
  if (flag == CV_ERR_FAILURE || flag == CV_TOO_MUCH_ACC || flag == CV_CONV_FAILURE) {
    CVodeGetEstLocalErrors(m->cv, m->v.ele);
    CVodeGetErrWeights(m->cv, m->v.ewt);
    const double *e = N_VGetArrayPointer(m->v.ele), *w = N_VGetArrayPointer(m->v.ewt);
    for (int i = 0; i < ig->ny; ++i)
      ig->ewt[i] = e[i] * w[i];
    dal__ode_var_name(ig, dal__ode_argmax(ig->ewt, ig->ny), var, sizeof var);
  }
  const char *name = dal_method_name(ig->method);
  switch (flag) {
  case CV_RHSFUNC_FAIL:
  case CV_FIRST_RHSFUNC_ERR:
  case CV_REPTD_RHSFUNC_ERR:
  case CV_UNREC_RHSFUNC_ERR:
    return dal__ode_rhs_fail(ig);
  case CV_ERR_FAILURE:
  case CV_TOO_MUCH_ACC:
    // a callback that keeps asking for a smaller step, not the solution, stopped us
    if (dal__ode_recov_blocked(ig)) return dal__ode_recov_fail(ig, h);
    return dal__ode_fail(ig, DAL_E_STEP,
                         "step size underflow at t=%.17g (h=%.3g, %s): error dominated by %s; "
                         "the solution may be singular there, or the tolerances too tight: "
                         "loosen rtol/atol or check the model near this time",
                         ig->t, h, name, var);
  case CV_CONV_FAILURE:
    return dal__ode_fail(ig, DAL_E_CONV,
                         "%s iteration failed to converge at t=%.17g (h=%.3g), dominated by "
                         "%s; the problem may be stiff (try DAL_METHOD_BDF) or singular there",
                         name, ig->t, h, var);
  case CV_TOO_MUCH_WORK:
    return dal__ode_fail(ig, DAL_E_MAXSTEPS,
                         "too many steps at t=%.17g before the target t=%.17g; raise "
                         "opts.max_steps or loosen the tolerances",
                         ig->t, ig->tout);
  default:
    return dal__ode_fail(ig, DAL_E_SOLVER, "CVODE (%s) failed at t=%.17g (code %d): %s", name,
                         ig->t, flag, ig->sun_err);
  }
}

// The projection moved the accepted step y (the integrator's) to ig->y by more than the
// requested tolerance (weighted RMS norm with the user's rtol, atol above 1). Only then is
// the integrator re-initialized at the projected point: a restart drops the multistep
// history back to order 1, and re-initializing after every step would keep Adams at order 1
// (measured: a million steps to t = 4e-6 on a Cartesian pendulum). Between restarts the
// reported states are projected and the integrator's own drift stays within the tolerance.
static int cv_moved(const dal_ode_integ *ig, const double *y) {
  double s = 0.0;
  for (int i = 0; i < ig->ny; ++i) {
    double w = (ig->y[i] - y[i]) / (ig->opts.atol + ig->opts.rtol * fabs(ig->y[i]));
    s += w * w;
  }
  return s > ig->ny;
}

// Dense output: CVODE's interpolating polynomial of the last step, the Nordsieck sum
// p(t) = sum_j zn[j] s^j, s = (t - tn) / h, j = 0..q (Hindmarsh et al. 2005, sec. 2.1), read by
// CVodeGetDky(t, 0). A call of the packaged SUNDIALS costs ~800-1300 instructions (its
// coefficient loop runs j iterations per column), more than the rest of an output. The first
// output of a step calls it with the probe vector, whose linear combination copies the columns
// it is handed; every output of the step, that one included, is then the Horner sum of the
// columns in s. An output is thus the same bits whichever call of the step read the columns (a
// run that samples more, a stored trajectory, gives the same outputs). The probed call checks
// the assumed form (q + 1 columns, coefficients the powers of s as CVODE forms them); a mismatch
// (another SUNDIALS) leaves every output to CVodeGetDky.

// the powers s^(n - 1 - i) that CVodeGetDky(t, 0) hands over with n columns zn[n - 1..0], each
// the product of that many factors s from 1
static void cv_powers(const cv_mem *m, double t, int n, double *c) {
  double s = (t - m->ptn) / m->ph, p = 1.0;
  c[n - 1] = p;
  for (int i = n - 2; i >= 0; --i)
    c[i] = p *= s;
}

// p(t) into yout from the step's columns: Horner in s, four (two) components at a time
static void cv_horner(const cv_mem *m, double t, double *yout) {
  double s = (t - m->ptn) / m->ph;
  int n = m->pn, ny = m->ny, i = 0;
  for (; i + 3 < ny; i += 4) {
    const double *z0 = m->zc + (size_t)i * (CV_QMAX + 1), *z1 = z0 + CV_QMAX + 1,
                 *z2 = z1 + CV_QMAX + 1, *z3 = z2 + CV_QMAX + 1;
    double y0 = z0[0], y1 = z1[0], y2 = z2[0], y3 = z3[0];
    for (int j = 1; j < n; ++j) {
      y0 = y0 * s + z0[j];
      y1 = y1 * s + z1[j];
      y2 = y2 * s + z2[j];
      y3 = y3 * s + z3[j];
    }
    yout[i] = y0;
    yout[i + 1] = y1;
    yout[i + 2] = y2;
    yout[i + 3] = y3;
  }
  for (; i + 1 < ny; i += 2) {
    const double *z0 = m->zc + (size_t)i * (CV_QMAX + 1), *z1 = z0 + CV_QMAX + 1;
    double y0 = z0[0], y1 = z1[0];
    for (int j = 1; j < n; ++j) {
      y0 = y0 * s + z0[j];
      y1 = y1 * s + z1[j];
    }
    yout[i] = y0;
    yout[i + 1] = y1;
  }
  if (i < ny) {
    const double *z = m->zc + (size_t)i * (CV_QMAX + 1);
    double y = z[0];
    for (int j = 1; j < n; ++j)
      y = y * s + z[j];
    yout[i] = y;
  }
}

// sum_j c[j] zc[., j] over the n copied columns into out: CVODE's sum (after a mismatch)
static void cv_column_sum(const cv_mem *m, int n, const double *c, double *out) {
  for (int i = 0; i < m->ny; ++i) {
    const double *z = m->zc + (size_t)i * (CV_QMAX + 1);
    double y = 0.0;
    for (int j = 0; j < n; ++j)
      y += c[j] * z[j];
    out[i] = y;
  }
}

// the probe's N_VLinearCombination: copy the columns and coefficients (pn = nvec); when they do
// not fit, sum them into pout (pn = 0)
static int cv_probe_sum(int nvec, realtype *c, N_Vector *x, N_Vector z) {
  cv_mem *m = ((cv_probe_content *)z->content)->m;
  int ny = m->ny, keep = nvec >= 1 && nvec <= CV_QMAX + 1;
  m->pn = 0;
  for (int i = 0; i < ny; ++i)
    m->pout[i] = 0.0;
  for (int j = 0; j < nvec; ++j) {
    // CVODE's columns are serial vectors (clones of y): their data without two calls
    const double *xj = x[j]->ops->nvgetarraypointer == N_VGetArrayPointer_Serial
                           ? NV_DATA_S(x[j])
                           : N_VGetArrayPointer(x[j]);
    if (!xj) return -1;
    if (keep) {
      m->pc[j] = c[j];
      for (int i = 0; i < ny; ++i)
        m->zc[(size_t)i * (CV_QMAX + 1) + j] = xj[i];
    } else {
      for (int i = 0; i < ny; ++i)
        m->pout[i] += c[j] * xj[i];
    }
  }
  if (keep) m->pn = nvec;
  return 0;
}

// CVodeGetDky(t, 0) through the probe into yout; on the step's first call, whether the columns
// it copied serve the step's outputs (then yout is their Horner sum)
static int cv_probe(dal_ode_integ *ig, cv_mem *m, double t, double *yout) {
  m->pn = 0;
  int flag = CVodeGetDky(m->cv, t, 0, m->probe);
  if (flag != CV_SUCCESS)
    return DAL_FAIL(ig->st, DAL_E_SOLVER,
                    "CVODE could not interpolate at t=%.17g in the step [%.17g, %.17g] (code %d)",
                    t, ig->tprev, ig->t, flag);
  if (m->pn == 0) {
    memcpy(yout, m->pout, (size_t)ig->ny * sizeof(double));
    return DAL_OK;
  }
  // the step's tn and h, and the coefficients as the powers of s
  double c[CV_QMAX + 1];
  if (!m->pbroken) {
    CVodeGetCurrentTime(m->cv, &m->ptn);
    CVodeGetLastStep(m->cv, &m->ph);
    if (m->ph != 0) {
      cv_powers(m, t, m->pn, c);
      m->pfast = memcmp(c, m->pc, (size_t)m->pn * sizeof(double)) == 0;
      m->pbroken = !m->pfast;
    }
  }
  if (m->pfast)
    cv_horner(m, t, yout);
  else
    cv_column_sum(m, m->pn, m->pc, yout);
  return DAL_OK;
}

static int cv_interp(dal_ode_integ *ig, double t, double *yout) {
  cv_mem *m = ig->impl;
  if (!(t >= ig->tprev && t <= ig->t))
    return DAL_FAIL(ig->st, DAL_E_ARG,
                    "CVODE's dense output asked at t=%.17g outside the last step [%.17g, %.17g]", t,
                    ig->tprev, ig->t);
  if (!m->pfast) return cv_probe(ig, m, t, yout);
  cv_horner(m, t, yout);
  m->nfast++;
  return DAL_OK;
}

// CVODE steps on (or fails and rescales its columns): the columns probed before are stale
static void cv_new_step(cv_mem *m) { m->pfast = 0; }

void dal__cvode_slow_dense(dal_ode_integ *ig) {
  cv_mem *m = ig->impl;
  m->pbroken = 1;
  m->pfast = 0;
}

long dal__cvode_fast_outputs(const dal_ode_integ *ig) { return ((const cv_mem *)ig->impl)->nfast; }

int dal__cvode_dky(dal_ode_integ *ig, double t, int k, double *out) {
  cv_mem *m = ig->impl;
  int flag = CVodeGetDky(m->cv, t, k, m->v.dky);
  if (flag == CV_SUCCESS)
    memcpy(out, N_VGetArrayPointer(m->v.dky), (size_t)ig->ny * sizeof(double));
  return flag;
}

// Without dense output and projection: CVODE steps on at its own pace (no stop at tout) and
// the state at tout comes from its interpolating polynomial; CVODE's own time may then lie
// beyond tout (m->ahead), and the next call goes on from there. Forcing a step to end at
// every output time (a stop time per call) breaks the multistep history: a loop of
// dal_advance to 986 irregular times over [0, 20] measured 113 x rtol for Adams and 125 x
// for BDF against 12 x and 39 x for one call (tests/test_dense.c).
// one CVODE step toward tout: *tret its time, *flag CVODE's (>= 0) return; 0, or the failure's
// status (cv_failure: a right-hand side that failed fatally, a collapsed step, CVODE's error)
static int cv_one_step(dal_ode_integ *ig, cv_mem *m, double tout, realtype *tret, int *flag) {
  ig->rhs_rc = 0;
  cv_new_step(m);
  *flag = CVode(m->cv, tout, m->v.y, tret, CV_ONE_STEP);
  cv_sync_stats(ig, m);
  if (*flag >= 0 && ig->rhs_fatal) *flag = CV_RHSFUNC_FAIL;
  if (*flag >= 0 && dal__ode_collapsed(ig, *tret)) *flag = CV_ERR_FAILURE;
  if (*flag < 0) return cv_failure(ig, m, *flag);
  ig->st->stats.foreign_code = *flag;
  return 0;
}

static int cv_advance_ahead(dal_ode_integ *ig, cv_mem *m, double tout) {
  int flag;
  if (!m->ahead && (flag = CVodeSetStopTime(m->cv, DBL_MAX)) != CV_SUCCESS)
    return cv_failure(ig, m, flag);
  m->ahead = 1;
  double tn = ig->t;
  CVodeGetCurrentTime(m->cv, &tn);
  while (tn < tout) {
    realtype tret = ig->t;
    int rc0 = cv_one_step(ig, m, tout, &tret, &flag);
    if (rc0) return rc0;
    int rc = dal__ode_accept(ig, tret, N_VGetArrayPointer(m->v.y), NULL);
    if (rc) return rc;
    tn = tret;
  }
  // the state at tout from the last step's polynomial
  flag = CVodeGetDky(m->cv, tout, 0, m->v.dky);
  if (flag != CV_SUCCESS) return cv_failure(ig, m, flag);
  memcpy(ig->y, N_VGetArrayPointer(m->v.dky), (size_t)ig->ny * sizeof(double));
  ig->tprev = ig->t = tout;
  return DAL_OK;
}

static int cv_advance(dal_ode_integ *ig, double tout) {
  cv_mem *m = ig->impl;
  if (!ig->hook && !(ig->prob->project && ig->opts.project)) return cv_advance_ahead(ig, m, tout);
  int flag0;
  if (m->ahead) {
    // CVODE is beyond the state (a call without dense output went ahead): restart at it
    double h = 0;
    CVodeGetCurrentStep(m->cv, &h);
    if ((flag0 = cv_restart(ig, m, h)) != CV_SUCCESS) return cv_failure(ig, m, flag0);
    m->ahead = 0;
  }
  int flag = CVodeSetStopTime(m->cv, tout);
  if (flag != CV_SUCCESS) return cv_failure(ig, m, flag);
  while (ig->t < tout) {
    realtype tret = ig->t;
    int rc0 = cv_one_step(ig, m, tout, &tret, &flag);
    if (rc0) return rc0;
    realtype hlast = 0, tn = tret;
    CVodeGetLastStep(m->cv, &hlast);
    CVodeGetCurrentTime(m->cv, &tn);
    int gap = dal__ode_step_gap(ig, tret, tn, hlast, flag == CV_TSTOP_RETURN, tout);
    if (gap) return gap;
    if (flag == CV_TSTOP_RETURN) tret = tout;
    if (tret > tout) return cv_failure(ig, m, CV_BAD_T);
    int projected = 0;
    int rc = dal__ode_accept(ig, tret, N_VGetArrayPointer(m->v.y), &projected);
    if (rc) return rc;
    if (projected && ig->t < tout && cv_moved(ig, N_VGetArrayPointer(m->v.y))) {
      double h = 0;
      CVodeGetCurrentStep(m->cv, &h);
      if ((flag = cv_restart(ig, m, h)) != CV_SUCCESS) return cv_failure(ig, m, flag);
      if ((flag = CVodeSetStopTime(m->cv, tout)) != CV_SUCCESS) return cv_failure(ig, m, flag);
    }
  }
  return DAL_OK;
}

static const dal_sun_setters setters = {CVodeSStolerances, CVodeSetInitStep, CVodeSetMinStep,
                                        CVodeSetMaxStep};

static const dal_ode_ops cv_ops = {cv_advance, cv_free, cv_interp, NULL, NULL};

int dal__cvode_create(dal_ode_integ *ig) {
  dal_state *st = ig->st;
  const dal_solve_opts *o = &ig->opts;
  int bdf = ig->method == DAL_METHOD_BDF;
  cv_mem *m = calloc(1, sizeof *m);
  if (!m) return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the CVODE integrator");
  ig->impl = m;
  ig->ops = &cv_ops;
  int flag = dal__sun_vecs_create(ig, &m->v, "CVODE");
  if (flag) return flag;
  // the dense output's probe: a serial vector on pout (the operations of y) whose linear
  // combination keeps the columns
  m->ny = ig->ny;
  m->pout = malloc((size_t)ig->ny * sizeof(double));
  m->zc = malloc((CV_QMAX + 1) * (size_t)ig->ny * sizeof(double));
  m->probe = m->pout && m->zc ? N_VNewEmpty(m->v.ctx) : NULL;
  if (!m->probe || N_VCopyOps(m->v.y, m->probe) != 0)
    return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the CVODE integrator");
  m->pcontent.serial.length = ig->ny;
  m->pcontent.serial.own_data = SUNFALSE;
  m->pcontent.serial.data = m->pout;
  m->pcontent.m = m;
  m->probe->content = &m->pcontent;
  m->probe->ops->nvlinearcombination = cv_probe_sum;
  m->cv = CVodeCreate(bdf ? CV_BDF : CV_ADAMS, m->v.ctx);
  if (!m->cv) return DAL_FAIL(st, DAL_E_NOMEM, "CVodeCreate failed");
  flag = CVodeSetErrHandlerFn(m->cv, dal__ode_sun_err, ig);
  if (!flag) flag = CVodeInit(m->cv, cv_rhs, ig->t, m->v.y);
  if (!flag) flag = CVodeSetUserData(m->cv, ig);
  if (!flag && bdf) {
    // Newton iteration on a dense difference-quotient Jacobian
    m->A = SUNDenseMatrix(ig->ny, ig->ny, m->v.ctx);
    m->LS = m->A ? SUNLinSol_Dense(m->v.y, m->A, m->v.ctx) : NULL;
    flag = m->LS ? CVodeSetLinearSolver(m->cv, m->LS, m->A) : CV_MEM_FAIL;
    if (!flag) flag = CVodeSetJacFn(m->cv, cv_jac);
    // the exact Newton matrix where the jets give it: minimal coordinates, no force callbacks
    // (plain doubles have no derivative), no work component; otherwise difference quotients
    char keep[DAL_ERRMSG_LEN];
    memcpy(keep, st->err, sizeof keep);
    if (!flag && ig->prob == &dal__problem_minimal && !o->work &&
        dal__tangent_supported(ig->sys, st, "bdf") == DAL_OK) {
      m->Af = calloc(4 * (size_t)ig->sys->n * (size_t)ig->sys->n + 1, sizeof(double));
      if (!m->Af || dal__tangent_create(ig->sys, &m->tg) != DAL_OK) flag = CV_MEM_FAIL;
    }
    memcpy(st->err, keep, sizeof keep);
    if (!flag && m->tg) flag = CVodeSetNonlinConvCoef(m->cv, NLS_COEF);
  } else if (!flag) {
    // functional (fixed-point) iteration, no Jacobian
    m->NLS = SUNNonlinSol_FixedPoint(m->v.y, 0, m->v.ctx);
    flag = m->NLS ? CVodeSetNonlinearSolver(m->cv, m->NLS) : CV_MEM_FAIL;
  }
  // the local tolerances and step bounds
  if (!flag) flag = dal__sun_set_tols(m->cv, &setters, ig);
  if (flag)
    return flag == CV_MEM_FAIL
               ? DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the CVODE integrator")
               : DAL_FAIL(st, DAL_E_SOLVER, "CVODE setup failed (code %d): %s", flag, ig->sun_err);
  return DAL_OK;
}
