/*
 * noise.c - Perlin's improved noise (ch. 10; Perlin 2002) with its
 * gradient, and fractal sums of it (Perlin 1985).
 * Tests: tests/texture/test_noise.c; vectors: tests/vectors/noise_perlin.csv
 */
#include "texture/noise.h"

#include <stddef.h>

/* Perlin's permutation of 0..255 (Perlin 2002, the reference's p[]),
 * written twice so that p[i + 1] needs no wrap for i up to 510. */
#define NOISE_PERMUTATION                                                   \
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225,  \
    140, 36, 103, 30, 69, 142, 8, 99, 37, 240, 21, 10, 23, 190, 6, 148,     \
    247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219, 203, 117, 35, 11, 32,  \
    57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68,     \
    175, 74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83, 111,    \
    229, 122, 60, 211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244,    \
    102, 143, 54, 65, 25, 63, 161, 1, 216, 80, 73, 209, 76, 132, 187, 208,  \
    89, 18, 169, 200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198, \
    173, 186, 3, 64, 52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118,     \
    126, 255, 82, 85, 212, 207, 206, 59, 227, 47, 16, 58, 17, 182, 189, 28, \
    42, 223, 183, 170, 213, 119, 248, 152, 2, 44, 154, 163, 70, 221, 153,   \
    101, 155, 167, 43, 172, 9, 129, 22, 39, 253, 19, 98, 108, 110, 79, 113, \
    224, 232, 178, 185, 112, 104, 218, 246, 97, 228, 251, 34, 242, 193,     \
    238, 210, 144, 12, 191, 179, 162, 241, 81, 51, 145, 235, 249, 14, 239,  \
    107, 49, 192, 214, 31, 181, 199, 106, 157, 184, 84, 204, 176, 115, 121, \
    50, 45, 127, 4, 150, 254, 138, 236, 205, 93, 222, 114, 67, 29, 24, 72,  \
    243, 141, 128, 195, 78, 66, 215, 61, 156, 180

static const unsigned char perm[512] = { NOISE_PERMUTATION,
                                         NOISE_PERMUTATION };

/* Perlin 2002: the fade curve 6t^5 - 15t^4 + 10t^3, whose first and second
 * derivatives vanish at 0 and 1, so noise is C2 across cell faces (the
 * 1985 curve 3t^2 - 2t^3 left the second derivative discontinuous). */
static real fade(real t) { return t * t * t * (t * (t * 6 - 15) + 10); }
static real fade_deriv(real t) { return 30 * t * t * (t * (t - 2) + 1); }

static real lerp(real t, real a, real b) { return a + t * (b - a); }

/* The gradient picked by the low four bits of a hash: the twelve vectors
 * from the centre of a cube to its edges' midpoints, (1,1,0) ... (0,-1,-1),
 * and four of them again to make sixteen (Perlin 2002, sec. 3): the
 * components u (grad_u, sign grad_su) and v (grad_v, grad_sv) are +-1,
 * the third 0. The reference picks them by branches, which a random hash
 * makes unpredictable; tables pick the same ones without a branch. */
static const unsigned char grad_u[16] = { 0, 0, 0, 0, 0, 0, 0, 0,
                                          1, 1, 1, 1, 1, 1, 1, 1 };
static const unsigned char grad_v[16] = { 1, 1, 1, 1, 2, 2, 2, 2,
                                          2, 2, 2, 2, 0, 2, 0, 2 };
static const real grad_su[16] = { 1, -1, 1, -1, 1, -1, 1, -1,
                                  1, -1, 1, -1, 1, -1, 1, -1 };
static const real grad_sv[16] = { 1, 1, -1, -1, 1, 1, -1, -1,
                                  1, 1, -1, -1, 1, 1, -1, -1 };

/* The dot product of that gradient with (x, y, z), in the reference's
 * order of operations, (+-u) + (+-v), so that the value matches it to the
 * last bit (u * -1 is -u exactly). */
static real grad(int hash, real x, real y, real z)
{
    int h = hash & 15;
    const real p[3] = { x, y, z };
    return p[grad_u[h]] * grad_su[h] + p[grad_v[h]] * grad_sv[h];
}

/* That gradient as a vector. */
static void gradient(int hash, VECTOR3 g)
{
    int h = hash & 15;
    vec_set(g, 0, 0, 0);
    g[grad_u[h]] = grad_su[h];
    g[grad_v[h]] = grad_sv[h];
}

/* The lattice cell of one coordinate, modulo 256, and the fraction in it.
 * fmod keeps the cell exact where (int) of a large value would overflow;
 * in Java's int range it equals the reference's (int)floor(x) & 255. */
static int cell(real x, real *frac)
{
    real f = floor(x);
    /* in [0, 1]; exact but where a tiny negative x rounds it up to 1,
     * which the fade curve takes to the next cell's value, continuously */
    *frac = x - f;
    return (int)fmod(f, REAL_C(256.0)) & 255;
}

