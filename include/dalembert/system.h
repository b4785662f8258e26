// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Model building: coordinates, particles, coordinate maps, constraints and forces ->
/// system.
///
/// A scene is built in a mutable dal_builder and compiled into an immutable dal_system that
/// any number of states (trajectories, threads) may share read-only.
///
/// Threads: a compiled system is never written after dal_builder_compile, so states of the
/// same system may step in parallel threads (one thread per state); the results are
/// bit-identical to serial runs (tests/test_threads.c). The library keeps no global mutable
/// state. The user's callbacks and the contexts given to the builder are then called from
/// those threads at the same time: they must not write shared data without synchronization.
/// A builder, like a state, is used by one thread at a time.
///
/// Conventions: spatial dimension d is 2 (x, y) or 3 (x, y, z); gravity is whatever vector the
/// user gives (typically (0, -g) in 2D, (0, 0, -g) in 3D). Units are the user's, consistent
/// (SI suggested). Indices are 0-based. Local matrices are row-major, global ones column-major.
#ifndef DAL_SYSTEM_H
#define DAL_SYSTEM_H

#include <stdio.h>

#include "dalembert/base.h"
#include "dalembert/jet.h"

#ifdef __cplusplus
extern "C" {
#endif

/// A smooth map out = f(in, t) of `nin` local inputs to `nout` outputs, written over jets.
/// `param` holds the instance's `nparam` parameters (borrowed); `ctx` is the instance's
/// user pointer. Return 0 on success, > 0 for a recoverable failure (the integrator retries
/// with a smaller step), < 0 to stop.
typedef int dal_jet_fn(const dal_jet *in, dal_jet t, const double *param, dal_jet *out, void *ctx);

/// Newest layout of the dal_primitive table this library knows. A table declares the layout it
/// was written for in `version`; the library reads only the fields that layout has, so a
/// primitive written for version 1 keeps working, and a table newer than the library is
/// refused by name at placement (DAL_E_ARG) instead of being misread.
#define DAL_PRIMITIVE_VERSION 2

/// A primitive: a coordinate map r = f(u, t) (`dal_map_*`) or a constraint phi = f(u, t)
/// (`dal_con_*`). Both are the same object, a smooth vector function over jets.
/// The library derives Jacobians, time derivatives and curvature terms from `eval`.
/// Fields are only ever appended (SQLite-style): write the table with designated initializers
/// and set `version` to the layout you filled (DAL_PRIMITIVE_VERSION for all fields).
typedef struct dal_primitive {
  const char *name; ///< short name, e.g. "pendulum"
  int version;      ///< table layout: 1 (fields up to `flags`) or 2 (parameter names, defaults)
  int nin;          ///< number of local inputs
  int nout;         ///< number of outputs (d for a map, 1.. for a constraint)
  int nparam;       ///< number of real parameters
  dal_jet_fn *eval; ///< the function
  const char *doc;  ///< one line: inputs, parameters, outputs
  unsigned flags;   ///< DAL_PRIM_* hints (0 if none); added in version 1 of the table
  /// Version 2: names of the nparam parameters, e.g. {"l", "x0", ...} (borrowed; NULL: the
  /// library calls them "p0", "p1", ...). Error messages and dal_system_print use them.
  const char *const *param_names;
  /// Version 2: defaults (nparam values, borrowed) taken by parameters a def leaves unset or omits
  /// at the end of its param_list; NaN marks a required parameter. NULL: all required.
  const double *param_defaults;
} dal_primitive;

/// Primitive hint: a map whose first d inputs are a parent's position p and whose output is
/// p + f(other inputs, t). The library then skips the d parent directions when it forms the
/// local Jacobian and uses the composite-mass (tree) assembly of M, Q and c. A wrong hint
/// gives wrong dynamics; leave flags 0 when unsure (the library still detects the case).
#define DAL_PRIM_TRANSLATES 1u

/// A parametric curve point p(s, t) of dimension d for dal_map_curve2/3: write p[0..d-1].
typedef int dal_curve_fn(dal_jet s, dal_jet t, dal_jet *p, void *ctx);

/// Context of dal_map_curve2/3 instances: the curve function and its own context.
typedef struct dal_curve {
  dal_curve_fn *fn; ///< the curve
  void *ctx;        ///< passed to fn (borrowed)
} dal_curve;

/// A point moving with time, x(t) (dimension d): anchors of springs/dampers, moving points.
typedef int dal_path_fn(dal_jet t, dal_jet *x, void *ctx);

/// A whole-system coordinate map: r (N x d, row-major) from q (n) and t.
typedef int dal_map_fn(const dal_jet *q, dal_jet t, dal_jet *r, void *ctx);

/// A potential over particle positions r (N x d, row-major) and t: write *U.
typedef int dal_potential_r_fn(const dal_jet *r, dal_jet t, dal_jet *U, void *ctx);

/// A potential over generalized coordinates q (n) and t: write *U.
typedef int dal_potential_q_fn(const dal_jet *q, dal_jet t, dal_jet *U, void *ctx);

/// A Lagrangian L(t, q, qdot) over jets (q, qdot have n entries): write *L.
typedef int dal_lagrangian_fn(dal_jet t, const dal_jet *q, const dal_jet *qdot, dal_jet *L,
                              void *ctx);

/// Cartesian applied forces: given t, r (N x d) and v (N x d), ADD forces into F (N x d).
/// Return 0 ok, > 0 recoverable (shrink step), < 0 stop.
typedef int dal_force_fn(double t, const double *r, const double *v, double *F, void *ctx);

/// Generalized forces: given t, q (n), qdot (n), ADD into Q (n). Same return convention.
typedef int dal_genforce_fn(double t, const double *q, const double *qdot, double *Q, void *ctx);

/// Mutable model under construction.
typedef struct dal_builder dal_builder;
/// Immutable compiled model; thread-safe to share read-only between states.
typedef struct dal_system dal_system;

/// Create a builder for spatial dimension `dim`: 2 or 3 for particles, or 0 for a system given
/// only by a Lagrangian (dal_builder_set_lagrangian; a Lagrangian system also accepts 2 or
/// 3). *out is NULL on failure. Returns DAL_OK, DAL_E_ARG (dim not 0, 2 or 3), DAL_E_NOMEM.
DAL_API int dal_builder_create(int dim, dal_builder **out);

/// Free a builder (NULL is a no-op). A compiled system does not depend on its builder.
DAL_API void dal_builder_destroy(dal_builder *b);

/// The message of the builder's last call: empty after a successful call (no stale text),
/// naming the culprit after a failure. Valid until the next call.
///
/// Every real input of the builder is refused when NaN or infinite (DAL_E_NONFINITE) or when
/// subnormal and nonzero (|x| < 2.2e-308: it carries fewer than 53 bits, so results made from
/// it are inexact; DAL_E_ARG): masses, stiffnesses, lengths, gravity, anchors, parameters.
DAL_API const char *dal_builder_errmsg(const dal_builder *b);

/// Add a generalized coordinate named `name` (copied; NULL gives "q<i>"). *index receives its
/// 0-based index (index may be NULL).
DAL_API int dal_builder_add_coord(dal_builder *b, const char *name, int *index);

/// Add a particle of mass `mass` (> 0, finite, not subnormal) named `name` (copied; NULL gives
/// "p<k>").
/// Its position must be given by dal_builder_place_def or a whole-system map.
DAL_API int dal_builder_add_particle(dal_builder *b, const char *name, double mass, int *index);

// ---------------------------------------------------------------------------------------
// Element definitions (Box2D v3 style): start from dal_default_*_def(), set the fields the
// scene needs, pass the def to dal_builder_*_def. The def is read during the call only (its
// arrays are copied). A def that did not come from its dal_default_*_def() constructor is
// refused (DAL_E_ARG) by its cookie. Defs are the only way to add elements (0.3 removed the
// positional dal_builder_place and friends; CHANGELOG.md shows the port), and options follow
// the same convention (base.h).

/// Largest number of parameters a def holds inline (param[]); a primitive with more takes
/// them all from the def's `param_list` instead.
#define DAL_MAX_PARAM 16

/// How a particle is placed: r = prim(parent position, q[coords], t; param).
typedef struct dal_place_def {
  const dal_primitive *prim; ///< a dal_map_* (nout == d); borrowed, must outlive the system.
                             ///< Required (default NULL).
  int parent;        ///< particle whose position feeds the first d inputs, added and placed before
                     ///< this one; -1 (default) for none
  const int *coords; ///< the ncoords coordinate indices feeding the remaining inputs, in order
                     ///< (copied); NULL (default) when ncoords is 0
  int ncoords;       ///< number of coordinate inputs, default 0
  /// Parameters by the primitive's index enum, e.g. param[DAL_PENDULUM_L]. Entries left as
  /// set by the constructor take prim->param_defaults; a required one must be set.
  double param[DAL_MAX_PARAM];
  /// Or: the first nparam_list parameters as an array (copied; at most prim->nparam values,
  /// those after it take prim->param_defaults), for a primitive with more than DAL_MAX_PARAM
  /// parameters or values kept in an array. NULL (default): param[] is read. Giving both an
  /// array and a set param[] entry is refused (DAL_E_ARG).
  const double *param_list;
  int nparam_list; ///< number of values in param_list, default 0
  void *ctx;       ///< passed to prim->eval (borrowed), default NULL
  int cookie;      ///< set by dal_default_place_def; do not touch
} dal_place_def;

/// A constraint phi(u, t) = 0 of prim->nout rows; inputs: positions of parts (d values each),
/// then coordinates.
typedef struct dal_constraint_def {
  const char *name;            ///< copied; NULL (default) gives "c<i>"
  const dal_primitive *prim;   ///< a dal_con_* or user primitive; borrowed. Required.
  const int *parts;            ///< the nparts particle indices (copied); NULL when nparts is 0
  int nparts;                  ///< number of particle inputs, default 0
  const int *coords;           ///< the ncoords coordinate indices (copied); NULL when 0
  int ncoords;                 ///< number of coordinate inputs, default 0
  double param[DAL_MAX_PARAM]; ///< as in dal_place_def (unset entries take the defaults)
  const double *param_list;    ///< or: parameters as an array, as in dal_place_def
  int nparam_list;             ///< number of values in param_list, default 0
  void *ctx;                   ///< passed to prim->eval (borrowed), default NULL
  int cookie;                  ///< set by dal_default_constraint_def; do not touch
} dal_constraint_def;

/// A linear spring U = k/2 (|r_a - x_b| - length)^2 between particle a and either particle b
/// or an anchor point x_b = anchor + path(t) (the moving-point convention x0 + x(t)).
typedef struct dal_spring_def {
  int a;             ///< first particle. Required (default -1).
  int b;             ///< second particle; -1 (default): the anchor point
  double k;          ///< stiffness (>= 0, force/length), default 0
  double length;     ///< rest length (>= 0, length), default 0
  double anchor[3];  ///< fixed part x0 of the anchor point (d values used), default origin
  dal_path_fn *path; ///< motion x(t) added to anchor (d jets in t); NULL (default): none
  void *ctx;         ///< passed to path (borrowed), default NULL
  int cookie;        ///< set by dal_default_spring_def; do not touch
} dal_spring_def;

/// A linear damper F_a = -c ((v_a - v_b) . e) e, e the unit vector from x_b to r_a, between
/// particle a and either particle b or the anchor point x_b = anchor + path(t).
typedef struct dal_damper_def {
  int a;             ///< first particle. Required (default -1).
  int b;             ///< second particle; -1 (default): the anchor point
  double c;          ///< damping coefficient (>= 0, force/velocity), default 0
  double anchor[3];  ///< fixed part x0 of the anchor point, default origin
  dal_path_fn *path; ///< motion x(t) added to anchor; NULL (default): none
  void *ctx;         ///< passed to path (borrowed), default NULL
  int cookie;        ///< set by dal_default_damper_def; do not touch
} dal_damper_def;

/// A place def with the defaults: no primitive (must be set), no parent, no coordinates,
/// every parameter unset (taking the primitive's defaults), no context.
DAL_API dal_place_def dal_default_place_def(void);
/// A constraint def with the defaults: no name, no primitive, no inputs, parameters unset.
DAL_API dal_constraint_def dal_default_constraint_def(void);
/// Sets the parameter of def->prim called `name` (its name in the primitive's table, e.g. "l"
/// or "w" of dal_map_pendulum; a 0-based index in decimal works too): the name-checked form
/// of def->param[DAL_PENDULUM_L] = value, which cannot pick an index of another primitive's
/// enum by mistake. Set def->prim first. Returns DAL_OK, or DAL_E_ARG (nothing set) when def,
/// def->prim or name is NULL or the primitive has no parameter of that name (the names are
/// listed with each primitive in primitives.h and by dal_system_print). The value itself is
/// checked when the def is placed, as for def->param.
DAL_API int dal_place_def_set(dal_place_def *def, const char *name, double value);
/// dal_place_def_set for a constraint def: sets the parameter `name` of def->prim.
DAL_API int dal_constraint_def_set(dal_constraint_def *def, const char *name, double value);
/// A spring def with the defaults: a = -1 (must be set), anchored (b = -1) at the origin, no
/// path, k = 0, length = 0.
DAL_API dal_spring_def dal_default_spring_def(void);
/// A damper def with the defaults: a = -1 (must be set), anchored at the origin, c = 0.
DAL_API dal_damper_def dal_default_damper_def(void);

/// Place particle `particle` as `def` says: local inputs are, in order, the position of
/// def->parent (d values; the parent must have been added before and placed first), then the
/// coordinates def->coords, so prim->nin == (parent >= 0 ? d : 0) + ncoords. Each particle is
/// placed once. Checks, each by name: the cookie, the particle and parent indices, that the
/// primitive is well formed (a name, nin >= 0, nout >= 1, nparam >= 0, an eval), its table
/// version (1 ... DAL_PRIMITIVE_VERSION), its input count, its output count against d,
/// coordinate indices, every parameter finite, every required parameter set ("parameter 'l'
/// of 'pendulum' ...") and a built-in's parameters in their domain (lengths and radii of
/// constraints > 0, those of maps nonzero, normals and directions of representable nonzero
/// length; primitives.h). Returns DAL_OK, DAL_E_ARG, DAL_E_NONFINITE or DAL_E_NOMEM; on
/// failure nothing changes and dal_builder_errmsg says why.
DAL_API int dal_builder_place_def(dal_builder *b, int particle, const dal_place_def *def);

/// Add the holonomic constraint phi(u, t) = 0 of `def`: local inputs are the positions of
/// def->parts (d values each), then the coordinates def->coords, so prim->nin == nparts * d +
/// ncoords; prim->nout rows are added. Residuals should be in length units (built-ins are).
/// *index (nullable) receives the index of its first row. Checks as dal_builder_place_def,
/// with particle indices for the inputs.
DAL_API int dal_builder_add_constraint_def(dal_builder *b, const dal_constraint_def *def,
                                           int *index);

/// Add the spring `def`. DAL_E_ARG for a bad particle index or a negative k or length,
/// DAL_E_NONFINITE for a non-finite k, length or anchor component.
DAL_API int dal_builder_add_spring_def(dal_builder *b, const dal_spring_def *def);

/// Add the damper `def`. Errors as dal_builder_add_spring_def.
DAL_API int dal_builder_add_damper_def(dal_builder *b, const dal_damper_def *def);

/// Give all particle positions at once by a user map r(q, t) (r is N x d row-major).
/// Exclusive with dal_builder_place_def.
DAL_API int dal_builder_set_map(dal_builder *b, dal_map_fn *fn, void *ctx);

/// Describe the system by a Lagrangian L(t, q, qdot) instead of particles (SICM's
/// Lagrangian->state-derivative). Exclusive with particles. Generalized forces may be added.
/// Energies of such a system (dal_state_energies) are read off L itself: U = -L(t, q, 0) plus
/// any U(q, t) potentials, T = L(t, q, qdot) - L(t, q, 0), E = T + U, T2 = 1/2 qdot' (d2L /
/// dqdot2) qdot, T1 = T - T2, T0 = 0 (a velocity-free term of L counts in U), and h the exact
/// Jacobi integral. For L = T - V with T quadratic in qdot these are the usual T and V.
DAL_API int dal_builder_set_lagrangian(dal_builder *b, dal_lagrangian_fn *fn, void *ctx);

/// Uniform gravity: acceleration vector g (d values, copied), force m_k g on every particle.
DAL_API int dal_builder_set_gravity(dal_builder *b, const double *g);

/// How a compiled system computes accelerations (and, with constraints, multipliers); where
/// each applies and what it costs is in solve.h ("Dynamics routes").
typedef enum dal_dynamics {
  DAL_DYNAMICS_AUTO = 0,  ///< the recursion where it applies (the default), else dense
  DAL_DYNAMICS_DENSE,     ///< assemble M and factor it (Cholesky; the KKT matrix with
                          ///< constraints)
  DAL_DYNAMICS_RECURSIVE, ///< the O(N) articulated-body recursion over the tree of placements
                          ///< (with constraints: the m x m loop system); dal_builder_compile
                          ///< fails with DAL_E_UNSUPPORTED naming the reason where it cannot
                          ///< apply
} dal_dynamics;

/// Choose the dynamics route (default DAL_DYNAMICS_AUTO). Both routes give the same
/// accelerations, multipliers and reactions to rounding; DENSE is there for comparisons and
/// for trees whose mass matrix is singular where constraints make the KKT matrix regular.
/// Returns DAL_E_ARG for an unknown value.
DAL_API int dal_builder_set_dynamics(dal_builder *b, dal_dynamics how);

/// Add a user potential U(r, t) over all particle positions; F = -grad U is exact.
DAL_API int dal_builder_add_potential_r(dal_builder *b, dal_potential_r_fn *fn, void *ctx);

/// Add a user potential U(q, t) over generalized coordinates; Q = -dU/dq is exact.
DAL_API int dal_builder_add_potential_q(dal_builder *b, dal_potential_q_fn *fn, void *ctx);

/// Add a user Cartesian force callback F(t, r, v) (non-potential; not in U).
DAL_API int dal_builder_add_force(dal_builder *b, dal_force_fn *fn, void *ctx);

/// Add a user generalized force callback Q(t, q, qdot) (non-potential; not in U).
DAL_API int dal_builder_add_genforce(dal_builder *b, dal_genforce_fn *fn, void *ctx);

/// Compile the builder into an immutable system. Validates the model (every particle placed,
/// indices, counts) and reports the first problem by name. The builder stays usable.
DAL_API int dal_builder_compile(dal_builder *b, dal_system **out);

/// Free a system (NULL is a no-op). All states of the system must be destroyed first.
DAL_API void dal_system_destroy(dal_system *sys);

/// The dynamics route the system uses (DAL_DYNAMICS_DENSE or DAL_DYNAMICS_RECURSIVE; AUTO
/// resolved at compile time). DAL_DYNAMICS_AUTO for NULL.
DAL_API dal_dynamics dal_system_dynamics(const dal_system *sys);
/// Spatial dimension d (2 or 3).
DAL_API int dal_system_dim(const dal_system *sys);
/// Number of generalized coordinates n.
DAL_API int dal_system_ncoords(const dal_system *sys);
/// Number of particles N (0 for a Lagrangian system).
DAL_API int dal_system_nparticles(const dal_system *sys);
/// Number of scalar constraint rows m (0: minimal coordinates, runs as an ODE).
DAL_API int dal_system_nconstraints(const dal_system *sys);
/// Name of coordinate i (NULL if out of range).
DAL_API const char *dal_system_coord_name(const dal_system *sys, int i);
/// Name of particle k (NULL if out of range).
DAL_API const char *dal_system_particle_name(const dal_system *sys, int k);
/// Name of the constraint owning row i (NULL if out of range).
DAL_API const char *dal_system_constraint_name(const dal_system *sys, int i);
/// Mass of particle k (NaN if out of range).
DAL_API double dal_system_mass(const dal_system *sys, int k);

/// Print the model to fp (like MuJoCo's mj_printModel): coordinates, particles with their
/// masses and how each is placed (primitive, parent, coordinates, named parameters),
/// constraints (rows, primitive, inputs, named parameters) and forces (gravity, springs and
/// dampers with their anchors, counts of callbacks). Numbers are printed with %.17g, so they
/// read back exactly. Returns DAL_OK, DAL_E_ARG (NULL argument) or DAL_E_IO.
DAL_API int dal_system_print(const dal_system *sys, FILE *fp);

#ifdef __cplusplus
}
#endif
#endif
