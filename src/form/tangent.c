// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The exact tangent of the equations of motion: K = dR/dq, C = dR/dqdot, dR/dt, M, by jets.
//
// The equations of motion are R = sum_k J_k' (m_k A_k - F_k) - Q_q = 0 with A_k the particle
// accelerations at the state's qddot. Split the forces into potential ones (gravity, springs,
// U(r, t), U(q, t): one potential V(q, t)) and dampers F_d. With the weights
// w_k = m_k A_k - F_d,k frozen at the state, R = dW/dq for W(q, t) = sum_k r_k . w_k + V, so
// along a tangent direction z = (dq, dqdot, dt)
//   dR_j[z] = D^2 W[e_j, (dq, dt)] + sum_k (J_k e_j) . (m_k dA_k - dF_d,k),
// where the second derivatives of W come from order-2 coefficients along e_i and e_i + e_j
// (polarization), and dr_k, dv_k, dA_k from three curves (the order-3 coefficient d3):
//   h_l(s) = r_k(q + s (qdot + l dq) + s^2/2 (qddot + 2 l dqdot), t + s (1 + l dt)), l = +-1:
//   dr = (h_1' - h_-1')/2,  dv = (h_1'' - h_-1'')/4,
//   dA = ((h_1''' - h_-1''')/2 - D^3 r[(dq, dt)]^3) / 3,
// the last term the third derivative along the straight line (q + s dq, t + s dt). This is
// the expansion of g(e, s) = r(q + e dq + s qdot + e s dqdot + s^2/2 qddot, t + s + e dt)
// along e = l s: h_l''' = g_sss + 3 l g_ess + 3 l^2 g_ees + l^3 g_eee, and dA = g_ess.
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "form.h"

int dal__tangent_create(const dal_system *sys, dal_tangent **out) {
  *out = NULL;
  dal_tangent *tg = calloc(1, sizeof *tg);
  if (!tg) return DAL_E_NOMEM;
  int n = sys->n, nd = sys->N * sys->dim, nlink = sys->nspring + sys->ndamper;
  // particle-sized scratch doubles as (2n + 1)-sized scratch for Lagrangian systems
  size_t sn = (size_t)n, snd = (size_t)(nd > 2 * n + 1 ? nd : 2 * n + 1) + 1, nt = sn + 1;
  size_t np = 2 * sn + 1;
  tg->n = n;
  tg->nd = nd;
  tg->jq = calloc(sn + 1, sizeof(dal_jet));
  tg->jv = calloc(sn + 1, sizeof(dal_jet));
  tg->HL = calloc(np * np, sizeof(double));
  tg->HLabs = calloc(np * np, sizeof(double));
  tg->jr = calloc(snd, sizeof(dal_jet));
  tg->jin = calloc((size_t)sys->max_in + 1, sizeof(dal_jet));
  tg->jout = calloc((size_t)sys->max_out + 1, sizeof(dal_jet));
  tg->cp = calloc(snd, sizeof(dal_jet));
  tg->cm = calloc(snd, sizeof(dal_jet));
  tg->d3diag = calloc(nt * snd, sizeof(double));
  tg->J = calloc(sn * snd + 1, sizeof(double));
  double **nds[] = {&tg->r, &tg->v, &tg->A, &tg->w, &tg->Fd, &tg->dr, &tg->dv, &tg->da, &tg->dF};
  for (size_t i = 0; i < sizeof nds / sizeof nds[0]; ++i)
    *nds[i] = calloc(snd, sizeof(double));
  tg->H = calloc(nt * nt, sizeof(double));
  tg->res = calloc(sn + 1, sizeof(double));
  tg->M = calloc(sn * sn + 1, sizeof(double));
  tg->Rq = calloc(sn * sn + 1, sizeof(double));
  tg->Ru = calloc(sn * sn + 1, sizeof(double));
  tg->Rt = calloc(sn + 1, sizeof(double));
  tg->Habs = calloc(nt * nt, sizeof(double));
  tg->Kabs = calloc(sn * sn + 1, sizeof(double));
  tg->Cabs = calloc(sn * sn + 1, sizeof(double));
  tg->L = calloc(sn * sn + 1, sizeof(double));
  tg->link = calloc(9 * (size_t)nlink + 1, sizeof(double));
  size_t sm = (size_t)sys->m + 1;
  tg->m = sys->m;
  tg->jc = calloc(sm, sizeof(dal_jet));
  tg->ccp = calloc(sm, sizeof(dal_jet));
  tg->ccm = calloc(sm, sizeof(dal_jet));
  tg->c3diag = calloc(nt * sm, sizeof(double));
  tg->G = calloc(sm * sn + 1, sizeof(double));
  tg->phit = calloc(sm, sizeof(double));
  tg->cres = calloc(3 * sm, sizeof(double));
  tg->Pq = calloc(sm * sn + 1, sizeof(double));
  tg->Aq = calloc(sm * sn + 1, sizeof(double));
  tg->Av = calloc(sm * sn + 1, sizeof(double));
  tg->At = calloc(sm, sizeof(double));
  size_t snk = sn + (size_t)sys->m;
  if (sys->m > 0) {
    tg->kkt = calloc(snk * snk + snk * (2 * sn + 1), sizeof(double));
    tg->kpiv = calloc(snk, sizeof(lapack_int));
  }
  int ok = (sys->m == 0 || (tg->kkt && tg->kpiv)) && tg->jc && tg->ccp && tg->ccm && tg->c3diag &&
           tg->G && tg->phit && tg->cres && tg->Pq && tg->Aq && tg->Av && tg->At;
  ok = ok && tg->jq && tg->jr && tg->jin && tg->jout && tg->cp && tg->cm && tg->d3diag && tg->J &&
       tg->H && tg->res && tg->M && tg->Rq && tg->Ru && tg->Rt && tg->L && tg->link && tg->Habs &&
       tg->Kabs && tg->Cabs && tg->jv && tg->HL && tg->HLabs;
  for (size_t i = 0; i < sizeof nds / sizeof nds[0]; ++i)
    ok = ok && *nds[i];
  if (!ok) {
    dal__tangent_free(tg);
    return DAL_E_NOMEM;
  }
  *out = tg;
  return DAL_OK;
}

