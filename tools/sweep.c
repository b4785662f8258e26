// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// dalembert sweep: the scene's run over a grid of one of its parameters, on threads
// (dal_sweep_run) or over MPI ranks (dal_sweep_run_mpi, when built with MPI). Every worker
// holds its own copy of the scene (read from the file's own text, so that a message names the
// file's line, with the --set values), and a trajectory rebuilds it for its value: a parameter
// may enter masses, gravity, initial values and formulas alike. Results are the final state at
// t1, bit for bit the same for any number of threads or ranks; CSV, or JSON (docs/cli.md).
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "json.h"
#ifdef DAL_CLI_MPI
#include "dalembert/mpi.h"
#endif

typedef struct sweep_ctx {
  cli *c;
  char **notes; // per trajectory: a note the library left after success (the sweep keeps
                // messages of failures only), or NULL
  char name[256];
  double lo, hi;
  int npts;
} sweep_ctx;

static double value_at(const sweep_ctx *s, long i) {
  return s->npts == 1 ? s->lo : s->lo + (s->hi - s->lo) * (double)i / (s->npts - 1);
}

static int worker_create(const dal_system *sys, int id, void *ctx, void **data) {
  (void)sys, (void)id;
  sweep_ctx *s = ctx;
  char msg[1024];
  dal_scene *sc = NULL;
  int rc = dal_scene_parse(s->c->text, s->c->path, &sc, msg, sizeof msg);
  if (!rc) rc = cli_set_params(s->c, sc, msg, sizeof msg);
  if (rc < 0) cli_error(s->c, rc, "%s", msg);
  if (rc) dal_scene_destroy(sc), sc = NULL;
  *data = sc;
  return rc > 0 ? DAL_E_ARG : rc;
}

static void worker_destroy(void *data, void *ctx) {
  (void)ctx;
  dal_scene_destroy(data);
}

// the trajectory: the worker's scene at its value, run as dal_scene_run does (its events
// attached, monitor NULL: dal_advance's run)
static int reduce(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx) {
  (void)sys, (void)st;
  const sweep_ctx *s = ctx;
  dal_scene *ws = tr->worker;
  dal_state *fin = NULL;
  dal_events *ev = NULL;
  int rc = dal_scene_set_param(ws, s->name, value_at(s, tr->index), tr->msg, DAL_SWEEP_MSG_LEN);
  if (!rc) rc = dal_scene_events(ws, &ev);
  if (!rc) rc = dal_scene_state(ws, &fin);
  if (!rc && ev) rc = dal_state_set_events(fin, ev);
  if (!rc) {
    double t1, dt;
    dal_solve_opts so = *dal_scene_opts(ws, NULL, &t1, &dt);
    so.cancel = cli_cancel; // Ctrl-C: a trajectory under way stops at its next step
    rc = dal_evolve(dal_scene_system(ws), fin, &so, t1, dt, NULL, NULL);
    if (rc == DAL_CANCELLED) rc = DAL_E_CALLBACK; // not finished: no result
    if (rc < 0) snprintf(tr->msg, DAL_SWEEP_MSG_LEN, "%s: %s", s->c->path, dal_state_errmsg(fin));
    // a note the library left after success (a moved start, a clamp): kept for the row
    if (rc >= 0 && dal_state_errmsg(fin)[0]) {
      size_t len = strlen(s->c->path) + strlen(dal_state_errmsg(fin)) + 3;
      char *note = malloc(len);
      if (note) snprintf(note, len, "%s: %s", s->c->path, dal_state_errmsg(fin));
      free(s->notes[tr->index]);
      s->notes[tr->index] = note;
    }
  }
  if (fin && rc >= 0) {
    int n = dal_system_ncoords(dal_scene_system(ws));
    memcpy(tr->result, dal_state_q(fin), (size_t)n * sizeof(double));
    memcpy(tr->result + n, dal_state_qdot(fin), (size_t)n * sizeof(double));
  }
  if (fin) dal_state_set_events(fin, NULL);
  dal_state_destroy(fin);
  dal_events_destroy(ev);
  return rc < 0 ? rc : 0;
}

