#!/bin/sh
# ab-grid.sh - `make ab-grid BASE=COMMIT`: the grid's speed against an
# earlier commit's, in runs that alternate between the two builds, so that
# the machine's drift (another job, the host's load) falls on both alike.
# For each kind of ray, PAIRS
# pairs of `bench_grid --trace KIND --passes PASSES` (the best pass of
# each run, Mrays/s at one thread), which goes first alternating, then
# each pair's ratio (this build over the base) and their mean. The base
# is built in a temporary worktree with the same flags; it needs
# bench_grid's --trace (commit da979c5 on).
# usage: tools/ab-grid.sh BENCH_GRID_BINARY BASE_COMMIT [KINDS] [PAIRS] [PASSES]
#   KINDS: camera, packets4, packets8, incoherent, comma-separated
#          (default incoherent,camera,packets8); PAIRS 6; PASSES 5
set -eu
bin=$1
base=$2
kinds=${3:-incoherent,camera,packets8}
pairs=${4:-6}
passes=${5:-5}
[ -x "$bin" ] || { echo "ab-grid: no binary $bin" >&2; exit 1; }
git rev-parse --verify --quiet "$base^{commit}" >/dev/null ||
    { echo "ab-grid: '$base' is not a commit" >&2; exit 1; }
wt=$(mktemp -d "${TMPDIR:-/tmp}/svet-ab.XXXXXX")
trap 'git worktree remove --force "$wt" >/dev/null 2>&1 || true; rm -rf "$wt"' EXIT
git worktree add --detach --quiet "$wt" "$base"
echo "ab-grid: building bench_grid at $base in $wt" >&2
make -C "$wt" -j2 build/float/bench/bench_grid >"$wt/build.log" 2>&1 ||
    { echo "ab-grid: the base did not build ($wt/build.log)" >&2; exit 1; }
old="$wt/build/float/bench/bench_grid"
"$old" --trace camera --passes 1 >/dev/null 2>&1 ||
    { echo "ab-grid: the base's bench_grid has no --trace (before da979c5)" >&2; exit 1; }
rate() { # binary kind -> Mrays/s of the best pass
    OMP_WAIT_POLICY=passive "$1" --trace "$2" --passes "$passes" |
        sed -n 's/.* \([0-9.]*\) Mrays\/s$/\1/p'
}
echo "| rays | base Mrays/s | this build | ratio |"
echo "|---|---:|---:|---:|"
for kind in $(echo "$kinds" | tr ',' ' '); do
    sum=0
    i=1
    while [ "$i" -le "$pairs" ]; do
        if [ $((i % 2)) -eq 1 ]; then
            a=$(rate "$old" "$kind"); b=$(rate "$bin" "$kind")
        else
            b=$(rate "$bin" "$kind"); a=$(rate "$old" "$kind")
        fi
        [ -n "$a" ] && [ -n "$b" ] ||
            { echo "ab-grid: no rate from --trace $kind" >&2; exit 1; }
        r=$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.3f", b / a }')
        sum=$(awk -v s="$sum" -v r="$r" 'BEGIN { print s + r }')
        echo "| $kind | $a | $b | $r |"
        i=$((i + 1))
    done
    awk -v s="$sum" -v n="$pairs" -v k="$kind" \
        'BEGIN { printf "| %s, mean of %d pairs | | | %.3f |\n", k, n, s / n }'
done
