# plot-converge.gp - the log-log plot of error against render time of one or
# more convergence series (CSV files of `svet converge`, format in
# include/stats/converge.h). `svet converge` runs it when gnuplot is installed;
# by hand:
#   gnuplot -e "files='out/converge/a.csv out/converge/b.csv'; out='plot.png'" \
#           tools/plot-converge.gp
# Variables: files (CSV paths separated by blanks; required), out (the PNG;
# required), titles (one word per file; default: the file names without
# .csv), ttl (the plot's title; default none), metric ("rel", the default,
# or "abs"), clock ("wall", the default, or "cpu": the series were timed
# by `svet converge --clock cpu` and their time column is cpu_seconds).
# Plotted against the time column: relrmse_noref, the relative RMSE
# (sqrt of the relative MSE, each value's error over sqrt(b^2 + 0.01)), or
# with metric='abs' rmse_noref, the RMSE; both with the reference's own
# noise taken out. The dashed line falls as 1/sqrt(t), the rate of an
# unbiased Monte Carlo estimate, through the last point of the first file:
# a series that bends away from it toward a floor is biased.

if (!exists("files") || !exists("out")) {
    print "plot-converge.gp: set files='a.csv ...' and out='plot.png' with -e"
    exit status 1
}
basename(s) = strstrt(s, "/") == 0 ? s : basename(s[strstrt(s, "/") + 1:])
stem(s) = strlen(s) > 4 && s[strlen(s) - 3:] eq ".csv" ? s[1:strlen(s) - 4] : s
title_of(i) = exists("titles") && words(titles) >= i ? word(titles, i) \
              : stem(basename(word(files, i)))

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
    set terminal pngcairo size 800,560 font ",10"
} else {
    set terminal png size 800,560
}
set output out
set datafile separator comma
set logscale xy
set format y "%g"
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
abs = exists("metric") && metric eq "abs"
col = abs ? "rmse_noref" : "relrmse_noref"
cpu = exists("clock") && clock eq "cpu"
secs = cpu ? "cpu_seconds" : "seconds"
set xlabel (cpu ? "render time (CPU-seconds, all threads)" : "render time (s)")
set ylabel (abs ? "RMSE" : "relative RMSE") . \
           " against the reference (its noise removed)"
set key outside right top noenhanced
if (exists("ttl")) { set title ttl noenhanced }

# the 1/sqrt(t) guide through the last (longest) point of the first series
first = word(files, 1)
stats first using secs nooutput
t_last = STATS_max
stats first using (column(secs) == t_last ? column(col) : NaN) nooutput
e_last = STATS_max
guide(t) = e_last * sqrt(t_last / t)

# gnuplot cycles 8 colours: series 9 to 16 are dashed, each with its own
# point type
plot for [i = 1:words(files)] word(files, i) using secs:col \
         with linespoints lc i dashtype 1 + (i - 1) / 8 \
         pointtype ((i - 1) % 13 + 1) pointsize 0.8 linewidth 1.5 \
         title title_of(i), \
     guide(x) with lines dt 3 lw 1.5 lc rgb "#444444" title "1/sqrt(t)"
