// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Generated code for expressions: standalone C source, and native code compiled at
/// first use, cached and attached in place of the bytecode.
///
/// The code of an expression is its register program (the one dal_expr_eval runs) written out
/// as straight-line C over the jet arithmetic of dalembert/jet.h, with common subexpressions
/// shared and constants folded. It computes exactly what the bytecode computes: the results are
/// identical to the last bit (tests/test_codegen.c checks values and jets on every example
/// scene and on 200 random expressions).
#ifndef DAL_CODEGEN_H
#define DAL_CODEGEN_H

#include <stdio.h>

#include "dalembert/base.h"
#include "dalembert/expr.h"
#include "dalembert/system.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Options of dal_codegen_attach; start from dal_codegen_default_opts().
typedef struct dal_codegen_opts {
  /// the compiler: a program and its words, split at blanks, run without a shell (NULL: the
  /// environment's CC, else "cc"); it must accept `-std=c11 -O2 -fPIC -shared -x c`
  const char *cc;
  /// the cache directory (NULL: $XDG_CACHE_HOME/dalembert, else $HOME/.cache/dalembert);
  /// created with mode 0700; refused when another user owns it or others may write to it
  const char *cache_dir;
  /// dal_scene_native only: 1 (default) also compiles the scene's equations of motion
  /// (dal_codegen_attach_eom), 0 the formulas alone (results bit-identical to the bytecode)
  int eom;
  int cookie; ///< set by dal_codegen_default_opts(); do not touch
} dal_codegen_opts;

/// The default options (compiler from CC, the per-user cache directory).
DAL_API dal_codegen_opts dal_codegen_default_opts(void);

/// Write a standalone C source for the n expressions e[0 .. n-1] to fp: no parser, no library,
/// no allocation; it needs only the C math library (-lm). For expression i it defines
///
///     int PREFIX_i(const dal_jet *in, dal_jet t, const double *param, dal_jet *out, void *ctx);
///
/// with the signature of a primitive's eval (dalembert/primitives.h): the nin inputs in(nin)
/// (for a Lagrangian q then qdot), the time t, the parameters param(nparam) (NULL: the values
/// the expression was made with) and the nout outputs out(nout); ctx is unused; it returns 0.
/// A table `const PREFIX_fn PREFIX_table[n]` gives each one's name, nin, nout, nparam,
/// default parameter values and function, and `PREFIX_count` is n. The type dal_jet and its
/// arithmetic come from the copy of dalembert/jet.h at the top of the file (guarded by
/// DAL_JET_H, so a program that includes dalembert/jet.h first uses that one).
/// Returns DAL_OK, DAL_E_ARG (NULL or prefix not an identifier), DAL_E_NOMEM or DAL_E_IO.
DAL_API int dal_codegen_write(dal_expr *const *e, int n, const char *prefix, FILE *fp);

/// Native code for the n expressions e[0 .. n-1]: their C source (as dal_codegen_write) is
/// compiled into one shared object by the system's compiler, kept in the cache under the hash
/// of its source and compiler, and loaded; afterwards each expression evaluates by it (every
/// caller: placements, constraints, potentials, Lagrangians, events), bit-identical to the
/// bytecode. A cached object is loaded only when the directory and the file belong to the
/// user, nobody else may write to them and the object's content hash equals the one written
/// beside it when it was compiled; otherwise it is compiled again. Not thread-safe: attach
/// before the expressions are shared (evaluation is then re-entrant), and destroy expressions
/// attached by one call from one thread (they share the loaded object). On failure (no compiler, a
/// refused cache, a compiler error) nothing is attached, the bytecode keeps running and msg says
/// why: DAL_E_UNSUPPORTED (no compiler), DAL_E_IO (the cache), DAL_E_ARG, DAL_E_NOMEM.
DAL_API int dal_codegen_attach(dal_expr *const *e, int n, const dal_codegen_opts *o, char *msg,
                               size_t msglen);

/// Compiled equations of motion of a minimal-coordinate system: from the closed form of its
/// positions (every particle placed by an expression, dal_expr_place_def) the symbolic layer
/// derives the Jacobians J_k = dr_k/dq and the curvature terms gamma_k, and the generated C
/// evaluates qddot = M^-1 (Q - c) in one straight-line function: M = sum m_k J_k' J_k and
/// Q - c = sum J_k' m_k (g - gamma_k) - dU/dq assembled, then an unrolled LDL' solve (common
/// subexpressions shared, constants folded). It is compiled into the cache like
/// dal_codegen_attach's code and attached to sys; afterwards the minimal-coordinate
/// right-hand side of every integration takes qddot from it (masses, gravity and the
/// placements' parameters read from the state, so per-trajectory parameters hold). Energies
/// and every other output still come from the general path, and so does qddot where the
/// compiled one declines (a pivot of M not positive, a value not finite), so its messages are
/// unchanged. The results agree with the general path's to rounding: |qddot - qddot_general|_i
/// <= 2^-45 (|qddot_i| + sum_j |(M^-1)_ij| (|Q_j| + |c_j|)), checked by tests/test_codegen_eom.c
/// on every example scene and on 200 random models. Forces covered: gravity, potentials of q
/// and of the positions by expressions (dal_expr_potential_q / _r). Not thread-safe: attach
/// before the system is shared. Returns DAL_OK; DAL_E_UNSUPPORTED (msg names the element)
/// for constraints, a global map, a Lagrangian, a placement not by an expression, springs,
/// dampers, force callbacks or more than 24 coordinates, and when there is no compiler;
/// DAL_E_TOO_LARGE past the symbolic algebra's bounds; DAL_E_IO (the cache), DAL_E_ARG,
/// DAL_E_NOMEM. On failure nothing is attached and the general path runs.
DAL_API int dal_codegen_attach_eom(dal_system *sys, const dal_codegen_opts *o, char *msg,
                                   size_t msglen);

/// 1 when sys has compiled equations of motion (dal_codegen_attach_eom), else 0.
DAL_API int dal_codegen_eom_attached(const dal_system *sys);

/// 1 when e evaluates by native code (dal_codegen_attach), 0 when by the bytecode.
DAL_API int dal_codegen_attached(const dal_expr *e);

#ifdef __cplusplus
}
#endif
#endif
