// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The standard Lagrange form: accelerations from L(t, q, qdot) by jets (the residual of
// Lagrange's equations along a proposed path, in state.c, uses them; SICM 1.7).
//
// Lagrange's equations expand to A qddot + X = dL/dq + Q_nc with A = d2L/dqdot2 and
// X_i = d2L/dqdot_i dq . qdot + d2L/dqdot_i dt. Second partials come from second directional
// derivatives by polarization: u'Hw = (D2(u + w) - D2(u) - D2(w)) / 2. When the system has
// L's parts p = dL/dqdot and dL/dq as one function (a scene file's Lagrangian, derived
// symbolically: base.h, dal__lagrangian_parts_fn), first derivatives of p suffice: A's column j
// along qdot_j, X along the motion, n + 1 evaluations of the parts instead of n (n + 3) / 2 + 1
// of L.
#include <math.h>
#include <string.h>

#include "eval.h"

// a non-finite value or derivative of L or its parts at the state's jets
static int lag_nonfinite(const dal_system *sys, dal_state *st) {
  // huge inputs: an overflow (a trial step too long), not a domain error of L
  double big = fmax(dal__jets_max(st->jq, sys->n), dal__jets_max(st->jv, sys->n));
  if (big > DAL_JET_OVERFLOW)
    return DAL_FAIL(st, DAL__RETRY_NONFINITE,
                    "Lagrangian overflows at t=%.17g, %s: its inputs reach %g (coordinates "
                    "or velocities whose products exceed double range)",
                    st->t, dal__qtext(sys, st->q).s, big);
  return DAL_FAIL(st, DAL_E_DOMAIN,
                  "Lagrangian produced a non-finite value or derivative at t=%.17g, %s", st->t,
                  dal__qtext(sys, st->q).s);
}

// evaluate L with the jets currently in st->jq, st->jv and time jet t; check finiteness
static int lag_eval(const dal_system *sys, dal_state *st, dal_jet t, dal_jet *L) {
  int rc = sys->lag(t, st->jq, st->jv, L, sys->lag_ctx);
  if (rc) return dal__cb_status(st, rc, "Lagrangian");
  return dal_jet_isfinite(*L) ? DAL_OK : lag_nonfinite(sys, st);
}

// the parts (dL/dqdot, dL/dq) into st->jout at the state's jets; values and first derivatives
// checked (the ones read)
static int parts_eval(const dal_system *sys, dal_state *st, dal_jet t) {
  int rc = sys->lag_parts(t, st->jq, st->jv, st->jout, sys->lag_parts_ctx);
  if (rc) return dal__cb_status(st, rc, "Lagrangian");
  for (int i = 0; i < 2 * sys->n; ++i)
    if (!isfinite(st->jout[i].v) || !isfinite(st->jout[i].d)) return lag_nonfinite(sys, st);
  return DAL_OK;
}

// A and rhs = dL/dq - X from the parts: column j of A is d(dL/dqdot)/dqdot_j (its lower half,
// mirrored: the two halves are derivatives of different formulas, equal to rounding), X the
// derivative of dL/dqdot along w = (dq = qdot, dt = 1)
static int terms_by_parts(const dal_system *sys, dal_state *st, double *A, double *rhs) {
  int n = sys->n, rc;
  dal_jet t0 = dal_const(st->t);
  for (int j = 0; j < n; ++j) {
    st->jv[j].d = 1.0;
    rc = parts_eval(sys, st, t0);
    st->jv[j].d = 0.0;
    if (rc) return rc;
    for (int i = j; i < n; ++i)
      A[(size_t)j * n + i] = A[(size_t)i * n + j] = st->jout[i].d;
  }
  for (int i = 0; i < n; ++i)
    st->jq[i].d = st->qdot[i];
  rc = parts_eval(sys, st, dal_var(st->t, 1.0));
  for (int i = 0; i < n; ++i)
    st->jq[i].d = 0.0;
  if (rc) return rc;
  for (int i = 0; i < n; ++i)
    rhs[i] = st->jout[n + i].v - st->jout[i].d;
  return DAL_OK;
}

