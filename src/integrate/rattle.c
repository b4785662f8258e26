// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// RATTLE: constrained Stormer-Verlet for Cartesian particles with holonomic constraints.
//
// Andersen, J. Comput. Phys. 52, 24 (1983); Leimkuhler and Reich, Simulating Hamiltonian
// Dynamics (Cambridge 2004), sec. 7.2; Hairer, Lubich, Wanner, Geometric Numerical
// Integration (2nd ed., Springer 2006), sec. VII.1.4, (1.26). With the constant diagonal mass
// matrix M of Cartesian particles, potential forces F = -grad U (q, t) and constraints
// phi(q, t) = 0 (G = dphi/dq):
//   v_h = v0 + h/2 M^-1 (F(q0, t0) + G(q0)' lambda)
//   q1  = q0 + h v_h,                       phi(q1, t1) = 0
//   v1  = v_h + h/2 M^-1 (F(q1, t1) + G(q1)' mu),   G(q1) v1 + dphi/dt (q1, t1) = 0.
// The position equations are solved for lambda by the simplified Newton iteration of
// Hairer-Lubich-Wanner (the matrix G(q0) M^-1 G(q0)' in place of G(q1) M^-1 G(q0)'), through
// the KKT factorization [M G'; G 0] of the start point (dense LAPACK or sparse KLU, so a step
// costs O(N) on chains): each iteration is one constraint evaluation and one KKT solve, and
// converges linearly with a factor of order h |v| / (the constraints' length scale). The
// velocity equations are one linear KKT solve at q1, whose factorization serves the next step's
// position iteration too: one factorization per step. Both residuals are driven to the level
// of rounding at every step (16 ulps of max(1, |q|) for phi) and recorded in dal_stats.
//
// Rheonomic constraints phi(q, t): the position constraint is imposed at t1 and the velocity
// constraint includes dphi/dt (q1, t1). This is RATTLE for the autonomous system in the
// extended phase space (q, t; p, p_t) with H_ext = H + p_t, where t moves exactly as t0 + h:
// the step is symplectic and symmetric there and second order; the energy then changes by the
// work of the moving constraint, and what is conserved is what the extended system conserves
// (e.g. a Jacobi integral when the constraint moves uniformly, shown in bench/symplectic.c).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "eval/eval.h"
#include "symplectic.h"

/// iterations of the position constraint solve before giving up
#define RAT_MAXIT 60
/// consecutive growing residuals that count as divergence
#define RAT_MAXGROW 3
/// position residual target in ulps of max(1, max |q|)
#define RAT_PHI_ULPS 16.0

#define EPS DBL_EPSILON

// The method's state x = (q (n), v (n), lambda (m)): lambda, the multipliers of the last
// position solve, is the next one's guess; kept in x so that a step from a copy (an off-grid
// output, a failed attempt) leaves the trajectory bit for bit.
typedef struct rat_mem {
  dal_state *st;
  int n, m;
  int cache_ok; // F0, G0 and the KKT factorization belong to the start of the next step
  double *minv; // inverse mass of each coordinate (n)
  double *F0;   // generalized forces at the start point (n)
  double *G0;   // compact G at the start point
  double *lam0; // multipliers at the start (KKT), the first position solve's guess (m)
  double *E, *qt, *ct, *vh, *u, *zero, *xk; // n
  double *yk, *b, *gu;                      // m
} rat_mem;

static int is_cartesian(const dal_primitive *p) {
  return p == &dal_map_cartesian2 || p == &dal_map_cartesian3 || p == &dal_map_fixed2 ||
         p == &dal_map_fixed3;
}

