#!/bin/sh
# bench-prepass.sh - what the global pre-pass costs a split render
# (scenes/README.md, "Split renders"; bench/results/scale.md): for each
# scene with a pre-pass (the photon maps of ch. 8 on scenes/caustic.scn,
# the irradiance cache of ch. 9 on scenes/cbox-irradiance.scn, the volume
# photon map of ch. 11 on scenes/smoky-cbox.scn) one render gives the
# set-up and sampling seconds of its summary line, wall and CPU. Then the
# set-up of a part that does not compute the pre-pass: for photon, which
# saves its maps, measured (svet render --load-prepass of the maps a
# render with --save-prepass wrote, whose set-up, the write included, is
# the first part's); for the others, which do not save theirs, the set-up of the
# method without a pre-pass (path, volpath: scene checks, acceleration
# structure), an estimate without the file's writing and reading. From
# them, in CPU seconds, N parts cost
#   repeated in every part:  N * setup + sampling
#   computed once and read:  first + (N - 1) * read + sampling
# (first: the set-up with --save-prepass, for photon; setup for others)
# Usage: sh tools/bench-prepass.sh SVET [SPP] [THREADS]
#        (make bench-prepass [PREPASS_SPP=16] [THREADS=2])
set -u
S=${1:?usage: bench-prepass.sh SVET [SPP] [THREADS]}
SPP=${2:-16}
TH=${3:-2}
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
load() { cut -d' ' -f1 /proc/loadavg; }
# secs OPTS...: "sampling-wall sampling-cpu setup-wall setup-cpu" from
# the summary line of svet render OPTS
secs() {
    $S render "$@" --threads $TH -o $T/x.exr 2>$T/err || {
        cat $T/err >&2; exit 1; }
    sed -n 's/.* spp in \([0-9.]*\) s (\([0-9.]*\) CPU-s) after \([0-9.]*\) s (\([0-9.]*\) CPU-s) of set-up.*/\1 \2 \3 \4/p' $T/err
}
rows=""
for c in "photon scenes/caustic.scn load" \
         "irradiance scenes/cbox-irradiance.scn path" \
         "volphoton scenes/smoky-cbox.scn volpath"; do
    set -- $c
    la=$(load)
    m=$(secs $2 --spp $SPP --set integrator=$1) || exit 1
    if [ $3 = load ]; then
        w=$(secs $2 --spp 1 --set integrator=$1 --save-prepass $T/pre) || exit 1
        b=$(secs $2 --spp 1 --set integrator=$1 --load-prepass $T/pre) || exit 1
        how="measured: --load-prepass of $(wc -c < $T/pre) bytes"
    else
        w=$m
        b=$(secs $2 --spp 1 --set integrator=$3) || exit 1
        how="estimate: the set-up of $3"
    fi
    [ -n "$m" ] && [ -n "$b" ] || { echo "bench-prepass: no summary line from svet render $2" >&2; exit 1; }
    echo "bench-prepass: $2 $1: $m; without computing the pre-pass: $b; load $la to $(load)" >&2
    # the first part's set-up: with --save-prepass where it saves
    rows="$rows$2|$1|$how|$m $b $la $(load) $(echo $w | cut -d' ' -f4)
"
done
echo "| scene, method | set-up CPU-s (wall s) | set-up of a part that reads the pre-pass, CPU-s (wall s) | sampling CPU-s (wall s), $SPP spp | 2 parts, CPU-s: repeated / once | 4 parts | 8 parts | load average (1 min) at start, end |"
echo "|:---|---:|---:|---:|---:|---:|---:|:---|"
printf '%s' "$rows" | awk -F'|' '{
    split($4, v, " ")
    # v[1..4]: sampling wall, CPU, set-up wall, CPU of the full render;
    # v[7], v[8]: set-up wall, CPU of a part that does not compute it
    su = v[4]; rd = v[8]; smp = v[2]; first = v[11]
    line = sprintf("| %s, %s | %.2f (%.2f) | %.2f (%.2f; %s) | %.2f (%.2f) |",
                   $1, $2, v[4], v[3], v[8], v[7], $3, v[2], v[1])
    for (n = 2; n <= 8; n *= 2)
        line = line sprintf(" %.2f / %.2f |", n * su + smp,
                            first + (n - 1) * rd + smp)
    printf "%s %s, %s |\n", line, v[9], v[10] }'