static int on_progress(long done, long total, long failed, void *ctx) {
  char extra[64];
  snprintf(extra, sizeof extra, "(%ld failed)", failed);
  cli_progress(ctx, "sweep: trajectories", (double)done, (double)total, extra);
  return cli_interrupted(); // cancel: the trajectories not started are recorded "not run"
}

// trajectory k's message: its failure, else a note, else ""
static const char *message(const sweep_ctx *s, const dal_sweep_out *o, long k) {
  const char *m = o->msgs + k * o->msg_len;
  return *m || !s->notes[k] ? m : s->notes[k];
}

static int write_rows(const sweep_ctx *s, const dal_sweep_out *o, int n, FILE *fp) {
  const dal_system *sys = dal_scene_system(s->c->sc);
  if (cli_json_asked(s->c)) {
    cli_json j = cli_json_start(fp);
    cli_json_str(&j, "command", "sweep");
    cli_json_str(&j, "scene", s->c->path);
    cli_json_str(&j, "param", s->name);
    cli_json_array(&j, "runs");
    for (long k = 0; k < s->npts; ++k) {
      const double *r = o->results + k * 2 * n;
      cli_json_object(&j, NULL);
      cli_json_int(&j, "index", k);
      cli_json_num(&j, "value", value_at(s, k));
      cli_json_str(&j, "status", dal_status_name(o->status[k]));
      for (int part = 0; part < 2; ++part) {
        cli_json_object(&j, part ? "qdot" : "q");
        for (int i = 0; i < n; ++i)
          cli_json_num(&j, dal_system_coord_name(sys, i), r[part * n + i]);
        cli_json_end(&j);
      }
      cli_json_str(&j, "message", message(s, o, k));
      cli_json_end(&j);
    }
    cli_json_end(&j);
    cli_json_int(&j, "failed", o->nfailed);
    cli_json_bool(&j, "complete", !cli_interrupted());
    return cli_json_finish(&j) ? DAL_E_IO : DAL_OK;
  }
  fprintf(fp, "index,%s,status", s->name);
  for (int i = 0; i < n; ++i)
    fprintf(fp, ",%s", dal_system_coord_name(sys, i));
  for (int i = 0; i < n; ++i)
    fprintf(fp, ",%s_dot", dal_system_coord_name(sys, i));
  fprintf(fp, ",message\n");
  for (long k = 0; k < s->npts; ++k) {
    fprintf(fp, "%ld,%.17g,%s", k, value_at(s, k), dal_status_name(o->status[k]));
    for (int i = 0; i < 2 * n; ++i)
      fprintf(fp, ",%.17g", o->results[k * 2 * n + i]);
    fprintf(fp, ",\"");
    for (const char *m = message(s, o, k); *m; ++m)
      fputs(*m == '"' ? "\"\"" : (char[2]){*m, 0}, fp);
    fprintf(fp, "\"\n");
  }
  return ferror(fp) ? DAL_E_IO : DAL_OK;
}

