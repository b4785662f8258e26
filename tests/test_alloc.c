// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Out-of-memory behaviour: every allocation the library itself makes is failed in turn, and
// the library must answer DAL_E_NOMEM (or DAL_E_SOLVER where a solver's setup fails) with a
// message, leak nothing and crash nowhere; and steps must not allocate.
//
// The executable defines malloc, calloc, realloc and free (glibc resolves the library's calls
// to them) and forwards to glibc's __libc_* functions. An allocation counts as the library's
// when its caller's address lies in the object that holds dal_primitive_count (libdalembert.so, or
// this executable when the library is static); allocations inside SUNDIALS, KLU, LAPACK and
// libc are counted separately and never failed: SUNDIALS 6.4 does not survive every allocation
// failure (it crashes in N_VClone, ARKodeButcherTable_LoadERK, CVodeFree ...), which the
// README documents as the limit of what the library promises.
//
// Not built under the sanitizers (they own malloc); valgrind does not run it.
#define _GNU_SOURCE
#include <dlfcn.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

void *__libc_malloc(size_t size);
void *__libc_calloc(size_t n, size_t size);
void *__libc_realloc(void *p, size_t size);
void __libc_free(void *p);

// ---------------------------------------------------------------- the shim
// The allocator hooks cannot take a context: the shim's state is this file's one mutable
// object (test code only; the test is single-threaded, OPENBLAS_NUM_THREADS=1).
#define LIVE_SLOTS (1 << 16)

static struct shim {
  int armed;              // count (and fail) while armed
  long lib_count;         // library allocations while armed
  long other_count;       // allocations by anyone else while armed
  long fail_at;           // fail the library allocation with this index (-1: none)
  int failed;             // the injected failure happened
  void *lib_base;         // load address of the library's object
  void *live[LIVE_SLOTS]; // library allocations not yet freed (open addressing)
  long nlive;
} S = {.fail_at = -1};

static size_t slot_of(void *p) { return ((uintptr_t)p >> 4) * 2654435761u % LIVE_SLOTS; }

static void live_add(void *p) {
  size_t i = slot_of(p);
  while (S.live[i] && S.live[i] != (void *)1)
    i = (i + 1) % LIVE_SLOTS;
  S.live[i] = p;
  S.nlive++;
}

static void live_remove(void *p) {
  for (size_t i = slot_of(p), k = 0; S.live[i] && k < LIVE_SLOTS; i = (i + 1) % LIVE_SLOTS, ++k)
    if (S.live[i] == p) {
      S.live[i] = (void *)1; // a tombstone
      S.nlive--;
      return;
    }
}

// a library allocation from `caller`: counted; the chosen one fails
static int lib_alloc(void *caller, int *fail) {
  *fail = 0;
  if (!S.armed) return 0;
  Dl_info info;
  if (!dladdr(caller, &info) || info.dli_fbase != S.lib_base) {
    S.other_count++;
    if (getenv("ALLOC_DEBUG")) {
      S.armed = 0;
      fprintf(stderr, "alloc by %s (%s)\n", info.dli_fname ? info.dli_fname : "?",
              info.dli_sname ? info.dli_sname : "?");
      S.armed = 1;
    }
    return 0;
  }
  if (S.lib_count++ == S.fail_at) {
    S.failed = 1;
    *fail = 1;
  }
  return 1;
}

void *malloc(size_t size) {
  int fail, lib = lib_alloc(__builtin_return_address(0), &fail);
  if (fail) return NULL;
  void *p = __libc_malloc(size);
  if (lib && p) live_add(p);
  return p;
}

void *calloc(size_t n, size_t size) {
  int fail, lib = lib_alloc(__builtin_return_address(0), &fail);
  if (fail) return NULL;
  void *p = __libc_calloc(n, size);
  if (lib && p) live_add(p);
  return p;
}

