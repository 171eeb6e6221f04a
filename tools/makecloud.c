/*
 * makecloud.c - writes the density grid of scenes/cloud.scn (ch. 11's
 * gridded medium) as a Mitsuba .vol file (medium/volgrid.h): a puffy
 * ellipsoid whose edge is broken up by a fractal sum of Perlin noise
 * (texture/noise.h, ch. 10). The grid depends on nothing but the numbers
 * below, so the file is the same on every run of the same build; the
 * committed scenes/cloud.vol is the float build's (`make cloud-vol`).
 * usage: makecloud OUT.vol [N]   (N cells per axis, default 32)
 * Tests: tests/render/test_tracer.c and make bitcheck render
 * scenes/cloud.scn, which reads the committed file.
 */
#include <stdio.h>
#include <stdlib.h>

#include "medium/volgrid.h"
#include "texture/noise.h"

/* The density at p in the grid's box [-1, 1]^3: 1 deep inside an
 * ellipsoid of semi-axes 0.9, 0.6, 0.75, falling to 0 over its edge, the
 * edge pushed in and out by four octaves of noise; clamped to [0, 1]. */
static float density(const VECTOR3 p)
{
    const real ax[3] = { REAL_C(0.9), REAL_C(0.6), REAL_C(0.75) };
    real r2 = 0;
    for (int k = 0; k < 3; k++)
        r2 += (p[k] / ax[k]) * (p[k] / ax[k]);
    noise_octaves_t o = { 4, 2, REAL_C(0.5) };
    VECTOR3 q = { REAL_C(2.5) * p[X] + REAL_C(11.3),
                  REAL_C(2.5) * p[Y] + REAL_C(4.1),
                  REAL_C(2.5) * p[Z] + REAL_C(7.7) };
    real d = 3 * (1 - r2) + 2 * noise_fractal(q, &o, NULL);
    return d <= 0 ? 0.0f : d >= 1 ? 1.0f : (float)d;
}

int main(int argc, char **argv)
{
    if (argc < 2 || argc > 3) {
        fprintf(stderr, "usage: makecloud OUT.vol [N]\n");
        return 2;
    }
    int n = argc == 3 ? atoi(argv[2]) : 32;
    if (n < 2 || n > 512) {
        fprintf(stderr, "makecloud: N must be 2..512\n");
        return 2;
    }
    const float lo[3] = { -1, -1, -1 }, hi[3] = { 1, 1, 1 };
    volgrid_t g;
    svet_error e;
    if (volgrid_alloc(&g, n, n, n, 1, lo, hi, VOLGRID_DEFAULT_MAX_VALUES,
                      &e)) {
        fprintf(stderr, "makecloud: %s\n", e.msg);
        return 1;
    }
    float mx = 0;
    for (int z = 0; z < n; z++)
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++) {
                /* the value of a cell stands at its centre (volgrid.h) */
                VECTOR3 p = { -1 + (2 * x + REAL_C(1.0)) / n,
                              -1 + (2 * y + REAL_C(1.0)) / n,
                              -1 + (2 * z + REAL_C(1.0)) / n };
                float v = density(p);
                g.plane[0][((size_t)z * (size_t)n + (size_t)y) * (size_t)n +
                           (size_t)x] = v;
                mx = v > mx ? v : mx;
            }
    g.max[0] = mx;
    svet_status st = volgrid_write(&g, argv[1], &e);
    volgrid_free(&g);
    if (st) {
        fprintf(stderr, "makecloud: %s\n", e.msg);
        return 1;
    }
    return 0;
}
