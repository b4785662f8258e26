set terminal pngcairo size 900,600 font ',11'
set output 'docs/img/sweep_bead.png'
set datafile separator ','
set key top left
set grid
set title 'Bead on a rotating ring: equilibria over the rate (one compiled system, sweep of long damped runs)'
set xlabel 'w / w_c   (w_c = sqrt(g/R))'
set ylabel 'settled theta (rad)'
set xrange [0:2.5]
set yrange [-1.7:1.7]
set samples 4000
wc = 3.1320919526731652
th(x) = acos(1.0 / (x * x))
set arrow from 1, graph 0 to 1, graph 1 nohead dt 3 lc rgb 'gray50'
plot (x > 1 ? th(x) : 1/0) w l lw 2 lc rgb '#1f77b4' t 'closed form cos(theta*) = g/(R w^2), stable', \
     (x > 1 ? -th(x) : 1/0) w l lw 2 lc rgb '#1f77b4' notitle, \
     (x <= 1 ? 0 : 1/0) w l lw 2 lc rgb '#2ca02c' t 'theta = 0, stable (w < w_c)', \
     (x > 1 ? 0 : 1/0) w l lw 2 dt 2 lc rgb '#d62728' t 'theta = 0, unstable (w > w_c)', \
     'docs/img/sweep_bead_chart.csv' u ($3 > 0 ? $2 / wc : 1/0):5 every ::1 w p pt 7 ps 0.7 lc rgb 'black' t 'sweep, start theta = +0.05', \
     'docs/img/sweep_bead_chart.csv' u ($3 < 0 ? $2 / wc : 1/0):5 every ::1 w p pt 6 ps 1.0 lc rgb '#ff7f0e' t 'sweep, start theta = -0.05'
