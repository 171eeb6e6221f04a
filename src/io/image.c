/*
 * image.c - float images and the per-pixel accumulation of a render
 * (ch. 5 adds samples, ch. 6 displays the mean). See image.h.
 * Tests: tests/io/test_image.c
 */
#include "io/image.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

svet_status image_check_size(long long width, long long height, int channels,
                             size_t elem, size_t *bytes, svet_error *err)
{
    if (width < 1 || height < 1)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "image size %lld x %lld: both must be at least 1",
                              width, height);
    if (width > IMAGE_MAX_DIM || height > IMAGE_MAX_DIM ||
        (uint64_t)width * (uint64_t)height > IMAGE_MAX_PIXELS)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "image size %lld x %lld exceeds the limit of %d "
                              "pixels a side, %llu in all",
                              width, height, IMAGE_MAX_DIM,
                              (unsigned long long)IMAGE_MAX_PIXELS);
    if (channels < 1 || elem < 1)
        return svet_error_set(err, SVET_ERR_RANGE, "image with %d channels of "
                              "%zu bytes", channels, elem);
    /* Multiply step by step, checking each product against SIZE_MAX: on a
     * 32-bit size_t the limits above still overflow. */
    size_t n = (size_t)width;
    const size_t factor[3] = { (size_t)height, (size_t)channels, elem };
    for (int i = 0; i < 3; i++) {
        if (n > SIZE_MAX / factor[i])
            return svet_error_set(err, SVET_ERR_NOMEM,
                                  "image size %lld x %lld x %d x %zu bytes "
                                  "overflows size_t",
                                  width, height, channels, elem);
        n *= factor[i];
    }
    if (bytes)
        *bytes = n;
    return SVET_OK;
}

svet_status image_check_read_size(long long width, long long height,
                                  int channels, size_t elem,
                                  const image_read_limits_t *lim,
                                  size_t *bytes, svet_error *err)
{
    uint64_t max = lim && lim->max_pixels ? lim->max_pixels
                                          : IMAGE_READ_MAX_PIXELS;
    if (max > IMAGE_MAX_PIXELS)
        max = IMAGE_MAX_PIXELS;
    if (width >= 1 && height >= 1 && width <= IMAGE_MAX_DIM &&
        height <= IMAGE_MAX_DIM && (uint64_t)width * (uint64_t)height > max)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "image size %lld x %lld (%llu pixels) exceeds "
                              "the limit of %llu pixels for an image read "
                              "from a file (svet: --max-pixels N or "
                              "SVET_MAX_PIXELS=N)", width, height,
                              (unsigned long long)((uint64_t)width *
                                                   (uint64_t)height),
                              (unsigned long long)max);
    return image_check_size(width, height, channels, elem, bytes, err);
}

svet_status image_alloc(image_t *img, int width, int height, int channels,
                        svet_error *err)
{
    memset(img, 0, sizeof *img);
    if (channels != 3 && channels != 4)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "image with %d channels: only 3 (RGB) or 4 "
                              "(RGBA)", channels);
    size_t bytes = 0;
    svet_status st = image_check_size(width, height, channels, sizeof(float),
                                      &bytes, err);
    if (st != SVET_OK)
        return st;
    img->px = calloc(1, bytes);
    if (!img->px)
        return svet_error_set(err, SVET_ERR_NOMEM, "image %d x %d: cannot "
                              "allocate %zu bytes", width, height, bytes);
    img->width = width;
    img->height = height;
    img->channels = channels;
    return SVET_OK;
}

void image_free(image_t *img)
{
    if (!img)
        return;
    free(img->px);
    memset(img, 0, sizeof *img);
}

svet_status image_copy(image_t *dst, const image_t *src, svet_error *err)
{
    svet_status st = image_alloc(dst, src->width, src->height, src->channels,
                                 err);
    if (st == SVET_OK)
        memcpy(dst->px, src->px, (size_t)src->width * (size_t)src->height *
                                     (size_t)src->channels * sizeof(float));
    return st;
}

/* --- accumulation -------------------------------------------------------- */

