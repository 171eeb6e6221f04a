/*
 * volgrid.c - the grids of gridded media (ch. 11) in Mitsuba's .vol
 * format: reading with every check a bad file needs, writing, lookups.
 * Tests: tests/medium/test_volgrid.c
 */
#include "medium/volgrid.h"
#include "io/fileio.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

void volgrid_free(volgrid_t *g)
{
    for (int c = 0; c < VOLGRID_MAX_CHANNELS; c++)
        free(g->plane[c]);
    memset(g, 0, sizeof *g);
}

/* The count of values, or 0 where it overflows or passes max_values. */
static size_t value_count(long long nx, long long ny, long long nz,
                          long long channels, size_t max_values)
{
    if (nx < 1 || ny < 1 || nz < 1 || channels < 1)
        return 0;
    /* each factor is below 2^31: the product of two fits in 2^62 */
    unsigned long long cells = (unsigned long long)nx * (unsigned long long)ny;
    if (cells > max_values)
        return 0;
    cells *= (unsigned long long)nz;
    if (cells > max_values || cells * (unsigned long long)channels > max_values)
        return 0;
    return (size_t)(cells * (unsigned long long)channels);
}

svet_status volgrid_alloc(volgrid_t *g, int nx, int ny, int nz, int channels,
                          const float lo[3], const float hi[3],
                          size_t max_values, svet_error *err)
{
    memset(g, 0, sizeof *g);
    if (channels < 1 || channels > VOLGRID_MAX_CHANNELS)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "a grid of %d channels: 1 to %d", channels,
                              VOLGRID_MAX_CHANNELS);
    if (value_count(nx, ny, nz, channels, max_values) == 0)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "a grid of %d x %d x %d cells and %d channels: "
                              "each size must be 1 or more and the values "
                              "at most %zu", nx, ny, nz, channels, max_values);
    for (int k = 0; k < 3; k++)
        if (!(isfinite(lo[k]) && isfinite(hi[k]) && lo[k] < hi[k]))
            return svet_error_set(err, SVET_ERR_RANGE,
                                  "a grid's box must be finite with min < max "
                                  "on every axis (axis %d: %g to %g)", k,
                                  (double)lo[k], (double)hi[k]);
    size_t cells = (size_t)nx * (size_t)ny * (size_t)nz;
    for (int c = 0; c < channels; c++) {
        g->plane[c] = calloc(cells, sizeof(float));
        if (!g->plane[c]) {
            volgrid_free(g);
            return svet_error_set(err, SVET_ERR_NOMEM,
                                  "a grid of %zu cells: out of memory", cells);
        }
    }
    g->nx = nx;
    g->ny = ny;
    g->nz = nz;
    g->channels = channels;
    memcpy(g->lo, lo, sizeof g->lo);
    memcpy(g->hi, hi, sizeof g->hi);
    return SVET_OK;
}

