// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// dalembert sweep: the scene's run over a grid of one of its parameters, on threads
// (dal_sweep_run) or over MPI ranks (dal_sweep_run_mpi, when built with MPI). Every worker
// holds its own copy of the scene (the text as written back, with the --set values), and a
// trajectory rebuilds it for its value: a parameter may enter masses, gravity, initial values
// and formulas alike. Results are the final state at t1, bit for bit the same for any number
// of threads or ranks.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#ifdef DAL_CLI_MPI
#include "dalembert/mpi.h"
#endif

typedef struct sweep_ctx {
  cli *c;
  char *text; // the scene written back
  size_t len;
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
  int rc = dal_scene_parse(s->text, s->c->path, (dal_scene **)data, msg, sizeof msg);
  if (rc) fprintf(stderr, "dalembert: sweep: %s\n", msg);
  return rc;
}

static void worker_destroy(void *data, void *ctx) {
  (void)ctx;
  dal_scene_destroy(data);
}

static int reduce(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx) {
  (void)sys, (void)st;
  const sweep_ctx *s = ctx;
  dal_scene *ws = tr->worker;
  dal_state *fin = NULL;
  int rc = dal_scene_set_param(ws, s->name, value_at(s, tr->index), tr->msg, DAL_SWEEP_MSG_LEN);
  if (!rc) rc = dal_scene_run(ws, NULL, &fin, tr->msg, DAL_SWEEP_MSG_LEN);
  if (fin && rc >= 0) {
    int n = dal_system_ncoords(dal_scene_system(ws));
    memcpy(tr->result, dal_state_q(fin), (size_t)n * sizeof(double));
    memcpy(tr->result + n, dal_state_qdot(fin), (size_t)n * sizeof(double));
  }
  dal_state_destroy(fin);
  return rc < 0 ? rc : 0;
}

static int on_progress(long done, long total, long failed, void *ctx) {
  char extra[64];
  snprintf(extra, sizeof extra, "(%ld failed)", failed);
  cli_progress(ctx, "sweep: trajectories", (double)done, (double)total, extra);
  return 0;
}

static int write_rows(const sweep_ctx *s, const dal_sweep_out *o, int n, FILE *fp) {
  const dal_system *sys = dal_scene_system(s->c->sc);
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
    for (const char *m = o->msgs + k * o->msg_len; *m; ++m)
      fputs(*m == '"' ? "\"\"" : (char[2]){*m, 0}, fp);
    fprintf(fp, "\"\n");
  }
  return ferror(fp) ? DAL_E_IO : DAL_OK;
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

const cli_opt cli_sweep_opts[] = {
    {"param", 0, CLI_TEXT, "NAME=LO:HI:N", "the scene parameter and its grid (required)", 0},
    {"threads", 0, CLI_COUNT, "K", "threads (default 1; 0: every processor)", 1024},
    {"mpi", 0, CLI_FLAG, NULL, "over MPI ranks (start with mpirun; rank 0 writes)", 0},
    CLI_OPT_OUTPUT("the final states"),
    CLI_END,
};

static int sweep_setup(cli *c, sweep_ctx *s) {
  const char *param = cli_text(c, "param");
  if (!param) return cli_error(c, CLI_USAGE, "needs --param NAME=LO:HI:N (a scene parameter)");
  int rc = cli_grid(c, "param", param, s->name, sizeof s->name, &s->lo, &s->hi, &s->npts);
  if (rc) return rc;
  FILE *m = open_memstream(&s->text, &s->len);
  if (!m) return DAL_E_NOMEM;
  rc = dal_scene_write(c->sc, m);
  if (fclose(m) && !rc) rc = DAL_E_NOMEM;
  return rc;
}

int cli_sweep(cli *c) {
  sweep_ctx s = {c, NULL, 0, "", 0, 0, 0};
  int rc = sweep_setup(c, &s), writer = 1;
  dal_scene *probe = NULL;
  if (!rc && !(rc = dal_scene_parse(s.text, c->path, &probe, c->msg, sizeof c->msg)))
    rc = dal_scene_set_param(probe, s.name, s.lo, c->msg, sizeof c->msg);
  dal_scene_destroy(probe);
  int n = dal_system_ncoords(dal_scene_system(c->sc));
  dal_sweep_out o = {0};
  dal_state *st0 = NULL;
  o.msg_len = DAL_SWEEP_MSG_LEN;
  if (!rc) {
    o.results = malloc((size_t)s.npts * 2 * (size_t)n * sizeof *o.results);
    o.status = calloc((size_t)s.npts, sizeof *o.status);
    o.msgs = calloc((size_t)s.npts, (size_t)o.msg_len);
    if (!o.results || !o.status || !o.msgs) rc = DAL_E_NOMEM;
  }
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
  }
  dal_state_destroy(st0);
  if (rc < 0) cli_error(c, rc, "%s", c->msg);
  if (!rc && writer) {
    FILE *fp = cli_out(c);
    rc = fp ? write_rows(&s, &o, n, fp) : DAL_E_IO;
    rc = cli_close(c, fp, rc);
    if (!rc && o.nfailed)
      cli_error(c, 0, "%ld of %d trajectories failed (their messages are in the CSV)", o.nfailed,
                s.npts);
  }
  free(o.results);
  free(o.status);
  free(o.msgs);
  free(s.text);
  return rc;
}
