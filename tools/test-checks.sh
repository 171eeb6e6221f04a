#!/bin/sh
# test-checks.sh - the checkers of `make check-tags` on a small tree made in
# a temporary directory: check-tags.sh must pass a tree where every listed
# equation is tagged and fail one with a tag missing or a range of tags;
# check-paths.sh must pass a Markdown file whose paths exist (patterns and
# placeholders skipped) and fail one that names a missing file.
# Prints one line for a case that went wrong (and exits 1), else a count.
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT
bad=0; n=0
expect() { # expect STATUS NAME COMMAND...: run COMMAND in $tmp
    want=$1; name=$2; shift 2
    (cd "$tmp" && "$@") >"$tmp/out" 2>&1; got=$?
    case "$want:$got" in pass:0) ok=1 ;; pass:*) ok=0 ;; fail:0) ok=0 ;; *) ok=1 ;; esac
    n=$((n + 1))
    if [ "$ok" -ne 1 ]; then
        echo "test-checks: $name: expected $want, exit $got:"; sed 's/^/    /' "$tmp/out"
        bad=1
    fi
}
mkdir -p "$tmp/src/a" "$tmp/include/a"
printf '1 1.1  first\n1 1.10 tenth\n' > "$tmp/tags.txt"
printf '/* eq. (1.1) */\n' > "$tmp/src/a/x.c"
printf '/* eq. (1.10) */\n' > "$tmp/include/a/x.h"
expect pass "every equation tagged" sh "$here/check-tags.sh" tags.txt
printf '/* eq. (1.10) only */\n' > "$tmp/src/a/x.c"
expect fail "eq. (1.1) missing, eq. (1.10) present" sh "$here/check-tags.sh" tags.txt
printf '/* eq. (1.1) */ /* eqs. (1.1)-(1.10) */\n' > "$tmp/src/a/x.c"
expect fail "a range of tags" sh "$here/check-tags.sh" tags.txt
printf '# ok\n`src/a/x.c`, [h](include/a/x.h), `src/*/*.c`, `include/<part>/<m>.h`, `tests/NAME.exr`\n' > "$tmp/ok.md"
expect pass "paths that exist" sh "$here/check-paths.sh"
printf 'see `src/a/gone.c`\n' > "$tmp/bad.md"
expect fail "a path that does not exist" sh "$here/check-paths.sh"
[ "$bad" -eq 0 ] && echo "test-checks: the checkers pass all $n cases"
exit $bad