// A = d2L/dqdot2 (n x n) at the state's jets (jq, jv constant): A_ii as second derivatives
// along the velocity directions e_i, A_ij by polarization
static int velocity_hessian(const dal_system *sys, dal_state *st, dal_jet t0, double *A) {
  int n = sys->n, rc;
  dal_jet L;
  for (int i = 0; i < n; ++i) {
    st->jv[i].d = 1.0;
    rc = lag_eval(sys, st, t0, &L);
    st->jv[i].d = 0.0;
    if (rc) return rc;
    A[(size_t)i * n + i] = L.dd;
  }
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
  return DAL_OK;
}

// A and rhs = dL/dq - X from L alone: second partials by polarization
static int terms_by_polarization(const dal_system *sys, dal_state *st, double *A, double *rhs) {
  int n = sys->n, rc;
  dal_jet L, t0 = dal_const(st->t), tw = dal_var(st->t, 1.0);
  // A = d2L/dqdot2
  if ((rc = velocity_hessian(sys, st, t0, A)) != 0) return rc;
  // w = (dq = qdot, dt = 1): W = D2(w), X_i = (D2(e_i^v + w) - A_ii - W) / 2
  for (int i = 0; i < n; ++i)
    st->jq[i].d = st->qdot[i];
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
  for (int i = 0; i < n; ++i)
    st->jq[i].d = 0.0;
  // dL/dq_i by first derivatives
  for (int i = 0; i < n; ++i) {
    st->jq[i].d = 1.0;
    rc = lag_eval(sys, st, t0, &L);
    st->jq[i].d = 0.0;
    if (rc) return rc;
    rhs[i] += L.d;
  }
  return DAL_OK;
}

int dal__lagrangian_terms(const dal_system *sys, dal_state *st, double *A, double *rhs,
                          double *h_out, int energies) {
  int n = sys->n, rc;
  dal_jet L, t0 = dal_const(st->t);
  for (int i = 0; i < n; ++i) {
    st->jq[i] = dal_const(st->q[i]);
    st->jv[i] = dal_const(st->qdot[i]);
  }
  rc = sys->lag_parts ? terms_by_parts(sys, st, A, rhs) : terms_by_polarization(sys, st, A, rhs);
  if (rc) return rc;
  // energy function h = qdot . dL/dqdot - L in one evaluation along dv = qdot; the second
  // derivative along the same direction is qdot' A qdot = 2 T2. Two evaluations an
  // integrator's right-hand side does not read: only when asked for
  double L1 = NAN, T2 = NAN, L0 = NAN;
  *h_out = NAN;
  if (energies) {
    for (int i = 0; i < n; ++i)
      st->jv[i].d = st->qdot[i];
    rc = lag_eval(sys, st, t0, &L);
    if (rc) return rc;
    *h_out = L.d - L.v;
    L1 = L.v;
    T2 = 0.5 * L.dd;
    // energies read off L (system.h): L(t, q, 0) in one more evaluation
    for (int i = 0; i < n; ++i)
      st->jv[i] = dal_const(0.0);
    rc = lag_eval(sys, st, t0, &L);
    for (int i = 0; i < n; ++i)
      st->jv[i] = dal_const(st->qdot[i]);
    if (rc) return rc;
    L0 = L.v;
  }
  // non-conservative generalized forces (and any U(q,t))
  memset(st->Q, 0, (size_t)n * sizeof(double));
  double U = 0.0;
  rc = dal__genforces(sys, st, &U, NULL);
  if (rc) return rc;
  *h_out += U;
  for (int i = 0; i < n; ++i)
    rhs[i] += st->Q[i];
  if (!energies) return DAL_OK;
  st->en.T = L1 - L0;
  st->en.U = U - L0;
  st->en.T2 = T2;
  st->en.T1 = st->en.T - T2;
  st->en.T0 = 0.0;
  return DAL_OK;
}
