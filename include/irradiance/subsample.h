/*
 * subsample.h - app. F: adaptive image subsampling, a way for any
 * integrator to compute fewer pixels. Every k-th pixel of every k-th row
 * is computed; each block between four computed corners is split while
 * its corners differ by more than a threshold (the largest channel's
 * contrast |a - b| / (a + b), as Mitchell 1987's adaptive sampling
 * measures it), down to single pixels; pixels left in blocks whose
 * corners agree are interpolated bilinearly from them (the idea of
 * Whitted 1980's adaptive supersampling, applied to whole pixels).
 * Tests: tests/irradiance/test_subsample.c
 */
#ifndef SVET_SUBSAMPLE_H
#define SVET_SUBSAMPLE_H

#include <stdint.h>

#include "core/error.h"
#include "io/image.h"

/* Compute pixel (x, y): its RGB in out[0..2]. */
typedef void (*subsample_pixel_fn)(void *ctx, int x, int y, float out[3]);

typedef struct {
    int step;         /* k: the coarse grid's spacing, a power of 2, >= 1 */
    real threshold;   /* the largest contrast between corners that is
                         interpolated, in [0, 1); 0 computes every pixel of
                         a block that is not constant */
} subsample_params_t;

/* Fill img (allocated, width x height, 3 channels) by subsampling; if
 * computed is not NULL it receives, per pixel, 1 where f computed it and
 * 0 where it was interpolated (the mask ch. 9's program draws). Returns
 * the number of pixels computed through *n_computed. The pixels are
 * computed in a fixed order (coarse grid in rows, then each block's
 * refinement depth first), so the image depends on f and the parameters
 * only. Fails with SVET_ERR_RANGE on a step that is not a power of 2 or
 * a threshold outside [0, 1). */
svet_status subsample_image(image_t *img, const subsample_params_t *p,
                            subsample_pixel_fn f, void *ctx,
                            uint8_t *computed, long *n_computed,
                            svet_error *err);

#endif
