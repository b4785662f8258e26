// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Explicit time dependence of the equations of motion (the exact df/dt at probe points), and
// Floquet analysis: the monodromy matrix over one period from the exact state-transition
// matrix, reduced to the constraint manifold, its multipliers with an accuracy from two
// tolerances, and a stability verdict (Floquet 1883; Yakubovich & Starzhinskii, Linear
// Differential Equations with Periodic Coefficients, 1975).
#include <complex.h>
#include <float.h>
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis.h"
#include "dalembert/dae.h"

/// probe points of dal_time_dependence (the state itself and pseudo-random ones around it)
#define DAL_TD_PROBES 6
/// df/dt is zero when |df/dt| <= this times ||A|| (|f| + ||A|| |y|) (rounding of an autonomous
/// field written with t, e.g. a steadily turning frame, is ~1e-15 of that)
#define DAL_TD_REL 1e-9

int dal__restore_state(const dal_system *sys, dal_state *st, double t, const double *y, int rc) {
  char keep[DAL_ERRMSG_LEN];
  memcpy(keep, st->err, sizeof keep);
  int erc = dal__analysis_eval(sys, st, t, y, y + sys->n);
  if (rc == DAL_OK) return erc;
  memcpy(st->err, keep, sizeof keep);
  return rc;
}

static double td_urand(unsigned long long *s) {
  *s ^= *s >> 12;
  *s ^= *s << 25;
  *s ^= *s >> 27;
  return (double)((*s * 2685821657736338717ULL) >> 11) * 0x1.0p-53;
}

// what moves with t at the evaluated state, by structure: placements with dr/dt != 0 at fixed
// q and constraint rows with dphi/dt != 0 (into buf; "" when neither)
static void td_culprits(const dal_system *sys, const dal_state *st, char *buf, size_t len) {
  size_t used = 0;
  int count = 0, d = sys->dim;
  buf[0] = '\0';
  for (int k = 0; k < sys->N && count < 3; ++k) {
    double s = 0.0, r = 0.0;
    for (int a = 0; a < d; ++a) {
      s = fmax(s, fabs(st->drdt[k * d + a]));
      r = fmax(r, fabs(st->r[k * d + a]));
    }
    if (s > 1e-14 * (1.0 + r) && used < len) {
      used += (size_t)snprintf(buf + used, len - used, "%sthe placement of particle '%s'",
                               count ? ", " : "", sys->part_names[k]);
      ++count;
    }
  }
  for (int c = 0; c < sys->ncon && count < 4; ++c) {
    const dal_con *cn = &sys->con[c];
    double s = 0.0;
    for (int i = 0; i < cn->prim->nout; ++i)
      s = fmax(s, fabs(st->phit[cn->row + i]));
    if (s > 1e-14 && used < len) {
      used += (size_t)snprintf(buf + used, len - used, "%sconstraint '%s'", count ? ", " : "",
                               cn->name);
      ++count;
    }
  }
}

// the largest |df/dt| relative to its scale at the state's (t, q, qdot), or a status < 0
static double td_probe(const dal_system *sys, dal_state *st, double ytyp, double *A, double *ft,
                       int *rc) {
  int n2 = 2 * sys->n;
  *rc = dal_vector_field_jacobian(sys, st, A, ft);
  if (*rc) return 0.0;
  double an = 0.0, fn = 0.0, yn = 0.0, tn = 0.0;
  for (int i = 0; i < n2; ++i) {
    double row = 0.0;
    for (int j = 0; j < n2; ++j)
      row += fabs(A[(size_t)j * n2 + i]);
    an = fmax(an, row);
    tn = fmax(tn, fabs(ft[i]));
  }
  for (int i = 0; i < sys->n; ++i) {
    fn = fmax(fn, fmax(fabs(st->qdot[i]), fabs(st->qddot[i])));
    yn = fmax(yn, fmax(fabs(st->q[i]), fabs(st->qdot[i])));
  }
  // |y| at least the probes' spread: near rest at the origin f and y vanish, and rounding in
  // df/dt would be measured against nothing
  double scale = an * (fn + an * fmax(yn, ytyp));
  // with no field at all (scale 0) nothing can be judged: other probes decide
  return tn > 0 && scale > 0 ? tn / scale : 0.0;
}

