# bias.gp - ch08_photons's table: the irradiance estimate's relative bias
# and standard deviation against k on log axes, one line per photon count,
# beside the k/(k-1) - 1 = 1/(k-1) of the k-nearest estimate's bias and
# the 1/sqrt(k - 2) of its spread (Poisson photons). Reads OUTDIR/bias.csv
# (chapters/ch08/ch08_photons.c).
#   gnuplot -c chapters/ch08/bias.gp OUTDIR [png|svg]
W = 1100; H = 520
call "chapters/figure.gp" ARG1 ARG2

f = csv("bias.csv")
set output fig("ch08_bias")
set multiplot layout 1, 2 title "The photon map's irradiance estimate under a point light, against E = I h / d^3"
set logscale xy
set xlabel "photons in the estimate k"
set key top right
set title "relative bias |mean / E - 1|"
plot for [n in "10000 100000 1000000"] f skip 2 using \
         (strcol(1) eq n ? $2 : NaN):(abs($3)) with linespoints pt 7 \
         title n . " photons", \
     1 / (x - 1) with lines lc rgb "#555555" dt 2 title "1/(k-1)"
set title "relative standard deviation over the maps"
plot for [n in "10000 100000 1000000"] f skip 2 using \
         (strcol(1) eq n ? $2 : NaN):4 with linespoints pt 7 \
         title n . " photons", \
     1 / sqrt(x - 2) with lines lc rgb "#555555" dt 2 title "1/sqrt(k-2)"
unset multiplot
