#!/bin/sh
# tradeoffs.sh - `make tradeoffs`: what each knob of the renderer costs and
# buys, measured. For every scene with a reference in tests/reference/
# (make reference), `svet converge` renders the scene as shipped (the
# baseline) and with one knob changed at a time, each for the same series
# of time budgets, against that reference; `svet converge --report` turns
# each scene's series into a table; gnuplot (if installed) draws them on
# one log-log plot. Writes docs/tradeoffs.md and docs/tradeoffs/*.png; the
# CSV series stay in out/tradeoffs/ (copied next to the document when
# gnuplot is missing).
#
# usage: sh tools/tradeoffs.sh [SCENE.scn ...]   (default: every scene
#        with a reference)
# environment:
#   SVET_FLOAT, SVET_DOUBLE  the two builds (build/float/svet, build/double/svet)
#   TIMES    the points of every series in seconds of rendering
#            (0.5,1,2,4,8,16): one progressive render per series, so a
#            series takes as long as its last point
#   THREADS  render threads (0: every core)
#   REFDIR   the references (tests/reference)
#   REPORT_ONLY=1  write the document again from the last run's series
#            (out/tradeoffs/), rendering nothing
#   OUT      the CSV directory (out/tradeoffs); DOC the document
#            (docs/tradeoffs.md)
# The knobs: the integrator (path = NEE + BSDF sampling with MIS; nee =
# light sampling alone; bsdf = BSDF sampling alone; direct = one bounce),
# the maximum depth (1, 2, 3 when below the scene's), Russian roulette off,
# float against double, and on the Cornell box the acceleration structure
# (brute force, uniform grid, hierarchical grid).
set -eu

svet=${SVET_FLOAT:-build/float/svet}
svetd=${SVET_DOUBLE:-build/double/svet}
times=${TIMES:-0.5,1,2,4,8,16}
threads=${THREADS:-0}
out=${OUT:-out/tradeoffs}
doc=${DOC:-docs/tradeoffs.md}
refdir=${REFDIR:-tests/reference}
figdir=$(dirname "$doc")/tradeoffs
for b in "$svet" "$svetd"; do
    [ -x "$b" ] || { echo "tradeoffs.sh: $b is not built" >&2; exit 1; }
