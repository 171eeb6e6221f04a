#!/bin/sh
# tradeoffs-photon.sh - `make tradeoffs-photon`: what the photon maps'
# settings cost and buy on scenes/caustic.scn (ch. 8), measured. A path
# traced reference (REF_SPP samples at half the scene's resolution, its own
# seed; by default twice the samples the path tracer reaches in 120 CPU-s,
# so that the reference's noise, which the table subtracts, does not
# swamp the error measured there) is rendered once into
# out/tradeoffs-photon/; `svet converge` then
# renders the path tracer (the baseline) and the photon and ppm methods,
# one setting changed at a time, for the same series of time budgets, and
# `svet converge --report` turns the series into a table. The budgets are
# CPU-seconds by default (`svet converge --clock cpu`, all threads
# together), which the other jobs of a shared machine hardly change, so
# that rows measured minutes apart compare; 120 CPU-s is a minute of both
# cores of a 2-core machine. Also the
# difference Fresnel's exact reflectance makes against Schlick's (the
# scene's glass with `fresnel schlick`), by `svet diff` of two path-traced
# renders. Writes docs/tradeoffs-photon.md.
# usage: sh tools/tradeoffs-photon.sh   (environment: SVET (build/float/svet),
#        CLOCK (cpu, or wall), TIMES (8,16,32,64,120; seconds on CLOCK),
#        ROWS (every row; or labels separated by commas, e.g. path,photon:
#        path, the baseline, is always run), THREADS (0), REF_SPP (65536),
#        REUSE (1: keep a row whose OUT/LABEL.csv exists), OUT, DOC)
set -eu
svet=${SVET:-build/float/svet}
clock=${CLOCK:-cpu}
times=${TIMES:-8,16,32,64,120}
rows=${ROWS:-}
threads=${THREADS:-0}
refspp=${REF_SPP:-65536}
reuse=${REUSE:-0}
out=${OUT:-out/tradeoffs-photon}
doc=${DOC:-docs/tradeoffs-photon.md}
scene=scenes/caustic.scn
[ -x "$svet" ] || { echo "tradeoffs-photon: no $svet (make first)" >&2; exit 1; }
case $clock in cpu | wall) ;; *)
    echo "tradeoffs-photon: CLOCK=$clock: expected cpu or wall" >&2; exit 1 ;;
esac
mkdir -p "$out"
t0=$(date +%s)
load0=$(cut -d' ' -f1-3 /proc/loadavg)
res=80x60
if [ ! -f "$out/ref.exr" ]; then
    echo "tradeoffs-photon: the reference, $refspp spp at $res" >&2
    "$svet" render "$scene" --set integrator=path --set resolution=$res \
        --spp "$refspp" --seed 7 --threads "$threads" -q \
        -o "$out/ref.exr" --variance "$out/ref-var.exr"
fi
files=
series() { # LABEL SETTINGS...: one row, unless ROWS leaves it out
    label=$1; shift
    case ",$rows," in ,, | *",$label,"* ) ;; *)
        [ "$label" = path ] || return 0 ;;
    esac
    if [ "$reuse" = 1 ] && [ -f "$out/$label.csv" ]; then
        files="$files $label"; return 0
    fi
    echo "tradeoffs-photon: $label ($(date -u +%H:%M:%S), load $(cut -d' ' -f1 /proc/loadavg))" >&2
    "$svet" converge "$scene" --ref "$out/ref.exr" --seed 1 \
        --time-list "$times" --clock "$clock" --threads "$threads" \
        --out "$out" --label "$label" --no-plot -q "$@" >/dev/null
    files="$files $label"
}
series path --set integrator=path
series photon
series max_radius=0.02 --set photonmap.max_radius=0.02
series max_radius=0.08 --set photonmap.max_radius=0.08
series k=20 --set photonmap.k=20
series k=100 --set photonmap.k=100
series gather=2 --set photonmap.gather=2
series gather=4 --set photonmap.gather=4
series gather=16 --set photonmap.gather=16
series precompute=0 --set photonmap.precompute=0
series precompute=4 --set photonmap.precompute=4
series caustic=400000 --set photonmap.caustic=400000
series global=50000 --set photonmap.global=50000
series global=400000 --set photonmap.global=400000
series filter=none --set photonmap.filter=none
series preview --set photonmap.gather=0 --set photonmap.max_radius=0.2
series ppm --set integrator=ppm --set photonmap.global=50000 \
    --set photonmap.radius=0.05
series ppm-global=200000 --set integrator=ppm --set photonmap.global=200000 \
    --set photonmap.radius=0.03
series ppm-alpha=0.5 --set integrator=ppm --set photonmap.global=50000 \
    --set photonmap.radius=0.05 --set photonmap.alpha=0.5
