/*
 * image_corpus.c - writes the seed corpus of fuzz_image.c into the
 * directory given: small files of every format and variant the readers
 * take, made by svet's writers (EXR R G B(A) half/float, none/ZIP; PNG 8
 * and 16 bits; PFM; PPM) and by the libraries directly (EXR with other
 * channels, subsampling and every compression OpenEXRCore writes; PNG
 * grey, palette, transparency, interlaced; PGM, grey PFM, big-endian PFM).
 * Build and run from the top directory (fuzz/README.md):
 *   cc -std=c11 -Iinclude $(pkg-config --cflags OpenEXR libpng) \
 *      fuzz/image_corpus.c build/float/libsvet.a \
 *      $(pkg-config --libs OpenEXR libpng) -lm -fopenmp -o out/image_corpus
 *   out/image_corpus fuzz/corpus/image
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <openexr.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/exrio.h"
#include "io/netpbm.h"
#include "io/pngio.h"

static const char *dir;

static const char *at(const char *name)
{
    static char buf[4096];
    snprintf(buf, sizeof buf, "%s/%s", dir, name);
    return buf;
}

static void check(svet_status st, const svet_error *e)
{
    if (st != SVET_OK) {
        fprintf(stderr, "image_corpus: %s\n", e->msg);
        exit(1);
    }
}

static void fill(image_t *img, int w, int h, int ch, float scale)
{
    svet_error e;
    check(image_alloc(img, w, h, ch, &e), &e);
    for (int i = 0; i < w * h * ch; i++)
        img->px[i] = scale * (float)((i * 37) % 101) / 100.0f;
}

/* An EXR of the given channels, type and compression through the C API. */
static void exr_file(const char *name, int w, int h, const char *const *chn,
                     const int *sampling, int n, exr_pixel_type_t type,
                     exr_compression_t comp)
{
    exr_context_t ctx;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    if (exr_start_write(&ctx, at(name), EXR_WRITE_FILE_DIRECTLY, &init))
        exit(1);
    int part;
    exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part);
    exr_initialize_required_attr_simple(ctx, part, w, h, comp);
    for (int i = 0; i < n; i++)
        exr_add_channel(ctx, part, chn[i], type, EXR_PERCEPTUALLY_LINEAR,
                        sampling[i], sampling[i]);
    if (exr_write_header(ctx))
        exit(1);
    int32_t lines = 1;
    exr_get_scanlines_per_chunk(ctx, part, &lines);
    float *buf = calloc((size_t)w * (size_t)lines * (size_t)n, sizeof(float));
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    for (int y = 0; y < h; y += lines) {
        exr_chunk_info_t ci;
        exr_write_scanline_chunk_info(ctx, part, y, &ci);
        if (y ? exr_encoding_update(ctx, part, &ci, &enc)
              : exr_encoding_initialize(ctx, part, &ci, &enc))
            exit(1);
        float *p = buf;
        for (int c = 0; c < enc.channel_count; c++) {
            exr_coding_channel_info_t *ch = &enc.channels[c];
            for (int i = 0; i < ch->width * ch->height; i++)
                p[i] = (float)(c + 1) + (float)((i + y) % 16) / 16.0f;
            ch->encode_from_ptr = (const uint8_t *)p;
            ch->user_pixel_stride = 4;
            ch->user_line_stride = 4 * ch->width;
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->user_bytes_per_element = 4;
            p += ch->width * ch->height;
        }
        if (y == 0)
            exr_encoding_choose_default_routines(ctx, part, &enc);
        if (exr_encoding_run(ctx, part, &enc)) {
            fprintf(stderr, "image_corpus: %s not written\n", name);
            exr_encoding_destroy(ctx, &enc);
            exr_finish(&ctx);
            free(buf);
            remove(at(name));
            return;
        }
    }
    exr_encoding_destroy(ctx, &enc);
    exr_finish(&ctx);
    free(buf);
}

/* A PNG of any colour type through libpng. */
static void png_file(const char *name, int w, int h, int color, int depth,
                     int interlace, int trns)
{
    FILE *f = fopen(at(name), "wb");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL,
                                              NULL, NULL);
    png_infop info = png_create_info_struct(png);
    if (!f || !info || setjmp(png_jmpbuf(png)))
        exit(1);
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, depth, color,
                 interlace, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (color == PNG_COLOR_TYPE_PALETTE) {
        png_color pal[4] = { { 0, 0, 0 }, { 255, 0, 0 }, { 0, 255, 0 },
                             { 0, 0, 255 } };
        png_set_PLTE(png, info, pal, 4);
    }
    if (trns) {
        png_byte alpha[2] = { 0, 128 };
        png_color_16 grey = { 0, 0, 0, 0, 1 };
        png_set_tRNS(png, info, alpha, color == PNG_COLOR_TYPE_PALETTE ? 2 : 0,
                     &grey);
    }
    png_write_info(png, info);
    size_t rowbytes = png_get_rowbytes(png, info);
    unsigned char *row = malloc(rowbytes);
    int passes = png_set_interlace_handling(png);
    for (int p = 0; p < passes; p++)
        for (int y = 0; y < h; y++) {
            for (size_t i = 0; i < rowbytes; i++)
                row[i] = (unsigned char)((i * 29 + (size_t)y * 7) &
                                         (depth < 8 ? 0x55 : 0xff));
            png_write_row(png, row);
        }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    free(row);
    fclose(f);
}

