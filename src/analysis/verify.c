// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Verification kit: user jet functions against central differences (a test oracle only), and
// model checks at a state (M SPD, Q = -dU/dq, Lagrange residual of a path, constraint rank).
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/base.h"

#define DAL_VERIFY_COOKIE 0x0fe41f1e

dal_verify_opts dal_default_verify_opts(void) {
  dal_verify_opts d, *o = &d;
  memset(o, 0, sizeof *o);
  o->nsamples = 16;
  o->lo = -1.0;
  o->hi = 1.0;
  o->t_lo = 0.0;
  o->t_hi = 1.0;
  o->h = 1e-3;
  o->tol_factor = 10.0;
  o->seed = 1;
  o->cookie = DAL_VERIFY_COOKIE;
  return d;
}

// ---------------------------------------------------------------------------------------
// one vector function f(in, t) over jets, whatever the user's signature

typedef struct vfun {
  const char *what;
  int nin, nout;
  int kind; // 0 primitive, 1 map, 2 potential r, 3 potential q, 4 Lagrangian
  const dal_primitive *prim;
  const double *param;
  union {
    dal_map_fn *map;
    dal_potential_r_fn *potr;
    dal_potential_q_fn *potq;
    dal_lagrangian_fn *lag;
  } fn;
  void *ctx;
} vfun;

static int vf_eval(const vfun *f, const dal_jet *in, dal_jet t, dal_jet *out) {
  switch (f->kind) {
  case 0:
    return f->prim->eval(in, t, f->param, out, f->ctx);
  case 1:
    return f->fn.map(in, t, out, f->ctx);
  case 2:
    return f->fn.potr(in, t, out, f->ctx);
  case 3:
    return f->fn.potq(in, t, out, f->ctx);
  default:
    return f->fn.lag(t, in, in + f->nin / 2, out, f->ctx);
  }
}

static double urand(unsigned long long *s) {
  *s ^= *s >> 12;
  *s ^= *s << 25;
  *s ^= *s >> 27;
  return (double)((*s * 2685821657736338717ULL) >> 11) * 0x1.0p-53;
}

// values of f at x + s u (value-only jets) into out (nout)
static int at(const vfun *f, const double *x, double t, const double *u, double s, dal_jet *jin,
              dal_jet *out, double *val) {
  for (int i = 0; i < f->nin; ++i)
    jin[i] = dal_const(x[i] + s * u[i]);
  int rc = vf_eval(f, jin, dal_const(t + s * u[f->nin]), out);
  if (rc) return rc;
  for (int r = 0; r < f->nout; ++r)
    val[r] = out[r].v;
  return 0;
}

// the derived bound of a central difference (see verify.h) and the comparison
static void compare(dal_verify_report *rep, const dal_verify_opts *o, int r, int order, double jet,
                    double dh, double dh2, double epsf, double h, double t) {
  double bound = fabs(dh - dh2) / 3.0 + (order == 1 ? 2.0 * epsf / h : 16.0 * epsf / (h * h));
  double err = fabs(jet - dh2), ratio = err / bound;
  if (!(bound > 0)) ratio = err > 0 ? INFINITY : 0.0;
  rep->checks++;
  if (!(ratio <= o->tol_factor)) rep->failures++;
  if (rep->checks == 1 || !(ratio <= rep->worst)) {
    rep->worst = ratio;
    rep->worst_output = r;
    rep->worst_order = order;
    rep->worst_jet = jet;
    rep->worst_fd = dh2;
    rep->worst_bound = bound;
    rep->worst_t = t;
  }
}

// the workspace of check_fun: a point x (nin) and direction u (nin + 1, t last), the values at
// 0, +-h, +-h/2 along u (nout each), jets in and out
typedef struct vwork {
  int nin, nout;
  double *x, *u, *f0, *fp, *fm, *fp2, *fm2;
  dal_jet *jin, *jout;
} vwork;

