// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The standard Lagrange form: accelerations from L(t, q, qdot) by jets, and the residual
// of Lagrange's equations along a proposed path (SICM 1.7, Lagrangian->state-derivative).
//
// Lagrange's equations expand to A qddot + X = dL/dq + Q_nc with A = d2L/dqdot2 and
// X_i = d2L/dqdot_i dq . qdot + d2L/dqdot_i dt. Second partials come from second directional
// derivatives by polarization: u'Hw = (D2(u + w) - D2(u) - D2(w)) / 2.
#include <math.h>
#include <string.h>

#include "internal.h"

// evaluate L with the jets currently in st->jq, st->jv and time jet t; check finiteness
static int lag_eval(const dal_system *sys, dal_state *st, dal_jet t, dal_jet *L) {
  int rc = sys->lag(t, st->jq, st->jv, L, sys->lag_ctx);
  if (rc) return dal__cb_status(st, rc, "Lagrangian");
  if (!dal_jet_isfinite(*L)) {
    char qs[256];
    dal__fmt_q(sys, st->q, qs, sizeof qs);
    // huge inputs: an overflow (a trial step too long), not a domain error of L
    double big = fmax(dal__jets_max(st->jq, sys->n), dal__jets_max(st->jv, sys->n));
    if (big > DAL_JET_OVERFLOW)
      return DAL_FAIL(st, DAL__RETRY_NONFINITE,
                      "Lagrangian overflows at t=%.17g, %s: its inputs reach %g (coordinates "
                      "or velocities whose products exceed double range)",
                      st->t, qs, big);
    return DAL_FAIL(st, DAL_E_DOMAIN,
                    "Lagrangian produced a non-finite value or derivative at t=%.17g, %s",
                    st->t, qs);
  }
  return DAL_OK;
}

int dal__lagrangian_terms(const dal_system *sys, dal_state *st, double *A, double *rhs,
                          double *h_out) {
  int n = sys->n, rc;
  dal_jet L;
  dal_jet t0 = dal_const(st->t), tw = dal_var(st->t, 1.0);
  for (int i = 0; i < n; ++i) {
    st->jq[i] = dal_const(st->q[i]);
    st->jv[i] = dal_const(st->qdot[i]);
  }
  // A_ii = D2 along velocity direction e_i
  for (int i = 0; i < n; ++i) {
    st->jv[i].d = 1.0;
    rc = lag_eval(sys, st, t0, &L);
    st->jv[i].d = 0.0;
    if (rc) return rc;
    A[(size_t)i * n + i] = L.dd;
  }
  // off-diagonal A_ij by polarization
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      st->jv[i].d = 1.0;
      st->jv[j].d = 1.0;
      rc = lag_eval(sys, st, t0, &L);
      st->jv[i].d = 0.0;
      st->jv[j].d = 0.0;
      if (rc) return rc;
      double aij = 0.5 * (L.dd - A[(size_t)i * n + i] - A[(size_t)j * n + j]);
      A[(size_t)j * n + i] = aij;
      A[(size_t)i * n + j] = aij;
    }
  // w = (dq = qdot, dt = 1): W = D2(w), X_i = (D2(e_i^v + w) - A_ii - W) / 2
  for (int i = 0; i < n; ++i) st->jq[i].d = st->qdot[i];
  rc = lag_eval(sys, st, tw, &L);
  if (rc) return rc;
  double W = L.dd;
  for (int i = 0; i < n; ++i) {
    st->jv[i].d = 1.0;
    rc = lag_eval(sys, st, tw, &L);
    st->jv[i].d = 0.0;
    if (rc) return rc;
    rhs[i] = -0.5 * (L.dd - A[(size_t)i * n + i] - W);
  }
  for (int i = 0; i < n; ++i) st->jq[i].d = 0.0;
  // dL/dq_i by first derivatives
  for (int i = 0; i < n; ++i) {
    st->jq[i].d = 1.0;
    rc = lag_eval(sys, st, t0, &L);
    st->jq[i].d = 0.0;
    if (rc) return rc;
    rhs[i] += L.d;
  }
  // energy function h = qdot . dL/dqdot - L in one evaluation along dv = qdot; the second
  // derivative along the same direction is qdot' A qdot = 2 T2
  for (int i = 0; i < n; ++i) st->jv[i].d = st->qdot[i];
  rc = lag_eval(sys, st, t0, &L);
  if (rc) return rc;
  *h_out = L.d - L.v;
  double L1 = L.v, T2 = 0.5 * L.dd, L0 = NAN;
  {
    // energies read off L (system.h): L(t, q, 0) in one more evaluation
    for (int i = 0; i < n; ++i) st->jv[i] = dal_const(0.0);
    rc = lag_eval(sys, st, t0, &L);
    for (int i = 0; i < n; ++i) st->jv[i] = dal_const(st->qdot[i]);
    if (rc) return rc;
    L0 = L.v;
  }
  // non-conservative generalized forces (and any U(q,t))
  memset(st->Q, 0, (size_t)n * sizeof(double));
  double U = 0.0;
  rc = dal__genforces(sys, st, &U, NULL);
  if (rc) return rc;
  *h_out += U;
  for (int i = 0; i < n; ++i) rhs[i] += st->Q[i];
  st->en.T = L1 - L0;
  st->en.U = U - L0;
  st->en.T2 = T2;
  st->en.T1 = st->en.T - T2;
  st->en.T0 = 0.0;
  return DAL_OK;
}

