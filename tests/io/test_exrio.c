/*
 * test_exrio.c - OpenEXR through the C API (exrio.h): float round trips bit
 * for bit, half within half precision, channels found by name, tiled and
 * deep files refused, bad files (made here: cut, flipped, patched to absurd
 * sizes) reported, failed writes harmless.
 */
#include "testutil.h"
#include "core/rng.h"
#include "imgtest.h"
#include "io/exrio.h"

#include <openexr.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static svet_status read_exr(const char *path, image_t *img, svet_error *err)
{
    return exrio_read(path, img, err);
}

START_TEST(float_exr_round_trip_is_bit_exact)
{
    svet_error err;
    long cases = 0;
    for (int ch = 3; ch <= 4; ch++)
        for (int comp = 0; comp < 2; comp++) {
            image_t img, back;
            /* 37 x 41: the last ZIP chunk (16 lines) is partial */
            imgtest_hdr_image(&img, 37, 41, ch);
            const uint32_t bits[] = { 0x80000000u, 0x00000001u, 0x7f7fffffu,
                                      0x7f800000u, 0xff800000u, 0x7fc00000u };
            for (int i = 0; i < 6; i++)
                memcpy(&img.px[ch * (5 + 7 * i)], &bits[i], 4);
            const char *path = imgtest_path("f.exr");
            ck_assert_msg(exrio_write(path, &img, EXRIO_FLOAT,
                                      comp ? EXRIO_ZIP : EXRIO_NONE, &err) ==
                              SVET_OK, "%s", err.msg);
            ck_assert_msg(exrio_read(path, &back, &err) == SVET_OK, "%s",
                          err.msg);
            ck_assert_int_eq(back.width, 37);
            ck_assert_int_eq(back.height, 41);
            ck_assert_int_eq(back.channels, ch);
            ck_assert_mem_eq(back.px, img.px,
                             (size_t)37 * 41 * (size_t)ch * sizeof(float));
            cases += 37 * 41 * ch;
            image_free(&img);
            image_free(&back);
        }
    test_report_cases("float_exr_round_trip_is_bit_exact", cases);
}
END_TEST

START_TEST(half_exr_round_trip_is_within_half_precision)
{
    /* A half has 11 significant bits: rounding to nearest errs by at most
     * 2^-11 relative for normal halves (|v| >= 2^-14), and by at most half
     * the subnormal spacing, 2^-25, below. Values that are halves already
     * come back exactly; beyond the largest half (65504) comes Inf. */
    svet_error err;
    image_t img, back;
    imgtest_hdr_image(&img, 64, 32, 4);
    float *px = img.px;
    px[0] = 65504.0f;       /* largest half */
    px[1] = 0x1p-14f;       /* smallest normal half */
    px[2] = 0x1p-24f;       /* smallest subnormal half */
    px[4] = 1e6f;           /* overflows */
    px[5] = -3.0f;
    px[6] = 1.0f + 0x1p-10f; /* exactly a half */
    const char *path = imgtest_path("h.exr");
    ck_assert_msg(exrio_write(path, &img, EXRIO_HALF, EXRIO_ZIP, &err) ==
                      SVET_OK, "%s", err.msg);
    ck_assert_msg(exrio_read(path, &back, &err) == SVET_OK, "%s", err.msg);
    ck_assert_int_eq(back.channels, 4);
    long cases = 0;
    for (size_t i = 0; i < 64 * 32 * 4; i++) {
        if (i == 4)
            continue;
        double v = (double)img.px[i], b = (double)back.px[i];
        if (fabs(v) >= 0x1p-14)
            ck_assert_rel(b, v, 0x1p-11, 0);
        else
            ck_assert_near(b, v, 0x1p-25);
        cases++;
    }
    ck_assert(back.px[0] == 65504.0f && back.px[1] == 0x1p-14f &&
              back.px[2] == 0x1p-24f && back.px[5] == -3.0f &&
              back.px[6] == 1.0f + 0x1p-10f);
    ck_assert(isinf(back.px[4]) && back.px[4] > 0);
    image_free(&img);
    image_free(&back);
    test_report_cases("half_exr_round_trip_is_within_half_precision", cases);
}
END_TEST

