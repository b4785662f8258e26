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
# IDA's forms again at one fixed step (5e-4 s: 400 steps in the region at every N), so that
# the step size is not what differs between neighbouring sizes
first=1
for form in ggl index1 index3; do
  "$here/cg_rows.sh" 'cliff_region*' "$tmp/$form.csv" "$exe" --fixed-h 5e-4 "$form" auto $sizes
  if ((first)); then head -1 "$tmp/$form.csv" | sed 's/$/,ir_per_step/' >"$dir/cliff_fixed.csv"; fi
  first=0
  awk -F, 'NR > 1 {printf "%s,%.6g\n", $0, ($6 > 0 ? $9 / $6 : 0)}' "$tmp/$form.csv" >>"$dir/cliff_fixed.csv"
  echo "cliff: $form at a fixed step done" >&2
done
# largest jump of the cost per step between neighbouring sizes (either way), per formulation,
# from N = 2 on (N = 1 -> 2 doubles the size); a size that failed breaks the chain
for f in cliff cliff_fixed; do
  awk -F, -v what="$f" 'NR > 1 && ($6 <= 0 || $8 != "DAL_OK") {fm = ""; next}
         NR > 1 {c = $10
           if ($2 == fm && $4 > 2 && pn >= 2) {r = c / p; if (r < 1) r = 1 / r
             if (r > w[fm]) {w[fm] = r; at[fm] = pn "->" $4}}
           fm = $2; p = c; pn = $4}
         END {for (k in w) printf "%s %s: largest jump between neighbours from N = 2 on %.2f (N = %s)\n",
                                  what, k, w[k], at[k]}' "$dir/$f.csv"
done
gnuplot -e "dir='$dir'" "$here/cliff.gp"
