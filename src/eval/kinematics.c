// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Kinematics by jets: positions, velocities, Jacobians, curvature terms, constraint rows.
//
// Each primitive instance is evaluated along each of its local input directions (its local
// Jacobian) and once along the state's motion s -> (q + s qdot, t + s), whose jet gives
// (r, v, gamma) exactly. A placement's local Jacobian has a parent block Lp (d x d) and
// coordinate columns Lc (d x ncoord); global Jacobians follow by the chain rule through
// parents, J_k = Lp_k J_parent + Lc_k, and are formed only when asked for.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "eval.h"

// position of coordinate j in a sorted list (or -1)
static int find_sorted(const int *list, int n, int j) {
  int lo = 0, hi = n - 1;
  while (lo <= hi) {
    int mid = (lo + hi) / 2;
    if (list[mid] == j) return mid;
    if (list[mid] < j)
      lo = mid + 1;
    else
      hi = mid - 1;
  }
  return -1;
}

dal_inst dal__inst(const dal_system *sys, const dal_state *st, int owner) {
  dal_inst in;
  if (owner >= 0) {
    const dal_place *pl = &sys->place[owner];
    in.prim = pl->prim;
    in.param = st->prm.ppool + pl->param_off;
    in.ctx = pl->ctx;
    in.npart = pl->parent >= 0 ? 1 : 0;
    in.parts = &pl->parent;
    in.ncoord = pl->ncoord;
    in.coords = sys->ipool + pl->coord_off;
  } else {
    const dal_con *c = &sys->con[-1 - owner];
    in.prim = c->prim;
    in.param = st->prm.ppool + c->param_off;
    in.ctx = c->ctx;
    in.npart = c->npart;
    in.parts = sys->ipool + c->part_off;
    in.ncoord = c->ncoord;
    in.coords = sys->ipool + c->coord_off;
  }
  return in;
}

// the owner of a primitive instance: particle k (owner = k >= 0) or constraint c (-1 - c)
static void owner_name(const dal_system *sys, int owner, char *buf, size_t len) {
  if (owner >= 0)
    snprintf(buf, len, "particle '%s'", sys->part_names[owner]);
  else
    snprintf(buf, len, "constraint '%s'", sys->con[-1 - owner].name);
}

// the failure of a jet function call (cold path of eval_checked): names the culprit
static int eval_failed(const dal_system *sys, dal_state *st, const dal_inst *in, dal_jet t,
                       int owner, int rc) {
  const char *kind = owner >= 0 ? "coordinate map" : "constraint";
  char name[160];
  if (rc) {
    char what[240];
    owner_name(sys, owner, name, sizeof name);
    snprintf(what, sizeof what, "%s '%s' of %s", kind, in->prim->name, name);
    return dal__cb_status(st, rc, what);
  }
  for (int i = 0; i < in->prim->nout; ++i)
    if (!dal_jet_isfinite(st->jout[i])) {
      char qs[256];
      owner_name(sys, owner, name, sizeof name);
      dal__fmt_q(sys, st->q, qs, sizeof qs);
      // huge inputs: the arithmetic overflowed (a trial step too long, or velocities whose
      // squares exceed double range), not a domain error of the function
      double big = fmax(dal__jets_max(st->jin, in->prim->nin), fmax(fabs(t.d), fabs(t.dd)));
      if (big > DAL_JET_OVERFLOW)
        return DAL_FAIL(st, DAL__RETRY_NONFINITE,
                        "%s '%s' of %s overflows at t=%.17g, %s: its inputs along the motion "
                        "reach %g (positions, velocities or accelerations whose products exceed "
                        "double range), output %d is (%g, %g, %g)",
                        kind, in->prim->name, name, st->t, qs, big, i, st->jout[i].v, st->jout[i].d,
                        st->jout[i].dd);
      return DAL_FAIL(st, DAL_E_DOMAIN,
                      "%s '%s' of %s produced a non-finite value or derivative (output %d: "
                      "%g, %g, %g) at t=%.17g, %s; an input is outside the primitive's domain "
                      "(sqrt/log/asin of an invalid value, a division by zero, a derivative of "
                      "sqrt at 0)",
                      kind, in->prim->name, name, i, st->jout[i].v, st->jout[i].d, st->jout[i].dd,
                      st->t, qs);
    }
  return DAL_OK;
}

