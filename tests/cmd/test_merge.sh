#!/bin/sh
# test_merge.sh - svet render --samples/--crop and svet merge (cmd/cmd_merge.c):
# 1, 2, 3 and 7 parts by samples and 4 by crop merge to the single render's
# EXR, PNG and variance bit for bit (an independent reference: the one-pass
# render), every refusal prints its message, and --resume after SIGINT,
# SIGTERM or SIGKILL ends on the uninterrupted render's bits; the photon
# and ppm methods merge too, and the photon maps saved once and read by
# every part (--save-prepass, --load-prepass) give the same bits; --half
# parts merge to a --half render.
# Usage: sh tests/cmd/test_merge.sh build/float/svet
set -u
S=${1:?usage: test_merge.sh SVET}
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
A="scenes/cbox.scn --spp 14 --set width=40 --set height=30 -q --threads 2"
fail=0
no() { echo "FAIL: $*"; fail=1; }
refuse() { # WHAT MESSAGE ARGS...
    what=$1; msg=$2; shift 2
    if "$S" "$@" 2>$T/err; then no "$what accepted"; fi
    grep -q "$msg" $T/err || no "$what: no '$msg' in: $(cat $T/err)"
}
nothing() { # WHAT: no x.exr, x.png or x.exr.part left by a refusal
    for e in .exr .png .exr.part; do
        if [ -e $T/x$e ]; then no "$1: wrote x$e"; fi
    done
    rm -f $T/x.exr $T/x.png $T/x.exr.part
}
$S render $A -o $T/full.exr --variance $T/fullv.exr || no "single render"
split() { # N: N sample ranges of 14
    n=$1; list=""; i=0
    while [ $i -lt $n ]; do
        f=$((14 * i / n)); t=$((14 * (i + 1) / n))
        $S render $A --samples $f:$t -o $T/p$n-$i.exr || no "part $f:$t"
        list="$list $T/p$n-$i.exr"; i=$((i + 1))
    done
    $S merge $list -o $T/m$n.exr --variance $T/m${n}v.exr || no "merge $n"
    for e in .exr .png v.exr; do
        cmp -s $T/full$e $T/m$n$e || no "$n parts by samples: $e differs"
    done
}
for n in 1 2 3 7; do split $n; done
# A wide range of sample magnitudes in one pixel: a tiny emitter of 1e12
# on a back wall of reflectance 1e-4, and a tiny bright light in the
# ceiling seen through diffuse bounces (fireflies near it). Samples 1e9
# apart in a pixel make a double sum depend on the order of its additions;
# the sums of svet's accumulation are exact integers (image.h), so the
# merged part file, sums and sums of squares, equals the single render's.
cat > $T/wide.scn <<'EOF'
camera position 0 0 3.9 target 0 0 0 up 0 1 0
camera fov 39.3077 fov_axis y width 24 height 24 filter box
render spp 14 maxdepth 7 roulette on roulette_depth 3 seed 0
render integrator path
tonemap operator linear exposure 0 curve srgb
material white lambert rho 0.885809 0.698859 0.666422
material dark lambert rho 0.0001 0.0001 0.0001
parallelogram c0 -1 -1 1   c1 1 -1 1   c2 1 -1 -1  c3 -1 -1 -1  material white
parallelogram c0 -1 1 -1   c1 1 1 -1   c2 1 1 1    c3 -1 1 1    material white
parallelogram c0 -1 -1 -1  c1 1 -1 -1  c2 1 1 -1   c3 -1 1 -1   material dark
parallelogram c0 1 -1 -1   c1 1 -1 1   c2 1 1 1    c3 1 1 -1    material white
parallelogram c0 -1 -1 1   c1 -1 -1 -1 c2 -1 1 -1  c3 -1 1 1    material white
parallelogram c0 -0.005 0.99 -0.005  c1 0.005 0.99 -0.005  c2 0.005 0.99 0.005  c3 -0.005 0.99 0.005  material white  emit 3e3 3e3 3e3
parallelogram c0 0.3 0.3 -0.99  c1 0.37 0.3 -0.99  c2 0.37 0.37 -0.99  c3 0.3 0.37 -0.99  material dark  emit 1e12 1e12 1e12
EOF
W="$T/wide.scn -q --threads 2"
$S render $W --samples 0:14 -o $T/wfull.exr --variance $T/wfullv.exr || no "wide: single render"
for n in 1 2 3 7; do
    list=""; i=0
    while [ $i -lt $n ]; do
        f=$((14 * i / n)); t=$((14 * (i + 1) / n))
        $S render $W --samples $f:$t -o $T/w$n-$i.exr || no "wide: part $f:$t"
        list="$list $T/w$n-$i.exr"; i=$((i + 1))
    done
    $S merge $list -o $T/wm$n.exr --variance $T/wm${n}v.exr || no "wide: merge $n"
    for e in .exr .exr.part .png v.exr; do
        cmp -s $T/wfull$e $T/wm$n$e || no "wide: $n parts by samples: $e differs"
    done
