/*
 * test_pngio.c - PNG through libpng (pngio.h): exact 8 and 16-bit round
 * trips, every colour type read, and bad files made here (cut, CRC
 * broken, a header that lies about the size with a valid CRC, absurd
 * sizes, empty, not PNG) reported with no crash and no leak.
 */
#include "testutil.h"
#include "imgtest.h"
#include "io/pngio.h"
#include "core/rng.h"

#include <png.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static svet_status read_png(const char *path, image_t *img, svet_error *err)
{
    return pngio_read(path, img, NULL, err);
}

START_TEST(png_8_and_16_bit_round_trips_are_exact)
{
    svet_error err;
    long cases = 0;
    for (int bits = 8; bits <= 16; bits += 8)
        for (int ch = 3; ch <= 4; ch++) {
            unsigned maxval = bits == 8 ? 255u : 65535u;
            image_t img, back;
            ck_assert_int_eq(image_alloc(&img, 53, 31, ch, &err), SVET_OK);
            size_t n = (size_t)53 * 31 * (size_t)ch;
            for (size_t i = 0; i < n; i++) /* codes all over the range */
                img.px[i] = (float)((i * 40503u) % (maxval + 1)) /
                            (float)maxval;
            const char *path = imgtest_path("rt.png");
            ck_assert_msg(pngio_write(path, &img, bits, &err) == SVET_OK,
                          "%s", err.msg);
            int got = 0;
            ck_assert_msg(pngio_read(path, &back, &got, &err) == SVET_OK,
                          "%s", err.msg);
            ck_assert_int_eq(got, bits);
            ck_assert_int_eq(back.channels, ch);
            ck_assert_int_eq(back.width, 53);
            ck_assert_int_eq(back.height, 31);
            /* the same codes, hence the same floats k / maxval */
            ck_assert_mem_eq(back.px, img.px, n * sizeof(float));
            cases += (long)n;
            image_free(&img);
            image_free(&back);
        }
    ck_assert_int_eq(pngio_write(imgtest_path("x.png"), NULL, 12, &err),
                     SVET_ERR_RANGE);
    test_report_cases("png_8_and_16_bit_round_trips_are_exact", cases);
}
END_TEST

/* A PNG of any colour type, written with libpng directly: 4 x 3 pixels,
 * sample value (x + 4 y) * step in every channel (palette: index). */
static void write_raw_png(const char *path, int color, int depth,
                          int interlace, bool trns)
{
    FILE *f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL,
                                              NULL, NULL);
    png_infop info = png_create_info_struct(png);
    ck_assert(png && info);
    if (setjmp(png_jmpbuf(png)))
        ck_abort_msg("libpng failed writing the test file");
    png_init_io(png, f);
    png_set_IHDR(png, info, 4, 3, depth, color, interlace,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_color pal[12];
    for (int i = 0; i < 12; i++)
        pal[i].red = pal[i].green = pal[i].blue = (png_byte)(20 * i);
    png_byte alpha[12];
    for (int i = 0; i < 12; i++)
        alpha[i] = (png_byte)(255 - 10 * i);
    if (color == PNG_COLOR_TYPE_PALETTE)
        png_set_PLTE(png, info, pal, 12);
    if (trns)
        png_set_tRNS(png, info, alpha, 12, NULL);
    png_write_info(png, info);
    int channels = color == PNG_COLOR_TYPE_GRAY_ALPHA ? 2 : 1;
    unsigned char rows[3][16] = { { 0 } };
    for (int y = 0; y < 3; y++)
        for (int x = 0; x < 4; x++) {
            int v = x + 4 * y; /* 0..11 */
            if (depth == 1) {
                rows[y][0] |= (unsigned char)((v & 1) << (7 - x));
            } else if (depth == 16) {
                rows[y][4 * x] = rows[y][4 * x + 2] = (unsigned char)v;
                rows[y][4 * x + 1] = rows[y][4 * x + 3] = 0x11;
            } else {
                for (int c = 0; c < channels; c++)
                    rows[y][channels * x + c] = (unsigned char)(
                        color == PNG_COLOR_TYPE_PALETTE ? v : 20 * v);
            }
        }
    png_bytep rp[3] = { rows[0], rows[1], rows[2] };
    png_write_image(png, rp);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    ck_assert_int_eq(fclose(f), 0);
}

