// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Gragg-Bulirsch-Stoer extrapolation with order and step-size control.
//
// Source: Hairer, Norsett, Wanner, Solving Ordinary Differential Equations I (2nd ed.,
// Springer 1993), sec. II.9: Gragg's midpoint rule (9.13) with the step-number sequence
// n_j = 2, 4, 6, 8, ... (9.8), Aitken-Neville extrapolation in h^2 (9.10), the error estimate
// err_j = ||T_{j,j-1} - T_{j,j}|| (9.23), the optimal step H_j (9.25) with safety factors
// 0.94, 0.65 and bounds 0.02^(1/(2j-1))/4 <= H_j/H <= 1/0.02^(1/(2j-1)), the work per unit
// step W_j = A_j / H_j (9.26), the order selection (9.27) (decrease if W_{k-1} < 0.8 W_k,
// increase if W_k < 0.9 W_{k-1}) and the convergence monitor "convergence in line k-1, k,
// hope for convergence in line k+1"; the stability check of the first two columns and the
// initial order k = 0.6 (-log10 rtol) + 1.5 follow the description of the code ODEX there.
// No smoothing step. Written for this library from the book's description.
// Round-off: the midpoint rule and the extrapolation run on increments z - y (whose rounding
// is relative to the increment, not to y), and the accepted increment is added to y by
// compensated (Kahan) summation, so that round-off does not accumulate linearly in the steps.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "solve_internal.h"

/// number of columns (the largest T_{j,1}); the target order column k stays below it
#define BS_KMAX 9
/// halvings tolerated for one step (recoverable failures, stability check) before giving up
#define BS_MAX_REJECT 60

// outcomes of an attempt, apart from the internal retry codes (DAL__RECOVERABLE ...)
enum { BS_ACCEPT = 0, BS_REJECT = 100, BS_UNSTABLE = 101 };

typedef struct bs_mem {
  double *f0;       // f(t, y) at the start of the step (ny)
  int f0_ok;        // f0 belongs to (ig->t, ig->y)
  double *za, *zb;  // midpoint rule iterates (ny)
  double *fz;       // f at a midpoint iterate (ny)
  double *T;        // extrapolation tableau, one row: T[(l-1) ny + i] (BS_KMAX x ny)
  double *ynew;     // accepted value (ny)
  double *c, *cnew; // compensation of ig->y and of ynew (ny each)
  double *yz;       // y + increment, where f is evaluated (ny)
  int nseq[BS_KMAX + 2];
  double A[BS_KMAX + 2];    // work A_j (9.26)
  double hopt[BS_KMAX + 2]; // optimal step of column j (9.25)
  double W[BS_KMAX + 2];    // work per unit step of column j
  double err[BS_KMAX + 2];  // error estimate of column j
  int k;                    // target column, 2 <= k <= BS_KMAX - 1
  double H;                 // proposed step
  int kshort;               // target column for steps shortened to land on an output time
  int rejected_last;        // the previous attempt was rejected
} bs_mem;

static void bs_free(void *p) {
  bs_mem *m = p;
  if (!m) return;
  free(m->f0);
  free(m->za);
  free(m->zb);
  free(m->fz);
  free(m->T);
  free(m->ynew);
  free(m->c);
  free(m->cnew);
  free(m->yz);
  free(m);
}

// scaled RMS norm of v with the weights of y (atol + rtol |y|)
static double wnorm(const dal_ode_integ *ig, const double *v, const double *y) {
  double s = 0.0;
  for (int i = 0; i < ig->ny; ++i) {
    double w = v[i] / (ig->atol + ig->rtol * fabs(y[i]));
    s += w * w;
  }
  return sqrt(s / ig->ny);
}

