#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Instructions per integrated second of each route of bench/codegen_bench.c (callgrind at
# T = 10 and T = 20, the difference over 10 s: set-up, compiler run and cache load removed),
# and the ratios to SymPy's C and to the C jets (docs/performance.md). The library's best
# route is `eom` (native formulas and compiled equations of motion, dal_scene_native's
# default); `c` the built-in C primitives; `scene` the bytecode; `native` formulas only.
#   bench/codegen.sh [BUILD_DIR] [SCENE ...]   (configure with -DDAL_BUILD_BENCH=ON; python3-sympy)
#   scenes: pendulum bead double spherical chain8 chain16 (default: all)
set -euo pipefail
B=${1:-build}/bench/dal_bench_codegen
shift || true
scenes=${*:-pendulum bead double spherical chain8 chain16}
[ -x "$B" ] || { echo "no $B: configure with -DDAL_BUILD_BENCH=ON (needs python3-sympy)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for s in $scenes; do # the native code compiled into the cache beforehand
  "$B" "$s" native 0.01 >/dev/null
  "$B" "$s" eom 0.01 >/dev/null
done
ir() { # instructions of one run
  valgrind --tool=callgrind --callgrind-out-file="$tmp/out" "$B" "$@" >"$tmp/stdout" 2>"$tmp/err"
  grep -o 'Collected : [0-9]*' "$tmp/err" | grep -o '[0-9]*$'
}
printf '%-9s %-7s %14s %8s %8s %8s\n' scene route "Ir/int. s" "/ sympy" "/ C jets" "steps"
for s in $scenes; do
  declare -A per=() steps=()
  for r in sympy c scene native eom; do
    a=$(ir $s $r 10)
    b=$(ir $s $r 20)
    steps[$r]=$(grep -o 'steps [0-9]*' "$tmp/stdout" | grep -o '[0-9]*$')
    per[$r]=$(( (b - a) / 10 ))
  done
  for r in sympy c scene native eom; do
    printf '%-9s %-7s %14d %8.2f %8.2f %8d\n' $s $r ${per[$r]} \
      "$(echo "${per[$r]} / ${per[sympy]}" | bc -l)" "$(echo "${per[$r]} / ${per[c]}" | bc -l)" \
      ${steps[$r]}
  done
  unset per steps
done
