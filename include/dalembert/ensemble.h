// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Ensembles and parameter sweeps: one compiled system, many trajectories, on a thread pool.
///
/// A sweep runs `ntraj` independent trajectories of one shared, immutable system. Trajectory i
/// starts from its parameter values (row i of a table, see params.h for what can be set) and
/// its initial state, is optionally advanced to t1, and is handed to a user reducer that
/// writes whatever it wants to keep (a final state, a Lyapunov exponent, an equilibrium, a
/// section) into its own result slot of `nresult` doubles. The library records a status and a
/// message per trajectory; a failing trajectory (invalid parameter, inconsistent constraints,
/// step failure, reducer failure) never stops the others.
///
/// Threads: POSIX threads, not OpenMP. The library already links pthreads (its thread-safety
/// tests use them), a pthread pool needs no compiler flag or runtime in the user's program
/// (OpenMP would add -fopenmp and a runtime to every consumer and nest badly with a user's own
/// OpenMP regions), and the pool's schedule is explicit. Each worker owns one dal_state
/// (created once, reused for its trajectories); the calling thread is worker 0.
///
/// Determinism: the result slot of trajectory i is out->results + i * nresult, whatever
/// thread computes it, and every trajectory starts from a state rewound to the same condition
/// (parameters reset to the system's, integrator history and statistics dropped), so the
/// results and dal_sweep_write_csv's output are identical bit for bit for any thread count,
/// schedule or (with dalembert/mpi.h) number of MPI ranks. Any aggregate the caller forms
/// from the slots afterwards has a fixed order too. tests/test_ensemble.c checks it.
///
/// Callbacks run in worker threads concurrently: the reducer and the system's own callbacks
/// must not write shared data without synchronization (per-worker data: opts.worker_create).
#ifndef DAL_ENSEMBLE_H
#define DAL_ENSEMBLE_H

#include <stdio.h>

#include "dalembert/base.h"
#include "dalembert/params.h"
#include "dalembert/solve.h"
#include "dalembert/state.h"
#include "dalembert/system.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Bytes of a per-trajectory message buffer handed to the reducer (dal_traj.msg).
#define DAL_SWEEP_MSG_LEN 512

/// What the reducer of trajectory `index` gets besides the system and its state.
typedef struct dal_traj {
  long index;           ///< trajectory index, 0 .. ntraj-1
  const double *values; ///< its parameter values (nparam; NULL if nparam = 0), borrowed
  double *result;       ///< its result slot (nresult doubles), NaN on entry; write here
  int nresult;          ///< size of the slot
  void *worker;         ///< this worker's data from opts.worker_create (NULL if none)
  int worker_id;        ///< 0 .. nthreads-1 (do not let results depend on it)
  char *msg;            ///< DAL_SWEEP_MSG_LEN bytes, "" on entry: a failing reducer may
                        ///< write its message here (else the state's message is kept)
} dal_traj;

/// Per-trajectory reducer: the state is set up (parameters, initial state) and, if the
/// sweep has solve options, advanced to t1 successfully. Drive it further if needed
/// (dal_advance, dal_evolve), then write into tr->result. Return 0 on success or a negative
/// status (e.g. that of a failing dal_advance; a positive value is recorded as
/// DAL_E_CALLBACK). Called concurrently from worker threads.
typedef int dal_reduce_fn(const dal_system *sys, dal_state *st, const dal_traj *tr, void *ctx);

/// Progress report, serialized (one call at a time, from any worker thread): `done` of
/// `total` trajectories finished, `failed` of them with a non-zero status. Return 0 to go on,
/// non-zero to cancel: trajectories not yet started are then recorded as DAL_E_CALLBACK
/// ("not run: the sweep was cancelled") and dal_sweep_run returns DAL_E_CALLBACK.
typedef int dal_progress_fn(long done, long total, long failed, void *ctx);

/// Per-worker data (e.g. a second state for a two-trajectory method): create writes *data;
/// return 0 or a negative status (the sweep then fails before running). Called in the
/// calling thread, before the workers start and after they stop.
typedef int dal_worker_create_fn(const dal_system *sys, int worker_id, void *ctx, void **data);
/// Free per-worker data (NULL-safe is up to the caller's function).
typedef void dal_worker_destroy_fn(void *data, void *ctx);

/// How trajectories are handed to workers. Either way trajectory i writes slot i.
typedef enum dal_schedule {
  DAL_SCHEDULE_DYNAMIC = 0, ///< workers take the next `chunk` trajectories from a shared
                            ///< counter: balances trajectories of uneven cost (default)
  DAL_SCHEDULE_STATIC,      ///< worker w runs a contiguous block of ntraj / nthreads
} dal_schedule;

