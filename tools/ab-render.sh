#!/bin/sh
# ab-render.sh - `make ab-render BASE=COMMIT`: the Cornell box's speed
# against an earlier commit's, in runs that alternate between the two
# builds, so that the machine's drift (another job, the host's load) falls
# on both alike. For each thread count, PAIRS pairs of `svet render
# scenes/cbox.scn --spp SPP` (camera samples per second from the
# summary line, and per CPU-second of the process from /usr/bin/time),
# which goes first alternating, then each pair's ratios (this build over
# the base) and their means. The base is built from `git archive` in a
# scratch directory with the same REAL and SIMD=on (or BASE_SVET names
# its binary, built already); the images are compared byte for byte.
# usage: tools/ab-render.sh SVET_BINARY BASE_COMMIT [THREADS] [PAIRS] [SPP]
#   THREADS: comma-separated (default 1,2); PAIRS 6; SPP 16
set -eu
bin=$1
base=$2
threads=${3:-1,2}
pairs=${4:-6}
spp=${5:-16}
real=${REAL:-float}
[ -x "$bin" ] || { echo "ab-render: no binary $bin" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "ab-render: needs /usr/bin/time (apt-get install time)" >&2; exit 1; }
dir=$(mktemp -d "${TMPDIR:-/tmp}/svet-ab-render.XXXXXX")
trap 'rm -rf "$dir"' EXIT
if [ -n "${BASE_SVET:-}" ]; then # the base's binary, built already
    old=$BASE_SVET
else
    mkdir "$dir/base"
    git archive "$base" | tar -x -C "$dir/base" ||
        { echo "ab-render: '$base' is not a commit" >&2; exit 1; }
    echo "ab-render: building svet ($real) at $base in $dir/base" >&2
    make -C "$dir/base" -j2 REAL="$real" "build/$real/svet" >"$dir/build.log" 2>&1 ||
        { echo "ab-render: the base did not build ($dir/build.log)" >&2; exit 1; }
    old="$dir/base/build/$real/svet"
fi
rate() { # binary threads tag -> "samples/s samples-per-CPU-second"
    OMP_WAIT_POLICY=passive /usr/bin/time -f 'cpu %U %S' -o "$dir/time" \
        "$1" render scenes/cbox.scn --spp "$spp" --threads "$2" \
        -o "$dir/$3.exr" 2>"$dir/log" >/dev/null
    s=$(sed -n 's/.* \([0-9.e+]*\) samples\/s.*/\1/p' "$dir/log")
    awk -v s="$s" -v n="$spp" '/^cpu/ { printf "%s %.4g\n", s, 65536 * n / ($2 + $3) }' "$dir/time"
}
echo "| threads | base samples/s | this build | ratio | base per CPU-s | this build | ratio |"
echo "|---:|---:|---:|---:|---:|---:|---:|"
for t in $(echo "$threads" | tr ',' ' '); do
    sum=0
    sumc=0
    i=1
    while [ "$i" -le "$pairs" ]; do
        if [ $((i % 2)) -eq 1 ]; then
            a=$(rate "$old" "$t" a); b=$(rate "$bin" "$t" b)
        else
            b=$(rate "$bin" "$t" b); a=$(rate "$old" "$t" a)
        fi
        cmp -s "$dir/a.exr" "$dir/b.exr" ||
            { echo "ab-render: the images differ ($t threads)" >&2; exit 1; }
        line=$(echo "$a $b" | awk '{ printf "%s %s %.3f %s %s %.3f", $1, $3, $3 / $1, $2, $4, $4 / $2 }')
        echo "$line" | awk -v t="$t" '{ printf "| %s | %s | %s | %s | %s | %s | %s |\n", t, $1, $2, $3, $4, $5, $6 }'
        sum=$(echo "$line" | awk -v s="$sum" '{ print s + $3 }')
        sumc=$(echo "$line" | awk -v s="$sumc" '{ print s + $6 }')
        i=$((i + 1))
    done
    awk -v s="$sum" -v c="$sumc" -v n="$pairs" -v t="$t" \
        'BEGIN { printf "| %s, mean of %d pairs | | | %.3f | | | %.3f |\n", t, n, s / n, c / n }'
done
