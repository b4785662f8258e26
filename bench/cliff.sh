#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The cliff sweep: instructions per step of the N-link chain against N (1 ... 512, about
# sqrt(2) apart) in every formulation, each route chosen automatically (callgrind: the
# machine's load does not move it). Writes RESULTS_DIR/cliff.csv and cliff.png/.svg, and
# prints the largest ratio between neighbouring sizes of the cost per step.
# Usage: bench/cliff.sh DAL_BENCH_CLIFF RESULTS_DIR
set -euo pipefail
exe=$1
dir=$2
here=$(dirname "$0")
mkdir -p "$dir"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sizes="1 2 3 4 6 8 11 16 23 32 45 64 91 128 181 256 362 512"
first=1
for form in ode index1-proj index1-baumgarte ggl index1 index3; do
  "$here/cg_rows.sh" 'cliff_region*' "$tmp/$form.csv" "$exe" "$form" auto $sizes
  if ((first)); then head -1 "$tmp/$form.csv" | sed 's/$/,ir_per_step/' >"$dir/cliff.csv"; fi
  first=0
  awk -F, 'NR > 1 {printf "%s,%.6g\n", $0, $9 / $6}' "$tmp/$form.csv" >>"$dir/cliff.csv"
  echo "cliff: $form done" >&2
done
# largest jump of the cost per step between neighbouring sizes (either way), per formulation
awk -F, 'NR > 1 && $6 > 0 {c = $10; if ($2 == f) {r = c / p; if (r < 1) r = 1 / r;
           if (r > w[f]) {w[f] = r; at[f] = pn "->" $4}} f = $2; p = c; pn = $4}
         END {for (k in w) printf "%s: largest jump between neighbours %.2f (N = %s)\n", k, w[k], at[k]}' \
  "$dir/cliff.csv"
gnuplot -e "dir='$dir'" "$here/cliff.gp"
