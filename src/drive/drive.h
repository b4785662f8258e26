// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The face of drive/: the events (events.c) and the stored trajectory (trajectory.c) as the
// integration driver (driver.c) runs them, each served by the integrator handle (dal_integ:
// the step just taken and its dense output).
#ifndef DAL_DRIVE_DRIVE_H
#define DAL_DRIVE_DRIVE_H

#include "dalembert/events.h"
#include "integrate/integrate.h"

/// a crossing found in the step just taken
typedef struct dal__pending {
  double t;      ///< located time (the side after the crossing)
  int event;     ///< index in the set
  int dir;       ///< +1 rising, -1 falling
  double g0, g1; ///< g before the step and at its end
} dal__pending;

/// signs of every g at the state's current (t, q, qdot) (a run starts); 0 or a status
int dal__events_begin(dal_events *ev, dal_state *st);
/// the crossings of the step [a, b] just taken by it (its window), located on its dense output
/// (it->ops->place moves it->st) and in time order; the signs move on to b. 0 or a negative
/// status (a g that is not finite: named)
int dal__events_scan(dal_events *ev, dal_integ *it);
/// the crossings found by the last scan
int dal__events_npending(const dal_events *ev);
const dal__pending *dal__events_pending(const dal_events *ev, int k);
/// event i stops the run
int dal__events_terminal(const dal_events *ev, int i);
/// name of event i
const char *dal__events_item_name(const dal_events *ev, int i);
/// log event i (direction dir) at the state's (t, q, qdot)
int dal__events_record(dal_events *ev, const dal_state *st, int i, int dir);
/// a run holds the set (on = 1) or lets it go (0): dal_events_add refuses while it is held
/// (an event function adding an event would move the items under the scan)
void dal__events_hold(dal_events *ev, int on);

/// attaching an object of system `owner` (NULL: detaching) to a state (events, trajectory):
/// DAL_E_ARG for a NULL st, DAL_E_STATE for a running state or another system's object (with
/// a message naming `what` and `thing`), else 0 (trajectory.c)
int dal__attach_check(dal_state *st, const dal_system *owner, const char *what, const char *thing);
/// the stored dense trajectory (trajectory.c): a run recording into tr starts at the state's
/// time, which must be where tr ends (or tr is empty): 0 or DAL_E_ARG with a message in st
int dal__traj_begin(dal_trajectory *tr, dal_state *st);
/// store the step [a, b] just taken by it (its window) as it->traj_pieces records of equal
/// length, each sampled from its dense output at its nodes (it->ops->place), except b, the
/// accepted step itself (it->ops->place_end); it->st is moved. 0 or DAL_E_NOMEM (message in
/// it->st)
int dal__traj_step(dal_trajectory *tr, dal_integ *it);
/// the run that dal__traj_begin let start ended with the state at time t: the record is valid
/// up to t (a run stopped inside its last step by an event or a monitor); nothing otherwise
void dal__traj_end(dal_trajectory *tr, double t);

/// column i of a selection is a coordinate q (columns.c; the CSV writer wraps those angles)
int dal__columns_is_q(const struct dal_columns *cols, int i);

#endif