void *realloc(void *old, size_t size) {
  int fail, lib = lib_alloc(__builtin_return_address(0), &fail);
  if (fail) return NULL;
  void *p = __libc_realloc(old, size);
  if (p && old && S.nlive) live_remove(old);
  if (lib && p) live_add(p);
  return p;
}

void free(void *p) {
  if (p && S.nlive) live_remove(p);
  __libc_free(p);
}

static void arm(long fail_at) {
  S.armed = 1;
  S.lib_count = S.other_count = 0;
  S.fail_at = fail_at;
  S.failed = 0;
  memset(S.live, 0, sizeof S.live);
  S.nlive = 0;
}

static void disarm(void) { S.armed = 0; }

// ---------------------------------------------------------------- scenarios
// A scenario builds a model, runs part of the API and frees everything; it returns the first
// failing status (DAL_OK if none) and checks that a failure left a message where an object
// could keep one.
static int msg_ok(int rc, const char *msg) { return rc == DAL_OK || (msg && msg[0]); }

typedef struct run {
  int rc;    // the first failing status
  int nomsg; // a failure without a message
} run;

static void note(run *r, int rc, const char *msg) {
  if (rc && !r->rc) r->rc = rc;
  if (!msg_ok(rc, msg)) r->nomsg = 1;
}

// a chain of N particles in Cartesian coordinates on rods (N = 1: the Cartesian pendulum),
// optionally in minimal coordinates instead (a pendulum chain by dal_map_hanging)
static int build(run *r, int N, int minimal, dal_builder **b, dal_system **sys) {
  static const double g2[2] = {0.0, -9.81};
  int rc = dal_builder_create(2, b);
  note(r, rc, "(no builder)");
  if (rc) return rc;
  for (int k = 0; k < N && !r->rc; ++k) {
    int c[2], p = k;
    note(r, dal_builder_add_coord(*b, NULL, &c[0]), dal_builder_errmsg(*b));
    if (!minimal) note(r, dal_builder_add_coord(*b, NULL, &c[1]), dal_builder_errmsg(*b));
    note(r, dal_builder_add_particle(*b, NULL, 1.0, &p), dal_builder_errmsg(*b));
    if (r->rc) break;
    if (minimal) {
      // unit links: a pendulum about the origin, then each hanging from the previous
      note(r, scn_place_swing(*b, NULL, p, k == 0 ? -1 : p - 1, 1.0, c[0]), dal_builder_errmsg(*b));
      continue;
    }
    dal_place_def pd = dal_default_place_def();
    pd.prim = &dal_map_cartesian2;
    pd.coords = c;
    pd.ncoords = 2;
    note(r, dal_builder_place_def(*b, p, &pd), dal_builder_errmsg(*b));
    // unit rods: to the origin, then each to the previous particle
    rc = k == 0 ? scn_add_rod(*b, NULL, p, -1, 1.0, NULL)
                : scn_add_rod(*b, NULL, p - 1, p, 1.0, NULL);
    note(r, rc, dal_builder_errmsg(*b));
  }
  if (!r->rc) note(r, dal_builder_set_gravity(*b, g2), dal_builder_errmsg(*b));
  if (!r->rc) note(r, dal_builder_compile(*b, sys), dal_builder_errmsg(*b));
  return r->rc;
}

// the chain slightly swung out, at rest
static void chain_state(const dal_system *sys, dal_state *st, int N, int minimal, run *r) {
  double q[200], qd[200];
  int n = minimal ? N : 2 * N;
  for (int i = 0; i < n; ++i)
    qd[i] = 0.0;
  for (int k = 0; k < N; ++k) {
    if (minimal) {
      q[k] = 0.3;
    } else {
      q[2 * k] = (k + 1) * sin(0.3);
      q[2 * k + 1] = -(k + 1) * cos(0.3);
    }
  }
  note(r, dal_state_set(sys, st, 0.0, q, qd), dal_state_errmsg(st));
}