void dal__tangent_free(dal_tangent *tg) {
  if (!tg) return;
  void *p[] = {tg->jq,   tg->jr,   tg->jin,    tg->jout, tg->cp,   tg->cm,   tg->d3diag, tg->J,
               tg->r,    tg->v,    tg->A,      tg->w,    tg->Fd,   tg->dr,   tg->dv,     tg->da,
               tg->dF,   tg->H,    tg->res,    tg->M,    tg->Rq,   tg->Ru,   tg->Rt,     tg->L,
               tg->link, tg->Habs, tg->Kabs,   tg->Cabs, tg->jv,   tg->HL,   tg->HLabs,  tg->jc,
               tg->ccp,  tg->ccm,  tg->c3diag, tg->G,    tg->phit, tg->cres, tg->Pq,     tg->Aq,
               tg->Av,   tg->At,   tg->kkt,    tg->kpiv};
  for (size_t i = 0; i < sizeof p / sizeof p[0]; ++i)
    free(p[i]);
  free(tg);
}

int dal__tangent_supported(const dal_system *sys, dal_state *st, const char *what) {
  if (sys->m > 0 && sys->lag)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "%s: the system is given by a Lagrangian and has %d constraint row(s) "
                    "(first: '%s'); the exact tangent covers constraints on particle systems "
                    "and Lagrangians in minimal coordinates: place particles by maps, or drop "
                    "the constraints",
                    what, sys->m, sys->con[0].name);
  if (sys->nforce > 0 || sys->ngenforce > 0)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "%s: the system has %d force callback(s) and %d generalized force "
                    "callback(s) given as plain doubles, which have no exact derivative; write "
                    "a conservative force as a jet potential (dal_builder_add_potential_r/q), "
                    "a linear damper with dal_builder_add_damper_def",
                    what, sys->nforce, sys->ngenforce);
  return DAL_OK;
}

// a user or primitive function failed or asked for a smaller step (there is none here)
static int cb_fail(const dal_system *sys, dal_state *st, int rc, const char *what) {
  return DAL_FAIL(st, DAL_E_CALLBACK,
                  "%s returned %d during the tangent evaluation at t=%.17g, %s; it must succeed "
                  "at the state and along the tangent curves through it",
                  what, rc, st->t, dal__qtext(sys, st->q).s);
}

// a non-finite jet: a domain error, or (finite value and derivatives, NaN d3) a function
// built with the order-2 constructors that cannot give a third derivative
static int jet_fail(const dal_system *sys, dal_state *st, dal_jet x, const char *what) {
  if (dal_jet_isfinite(x))
    return DAL_FAIL(st, DAL_E_DOMAIN,
                    "%s gives no third derivative (d3 = %g at t=%.17g, %s): it builds jets with "
                    "dal_jet_make or dal_jet_chain, whose third derivative is unknown; the "
                    "exact tangent needs it: use dal_jet_make3 / dal_jet_chain3, or the dal_* "
                    "operations",
                    what, x.d3, st->t, dal__qtext(sys, st->q).s);
  return DAL_FAIL(st, DAL_E_DOMAIN,
                  "%s produced a non-finite value or derivative (%g, %g, %g) at t=%.17g, %s, "
                  "along a tangent curve: an input is outside its domain",
                  what, x.v, x.d, x.dd, st->t, dal__qtext(sys, st->q).s);
}

