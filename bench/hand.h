// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Hand-written equations of motion (no dalembert) and a direct SUNDIALS driver for them.
//
// These are the benchmark's baseline and its references: the planar N-link chain in minimal
// coordinates derived by hand (dense mass matrix + LAPACKE Cholesky, and an O(N) form through
// the rod tensions), and the small scenes' equations, integrated by the same SUNDIALS
// integrators the library uses (CVODE Adams/BDF, ARKODE ERKStep Dormand-Prince/Fehlberg).
#ifndef DAL_BENCH_HAND_H
#define DAL_BENCH_HAND_H

#include "dalembert/solve.h"

/// y' = f(t, y) for a hand-written scene; returns 0 ok, > 0 recoverable, < 0 stop.
typedef int hand_rhs_fn(double t, const double *y, double *ydot, void *ctx);

/// Statistics of a hand-written run.
typedef struct hand_stats {
  long steps;     ///< accepted steps
  long rhs_evals; ///< right-hand-side evaluations (including difference-quotient Jacobians)
  int status;     ///< 0, or the raw SUNDIALS return code (< 0)
} hand_stats;

/// Integrate y (n, in/out) from t0 to t1 with `method` (DOPRI5, FEHLBERG78, ADAMS, BDF) at
/// scalar tolerances rtol, atol. Creates and frees all SUNDIALS memory inside (as a library
/// advance from a fresh state does). Returns 0 or a negative SUNDIALS code.
int hand_integrate(hand_rhs_fn *f, void *ctx, int n, double *y, double t0, double t1,
                   dal_method method, double rtol, double atol, long max_steps, hand_stats *out);

/// Planar N-link chain: pivot at the origin, link i of length l[i] from particle i-1 to
/// particle i of mass m[i], angle th[i] from the downward vertical (counter-clockwise),
/// gravity (0, -g). y = (th (N), thdot (N)).
typedef struct hand_chain {
  int N;
  double g;
  double *m, *l;                ///< masses and lengths (N)
  double *mu;                   ///< tail masses mu_i = sum_{k >= i} m_k (N)
  double *s, *c;                ///< scratch sin/cos (N)
  double *M;                    ///< dense mass matrix (N x N, column-major)
  double *b;                    ///< right-hand side / solution (N)
  double *diag, *off, *rhs, *T; ///< tridiagonal tension system (N)
  double *ax, *ay;              ///< particle accelerations (N)
  long nevals;                  ///< right-hand-side evaluations so far
} hand_chain;

/// Allocate a chain of N links with unit masses and lengths and gravity g. Returns NULL on
/// out-of-memory.
hand_chain *hand_chain_create(int N, double g);
void hand_chain_destroy(hand_chain *ch);

/// Dense minimal-coordinate equations: M(th) thdd = Q - c with
/// M_ij = mu_max(i,j) l_i l_j cos(th_i - th_j), c_i = sum_j mu_max(i,j) l_i l_j
/// sin(th_i - th_j) thd_j^2, Q_i = -g l_i mu_i sin th_i; Cholesky by LAPACKE. Written lean:
/// sin and cos once per link, the lower triangle of M only, c in O(N) by prefix sums, the
/// NaN-scan-free LAPACKE calls the library makes. ctx: hand_chain.
int hand_chain_rhs_dense(double t, const double *y, double *ydot, void *ctx);

/// The same equations in O(N): rod tensions T_k from a symmetric tridiagonal system
/// (projecting a_k - a_{k-1} on each link), then thdd_k = (a_k - a_{k-1}) . n_k / l_k.
int hand_chain_rhs_tridiag(double t, const double *y, double *ydot, void *ctx);

/// Particle positions (N x 2, row-major) of a chain state y.
void hand_chain_positions(const hand_chain *ch, const double *y, double *r);

/// Bead on a ring of radius R turning at rate w about the vertical, theta from the bottom:
/// thdd = sin th (w^2 cos th - g/R). ctx: double[3] = (R, w, g).
int hand_ring_rhs(double t, const double *y, double *ydot, void *ctx);

/// Pendulum of length l whose pivot moves vertically as a cos(w t):
/// thdd = -(g - a w^2 cos(w t)) sin th / l. ctx: double[4] = (l, a, w, g).
int hand_driven_rhs(double t, const double *y, double *ydot, void *ctx);

/// Spherical pendulum in Cartesian coordinates, pivot at the origin, gravity (0, 0, -g):
/// a = g_vec - ((v.v + r.g_vec) / |r|^2) r. y = (r (3), v (3)). ctx: double[1] = (g).
int hand_spherical_rhs(double t, const double *y, double *ydot, void *ctx);

#endif
