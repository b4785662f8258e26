// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The standard scenes of the tests and benchmarks, built once from defs with a few knobs.
//
// A test reads best as: get the standard scene, change one knob, check one property against
// its independent reference. Every scene is planar (d = 2, gravity (0, -g)) unless it says 3D
// (gravity (0, 0, -g)); names are fixed so that messages and parameter strings can rely on
// them: one particle "bob" (the bead: "bead"), two "upper" and "lower", a chain "p0", "p1",
// ...; angles "theta" ("theta1", "theta2"; a chain "th0", "th1", ...), Cartesian coordinates
// "x", "y" ("x1", "y1", "x2", "y2"; a chain "x0", "y0", ...); rods "rod" ("rod1", "rod2"; a
// chain "rod0", ...). Examples do not use this library: they stay as a user writes them.
#ifndef DAL_TESTS_SCENES_H
#define DAL_TESTS_SCENES_H

#include "dalembert/dalembert.h"

/// Gravity of the standard scenes unless a test changes it (m/s^2).
#define SCN_G 9.81

/// The knobs of the standard scenes. Start from scn_default() and change what the test needs.
typedef struct scn_knobs {
  double g;         ///< gravity magnitude (m/s^2), default SCN_G
  double m, m2;     ///< masses of the first and the second particle (every chain
                    ///< particle: m), default 1
  double l, l2;     ///< rod lengths (first, second; every chain link: l), default 1
  double ax, ay, w; ///< pendulum pivot drive (ax cos wt, ay cos wt) (dal_map_pendulum),
  double ph;        ///< phase of that drive (rad), default 0
  double x0, y0;    ///< the (first) pivot or rod anchor, default the origin
  double z0;        ///< 3D scenes (spherical pendulum): the pivot's z, default 0
  const dal_moving_point *pivot; ///< Cartesian scenes: the moving anchor of the first rod,
                                 ///< default NULL (fixed at the origin)
  double R, spin;                ///< bead: ring radius (default 1) and turning rate (default 0)
  double phi0;                   ///< bead: the ring's plane angle at t = 0 (rad), default 0
  double k;                      ///< oscillator, hanging spring: stiffness, default 1
  double c;                      ///< hanging spring: damping coefficient, default 0
  int N;                         ///< chain: number of particles, default 4
  dal_dynamics dynamics;         ///< the dynamics route, default DAL_DYNAMICS_AUTO
} scn_knobs;

/// The defaults listed in scn_knobs.
scn_knobs scn_default(void);
/// The defaults without gravity (g = 0).
scn_knobs scn_weightless(void);

/// Compile b (when rc is 0) and destroy it; on failure print the builder's message to stderr
/// and return NULL. For scenes a test builds itself on top of scn_* builders.
dal_system *scn_finish(dal_builder *b, int rc);

// Pieces for scenes a test builds itself (each returns a library status, 0 on success; NULL
// knobs: the defaults).

/// A builder of dimension d (2 or 3) with gravity -k->g along the last axis (none when k->g is
/// 0) and the dynamics route k->dynamics.
int scn_builder(const scn_knobs *k, int d, dal_builder **b);
/// Particle `name` (mass m) in its own Cartesian coordinates named x and y
/// (dal_map_cartesian2); its index in *p.
int scn_add_xy(dal_builder *b, const char *name, double m, const char *x, const char *y, int *p);
/// Particle `name` (mass m) in its own 3D Cartesian coordinates "x", "y", "z"
/// (dal_map_cartesian3); its index in *p.
int scn_add_xyz(dal_builder *b, const char *name, double m, int *p);
/// A rod `name` of length l: from particle a to the anchor (k->x0, k->y0), moving by k->pivot
/// when set (dal_con_anchor2), when b2 < 0; else between particles a and b2 (dal_con_distance2).
int scn_add_rod(dal_builder *b, const char *name, int a, int b2, double l, const scn_knobs *k);
/// Particle `name` (mass m) in the angle coordinate `coord`: on the pendulum map about the pivot
/// (k->x0, k->y0) driven by (k->ax, k->ay, k->w, k->ph) when parent < 0, else hanging from
/// particle `parent` on length l (dal_map_hanging); its index in *p.
int scn_add_swing(dal_builder *b, const scn_knobs *k, const char *name, double m, int parent,
                  double l, const char *coord, int *p);
/// Place the particle p already added on the coordinate `coord` as scn_add_swing does: on the
/// pendulum map (k's pivot and drive) when parent < 0, else hanging from parent on length l.
int scn_place_swing(dal_builder *b, const scn_knobs *k, int p, int parent, double l, int coord);

// Every scene takes its knobs by pointer, NULL for the defaults, and returns the compiled
// system (NULL after printing the builder's message when it cannot be built).

