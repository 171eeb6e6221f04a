/*
 * netpbm.c - PFM and PPM/PGM read and write with libc alone. See netpbm.h.
 * Every header field is checked before anything is allocated, and the
 * file's length against what the header promises, so a lying or truncated
 * file costs an error message, not memory.
 * Tests: tests/io/test_netpbm.c
 */
#include "io/netpbm.h"
#include "io/fileio.h"

#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* --- reading the header -------------------------------------------------- */

typedef struct {
    FILE *f;
    const char *path;
    const image_read_limits_t *lim;
    svet_error *err;
} reader_t;

/* Open path and check its magic number, "P" then `colour` (3 planes) or
 * `grey` (1 plane). On failure nothing stays open. */
static svet_status open_reader(reader_t *r, const char *path, char colour,
                               char grey, const char *what, int *planes,
                               const image_read_limits_t *lim,
                               svet_error *err)
{
    r->path = path;
    r->lim = lim;
    r->err = err;
    svet_status st = fileio_open_read(path, &r->f, err);
    if (st != SVET_OK)
        return st;
    int m0 = getc(r->f), m1 = getc(r->f);
    if (m0 != 'P' || (m1 != colour && m1 != grey)) {
        fclose(r->f);
        return svet_error_set(err, SVET_ERR_PARSE, "%s: not %s (it must "
                              "start with \"P%c\" or \"P%c\")", path, what,
                              colour, grey);
    }
    *planes = m1 == colour ? 3 : 1;
    return SVET_OK;
}

/* Skip whitespace and '#' comments (to the end of their line). */
static int skip_space(reader_t *r)
{
    int c;
    for (;;) {
        c = getc(r->f);
        if (c == '#') {
            while (c != EOF && c != '\n' && c != '\r')
                c = getc(r->f);
        } else if (c == EOF || !isspace(c)) {
            return c;
        }
    }
}

/* A decimal integer header field. The value is capped well above any
 * limit (2^40) so that "99999999999999999999" cannot wrap around into a
 * small plausible size. */
static svet_status read_uint(reader_t *r, const char *field, long long *v)
{
    int c = skip_space(r);
    if (c == EOF)
        return svet_error_set(r->err, SVET_ERR_PARSE, "%s: truncated header "
                              "(no %s)", r->path, field);
    if (!isdigit(c))
        return svet_error_set(r->err, SVET_ERR_PARSE, "%s: header: the %s "
                              "is not a number (found '%c')", r->path, field,
                              isprint(c) ? c : '?');
    long long x = 0;
    while (c != EOF && isdigit(c)) {
        if (x < (1LL << 40))
            x = 10 * x + (c - '0');
        c = getc(r->f);
    }
    if (c != EOF && !isspace(c))
        return svet_error_set(r->err, SVET_ERR_PARSE, "%s: header: the %s is "
                              "followed by '%c', not white space", r->path,
                              field, isprint(c) ? c : '?');
    /* The single white-space character after the last field is eaten
     * here, as both formats require before the raster. */
    *v = x;
    return SVET_OK;
}

/* Bytes left from the current position to the end, or -1 if the stream
 * cannot tell (a pipe). */
static long long bytes_left(FILE *f)
{
    long here = ftell(f);
    if (here < 0 || fseek(f, 0, SEEK_END) != 0)
        return -1;
    long end = ftell(f);
    if (end < 0 || fseek(f, here, SEEK_SET) != 0)
        return -1;
    return (long long)end - here;
}

/* Check the dimensions and that the file holds the raster they promise
 * (elem bytes a sample, `planes` samples a pixel), then allocate img and
 * read the raster into *buf (the caller frees it, also on failure). */
static svet_status load_raster(reader_t *r, long long w, long long h,
                               size_t elem, int planes, image_t *img,
                               unsigned char **buf)
{
    size_t need;
    svet_status st = image_check_read_size(w, h, planes, elem, r->lim,
                                           &need, r->err);
    if (st != SVET_OK) {
        svet_error_prefix(r->err, r->path);
        return st;
    }
    long long left = bytes_left(r->f);
    if (left >= 0 && (unsigned long long)left < need)
        return svet_error_set(r->err, SVET_ERR_PARSE, "%s: truncated: the "
                              "header promises %lld x %lld pixels, %zu bytes, "
                              "the file holds %lld", r->path, w, h, need,
                              left);
    if ((st = image_alloc(img, (int)w, (int)h, 3, r->err)) != SVET_OK) {
        svet_error_prefix(r->err, r->path);
        return st;
    }
    *buf = malloc(need);
    if (!*buf)
        return svet_error_set(r->err, SVET_ERR_NOMEM, "%s: out of memory",
                              r->path);
    size_t got = fread(*buf, 1, need, r->f);
    if (got != need)
        return svet_error_set(r->err, ferror(r->f) ? SVET_ERR_IO
                                                   : SVET_ERR_PARSE,
                              "%s: truncated: %zu bytes of pixels expected, "
                              "%zu found", r->path, need, got);
    return SVET_OK;
}

