/*
 * test_converge.c - convergence measurements (converge.h): error, bias and
 * efficiency of images with a known error pattern, reading series that
 * follow MSE = b^2 + c / t exactly (log-log interpolation is exact on a
 * power law, and the extrapolation is the law itself), and the CSV files
 * read back.
 */
#include "testutil.h"
#include "stats/converge.h"
#include "imgtest.h"

#include <stdlib.h>
#include <string.h>

static void filled(image_t *img, int w, int h, float v)
{
    ck_assert_int_eq(image_alloc(img, w, h, 3, NULL), SVET_OK);
    for (size_t i = 0; i < (size_t)w * (size_t)h * 3; i++)
        img->px[i] = v;
}

START_TEST(error_bias_and_efficiency_of_a_known_pattern)
{
    /* reference 0.5 everywhere with variance vr; the render 0.5 +- d
     * alternating, variance v: MSE = d^2 exactly (d, 0.5 +- d exact in
     * float), the render's own MSE d^2 - vr, bias^2 = d^2 - v - vr; the
     * relative forms divide each by 0.5^2 + 0.01 = 0.26 */
    const float d = 0.125f, v = 0.01f, vr = 0.001f;
    image_t img, var, ref, rvar;
    filled(&ref, 20, 10, 0.5f);
    filled(&rvar, 20, 10, vr);
    filled(&img, 20, 10, 0.5f);
    filled(&var, 20, 10, v);
    for (size_t i = 0; i < 20 * 10 * 3; i++)
        img.px[i] += i % 2 ? d : -d;
    converge_point_t pt;
    memset(&pt, 0, sizeof pt);
    pt.seconds = 4;
    ck_assert_int_eq(converge_measure(&img, &var, &ref, &rvar, &pt, NULL),
                     SVET_OK);
    const double dd = (double)d, vv = (double)v, vvr = (double)vr;
    ck_assert_rel(pt.rmse, dd, 1e-12, 0);
    ck_assert_rel(pt.psnr, -20 * log10(dd), 1e-12, 0); /* peak 1 */
    for (int m = CONVERGE_ABS; m <= CONVERGE_REL; m++) {
        converge_metric M = (converge_metric)m;
        double k = m == CONVERGE_REL ? 0.26 : 1;
        ck_assert_rel(pt.mse[m], dd * dd / k, 1e-12, 0);
        ck_assert_rel(pt.variance[m], vv / k, 1e-12, 0);
        ck_assert_rel(pt.ref_variance[m], vvr / k, 1e-12, 0);
        ck_assert_rel(converge_error(&pt, M), sqrt((dd * dd - vvr) / k),
                      1e-12, 0);
        ck_assert_rel(converge_bias2(&pt, M), (dd * dd - vv - vvr) / k,
                      1e-12, 0);
        ck_assert_rel(converge_efficiency(&pt, M), k / (vv * 4), 1e-12, 0);
        ck_assert_rel(converge_efficiency_mse(&pt, M),
                      k / ((dd * dd - vvr) * 4), 1e-12, 0);
        /* bias^2 = 0.0046 < v + vr = 0.011: noise explains the error */
        double b;
        ck_assert(!converge_biased(&pt, 1, M, &b));
        ck_assert_rel(b, sqrt((dd * dd - vv - vvr) / k), 1e-12, 0);
    }
    /* without variance images: every error is bias */
    ck_assert_int_eq(converge_measure(&img, NULL, &ref, NULL, &pt, NULL),
                     SVET_OK);
    ck_assert(pt.variance[0] == 0 && pt.ref_variance[1] == 0);
    double b;
    ck_assert(converge_biased(&pt, 1, CONVERGE_ABS, &b));
    ck_assert_rel(b, dd, 1e-12, 0);
    /* ... unless it is one sample per pixel, which has no variance */
    pt.spp = 1;
    ck_assert(!converge_biased(&pt, 1, CONVERGE_ABS, &b));
    ck_assert(converge_efficiency(&pt, CONVERGE_REL) == 0);
    image_t small;
    filled(&small, 10, 10, 0);
    svet_error err;
    ck_assert_int_eq(converge_measure(&img, &small, &ref, NULL, &pt, &err),
                     SVET_ERR_RANGE);
    image_free(&small);
    image_free(&img);
    image_free(&var);
    image_free(&ref);
    image_free(&rvar);
}
END_TEST

/* A series at times t[i] whose MSE is exactly b2 + c / t (no reference
 * noise), with variance c / t: what an estimator of bias b gives. */
