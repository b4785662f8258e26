// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Expressions: formulas compiled to jet programs, usable as primitives and callbacks, and
/// the same formulas differentiated, simplified and printed.
///
/// A dal_expr is a vector of formulas over named inputs (coordinates, particle positions, and
/// with `velocities` their velocities named input + "dot"), the time `t` and named parameters:
///
///   "l*sin(theta)"   "-l*cos(theta) + a*cos(omega*t)"   "1/2*m*(thetadot*l)^2 + m*g*l*cos(theta)"
///
/// Grammar: numbers (12, 0.5, 1e-3), names, + - * / ^ (also **; right-associative, binding
/// tighter than unary minus: -x^2 = -(x^2)), unary minus and plus, parentheses, and the
/// functions sin cos tan asin acos atan sinh cosh tanh exp log sqrt (one argument), atan2(y, x),
/// hypot(a, b) and pow(a, b). `pi` is the constant unless a name shadows it. Powers with an
/// integer constant exponent are exact for any sign of the base; other exponents need a
/// positive base.
///
/// Compilation hash-conses the formulas (a repeated subexpression is evaluated once), splits off
/// what depends only on parameters and constants (evaluated in doubles), and allocates registers
/// by last use; evaluation runs the instruction list over dal_jet to order 3 (the order the
/// library uses) on the stack, with no allocation. A compiled expression is immutable: threads
/// may evaluate it at the same time.
///
/// Where an expression goes (each adapter's ctx is the dal_expr, borrowed: it must outlive the
/// system):
///   coordinate map of one particle   dal_expr_primitive + dal_expr_place_def (nout = d; inputs
///                                    the parent's position, if any, then the coordinates)
///   constraint                       dal_expr_primitive + dal_expr_constraint_def (inputs the
///                                    particles' positions, d each, then the coordinates)
///   whole-system map r(q, t)         dal_expr_map (nout = N d, inputs q)
///   potential U(r, t) / U(q, t)      dal_expr_potential_r / dal_expr_potential_q (nout = 1)
///   Lagrangian L(t, q, qdot)         dal_expr_lagrangian (nout = 1, velocities = 1, inputs q)
///   moving point / prescribed f(t)   dal_expr_path / dal_expr_time (no inputs)
///   event g(t, q, qdot)              dal_expr_event (nout = 1, velocities = 1)
/// As a primitive the parameters are the primitive's named parameters, with the expression's
/// values as defaults: a def may set them (def.param[i], i in the order of the def's `params`)
/// and a state may override them per trajectory ("place:<particle>:<i>", "con:<name>:<i>",
/// params.h). The callback adapters read the expression's own values.
///
/// Errors: a formula that does not parse is refused with a message naming the formula, the
/// column (1-based) and the unknown symbol or the bad token. At run time a function outside its
/// domain (log of a negative number, ...) produces NaN, which the library reports as
/// DAL_E_DOMAIN naming the primitive (whose name is the def's name); dal_expr_check names the
/// formula, column and function.
#ifndef DAL_EXPR_H
#define DAL_EXPR_H

#include <stddef.h>
#include <stdio.h>

#include "dalembert/base.h"
#include "dalembert/jet.h"
#include "dalembert/system.h"

