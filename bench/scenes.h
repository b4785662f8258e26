// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The benchmark's registry of scenes: how each is built through the public API (minimal and
// redundant coordinates), its hand-written twin, and its independent reference.
#ifndef DAL_BENCH_SCENES_H
#define DAL_BENCH_SCENES_H

#include <stddef.h>

#include "dalembert/dalembert.h"
#include "hand.h"

/// Kinds of scenes.
typedef enum scene_kind {
  SC_HO2D,
  SC_PENDULUM,
  SC_RING,
  SC_DRIVEN,
  SC_DOUBLE,
  SC_CHAIN
} scene_kind;

/// One benchmark scene: a kind, its size and horizon.
typedef struct bench_scene {
  char name[32];   ///< CSV name: ho2d, pendulum, ring, driven, double, chain<N>
  scene_kind kind; ///< which scene
  int N;           ///< links of a chain (1 for a pendulum, 2 for the double pendulum)
  double t1;       ///< final time (s)
} bench_scene;

/// Fill a scene of the given kind (N used by SC_CHAIN; t1 <= 0 picks the default horizon).
void scene_init(bench_scene *sc, scene_kind kind, int N, double t1);

/// Number of compared particles and spatial dimension of a scene.
int scene_np(const bench_scene *sc);
int scene_dim(const bench_scene *sc);

/// A scene built through the library: system, one state, the initial (q, qdot).
/// The first scene_np() particles of the system are the compared ones (same order as the
/// reference); fixed auxiliary particles, if any, come after them.
typedef struct bench_model {
  dal_system *sys;
  dal_state *st;
  int n;
  double *q0, *qd0;
} bench_model;

/// Build the scene in minimal (redundant = 0) or redundant Cartesian coordinates with
/// constraints (redundant = 1). Returns DAL_OK, a library status (message in err), or
/// DAL_E_UNSUPPORTED when the scene has no such form.
int scene_model(const bench_scene *sc, int redundant, bench_model *m, char *err, size_t len);
/// The same with a chosen dynamics route (dal_builder_set_dynamics).
int scene_model_route(const bench_scene *sc, int redundant, dal_dynamics how, bench_model *m,
                      char *err, size_t len);
void scene_model_free(bench_model *m);

/// Set the model's state to its initial value (t = 0).
int scene_model_reset(bench_model *m);

/// The scene's reference particle positions at t1 (np x dim), and how it was obtained:
/// `agree` is the max-norm difference between the two independent computations when the
/// reference is numerical (0 for a closed form); `how` describes it.
int scene_reference(const bench_scene *sc, double *r, double *agree, char *how, size_t len);

/// A cheaper reference for large chains: the O(N) hand-written form by Fehlberg 7(8) at
/// rtol 1e-12 (no second computation; for errors of 1e-9 and above).
int scene_reference_fast(const bench_scene *sc, double *r);

/// True when the scene has a hand-written minimal-coordinate twin (pendulum, double, chain).
int scene_has_hand(const bench_scene *sc);

/// The hand-written twin: a chain and its initial state y0 (2N), allocated here.
hand_chain *scene_hand_chain(const bench_scene *sc, double *y0);

/// Closed loops on a tree: the four-bar linkage and a chain held at both ends.
enum { LOOP_FOURBAR = 0, LOOP_HELD = 1 };

/// Compared particles of a loop scene (the first ones of either form): 2 for the four-bar,
/// NL - 1 for the held chain of NL links.
int loop_np(int which, int NL);

/// Build a loop scene as a tree of placements plus loop-closure rows (cart = 0; route `how`)
/// or in Cartesian coordinates with every link a constraint (cart = 1), with its consistent
/// initial state. Returns DAL_OK or a library status (message in err).
int loop_model(int which, int NL, int cart, dal_dynamics how, bench_model *m, char *err,
               size_t len);

#endif
