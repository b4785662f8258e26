#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The large chain in minimal coordinates against the hand-written O(N) chain, in instructions
# (callgrind): the library's automatic route (the articulated-body recursion) and the
# hand-written chain (rod tensions from a tridiagonal system, bench/hand.c) by CVODE Adams at
# the same local tolerance (the same steps), rtol 1e-6, the horizons of the cost-growth runs.
# Splits the library's run into the right-hand side (kinematics, forces, recursion) and the
# rest (CVODE, setup, the final evaluation of every output), and gives the cost per
# right-hand side per link on both sides. Appends to min_ir.csv:
#   label,N,t1,rhs_lib,rhs_hand,ir_lib,ir_hand,ratio,rhs_ir_lib,rhs_ir_hand,kin,forces,aba,
#   cvode_lib,cvode_hand
# Usage: bench/min_ir.sh DAL_BENCH_DAE RESULTS_DIR LABEL [N ...]  (default 128 ... 4096)
set -euo pipefail
exe=$1
dir=$2
label=$3
shift 3
sizes=${*:-128 256 512 1024 2048 4096}
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
ir_start min_ir "$dir"
csv=$dir/min_ir.csv
[[ -f $csv ]] || echo "label,N,t1,rhs_lib,rhs_hand,ir_lib,ir_hand,ratio,rhs_ir_lib,rhs_ir_hand,kin,forces,aba,cvode_lib,cvode_hand" >"$csv"
# inclusive instructions of a function in an annotated profile (0 when absent)
incl() {
  awk -v f="$2" '$0 ~ "[:]" f "([ .]|$)" {gsub(",", "", $1); v = $1; exit} END {print v + 0}' "$1"
}
for N in $sizes; do
  # the horizons of the cost-growth runs (bench.c cost_t1)
  if ((N <= 128)); then t1=0.5; elif ((N <= 512)); then t1=0.2; elif ((N <= 1024)); then t1=0.1; else t1=0.05; fi
  sl=$(valgrind --tool=callgrind --toggle-collect=ir_region --callgrind-out-file="$tmp/l.cg" \
    "$exe" ir min "$N" 1e-6 "$t1" 2>/dev/null)
  sh=$(valgrind --tool=callgrind --toggle-collect=ir_region --callgrind-out-file="$tmp/h.cg" \
    "$exe" ir hand "$N" 1e-6 "$t1" 2>/dev/null)
  callgrind_annotate --inclusive=yes --threshold=100 "$tmp/l.cg" 2>/dev/null >"$tmp/l.txt"
  callgrind_annotate --inclusive=yes --threshold=100 "$tmp/h.cg" 2>/dev/null >"$tmp/h.txt"
  tl=$(awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1; exit}' "$tmp/l.txt")
  th=$(awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1; exit}' "$tmp/h.txt")
  rl=$(echo "$sl" | tr ' ' '\n' | awk -F= '$1 == "rhs_evals" {print $2; exit}')
  rh=$(echo "$sh" | tr ' ' '\n' | awk -F= '$1 == "rhs_evals" {print $2; exit}')
  awk -v l="$label" -v N="$N" -v t="$t1" -v rl="$rl" -v rh="$rh" -v tl="$tl" -v th="$th" \
    -v ril="$(incl "$tmp/l.txt" minimal_rhs)" -v rih="$(incl "$tmp/h.txt" hand_chain_rhs_tridiag)" \
    -v kin="$(incl "$tmp/l.txt" dal__kinematics)" -v fo="$(incl "$tmp/l.txt" dal__forces)" \
    -v dy="$(incl "$tmp/l.txt" dal__dynamics)" -v aba="$(incl "$tmp/l.txt" dal__aba_accel)" \
    -v cl="$(incl "$tmp/l.txt" CVode)" -v ch="$(incl "$tmp/h.txt" CVode)" 'BEGIN {
      # forces: dal__forces on the right-hand side (dal__dynamics before it existed)
      printf "%s,%d,%s,%d,%d,%.0f,%.0f,%.4f,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f\n", l, N, t, rl,
             rh, tl, th, tl / th, ril, rih, kin, (fo > 0 ? fo : dy), aba, cl, ch }' >>"$csv"
  echo "min_ir $label N=$N: $(tail -1 "$csv")" >&2
done
