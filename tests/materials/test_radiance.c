/*
 * test_radiance.c - RADIANCE arithmetic and luminance (radiance.h).
 */
#include "testutil.h"
#include "materials/radiance.h"

START_TEST(arithmetic_and_luminance)
{
    RADIANCE a = rad_make(1, 2, 3), b = rad_grey(2);
    RADIANCE s = rad_add(a, b), m = rad_mul(a, b), k = rad_scale(a, 3);
    ck_assert(s.r == 3 && s.g == 4 && s.b == 5);
    ck_assert(m.r == 2 && m.g == 4 && m.b == 6);
    ck_assert(k.r == 3 && k.g == 6 && k.b == 9);
    ck_assert(rad_max(a) == 3 && rad_average(a) == 2);
    ck_assert(rad_is_black(rad_grey(0)) && !rad_is_black(a));
    /* white has luminance 1: the Y row of the sRGB matrix sums to 1
     * (IEC 61966-2-1: 0.2126 + 0.7152 + 0.0722) */
    ck_assert_near(rad_luminance(rad_grey(1)), 1, 2 * REAL_EPSILON);
    ck_assert(!rad_is_finite(rad_make(0, (real)NAN, 0)));
    ck_assert(!rad_is_finite(rad_make((real)INFINITY, 0, 0)));
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("radiance (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, arithmetic_and_luminance);
    suite_add_tcase(s, tc);
    return s;
}
