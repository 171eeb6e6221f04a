#!/bin/sh
# reference.sh - `make reference`: the converged reference renders of
# tests/reference/ (their README says what they are for), one per scene
# file scenes/*.scn: at half the scene's resolution (the files stay small),
# REF_SPP samples per pixel (4096), seed 0 (or the next, below), by the
# float build of `svet render`. For scene NAME it writes NAME.exr (the
# mean, 32-bit float, ZIP), NAME-var.exr (the per-pixel variance of the
# mean), NAME.png (tone-mapped, to look at) and NAME.txt (the exact
# command, seed, spp, build and render time, as "key = value" lines that
# tests/render/test_reference.c reads).
#
# usage: sh tools/reference.sh SVET [SCENE.scn ...]
#   SVET     the svet binary (make reference passes build/float/svet)
#   SCENE    only these scenes (default: every scenes/*.scn)
#        sh tools/reference.sh --table
#            only rewrite the table of tests/reference/README.md
# environment: REF_SPP (samples per pixel, default 4096), REF_DIR (default
# tests/reference), REF_THREADS (default 0: every core).
set -eu

svet=${1:?usage: sh tools/reference.sh SVET [SCENE.scn ...]}
shift
table_only=no
if [ "$svet" = --table ]; then
    table_only=yes
elif [ ! -x "$svet" ]; then
    echo "reference.sh: $svet is not built" >&2; exit 1
fi
spp=${REF_SPP:-4096}
dir=${REF_DIR:-tests/reference}
threads=${REF_THREADS:-0}
[ $# -gt 0 ] || set -- scenes/*.scn
mkdir -p "$dir"

# The build, for the record: compiler and the exact flags of the Makefile.
cc_line=$(${CC:-cc} --version 2>/dev/null | head -n 1)
cflags=$(make -s --no-print-directory --eval 'print-cflags: ; @echo $(ALL_CFLAGS)' \
         print-cflags REAL="${REAL:-float}" 2>/dev/null || echo unknown)
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -n 1)
cores=$(nproc 2>/dev/null || echo "?")

# The scene's own image size: the last `width` and `height` given on
# `camera` lines (scenes/README.md), 256 when absent.
scene_size() {
    awk '$1 == "camera" { for (i = 2; i < NF; i++) {
             if ($i == "width") w = $(i + 1); if ($i == "height") h = $(i + 1) } }
         END { print (w ? w : 256), (h ? h : 256) }' "$1"
}

total0=$(date +%s)
[ "$table_only" = yes ] && set --
for scene in "$@"; do
    name=$(basename "$scene" .scn)
    size=$(scene_size "$scene")
    w=$(( ${size% *} / 2 )); h=$(( ${size#* } / 2 ))
    [ "$w" -ge 1 ] && [ "$h" -ge 1 ] || { w=${size% *}; h=${size#* }; }
    # OpenEXR 3.1's ZIP writer corrupts a chunk whose deflated size equals
    # its raw size (openexr issue 2306). The files are checked after
    # writing (svet converge --ztest refuses a negative or non-finite
    # value) and, when hit, the scene is rendered again with the next
    # seed: other samples, other chunk sizes. The seed used is recorded.
    seed=0
    while :; do
        cmd="$svet render $scene --spp $spp --seed $seed --threads $threads --set resolution=${w}x${h} -o $dir/$name.exr --variance $dir/$name-var.exr --png $dir/$name.png"
        echo "reference.sh: $name: ${w}x${h}, $spp spp, seed $seed" >&2
        t0=$(date +%s.%N)
        # keep the summary line of svet render (time, samples/s, rays/s)
        $cmd 2>"$dir/.$name.log" >/dev/null || {
            cat "$dir/.$name.log" >&2; rm -f "$dir/.$name.log"; exit 1; }
        summary=$(tail -n 1 "$dir/.$name.log")
        rm -f "$dir/.$name.log"
        t1=$(date +%s.%N)
        "$svet" converge --ztest "$dir/$name.exr" --spp "$spp" \
            --ref "$dir/$name.exr" --ref-spp "$spp" >/dev/null && break
        [ "$seed" -lt 3 ] || { echo "reference.sh: $name: corrupt files" \
                                    "with seeds 0 to 3" >&2; exit 1; }
        seed=$(( seed + 1 ))
    done
    secs=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }')
    blob=$(git hash-object "$scene" 2>/dev/null || echo unknown)
    {
        echo "# $dir/$name.txt - how $name.exr and $name-var.exr were made (make reference)."
        echo "# $name.exr: the mean image, linear RGB, 32-bit float EXR (ZIP)."
        echo "# $name-var.exr: per pixel and channel the variance of that mean"
        echo "#   (svet render --variance: s^2 / spp, s^2 the unbiased sample variance)."
        echo "scene = $scene"
        echo "scene_blob = $blob"
        echo "resolution = ${w}x${h}"
        echo "spp = $spp"
        echo "seed = $seed"
        echo "command = $cmd"
        echo "real = ${REAL:-float}"
        echo "compiler = $cc_line"
        echo "cflags = $cflags"
        echo "machine = $cpu, $cores cores"
        echo "render_seconds = $secs"
        echo "render_summary = $summary"
        echo "date = $(date -u +%Y-%m-%d)"
    } > "$dir/$name.txt"
    echo "reference.sh: $name: $secs s" >&2
done
total1=$(date +%s)
[ "$table_only" = yes ] ||
echo "reference.sh: $(( total1 - total0 )) s in all; $(du -ch "$dir"/*.exr | tail -n 1 | cut -f 1) of EXR in $dir" >&2

# The table of every reference in the directory, between the markers
# <!-- reference-table ... --> and <!-- /reference-table --> of its README.
table() {
    echo "| scene | resolution | spp | render time | files (EXR + variance + PNG) |"
    echo "|---|---|---:|---:|---:|"
    total=0
    for t in "$dir"/*.txt; do
        n=$(basename "$t" .txt)
        bytes=$(cat "$dir/$n.exr" "$dir/$n-var.exr" "$dir/$n.png" 2>/dev/null | wc -c)
        total=$(( total + bytes ))
        printf '| `%s` | %s | %s | %s s | %s kB |\n' \
            "$(sed -n 's/^scene = //p' "$t")" "$(sed -n 's/^resolution = //p' "$t")" \
            "$(sed -n 's/^spp = //p' "$t")" "$(sed -n 's/^render_seconds = //p' "$t")" \
            $(( (bytes + 512) / 1024 ))
    done
    echo
    echo "In all $(awk -v b="$total" 'BEGIN { printf "%.1f", b / 1048576 }') MB;" \
         "render times as measured by make reference" \
         "($(sed -n 's/^machine = //p' "$t"), $(sed -n 's/^date = //p' "$t");" \
         "see each NAME.txt)."
}
readme="$dir/README.md"
if [ -f "$readme" ] && grep -q '^<!-- reference-table' "$readme"; then
    table > "$dir/.table"
    awk -v tf="$dir/.table" '
        /^<!-- reference-table/ { print; while ((getline l < tf) > 0) print l; skip = 1; next }
        /^<!-- \/reference-table -->/ { skip = 0 }
        !skip' "$readme" > "$readme.tmp"
    grep -q '^<!-- /reference-table -->' "$readme.tmp" || {
        # first time: close the block after the table
        awk -v tf="$dir/.table" '
            /^<!-- reference-table/ { print; while ((getline l < tf) > 0) print l;
                                      print "<!-- /reference-table -->"; next } { print }' \
            "$readme" > "$readme.tmp"; }
    mv "$readme.tmp" "$readme"
    rm -f "$dir/.table"
fi
