/*
 * test_text.c - include/core/text.h: the byte-order mark is found at the
 * start of a text and nowhere else.
 */
#include "testutil.h"
#include "core/text.h"

START_TEST(bom_is_three_bytes_at_the_start)
{
    ck_assert_uint_eq(text_bom_length(TEXT_BOM "camera", 9), 3);
    ck_assert_uint_eq(text_bom_length(TEXT_BOM, 3), 3);
}
END_TEST

START_TEST(text_without_a_bom_has_none)
{
    ck_assert_uint_eq(text_bom_length("camera", 6), 0);
    ck_assert_uint_eq(text_bom_length("", 0), 0);
    ck_assert_uint_eq(text_bom_length(NULL, 0), 0);
    /* a cut mark, a mark later in the text, UTF-16's FF FE */
    ck_assert_uint_eq(text_bom_length("\xEF\xBB", 2), 0);
    ck_assert_uint_eq(text_bom_length(TEXT_BOM, 2), 0);
    ck_assert_uint_eq(text_bom_length("v " TEXT_BOM, 5), 0);
    ck_assert_uint_eq(text_bom_length("\xFF\xFEv", 3), 0);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("text");
    TCase *tc = tcase_create("bom");
    tcase_add_test(tc, bom_is_three_bytes_at_the_start);
    tcase_add_test(tc, text_without_a_bom_has_none);
    suite_add_tcase(s, tc);
    return s;
}
