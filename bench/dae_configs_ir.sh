#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The default DAE configuration against every forced one in instructions (callgrind; the
# machine's load does not move them): the 32-link Cartesian chain to t = 1 s at rtol
# 1e-3 ... 1e-10, one run of each configuration inside dal_bench_dae's measured region.
# Writes dae_configs_ir.csv (or NAME): rtol,config,ir,rhs,steps,jac,err
# Usage: bench/dae_configs_ir.sh DAL_BENCH_DAE RESULTS_DIR [NAME]
set -euo pipefail
exe=$1
dir=$2
if ! command -v valgrind >/dev/null; then
  echo "dae_configs_ir: valgrind not installed; skipped" >&2
  exit 0
fi
out=$dir/${3:-dae_configs_ir.csv}
echo "rtol,config,ir,rhs,steps,jac,err" >"$out"
# name form linsol method (the names of dal_bench_dae configs)
configs="default:auto:auto:auto ggl/bdf/dense:ggl:dense:bdf ggl/bdf/klu:ggl:klu:bdf
index1-proj/dopri5:index1proj:auto:dopri5 index1-proj/fehlberg78:index1proj:auto:fehlberg78
index1-proj/bs:index1proj:auto:bs index1-proj/adams:index1proj:auto:adams"
for r in 1e-3 1e-4 1e-5 1e-6 1e-7 1e-8 1e-9 1e-10; do
  for c in $configs; do
    IFS=: read -r name form linsol method <<<"$c"
    # the error from a plain run (the reference is computed outside the measured region)
    err=$("$exe" ir cart 32 "$r" 1.0 "$form" "$linsol" "$method" --err 2>/dev/null |
      tr ' ' '\n' | awk -F= '$1 == "err" {print $2}')
    valgrind --tool=callgrind --toggle-collect=ir_region --callgrind-out-file=/dev/null \
      "$exe" ir cart 32 "$r" 1.0 "$form" "$linsol" "$method" >"$dir/.dae_cfg.txt" 2>&1 || true
    awk -v r="$r" -v n="$name" -v e="${err:-nan}" '
      /Collected :/ {gsub(",", "", $NF); ir = $NF}
      /rhs_evals=/ {for (i = 1; i <= NF; ++i) {split($i, a, "="); s[a[1]] = a[2]}}
      END {printf "%s,%s,%s,%s,%s,%s,%s\n", r, n, ir, s["rhs_evals"], s["steps"], s["jac_evals"], e}' \
      "$dir/.dae_cfg.txt" >>"$out"
  done
  echo "dae_configs_ir: rtol $r done" >&2
done
rm -f "$dir/.dae_cfg.txt"
