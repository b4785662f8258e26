// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Private interface of the structure-preserving fixed-step methods (variational, RATTLE).
//
// The integrator handle (integ.c) sees three calls: dal__symplectic_method, dal__symplectic_resolve
// and dal__symplectic_create (a dal_ode_integ constructor like dal__rk4_create). Inside, one
// fixed-grid driver with symmetric compositions (symplectic.c) runs a base method
// (variational.c, rattle.c) on the method's own state x through dal_symp_base.
#ifndef DAL_INTEGRATE_SYMPLECTIC_H
#define DAL_INTEGRATE_SYMPLECTIC_H

#include "families.h"

/// 1 for DAL_METHOD_VARIATIONAL*, DAL_METHOD_RATTLE*, else 0.
int dal__symplectic_method(dal_method m);

/// The formulation of a symplectic method: the ODE problem whose y = (q, qdot) the state
/// exchanges with the integrator (minimal for the variational method, index-1 layout (q, v)
/// for RATTLE). Checks that the system suits the method (DAL_E_UNSUPPORTED with a message
/// naming the culprit and the remedy otherwise).
int dal__symplectic_resolve(const dal_system *sys, dal_state *st, const dal_solve_opts *o,
                            dal_method m, const dal_ode_problem **prob);

/// Constructor of the ODE integrator for a symplectic method: fills ig->impl and ig->ops.
/// May move the state onto the constraints (RATTLE) and refreshes ig->y then.
int dal__symplectic_create(dal_ode_integ *ig);

/// A base (second-order, symmetric) one-step method on its own state x (nx values), e.g.
/// x = (q, p). All calls return 0 or a negative status with the state's message set.
typedef struct dal_symp_base {
  int nx;    ///< size of x
  void *mem; ///< the method's memory
  /// x from y = (q, qdot) at time t (start of a run)
  int (*from_y)(dal_ode_integ *ig, void *mem, double t, const double *y, double *x);
  /// y = (q, qdot) from x at time t (outputs, failures)
  int (*to_y)(dal_ode_integ *ig, void *mem, double t, const double *x, double *y);
  /// one step of size h (either sign) from (t, x), in place; c (nx) carries the
  /// compensation of the compensated (Kahan) summation of x
  int (*step)(dal_ode_integ *ig, void *mem, double t, double h, double *x, double *c);
  /// what step cached about its last end point no longer belongs to the next start point
  void (*invalidate)(void *mem);
  void (*free)(void *mem);
} dal_symp_base;

/// base methods: the midpoint variational integrator (variational.c) and RATTLE
/// (rattle.c); fill *b, allocate everything a step needs
int dal__variational_base(dal_ode_integ *ig, dal_symp_base *b);
int dal__rattle_base(dal_ode_integ *ig, dal_symp_base *b);

/// check that the system suits the method (no allocation): variational needs m = 0; RATTLE
/// Cartesian particles with masses on every coordinate and potential forces only
int dal__variational_check(const dal_system *sys, dal_state *st, const char *name);
int dal__rattle_check(const dal_system *sys, dal_state *st, const char *name);

#endif
