#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Run a benchmark program that prints one CSV row per measured run (first column: the row
# number K) and asks callgrind to dump its counts after each run (CALLGRIND_DUMP_STATS_AT
# "rowK"), counting only inside the functions matching TOGGLE; append the instructions of
# each run to its row as the column `ir`.
# Usage: bench/cg_rows.sh TOGGLE OUT.csv PROGRAM [ARGS ...]
set -euo pipefail
toggle=$1
out=$2
shift 2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
valgrind --tool=callgrind "--toggle-collect=$toggle" --dump-instr=no \
  --callgrind-out-file="$tmp/cg.out" "$@" >"$tmp/rows.csv" 2>"$tmp/valgrind.log" || {
  tail -20 "$tmp/valgrind.log" >&2
  exit 1
}
for f in "$tmp"/cg.out.*; do
  awk '/^desc: Trigger: Client Request: row/ {sub(/.*row/, ""); r = $0}
       /^summary:/ {s = $2} END {if (r != "") print r "," s}' "$f"
done | sort -t, -k1,1n >"$tmp/ir.csv"
awk -F, 'NR == FNR {ir[$1] = $2; next}
         FNR == 1 {print $0 ",ir"; next}
         {print $0 "," ($1 in ir ? ir[$1] : "nan")}' "$tmp/ir.csv" "$tmp/rows.csv" >"$out"
