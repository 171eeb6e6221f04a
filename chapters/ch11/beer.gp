# beer.gp - ch11_media's Beer-Lambert plot: the transmittance through a
# medium of sigma_t = (0.5, 1, 2) against the distance d, per channel,
# exact exp(-sigma_t d) as lines and the mean of ratio-tracking estimates
# (a majorant twice sigma_t) as points with their standard errors. Reads
# OUTDIR/beer.csv (chapters/ch11/ch11_media.c).
#   gnuplot -c chapters/ch11/beer.gp OUTDIR [png|svg]
W = 800; H = 520
call "chapters/figure.gp" ARG1 ARG2

f = csv("beer.csv")
set output fig("ch11_beer")
set title "Beer-Lambert: exact (lines) and ratio tracking (points)"
set xlabel "distance d"
set ylabel "transmittance"
set logscale y
set key top right
plot f skip 2 using 1:2 with lines lt 1 title "exp(-0.5 d)", \
     f skip 2 using 1:3 with lines lt 2 title "exp(-d)", \
     f skip 2 using 1:4 with lines lt 3 title "exp(-2 d)", \
     f skip 2 using 1:5:8 with yerrorbars lt 1 pt 7 ps 0.6 notitle, \
     f skip 2 using 1:6:9 with yerrorbars lt 2 pt 7 ps 0.6 notitle, \
     f skip 2 using 1:7:10 with yerrorbars lt 3 pt 7 ps 0.6 notitle
