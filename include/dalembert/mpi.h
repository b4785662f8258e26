// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
/// @file
/// @brief Sweeps over MPI ranks (library dalembert_mpi): each rank runs its part, rank 0 gathers.
///
/// Every rank compiles the same system and calls dal_sweep_run_mpi collectively with the same
/// sweep and options. Rank r runs the trajectories of part r of `size` (dal_sweep_part_of with
/// opts.part_block: blocks dealt round-robin), on opts.nthreads threads of its own; rank 0
/// then receives every rank's slots and holds the whole sweep in index order, so
/// dal_sweep_write_csv on rank 0 writes the same bytes as a single-process run. Build with
/// -DDAL_WITH_MPI=AUTO|ON (CMake target dalembert::dalembert_mpi); the core library and
/// dalembert.h do not depend on MPI. See docs/ensembles.md for clusters.
#ifndef DAL_MPI_H
#define DAL_MPI_H

#include <mpi.h>

#include "dalembert/ensemble.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Run the sweep over the ranks of `comm` (collective). `out` holds full-size arrays
/// (ntraj entries; msgs NULL on all ranks or set with the same msg_len on all) on every rank:
/// a rank writes its own slots, and on return rank 0 holds all of them, with out->nrun and
/// out->nfailed summed over the ranks (other ranks keep their own counts). opts->part and
/// opts->nparts must be left at their defaults (the ranks are the parts). Progress callbacks
/// report each rank's own part. Returns on every rank the most negative status of any rank
/// (DAL_OK when all ran), DAL_E_ARG or DAL_E_NONFINITE as dal_sweep_run (a rejected sweep:
/// nothing is gathered), or DAL_E_SOLVER when an MPI call failed; `errmsg` (nullable, errlen
/// bytes) receives this rank's message.
DAL_API int dal_sweep_run_mpi(const dal_system *sys, const dal_sweep *sw,
                              const dal_sweep_opts *opts, dal_sweep_out *out, MPI_Comm comm,
                              char *errmsg, size_t errlen);

#ifdef __cplusplus
}
#endif
#endif
