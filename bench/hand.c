// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Hand-written equations of motion and a direct SUNDIALS (CVODE, ARKODE ERKStep) driver.
//
// Chain equations: Lagrange's equations of a planar chain of point masses in absolute link
// angles (e.g. Goldstein, Classical Mechanics, ch. 1-2); the O(N) form projects the link
// acceleration a_k - a_{k-1} on the link direction to get a tridiagonal system for the rod
// tensions. Integrators: CVODE (Hindmarsh et al., ACM TOMS 31, 2005) and ARKODE ERKStep
// (Reynolds et al., ACM TOMS 49, 2023), SUNDIALS 6.4.1.
#include "hand.h"

#include <arkode/arkode_butcher_erk.h>
#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <lapacke.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdlib.h>
#include <string.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

// the user function and its context, seen through SUNDIALS' callback signature
typedef struct hand_call {
  hand_rhs_fn *f;
  void *ctx;
} hand_call;

static int sun_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void *user) {
  const hand_call *c = user;
  return c->f(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot), c->ctx);
}

// Fehlberg 7(8) as the library runs it: ARKODE 6.4.1 reuses the last stage as the next
// first stage whenever c_s = 1, which Fehlberg's 13th stage has without being y_{n+1}; one
// appended stage equal to y_{n+1} (row b, c = 1, weight 0) makes that reuse exact, so the
// method keeps order 8 at 13 evaluations per step (coefficients: ARKODE's own table)
static int set_fehlberg_fsal(void *mem) {
  ARKodeButcherTable F = ARKodeButcherTable_LoadERK(ARKODE_FEHLBERG_13_7_8);
  if (!F) return -1;
  int s = F->stages;
  ARKodeButcherTable G = ARKodeButcherTable_Alloc(s + 1, SUNTRUE);
  if (!G) {
    ARKodeButcherTable_Free(F);
    return -1;
  }
  for (int i = 0; i < s; ++i) {
    G->c[i] = F->c[i];
    G->b[i] = F->b[i];
    G->d[i] = F->d[i];
    for (int j = 0; j < s; ++j)
      G->A[i][j] = F->A[i][j];
    G->A[s][i] = F->b[i];
  }
  G->c[s] = 1.0;
  G->b[s] = G->d[s] = 0.0;
  G->q = F->q;
  G->p = F->p;
  int rc = ERKStepSetTable(mem, G);
  ARKodeButcherTable_Free(G);
  ARKodeButcherTable_Free(F);
  return rc;
}

static int run_erk(SUNContext sctx, hand_call *call, N_Vector y, double t0, double t1,
                   dal_method method, double rtol, double atol, long max_steps, hand_stats *out) {
  void *mem = ERKStepCreate(sun_rhs, t0, y, sctx);
  if (!mem) return -1;
  int rc = method == DAL_METHOD_DOPRI5 ? ERKStepSetTableNum(mem, ARKODE_DORMAND_PRINCE_7_4_5)
                                       : set_fehlberg_fsal(mem);
  if (!rc) rc = ERKStepSetUserData(mem, call);
  if (!rc) rc = ERKStepSStolerances(mem, rtol, atol);
  if (!rc) rc = ERKStepSetMaxNumSteps(mem, max_steps);
  if (!rc) rc = ERKStepSetStopTime(mem, t1);
  double t = t0;
  if (!rc) rc = ERKStepEvolve(mem, t1, y, &t, ARK_NORMAL);
  long nst = 0, nfe = 0;
  ERKStepGetNumSteps(mem, &nst);
  ERKStepGetNumRhsEvals(mem, &nfe);
  out->steps = nst;
  out->rhs_evals = nfe;
  ERKStepFree(&mem);
  return rc < 0 ? rc : 0;
}

static int run_cvode(SUNContext sctx, hand_call *call, N_Vector y, double t0, double t1,
                     dal_method method, double rtol, double atol, long max_steps, hand_stats *out) {
  int adams = method == DAL_METHOD_ADAMS;
  void *mem = CVodeCreate(adams ? CV_ADAMS : CV_BDF, sctx);
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  SUNNonlinearSolver NLS = NULL;
  if (!mem) return -1;
  int rc = CVodeInit(mem, sun_rhs, t0, y);
  if (!rc) rc = CVodeSetUserData(mem, call);
  if (!rc) rc = CVodeSStolerances(mem, rtol, atol);
  if (!rc) rc = CVodeSetMaxNumSteps(mem, max_steps);
  if (!rc) rc = CVodeSetStopTime(mem, t1);
  if (!rc && adams) {
    // Adams with functional (fixed-point) iteration: no Jacobian
    NLS = SUNNonlinSol_FixedPoint(y, 0, sctx);
    rc = NLS ? CVodeSetNonlinearSolver(mem, NLS) : -1;
  } else if (!rc) {
    // BDF with Newton and a dense difference-quotient Jacobian
    sunindextype n = N_VGetLength(y);
    A = SUNDenseMatrix(n, n, sctx);
    LS = A ? SUNLinSol_Dense(y, A, sctx) : NULL;
    rc = LS ? CVodeSetLinearSolver(mem, LS, A) : -1;
  }
  double t = t0;
  if (!rc) rc = CVode(mem, t1, y, &t, CV_NORMAL);
  long nst = 0, nfe = 0, nfels = 0;
  CVodeGetNumSteps(mem, &nst);
  CVodeGetNumRhsEvals(mem, &nfe);
  if (!adams) CVodeGetNumLinRhsEvals(mem, &nfels);
  out->steps = nst;
  out->rhs_evals = nfe + nfels;
  CVodeFree(&mem);
  SUNNonlinSolFree(NLS);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  return rc < 0 ? rc : 0;
}

