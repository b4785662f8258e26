// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Variational integrator of the midpoint discrete Lagrangian in minimal coordinates.
//
// Discrete mechanics (Marsden and West, Discrete mechanics and variational integrators, Acta
// Numerica 10, 357-514 (2001), sec. 1.3, 1.6 and 3.2): with the midpoint discrete Lagrangian
//   L_d(q0, q1) = h L(qm, v, t + h/2),  qm = (q0 + q1) / 2,  v = (q1 - q0) / h,
// and the discrete Lagrange-d'Alembert forcing f_d^- = f_d^+ = (h/2) Q(qm, v, t + h/2) of
// the non-conservative generalized forces Q, the position-momentum form of the discrete
// Euler-Lagrange equations, p0 = -D1 L_d - f_d^-, p1 = D2 L_d + f_d^+, reads
//   L_v - (h/2) (L_q + Q) = p0,   p1 = p0 + h (L_q + Q),     all at (qm, v, t + h/2).
// The first is solved for the increment D = q1 - q0 by Newton's method with the matrix
//   h dR/dD = L_vv + (h/2) (L_vq - L_qv) - (h^2/4) L_qq   (L_vq[i][j] = d2L/dv_i dq_j),
// then q and p are updated by compensated summation. The map (q0, p0) -> (q1, p1) is
// symplectic and conserves the momentum of every symmetry of L (discrete Noether theorem)
// whenever Q = 0 (Marsden-West, sec. 1.3.2 and 1.3.3); the method is symmetric and of second
// order. The state's qdot is the continuous Legendre transform's inverse of p:
// p = dL/dqdot (q, qdot, t).
//
// Where L's derivatives come from:
//  - a Lagrangian system (dal_builder_set_lagrangian, potentials U(q, t) subtracted): L is a
//    jet function of (q, v) as independent inputs, so its gradient and its whole Hessian in
//    z = (q, v) come from second directional derivatives by polarization,
//    z_a' H z_b = (D2(e_a + e_b) - D2(e_a) - D2(e_b)) / 2  (2n^2 + n evaluations of L):
//    Newton with the exact matrix, quadratic convergence.
//  - a particle system: L = sum m_k |v_k|^2 / 2 - U is not a jet function of (q, v): its
//    velocities v_k = J_k(q) v + dr_k/dt are first derivatives of the maps, so L_qq would need
//    third derivatives of the maps, one order beyond the jets. The residual is still exact:
//    L_v = sum m_k J_k' v_k from the particle Jacobians, and L_q + Q = T_q + Q with Q from
//    d'Alembert's generalized forces (potentials, springs, dampers, callbacks: everything
//    dal_forward sums) and T_q,j = sum m_k v_k . dv_k/dq_j, where
//    dv_k/dq_j = r_k''[(v, 1), (e_j, 0)] = (gamma_k(v + s e_j) - gamma_k(v - s e_j)) / (4 s)
//    is exact algebra (gamma_k(w), the curvature term along (w, 1), is a quadratic form in w),
//    not a difference quotient. The Newton matrix keeps every term of order h^0 and h^1:
//    M + (h/2) (L_vq - L_qv), whose antisymmetric (gyroscopic) part is
//    sum m_k (J_k[:,i] . dv_k/dq_j - J_k[:,j] . dv_k/dq_i); only the (h^2/4) L_qq term is left
//    out, so the iteration converges linearly with factor about (h omega)^2 / 4 for the
//    fastest frequency omega (and fails, DAL_E_CONV, beyond h omega ~ 2).
//  - non-conservative forces enter the residual exactly; their derivatives are not in the
//    Newton matrix (user callbacks are plain functions, not jets), which only slows the
//    convergence by a factor of order h |dQ/dqdot| / M.
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/linalg.h"
#include "symplectic.h"

/// Newton iterations of one step before giving up
#define VAR_MAXIT 50
/// consecutive growing corrections that count as divergence
#define VAR_MAXGROW 3
/// iterations of the inverse Legendre transform (Lagrangian route)
#define VAR_LEG_MAXIT 30

#define EPS DBL_EPSILON

