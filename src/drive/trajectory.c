// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The stored dense trajectory: each accepted step sampled from the method's dense output at
// Chebyshev-Lobatto points, evaluated afterwards by barycentric interpolation (Berrut and
// Trefethen, "Barycentric Lagrange interpolation", SIAM Review 46 (2004), sec. 5).
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "drive.h"

/// intervals per step: NODES = TRAJ_DEG + 1 sample points, the degree of the interpolant
#define TRAJ_DEG 8
#define NODES (TRAJ_DEG + 1)
/// per-step header: a, b (the step), c (the record is valid up to c <= b)
#define HEAD 3

struct dal_trajectory {
  const dal_system *sys;
  size_t n;      // coordinates
  size_t stride; // doubles per step: HEAD + NODES * 2n
  long nsteps, cap;
  int active;   // a run records into it (dal__traj_begin .. dal__traj_end)
  double *data; // nsteps x stride: a, b, c, then per node q (n), qdot (n)
  char err[DAL_ERRMSG_LEN];
};

// node j of the reference interval [-1, 1]: x_j = -cos(j pi / DEG) (x_0 = -1, x_DEG = 1)
static double node_x(int j) {
  if (j == 0) return -1.0;
  if (j == TRAJ_DEG) return 1.0;
  if (2 * j == TRAJ_DEG) return 0.0;
  return -cos(3.14159265358979323846 * j / TRAJ_DEG);
}

int dal_trajectory_create(const dal_system *sys, dal_trajectory **out) {
  if (!out) return DAL_E_ARG;
  *out = NULL;
  if (!sys) return DAL_E_ARG;
  dal_trajectory *tr = calloc(1, sizeof *tr);
  if (!tr) return DAL_E_NOMEM;
  tr->sys = sys;
  tr->n = (size_t)sys->n;
  tr->stride = HEAD + NODES * 2 * tr->n;
  *out = tr;
  return DAL_OK;
}

void dal_trajectory_destroy(dal_trajectory *tr) {
  if (!tr) return;
  free(tr->data);
  free(tr);
}

const char *dal_trajectory_errmsg(const dal_trajectory *tr) { return tr ? tr->err : ""; }

int dal__attach_check(dal_state *st, const dal_system *owner, const char *what, const char *thing) {
  if (!st) return DAL_E_ARG;
  if (dal__check_idle(st, what)) return DAL_E_STATE;
  if (owner && owner != st->sys)
    return DAL_FAIL(st, DAL_E_STATE,
                    "%s: the %s belongs to another system; create it with this state's system",
                    what, thing);
  return DAL_OK;
}

int dal_state_set_trajectory(dal_state *st, dal_trajectory *tr) {
  int rc = dal__attach_check(st, tr ? tr->sys : NULL, "state_set_trajectory", "trajectory");
  if (rc) return rc;
  st->traj = tr;
  return DAL_OK;
}

long dal_trajectory_span(const dal_trajectory *tr, double *t0, double *t1) {
  if (!tr) return DAL_E_ARG;
  if (t0) *t0 = tr->nsteps ? tr->data[0] : NAN;
  if (t1) *t1 = tr->nsteps ? tr->data[(size_t)(tr->nsteps - 1) * tr->stride + 2] : NAN;
  return tr->nsteps;
}

int dal__traj_begin(dal_trajectory *tr, dal_state *st) {
  double end = tr->nsteps ? tr->data[(size_t)(tr->nsteps - 1) * tr->stride + 2] : st->t;
  tr->active = fabs(st->t - end) <= DAL_TINY_STEP(end);
  if (tr->active) return DAL_OK;
  return DAL_FAIL(st, DAL_E_ARG,
                  "the attached trajectory ends at t=%.17g but the run starts at t=%.17g; a "
                  "recorded run continues where the trajectory ends: attach a new trajectory "
                  "(dal_state_set_trajectory) to record from here",
                  end, st->t);
}

