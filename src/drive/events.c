// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Events: definitions, sign changes over a step, crossings located on the dense output, the log.
//
// The driver (driver.c) calls dal__events_begin at the start of a run and dal__events_scan
// after every accepted step with the integrator handle, whose dense output places the state
// anywhere in the step just taken. A crossing is bracketed by the sign kept from the step before
// and the sign at the step's end, and closed to a few ulps of t by the Anderson-Bjorck variant of
// regula falsi (Anderson and Bjorck, BIT 13, 253 (1973)), which keeps the bracket and
// converges superlinearly where the plain method stalls on one side.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drive.h"

#define EVENT_COOKIE 0x0da1e7e1
/// iterations of the root finder (a bracket of doubles halves at worst: ~64 bisections)
#define EVENT_MAX_ITER 200

typedef struct ev_item {
  char name[64];
  dal_event_fn *g;
  dal_event_state_fn *gs;
  int row; // global constraint row of a multiplier event, or -1
  void *ctx;
  int dir, terminal;
  int sign;  // sign of g at the last point where it was nonzero (0: not yet known)
  double gv; // g at the last point checked (0 there: a crossing or a touch, decided later)
  double tv; // time of that point (a call continuing from it keeps the sign; NaN: none)
} ev_item;

struct dal_events {
  const dal_system *sys;
  int n, cap;
  ev_item *it;
  long nlog, caplog;
  dal_event_record *log;
  double *logq; // 2n per entry: q, qdot
  int npend;
  dal__pending *pend; // crossings of the current step, in time order (n)
  int held;           // runs using the set now (dal__events_hold)
  char err[DAL_ERRMSG_LEN];
};

dal_event_def dal_default_event_def(void) {
  dal_event_def d;
  memset(&d, 0, sizeof d);
  d.cookie = EVENT_COOKIE;
  d.name = "event";
  d.direction = DAL_EVENT_BOTH;
  return d;
}

int dal_events_create(const dal_system *sys, dal_events **out) {
  if (!out) return DAL_E_ARG;
  *out = NULL;
  if (!sys) return DAL_E_ARG;
  dal_events *ev = calloc(1, sizeof *ev);
  if (!ev) return DAL_E_NOMEM;
  ev->sys = sys;
  *out = ev;
  return DAL_OK;
}

void dal_events_destroy(dal_events *ev) {
  if (!ev) return;
  free(ev->it);
  free(ev->log);
  free(ev->logq);
  free(ev->pend);
  free(ev);
}

const char *dal_events_errmsg(const dal_events *ev) { return ev ? ev->err : ""; }
int dal_events_size(const dal_events *ev) { return ev ? ev->n : 0; }
const char *dal_events_name(const dal_events *ev, int i) {
  return ev && i >= 0 && i < ev->n ? ev->it[i].name : NULL;
}

// the global row of row `row` of the constraint called `name`, or a message
static int find_row(dal_events *ev, const char *name, int row, int *out) {
  const dal_system *sys = ev->sys;
  for (int c = 0; c < sys->ncon; ++c) {
    if (strcmp(sys->con[c].name, name) != 0) continue;
    int nout = sys->con[c].prim->nout;
    if (row < 0 || row >= nout)
      return dal__set_err(ev->err, DAL_E_ARG,
                          "events_add: constraint '%s' has rows 0 ... %d, not %d; set def.row",
                          name, nout - 1, row);
    *out = sys->con[c].row + row;
    return DAL_OK;
  }
  char list[300] = "";
  size_t len = 0;
  for (int c = 0; c < sys->ncon && len + 2 < sizeof list; ++c)
    len +=
        (size_t)snprintf(list + len, sizeof list - len, "%s'%s'", c ? ", " : "", sys->con[c].name);
  if (len >= sizeof list) len = sizeof list - 1;
  return dal__set_err(ev->err, DAL_E_ARG,
                      "events_add: the system has no constraint '%s' (its constraints: %s); a "
                      "multiplier event names one of them",
                      name,
                      sys->ncon ? list
                                : "none, it is in minimal coordinates: use g_state "
                                  "with dal_state_reactions instead");
}

void dal__events_hold(dal_events *ev, int on) { ev->held += on ? 1 : -1; }