int dal_time_dependence(const dal_system *sys, dal_state *st, char *what, size_t len) {
  int rc = dal__check_pair(sys, st, "time_dependence");
  if (rc) return rc;
  if (what && len) what[0] = '\0';
  int n = sys->n;
  size_t sn = (size_t)n, n2 = 2 * sn;
  double *buf = malloc((n2 * n2 + 3 * n2 + 1) * sizeof(double));
  if (!buf) return DAL_FAIL(st, DAL_E_NOMEM, "time_dependence: out of memory");
  double *A = buf, *ft = A + n2 * n2, *y0 = ft + n2, *y = y0 + n2, t0 = st->t;
  memcpy(y0, st->q, sn * sizeof(double));
  memcpy(y0 + sn, st->qdot, sn * sizeof(double));
  double worst = 0.0, worst_t = t0, ytyp = 0.0;
  for (size_t i = 0; i < n2; ++i)
    ytyp = fmax(ytyp, fabs(y0[i]));
  ytyp = 0.3 * (1.0 + ytyp);
  unsigned long long seed = 0x9e3779b97f4a7c15ULL;
  int tried = 0;
  char who[384] = "";
  for (int p = 0; p < DAL_TD_PROBES; ++p) {
    // the state itself, then (t, q, qdot) moved by up to 30% of (1 + |.|) and t by up to 7
    double t = t0;
    memcpy(y, y0, n2 * sizeof(double));
    if (p > 0) {
      t = t0 + 7.0 * td_urand(&seed);
      for (size_t i = 0; i < n2; ++i)
        y[i] += 0.3 * (2.0 * td_urand(&seed) - 1.0) * (1.0 + fabs(y0[i]));
    }
    int prc = dal_state_set(sys, st, t, y, y + sn);
    if (!prc && sys->m > 0) prc = dal_make_consistent(sys, st, 0.0, NULL);
    double r = prc ? 0.0 : td_probe(sys, st, ytyp, A, ft, &prc);
    if (prc && p == 0) { // the state itself must evaluate (the tangent covers the system)
      rc = prc;
      break;
    }
    if (prc) continue; // a probe point the model refuses (a chart singularity): skip it
    ++tried;
    if (r > worst) { // what moves with t, read where the dependence shows most
      worst = r;
      worst_t = t;
      if (what && len) td_culprits(sys, st, who, sizeof who);
    }
    if (p == 0 && what && len) td_culprits(sys, st, who, sizeof who);
  }
  // back to the state as given, evaluated, with the structural culprits read there
  rc = dal__restore_state(sys, st, t0, y0, rc);
  free(buf);
  if (rc) return rc;
  int dependent = worst > DAL_TD_REL;
  if (what && len) {
    if (dependent)
      snprintf(what, len,
               "the equations of motion depend on time explicitly (|df/dt| %.3g of its scale "
               "at t=%.6g%s%s)",
               worst, worst_t, who[0] ? "; moving: " : "", who[0] ? who : "");
    else
      snprintf(what, len,
               "the equations of motion do not depend on time explicitly (%d probe points)%s%s",
               tried, who[0] ? "; moving steadily in these coordinates: " : "", who);
  }
  return dependent;
}

// ---------------------------------------------------------------------------------------------
// Floquet multipliers

// sort multipliers by decreasing modulus, then by increasing argument
static void sort_mult(int k, double *re, double *im) {
  for (int i = 1; i < k; ++i) {
    double r = re[i], m = im[i], a = hypot(r, m), g = atan2(m, r);
    int j = i - 1;
    while (j >= 0) {
      double aj = hypot(re[j], im[j]);
      if (aj > a || (aj == a && atan2(im[j], re[j]) <= g)) break;
      re[j + 1] = re[j];
      im[j + 1] = im[j];
      --j;
    }
    re[j + 1] = r;
    im[j + 1] = m;
  }
}