// particle jets tg->jr along the curve given by the coordinate jets tg->jq and the time jet tj;
// order3: the third derivatives are needed (and checked)
static int particle_curve(const dal_system *sys, dal_state *st, dal_tangent *tg, dal_jet tj,
                          int order3) {
  int d = sys->dim;
  char what[200];
  if (sys->map) {
    int rc = sys->map(tg->jq, tj, tg->jr, sys->map_ctx);
    if (rc) return cb_fail(sys, st, rc, "the whole-system coordinate map");
    for (int i = 0; i < tg->nd; ++i)
      if (!(order3 ? dal_jet_isfinite3(tg->jr[i]) : dal_jet_isfinite(tg->jr[i]))) {
        snprintf(what, sizeof what, "the whole-system coordinate map (particle '%s')",
                 sys->part_names[i / d]);
        return jet_fail(sys, st, tg->jr[i], what);
      }
    return DAL_OK;
  }
  for (int k = 0; k < sys->N; ++k) {
    const dal_place *pl = &sys->place[k];
    const dal_primitive *prim = pl->prim;
    const int *coords = sys->ipool + pl->coord_off;
    int m = 0;
    if (pl->parent >= 0)
      for (int b = 0; b < d; ++b)
        tg->jin[m++] = tg->jr[pl->parent * d + b];
    for (int i = 0; i < pl->ncoord; ++i)
      tg->jin[m++] = tg->jq[coords[i]];
    int rc = prim->eval(tg->jin, tj, st->prm.ppool + pl->param_off, tg->jout, pl->ctx);
    if (rc) {
      snprintf(what, sizeof what, "coordinate map '%s' of particle '%s'", prim->name,
               sys->part_names[k]);
      return cb_fail(sys, st, rc, what);
    }
    for (int b = 0; b < d; ++b) {
      dal_jet x = tg->jout[b];
      if (!(order3 ? dal_jet_isfinite3(x) : dal_jet_isfinite(x))) {
        snprintf(what, sizeof what, "coordinate map '%s' of particle '%s'", prim->name,
                 sys->part_names[k]);
        return jet_fail(sys, st, x, what);
      }
      tg->jr[k * d + b] = x;
    }
  }
  return DAL_OK;
}

// constraint jets tg->jc along the current curve (particle jets tg->jr and coordinate jets tg->jq
// set): every constraint block with its particle positions, then its coordinates, as inputs
static int constraint_curve(const dal_system *sys, dal_state *st, dal_tangent *tg, dal_jet tj,
                            int order3) {
  int d = sys->dim;
  char what[200];
  for (int c = 0; c < sys->ncon; ++c) {
    const dal_con *con = &sys->con[c];
    const int *parts = sys->ipool + con->part_off, *coords = sys->ipool + con->coord_off;
    int k = 0;
    for (int p = 0; p < con->npart; ++p)
      for (int b = 0; b < d; ++b)
        tg->jin[k++] = tg->jr[parts[p] * d + b];
    for (int i = 0; i < con->ncoord; ++i)
      tg->jin[k++] = tg->jq[coords[i]];
    int rc = con->prim->eval(tg->jin, tj, st->prm.ppool + con->param_off, tg->jout, con->ctx);
    if (rc) {
      snprintf(what, sizeof what, "constraint '%s' (%s)", con->name, con->prim->name);
      return cb_fail(sys, st, rc, what);
    }
    for (int o = 0; o < con->prim->nout; ++o) {
      dal_jet x = tg->jout[o];
      if (!(order3 ? dal_jet_isfinite3(x) : dal_jet_isfinite(x))) {
        snprintf(what, sizeof what, "constraint '%s' (%s)", con->name, con->prim->name);
        return jet_fail(sys, st, x, what);
      }
      tg->jc[con->row + o] = x;
    }
  }
  return DAL_OK;
}

// particle jets and, with constraint rows, constraint jets along the current curve
static int curve(const dal_system *sys, dal_state *st, dal_tangent *tg, dal_jet tj, int order3) {
  int rc = particle_curve(sys, st, tg, tj, order3);
  if (!rc && tg->m > 0) rc = constraint_curve(sys, st, tg, tj, order3);
  return rc;
}

