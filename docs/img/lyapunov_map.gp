set terminal pngcairo size 950,720 font ',11'
set output 'docs/img/lyapunov_map.png'
set datafile separator ','
set title "Driven damped pendulum: largest Lyapunov exponent (exact tangent dynamics)\nI theta'' = -sin theta + a w^2 cos(w t) cos theta - b theta', b = 0.5, I = 1.001; averaged over t = 400 after 100"
set xlabel 'drive frequency w (rad per time unit; small-oscillation frequency = 1)'
set ylabel 'support amplitude a (units of l)'
set cblabel 'lambda_1 (1 / time unit)'
set xrange [0.3:1.5]
set yrange [0:3]
set palette defined (-0.3 '#08306b', -0.1 '#6baed6', 0 '#f7f7f7', 0.1 '#fc9272', 0.3 '#a50f15')
set cbrange [-0.3:0.3]
set key bottom left opaque box
plot 'docs/img/lyapunov_map.csv' u 3:2:5 every ::1 w image notitle, \
     'docs/img/lyapunov_map.csv' u 3:($5 > 0.01 ? $2 : 1/0) every ::1 w p pt 7 ps 0.3 lc rgb 'black' t 'lambda_1 > 0.01 (chaotic)'