// a random point and a random unit direction over (inputs, t) into w->x, w->u and *t; returns
// the scale max(1, |x|, |t|)
static double random_point(vwork *w, const dal_verify_opts *o, unsigned long long *seed,
                           double *t) {
  int nin = w->nin;
  double xmax = 1.0, un = 0.0, *x = w->x, *u = w->u;
  for (int i = 0; i < nin; ++i) {
    double lo = o->in_lo ? o->in_lo[i] : o->lo, hi = o->in_hi ? o->in_hi[i] : o->hi;
    x[i] = lo + (hi - lo) * urand(seed);
    xmax = fmax(xmax, fabs(x[i]));
  }
  *t = o->t_lo + (o->t_hi - o->t_lo) * urand(seed);
  xmax = fmax(xmax, fabs(*t));
  for (int i = 0; i <= nin; ++i) {
    u[i] = 2.0 * urand(seed) - 1.0;
    un += u[i] * u[i];
  }
  un = sqrt(un);
  for (int i = 0; i <= nin; ++i)
    u[i] /= un;
  return xmax;
}

// sample s at (w->x, t) along w->u: the jets against central differences at h and h/2 of
// every output; 0 or the status that ends the check (rep->msg set)
static int check_sample(const vfun *f, const dal_verify_opts *o, vwork *w, int s, double t,
                        double xmax, dal_verify_report *rep) {
  int nin = w->nin, nout = w->nout;
  double *x = w->x, *u = w->u;
  dal_jet *jin = w->jin, *jout = w->jout;
  // the jets along u
  for (int i = 0; i < nin; ++i)
    jin[i] = dal_var(x[i], u[i]);
  int rc = vf_eval(f, jin, dal_var(t, u[nin]), jout), status = DAL_OK;
  if (rc) {
    snprintf(rep->msg, sizeof rep->msg, "%s: evaluation failed (returned %d) at sample %d, t=%g",
             f->what, rc, s, t);
    return DAL_E_CALLBACK;
  }
  rep->samples++;
  dal_jet J[64];
  int nkeep = nout < 64 ? nout : 64;
  for (int r = 0; r < nout; ++r) {
    if (!dal_jet_isfinite(jout[r])) {
      rep->failures++;
      snprintf(rep->msg, sizeof rep->msg,
               "%s: output %d is not finite (%g, %g, %g) at sample %d, t=%g; restrict the "
               "input ranges to the function's domain",
               f->what, r, jout[r].v, jout[r].d, jout[r].dd, s, t);
      status = DAL_E_DOMAIN;
    }
    if (r < nkeep) J[r] = jout[r];
  }
  if (status) return status;
  // central differences at h and h/2
  double h = o->h * xmax, *f0 = w->f0, *fp = w->fp, *fm = w->fm, *fp2 = w->fp2, *fm2 = w->fm2;
  if ((rc = at(f, x, t, u, 0.0, jin, jout, f0)) || (rc = at(f, x, t, u, h, jin, jout, fp)) ||
      (rc = at(f, x, t, u, -h, jin, jout, fm)) || (rc = at(f, x, t, u, 0.5 * h, jin, jout, fp2)) ||
      (rc = at(f, x, t, u, -0.5 * h, jin, jout, fm2))) {
    snprintf(rep->msg, sizeof rep->msg,
             "%s: evaluation failed (returned %d) near sample %d, t=%g; shrink opts.h or the "
             "input ranges",
             f->what, rc, s, t);
    return DAL_E_CALLBACK;
  }
  for (int r = 0; r < nout; ++r) {
    // outputs beyond 64 are re-evaluated one at a time only for the jet (rare)
    dal_jet jr = r < nkeep ? J[r] : dal_const(NAN);
    if (r >= nkeep) {
      for (int i = 0; i < nin; ++i)
        jin[i] = dal_var(x[i], u[i]);
      if (vf_eval(f, jin, dal_var(t, u[nin]), jout) == 0) jr = jout[r];
    }
    double fmag = fmax(fmax(fabs(f0[r]), fabs(fp[r])), fmax(fabs(fm[r]), xmax));
    double epsf = 64.0 * DBL_EPSILON * fmag;
    double d1h = (fp[r] - fm[r]) / (2.0 * h), d1h2 = (fp2[r] - fm2[r]) / h;
    double d2h = (fp[r] - 2.0 * f0[r] + fm[r]) / (h * h);
    double d2h2 = (fp2[r] - 2.0 * f0[r] + fm2[r]) / (0.25 * h * h);
    compare(rep, o, r, 1, jr.d, d1h, d1h2, epsf, h, t);
    compare(rep, o, r, 2, jr.dd, d2h, d2h2, epsf, h, t);
  }
  return DAL_OK;
}

