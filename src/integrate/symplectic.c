// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Fixed-grid driver of the symplectic methods: symmetric compositions, off-grid outputs.
//
// A symmetric second-order base method Phi_h (variational midpoint, RATTLE) is composed as
// Phi_{g_s h} o ... o Phi_{g_1 h} with symmetric coefficients (Hairer, Lubich, Wanner,
// Geometric Numerical Integration, 2nd ed., Springer 2006, sec. II.4 and V.3):
//  - order 4: the triple jump g1 = g3 = 1 / (2 - 2^(1/3)), g2 = 1 - 2 g1 (Yoshida, Phys. Lett.
//    A 150, 262 (1990); Suzuki, Phys. Lett. A 146, 319 (1990));
//  - order 6: the 9-stage composition of Kahan and Li, Math. Comp. 66, 1089 (1997), scheme
//    s9odr6a, with the coefficients as printed in Hairer-Lubich-Wanner, sec. V.3.2, (3.12);
//    its error constants are much smaller than those of Yoshida's 7-stage order-6 scheme.
// Every composition of symplectic steps is symplectic, and a symmetric composition of a
// symmetric method is symmetric.
//
// The grid t_k = t_b + k H (H = opts.fixed_step) is the method's own: an output time between
// grid points is served by one extra composed step of the remaining length from the last
// grid point into a copy, so outputs (dal_evolve's monitor times, dal_advance targets) never
// change the trajectory, which keeps its long-time behaviour (a shortened step would perturb
// the modified Hamiltonian at every output). The state x of the base method is summed with
// compensation (Kahan) at every step.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "symplectic.h"

/// spacing test of grid and output times: within a few ulps of the larger one, and within
/// a negligible fraction of the step (at large |t| a few ulps are a long time)
#define SYMP_NEAR_ULPS 8.0
#define SYMP_NEAR_STEP 1e-9

// composition coefficients; the triple jump is exact in closed form (filled at create)
static const double kahan_li6[9] = {
    0.39216144400731413927925056,  0.33259913678935943859974864, -0.70624617255763935980996482,
    0.08221359629355080023149045,  0.79854399093482996339895035, 0.08221359629355080023149045,
    -0.70624617255763935980996482, 0.33259913678935943859974864, 0.39216144400731413927925056};

typedef struct symp_mem {
  dal_symp_base base;
  double gam[9];   // composition coefficients
  double cum[10];  // cum[i] = g_1 + ... + g_i (start of substep i+1 as a fraction of h)
  int ns;          // stages
  double H;        // grid step
  double tb;       // grid origin
  long k;          // grid index of x
  double *x, *c;   // state at grid point k and its compensation
  double *xw, *cw; // work copies (a step commits only when it succeeds)
  // dense output (ig->hook): the step [ig->tprev, ig->t] starts from xs, cs at time ts, and
  // a time inside it is served like an off-grid output: one composed step into xi, ci
  const double *xs, *cs;
  double ts;
  double *xi, *ci;
} symp_mem;

int dal__symplectic_method(dal_method m) { return dal__method_can(m, DAL__CAP_SYMPLECTIC); }

// each method: its base method (RATTLE on the constraints, else the variational integrator)
// and the order of the symmetric composition around it
static const struct {
  dal_method m;
  int rattle, order;
} kinds[] = {
    {DAL_METHOD_VARIATIONAL, 0, 2},  {DAL_METHOD_VARIATIONAL4, 0, 4},
    {DAL_METHOD_VARIATIONAL6, 0, 6}, {DAL_METHOD_RATTLE, 1, 2},
    {DAL_METHOD_RATTLE4, 1, 4},      {DAL_METHOD_RATTLE6, 1, 6},
};

static int kind_of(dal_method m) {
  for (int i = 0; i < (int)(sizeof kinds / sizeof kinds[0]); ++i)
    if (kinds[i].m == m) return i;
  DAL_ASSERT(0); // dal__symplectic_method(m) holds for every caller
  return 0;
}

static int is_rattle(dal_method m) { return kinds[kind_of(m)].rattle; }

static int order_of(dal_method m) { return kinds[kind_of(m)].order; }

int dal__symplectic_resolve(const dal_system *sys, dal_state *st, const dal_solve_opts *o,
                            dal_method m, const dal_ode_problem **prob) {
  const char *name = dal_method_name(m);
  int rattle = is_rattle(m);
  // RATTLE is its own treatment of the constraints: no DAE formulation applies
  int form_ok = rattle ? o->form == DAL_FORM_AUTO || o->form == DAL_FORM_INDEX1 ||
                             (o->form == DAL_FORM_ODE && sys->m == 0)
                       : o->form == DAL_FORM_AUTO || o->form == DAL_FORM_ODE;
  if (!form_ok)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    rattle ? "method '%s' enforces the constraints itself (positions and "
                             "velocities at every step) and runs with DAL_FORM_AUTO, not with "
                             "formulation '%s'"
                           : "method '%s' integrates minimal coordinates (DAL_FORM_ODE or AUTO), "
                             "not formulation '%s'; for constrained Cartesian scenes use "
                             "DAL_METHOD_RATTLE",
                    name, dal_formulation_name(o->form));
  int rc = rattle ? dal__rattle_check(sys, st, name) : dal__variational_check(sys, st, name);
  if (rc) return rc;
  *prob = rattle && sys->m ? &dal__problem_index1 : &dal__problem_minimal;
  return DAL_OK;
}

