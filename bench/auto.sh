#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The work-precision table behind DAL_METHOD_AUTO and the default atol, in instructions
# (callgrind; the machine's load does not move them). Writes to RESULTS_DIR:
#   auto_refs.csv   reference positions of every scene at its final time (native run)
#   auto_sweep.csv  one row per (scene, method, atol rule, rtol): error, rhs, steps, ir
#   auto_table.md   for each scene, N and error band: the cheapest configuration and
#                   AUTO's cost over it (dal_bench_auto table)
# Usage: bench/auto.sh DAL_BENCH_AUTO RESULTS_DIR [--quick]
set -euo pipefail
exe=$1
dir=$2
mode=${3:-}
if ! command -v valgrind >/dev/null; then
  echo "auto.sh: valgrind not installed (DAL_WITH_VALGRIND=1 scripts/deps.sh)" >&2
  exit 1
fi
mkdir -p "$dir"
"$exe" refs "$dir/auto_refs.csv" $mode
# one callgrind dump per run, counted in auto_region only (gcc may clone the static function:
# auto_region.isra.0)
"$(dirname "$0")/cg_rows.sh" 'auto_region*' "$dir/auto_sweep.csv" "$exe" sweep \
  "$dir/auto_refs.csv" $mode
"$exe" table "$dir/auto_sweep.csv" >"$dir/auto_table.md"
echo "auto.sh: $(($(wc -l <"$dir/auto_sweep.csv") - 1)) runs; table in $dir/auto_table.md" >&2
