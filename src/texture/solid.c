/*
 * solid.c - the solid textures of ch. 10 (Perlin 1985; Peachey 1985):
 * checker, noise, fractal sum, turbulence, marble, wood and granite as
 * blend factors with their gradients.
 * Tests: tests/texture/test_solid.c
 */
#include "texture/solid.h"

#include <stddef.h>

solid_texture_t solid_default(solid_kind_t kind, RADIANCE a, RADIANCE b)
{
    solid_texture_t t;
    t.kind = kind;
    t.a = a;
    t.b = b;
    t.scale = 1;
    t.octaves = noise_octaves_default();
    t.amplitude = kind == SOLID_WOOD ? REAL_C(0.3) : 5;
    t.rings = 4;
    return t;
}

static void scale3(VECTOR3 g, real s)
{
    g[X] *= s;
    g[Y] *= s;
    g[Z] *= s;
}

/* f clamped to [0, 1]; the gradient is 0 where the clamp acts */
static real clamp01(real f, VECTOR3 grad)
{
    if (f >= 0 && f <= 1)
        return f;
    if (grad)
        vec_set(grad, 0, 0, 0);
    return f < 0 ? 0 : 1;
}

/* The factor of p already scaled, and its gradient in those units. */
static real factor(const solid_texture_t *t, const VECTOR3 q, VECTOR3 g)
{
    VECTOR3 gn;
    real n;
    switch (t->kind) {
    case SOLID_CHECKER: {
        /* the parity of floor(x) + floor(y) + floor(z), by fmod so that
         * no coordinate overflows an integer; not finite reads as 0 */
        real s = 0;
        for (int k = 0; k < 3; k++)
            s += isfinite(q[k]) ? fmod(fabs(floor(q[k])), REAL_C(2.0)) : 0;
        if (g)
            vec_set(g, 0, 0, 0);
        return fmod(s, REAL_C(2.0));
    }
    case SOLID_NOISE:
        n = noise_perlin_grad(q, g ? gn : NULL);
        if (g)
            vec_set(g, gn[X] / 2, gn[Y] / 2, gn[Z] / 2);
        return (1 + n) / 2;
    case SOLID_FRACTAL:
        n = noise_fractal(q, &t->octaves, g ? gn : NULL);
        if (g)
            vec_set(g, gn[X] / 2, gn[Y] / 2, gn[Z] / 2);
        return clamp01((1 + n) / 2, g);
    case SOLID_TURBULENCE:
        n = noise_turbulence(q, &t->octaves, g);
        return clamp01(n, g);
    case SOLID_MARBLE: {
        /* Perlin 1985, "marble": a sine of x whose phase turbulence
         * bends into veins */
        real tu = noise_turbulence(q, &t->octaves, g ? gn : NULL);
        real phase = q[X] + t->amplitude * tu;
        if (g) {
            real c = cos(phase) / 2;
            vec_set(g, c * (1 + t->amplitude * gn[X]),
                    c * t->amplitude * gn[Y], c * t->amplitude * gn[Z]);
        }
        return (1 + sin(phase)) / 2;
    }
    case SOLID_WOOD: {
        /* concentric rings about the y axis (Peachey 1985's tree trunk),
         * their radius shifted by noise so that no ring is a true circle;
         * f = the fraction of the ring, a sawtooth from 0 to 1 */
        real r = sqrt(q[X] * q[X] + q[Z] * q[Z]);
        n = noise_perlin_grad(q, g ? gn : NULL);
        real rr = t->rings * r + t->amplitude * n;
        real f = rr - floor(rr);
        if (g) {
            real dr = t->rings / (r > 0 ? r : 1);
            vec_set(g, dr * q[X] + t->amplitude * gn[X],
                    t->amplitude * gn[Y], dr * q[Z] + t->amplitude * gn[Z]);
            if (r == 0)
                g[X] = g[Z] = 0;
        }
        return f;
    }
    case SOLID_GRANITE: {
        /* speckles: turbulence at four times the frequency, stretched so
         * that its upper part saturates (Ebert et al., "Texturing and
         * Modeling", ch. 2's granite) */
        VECTOR3 q4 = { 4 * q[X], 4 * q[Y], 4 * q[Z] };
        n = noise_turbulence(q4, &t->octaves, g);
        if (g)
            scale3(g, 4 * 2);
        return clamp01(2 * n, g);
    }
    }
    if (g)
        vec_set(g, 0, 0, 0);
    return 0;
}

real solid_factor(const solid_texture_t *t, const VECTOR3 p, VECTOR3 grad)
{
    VECTOR3 q = { p[X] * t->scale, p[Y] * t->scale, p[Z] * t->scale };
    real f = factor(t, q, grad);
    if (grad)
        scale3(grad, t->scale); /* the chain rule for p -> scale p */
    return f;
}

RADIANCE solid_eval(const solid_texture_t *t, const VECTOR3 p)
{
    real f = solid_factor(t, p, NULL);
    return rad_add(rad_scale(t->a, 1 - f), rad_scale(t->b, f));
}
