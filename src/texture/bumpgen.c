/*
 * bumpgen.c - app. G: the generated bump textures (waves, ripples,
 * bricks, orange peel, dents) as heights with exact partial derivatives.
 * Tests: tests/texture/test_bumpgen.c
 */
#include "texture/bumpgen.h"
#include "texture/noise.h"

#include <stdlib.h>

bumpgen_t bumpgen_default(bumpgen_kind_t kind)
{
    bumpgen_t b = { kind, 8, 0, REAL_C(0.5), REAL_C(0.5), 2, REAL_C(0.25),
                    REAL_C(0.1), REAL_C(0.01) };
    return b;
}

/* 3t^2 - 2t^3 of (x - a) / (b - a) clamped to [0, 1], and its derivative
 * in x: a smooth step from 0 at a to 1 at b. */
static real smoothstep(real a, real b, real x, real *d)
{
    real t = (x - a) / (b - a);
    if (t <= 0 || t >= 1) {
        *d = 0;
        return t <= 0 ? 0 : 1;
    }
    *d = 6 * t * (1 - t) / (b - a);
    return t * t * (3 - 2 * t);
}

/* Distance from x to the nearer end of [0, w], and its derivative. */
static real edge_distance(real x, real w, real *d)
{
    if (x < w - x) {
        *d = 1;
        return x;
    }
    *d = -1;
    return w - x;
}

static real bricks(const bumpgen_t *b, real u, real v, real *hu, real *hv)
{
    /* the row, and every other row shifted by half a brick (running bond) */
    real row = floor(v / b->brick_h);
    real y = v - row * b->brick_h;
    real shift = fmod(fabs(row), REAL_C(2.0)) * REAL_C(0.5) * b->brick_w;
    real xs = u + shift;
    real x = xs - floor(xs / b->brick_w) * b->brick_w;
    /* sunken in the mortar (within m/2 of a joint's centre line), a
     * smooth bevel up to the brick's face over the next m/2 */
    real dxd, dyd, sx, sy;
    real dx = edge_distance(x, b->brick_w, &dxd);
    real dy = edge_distance(y, b->brick_h, &dyd);
    real half = b->mortar * REAL_C(0.5);
    real fx = smoothstep(half, b->mortar, dx, &sx);
    real fy = smoothstep(half, b->mortar, dy, &sy);
    *hu = sx * dxd * fy;
    *hv = fx * sy * dyd;
    return fx * fy;
}

real bumpgen_height(const bumpgen_t *b, real u, real v, real *du, real *dv)
{
    real hu = 0, hv = 0, h = 0;
    const real two_pi = 2 * REAL_PI;
    switch (b->kind) {
    case BUMPGEN_WAVES: {
        real cu = cos(b->angle), cv = sin(b->angle);
        real ph = two_pi * b->frequency * (u * cu + v * cv);
        h = (1 + sin(ph)) / 2;
        real d = cos(ph) / 2 * two_pi * b->frequency;
        hu = d * cu;
        hv = d * cv;
        break;
    }
    case BUMPGEN_RIPPLES: {
        real x = u - b->cu, y = v - b->cv, r = sqrt(x * x + y * y);
        real ph = two_pi * b->frequency * r, e = exp(-b->damping * r);
        h = e * (1 + cos(ph)) / 2;
        /* dh/dr, then along (x, y) / r; at the centre the gradient is 0 */
        real dr = e * (-b->damping * (1 + cos(ph)) / 2 -
                       sin(ph) / 2 * two_pi * b->frequency);
        if (r > 0) {
            hu = dr * x / r;
            hv = dr * y / r;
        }
        break;
    }
    case BUMPGEN_BRICKS:
        h = bricks(b, u, v, &hu, &hv);
        break;
    case BUMPGEN_ORANGE_PEEL: {
        noise_octaves_t o = { 2, 2, REAL_C(0.5) };
        VECTOR3 p = { b->frequency * u, b->frequency * v, REAL_C(0.5) }, g;
        real n = noise_fractal(p, &o, g);
        h = (1 + n) / 2;
        hu = g[X] / 2 * b->frequency;
        hv = g[Y] / 2 * b->frequency;
        if (h < 0 || h > 1) {
            h = h < 0 ? 0 : 1;
            hu = hv = 0;
        }
        break;
    }
    case BUMPGEN_DENTS: {
        /* a pit where the noise falls below -0.25, its rim smooth */
        VECTOR3 p = { b->frequency * u, b->frequency * v, REAL_C(0.5) }, g;
        real n = noise_perlin_grad(p, g), d;
        h = smoothstep(REAL_C(-0.45), REAL_C(-0.25), n, &d);
        hu = d * g[X] * b->frequency;
        hv = d * g[Y] * b->frequency;
        break;
    }
    }
    if (du)
        *du = hu;
    if (dv)
        *dv = hv;
    return h;
}

svet_status bumpgen_image(const bumpgen_t *b, int width, int height,
                          float **out, svet_error *err)
{
    *out = NULL;
    if (width < 1 || height < 1 || width > 65536 || height > 65536)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "bump image of %d x %d: each side must be 1 "
                              "to 65536", width, height);
    float *px = malloc(sizeof *px * (size_t)width * (size_t)height);
    if (!px)
        return svet_error_set(err, SVET_ERR_NOMEM,
                              "bump image of %d x %d: out of memory", width,
                              height);
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++)
            px[(size_t)y * (size_t)width + (size_t)x] = (float)bumpgen_height(
                b, ((real)x + REAL_C(0.5)) / (real)width,
                ((real)y + REAL_C(0.5)) / (real)height, NULL, NULL);
    *out = px;
    return SVET_OK;
}
