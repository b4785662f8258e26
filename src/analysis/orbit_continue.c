// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Natural-parameter continuation of periodic orbits with the detection of folds (a real
// multiplier through +1: the sign of prod (mu_i - 1) changes) and period doublings (through
// -1: the sign of prod (mu_i + 1) changes), each located by bisection in the parameter
// (Seydel, Practical Bifurcation and Stability Analysis, 2010, sec. 7.4-7.6; the test
// functions of AUTO-07p and MATCONT).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis.h"

#define DAL_ORBIT_CONT_COOKIE 0x0c0b17c0

dal_orbit_continuation_opts dal_default_orbit_continuation_opts(void) {
  dal_orbit_continuation_opts d;
  memset(&d, 0, sizeof d);
  d.cookie = DAL_ORBIT_CONT_COOKIE;
  d.p0 = 0.0;
  d.p1 = 1.0;
  d.npoints = 41;
  d.t = 0.0;
  d.locate = 1;
  d.ptol = 0.0;
  d.orbit = dal_default_orbit_opts();
  return d;
}

// one solved point: system, state at the orbit's start, multipliers and the signs of the
// two test functions prod (mu - 1) and prod (mu + 1)
typedef struct opoint {
  dal_system *sys;
  dal_state *st;
  dal_orbit_report rep;
  double *re, *im;
  int fold, pd;
  int borrowed; // the system is the caller's
} opoint;

static void opoint_free(opoint *p) {
  dal_state_destroy(p->st);
  if (!p->borrowed) dal_system_destroy(p->sys);
  free(p->re);
  memset(p, 0, sizeof *p);
}

// sign of the real product prod (mu_i - s) (0 when a factor vanishes)
static int test_sign(int k2, const double *re, const double *im, double s) {
  double complex_re = 1.0, complex_im = 0.0;
  for (int i = 0; i < k2; ++i) {
    double a = re[i] - s, b = im[i];
    double x = complex_re * a - complex_im * b, y = complex_re * b + complex_im * a;
    complex_re = x;
    complex_im = y;
  }
  return complex_re > 0 ? 1 : complex_re < 0 ? -1 : 0;
}

typedef struct orun {
  dal_rebuild_fn *rebuild;
  const dal_orbit_continuation_opts *o;
  dal_orbit_branch_fn *point;
  dal_continuation_report *r;
  void *ctx;
  int ny; // 2n
} orun;

// the orbit at p from the start y (2n values)
static int solve_at(orun *c, double p, const double *y, opoint *pt) {
  memset(pt, 0, sizeof *pt);
  pt->borrowed = c->o->borrowed != 0;
  int rc = c->rebuild(p, &pt->sys, c->ctx);
  if (rc || !pt->sys) {
    snprintf(c->r->msg, sizeof c->r->msg, "rebuild at p=%.17g failed (%d)", p, rc);
    return DAL_E_CALLBACK;
  }
  int n = dal_system_ncoords(pt->sys), k2 = 2 * (n - dal_system_nconstraints(pt->sys));
  if (2 * n != c->ny) {
    snprintf(c->r->msg, sizeof c->r->msg,
             "rebuild at p=%.17g gave %d coordinates, the branch has %d", p, n, c->ny / 2);
    opoint_free(pt);
    return DAL_E_ARG;
  }
  pt->re = calloc(2 * (size_t)k2 + 1, sizeof(double));
  if (!pt->re || dal_state_create(pt->sys, &pt->st)) {
    opoint_free(pt);
    snprintf(c->r->msg, sizeof c->r->msg, "out of memory at p=%.17g", p);
    return DAL_E_NOMEM;
  }
  pt->im = pt->re + k2;
  rc = dal_state_set(pt->sys, pt->st, c->o->t, y, y + n);
  if (!rc) rc = dal_periodic_orbit(pt->sys, pt->st, &c->o->orbit, pt->re, pt->im, &pt->rep);
  if (rc) {
    snprintf(c->r->msg, sizeof c->r->msg, "at p=%.17g: %s", p, dal_state_errmsg(pt->st));
    opoint_free(pt);
    return rc;
  }
  pt->fold = test_sign(k2, pt->re, pt->im, 1.0);
  pt->pd = test_sign(k2, pt->re, pt->im, -1.0);
  return DAL_OK;
}

static void start_of(const opoint *pt, int n, double *y) {
  memcpy(y, dal_state_q(pt->st), (size_t)n * sizeof(double));
  memcpy(y + n, dal_state_qdot(pt->st), (size_t)n * sizeof(double));
}

