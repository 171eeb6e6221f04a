/*
 * test_ztest.c - the Z-test of a render against a reference (ztest.h):
 * p-values against published normal quantiles, Sidak's threshold in long
 * double, synthetic images whose noise is drawn from a known normal
 * distribution (they must pass), a 5 % bias hidden in the per-pixel noise
 * (the block levels must find it), zero-variance values, rounding, NaN,
 * the variance floor, the levels' geometry.
 */
#include "testutil.h"
#include "core/rng.h"
#include "stats/ztest.h"

#include <string.h>

/* A standard normal draw (Box-Muller) from g, in double. */
static double normal(pcg32_t *g)
{
    double u1 = ((double)pcg32_next(g) + 0.5) * 0x1p-32;
    double u2 = ((double)pcg32_next(g) + 0.5) * 0x1p-32;
    return sqrt(-2 * log(u1)) * cos(6.283185307179586 * u2);
}

static void alloc3(image_t *img, int w, int h)
{
    ck_assert_int_eq(image_alloc(img, w, h, 3, NULL), SVET_OK);
}

/* The true image of the synthetic tests: smooth, 0.2 .. 1.0. */
static double truth(int x, int y, int c)
{
    return 0.6 + 0.4 * sin(0.1 * x + 0.7 * c) * cos(0.13 * y);
}

/* mean = scale * truth + N(0, (rel * truth)^2), with var = that variance:
 * a render whose per-pixel noise has relative standard deviation rel. */
static void noisy(image_t *mean, image_t *var, int w, int h, double scale,
                  double rel, uint64_t seed)
{
    alloc3(mean, w, h);
    alloc3(var, w, h);
    pcg32_t g;
    pcg32_seed(&g, seed, 11);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++) {
                double t = truth(x, y, c), sd = rel * t;
                image_at(mean, x, y)[c] = (float)(scale * t + sd * normal(&g));
                image_at(var, x, y)[c] = (float)(sd * sd);
            }
}

START_TEST(pvalue_matches_published_normal_quantiles)
{
    /* two-sided quantiles z_{1-p/2} of the standard normal (Abramowitz &
     * Stegun, table 26.5; 16 digits from any statistics library) */
    static const double z[] = { 1.959963984540054, 2.5758293035489004,
                                3.2905267314918945, 4.891638475698996 };
    static const double p[] = { 0.05, 0.01, 0.001, 1e-6 };
    for (int i = 0; i < 4; i++) {
        ck_assert_rel(ztest_pvalue(z[i]), p[i], 1e-9, 0);
        ck_assert_rel(ztest_pvalue(-z[i]), p[i], 1e-9, 0);
    }
    ck_assert(ztest_pvalue(0) == 1);
    ck_assert(ztest_pvalue((double)INFINITY) == 0);
    ck_assert(isnan(ztest_pvalue((double)NAN)));
}
END_TEST

START_TEST(sidak_threshold_matches_long_double)
{
    ck_assert_rel(ztest_sidak(0.01, 1), 0.01, 1e-15, 0);
    const double n[] = { 2, 3, 100, 49152, 1e6 };
    for (int i = 0; i < 5; i++) {
        /* 1 - (1 - a)^(1/n) with 64-bit mantissas: the cancellation
         * leaves about 19 - log10(n) digits, 1e-12 is far inside */
        long double ref = 1.0L - powl(1.0L - 0.01L, 1.0L / (long double)n[i]);
        ck_assert_rel(ztest_sidak(0.01, n[i]), (double)ref, 1e-9, 0);
        /* and it lies between Bonferroni's alpha / n and the first-order
         * -log(1 - alpha) / n */
        ck_assert(ztest_sidak(0.01, n[i]) >= 0.01 / n[i]);
        ck_assert(ztest_sidak(0.01, n[i]) <= -log1p(-0.01) / n[i]);
    }
}
END_TEST

