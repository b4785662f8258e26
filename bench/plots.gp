# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Charts of the benchmark CSV files: PNG for the README, SVG beside each (and one SVG per
# work-precision scene). Every curve is read through an awk filter so that its rows are
# contiguous whatever the row order of the file.
# Usage: gnuplot -e "dir='bench/results'" bench/plots.gp

if (!exists("dir")) dir = "bench/results"
set datafile separator ","
set datafile missing "nan"
set grid lw 0.5 lc rgb "#dddddd"
set border lw 0.8
set key below font ",9" spacing 1.0 samplen 3 width 1

methods = "dopri5 fehlberg78 bs rk4 adams bdf"
forms = "ode handwritten ggl index1 index1-baumgarte index1-proj index3"
mcolor(m) = m eq "dopri5" ? 0x1f77b4 : m eq "fehlberg78" ? 0xff7f0e : m eq "bs" ? 0x2ca02c : \
            m eq "rk4" ? 0x7f7f7f : m eq "adams" ? 0xd62728 : m eq "bdf" ? 0x9467bd : 0x000000
fpt(f) = f eq "ode" ? 7 : f eq "handwritten" ? 4 : f eq "ggl" ? 9 : f eq "index1" ? 1 : \
         f eq "index1-baumgarte" ? 2 : f eq "index1-proj" ? 5 : f eq "index3" ? 11 : 6
fdt(f) = f eq "handwritten" ? 2 : f eq "ode" ? 1 : f eq "handwritten-tridiag" ? 3 : 4
fcolor(f) = f eq "ode" ? 0x1f77b4 : f eq "ggl" ? 0x9467bd : f eq "handwritten" ? 0xd62728 : \
            f eq "index1" ? 0xff7f0e : f eq "index1-baumgarte" ? 0x2ca02c : \
            f eq "index1-proj" ? 0x17becf : f eq "index3" ? 0x8c564b : 0x7f7f7f
fof(c) = substr(c, 1, strstrt(c, "/") - 1)
mof(c) = substr(c, strstrt(c, "/") + 1, strlen(c))
exists_file(f) = system("test -s ".f." && echo 1 || echo 0") eq "1"
# distinct values of an awk expression over the data rows of a file
distinct(expr, f) = system("awk -F, 'NR>1 {print ".expr."}' ".f." | awk '!c[$0]++' | tr '\\n' ' '")
# the data rows of a file where an awk condition holds
rows(cond, f) = "< awk -F, 'NR>1 && ".cond."' ".f

png(name) = sprintf("set terminal pngcairo size 900,600 font 'Sans,10'; set output '%s/%s.png'", dir, name)
svg(name) = sprintf("set terminal svg size 900,600 font 'Sans,10' dynamic; set output '%s/%s.svg'", dir, name)

# ------------------------------------------------------------------ work-precision
wp = dir."/work_precision.csv"
scenes = distinct("$1", wp)
combos(s) = system("awk -F, -v s=".s." 'NR>1 && $1==s {print $2\"/\"$3}' ".wp." | awk '!c[$0]++' | tr '\\n' ' '")
# the overview shows the formulations one would run (the minimal ODE, GGL, index-1 with
# projection) and the hand-written reference; every formulation is in the per-scene charts
mainforms = "ode handwritten ggl index1-proj"
combos_main(s) = system("awk -F, -v s=".s." 'NR>1 && $1==s && ($2==\"ode\" || $2==\"handwritten\" || $2==\"ggl\" || $2==\"index1-proj\") {print $2\"/\"$3}' ".wp." | awk '!c[$0]++' | tr '\\n' ' '")
wpsel(s, c) = rows(sprintf("$1==\"%s\" && $2==\"%s\" && $3==\"%s\" && $8+0 > 0", s, fof(c), mof(c)), wp)

set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "wall time per run (s)"
set ylabel "max position error at t1"
# one chart per scene (PNG and SVG), every formulation, with its own legend
do for [s in scenes] {
  cs = combos(s)
  set title "work-precision: ".s." (each point one rtol; legend formulation/method)"
  do for [fmt in "svg png"] {
    if (fmt eq "svg") { eval svg("wp_".s) } else { eval png("wp_".s) }
    plot for [c in cs] wpsel(s, c) using 5:8 with linespoints lw 1.2 ps 0.7 \
         lc rgb mcolor(mof(c)) pt fpt(fof(c)) dt fdt(fof(c)) title c
    set output
  }
}