// anchor of a spring or damper along the time jet tj (fixed point x0 or the path x(t))
static int anchor_jets(const dal_system *sys, dal_state *st, const dal_link *l, dal_jet tj,
                       dal_jet *x, const char *kind) {
  int d = sys->dim;
  if (!l->fn) {
    for (int b = 0; b < d; ++b)
      x[b] = dal_const(l->x0[b]);
    return DAL_OK;
  }
  char what[160];
  snprintf(what, sizeof what, "%s anchor path of particle '%s'", kind, sys->part_names[l->a]);
  int rc = l->fn(tj, x, l->ctx);
  if (rc) return cb_fail(sys, st, rc, what);
  for (int b = 0; b < d; ++b)
    if (!dal_jet_isfinite(x[b])) return jet_fail(sys, st, x[b], what);
  return DAL_OK;
}

// the potential V(q, t) (gravity, springs, U(r, t), U(q, t)) along the current curve
static int potential(const dal_system *sys, dal_state *st, dal_tangent *tg, dal_jet tj,
                     dal_jet *V) {
  int d = sys->dim, rc;
  dal_jet s = dal_const(0.0);
  if (st->prm.has_gravity)
    for (int k = 0; k < sys->N; ++k)
      for (int b = 0; b < d; ++b)
        s = dal_sub(s, dal_scale(tg->jr[k * d + b], st->prm.mass[k] * st->prm.g[b]));
  for (int i = 0; i < sys->nspring; ++i) {
    const dal_link *l = &st->prm.springs[i];
    dal_jet x[3], diff[3];
    if (l->b >= 0) {
      for (int b = 0; b < d; ++b)
        x[b] = tg->jr[l->b * d + b];
    } else if ((rc = anchor_jets(sys, st, l, tj, x, "spring")) != 0) {
      return rc;
    }
    for (int b = 0; b < d; ++b)
      diff[b] = dal_sub(tg->jr[l->a * d + b], x[b]);
    dal_jet ext = dal_addc(dal_norm(diff, d), -l->L);
    dal_jet e = dal_scale(dal_sq(ext), 0.5 * l->k);
    if (!dal_jet_isfinite(e)) {
      char what[160];
      snprintf(what, sizeof what, "spring on particle '%s' (zero length?)", sys->part_names[l->a]);
      return jet_fail(sys, st, e, what);
    }
    s = dal_add(s, e);
  }
  for (int i = 0; i < sys->npotr; ++i) {
    dal_jet U;
    rc = sys->potr[i].fn.potr(tg->jr, tj, &U, sys->potr[i].ctx);
    if (rc) return cb_fail(sys, st, rc, "potential U(r,t)");
    if (!dal_jet_isfinite(U)) return jet_fail(sys, st, U, "potential U(r,t)");
    s = dal_add(s, U);
  }
  for (int i = 0; i < sys->npotq; ++i) {
    dal_jet U;
    rc = sys->potq[i].fn.potq(tg->jq, tj, &U, sys->potq[i].ctx);
    if (rc) return cb_fail(sys, st, rc, "potential U(q,t)");
    if (!dal_jet_isfinite(U)) return jet_fail(sys, st, U, "potential U(q,t)");
    s = dal_add(s, U);
  }
  *V = s;
  return DAL_OK;
}

// damper forces at the state into F (nd; may be NULL) and, when dF is not NULL, their derivatives
// along a direction with particle derivatives dr, dv (nd) and time component dt; anchors move with
// x(t): derivative x' dt of the position and x'' dt of the velocity (tg->link); the dampers
// are the state's (st->prm.dampers: a per-trajectory coefficient override applies here too)
static void dampers(const dal_system *sys, const dal_state *st, dal_tangent *tg, const double *dr,
                    const double *dv, double dt, double *F, double *dF) {
  int d = sys->dim;
  if (F) memset(F, 0, (size_t)tg->nd * sizeof(double));
  if (dF) memset(dF, 0, (size_t)tg->nd * sizeof(double));
  for (int i = 0; i < sys->ndamper; ++i) {
    const dal_link *l = &st->prm.dampers[i];
    const double *an = tg->link + 9 * (size_t)(sys->nspring + i);
    dal_jet diff[3], rel = dal_const(0.0);
    for (int b = 0; b < d; ++b) {
      int pa = l->a * d + b, pb = l->b * d + b;
      dal_jet ra = dal_var(tg->r[pa], dF ? dr[pa] : 0.0), va = dal_var(tg->v[pa], dF ? dv[pa] : 0);
      dal_jet rb, vb;
      if (l->b >= 0) {
        rb = dal_var(tg->r[pb], dF ? dr[pb] : 0.0);
        vb = dal_var(tg->v[pb], dF ? dv[pb] : 0.0);
      } else {
        rb = dal_var(an[b], an[3 + b] * dt);
        vb = dal_var(an[3 + b], an[6 + b] * dt);
      }
      diff[b] = dal_sub(ra, rb);
      rel = dal_add(rel, dal_mul(dal_sub(va, vb), diff[b]));
    }
    // f e with e = diff / |diff|, f = c (v_a - v_b) . e: f e = c rel diff / |diff|^2
    dal_jet len2 = dal_const(0.0);
    for (int b = 0; b < d; ++b)
      len2 = dal_add(len2, dal_sq(diff[b]));
    dal_jet coef = dal_scale(dal_div(rel, len2), l->k);
    for (int b = 0; b < d; ++b) {
      dal_jet fb = dal_mul(coef, diff[b]);
      if (F) F[l->a * d + b] -= fb.v;
      if (dF) dF[l->a * d + b] -= fb.d;
      if (l->b >= 0) {
        if (F) F[l->b * d + b] += fb.v;
        if (dF) dF[l->b * d + b] += fb.d;
      }
    }
  }
}