// call a jet function on st->jin and check that every output is finite; names the culprit
// (this runs twice per placement on every evaluation: one test of the outputs' sum, which is
// finite when they all are; an overflowing sum of finite outputs only costs the exact check
// of the cold path, which then finds nothing; the message is formatted only on failure)
static int eval_checked(const dal_system *sys, dal_state *st, const dal_inst *in, dal_jet t,
                        int owner) {
  int rc = in->prim->eval(st->jin, t, in->param, st->jout, in->ctx);
  double z = 0.0;
  for (int i = 0; i < in->prim->nout; ++i)
    z += st->jout[i].v + st->jout[i].d + st->jout[i].dd;
  if (rc || !isfinite(z)) return eval_failed(sys, st, in, t, owner, rc);
  return DAL_OK;
}

// the values u of an instance's inputs (particle positions, then coordinates) as jets on the
// curve u + s d1 + s^2/2 d2 (d1, d2 nullable)
static void load_inputs(const dal_system *sys, dal_state *st, const dal_inst *in, const double *d1,
                        const double *d2) {
  int d = sys->dim, k = 0;
  for (int a = 0; a < in->npart; ++a)
    for (int b = 0; b < d; ++b, ++k)
      st->jin[k] = dal_jet_make(st->r[in->parts[a] * d + b], d1 ? d1[k] : 0.0, d2 ? d2[k] : 0.0);
  for (int i = 0; i < in->ncoord; ++i, ++k)
    st->jin[k] = dal_jet_make(st->q[in->coords[i]], d1 ? d1[k] : 0.0, d2 ? d2[k] : 0.0);
}

int dal__prim_eval(const dal_system *sys, dal_state *st, int owner, const double *d1,
                   const double *d2, double tdot) {
  dal_inst in = dal__inst(sys, st, owner);
  load_inputs(sys, st, &in, d1, d2);
  return eval_checked(sys, st, &in, dal_var(st->t, tdot), owner);
}

// the state's motion in an instance's local inputs: d1 = (v of particles, qdot of
// coordinates), d2 = (gamma of particles, 0) into st->dir (2 x nin)
static void local_motion(const dal_system *sys, dal_state *st, const dal_inst *in) {
  int d = sys->dim, nin = in->prim->nin, k = 0;
  double *d1 = st->dir, *d2 = st->dir + nin;
  for (int a = 0; a < in->npart; ++a)
    for (int b = 0; b < d; ++b, ++k) {
      d1[k] = st->v[in->parts[a] * d + b];
      d2[k] = st->gamma[in->parts[a] * d + b];
    }
  for (int i = 0; i < in->ncoord; ++i, ++k) {
    d1[k] = st->qdot[in->coords[i]];
    d2[k] = 0.0;
  }
}