/* The eight corner hashes of the cell (ix, iy, iz), in the order
 * 000, 100, 010, 110, 001, 101, 011, 111 (x fastest). */
static void corner_hashes(int ix, int iy, int iz, int h[8])
{
    int a = perm[ix] + iy, aa = perm[a] + iz, ab = perm[a + 1] + iz;
    int b = perm[ix + 1] + iy, ba = perm[b] + iz, bb = perm[b + 1] + iz;
    h[0] = perm[aa];
    h[1] = perm[ba];
    h[2] = perm[ab];
    h[3] = perm[bb];
    h[4] = perm[aa + 1];
    h[5] = perm[ba + 1];
    h[6] = perm[ab + 1];
    h[7] = perm[bb + 1];
}

real noise_perlin_grad(const VECTOR3 p, VECTOR3 g)
{
    if (!(isfinite(p[X]) && isfinite(p[Y]) && isfinite(p[Z]))) {
        if (g)
            vec_set(g, 0, 0, 0);
        return 0;
    }
    real x, y, z;
    int ix = cell(p[X], &x), iy = cell(p[Y], &y), iz = cell(p[Z], &z);
    int h[8];
    corner_hashes(ix, iy, iz, h);

    /* the dot products at the corners, the corner at (i, j, k) seeing
     * the point at (x - i, y - j, z - k) */
    real d[8];
    for (int c = 0; c < 8; c++)
        d[c] = grad(h[c], (c & 1) ? x - 1 : x, (c & 2) ? y - 1 : y,
                    (c & 4) ? z - 1 : z);

    /* Perlin 2002: blend along x, then y, then z, with the fade curve */
    real u = fade(x), v = fade(y), w = fade(z);
    real x00 = lerp(u, d[0], d[1]), x10 = lerp(u, d[2], d[3]);
    real x01 = lerp(u, d[4], d[5]), x11 = lerp(u, d[6], d[7]);
    real y0 = lerp(v, x00, x10), y1 = lerp(v, x01, x11);
    real n = lerp(w, y0, y1);
    if (!g)
        return n;

    /* d n / dp: the derivative of each lerp(t, a, b) is
     * lerp(t, a', b') + t' (b - a), with t' the fade curve's derivative
     * along its own axis, and a corner's d' its constant gradient G_c */
    VECTOR3 gc[8], gx[4], gy[2];
    for (int c = 0; c < 8; c++)
        gradient(h[c], gc[c]);
    real du = fade_deriv(x), dv = fade_deriv(y), dw = fade_deriv(z);
    const real xs[4] = { x00, x10, x01, x11 };
    for (int r = 0; r < 4; r++) {
        for (int k = 0; k < 3; k++)
            gx[r][k] = lerp(u, gc[2 * r][k], gc[2 * r + 1][k]);
        gx[r][X] += du * (d[2 * r + 1] - d[2 * r]);
    }
    for (int r = 0; r < 2; r++) {
        for (int k = 0; k < 3; k++)
            gy[r][k] = lerp(v, gx[2 * r][k], gx[2 * r + 1][k]);
        gy[r][Y] += dv * (xs[2 * r + 1] - xs[2 * r]);
    }
    for (int k = 0; k < 3; k++)
        g[k] = lerp(w, gy[0][k], gy[1][k]);
    g[Z] += dw * (y1 - y0);
    return n;
}

real noise_perlin(const VECTOR3 p) { return noise_perlin_grad(p, NULL); }

noise_octaves_t noise_octaves_default(void)
{
    noise_octaves_t o = { 6, 2, REAL_C(0.5) };
    return o;
}

/* The sum over octaves of gain^i f(noise(lacunarity^i p)), f the identity
 * or the absolute value, with the chain rule for the gradient. */
static real octave_sum(const VECTOR3 p, const noise_octaves_t *o,
                       VECTOR3 grad, bool absolute)
{
    int octaves = o->octaves < 1 ? 1
                : o->octaves > NOISE_MAX_OCTAVES ? NOISE_MAX_OCTAVES
                                                 : o->octaves;
    real sum = 0, amp = 1, freq = 1;
    if (grad)
        vec_set(grad, 0, 0, 0);
    for (int i = 0; i < octaves; i++) {
        VECTOR3 q = { p[X] * freq, p[Y] * freq, p[Z] * freq }, gi;
        real n = noise_perlin_grad(q, grad ? gi : NULL);
        real s = (absolute && n < 0) ? -amp : amp;
        sum += s * n;
        if (grad)
            for (int k = 0; k < 3; k++)
                grad[k] += s * freq * gi[k];
        amp *= o->gain;
        freq *= o->lacunarity;
    }
    return sum;
}

real noise_fractal(const VECTOR3 p, const noise_octaves_t *o, VECTOR3 grad)
{
    return octave_sum(p, o, grad, false);
}

real noise_turbulence(const VECTOR3 p, const noise_octaves_t *o,
                      VECTOR3 grad)
{
    return octave_sum(p, o, grad, true);
}
