/*
 * test_rng_vectors.c - the random numbers of ch. 4 (include/core/rng.h) against
 * tests/vectors/rng_pcg32.csv and rng_sample.csv (written by
 * tools/vectors_rng.c from an independent implementation): raw PCG32
 * output, rng_for_sample, rng_dimension and pcg32_real, all exact.
 */
#include "testutil.h"
#include "core/rng.h"

#include <inttypes.h>
#include <stdlib.h>

static uint64_t u64(testcsv_t *c, const char *col)
{
    const char *s = testcsv_str(c, col);
    char *end;
    uint64_t v = strtoull(s, &end, 10);
    ck_assert_msg(end != s && *end == '\0', "%s:%d: %s = '%s' is not an "
                  "unsigned integer", c->path, c->line, col, s);
    return v;
}

START_TEST(pcg32_matches_the_vectors)
{
    testcsv_t c;
    testcsv_open(&c, "rng_pcg32.csv");
    long rows = 0;
    pcg32_t g = { 0, 1 };
    uint64_t cur_state = 0, cur_seq = 0;
    long next_index = -1;
    while (testcsv_next(&c)) {
        uint64_t st = u64(&c, "initstate"), seq = u64(&c, "initseq");
        long index = (long)u64(&c, "index");
        if (next_index < 0 || st != cur_state || seq != cur_seq ||
            index != next_index) {
            /* A new seed pair (or a gap): reseed and skip to index. */
            pcg32_seed(&g, st, seq);
            pcg32_advance(&g, (uint64_t)index);
            cur_state = st;
            cur_seq = seq;
        }
        uint32_t expect = (uint32_t)u64(&c, "output");
        uint32_t got = pcg32_next(&g);
        ck_assert_msg(got == expect, "%s:%d: pcg32(%" PRIu64 ", %" PRIu64
                      ") output %ld = 0x%08" PRIx32 ", expected 0x%08" PRIx32,
                      c.path, c.line, st, seq, index, got, expect);
        next_index = index + 1;
        rows++;
    }
    testcsv_close(&c);
    ck_assert(rows > 0);
    test_report_cases("pcg32_matches_the_vectors", rows);
}
END_TEST

START_TEST(per_sample_draws_match_the_vectors)
{
    testcsv_t c;
    testcsv_open(&c, "rng_sample.csv");
    long rows = 0;
    while (testcsv_next(&c)) {
        uint64_t seed = u64(&c, "seed"), pixel = u64(&c, "pixel");
        uint64_t sample = u64(&c, "sample"), k = u64(&c, "k");
        uint32_t expect = (uint32_t)u64(&c, "u32");
        pcg32_t g;
        rng_for_sample(&g, seed, pixel, sample);
        pcg32_advance(&g, k);
        pcg32_t h = g;
        ck_assert_msg(pcg32_next(&g) == expect, "%s:%d: u32", c.path, c.line);
        /* pcg32_real is exact in both builds: compare with == */
#ifdef SVET_DOUBLE
        double want = testcsv_num(&c, "real_double");
#else
        double want = testcsv_num(&c, "real_float");
#endif
        real u = pcg32_real(&h);
        ck_assert_msg((double)u == want, "%s:%d: pcg32_real = %.17g, expected "
                      "%.17g", c.path, c.line, (double)u, want);
        ck_assert((double)rng_dimension(seed, pixel, sample, k) == want);
        rows++;
    }
    testcsv_close(&c);
    ck_assert(rows > 0);
    test_report_cases("per_sample_draws_match_the_vectors", rows);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("rng vectors (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, pcg32_matches_the_vectors);
    tcase_add_test(tc, per_sample_draws_match_the_vectors);
    suite_add_tcase(s, tc);
    return s;
}