// room for one more step; 0 or DAL_E_NOMEM
static int grow(dal_trajectory *tr, dal_state *st) {
  if (tr->nsteps < tr->cap) return DAL_OK;
  long cap = tr->cap ? 2 * tr->cap : 64;
  double *d = realloc(tr->data, (size_t)cap * tr->stride * sizeof(double));
  if (!d)
    return DAL_FAIL(st, DAL_E_NOMEM,
                    "out of memory storing step %ld of the attached trajectory at t=%.17g (%ld "
                    "steps of %zu doubles held); the run stopped at that step",
                    tr->nsteps + 1, st->t, tr->nsteps, tr->stride);
  tr->data = d;
  tr->cap = cap;
  return DAL_OK;
}

// one record: [a, b] of the step just taken by it, sampled at the nodes from its dense output
// (the last at the accepted step itself when `end` is set)
static int store(dal_trajectory *tr, dal_integ *it, double a, double b, int end) {
  dal_state *st = it->st;
  int (*place)(dal_integ *, double) = it->ops->place;
  int (*place_end)(dal_integ *) = it->ops->place_end;
  int rc = grow(tr, st);
  if (rc) return rc;
  double *s = tr->data + (size_t)tr->nsteps * tr->stride;
  size_t n = tr->n;
  s[0] = a;
  s[1] = b;
  s[2] = b;
  for (int j = 0; j < NODES; ++j) {
    double t = j == TRAJ_DEG ? b : j == 0 ? a : a + 0.5 * (b - a) * (1.0 + node_x(j));
    if ((rc = j == TRAJ_DEG && end ? place_end(it) : place(it, t)) != 0) return rc;
    double *v = s + HEAD + (size_t)j * 2 * n;
    memcpy(v, st->q, n * sizeof(double));
    memcpy(v + n, st->qdot, n * sizeof(double));
    for (size_t i = 0; i < 2 * n; ++i)
      if (!isfinite(v[i]))
        // the method's dense output overflowed inside an accepted step (derivatives beyond
        // double range: a step of 1e-157 s over which qdot grows to 1e142, say): nothing to
        // store that evaluation could trust
        return DAL_FAIL(st, DAL_E_NONFINITE,
                        "trajectory: the dense output of the step [%.17g, %.17g] is not finite at "
                        "t=%.17g (%s[%zu] = %g): the motion leaves double range there; the run "
                        "stopped at that step and the trajectory ends before it",
                        a, b, t, i < n ? "q" : "qdot", i % n, v[i]);
  }
  tr->nsteps++;
  return DAL_OK;
}

int dal__traj_step(dal_trajectory *tr, dal_integ *it) {
  double a = 0, b = 0;
  it->ops->window(it, &a, &b);
  // the step in the method's number of records of equal length; the last ends on the accepted
  // step itself
  int pieces = it->traj_pieces;
  for (int p = 0; p < pieces; ++p) {
    double ta = p == 0 ? a : a + (b - a) * p / pieces;
    double tb = p == pieces - 1 ? b : a + (b - a) * (p + 1) / pieces;
    int rc = store(tr, it, ta, tb, p == pieces - 1);
    if (rc) return rc;
  }
  return DAL_OK;
}

void dal__traj_end(dal_trajectory *tr, double t) {
  if (!tr->active) return;
  tr->active = 0;
  // records wholly after a stop inside the step (a step stored in pieces) go
  while (tr->nsteps > 1 && tr->data[(size_t)(tr->nsteps - 1) * tr->stride] > t)
    tr->nsteps--;
  if (!tr->nsteps) return;
  double *s = tr->data + (size_t)(tr->nsteps - 1) * tr->stride;
  // a stop inside the last step cuts it; a few ulps beyond it (a run over an interval no step
  // can take) extends it
  if (t >= s[0] && t <= s[1] + DAL_TINY_STEP(s[1])) s[2] = t;
}

