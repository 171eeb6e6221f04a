/*
 * test_imageio.c - images by name (imageio.h): formats told by content,
 * written by extension, and a render saved as HDR plus display image;
 * every reader's limit of pixels, and what it does with a directory, a
 * FIFO or a device; every writer on a full disk.
 */
#include "testutil.h"
#include "imgtest.h"
#include "io/exrio.h"
#include "io/imageio.h"
#include "io/netpbm.h"
#include "io/pngio.h"
#include "colour/colour.h"

#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

START_TEST(files_are_read_by_their_content_not_their_name)
{
    image_t img, back;
    svet_error err;
    imgtest_hdr_image(&img, 6, 5, 3);
    /* a PFM written under a .exr name: the reader looks at the bytes */
    const char *misnamed = imgtest_path("really-a-pfm.exr");
    ck_assert_int_eq(imageio_write(imgtest_path("x.pfm"), &img, &err),
                     SVET_OK);
    unsigned char *bytes;
    size_t n = imgtest_read_bytes(imgtest_path("x.pfm"), &bytes);
    imgtest_write_bytes(misnamed, bytes, n);
    free(bytes);
    imageio_format_t f;
    ck_assert_int_eq(imageio_read(misnamed, &back, false, &f, &err), SVET_OK);
    ck_assert_int_eq(f, IMAGEIO_PFM);
    ck_assert_mem_eq(back.px, img.px, 6 * 5 * 3 * sizeof(float));
    image_free(&back);
    /* each format by extension, and back */
    const char *names[] = { "a.exr", "a.pfm", "a.png", "a.ppm" };
    const imageio_format_t fmts[] = { IMAGEIO_EXR, IMAGEIO_PFM, IMAGEIO_PNG,
                                      IMAGEIO_PPM };
    for (int i = 0; i < 4; i++) {
        ck_assert_int_eq(imageio_format_from_name(names[i]), fmts[i]);
        ck_assert_msg(imageio_write(imgtest_path(names[i]), &img, &err) ==
                          SVET_OK, "%s", err.msg);
        ck_assert_int_eq(imageio_read(imgtest_path(names[i]), &back, false,
                                      &f, &err), SVET_OK);
        ck_assert_int_eq(f, fmts[i]);
        if (!imageio_is_display(f)) /* linear formats are exact */
            ck_assert_mem_eq(back.px, img.px, 6 * 5 * 3 * sizeof(float));
        image_free(&back);
    }
    ck_assert_int_eq(imageio_format_from_name("A.PNG"), IMAGEIO_PNG);
    ck_assert_int_eq(imageio_format_from_name("dir.png/file"),
                     IMAGEIO_UNKNOWN);
    ck_assert_int_eq(imageio_write(imgtest_path("a.jpg"), &img, &err),
                     SVET_ERR_UNSUPPORTED);
    image_free(&img);
}
END_TEST

START_TEST(display_files_can_be_read_back_as_linear)
{
    image_t img, back;
    svet_error err;
    ck_assert_int_eq(image_alloc(&img, 3, 1, 3, &err), SVET_OK);
    for (int i = 0; i < 9; i++)
        img.px[i] = (float)colour_srgb_decode_byte((uint8_t)(40 * i));
    /* encode to codes, write, read back linear: the same linear values */
    for (int i = 0; i < 9; i++)
        img.px[i] = (float)colour_srgb_encode((real)img.px[i]);
    const char *path = imgtest_path("lin.png");
    ck_assert_int_eq(imageio_write(path, &img, &err), SVET_OK);
    ck_assert_int_eq(imageio_read(path, &back, true, NULL, &err), SVET_OK);
    for (int i = 0; i < 9; i++)
        ck_assert_rel(back.px[i], colour_srgb_decode_byte((uint8_t)(40 * i)),
                      1e-5, 1e-7);
    image_free(&back);
    image_free(&img);
}
END_TEST

START_TEST(a_render_is_saved_as_hdr_and_display_image)
{
    image_t img, hdr, disp;
    svet_error err;
    imgtest_hdr_image(&img, 16, 8, 3);
    image_at(&img, 2, 2)[1] = NAN; /* a bad pixel, to be reported */
    tonemap_result_t res;
    const char *h = imgtest_path("render.exr"), *d = imgtest_path("render.png");
    ck_assert_msg(imageio_save_render(&img, h, d, NULL, &res, &err) ==
                      SVET_OK, "%s", err.msg);
    ck_assert_uint_eq(res.nonfinite, 1);
    ck_assert_int_eq(imageio_read(h, &hdr, false, NULL, &err), SVET_OK);
    ck_assert_int_eq(memcmp(hdr.px, img.px, 16 * 8 * 3 * sizeof(float)), 0);
    ck_assert_int_eq(imageio_read(d, &disp, false, NULL, &err), SVET_OK);
    ck_assert(image_at(&disp, 2, 2)[0] == 0.0f); /* written black */
    image_free(&hdr);
    image_free(&disp);
    /* the formats must match the roles */
    ck_assert_int_eq(imageio_save_render(&img, d, NULL, NULL, NULL, &err),
                     SVET_ERR_UNSUPPORTED);
    ck_assert_int_eq(imageio_save_render(&img, NULL, h, NULL, NULL, &err),
                     SVET_ERR_UNSUPPORTED);
    image_free(&img);
}
END_TEST

