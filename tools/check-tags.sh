#!/bin/sh
# check-tags.sh - every equation listed in tools/eq-tags.txt is tagged in
# src/ or include/ as "eq. (N.M)", one tag per equation (a range such as
# "eqs. (1.9)-(1.10)" cannot be grepped for one number, so it is refused).
# Used by `make check-tags`, which `make test` runs first.
# Exit 0 when all is well; 1 with one line per problem otherwise.
list=${1:-tools/eq-tags.txt}
[ -r "$list" ] || { echo "check-tags: cannot read $list"; exit 1; }
dirs="src include"
bad=0; n=0
while read -r chapter num what; do
    case "$chapter" in ''|'#'*) continue ;; esac
    n=$((n + 1))
    tag="eq. ($num)"
    if ! grep -rqF -- "$tag" $dirs; then
        echo "$list: ch. $chapter: '$tag' ($what) is tagged nowhere in $dirs"
        bad=$((bad + 1))
    fi
done < "$list"
# A range: "eqs. (1.9)-(1.10)", "eq. (1.11)-(1.12)", "eqs. (1.9) - (1.10)".
ranges=$(grep -rnE 'eqs?\. \([A-Z0-9]+\.[0-9]+\) ?(-|to) ?\(?[A-Z0-9]+\.[0-9]+' $dirs)
if [ -n "$ranges" ]; then
    printf '%s\n' "$ranges" | sed 's/$/  <- write one "eq. (N.M)" per equation/'
    bad=$((bad + $(printf '%s\n' "$ranges" | wc -l)))
fi
if [ "$bad" -ne 0 ]; then
    echo "check-tags: $bad problem(s)"
    exit 1
fi
echo "check-tags: $n equations tagged"
