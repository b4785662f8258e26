// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// SUNDIALS IDA glue for the DAE formulations of form/dae.c (GGL, index-3, index-1): setup,
// tolerances, the residual and Newton-matrix callbacks, advance, and failures named.
//
// lambda and mu are algebraic and kept out of IDA's error test (IDASetId + IDASetSuppressAlg).
// The Newton matrix comes from form/dae.c (exact pieces, no difference quotients) with KLU, and
// with the dense solver when it is the whole Jacobian (dal__dae_newton_exact); otherwise the
// dense solver uses IDA's difference quotients.
#include <float.h>
#include <ida/ida.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#include <sunnonlinsol/sunnonlinsol_newton.h>

#include "form/form.h"
#include "integrate.h"
#include "nvec.h"

typedef struct ida_mem {
  const dal_system *sys;
  dal_state *st;
  dal_solve_opts opts;
  dal_dae f;                    // the formulation (sizes, residual, Newton matrix)
  int n, m, neq, off_l, off_mu; // copies of f's sizes
  int sparse, started;
  double rtol;   // the relative tolerance IDA runs at (calibrated and floored)
  double fscale; // the start's largest |lambda_r| (the multipliers' absolute tolerance)
  // the retreat to DAL_IDA_TOL_FLOOR after a failure below it: the time, the tolerance run
  // before, and the note for the state's message
  double raised_t, raised_from;
  char note[DAL_ERRMSG_LEN];
  double h0;        // the first step handed to IDA (0 until the first advance)
  double *sl, *smu; // (m each) how far a unit of lambda_r / mu_r moves v / q per unit step
  SUNContext ctx;
  void *ida;
  N_Vector y, yp, id, atol, w1, w2;
  SUNMatrix A;
  SUNLinearSolver LS, watch; // the dense or KLU solver, and the wrapper IDA calls (watch_*)
  // statistics already added to the state
  long nst, nre, nje, nni, netf, ncfn;
  // failures seen inside callbacks and from IDA's error handler
  int cb_status;
  char cb_msg[DAL_ERRMSG_LEN];
  char ida_msg[256];
  // for failure messages: the vector of the last linear solve (a Newton correction) and IDA's
  // current error weights (both IDA's own storage, alive while IDA is), the correction's
  // largest error-weighted component (index, weighted size), the start's rank check
  N_Vector ncor;
  const double *ewt;
  int ncor_i;
  double ncor_v;
  dal_constraint_report rank0;
  // dense output (driver.c): after every step from tprev to tcur, hook(hook_ctx)
  int (*hook)(void *ctx);
  void *hook_ctx;
  double tprev, tcur;
  // IDA's Newton solver on systems of DAL_IDA_UPKEEP_MIN unknowns and more (newton_solve), or
  // NULL (IDA's own)
  SUNNonlinearSolver nls;
  long nls_nni, nls_nsetups; // IDA's counts at the last Newton solve's start
  int nls_slow;              // solves in a row that took two or more iterations without a setup
} ida_mem;

static const char *form_name(dal_formulation f) {
  return f == DAL_FORM_INDEX3 ? "index-3" : f == DAL_FORM_INDEX1 ? "index-1" : "GGL";
}

// SUNDIALS messages are kept (for our error text), never printed
static void silent_handler(int code, const char *module, const char *function, char *msg,
                           void *data) {
  ida_mem *w = data;
  (void)code;
  (void)module;
  snprintf(w->ida_msg, sizeof w->ida_msg, "%s: %s", function, msg);
}

// name of unknown i for messages
static void unknown_name(const ida_mem *w, int i, char *buf, size_t len) {
  const dal_system *sys = w->sys;
  int n = w->n;
  if (i < n)
    snprintf(buf, len, "q[%d] (position coordinate '%s')", i, sys->coord_names[i]);
  else if (i < 2 * n)
    snprintf(buf, len, "v[%d] (velocity of '%s')", i - n, sys->coord_names[i - n]);
  else if (i == w->f.off_w)
    snprintf(buf, len, "W (the work of the non-potential forces)");
  else if (i < w->off_l + w->m)
    snprintf(buf, len, "lambda[%d] (multiplier of constraint '%s')", i - w->off_l,
             sys->con[sys->row_con[i - w->off_l]].name);
  else
    snprintf(buf, len, "mu[%d] (GGL's velocity multiplier of constraint '%s')", i - w->off_mu,
             sys->con[sys->row_con[i - w->off_mu]].name);
}

// map a callback status to IDA's convention and remember it
static int cb_fail(ida_mem *w, int rc) {
  if (rc == DAL__RECOVERABLE) return 1;
  w->cb_status = rc;
  memcpy(w->cb_msg, w->st->err, sizeof w->cb_msg);
  return -1;
}

static int residual(double t, N_Vector yy, N_Vector yp, N_Vector rr, void *data) {
  ida_mem *w = data;
  int rc = dal__dae_residual(&w->f, t, N_VGetArrayPointer(yy), N_VGetArrayPointer(yp),
                             N_VGetArrayPointer(rr));
  return rc ? cb_fail(w, rc) : 0;
}

