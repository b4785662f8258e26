// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// DAE integration of redundant coordinates through SUNDIALS IDA: GGL, index-3 and index-1.
//
// Unknowns y = (q, v, lambda[, mu]) with residuals (Gear, Gupta and Leimkuhler, J. Comput.
// Appl. Math. 12-13, 1985; Hairer and Wanner, Solving ODEs II, VII.1-VII.3; Brenan, Campbell
// and Petzold, Numerical Solution of IVPs in DAEs, SIAM 1996):
//   GGL:    q' - v + G' mu,  M v' - (Q - c) - G' lambda,  G v + phi_t,  phi
//   index3: q' - v,          M v' - (Q - c) - G' lambda,  phi
//   index1: q' - v,          M v' - (Q - c) - G' lambda,
//           G v' + gamma_phi + 2 alpha (G v + phi_t) + beta^2 phi
// lambda and mu are algebraic and kept out of IDA's error test (IDASetId + IDASetSuppressAlg);
// index-3 keeps v out of it too (the error test then sees q only).
// Small systems use IDA's dense solver with its difference-quotient Newton matrix; large ones
// KLU with a Newton matrix assembled here in compressed columns from exact pieces: M, G, G',
// and the geometric stiffness sum_i w_i Hess(phi_i) of each constraint, computed from jets by
// polarization within its local inputs (the curvature of non-Cartesian particle maps and the
// derivatives of applied forces are left out of the Newton matrix, never out of the residual).
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

#include "dae_internal.h"
#include "solve_internal.h"

typedef struct ida_mem {
  const dal_system *sys;
  dal_state *st;
  dal_solve_opts opts;
  dal_formulation form;
  int n, m, neq, off_l, off_mu; // offsets of lambda and mu in y (mu: -1 unless GGL)
  int sparse, started;
  SUNContext ctx;
  void *ida;
  N_Vector y, yp, id, atol, w1, w2;
  SUNMatrix A;
  SUNLinearSolver LS;
  // sparse Newton matrix: pattern (CSC) and values
  int nnz, recording;
  long long nkeys;
  long long *keys;
  sunindextype *colptr, *rowind;
  double *val;
  // geometric-stiffness scratch
  int max_dep;
  double *H, *hv, *Ju, *tmp, *Hq, *dir, *udot, *g0;
  // statistics already added to the state
  long nst, nre, nje, nni, netf, ncfn;
  // failures seen inside callbacks and from IDA's error handler
  int cb_status;
  char cb_msg[DAL_ERRMSG_LEN];
  char ida_msg[256];
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
    snprintf(buf, len, "q[%d] (coordinate '%s')", i, sys->coord_names[i]);
  else if (i < 2 * n)
    snprintf(buf, len, "v[%d] (velocity of '%s')", i - n, sys->coord_names[i - n]);
  else if (i < w->off_l + w->m)
    snprintf(buf, len, "lambda[%d] (constraint '%s')", i - w->off_l,
             sys->con[sys->row_con[i - w->off_l]].name);
  else
    snprintf(buf, len, "mu[%d] (constraint '%s')", i - w->off_mu,
             sys->con[sys->row_con[i - w->off_mu]].name);
}

// map a callback status to IDA's convention and remember it
static int cb_fail(ida_mem *w, int rc) {
  if (rc == DAL__RECOVERABLE) return 1;
  w->cb_status = rc;
  memcpy(w->cb_msg, w->st->err, sizeof w->cb_msg);
  return -1;
}

// the state at (t, q, v) with kinematics, constraint rows and forces (M applied through J)
static int eval_at(ida_mem *w, double t, const double *y) {
  const dal_system *sys = w->sys;
  dal_state *st = w->st;
  st->t = t;
  memcpy(st->q, y, (size_t)w->n * sizeof(double));
  memcpy(st->qdot, y + w->n, (size_t)w->n * sizeof(double));
  dal__state_moved(st);
  // the residual applies M through the particle Jacobians: no dense assembly
  return dal__eval(sys, st, DAL_P_KIN | DAL_P_J | DAL_P_CON | DAL_P_DYN);
}

