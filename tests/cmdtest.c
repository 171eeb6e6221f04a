/*
 * cmdtest.c - running the built svet command from a suite; see cmdtest.h.
 */
#include "cmdtest.h"
#include "testutil.h"

#include <libgen.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

static char svet_path[1024];

const char *cmdtest_svet(void)
{
    if (!svet_path[0]) {
        char self[1024];
        ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
        ck_assert(n > 0);
        self[n] = '\0';
        char *tests_dir = dirname(self); /* <build>/tests */
        snprintf(svet_path, sizeof svet_path, "%s/../svet", tests_dir);
        ck_assert_msg(access(svet_path, X_OK) == 0, "%s is not built (make "
                      "%s builds it)", svet_path, "build/<real>/svet");
    }
    return svet_path;
}

static int run_shell(char *out, size_t cap, const char *cmd)
{
    FILE *p = popen(cmd, "r");
    ck_assert_ptr_nonnull(p);
    size_t n = fread(out, 1, cap - 1, p);
    out[n] = '\0';
    int status = pclose(p);
    ck_assert(WIFEXITED(status));
    return WEXITSTATUS(status);
}

int cmdtest_run(char *out, size_t cap, const char *args)
{
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "'%s' %s 2>&1", cmdtest_svet(), args);
    return run_shell(out, cap, cmd);
}

int cmdtest_run_timed(char *out, size_t cap, int seconds, const char *args)
{
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "timeout -k 2 %d '%s' %s 2>&1", seconds,
             cmdtest_svet(), args);
    return run_shell(out, cap, cmd);
}
