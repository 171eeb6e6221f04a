#!/bin/sh
# render-frames.sh - an animation (scenes/README.md, "Animations") with GNU
# parallel: one frame per job, or PARTS parts of each frame by samples and
# then svet merge per frame. Usage:
#   tools/render-frames.sh SCENE OUT.exr [parallel options, e.g.
#       --sshlogin 4/host1,4/host2 --workdir . -j 2] -- [svet render options]
# OUT.exr is the frame pattern of svet render: one %d, %Nd or %0Nd is the
# frame number (out/orbit-%04d.exr); a name without one gets -%04d before
# .exr, as svet render does. From the environment: SVET (default
# build/float/svet), FRAMES=A:B (frames A..B-1; default all, from svet
# render --frame-count), PARTS (default 1) and, when PARTS > 1, SPP (the
# samples per pixel, split as render-parallel.sh splits them; at least
# PARTS, so that no part is empty). A bad FRAMES, PARTS or SPP is refused
# with a message before anything runs. SVET, the
# scene and the outputs must be at the same paths on every host (a shared
# file system): the merges run here.
# Tests: tests/cmd/test_frames.sh
set -eu
SCENE=${1:?usage: render-frames.sh SCENE OUT.exr [parallel opts] [-- render opts]}
OUT=${2:?OUT.exr}; shift 2
SVET=${SVET:-build/float/svet}
PARTS=${PARTS:-1}
popts=""
while [ $# -gt 0 ] && [ "$1" != -- ]; do popts="$popts $1"; shift; done
[ $# -gt 0 ] && shift
die() { echo "render-frames.sh: $*" >&2; exit 1; }
command -v parallel >/dev/null || die "GNU parallel is not installed"
count() { case $1 in ''|*[!0-9]*) return 1 ;; esac; }
count "$PARTS" && [ "$PARTS" -ge 1 ] ||
    die "PARTS=$PARTS: expected a whole number of parts, 1 or more"
case $OUT in *%*) ;; *.exr) OUT="${OUT%.exr}-%04d.exr" ;; *) OUT="$OUT-%04d" ;; esac
if [ -n "${FRAMES:-}" ]; then
    a=${FRAMES%%:*}; b=${FRAMES#*:}
    count "$a" && count "$b" && [ "$a" -lt "$b" ] ||
        die "FRAMES=$FRAMES: expected A:B, the frames A..B-1 (A < B)"
else
    a=0; b=$("$SVET" render "$SCENE" "$@" --frame-count) || exit 2
    [ "$b" -gt 0 ] || { echo "render-frames.sh: $SCENE has no animation" >&2; exit 1; }
fi
if [ "$PARTS" -le 1 ]; then
    # shellcheck disable=SC2086
    exec parallel $popts "$SVET" render "$SCENE" --frame {} -q "$@" -o "$OUT" \
        ::: $(seq "$a" $((b - 1)))
fi
SPP=${SPP:?set SPP to the samples per pixel to split a frame in PARTS}
count "$SPP" && [ "$SPP" -ge "$PARTS" ] ||
    die "SPP=$SPP: expected a whole number of samples, at least PARTS=$PARTS"
base=${OUT%.exr}
list=$(mktemp)
trap 'rm -f "$list"' EXIT
f=$a
while [ "$f" -lt "$b" ]; do
    k=0
    while [ "$k" -lt "$PARTS" ]; do
        echo "$f $((SPP * k / PARTS)) $((SPP * (k + 1) / PARTS)) $k"
        k=$((k + 1))
    done
    f=$((f + 1))
done > "$list"
# shellcheck disable=SC2086
parallel $popts --colsep ' ' "$SVET" render "$SCENE" --frame {1} --spp "$SPP" \
    --samples {2}:{3} -q "$@" -o "$base.part-{4}.exr" :::: "$list"
f=$a
while [ "$f" -lt "$b" ]; do
    parts=""; k=0
    while [ "$k" -lt "$PARTS" ]; do
        # shellcheck disable=SC2059
        parts="$parts $(printf "$base.part-$k.exr" "$f")"; k=$((k + 1))
    done
    # shellcheck disable=SC2059,SC2086
    "$SVET" merge $parts -o "$(printf "$OUT" "$f")"
    f=$((f + 1))
done
