// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Explicit adaptive Runge-Kutta through SUNDIALS ARKODE ERKStep: Dormand-Prince 5(4) and
// Fehlberg 7(8) (tables ARKODE_DORMAND_PRINCE_7_4_5 and ARKODE_FEHLBERG_13_7_8 made FSAL;
// Hairer-Norsett-Wanner, Solving ODEs I, sec. II.5 and II.10). One internal step per call, so
// the driver keeps every accepted step and can project or restart there.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <arkode/arkode_butcher_erk.h>
#include <arkode/arkode_erkstep.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include "integrate.h"
#include "nvec.h"

/// consecutive recoverable right-hand-side failures tolerated before giving up
#define ERK_MAX_RECOVER 30
/// accepted points before a step that Fehlberg 7(8)'s dense output interpolates through
#define FEHL_HIST 5

typedef struct erk_mem {
  void *ark;
  dal_sun_vecs v;        // context and vectors
  ARKodeButcherTable fb; // Fehlberg 7(8): its table for the dense output's partial steps
  double *K, *yk;        // its stages (stages x ny) and stage argument (ny)
  // Fehlberg 7(8)'s dense output (fehlberg_interp): the last FEHL_HIST accepted points of
  // the run with their slopes, oldest first, and the interpolant of the current step
  int nh;                      // points held
  double ht[FEHL_HIST];        // their times
  double *hy, *hf;             // their y and f (FEHL_HIST x ny each)
  int nz;                      // nodes of the current step's interpolant
  double zt[FEHL_HIST + 1];    // their times
  double *zy, *zf;             // their y and f ((FEHL_HIST + 1) x ny each)
  double *cf, *cf7;            // its Newton coefficients, and those of the check
  double ct0, ct1;             // the step it was built for
  long n_hist, n_mid, n_inner; // steps served by each of fehlberg_build's interpolants
  long nfe_base, netf_base;    // counters already added to the state's statistics
  // the last right-hand side ARKODE asked for in a run with an after-step hook: its time and
  // vectors (borrowed from ARKODE)
  double last_t;
  const double *last_y, *last_f;
} erk_mem;

static int erk_rhs(realtype t, N_Vector y, N_Vector ydot, void *ud) {
  dal_ode_integ *ig = ud;
  double *yv = N_VGetArrayPointer(y), *f = N_VGetArrayPointer(ydot);
  if (ig->hook) {
    // kept for erk_end_slope (the dense output)
    erk_mem *m = ig->impl;
    m->last_t = t;
    m->last_y = yv;
    m->last_f = f;
  }
  return dal__ode_rhs(ig, t, yv, f);
}

static void erk_free(void *p) {
  erk_mem *m = p;
  if (!m) return;
  if (m->ark) ERKStepFree(&m->ark);
  if (m->fb) ARKodeButcherTable_Free(m->fb);
  free(m->K);
  free(m->yk);
  free(m->hy);
  free(m->hf);
  free(m->zy);
  free(m->zf);
  free(m->cf);
  free(m->cf7);
  dal__sun_vecs_free(&m->v);
  free(m);
}

// add the error-test failures since the last call to the statistics
static void erk_sync_stats(dal_ode_integ *ig, erk_mem *m) {
  long netf = 0;
  ERKStepGetNumErrTestFails(m->ark, &netf);
  ig->st->stats.rejected += netf - m->netf_base;
  m->netf_base = netf;
}

// restart the integrator at the last accepted step with initial step h (0: estimate)
static int erk_restart(dal_ode_integ *ig, erk_mem *m, double h) {
  erk_sync_stats(ig, m);
  memcpy(N_VGetArrayPointer(m->v.y), ig->y, (size_t)ig->ny * sizeof(double));
  int flag = ERKStepSetInitStep(m->ark, h);
  if (flag == ARK_SUCCESS) flag = ERKStepReset(m->ark, ig->t, m->v.y);
  // a reset forgets the stop time
  if (flag == ARK_SUCCESS) flag = ERKStepSetStopTime(m->ark, ig->tout);
  m->netf_base = 0;
  ERKStepGetNumErrTestFails(m->ark, &m->netf_base);
  return flag;
}

