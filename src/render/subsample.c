/*
 * subsample.c - app. F: adaptive subsampling of an image by splitting
 * blocks whose corners disagree (Mitchell 1987's contrast), bilinear
 * interpolation of the rest (Whitted 1980's adaptive supersampling, on
 * whole pixels), level by level so that the pixels of one level can be
 * computed in parallel and the image does not depend on the thread count.
 * Tests: tests/render/test_subsample.c
 */
#include "render/subsample.h"

#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

/* A block: corners (x0, y0) and (x1, y1), both inclusive. */
typedef struct {
    int x0, y0, x1, y1;
} blk_t;

/* A growing list of blocks, or of pixel indices. */
typedef struct {
    blk_t *b;
    long n, cap;
} blist_t;

typedef struct {
    long *i;
    long n, cap;
} plist_t;

static bool blist_push(blist_t *l, blk_t b)
{
    if (l->n == l->cap) {
        long cap = l->cap ? 2 * l->cap : 64;
        blk_t *p = realloc(l->b, (size_t)cap * sizeof *p);
        if (!p)
            return false;
        l->b = p;
        l->cap = cap;
    }
    l->b[l->n++] = b;
    return true;
}

static bool plist_push(plist_t *l, long i)
{
    if (l->n == l->cap) {
        long cap = l->cap ? 2 * l->cap : 64;
        long *p = realloc(l->i, (size_t)cap * sizeof *p);
        if (!p)
            return false;
        l->i = p;
        l->cap = cap;
    }
    l->i[l->n++] = i;
    return true;
}

typedef struct {
    image_t *img;
    uint8_t *state;  /* 0: not asked for, 1: listed, 2: computed */
    plist_t want;    /* the pixels this level computes, in listed order */
} state_t;

/* List pixel (x, y) for computing, once. */
static bool ask(state_t *s, int x, int y)
{
    long i = (long)y * s->img->width + x;
    if (s->state[i])
        return true;
    s->state[i] = 1;
    return plist_push(&s->want, i);
}

static bool ask_corners(state_t *s, const blk_t *b)
{
    return ask(s, b->x0, b->y0) && ask(s, b->x1, b->y0) &&
           ask(s, b->x0, b->y1) && ask(s, b->x1, b->y1);
}

/* Compute the listed pixels, in parallel; false when stopped. */
static bool compute(state_t *s, subsample_pixel_fn f, void *ctx, int threads,
                    const volatile sig_atomic_t *stop)
{
    const int w = s->img->width;
    const long n = s->want.n;
    const long *want = s->want.i;
    uint8_t *state = s->state;
    image_t *img = s->img;
    long skipped = 0;
#ifdef _OPENMP
    int nt = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 4) num_threads(nt) \
    reduction(+ : skipped)
#else
    (void)threads;
#endif
    for (long k = 0; k < n; k++) {
        if (stop && *stop) {
            skipped++; /* an OpenMP loop cannot break: pass over the rest */
            continue;
        }
        long i = want[k];
        int x = (int)(i % w), y = (int)(i / w);
        f(ctx, x, y, image_at(img, x, y));
        state[i] = 2;
    }
    s->want.n = 0;
    return skipped == 0;
}

/* Mitchell 1987's contrast of two values, per channel, the largest */
static real contrast(const float *a, const float *b)
{
    real worst = 0;
    for (int c = 0; c < 3; c++) {
        real x = (real)a[c], y = (real)b[c], sum = fabs(x) + fabs(y);
        real d = sum > 0 ? fabs(x - y) / sum : 0;
        if (!(d <= 1)) /* NaN or infinite: the block is refined */
            d = 1;
        worst = d > worst ? d : worst;
    }
    return worst;
}

/* a + t (b - a): exactly a where b = a, so a constant block stays
 * constant to the bit */
static real lerp(real a, real b, real t)
{
    return a + t * (b - a);
}

/* The pixels of block b that were not computed, from its corners. */
static void interpolate(image_t *img, const uint8_t *state, const blk_t *b)
{
    const float *c[4] = { image_at(img, b->x0, b->y0),
                          image_at(img, b->x1, b->y0),
                          image_at(img, b->x0, b->y1),
                          image_at(img, b->x1, b->y1) };
    real w = (real)(b->x1 - b->x0), h = (real)(b->y1 - b->y0);
    for (int y = b->y0; y <= b->y1; y++)
        for (int x = b->x0; x <= b->x1; x++) {
            size_t i = (size_t)y * (size_t)img->width + (size_t)x;
            if (state[i] == 2)
                continue;
            real tx = w > 0 ? (real)(x - b->x0) / w : 0;
            real ty = h > 0 ? (real)(y - b->y0) / h : 0;
            float *px = image_at(img, x, y);
            for (int k = 0; k < 3; k++) {
                real top = lerp((real)c[0][k], (real)c[1][k], tx);
                real bot = lerp((real)c[2][k], (real)c[3][k], tx);
                px[k] = (float)lerp(top, bot, ty);
            }
        }
}

