#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The dense-output table of docs/performance.md from two runs of bench/dense_ir.c under
# bench/cg_rows.sh (BEFORE.csv and AFTER.csv: row,scene,method,rtol,mode,steps,rhs,status,ir):
# per scene, method and rtol the plain advance's instructions, evolve reading q over advance
# before and after, the right-hand sides of advance and evolve, evolve reading the energies
# over advance, and the extra instructions per output (10 000 outputs).
# Usage: bench/dense_table.sh BEFORE.csv AFTER.csv
set -euo pipefail
awk -F, 'FNR == 1 {file++; next}
  {k = $2 "|" $3 "|" $4; ir[file, k, $5] = $9; rhs[file, k, $5] = $7
   if (file == 2 && !(k in seen)) {seen[k] = 1; order[++n] = k}}
  END {
    print "| scene | method | rtol | advance (Ir) | evolve, q / advance: before | after | extra Ir per output | rhs advance / evolve | evolve, energies / advance |"
    print "|---|---|---|---:|---:|---:|---:|---:|---:|"
    worst = 0
    for (i = 1; i <= n; ++i) {
      k = order[i]; split(k, p, "|")
      a = ir[2, k, "advance"]; q = ir[2, k, "evolve-q"]; e = ir[2, k, "evolve-energies"]
      b = ir[1, k, "advance"] > 0 ? ir[1, k, "evolve-q"] / ir[1, k, "advance"] : 0
      printf "| %s | %s | %s | %.3g | %.2f | %.2f | %.0f | %d / %d | %.2f |\n", p[1], p[2], p[3], a,
             b, q / a, (q - a) / 10000, rhs[2, k, "advance"], rhs[2, k, "evolve-q"], e / a
    }
  }' "$1" "$2"
