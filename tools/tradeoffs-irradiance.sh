#!/bin/sh
# tradeoffs-irradiance.sh - `make tradeoffs-irradiance`: what the
# irradiance cache (ch. 9) and app. F's subsampling cost and buy on the
# Cornell box (scenes/cbox.scn), measured. A path-traced reference
# (REF_SPP samples at RES, its own seed) is rendered once into
# out/tradeoffs-irradiance/; `svet converge` then renders the path tracer
# (the baseline) and `integrator irradiance` with one setting changed at a
# time (a, M x N, gradients, neighbour clamping) for the same series of
# time budgets, its pre-pass included, and `svet converge --report` turns
# them into a table read at REPORT_TIME seconds. Those seconds are
# CPU-seconds by default (`svet converge --clock cpu`, all threads
# together), which the machine's other jobs hardly change; the default
# budgets are then twice the wall-clock ones at 2 threads. Subsampling
# renders the
# whole image in one pass (render.h), so its rows are single renders at a
# few sample counts, timed by the wall clock around `svet render` (scene
# reading and the pre-pass included) and compared with `svet diff`, beside
# the same renders without it. Writes docs/tradeoffs-irradiance.md.
# usage: sh tools/tradeoffs-irradiance.sh   (environment: SVET
#        (build/float/svet), CLOCK (cpu, or wall), TIMES (2,4,8,16 CPU-s;
#        1,2,4,8 s of wall), REPORT_TIME (10 CPU-s; 5 s), THREADS (2),
#        REF_SPP (4096), RES (80x80), COUNT_SPP (16), SUB_SPP (16 64 256),
#        EFF_RES (256x256), EFF_REF_SPP (1024), EFF_TIMES (5,10,20 CPU-s;
#        2.5,5,10 s), IND_REF_SPP (2048), IND_TIMES (0.5,1,1.5,2,3,5,10,20
#        CPU-s; half that of wall), NICE (10), OUT, DOC, ONLY)
# The section on the indirect diffuse light alone (`render light
# indirect`, at EFF_RES with EFF_TIMES) runs with the rest; ONLY=indirect
# runs just it and puts it in place of its section of an existing DOC.
set -eu
svet=${SVET:-build/float/svet}
clock=${CLOCK:-cpu}
case $clock in
cpu) times=${TIMES:-2,4,8,16}; rtime=${REPORT_TIME:-10}; unit=CPU-s
     units="CPU-seconds (\`svet converge --clock cpu\`: all threads together,
which the machine's other jobs hardly change)" ;;
wall) times=${TIMES:-1,2,4,8}; rtime=${REPORT_TIME:-5}; unit=s
      units="seconds of wall-clock time" ;;
*) echo "tradeoffs-irradiance: CLOCK=$clock: expected cpu or wall" >&2
   exit 1 ;;
esac
threads=${THREADS:-2}
refspp=${REF_SPP:-4096}
res=${RES:-80x80}
out=${OUT:-out/tradeoffs-irradiance}
doc=${DOC:-docs/tradeoffs-irradiance.md}
scene=scenes/cbox.scn
only=${ONLY:-}
case $only in
''|indirect) ;;
*) echo "tradeoffs-irradiance: ONLY=$only: expected indirect or nothing" >&2
   exit 1 ;;