static svet_status read_any(const char *path, image_t *img, svet_error *err)
{
    return imageio_read(path, img, false, NULL, err);
}

START_TEST(unknown_and_empty_files_are_refused)
{
    const char *path = imgtest_path("junk.img");
    imgtest_write_bytes(path, "GIF89a....", 10);
    imgtest_check_bad_file(read_any, path, SVET_ERR_PARSE,
                           "not an EXR, PFM, PNG or PPM");
    imgtest_write_bytes(path, "", 0);
    imgtest_check_bad_file(read_any, path, SVET_ERR_PARSE, "empty");
    imgtest_check_bad_file(read_any, imgtest_path("none"), SVET_ERR_IO,
                           "cannot open");
}
END_TEST

/* The readers, each with the limits of `limits`, as imgtest_reader_fn. */
static image_read_limits_t limits;

static svet_status read_exr_lim(const char *path, image_t *img,
                                svet_error *err)
{
    return exrio_read_with(path, img, &limits, err);
}

static svet_status read_pfm_lim(const char *path, image_t *img,
                                svet_error *err)
{
    return netpbm_read_pfm_with(path, img, &limits, err);
}

static svet_status read_png_lim(const char *path, image_t *img,
                                svet_error *err)
{
    return pngio_read_with(path, img, NULL, &limits, err);
}

static svet_status read_ppm_lim(const char *path, image_t *img,
                                svet_error *err)
{
    return netpbm_read_ppm_with(path, img, NULL, &limits, err);
}

static svet_status read_any_lim(const char *path, image_t *img,
                                svet_error *err)
{
    return imageio_read_with(path, img, false, NULL, &limits, err);
}

static const struct {
    const char *name;
    imgtest_reader_fn read;
} readers[] = {
    { "x.exr", read_exr_lim }, { "x.pfm", read_pfm_lim },
    { "x.png", read_png_lim }, { "x.ppm", read_ppm_lim },
    { "x.exr", read_any_lim }, { "x.png", read_any_lim },
};
enum { NREADERS = sizeof readers / sizeof readers[0] };

START_TEST(every_reader_keeps_to_the_pixel_limit)
{
    /* A header may claim far more pixels than its bytes hold (a PNG of
     * 783 KB can declare 16384 x 16384, which deflate can just about
     * expand to): every reader refuses an image beyond its limit before
     * allocating, and reads one at the limit. */
    image_t img;
    svet_error err;
    imgtest_hdr_image(&img, 11, 10, 3);
    for (int i = 0; i < NREADERS; i++) {
        const char *path = imgtest_path(readers[i].name);
        ck_assert_int_eq(imageio_write(path, &img, &err), SVET_OK);
        limits.max_pixels = 110;
        image_t back;
        ck_assert_msg(readers[i].read(path, &back, &err) == SVET_OK, "%s",
                      err.msg);
        image_free(&back);
        limits.max_pixels = 109;
        imgtest_check_bad_file(readers[i].read, path, SVET_ERR_RANGE,
                               "exceeds the limit of 109 pixels");
    }
    image_free(&img);

    /* the default (0, or no limits at all): IMAGE_READ_MAX_PIXELS */
    limits.max_pixels = 0;
    const char *pfm = imgtest_path("big.pfm");
    imgtest_write_bytes(pfm, "PF\n16384 16384\n-1\n0123456789ab", 30);
    imgtest_check_bad_file(read_pfm_lim, pfm, SVET_ERR_RANGE,
                           "exceeds the limit of 67108864 pixels");
    imgtest_check_bad_file(read_any, pfm, SVET_ERR_RANGE, "limit");
    const char *ppm = imgtest_path("big.ppm");
    imgtest_write_bytes(ppm, "P6\n8193 8192\n255\n012345", 23);
    imgtest_check_bad_file(read_any, ppm, SVET_ERR_RANGE, "limit");
    /* a raised limit lets the header through to the next check */
    limits.max_pixels = IMAGE_MAX_PIXELS;
    imgtest_check_bad_file(read_pfm_lim, pfm, SVET_ERR_PARSE, "truncated");
    test_report_cases("every_reader_keeps_to_the_pixel_limit",
                      2 * NREADERS + 4);
}
END_TEST