// local Jacobian loc (nout x nin, row-major) by one evaluation per input direction
// (directions before `first` are skipped: the caller fills those columns)
static int local_jacobian(const dal_system *sys, dal_state *st, const dal_inst *in, int owner,
                          int first) {
  int nin = in->prim->nin, nout = in->prim->nout, d = sys->dim, k = 0;
  dal_jet t = dal_const(st->t);
  // the inputs' values (particle positions, then coordinates) with no direction yet
  for (int a = 0; a < in->npart; ++a) {
    const double *r = st->r + in->parts[a] * d;
    for (int b = 0; b < d; ++b)
      st->jin[k++] = dal_const(r[b]);
  }
  for (int i = 0; i < in->ncoord; ++i)
    st->jin[k++] = dal_const(st->q[in->coords[i]]);
  for (int i = first; i < nin; ++i) {
    if (i > first) st->jin[i - 1].d = 0.0;
    st->jin[i].d = 1.0;
    int rc = eval_checked(sys, st, in, t, owner);
    if (rc) return rc;
    for (int a = 0; a < nout; ++a)
      st->loc[a * nin + i] = st->jout[a].d;
  }
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
    while (dep_out[c] != dp[cp])
      ++c; // subset of a sorted list: always found
    for (int r = 0; r < nrow; ++r) {
      double s = 0.0;
      for (int b = 0; b < d; ++b)
        s += loc[r * nin + col0 + b] * Jp[b * ndp + cp];
      out[r * ndep_out + c] += s;
    }
  }
}

// the whole-system map gave a non-finite output i (along coordinate direction `dir`, or the
// motion when NULL): an overflow of huge inputs (a retry) or a domain error
static int map_nonfinite(const dal_system *sys, dal_state *st, int i, const char *dir) {
  double big = dal__jets_max(st->jq, sys->n);
  if (big > DAL_JET_OVERFLOW)
    return DAL_FAIL(st, DAL__RETRY_NONFINITE,
                    "whole-system coordinate map overflows for particle '%s' at t=%.17g: its "
                    "inputs along the motion reach %g (coordinates, velocities whose products "
                    "exceed double range)",
                    sys->part_names[i / sys->dim], st->t, big);
  return DAL_FAIL(st, DAL_E_DOMAIN,
                  "whole-system coordinate map produced a non-finite value for particle '%s' at "
                  "t=%.17g%s%s%s",
                  sys->part_names[i / sys->dim], st->t, dir ? " (coordinate direction '" : "",
                  dir ? dir : "", dir ? "')" : "");
}

// whole-system user map: all particles from r(q, t), with J (all n columns per particle)
static int kinematics_map(const dal_system *sys, dal_state *st) {
  int n = sys->n, Nd = sys->N * sys->dim;
  dal_jet t = dal_const(st->t);
  for (int j = 0; j < n; ++j)
    st->jq[j] = dal_const(st->q[j]);
  for (int j = 0; j < n; ++j) {
    st->jq[j].d = 1.0;
    int rc = sys->map(st->jq, t, st->jr, sys->map_ctx);
    st->jq[j].d = 0.0;
    if (rc) return dal__cb_status(st, rc, "whole-system coordinate map");
    for (int i = 0; i < Nd; ++i) {
      if (!dal_jet_isfinite(st->jr[i])) return map_nonfinite(sys, st, i, sys->coord_names[j]);
      st->J[(size_t)(i / sys->dim) * sys->dim * n + (size_t)(i % sys->dim) * n + j] = st->jr[i].d;
    }
  }
  for (int j = 0; j < n; ++j)
    st->jq[j] = dal_var(st->q[j], st->qdot[j]);
  int rc = sys->map(st->jq, dal_var(st->t, 1.0), st->jr, sys->map_ctx);
  if (rc) return dal__cb_status(st, rc, "whole-system coordinate map");
  for (int i = 0; i < Nd; ++i) {
    if (!dal_jet_isfinite(st->jr[i])) return map_nonfinite(sys, st, i, NULL);
    st->r[i] = st->jr[i].v;
    st->v[i] = st->jr[i].d;
    st->gamma[i] = st->jr[i].dd;
  }
  // explicit time derivative dr/dt = v - J qdot
  int d = sys->dim;
  for (int k = 0; k < sys->N; ++k)
    for (int a = 0; a < d; ++a) {
      const double *row = st->J + (size_t)k * d * n + (size_t)a * n;
      double s = 0.0;
      for (int c = 0; c < n; ++c)
        s += row[c] * st->qdot[c];
      st->drdt[k * d + a] = st->v[k * d + a] - s;
    }
  st->tree = 0;
  st->have |= DAL_P_KIN | DAL_P_J;
  return DAL_OK;
}