/* --- files with other channels, written here through the C API ---------- */

/* The value every test channel holds at (x, y): distinct per name. */
static float channel_value(const char *name, int x, int y)
{
    return (float)(name[0] + 100 * x + 10000 * y);
}

/* Writes for the library into a FILE of ours, so that it cannot delete
 * the header-only tiled and deep files below as incomplete. */
static int64_t to_file(exr_const_context_t ctxt, void *ud, const void *buf,
                       uint64_t sz, uint64_t offset,
                       exr_stream_error_func_ptr_t error_cb)
{
    (void)ctxt;
    (void)error_cb;
    FILE *f = ud;
    if (fseek(f, (long)offset, SEEK_SET) != 0 || fwrite(buf, 1, sz, f) != sz)
        return -1;
    return (int64_t)sz;
}

static void quiet(exr_const_context_t ctxt, exr_result_t code,
                  const char *msg)
{
    (void)ctxt;
    (void)code;
    (void)msg;
}

/* One channel of a file written here: its name, pixel type and
 * subsampling (1 for full resolution). */
typedef struct {
    const char *name;
    exr_pixel_type_t type;
    int sampling;
} test_channel_t;

/* Write a w x h file with the given channels and compression, each
 * channel holding `value(name, x, y)` (the library converts the floats to
 * the channel's type); for the tiled and deep storages, only the header
 * and an empty offset table (enough for a reader to see what the file
 * is). Returns false, with no file, for a compression this version of the
 * library cannot write (EXR_ERR_FEATURE_NOT_IMPLEMENTED). */
static bool write_layout(const char *path, int w, int h,
                         const test_channel_t *chs, int n,
                         exr_storage_t storage, exr_compression_t comp,
                         float (*value)(const char *, int, int))
{
    exr_context_t ctx;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    FILE *f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    init.write_fn = to_file;
    init.user_data = f;
    init.error_handler_fn = quiet; /* the asserts say what failed */
    ck_assert_int_eq(exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY,
                                     &init), EXR_ERR_SUCCESS);
    int part;
    ck_assert_int_eq(exr_add_part(ctx, NULL, storage, &part), EXR_ERR_SUCCESS);
    ck_assert_int_eq(exr_initialize_required_attr_simple(ctx, part, w, h,
                                                         comp),
                     EXR_ERR_SUCCESS);
    if (storage == EXR_STORAGE_TILED)
        ck_assert_int_eq(exr_set_tile_descriptor(ctx, part, 8, 8,
                                                 EXR_TILE_ONE_LEVEL,
                                                 EXR_TILE_ROUND_DOWN),
                         EXR_ERR_SUCCESS);
    if (storage == EXR_STORAGE_DEEP_SCANLINE)
        ck_assert_int_eq(exr_set_version(ctx, part, 1), EXR_ERR_SUCCESS);
    for (int i = 0; i < n; i++)
        ck_assert_int_eq(exr_add_channel(ctx, part, chs[i].name, chs[i].type,
                                         EXR_PERCEPTUALLY_LINEAR,
                                         chs[i].sampling, chs[i].sampling),
                         EXR_ERR_SUCCESS);
    ck_assert_int_eq(exr_write_header(ctx), EXR_ERR_SUCCESS);
    if (storage == EXR_STORAGE_SCANLINE) {
        int32_t lines = 1;
        ck_assert_int_eq(exr_get_scanlines_per_chunk(ctx, part, &lines),
                         EXR_ERR_SUCCESS);
        /* room for every channel of the largest chunk */
        float *plane = malloc(sizeof(float) * (size_t)w * (size_t)lines *
                              (size_t)n);
        ck_assert_ptr_nonnull(plane);
        exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
        for (int y = 0; y < h; y += lines) {
            exr_chunk_info_t ci;
            ck_assert_int_eq(exr_write_scanline_chunk_info(ctx, part, y, &ci),
                             EXR_ERR_SUCCESS);
            ck_assert_int_eq(y ? exr_encoding_update(ctx, part, &ci, &enc)
                               : exr_encoding_initialize(ctx, part, &ci, &enc),
                             EXR_ERR_SUCCESS);
            float *next = plane;
            for (int c = 0; c < enc.channel_count; c++) {
                exr_coding_channel_info_t *ch = &enc.channels[c];
                int s = ch->y_samples > 0 ? ch->y_samples : 1;
                int first = (ci.start_y + s - 1) / s; /* sampled rows */
                for (int j = 0; j < ch->height; j++)
                    for (int x = 0; x < ch->width; x++)
                        next[(size_t)j * (size_t)ch->width + (size_t)x] =
                            value(ch->channel_name, x * ch->x_samples,
                                  (first + j) * s);
                ch->encode_from_ptr = (const uint8_t *)next;
                ch->user_pixel_stride = 4;
                ch->user_line_stride = 4 * ch->width;
                ch->user_data_type = EXR_PIXEL_FLOAT;
                ch->user_bytes_per_element = 4;
                next += (size_t)ch->width * (size_t)ch->height;
            }
            if (y == 0)
                ck_assert_int_eq(exr_encoding_choose_default_routines(
                                     ctx, part, &enc), EXR_ERR_SUCCESS);
            exr_result_t rv = exr_encoding_run(ctx, part, &enc);
            if (rv == EXR_ERR_FEATURE_NOT_IMPLEMENTED && y == 0) {
                exr_encoding_destroy(ctx, &enc);
                free(plane);
                exr_finish(&ctx);
                fclose(f);
                remove(path);
                return false;
            }
            ck_assert_int_eq(rv, EXR_ERR_SUCCESS);
        }
        exr_encoding_destroy(ctx, &enc);
        free(plane);
    }
    exr_finish(&ctx);
    ck_assert_int_eq(fclose(f), 0);
    return true;
}