static int check_fun(const vfun *f, const dal_verify_opts *opts, dal_verify_report *out) {
  dal_verify_opts o;
  if (opts)
    o = *opts;
  else
    o = dal_default_verify_opts();
  dal_verify_report local, *rep = out ? out : &local;
  memset(rep, 0, sizeof *rep);
  rep->worst_output = -1;
  if (o.cookie != DAL_VERIFY_COOKIE) {
    snprintf(rep->msg, sizeof rep->msg,
             "%s: options were not initialized: start from dal_default_verify_opts()", f->what);
    return DAL_E_ARG;
  }
  if (f->nin < 0 || f->nout < 1 || o.nsamples < 1 || !(o.h > 0) || !(o.tol_factor > 0) ||
      !isfinite(o.lo) || !isfinite(o.hi) || !isfinite(o.t_lo) || !isfinite(o.t_hi)) {
    snprintf(rep->msg, sizeof rep->msg, "%s: invalid sizes or options", f->what);
    return DAL_E_ARG;
  }
  int nin = f->nin, nout = f->nout, status = DAL_OK;
  // one block: x, u (nin + 1), values at 5 points (5 nout), jets in (nin), out (nout)
  size_t nd = (size_t)nin * 2 + 1 + (size_t)nout * 5, nj = (size_t)nin + (size_t)nout;
  vwork w = {.nin = nin, .nout = nout};
  w.x = malloc(nd * sizeof(double) + 1);
  w.jin = malloc(nj * sizeof(dal_jet) + sizeof(dal_jet));
  if (!w.x || !w.jin) {
    free(w.x);
    free(w.jin);
    snprintf(rep->msg, sizeof rep->msg, "%s: out of memory", f->what);
    return DAL_E_NOMEM;
  }
  w.jout = w.jin + nin;
  w.u = w.x + nin;
  w.f0 = w.u + nin + 1;
  w.fp = w.f0 + nout;
  w.fm = w.fp + nout;
  w.fp2 = w.fm + nout;
  w.fm2 = w.fp2 + nout;
  unsigned long long seed = o.seed ? o.seed : 1;
  for (int s = 0; s < o.nsamples && status == DAL_OK; ++s) {
    double t = 0.0, xmax = random_point(&w, &o, &seed, &t);
    status = check_sample(f, &o, &w, s, t, xmax, rep);
  }
  free(w.x);
  free(w.jin);
  if (status == DAL_OK && rep->failures) status = DAL_E_VERIFY;
  if (status == DAL_OK || status == DAL_E_VERIFY)
    snprintf(rep->msg, sizeof rep->msg,
             "%s: %s; worst entry output %d, %s derivative: jet %.9g vs central differences "
             "%.9g (bound %.2g, %.2g x bound, pass <= %g) at t=%g; %d samples, %d entries, %d "
             "failed",
             f->what, status ? "jets DISAGREE with finite differences" : "jets agree",
             rep->worst_output, rep->worst_order == 1 ? "first" : "second", rep->worst_jet,
             rep->worst_fd, rep->worst_bound, rep->worst, o.tol_factor, rep->worst_t, rep->samples,
             rep->checks, rep->failures);
  return status;
}

int dal_verify_primitive(const dal_primitive *prim, const double *param, void *ctx,
                         const dal_verify_opts *o, dal_verify_report *rep) {
  if (!prim || !prim->eval) return DAL_E_ARG;
  if (prim->version < 1 || prim->version > DAL_PRIMITIVE_VERSION) return DAL_E_ARG;
  char what[96];
  snprintf(what, sizeof what, "primitive '%s'", prim->name ? prim->name : "(unnamed)");
  if (!param && prim->nparam > 0) {
    if (prim->version < 2 || !prim->param_defaults) return DAL_E_ARG;
    for (int i = 0; i < prim->nparam; ++i)
      if (isnan(prim->param_defaults[i])) return DAL_E_ARG; // a required parameter
    param = prim->param_defaults;
  }
  vfun f = {.what = what,
            .nin = prim->nin,
            .nout = prim->nout,
            .kind = 0,
            .prim = prim,
            .param = param,
            .ctx = ctx};
  return check_fun(&f, o, rep);
}

