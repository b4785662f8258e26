// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The flow map's derivatives: the state-transition matrix Phi(t1, t0) = dy(t1)/dy(t0) and the
// forward sensitivities dy(t1)/dp to named parameters, by the variational equations
//   Phi' = A(t) Phi, Phi(t0) = I,   S' = A(t) S + df/dp, S(t0) = 0,   A = df/dy (exact tangent)
// integrated with the trajectory as one first-order problem through the library's ODE
// integrators, so that their error control covers Phi and S too. Minimal coordinates run
// f = (qdot, qddot); constraint rows run the index-1 vector field (accelerations and
// multipliers from the KKT system) in the full space, whose tangent leaves the manifold's
// tangent space invariant (tangent_con.c).
//
// df/dp is exact: masses, gravity, spring constants and damper coefficients enter the residual
// R = sum_k J_k' (m_k A_k - F_k) in closed form, so dR/dp = sum_k J_k' d(m_k A_k - F_k)/dp at
// the state's accelerations, and df/dp = (0, -M^-1 dR/dp) (or the KKT solve with constraint
// rows). Parameters of primitives enter as plain doubles and have no exact derivative: refused.
//
// The variational equations are a plain first-order problem (dal_first_order) whose context
// is the var_problem below, run behind the integrator handle (dal__integ_create_fo): any
// method whose row can run one explicitly runs them.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis.h"
#include "integrate/integrate.h"

typedef struct var_problem {
  dal_first_order fo;          // y = (q, qdot, Phi, S), run by the library's integrators
  dal_solve_opts opts;         // the options the base problem's rhs reads
  const dal_ode_problem *base; // minimal or index-1
  dal_tangent *tg;
  int n, m, np;
  double *A;          // 2n x 2n
  double *B;          // (n + m) x np: -dR/dp (and 0 for the constraint rows), then solved
  double *f;          // N d scratch
  dal_param_ref *ref; // np
  double *y0;         // the start (fo.ny)
} var_problem;

// y = (q, qdot, Phi, S): the trajectory from the state, Phi = I, S = 0 (y comes zeroed)
static void var_from_state(const dal_system *sys, const dal_state *st, double *y) {
  size_t n2 = 2 * (size_t)sys->n;
  memcpy(y, st->q, (size_t)sys->n * sizeof(double));
  memcpy(y + sys->n, st->qdot, (size_t)sys->n * sizeof(double));
  for (size_t i = 0; i < n2; ++i)
    y[n2 + i * n2 + i] = 1.0;
}

// dR/dp for one parameter at the evaluated tangent (n values into out)
static void residual_dp(const dal_system *sys, const dal_state *st, dal_tangent *tg, double *f,
                        const dal_param_ref *ref, double *out) {
  int d = sys->dim, nd = tg->nd, n = tg->n;
  memset(f, 0, (size_t)nd * sizeof(double));
  const double *g = st->prm.g;
  switch (ref->kind) {
  case DAL_PARAM_MASS: // d(m A - m g)/dm
    for (int b = 0; b < d; ++b)
      f[ref->target * d + b] = tg->A[ref->target * d + b] - (st->prm.has_gravity ? g[b] : 0.0);
    break;
  case DAL_PARAM_GRAVITY: // F = m g
    for (int k = 0; k < sys->N; ++k)
      f[k * d + ref->index] = -st->prm.mass[k];
    break;
  case DAL_PARAM_SPRING_K:
  case DAL_PARAM_SPRING_L:
  case DAL_PARAM_DAMPER_C: {
    int spring = ref->kind != DAL_PARAM_DAMPER_C;
    const dal_link *l = spring ? &st->prm.springs[ref->target] : &st->prm.dampers[ref->target];
    const double *an = tg->link + 9 * (size_t)(spring ? ref->target : sys->nspring + ref->target);
    double e[3], len = 0.0, rel = 0.0;
    for (int b = 0; b < d; ++b) {
      double xb = l->b >= 0 ? tg->r[l->b * d + b] : an[b];
      e[b] = tg->r[l->a * d + b] - xb;
      len += e[b] * e[b];
    }
    len = sqrt(len);
    for (int b = 0; b < d; ++b) {
      e[b] /= len;
      double vb = l->b >= 0 ? tg->v[l->b * d + b] : an[3 + b];
      rel += (tg->v[l->a * d + b] - vb) * e[b];
    }
    // -dF_a/dp: U = k/2 (len - L)^2 gives -F_a = k (len - L) e; a damper F_a = -c rel e
    double s = ref->kind == DAL_PARAM_SPRING_K   ? len - l->L
               : ref->kind == DAL_PARAM_SPRING_L ? -l->k
                                                 : rel;
    for (int b = 0; b < d; ++b) {
      f[l->a * d + b] += s * e[b];
      if (l->b >= 0) f[l->b * d + b] -= s * e[b];
    }
    break;
  }
  default:
    break;
  }
  for (int i = 0; i < n; ++i) {
    double x = 0.0;
    for (int c = 0; c < nd; ++c)
      x += tg->J[(size_t)i * nd + c] * f[c];
    out[i] = x;
  }
}

