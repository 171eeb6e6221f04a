/*
 * subsample.h - app. F: adaptive image subsampling, a way for any
 * integrator to compute fewer pixels. Every k-th pixel of every k-th row
 * is computed; each block between four computed corners is split while
 * its corners differ by more than a threshold (the largest channel's
 * contrast |a - b| / (a + b), as Mitchell 1987's adaptive sampling
 * measures it), down to single pixels; pixels left in blocks whose
 * corners agree are interpolated bilinearly from them (the idea of
 * Whitted 1980's adaptive supersampling, applied to whole pixels).
 * The renderer offers it as `render subsample step K threshold T`
 * (render.h, scenes/README.md) where a program lists it in its
 * scene_features_t (scene.h); ch. 9's program draws its mask.
 * Tests: tests/render/test_subsample.c
 */
#ifndef SVET_SUBSAMPLE_H
#define SVET_SUBSAMPLE_H

#include <signal.h>
#include <stdbool.h>
#include <stdint.h>

#include "core/error.h"
#include "io/image.h"

/* Compute pixel (x, y): its RGB in out[0..2]. Called from several threads
 * at once (never twice for one pixel) by subsample_image_threads(). */
typedef void (*subsample_pixel_fn)(void *ctx, int x, int y, float out[3]);

typedef struct {
    int step;         /* k: the coarse grid's spacing, a power of 2, >= 1 */
    real threshold;   /* the largest contrast between corners that is
                         interpolated, in [0, 1); 0 computes every pixel of
                         a block that is not constant */
} subsample_params_t;

/* The largest step and the checks of the parameters, shared with the
 * scene file's `render subsample` (its messages add file:line:col). */
#define SUBSAMPLE_MAX_STEP 256

/* Fill img (allocated, width x height, 3 channels) by subsampling; if
 * computed is not NULL it receives, per pixel, 1 where f computed it and
 * 0 where it was interpolated (the mask ch. 9's program draws). Returns
 * the number of pixels computed through *n_computed. The work goes level
 * by level, coarse to fine: the pixels one level needs are listed in a
 * fixed order and then computed (in parallel by
 * subsample_image_threads()), the blocks are split or kept in list
 * order, and the interpolation runs last, coarse blocks first, the finer
 * ones after them where they share an edge. Which pixels are computed
 * and every interpolated value therefore depend on f and the parameters
 * only: not on the thread count. Fails with SVET_ERR_RANGE on a step
 * that is not a power of 2 in [1, SUBSAMPLE_MAX_STEP] or a threshold
 * outside [0, 1), SVET_ERR_NOMEM. One thread. */
svet_status subsample_image(image_t *img, const subsample_params_t *p,
                            subsample_pixel_fn f, void *ctx,
                            uint8_t *computed, long *n_computed,
                            svet_error *err);

/* The same with `threads` threads (0: all cores), given up as soon as
 * *stop (when not NULL) is non-zero: then *stopped (may be NULL) is set
 * and img holds only some of the pixels. */
svet_status subsample_image_threads(image_t *img,
                                    const subsample_params_t *p,
                                    subsample_pixel_fn f, void *ctx,
                                    uint8_t *computed, long *n_computed,
                                    int threads,
                                    const volatile sig_atomic_t *stop,
                                    bool *stopped, svet_error *err);

/* What a program offers the renderer (scene_features_t.subsample): the
 * renderer calls through it, so that a program without app. F links none
 * of this module. */
typedef struct subsample_ops {
    svet_status (*image)(image_t *img, const subsample_params_t *p,
                         subsample_pixel_fn f, void *ctx, uint8_t *computed,
                         long *n_computed, int threads,
                         const volatile sig_atomic_t *stop, bool *stopped,
                         svet_error *err);
} subsample_ops_t;

extern const subsample_ops_t subsample_ops;

#endif
