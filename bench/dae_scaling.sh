#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The Cartesian chain's cost over N in GGL with KLU (issue 36): dal_bench_dae scaling under
# callgrind (one run per N, counted in ir_region only), then per simulated second the Newton
# iterations, Newton matrices (Jacobians, each a KLU refactorization), steps and instructions,
# the ratio of each N's instructions to the size before it, and the fitted exponent of
# instructions per simulated second over N.
# Usage: bench/dae_scaling.sh DAL_BENCH_DAE OUT.csv RTOL T1 [N ...]   (runs and tabulates)
#        bench/dae_scaling.sh --table OUT.csv [BEFORE.csv]            (tabulates only)
set -euo pipefail
table() {
  awk -F, 'FNR == 1 {file++; next}
    {k = $2; ir[file, k] = $10; it[file, k] = $6; jac[file, k] = $7; st[file, k] = $5; t1 = $4
     rt = $3; if (file == 1) order[++n] = k}
    END {
      two = file == 2
      printf "rtol %s, t1 = %s s; per simulated second%s:\n\n", rt, t1, two ? " (before -> after)" : ""
      print "| N | Newton iterations | Jacobians | steps | iterations / step | instructions | ratio to the N before |"
      print "|---:|---:|---:|---:|---:|---:|---:|"
      for (f = 1; f <= 1 + two; ++f) {sx[f] = sy[f] = sxx[f] = sxy[f] = 0; worst[f] = 0}
      for (i = 1; i <= n; ++i) {
        k = order[i]
        for (f = 1; f <= 1 + two; ++f) {
          x = log(k); y = log(ir[f, k] / t1)
          sx[f] += x; sy[f] += y; sxx[f] += x * x; sxy[f] += x * y
          r[f] = i > 1 ? ir[f, k] / ir[f, order[i - 1]] : 0
          if (r[f] > worst[f]) {worst[f] = r[f]; wat[f] = order[i - 1] " -> " k}
        }
        if (two)
          printf "| %d | %.0f -> %.0f | %.0f -> %.0f | %.0f -> %.0f | %.2f -> %.2f | %.3g -> %.3g | %s -> %s |\n", k,
                 it[1, k] / t1, it[2, k] / t1, jac[1, k] / t1, jac[2, k] / t1, st[1, k] / t1,
                 st[2, k] / t1, it[1, k] / st[1, k], it[2, k] / st[2, k], ir[1, k] / t1,
                 ir[2, k] / t1, (i > 1 ? sprintf("%.2f", r[1]) : "-"), (i > 1 ? sprintf("%.2f", r[2]) : "-")
        else
          printf "| %d | %.0f | %.0f | %.0f | %.2f | %.3g | %s |\n", k, it[1, k] / t1, jac[1, k] / t1,
                 st[1, k] / t1, it[1, k] / st[1, k], ir[1, k] / t1, (i > 1 ? sprintf("%.2f", r[1]) : "-")
      }
      printf "\n"
      for (f = 1; f <= 1 + two; ++f)
        printf "%sinstructions per simulated second N^%.2f over N = %s ... %s; largest neighbour ratio %.2f (%s)\n",
               (two ? (f == 1 ? "before: " : "after: ") : ""), (n * sxy[f] - sx[f] * sy[f]) / (n * sxx[f] - sx[f] * sx[f]),
               order[1], order[n], worst[f], wat[f]
    }' "$@"
}
if [[ ${1:-} == --table ]]; then
  shift
  if [[ $# -eq 2 ]]; then table "$2" "$1"; else table "$1"; fi
  exit 0
fi
exe=$1
out=$2
shift 2
"$(dirname "$0")/cg_rows.sh" 'ir_region*' "$out" "$exe" scaling "$@"
table "$out"
