// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Model building: coordinates, particles, coordinate maps, constraints and forces -> system.
//
// A scene is built in a mutable dal_builder and compiled into an immutable dal_system that
// any number of states (trajectories, threads) may share read-only.
//
// Threads: a compiled system is never written after dal_builder_compile, so states of the
// same system may step in parallel threads (one thread per state); the results are
// bit-identical to serial runs (tests/test_threads.c). The library keeps no global mutable
// state. The user's callbacks and the contexts given to the builder are then called from
// those threads at the same time: they must not write shared data without synchronization.
// A builder, like a state, is used by one thread at a time.
//
// Conventions: spatial dimension d is 2 (x, y) or 3 (x, y, z); gravity is whatever vector the
// user gives (typically (0, -g) in 2D, (0, 0, -g) in 3D). Units are the user's, consistent
// (SI suggested). Indices are 0-based. Local matrices are row-major, global ones column-major.
#ifndef DAL_SYSTEM_H
#define DAL_SYSTEM_H

#include "dalembert/base.h"
#include "dalembert/jet.h"

#ifdef __cplusplus
extern "C" {
#endif

/// A smooth map out = f(in, t) of `nin` local inputs to `nout` outputs, written over jets.
/// `param` holds the instance's `nparam` parameters (borrowed); `ctx` is the instance's
/// user pointer. Return 0 on success, > 0 for a recoverable failure (the integrator retries
/// with a smaller step), < 0 to stop.
typedef int dal_jet_fn(const dal_jet *in, dal_jet t, const double *param, dal_jet *out,
                       void *ctx);

/// A primitive: a coordinate map r = f(u, t) (`dal_map_*`) or a constraint phi = f(u, t)
/// (`dal_con_*`). Both are the same object, a smooth vector function over jets.
/// The library derives Jacobians, time derivatives and curvature terms from `eval`.
typedef struct dal_primitive {
  const char *name; ///< short name, e.g. "pendulum"
  int version;      ///< ops are only ever appended; 1 for the first version
  int nin;          ///< number of local inputs
  int nout;         ///< number of outputs (d for a map, 1.. for a constraint)
  int nparam;       ///< number of real parameters
  dal_jet_fn *eval; ///< the function
  const char *doc;  ///< one line: inputs, parameters, outputs
  unsigned flags;   ///< DAL_PRIM_* hints (0 if none); added in version 1 of the table
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
typedef int dal_genforce_fn(double t, const double *q, const double *qdot, double *Q,
                            void *ctx);

/// Mutable model under construction.
typedef struct dal_builder dal_builder;
/// Immutable compiled model; thread-safe to share read-only between states.
typedef struct dal_system dal_system;

/// Create a builder for spatial dimension `dim` (2 or 3). *out is NULL on failure.
/// Returns DAL_OK, DAL_E_ARG (dim not 2 or 3), DAL_E_NOMEM.
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
/// Its position must be given by dal_builder_place or a whole-system map.
DAL_API int dal_builder_add_particle(dal_builder *b, const char *name, double mass, int *index);

/// Place particle `particle` by primitive `prim` (a dal_map_*, nout == d; borrowed, must
/// outlive the system). Local inputs are, in order: the position of particle `parent`
/// (d values; parent < 0 for none; the parent must have been added (parent < particle) and
/// placed first), then the coordinates coords[0..ncoords-1]. Hence
/// prim->nin == (parent >= 0 ? d : 0) + ncoords. `param` (nparam values, copied) must match
/// prim->nparam; `ctx` is passed to prim->eval (borrowed). Each particle is placed once.
/// A primitive must be well formed (a name, nin >= 0, nout >= 1, nparam >= 0, an eval), and a
/// built-in's parameters must lie in their domain (lengths and radii of constraints > 0, those
/// of maps nonzero, normals and directions of representable nonzero length; primitives.h):
/// DAL_E_ARG naming the parameter otherwise.
DAL_API int dal_builder_place(dal_builder *b, int particle, const dal_primitive *prim,
                              int parent, int ncoords, const int *coords, int nparam,
                              const double *param, void *ctx);

/// Give all particle positions at once by a user map r(q, t) (r is N x d row-major).
/// Exclusive with dal_builder_place.
DAL_API int dal_builder_set_map(dal_builder *b, dal_map_fn *fn, void *ctx);

/// Describe the system by a Lagrangian L(t, q, qdot) instead of particles (SICM's
/// Lagrangian->state-derivative). Exclusive with particles. Generalized forces may be added.
DAL_API int dal_builder_set_lagrangian(dal_builder *b, dal_lagrangian_fn *fn, void *ctx);

/// Add the holonomic constraint phi(u, t) = 0 named `name` (copied; NULL gives "c<i>").
/// Local inputs: positions of particles parts[0..nparts-1] (d values each), then coordinates
/// coords[0..ncoords-1]; prim->nin must equal nparts * d + ncoords. prim->nout rows are
/// added. Residuals should be in length units (built-ins are). *index receives the index of
/// the first row (may be NULL).
DAL_API int dal_builder_add_constraint(dal_builder *b, const char *name,
                                       const dal_primitive *prim, int nparts, const int *parts,
                                       int ncoords, const int *coords, int nparam,
                                       const double *param, void *ctx, int *index);

/// Uniform gravity: acceleration vector g (d values, copied), force m_k g on every particle.
DAL_API int dal_builder_set_gravity(dal_builder *b, const double *g);

/// Linear spring between particles a and b: stiffness k (>= 0), rest length L (>= 0),
/// U = k/2 (|r_b - r_a| - L)^2.
DAL_API int dal_builder_add_spring(dal_builder *b, int pa, int pb, double k, double L);

/// Linear spring from particle p to an anchor x(t) (fn may be NULL: fixed anchor at x0,
/// d values copied). U = k/2 (|r_p - x(t)| - L)^2.
DAL_API int dal_builder_add_anchor_spring(dal_builder *b, int p, const double *x0,
                                          dal_path_fn *fn, void *ctx, double k, double L);

/// Linear damper between particles a and b: F_b = -c ((v_b - v_a) . e) e, e = unit vector
/// from a to b; F_a = -F_b. c >= 0.
DAL_API int dal_builder_add_damper(dal_builder *b, int pa, int pb, double c);

/// Linear damper from particle p to an anchor x(t) (fn NULL: fixed at x0), as above.
DAL_API int dal_builder_add_anchor_damper(dal_builder *b, int p, const double *x0,
                                          dal_path_fn *fn, void *ctx, double c);

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

#ifdef __cplusplus
}
#endif
#endif
