#!/bin/sh
# bench-scale.sh - the overhead of a split render (README: renders over
# several machines): the Cornell box (or SCENE) rendered once, then split
# by samples into 2, 4 and 8 parts run one after another on this machine
# and merged (svet merge). Prints a markdown table: the parts' time plus
# the merge's over the single render's, the merge alone, the size of one
# part file, and whether the merged EXR is the single render's bytes (cmp).
# SCENE and OPTS (svet render options, e.g. "--set integrator=irradiance")
# measure another scene or method: a method with a pre-pass (photon maps,
# the irradiance cache) computes it in every part, and the ratio shows
# what that costs. The default, 4096 samples of the Cornell box rendered
# five times over, is meant for an otherwise idle machine (rates are what
# it measures); the load average printed beside each row says how idle.
# Usage: sh tools/bench-scale.sh SVET [SPP] [THREADS] [SCENE] [OPTS]
#        (make bench-scale [SCALE_SPP=N] [THREADS=T] [SCALE_SCENE=F]
#         [SCALE_OPTS="..."])
set -u
S=${1:?usage: bench-scale.sh SVET [SPP] [THREADS] [SCENE] [OPTS]}
SPP=${2:-4096}
TH=${3:-2}
SCENE=${4:-scenes/cbox.scn}
OPTS=${5:-}
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
A="$SCENE $OPTS --spp $SPP -q --threads $TH"
now() { date +%s.%N; }
load() { cut -d' ' -f1 /proc/loadavg; }
single() {
    t0=$(now)
    $S render $A -o $T/full$1.exr || exit 1
    t1=$(now)
    echo "$t0 $t1" | awk '{ printf "%.2f", $2 - $1 }'
}
# The single render runs before and after the parts and its mean is the
# reference: on a shared machine the load drifts over the run, and the
# mean of both ends cancels a steady drift to first order.
l0=$(load)
s0=$(single 0)
echo "bench-scale: single render $s0 s, load $l0 to $(load)" >&2
rows=""
for n in 2 4 8; do
    list=""; i=0
    la=$(load)
    t0=$(now)
    while [ $i -lt $n ]; do
        f=$((SPP * i / n)); t=$((SPP * (i + 1) / n))
        $S render $A --samples $f:$t -o $T/p$n-$i.exr || exit 1
        list="$list $T/p$n-$i.exr"; i=$((i + 1))
    done
    tm=$(now)
    $S merge $list -o $T/m$n.exr || exit 1
    t1=$(now)
    same=no; cmp -s $T/full0.exr $T/m$n.exr && same=yes
    bytes=$(wc -c < $T/p$n-0.exr.part)
    rows="$rows$n $t0 $tm $t1 $bytes $same $la $(load)
"
    echo "$n $t0 $tm $t1 $la $(load)" | awk '{ printf "bench-scale: %d parts %.2f s, merge %.2f s, load %s to %s\n", $1, $4 - $2, $4 - $3, $5, $6 }' >&2
done
l1=$(load)
s1=$(single 1)
cmp -s $T/full0.exr $T/full1.exr || { echo "bench-scale: the two single renders differ" >&2; exit 1; }
single=$(echo "$s0 $s1" | awk '{ printf "%.2f", ($1 + $2) / 2 }')
echo "| parts | seconds (parts + merge) | over the single render | merge seconds | bytes of one part file | merged = single | load average (1 min) at start, end |"
echo "|---:|---:|---:|---:|---:|:---|:---|"
echo "| 1 (single render, mean of $s0 before and $s1 after) | $single | 1 | | | | $l0, $l1 |"
printf '%s' "$rows" | awk -v s=$single '{
    printf "| %d | %.2f | %.3f | %.2f | %d | %s | %s, %s |\n", $1, $4 - $2,
           ($4 - $2) / s, $4 - $3, $5, $6, $7, $8 }'