// one monodromy from (t0, y0) over T: the reduced matrix Mr (k2 x k2), the end point yT (2n);
// Z0 = [N 0; Y N] and P0 = [N' 0; -N'Y N' N'] from the start (m > 0)
static int monodromy(const dal_system *sys, dal_state *st, const dal_solve_opts *o, double t0,
                     const double *y0, double T, const double *Z, const double *P, double *Phi,
                     double *tmp, double *Mr, double *yT) {
  int n = sys->n, k2 = 2 * (n - sys->m), rc;
  size_t sn = (size_t)n, n2 = 2 * sn;
  if ((rc = dal__analysis_eval(sys, st, t0, y0, y0 + sn)) != 0) return rc;
  if ((rc = dal_state_transition(sys, st, o, t0 + T, Phi, 0, NULL, NULL)) != 0) return rc;
  memcpy(yT, st->q, sn * sizeof(double));
  memcpy(yT + sn, st->qdot, sn * sizeof(double));
  if (sys->m == 0) {
    memcpy(Mr, Phi, n2 * n2 * sizeof(double));
    return DAL_OK;
  }
  // tmp = Phi Z (2n x k2), Mr = P tmp
  dal__gemm('N', 'N', (int)n2, k2, (int)n2, Phi, (int)n2, Z, (int)n2, tmp, (int)n2);
  dal__gemm('N', 'N', k2, k2, (int)n2, P, k2, tmp, (int)n2, Mr, k2);
  return DAL_OK;
}

// the basis Z (2n x k2) of the manifold's tangent space at the evaluated state and the
// projector P (k2 x 2n) with P Z = I (see monodromy)
static int manifold_basis(const dal_system *sys, dal_state *st, double *Z, double *P) {
  dal_tangent *tg = NULL;
  if (dal__tangent_create(sys, &tg)) return DAL_FAIL(st, DAL_E_NOMEM, "floquet: out of memory");
  int rc = dal__tangent_eval(sys, st, tg, 0);
  if (!rc) rc = dal__tangent_on_manifold(sys, st, tg, "floquet");
  if (!rc) rc = dal__tangent_manifold(sys, st, tg, Z, P);
  dal__tangent_free(tg);
  return rc;
}

// eigenvalues of the k2 x k2 matrix Mr (copied into work), sorted
static int mult_eig(dal_state *st, int k2, const double *Mr, double *work, double *re, double *im) {
  memcpy(work, Mr, (size_t)k2 * (size_t)k2 * sizeof(double));
  lapack_int info =
      LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', k2, work, k2, re, im, NULL, 1, NULL, 1);
  if (info != 0)
    return DAL_FAIL(st, DAL_E_SINGULAR,
                    "floquet: LAPACK dgeev did not converge on the monodromy (info %d)", (int)info);
  sort_mult(k2, re, im);
  return DAL_OK;
}

// the verdict from the multipliers and their accuracy (see dal_floquet_report)
dal_stability dal__floquet_verdict(int k2, const double *re, const double *im, double acc,
                                   int skip1, int skip2, double *max_abs) {
  double big = 0.0, small = INFINITY;
  int edge = 0;
  for (int i = 0; i < k2; ++i) {
    if (i == skip1 || i == skip2) continue;
    double a = hypot(re[i], im[i]);
    big = fmax(big, a);
    small = fmin(small, a);
    // on the unit circle within the accuracy and within it of +1 or -1: a pair there may
    // leave the circle (a period-doubling or fold boundary)
    if (fabs(a - 1.0) <= acc &&
        (hypot(re[i] - 1.0, im[i]) <= 2 * acc || hypot(re[i] + 1.0, im[i]) <= 2 * acc))
      edge = 1;
  }
  *max_abs = big;
  if (big == 0.0 && small == INFINITY) return DAL_NEUTRAL; // every multiplier skipped
  if (big > 1.0 + acc) return DAL_UNSTABLE;
  if (big < 1.0 - acc) return DAL_ASYMPTOTIC;
  return edge ? DAL_MARGINAL : DAL_NEUTRAL;
}

