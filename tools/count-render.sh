#!/bin/sh
# count-render.sh - `make count-render`: instructions per camera sample of
# the Cornell box (bench/results/render.md's table), counted by valgrind's
# callgrind over render_pass's parallel region only (gcc's outlined
# render_pass._omp_fn.0, which link-time optimisation renames and into whose
# caller it folds render_pass itself), so the count does not depend on the
# machine's load. Needs valgrind (apt-get install valgrind). Counted with
# the Makefile's -march=native; valgrind 3.19 does not run AVX-512 code,
# so on such a CPU count a build made with `make ARCH=-march=x86-64-v3`.
# usage: tools/count-render.sh SVET_BINARY [SCENE]
set -eu
svet=$1
scene=${2:-scenes/cbox.scn}
command -v valgrind >/dev/null || { echo "count-render: valgrind is not installed" >&2; exit 1; }
mkdir -p out
out=out/callgrind.render
[ -r "$scene" ] || { echo "count-render: cannot read $scene" >&2; exit 1; }
if ! valgrind --tool=callgrind --callgrind-out-file="$out" \
    --toggle-collect='render_pass._omp_fn*' "$svet" render "$scene" --spp 1 \
    --threads 1 -o out/count-render.exr >out/count-render.log 2>&1; then
    echo "count-render: $svet render $scene failed under valgrind (out/count-render.log)" >&2
    exit 1
fi
total=$(callgrind_annotate "$out" | awk '/PROGRAM TOTALS/ { gsub(",", "", $1); print $1 }')
# the image size from the camera line's width and height
size=$(awk '$1 == "camera" { for (i = 2; i < NF; i++) { if ($i == "width") w = $(i + 1); if ($i == "height") h = $(i + 1) } } END { print w * h }' "$scene")
# gcc names the parallel region render_pass._omp_fn.N (with a suffix under
# LTO); another compiler's name would match nothing and count 0
if [ -z "$total" ] || [ "$total" -eq 0 ]; then
    echo "count-render: nothing counted in render_pass._omp_fn* (a build by gcc with OpenMP is needed)" >&2
    exit 1
fi
[ "${size:-0}" -gt 0 ] || { echo "count-render: no camera width and height in $scene" >&2; exit 1; }
echo "$scene: $total instructions in render_pass, $size camera samples (1 spp): $((total / size)) per sample"
