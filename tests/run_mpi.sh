#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Run test_ensemble_mpi on 1 and 2 ranks and require byte-identical CSV files.
# usage: run_mpi.sh <mpiexec> <test binary> <output dir>
set -euo pipefail
mpiexec=$1 bin=$2 dir=$3
mkdir -p "$dir"
# root in containers and CI: Open MPI refuses to run as root unless told
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# shared-memory transport only (no network probing on a single machine)
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
for np in 1 2; do
  "$mpiexec" -np "$np" --oversubscribe "$bin" "$dir/sweep_np$np.csv"
done
cmp "$dir/sweep_np1.csv" "$dir/sweep_np2.csv"
echo "run_mpi: np 1 and np 2 CSV identical ($(wc -l <"$dir/sweep_np1.csv") lines)"