START_TEST(levels_run_from_pixels_to_the_whole_image)
{
    image_t a, v;
    noisy(&a, &v, 160, 120, 1, 0.1, 1);
    ztest_image_t A = { &a, &v, 16 };
    ztest_params_t p;
    ztest_params_default(&p);
    ztest_result_t r;
    ck_assert_int_eq(ztest_run(&A, &A, &p, &r, NULL, NULL), SVET_OK);
    /* blocks of 1, 4, 16, 64 pixels, then one block of the whole image */
    static const int side[] = { 1, 4, 16, 64, 160 },
                     cols[] = { 160, 40, 10, 3, 1 },
                     rows[] = { 120, 30, 8, 2, 1 };
    ck_assert_int_eq(r.nlevels, 5);
    long values = 0;
    for (int l = 0; l < 5; l++) {
        ck_assert_int_eq(r.level[l].block, side[l]);
        ck_assert_int_eq(r.level[l].cols, cols[l]);
        ck_assert_int_eq(r.level[l].rows, rows[l]);
        ck_assert_int_eq(r.level[l].cells, (long)cols[l] * rows[l]);
        ck_assert_int_eq(r.level[l].failed, 0); /* an image against itself */
        ck_assert(r.level[l].min_p == 1);
        values += 3L * cols[l] * rows[l];
    }
    ck_assert_int_eq(r.values, values);
    ck_assert_rel(r.threshold, ztest_sidak(0.01, (double)values), 1e-15, 0);
    ck_assert(r.pass);
    p.block_factor = 1; /* the pixel level alone */
    ck_assert_int_eq(ztest_run(&A, &A, &p, &r, NULL, NULL), SVET_OK);
    ck_assert_int_eq(r.nlevels, 1);
    image_free(&a);
    image_free(&v);
}
END_TEST

START_TEST(renders_of_the_same_image_pass)
{
    /* Both sides unbiased with known normal noise: each trial fails with
     * probability at most alpha = 0.01 (Sidak over every value; blocks are
     * sums of normals, so exactly normal). Over T = 40 trials the number
     * of failures is at most Binomial(40, 0.01), mean 0.4; P(X >= 5) is
     * 6e-5, so more than 4 failures means the test is too strict. */
    const int T = 40;
    int failures = 0;
    ztest_params_t p;
    ztest_params_default(&p);
    for (int t = 0; t < T; t++) {
        image_t a, va, b, vb;
        noisy(&a, &va, 48, 40, 1, 0.3, 100 + (uint64_t)t);
        noisy(&b, &vb, 48, 40, 1, 0.05, 900 + (uint64_t)t);
        /* equal spp: the floor only raises a variance up to the other
         * side's, keeping the test valid */
        ztest_image_t A = { &a, &va, 64 }, B = { &b, &vb, 64 };
        ztest_result_t r;
        ck_assert_int_eq(ztest_run(&A, &B, &p, &r, NULL, NULL), SVET_OK);
        failures += !r.pass;
        image_free(&a);
        image_free(&va);
        image_free(&b);
        image_free(&vb);
    }
    test_report_cases("renders_of_the_same_image_pass", T);
    ck_assert_msg(failures <= 4, "%d of %d unbiased trials failed", failures,
                  T);
}
END_TEST

