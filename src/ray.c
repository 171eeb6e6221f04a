/*
 * ray.c - spawning rays from surface points with a bound on the hit point's
 * floating-point error (pbrt-v3 sec. 3.9.5, OffsetRayOrigin and SpawnRayTo).
 * Tests: tests/test_ray.c
 */
#include "ray.h"

#include <stdbool.h>

#include "simd.h"

#if defined(SIMD_REAL) && !defined(SVET_DOUBLE)
/* The three coordinates at once, lane i = coordinate i, without a branch
 * per coordinate: the offset's direction along an axis-aligned normal
 * changes from one wall to the next, so offset_coord()'s branches were
 * often mispredicted (callgrind --branch-sim: 5.5 a camera sample in the
 * Cornell box). Each lane computes offset_coord()'s bits: the same
 * product n_i d and sum p_i + n_i d (one IEEE operation each), and then
 * the step real_next_up() takes, written as masks:
 *   next_down(q) = -next_up(-q)  (real.h): a lane moving down flips the
 *     sign bit of q, steps up, and flips it back;
 *   next_up(x): x itself when !(x < inf) (NaN, +inf); the bits 1
 *     (REAL_TRUE_MIN) when x == 0 (either zero); else the bits plus one
 *     when x > 0 and minus one when x < 0 (the magnitude's bits are
 *     ordered as the magnitudes are);
 *   a lane whose offset is neither > 0 nor < 0 (a zero, NaN) keeps q.
 * The side test stays a branch: as a mask it made every lane wait for
 * w . n, and the renders took longer. test_ray.c compares the bits with
 * libm's nextafter on every class of input. */
static void offset_origin_vec(VECTOR3 po, const VECTOR3 p, real d,
                              bool flip, const VECTOR3 n)
{
    const __m128 sign = _mm_set1_ps(-0.0f);
    const __m128i one = _mm_set1_epi32(1);
    __m128 vd = _mm_set1_ps(d);
    if (flip) /* -d: d with its sign bit flipped, as C's negation */
        vd = _mm_xor_ps(vd, sign);
    __m128 off = _mm_mul_ps(_mm_set_ps(0, n[Z], n[Y], n[X]), vd);
    __m128 q = _mm_add_ps(_mm_set_ps(0, p[Z], p[Y], p[X]), off);
    __m128 up = _mm_cmpgt_ps(off, _mm_setzero_ps());
    __m128 down = _mm_cmplt_ps(off, _mm_setzero_ps());
    __m128 flipq = _mm_and_ps(down, sign);
    __m128 x = _mm_xor_ps(q, flipq); /* next_up(x) is asked for */
    __m128i xi = _mm_castps_si128(x);
    __m128i pos = _mm_castps_si128(_mm_cmpgt_ps(x, _mm_setzero_ps()));
    __m128i zero = _mm_castps_si128(_mm_cmpeq_ps(x, _mm_setzero_ps()));
    __m128i finite =
        _mm_castps_si128(_mm_cmplt_ps(x, _mm_set1_ps((real)INFINITY)));
    /* + 1 where x > 0, - 1 (all ones) elsewhere: ~pos | 1 */
    __m128i step =
        _mm_or_si128(_mm_andnot_si128(pos, _mm_set1_epi32(-1)), one);
    __m128i r = _mm_add_epi32(xi, step);
    r = _mm_or_si128(_mm_andnot_si128(zero, r), _mm_and_si128(zero, one));
    r = _mm_or_si128(_mm_and_si128(finite, r), _mm_andnot_si128(finite, xi));
    __m128 moved = _mm_xor_ps(_mm_castsi128_ps(r), flipq);
    __m128 move = _mm_or_ps(up, down);
    __m128 res = _mm_or_ps(_mm_and_ps(move, moved), _mm_andnot_ps(move, q));
    float out[4];
    _mm_storeu_ps(out, res);
    vec_set(po, out[0], out[1], out[2]);
}
#else
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
#endif

void ray_offset_origin(VECTOR3 po, const VECTOR3 p, const VECTOR3 p_error,
                       const VECTOR3 n, const VECTOR3 w)
{
    /* The smallest offset along n that leaves the box of possible true
     * points: the support of that box in direction n, toward w's side
     * (n (-d) is -(n d) bit for bit: rounding is symmetric). */
    real d = fabs(n[X]) * p_error[X] + fabs(n[Y]) * p_error[Y] +
             fabs(n[Z]) * p_error[Z];
#if defined(SIMD_REAL) && !defined(SVET_DOUBLE)
    offset_origin_vec(po, p, d, SVECTOR3(w, n) < 0, n);
#else
    if (SVECTOR3(w, n) < 0)
        d = -d;
    real x = offset_coord(p[X], n[X] * d), y = offset_coord(p[Y], n[Y] * d),
         z = offset_coord(p[Z], n[Z] * d);
    vec_set(po, x, y, z);
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
