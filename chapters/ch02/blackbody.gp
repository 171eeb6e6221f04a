# blackbody.gp - the colour of a blackbody from 1000 K to 12000 K: a strip
# of its colour at full brightness (as ch02_blackbody.ppm's top band) and
# its chromaticity coordinates x, y against the temperature. Reads
# OUTDIR/ch02_blackbody.csv (chapters/ch02/ch02_colour.c).
#   gnuplot -c chapters/ch02/blackbody.gp OUTDIR [png|svg]
W = 900; H = 520
call "chapters/figure.gp" ARG1 ARG2

f = csv("ch02_blackbody.csv")
rgb(r, g, b) = int(r) * 65536 + int(g) * 256 + int(b)
set output fig("ch02_blackbody")
set title "A blackbody's colour and chromaticity against its temperature (Planck; CIE 1931)"
set xlabel "temperature T (K)"
set ylabel "chromaticity coordinate"
set xrange [1000:12000]
set yrange [0:0.8]
set xtics 1000, 1000, 12000
set ytics 0, 0.1, 0.6
set key right center opaque
set style fill solid noborder
set object 1 rect from 1000, 0.65 to 12000, 0.8 fc rgb "#303030" fs solid 1.0 behind
set label 1 "colour at full brightness (sRGB display)" at 1150, 0.775 front tc rgb "white"
plot f skip 2 using 1:(0.705):(25):(0.045):(rgb($4, $5, $6)) with boxxyerror fs solid 1.0 noborder lc rgb variable notitle, \
     "" skip 2 using 1:2 with lines lt 1 title "x", \
     "" skip 2 using 1:3 with lines lt 2 title "y"
