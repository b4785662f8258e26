// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Scene files: a whole model and its run as text, read into a system, written back, run.
///
/// One element per line; `#` starts a comment (units go there); formulas are the rest of a line
/// (docs/expressions.md has the grammar and why it is not YAML):
///
///   dim 2                                   # spatial dimension (2 or 3; 0: a Lagrangian only)
///   param g = 9.8                           # named parameters, usable in every formula
///   param omega = 2*sqrt(g)                 # a formula of the parameters above
///   coord theta q=1 v=0                     # a coordinate with its initial value and rate
///   particle bob mass=m                     # mass: a formula of the parameters
///   place bob = l*sin(theta); a*cos(omega*t) - l*cos(theta)     # r(q, t) by formulas
///   place bob pendulum theta l=1 ay=a w=omega                    # or by a built-in primitive
///   place b parent=a = x_a + l*sin(th2); y_a - l*cos(th2)       # parent's position x_a, y_a
///   constraint rod parts=a,b = sqrt((x_b - x_a)^2 + (y_b - y_a)^2) - l
///   constraint rod distance2 parts=a,b L=1  # a built-in constraint
///   spring a b k=10 L=1                     # or: spring a anchor=0,1 k=10 L=0
///   damper a b c=0.1                        # or: damper a anchor=0,0 c=0.1
///   force theta = -c*thetadot + F*cos(w*t)  # a generalized force Q(t, q, qdot) on a coordinate
///   gravity 0 -g
///   potential = 1/2*k*theta^2               # a further U(q, t)
///   lagrangian = 1/2*m*xdot^2 - 1/2*k*x^2   # instead of particles (dim 0)
///   run method=bs rtol=1e-12 t1=100 dt=0.01 # method, tolerances, end time, output step
///   event bottom falling terminal = theta   # g(t, q, qdot): located crossings; terminal stops
///   section up rising = sin(theta)          # a surface section: the crossings are its points
///   section strobe period=2*pi/omega        # a stroboscopic section: the state every period
///
/// Event and section formulas may use t, the coordinates, their rates (theta -> thetadot) and
/// the parameters. Formulas may use the coordinates, t, the parameters and (in `place ... parent=`,
/// and in constraints) the positions x_<p>, y_<p>, z_<p> of the particles named. Built-in primitive
/// parameters are given by their names (primitives.h) as formulas; every value after key= is a
/// formula of the parameters and may hold spaces (q=0.5 * a). Lists and names have no length
/// limit; a name given twice is refused on the later line, naming the earlier.
/// Messages name the file and line: "pend.scene:7: place bob: formula 1 'l*sin(thet)', column 7:
/// unknown symbol 'thet' ...".
#ifndef DAL_SCENE_H
#define DAL_SCENE_H

#include <stddef.h>
#include <stdio.h>

#include "dalembert/base.h"
#include "dalembert/codegen.h"
#include "dalembert/events.h"
#include "dalembert/expr.h"
#include "dalembert/solve.h"
#include "dalembert/state.h"
#include "dalembert/system.h"