// The method's state x: besides (q, p) it carries what the next step starts from, so that a
// step from a copy (an off-grid output, a failed attempt) leaves the trajectory bit for bit:
//   x = (q (n), p (n), vg1 (n), vg2 (n), tg1, tg2, ng, C (n x n, particle route only))
// vg1, vg2: midpoint velocities of the last two steps at times tg1, tg2 (ng of them known),
// the Newton predictor; C: the secant estimate of -L_qq / 4 (see secant()).
enum { X_VG1 = 2, X_VG2 = 3, X_HIST = 4 };

typedef struct var_mem {
  dal_state *st;
  int n, Nd, lag, nx;
  double *D, *dlt, *qm, *v, *Lv, *F, *R, *Qg, *qdot; // n each
  double *B, *S, *L;                                 // n x n
  double *sk, *Rk, *yk; // the last Newton correction, residual, and the secant's y (n)
  double *Hz;           // (2n) x (2n), Lagrangian
  double *vk, *gp;      // N x d
  lapack_int *ipiv;     // n
} var_mem;

int dal__variational_check(const dal_system *sys, dal_state *st, const char *name) {
  if (sys->m > 0)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "method '%s' needs minimal coordinates, but the system has %d constraint "
                    "rows (first: '%s'); use DAL_METHOD_RATTLE for Cartesian particles with "
                    "constraints, or describe the scene by coordinate maps",
                    name, sys->m, sys->con[0].name);
  if (sys->n == 0)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED, "method '%s': the system has no coordinates", name);
  if (!sys->dense_M && !sys->lag)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "method '%s' solves with the dense mass matrix, which a system of %d "
                    "coordinates does not store; use an adaptive method",
                    name, sys->n);
  return DAL_OK;
}

// ---------------------------------------------------------------------------------------------
// Lagrangian route: L(t, q, v) - sum U(q, t) over jets

// evaluate at the jets in st->jq, st->jv (directions set by the caller) and time t
static int lag_eval(const dal_system *sys, dal_state *st, double t, dal_jet *out) {
  dal_jet L;
  int rc = sys->lag(dal_const(t), st->jq, st->jv, &L, sys->lag_ctx);
  if (rc) return dal__cb_status(st, rc, "Lagrangian");
  for (int i = 0; i < sys->npotq; ++i) {
    dal_jet U = dal_const(0.0);
    rc = sys->potq[i].fn.potq(st->jq, dal_const(t), &U, sys->potq[i].ctx);
    if (rc) return dal__cb_status(st, rc, "potential U(q,t)");
    L = dal_sub(L, U);
  }
  if (!dal_jet_isfinite(L)) {
    return DAL_FAIL(st, DAL_E_DOMAIN,
                    "Lagrangian (with the potentials U(q,t)) produced a non-finite value or "
                    "derivative at t=%.17g, %s",
                    t, dal__qtext(sys, st->q).s);
  }
  *out = L;
  return DAL_OK;
}

// direction e_a of z = (q, v) on (s = 1) or off (s = 0)
static void lag_dir(dal_state *st, int n, int a, double s) {
  if (a < n)
    st->jq[a].d = s;
  else
    st->jv[a - n].d = s;
}

// base point (q, v) of the jets, no direction; st's t, q, qdot name the point in messages
static void lag_base(dal_state *st, int n, double t, const double *q, const double *v) {
  st->t = t;
  for (int i = 0; i < n; ++i) {
    st->q[i] = q[i];
    st->qdot[i] = v[i];
    st->jq[i] = dal_const(q[i]);
    st->jv[i] = dal_const(v[i]);
  }
}