// the step whose span holds t (the later one at a joint), or -1
static long find_step(const dal_trajectory *tr, double t) {
  long lo = 0, hi = tr->nsteps - 1;
  if (t < tr->data[0]) return -1;
  while (lo < hi) { // the last step with a <= t
    long mid = lo + (hi - lo + 1) / 2;
    if (tr->data[(size_t)mid * tr->stride] <= t)
      lo = mid;
    else
      hi = mid - 1;
  }
  return t <= tr->data[(size_t)lo * tr->stride + 2] ? lo : -1;
}

// the barycentric sum of the NODES values v[0], v[stride], ... with weights w (sum den); values
// near the end of double range (|v| ~ 1e308, whose weighted partial sums overflow) are summed
// scaled by their largest magnitude
static double bary(const double *w, double den, const double *v, size_t stride) {
  double sum = 0.0, big = 0.0;
  for (int j = 0; j < NODES; ++j)
    sum += w[j] * v[(size_t)j * stride];
  if (isfinite(sum / den)) return sum / den;
  for (int j = 0; j < NODES; ++j)
    big = fmax(big, fabs(v[(size_t)j * stride]));
  if (!isfinite(big) || big == 0.0) return sum / den;
  sum = 0.0;
  for (int j = 0; j < NODES; ++j)
    sum += w[j] * (v[(size_t)j * stride] / big);
  return sum / den * big;
}

int dal_trajectory_eval(dal_trajectory *tr, double t, double *q, double *qdot) {
  if (!tr) return DAL_E_ARG;
  if (!isfinite(t))
    return dal__set_err(tr->err, DAL_E_NONFINITE, "trajectory_eval: t = %g; give a finite time", t);
  if (!tr->nsteps)
    return dal__set_err(tr->err, DAL_E_ARG,
                        "trajectory_eval: the trajectory is empty (t = %.17g asked); attach it "
                        "with dal_state_set_trajectory before integrating",
                        t);
  long k = find_step(tr, t);
  if (k < 0) {
    double t0 = 0, t1 = 0;
    dal_trajectory_span(tr, &t0, &t1);
    return dal__set_err(tr->err, DAL_E_ARG,
                        "trajectory_eval: t = %.17g lies outside the recorded span [%.17g, "
                        "%.17g]; evaluate inside it",
                        t, t0, t1);
  }
  const double *s = tr->data + (size_t)k * tr->stride;
  size_t n = tr->n;
  double a = s[0], b = s[1], x = 2.0 * (t - a) / (b - a) - 1.0;
  // barycentric weights of the Chebyshev-Lobatto points: (-1)^j, halved at both ends
  double w[NODES], den = 0.0;
  int hit = -1;
  for (int j = 0; j < NODES; ++j) {
    double dx = x - node_x(j);
    if (dx == 0.0 || (j == 0 && t == a) || (j == TRAJ_DEG && t == b)) {
      hit = j;
      break;
    }
    w[j] = ((j & 1) ? -1.0 : 1.0) * (j == 0 || j == TRAJ_DEG ? 0.5 : 1.0) / dx;
    den += w[j];
  }
  for (size_t i = 0; i < n; ++i) {
    double sq = 0.0, sv = 0.0;
    if (hit >= 0) {
      sq = s[HEAD + (size_t)hit * 2 * n + i];
      sv = s[HEAD + (size_t)hit * 2 * n + n + i];
    } else {
      sq = bary(w, den, s + HEAD + i, 2 * n);
      sv = bary(w, den, s + HEAD + n + i, 2 * n);
    }
    if (!isfinite(sq) || !isfinite(sv))
      return dal__set_err(tr->err, DAL_E_NONFINITE,
                          "trajectory_eval: %s[%zu] at t = %.17g is beyond double range",
                          isfinite(sq) ? "qdot" : "q", i, t);
    if (q) q[i] = sq;
    if (qdot) qdot[i] = sv;
  }
  tr->err[0] = 0;
  return DAL_OK;
}