static int32_t le_i32(const unsigned char *b)
{
    return (int32_t)((uint32_t)b[0] | (uint32_t)b[1] << 8 |
                     (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24);
}

static float le_f32(const unsigned char *b)
{
    uint32_t u = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 |
                 (uint32_t)b[3] << 24;
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

static void put_le32(unsigned char *b, uint32_t u)
{
    b[0] = (unsigned char)u;
    b[1] = (unsigned char)(u >> 8);
    b[2] = (unsigned char)(u >> 16);
    b[3] = (unsigned char)(u >> 24);
}

svet_status volgrid_read(volgrid_t *g, const char *path, size_t max_values,
                         svet_error *err)
{
    memset(g, 0, sizeof *g);
    FILE *f;
    svet_status ost = fileio_open_read(path, &f, err); /* regular files only */
    if (ost != SVET_OK)
        return ost;
    struct stat sb;
    if (fstat(fileno(f), &sb) != 0) {
        fclose(f);
        return svet_error_set(err, SVET_ERR_IO, "%s: cannot read: %s", path,
                              strerror(errno));
    }
    long long size = (long long)sb.st_size;
    unsigned char h[VOLGRID_HEADER_BYTES];
    svet_status st = SVET_OK;
    if (fread(h, 1, sizeof h, f) != sizeof h) {
        st = svet_error_set(err, SVET_ERR_PARSE,
                            "%s: %lld bytes, shorter than a .vol header (48)",
                            path, size);
        goto done;
    }
    if (memcmp(h, "VOL", 3) != 0) {
        st = svet_error_set(err, SVET_ERR_PARSE,
                            "%s: not a .vol grid (it does not start with VOL)",
                            path);
        goto done;
    }
    if (h[3] != 3 || le_i32(h + 4) != 1) {
        st = svet_error_set(err, SVET_ERR_UNSUPPORTED,
                            "%s: .vol version %d, encoding %d: only version "
                            "3 with encoding 1 (float32) is read", path, h[3],
                            (int)le_i32(h + 4));
        goto done;
    }
    int32_t nx = le_i32(h + 8), ny = le_i32(h + 12), nz = le_i32(h + 16);
    int32_t ch = le_i32(h + 20);
    float lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = le_f32(h + 24 + 4 * k);
        hi[k] = le_f32(h + 36 + 4 * k);
    }
    size_t n = value_count(nx, ny, nz, ch, max_values);
    if (ch >= 1 && ch <= VOLGRID_MAX_CHANNELS && n > 0 &&
        (long long)n * 4 + VOLGRID_HEADER_BYTES != size) {
        st = svet_error_set(err, SVET_ERR_PARSE,
                            "%s: %lld bytes, but its header declares %d x %d x "
                            "%d cells of %d channels, %lld bytes: %s", path,
                            size, (int)nx, (int)ny, (int)nz, (int)ch,
                            (long long)n * 4 + VOLGRID_HEADER_BYTES,
                            (long long)n * 4 + VOLGRID_HEADER_BYTES > size
                                ? "truncated" : "bytes after the grid");
        goto done;
    }
    st = volgrid_alloc(g, nx, ny, nz, ch, lo, hi, max_values, err);
    if (st != SVET_OK) {
        svet_error_prefix(err, path);
        goto done;
    }
    /* the values, channel fastest, in blocks */
    size_t cells = (size_t)nx * (size_t)ny * (size_t)nz, i = 0;
    unsigned char buf[4096 * 4];
    for (int c = 0; c < ch; c++)
        g->max[c] = -INFINITY;
    while (i < cells * (size_t)ch) {
        size_t want = cells * (size_t)ch - i;
        if (want > 4096)
            want = 4096;
        if (fread(buf, 4, want, f) != want) {
            st = svet_error_set(err, SVET_ERR_IO, "%s: read error", path);
            goto done;
        }
        for (size_t j = 0; j < want; j++, i++) {
            float v = le_f32(buf + 4 * j);
            if (!isfinite(v)) {
                size_t cell = i / (size_t)ch;
                st = svet_error_set(err, SVET_ERR_RANGE,
                                    "%s: value %g at cell (%zu, %zu, %zu) "
                                    "channel %zu: values must be finite",
                                    path, (double)v, cell % (size_t)nx,
                                    cell / (size_t)nx % (size_t)ny,
                                    cell / ((size_t)nx * (size_t)ny),
                                    i % (size_t)ch);
                goto done;
            }
            int c = (int)(i % (size_t)ch);
            g->plane[c][i / (size_t)ch] = v;
            if (v > g->max[c])
                g->max[c] = v;
        }
    }
done:
    fclose(f);
    if (st != SVET_OK)
        volgrid_free(g);
    return st;
}

svet_status volgrid_write(const volgrid_t *g, const char *path,
                          svet_error *err)
{
    fileio_t out;
    svet_status st = fileio_begin(&out, path, err);
    if (st != SVET_OK)
        return st;
    unsigned char h[VOLGRID_HEADER_BYTES];
    memcpy(h, "VOL", 3);
    h[3] = 3;
    put_le32(h + 4, 1);
    put_le32(h + 8, (uint32_t)g->nx);
    put_le32(h + 12, (uint32_t)g->ny);
    put_le32(h + 16, (uint32_t)g->nz);
    put_le32(h + 20, (uint32_t)g->channels);
    for (int k = 0; k < 3; k++) {
        uint32_t a, b;
        memcpy(&a, &g->lo[k], 4);
        memcpy(&b, &g->hi[k], 4);
        put_le32(h + 24 + 4 * k, a);
        put_le32(h + 36 + 4 * k, b);
    }
    fwrite(h, 1, sizeof h, out.f);
    size_t cells = (size_t)g->nx * (size_t)g->ny * (size_t)g->nz;
    for (size_t i = 0; i < cells; i++)
        for (int c = 0; c < g->channels; c++) {
            unsigned char b[4];
            uint32_t u;
            memcpy(&u, &g->plane[c][i], 4);
            put_le32(b, u);
            fwrite(b, 1, 4, out.f);
        }
    return fileio_commit(&out, err); /* checks every write */
}

interp_grid_t volgrid_channel(const volgrid_t *g, int c)
{
    interp_grid_t ig = { g->nx, g->ny, g->nz, g->plane[c] };
    return ig;
}

real volgrid_eval(const volgrid_t *g, int c, const VECTOR3 p)
{
    /* world -> [0, 1]^3 of the box -> grid coordinates, whose integer
     * points are the cell centres */
    VECTOR3 q;
    const int n[3] = { g->nx, g->ny, g->nz };
    for (int k = 0; k < 3; k++)
        q[k] = (p[k] - (real)g->lo[k]) / ((real)g->hi[k] - (real)g->lo[k]) *
                   (real)n[k] - REAL_C(0.5);
    interp_grid_t ig = volgrid_channel(g, c);
    return interp_trilinear(&ig, q);
}