// gradient (Lq, Lv) and, over the index range [a0, 2n), the Hessian Hz (2n x 2n, col-major)
// by polarization; a0 = n restricts both to the velocity block
static int lag_terms(const dal_system *sys, var_mem *m, double t, int a0, double *Lq, double *Lv,
                     int hess) {
  dal_state *st = m->st;
  int n = m->n, n2 = 2 * n, rc;
  double *H = m->Hz;
  dal_jet L;
  for (int a = a0; a < n2; ++a) {
    lag_dir(st, n, a, 1.0);
    rc = lag_eval(sys, st, t, &L);
    lag_dir(st, n, a, 0.0);
    if (rc) return rc;
    if (a < n)
      Lq[a] = L.d;
    else
      Lv[a - n] = L.d;
    H[(size_t)a * n2 + a] = L.dd;
  }
  st->stats.rhs_evals += n2 - a0;
  if (!hess) return DAL_OK;
  for (int a = a0; a < n2; ++a)
    for (int b = a + 1; b < n2; ++b) {
      lag_dir(st, n, a, 1.0);
      lag_dir(st, n, b, 1.0);
      rc = lag_eval(sys, st, t, &L);
      lag_dir(st, n, a, 0.0);
      lag_dir(st, n, b, 0.0);
      if (rc) return rc;
      double hab = 0.5 * (L.dd - H[(size_t)a * n2 + a] - H[(size_t)b * n2 + b]);
      H[(size_t)b * n2 + a] = hab;
      H[(size_t)a * n2 + b] = hab;
    }
  st->stats.rhs_evals += (long)(n2 - a0) * (n2 - a0 - 1) / 2;
  return DAL_OK;
}

// non-conservative generalized forces of the user callbacks at (t, q, v), into Qg
static int lag_genforces(const dal_system *sys, var_mem *m, double t, const double *q,
                         const double *v) {
  dal_state *st = m->st;
  memset(m->Qg, 0, (size_t)m->n * sizeof(double));
  for (int i = 0; i < sys->ngenforce; ++i) {
    int rc = sys->genforces[i].fn.gen(t, q, v, m->Qg, sys->genforces[i].ctx);
    if (rc) return dal__cb_status(st, rc, "generalized force callback");
  }
  for (int j = 0; j < m->n; ++j)
    if (!isfinite(m->Qg[j]))
      return DAL_FAIL(st, DAL_E_NONFINITE,
                      "generalized force on coordinate '%s' is %g at t=%.17g; check the force "
                      "callbacks",
                      sys->coord_names[j], m->Qg[j], t);
  return DAL_OK;
}

// ---------------------------------------------------------------------------------------------
// particle route: L from the kinematics

// out (n) = sum_k m_k J_k' w_k for w (N x d); needs the compact J
static void jt_mass_apply(const dal_system *sys, const dal_state *st, const double *w,
                          double *out) {
  int d = sys->dim;
  memset(out, 0, (size_t)sys->n * sizeof(double));
  for (int k = 0; k < sys->N; ++k) {
    const int *dk = sys->pdep + sys->pdep_off[k];
    int ndk = sys->pdep_off[k + 1] - sys->pdep_off[k];
    const double *Jk = st->J + sys->pj_off[k];
    for (int a = 0; a < d; ++a) {
      double f = st->prm.mass[k] * w[k * d + a];
      for (int c = 0; c < ndk; ++c)
        out[dk[c]] += Jk[a * ndk + c] * f;
    }
  }
}

// kinematics (and dynamics) at (t, q, v)
static int part_point(const dal_system *sys, dal_state *st, double t, const double *q,
                      const double *v, int dyn) {
  st->t = t;
  memcpy(st->q, q, (size_t)sys->n * sizeof(double));
  memcpy(st->qdot, v, (size_t)sys->n * sizeof(double));
  dal__state_moved(st);
  int rc = dal__kinematics(sys, st, 1);
  if (rc == 0 && dyn) rc = dal__dynamics(sys, st, 2, NULL); // with the whole M (Newton)
  st->stats.rhs_evals++;
  return rc;
}