int dal_events_add(dal_events *ev, const dal_event_def *d) {
  if (!ev) return DAL_E_ARG;
  ev->err[0] = 0;
  if (ev->held)
    return dal__set_err(ev->err, DAL_E_STATE,
                        "events_add: the event set is in use by a running dal_advance or "
                        "dal_evolve (called from one of its callbacks); add events between runs");
  if (!d) return dal__set_err(ev->err, DAL_E_ARG, "events_add: def is NULL");
  if (d->cookie != EVENT_COOKIE)
    return dal__set_err(ev->err, DAL_E_ARG,
                        "events_add: the definition was not made by dal_default_event_def() "
                        "(start from it, then set the fields)");
  const char *name = d->name ? d->name : "event";
  int kinds = (d->g != NULL) + (d->g_state != NULL) + (d->constraint != NULL);
  if (kinds != 1)
    return dal__set_err(ev->err, DAL_E_ARG,
                        "events_add: event '%s' sets %d of g, g_state and constraint; set "
                        "exactly one",
                        name, kinds);
  if (d->direction < DAL_EVENT_FALLING || d->direction > DAL_EVENT_RISING)
    return dal__set_err(ev->err, DAL_E_ARG,
                        "events_add: event '%s' has direction %d; use DAL_EVENT_BOTH, "
                        "DAL_EVENT_RISING or DAL_EVENT_FALLING",
                        name, (int)d->direction);
  int row = -1;
  if (d->constraint) {
    int rc = find_row(ev, d->constraint, d->row, &row);
    if (rc) return rc;
  }
  if (ev->n == ev->cap) {
    int cap = ev->cap ? 2 * ev->cap : 4;
    ev_item *it = realloc(ev->it, (size_t)cap * sizeof *it);
    if (!it) return dal__set_err(ev->err, DAL_E_NOMEM, "events_add: out of memory");
    ev->it = it;
    dal__pending *p = realloc(ev->pend, (size_t)cap * sizeof *p);
    if (!p) return dal__set_err(ev->err, DAL_E_NOMEM, "events_add: out of memory");
    ev->pend = p;
    ev->cap = cap;
  }
  ev_item *e = &ev->it[ev->n];
  memset(e, 0, sizeof *e);
  e->tv = NAN;
  snprintf(e->name, sizeof e->name, "%s", name);
  e->g = d->g;
  e->gs = d->g_state;
  e->row = row;
  e->ctx = d->ctx;
  e->dir = (int)d->direction;
  e->terminal = d->terminal != 0;
  return ev->n++;
}

int dal_state_set_events(dal_state *st, dal_events *ev) {
  int rc = dal__attach_check(st, ev ? ev->sys : NULL, "state_set_events", "event set");
  if (rc) return rc;
  st->events = ev;
  return DAL_OK;
}

long dal_events_count(const dal_events *ev) { return ev ? ev->nlog : 0; }

int dal_events_get(const dal_events *ev, long i, dal_event_record *rec, double *q, double *qdot) {
  if (!ev) return DAL_E_ARG;
  if (i < 0 || i >= ev->nlog) return DAL_E_ARG;
  size_t n = (size_t)ev->sys->n;
  if (rec) *rec = ev->log[i];
  if (q) memcpy(q, ev->logq + (size_t)i * 2 * n, n * sizeof(double));
  if (qdot) memcpy(qdot, ev->logq + (size_t)i * 2 * n + n, n * sizeof(double));
  return DAL_OK;
}

void dal_events_clear(dal_events *ev) {
  if (ev) ev->nlog = 0;
}