static void series(converge_point_t *p, int n, const double *t, double c,
                   double b2)
{
    memset(p, 0, (size_t)n * sizeof *p);
    for (int i = 0; i < n; i++) {
        p[i].seconds = t[i];
        p[i].spp = 1L << i;
        for (int m = 0; m < 2; m++) {
            /* the relative metric at another scale, to tell them apart */
            double k = m ? 3 : 1;
            p[i].variance[m] = k * c / t[i];
            p[i].mse[m] = k * (b2 + c / t[i]);
        }
        p[i].rmse = sqrt(p[i].mse[0]);
    }
}

/* The absolute metric's readings of a 5-point series p. */
#define ERROR_AT(t, how) converge_error_at(p, 5, CONVERGE_ABS, t, how)
#define TIME_TO(e, how) converge_time_to(p, 5, CONVERGE_ABS, e, how)

START_TEST(an_unbiased_series_is_read_exactly_off_its_power_law)
{
    const double t[] = { 0.5, 1, 2, 4, 8 }, c = 0.02;
    converge_point_t p[5];
    series(p, 5, t, c, 0);
    ck_assert(!converge_biased(p, 5, CONVERGE_ABS, NULL));
    converge_how how;
    /* between points: log-log interpolation of e = sqrt(c / t) is exact */
    const double ts[] = { 0.5, 0.7, 3, 5.5, 8 };
    for (int i = 0; i < 5; i++) {
        ck_assert_rel(ERROR_AT(ts[i], &how), sqrt(c / ts[i]), 1e-12, 0);
        ck_assert_int_eq(how, CONVERGE_MEASURED);
        ck_assert_rel(TIME_TO(sqrt(c / ts[i]), &how), ts[i], 1e-12, 0);
        ck_assert_int_eq(how, ts[i] == 0.5 ? CONVERGE_EXTRAPOLATED
                                           : CONVERGE_MEASURED);
    }
    /* beyond them: the 1/t law from the nearest end */
    ck_assert_rel(ERROR_AT(100, &how), sqrt(c / 100), 1e-12, 0);
    ck_assert_int_eq(how, CONVERGE_EXTRAPOLATED);
    ck_assert_rel(ERROR_AT(0.1, &how), sqrt(c / 0.1), 1e-12, 0);
    ck_assert_rel(TIME_TO(sqrt(c / 100), &how), 100, 1e-12, 0);
    ck_assert_int_eq(how, CONVERGE_EXTRAPOLATED);
    ck_assert_rel(TIME_TO(sqrt(c / 0.1), &how), 0.1, 1e-12, 0);
    ck_assert_int_eq(how, CONVERGE_EXTRAPOLATED);
    /* efficiency 1 / (variance t) = 1 / c at every point */
    for (int i = 0; i < 5; i++)
        ck_assert_rel(converge_efficiency(&p[i], CONVERGE_ABS), 1 / c, 1e-12,
                      0);
    /* the relative metric reads its own columns: 3 times the MSE */
    ck_assert_rel(converge_error_at(p, 5, CONVERGE_REL, 3, &how),
                  sqrt(3 * c / 3), 1e-12, 0);
    /* nothing to read from no points */
    ck_assert(isnan(converge_error_at(p, 0, CONVERGE_ABS, 1, &how)));
    ck_assert_int_eq(how, CONVERGE_UNKNOWN);
    ck_assert(isnan(converge_time_to(p, 0, CONVERGE_ABS, 1, &how)));
}
END_TEST

START_TEST(a_biased_series_never_falls_below_its_bias)
{
    /* MSE = b^2 + c / t with b^2 = 0.01: at t = 8 the noise is
     * 0.0025 < b^2, so the series reads as biased, and the extrapolation
     * is the law itself */
    const double t[] = { 0.5, 1, 2, 4, 8 }, c = 0.02, b2 = 0.01;
    converge_point_t p[5];
    series(p, 5, t, c, b2);
    double b;
    ck_assert(converge_biased(p, 5, CONVERGE_ABS, &b));
    ck_assert_rel(b, 0.1, 1e-12, 0);
    converge_how how;
    ck_assert_rel(ERROR_AT(1000, &how), sqrt(b2 + c / 1000), 1e-12, 0);
    ck_assert_int_eq(how, CONVERGE_EXTRAPOLATED);
    ck_assert(TIME_TO(0.1, &how) == (double)INFINITY);
    ck_assert_int_eq(how, CONVERGE_NEVER);
    ck_assert(TIME_TO(0.05, &how) == (double)INFINITY);
    /* an error above the bias but below the last point: b^2 + c / t = e^2 */
    double e = sqrt(b2 + c / 20);
    ck_assert_rel(TIME_TO(e, &how), 20, 1e-12, 0);
    ck_assert_int_eq(how, CONVERGE_EXTRAPOLATED);
    /* the same law with b^2 below the noise at t = 8 is not called biased */
    series(p, 5, t, c, 0.001);
    ck_assert(!converge_biased(p, 5, CONVERGE_ABS, NULL));
}
END_TEST

