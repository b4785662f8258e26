# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Charts of dal_bench_symplectic's CSV files (PNG, and SVG beside each).
# Usage: gnuplot -e "dir='bench/results'" bench/symplectic.gp

if (!exists("dir")) dir = "bench/results"
set datafile separator ","
set datafile missing "nan"
set grid lw 0.5 lc rgb "#dddddd"
set border lw 0.8
set key below font ",9" spacing 1.0 samplen 3 width 1

mcolor(m) = m eq "variational" ? 0xd62728 : m eq "variational4" ? 0xff7f0e : \
            m eq "variational6" ? 0x8c564b : m eq "rattle" ? 0xd62728 : m eq "rattle4" ? 0xff7f0e : \
            m eq "rattle6" ? 0x8c564b : m eq "dopri5" ? 0x1f77b4 : m eq "bs" ? 0x2ca02c : \
            m eq "bs-proj" ? 0x2ca02c : m eq "bdf-ggl" ? 0x9467bd : m eq "bdf" ? 0x9467bd : 0x7f7f7f
fcolor(f) = f eq "symplectic" ? 0xd62728 : f eq "dopri5" ? 0x1f77b4 : f eq "bs" ? 0x2ca02c : \
            f eq "bs-proj" ? 0x2ca02c : f eq "bdf-ggl" ? 0x9467bd : 0x7f7f7f
distinct(expr, f) = system("awk -F, 'NR>1 {print ".expr."}' ".f." | awk '!c[$0]++' | tr '\\n' ' '")
rows(cond, f) = "< awk -F, 'NR>1 && ".cond."' ".f

