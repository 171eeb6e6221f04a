/*
 * ray.c - spawning rays from surface points with a bound on the hit point's
 * floating-point error (pbrt-v3 sec. 3.9.5, OffsetRayOrigin and SpawnRayTo).
 * The offset's last step with the three axes in vector lanes, the same
 * bits, is src/core/fast/ray_simd.c (SIMD=on builds).
 * Tests: tests/core/test_ray.c
 */
#include "core/ray.h"

/* One coordinate: p + offset, rounded one more ulp away from the surface
 * (the sum was rounded; the extra ulp makes the offset at least what was
 * asked). */
static inline real offset_coord(real p, real offset)
{
    real q = p + offset;
    if (offset > 0)
        return real_next_up(q);
    if (offset < 0)
        return real_next_down(q);
    return q;
}

void ray_offset_along_plain(VECTOR3 po, const VECTOR3 p, const VECTOR3 n,
                            real d)
{
    real x = offset_coord(p[X], n[X] * d), y = offset_coord(p[Y], n[Y] * d),
         z = offset_coord(p[Z], n[Z] * d);
    vec_set(po, x, y, z);
}

void ray_offset_origin(VECTOR3 po, const VECTOR3 p, const VECTOR3 p_error,
                       const VECTOR3 n, const VECTOR3 w)
{
    /* The smallest offset along n that leaves the box of possible true
     * points: the support of that box in direction n, toward w's side
     * (n (-d) is -(n d) bit for bit: rounding is symmetric). */
    real d = fabs(n[X]) * p_error[X] + fabs(n[Y]) * p_error[Y] +
             fabs(n[Z]) * p_error[Z];
#ifdef SVET_SIMD
    /* Two calls rather than d = -d: a compiler that turns the sign into a
     * select makes the vector step wait for the dot product, where a
     * predicted branch does not. */
    if (SVECTOR3(w, n) < 0)
        ray_offset_along_simd(po, p, n, -d);
    else
        ray_offset_along_simd(po, p, n, d);
#else
    if (SVECTOR3(w, n) < 0)
        d = -d;
    ray_offset_along_plain(po, p, n, d);
#endif
}

void ray_spawn(ray_t *r, const VECTOR3 p, const VECTOR3 p_error,
               const VECTOR3 n, const VECTOR3 w)
{
    ray_offset_origin(r->o, p, p_error, n, w);
    vec_copy(r->d, w);
}

real ray_spawn_to(ray_t *r, const VECTOR3 p0, const VECTOR3 p0_error,
                  const VECTOR3 n0, const VECTOR3 p1, const VECTOR3 p1_error,
                  const VECTOR3 n1)
{
    VECTOR3 d, back, q1;
    vec_sub(d, p1, p0);
    ray_offset_origin(r->o, p0, p0_error, n0, d);
    vec_sub(back, r->o, p1);
    ray_offset_origin(q1, p1, p1_error, n1, back);
    vec_sub(r->d, q1, r->o);
    return 1 - RAY_SHADOW_EPSILON;
}
