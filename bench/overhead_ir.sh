#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Library overhead against the hand-written chain in instructions executed (callgrind), which
# the machine's load does not disturb: one run of each side per (N, method), counted only
# inside dal_bench's measured region. Writes overhead_ir.csv.
# Usage: bench/overhead_ir.sh DAL_BENCH RESULTS_DIR [--quick | --full]
set -euo pipefail
exe=$1
dir=$2
mode=${3:---quick}
if ! command -v valgrind >/dev/null; then
  echo "overhead_ir: valgrind not installed (DAL_WITH_VALGRIND=1 scripts/deps.sh); skipped" >&2
  exit 0
fi
methods="adams"
t1=0.25
if [[ $mode == --full ]]; then
  methods="adams dopri5 fehlberg78 bdf"
  t1=1.0
fi
rtol=1e-8
out=$dir/overhead_ir.csv
echo "N,method,rtol,t1,ir_lib,ir_hand,ratio,rhs_lib,rhs_hand" >"$out"
# instructions collected in the region and the run's rhs count: "IR RHS"
count() {
  valgrind --tool=callgrind --toggle-collect=ir_region --callgrind-out-file=/dev/null \
    "$exe" ir "$@" 2>&1 | awk '/Collected :/ {gsub(",", "", $NF); ir = $NF}
      /^rhs_evals=/ {split($1, a, "="); rhs = a[2]} END {print ir, rhs}'
}
for N in 1 2 4 8 16 32; do
  for m in $methods; do
    read -r il rl < <(count lib "$N" "$m" "$rtol" "$t1")
    read -r ih rh < <(count hand "$N" "$m" "$rtol" "$t1")
    awk -v N="$N" -v m="$m" -v r="$rtol" -v t="$t1" -v il="$il" -v ih="$ih" -v rl="$rl" \
      -v rh="$rh" 'BEGIN {printf "%d,%s,%s,%s,%d,%d,%.4f,%d,%d\n", N, m, r, t, il, ih, il / ih, rl, rh}' \
      >>"$out"
    echo "overhead_ir N=$N $m: $(tail -1 "$out")" >&2
  done
done