// column j: T_{j,1} by Gragg's midpoint rule with n_j sub-steps over [t, t + H], then the
// extrapolated row T_{j,2..j}, all as increments over y; returns 0, BS_UNSTABLE (stability
// check) or the rhs code
static int bs_column(dal_ode_integ *ig, bs_mem *m, double t, double H, int j) {
  int ny = ig->ny, n = m->nseq[j], rc;
  double h = H / n, *z0 = m->za, *z1 = m->zb;
  const double *y = ig->y;
  for (int i = 0; i < ny; ++i) {
    z0[i] = 0.0;
    z1[i] = h * m->f0[i];
  }
  for (int s = 1; s < n; ++s) {
    for (int i = 0; i < ny; ++i)
      m->yz[i] = y[i] + z1[i];
    if ((rc = dal__ode_rhs(ig, t + s * h, m->yz, m->fz)) != 0) return rc;
    if (s == 1 && j <= 2) {
      // stability check: f must not change by more than twice its size over one sub-step
      double del1 = 0.0, del2 = 0.0;
      for (int i = 0; i < ny; ++i) {
        double sc = ig->atol + ig->rtol * fabs(y[i]);
        del1 += (m->f0[i] / sc) * (m->f0[i] / sc);
        del2 += ((m->fz[i] - m->f0[i]) / sc) * ((m->fz[i] - m->f0[i]) / sc);
      }
      if (del2 > 4.0 * fmax(del1, 1e-300)) return BS_UNSTABLE;
    }
    for (int i = 0; i < ny; ++i)
      z0[i] += 2.0 * h * m->fz[i];
    double *sw = z0;
    z0 = z1;
    z1 = sw;
  }
  // Aitken-Neville in h^2: T_{j,l+1} = T_{j,l} + (T_{j,l} - T_{j-1,l}) / ((n_j/n_{j-l})^2 - 1)
  for (int i = 0; i < ny; ++i) {
    double cur = z1[i];
    for (int l = 1; l < j; ++l) {
      double r = (double)n / m->nseq[j - l], prev = m->T[(size_t)(l - 1) * ny + i];
      m->T[(size_t)(l - 1) * ny + i] = cur;
      cur += (cur - prev) / (r * r - 1.0);
    }
    m->T[(size_t)(j - 1) * ny + i] = cur;
    if (!isfinite(cur)) {
      // the step overflowed: a retry with a shorter one
      char var[128];
      snprintf(ig->rhs_err, sizeof ig->rhs_err,
               "extrapolated value of %s is not finite at t=%.17g (H=%.3g): the step overflows",
               dal__ode_var_name(ig, i, var, sizeof var), t, H);
      ig->nrecov++;
      ig->recov_t = t + H;
      ig->recov_rc = DAL__RETRY_NONFINITE;
      return DAL__RETRY_NONFINITE;
    }
  }
  return DAL_OK;
}

// error estimate, optimal step and work of column j >= 2 (9.23), (9.25), (9.26)
static void bs_estimate(dal_ode_integ *ig, bs_mem *m, double H, int j) {
  int ny = ig->ny;
  const double *Tjj = m->T + (size_t)(j - 1) * ny, *Tj1 = m->T + (size_t)(j - 2) * ny;
  double s = 0.0;
  for (int i = 0; i < ny; ++i) {
    double sc = ig->atol + ig->rtol * fmax(fabs(ig->y[i]), fabs(ig->y[i] + Tjj[i]));
    double e = (Tjj[i] - Tj1[i]) / sc;
    ig->ewt[i] = e; // kept to name the dominating variable
    s += e * e;
  }
  double err = sqrt(s / ny), expo = 1.0 / (2 * j - 1), facmin = pow(0.02, expo);
  double fac = err > 0 ? 0.94 * pow(0.65 / err, expo) : 1.0 / facmin;
  fac = fmin(1.0 / facmin, fmax(facmin / 4.0, fac));
  m->err[j] = err;
  m->hopt[j] = H * fac;
  m->W[j] = m->A[j] / m->hopt[j];
}

// order and step after accepting T_{kc,kc} (9.27); no increase right after a rejection
static void bs_select(bs_mem *m, int kc, double H) {
  int knew = kc;
  if (kc == 2)
    knew = 3;
  else if (m->W[kc - 1] < 0.8 * m->W[kc])
    knew = kc - 1;
  else if (m->W[kc] < 0.9 * m->W[kc - 1])
    knew = kc + 1;
  if (knew < 2) knew = 2;
  if (knew > BS_KMAX - 1) knew = BS_KMAX - 1;
  double Hn = knew <= kc ? m->hopt[knew] : m->hopt[kc] * m->A[knew] / m->A[kc];
  if (m->rejected_last) {
    if (knew > kc) knew = kc;
    if (knew < 2) knew = 2;
    Hn = fmin(m->hopt[knew], H);
  }
  m->k = knew;
  m->H = Hn;
}

// order and step after rejecting at line kc: k_new <= kc, H_new = H_{k_new}
static void bs_reject(bs_mem *m, int kc) {
  int knew = kc;
  if (kc >= 3 && m->W[kc - 1] < 0.8 * m->W[kc]) knew = kc - 1;
  if (knew < 2) knew = 2;
  m->k = m->kshort = knew;
  m->H = m->hopt[knew];
}

