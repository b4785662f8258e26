#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Ensemble benchmark: 1 vs 2 threads, 1 vs 2 MPI ranks, sweep vs plain loop, paired -> CSV.
# usage: bench/ensemble.sh <build dir> [pairs] [--no-inprocess]
#   writes bench/results/ensemble.csv. Default 7 pairs.
#
# 1. Whole-process pairs: command A and command B run in turn (A B A B ...), each timed from
#    outside by /usr/bin/time (wall, user + system seconds), and the ratio A/B taken pair by
#    pair, so that a change of machine load between pairs cancels; min, median and max of the
#    ratios are reported. On a machine shared with other work, quote the median and read the
#    min-max spread as the noise. Rows (ratio = A/B):
#      threads   A = sweep on 1 thread, B = 2 threads (ratio = speed-up)
#      mpi       A = mpirun -np 1, B = mpirun -np 2, 1 thread per rank (ratio = speed-up;
#                mpirun's start-up is inside both)
#                and, from one 2-thread sweep, each worker's thread CPU time: how evenly
#                the pool splits the work (load-independent; the wall-clock speed-up is
#                what the scheduler grants on top of it)
#      overhead  A = dal_sweep_run on 1 thread, B = a plain loop of dal_state_set_param,
#                dal_state_set, dal_advance (ratio - 1 = the machinery's share), for 256
#                trajectories to t = 20 and 256 short ones to t = 0.01
# 2. In-process rows of dal_bench_ensemble (interleaved repetitions inside one process:
#    threads, overhead, uneven costs with static vs dynamic schedules).
# 3. Instruction counts under valgrind --tool=callgrind (load-independent): one pass of the
#    256 short trajectories as a plain loop and as a 1-thread sweep.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bdir=${1:-$root/build} pairs=${2:-7} inprocess=1
[[ ${3:-} == --no-inprocess ]] && inprocess=0
out=$root/bench/results/ensemble.csv
bench=$bdir/bench/dal_bench_ensemble mpib=$bdir/bench/dal_bench_ensemble_mpi
mkdir -p "$(dirname "$out")"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader
export OMPI_MCA_btl_vader_single_copy_mechanism=none

# one timed run: appends "wall cpu" to file $1; the command is the rest
timed() {
  local f=$1
  shift
  /usr/bin/time -f '%e %U %S' -o "$tmp/t" "$@" >/dev/null 2>&1
  awk '{ print $1, $2 + $3 }' "$tmp/t" >>"$f"
}

# pair NAME 'A' 'B': one warm-up of each, then $pairs pairs A B; prints the CSV row
pair() {
  local name=$1 a=$2 b=$3
  : >"$tmp/a"
  : >"$tmp/b"
  timed /dev/null $a
  timed /dev/null $b
  for ((r = 0; r < pairs; ++r)); do
    timed "$tmp/a" $a
    timed "$tmp/b" $b
  done
  paste -d' ' "$tmp/a" "$tmp/b" | awk -v name="$name" '
    function med(x, n,   i, j, t, y) {
      for (i = 1; i <= n; ++i) y[i] = x[i]
      for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j) if (y[j] < y[i]) { t = y[i]; y[i] = y[j]; y[j] = t }
      lo = y[1]; hi = y[n]
      return n % 2 ? y[(n + 1) / 2] : 0.5 * (y[n / 2] + y[n / 2 + 1])
    }
    { ++n; wa[n] = $1; ca[n] = $2; wb[n] = $3; cb[n] = $4
      rw[n] = $3 > 0 ? $1 / $3 : 0; rc[n] = $4 > 0 ? $2 / $4 : 0 }
    END {
      ma = med(wa, n); mb = med(wb, n); mca = med(ca, n); mcb = med(cb, n)
      m = med(rw, n); l = lo; h = hi; mc = med(rc, n); lc = lo; hc = hi
      printf "pair,%s,%d,%.3f,%.3f,%.3f,%.3f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", name, n, ma, mb, mca, mcb, l, m, h, lc, mc, hc
    }'
}

{
  echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(nproc) cores; load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "kind,name,pairs,A_wall_median_s,B_wall_median_s,A_cpu_median_s,B_cpu_median_s,wall_ratio_min,wall_ratio_median,wall_ratio_max,cpu_ratio_min,cpu_ratio_median,cpu_ratio_max"
  pair "threads: sweep 256 traj t=20 1 thread / 2 threads" "$bench sweep 20 1" "$bench sweep 20 2"
  # how evenly 2 workers split the CPU work (load-independent): the speed-up free cores allow
  echo "# $("$bench" split 20 2)"
  echo "# load average: $(cut -d' ' -f1-3 /proc/loadavg)"
  if [[ -x $mpib ]] && command -v mpirun >/dev/null; then
    pair "mpi: sweep 256 traj t=20 1 rank / 2 ranks" \
      "mpirun -np 1 --oversubscribe $mpib 1" "mpirun -np 2 --oversubscribe $mpib 1"
    echo "# load average: $(cut -d' ' -f1-3 /proc/loadavg)"
  fi
  pair "overhead: sweep 1 thread / plain loop 256 traj t=20" "$bench sweep 20 1" "$bench loop 20"
  pair "overhead: sweep 1 thread / plain loop 256 traj t=0.01" "$bench sweep 0.01 1" \
    "$bench loop 0.01"
  echo "# load average: $(cut -d' ' -f1-3 /proc/loadavg)"
  if ((inprocess)); then
    "$bench" "$pairs"
  fi
  # machinery overhead in instructions (load-independent)
  if command -v valgrind >/dev/null; then
    for m in loop sweep; do
      ir=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null \
             "$bench" "$m" 0.01 2>&1 | awk '/refs:/ { gsub(",", "", $NF); print $NF }')
      echo "callgrind,$m 256 traj t=0.01 instructions,1,$ir"
    done
  fi
  echo "# load average at end: $(cut -d' ' -f1-3 /proc/loadavg)"
} | tee "$out"