case $svet in /*) sv=$svet ;; *) sv=$PWD/$svet ;; esac
report=$(cd "$out" && "$sv" converge --report $(for f in $files; do printf '%s.csv ' "$f"; done))
# The photon rows against the path tracer, read off the table (columns:
# method, spp, error, time to the baseline's error, speed-up, efficiency,
# x baseline, rays/s, biased?): the largest speed-up at equal error and
# the largest efficiency ratio, and the shipped setting's.
summary=$(printf '%s\n' "$report" | awk -F'|' '
    function num(x) { gsub(/[ ~*]/, "", x); return x == "-" || x == "" ? 0 : x + 0 }
    /^\| / && $2 !~ /method/ && $2 !~ /^-+$/ {
        m = $2; gsub(/ /, "", m)
        if (m == "path") { perr = $4; next }
        if (m == "photon") { serr = $4; ssp = $6; sx = $8 }
        if (num($6) > bs) { bs = num($6); bsm = m; bserr = $4 }
        if (num($8) > bx) { bx = num($8); bxm = m; bxb = $10 }
    }
    END {
        gsub(/ /, "", perr); gsub(/ /, "", serr); gsub(/ /, "", bserr)
        gsub(/ /, "", ssp); gsub(/ /, "", sx); gsub(/^ +| +$|\*/, "", bxb)
        printf "The shipped setting (`photon`): relative RMSE %s against the path tracer'"'"'s %s at the last time, speed-up %s at the path tracer'"'"'s error there, efficiency %s times the path tracer'"'"'s. ", serr, perr, ssp, sx
        printf "The largest speed-up at equal error is %.2f (`%s`, error %s); the largest efficiency ratio is %.2f (`%s`, biased: %s).", bs, bsm, bserr, bx, bxm, bxb
    }')
# Fresnel: the path tracer's image with the scene's exact reflectance
# against the same with Schlick's
sed 's/fresnel exact/fresnel schlick/' "$scene" > "$out/caustic-schlick.scn"
for v in exact schlick; do
    s=$scene; [ $v = schlick ] && s=$out/caustic-schlick.scn
    "$svet" render "$s" --set integrator=path --set resolution=$res \
        --spp 1024 --seed 3 --threads "$threads" -q -o "$out/fresnel-$v.exr"
done
fresnel=$("$svet" diff "$out/fresnel-schlick.exr" "$out/fresnel-exact.exr")
noise=$("$svet" diff "$out/fresnel-exact.exr" "$out/ref.exr" --metric relmse |
       awk '$1 == "relmse" { print $2 }')
t1=$(date +%s)
if [ "$clock" = cpu ]; then
    unit="CPU-seconds (\`svet converge --clock cpu\`: the CPU time of the
render's threads together, which the machine's other jobs hardly change,
so that rows measured minutes apart compare; 120 CPU-s is a minute of
both cores)"
    minute="${times##*,} CPU-s; a minute of both cores is 120 CPU-s"
else
    unit="seconds of wall-clock time (CLOCK=wall: rows measured at
different times compare only on a quiet machine)"
    minute="${times##*,} s of wall-clock time"
fi
load1=$(cut -d' ' -f1-3 /proc/loadavg)
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -n 1)
cat > "$doc" <<END
# Photon maps on caustic.scn: what each setting costs and buys

Generated by \`make tradeoffs-photon\` (tools/tradeoffs-photon.sh, \`svet
converge\`); regenerate it rather than editing it. Every series is one
progressive render of \`scenes/caustic.scn\` at $res with $( [ "$threads" = 0 ] && echo "every core" || echo "$threads threads"),
seed 1, measured after $times $unit, the photon tracing included,
against the path tracer's image of $refspp samples per pixel (seed 7).
The baseline is the path tracer; \`photon\` is the scene as shipped
($(grep '^photonmap' "$scene")), each other row changes one setting of it.

Machine: $cpu, $(nproc) cores; $(${CC:-cc} --version | head -n 1). Measured
$(date -u '+%Y-%m-%d %H:%M UTC') in $(( (t1 - t0) / 60 )) min $(( (t1 - t0) % 60 )) s, load average $load0 at the start
and $load1 at the end: **the machine was shared with other jobs**$( [ "$clock" = cpu ] && echo "; CPU times hardly depend on the load, the run's length does." || echo ", so the times are noisy and longer than on a quiet machine.")

$report

$summary

The efficiency counts only the render's own variance between the
samples of a pixel; a fixed photon map's noise is the same for every
sample and shows as bias instead, so for \`photon\` the speed-up at equal
error is the fair comparison. It is the one to hold against the aim of
5 times the path tracer's efficiency at the error the path tracer reaches
in a minute (the last time of the series here is $minute): a
speed-up of 5 at a minute.

How to read it (\`svet converge --help\`): the error at the common time,
the time each method needs to reach the path tracer's error there, the
efficiency 1 / (variance x time) relative to the baseline's, and
"biased" where the squared bias exceeds the noise at the last point (the
photon map's blur: its error stops falling, as the fixed-radius estimate
must; ppm's radius shrinks and its error keeps falling).

## Fresnel: exact against Schlick

The path tracer's images (1024 samples at $res) with the glass's exact
Fresnel reflectance and with Schlick's (1.7), \`svet diff\` of Schlick's
against the exact one:

\`\`\`
$fresnel
\`\`\`

and, for scale, the exact image against the reference (their noise):
relmse $noise: a relmse of Schlick's against the exact image above that
is a difference the noise does not explain, and its largest pixel (max)
shows where it lies.
END
echo "wrote $doc" >&2
