// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Private interface of the analysis files: the exact tangent workspace (analysis_tangent.c).
#ifndef DAL_ANALYSIS_INTERNAL_H
#define DAL_ANALYSIS_INTERNAL_H

#include "dalembert/analysis.h"
#include "internal.h"

/// Workspace of the exact tangent of one system (all arrays allocated by dal__tangent_create;
/// nothing is allocated by an evaluation). n coordinates, nd = N d particle components.
typedef struct dal_tangent {
  int n, nd;
  dal_jet *jq;           // n: coordinate jets of the current curve
  dal_jet *jv;           // n: velocity jets (Lagrangian systems)
  dal_jet *jr;           // nd: particle jets along the current curve
  dal_jet *jin;          // max_in: inputs of one primitive instance
  dal_jet *jout;         // max_out
  dal_jet *cp, *cm;      // nd: particle jets along the curves lambda = +1 and -1
  double *d3diag;        // (n + 1) x nd: third derivatives along e_i (i = n: the time direction)
  double *J;             // n x nd: J[i * nd + c] = d r_c / d q_i
  double *r, *v, *A, *w; // nd: positions, velocities, accelerations, frozen weights m A - F_d
  double *Fd;            // nd: damper forces at the state
  double *dr, *dv, *da, *dF; // nd: derivatives along one tangent direction
  double *H;          // (n + 1)^2, column-major: second derivatives of W = sum r . w + V in (q, t)
  double *res;        // n: R = dW/dq at the state (zero up to rounding when qddot is current)
  double *M;          // n x n mass matrix, from the particle Jacobians
  double *Rq, *Ru;    // n x n: K = dR/dq, C = dR/dqdot
  double *Rt;         // n: dR/dt
  double *Habs;       // (n + 1)^2: sums of the magnitudes behind H (rounding scale)
  double *Kabs;       // n x n: sums of the magnitudes of the terms of K (rounding scale)
  double *Cabs;       // n x n: the same for C
  double *HL, *HLabs; // (2n + 1)^2: Hessian of L in (q, qdot, t) (Lagrangian systems)
  double *L;          // n x n Cholesky factor of M
  double *link;       // per spring and damper: anchor x, x', x'' (3 x 3)
} dal_tangent;

/// Allocate the workspace of sys. Returns DAL_OK or DAL_E_NOMEM (*out NULL then).
int dal__tangent_create(const dal_system *sys, dal_tangent **out);
/// Free (NULL is a no-op).
void dal__tangent_free(dal_tangent *tg);
/// DAL_OK if the exact tangent covers sys, else DAL_E_UNSUPPORTED with the reason in st's
/// message, prefixed by `what` (the public function's name).
int dal__tangent_supported(const dal_system *sys, dal_state *st, const char *what);
/// The tangent at the state's (t, q, qdot) with its current qddot (call dal_forward first):
/// tg->M, Rq, Ru, and Rt when want_t. Returns DAL_OK, DAL_E_DOMAIN, DAL_E_CALLBACK.
int dal__tangent_eval(const dal_system *sys, dal_state *st, dal_tangent *tg, int want_t);
/// The same for a system given by a Lagrangian (analysis_lagrangian.c).
int dal__tangent_lagrangian(const dal_system *sys, dal_state *st, dal_tangent *tg, int want_t);
/// Factor tg->M into tg->L (Cholesky). Returns DAL_OK or DAL_E_SINGULAR (message set).
int dal__tangent_factor(const dal_system *sys, dal_state *st, dal_tangent *tg);
/// B (n x k, column-major) = M^-1 B with the factor of dal__tangent_factor.
void dal__tangent_msolve(dal_tangent *tg, int k, double *B);
/// The flow Jacobian A = df/dy (2n x 2n) and ft = df/dt (2n; NULL to skip) from the last
/// evaluation (factor first). Uses tg->dr.. as no scratch; A, ft caller-owned.
void dal__tangent_flow(dal_tangent *tg, double *A, double *ft);

/// Evaluate sys at (t, q, qdot) into st (state set and forward; the integrator memory of st
/// is dropped). Returns the status of dal_state_set / dal_forward.
int dal__analysis_eval(const dal_system *sys, dal_state *st, double t, const double *q,
                       const double *qdot);

#endif
