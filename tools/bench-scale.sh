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
# four times over, is meant for an otherwise idle machine (rates are what
# it measures).
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
t0=$(now)
$S render $A -o $T/full.exr || exit 1
t1=$(now)
single=$(echo "$t0 $t1" | awk '{ printf "%.2f", $2 - $1 }')
echo "| parts | seconds (parts + merge) | over the single render | merge seconds | bytes of one part file | merged = single |"
echo "|---:|---:|---:|---:|---:|:---|"
echo "| 1 (single render) | $single | 1 | | | |"
for n in 2 4 8; do
    list=""; i=0
    t0=$(now)
    while [ $i -lt $n ]; do
        f=$((SPP * i / n)); t=$((SPP * (i + 1) / n))
        $S render $A --samples $f:$t -o $T/p$n-$i.exr || exit 1
        list="$list $T/p$n-$i.exr"; i=$((i + 1))
    done
    tm=$(now)
    $S merge $list -o $T/m$n.exr || exit 1
    t1=$(now)
    same=no; cmp -s $T/full.exr $T/m$n.exr && same=yes
    bytes=$(wc -c < $T/p$n-0.exr.part)
    echo "$t0 $tm $t1 $single" | awk -v n=$n -v b=$bytes -v s=$same '{
        printf "| %d | %.2f | %.3f | %.2f | %d | %s |\n", n, $3 - $1,
               ($3 - $1) / $4, $3 - $2, b, s }'
done
