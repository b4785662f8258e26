// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Verification kit for users' own models: jets against finite differences, model checks.
///
/// The library trusts every jet function it is given: a wrong derivative in a user primitive,
/// map, potential or Lagrangian gives wrong dynamics, quietly. These checks are what the
/// library's own registry test does, made available: call them from a small program and
/// register it as a ctest of your project (cmake/dalembertVerify.cmake:
/// dalembert_add_verify_test). Finite differences are used here only as an oracle.
///
/// Jet checks: at `nsamples` random points (inputs uniform in [lo, hi] per input, t uniform in
/// [t_lo, t_hi]) and random unit directions u over (inputs, t), the jet's first and second
/// directional derivatives are compared with central differences D1(h) = (f(x + h u) - f(x -
/// h u)) / 2h and D2(h) = (f(x + h u) - 2 f(x) + f(x - h u)) / h^2. The error bound is derived,
/// not guessed: the truncation error of the h/2 estimate is |D(h) - D(h/2)| / 3 (both are
/// O(h^2), Richardson), plus the rounding of f, taken as 64 eps max(1, |f|, |x|) and divided by
/// h (D1) or h^2 (D2). An entry passes when |jet - D(h/2)| <= tol_factor * bound. Every jet
/// output (value and both derivatives) must also be finite at every sample point.
#ifndef DAL_VERIFY_H
#define DAL_VERIFY_H

#include "dalembert/base.h"
#include "dalembert/state.h"
#include "dalembert/system.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Options of the jet checks. Always start from dal_default_verify_opts() (options that did not
/// come from it are refused, DAL_E_ARG); NULL options mean the defaults.
typedef struct dal_verify_opts {
  int nsamples;            ///< sample points (default 16)
  double lo;               ///< lower end of every input's range (default -1; see in_lo)
  double hi;               ///< upper end of every input's range (default 1; see in_hi)
  const double *in_lo;     ///< per-input lower bounds (nin values; borrowed; nullable)
  const double *in_hi;     ///< per-input upper bounds (nin values; borrowed; nullable)
  double t_lo;             ///< lower end of the range of t (default 0)
  double t_hi;             ///< upper end of the range of t (default 1)
  double h;                ///< finite-difference step relative to max(1, |x|) (default 1e-3)
  double tol_factor;       ///< multiple of the derived bound that still passes (default 10)
  unsigned long long seed; ///< random seed (default 1): the same seed gives the same points
  int cookie;              ///< set by dal_default_verify_opts; do not touch
} dal_verify_opts;

/// The defaults listed in dal_verify_opts.
DAL_API dal_verify_opts dal_default_verify_opts(void);

/// What a jet check found. The worst entry is the one with the largest error / bound ratio.
typedef struct dal_verify_report {
  int samples;        ///< sample points evaluated
  int checks;         ///< derivative entries compared
  int failures;       ///< entries beyond tol_factor * bound, plus non-finite outputs
  double worst;       ///< largest |jet - fd| / bound over all entries (<= tol_factor passes)
  int worst_output;   ///< output index of the worst entry
  int worst_order;    ///< 1 (first derivative) or 2 (second) of the worst entry
  double worst_jet;   ///< the worst entry's jet derivative
  double worst_fd;    ///< its central-difference estimate (step h/2)
  double worst_bound; ///< its derived error bound
  double worst_t;     ///< t of the worst sample
  char msg[320];      ///< one line naming the function, the worst entry and the verdict
} dal_verify_report;

/// Check a primitive's jets: out = prim->eval(in, t; param, ctx), nin inputs, nout outputs.
/// `param` (prim->nparam values; NULL takes prim->param_defaults) and `ctx` as the instance
/// would get them. `o` NULL takes the defaults; `rep` is nullable. Returns DAL_OK when every
/// entry passes, DAL_E_VERIFY when one does not (the report names it), DAL_E_DOMAIN for a
/// non-finite output, DAL_E_CALLBACK when eval fails, DAL_E_ARG / DAL_E_NOMEM.
DAL_API int dal_verify_primitive(const dal_primitive *prim, const double *param, void *ctx,
                                 const dal_verify_opts *o, dal_verify_report *rep);

