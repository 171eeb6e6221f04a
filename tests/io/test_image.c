/*
 * test_image.c - images and the accumulation of samples (image.h): sizes
 * checked before allocation, means, exact merges of passes, NaN/Inf
 * samples counted and not added, quantisation.
 */
#include "testutil.h"
#include "imgtest.h"
#include "io/image.h"
#include "core/rng.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

START_TEST(image_alloc_rejects_absurd_sizes)
{
    image_t img;
    svet_error err;
    const struct { int w, h, c; svet_status st; } cases[] = {
        { 0, 10, 3, SVET_ERR_RANGE },     { 10, 0, 3, SVET_ERR_RANGE },
        { -5, 10, 3, SVET_ERR_RANGE },    { 10, -5, 4, SVET_ERR_RANGE },
        { INT_MAX, INT_MAX, 3, SVET_ERR_RANGE },
        { IMAGE_MAX_DIM + 1, 1, 3, SVET_ERR_RANGE },
        { IMAGE_MAX_DIM, IMAGE_MAX_DIM, 3, SVET_ERR_RANGE }, /* 2^32 px */
        { 10, 10, 2, SVET_ERR_RANGE },    { 10, 10, 5, SVET_ERR_RANGE },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        svet_error_clear(&err);
        ck_assert_int_eq(image_alloc(&img, cases[i].w, cases[i].h,
                                     cases[i].c, &err), cases[i].st);
        ck_assert_ptr_null(img.px);
        ck_assert(err.msg[0] != '\0');
        image_free(&img); /* safe on the zeroed image */
    }
    /* 2^31 x 2^31, as a header might claim */
    ck_assert_int_eq(image_check_size(1LL << 31, 1LL << 31, 3, 4, NULL, &err),
                     SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(err.msg, "2147483648"));
    /* a byte count that overflows size_t is NOMEM, not a wrapped size */
    size_t bytes = 1;
    ck_assert_int_eq(image_check_size(1000, 1000, 4, SIZE_MAX / 1000, &bytes,
                                      &err), SVET_ERR_NOMEM);
    ck_assert_uint_eq(bytes, 1); /* untouched */
    ck_assert_int_eq(image_check_size(7, 5, 3, 4, &bytes, &err), SVET_OK);
    ck_assert_uint_eq(bytes, 7 * 5 * 3 * 4);
    test_report_cases("image_alloc_rejects_absurd_sizes",
                      (long)(sizeof cases / sizeof cases[0]) + 3);
}
END_TEST

START_TEST(image_alloc_zeroes_and_free_is_idempotent)
{
    image_t img;
    svet_error err;
    ck_assert_int_eq(image_alloc(&img, 5, 3, 4, &err), SVET_OK);
    for (int i = 0; i < 5 * 3 * 4; i++)
        ck_assert(img.px[i] == 0.0f);
    image_set(&img, 4, 2, rad_make(REAL_C(1), REAL_C(2), REAL_C(3)));
    ck_assert(image_at(&img, 4, 2) == img.px + (2 * 5 + 4) * 4);
    RADIANCE c = image_get(&img, 4, 2);
    ck_assert(c.r == 1 && c.g == 2 && c.b == 3);
    image_t copy;
    ck_assert_int_eq(image_copy(&copy, &img, &err), SVET_OK);
    ck_assert_mem_eq(copy.px, img.px, 5 * 3 * 4 * sizeof(float));
    image_free(&copy);
    image_free(&img);
    image_free(&img);
    image_free(NULL);
    ck_assert_ptr_null(img.px);
}
END_TEST

