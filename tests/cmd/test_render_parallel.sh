#!/bin/sh
# test_render_parallel.sh - tools/render-parallel.sh in 3 parts equals the
# single render bit for bit, and more parts than samples are refused
# with a message; skips (exit 0, with a message) without GNU parallel.
# Usage: sh tests/cmd/test_render_parallel.sh build/float/svet
set -u
S=${1:?usage: test_render_parallel.sh SVET}
command -v parallel >/dev/null || { echo "test_render_parallel: skipped: GNU parallel is not installed"; exit 0; }
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
O="--set width=32 --set height=24 --threads 1"
$S render scenes/cbox.scn --spp 9 $O -q -o $T/full.exr || exit 1
SVET=$S SPP=9 sh tools/render-parallel.sh scenes/cbox.scn 3 $T/par.exr -- $O || exit 1
cmp $T/full.exr $T/par.exr && cmp $T/full.png $T/par.png || exit 1
# more parts than samples: refused before anything runs
if SVET=$S SPP=2 sh tools/render-parallel.sh scenes/cbox.scn 3 $T/few.exr \
    -- $O 2>$T/err; then
    echo "FAIL: 3 parts of 2 samples accepted"; exit 1
fi
grep -qF "SPP=2: expected a whole number of samples, at least PARTS=3" $T/err ||
    { echo "FAIL: 3 parts of 2 samples: $(cat $T/err)"; exit 1; }
ls $T/few.exr* >/dev/null 2>&1 && { echo "FAIL: a refused split wrote"; exit 1; }
echo "test_render_parallel: passed"
