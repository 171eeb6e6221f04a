#!/bin/sh
# run-tests.sh - run each check suite given on the command line, then print
# one closing line "N passed, N failed" over all suites (used by make test).
# TEST_JOBS suites run at once (default: the number of cores, at most 4,
# since a suite's renders use every core already), each into a file of its
# own; each output is printed whole, the suites in the order given, so a
# run reads the same for any number of jobs (TEST_JOBS=1: one by one).
# check's per-test timeout only catches hangs; the default 4 s is too short
# for the statistical suites on a loaded machine. Tests never time code.
CK_DEFAULT_TIMEOUT=${CK_DEFAULT_TIMEOUT:-600}; export CK_DEFAULT_TIMEOUT
jobs=${TEST_JOBS:-$(nproc 2>/dev/null || echo 1)}
case "$jobs" in ''|*[!0-9]*|0) jobs=1 ;; esac
[ "$jobs" -gt 4 ] && [ -z "${TEST_JOBS:-}" ] && jobs=4
dir=$(mktemp -d "${TMPDIR:-/tmp}/svet-tests.XXXXXX") || exit 1
trap 'rm -rf "$dir"' EXIT
trap 'exit 130' INT TERM
# suite k writes $dir/k.out, then its exit status to $dir/k.rc (renamed
# into place, so a .rc file that exists is complete)
[ $# -gt 0 ] || { echo "$REAL: 0 passed, 0 failed"; exit 0; }
k=0
for t in "$@"; do
    k=$((k + 1))
    printf 'run-tests.sh\n%s/%s\n%s\n' "$dir" "$k" "$t"
done | xargs -P "$jobs" -n 3 sh -c \
    '"$2" >"$1.out" 2>&1; echo $? >"$1.tmp"; mv "$1.tmp" "$1.rc"' &
runner=$!
passed=0; failed=0; bad=""
k=0
for t in "$@"; do
    k=$((k + 1))
    while [ ! -f "$dir/$k.rc" ]; do
        # the runner gone and no status: the suite never ran to the end
        if ! kill -0 "$runner" 2>/dev/null && [ ! -f "$dir/$k.rc" ]; then
            echo 1 >"$dir/$k.rc"; break
        fi
        sleep 1
    done
    rc=$(cat "$dir/$k.rc")
    out=$(cat "$dir/$k.out" 2>/dev/null)
    printf '%s\n' "$out" | grep -v '^$'
    line=$(printf '%s\n' "$out" | grep -E '^[0-9]+%: Checks: ' | tail -n 1)
    if [ -z "$line" ]; then
        echo "$t: no check summary (exit $rc)"; failed=$((failed + 1)); bad="$bad $t"
        continue
    fi
    n=$(echo "$line" | sed -E 's/.*Checks: ([0-9]+).*/\1/')
    f=$(echo "$line" | sed -E 's/.*Failures: ([0-9]+).*/\1/')
    e=$(echo "$line" | sed -E 's/.*Errors: ([0-9]+).*/\1/')
    passed=$((passed + n - f - e)); failed=$((failed + f + e))
    if [ "$rc" -ne 0 ] || [ $((f + e)) -ne 0 ]; then bad="$bad $t"; fi
done
wait "$runner"
echo "$REAL: $passed passed, $failed failed"
if [ -n "$bad" ]; then echo "failing suites:$bad"; exit 1; fi
exit 0
