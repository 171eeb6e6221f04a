#!/bin/sh
# count-grid.sh - `make count-grid`: instructions per ray of the grid at 1e6
# triangles (bench/results/grid.md, "Instructions per ray"), for camera rays
# one at a time, in packets of 4 x 4 and 8 x 8, and incoherent rays: one
# pass of `bench_grid --trace KIND` under valgrind's callgrind, counting
# trace_pass() only (the queries' set-up, the traversal, their finish),
# so the figures do not depend on the machine's load. Needs valgrind;
# with AVX-512 CPUs see tools/count-render.sh.
# usage: tools/count-grid.sh BENCH_GRID_BINARY
set -eu
bin=$1
command -v valgrind >/dev/null || { echo "count-grid: valgrind is not installed" >&2; exit 1; }
mkdir -p out
rays=262144 # bench_grid's 512 x 512 camera, and as many incoherent rays
for kind in camera packets4 packets8 incoherent; do
    out=out/callgrind.grid-$kind
    if ! valgrind --tool=callgrind --callgrind-out-file="$out" \
        --toggle-collect='trace_pass*' "$bin" --trace "$kind" --passes 1 \
        >out/count-grid.log 2>&1; then
        echo "count-grid: $bin --trace $kind failed under valgrind (out/count-grid.log)" >&2
        exit 1
    fi
    total=$(callgrind_annotate "$out" | awk '/PROGRAM TOTALS/ { gsub(",", "", $1); print $1 }')
    if [ -z "$total" ] || [ "$total" -eq 0 ]; then
        echo "count-grid: nothing counted in trace_pass (inlined by the compiler?)" >&2
        exit 1
    fi
    echo "$kind: $total instructions, $rays rays: $((total / rays)) per ray"
done
