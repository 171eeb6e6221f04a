#!/bin/sh
# check-links.sh - a chapter program links only the parts its chapter uses
# (chapters/README.md, "Optional parts"): fail when the program's code has
# a function whose name starts with one of the given prefixes (extended
# regular expressions: ch05's grid, mesh, primset, ...). Reads the linked
# binary's text and weak symbols (nm), local ones included: a module's
# functions, or, where link-time optimisation has inlined them all, the
# weak symbol it leaves for each source file (grid.c.1a2b3c4d), so a
# module listed but unused does not count.
# usage: tools/check-links.sh BINARY PREFIX...
set -u
bin=$1
shift
[ -x "$bin" ] || { echo "check-links: no program $bin" >&2; exit 1; }
[ $# -gt 0 ] || { echo "$bin: links nothing forbidden (no list)"; exit 0; }
pat=$(printf '%s|' "$@")
pat="^(${pat%|})"
bad=$(nm --defined-only "$bin" | awk '$2 ~ /^[TtWwi]$/ { print $3 }' |
      grep -E "$pat" | sort -u)
if [ -n "$bad" ]; then
    echo "$bin: links code its chapter does not use:"
    printf '  %s\n' $bad
    exit 1
fi
echo "$bin: links none of $*"