int dal__rattle_check(const dal_system *sys, dal_state *st, const char *name) {
  if (sys->lag)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "method '%s' needs Cartesian particles; this system is given by a "
                    "Lagrangian: use DAL_METHOD_VARIATIONAL",
                    name);
  if (sys->map || !sys->place)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "method '%s' needs particles placed by dal_map_cartesian2/3 (or fixed "
                    "points); this system gives its positions by a whole-system map: use "
                    "DAL_METHOD_VARIATIONAL (minimal coordinates) or DAL_FORM_GGL",
                    name);
  for (int k = 0; k < sys->N; ++k)
    if (!is_cartesian(sys->place[k].prim))
      return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                      "method '%s' needs Cartesian particles (constant mass matrix), but "
                      "particle '%s' is placed by map '%s': place it by dal_map_cartesian%d "
                      "with constraints, or use DAL_METHOD_VARIATIONAL for minimal coordinates",
                      name, sys->part_names[k], sys->place[k].prim->name, sys->dim);
  const char *kind = sys->ndamper     ? "damper"
                     : sys->nforce    ? "force callback (dal_builder_add_force)"
                     : sys->ngenforce ? "generalized force callback (dal_builder_add_genforce)"
                                      : NULL;
  if (kind)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "method '%s' integrates potential forces only (gravity, springs, "
                    "potentials), but the system has a %s; use DAL_FORM_GGL (IDA) or, in "
                    "minimal coordinates, DAL_METHOD_VARIATIONAL (forces by the discrete "
                    "Lagrange-d'Alembert principle)",
                    name, kind);
  return DAL_OK;
}

// kinematics and constraint rows (and forces) at (t, q, v)
static int rat_eval(const dal_system *sys, rat_mem *m, double t, const double *q, const double *v,
                    int dyn) {
  dal_state *st = m->st;
  st->t = t;
  memcpy(st->q, q, (size_t)m->n * sizeof(double));
  memcpy(st->qdot, v, (size_t)m->n * sizeof(double));
  dal__state_moved(st);
  st->stats.rhs_evals++;
  int rc = dal__kinematics(sys, st, 1);
  if (rc == 0 && m->m) rc = dal__constraints(sys, st);
  if (rc == 0 && dyn) rc = dal__dynamics(sys, st, 1, NULL);
  return rc;
}

// forces, G and the KKT factorization at the start point (t, q, v) of a step
static int rat_start(const dal_system *sys, rat_mem *m, double t, const double *q,
                     const double *v) {
  int rc = rat_eval(sys, m, t, q, v, 1);
  if (rc == 0 && m->m) rc = dal__kkt_factor(sys, m->st, DAL_KKT_MASS, "RATTLE step");
  if (rc) return rc;
  memcpy(m->F0, m->st->Q, (size_t)m->n * sizeof(double));
  if (m->m) memcpy(m->G0, m->st->G, (size_t)sys->g_total * sizeof(double));
  m->st->stats.jac_evals++;
  m->cache_ok = 1;
  return DAL_OK;
}

static double max_abs(const double *x, int n, int *at) {
  double mx = 0.0;
  *at = 0;
  for (int i = 0; i < n; ++i)
    if (!(fabs(x[i]) <= mx)) {
      mx = fabs(x[i]);
      *at = i;
      if (isnan(mx)) break;
    }
  return mx;
}

// the positions of the step of h from (t, x = (q0, v0, lambda), compensation c): simplified
// Newton on the multipliers (m->E the displacement beyond h v0) until phi(q1, t + h) = 0;
// q1 into m->qt (compensation m->ct), the half-step velocity into m->vh, *res: the last
// constraint residual
static int rat_positions(const dal_system *sys, rat_mem *m, double t, double h, double *x,
                         const double *c, double *res) {
  dal_state *st = m->st;
  int n = m->n, nc = m->m, rc, grow = 0, worst = 0;
  double *q0 = x, *v0 = x + n, *lam = x + 2 * n, t1 = t + h, rprev = INFINITY;
  for (int it = 0;; ++it) {
    double qmax = 1.0;
    for (int i = 0; i < n; ++i) {
      m->qt[i] = q0[i];
      m->ct[i] = c[i];
      dal__ksum(&m->qt[i], &m->ct[i], h * v0[i] + m->E[i]);
      m->vh[i] = v0[i] + m->E[i] / h;
      qmax = fmax(qmax, fabs(m->qt[i]));
    }
    if ((rc = rat_eval(sys, m, t1, m->qt, m->vh, 0)) != 0) return rc;
    if (!nc) return DAL_OK;
    *res = max_abs(st->phi, nc, &worst);
    double tol = RAT_PHI_ULPS * EPS * qmax;
    if (*res <= tol || (it >= 2 && *res >= 0.5 * rprev && *res <= 1e3 * tol)) return DAL_OK;
    grow = *res > rprev ? grow + 1 : 0;
    if (!isfinite(*res) || grow >= RAT_MAXGROW || it >= RAT_MAXIT) {
      return DAL_FAIL(st, DAL_E_CONV,
                      "RATTLE step from t=%.17g, %s (h=%.3g): the position constraints do not "
                      "converge (constraint '%s', row %d, residual %.3g after %d iterations, %s); "
                      "the step is too long for the motion or the constraints become dependent: "
                      "reduce opts.fixed_step",
                      t, dal__qtext(sys, q0).s, h, sys->con[sys->row_con[worst]].name, worst, *res,
                      it,
                      isfinite(*res) ? (grow >= RAT_MAXGROW ? "growing" : "converging too slowly")
                                     : "not finite");
    }
    rprev = *res;
    for (int r = 0; r < nc; ++r)
      m->b[r] = -st->phi[r];
    dal__kkt_solve(sys, st, m->zero, m->b, m->xk, m->yk);
    st->stats.nonlin_iters++;
    for (int i = 0; i < n; ++i)
      m->E[i] += m->xk[i];
    for (int r = 0; r < nc; ++r)
      lam[r] += 2.0 * m->yk[r] / (h * h);
  }
}

