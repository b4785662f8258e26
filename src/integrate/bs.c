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
// is relative to the increment, not to y), the midpoint rule's sums are compensated, and the
// accepted increment is added to y by compensated (Kahan) summation, so that round-off does
// not accumulate linearly in the steps. Without dense output and at local tolerances below
// BS_BULIRSCH_RTOL (requests below 2e-10), the step numbers are Bulirsch's sequence
// n_j = 2, 4, 6, 8, 12, 16, 24, 32, 48 (HNW (9.7')): the extrapolated value is
// sum_j c_j T_{j,1} with sum |c_j| <= 9.1 for every column, where the harmonic sequence
// 2, 4, 6, ... has 26 in column 6 and 119 in column 8; the rounding of each T_{j,1} is
// amplified by that sum, which set a floor of 4e-14 ... 1.7e-13 on SICM's oscillator at t = 10
// (now 3e-15 ... 1e-14, tests/test_rounding.c). A step's length is the difference of the two
// representable times it joins (t + H rounded, minus t), so that y and t do not drift apart
// by the rounding of t + H in every step.
//
// Dense output (an advance call whose after-step hook reads the steps, ig->dense): the
// extrapolated dense output of Hairer & Ostermann (1990), HNW sec. II.9 "dense output for
// extrapolation methods", as in ODEX. The step numbers become n_j = 4j - 2 (2, 6, 10, ...), so
// that the midpoint of the step is a grid point of odd index in every row and the values
// there have an expansion in h^2. Row j gives the midpoint value and, by central differences
// of its f values, the derivatives of order l = 1 .. 2j at the midpoint (order 2j needs f at
// the row's end point, evaluated for the rows below the target column only); these are
// extrapolated over the rows that have them. The interpolant is the polynomial of degree
// mu + 4 in s = theta - 1/2 through y0, H f0, y1, H f1 (f1 = f(t1, y1), reused as the next
// step's f0) and the scaled derivatives H^l y^(l)(mid), l = 0 .. mu, with mu = 2 kappa - 3
// (kappa the accepted column; ODEX's default). Its last term a_{mu+4} (s^2 - 1/4)^2 s^mu
// estimates the interpolation error; a step whose estimate exceeds the tolerance (the norm of
// err) gets one more column (when its error estimate converges, the step ends with it and the
// interpolant of the next degree), else it is rejected; the next step is limited by the
// estimate. Against rejecting at once, the extra column takes 4.4% fewer right-hand sides and
// halves the worst error over the pendulum sweep of tests/test_dense_bs.c (19 -> 10 x rtol).
// Without a hook n_j = 2j runs (or Bulirsch's sequence at tight tolerances, above), and no dense
// data is kept (measured on the pendulum, tests/test_dense_bs.c: n_j = 4j - 2 alone costs about the
// same right-hand sides but takes longer steps whose error at the step points between 0 and 10
// reaches 127 x rtol; the interpolation error control keeps it below 16).
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "families.h"
#include "integrate.h"