static int var_rhs(void *ctx, dal_state *st, double t, const double *y, double *ydot) {
  var_problem *vp = ctx;
  const dal_system *sys = st->sys;
  int n = vp->n, m = vp->m, np = vp->np, rc;
  size_t n2 = 2 * (size_t)n, nk = (size_t)(n + m);
  if ((rc = vp->base->rhs(sys, st, &vp->opts, t, y, ydot, DAL_P_ACC)) != 0) return rc;
  // the exact tangent at (t, q, qdot) with the accelerations (and multipliers) just computed
  if ((rc = dal__tangent_eval(sys, st, vp->tg, 0)) != 0) return rc;
  if (m > 0) {
    rc = dal__tangent_kkt(sys, st, vp->tg, vp->A, NULL, NULL);
  } else if ((rc = dal__tangent_factor(sys, st, vp->tg)) == 0) {
    dal__tangent_flow(vp->tg, vp->A, NULL);
  }
  if (rc) return rc;
  // df/dp = (0, a_p): M a_p = -dR/dp, or the KKT system with zero constraint rows
  for (int j = 0; j < np; ++j) {
    double *b = vp->B + (size_t)j * nk;
    residual_dp(sys, st, vp->tg, vp->f, &vp->ref[j], b);
    for (size_t i = 0; i < nk; ++i)
      b[i] = i < (size_t)n ? -b[i] : 0.0;
  }
  if (m > 0)
    dal__tangent_kkt_solve(vp->tg, np, vp->B);
  else
    for (int j = 0; j < np; ++j)
      dal__tangent_msolve(vp->tg, 1, vp->B + (size_t)j * nk);
  // Y' = A Y (+ df/dp) for the 2n columns of Phi and the np of S
  const double *A = vp->A;
  for (size_t c = 0; c < n2 + (size_t)np; ++c) {
    const double *Y = y + n2 + c * n2;
    double *Yd = ydot + n2 + c * n2;
    for (size_t i = 0; i < n2; ++i)
      Yd[i] = 0.0;
    for (size_t l = 0; l < n2; ++l) {
      double yl = Y[l];
      if (yl == 0.0) continue;
      const double *Al = A + l * n2;
      for (size_t i = 0; i < n2; ++i)
        Yd[i] += Al[i] * yl;
    }
    if (c >= n2) {
      const double *ap = vp->B + (c - n2) * nk;
      for (int i = 0; i < n; ++i)
        Yd[n + i] += ap[i];
    }
  }
  return DAL_OK;
}