// the chart: a panel per coordinate, its final value against the parameter (the runs that
// failed left out)
static int sweep_chart(const sweep_ctx *s, const dal_sweep_out *o, int n, cli_file *f) {
  const dal_system *sys = dal_scene_system(s->c->sc);
  double *xy = malloc((size_t)s->npts * (1 + (size_t)n) * sizeof *xy);
  cli_panel *pan = calloc((size_t)n + 1, sizeof *pan);
  cli_series *se = calloc((size_t)n + 1, sizeof *se);
  char(*title)[400] = calloc((size_t)n + 1, sizeof *title);
  if (!xy || !pan || !se || !title) {
    free(xy), free(pan), free(se), free(title);
    return cli_error(s->c, DAL_E_NOMEM, "out of memory for the chart");
  }
  size_t w = 1 + (size_t)n;
  for (long k = 0; k < s->npts; ++k) { // rows: the value, then the final q (NaN: failed)
    xy[(size_t)k * w] = value_at(s, k);
    for (int i = 0; i < n; ++i)
      xy[(size_t)k * w + 1 + (size_t)i] = o->status[k] >= 0 ? o->results[k * 2 * n + i] : NAN;
  }
  for (int i = 0; i < n; ++i) {
    const char *name = dal_system_coord_name(sys, i);
    snprintf(title[i], sizeof title[i], "%s: %s at the end against %s", s->c->path, name, s->name);
    se[i] = (cli_series){NULL, xy, xy + 1 + i, NULL, (size_t)s->npts, w, 0};
    pan[i] = (cli_panel){title[i], s->name, name, &se[i], 1};
  }
  int rc = cli_chart(s->c, f, pan, n);
  free(xy), free(pan), free(se), free(title);
  return rc;
}