do for [fmt in "png svg"] {
  ext = fmt eq "png" ? ".png" : ".svg"
  if (fmt eq "png") { set terminal pngcairo size 1200,900 font ",10" noenhanced } else { set terminal svg size 1200,900 font ",10" noenhanced }

  # 1. invariant error (running maximum) against time, four scenes
  f = dir."/sym_longrun.csv"
  set output dir."/sym_energy".ext
  set multiplot layout 2,2 title "invariant error against time: symplectic (bounded) vs adaptive at matched cost"
  set logscale xy
  set format y "%.0e"
  set xlabel "time (periods)"
  set ylabel "max |invariant error| / (m g l)"
  do for [sc in "pendulum ring ring_cartesian double_cartesian"] {
    set title sc.(sc eq "ring" ? " (Jacobi integral h)" : sc eq "ring_cartesian" ? " (E - w Lz, RATTLE)" : " (energy)")
    ms = distinct("($1==\"".sc."\" ? $2 : \"\")", f)
    plot for [m in ms] rows("$1==\"".sc."\" && $2==\"".m."\"", f) u 5:7 w l lw 1.6 lc rgb mcolor(m) \
         t sprintf("%s %s", m, system("awk -F, 'NR>1 && $1==\"".sc."\" && $2==\"".m."\" {p=$3} END {print p}' ".f))
  }
  unset multiplot

  # 2. phase error of the pendulum: t (symplectic) against t^2 (adaptive)
  set output dir."/sym_phase".ext
  set multiplot layout 1,1
  set title "pendulum (120 deg): theta error against time, slopes 1 and 2 for reference"
  set ylabel "max |theta error| (rad)"
  ms = distinct("($1==\"pendulum\" ? $2 : \"\")", f)
  plot for [m in ms] rows("$1==\"pendulum\" && $2==\"".m."\"", f) u 5:9 w l lw 1.6 lc rgb mcolor(m) t m, \
       1e-6*x w l dt 2 lc rgb "#888888" t "~ t", 1e-9*x*x w l dt 3 lc rgb "#444444" t "~ t^2"
  unset multiplot

  # 3. cost of reaching a target accuracy against the horizon (crossover), target 1e-6
  g = dir."/sym_crosscost.csv"
  set output dir."/sym_crossover".ext
  set multiplot layout 2,2 title "CPU time to keep the invariant error below 1e-6 up to a horizon (dashed: extrapolated)"
  set xlabel "horizon (periods)"
  set ylabel "CPU seconds (cheapest configuration)"
  do for [sc in "pendulum ring ring_cartesian double_cartesian"] {
    set title sc
    fs = distinct("($1==\"".sc."\" ? $3 : \"\")", g)
    plot for [fa in fs] rows("$1==\"".sc."\" && $2==\"1e-06\" && $3==\"".fa."\" && $6==0", g) u 4:5 \
           w l lw 2 lc rgb fcolor(fa) t fa, \
         for [fa in fs] rows("$1==\"".sc."\" && $2==\"1e-06\" && $3==\"".fa."\" && $6==1", g) u 4:5 \
           w l lw 1.5 dt 2 lc rgb fcolor(fa) notitle
  }
  unset multiplot

  # 4. failures: stiff spring, drive, near-separatrix orbit
  set output dir."/sym_failures".ext
  set multiplot layout 2,2 title "where the symplectic methods fail"
  s = dir."/sym_stiff.csv"
  set title "stiff spring (w_fast = 100): error of the slow mass at t = 20 (crosses at 1e2: blew up)"
  set xlabel "CPU seconds"
  set ylabel "|x1 error|"
  ms = distinct("$1", s)
  scol(m) = m eq "rattle" ? 0xd62728 : m eq "variational" ? 0xff7f0e : mcolor(m)
  plot for [m in ms] rows("$1==\"".m."\" && $6==\"ok\"", s) u 3:5 w p pt 7 ps 1.0 lc rgb scol(m) t m, \
       for [m in ms] rows("$1==\"".m."\" && $6!=\"ok\"", s) u 3:(1e2) w p pt 2 ps 1.5 lc rgb scol(m) notitle
  d = dir."/sym_drive.csv"
  set title "driven pendulum (energy input): |theta error| against t"
  set xlabel "t (s)"
  set ylabel "|theta error| (rad)"
  unset logscale x
  ms = distinct("$1", d)
  plot for [m in ms] rows("$1==\"".m."\"", d) u 3:4 w l lw 1.4 lc rgb mcolor(m) t m
  p = dir."/sym_separatrix.csv"
  set title "near-separatrix pendulum: theta(t), variational h = 0.05 and 0.2 vs exact"
  set ylabel "theta (rad)"
  unset logscale y
  set format y "%g"
  plot rows("$1==\"variational\" && $2==0.2", p) u 3:4 w l lw 1.2 lc rgb "#ff7f0e" t "variational h = 0.2", \
       rows("$1==\"variational\" && $2==0.05", p) u 3:4 w l lw 1.4 lc rgb mcolor("variational") t "variational h = 0.05", \
       rows("$1==\"variational\" && $2==0.05", p) u 3:5 w l lw 1.4 dt 2 lc rgb "#000000" t "exact"
  r = dir."/sym_rounding.csv"
  set title "round-off of RK4 on q'' = -q against the same recurrence in long double"
  set logscale xy
  set format y "%.0e"
  set xlabel "steps N"
  set ylabel "RMS error"
  plot for [h in "0.001 0.01 0.1"] rows("$1==\"compensated\" && $2==".h, r) u 3:4 w lp pt 7 ps 0.7 \
         lc rgb (h eq "0.001" ? "#d62728" : h eq "0.01" ? "#ff7f0e" : "#8c564b") t "compensated h = ".h, \
       for [h in "0.001 0.01 0.1"] rows("$1==\"uncompensated\" && $2==".h, r) u 3:4 w lp pt 5 ps 0.7 dt 2 \
         lc rgb (h eq "0.001" ? "#1f77b4" : h eq "0.01" ? "#17becf" : "#9467bd") t "uncompensated h = ".h, \
       1e-17*sqrt(x) w l dt 3 lc rgb "#888888" t "~ sqrt(N)", 1e-19*x w l dt 4 lc rgb "#444444" t "~ N"
  unset multiplot
  unset logscale
}
