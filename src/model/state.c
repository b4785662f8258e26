// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Trajectory state: allocation (all workspace up front), setting, accessors, error text, and
// the Lagrange-equation residual of a proposed path.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"

int dal_state_create(const dal_system *sys, dal_state **out) {
  if (!out) return DAL_E_ARG;
  *out = NULL;
  if (!sys) return DAL_E_ARG;
  dal_state *st = calloc(1, sizeof *st);
  if (!st) return DAL_E_NOMEM;
  size_t n = (size_t)sys->n, Nd = (size_t)sys->N * (size_t)sys->dim, m = (size_t)sys->m;
  st->sys = sys;
  dal__params_init(st);
  // (q, qdot) in one block, the layout of y in the minimal and index-1 forms: their dense
  // output writes straight into it
  st->q = calloc(2 * n + 1, sizeof(double));
  st->qdot = st->q ? st->q + n : NULL;
  st->qddot = calloc(n, sizeof(double));
  st->Q = calloc(n, sizeof(double));
  st->c = calloc(n, sizeof(double));
  st->work = calloc(4 * n + 1, sizeof(double));
  st->Lc = calloc((size_t)sys->ploc_off[sys->N] + 1, sizeof(double));
  st->cf = calloc(2 * Nd + 1, sizeof(double));
  st->r = calloc(Nd + 1, sizeof(double));
  st->v = calloc(Nd + 1, sizeof(double));
  st->a = calloc(Nd + 1, sizeof(double));
  st->drdt = calloc(Nd + 1, sizeof(double));
  st->gamma = calloc(Nd + 1, sizeof(double));
  st->F = calloc(Nd + 1, sizeof(double));
  st->N = calloc(Nd + 1, sizeof(double));
  st->J = calloc(sys->store_J ? (size_t)sys->pj_off[sys->N] + 1 : 1, sizeof(double));
  st->Lp = calloc(Nd * (size_t)sys->dim + 1, sizeof(double));
  if (sys->dense_M) {
    st->M = calloc(n * n, sizeof(double));
    st->L = calloc(n * n, sizeof(double));
  }
  if (m) {
    st->lambda = calloc(m, sizeof(double));
    st->phi = calloc(m, sizeof(double));
    st->phidot = calloc(m, sizeof(double));
    st->gphi = calloc(m, sizeof(double));
    st->G = calloc((size_t)sys->g_total + 1, sizeof(double));
    st->Gl = calloc((size_t)sys->con_loff[sys->ncon] + 1, sizeof(double));
    st->phit = calloc(m, sizeof(double));
    st->kkt = dal__kkt_create(sys);
  }
  if (sys->aba) st->aba = dal__aba_create(sys);
  size_t jn = (size_t)sys->max_in, jo = (size_t)sys->max_out;
  st->jin = calloc(jn + 1, sizeof(dal_jet));
  st->jout = calloc(jo + 1, sizeof(dal_jet));
  st->loc = calloc(jn * jo + 1, sizeof(double));
  st->dir = calloc(2 * jn + 1, sizeof(double));
  st->jq = calloc(n + 1, sizeof(dal_jet));
  st->jv = calloc(n + 1, sizeof(dal_jet));
  st->jr = calloc(Nd + 1, sizeof(dal_jet));
  if (!st->q || !st->qdot || !st->qddot || !st->Q || !st->c || !st->work || !st->r || !st->v ||
      !st->a || !st->drdt || !st->gamma || !st->F || !st->N || !st->J ||
      (sys->dense_M && (!st->M || !st->L)) ||
      (m && (!st->lambda || !st->phi || !st->phidot || !st->gphi || !st->G || !st->Gl ||
             !st->phit || !st->kkt)) ||
      !st->jin || !st->Lc || !st->Lp || !st->dir || !st->cf || (sys->aba && !st->aba) ||
      !st->jout || !st->loc || !st->jq || !st->jv || !st->jr) {
    dal_state_destroy(st);
    return DAL_E_NOMEM;
  }
  st->integ_opts = dal_default_solve_opts();
  *out = st;
  return DAL_OK;
}