svet_status subsample_image_threads(image_t *img,
                                    const subsample_params_t *p,
                                    subsample_pixel_fn f, void *ctx,
                                    uint8_t *computed, long *n_computed,
                                    int threads,
                                    const volatile sig_atomic_t *stop,
                                    bool *stopped, svet_error *err)
{
    if (stopped)
        *stopped = false;
    if (p->step < 1 || p->step > SUBSAMPLE_MAX_STEP ||
        (p->step & (p->step - 1)) != 0)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "subsampling step %d: a power of 2 in "
                              "[1, %d]", p->step, SUBSAMPLE_MAX_STEP);
    if (!(p->threshold >= 0 && p->threshold < 1))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "subsampling threshold %g: in [0, 1)",
                              (double)p->threshold);
    const int W = img->width, H = img->height, k = p->step;
    size_t n = (size_t)W * (size_t)H;
    state_t s = { img, calloc(n, 1), { NULL, 0, 0 } };
    blist_t cur = { NULL, 0, 0 }, next = { NULL, 0, 0 },
            leaves = { NULL, 0, 0 };
    bool ok = s.state != NULL, live = true;
    /* the coarse blocks: every k-th pixel of every k-th row, the last
     * row and column cut short at the image's edge */
    for (int y0 = 0; ok && (y0 < H - 1 || y0 == 0); y0 += k) {
        int y1 = y0 + k < H ? y0 + k : H - 1;
        for (int x0 = 0; ok && (x0 < W - 1 || x0 == 0); x0 += k) {
            blk_t b = { x0, y0, x0 + k < W ? x0 + k : W - 1, y1 };
            ok = blist_push(&cur, b) && ask_corners(&s, &b);
            if (W == 1)
                break;
        }
        if (H == 1)
            break;
    }
    while (ok && live && cur.n > 0) {
        live = compute(&s, f, ctx, threads, stop);
        if (!live)
            break;
        next.n = 0;
        for (long i = 0; ok && i < cur.n; i++) {
            blk_t b = cur.b[i];
            if (b.x1 - b.x0 <= 1 && b.y1 - b.y0 <= 1)
                continue; /* every pixel of it is a corner */
            const float *c[4] = { image_at(img, b.x0, b.y0),
                                  image_at(img, b.x1, b.y0),
                                  image_at(img, b.x0, b.y1),
                                  image_at(img, b.x1, b.y1) };
            real worst = 0;
            for (int a = 0; a < 4; a++)
                for (int e = a + 1; e < 4; e++) {
                    real d = contrast(c[a], c[e]);
                    worst = d > worst ? d : worst;
                }
            if (!(worst > p->threshold || (p->threshold == 0 && worst > 0))) {
                ok = blist_push(&leaves, b);
                continue;
            }
            /* split into four (two where one side is a single step) */
            int xm = b.x0 + (b.x1 - b.x0 + 1) / 2,
                ym = b.y0 + (b.y1 - b.y0 + 1) / 2;
            if (b.x1 - b.x0 <= 1)
                xm = b.x1;
            if (b.y1 - b.y0 <= 1)
                ym = b.y1;
            blk_t q[4] = { { b.x0, b.y0, xm, ym }, { xm, b.y0, b.x1, ym },
                           { b.x0, ym, xm, b.y1 }, { xm, ym, b.x1, b.y1 } };
            for (int j = 0; ok && j < 4; j++) {
                if ((j & 1) && !(xm < b.x1))
                    continue;
                if ((j & 2) && !(ym < b.y1))
                    continue;
                ok = blist_push(&next, q[j]) && ask_corners(&s, &q[j]);
            }
        }
        blist_t t = cur;
        cur = next;
        next = t;
    }
    long count = 0;
    if (ok && live) {
        for (long i = 0; i < leaves.n; i++)
            interpolate(img, s.state, &leaves.b[i]);
        for (size_t i = 0; i < n; i++) {
            count += s.state[i] == 2;
            if (computed)
                computed[i] = s.state[i] == 2;
        }
    }
    free(s.state);
    free(s.want.i);
    free(cur.b);
    free(next.b);
    free(leaves.b);
    if (!ok)
        return svet_error_set(err, SVET_ERR_NOMEM,
                              "subsampling: out of memory");
    if (!live && stopped)
        *stopped = true;
    if (n_computed)
        *n_computed = count;
    return SVET_OK;
}

svet_status subsample_image(image_t *img, const subsample_params_t *p,
                            subsample_pixel_fn f, void *ctx,
                            uint8_t *computed, long *n_computed,
                            svet_error *err)
{
    return subsample_image_threads(img, p, f, ctx, computed, n_computed, 1,
                                   NULL, NULL, err);
}

const subsample_ops_t subsample_ops = { subsample_image_threads };