// W = sum r . w + V along the current curve: its second derivative (and first in *W1), and in
// *Wabs the sum of the magnitudes of its terms (the scale of its rounding)
static int weighted(const dal_system *sys, dal_state *st, dal_tangent *tg, dal_jet tj, double *W2,
                    double *W1, double *Wabs) {
  dal_jet V;
  int rc = potential(sys, st, tg, tj, &V);
  if (rc) return rc;
  double s2 = V.dd, s1 = V.d, sa = fabs(V.dd);
  for (int c = 0; c < tg->nd; ++c) {
    s2 += tg->jr[c].dd * tg->w[c];
    s1 += tg->jr[c].d * tg->w[c];
    sa += fabs(tg->jr[c].dd * tg->w[c]);
  }
  // the constraint forces G' lambda at frozen multipliers: W gains -lambda . phi
  const double *lam = tg->lam ? tg->lam : st->lambda;
  for (int r = 0; r < tg->m; ++r) {
    s2 -= tg->jc[r].dd * lam[r];
    s1 -= tg->jc[r].d * lam[r];
    sa += fabs(tg->jc[r].dd * lam[r]);
  }
  *W2 = s2;
  *Wabs = sa;
  if (W1) *W1 = s1;
  return DAL_OK;
}

// coordinate jets of the straight line (q + s e_i + s e_j, t + s [i or j is the time index n])
static dal_jet line(dal_tangent *tg, const double *q, double t, int i, int j) {
  int n = tg->n;
  for (int c = 0; c < n; ++c)
    tg->jq[c] = dal_const(q[c]);
  if (i < n) tg->jq[i].d += 1.0;
  if (j >= 0 && j < n) tg->jq[j].d += 1.0;
  return dal_var(t, (i == n) + (j == n));
}

// anchors of springs and dampers: x, x', x'' at t
static int tangent_anchors(const dal_system *sys, dal_state *st, dal_tangent *tg) {
  int d = sys->dim, rc;
  for (int i = 0; i < sys->nspring + sys->ndamper; ++i) {
    int spring = i < sys->nspring;
    const dal_link *l = spring ? &st->prm.springs[i] : &st->prm.dampers[i - sys->nspring];
    if (l->b >= 0) continue;
    dal_jet x[3];
    if ((rc = anchor_jets(sys, st, l, dal_var(st->t, 1.0), x, spring ? "spring" : "damper")) != 0)
      return rc;
    for (int b = 0; b < d; ++b) {
      tg->link[9 * i + b] = x[b].v;
      tg->link[9 * i + 3 + b] = x[b].d;
      tg->link[9 * i + 6 + b] = x[b].dd;
    }
  }
  return DAL_OK;
}

// the state's curve (q + s qdot + s^2/2 qddot, t + s): positions, velocities, accelerations,
// the constraint residuals, the damper forces and the weights m a - Fd
static int tangent_at_state(const dal_system *sys, dal_state *st, dal_tangent *tg,
                            const double *a) {
  int n = tg->n, nd = tg->nd, m = tg->m, d = sys->dim, rc;
  for (int c = 0; c < n; ++c)
    tg->jq[c] = dal_jet_make3(st->q[c], st->qdot[c], a[c], 0.0);
  if ((rc = curve(sys, st, tg, dal_var(st->t, 1.0), 0)) != 0) return rc;
  for (int c = 0; c < nd; ++c) {
    tg->r[c] = tg->jr[c].v;
    tg->v[c] = tg->jr[c].d;
    tg->A[c] = tg->jr[c].dd;
  }
  for (int r = 0; r < m; ++r) {
    tg->cres[r] = tg->jc[r].v;
    tg->cres[m + r] = tg->jc[r].d;
    tg->cres[2 * m + r] = tg->jc[r].dd;
  }
  dampers(sys, st, tg, NULL, NULL, 0.0, tg->Fd, NULL);
  for (int c = 0; c < nd; ++c)
    tg->w[c] = st->prm.mass[c / d] * tg->A[c] - tg->Fd[c];
  return DAL_OK;
}