// the failure message and status for an ARKODE return code
static int erk_failure(dal_ode_integ *ig, erk_mem *m, int flag) {
  char var[128];
  double h = 0;
  ERKStepGetCurrentStep(m->ark, &h);
  ig->st->stats.foreign_code = flag;
  // an unrecoverable right-hand side decides, whatever the integrator made of it
  if (ig->rhs_fatal) flag = ARK_RHSFUNC_FAIL;
  switch (flag) {
  case ARK_RHSFUNC_FAIL:
  case ARK_FIRST_RHSFUNC_ERR:
  case ARK_REPTD_RHSFUNC_ERR:
  case ARK_UNREC_RHSFUNC_ERR:
    return dal__ode_rhs_fail(ig);
  case ARK_ERR_FAILURE:
  case ARK_TOO_MUCH_ACC: {
    // a callback that keeps asking for a smaller step, not the solution, stopped us
    if (dal__ode_recov_blocked(ig)) return dal__ode_recov_fail(ig, h);
    // dominating variable: the largest weighted local error estimate of the failed try
    ERKStepGetEstLocalErrors(m->ark, m->v.ele);
    ERKStepGetErrWeights(m->ark, m->v.ewt);
    const double *e = N_VGetArrayPointer(m->v.ele), *w = N_VGetArrayPointer(m->v.ewt);
    for (int i = 0; i < ig->ny; ++i)
      ig->ewt[i] = e[i] * w[i];
    int i = dal__ode_argmax(ig->ewt, ig->ny);
    return dal__ode_fail(ig, DAL_E_STEP,
                         "step size underflow at t=%.17g (h=%.3g, %s): error dominated by %s; "
                         "the solution may be singular there, or the tolerances too tight: "
                         "loosen rtol/atol or check the model near this time",
                         ig->t, h, dal_method_name(ig->method),
                         dal__ode_var_name(ig, i, var, sizeof var));
  }
  case ARK_TOO_MUCH_WORK:
    return dal__ode_fail(ig, DAL_E_MAXSTEPS,
                         "too many steps at t=%.17g before the target t=%.17g; raise "
                         "opts.max_steps or loosen the tolerances",
                         ig->t, ig->tout);
  case ARK_CONV_FAILURE:
    return dal__ode_fail(ig, DAL_E_CONV, "convergence failure at t=%.17g: %s", ig->t, ig->sun_err);
  default:
    return dal__ode_fail(ig, DAL_E_SOLVER, "ARKODE failed at t=%.17g (code %d): %s", ig->t, flag,
                         ig->sun_err);
  }
}

// Fehlberg 7(8) with an appended first-same-as-last stage. ARKODE 6.4.1 reuses the last
// stage's f as the next step's first stage whenever the last node c_s is 1; Fehlberg's 13th
// stage has c = 1 but is not y_{n+1}, so the stock ARKODE_FEHLBERG_13_7_8 table converges at
// order 7 instead of 8 (measured: error ratio 128, not 256, per halving on the pendulum). The
// extra stage Y_14 = y_n + h sum_j b_j k_j = y_{n+1} (c = 1, weight 0) makes the reuse exact:
// still 13 evaluations per step, order 8 propagated, order-7 embedding for the error estimate.
// The coefficients are ARKODE's own (Fehlberg, NASA TR R-287, 1968).
static int erk_set_fehlberg(void *ark) {
  ARKodeButcherTable F = ARKodeButcherTable_LoadERK(ARKODE_FEHLBERG_13_7_8);
  if (!F) return ARK_MEM_FAIL;
  int s = F->stages;
  ARKodeButcherTable G = ARKodeButcherTable_Alloc(s + 1, SUNTRUE);
  if (!G) {
    ARKodeButcherTable_Free(F);
    return ARK_MEM_FAIL;
  }
  for (int i = 0; i < s; ++i) {
    G->c[i] = F->c[i];
    G->b[i] = F->b[i];
    G->d[i] = F->d[i];
    for (int j = 0; j < s; ++j)
      G->A[i][j] = F->A[i][j];
  }
  for (int j = 0; j < s; ++j)
    G->A[s][j] = F->b[j];
  G->c[s] = 1.0;
  G->b[s] = G->d[s] = 0.0;
  G->q = F->q;
  G->p = F->p;
  int flag = ERKStepSetTable(ark, G);
  ARKodeButcherTable_Free(G);
  ARKodeButcherTable_Free(F);
  return flag;
}

