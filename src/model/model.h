// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The face of model/: builder, system and state (the lazy evaluation of a state handed to a
// callback, the per-trajectory parameters), and the checks of a model's numbers, shared by the
// builder (builder.c) and the per-trajectory overrides (params.c) so that both refuse the same
// values with the same messages (validate.c).
#ifndef DAL_MODEL_MODEL_H
#define DAL_MODEL_MODEL_H

#include "eval/eval.h"

/// The remedy every message about a subnormal input ends with
#define DAL__SUBNORMAL_REMEDY                                                                      \
  "a subnormal number (|x| < 2.2e-308) carries fewer than 53 significant bits, so results "        \
  "computed from it are inexact; rescale the units, or give 0 if 0 is meant"

/// A particle's mass: finite (DAL_E_NONFINITE), positive and normal (DAL_E_ARG). name: the
/// particle's name in the message. Writes the message into err (DAL_ERRMSG_LEN) on failure.
int dal__check_mass(char *err, const char *name, double mass);

/// One value of a primitive's parameter (index i): finite and not subnormal. what: the owner
/// in the message ("placing particle 'bob'", "constraint 'rod'").
int dal__check_prim_value(char *err, const char *what, const dal_primitive *prim, int i, double x);

/// A built-in primitive's whole parameter vector (nparam values) in its domain (a rod of length
/// 0, a zero normal): DAL_E_ARG naming the parameter, else 0.
int dal__check_prim_domain(char *err, const char *what, const dal_primitive *prim,
                           const double *param);

/// Gravity component i: finite and not subnormal.
int dal__check_gravity(char *err, int i, double g);

/// A spring's or damper's coefficient k and length L (0 for a damper): finite, >= 0, not
/// subnormal. kind: "spring", "anchor spring", "damper" or "anchor damper"; part: the name of
/// its first particle.
int dal__check_link(char *err, const char *kind, const char *part, double k, double L);

/// A state handed to a monitor or event function at a dense-output time is evaluated only
/// when the callback reads a product (st->lazy): reading q alone costs nothing; the public
/// readers call this first (state.c; nothing happens unless st->lazy)
void dal__lazy_eval(const dal_state *st);
/// the same for the products p only (DAL_P_*): a reader evaluates what it reads
void dal__lazy_eval_for(const dal_state *st, unsigned p);
/// End a callback's hold on a lazily evaluated state: 0, or the status of an evaluation that
/// failed while the callback read it, with the message "<who> at t=...: evaluating the state
/// failed: ..." (state.c)
int dal__lazy_end(dal_state *st, const char *who);

/// drop integrator memory (dal_state_set, dal_state_destroy, parameter changes); the KKT
/// factorization's history goes with it, so that results do not depend on a state's past
/// (params.c)
void dal__integ_reset(dal_state *st);

/// per-trajectory parameters (params.c): point at the system's arrays / free owned copies
void dal__params_init(dal_state *st);
void dal__params_free(dal_state *st);
/// restore the system's values into the state's owned copies (keeps the buffers: no allocation)
void dal__params_rewind(dal_state *st);
/// name of parameter i of prim: its param_names entry, else "p<i>" written into buf
/// (validate.c)
const char *dal__param_name(const dal_primitive *prim, int i, char *buf, size_t len);
/// Give a Lagrangian system (dal_builder_set_lagrangian first) its parts dL/dqdot and dL/dq as
/// one function (base.h, dal__lagrangian_parts_fn; fn NULL: none): the accelerations then come
/// from them, the energies still from L (builder.c)
int dal__builder_set_lagrangian_parts(dal_builder *b, dal__lagrangian_parts_fn *fn, void *ctx);
/// DAL_OK when prim->version is one this library reads, else DAL_E_ARG with a message in err
/// (builder.c)
int dal__prim_version_ok(const dal_primitive *prim, char *err, const char *what);

/// Domain check of a built-in primitive's parameters (constraints/registry.c: the built-in
/// primitives are the model's bricks and are compiled with it): NULL when they
/// are fine (or prim is not a built-in), else the name of the offending quantity ("rod length
/// L", "normal n") with *bad its first parameter index and *rule what it must be.
const char *dal__builtin_param_check(const dal_primitive *prim, const double *param, int *bad,
                                     const char **rule);

#endif
