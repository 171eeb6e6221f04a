/*
 * image.h - the images of ch. 5 and ch. 6: a float RGB(A) image, and the
 * accumulation a renderer adds its samples to (sum and count per pixel), so
 * that renders made in passes, or on several machines, merge exactly.
 * File formats live in netpbm.h (PFM, PPM), exrio.h and pngio.h; every
 * writer goes through fileio.h (temporary file, then rename).
 * Tests: tests/io/test_image.c
 */
#ifndef SVET_IMAGE_H
#define SVET_IMAGE_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "core/error.h"
#include "materials/radiance.h"

/* Limits that every reader checks before it allocates: a header that
 * claims 2^31 x 2^31 pixels is an error, not a 16-exabyte malloc. 65536
 * pixels a side is eight times an 8K frame; 2^28 pixels is a 16384^2 image
 * (4 GiB as RGBA floats). */
#define IMAGE_MAX_DIM 65536
#define IMAGE_MAX_PIXELS (UINT64_C(1) << 28)

/* The pixels a reader loads from one file unless told otherwise: 2^26
 * (8192 x 8192, 768 MiB as RGB floats, about four 8K frames). A file's
 * header can claim far more than its bytes hold (a few hundred kilobytes
 * of deflate stream expand a thousandfold), so the claim is checked
 * against this before anything is allocated. The svet command raises or
 * lowers it with --max-pixels or SVET_MAX_PIXELS (cmd/README.md). */
#define IMAGE_READ_MAX_PIXELS (UINT64_C(1) << 26)

/* What a reader may load; every reader's *_with() variant takes one, and
 * NULL means the defaults. */
typedef struct {
    uint64_t max_pixels; /* width x height at most; 0: IMAGE_READ_MAX_PIXELS
                            (never more than IMAGE_MAX_PIXELS) */
} image_read_limits_t;

/* A resolved image: linear values as floats whatever `real` is (files hold
 * 32-bit floats or halves, and an image of doubles would double the memory
 * for nothing a display can show). Pixel (x, y) is at
 * px[(y * width + x) * channels], x to the right, y DOWN: row 0 is the top
 * row, as in EXR and PNG (PFM's bottom-up rows are flipped on I/O). */
typedef struct {
    int width, height; /* pixels, each in 1..IMAGE_MAX_DIM */
    int channels;      /* 3: R G B, or 4: R G B A (straight, not premultiplied) */
    float *px;         /* width * height * channels floats, interleaved */
} image_t;

/* Allocate img as width x height with `channels` (3 or 4) channels, all
 * zero. img is written even on failure (zeroed), so image_free() is always
 * safe on it. Fails with SVET_ERR_RANGE for a size below 1, above
 * IMAGE_MAX_DIM a side or IMAGE_MAX_PIXELS in all, or channels not 3 or 4;
 * with SVET_ERR_NOMEM when the byte count overflows size_t or malloc
 * fails. */
svet_status image_alloc(image_t *img, int width, int height, int channels,
                        svet_error *err);

/* Release the pixels and zero *img. Safe on a zeroed or freed image and
 * on NULL. This function can't fail. */
void image_free(image_t *img);

/* The byte count of a width x height x channels array of elem-byte values,
 * in *bytes. Fails with SVET_ERR_RANGE as image_alloc() does, and with
 * SVET_ERR_NOMEM when the product overflows size_t. Readers call it on the
 * dimensions a header claims before allocating anything. */
svet_status image_check_size(long long width, long long height, int channels,
                             size_t elem, size_t *bytes, svet_error *err);

/* The check of a reader on the size a header claims, before it allocates:
 * fails with SVET_ERR_RANGE when width x height exceeds lim's max_pixels
 * (the message gives both numbers and says how svet raises the limit), and
 * otherwise as image_check_size() does; *bytes as there. lim may be NULL
 * (the defaults). */
svet_status image_check_read_size(long long width, long long height,
                                  int channels, size_t elem,
                                  const image_read_limits_t *lim,
                                  size_t *bytes, svet_error *err);

/* Copy src into dst (allocated here; dst must not hold pixels). Fails as
 * image_alloc() does. */
svet_status image_copy(image_t *dst, const image_t *src, svet_error *err);

/* The first value of pixel (x, y); the caller keeps 0 <= x < width and
 * 0 <= y < height. */
static inline float *image_at(const image_t *img, int x, int y)
{
    return img->px + ((size_t)y * (size_t)img->width + (size_t)x) *
                         (size_t)img->channels;
}

