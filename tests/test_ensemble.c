// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Sweeps: determinism over threads and schedules, failures recorded, progress, closed forms.
//
// 1. A driven-pendulum sweep over a (drive amplitude, frequency) grid with per-trajectory
//    initial states: results equal a plain loop (fresh state, dal_state_set_param,
//    dal_advance per trajectory) bit for bit, and the CSV is byte-identical for 1, 2 and 4
//    threads, static and dynamic schedules, chunk sizes 1 and 3, and split in 3 parts.
// 2. Closed form: a mass on a spring, x(t) = cos(sqrt(k/m) t), over a (k, m) grid.
// 3. Failures: negative and NaN masses, a rod that cannot close its loop, a failing reducer:
//    the sweep completes; those rows carry their status and message, the others are exact.
// 4. Progress: serialized calls, done counts 1..ntraj; cancellation leaves "not run" rows.
//    Rejected sweeps: bad sizes are DAL_E_ARG, non-finite t0 / t1 DAL_E_NONFINITE, no slot
//    written.
// 5. Per-worker data: a second state per worker (two-trajectory methods), copied parameters.
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

static const double PI = 3.14159265358979323846;

// pendulum of length 1 with a horizontally driven support (ax cos(w t), 0)
static dal_system *driven(void) {
  scn_knobs k = scn_default(); // a drive of zero amplitude at w = 1, set per trajectory
  k.w = 1.0;
  return scn_pendulum(&k);
}

// a particle on an anchor spring (rest length 0) at the origin, no gravity
static dal_system *oscillator(void) { return scn_oscillator(NULL); }

// a closed loop (test_params.c): rod from (0.5, 0), ring of radius 1, link of 0.8
static dal_system *loop(void) {
  scn_knobs k = scn_default();
  k.x0 = 0.5;
  return scn_closed_loop(&k, 0.8);
}

// reducer: final q, qdot, total energy and accepted steps
static int keep_final(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx) {
  (void)ctx;
  int n = dal_system_ncoords(sys);
  dal_energies e;
  dal_stats s;
  dal_state_energies(st, &e);
  dal_state_stats(st, &s);
  for (int i = 0; i < n; ++i) {
    tr->result[i] = dal_state_q(st)[i];
    tr->result[n + i] = dal_state_qdot(st)[i];
  }
  tr->result[2 * n] = e.E;
  tr->result[2 * n + 1] = (double)s.steps;
  return 0;
}

// the CSV of a sweep as a string (caller frees)
static char *csv_of(const dal_system *sys, const dal_sweep *sw, const dal_sweep_out *out) {
  FILE *fp = tmpfile();
  if (!fp) return NULL;
  int rc = dal_sweep_write_csv(fp, sys, sw, out, NULL);
  long len = ftell(fp);
  char *buf = rc || len < 0 ? NULL : malloc((size_t)len + 1);
  if (buf) {
    rewind(fp);
    size_t got = fread(buf, 1, (size_t)len, fp);
    buf[got] = 0;
  }
  fclose(fp);
  return buf;
}

typedef struct progress_log {
  long calls, last_done, bad_order, cancel_at;
} progress_log;

static int on_progress(long done, long total, long failed, void *ctx) {
  progress_log *lg = ctx;
  (void)failed;
  if (done != lg->last_done + 1 || done > total) lg->bad_order++;
  lg->last_done = done;
  lg->calls++;
  return lg->cancel_at > 0 && done >= lg->cancel_at;
}