int dal_floquet(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double period,
                double *mu_re, double *mu_im, double *monodromy_out, dal_floquet_report *rep) {
  int rc = dal__check_pair(sys, st, "floquet");
  if (rc) return rc;
  if (!isfinite(period) || !(period > 0))
    return DAL_FAIL(st, DAL_E_ARG, "floquet: the period %g must be finite and > 0", period);
  int n = sys->n, k = n - sys->m;
  if (k <= 0)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "floquet: the system has no degrees of freedom (%d constraint row(s) on %d "
                    "coordinate(s)): no multipliers",
                    sys->m, n);
  // the two runs: at the requested tolerance and 10x looser (the accuracy is their distance)
  dal_solve_opts oa = opts ? *opts : dal_default_solve_opts(), ob;
  if (!opts) oa.rtol = 1e-10;
  if ((rc = dal__check_opts(st, &oa)) != 0) return rc;
  ob = oa;
  ob.rtol = fmin(10 * oa.rtol, 0.1);
  if (oa.atol > 0) ob.atol = 10 * oa.atol;
  size_t sn = (size_t)n, n2 = 2 * sn, k2 = 2 * (size_t)k;
  double *buf =
      malloc((3 * n2 * n2 + 4 * n2 * k2 + 3 * k2 * k2 + 4 * k2 + 3 * n2 + 1) * sizeof(double));
  int *used = malloc((k2 + 1) * sizeof(int));
  if (!buf || !used) {
    free(buf);
    free(used);
    return DAL_FAIL(st, DAL_E_NOMEM, "floquet: out of memory");
  }
  double *Phi = buf, *tmp = Phi + n2 * n2, *Z = tmp + n2 * n2, *P = Z + n2 * k2;
  double *Ma = P + n2 * k2, *Mb = Ma + k2 * k2, *work = Mb + k2 * k2;
  double *ar = work + k2 * k2, *ai = ar + k2, *br = ai + k2, *bi = br + k2;
  double *y0 = bi + k2, *yA = y0 + n2, *yB = yA + n2, t0 = st->t;
  memcpy(y0, st->q, sn * sizeof(double));
  memcpy(y0 + sn, st->qdot, sn * sizeof(double));
  if ((rc = dal__analysis_eval(sys, st, t0, y0, y0 + sn)) != 0) goto done;
  if (sys->m > 0 && (rc = manifold_basis(sys, st, Z, P)) != 0) goto done;
  if ((rc = monodromy(sys, st, &oa, t0, y0, period, Z, P, Phi, tmp, Ma, yA)) != 0) goto done;
  if ((rc = monodromy(sys, st, &ob, t0, y0, period, Z, P, Phi, tmp, Mb, yB)) != 0) goto done;
  if ((rc = mult_eig(st, (int)k2, Ma, work, ar, ai)) != 0) goto done;
  if ((rc = mult_eig(st, (int)k2, Mb, work, br, bi)) != 0) goto done;
  // the return gap: a Floquet analysis needs a T-periodic solution through the state
  double gap = 0.0, dy = 0.0, mnorm = 0.0;
  int gi = 0;
  for (size_t i = 0; i < n2; ++i) {
    double g = fabs(yA[i] - y0[i]) / (1.0 + fabs(y0[i]));
    if (g > gap) {
      gap = g;
      gi = (int)i;
    }
    dy = fmax(dy, fabs(yA[i] - yB[i]) / (1.0 + fabs(y0[i])));
  }
  for (size_t i = 0; i < k2 * k2; ++i)
    mnorm += Ma[i] * Ma[i];
  mnorm = sqrt(mnorm);
  double gap_tol = 1e-6 + 1e3 * oa.rtol + 10 * dy;
  if (!(gap <= gap_tol)) {
    rc = DAL_FAIL(st, DAL_E_ARG,
                  "floquet: the state does not return after the period T=%.17g: |y(T) - y(0)| "
                  "= %.3g (relative, %s of '%s') against %.3g: it is not on a T-periodic "
                  "solution; check the period (a multiple of the drive's), or find the orbit "
                  "first (dal_periodic_orbit, dalembert orbit)",
                  period, gap, (size_t)gi < sn ? "position" : "velocity",
                  sys->coord_names[(size_t)gi % sn], gap_tol);
    goto done;
  }
  double acc = fmax(dal__match_distance((int)k2, ar, ai, br, bi, used), 1e3 * DBL_EPSILON * mnorm);
  dal_floquet_report r;
  memset(&r, 0, sizeof r);
  r.count = (int)k2;
  r.period = period;
  r.accuracy = acc;
  r.gap = gap;
  r.verdict = dal__floquet_verdict((int)k2, ar, ai, acc, -1, -1, &r.max_abs);
  double complex det = 1.0;
  for (size_t i = 0; i < k2; ++i) {
    det *= ar[i] + I * ai[i];
    r.trace += ar[i];
  }
  r.det = creal(det);
  if (mu_re) memcpy(mu_re, ar, k2 * sizeof(double));
  if (mu_im) memcpy(mu_im, ai, k2 * sizeof(double));
  if (monodromy_out) memcpy(monodromy_out, Ma, k2 * k2 * sizeof(double));
  if (rep) *rep = r;