// one attempt of a step of size H from (ig->t, ig->y); BS_ACCEPT (result in m->ynew and the
// accepted column in *kc), BS_REJECT (m->k, m->H set for the retry), or a negative code.
// A recoverable right-hand-side failure or the stability check halve the step.
static int bs_attempt(dal_ode_integ *ig, bs_mem *m, double H, int k, int *kc) {
  int rc;
  double t = ig->t, n1 = m->nseq[1];
  for (int j = 1; j <= k + 1; ++j) {
    rc = bs_column(ig, m, t, H, j);
    if (dal__is_retry(rc) || rc == BS_UNSTABLE) {
      m->H = 0.5 * H;
      return rc;
    }
    if (rc) return rc;
    if (j < 2) continue;
    bs_estimate(ig, m, H, j);
    double e = m->err[j];
    int accept = 0, reject = 0;
    if (j == k - 1) {
      // convergence in line k-1
      double bound = (double)m->nseq[k + 1] * m->nseq[k] / (n1 * n1);
      accept = e <= 1.0;
      reject = !accept && e > bound * bound;
    } else if (j == k) {
      // convergence in line k
      double bound = m->nseq[k + 1] / n1;
      accept = e <= 1.0;
      reject = !accept && e > bound * bound;
    } else if (j == k + 1) {
      // hope for convergence in line k+1
      accept = e <= 1.0;
      reject = !accept;
    }
    if (accept) {
      // y + increment, compensated
      const double *Tj = m->T + (size_t)(j - 1) * ig->ny;
      for (int i = 0; i < ig->ny; ++i) {
        m->ynew[i] = ig->y[i];
        m->cnew[i] = m->c[i];
        dal__ksum(&m->ynew[i], &m->cnew[i], Tj[i]);
      }
      *kc = j;
      return BS_ACCEPT;
    }
    if (reject) {
      bs_reject(m, j > k ? k : j);
      return BS_REJECT;
    }
  }
  return BS_REJECT; // not reached: line k+1 always decides
}

// initial step: Hairer-Norsett-Wanner sec. II.4 (starting step size), order p = 2k
static int bs_initial_step(dal_ode_integ *ig, bs_mem *m, double tout, double *H) {
  int ny = ig->ny, rc;
  double d0 = wnorm(ig, ig->y, ig->y), d1 = wnorm(ig, m->f0, ig->y);
  double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
  h0 = fmin(h0, tout - ig->t);
  for (int i = 0; i < ny; ++i)
    m->za[i] = ig->y[i] + h0 * m->f0[i];
  if ((rc = dal__ode_rhs(ig, ig->t + h0, m->za, m->fz)) != 0) return rc;
  for (int i = 0; i < ny; ++i)
    m->zb[i] = m->fz[i] - m->f0[i];
  double d2 = wnorm(ig, m->zb, ig->y) / h0, dm = fmax(d1, d2);
  double h1 = dm <= 1e-15 ? fmax(1e-6, h0 * 1e-3) : pow(0.01 / dm, 1.0 / (2 * m->k + 1));
  *H = fmin(100 * h0, h1);
  return DAL_OK;
}