// second derivatives of W in (q, t) (nt of them): diagonal along e_i (also J, dR at the state
// and the third derivatives of the particles along e_i), then e_i + e_j by polarization
static int tangent_hessian(const dal_system *sys, dal_state *st, dal_tangent *tg, int nt) {
  int n = tg->n, nd = tg->nd, m = tg->m, rc;
  const double t = st->t, *q = st->q;
  double *H = tg->H;
  size_t ldh = (size_t)n + 1;
  for (int i = 0; i < nt; ++i) {
    dal_jet tj = line(tg, q, t, i, -1);
    if ((rc = curve(sys, st, tg, tj, 1)) != 0) return rc;
    double W1;
    rc = weighted(sys, st, tg, tj, &H[i * ldh + i], &W1, &tg->Habs[i * ldh + i]);
    if (rc) return rc;
    if (i < n) {
      tg->res[i] = W1;
      for (int c = 0; c < nd; ++c)
        tg->J[(size_t)i * nd + c] = tg->jr[c].d;
    }
    for (int c = 0; c < nd; ++c)
      tg->d3diag[(size_t)i * nd + c] = tg->jr[c].d3;
    for (int r = 0; r < m; ++r) {
      tg->c3diag[(size_t)i * m + r] = tg->jc[r].d3;
      if (i < n)
        tg->G[(size_t)i * m + r] = tg->jc[r].d;
      else
        tg->phit[r] = tg->jc[r].d;
    }
  }
  for (int i = 0; i < nt; ++i)
    for (int j = i + 1; j < nt; ++j) {
      dal_jet tj = line(tg, q, t, i, j);
      double W2, Wa;
      if ((rc = curve(sys, st, tg, tj, 0)) != 0) return rc;
      if ((rc = weighted(sys, st, tg, tj, &W2, NULL, &Wa)) != 0) return rc;
      H[j * ldh + i] = H[i * ldh + j] = 0.5 * (W2 - H[i * ldh + i] - H[j * ldh + j]);
      tg->Habs[j * ldh + i] = tg->Habs[i * ldh + j] =
          0.5 * (Wa + tg->Habs[i * ldh + i] + tg->Habs[j * ldh + j]);
    }
  return DAL_OK;
}

// M = sum_k m_k J_k' J_k from the particle Jacobian columns
static void tangent_mass(const dal_system *sys, const dal_state *st, dal_tangent *tg) {
  int n = tg->n, nd = tg->nd, d = sys->dim;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) {
      double s = 0.0;
      const double *Ji = tg->J + (size_t)i * nd, *Jj = tg->J + (size_t)j * nd;
      for (int c = 0; c < nd; ++c)
        s += st->prm.mass[c / d] * Ji[c] * Jj[c];
      tg->M[(size_t)j * n + i] = tg->M[(size_t)i * n + j] = s;
    }
}

