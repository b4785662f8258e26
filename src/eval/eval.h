// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Private interface of the redundant-coordinate side: KKT solves, projections, diagnostics.
#ifndef DAL_DAE_INTERNAL_H
#define DAL_DAE_INTERNAL_H

#include "base/base.h"
#include "dalembert/dae.h"
#include "linalg/linalg.h"

/// KKT metric: the (1,1) block is the identity (minimum-norm position steps) or M.
enum { DAL_KKT_IDENTITY = 0, DAL_KKT_MASS = 1 };

/// Factor K = [A G'; G 0] at the state's current kinematics and constraint rows (A = I or M;
/// M is the dense st->M or, for large systems, assembled sparse from the particle Jacobians).
/// `what` names the caller in the error message. Returns 0 or DAL_E_CONSTRAINT /
/// DAL_E_SINGULAR / DAL_E_NOMEM with the state's message naming the culprit.
int dal__kkt_factor(const dal_system *sys, dal_state *st, int metric, const char *what);

/// 1 when dal__kkt_factor with the mass metric reads the dense st->M (the dense KKT matrix),
/// 0 when it does not (the loop system of a tree, or the sparse KKT matrix assembled from the
/// particle Jacobians): a caller then need not ask for DAL_P_MLOW, an O(n^2) assembly.
int dal__kkt_reads_M(const dal_system *sys, const dal_state *st);

/// Solve A x = a + G' y, G x = b with the last factorization: a (n), b (m) -> x (n), y (m).
/// x may alias a and y may alias b. No allocation.
void dal__kkt_solve(const dal_system *sys, dal_state *st, const double *a, const double *b,
                    double *x, double *y);

/// Scratch vector i (0..3) of n + m doubles owned by the state's KKT workspace.
double *dal__kkt_scratch(dal_state *st, int i);

/// Dense G (m x n, column-major, leading dimension ld >= m) from the compact blocks.
void dal__dense_G(const dal_system *sys, const dal_state *st, double *G, int ld);

/// y (n) = G' lambda for the state's current G (compact blocks).
void dal__gt_apply(const dal_system *sys, const dal_state *st, const double *lambda, double *y);

/// max |x_i| over n entries (NaN counts as largest); *at (nullable) receives its index
double dal__max_abs(const double *x, int n, int *at);

/// Rank check (diagnose.c): writes the named message into the state when G is rank
/// deficient. Returns DAL_OK, DAL_E_CONSTRAINT or DAL_E_NOMEM; rep is nullable.
int dal__check_rank(const dal_system *sys, dal_state *st, dal_constraint_report *rep);

#endif