static int jacobian(double t, double cj, N_Vector yy, N_Vector yp, N_Vector rr, SUNMatrix J,
                    void *data, N_Vector t1, N_Vector t2, N_Vector t3) {
  ida_mem *w = data;
  (void)yp;
  (void)rr;
  (void)t1;
  (void)t2;
  (void)t3;
  dal_dae_sink s = {w->sparse ? DAL_SINK_SPARSE : DAL_SINK_DENSE, 0, NULL,
                    w->sparse ? SM_DATA_S(J) : SM_DATA_D(J)};
  if (w->sparse) {
    // IDA zeroes the matrix, pattern included, before each call: write the pattern, and sum
    // the entries straight into its values
    sunindextype *cp = SM_INDEXPTRS_S(J), *ri = SM_INDEXVALS_S(J);
    for (int j = 0; j <= w->f.neq; ++j)
      cp[j] = w->f.pat.colptr[j];
    for (int k = 0; k < w->f.pat.nnz; ++k)
      ri[k] = w->f.pat.rowind[k];
    memset(SM_DATA_S(J), 0, (size_t)w->f.pat.nnz * sizeof(double));
  }
  int rc = dal__dae_newton(&w->f, t, cj, N_VGetArrayPointer(yy), &s);
  if (rc) return cb_fail(w, rc);
  return 0;
}

// The linear solver IDA sees: the dense or KLU solver, watched. The solution of each solve is
// a Newton correction; the vector holding it is remembered (no copy: a step costs nothing
// more), so that a convergence failure names the unknown that kept moving (newton_culprit),
// not a guess from the last step's error.
static ida_mem *watched(SUNLinearSolver S) { return S->content; }
static SUNLinearSolver_Type watch_type(SUNLinearSolver S) {
  return SUNLinSolGetType(watched(S)->LS);
}
static SUNLinearSolver_ID watch_id(SUNLinearSolver S) { return SUNLinSolGetID(watched(S)->LS); }
static int watch_init(SUNLinearSolver S) { return SUNLinSolInitialize(watched(S)->LS); }
static int watch_setup(SUNLinearSolver S, SUNMatrix A) { return SUNLinSolSetup(watched(S)->LS, A); }
static sunindextype watch_lastflag(SUNLinearSolver S) { return SUNLinSolLastFlag(watched(S)->LS); }
static int watch_solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, sunrealtype tol) {
  ida_mem *w = watched(S);
  w->ncor = x;
  return SUNLinSolSolve(w->LS, A, x, b, tol);
}

// after a convergence failure: the largest error-weighted component of the last correction
static void newton_culprit(ida_mem *w) {
  w->ncor_i = -1;
  w->ncor_v = 0.0;
  if (!w->ncor || !w->ewt) return;
  const double *dx = N_VGetArrayPointer(w->ncor);
  for (int i = 0; i < w->neq; ++i)
    if (fabs(dx[i] * w->ewt[i]) > w->ncor_v) {
      w->ncor_v = fabs(dx[i] * w->ewt[i]);
      w->ncor_i = i;
    }
}
static SUNLinearSolver watch_create(ida_mem *w) {
  SUNLinearSolver S = SUNLinSolNewEmpty(w->ctx);
  if (!S) return NULL;
  S->content = w;
  S->ops->gettype = watch_type;
  S->ops->getid = watch_id;
  S->ops->initialize = watch_init;
  S->ops->setup = watch_setup;
  S->ops->solve = watch_solve;
  S->ops->lastflag = watch_lastflag;
  return S;
}

// Error weights. q and v (and W): 1 / (rtol |y_i| + atol_i), IDA's own rule. The multipliers
// are out of the error test but in the Newton convergence test, where IDA weighs them like
// any unknown. An index-2 multiplier is determined by the iteration only to cj times the
// rounding of its constraint row: a correction d lambda moves v by h M^-1 G' d lambda and
// changes the residual G v + phi_t by h G M^-1 G' d lambda, so rounding eps |G v| in that row
// comes back as d lambda ~ eps |G v| / (h |G M^-1 G'|) (docs/dae.md: 3e-10 at h = 3e-7 on the
// spherical pendulum, against a weight asking 2e-11). Weighted by its own size the multiplier
// fails the convergence test from rounding alone, IDA shrinks h, cj grows, and the start
// collapses. So a multiplier is weighed by what it does to the differential unknowns over
// the step: d lambda_r is small enough when h sl_r d lambda_r is within v's tolerance (mu_r:
// h smu_r d mu_r within q's) times DAL_IDA_MULT_SHARE, and never tighter than by its own size
// (rtol |lambda_r| + atol).
static int ewt_fn(N_Vector yv, N_Vector ewt, void *data) {
  ida_mem *w = data;
  const double *y = N_VGetArrayPointer(yv), *at = N_VGetArrayPointer(w->atol);
  double *e = N_VGetArrayPointer(ewt);
  int n = w->n, m = w->m;
  w->ewt = e;
  double tq = INFINITY, tv = INFINITY;
  for (int i = 0; i < w->neq; ++i) {
    double tol = w->rtol * fabs(y[i]) + at[i];
    if (!(tol > 0.0)) return -1;
    e[i] = 1.0 / tol;
    if (i < n)
      tq = fmin(tq, tol);
    else if (i < 2 * n)
      tv = fmin(tv, tol);
  }
  if (w->f.form == DAL_FORM_INDEX3 || !w->sl) return 0;
  double h = 0.0;
  IDAGetCurrentStep(w->ida, &h);
  h = fabs(h);
  if (!(h > 0.0)) h = w->h0;
  if (!(h > 0.0)) return 0;
  // the share of v's (q's) tolerance a multiplier's correction may take
  h /= DAL_IDA_MULT_SHARE;
  for (int r = 0; r < m; ++r) {
    int il = w->off_l + r;
    if (w->sl[r] > 0.0) e[il] = fmin(e[il], w->sl[r] * h / tv);
    if (w->off_mu >= 0 && w->smu[r] > 0.0) {
      int im = w->off_mu + r;
      e[im] = fmin(e[im], w->smu[r] * h / tq);
    }
  }
  return 0;
}