done
if [ $# -eq 0 ]; then
    for t in "$refdir"/*.txt; do
        [ -e "$t" ] || continue
        set -- "$@" "$(sed -n 's/^scene = //p' "$t")"
    done
fi
[ $# -gt 0 ] || { echo "tradeoffs.sh: no references (make reference)" >&2; exit 1; }
mkdir -p "$out" "$figdir"
have_gnuplot=no
command -v gnuplot >/dev/null 2>&1 && have_gnuplot=yes

# A render setting of the scene file (the last value given on `render`
# lines), or the default.
setting() {
    awk -v key="$2" -v def="$3" '$1 == "render" {
            for (i = 2; i < NF; i++) if ($i == key) v = $(i + 1) }
         END { print (v != "" ? v : def) }' "$1"
}

# The methods of one scene, one per line: LABEL BUILD [--set KEY=VALUE ...]
methods() {
    scene=$1
    md=$(setting "$scene" maxdepth 5)
    integ=$(setting "$scene" integrator path)
    echo "baseline f"
    echo "double d"
    for i in nee bsdf direct; do
        [ "$i" = "$integ" ] || echo "$i f --set integrator=$i"
    done
    for d in 1 2 3; do
        [ "$d" -lt "$md" ] && echo "maxdepth=$d f --set maxdepth=$d"
    done
    echo "roulette=off f --set roulette=off"
    if [ "$(basename "$scene" .scn)" = cbox ]; then
        for a in brute grid hgrid; do echo "accel=$a f --set accel=$a"; done
    fi
    return 0
}

# The CSV files of one scene's series, in the order of methods().
series_files() {
    methods "$1" | while read -r label rest; do
        printf '%s ' "$out/$(basename "$1" .scn)/$label.csv"; done
}

nruns=0
for scene in "$@"; do
    nruns=$(( nruns + $(methods "$scene" | wc -l) ))
done
budget=${times##*,}
[ "${REPORT_ONLY:-0}" = 1 ] ||
echo "tradeoffs.sh: $nruns series of $budget s of rendering each:" \
     "about $(awk -v n="$nruns" -v b="$budget" 'BEGIN { printf "%.0f", n * (b + 0.5) / 60 }') min" >&2

if [ "${REPORT_ONLY:-0}" = 1 ]; then
    # the document again from the series of the last run
    [ -f "$out/run.env" ] || { echo "tradeoffs.sh: no $out/run.env" >&2; exit 1; }
    . "$out/run.env"
    set --
else
load0=$(cut -d ' ' -f 1-3 /proc/loadavg 2>/dev/null || echo "?")
t0=$(date +%s)
fi
for scene in "$@"; do
    name=$(basename "$scene" .scn)
    mkdir -p "$out/$name"
    rm -f "$out/$name"/*.csv
    methods "$scene" | while read -r label build sets; do
        bin=$svet
        [ "$build" = d ] && bin=$svetd
        echo "tradeoffs.sh: $name: $label" >&2
        # shellcheck disable=SC2086 # sets is a list of options
        "$bin" converge "$scene" --ref "$refdir/$name.exr" --seed 1 \
            --threads "$threads" --time-list "$times" --out "$out/$name" \
            --label "$label" --no-plot -q $sets >/dev/null
    done
done
if [ "${REPORT_ONLY:-0}" = 1 ]; then
    set -- $scenes
else
t1=$(date +%s)
load1=$(cut -d ' ' -f 1-3 /proc/loadavg 2>/dev/null || echo "?")
cat > "$out/run.env" <<EOF
t0=$t0; t1=$t1; load0='$load0'; load1='$load1'; times='$times'
threads='$threads'; scenes='$*'
EOF
fi

# --- the document ------------------------------------------------------------
# each scene's table first: the summary at the top is read off them
for scene in "$@"; do
    name=$(basename "$scene" .scn)
    # shellcheck disable=SC2046 # a list of files
    "$svet" converge --report $(series_files "$scene") > "$out/$name.md"
done

# The summary: per method and scene, the efficiency relative to the
# baseline (column 8 of a report row) and a mark where the method is
# biased (column 10).
summary() {
    for scene in "$@"; do
        name=$(basename "$scene" .scn)
        awk -F'|' -v scene="$name" '/^\| / && $2 !~ /method/ {
                gsub(/ /, "", $2); gsub(/ /, "", $8)
                print scene, $2, $8 ($10 ~ /yes/ ? "*" : "") }' "$out/$name.md"
    done | awk -v scenes="$*" '
        { key = $2; if (!(key in seen)) { seen[key] = 1; order[++n] = key }
          cell[key, $1] = $3 }
        END {
            ns = split(scenes, sc, " ")
            for (j = 1; j <= ns; j++) { sub(/.*\//, "", sc[j]); sub(/\.scn$/, "", sc[j]) }
            printf "| method |"; for (j = 1; j <= ns; j++) printf " %s |", sc[j]; print ""
            printf "|---|"; for (j = 1; j <= ns; j++) printf "---:|"; print ""
            for (i = 1; i <= n; i++) {
                printf "| %s |", order[i]
                for (j = 1; j <= ns; j++) {
                    v = cell[order[i], sc[j]]; printf " %s |", v == "" ? "-" : v }
                print ""
            }
        }'
}

cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -n 1)
tmp="$doc.tmp"
{
cat <<EOF
# Speed and accuracy: what each knob costs and buys

Generated by \`make tradeoffs\` (tools/tradeoffs.sh, \`svet converge\`);
regenerate it rather than editing it. Every table and plot below comes
from renders of the shipped scenes against their converged references in
\`tests/reference/\` (\`make reference\`: half the scenes' resolution,
4096 samples per pixel), at their resolution. Each series is one
progressive render with $( [ "$threads" = 0 ] && echo "every core" || echo "$threads threads"), seed 1, measured after
$times seconds of rendering.

Machine: $cpu, $(nproc) cores; $(${CC:-cc} --version | head -n 1); float and
double builds with the Makefile's flags (${SVET_FLAGS:-see the Makefile}). Measured $(date -u +%Y-%m-%d) in
$(( (t1 - t0) / 60 )) min $(( (t1 - t0) % 60 )) s, load average $load0 at the start and
$load1 at the end: **on a shared machine the times are noisy** (a load
above the core count slows every series, not always equally); a quiet
machine gives the same tables with smaller times.

The photon maps of ch. 8 (their counts, k, radius and gather rays, and
progressive photon mapping) against the path tracer on \`caustic.scn\` are
measured apart, by \`make tradeoffs-photon\`, in CPU-seconds:
[docs/tradeoffs-photon.md](tradeoffs-photon.md).
The media of ch. 11 (volumetric path tracing on \`smoky-cbox.scn\` and
\`cloud.scn\`) are measured apart too, by \`make tradeoffs-media\`:
\`docs/tradeoffs-media.md\`; their cross-check against Mitsuba 3 is
\`bench/results/media.md\` (\`make bench-media\`).

## Summary: efficiency against the baseline

Each cell is a method's efficiency 1 / (variance x time) divided by the
baseline's on that scene (larger is better; 1.00 is the scene as
shipped). \`*\` marks a biased method: its variance is low but its error
stops falling (see the scene's table). \`-\`: not run on that scene.

EOF
summary "$@"
cat <<EOF

## How to read the tables

- **Error**: the *relative* RMSE, the square root of the mean over every
  pixel value of (a - b)^2 / (b^2 + 0.01), with the reference's own noise
  taken out (its variance image is subtracted). The absolute RMSE of these
  scenes is made mostly by the noisy pixels on the edge of the light
  (18 times brighter than anything it lights); the relative error counts
  each pixel by how visible its error is. The CSV files hold both.
- **RMSE at T s**: the error each method reaches in the same time T, the
  longest time every series reached. **time to E**: the time it needs to
  reach the error E that the baseline (the scene as shipped) reaches at T;
  **speed-up** is the baseline's time over the method's. \`~\` marks a value
  extrapolated beyond the measured points by MSE = bias^2 + c/t.
- **efficiency** = 1 / (variance x time), with the renderer's own variance
  estimate (render_variance, relative to b^2 + 0.01, averaged over the
  image): it stays constant along an unbiased series (variance ~ 1/N,
  time ~ N), so it puts methods on one number; **x baseline** divides it by
  the baseline's. A method with low variance but a bias scores well here
  and badly in the error columns: read them together.
- **biased?**: at the last point, the squared error exceeds twice what the
  variances of render and reference explain; the error stops falling at
  about the estimated bias (the relative RMSE it can never go below).
  \`direct\` and \`maxdepth=N\` are biased by construction wherever paths
  of more bounces carry visible light (the Cornell box's ceiling is lit
  only indirectly), and \`bsdf\` is where a light is a point, which no
  BSDF sample can hit (point_plane renders black; mixed loses the point
  light behind its paper screen). The baseline, \`nee\`
  (light sampling without MIS; emitters reached after a mirror or glass
  bounce still count), \`bsdf\` with area lights, roulette on or off,
  float and double, and every acceleration structure must not be: where
  the table says otherwise, look for a bug, or for an estimator whose
  variance estimate is itself too noisy at this sample count.
- **rays/s**: every ray traced (camera, bounce, shadow) per second of the
  series: the speed of the tracer rather than of the estimator.

The knobs: \`baseline\` is the scene file as shipped (for most scenes the
path tracer: next-event estimation and BSDF sampling joined by MIS, Russian
roulette on); \`double\` the same in the double build; \`nee\`, \`bsdf\`,
\`direct\` the other integrators (scenes/README.md); \`maxdepth=N\` fewer
scattering events; \`roulette=off\` paths run to the maximum depth;
\`accel=...\` brute force, the uniform or the hierarchical grid (ch. 7) for
finding hits, which must change only the speed. On the Cornell box
\`baseline\` and \`accel=brute\` are the same computation (for 8 objects
the renderer's automatic choice is brute force, include/accel/accel.h): the
difference between their rows is the noise of the measurement.

EOF
for scene in "$@"; do
    name=$(basename "$scene" .scn)
    files=$(series_files "$scene")
    echo "## $name ($scene)"
    echo
    cat "$out/$name.md"
    echo
    if [ "$have_gnuplot" = yes ]; then
        titles=$(methods "$scene" | while read -r label rest; do
                     printf '%s ' "$label"; done)
        gnuplot -e "files='$files'; titles='$titles'; out='$figdir/$name.png'; ttl='$name: relative RMSE against time'" \
            tools/plot-converge.gp
        echo "![$name: relative RMSE against render time, log-log](tradeoffs/$name.png)"
    else
        # one CSV of every series, the header once
        # shellcheck disable=SC2086 # a list of files
        awk '/^#/ { next } /^method,/ { if (h++) next } { print }' $files \
            > "$figdir/$name.csv"
        echo "gnuplot is not installed: no plot; the series are in" \
             "[tradeoffs/$name.csv](tradeoffs/$name.csv) (plot them with" \
             "tools/plot-converge.gp)."
    fi
    echo
done
} > "$tmp"
mv "$tmp" "$doc"
echo "tradeoffs.sh: wrote $doc in $(( t1 - t0 )) s of rendering" >&2