done
# a merge of merges: samples 0:6 and 6:14, each merged from its parts
$S merge $T/w7-0.exr $T/w7-1.exr $T/w7-2.exr -o $T/wa.exr || no "wide: merge 0:6"
$S merge $T/w7-3.exr $T/w7-4.exr $T/w7-5.exr $T/w7-6.exr -o $T/wb.exr || no "wide: merge 6:14"
$S merge $T/wb.exr $T/wa.exr -o $T/wab.exr --variance $T/wabv.exr || no "wide: merge of merges"
for e in .exr .exr.part .png v.exr; do
    cmp -s $T/wfull$e $T/wab$e || no "wide: a merge of merges: $e differs"
done
# the Part II methods: every part runs the pre-pass from the scene and seed
# (photon maps), ppm's map of each sample index follows the index
for m in photon ppm; do
    P="scenes/caustic.scn --spp 4 --set resolution=48x32 --set integrator=$m -q"
    $S render $P -o $T/f$m.exr || no "$m: single render"
    $S render $P --samples 0:1 -o $T/a$m.exr || no "$m: part 0:1"
    $S render $P --samples 1:4 -o $T/b$m.exr || no "$m: part 1:4"
    $S merge $T/a$m.exr $T/b$m.exr -o $T/m$m.exr || no "$m: merge"
    cmp -s $T/f$m.exr $T/m$m.exr || no "$m: 2 parts by samples: EXR differs"