// DOPRI5's slope at the end of the step: its last stage (first same as last), which ARKODE's
// interpolation module keeps; the driver's cubic Hermite (ode.c) is its dense output
static int erk_end_slope(dal_ode_integ *ig, double *f) {
  erk_mem *m = ig->impl;
  size_t bytes = (size_t)ig->ny * sizeof(double);
  // DOPRI5's last stage is evaluated at the step's end (its last row of A is b): when that
  // was ARKODE's last call and succeeded, its slope is the one the interpolation module keeps
  if (ig->method == DAL_METHOD_DOPRI5 && m->last_f && m->last_t == ig->t && ig->rhs_rc == 0 &&
      memcmp(m->last_y, ig->y, bytes) == 0) {
    memcpy(f, m->last_f, bytes);
    return DAL_OK;
  }
  int flag = ERKStepGetDky(m->ark, ig->t, 1, m->v.dky);
  if (flag != ARK_SUCCESS)
    return DAL_FAIL(ig->st, DAL_E_SOLVER, "ARKODE could not give the slope at t=%.17g (code %d)",
                    ig->t, flag);
  memcpy(f, N_VGetArrayPointer(m->v.dky), bytes);
  return DAL_OK;
}

// y at tprev + tau of Fehlberg 7(8)'s step from (tprev, yprev): one step of the method
// itself of length tau (order 8 like the step), its first stage the step's start slope hf0
static int fehlberg_partial(dal_ode_integ *ig, double tau, double *yout) {
  erk_mem *m = ig->impl;
  ARKodeButcherTable F = m->fb;
  int ny = ig->ny, s = F->stages;
  memcpy(m->K, ig->hf0, (size_t)ny * sizeof(double));
  for (int i = 1; i < s; ++i) {
    for (int k = 0; k < ny; ++k) {
      double a = 0.0;
      for (int j = 0; j < i; ++j)
        a += F->A[i][j] * m->K[(size_t)j * ny + k];
      m->yk[k] = ig->yprev[k] + tau * a;
    }
    int rc = dal__ode_eval(ig, ig->tprev + F->c[i] * tau, m->yk, m->K + (size_t)i * ny, DAL_P_ACC);
    if (rc) return dal__public_status(rc);
    ig->st->stats.rhs_evals++;
  }
  for (int k = 0; k < ny; ++k) {
    double a = 0.0;
    for (int j = 0; j < s; ++j)
      a += F->b[j] * m->K[(size_t)j * ny + k];
    yout[k] = ig->yprev[k] + tau * a;
  }
  return DAL_OK;
}

// Newton coefficients of the Hermite interpolant through nz nodes zt with values y (node x
// ny) and slopes f: divided differences on the doubled nodes z_0, z_0, z_1, z_1, ... (2 nz
// per component, component after component)
static void hermite_newton(int ny, int nz, const double *zt, const double *y, const double *f,
                           double *cf) {
  double d[2 * (FEHL_HIST + 1)];
  int Z = 2 * nz;
  for (int k = 0; k < ny; ++k) {
    for (int i = 0; i < Z; ++i)
      d[i] = y[(size_t)(i / 2) * ny + k];
    // order 1: the slope at a doubled node, else the difference quotient
    for (int i = Z - 1; i >= 1; --i)
      d[i] =
          (i & 1) ? f[(size_t)(i / 2) * ny + k] : (d[i] - d[i - 1]) / (zt[i / 2] - zt[(i - 1) / 2]);
    for (int o = 2; o < Z; ++o)
      for (int i = Z - 1; i >= o; --i)
        d[i] = (d[i] - d[i - 1]) / (zt[i / 2] - zt[(i - o) / 2]);
    // coefficient i of every component together (cf[i ny + k]): hermite_eval reads each
    // t - zt once for a block of components
    for (int i = 0; i < Z; ++i)
      cf[(size_t)i * ny + k] = d[i];
  }
}

