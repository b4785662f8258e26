// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// d'Alembert's principle: applied forces, M = sum m J'J, Q = sum J'F, c = sum m J' gamma,
// accelerations, reactions N_k = m_k a_k - F_k, energies T, U, E and h.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "eval.h"
#include "linalg/linalg.h"

// position and velocity of a link's anchor, x0 + x(t) (the moving-point convention)
static int anchor(const dal_system *sys, dal_state *st, const dal_link *l, double *x, double *xd,
                  const char *kind) {
  int d = sys->dim;
  if (!l->fn) {
    memcpy(x, l->x0, (size_t)d * sizeof(double));
    memset(xd, 0, (size_t)d * sizeof(double));
    return DAL_OK;
  }
  dal_jet jx[3] = {dal_const(0.0), dal_const(0.0), dal_const(0.0)};
  char what[160];
  snprintf(what, sizeof what, "%s anchor path of particle '%s'", kind, sys->part_names[l->a]);
  int rc = l->fn(dal_var(st->t, 1.0), jx, l->ctx);
  if (rc) return dal__cb_status(st, rc, what);
  for (int b = 0; b < d; ++b) {
    if (!isfinite(jx[b].v) || !isfinite(jx[b].d))
      return DAL_FAIL(st, DAL_E_DOMAIN, "%s is not finite at t=%.17g", what, st->t);
    x[b] = l->x0[b] + jx[b].v;
    xd[b] = jx[b].d;
  }
  return DAL_OK;
}

// unit vector e from a to b and distance; fails on coincident points
static int direction(const dal_system *sys, dal_state *st, const double *ra, const double *rb,
                     double *e, double *len, const dal_link *l, const char *kind) {
  int d = sys->dim;
  double s = 0.0;
  for (int b = 0; b < d; ++b) {
    e[b] = rb[b] - ra[b];
    s += e[b] * e[b];
  }
  *len = sqrt(s);
  if (*len == 0.0)
    return DAL_FAIL(st, DAL_E_DOMAIN,
                    "%s on particle '%s' has zero length at t=%.17g: its direction is "
                    "undefined; start the particles apart",
                    kind, sys->part_names[l->a], st->t);
  for (int b = 0; b < d; ++b)
    e[b] /= *len;
  return DAL_OK;
}

// applied Cartesian forces F (N x d) and their potential energy
// pw (nullable): pw[0] += power of the non-conservative forces (dampers, force callbacks),
// pw[1] += explicit time derivative of the potential energy (moving spring anchors, U(r,t))
// the user potentials over positions: F -= grad U (exact by jets), U added to *U, and their
// explicit time derivative to pw[1] when the power is asked for (pw not NULL)
static int position_potentials(const dal_system *sys, dal_state *st, double *U, double *pw) {
  int d = sys->dim, Nd = sys->N * d, rc;
  for (int i = 0; i < sys->npotr; ++i) {
    dal_jet Uj;
    for (int j = 0; j < Nd; ++j)
      st->jr[j] = dal_const(st->r[j]);
    for (int j = 0; j < Nd; ++j) {
      st->jr[j].d = 1.0;
      rc = sys->potr[i].fn.potr(st->jr, dal_const(st->t), &Uj, sys->potr[i].ctx);
      st->jr[j].d = 0.0;
      if (rc) return dal__cb_status(st, rc, "potential U(r,t)");
      if (!dal_jet_isfinite(Uj))
        return DAL_FAIL(st, DAL_E_DOMAIN,
                        "potential U(r,t) #%d is not finite at t=%.17g (gradient along "
                        "particle '%s', component %d)",
                        i, st->t, sys->part_names[j / d], j % d);
      st->F[j] -= Uj.d;
    }
    if (Nd == 0 || pw) {
      // the value, and its explicit time derivative when the power is asked for
      rc = sys->potr[i].fn.potr(st->jr, dal_var(st->t, pw ? 1.0 : 0.0), &Uj, sys->potr[i].ctx);
      if (rc) return dal__cb_status(st, rc, "potential U(r,t)");
      if (pw) pw[1] += Uj.d;
    }
    *U += Uj.v;
  }
  return DAL_OK;
}