// tangent direction z: dq = e_i (z < n), dqdot = e_i (n <= z < 2n), dt = 1 (z = 2n); the
// columns of Rq, Ru or Rt (with their rounding scales) and of the constraint rows' residuals
static int tangent_direction(const dal_system *sys, dal_state *st, dal_tangent *tg, const double *a,
                             int z) {
  int n = tg->n, nd = tg->nd, m = tg->m, d = sys->dim, rc;
  const double t = st->t, *q = st->q, *u = st->qdot, *H = tg->H;
  size_t ldh = (size_t)n + 1;
  int qdir = z < n, udir = z >= n && z < 2 * n, i = qdir ? z : udir ? z - n : n;
  for (int l = 0; l < 2; ++l) {
    double lam = l ? -1.0 : 1.0;
    for (int c = 0; c < n; ++c) {
      double dq = qdir && c == i ? lam : 0.0, du = udir && c == i ? 2.0 * lam : 0.0;
      tg->jq[c] = dal_jet_make3(q[c], u[c] + dq, a[c] + du, 0.0);
    }
    dal_jet tj = dal_var(t, udir || qdir ? 1.0 : 1.0 + lam);
    if ((rc = curve(sys, st, tg, tj, 1)) != 0) return rc;
    memcpy(l ? tg->cm : tg->cp, tg->jr, (size_t)nd * sizeof(dal_jet));
    if (m > 0) memcpy(l ? tg->ccm : tg->ccp, tg->jc, (size_t)m * sizeof(dal_jet));
  }
  const double *pure = udir ? NULL : tg->d3diag + (size_t)i * nd;
  // the constraint rows' velocity and acceleration residuals along the direction
  for (int r = 0; r < m; ++r) {
    double cpure = udir ? 0.0 : tg->c3diag[(size_t)i * m + r];
    double dacc = (0.5 * (tg->ccp[r].d3 - tg->ccm[r].d3) - cpure) / 3.0;
    if (qdir) {
      tg->Pq[(size_t)i * m + r] = 0.25 * (tg->ccp[r].dd - tg->ccm[r].dd);
      tg->Aq[(size_t)i * m + r] = dacc;
    } else if (udir) {
      tg->Av[(size_t)i * m + r] = dacc;
    } else {
      tg->At[r] = dacc;
    }
  }
  for (int c = 0; c < nd; ++c) {
    tg->dr[c] = 0.5 * (tg->cp[c].d - tg->cm[c].d);
    tg->dv[c] = 0.25 * (tg->cp[c].dd - tg->cm[c].dd);
    tg->da[c] = (0.5 * (tg->cp[c].d3 - tg->cm[c].d3) - (pure ? pure[c] : 0.0)) / 3.0;
  }
  dampers(sys, st, tg, tg->dr, tg->dv, udir || qdir ? 0.0 : 1.0, NULL, tg->dF);
  double *col = qdir ? tg->Rq + (size_t)i * n : udir ? tg->Ru + (size_t)i * n : tg->Rt;
  double *cabs = qdir ? tg->Kabs + (size_t)i * n : udir ? tg->Cabs + (size_t)i * n : NULL;
  for (int j = 0; j < n; ++j) {
    const double *Jj = tg->J + (size_t)j * nd;
    double s = udir ? 0.0 : H[i * ldh + j], sa = udir ? 0.0 : tg->Habs[i * ldh + j];
    for (int c = 0; c < nd; ++c) {
      double x = Jj[c] * (st->prm.mass[c / d] * tg->da[c] - tg->dF[c]);
      s += x;
      sa += fabs(x);
    }
    col[j] = s;
    if (cabs) cabs[j] = sa;
  }
  return DAL_OK;
}

int dal__tangent_eval(const dal_system *sys, dal_state *st, dal_tangent *tg, int want_t) {
  if (sys->lag) return dal__tangent_lagrangian(sys, st, tg, want_t);
  int n = tg->n, nt = want_t ? n + 1 : n, rc;
  const double *a = tg->acc ? tg->acc : st->qddot;
  if ((rc = tangent_anchors(sys, st, tg)) != 0 || (rc = tangent_at_state(sys, st, tg, a)) != 0 ||
      (rc = tangent_hessian(sys, st, tg, nt)) != 0)
    return rc;
  tangent_mass(sys, st, tg);
  // each tangent direction: dq = e_i (i < n), dqdot = e_i (n <= i < 2n), dt = 1 (i = 2n)
  int ndir = 2 * n + (want_t ? 1 : 0);
  for (int z = 0; z < ndir; ++z)
    if ((rc = tangent_direction(sys, st, tg, a, z)) != 0) return rc;
  return DAL_OK;
}

int dal__tangent_factor(const dal_system *sys, dal_state *st, dal_tangent *tg) {
  int n = tg->n;
  memcpy(tg->L, tg->M, (size_t)n * (size_t)n * sizeof(double));
  lapack_int info = LAPACKE_dpotrf_work(LAPACK_COL_MAJOR, 'L', n, tg->L, n);
  if (info != 0) {
    int bad = info > 0 ? (int)info - 1 : 0;
    return DAL_FAIL(st, DAL_E_SINGULAR,
                    "mass matrix not positive definite at t=%.17g, %s (coordinate '%s'): the "
                    "tangent needs M^-1; use another chart",
                    st->t, dal__qtext(sys, st->q).s, sys->coord_names[bad]);
  }
  return DAL_OK;
}

void dal__tangent_msolve(dal_tangent *tg, int k, double *B) {
  int n = tg->n;
  if (k > 0) LAPACKE_dpotrs_work(LAPACK_COL_MAJOR, 'L', n, k, tg->L, n, B, n);
}

