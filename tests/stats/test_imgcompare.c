/*
 * test_imgcompare.c - error measures (imgcompare.h): a known error pattern
 * against sums done independently in long double, the PSNR of uniform
 * noise against its variance, identical images, NaN/Inf pairs, the error
 * image.
 */
#include "testutil.h"
#include "stats/imgcompare.h"
#include "core/rng.h"

#include <string.h>

static void random_image(image_t *img, int w, int h, uint64_t seed)
{
    svet_error err;
    ck_assert_int_eq(image_alloc(img, w, h, 3, &err), SVET_OK);
    pcg32_t g;
    pcg32_seed(&g, seed, 3);
    for (size_t i = 0; i < (size_t)w * (size_t)h * 3; i++)
        img->px[i] = 0.2f + 0.8f * (float)pcg32_real(&g);
}

START_TEST(metrics_of_a_known_error_match_independent_sums)
{
    /* a = b +- d, alternating: MSE = d^2, MAE = d, max = d, PSNR (peak 1)
     * = -20 log10 d exactly in real arithmetic; relMSE summed here in long
     * double from the same float pixels. */
    image_t a, b;
    random_image(&b, 40, 30, 1);
    svet_error err;
    const float d = 0.0625f;
    /* b on a grid of 2^-10: then b +- d and a - b are exact in float */
    for (size_t i = 0; i < 40 * 30 * 3; i++)
        b.px[i] = floorf(b.px[i] * 1024.0f) / 1024.0f;
    ck_assert_int_eq(image_copy(&a, &b, &err), SVET_OK);
    long double rel = 0;
    for (size_t i = 0; i < 40 * 30 * 3; i++) {
        a.px[i] = b.px[i] + (i % 2 ? d : -d);
        long double e = (long double)a.px[i] - (long double)b.px[i];
        long double lb = (long double)b.px[i];
        rel += e * e / (lb * lb + 0.01L);
    }
    imgcompare_t m;
    ck_assert_int_eq(imgcompare(&a, &b, 1, IMGCOMPARE_EPS, &m, &err),
                     SVET_OK);
    ck_assert_uint_eq(m.n, 40 * 30 * 3);
    ck_assert_uint_eq(m.nonfinite, 0);
    ck_assert_rel(m.mse, 0.0625 * 0.0625, 1e-12, 0);
    ck_assert_rel(m.rmse, 0.0625, 1e-12, 0);
    ck_assert_rel(m.mae, 0.0625, 1e-12, 0);
    ck_assert_rel(m.max_abs, 0.0625, 1e-12, 0);
    ck_assert_rel(m.psnr, -20 * log10(0.0625), 1e-12, 0); /* 24.08 dB */
    ck_assert_rel(m.relmse, (double)(rel / (40 * 30 * 3)), 1e-12, 0);
    /* the largest error, and where */
    image_at(&a, 17, 23)[2] += 0.5f;
    ck_assert_int_eq(imgcompare(&a, &b, 1, IMGCOMPARE_EPS, &m, &err),
                     SVET_OK);
    ck_assert(m.max_x == 17 && m.max_y == 23 && m.max_c == 2);
    ck_assert_rel(m.max_abs, fabs((double)image_at(&a, 17, 23)[2] -
                                  (double)image_at(&b, 17, 23)[2]), 1e-12, 0);
    image_free(&a);
    image_free(&b);
}
END_TEST

START_TEST(psnr_of_uniform_noise_matches_its_variance)
{
    /* a = b + u, u uniform on (-h, h): E[u^2] = h^2 / 3, so MSE -> h^2/3
     * and PSNR -> 10 log10(3 / h^2). The tolerance from the variance:
     * Var(u^2) = E[u^4] - E[u^2]^2 = h^4/5 - h^4/9 = 4 h^4 / 45, so the
     * mean of N squares has standard deviation h^2 sqrt(4 / (45 N)), which
     * relative to the mean h^2/3 is 3 sqrt(4 / (45 N)) = 0.20% for
     * N = 196608. Five sigma: 1.0% on the MSE, 0.043 dB on the PSNR. */
    image_t a, b;
    random_image(&b, 256, 256, 2);
    svet_error err;
    ck_assert_int_eq(image_copy(&a, &b, &err), SVET_OK);
    const double h = 0.05;
    pcg32_t g;
    pcg32_seed(&g, 99, 5);
    const size_t N = 256 * 256 * 3;
    for (size_t i = 0; i < N; i++)
        a.px[i] += (float)(h * (2 * (double)pcg32_real(&g) - 1));
    imgcompare_t m;
    ck_assert_int_eq(imgcompare(&a, &b, 1, IMGCOMPARE_EPS, &m, &err),
                     SVET_OK);
    double sigma_rel = 3 * sqrt(4.0 / (45.0 * (double)N));
    ck_assert_rel(m.mse, h * h / 3, 5 * sigma_rel, 0);
    ck_assert_near(m.psnr, 10 * log10(3 / (h * h)),
                   10 * log10(1 + 5 * sigma_rel));
    ck_assert(m.max_abs <= h * (1 + 1e-6));
    /* peak <= 0: the reference's maximum, here just below 1 */
    imgcompare_t m2;
    ck_assert_int_eq(imgcompare(&a, &b, 0, IMGCOMPARE_EPS, &m2, &err),
                     SVET_OK);
    ck_assert(m2.peak <= 1 && m2.peak > 0.99);
    ck_assert_rel(m2.psnr, m.psnr + 20 * log10(m2.peak), 1e-9, 0);
    image_free(&a);
    image_free(&b);
    test_report_cases("psnr_of_uniform_noise_matches_its_variance", (long)N);
}
END_TEST