/* Pixel (x, y) as a RADIANCE (alpha, if any, is not part of it). */
static inline RADIANCE image_get(const image_t *img, int x, int y)
{
    const float *p = image_at(img, x, y);
    return rad_make((real)p[0], (real)p[1], (real)p[2]);
}

/* Set the colour of pixel (x, y); alpha, if any, is left as it was. */
static inline void image_set(image_t *img, int x, int y, RADIANCE c)
{
    float *p = image_at(img, x, y);
    p[0] = (float)c.r;
    p[1] = (float)c.g;
    p[2] = (float)c.b;
}

/* An encoded value v in [0, 1] as an integer code 0..maxval, rounded to
 * nearest (ties up); values below 0 and NaN give 0, above 1 give maxval.
 * maxval 255 is an 8-bit file, 65535 a 16-bit one, and for them
 * image_quantize((float)k / maxval, maxval) == k for every code k, so an
 * image read from a file is written back to the same codes. */
static inline unsigned image_quantize(float v, unsigned maxval)
{
    double s = (double)v * (double)maxval + 0.5;
    if (!(s >= 1.0)) /* also NaN */
        return 0;
    if (s >= (double)maxval)
        return maxval;
    return (unsigned)s;
}

/* --- accumulation -------------------------------------------------------- */

/* An exact sum: a signed 192-bit integer (two's complement, w[0] the low
 * 64 bits) counting units of 2^-q for a fixed q. Integer addition is
 * associative, so a sum of samples has the same bits in every order and
 * grouping: that is what makes a render split over sample ranges or
 * machines merge to the single render's bits by construction. This is the
 * "exact accumulator over a bounded exponent window" of reproducible
 * summation (Demmel & Nguyen, "Parallel Reproducible Summation", IEEE TC
 * 2015, section II, whose binned sums need the window only where the
 * values are): a renderer knows its window in advance, so one fixed-point
 * integer does it. */
typedef struct {
    uint64_t w[3];
} image_fixed_t;

/* The windows of the accumulation. A sample whose channels are all below
 * IMAGE_SAMPLE_MAX = 2^40 in magnitude is added; its value goes into the
 * sum in units of 2^-IMAGE_SUM_Q (every float of magnitude 2^-72 or more,
 * and every double of 2^-43 or more, exactly; smaller values lose their
 * bits below 2^-96, toward zero), its square into the sum of squares in
 * units of 2^-IMAGE_SUM2_Q. With at most IMAGE_MAX_COUNT = 2^46 samples a
 * pixel, |sum| < 2^(46+40+96) = 2^182 and sum2 < 2^(46+80+64) = 2^190,
 * inside the 191 bits of magnitude. */
#define IMAGE_SUM_Q 96
#define IMAGE_SUM2_Q 64
#define IMAGE_SAMPLE_MAX 0x1p40
#define IMAGE_MAX_COUNT (UINT64_C(1) << 46)

/* s += t, modulo 2^192 (exact while the true sum is in the window). This
 * function can't fail. */
static inline void image_fixed_add(image_fixed_t *s, const image_fixed_t *t)
{
    uint64_t carry = 0;
    for (int k = 0; k < 3; k++) {
        uint64_t a = s->w[k] + t->w[k];
        uint64_t c = a < t->w[k];
        s->w[k] = a + carry;
        carry = c | (s->w[k] < carry);
    }
}

/* s += v 2^q, the product truncated toward zero to an integer. v must be
 * finite with |v| 2^q < 2^180 (the windows above). The value is read off
 * the bits of the double, |v| = m 2^e with an integer m < 2^53, and m is
 * shifted into place. This function can't fail. */
static inline void image_fixed_add_double(image_fixed_t *s, double v, int q)
{
    uint64_t b;
    memcpy(&b, &v, sizeof b);
    int be = (int)((b >> 52) & 0x7ff);
    uint64_t m = b & ((UINT64_C(1) << 52) - 1);
    int sh = (be ? be - 1075 : -1074) + q; /* |v| 2^q = m 2^sh */
    if (be)
        m |= UINT64_C(1) << 52;
    if (sh < 0) {
        m = sh > -64 ? m >> -sh : 0;
        sh = 0;
    }
    image_fixed_t t = { { 0, 0, 0 } };
    t.w[sh / 64] = m << (sh % 64);
    if (sh % 64 && sh / 64 < 2)
        t.w[sh / 64 + 1] = m >> (64 - sh % 64);
    if (b >> 63) { /* negative: two's complement, ~t + 1 */
        for (int k = 0; k < 3; k++)
            t.w[k] = ~t.w[k];
        const image_fixed_t one = { { 1, 0, 0 } };
        image_fixed_add(&t, &one);
    }
    image_fixed_add(s, &t);
}