static void test_determinism(void) {
  dal_system *sys = driven();
  CHECK(sys != NULL);
  if (!sys) return;
  enum { NA = 4, NW = 6, NT = NA * NW, NR = 4 };
  double values[NT * 2], q0[NT], v0[NT];
  int count[2] = {NA, NW};
  double lo[2] = {0.0, 2.0}, hi[2] = {0.3, 8.0};
  CHECK(dal_sweep_grid(2, count, lo, hi, values) == NT);
  CHECK(values[0] == 0.0 && values[1] == 2.0 && values[2 * NW - 1] == 8.0);
  CHECK(values[2 * NW] == 0.3 * 1.0 / 3 && values[2 * NT - 2] == 0.3);
  for (int i = 0; i < NT; ++i) {
    q0[i] = 0.1 + 0.05 * i;
    v0[i] = 0.3 - 0.02 * i;
  }
  dal_param_ref par[2];
  CHECK_OK(dal_param_find(sys, "place:bob:3", &par[0], NULL, 0));
  CHECK_OK(dal_param_find(sys, "place:bob:5", &par[1], NULL, 0));
  dal_solve_opts so = dal_default_solve_opts();
  so.method = DAL_METHOD_DOPRI5;
  dal_sweep sw = {.ntraj = NT,
                  .nparam = 2,
                  .params = par,
                  .values = values,
                  .t0 = 0.0,
                  .q0 = q0,
                  .qdot0 = v0,
                  .state_stride = 1,
                  .solve = &so,
                  .t1 = 3.0,
                  .nresult = NR,
                  .reduce = keep_final};
  // the plain loop: a fresh state per trajectory
  double ref[NT * NR];
  for (int i = 0; i < NT; ++i) {
    dal_state *st = NULL;
    CHECK_OK(dal_state_create(sys, &st));
    for (int j = 0; j < 2; ++j)
      CHECK_OK(dal_state_set_param(sys, st, &par[j], values[2 * i + j]));
    CHECK_OK(dal_state_set(sys, st, 0.0, &q0[i], &v0[i]));
    CHECK_OK(dal_advance(sys, st, &so, 3.0));
    dal_traj tr = {i, values + 2 * i, ref + i * NR, NR, NULL, 0, NULL};
    keep_final(sys, st, &tr, NULL);
    dal_state_destroy(st);
  }
  char *first = NULL;
  const int threads[] = {1, 2, 4};
  for (int ti = 0; ti < 3; ++ti)
    for (int sched = 0; sched < 2; ++sched)
      for (int chunk = 1; chunk <= 3; chunk += 2) {
        double res[NT * NR];
        int status[NT];
        char msgs[NT * 64];
        dal_sweep_out out = {res, status, msgs, 64, 0, 0};
        dal_sweep_opts o = dal_default_sweep_opts();
        o.nthreads = threads[ti];
        o.schedule = sched ? DAL_SCHEDULE_STATIC : DAL_SCHEDULE_DYNAMIC;
        o.chunk = chunk;
        char err[256];
        CHECK_OK(dal_sweep_run(sys, &sw, &o, &out, err, sizeof err));
        CHECK(out.nfailed == 0 && out.nrun == NT);
        CHECK_MSG(memcmp(res, ref, sizeof res) == 0,
                  "threads %d sched %d chunk %d: results differ "
                  "from the plain loop",
                  threads[ti], sched, chunk);
        char *csv = csv_of(sys, &sw, &out);
        CHECK(csv != NULL);
        if (!first)
          first = csv;
        else {
          CHECK_MSG(csv && strcmp(csv, first) == 0, "threads %d sched %d chunk %d: CSV differs",
                    threads[ti], sched, chunk);
          free(csv);
        }
      }
  // the same sweep in 3 parts (a job array), merged
  double res[NT * NR];
  int status[NT];
  char msgs[NT * 64];
  dal_sweep_out out = {res, status, msgs, 64, 0, 0};
  long total = 0;
  for (int part = 0; part < 3; ++part) {
    dal_sweep_opts o = dal_default_sweep_opts();
    o.nthreads = 2;
    o.part = part;
    o.nparts = 3;
    o.part_block = 2;
    CHECK_OK(dal_sweep_run(sys, &sw, &o, &out, NULL, 0));
    total += out.nrun;
  }
  CHECK(total == NT);
  char *csv = csv_of(sys, &sw, &out);
  CHECK(csv && first && strcmp(csv, first) == 0);
  // per-trajectory initial states: their columns follow the parameters, each row holds its own
  const char *head = "index,place:bob:3,place:bob:5,q0:theta,qdot0:theta,status,r0,r1,r2,r3,"
                     "message\n";
  CHECK_MSG(first && strncmp(first, head, strlen(head)) == 0, "CSV header: %.80s",
            first ? first : "(none)");
  for (int i = 0; first && i < NT; i += 7) {
    char want[160];
    snprintf(want, sizeof want, "\n%d,%.17g,%.17g,%.17g,%.17g,DAL_OK,", i, values[2 * i],
             values[2 * i + 1], q0[i], v0[i]);
    CHECK_MSG(strstr(first, want) != NULL, "CSV row %d lacks its start: %s", i, want + 1);
  }
  free(csv);
  free(first);
  dal_system_destroy(sys);
}