// ---------------------------------------------------------------------------------------

void dal__ida_free(void *mem) {
  ida_mem *w = mem;
  if (!w) return;
  if (w->ida) IDAFree(&w->ida);
  if (w->nls) SUNNonlinSolFree(w->nls);
  if (w->watch) SUNLinSolFreeEmpty(w->watch);
  if (w->LS) SUNLinSolFree(w->LS);
  if (w->A) SUNMatDestroy(w->A);
  N_Vector vs[] = {w->y, w->yp, w->id, w->atol, w->w1, w->w2};
  for (size_t i = 0; i < sizeof vs / sizeof vs[0]; ++i)
    if (vs[i]) N_VDestroy(vs[i]);
  if (w->ctx) SUNContext_Free(&w->ctx);
  free(w->sl);
  dal__dae_free(&w->f);
  free(w);
}

// y and y' from the state's consistent (t, q, qdot, qddot, lambda)
static void load_y(ida_mem *w) {
  const dal_state *st = w->st;
  int n = w->n, m = w->m;
  double *y = N_VGetArrayPointer(w->y), *yp = N_VGetArrayPointer(w->yp);
  memset(y, 0, (size_t)w->neq * sizeof(double));
  memset(yp, 0, (size_t)w->neq * sizeof(double));
  memcpy(y, st->q, (size_t)n * sizeof(double));
  memcpy(y + n, st->qdot, (size_t)n * sizeof(double));
  if (m) memcpy(y + w->off_l, st->lambda, (size_t)m * sizeof(double));
  memcpy(yp, st->qdot, (size_t)n * sizeof(double));
  memcpy(yp + n, st->qddot, (size_t)n * sizeof(double));
  if (w->f.off_w >= 0) {
    y[w->f.off_w] = st->W;
    yp[w->f.off_w] = st->power; // the start is evaluated with DAL_P_ALL (power included)
  }
}

// a SUNDIALS setup call; on a negative flag the state's message names the call (returns)
#define IDA_CHECK(call)                                                                            \
  do {                                                                                             \
    int f_ = (call);                                                                               \
    if (f_ < 0) {                                                                                  \
      w->st->stats.foreign_code = f_;                                                              \
      return DAL_FAIL(w->st, DAL_E_SOLVER, "IDA setup failed in %s (flag %d): %s", #call, f_,      \
                      w->ida_msg);                                                                 \
    }                                                                                              \
  } while (0)

// the forms and systems IDA runs; 0 or DAL_E_UNSUPPORTED with the state's message set
static int check_form(const dal_system *sys, dal_state *st, const dal_solve_opts *opts,
                      dal_formulation form) {
  if (form != DAL_FORM_GGL && form != DAL_FORM_INDEX3 && form != DAL_FORM_INDEX1)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "the DAE integrator (IDA) runs the GGL, index-3 and index-1 forms, not "
                    "'%s'",
                    dal_formulation_name(form));
  if (form == DAL_FORM_INDEX1 && opts->project)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "the index-1 form with projection runs with the ODE methods (DOPRI5, "
                    "Fehlberg 7(8), Bulirsch-Stoer, Adams), not with BDF in IDA; with BDF use "
                    "Baumgarte terms (opts.baumgarte_alpha/beta) or the GGL form");
  if (sys->lag)
    return DAL_FAIL(st, DAL_E_UNSUPPORTED,
                    "a Lagrangian system has no particles or constraints for the DAE "
                    "integrator; use an ODE method");
  return 0;
}

// the workspace: the formulation and its sizes, the calibrated tolerance, the linear solver's
// kind and the SUNDIALS context; 0 and *out, or a status (nothing left allocated)
static int mem_create(const dal_system *sys, dal_state *st, const dal_solve_opts *opts,
                      dal_formulation form, const dal_constraint_report *rank0, ida_mem **out) {
  ida_mem *w = calloc(1, sizeof *w);
  if (!w) return DAL_FAIL(st, DAL_E_NOMEM, "IDA: out of memory");
  w->rank0 = *rank0;
  w->ncor_i = -1;
  w->sys = sys;
  w->st = st;
  w->opts = *opts;
  if (dal__dae_init(&w->f, sys, st, form, opts->baumgarte_alpha, opts->baumgarte_beta,
                    opts->work)) {
    free(w);
    return DAL_FAIL(st, DAL_E_NOMEM, "IDA: out of memory");
  }
  w->n = w->f.n;
  w->m = w->f.m;
  w->neq = w->f.neq;
  w->off_l = w->f.off_l;
  w->off_mu = w->f.off_mu;
  // the calibrated tolerance (solve.h), no lower than IDA is tried at; below
  // DAL_IDA_TOL_FLOOR a failed step retreats to it (raise_floor); a clamp is reported in the
  // statistics
  double fac = dal__dae_tol_factor(form);
  w->rtol = fmax(fac * opts->rtol, DAL_IDA_TOL_TRY);
  st->stats.rtol_used = w->rtol;
  w->sparse =
      opts->linsol == DAL_LINSOL_KLU ||
      (opts->linsol == DAL_LINSOL_AUTO && (w->neq >= opts->sparse_threshold || !sys->dense_M));
  if (SUNContext_Create(NULL, &w->ctx) != 0) {
    dal__dae_free(&w->f);
    free(w);
    return DAL_FAIL(st, DAL_E_NOMEM, "IDA: cannot create the SUNDIALS context");
  }
  *out = w;
  return 0;
}

