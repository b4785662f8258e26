#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Instructions per integrated second of each route of bench/scene_route.c (callgrind at T and
# 2T, the difference over T: set-up, compiler run and cache load removed), side by side in one
# run, with the ratios to the C route (docs/performance.md, "Scene files against C").
#   bench/scene_route.sh [BUILD_DIR] [T] [SCENE:ROUTE,ROUTE...]...   (-DDAL_BUILD_BENCH=ON)
# Without rows: every row of docs/performance.md; the first route of a row is its reference.
set -euo pipefail
B=${1:-build}/bench/dal_bench_scene_route
T=${2:-5}
[ -x "$B" ] || { echo "no $B: configure with -DDAL_BUILD_BENCH=ON" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
ir() { # instructions of one run
  valgrind --tool=callgrind --callgrind-out-file="$tmp/out" "$B" "$@" >"$tmp/line" 2>"$tmp/err"
  grep -o 'Collected : [0-9]*' "$tmp/err" | grep -o '[0-9]*$'
}
rows() { # SCENE ROUTE...: one table row per route, the first route the reference
  local s=$1 ref=$2
  shift
  declare -A per=()
  for r in "$@"; do
    case $r in native | lagn) "$B" "$s" "$r" 0.01 >/dev/null ;; esac # compiled beforehand
    a=$(ir "$s" "$r" "$T")
    b=$(ir "$s" "$r" "$(echo "2 * $T" | bc -l)")
    per[$r]=$(echo "($b - $a) / $T" | bc)
    printf '| %s | %s | %s | %d | %.2f |\n' "$s" "$r" "$(grep -o 'route=[a-z]*' "$tmp/line" | cut -d= -f2)" \
      "${per[$r]}" "$(echo "${per[$r]} / ${per[$ref]}" | bc -l)"
  done
}
printf '| scene | route | dynamics | Ir / integrated s | / first row |\n|---|---|---|---|---|\n'
shift $(($# < 2 ? $# : 2))
[ $# -gt 0 ] || set -- pendulum:c,scene,native bead:c,scene,native chain16:c,scene,native \
  pendulum:c,lag,lagn,lagc oscillator:c,scene,lag,lagn,lagc
for spec in "$@"; do
  IFS=, read -r -a routes <<<"${spec#*:}"
  rows "${spec%%:*}" "${routes[@]}"
done
