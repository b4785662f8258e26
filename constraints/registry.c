// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Registry of built-in primitives, in a fixed order that only grows.
#include <string.h>

#include "dalembert/primitives.h"

static const dal_primitive *const registry[] = {
    &dal_map_cartesian2, &dal_map_cartesian3, &dal_map_fixed2,    &dal_map_fixed3,
    &dal_map_pendulum,   &dal_map_hanging,    &dal_map_spherical, &dal_map_ring,
    &dal_map_curve2,     &dal_map_curve3,     &dal_map_sphere,
    &dal_con_distance2,  &dal_con_distance3,  &dal_con_anchor2,   &dal_con_anchor3,
    &dal_con_circle2,    &dal_con_circle3,    &dal_con_turning_circle, &dal_con_sphere,
    &dal_con_plane,      &dal_con_line2,      &dal_con_line3,     &dal_con_turning_line2,
    &dal_con_prescribed,
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
