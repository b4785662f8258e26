// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// DAE formulations of redundant coordinates: residuals, error-test masks, Newton matrices.
//
// Unknowns y = (q, v, lambda[, mu]) with residuals (Gear, Gupta and Leimkuhler, J. Comput.
// Appl. Math. 12-13, 1985; Hairer and Wanner, Solving ODEs II, VII.1-VII.3; Brenan, Campbell
// and Petzold, Numerical Solution of IVPs in DAEs, SIAM 1996):
//   GGL:    q' - v + G' mu,  M v' - (Q - c) - G' lambda,  G v + phi_t,  phi
//   index3: q' - v,          M v' - (Q - c) - G' lambda,  phi
//   index1: q' - v,          M v' - (Q - c) - G' lambda,
//           G v' + gamma_phi + 2 alpha (G v + phi_t) + beta^2 phi
// The Newton matrix is assembled from exact pieces: M, G, G', and the geometric stiffness
// sum_i w_i Hess(phi_i) of each constraint, computed from jets by polarization within its local
// inputs.
#include "form.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int dal__dae_init(dal_dae *f, const dal_system *sys, dal_state *st, dal_formulation form,
                  double alpha, double beta, int work) {
  memset(f, 0, sizeof *f);
  f->sys = sys;
  f->st = st;
  f->form = form;
  f->alpha = alpha;
  f->beta = beta;
  f->n = sys->n;
  f->m = sys->m;
  f->off_l = 2 * f->n;
  f->off_mu = form == DAL_FORM_GGL ? 2 * f->n + f->m : -1;
  f->neq = 2 * f->n + (form == DAL_FORM_GGL ? 2 : 1) * f->m;
  f->off_w = work ? f->neq++ : -1;
  int max_dep = 1;
  for (int ci = 0; ci < sys->ncon; ++ci)
    if (sys->con[ci].ndep > max_dep) max_dep = sys->con[ci].ndep;
  size_t mi = (size_t)sys->max_in, mo = (size_t)sys->max_out, md = (size_t)max_dep;
  f->H = malloc((mo * mi * mi + 1) * sizeof(double));
  f->hv = malloc((mo * mi + 1) * sizeof(double));
  f->Ju = malloc((mi * md + 1) * sizeof(double));
  f->tmp = malloc((mi * mi + 1) * sizeof(double));
  f->Hq = malloc((md * md + 1) * sizeof(double));
  f->dir = malloc((mi + 1) * sizeof(double));
  f->udot = malloc((mi + 1) * sizeof(double));
  f->g0 = malloc((mo + 1) * sizeof(double));
  if (!f->H || !f->hv || !f->Ju || !f->tmp || !f->Hq || !f->dir || !f->udot || !f->g0) {
    dal__dae_free(f);
    return DAL_E_NOMEM;
  }
  return DAL_OK;
}

void dal__dae_free(dal_dae *f) {
  double *p[] = {f->H, f->hv, f->Ju, f->tmp, f->Hq, f->dir, f->udot, f->g0};
  for (size_t i = 0; i < sizeof p / sizeof p[0]; ++i)
    free(p[i]);
  dal__csc_free(&f->pat);
  free(f->pos);
  f->pos = NULL;
  f->H = f->hv = f->Ju = f->tmp = f->Hq = f->dir = f->udot = f->g0 = NULL;
}

int dal__dae_eval(dal_dae *f, double t, const double *y) {
  dal_state *st = f->st;
  st->t = t;
  memcpy(st->q, y, (size_t)f->n * sizeof(double));
  memcpy(st->qdot, y + f->n, (size_t)f->n * sizeof(double));
  dal__state_moved(st);
  // the residual applies M through the particle Jacobians: no dense assembly
  return dal__eval(f->sys, st,
                   DAL_P_KIN | DAL_P_J | DAL_P_CON | DAL_P_DYN | (f->off_w >= 0 ? DAL_P_PW : 0u));
}