START_TEST(every_png_colour_type_is_read_as_rgb_or_rgba)
{
    const char *path = imgtest_path("types.png");
    image_t img;
    svet_error err;
    int bits;
    /* grey 8, interlaced: value 20 v / 255 in R, G and B */
    write_raw_png(path, PNG_COLOR_TYPE_GRAY, 8, PNG_INTERLACE_ADAM7, false);
    ck_assert_msg(pngio_read(path, &img, &bits, &err) == SVET_OK, "%s",
                  err.msg);
    ck_assert_int_eq(img.channels, 3);
    for (int c = 0; c < 3; c++)
        ck_assert(image_at(&img, 3, 2)[c] == 220.0f / 255.0f);
    image_free(&img);
    /* grey + alpha */
    write_raw_png(path, PNG_COLOR_TYPE_GRAY_ALPHA, 8, PNG_INTERLACE_NONE,
                  false);
    ck_assert_int_eq(pngio_read(path, &img, &bits, &err), SVET_OK);
    ck_assert_int_eq(img.channels, 4);
    ck_assert(image_at(&img, 1, 1)[2] == 100.0f / 255.0f);
    ck_assert(image_at(&img, 1, 1)[3] == 100.0f / 255.0f);
    image_free(&img);
    /* palette with tRNS: colour from the palette, alpha from tRNS */
    write_raw_png(path, PNG_COLOR_TYPE_PALETTE, 8, PNG_INTERLACE_NONE, true);
    ck_assert_int_eq(pngio_read(path, &img, &bits, &err), SVET_OK);
    ck_assert_int_eq(img.channels, 4);
    ck_assert(image_at(&img, 2, 1)[0] == 120.0f / 255.0f); /* index 6 */
    ck_assert(image_at(&img, 2, 1)[3] == 195.0f / 255.0f);
    image_free(&img);
    /* 1-bit grey: 0 or 1, scaled to 0 or 255 */
    write_raw_png(path, PNG_COLOR_TYPE_GRAY, 1, PNG_INTERLACE_NONE, false);
    ck_assert_int_eq(pngio_read(path, &img, &bits, &err), SVET_OK);
    ck_assert_int_eq(bits, 8);
    ck_assert(image_at(&img, 1, 0)[1] == 1.0f && image_at(&img, 2, 0)[1] ==
                                                     0.0f);
    image_free(&img);
    /* 16-bit grey + alpha: big-endian samples (v, 0x11) */
    write_raw_png(path, PNG_COLOR_TYPE_GRAY_ALPHA, 16, PNG_INTERLACE_NONE,
                  false);
    ck_assert_int_eq(pngio_read(path, &img, &bits, &err), SVET_OK);
    ck_assert_int_eq(bits, 16);
    ck_assert(image_at(&img, 3, 2)[0] == (float)(11 * 256 + 0x11) / 65535.0f);
    image_free(&img);
    test_report_cases("every_png_colour_type_is_read_as_rgb_or_rgba", 5);
}
END_TEST