/* Float channels of full resolution, uncompressed, as channel_value(). */
static void write_channels(const char *path, int w, int h,
                           const char *const *names, int n,
                           exr_storage_t storage)
{
    test_channel_t chs[8];
    ck_assert_int_le(n, 8);
    for (int i = 0; i < n; i++)
        chs[i] = (test_channel_t){ names[i], EXR_PIXEL_FLOAT, 1 };
    ck_assert(write_layout(path, w, h, chs, n, storage, EXR_COMPRESSION_NONE,
                           channel_value));
}

START_TEST(channels_are_found_by_name_whatever_else_is_there)
{
    const char *path = imgtest_path("ch.exr");
    static const char *const set[] = { "Z", "B", "depth", "G", "R", "A" };
    write_channels(path, 5, 3, set, 6, EXR_STORAGE_SCANLINE);
    image_t img;
    svet_error err;
    ck_assert_msg(exrio_read(path, &img, &err) == SVET_OK, "%s", err.msg);
    ck_assert_int_eq(img.channels, 4);
    const char *rgba = "RGBA";
    for (int y = 0; y < 3; y++)
        for (int x = 0; x < 5; x++)
            for (int c = 0; c < 4; c++) {
                char name[2] = { rgba[c], 0 };
                ck_assert(image_at(&img, x, y)[c] ==
                          channel_value(name, x, y));
            }
    image_free(&img);

    /* Y alone is grey; Y with A keeps the alpha */
    static const char *const grey[] = { "Y", "A" };
    for (int n = 1; n <= 2; n++) {
        write_channels(path, 4, 2, grey, n, EXR_STORAGE_SCANLINE);
        ck_assert_msg(exrio_read(path, &img, &err) == SVET_OK, "%s", err.msg);
        ck_assert_int_eq(img.channels, n == 1 ? 3 : 4);
        for (int c = 0; c < 3; c++)
            ck_assert(image_at(&img, 3, 1)[c] == channel_value("Y", 3, 1));
        if (n == 2)
            ck_assert(image_at(&img, 3, 1)[3] == channel_value("A", 3, 1));
        image_free(&img);
    }
}
END_TEST

/* A value every half holds exactly (k + n/64 with k < 16 and n < 128 has
 * at most 11 significant bits) and smooth, so that the lossy compressions
 * (B44, DWA) stay close: distinct per channel name. */