# all scenes on one page for the README, with one shared legend panel
nsc = words(scenes)
rowsn = (nsc + 1 + 3) / 4
set terminal pngcairo size 1600, 420 * rowsn font 'Sans,10'
set output dir."/wp_all.png"
set multiplot layout rowsn, 4 title "Error at the final time against wall time; each point one rtol. Minimal ODE, GGL, index-1 + projection and the hand-written reference (all formulations: the per-scene charts)" font ",12"
unset key
set xlabel "wall time (s)" offset 0, 0.5
set ylabel "max position error" offset 1.5, 0
do for [s in scenes] {
  cs = combos_main(s)
  set title s
  plot for [c in cs] wpsel(s, c) using 5:8 with linespoints lw 1.1 ps 0.6 \
       lc rgb mcolor(mof(c)) pt fpt(fof(c)) dt fdt(fof(c))
}
# the legend: colour = method, point and dash = formulation
unset border
unset tics
unset grid
unset xlabel
unset ylabel
unset title
unset logscale
set xrange [0:1]
set yrange [0:1]
set key inside center center vertical maxrows 7 font ",10" spacing 1.2 samplen 3 box
plot for [m in methods] NaN with lines lw 2.5 lc rgb mcolor(m) title "method ".m, \
     for [f in mainforms] NaN with linespoints lw 1.2 lc rgb "black" pt fpt(f) dt fdt(f) title f
unset multiplot
set output
set border 31 lw 0.8
set tics
set grid xtics ytics lw 0.5 lc rgb "#dddddd"
set xrange [*:*]
set yrange [*:*]
set key below font ",9" spacing 1.0 samplen 3 width 1 nobox maxrows auto

# ------------------------------------------------------------------ overhead vs hand-written
ov = dir."/overhead.csv"
oi = dir."/overhead_ir.csv"
if (exists_file(ov)) {
  ovm = distinct("$2", ov)
  irm = exists_file(oi) ? distinct("$2", oi) : ""
  set logscale x 2
  unset logscale y
  set format x "%g"
  set format y "%g"
  set yrange [0:*]
  set xlabel "chain links N"
  set ylabel "library / hand-written"
  set title "Library overhead against the hand-written chain (same SUNDIALS integrator, same steps)"
  do for [k = 1:2] {
    if (k == 1) { eval png("overhead") } else { eval svg("overhead") }
    plot for [m in ovm] rows("$2==\"".m."\"", ov) using 1:6 with linespoints lw 1 dt 2 \
         lc rgb mcolor(m) pt 6 title "wall time, ".m, \
         for [m in irm] rows("$2==\"".m."\"", oi) using 1:7 with linespoints lw 2.5 \
         lc rgb mcolor(m) pt 7 title "instructions, ".m, \
         1.3 with lines dt 3 lw 1.5 lc rgb "#555555" title "1.3x target"
    set output
  }
  set yrange [*:*]
}

# ------------------------------------------------------------------ cost growth
cg = dir."/cost_growth.csv"
cf = dir."/cost_fit.csv"
if (exists_file(cg)) {
  cgf = distinct("$1", cg)
  expo(f) = system("awk -F, -v f=".f." '$1==f && $6==16 {printf \"%.2f\", $4}' ".cf)
  meth(f) = system("awk -F, -v f=".f." 'NR>1 && $1==f {printf \"%s, rtol %s\", $2, $4; exit}' ".cg)
  cross = system("awk -F, '$1==\"crossover\" && $2==\"ggl-vs-ode\" {printf \"%.0f\", $4}' ".cf)
  set logscale xy
  set logscale x 2
  set format x "%g"
  set format y "10^{%L}"
  set xlabel "chain links N"
  set ylabel "wall time per simulated second (s)"
  crosstxt = (cross eq "nan" || cross eq "-nan") ? "never cheaper than the ODE" : "cheaper than the ODE from N = ".cross
  set title "Cost growth of the N-link chain (fit over N >= 16; sparse DAE ".crosstxt.")"
  do for [k = 1:2] {
    if (k == 1) { eval png("cost_growth") } else { eval svg("cost_growth") }
    plot for [f in cgf] rows("$1==\"".f."\"", cg) using 3:5 with linespoints lw 1.5 ps 0.8 \
         lc rgb fcolor(f) pt fpt(f) dt fdt(f) title f." (".meth(f)."): exponent ".expo(f)
    set output
  }
}

# ------------------------------------------------------------------ constraint drift
dr = dir."/drift.csv"
if (exists_file(dr)) {
  drf = distinct("$1\"/\"$2", dr)
  unset logscale x
  set logscale y
  set format x "%g"
  set format y "10^{%L}"
  set xlabel "t (s)"
  set ylabel "max |phi| over [0, t] (length units)"
  set title "Constraint drift, Cartesian double pendulum, rtol 1e-6 (a zero is drawn at 1e-17)"
  do for [k = 1:2] {
    if (k == 1) { eval png("drift") } else { eval svg("drift") }
    plot for [c in drf] rows(sprintf("$1==\"%s\" && $2==\"%s\"", fof(c), mof(c)), dr) \
         using 4:($7 > 1e-17 ? $7 : 1e-17) with lines lw 2 lc rgb fcolor(fof(c)) title c
    set output
  }
}

