#!/bin/sh
# test_frames.sh - animations in svet render (render/animation.c,
# cmd/cmd_render.c): frame k rendered alone is the bits of frame k of a
# sequence (one thread against two); frame 0 of a keyless animation is the
# still scene rendered with seed ^ splitmix64(0) (the documented seed); a
# frame split by samples and by crop and merged is the frame rendered
# whole, and parts of two frames are refused; tools/render-frames.sh under
# GNU parallel gives the serial bits, whole frames and frames in parts
# (skipped with a message without parallel); the refusals of svet render
# and of render-frames.sh print their messages and overwrite nothing.
# Usage: sh tests/cmd/test_frames.sh build/float/svet
set -u
S=${1:?usage: test_frames.sh SVET}
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
fail=0
no() { echo "FAIL: $*"; fail=1; }
body='material white lambert rho 0.8
material red lambert rho 0.6 0.05 0.05
parallelogram c0 -1 -1 1  c1 1 -1 1  c2 1 -1 -1 c3 -1 -1 -1 material white
parallelogram c0 -1 -1 -1 c1 1 -1 -1 c2 1 1 -1  c3 -1 1 -1  material white
parallelogram c0 -1 -1 1  c1 -1 -1 -1 c2 -1 1 -1 c3 -1 1 1  material red
sphere centre 0.3 -0.6 0 radius 0.4 material white
parallelogram c0 -0.3 0.99 -0.3 c1 0.3 0.99 -0.3 c2 0.3 0.99 0.3 c3 -0.3 0.99 0.3 material white emit 12'
cat > "$T/a.scn" <<SCENE
camera position 0 0 3.9 target 0 0 0 up 0 1 0 fov 40 width 24 height 20
render spp 6 maxdepth 4 seed 5
animation frames 3
key 0 camera position -0.5 0.2 3.9
key 2 camera position 0.5 0 3 fov 45
$body
SCENE
R="$T/a.scn -q"
$S render $R --threads 2 -o "$T/seq-%d.exr" || no "the sequence"
[ "$($S render $R --frame-count)" = 3 ] || no "--frame-count is not 3"
[ "$($S render scenes/cbox.scn --frame-count)" = 0 ] ||
    no "--frame-count of a still scene is not 0"
for k in 2 0 1; do
    $S render $R --threads 1 --frame $k -o $T/one.exr || no "frame $k alone"
    for e in exr png; do
        cmp -s $T/seq-$k.$e $T/one-000$k.$e ||
            no "frame $k alone: its $e differs from the sequence's"
    done
done
cmp -s $T/seq-0.exr $T/seq-1.exr && no "frames 0 and 1 are the same image"
# the default name: -%04d before the extension
$S render $R --frames 1:2 -o $T/n.exr || no "--frames 1:2"
cmp -s $T/seq-1.exr $T/n-0001.exr || no "--frames 1:2 differs from frame 1"
[ -f $T/n-0000.exr ] && no "--frames 1:2 wrote frame 0"
# frame 0's seed is seed ^ splitmix64(0) = 5 ^ 0xe220a8397b1dcdaf
# = 16294208416658607530: the still scene's image at that seed
sed '/^animation/d; /^key/d' $T/a.scn > $T/still.scn
sed '/^key/d' $T/a.scn > $T/keyless.scn
$S render $T/still.scn -q --seed 16294208416658607530 -o $T/still.exr ||
    no "the still scene"
$S render $T/keyless.scn -q --frame 0 -o $T/keyless.exr ||
    no "the keyless animation"
cmp -s $T/still.exr $T/keyless-0000.exr ||
    no "frame 0 is not the still scene at seed ^ splitmix64(0)"
# frame 1 in 3 parts by samples, and in 2 by crop, merged: the whole frame
for r in 0:1 1:4 4:6; do
    $S render $R --frame 1 --samples $r -o "$T/s$r-%d.exr" ||
        no "frame 1 samples $r"
done
$S merge "$T/s0:1-1.exr" "$T/s4:6-1.exr" "$T/s1:4-1.exr" -o $T/ms.exr ||
    no "merge by samples"