done
# the photon maps saved once (--save-prepass) and read by the parts
# (--load-prepass): the parts merge to the single render's bits, which
# traced its maps itself; a part that reads them is the part that traces
# them, byte for byte
P="scenes/caustic.scn --spp 4 --set resolution=48x32 --set integrator=photon -q"
$S render $P --samples 0:1 --save-prepass $T/maps -o $T/s0.exr || no "--save-prepass"
head -3 $T/maps | grep -q "^identity [0-9a-f]*$" || no "the saved pre-pass has no identity line"
$S render $P --samples 1:3 --load-prepass $T/maps -o $T/s1.exr || no "--load-prepass part 1:3"
$S render $P --samples 3:4 --load-prepass $T/maps --threads 1 -o $T/s2.exr || no "--load-prepass part 3:4"
$S merge $T/s0.exr $T/s1.exr $T/s2.exr -o $T/sm.exr || no "merge of parts of a saved pre-pass"
cmp -s $T/fphoton.exr $T/sm.exr || no "saved pre-pass: the merge differs from the single render"
$S render $P --samples 1:4 -o $T/s3.exr || no "photon part 1:4"
$S render $P --samples 1:4 --load-prepass $T/maps -o $T/s4.exr || no "--load-prepass part 1:4"
cmp -s $T/s3.exr.part $T/s4.exr.part || no "a part of the saved pre-pass differs from one that traced it"
# refusals: another seed's or setting's scene, a file that is not a
# pre-pass, is cut short or is of another real type, a method without a
# saved pre-pass, both options at once; none writes an image
rm -f $T/x.exr $T/x.png $T/x.exr.part
refuse "a pre-pass of another seed" "the pre-pass of another scene, seed or settings" render $P --seed 5 --load-prepass $T/maps -o $T/x.exr
refuse "a pre-pass of another setting" "the pre-pass of another scene, seed or settings" render $P --set maxdepth=3 --load-prepass $T/maps -o $T/x.exr
refuse "a part file as a pre-pass" "not a pre-pass file" render $P --load-prepass $T/s0.exr.part -o $T/x.exr
head -c 5000 $T/maps > $T/cutmaps
refuse "a truncated pre-pass" "cutmaps: a photon map of [0-9]* photons truncated" render $P --load-prepass $T/cutmaps -o $T/x.exr
sed '3s/^real .*/real quad/' $T/maps > $T/quadmaps
refuse "a pre-pass of another real type" "a pre-pass of a quad build, this one is" render $P --load-prepass $T/quadmaps -o $T/x.exr
sed '4s/.*/photon maps 2/' $T/maps > $T/twomaps
refuse "a pre-pass of another layout" "not the pre-pass of integrator photon" render $P --load-prepass $T/twomaps -o $T/x.exr
refuse "ppm's pre-pass" "integrator ppm does not save its pre-pass" render $P --set integrator=ppm --load-prepass $T/maps -o $T/x.exr
refuse "path's pre-pass" "the integrator has no pre-pass" render $A --save-prepass $T/x.pre -o $T/x.exr
refuse "both pre-pass options" "one of them at a time" render $P --save-prepass $T/x.pre --load-prepass $T/maps -o $T/x.exr
nothing "the pre-pass refusals"
[ -e $T/x.pre ] && no "a refused --save-prepass wrote its file"
$S render scenes/caustic.scn --spp 1 --set resolution=16x12 -o $T/d.exr 2>&1 |
    grep -q "; photon maps (ch. 8): " || no "the summary names the method"
for c in 0:20,0:15 20:40,0:15 0:20,15:30 20:40,15:30; do
    $S render $A --crop $c -o $T/c$c.exr --variance $T/cv$c.exr || no "crop $c"
done
$S merge $T/c0:20,0:15.exr $T/c20:40,0:15.exr $T/c0:20,15:30.exr \
    $T/c20:40,15:30.exr -o $T/mc.exr --variance $T/mcv.exr || no "merge crop"
cmp -s $T/full.exr $T/mc.exr || no "4 crops: EXR differs"
cmp -s $T/full.png $T/mc.png || no "4 crops: PNG differs"
cmp -s $T/fullv.exr $T/mcv.exr || no "4 crops: variance differs"
# --half parts merge to a single --half render's bytes (half floats; an
# independent check: the part file says so and the EXR is smaller), and
# half and float parts together are refused
$S render $A --half -o $T/hfull.exr || no "single --half render"
$S render $A --half --samples 0:5 -o $T/h0.exr || no "--half part 0:5"
$S render $A --half --samples 5:14 -o $T/h1.exr || no "--half part 5:14"
$S merge $T/h0.exr $T/h1.exr -o $T/hm.exr || no "merge of --half parts"
cmp -s $T/hfull.exr $T/hm.exr || no "2 --half parts: EXR differs"
cmp -s $T/hfull.png $T/hm.png || no "2 --half parts: PNG differs"
grep -qx "exr half" $T/hm.exr.part || no "the merged part file is not half"
grep -qx "exr float" $T/m2.exr.part || no "a float part file is not float"
[ "$(wc -c < $T/hm.exr)" -lt "$(wc -c < $T/m2.exr)" ] ||
    no "the merged --half EXR is not smaller than the float one"
