# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The cffi (API mode) description of the C library: the declarations Python calls, compiled
# against the installed headers so that struct layouts and constants come from the compiler.
#
# Used two ways: CMake runs `python3 _build.py emit OUT.c` and compiles the C file itself (one
# library target, rpath handled by CMake); setup.py hands `ffi` to cffi's setuptools hook
# (cffi_modules), which finds the installed library by pkg-config or DALEMBERT_PREFIX.
import os
import shlex
import subprocess
import sys

import cffi

# Only names: every struct is partial ("...;") and every enum takes its values from the
# headers ("..."), so nothing here can drift from the C declarations.
CDEF = r"""
typedef enum { DAL_OK, DAL_STOPPED, DAL_EVENT, DAL_CANCELLED, DAL_E_ARG, DAL_E_NOMEM,
  DAL_E_NONFINITE, DAL_E_DOMAIN, DAL_E_SINGULAR, DAL_E_CALLBACK, DAL_E_CONSTRAINT, DAL_E_INIT,
  DAL_E_STEP, DAL_E_MAXSTEPS, DAL_E_CONV, DAL_E_SOLVER, DAL_E_TIME, DAL_E_STATE,
  DAL_E_UNSUPPORTED, DAL_E_IO, DAL_E_VERIFY, ... } dal_status;
const char *dal_status_string(int status);
const char *dal_status_name(int status);
const char *dal_version(void);

typedef enum { DAL_METHOD_AUTO, DAL_METHOD_DOPRI5, DAL_METHOD_FEHLBERG78, DAL_METHOD_BS,
  DAL_METHOD_RK4, DAL_METHOD_ADAMS, DAL_METHOD_BDF, DAL_METHOD_VARIATIONAL,
  DAL_METHOD_VARIATIONAL4, DAL_METHOD_VARIATIONAL6, DAL_METHOD_RATTLE, DAL_METHOD_RATTLE4,
  DAL_METHOD_RATTLE6, ... } dal_method;
typedef enum { DAL_FORM_AUTO, DAL_FORM_ODE, DAL_FORM_GGL, DAL_FORM_INDEX1, DAL_FORM_INDEX3,
  ... } dal_formulation;
typedef enum { DAL_EXPR_TEXT, DAL_EXPR_LATEX, ... } dal_expr_format;
typedef enum { DAL_UNSTABLE, DAL_MARGINAL, DAL_NEUTRAL, DAL_ASYMPTOTIC, ... } dal_stability;

typedef struct dal_system dal_system;
typedef struct dal_state dal_state;
typedef struct dal_scene dal_scene;
typedef struct dal_events dal_events;
typedef struct dal_trajectory dal_trajectory;

typedef struct {
  dal_method method;
  dal_formulation form;
  double rtol;
  double atol;
  double hmax;
  double fixed_step;
  long max_steps;
  ...;
} dal_solve_opts;
dal_solve_opts dal_default_solve_opts(void);
const char *dal_method_name(dal_method m);
const char *dal_formulation_name(dal_formulation f);

typedef struct {
  long steps;
  long rejected;
  long rhs_evals;
  long jac_evals;
  double rtol_used;
  dal_method method_used;
  dal_formulation form_used;
  int fallbacks;
  double fallback_t;
  ...;
} dal_stats;
int dal_state_stats(const dal_state *st, dal_stats *out);
int dal_advance(const dal_system *sys, dal_state *st, const dal_solve_opts *opts, double t1);

typedef struct {
  double T; double U; double E; double h; double W;
  ...;
} dal_energies;

int dal_scene_parse(const char *text, const char *name, dal_scene **out, char *msg,
                    size_t msglen);
void dal_scene_destroy(dal_scene *sc);
int dal_scene_set_param(dal_scene *sc, const char *name, double value, char *msg,
                        size_t msglen);
const dal_system *dal_scene_system(const dal_scene *sc);
const dal_solve_opts *dal_scene_opts(const dal_scene *sc, double *t0, double *t1, double *dt);
int dal_scene_state(const dal_scene *sc, dal_state **out);
int dal_scene_events(const dal_scene *sc, dal_events **out);
int dal_scene_event_is_section(const dal_scene *sc, int i);
double dal_scene_strobe(const dal_scene *sc);

int dal_system_dim(const dal_system *sys);
int dal_system_ncoords(const dal_system *sys);
int dal_system_nparticles(const dal_system *sys);
int dal_system_nconstraints(const dal_system *sys);
const char *dal_system_coord_name(const dal_system *sys, int i);
const char *dal_system_particle_name(const dal_system *sys, int k);
const char *dal_system_constraint_name(const dal_system *sys, int i);

int dal_state_create(const dal_system *sys, dal_state **out);
void dal_state_destroy(dal_state *st);
const char *dal_state_errmsg(const dal_state *st);
int dal_state_set(const dal_system *sys, dal_state *st, double t, const double *q,
                  const double *qdot);
int dal_forward(const dal_system *sys, dal_state *st);
double dal_state_time(const dal_state *st);
const double *dal_state_q(const dal_state *st);
const double *dal_state_qdot(const dal_state *st);
const double *dal_state_positions(const dal_state *st);
const double *dal_state_lambda(const dal_state *st);
int dal_state_energies(const dal_state *st, dal_energies *out);

int dal_events_create(const dal_system *sys, dal_events **out);
void dal_events_destroy(dal_events *ev);
const char *dal_events_errmsg(const dal_events *ev);
int dal_events_size(const dal_events *ev);
const char *dal_events_name(const dal_events *ev, int i);
typedef struct { double t; int event; int direction; ...; } dal_event_record;
long dal_events_count(const dal_events *ev);
int dal_events_get(const dal_events *ev, long i, dal_event_record *rec, double *q, double *qdot);

int dal_trajectory_create(const dal_system *sys, dal_trajectory **out);
void dal_trajectory_destroy(dal_trajectory *tr);
int dal_trajectory_eval(dal_trajectory *tr, double t, double *q, double *qdot);
long dal_trajectory_span(const dal_trajectory *tr, double *t0, double *t1);
const char *dal_trajectory_errmsg(const dal_trajectory *tr);

int dal_linearize(const dal_system *sys, dal_state *st, double *M, double *C, double *K);
int dal_linearize_inputs(const dal_system *sys, dal_state *st, int ninput,
                         const char *const *inputs, double *B, double *Af, double *Bf);
int dal_state_transition(const dal_system *sys, dal_state *st, const dal_solve_opts *opts,
                         double t1, double *Phi, int nparam, const char *const *params,
                         double *S);
const char *dal_stability_name(dal_stability s);
typedef struct {
  dal_stability verdict; double max_real; double tau; double asymmetry; double gyroscopic;
  double accel; ...;
} dal_modes;
int dal_normal_modes(const dal_system *sys, dal_state *st, double *omega2, double *shapes,
                     double *lambda_re, double *lambda_im, dal_modes *out);
typedef struct { double xtol; int max_iter; double max_step; ...; } dal_equilibrium_opts;
dal_equilibrium_opts dal_default_equilibrium_opts(void);
typedef struct { int iterations; double step; double accel; double unsteady; ...; }
  dal_equilibrium_report;
int dal_equilibrium(const dal_system *sys, dal_state *st, const dal_equilibrium_opts *o,
                    dal_equilibrium_report *rep);
typedef struct {
  int nexp; double t_end; double transient; double renorm; dal_method method; double rtol;
  double atol; double h; long max_steps; ...;
} dal_lyapunov_opts;
dal_lyapunov_opts dal_default_lyapunov_opts(void);

/* the module's own C helpers (pyd_*), compiled with it */
typedef struct {
  long cap, len;
  int n, N, d, m, drop;
  double *t, *q, *qdot, *pos, *lam, *energy;
  double tnow;
  ...;
} pyd_rows;
double pyd_progress(pyd_rows *rows);
int pyd_solve(const dal_system *sys, dal_state *st, dal_solve_opts *o, int grid, double t1,
              double dt, const double *times, size_t ntimes, pyd_rows *rows, dal_trajectory *tr,
              dal_events *ev, int *cancel);
int pyd_lyapunov(const dal_system *sys, dal_state *st, dal_lyapunov_opts *o, double *exps,
                 double *errs, int *cancel);
void pyd_sigint_begin(int *cancel);
void pyd_sigint_end(void);
char *pyd_scene_text(const dal_scene *sc, int show, dal_expr_format fmt, int *rc, char *msg,
                     size_t msglen);
void pyd_free(void *p);
int pyd_formula_value(const char *formula, int nparam, const char *const *pnames,
                      const double *pvals, double *out, char *msg, size_t msglen);
int pyd_add_event(dal_events *ev, const dal_system *sys, const char *name, const char *formula,
                  int nparam, const char *const *pnames, const double *pvals, int direction,
                  int terminal, char *msg, size_t msglen);
void pyd_events_destroy(dal_events *ev);
int pyd_sweep(const dal_system *sys, int nparam, const char *const *names,
              const double *values, long ntraj, const double *q0, const double *qdot0, double t0,
              const dal_solve_opts *o, double t1, int nthreads, double *results, int *status,
              char *msgs, int msglen, char *err, size_t errlen);
"""

