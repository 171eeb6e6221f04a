/*
 * cmdtest.h - running the built svet command from a suite: the binary is
 * the one beside the suite (<build>/svet for <build>/tests/test_X), so
 * `make test` tests the command of the matching REAL.
 */
#ifndef SVET_CMDTEST_H
#define SVET_CMDTEST_H

#include <stddef.h>

/* Path of <build>/svet; fails the test if it is not built. */
const char *cmdtest_svet(void);

/* Run `svet ARGS` (a shell fragment) and return its exit code; its stdout
 * and stderr together go into out (cap bytes, NUL-terminated). Fails the
 * test if the command did not exit normally. */
int cmdtest_run(char *out, size_t cap, const char *args);

/* cmdtest_run() for a command that might hang: killed after `seconds`
 * (by timeout(1)), when it returns 124 or 137 rather than leave a stray
 * process behind the test's own time-out. */
int cmdtest_run_timed(char *out, size_t cap, int seconds, const char *args);

#endif