/// A pendulum in its angle theta from the downward vertical: "bob" (m) on a rod l about the
/// pivot (x0, y0), driven by (ax, ay, w, ph).
dal_system *scn_pendulum(const scn_knobs *k);
/// The same circle in Cartesian coordinates (x, y): "bob" on the rod "rod" (dal_con_anchor2,
/// length l) to (x0, y0), plus k->pivot's motion when set.
dal_system *scn_cart_pendulum(const scn_knobs *k);
/// The double pendulum in its angles theta1, theta2: "upper" (m) on l about the origin (driven
/// as scn_pendulum), "lower" (m2) hanging from it on l2.
dal_system *scn_double_pendulum(const scn_knobs *k);
/// The double pendulum in Cartesian coordinates (x1, y1, x2, y2): "rod1" (anchor, l; to
/// k->pivot when set) and "rod2" (distance, l2).
dal_system *scn_cart_double_pendulum(const scn_knobs *k);
/// Likharev's bead (m) on a ring of radius R turning at `spin` about the vertical (3D, theta).
dal_system *scn_bead(const scn_knobs *k);
/// The same bead in Cartesian coordinates (x, y, z) on the turning circle "ring"
/// (dal_con_turning_circle, radius R, rate spin; two constraint rows).
dal_system *scn_cart_bead(const scn_knobs *k);
/// The spherical pendulum's particle "bob" (mass k->m) in (theta, phi) on dal_map_spherical of
/// length k->l about (k->x0, k->y0, k->z0); its index in *p.
int scn_add_spherical(dal_builder *b, const scn_knobs *k, int *p);
/// The spherical pendulum (3D): scn_add_spherical under gravity.
dal_system *scn_spherical(const scn_knobs *k);
/// The same in Cartesian coordinates (x, y, z): "bob" on the rod "rod" (dal_con_anchor3, length
/// l) to (x0, y0, z0).
dal_system *scn_cart_spherical(const scn_knobs *k);
/// An anisotropic trap turning at rate w: U = (k1 x'^2 + k2 y'^2) / 2 in the components (x', y')
/// of r in the turning frame.
typedef struct scn_trap {
  double w, k1, k2; ///< rate (rad/s) and stiffnesses
} scn_trap;
/// The ion "ion" (mass m) in the rotating frame's coordinates (x, y) (r = Rot(w t) (x, y), a user
/// primitive "rotating" with param (w)) in the trap tr (borrowed; must outlive the system), no
/// gravity.
dal_system *scn_rotating_trap(const scn_trap *tr, double m);
/// The 2D isotropic oscillator: "bob" (m) in Cartesian (x, y) on a zero-length spring of
/// stiffness k to the origin, no gravity.
dal_system *scn_oscillator(const scn_knobs *k);
/// A mass hanging on a spring: "bob" (m) in Cartesian (x, y) on a spring of stiffness k and
/// rest length l to the origin, with a damper c to the origin (none when c = 0), under gravity.
dal_system *scn_hanging_spring(const scn_knobs *k);
/// A chain of N pendulums in their angles th0 ... : "p0" on l about the origin, each next
/// hanging from its parent on l.
dal_system *scn_chain(const scn_knobs *k);
/// The chain in Cartesian coordinates: "rod0" (anchor, l) and "rod<i>" (distance, l).
dal_system *scn_cart_chain(const scn_knobs *k);
/// The four-bar linkage: ground pivots A = (0, 0) and D = (3, 0); crank AB = 1, coupler
/// BC = 3.5, rocker CD = 2, massless links, masses 1 at "B" and 2 at "C", the crank at th1 (rad
/// from the downward vertical) turning at w1 (rad/s), the coupler's rate from the closure.
/// Tree (cart = 0): B on the pendulum map about A ("crank"), C hanging from B ("coupler"),
/// the loop row "CD"; Cartesian (cart = 1): (xB, yB, xC, yC) with the rods "AB", "BC", "CD".
/// The consistent initial state in q, qd: 2 entries each (tree) or 4 (Cartesian).
dal_system *scn_fourbar(const scn_knobs *k, int cart, double th1, double w1, double *q, double *qd);
/// A chain of k->N unit links and N - 1 unit masses "p0" ... between A = (0, 0) and
/// B = (N sin 60deg, 0), released from rest as a V. Tree (cart = 0): "p0" on the pendulum map
/// about A, each next hanging ("th0", ...), the last rod "held" to B as a loop row; Cartesian
/// (cart = 1): ("x0", "y0", ...) with N unnamed rods but the last, "held". The initial state
/// in q, qd: N - 1 entries each (tree) or 2 (N - 1) (Cartesian).
dal_system *scn_held_chain(const scn_knobs *k, int cart, double *q, double *qd);
/// A closed loop: "p" (mass m) in unnamed Cartesian coordinates on the rod "rod" of length l
/// from (x0, y0), "s" (mass m2) on the circle "ring" of radius R about the origin
/// (dal_con_circle2), tied by the rod "link" of length `link`: 4 coordinates, 2 + 1 + 1
/// constraint rows.
dal_system *scn_closed_loop(const scn_knobs *k, double link);

// References shared by the tests and the benchmarks.

/// RK4 with the fixed step H (the last step shortened to end at T) on the unit oscillator
/// q'' = -q in the plane, y = (q1, q2, v1, v2) from y0 (4) to out (4): the classical recurrence
/// in long double with a compensated update (naive = 0), or in double with the uncompensated
/// update y + h/6 (k1 + 2 k2 + 2 k3 + k4) (naive = 1). The round-off reference of the library's
/// RK4.
void scn_rk4_replica(const double *y0, double T, double H, int naive, double *out);

/// Solver options from dal_default_solve_opts() with the formulation f, the method m and
/// rtol = atol = tol.
dal_solve_opts scn_opts(dal_formulation f, dal_method m, double tol);

/// Monitors for dal_evolve: add q[0] (scn_sum_q0) or the total energy E (scn_sum_energy, one
/// evaluation per output) at every output to *(double *)ctx; the second returns -1 when the
/// energies fail.
int scn_sum_q0(const dal_system *sys, const dal_state *st, void *ctx);
int scn_sum_energy(const dal_system *sys, const dal_state *st, void *ctx);

#endif