// the options the variational equations run with (an explicit method, no Baumgarte terms,
// the index-1 form with constraint rows); 0 or a status with the state's message set
static int transition_opts(const dal_system *sys, dal_state *st, const dal_solve_opts *opts,
                           dal_solve_opts *out) {
  int rc;
  dal_solve_opts o;
  if (opts)
    o = *opts;
  else
    o = dal_default_solve_opts();
  if ((rc = dal__check_opts(st, &o)) != 0) return rc;
  o = dal__effective_opts(&o); // atol following rtol
  // the method rows' explicit methods (an implicit one would iterate on all of Phi and S)
  dal_method meth = DAL_METHOD_AUTO;
  if ((rc = dal__fo_method(st, o.method, o.rtol, DAL__CAP_EXPLICIT, "state_transition", &meth)) !=
      0)
    return rc;
  if (sys->m > 0 && (o.baumgarte_alpha != 0.0 || o.baumgarte_beta != 0.0))
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "state_transition: Baumgarte terms change the flow off the manifold; leave "
                    "opts.baumgarte_alpha and _beta at 0");
  o.method = meth;
  o.form = sys->m > 0 ? DAL_FORM_INDEX1 : o.form;
  o.work = 0;
  o.project = 0;
  *out = o;
  return dal__tangent_supported(sys, st, "state_transition");
}

// the variational problem of (sys, nparam named parameters) into vp (zeroed first; its
// memory is freed by var_free); 0 or a status with the state's message set
static int var_setup(const dal_system *sys, dal_state *st, const dal_solve_opts *o, int nparam,
                     const char *const *params, var_problem *vp) {
  memset(vp, 0, sizeof *vp);
  vp->base = sys->m > 0 ? &dal__problem_index1 : &dal__problem_minimal;
  vp->opts = *o;
  vp->n = sys->n;
  vp->m = sys->m;
  vp->np = nparam;
  size_t n = (size_t)sys->n, n2 = 2 * n, nk = n + (size_t)sys->m;
  vp->fo.ny = (int)(n2 * (1 + n2 + (size_t)nparam));
  vp->fo.rhs = var_rhs;
  vp->fo.ctx = vp;
  vp->fo.tol_factor = vp->base->tol_factor; // the index-1 form's projection error as in advance
  char msg[256];
  vp->ref = calloc((size_t)nparam + 1, sizeof *vp->ref);
  vp->A = calloc(n2 * n2, sizeof(double));
  vp->B = calloc(nk * (size_t)nparam + 1, sizeof(double));
  vp->f = calloc((size_t)(sys->N * sys->dim) + 1, sizeof(double));
  vp->y0 = calloc((size_t)vp->fo.ny, sizeof(double));
  vp->fo.y0 = vp->y0;
  if (!vp->ref || !vp->A || !vp->B || !vp->f || !vp->y0 || dal__tangent_create(sys, &vp->tg))
    return DAL_FAIL(st, DAL_E_NOMEM, "state_transition: out of memory");
  for (int j = 0; j < nparam; ++j) {
    int rc = dal_param_find(sys, params[j], &vp->ref[j], msg, sizeof msg);
    if (rc) return DAL_FAIL(st, rc, "state_transition: parameter %d: %s", j, msg);
    dal_param_kind k = vp->ref[j].kind;
    if (k == DAL_PARAM_PLACE || k == DAL_PARAM_CONSTRAINT || sys->lag)
      return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                      "state_transition: parameter '%s' has no exact derivative (%s); "
                      "sensitivities cover masses, gravity, springs and dampers of particle "
                      "systems",
                      params[j],
                      sys->lag ? "the system is a Lagrangian"
                               : "primitive parameters enter the jet functions as plain doubles");
  }
  return DAL_OK;
}

static void var_free(var_problem *vp) {
  dal__tangent_free(vp->tg);
  DAL_FREE(vp->ref, vp->A, vp->B, vp->f, vp->y0);
}

