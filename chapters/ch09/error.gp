# error.gp - ch09_irradiance's table: the cache's relative RMS difference
# from the path tracer against Ward's accuracy a, with and without app.
# E's gradients, and the records each a took. Reads OUTDIR/error.csv
# (chapters/ch09/ch09_irradiance.c).
#   gnuplot -c chapters/ch09/error.gp OUTDIR [png|svg]
W = 1100; H = 520
call "chapters/figure.gp" ARG1 ARG2

f = csv("error.csv")
set output fig("ch09_error")
set multiplot layout 1, 2 title "The irradiance cache on the Cornell box against the path tracer"
set logscale x
set xlabel "Ward's accuracy a"
set key top left
set title "relative RMS difference from the path tracer"
plot f skip 2 using 1:3 with linespoints pt 7 title "with gradients", \
     f skip 2 using 1:5 with linespoints pt 5 title "without gradients"
set logscale y
set title "records in the cache"
plot f skip 2 using 1:2 with linespoints pt 7 title "with gradients", \
     f skip 2 using 1:4 with linespoints pt 5 title "without gradients"
unset multiplot
