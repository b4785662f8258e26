// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Built-in primitives: coordinate maps (dal_map_*) and constraints (dal_con_*), and the registry.
//
// Each is a dal_primitive (see system.h): inputs, parameters and outputs are listed with it.
// The builder refuses parameters outside a built-in's domain, naming them: the length or radius
// of a constraint (rods, circles, spheres) must be > 0, that of a map (pendulums, ring, sphere)
// nonzero, and a normal or direction (plane, line, circle3) a nonzero vector whose squared
// length is a normal double.
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

/// Context of dal_con_anchor2/3 for a moving anchor: the point is x0 + x(t), where fn writes
/// x (d jets in t; their d and dd are the point's velocity and acceleration). Borrowed: must
/// outlive the system.
typedef struct dal_moving_point {
  dal_path_fn *fn; ///< the motion x(t) added to the fixed part x0
  void *ctx;       ///< passed to fn (borrowed)
} dal_moving_point;

/// A scalar function of time over jets for prescribed motions: write *f = f(t).
typedef int dal_time_fn(dal_jet t, dal_jet *f, void *ctx);

/// Context of dal_con_prescribed: q_i = q0 + f(t). Borrowed: must outlive the system.
typedef struct dal_prescribed {
  dal_time_fn *fn; ///< f(t)
  void *ctx;       ///< passed to fn (borrowed)
} dal_prescribed;

// Constraints phi(u, t) = 0 for dal_builder_add_constraint. Inputs are particle positions
// (d values each, in the order of `parts`) then coordinates. Every residual is in length
// units (a signed distance), so tolerances mean the same for a rod of 1e-3 and of 1e3; only
// dal_con_prescribed is in the units of its coordinate. The multiplier of a row is the
// generalized force G' lambda it exerts (see dae.h): for a distance row (|b - a| - L) the
// force on b is lambda e, e the unit vector from a to b, so lambda = -T for a rod in tension T.

/// 2D rod between particles a and b. parts: (a, b). in: (xa, ya, xb, yb). param: (L), the
/// length (> 0). out: |r_b - r_a| - L. Undefined when the particles coincide.
DAL_API extern const dal_primitive dal_con_distance2;
/// 3D rod between particles a and b. parts: (a, b). in: (xa, ya, za, xb, yb, zb).
/// param: (L). out: |r_b - r_a| - L.
DAL_API extern const dal_primitive dal_con_distance3;
/// 2D rod from a particle to a fixed or moving point. parts: (p). in: (x, y).
/// param: (L, x0, y0). ctx: NULL (fixed point x0) or a dal_moving_point (point x0 + x(t)).
/// out: |r - p(t)| - L. A driven pendulum's pivot is a moving point.
DAL_API extern const dal_primitive dal_con_anchor2;
/// 3D rod from a particle to a fixed or moving point. parts: (p). in: (x, y, z).
/// param: (L, x0, y0, z0). ctx: NULL or a dal_moving_point. out: |r - p(t)| - L.
DAL_API extern const dal_primitive dal_con_anchor3;
/// 2D particle on a circle of radius R centred at c. in: (x, y). param: (R, cx, cy).
/// out: |r - c| - R.
DAL_API extern const dal_primitive dal_con_circle2;
/// 3D particle on a circle of radius R centred at c in the plane of normal n (any length
/// > 0). in: (x, y, z). param: (R, cx, cy, cz, nx, ny, nz). out (2 rows): n.(r - c)/|n| and
/// |in-plane part of r - c| - R.
DAL_API extern const dal_primitive dal_con_circle3;
/// 3D particle on a circle turning with time (bead on a rotating ring): radius R, centre c,
/// its plane contains the vertical line through c and turns about it at rate w (rad/s), the
/// plane's horizontal direction being (cos a, sin a, 0), a = w t + phi0. Same motion as
/// dal_map_ring with c = 0. in: (x, y, z). param: (R, w, phi0, cx, cy, cz).
/// out (2 rows): n(t).(r - c) with n(t) = (-sin a, cos a, 0), and |r - c| - R.
DAL_API extern const dal_primitive dal_con_turning_circle;
/// 3D particle on a sphere of radius R centred at c. in: (x, y, z). param: (R, cx, cy, cz).
/// out: |r - c| - R.
DAL_API extern const dal_primitive dal_con_sphere;
/// 3D particle on the plane through c with normal n (any length > 0). in: (x, y, z).
/// param: (cx, cy, cz, nx, ny, nz). out: n.(r - c) / |n|.
DAL_API extern const dal_primitive dal_con_plane;
/// 2D particle on the line through c with direction a (any length > 0). in: (x, y).
/// param: (cx, cy, ax, ay). out: signed distance from the line, positive to the left of a.
DAL_API extern const dal_primitive dal_con_line2;
/// 3D particle on the line through c with direction a (any length > 0). in: (x, y, z).
/// param: (cx, cy, cz, ax, ay, az). out (2 rows): the components of r - c along an
/// orthonormal pair normal to a (a fixed function of a).
DAL_API extern const dal_primitive dal_con_line3;
/// 2D particle on a line turning about the point c (bead on a rotating rod): the line's
/// angle from the x axis is a = w t + phi0. in: (x, y). param: (cx, cy, w, phi0).
/// out: -(x - cx) sin a + (y - cy) cos a, the signed distance from the line.
DAL_API extern const dal_primitive dal_con_turning_line2;
/// Prescribed coordinate q = q0 + f(t) (a driven joint). coords: (i). in: (q_i).
/// param: (q0). ctx: NULL (q_i held at q0) or a dal_prescribed giving f(t).
/// out: q_i - q0 - f(t), in the units of the coordinate.
DAL_API extern const dal_primitive dal_con_prescribed;

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