// the Newton form (hermite_newton) at t into yout: the nested form over the doubled nodes,
// two coefficients per node, four (two) components at a time (their sums in registers, each
// t - zt read once for the four; each component's operations are those of a one-component
// loop, so the result does not depend on the blocking)
static void hermite_eval(int ny, int nz, const double *zt, const double *cf, double t,
                         double *yout) {
  double dz[FEHL_HIST + 1];
  for (int i = 0; i < nz; ++i)
    dz[i] = t - zt[i];
  size_t top = (size_t)(2 * nz - 1) * (size_t)ny;
  int k = 0;
  for (; k + 4 <= ny; k += 4) {
    const double *c = cf + top + k;
    double p0 = c[0], p1 = c[1], p2 = c[2], p3 = c[3];
    for (int i = nz - 1; i > 0; --i) {
      const double *c2 = c - ny, *c1 = c2 - ny, a = dz[i], b = dz[i - 1];
      p0 = (p0 * a + c2[0]) * b + c1[0];
      p1 = (p1 * a + c2[1]) * b + c1[1];
      p2 = (p2 * a + c2[2]) * b + c1[2];
      p3 = (p3 * a + c2[3]) * b + c1[3];
      c = c1;
    }
    yout[k] = p0 * dz[0] + cf[k];
    yout[k + 1] = p1 * dz[0] + cf[k + 1];
    yout[k + 2] = p2 * dz[0] + cf[k + 2];
    yout[k + 3] = p3 * dz[0] + cf[k + 3];
  }
  for (; k + 2 <= ny; k += 2) {
    const double *c = cf + top + k;
    double p0 = c[0], p1 = c[1];
    for (int i = nz - 1; i > 0; --i) {
      const double *c2 = c - ny, *c1 = c2 - ny, a = dz[i], b = dz[i - 1];
      p0 = (p0 * a + c2[0]) * b + c1[0];
      p1 = (p1 * a + c2[1]) * b + c1[1];
      c = c1;
    }
    yout[k] = p0 * dz[0] + cf[k];
    yout[k + 1] = p1 * dz[0] + cf[k + 1];
  }
  for (; k < ny; ++k) {
    const double *c = cf + top + k;
    double p = c[0];
    for (int i = nz - 1; i > 0; --i) {
      const double *c2 = c - ny, *c1 = c2 - ny;
      p = (p * dz[i] + c2[0]) * dz[i - 1] + c1[0];
      c = c1;
    }
    yout[k] = p * dz[0] + cf[k];
  }
}

// the interpolant through the nz nodes in zt, zy, zf into cf; with check, the largest
// difference at the quarter points of the step to the one without the oldest node, in units
// of the requested tolerance (the error control runs at tol_factor of it)
static double fehlberg_fit(dal_ode_integ *ig, int nz, int check) {
  erk_mem *m = ig->impl;
  int ny = ig->ny;
  m->nz = nz;
  hermite_newton(ny, nz, m->zt, m->zy, m->zf, m->cf);
  if (!check) return 0.0;
  hermite_newton(ny, nz - 1, m->zt + 1, m->zy + ny, m->zf + ny, m->cf7);
  double c = 1.0 / dal__tol_factor(ig->method), h = ig->t - ig->tprev, worst = 0.0;
  double *a = m->yk, *b = m->K;
  for (int q = 1; q <= 3; ++q) {
    double t = ig->tprev + 0.25 * q * h;
    hermite_eval(ny, nz, m->zt, m->cf, t, a);
    hermite_eval(ny, nz - 1, m->zt + 1, m->cf7, t, b);
    for (int k = 0; k < ny; ++k)
      worst = fmax(worst, fabs(a[k] - b[k]) / (c * (ig->atol + ig->rtol * fabs(a[k]))));
  }
  return worst;
}