void dal__tangent_flow(dal_tangent *tg, double *A, double *ft) {
  int n = tg->n;
  size_t n2 = 2 * (size_t)n;
  memset(A, 0, n2 * n2 * sizeof(double));
  for (int i = 0; i < n; ++i)
    A[((size_t)n + i) * n2 + i] = 1.0; // dq' / dqdot = I
  // lower block rows: -M^-1 [K C], solved column by column in place
  for (int c = 0; c < 2 * n; ++c) {
    double *col = A + (size_t)c * n2 + n;
    const double *src = c < n ? tg->Rq + (size_t)c * n : tg->Ru + (size_t)(c - n) * n;
    for (int j = 0; j < n; ++j)
      col[j] = -src[j];
    // columns of A are not contiguous in n-blocks of one matrix: solve one at a time
    dal__tangent_msolve(tg, 1, col);
  }
  if (ft) {
    for (int j = 0; j < n; ++j) {
      ft[j] = 0.0;
      ft[n + j] = -tg->Rt[j];
    }
    dal__tangent_msolve(tg, 1, ft + n);
  }
}

int dal__analysis_eval(const dal_system *sys, dal_state *st, double t, const double *q,
                       const double *qdot) {
  int rc = dal_state_set(sys, st, t, q, qdot);
  if (!rc) rc = dal_forward(sys, st);
  return rc;
}

// common start of the public calls: checks, evaluation at the state, workspace, tangent; with
// constraint rows the state must be on the manifold
static int start(const dal_system *sys, dal_state *st, const char *what, int want_t,
                 dal_tangent **tg) {
  *tg = NULL;
  if (!st) return DAL_E_ARG;
  if (!sys || st->sys != sys)
    return DAL_FAIL(st, DAL_E_STATE, "%s: the state belongs to another system", what);
  int rc = dal__tangent_supported(sys, st, what);
  if (!rc) rc = dal_forward(sys, st);
  if (rc) return rc;
  if (dal__tangent_create(sys, tg))
    return DAL_FAIL(st, DAL_E_NOMEM, "%s: out of memory for the tangent workspace", what);
  rc = dal__tangent_eval(sys, st, *tg, want_t);
  if (!rc && sys->m > 0) rc = dal__tangent_on_manifold(sys, st, *tg, what);
  if (rc) {
    dal__tangent_free(*tg);
    *tg = NULL;
  }
  return rc;
}

int dal_linearize(const dal_system *sys, dal_state *st, double *M, double *C, double *K) {
  dal_tangent *tg;
  int rc = start(sys, st, "linearize", 0, &tg);
  if (rc) return rc;
  if (sys->m > 0) {
    rc = dal__tangent_reduced(sys, st, tg, NULL, NULL, M, C, K);
    dal__tangent_free(tg);
    return rc;
  }
  size_t nn = (size_t)tg->n * (size_t)tg->n * sizeof(double);
  if (M) memcpy(M, tg->M, nn);
  if (C) memcpy(C, tg->Ru, nn);
  if (K) memcpy(K, tg->Rq, nn);
  dal__tangent_free(tg);
  return DAL_OK;
}

int dal_linearize_full(const dal_system *sys, dal_state *st, double *M, double *C, double *K,
                       double *G, double *N) {
  dal_tangent *tg;
  int rc = start(sys, st, "linearize_full", 0, &tg);
  if (rc) return rc;
  int n = tg->n, m = tg->m;
  size_t nn = (size_t)n * (size_t)n * sizeof(double);
  if (M) memcpy(M, tg->M, nn);
  if (C) memcpy(C, tg->Ru, nn);
  if (K) memcpy(K, tg->Rq, nn);
  if (G && m > 0) memcpy(G, tg->G, (size_t)m * (size_t)n * sizeof(double));
  if (N && m > 0) rc = dal__tangent_basis(sys, st, tg, N, NULL, NULL);
  if (N && m == 0) {
    memset(N, 0, nn);
    for (int i = 0; i < n; ++i)
      N[(size_t)i * n + i] = 1.0;
  }
  dal__tangent_free(tg);
  return rc;
}

int dal_vector_field_jacobian(const dal_system *sys, dal_state *st, double *A, double *ft) {
  if (st && !A) return DAL_FAIL(st, DAL_E_ARG, "vector_field_jacobian: A is NULL");
  dal_tangent *tg;
  int rc = start(sys, st, "vector_field_jacobian", ft != NULL, &tg);
  if (rc) return rc;
  if (sys->m > 0) {
    rc = dal__tangent_kkt(sys, st, tg, A, ft, NULL);
  } else {
    rc = dal__tangent_factor(sys, st, tg);
    if (!rc) dal__tangent_flow(tg, A, ft);
  }
  dal__tangent_free(tg);
  return rc;
}