static int residual(double t, N_Vector yy, N_Vector yp, N_Vector rr, void *data) {
  ida_mem *w = data;
  const dal_system *sys = w->sys;
  dal_state *st = w->st;
  int n = w->n, m = w->m;
  const double *y = N_VGetArrayPointer(yy), *yd = N_VGetArrayPointer(yp);
  double *F = N_VGetArrayPointer(rr);
  int rc = eval_at(w, t, y);
  if (rc) return cb_fail(w, rc);
  const double *v = y + n, *lam = y + w->off_l, *vd = yd + n;
  double *Fq = F, *Fv = F + n, *Fl = F + w->off_l;
  // Fq = q' - v (+ G' mu)
  if (w->form == DAL_FORM_GGL && m)
    dal__gt_apply(sys, st, y + w->off_mu, Fq);
  else
    memset(Fq, 0, (size_t)n * sizeof(double));
  for (int i = 0; i < n; ++i)
    Fq[i] += yd[i] - v[i];
  // Fv = M v' - (Q - c) - G' lambda
  dal__mass_apply(sys, st, vd, Fv);
  double *gl = m ? dal__kkt_scratch(st, 0) : NULL; // no KKT workspace when m = 0
  if (m) dal__gt_apply(sys, st, lam, gl);
  for (int i = 0; i < n; ++i)
    Fv[i] -= st->Q[i] - st->c[i] + (m ? gl[i] : 0.0);
  // constraint rows
  if (w->form == DAL_FORM_GGL) {
    for (int r = 0; r < m; ++r) {
      Fl[r] = st->phidot[r];
      F[w->off_mu + r] = st->phi[r];
    }
  } else if (w->form == DAL_FORM_INDEX3) {
    if (m) memcpy(Fl, st->phi, (size_t)m * sizeof(double));
  } else {
    double al = w->opts.baumgarte_alpha, be = w->opts.baumgarte_beta;
    memset(Fl, 0, (size_t)m * sizeof(double));
    for (int ci = 0; ci < sys->ncon; ++ci) {
      const dal_con *c = &sys->con[ci];
      const int *dc = sys->cdep + c->dep_off;
      const double *Gc = st->G + c->g_off;
      for (int r = 0; r < c->prim->nout; ++r)
        for (int k = 0; k < c->ndep; ++k)
          Fl[c->row + r] += Gc[r * c->ndep + k] * vd[dc[k]];
    }
    for (int r = 0; r < m; ++r)
      Fl[r] += st->gphi[r] + 2.0 * al * st->phidot[r] + be * be * st->phi[r];
  }
  return 0;
}

// ---------------------------------------------------------------------------------------
// sparse Newton matrix dF/dy + cj dF/dy'

static int find_entry(const ida_mem *w, int row, int col) {
  int lo = (int)w->colptr[col], hi = (int)w->colptr[col + 1] - 1;
  while (lo <= hi) {
    int mid = (lo + hi) / 2;
    if (w->rowind[mid] == row) return mid;
    if (w->rowind[mid] < row)
      lo = mid + 1;
    else
      hi = mid - 1;
  }
  return -1;
}

// one entry: counted, recorded (pattern) or accumulated (values)
static void jadd(ida_mem *w, int row, int col, double v) {
  if (w->recording) {
    if (w->keys) w->keys[w->nkeys] = (long long)col * w->neq + row;
    w->nkeys++;
    return;
  }
  int p = find_entry(w, row, col);
  DAL_ASSERT(p >= 0);
  w->val[p] += v;
}

// evaluate constraint c with inputs at their values plus directions dir (local, nin) and
// time rate tdot; results in st->jout
static int con_dir(ida_mem *w, const dal_con *c, const double *dir, double tdot) {
  const dal_system *sys = w->sys;
  dal_state *st = w->st;
  int d = sys->dim, k = 0;
  const int *parts = sys->ipool + c->part_off, *coords = sys->ipool + c->coord_off;
  for (int a = 0; a < c->npart; ++a)
    for (int b = 0; b < d; ++b, ++k)
      st->jin[k] = dal_var(st->r[parts[a] * d + b], dir[k]);
  for (int i = 0; i < c->ncoord; ++i, ++k)
    st->jin[k] = dal_var(st->q[coords[i]], dir[k]);
  int rc =
      c->prim->eval(st->jin, dal_var(st->t, tdot), sys->ppool + c->param_off, st->jout, c->ctx);
  if (rc) {
    char what[160];
    snprintf(what, sizeof what, "constraint '%s' ('%s')", c->name, c->prim->name);
    return dal__cb_status(st, rc, what);
  }
  return DAL_OK;
}