void dal_state_destroy(dal_state *st) {
  if (!st) return;
  dal__integ_reset(st);
  dal__params_free(st);
  dal__kkt_free(st->kkt);
  dal__aba_free(st->aba);
  DAL_FREE(st->q, st->qddot, st->Q, st->c, st->work, st->r, st->v, st->a, st->drdt, st->gamma,
           st->F, st->N, st->J, st->M, st->L, st->lambda, st->phi, st->phidot, st->gphi, st->G,
           st->loc, st->Lc, st->cf, st->Lp, st->Gl, st->dir, st->phit, st->jin, st->jout, st->jq,
           st->jv, st->jr, st);
}

const char *dal_state_errmsg(const dal_state *st) { return st ? st->err : ""; }

int dal_state_set(const dal_system *sys, dal_state *st, double t, const double *q,
                  const double *qdot) {
  int pair = dal__check_pair(sys, st, "state_set");
  if (pair) return pair;
  if ((pair = dal__check_idle(st, "state_set")) != 0) return pair;
  if (!q || !qdot) return DAL_FAIL(st, DAL_E_ARG, "state_set: q or qdot is NULL");
  if (!isfinite(t)) return DAL_FAIL(st, DAL_E_NONFINITE, "state_set: time is %g", t);
  for (int i = 0; i < sys->n; ++i) {
    if (!isfinite(q[i]))
      return DAL_FAIL(st, DAL_E_NONFINITE, "state_set: coordinate '%s' is %g", sys->coord_names[i],
                      q[i]);
    if (!isfinite(qdot[i]))
      return DAL_FAIL(st, DAL_E_NONFINITE, "state_set: velocity of coordinate '%s' is %g",
                      sys->coord_names[i], qdot[i]);
  }
  dal__integ_reset(st);
  memset(&st->stats, 0, sizeof st->stats);
  st->t = t;
  memcpy(st->q, q, (size_t)sys->n * sizeof(double));
  memcpy(st->qdot, qdot, (size_t)sys->n * sizeof(double));
  st->W = 0.0;
  dal__state_moved(st);
  st->err[0] = 0;
  return DAL_OK;
}

int dal_forward(const dal_system *sys, dal_state *st) {
  int pair = dal__check_pair(sys, st, "forward");
  if (pair) return pair;
  int rc = dal__eval(sys, st, DAL_P_ALL);
  // a recoverable callback request has no step to shrink here: report it as a failure
  rc = dal__public_status(rc);
  return rc;
}

// Accessors: a product is handed out only while it is current for the state's (t, q, qdot)
// (st->have); before an evaluation, after dal_state_set and after a failed evaluation the
// pointer is NULL, never a view of stale or unset values.
static const double *current(const dal_state *st, unsigned p, const double *x) {
  dal__lazy_eval_for(st, p);
  return st && (st->have & p) == p ? x : NULL;
}

int dal__lazy_end(dal_state *st, const char *who) {
  st->lazy = 0;
  if (!st->lazy_rc) return DAL_OK;
  char why[DAL_ERRMSG_LEN];
  memcpy(why, st->err, sizeof why);
  int rc = st->lazy_rc;
  st->lazy_rc = 0;
  return DAL_FAIL(st, rc, "%s at t=%.17g: evaluating the state failed: %.400s", who, st->t, why);
}

void dal__lazy_eval_for(const dal_state *cst, unsigned p) {
  // the driver's own state, lent to a monitor or event function as const: evaluated on the
  // first read of a product, and only as far as that product needs (reading the energies
  // costs no accelerations); on failure the products stay unset (accessors give NULL and the
  // message is the state's)
  if (!cst || !cst->lazy || cst->lazy_rc) return;
  dal_state *st = (dal_state *)cst;
  if ((st->have & p) != p) {
    // no step can shrink at an output time: a recoverable request is a failure here
    int rc = dal__public_status(dal__eval(st->sys, st, st->have | p));
    if (rc) {
      st->lazy_rc = rc;
      return;
    }
  }
  if ((st->have & DAL_P_ALL) == DAL_P_ALL) st->lazy = 0;
}

