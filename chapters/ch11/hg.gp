# hg.gp - ch11_media's Henyey-Greenstein lobes in polar form: p(theta) per
# unit solid angle for g = -0.6, 0, 0.3, 0.8 (theta from the direction of
# travel, mirrored below the axis), the exact pdf as lines and a histogram
# of the exact sampler as points; log radius would hide the back lobes,
# so the radius is p^(1/2). Reads OUTDIR/hg.csv
# (chapters/ch11/ch11_media.c).
#   gnuplot -c chapters/ch11/hg.gp OUTDIR [png|svg]
W = 760; H = 620
call "chapters/figure.gp" ARG1 ARG2

f = csv("hg.csv")
set output fig("ch11_hg")
set title "HG lobes: radius sqrt(p(theta)), exact (lines) and sampled (points)"
set size ratio -1
set xlabel "along the direction of travel"
set key top left
r(p) = sqrt(p)
plot for [j = 0:3] f skip 2 using (r(column(2 + 2 * j)) * cos($1)):(r(column(2 + 2 * j)) * sin($1)) \
         with lines lt (j + 1) title "g = " . word("-0.6 0 0.3 0.8", j + 1), \
     for [j = 0:3] f skip 2 using (r(column(2 + 2 * j)) * cos($1)):(-r(column(2 + 2 * j)) * sin($1)) \
         with lines lt (j + 1) notitle, \
     for [j = 0:3] f skip 2 every 3 using (r(column(3 + 2 * j)) * cos($1)):(r(column(3 + 2 * j)) * sin($1)) \
         with points lt (j + 1) pt 7 ps 0.5 notitle