// Lv = L_v, F = T_q + Q at (t, q, v); with S: S[j n + i] = sum m_k J_k[:,i] . dv_k/dq_j
static int part_terms(const dal_system *sys, var_mem *m, double t, const double *q, const double *v,
                      int want_S) {
  dal_state *st = m->st;
  int n = m->n, Nd = m->Nd, d = sys->dim, rc;
  if ((rc = part_point(sys, st, t, q, v, 1)) != 0) return rc;
  memcpy(m->vk, st->v, (size_t)Nd * sizeof(double));
  jt_mass_apply(sys, st, m->vk, m->Lv);
  memcpy(m->F, st->Q, (size_t)n * sizeof(double));
  // dv_k/dq_j from the curvature terms along (v +- s e_j, 1); s keeps both of the size of v
  double s = 1.0;
  for (int i = 0; i < n; ++i)
    s = fmax(s, fabs(v[i]));
  for (int j = 0; j < n; ++j) {
    st->qdot[j] = v[j] + s;
    rc = dal__kinematics(sys, st, 1);
    if (rc == 0) {
      memcpy(m->gp, st->gamma, (size_t)Nd * sizeof(double));
      st->qdot[j] = v[j] - s;
      rc = dal__kinematics(sys, st, 1);
    }
    st->qdot[j] = v[j];
    st->stats.rhs_evals += 2;
    if (rc) return rc;
    double tq = 0.0;
    for (int e = 0; e < Nd; ++e) {
      double w = (m->gp[e] - st->gamma[e]) / (4.0 * s);
      m->gp[e] = w;
      tq += st->prm.mass[e / d] * m->vk[e] * w;
    }
    m->F[j] += tq;
    if (want_S) jt_mass_apply(sys, st, m->gp, m->S + (size_t)j * n);
  }
  return DAL_OK;
}

// ---------------------------------------------------------------------------------------------
// the step

// R = L_v - (h/2) F - p0 and the Newton matrix B = h dR/dD at (t, qm, v)
static int newton_terms(dal_ode_integ *ig, var_mem *m, double t, double h, const double *p0) {
  const dal_system *sys = ig->sys;
  int n = m->n, rc;
  if (m->lag) {
    lag_base(m->st, n, t, m->qm, m->v);
    if ((rc = lag_terms(sys, m, t, 0, m->F, m->Lv, 1)) != 0) return rc;
    if ((rc = lag_genforces(sys, m, t, m->qm, m->v)) != 0) return rc;
    int n2 = 2 * n;
    const double *H = m->Hz;
    for (int j = 0; j < n; ++j) {
      m->F[j] += m->Qg[j];
      for (int i = 0; i < n; ++i) {
        double vv = H[(size_t)(n + j) * n2 + n + i], vq = H[(size_t)j * n2 + n + i];
        double qv = H[(size_t)(n + j) * n2 + i], qq = H[(size_t)j * n2 + i];
        m->B[(size_t)j * n + i] = vv + 0.5 * h * (vq - qv) - 0.25 * h * h * qq;
      }
    }
  } else {
    if ((rc = part_terms(sys, m, t, m->qm, m->v, 1)) != 0) return rc;
    const double *M = m->st->M;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        m->B[(size_t)j * n + i] =
            M[(size_t)j * n + i] + 0.5 * h * (m->S[(size_t)j * n + i] - m->S[(size_t)i * n + j]);
  }
  for (int i = 0; i < n; ++i)
    m->R[i] = m->Lv[i] - 0.5 * h * m->F[i] - p0[i];
  return DAL_OK;
}

// Particle route: the Newton matrix lacks -(h^2/4) L_qq (third derivatives of the maps). Its
// estimate h^2 C is refined by Broyden's secant update along each Newton correction s,
// (B + h^2 C) s = y with y = h (R_new - R_old), and carried from step to step (L_qq changes
// slowly along the motion), which brings the iteration close to quadratic convergence. The
// update is skipped when s is too small for y to rise above the rounding of R.
static void secant(var_mem *m, double *C, double h, int have_s) {
  int n = m->n;
  if (have_s) {
    double ss = 0.0, smax = 0.0, dmax = 0.0;
    for (int i = 0; i < n; ++i) {
      ss += m->sk[i] * m->sk[i];
      smax = fmax(smax, fabs(m->sk[i]));
      dmax = fmax(dmax, fabs(m->D[i]));
    }
    if (smax > 1e5 * EPS * dmax && ss > 0.0) {
      // r = y - (B + h^2 C) s, then C += r s' / (h^2 s's)
      for (int i = 0; i < n; ++i) {
        double r = h * (m->R[i] - m->Rk[i]);
        for (int j = 0; j < n; ++j)
          r -= (m->B[(size_t)j * n + i] + h * h * C[(size_t)j * n + i]) * m->sk[j];
        m->yk[i] = r / (h * h * ss);
      }
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          C[(size_t)j * n + i] += m->yk[i] * m->sk[j];
    }
  }
  for (int k = 0; k < n * n; ++k)
    m->B[k] += h * h * C[k];
  memcpy(m->Rk, m->R, (size_t)n * sizeof(double));
}

