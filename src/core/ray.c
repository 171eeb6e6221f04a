/*
 * ray.c - spawning rays from surface points with a bound on the hit point's
 * floating-point error (pbrt-v3 sec. 3.9.5, OffsetRayOrigin and SpawnRayTo).
 * Tests: tests/core/test_ray.c
 */
#include "core/ray.h"

#include <stdbool.h>

#include "core/simd.h"

#if defined(SIMD_REAL) && !defined(SVET_DOUBLE)
#define OFFSET_VEC 1
typedef __m128 ov_t;
typedef __m128i ovi_t;
#define OV_SET1 _mm_set1_ps
#define OV_SET3(x, y, z) _mm_set_ps(0, z, y, x)
#define OV_MUL _mm_mul_ps
#define OV_ADD _mm_add_ps
#define OV_GT _mm_cmpgt_ps
#define OV_LT _mm_cmplt_ps
#define OV_EQ _mm_cmpeq_ps
#define OV_AND _mm_and_ps
#define OV_ANDNOT _mm_andnot_ps
#define OV_OR _mm_or_ps
#define OV_XOR _mm_xor_ps
#define OV_ZERO _mm_setzero_ps
#define OV_STORE _mm_storeu_ps
#define OV_BITS _mm_castps_si128
#define OV_REAL _mm_castsi128_ps
#define OVI_SET1 _mm_set1_epi32
#define OVI_ADD _mm_add_epi32
#define OVI_AND _mm_and_si128
#define OVI_ANDNOT _mm_andnot_si128
#define OVI_OR _mm_or_si128
#elif defined(SVET_DOUBLE) && defined(__AVX2__)
#define OFFSET_VEC 1
typedef __m256d ov_t;
typedef __m256i ovi_t;
#define OV_SET1 _mm256_set1_pd
#define OV_SET3(x, y, z) _mm256_set_pd(0, z, y, x)
#define OV_MUL _mm256_mul_pd
#define OV_ADD _mm256_add_pd
#define OV_GT(a, b) _mm256_cmp_pd(a, b, _CMP_GT_OQ)
#define OV_LT(a, b) _mm256_cmp_pd(a, b, _CMP_LT_OQ)
#define OV_EQ(a, b) _mm256_cmp_pd(a, b, _CMP_EQ_OQ)
#define OV_AND _mm256_and_pd
#define OV_ANDNOT _mm256_andnot_pd
#define OV_OR _mm256_or_pd
#define OV_XOR _mm256_xor_pd
#define OV_ZERO _mm256_setzero_pd
#define OV_STORE _mm256_storeu_pd
#define OV_BITS _mm256_castpd_si256
#define OV_REAL _mm256_castsi256_pd
#define OVI_SET1 _mm256_set1_epi64x
#define OVI_ADD _mm256_add_epi64
#define OVI_AND _mm256_and_si256
#define OVI_ANDNOT _mm256_andnot_si256
#define OVI_OR _mm256_or_si256
#endif

#ifdef OFFSET_VEC
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
 * libm's nextafter on every class of input. Float uses SSE2's four
 * lanes; double uses AVX2's four (its integer lanes step the bits).
 * Without them the plain code below. */
static void offset_origin_vec(VECTOR3 po, const VECTOR3 p, real d,
                              bool flip, const VECTOR3 n)
{
    const ov_t sign = OV_SET1(-REAL_C(0.0));
    const ovi_t one = OVI_SET1(1);
    ov_t vd = OV_SET1(d);
    if (flip) /* -d: d with its sign bit flipped, as C's negation */
        vd = OV_XOR(vd, sign);
    ov_t off = OV_MUL(OV_SET3(n[X], n[Y], n[Z]), vd);
    ov_t q = OV_ADD(OV_SET3(p[X], p[Y], p[Z]), off);
    ov_t up = OV_GT(off, OV_ZERO());
    ov_t down = OV_LT(off, OV_ZERO());
    ov_t flipq = OV_AND(down, sign);
    ov_t x = OV_XOR(q, flipq); /* next_up(x) is asked for */
    ovi_t xi = OV_BITS(x);
    ovi_t pos = OV_BITS(OV_GT(x, OV_ZERO()));
    ovi_t zero = OV_BITS(OV_EQ(x, OV_ZERO()));
    ovi_t finite = OV_BITS(OV_LT(x, OV_SET1((real)INFINITY)));
    /* + 1 where x > 0, - 1 (all ones) elsewhere: ~pos | 1 */
    ovi_t step = OVI_OR(OVI_ANDNOT(pos, OVI_SET1(-1)), one);
    ovi_t r = OVI_ADD(xi, step);
    r = OVI_OR(OVI_ANDNOT(zero, r), OVI_AND(zero, one));
    r = OVI_OR(OVI_AND(finite, r), OVI_ANDNOT(finite, xi));
    ov_t moved = OV_XOR(OV_REAL(r), flipq);
    ov_t move = OV_OR(up, down);
    ov_t res = OV_OR(OV_AND(move, moved), OV_ANDNOT(move, q));
    real out[4];
    OV_STORE(out, res);
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
#ifdef OFFSET_VEC
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
