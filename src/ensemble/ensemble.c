// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Parameter sweeps over a pthread pool: one state per worker, slot i for trajectory i.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dalembert/ensemble.h"
#include "model/model.h"

#define DAL_SWEEP_COOKIE 0x5eed0a11

dal_sweep_opts dal_default_sweep_opts(void) {
  dal_sweep_opts d, *o = &d;
  memset(o, 0, sizeof *o);
  o->cookie = DAL_SWEEP_COOKIE;
  o->nthreads = 1;
  o->schedule = DAL_SCHEDULE_DYNAMIC;
  o->chunk = 1;
  o->progress_every = 1;
  o->part = 0;
  o->nparts = 1;
  o->part_block = 1;
  return d;
}

int dal_sweep_part_of(long i, int nparts, int block) {
  if (nparts <= 1 || i < 0) return 0;
  if (block < 1) block = 1;
  return (int)((i / block) % nparts);
}

long dal_sweep_grid(int naxes, const int *count, const double *lo, const double *hi,
                    double *values) {
  if (naxes < 1 || !count || !lo || !hi || !values) return DAL_E_ARG;
  long rows = 1;
  for (int a = 0; a < naxes; ++a) {
    if (count[a] < 1 || !isfinite(lo[a]) || !isfinite(hi[a])) return DAL_E_ARG;
    rows *= count[a];
  }
  for (long r = 0; r < rows; ++r) {
    long rest = r;
    for (int a = naxes - 1; a >= 0; --a) {
      long k = rest % count[a];
      rest /= count[a];
      double v = count[a] == 1 ? lo[a] : lo[a] + (hi[a] - lo[a]) * (double)k / (count[a] - 1);
      values[r * naxes + a] = v;
    }
  }
  return rows;
}

// shared run data: the work list, its cursor and the progress counters
typedef struct pool {
  const dal_system *sys;
  const dal_sweep *sw;
  const dal_sweep_opts *o;
  dal_sweep_out *out;
  long *idx, count; // the trajectories of this part, in index order
  int nthreads;
  pthread_mutex_t lock;
  long next, done, failed, since_report;
  int cancelled;
} pool;

typedef struct worker {
  pool *p;
  int id;
  dal_state *st;
  void *data;
  int started;
  pthread_t thread;
} worker;

// record a trajectory's status and message
static void record(pool *p, long i, int status, const char *msg) {
  p->out->status[i] = status;
  if (p->out->msgs)
    snprintf(p->out->msgs + (size_t)i * (size_t)p->out->msg_len, (size_t)p->out->msg_len, "%s",
             status ? msg : "");
}

// one trajectory from a rewound state; returns its status
static int run_one(pool *p, worker *w, long i, char *tmsg) {
  const dal_system *sys = p->sys;
  const dal_sweep *sw = p->sw;
  dal_state *st = w->st;
  int rc;
  double *slot = sw->nresult ? p->out->results + (size_t)i * (size_t)sw->nresult : NULL;
  for (int k = 0; k < sw->nresult; ++k)
    slot[k] = NAN;
  tmsg[0] = 0;
  // rewind: the system's parameters, the sticky Jacobian mode of a fresh state (state.c)
  dal__params_rewind(st);

  const double *vals = sw->nparam ? sw->values + (size_t)i * (size_t)sw->nparam : NULL;
  for (int j = 0; j < sw->nparam; ++j) {
    rc = dal_state_set_param(sys, st, &sw->params[j], vals[j]);
    if (rc) {
      snprintf(tmsg, DAL_SWEEP_MSG_LEN, "%s", st->err);
      return rc;
    }
  }
  size_t off = (size_t)sw->state_stride * (size_t)i;
  rc = dal_state_set(sys, st, sw->t0, sw->q0 + off, sw->qdot0 + off);
  if (!rc && sw->solve) rc = dal_advance(sys, st, sw->solve, sw->t1);
  if (rc) {
    snprintf(tmsg, DAL_SWEEP_MSG_LEN, "%s", st->err);
    return rc;
  }
  if (!sw->reduce) return DAL_OK;
  dal_traj tr = {i, vals, slot, sw->nresult, w->data, w->id, tmsg};
  rc = sw->reduce(sys, st, &tr, sw->ctx);
  if (rc == 0) return DAL_OK;
  if (!tmsg[0]) {
    if (st->err[0])
      snprintf(tmsg, DAL_SWEEP_MSG_LEN, "%s", st->err);
    else
      snprintf(tmsg, DAL_SWEEP_MSG_LEN, "reducer of trajectory %ld returned %d", i, rc);
  }
  return rc < 0 ? rc : DAL_E_CALLBACK;
}

