/*
 * ztest.h - is a render the same as a reference, up to its noise? The
 * per-pixel Z-test of Mitsuba 3's render tests (src/render/tests/
 * test_renders.py): for every pixel value z = (a - b) / sqrt(var_a + var_b),
 * a two-sided p-value, a significance Sidak-corrected over all the values
 * tested, and the render passes when at least 99.5 % of the pixels pass.
 * The same test then runs on blocks of 4 x 4, 16 x 16, ... pixels up to the
 * whole image, where a bias too small to see in one noisy pixel adds up.
 * Tests: tests/stats/test_ztest.c (synthetic images), tests/render/test_reference.c
 */
#ifndef SVET_ZTEST_H
#define SVET_ZTEST_H

#include <stdbool.h>
#include "core/error.h"
#include "io/image.h"

#define ZTEST_ALPHA 0.01       /* chance of failing a correct render */
#define ZTEST_MIN_PASS 0.995   /* fraction of a level's cells that must pass */
#define ZTEST_BLOCK_FACTOR 4   /* block side grows 4x from level to level */
#define ZTEST_ROUND_REL 1e-5   /* differences this small (relative) are
                                  rounding */
#define ZTEST_MAX_LEVELS 16

typedef struct {
    double alpha;        /* family-wise significance over every value of
                            every level (Sidak): a correct render fails
                            with probability at most alpha */
    double min_pass;     /* a level passes when at least this fraction of
                            its cells (pixels, blocks) pass */
    int block_factor;    /* >= 2: levels of blocks 1, f, f^2, ... pixels a
                            side, the last one the whole image; 1: the
                            pixel level alone */
    double round_rel;    /* |a - b| up to round_rel max(|a|, |b|) is
                            rounding, not bias: it is taken off |a - b|
                            before the test. Where the variance is 0 on
                            both sides (an empty background, an emitter
                            seen directly) the values must agree to it;
                            where an estimator has almost no variance (the
                            furnace: 0.5 up to the last bit) the float
                            rounding of two builds differs by more than
                            its "noise" */
} ztest_params_t;

/* One side of the comparison. */
typedef struct {
    const image_t *mean; /* the image (R G B are tested; alpha is not) */
    const image_t *var;  /* per-pixel variance of the mean (render.h's
                            render_variance), or NULL for an exact image */
    double spp;          /* samples per pixel behind it; 0 if unknown */
} ztest_image_t;

/* What one level found. Cells are pixels at level 0, else blocks; a cell
 * passes when its three values (R, G, B) pass. */
typedef struct {
    int block;          /* block side in pixels (1: pixels) */
    int cols, rows;     /* cells across and down (edge blocks are partial) */
    long cells, failed; /* cells tested and rejected */
    long zero_var;      /* values with zero variance on both sides */
    double min_p;       /* the smallest p-value of the level */
    double worst_z;     /* the z of that value (signed: a - b over sigma;
                           +-Inf where zero variances disagree) */
    int worst_x, worst_y, worst_c; /* its cell and channel */
    bool pass;          /* failed <= (1 - min_pass) cells */
} ztest_level_t;

typedef struct {
    int nlevels;
    ztest_level_t level[ZTEST_MAX_LEVELS];
    long values;        /* values tested over all levels */
    double threshold;   /* per-value significance: 1 - (1 - alpha)^(1/values) */
    bool pass;          /* every level passed */
} ztest_result_t;

/* alpha 0.01, min_pass 0.995, block_factor 4, round_rel 1e-5. This
 * function can't fail. */
void ztest_params_default(ztest_params_t *p);

/* Test image a against b (which is which does not matter; b is usually the
 * reference). Each side's variance of the mean is raised to at least the
 * other side's per-sample variance (var x spp) divided by its own spp,
 * when both spp are known: under the hypothesis both images average the
 * same estimator, and the per-sample variance of a 16-sample render misses
 * the rare bright paths that a 16384-sample reference has seen (Mitsuba
 * takes the reference's alone). A NaN or infinite value fails. When pvalue
 * is not NULL it receives the per-pixel p-values (3 channels, allocated
 * here). Fails with SVET_ERR_RANGE when the sizes differ or a parameter is
 * out of range, SVET_ERR_NOMEM. */
svet_status ztest_run(const ztest_image_t *a, const ztest_image_t *b,
                      const ztest_params_t *p, ztest_result_t *res,
                      image_t *pvalue, svet_error *err);

/* The two-sided p-value of z for a standard normal, erfc(|z| / sqrt 2);
 * 0 for infinite z, 1 for z = 0, NaN for NaN. This function can't fail. */
double ztest_pvalue(double z);

/* Sidak's per-test significance for n independent tests at family-wise
 * significance alpha: 1 - (1 - alpha)^(1/n), computed without
 * cancellation. This function can't fail. */
double ztest_sidak(double alpha, double n);

#endif