done:
  // the state back at its start, evaluated
  rc = dal__restore_state(sys, st, t0, y0, rc);
  free(buf);
  free(used);
  return rc;
}

const char *dal_floquet_verdict_name(dal_stability s) {
  switch (s) {
  case DAL_UNSTABLE:
    return "unstable";
  case DAL_MARGINAL:
    return "boundary";
  case DAL_NEUTRAL:
    return "stable";
  case DAL_ASYMPTOTIC:
    return "asymptotically stable";
  }
  return "unknown";
}

int dal__equilibrium_all_times(const dal_system *sys, dal_state *st, double *worst_out,
                               double *t_out) {
  int n = sys->n, m = sys->m, d = sys->dim;
  size_t sn = (size_t)n;
  double *y = calloc(2 * sn + 4 * sn * sn + 1, sizeof(double)), *A = y + 2 * sn;
  if (!y) return DAL_FAIL(st, DAL_E_NOMEM, "equilibrium: out of memory");
  memcpy(y, st->q, sn * sizeof(double));
  double t0 = st->t, worst = 0.0, wt = t0, qs = 0.0;
  for (int i = 0; i < n; ++i)
    qs = fmax(qs, fabs(y[i]));
  qs += 1.0;
  unsigned long long seed = 0x2545f4914f6cdd1dULL;
  int rc = DAL_OK;
  for (int p = 0; p < DAL_TD_PROBES && rc == DAL_OK; ++p) {
    double t = t0 + 7.0 * td_urand(&seed);
    if ((rc = dal__analysis_eval(sys, st, t, y, y + sn)) != 0) break;
    const double *M = dal_state_mass_matrix(st);
    // force scale per sqrt(mass): applied forces and the drive's accelerations at qdot = 0
    double fs = 0.0, mt = 0.0;
    for (int k = 0; k < sys->N; ++k) {
      double f2 = 0.0, g2 = 0.0, mk = st->prm.mass[k];
      for (int a = 0; a < d; ++a) {
        f2 += st->F[k * d + a] * st->F[k * d + a];
        g2 += st->gamma[k * d + a] * st->gamma[k * d + a];
      }
      if (mk > 0) fs += sqrt(f2 / mk) + sqrt(mk * g2);
      mt += mk;
    }
    double as = mt > 0 ? fs / sqrt(mt) : fs, vs = sqrt(as * qs) + 1e-300;
    fs += 1e-300;
    // without constraint rows: qddot_i against the change a move by 1 + |q| makes,
    // sum_j |df_i/dq_j| (1 + |q|) (near the origin the forces themselves vanish)
    if (m == 0) {
      if ((rc = dal_vector_field_jacobian(sys, st, A, NULL)) != 0) break;
      for (int i = 0; i < n; ++i) {
        double s = 0.0;
        for (int j = 0; j < n; ++j)
          s += fabs(A[(size_t)j * 2 * n + n + i]);
        double r = fabs(st->qddot[i]) / (s * qs + 1e-300);
        if (!(r <= worst)) worst = r, wt = t;
      }
      continue;
    }
    // with them: (M qddot)_i / sqrt(M_ii) against fs, phi against 1 + |q|, dphi/dt
    // (= G qdot + phi_t at qdot = 0) against the velocity scale sqrt(a L)
    for (int i = 0; i < n; ++i) {
      double s = 0.0, mii = sqrt(fabs(M[(size_t)i * n + i])) + 1e-300;
      for (int j = 0; j < n; ++j)
        s += M[(size_t)j * n + i] * st->qddot[j];
      double r = fabs(s) / mii / fs;
      if (!(r <= worst)) worst = r, wt = t;
    }
    for (int r = 0; r < m; ++r) {
      double a = fabs(st->phi[r]) / qs, b = fabs(st->phidot[r]) / vs;
      if (!(a <= worst)) worst = a, wt = t;
      if (!(b <= worst)) worst = b, wt = t;
    }
  }
  rc = dal__restore_state(sys, st, t0, y, rc);
  free(y);
  if (worst_out) *worst_out = worst;
  if (t_out) *t_out = wt;
  if (rc) return rc;
  return worst <= 1e-8;
}
