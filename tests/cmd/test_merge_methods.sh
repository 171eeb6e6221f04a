#!/bin/sh
# test_merge_methods.sh - split renders of the Part II rendering methods
# (scenes/README.md, "Split renders"; cmd/cmd_render.c, cmd/cmd_merge.c):
# for photon and ppm (ch. 8), irradiance (ch. 9), volpath on a homogeneous
# medium and on a grid (.vol), and volsingle (ch. 11), 1, 2, 3 and 7 parts
# by samples and 4 by crop merge to the EXR, PNG and variance of the single
# render bit for bit (the independent reference: one render of all the
# samples, with another thread count than the parts'). The pre-passes
# (photon maps, the irradiance cache) are computed in each part from the
# scene and seed alone, over the whole image whatever the crop, so every
# part has the single render's; the parts of a scene with another photon
# count or cache setting are refused with their message.
# Usage: sh tests/cmd/test_merge_methods.sh build/float/svet
set -u
S=${1:?usage: test_merge_methods.sh SVET}
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
fail=0
no() { echo "FAIL: $*"; fail=1; }
# the parts alternate 1 and 2 threads; the single render has 2
th() { echo $(($1 % 2 + 1)); }
# check NAME WHAT ARGS...: the method's summary line, then the splits of 7
# samples of a 32 x 24 image
check() {
    name=$1; what=$2; shift 2
    A="$* --spp 7 --set resolution=32x24"
    $S render $A --threads 2 -o $T/$name.exr --variance $T/${name}v.exr \
        2>$T/log || no "$name: single render"
    grep -qF "; $what" $T/log || no "$name: the summary does not name '$what'"
    for n in 1 2 3 7; do
        list=""; i=0
        while [ $i -lt $n ]; do
            f=$((7 * i / n)); t=$((7 * (i + 1) / n))
            $S render $A -q --threads $(th $i) --samples $f:$t \
                -o $T/$name-p$n-$i.exr || no "$name: part $f:$t"
            list="$T/$name-p$n-$i.exr $list"; i=$((i + 1)) # last first
        done
        $S merge $list -o $T/$name-m$n.exr --variance $T/$name-m${n}v.exr ||
            no "$name: merge of $n"
        for e in .exr .png v.exr; do
            cmp -s $T/$name$e $T/$name-m$n$e ||
                no "$name: $n parts by samples: $e differs"
        done
    done
    list=""; i=0
    for c in 0:16,0:12 16:32,0:12 0:16,12:24 16:32,12:24; do
        $S render $A -q --threads $(th $i) --crop $c -o $T/$name-c$i.exr ||
            no "$name: crop $c"
        list="$list $T/$name-c$i.exr"; i=$((i + 1))
    done
    $S merge $list -o $T/$name-mc.exr --variance $T/$name-mcv.exr ||
        no "$name: merge of 4 crops"
    for e in .exr .png v.exr; do
        cmp -s $T/$name$e $T/$name-mc$e || no "$name: 4 crops: $e differs"
    done
}
P="--set photonmap.global=5000 --set photonmap.caustic=10000"
check photon "photon maps (ch. 8)" scenes/caustic.scn $P
check ppm "progressive photon maps" scenes/caustic.scn $P \
    --set integrator=ppm --set photonmap.radius=0.1
check irradiance "irradiance cache (ch. 9)" scenes/cbox.scn \
    --set integrator=irradiance
check volpath "volumetric path tracing (ch. 11)" scenes/smoky-cbox.scn
check volsingle "single scattering by ray marching (ch. 11)" \
    scenes/smoky-cbox.scn --set integrator=volsingle
check cloud "volumetric path tracing (ch. 11)" scenes/cloud.scn
# each method's image is its own: not the path tracer's
$S render scenes/caustic.scn $P --set integrator=path --spp 7 \
    --set resolution=32x24 -q -o $T/path.exr || no "the path tracer"
for m in photon ppm; do
    cmp -s $T/path.exr $T/$m.exr && no "$m: the path tracer's image"
done
refuse() { # WHAT MESSAGE ARGS...
    what=$1; msg=$2; shift 2
    if "$S" "$@" 2>$T/err; then no "$what accepted"; fi
    grep -qF -- "$msg" $T/err || no "$what: no '$msg' in: $(cat $T/err)"
}
# a part of another pre-pass: another photon count, another cache
R="--spp 7 --set resolution=32x24 -q"
$S render scenes/caustic.scn $R --set photonmap.global=6000 \
    --set photonmap.caustic=10000 --samples 3:7 -o $T/other.exr ||
    no "photon: a part of 6000 photons"
refuse "photon: parts of two photon counts" \
    "different scenes, seeds or settings" \
    merge $T/photon-p2-0.exr $T/other.exr -o $T/x.exr
$S render scenes/cbox.scn $R --set integrator=irradiance \
    --set irradiance.a=0.3 --samples 3:7 -o $T/othera.exr ||
    no "irradiance: a part of a = 0.3"
refuse "irradiance: parts of two caches" "different scenes, seeds or settings" \
    merge $T/irradiance-p2-0.exr $T/othera.exr -o $T/x.exr
[ $fail = 0 ] && echo "test_merge_methods: all passed"
exit $fail