static int keep_x(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx) {
  (void)sys;
  (void)ctx;
  tr->result[0] = dal_state_q(st)[0];
  return 0;
}

static void test_closed_form(void) {
  dal_system *sys = oscillator();
  CHECK(sys != NULL);
  if (!sys) return;
  enum { NK = 5, NM = 4, NT = NK * NM };
  double values[NT * 2], res[NT];
  int count[2] = {NK, NM}, status[NT];
  double lo[2] = {0.5, 0.2}, hi[2] = {8.0, 3.0};
  dal_sweep_grid(2, count, lo, hi, values);
  dal_param_ref par[2];
  CHECK_OK(dal_param_find(sys, "spring:0:k", &par[0], NULL, 0));
  CHECK_OK(dal_param_find(sys, "mass:bob", &par[1], NULL, 0));
  double q0[2] = {1.0, 0.0}, v0[2] = {0.0, 0.0};
  dal_solve_opts so = dal_default_solve_opts();
  so.rtol = 1e-11;
  so.atol = 1e-13;
  dal_sweep sw = {.ntraj = NT,
                  .nparam = 2,
                  .params = par,
                  .values = values,
                  .q0 = q0,
                  .qdot0 = v0,
                  .solve = &so,
                  .t1 = 2.0,
                  .nresult = 1,
                  .reduce = keep_x};
  dal_sweep_out out = {res, status, NULL, 0, 0, 0};
  dal_sweep_opts o = dal_default_sweep_opts();
  o.nthreads = 2;
  CHECK_OK(dal_sweep_run(sys, &sw, &o, &out, NULL, 0));
  for (int i = 0; i < NT; ++i) {
    double k = values[2 * i], m = values[2 * i + 1];
    CHECK(status[i] == DAL_OK);
    CHECK_CLOSE(res[i], cos(sqrt(k / m) * 2.0), 1e-8);
  }
  dal_system_destroy(sys);
}

static int failing_reducer(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx) {
  (void)ctx;
  if (tr->index == 7) {
    snprintf(tr->msg, DAL_SWEEP_MSG_LEN, "reducer: no section crossing in trajectory %ld",
             tr->index);
    return DAL_E_CALLBACK;
  }
  const double *q = dal_state_q(st);
  (void)sys;
  tr->result[0] = hypot(q[0] - 0.5, q[1]); // the rod's length, as the state has it
  tr->result[1] = hypot(q[0] - q[2], q[1] - q[3]);
  return 0;
}

static void test_failures(void) {
  dal_system *sys = loop();
  CHECK(sys != NULL);
  if (!sys) return;
  enum { NT = 9 };
  // (rod length, mass of p): 3 bad masses, 2 rods that cannot close, 1 reducer failure
  double values[NT * 2] = {1.0, 1.0, 1.1, -1.0, 0.9, 2.0, 5.0, 1.0,  1.2,
                           NAN, 4.0, 1.0, 1.05, 0.0, 1.0, 3.0, 0.95, 1.5};
  int expect[NT] = {DAL_OK,           DAL_E_ARG,       DAL_OK,
                    DAL_E_CONSTRAINT, DAL_E_NONFINITE, DAL_E_CONSTRAINT,
                    DAL_E_ARG,        DAL_E_CALLBACK,  DAL_OK};
  dal_param_ref par[2];
  CHECK_OK(dal_param_find(sys, "con:rod:0", &par[0], NULL, 0));
  CHECK_OK(dal_param_find(sys, "mass:p", &par[1], NULL, 0));
  double q0[4] = {0.9, -0.9, 0.3, -0.9}, v0[4] = {0, 0, 0, 0}, res[NT * 2];
  int status[NT];
  char msgs[NT * 512];
  dal_solve_opts so = dal_default_solve_opts();
  dal_sweep sw = {.ntraj = NT,
                  .nparam = 2,
                  .params = par,
                  .values = values,
                  .q0 = q0,
                  .qdot0 = v0,
                  .solve = &so,
                  .t1 = 0.5,
                  .nresult = 2,
                  .reduce = failing_reducer};
  dal_sweep_out out = {res, status, msgs, 512, 0, 0};
  dal_sweep_opts o = dal_default_sweep_opts();
  o.nthreads = 2;
  CHECK_OK(dal_sweep_run(sys, &sw, &o, &out, NULL, 0));
  CHECK(out.nfailed == 6 && out.nrun == NT);
  for (int i = 0; i < NT; ++i) {
    const char *m = msgs + i * 512;
    CHECK_MSG(status[i] == expect[i], "trajectory %d: %s (%s), expected %s", i,
              dal_status_name(status[i]), m, dal_status_name(expect[i]));
    if (status[i] == DAL_OK) {
      CHECK(m[0] == 0);
      CHECK_CLOSE(res[2 * i], values[2 * i], 1e-7); // the overridden rod holds
      CHECK_CLOSE(res[2 * i + 1], 0.8, 1e-7);
    } else {
      CHECK(isnan(res[2 * i]) && isnan(res[2 * i + 1]));
    }
  }
  CHECK(strstr(msgs + 1 * 512, "particle 'p': mass -1 is not positive"));
  CHECK(strstr(msgs + 4 * 512, "particle 'p': mass is nan"));
  CHECK(strstr(msgs + 3 * 512, "'rod'") && strstr(msgs + 3 * 512, "conflict"));
  CHECK(strstr(msgs + 7 * 512, "no section crossing in trajectory 7"));
  // the CSV carries statuses and messages
  char *csv = csv_of(sys, &sw, &out);
  CHECK(csv && strstr(csv, "\n1,1.1000000000000001,-1,DAL_E_ARG,nan,nan,\"particle 'p': mass -1"));
  CHECK(csv && strstr(csv, "\n3,5,1,DAL_E_CONSTRAINT,nan,nan,\"constraints 'rod'"));
  CHECK(csv && strstr(csv, "\n0,1,1,DAL_OK,"));
  free(csv);
  dal_system_destroy(sys);
}

