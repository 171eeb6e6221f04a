/*
 * test_rng.c - PCG32 against its published output, SplitMix64 against its
 * published values, jump-ahead against stepping, the range of pcg32_real,
 * per-sample seeding, and a chi-square test of uniformity.
 */
#include "testutil.h"
#include "core/rng.h"

#include <math.h>

START_TEST(pcg32_reproduces_the_reference_demo)
{
    /* pcg-c-basic's pcg32-demo, seeds 42 and 54 (pcg-random.org). */
    static const uint32_t expect[6] = { 0xa15c02b7, 0x7b47f409, 0xba1d3330,
                                        0x83d2f293, 0xbfa4784b, 0xcbed606e };
    pcg32_t g;
    pcg32_seed(&g, 42, 54);
    for (int i = 0; i < 6; i++)
        ck_assert_uint_eq(pcg32_next(&g), expect[i]);
}
END_TEST

START_TEST(splitmix64_reproduces_published_values)
{
    /* First outputs of SplitMix64 seeded with 0 and with 1234567
     * (java.util.SplittableRandom's mix64 after one golden-ratio step). */
    ck_assert(splitmix64(0) == UINT64_C(0xe220a8397b1dcdaf));
    ck_assert(splitmix64(1234567) == UINT64_C(6457827717110365317));
}
END_TEST

START_TEST(advance_equals_stepping)
{
    pcg32_t a, b;
    pcg32_seed(&a, 123, 456);
    b = a;
    for (int i = 0; i < 1000; i++)
        (void)pcg32_next(&a);
    pcg32_advance(&b, 1000);
    ck_assert(a.state == b.state);
    pcg32_advance(&b, (uint64_t)-1000); /* and back */
    pcg32_t c;
    pcg32_seed(&c, 123, 456);
    ck_assert(b.state == c.state);
    /* rng_dimension(k) is the k-th draw of rng_for_sample */
    pcg32_t s;
    rng_for_sample(&s, 9, 1234, 77);
    for (uint64_t k = 0; k < 50; k++)
        ck_assert(pcg32_real(&s) == rng_dimension(9, 1234, 77, k));
}
END_TEST

START_TEST(real_draws_lie_in_the_half_open_unit_interval)
{
    pcg32_t g = { UINT64_MAX, 1 };
    /* The largest output must map below 1: force it through the formula. */
#ifdef SVET_DOUBLE
    real top = (real)UINT32_MAX * REAL_C(0x1p-32);
#else
    real top = (real)(UINT32_MAX >> 8) * REAL_C(0x1p-24);
#endif
    ck_assert(top < 1);
    ck_assert(top == nextafter(REAL_C(1.0), REAL_C(0.0)) || top < 1);
    for (int i = 0; i < 100000; i++) {
        real u = pcg32_real(&g);
        ck_assert(u >= 0 && u < 1);
    }
    test_report_cases("real_draws_lie_in_the_half_open_unit_interval", 100000);
}
END_TEST

START_TEST(bounded_draws_are_uniform_chi_square)
{
    /* 7 bins, 70000 draws: chi-square with 6 degrees of freedom. The 0.999
     * quantile is 22.46 (any chi-square table), so a correct generator fails
     * this fixed-seed test with probability 1e-3 over seeds - and this seed
     * is fixed. */
    pcg32_t g;
    pcg32_seed(&g, 2024, 1);
    long count[7] = { 0 };
    const int n = 70000;
    for (int i = 0; i < n; i++)
        count[pcg32_bounded(&g, 7)]++;
    double chi2 = 0, e = n / 7.0;
    for (int i = 0; i < 7; i++)
        chi2 += (count[i] - e) * (count[i] - e) / e;
    ck_assert_msg(chi2 < 22.46, "chi2 = %g", chi2);
    test_report_cases("bounded_draws_are_uniform_chi_square", n);
}
END_TEST

START_TEST(samples_of_different_pixels_and_indices_differ)
{
    pcg32_t a, b, c;
    rng_for_sample(&a, 1, 0, 0);
    rng_for_sample(&b, 1, 1, 0);
    rng_for_sample(&c, 1, 0, 1);
    uint32_t x = pcg32_next(&a), y = pcg32_next(&b), z = pcg32_next(&c);
    ck_assert(x != y && x != z && y != z);
    /* same triple, same numbers */
    rng_for_sample(&b, 1, 0, 0);
    ck_assert_uint_eq(pcg32_next(&b), x);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("rng (" REAL_NAME ")");
    TCase *tc = tcase_create("pcg32");
    tcase_add_test(tc, pcg32_reproduces_the_reference_demo);
    tcase_add_test(tc, splitmix64_reproduces_published_values);
    tcase_add_test(tc, advance_equals_stepping);
    tcase_add_test(tc, real_draws_lie_in_the_half_open_unit_interval);
    tcase_add_test(tc, bounded_draws_are_uniform_chi_square);
    tcase_add_test(tc, samples_of_different_pixels_and_indices_differ);
    suite_add_tcase(s, tc);
    return s;
}
