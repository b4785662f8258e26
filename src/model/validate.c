// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The checks of a model's numbers, one copy for the builder and the per-trajectory overrides.
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "model.h"

// a nonzero subnormal (|x| < DBL_MIN) carries fewer than 53 significant bits: masses,
// stiffnesses and lengths made of one give inexact results, so they are refused
static int subnormal(double x) { return x != 0.0 && fabs(x) < DBL_MIN; }
#define SUBNORMAL_REMEDY DAL__SUBNORMAL_REMEDY

int dal__check_mass(char *err, const char *nm, double mass) {
  if (!isfinite(mass))
    return dal__set_err(err, DAL_E_NONFINITE,
                        "particle '%s': mass is %g; give a finite positive mass", nm, mass);
  if (mass <= 0)
    return dal__set_err(err, DAL_E_ARG,
                        "particle '%s': mass %g is not positive; a massless point belongs in a "
                        "constraint or a coordinate map, not a particle",
                        nm, mass);
  if (subnormal(mass))
    return dal__set_err(err, DAL_E_ARG, "particle '%s': mass %g is subnormal; " SUBNORMAL_REMEDY,
                        nm, mass);
  return DAL_OK;
}

// a parameter's name for messages: its name in the primitive's table, or p<i>
const char *dal__param_name(const dal_primitive *prim, int i, char *buf, size_t len) {
  if (prim->version >= 2 && prim->param_names && prim->param_names[i]) return prim->param_names[i];
  snprintf(buf, len, "p%d", i);
  return buf;
}

int dal__check_prim_value(char *err, const char *what, const dal_primitive *prim, int i, double x) {
  char nb[16];
  if (!isfinite(x))
    return dal__set_err(err, DAL_E_NONFINITE,
                        "%s: parameter '%s' of '%s' (index %d) is %g; give a finite value", what,
                        dal__param_name(prim, i, nb, sizeof nb), prim->name, i, x);
  if (subnormal(x))
    return dal__set_err(err, DAL_E_ARG,
                        "%s: parameter '%s' of '%s' (index %d) is %g, subnormal; " SUBNORMAL_REMEDY,
                        what, dal__param_name(prim, i, nb, sizeof nb), prim->name, i, x);
  return DAL_OK;
}

int dal__check_prim_domain(char *err, const char *what, const dal_primitive *prim,
                           const double *param) {
  char nb[16];
  int bad = 0;
  const char *rule = NULL, *quantity = dal__builtin_param_check(prim, param, &bad, &rule);
  if (quantity)
    return dal__set_err(err, DAL_E_ARG,
                        "%s: parameter '%s' of '%s' (index %d, %s) is %g; the %s %s", what,
                        dal__param_name(prim, bad, nb, sizeof nb), prim->name, bad, quantity,
                        param[bad], quantity, rule);
  return DAL_OK;
}

int dal__check_gravity(char *err, int i, double g) {
  if (!isfinite(g)) return dal__set_err(err, DAL_E_NONFINITE, "gravity component %d is %g", i, g);
  if (subnormal(g))
    return dal__set_err(err, DAL_E_ARG, "gravity component %d is %g, subnormal; " SUBNORMAL_REMEDY,
                        i, g);
  return DAL_OK;
}

int dal__check_link(char *err, const char *kind, const char *part, double k, double L) {
  if (!isfinite(k) || !isfinite(L))
    return dal__set_err(err, DAL_E_NONFINITE,
                        "%s on particle '%s': coefficient %g or length %g is not finite", kind,
                        part, k, L);
  if (k < 0 || L < 0)
    return dal__set_err(err, DAL_E_ARG,
                        "%s on particle '%s': coefficient %g and length %g must be >= 0", kind,
                        part, k, L);
  if (subnormal(k) || subnormal(L))
    return dal__set_err(err, DAL_E_ARG,
                        "%s on particle '%s': %s %g is subnormal; " SUBNORMAL_REMEDY, kind, part,
                        subnormal(k) ? "coefficient" : "length", subnormal(k) ? k : L);
  return DAL_OK;
}
