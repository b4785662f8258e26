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

# the viewers of the seed scenes: one self-contained HTML page each (open in any browser)
cli="$bdir/dalembert"
scenes="$root/examples/scenes"
"$cli" view "$scenes/driven_pendulum.scene" -o "$out/view_driven_pendulum.html"
"$cli" view "$scenes/driven_pendulum.scene" --set thetadot0=1e-10 \
  -o "$out/view_driven_pendulum_1e-10.html"
"$cli" view "$scenes/bead_ring_below.scene" -o "$out/view_bead_below.html"
"$cli" view "$scenes/bead_ring_above.scene" -o "$out/view_bead_above.html"
"$cli" view "$root/tests/view/cart_double_pendulum.scene" -o "$out/view_cart_double_pendulum.html"
# SICM's two driven orbits side by side (each page plays on its own)
cat > "$out/view_driven_pendulum_both.html" << 'EOF'
<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>SICM's two driven orbits</title></head>
<body style="margin:0;display:flex">
<iframe src="view_driven_pendulum.html" style="width:50%;height:100vh;border:0"></iframe>
<iframe src="view_driven_pendulum_1e-10.html" style="width:50%;height:100vh;border:0"></iframe>
</body></html>
EOF
# the driven pendulum's section and the Lyapunov exponents' convergence, as SVG charts
"$cli" section "$scenes/driven_pendulum.scene" --wrap -o "$out/section_driven_pendulum.csv" \
  --chart "$out/section_driven_pendulum.svg"
"$cli" lyapunov "$scenes/driven_pendulum.scene" --chart "$out/lyapunov_driven_pendulum.svg" \
  > "$out/lyapunov_driven_pendulum.csv"

echo
ls -1 "$out"
echo "open a viewer: xdg-open $out/view_driven_pendulum_both.html (SICM's two orbits side by side;"
echo "file://$out/view_driven_pendulum.html#t=1.25 in a browser opens one paused at t = 1.25)"
echo "demo output: $out"