double image_fixed_value(const image_fixed_t *s, int q)
{
    image_fixed_t t = *s;
    const bool negative = t.w[2] >> 63;
    if (negative) { /* the magnitude: ~t + 1 */
        for (int k = 0; k < 3; k++)
            t.w[k] = ~t.w[k];
        const image_fixed_t one = { { 1, 0, 0 } };
        image_fixed_add(&t, &one);
    }
    /* 0x1p128 and 0x1p64 scale exactly; ldexp by -q is exact above the
     * subnormals, which a value of at least 2^-q never reaches */
    double v = (double)t.w[2] * 0x1p128 + (double)t.w[1] * 0x1p64 +
               (double)t.w[0];
    v = ldexp(v, -q);
    return negative ? -v : v;
}

svet_status image_accum_alloc(image_accum_t *acc, int width, int height,
                              svet_error *err)
{
    memset(acc, 0, sizeof *acc);
    size_t sum_bytes = 0, count_bytes = 0;
    svet_status st = image_check_size(width, height, 3, sizeof(image_fixed_t),
                                      &sum_bytes, err);
    if (st == SVET_OK)
        st = image_check_size(width, height, 1, sizeof(uint64_t), &count_bytes,
                              err);
    if (st != SVET_OK)
        return st;
    acc->sum = calloc(1, sum_bytes);
    acc->count = calloc(1, count_bytes);
    acc->nonfinite = calloc(1, count_bytes);
    if (!acc->sum || !acc->count || !acc->nonfinite) {
        image_accum_free(acc);
        return svet_error_set(err, SVET_ERR_NOMEM, "accumulation %d x %d: "
                              "cannot allocate %zu bytes", width, height,
                              sum_bytes + 2 * count_bytes);
    }
    acc->width = width;
    acc->height = height;
    return SVET_OK;
}

void image_accum_free(image_accum_t *acc)
{
    if (!acc)
        return;
    free(acc->sum);
    free(acc->count);
    free(acc->nonfinite);
    memset(acc, 0, sizeof *acc);
}

svet_status image_accum_merge(image_accum_t *dst, const image_accum_t *src,
                              svet_error *err)
{
    if (dst->width != src->width || dst->height != src->height)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "cannot merge a %d x %d accumulation into a "
                              "%d x %d one", src->width, src->height,
                              dst->width, dst->height);
    size_t n = (size_t)dst->width * (size_t)dst->height;
    for (size_t i = 0; i < 3 * n; i++)
        image_fixed_add(&dst->sum[i], &src->sum[i]);
    for (size_t i = 0; i < n; i++) {
        dst->count[i] += src->count[i];
        dst->nonfinite[i] += src->nonfinite[i];
    }
    return SVET_OK;
}

svet_status image_accum_resolve(const image_accum_t *acc, image_t *out,
                                uint64_t *empty, svet_error *err)
{
    svet_status st = image_alloc(out, acc->width, acc->height, 3, err);
    if (st != SVET_OK)
        return st;
    size_t n = (size_t)acc->width * (size_t)acc->height;
    uint64_t n_empty = 0;
    for (size_t i = 0; i < n; i++) {
        if (acc->count[i] == 0) {
            n_empty++; /* calloc left it black */
            continue;
        }
        /* Divide rather than multiply by 1/n: n equal samples give that
         * sample back exactly. */
        double n_i = (double)acc->count[i];
        for (int c = 0; c < 3; c++)
            out->px[3 * i + (size_t)c] =
                (float)(image_fixed_value(&acc->sum[3 * i + (size_t)c],
                                          IMAGE_SUM_Q) / n_i);
    }
    if (empty)
        *empty = n_empty;
    return SVET_OK;
}

static uint64_t total(const uint64_t *v, const image_accum_t *acc)
{
    uint64_t t = 0;
    size_t n = (size_t)acc->width * (size_t)acc->height;
    for (size_t i = 0; i < n; i++)
        t += v[i];
    return t;
}

uint64_t image_accum_samples(const image_accum_t *acc)
{
    return total(acc->count, acc);
}

uint64_t image_accum_nonfinite(const image_accum_t *acc)
{
    return total(acc->nonfinite, acc);
}