START_TEST(five_percent_bias_fails_at_the_block_levels)
{
    /* Per-pixel relative noise 20 % on a, 2 % on b: a 5 % scale moves one
     * pixel by z = 0.05 / 0.2 = 0.25 sigma, invisible against the Sidak
     * threshold (|z| > 5.0 for ~30000 values); over the whole image
     * (N = 64 x 48 pixels) the mean moves by 0.05 mean(t) while its
     * sigma is 0.2 rms(t) / sqrt(N): z ~ 0.05 / 0.2 x 55 ~ 14. */
    image_t a, va, b, vb;
    noisy(&a, &va, 64, 48, 1.05, 0.2, 7);
    noisy(&b, &vb, 64, 48, 1, 0.02, 8);
    ztest_image_t A = { &a, &va, 16 }, B = { &b, &vb, 1600 };
    ztest_params_t p;
    ztest_params_default(&p);
    ztest_result_t r;
    ck_assert_int_eq(ztest_run(&A, &B, &p, &r, NULL, NULL), SVET_OK);
    ck_assert_msg(r.level[0].pass, "pixel level: %ld of %ld failed",
                  r.level[0].failed, r.level[0].cells);
    const ztest_level_t *top = &r.level[r.nlevels - 1];
    ck_assert_int_eq(top->cells, 1);
    ck_assert_msg(!top->pass && top->worst_z > 10, "whole image z = %g",
                  top->worst_z);
    ck_assert(!r.pass);
    /* the same with the bias taken away passes */
    image_free(&a);
    image_free(&va);
    noisy(&a, &va, 64, 48, 1, 0.2, 7);
    ck_assert_int_eq(ztest_run(&A, &B, &p, &r, NULL, NULL), SVET_OK);
    ck_assert(r.pass);
    image_free(&a);
    image_free(&va);
    image_free(&b);
    image_free(&vb);
}
END_TEST

START_TEST(zero_variance_values_must_agree)
{
    /* Exact images (no variance image): a background and an emitter seen
     * directly. Equal within 1e-5 relative passes; a difference of 1e-3
     * fails. */
    image_t a, b;
    alloc3(&a, 32, 32);
    alloc3(&b, 32, 32);
    for (int y = 0; y < 32; y++)
        for (int x = 0; x < 32; x++)
            for (int c = 0; c < 3; c++)
                image_at(&a, x, y)[c] = image_at(&b, x, y)[c] =
                    x < 16 ? 0.0f : 18.387f;
    image_at(&a, 20, 5)[1] *= 1 + 1e-6f; /* rounding of a mean */
    ztest_image_t A = { &a, NULL, 16 }, B = { &b, NULL, 1024 };
    ztest_params_t p;
    ztest_params_default(&p);
    ztest_result_t r;
    ck_assert_int_eq(ztest_run(&A, &B, &p, &r, NULL, NULL), SVET_OK);
    ck_assert(r.pass);
    ck_assert_int_eq(r.level[0].zero_var, 32 * 32 * 3);
    image_at(&a, 20, 5)[1] = 18.387f * 1.001f;
    ck_assert_int_eq(ztest_run(&A, &B, &p, &r, NULL, NULL), SVET_OK);
    ck_assert_int_eq(r.level[0].failed, 1);
    ck_assert(r.level[0].pass); /* 1 pixel of 1024: within the 0.5 % */
    ck_assert(r.level[0].worst_x == 20 && r.level[0].worst_y == 5 &&
              r.level[0].worst_c == 1 && isinf(r.level[0].worst_z) &&
              r.level[0].worst_z > 0);
    /* its 4 x 4 block is off by 0.001 / 16 relative: fails too, and with
     * 64 blocks one failure is more than 0.5 % (larger blocks dilute the
     * difference below 1e-5) */
    ck_assert_int_eq(r.level[1].failed, 1);
    ck_assert(!r.level[1].pass && !r.pass);
    image_free(&a);
    image_free(&b);
}
END_TEST

