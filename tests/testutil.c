/*
 * testutil.c - main() for every suite, and the CSV vector reader.
 * See testutil.h.
 */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int main(void)
{
    SRunner *sr = srunner_create(test_suite());
    /* Sanitizer builds run in one process so that a report aborts the
     * suite visibly; otherwise check forks per test, so one crash fails
     * one test rather than the suite. */
    if (getenv("SVET_SANITIZE"))
        srunner_set_fork_status(sr, CK_NOFORK);
    srunner_run_all(sr, CK_NORMAL);
    int failed = srunner_ntests_failed(sr);
    srunner_free(sr);
    return failed == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

void test_report_cases(const char *test, long n)
{
    printf("  %s: %ld cases\n", test, n);
    fflush(stdout);
}

static int split(char *s, char **out)
{
    int n = 0;
    char *p = s;
    for (;;) {
        if (n == TESTCSV_MAXCOL)
            break;
        out[n++] = p;
        char *comma = strchr(p, ',');
        if (!comma)
            break;
        *comma = '\0';
        p = comma + 1;
    }
    return n;
}

static bool read_line(testcsv_t *c, char *buf, size_t len)
{
    while (fgets(buf, (int)len, c->f)) {
        c->line++;
        buf[strcspn(buf, "\r\n")] = '\0';
        if (buf[0] == '#' || buf[0] == '\0')
            continue;
        return true;
    }
    return false;
}

void testcsv_open(testcsv_t *c, const char *name)
{
    static char path[1024];
    memset(c, 0, sizeof *c);
    snprintf(path, sizeof path, "tests/vectors/%s", name);
    c->path = path;
    c->f = fopen(path, "r");
    ck_assert_msg(c->f != NULL, "cannot open %s (run tests from the top "
                                "directory)", path);
    ck_assert_msg(read_line(c, c->header, sizeof c->header),
                  "%s: no header row", path);
    c->ncol = split(c->header, c->names);
}

bool testcsv_next(testcsv_t *c)
{
    if (!read_line(c, c->buf, sizeof c->buf))
        return false;
    int n = split(c->buf, c->fields);
    ck_assert_msg(n == c->ncol, "%s:%d: %d fields, header has %d", c->path,
                  c->line, n, c->ncol);
    return true;
}

const char *testcsv_str(testcsv_t *c, const char *col)
{
    for (int i = 0; i < c->ncol; i++)
        if (strcmp(c->names[i], col) == 0)
            return c->fields[i];
    ck_abort_msg("%s: no column '%s'", c->path, col);
    return "";
}

double testcsv_num(testcsv_t *c, const char *col)
{
    const char *s = testcsv_str(c, col);
    char *end;
    double v = strtod(s, &end);
    ck_assert_msg(end != s && *end == '\0', "%s:%d: column %s: '%s' is not a "
                  "number", c->path, c->line, col, s);
    return v;
}

void testcsv_close(testcsv_t *c)
{
    if (c->f)
        fclose(c->f);
    c->f = NULL;
}