esac
[ -x "$svet" ] || { echo "tradeoffs-irradiance: no $svet (make first)" >&2; exit 1; }
mkdir -p "$out"
t0=$(date +%s)
load0=$(cut -d' ' -f1-3 /proc/loadavg)
niceness=${NICE:-10}
count_spp=${COUNT_SPP:-16}
sub_spp=${SUB_SPP:-16 64 256}
sv() { nice -n "$niceness" "$svet" "$@"; }
# the irradiance row against the baseline: speed-up (time ratio at the
# path tracer's error at REPORT_TIME) and efficiency ratio
row_of() { # LABEL: "speed-up efficiency-ratio" of that row
    printf '%s\n' "$report" |
    awk -F'|' -v l=" $1 " '$2 == l { gsub(/ /, "", $6); gsub(/ /, "", $8);
                                    print $6 " " $8 }'
}
# each setting's own log at COUNT_SPP: records, lookups, records per lookup
count_row() { # LABEL SETTINGS...
    label=$1; shift
    sv render "$scene" "$@" --set resolution=${cres:-$res} --spp "$count_spp" \
        --seed 1 --threads "$threads" -o "$out/count.exr" 2> "$out/count.txt"
    sed -n 's/^svet render: irradiance cache: \([0-9]*\) records .*; \([0-9]*\) lookups, \([0-9]*\) of them.*records per lookup \(.*\) %$/\1 \2 \3 \4/p' \
        "$out/count.txt" |
    awk -v l="$label" '{ printf "| %s | %d | %d | %d | %s %% |\n", l, $1, $2,
                         $3, $4 }'
}
num() { printf '%s\n' "$1" | sed 's/[^0-9.e+-]//g'; }
effres=${EFF_RES:-256x256}
effrefspp=${EFF_REF_SPP:-1024}
case $clock in
cpu) efftimes=${EFF_TIMES:-5,10,20} ;;
*) efftimes=${EFF_TIMES:-2.5,5,10} ;;
esac
# the path tracer follows up to 7 bounces (cbox.scn's maxdepth), so the
# cache's gathers follow 6 after the record's own vertex
irr="--set integrator=irradiance --set irradiance.bounces=6"
# a larger a and min_r: far fewer records, under 1 % of the lookups
fast="$irr --set irradiance.a=0.3 --set irradiance.min_r=10"
# larger still: fewer records and gathers, more interpolation error
faster="$irr --set irradiance.a=0.5 --set irradiance.min_r=20"
fastest="$irr --set irradiance.a=0.5 --set irradiance.max_r=40 --set irradiance.min_r=30"
# The indirect diffuse light alone (`render light indirect`): the path
# tracer's error at REPORT_TIME is the reference error, and each cache
# setting's time to it and records per lookup are measured against a
# path-traced reference of the indirect light; indirect_text then sets
# $indsection.
ind="$out/indirect"
indrefspp=${IND_REF_SPP:-2048}
# budgets down to a fraction of REPORT_TIME: the cache's time to the
# path tracer's error is then measured (its pre-pass takes most of it),
# not extrapolated back from longer runs
case $clock in
cpu) indtimes=${IND_TIMES:-0.5,1,1.5,2,3,5,10,20} ;;
*) indtimes=${IND_TIMES:-0.25,0.5,0.75,1,1.5,2.5,5,10} ;;
esac
indlabels="irradiance a=0.3+min_r=10 a=0.5+min_r=20 a=0.5+min_r=30+max_r=40"
lset="--set light=indirect"
indirect_section() {
    mkdir -p "$ind"
    if [ ! -f "$ind/ref.exr" ]; then
        echo "tradeoffs-irradiance: the indirect light's reference," \
             "$indrefspp spp at $effres" >&2
        sv render "$scene" --set integrator=path --set resolution=$effres \
            $lset --spp "$indrefspp" --seed 7 --threads "$threads" -q \
            -o "$ind/ref.exr" --variance "$ind/ref-var.exr"
    fi
    indseries() { # LABEL SETTINGS...
        label=$1; shift
        echo "tradeoffs-irradiance: $label, indirect light, at $effres" >&2
        sv converge "$scene" --ref "$ind/ref.exr" --seed 1 \
            --time-list "$indtimes" --clock "$clock" --threads "$threads" \
            --out "$ind" --label "$label" --no-plot -q \
            --set resolution=$effres $lset "$@" >/dev/null
    }
    indseries path --set integrator=path
    indseries irradiance $irr
    indseries a=0.3+min_r=10 $fast
    indseries a=0.5+min_r=20 $faster
    indseries a=0.5+min_r=30+max_r=40 $fastest
    indreport=$(cd "$ind" && "$OLDPWD/$svet" converge --report \
        --time "$rtime" path.csv $(for l in $indlabels; do
                                      printf '%s.csv ' "$l"; done))
    echo "tradeoffs-irradiance: record counts, indirect light" >&2
    indcounts=$(cres=$effres
        count_row irradiance $irr $lset
        count_row a=0.3+min_r=10 $fast $lset
        count_row a=0.5+min_r=20 $faster $lset
        count_row a=0.5+min_r=30+max_r=40 $fastest $lset)
}
# The text of that section from indirect_section's tables and the
# times indt0, indt1 and loads indload0, indload1 around it.
indirect_text() {
    # the path tracer's error at REPORT_TIME, and for each cache setting
    # the time of its first image at or below it (the measured time to
    # it is at most that: the report interpolates between that image and
    # the point before, the pre-pass's end with no image yet), the
    # speed-up that time gives, the efficiency ratio and records per
    # lookup
    inde=$(printf '%s\n' "$indreport" |
           sed -n 's/.*relative RMSE of \([0-9.e+-]*\) that.*/\1/p')
    indsummary=$(for l in $indlabels; do
        ratio=$(report=$indreport row_of "$l")
        pl=$(printf '%s\n' "$indcounts" |
             awk -F'|' -v l=" $l " '$2 == l { gsub(/[ %]/, "", $6); print $6 }')
        first=$(awk -F, -v e="$inde" '/^#/ || $1 == "method" { next }
                    $2 > 0 && $16 <= e + 0 { print $3 " " $2; exit }' \
                    "$ind/$l.csv")
        # records per lookup at that image's spp: the lookups grow with
        # the samples (one per camera sample that meets a diffuse surface)
        fpl=$(printf '%s\n' "$indcounts" |
              awk -F'|' -v l=" $l " -v n="${first#* }" -v c="$count_spp" '
                  $2 == l && n + 0 > 0 { printf "%.3g", 100 * $3 / ($4 * n / c) }')
        first=${first% *}
        printf '%s %s %s %s %s %s\n' "$l" "${ratio#* }" "${pl:-100}" \
            "${first:--}" "$(awk -v t="$rtime" -v f="${first:-0}" 'BEGIN {
                if (f > 0) printf "%.1f", t / f; else print "-" }')" \
            "${fpl:-100}"
    done)
    indwords=$(printf '%s\n' "$indsummary" | awk '{
        printf "%s`%s`: %s, efficiency ratio %s, %s %% of the lookups as " \
               "records", (NR > 1 ? "; " : ""), $1,
               ($5 == "-" ? "no image at or below it within the budgets" \
                 : sprintf("its first image at or below it after %.3g %s, " \
                           "at least %s times as fast (records %s %% of " \
                           "that image'"'"'s lookups)", $4, u, $5, $6)),
               $2, $3 }' u="$unit")
    indverdict=$(printf '%s\n' "$indsummary" | awk '{
        s = $5;
        if (s != "-" && s + 0 >= 10 && $3 + 0 <= 1 && $6 + 0 <= 1) ok = 1;
        else if (s != "-" && s + 0 >= 10) fast = 1 }
        END { if (ok) print "holds";
              else if (fast) print "is reached in speed only with more " \
                                   "than 1 % of the lookups as records";
              else print "does not hold" }')
    cat > "$ind/section.md" <<END
## At about 100 samples per pixel: the indirect diffuse light alone

\`scenes/cbox.scn\` at $effres with \`render light indirect\`
(\`--set light=indirect\`, scenes/README.md): the light the first
diffuse vertex reflects of light that has bounced at least once more,
without the emitters the camera sees and without the direct light, which
both methods compute alike. The path tracer (up to 7 bounces) and the
cache settings above, on the same clock and threads, budgets of
$indtimes $unit (the short ones for the cache's pre-pass and first
passes), against a path-traced reference of the indirect light
of $indrefspp samples per pixel (seed 7, its noise taken out); the
reference error is the path tracer's at $rtime $unit (about
$(awk -v t="$rtime" -v n="$threads" 'BEGIN { print t / n }') s of wall-clock time at $threads threads; its spp column). \`a=0.5+min_r=20\`
is \`irradiance.a=0.5 irradiance.min_r=20\`, fewer records still, and
\`a=0.5+min_r=30+max_r=40\` adds \`irradiance.min_r=30 irradiance.max_r=40\`. Run
alone with \`ONLY=indirect NICE=$niceness make tradeoffs-irradiance\`
(load average $indload0 at its start, $indload1 at its end, measured
$(date -u '+%Y-%m-%d %H:%M UTC') in $(( (indt1 - indt0) / 60 )) min $(( (indt1 - indt0) % 60 )) s).

$indreport

Records of the same renders at $count_spp spp (seed 1; fewer samples
than the series take at $rtime $unit, so the share of lookups is if
anything larger here):

| setting | records | lookups | gathered afresh | records per lookup |
|---|---:|---:|---:|---:|
$indcounts

The speed-up column is the efficiency ratio at equal error (the
efficiency 1 / (variance x time) leaves a biased setting's bias out).
Where a budget ends before the cache's pre-pass does, its point is the
pre-pass's end with no image yet (spp 0), and the time to the error is
interpolated between it and the first image: the true time lies between
the two, so the words below take the speed-up from the first image at
or below the error, the lower bound, never from an extrapolation.

**Measured:** at the relative error ${inde:-?} the path tracer reaches in
$rtime $unit on the indirect diffuse light alone, $indwords. Ten times
the path tracer's efficiency with records at most 1 % of lookups
**$indverdict** on the indirect light.
END
    indsection=$(cat "$ind/section.md")
}
if [ "$only" = indirect ]; then
    [ -f "$doc" ] || { echo "tradeoffs-irradiance: ONLY=indirect: no $doc" >&2
                       exit 1; }
    indt0=$(date +%s); indload0=$(cut -d' ' -f1-3 /proc/loadavg)
    indirect_section
    indt1=$(date +%s); indload1=$(cut -d' ' -f1-3 /proc/loadavg)
    indirect_text
    # its section of $doc replaced (or put before the record counts)
    printf '%s\n' "$indsection" > "$out/indirect.md"
    awk -v f="$out/indirect.md" '
        function put() { while ((getline l < f) > 0) print l; print ""; done = 1 }
        /^## At about 100 samples per pixel: the indirect/ { put(); skip = 1; next }
        skip && /^## / { skip = 0 }
        !done && /^## Records created/ { put() }
        !skip { print }' "$doc" > "$doc.new" && mv "$doc.new" "$doc"
    echo "wrote the indirect section of $doc" >&2
    exit 0
fi
if [ ! -f "$out/ref.exr" ]; then
    echo "tradeoffs-irradiance: the reference, $refspp spp at $res" >&2
    sv render "$scene" --set integrator=path --set resolution=$res \
        --spp "$refspp" --seed 7 --threads "$threads" -q \
        -o "$out/ref.exr" --variance "$out/ref-var.exr"
fi
series() { # LABEL SETTINGS...
    label=$1; shift
    echo "tradeoffs-irradiance: $label" >&2
    sv converge "$scene" --ref "$out/ref.exr" --seed 1 \
        --time-list "$times" --clock "$clock" --threads "$threads" \
        --out "$out" \
        --label "$label" --no-plot -q "$@" >/dev/null
}
series path --set integrator=path
series irradiance $irr
series a=0.3 $irr --set irradiance.a=0.3
series a=0.08 $irr --set irradiance.a=0.08
series a=0.3+min_r=10 $fast
series a=0.3+min_r=10+gradients=off $fast --set irradiance.gradients=off
series MxN=4x16 $irr --set irradiance.m=4 --set irradiance.n=16
series MxN=16x64 $irr --set irradiance.m=16 --set irradiance.n=64
series gradients=off $irr --set irradiance.gradients=off
series clamp=off $irr --set irradiance.clamp=off
series bounces=1 $irr --set irradiance.bounces=1
files="path irradiance a=0.3 a=0.08 a=0.3+min_r=10 a=0.3+min_r=10+gradients=off MxN=4x16 MxN=16x64 gradients=off clamp=off bounces=1"
report=$(cd "$out" && "$OLDPWD/$svet" converge --report --time "$rtime" \
    $(for f in $files; do printf '%s.csv ' "$f"; done))
ratio=$(row_of irradiance)
speedup=${ratio% *}
effx=${ratio#* }
ratio=$(row_of a=0.3+min_r=10)
fspeedup=${ratio% *}
feffx=${ratio#* }
echo "tradeoffs-irradiance: record counts" >&2
counttable=$(
    count_row irradiance $irr
    count_row a=0.3 $irr --set irradiance.a=0.3
    count_row a=0.08 $irr --set irradiance.a=0.08
    count_row a=0.3+min_r=10 $fast
    count_row MxN=4x16 $irr --set irradiance.m=4 --set irradiance.n=16
    count_row MxN=16x64 $irr --set irradiance.m=16 --set irradiance.n=64
    count_row clamp=off $irr --set irradiance.clamp=off
    count_row bounces=1 $irr --set irradiance.bounces=1)
# app. F: single renders with and without subsampling, wall-clock timed
now() { date +%s.%N; }
sub_row() { # LABEL SPP SETTINGS...
    label=$1; spp=$2; shift 2
    f="$out/sub-$(printf '%s' "$label" | tr ' =/' '___')-$spp.exr"
    s0=$(now)
    sv render "$scene" --set resolution=$res --spp "$spp" --seed 1 \
        --threads "$threads" -o "$f" "$@" 2> "$out/sub.log"
    s1=$(now)
    px=$(sed -n 's/.*(app. F): \([0-9]*\) of \([0-9]*\) pixels.*/\1 of \2/p' \
         "$out/sub.log")
    e=$("$svet" diff "$f" "$out/ref.exr" --metric relmse |
       awk '$1 == "relmse" { print $2 }')
    awk -v l="$label" -v n="$spp" -v a="$s0" -v b="$s1" -v e="$e" \
        -v p="${px:-all}" 'BEGIN { t = b - a;
        printf "| %s | %d | %.2f | %s | %.3g | %.3g |\n", l, n, t, p, e,
               1 / (e * t) }'
}
# the whole cbox.scn image at about 100 spp, where the path tracer's
# REPORT_TIME (5 s of wall at 2 threads) is about 100 spp; the path
# tracer, the defaults and the cheap setting, read at REPORT_TIME
eff="$out/eff"
mkdir -p "$eff"
if [ ! -f "$eff/ref.exr" ]; then
    echo "tradeoffs-irradiance: the reference, $effrefspp spp at $effres" >&2
    sv render "$scene" --set integrator=path --set resolution=$effres \
        --spp "$effrefspp" --seed 7 --threads "$threads" -q \
        -o "$eff/ref.exr" --variance "$eff/ref-var.exr"
fi
effseries() { # LABEL SETTINGS...
    label=$1; shift
    echo "tradeoffs-irradiance: $label at $effres" >&2
    sv converge "$scene" --ref "$eff/ref.exr" --seed 1 \
        --time-list "$efftimes" --clock "$clock" --threads "$threads" \
        --out "$eff" --label "$label" --no-plot -q \
        --set resolution=$effres "$@" >/dev/null
}
effseries path --set integrator=path
effseries a=0.3+min_r=10 $fast
effseries irradiance $irr
effreport=$(cd "$eff" && "$OLDPWD/$svet" converge --report --time "$rtime" \
    path.csv a=0.3+min_r=10.csv irradiance.csv)
report_full=$report
report=$effreport
ratio=$(row_of a=0.3+min_r=10)
espeedup=${ratio% *}
eeffx=${ratio#* }
ratio=$(row_of irradiance)
edspeedup=${ratio% *}
report=$report_full
echo "tradeoffs-irradiance: record counts at $effres" >&2
effcounts=$(cres=$effres; count_row a=0.3+min_r=10 $fast)
indt0=$(date +%s); indload0=$(cut -d' ' -f1-3 /proc/loadavg)
indirect_section
indt1=$(date +%s); indload1=$(cut -d' ' -f1-3 /proc/loadavg)
indirect_text
echo "tradeoffs-irradiance: subsampling" >&2
subtable=$(
    for spp in $sub_spp; do
        sub_row "path" $spp --set integrator=path
        sub_row "path, step 4, threshold 0.1" $spp --set integrator=path \
            --set subsample.step=4 --set subsample.threshold=0.1
        sub_row "path, step 4, threshold 0.3" $spp --set integrator=path \
            --set subsample.step=4 --set subsample.threshold=0.3
        sub_row "path, step 8, threshold 0.5" $spp --set integrator=path \
            --set subsample.step=8 --set subsample.threshold=0.5
    done
    for spp in $sub_spp; do
        sub_row "irradiance a 0.3, min_r 10" $spp $fast
        sub_row "irradiance a 0.3, min_r 10, step 4, threshold 0.05" $spp \
            $fast --set subsample.step=4 --set subsample.threshold=0.05
        sub_row "irradiance a 0.3, min_r 10, step 8, threshold 0.1" $spp \
            $fast --set subsample.step=8 --set subsample.threshold=0.1
    done)
t1=$(date +%s)
load1=$(cut -d' ' -f1-3 /proc/loadavg)
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -n 1)
# the 10-times question: the fast setting's speed-up and its records per
# lookup, as numbers
fast_or_never() { # a speed-up column's value, in words
    case ${1:--} in
    -) echo "never reach it (the error floor lies above)" ;;
    *) echo "$1 times as fast" ;;
    esac
}
fpl=$(printf '%s\n' "$counttable" |
      awk -F'|' '$2 == " a=0.3+min_r=10 " { gsub(/[ %]/, "", $6); print $6 }')
efpl=$(printf '%s\n' "$effcounts" |
       awk -F'|' '$2 == " a=0.3+min_r=10 " { gsub(/[ %]/, "", $6); print $6 }')
verdict=$(awk -v s="$(num "${espeedup:-0}")" -v p="${efpl:-100}" 'BEGIN {
    if (s + 0 >= 10 && p + 0 <= 1) print "holds";
    else if (s + 0 >= 10) print "is reached in speed, but with more than 1 % of the lookups as records";
    else print "does not hold" }')
cat > "$doc" <<END
# The irradiance cache and subsampling on the Cornell box: cost and gain

Generated by \`make tradeoffs-irradiance\` (tools/tradeoffs-irradiance.sh,
\`svet converge\`, \`svet render\`, \`svet diff\`); regenerate it rather
than editing it. Every series renders \`scenes/cbox.scn\` at $res with
$threads threads, seed 1, measured after $times $units (the cache's
pre-pass included) against the path tracer's image of $refspp samples
per pixel (seed 7; its own noise is taken out of the errors). The
baseline is the path tracer (up to 7 bounces); \`irradiance\` is
\`render integrator irradiance\` with the defaults of scenes/README.md
(a 0.15, M x N 8 x 32, R in [1, 20] pixels, gradients and neighbour
clamping on) but 6 bounces (\`irradiance.bounces=6\`, so that its gathers
follow as many bounces as the path tracer); each other row changes one
setting of it. \`a=0.3+min_r=10\` is the cheap setting whose records stay
under 1 % of the lookups. The error is over the whole image: direct
light is computed the same way by both (chapter 5's light sampling at
every pixel sample), so its noise is in both rows; the section on the
indirect diffuse light alone leaves it out.

Machine: $cpu, $(nproc) cores; $(${CC:-cc} --version | head -n 1). Command:
\`NICE=$niceness make tradeoffs-irradiance\` (the renders run under \`nice -n
$niceness\`; TIMES=$times, REPORT_TIME=$rtime, COUNT_SPP=$count_spp,
SUB_SPP="$sub_spp"). Measured $(date -u '+%Y-%m-%d %H:%M UTC') in
$(( (t1 - t0) / 60 )) min $(( (t1 - t0) % 60 )) s, load average $load0 at
the start and $load1 at the end: **the machine was shared with other
jobs**, so the wall-clock times (the subsampling table) are noisy and
longer than on a quiet machine; the CPU-seconds are less affected.

$report

How to read it (\`svet converge --help\`): the relative error at
$rtime $unit, the time each method needs to reach the path tracer's error
there, the speed-up (the path tracer's time over that time: the
efficiency ratio at equal error), the efficiency 1 / (variance x time)
and its ratio to the baseline's, and "biased" where the squared bias
exceeds the noise at the last point (the cache's interpolation error:
the error stops falling, the floor a smaller a lowers).

At $res the path tracer's $rtime $unit are far more than 100 samples per
pixel, and its error there lies below the cache's floor wherever a
"never (bias)" stands: the defaults are $(fast_or_never "$speedup")
(efficiency ratio ${effx:-?}), a 0.3 with min_r 10 $(fast_or_never "$fspeedup")
(efficiency ratio ${feffx:-?}; ${fpl:-?} % of the lookups as records).
The next section measures the whole image at about 100 samples per pixel.

## At about 100 samples per pixel: the whole image

\`scenes/cbox.scn\` at $effres, the same clock and threads, budgets of
$efftimes $unit, against a path-traced reference of $effrefspp samples per
pixel (seed 7, its noise taken out): at $rtime $unit (about
$(awk -v t="$rtime" -v n="$threads" 'BEGIN { print t / n }') s of wall-clock time at $threads threads) the spp column gives the
path tracer's samples per pixel there.

$effreport

Records at $effres ($count_spp spp, seed 1; fewer samples than the series
take at $rtime $unit, so the share of lookups is if anything larger here):

| setting | records | lookups | gathered afresh | records per lookup |
|---|---:|---:|---:|---:|
$effcounts

**Measured:** at the error the path tracer reaches in $rtime $unit on the
whole image, the cache with a 0.3 and min_r 10 is ${espeedup:-?} times
as fast (the speed-up column: the efficiency ratio at equal error; its
efficiency 1 / (variance x time) is ${eeffx:-?} times the path
tracer's, a figure that leaves its bias out), with ${efpl:-?} % of the
lookups as records; the defaults (a 0.15, min_r 1) are ${edspeedup:-?}
times as fast. Ten times the path tracer's efficiency with
records at most 1 % of lookups **$verdict** on the whole image. The
error there includes the direct light, which both compute alike, with
the same noise; the next section measures the indirect diffuse light
alone.

$indsection

## Records created and records per lookup

Each setting's own log (\`svet render\`, $count_spp spp at $res, seed 1):
the records the pre-pass created, the lookups of the final pass, the
lookups no record covered (each gathers afresh and is not stored: the
final pass only reads the cache), and records as a share of lookups.

| setting | records | lookups | gathered afresh | records per lookup |
|---|---:|---:|---:|---:|
$counttable

## App. F: subsampling, and the cache's error floor

Single renders at a few sample counts, the wall-clock seconds of the
whole \`svet render\` (reading, pre-pass, writing included), the pixels
computed (the rest interpolated), the relative MSE against the reference
(\`svet diff --metric relmse\`, the reference's noise not taken out) and
1 / (relMSE x seconds), larger is better (compare rows of one integrator
and sample count):

| render | spp | seconds | pixels computed | relMSE | 1 / (relMSE x s) |
|---|---:|---:|---|---:|---:|
$subtable

The path tracer's relMSE falls as 1 / spp; the cache's stops falling
where its interpolation error (the bias of a and of the clamp of R)
dominates: its relMSE at the largest sample count is its error floor.
Where the path tracer's pixels are noisy, neighbours differ by more than
a small threshold almost everywhere and nearly every pixel is computed;
a larger threshold interpolates more and blurs edges and noise alike.
The irradiance cache's image is smooth, so subsampling skips more of it.
END
echo "wrote $doc" >&2