START_TEST(accumulation_resolves_to_the_mean_and_counts_empty_pixels)
{
    image_accum_t acc;
    svet_error err;
    ck_assert_int_eq(image_accum_alloc(&acc, 3, 2, &err), SVET_OK);
    /* pixel (1, 0): 1, 2, 4 -> mean 7/3; pixel (2, 1): one sample */
    image_accum_add(&acc, 1, 0, rad_grey(REAL_C(1)));
    image_accum_add(&acc, 1, 0, rad_grey(REAL_C(2)));
    image_accum_add(&acc, 1, 0, rad_make(REAL_C(4), REAL_C(4), REAL_C(-1)));
    image_accum_add(&acc, 2, 1, rad_make(REAL_C(0.5), REAL_C(0), REAL_C(8)));
    image_t img;
    uint64_t empty = 99;
    ck_assert_int_eq(image_accum_resolve(&acc, &img, &empty, &err), SVET_OK);
    ck_assert_uint_eq(empty, 4);
    ck_assert_int_eq(img.channels, 3);
    const float *p = image_at(&img, 1, 0);
    ck_assert(p[0] == (float)(7.0 / 3.0) && p[1] == (float)(7.0 / 3.0));
    ck_assert(p[2] == (float)(2.0 / 3.0)); /* signed samples are kept */
    p = image_at(&img, 2, 1);
    ck_assert(p[0] == 0.5f && p[1] == 0.0f && p[2] == 8.0f);
    ck_assert(image_at(&img, 0, 0)[0] == 0.0f);
    ck_assert_uint_eq(image_accum_samples(&acc), 4);
    image_free(&img);
    image_accum_free(&acc);
    image_accum_free(&acc);
}
END_TEST

START_TEST(nonfinite_samples_are_counted_not_added)
{
    image_accum_t acc;
    svet_error err;
    ck_assert_int_eq(image_accum_alloc(&acc, 2, 1, &err), SVET_OK);
    image_accum_add(&acc, 0, 0, rad_grey(REAL_C(3)));
    image_accum_add(&acc, 0, 0, rad_make(REAL_C(1), (real)NAN, REAL_C(1)));
    image_accum_add(&acc, 0, 0, rad_make((real)INFINITY, 0, 0));
    image_accum_add(&acc, 0, 0, rad_make(0, 0, -(real)INFINITY));
    image_accum_add(&acc, 0, 0, rad_grey(REAL_C(5)));
    image_accum_add(&acc, 1, 0, rad_grey((real)NAN));
    ck_assert_uint_eq(image_accum_nonfinite(&acc), 4);
    ck_assert_uint_eq(acc.nonfinite[0], 3);
    ck_assert_uint_eq(acc.nonfinite[1], 1);
    ck_assert_uint_eq(image_accum_samples(&acc), 2);
    image_t img;
    uint64_t empty;
    ck_assert_int_eq(image_accum_resolve(&acc, &img, &empty, &err), SVET_OK);
    /* the mean of the finite samples 3 and 5; the NaN-only pixel black */
    for (int c = 0; c < 3; c++) {
        ck_assert(image_at(&img, 0, 0)[c] == 4.0f);
        ck_assert(image_at(&img, 1, 0)[c] == 0.0f);
    }
    ck_assert_uint_eq(empty, 1);
    image_free(&img);
    image_accum_free(&acc);
}
END_TEST

/* A sample of pixel i, pass-independent: a float in [0, 16) (double in the
 * double build), a multiple of 2^-20 (2^-28). */
static RADIANCE sample_of(int i, int s)
{
    pcg32_t g;
    rng_for_sample(&g, 7, (uint64_t)i, (uint64_t)s);
    real r = 16 * pcg32_real(&g), gg = 16 * pcg32_real(&g);
    return rad_make(r, gg, 16 * pcg32_real(&g));
}

