// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Joint forces: the force each placement exerts on its particle, from the reactions by
// Newton's third law through the tree of placements (state.h: dal_joint_forces).
#include <string.h>

#include "model.h"

int dal_joint_forces(const dal_system *sys, const dal_state *st, double *F) {
  int pair = dal__check_pair(sys, st, "joint_forces");
  if (pair) return pair;
  if (!F) return DAL_FAIL_C(st, DAL_E_ARG, "joint_forces: F is NULL");
  if (sys->lag || !sys->place)
    return DAL_FAIL_C(st, DAL_E_UNSUPPORTED,
                      "joint_forces: the system has no placements (%s), so there are no joints; "
                      "the reaction on each particle is dal_state_reactions",
                      sys->lag ? "a Lagrangian" : "one map r(q, t) for all particles");
  dal__lazy_eval(st);
  const unsigned need = DAL_P_KIN | DAL_P_CON | DAL_P_ACC | DAL_P_OUT;
  if ((st->have & need) != need)
    return DAL_FAIL_C(st, DAL_E_STATE,
                      "joint_forces: the state holds no evaluated reactions at its (t, q, qdot); "
                      "call dal_forward or integrate first");
  // the explicit constraints' share of the reactions (rows on particles; from the multipliers)
  int rc = dal_constraint_forces(sys, st, F);
  if (rc) return rc;
  int d = sys->dim, N = sys->N;
  for (int i = 0; i < N * d; ++i)
    F[i] = st->N[i] - F[i];
  // children after their parents (builder.c): the leaves first, each joint's force handed to
  // its parent as the reaction -Lp' J (Lp = dr_k / dr_parent; I for a translating map)
  for (int k = N - 1; k >= 0; --k) {
    int p = sys->place[k].prim ? sys->place[k].parent : -1;
    if (p < 0) continue;
    const double *Lp = st->Lp + (size_t)k * (size_t)d * (size_t)d;
    for (int a = 0; a < d; ++a) {
      double s = 0.0;
      for (int b = 0; b < d; ++b)
        s += Lp[b * d + a] * F[k * d + b];
      F[p * d + a] += s;
    }
  }
  return DAL_OK;
}