static int report(orun *c, double p, const opoint *pt, dal_orbit_kind kind) {
  if (c->point && c->point(p, pt->sys, pt->st, &pt->rep, pt->re, pt->im, kind, c->ctx)) {
    snprintf(c->r->msg, sizeof c->r->msg, "stopped by the point callback at p=%.17g", p);
    return DAL_E_CALLBACK;
  }
  return DAL_OK;
}

// bisection on the sign of one test function between a (sign sa, start ya) and b
static int locate(orun *c, double a, double b, int sa, int pd, const double *ya, double *ywork) {
  int n = c->ny / 2, rc = DAL_OK;
  memcpy(ywork, ya, (size_t)c->ny * sizeof(double));
  opoint mid;
  memset(&mid, 0, sizeof mid);
  double ptol = c->o->ptol > 0 ? c->o->ptol : 1e-10 * fabs(c->o->p1 - c->o->p0);
  while (fabs(b - a) > ptol) {
    double pm = 0.5 * (a + b);
    opoint_free(&mid);
    if ((rc = solve_at(c, pm, ywork, &mid)) != 0) return rc;
    int s = pd ? mid.pd : mid.fold;
    if (s == sa) {
      a = pm;
      start_of(&mid, n, ywork);
    } else {
      b = pm;
    }
  }
  if (mid.sys) {
    rc = report(c, 0.5 * (a + b), &mid, pd ? DAL_ORBIT_PERIOD_DOUBLING : DAL_ORBIT_FOLD);
    if (!rc) ++c->r->ncritical;
  }
  opoint_free(&mid);
  return rc;
}

int dal_orbit_continue(dal_rebuild_fn *rebuild, const double *y0,
                       const dal_orbit_continuation_opts *o, dal_orbit_branch_fn *point,
                       dal_continuation_report *rep, void *ctx) {
  dal_continuation_report r;
  memset(&r, 0, sizeof r);
  if (!rebuild || !y0 || !o || o->cookie != DAL_ORBIT_CONT_COOKIE || o->npoints < 2 ||
      !isfinite(o->p0) || !isfinite(o->p1) || o->p0 == o->p1 || !isfinite(o->t)) {
    snprintf(r.msg, sizeof r.msg,
             "orbit_continue: needs rebuild, y0, options from "
             "dal_default_orbit_continuation_opts with finite p0 != p1 and npoints >= 2");
    if (rep) *rep = r;
    return DAL_E_ARG;
  }
  // the size of the branch from the first system
  dal_system *first = NULL;
  if (rebuild(o->p0, &first, ctx) || !first) {
    snprintf(r.msg, sizeof r.msg, "rebuild at p=%.17g failed", o->p0);
    if (rep) *rep = r;
    return DAL_E_CALLBACK;
  }
  int n = dal_system_ncoords(first);
  if (!o->borrowed) dal_system_destroy(first);
  orun c = {rebuild, o, point, &r, ctx, 2 * n};
  double *y = calloc(4 * (size_t)n + 1, sizeof(double)), *yw = y + 2 * n;
  if (!y) return DAL_E_NOMEM;
  memcpy(y, y0, 2 * (size_t)n * sizeof(double));
  opoint prev, cur;
  memset(&prev, 0, sizeof prev);
  int rc = DAL_OK;
  for (int i = 0; i < o->npoints; ++i) {
    double p = o->p0 + (o->p1 - o->p0) * i / (o->npoints - 1);
    if ((rc = solve_at(&c, p, y, &cur)) != 0) break;
    r.p_end = p;
    // a test function changed sign since the last point: locate, then report this point
    if (prev.sys && o->locate) {
      double pp = o->p0 + (o->p1 - o->p0) * (i - 1) / (o->npoints - 1);
      double *yp = calloc(2 * (size_t)n + 1, sizeof(double));
      if (!yp) {
        rc = DAL_E_NOMEM;
        opoint_free(&cur);
        break;
      }
      start_of(&prev, n, yp);
      if (prev.fold * cur.fold < 0) rc = locate(&c, pp, p, prev.fold, 0, yp, yw);
      if (!rc && prev.pd * cur.pd < 0) rc = locate(&c, pp, p, prev.pd, 1, yp, yw);
      free(yp);
      if (rc) {
        opoint_free(&cur);
        break;
      }
    }
    if ((rc = report(&c, p, &cur, DAL_ORBIT_REGULAR)) != 0) {
      opoint_free(&cur);
      break;
    }
    ++r.npoints;
    start_of(&cur, n, y);
    opoint_free(&prev);
    prev = cur;
  }
  opoint_free(&prev);
  free(y);
  if (rep) *rep = r;
  return rc;
}
