/*
 * test_error.c - status codes and messages (error.h).
 */
#include "testutil.h"
#include "core/error.h"

#include <string.h>

START_TEST(error_set_formats_and_returns_status)
{
    svet_error e;
    svet_error_clear(&e);
    ck_assert_int_eq(svet_error_set(&e, SVET_ERR_PARSE, "%s:%d:%d: unknown "
                                    "material '%s'", "cbox.scn", 14, 3, "whte"),
                     SVET_ERR_PARSE);
    ck_assert_str_eq(e.msg, "cbox.scn:14:3: unknown material 'whte'");
    ck_assert_int_eq(e.status, SVET_ERR_PARSE);
    svet_error_prefix(&e, "svet");
    ck_assert_str_eq(e.msg, "svet: cbox.scn:14:3: unknown material 'whte'");
    /* NULL is allowed: the status still comes back */
    ck_assert_int_eq(svet_error_set(NULL, SVET_ERR_IO, "x"), SVET_ERR_IO);
}
END_TEST

START_TEST(long_messages_are_truncated_not_overflowed)
{
    svet_error e;
    char big[2000];
    memset(big, 'a', sizeof big - 1);
    big[sizeof big - 1] = '\0';
    svet_error_set(&e, SVET_ERR_IO, "%s", big);
    ck_assert_uint_eq(strlen(e.msg), SVET_ERROR_LEN - 1);
    svet_error_prefix(&e, big);
    ck_assert_uint_eq(strlen(e.msg), SVET_ERROR_LEN - 1);
    ck_assert_str_eq(svet_status_name(SVET_ERR_NOMEM), "out of memory");
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("error");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, error_set_formats_and_returns_status);
    tcase_add_test(tc, long_messages_are_truncated_not_overflowed);
    suite_add_tcase(s, tc);
    return s;
}
