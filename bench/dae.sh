#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The sparse DAE's benchmarks (issue 13, items 3 and 4), in one run:
#   - where the instructions of GGL + KLU go on the 256- and 1024-link Cartesian chain, and the
#     ratio to minimal coordinates at the same accuracy (bench/dae_ir.sh -> dae_ir.csv,
#     dae_ratio.csv), for this tree and, with --before, for an older commit built beside it;
#   - every DAE configuration beside the default on the 32-link chain at rtol 1e-3 ... 1e-10
#     (dal_bench_dae configs -> dae_configs.csv, wall times of interleaved runs, and
#     bench/dae_configs_ir.sh -> dae_configs_ir.csv, instructions; ratio default / best per rtol);
#   - the large chain in minimal coordinates against the hand-written O(N) chain, in
#     instructions per run and per right-hand side (bench/min_ir.sh -> min_ir.csv);
#   - the tables of docs/performance.md between <!-- dae:begin/end --> (bench/dae_report.sh).
# Usage: bench/dae.sh [--before COMMIT] [--full]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$root/bench/lib.sh"
before=
mode=--quick
while (($#)); do
  case $1 in
    --before) before=$2; shift 2 ;;
    --full) mode=--full; shift ;;
    --quick) shift ;;
    *) echo "usage: bench/dae.sh [--before COMMIT] [--full]" >&2; exit 2 ;;
  esac
done
out=$root/bench/results
mkdir -p "$out"
# Release with symbols: callgrind names the callbacks (residual, jacobian)
build() { # source dir, build dir
  bench_build "$1" "$2" dal_bench_dae 2 -DCMAKE_C_FLAGS=-g >/dev/null
}
rm -f "$out/dae_ir.csv" "$out/dae_ratio.csv" "$out/min_ir.csv"
if [[ -n $before ]]; then
  # the older library with this tree's benchmark program
  src=$(mktemp -d)
  trap 'rm -rf "$src"' EXIT
  git -C "$root" archive "$before" | tar -x -C "$src"
  cp "$root"/bench/dae_bench.c "$root"/bench/hand.[ch] "$root"/bench/util.[ch] "$src/bench/"
  if ! grep -q dal_bench_dae "$src/bench/CMakeLists.txt"; then
    sed -n '/^# the chain in Cartesian coordinates (DAE forms)/,$p' "$root/bench/CMakeLists.txt" \
      >>"$src/bench/CMakeLists.txt"
  fi
  build "$src" "$src/build"
  "$root/bench/dae_ir.sh" "$src/build/bench/dal_bench_dae" "$out" "before ($before)"
  "$root/bench/dae_configs_ir.sh" "$src/build/bench/dal_bench_dae" "$out" dae_configs_ir_before.csv
  "$root/bench/min_ir.sh" "$src/build/bench/dal_bench_dae" "$out" "before ($before)"
else
  rm -f "$out/dae_configs_ir_before.csv"
fi
bdir=${DAL_DAE_BUILD_DIR:-$root/build-prof}
build "$root" "$bdir"
head=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
"$root/bench/dae_ir.sh" "$bdir/bench/dal_bench_dae" "$out" "after ($head)"
"$root/bench/min_ir.sh" "$bdir/bench/dal_bench_dae" "$out" "after ($head)"
"$bdir/bench/dal_bench_dae" configs "$mode" --out "$out"
"$root/bench/dae_configs_ir.sh" "$bdir/bench/dal_bench_dae" "$out"
{
  echo "date=$(date -u +%Y-%m-%d)"
  echo "cpu=$(awk -F': ' '/^model name/ {print $2; exit}' /proc/cpuinfo)"
  echo "nproc=$(nproc)"
  echo "commit=$head"
  echo "before=${before:--}"
  echo "mode=$mode"
} >"$out/dae_machine.txt"
"$root/bench/dae_report.sh" "$out" "$root/docs/performance.md"
