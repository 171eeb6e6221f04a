# roulette.gp - Russian roulette against truncation on the furnace L = Le +
# rho L (rho = 0.8, exact L = 5): the variance of roulette against its
# continuation probability q (measured, and exact: infinite below q =
# rho^2), its efficiency 1 / (variance x vertices per path), and the bias
# that truncation after d bounces pays instead. Reads
# OUTDIR/ch04_roulette.csv (chapters/ch04/ch04_montecarlo.c).
#   gnuplot -c chapters/ch04/roulette.gp OUTDIR [png|svg]
W = 1200; H = 440
call "chapters/figure.gp" ARG1 ARG2

f = csv("ch04_roulette.csv")
roul(c) = strcol(1) eq "roulette" ? column(c) : NaN
trunc(c) = strcol(1) eq "truncate" ? column(c) : NaN
set output fig("ch04_roulette")
set multiplot layout 1, 3 title "Ending a path: Russian roulette against truncation (furnace, ρ = 0.8, exact L = 5)"
set xlabel "continuation probability q"
set xrange [0.55:1]
set key right top
set title "roulette: variance of one path's estimate"
set ylabel "variance"
set logscale y
set format y "%g"
set arrow 1 from 0.64, graph 0 to 0.64, graph 1 nohead dt 3 lc rgb "#777777"
set label 1 "q = ρ^2: infinite\nvariance below" at 0.645, graph 0.12 left font ",9"
plot f skip 2 using (roul(2)):(roul(5)) with linespoints lt 3 pt 7 title "measured", \
     "" skip 2 using (roul(2)):(roul(6) > 0 && roul(6) < 1e300 ? roul(6) : NaN) with linespoints lt 5 dt 2 pt 6 title "exact"
unset logscale y
unset arrow 1
unset label 1
set title "roulette: efficiency 1 / (variance × vertices)"
set ylabel "efficiency"
set autoscale y
plot f skip 2 using (roul(2)):(roul(8)) with linespoints lt 1 pt 7 title "measured"
set title "truncation after d bounces: bias"
set xlabel "bounces d"
set xrange [0:55]
set ylabel "|bias| = ρ^d / (1 - ρ)"
set logscale y
set format y "10^{%L}"
plot f skip 2 using (trunc(2)):(abs(trunc(4))) with linespoints lt 4 pt 7 title "truncation (zero variance)"
unset multiplot