int dal_verify_map(dal_map_fn *fn, int n, int N, int d, const dal_verify_opts *o,
                   dal_verify_report *rep, void *ctx) {
  if (!fn || n < 1 || N < 1 || (d != 2 && d != 3)) return DAL_E_ARG;
  vfun f = {.what = "map r(q, t)", .nin = n, .nout = N * d, .kind = 1, .fn.map = fn, .ctx = ctx};
  return check_fun(&f, o, rep);
}

int dal_verify_potential_r(dal_potential_r_fn *fn, int N, int d, const dal_verify_opts *o,
                           dal_verify_report *rep, void *ctx) {
  if (!fn || N < 1 || (d != 2 && d != 3)) return DAL_E_ARG;
  vfun f = {
      .what = "potential U(r, t)", .nin = N * d, .nout = 1, .kind = 2, .fn.potr = fn, .ctx = ctx};
  return check_fun(&f, o, rep);
}

int dal_verify_potential_q(dal_potential_q_fn *fn, int n, const dal_verify_opts *o,
                           dal_verify_report *rep, void *ctx) {
  if (!fn || n < 1) return DAL_E_ARG;
  vfun f = {.what = "potential U(q, t)", .nin = n, .nout = 1, .kind = 3, .fn.potq = fn, .ctx = ctx};
  return check_fun(&f, o, rep);
}

int dal_verify_lagrangian(dal_lagrangian_fn *fn, int n, const dal_verify_opts *o,
                          dal_verify_report *rep, void *ctx) {
  if (!fn || n < 1) return DAL_E_ARG;
  vfun f = {.what = "Lagrangian L(t, q, qdot)",
            .nin = 2 * n,
            .nout = 1,
            .kind = 4,
            .fn.lag = fn,
            .ctx = ctx};
  return check_fun(&f, o, rep);
}

// ---------------------------------------------------------------------------------------
// model checks at a state

// smallest pivot^2 / largest diagonal of an in-place Cholesky of A (n x n, column-major)
static double chol_min_pivot(int n, double *A) {
  double dmax = 0.0, pmin = INFINITY;
  for (int i = 0; i < n; ++i)
    dmax = fmax(dmax, fabs(A[(size_t)i * n + i]));
  for (int j = 0; j < n; ++j) {
    double s = A[(size_t)j * n + j];
    for (int k = 0; k < j; ++k)
      s -= A[(size_t)k * n + j] * A[(size_t)k * n + j];
    pmin = fmin(pmin, s);
    if (!(s > 0)) return dmax > 0 ? s / dmax : -1.0;
    double l = sqrt(s);
    A[(size_t)j * n + j] = l;
    for (int i = j + 1; i < n; ++i) {
      double v = A[(size_t)j * n + i];
      for (int k = 0; k < j; ++k)
        v -= A[(size_t)k * n + i] * A[(size_t)k * n + j];
      A[(size_t)j * n + i] = v / l;
    }
  }
  return dmax > 0 ? pmin / dmax : -1.0;
}

// potential energy U at (t, q) with velocities qdot, on a scratch state
static int energy_at(const dal_system *sys, dal_state *w, double t, const double *q,
                     const double *qdot, double *U) {
  int rc = dal_state_set(sys, w, t, q, qdot);
  if (!rc) rc = dal_forward(sys, w);
  dal_energies en;
  if (!rc) rc = dal_state_energies(w, &en);
  if (!rc) *U = en.U;
  return rc;
}

typedef struct path_pt {
  const double *q, *qd, *qdd;
  int n;
} path_pt;

static int path_at(dal_jet t, dal_jet *q, void *ctx) {
  (void)t;
  const path_pt *p = ctx;
  for (int i = 0; i < p->n; ++i)
    q[i] = dal_jet_make(p->q[i], p->qd[i], p->qdd[i]);
  return 0;
}

