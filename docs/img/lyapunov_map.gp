set terminal pngcairo size 950,700 font ',11'
set output 'docs/img/lyapunov_map.png'
set datafile separator ','
set title "Driven damped pendulum (b = 0.5): largest Lyapunov exponent\nsupport x = a cos(w t); two-trajectory estimate, T = 400 after a transient of 100"
set xlabel 'drive frequency w (units of the small-oscillation frequency)'
set ylabel 'drive amplitude a (units of l)'
set cblabel 'lambda'
set xrange [0.3:1.5]
set yrange [0:3]
set palette defined (-0.3 '#08306b', -0.1 '#6baed6', 0 '#f7f7f7', 0.1 '#fc9272', 0.3 '#a50f15')
set cbrange [-0.3:0.3]
set view map
set key bottom left opaque box
plot 'docs/img/lyapunov_map.csv' u 3:2:5 every ::1 w image notitle, \
     'docs/img/lyapunov_map.csv' u 3:($5 > 0.01 ? $2 : 1/0) every ::1 w p pt 7 ps 0.3 lc rgb 'black' t 'lambda > 0.01 (chaotic)'
