# noise.gp - Perlin's improved noise (Perlin 2002) along the line
# (x, 0.5, 0.3): its value, its analytic derivative d/dx
# (noise_perlin_grad) and a central difference of step 1e-3 drawn over it;
# the value is zero where x is an integer only on the lattice, not here.
# Reads OUTDIR/ch10_noise.csv (chapters/ch10/ch10_textures.c).
#   gnuplot -c chapters/ch10/noise.gp OUTDIR [png|svg]
W = 900; H = 500
call "chapters/figure.gp" ARG1 ARG2

f = csv("ch10_noise.csv")
set output fig("ch10_noise")
set title "Improved noise along (x, 0.5, 0.3) and its derivative"
set xlabel "x (lattice cells)"
set ylabel "value"
set key right top
plot f skip 2 using 1:2 with lines lt 1 lw 2 title "noise", \
     "" skip 2 using 1:3 with lines lt 2 lw 2 title "d noise / dx, analytic", \
     "" skip 2 using 1:4 with points lt 3 pt 7 ps 0.3 title "central difference"
