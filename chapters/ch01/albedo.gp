# albedo.gp - the albedo of each reflection model with rho = 1 against the
# angle theta_o of the outgoing direction: the fraction of light that the
# surface keeps (1: it loses nothing), by Monte Carlo with the lobes' own
# sampling, with one standard error as bars. Reads OUTDIR/ch01_albedo.csv
# (chapters/ch01/ch01_brdf.c); columns model,param,value,theta_deg,albedo,
# stderr.
#   gnuplot -c chapters/ch01/albedo.gp OUTDIR [png|svg]
W = 1000; H = 480
call "chapters/figure.gp" ARG1 ARG2

f = csv("ch01_albedo.csv")
# the albedo of one row of the table (model m, parameter value v), else NaN
sel(m, v) = strcol(1) eq m && abs(column(3) - v) < 1e-9 ? column(5) : NaN
set output fig("ch01_albedo")
set multiplot layout 1, 2 title "Albedo ∫ f cos θ_i dω_i with ρ = 1 against the angle of view (Monte Carlo, ± 1 standard error)"
set xlabel "θ_o (degrees from the normal)"
set ylabel "albedo"
set xrange [0:90]
set yrange [0:1.6]
set xtics 0, 15, 90
set key left top
set title "modified Phong (1.8) against e; Lambert (1.5)"
plot for [e in "1 10 100 1000"] f skip 2 using 4:(sel("phong (1.8)", e + 0)):6 \
         with yerrorlines pt 7 ps 0.6 title "Phong, e = " . e, \
     f skip 2 using 4:(sel("lambert (1.5)", 0)):6 with yerrorlines lt 5 pt 7 ps 0.6 title "Lambert"
set title "Ward (1.9): as the book prints it (solid), bounded (dashed)"
set yrange [0:2]
set key left top maxrows 3 samplen 2
plot for [i = 1:3] f skip 2 using 4:(sel("ward (1.9)", word("0.05 0.2 0.7", i) + 0)):6 \
         with yerrorlines lt i pt 7 ps 0.6 title "book α = " . word("0.05 0.2 0.7", i), \
     for [i = 1:3] f skip 2 using 4:(sel("ward bounded", word("0.05 0.2 0.7", i) + 0)):6 \
         with yerrorlines lt i dt 2 pt 6 ps 0.6 title "bounded α = " . word("0.05 0.2 0.7", i)
unset multiplot