$S merge $T/hm.exr -o $T/hmm.exr || no "merge of a merged --half image"
cmp -s $T/hfull.exr $T/hmm.exr || no "a merge of the --half merge differs"
# --half changes the EXR's pixel type only: a --half part holds the sums
# of the float part of the same samples (the float merge above is the
# single render's), its header but the 'exr' line the same
$S render $A --samples 0:5 -o $T/f0.exr || no "float part 0:5"
sed -n '7p' $T/f0.exr.part | grep -qx "exr float" || no "line 7 of a float part is not 'exr float'"
sed '7d' $T/h0.exr.part > $T/h0.body; sed '7d' $T/f0.exr.part > $T/f0.body
cmp -s $T/h0.body $T/f0.body || no "a --half part's sums are not the float part's"
# the comparisons above can fail: a half merge of wrong sums (the colour
# sums of pixel (20, 15) zeroed in one part), and half parts relabelled
# float, differ from the single --half render; relabelled they are the
# float render's bytes
awk 'NR == 8 + 15 * 40 + 20 { $1 = 0; $2 = 0; $3 = 0 } { print }' \
    $T/h1.exr.part > $T/hz.exr.part; cp $T/h1.exr $T/hz.exr
$S merge $T/h0.exr $T/hz.exr -o $T/hzm.exr || no "merge of a --half part with a zeroed pixel"
cmp -s $T/hfull.exr $T/hzm.exr && no "a --half merge of a zeroed pixel has the single render's bytes"
for k in 0 1; do
    sed '7s/^exr half$/exr float/' $T/h$k.exr.part > $T/hf$k.exr.part
    cp $T/h$k.exr $T/hf$k.exr