#define PATH_K 12 // output intervals of the integrated path
#define PATH_DT                                                                                    \
  2e-3 // their length: 4th-order differences of q stay below 1e-8 relative for
       // frequencies up to ~20 rad/s, above the integration noise (rtol 1e-12)
#define PATH_TOL 1e-5

// the Lagrange residual of an integrated path, by 4th-order central differences of q(t)
static int check_path(const dal_system *sys, const dal_state *st, dal_state *w,
                      dal_model_report *rep) {
  int n = sys->n, rc;
  // positions and constraint forces at the K + 1 output times, their scales, and scratch
  size_t sz = (size_t)(PATH_K + 1) * (size_t)n;
  double *qc = malloc((2 * sz + (PATH_K + 1) + 3 * (size_t)n) * sizeof(double));
  if (!qc) return DAL_E_NOMEM;
  double *Qc = qc + sz, *scale = Qc + sz, *fd1 = scale + PATH_K + 1, *fd2 = fd1 + n, *res = fd2 + n;
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-12;
  o.method = DAL_METHOD_BS;
  if (sys->m) {
    o.form = DAL_FORM_INDEX1;
    o.project = 1;
  }
  double t0 = dal_state_time(st);
  rc = dal_state_set(sys, w, t0, dal_state_q(st), dal_state_qdot(st));
  if (!rc && sys->m) rc = dal_make_consistent(sys, w, 0.0, NULL);
  for (int k = 0; k <= PATH_K && !rc; ++k) {
    if (k) rc = dal_advance(sys, w, &o, t0 + k * PATH_DT);
    if (!rc) rc = dal_forward(sys, w);
    if (rc) break;
    memcpy(qc + (size_t)k * n, dal_state_q(w), (size_t)n * sizeof(double));
    dal_constraint_genforces(sys, w, Qc + (size_t)k * n);
    // scale of the equation's terms: |Q|, |c|, |M qddot|
    double sc = 1e-300;
    const double *M = dal_state_mass_matrix(w), *a = dal_state_qddot(w);
    for (int i = 0; i < n; ++i) {
      sc = fmax(sc, fmax(fabs(dal_state_genforces(w)[i]), fabs(dal_state_bias(w)[i])));
      sc = fmax(sc, fabs(Qc[(size_t)k * n + i]));
      if (M) {
        double s = 0.0;
        for (int j = 0; j < n; ++j)
          s += M[(size_t)j * n + i] * a[j];
        sc = fmax(sc, fabs(s));
      }
    }
    scale[k] = sc;
  }
  if (rc) {
    free(qc);
    return rc;
  }
  // interior points with two neighbours on each side
  double worst = 0.0;
  int wc = -1;
  for (int k = 2; k <= PATH_K - 2 && !rc; ++k) {
    const double *qm2 = qc + (size_t)(k - 2) * n, *qm1 = qc + (size_t)(k - 1) * n;
    const double *q0 = qc + (size_t)k * n, *qp1 = qc + (size_t)(k + 1) * n,
                 *qp2 = qc + (size_t)(k + 2) * n;
    for (int i = 0; i < n; ++i) {
      fd1[i] = (qm2[i] - 8.0 * qm1[i] + 8.0 * qp1[i] - qp2[i]) / (12.0 * PATH_DT);
      fd2[i] = (-qp2[i] + 16.0 * qp1[i] - 30.0 * q0[i] + 16.0 * qm1[i] - qm2[i]) /
               (12.0 * PATH_DT * PATH_DT);
    }
    path_pt p = {q0, fd1, fd2, n};
    rc = dal_lagrange_residual(sys, w, path_at, t0 + k * PATH_DT, res, &p);
    for (int i = 0; i < n && !rc; ++i) {
      double r = fabs(res[i] - Qc[(size_t)k * n + i]) / scale[k];
      if (r > worst) {
        worst = r;
        wc = i;
      }
    }
  }
  free(qc);
  if (rc) return rc;
  rep->path_residual = worst;
  rep->path_coord = wc;
  rep->path_checked = 1;
  return DAL_OK;
}