static float layout_value(const char *name, int x, int y)
{
    static const char *const names[] = { "R", "G", "B", "A", "Y", "Z",
                                         "X", "RY", "BY", "depth" };
    int k = 0;
    for (int i = 0; i < 10; i++)
        if (strcmp(name, names[i]) == 0)
            k = i + 1;
    return (float)k + (float)((x + y) % 128) / 64.0f;
}

/* How far a compression may move a value of this type: 0 for the
 * lossless ones. B44 and DWA quantise halves; PXR24 rounds floats to 24
 * bits (2^-15 relative). */
static double layout_tolerance(exr_compression_t comp, exr_pixel_type_t t)
{
    switch (comp) {
    case EXR_COMPRESSION_B44:
    case EXR_COMPRESSION_B44A:
        return t == EXR_PIXEL_HALF ? 0.02 : 0;
    case EXR_COMPRESSION_DWAA:
    case EXR_COMPRESSION_DWAB:
        return t == EXR_PIXEL_HALF ? 0.05 : 0;
    case EXR_COMPRESSION_PXR24:
        return t == EXR_PIXEL_FLOAT ? 0x1p-15 * 20 : 0;
    default:
        return 0;
    }
}

START_TEST(every_layout_and_compression_reads_back)
{
    /* The channel sets renderers and tools write, in half and in float,
     * through every compression the library writes. A skipped channel
     * (Z, Y beside R G B, X, RY, BY) once crashed the half reader. */
    const exr_pixel_type_t H = EXR_PIXEL_HALF, F = EXR_PIXEL_FLOAT;
    typedef struct {
        const char *what;
        test_channel_t ch[4];
        int n;
        const char *read; /* the channels of the image: "RGB", "RGBA",
                             "Y" (grey) or "YA" */
    } layout_t;
    const layout_t layouts[] = {
        { "R G B + Z", { { "R", H, 1 }, { "G", H, 1 }, { "B", H, 1 },
                         { "Z", F, 1 } }, 4, "RGB" },
        { "R G B + Y", { { "R", H, 1 }, { "G", H, 1 }, { "B", H, 1 },
                         { "Y", H, 1 } }, 4, "RGB" },
        { "X Y Z", { { "X", H, 1 }, { "Y", H, 1 }, { "Z", H, 1 } }, 3, "Y" },
        { "Y RY BY", { { "Y", H, 1 }, { "RY", H, 2 }, { "BY", H, 2 } }, 3,
          "Y" },
        { "R G B A", { { "R", H, 1 }, { "G", H, 1 }, { "B", H, 1 },
                       { "A", H, 1 } }, 4, "RGBA" },
        { "R G B", { { "R", H, 1 }, { "G", H, 1 }, { "B", H, 1 } }, 3,
          "RGB" },
        { "Y", { { "Y", H, 1 } }, 1, "Y" },
        { "Y A", { { "Y", H, 1 }, { "A", H, 1 } }, 2, "YA" },
        { "R G B depth", { { "R", H, 1 }, { "G", H, 1 }, { "B", H, 1 },
                           { "depth", H, 1 } }, 4, "RGB" },
        { "R G B + Y 2 x 2", { { "R", H, 1 }, { "G", H, 1 }, { "B", H, 1 },
                               { "Y", H, 2 } }, 4, "RGB" },
    };
    const exr_compression_t comps[] = {
        EXR_COMPRESSION_NONE, EXR_COMPRESSION_RLE,  EXR_COMPRESSION_ZIPS,
        EXR_COMPRESSION_ZIP,  EXR_COMPRESSION_PIZ,  EXR_COMPRESSION_PXR24,
        EXR_COMPRESSION_B44,  EXR_COMPRESSION_B44A, EXR_COMPRESSION_DWAA,
        EXR_COMPRESSION_DWAB
    };
    const char *path = imgtest_path("layout.exr");
    /* partial last chunks of 16 and 32 lines; even for the 2 x 2
     * subsampled chroma */
    const int w = 38, h = 42;
    enum { NCOMP = sizeof comps / sizeof comps[0] };
    bool written[NCOMP] = { false }, unwritable[NCOMP] = { false };
    long cases = 0;
    for (size_t l = 0; l < sizeof layouts / sizeof layouts[0]; l++)
        for (int type = 0; type < 2; type++)
            for (size_t c = 0; c < sizeof comps / sizeof comps[0]; c++) {
                layout_t lay = layouts[l];
                for (int i = 0; i < lay.n; i++)
                    if (type == 1 && lay.ch[i].type == H)
                        lay.ch[i].type = F; /* the float variant */
                if (!write_layout(path, w, h, lay.ch, lay.n,
                                  EXR_STORAGE_SCANLINE, comps[c],
                                  layout_value)) {
                    unwritable[c] = true;
                    continue;
                }
                written[c] = true;
                image_t img;
                svet_error err;
                ck_assert_msg(exrio_read(path, &img, &err) == SVET_OK,
                              "%s, %s, compression %d: %s", lay.what,
                              type ? "float" : "half", (int)comps[c],
                              err.msg);
                bool grey = lay.read[0] == 'Y';
                int nch = strchr(lay.read, 'A') ? 4 : 3;
                ck_assert_int_eq(img.channels, nch);
                ck_assert_int_eq(img.width, w);
                ck_assert_int_eq(img.height, h);
                double tol = layout_tolerance(comps[c], lay.ch[0].type);
                for (int y = 0; y < h; y++)
                    for (int x = 0; x < w; x++)
                        for (int k = 0; k < nch; k++) {
                            char name[2] = { grey && k < 3 ? 'Y' : "RGBA"[k],
                                             0 };
                            double want = layout_value(name, x, y);
                            double got = image_at(&img, x, y)[k];
                            ck_assert_msg(fabs(got - want) <= tol * want,
                                          "%s, %s, compression %d: (%d, %d) "
                                          "channel %d is %g, not %g",
                                          lay.what, type ? "float" : "half",
                                          (int)comps[c], x, y, k, got, want);
                            cases++;
                        }
                image_free(&img);
            }
    /* Say which compressions this library version cannot write (and so
     * are not tested here); the lossless ones must all be there. */
    for (int c = 0; c < NCOMP; c++) {
        if (unwritable[c])
            printf("  every_layout_and_compression_reads_back: compression "
                   "%d: this OpenEXRCore does not write it, not tested\n",
                   (int)comps[c]);
        if (comps[c] <= EXR_COMPRESSION_PXR24)
            ck_assert_msg(written[c], "compression %d", (int)comps[c]);
    }
    test_report_cases("every_layout_and_compression_reads_back", cases);
}
END_TEST