int dal_events_write_csv(const dal_events *ev, FILE *fp, int which, int wrap_angles) {
  if (!ev) return DAL_E_ARG;
  dal_events *w = (dal_events *)ev; // the message buffer only
  if (!fp) return dal__set_err(w->err, DAL_E_ARG, "events_write_csv: fp is NULL");
  if (which < -1 || which >= ev->n)
    return dal__set_err(w->err, DAL_E_ARG,
                        "events_write_csv: event %d does not exist (0 ... %d, or -1 for all)",
                        which, ev->n - 1);
  const dal_system *sys = ev->sys;
  int n = sys->n, ok = fprintf(fp, "t,event,direction") > 0;
  for (int i = 0; i < n; ++i)
    ok = ok && fprintf(fp, ",%s", sys->coord_names[i]) > 0;
  for (int i = 0; i < n; ++i)
    ok = ok && fprintf(fp, ",%s_dot", sys->coord_names[i]) > 0;
  ok = ok && fputc('\n', fp) != EOF;
  for (long k = 0; k < ev->nlog && ok; ++k) {
    const dal_event_record *r = &ev->log[k];
    if (which >= 0 && r->event != which) continue;
    const double *x = ev->logq + (size_t)k * 2 * (size_t)n;
    ok = fprintf(fp, "%.17g,%s,%d", r->t, ev->it[r->event].name, r->direction) > 0;
    for (int i = 0; i < 2 * n && ok; ++i) {
      double v = x[i];
      if (wrap_angles && i < n) v = dal__wrap_pi(v);
      ok = fprintf(fp, ",%.17g", v) > 0;
    }
    ok = ok && fputc('\n', fp) != EOF;
  }
  if (!ok || ferror(fp))
    return dal__set_err(w->err, DAL_E_IO, "events_write_csv: writing the log failed");
  return DAL_OK;
}

// ---------------------------------------------------------------------------------------------
// the driver's side

// g of event i at the state's (t, q, qdot) (placed, not evaluated)
static int value(dal_events *ev, int i, dal_state *st, double *g) {
  ev_item *e = &ev->it[i];
  const dal_system *sys = ev->sys;
  if (e->g) {
    *g = e->g(st->t, st->q, st->qdot, e->ctx);
  } else if (e->gs) {
    st->lazy = 1;
    st->lazy_rc = 0;
    st->err[0] = 0;
    *g = e->gs(sys, st, e->ctx);
    // a state that could not be evaluated here: the event's value means nothing
    char who[96];
    snprintf(who, sizeof who, "event '%s'", e->name);
    int rc = dal__lazy_end(st, who);
    if (rc) return rc;
  } else {
    int rc = dal__public_status(dal__eval(sys, st, DAL_P_ACC));
    if (rc) return rc;
    *g = st->lambda[e->row];
  }
  if (!isfinite(*g))
    return DAL_FAIL(st, DAL_E_CALLBACK,
                    "event '%s' returned %g at t=%.17g; an event function must be finite "
                    "(the run stopped at the last accepted step)",
                    e->name, *g, st->t);
  return DAL_OK;
}

static int sgn(double x) { return (x > 0) - (x < 0); }

int dal__events_begin(dal_events *ev, dal_state *st) {
  for (int i = 0; i < ev->n; ++i) {
    double g = 0.0;
    int rc = value(ev, i, st, &g);
    if (rc) return rc;
    ev_item *e = &ev->it[i];
    // a zero where the previous call ended (a step end exactly on it) is still undecided:
    // keep the sign from before it, so that a crossing there is logged and a touch is not
    if (!(g == 0.0 && e->sign != 0 && e->tv == st->t)) e->sign = sgn(g);
    e->gv = g;
    e->tv = st->t;
  }
  ev->npend = 0;
  return DAL_OK;
}

// close the bracket [a, b] (g(a) = ga of sign -s1, g(b) = gb of sign s1 or 0) of event i in
// the step just taken by it
static int locate(dal_events *ev, int i, dal_integ *it, double a, double ga, double b, double gb,
                  double *root) {
  dal_state *st = it->st;
  int (*place)(dal_integ *, double) = it->ops->place;
  double lo = a, hi = b, flo = ga, fhi = gb;
  int last = 0;
  for (int k = 0; k < EVENT_MAX_ITER && fhi != 0.0; ++k) {
    if (hi - lo <= 4.0 * DBL_EPSILON * fmax(fabs(lo), fabs(hi))) break;
    double c = hi - fhi * (hi - lo) / (fhi - flo);
    if (!(c > lo && c < hi)) c = lo + 0.5 * (hi - lo);
    if (!(c > lo && c < hi)) break; // lo and hi are neighbours
    int rc = place(it, c);
    double fc = 0.0;
    if (!rc) rc = value(ev, i, st, &fc);
    if (rc) return rc;
    if (fc == 0.0) {
      hi = c;
      break;
    }
    if (sgn(fc) == sgn(fhi)) {
      // Anderson-Bjorck: scale the retained end when the same end moves twice
      double m = 1.0 - fc / fhi;
      if (last > 0) flo *= m > 0 ? m : 0.5;
      hi = c;
      fhi = fc;
      last = 1;
    } else {
      double m = 1.0 - fc / flo;
      if (last < 0) fhi *= m > 0 ? m : 0.5;
      lo = c;
      flo = fc;
      last = -1;
    }
  }
  *root = hi; // the side after the crossing: a restart there does not find it again
  return DAL_OK;
}