// node i of the step's interpolant: the record's point r, or y and f at tprev + theta h (an
// inner point: a partial step of the method and one right-hand side, 13 in all)
static void fehlberg_node_rec(dal_ode_integ *ig, int i, int r) {
  erk_mem *m = ig->impl;
  size_t ny = (size_t)ig->ny;
  m->zt[i] = m->ht[r];
  memcpy(m->zy + i * ny, m->hy + r * ny, ny * sizeof(double));
  memcpy(m->zf + i * ny, m->hf + r * ny, ny * sizeof(double));
}
static int fehlberg_node_inner(dal_ode_integ *ig, int i, double theta) {
  erk_mem *m = ig->impl;
  size_t ny = (size_t)ig->ny;
  double tau = theta * (ig->t - ig->tprev), *yi = m->zy + i * ny, *fi = m->zf + i * ny;
  int rc = dal__ode_start_slope(ig);
  if (!rc) rc = fehlberg_partial(ig, tau, yi);
  if (rc) return rc;
  if ((rc = dal__ode_eval(ig, ig->tprev + tau, yi, fi, DAL_P_ACC)) != 0)
    return dal__public_status(rc);
  ig->st->stats.rhs_evals++;
  m->zt[i] = ig->tprev + tau;
  return DAL_OK;
}
static void fehlberg_node_end(dal_ode_integ *ig, int i) {
  erk_mem *m = ig->impl;
  size_t ny = (size_t)ig->ny;
  m->zt[i] = ig->t;
  memcpy(m->zy + i * ny, ig->y, ny * sizeof(double));
  memcpy(m->zf + i * ny, ig->hf1, ny * sizeof(double));
}

// The step's interpolant, the cheapest that passes its check (its difference to the one
// without its oldest node within the requested tolerance): (1) through the FEHL_HIST accepted
// points before the step and its end (degree 9, no right-hand side); (2) through the newest
// three of them, the step's midpoint and its end (degree 9, 13 right-hand sides); else (3)
// through the step's start, two inner points and its end (degree 7, 13 or 26 right-hand
// sides). A start or a gap in the record goes to (3) at once.
static int fehlberg_build(dal_ode_integ *ig) {
  erk_mem *m = ig->impl;
  int rc = dal__ode_end_slope(ig), nh = m->nh, mid = 0;
  if (rc) return rc;
  int rec = nh > 0 && m->ht[nh - 1] == ig->tprev;
  if (rec && nh == FEHL_HIST) {
    for (int i = 0; i < FEHL_HIST; ++i)
      fehlberg_node_rec(ig, i, i);
    fehlberg_node_end(ig, FEHL_HIST);
    if (fehlberg_fit(ig, FEHL_HIST + 1, 1) <= 1.0) {
      m->n_hist++;
      goto done;
    }
  }
  if (rec && nh >= 3) {
    for (int i = 0; i < 3; ++i)
      fehlberg_node_rec(ig, i, nh - 3 + i);
    if ((rc = fehlberg_node_inner(ig, 3, 0.5)) != 0) return rc;
    fehlberg_node_end(ig, 4);
    mid = 1;
    if (fehlberg_fit(ig, 5, 1) <= 1.0) {
      m->n_mid++;
      goto done;
    }
  }
  // (3): the midpoint already computed moves to node 2 (nodes 0, 1/4, 1/2, 1), else 1/3, 2/3
  size_t ny = (size_t)ig->ny;
  if (mid) {
    m->zt[2] = m->zt[3];
    memcpy(m->zy + 2 * ny, m->zy + 3 * ny, ny * sizeof(double));
    memcpy(m->zf + 2 * ny, m->zf + 3 * ny, ny * sizeof(double));
  } else if ((rc = fehlberg_node_inner(ig, 2, 2.0 / 3.0)) != 0) {
    return rc;
  }
  if ((rc = fehlberg_node_inner(ig, 1, mid ? 0.25 : 1.0 / 3.0)) != 0) return rc;
  m->zt[0] = ig->tprev;
  memcpy(m->zy, ig->yprev, ny * sizeof(double));
  memcpy(m->zf, ig->hf0, ny * sizeof(double));
  fehlberg_node_end(ig, 3);
  fehlberg_fit(ig, 4, 0);
  m->n_inner++;
done:
  m->ct0 = ig->tprev;
  m->ct1 = ig->t;
  return DAL_OK;
}

