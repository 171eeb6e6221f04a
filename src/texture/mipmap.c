/*
 * mipmap.c - the mip map of ch. 10 (Williams 1983): building the pyramid
 * by 2 x 2 box filtering, and nearest, bilinear and trilinear lookups
 * with repeat, clamp and mirror wrapping.
 * Tests: tests/texture/test_mipmap.c
 */
#include "texture/mipmap.h"
#include "texture/interp.h"

#include <stdlib.h>
#include <string.h>

void mipmap_free(mipmap_t *m)
{
    for (int l = 0; l < MIPMAP_MAX_LEVELS; l++) {
        free(m->level[l].px);
        m->level[l].px = NULL;
    }
    m->levels = 0;
}

/* Fold a texel index into 0 .. n - 1 by the wrap mode. */
static int wrap_index(int i, int n, mipmap_wrap_t w)
{
    if (w == MIPMAP_CLAMP)
        return i < 0 ? 0 : i >= n ? n - 1 : i;
    if (w == MIPMAP_REPEAT) {
        int r = i % n;
        return r < 0 ? r + n : r;
    }
    /* mirror: period 2n, the second half reversed */
    long p = 2 * (long)n;
    long r = (long)i % p;
    if (r < 0)
        r += p;
    return (int)(r < n ? r : p - 1 - r);
}

static const float *texel_ptr(const mipmap_t *m, int l, int x, int y)
{
    const mipmap_level_t *lv = &m->level[l];
    x = wrap_index(x, lv->width, m->wrap);
    y = wrap_index(y, lv->height, m->wrap);
    return lv->px + ((size_t)y * (size_t)lv->width + (size_t)x) *
                        (size_t)m->channels;
}

void mipmap_texel(const mipmap_t *m, int level, int x, int y, real *out)
{
    const float *p = texel_ptr(m, level, x, y);
    for (int c = 0; c < m->channels; c++)
        out[c] = (real)p[c];
}

svet_status mipmap_build(mipmap_t *m, const float *px, int width, int height,
                         int channels, mipmap_wrap_t wrap, svet_error *err)
{
    memset(m, 0, sizeof *m);
    if (width < 1 || height < 1 || width > 65536 || height > 65536)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "texture of %d x %d texels: each side must be "
                              "1 to 65536", width, height);
    if (channels < 1 || channels > MIPMAP_MAX_CHANNELS)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "texture of %d channels: 1 to %d", channels,
                              MIPMAP_MAX_CHANNELS);
    m->channels = channels;
    m->wrap = wrap;
    int w = width, h = height;
    for (int l = 0; l < MIPMAP_MAX_LEVELS; l++) {
        size_t n = (size_t)w * (size_t)h * (size_t)channels;
        m->level[l].width = w;
        m->level[l].height = h;
        m->level[l].px = malloc(n * sizeof(float));
        if (!m->level[l].px) {
            mipmap_free(m);
            return svet_error_set(err, SVET_ERR_NOMEM,
                                  "texture of %d x %d texels: out of memory",
                                  width, height);
        }
        m->levels = l + 1;
        if (l == 0)
            memcpy(m->level[0].px, px, n * sizeof(float));
        else
            /* Williams 1983: each texel the mean of the four below it */
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++) {
                    float *o = m->level[l].px +
                               ((size_t)y * (size_t)w + (size_t)x) *
                                   (size_t)channels;
                    const float *a = texel_ptr(m, l - 1, 2 * x, 2 * y);
                    const float *b = texel_ptr(m, l - 1, 2 * x + 1, 2 * y);
                    const float *c = texel_ptr(m, l - 1, 2 * x, 2 * y + 1);
                    const float *d = texel_ptr(m, l - 1, 2 * x + 1, 2 * y + 1);
                    for (int k = 0; k < channels; k++)
                        o[k] = ((a[k] + b[k]) + (c[k] + d[k])) * 0.25f;
                }
        if (w == 1 && h == 1)
            break;
        w = (w + 1) / 2;
        h = (h + 1) / 2;
    }
    return SVET_OK;
}

/* Bilinear on one level: the texel centres stand at (i + 0.5) / width. */
static void bilinear(const mipmap_t *m, int l, real s, real t, real *out)
{
    const mipmap_level_t *lv = &m->level[l];
    real x = s * (real)lv->width - REAL_C(0.5);
    real y = t * (real)lv->height - REAL_C(0.5);
    real fx = floor(x), fy = floor(y);
    int x0 = (int)fx, y0 = (int)fy;
    real tx = x - fx, ty = y - fy;
    const float *a = texel_ptr(m, l, x0, y0), *b = texel_ptr(m, l, x0 + 1, y0);
    const float *c = texel_ptr(m, l, x0, y0 + 1);
    const float *d = texel_ptr(m, l, x0 + 1, y0 + 1);
    for (int k = 0; k < m->channels; k++)
        out[k] = interp_lerp(ty, interp_lerp(tx, (real)a[k], (real)b[k]),
                             interp_lerp(tx, (real)c[k], (real)d[k]));
}

/* A coordinate folded into [-2, 2] for the integer conversions: repeat
 * and mirror are periodic in 2 (fmod is exact), clamp is constant beyond
 * [0, 1]. NaN and infinities read as 0. */
static real tame(real s, mipmap_wrap_t w)
{
    if (w == MIPMAP_CLAMP)
        s = s < -1 ? -1 : s > 2 ? 2 : s;
    else if (fabs(s) > 2)
        s = fmod(s, REAL_C(2.0));
    return s == s ? s : 0;
}

void mipmap_lookup(const mipmap_t *m, mipmap_filter_t filter, real s, real t,
                   real width, real *out)
{
    s = tame(s, m->wrap);
    t = tame(t, m->wrap);
    if (filter == MIPMAP_NEAREST) {
        const mipmap_level_t *lv = &m->level[0];
        mipmap_texel(m, 0, (int)floor(s * (real)lv->width),
                     (int)floor(t * (real)lv->height), out);
        return;
    }
    if (filter == MIPMAP_BILINEAR || m->levels == 1) {
        bilinear(m, 0, s, t, out);
        return;
    }
    /* the level whose texel is as wide as the footprint (Williams 1983) */
    int side = m->level[0].width > m->level[0].height ? m->level[0].width
                                                       : m->level[0].height;
    real texels = width * (real)side;
    real lambda = texels > 1 ? log2(texels) : 0; /* NaN width: level 0 */
    real top = (real)(m->levels - 1);
    if (!(lambda < top)) {
        bilinear(m, m->levels - 1, s, t, out);
        return;
    }
    int l0 = (int)floor(lambda);
    real f = lambda - (real)l0;
    real lo[MIPMAP_MAX_CHANNELS], hi[MIPMAP_MAX_CHANNELS];
    bilinear(m, l0, s, t, lo);
    bilinear(m, l0 + 1, s, t, hi);
    for (int k = 0; k < m->channels; k++)
        out[k] = interp_lerp(f, lo[k], hi[k]); /* app. L, between levels */
}
