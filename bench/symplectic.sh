#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Long runs of the symplectic methods against the adaptive ones: Release build,
# dal_bench_symplectic -> bench/results/sym_*.csv and sym_summary.md, gnuplot charts.
# Usage: bench/symplectic.sh [--quick | --full] [OUTDIR]
#   quick (default): 1e4 pendulum periods, a few minutes; full: 1e5 periods, ~15-20 minutes.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$root/bench/lib.sh"
mode=$(bench_mode "bench/symplectic.sh [--quick | --full] [OUTDIR]" "${1:-}")
out=${2:-$root/bench/results}
bdir=${DAL_BENCH_BUILD_DIR:-$root/build-release}
"$root/scripts/deps.sh"
bench_build "$root" "$bdir" dal_bench_symplectic
mkdir -p "$out"
"$bdir/bench/dal_bench_symplectic" "$mode" --out "$out"
rm -f "$out"/sym_*.png "$out"/sym_*.svg
gnuplot -e "dir='$out'" "$root/bench/symplectic.gp" 2>&1 | { grep -v "Skipping data file" || true; } >&2
echo "bench_symplectic: $out/sym_summary.md and charts sym_*.png"
