#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The viewer's cost (a benchmark, not a timed test): `dalembert view` of the driven pendulum over
# 100 s at 60 frames per second, of chains of N particles (parent placements by formulas) over
# 100 s at 60 fps, and 10^4 frames of 10 particles (the 2-D chain and ten 3-D spherical
# pendulums, 166.65 s at 60 fps): wall time, page size, bytes per frame and particle.
# Usage: bench/view.sh DALEMBERT OUT.csv
set -euo pipefail
cli=$1
out=$2
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "scene,particles,dim,t1,fps,frames,bytes,seconds,bytes_per_frame_particle" > "$out"
row() { # name particles dim t1 fps scene
  local t0 t1 bytes frames
  t0=$(date +%s.%N)
  "$cli" view "$6" -o "$work/page.html" --t1 "$4" --fps "$5" 2> /dev/null
  t1=$(date +%s.%N)
  bytes=$(stat -c %s "$work/page.html")
  frames=$(awk -v a="$4" -v f="$5" 'BEGIN { printf "%d", a * f + 1 }')
  awk -v n="$1" -v p="$2" -v d="$3" -v T="$4" -v f="$5" -v fr="$frames" -v b="$bytes" \
    -v s0="$t0" -v s1="$t1" 'BEGIN { printf "%s,%d,%d,%g,%g,%d,%d,%.3f,%.2f\n", n, p, d, T, f,
    fr, b, s1 - s0, b / (fr * p) }' >> "$out"
}
row driven_pendulum 1 2 100 60 "$here/../examples/scenes/driven_pendulum.scene"
row bead_ring_above 1 3 100 60 "$here/../examples/scenes/bead_ring_above.scene"
# 10^4 frames of 10 particles in 3-D: ten spherical pendulums in formulas, each on a circle whose
# plane turns (the most the page stores per particle: its place, its circle's centre and tangent)
s="$work/spherical10.scene"
{
  echo "dim 3"
  for ((i = 0; i < 10; ++i)); do
    echo "coord th$i q=1 v=0"
    echo "coord ph$i q=0 v=$((2 + i % 3))"
    echo "particle p$i mass=1"
    echo "place p$i = $i*1.5 + sin(th$i)*cos(ph$i); sin(th$i)*sin(ph$i); -cos(th$i)"
  done
  echo "gravity 0 0 -9.81"
  echo "run method=dopri5 rtol=1e-8 t1=100 dt=0.01"
} > "$s"
row spherical10 10 3 166.65 60 "$s"
for n in 2 5 10 20; do # a chain of n pendulums in formulas, released from 1 rad
  s="$work/chain$n.scene"
  {
    echo "dim 2"
    echo "param g = 9.81"
    for ((i = 0; i < n; ++i)); do echo "coord th$i q=1 v=0"; echo "particle p$i mass=1"; done
    echo "place p0 = sin(th0); -cos(th0)"
    for ((i = 1; i < n; ++i)); do
      echo "place p$i parent=p$((i - 1)) = x_p$((i - 1)) + sin(th$i); y_p$((i - 1)) - cos(th$i)"
    done
    echo "gravity 0 -g"
    echo "run method=dopri5 rtol=1e-8 t1=100 dt=0.01"
  } > "$s"
  row "chain$n" "$n" 2 100 60 "$s"
  [ "$n" = 10 ] && row chain10 10 2 166.65 60 "$s" # 10^4 frames
done
column -s, -t < "$out"