/* A header, then nbody bytes of a pattern, each ANDed with mask. */
static void bytes_file(const char *name, const char *head, size_t nbody,
                       unsigned mask)
{
    FILE *f = fopen(at(name), "wb");
    if (!f)
        exit(1);
    fputs(head, f);
    for (size_t i = 0; i < nbody; i++)
        fputc((int)((i * 53) & mask), f);
    fclose(f);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: image_corpus DIR\n");
        return 1;
    }
    dir = argv[1];
    svet_error e;
    image_t rgb, rgba;
    fill(&rgb, 7, 5, 3, 4.0f);
    fill(&rgba, 5, 4, 4, 1.0f);
    /* svet's own writers */
    check(exrio_write(at("svet-half-zip.exr"), &rgb, EXRIO_HALF, EXRIO_ZIP,
                      &e), &e);
    check(exrio_write(at("svet-float-none.exr"), &rgba, EXRIO_FLOAT,
                      EXRIO_NONE, &e), &e);
    check(exrio_write(at("svet-float-zip.exr"), &rgb, EXRIO_FLOAT, EXRIO_ZIP,
                      &e), &e);
    check(netpbm_write_pfm(at("svet.pfm"), &rgb, &e), &e);
    check(netpbm_write_ppm(at("svet-8.ppm"), &rgba, 8, &e), &e);
    check(netpbm_write_ppm(at("svet-16.ppm"), &rgb, 16, &e), &e);
    for (int i = 0; i < 35; i++) /* display codes in [0, 1] */
        rgb.px[i] = rgb.px[i] / 4.0f;
    check(pngio_write(at("svet-8.png"), &rgb, 8, &e), &e);
    check(pngio_write(at("svet-16-rgba.png"), &rgba, 16, &e), &e);
    image_free(&rgb);
    image_free(&rgba);

    /* EXR layouts and compressions, through OpenEXRCore */
    static const char *const rgbz[] = { "R", "G", "B", "Z" };
    static const char *const yc[] = { "Y", "RY", "BY" };
    static const char *const xyz[] = { "X", "Y", "Z" };
    static const char *const ya[] = { "Y", "A" };
    static const int one[] = { 1, 1, 1, 1 }, sub[] = { 1, 2, 2 };
    static const struct {
        exr_compression_t c;
        const char *name;
    } comps[] = { { EXR_COMPRESSION_RLE, "rle" }, { EXR_COMPRESSION_ZIPS,
                  "zips" }, { EXR_COMPRESSION_PIZ, "piz" },
                  { EXR_COMPRESSION_PXR24, "pxr24" },
                  { EXR_COMPRESSION_B44, "b44" },
                  { EXR_COMPRESSION_B44A, "b44a" } };
    char name[64];
    for (size_t i = 0; i < sizeof comps / sizeof comps[0]; i++) {
        snprintf(name, sizeof name, "rgbz-half-%s.exr", comps[i].name);
        exr_file(name, 9, 18, rgbz, one, 4, EXR_PIXEL_HALF, comps[i].c);
    }
    exr_file("rgbz-float-piz.exr", 6, 4, rgbz, one, 4, EXR_PIXEL_FLOAT,
             EXR_COMPRESSION_PIZ);
    exr_file("yc-half-zip.exr", 8, 6, yc, sub, 3, EXR_PIXEL_HALF,
             EXR_COMPRESSION_ZIP);
    exr_file("xyz-uint-none.exr", 4, 3, xyz, one, 3, EXR_PIXEL_UINT,
             EXR_COMPRESSION_NONE);
    exr_file("ya-float-rle.exr", 5, 5, ya, one, 2, EXR_PIXEL_FLOAT,
             EXR_COMPRESSION_RLE);

    /* PNG colour types through libpng */
    png_file("grey-1.png", 9, 5, PNG_COLOR_TYPE_GRAY, 1, PNG_INTERLACE_NONE,
             0);
    png_file("grey-alpha-16.png", 4, 3, PNG_COLOR_TYPE_GRAY_ALPHA, 16,
             PNG_INTERLACE_NONE, 0);
    png_file("palette-2-trns.png", 6, 6, PNG_COLOR_TYPE_PALETTE, 2,
             PNG_INTERLACE_NONE, 1);
    png_file("grey-8-trns.png", 5, 4, PNG_COLOR_TYPE_GRAY, 8,
             PNG_INTERLACE_NONE, 1);
    png_file("rgb-8-interlaced.png", 11, 9, PNG_COLOR_TYPE_RGB, 8,
             PNG_INTERLACE_ADAM7, 0);

    /* netpbm variants by hand */
    bytes_file("grey.pfm", "Pf\n3 2\n-1.0\n", 3 * 2 * 4, 0xff);
    bytes_file("big-endian.pfm", "PF\n2 2\n1.0\n", 2 * 2 * 12, 0xff);
    bytes_file("grey-8.pgm", "P5\n# a comment\n4 3\n255\n", 12, 0xff);
    bytes_file("maxval-1000.ppm", "P6 2 2 1000\n", 2 * 2 * 6, 0x03);
    return 0;
}