START_TEST(missing_channels_are_named_in_the_error)
{
    const char *path = imgtest_path("rg.exr");
    static const char *const rg[] = { "R", "G" };
    write_channels(path, 4, 4, rg, 2, EXR_STORAGE_SCANLINE);
    imgtest_check_bad_file(read_exr, path, SVET_ERR_PARSE, "the file has: G R");
    static const char *const z[] = { "Z" };
    write_channels(path, 4, 4, z, 1, EXR_STORAGE_SCANLINE);
    imgtest_check_bad_file(read_exr, path, SVET_ERR_PARSE, "no R, G, B");
    /* a channel that is read must be full resolution */
    const test_channel_t sub[] = { { "R", EXR_PIXEL_HALF, 1 },
                                   { "G", EXR_PIXEL_HALF, 2 },
                                   { "B", EXR_PIXEL_HALF, 1 } };
    ck_assert(write_layout(path, 4, 4, sub, 3, EXR_STORAGE_SCANLINE,
                           EXR_COMPRESSION_ZIP, layout_value));
    imgtest_check_bad_file(read_exr, path, SVET_ERR_UNSUPPORTED,
                           "channel G is subsampled (2 x 2)");
}
END_TEST

START_TEST(tiled_and_deep_files_are_refused_as_unsupported)
{
    static const char *const rgb[] = { "R", "G", "B" };
    const char *path = imgtest_path("tiled.exr");
    write_channels(path, 16, 16, rgb, 3, EXR_STORAGE_TILED);
    imgtest_check_bad_file(read_exr, path, SVET_ERR_UNSUPPORTED, "tiled");
    path = imgtest_path("deep.exr");
    write_channels(path, 16, 16, rgb, 3, EXR_STORAGE_DEEP_SCANLINE);
    imgtest_check_bad_file(read_exr, path, SVET_ERR_UNSUPPORTED, "deep");
}
END_TEST