// a grid time and an output time within rounding of each other, where the time between them
// moves nothing: a few ulps that are also a negligible fraction of the step H
static int near_time(double a, double b, double H) {
  double d = fabs(a - b);
  return d <= SYMP_NEAR_ULPS * DBL_EPSILON * fmax(fabs(a), fabs(b)) && d <= SYMP_NEAR_STEP * H;
}

static double grid_time(const symp_mem *m, long k) { return m->tb + (double)k * m->H; }

// one composed step of length h from (t, x) in place
static int composed_step(dal_ode_integ *ig, symp_mem *m, double t, double h, double *x, double *c) {
  for (int i = 0; i < m->ns; ++i) {
    int rc = m->base.step(ig, m->base.mem, t + m->cum[i] * h, m->gam[i] * h, x, c);
    if (rc) return rc;
  }
  return DAL_OK;
}

// the last accepted grid point as the integrator's last accepted step (failures)
static void back_to_grid(dal_ode_integ *ig, symp_mem *m) {
  double t = grid_time(m, m->k);
  // if even the conversion fails, or gives values beyond double range (a velocity from momenta
  // that overflow), the previous output point stays the last accepted step
  if (m->base.to_y(ig, m->base.mem, t, m->x, ig->ydot) != 0) return;
  for (int i = 0; i < ig->ny; ++i)
    if (!isfinite(ig->ydot[i])) return;
  memcpy(ig->y, ig->ydot, (size_t)ig->ny * sizeof(double));
  ig->t = t;
}

static int fail_step(dal_ode_integ *ig, symp_mem *m, int rc) {
  char msg[DAL_ERRMSG_LEN];
  memcpy(msg, ig->st->err, sizeof msg);
  m->base.invalidate(m->base.mem);
  back_to_grid(ig, m);
  if (rc == DAL__RECOVERABLE)
    return dal__ode_fail(ig, DAL_E_CALLBACK,
                         "%s; a fixed-step %s step cannot shrink: reduce opts.fixed_step (%.3g); "
                         "stopped at t=%.17g (last accepted step)",
                         msg, dal_method_name(ig->method), m->H, ig->t);
  return dal__ode_fail(ig, rc, "%s; stopped at t=%.17g (last accepted step) before t=%.17g", msg,
                       ig->t, ig->tout);
}

// dense output: the composed step of length t - ts from the start of the step (the same
// partial step that serves an off-grid output; the trajectory is not touched)
static int symp_interp(dal_ode_integ *ig, double t, double *yout) {
  symp_mem *m = ig->impl;
  size_t bytes = (size_t)m->base.nx * sizeof(double);
  memcpy(m->xi, m->xs, bytes);
  memcpy(m->ci, m->cs, bytes);
  // the base's caches belong to the last grid point, not to the step's start
  m->base.invalidate(m->base.mem);
  int rc = composed_step(ig, m, m->ts, t - m->ts, m->xi, m->ci);
  m->base.invalidate(m->base.mem);
  if (!rc) rc = m->base.to_y(ig, m->base.mem, t, m->xi, yout);
  return dal__public_status(rc);
}

// the step from (ts, xs) to (t, y) is accepted: tell the driver's hook
static int symp_hook(dal_ode_integ *ig, symp_mem *m, double ts, const double *xs, const double *cs,
                     double t, const double *y) {
  m->xs = xs;
  m->cs = cs;
  m->ts = ts;
  memcpy(ig->yprev, ig->y, (size_t)ig->ny * sizeof(double));
  memcpy(ig->y, y, (size_t)ig->ny * sizeof(double));
  ig->tprev = ig->t;
  ig->t = t;
  ig->hvalid = 0;
  return ig->hook(ig->hook_ctx);
}

