set terminal pngcairo size 950,640 font ',11'
set output 'docs/img/sweep_bead.png'
set datafile separator ','
set key inside bottom left opaque box
set grid
set title "Bead on a ring turning at rate w (R = 1, g = 9.81): equilibria and their stability\none compiled system, 250 rates, dal\\_equilibrium + dal\\_normal\\_modes per rate; pitchfork at w_c = sqrt(g/R) = 3.132 rad/s"
set xlabel 'ring rate w (rad/s)'
set ylabel 'equilibrium angle theta from the bottom (rad)'
set xrange [0:7.83023]
set yrange [-3.5:3.8]
set ytics ('-pi' -pi, '-pi/2' -pi/2, '0' 0, 'pi/2' pi/2, 'pi' pi)
set samples 3000
wc = 3.1320919526731652
th(x) = acos(wc * wc / (x * x))
set arrow from wc, graph 0 to wc, graph 1 nohead dt 3 lw 1.5 lc rgb 'gray40'
set label 'w_c = sqrt(g/R)' at wc, 3.55 offset 0.6, 0 tc rgb 'gray30'
plot (x > wc ? th(x) : 1/0) w l lw 1 lc rgb 'black' t 'closed form cos(theta*) = g/(R w^2)', \
     (x > wc ? -th(x) : 1/0) w l lw 1 lc rgb 'black' notitle, \
     'docs/img/sweep_bead_chart.csv' u 1:($3 == 1 ? $2 : 1/0) every ::1 w p pt 7 ps 0.55 lc rgb '#1f77b4' t 'stable (neutral: Omega^2 > 0)', \
     'docs/img/sweep_bead_chart.csv' u 1:($3 == 0 ? $2 : 1/0) every ::1 w p pt 6 ps 0.6 lc rgb '#d62728' t 'unstable (Omega^2 < 0)'