int dal__dae_residual(dal_dae *f, double t, const double *y, const double *yp, double *F) {
  const dal_system *sys = f->sys;
  dal_state *st = f->st;
  int n = f->n, m = f->m;
  int rc = dal__dae_eval(f, t, y);
  if (rc) return rc;
  const double *v = y + n, *lam = y + f->off_l, *vd = yp + n;
  double *Fq = F, *Fv = F + n, *Fl = F + f->off_l;
  // Fq = q' - v (+ G' mu)
  if (f->form == DAL_FORM_GGL && m)
    dal__gt_apply(sys, st, y + f->off_mu, Fq);
  else
    memset(Fq, 0, (size_t)n * sizeof(double));
  for (int i = 0; i < n; ++i)
    Fq[i] += yp[i] - v[i];
  // Fv = M v' - (Q - c) - G' lambda
  dal__mass_apply(sys, st, vd, Fv);
  double *gl = m ? dal__kkt_scratch(st, 0) : NULL; // no KKT workspace when m = 0
  if (m) dal__gt_apply(sys, st, lam, gl);
  for (int i = 0; i < n; ++i)
    Fv[i] -= st->Q[i] - st->c[i] + (m ? gl[i] : 0.0);
  // constraint rows
  if (f->form == DAL_FORM_GGL) {
    for (int r = 0; r < m; ++r) {
      Fl[r] = st->phidot[r];
      F[f->off_mu + r] = st->phi[r];
    }
  } else if (f->form == DAL_FORM_INDEX3) {
    if (m) memcpy(Fl, st->phi, (size_t)m * sizeof(double));
  } else {
    dal__g_mul(sys, st->G, vd, Fl);
    for (int r = 0; r < m; ++r)
      Fl[r] += st->gphi[r] + 2.0 * f->alpha * st->phidot[r] + f->beta * f->beta * st->phi[r];
  }
  if (f->off_w >= 0) {
    // W' = dE/dt with the accelerations v' and multipliers lambda of this iterate
    memcpy(st->qddot, vd, (size_t)n * sizeof(double));
    if (m) memcpy(st->lambda, lam, (size_t)m * sizeof(double));
    st->have |= DAL_P_ACC;
    if ((rc = dal__finish(sys, st)) != 0) return rc;
    dal__power(sys, st);
    F[f->off_w] = yp[f->off_w] - st->power;
  }
  return DAL_OK;
}

double dal__dae_tol_factor(dal_formulation form) {
  // measured on the Cartesian pendulum released at 60, 120 and 170 degrees against the
  // elliptic solution, error at t = 10 over rtol = 1e-4 ... 1e-11 (solve.h): GGL worst 14.5x;
  // index-1 without stabilization drifts (worst 34x to 1e-9, 77x at 1e-10); index-3 is
  // 1e3-1e5 x whatever the factor (kept to show where it fails)
  switch (form) {
  case DAL_FORM_INDEX1:
    return 0.0002;
  default:
    return 0.001;
  }
}

int dal__dae_row_scales(dal_dae *f, double *sl, double *smu) {
  const dal_system *sys = f->sys;
  dal_state *st = f->st;
  int n = f->n, m = f->m;
  // the diagonal of M (once per start; O(n), no column-by-column products)
  double *md = malloc(((size_t)n + 1) * sizeof(double));
  if (!md) return DAL_E_NOMEM;
  dal__mass_diag(sys, st, md);
  for (int r = 0; r < m; ++r)
    sl[r] = smu[r] = 0.0;
  // each row of G from its constraint's local block (the rows of G' e_r, O(nnz))
  for (int ci = 0; ci < sys->ncon; ++ci) {
    const dal_con *c = &sys->con[ci];
    const int *dc = sys->cdep + c->dep_off;
    const double *Gc = st->G + c->g_off;
    for (int r = 0; r < c->prim->nout; ++r) {
      int row = c->row + r;
      for (int k = 0; k < c->ndep; ++k) {
        double g = fabs(Gc[r * c->ndep + k]);
        smu[row] = fmax(smu[row], g);
        if (md[dc[k]] > 0.0) sl[row] = fmax(sl[row], g / md[dc[k]]);
      }
    }
  }
  free(md);
  return DAL_OK;
}

