# figure.gp - what every chapter's gnuplot script shares: the output
# directory and format from its command line, the terminal, CSV input.
# A script sets W and H (pixels), then `call "chapters/figure.gp" ARG1 ARG2`.
# Every script is run from the top directory as
#   gnuplot -c chapters/chNN/NAME.gp OUTDIR [png|svg]
# reads the CSV files that the chapter's program wrote into OUTDIR and
# writes its figures there (`make figures` runs every script, both formats).
dir = ARGC >= 1 && ARG1 ne "" ? ARG1 : "out"
fmt = ARGC >= 2 && ARG2 ne "" ? ARG2 : "png"
if (!exists("W")) { W = 800 }
if (!exists("H")) { H = 560 }
csv(name) = dir . "/" . name
fig(name) = dir . "/" . name . "." . fmt
if (fmt eq "svg") {
    set terminal svg size W, H dynamic enhanced font "sans,13" background rgb "white"
} else {
    if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
        set terminal pngcairo size W, H enhanced font "sans,11"
    } else {
        set terminal png size W, H
    }
}
set datafile separator comma
set datafile commentschars "#"
set grid lc rgb "#dddddd"
set key box opaque
set linetype 1 lc rgb "#c81e1e" lw 2
set linetype 2 lc rgb "#148228" lw 2
set linetype 3 lc rgb "#1e3cc8" lw 2
set linetype 4 lc rgb "#e68200" lw 2
set linetype 5 lc rgb "#000000" lw 2
set linetype 6 lc rgb "#8c2d9b" lw 2
