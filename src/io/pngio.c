/*
 * pngio.c - PNG read and write through libpng. libpng reports errors by
 * longjmp() to the setjmp() point of the call; here every setjmp() lives
 * in a small function (write_rows, read_rows) that allocates nothing the
 * caller cannot see: buffers hang off a struct owned by the caller, which
 * frees them on either path. So a longjmp never skips a free, and no local
 * changed after setjmp() is read after it (C11 7.13.2.1: such locals are
 * indeterminate unless volatile). See pngio.h. Tests: tests/io/test_pngio.c
 */
#include "io/pngio.h"
#include "io/fileio.h"

#include <png.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

/* What libpng's error callback reaches through png_get_error_ptr(). */
typedef struct {
    const char *path;
    svet_error *err;
    char warning[160]; /* libpng's last warning */
} png_msg_t;

/* libpng often gives the reason as a warning just before a terse error
 * ("Image width exceeds user limit in IHDR", then "Invalid IHDR data"):
 * the message carries both. */
static void on_error(png_structp png, png_const_charp msg)
{
    png_msg_t *m = png_get_error_ptr(png);
    if (m->warning[0])
        svet_error_set(m->err, SVET_ERR_PARSE, "%s: %s (%s)", m->path, msg,
                       m->warning);
    else
        svet_error_set(m->err, SVET_ERR_PARSE, "%s: %s", m->path, msg);
    png_longjmp(png, 1);
}

/* Warnings are kept for the error message, never printed: a library does
 * not print (and most warnings are harmless: an unknown chunk, an sRGB
 * profile libpng dislikes). */
static void on_warning(png_structp png, png_const_charp msg)
{
    png_msg_t *m = png_get_error_ptr(png);
    snprintf(m->warning, sizeof m->warning, "%s", msg);
}

/* --- writing --------------------------------------------------------------- */

static int write_rows(png_structp png, png_infop info, FILE *f,
                      const image_t *img, int bits, unsigned char *row)
{
    if (setjmp(png_jmpbuf(png)))
        return -1;
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)img->width,
                 (png_uint_32)img->height, bits,
                 img->channels == 4 ? PNG_COLOR_TYPE_RGB_ALPHA
                                    : PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    const unsigned maxval = bits == 16 ? 65535u : 255u;
    const size_t n = (size_t)img->width * (size_t)img->channels;
    for (int y = 0; y < img->height; y++) {
        const float *p = image_at(img, 0, y);
        for (size_t i = 0; i < n; i++) {
            unsigned v = image_quantize(p[i], maxval);
            if (bits == 16) { /* PNG stores 16-bit samples big-endian */
                row[2 * i] = (unsigned char)(v >> 8);
                row[2 * i + 1] = (unsigned char)(v & 0xff);
            } else {
                row[i] = (unsigned char)v;
            }
        }
        png_write_row(png, row);
    }
    png_write_end(png, NULL);
    return 0;
}

svet_status pngio_write_to(fileio_t *out, const image_t *img, int bits,
                           svet_error *err)
{
    const char *path = out->path;
    svet_error local;
    if (!err) /* the callbacks write the message somewhere */
        err = &local;
    if (bits != 8 && bits != 16)
        return svet_error_set(err, SVET_ERR_RANGE, "%s: a PNG is written "
                              "with 8 or 16 bits, not %d", path, bits);
    png_msg_t msg = { path, err, "" };
    unsigned char *row = malloc((size_t)img->width * (size_t)img->channels *
                                (size_t)(bits / 8));
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &msg,
                                              on_error, on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!row || !info) {
        png_destroy_write_struct(png ? &png : NULL, NULL);
        free(row);
        return svet_error_set(err, SVET_ERR_NOMEM, "%s: out of memory",
                              path);
    }
    svet_status st = SVET_OK;
    if (write_rows(png, info, out->f, img, bits, row) != 0)
        st = err->status = SVET_ERR_IO; /* on_error wrote the message */
    png_destroy_write_struct(&png, &info);
    free(row);
    return st;
}

svet_status pngio_write(const char *path, const image_t *img, int bits,
                        svet_error *err)
{
    fileio_t out;
    svet_status st = fileio_begin(&out, path, err);
    if (st == SVET_OK)
        st = pngio_write_to(&out, img, bits, err);
    if (st != SVET_OK) {
        fileio_abort(&out);
        return st;
    }
    return fileio_commit(&out, err);
}

