#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Regenerate every benchmark figure: Release build, dal_bench -> bench/results/*.csv, gnuplot
# charts (PNG + SVG), and the tables of docs/performance.md (bench/report.sh).
# Usage: bench/bench.sh [--quick | --full]   (quick: a few minutes; full: much longer)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$root/bench/lib.sh"
mode=$(bench_mode "bench/bench.sh [--quick | --full]" "${1:-}")
"$root/scripts/deps.sh"
bdir=${DAL_BENCH_BUILD_DIR:-$root/build-release}
out=$root/bench/results
start=$(date +%s)
bench_build "$root" "$bdir" dal_bench "$(nproc)"
mkdir -p "$out"
# where and when: read by bench/report.sh
{
  echo "date=$(date -u +%Y-%m-%d)"
  echo "machine=$(uname -m)"
  echo "nproc=$(nproc)"
  echo "cpu=$(awk -F': ' '/^model name/ {print $2; exit}' /proc/cpuinfo)"
  # the version is written once, in include/dalembert/base.h
  echo "version=$(awk '/^#define DAL_VERSION_(MAJOR|MINOR|PATCH) / {v = v (v == "" ? "" : ".") $3}
                       END {print v}' "$root/include/dalembert/base.h")"
  echo "commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "mode=$mode"
} >"$out/machine.txt"
"$bdir/bench/dal_bench" "$mode" --out "$out"
"$root/bench/overhead_ir.sh" "$bdir/bench/dal_bench" "$out" "$mode"
# the charts bench/plots.gp draws; the symplectic ones (sym_*) belong to symplectic.sh,
# the cliff chart to bench/cliff.sh
find "$out" -maxdepth 1 \( -name '*.png' -o -name '*.svg' \) ! -name 'sym_*' ! -name 'cliff.*' -delete
# (gnuplot warns about curves without points, e.g. a formulation that failed at every rtol)
gnuplot -e "dir='$out'" "$root/bench/plots.gp" 2>&1 | { grep -v "Skipping data file" || true; } >&2
"$root/bench/report.sh" "$out" "$root/docs/performance.md"
echo "bench: results, charts and summary in $out ($(($(date +%s) - start)) s)"