// the next range [*lo, *hi) of positions in the work list for worker w; 0 when none is left
static int grab(pool *p, worker *w, long *lo, long *hi, long *static_pos) {
  if (p->o->schedule == DAL_SCHEDULE_STATIC) {
    long b = p->count * w->id / p->nthreads, e = p->count * (w->id + 1) / p->nthreads;
    if (*static_pos < b) *static_pos = b;
    if (*static_pos >= e) return 0;
    pthread_mutex_lock(&p->lock);
    int stop = p->cancelled;
    pthread_mutex_unlock(&p->lock);
    if (stop) return 0;
    *lo = (*static_pos)++;
    *hi = *lo + 1;
    return 1;
  }
  pthread_mutex_lock(&p->lock);
  int ok = !p->cancelled && p->next < p->count;
  if (ok) {
    *lo = p->next;
    p->next += p->o->chunk;
    if (p->next > p->count) p->next = p->count;
    *hi = p->next;
  }
  pthread_mutex_unlock(&p->lock);
  return ok;
}

static void *work(void *arg) {
  worker *w = arg;
  pool *p = w->p;
  char tmsg[DAL_SWEEP_MSG_LEN];
  long lo, hi, spos = -1;
  while (grab(p, w, &lo, &hi, &spos)) {
    for (long pos = lo; pos < hi; ++pos) {
      long i = p->idx[pos];
      int rc = run_one(p, w, i, tmsg);
      record(p, i, rc, tmsg);
      pthread_mutex_lock(&p->lock);
      p->done++;
      if (rc) p->failed++;
      if (p->o->progress && !p->cancelled &&
          (++p->since_report >= p->o->progress_every || p->done == p->count)) {
        p->since_report = 0;
        if (p->o->progress(p->done, p->count, p->failed, p->o->progress_ctx)) p->cancelled = 1;
      }
      pthread_mutex_unlock(&p->lock);
    }
  }
  return NULL;
}

// write a sweep error message (if the caller gave a buffer) and return the code
static int sweep_fail(char *buf, size_t len, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static int sweep_fail(char *buf, size_t len, int code, const char *fmt, ...) {
  if (buf && len) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, len, fmt, ap);
    va_end(ap);
  }
  return code;
}
#define SFAIL(code, ...) sweep_fail(errmsg, errlen, (code), __VA_ARGS__)

// the sweep's arguments and options, each refusal naming the field
static int check_sweep(const dal_system *sys, const dal_sweep *sw, const dal_sweep_opts *o,
                       const dal_sweep_out *out, char *errmsg, size_t errlen) {
  if (!sys || !sw || !o || !out)
    return SFAIL(DAL_E_ARG, "sweep: system, sweep, options or out is NULL");
  if (o->cookie != DAL_SWEEP_COOKIE)
    return SFAIL(DAL_E_ARG, "sweep options were not initialized: call dal_default_sweep_opts() "
                            "before setting fields");
  if (sw->ntraj < 1) return SFAIL(DAL_E_ARG, "sweep: ntraj is %ld; give at least 1", sw->ntraj);
  if (sw->nparam < 0 || (sw->nparam > 0 && (!sw->params || !sw->values)))
    return SFAIL(DAL_E_ARG, "sweep: %d parameters need params and values tables", sw->nparam);
  if (!sw->q0 || !sw->qdot0) return SFAIL(DAL_E_ARG, "sweep: q0 or qdot0 is NULL");
  if (sw->state_stride != 0 && sw->state_stride != sys->n)
    return SFAIL(DAL_E_ARG,
                 "sweep: state_stride is %d; use 0 (one initial state) or n = %d (one "
                 "per trajectory)",
                 sw->state_stride, sys->n);
  if (sw->nresult < 0 || (sw->nresult > 0 && !out->results))
    return SFAIL(DAL_E_ARG, "sweep: %d results per trajectory need out->results", sw->nresult);
  if (!out->status) return SFAIL(DAL_E_ARG, "sweep: out->status is NULL");
  if (out->msgs && out->msg_len < 1)
    return SFAIL(DAL_E_ARG, "sweep: out->msgs is set with msg_len %d; give msg_len > 0",
                 out->msg_len);
  if (!isfinite(sw->t0))
    return SFAIL(DAL_E_NONFINITE, "sweep: initial time t0 is %g; give a finite time", sw->t0);
  if (sw->solve && !isfinite(sw->t1))
    return SFAIL(DAL_E_NONFINITE, "sweep: target time t1 is %g; give a finite time", sw->t1);
  if (o->nthreads < 0 || o->chunk < 1 || o->progress_every < 1 || o->nparts < 1 || o->part < 0 ||
      o->part >= o->nparts || o->part_block < 1 ||
      (o->schedule != DAL_SCHEDULE_DYNAMIC && o->schedule != DAL_SCHEDULE_STATIC))
    return SFAIL(DAL_E_ARG,
                 "sweep options: nthreads %d (>= 0), chunk %d (>= 1), progress_every "
                 "%ld (>= 1), part %d of nparts %d, part_block %d (>= 1), schedule %d",
                 o->nthreads, o->chunk, o->progress_every, o->part, o->nparts, o->part_block,
                 (int)o->schedule);
  for (int j = 0; j < sw->nparam; ++j) {
    char m[DAL_ERRMSG_LEN];
    if (dal_param_check(sys, &sw->params[j], m, sizeof m))
      return SFAIL(DAL_E_ARG, "sweep parameter %d: %s", j, m);
  }
  return DAL_OK;
}

