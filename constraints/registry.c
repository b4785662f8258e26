// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Registry of built-in primitives, in a fixed order that only grows.
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "dalembert/primitives.h"
#include "model/model.h"

static const dal_primitive *const registry[] = {
    &dal_map_cartesian2, &dal_map_cartesian3,     &dal_map_fixed2,        &dal_map_fixed3,
    &dal_map_pendulum,   &dal_map_hanging,        &dal_map_spherical,     &dal_map_ring,
    &dal_map_curve2,     &dal_map_curve3,         &dal_map_sphere,        &dal_con_distance2,
    &dal_con_distance3,  &dal_con_anchor2,        &dal_con_anchor3,       &dal_con_circle2,
    &dal_con_circle3,    &dal_con_turning_circle, &dal_con_sphere,        &dal_con_plane,
    &dal_con_line2,      &dal_con_line3,          &dal_con_turning_line2, &dal_con_prescribed,
};

int dal_primitive_count(void) { return (int)(sizeof registry / sizeof registry[0]); }

const dal_primitive *dal_primitive_get(int i) {
  return (i >= 0 && i < dal_primitive_count()) ? registry[i] : NULL;
}

const dal_primitive *dal_primitive_find(const char *name) {
  if (!name) return NULL;
  for (int i = 0; i < dal_primitive_count(); ++i)
    if (strcmp(registry[i]->name, name) == 0) return registry[i];
  return NULL;
}

// Parameter domains of the built-ins, checked when an instance is added: a parameter outside
// its domain gives a model that fails only later (a rod of length 0 ties two particles to a
// point where its gradient does not exist; a normal of length 0 or beyond 1e154 cannot be
// normalized), so it is refused with the parameter's name.
enum { RULE_POSITIVE, RULE_NONZERO, RULE_DIRECTION };

typedef struct param_rule {
  const dal_primitive *prim;
  int first, count, kind;
  const char *what;
} param_rule;

static const param_rule rules[] = {
    {&dal_con_distance2, 0, 1, RULE_POSITIVE, "rod length L"},
    {&dal_con_distance3, 0, 1, RULE_POSITIVE, "rod length L"},
    {&dal_con_anchor2, 0, 1, RULE_POSITIVE, "rod length L"},
    {&dal_con_anchor3, 0, 1, RULE_POSITIVE, "rod length L"},
    {&dal_con_circle2, 0, 1, RULE_POSITIVE, "radius R"},
    {&dal_con_circle3, 0, 1, RULE_POSITIVE, "radius R"},
    {&dal_con_circle3, 4, 3, RULE_DIRECTION, "plane normal n"},
    {&dal_con_turning_circle, 0, 1, RULE_POSITIVE, "radius R"},
    {&dal_con_sphere, 0, 1, RULE_POSITIVE, "radius R"},
    {&dal_con_plane, 3, 3, RULE_DIRECTION, "normal n"},
    {&dal_con_line2, 2, 2, RULE_DIRECTION, "direction a"},
    {&dal_con_line3, 3, 3, RULE_DIRECTION, "direction a"},
    {&dal_map_pendulum, 0, 1, RULE_NONZERO, "length l"},
    {&dal_map_hanging, 0, 1, RULE_NONZERO, "length l"},
    {&dal_map_spherical, 0, 1, RULE_NONZERO, "length l"},
    {&dal_map_ring, 0, 1, RULE_NONZERO, "radius R"},
    {&dal_map_sphere, 0, 1, RULE_NONZERO, "radius R"},
};

const char *dal__builtin_param_check(const dal_primitive *prim, const double *param, int *bad,
                                     const char **rule) {
  static const char *const need[] = {
      "must be > 0", "must be nonzero",
      "must be a nonzero vector whose squared length is a normal double (components between "
      "about 1e-154 and 1e154 in size)"};
  for (size_t i = 0; i < sizeof rules / sizeof rules[0]; ++i) {
    const param_rule *r = &rules[i];
    if (r->prim != prim) continue;
    const double *p = param + r->first;
    *bad = r->first;
    *rule = need[r->kind];
    if (r->kind == RULE_POSITIVE && !(p[0] > 0.0)) return r->what;
    if (r->kind == RULE_NONZERO && p[0] == 0.0) return r->what;
    if (r->kind == RULE_DIRECTION) {
      double s = 0.0;
      for (int k = 0; k < r->count; ++k)
        s += p[k] * p[k];
      if (!(s >= DBL_MIN) || !isfinite(s)) return r->what;
    }
  }
  return NULL;
}