// IDA's vectors with the library's kernels; IDA's work vectors are clones of these and
// inherit them. 0 or DAL_E_NOMEM (what was made is freed by dal__ida_free)
static int vectors_create(ida_mem *w) {
  sunindextype neq = w->neq;
  w->y = N_VNew_Serial(neq, w->ctx);
  w->yp = N_VNew_Serial(neq, w->ctx);
  w->id = N_VNew_Serial(neq, w->ctx);
  w->atol = N_VNew_Serial(neq, w->ctx);
  w->w1 = N_VNew_Serial(neq, w->ctx);
  w->w2 = N_VNew_Serial(neq, w->ctx);
  if (!w->y || !w->yp || !w->id || !w->atol || !w->w1 || !w->w2)
    return DAL_FAIL(w->st, DAL_E_NOMEM, "IDA: out of memory for %d unknowns", w->neq);
  N_Vector vs[] = {w->y, w->yp, w->id, w->atol, w->w1, w->w2};
  for (size_t i = 0; i < sizeof vs / sizeof vs[0]; ++i)
    dal__nvec_fast(vs[i]);
  return 0;
}

// error test on q and v; lambda and mu (algebraic) out of it. Index-3 keeps only q in
// the error test, the usual practice for the higher-index variables of a BDF code (Brenan,
// Campbell and Petzold, sec. 5.4): with v in it the steps collapse at rtol <= 1e-6.
// Absolute tolerances: opts.atol for q and v; multipliers and mu get loose ones, they only
// weigh Newton corrections. Then the multipliers' reach for their error weights (ewt_fn).
// the absolute tolerances for the current w->rtol (set again when it is raised)
static void atol_fill(ida_mem *w) {
  const dal_solve_opts *opts = &w->opts;
  double *at = N_VGetArrayPointer(w->atol);
  // a clamped rtol raises atol in proportion: the requested ratio atol / rtol is kept
  double atol = opts->atol * (w->rtol / opts->rtol);
  for (int i = 0; i < w->neq; ++i)
    at[i] = atol;
  for (int r = 0; r < w->m; ++r) {
    at[w->off_l + r] = fmax(atol, w->rtol * fmax(w->fscale, 1.0));
    if (w->off_mu >= 0) at[w->off_mu + r] = fmax(atol, sqrt(opts->atol));
  }
}

// 0 or DAL_E_NOMEM
static int weights_set(ida_mem *w) {
  double *id = N_VGetArrayPointer(w->id);
  w->fscale = 0.0;
  for (int r = 0; r < w->m; ++r)
    w->fscale = fmax(w->fscale, fabs(w->st->lambda[r]));
  dal__dae_mask(&w->f, id);
  atol_fill(w);
  // the multipliers' reach
  if (w->m > 0) {
    w->sl = malloc(2 * (size_t)w->m * sizeof(double));
    if (!w->sl || dal__dae_row_scales(&w->f, w->sl, w->sl + w->m))
      return DAL_FAIL(w->st, DAL_E_NOMEM, "IDA: out of memory for %d constraint rows", w->m);
    w->smu = w->sl + w->m;
  }
  return 0;
}

// IDA's Newton solver (SUNDIALS' own, behind IDA's convergence test) with one change: IDA
// rebuilds the Newton matrix only when cj moved, so at a steady step size the matrix ages
// while the motion turns, and every step comes to need a second iteration (the Cartesian
// chain at 724 links, rtol 1e-6: 287 iterations in 138 steps with 8 matrices). After
// DAL_IDA_STALE_SOLVES solves in a row that each took two or more iterations without a new
// matrix, this solve starts with a new one (IDA's own setup, which resets its cj and rate).
static int newton_solve(SUNNonlinearSolver nls, N_Vector y0, N_Vector ycor, N_Vector wt,
                        realtype tol, booleantype setup, void *mem) {
  void *ud = NULL;
  long nni = 0, nsetups = 0;
  IDAGetUserData(mem, &ud);
  IDAGetNumNonlinSolvIters(mem, &nni);
  IDAGetNumLinSolvSetups(mem, &nsetups);
  ida_mem *w = ud;
  // the solve before this one: its iterations, and whether it had a new matrix
  if (nsetups != w->nls_nsetups || nni - w->nls_nni < 2)
    w->nls_slow = 0;
  else
    w->nls_slow++;
  w->nls_nni = nni;
  w->nls_nsetups = nsetups;
  if (w->nls_slow >= DAL_IDA_STALE_SOLVES) {
    setup = SUNTRUE;
    w->nls_slow = 0;
  }
  return SUNNonlinSolSolve_Newton(nls, y0, ycor, wt, tol, setup, mem);
}

