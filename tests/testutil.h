/*
 * testutil.h - what every check suite shares: the main() that runs a suite,
 * real-valued asserts, the count of cases a test tried, and a reader for the
 * CSV test vectors of tests/vectors/ (format in tests/vectors/README.md).
 * Each tests/test_<module>.c defines `Suite *test_suite(void)`.
 */
#ifndef SVET_TESTUTIL_H
#define SVET_TESTUTIL_H

#include <check.h>
#include <stdbool.h>
#include <stdio.h>
#include "core/real.h"

/* check's own ck_assert_msg (which every ck_assert_* calls) also reports
 * each assertion that passes to the runner (_mark_point: a record written
 * to a file, so that a test that crashes later is reported at the last
 * point it passed). The exhaustive and statistical suites pass millions of
 * assertions, and those writes cost more than the checks themselves. Here a
 * passing assertion does nothing and a failing one fails exactly as in
 * check; a crash is reported at the test's start, or at a mark_point(). */
#undef ck_assert_msg
#define ck_assert_msg(expr, ...)                                               \
    ((expr) ? (void)0                                                          \
            : _ck_assert_failed(__FILE__, __LINE__,                            \
                                "Assertion '" #expr "' failed", __VA_ARGS__))

/* Defined by each test file; testutil.c's main() runs it. */
Suite *test_suite(void);

/* Assert |a - b| <= tol (both converted to double), with a message that
 * shows the values; NaN never passes. */
#define ck_assert_near(a, b, tol)                                              \
    do {                                                                       \
        double a_ = (double)(a), b_ = (double)(b), t_ = (double)(tol);         \
        ck_assert_msg(fabs(a_ - b_) <= t_,                                     \
                      "%s = %.17g, %s = %.17g, |diff| = %.3g > tol %.3g", #a,  \
                      a_, #b, b_, fabs(a_ - b_), t_);                          \
    } while (0)

/* Relative: |a - b| <= rel max(|a|, |b|) + abs. */
#define ck_assert_rel(a, b, rel, abs_)                                         \
    ck_assert_near(a, b,                                                       \
                   (double)(rel) * fmax(fabs((double)(a)), fabs((double)(b))) + \
                       (double)(abs_))

/* Print "<test>: <n> cases" so a reader of `make test` sees how much a
 * randomised test tried. */
void test_report_cases(const char *test, long n);

/* --- CSV test vectors ---------------------------------------------------- */
#define TESTCSV_MAXCOL 64
typedef struct {
    FILE *f;
    const char *path;
    int line;                 /* line number of the current row */
    int ncol;
    char *names[TESTCSV_MAXCOL];
    char *fields[TESTCSV_MAXCOL];
    char buf[4096];
    char header[4096];
} testcsv_t;

/* Open tests/vectors/<name>, skip '#' comment lines, read the header row.
 * Fails the calling test if the file is missing or has no header. */
void testcsv_open(testcsv_t *c, const char *name);
/* Next data row; false at the end. */
bool testcsv_next(testcsv_t *c);
/* Field of the current row by column name, as text / as a double (strtod:
 * accepts inf, nan and hex floats). Fails the test on an unknown column. */
const char *testcsv_str(testcsv_t *c, const char *col);
double testcsv_num(testcsv_t *c, const char *col);
void testcsv_close(testcsv_t *c);

#endif