static bool host_is_little_endian(void)
{
    const uint16_t one = 1;
    unsigned char b;
    memcpy(&b, &one, 1);
    return b == 1;
}

/* --- PFM ------------------------------------------------------------------ */

svet_status netpbm_read_pfm(const char *path, image_t *img, svet_error *err)
{
    return netpbm_read_pfm_with(path, img, NULL, err);
}

svet_status netpbm_read_pfm_with(const char *path, image_t *img,
                                 const image_read_limits_t *lim,
                                 svet_error *err)
{
    memset(img, 0, sizeof *img);
    reader_t r;
    int planes = 3;
    svet_status st = open_reader(&r, path, 'F', 'f', "a PFM file", &planes,
                                 lim, err);
    if (st != SVET_OK)
        return st;
    unsigned char *buf = NULL;
    long long w, h;
    if ((st = read_uint(&r, "width", &w)) != SVET_OK ||
        (st = read_uint(&r, "height", &h)) != SVET_OK)
        goto done;
    /* The scale: a number whose sign gives the byte order. */
    char tok[64];
    int c = skip_space(&r), n = 0;
    while (c != EOF && !isspace(c) && n < (int)sizeof tok - 1) {
        tok[n++] = (char)c;
        c = getc(r.f);
    }
    tok[n] = '\0';
    char *end;
    double scale = strtod(tok, &end);
    if (n == 0 || *end != '\0' || !isfinite(scale) || scale == 0 ||
        !isspace(c)) {
        st = svet_error_set(err, SVET_ERR_PARSE, "%s: header: the scale '%s' "
                            "is not a nonzero number followed by white space",
                            path, tok);
        goto done;
    }
    if ((st = load_raster(&r, w, h, sizeof(float), planes, img, &buf)) !=
        SVET_OK)
        goto done;
    bool swap = (scale < 0) != host_is_little_endian();
    for (int y = 0; y < img->height; y++) {
        /* PFM rows run bottom to top */
        const unsigned char *row =
            buf + (size_t)(img->height - 1 - y) * (size_t)img->width *
                      (size_t)planes * 4;
        for (int x = 0; x < img->width; x++) {
            float *p = image_at(img, x, y);
            for (int k = 0; k < planes; k++) {
                unsigned char b[4];
                memcpy(b, row + ((size_t)x * (size_t)planes + (size_t)k) * 4,
                       4);
                if (swap) {
                    unsigned char t = b[0];
                    b[0] = b[3];
                    b[3] = t;
                    t = b[1];
                    b[1] = b[2];
                    b[2] = t;
                }
                memcpy(&p[k], b, 4);
            }
            if (planes == 1)
                p[1] = p[2] = p[0];
        }
    }
done:
    free(buf);
    fclose(r.f);
    if (st != SVET_OK)
        image_free(img);
    return st;
}

svet_status netpbm_write_pfm(const char *path, const image_t *img,
                             svet_error *err)
{
    size_t row_bytes = (size_t)img->width * 3 * sizeof(float);
    float *row = malloc(row_bytes);
    if (!row)
        return svet_error_set(err, SVET_ERR_NOMEM, "%s: out of memory", path);
    fileio_t out;
    svet_status st = fileio_begin(&out, path, err);
    if (st != SVET_OK) {
        free(row);
        return st;
    }
    /* Little-endian is what a PC writes; a big-endian host says so with a
     * positive scale rather than swapping. */
    fprintf(out.f, "PF\n%d %d\n%s\n", img->width, img->height,
            host_is_little_endian() ? "-1.0" : "1.0");
    for (int y = img->height - 1; y >= 0; y--) {
        for (int x = 0; x < img->width; x++)
            memcpy(row + 3 * x, image_at(img, x, y), 3 * sizeof(float));
        if (fwrite(row, 1, row_bytes, out.f) != row_bytes)
            break; /* fileio_commit() reports it */
    }
    free(row);
    return fileio_commit(&out, err);
}