// never DAL_OK with a non-finite residual: a path whose accelerations or speeds are too large
// for double precision makes M qddot + c - Q overflow
static int residual_finite(const dal_system *sys, dal_state *st, const double *res, double t) {
  for (int i = 0; i < sys->n; ++i)
    if (!isfinite(res[i]))
      return DAL_FAIL(st, DAL_E_NONFINITE,
                      "lagrange_residual: the residual of coordinate '%s' overflows (%g) at "
                      "t=%.17g: the path's velocities or accelerations are too large for double "
                      "precision",
                      sys->coord_names[i], res[i], t);
  return DAL_OK;
}

int dal_lagrange_residual(const dal_system *sys, dal_state *st, dal_path_q_fn *path, double t,
                          double *res, void *ctx) {
  int pair = dal__check_pair(sys, st, "lagrange_residual");
  if (pair) return pair;
  if (!path || !res) return DAL_FAIL(st, DAL_E_ARG, "lagrange_residual: path or res is NULL");
  if (!isfinite(t)) return DAL_FAIL(st, DAL_E_NONFINITE, "lagrange_residual: t is %g", t);
  int n = sys->n, rc;
  // the path's local tuple at t: q, qdot, qddot
  rc = path(dal_var(t, 1.0), st->jq, ctx);
  if (rc) return DAL_FAIL(st, DAL_E_CALLBACK, "proposed path failed (returned %d) at t=%.17g",
                          rc, t);
  double *qdd = st->work;
  for (int i = 0; i < n; ++i) {
    if (!dal_jet_isfinite(st->jq[i]))
      return DAL_FAIL(st, DAL_E_DOMAIN, "proposed path: coordinate '%s' is not finite at "
                                        "t=%.17g", sys->coord_names[i], t);
    st->q[i] = st->jq[i].v;
    st->qdot[i] = st->jq[i].d;
    qdd[i] = st->jq[i].dd;
  }
  st->t = t;
  dal__integ_reset(st);
  dal__state_moved(st);
  if (sys->lag) {
    double h, *rhs = st->work + n;
    rc = dal__lagrangian_terms(sys, st, st->M, rhs, &h);
    st->have |= DAL_P_M | DAL_P_MLOW;
    if (rc) return dal__public_status(rc);
    for (int i = 0; i < n; ++i) {
      double s = -rhs[i];
      for (int j = 0; j < n; ++j) s += st->M[(size_t)j * n + i] * qdd[j];
      res[i] = s;
    }
    return residual_finite(sys, st, res, t);
  }
  if ((rc = dal__eval(sys, st, DAL_P_J | DAL_P_DYN)) != 0)
    return dal__public_status(rc);
  dal__mass_apply(sys, st, qdd, res);
  for (int i = 0; i < n; ++i) res[i] += st->c[i] - st->Q[i];
  return residual_finite(sys, st, res, t);
}