// run on threads, or over MPI ranks (rank 0 writes); *writer says whether this process writes
static int run_sweep(cli *c, const dal_sweep *sw, dal_sweep_opts *so, dal_sweep_out *o,
                     int *writer) {
  *writer = 1;
  if (!cli_given(c, "mpi"))
    return dal_sweep_run(dal_scene_system(c->sc), sw, so, o, c->msg, sizeof c->msg);
#ifdef DAL_CLI_MPI
  int rank = 0, was = 0;
  MPI_Initialized(&was);
  if (!was && MPI_Init(NULL, NULL) != MPI_SUCCESS) {
    snprintf(c->msg, sizeof c->msg, "sweep --mpi: MPI_Init failed");
    return DAL_E_SOLVER;
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  *writer = rank == 0;
  if (rank) so->progress = NULL;
  int rc =
      dal_sweep_run_mpi(dal_scene_system(c->sc), sw, so, o, MPI_COMM_WORLD, c->msg, sizeof c->msg);
  if (!was) MPI_Finalize();
  return rc;
#else
  (void)sw, (void)so, (void)o;
  snprintf(c->msg, sizeof c->msg,
           "sweep --mpi: this dalembert was built without MPI (configure the library with "
           "-DDAL_WITH_MPI=ON and start it with mpirun); --threads K runs the sweep on threads");
  return DAL_E_UNSUPPORTED;
#endif
}

// whether the scene has a parameter `name`: a line "param NAME ..." of its text written back
static int has_param(const cli *c, const char *name) {
  char *text = NULL;
  size_t len = 0;
  FILE *m = open_memstream(&text, &len);
  if (!m) return 0;
  int rc = dal_scene_write(c->sc, m);
  if (fclose(m)) rc = DAL_E_NOMEM;
  int found = 0;
  size_t n = strlen(name);
  for (const char *l = text; !rc && l && *l && !found; l = strchr(l, '\n'), l = l ? l + 1 : l)
    found = !strncmp(l, "param ", 6) && !strncmp(l + 6, name, n) && strchr(" =\t", l[6 + n]);
  free(text);
  return found;
}

const cli_opt cli_sweep_opts[] = {
    {"param", 0, CLI_TEXT, "NAME=LO:HI:N", "the scene parameter and its grid (required)", 0},
    {"threads", 0, CLI_COUNT, "K", "threads (default 1; 0: every processor)", 1024},
    {"mpi", 0, CLI_FLAG, NULL, "over MPI ranks (start with mpirun; rank 0 writes)", 0},
    CLI_OPT_OUTPUT("the final states"),
    CLI_OPT_FORMAT,
    CLI_OPT_CHART("each coordinate's final value against the parameter"),
    CLI_END,
};

int cli_sweep(cli *c) {
  sweep_ctx s = {c, NULL, "", 0, 0, 0};
  const char *param = cli_text(c, "param");
  if (!param) return cli_error(c, CLI_USAGE, "needs --param NAME=LO:HI:N (a scene parameter)");
  int rc = cli_grid(c, "param", param, s.name, sizeof s.name, &s.lo, &s.hi, &s.npts), writer = 1;
  if (rc) return rc;
  if (!has_param(c, s.name))
    return cli_error(c, DAL_E_ARG, "--param: %s has no parameter '%s'", c->path, s.name);
  int n = dal_system_ncoords(dal_scene_system(c->sc));
  dal_sweep_out o = {0};
  dal_state *st0 = NULL;
  o.msg_len = DAL_SWEEP_MSG_LEN;
  o.results = malloc((size_t)s.npts * 2 * (size_t)n * sizeof *o.results);
  o.status = calloc((size_t)s.npts, sizeof *o.status);
  o.msgs = calloc((size_t)s.npts, (size_t)o.msg_len);
  s.notes = calloc((size_t)s.npts, sizeof *s.notes);
  if (!o.results || !o.status || !o.msgs || !s.notes)
    rc = cli_error(c, DAL_E_NOMEM, "out of memory for %d results of %d numbers and a message",
                   s.npts, 2 * n);
  if (!rc) {
    dal_sweep sw = {.ntraj = s.npts, .nresult = 2 * n, .reduce = reduce, .ctx = &s};
    dal_scene_opts(c->sc, &sw.t0, NULL, NULL);
    // the shared system's start (each trajectory runs its own scene's)
    rc = dal_scene_state(c->sc, &st0);
    if (!rc) {
      sw.q0 = dal_state_q(st0);
      sw.qdot0 = dal_state_qdot(st0);
    }
    dal_sweep_opts so = dal_default_sweep_opts();
    so.nthreads = (int)cli_num(c, "threads", 1);
    so.worker_create = worker_create;
    so.worker_destroy = worker_destroy;
    so.worker_ctx = &s;
    so.progress = on_progress;
    so.progress_ctx = c;
    if (!rc) rc = run_sweep(c, &sw, &so, &o, &writer);
    if (rc < 0 && !(rc == DAL_E_CALLBACK && cli_interrupted())) cli_error(c, rc, "%s", c->msg);
  }
  dal_state_destroy(st0);
  int stopped = rc == DAL_E_CALLBACK && cli_interrupted();
  if (stopped) {
    long run = 0;
    for (long k = 0; k < s.npts; ++k)
      run += o.status[k] != DAL_E_CALLBACK;
    cli_error(c, 0,
              "interrupted: %ld of %d trajectories finished; the others are marked DAL_E_CALLBACK",
              run, s.npts);
    rc = DAL_OK;
  }
  if (!rc && writer) {
    // the chart, then the rows: when either fails neither is left
    const char *chart = cli_text(c, "chart");
    cli_file cf = {0};
    FILE *fp = cli_out(c);
    rc = fp ? write_rows(&s, &o, n, fp) : DAL_E_IO;
    if (chart && rc >= 0 && !(rc = cli_open(c, chart, &cf)))
      rc = cli_commit(c, &cf, sweep_chart(&s, &o, n, &cf));
    int done = cli_close(c, rc);
    if (chart && done < 0 && rc >= 0) remove(chart);
    rc = done;
    long notes = 0;
    for (long k = 0; k < s.npts; ++k)
      notes += s.notes[k] != NULL;
    if (!rc && notes)
      cli_error(c, 0, "note: %ld of %d trajectories left a note (in their message)", notes, s.npts);
    if (!rc && o.nfailed && !stopped)
      cli_error(c, 0, "%ld of %d trajectories failed (their messages are in the %s)", o.nfailed,
                s.npts, cli_json_asked(c) ? "JSON" : "CSV");
  }
  for (long k = 0; s.notes && k < s.npts; ++k)
    free(s.notes[k]);
  free(s.notes);
  free(o.results);
  free(o.status);
  free(o.msgs);
  return rc;
}