static int rat_step(dal_ode_integ *ig, void *mem, double t, double h, double *x, double *c) {
  rat_mem *m = mem;
  const dal_system *sys = ig->sys;
  dal_state *st = m->st;
  int n = m->n, nc = m->m, rc;
  double *q0 = x, *v0 = x + n, *lam = x + 2 * n, res = 0.0;
  if (h == 0.0) return DAL_OK;
  if (!m->cache_ok && (rc = rat_start(sys, m, t, q0, v0)) != 0) return rc;
  m->cache_ok = 0;
  // kick with the forces and the multipliers' guess: E = h^2/2 M^-1 (F0 + G0' lambda)
  if (nc)
    dal__gt_mul(sys, m->G0, lam, m->u);
  else
    memset(m->u, 0, (size_t)n * sizeof(double));
  for (int i = 0; i < n; ++i)
    m->E[i] = 0.5 * h * h * m->minv[i] * (m->F0[i] + m->u[i]);
  // positions: simplified Newton on the multipliers until phi(q1, t1) = 0
  if ((rc = rat_positions(sys, m, t, h, x, c, &res)) != 0) return rc;
  // forces at q1 (kinematics and constraint rows are current at (t1, q1, v_h))
  if ((rc = dal__dynamics(sys, st, 1, NULL)) != 0) return rc;
  for (int i = 0; i < n; ++i)
    m->u[i] = 0.5 * h * m->minv[i] * st->Q[i];
  double resv = 0.0;
  if (nc) {
    // velocities: v1 = v_h + u + dv with M dv = G1' mu, G1 v1 + dphi/dt = 0; phidot holds
    // G1 v_h + dphi/dt
    if ((rc = dal__kkt_factor(sys, st, DAL_KKT_MASS, "RATTLE step")) != 0) return rc;
    st->stats.jac_evals++;
    dal__g_mul(sys, st->G, m->u, m->gu);
    for (int r = 0; r < nc; ++r)
      m->b[r] = -(st->phidot[r] + m->gu[r]);
    dal__kkt_solve(sys, st, m->zero, m->b, m->xk, m->yk);
    for (int i = 0; i < n; ++i)
      m->u[i] += m->xk[i];
    // the velocity residual G1 v1 + dphi/dt = phidot + G1 (u + dv)
    dal__g_mul(sys, st->G, m->u, m->gu);
    for (int r = 0; r < nc; ++r)
      resv = fmax(resv, fabs(st->phidot[r] + m->gu[r]));
    memcpy(m->G0, st->G, (size_t)sys->g_total * sizeof(double));
  }
  memcpy(m->F0, st->Q, (size_t)n * sizeof(double));
  // commit: q1 (already summed into qt, ct) and v1 = v0 + E/h + u, compensated
  for (int i = 0; i < n; ++i) {
    q0[i] = m->qt[i];
    c[i] = m->ct[i];
    dal__ksum(&v0[i], &c[n + i], m->E[i] / h + m->u[i]);
  }
  m->cache_ok = 1;
  if (res > st->stats.max_phi) st->stats.max_phi = res;
  if (resv > st->stats.max_phidot) st->stats.max_phidot = resv;
  return DAL_OK;
}