static int applied_forces(const dal_system *sys, dal_state *st, double *U, double *pw) {
  int d = sys->dim, N = sys->N, rc;
  memset(st->F, 0, (size_t)N * (size_t)d * sizeof(double));
  *U = 0.0;
  if (st->prm.has_gravity)
    for (int k = 0; k < N; ++k)
      for (int b = 0; b < d; ++b) {
        st->F[k * d + b] += st->prm.mass[k] * st->prm.g[b];
        *U -= st->prm.mass[k] * st->prm.g[b] * st->r[k * d + b];
      }
  for (int i = 0; i < sys->nspring + sys->ndamper; ++i) {
    int spring = i < sys->nspring;
    const dal_link *l = spring ? &st->prm.springs[i] : &st->prm.dampers[i - sys->nspring];
    const char *kind = spring ? "spring" : "damper";
    double xa[3], va[3], e[3], len;
    const double *rb = st->r + l->a * d, *vb = st->v + l->a * d;
    const double *ra = xa, *vra = va;
    if (l->b >= 0) {
      // a spring between particles a and b pulls along e from a to b
      ra = st->r + l->b * d;
      vra = st->v + l->b * d;
    } else if ((rc = anchor(sys, st, l, xa, va, kind)) != 0) {
      return rc;
    }
    // e points from the other end to particle a
    if ((rc = direction(sys, st, ra, rb, e, &len, l, kind)) != 0) return rc;
    double f, ev = 0.0; // ev: e . (v_a - v_other)
    for (int b = 0; b < d; ++b)
      ev += (vb[b] - vra[b]) * e[b];
    if (spring) {
      f = l->k * (len - l->L);
      *U += 0.5 * l->k * (len - l->L) * (len - l->L);
      // a moving anchor changes U explicitly: dU/dt = -f e . xdot_anchor
      if (pw && l->b < 0)
        for (int b = 0; b < d; ++b)
          pw[1] -= f * e[b] * vra[b];
    } else {
      f = l->k * ev;
      // the damper's power on the particles (an anchor's motion is external)
      if (pw) {
        double s = 0.0;
        for (int b = 0; b < d; ++b)
          s += e[b] * (vb[b] - (l->b >= 0 ? vra[b] : 0.0));
        pw[0] -= f * s;
      }
    }
    for (int b = 0; b < d; ++b) {
      st->F[l->a * d + b] -= f * e[b];
      if (l->b >= 0) st->F[l->b * d + b] += f * e[b];
    }
  }
  // user potentials over positions: F -= grad U, exact by jets
  int Nd = N * d;
  if (sys->npotr > 0 && (rc = position_potentials(sys, st, U, pw)) != 0) return rc;
  // user Cartesian forces
  double *F0 = st->cf; // scratch (Nd): forces before the callbacks, for their power
  if (pw && sys->nforce) memcpy(F0, st->F, (size_t)Nd * sizeof(double));
  for (int i = 0; i < sys->nforce; ++i) {
    rc = sys->forces[i].fn.force(st->t, st->r, st->v, st->F, sys->forces[i].ctx);
    if (rc) return dal__cb_status(st, rc, "force callback");
  }
  if (pw && sys->nforce)
    for (int j = 0; j < Nd; ++j)
      pw[0] += (st->F[j] - F0[j]) * st->v[j];
  for (int j = 0; j < Nd; ++j)
    if (!isfinite(st->F[j]))
      return DAL_FAIL(st, DAL_E_NONFINITE,
                      "applied force on particle '%s' (component %d) is %g at t=%.17g; check "
                      "the force callbacks",
                      sys->part_names[j / d], j % d, st->F[j], st->t);
  return DAL_OK;
}

int dal__forces(const dal_system *sys, dal_state *st) {
  DAL_NEED(st, DAL_P_KIN);
  int d = sys->dim, N = sys->N;
  if (sys->nspring || sys->ndamper || sys->npotr || sys->nforce) {
    double U = 0.0;
    return N > 0 ? applied_forces(sys, st, &U, NULL) : DAL_OK;
  }
  // gravity alone (or no force): F = 0 + m g as applied_forces sums it, without U
  double z = 0.0;
  for (int k = 0; k < N; ++k)
    for (int b = 0; b < d; ++b) {
      double f = 0.0 + (st->prm.has_gravity ? st->prm.mass[k] * st->prm.g[b] : 0.0);
      st->F[k * d + b] = f;
      z += f;
    }
  // a non-finite sum: the general routine names the force
  if (!isfinite(z)) {
    double U = 0.0;
    return applied_forces(sys, st, &U, NULL);
  }
  return DAL_OK;
}