SOURCE = r"""
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <dalembert/dalembert.h>
#include <dalembert/scene.h>
#include <dalembert/expr.h>
#include <dalembert/analysis.h>
#include <dalembert/ensemble.h>


typedef struct pyd_rows {
  long cap, len;
  int n, N, d, m;
  int drop; /* rows past cap: dropped (the end time added to t_eval) or a failure */
  double *t, *q, *qdot, *pos, *lam, *energy;
  double tnow; /* time of the last output, read by the progress bar's thread */
} pyd_rows;

double pyd_progress(pyd_rows *r) {
  double t;
  __atomic_load(&r->tnow, &t, __ATOMIC_RELAXED);
  return t;
}

/* one output row into the caller's numpy buffers: no Python per step */
static int pyd_monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  pyd_rows *r = ctx;
  if (r->len >= r->cap) return r->drop ? 0 : -1;
  long i = r->len;
  size_t n = (size_t)r->n;
  double t = dal_state_time(st);
  r->t[i] = t;
  __atomic_store(&r->tnow, &t, __ATOMIC_RELAXED);
  memcpy(r->q + i * n, dal_state_q(st), n * sizeof(double));
  memcpy(r->qdot + i * n, dal_state_qdot(st), n * sizeof(double));
  if (r->pos) {
    const double *p = dal_state_positions(st);
    size_t k = (size_t)r->N * (size_t)r->d;
    if (!p) return -1;
    memcpy(r->pos + i * k, p, k * sizeof(double));
  }
  if (r->lam && r->m) {
    const double *l = dal_state_lambda(st);
    for (int j = 0; j < r->m; ++j) r->lam[i * r->m + j] = l ? l[j] : NAN;
  }
  if (r->energy) {
    dal_energies e;
    if (dal_state_energies(st, &e)) return -1;
    double *E = r->energy + 4 * i;
    E[0] = e.E, E[1] = e.T, E[2] = e.U, E[3] = e.h;
  }
  r->len++;
  return 0;
}

static int pyd_cancel_fn(void *ctx) { return __atomic_load_n((int *)ctx, __ATOMIC_RELAXED); }

/* Ctrl-C during a C call of the main thread: Python's SIGINT handler is replaced by one that
   sets the run's cancel flag, and put back after the call (one call at a time: the main
   thread's; the module's only mutable statics) */
static int *pyd_sig_flag;
static struct sigaction pyd_sig_old;

static void pyd_on_sigint(int sig) {
  (void)sig;
  if (pyd_sig_flag) __atomic_store_n(pyd_sig_flag, 1, __ATOMIC_RELAXED);
}

void pyd_sigint_begin(int *cancel) {
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = pyd_on_sigint;
  sigemptyset(&sa.sa_mask);
  pyd_sig_flag = cancel;
  sigaction(SIGINT, &sa, &pyd_sig_old);
}

void pyd_sigint_end(void) {
  sigaction(SIGINT, &pyd_sig_old, NULL);
  pyd_sig_flag = NULL;
}

/* the cancel hook (solve.h): the int Ctrl-C sets, read after every accepted step */
static void pyd_set_cancel(dal_solve_opts *o, int *cancel) {
  o->cancel = cancel ? pyd_cancel_fn : NULL;
  o->cancel_ctx = cancel;
}

int pyd_solve(const dal_system *sys, dal_state *st, dal_solve_opts *o, int grid, double t1,
              double dt, const double *times, size_t ntimes, pyd_rows *rows, dal_trajectory *tr,
              dal_events *ev, int *cancel) {
  pyd_set_cancel(o, cancel);
  int rc = DAL_OK;
  if (tr) rc = dal_state_set_trajectory(st, tr);
  if (!rc && ev) rc = dal_state_set_events(st, ev);
  if (!rc) {
    if (grid)
      rc = dal_evolve(sys, st, o, t1, dt, pyd_monitor, rows);
    else
      rc = dal_evolve_at(sys, st, o, times, ntimes, pyd_monitor, rows);
  }
  if (ev) dal_state_set_events(st, NULL);
  if (tr) dal_state_set_trajectory(st, NULL);
  pyd_set_cancel(o, NULL);
  return rc;
}

typedef struct pyd_lctx { int *cancel; } pyd_lctx;
static int pyd_lyap_monitor(double t, const double *e, int n, void *ctx) {
  (void)t, (void)e, (void)n;
  pyd_lctx *c = ctx;
  return c->cancel ? pyd_cancel_fn(c->cancel) : 0;
}

int pyd_lyapunov(const dal_system *sys, dal_state *st, dal_lyapunov_opts *o, double *exps,
                 double *errs, int *cancel) {
  pyd_lctx c = {cancel};
  return dal_lyapunov(sys, st, o, exps, errs, pyd_lyap_monitor, &c);
}

/* the scene written back (show = 0) or its equations (show = 1), as a malloc'd string */
char *pyd_scene_text(const dal_scene *sc, int show, dal_expr_format fmt, int *rc, char *msg,
                     size_t msglen) {
  char *buf = NULL;
  size_t len = 0;
  FILE *fp = open_memstream(&buf, &len);
  if (!fp) {
    *rc = DAL_E_NOMEM;
    return NULL;
  }
  *rc = show ? dal_scene_show(sc, fp, fmt, msg, msglen) : dal_scene_write(sc, fp);
  if (fclose(fp) && !*rc) *rc = DAL_E_IO;
  return buf;
}

void pyd_free(void *p) { free(p); }

/* the value of a formula of parameters (a `param` line written back as its formula) */
int pyd_formula_value(const char *formula, int nparam, const char *const *pnames,
                      const double *pvals, double *out, char *msg, size_t msglen) {
  dal_expr_def d = dal_default_expr_def();
  d.name = "param";
  d.formulas = &formula;
  d.nout = 1;
  d.params = pnames;
  d.values = pvals;
  d.nparam = nparam;
  dal_expr *e = NULL;
  int rc = dal_expr_create(&d, &e, msg, msglen);
  if (rc) return rc;
  dal_jet in = dal_const(0.0), res;
  rc = dal_expr_eval(e, &in, dal_const(0.0), NULL, &res);
  dal_expr_destroy(e);
  *out = res.v;
  return rc;
}

/* an event g(t, q, qdot) from a formula; the expression is owned by the event set's list */
typedef struct pyd_evx {
  dal_events *ev;
  dal_expr **ex;
  int nex;
} pyd_evx;

int pyd_add_event(dal_events *ev, const dal_system *sys, const char *name, const char *formula,
                  int nparam, const char *const *pnames, const double *pvals, int direction,
                  int terminal, char *msg, size_t msglen) {
  int n = dal_system_ncoords(sys);
  const char **in = malloc((size_t)(n ? n : 1) * sizeof *in);
  if (!in) return DAL_E_NOMEM;
  for (int i = 0; i < n; ++i) in[i] = dal_system_coord_name(sys, i);
  dal_expr_def d = dal_default_expr_def();
  d.name = name;
  d.formulas = &formula;
  d.nout = 1;
  d.inputs = in;
  d.nin = n;
  d.velocities = 1;
  d.params = pnames;
  d.values = pvals;
  d.nparam = nparam;
  dal_expr *e = NULL;
  int rc = dal_expr_create(&d, &e, msg, msglen);
  free(in);
  if (rc) return rc;
  dal_event_def ed = dal_default_event_def();
  ed.name = name;
  ed.g = dal_expr_event;
  ed.ctx = e;
  ed.direction = (dal_event_direction)direction;
  ed.terminal = terminal;
  int k = dal_events_add(ev, &ed);
  if (k < 0) {
    snprintf(msg, msglen, "%s", dal_events_errmsg(ev));
    dal_expr_destroy(e);
  }
  return k;
}

void pyd_events_destroy(dal_events *ev) { dal_events_destroy(ev); }

/* a sweep over named parameters; the result slot holds the final q and qdot */
static int pyd_reduce(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx) {
  (void)ctx;
  int n = dal_system_ncoords(sys);
  memcpy(tr->result, dal_state_q(st), (size_t)n * sizeof(double));
  memcpy(tr->result + n, dal_state_qdot(st), (size_t)n * sizeof(double));
  return 0;
}

int pyd_sweep(const dal_system *sys, int nparam, const char *const *names,
              const double *values, long ntraj, const double *q0, const double *qdot0, double t0,
              const dal_solve_opts *o, double t1, int nthreads, double *results, int *status,
              char *msgs, int msglen, char *err, size_t errlen) {
  dal_param_ref *refs = calloc((size_t)(nparam ? nparam : 1), sizeof *refs);
  if (!refs) return DAL_E_NOMEM;
  for (int i = 0; i < nparam; ++i) {
    int rc = dal_param_find(sys, names[i], &refs[i], err, errlen);
    if (rc) {
      free(refs);
      return rc;
    }
  }
  dal_sweep sw = {0};
  sw.ntraj = ntraj;
  sw.nparam = nparam;
  sw.params = refs;
  sw.values = values;
  sw.t0 = t0;
  sw.q0 = q0;
  sw.qdot0 = qdot0;
  sw.state_stride = 0;
  sw.solve = o;
  sw.t1 = t1;
  sw.nresult = 2 * dal_system_ncoords(sys);
  sw.reduce = pyd_reduce;
  dal_sweep_opts so = dal_default_sweep_opts();
  so.nthreads = nthreads;
  dal_sweep_out out = {results, status, msgs, msglen, 0, 0};
  int rc = dal_sweep_run(sys, &sw, &so, &out, err, errlen);
  free(refs);
  return rc;
}
"""


