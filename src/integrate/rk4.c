// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Classical fourth-order Runge-Kutta at the fixed step opts.fixed_step (Kutta 1901; Hairer-
// Norsett-Wanner, Solving ODEs I, sec. II.1, Table 1.2 left). A step whose right-hand side
// asks for a smaller step, or whose result overflows, is redone as two halves, recursively.
// The solution is updated by compensated (Kahan) summation of the increments (Hairer-Norsett-
// Wanner I, sec. II.10, "round-off error"), so that round-off does not accumulate linearly
// over many small steps. The increment is h * (k1 / 6 + k2 / 3 + k3 / 3 + k4 / 6), not
// (h / 6) * (...): a rounded coefficient h / 6 is the same in every step, a systematic bias that
// grows linearly (2.4e-13 after 1e6 steps of 1e-3 on q'' = -q, against 7e-16 without it;
// bench/symplectic.c), and the stages are scaled before the sum so that it cannot overflow
// where the result is representable.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "families.h"
#include "integrate.h"

/// halvings of one step tolerated for recoverable right-hand-side failures
#define RK4_MAX_HALVINGS 20

typedef struct rk4_mem {
  double *k1, *k2, *k3, *k4, *yt, *y1; // ny each
  double *c, *c1; // compensation of ig->y and of the step's result y1 (ny each)
} rk4_mem;

static void rk4_free(void *p) {
  rk4_mem *m = p;
  if (!m) return;
  free(m->k1);
  free(m->k2);
  free(m->k3);
  free(m->k4);
  free(m->yt);
  free(m->y1);
  free(m->c);
  free(m->c1);
  free(m);
}

// one RK4 step of size h from (t, y) into y1; returns 0 or the right-hand side's code
static int rk4_step(dal_ode_integ *ig, rk4_mem *m, double t, const double *y, double h,
                    double *y1) {
  int ny = ig->ny, rc;
  if ((rc = dal__ode_rhs(ig, t, y, m->k1)) != 0) return rc;
  for (int i = 0; i < ny; ++i)
    m->yt[i] = y[i] + 0.5 * h * m->k1[i];
  if ((rc = dal__ode_rhs(ig, t + 0.5 * h, m->yt, m->k2)) != 0) return rc;
  for (int i = 0; i < ny; ++i)
    m->yt[i] = y[i] + 0.5 * h * m->k2[i];
  if ((rc = dal__ode_rhs(ig, t + 0.5 * h, m->yt, m->k3)) != 0) return rc;
  for (int i = 0; i < ny; ++i)
    m->yt[i] = y[i] + h * m->k3[i];
  if ((rc = dal__ode_rhs(ig, t + h, m->yt, m->k4)) != 0) return rc;
  int bad = -1;
  for (int i = 0; i < ny; ++i) {
    y1[i] = y[i];
    m->c1[i] = m->c[i];
    // each stage divided before the sum (a sum of large stages must not overflow where the
    // result is representable), by 6 and 3 per value: no rounded coefficient h / 6 repeats
    dal__ksum(&y1[i], &m->c1[i],
              h * (m->k1[i] / 6.0 + m->k2[i] / 3.0 + m->k3[i] / 3.0 + m->k4[i] / 6.0));
    if (bad < 0 && !isfinite(y1[i])) bad = i;
  }
  if (bad >= 0) {
    char var[128];
    snprintf(ig->rhs_err, sizeof ig->rhs_err,
             "the RK4 step from t=%.17g (h=%.3g) overflows: %s becomes %g", t, h,
             dal__ode_var_name(ig, bad, var, sizeof var), y1[bad]);
    ig->nrecov++;
    ig->recov_t = t + h;
    ig->recov_rc = DAL__RETRY_NONFINITE;
    return DAL__RETRY_NONFINITE;
  }
  return DAL_OK;
}

static int rk4_advance(dal_ode_integ *ig, double tout) {
  rk4_mem *m = ig->impl;
  double H = ig->opts.fixed_step, full = H, tend = ig->t;
  int depth = 0; // halvings of the current full step
  while (ig->t < tout) {
    if (ig->t >= tend) {
      // a new full step; the last one lands on tout (no sliver below 1e-9 H)
      depth = 0;
      tend = ig->t + H;
      if (tend > tout - 1e-9 * H) tend = tout;
      full = tend - ig->t;
    }
    double h = ldexp(full, -depth);
    double tn = h >= tend - ig->t ? tend : ig->t + h;
    int rc = rk4_step(ig, m, ig->t, ig->y, tn - ig->t, m->y1);
    if (dal__is_retry(rc) && depth < RK4_MAX_HALVINGS) {
      // the right-hand side asked for a smaller step, or the step overflowed: halve it
      ig->st->stats.rejected++;
      ++depth;
      continue;
    }
    // still failing after the last halving: the status of the cause
    if (dal__is_retry(rc)) return dal__ode_recov_fail(ig, tn - ig->t);
    if (rc)
      return dal__ode_fail(ig, rc,
                           "%s; stopped at t=%.17g (last accepted step) before the target "
                           "t=%.17g",
                           ig->rhs_err, ig->t, tout);
    int projected = 0;
    if ((rc = dal__ode_accept(ig, tn, m->y1, &projected)) != 0) return rc;
    // the compensation belongs to the accepted sum (a projection starts a new one)
    double *sw = m->c;
    m->c = m->c1;
    m->c1 = sw;
    if (projected) memset(m->c, 0, (size_t)ig->ny * sizeof(double));
  }
  return DAL_OK;
}

// the caller changed y[i0 ..]: their compensations start anew
static void rk4_changed_y(dal_ode_integ *ig, int i0) {
  rk4_mem *m = ig->impl;
  memset(m->c + i0, 0, (size_t)(ig->ny - i0) * sizeof(double));
}

static const dal_ode_ops rk4_ops = {rk4_advance, rk4_free, NULL, NULL, rk4_changed_y};

int dal__rk4_create(dal_ode_integ *ig) {
  rk4_mem *m = calloc(1, sizeof *m);
  if (!m) return DAL_FAIL(ig->st, DAL_E_NOMEM, "out of memory creating the RK4 integrator");
  ig->impl = m;
  ig->ops = &rk4_ops;
  size_t ny = (size_t)ig->ny + 1;
  m->k1 = calloc(ny, sizeof(double));
  m->k2 = calloc(ny, sizeof(double));
  m->k3 = calloc(ny, sizeof(double));
  m->k4 = calloc(ny, sizeof(double));
  m->yt = calloc(ny, sizeof(double));
  m->y1 = calloc(ny, sizeof(double));
  m->c = calloc(ny, sizeof(double));
  m->c1 = calloc(ny, sizeof(double));
  if (!m->k1 || !m->k2 || !m->k3 || !m->k4 || !m->yt || !m->y1 || !m->c || !m->c1)
    return DAL_FAIL(ig->st, DAL_E_NOMEM, "out of memory creating the RK4 integrator");
  return DAL_OK;
}
