// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The exact tangent of a system given by a Lagrangian L(t, q, qdot), by jets of order 3.
//
// In the space p = (q, qdot, t) (2n + 1 coordinates) Lagrange's equations read
//   R_j = D^2 L[x_j, w] - D L[(e_j, 0, 0)] - Q_j = 0,  x_j = (0, e_j, 0),  w = (qdot, qddot, 1),
// (w is the velocity of the state's curve in p; Q_j = -dU/dq_j of the potentials U(q, t)).
// Along a direction z = (dq, dqdot, dt) at fixed qddot, w changes by w' = (dqdot, 0, 0), so
//   dR_j[z] = D^3 L[x_j, w, z] + D^2 L[x_j, w'] - D^2 L[(e_j, 0, 0), z] + D^2 U[e_j, (dq, dt)].
// With v = x_j + w or x_j - w, 4 D^2 L(p)[x_j, w] = D^2 L(p)[v+]^2 - D^2 L(p)[v-]^2, and the
// derivative along z of D^2 L(p + e z)[v + e v']^2 is g_ess of g(e, s) = L(p + e z + s (v + e v'));
// on the curves e = l s, l = +-1, it is ((h_1''' - h_-1''')/2 - D^3 L[z]^3) / 3 with
// h_l(s) = L(p + s (v + l z) + s^2 l v') (see tangent.c for the expansion). Second
// partials of L (and of U) come from order-2 coefficients by polarization.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "form.h"

// L along the curve p + s d + s^2/2 dd in (q, qdot, t) (2n + 1 entries each; dd may be NULL)
static int lag_curve(const dal_system *sys, dal_state *st, dal_tangent *tg, const double *d,
                     const double *dd, int order3, dal_jet *L) {
  int n = sys->n;
  for (int i = 0; i < n; ++i) {
    tg->jq[i] = dal_jet_make3(st->q[i], d[i], dd ? dd[i] : 0.0, 0.0);
    tg->jv[i] = dal_jet_make3(st->qdot[i], d[n + i], dd ? dd[n + i] : 0.0, 0.0);
  }
  dal_jet t = dal_jet_make3(st->t, d[2 * n], dd ? dd[2 * n] : 0.0, 0.0);
  int rc = sys->lag(t, tg->jq, tg->jv, L, sys->lag_ctx);
  char qs[256];
  if (rc) {
    dal__fmt_q(sys, st->q, qs, sizeof qs);
    return DAL_FAIL(st, DAL_E_CALLBACK,
                    "the Lagrangian returned %d during the tangent evaluation at t=%.17g, %s", rc,
                    st->t, qs);
  }
  if (!(order3 ? dal_jet_isfinite3(*L) : dal_jet_isfinite(*L))) {
    dal__fmt_q(sys, st->q, qs, sizeof qs);
    if (dal_jet_isfinite(*L))
      return DAL_FAIL(st, DAL_E_DOMAIN,
                      "the Lagrangian gives no third derivative (d3 = %g at t=%.17g, %s): it "
                      "builds jets with dal_jet_make or dal_jet_chain; the exact tangent needs "
                      "it: use dal_jet_make3 / dal_jet_chain3, or the dal_* operations",
                      L->d3, st->t, qs);
    return DAL_FAIL(st, DAL_E_DOMAIN,
                    "the Lagrangian produced a non-finite value or derivative (%g, %g, %g) at "
                    "t=%.17g, %s, along a tangent curve",
                    L->v, L->d, L->dd, st->t, qs);
  }
  return DAL_OK;
}

// sum of the potentials U(q, t) along the line (q + s dq, t + s dt)
static int potq_line(const dal_system *sys, dal_state *st, dal_tangent *tg, const double *dq,
                     double dt, dal_jet *U) {
  dal_jet s = dal_const(0.0), u;
  for (int i = 0; i < sys->n; ++i)
    tg->jq[i] = dal_var(st->q[i], dq[i]);
  for (int k = 0; k < sys->npotq; ++k) {
    int rc = sys->potq[k].fn.potq(tg->jq, dal_var(st->t, dt), &u, sys->potq[k].ctx);
    if (rc)
      return DAL_FAIL(st, DAL_E_CALLBACK,
                      "potential U(q,t) returned %d during the tangent evaluation at t=%.17g", rc,
                      st->t);
    if (!dal_jet_isfinite(u))
      return DAL_FAIL(st, DAL_E_DOMAIN, "potential U(q,t) is not finite at t=%.17g", st->t);
    s = dal_add(s, u);
  }
  *U = s;
  return DAL_OK;
}

// the Hessian of L over (q, qdot, t) into tg->HL (its rounding scales into tg->HLabs):
// diagonal along e_i, off-diagonal by polarization; - dL/dq_i into tg->res
static int lagrangian_hessian(const dal_system *sys, dal_state *st, dal_tangent *tg) {
  int n = sys->n, np = 2 * n + 1, rc;
  size_t ld = (size_t)np;
  double *HL = tg->HL, *Ha = tg->HLabs, *d = tg->dr; // dr: scratch of 2n + 1 here
  dal_jet L;
  for (int i = 0; i < np; ++i) {
    memset(d, 0, ld * sizeof(double));
    d[i] = 1.0;
    if ((rc = lag_curve(sys, st, tg, d, NULL, 0, &L)) != 0) return rc;
    HL[i * ld + i] = L.dd;
    Ha[i * ld + i] = fabs(L.dd);
    if (i < n) tg->res[i] = -L.d; // - dL/dq_i
  }
  for (int i = 0; i < np; ++i)
    for (int j = i + 1; j < np; ++j) {
      memset(d, 0, ld * sizeof(double));
      d[i] = d[j] = 1.0;
      if ((rc = lag_curve(sys, st, tg, d, NULL, 0, &L)) != 0) return rc;
      HL[j * ld + i] = HL[i * ld + j] = 0.5 * (L.dd - HL[i * ld + i] - HL[j * ld + j]);
      Ha[j * ld + i] = Ha[i * ld + j] = 0.5 * (fabs(L.dd) + Ha[i * ld + i] + Ha[j * ld + j]);
    }
  return DAL_OK;
}

