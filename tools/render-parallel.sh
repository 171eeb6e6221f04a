#!/bin/sh
# render-parallel.sh - a split render with GNU parallel, then svet merge
# (scenes/README.md, "Split renders"). Usage:
#   tools/render-parallel.sh SCENE PARTS OUT.exr [parallel options, e.g.
#       --sshlogin 4/host1,4/host2 --workdir .] -- [svet render options]
# Part k of PARTS renders samples [spp*k/PARTS, spp*(k+1)/PARTS); SVET
# (default build/float/svet) and the scene must be at the same path on
# every host; SPP at least PARTS, so that no part is empty (else refused
# before anything runs). Tests: tests/cmd/test_render_parallel.sh
set -eu
SCENE=${1:?usage: render-parallel.sh SCENE PARTS OUT.exr [opts] [-- render opts]}
PARTS=${2:?PARTS}; OUT=${3:?OUT.exr}; shift 3
SVET=${SVET:-build/float/svet}
SPP=${SPP:?set SPP to the samples per pixel}
popts=""
while [ $# -gt 0 ] && [ "$1" != -- ]; do popts="$popts $1"; shift; done
[ $# -gt 0 ] && shift
die() { echo "render-parallel.sh: $*" >&2; exit 1; }
command -v parallel >/dev/null || die "GNU parallel is not installed"
count() { case $1 in ''|*[!0-9]*) return 1 ;; esac; }
count "$PARTS" && [ "$PARTS" -ge 1 ] ||
    die "PARTS=$PARTS: expected a whole number of parts, 1 or more"
count "$SPP" && [ "$SPP" -ge "$PARTS" ] ||
    die "SPP=$SPP: expected a whole number of samples, at least PARTS=$PARTS"
k=0; ranges=""
while [ $k -lt "$PARTS" ]; do
    ranges="$ranges $((SPP * k / PARTS)):$((SPP * (k + 1) / PARTS))"; k=$((k + 1))
done
# shellcheck disable=SC2086
parallel $popts "$SVET" render "$SCENE" --spp "$SPP" --samples {} -q "$@" \
    -o "$OUT.part-{#}.exr" ::: $ranges
k=1; parts=""
while [ $k -le "$PARTS" ]; do parts="$parts $OUT.part-$k.exr"; k=$((k + 1)); done
# shellcheck disable=SC2086
"$SVET" merge $parts -o "$OUT"