// IDA itself on the loaded y, y': residual, error weights, algebraic mask, step bounds
static int ida_setup(ida_mem *w) {
  const dal_solve_opts *opts = &w->opts;
  w->ida = IDACreate(w->ctx);
  if (!w->ida) return DAL_FAIL(w->st, DAL_E_NOMEM, "IDA: IDACreate failed (out of memory)");
  IDA_CHECK(IDASetErrHandlerFn(w->ida, silent_handler, w));
  IDA_CHECK(IDAInit(w->ida, residual, w->st->t, w->y, w->yp));
  IDA_CHECK(IDAWFtolerances(w->ida, ewt_fn));
  IDA_CHECK(IDASetUserData(w->ida, w));
  IDA_CHECK(IDASetId(w->ida, w->id));
  IDA_CHECK(IDASetSuppressAlg(w->ida, SUNTRUE));
  IDA_CHECK(IDASetMaxNumSteps(w->ida, opts->max_steps > 0 ? opts->max_steps : 1000000));
  if (opts->hmax > 0) IDA_CHECK(IDASetMaxStep(w->ida, opts->hmax));
  if (opts->hmin > 0) IDA_CHECK(IDASetMinStep(w->ida, opts->hmin));
  if (w->neq < DAL_IDA_UPKEEP_MIN) return 0;
  // the Newton upkeep of larger systems (bounds.h): a Newton matrix is rebuilt on a 5% change
  // of cj, and a matrix that keeps needing a second iteration is rebuilt (newton_solve)
  IDA_CHECK(IDASetDeltaCjLSetup(w->ida, DAL_IDA_DCJ));
  w->nls = SUNNonlinSol_Newton(w->y, w->ctx);
  if (!w->nls) return DAL_FAIL(w->st, DAL_E_NOMEM, "IDA: cannot create the Newton solver");
  w->nls->ops->solve = newton_solve;
  IDA_CHECK(IDASetNonlinearSolver(w->ida, w->nls));
  return 0;
}

// the KLU or dense linear solver behind the watch wrapper, and the Newton matrix callback
// where it is exact
static int linsol_setup(ida_mem *w) {
  sunindextype neq = w->neq;
  if (w->sparse) {
    if (dal__dae_pattern(&w->f))
      return DAL_FAIL(w->st, DAL_E_NOMEM, "IDA: out of memory for the sparse Jacobian");
    w->A = SUNSparseMatrix(neq, neq, w->f.pat.nnz, CSC_MAT, w->ctx);
    w->LS = w->A ? SUNLinSol_KLU(w->y, w->A, w->ctx) : NULL;
  } else {
    w->A = SUNDenseMatrix(neq, neq, w->ctx);
    w->LS = w->A ? SUNLinSol_Dense(w->y, w->A, w->ctx) : NULL;
  }
  if (w->LS) w->watch = watch_create(w);
  if (!w->A || !w->LS || !w->watch)
    return DAL_FAIL(w->st, DAL_E_NOMEM, "IDA: cannot create the %s linear solver (%d unknowns)",
                    w->sparse ? "KLU" : "dense", w->neq);
  IDA_CHECK(IDASetLinearSolver(w->ida, w->watch, w->A));
  if (w->sparse || dal__dae_newton_exact(w->sys)) IDA_CHECK(IDASetJacFn(w->ida, jacobian));
  return 0;
}

int dal__ida_create(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, void **mem) {
  *mem = NULL;
  dal_formulation form = opts->form == DAL_FORM_AUTO ? DAL_FORM_GGL : opts->form;
  int rc = check_form(sys, st, opts, form);
  if (rc) return rc;
  // consistent start: rank check, projections, KKT accelerations and multipliers
  dal_constraint_report rank0;
  rc = dal__dae_start_checked(sys, st, opts->init_max_move, NULL, &rank0);
  if (rc) return rc;
  // the workspace and context, the vectors, the weights, IDA, the linear solver
  ida_mem *w = NULL;
  rc = mem_create(sys, st, opts, form, &rank0, &w);
  if (rc) return rc;
  rc = vectors_create(w);
  if (!rc) rc = weights_set(w);
  if (!rc) {
    load_y(w);
    rc = ida_setup(w);
  }
  if (!rc) rc = linsol_setup(w);
  if (rc) {
    dal__ida_free(w);
    return rc;
  }
  *mem = w;
  return DAL_OK;
}

// add IDA's counters since the last call to the state's statistics
static void update_stats(ida_mem *w, int flag) {
  dal_stats *s = &w->st->stats;
  long nst = 0, nre = 0, nje = 0, nni = 0, netf = 0, ncfn = 0, nreLS = 0;
  IDAGetNumSteps(w->ida, &nst);
  IDAGetNumResEvals(w->ida, &nre);
  IDAGetNumJacEvals(w->ida, &nje);
  IDAGetNumLinResEvals(w->ida, &nreLS);
  IDAGetNumNonlinSolvIters(w->ida, &nni);
  IDAGetNumErrTestFails(w->ida, &netf);
  IDAGetNumNonlinSolvConvFails(w->ida, &ncfn);
  nre += nreLS;
  s->steps += nst - w->nst;
  s->rhs_evals += nre - w->nre;
  s->jac_evals += nje - w->nje;
  s->nonlin_iters += nni - w->nni;
  s->rejected += (netf - w->netf) + (ncfn - w->ncfn);
  w->nst = nst;
  w->nre = nre;
  w->nje = nje;
  w->nni = nni;
  w->netf = netf;
  w->ncfn = ncfn;
  double h = 0.0;
  if (IDAGetLastStep(w->ida, &h) == IDA_SUCCESS && h != 0.0) s->last_h = h;
  s->foreign_code = flag;
}

// the state at (t, y) evaluated as after dal_forward
static int finish_state(ida_mem *w, double t, const double *y) {
  dal_state *st = w->st;
  if (w->f.off_w >= 0) st->W = y[w->f.off_w];
  st->t = t;
  memcpy(st->q, y, (size_t)w->n * sizeof(double));
  memcpy(st->qdot, y + w->n, (size_t)w->n * sizeof(double));
  dal__state_moved(st);
  return dal__public_status(dal__eval(w->sys, st, DAL_P_ALL));
}

