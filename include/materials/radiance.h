/*
 * radiance.h - RADIANCE, the quantity a path carries. Chapter 1 makes it a
 * single float ("typedef float RADIANCE;"), which can only give a grey
 * image; chapter 2 gives it colour, and svet uses that form throughout:
 * linear RGB with Rec. 709 (sRGB) primaries, in W/(m^2 sr) per channel.
 * Header only. Tests: tests/materials/test_radiance.c
 */
#ifndef SVET_RADIANCE_H
#define SVET_RADIANCE_H

#include <stdbool.h>
#include "core/real.h"

/* Radiance, eq. (1.1): L(x, Psi) = dPhi / (ds cos(theta) domega), the flux
 * through a small area ds around x into a small cone domega around Psi,
 * per unit of the area seen from Psi (ds cos theta). It stays constant
 * along a ray in empty space, which is why a path can carry it from point
 * to point. */
typedef struct {
    real r, g, b; /* linear Rec. 709 RGB */
} RADIANCE;

static inline RADIANCE rad_make(real r, real g, real b)
{
    RADIANCE c = { r, g, b };
    return c;
}

/* The grey radiance of chapter 1: the same value in every channel. */
static inline RADIANCE rad_grey(real v)
{
    return rad_make(v, v, v);
}

static inline RADIANCE rad_add(RADIANCE a, RADIANCE b)
{
    return rad_make(a.r + b.r, a.g + b.g, a.b + b.b);
}

static inline RADIANCE rad_mul(RADIANCE a, RADIANCE b)
{
    return rad_make(a.r * b.r, a.g * b.g, a.b * b.b);
}

static inline RADIANCE rad_scale(RADIANCE a, real s)
{
    return rad_make(a.r * s, a.g * s, a.b * s);
}

static inline bool rad_is_black(RADIANCE a)
{
    return a.r == 0 && a.g == 0 && a.b == 0;
}

static inline real rad_max(RADIANCE a)
{
    return real_max(a.r, real_max(a.g, a.b));
}

static inline real rad_average(RADIANCE a)
{
    return (a.r + a.g + a.b) / 3;
}

/* Luminance Y of linear Rec. 709 RGB (IEC 61966-2-1, the middle row of the
 * RGB-to-XYZ matrix), in the units of the radiance. */
static inline real rad_luminance(RADIANCE a)
{
    return REAL_C(0.2126) * a.r + REAL_C(0.7152) * a.g + REAL_C(0.0722) * a.b;
}

static inline bool rad_is_finite(RADIANCE a)
{
    return isfinite(a.r) && isfinite(a.g) && isfinite(a.b);
}

#endif