static void test_progress(void) {
  dal_system *sys = oscillator();
  if (!sys) return;
  enum { NT = 12 };
  double values[NT], res[NT], q0[2] = {1, 0}, v0[2] = {0, 0};
  int status[NT];
  char msgs[NT * 128];
  for (int i = 0; i < NT; ++i)
    values[i] = 1.0 + i;
  dal_param_ref par;
  CHECK_OK(dal_param_find(sys, "spring:0:k", &par, NULL, 0));
  dal_solve_opts so = dal_default_solve_opts();
  dal_sweep sw = {.ntraj = NT,
                  .nparam = 1,
                  .params = &par,
                  .values = values,
                  .q0 = q0,
                  .qdot0 = v0,
                  .solve = &so,
                  .t1 = 1.0,
                  .nresult = 1,
                  .reduce = keep_x};
  dal_sweep_out out = {res, status, msgs, 128, 0, 0};
  for (int threads = 1; threads <= 4; threads *= 2) {
    progress_log lg = {0, 0, 0, 0};
    dal_sweep_opts o = dal_default_sweep_opts();
    o.nthreads = threads;
    o.progress = on_progress;
    o.progress_ctx = &lg;
    CHECK_OK(dal_sweep_run(sys, &sw, &o, &out, NULL, 0));
    CHECK(lg.calls == NT && lg.last_done == NT && lg.bad_order == 0);
  }
  // cancel after 5 of 12 (one thread: exactly 5 run)
  progress_log lg = {0, 0, 0, 5};
  dal_sweep_opts o = dal_default_sweep_opts();
  o.progress = on_progress;
  o.progress_ctx = &lg;
  char err[256];
  CHECK(dal_sweep_run(sys, &sw, &o, &out, err, sizeof err) == DAL_E_CALLBACK);
  CHECK(strstr(err, "cancelled") != NULL);
  CHECK(out.nrun == 5);
  for (int i = 0; i < NT; ++i) {
    CHECK(i < 5 ? status[i] == DAL_OK : status[i] == DAL_E_CALLBACK);
    CHECK(i < 5 || (isnan(res[i]) && strstr(msgs + i * 128, "not run")));
  }
  // invalid sweeps are rejected before anything runs
  dal_param_ref badp = {DAL_PARAM_MASS, 4, 0};
  dal_sweep bad = sw;
  bad.params = &badp;
  o = dal_default_sweep_opts();
  CHECK(dal_sweep_run(sys, &bad, &o, &out, err, sizeof err) == DAL_E_ARG);
  CHECK(strstr(err, "particle index 4 out of range") != NULL);
  bad = sw;
  bad.ntraj = 0;
  CHECK(dal_sweep_run(sys, &bad, &o, &out, err, sizeof err) == DAL_E_ARG);
  // non-finite times are DAL_E_NONFINITE (the library's convention for non-finite input),
  // named in the message, and reject the sweep before any slot is written
  const double nonfinite[3] = {NAN, INFINITY, -INFINITY};
  for (int k = 0; k < 6; ++k) {
    bad = sw;
    if (k < 3)
      bad.t1 = nonfinite[k];
    else
      bad.t0 = nonfinite[k - 3];
    for (int i = 0; i < NT; ++i)
      status[i] = 12345;
    out.nrun = -1;
    CHECK(dal_sweep_run(sys, &bad, &o, &out, err, sizeof err) == DAL_E_NONFINITE);
    CHECK(strstr(err, k < 3 ? "target time t1" : "initial time t0") != NULL);
    CHECK(status[0] == 12345 && status[NT - 1] == 12345 && out.nrun == -1);
  }
  // t1 is only read with solve options: a reducer-driven sweep ignores it
  bad = sw;
  bad.solve = NULL;
  bad.t1 = NAN;
  CHECK_OK(dal_sweep_run(sys, &bad, &o, &out, err, sizeof err));
  CHECK(out.nrun == NT && out.nfailed == 0);
  dal_sweep_opts raw;
  memset(&raw, 0, sizeof raw);
  CHECK(dal_sweep_run(sys, &sw, &raw, &out, err, sizeof err) == DAL_E_ARG);
  CHECK(strstr(err, "dal_default_sweep_opts") != NULL);
  dal_system_destroy(sys);
}