/// Check a whole-system map r(q, t): n coordinates, N particles in dimension d (r is N x d).
/// Returns as dal_verify_primitive.
DAL_API int dal_verify_map(dal_map_fn *fn, int n, int N, int d, const dal_verify_opts *o,
                           dal_verify_report *rep, void *ctx);

/// Check a potential U(r, t) over N particles in dimension d (N x d inputs).
DAL_API int dal_verify_potential_r(dal_potential_r_fn *fn, int N, int d, const dal_verify_opts *o,
                                   dal_verify_report *rep, void *ctx);

/// Check a potential U(q, t) over n coordinates.
DAL_API int dal_verify_potential_q(dal_potential_q_fn *fn, int n, const dal_verify_opts *o,
                                   dal_verify_report *rep, void *ctx);

/// Check a Lagrangian L(t, q, qdot) over n coordinates: the inputs are (q, qdot), 2n values
/// (in_lo/in_hi, if given, have 2n entries).
DAL_API int dal_verify_lagrangian(dal_lagrangian_fn *fn, int n, const dal_verify_opts *o,
                                  dal_verify_report *rep, void *ctx);

/// What dal_verify_model found at a state.
typedef struct dal_model_report {
  double mass_asym;     ///< max |M_ij - M_ji| / max |M_ij| (0 for an exactly symmetric M)
  double mass_pivot;    ///< smallest Cholesky pivot^2 / largest diagonal entry (> 0: SPD)
  int mass_checked;     ///< 1 when M was available (dense) and checked
  double force_err;     ///< max_j |Q_j + dU/dq_j| / bound (dU/dq by central differences)
  int force_coord;      ///< coordinate of that maximum (-1 if not checked)
  int force_checked;    ///< 1 when every applied force is a potential force (else skipped)
  double path_residual; ///< max |Lagrange residual - G' lambda| / scale along a short
                        ///< integrated path (relative to max |M qddot|, |Q|, |c|)
  int path_coord;       ///< coordinate of that maximum
  int path_checked;     ///< 1 when the path was integrated and checked
  int rank;             ///< constraint rank at the state (m when full; -1 if not checked)
  int m;                ///< constraint rows
  double rmin;          ///< smallest pivot ratio of the rank-revealing QR (1 if m = 0)
  int passed;           ///< 1 when every check that ran passed
  char msg[320];        ///< one line naming the first failing check, or "model checks passed"
} dal_model_report;

/// Check a model at the state's (t, q, qdot): M symmetric positive definite; for systems whose
/// applied forces all come from potentials (gravity, springs, U(r, t), U(q, t)), Q against
/// -dU/dq by central differences of U with the derived bound above; the Lagrange residual
/// d/dt dL/dqdot - dL/dq - Q (dal_lagrange_residual) along a path integrated from the state for
/// 12 output intervals of 2e-3 (path derivatives by 4th-order central differences, pass below 1e-5
/// relative), which for a constrained system must equal G' lambda; the rank of the
/// constraints (dal_check_constraints). The state is left evaluated at its (t, q, qdot).
/// `o` nullable (only tol_factor is used); `rep` nullable. Returns DAL_OK when all pass,
/// DAL_E_VERIFY naming the first failing check, DAL_E_ARG for a NULL state, DAL_E_STATE for a
/// NULL system or a state of another system (as every (system, state) call; the message in the
/// state), DAL_E_NOMEM, or the status of a failing evaluation; rep->msg names the cause.
DAL_API int dal_verify_model(const dal_system *sys, dal_state *st, const dal_verify_opts *o,
                             dal_model_report *rep);

#ifdef __cplusplus
}
#endif
#endif