// A particle placed by its own Cartesian coordinates (dal_map_cartesian2/3, no parent): the
// identity map, whose jets give r = q, v = qdot, gamma = 0, local Jacobian I and dr/dt =
// v - I qdot = 0 exactly; written out here because this is the whole kinematics of the
// redundant-coordinate (DAE) scenes (tests/test_newton.c compares it with the jet path).
static inline int cartesian_place(const dal_place *pl, int d) {
  return pl->parent < 0 && pl->prim == (d == 2 ? &dal_map_cartesian2 : &dal_map_cartesian3);
}

// J_k = Lp_k J_parent + Lc_k over k's dependency columns (parents first)
void dal__jacobians(const dal_system *sys, dal_state *st) {
  DAL_NEED(st, DAL_P_KIN);
  DAL_ASSERT(sys->store_J);
  int d = sys->dim;
  for (int k = 0; k < sys->N; ++k) {
    const dal_place *pl = &sys->place[k];
    const int *coords = sys->ipool + pl->coord_off;
    const int *dk = sys->pdep + sys->pdep_off[k];
    int ndk = sys->pdep_off[k + 1] - sys->pdep_off[k], nc = pl->ncoord;
    double *Jk = st->J + sys->pj_off[k];
    const double *Lk = st->Lc + sys->ploc_off[k];
    if (cartesian_place(pl, d)) {
      // the identity on k's own coordinates (its dependencies, sorted)
      for (int a = 0; a < d; ++a)
        for (int c = 0; c < ndk; ++c)
          Jk[a * ndk + c] = dk[c] == coords[a] ? 1.0 : 0.0;
      continue;
    }
    memset(Jk, 0, (size_t)d * (size_t)ndk * sizeof(double));
    if (pl->parent >= 0)
      chain_particle(sys, st, pl->parent, st->Lp + (size_t)k * d * d, d, 0, d, dk, ndk, Jk);
    for (int i = 0; i < nc; ++i) {
      int c = find_sorted(dk, ndk, coords[i]);
      for (int a = 0; a < d; ++a)
        Jk[a * ndk + c] += Lk[a * nc + i];
    }
  }
  st->have |= DAL_P_J;
}

// The common placement, a translating map of one coordinate (chains, pendulums hanging from a
// particle), for d = 2 or 3 (a constant once inlined): the same two evaluations as the general
// loop below (the column along the coordinate, then the motion) without its bookkeeping.
static inline int place_translating1(const dal_system *sys, dal_state *st, int k, const int d) {
  const dal_place *pl = &sys->place[k];
  dal_inst in = dal__inst(sys, st, k);
  int p = pl->parent, j = in.coords[0], rc;
  const double *rp = st->r + p * d, *vp = st->v + p * d, *gp = st->gamma + p * d;
  const double *rtp = st->drdt + p * d;
  double *Lp = st->Lp + (size_t)k * d * d, *Lk = st->Lc + sys->ploc_off[k];
  dal_jet *jin = st->jin, *jout = st->jout;
  for (int b = 0; b < d; ++b)
    jin[b] = dal_const(rp[b]);
  jin[d] = dal_var(st->q[j], 1.0);
  if ((rc = eval_checked(sys, st, &in, dal_const(st->t), k)) != 0) return rc;
  for (int a = 0; a < d; ++a) {
    Lk[a] = jout[a].d;
    for (int b = 0; b < d; ++b)
      Lp[a * d + b] = a == b;
  }
  for (int b = 0; b < d; ++b)
    jin[b] = dal_jet_make(rp[b], vp[b], gp[b]);
  double qd = st->qdot[j];
  jin[d] = dal_var(st->q[j], qd);
  if ((rc = eval_checked(sys, st, &in, dal_var(st->t, 1.0), k)) != 0) return rc;
  // dr/dt = v - (v_p - drdt_p) - Lc qdot
  for (int a = 0; a < d; ++a) {
    double v = jout[a].d;
    st->r[k * d + a] = jout[a].v;
    st->v[k * d + a] = v;
    st->gamma[k * d + a] = jout[a].dd;
    st->drdt[k * d + a] = v - (vp[a] - rtp[a]) - Lk[a] * qd;
  }
  return DAL_OK;
}

