/*
 * subsample.c - app. F: adaptive subsampling of an image by recursive
 * splitting of blocks whose corners disagree, bilinear interpolation of
 * the rest.
 * Tests: tests/irradiance/test_subsample.c
 */
#include "irradiance/subsample.h"

#include <stdlib.h>
#include <string.h>

typedef struct {
    image_t *img;
    uint8_t *done;     /* 1 where computed */
    uint8_t *mask;     /* the caller's, or NULL */
    subsample_pixel_fn f;
    void *ctx;
    real threshold;
    long n;
} state_t;

/* pixel (x, y) computed once, on demand */
static const float *get(state_t *s, int x, int y)
{
    size_t i = (size_t)y * (size_t)s->img->width + (size_t)x;
    float *px = image_at(s->img, x, y);
    if (!s->done[i]) {
        s->f(s->ctx, x, y, px);
        s->done[i] = 1;
        s->n++;
        if (s->mask)
            s->mask[i] = 1;
    }
    return px;
}

/* Mitchell 1987's contrast of two values, per channel, the largest */
static real contrast(const float *a, const float *b)
{
    real worst = 0;
    for (int c = 0; c < 3; c++) {
        real x = (real)a[c], y = (real)b[c], sum = fabs(x) + fabs(y);
        real d = sum > 0 ? fabs(x - y) / sum : 0;
        if (!(d <= 1)) /* NaN: the block is refined */
            d = 1;
        worst = d > worst ? d : worst;
    }
    return worst;
}

/* The block with corners (x0, y0) and (x1, y1), both inclusive; x1 - x0
 * and y1 - y0 are powers of 2 (or the image's edge cut them short). */
static void block(state_t *s, int x0, int y0, int x1, int y1)
{
    if (x1 - x0 <= 1 && y1 - y0 <= 1) {
        get(s, x0, y0);
        get(s, x1, y0);
        get(s, x0, y1);
        get(s, x1, y1);
        return;
    }
    const float *c[4] = { get(s, x0, y0), get(s, x1, y0), get(s, x0, y1),
                          get(s, x1, y1) };
    real worst = 0;
    for (int i = 0; i < 4; i++)
        for (int j = i + 1; j < 4; j++) {
            real d = contrast(c[i], c[j]);
            worst = d > worst ? d : worst;
        }
    if (worst > s->threshold || (s->threshold == 0 && worst > 0)) {
        /* split into four, each refined in turn */
        int xm = x0 + (x1 - x0 + 1) / 2, ym = y0 + (y1 - y0 + 1) / 2;
        if (x1 - x0 <= 1)
            xm = x1;
        if (y1 - y0 <= 1)
            ym = y1;
        block(s, x0, y0, xm, ym);
        if (xm < x1)
            block(s, xm, y0, x1, ym);
        if (ym < y1)
            block(s, x0, ym, xm, y1);
        if (xm < x1 && ym < y1)
            block(s, xm, ym, x1, y1);
        return;
    }
    /* the corners agree: the pixels between them are interpolated */
    real w = (real)(x1 - x0), h = (real)(y1 - y0);
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            size_t i = (size_t)y * (size_t)s->img->width + (size_t)x;
            if (s->done[i])
                continue;
            real tx = w > 0 ? (real)(x - x0) / w : 0;
            real ty = h > 0 ? (real)(y - y0) / h : 0;
            float *px = image_at(s->img, x, y);
            for (int k = 0; k < 3; k++) {
                real top = (1 - tx) * (real)c[0][k] + tx * (real)c[1][k];
                real bot = (1 - tx) * (real)c[2][k] + tx * (real)c[3][k];
                px[k] = (float)((1 - ty) * top + ty * bot);
            }
        }
}

svet_status subsample_image(image_t *img, const subsample_params_t *p,
                            subsample_pixel_fn f, void *ctx,
                            uint8_t *computed, long *n_computed,
                            svet_error *err)
{
    if (p->step < 1 || (p->step & (p->step - 1)) != 0)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "subsampling step %d: a power of 2, 1 or more",
                              p->step);
    if (!(p->threshold >= 0 && p->threshold < 1))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "subsampling threshold %g: in [0, 1)",
                              (double)p->threshold);
    size_t n = (size_t)img->width * (size_t)img->height;
    uint8_t *done = calloc(n, 1);
    if (!done)
        return svet_error_set(err, SVET_ERR_NOMEM,
                              "subsampling: out of memory");
    if (computed)
        memset(computed, 0, n);
    state_t s = { img, done, computed, f, ctx, p->threshold, 0 };
    int k = p->step;
    for (int y0 = 0; y0 < img->height - 1 || y0 == 0; y0 += k) {
        int y1 = y0 + k < img->height ? y0 + k : img->height - 1;
        for (int x0 = 0; x0 < img->width - 1 || x0 == 0; x0 += k) {
            int x1 = x0 + k < img->width ? x0 + k : img->width - 1;
            block(&s, x0, y0, x1, y1);
            if (img->width == 1)
                break;
        }
        if (img->height == 1)
            break;
    }
    free(done);
    if (n_computed)
        *n_computed = s.n;
    return SVET_OK;
}