// local Hessians H (nout x nin x nin) and hv = H_ext (udot, 1) (nout x nin) of constraint c
static int con_curvature(ida_mem *w, const dal_con *c) {
  const dal_system *sys = w->sys;
  dal_state *st = w->st;
  int nin = c->prim->nin, nout = c->prim->nout, d = sys->dim, rc;
  const int *parts = sys->ipool + c->part_off, *coords = sys->ipool + c->coord_off;
  double *dir = w->dir, *H = w->H, *hv = w->hv;
  // local velocities udot
  int k = 0;
  for (int a = 0; a < c->npart; ++a)
    for (int b = 0; b < d; ++b)
      w->udot[k++] = st->v[parts[a] * d + b];
  for (int i = 0; i < c->ncoord; ++i)
    w->udot[k++] = st->qdot[coords[i]];
  memset(dir, 0, (size_t)nin * sizeof(double));
  // diagonal: along e_i
  for (int i = 0; i < nin; ++i) {
    dir[i] = 1.0;
    rc = con_dir(w, c, dir, 0.0);
    dir[i] = 0.0;
    if (rc) return rc;
    for (int r = 0; r < nout; ++r)
      H[(r * nin + i) * nin + i] = st->jout[r].dd;
  }
  // off-diagonal by polarization: along e_i + e_j
  for (int i = 0; i < nin; ++i)
    for (int j = i + 1; j < nin; ++j) {
      dir[i] = dir[j] = 1.0;
      rc = con_dir(w, c, dir, 0.0);
      dir[i] = dir[j] = 0.0;
      if (rc) return rc;
      for (int r = 0; r < nout; ++r) {
        double h = 0.5 * (st->jout[r].dd - H[(r * nin + i) * nin + i] - H[(r * nin + j) * nin + j]);
        H[(r * nin + i) * nin + j] = H[(r * nin + j) * nin + i] = h;
      }
    }
  // mixed with the motion: along (udot, 1) and (udot + e_i, 1)
  rc = con_dir(w, c, w->udot, 1.0);
  if (rc) return rc;
  double *g0 = w->g0;
  for (int r = 0; r < nout; ++r)
    g0[r] = st->jout[r].dd;
  for (int i = 0; i < nin; ++i) {
    double keep = w->udot[i];
    w->udot[i] = keep + 1.0;
    rc = con_dir(w, c, w->udot, 1.0);
    w->udot[i] = keep;
    if (rc) return rc;
    for (int r = 0; r < nout; ++r) {
      hv[r * nin + i] = 0.5 * (st->jout[r].dd - g0[r] - H[(r * nin + i) * nin + i]);
    }
  }
  return DAL_OK;
}

// Ju (nin x ndep): derivative of the local inputs with respect to the dependency coordinates
static void local_chain(ida_mem *w, const dal_con *c) {
  const dal_system *sys = w->sys;
  const dal_state *st = w->st;
  int d = sys->dim, nin = c->prim->nin, nd = c->ndep;
  const int *dc = sys->cdep + c->dep_off;
  const int *parts = sys->ipool + c->part_off, *coords = sys->ipool + c->coord_off;
  memset(w->Ju, 0, (size_t)nin * (size_t)nd * sizeof(double));
  for (int a = 0; a < c->npart; ++a) {
    int p = parts[a];
    const int *dp = sys->pdep + sys->pdep_off[p];
    int ndp = sys->pdep_off[p + 1] - sys->pdep_off[p];
    const double *Jp = st->J + sys->pj_off[p];
    int col = 0;
    for (int cp = 0; cp < ndp; ++cp) {
      while (dc[col] != dp[cp])
        ++col;
      for (int b = 0; b < d; ++b)
        w->Ju[(a * d + b) * nd + col] = Jp[b * ndp + cp];
    }
  }
  for (int i = 0; i < c->ncoord; ++i) {
    int col = 0;
    while (dc[col] != coords[i])
      ++col;
    w->Ju[(c->npart * d + i) * nd + col] += 1.0;
  }
}

