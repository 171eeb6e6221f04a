/*
 * pngio.h - PNG files through libpng (1.6): the display output of ch. 6,
 * 8 or 16 bits per channel. The prefix is pngio_ because png_ is libpng's.
 * PNG holds ENCODED values (codes of a display transfer curve, normally
 * sRGB): tone-map and encode first (tonemap.h), then write.
 * Tests: tests/io/test_pngio.c
 */
#ifndef SVET_PNGIO_H
#define SVET_PNGIO_H

#include "core/error.h"
#include "io/fileio.h"
#include "io/image.h"

/* Write img as a PNG: RGB for 3 channels, RGBA (straight alpha) for 4,
 * with `bits` 8 or 16 per channel. Values are codes in [0, 1], quantised
 * by image_quantize() (clamped, NaN as 0). No colour chunk is written (a
 * PNG without one is taken as sRGB by viewers). Goes through a temporary
 * file (fileio.h). Fails with SVET_ERR_RANGE for other bits, SVET_ERR_IO
 * (the path and libpng's or the system's reason), SVET_ERR_NOMEM. */
svet_status pngio_write(const char *path, const image_t *img, int bits,
                        svet_error *err);

/* The same into out, begun by fileio_begin() or fileio_set_begin(), which
 * the caller then commits or aborts (messages name out->path). Fails as
 * pngio_write() does. */
svet_status pngio_write_to(fileio_t *out, const image_t *img, int bits,
                           svet_error *err);

/* Read any PNG (grey, grey+alpha, palette, RGB, RGBA; 1 to 16 bits;
 * interlaced or not) into img, allocated here: 3 channels, or 4 if the
 * file has alpha (an alpha channel or a tRNS chunk); grey is copied to R,
 * G and B. Values are code / (2^depth - 1): encoded, not linearised
 * (colour_srgb_decode() does that). *bits (if not NULL) receives 16 for a
 * 16-bit file, else 8. img is zeroed on entry and left zeroed on failure.
 * Fails with SVET_ERR_IO (cannot open), SVET_ERR_PARSE (not a PNG; a
 * corrupt, truncated or lying file: libpng's message follows the path),
 * SVET_ERR_RANGE (dimensions beyond the limits of image.h),
 * SVET_ERR_NOMEM. A directory, FIFO or device is refused (fileio.h). */
svet_status pngio_read(const char *path, image_t *img, int *bits,
                       svet_error *err);

/* pngio_read() with the limits of `lim` (NULL: the defaults of image.h):
 * a file of more pixels than lim allows fails with SVET_ERR_RANGE before
 * its rows are allocated or decoded. */
svet_status pngio_read_with(const char *path, image_t *img, int *bits,
                            const image_read_limits_t *lim, svet_error *err);

#endif
