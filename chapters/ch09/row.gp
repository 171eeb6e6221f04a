# row.gp - ch09_irradiance's middle row of the Cornell box, green channel:
# the cache with and without app. E's gradients beside the path tracer.
# Reads OUTDIR/row.csv (chapters/ch09/ch09_irradiance.c).
#   gnuplot -c chapters/ch09/row.gp OUTDIR [png|svg]
W = 900; H = 520
call "chapters/figure.gp" ARG1 ARG2

f = csv("row.csv")
set output fig("ch09_row")
set title "The Cornell box's middle row: the irradiance cache against the path tracer"
set xlabel "pixel x"
set ylabel "radiance, green channel (W sr^{-1} m^{-2})"
set key top right
plot f skip 2 using 1:4 with lines lt 3 title "path tracer", \
     f skip 2 using 1:2 with lines lt 1 title "cache, with gradients", \
     f skip 2 using 1:3 with lines lt 2 dt 2 title "cache, without gradients"