// Hq (nd x nd) = Ju' (sum_r wt_r H_r) Ju
static void chained_hessian(ida_mem *w, const dal_con *c, const double *wt) {
  int nin = c->prim->nin, nout = c->prim->nout, nd = c->ndep;
  double *Hs = w->tmp; // nin x nin then reused
  memset(Hs, 0, (size_t)nin * (size_t)nin * sizeof(double));
  for (int r = 0; r < nout; ++r)
    for (int i = 0; i < nin * nin; ++i)
      Hs[i] += wt[r] * w->H[r * nin * nin + i];
  for (int a = 0; a < nd; ++a)
    for (int b = 0; b < nd; ++b) {
      double s = 0.0;
      for (int i = 0; i < nin; ++i) {
        double ji = w->Ju[i * nd + a];
        if (ji == 0.0) continue;
        for (int j = 0; j < nin; ++j)
          s += ji * Hs[i * nin + j] * w->Ju[j * nd + b];
      }
      w->Hq[a * nd + b] = s;
    }
}

// all entries of the Newton matrix (pattern mode when recording)
static int assemble(ida_mem *w, double cj, const double *y) {
  const dal_system *sys = w->sys;
  dal_state *st = w->st;
  int n = w->n, d = sys->dim, rc;
  double al = w->opts.baumgarte_alpha, be = w->opts.baumgarte_beta;
  // q' and v in the q rows; cj M in the v rows
  for (int i = 0; i < n; ++i) {
    jadd(w, i, i, cj);
    jadd(w, i, n + i, -1.0);
  }
  for (int p = 0; p < sys->N; ++p) {
    const int *dp = sys->pdep + sys->pdep_off[p];
    int nd = sys->pdep_off[p + 1] - sys->pdep_off[p];
    const double *Jp = st->J + sys->pj_off[p];
    for (int a = 0; a < nd; ++a)
      for (int b = 0; b < nd; ++b) {
        double s = 0.0;
        for (int c = 0; c < d; ++c)
          s += Jp[c * nd + a] * Jp[c * nd + b];
        jadd(w, n + dp[a], n + dp[b], cj * sys->mass[p] * s);
      }
  }
  for (int ci = 0; ci < sys->ncon; ++ci) {
    const dal_con *c = &sys->con[ci];
    const int *dc = sys->cdep + c->dep_off;
    const double *Gc = st->G + c->g_off;
    int nout = c->prim->nout, nd = c->ndep, nin = c->prim->nin;
    // curvature terms (values only; the pattern is the constraint's dependency block)
    if (!w->recording) {
      rc = con_curvature(w, c);
      if (rc) return rc;
      local_chain(w, c);
    }
    for (int r = 0; r < nout; ++r) {
      int row = c->row + r;
      for (int k = 0; k < nd; ++k) {
        double g = Gc[r * nd + k];
        int j = dc[k];
        jadd(w, n + j, w->off_l + row, -g); // -G' lambda in the v rows
        if (w->form == DAL_FORM_GGL) {
          jadd(w, j, w->off_mu + row, g);    // G' mu in the q rows
          jadd(w, w->off_l + row, n + j, g); // G v
          jadd(w, w->off_mu + row, j, g);    // phi
        } else if (w->form == DAL_FORM_INDEX3) {
          jadd(w, w->off_l + row, j, g); // phi
        } else {
          jadd(w, w->off_l + row, n + j, (cj + 2.0 * al) * g); // G v' + 2 alpha G v
          jadd(w, w->off_l + row, j, be * be * g);             // beta^2 phi
        }
        // d(G v + phi_t)/dq = Ju' hv (GGL: q columns; index1: v and q columns)
        if (w->form != DAL_FORM_INDEX3) {
          double s = 0.0;
          if (!w->recording)
            for (int i = 0; i < nin; ++i)
              s += w->Ju[i * nd + k] * w->hv[r * nin + i];
          if (w->form == DAL_FORM_GGL) {
            jadd(w, w->off_l + row, j, s);
          } else {
            jadd(w, w->off_l + row, n + j, 2.0 * s);
            jadd(w, w->off_l + row, j, 2.0 * al * s);
          }
        }
      }
    }
    // geometric stiffness: -sum lambda_r H_r in the v rows, +sum mu_r H_r in the q rows
    if (!w->recording) chained_hessian(w, c, y + w->off_l + c->row);
    for (int a = 0; a < nd; ++a)
      for (int b = 0; b < nd; ++b)
        jadd(w, n + dc[a], dc[b], w->recording ? 0.0 : -w->Hq[a * nd + b]);
    if (w->form == DAL_FORM_GGL) {
      if (!w->recording) chained_hessian(w, c, y + w->off_mu + c->row);
      for (int a = 0; a < nd; ++a)
        for (int b = 0; b < nd; ++b)
          jadd(w, dc[a], dc[b], w->recording ? 0.0 : w->Hq[a * nd + b]);
    }
  }
  return DAL_OK;
}