// generalized terms from user callbacks over q: Q += Q_user - dU/dq, U += U(q); pw as in
// applied_forces (Q_user . qdot and dU(q,t)/dt)
int dal__genforces(const dal_system *sys, dal_state *st, double *U, double *pw) {
  int n = sys->n, rc;
  for (int i = 0; i < sys->npotq; ++i) {
    dal_jet Uj = dal_const(0.0);
    for (int j = 0; j < n; ++j)
      st->jq[j] = dal_const(st->q[j]);
    for (int j = 0; j < n; ++j) {
      st->jq[j].d = 1.0;
      rc = sys->potq[i].fn.potq(st->jq, dal_const(st->t), &Uj, sys->potq[i].ctx);
      st->jq[j].d = 0.0;
      if (rc) return dal__cb_status(st, rc, "potential U(q,t)");
      if (!dal_jet_isfinite(Uj))
        return DAL_FAIL(st, DAL_E_DOMAIN,
                        "potential U(q,t) #%d is not finite at t=%.17g (derivative along "
                        "coordinate '%s')",
                        i, st->t, sys->coord_names[j]);
      st->Q[j] -= Uj.d;
    }
    if (pw || n == 0) {
      for (int j = 0; j < n; ++j)
        st->jq[j] = dal_const(st->q[j]);
      rc = sys->potq[i].fn.potq(st->jq, dal_var(st->t, 1.0), &Uj, sys->potq[i].ctx);
      if (rc) return dal__cb_status(st, rc, "potential U(q,t)");
      if (pw) pw[1] += Uj.d;
    }
    *U += Uj.v;
  }
  double qv0 = 0.0; // Q . qdot before the callbacks, for their power
  for (int j = 0; j < n && pw && sys->ngenforce; ++j)
    qv0 += st->Q[j] * st->qdot[j];
  for (int i = 0; i < sys->ngenforce; ++i) {
    rc = sys->genforces[i].fn.gen(st->t, st->q, st->qdot, st->Q, sys->genforces[i].ctx);
    if (rc) return dal__cb_status(st, rc, "generalized force callback");
  }
  if (pw && sys->ngenforce) {
    double qv = 0.0;
    for (int j = 0; j < n; ++j)
      qv += st->Q[j] * st->qdot[j];
    pw[0] += qv - qv0;
  }
  for (int j = 0; j < n; ++j)
    if (!isfinite(st->Q[j]))
      return DAL_FAIL(st, DAL_E_NONFINITE,
                      "generalized force on coordinate '%s' is %g at t=%.17g; check the force "
                      "callbacks",
                      sys->coord_names[j], st->Q[j], st->t);
  return DAL_OK;
}