cmp -s $T/seq-1.exr $T/ms.exr || no "frame 1 by samples: EXR differs"
cmp -s $T/seq-1.png $T/ms.png || no "frame 1 by samples: PNG differs"
$S render $R --frame 1 --crop 0:24,0:9 -o "$T/c0-%d.exr" || no "crop 0"
$S render $R --frame 1 --crop 0:24,9:20 -o "$T/c1-%d.exr" || no "crop 1"
$S merge $T/c0-1.exr $T/c1-1.exr -o $T/mc.exr || no "merge by crop"
cmp -s $T/seq-1.exr $T/mc.exr || no "frame 1 by crop: EXR differs"
$S render $R --frame 2 --samples 1:6 -o "$T/f2-%d.exr" || no "frame 2 part"
refuse() { # WHAT MESSAGE ARGS...
    what=$1; msg=$2; shift 2
    if "$S" "$@" 2>$T/err; then no "$what accepted"; fi
    grep -qF -- "$msg" $T/err || no "$what: no '$msg' in: $(cat $T/err)"
}
refuse "parts of two frames" "different scenes, seeds or settings" \
    merge "$T/s0:1-1.exr" $T/f2-2.exr -o $T/x.exr
# the refusals: nothing rendered, nothing overwritten
for k in 0 2 3; do echo keep > $T/keep-000$k.exr; done
refuse "a frame out of range" "--frame 3: the animation has frames 0..2" \
    render $R --frame 3 -o $T/keep.exr
refuse "frames out of range" "--frames 2:5: the animation has frames 0..2" \
    render $R --frames 2:5 -o $T/keep.exr
refuse "one frame out of range by --frames" \
    "--frames 3:4: the animation has frames 0..2" \
    render $R --frames 3:4 -o $T/keep.exr
refuse "an empty --frames" "bad value" render $R --frames 2:2 -o $T/keep.exr
refuse "a bad --frame" "bad value" render $R --frame x -o $T/keep.exr
refuse "--frame of a still scene" "the scene has no animation" \
    render $T/still.scn --frame 0 -o $T/keep.exr
refuse "a bad pattern" "is a bad frame pattern: a '%' starts" \
    render $R -o "$T/keep-%s.exr"
refuse "two frame numbers" "two frame numbers" render $R -o "$T/keep-%d-%d.exr"
refuse "a bad --png pattern" "the PNG output '$T/k%x.png' is a bad frame pattern" \
    render $R -o $T/keep.exr --png "$T/k%x.png"
cat > "$T/bad.scn" <<SCENE
camera position 0 0 3.9 target 0 0 0
animation frames 3
key 0 camera position 0 0 -1
key 2 camera position 0 0 1
$body
SCENE
refuse "a frame without an image" "frame 1: " render $T/bad.scn -q -o $T/keep.exr
for k in 0 2 3; do
    [ "$(cat $T/keep-000$k.exr)" = keep ] ||
        no "a refusal overwrote keep-000$k.exr"
done
# tools/render-frames.sh: GNU parallel, one frame per job, then two parts
# of each frame merged per frame: the serial bits
if command -v parallel >/dev/null; then
    SVET=$S sh tools/render-frames.sh $T/a.scn "$T/par-%d.exr" -j 2 -- \
        --threads 1 || no "render-frames.sh"
    SVET=$S FRAMES=1:3 PARTS=2 SPP=6 sh tools/render-frames.sh $T/a.scn \
        "$T/pp-%d.exr" -j 2 -- --threads 1 || no "render-frames.sh in parts"
    for k in 0 1 2; do
        cmp -s $T/seq-$k.exr $T/par-$k.exr ||
            no "render-frames.sh: frame $k differs"
    done
    for k in 1 2; do
        cmp -s $T/seq-$k.exr $T/pp-$k.exr ||
            no "render-frames.sh in parts: frame $k differs"
    done
    [ -f $T/pp-0.exr ] && no "render-frames.sh FRAMES=1:3 rendered frame 0"
    # its refusals, before anything runs
    script() { # WHAT MESSAGE ENV...
        what=$1; msg=$2; shift 2
        if env SVET=$S "$@" sh tools/render-frames.sh $T/a.scn \
            "$T/sr-%d.exr" -- --threads 1 2>$T/err; then
            no "render-frames.sh: $what accepted"
        fi
        grep -qF -- "$msg" $T/err ||
            no "render-frames.sh: $what: no '$msg' in: $(cat $T/err)"
    }
    script "an empty FRAMES" "FRAMES=2:2: expected A:B" FRAMES=2:2
    script "a FRAMES without B" "FRAMES=1: expected A:B" FRAMES=1
    script "PARTS=0" "PARTS=0: expected a whole number of parts" PARTS=0
    script "more parts than samples" "SPP=2: expected a whole number of \
samples, at least PARTS=3" PARTS=3 SPP=2
    script "a frame out of range" "--frame 3: the animation has frames 0..2" \
        FRAMES=3:4
    ls $T/sr-* >/dev/null 2>&1 && no "a refusal of render-frames.sh wrote a frame"
else
    echo "test_frames: render-frames.sh skipped: GNU parallel is not installed"
fi
[ $fail = 0 ] && echo "test_frames: all passed"
exit $fail
