#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Ensemble benchmark rows: threads, overhead, schedules, and 1 vs 2 MPI ranks -> CSV.
# usage: bench/ensemble.sh <build dir> [reps]   (writes bench/results/ensemble.csv)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bdir=${1:-$root/build} reps=${2:-7}
out=$root/bench/results/ensemble.csv
mkdir -p "$(dirname "$out")"
{
  echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(nproc) cores, load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
  "$bdir/bench/dal_bench_ensemble" "$reps"
  if [[ -x $bdir/bench/dal_bench_ensemble_mpi ]]; then
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader
    export OMPI_MCA_btl_vader_single_copy_mechanism=none
    # interleave the rank counts: a load change hits both alike
    for ((r = 0; r < reps; ++r)); do
      mpirun -np 1 --oversubscribe "$bdir/bench/dal_bench_ensemble_mpi" 1
      mpirun -np 2 --oversubscribe "$bdir/bench/dal_bench_ensemble_mpi" 1
    done | awk -F, -v reps="$reps" '
      { n[$2]++; t[$2, n[$2]] = $4 }
      END {
        for (c in n) {
          k = n[c]; for (i = 1; i <= k; ++i) v[i] = t[c, i];
          for (i = 1; i <= k; ++i) for (j = i + 1; j <= k; ++j) if (v[j] < v[i]) { x = v[i]; v[i] = v[j]; v[j] = x }
          mn[c] = v[1]; md[c] = (k % 2) ? v[(k + 1) / 2] : 0.5 * (v[k / 2] + v[k / 2 + 1])
        }
        b = "256 traj t=20 1 rank 1 thread"; o = "256 traj t=20 2 ranks 1 thread"
        printf "mpi,%s,%d,%.6f,%.6f,1.000,1.000\n", b, n[b], mn[b], md[b]
        printf "mpi,%s,%d,%.6f,%.6f,%.3f,%.3f\n", o, n[o], mn[o], md[o], mn[b] / mn[o], md[b] / md[o]
      }'
  fi
  # machinery overhead in instructions (load-independent): one pass of 256 short
  # trajectories as a plain loop and as a 1-thread sweep under callgrind
  if command -v valgrind >/dev/null; then
    for m in loop sweep; do
      ir=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null \
             "$bdir/bench/dal_bench_ensemble" "$m" 0.01 2>&1 | awk '/refs:/ { gsub(",", "", $NF); print $NF }')
      echo "callgrind,$m 256 traj t=0.01 instructions,1,$ir,$ir,,"
    done
  fi
  echo "# load average at end: $(cut -d' ' -f1-3 /proc/loadavg)"
} | tee "$out"