/* Read path back: n points, timed by clock (the caller frees them). */
static converge_point_t *read_back(const char *path, char *method,
                                   size_t method_len, converge_clock clock,
                                   int n)
{
    converge_point_t *q;
    int got;
    converge_clock c = clock == CONVERGE_CPU ? CONVERGE_WALL : CONVERGE_CPU;
    svet_error err;
    ck_assert_int_eq(converge_csv_read(path, method, method_len, &c, &q,
                                       &got, &err), SVET_OK);
    ck_assert_int_eq(got, n);
    ck_assert_int_eq(c, clock);
    return q;
}

START_TEST(csv_files_read_back)
{
    const double t[] = { 0.25, 0.5, 1 };
    converge_point_t p[3];
    series(p, 3, t, 0.03, 0.0001);
    for (int i = 0; i < 3; i++) {
        p[i].ref_variance[0] = 1e-5;
        p[i].ref_variance[1] = 2e-5;
        p[i].psnr = 20 + i;
        p[i].rays = 1e9 + i;
    }
    const char *path = imgtest_path("series.csv");
    svet_error err;
    ck_assert_int_eq(converge_csv_write(path, "path-maxdepth=7",
                                        "scene cbox\nbuild float",
                                        CONVERGE_WALL, p, 3, &err), SVET_OK);
    char method[64];
    converge_point_t *q = read_back(path, method, sizeof method,
                                    CONVERGE_WALL, 3);
    int n;
    ck_assert_str_eq(method, "path-maxdepth=7");
    for (int i = 0; i < 3; i++) {
        /* 9 significant digits written */
        ck_assert_int_eq(q[i].spp, p[i].spp);
        ck_assert_rel(q[i].seconds, p[i].seconds, 1e-8, 0);
        ck_assert_rel(q[i].rmse, p[i].rmse, 1e-8, 0);
        ck_assert_rel(q[i].psnr, p[i].psnr, 1e-8, 0);
        for (int m = 0; m < 2; m++) {
            ck_assert_rel(q[i].mse[m], p[i].mse[m], 1e-8, 0);
            ck_assert_rel(q[i].variance[m], p[i].variance[m], 1e-8, 0);
            ck_assert_rel(q[i].ref_variance[m], p[i].ref_variance[m], 1e-8, 0);
        }
        ck_assert(q[i].rays == p[i].rays);
    }
    free(q);
    /* the comment lines and the header */
    unsigned char *bytes;
    size_t len = imgtest_read_bytes(path, &bytes);
    ck_assert(len > 0);
    ck_assert(strncmp((char *)bytes, "# scene cbox\n# build float\nmethod,spp,"
                      "seconds,rays,", 46) == 0);
    free(bytes);
    /* names that would break the CSV are refused, and the file kept */
    ck_assert_int_eq(converge_csv_write(path, "a,b", NULL, CONVERGE_WALL,
                                        p, 3, &err),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(converge_csv_write(path, "", NULL, CONVERGE_WALL, p,
                                        3, &err),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(converge_csv_read(path, method, sizeof method, NULL,
                                       &q, &n, &err), SVET_OK);
    ck_assert_int_eq(n, 3);
    free(q);
}
END_TEST

/* a series on the CPU clock names it in the header, and reads back so */
START_TEST(the_csv_header_names_the_clock)
{
    const double t[] = { 0.25, 0.5, 1 };
    converge_point_t p[3];
    series(p, 3, t, 0.03, 0.0001);
    const char *path = imgtest_path("cpu.csv");
    svet_error err;
    ck_assert_int_eq(converge_csv_write(path, "photon", "c", CONVERGE_CPU, p,
                                        3, &err), SVET_OK);
    unsigned char *bytes;
    size_t len = imgtest_read_bytes(path, &bytes);
    const char *want = "# c\nmethod,spp,cpu_seconds,rays,";
    ck_assert(len > strlen(want));
    ck_assert(strncmp((char *)bytes, want, strlen(want)) == 0);
    free(bytes);
    char method[16];
    converge_point_t *q = read_back(path, method, sizeof method,
                                    CONVERGE_CPU, 3);
    ck_assert_str_eq(method, "photon");
    for (int i = 0; i < 3; i++)
        ck_assert_rel(q[i].seconds, p[i].seconds, 1e-8, 0);
    free(q);
    ck_assert_str_eq(converge_clock_name(CONVERGE_CPU), "cpu");
    ck_assert_str_eq(converge_clock_name(CONVERGE_WALL), "wall");
}
END_TEST

/* the columns converge_csv_read needs, in another order than written */
#define HEADER "method,spp,seconds,rays,rmse,psnr,mse,variance,ref_variance," \
               "relmse,relvariance,ref_relvariance\n"

START_TEST(malformed_csv_files_are_refused_with_their_line)
{
    static const struct {
        const char *text, *words;
        svet_status st;
    } bad[] = {
        { "# only a comment\n", "no header row", SVET_ERR_PARSE },
        { "method,spp,seconds,rays\n", "no column 'rmse'", SVET_ERR_PARSE },
        { "method,spp,rays,rmse\n", "no column 'seconds' (wall clock) or "
          "'cpu_seconds'", SVET_ERR_PARSE },
        { "method,spp,seconds,cpu_seconds,rays\n", "both a column",
          SVET_ERR_PARSE },
        { HEADER "a,1,0.5,0,1,1,x,1,1,1,1,1\n", ":2: column 'mse'",
          SVET_ERR_PARSE },
        { HEADER "a,1,0.5,0,1\n", ":2: column 'psnr'", SVET_ERR_PARSE },
        { HEADER "a,-3,0.5,0,1,1,1,1,1,1,1,1\n", "spp >= 0", SVET_ERR_PARSE },
    };
    const char *path = imgtest_path("bad.csv");
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        imgtest_write_bytes(path, bad[i].text, strlen(bad[i].text));
        static converge_point_t dummy;
        converge_point_t *q = &dummy; /* must come back NULL */
        int n = -1;
        char method[8];
        svet_error err;
        ck_assert_int_eq(converge_csv_read(path, method, sizeof method, NULL,
                                           &q, &n, &err), bad[i].st);
        ck_assert_msg(strstr(err.msg, bad[i].words) && strstr(err.msg, path),
                      "case %zu: '%s'", i, err.msg);
        ck_assert(q == NULL && n == 0);
    }
    /* a header and no rows: valid, empty */
    const char *ok = HEADER;
    imgtest_write_bytes(path, ok, strlen(ok));
    converge_point_t *q;
    int n;
    char method[8];
    ck_assert_int_eq(converge_csv_read(path, method, sizeof method, NULL,
                                       &q, &n, NULL), SVET_OK);
    ck_assert(n == 0 && method[0] == '\0');
    free(q);
    /* a byte-order mark before the header is skipped, not glued to
     * "method" (a spreadsheet's "CSV UTF-8" writes one) */
    const char *bom = "\xEF\xBB\xBF" HEADER "a,1,0.5,0,1,1,1,1,1,1,1,1\n";
    imgtest_write_bytes(path, bom, strlen(bom));
    ck_assert_int_eq(converge_csv_read(path, method, sizeof method, NULL,
                                       &q, &n, NULL), SVET_OK);
    ck_assert(n == 1 && strcmp(method, "a") == 0);
    free(q);
    svet_error err;
    ck_assert_int_eq(converge_csv_read(imgtest_path("missing.csv"), method,
                                       sizeof method, NULL, &q, &n, &err),
                     SVET_ERR_IO);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("converge (" REAL_NAME ")");
    TCase *tc = tcase_create("converge");
    tcase_add_test(tc, error_bias_and_efficiency_of_a_known_pattern);
    tcase_add_test(tc, an_unbiased_series_is_read_exactly_off_its_power_law);
    tcase_add_test(tc, a_biased_series_never_falls_below_its_bias);
    tcase_add_test(tc, csv_files_read_back);
    tcase_add_test(tc, the_csv_header_names_the_clock);
    tcase_add_test(tc, malformed_csv_files_are_refused_with_their_line);
    suite_add_tcase(s, tc);
    return s;
}