// the component dominating the weighted local error estimate (differential ones first)
static int dominating(ida_mem *w) {
  if (IDAGetErrWeights(w->ida, w->w1) != IDA_SUCCESS ||
      IDAGetEstLocalErrors(w->ida, w->w2) != IDA_SUCCESS)
    return -1;
  const double *ew = N_VGetArrayPointer(w->w1), *le = N_VGetArrayPointer(w->w2);
  int best = -1;
  double bmax = -1.0;
  for (int pass = 0; pass < 2 && best < 0; ++pass)
    for (int i = pass ? 2 * w->n : 0; i < (pass ? w->neq : 2 * w->n); ++i) {
      double e = fabs(ew[i] * le[i]);
      if (e > bmax && e > 0.0) {
        bmax = e;
        best = i;
      }
    }
  return best;
}

// the fallback form named as the remedy of a failure at a regular point (solve.h)
#define IDA_FALLBACK_REMEDY                                                                        \
  "the index-1 form with projection and Bulirsch-Stoer goes on where IDA stops "                   \
  "(DAL_FORM_INDEX1, opts.project = 1, DAL_METHOD_BS; the default options fall back to it)"

// what IDA's failure flag means and its usual remedy; *ask: the constraints could be to blame
static int failure_kind(const ida_mem *w, int flag, const char **what, const char **remedy,
                        int *ask) {
  *ask = 0;
  switch (flag) {
  case IDA_TOO_MUCH_WORK:
    *what = "too many steps before the target time";
    *remedy = "raise opts.max_steps, or loosen the tolerances";
    return DAL_E_MAXSTEPS;
  case IDA_TOO_MUCH_ACC:
    *what = "the tolerances are too tight for double precision";
    *remedy = "loosen rtol/atol";
    return DAL_E_STEP;
  case IDA_ERR_FAIL:
    // a collapse of the step size at a regular point: the fallback form is the remedy
    // (solve.h), a discontinuous force the other suspect (issue 31: not "loosen")
    *ask = 1;
    *what = "repeated error-test failures (step size underflow)";
    *remedy = IDA_FALLBACK_REMEDY ", or check the forces for discontinuities";
    return DAL_E_STEP;
  case IDA_CONV_FAIL:
  case IDA_NLS_FAIL:
    *ask = 1;
    *what = "Newton failed repeatedly";
    *remedy = IDA_FALLBACK_REMEDY;
    return DAL_E_CONV;
  case IDA_LINIT_FAIL:
  case IDA_LSETUP_FAIL:
  case IDA_LSOLVE_FAIL:
    *ask = 1;
    *what = "the linear solver failed (singular iteration matrix)";
    *remedy = "check that every mass is positive";
    return DAL_E_SOLVER;
  case IDA_RES_FAIL:
  case IDA_FIRST_RES_FAIL:
    *what = "the residual evaluation failed";
    *remedy = "see the cause below";
    return w->cb_status ? w->cb_status : DAL_E_CALLBACK;
  case IDA_REP_RES_ERR:
    *what = "a callback asked for smaller steps repeatedly";
    *remedy = "check the callback's domain";
    return DAL_E_CALLBACK;
  default:
    *what = "IDA failed";
    *remedy = "see IDA's message";
    return DAL_E_SOLVER;
  }
}

// A constraint whose gradient nearly vanishes at the state (max_j |G_rj| below
// DAL_IDA_DEP_DROP times the start's, which the relative rank test cannot see): a singular
// point of that constraint (a cusp). Writes the verdict and returns 1 if one is found.
static int vanishing_row(ida_mem *w, char *buf, size_t len) {
  int m = w->m, worst = -1;
  double *g = malloc(2 * (size_t)m * sizeof(double)), ratio = DAL_IDA_DEP_DROP;
  if (!g || dal__dae_row_scales(&w->f, g, g + m)) {
    free(g);
    return 0;
  }
  for (int r = 0; r < m; ++r)
    if (w->smu[r] > 0.0 && g[m + r] < ratio * w->smu[r]) {
      ratio = g[m + r] / w->smu[r];
      worst = r;
    }
  if (worst >= 0)
    snprintf(buf, len,
             "the gradient of constraint '%s' nearly vanishes here (max |dphi/dq| %.3g, %.3g at "
             "the start), a singular point of it; check the constraints",
             w->sys->con[w->sys->row_con[worst]].name, g[m + worst], w->smu[worst]);
  free(g);
  return worst >= 0;
}

