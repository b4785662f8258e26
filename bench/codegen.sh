#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Instructions per integrated second of each route of bench/codegen_bench.c (callgrind at
# T = 10 and T = 20, the difference over 10 s: set-up, compiler run and cache load removed),
# and the ratios to SymPy's closed form and to the C jets (docs/performance.md).
#   bench/codegen.sh [BUILD_DIR]     (configure with -DDAL_BUILD_BENCH=ON; python3-sympy)
set -euo pipefail
B=${1:-build}/bench/dal_bench_codegen
[ -x "$B" ] || { echo "no $B: configure with -DDAL_BUILD_BENCH=ON (needs python3-sympy)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$B" pendulum native 0.01 >/dev/null # the native code compiled into the cache beforehand
"$B" bead native 0.01 >/dev/null
ir() { # instructions of one run
  valgrind --tool=callgrind --callgrind-out-file="$tmp/out" "$B" "$@" >/dev/null 2>"$tmp/err"
  grep -o 'Collected : [0-9]*' "$tmp/err" | grep -o '[0-9]*$'
}
printf '%-9s %-7s %14s %12s %12s\n' scene route "Ir/int. s" "/ sympy" "/ C jets"
for s in pendulum bead; do
  declare -A per=()
  for r in sympy c scene native; do
    a=$(ir $s $r 10)
    b=$(ir $s $r 20)
    per[$r]=$(( (b - a) / 10 ))
  done
  for r in sympy c scene native; do
    printf '%-9s %-7s %14d %12.2f %12.2f\n' $s $r ${per[$r]} \
      "$(echo "${per[$r]} / ${per[sympy]}" | bc -l)" "$(echo "${per[$r]} / ${per[c]}" | bc -l)"
  done
  unset per
done