void dal__lazy_eval(const dal_state *cst) { dal__lazy_eval_for(cst, DAL_P_ALL); }

double dal_state_time(const dal_state *st) { return st ? st->t : NAN; }
const double *dal_state_q(const dal_state *st) { return st ? st->q : NULL; }
const double *dal_state_qdot(const dal_state *st) { return st ? st->qdot : NULL; }
const double *dal_state_qddot(const dal_state *st) {
  return current(st, DAL_P_ACC, st ? st->qddot : NULL);
}
const double *dal_state_positions(const dal_state *st) {
  return current(st, DAL_P_KIN, st ? st->r : NULL);
}
const double *dal_state_velocities(const dal_state *st) {
  return current(st, DAL_P_KIN, st ? st->v : NULL);
}
const double *dal_state_accelerations(const dal_state *st) {
  return current(st, DAL_P_OUT, st ? st->a : NULL);
}
const double *dal_state_drdt(const dal_state *st) {
  return current(st, DAL_P_KIN, st ? st->drdt : NULL);
}
const double *dal_state_gamma(const dal_state *st) {
  return current(st, DAL_P_KIN, st ? st->gamma : NULL);
}
const double *dal_state_mass_matrix(const dal_state *st) {
  return current(st, DAL_P_M, st ? st->M : NULL);
}
const double *dal_state_genforces(const dal_state *st) {
  return current(st, DAL_P_DYN, st ? st->Q : NULL);
}
const double *dal_state_bias(const dal_state *st) {
  // a Lagrangian system has no velocity-product terms of its own (they are inside L)
  return st && st->sys->lag ? NULL : current(st, DAL_P_DYN, st ? st->c : NULL);
}
const double *dal_state_forces(const dal_state *st) {
  return current(st, DAL_P_DYN, st ? st->F : NULL);
}
const double *dal_state_reactions(const dal_state *st) {
  return current(st, DAL_P_OUT, st ? st->N : NULL);
}
const double *dal_state_lambda(const dal_state *st) {
  return current(st, DAL_P_ACC, st ? st->lambda : NULL);
}
const double *dal_state_phi(const dal_state *st) {
  return current(st, DAL_P_CON, st ? st->phi : NULL);
}
const double *dal_state_phidot(const dal_state *st) {
  return current(st, DAL_P_CON, st ? st->phidot : NULL);
}

int dal_state_energies(const dal_state *st, dal_energies *out) {
  if (!st) return DAL_E_ARG;
  if (!out) return DAL_FAIL_C(st, DAL_E_ARG, "state_energies: out is NULL");
  // (h is final only with the outputs where constraints may move: dal__finish)
  dal__lazy_eval_for(st, DAL_P_DYN | (st->sys->m ? DAL_P_OUT : 0u));
  if (!(st->have & DAL_P_DYN))
    return DAL_FAIL_C(st, DAL_E_STATE,
                      "state_energies: the state is not evaluated at its (t, q, qdot); call "
                      "dal_forward (or integrate) first");
  // never DAL_OK with a non-finite answer (a Lagrangian system has only E = h; the split
  // T, U, T2, T1, T0 does not exist there and is NaN by definition)
  const dal_energies *e = &st->en;
  int lag = st->sys->lag != NULL;
  // h is NaN by definition where a constraint depends on t (state.h); an overflow is inf
  int h_ok = isfinite(e->h) || (isnan(e->h) && st->sys->m > 0);
  if (!isfinite(e->E) || !h_ok ||
      (!lag && !(isfinite(e->T) && isfinite(e->U) && isfinite(e->T2) && isfinite(e->T1) &&
                 isfinite(e->T0))))
    return DAL_FAIL_C(st, DAL_E_NONFINITE,
                      "state_energies: the energies overflow at t=%.17g (T = %g, U = %g): the "
                      "velocities or positions are too large for double precision",
                      st->t, e->T, e->U);
  *out = st->en;
  out->W = st->W;
  return DAL_OK;
}