// the work list: this part's trajectories in index order, each marked as not run until it runs
// (what a cancelled sweep leaves); p->count its length
static int work_list(pool *p, char *errmsg, size_t errlen) {
  const dal_sweep *sw = p->sw;
  const dal_sweep_opts *o = p->o;
  dal_sweep_out *out = p->out;
  long count = 0;
  for (long i = 0; i < sw->ntraj; ++i)
    count += dal_sweep_part_of(i, o->nparts, o->part_block) == o->part;
  p->idx = malloc((size_t)(count ? count : 1) * sizeof(long));
  if (!p->idx) return SFAIL(DAL_E_NOMEM, "sweep: out of memory");
  count = 0;
  for (long i = 0; i < sw->ntraj; ++i)
    if (dal_sweep_part_of(i, o->nparts, o->part_block) == o->part) p->idx[count++] = i;
  p->count = count;
  for (long pos = 0; pos < count; ++pos) {
    long i = p->idx[pos];
    for (int k = 0; k < sw->nresult; ++k)
      out->results[(size_t)i * (size_t)sw->nresult + k] = NAN;
    record(p, i, DAL_E_CALLBACK, "not run: the sweep was cancelled");
  }
  return DAL_OK;
}

// the workers' states and data (a failure leaves what was created for the caller to free)
static int create_workers(pool *p, worker *ws, char *errmsg, size_t errlen) {
  const dal_sweep_opts *o = p->o;
  int rc = DAL_OK;
  for (int w = 0; w < p->nthreads && !rc; ++w) {
    ws[w].p = p;
    ws[w].id = w;
    rc = dal_state_create(p->sys, &ws[w].st);
    if (rc) return SFAIL(rc, "sweep: out of memory creating the state of worker %d", w);
    if (o->worker_create) {
      rc = o->worker_create(p->sys, w, o->worker_ctx, &ws[w].data);
      if (rc)
        SFAIL(rc < 0 ? rc : DAL_E_CALLBACK, "sweep: worker_create of worker %d returned %d", w, rc);
      if (rc > 0) rc = DAL_E_CALLBACK;
    }
  }
  return rc;
}

// run the workers: the caller is worker 0; a thread that cannot start leaves its share to the
// others
static int run_workers(pool *p, worker *ws, char *errmsg, size_t errlen) {
  int nthreads = p->nthreads;
  if (pthread_mutex_init(&p->lock, NULL) != 0)
    return SFAIL(DAL_E_NOMEM, "sweep: could not initialize a mutex");
  for (int w = 1; w < nthreads; ++w)
    ws[w].started = pthread_create(&ws[w].thread, NULL, work, &ws[w]) == 0;
  work(&ws[0]);
  // a static block whose thread did not start is run by the caller (dynamic: already done)
  for (int w = 1; w < nthreads; ++w)
    if (!ws[w].started) work(&ws[w]);
  for (int w = 1; w < nthreads; ++w)
    if (ws[w].started) pthread_join(ws[w].thread, NULL);
  pthread_mutex_destroy(&p->lock);
  p->out->nrun = p->done;
  p->out->nfailed = p->failed;
  if (p->cancelled)
    return SFAIL(DAL_E_CALLBACK,
                 "sweep: cancelled by the progress callback after %ld of %ld trajectories", p->done,
                 p->count);
  return DAL_OK;
}

