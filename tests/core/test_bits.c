/*
 * test_bits.c - bits.h's count and lowest set bit, the instruction paths
 * and the plain ones, against a bit-by-bit reading of the word (the
 * definition) on single bits, the ends, all ones and random words of
 * every density.
 */
#include "testutil.h"
#include "core/bits.h"
#include "core/rng.h"

/* The definitions, one bit at a time. */
static int count_by_bits(uint64_t x)
{
    int n = 0;
    for (int i = 0; i < 64; i++)
        n += (int)(x >> i & 1);
    return n;
}

static int lowest_by_bits(uint64_t x)
{
    for (int i = 0; i < 64; i++)
        if (x >> i & 1)
            return i;
    return -1;
}

static void check_word(uint64_t x)
{
    int c = count_by_bits(x);
    ck_assert_int_eq(bits_count(x), c);
    ck_assert_int_eq(bits_count_plain(x), c);
    if (x) {
        int l = lowest_by_bits(x);
        ck_assert_int_eq(bits_lowest(x), l);
        ck_assert_int_eq(bits_lowest_plain(x), l);
    } else {
        ck_assert_int_eq(bits_lowest_plain(x), 64); /* ends, no hang */
    }
}

START_TEST(count_and_lowest_bit_agree_with_the_bits_one_by_one)
{
    long n = 0;
    check_word(0), n++;
    check_word(~UINT64_C(0)), n++;
    for (int i = 0; i < 64; i++) {
        check_word(UINT64_C(1) << i), n++;
        check_word(~UINT64_C(0) << i), n++; /* bits i ... 63 */
        check_word(~(UINT64_C(1) << i)), n++;
    }
    /* random words, sparse to dense: an AND of k draws keeps a bit with
     * probability 2^-k, an OR with 1 - 2^-k */
    pcg32_t g;
    pcg32_seed(&g, 11, 3);
    for (int k = 1; k <= 6; k++)
        for (int j = 0; j < 20000; j++) {
            uint64_t a = ~UINT64_C(0), o = 0;
            for (int d = 0; d < k; d++) {
                uint64_t w = (uint64_t)pcg32_next(&g) << 32 | pcg32_next(&g);
                a &= w;
                o |= w;
            }
            check_word(a), check_word(o), n += 2;
        }
    test_report_cases("count_and_lowest_bit_agree_with_the_bits_one_by_one",
                      n);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("bits");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, count_and_lowest_bit_agree_with_the_bits_one_by_one);
    suite_add_tcase(s, tc);
    return s;
}