START_TEST(merged_passes_equal_one_accumulation_bit_for_bit)
{
    /* The samples are multiples of 2^-20 (float build; 2^-28 in double)
     * below 16, 256 of them per pixel: every partial sum is a multiple of
     * that quantum below 2^12, i.e. an integer below 2^32 (2^40) quanta,
     * exactly representable in double. So the sums are exact, and a merge
     * of passes gives the same bits as one accumulation, in any order
     * (image.h). The split point differs from pixel to pixel. */
    enum { W = 17, H = 9, N = 256 };
    image_accum_t one, a, b, c, abc, cba;
    svet_error err;
    image_accum_t *all[] = { &one, &a, &b, &c, &abc, &cba };
    for (int k = 0; k < 6; k++)
        ck_assert_int_eq(image_accum_alloc(all[k], W, H, &err), SVET_OK);
    long cases = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int i = y * W + x, cut1 = (i * 37) % N, cut2 = cut1 + (N - cut1) / 3;
            for (int s = 0; s < N; s++) {
                RADIANCE L = sample_of(i, s);
                image_accum_add(&one, x, y, L);
                image_accum_add(s < cut1 ? &a : s < cut2 ? &b : &c, x, y, L);
                cases++;
            }
        }
    ck_assert_int_eq(image_accum_merge(&abc, &a, &err), SVET_OK);
    ck_assert_int_eq(image_accum_merge(&abc, &b, &err), SVET_OK);
    ck_assert_int_eq(image_accum_merge(&abc, &c, &err), SVET_OK);
    ck_assert_int_eq(image_accum_merge(&cba, &c, &err), SVET_OK);
    ck_assert_int_eq(image_accum_merge(&cba, &b, &err), SVET_OK);
    ck_assert_int_eq(image_accum_merge(&cba, &a, &err), SVET_OK);
    size_t n = (size_t)W * H;
    ck_assert_mem_eq(abc.sum, one.sum, 3 * n * sizeof(image_fixed_t));
    ck_assert_mem_eq(cba.sum, one.sum, 3 * n * sizeof(image_fixed_t));
    ck_assert_mem_eq(abc.count, one.count, n * sizeof(uint64_t));
    image_t i1, i2;
    ck_assert_int_eq(image_accum_resolve(&one, &i1, NULL, &err), SVET_OK);
    ck_assert_int_eq(image_accum_resolve(&cba, &i2, NULL, &err), SVET_OK);
    ck_assert_mem_eq(i1.px, i2.px, 3 * n * sizeof(float));
    /* independent check of one pixel's mean, in long double */
    long double ref = 0;
    for (int s = 0; s < N; s++)
        ref += (long double)sample_of(5 * W + 3, s).g;
    ck_assert_near(image_at(&i1, 3, 5)[1], (double)(ref / N), 1e-6);
    image_free(&i1);
    image_free(&i2);
    for (int k = 0; k < 6; k++)
        image_accum_free(all[k]);
    test_report_cases("merged_passes_equal_one_accumulation_bit_for_bit",
                      cases);
}
END_TEST

START_TEST(wide_range_sums_are_exact_in_any_order)
{
    /* Samples of 2^35, 2^-40 and -2^-40 and 1: a double sum of them
     * rounds (2^35 + 2^-40 needs 76 bits), so its result depends on the
     * order. The fixed-point sums must give the same bits forward,
     * backward and split into two merged halves, and the exact value:
     * k big + m small - j small + ones, worked out by hand. */
    const double v[4] = { 0x1p35, 0x1p-40, -0x1p-40, 1.0 };
    enum { N = 4000 };
    image_accum_t fw, bw, h1, h2;
    svet_error err;
    image_accum_t *all[] = { &fw, &bw, &h1, &h2 };
    for (int k = 0; k < 4; k++)
        ck_assert_int_eq(image_accum_alloc(all[k], 1, 1, &err), SVET_OK);
    /* sample s is v[s % 4], but the negative one only for s % 8 == 2
     * (the positive small one otherwise), so the sum is positive */
    double sample[N];
    for (int s = 0; s < N; s++)
        sample[s] = s % 8 == 6 ? v[1] : v[s % 4];
    for (int s = 0; s < N; s++) {
        image_accum_add(&fw, 0, 0, rad_grey((real)sample[s]));
        image_accum_add(&bw, 0, 0, rad_grey((real)sample[N - 1 - s]));
        image_accum_add(s % 3 ? &h1 : &h2, 0, 0, rad_grey((real)sample[s]));
    }
    ck_assert_int_eq(image_accum_merge(&h2, &h1, &err), SVET_OK);
    ck_assert_mem_eq(fw.sum, bw.sum, 3 * sizeof(image_fixed_t));
    ck_assert_mem_eq(fw.sum, h2.sum, 3 * sizeof(image_fixed_t));
    uint64_t big = 0, small = 0, ones = 0; /* small: net count of 2^-40 */
    for (int s = 0; s < N; s++) {
        if (sample[s] == v[0])
            big++;
        else if (sample[s] == v[3])
            ones++;
        else if (sample[s] == v[1])
            small++;
        else
            small--;
    }
    ck_assert_uint_eq(small, 1000 + 500 - 500);
    /* the exact sum in units of 2^-96: big 2^131 + ones 2^96 + small 2^56,
     * limb by limb (2^131 = 2^128 2^3, 2^96 = 2^64 2^32) */
    const image_fixed_t *t = &fw.sum[1];
    ck_assert_uint_eq(t->w[0], (small & 255) << 56);
    ck_assert_uint_eq(t->w[1], (ones << 32) + (small >> 8));
    ck_assert_uint_eq(t->w[2], big << 3);
    /* its double: within an ulp of the correctly rounded value */
    double ref = (double)big * 0x1p35 + (double)ones + (double)small * 0x1p-40;
    ck_assert(fabs(image_fixed_value(t, IMAGE_SUM_Q) - ref) <= ref * 0x1p-52);
    /* and a sum that fits a double comes back exactly: negatives too */
    image_fixed_t z = { { 0, 0, 0 } };
    image_fixed_add_double(&z, -3.25, IMAGE_SUM_Q);
    image_fixed_add_double(&z, 0x1p-70, IMAGE_SUM_Q);
    ck_assert(image_fixed_value(&z, IMAGE_SUM_Q) == -3.25 + 0x1p-70);
    image_fixed_add_double(&z, 3.25, IMAGE_SUM_Q);
    image_fixed_add_double(&z, -0x1p-70, IMAGE_SUM_Q);
    ck_assert(z.w[0] == 0 && z.w[1] == 0 && z.w[2] == 0);
    /* a sample at the window's edge is dropped, one just inside is not */
    ck_assert(!image_accum_add(&fw, 0, 0, rad_grey((real)IMAGE_SAMPLE_MAX)));
    ck_assert(image_accum_add(&fw, 0, 0, rad_grey((real)(0.5 * IMAGE_SAMPLE_MAX))));
    for (int k = 0; k < 4; k++)
        image_accum_free(all[k]);
}
END_TEST