static int symp_advance(dal_ode_integ *ig, double tout) {
  symp_mem *m = ig->impl;
  size_t bytes = (size_t)m->base.nx * sizeof(double);
  int rc;
  for (;;) {
    double tk = grid_time(m, m->k), tn = grid_time(m, m->k + 1);
    if (near_time(tk, tout, m->H) || (tn > tout && !near_time(tn, tout, m->H))) break;
    // the progress guard (as RK4's): a grid step of a few ulps of t does not resolve time
    if (!(tn - tk > DAL_TINY_STEP(tk))) {
      back_to_grid(ig, m);
      return dal__ode_fail(ig, DAL_E_ARG,
                           "opts.fixed_step = %.3g is below the floating-point resolution of t "
                           "near t=%.17g (grid steps of %.3g, a few ulps): the grid does not "
                           "advance; use a larger step or restart the clock near 0",
                           m->H, tk, tn - tk);
    }
    if (ig->ncall >= ig->opts.max_steps) {
      back_to_grid(ig, m);
      return dal__ode_fail(ig, DAL_E_MAXSTEPS,
                           "%ld steps of h=%.3g taken at t=%.17g before the target t=%.17g "
                           "(opts.max_steps); raise max_steps or, if the accuracy allows, "
                           "opts.fixed_step",
                           ig->ncall, m->H, tk, tout);
    }
    // step a copy; commit it only when the whole composed step succeeds
    memcpy(m->xw, m->x, bytes);
    memcpy(m->cw, m->c, bytes);
    rc = composed_step(ig, m, tk, m->H, m->xw, m->cw);
    if (rc) return fail_step(ig, m, rc);
    double *sw = m->x;
    m->x = m->xw;
    m->xw = sw;
    sw = m->c;
    m->c = m->cw;
    m->cw = sw;
    m->k++;
    ig->ncall++;
    ig->st->stats.steps++;
    ig->st->stats.last_h = m->H;
    if (ig->hook) {
      // the grid point as the accepted step; the previous one (now in xw, cw) starts it
      double tg = grid_time(m, m->k);
      if ((rc = m->base.to_y(ig, m->base.mem, tg, m->x, ig->ydot)) != 0)
        return fail_step(ig, m, rc);
      if ((rc = symp_hook(ig, m, tk, m->xw, m->cw, tg, ig->ydot)) != 0) return rc;
    }
  }
  double tk = grid_time(m, m->k);
  if (near_time(tk, tout, m->H)) {
    rc = m->base.to_y(ig, m->base.mem, tk, m->x, ig->ydot);
  } else {
    // off the grid: one composed step of the remaining length into a copy
    memcpy(m->xw, m->x, bytes);
    memcpy(m->cw, m->c, bytes);
    rc = composed_step(ig, m, tk, tout - tk, m->xw, m->cw);
    m->base.invalidate(m->base.mem);
    if (rc) return fail_step(ig, m, rc);
    rc = m->base.to_y(ig, m->base.mem, tout, m->xw, ig->ydot);
  }
  if (rc) return fail_step(ig, m, rc);
  if (ig->hook && tout > ig->t && !near_time(tk, tout, m->H)) {
    // the last piece [t_k, tout] is a step of its own for dense output and events
    if ((rc = m->base.to_y(ig, m->base.mem, tk, m->x, ig->y)) != 0) return fail_step(ig, m, rc);
    ig->t = tk;
    return symp_hook(ig, m, tk, m->x, m->c, tout, ig->ydot);
  }
  memcpy(ig->y, ig->ydot, (size_t)ig->ny * sizeof(double));
  ig->t = tout;
  return DAL_OK;
}

static void symp_free(void *p) {
  symp_mem *m = p;
  if (!m) return;
  if (m->base.free) m->base.free(m->base.mem);
  free(m->x);
  free(m->c);
  free(m->xw);
  free(m->cw);
  free(m->xi);
  free(m->ci);
  free(m);
}

static const dal_ode_ops symp_ops = {symp_advance, symp_free, symp_interp, NULL, NULL};

int dal__symplectic_create(dal_ode_integ *ig) {
  symp_mem *m = calloc(1, sizeof *m);
  if (!m) return DAL_FAIL(ig->st, DAL_E_NOMEM, "out of memory creating the integrator");
  ig->impl = m;
  ig->ops = &symp_ops;
  int order = order_of(ig->method);
  if (order == 2) {
    m->ns = 1;
    m->gam[0] = 1.0;
  } else if (order == 4) {
    m->ns = 3;
    m->gam[0] = m->gam[2] = 1.0 / (2.0 - cbrt(2.0));
    m->gam[1] = 1.0 - 2.0 * m->gam[0];
  } else {
    m->ns = 9;
    memcpy(m->gam, kahan_li6, sizeof kahan_li6);
  }
  m->cum[0] = 0.0;
  for (int i = 0; i < m->ns; ++i)
    m->cum[i + 1] = m->cum[i] + m->gam[i];
  m->H = ig->opts.fixed_step;
  m->tb = ig->t;
  m->k = 0;
  int rc =
      is_rattle(ig->method) ? dal__rattle_base(ig, &m->base) : dal__variational_base(ig, &m->base);
  if (rc) return rc;
  size_t nx = (size_t)m->base.nx + 1;
  m->x = calloc(nx, sizeof(double));
  m->c = calloc(nx, sizeof(double));
  m->xw = calloc(nx, sizeof(double));
  m->cw = calloc(nx, sizeof(double));
  m->xi = calloc(nx, sizeof(double));
  m->ci = calloc(nx, sizeof(double));
  if (!m->x || !m->c || !m->xw || !m->cw || !m->xi || !m->ci)
    return DAL_FAIL(ig->st, DAL_E_NOMEM, "out of memory creating the integrator");
  // the base may have moved the state (RATTLE: onto the constraints): start from it
  ig->prob->from_state(ig->sys, ig->st, ig->y);
  ig->t = ig->st->t;
  m->tb = ig->t;
  return m->base.from_y(ig, m->base.mem, ig->t, ig->y, m->x);
}
