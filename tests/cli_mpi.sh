#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# dalembert sweep --mpi on 2 ranks writes the same bytes as on 1 thread (with MPI); without MPI
# it is refused with exit status 15 (DAL_E_UNSUPPORTED) and a message.
# usage: cli_mpi.sh <dalembert> <scene> <output dir> [<mpiexec>]
set -uo pipefail
cli=$1 scene=$2 dir=$3 mpiexec=${4:-}
mkdir -p "$dir"
args=(sweep "$scene" --param omega=0:6:7 --no-progress)
"$cli" "${args[@]}" --threads 1 >"$dir/threads.csv" || exit 1
if [ -z "$mpiexec" ]; then
  "$cli" "${args[@]}" --mpi >/dev/null 2>"$dir/mpi.err"
  rc=$?
  grep -q "built without MPI" "$dir/mpi.err" && [ "$rc" -eq 15 ] || { echo "exit $rc"; exit 1; }
  echo "cli_mpi: --mpi refused without MPI (exit 15)"
  exit 0
fi
# root in containers and CI: Open MPI refuses to run as root unless told
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
"$mpiexec" -np 2 --oversubscribe "$cli" "${args[@]}" --mpi >"$dir/mpi.csv" || exit 1
cmp "$dir/threads.csv" "$dir/mpi.csv" || exit 1
echo "cli_mpi: 2 ranks and 1 thread write the same $(wc -l <"$dir/mpi.csv") lines"
