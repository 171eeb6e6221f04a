/*
 * mipmap.h - image textures of ch. 10 as a mip map (Williams, "Pyramidal
 * Parametrics", SIGGRAPH 1983): the image and its successive halvings,
 * looked up by nearest texel, bilinearly, or trilinearly between the two
 * levels whose texel size brackets the lookup's footprint, the level blend
 * being app. L's linear interpolation. Wrap modes repeat, clamp and mirror.
 * Tests: tests/texture/test_mipmap.c
 */
#ifndef SVET_MIPMAP_H
#define SVET_MIPMAP_H

#include "core/error.h"
#include "core/real.h"

#define MIPMAP_MAX_LEVELS 17     /* 65536 = 2^16 texels wide, and 1 x 1 */
#define MIPMAP_MAX_CHANNELS 4

/* What lies beyond [0, 1) in s and t. */
typedef enum {
    MIPMAP_REPEAT, /* the image tiles the plane */
    MIPMAP_CLAMP,  /* the border texels continue outward */
    MIPMAP_MIRROR  /* tiles, every other one flipped: no seams */
} mipmap_wrap_t;

typedef enum {
    MIPMAP_NEAREST,   /* the texel holding (s, t), on level 0 */
    MIPMAP_BILINEAR,  /* the four nearest texel centres, on level 0 */
    MIPMAP_TRILINEAR  /* bilinear on the two levels around the footprint */
} mipmap_filter_t;

/* One level: width x height texels of `channels` floats, row by row;
 * row 0 is the image's first row as stored. */
typedef struct {
    int width, height;
    float *px;
} mipmap_level_t;

typedef struct {
    int levels;   /* 1 + floor(log2(max(width, height))) */
    int channels; /* 1 to MIPMAP_MAX_CHANNELS */
    mipmap_wrap_t wrap;
    mipmap_level_t level[MIPMAP_MAX_LEVELS];
} mipmap_t;

/* Build the pyramid of a width x height image of `channels` floats per
 * texel (copied: px may be freed after). Level l + 1 halves level l,
 * rounding up, each texel the mean of the 2 x 2 texels below it, read
 * through the wrap mode where an odd size leaves one out. The image must
 * hold finite values. Fails (SVET_ERR_RANGE) on a size outside 1..65536
 * or a channel count outside 1..4, SVET_ERR_NOMEM when memory runs out;
 * m is then empty and mipmap_free() is harmless. */
svet_status mipmap_build(mipmap_t *m, const float *px, int width, int height,
                         int channels, mipmap_wrap_t wrap, svet_error *err);

void mipmap_free(mipmap_t *m);

/* The texel (x, y) of a level, any integers, folded into the level by the
 * wrap mode; its channels go to out[0 .. channels - 1]. Can't fail. */
void mipmap_texel(const mipmap_t *m, int level, int x, int y, real *out);

/* The texture at (s, t), s = 0 the left edge of the image and s = 1 its
 * right, t = 0 its first row and t = 1 past its last. `width` is the
 * footprint of the lookup in the same units (a pixel's extent on the
 * texture, e.g. from ray differentials); only the trilinear filter reads
 * it: the level is log2(width * max(image width, height)), clamped to the
 * pyramid. A NaN s, t or width reads as 0. Can't fail. */
void mipmap_lookup(const mipmap_t *m, mipmap_filter_t filter, real s, real t,
                   real width, real *out);

#endif