/* --- PPM / PGM ------------------------------------------------------------- */

svet_status netpbm_read_ppm(const char *path, image_t *img, int *bits,
                            svet_error *err)
{
    return netpbm_read_ppm_with(path, img, bits, NULL, err);
}

svet_status netpbm_read_ppm_with(const char *path, image_t *img, int *bits,
                                 const image_read_limits_t *lim,
                                 svet_error *err)
{
    memset(img, 0, sizeof *img);
    reader_t r;
    int planes = 3;
    svet_status st = open_reader(&r, path, '6', '5', "a binary PPM/PGM file",
                                 &planes, lim, err);
    if (st != SVET_OK)
        return st;
    unsigned char *buf = NULL;
    long long w, h, maxval;
    if ((st = read_uint(&r, "width", &w)) != SVET_OK ||
        (st = read_uint(&r, "height", &h)) != SVET_OK ||
        (st = read_uint(&r, "maxval", &maxval)) != SVET_OK)
        goto done;
    if (maxval < 1 || maxval > 65535) {
        st = svet_error_set(err, SVET_ERR_PARSE, "%s: header: maxval %lld is "
                            "not in 1..65535", path, maxval);
        goto done;
    }
    size_t bytes_per = maxval > 255 ? 2 : 1;
    if ((st = load_raster(&r, w, h, bytes_per, planes, img, &buf)) != SVET_OK)
        goto done;
    size_t n = (size_t)img->width * (size_t)img->height;
    for (size_t i = 0; i < n; i++) {
        for (int k = 0; k < planes; k++) {
            size_t j = i * (size_t)planes + (size_t)k;
            unsigned v = bytes_per == 2
                             ? (unsigned)buf[2 * j] << 8 | buf[2 * j + 1]
                             : buf[j];
            if (v > (unsigned)maxval) {
                st = svet_error_set(err, SVET_ERR_PARSE, "%s: pixel %zu has "
                                    "code %u above maxval %lld", path, i, v,
                                    maxval);
                goto done;
            }
            img->px[3 * i + (size_t)k] = (float)v / (float)maxval;
        }
        if (planes == 1)
            img->px[3 * i + 1] = img->px[3 * i + 2] = img->px[3 * i];
    }
    if (bits)
        *bits = bytes_per == 2 ? 16 : 8;
done:
    free(buf);
    fclose(r.f);
    if (st != SVET_OK)
        image_free(img);
    return st;
}

svet_status netpbm_write_ppm(const char *path, const image_t *img, int bits,
                             svet_error *err)
{
    if (bits != 8 && bits != 16)
        return svet_error_set(err, SVET_ERR_RANGE, "%s: a PPM has 8 or 16 "
                              "bits, not %d", path, bits);
    unsigned maxval = bits == 8 ? 255u : 65535u;
    size_t bytes_per = bits == 8 ? 1 : 2;
    size_t row_bytes = (size_t)img->width * 3 * bytes_per;
    unsigned char *row = malloc(row_bytes);
    if (!row)
        return svet_error_set(err, SVET_ERR_NOMEM, "%s: out of memory", path);
    fileio_t out;
    svet_status st = fileio_begin(&out, path, err);
    if (st != SVET_OK) {
        free(row);
        return st;
    }
    fprintf(out.f, "P6\n%d %d\n%u\n", img->width, img->height, maxval);
    for (int y = 0; y < img->height; y++) {
        for (int x = 0; x < img->width; x++) {
            const float *p = image_at(img, x, y);
            for (int k = 0; k < 3; k++) {
                unsigned v = image_quantize(p[k], maxval);
                size_t j = (size_t)x * 3 + (size_t)k;
                if (bytes_per == 2) {
                    row[2 * j] = (unsigned char)(v >> 8);
                    row[2 * j + 1] = (unsigned char)(v & 0xff);
                } else {
                    row[j] = (unsigned char)v;
                }
            }
        }
        if (fwrite(row, 1, row_bytes, out.f) != row_bytes)
            break; /* fileio_commit() reports it */
    }
    free(row);
    return fileio_commit(&out, err);
}