/// The trajectories of a sweep (borrowed arrays; must stay valid during dal_sweep_run).
typedef struct dal_sweep {
  long ntraj;                  ///< number of trajectories (>= 1)
  int nparam;                  ///< parameters set per trajectory (>= 0)
  const dal_param_ref *params; ///< the parameters (nparam), see params.h / dal_param_find
  const double *values;        ///< values (ntraj x nparam, row-major): row i for trajectory i
  double t0;                   ///< initial time
  const double *q0;            ///< initial coordinates: n values, or ntraj x n (see stride)
  const double *qdot0;         ///< initial velocities: n values, or ntraj x n (see stride)
  int state_stride;            ///< 0: the same q0, qdot0 for all; n: row i for trajectory i
  const dal_solve_opts *solve; ///< non-NULL: advance each trajectory to t1 before reducing;
                               ///< NULL: the reducer drives the state itself
  double t1;                   ///< target time with `solve`
  int nresult;                 ///< doubles per result slot (>= 0)
  dal_reduce_fn *reduce;       ///< the reducer (NULL: keep nothing beyond the status)
  void *ctx;                   ///< passed to reduce (borrowed)
} dal_sweep;

/// Sweep options. Always start from dal_default_sweep_opts().
typedef struct dal_sweep_opts {
  int cookie;                            ///< set by dal_default_sweep_opts; do not touch
  int nthreads;                          ///< worker threads incl. the caller (default 1;
                                         ///< 0: the number of online processors)
  dal_schedule schedule;                 ///< default DAL_SCHEDULE_DYNAMIC
  int chunk;                             ///< trajectories per grab (dynamic), default 1
  dal_progress_fn *progress;             ///< nullable
  void *progress_ctx;                    ///< passed to progress
  long progress_every;                   ///< call progress every this many trajectories and
                                         ///< at the end (default 1)
  dal_worker_create_fn *worker_create;   ///< nullable: per-worker data
  dal_worker_destroy_fn *worker_destroy; ///< nullable
  void *worker_ctx;                      ///< passed to worker_create / worker_destroy
  int part;                              ///< run only the trajectories of part `part` of
                                         ///< `nparts` (default 0 of 1: all); see
                                         ///< dal_sweep_part_of. For job arrays and MPI ranks
  int nparts;                            ///< number of parts (default 1)
  int part_block;                        ///< block size of the partition (default 1)
} dal_sweep_opts;

/// Where results go (caller-owned arrays of ntraj entries each).
typedef struct dal_sweep_out {
  double *results; ///< ntraj x nresult (may be NULL when nresult = 0)
  int *status;     ///< ntraj statuses (DAL_OK or the trajectory's failure)
  char *msgs;      ///< nullable: ntraj x msg_len bytes, each the trajectory's message ("" ok)
  int msg_len;     ///< bytes per message (> 0 when msgs is set; messages are truncated)
  long nfailed;    ///< set by dal_sweep_run: trajectories of this part with status != 0
  long nrun;       ///< set by dal_sweep_run: trajectories of this part run
} dal_sweep_out;

/// Fill *o with the defaults (1 thread, dynamic schedule, chunk 1, no progress, all parts).
DAL_API dal_sweep_opts dal_default_sweep_opts(void);

/// The part (0 .. nparts-1) trajectory i belongs to: (i / block) mod nparts, i.e. blocks of
/// `block` trajectories dealt round-robin (block 1 interleaves neighbours of a grid, which
/// spreads a cost that varies smoothly across the grid evenly over the parts).
DAL_API int dal_sweep_part_of(long i, int nparts, int block);

/// Run the sweep (or the part opts->part of it) over opts->nthreads threads; out->results,
/// status and msgs of the part's trajectories are written, other slots are left untouched.
/// Returns DAL_OK when every trajectory ran (each may have failed: see out->status, nfailed);
/// DAL_E_ARG for an invalid sweep or options (message in errmsg, `errlen` bytes, nullable);
/// DAL_E_NONFINITE for a non-finite t0, or t1 with solve options (a non-finite entry of q0,
/// qdot0 or a parameter value is a per-trajectory failure instead); DAL_E_NOMEM;
/// DAL_E_CALLBACK when the progress callback cancelled; a worker_create status. Nothing runs
/// and no slot is written when the sweep is rejected (DAL_E_ARG, DAL_E_NONFINITE).
DAL_API int dal_sweep_run(const dal_system *sys, const dal_sweep *sw, const dal_sweep_opts *o,
                          dal_sweep_out *out, char *errmsg, size_t errlen);

/// Fill a grid table for dal_sweep.values: naxes axes, axis a with count[a] >= 1 points
/// lo[a] + (hi[a] - lo[a]) k / (count[a] - 1) (lo[a] when count[a] = 1); the last axis runs
/// fastest. `values` holds prod(count) x naxes doubles (caller-owned). Returns the number of
/// rows, or DAL_E_ARG.
DAL_API long dal_sweep_grid(int naxes, const int *count, const double *lo, const double *hi,
                            double *values);

/// Write the sweep as CSV, one row per trajectory in index order: index, the parameter
/// values (columns named by dal_param_name), with per-trajectory initial states
/// (state_stride = n) the trajectory's q0 and qdot0 (columns "q0:<coordinate>", then
/// "qdot0:<coordinate>"), status (dal_status_name), the results (columns
/// result_names[0..nresult-1], or r0, r1, ... when result_names is NULL) and the message
/// (quoted). Numbers are printed with %.17g, so equal results give equal bytes. Returns
/// DAL_OK or DAL_E_IO / DAL_E_ARG.
DAL_API int dal_sweep_write_csv(FILE *fp, const dal_system *sys, const dal_sweep *sw,
                                const dal_sweep_out *out, const char *const *result_names);

#ifdef __cplusplus
}
#endif
#endif
