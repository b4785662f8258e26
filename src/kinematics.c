// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Kinematics by jets: positions, velocities, Jacobians, curvature terms, constraint rows.
//
// Each primitive instance is evaluated along each of its local input directions (its local
// Jacobian) and once along the state's direction s -> (q + s qdot, t + s), whose jet gives
// (r, v, gamma) exactly. Global Jacobians follow by the chain rule through parents.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "internal.h"

// position of coordinate j in a sorted list (or -1)
static int find_sorted(const int *list, int n, int j) {
  int lo = 0, hi = n - 1;
  while (lo <= hi) {
    int mid = (lo + hi) / 2;
    if (list[mid] == j) return mid;
    if (list[mid] < j) lo = mid + 1;
    else hi = mid - 1;
  }
  return -1;
}

// the owner of a primitive instance: particle k (owner = k >= 0) or constraint c (-1 - c)
static void owner_name(const dal_system *sys, int owner, char *buf, size_t len) {
  if (owner >= 0) snprintf(buf, len, "particle '%s'", sys->part_names[owner]);
  else snprintf(buf, len, "constraint '%s'", sys->con[-1 - owner].name);
}

// call a jet function and check that every output is finite; names the culprit (the name
// is only formatted on failure: this runs on every evaluation)
static int eval_checked(const dal_system *sys, dal_state *st, const dal_primitive *prim,
                        const double *param, void *ctx, dal_jet t, int owner) {
  const char *kind = owner >= 0 ? "coordinate map" : "constraint";
  char name[160];
  int rc = prim->eval(st->jin, t, param, st->jout, ctx);
  if (rc) {
    char what[240];
    owner_name(sys, owner, name, sizeof name);
    snprintf(what, sizeof what, "%s '%s' of %s", kind, prim->name, name);
    return dal__cb_status(st, rc, what);
  }
  for (int i = 0; i < prim->nout; ++i)
    if (!dal_jet_isfinite(st->jout[i])) {
      char qs[256];
      owner_name(sys, owner, name, sizeof name);
      dal__fmt_q(sys, st->q, qs, sizeof qs);
      return DAL_FAIL(st, DAL_E_DOMAIN,
                      "%s '%s' of %s produced a non-finite value or derivative (output %d: "
                      "%g, %g, %g) at t=%.17g, %s; an input is outside the primitive's domain "
                      "(sqrt/log/asin of an invalid value, a division by zero, a derivative of "
                      "sqrt at 0)",
                      kind, prim->name, name, i, st->jout[i].v, st->jout[i].d, st->jout[i].dd,
                      st->t, qs);
    }
  return DAL_OK;
}

// fill jin with the values u of an instance's inputs: particle positions, then coordinates;
// mode 0: values only, mode 1: the state direction (v and gamma of particles, qdot of coords)
static void load_inputs(const dal_system *sys, dal_state *st, int npart, const int *parts,
                        int ncoord, const int *coords, int mode) {
  int d = sys->dim, k = 0;
  for (int a = 0; a < npart; ++a)
    for (int b = 0; b < d; ++b, ++k) {
      int p = parts[a] * d + b;
      st->jin[k] = mode ? dal_jet_make(st->r[p], st->v[p], st->gamma[p]) : dal_const(st->r[p]);
    }
  for (int i = 0; i < ncoord; ++i, ++k) {
    int j = coords[i];
    st->jin[k] = mode ? dal_var(st->q[j], st->qdot[j]) : dal_const(st->q[j]);
  }
}

// local Jacobian loc (nout x nin, row-major) by one evaluation per input direction
// (directions before `first` are skipped: the caller fills those columns)
static int local_jacobian(const dal_system *sys, dal_state *st, const dal_primitive *prim,
                          const double *param, void *ctx, int owner, int first) {
  int nin = prim->nin, nout = prim->nout;
  dal_jet t = dal_const(st->t);
  for (int i = first; i < nin; ++i) {
    if (i > first) st->jin[i - 1].d = 0.0;
    st->jin[i].d = 1.0;
    int rc = eval_checked(sys, st, prim, param, ctx, t, owner);
    if (rc) return rc;
    for (int a = 0; a < nout; ++a) st->loc[a * nin + i] = st->jout[a].d;
  }
  if (nin > first) st->jin[nin - 1].d = 0.0;
  return DAL_OK;
}