static int cmp_ll(const void *x, const void *y) {
  long long a = *(const long long *)x, b = *(const long long *)y;
  return (a > b) - (a < b);
}

// the fixed sparsity pattern: count, record, sort, compress
static int build_pattern(ida_mem *w) {
  w->recording = 1;
  w->keys = NULL;
  w->nkeys = 0;
  assemble(w, 1.0, NULL);
  w->keys = malloc((size_t)(w->nkeys + 1) * sizeof(long long));
  if (!w->keys) return -1;
  w->nkeys = 0;
  assemble(w, 1.0, NULL);
  w->recording = 0;
  qsort(w->keys, (size_t)w->nkeys, sizeof(long long), cmp_ll);
  long long nu = 0;
  for (long long i = 0; i < w->nkeys; ++i)
    if (nu == 0 || w->keys[nu - 1] != w->keys[i]) w->keys[nu++] = w->keys[i];
  w->nnz = (int)nu;
  w->colptr = calloc((size_t)w->neq + 1, sizeof(sunindextype));
  w->rowind = malloc((size_t)(nu + 1) * sizeof(sunindextype));
  w->val = malloc((size_t)(nu + 1) * sizeof(double));
  if (!w->colptr || !w->rowind || !w->val) return -1;
  for (long long i = 0; i < nu; ++i) {
    w->rowind[i] = (sunindextype)(w->keys[i] % w->neq);
    w->colptr[w->keys[i] / w->neq + 1]++;
  }
  for (int j = 0; j < w->neq; ++j)
    w->colptr[j + 1] += w->colptr[j];
  free(w->keys);
  w->keys = NULL;
  return 0;
}

static int jacobian(double t, double cj, N_Vector yy, N_Vector yp, N_Vector rr, SUNMatrix J,
                    void *data, N_Vector t1, N_Vector t2, N_Vector t3) {
  ida_mem *w = data;
  (void)yp;
  (void)rr;
  (void)t1;
  (void)t2;
  (void)t3;
  const double *y = N_VGetArrayPointer(yy);
  int rc = eval_at(w, t, y);
  if (rc) return cb_fail(w, rc);
  memset(w->val, 0, (size_t)w->nnz * sizeof(double));
  rc = assemble(w, cj, y);
  if (rc) return cb_fail(w, rc);
  // IDA zeroes the matrix, pattern included, before each call: write it again
  memcpy(SM_INDEXPTRS_S(J), w->colptr, ((size_t)w->neq + 1) * sizeof(sunindextype));
  memcpy(SM_INDEXVALS_S(J), w->rowind, (size_t)w->nnz * sizeof(sunindextype));
  memcpy(SM_DATA_S(J), w->val, (size_t)w->nnz * sizeof(double));
  return 0;
}

// ---------------------------------------------------------------------------------------

void dal__ida_free(void *mem) {
  ida_mem *w = mem;
  if (!w) return;
  if (w->ida) IDAFree(&w->ida);
  if (w->LS) SUNLinSolFree(w->LS);
  if (w->A) SUNMatDestroy(w->A);
  N_Vector vs[] = {w->y, w->yp, w->id, w->atol, w->w1, w->w2};
  for (size_t i = 0; i < sizeof vs / sizeof vs[0]; ++i)
    if (vs[i]) N_VDestroy(vs[i]);
  if (w->ctx) SUNContext_Free(&w->ctx);
  free(w->keys);
  free(w->colptr);
  free(w->rowind);
  free(w->val);
  free(w->H);
  free(w->hv);
  free(w->Ju);
  free(w->tmp);
  free(w->Hq);
  free(w->dir);
  free(w->udot);
  free(w->g0);
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
}