static void place_cartesian(const dal_system *sys, dal_state *st, int k, int d) {
  const dal_place *pl = &sys->place[k];
  const int *coords = sys->ipool + pl->coord_off;
  double *Lk = st->Lc + sys->ploc_off[k];
  for (int a = 0; a < d; ++a) {
    int j = coords[a];
    st->r[k * d + a] = st->q[j];
    st->v[k * d + a] = st->qdot[j];
    st->gamma[k * d + a] = 0.0;
    st->drdt[k * d + a] = 0.0;
    for (int i = 0; i < d; ++i)
      Lk[a * d + i] = a == i;
  }
}

// A particle hanging from its parent by a rod of length l at angle q (dal_map_hanging, the
// links of planar chains): r = r_p + l (sin q, -cos q). Its two jet evaluations (along the
// coordinate, then along the motion) written out with one sin and cos, in the jet path's own
// arithmetic and order (dal_var, dal_sincos, dal_scale, dal_add/dal_sub of jet.h), so the
// results agree bit for bit (tests/test_fastpath.c). Returns 0, or -1 when a result is not
// finite (nothing is written; the jet path then names the failure).
static int place_hanging(const dal_system *sys, dal_state *st, int k) {
  const dal_place *pl = &sys->place[k];
  int p = pl->parent, j = sys->ipool[pl->coord_off];
  double l = st->prm.ppool[pl->param_off], q = st->q[j], qd = st->qdot[j];
  const double *rp = st->r + p * 2, *vp = st->v + p * 2, *gp = st->gamma + p * 2;
  const double *rtp = st->drdt + p * 2;
  double sv = sin(q), cv = cos(q);
  // along the coordinate (direction 1): the column Lc
  double L0 = 0.0 + l * (cv * 1.0), L1 = 0.0 - l * (-sv * 1.0);
  // along the motion: sin and cos of (q, qd, 0) and the parent's (r, v, gamma)
  double sd = cv * qd, sdd = cv * 0.0 + -sv * qd * qd;
  double cd = -sv * qd, cdd = -sv * 0.0 + -cv * qd * qd;
  double r0 = rp[0] + l * sv, v0 = vp[0] + l * sd, g0 = gp[0] + l * sdd;
  double r1 = rp[1] - l * cv, v1 = vp[1] - l * cd, g1 = gp[1] - l * cdd;
  if (!isfinite(r0 + v0 + g0 + r1 + v1 + g1 + L0 + L1)) return -1;
  double *Lp = st->Lp + (size_t)k * 4, *Lk = st->Lc + sys->ploc_off[k];
  Lk[0] = L0;
  Lk[1] = L1;
  Lp[0] = Lp[3] = 1.0;
  Lp[1] = Lp[2] = 0.0;
  st->r[k * 2] = r0;
  st->r[k * 2 + 1] = r1;
  st->v[k * 2] = v0;
  st->v[k * 2 + 1] = v1;
  st->gamma[k * 2] = g0;
  st->gamma[k * 2 + 1] = g1;
  st->drdt[k * 2] = v0 - (vp[0] - rtp[0]) - L0 * qd;
  st->drdt[k * 2 + 1] = v1 - (vp[1] - rtp[1]) - L1 * qd;
  return 0;
}