/// number of columns (the largest T_{j,1}); the target order column k stays below it
#define BS_KMAX 9
/// local rtol below which the steps without dense output use Bulirsch's sequence (rounding
/// matters there); above it, the harmonic sequence whose Jacobi-integral drift on the turning
/// bead the tolerance factor was calibrated with (Bulirsch's gives 28 and 51 x rtol over 1000
/// periods at rtol 1e-6 and 1e-8, against the table's 20; tests/test_core.c)
#define BS_BULIRSCH_RTOL 1e-12
/// halvings tolerated for one step (recoverable failures, stability check) before giving up
#define BS_MAX_REJECT 60
/// largest step number with the dense sequence n_j = 4j - 2 (j <= BS_KMAX)
#define BS_NMAX (4 * BS_KMAX - 2)
/// coefficients of the interpolant: degree mu + 4 <= 2 BS_KMAX + 1
#define BS_NCOEF (2 * BS_KMAX + 2)
/// the interpolation error estimate above which a step is rejected (scaled norm, like err).
/// Looser bounds and aims (1 ... 10, 0.1 ... 1, some with the step error counted 2 ... 5 times
/// in the dense mode) save up to 8% of the right-hand sides but raise the worst error of the
/// pendulum sweep of tests/test_dense_bs.c (352 runs, 90 ... 176 degrees, rtol 1e-4 ... 1e-11)
/// from 10 to 14 ... 62 x rtol
#define BS_DENSE_REJECT 1.0
/// the interpolation error the next step aims at: the estimate (one coefficient) scatters by
/// a factor of ten between neighbouring steps, so that aiming at the bound itself gets many
/// steps rejected (a retry after a rejection aims at the bound, as ODEX's step after a
/// dense-output rejection)
#define BS_DENSE_TARGET 0.1

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
  double *ca, *cb;  // compensations of za and zb (ny each)
  int bulirsch;     // Bulirsch's sequence without dense output (local rtol < BS_BULIRSCH_RTOL)
  int nseq[BS_KMAX + 2];
  double A[BS_KMAX + 2];    // work A_j (9.26)
  double hopt[BS_KMAX + 2]; // optimal step of column j (9.25)
  double W[BS_KMAX + 2];    // work per unit step of column j
  double err[BS_KMAX + 2];  // error estimate of column j
  int k;                    // target column, 2 <= k <= BS_KMAX - 1
  double H;                 // proposed step
  int kshort;               // target column for steps shortened to land on an output time
  int rejected_last;        // the previous attempt was rejected
  // dense output
  int dense;             // this advance call keeps dense output (n_j = 4j - 2)
  int endf;              // rows j <= endf evaluate f at their end point (dense)
  double *F;             // f at the grid points of the current row ((BS_NMAX + 1) x ny)
  double *D;             // scaled midpoint derivatives H^l y^(l), row j at (j^2 - 1) ny,
                         // l = 0 .. lmax[j] (l = 0: the midpoint value as an increment)
  double *Dkeep;         // D as the rows left it (bs_dense_build extrapolates D in place)
  int lmax[BS_KMAX + 2]; // highest derivative row j holds
  double *f1;            // f(t1, y1) of the step being accepted (ny)
  double errint;         // interpolation error estimate of the step being accepted
  struct bs_dense {
    double t0, t1, H; // the step
    double slack;     // interp accepts t in [t0 - slack, t1 + slack] (rounding of t0, t1)
    int deg;          // degree of the interpolant in s = (t - t0) / H - 1/2
    double *y0, *y1;  // y at t0 and t1 (ny each)
    double *a;        // coefficients a_q of s^q, a[q ny + i] (BS_NCOEF x ny)
  } dd[2];
  int cur; // the record of the last accepted step (-1: none, or not a dense step)
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
  free(m->ca);
  free(m->cb);
  free(m->F);
  free(m->D);
  free(m->Dkeep);
  free(m->f1);
  for (int b = 0; b < 2; ++b) {
    free(m->dd[b].y0);
    free(m->dd[b].y1);
    free(m->dd[b].a);
  }
  free(m);
}