# ------------------------------------------------------------------ energy error
en = dir."/energy.csv"
if (exists_file(en)) {
  enf = distinct("$1\"/\"$2", en)
  unset logscale x
  set logscale y
  set format x "%g"
  set format y "10^{%L}"
  set xlabel "t (s)"
  set ylabel "|E(t) - E(0)| / |E(0)|"
  set title "Energy error of each integrator, double pendulum, rtol 1e-8 (rk4: h = 1e-3)"
  do for [k = 1:2] {
    if (k == 1) { eval png("energy") } else { eval svg("energy") }
    plot for [c in enf] rows(sprintf("$1==\"%s\" && $2==\"%s\" && $5+0 > 0", fof(c), mof(c)), en) \
         using 4:5 with lines lw 1.5 lc rgb mcolor(mof(c)) dt fdt(fof(c)) title c
    set output
  }
}

# ------------------------------------------------------------------ DAE tolerance sweep
dt = dir."/dae_tolerance.csv"
if (exists_file(dt)) {
  dtf = distinct("$1", dt)
  set logscale xy
  set format x "10^{%L}"
  set format y "10^{%L}"
  set xlabel "requested rtol (= atol)"
  set ylabel "max position error at t = 5 s"
  set xrange [*:*] reverse
  set title "IDA (BDF) on the Cartesian double pendulum: achieved error; crosses at 1: the run failed"
  do for [k = 1:2] {
    if (k == 1) { eval png("dae_tolerance") } else { eval svg("dae_tolerance") }
    plot for [f in dtf] rows("$1==\"".f."\" && $4==\"DAL_OK\"", dt) using 3:8 \
           with linespoints lw 1.5 lc rgb fcolor(f) pt fpt(f) title f, \
         for [f in dtf] rows("$1==\"".f."\" && $4!=\"DAL_OK\"", dt) using 3:(1.0) \
           with points ps 2 lw 2 pt 2 lc rgb fcolor(f) title f." failed", \
         x with lines dt 3 lc rgb "#555555" title "error = rtol"
    set output
  }
  set xrange [*:*] noreverse
}

# ------------------------------------------------------------------ stiff spring pendulum
sf = dir."/stiff.csv"
if (exists_file(sf)) {
  sfm = distinct("$2", sf)
  sfr = distinct("$3", sf)
  set logscale xy
  set format x "10^{%L}"
  set format y "10^{%L}"
  set xlabel "spring stiffness k (N/m), unit mass"
  set ylabel "right-hand-side evaluations for t in [0, 1]"
  set title "Explicit vs implicit on a stiff spring pendulum (solid: first rtol, dashed: second; crosses: failed)"
  do for [k = 1:2] {
    if (k == 1) { eval png("stiff") } else { eval svg("stiff") }
    plot for [i = 1:words(sfr)] for [m in sfm] rows(sprintf("$2==\"%s\" && $3==\"%s\" && $4==\"DAL_OK\"", m, word(sfr, i)), sf) \
           using 1:6 with linespoints lw 1.5 pt 7 dt i lc rgb mcolor(m) title m.", rtol ".word(sfr, i), \
         for [m in sfm] rows("$2==\"".m."\" && $4!=\"DAL_OK\"", sf) using 1:6 \
           with points ps 2 lw 2 pt 2 lc rgb mcolor(m) notitle
    set output
  }
}

# ------------------------------------------------------------------ coordinate singularity
sg = dir."/singular.csv"
if (exists_file(sg)) {
  sgr = distinct("$3\"/\"$4", sg)
  set logscale y
  unset logscale x
  set format y "10^{%L}"
  set format x "%g"
  set xlabel "case: initial azimuthal rate phidot0 (theta0 = 60 deg), or a start at the pole"
  set ylabel "right-hand-side evaluations for t in [0, 3]"
  set xtics ("start at pole" 0, "1e-1" 1, "1e-3" 2, "1e-5" 3, "1e-7" 4, "0 (through)" 5)
  set xrange [-0.5:5.5]
  set title "Spherical pendulum at its pole: minimal (theta, phi) vs redundant (x, y, z + rod); crosses: failed"
  do for [k = 1:2] {
    if (k == 1) { eval png("singular") } else { eval svg("singular") }
    plot for [c in sgr] rows(sprintf("$3==\"%s\" && $4==\"%s\" && $6==\"DAL_OK\"", fof(c), mof(c)), sg) \
           using 11:8 with linespoints lw 1.3 pt fpt(fof(c)) lc rgb mcolor(mof(c)) dt fdt(fof(c)) title c, \
         for [c in sgr] rows(sprintf("$3==\"%s\" && $4==\"%s\" && $6!=\"DAL_OK\"", fof(c), mof(c)), sg) \
           using 11:($8 > 0 ? $8 : 1) with points ps 2.5 lw 2 pt 2 lc rgb mcolor(mof(c)) notitle
    set output
  }
}