// per-worker second state: the reducer runs a copy with the same parameters, shifted by a
// quarter period, and keeps the distance between the two at t1 against the closed form
static int make_state(const dal_system *sys, int id, void *ctx, void **data) {
  (void)id;
  (void)ctx;
  dal_state *st = NULL;
  int rc = dal_state_create(sys, &st);
  *data = st;
  return rc;
}

static void free_state(void *data, void *ctx) {
  (void)ctx;
  dal_state_destroy(data);
}

static int pair(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx) {
  (void)ctx;
  dal_state *other = tr->worker;
  double k = tr->values[0], w = sqrt(k);
  double q[2] = {cos(w * 0.3), 0}, v[2] = {-w * sin(w * 0.3), 0};
  dal_solve_opts so = dal_default_solve_opts();
  so.rtol = 1e-11;
  so.atol = 1e-13;
  int rc = dal_state_copy_params(sys, other, st);
  if (!rc) rc = dal_state_set(sys, other, 0.0, q, v);
  if (!rc) rc = dal_advance(sys, other, &so, 1.0);
  if (!rc) rc = dal_advance(sys, st, &so, 1.0);
  if (rc) return rc;
  tr->result[0] = dal_state_q(other)[0] - dal_state_q(st)[0];
  return 0;
}

static void test_workers(void) {
  dal_system *sys = oscillator();
  if (!sys) return;
  enum { NT = 8 };
  double values[NT], res[NT], q0[2] = {1, 0}, v0[2] = {0, 0};
  int status[NT];
  for (int i = 0; i < NT; ++i)
    values[i] = 0.5 + 0.7 * i;
  dal_param_ref par = {DAL_PARAM_SPRING_K, 0, 0};
  dal_sweep sw = {.ntraj = NT,
                  .nparam = 1,
                  .params = &par,
                  .values = values,
                  .q0 = q0,
                  .qdot0 = v0,
                  .nresult = 1,
                  .reduce = pair};
  dal_sweep_out out = {res, status, NULL, 0, 0, 0};
  dal_sweep_opts o = dal_default_sweep_opts();
  o.nthreads = 3;
  o.worker_create = make_state;
  o.worker_destroy = free_state;
  CHECK_OK(dal_sweep_run(sys, &sw, &o, &out, NULL, 0));
  for (int i = 0; i < NT; ++i) {
    double w = sqrt(values[i]);
    CHECK(status[i] == DAL_OK);
    CHECK_CLOSE(res[i], cos(w * 1.3) - cos(w * 1.0), 1e-8);
  }
  (void)PI;
  dal_system_destroy(sys);
}

int main(void) {
  test_determinism();
  test_closed_form();
  test_failures();
  test_progress();
  test_workers();
  return check_summary("test_ensemble");
}
