/*
 * imageio.h - images by file name: read any format svet knows (EXR, PFM,
 * PNG, PPM/PGM), recognised by its first bytes, not its name; write by the
 * name's extension. The one call a renderer needs to save its result as
 * linear HDR plus a tone-mapped picture is imageio_save_render().
 * Tests: tests/io/test_imageio.c
 */
#ifndef SVET_IMAGEIO_H
#define SVET_IMAGEIO_H

#include <stdbool.h>
#include "core/error.h"
#include "io/image.h"
#include "colour/tonemap.h"

typedef enum {
    IMAGEIO_UNKNOWN,
    IMAGEIO_EXR, /* linear, half or float */
    IMAGEIO_PFM, /* linear, float */
    IMAGEIO_PNG, /* encoded display codes, 8 or 16 bits */
    IMAGEIO_PPM  /* encoded display codes (P6 or P5), 8 or 16 bits */
} imageio_format_t;

/* The format a file name asks for by its extension (case-insensitive:
 * .exr .pfm .png .ppm .pgm), or IMAGEIO_UNKNOWN. Can't fail. */
imageio_format_t imageio_format_from_name(const char *path);

/* True for formats that hold display codes rather than linear values. */
bool imageio_is_display(imageio_format_t f);

/* Read path, whatever its format, into img (allocated here). The format is
 * told by the file's first bytes; *format (if not NULL) receives it. PNG
 * and PPM values are returned as stored (codes / maxval); with `linearise`
 * they are decoded with the sRGB curve (colour_srgb_decode) so that they
 * compare with linear images. Fails as the format's reader does; a file of
 * no known format gives SVET_ERR_PARSE ("not an EXR, PFM, PNG or PPM
 * file"). */
svet_status imageio_read(const char *path, image_t *img, bool linearise,
                         imageio_format_t *format, svet_error *err);

/* imageio_read() with the limits of `lim` (NULL: the defaults of
 * image.h), handed to the format's reader. */
svet_status imageio_read_with(const char *path, image_t *img, bool linearise,
                              imageio_format_t *format,
                              const image_read_limits_t *lim,
                              svet_error *err);

/* Replace the R, G, B display codes of img by linear values with the sRGB
 * curve (colour_srgb_decode); alpha is left alone. Can't fail. */
void imageio_decode_srgb(image_t *img);

/* Write img to path in the format of its extension: .exr as 32-bit float
 * with ZIP (exact), .pfm, and .png/.ppm as 8-bit codes of values already
 * encoded in [0, 1]. Fails with SVET_ERR_UNSUPPORTED for another
 * extension, else as the format's writer does. */
svet_status imageio_write(const char *path, const image_t *img,
                          svet_error *err);

/* Save a render: the linear image as `hdr_path` (.exr or .pfm, exact
 * floats; NULL to skip) and, tone-mapped with `tm` (NULL: Reinhard with
 * the defaults of tonemap.h) and sRGB-encoded, as `display_path` (.png or
 * .ppm, 8 bits; NULL to skip). res (may be NULL) receives what the tone
 * mapping found (NaN/Inf pixels and so on). Each file goes through a
 * temporary file, so an earlier output survives a failure. Fails as
 * imageio_write() and tonemap_apply() do. */
svet_status imageio_save_render(const image_t *img, const char *hdr_path,
                                const char *display_path,
                                const tonemap_params_t *tm,
                                tonemap_result_t *res, svet_error *err);

#endif