/* A good file's bytes, to damage. */
static size_t good_file(unsigned char **bytes, exrio_compression_t comp)
{
    image_t img;
    svet_error err;
    imgtest_hdr_image(&img, 40, 40, 3);
    const char *path = imgtest_path("good.exr");
    ck_assert_int_eq(exrio_write(path, &img, EXRIO_HALF, comp, &err), SVET_OK);
    image_free(&img);
    return imgtest_read_bytes(path, bytes);
}

START_TEST(bad_exr_files_get_clear_errors)
{
    const char *path = imgtest_path("bad.exr");
    long cases = 0;
    imgtest_write_bytes(path, "", 0);
    imgtest_check_bad_file(read_exr, path, SVET_ERR_PARSE, NULL);
    imgtest_write_bytes(path, "this is not an image\n", 21);
    imgtest_check_bad_file(read_exr, path, SVET_ERR_PARSE, NULL);
    imgtest_write_bytes(path, "\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16);
    imgtest_check_bad_file(read_exr, path, SVET_ERR_PARSE, NULL);
    imgtest_check_bad_file(read_exr, imgtest_path("none.exr"), SVET_ERR_IO,
                           "cannot open");
    cases += 4;

    unsigned char *good;
    size_t n = good_file(&good, EXRIO_ZIP);
    /* cut anywhere: in the magic, the header, the offset table, the data */
    const size_t cuts[] = { 3, 20, 150, 300, n / 2, n - 1 };
    for (size_t i = 0; i < sizeof cuts / sizeof cuts[0]; i++, cases++) {
        imgtest_write_bytes(path, good, cuts[i]);
        imgtest_check_bad_file(read_exr, path, SVET_ERR_PARSE, NULL);
    }
    /* scribble over the compressed pixels: zlib or the size check objects */
    unsigned char *bad = malloc(n);
    ck_assert_ptr_nonnull(bad);
    memcpy(bad, good, n);
    for (size_t i = n - 200; i < n - 100; i++)
        bad[i] ^= 0x5a;
    imgtest_write_bytes(path, bad, n);
    imgtest_check_bad_file(read_exr, path, SVET_ERR_PARSE, "pixels");
    cases++;

    /* an uncompressed chunk that claims fewer bytes than its pixels hold
     * (found by fuzz_image): it read as zeros, or garbage, with SVET_OK */
    unsigned char *raw;
    size_t nraw = good_file(&raw, EXRIO_NONE);
    const size_t chunk = 8 + 40 * 3 * 2; /* y, size, one line of halves */
    unsigned char *c0 = raw + nraw - 40 * chunk;
    ck_assert_int_eq(c0[0] | c0[1] << 8, 0);     /* line 0 */
    ck_assert_int_eq(c0[4] | c0[5] << 8, 240);   /* its size */
    c0[4] = 120;
    imgtest_write_bytes(path, raw, nraw);
    imgtest_check_bad_file(read_exr, path, SVET_ERR_PARSE, "pixels");
    free(raw);
    cases++;

    /* an absurd data window: 2^31 - 1 pixels a side */
    memcpy(bad, good, n);
    static const char key[] = "dataWindow\0box2i";
    unsigned char *at = NULL;
    for (size_t i = 0; i + sizeof key < n && !at; i++)
        if (memcmp(good + i, key, sizeof key) == 0)
            at = bad + i + sizeof key + 4; /* past the name, type, size */
    ck_assert_ptr_nonnull(at);
    const unsigned char big[8] = { 0xfe, 0xff, 0xff, 0x7f,
                                   0xfe, 0xff, 0xff, 0x7f };
    memcpy(at + 8, big, 8); /* xmax, ymax = 2^31 - 2 */
    imgtest_write_bytes(path, bad, n);
    imgtest_check_bad_file(read_exr, path, SVET_ERR_PARSE, NULL);
    /* and an inverted one: max below min */
    memcpy(bad, good, n);
    memset(at + 8, 0xff, 8); /* xmax, ymax = -1 */
    imgtest_write_bytes(path, bad, n);
    imgtest_check_bad_file(read_exr, path, SVET_ERR_PARSE, NULL);
    cases += 2;
    free(bad);
    free(good);
    test_report_cases("bad_exr_files_get_clear_errors", cases);
}
END_TEST

static svet_status write_exr(const char *path, const void *img,
                             svet_error *err)
{
    return exrio_write(path, img, EXRIO_FLOAT, EXRIO_NONE, err);
}

START_TEST(a_failed_exr_write_keeps_the_old_file)
{
    image_t img;
    imgtest_hdr_image(&img, 256, 128, 4); /* 512 KiB of floats */
    imgtest_check_failed_write_keeps_old(write_exr, &img,
                                         imgtest_path("old.exr"), 65536);
    svet_error err;
    ck_assert_int_eq(exrio_write("/nonexistent-svet-dir/a.exr", &img,
                                 EXRIO_HALF, EXRIO_ZIP, &err), SVET_ERR_IO);
    ck_assert_ptr_nonnull(strstr(err.msg, "/nonexistent-svet-dir/a.exr"));
    image_free(&img);
}
END_TEST

START_TEST(zip_chunks_that_compress_to_their_own_size_read_back_exactly)
{
    /* OpenEXRCore before 3.4.8 (openexr issue #2306) corrupts a ZIP chunk
     * whose zlib stream is exactly as long as the raw chunk; exrio.c stores
     * the raw bytes then. Of 300 render-like images drawn as below, image
     * 37 (83 x 66) has such a chunk, its last: without the fix it reads
     * back as noise from row 64 on. The numbers of images 0..36 are drawn,
     * the images not written; image 37 must read back bit for bit. */
    pcg32_t g;
    pcg32_seed(&g, 1, 2);
    const char *path = imgtest_path("zip.exr");
    long values = 0;
    for (int it = 0; it <= 37; it++) {
        image_t a, b;
        int w = 64 + (int)pcg32_bounded(&g, 200);
        int h = 32 + (int)pcg32_bounded(&g, 200);
        ck_assert_int_eq(image_alloc(&a, w, h, 3, NULL), SVET_OK);
        for (size_t i = 0; i < (size_t)w * (size_t)h * 3; i++) {
            float v = (float)pcg32_real(&g);
            a.px[i] = i % 7 == 0 ? 0.0f : v * v * 3.0f;
        }
        if (it < 37) {
            image_free(&a);
            continue;
        }
        ck_assert_int_eq(exrio_write(path, &a, EXRIO_FLOAT, EXRIO_ZIP, NULL),
                         SVET_OK);
        ck_assert_int_eq(exrio_read(path, &b, NULL), SVET_OK);
        ck_assert_msg(memcmp(a.px, b.px, (size_t)w * (size_t)h * 3 *
                                              sizeof(float)) == 0,
                      "image %d (%d x %d) did not read back exactly", it, w, h);
        values += (long)w * h * 3;
        image_free(&a);
        image_free(&b);
    }
    test_report_cases("zip_chunks_that_compress_to_their_own_size_read_back_"
                      "exactly", values);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("exrio");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, float_exr_round_trip_is_bit_exact);
    tcase_add_test(tc, half_exr_round_trip_is_within_half_precision);
    tcase_add_test(tc, channels_are_found_by_name_whatever_else_is_there);
    tcase_add_test(tc, every_layout_and_compression_reads_back);
    tcase_add_test(tc, missing_channels_are_named_in_the_error);
    tcase_add_test(tc, tiled_and_deep_files_are_refused_as_unsupported);
    tcase_add_test(tc, bad_exr_files_get_clear_errors);
    tcase_add_test(tc, a_failed_exr_write_keeps_the_old_file);
    tcase_add_test(tc, zip_chunks_that_compress_to_their_own_size_read_back_exactly);
    suite_add_tcase(s, tc);
    return s;
}