START_TEST(identical_images_have_zero_error_and_infinite_psnr)
{
    image_t a;
    random_image(&a, 9, 9, 3);
    imgcompare_t m;
    svet_error err;
    ck_assert_int_eq(imgcompare(&a, &a, 1, IMGCOMPARE_EPS, &m, &err),
                     SVET_OK);
    ck_assert(m.mse == 0 && m.rmse == 0 && m.relmse == 0 && m.mae == 0 &&
              m.max_abs == 0);
    ck_assert(isinf(m.psnr) && m.psnr > 0);
    image_free(&a);
}
END_TEST

START_TEST(nonfinite_pairs_are_counted_and_left_out)
{
    image_t a, b;
    random_image(&a, 4, 1, 4);
    random_image(&b, 4, 1, 5);
    imgcompare_t clean, m;
    svet_error err;
    ck_assert_int_eq(imgcompare(&a, &b, 1, 1e-2, &clean, &err), SVET_OK);
    /* the same sums without pixel 3's values */
    image_t a3, b3;
    ck_assert_int_eq(image_alloc(&a3, 3, 1, 3, &err), SVET_OK);
    ck_assert_int_eq(image_alloc(&b3, 3, 1, 3, &err), SVET_OK);
    memcpy(a3.px, a.px, 9 * sizeof(float));
    memcpy(b3.px, b.px, 9 * sizeof(float));
    image_at(&a, 3, 0)[0] = NAN;
    image_at(&b, 3, 0)[1] = INFINITY;
    image_at(&a, 3, 0)[2] = -INFINITY;
    ck_assert_int_eq(imgcompare(&a, &b, 1, 1e-2, &m, &err), SVET_OK);
    ck_assert_uint_eq(m.nonfinite, 3);
    ck_assert_uint_eq(m.n, 9);
    ck_assert_int_eq(imgcompare(&a3, &b3, 1, 1e-2, &clean, &err), SVET_OK);
    ck_assert(m.mse == clean.mse && m.relmse == clean.relmse &&
              m.mae == clean.mae);
    image_t e;
    ck_assert_int_eq(imgcompare_error_image(&a, &b, IMGCOMPARE_ABS, 1e-2, &e,
                                            &err), SVET_OK);
    ck_assert(isnan(image_at(&e, 3, 0)[0]) && isnan(image_at(&e, 3, 0)[2]));
    ck_assert(isfinite(image_at(&e, 2, 0)[0]));
    image_free(&e);
    image_free(&a);
    image_free(&b);
    image_free(&a3);
    image_free(&b3);
}
END_TEST

START_TEST(error_images_hold_each_kind_of_error)
{
    image_t a, b, e;
    svet_error err;
    ck_assert_int_eq(image_alloc(&a, 2, 1, 3, &err), SVET_OK);
    ck_assert_int_eq(image_alloc(&b, 2, 1, 4, &err), SVET_OK); /* alpha: ignored */
    image_at(&a, 0, 0)[0] = 1.5f; /* b = 1: error 0.5 */
    image_at(&b, 0, 0)[0] = 1.0f;
    image_at(&a, 1, 0)[1] = 0.25f; /* b = 0: error 0.25 */
    image_at(&b, 0, 0)[3] = 0.3f;
    ck_assert_int_eq(imgcompare_error_image(&a, &b, IMGCOMPARE_ABS, 0.01, &e,
                                            &err), SVET_OK);
    ck_assert(image_at(&e, 0, 0)[0] == 0.5f && image_at(&e, 1, 0)[1] == 0.25f);
    ck_assert_int_eq(e.channels, 3);
    image_free(&e);
    ck_assert_int_eq(imgcompare_error_image(&a, &b, IMGCOMPARE_SQUARED, 0.01,
                                            &e, &err), SVET_OK);
    ck_assert(image_at(&e, 0, 0)[0] == 0.25f);
    image_free(&e);
    /* relative: 0.5 / sqrt(1 + 0.01), 0.25 / sqrt(0.01) = 2.5 */
    ck_assert_int_eq(imgcompare_error_image(&a, &b, IMGCOMPARE_REL, 0.01, &e,
                                            &err), SVET_OK);
    ck_assert_rel(image_at(&e, 0, 0)[0], 0.5 / sqrt(1.01), 1e-6, 0);
    ck_assert_rel(image_at(&e, 1, 0)[1], 2.5, 1e-6, 0);
    image_free(&e);
    /* sizes must agree; eps must be positive */
    image_t c;
    ck_assert_int_eq(image_alloc(&c, 2, 2, 3, &err), SVET_OK);
    imgcompare_t m;
    ck_assert_int_eq(imgcompare(&a, &c, 1, 0.01, &m, &err), SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(err.msg, "2 x 1"));
    ck_assert_int_eq(imgcompare_error_image(&a, &c, IMGCOMPARE_ABS, 0.01, &e,
                                            &err), SVET_ERR_RANGE);
    ck_assert_ptr_null(e.px);
    ck_assert_int_eq(imgcompare(&a, &b, 1, 0, &m, &err), SVET_ERR_RANGE);
    image_free(&a);
    image_free(&b);
    image_free(&c);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("imgcompare");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, metrics_of_a_known_error_match_independent_sums);
    tcase_add_test(tc, psnr_of_uniform_noise_matches_its_variance);
    tcase_add_test(tc, identical_images_have_zero_error_and_infinite_psnr);
    tcase_add_test(tc, nonfinite_pairs_are_counted_and_left_out);
    tcase_add_test(tc, error_images_hold_each_kind_of_error);
    suite_add_tcase(s, tc);
    return s;
}
