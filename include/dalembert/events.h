// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Events and Poincare sections: functions of the motion whose zero crossings are located on
/// the integrator's dense output, logged, and optionally stop the run.
///
/// An event is a function g of the motion; it occurs where g changes sign between two
/// accepted steps. dal_advance and dal_evolve check every event attached to the state
/// (dal_state_set_events) after each accepted step, locate each crossing on the method's dense
/// output to rounding (Anderson-Bjorck regula falsi on the interpolant: the bracket is closed
/// to a few ulps of t), record it in the event log (time, event, direction, q and qdot there)
/// and, for a terminal event, stop there: the state is then exactly at the crossing (on the
/// side after it), evaluated as after dal_forward, and the call returns DAL_EVENT (a positive
/// status, not an error; dal_state_errmsg names the event and the time). Calling again continues
/// from there without finding the same crossing again.
///
/// Accuracy: the crossing time is as accurate as the dense output, i.e. the method's tolerance
/// (tests/test_events.c: the pendulum's period from its zero crossings against
/// 4 sqrt(l/g) K(sin^2(theta0/2)) to 1e-12 relative at rtol 1e-12).
/// Limits: two crossings of the same g inside one step cancel and are not seen (a g that
/// oscillates faster than the steps: bound the step with opts.hmax); a g that only touches
/// zero is not a crossing. A g that is exactly 0 at a step's end is decided by the next step (a
/// sign change is a crossing located at the zero, a return to the old sign a touch), also when
/// a call ends there and the next call continues from it. A g that is exactly 0 at the start
/// of a call (a state just set) takes its sign from its first nonzero value without an event.
///
/// Poincare sections: a surface section is a non-terminal event with a direction (theta = 0
/// crossed upwards, say); its log is the section (dal_events_write_csv). A stroboscopic section
/// (the state once per period T of a drive) is dal_evolve with dt = T and a monitor, e.g.
/// dal_csv_monitor (docs/events.md: sections, their accuracy and cost;
/// examples/sicm_section.c draws both kinds).
#ifndef DAL_EVENTS_H
#define DAL_EVENTS_H

#include <stdio.h>

#include "dalembert/base.h"
#include "dalembert/state.h"
#include "dalembert/system.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Event function of the coordinates: g(t, q, qdot) with q, qdot of length n (the system's
/// coordinates). Cheap: no evaluation of the model is needed to call it. Return a finite
/// value; NaN or inf stops the run with DAL_E_CALLBACK naming the event.
typedef double dal_event_fn(double t, const double *q, const double *qdot, void *ctx);

/// Event function of the evaluated state: read anything dal_forward computes (reactions,
/// multipliers, accelerations, energies) through the state accessors. Costs one evaluation of
/// the model per call.
typedef double dal_event_state_fn(const dal_system *sys, const dal_state *st, void *ctx);

/// Which sign changes of g count.
typedef enum dal_event_direction {
  DAL_EVENT_BOTH = 0,     ///< either way
  DAL_EVENT_RISING = 1,   ///< from g < 0 to g > 0
  DAL_EVENT_FALLING = -1, ///< from g > 0 to g < 0
} dal_event_direction;

/// Definition of an event. Start from dal_default_event_def() and set exactly one of `g`,
/// `g_state` and `constraint`.
typedef struct dal_event_def {
  int cookie;                    ///< set by dal_default_event_def; do not touch
  const char *name;              ///< name in messages and in the log (copied), default "event"
  dal_event_fn *g;               ///< g(t, q, qdot), or NULL
  dal_event_state_fn *g_state;   ///< g of the evaluated state, or NULL
  const char *constraint;        ///< or: the name of a constraint; g is its multiplier lambda
                                 ///< (row `row`): a rod or rope goes slack, a bead leaves its
                                 ///< wire where it changes sign (dae.h for the sign convention)
  int row;                       ///< row of that constraint, 0 ... rows - 1 (default 0)
  void *ctx;                     ///< passed to g or g_state (borrowed)
  dal_event_direction direction; ///< default DAL_EVENT_BOTH
  int terminal;                  ///< nonzero: stop the run at the crossing (DAL_EVENT)
} dal_event_def;

/// A definition with the defaults above (no function set yet).
DAL_API dal_event_def dal_default_event_def(void);

/// A set of events and their log, for one system. Not thread-safe; one per state.
typedef struct dal_events dal_events;

/// Create an empty event set for `sys` (borrowed; must outlive the set). *out is NULL on
/// failure. Returns DAL_OK, DAL_E_ARG (NULL argument), DAL_E_NOMEM.
DAL_API int dal_events_create(const dal_system *sys, dal_events **out);

/// Free the set (NULL is fine). Detach it from any state first (dal_state_set_events).
DAL_API void dal_events_destroy(dal_events *ev);

/// Add an event; returns its index (0, 1, ...) or a negative status: DAL_E_ARG (a def not
/// made by dal_default_event_def, none or several of g / g_state / constraint, a direction
/// out of range, an unknown constraint name or row: the message names it and lists the
/// constraints), DAL_E_NOMEM. Message in dal_events_errmsg.
DAL_API int dal_events_add(dal_events *ev, const dal_event_def *def);

/// Message of the last failing call on the set ("" if none).
DAL_API const char *dal_events_errmsg(const dal_events *ev);

/// Number of events in the set.
DAL_API int dal_events_size(const dal_events *ev);

/// Name of event i (NULL if out of range).
DAL_API const char *dal_events_name(const dal_events *ev, int i);

/// Attach an event set to a state (borrowed: it must stay alive while attached), or detach
/// with NULL. dal_advance and dal_evolve then check its events. Returns DAL_E_STATE for a set
/// of another system.
DAL_API int dal_state_set_events(dal_state *st, dal_events *ev);

/// One entry of the event log.
typedef struct dal_event_record {
  double t;      ///< time of the crossing (s)
  int event;     ///< index of the event in the set
  int direction; ///< +1 rising, -1 falling
} dal_event_record;

/// Number of entries in the log.
DAL_API long dal_events_count(const dal_events *ev);

/// Entry i of the log (0 = oldest) into *rec, and the coordinates there into q and qdot
/// (length n each; either may be NULL). Returns DAL_E_ARG for i out of range.
DAL_API int dal_events_get(const dal_events *ev, long i, dal_event_record *rec, double *q,
                           double *qdot);

/// Empty the log (the events stay).
DAL_API void dal_events_clear(dal_events *ev);

/// Write the log as CSV: a header "t,event,direction,<q names>,<qdot names>" and one row per
/// entry; only entries of event `which` (or all for -1). With wrap_angles, q is written wrapped
/// to [-pi, pi). Returns DAL_E_ARG, DAL_E_IO (with the message in dal_events_errmsg).
DAL_API int dal_events_write_csv(const dal_events *ev, FILE *fp, int which, int wrap_angles);

#ifdef __cplusplus
}
#endif
#endif
