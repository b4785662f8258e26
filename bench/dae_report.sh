#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The sparse DAE's tables, computed from dae_ir.csv, dae_ratio.csv, dae_configs.csv and
# dae_configs_ir.csv only:
# writes dae_summary.md and copies it into docs/performance.md between <!-- dae:begin/end -->.
# Usage: bench/dae_report.sh [results-dir] [target markdown file]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
dir=${1:-$root/bench/results}
doc=${2:-$root/docs/performance.md}
out=$dir/dae_summary.md
meta() { awk -F'=' -v k="$1" '$1==k {sub(/^[^=]*=/, ""); print; exit}' "$dir/dae_machine.txt"; }

{
  cmd="bench/dae.sh"
  [[ $(meta before) != - ]] && cmd="$cmd --before $(meta before)"
  echo "_Measured $(meta date), $(meta nproc) cores, $(meta cpu); \`$cmd\` at commit"
  echo "$(meta commit). Computed by \`bench/dae_report.sh\` from \`dae_ir.csv\`, \`dae_ratio.csv\`,"
  echo "\`dae_configs.csv\`, \`dae_configs_ir.csv\` and \`min_ir.csv\`._"
  echo
  if [[ -s $dir/dae_ir.csv ]]; then
    echo "**Where the instructions go** (\`dae_ir.csv\`; callgrind, one run inside the measured"
    echo "region): the N-link Cartesian chain (2N coordinates, N rods, 6N unknowns) in GGL with"
    echo "KLU at rtol 1e-6, released from rest at 45 degrees, to t = 0.2 s (N = 256) and 0.1 s"
    echo "(N = 1024). Inclusive instruction counts: the residual (kinematics, constraint rows,"
    echo "forces, M v', G' lambda, G' mu), the Newton matrix (assembly from exact pieces), KLU's"
    echo "factorizations and solves, IDA's own work (its vector operations, error test, step"
    echo "control) and the setup (consistent start, pattern); share of the total in brackets."
    echo
    awk -F, 'NR > 1 { c[++n] = $1 " N=" $2; for (k = 5; k <= 14; ++k) v[n, k] = $k }
      END {
        printf "| part |"; for (i = 1; i <= n; ++i) printf " %s |", c[i]; printf "\n"
        printf "|---|"; for (i = 1; i <= n; ++i) printf "---:|"; printf "\n"
        split("residual,Newton matrix,KLU factorization,KLU solves,IDA itself,setup", name, ",")
        split("7,8,9,10,11,6", col, ",")
        for (r = 1; r <= 6; ++r) {
          printf "| %s |", name[r]
          for (i = 1; i <= n; ++i)
            printf " %.3g (%.0f%%) |", v[i, col[r]], 100 * v[i, col[r]] / v[i, 5]
          printf "\n"
        }
        printf "| **total** |"; for (i = 1; i <= n; ++i) printf " **%.3g** |", v[i, 5]; printf "\n"
        printf "| residuals / steps / Jacobians |"
        for (i = 1; i <= n; ++i) printf " %d / %d / %d |", v[i, 12], v[i, 13], v[i, 14]
        printf "\n"
      }' "$dir/dae_ir.csv"
    echo
  fi
  if [[ -s $dir/dae_ratio.csv ]]; then
    echo "**Against minimal coordinates at the same accuracy** (\`dae_ratio.csv\`): each side"
    echo "at the loosest rtol of 1e-4 ... 1e-9 whose max position error at t1 (against the"
    echo "hand-written O(N) chain by Fehlberg 7(8) at rtol 1e-12) is below 1e-8; minimal"
    echo "coordinates through the library's automatic route (the articulated-body recursion) with"
    echo "Adams. Instructions of one run each."
    echo
    echo "| | N | t1 (s) | GGL + KLU: rtol, error | instructions | minimal (Adams): rtol, error | instructions | GGL / minimal |"
    echo "|---|---:|---:|---|---:|---|---:|---:|"
    awk -F, 'NR > 1 { printf "| %s | %d | %s | %s, %s | %.3g | %s, %s | %.3g | %.2f |\n", $1, $2,
                       $3, $5, $6, $7, $8, $9, $10, $11 }' "$dir/dae_ratio.csv"
    echo
  fi
  if [[ -s $dir/dae_configs.csv ]]; then
    echo "**The default DAE configuration against every forced one** (\`dae_configs_ir.csv\`,"
    echo "\`dae_configs.csv\`): the 32-link Cartesian chain (192 unknowns) to t = 1 s, the"
    echo "default options with only rtol set beside GGL (BDF) with dense LU and with KLU and the"
    echo "index-1 form with projection by DOPRI5, Fehlberg 7(8), Bulirsch-Stoer and Adams. The"
    echo "ratio in instructions (callgrind, one run each) is the measure; the wall-time ratio"
    echo "(medians of runs interleaved in one process) is given beside it, and moves with the"
    echo "load of the shared machine (the default and the configuration it runs as are the same"
    echo "computation)."
    echo
    echo "| rtol | default runs as (same steps and error) | its error | best forced (instructions) | its error | default / best, instructions | default / best, wall time | before: default / best, instructions |"
    echo "|---:|---|---:|---|---:|---:|---:|---:|"
    [[ -s $dir/dae_configs_ir.csv ]] || : >"$dir/dae_configs_ir.csv"
    before=$dir/dae_configs_ir_before.csv
    [[ -s $before ]] || before=/dev/null
    awk -F, -v bf="$before" -v irf="$dir/dae_configs_ir.csv" 'FNR == 1 { next }
      FILENAME == bf {
        r = $1 + 0
        if ($2 == "default") { pdi[r] = $3 }
        else if ($3 > 0 && $7 != "nan" && (!(r in pbi) || $3 < pbi[r])) { pbi[r] = $3 }
        next
      }
      FILENAME == irf {
        r = $1 + 0
        if ($2 == "default") { di[r] = $3 }
        else if ($3 > 0 && $7 != "nan" && (!(r in bi) || $3 < bi[r])) { bi[r] = $3; bn[r] = $2; be[r] = $7 }
        next
      }
      {
        r = $3 + 0
        if (!(r in seen)) { seen[r] = 1; order[++n] = r }
        if ($4 == "default") { de[r] = $11; dr[r] = $12; what[r] = $5 }
      }
      END {
        worst = 0; worstw = 0
        for (i = 1; i <= n; ++i) {
          r = order[i]
          ri = (r in bi) && bi[r] > 0 ? di[r] / bi[r] : -1
          pr = (r in pbi) && pbi[r] > 0 ? sprintf("%.2f", pdi[r] / pbi[r]) : "-"
          printf "| %g | %s | %.2g | %s | %.2g | %s | %.2f | %s |\n", r, what[r], de[r],
                 ((r in bn) ? bn[r] : "-"), be[r], (ri > 0 ? sprintf("%.2f", ri) : "-"), dr[r], pr
          if (ri > worst) { worst = ri; wr = r }
          if (dr[r] > worstw) { worstw = dr[r]; wwr = r }
        }
        printf "\nLargest default / best: %.2f in instructions (rtol %g), %.2f in wall time (rtol %g); target: never above 3.\n", worst, wr, worstw, wwr
      }' "$before" "$dir/dae_configs_ir.csv" "$dir/dae_configs.csv"
    echo
  fi
  if [[ -s $dir/min_ir.csv ]]; then
    echo "**The large chain in minimal coordinates against the hand-written O(N) chain**"
    echo "(\`min_ir.csv\`, \`bench/min_ir.sh\`): the library's automatic route (the"
    echo "articulated-body recursion) and the chain derived by hand in its O(N) form (rod"
    echo "tensions from a tridiagonal system), both by CVODE Adams at the same local tolerance"
    echo "(rtol 1e-6: the same steps, equal right-hand-side counts), the horizons of the"
    echo "cost-growth runs; instructions of one run each. Per right-hand side and link: the"
    echo "library's evaluation (kinematics + forces + recursion + the rest of the pipeline;"
    echo "it includes the run's final evaluation of every output, which up to 512 coordinates"
    echo "assembles the dense M, O(N^2)) against the hand-written function; the rest of each"
    echo "run is CVODE's own work (the same code on both sides) and the setup."
    echo
    echo "(Before, the forces column is all of dal__dynamics: forces, Q, c and the energies.)"
    echo
    echo "| | N | rhs | library | hand-written | ratio | per rhs and link: library (kinematics / forces / recursion) | hand-written |"
    echo "|---|---:|---:|---:|---:|---:|---|---:|"
    awk -F, 'NR > 1 {
        e = $4 * $2
        printf "| %s | %d | %d | %.3g | %.3g | %.2f | %.0f (%.0f / %.0f / %.0f) | %.0f |\n", $1, $2,
               $4, $6, $7, $8, $9 / e, $11 / e, $12 / e, $13 / e, $10 / ($5 * $2)
      }' "$dir/min_ir.csv"
    echo
    # least-squares exponents over N of the last label (per simulated second, per rhs)
    awk -F, 'NR > 1 { lab[NR] = $1; last = $1 }
      NR > 1 { L[NR] = $0 }
      END {
        n = 0
        for (i in L) {
          split(L[i], f, ",")
          if (f[1] != last) continue
          x = log(f[2]); ++n
          y1 = log(f[6] / f[3]); y2 = log(f[7] / f[3]); y3 = log(f[9] / f[4]); y4 = log(f[10] / f[5])
          sx += x; sxx += x * x; s1 += y1; s2 += y2; s3 += y3; s4 += y4
          p1 += x * y1; p2 += x * y2; p3 += x * y3; p4 += x * y4
          if (f[8] > worst) { worst = f[8]; wn = f[2] }
        }
        den = n * sxx - sx * sx
        if (n < 2 || den == 0) exit
        printf "Fitted exponents (%s, N = 128 ... 4096): instructions per simulated second N^%.2f for the library and N^%.2f for the hand-written chain; per right-hand side N^%.2f and N^%.2f (target <= 1.1). Largest ratio %.2f at N = %d (target 1.5).\n",
               last, (n * p1 - sx * s1) / den, (n * p2 - sx * s2) / den, (n * p3 - sx * s3) / den,
               (n * p4 - sx * s4) / den, worst, wn
      }' "$dir/min_ir.csv"
    echo
  fi
} >"$out"

if [[ -f $doc ]] && grep -q '<!-- dae:begin -->' "$doc"; then
  awk -v f="$out" '
    /<!-- dae:begin -->/ { print; while ((getline l < f) > 0) print l; skip = 1; next }
    /<!-- dae:end -->/ { skip = 0 }
    !skip' "$doc" >"$doc.tmp" && mv "$doc.tmp" "$doc"
  echo "dae_report: tables written into $doc" >&2
else
  echo "dae_report: $out written ($doc has no dae markers)" >&2
fi
