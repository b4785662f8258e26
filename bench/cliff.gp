# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The cliff sweep (bench/cliff.sh): instructions per step and link against N.
# Usage: gnuplot -e "dir='bench/results'" bench/cliff.gp
if (!exists("dir")) dir = 'bench/results'
set datafile separator ','
set logscale xy
set xlabel 'links N'
set ylabel 'instructions per step and link'
set key outside right
set grid
forms = "ode index1-proj index1-baumgarte ggl index1 index3"
plot_cmd = "plot for [f in forms] dir.'/cliff.csv' using ((strcol(2) eq f) ? $4 : NaN):($10 / $4) with linespoints title f"
set terminal pngcairo size 900,540
set output dir.'/cliff.png'
set title 'N-link chain: cost per step and link, every formulation (callgrind)'
eval plot_cmd
set terminal svg size 900,540
set output dir.'/cliff.svg'
eval plot_cmd