// the first failed check of dal_verify_model and why
typedef struct verdict {
  const char *fail;
  char why[200];
} verdict;

// M symmetric positive definite (A: n x n scratch for its factor)
static void check_mass(const dal_state *st, int n, double *A, dal_model_report *rep, verdict *v) {
  const double *M = dal_state_mass_matrix(st);
  if (!M) return;
  double mmax = 0.0, asym = 0.0;
  for (size_t i = 0; i < (size_t)n * n; ++i)
    mmax = fmax(mmax, fabs(M[i]));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < i; ++j)
      asym = fmax(asym, fabs(M[(size_t)j * n + i] - M[(size_t)i * n + j]));
  rep->mass_asym = mmax > 0 ? asym / mmax : 0.0;
  memcpy(A, M, (size_t)n * n * sizeof(double));
  rep->mass_pivot = chol_min_pivot(n, A);
  rep->mass_checked = 1;
  if (rep->mass_asym > 1e-12) {
    v->fail = "mass matrix";
    snprintf(v->why, sizeof v->why, "M is not symmetric (max |M_ij - M_ji| / max |M| = %.3g)",
             rep->mass_asym);
  } else if (!(rep->mass_pivot > 1e-14)) {
    v->fail = "mass matrix";
    snprintf(v->why, sizeof v->why,
             "M is not positive definite (smallest Cholesky pivot^2 / max diagonal %.3g)",
             rep->mass_pivot);
  }
}

// Q against -dU/dq by differences of the energy at (q +- h e_j, qd) evaluated in w; the status
// of an evaluation that failed
static int check_forces(const dal_system *sys, const dal_state *st, dal_state *w, double t,
                        double *q, const double *qd, double tolf, dal_model_report *rep,
                        verdict *v) {
  int n = sys->n, rc = DAL_OK, wc = -1;
  double worst = 0.0;
  const double *Q = dal_state_genforces(st);
  for (int j = 0; j < n && !rc; ++j) {
    double qj = q[j], h = 1e-4 * fmax(1.0, fabs(qj)), U[4];
    const double s[4] = {h, -h, 0.5 * h, -0.5 * h};
    for (int k = 0; k < 4 && !rc; ++k) {
      q[j] = qj + s[k];
      rc = energy_at(sys, w, t, q, qd, &U[k]);
    }
    q[j] = qj;
    if (rc) return rc;
    double dh = (U[0] - U[1]) / (2 * h), dh2 = (U[2] - U[3]) / h;
    double epsf = 64.0 * DBL_EPSILON * fmax(1.0, fmax(fabs(U[0]), fabs(U[1])));
    double bound = fabs(dh - dh2) / 3.0 + 2.0 * epsf / h;
    double r = fabs(Q[j] + dh2) / bound;
    if (r > worst) {
      worst = r;
      wc = j;
    }
  }
  rep->force_err = worst;
  rep->force_coord = wc;
  rep->force_checked = 1;
  if (!v->fail && worst > tolf) {
    v->fail = "forces";
    snprintf(v->why, sizeof v->why,
             "Q of coordinate '%s' differs from -dU/dq by %.3g x the difference bound (a "
             "potential whose jets disagree with its values?)",
             sys->coord_names[wc], worst);
  }
  return DAL_OK;
}

// the constraint rank at the state (a rank defect is a failed check, not a status)
static int check_rank(const dal_system *sys, dal_state *st, dal_model_report *rep, verdict *v) {
  if (!sys->m) {
    rep->rank = 0;
    return DAL_OK;
  }
  dal_constraint_report cr;
  int crc = dal_check_constraints(sys, st, &cr);
  rep->rank = cr.rank;
  rep->rmin = cr.rmin;
  if (crc == DAL_E_CONSTRAINT && !v->fail) {
    v->fail = "constraints";
    snprintf(v->why, sizeof v->why, "%.190s", dal_state_errmsg(st));
  } else if (crc && crc != DAL_E_CONSTRAINT) {
    return crc;
  }
  return DAL_OK;
}