done
$S merge $T/hf0.exr $T/hf1.exr -o $T/hfm.exr || no "merge of --half parts relabelled float"
cmp -s $T/hfull.exr $T/hfm.exr && no "half parts relabelled float merge to the --half render's bytes"
cmp -s $T/full.exr $T/hfm.exr || no "half parts relabelled float: not the float render's bytes"
# mixing half and float parts is refused whichever comes first, naming
# both files, and writes nothing; so is a pixel type that is neither.
# The parts of each pair make the whole sample range, so the pixel type
# is the only reason to refuse them.
$S render $A --samples 5:14 -o $T/f1.exr || no "float part 5:14"
$S render $A --half --samples 0:2 -o $T/ha.exr || no "--half part 0:2"
$S render $A --half --samples 2:5 -o $T/hb.exr || no "--half part 2:5"
$S merge $T/ha.exr $T/hb.exr -o $T/hab.exr || no "merge of --half parts 0:2, 2:5"
rm -f $T/x.exr $T/x.png $T/x.exr.part
refuse "half and float parts" "h0.exr and .*f1.exr: one EXR is half, the other float" merge $T/h0.exr $T/f1.exr -o $T/x.exr
nothing "half and float parts"
refuse "float and half parts" "f0.exr and .*h1.exr: one EXR is half, the other float" merge $T/f0.exr $T/h1.exr -o $T/x.exr
nothing "float and half parts"
refuse "a merged --half image and a float part" "hab.exr and .*f1.exr: one EXR is half, the other float" merge $T/hab.exr $T/f1.exr -o $T/x.exr
nothing "a merged --half image and a float part"
sed '7s/^exr half$/exr quarter/' $T/h1.exr.part > $T/hq.exr.part; cp $T/h1.exr $T/hq.exr
refuse "an unknown pixel type" "no 'exr half' or 'exr float' line" merge $T/h0.exr $T/hq.exr -o $T/x.exr
nothing "an unknown pixel type"
refuse "a gap" "samples 4:9 of pixel (0, 0) are missing" merge $T/p3-0.exr $T/p3-2.exr -o $T/x.exr
refuse "an overlap" "overlap another part" merge $T/p2-0.exr $T/p2-0.exr -o $T/x.exr
refuse "a missing crop" "pixel (20, 0) is in no part" merge $T/c0:20,0:15.exr -o $T/x.exr
$S render $A --seed 9 --samples 7:14 -o $T/seed.exr || no "seed part"
refuse "another seed" "different scenes, seeds or settings" merge $T/p2-0.exr $T/seed.exr -o $T/x.exr
$S render scenes/cbox.scn --spp 14 --set width=40 --set height=30 --set maxdepth=2 -q --samples 7:14 -o $T/set.exr || no "set part"
refuse "another setting" "different scenes, seeds or settings" merge $T/p2-0.exr $T/set.exr -o $T/x.exr
refuse "a non-part" "cannot open" merge $T/full.exr -o $T/x.exr
# the files a scene names are part of its identity: a mesh edited
# between two parts is refused, the same mesh merges
cat > $T/tri.scn <<'EOF'
camera position 0 0 3 target 0 0 0 width 8 height 8
render spp 4
material m lambert rho 0.5
light point position 0 0 2 intensity 1
mesh file tri.obj material m
EOF
printf 'v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n' > $T/tri.obj
$S render $T/tri.scn -q --samples 0:2 -o $T/t0.exr || no "mesh part 0:2"
$S render $T/tri.scn -q --samples 2:4 -o $T/t1.exr || no "mesh part 2:4"
$S merge $T/t0.exr $T/t1.exr -o $T/tm.exr || no "the same mesh's parts"
printf 'v -1 -1 0\nv 1 -1 0\nv 0 0.9 0\nf 1 2 3\n' > $T/tri.obj
$S render $T/tri.scn -q --samples 2:4 -o $T/t2.exr || no "edited mesh part"
refuse "an edited mesh" "different scenes, seeds or settings" merge $T/t0.exr $T/t2.exr -o $T/x.exr
sed '8,$s/^[0-9a-f-]*/nan/' $T/p2-1.exr.part > $T/nan.exr.part; cp $T/p2-1.exr $T/nan.exr
refuse "a NaN sum" "'nan' is not a sum" merge $T/p2-0.exr $T/nan.exr -o $T/x.exr
head -c 300 $T/p2-1.exr.part > $T/cut.exr.part; cp $T/p2-1.exr $T/cut.exr
refuse "a truncated part" "truncated at pixel" merge $T/p2-0.exr $T/cut.exr -o $T/x.exr
refuse "a bad range" "samples" render $A --samples 5:5 -o $T/x.exr
refuse "a crop outside" "outside the 40x30 image" render $A --crop 0:41,0:5 -o $T/x.exr
# --resume after a real signal: SIGINT, SIGTERM, and SIGKILL (the last
# checkpoint's part file is what is left)
R="scenes/cbox.scn --spp 256 --passes 64 --set width=128 --set height=96 -q --threads 1"
$S render $R -o $T/rfull.exr || no "resume reference"
for sig in INT TERM KILL; do
    rm -f $T/r$sig.exr*
    $S render $R --checkpoint -o $T/r$sig.exr & pid=$!
    # the signal comes once the first checkpoint is on disk, while the
    # render is still under way
    i=0
    while [ ! -f $T/r$sig.exr.part ] && [ $i -lt 200 ]; do
        sleep 0.05; i=$((i + 1))
    done
    kill -$sig $pid 2>/dev/null || no "SIG$sig: the render ended before the signal"
    wait $pid
    [ -f $T/r$sig.exr.part ] || { no "SIG$sig: no checkpoint's part file"; continue; }
    cmp -s $T/rfull.exr $T/r$sig.exr && no "SIG$sig: the interrupted render is already whole"
    $S render $R --resume -o $T/r$sig.exr || no "resume after SIG$sig"
    cmp -s $T/rfull.exr $T/r$sig.exr || no "resume after SIG$sig: EXR differs"
    cmp -s $T/rfull.png $T/r$sig.png || no "resume after SIG$sig: PNG differs"
done
refuse "resume of another seed" "another scene, seed" render $R --seed 3 --resume -o $T/rINT.exr
[ $fail = 0 ] && echo "test_merge: all passed"
exit $fail
