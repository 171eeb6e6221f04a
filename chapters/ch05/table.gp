# table.gp - ch05_cases's table as bars: for each case of ch. 5, the
# relative mean squared error of each strategy's image against the
# reference at equal time (lower is better), and its efficiency
# 1 / (relMSE x seconds) relative to `path` (higher is better; path = 1).
# Reads OUTDIR/table.csv (chapters/ch05/ch05_cases.c).
#   gnuplot -c chapters/ch05/table.gp OUTDIR [png|svg]
W = 1100; H = 860
call "chapters/figure.gp" ARG1 ARG2

f = csv("table.csv")
cases = "point area mirror diffuse glossy mixed glass"
strategies = "bsdf nee path direct"
array what[4] = ["BSDF sampling", "light sampling (NEE)", "both, by MIS (path)", "direct lighting only"]
idx(s, i) = i > words(cases) ? NaN : word(cases, i) eq s ? i : idx(s, i + 1)
# x of the bar of strategy k (1..4) in its case's group
bar(k) = strcol(2) eq word(strategies, k) ? idx(strcol(1), 1) + (k - 2.5) * 0.2 : NaN
set output fig("ch05_table")
set multiplot layout 2, 1 title "Chapter 5's cases, every strategy at equal time, against a reference"
set style fill solid 0.85 border -1
set boxwidth 0.19
set xrange [0.4:7.6]
set xtics ("point light" 1, "area light" 2, "mirror" 3, "diffuse\n(Cornell box)" 4, "glossy" 5, "mixed" 6, "glass" 7) scale 0
set logscale y
set format y "10^{%L}"
set grid ytics
set key outside right top
set title "relative MSE against the reference (lower is better)"
set ylabel "relMSE"
stats f skip 2 using 6 nooutput
set yrange [10**floor(log10(STATS_min) - 0.5):10**ceil(log10(STATS_max))]
plot for [k = 1:4] f skip 2 using (bar(k)):6 with boxes lt k title what[k]
set title "efficiency 1 / (relMSE × seconds), relative to path's (higher is better)"
set ylabel "efficiency / path's"
stats f skip 2 using 9 nooutput
set yrange [10**floor(log10(STATS_min) - 0.5):10**ceil(log10(STATS_max) + 0.1)]
set bmargin 4
plot for [k = 1:4] f skip 2 using (bar(k)):9 with boxes lt k title what[k], \
     1 with lines lc rgb "#444444" dt 2 notitle
unset multiplot