#ifdef __cplusplus
extern "C" {
#endif

/// A scene read from text: its elements, the compiled system and the run (opaque).
typedef struct dal_scene dal_scene;

/// Read a scene from `text`; `name` (nullable) names it in messages. On failure *out is NULL
/// and msg names the line and the culprit. Returns DAL_OK, DAL_E_ARG (syntax, unknown names,
/// a model the builder refuses: its status), DAL_E_NONFINITE, DAL_E_NOMEM.
DAL_API int dal_scene_parse(const char *text, const char *name, dal_scene **out, char *msg,
                            size_t msglen);

/// Read a scene file (dal_scene_parse of its contents; DAL_E_IO when it cannot be read).
DAL_API int dal_scene_read(const char *path, dal_scene **out, char *msg, size_t msglen);

/// Print the scene-file grammar (one line per element, the table the reader uses) to fp.
/// Returns DAL_OK, DAL_E_ARG (fp NULL), DAL_E_IO.
DAL_API int dal_scene_help(FILE *fp);

/// Free a scene and everything it built (NULL is a no-op). No state of its system may remain.
DAL_API void dal_scene_destroy(dal_scene *sc);

/// Write the scene back as text (comments dropped, numbers with %.17g, formulas as read): read
/// again it gives the same system and run, bit for bit. Returns DAL_OK, DAL_E_ARG, DAL_E_IO.
DAL_API int dal_scene_write(const dal_scene *sc, FILE *fp);

/// Override parameter `name` (a `param` line's value) and rebuild the system. States of the
/// old system must be destroyed first. Returns DAL_OK, DAL_E_ARG (unknown name; msg says),
/// DAL_E_NONFINITE, or the rebuild's status (the scene then keeps the old value and system).
DAL_API int dal_scene_set_param(dal_scene *sc, const char *name, double value, char *msg,
                                size_t msglen);

/// The compiled system (borrowed from sc).
DAL_API const dal_system *dal_scene_system(const dal_scene *sc);

/// The run's options (method, rtol, atol; borrowed from sc) and times t0, t1, dt (nullable).
DAL_API const dal_solve_opts *dal_scene_opts(const dal_scene *sc, double *t0, double *t1,
                                             double *dt);

/// A new state of the scene's system at t0 with the coordinates' initial values (the caller
/// destroys it). Returns DAL_OK or the status of dal_state_create / dal_state_set.
DAL_API int dal_scene_state(const dal_scene *sc, dal_state **out);

/// Run the scene: from its initial state to t1 with output every dt, written as CSV to `csv`
/// (nullable: no output), its events attached (a terminal one stops the run: DAL_EVENT).
/// `st` (nullable) receives the final state (else it is destroyed). Returns the status of
/// dal_evolve (its message in msg).
DAL_API int dal_scene_run(const dal_scene *sc, FILE *csv, dal_state **st, char *msg, size_t msglen);

/// A new event set (events.h) of the scene's `event` and surface `section` lines, in the
/// order of the file (event i is the i-th such line; the caller destroys it after detaching
/// it). Returns DAL_OK, DAL_E_ARG (sc or out NULL), DAL_E_NOMEM.
DAL_API int dal_scene_events(const dal_scene *sc, dal_events **out);

/// Whether event i of dal_scene_events is a surface `section` line (1) or an `event` line
/// (0); -1 when i is out of range.
DAL_API int dal_scene_event_is_section(const dal_scene *sc, int i);

/// The period of the scene's stroboscopic section (`section <name> period=T`, time units),
/// 0 when it has none.
DAL_API double dal_scene_strobe(const dal_scene *sc);

/// dal_scene_run with an event set `ev` from dal_scene_events (nullable: the scene's events
/// are still honoured, their log dropped), attached during the run: afterwards its log holds
/// the crossings. A terminal event ends the run early with DAL_EVENT (positive, not an error).
DAL_API int dal_scene_run_events(const dal_scene *sc, FILE *csv, dal_events *ev, dal_state **st,
                                 char *msg, size_t msglen);

/// Print the scene's equations: r_k(q, t) of every particle, T, U, L, the mass matrix, the
/// forces and the accelerations (one coordinate: the state derivative; two or three: M^-1 F by
/// Cramer's rule; more: M qddot = F), in format fmt. Dampers add Rayleigh's function D (along
/// each damper's axis) and their forces Q = -dD/dqdot (M qddot = F + Q); constraints by formulas
/// add their rows phi(q, t) and G = dphi/dq (M qddot = F + G' lambda, phi = 0; the
/// accelerations are then not solved). Particles placed by the built-in maps with formulas
/// (pendulum, hanging, ring, spherical, sphere, cartesian, fixed) are shown by those formulas,
/// built-in constraints by the formulas of their rows (all but on_line3 and the curves), force
/// lines join Q. Returns DAL_OK, DAL_E_UNSUPPORTED (a placement or built-in constraint without
/// formulas: msg names its line), DAL_E_TOO_LARGE (an equation past dal_expr_print's bounds:
/// msg says so), DAL_E_IO, DAL_E_NOMEM.
DAL_API int dal_scene_show(const dal_scene *sc, FILE *fp, dal_expr_format fmt, char *msg,
                           size_t msglen);

/// Native code for every formula of the scene (dal_codegen_attach over its expressions),
/// attached again whenever the scene is rebuilt (dal_scene_set_param): results bit-identical to
/// the bytecode, faster. Unless o->eom is 0, also the scene's compiled equations of motion
/// (dal_codegen_attach_eom: a minimal-coordinate scene placed by formulas; results within a
/// stated rounding bound of the general path); where they are out of reach the call still
/// returns DAL_OK and msg holds a note saying why. o NULL: default options. On failure the
/// bytecode keeps running and msg says why (DAL_E_UNSUPPORTED: no compiler; DAL_E_IO: the cache
/// refused or unwritable).
DAL_API int dal_scene_native(dal_scene *sc, const dal_codegen_opts *o, char *msg, size_t msglen);

/// The number of expressions the scene made (its formulas, compiled; the order of its lines;
/// a `lagrangian` line makes two: L, then its parts dL/dqdot and dL/dq the accelerations read).
DAL_API int dal_scene_nexprs(const dal_scene *sc);

/// Expression i (0 <= i < dal_scene_nexprs) of the scene, borrowed (valid until the scene is
/// destroyed or rebuilt by dal_scene_set_param); NULL when i is out of range. Entry i of the
/// table dal_scene_write_c writes is this expression.
DAL_API const dal_expr *dal_scene_expr(const dal_scene *sc, int i);

/// The scene's formulas as a standalone C source (dal_codegen_write with `prefix`): one jet
/// function per expression the scene made, in the order of its lines, each named in the
/// source's table by the element that made it. Returns the codes of dal_codegen_write.
DAL_API int dal_scene_write_c(const dal_scene *sc, const char *prefix, FILE *fp);

#ifdef __cplusplus
}
#endif
#endif
