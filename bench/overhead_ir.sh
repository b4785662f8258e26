#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Ratios in instructions executed (callgrind), which the machine's load does not disturb: one
# run of each side, counted only inside dal_bench's measured region (ir_region). Writes
#   overhead_ir.csv  the chain at N = 1 ... 32: the library (automatic route), the library
#                    forced to the dense route, the lean hand-written dense chain and the
#                    hand-written O(N) chain, same integrator and tolerance
#   cost_ir.csv      the chain at N = 128 ... 4096: the library against the hand-written O(N)
#                    chain (Adams, rtol 1e-6, the horizons of the cost-growth runs)
#   loops_ir.csv     the four-bar linkage and a 64-link chain held at both ends: tree plus
#                    loop rows (recursion, or forced through the KKT matrix) and Cartesian
#                    (GGL; index-1 with projection)
#   routes_ir.csv    the Cartesian N-link chain (N rods): m x m loop system against the KKT
#                    matrix (the measurement behind DAL_LOOP_ROWS_MAX)
# Usage: bench/overhead_ir.sh DAL_BENCH RESULTS_DIR [--quick | --full]
set -euo pipefail
exe=$1
dir=$2
mode=${3:---quick}
if ! command -v valgrind >/dev/null; then
  echo "overhead_ir: valgrind not installed (DAL_WITH_VALGRIND=1 scripts/deps.sh); skipped" >&2
  exit 0
fi
methods="adams dopri5"
t1=0.25
if [[ $mode == --full ]]; then
  methods="adams dopri5 fehlberg78 bdf"
  t1=1.0
fi
rtol=1e-8
# instructions collected in the region and the run's rhs count: "IR RHS"
count() {
  valgrind --tool=callgrind --toggle-collect=ir_region --callgrind-out-file=/dev/null \
    "$exe" "$@" 2>&1 | awk '/Collected :/ {gsub(",", "", $NF); ir = $NF}
      /rhs_evals=/ {for (i = 1; i <= NF; ++i) if ($i ~ /^rhs_evals=/) {split($i, a, "="); rhs = a[2]}}
      END {print ir, rhs}'
}

# ---------------------------------------------------------------- small N: per-evaluation overhead
out=$dir/overhead_ir.csv
echo "N,method,rtol,t1,ir_lib,ir_hand,ratio,rhs_lib,rhs_hand,ir_tridiag,ratio_tridiag,rhs_tridiag,ir_dense,ratio_dense,rhs_dense" >"$out"
for N in 1 2 4 8 16 32; do
  for m in $methods; do
    read -r il rl < <(count ir lib "$N" "$m" "$rtol" "$t1")
    read -r ih rh < <(count ir hand "$N" "$m" "$rtol" "$t1")
    read -r it rt < <(count ir tridiag "$N" "$m" "$rtol" "$t1")
    read -r id rd < <(count ir dense "$N" "$m" "$rtol" "$t1")
    awk -v N="$N" -v m="$m" -v r="$rtol" -v t="$t1" -v il="$il" -v ih="$ih" -v rl="$rl" \
      -v rh="$rh" -v it="$it" -v rt="$rt" -v id="$id" -v rd="$rd" 'BEGIN {
        printf "%d,%s,%s,%s,%.0f,%.0f,%.4f,%d,%d,%.0f,%.4f,%d,%.0f,%.4f,%d\n", N, m, r, t, il, ih,
               il / ih, rl, rh, it, il / it, rt, id, id / ih, rd }' >>"$out"
    echo "overhead_ir N=$N $m: $(tail -1 "$out")" >&2
  done
done

# ---------------------------------------------------------------- large N: the O(N) target
out=$dir/cost_ir.csv
echo "N,method,rtol,t1,ir_lib,ir_tridiag,ratio,rhs_lib,rhs_tridiag" >"$out"
for N in 128 256 512 1024 2048 4096; do
  # the horizons of the cost-growth runs (bench.c cost_t1)
  if ((N <= 128)); then h=0.5; elif ((N <= 512)); then h=0.2; elif ((N <= 1024)); then h=0.1; else h=0.05; fi
  read -r il rl < <(count ir lib "$N" adams 1e-6 "$h")
  read -r it rt < <(count ir tridiag "$N" adams 1e-6 "$h")
  awk -v N="$N" -v t="$h" -v il="$il" -v it="$it" -v rl="$rl" -v rt="$rt" 'BEGIN {
      printf "%d,adams,1e-06,%s,%.0f,%.0f,%.4f,%d,%d\n", N, t, il, it, il / it, rl, rt }' >>"$out"
  echo "cost_ir N=$N: $(tail -1 "$out")" >&2
done

# ---------------------------------------------------------------- closed loops on a tree
out=$dir/loops_ir.csv
echo "scene,form,method,rtol,t1,ir,rhs" >"$out"
for scene in fourbar held64; do
  h=2.0
  [[ $scene == held64 ]] && h=1.0
  for form in tree tree-dense cart-ggl cart-index1; do
    m=dopri5
    r=1e-6
    # GGL in IDA: BDF, two more digits (its error is 100-1000x its tolerance)
    [[ $form == cart-ggl ]] && m=bdf && r=1e-8
    read -r ir rh < <(count irloop "$scene" "$form" "$m" "$r" "$h")
    echo "$scene,$form,$m,$r,$h,$ir,$rh" >>"$out"
    echo "loops_ir: $(tail -1 "$out")" >&2
  done
done

# ---------------------------------------------------------------- loop system or KKT matrix
out=$dir/routes_ir.csv
echo "N,m,ir_loop,ir_kkt,ratio,rhs_loop,rhs_kkt" >"$out"
for N in 4 16 32 64 72 128; do
  read -r il rl < <(count irroute "$N" recursive 1e-6 0.2)
  read -r ik rk < <(count irroute "$N" dense 1e-6 0.2)
  awk -v N="$N" -v il="$il" -v ik="$ik" -v rl="$rl" -v rk="$rk" 'BEGIN {
      printf "%d,%d,%.0f,%.0f,%.4f,%d,%d\n", N, N, il, ik, il / ik, rl, rk }' >>"$out"
  echo "routes_ir: $(tail -1 "$out")" >&2
done
