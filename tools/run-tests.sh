#!/bin/sh
# run-tests.sh - run each check suite given on the command line, then print
# one closing line "N passed, N failed" over all suites (used by make test).
# check's per-test timeout only catches hangs; the default 4 s is too short
# for the statistical suites on a loaded machine. Tests never time code.
CK_DEFAULT_TIMEOUT=${CK_DEFAULT_TIMEOUT:-600}; export CK_DEFAULT_TIMEOUT
passed=0; failed=0; bad=""
for t in "$@"; do
    out=$("$t" 2>&1); rc=$?
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
echo "$REAL: $passed passed, $failed failed"
if [ -n "$bad" ]; then echo "failing suites:$bad"; exit 1; fi
exit 0