int dal__kinematics(const dal_system *sys, dal_state *st, int want_J) {
  int d = sys->dim, rc;
  st->tree = sys->place != NULL;
  if (sys->N == 0) {
    st->have |= DAL_P_KIN | DAL_P_J;
    return DAL_OK;
  }
  if (sys->map) return kinematics_map(sys, st);
  for (int k = 0; k < sys->N; ++k) {
    const dal_place *pl = &sys->place[k];
    if (cartesian_place(pl, d)) {
      place_cartesian(sys, st, k, d);
      continue;
    }
    if (pl->prim == &dal_map_hanging && d == 2 && pl->parent >= 0 && pl->ncoord == 1 &&
        place_hanging(sys, st, k) == 0)
      continue;
    if (pl->ncoord == 1 && pl->parent >= 0 && (pl->prim->flags & DAL_PRIM_TRANSLATES) &&
        pl->prim->nin == d + 1) {
      rc = d == 2 ? place_translating1(sys, st, k, 2) : place_translating1(sys, st, k, 3);
      if (rc) return rc;
      continue;
    }
    dal_inst in = dal__inst(sys, st, k);
    int np = in.npart, nin = in.prim->nin, nc = pl->ncoord, p = pl->parent;
    // local Jacobian at the current values; a translating map's parent block is I
    int translates = np && (in.prim->flags & DAL_PRIM_TRANSLATES);
    rc = local_jacobian(sys, st, &in, k, translates ? d : 0);
    if (rc) return rc;
    double *Lp = st->Lp + (size_t)k * d * d, *Lk = st->Lc + sys->ploc_off[k];
    const double *vp = st->v + (np ? p * d : 0), *rtp = st->drdt + (np ? p * d : 0);
    if (translates) {
      static const double eye[2][9] = {{1, 0, 0, 1}, {1, 0, 0, 0, 1, 0, 0, 0, 1}};
      memcpy(Lp, eye[d - 2], (size_t)(d * d) * sizeof(double));
    } else if (np) {
      int identity = 1;
      for (int a = 0; a < d; ++a)
        for (int b = 0; b < d; ++b) {
          Lp[a * d + b] = st->loc[a * nin + b];
          identity &= Lp[a * d + b] == (a == b);
        }
      st->tree &= identity;
    }
    if (nc == 1)
      for (int a = 0; a < d; ++a)
        Lk[a] = st->loc[a * nin + np * d];
    else
      for (int a = 0; a < d; ++a)
        for (int i = 0; i < nc; ++i)
          Lk[a * nc + i] = st->loc[a * nin + np * d + i];
    // along the state's motion: the inputs keep their values and move along (v, gamma) of the
    // parent and (qdot, 0) of the coordinates; r, v, gamma
    dal_jet *jin = st->jin;
    for (int b = 0; b < d && np; ++b) {
      jin[b].d = vp[b];
      jin[b].dd = st->gamma[p * d + b];
    }
    for (int i = 0; i < nc; ++i) {
      jin[np * d + i].d = st->qdot[in.coords[i]];
      jin[np * d + i].dd = 0.0;
    }
    rc = eval_checked(sys, st, &in, dal_var(st->t, 1.0), k);
    if (rc) return rc;
    // dr/dt = v - J_k qdot, with J_k qdot = Lp_k (v_p - drdt_p) + Lc_k qdot_local
    for (int a = 0; a < d; ++a) {
      double s = 0.0, v = st->jout[a].d;
      if (translates)
        s = vp[a] - rtp[a];
      else
        for (int b = 0; b < d && np; ++b)
          s += Lp[a * d + b] * (vp[b] - rtp[b]);
      if (nc == 1)
        s += Lk[a] * jin[np * d].d;
      else
        for (int i = 0; i < nc; ++i)
          s += Lk[a * nc + i] * jin[np * d + i].d;
      st->r[k * d + a] = st->jout[a].v;
      st->v[k * d + a] = v;
      st->gamma[k * d + a] = st->jout[a].dd;
      st->drdt[k * d + a] = v - s;
    }
  }
  st->have |= DAL_P_KIN;
  // global Jacobians only when asked for (the caller asks when the assembly of M for a link
  // that is not a translation needs them; Q and c come from the local blocks)
  if (want_J) dal__jacobians(sys, st);
  return DAL_OK;
}

