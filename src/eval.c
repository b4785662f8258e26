// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The evaluation pipeline: a caller asks for the products it needs at the state's (t, q, qdot)
// and gets those and what they depend on, each marked current (MuJoCo's staged forward).
//
// Stages: kinematics (r, v, gamma, drdt; J when asked or needed) -> constraint rows ->
// forces, Q, c and energies (and M when asked or needed) -> accelerations (Cholesky of M, or
// the KKT system with multipliers; for trees the articulated-body recursion of aba.c, with
// the m x m loop system for multipliers) -> outputs (particle accelerations and reactions).
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "internal.h"
#include "linalg.h"

// a Lagrangian system: A = d2L/dqdot2 in st->M, qddot, and h = E
static int eval_lagrangian(const dal_system *sys, dal_state *st) {
  double h;
  int rc = dal__lagrangian_terms(sys, st, st->M, st->qddot, &h);
  if (rc) return rc;
  st->have |= DAL_P_DYN | DAL_P_M | DAL_P_MLOW;
  int bad = -1;
  if (dal__chol_solve(sys->n, st->M, st->L, st->qddot, &bad)) {
    char qs[256];
    dal__fmt_q(sys, st->q, qs, sizeof qs);
    return DAL_FAIL(st, DAL_E_SINGULAR,
                    "d2L/dqdot2 singular or not positive definite at t=%.17g, %s: coordinate "
                    "'%s' is degenerate; use another chart",
                    st->t, qs, sys->coord_names[bad]);
  }
  // T, U, T2, T1, T0 come from dal__lagrangian_terms (read off L, system.h)
  st->en.E = st->en.T + st->en.U;
  st->en.h = h;
  st->have |= DAL_P_ACC | DAL_P_OUT | DAL_P_KIN | DAL_P_J | DAL_P_CON;
  return DAL_OK;
}

void dal__power(const dal_system *sys, dal_state *st) {
  DAL_NEED(st, DAL_P_OUT | DAL_P_PW);
  // reactions of moving maps and multipliers of moving constraints do work; fixed ones do not
  double p = st->pw[0] + st->pw[1];
  for (int i = 0; i < sys->N * sys->dim; ++i) p += st->N[i] * st->drdt[i];
  for (int r = 0; r < sys->m; ++r) p -= st->lambda[r] * st->phit[r];
  st->power = p;
  st->have |= DAL_P_POW;
}

int dal__eval(const dal_system *sys, dal_state *st, unsigned need) {
  int m = sys->m, rc;
  st->have = 0;
  if (sys->lag) return eval_lagrangian(sys, st);
  if (need & DAL_P_POW) need |= DAL_P_OUT | DAL_P_PW;
  if (need & DAL_P_PW) need |= DAL_P_DYN;
  // what each product needs: outputs need accelerations; accelerations need forces and M
  // (Cholesky when m = 0, or the KKT system, whose dense form reads the lower M and whose
  // sparse form reads J); constraint rows need J
  // (the recursion needs neither M nor J: its constraint rows come from the local blocks);
  // large recursive trees store no J at all
  if (need & DAL_P_OUT) need |= DAL_P_ACC;
  if (need & DAL_P_ACC) {
    need |= DAL_P_DYN | (m ? DAL_P_CON : 0u);
    if (sys->dense_M && !sys->aba) need |= DAL_P_MLOW;
  }
  if ((need & DAL_P_CON) && !sys->aba) need |= DAL_P_J;
  if (need & DAL_P_M) need |= DAL_P_MLOW;
  if (need & DAL_P_MLOW) need |= DAL_P_DYN;
  if (!sys->store_J) need &= ~DAL_P_J;
  if ((rc = dal__kinematics(sys, st, (need & DAL_P_J) != 0)) != 0) return rc;
  // M of a tree with a link that is not a translation is assembled through J
  if ((need & DAL_P_MLOW) && sys->dense_M && !st->tree && !(st->have & DAL_P_J))
    dal__jacobians(sys, st);
  if ((need & DAL_P_CON) && m && (rc = dal__constraints(sys, st)) != 0) return rc;
  if (need & DAL_P_CON) st->have |= DAL_P_CON;
  if (need & DAL_P_DYN) {
    int want_M = (need & DAL_P_M) ? 2 : (need & DAL_P_MLOW) ? 1 : 0;
    st->pw[0] = st->pw[1] = 0.0;
    if ((rc = dal__dynamics(sys, st, want_M, (need & DAL_P_PW) ? st->pw : NULL)) != 0) return rc;
    if (need & DAL_P_PW) st->have |= DAL_P_PW;
  }
  if (need & DAL_P_ACC) {
    rc = m          ? dal__solve_kkt(sys, st)
         : sys->aba ? dal__aba_accel(sys, st)
                    : dal__solve_unconstrained(sys, st);
    if (rc) return rc;
    st->have |= DAL_P_ACC;
  }
  if ((need & DAL_P_OUT) && (rc = dal__finish(sys, st)) != 0) return rc;
  if (need & DAL_P_POW) dal__power(sys, st);
  return DAL_OK;
}