// the Hessian of the potentials U(q, t) in (q, t) into tg->H (index n = time), and dU/dq
// added to tg->res
static int potential_hessian(const dal_system *sys, dal_state *st, dal_tangent *tg) {
  int n = sys->n, nt = n + 1, rc;
  size_t ldh = (size_t)n + 1;
  double *dq = tg->dF;
  dal_jet U;
  for (int i = 0; i < nt; ++i) {
    memset(dq, 0, (size_t)n * sizeof(double));
    if (i < n) dq[i] = 1.0;
    if ((rc = potq_line(sys, st, tg, dq, i == n, &U)) != 0) return rc;
    tg->H[i * ldh + i] = U.dd;
    if (i < n) tg->res[i] += U.d;
  }
  for (int i = 0; i < nt; ++i)
    for (int j = i + 1; j < nt; ++j) {
      memset(dq, 0, (size_t)n * sizeof(double));
      if (i < n) dq[i] = 1.0;
      if (j < n) dq[j] = 1.0;
      if ((rc = potq_line(sys, st, tg, dq, (i == n) + (j == n), &U)) != 0) return rc;
      tg->H[j * ldh + i] = tg->H[i * ldh + j] =
          0.5 * (U.dd - tg->H[i * ldh + i] - tg->H[j * ldh + j]);
    }
  return DAL_OK;
}

int dal__tangent_lagrangian(const dal_system *sys, dal_state *st, dal_tangent *tg, int want_t) {
  int n = sys->n, np = 2 * n + 1, rc;
  size_t ld = (size_t)np;
  double *HL = tg->HL, *d = tg->dr, *dd = tg->dv; // dr, dv: scratch of 2n + 1 here
  dal_jet L;
  // Hessian of L over (q, qdot, t), and - dL/dq into tg->res
  double *Ha = tg->HLabs;
  if ((rc = lagrangian_hessian(sys, st, tg)) != 0) return rc;
  // M = d2L/dqdot2, and R_j = D^2 L[x_j, w] - dL/dq_j (+ dU/dq_j below)
  double *w = tg->da; // 2n + 1 entries
  for (int i = 0; i < n; ++i) {
    w[i] = st->qdot[i];
    w[n + i] = st->qddot[i];
  }
  w[2 * n] = 1.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j)
      tg->M[(size_t)j * n + i] = HL[(n + j) * ld + n + i];
    double s = 0.0;
    for (int c = 0; c < np; ++c)
      s += HL[c * ld + n + i] * w[c];
    tg->res[i] += s;
  }
  // potentials U(q, t): their Hessian in (q, t) into tg->H (index n = time)
  size_t ldh = (size_t)n + 1;
  if (sys->npotq > 0 && (rc = potential_hessian(sys, st, tg)) != 0) return rc;

  // each direction z: e_i in q (i < n), in qdot (n <= i < 2n), in t (i = 2n)
  int ndir = want_t ? np : 2 * n;
  for (int z = 0; z < ndir; ++z) {
    // the third derivative along the straight line p + s z
    memset(d, 0, ld * sizeof(double));
    d[z] = 1.0;
    if ((rc = lag_curve(sys, st, tg, d, NULL, 1, &L)) != 0) return rc;
    double pz = L.d3;
    int udir = z >= n && z < 2 * n;
    double *col = z < n ? tg->Rq + (size_t)z * n : udir ? tg->Ru + (size_t)(z - n) * n : tg->Rt;
    double *cabs = z < n ? tg->Kabs + (size_t)z * n : udir ? tg->Cabs + (size_t)(z - n) * n : NULL;
    for (int j = 0; j < n; ++j) {
      double ge[2], gabs = 0.0;
      for (int sg = 0; sg < 2; ++sg) {
        double sign = sg ? -1.0 : 1.0, h[2];
        // v = x_j +- w, v' = +- (dqdot, 0, 0): dqdot is z's qdot component
        for (int l = 0; l < 2; ++l) {
          double lam = l ? -1.0 : 1.0;
          for (int c = 0; c < np; ++c) {
            d[c] = sign * w[c] + (c == n + j ? 1.0 : 0.0) + (c == z ? lam : 0.0);
            dd[c] = 0.0;
          }
          if (udir) dd[z - n] = 2.0 * lam * sign; // 2 l v' in the q slot of dqdot's index
          if ((rc = lag_curve(sys, st, tg, d, dd, 1, &L)) != 0) return rc;
          h[l] = L.d3;
          gabs += fabs(L.d3);
        }
        ge[sg] = (0.5 * (h[0] - h[1]) - pz) / 3.0;
      }
      double s = 0.25 * (ge[0] - ge[1]) - HL[z * ld + j];
      double sa = 0.25 * gabs + Ha[z * ld + j];
      if (sys->npotq > 0 && !udir) {
        int zi = z < n ? z : n; // U depends on (q, t) only
        s += tg->H[zi * ldh + j];
        sa += fabs(tg->H[zi * ldh + j]);
      }
      col[j] = s;
      if (cabs) cabs[j] = sa;
    }
  }
  return DAL_OK;
}