typedef struct scen {
  const char *name;
  int N, minimal;
  dal_method method;
  dal_formulation form;
  dal_linsol linsol;
  int integrate, consistent;
  int record; // the run records a dal_trajectory (over 2 s: its storage grows)
} scen;

static int scenario(const scen *sc) {
  run r = {0, 0};
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  dal_trajectory *tr = NULL;
  if (build(&r, sc->N, sc->minimal, &b, &sys) == DAL_OK) {
    int rc = dal_state_create(sys, &st);
    note(&r, rc, "(no state)");
    if (!rc) chain_state(sys, st, sc->N, sc->minimal, &r);
    if (!r.rc) note(&r, dal_forward(sys, st), dal_state_errmsg(st));
    if (!r.rc && sc->consistent) {
      note(&r, dal_check_constraints(sys, st, NULL), dal_state_errmsg(st));
      if (!r.rc) note(&r, dal_make_consistent(sys, st, 0.0, NULL), dal_state_errmsg(st));
    }
    if (!r.rc && sc->integrate) {
      dal_solve_opts o = dal_default_solve_opts();
      o.method = sc->method;
      o.form = sc->form;
      o.linsol = sc->linsol;
      o.rtol = 1e-6;
      o.atol = 1e-8;
      o.project = sc->form == DAL_FORM_INDEX1;
      if (sc->record) {
        note(&r, dal_trajectory_create(sys, &tr), "(no trajectory)");
        if (!r.rc) note(&r, dal_state_set_trajectory(st, tr), dal_state_errmsg(st));
      }
      if (!r.rc) note(&r, dal_advance(sys, st, &o, sc->record ? 2.0 : 0.02), dal_state_errmsg(st));
    }
  }
  dal_trajectory_destroy(tr);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
  return r.nomsg ? 1 : r.rc;
}

static const scen scens[] = {
    {"forward, chain of 3 (dense KKT)", 3, 0, DAL_METHOD_AUTO, DAL_FORM_AUTO, DAL_LINSOL_AUTO, 0, 1,
     0},
    {"forward, chain of 70 (sparse KKT)", 70, 0, DAL_METHOD_AUTO, DAL_FORM_AUTO, DAL_LINSOL_AUTO, 0,
     1, 0},
    {"dopri5, double pendulum", 2, 1, DAL_METHOD_DOPRI5, DAL_FORM_AUTO, DAL_LINSOL_AUTO, 1, 0, 0},
    {"fehlberg78, double pendulum", 2, 1, DAL_METHOD_FEHLBERG78, DAL_FORM_AUTO, DAL_LINSOL_AUTO, 1,
     0, 0},
    {"bs, double pendulum", 2, 1, DAL_METHOD_BS, DAL_FORM_AUTO, DAL_LINSOL_AUTO, 1, 0, 0},
    {"rk4, double pendulum", 2, 1, DAL_METHOD_RK4, DAL_FORM_AUTO, DAL_LINSOL_AUTO, 1, 0, 0},
    {"adams, double pendulum", 2, 1, DAL_METHOD_ADAMS, DAL_FORM_AUTO, DAL_LINSOL_AUTO, 1, 0, 0},
    {"bdf, double pendulum", 2, 1, DAL_METHOD_BDF, DAL_FORM_AUTO, DAL_LINSOL_AUTO, 1, 0, 0},
    {"index-1 + projection, dopri5, chain of 2", 2, 0, DAL_METHOD_DOPRI5, DAL_FORM_INDEX1,
     DAL_LINSOL_AUTO, 1, 0, 0},
    {"ggl in IDA (dense), chain of 2", 2, 0, DAL_METHOD_BDF, DAL_FORM_GGL, DAL_LINSOL_DENSE, 1, 0,
     0},
    {"ggl in IDA (KLU), chain of 2", 2, 0, DAL_METHOD_BDF, DAL_FORM_GGL, DAL_LINSOL_KLU, 1, 0, 0},
    {"dopri5 recording a trajectory, double pendulum", 2, 1, DAL_METHOD_DOPRI5, DAL_FORM_AUTO,
     DAL_LINSOL_AUTO, 1, 0, 1},
};

