#!/bin/sh
# bench-prepass.sh - what the global pre-pass costs a split render
# (scenes/README.md, "Split renders"; bench/results/scale.md): for each
# scene with a pre-pass (the photon maps of ch. 8 on scenes/caustic.scn,
# the irradiance cache of ch. 9 on scenes/cbox-irradiance.scn, the volume
# photon map of ch. 13 on scenes/smoky-cbox.scn) one render gives the
# set-up and sampling seconds of its summary line, wall and CPU; a render
# of one sample by the method without a pre-pass (path, volpath) gives the
# rest of the set-up (scene checks, acceleration structure), which every
# part pays either way. From them, in CPU seconds, N parts cost
#   repeated in every part:  N * setup + sampling
#   computed once and read:  N * rest + (setup - rest) + sampling
# (the second without the time to write and read the saved pre-pass).
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
for c in "photon scenes/caustic.scn path" \
         "irradiance scenes/cbox-irradiance.scn path" \
         "volphoton scenes/smoky-cbox.scn volpath"; do
    set -- $c
    la=$(load)
    m=$(secs $2 --spp $SPP --set integrator=$1) || exit 1
    b=$(secs $2 --spp 1 --set integrator=$3) || exit 1
    [ -n "$m" ] && [ -n "$b" ] || { echo "bench-prepass: no summary line from svet render $2" >&2; exit 1; }
    echo "bench-prepass: $2 $1: $m; $3: $b; load $la to $(load)" >&2
    rows="$rows$2 $1 $m $b $la $(load)
"
done
echo "| scene, method | set-up s (CPU-s) | of it the rest (CPU-s) | sampling s (CPU-s), $SPP spp | 2 parts, CPU-s: repeated / once | 4 parts | 8 parts | load average (1 min) at start, end |"
echo "|:---|---:|---:|---:|---:|---:|---:|:---|"
printf '%s' "$rows" | awk '{
    # $3..$6: sampling wall, cpu, set-up wall, cpu; $9, $10: the rest
    # of the set-up, wall and CPU (from the method without a pre-pass)
    su = $6; rest = $10; smp = $4
    if (rest > su) rest = su
    line = sprintf("| %s, %s | %.2f (%.2f) | %.2f (%.2f) | %.2f (%.2f) |",
                   $1, $2, $5, $6, $9, $10, $3, $4)
    for (n = 2; n <= 8; n *= 2)
        line = line sprintf(" %.2f / %.2f |", n * su + smp,
                            n * rest + (su - rest) + smp)
    printf "%s %s, %s |\n", line, $11, $12 }'