// the step-number sequence: n_j = 2j, or n_j = 4j - 2 with dense output; work A_1 = n_1 + 1,
// A_j = A_{j-1} + n_j (9.26)
static void bs_sequence(bs_mem *m, int dense) {
  m->dense = dense;
  // Bulirsch's sequence: n_j = 2, 4, 6 and then n_{j-2} doubled
  static const int bulirsch[BS_KMAX + 2] = {0, 2, 4, 6, 8, 12, 16, 24, 32, 48, 64};
  for (int j = 1; j <= BS_KMAX + 1; ++j)
    m->nseq[j] = dense ? 4 * j - 2 : m->bulirsch ? bulirsch[j] : 2 * j;
  m->A[1] = m->nseq[1] + 1;
  for (int j = 2; j <= BS_KMAX + 1; ++j)
    m->A[j] = m->A[j - 1] + m->nseq[j];
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

// dense output, row j: the scaled derivatives H^l y^(l) at the midpoint, l = 1 .. lmax, from
// the f values F[p] at the grid points p = 0 .. N of the row (N = n or n - 1): with central
// differences g^(0)_p = f_p, g^(q)_p = g^(q-1)_{p+1} - g^(q-1)_{p-1},
// y^(q+1)(mid) ~ g^(q)_{n/2} / (2h)^q, hence H^(q+1) y^(q+1) ~ H (n/2)^q g^(q)_{n/2}.
// The differences overwrite F in place: after level q, F[p] holds g^(q)_{p+q}.
static void bs_dense_row(dal_ode_integ *ig, bs_mem *m, double H, int j, int N) {
  int ny = ig->ny, n = m->nseq[j], mid = n / 2, lmax = N - mid + 1;
  double *D = m->D + (size_t)(j * j - 1) * ny, *F = m->F, sc = H;
  for (int i = 0; i < ny; ++i)
    D[ny + i] = H * F[(size_t)mid * ny + i];
  for (int q = 1; q < lmax; ++q) {
    // the grid points p = 0 .. N - 2q at once (F is contiguous)
    const double *F2 = F + 2 * (size_t)ny;
    for (size_t x = 0; x < (size_t)(N - 2 * q + 1) * ny; ++x)
      F[x] = F2[x] - F[x];
    sc *= 0.5 * n;
    const double *g = F + (size_t)(mid - q) * ny;
    for (int i = 0; i < ny; ++i)
      D[(size_t)(q + 1) * ny + i] = sc * g[i];
  }
  m->lmax[j] = lmax;
}

// column j: T_{j,1} by Gragg's midpoint rule with n_j sub-steps over [t, t + H], then the
// extrapolated row T_{j,2..j}, all as increments over y; returns 0, BS_UNSTABLE (stability
// check) or the rhs code. With dense output the f values of the row are kept in m->F and the
// row's midpoint data go to m->D.
static int bs_column(dal_ode_integ *ig, bs_mem *m, double t, double H, int j) {
  int ny = ig->ny, n = m->nseq[j], rc;
  double h = H / n, *z0 = m->za, *z1 = m->zb, *F = m->dense ? m->F : NULL;
  double *c0 = m->ca, *c1 = m->cb;
  const double *y = ig->y;
  for (int i = 0; i < ny; ++i) {
    z0[i] = 0.0;
    z1[i] = h * m->f0[i];
    c0[i] = c1[i] = 0.0;
  }
  if (F) memcpy(F, m->f0, (size_t)ny * sizeof(double));
  for (int s = 1; s < n; ++s) {
    double *fs = F ? F + (size_t)s * ny : m->fz;
    for (int i = 0; i < ny; ++i)
      m->yz[i] = y[i] + z1[i];
    if ((rc = dal__ode_rhs(ig, t + s * h, m->yz, fs)) != 0) return rc;
    if (s == 1 && j <= 2) {
      // stability check: f must not change by more than twice its size over one sub-step
      double del1 = 0.0, del2 = 0.0;
      for (int i = 0; i < ny; ++i) {
        double sc = ig->atol + ig->rtol * fabs(y[i]);
        del1 += (m->f0[i] / sc) * (m->f0[i] / sc);
        del2 += ((fs[i] - m->f0[i]) / sc) * ((fs[i] - m->f0[i]) / sc);
      }
      if (del2 > 4.0 * fmax(del1, 1e-300)) return BS_UNSTABLE;
    }
    // the midpoint value of the row (an increment), for the dense output
    if (F && 2 * s == n) memcpy(m->D + (size_t)(j * j - 1) * ny, z1, (size_t)ny * sizeof(double));
    // z_{s+1} = z_{s-1} + 2h f_s, compensated (the compensations swap with the iterates)
    for (int i = 0; i < ny; ++i)
      dal__ksum(&z0[i], &c0[i], 2.0 * h * fs[i]);
    double *sw = z0;
    z0 = z1;
    z1 = sw;
    sw = c0;
    c0 = c1;
    c1 = sw;
  }
  if (F) {
    // f at the end point of the row gives the derivative of order 2j (not needed in the last
    // two columns, see bs_dense_build)
    int N = n - 1;
    if (j <= m->endf) {
      for (int i = 0; i < ny; ++i)
        m->yz[i] = y[i] + z1[i];
      if ((rc = dal__ode_rhs(ig, t + H, m->yz, F + (size_t)n * ny)) != 0) return rc;
      N = n;
    }
    bs_dense_row(ig, m, H, j, N);
  }
  // Aitken-Neville in h^2: T_{j,l+1} = T_{j,l} + (T_{j,l} - T_{j-1,l}) / ((n_j/n_{j-l})^2 - 1)
  for (int i = 0; i < ny; ++i) {
    double cur = z1[i] - c1[i];
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

// the step's result T_{j,j}: y + increment, compensated, into m->ynew
static inline void bs_take(dal_ode_integ *ig, bs_mem *m, int j) {
  const double *Tj = m->T + (size_t)(j - 1) * ig->ny;
  for (int i = 0; i < ig->ny; ++i) {
    m->ynew[i] = ig->y[i];
    m->cnew[i] = m->c[i];
    dal__ksum(&m->ynew[i], &m->cnew[i], Tj[i]);
  }
}

// one attempt of a step of size H from (ig->t, ig->y); BS_ACCEPT (result in m->ynew and the
// accepted column in *kc), BS_REJECT (m->k, m->H set for the retry), or a negative code.
// A recoverable right-hand-side failure or the stability check halve the step.
static int bs_attempt(dal_ode_integ *ig, bs_mem *m, double H, int k, int *kc) {
  int rc;
  double t = ig->t, n1 = m->nseq[1];
  // with dense output, the rows that may give the derivative of order 2j need the f value at
  // their end point: j <= kappa - 2 for the accepted column kappa <= k + 1
  m->endf = k - 1;
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
      bs_take(ig, m, j);
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

// max over s in [-1/2, 1/2] of (1/4 - s^2)^2 |s|^mu: at s^2 = mu / (4 (mu + 4))
static double bs_errfac(int mu) {
  double u = mu / (4.0 * (mu + 4.0));
  return (0.25 - u) * (0.25 - u) * pow(u, 0.5 * mu);
}

// the interpolant of the step just accepted at column kc (increment m->T row kc - 1, end
// value m->ynew, f1 = m->f1 at t1) into the free record; sets m->errint. Returns the record.
//   P(s) = sum_{l <= mu} d_l s^l / l! + s^(mu+1) R(s), s = theta - 1/2, R cubic:
// the Taylor part has the extrapolated midpoint derivatives d_l = H^l y^(l)(mid), and R makes
// P(-1/2) = 0, P'(-1/2) = H f0, P(1/2) = T_kc,kc, P'(1/2) = H f1 (increments over y0).
static int bs_dense_build(dal_ode_integ *ig, bs_mem *m, int kc, double H, double t1) {
  int ny = ig->ny, b = m->cur == 0 ? 1 : 0, mu = 2 * kc - 3, p = mu + 1;
  struct bs_dense *d = &m->dd[b];
  double *a = d->a;
  // extrapolate each derivative l <= mu over the rows j0(l) .. kc that hold it (Aitken-Neville
  // in h^2, in place in D, descending j). Level q of row j needs row j - 1 and the sequence
  // ratio n_j / n_{j-q}; it applies to the derivatives that row j - q holds (lmax grows with
  // j), which lie next to each other in row j: one sweep over them per (q, j)
  for (int q = 1; q < kc; ++q) {
    for (int j = kc; j > q; --j) {
      int L = m->lmax[j - q] < mu ? m->lmax[j - q] : mu;
      double r = (double)m->nseq[j] / m->nseq[j - q], den = r * r - 1.0;
      double *cur = m->D + (size_t)(j * j - 1) * ny;
      const double *prev = m->D + (size_t)((j - 1) * (j - 1) - 1) * ny;
      for (size_t x = 0; x < (size_t)(L + 1) * ny; ++x)
        cur[x] += (cur[x] - prev[x]) / den;
    }
  }
  double fact = 1.0;
  const double *dk = m->D + (size_t)(kc * kc - 1) * ny;
  for (int l = 0; l <= mu; ++l) {
    if (l > 1) fact *= l;
    for (int i = 0; i < ny; ++i)
      a[(size_t)l * ny + i] = dk[(size_t)l * ny + i] / fact;
  }
  // the cubic R from the end conditions: with e = Y - T (value) and e' (derivative) at
  // sigma = +-1/2, R(sigma) = e / sigma^p, R'(sigma) = (e' - p e / sigma) / sigma^p
  const double *Tkk = m->T + (size_t)(kc - 1) * ny;
  double sp = ldexp(1.0, -p), s = 0.0; // (1/2)^p
  for (int i = 0; i < ny; ++i) {
    double Tp = 0.0, Tm = 0.0, dTp = 0.0, dTm = 0.0;
    for (int l = mu; l >= 0; --l) {
      double al = a[(size_t)l * ny + i];
      dTp = dTp * 0.5 + Tp;
      dTm = dTm * -0.5 + Tm;
      Tp = Tp * 0.5 + al;
      Tm = Tm * -0.5 + al;
    }
    double em = 0.0 - Tm, ep = Tkk[i] - Tp;
    double dem = H * m->f0[i] - dTm, dep = H * m->f1[i] - dTp;
    double sgn = (p & 1) ? -1.0 : 1.0; // (-1/2)^p = sgn sp
    double Rm = em / (sgn * sp), Rp = ep / sp;
    double dRm = (dem + 2.0 * p * em) / (sgn * sp), dRp = (dep - 2.0 * p * ep) / sp;
    double S0 = Rp + Rm, D0 = Rp - Rm, S1 = dRp + dRm, D1 = dRp - dRm;
    double c3 = S1 - 2.0 * D0;
    a[(size_t)p * ny + i] = 0.5 * S0 - 0.125 * D1;
    a[(size_t)(p + 1) * ny + i] = 1.5 * D0 - 0.25 * S1;
    a[(size_t)(p + 2) * ny + i] = 0.5 * D1;
    a[(size_t)(p + 3) * ny + i] = c3;
    // error estimate: the last term c3 (1/4 - s^2)^2 s^mu (the difference to the interpolant
    // with one midpoint derivative less), scaled like the step's error
    double sc = ig->atol + ig->rtol * fmax(fabs(ig->y[i]), fabs(m->ynew[i]));
    s += (c3 / sc) * (c3 / sc);
  }
  m->errint = sqrt(s / ny) * bs_errfac(mu);
  d->t0 = ig->t;
  d->t1 = t1;
  d->H = H;
  d->slack = 4.0 * DBL_EPSILON * fmax(fabs(d->t0), fabs(d->t1));
  d->deg = mu + 4;
  memcpy(d->y0, ig->y, (size_t)ny * sizeof(double));
  memcpy(d->y1, m->ynew, (size_t)ny * sizeof(double));
  return b;
}

// step factor from the interpolation error estimate (of order deg in H) aiming at target,
// between 0.2 and 4
static double bs_dense_fac(double errint, int deg, double target) {
  double fac = 0.94 * pow(target / fmax(errint, 1e-300), 1.0 / deg);
  return fmin(4.0, fmax(0.2, fac));
}

// y0 + P(s) for the w <= 4 components from i0 (Horner's rule; w is a constant where this is
// inlined, so that the w sums stay in registers while the coefficients are read once)
static inline void bs_horner(const struct bs_dense *d, int ny, int i0, int w, double s,
                             double *yout) {
  double acc[4];
  const double *a = d->a + (size_t)d->deg * ny + i0;
  for (int k = 0; k < w; ++k)
    acc[k] = a[k];
  for (int q = d->deg; q > 0; --q) {
    a -= ny;
    for (int k = 0; k < w; ++k)
      acc[k] = acc[k] * s + a[k];
  }
  for (int k = 0; k < w; ++k)
    yout[i0 + k] = d->y0[i0 + k] + acc[k];
}

// y at t in [tprev, t] of the last accepted step, from its interpolant (the integration is not
// touched). Dense data exist for the steps of an advance call that started with a hook.
static int bs_interp(dal_ode_integ *ig, double t, double *yout) {
  bs_mem *m = ig->impl;
  int ny = ig->ny;
  if (m->cur < 0) {
    if (t == ig->t) {
      memcpy(yout, ig->y, (size_t)ny * sizeof(double));
      return DAL_OK;
    }
    return DAL_FAIL(ig->st, DAL_E_UNSUPPORTED,
                    "Bulirsch-Stoer: no dense output for the step ending at t=%.17g (dense "
                    "output is kept only when the after-step hook is set before advance)",
                    ig->t);
  }
  const struct bs_dense *d = &m->dd[m->cur];
  if (!(t >= d->t0 - d->slack && t <= d->t1 + d->slack))
    return DAL_FAIL(ig->st, DAL_E_ARG,
                    "Bulirsch-Stoer dense output: t=%.17g lies outside the last step "
                    "[%.17g, %.17g]",
                    t, d->t0, d->t1);
  if (t == d->t1) {
    memcpy(yout, d->y1, (size_t)ny * sizeof(double));
    return DAL_OK;
  }
  double s = (t - d->t0) / d->H - 0.5;
  int i = 0;
  for (; i + 4 <= ny; i += 4)
    bs_horner(d, ny, i, 4, s, yout);
  for (; i + 2 <= ny; i += 2)
    bs_horner(d, ny, i, 2, s, yout);
  if (i < ny) bs_horner(d, ny, i, 1, s, yout);
  return DAL_OK;
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

// the start of a step: f at the step's start, and on the first step the initial step size
static int bs_step_start(dal_ode_integ *ig, bs_mem *m, double tout) {
  const dal_solve_opts *o = &ig->opts;
  int rc;
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
  return DAL_OK;
}

// the proposed step, bounded by hmax; a step that nearly reaches tout lands on it. Sets the
// step *H, its end *t1 and whether it is *shortened; nonzero when the step size stalled.
static inline int bs_step_size(dal_ode_integ *ig, bs_mem *m, double tout, double *H, double *t1,
                               int *shortened) {
  const dal_solve_opts *o = &ig->opts;
  double Hprop = o->hmax > 0 ? fmin(m->H, o->hmax) : m->H, h = Hprop;
  int last = 0;
  if (ig->t + 1.01 * h >= tout) {
    h = tout - ig->t;
    last = 1;
  }
  // the progress guard: a step of a few ulps of t (a collapsed first-step estimate, or a
  // step size control driven down) stops at once with its cause
  double hfloor = fmax(o->hmin, DAL_TINY_STEP(ig->t));
  if (h < hfloor && !last) return dal__ode_stall(ig, h, "the step size fell to a few ulps of t");
  // a shortened step uses the order that sufficed for the last shortened one: with outputs
  // denser than the natural steps a low order is cheapest; the natural order and step are
  // kept for the next full step
  *shortened = last && h < Hprop;
  *t1 = last ? tout : ig->t + h;
  // the step actually taken is the difference of the representable times (exact: t1 is
  // t + H rounded); integrating H itself would shift the solution against t by the rounding
  // of t + H, up to half an ulp of t in every step
  *H = *t1 - ig->t;
  return DAL_OK;
}

// one attempt of the step H to t1 at column *kc, with its interpolant (buffer *b, else -1)
// when dense output is on. Returns bs_attempt's verdict, which the interpolation error can
// turn into BS_REJECT.
static inline int bs_step_try(dal_ode_integ *ig, bs_mem *m, double H, double t1, int shortened,
                              int *kc, int *b) {
  int rc = bs_attempt(ig, m, H, shortened ? m->kshort : m->k, kc);
  *b = -1;
  if (rc != BS_ACCEPT || !m->dense) return rc;
  // the interpolant needs f(t1, y1) (the next step's f0); its error estimate can still
  // reject the step. Too large an estimate first gets one more column (a higher-degree
  // interpolant from the same step, n_{kc+1} right-hand sides instead of a new step)
  size_t nkeep = (size_t)((*kc + 1) * (*kc + 1) - 1) * ig->ny;
  for (int more = *kc < BS_KMAX;; more = 0) {
    if (more) memcpy(m->Dkeep, m->D, nkeep * sizeof(double));
    if ((rc = dal__ode_rhs(ig, t1, m->ynew, m->f1)) != 0) {
      if (dal__is_retry(rc)) m->H = 0.5 * H;
      return rc;
    }
    *b = bs_dense_build(ig, m, *kc, H, t1);
    if (m->errint <= BS_DENSE_REJECT) return BS_ACCEPT;
    if (more) {
      memcpy(m->D, m->Dkeep, nkeep * sizeof(double));
      int j = *kc + 1;
      rc = bs_column(ig, m, ig->t, H, j);
      if (rc == 0) bs_estimate(ig, m, H, j);
      if (rc == 0 && m->err[j] <= 1.0) {
        bs_take(ig, m, j);
        *kc = j;
        continue;
      }
      if (dal__is_retry(rc) || rc == BS_UNSTABLE) m->H = 0.5 * H;
      if (rc) return rc;
    }
    m->H = H * bs_dense_fac(m->errint, m->dd[*b].deg, BS_DENSE_REJECT);
    return BS_REJECT;
  }
}

// rejected: bs_attempt has set the order and step of the retry. Counts the rejection;
// nonzero (the failure) after too many in a row.
static int bs_step_rejected(dal_ode_integ *ig, bs_mem *m, int rc, double H, int *nrej) {
  char var[128];
  m->rejected_last = 1;
  ig->st->stats.rejected++;
  if (++*nrej > BS_MAX_REJECT) {
    if (dal__is_retry(rc)) return dal__ode_recov_fail(ig, H);
    return dal__ode_fail(ig, DAL_E_STEP,
                         "step size underflow at t=%.17g (H=%.3g after %d rejections): "
                         "error dominated by %s; loosen rtol/atol or check the model near "
                         "this time",
                         ig->t, H, *nrej,
                         dal__ode_var_name(ig, dal__ode_argmax(ig->ewt, ig->ny), var, sizeof var));
  }
  return DAL_OK;
}

// accepted: choose the next order and step (9.27); a shortened step only chooses the
// order of the next shortened step: the first column that converged, plus one
static inline void bs_step_control(bs_mem *m, int kc, double H, int shortened, int b) {
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
  // the next step is limited by the interpolation error too
  if (b >= 0 && !shortened)
    m->H = fmin(m->H, H * bs_dense_fac(m->errint, m->dd[b].deg, BS_DENSE_TARGET));
  m->rejected_last = 0;
  m->f0_ok = 0;
}

// hands the accepted step to t1 (dense data in buffer b, or -1) to dal__ode_accept. Returns
// its status; ig->t != t1 after it when the progress guard refused the step.
static int bs_step_accept(dal_ode_integ *ig, bs_mem *m, double t1, int b) {
  int projected = 0, prev = m->cur;
  // the dense data of the step are ready before dal__ode_accept (which calls the hook)
  m->cur = b;
  int rc = dal__ode_accept(ig, t1, m->ynew, &projected);
  if (ig->t != t1) {
    // refused by the progress guard: the last step stays the one to read
    m->cur = prev;
    return rc;
  }
  // the compensation belongs to the accepted sum (a projection starts a new one)
  double *sw = m->c;
  m->c = m->cnew;
  m->cnew = sw;
  if (projected) memset(m->c, 0, (size_t)ig->ny * sizeof(double));
  if (b >= 0 && !projected) {
    // f(t1, y1) is the next step's f0
    sw = m->f0;
    m->f0 = m->f1;
    m->f1 = sw;
    m->f0_ok = 1;
  }
  return rc;
}

static int bs_advance(dal_ode_integ *ig, double tout) {
  bs_mem *m = ig->impl;
  int nrej = 0, rc;
  // dense output when a hook reads the steps (the driver says so before advance; a hook that
  // only asks the cancel hook keeps the plain sequence and so the plain run's steps)
  if (ig->dense != m->dense) bs_sequence(m, ig->dense);
  while (ig->t < tout) {
    if ((rc = bs_step_start(ig, m, tout)) != 0) return rc;
    double H = 0.0, t1 = 0.0;
    int shortened = 0, kc = 0, b = -1;
    if ((rc = bs_step_size(ig, m, tout, &H, &t1, &shortened)) != 0) return rc;
    rc = bs_step_try(ig, m, H, t1, shortened, &kc, &b);
    if (dal__is_retry(rc) || rc == BS_REJECT || rc == BS_UNSTABLE) {
      if ((rc = bs_step_rejected(ig, m, rc, H, &nrej)) != 0) return rc;
      continue;
    }
    if (rc)
      return dal__ode_fail(ig, rc,
                           "%s; stopped at t=%.17g (last accepted step) before the "
                           "target t=%.17g",
                           ig->rhs_err, ig->t, tout);
    bs_step_control(m, kc, H, shortened, b);
    nrej = 0;
    // stopped after the step: refused by the progress guard, or accepted and stopped by the
    // hook (DAL__HOOK_STOP) or opts.max_steps
    rc = bs_step_accept(ig, m, t1, b);
    if (rc || ig->t != t1) return rc;
  }
  return DAL_OK;
}

// the caller changed y[i0 ..]: their compensations start anew, f at the step's start is
// evaluated again, and the last step has no dense output any more (the order and step stay)
static void bs_changed_y(dal_ode_integ *ig, int i0) {
  bs_mem *m = ig->impl;
  memset(m->c + i0, 0, (size_t)(ig->ny - i0) * sizeof(double));
  m->f0_ok = 0;
  m->cur = -1;
}

static const dal_ode_ops bs_ops = {bs_advance, bs_free, bs_interp, NULL, bs_changed_y};

int dal__bs_create(dal_ode_integ *ig) {
  bs_mem *m = calloc(1, sizeof *m);
  if (!m) return DAL_FAIL(ig->st, DAL_E_NOMEM, "out of memory creating the BS integrator");
  ig->impl = m;
  ig->ops = &bs_ops;
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
  m->ca = calloc(ny, sizeof(double));
  m->cb = calloc(ny, sizeof(double));
  m->F = calloc((BS_NMAX + 1) * ny, sizeof(double));
  m->D = calloc((size_t)(BS_KMAX * BS_KMAX + 2 * BS_KMAX) * ny, sizeof(double));
  m->Dkeep = calloc((size_t)(BS_KMAX * BS_KMAX + 2 * BS_KMAX) * ny, sizeof(double));
  m->f1 = calloc(ny, sizeof(double));
  int ok = m->f0 && m->za && m->zb && m->ca && m->cb && m->fz && m->ynew && m->T && m->c &&
           m->cnew && m->yz && m->F && m->D && m->Dkeep && m->f1;
  for (int b = 0; b < 2; ++b) {
    m->dd[b].y0 = calloc(ny, sizeof(double));
    m->dd[b].y1 = calloc(ny, sizeof(double));
    m->dd[b].a = calloc(BS_NCOEF * ny, sizeof(double));
    ok = ok && m->dd[b].y0 && m->dd[b].y1 && m->dd[b].a;
  }
  if (!ok) return DAL_FAIL(ig->st, DAL_E_NOMEM, "out of memory creating the BS integrator");
  m->cur = -1;
  m->bulirsch = ig->rtol < BS_BULIRSCH_RTOL;
  bs_sequence(m, 0);
  int k = (int)(-log10(ig->rtol) * 0.6 + 1.5);
  m->k = k < 2 ? 2 : k > BS_KMAX - 1 ? BS_KMAX - 1 : k;
  m->kshort = m->k;
  m->H = 0.0;
  return DAL_OK;
}