def _pkg_config(*args):
    try:
        out = subprocess.run(["pkg-config", *args, "dalembert"], check=True,
                             capture_output=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return []
    return shlex.split(out)


def make_ffi(include_dirs=(), library_dirs=(), rpath=()):
    """The FFI builder; the library found by the given dirs, DALEMBERT_PREFIX or pkg-config."""
    include_dirs, library_dirs, rpath = list(include_dirs), list(library_dirs), list(rpath)
    prefix = os.environ.get("DALEMBERT_PREFIX")
    if prefix:
        include_dirs.append(os.path.join(prefix, "include"))
        for sub in ("lib", "lib64", "lib/x86_64-linux-gnu", "lib/aarch64-linux-gnu"):
            d = os.path.join(prefix, sub)
            if os.path.exists(os.path.join(d, "libdalembert.so")):
                library_dirs.append(d)
                rpath.append(d)
    elif not include_dirs:
        include_dirs += [f[2:] for f in _pkg_config("--cflags-only-I")]
        libs = [f[2:] for f in _pkg_config("--libs-only-L")]
        library_dirs += libs
        rpath += libs
    ffi = cffi.FFI()
    ffi.cdef(CDEF)
    ffi.set_source("dalembert._dal", SOURCE, include_dirs=include_dirs,
                   library_dirs=library_dirs, libraries=["dalembert", "m"],
                   extra_link_args=[f"-Wl,-rpath,{d}" for d in rpath])
    return ffi


ffi = make_ffi() if __name__ != "__main__" else None

if __name__ == "__main__":
    # python3 _build.py emit OUT.c: the C source of the module, for CMake to compile
    if len(sys.argv) != 3 or sys.argv[1] != "emit":
        sys.exit("usage: _build.py emit OUT.c")
    make_ffi(include_dirs=["/nonexistent"]).emit_c_code(sys.argv[2])
