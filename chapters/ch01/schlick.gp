# schlick.gp - Schlick's approximation (1.7) of the Fresnel reflectance,
# rho_s(theta) = rho_s(0) + (1 - rho_s(0)) (1 - cos theta)^5, for glass
# (0.04) to a metal (0.9), and the book's transmission rho_t(theta) =
# rho_t(0) (1 - (1 - cos theta)^5) of the glass. Reads
# OUTDIR/ch01_schlick.csv (chapters/ch01/ch01_brdf.c).
#   gnuplot -c chapters/ch01/schlick.gp OUTDIR [png|svg]
W = 800; H = 520
call "chapters/figure.gp" ARG1 ARG2

f = csv("ch01_schlick.csv")
set output fig("ch01_schlick")
set title "Schlick's Fresnel approximation (1.7) and the book's transmission"
set xlabel "angle of incidence θ (degrees from the normal)"
set ylabel "reflectance ρ_s(θ), transmittance ρ_t(θ)"
set xrange [0:90]
set yrange [0:1]
set xtics 0, 15, 90
set ytics 0, 0.1, 1
set mxtics 3
set key left center
plot f skip 2 using 1:2 with lines lt 1 title "ρ_s, ρ_s(0) = 0.04 (glass)", \
     "" skip 2 using 1:3 with lines lt 2 title "ρ_s, ρ_s(0) = 0.2", \
     "" skip 2 using 1:4 with lines lt 3 title "ρ_s, ρ_s(0) = 0.5", \
     "" skip 2 using 1:5 with lines lt 4 title "ρ_s, ρ_s(0) = 0.9 (metal)", \
     "" skip 2 using 1:6 with lines lt 5 dt 2 title "ρ_t, ρ_t(0) = 0.96 (the glass)"