/* --- reading --------------------------------------------------------------- */

/* Buffers of one read, owned by pngio_read. */
typedef struct {
    const image_read_limits_t *lim; /* what may be loaded */
    unsigned char *data;  /* the decoded rows */
    png_bytep *rows;      /* pointers into data */
    png_uint_32 w, h;
    int channels;         /* after the transforms: 3 or 4 */
    int depth;            /* after the transforms: 8 or 16 */
    long long file_bytes; /* size of the file, for the plausibility check */
} png_read_t;

/* libpng's own reader says only "Read Error" at the end of the file. */
static void read_data(png_structp png, png_bytep data, size_t n)
{
    FILE *f = png_get_io_ptr(png);
    if (fread(data, 1, n, f) != n)
        png_error(png, ferror(f) ? "read error"
                                 : "unexpected end of file (truncated)");
}

/* Walk the chunks after the signature (f just past it) and refuse a
 * chunk other than the pixels' (IDAT) that claims more bytes than the file
 * holds: libpng would allocate the claimed length before reading, so a
 * 60-byte file could ask for 2 GB (found by fuzz/fuzz_image.c). A short
 * IDAT is left to libpng, which reports the truncation. f is left just
 * past the signature. file_bytes < 0: the size is unknown; nothing is
 * checked. */
static svet_status chunks_fit(FILE *f, long file_bytes, const char *path,
                              svet_error *err)
{
    if (file_bytes < 0)
        return SVET_OK;
    long pos = 8;
    unsigned char h[8];
    while (pos + 8 <= file_bytes && fseek(f, pos, SEEK_SET) == 0 &&
           fread(h, 1, sizeof h, f) == sizeof h) {
        unsigned long len = (unsigned long)h[0] << 24 | (unsigned long)h[1]
                            << 16 | (unsigned long)h[2] << 8 | h[3];
        bool idat = memcmp(h + 4, "IDAT", 4) == 0;
        if (!idat && (double)len + 12.0 > (double)(file_bytes - pos)) {
            fseek(f, 8, SEEK_SET);
            return svet_error_set(err, SVET_ERR_PARSE,
                                  "%s: the chunk at byte %ld claims %lu "
                                  "bytes, more than the file holds",
                                  path, pos, len);
        }
        if (memcmp(h + 4, "IEND", 4) == 0 || len > 0x7fffffffUL)
            break;
        pos += (long)len + 12;
    }
    fseek(f, 8, SEEK_SET);
    return SVET_OK;
}

/* The largest chunk other than IDAT that a read keeps in memory. */
#define PNGIO_MAX_CHUNK (16L << 20)