void dal__dae_mask(const dal_dae *f, double *id) {
  // index-3 keeps only q in the error test, the usual practice for the higher-index variables
  // of a BDF code (Brenan, Campbell and Petzold, sec. 5.4): with v in it the steps collapse
  int nerr = (f->form == DAL_FORM_INDEX3 ? 1 : 2) * f->n;
  for (int i = 0; i < f->neq; ++i)
    id[i] = i < nerr || i == f->off_w ? 1.0 : 0.0;
}

// ---------------------------------------------------------------------------------------
// Newton matrix dF/dy + cj dF/dy'

// one entry: the sparse sink adds at the position recorded for the s->n-th entry by
// dal__dae_pattern (no search per entry: the assembly visits the entries in a fixed order)
static inline void jadd(const dal_dae *f, dal_dae_sink *s, int row, int col, double v) {
  switch (s->mode) {
  case DAL_SINK_SPARSE:
    DAL_ASSERT(s->n < f->npos && f->pos[s->n] == dal__csc_find(&f->pat, row, col));
    s->val[f->pos[s->n++]] += v;
    break;
  case DAL_SINK_DENSE:
    s->val[(size_t)col * f->neq + row] += v;
    break;
  case DAL_SINK_COUNT:
    s->n++;
    break;
  case DAL_SINK_KEYS:
    s->keys[s->n++] = dal__csc_key(f->neq, row, col);
    break;
  default: // DAL_SINK_POS
    f->pos[s->n++] = dal__csc_find(&f->pat, row, col);
  }
}

// local Hessians H (nout x nin x nin) and hv = H_ext (udot, 1) (nout x nin) of constraint ci,
// by polarization of second directional derivatives along straight lines
static int con_curvature(dal_dae *f, int ci) {
  const dal_system *sys = f->sys;
  dal_state *st = f->st;
  const dal_con *c = &sys->con[ci];
  int nin = c->prim->nin, nout = c->prim->nout, d = sys->dim, owner = -1 - ci, rc;
  const int *parts = sys->ipool + c->part_off, *coords = sys->ipool + c->coord_off;
  double *dir = f->dir, *H = f->H, *hv = f->hv;
  // local velocities udot
  int k = 0;
  for (int a = 0; a < c->npart; ++a)
    for (int b = 0; b < d; ++b)
      f->udot[k++] = st->v[parts[a] * d + b];
  for (int i = 0; i < c->ncoord; ++i)
    f->udot[k++] = st->qdot[coords[i]];
  memset(dir, 0, (size_t)nin * sizeof(double));
  // diagonal: along e_i
  for (int i = 0; i < nin; ++i) {
    dir[i] = 1.0;
    rc = dal__prim_eval(sys, st, owner, dir, NULL, 0.0);
    dir[i] = 0.0;
    if (rc) return rc;
    for (int r = 0; r < nout; ++r)
      H[(r * nin + i) * nin + i] = st->jout[r].dd;
  }
  // off-diagonal: along e_i + e_j
  for (int i = 0; i < nin; ++i)
    for (int j = i + 1; j < nin; ++j) {
      dir[i] = dir[j] = 1.0;
      rc = dal__prim_eval(sys, st, owner, dir, NULL, 0.0);
      dir[i] = dir[j] = 0.0;
      if (rc) return rc;
      for (int r = 0; r < nout; ++r) {
        double h = 0.5 * (st->jout[r].dd - H[(r * nin + i) * nin + i] - H[(r * nin + j) * nin + j]);
        H[(r * nin + i) * nin + j] = H[(r * nin + j) * nin + i] = h;
      }
    }
  // mixed with the motion: along (udot, 1) and (udot + e_i, 1)
  rc = dal__prim_eval(sys, st, owner, f->udot, NULL, 1.0);
  if (rc) return rc;
  for (int r = 0; r < nout; ++r)
    f->g0[r] = st->jout[r].dd;
  for (int i = 0; i < nin; ++i) {
    double keep = f->udot[i];
    f->udot[i] = keep + 1.0;
    rc = dal__prim_eval(sys, st, owner, f->udot, NULL, 1.0);
    f->udot[i] = keep;
    if (rc) return rc;
    for (int r = 0; r < nout; ++r)
      hv[r * nin + i] = 0.5 * (st->jout[r].dd - f->g0[r] - H[(r * nin + i) * nin + i]);
  }
  return DAL_OK;
}