START_TEST(rounding_differences_are_not_bias)
{
    /* The furnace's estimator is exact up to rounding: 0.5 with a variance
     * of the mean near 1e-18. Two builds that round differently by a few
     * ulps (1e-6 relative) must pass; 1e-4 relative is a bias. */
    image_t a, b, va, vb;
    alloc3(&a, 16, 16);
    alloc3(&b, 16, 16);
    alloc3(&va, 16, 16);
    alloc3(&vb, 16, 16);
    for (size_t i = 0; i < 16 * 16 * 3; i++) {
        a.px[i] = 0.5f;
        b.px[i] = 0.5f * (1 + 2e-6f);
        va.px[i] = vb.px[i] = 1e-18f;
    }
    ztest_image_t A = { &a, &va, 64 }, B = { &b, &vb, 4096 };
    ztest_params_t p;
    ztest_params_default(&p);
    ztest_result_t r;
    ck_assert_int_eq(ztest_run(&A, &B, &p, &r, NULL, NULL), SVET_OK);
    ck_assert(r.pass);
    for (int l = 0; l < r.nlevels; l++)
        ck_assert(r.level[l].min_p == 1);
    for (size_t i = 0; i < 16 * 16 * 3; i++)
        b.px[i] = 0.5f * (1 + 1e-4f);
    ck_assert_int_eq(ztest_run(&A, &B, &p, &r, NULL, NULL), SVET_OK);
    ck_assert(!r.pass && r.level[0].failed == 16 * 16);
    image_free(&a);
    image_free(&b);
    image_free(&va);
    image_free(&vb);
}
END_TEST

START_TEST(nan_values_fail)
{
    image_t a, v;
    noisy(&a, &v, 8, 8, 1, 0.1, 3);
    image_t b;
    ck_assert_int_eq(image_copy(&b, &a, NULL), SVET_OK);
    image_at(&a, 3, 4)[0] = (float)NAN;
    ztest_image_t A = { &a, &v, 4 }, B = { &b, &v, 4 };
    ztest_params_t p;
    ztest_params_default(&p);
    ztest_result_t r;
    ck_assert_int_eq(ztest_run(&A, &B, &p, &r, NULL, NULL), SVET_OK);
    ck_assert_int_eq(r.level[0].failed, 1);
    ck_assert(r.level[0].min_p == 0 && isnan(r.level[0].worst_z));
    ck_assert(!r.pass);
    image_free(&a);
    image_free(&b);
    image_free(&v);
}
END_TEST

START_TEST(variance_floor_takes_the_better_sampled_side)
{
    /* One pixel: a = 0 from 16 samples that all happened to be 0 (its
     * variance estimate is 0), b = 1 with variance of the mean 0.01 from
     * 1024 samples, i.e. per-sample variance 10.24. Under the hypothesis
     * a's variance of the mean is 10.24 / 16 = 0.64:
     * z = (0 - 1) / sqrt(0.64 + 0.01). Without the spp the test would
     * believe a exact: z = -1 / 0.1 = -10. */
    image_t a, va, b, vb;
    alloc3(&a, 1, 1);
    alloc3(&va, 1, 1);
    alloc3(&b, 1, 1);
    alloc3(&vb, 1, 1);
    for (int c = 0; c < 3; c++) {
        b.px[c] = 1;
        vb.px[c] = 0.01f;
    }
    ztest_image_t A = { &a, &va, 16 }, B = { &b, &vb, 1024 };
    ztest_params_t p;
    ztest_params_default(&p);
    p.block_factor = 1;
    ztest_result_t r;
    image_t pv;
    ck_assert_int_eq(ztest_run(&A, &B, &p, &r, &pv, NULL), SVET_OK);
    /* |a - b| less the rounding allowance 1e-5 max(|a|, |b|) */
    double z = -(1 - ZTEST_ROUND_REL) / sqrt(0.64 + (double)0.01f);
    ck_assert_rel(r.level[0].worst_z, z, 1e-6, 0);
    ck_assert_rel(pv.px[0], ztest_pvalue(z), 1e-6, 0);
    ck_assert(r.pass);
    image_free(&pv);
    A.spp = 0; /* unknown: no floor */
    ck_assert_int_eq(ztest_run(&A, &B, &p, &r, NULL, NULL), SVET_OK);
    ck_assert_rel(r.level[0].worst_z, -10 * (1 - ZTEST_ROUND_REL), 1e-6, 0);
    ck_assert(!r.pass);
    image_free(&a);
    image_free(&va);
    image_free(&b);
    image_free(&vb);
}
END_TEST

