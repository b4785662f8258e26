// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Outputs people look at: named columns of a state (positions, forces, work) and the
/// self-contained HTML viewer of a motion.
///
/// Column names (the selection and the CSV header use the same names):
///
/// | name            | what                                                           |
/// |-----------------|----------------------------------------------------------------|
/// | `t`             | time                                                           |
/// | `q:C`           | coordinate C (header: `C`)                                     |
/// | `qdot:C`        | its rate (header: `C_dot`)                                     |
/// | `x:P` `y:P` `z:P` | position of particle P (`z` in 3-D scenes only)             |
/// | `vx:P` `vy:P` `vz:P` | its velocity                                             |
/// | `Rx:P` `Ry:P` `Rz:P` | the reaction N_P = m a_P - F_P on it (dal_state_reactions) |
/// | `Jx:P` `Jy:P` `Jz:P` | the force of its own placement's joint (dal_joint_forces) |
/// | `lambda:K`      | the multiplier of constraint K (`lambda:K.i` for row i of a    |
/// |                 | constraint of several rows)                                    |
/// | `T` `U` `E` `h` | kinetic, potential, total energy and the Jacobi integral       |
/// |                 | (dal_energies; h is NaN where it does not exist)               |
/// | `P`             | the power dE/dt of non-conservative forces, drives and moving  |
/// |                 | constraints                                                    |
/// | `W`             | the work done by them since dal_state_set (needs opts.work)    |
///
/// A selection is a comma-separated list of these names; the part after `:` may be a glob
/// (`*` any run, `?` one character): `x:*,y:*,lambda:*`. The default selection (NULL or "")
/// is `t,q:*,qdot:*,E,h`, the columns dal_csv_monitor has always written.
#ifndef DAL_OUTPUT_H
#define DAL_OUTPUT_H

#include <stddef.h>
#include <stdio.h>

#include "dalembert/base.h"
#include "dalembert/events.h"
#include "dalembert/solve.h"
#include "dalembert/state.h"
#include "dalembert/system.h"

#ifdef __cplusplus
extern "C" {
#endif

/// A selection of named columns for one system (immutable once made; may be shared).
typedef struct dal_columns dal_columns;

/// Make the selection `spec` (nullable: the default `t,q:*,qdot:*,E,h`) of `sys` (borrowed;
/// must outlive it). Every item must name at least one column: an unknown name, a glob that
/// matches nothing, `z:` in a 2-D scene or `Jx:` in a system without placements is DAL_E_ARG
/// with msg (nullable) naming the item and what exists. *out is NULL on failure. Returns
/// DAL_OK, DAL_E_ARG, DAL_E_NOMEM.
DAL_API int dal_columns_create(const dal_system *sys, const char *spec, dal_columns **out,
                               char *msg, size_t msglen);

/// Free a selection (NULL is a no-op).
DAL_API void dal_columns_destroy(dal_columns *cols);

/// Number of columns selected (0 for NULL).
DAL_API int dal_columns_count(const dal_columns *cols);

/// Header name of column i (borrowed from cols), NULL when i is out of range.
DAL_API const char *dal_columns_name(const dal_columns *cols, int i);

/// Whether the selection reads the work W (then run with opts.work set, or W stays 0).
DAL_API int dal_columns_need_work(const dal_columns *cols);

/// Evaluate the columns at the state into row (dal_columns_count doubles, caller-owned). The
/// state must be evaluated at its (t, q, qdot) (after dal_forward, or inside a monitor of
/// dal_evolve, where what is read is evaluated on demand). Returns DAL_OK, DAL_E_ARG (a NULL
/// argument), DAL_E_STATE (another system's state, or one not evaluated; message in the
/// state), or the status of the evaluation that failed.
DAL_API int dal_columns_eval(const dal_system *sys, const dal_state *st, const dal_columns *cols,
                             double *row);

/// Write the header line (names separated by commas, then a newline). Returns DAL_OK,
/// DAL_E_ARG, DAL_E_IO.
DAL_API int dal_columns_write_header(const dal_columns *cols, FILE *fp);

/// Options of dal_view_write; start from dal_default_view_opts().
typedef struct dal_view_opts {
  double t1;                   ///< end time of the motion (seconds; from the state's time)
  double fps;                  ///< frames per second of motion time (default 60)
  const char *title;           ///< page title (nullable: "dalembert")
  const dal_solve_opts *solve; ///< integration options (nullable: dal_default_solve_opts())
  double trail;                ///< trail length in seconds (default 1; 0: none)
  double strobe;               ///< period of a stroboscopic section (seconds; 0: none): the state
                               ///< every strobe from the start is a section point of the phase plot
  const int *sections;         ///< nullable: per event of the page's event set (dal_events_size
                               ///< flags), nonzero when its crossings are section points; NULL:
                               ///< every event's are (a scene's: dal_scene_event_is_section)
} dal_view_opts;

/// The default view options: t1 = 10, fps = 60, trail = 1.
DAL_API dal_view_opts dal_default_view_opts(void);

/// Write one self-contained HTML page to fp playing the motion of `st` (moved to the end time:
/// the run uses dal_evolve_at at the frame times t0 + k / fps, so frames come from the dense
/// output, never from raw steps). The page draws particles (radius growing with the cube root of
/// the mass), the links of placements (parent to child, and the pivot of a built-in pendulum,
/// hanging or spherical map), distance and anchor constraints, springs as coils, dampers, the
/// curves and surfaces of the built-in constraints and maps in their frame at each time
/// (circles, lines, the turning circle and line, spheres, planes), and trails; it plays, pauses,
/// steps, scrubs, and opens paused at `FILE.html#t=1.25`; 3-D scenes rotate by drag and zoom by
/// wheel; beside it q(t), a phase portrait, E - E(0), h - h(0) where the Jacobi integral is an
/// invariant unlike E, the multipliers, and the section points: the strobe's and the crossings
/// of `ev` (nullable: an event set attached for the run, its crossings read after it; opts
/// sections says which of its events are sections). Positions and plots are stored within
/// 1/131068 of each coordinate's range over the run (docs/guide.md, "Seeing the motion"). The
/// page needs no network: no URL outside itself. At most 200000 frames. Returns DAL_OK, DAL_E_ARG
/// (NULL sys, st or fp; t1 not after the state's time; fps <= 0; too many frames), DAL_E_NOMEM,
/// DAL_E_IO, or the run's status (message in the state). On failure the page is not complete:
/// the caller must not keep it (dalembert view writes to a temporary file and renames it).
DAL_API int dal_view_write(const dal_system *sys, dal_state *st, const dal_view_opts *opts,
                           dal_events *ev, FILE *fp);

/// Write an SVG picture to fp: the configurations of `st`'s motion at times[0 .. n) (1 <= n <=
/// 1000, non-decreasing, not before the state's time; seconds) drawn over each other, the later
/// ones more opaque (the textbook figure of a swinging pendulum): particles sized by mass, the
/// links, pivots and anchors the viewer draws (springs dashed finely, dampers coarsely), and the
/// curves of circles at the last time. The state runs to times[n - 1] (dal_evolve_at with
/// `solve`, nullable: the defaults). Returns DAL_OK, DAL_E_ARG (NULL sys, st, fp or times; n out
/// of range; a system without particles), DAL_E_NOMEM, DAL_E_IO, or the run's status, which
/// refuses a bad list (message in the state); on failure the picture is not complete.
DAL_API int dal_picture_write(const dal_system *sys, dal_state *st, const double *times, size_t n,
                              const dal_solve_opts *solve, FILE *fp);

#ifdef __cplusplus
}
#endif
#endif