// Ju (nin x ndep): derivative of constraint ci's local inputs with respect to its dependency
// coordinates
static void local_chain(dal_dae *f, int ci) {
  const dal_system *sys = f->sys;
  const dal_state *st = f->st;
  const dal_con *c = &sys->con[ci];
  int d = sys->dim, nin = c->prim->nin, nd = c->ndep;
  const int *dc = sys->cdep + c->dep_off;
  const int *parts = sys->ipool + c->part_off, *coords = sys->ipool + c->coord_off;
  memset(f->Ju, 0, (size_t)nin * (size_t)nd * sizeof(double));
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
        f->Ju[(a * d + b) * nd + col] = Jp[b * ndp + cp];
    }
  }
  for (int i = 0; i < c->ncoord; ++i) {
    int col = 0;
    while (dc[col] != coords[i])
      ++col;
    f->Ju[(c->npart * d + i) * nd + col] += 1.0;
  }
}

// Hq (nd x nd) = Ju' (sum_r wt_r H_r) Ju for constraint ci
static void chained_hessian(dal_dae *f, int ci, const double *wt) {
  const dal_con *c = &f->sys->con[ci];
  int nin = c->prim->nin, nout = c->prim->nout, nd = c->ndep;
  double *Hs = f->tmp;
  memset(Hs, 0, (size_t)nin * (size_t)nin * sizeof(double));
  for (int r = 0; r < nout; ++r)
    for (int i = 0; i < nin * nin; ++i)
      Hs[i] += wt[r] * f->H[r * nin * nin + i];
  for (int a = 0; a < nd; ++a)
    for (int b = 0; b < nd; ++b) {
      double s = 0.0;
      for (int i = 0; i < nin; ++i) {
        double ji = f->Ju[i * nd + a];
        if (ji == 0.0) continue;
        for (int j = 0; j < nin; ++j)
          s += ji * Hs[i * nin + j] * f->Ju[j * nd + b];
      }
      f->Hq[a * nd + b] = s;
    }
}

// every entry (values are ignored by the counting and key sinks; y may be NULL there)
// the q rows (q' - v: cj and -1) and cj M in the v rows, particle by particle (values: the
// entries, else the pattern only)
static void assemble_mass(dal_dae *f, double cj, dal_dae_sink *s, int values) {
  const dal_system *sys = f->sys;
  const dal_state *st = f->st;
  int n = f->n, d = sys->dim;
  for (int i = 0; i < n; ++i) {
    jadd(f, s, i, i, cj);
    jadd(f, s, i, n + i, -1.0);
  }
  for (int p = 0; p < sys->N; ++p) {
    const int *dp = sys->pdep + sys->pdep_off[p];
    int nd = sys->pdep_off[p + 1] - sys->pdep_off[p];
    const double *Jp = st->J + sys->pj_off[p];
    for (int a = 0; a < nd; ++a)
      for (int b = 0; b < nd; ++b) {
        double v = 0.0;
        for (int c = 0; c < d && values; ++c)
          v += Jp[c * nd + a] * Jp[c * nd + b];
        jadd(f, s, n + dp[a], n + dp[b], cj * st->prm.mass[p] * v);
      }
  }
}