// solve B x = b in place (LU with partial pivoting); names a degenerate coordinate
static int newton_solve(dal_ode_integ *ig, var_mem *m, double t, double *b) {
  int n = m->n;
  lapack_int info = LAPACKE_dgetrf_work(LAPACK_COL_MAJOR, n, n, m->B, n, m->ipiv);
  if (info == 0) info = LAPACKE_dgetrs_work(LAPACK_COL_MAJOR, 'N', n, 1, m->B, n, m->ipiv, b, n);
  if (info != 0) {
    int bad = info > 0 ? (int)info - 1 : 0;
    return DAL_FAIL(m->st, DAL_E_SINGULAR,
                    "variational step: the Newton matrix of the discrete Euler-Lagrange "
                    "equations is singular at t=%.17g, %s: coordinate '%s' is degenerate "
                    "(d2L/dqdot2 singular there, e.g. a chart singularity); use another chart "
                    "or redundant coordinates with DAL_METHOD_RATTLE",
                    t, dal__qtext(ig->sys, m->qm).s, ig->sys->coord_names[bad]);
  }
  return DAL_OK;
}

static int var_step(dal_ode_integ *ig, void *mem, double t, double h, double *x, double *c) {
  var_mem *m = mem;
  dal_state *st = m->st;
  int n = m->n, rc, grow = 0;
  double *q0 = x, *p0 = x + n, tm = t + 0.5 * h, nprev = INFINITY;
  double *vg1 = x + X_VG1 * n, *vg2 = x + X_VG2 * n, *hist = x + X_HIST * n, *C = hist + 3;
  if (h == 0.0) return DAL_OK;
  // predictor: the midpoint velocity extrapolated linearly in time from the last two steps
  double w = hist[2] >= 2 && hist[0] != hist[1] ? (tm - hist[0]) / (hist[0] - hist[1]) : 0.0;
  if (!(fabs(w) <= 4.0)) w = 0.0;
  for (int i = 0; i < n; ++i)
    m->D[i] = h * (vg1[i] + w * (vg1[i] - vg2[i]));
  for (int it = 1;; ++it) {
    for (int i = 0; i < n; ++i) {
      m->qm[i] = q0[i] + 0.5 * m->D[i];
      m->v[i] = m->D[i] / h;
    }
    if ((rc = newton_terms(ig, m, tm, h, p0)) != 0) return rc;
    if (!m->lag) secant(m, C, h, it > 1);
    for (int i = 0; i < n; ++i)
      m->dlt[i] = -h * m->R[i];
    if ((rc = newton_solve(ig, m, tm, m->dlt)) != 0) return rc;
    st->stats.nonlin_iters++;
    st->stats.jac_evals++;
    double nrm = 0.0, dmax = 0.0;
    int worst = 0;
    memcpy(m->sk, m->dlt, (size_t)n * sizeof(double));
    for (int i = 0; i < n; ++i) {
      m->D[i] += m->dlt[i];
      dmax = fmax(dmax, fabs(m->D[i]));
      if (!(fabs(m->dlt[i]) <= nrm)) {
        nrm = fabs(m->dlt[i]);
        worst = i;
      }
    }
    // converged: the correction no longer changes the increment beyond a few ulps, or it
    // stopped decreasing at the level of rounding
    if (nrm <= 4.0 * EPS * dmax) break;
    if (it >= 2 && nrm >= 0.5 * nprev && nrm <= 1e-8 * dmax) break;
    grow = nrm > nprev ? grow + 1 : 0;
    // a growing correction: the carried secant estimate does not fit here, start it afresh
    if (grow && !m->lag) memset(C, 0, (size_t)n * n * sizeof(double));
    if (!isfinite(nrm) || grow >= VAR_MAXGROW || it >= VAR_MAXIT) {
      return DAL_FAIL(st, DAL_E_CONV,
                      "variational step from t=%.17g, %s (h=%.3g): the discrete "
                      "Euler-Lagrange equations do not converge (Newton correction of '%s' "
                      "%.3g after %d iterations, %s); the step is too long for the fastest "
                      "motion (h omega > ~1) or nears a degenerate configuration: reduce "
                      "opts.fixed_step",
                      t, dal__qtext(ig->sys, q0).s, h, ig->sys->coord_names[worst], nrm, it,
                      isfinite(nrm) ? (grow >= VAR_MAXGROW ? "growing" : "not yet converged")
                                    : "not finite");
    }
    nprev = nrm;
  }
  // q1 = q0 + D, p1 = p0 + h (L_q + Q), summed with compensation
  memcpy(vg2, vg1, (size_t)n * sizeof(double));
  hist[1] = hist[0];
  hist[0] = tm;
  hist[2] = hist[2] < 2 ? hist[2] + 1 : 2;
  for (int i = 0; i < n; ++i) {
    dal__ksum(&q0[i], &c[i], m->D[i]);
    dal__ksum(&p0[i], &c[n + i], h * m->F[i]);
    vg1[i] = m->D[i] / h;
  }
  return DAL_OK;
}

