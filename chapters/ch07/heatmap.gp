# heatmap.gp - where a ray's time goes in the grids of ch. 7: for each
# scene, the number of cells that the camera ray of each pixel visits in
# the uniform grid and in the hierarchical grid (every level counted), on
# one logarithmic colour scale per scene so that the two compare; the
# colours are those of ch07_grids' PPM heat maps. Reads
# OUTDIR/ch07_{spheres,stadium}_{grid,hgrid}_cells.csv
# (chapters/ch07/ch07_grids.c).
#   gnuplot -c chapters/ch07/heatmap.gp OUTDIR [png|svg]
W = 1100; H = 900
call "chapters/figure.gp" ARG1 ARG2

set output fig("ch07_heatmap")
set multiplot layout 2, 2 title "Cells visited per camera ray (the walk of Amanatides and Woo), uniform grid against hierarchical grid"
set palette defined (0 "black", 1 "#590d8c", 2 "#e62633", 3 "#ffcc1a", 4 "white")
set logscale cb
set cblabel "cells visited per ray (log scale)"
set cbtics ("0" 1, "1" 2, "3" 4, "10" 11, "30" 31, "100" 101, "300" 301, "1000" 1001)
set size ratio -1
unset xtics
unset ytics
unset grid
unset key
set yrange [*:*] reverse
array title_of[2] = ["5 × 5 × 5 UV spheres (1e5 triangles)", "the teapot in a stadium (1e5 triangles)"]
do for [s = 1:2] {
    scene = word("spheres stadium", s)
    cmax = 1
    do for [k in "grid hgrid"] {
        stats csv("ch07_" . scene . "_" . k . "_cells.csv") matrix using 3 nooutput
        cmax = STATS_max > cmax ? STATS_max : cmax
    }
    set cbrange [1:cmax + 1]
    do for [k in "grid hgrid"] {
        set title title_of[s] . ": " . (k eq "grid" ? "uniform grid" : "hierarchical grid")
        plot csv("ch07_" . scene . "_" . k . "_cells.csv") matrix using 1:2:($3 + 1) with image
    }
}
unset multiplot
