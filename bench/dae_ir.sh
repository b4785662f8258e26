#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Where the instructions of the sparse DAE go (callgrind, unaffected by the machine's load):
# the N-link Cartesian chain in GGL with KLU, one run of dal_bench_dae inside its measured
# region, split by the inclusive counts of the residual, the Newton matrix, KLU's factorization
# and solves, IDA's own work and the setup; and its ratio to minimal coordinates (the
# articulated-body recursion, Adams) at the same accuracy. Writes (appends with a label)
#   dae_ir.csv     label,N,t1,rtol,total,setup,residual,newton,klu_factor,klu_solve,ida_rest,
#                  rhs,steps,jac
#   dae_ratio.csv  label,N,t1,target,ggl_rtol,ggl_err,ggl_ir,min_rtol,min_err,min_ir,ratio
#                  (each side at the loosest rtol of 1e-4 ... 1e-9 whose error at t1, against
#                  the hand-written O(N) chain at rtol 1e-12, is below the target)
# Usage: bench/dae_ir.sh DAL_BENCH_DAE RESULTS_DIR LABEL [N ...]   (default N: 256 1024)
# Build dal_bench_dae with -g (symbols of the static callbacks), e.g.
#   cmake -S . -B build-prof -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS=-g -DDAL_BUILD_BENCH=ON
set -euo pipefail
exe=$1
dir=$2
label=$3
shift 3
sizes=${*:-256 1024}
target=1e-8
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
ir_start dae_ir "$dir"
horizon() { if (($1 <= 256)); then echo 0.2; else echo 0.1; fi; }
# inclusive instructions of a function in a profile (0 when absent)
incl() {
  awk -v f="$2" '$0 ~ "[:]" f "([ .]|$)" {gsub(",", "", $1); print $1; exit}' "$1"
}
csv=$dir/dae_ir.csv
[[ -f $csv ]] || echo "label,N,t1,rtol,total,setup,residual,newton,klu_factor,klu_solve,ida_rest,rhs,steps,jac" >"$csv"
rcsv=$dir/dae_ratio.csv
[[ -f $rcsv ]] || echo "label,N,t1,target,ggl_rtol,ggl_err,ggl_ir,min_rtol,min_err,min_ir,ratio" >"$rcsv"
for N in $sizes; do
  t1=$(horizon "$N")
  # ---- the profile at a fixed workload: GGL, KLU, rtol 1e-6
  out=$tmp/p.cg
  stats=$(valgrind --tool=callgrind --toggle-collect=ir_region --callgrind-out-file="$out" \
    "$exe" ir cart "$N" 1e-6 "$t1" ggl klu bdf 2>/dev/null)
  callgrind_annotate --inclusive=yes --threshold=100 "$out" 2>/dev/null >"$tmp/a.txt"
  total=$(awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1; exit}' "$tmp/a.txt")
  setup=$(incl "$tmp/a.txt" dal__ida_create)
  solve=$(incl "$tmp/a.txt" IDASolve)
  res=$(incl "$tmp/a.txt" residual)
  jac=$(incl "$tmp/a.txt" jacobian)
  kf=$(incl "$tmp/a.txt" SUNLinSolSetup_KLU)
  ks=$(incl "$tmp/a.txt" SUNLinSolSolve_KLU)
  get() { echo "$stats" | tr ' ' '\n' | awk -F= -v k="$1" '$1 == k {print $2}'; }
  awk -v l="$label" -v N="$N" -v t="$t1" -v T="$total" -v s="${setup:-0}" -v S="${solve:-0}" \
    -v r="${res:-0}" -v j="${jac:-0}" -v kf="${kf:-0}" -v ks="${ks:-0}" -v rhs="$(get rhs_evals)" \
    -v st="$(get steps)" -v je="$(get jac_evals)" 'BEGIN {
      printf "%s,%d,%s,1e-06,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f,%d,%d,%d\n", l, N, t, T, s, r, j, kf, ks,
             S - r - j - kf - ks, rhs, st, je }' >>"$csv"
  echo "dae_ir $label N=$N: $(tail -1 "$csv")" >&2
  # ---- the ratio to minimal coordinates at the same accuracy
  pick() { # form -> "rtol err" of the loosest rtol meeting the target
    for r in 1e-4 1e-5 1e-6 1e-7 1e-8 1e-9; do
      local line e
      if [[ $1 == cart ]]; then
        line=$("$exe" ir cart "$N" "$r" "$t1" ggl klu bdf --err 2>/dev/null || true)
      else
        line=$("$exe" ir min "$N" "$r" "$t1" --err 2>/dev/null || true)
      fi
      e=$(echo "$line" | tr ' ' '\n' | awk -F= '$1 == "err" {print $2}')
      if [[ -n $e ]] && awk -v e="$e" -v t="$target" 'BEGIN {exit !(e <= t)}'; then
        echo "$r $e"
        return
      fi
    done
    echo "- -"
  }
  count() {
    valgrind --tool=callgrind --toggle-collect=ir_region --callgrind-out-file=/dev/null "$@" 2>&1 |
      awk '/Collected :/ {gsub(",", "", $NF); print $NF}'
  }
  read -r gr ge < <(pick cart)
  read -r mr me < <(pick min)
  gi=0
  mi=0
  [[ $gr != - ]] && gi=$(count "$exe" ir cart "$N" "$gr" "$t1" ggl klu bdf)
  [[ $mr != - ]] && mi=$(count "$exe" ir min "$N" "$mr" "$t1")
  awk -v l="$label" -v N="$N" -v t="$t1" -v T="$target" -v gr="$gr" -v ge="$ge" -v gi="$gi" \
    -v mr="$mr" -v me="$me" -v mi="$mi" 'BEGIN {
      printf "%s,%d,%s,%s,%s,%s,%.0f,%s,%s,%.0f,%.2f\n", l, N, t, T, gr, ge, gi, mr, me, mi,
             (mi > 0 ? gi / mi : 0) }' >>"$rcsv"
  echo "dae_ratio $label N=$N: $(tail -1 "$rcsv")" >&2
done
