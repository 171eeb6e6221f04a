/*
 * exrio.h - OpenEXR files through the library's C API (OpenEXRCore 3.1,
 * <openexr.h>): the linear HDR output of the renderer. Scanline images,
 * R G B (and A), half or float, uncompressed or ZIP. The prefix is exrio_
 * because exr_ is the library's own.
 * Tests: tests/io/test_exrio.c
 */
#ifndef SVET_EXRIO_H
#define SVET_EXRIO_H

#include "core/error.h"
#include "io/fileio.h"
#include "io/image.h"

typedef enum {
    EXRIO_HALF,  /* 16-bit float: 11 significant bits, max 65504 */
    EXRIO_FLOAT  /* 32-bit float: the image's values bit for bit */
} exrio_pixel_t;

typedef enum {
    EXRIO_NONE, /* uncompressed */
    EXRIO_ZIP   /* lossless deflate, 16 scanlines per chunk */
} exrio_compression_t;

/* Write img as a single-part scanline EXR with channels R G B (and A if
 * img has 4 channels), every channel of type `pixel`, data window and
 * display window (0,0)-(width-1,height-1), increasing-y line order. A float
 * value too large for a half becomes +-Inf, as the library converts it.
 * Goes through a temporary file (fileio.h): the target is replaced only if
 * the whole file was written. Fails with SVET_ERR_IO (the path and the
 * library's or system's reason), SVET_ERR_NOMEM. */
svet_status exrio_write(const char *path, const image_t *img,
                        exrio_pixel_t pixel, exrio_compression_t compression,
                        svet_error *err);

/* The same into out, begun by fileio_begin() or fileio_set_begin(), which
 * the caller then commits or aborts (messages name out->path). Fails as
 * exrio_write() does. */
svet_status exrio_write_to(fileio_t *out, const image_t *img,
                           exrio_pixel_t pixel,
                           exrio_compression_t compression, svet_error *err);

/* Read the first part of an EXR file into img (allocated here): its data
 * window becomes the image (the display window and the window's offset are
 * not kept). Channels are found by name in any order: R, G and B give a
 * 3-channel image, plus A a 4-channel one; without R, G and B, a Y (with
 * or without A) is read as grey, copied to R, G and B: so are luminance
 * and chroma files (Y RY BY) and X Y Z files, whose other channels are not
 * used. Every other channel (Z, depth, subsampled chroma, ...) is decoded
 * and left out. Half, float and uint channels are converted to float;
 * every compression the library knows is read. img is
 * zeroed on entry and left zeroed on failure. Fails with SVET_ERR_IO
 * (cannot open or read), SVET_ERR_PARSE (not an EXR file, a corrupt header
 * or chunk, a truncated file, R G B incomplete: the message lists the
 * channels found), SVET_ERR_UNSUPPORTED (tiled or deep files; R, G, B,
 * A or the Y read subsampled), SVET_ERR_RANGE (dimensions beyond the
 * limits of image.h or `lim`), SVET_ERR_NOMEM. A directory, FIFO or
 * device is refused (fileio.h).
 * Every message starts with the path. */
svet_status exrio_read(const char *path, image_t *img, svet_error *err);

/* exrio_read() with the limits of `lim` (NULL: the defaults of image.h):
 * a file of more pixels than lim allows fails with SVET_ERR_RANGE before
 * its pixels are allocated. */
svet_status exrio_read_with(const char *path, image_t *img,
                            const image_read_limits_t *lim, svet_error *err);

#endif