int dal_state_transition(const dal_system *sys, dal_state *st, const dal_solve_opts *opts,
                         double t1, double *Phi, int nparam, const char *const *params, double *S) {
  int rc = dal__check_pair(sys, st, "state_transition");
  if (rc) return rc;
  if (!Phi && !S) return DAL_FAIL(st, DAL_E_ARG, "state_transition: Phi and S are both NULL");
  if (nparam < 0 || (nparam > 0 && (!params || !S)) || (nparam == 0 && S))
    return DAL_FAIL(st, DAL_E_ARG,
                    "state_transition: nparam = %d needs %s; S goes with nparam > 0 names", nparam,
                    nparam > 0 ? "the names and S" : "S = NULL");
  if (!isfinite(t1) || !(t1 > st->t))
    return DAL_FAIL(st, DAL_E_ARG, "state_transition: t1 = %g must be finite and after t = %g", t1,
                    st->t);
  dal_solve_opts o;
  if ((rc = transition_opts(sys, st, opts, &o)) != 0) return rc;
  var_problem vp;
  dal_integ *it = NULL;
  size_t n = (size_t)sys->n, n2 = 2 * n;
  if ((rc = var_setup(sys, st, &o, nparam, params, &vp)) != 0) goto done;
  // a consistent start on the manifold (the tangent space is then invariant)
  if ((rc = dal__analysis_eval(sys, st, st->t, st->q, st->qdot)) != 0) goto done;
  if (sys->m > 0) {
    if ((rc = dal__tangent_eval(sys, st, vp.tg, 0)) != 0) goto done;
    if ((rc = dal__tangent_on_manifold(sys, st, vp.tg, "state_transition")) != 0) goto done;
  }
  var_from_state(sys, st, vp.y0);
  if ((rc = dal__integ_create_fo(sys, st, &o, &vp.fo, &it)) != 0) goto done;
  if ((rc = it->ops->advance(it, t1, NULL, NULL)) == 0) {
    const double *y = it->y;
    if (Phi) memcpy(Phi, y + n2, n2 * n2 * sizeof(double));
    if (S) memcpy(S, y + n2 + n2 * n2, n2 * (size_t)nparam * sizeof(double));
    rc = dal__analysis_eval(sys, st, t1, y, y + n);
  }
done:
  dal__integ_destroy(it);
  var_free(&vp);
  return rc;
}

// ---------------------------------------------------------------------------------------------
// linearization with inputs

// resolve one input name: "force:<coordinate>" (*coord >= 0) or a parameter with an exact
// derivative (*ref)
static int resolve_input(const dal_system *sys, dal_state *st, const char *name, int *coord,
                         dal_param_ref *ref) {
  *coord = -1;
  if (!name) return DAL_FAIL(st, DAL_E_ARG, "linearize_inputs: an input name is NULL");
  if (strncmp(name, "force:", 6) == 0) {
    const char *c = name + 6;
    for (int i = 0; i < sys->n; ++i)
      if (strcmp(sys->coord_names[i], c) == 0) *coord = i;
    if (*coord < 0) {
      char *end = NULL;
      long v = strtol(c, &end, 10);
      if (end != c && *end == '\0' && v >= 0 && v < sys->n) *coord = (int)v;
    }
    if (*coord < 0)
      return DAL_FAIL(st, DAL_E_ARG,
                      "linearize_inputs: input '%s': no coordinate '%s' (a name given to the "
                      "builder or a 0-based index below %d)",
                      name, c, sys->n);
    return DAL_OK;
  }
  char msg[256];
  int rc = dal_param_find(sys, name, ref, msg, sizeof msg);
  if (rc) return DAL_FAIL(st, rc, "linearize_inputs: input '%s': %s", name, msg);
  if (ref->kind == DAL_PARAM_PLACE || ref->kind == DAL_PARAM_CONSTRAINT || sys->lag)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "linearize_inputs: input '%s' has no exact derivative (%s); inputs are "
                    "generalized forces \"force:<coordinate>\", masses, gravity, springs and "
                    "dampers",
                    name,
                    sys->lag ? "the system is a Lagrangian"
                             : "primitive parameters enter the jet functions as plain doubles");
  return DAL_OK;
}

// without constraint rows: B = b, the first-order Af, and Bf = (0, M^-1 b); R holds the
// columns b_j (n + m apart)
static int inputs_free_space(const dal_system *sys, dal_state *st, dal_tangent *tg, int ninput,
                             const double *R, double *B, double *Af, double *Bf) {
  size_t sn = (size_t)sys->n, nk = sn + (size_t)sys->m, ni = (size_t)ninput;
  int rc = dal__tangent_factor(sys, st, tg);
  if (rc) return rc;
  if (B) memcpy(B, R, sn * ni * sizeof(double));
  if (Af) dal__tangent_flow(tg, Af, NULL);
  if (Bf) {
    for (size_t j = 0; j < ni; ++j) {
      double *c = Bf + j * 2 * sn;
      memset(c, 0, sn * sizeof(double));
      memcpy(c + sn, R + j * nk, sn * sizeof(double));
      dal__tangent_msolve(tg, 1, c + sn);
    }
  }
  return DAL_OK;
}

