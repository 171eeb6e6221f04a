/*
 * test_netpbm.c - PFM and PPM/PGM without a library (netpbm.h): bit-exact
 * round trips, both byte orders, row order, and bad files made here byte
 * by byte (truncated, absurd, lying, empty, not images).
 */
#include "testutil.h"
#include "imgtest.h"
#include "io/netpbm.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

START_TEST(pfm_round_trip_is_bit_exact_even_for_nan_and_inf)
{
    image_t img, back;
    svet_error err;
    imgtest_hdr_image(&img, 13, 7, 3);
    /* the awkward values: signed zero, subnormal, extremes, NaN payload */
    const uint32_t bits[] = { 0x80000000u, 0x00000001u, 0x7f7fffffu,
                              0x7f800000u, 0xff800000u, 0x7fc01234u };
    for (int i = 0; i < 6; i++)
        memcpy(&img.px[3 * i + 1], &bits[i], 4);
    const char *path = imgtest_path("a.pfm");
    ck_assert_int_eq(netpbm_write_pfm(path, &img, &err), SVET_OK);
    ck_assert_int_eq(netpbm_read_pfm(path, &back, &err), SVET_OK);
    ck_assert_int_eq(back.width, 13);
    ck_assert_int_eq(back.height, 7);
    ck_assert_mem_eq(back.px, img.px, 13 * 7 * 3 * sizeof(float));
    image_free(&back);
    /* an RGBA image loses its alpha, keeps its colour */
    image_t rgba;
    imgtest_hdr_image(&rgba, 4, 3, 4);
    ck_assert_int_eq(netpbm_write_pfm(path, &rgba, &err), SVET_OK);
    ck_assert_int_eq(netpbm_read_pfm(path, &back, &err), SVET_OK);
    ck_assert_int_eq(back.channels, 3);
    for (int y = 0; y < 3; y++)
        for (int x = 0; x < 4; x++)
            ck_assert_mem_eq(image_at(&back, x, y), image_at(&rgba, x, y),
                             3 * sizeof(float));
    image_free(&back);
    image_free(&rgba);
    image_free(&img);
}
END_TEST

/* Bytes of a float in the given order. */
static void put_float(unsigned char *b, float v, bool big)
{
    uint32_t u;
    memcpy(&u, &v, 4);
    for (int i = 0; i < 4; i++)
        b[big ? 3 - i : i] = (unsigned char)(u >> (8 * i));
}

START_TEST(pfm_reads_both_byte_orders_and_rows_bottom_up)
{
    /* 2 x 2, rows in the file bottom first: bottom (1 2 3)(4 5 6), top
     * (7 8 9)(10 11 12); grey "Pf" likewise. */
    for (int big = 0; big < 2; big++) {
        unsigned char file[64 + 48];
        int h = snprintf((char *)file, 64, "PF\n2 2\n%s\n", big ? "1.0"
                                                                 : "-1.0");
        for (int i = 0; i < 12; i++)
            put_float(file + h + 4 * i, (float)(i + 1), big);
        const char *path = imgtest_path("order.pfm");
        imgtest_write_bytes(path, file, (size_t)h + 48);
        image_t img;
        svet_error err;
        ck_assert_int_eq(netpbm_read_pfm(path, &img, &err), SVET_OK);
        ck_assert(image_at(&img, 0, 1)[0] == 1.0f); /* bottom left */
        ck_assert(image_at(&img, 1, 1)[2] == 6.0f);
        ck_assert(image_at(&img, 0, 0)[0] == 7.0f); /* top left */
        ck_assert(image_at(&img, 1, 0)[2] == 12.0f);
        image_free(&img);

        h = snprintf((char *)file, 64, "Pf\n3 1\n%s\n", big ? "2" : "-2");
        for (int i = 0; i < 3; i++)
            put_float(file + h + 4 * i, 0.25f * (float)i, big);
        imgtest_write_bytes(path, file, (size_t)h + 12);
        ck_assert_int_eq(netpbm_read_pfm(path, &img, &err), SVET_OK);
        ck_assert_int_eq(img.channels, 3);
        for (int c = 0; c < 3; c++)
            ck_assert(image_at(&img, 2, 0)[c] == 0.5f);
        image_free(&img);
    }
}
END_TEST