// out (nrow x ndep_out) += loc[:, col0 .. col0+d) * J_p without J: the row w = loc[r, col0..]
// walks from p to its root, adding w Lc_b to b's coordinate columns and turning into w Lp_b
// (O(depth) per row; the recursion's systems keep no global Jacobians on their fast path)
static void chain_local(const dal_system *sys, const dal_state *st, int p, const double *loc,
                        int nin, int col0, int nrow, const int *dep_out, int ndep_out,
                        double *out) {
  int d = sys->dim;
  for (int r = 0; r < nrow; ++r) {
    double w[3], t[3];
    for (int a = 0; a < d; ++a)
      w[a] = loc[r * nin + col0 + a];
    for (int b = p; b >= 0; b = sys->place[b].parent) {
      const dal_place *pb = &sys->place[b];
      const int *cb = sys->ipool + pb->coord_off;
      const double *Lc = st->Lc + sys->ploc_off[b], *Lp = st->Lp + (size_t)b * d * d;
      for (int i = 0; i < pb->ncoord; ++i) {
        double s = 0.0;
        for (int a = 0; a < d; ++a)
          s += w[a] * Lc[a * pb->ncoord + i];
        out[r * ndep_out + find_sorted(dep_out, ndep_out, cb[i])] += s;
      }
      if (pb->parent < 0) break;
      for (int a = 0; a < d; ++a) {
        t[a] = 0.0;
        for (int c = 0; c < d; ++c)
          t[a] += w[c] * Lp[c * d + a];
      }
      for (int a = 0; a < d; ++a)
        w[a] = t[a];
    }
  }
}

// A rod, |r_b - r_a| - L between two particles (dal_con_distance2/3) or to a fixed point x0
// (dal_con_anchor2/3 without a moving-point context): the local row G = (-e, e) / |e|, phi,
// phidot and gamma_phi from the same arithmetic, in the same order, as the jet path (dal_sub,
// dal_sq, dal_add, dal_sqrt of jet.h), so the results agree bit for bit (tests/test_newton.c).
// Rods are most of the constraints of redundant-coordinate scenes, and this replaces nin + 1
// jet evaluations by a few flops. Returns 0 when it applies and the rod has a length;
// otherwise nothing is written and the jet path runs (it names a zero-length rod).
static int rod_rows(const dal_system *sys, dal_state *st, const dal_con *c, const dal_inst *in) {
  int d = sys->dim, two = c->prim == &dal_con_distance2 || c->prim == &dal_con_distance3;
  const double *p = in->param;
  const int *parts = in->parts;
  // e = r_b - r_a (or r - x0) with its first and second derivative along the motion
  const double *ra = two ? st->r + parts[0] * d : p + 1, *rb = st->r + parts[two] * d;
  const double *vb = st->v + parts[two] * d, *gb = st->gamma + parts[two] * d;
  double e[3], s = 0.0, sd = 0.0, sdd = 0.0;
  for (int i = 0; i < d; ++i) {
    e[i] = rb[i] - ra[i];
    double w = two ? vb[i] - st->v[parts[0] * d + i] : vb[i];
    double g = two ? gb[i] - st->gamma[parts[0] * d + i] : gb[i];
    s += e[i] * e[i];
    sd += 2.0 * e[i] * w;
    sdd += 2.0 * (w * w + e[i] * g);
  }
  // |e| as dal_sqrt: the derivatives d, dd of the square root of (s, sd, sdd)
  double len = sqrt(s), len2 = 2.0 * len;
  double dl = 0.0, ddl = 0.0;
  if (sd != 0.0 || sdd != 0.0) {
    dl = sd / len2;
    ddl = (sdd - 2.0 * dl * dl) / len2;
  }
  if (!(len > 0.0) || !isfinite(len2) || !isfinite(dl) || !isfinite(ddl)) return -1;
  // the local row: along the input direction of e_i, s' = +-2 e_i and |e|' = s' / (2 |e|)
  for (int i = 0; i < d; ++i) {
    double gi = 2.0 * e[i] / len2;
    if (!isfinite(gi)) return -1;
    if (two) st->loc[i] = -2.0 * e[i] / len2;
    st->loc[(two ? d : 0) + i] = gi;
  }
  st->phi[c->row] = len - p[0];
  st->phidot[c->row] = dl;
  st->gphi[c->row] = ddl;
  return 0;
}

