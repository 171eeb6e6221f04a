/*
 * netpbm.h - image files that need no library, so that a chapter program
 * builds with `cc ... -lm` alone: PFM (Portable Float Map: 32-bit floats,
 * linear HDR) and PPM (P6: 8 or 16-bit codes, usually sRGB-encoded).
 * Formats: netpbm.sourceforge.net/doc/ppm.html and Paul Debevec's PFM
 * (www.pauldebevec.com/Research/HDR/PFM/). Tests: tests/io/test_netpbm.c
 */
#ifndef SVET_NETPBM_H
#define SVET_NETPBM_H

#include "core/error.h"
#include "io/image.h"

/* Write img (3 or 4 channels; alpha is dropped) as a colour PFM ("PF"),
 * little-endian (scale -1), rows bottom to top as the format orders them.
 * Values are written bit for bit, NaN and Inf included. Goes through a
 * temporary file (fileio.h). Fails with SVET_ERR_IO (the path and the
 * reason) or SVET_ERR_NOMEM. */
svet_status netpbm_write_pfm(const char *path, const image_t *img,
                             svet_error *err);

/* Read a PFM, colour ("PF") or grey ("Pf", copied to R, G and B), of either
 * byte order (the sign of the scale: negative little-endian, positive
 * big-endian), into img (allocated here, 3 channels, row 0 at the top).
 * Values are returned as stored: the magnitude of the scale is not applied
 * (no common writer means anything by it). img is zeroed on entry and left
 * zeroed on failure. Fails with SVET_ERR_IO (cannot open / read),
 * SVET_ERR_PARSE (not a PFM, a malformed header, truncated data, a zero or
 * non-finite scale), SVET_ERR_RANGE (dimensions below 1 or beyond the
 * limits of image.h) or SVET_ERR_NOMEM; every message starts with the
 * path. A directory, FIFO or device is refused (fileio.h). */
svet_status netpbm_read_pfm(const char *path, image_t *img, svet_error *err);

/* netpbm_read_pfm() with the limits of `lim` (NULL: the defaults of
 * image.h): a file of more pixels than lim allows fails with
 * SVET_ERR_RANGE before anything is allocated. */
svet_status netpbm_read_pfm_with(const char *path, image_t *img,
                                 const image_read_limits_t *lim,
                                 svet_error *err);

/* Write img (3 or 4 channels; alpha is dropped) as a binary PPM ("P6")
 * with `bits` 8 (maxval 255) or 16 (maxval 65535, big-endian as the format
 * says). Values are taken as ENCODED codes in [0, 1] (apply the display
 * transfer first: tonemap.h), quantised by image_quantize(). Fails with
 * SVET_ERR_RANGE for other bits, otherwise as netpbm_write_pfm(). */
svet_status netpbm_write_ppm(const char *path, const image_t *img, int bits,
                             svet_error *err);

/* Read a binary PPM ("P6") or PGM ("P5", copied to R, G and B) with any
 * maxval 1..65535 into img (3 channels) as code / maxval: encoded values
 * in [0, 1], not linearised. *bits (if not NULL) receives 8 for maxval <=
 * 255, else 16. '#' comments in the header are skipped. Fails as
 * netpbm_read_pfm() does. */
svet_status netpbm_read_ppm(const char *path, image_t *img, int *bits,
                            svet_error *err);

/* netpbm_read_ppm() with the limits of `lim`, as netpbm_read_pfm_with(). */
svet_status netpbm_read_ppm_with(const char *path, image_t *img, int *bits,
                                 const image_read_limits_t *lim,
                                 svet_error *err);

#endif