START_TEST(pvalue_image_holds_the_pixel_level)
{
    /* two pixels, variance 1 on each side: z = d / sqrt(2) */
    image_t a, b, v;
    alloc3(&a, 2, 1);
    alloc3(&b, 2, 1);
    alloc3(&v, 2, 1);
    for (int c = 0; c < 3; c++) {
        image_at(&a, 0, 0)[c] = (float)(1.5 * (c + 1));
        image_at(&v, 0, 0)[c] = image_at(&v, 1, 0)[c] = 1;
    }
    ztest_image_t A = { &a, &v, 0 }, B = { &b, &v, 0 };
    ztest_params_t p;
    ztest_params_default(&p);
    ztest_result_t r;
    image_t pv;
    ck_assert_int_eq(ztest_run(&A, &B, &p, &r, &pv, NULL), SVET_OK);
    const double keep = 1 - ZTEST_ROUND_REL; /* the rounding allowance */
    for (int c = 0; c < 3; c++) {
        ck_assert_rel(image_at(&pv, 0, 0)[c],
                      erfc(keep * 1.5 * (c + 1) / sqrt(2.0) / sqrt(2.0)),
                      1e-6, 0);
        ck_assert(image_at(&pv, 1, 0)[c] == 1);
    }
    /* the whole image: mean difference 1.5 (c + 1) / 2 over
     * sqrt((1 + 1) / 4 + (1 + 1) / 4) = 1 */
    ck_assert_rel(r.level[1].worst_z, keep * 0.75 * 3, 1e-12, 0);
    image_free(&pv);
    image_free(&a);
    image_free(&b);
    image_free(&v);
}
END_TEST

START_TEST(mismatched_sizes_and_parameters_are_refused)
{
    image_t a, b;
    alloc3(&a, 4, 4);
    alloc3(&b, 4, 5);
    ztest_image_t A = { &a, NULL, 0 }, B = { &b, NULL, 0 };
    ztest_params_t p;
    ztest_params_default(&p);
    ztest_result_t r;
    svet_error err;
    image_t pv;
    ck_assert_int_eq(ztest_run(&A, &B, &p, &r, &pv, &err), SVET_ERR_RANGE);
    ck_assert(pv.px == NULL);
    ck_assert_ptr_nonnull(strstr(err.msg, "4 x 4 against 4 x 5"));
    B.mean = &a;
    A.var = &b; /* a variance image of the wrong size */
    ck_assert_int_eq(ztest_run(&A, &B, &p, &r, NULL, &err), SVET_ERR_RANGE);
    A.var = NULL;
    p.alpha = 0;
    ck_assert_int_eq(ztest_run(&A, &B, &p, &r, NULL, &err), SVET_ERR_RANGE);
    ztest_params_default(&p);
    A.spp = -1;
    ck_assert_int_eq(ztest_run(&A, &B, &p, &r, NULL, &err), SVET_ERR_RANGE);
    image_free(&a);
    image_free(&b);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("ztest (" REAL_NAME ")");
    TCase *tc = tcase_create("ztest");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, pvalue_matches_published_normal_quantiles);
    tcase_add_test(tc, sidak_threshold_matches_long_double);
    tcase_add_test(tc, levels_run_from_pixels_to_the_whole_image);
    tcase_add_test(tc, renders_of_the_same_image_pass);
    tcase_add_test(tc, five_percent_bias_fails_at_the_block_levels);
    tcase_add_test(tc, zero_variance_values_must_agree);
    tcase_add_test(tc, rounding_differences_are_not_bias);
    tcase_add_test(tc, nan_values_fail);
    tcase_add_test(tc, variance_floor_takes_the_better_sampled_side);
    tcase_add_test(tc, pvalue_image_holds_the_pixel_level);
    tcase_add_test(tc, mismatched_sizes_and_parameters_are_refused);
    suite_add_tcase(s, tc);
    return s;
}
