# brdf_lobes.gp - the BRDF lobes of ch01_brdf as polar plots in the plane
# of incidence (figs. 1.4-1.5 of the book): for light arriving from Psi_i
# at 45 degrees on the left, the distance of the curve from the centre in
# the direction Psi_r is f(Psi_i, Psi_r) cos(theta_r), the intensity
# reflected toward Psi_r per unit irradiance. Each curve is scaled to its
# own peak (the peaks differ by orders of magnitude); the legend gives the
# peak of f. Reads OUTDIR/ch01_lobe_*.csv (chapters/ch01/ch01_brdf.c).
#   gnuplot -c chapters/ch01/brdf_lobes.gp OUTDIR [png|svg]
W = 800; H = 470
call "chapters/figure.gp" ARG1 ARG2

set polar
set angles degrees
set theta top clockwise
set size ratio -1
set trange [-90:90]
set rrange [0:1]
set xrange [-1.1:1.1]
set yrange [0:1.1]
unset border
unset xtics
unset ytics
set rtics 0.25 format "%.2f" scale 0.5
unset ttics
do for [a = -75:75:15] {
    t = a == 0 ? "0° (normal)" : sprintf("%d°", a)
    set label 100 + a t at first 1.05 * sin(a), 1.05 * cos(a) \
        center font ",9" tc rgb "#555555"
}
set grid polar 15 rtics lt 1 lc rgb "#cccccc" lw 0.5
set key at screen 0.5, 0.02 center bottom horizontal samplen 2 spacing 1.2 maxrows 2
set tmargin 3
set bmargin 5
set lmargin 2
set rmargin 2
set arrow 1 from 0, 0 to -sin(45), cos(45) nohead lc rgb "#555555" lw 2
set arrow 2 from 0, 0 to sin(45), cos(45) nohead dt 2 lc rgb "#555555" lw 2
set label 11 "Ψ_i (θ_i = 45°)" at first -0.8, 0.88 right tc rgb "#555555"
set label 12 "mirror\ndirection (1.4)" at first 0.8, 0.92 left tc rgb "#555555"
set label 13 "radius: f cos θ_r, scaled to each curve's peak\nangle: θ_r from the normal" at first -1.12, 1.1 left tc rgb "#555555"

do for [name in "lambert phong ward ward_bounded ward_aniso"] {
    f = csv("ch01_lobe_" . name . ".csv")
    unset polar
    set autoscale xy
    stats f skip 2 nooutput
    n = (STATS_columns - 1) / 2
    array fpk[n]
    array rpk[n]
    do for [k = 1:n] {
        stats f using (column(2 * k)) skip 2 nooutput
        fpk[k] = STATS_max
        stats f using (column(2 * k + 1)) skip 2 nooutput
        rpk[k] = STATS_max
    }
    if (name eq "lambert") {
        set title "Lambert (1.5), ρ = 1: f = 1/π everywhere; the cosine law's circle"
        lab1 = "Lambert"
    }
    if (name eq "phong") {
        set title "Modified Phong (1.8), normalised, ρ_s = 1, against the exponent e"
        lab1 = "e = 1"; lab2 = "e = 10"; lab3 = "e = 100"
    }
    if (name eq "ward") {
        set title "Ward (1.9) as the book prints it, ρ_s = 1, against the roughness α"
        lab1 = "α = 0.05"; lab2 = "α = 0.15"; lab3 = "α = 0.4"
    }
    if (name eq "ward_bounded") {
        set title "Ward (1.9) with the bounded normalisation, ρ_s = 1, against α"
        lab1 = "α = 0.05"; lab2 = "α = 0.15"; lab3 = "α = 0.4"
    }
    if (name eq "ward_aniso") {
        set title "Anisotropic Ward (1.10), α_x = 0.4, α_y = 0.08: two planes of incidence"
        lab1 = "plane through u (α_x)"; lab2 = "plane through v (α_y)"
    }
    set polar
    set theta top clockwise
    set xrange [-1.1:1.1]
    set yrange [0:1.12]
    set output fig("ch01_lobe_" . name)
    plot for [k = 1:n] f skip 2 using 1:(column(2 * k + 1) / rpk[k]) \
         with lines lt (n == 2 ? 2 * k - 1 : k) \
         title sprintf("%s, peak f = %.3g sr^{-1}", \
                       value(sprintf("lab%d", k)), fpk[k])
    undefine fpk rpk
}