static int rat_from_y(dal_ode_integ *ig, void *mem, double t, const double *y, double *x) {
  (void)ig;
  (void)t;
  rat_mem *m = mem;
  memcpy(x, y, 2 * (size_t)m->n * sizeof(double));
  memcpy(x + 2 * m->n, m->lam0, (size_t)m->m * sizeof(double));
  m->cache_ok = 0;
  return DAL_OK;
}

static int rat_to_y(dal_ode_integ *ig, void *mem, double t, const double *x, double *y) {
  (void)ig;
  (void)t;
  rat_mem *m = mem;
  memcpy(y, x, 2 * (size_t)m->n * sizeof(double));
  return DAL_OK;
}

static void rat_invalidate(void *mem) { ((rat_mem *)mem)->cache_ok = 0; }

static void rat_free(void *mem) {
  rat_mem *m = mem;
  if (!m) return;
  DAL_FREE(m->minv, m->F0, m->G0, m->lam0, m->E, m->qt, m->ct, m->vh, m->u, m->zero, m->xk, m->yk,
           m->b, m->gu, m);
}

int dal__rattle_base(dal_ode_integ *ig, dal_symp_base *b) {
  const dal_system *sys = ig->sys;
  dal_state *st = ig->st;
  rat_mem *m = calloc(1, sizeof *m);
  if (!m) return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the RATTLE integrator");
  m->st = st;
  m->n = sys->n;
  m->m = sys->m;
  // (nx, mem, from_y, to_y, step, invalidate, free)
  *b =
      (dal_symp_base){2 * m->n + m->m, m, rat_from_y, rat_to_y, rat_step, rat_invalidate, rat_free};
  size_t n = (size_t)m->n + 1, mm = (size_t)m->m + 1;
  double **vn[] = {&m->minv, &m->F0, &m->E, &m->qt, &m->ct, &m->vh, &m->u, &m->zero, &m->xk};
  double **vm[] = {&m->lam0, &m->yk, &m->b, &m->gu};
  int ok = 1;
  for (size_t i = 0; i < sizeof vn / sizeof vn[0]; ++i)
    ok &= (*vn[i] = calloc(n, sizeof(double))) != NULL;
  for (size_t i = 0; i < sizeof vm / sizeof vm[0]; ++i)
    ok &= (*vm[i] = calloc(mm, sizeof(double))) != NULL;
  m->G0 = calloc((size_t)sys->g_total + 1, sizeof(double));
  if (!ok || !m->G0)
    return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the RATTLE integrator");
  // the constant diagonal mass matrix of Cartesian particles: every coordinate needs a mass
  for (int k = 0; k < sys->N; ++k) {
    const dal_place *pl = &sys->place[k];
    for (int i = 0; i < pl->ncoord; ++i)
      m->minv[sys->ipool[pl->coord_off + i]] += st->prm.mass[k];
  }
  for (int i = 0; i < m->n; ++i) {
    if (!(m->minv[i] > 0.0))
      return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                      "method '%s': coordinate '%s' moves no particle (no mass), so RATTLE "
                      "cannot integrate it; make it a particle coordinate or use DAL_FORM_GGL",
                      dal_method_name(ig->method), sys->coord_names[i]);
    m->minv[i] = 1.0 / m->minv[i];
  }
  if (m->m == 0) return DAL_OK;
  // a consistent start (rank check, positions and velocities onto the constraints, KKT
  // multipliers), then positions to the level of rounding for the first step
  int rc = dal__dae_start(sys, st, ig->opts.init_max_move, NULL);
  if (rc) return rc;
  memcpy(m->lam0, st->lambda, (size_t)m->m * sizeof(double));
  double qmax = 1.0;
  for (int i = 0; i < m->n; ++i)
    qmax = fmax(qmax, fabs(st->q[i]));
  rc = dal__project_state(sys, st, 64.0 * EPS * qmax, 10, NULL);
  return rc == DAL__RECOVERABLE ? DAL_E_CALLBACK : rc;
}
