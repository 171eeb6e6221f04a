# chromaticity.gp - the CIE 1931 xy chromaticity diagram: the spectral
# locus filled with its colours (as near as sRGB can show them) and marked
# in nanometres, the sRGB gamut, the Planckian locus in kelvin and the
# white points of app. J. Reads OUTDIR/ch02_{fill,locus,planck,points,gamut}.csv
# (chapters/ch02/ch02_colour.c).
#   gnuplot -c chapters/ch02/chromaticity.gp OUTDIR [png|svg]
W = 760; H = 800
call "chapters/figure.gp" ARG1 ARG2

set output fig("ch02_chromaticity")
set title "CIE 1931 chromaticity diagram (2° observer)"
set xlabel "x"
set ylabel "y"
set size ratio -1
set xrange [0:0.8]
set yrange [0:0.9]
set xtics 0, 0.1, 0.8
set ytics 0, 0.1, 0.9
set mxtics 2
set mytics 2
set grid front lc rgb "#bbbbbb"
set key right top
# the line of purples joins the ends of the drawn locus, 380 and 700 nm
fl = csv("ch02_locus.csv")
do for [c = 2:3] {
    stats fl skip 2 using ($1 == 380 ? column(c) : NaN) nooutput
    if (c == 2) { v_x = STATS_max } else { v_y = STATS_max }
    stats fl skip 2 using ($1 == 700 ? column(c) : NaN) nooutput
    if (c == 2) { r_x = STATS_max } else { r_y = STATS_max }
}
set arrow 1 from v_x, v_y to r_x, r_y nohead lw 1 lc rgb "black" front
# wavelengths marked on the locus, as in the book's figure
marked(l) = (l >= 460 && l <= 620 && int(l) % 10 == 0 && (l <= 600 || l == 620)) || l == 380 || l == 700
# labels pushed outward from the white point E
lx(x, y) = x + 0.035 * (x - 1.0/3) / sqrt((x - 1.0/3)**2 + (y - 1.0/3)**2)
ly(x, y) = y + 0.035 * (y - 1.0/3) / sqrt((x - 1.0/3)**2 + (y - 1.0/3)**2)
plot csv("ch02_fill.csv") skip 2 using 1:2:3:4:5 with rgbimage notitle, \
     csv("ch02_locus.csv") skip 2 using 2:($1 >= 380 && $1 <= 700 ? $3 : NaN) with lines lw 2 lc rgb "black" title "spectral locus (nm)", \
     csv("ch02_locus.csv") skip 2 using (marked($1) ? $2 : NaN):3 with points pt 7 ps 0.6 lc rgb "black" notitle, \
     csv("ch02_locus.csv") skip 2 using (marked($1) ? lx($2, $3) : NaN):(ly($2, $3)):(sprintf("%d", $1)) with labels font ",9" notitle, \
     csv("ch02_gamut.csv") skip 2 using 2:3 with lines lw 2 lc rgb "#222222" title "sRGB gamut", \
     csv("ch02_planck.csv") skip 2 using 2:3 with lines lw 2 lc rgb "#8c2d9b" title "Planckian locus (K)", \
     csv("ch02_planck.csv") skip 2 using ((abs($1 - 1000) < 5 || abs($1 - 1500) < 8 || abs($1 - 2000) < 10 || abs($1 - 3000) < 15 || abs($1 - 10000) < 50) ? $2 : NaN):3:(sprintf("%.0f K", $1 < 1010 ? 1000 : $1 < 1520 ? 1500 : $1 < 2020 ? 2000 : $1 < 3030 ? 3000 : 10000)) with labels point pt 7 ps 0.5 lc rgb "#8c2d9b" offset 0, -1 font ",9" tc rgb "#8c2d9b" notitle, \
     csv("ch02_points.csv") skip 2 every ::3 using 2:3 with points pt 6 ps 1.5 lw 2 lc rgb "black" title "white points", \
     csv("ch02_points.csv") skip 2 every ::3 using (strcol(1) eq "D65" ? $2 - 0.05 : $2 + 0.012):(strcol(1) eq "E" ? $3 - 0.018 : $3 + 0.014):1 with labels left font ",10" notitle
