// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Consumer check of the MPI library: built against an install with find_package(dalembert
// COMPONENTS mpi) or pkg-config's dalembert_mpi, it must compile (dalembert/mpi.h with <mpi.h>),
// link and load. MPI itself is not started here (tests/test_ensemble_mpi.c runs the sweeps).
#include <dalembert/dalembert.h>
#include <dalembert/mpi.h>
#include <stdio.h>

typedef int run_mpi_fn(const dal_system *, const dal_sweep *, const dal_sweep_opts *,
                       dal_sweep_out *, MPI_Comm, char *, size_t);

int main(void) {
  run_mpi_fn *volatile run = dal_sweep_run_mpi;
  printf("consumer_mpi: dalembert %s, dal_sweep_run_mpi %s\n", dal_version(),
         run ? "resolved" : "missing");
  return run ? 0 : 1;
}
