// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Built-in primitives: coordinate maps (dal_map_*) and constraints (dal_con_*), and the
/// registry.
///
/// Each is a dal_primitive (see system.h): inputs, parameters and outputs are listed with it.
/// The builder refuses parameters outside a built-in's domain, naming them: the length or radius
/// of a constraint (rods, circles, spheres) must be > 0, that of a map (pendulums, ring, sphere)
/// nonzero, and a normal or direction (plane, line, circle3) a nonzero vector whose squared
/// length is a normal double.
/// Angles in radians, rates in rad/s. "Pivot motion" parameters describe a point
/// p(t) = (x0 + ax cos(w t + ph), y0 + ay cos(w t + ph)).
#ifndef DAL_PRIMITIVES_H
#define DAL_PRIMITIVES_H

#include "dalembert/system.h"

#ifdef __cplusplus
extern "C" {
#endif

// Parameter indices. Each built-in primitive's parameters have names (prim->param_names, used
// in error messages) and an index enum, so a def reads as what it means:
//   d.param[DAL_PENDULUM_L] = 1.0;
// A parameter left unset in a def (or omitted at the end of its param_list) takes its
// default, listed here; "required" ones have none and must be given.
// Moving points follow one convention everywhere: the point is x0 + x(t), a fixed part x0 (a
// parameter or def field, default the origin) plus an optional motion x(t) from a callback.

/// dal_map_fixed2/3: the point. Defaults: origin.
enum dal_fixed_param {
  DAL_FIXED_X,           ///< x (length), default 0
  DAL_FIXED_Y,           ///< y (length), default 0
  DAL_FIXED_Z,           ///< z (length, 3D only), default 0
  DAL_FIXED2_NPARAM = 2, ///< parameter count of dal_map_fixed2
  DAL_FIXED3_NPARAM = 3, ///< parameter count of dal_map_fixed3
};
/// dal_map_pendulum: length and pivot motion p(t) = (x0 + ax cos(w t + ph), y0 + ay cos(w t +
/// ph)). Defaults: pivot fixed at the origin (no drive); l required.
enum dal_pendulum_param {
  DAL_PENDULUM_L,      ///< rod length l (> 0, length), required
  DAL_PENDULUM_X0,     ///< pivot x0 (length), default 0
  DAL_PENDULUM_Y0,     ///< pivot y0 (length), default 0
  DAL_PENDULUM_AX,     ///< drive amplitude along x (length), default 0
  DAL_PENDULUM_AY,     ///< drive amplitude along y (length), default 0
  DAL_PENDULUM_W,      ///< drive angular frequency w (rad/s), default 0
  DAL_PENDULUM_PH,     ///< drive phase ph (rad), default 0
  DAL_PENDULUM_NPARAM, ///< parameter count (7)
};
/// dal_map_hanging: rod length (required).
enum dal_hanging_param {
  DAL_HANGING_L,      ///< rod length l (> 0, length), required
  DAL_HANGING_NPARAM, ///< parameter count (1)
};
/// dal_map_spherical: length and fixed pivot. Defaults: pivot at the origin; l required.
enum dal_spherical_param {
  DAL_SPHERICAL_L,      ///< rod length l (> 0, length), required
  DAL_SPHERICAL_X0,     ///< pivot x (length), default 0
  DAL_SPHERICAL_Y0,     ///< pivot y (length), default 0
  DAL_SPHERICAL_Z0,     ///< pivot z (length), default 0
  DAL_SPHERICAL_NPARAM, ///< parameter count (4)
};
/// dal_map_ring: radius (required), turning rate and initial angle (default 0: a still ring).
enum dal_ring_param {
  DAL_RING_R,      ///< radius R (> 0, length), required
  DAL_RING_W,      ///< turning rate w (rad/s), default 0
  DAL_RING_PHI0,   ///< angle of the ring's plane at t = 0 (rad), default 0
  DAL_RING_NPARAM, ///< parameter count (3)
};
/// dal_map_sphere and dal_con_sphere: radius (required) and centre (default origin).
enum dal_sphere_param {
  DAL_SPHERE_R,      ///< radius R (> 0, length), required
  DAL_SPHERE_CX,     ///< centre x (length), default 0
  DAL_SPHERE_CY,     ///< centre y (length), default 0
  DAL_SPHERE_CZ,     ///< centre z (length), default 0
  DAL_SPHERE_NPARAM, ///< parameter count (4)
};
/// dal_con_distance2/3: rod length (required).
enum dal_distance_param {
  DAL_DISTANCE_L,      ///< rod length L (> 0, length), required
  DAL_DISTANCE_NPARAM, ///< parameter count (1)
};
/// dal_con_anchor2/3: rod length (required) and the fixed part x0 of the anchor point
/// x0 + x(t) (default origin; x(t) from a dal_moving_point context, else 0).
enum dal_anchor_param {
  DAL_ANCHOR_L,           ///< rod length L (> 0, length), required
  DAL_ANCHOR_X0,          ///< anchor x0 (length), default 0
  DAL_ANCHOR_Y0,          ///< anchor y0 (length), default 0
  DAL_ANCHOR_Z0,          ///< anchor z0 (length, 3D only), default 0
  DAL_ANCHOR2_NPARAM = 3, ///< parameter count of dal_con_anchor2
  DAL_ANCHOR3_NPARAM = 4, ///< parameter count of dal_con_anchor3
};
/// dal_con_circle2/3: radius (required), centre (default origin), plane normal (3D, default
/// +z).
enum dal_circle_param {
  DAL_CIRCLE_R,           ///< radius R (> 0, length), required
  DAL_CIRCLE_CX,          ///< centre x (length), default 0
  DAL_CIRCLE_CY,          ///< centre y (length), default 0
  DAL_CIRCLE_CZ,          ///< centre z (length, 3D only), default 0
  DAL_CIRCLE_NX,          ///< plane normal x (3D only), default 0
  DAL_CIRCLE_NY,          ///< plane normal y (3D only), default 0
  DAL_CIRCLE_NZ,          ///< plane normal z (3D only), default 1
  DAL_CIRCLE2_NPARAM = 3, ///< parameter count of dal_con_circle2
  DAL_CIRCLE3_NPARAM = 7, ///< parameter count of dal_con_circle3
};
/// dal_con_turning_circle: radius (required), turning rate, initial angle, centre.
enum dal_turning_circle_param {
  DAL_TURNING_CIRCLE_R,      ///< radius R (> 0, length), required
  DAL_TURNING_CIRCLE_W,      ///< turning rate w (rad/s), default 0
  DAL_TURNING_CIRCLE_PHI0,   ///< angle of the plane at t = 0 (rad), default 0
  DAL_TURNING_CIRCLE_CX,     ///< centre x (length), default 0
  DAL_TURNING_CIRCLE_CY,     ///< centre y (length), default 0
  DAL_TURNING_CIRCLE_CZ,     ///< centre z (length), default 0
  DAL_TURNING_CIRCLE_NPARAM, ///< parameter count (6)
};
/// dal_con_plane: a point on the plane (default origin) and its normal (default +z).
enum dal_plane_param {
  DAL_PLANE_CX,     ///< point x (length), default 0
  DAL_PLANE_CY,     ///< point y (length), default 0
  DAL_PLANE_CZ,     ///< point z (length), default 0
  DAL_PLANE_NX,     ///< normal x, default 0
  DAL_PLANE_NY,     ///< normal y, default 0
  DAL_PLANE_NZ,     ///< normal z, default 1
  DAL_PLANE_NPARAM, ///< parameter count (6)
};
/// dal_con_line2: a point on the line (default origin) and its direction (default +x).
enum dal_line2_param {
  DAL_LINE2_CX,     ///< point x (length), default 0
  DAL_LINE2_CY,     ///< point y (length), default 0
  DAL_LINE2_AX,     ///< direction x, default 1
  DAL_LINE2_AY,     ///< direction y, default 0
  DAL_LINE2_NPARAM, ///< parameter count (4)
};
/// dal_con_line3: a point on the line (default origin) and its direction (default +x).
enum dal_line3_param {
  DAL_LINE3_CX,     ///< point x (length), default 0
  DAL_LINE3_CY,     ///< point y (length), default 0
  DAL_LINE3_CZ,     ///< point z (length), default 0
  DAL_LINE3_AX,     ///< direction x, default 1
  DAL_LINE3_AY,     ///< direction y, default 0
  DAL_LINE3_AZ,     ///< direction z, default 0
  DAL_LINE3_NPARAM, ///< parameter count (6)
};
/// dal_con_turning_line2: centre of rotation (default origin), rate and initial angle.
enum dal_turning_line2_param {
  DAL_TURNING_LINE2_CX,     ///< centre x (length), default 0
  DAL_TURNING_LINE2_CY,     ///< centre y (length), default 0
  DAL_TURNING_LINE2_W,      ///< turning rate w (rad/s), default 0
  DAL_TURNING_LINE2_PHI0,   ///< line angle at t = 0 (rad), default 0
  DAL_TURNING_LINE2_NPARAM, ///< parameter count (4)
};
/// dal_con_prescribed: the fixed part q0 of q = q0 + f(t) (default 0).
enum dal_prescribed_param {
  DAL_PRESCRIBED_Q0,     ///< q0 (units of the coordinate), default 0
  DAL_PRESCRIBED_NPARAM, ///< parameter count (1)
};

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

// Constraints phi(u, t) = 0 for dal_builder_add_constraint_def. Inputs are particle positions
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