int dal_linearize_inputs(const dal_system *sys, dal_state *st, int ninput,
                         const char *const *inputs, double *B, double *Af, double *Bf) {
  int rc = dal__check_pair(sys, st, "linearize_inputs");
  if (rc) return rc;
  if (ninput < 0 || (ninput > 0 && !inputs))
    return DAL_FAIL(st, DAL_E_ARG, "linearize_inputs: ninput = %d needs %d names", ninput, ninput);
  if ((rc = dal__tangent_supported(sys, st, "linearize_inputs")) != 0) return rc;
  if ((rc = dal_forward(sys, st)) != 0) return rc;
  int n = sys->n, m = sys->m, k = n - m;
  size_t sn = (size_t)n, sk = (size_t)k, nk = sn + (size_t)m, k2 = 2 * sk, ni = (size_t)ninput;
  dal_tangent *tg = NULL;
  double *buf = calloc(nk * (ni + 1) + k2 * k2 + sk * sk + sn * sk + ni * sk +
                           (size_t)(sys->N * sys->dim) + 1,
                       sizeof(double));
  if (!buf || dal__tangent_create(sys, &tg)) {
    free(buf);
    return DAL_FAIL(st, DAL_E_NOMEM, "linearize_inputs: out of memory");
  }
  double *R = buf, *Ar = R + nk * (ni + 1), *Mr = Ar + k2 * k2, *N = Mr + sk * sk;
  double *Br = N + sn * sk, *f = Br + ni * sk;
  if ((rc = dal__tangent_eval(sys, st, tg, 0)) != 0) goto done;
  if (m > 0 && (rc = dal__tangent_on_manifold(sys, st, tg, "linearize_inputs")) != 0) goto done;
  // the input columns of the full residual: dR/du = -e_j for a generalized force, dR/dp else
  for (int j = 0; j < ninput; ++j) {
    int coord;
    dal_param_ref ref;
    if ((rc = resolve_input(sys, st, inputs[j], &coord, &ref)) != 0) goto done;
    double *col = R + (size_t)j * nk;
    if (coord >= 0)
      col[coord] = 1.0;
    else {
      residual_dp(sys, st, tg, f, &ref, col);
      for (int i = 0; i < n; ++i)
        col[i] = -col[i];
    }
  }
  // R columns now hold b_j = -dR/du_j: M dq'' + C dq' + K dq = b du (full space)
  if (m == 0) {
    rc = inputs_free_space(sys, st, tg, ninput, R, B, Af, Bf);
  } else {
    // reduced: B_r = N' b, and the first-order Bf = (0, M_r^-1 B_r) = (0, N' da) with da from
    // the KKT system [M G'; G 0] (da; -dlambda) = (b; 0)
    if ((rc = dal__tangent_reduced(sys, st, tg, N, Ar, Mr, NULL, NULL)) != 0) goto done;
    dal__gemm('T', 'N', (int)sk, (int)ni, n, N, n, R, (int)nk, Br, (int)sk);
    if (B) memcpy(B, Br, sk * ni * sizeof(double));
    if (Af) memcpy(Af, Ar, k2 * k2 * sizeof(double));
    if (Bf) {
      dal__tangent_kkt_solve(tg, ninput, R); // tg's LU factors are the reduction's
      for (size_t j = 0; j < ni; ++j)
        memset(Bf + j * k2, 0, sk * sizeof(double));
      dal__gemm('T', 'N', (int)sk, (int)ni, n, N, n, R, (int)nk, Bf + sk, (int)k2);
    }
  }
done:
  free(buf);
  dal__tangent_free(tg);
  return rc;
}