// Are the constraints to blame? dal_check_constraints at the state (the last accepted step):
// dependent rows, or gradients whose smallest pivot ratio fell below DAL_IDA_DEP_DROP times
// the start's (becoming dependent: a singular point), or one that nearly vanishes, or nothing
// wrong. The verdict goes into
// buf; returns 1 when the constraints are the culprit.
static int constraint_verdict(ida_mem *w, char *buf, size_t len) {
  dal_state *st = w->st;
  char keep[DAL_ERRMSG_LEN];
  memcpy(keep, st->err, sizeof keep);
  dal_constraint_report rep;
  int rc = dal_check_constraints(w->sys, st, &rep), blame = 0;
  if (rc == DAL_E_CONSTRAINT) {
    snprintf(buf, len, "the constraint check fails here: %.260s; fix or remove them", st->err);
    blame = 1;
  } else if (rc != DAL_OK || rep.rank < 0) {
    snprintf(buf, len, "the constraints were not checked here (%s)",
             rc ? dal_status_name(rc) : "too many rows for the rank test");
  } else if (rep.rmin < DAL_IDA_DEP_DROP * w->rank0.rmin) {
    snprintf(buf, len,
             "the constraints become dependent: the smallest pivot ratio of their gradients "
             "(dal_check_constraints' rank test) fell from %.3g at the start to %.3g here, a "
             "singular configuration; check the constraints",
             w->rank0.rmin, rep.rmin);
    blame = 1;
  } else if ((blame = vanishing_row(w, buf, len)) == 0) {
    snprintf(buf, len,
             "the constraints pass dal_check_constraints here (rank %d of %d, smallest pivot "
             "ratio %.3g, %.3g at the start): not their defect",
             rep.rank, rep.m, rep.rmin, w->rank0.rmin);
  }
  memcpy(st->err, keep, sizeof keep);
  return blame;
}

// The failure message: the state's time (its last accepted step) and the step IDA tried, what
// failed, the unknown that dominated (the last Newton correction for a convergence failure,
// the local error estimate otherwise), the constraints' verdict where they could be to blame,
// the remedy, and IDA's own words.
static int map_failure(ida_mem *w, int flag, double hfail) {
  dal_state *st = w->st;
  const char *what, *remedy;
  int ask, code = failure_kind(w, flag, &what, &remedy, &ask);
  if (code == DAL_E_CONV) newton_culprit(w);
  char var[320] = "error dominated by no variable", name[160];
  int conv = code == DAL_E_CONV && w->ncor_i >= 0, dom = conv ? w->ncor_i : dominating(w);
  if (dom >= 0) unknown_name(w, dom, name, sizeof name);
  if (conv)
    snprintf(var, sizeof var, "correction dominated by %s (%.3g x its tolerance)", name, w->ncor_v);
  else if (dom >= 0)
    snprintf(var, sizeof var, "error dominated by %s", name);
  char verdict[DAL_ERRMSG_LEN] = "";
  if (ask && w->m > 0 && constraint_verdict(w, verdict, sizeof verdict)) remedy = "";
  char cause[DAL_ERRMSG_LEN] = "", tres[160] = "";
  if (code == w->cb_status && w->cb_status)
    snprintf(cause, sizeof cause, "; cause: %.400s", w->cb_msg);
  // far from t = 0, a step of a few ulps of t: the clock cannot resolve the motion here
  if (fabs(st->t) > 1.0 && fabs(hfail) < 64.0 * DBL_EPSILON * fabs(st->t))
    snprintf(tres, sizeof tres, ", %.0f ulps of t (restart the clock near t = 0)",
             fabs(hfail) / (DBL_EPSILON * fabs(st->t)));
  return DAL_FAIL(st, code,
                  "IDA (%s, %s) at t=%.17g (last accepted step), h=%.3g%s: %s; %s; "
                  "%s%s%s%s [IDA flag %d: %.120s]",
                  form_name(w->f.form), w->sparse ? "KLU" : "dense", st->t, hfail, tres, what, var,
                  verdict, verdict[0] && remedy[0] ? "; " : "", remedy, cause, flag, w->ida_msg);
}

// A step failed below DAL_IDA_TOL_FLOOR (the Newton iteration or the error test, where
// rounding may dominate at such tolerances on some scenes): IDA restarts from its last
// accepted step at the floor, and the note says so. 1 when it restarted, 0 when the failure
// stands (at or above the floor already, a callback's failure, or IDA refused the restart)
static int raise_floor(ida_mem *w, int flag) {
  if (w->rtol >= DAL_IDA_TOL_FLOOR || w->cb_status ||
      (flag != IDA_ERR_FAIL && flag != IDA_CONV_FAIL && flag != IDA_TOO_MUCH_ACC))
    return 0;
  double t = 0.0, h = 0.0;
  if (IDAGetCurrentTime(w->ida, &t) != IDA_SUCCESS ||
      IDAGetDky(w->ida, t, 0, w->y) != IDA_SUCCESS || IDAGetDky(w->ida, t, 1, w->yp) != IDA_SUCCESS)
    return 0;
  IDAGetLastStep(w->ida, &h);
  w->raised_from = w->rtol;
  w->raised_t = t;
  w->rtol = DAL_IDA_TOL_FLOOR;
  w->st->stats.rtol_used = w->rtol;
  atol_fill(w);
  if (IDAReInit(w->ida, t, w->y, w->yp) != IDA_SUCCESS) return 0;
  // IDAReInit restarts IDA's counters (update_stats adds the differences)
  w->nst = w->nre = w->nje = w->nni = w->netf = w->ncfn = 0;
  if (h != 0.0) IDASetInitStep(w->ida, h);
  w->cb_status = 0;
  w->ida_msg[0] = 0;
  w->ncor = NULL;
  snprintf(w->note, sizeof w->note,
           "note: IDA's step failed at t=%.17g at the local tolerance %g (below its floor %g, "
           "where rounding can stall the Newton iteration): it continued from there at the "
           "floor (dal_stats.rtol_used), so expect errors above rtol from there on",
           t, w->raised_from, DAL_IDA_TOL_FLOOR);
  return 1;
}

const char *dal__ida_note(const void *mem) {
  const ida_mem *w = mem;
  return w->note;
}