int dal_state_jacobian(const dal_system *sys, const dal_state *st, int k, double *J) {
  int pair = dal__check_pair(sys, st, "state_jacobian");
  if (pair) return pair;
  if (!J) return DAL_FAIL_C(st, DAL_E_ARG, "state_jacobian: J is NULL");
  dal__lazy_eval(st);
  if (k < 0 || k >= sys->N)
    return DAL_FAIL_C(st, DAL_E_ARG, "state_jacobian: particle index %d out of range [0, %d)", k,
                      sys->N);
  if (!(st->have & DAL_P_KIN))
    return DAL_FAIL_C(st, DAL_E_STATE,
                      "state_jacobian: the state is not evaluated at its (t, q, qdot); call "
                      "dal_forward (or integrate) first");
  int d = sys->dim, n = sys->n;
  memset(J, 0, (size_t)d * (size_t)n * sizeof(double));
  if (!(st->have & DAL_P_J)) {
    // from the local blocks: J_k = sum over b = k and its ancestors of P_b Lc_b, with
    // P_k = I and P_parent(b) = P_b Lp_b
    double P[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, T[9];
    if (d == 2) P[2] = 0, P[3] = 1, P[4] = 0;
    for (int b = k; b >= 0; b = sys->place[b].parent) {
      const dal_place *pb = &sys->place[b];
      const int *cb = sys->ipool + pb->coord_off;
      const double *Lb = st->Lc + sys->ploc_off[b], *Lp = st->Lp + (size_t)b * d * d;
      for (int a = 0; a < d; ++a)
        for (int i = 0; i < pb->ncoord; ++i) {
          double s = 0.0;
          for (int c = 0; c < d; ++c)
            s += P[a * d + c] * Lb[c * pb->ncoord + i];
          J[a * n + cb[i]] += s;
        }
      dal__gemm('N', 'N', d, d, d, Lp, d, P, d, T, d); // row-major T = P Lp
      memcpy(P, T, (size_t)d * d * sizeof(double));
    }
    return DAL_OK;
  }
  const int *dep = sys->pdep + sys->pdep_off[k];
  int nd = sys->pdep_off[k + 1] - sys->pdep_off[k];
  const double *Jk = st->J + sys->pj_off[k];
  for (int a = 0; a < d; ++a)
    for (int c = 0; c < nd; ++c)
      J[a * n + dep[c]] = Jk[a * nd + c];
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
  if ((pair = dal__check_idle(st, "lagrange_residual")) != 0) return pair;
  if (!path || !res) return DAL_FAIL(st, DAL_E_ARG, "lagrange_residual: path or res is NULL");
  if (!isfinite(t)) return DAL_FAIL(st, DAL_E_NONFINITE, "lagrange_residual: t is %g", t);
  int n = sys->n, rc;
  // the path's local tuple at t: q, qdot, qddot
  rc = path(dal_var(t, 1.0), st->jq, ctx);
  if (rc)
    return DAL_FAIL(st, DAL_E_CALLBACK, "proposed path failed (returned %d) at t=%.17g", rc, t);
  double *qdd = st->work;
  for (int i = 0; i < n; ++i) {
    if (!dal_jet_isfinite(st->jq[i]))
      return DAL_FAIL(st, DAL_E_DOMAIN,
                      "proposed path: coordinate '%s' is not finite at "
                      "t=%.17g",
                      sys->coord_names[i], t);
    st->q[i] = st->jq[i].v;
    st->qdot[i] = st->jq[i].d;
    qdd[i] = st->jq[i].dd;
  }
  st->t = t;
  dal__integ_reset(st);
  dal__state_moved(st);
  if (sys->lag) {
    double h, *rhs = st->work + n;
    rc = dal__lagrangian_terms(sys, st, st->M, rhs, &h, 0);
    st->have |= DAL_P_M | DAL_P_MLOW;
    if (rc) return dal__public_status(rc);
    for (int i = 0; i < n; ++i) {
      double s = -rhs[i];
      for (int j = 0; j < n; ++j)
        s += st->M[(size_t)j * n + i] * qdd[j];
      res[i] = s;
    }
    return residual_finite(sys, st, res, t);
  }
  if ((rc = dal__eval(sys, st, DAL_P_J | DAL_P_DYN)) != 0) return dal__public_status(rc);
  dal__mass_apply(sys, st, qdd, res);
  for (int i = 0; i < n; ++i)
    res[i] += st->c[i] - st->Q[i];
  return residual_finite(sys, st, res, t);
}

// Constraint forces from the multipliers of an evaluated state (dae.h); the state a monitor
// holds is evaluated here on first use
static int multipliers_current(const dal_state *st, const char *what) {
  if ((st->have & (DAL_P_CON | DAL_P_ACC)) == (DAL_P_CON | DAL_P_ACC)) return DAL_OK;
  return DAL_FAIL_C(st, DAL_E_STATE,
                    "%s: the state holds no evaluated multipliers at its (t, q, qdot); call "
                    "dal_forward or integrate first",
                    what);
}

int dal_constraint_genforces(const dal_system *sys, const dal_state *st, double *Qc) {
  int pair = dal__check_pair(sys, st, "constraint_genforces");
  if (pair) return pair;
  if (!Qc) return DAL_FAIL_C(st, DAL_E_ARG, "constraint_genforces: Qc is NULL");
  dal__lazy_eval(st);
  int rc = multipliers_current(st, "constraint_genforces");
  if (rc) return rc;
  if (sys->m == 0) {
    memset(Qc, 0, (size_t)sys->n * sizeof(double));
    return DAL_OK;
  }
  dal__gt_apply(sys, st, st->lambda, Qc);
  return DAL_OK;
}

int dal_constraint_forces(const dal_system *sys, const dal_state *st, double *F) {
  int pair = dal__check_pair(sys, st, "constraint_forces");
  if (pair) return pair;
  if (!F) return DAL_FAIL_C(st, DAL_E_ARG, "constraint_forces: F is NULL");
  dal__lazy_eval(st);
  int rc = multipliers_current(st, "constraint_forces");
  if (rc) return rc;
  int d = sys->dim;
  memset(F, 0, (size_t)sys->N * (size_t)d * sizeof(double));
  if (sys->m == 0) return DAL_OK;
  // F_k = (dphi/dr_k)' lambda from each constraint's local Jacobian at the evaluated point
  for (int ci = 0; ci < sys->ncon; ++ci) {
    const dal_con *c = &sys->con[ci];
    const int *parts = sys->ipool + c->part_off;
    int nin = c->prim->nin;
    const double *Gl = st->Gl + sys->con_loff[ci];
    for (int i = 0; i < c->npart * d; ++i) {
      double f = 0.0;
      for (int r = 0; r < c->prim->nout; ++r)
        f += Gl[r * nin + i] * st->lambda[c->row + r];
      F[parts[i / d] * d + i % d] += f;
    }
  }
  return DAL_OK;
}

// the last consistent start's report, kept for the user
int dal_state_init_report(const dal_state *st, dal_init_report *out) {
  if (!st || !out) return DAL_E_ARG;
  if (!st->init_rep_valid) {
    memset(out, 0, sizeof *out);
    out->phi_row = out->phidot_row = out->dq_coord = out->dqdot_coord = -1;
    return DAL_E_STATE;
  }
  *out = st->init_rep;
  return DAL_OK;
}