int dal__events_scan(dal_events *ev, dal_integ *it) {
  dal_state *st = it->st;
  double a = 0, b = 0;
  it->ops->window(it, &a, &b);
  ev->npend = 0;
  int rc = it->ops->place(it, b);
  if (rc) return rc;
  // g at the step's end for every event, before any root finding moves the state
  for (int i = 0; i < ev->n; ++i) {
    double g = 0.0;
    if ((rc = value(ev, i, st, &g)) != 0) return rc;
    ev_item *e = &ev->it[i];
    int s0 = e->sign, s1 = sgn(g);
    double g0 = e->gv;
    // a zero at the step's end is not a crossing yet: g may only touch zero there (events.h).
    // The sign from before it is kept; the next step's end decides (a crossing is then
    // located at the zero, the start of that step)
    if (s1 != 0 || s0 == 0) e->sign = s1;
    e->gv = g;
    e->tv = b;
    if (s0 == 0 || s1 == 0 || s1 == s0) continue;
    int dir = s1 != 0 ? s1 : -s0;
    if (e->dir != DAL_EVENT_BOTH && e->dir != dir) continue;
    ev->pend[ev->npend].event = i;
    ev->pend[ev->npend].dir = dir;
    ev->pend[ev->npend].t = b;
    ev->pend[ev->npend].g0 = g0;
    ev->pend[ev->npend].g1 = g;
    ev->npend++;
  }
  for (int k = 0; k < ev->npend; ++k) {
    dal__pending *p = &ev->pend[k];
    if (p->g1 == 0.0) continue;
    // g at a is the value kept from the step before (the sign if that value was 0)
    double ga = p->g0 != 0.0 ? p->g0 : -(double)p->dir;
    if ((rc = locate(ev, p->event, it, a, ga, b, p->g1, &p->t)) != 0) return rc;
  }
  // in time order (insertion sort: a handful of events), ties in the order of the set
  for (int k = 1; k < ev->npend; ++k) {
    dal__pending x = ev->pend[k];
    int j = k - 1;
    while (j >= 0 && ev->pend[j].t > x.t) {
      ev->pend[j + 1] = ev->pend[j];
      --j;
    }
    ev->pend[j + 1] = x;
  }
  return DAL_OK;
}

int dal__events_npending(const dal_events *ev) { return ev->npend; }
const dal__pending *dal__events_pending(const dal_events *ev, int k) { return &ev->pend[k]; }
int dal__events_terminal(const dal_events *ev, int i) { return ev->it[i].terminal; }

int dal__events_record(dal_events *ev, const dal_state *st, int i, int dir) {
  size_t n = (size_t)ev->sys->n;
  if (ev->nlog == ev->caplog) {
    long cap = ev->caplog ? 2 * ev->caplog : 64;
    dal_event_record *r = realloc(ev->log, (size_t)cap * sizeof *r);
    if (!r) return DAL_FAIL_C(st, DAL_E_NOMEM, "out of memory growing the event log");
    ev->log = r;
    double *q = realloc(ev->logq, (size_t)cap * 2 * n * sizeof(double) + 1);
    if (!q) return DAL_FAIL_C(st, DAL_E_NOMEM, "out of memory growing the event log");
    ev->logq = q;
    ev->caplog = cap;
  }
  dal_event_record *r = &ev->log[ev->nlog];
  r->t = st->t;
  r->event = i;
  r->direction = dir;
  memcpy(ev->logq + (size_t)ev->nlog * 2 * n, st->q, n * sizeof(double));
  memcpy(ev->logq + (size_t)ev->nlog * 2 * n + n, st->qdot, n * sizeof(double));
  ev->nlog++;
  return DAL_OK;
}

const char *dal__events_item_name(const dal_events *ev, int i) { return ev->it[i].name; }