// out (nrow x ndep_out) += loc[:, col0 .. col0+d) * J_p (d x ndep_p), mapping p's dependency
// columns into the output's (both sorted; p's are a subset)
static void chain_particle(const dal_system *sys, const dal_state *st, int p, const double *loc,
                           int nin, int col0, int nrow, const int *dep_out, int ndep_out,
                           double *out) {
  int d = sys->dim;
  const int *dp = sys->pdep + sys->pdep_off[p];
  int ndp = sys->pdep_off[p + 1] - sys->pdep_off[p];
  const double *Jp = st->J + sys->pj_off[p];
  int c = 0;
  for (int cp = 0; cp < ndp; ++cp) {
    while (dep_out[c] != dp[cp]) ++c; // subset of a sorted list: always found
    for (int r = 0; r < nrow; ++r) {
      double s = 0.0;
      for (int b = 0; b < d; ++b) s += loc[r * nin + col0 + b] * Jp[b * ndp + cp];
      out[r * ndep_out + c] += s;
    }
  }
}

// whole-system user map: all particles from r(q, t)
static int kinematics_map(const dal_system *sys, dal_state *st) {
  int n = sys->n, Nd = sys->N * sys->dim;
  dal_jet t = dal_const(st->t);
  for (int j = 0; j < n; ++j) st->jq[j] = dal_const(st->q[j]);
  for (int j = 0; j < n; ++j) {
    st->jq[j].d = 1.0;
    int rc = sys->map(st->jq, t, st->jr, sys->map_ctx);
    st->jq[j].d = 0.0;
    if (rc) return dal__cb_status(st, rc, "whole-system coordinate map");
    for (int i = 0; i < Nd; ++i) {
      if (!dal_jet_isfinite(st->jr[i]))
        return DAL_FAIL(st, DAL_E_DOMAIN,
                        "whole-system coordinate map produced a non-finite value for particle "
                        "'%s' at t=%.17g (coordinate direction '%s')",
                        sys->part_names[i / sys->dim], st->t, sys->coord_names[j]);
      // particle k's compact J has all n columns: J_k[a, j]
      st->J[(size_t)(i / sys->dim) * sys->dim * n + (size_t)(i % sys->dim) * n + j] =
          st->jr[i].d;
    }
  }
  for (int j = 0; j < n; ++j) st->jq[j] = dal_var(st->q[j], st->qdot[j]);
  int rc = sys->map(st->jq, dal_var(st->t, 1.0), st->jr, sys->map_ctx);
  if (rc) return dal__cb_status(st, rc, "whole-system coordinate map");
  for (int i = 0; i < Nd; ++i) {
    if (!dal_jet_isfinite(st->jr[i]))
      return DAL_FAIL(st, DAL_E_DOMAIN,
                      "whole-system coordinate map produced a non-finite value for particle "
                      "'%s' at t=%.17g", sys->part_names[i / sys->dim], st->t);
    st->r[i] = st->jr[i].v;
    st->v[i] = st->jr[i].d;
    st->gamma[i] = st->jr[i].dd;
  }
  return DAL_OK;
}