int dal__ida_advance(const dal_system *sys, dal_state *st, void *mem, double tout) {
  ida_mem *w = mem;
  (void)sys;
  DAL_ASSERT(w && w->st == st && w->sys == sys);
  double t0 = st->t;
  if (tout == t0) return finish_state(w, t0, N_VGetArrayPointer(w->y));
  if (!w->started) {
    // IDA's own first step is ~1e-16 at tight tolerances and fails: start near 0.1 sqrt(rtol)
    double h0 = w->opts.h0 > 0 ? w->opts.h0 : DAL_IDA_H0_FACTOR * sqrt(w->rtol);
    if (w->opts.hmax > 0 && h0 > w->opts.hmax) h0 = w->opts.hmax;
    if (h0 > fabs(tout - t0)) h0 = fabs(tout - t0);
    IDASetInitStep(w->ida, tout > t0 ? h0 : -h0);
    w->h0 = h0;
    w->started = 1;
  }
  w->cb_status = 0;
  w->ida_msg[0] = 0;
  w->ncor = NULL;
  // progress guard: no step below a few ulps of t (IDA would otherwise creep towards a point
  // it cannot pass, e.g. a callback that keeps returning > 0 or a constraint that becomes
  // unsatisfiable, with a million steps that do not move t); opts.hmin when larger
  double hmin = fmax(w->opts.hmin, DAL_TINY_STEP(fmax(fabs(t0), fabs(tout))));
  IDASetMinStep(w->ida, w->opts.hmax > 0 ? fmin(hmin, w->opts.hmax) : hmin);
  double tret = t0;
  int flag;
retry:
  IDASetStopTime(w->ida, tout);
  if (w->hook) {
    // one step at a time, the driver's hook after each (dense output, events)
    w->tcur = t0;
    for (;;) {
      flag = IDASolve(w->ida, tout, &tret, w->y, w->yp, IDA_ONE_STEP);
      update_stats(w, flag);
      if (flag < 0 && raise_floor(w, flag)) goto retry;
      if (flag < 0) break;
      if (flag == IDA_TSTOP_RETURN) tret = tout;
      w->tprev = w->tcur;
      w->tcur = tret;
      int rc = w->hook(w->hook_ctx);
      if (rc) return rc;
      if (tret >= tout) return finish_state(w, tout, N_VGetArrayPointer(w->y));
    }
  } else {
    flag = IDASolve(w->ida, tout, &tret, w->y, w->yp, IDA_NORMAL);
    update_stats(w, flag);
    if (flag < 0 && raise_floor(w, flag)) goto retry;
  }
  if (flag >= 0) return finish_state(w, tret, N_VGetArrayPointer(w->y));
  // failure: the last accepted step, then the message naming time and variable (and, for
  // repeated recoverable residual failures, the callback that asked last: its message is
  // still the state's)
  char recov[DAL_ERRMSG_LEN] = "";
  if (flag == IDA_REP_RES_ERR) memcpy(recov, st->err, sizeof recov);
  double tcur = t0;
  IDAGetCurrentTime(w->ida, &tcur);
  if (IDAGetDky(w->ida, tcur, 0, w->w1) == IDA_SUCCESS) {
    char keep[DAL_ERRMSG_LEN];
    memcpy(keep, st->err, sizeof keep);
    if (finish_state(w, tcur, N_VGetArrayPointer(w->w1)) != 0) memcpy(st->err, keep, sizeof keep);
  }
  double hcur = 0.0;
  IDAGetCurrentStep(w->ida, &hcur);
  int rc = map_failure(w, flag, hcur);
  if (w->note[0]) {
    size_t used = strlen(st->err);
    snprintf(st->err + used, sizeof st->err - used,
             "; it had run at the local tolerance %g until t=%.17g, then at its floor %g",
             w->raised_from, w->raised_t, DAL_IDA_TOL_FLOOR);
  }
  if (recov[0]) {
    char msg[DAL_ERRMSG_LEN];
    snprintf(msg, sizeof msg, "%.200s; it kept asking while IDA shrank the step: %.260s", recov,
             st->err);
    memcpy(st->err, msg, sizeof msg);
  }
  return rc;
}

void dal__ida_set_hook(void *mem, int (*hook)(void *ctx), void *ctx) {
  ida_mem *w = mem;
  w->hook = hook;
  w->hook_ctx = ctx;
}

void dal__ida_window(const void *mem, double *t0, double *t1) {
  const ida_mem *w = mem;
  *t0 = w->tprev;
  *t1 = w->tcur;
}

int dal__ida_place(void *mem, double t) {
  ida_mem *w = mem;
  dal_state *st = w->st;
  // the step's end is IDA's solution itself; inside, its interpolating polynomial
  const double *y = N_VGetArrayPointer(w->y);
  if (t != w->tcur) {
    int flag = IDAGetDky(w->ida, t, 0, w->w1);
    if (flag != IDA_SUCCESS)
      return DAL_FAIL(st, DAL_E_SOLVER,
                      "IDA could not interpolate at t=%.17g in the step [%.17g, %.17g] (code %d)",
                      t, w->tprev, w->tcur, flag);
    y = N_VGetArrayPointer(w->w1);
  }
  if (w->f.off_w >= 0) st->W = y[w->f.off_w];
  st->t = t;
  memcpy(st->q, y, (size_t)w->n * sizeof(double));
  memcpy(st->qdot, y + w->n, (size_t)w->n * sizeof(double));
  dal__state_moved(st);
  return DAL_OK;
}
