# error.gp - Monte Carlo error against the number of samples N on log-log
# axes, for the two integrals of ch04_montecarlo (the irradiance integral
# and int_0^pi sin x dx), one line per sampling method, beside the N^-1/2
# of plain Monte Carlo and the N^-1 and N^-1.5 of stratification. A
# method whose error is at the bottom of the plot is exact to rounding
# (its pdf is proportional to the integrand). Reads OUTDIR/ch04_irradiance.csv
# and OUTDIR/ch04_sine.csv (chapters/ch04/ch04_montecarlo.c).
#   gnuplot -c chapters/ch04/error.gp OUTDIR [png|svg]
W = 1100; H = 600
call "chapters/figure.gp" ARG1 ARG2

set output fig("ch04_error")
set multiplot layout 1, 2 title "Monte Carlo integration: RMS error over independent runs against the number of samples N"
set logscale xy
set format x "4^{%L}"
set logscale x 4
set format y "10^{%L}"
set xlabel "samples N" offset 0, 0.5
set bmargin 8
set ylabel "RMS error (units of the integral)"
set key below maxrows 3 samplen 2 noenhanced
set yrange [1e-10:10]
set title "irradiance ∫_H cos^4θ dω = 2π/5 (radiance cos^3θ)" enhanced
f = csv("ch04_irradiance.csv")
stats f skip 2 using 2 nooutput
u1 = STATS_max
plot for [c = 2:6] f skip 1 using 1:(column(c) > 0 ? column(c) : NaN) \
         with linespoints lt c - 1 pt 7 ps 0.6 title columnhead(c), \
     u1 / sqrt(x) with lines lc rgb "#555555" dt 2 lw 1.5 title "N^-1/2", \
     u1 / x with lines lc rgb "#555555" dt 3 lw 2 title "N^-1"
set title "∫_0^π sin x dx = 2" enhanced
f = csv("ch04_sine.csv")
stats f skip 2 using 2 nooutput
u1 = STATS_max
plot for [c = 2:5] f skip 1 using 1:(column(c) > 0 ? column(c) : NaN) \
         with linespoints lt c - 1 pt 7 ps 0.6 title columnhead(c), \
     u1 / sqrt(x) with lines lc rgb "#555555" dt 2 lw 1.5 title "N^-1/2", \
     u1 / x**1.5 with lines lc rgb "#555555" dt 3 lw 2 title "N^-1.5"
unset multiplot