/* The value of s, s 2^-q, as a double: the limbs are converted and added
 * from the top, so the result is exact whenever the value fits a double
 * and within an ulp otherwise, and always the same bits for the same s.
 * This function can't fail. */
double image_fixed_value(const image_fixed_t *s, int q);

/* The running sums of a render. Each sample adds its radiance to `sum` and
 * 1 to `count`; the image is sum / count (image_accum_resolve). A sample
 * with a NaN or infinite channel, or one of magnitude IMAGE_SAMPLE_MAX or
 * more, is not added: it goes to `nonfinite` only, so one bad path cannot
 * blacken or whiten a pixel for ever, and the count says it happened (a
 * correct renderer keeps it at 0).
 *
 * Exactness of a merge. Floating-point addition is not associative:
 * (a1 + a2) + (b1 + b2) and ((a1 + a2) + b1) + b2 can differ in the last
 * bit once a pixel's samples span more than the 53 bits of a double (a
 * firefly of 1e4 and samples of 1e-5 do). The sums here are exact
 * fixed-point integers (image_fixed_t), so every order and grouping of
 * the same samples gives the same bits: a render split by samples, by
 * pixels or both, merged in any order, equals the single render bit for
 * bit, in the float and in the double build. The rule: a sample's
 * contribution is a function of the sample alone (its bits truncated
 * below 2^-96, its square's below 2^-64), and sums of those are exact.
 * The price is memory: 24 bytes a channel where a double sum took 8.
 * A weighted (filtered) sum would need a weight sum in place of the count;
 * svet's pixels are boxes, one sample one vote. */
typedef struct {
    int width, height;
    image_fixed_t *sum;  /* 3 per pixel: R G B sums of the added samples,
                            units of 2^-IMAGE_SUM_Q */
    uint64_t *count;     /* samples added to each pixel */
    uint64_t *nonfinite; /* samples dropped from each pixel: NaN, Inf or
                            beyond IMAGE_SAMPLE_MAX */
} image_accum_t;

/* Allocate an empty accumulation (all sums and counts zero). acc is zeroed
 * first, so image_accum_free() is always safe on it. Fails as image_alloc()
 * does. */
svet_status image_accum_alloc(image_accum_t *acc, int width, int height,
                              svet_error *err);

/* Release and zero. Safe on a zeroed or freed accumulation and on NULL.
 * This function can't fail. */
void image_accum_free(image_accum_t *acc);

/* Add one sample of radiance L to pixel (x, y), or count it as dropped
 * if a channel is NaN, infinite or IMAGE_SAMPLE_MAX or more in magnitude;
 * true if it was added. The caller keeps (x, y) inside. Not thread-safe
 * for the same pixel: give threads disjoint pixels (rows or tiles), as
 * svet's renderer does. This function can't fail. */
static inline bool image_accum_add(image_accum_t *acc, int x, int y,
                                   RADIANCE L)
{
    size_t i = (size_t)y * (size_t)acc->width + (size_t)x;
    const double v[3] = { (double)L.r, (double)L.g, (double)L.b };
    if (!(fabs(v[0]) < IMAGE_SAMPLE_MAX && fabs(v[1]) < IMAGE_SAMPLE_MAX &&
          fabs(v[2]) < IMAGE_SAMPLE_MAX)) { /* also NaN */
        acc->nonfinite[i]++;
        return false;
    }
    for (int c = 0; c < 3; c++)
        image_fixed_add_double(&acc->sum[3 * i + (size_t)c], v[c],
                               IMAGE_SUM_Q);
    acc->count[i]++;
    return true;
}

/* dst += src: sums, counts and non-finite counts, pixel by pixel. Fails
 * with SVET_ERR_RANGE (and leaves dst unchanged) if the sizes differ. */
svet_status image_accum_merge(image_accum_t *dst, const image_accum_t *src,
                              svet_error *err);

/* The mean image, sum / count per pixel (3 channels), into out (allocated
 * here; out must not hold pixels). A pixel with no finite sample is black:
 * *empty (if not NULL) receives how many there were. Fails as image_alloc()
 * does. */
svet_status image_accum_resolve(const image_accum_t *acc, image_t *out,
                                uint64_t *empty, svet_error *err);

/* Totals over the image: finite samples added, and samples dropped as
 * NaN/Inf. This function can't fail. */
uint64_t image_accum_samples(const image_accum_t *acc);
uint64_t image_accum_nonfinite(const image_accum_t *acc);

#endif