// a rod on particle positions (its inputs may also be given as coordinates: the jet path)
static int is_rod(const dal_con *c) {
  if (c->ncoord) return 0;
  if (c->prim == &dal_con_distance2 || c->prim == &dal_con_distance3) return c->npart == 2;
  return (c->prim == &dal_con_anchor2 || c->prim == &dal_con_anchor3) && !c->ctx && c->npart == 1;
}

int dal__constraints(const dal_system *sys, dal_state *st) {
  int d = sys->dim, rc;
  // compact G through the global Jacobians, or (recursive systems) through the local blocks
  int have_J = (st->have & DAL_P_J) != 0;
  DAL_NEED(st, DAL_P_KIN);
  DAL_ASSERT(have_J || sys->aba);
  for (int ci = 0; ci < sys->ncon; ++ci) {
    const dal_con *c = &sys->con[ci];
    dal_inst in = dal__inst(sys, st, -1 - ci);
    int nin = in.prim->nin, nout = in.prim->nout;
    if (!is_rod(c) || rod_rows(sys, st, c, &in) != 0) {
      rc = local_jacobian(sys, st, &in, -1 - ci, 0);
      if (rc) return rc;
      local_motion(sys, st, &in);
      load_inputs(sys, st, &in, st->dir, st->dir + nin);
      rc = eval_checked(sys, st, &in, dal_var(st->t, 1.0), -1 - ci);
      if (rc) return rc;
      for (int r = 0; r < nout; ++r) {
        st->phi[c->row + r] = st->jout[r].v;
        st->phidot[c->row + r] = st->jout[r].d;
        st->gphi[c->row + r] = st->jout[r].dd;
      }
    }
    memcpy(st->Gl + sys->con_loff[ci], st->loc, (size_t)nout * (size_t)nin * sizeof(double));
    const int *dc = sys->cdep + c->dep_off;
    double *G = st->G + c->g_off;
    memset(G, 0, (size_t)nout * (size_t)c->ndep * sizeof(double));
    for (int a = 0; a < c->npart; ++a) {
      int p = in.parts[a];
      if (sys->place && cartesian_place(&sys->place[p], d)) {
        // J_p = I on p's own coordinates: the local columns are G's columns
        const int *cp = sys->ipool + sys->place[p].coord_off;
        for (int b = 0; b < d; ++b) {
          int col = find_sorted(dc, c->ndep, cp[b]);
          for (int r = 0; r < nout; ++r)
            G[r * c->ndep + col] += st->loc[r * nin + a * d + b];
        }
      } else if (have_J) {
        chain_particle(sys, st, p, st->loc, nin, a * d, nout, dc, c->ndep, G);
      } else {
        chain_local(sys, st, p, st->loc, nin, a * d, nout, dc, c->ndep, G);
      }
    }
    for (int i = 0; i < c->ncoord; ++i) {
      int col = find_sorted(dc, c->ndep, in.coords[i]);
      for (int r = 0; r < nout; ++r)
        G[r * c->ndep + col] += st->loc[r * nin + c->npart * d + i];
    }
  }
  st->have |= DAL_P_CON;
  return DAL_OK;
}
