#!/bin/sh
# bitcheck.sh - `make bitcheck`: every shipped scene renders to the same
# bytes with every build given, at 1 and at 2 threads. The first binary at
# one thread is the reference; each scenes/*.scn is rendered small (SIZE x
# SIZE pixels, SPP samples) by every binary at each thread count, and its
# EXR and PNG are compared with the reference's byte for byte. Binaries of
# one REAL only: float and double images differ by design.
# With BASE=COMMIT in the environment, that commit's svet (built with
# REAL, default float, in a scratch copy from git archive) is the
# reference instead, so a change is compared with the tree before it.
# usage: tools/bitcheck.sh SVET_REF SVET_OTHER... (SIZE, SPP, SCENES, BASE,
#        REAL from the environment; default 64, 8, scenes/*.scn)
# Exit 0 when every image matches, 1 when one differs or a render fails.
set -u
[ $# -ge 1 ] || { echo "usage: tools/bitcheck.sh SVET_REF SVET_OTHER..." >&2; exit 1; }
size=${SIZE:-64}
spp=${SPP:-8}
scenes=${SCENES:-$(ls scenes/*.scn)}
for bin in "$@"; do
    [ -x "$bin" ] || { echo "bitcheck: no binary $bin" >&2; exit 1; }
done
dir=$(mktemp -d "${TMPDIR:-/tmp}/svet-bitcheck.XXXXXX")
trap 'rm -rf "$dir"' EXIT
if [ -n "${BASE:-}" ]; then
    real=${REAL:-float}
    mkdir "$dir/base"
    git archive "$BASE" | tar -x -C "$dir/base" ||
        { echo "bitcheck: '$BASE' is not a commit" >&2; exit 1; }
    echo "bitcheck: building svet ($real) at $BASE" >&2
    make -C "$dir/base" -j2 REAL="$real" "build/$real/svet" \
        >"$dir/base/build.log" 2>&1 ||
        { echo "bitcheck: the base did not build:" >&2
          tail -20 "$dir/base/build.log" >&2; exit 1; }
    set -- "$dir/base/build/$real/svet" "$@"
fi
ref=$1
label=${BASE:+$BASE\'s build}
label=${label:-$ref}
fail=0
n=0
for scn in $scenes; do
    name=$(basename "$scn" .scn)
    run() { # binary threads output-stem
        "$1" render "$scn" --spp "$spp" --threads "$2" --seed 7 \
            --set width="$size" --set height="$size" -q -o "$3.exr" \
            >"$3.log" 2>&1
    }
    if ! run "$ref" 1 "$dir/$name-ref"; then
        echo "bitcheck: $ref failed on $scn:"; cat "$dir/$name-ref.log"
        fail=1; continue
    fi
    i=0
    for bin in "$@"; do
        for t in 1 2; do
            [ "$bin" = "$ref" ] && [ "$t" = 1 ] && [ "$i" = 0 ] && continue
            out="$dir/$name-$i-$t"
            if ! run "$bin" "$t" "$out"; then
                echo "bitcheck: $bin failed on $scn:"; cat "$out.log"
                fail=1; continue
            fi
            for ext in exr png; do
                n=$((n + 1))
                if ! cmp -s "$dir/$name-ref.$ext" "$out.$ext"; then
                    echo "bitcheck: $scn: $bin at $t threads differs from $label at 1 ($ext)"
                    fail=1
                fi
            done
        done
        i=$((i + 1))
    done
done
if [ "$fail" = 0 ]; then
    echo "bitcheck: $n images, every one the same bytes as $label at one thread ($size x $size, $spp spp)"
fi
exit $fail
