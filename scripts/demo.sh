#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# README command 1: install dependencies, build, run the seed scenes and draw their charts.
# Output folder: $DAL_DEMO_DIR or ./demo-output (named at the end).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/build.sh"
bdir=${DAL_BUILD_DIR:-$root/build}
out=${DAL_DEMO_DIR:-$PWD/demo-output}
mkdir -p "$out"
out=$(cd "$out" && pwd)

# the scenes write their CSVs and gnuplot scripts into $out (and draw when gnuplot exists)
"$bdir/examples/demo" "$out"

# draw any chart still missing from its script
if command -v gnuplot >/dev/null 2>&1; then
  for gp in "$out"/*.gp; do
    [ -e "$gp" ] || continue
    png=${gp%.gp}.png
    [ -s "$png" ] || gnuplot "$gp" || echo "gnuplot failed on $gp"
  done
else
  echo "gnuplot not found: charts skipped (install gnuplot-nox; scripts are in $out)"
fi

echo
ls -1 "$out"
echo "demo output: $out"
