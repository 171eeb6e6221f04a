# convergence.gp - the estimator of the rendering equation converging for
# one pixel: left, the estimate of L after N paths with one standard error
# as bars; right, the standard error sqrt(Var/N) against N on log-log axes
# beside the 1/sqrt(N) line of ch. 4. Reads OUTDIR/ch03_convergence.csv
# (chapters/ch03/ch03_estimator.c).
#   gnuplot -c chapters/ch03/convergence.gp OUTDIR [png|svg]
W = 1000; H = 460
call "chapters/figure.gp" ARG1 ARG2

f = csv("ch03_convergence.csv")
stats f skip 2 using 1 nooutput
n_last = STATS_max
stats f skip 2 using ($1 == n_last ? $3 : NaN) nooutput
se_last = STATS_max
set output fig("ch03_convergence")
set multiplot layout 1, 2 title "One pixel of the ch. 3 room: the path-tracing estimate against the number of paths N"
set logscale x 2
set format x "2^{%L}"
set xlabel "paths N"
set title "estimate ± 1 standard error"
set ylabel "L, green channel (W m^{-2} sr^{-1})"
set key right top
stats f skip 2 using ($1 >= 64 ? $2 - 2 * $3 : NaN) nooutput
lo = STATS_min
stats f skip 2 using ($1 >= 64 ? $2 + 2 * $3 : NaN) nooutput
set yrange [lo:STATS_max]
plot f skip 2 using 1:2:3 with yerrorlines lt 3 pt 7 ps 0.6 title "estimate after N paths"
set autoscale y
set title "standard error sqrt(Var/N)"
set logscale y
set format y "%g"
set ylabel "standard error (W m^{-2} sr^{-1})"
plot f skip 2 using 1:($3 > 0 ? $3 : NaN) with linespoints lt 1 pt 7 ps 0.6 title "measured", \
     se_last * sqrt(n_last / x) with lines lt 5 dt 2 title "∝ 1/sqrt(N)"
unset multiplot
