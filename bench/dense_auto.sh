#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# AUTO's choice for runs with outputs on three and more coordinates: bench/dense_auto.c under
# callgrind for the chain at the given sizes, then for each size and error band the
# instructions each method needs to reach it (interpolated log-log between the rtols that
# bracket it, as dal_bench_auto's table does), over the cheapest.
# Usage: bench/dense_auto.sh DAL_BENCH_DENSE_AUTO OUT.csv N [N ...]
#        bench/dense_auto.sh --table OUT.csv   (the table of an existing run)
set -euo pipefail
here=$(dirname "$0")
if [[ $1 != --table ]]; then
  exe=$1
  out=$2
  shift 2
  "$here/cg_rows.sh" 'dense_auto_region*' "$out" "$exe" "$@"
else
  out=$2
fi
awk -F, 'NR > 1 && $5 == "DAL_OK" {k = $2 SUBSEP $3; n[k]++; r[k, n[k]] = $4; e[k, n[k]] = $6
           c[k, n[k]] = $8; if (!($2 in sz)) {sz[$2] = 1; order[++ns] = $2}; if (!($3 in mm)) {
           mm[$3] = 1; meth[++nm] = $3}}
  function cost(k, band,   i, w) {
    for (i = 1; i <= n[k]; ++i) if (e[k, i] <= band) {
      if (i == 1 || e[k, i - 1] <= band) return c[k, i]
      w = (log(band) - log(e[k, i - 1])) / (log(e[k, i]) - log(e[k, i - 1]))
      return exp(log(c[k, i - 1]) + w * (log(c[k, i]) - log(c[k, i - 1])))
    }
    return -1
  }
  END {
    nb = split("1e-7 1e-8 1e-9 1e-10", bands, " ")
    line = "| N | error band"; sep = "|---:|---:"
    for (j = 1; j <= nm; ++j) {line = line " | " meth[j] " / best"; sep = sep "|---:"}
    print line " |"; print sep "|"
    for (i = 1; i <= ns; ++i) for (b = 1; b <= nb; ++b) {
      best = -1
      for (j = 1; j <= nm; ++j) {x[j] = cost(order[i] SUBSEP meth[j], bands[b] + 0)
        if (x[j] > 0 && (best < 0 || x[j] < best)) best = x[j]}
      if (best < 0) continue
      line = "| " order[i] " | " bands[b]
      for (j = 1; j <= nm; ++j) line = line (x[j] > 0 ? sprintf(" | %.2f", x[j] / best) : " | -")
      print line " |"
    }
  }' "$out"