// Dense output of Fehlberg 7(8), built once per step, then 2 nz multiply-adds per component
// and output: the Hermite interpolant through y and f at the step's end and the FEHL_HIST
// accepted points before it (Hairer-Norsett-Wanner I, sec. II.6; no right-hand side beyond the
// slope at each step's end, the method's own last stage), where it passes its check, else
// through two inner points of the step by partial steps. Before: one partial step per output
// (12 right-hand sides each: 12-68x a plain advance at outputs every 0.001).
static int fehlberg_interp(dal_ode_integ *ig, double t, double *yout) {
  erk_mem *m = ig->impl;
  if (m->ct0 != ig->tprev || m->ct1 != ig->t) {
    int rc = fehlberg_build(ig);
    if (rc) {
      m->ct0 = m->ct1 = NAN;
      return rc;
    }
  }
  hermite_eval(ig->ny, m->nz, m->zt, m->cf, t, yout);
  return DAL_OK;
}

// after an accepted step with a hook: the step's end (y, f) joins the record of the run that
// Fehlberg's dense output interpolates through; a record that does not end at the step's
// start (the first step, or steps taken without a hook) starts again
static int fehlberg_record(dal_ode_integ *ig) {
  erk_mem *m = ig->impl;
  int ny = ig->ny, rc = dal__ode_end_slope(ig);
  if (rc) return rc;
  size_t bytes = (size_t)ny * sizeof(double);
  if (m->nh == 0 || m->ht[m->nh - 1] != ig->tprev) {
    m->nh = 0;
    if (ig->hvalid & 1) {
      m->ht[0] = ig->tprev;
      memcpy(m->hy, ig->yprev, bytes);
      memcpy(m->hf, ig->hf0, bytes);
      m->nh = 1;
    }
  }
  if (m->nh == FEHL_HIST) {
    memmove(m->hy, m->hy + ny, (size_t)(FEHL_HIST - 1) * bytes);
    memmove(m->hf, m->hf + ny, (size_t)(FEHL_HIST - 1) * bytes);
    memmove(m->ht, m->ht + 1, (size_t)(FEHL_HIST - 1) * sizeof(double));
    m->nh--;
  }
  m->ht[m->nh] = ig->t;
  memcpy(m->hy + (size_t)m->nh * ny, ig->y, bytes);
  memcpy(m->hf + (size_t)m->nh * ny, ig->hf1, bytes);
  m->nh++;
  return DAL_OK;
}

static int erk_advance(dal_ode_integ *ig, double tout) {
  erk_mem *m = ig->impl;
  int recover = 0, flag = ERKStepSetStopTime(m->ark, tout);
  if (flag != ARK_SUCCESS) return erk_failure(ig, m, flag);
  while (ig->t < tout) {
    realtype tret = ig->t;
    ig->rhs_rc = 0;
    flag = ERKStepEvolve(m->ark, tout, m->v.y, &tret, ARK_ONE_STEP);
    erk_sync_stats(ig, m);
    if (flag >= 0 && ig->rhs_fatal) flag = ARK_RHSFUNC_FAIL;
    if (flag >= 0 && dal__ode_collapsed(ig, tret)) flag = ARK_ERR_FAILURE;
    if (flag < 0) {
      // ERKStep treats any right-hand-side failure as final: a recoverable one restarts
      // here from the last accepted step with a quarter of the step that failed
      if (!ig->rhs_fatal && dal__is_retry(ig->rhs_rc) && recover < ERK_MAX_RECOVER) {
        double h = 0;
        ERKStepGetCurrentStep(m->ark, &h);
        if (!(h > 0)) h = ig->st->stats.last_h;
        ig->st->stats.rejected++;
        ++recover;
        flag = erk_restart(ig, m, h > 0 ? 0.25 * h : 0.0);
        if (flag == ARK_SUCCESS) continue;
      }
      return erk_failure(ig, m, flag);
    }
    recover = 0;
    ig->st->stats.foreign_code = flag;
    // a step that reached the stop time within rounding lands exactly on tout
    realtype hlast = 0, tn = tret;
    ERKStepGetLastStep(m->ark, &hlast);
    ERKStepGetCurrentTime(m->ark, &tn);
    int gap = dal__ode_step_gap(ig, tret, tn, hlast, flag == ARK_TSTOP_RETURN, tout);
    if (gap) return gap;
    if (flag == ARK_TSTOP_RETURN) tret = tout;
    if (tret > tout) return erk_failure(ig, m, ARK_BAD_T);
    int projected = 0;
    int rc = dal__ode_accept(ig, tret, N_VGetArrayPointer(m->v.y), &projected);
    if (!rc && ig->hook && m->fb) rc = fehlberg_record(ig);
    if (rc) return rc;
    if (projected && ig->t < tout) {
      double h = 0;
      ERKStepGetCurrentStep(m->ark, &h); // the step proposed next, not the one taken
      if ((flag = erk_restart(ig, m, h)) != ARK_SUCCESS) return erk_failure(ig, m, flag);
    }
  }
  return DAL_OK;
}

