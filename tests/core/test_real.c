/*
 * test_real.c - the inline functions of include/core/real.h that stand in for
 * libm in hot paths (real_max/min, real_next_up/down, real_pow2,
 * real_ldexp, real_ilogb), each checked against the libm function it
 * replaces, over random bit patterns and every special value.
 */
#include "testutil.h"
#include "core/real.h"
#include "core/rng.h"

#include <string.h>

static real from_bits(real_bits_t u)
{
    real_union_t v;
    v.u = u;
    return v.x;
}

static real_bits_t bits_of(real x)
{
    real_union_t v;
    v.x = x;
    return v.u;
}

/* Same bits, or both NaN (a NaN's payload is not part of the contract). */
static bool same(real a, real b)
{
    return (isnan(a) && isnan(b)) || bits_of(a) == bits_of(b);
}

/* Random reals of every kind: uniform bit patterns (all exponents,
 * subnormals and NaNs included) and the special values. */
static real any_real(pcg32_t *g, int i)
{
    static const real special[] = {
        0, -(real)0, 1, -1, REAL_MIN, -REAL_MIN, REAL_MAX, -REAL_MAX,
        REAL_TRUE_MIN, -REAL_TRUE_MIN, REAL_EPSILON, (real)INFINITY,
        -(real)INFINITY, (real)NAN
    };
    const int ns = (int)(sizeof special / sizeof special[0]);
    if (i < ns)
        return special[i];
    real_bits_t u = (real_bits_t)pcg32_next(g);
#ifdef SVET_DOUBLE
    u = u << 32 | (real_bits_t)pcg32_next(g);
#endif
    return from_bits(u);
}

START_TEST(next_up_and_down_are_nextafter)
{
    pcg32_t g;
    pcg32_seed(&g, 1, 2);
    long n = 0;
    for (int i = 0; i < 200000; i++, n++) {
        real x = any_real(&g, i);
        ck_assert_msg(same(real_next_up(x), nextafter(x, (real)INFINITY)),
                      "next_up(%a)", (double)x);
        ck_assert_msg(same(real_next_down(x), nextafter(x, -(real)INFINITY)),
                      "next_down(%a)", (double)x);
    }
    test_report_cases("next_up_and_down_are_nextafter", n);
}
END_TEST

START_TEST(pow2_ldexp_and_ilogb_are_libms)
{
    pcg32_t g;
    pcg32_seed(&g, 3, 4);
    long n = 0;
    for (int e = REAL_MIN_EXP - 1; e <= REAL_MAX_EXP - 1; e++, n++)
        ck_assert(same(real_pow2(e), ldexp(REAL_C(1.0), e)));
    for (int i = 0; i < 200000; i++, n++) {
        real x = any_real(&g, i);
        /* exponents across the whole range and beyond, where the result
         * overflows, underflows to subnormals or to zero */
        int e = (int)pcg32_bounded(&g, 2 * (REAL_MAX_EXP + 60)) -
                (REAL_MAX_EXP + 60);
        ck_assert_msg(same(real_ldexp(x, e), ldexp(x, e)), "ldexp(%a, %d)",
                      (double)x, e);
        ck_assert_msg(real_ilogb(x) == ilogb(x), "ilogb(%a)", (double)x);
    }
    test_report_cases("pow2_ldexp_and_ilogb_are_libms", n);
}
END_TEST

START_TEST(max_and_min_agree_with_fmax_and_fmin_without_nan)
{
    pcg32_t g;
    pcg32_seed(&g, 5, 6);
    long n = 0;
    for (int i = 0; i < 100000; i++) {
        real a = any_real(&g, i), b = any_real(&g, i + 1);
        if (isnan(a) || isnan(b) || (a == 0 && b == 0))
            continue; /* NaN and the sign of zero: see real.h */
        n++;
        ck_assert(same(real_max(a, b), fmax(a, b)));
        ck_assert(same(real_min(a, b), fmin(a, b)));
    }
    test_report_cases("max_and_min_agree_with_fmax_and_fmin_without_nan", n);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("real");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, next_up_and_down_are_nextafter);
    tcase_add_test(tc, pow2_ldexp_and_ilogb_are_libms);
    tcase_add_test(tc, max_and_min_agree_with_fmax_and_fmin_without_nan);
    suite_add_tcase(s, tc);
    return s;
}
