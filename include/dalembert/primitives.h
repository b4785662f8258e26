// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Built-in primitives: coordinate maps (dal_map_*) and constraints (dal_con_*), and the registry.
//
// Each is a dal_primitive (see system.h): inputs, parameters and outputs are listed with it.
// Angles in radians, rates in rad/s. "Pivot motion" parameters describe a point
// p(t) = (x0 + ax cos(w t + ph), y0 + ay cos(w t + ph)).
#ifndef DAL_PRIMITIVES_H
#define DAL_PRIMITIVES_H

#include "dalembert/system.h"

#ifdef __cplusplus
extern "C" {
#endif

/// 2D identity map. in: (x, y). param: none. out: (x, y).
DAL_API extern const dal_primitive dal_map_cartesian2;
/// 3D identity map. in: (x, y, z). param: none. out: (x, y, z).
DAL_API extern const dal_primitive dal_map_cartesian3;
/// 2D fixed point. in: none. param: (x, y). out: (x, y).
DAL_API extern const dal_primitive dal_map_fixed2;
/// 3D fixed point. in: none. param: (x, y, z). out: (x, y, z).
DAL_API extern const dal_primitive dal_map_fixed3;
/// 2D pendulum about a (possibly moving) pivot, theta measured from the downward vertical
/// (-y), counter-clockwise. in: (theta). param: (l, x0, y0, ax, ay, w, ph).
/// out: p(t) + l (sin theta, -cos theta).
DAL_API extern const dal_primitive dal_map_pendulum;
/// 2D pendulum hanging from another particle (chains, double pendulum).
/// in: (x_parent, y_parent, theta). param: (l). out: parent + l (sin theta, -cos theta).
DAL_API extern const dal_primitive dal_map_hanging;
/// 3D spherical pendulum about a fixed pivot, polar angle theta from the downward vertical
/// (-z), azimuth phi about z. in: (theta, phi). param: (l, x0, y0, z0).
/// out: pivot + l (sin th cos ph, sin th sin ph, -cos th). Singular at theta = 0, pi.
DAL_API extern const dal_primitive dal_map_spherical;
/// 3D bead on a ring of radius R turning about the vertical z axis through its centre at rate
/// w; theta is the polar angle from the ring's bottom point. in: (theta).
/// param: (R, w, phi0). out: (R sin th cos(w t + phi0), R sin th sin(w t + phi0), -R cos th).
DAL_API extern const dal_primitive dal_map_ring;
/// 2D point on a user parametric curve p(s, t). in: (s). param: none.
/// ctx: a dal_curve (borrowed). out: p(s, t).
DAL_API extern const dal_primitive dal_map_curve2;
/// 3D point on a user parametric curve p(s, t). in: (s). param: none. ctx: a dal_curve.
DAL_API extern const dal_primitive dal_map_curve3;
/// 3D point on a sphere of radius R centred at c, polar angle theta from +z, azimuth phi.
/// in: (theta, phi). param: (R, cx, cy, cz). out: c + R (sin th cos ph, sin th sin ph, cos th).
DAL_API extern const dal_primitive dal_map_sphere;

/// Number of built-in primitives in the registry.
DAL_API int dal_primitive_count(void);
/// Built-in primitive i of the registry (NULL if out of range).
DAL_API const dal_primitive *dal_primitive_get(int i);
/// Built-in primitive by name (NULL if none).
DAL_API const dal_primitive *dal_primitive_find(const char *name);

#ifdef __cplusplus
}
#endif
#endif