// Q and c for any tree of placements by subtree sums (carried to a parent through Lp_k'; the
// chain rule J_k = Lp_k J_p + Lc_k), and M by composite masses when every parent link is a
// translation (r_k = r_p + f): then J_k = sum of L_a over the ancestors a of k (L_a: a's local
// coordinate columns), so
//   M = sum_a sum_{b ancestor-or-self of a} mu_a (L_a' L_b + L_b' L_a for b != a),
//   Q = sum_a L_a' (sum of F over a's subtree),  c = sum_a L_a' (sum of m gamma over it),
// with mu_a the subtree mass: O(N depth) work instead of O(N n^2) (Featherstone's composite
// rigid body idea for point masses).
// Q and c by subtree sums for d = 2 or 3 (a constant once inlined): cf and cg start as F and
// m gamma; leaves first, a placement's sums are complete when it is reached
static inline void subtree_sums(const dal_system *sys, dal_state *st, const int d) {
  int N = sys->N;
  double *restrict cf = st->cf, *restrict cg = st->cf + N * d;
  for (int e = 0; e < N * d; ++e)
    cf[e] = st->F[e];
  for (int k = 0; k < N; ++k)
    for (int a = 0; a < d; ++a)
      cg[k * d + a] = st->prm.mass[k] * st->gamma[k * d + a];
  for (int k = N - 1; k >= 0; --k) {
    const dal_place *pk = &sys->place[k];
    const int *ck = sys->ipool + pk->coord_off;
    const double *Lk = st->Lc + sys->ploc_off[k], *fk = cf + k * d, *gk = cg + k * d;
    int nk = pk->ncoord, p = pk->parent;
    for (int i = 0; i < nk; ++i) {
      double q = 0.0, c = 0.0;
      for (int a = 0; a < d; ++a) {
        q += Lk[a * nk + i] * fk[a];
        c += Lk[a * nk + i] * gk[a];
      }
      st->Q[ck[i]] += q;
      st->c[ck[i]] += c;
    }
    if (p < 0) continue;
    double *fp = cf + p * d, *gp = cg + p * d;
    if (st->tree) {
      for (int a = 0; a < d; ++a) {
        fp[a] += fk[a];
        gp[a] += gk[a];
      }
    } else {
      // a link that is not a translation: the subtree's sums reach the parent through
      // dr_k/dr_p, as Lp_k' (the same chain rule as J_k = Lp_k J_p + Lc_k)
      const double *Lp = st->Lp + (size_t)k * d * d;
      for (int a = 0; a < d; ++a)
        for (int b = 0; b < d; ++b) {
          fp[a] += Lp[b * d + a] * fk[b];
          gp[a] += Lp[b * d + a] * gk[b];
        }
    }
  }
}

static void tree_assembly(const dal_system *sys, dal_state *st, int want_M) {
  int d = sys->dim, n = sys->n, N = sys->N;
  if (d == 2)
    subtree_sums(sys, st, 2);
  else
    subtree_sums(sys, st, 3);
  for (int k = 0; k < N && want_M; ++k) {
    const dal_place *pk = &sys->place[k];
    const int *ck = sys->ipool + pk->coord_off;
    const double *Lk = st->Lc + sys->ploc_off[k];
    int nk = pk->ncoord;
    // lower triangle only (M[col * n + row], row >= col); a pair and its transpose are
    // one entry there, a coordinate paired with itself counts twice
    double *restrict M = st->M;
    const double muk = st->prm.mu[k];
    for (int b = k; b >= 0; b = sys->place[b].parent) {
      const dal_place *pb = &sys->place[b];
      const int *cb = sys->ipool + pb->coord_off;
      const double *restrict Lb = st->Lc + sys->ploc_off[b];
      int nb = pb->ncoord;
      if (nk == 1 && nb == 1) {
        // one coordinate each (chains, pendulums): one entry
        double v = 0.0;
        for (int a = 0; a < d; ++a)
          v += Lk[a] * Lb[a];
        int r = ck[0] > cb[0] ? ck[0] : cb[0], c = ck[0] > cb[0] ? cb[0] : ck[0];
        M[(size_t)c * n + r] += (r == c && b != k ? 2.0 : 1.0) * muk * v;
        continue;
      }
      for (int i = 0; i < nk; ++i)
        for (int j = 0; j < (b == k ? i + 1 : nb); ++j) {
          double v = 0.0;
          for (int a = 0; a < d; ++a)
            v += Lk[a * nk + i] * Lb[a * nb + j];
          v *= muk;
          int r = ck[i], c = cb[j];
          if (r == c && (b != k || i != j)) v *= 2.0;
          if (r < c) {
            int tmp = r;
            r = c;
            c = tmp;
          }
          M[(size_t)c * n + r] += v;
        }
    }
  }
}