START_TEST(ppm_8_and_16_bit_round_trips_are_exact)
{
    svet_error err;
    const int bits[2] = { 8, 16 };
    long cases = 0;
    for (int b = 0; b < 2; b++) {
        unsigned maxval = bits[b] == 8 ? 255u : 65535u;
        image_t img, back;
        ck_assert_int_eq(image_alloc(&img, 61, 29, 3, &err), SVET_OK);
        for (size_t i = 0; i < 61 * 29 * 3; i++)
            img.px[i] = (float)((i * 7919u) % (maxval + 1)) / (float)maxval;
        const char *path = imgtest_path("rt.ppm");
        ck_assert_int_eq(netpbm_write_ppm(path, &img, bits[b], &err), SVET_OK);
        int got_bits = 0;
        ck_assert_int_eq(netpbm_read_ppm(path, &back, &got_bits, &err),
                         SVET_OK);
        ck_assert_int_eq(got_bits, bits[b]);
        for (size_t i = 0; i < 61 * 29 * 3; i++, cases++)
            ck_assert_uint_eq(image_quantize(back.px[i], maxval),
                              image_quantize(img.px[i], maxval));
        image_free(&img);
        image_free(&back);
    }
    ck_assert_int_eq(netpbm_write_ppm(imgtest_path("x.ppm"), NULL, 12, &err),
                     SVET_ERR_RANGE);
    test_report_cases("ppm_8_and_16_bit_round_trips_are_exact", cases);
}
END_TEST

START_TEST(ppm_reader_takes_comments_grey_and_any_maxval)
{
    /* P5 (grey), a comment, maxval 1000 (two bytes a sample, big-endian) */
    const unsigned char pgm[] = "P5\n# made by hand\n2 1 # width height\n"
                                "1000\n\x01\xf4\x03\xe8";
    const char *path = imgtest_path("g.pgm");
    imgtest_write_bytes(path, pgm, sizeof pgm - 1);
    image_t img;
    svet_error err;
    int bits;
    ck_assert_int_eq(netpbm_read_ppm(path, &img, &bits, &err), SVET_OK);
    ck_assert_int_eq(bits, 16);
    for (int c = 0; c < 3; c++) {
        ck_assert(image_at(&img, 0, 0)[c] == 0.5f);
        ck_assert(image_at(&img, 1, 0)[c] == 1.0f);
    }
    image_free(&img);
}
END_TEST

static svet_status read_pfm(const char *path, image_t *img, svet_error *err)
{
    return netpbm_read_pfm(path, img, err);
}

static svet_status read_ppm(const char *path, image_t *img, svet_error *err)
{
    return netpbm_read_ppm(path, img, NULL, err);
}

/* Write `text` (then `extra` zero bytes) as a file and expect the reader
 * to refuse it. */
static void bad(imgtest_reader_fn reader, const char *name, const char *text,
                size_t extra, svet_status st, const char *words)
{
    size_t n = strlen(text);
    unsigned char *buf = calloc(1, n + extra + 1);
    ck_assert_ptr_nonnull(buf);
    memcpy(buf, text, n);
    const char *path = imgtest_path(name);
    imgtest_write_bytes(path, buf, n + extra);
    free(buf);
    imgtest_check_bad_file(reader, path, st, words);
}

