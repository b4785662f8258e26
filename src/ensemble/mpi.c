// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Sweeps over MPI ranks: rank r runs part r, rank 0 gathers every slot in index order.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dalembert/mpi.h"

// number of trajectories of part r
static long part_count(const dal_sweep *sw, int r, int nparts, int block) {
  long c = 0;
  for (long i = 0; i < sw->ntraj; ++i)
    c += dal_sweep_part_of(i, nparts, block) == r;
  return c;
}

// pack (unpack = 0) or unpack (1) the slots of part r between out and the contiguous buffers
static void move_slots(const dal_sweep *sw, dal_sweep_out *out, int r, int nparts, int block,
                       double *res, int *status, char *msgs, int unpack) {
  size_t nr = (size_t)sw->nresult, ml = (size_t)out->msg_len, j = 0;
  for (long i = 0; i < sw->ntraj; ++i) {
    if (dal_sweep_part_of(i, nparts, block) != r) continue;
    double *ro = out->results ? out->results + (size_t)i * nr : NULL;
    char *mo = out->msgs ? out->msgs + (size_t)i * ml : NULL;
    if (unpack) {
      if (nr) memcpy(ro, res + j * nr, nr * sizeof(double));
      out->status[i] = status[j];
      if (mo) memcpy(mo, msgs + j * ml, ml);
    } else {
      if (nr) memcpy(res + j * nr, ro, nr * sizeof(double));
      status[j] = out->status[i];
      if (mo) memcpy(msgs + j * ml, mo, ml);
    }
    ++j;
  }
}

// gather every part's slots on rank 0 (each rank's count follows from the partition, blocks of
// `block` trajectories); *all_ok: every rank had the memory; returns the MPI error bits
static int gather_slots(const dal_sweep *sw, dal_sweep_out *out, MPI_Comm comm, int rank, int size,
                        int block, int *all_ok) {
  int ml = out->msgs ? out->msg_len : 0, nr = sw->nresult;
  long mine = part_count(sw, rank, size, block);
  long cap = rank == 0 ? 0 : mine;
  for (int r = 1; r < size && rank == 0; ++r) {
    long c = part_count(sw, r, size, block);
    if (c > cap) cap = c;
  }
  double *res = malloc(((size_t)cap * (size_t)nr + 1) * sizeof(double));
  int *status = malloc(((size_t)cap + 1) * sizeof(int));
  char *msgs = malloc((size_t)cap * (size_t)ml + 1);
  int ok = res && status && msgs;
  *all_ok = 0;
  MPI_Allreduce(&ok, all_ok, 1, MPI_INT, MPI_MIN, comm);
  int merr = MPI_SUCCESS;
  if (*all_ok && rank != 0) {
    move_slots(sw, out, rank, size, block, res, status, msgs, 0);
    merr |= MPI_Send(res, (int)(mine * nr), MPI_DOUBLE, 0, 1, comm);
    merr |= MPI_Send(status, (int)mine, MPI_INT, 0, 2, comm);
    merr |= MPI_Send(msgs, (int)(mine * ml), MPI_CHAR, 0, 3, comm);
  } else if (*all_ok) {
    // receive rank by rank in rank order: the unpacked layout does not depend on timing
    for (int r = 1; r < size; ++r) {
      long c = part_count(sw, r, size, block);
      merr |= MPI_Recv(res, (int)(c * nr), MPI_DOUBLE, r, 1, comm, MPI_STATUS_IGNORE);
      merr |= MPI_Recv(status, (int)c, MPI_INT, r, 2, comm, MPI_STATUS_IGNORE);
      merr |= MPI_Recv(msgs, (int)(c * ml), MPI_CHAR, r, 3, comm, MPI_STATUS_IGNORE);
      move_slots(sw, out, r, size, block, res, status, msgs, 1);
    }
  }
  free(res);
  free(status);
  free(msgs);
  return merr;
}

int dal_sweep_run_mpi(const dal_system *sys, const dal_sweep *sw, const dal_sweep_opts *opts,
                      dal_sweep_out *out, MPI_Comm comm, char *errmsg, size_t errlen) {
  int rank = 0, size = 1;
  if (errmsg && errlen) errmsg[0] = 0;
  if (MPI_Comm_rank(comm, &rank) != MPI_SUCCESS || MPI_Comm_size(comm, &size) != MPI_SUCCESS) {
    if (errmsg && errlen) snprintf(errmsg, errlen, "sweep over MPI: invalid communicator");
    return DAL_E_SOLVER;
  }
  int rc = DAL_OK;
  dal_sweep_opts o;
  if (!opts || !sw || !out) {
    rc = DAL_E_ARG;
    if (errmsg && errlen) snprintf(errmsg, errlen, "sweep over MPI: sweep, options or out is NULL");
  } else if (opts->nparts != 1 || opts->part != 0) {
    rc = DAL_E_ARG;
    if (errmsg && errlen)
      snprintf(errmsg, errlen,
               "sweep over MPI: leave opts.part and opts.nparts at their defaults "
               "(the %d ranks are the parts)",
               size);
  } else {
    o = *opts;
    o.part = rank;
    o.nparts = size;
    rc = dal_sweep_run(sys, sw, &o, out, errmsg, errlen);
  }
  // a sweep every rank rejected (bad arguments, non-finite times) ran nowhere and wrote no
  // slot: stop before gathering
  int worst = rc, rejected = rc == DAL_E_ARG || rc == DAL_E_NONFINITE, any_rejected = rejected;
  if (MPI_Allreduce(&rc, &worst, 1, MPI_INT, MPI_MIN, comm) != MPI_SUCCESS ||
      MPI_Allreduce(&rejected, &any_rejected, 1, MPI_INT, MPI_MAX, comm) != MPI_SUCCESS)
    return DAL_E_SOLVER;
  if (any_rejected) return worst;

  // gather every part's slots on rank 0 (each rank's count follows from the partition)
  int all_ok = 0, merr = gather_slots(sw, out, comm, rank, size, o.part_block, &all_ok);
  long counts[2] = {out->nrun, out->nfailed}, sums[2] = {0, 0};
  merr |= MPI_Reduce(counts, sums, 2, MPI_LONG, MPI_SUM, 0, comm);
  if (rank == 0 && merr == MPI_SUCCESS) {
    out->nrun = sums[0];
    out->nfailed = sums[1];
  }
  if (!all_ok) {
    if (errmsg && errlen) snprintf(errmsg, errlen, "sweep over MPI: out of memory gathering");
    return DAL_E_NOMEM;
  }
  if (merr != MPI_SUCCESS) {
    if (errmsg && errlen) snprintf(errmsg, errlen, "sweep over MPI: a send or receive failed");
    return DAL_E_SOLVER;
  }
  return worst;
}
