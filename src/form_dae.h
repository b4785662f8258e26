// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The DAE formulations of redundant coordinates (GGL, index-3, index-1) behind one interface:
// sizes, residual, error-test mask and Newton-matrix entries (private; form_dae.c).
#ifndef DAL_FORM_DAE_H
#define DAL_FORM_DAE_H

#include "dae_internal.h"
#include "sparse.h"

/// A DAE formulation on a system and a state (the state is its workspace).
/// Unknowns y = (q, v, lambda[, mu][, W]).
typedef struct dal_dae {
  const dal_system *sys;
  dal_state *st;
  dal_formulation form; ///< DAL_FORM_GGL, DAL_FORM_INDEX3 or DAL_FORM_INDEX1
  double alpha, beta;   ///< index-1 Baumgarte terms
  int n, m, neq;
  int off_l, off_mu; ///< offsets of lambda and mu in y (mu: -1 unless GGL)
  int off_w;         ///< offset of the work W (last unknown; -1 unless opts.work)
  dal_csc pat;       ///< pattern of the Newton matrix (after dal__dae_pattern)
  int *pos;          ///< position in pat's values of each Newton-matrix entry, in assembly
                     ///< order (after dal__dae_pattern; the sparse sink's addresses)
  size_t npos;       ///< number of entries assembled (with repetitions)
  // geometric-stiffness scratch (max_in, max_out, largest constraint dependency count)
  double *H, *hv, *Ju, *tmp, *Hq, *dir, *udot, *g0;
} dal_dae;

/// Where Newton-matrix entries go: counted, recorded as keys, their positions in the pattern
/// recorded (these three build the pattern), summed into a sparse value array of the pattern
/// (through f->pos: the entries come in the same order every time), or into a dense
/// column-major matrix (leading dimension neq).
typedef struct dal_dae_sink {
  int mode; ///< DAL_SINK_COUNT, DAL_SINK_KEYS, DAL_SINK_POS, DAL_SINK_SPARSE, DAL_SINK_DENSE
  size_t n; ///< entries so far (start at 0)
  long long *keys;
  double *val;
} dal_dae_sink;
enum { DAL_SINK_COUNT, DAL_SINK_KEYS, DAL_SINK_POS, DAL_SINK_SPARSE, DAL_SINK_DENSE };

/// Set up form f (sizes, scratch). Returns 0 or DAL_E_NOMEM.
int dal__dae_init(dal_dae *f, const dal_system *sys, dal_state *st, dal_formulation form,
                  double alpha, double beta, int work);
void dal__dae_free(dal_dae *f);
/// The Newton matrix's pattern (f->pat) and the position of every assembled entry in it
/// (f->pos). Returns 0 or -1 (out of memory).
int dal__dae_pattern(dal_dae *f);
/// Evaluate the state at (t, q, v) from y: kinematics, constraint rows, forces (M through J).
int dal__dae_eval(dal_dae *f, double t, const double *y);
/// Residual F (neq) at (t, y, y'); evaluates the state there.
int dal__dae_residual(dal_dae *f, double t, const double *y, const double *yp, double *F);
/// Local tolerance factor of a DAE form in IDA (calibrated like the ODE methods' factors).
double dal__dae_tol_factor(dal_formulation form);
/// Error-test mask id (neq): 1 for variables in the error test (q and v; index-3: q only),
/// 0 for the algebraic ones (lambda, mu).
void dal__dae_mask(const dal_dae *f, double *id);
/// Newton matrix dF/dy + cj dF/dy' at (t, y) into the sink, from exact pieces: M, G, G', the
/// constraints' geometric stiffness sum_i w_i Hess(phi_i) (jets, by polarization) and the
/// derivative of G v + phi_t. Left out: the curvature of non-Cartesian particle maps
/// (dM/dq v') and the derivatives of applied forces. Evaluates the state at (t, y).
int dal__dae_newton(dal_dae *f, double t, double cj, const double *y, dal_dae_sink *out);
/// true when dal__dae_newton's matrix is the whole Jacobian of the residual (Cartesian
/// particles, no forces but gravity): then no difference quotients are needed anywhere.
int dal__dae_newton_exact(const dal_system *sys);

#endif