// ---------------------------------------------------------------------------------------------
// Legendre transforms p = dL/dqdot (q, qdot, t)

static int var_from_y(dal_ode_integ *ig, void *mem, double t, const double *y, double *x) {
  var_mem *m = mem;
  const dal_system *sys = ig->sys;
  int n = m->n, rc;
  const double *q = y, *qd = y + n;
  memcpy(x, q, (size_t)n * sizeof(double));
  memcpy(m->qdot, qd, (size_t)n * sizeof(double));
  // the predictor starts from qdot; no secant estimate yet
  memset(x + 2 * n, 0, (size_t)(m->nx - 2 * n) * sizeof(double));
  memcpy(x + X_VG1 * n, qd, (size_t)n * sizeof(double));
  x[X_HIST * n + 2] = 1;
  if (m->lag) {
    lag_base(m->st, n, t, q, qd);
    return lag_terms(sys, m, t, n, m->F, x + n, 0);
  }
  if ((rc = part_point(sys, m->st, t, q, qd, 0)) != 0) return rc;
  jt_mass_apply(sys, m->st, m->st->v, x + n);
  return DAL_OK;
}

static int var_to_y(dal_ode_integ *ig, void *mem, double t, const double *x, double *y) {
  var_mem *m = mem;
  const dal_system *sys = ig->sys;
  dal_state *st = m->st;
  int n = m->n, rc, bad = 0;
  const double *q = x, *p = x + n;
  double *qd = y + n;
  memcpy(y, q, (size_t)n * sizeof(double));
  memcpy(qd, m->qdot, (size_t)n * sizeof(double));
  if (!m->lag) {
    // M qdot = p - b, b = sum m_k J_k' dr_k/dt (independent of qdot)
    if ((rc = part_point(sys, st, t, q, qd, 1)) != 0) {
      // the forces failed here (a callback failing from some time on): the velocities of
      // the momenta need only M, which the kinematics give; so a failure can fall back to
      // this point, the last accepted one (a cold path: M column by column)
      if (!st->M || part_point(sys, st, t, q, qd, 0) != 0) return rc;
      for (int j = 0; j < n; ++j) {
        memset(qd, 0, (size_t)n * sizeof(double));
        qd[j] = 1.0;
        dal__mass_apply(sys, st, qd, st->M + (size_t)j * n);
      }
    }
    jt_mass_apply(sys, st, st->drdt, qd);
    for (int i = 0; i < n; ++i)
      qd[i] = p[i] - qd[i];
    if (dal__chol_solve(n, st->M, m->L, qd, &bad) != 0) goto singular;
  } else {
    // Newton on dL/dqdot (q, qdot) = p with the matrix d2L/dqdot2 (one iteration when L is
    // quadratic in qdot, a second one confirms)
    double nprev = INFINITY;
    for (int it = 0;; ++it) {
      lag_base(st, n, t, q, qd);
      if ((rc = lag_terms(sys, m, t, n, m->F, m->Lv, 1)) != 0) return rc;
      int n2 = 2 * n;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          m->B[(size_t)j * n + i] = m->Hz[(size_t)(n + j) * n2 + n + i];
      for (int i = 0; i < n; ++i)
        m->dlt[i] = p[i] - m->Lv[i];
      if (dal__chol_solve(n, m->B, m->L, m->dlt, &bad) != 0) goto singular;
      double nrm = 0.0, vmax = 0.0;
      for (int i = 0; i < n; ++i) {
        qd[i] += m->dlt[i];
        if (!(fabs(m->dlt[i]) <= nrm)) {
          nrm = fabs(m->dlt[i]);
          bad = i;
        }
        vmax = fmax(vmax, fabs(qd[i]));
      }
      if (nrm <= 4.0 * EPS * vmax || (it >= 1 && nrm >= 0.5 * nprev && nrm <= 1e-8 * vmax)) break;
      if (!isfinite(nrm) || it >= VAR_LEG_MAXIT)
        return DAL_FAIL(st, DAL_E_CONV,
                        "variational method: the velocities for the momenta at t=%.17g "
                        "(dL/dqdot = p) do not converge (correction %.3g of '%s'); "
                        "d2L/dqdot2 is nearly singular there",
                        t, nrm, sys->coord_names[bad]);
      nprev = nrm;
    }
  }
  memcpy(m->qdot, qd, (size_t)n * sizeof(double));
  return DAL_OK;
singular : {
  return DAL_FAIL(st, DAL_E_SINGULAR,
                  "variational method: %s singular or not positive definite at t=%.17g, %s: "
                  "coordinate '%s' is degenerate (e.g. a chart singularity); use another chart",
                  m->lag ? "d2L/dqdot2" : "mass matrix", t, dal__qtext(sys, q).s,
                  sys->coord_names[bad]);
}
}

