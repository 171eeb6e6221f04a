#!/bin/sh
# bench-scale.sh - the overhead of a split render (README: renders over
# several machines): the Cornell box (or SCENE) rendered once, then split
# by samples into 2, 4 and 8 parts run one after another on this machine
# and merged (svet merge). Prints a markdown table: the parts' time plus
# the merge's over the single render's, in wall seconds and in CPU
# seconds (user + system of the svet processes, from /usr/bin/time), the
# merge alone, the size of one part file, and whether the merged EXR is
# the single render's bytes (cmp). On a shared machine the wall clock
# carries the other users' load; the CPU seconds count only svet's own
# work, so their ratio is the one that measures the split.
# SCENE and OPTS (svet render options, e.g. "--set integrator=irradiance")
# measure another scene or method: a method with a pre-pass (photon maps,
# the irradiance cache) computes it in every part, and the ratio shows
# what that costs. The load average printed beside each row says how
# idle the machine was.
# Usage: sh tools/bench-scale.sh SVET [SPP] [THREADS] [SCENE] [OPTS]
#        (make bench-scale [SCALE_SPP=N] [THREADS=T] [SCALE_SCENE=F]
#         [SCALE_OPTS="..."])
set -u
S=${1:?usage: bench-scale.sh SVET [SPP] [THREADS] [SCENE] [OPTS]}
SPP=${2:-4096}
TH=${3:-2}
SCENE=${4:-scenes/cbox.scn}
OPTS=${5:-}
[ -x /usr/bin/time ] || { echo "bench-scale: needs /usr/bin/time (Debian: apt-get install time)" >&2; exit 1; }
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
A="$SCENE $OPTS --spp $SPP -q --threads $TH"
load() { cut -d' ' -f1 /proc/loadavg; }
# run FILE CMD...: runs CMD under /usr/bin/time and appends "wall cpu"
# (CPU = user + system seconds of CMD and its children) to FILE.
run() {
    f=$1; shift
    /usr/bin/time -f '%e %U %S' -o $T/time "$@" || exit 1
    awk '{ printf "%s %.2f\n", $1, $2 + $3 }' $T/time >> "$f"
}
# sum FILE: "wall cpu" summed over the lines of FILE.
sum() { awk '{ w += $1; c += $2 } END { printf "%.2f %.2f", w, c }' "$1"; }
single() {
    : > $T/s$1
    run $T/s$1 $S render $A -o $T/full$1.exr
    sum $T/s$1
}
# The single render runs before and after the parts and its mean is the
# reference: on a shared machine the load drifts over the run, and the
# mean of both ends cancels a steady drift to first order.
l0=$(load)
s0=$(single 0) && [ -n "$s0" ] || exit 1
echo "bench-scale: single render (wall, CPU s) $s0, load $l0 to $(load)" >&2
rows=""
for n in 2 4 8; do
    list=""; i=0
    la=$(load)
    : > $T/r$n; : > $T/m$n
    while [ $i -lt $n ]; do
        f=$((SPP * i / n)); t=$((SPP * (i + 1) / n))
        run $T/r$n $S render $A --samples $f:$t -o $T/p$n-$i.exr
        list="$list $T/p$n-$i.exr"; i=$((i + 1))
    done
    run $T/m$n $S merge $list -o $T/m$n.exr
    same=no; cmp -s $T/full0.exr $T/m$n.exr && same=yes
    bytes=$(wc -c < $T/p$n-0.exr.part)
    # n, parts wall, parts CPU, merge wall, merge CPU, bytes, same, loads
    rows="$rows$n $(sum $T/r$n) $(sum $T/m$n) $bytes $same $la $(load)
"
    echo "$n $(sum $T/r$n) $(sum $T/m$n) $la $(load)" | awk '{ printf "bench-scale: %d parts %.2f s (CPU %.2f s), merge %.2f s (CPU %.2f s), load %s to %s\n", $1, $2 + $4, $3 + $5, $4, $5, $6, $7 }' >&2
done
l1=$(load)
s1=$(single 1) && [ -n "$s1" ] || exit 1
cmp -s $T/full0.exr $T/full1.exr || { echo "bench-scale: the two single renders differ" >&2; exit 1; }
echo "| parts | wall s (parts + merge) | over the single, wall | CPU s (parts + merge) | over the single, CPU | merge wall s | merge CPU s | bytes of one part file | merged = single | load average (1 min) at start, end |"
echo "|---:|---:|---:|---:|---:|---:|---:|---:|:---|:---|"
echo "$s0 $s1 $l0 $l1" | awk '{ printf "| 1 (single render, mean of %s s / %s CPU-s before and %s s / %s CPU-s after) | %.2f | 1 | %.2f | 1 | | | | | %s, %s |\n", $1, $2, $3, $4, ($1 + $3) / 2, ($2 + $4) / 2, $5, $6 }'
printf '%s' "$rows" | awk -v sw=$(echo "$s0 $s1" | awk '{ print ($1 + $3) / 2 }') \
    -v sc=$(echo "$s0 $s1" | awk '{ print ($2 + $4) / 2 }') '{
    w = $2 + $4; c = $3 + $5
    printf "| %d | %.2f | %.3f | %.2f | %.3f | %.2f | %.2f | %d | %s | %s, %s |\n",
           $1, w, w / sw, c, c / sc, $4, $5, $6, $7, $8, $9 }'