// ---------------------------------------------------------------- allocations in steps
// allocations of a second advance with the same options (the integrator exists): a step
// allocates nothing of the library's own; the solvers' counts are reported
static void steps_allocate(const scen *sc) {
  run r = {0, 0};
  dal_builder *b = NULL;
  dal_system *sys = NULL;
  dal_state *st = NULL;
  CHECK_OK(build(&r, sc->N, sc->minimal, &b, &sys));
  CHECK_OK(dal_state_create(sys, &st));
  chain_state(sys, st, sc->N, sc->minimal, &r);
  dal_solve_opts o = dal_default_solve_opts();
  o.method = sc->method;
  o.form = sc->form;
  o.linsol = sc->linsol;
  o.project = sc->form == DAL_FORM_INDEX1;
  CHECK_OK(dal_advance(sys, st, &o, 0.1)); // creates the integrator, takes its first steps
  dal_stats s0, s1;
  CHECK_OK(dal_state_stats(st, &s0));
  arm(-1);
  int rc = dal_advance(sys, st, &o, 1.0);
  disarm();
  CHECK_OK(rc);
  CHECK_OK(dal_state_stats(st, &s1));
  CHECK_MSG(S.lib_count == 0, "%s: %ld library allocations in %ld steps", sc->name, S.lib_count,
            s1.steps - s0.steps);
  printf("  steps: %-42s %5ld steps, library allocations %ld, solver/libc allocations %ld\n",
         sc->name, s1.steps - s0.steps, S.lib_count, S.other_count);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
}

int main(void) {
  // the object holding a function of the library (not a data object: an executable may
  // hold copies of those); the function pointer's bytes, as ISO C converts no such pointer
  int (*fn)(void) = dal_primitive_count;
  void *addr;
  memcpy(&addr, &fn, sizeof addr);
  Dl_info info;
  if (!dladdr(addr, &info)) {
    fprintf(stderr, "test_alloc: dladdr failed\n");
    return 1;
  }
  S.lib_base = info.dli_fbase;
  int nsc = (int)(sizeof scens / sizeof scens[0]);
  long total = 0;
  for (int i = 0; i < nsc; ++i) {
    const scen *sc = &scens[i];
    // the allocations of a clean run
    arm(-1);
    int rc = scenario(sc);
    long count = S.lib_count, others = S.other_count, leak = S.nlive;
    disarm();
    CHECK_MSG(rc == DAL_OK && leak == 0, "%s: clean run %s, %ld leaked", sc->name,
              dal_status_name(rc), leak);
    // every one of them failed in turn
    int bad = 0;
    for (long k = 0; k < count; ++k) {
      arm(k);
      rc = scenario(sc);
      int hit = S.failed;
      leak = S.nlive;
      disarm();
      int ok = hit && (rc == DAL_E_NOMEM || rc == DAL_E_SOLVER) && leak == 0;
      if (!ok && bad++ < 5)
        fprintf(stderr, "%s: allocation %ld of %ld failed: %s (hit %d), %ld leaked\n", sc->name, k,
                count, rc == 1 ? "a failure without a message" : dal_status_name(rc), hit, leak);
      CHECK(ok || bad > 5);
    }
    CHECK_MSG(bad == 0, "%s: %d of %ld injected failures mishandled", sc->name, bad, count);
    printf("%-45s %4ld library allocations failed in turn (%ld others, not failed): %s\n", sc->name,
           count, others, bad ? "FAIL" : "ok");
    total += count;
  }
  printf("%ld injection points in all\n", total);
  for (int i = 2; i < nsc; ++i)
    if (!scens[i].record) steps_allocate(&scens[i]);
  return check_summary("test_alloc");
}
