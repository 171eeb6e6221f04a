#!/bin/sh
# check-cc-lines.sh - each chapter program's first comment is the one cc
# line that builds it alone (smallpt style). Run each such line from the top
# directory into a scratch directory; fail if any does not build.
set -u
top=$(pwd); scratch=$(mktemp -d); fail=0
for src in "$@"; do
    line=$(sed -n '1,3p' "$src" | grep -o 'cc .*' | sed 's: \*/.*$::' | head -n 1)
    if [ -z "$line" ]; then echo "$src: no cc line in its first comment"; fail=1; continue; fi
    # build into the scratch directory: rewrite the -o target
    cmd=$(echo "$line" | sed -E "s:-o ([^ ]+):-o $scratch/\\1:")
    if (cd "$top" && sh -c "$cmd") >"$scratch/log" 2>&1; then
        if grep -q 'warning' "$scratch/log"; then echo "$src: builds, with warnings:"; cat "$scratch/log"; fail=1
        else echo "$src: ok"; fi
    else
        echo "$src: FAILED: $line"; cat "$scratch/log"; fail=1
    fi
done
rm -rf "$scratch"
exit $fail