START_TEST(merge_refuses_a_different_size_and_leaves_dst_alone)
{
    image_accum_t a, b;
    svet_error err;
    ck_assert_int_eq(image_accum_alloc(&a, 4, 4, &err), SVET_OK);
    ck_assert_int_eq(image_accum_alloc(&b, 4, 5, &err), SVET_OK);
    image_accum_add(&a, 0, 0, rad_grey(1));
    image_accum_add(&b, 0, 0, rad_grey(1));
    ck_assert_int_eq(image_accum_merge(&a, &b, &err), SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(err.msg, "4 x 5"));
    ck_assert_uint_eq(a.count[0], 1);
    ck_assert(image_fixed_value(&a.sum[0], IMAGE_SUM_Q) == 1.0);
    image_accum_free(&a);
    image_accum_free(&b);
    ck_assert_int_eq(image_accum_alloc(&b, 0, 5, &err), SVET_ERR_RANGE);
    ck_assert_ptr_null(b.sum);
}
END_TEST

START_TEST(quantize_round_trips_every_code_and_clamps)
{
    const unsigned maxv[2] = { 255, 65535 };
    long cases = 0;
    for (int m = 0; m < 2; m++)
        for (unsigned k = 0; k <= maxv[m]; k++, cases++)
            ck_assert_uint_eq(image_quantize((float)k / (float)maxv[m],
                                             maxv[m]), k);
    ck_assert_uint_eq(image_quantize(-0.5f, 255), 0);
    ck_assert_uint_eq(image_quantize(1.5f, 255), 255);
    ck_assert_uint_eq(image_quantize(NAN, 255), 0);
    ck_assert_uint_eq(image_quantize(INFINITY, 65535), 65535);
    ck_assert_uint_eq(image_quantize(-INFINITY, 65535), 0);
    /* rounding to nearest: 0.5/255 is a tie, which goes up */
    ck_assert_uint_eq(image_quantize(0.499f / 255.0f, 255), 0);
    ck_assert_uint_eq(image_quantize(0.501f / 255.0f, 255), 1);
    test_report_cases("quantize_round_trips_every_code_and_clamps", cases);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("image");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, image_alloc_rejects_absurd_sizes);
    tcase_add_test(tc, image_alloc_zeroes_and_free_is_idempotent);
    tcase_add_test(tc, accumulation_resolves_to_the_mean_and_counts_empty_pixels);
    tcase_add_test(tc, nonfinite_samples_are_counted_not_added);
    tcase_add_test(tc, merged_passes_equal_one_accumulation_bit_for_bit);
    tcase_add_test(tc, wide_range_sums_are_exact_in_any_order);
    tcase_add_test(tc, merge_refuses_a_different_size_and_leaves_dst_alone);
    tcase_add_test(tc, quantize_round_trips_every_code_and_clamps);
    suite_add_tcase(s, tc);
    return s;
}