int hand_integrate(hand_rhs_fn *f, void *ctx, int n, double *y, double t0, double t1,
                   dal_method method, double rtol, double atol, long max_steps, hand_stats *out) {
  hand_stats dummy;
  if (!out) out = &dummy;
  memset(out, 0, sizeof *out);
  SUNContext sctx = NULL;
  if (SUNContext_Create(NULL, &sctx)) return out->status = -1;
  N_Vector v = N_VNew_Serial(n, sctx);
  if (!v) {
    SUNContext_Free(&sctx);
    return out->status = -1;
  }
  memcpy(N_VGetArrayPointer(v), y, (size_t)n * sizeof(double));
  hand_call call = {f, ctx};
  int rc;
  switch (method) {
  case DAL_METHOD_DOPRI5:
  case DAL_METHOD_FEHLBERG78:
    rc = run_erk(sctx, &call, v, t0, t1, method, rtol, atol, max_steps, out);
    break;
  case DAL_METHOD_ADAMS:
  case DAL_METHOD_BDF:
    rc = run_cvode(sctx, &call, v, t0, t1, method, rtol, atol, max_steps, out);
    break;
  default:
    rc = -1;
  }
  memcpy(y, N_VGetArrayPointer(v), (size_t)n * sizeof(double));
  N_VDestroy(v);
  SUNContext_Free(&sctx);
  out->status = rc;
  return rc;
}

hand_chain *hand_chain_create(int N, double g) {
  hand_chain *ch = calloc(1, sizeof *ch);
  if (!ch) return NULL;
  size_t n = (size_t)N;
  ch->N = N;
  ch->g = g;
  double **arr[] = {&ch->m,    &ch->l,   &ch->mu,  &ch->s, &ch->c,  &ch->b,
                    &ch->diag, &ch->off, &ch->rhs, &ch->T, &ch->ax, &ch->ay};
  for (size_t i = 0; i < sizeof arr / sizeof arr[0]; ++i)
    if (!(*arr[i] = calloc(n, sizeof(double)))) {
      hand_chain_destroy(ch);
      return NULL;
    }
  // the dense matrix only where it is affordable
  if (N <= 4096 && !(ch->M = calloc(n * n, sizeof(double)))) {
    hand_chain_destroy(ch);
    return NULL;
  }
  for (int i = 0; i < N; ++i)
    ch->m[i] = ch->l[i] = 1.0;
  for (int i = N - 1; i >= 0; --i)
    ch->mu[i] = ch->m[i] + (i + 1 < N ? ch->mu[i + 1] : 0.0);
  return ch;
}

void hand_chain_destroy(hand_chain *ch) {
  if (!ch) return;
  double *arr[] = {ch->m,   ch->l,   ch->mu, ch->s,  ch->c,  ch->b, ch->diag,
                   ch->off, ch->rhs, ch->T,  ch->ax, ch->ay, ch->M};
  for (size_t i = 0; i < sizeof arr / sizeof arr[0]; ++i)
    free(arr[i]);
  free(ch);
}

int hand_chain_rhs_dense(double t, const double *y, double *ydot, void *ctx) {
  (void)t;
  hand_chain *ch = ctx;
  int N = ch->N;
  const double *th = y, *w = y + N;
  double *M = ch->M, *b = ch->b, *lc = ch->c, *ls = ch->s, *l = ch->l, *mu = ch->mu;
  double *A = ch->ax, *B = ch->ay; // scratch: prefix sums of the velocity terms
  ch->nevals++;
  // sin and cos once per link, scaled by the link length
  for (int i = 0; i < N; ++i) {
    double si = sin(th[i]), ci = cos(th[i]);
    lc[i] = l[i] * ci;
    ls[i] = l[i] * si;
  }
  // lower triangle of M: M_ij = mu_i l_i l_j cos(th_i - th_j) for i >= j
  for (int j = 0; j < N; ++j) {
    double *col = M + (size_t)j * N;
    for (int i = j; i < N; ++i)
      col[i] = mu[i] * (lc[i] * lc[j] + ls[i] * ls[j]);
  }
  // c_i = l_i sum_j mu_max(i,j) l_j sin(th_i - th_j) w_j^2 = ls_i X_i - lc_i Y_i with
  // X_i = sum_j mu_max(i,j) lc_j w_j^2, Y_i likewise with ls_j: a prefix sum (j <= i, weight
  // mu_i) plus a suffix sum (j > i, weight mu_j), O(N) instead of O(N^2)
  double px = 0.0, py = 0.0;
  for (int i = 0; i < N; ++i) {
    double w2 = w[i] * w[i];
    px += lc[i] * w2;
    py += ls[i] * w2;
    A[i] = mu[i] * px;
    B[i] = mu[i] * py;
  }
  double sx = 0.0, sy = 0.0;
  for (int i = N - 1; i >= 0; --i) {
    b[i] = -ch->g * mu[i] * ls[i] - (ls[i] * (A[i] + sx) - lc[i] * (B[i] + sy));
    double w2 = w[i] * w[i];
    sx += mu[i] * lc[i] * w2;
    sy += mu[i] * ls[i] * w2;
  }
  // the same LAPACK calls as the library (the _work variants skip the NaN scans)
  if (LAPACKE_dpotrf_work(LAPACK_COL_MAJOR, 'L', N, M, N)) return -1;
  if (LAPACKE_dpotrs_work(LAPACK_COL_MAJOR, 'L', N, 1, M, N, b, N)) return -1;
  memcpy(ydot, w, (size_t)N * sizeof(double));
  memcpy(ydot + N, b, (size_t)N * sizeof(double));
  return 0;
}