#define IDA_CHECK(call)                                                                            \
  do {                                                                                             \
    int f_ = (call);                                                                               \
    if (f_ < 0) {                                                                                  \
      st->stats.foreign_code = f_;                                                                 \
      rc = DAL_FAIL(st, DAL_E_SOLVER, "IDA setup failed in %s (flag %d): %s", #call, f_,           \
                    w->ida_msg);                                                                   \
      goto fail;                                                                                   \
    }                                                                                              \
  } while (0)

int dal__ida_create(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, void **mem) {
  *mem = NULL;
  dal_formulation form = opts->form == DAL_FORM_AUTO ? DAL_FORM_GGL : opts->form;
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
  // consistent start: rank check, projections, KKT accelerations and multipliers
  int rc = dal__dae_start(sys, st, NULL);
  if (rc) return rc;
  ida_mem *w = calloc(1, sizeof *w);
  if (!w) return DAL_FAIL(st, DAL_E_NOMEM, "IDA: out of memory");
  w->sys = sys;
  w->st = st;
  w->opts = *opts;
  w->form = form;
  w->n = sys->n;
  w->m = sys->m;
  w->off_l = 2 * w->n;
  w->off_mu = form == DAL_FORM_GGL ? 2 * w->n + w->m : -1;
  w->neq = 2 * w->n + (form == DAL_FORM_GGL ? 2 : 1) * w->m;
  w->sparse =
      opts->linsol == DAL_LINSOL_KLU ||
      (opts->linsol == DAL_LINSOL_AUTO && (w->neq >= opts->sparse_threshold || !sys->dense_M));
  if (SUNContext_Create(NULL, &w->ctx) != 0) {
    free(w);
    return DAL_FAIL(st, DAL_E_NOMEM, "IDA: cannot create the SUNDIALS context");
  }
  sunindextype neq = w->neq;
  w->y = N_VNew_Serial(neq, w->ctx);
  w->yp = N_VNew_Serial(neq, w->ctx);
  w->id = N_VNew_Serial(neq, w->ctx);
  w->atol = N_VNew_Serial(neq, w->ctx);
  w->w1 = N_VNew_Serial(neq, w->ctx);
  w->w2 = N_VNew_Serial(neq, w->ctx);
  if (!w->y || !w->yp || !w->id || !w->atol || !w->w1 || !w->w2) {
    rc = DAL_FAIL(st, DAL_E_NOMEM, "IDA: out of memory for %d unknowns", w->neq);
    goto fail;
  }
  // error test on q and v; lambda and mu (algebraic) out of it. Index-3 keeps only q in
  // the error test, the usual practice for the higher-index variables of a BDF code (Brenan,
  // Campbell and Petzold, sec. 5.4): with v in it the steps collapse at rtol <= 1e-6.
  // Absolute tolerances: opts.atol for q and v; multipliers and mu get loose ones, they only
  // weigh Newton corrections.
  {
    int nerr = (form == DAL_FORM_INDEX3 ? 1 : 2) * w->n;
    double *id = N_VGetArrayPointer(w->id), *at = N_VGetArrayPointer(w->atol);
    double fscale = 0.0;
    for (int r = 0; r < w->m; ++r)
      fscale = fmax(fscale, fabs(st->lambda[r]));
    for (int i = 0; i < w->neq; ++i) {
      id[i] = i < nerr ? 1.0 : 0.0;
      at[i] = opts->atol;
    }
    for (int r = 0; r < w->m; ++r) {
      at[w->off_l + r] = fmax(opts->atol, opts->rtol * fmax(fscale, 1.0));
      if (w->off_mu >= 0) at[w->off_mu + r] = fmax(opts->atol, sqrt(opts->atol));
    }
  }
  load_y(w);
  w->ida = IDACreate(w->ctx);
  if (!w->ida) {
    rc = DAL_FAIL(st, DAL_E_NOMEM, "IDA: IDACreate failed (out of memory)");
    goto fail;
  }
  IDA_CHECK(IDASetErrHandlerFn(w->ida, silent_handler, w));
  IDA_CHECK(IDAInit(w->ida, residual, st->t, w->y, w->yp));
  IDA_CHECK(IDASVtolerances(w->ida, opts->rtol, w->atol));
  IDA_CHECK(IDASetUserData(w->ida, w));
  IDA_CHECK(IDASetId(w->ida, w->id));
  IDA_CHECK(IDASetSuppressAlg(w->ida, SUNTRUE));
  IDA_CHECK(IDASetMaxNumSteps(w->ida, opts->max_steps > 0 ? opts->max_steps : 1000000));
  if (opts->hmax > 0) IDA_CHECK(IDASetMaxStep(w->ida, opts->hmax));
  if (opts->hmin > 0) IDA_CHECK(IDASetMinStep(w->ida, opts->hmin));
  if (w->sparse) {
    w->max_dep = 1;
    for (int ci = 0; ci < sys->ncon; ++ci)
      if (sys->con[ci].ndep > w->max_dep) w->max_dep = sys->con[ci].ndep;
    size_t mi = (size_t)sys->max_in, mo = (size_t)sys->max_out, md = (size_t)w->max_dep;
    w->H = malloc((mo * mi * mi + 1) * sizeof(double));
    w->hv = malloc((mo * mi + 1) * sizeof(double));
    w->Ju = malloc((mi * md + 1) * sizeof(double));
    w->tmp = malloc((mi * mi + 1) * sizeof(double));
    w->Hq = malloc((md * md + 1) * sizeof(double));
    w->dir = malloc((mi + 1) * sizeof(double));
    w->udot = malloc((mi + 1) * sizeof(double));
    w->g0 = malloc((mo + 1) * sizeof(double));
    if (!w->H || !w->hv || !w->Ju || !w->tmp || !w->Hq || !w->dir || !w->udot || !w->g0 ||
        build_pattern(w)) {
      rc = DAL_FAIL(st, DAL_E_NOMEM, "IDA: out of memory for the sparse Jacobian");
      goto fail;
    }
    w->A = SUNSparseMatrix(neq, neq, w->nnz, CSC_MAT, w->ctx);
    w->LS = w->A ? SUNLinSol_KLU(w->y, w->A, w->ctx) : NULL;
  } else {
    w->A = SUNDenseMatrix(neq, neq, w->ctx);
    w->LS = w->A ? SUNLinSol_Dense(w->y, w->A, w->ctx) : NULL;
  }
  if (!w->A || !w->LS) {
    rc = DAL_FAIL(st, DAL_E_NOMEM, "IDA: cannot create the %s linear solver (%d unknowns)",
                  w->sparse ? "KLU" : "dense", w->neq);
    goto fail;
  }
  IDA_CHECK(IDASetLinearSolver(w->ida, w->LS, w->A));
  if (w->sparse) IDA_CHECK(IDASetJacFn(w->ida, jacobian));
  *mem = w;
  return DAL_OK;
fail:
  dal__ida_free(w);
  return rc;
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
  st->t = t;
  memcpy(st->q, y, (size_t)w->n * sizeof(double));
  memcpy(st->qdot, y + w->n, (size_t)w->n * sizeof(double));
  dal__state_moved(st);
  int rc = dal__eval(w->sys, st, DAL_P_ALL);
  return rc == DAL__RECOVERABLE ? DAL_E_CALLBACK : rc;
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

static int map_failure(ida_mem *w, int flag, double tfail) {
  dal_state *st = w->st;
  const char *what, *remedy;
  int code;
  switch (flag) {
  case IDA_TOO_MUCH_WORK:
    code = DAL_E_MAXSTEPS;
    what = "too many steps before the target time";
    remedy = "raise opts.max_steps, or loosen the tolerances";
    break;
  case IDA_TOO_MUCH_ACC:
    code = DAL_E_STEP;
    what = "the tolerances are too tight for double precision";
    remedy = "loosen rtol/atol";
    break;
  case IDA_ERR_FAIL:
    code = DAL_E_STEP;
    what = "repeated error-test failures (step size underflow)";
    remedy = "loosen the tolerances, or check the forces for discontinuities and the "
             "constraints for a near-singular configuration";
    break;
  case IDA_CONV_FAIL:
  case IDA_NLS_FAIL:
    code = DAL_E_CONV;
    what = "the Newton iteration failed to converge repeatedly";
    remedy = w->form == DAL_FORM_GGL
                 ? "check the constraints (dal_check_constraints) for near-redundancy or a "
                   "vanishing gradient near this configuration"
                 : "check the constraints (dal_check_constraints) for near-redundancy, or use "
                   "the GGL form";
    break;
  case IDA_LINIT_FAIL:
  case IDA_LSETUP_FAIL:
  case IDA_LSOLVE_FAIL:
    code = DAL_E_SOLVER;
    what = "the linear solver failed (singular iteration matrix)";
    remedy = "check for redundant constraints (dal_check_constraints) and positive masses";
    break;
  case IDA_RES_FAIL:
  case IDA_FIRST_RES_FAIL:
    code = w->cb_status ? w->cb_status : DAL_E_CALLBACK;
    what = "the residual evaluation failed";
    remedy = "see the cause below";
    break;
  case IDA_REP_RES_ERR:
    code = DAL_E_CALLBACK;
    what = "a callback asked for smaller steps repeatedly";
    remedy = "check the callback's domain";
    break;
  default:
    code = DAL_E_SOLVER;
    what = "IDA failed";
    remedy = "see IDA's message";
    break;
  }
  char var[160] = "no variable";
  int dom = dominating(w);
  if (dom >= 0) unknown_name(w, dom, var, sizeof var);
  char cause[DAL_ERRMSG_LEN] = "";
  if (code == w->cb_status && w->cb_status)
    snprintf(cause, sizeof cause, "; cause: %.400s", w->cb_msg);
  return DAL_FAIL(st, code,
                  "IDA (%s form, %s) at t=%.17g: %s; error dominated by %s; %s; the state "
                  "holds the last accepted step (t=%.17g)%s [IDA flag %d: %.120s]",
                  form_name(w->form), w->sparse ? "KLU" : "dense", tfail, what, var, remedy, st->t,
                  cause, flag, w->ida_msg);
}

int dal__ida_advance(const dal_system *sys, dal_state *st, void *mem, double tout) {
  ida_mem *w = mem;
  (void)sys;
  DAL_ASSERT(w && w->st == st && w->sys == sys);
  double t0 = st->t;
  if (tout == t0) return finish_state(w, t0, N_VGetArrayPointer(w->y));
  if (!w->started) {
    // IDA's own first step is ~1e-16 at tight tolerances and fails: start near 0.1 sqrt(rtol)
    double h0 = w->opts.h0 > 0 ? w->opts.h0 : DAL_IDA_H0_FACTOR * sqrt(w->opts.rtol);
    if (w->opts.hmax > 0 && h0 > w->opts.hmax) h0 = w->opts.hmax;
    if (h0 > fabs(tout - t0)) h0 = fabs(tout - t0);
    IDASetInitStep(w->ida, tout > t0 ? h0 : -h0);
    w->started = 1;
  }
  w->cb_status = 0;
  w->ida_msg[0] = 0;
  // progress guard: no step below a few ulps of t (IDA would otherwise creep towards a point
  // it cannot pass, e.g. a callback that keeps returning > 0 or a constraint that becomes
  // unsatisfiable, with a million steps that do not move t); opts.hmin when larger
  double hmin = fmax(w->opts.hmin, DAL_TINY_STEP(fmax(fabs(t0), fabs(tout))));
  IDASetMinStep(w->ida, w->opts.hmax > 0 ? fmin(hmin, w->opts.hmax) : hmin);
  IDASetStopTime(w->ida, tout);
  double tret = t0;
  int flag = IDASolve(w->ida, tout, &tret, w->y, w->yp, IDA_NORMAL);
  update_stats(w, flag);
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
  int rc = map_failure(w, flag, tcur + hcur);
  if (recov[0]) {
    char msg[DAL_ERRMSG_LEN];
    snprintf(msg, sizeof msg, "%.200s; it kept asking while IDA shrank the step: %.260s", recov,
             st->err);
    memcpy(st->err, msg, sizeof msg);
  }
  return rc;
}