static int read_rows(png_structp png, png_infop info, FILE *f, png_read_t *r,
                     const png_msg_t *m)
{
    if (setjmp(png_jmpbuf(png)))
        return -1;
    png_set_read_fn(png, f, read_data);
    png_set_sig_bytes(png, 8);
    /* libpng checks IHDR against these before any row is decoded. */
    png_set_user_limits(png, IMAGE_MAX_DIM, IMAGE_MAX_DIM);
    /* A chunk other than the pixels (text, ICC profile) is read whole into
     * memory; its length is the file's word, so a 60-byte file can ask for
     * 2 GB (found by fuzz/fuzz_image.c). No real one needs more than this;
     * libpng refuses the chunk (or the file, for a critical one). */
    png_set_chunk_malloc_max(png, PNGIO_MAX_CHUNK);
    png_set_chunk_cache_max(png, 1000);
    png_read_info(png, info);
    int depth, color;
    png_get_IHDR(png, info, &r->w, &r->h, &depth, &color, NULL, NULL, NULL);
    if (image_check_read_size(r->w, r->h, 4, 2, r->lim, NULL, m->err) !=
        SVET_OK) {
        svet_error_prefix(m->err, m->path);
        return -1;
    }
    /* A lying header: deflate cannot expand data more than 1032-fold, so
     * the file must hold at least raw/1032 bytes of compressed rows
     * (raw: each row is one filter byte plus its samples). Checked
     * before the big allocation. */
    int file_channels = png_get_channels(png, info);
    double raw = (double)r->h *
                 (1.0 + ((double)r->w * file_channels * depth + 7) / 8);
    if (r->file_bytes >= 0 && raw > 1032.0 * (double)r->file_bytes + 4096) {
        svet_error_set(m->err, SVET_ERR_PARSE, "%s: the header claims %u x "
                       "%u pixels, which %lld bytes of PNG cannot hold "
                       "(corrupt or truncated)", m->path, (unsigned)r->w,
                       (unsigned)r->h, r->file_bytes);
        return -1;
    }
    /* Everything to 8 or 16-bit RGB(A). */
    if (color == PNG_COLOR_TYPE_PALETTE)
        png_set_palette_to_rgb(png);
    if (color == PNG_COLOR_TYPE_GRAY && depth < 8)
        png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS))
        png_set_tRNS_to_alpha(png);
    if (color == PNG_COLOR_TYPE_GRAY || color == PNG_COLOR_TYPE_GRAY_ALPHA)
        png_set_gray_to_rgb(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    r->channels = png_get_channels(png, info);
    r->depth = png_get_bit_depth(png, info);
    if ((r->channels != 3 && r->channels != 4) ||
        (r->depth != 8 && r->depth != 16)) {
        svet_error_set(m->err, SVET_ERR_UNSUPPORTED, "%s: %d channels of %d "
                       "bits after expansion", m->path, r->channels,
                       r->depth);
        return -1;
    }
    size_t rowbytes = png_get_rowbytes(png, info);
    r->data = malloc(rowbytes * r->h);
    r->rows = malloc(sizeof *r->rows * r->h);
    if (!r->data || !r->rows) {
        svet_error_set(m->err, SVET_ERR_NOMEM, "%s: out of memory", m->path);
        return -1;
    }
    for (png_uint_32 y = 0; y < r->h; y++)
        r->rows[y] = r->data + y * rowbytes;
    png_read_image(png, r->rows);
    png_read_end(png, NULL);
    return 0;
}

svet_status pngio_read(const char *path, image_t *img, int *bits,
                       svet_error *err)
{
    return pngio_read_with(path, img, bits, NULL, err);
}

svet_status pngio_read_with(const char *path, image_t *img, int *bits,
                            const image_read_limits_t *lim, svet_error *err)
{
    memset(img, 0, sizeof *img);
    svet_error local;
    if (!err) /* the callbacks write the message somewhere */
        err = &local;
    FILE *f;
    svet_status st = fileio_open_read(path, &f, err);
    if (st != SVET_OK)
        return st;
    png_read_t r = { .lim = lim, .file_bytes = -1 };
    if (fseek(f, 0, SEEK_END) == 0) {
        long end = ftell(f);
        r.file_bytes = end;
        rewind(f);
    }
    unsigned char sig[8];
    size_t got = fread(sig, 1, sizeof sig, f);
    if (got != sizeof sig || png_sig_cmp(sig, 0, sizeof sig) != 0) {
        fclose(f);
        return svet_error_set(err, SVET_ERR_PARSE, "%s: not a PNG file (%s)",
                              path, got == 0 ? "it is empty"
                                             : "wrong signature");
    }
    if ((st = chunks_fit(f, r.file_bytes, path, err)) != SVET_OK) {
        fclose(f);
        return st;
    }
    png_msg_t msg = { path, err, "" };
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &msg,
                                             on_error, on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        st = svet_error_set(err, SVET_ERR_NOMEM, "%s: out of memory", path);
    } else if (read_rows(png, info, f, &r, &msg) != 0) {
        st = err->status;
    } else if ((st = image_alloc(img, (int)r.w, (int)r.h, r.channels, err)) ==
               SVET_OK) {
        const float maxval = r.depth == 16 ? 65535.0f : 255.0f;
        const size_t n = (size_t)r.w * (size_t)r.channels;
        for (png_uint_32 y = 0; y < r.h; y++) {
            const unsigned char *s = r.rows[y];
            float *p = image_at(img, 0, (int)y);
            for (size_t i = 0; i < n; i++) {
                unsigned v = r.depth == 16
                                 ? (unsigned)s[2 * i] << 8 | s[2 * i + 1]
                                 : s[i];
                p[i] = (float)v / maxval;
            }
        }
    } else {
        svet_error_prefix(err, path);
    }
    png_destroy_read_struct(png ? &png : NULL, info ? &info : NULL, NULL);
    free(r.rows);
    free(r.data);
    fclose(f);
    if (bits && st == SVET_OK)
        *bits = r.depth;
    return st;
}