int dal_sweep_run(const dal_system *sys, const dal_sweep *sw, const dal_sweep_opts *o,
                  dal_sweep_out *out, char *errmsg, size_t errlen) {
  if (errmsg && errlen) errmsg[0] = 0;
  int rc = check_sweep(sys, sw, o, out, errmsg, errlen);
  if (rc) return rc;
  int nthreads = o->nthreads;
  if (nthreads == 0) {
    long np = sysconf(_SC_NPROCESSORS_ONLN);
    nthreads = np > 0 ? (int)(np < 1024 ? np : 1024) : 1;
  }

  // the work list: this part's trajectories in index order
  pool p = {.sys = sys, .sw = sw, .o = o, .out = out};
  rc = work_list(&p, errmsg, errlen);
  if (rc) return rc;
  if (nthreads > p.count) nthreads = p.count > 0 ? (int)p.count : 1;
  p.nthreads = nthreads;
  out->nfailed = 0;
  out->nrun = 0;

  // workers: one state each, created here so that a failure runs nothing
  worker *ws = calloc((size_t)nthreads, sizeof(worker));
  rc = ws ? create_workers(&p, ws, errmsg, errlen) : SFAIL(DAL_E_NOMEM, "sweep: out of memory");
  if (!rc) rc = run_workers(&p, ws, errmsg, errlen);
  for (int w = 0; ws && w < nthreads; ++w) {
    if (o->worker_destroy && ws[w].data) o->worker_destroy(ws[w].data, o->worker_ctx);
    dal_state_destroy(ws[w].st);
  }
  free(ws);
  free(p.idx);
  return rc;
}

// a CSV field in double quotes, inner quotes doubled, newlines as spaces
static int put_quoted(FILE *fp, const char *s) {
  if (fputc('"', fp) == EOF) return -1;
  for (; *s; ++s) {
    int c = *s == '\n' || *s == '\r' ? ' ' : *s;
    if (c == '"' && fputc('"', fp) == EOF) return -1;
    if (fputc(c, fp) == EOF) return -1;
  }
  return fputc('"', fp) == EOF ? -1 : 0;
}

int dal_sweep_write_csv(FILE *fp, const dal_system *sys, const dal_sweep *sw,
                        const dal_sweep_out *out, const char *const *result_names) {
  if (!fp || !sys || !sw || !out || !out->status || (sw->nresult > 0 && !out->results))
    return DAL_E_ARG;
  char name[160];
  int bad = fprintf(fp, "index") < 0;
  for (int j = 0; j < sw->nparam; ++j) {
    if (dal_param_name(sys, &sw->params[j], name, sizeof name)) return DAL_E_ARG;
    bad |= fprintf(fp, ",%s", name) < 0;
  }
  // per-trajectory initial states (state_stride = n): their columns follow the parameters
  int n = dal_system_ncoords(sys), own_start = sw->state_stride > 0 && sw->q0 && sw->qdot0;
  for (int w = 0; own_start && w < 2; ++w)
    for (int j = 0; j < n; ++j)
      bad |= fprintf(fp, ",%s:%s", w ? "qdot0" : "q0", dal_system_coord_name(sys, j)) < 0;
  bad |= fprintf(fp, ",status") < 0;
  for (int k = 0; k < sw->nresult; ++k)
    bad |= (result_names ? fprintf(fp, ",%s", result_names[k]) : fprintf(fp, ",r%d", k)) < 0;
  bad |= fprintf(fp, ",message\n") < 0;
  for (long i = 0; i < sw->ntraj && !bad; ++i) {
    bad |= fprintf(fp, "%ld", i) < 0;
    for (int j = 0; j < sw->nparam; ++j)
      bad |= fprintf(fp, ",%.17g", sw->values[(size_t)i * (size_t)sw->nparam + j]) < 0;
    for (int w = 0; own_start && w < 2; ++w) {
      const double *x = (w ? sw->qdot0 : sw->q0) + (size_t)i * (size_t)sw->state_stride;
      for (int j = 0; j < n; ++j)
        bad |= fprintf(fp, ",%.17g", x[j]) < 0;
    }
    bad |= fprintf(fp, ",%s", dal_status_name(out->status[i])) < 0;
    for (int k = 0; k < sw->nresult; ++k)
      bad |= fprintf(fp, ",%.17g", out->results[(size_t)i * (size_t)sw->nresult + k]) < 0;
    bad |= fputc(',', fp) == EOF;
    bad |= put_quoted(fp, out->msgs ? out->msgs + (size_t)i * (size_t)out->msg_len : "") != 0;
    bad |= fputc('\n', fp) == EOF;
  }
  return bad ? DAL_E_IO : DAL_OK;
}