static int bs_advance(dal_ode_integ *ig, double tout) {
  bs_mem *m = ig->impl;
  const dal_solve_opts *o = &ig->opts;
  char var[128];
  int nrej = 0, rc;
  while (ig->t < tout) {
    if (!m->f0_ok) {
      rc = dal__ode_rhs(ig, ig->t, ig->y, m->f0);
      if (rc)
        return dal__ode_fail(ig, rc,
                             "%s; at an accepted step, where no smaller step can help; stopped "
                             "at t=%.17g before the target t=%.17g",
                             ig->rhs_err, ig->t, tout);
      m->f0_ok = 1;
    }
    if (!(m->H > 0)) {
      double H0 = o->h0;
      if (!(H0 > 0) && (rc = bs_initial_step(ig, m, tout, &H0)) != 0) {
        if (dal__is_retry(rc)) {
          H0 = 1e-6 * fmax(1.0, tout - ig->t);
        } else {
          return dal__ode_fail(ig, rc, "%s; stopped at t=%.17g before the target t=%.17g",
                               ig->rhs_err, ig->t, tout);
        }
      }
      m->H = H0;
    }
    // the proposed step, bounded by hmax; a step that nearly reaches tout lands on it
    double Hprop = o->hmax > 0 ? fmin(m->H, o->hmax) : m->H, H = Hprop;
    int last = 0;
    if (ig->t + 1.01 * H >= tout) {
      H = tout - ig->t;
      last = 1;
    }
    // the progress guard: a step of a few ulps of t (a collapsed first-step estimate, or a
    // step size control driven down) stops at once with its cause
    double hfloor = fmax(o->hmin, DAL_TINY_STEP(ig->t));
    if (H < hfloor && !last)
      return dal__ode_stall(ig, H, "the step size fell to a few ulps of t");
    // a shortened step uses the order that sufficed for the last shortened one: with outputs
    // denser than the natural steps a low order is cheapest; the natural order and step are
    // kept for the next full step
    int shortened = last && H < Hprop, kc = 0;
    rc = bs_attempt(ig, m, H, shortened ? m->kshort : m->k, &kc);
    if (dal__is_retry(rc) || rc == BS_REJECT || rc == BS_UNSTABLE) {
      // rejected: bs_attempt has set the order and step of the retry
      m->rejected_last = 1;
      ig->st->stats.rejected++;
      if (++nrej > BS_MAX_REJECT) {
        if (dal__is_retry(rc)) return dal__ode_recov_fail(ig, H);
        return dal__ode_fail(
            ig, DAL_E_STEP,
            "step size underflow at t=%.17g (H=%.3g after %d rejections): "
            "error dominated by %s; loosen rtol/atol or check the model near "
            "this time",
            ig->t, H, nrej,
            dal__ode_var_name(ig, dal__ode_argmax(ig->ewt, ig->ny), var, sizeof var));
      }
      continue;
    }
    if (rc)
      return dal__ode_fail(ig, rc,
                           "%s; stopped at t=%.17g (last accepted step) before the "
                           "target t=%.17g",
                           ig->rhs_err, ig->t, tout);
    // accepted: choose the next order and step (9.27); a shortened step only chooses the
    // order of the next shortened step: the first column that converged, plus one
    if (!shortened || m->rejected_last) {
      bs_select(m, kc, H);
      m->kshort = m->k;
    } else {
      int jmin = kc;
      for (int j = 2; j < kc; ++j)
        if (m->err[j] <= 1.0) {
          jmin = j;
          break;
        }
      m->kshort = jmin + 1 < m->k ? jmin + 1 : m->k;
    }
    m->rejected_last = 0;
    nrej = 0;
    m->f0_ok = 0;
    int projected = 0;
    if ((rc = dal__ode_accept(ig, last ? tout : ig->t + H, m->ynew, &projected)) != 0) return rc;
    // the compensation belongs to the accepted sum (a projection starts a new one)
    double *sw = m->c;
    m->c = m->cnew;
    m->cnew = sw;
    if (projected) memset(m->c, 0, (size_t)ig->ny * sizeof(double));
  }
  return DAL_OK;
}

int dal__bs_create(dal_ode_integ *ig) {
  bs_mem *m = calloc(1, sizeof *m);
  if (!m) return DAL_FAIL(ig->st, DAL_E_NOMEM, "out of memory creating the BS integrator");
  ig->impl = m;
  ig->free_impl = bs_free;
  ig->advance = bs_advance;
  size_t ny = (size_t)ig->ny + 1;
  m->f0 = calloc(ny, sizeof(double));
  m->za = calloc(ny, sizeof(double));
  m->zb = calloc(ny, sizeof(double));
  m->fz = calloc(ny, sizeof(double));
  m->ynew = calloc(ny, sizeof(double));
  m->T = calloc(BS_KMAX * ny, sizeof(double));
  m->c = calloc(ny, sizeof(double));
  m->cnew = calloc(ny, sizeof(double));
  m->yz = calloc(ny, sizeof(double));
  if (!m->f0 || !m->za || !m->zb || !m->fz || !m->ynew || !m->T || !m->c || !m->cnew || !m->yz)
    return DAL_FAIL(ig->st, DAL_E_NOMEM, "out of memory creating the BS integrator");
  // step numbers n_j = 2j and work A_1 = n_1 + 1, A_j = A_{j-1} + n_j
  for (int j = 1; j <= BS_KMAX + 1; ++j)
    m->nseq[j] = 2 * j;
  m->A[1] = m->nseq[1] + 1;
  for (int j = 2; j <= BS_KMAX + 1; ++j)
    m->A[j] = m->A[j - 1] + m->nseq[j];
  int k = (int)(-log10(ig->rtol) * 0.6 + 1.5);
  m->k = k < 2 ? 2 : k > BS_KMAX - 1 ? BS_KMAX - 1 : k;
  m->kshort = m->k;
  m->H = 0.0;
  return DAL_OK;
}