static void var_invalidate(void *mem) { (void)mem; }

static void var_free(void *mem) {
  var_mem *m = mem;
  if (!m) return;
  DAL_FREE(m->D, m->dlt, m->qm, m->v, m->Lv, m->F, m->R, m->Qg, m->qdot, m->B, m->S, m->L, m->Hz,
           m->vk, m->gp, m->sk, m->Rk, m->yk, m->ipiv, m);
}

int dal__variational_base(dal_ode_integ *ig, dal_symp_base *b) {
  const dal_system *sys = ig->sys;
  dal_state *st = ig->st;
  var_mem *m = calloc(1, sizeof *m);
  if (!m) return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the variational integrator");
  m->st = st;
  m->n = sys->n;
  m->Nd = sys->N * sys->dim;
  m->lag = sys->lag != NULL;
  // the particle route reads the particle Jacobians: form them on every evaluation
  m->nx = X_HIST * m->n + 3 + (m->lag ? 0 : m->n * m->n);
  // (nx, mem, from_y, to_y, step, invalidate, free)
  *b = (dal_symp_base){m->nx, m, var_from_y, var_to_y, var_step, var_invalidate, var_free};
  size_t n = (size_t)m->n + 1, nn = n * n, nd = (size_t)m->Nd + 1;
  double **vecs[] = {&m->D, &m->dlt, &m->qm,   &m->v,  &m->Lv, &m->F,
                     &m->R, &m->Qg,  &m->qdot, &m->sk, &m->Rk, &m->yk};
  int ok = 1;
  for (size_t i = 0; i < sizeof vecs / sizeof vecs[0]; ++i)
    ok &= (*vecs[i] = calloc(n, sizeof(double))) != NULL;
  m->B = calloc(nn, sizeof(double));
  m->S = calloc(nn, sizeof(double));
  m->L = calloc(nn, sizeof(double));
  m->Hz = calloc(4 * nn, sizeof(double));
  m->vk = calloc(nd, sizeof(double));
  m->gp = calloc(nd, sizeof(double));
  m->ipiv = calloc(n, sizeof(lapack_int));
  if (!ok || !m->B || !m->S || !m->L || !m->Hz || !m->vk || !m->gp || !m->ipiv)
    return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the variational integrator");
  return DAL_OK;
}
