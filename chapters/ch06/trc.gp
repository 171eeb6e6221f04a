# trc.gp - the histogram adjustment of Ward Larson, Rushmeier and Piatko
# (1997) on ch06's HDR room: above, the tone reproduction curve, display
# luminance Ld against world luminance Lw on log-log axes, with the linear
# ceiling and without it (naive histogram equalisation), beside lines of
# slope 1 (the contrast of a linear map, which the adjusted curve never
# exceeds); below, on the same Lw axis, the histogram of the image's
# foveal luminances before and after the ceiling trimmed it. Reads
# OUTDIR/ch06_trc_curve.csv and OUTDIR/ch06_trc_bins.csv
# (chapters/ch06/ch06_display.c).
#   gnuplot -c chapters/ch06/trc.gp OUTDIR [png|svg]
W = 900; H = 820
call "chapters/figure.gp" ARG1 ARG2

fc = csv("ch06_trc_curve.csv")
fb = csv("ch06_trc_bins.csv")
stats fc skip 2 using 1 nooutput
lw_lo = STATS_min; lw_hi = STATS_max
stats fb skip 3 using 4 nooutput
top = STATS_max
ceiling = real(system("sed -n 's/^# ceiling \\([0-9.e+-]*\\).*/\\1/p' " . fb))
set output fig("ch06_trc")
set multiplot layout 2, 1 title "Histogram adjustment (Ward Larson et al. 1997): the tone reproduction curve of ch06's room"
set lmargin 12
set logscale x
set format x "10^{%L}"
set xrange [lw_lo:lw_hi]
set xlabel "world luminance L_w (W m^{-2} sr^{-1}, foveal average)"
set title "display luminance against world luminance"
set logscale y
set format y "%g"
set ylabel "display luminance L_d (cd/m^2)"
set yrange [0.7:150]
set key right bottom opaque
plot fc skip 2 using 1:2 with lines lt 3 lw 2.5 title "histogram adjustment (linear ceiling)", \
     "" skip 2 using 1:4 with lines lt 1 title "naive histogram equalisation", \
     for [k = -2:3] 10**k * x with lines lc rgb "#aaaaaa" dt 3 notitle, \
     NaN with lines lc rgb "#aaaaaa" dt 3 title "slope 1 (a linear map)"
unset logscale y
set format y "%g"
set title "histogram of ln L_w: counts per bin"
set ylabel "pixels (foveal blocks) per bin"
set yrange [0:top * 1.05]
set style fill solid 0.6 noborder
plot fb skip 3 using (sqrt($2 * $3)):($4 / 2):2:3:(0):4 with boxxyerror fs solid 0.35 lc rgb "#1e3cc8" title "before the ceiling", \
     "" skip 3 using (sqrt($2 * $3)):($5 / 2):2:3:(0):5 with boxxyerror fs solid 0.8 lc rgb "#1e3cc8" title "after the ceiling", \
     ceiling with lines lc rgb "#c81e1e" dt 2 lw 2 title sprintf("ceiling: %.0f per bin", ceiling)
unset multiplot
