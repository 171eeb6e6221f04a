#!/bin/sh
# check-paths.sh - every path into the tree that a Markdown file names
# (src/..., include/..., tests/..., chapters/..., bench/..., tools/...,
# scenes/..., docs/..., cmd/..., fuzz/...) exists, so the docs follow the
# files when they move. Patterns (`src/*/*.c`, `include/<part>/<m>.h`) and
# what is made by a build or a run (build/, out/) are not paths to check.
# Used by `make check-tags`, which `make test` runs first.
# Exit 0 when all is well; 1 with one line per missing path otherwise.
bad=0; n=0
files=$(git ls-files '*.md' 2>/dev/null || find . -name '*.md' -not -path './build/*')
tmp=$(mktemp) || exit 1
trap 'rm -f "$tmp"' EXIT
for md in $files; do
    # A path starts at a word boundary (not inside build/float/tests/...)
    # and runs over [A-Za-z0-9_./-]; one with a pattern character is skipped.
    grep -noE '(^|[^A-Za-z0-9_./-])(src|include|tests|chapters|bench|tools|scenes|docs|cmd|fuzz)/[A-Za-z0-9_./<>*{}$%-]*' "$md" |
    while IFS=: read -r line match; do
        p=$(printf '%s' "$match" | sed -E 's/^[^a-z]//; s/[.,;:]+$//')
        case "$p" in *'<'*|*'>'*|*'*'*|*'{'*|*'$'*|*'%'*|*'...'*) continue ;; esac
        # placeholders (tests/reference/NAME.exr, chapters/chNN/) and other
        # projects' files cited by name (pbrt-v3's src/tests/bsdfs.cpp)
        case "$p" in *NAME*|*NN*|*.cpp|*.py|fuzz/findings/*) continue ;; esac
        printf '%s:%s: %s\n' "$md" "$line" "$p"
    done
done > "$tmp"
while IFS= read -r row; do
    p=${row##*: }
    n=$((n + 1))
    if [ ! -e "$p" ]; then
        echo "$row: no such file or directory"
        bad=$((bad + 1))
    fi
done < "$tmp"
if [ "$bad" -ne 0 ]; then
    echo "check-paths: $bad of $n paths named in *.md do not exist"
    exit 1
fi
echo "check-paths: $n paths named in *.md exist"
