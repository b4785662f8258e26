// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Private interface of the model files: the checks of a model's numbers, shared by the builder
// (builder.c) and the per-trajectory overrides (params.c) so that both refuse the same values
// with the same messages (validate.c).
#ifndef DAL_MODEL_INTERNAL_H
#define DAL_MODEL_INTERNAL_H

#include "base/base.h"

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

#endif