int dal__kinematics(const dal_system *sys, dal_state *st) {
  int d = sys->dim, rc;
  if (sys->N == 0) return DAL_OK;
  if (sys->map) {
    rc = kinematics_map(sys, st);
    if (rc) return rc;
    st->tree = 0;
    st->J_valid = 1;
  } else {
  restart:
    st->tree = 1;
    st->J_valid = st->need_J;
    for (int k = 0; k < sys->N; ++k) {
      const dal_place *pl = &sys->place[k];
      const dal_primitive *prim = pl->prim;
      const int *coords = sys->ipool + pl->coord_off;
      const double *param = st->prm.ppool + pl->param_off;
      int np = pl->parent >= 0 ? 1 : 0, nin = prim->nin, nc = pl->ncoord;
      // local Jacobian at the current values; a translating map's parent block is I
      int translates = np && (prim->flags & DAL_PRIM_TRANSLATES);
      load_inputs(sys, st, np, &pl->parent, nc, coords, 0);
      rc = local_jacobian(sys, st, prim, param, pl->ctx, k, translates ? d : 0);
      if (rc) return rc;
      int identity = 1;
      for (int a = 0; a < d && np; ++a)
        for (int b = 0; b < d; ++b) {
          if (translates) st->loc[a * nin + b] = a == b;
          identity &= st->loc[a * nin + b] == (a == b);
        }
      st->tree &= identity;
      if (!identity && !st->J_valid) {
        // a link that is not a translation: form J for every particle from now on
        st->need_J = 1;
        goto restart;
      }
      double *Lk = st->Lc + sys->ploc_off[k];
      for (int a = 0; a < d; ++a)
        for (int i = 0; i < nc; ++i) Lk[a * nc + i] = st->loc[a * nin + np * d + i];
      // along the state direction: r, v, gamma
      load_inputs(sys, st, np, &pl->parent, pl->ncoord, coords, 1);
      rc = eval_checked(sys, st, prim, param, pl->ctx, dal_var(st->t, 1.0), k);
      if (rc) return rc;
      for (int a = 0; a < d; ++a) {
        st->r[k * d + a] = st->jout[a].v;
        st->v[k * d + a] = st->jout[a].d;
        st->gamma[k * d + a] = st->jout[a].dd;
      }
      // global Jacobian by the chain rule (not needed by a tree of translations without
      // constraints: M, Q, c, dr/dt and accelerations then come from the local columns)
      const int *dk = sys->pdep + sys->pdep_off[k];
      int ndk = sys->pdep_off[k + 1] - sys->pdep_off[k];
      double *Jk = st->J + sys->pj_off[k];
      if (st->J_valid) {
        memset(Jk, 0, (size_t)d * (size_t)ndk * sizeof(double));
        if (np) chain_particle(sys, st, pl->parent, st->loc, nin, 0, d, dk, ndk, Jk);
        for (int i = 0; i < nc; ++i) {
          int c = find_sorted(dk, ndk, coords[i]);
          for (int a = 0; a < d; ++a) Jk[a * ndk + c] += Lk[a * nc + i];
        }
      }
      // dr/dt = v - J qdot; through a translation J_k qdot = J_p qdot + L_k qdot_local
      if (identity) {
        int p = pl->parent;
        for (int a = 0; a < d; ++a) {
          double s = np ? st->v[p * d + a] - st->drdt[p * d + a] : 0.0;
          for (int i = 0; i < nc; ++i) s += Lk[a * nc + i] * st->qdot[coords[i]];
          st->drdt[k * d + a] = st->v[k * d + a] - s;
        }
      } else {
        for (int a = 0; a < d; ++a) {
          double s = 0.0;
          for (int c = 0; c < ndk; ++c) s += Jk[a * ndk + c] * st->qdot[dk[c]];
          st->drdt[k * d + a] = st->v[k * d + a] - s;
        }
      }
    }
    return DAL_OK;
  }
  // explicit time derivative dr/dt = v - J qdot
  for (int k = 0; k < sys->N; ++k) {
    const int *dk = sys->pdep + sys->pdep_off[k];
    int ndk = sys->pdep_off[k + 1] - sys->pdep_off[k];
    const double *Jk = st->J + sys->pj_off[k];
    for (int a = 0; a < d; ++a) {
      double s = 0.0;
      for (int c = 0; c < ndk; ++c) s += Jk[a * ndk + c] * st->qdot[dk[c]];
      st->drdt[k * d + a] = st->v[k * d + a] - s;
    }
  }
  return DAL_OK;
}

int dal__constraints(const dal_system *sys, dal_state *st) {
  int d = sys->dim, rc;
  for (int ci = 0; ci < sys->ncon; ++ci) {
    const dal_con *c = &sys->con[ci];
    const dal_primitive *prim = c->prim;
    const int *parts = sys->ipool + c->part_off;
    const int *coords = sys->ipool + c->coord_off;
    const double *param = st->prm.ppool + c->param_off;
    int nin = prim->nin, nout = prim->nout;
    load_inputs(sys, st, c->npart, parts, c->ncoord, coords, 0);
    rc = local_jacobian(sys, st, prim, param, c->ctx, -1 - ci, 0);
    if (rc) return rc;
    load_inputs(sys, st, c->npart, parts, c->ncoord, coords, 1);
    rc = eval_checked(sys, st, prim, param, c->ctx, dal_var(st->t, 1.0), -1 - ci);
    if (rc) return rc;
    for (int r = 0; r < nout; ++r) {
      st->phi[c->row + r] = st->jout[r].v;
      st->phidot[c->row + r] = st->jout[r].d;
      st->gphi[c->row + r] = st->jout[r].dd;
    }
    const int *dc = sys->cdep + c->dep_off;
    double *G = st->G + c->g_off;
    memset(G, 0, (size_t)nout * (size_t)c->ndep * sizeof(double));
    for (int a = 0; a < c->npart; ++a)
      chain_particle(sys, st, parts[a], st->loc, nin, a * d, nout, dc, c->ndep, G);
    for (int i = 0; i < c->ncoord; ++i) {
      int col = find_sorted(dc, c->ndep, coords[i]);
      for (int r = 0; r < nout; ++r) G[r * c->ndep + col] += st->loc[r * nin + c->npart * d + i];
    }
  }
  return DAL_OK;
}
