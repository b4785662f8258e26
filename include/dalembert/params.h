// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Per-trajectory parameters: a state overrides masses, primitive parameters, gravity,
/// springs.
///
/// A compiled system is immutable and shared; a state may override its parameters for its own
/// trajectory without a new builder or compile. Until the first override a state reads the
/// system's values; an override copies the affected array into the state (copy-on-write, one
/// allocation the first time, none after) and changes only that state. Overrides are validated
/// like the builder's calls, with the same messages (kept in dal_state_errmsg), and on failure
/// the state is unchanged. A successful override discards the integrator history (as
/// dal_state_set does) and marks the state's outputs stale: call dal_state_set or dal_forward
/// before reading them. dal_state_set keeps the overrides; dal_state_reset_params drops them.
///
/// Addressing. A parameter is a dal_param_ref (kind, target, index) or a name:
/// @verbatim
///   "mass:<particle>"              mass of a particle (> 0)
///   "place:<particle>:<p>"         parameter p of the primitive placing that particle: its
///                                  name in the primitive's table or its 0-based index in the
///                                  documented order (primitives.h); e.g. the drive of
///                                  dal_map_pendulum (l, x0, y0, ax, ay, w, ph) is
///                                  "place:bob:ax" or "place:bob:3", "place:bob:w" or
///                                  "place:bob:5"
///   "con:<constraint>:<p>"         parameter p of a constraint, e.g. "con:rod:l" or "con:rod:0"
///   "gravity:<i>"                  component i (0 = x, 1 = y, 2 = z) of gravity
///   "spring:<j>:k", "spring:<j>:L" stiffness / rest length of the j-th spring (anchor springs
///                                  included, in the order they were added)
///   "damper:<j>:c"                 coefficient of the j-th damper (anchor dampers included)
/// @endverbatim
/// `<particle>` and `<constraint>` are the names given to the builder, or 0-based indices.
/// In a dal_param_ref a primitive's parameter is its index, the value of its named index enum
/// in primitives.h (DAL_PENDULUM_W = 5). An unknown parameter name is refused with a message
/// that lists the primitive's parameter names.
///
/// What cannot be overridden (it is not data of the compiled system): the structure (counts,
/// inputs, which primitive), user callbacks and their contexts (a force callback's constants
/// live in the caller's ctx; give each thread its own system or read per-trajectory values
/// from a context the caller indexes), anchor positions and anchor paths.
#ifndef DAL_PARAMS_H
#define DAL_PARAMS_H

#include <stddef.h>

#include "dalembert/base.h"
#include "dalembert/state.h"
#include "dalembert/system.h"

#ifdef __cplusplus
extern "C" {
#endif

/// What a parameter reference points at.
typedef enum dal_param_kind {
  DAL_PARAM_NONE = 0,   ///< no parameter (an unset reference)
  DAL_PARAM_MASS,       ///< mass of particle `target` (index unused, 0)
  DAL_PARAM_PLACE,      ///< parameter `index` of the primitive placing particle `target`
  DAL_PARAM_CONSTRAINT, ///< parameter `index` of constraint `target` (order of addition)
  DAL_PARAM_GRAVITY,    ///< gravity component `index` (0 .. d-1); target unused, 0
  DAL_PARAM_SPRING_K,   ///< stiffness of spring `target` (order of addition)
  DAL_PARAM_SPRING_L,   ///< rest length of spring `target`
  DAL_PARAM_DAMPER_C,   ///< coefficient of damper `target` (order of addition)
} dal_param_kind;

/// A reference to one real parameter of a compiled system.
typedef struct dal_param_ref {
  dal_param_kind kind; ///< what it points at
  int target;          ///< particle, constraint, spring or damper index (0-based)
  int index;           ///< parameter index within the target (primitive parameter, component)
} dal_param_ref;

/// Resolve a parameter name (syntax in the header comment) against `sys` into *out.
/// `msg` (nullable, `msglen` bytes) receives an error message naming what was not found and
/// the valid choices. Returns DAL_OK, DAL_E_ARG (unknown name, index out of range, syntax).
DAL_API int dal_param_find(const dal_system *sys, const char *name, dal_param_ref *out, char *msg,
                           size_t msglen);

/// Check that `ref` points at an existing parameter of `sys`; `msg` as above.
/// Returns DAL_OK or DAL_E_ARG.
DAL_API int dal_param_check(const dal_system *sys, const dal_param_ref *ref, char *msg,
                            size_t msglen);

/// Write the canonical name of `ref` ("mass:bob", "place:bob:5", ...) into buf (len bytes,
/// truncated). Returns DAL_OK or DAL_E_ARG for an invalid reference.
DAL_API int dal_param_name(const dal_system *sys, const dal_param_ref *ref, char *buf, size_t len);

/// The compiled system's value of a parameter into *value. Returns DAL_OK or DAL_E_ARG.
DAL_API int dal_system_param(const dal_system *sys, const dal_param_ref *ref, double *value);

/// The state's value of a parameter (its override, or the system's value) into *value.
/// Returns DAL_OK, DAL_E_ARG, DAL_E_STATE (state of another system).
DAL_API int dal_state_param(const dal_system *sys, const dal_state *st, const dal_param_ref *ref,
                            double *value);

/// Override one parameter for this state. Validation as in the builder: masses finite and
/// > 0, primitive parameters and gravity finite, spring and damper constants finite and >= 0.
/// Returns DAL_OK; DAL_E_NONFINITE or DAL_E_ARG naming the particle/constraint/link, the
/// parameter and the remedy (dal_state_errmsg); DAL_E_STATE; DAL_E_NOMEM (first override of
/// an array). On failure the state is unchanged.
DAL_API int dal_state_set_param(const dal_system *sys, dal_state *st, const dal_param_ref *ref,
                                double value);

/// dal_state_set_param by name (dal_param_find); an unknown name is DAL_E_ARG with the
/// message in dal_state_errmsg.
DAL_API int dal_state_set_param_named(const dal_system *sys, dal_state *st, const char *name,
                                      double value);

/// Override the mass of particle k (> 0, finite) for this state.
DAL_API int dal_state_set_mass(const dal_system *sys, dal_state *st, int k, double mass);

/// Override gravity for this state: g (d values, copied, finite). Turns gravity on for a
/// system compiled without it.
DAL_API int dal_state_set_gravity(const dal_system *sys, dal_state *st, const double *g);

/// Drop every override: the state reads the system's parameters again. Discards the
/// integrator history. Returns DAL_OK, DAL_E_ARG, DAL_E_STATE.
DAL_API int dal_state_reset_params(const dal_system *sys, dal_state *st);

/// Give `dst` the parameters of `src` (overrides included); both belong to `sys`.
/// Returns DAL_OK, DAL_E_ARG, DAL_E_STATE, DAL_E_NOMEM (dst unchanged on failure).
DAL_API int dal_state_copy_params(const dal_system *sys, dal_state *dst, const dal_state *src);

#ifdef __cplusplus
}
#endif
#endif