int dal__dynamics(const dal_system *sys, dal_state *st, int want_M, double *pw) {
  int d = sys->dim, n = sys->n, rc;
  DAL_NEED(st, DAL_P_KIN);
  want_M = sys->dense_M ? want_M : 0;
  double U = 0.0;
  memset(st->Q, 0, (size_t)n * sizeof(double));
  memset(st->c, 0, (size_t)n * sizeof(double));
  if (sys->N > 0) {
    rc = applied_forces(sys, st, &U, pw);
    if (rc) return rc;
  }
  // Q = sum J_k' F_k, c = sum m_k J_k' gamma_k, M = sum m_k J_k' J_k (over dependencies)
  if (want_M) memset(st->M, 0, (size_t)n * (size_t)n * sizeof(double));
  if (st->tree || (sys->place && !want_M)) {
    tree_assembly(sys, st, want_M);
  } else {
    DAL_NEED(st, DAL_P_J);
    for (int k = 0; k < sys->N; ++k) {
      const int *dk = sys->pdep + sys->pdep_off[k];
      int ndk = sys->pdep_off[k + 1] - sys->pdep_off[k];
      const double *Jk = st->J + sys->pj_off[k];
      double m = st->prm.mass[k];
      for (int a = 0; a < d; ++a) {
        const double *row = Jk + a * ndk;
        double f = st->F[k * d + a], g = m * st->gamma[k * d + a];
        for (int c = 0; c < ndk; ++c) {
          st->Q[dk[c]] += row[c] * f;
          st->c[dk[c]] += row[c] * g;
        }
        if (want_M)
          for (int c2 = 0; c2 < ndk; ++c2) {
            double *col = st->M + (size_t)dk[c2] * n;
            // m (J_ac J_ac2): the product is symmetric in (c, c2), so M is exactly symmetric
            for (int c = 0; c < ndk; ++c)
              col[dk[c]] += m * (row[c] * row[c2]);
          }
      }
    }
  }
  // energies: T from v, and its split by powers of qdot through J qdot = v - dr/dt
  double T = 0.0, T2 = 0.0, T1 = 0.0, T0 = 0.0;
  for (int k = 0; k < sys->N; ++k) {
    double m = st->prm.mass[k];
    for (int a = 0; a < d; ++a) {
      double v = st->v[k * d + a], rt = st->drdt[k * d + a], jq = v - rt;
      T += 0.5 * m * v * v;
      T2 += 0.5 * m * jq * jq;
      T1 += m * jq * rt;
      T0 += 0.5 * m * rt * rt;
    }
  }
  rc = dal__genforces(sys, st, &U, pw);
  if (rc) return rc;
  st->en.T = T;
  st->en.U = U;
  st->en.E = T + U;
  st->en.T2 = T2;
  st->en.T1 = T1;
  st->en.T0 = T0;
  st->en.h = T2 - T0 + U;
  st->have |= DAL_P_DYN;
  if (want_M) {
    // the tree assembly writes the lower triangle; mirror it when the caller reads all of M
    // (an integrator's unconstrained right-hand side needs only the lower one, which
    // Cholesky reads)
    if (want_M > 1 && st->tree)
      for (int j = 0; j < n; ++j)
        for (int i = j + 1; i < n; ++i)
          st->M[(size_t)i * n + j] = st->M[(size_t)j * n + i];
    st->have |= want_M > 1 || !st->tree ? DAL_P_M | DAL_P_MLOW : DAL_P_MLOW;
  }
  return DAL_OK;
}

void dal__mass_apply(const dal_system *sys, const dal_state *st, const double *x, double *y) {
  int n = sys->n, d = sys->dim;
  memset(y, 0, (size_t)n * sizeof(double));
  if (!(st->have & (DAL_P_J | DAL_P_M))) {
    // neither J nor M stored (large recursive trees): through the local blocks
    dal__tree_mass_apply(sys, st, x, y);
    return;
  }
  if (!(st->have & DAL_P_J)) {
    DAL_NEED(st, DAL_P_M);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        y[i] += st->M[(size_t)j * n + i] * x[j];
    return;
  }
  for (int k = 0; k < sys->N; ++k) {
    const int *dk = sys->pdep + sys->pdep_off[k];
    int ndk = sys->pdep_off[k + 1] - sys->pdep_off[k];
    const double *Jk = st->J + sys->pj_off[k];
    for (int a = 0; a < d; ++a) {
      double s = 0.0;
      for (int c = 0; c < ndk; ++c)
        s += Jk[a * ndk + c] * x[dk[c]];
      s *= st->prm.mass[k];
      for (int c = 0; c < ndk; ++c)
        y[dk[c]] += Jk[a * ndk + c] * s;
    }
  }
}