START_TEST(bad_pfm_files_get_clear_errors)
{
    bad(read_pfm, "empty.pfm", "", 0, SVET_ERR_PARSE, "not a PFM");
    bad(read_pfm, "text.pfm", "hello, world\n", 0, SVET_ERR_PARSE,
        "not a PFM");
    bad(read_pfm, "png.pfm", "\x89PNG\r\n\x1a\n", 0, SVET_ERR_PARSE,
        "not a PFM");
    bad(read_pfm, "huge.pfm", "PF\n2147483648 2147483648\n-1\n", 64,
        SVET_ERR_RANGE, "2147483648");
    bad(read_pfm, "digits.pfm", "PF\n99999999999999999999999 2\n-1\n", 64,
        SVET_ERR_RANGE, "exceeds");
    bad(read_pfm, "neg.pfm", "PF\n-3 2\n-1\n", 64, SVET_ERR_PARSE, "width");
    bad(read_pfm, "zero.pfm", "PF\n0 2\n-1\n", 64, SVET_ERR_RANGE,
        "at least 1");
    bad(read_pfm, "scale0.pfm", "PF\n1 1\n0\n", 12, SVET_ERR_PARSE, "scale");
    bad(read_pfm, "scalenan.pfm", "PF\n1 1\nnan\n", 12, SVET_ERR_PARSE,
        "scale");
    bad(read_pfm, "cut.pfm", "PF\n4 4\n-1\n", 4 * 4 * 12 - 1,
        SVET_ERR_PARSE, "truncated");
    bad(read_pfm, "nohead.pfm", "PF\n4", 0, SVET_ERR_PARSE, "truncated");
    /* a header that promises 8192^2 pixels (within the limit of pixels
     * read) over 12 bytes: refused before the 768 MiB allocation */
    bad(read_pfm, "lying.pfm", "PF\n8192 8192\n-1\n", 12, SVET_ERR_PARSE,
        "truncated");
    bad(read_pfm, "missing.pfm", "PF", 0, SVET_ERR_PARSE,
        "truncated");
    imgtest_check_bad_file(read_pfm, imgtest_path("does-not-exist.pfm"),
                           SVET_ERR_IO, "cannot open");
    test_report_cases("bad_pfm_files_get_clear_errors", 14);
}
END_TEST

START_TEST(bad_ppm_files_get_clear_errors)
{
    bad(read_ppm, "empty.ppm", "", 0, SVET_ERR_PARSE, "not a binary PPM");
    bad(read_ppm, "ascii.ppm", "P3\n1 1\n255\n0 0 0\n", 0, SVET_ERR_PARSE,
        "not a binary PPM");
    bad(read_ppm, "huge.ppm", "P6\n2147483648 2147483648\n255\n", 64,
        SVET_ERR_RANGE, "2147483648");
    bad(read_ppm, "maxval0.ppm", "P6\n1 1\n0\n", 3, SVET_ERR_PARSE, "maxval");
    bad(read_ppm, "maxval.ppm", "P6\n1 1\n70000\n", 6, SVET_ERR_PARSE,
        "maxval");
    bad(read_ppm, "cut.ppm", "P6\n10 10\n255\n", 299, SVET_ERR_PARSE,
        "truncated");
    bad(read_ppm, "word.ppm", "P6\nten 10\n255\n", 300, SVET_ERR_PARSE,
        "width");
    bad(read_ppm, "glued.ppm", "P6\n10x10\n255\n", 300, SVET_ERR_PARSE,
        "followed by");
    /* a sample above maxval */
    bad(read_ppm, "above.ppm", "P5\n1 1\n100\n\xc8", 0, SVET_ERR_PARSE,
        "above maxval");
    test_report_cases("bad_ppm_files_get_clear_errors", 9);
}
END_TEST

static svet_status write_pfm(const char *path, const void *img,
                             svet_error *err)
{
    return netpbm_write_pfm(path, img, err);
}

static svet_status write_ppm16(const char *path, const void *img,
                               svet_error *err)
{
    return netpbm_write_ppm(path, img, 16, err);
}

START_TEST(failed_pfm_and_ppm_writes_keep_the_old_file)
{
    image_t img;
    imgtest_hdr_image(&img, 256, 128, 3); /* 384 KiB of PFM, 192 of PPM */
    imgtest_check_failed_write_keeps_old(write_pfm, &img,
                                         imgtest_path("old.pfm"), 32768);
    imgtest_check_failed_write_keeps_old(write_ppm16, &img,
                                         imgtest_path("old.ppm"), 32768);
    image_free(&img);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("netpbm");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, pfm_round_trip_is_bit_exact_even_for_nan_and_inf);
    tcase_add_test(tc, pfm_reads_both_byte_orders_and_rows_bottom_up);
    tcase_add_test(tc, ppm_8_and_16_bit_round_trips_are_exact);
    tcase_add_test(tc, ppm_reader_takes_comments_grey_and_any_maxval);
    tcase_add_test(tc, bad_pfm_files_get_clear_errors);
    tcase_add_test(tc, bad_ppm_files_get_clear_errors);
    tcase_add_test(tc, failed_pfm_and_ppm_writes_keep_the_old_file);
    suite_add_tcase(s, tc);
    return s;
}