static const dal_sun_setters setters = {ERKStepSStolerances, ERKStepSetInitStep, ERKStepSetMinStep,
                                        ERKStepSetMaxStep};

// DOPRI5 with the Hermite interpolant of its stored slopes; Fehlberg 7(8) with its own
static const dal_ode_ops dopri5_ops = {erk_advance, erk_free, NULL, erk_end_slope, NULL};
static const dal_ode_ops fehlberg_ops = {erk_advance, erk_free, fehlberg_interp, erk_end_slope,
                                         NULL};

int dal__erk_create(dal_ode_integ *ig) {
  dal_state *st = ig->st;
  const dal_solve_opts *o = &ig->opts;
  erk_mem *m = calloc(1, sizeof *m);
  if (!m) return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the ERK integrator");
  ig->impl = m;
  ig->ops = ig->method == DAL_METHOD_FEHLBERG78 ? &fehlberg_ops : &dopri5_ops;
  int flag = dal__sun_vecs_create(ig, &m->v, "ERK");
  if (flag) return flag;
  m->ark = ERKStepCreate(erk_rhs, ig->t, m->v.y, m->v.ctx);
  if (!m->ark) return DAL_FAIL(st, DAL_E_NOMEM, "ERKStepCreate failed");
  flag = ERKStepSetErrHandlerFn(m->ark, dal__ode_sun_err, ig);
  if (!flag) flag = ERKStepSetUserData(m->ark, ig);
  if (!flag && ig->method == DAL_METHOD_FEHLBERG78) {
    flag = erk_set_fehlberg(m->ark);
    m->fb = ARKodeButcherTable_LoadERK(ARKODE_FEHLBERG_13_7_8);
    m->K = m->fb ? calloc((size_t)m->fb->stages * (size_t)ig->ny + 1, sizeof(double)) : NULL;
    m->yk = calloc((size_t)ig->ny + 1, sizeof(double));
    size_t nz = FEHL_HIST + 1, ny1 = (size_t)ig->ny + 1;
    m->hy = calloc(nz * ny1, sizeof(double));
    m->hf = calloc(nz * ny1, sizeof(double));
    m->zy = calloc(nz * ny1, sizeof(double));
    m->zf = calloc(nz * ny1, sizeof(double));
    m->cf = calloc(2 * nz * ny1, sizeof(double));
    m->cf7 = calloc(2 * nz * ny1, sizeof(double));
    m->ct0 = m->ct1 = NAN;
    if (!m->K || !m->yk || !m->hy || !m->hf || !m->zy || !m->zf || !m->cf || !m->cf7)
      return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the ERK integrator");
  } else if (!flag)
    flag = ERKStepSetTableNum(m->ark, ARKODE_DORMAND_PRINCE_7_4_5);
  // ARKODE's interpolant serves only the end slope (Hermite of degree 3 keeps the stored f)
  if (!flag) flag = ERKStepSetInterpolantDegree(m->ark, 3);
  if (!flag && o->fixed_erk) flag = ERKStepSetFixedStep(m->ark, o->fixed_step);
  // the local tolerances and step bounds
  if (!flag) flag = dal__sun_set_tols(m->ark, &setters, ig);
  // steps are counted per advance call by the driver; one internal step per ERKStepEvolve
  if (!flag) flag = ERKStepSetMaxNumSteps(m->ark, 0);
  if (flag)
    return DAL_FAIL(st, DAL_E_SOLVER, "ARKODE ERKStep setup failed (code %d): %s", flag,
                    ig->sun_err);
  return DAL_OK;
}