void dal__mass_diag(const dal_system *sys, const dal_state *st, double *md) {
  int n = sys->n, d = sys->dim;
  if (!(st->have & DAL_P_J) && (st->have & DAL_P_M)) {
    for (int j = 0; j < n; ++j)
      md[j] = st->M[(size_t)j * n + j];
    return;
  }
  if (!(st->have & DAL_P_J)) {
    // the local blocks only (large recursive trees): a column at a time
    double *e = calloc(2 * (size_t)n + 1, sizeof(double));
    if (!e) {
      for (int j = 0; j < n; ++j)
        md[j] = 0.0;
      return;
    }
    for (int j = 0; j < n; ++j) {
      e[j] = 1.0;
      dal__mass_apply(sys, st, e, e + n);
      e[j] = 0.0;
      md[j] = e[n + j];
    }
    free(e);
    return;
  }
  // sum_k m_k |J_k e_j|^2 in dal__mass_apply's order (a particle's coordinates are distinct)
  memset(md, 0, (size_t)n * sizeof(double));
  for (int k = 0; k < sys->N; ++k) {
    const int *dk = sys->pdep + sys->pdep_off[k];
    int ndk = sys->pdep_off[k + 1] - sys->pdep_off[k];
    const double *Jk = st->J + sys->pj_off[k];
    for (int a = 0; a < d; ++a)
      for (int c = 0; c < ndk; ++c) {
        double s = Jk[a * ndk + c] * st->prm.mass[k];
        md[dk[c]] += Jk[a * ndk + c] * s;
      }
  }
}

int dal__solve_unconstrained(const dal_system *sys, dal_state *st) {
  int n = sys->n;
  for (int j = 0; j < n; ++j)
    st->qddot[j] = st->Q[j] - st->c[j];
  int bad = -1;
  DAL_NEED(st, DAL_P_MLOW | DAL_P_DYN);
  int rc = dal__chol_solve(n, st->M, st->L, st->qddot, &bad);
  if (rc) return dal__fail_degenerate(sys, st, bad, NULL);
  return DAL_OK;
}

int dal__finish(const dal_system *sys, dal_state *st) {
  int d = sys->dim;
  DAL_NEED(st, DAL_P_KIN | DAL_P_DYN | DAL_P_ACC);
  for (int k = 0; k < sys->N; ++k) {
    for (int a = 0; a < d; ++a) {
      double s = st->gamma[k * d + a];
      if (sys->place) {
        // a_k = Lp_k (a_p - gamma_p) + Lc_k qddot_local + gamma_k
        const dal_place *pk = &sys->place[k];
        const int *ck = sys->ipool + pk->coord_off;
        const double *Lk = st->Lc + sys->ploc_off[k], *Lp = st->Lp + (size_t)k * d * d;
        int p = pk->parent;
        for (int b = 0; b < d && p >= 0; ++b)
          s += Lp[a * d + b] * (st->a[p * d + b] - st->gamma[p * d + b]);
        for (int i = 0; i < pk->ncoord; ++i)
          s += Lk[a * pk->ncoord + i] * st->qddot[ck[i]];
      } else {
        DAL_NEED(st, DAL_P_J);
        const int *dk = sys->pdep + sys->pdep_off[k];
        int ndk = sys->pdep_off[k + 1] - sys->pdep_off[k];
        const double *Jk = st->J + sys->pj_off[k];
        for (int c = 0; c < ndk; ++c)
          s += Jk[a * ndk + c] * st->qddot[dk[c]];
      }
      st->a[k * d + a] = s;
      st->N[k * d + a] = st->prm.mass[k] * s - st->F[k * d + a];
    }
  }
  // explicit time derivatives of the constraint rows, exactly (along t only); h is the
  // Jacobi integral only when none depends on t (state.h)
  int moving = 0;
  for (int ci = 0; ci < sys->ncon; ++ci) {
    int rc = dal__prim_eval(sys, st, -1 - ci, NULL, NULL, 1.0);
    if (rc) return rc;
    const dal_con *c = &sys->con[ci];
    for (int r = 0; r < c->prim->nout; ++r) {
      st->phit[c->row + r] = st->jout[r].d;
      moving |= st->jout[r].d != 0.0;
    }
  }
  if (moving) st->en.h = NAN;
  st->have |= DAL_P_OUT;
  return DAL_OK;
}
