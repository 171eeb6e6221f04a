# grazing.gp - a checkerboard plane toward its horizon, one lookup a pixel
# by each mip-map filter (Williams 1983): the RMS error of each image row
# against 16 x 16 bilinear samples a pixel, rows counted from the top of
# the image (the horizon) down (nearer the eye). Reads
# OUTDIR/ch10_grazing.csv (chapters/ch10/ch10_textures.c).
#   gnuplot -c chapters/ch10/grazing.gp OUTDIR [png|svg]
W = 900; H = 500
call "chapters/figure.gp" ARG1 ARG2

f = csv("ch10_grazing.csv")
set output fig("ch10_grazing")
set title "The grazing checkerboard: one lookup a pixel against a supersampled reference"
set xlabel "image row (0: the top, toward the horizon; 63: nearest the eye)"
set ylabel "RMS error of the row (texture value)"
set key right top
plot f skip 2 using 1:2 with lines lt 1 lw 2 title "nearest texel", \
     "" skip 2 using 1:3 with lines lt 2 lw 2 title "bilinear", \
     "" skip 2 using 1:4 with lines lt 3 lw 2 title "trilinear (mip map)"
