# white_balance.gp - the colour error left by each white balance of app. J:
# a colour chart lit by illuminant A, carried to D65 by XYZ scaling, von
# Kries or Bradford, against the same chart in daylight, as the mean and
# the largest CIE 1976 Delta E*ab over its 24 patches (about 2.3 is a just
# noticeable difference). Reads OUTDIR/ch02_white_balance.csv
# (chapters/ch02/ch02_colour.c).
#   gnuplot -c chapters/ch02/white_balance.gp OUTDIR [png|svg]
W = 800; H = 480
call "chapters/figure.gp" ARG1 ARG2

set output fig("ch02_white_balance")
set title "White balance from illuminant A to D65: colour error against daylight (24 patches)"
set ylabel "ΔE*_{ab} (CIE 1976)"
set logscale y
set yrange [1:100]
set format y "%g"
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set boxwidth 0.9
set key left top
set grid ytics mytics
plot csv("ch02_white_balance.csv") skip 2 using 2:xtic(1) lt 3 title "mean", \
     "" skip 2 using 3 lt 4 title "largest"