#ifdef __cplusplus
extern "C" {
#endif

/// A compiled vector of formulas (opaque, immutable after dal_expr_create).
typedef struct dal_expr dal_expr;

/// Longest formula accepted (characters).
#define DAL_EXPR_MAX_LEN 65536
/// Largest number of coordinates of an event expression (dal_expr_event).
#define DAL_EXPR_EVENT_MAXN 128

/// What an expression is made of. Start from dal_default_expr_def().
typedef struct dal_expr_def {
  const char *name;            ///< name in messages and of the primitive (copied); default "expr"
  const char *const *formulas; ///< the nout formulas (copied). Required
  int nout;                    ///< number of formulas (>= 1)
  const char *const *inputs;   ///< names of the nin inputs, in order (copied); NULL when nin is 0
  int nin;                     ///< number of named inputs, default 0
  /// 1: the inputs are followed by their velocities, named input + "dot" ("theta" ->
  /// "thetadot"), so the expression has 2 nin inputs (Lagrangians, event functions); default 0
  int velocities;
  const char *const *params; ///< names of the nparam parameters (copied); NULL when 0
  const double *values;      ///< their values (copied; the primitive's defaults); NULL: all 0
  int nparam;                ///< number of parameters, default 0
  int cookie;                ///< set by dal_default_expr_def; do not touch
} dal_expr_def;

/// A def with no formulas (to be set), no inputs, no parameters, no velocities, name "expr".
DAL_API dal_expr_def dal_default_expr_def(void);

/// Parse and compile `def` into *out (NULL on failure). `msg` (nullable, msglen bytes)
/// receives the reason: the formula, the column and the unknown symbol or bad token, or a
/// name given twice, or a formula too large (more than 255 live registers). Returns DAL_OK,
/// DAL_E_ARG (syntax, names, counts, a def not from dal_default_expr_def), DAL_E_NONFINITE
/// (a parameter value), DAL_E_NOMEM.
DAL_API int dal_expr_create(const dal_expr_def *def, dal_expr **out, char *msg, size_t msglen);

/// Free an expression (NULL is a no-op). No system may still use it.
DAL_API void dal_expr_destroy(dal_expr *e);

/// Number of outputs (formulas).
DAL_API int dal_expr_nout(const dal_expr *e);
/// Number of inputs (2 nin with velocities).
DAL_API int dal_expr_nin(const dal_expr *e);
/// Number of parameters.
DAL_API int dal_expr_nparam(const dal_expr *e);
/// Name of input i (velocities included), parameter names after them at nin + j; NULL if out of
/// range.
DAL_API const char *dal_expr_symbol(const dal_expr *e, int i);
/// Values of the parameters (nparam values; borrowed from e).
DAL_API const double *dal_expr_values(const dal_expr *e);
/// 1 when some formula of e depends on input i (on t for i = -1), else 0.
DAL_API int dal_expr_depends(const dal_expr *e, int i);
/// Number of instructions the compiled program runs per evaluation (scalar and jet parts).
DAL_API int dal_expr_ninstructions(const dal_expr *e);

/// Evaluate: out (nout jets) from in (nin jets), t and param (nparam values; NULL: the
/// expression's own values). No allocation. Returns DAL_OK or DAL_E_ARG (NULL e, in, out).
DAL_API int dal_expr_eval(const dal_expr *e, const dal_jet *in, dal_jet t, const double *param,
                          dal_jet *out);

/// Evaluate as dal_expr_eval and report the first operation whose value is not finite:
/// DAL_E_DOMAIN with msg naming the formula, the column and the function or operator.
DAL_API int dal_expr_check(const dal_expr *e, const dal_jet *in, dal_jet t, const double *param,
                           dal_jet *out, char *msg, size_t msglen);

/// The expression as a primitive (nin, nout, nparam, named parameters with the expression's
/// values as defaults; borrowed from e). Its eval needs ctx = e: use dal_expr_place_def or
/// dal_expr_constraint_def, which fill a dal_place_def or dal_constraint_def with ctx = e.
DAL_API const dal_primitive *dal_expr_primitive(const dal_expr *e);

/// Set def->prim and def->ctx to place a particle by e (nout must be the dimension). Returns
/// DAL_OK, or DAL_E_ARG for NULL or more than DAL_MAX_PARAM parameters.
DAL_API int dal_expr_place_def(const dal_expr *e, dal_place_def *def);

/// Set def->prim and def->ctx to add e as a constraint (nout rows). As dal_expr_place_def.
DAL_API int dal_expr_constraint_def(const dal_expr *e, dal_constraint_def *def);

/// dal_map_fn over an expression (ctx: the dal_expr; inputs q, nout = N d).
DAL_API int dal_expr_map(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx);
/// dal_potential_r_fn (ctx: the dal_expr; inputs r, N d of them; nout = 1).
DAL_API int dal_expr_potential_r(const dal_jet *r, dal_jet t, dal_jet *U, void *ctx);
/// dal_potential_q_fn (ctx: the dal_expr; inputs q; nout = 1).
DAL_API int dal_expr_potential_q(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx);
/// dal_lagrangian_fn (ctx: the dal_expr; velocities = 1, inputs q; nout = 1).
DAL_API int dal_expr_lagrangian(dal_jet t, const dal_jet *q, const dal_jet *qdot, dal_jet *L,
                                void *ctx);
/// dal_path_fn (ctx: the dal_expr; no inputs; nout = d).
DAL_API int dal_expr_path(dal_jet t, dal_jet *x, void *ctx);
/// dal_time_fn (ctx: the dal_expr; no inputs; nout = 1).
DAL_API int dal_expr_time(dal_jet t, dal_jet *f, void *ctx);
/// dal_event_fn (events.h; ctx: the dal_expr; velocities = 1, inputs q; nout = 1): returns
/// g(t, q, qdot), NaN when it cannot be evaluated (no ctx, no velocities, or more than
/// DAL_EXPR_EVENT_MAXN coordinates).
DAL_API double dal_expr_event(double t, const double *q, const double *qdot, void *ctx);

// ---------------------------------------------------------------------------------------
// Equations shown: the same formulas as symbols. Every result below is simplified: numbers
// folded, 0 and 1 dropped, like terms collected (2 x + 3 x = 5 x, x^a x^b = x^(a + b)),
// products of sums multiplied out, c X sin(u)^2 + c X cos(u)^2 = c X; printing takes common
// factors out of sums (m l^2 a + m l b = m l (l a + b)).

/// Output formats of dal_expr_print.
typedef enum dal_expr_format {
  DAL_EXPR_TEXT = 0, ///< plain text that dal_expr_create reads back ("1/2*m*l^2*thetadot^2")
  DAL_EXPR_LATEX,    ///< LaTeX math ("\frac{1}{2} l^{2} m \dot{\theta}^{2}")
  DAL_EXPR_SCHEME,   ///< SICM's prefix notation ("(* 1/2 (expt l 2) m (expt thetadot 2))")
} dal_expr_format;

/// Print formula k of e, simplified, into buf (len bytes, truncated, NUL-terminated; buf may
/// be NULL when len is 0). Returns the length of the whole text (as snprintf), or DAL_E_ARG
/// (NULL e, k out of range, unknown format), DAL_E_NOMEM, DAL_E_TOO_LARGE (too large to show:
/// the simplification went past 2^21 operations or 2^19 nodes, or the text past 256 KiB; each
/// print is so bounded in time, about a second at most).
DAL_API int dal_expr_print(const dal_expr *e, int k, dal_expr_format fmt, char *buf, size_t len);

/// The derivative of formula k of e along input j (0 <= j < dal_expr_nin(e)), or along t for
/// j = -1, simplified, as a new one-formula expression with e's inputs and parameters (*out;
/// the caller destroys it). Returns DAL_OK, DAL_E_ARG, DAL_E_NOMEM, DAL_E_TOO_LARGE (past the
/// bounds of dal_expr_print; msg says so).
DAL_API int dal_expr_derivative(const dal_expr *e, int k, int j, dal_expr **out, char *msg,
                                size_t msglen);

/// A model of particles given by formulas, from which T, U and L are derived symbolically.
/// Start from dal_default_expr_model_def().
typedef struct dal_expr_model_def {
  const char *name;             ///< name in messages (copied); default "model"
  int dim;                      ///< spatial dimension d (1, 2 or 3). Required
  const char *const *coords;    ///< names of the ncoords generalized coordinates
  int ncoords;                  ///< number of coordinates n (>= 1)
  const char *const *masses;    ///< nparticles formulas of the masses ("m", "2")
  int nparticles;               ///< number of particles N (>= 1)
  const char *const *positions; ///< N d formulas r_k(q, t), particle by particle
  const char *const *gravity;   ///< d formulas of the gravity vector ("0", "-g"); NULL: none
  const char *potential;        ///< a further potential U(q, t); NULL: none
  const char *const *params;    ///< names of the nparam parameters
  const double *values;         ///< their values (NULL: all 0)
  int nparam;                   ///< number of parameters
  int cookie;                   ///< set by dal_default_expr_model_def; do not touch
} dal_expr_model_def;

/// A model def with no coordinates, particles or parameters, dim 0 (to be set), name "model".
DAL_API dal_expr_model_def dal_default_expr_model_def(void);

/// The kinetic energy T = sum_k 1/2 m_k |v_k|^2 with v_k = sum_j dr_k/dq_j qdot_j + dr_k/dt,
/// the potential U = -sum_k m_k g . r_k + U(q, t) and L = T - U of a model, each a
/// one-formula expression over the coordinates with velocities (inputs q, qdot), t and the
/// parameters (T, U, L nullable: the ones wanted). Errors name the formula and column as
/// dal_expr_create. Returns DAL_OK, DAL_E_ARG, DAL_E_NONFINITE, DAL_E_NOMEM, DAL_E_TOO_LARGE.
DAL_API int dal_expr_model_energies(const dal_expr_model_def *def, dal_expr **T, dal_expr **U,
                                    dal_expr **L, char *msg, size_t msglen);

/// Lagrange's equations d/dt dL/dqdot - dL/dq = 0 of a Lagrangian expression, written
/// M(q, t) qddot = F(t, q, qdot), each part an expression over the Lagrangian's inputs
/// (coordinates with velocities), t and parameters; the caller owns them
/// (dal_expr_equations_destroy).
typedef struct dal_expr_equations {
  int n;              ///< number of coordinates
  dal_expr *momentum; ///< p_i = dL/dqdot_i (n formulas)
  dal_expr *mass;     ///< M_ij = d2L/dqdot_i dqdot_j (n x n formulas, row-major)
  dal_expr *force;    ///< F_i = dL/dq_i - sum_j d2L/dqdot_i dq_j qdot_j - d2L/dqdot_i dt (n)
  dal_expr *accel;    ///< qddot = M^-1 F when n == 1 (the state derivative's last part), NULL
                      ///< for n > 1
} dal_expr_equations;

/// Derive Lagrange's equations from L (one formula, velocities = 1) into *eq. Returns DAL_OK,
/// DAL_E_ARG (L not a Lagrangian expression), DAL_E_NOMEM, DAL_E_TOO_LARGE (past the bounds of
/// dal_expr_print); on failure *eq holds no expression.
DAL_API int dal_expr_lagrange(const dal_expr *L, dal_expr_equations *eq, char *msg, size_t msglen);

/// Free the expressions of eq (NULL members are skipped) and zero it.
DAL_API void dal_expr_equations_destroy(dal_expr_equations *eq);

#ifdef __cplusplus
}
#endif
#endif