// the report's verdict and message
static void summarize(dal_model_report *rep, const verdict *v) {
  rep->passed = v->fail == NULL;
  if (v->fail)
    snprintf(rep->msg, sizeof rep->msg, "model check failed (%s): %s", v->fail, v->why);
  else
    snprintf(rep->msg, sizeof rep->msg,
             "model checks passed: M asym %.2g, pivot %.2g; Q vs -dU/dq %s %.2g x bound; path "
             "residual %.2g; rank %d of %d",
             rep->mass_asym, rep->mass_pivot, rep->force_checked ? "" : "(skipped)", rep->force_err,
             rep->path_residual, rep->rank, rep->m);
}

int dal_verify_model(const dal_system *sys, dal_state *st, const dal_verify_opts *opts,
                     dal_model_report *out) {
  dal_model_report local, *rep = out ? out : &local;
  memset(rep, 0, sizeof *rep);
  rep->force_coord = rep->path_coord = rep->rank = -1;
  rep->rmin = 1.0;
  // the (system, state) convention of state.h: no state is DAL_E_ARG, a NULL system or a state
  // of another system DAL_E_STATE with the message in the state; rep->msg says it too
  if (!st) {
    snprintf(rep->msg, sizeof rep->msg, "model check: the state is NULL");
    return DAL_E_ARG;
  }
  int pair = dal__check_pair(sys, st, "verify_model");
  if (pair) {
    snprintf(rep->msg, sizeof rep->msg, "model check: %.290s", dal_state_errmsg(st));
    return pair;
  }
  if (opts && opts->cookie != DAL_VERIFY_COOKIE) {
    snprintf(rep->msg, sizeof rep->msg,
             "model check: options were not initialized: start from dal_default_verify_opts()");
    return DAL_E_ARG;
  }
  double tolf = opts && opts->tol_factor > 0 ? opts->tol_factor : 10.0;
  int n = sys->n, rc = dal_forward(sys, st);
  if (rc) {
    snprintf(rep->msg, sizeof rep->msg, "model check: evaluation failed: %.250s",
             dal_state_errmsg(st));
    return rc;
  }
  rep->m = sys->m;
  double t = dal_state_time(st);
  double *buf = malloc(((size_t)n * n + 4 * (size_t)n + 1) * sizeof(double));
  dal_state *w = NULL;
  if (!buf || dal_state_create(sys, &w)) {
    free(buf);
    return DAL_E_NOMEM;
  }
  double *A = buf, *q = A + (size_t)n * n, *qd = q + n; // M's factor, the state's q, qdot
  memcpy(q, dal_state_q(st), (size_t)n * sizeof(double));
  memcpy(qd, dal_state_qdot(st), (size_t)n * sizeof(double));
  verdict v = {NULL, ""};
  // M symmetric positive definite
  check_mass(st, n, A, rep, &v);
  // Q against -dU/dq when every applied force is a potential force
  if (!sys->lag && !sys->ndamper && !sys->nforce && !sys->ngenforce) {
    rc = check_forces(sys, st, w, t, q, qd, tolf, rep, &v);
    if (rc) {
      snprintf(rep->msg, sizeof rep->msg, "model check: evaluation near the state failed: %.240s",
               dal_state_errmsg(w));
      goto done;
    }
  }
  // the Lagrange residual of a short integrated path
  rc = check_path(sys, st, w, rep);
  if (rc) {
    snprintf(rep->msg, sizeof rep->msg, "model check: integrating the path failed: %.240s",
             dal_state_errmsg(w));
    goto done;
  }
  if (!v.fail && rep->path_residual > PATH_TOL) {
    v.fail = "path";
    snprintf(v.why, sizeof v.why,
             "the Lagrange residual of an integrated path is %.3g (relative) on coordinate '%s' "
             "(pass below %g)",
             rep->path_residual, sys->coord_names[rep->path_coord], PATH_TOL);
  }
  // constraint rank at the state
  rc = check_rank(sys, st, rep, &v);
  if (rc) goto done;
  summarize(rep, &v);
  rc = v.fail ? DAL_E_VERIFY : DAL_OK;
done:
  dal_state_destroy(w);
  free(buf);
  int frc = dal_forward(sys, st); // leave the state evaluated where it was
  return rc ? rc : frc;
}
