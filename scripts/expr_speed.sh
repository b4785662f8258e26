#!/bin/sh
# SPDX-License-Identifier: MIT
# Instructions per right-hand side (dal_forward) of scenes placed by expressions and by the
# C primitives: cachegrind's instruction count at N = 2000 minus N = 1000, over 1000.
# Usage: scripts/expr_speed.sh [build-dir]   (needs valgrind; build type RelWithDebInfo)
set -e
B=${1:-build}
ir() {
  valgrind --tool=cachegrind --cache-sim=no --cachegrind-out-file=/dev/null "$B/bench/dal_bench_expr" "$@" 2>&1 |
    sed -n 's/.*I *refs: *//p' | tr -d ,
}
printf '| scene | C jets | expressions | ratio | native code | ratio |\n|---|---|---|---|---|---|\n'
for s in pendulum bead chain32; do
  "$B/bench/dal_bench_expr" $s native 1 >/dev/null # compiled into the cache beforehand
  c=$(( ($(ir $s c 2000) - $(ir $s c 1000)) / 1000 ))
  e=$(( ($(ir $s expr 2000) - $(ir $s expr 1000)) / 1000 ))
  n=$(( ($(ir $s native 2000) - $(ir $s native 1000)) / 1000 ))
  printf '| %s | %d | %d | %s | %d | %s |\n' "$s" "$c" "$e" "$(awk "BEGIN{printf \"%.2f\", $e/$c}")" \
    "$n" "$(awk "BEGIN{printf \"%.2f\", $n/$c}")"
done