static int assemble(dal_dae *f, double cj, const double *y, dal_dae_sink *s) {
  const dal_system *sys = f->sys;
  dal_state *st = f->st;
  int n = f->n, rc, values = s->mode >= DAL_SINK_SPARSE;
  s->n = 0;
  double al = f->alpha, be = f->beta;
  // W' - P: cj on the diagonal (dP/dy is left out: a Newton approximation)
  if (f->off_w >= 0) jadd(f, s, f->off_w, f->off_w, cj);
  // q' and v in the q rows; cj M in the v rows
  assemble_mass(f, cj, s, values);
  for (int ci = 0; ci < sys->ncon; ++ci) {
    const dal_con *c = &sys->con[ci];
    const int *dc = sys->cdep + c->dep_off;
    const double *Gc = st->G + c->g_off;
    int nout = c->prim->nout, nd = c->ndep, nin = c->prim->nin;
    // curvature terms (values only; the pattern is the constraint's dependency block)
    if (values) {
      rc = con_curvature(f, ci);
      if (rc) return rc;
      local_chain(f, ci);
    }
    for (int r = 0; r < nout; ++r) {
      int row = c->row + r;
      for (int k = 0; k < nd; ++k) {
        double g = values ? Gc[r * nd + k] : 0.0;
        int j = dc[k];
        jadd(f, s, n + j, f->off_l + row, -g); // -G' lambda in the v rows
        if (f->form == DAL_FORM_GGL) {
          jadd(f, s, j, f->off_mu + row, g);    // G' mu in the q rows
          jadd(f, s, f->off_l + row, n + j, g); // G v
          jadd(f, s, f->off_mu + row, j, g);    // phi
        } else if (f->form == DAL_FORM_INDEX3) {
          jadd(f, s, f->off_l + row, j, g); // phi
        } else {
          jadd(f, s, f->off_l + row, n + j, (cj + 2.0 * al) * g); // G v' + 2 alpha G v
          jadd(f, s, f->off_l + row, j, be * be * g);             // beta^2 phi
        }
        // d(G v + phi_t)/dq = Ju' hv (GGL: q columns; index-1: v and q columns)
        if (f->form != DAL_FORM_INDEX3) {
          double h = 0.0;
          for (int i = 0; i < nin && values; ++i)
            h += f->Ju[i * nd + k] * f->hv[r * nin + i];
          if (f->form == DAL_FORM_GGL) {
            jadd(f, s, f->off_l + row, j, h);
          } else {
            jadd(f, s, f->off_l + row, n + j, 2.0 * h);
            jadd(f, s, f->off_l + row, j, 2.0 * al * h);
          }
        }
      }
    }
    // geometric stiffness: -sum lambda_r H_r in the v rows, +sum mu_r H_r in the q rows
    // (index-1 leaves d(G v' + gamma_phi)/dq out of its constraint rows: a Newton
    // approximation)
    if (values) chained_hessian(f, ci, y + f->off_l + c->row);
    for (int a = 0; a < nd; ++a)
      for (int b = 0; b < nd; ++b)
        jadd(f, s, n + dc[a], dc[b], values ? -f->Hq[a * nd + b] : 0.0);
    if (f->form == DAL_FORM_GGL) {
      if (values) chained_hessian(f, ci, y + f->off_mu + c->row);
      for (int a = 0; a < nd; ++a)
        for (int b = 0; b < nd; ++b)
          jadd(f, s, dc[a], dc[b], values ? f->Hq[a * nd + b] : 0.0);
    }
  }
  return DAL_OK;
}

int dal__dae_pattern(dal_dae *f) {
  dal_dae_sink s = {DAL_SINK_COUNT, 0, NULL, NULL};
  assemble(f, 1.0, NULL, &s);
  size_t count = s.n;
  s.keys = malloc((count + 1) * sizeof(long long));
  if (!s.keys) return -1;
  s.mode = DAL_SINK_KEYS;
  assemble(f, 1.0, NULL, &s);
  dal__csc_free(&f->pat);
  int rc = dal__csc_build(&f->pat, f->neq, s.keys, s.n);
  free(s.keys);
  if (rc) return rc;
  free(f->pos);
  f->npos = count;
  if (!(f->pos = malloc((count + 1) * sizeof(int)))) return -1;
  s.mode = DAL_SINK_POS;
  assemble(f, 1.0, NULL, &s);
  return 0;
}

int dal__dae_newton(dal_dae *f, double t, double cj, const double *y, dal_dae_sink *out) {
  int rc = dal__dae_eval(f, t, y);
  if (rc) return rc;
  return assemble(f, cj, y, out);
}

int dal__dae_newton_exact(const dal_system *sys) {
  if (sys->map || !sys->place || sys->nspring || sys->ndamper || sys->npotr || sys->npotq ||
      sys->nforce || sys->ngenforce)
    return 0;
  for (int k = 0; k < sys->N; ++k) {
    const dal_primitive *p = sys->place[k].prim;
    if (sys->place[k].parent >= 0 || (p != &dal_map_cartesian2 && p != &dal_map_cartesian3))
      return 0;
  }
  return 1;
}