START_TEST(directories_fifos_and_devices_are_refused_without_blocking)
{
    /* Opening a FIFO for reading waits for a writer; reading /dev/zero
     * never ends. Every reader says what the file is instead. */
    char fifo[1024], dir[1024];
    imgtest_special_files(fifo, dir, sizeof fifo);
    limits.max_pixels = 0;
    for (int i = 0; i < NREADERS; i++) {
        imgtest_check_bad_file(readers[i].read, dir, SVET_ERR_IO,
                               "is a directory");
        imgtest_check_bad_file(readers[i].read, fifo, SVET_ERR_IO, "FIFO");
        imgtest_check_bad_file(readers[i].read, "/dev/zero", SVET_ERR_IO,
                               "device");
    }
    test_report_cases("directories_fifos_and_devices_are_refused_without_"
                      "blocking", 3 * NREADERS);
}
END_TEST

START_TEST(every_writer_fails_cleanly_on_a_full_disk)
{
    /* A full disk fails the first write of every format: the EXR header
     * (whose failure once hung the EXR writer for ever, its error handler
     * waiting on a lock the failing call held), the PNG rows, the PFM and
     * PPM data at the final flush. Each must report it, keep the old file
     * and leave no temporary file. */
    const char *dir = imgtest_small_disk(64);
    if (!dir)
        return;
    static const char *const names[] = { "a.exr", "b.pfm", "c.png", "d.ppm",
                                         "e.exr" };
    enum { N = sizeof names / sizeof names[0] };
    char paths[N][1100];
    static const char old[] = "the previous output";
    for (int i = 0; i < N; i++) {
        snprintf(paths[i], sizeof paths[i], "%s/%s", dir, names[i]);
        imgtest_write_bytes(paths[i], old, sizeof old);
    }
    imgtest_fill_disk(dir);
    image_t img;
    imgtest_hdr_image(&img, 64, 64, 3);
    for (int i = 0; i < N; i++) {
        svet_error err;
        svet_status st = i == 4 ? exrio_write(paths[i], &img, EXRIO_HALF,
                                              EXRIO_NONE, &err)
                                : imageio_write(paths[i], &img, &err);
        ck_assert_msg(st == SVET_ERR_IO, "%s: %s", paths[i],
                      svet_status_name(st));
        ck_assert_msg(strstr(err.msg, paths[i]) != NULL, "%s", err.msg);
        ck_assert_msg(imgtest_file_is(paths[i], old, sizeof old),
                      "%s was changed", paths[i]);
        ck_assert_int_eq(imgtest_count_temps(paths[i]), 0);
    }
    image_free(&img);
    test_report_cases("every_writer_fails_cleanly_on_a_full_disk", N);
}
END_TEST

START_TEST(inputs_that_once_failed_are_handled)
{
    /* tests/data/image/regress-*: files that once crashed or misread a
     * reader (and, as they are found, the fuzzer's findings, minimised).
     * Each must read, or fail with a message that starts with its name;
     * the fuzz target's check (fuzz/fuzz_image.c). */
    const char *dir = "tests/data/image";
    DIR *d = opendir(dir);
    ck_assert_msg(d != NULL, "no %s (run from the top directory)", dir);
    struct dirent *e;
    int n = 0;
    while ((e = readdir(d)) != NULL) {
        if (strncmp(e->d_name, "regress-", 8) != 0)
            continue;
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        image_t img;
        svet_error err;
        svet_error_clear(&err);
        svet_status st = imageio_read(path, &img, true, NULL, &err);
        ck_assert_msg(st == SVET_OK ||
                          strncmp(err.msg, path, strlen(path)) == 0,
                      "%s: %s", path, err.msg);
        if (st == SVET_OK) {
            size_t k = (size_t)img.width * (size_t)img.height *
                       (size_t)img.channels;
            for (size_t i = 0; i < k; i++)
                ck_assert_msg(isfinite(img.px[i]), "%s: value %zu", path, i);
        }
        image_free(&img);
        n++;
    }
    closedir(d);
    ck_assert_int_ge(n, 7);
    test_report_cases("inputs_that_once_failed_are_handled", n);
    /* a 56-byte PNG whose zTXt chunk claims 1.7 GB is refused before
     * libpng allocates it */
    image_t img;
    svet_error err;
    const char *png = "tests/data/image/regress-png-huge-chunk.png";
    ck_assert_int_eq(imageio_read(png, &img, true, NULL, &err),
                     SVET_ERR_PARSE);
    ck_assert_msg(strstr(err.msg, "claims 1701593459 bytes"), "%s", err.msg);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("imageio");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, files_are_read_by_their_content_not_their_name);
    tcase_add_test(tc, display_files_can_be_read_back_as_linear);
    tcase_add_test(tc, a_render_is_saved_as_hdr_and_display_image);
    tcase_add_test(tc, unknown_and_empty_files_are_refused);
    tcase_add_test(tc, every_reader_keeps_to_the_pixel_limit);
    tcase_add_test(tc,
                   directories_fifos_and_devices_are_refused_without_blocking);
    tcase_add_test(tc, every_writer_fails_cleanly_on_a_full_disk);
    tcase_add_test(tc, inputs_that_once_failed_are_handled);
    suite_add_tcase(s, tc);
    return s;
}