int hand_chain_rhs_tridiag(double t, const double *y, double *ydot, void *ctx) {
  (void)t;
  hand_chain *ch = ctx;
  int N = ch->N;
  const double *th = y, *w = y + N;
  double *s = ch->s, *c = ch->c, *m = ch->m, *l = ch->l, *g = &ch->g;
  double *dg = ch->diag, *off = ch->off, *r = ch->rhs, *T = ch->T;
  ch->nevals++;
  for (int i = 0; i < N; ++i) {
    s[i] = sin(th[i]);
    c[i] = cos(th[i]);
  }
  // (a_k - a_{k-1}) . e_k = -l_k w_k^2 with a_k = F_k / m_k, e_k = (s_k, -c_k); negated:
  // (1/m_k + 1/m_{k-1}) T_k - (e_k.e_{k+1}/m_k) T_{k+1} - (e_{k-1}.e_k/m_{k-1}) T_{k-1}
  //   = l_k w_k^2 (+ g cos th_1 for the first link, whose pivot does not fall)
  for (int k = 0; k < N; ++k) {
    dg[k] = 1.0 / m[k] + (k > 0 ? 1.0 / m[k - 1] : 0.0);
    off[k] = k + 1 < N ? -(s[k] * s[k + 1] + c[k] * c[k + 1]) / m[k] : 0.0;
    r[k] = l[k] * w[k] * w[k] + (k == 0 ? *g * c[0] : 0.0);
  }
  // Thomas algorithm (symmetric positive definite, no pivoting needed)
  for (int k = 1; k < N; ++k) {
    double f = off[k - 1] / dg[k - 1];
    dg[k] -= f * off[k - 1];
    r[k] -= f * r[k - 1];
  }
  T[N - 1] = r[N - 1] / dg[N - 1];
  for (int k = N - 2; k >= 0; --k)
    T[k] = (r[k] - off[k] * T[k + 1]) / dg[k];
  // particle accelerations from the forces, then the angular ones
  double pax = 0.0, pay = 0.0;
  for (int k = 0; k < N; ++k) {
    double fx = -T[k] * s[k], fy = T[k] * c[k] - m[k] * *g;
    if (k + 1 < N) {
      fx += T[k + 1] * s[k + 1];
      fy -= T[k + 1] * c[k + 1];
    }
    double ax = fx / m[k], ay = fy / m[k];
    ydot[k] = w[k];
    ydot[N + k] = ((ax - pax) * c[k] + (ay - pay) * s[k]) / l[k];
    pax = ax;
    pay = ay;
  }
  return 0;
}

void hand_chain_positions(const hand_chain *ch, const double *y, double *r) {
  double x = 0.0, z = 0.0;
  for (int k = 0; k < ch->N; ++k) {
    x += ch->l[k] * sin(y[k]);
    z -= ch->l[k] * cos(y[k]);
    r[2 * k] = x;
    r[2 * k + 1] = z;
  }
}

int hand_ring_rhs(double t, const double *y, double *ydot, void *ctx) {
  (void)t;
  const double *p = ctx;
  double R = p[0], w = p[1], g = p[2];
  ydot[0] = y[1];
  ydot[1] = sin(y[0]) * (w * w * cos(y[0]) - g / R);
  return 0;
}

int hand_driven_rhs(double t, const double *y, double *ydot, void *ctx) {
  const double *p = ctx;
  double l = p[0], a = p[1], w = p[2], g = p[3];
  ydot[0] = y[1];
  ydot[1] = -(g - a * w * w * cos(w * t)) * sin(y[0]) / l;
  return 0;
}

int hand_spherical_rhs(double t, const double *y, double *ydot, void *ctx) {
  (void)t;
  double g = *(const double *)ctx;
  const double *r = y, *v = y + 3;
  double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  double rr = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
  double lam = (vv - g * r[2]) / rr;
  for (int i = 0; i < 3; ++i) {
    ydot[i] = v[i];
    ydot[3 + i] = -lam * r[i];
  }
  ydot[5] -= g;
  return 0;
}