START_TEST(bad_png_files_get_clear_errors)
{
    svet_error err;
    image_t img;
    imgtest_hdr_image(&img, 40, 40, 3);
    for (size_t i = 0; i < 40 * 40 * 3; i++)
        img.px[i] = fminf(img.px[i], 1.0f) * 0.5f;
    const char *good_path = imgtest_path("good.png");
    ck_assert_int_eq(pngio_write(good_path, &img, 8, &err), SVET_OK);
    image_free(&img);
    unsigned char *good;
    size_t n = imgtest_read_bytes(good_path, &good);
    ck_assert(imgtest_png_crc32(good + 12, 17) == ((uint32_t)good[29] << 24 |
                                          (uint32_t)good[30] << 16 |
                                          (uint32_t)good[31] << 8 | good[32]));
    unsigned char *bad = malloc(n);
    ck_assert_ptr_nonnull(bad);
    const char *path = imgtest_path("bad.png");
    long cases = 0;

    imgtest_write_bytes(path, "", 0);
    imgtest_check_bad_file(read_png, path, SVET_ERR_PARSE, "empty");
    imgtest_write_bytes(path, "GIF89a and so on", 16);
    imgtest_check_bad_file(read_png, path, SVET_ERR_PARSE, "not a PNG");
    imgtest_check_bad_file(read_png, imgtest_path("none.png"), SVET_ERR_IO,
                           "cannot open");
    cases += 3;
    /* cut in the signature, IHDR, IDAT, before IEND */
    const size_t cuts[] = { 5, 20, 40, n / 2, n - 12 };
    for (size_t i = 0; i < sizeof cuts / sizeof cuts[0]; i++, cases++) {
        imgtest_write_bytes(path, good, cuts[i]);
        imgtest_check_bad_file(read_png, path, SVET_ERR_PARSE, NULL);
    }
    /* IHDR changed without fixing its CRC */
    memcpy(bad, good, n);
    bad[19] ^= 1;
    imgtest_write_bytes(path, bad, n);
    imgtest_check_bad_file(read_png, path, SVET_ERR_PARSE, "CRC");
    /* a lying header with a valid CRC: 400 x 40 claimed, 40 x 40 stored */
    memcpy(bad, good, n);
    imgtest_png_patch_ihdr(bad, 400, 40);
    imgtest_write_bytes(path, bad, n);
    imgtest_check_bad_file(read_png, path, SVET_ERR_PARSE, NULL);
    /* lying by far: 8000 x 8000 (within the limit of pixels read) from a
     * few hundred bytes, refused before the 370 MB allocation */
    imgtest_png_patch_ihdr(bad, 8000, 8000);
    imgtest_write_bytes(path, bad, n);
    imgtest_check_bad_file(read_png, path, SVET_ERR_PARSE, "cannot hold");
    /* 16384 x 16384, as a 783 KB file can claim and deflate can just
     * about fill: beyond the limit of pixels read, refused before libpng
     * decodes a row */
    imgtest_png_patch_ihdr(bad, 16384, 16384);
    imgtest_write_bytes(path, bad, n);
    imgtest_check_bad_file(read_png, path, SVET_ERR_RANGE,
                           "exceeds the limit of 67108864 pixels");
    imgtest_png_patch_ihdr(bad, 20000, 20000); /* 4e8 pixels: beyond IMAGE_MAX_PIXELS */
    imgtest_write_bytes(path, bad, n);
    imgtest_check_bad_file(read_png, path, SVET_ERR_RANGE, "limit");
    /* absurd: 2^31 - 1 a side (libpng's own limit), and our limit */
    imgtest_png_patch_ihdr(bad, 0x7fffffffu, 0x7fffffffu);
    imgtest_write_bytes(path, bad, n);
    imgtest_check_bad_file(read_png, path, SVET_ERR_PARSE, NULL);
    imgtest_png_patch_ihdr(bad, IMAGE_MAX_DIM + 1, 1);
    imgtest_write_bytes(path, bad, n);
    imgtest_check_bad_file(read_png, path, SVET_ERR_PARSE, "limit");
    imgtest_png_patch_ihdr(bad, 0, 40);
    imgtest_write_bytes(path, bad, n);
    imgtest_check_bad_file(read_png, path, SVET_ERR_PARSE, NULL);
    cases += 7;
    /* the compressed data scribbled over (CRC broken, then recomputed) */
    memcpy(bad, good, n);
    size_t idat = 0;
    for (size_t i = 8; i + 8 < n && !idat; i++)
        if (memcmp(bad + i, "IDAT", 4) == 0)
            idat = i;
    ck_assert(idat > 0);
    uint32_t len = (uint32_t)bad[idat - 4] << 24 | (uint32_t)bad[idat - 3]
                   << 16 | (uint32_t)bad[idat - 2] << 8 | bad[idat - 1];
    for (uint32_t i = 2; i < len && i < 60; i++)
        bad[idat + 4 + i] ^= 0xa5;
    imgtest_write_bytes(path, bad, n);
    imgtest_check_bad_file(read_png, path, SVET_ERR_PARSE, NULL);
    imgtest_put_be32(bad + idat + 4 + len, imgtest_png_crc32(bad + idat, 4 + len));
    imgtest_write_bytes(path, bad, n);
    imgtest_check_bad_file(read_png, path, SVET_ERR_PARSE, NULL);
    cases += 2;
    free(bad);
    free(good);
    test_report_cases("bad_png_files_get_clear_errors", cases);
}
END_TEST

static svet_status write_png16(const char *path, const void *img,
                               svet_error *err)
{
    return pngio_write(path, img, 16, err);
}

START_TEST(a_failed_png_write_keeps_the_old_file)
{
    image_t img;
    /* random codes do not compress: 256 KiB against a 16 KiB limit */
    imgtest_hdr_image(&img, 256, 128, 4);
    pcg32_t g;
    pcg32_seed(&g, 1, 2);
    for (size_t i = 0; i < 256 * 128 * 4; i++)
        img.px[i] = (float)(pcg32_next(&g) >> 16) / 65535.0f;
    imgtest_check_failed_write_keeps_old(write_png16, &img,
                                         imgtest_path("old.png"), 16384);
    image_free(&img);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("pngio");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, png_8_and_16_bit_round_trips_are_exact);
    tcase_add_test(tc, every_png_colour_type_is_read_as_rgb_or_rgba);
    tcase_add_test(tc, bad_png_files_get_clear_errors);
    tcase_add_test(tc, a_failed_png_write_keeps_the_old_file);
    suite_add_tcase(s, tc);
    return s;
}
