/*
 * ray.h - rays, and spawning new rays from a surface point without
 * re-hitting that surface. svet does not push a spawned ray off by a fixed
 * epsilon (which fails at large scales and leaks light at small ones): each
 * hit point carries a bound on its floating-point error, and the origin is
 * moved just past that bound along the normal - Pharr, Jakob, Humphreys,
 * "Physically Based Rendering", 3rd ed., sec. 3.9 (pbrt-v3
 * core/geometry.h, OffsetRayOrigin).
 * Tests: tests/core/test_ray.c
 */
#ifndef SVET_RAY_H
#define SVET_RAY_H

#include "core/vec.h"

/* The points o + t d for t in (tmin, tmax). d need not be unit length:
 * an affine transform keeps t and changes |d| (xform.h). */
typedef struct {
    VECTOR3 o; /* origin */
    VECTOR3 d; /* direction */
} ray_t;

/* Parametric tolerance of a shadow ray aimed at a point: it ends at
 * 1 - RAY_SHADOW_EPSILON of the way (pbrt-v3's ShadowEpsilon). */
#define RAY_SHADOW_EPSILON REAL_C(1e-4)

/* p = o + t d */
static inline void ray_at(VECTOR3 p, const ray_t *r, real t)
{
    vec_add_scaled(p, r->o, t, r->d);
}

/* gamma(n) = n u / (1 - n u), u the unit roundoff: the relative error bound
 * of n successive roundings (Higham 2002, sec. 3.1; pbrt-v3 sec. 3.9.1). */
static inline real ray_gamma(int n)
{
    return ((real)n * REAL_UNIT_ROUNDOFF) / (1 - (real)n * REAL_UNIT_ROUNDOFF);
}

/* A point po just off the surface through p (absolute error bound p_error
 * per axis, normal n of either orientation), on the side toward which w
 * points: p moved by (|n| . p_error) along +-n, then rounded one more ulp
 * away from the surface. This function can't fail. */
void ray_offset_origin(VECTOR3 po, const VECTOR3 p, const VECTOR3 p_error,
                       const VECTOR3 n, const VECTOR3 w);

/* ray_offset_origin()'s last step, d already signed toward w's side:
 * po_i = p_i + n_i d rounded one more ulp in the direction of n_i d (a
 * coordinate whose n_i d is zero or NaN keeps the rounded sum). _plain is
 * ray.c's scalar code; _simd, in SIMD=on builds (src/core/fast/
 * ray_simd.c), gives its bits with the three axes in vector lanes, and is
 * what ray_offset_origin() calls there. Test hooks: tests/core/test_ray.c
 * compares the two. These functions can't fail. */
void ray_offset_along_plain(VECTOR3 po, const VECTOR3 p, const VECTOR3 n,
                            real d);
#ifdef SVET_SIMD
void ray_offset_along_simd(VECTOR3 po, const VECTOR3 p, const VECTOR3 n,
                           real d);
#endif

/* A ray leaving the surface point p (error p_error, normal n) in direction
 * w, to be traced over (0, infinity). */
void ray_spawn(ray_t *r, const VECTOR3 p, const VECTOR3 p_error,
               const VECTOR3 n, const VECTOR3 w);

/* A shadow ray from surface point p0 to surface point p1, both offset off
 * their surfaces; trace it over (0, returned tmax) to test visibility
 * without hitting either surface. Pass a zero p1_error for a point light. */
real ray_spawn_to(ray_t *r, const VECTOR3 p0, const VECTOR3 p0_error,
                  const VECTOR3 n0, const VECTOR3 p1, const VECTOR3 p1_error,
                  const VECTOR3 n1);

#endif
