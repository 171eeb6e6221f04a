/*
 * ray_simd.c - speed layer of ray.c (SIMD=on): ray_offset_along() with
 * the three coordinates in the lanes of one vector, lane i = axis i, and
 * no branch per coordinate. The offset's direction along an axis-aligned
 * normal changes from one wall to the next, so offset_coord()'s branches
 * in ray.c are often mispredicted; here the step of real_next_up() is
 * written as masks. Float uses SSE2's four lanes, double AVX2's four;
 * without them, ray.c's plain code.
 * Tests: tests/core/test_ray.c (against ray_offset_along_plain, bit for bit)
 */
#include "core/ray.h"

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
#elif defined(SIMD_REAL) && defined(SVET_DOUBLE) && defined(__AVX2__)
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
/* Each lane computes offset_coord()'s bits: the same product n_i d and
 * sum p_i + n_i d (one IEEE operation each), and then the step
 * real_next_up() takes, written as masks:
 *   next_down(q) = -next_up(-q)  (real.h): a lane moving down flips the
 *     sign bit of q, steps up, and flips it back;
 *   next_up(x): x itself when !(x < inf) (NaN, +inf); the bits 1
 *     (REAL_TRUE_MIN) when x == 0 (either zero); else the bits plus one
 *     when x > 0 and minus one when x < 0 (the magnitude's bits are
 *     ordered as the magnitudes are);
 *   a lane whose offset is neither > 0 nor < 0 (a zero, NaN) keeps q. */
void ray_offset_along_simd(VECTOR3 po, const VECTOR3 p, const VECTOR3 n,
                           real d)
{
    const ov_t sign = OV_SET1(-REAL_C(0.0));
    const ovi_t one = OVI_SET1(1);
    ov_t off = OV_MUL(OV_SET3(n[X], n[Y], n[Z]), OV_SET1(d));
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
void ray_offset_along_simd(VECTOR3 po, const VECTOR3 p, const VECTOR3 n,
                           real d)
{
    ray_offset_along_plain(po, p, n, d);
}
#endif
