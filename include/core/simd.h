/*
 * simd.h - vectors of real for the culling tests: SSE2's 4 floats or 2
 * doubles (vreal, V_), where the compiler targets SSE2 (every x86-64
 * does), used by the mesh triangles' sign test (mesh.h); and the widest
 * vectors the compiler targets (vwreal, VW_): AVX's 8 floats or 4 doubles
 * where it targets AVX (the Makefile's -march=native on such a machine),
 * else the same as V_, used by brute force's parallelogram batch
 * (fast/parallelogram_cull.c) and the sign test of a grid cell's
 * triangles (mesh.h). Each macro is one IEEE operation, so code written
 * with them computes in every lane the bits that the same expressions give
 * in plain C, as long as it keeps their order (neither has a fused
 * multiply-add, and the build has -ffp-contract=off); V_MAX(a, b) is
 * a > b ? a : b, real_max's answer, NaN included, and every comparison is
 * false when either side is NaN (AVX's _CMP_*_OQ, as SSE2's), V_NEQ
 * included: a < b or a > b, ordered (_CMP_NEQ_OQ; SSE2 has no one
 * instruction for it, so there it is the two). VW_LOAD2(lo, hi),
 * where the widest vectors hold twice SSE2's (AVX), loads VLANES reals
 * from lo into the low lanes and VLANES from hi into the high ones.
 * Without SSE2, or in a build without SVET_SIMD
 * (`make SIMD=off`, a chapter's one-line cc command), SIMD_REAL is
 * undefined and the callers run their plain loops.
 * Tests: tests/geometry/test_parallelogram.c and tests/mesh/test_mesh.c (the vector
 * loops against their plain loops)
 */
#ifndef SVET_SIMD_H
#define SVET_SIMD_H

#include "core/real.h"

/* The intrinsics' headers only in a build with the speed layers
 * (SVET_SIMD), wherever the compiler targets their instructions: the
 * plain build includes none of them. */
#if defined(SVET_SIMD) && defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(SVET_SIMD) && defined(__AVX__)
#include <immintrin.h>
#endif

#if defined(__SSE2__) && defined(SVET_SIMD)
#define SIMD_REAL 1
#ifdef SVET_DOUBLE
typedef __m128d vreal;
#define VLANES 2
#define V_SET1 _mm_set1_pd
#define V_LOAD _mm_loadu_pd
#define V_ADD _mm_add_pd
#define V_SUB _mm_sub_pd
#define V_MUL _mm_mul_pd
#define V_DIV _mm_div_pd
#define V_MAX _mm_max_pd
#define V_AND _mm_and_pd
#define V_ANDNOT _mm_andnot_pd
#define V_OR _mm_or_pd
#define V_XOR _mm_xor_pd
#define V_GT _mm_cmpgt_pd
#define V_GE _mm_cmpge_pd
#define V_LT _mm_cmplt_pd
#define V_LE _mm_cmple_pd
#define V_MASK _mm_movemask_pd
#ifdef __AVX__
#define V_NEQ(a, b) _mm_cmp_pd(a, b, _CMP_NEQ_OQ)
#endif
#else
typedef __m128 vreal;
#define VLANES 4
#define V_SET1 _mm_set1_ps
#define V_LOAD _mm_loadu_ps
#define V_ADD _mm_add_ps
#define V_SUB _mm_sub_ps
#define V_MUL _mm_mul_ps
#define V_DIV _mm_div_ps
#define V_MAX _mm_max_ps
#define V_AND _mm_and_ps
#define V_ANDNOT _mm_andnot_ps
#define V_OR _mm_or_ps
#define V_XOR _mm_xor_ps
#define V_GT _mm_cmpgt_ps
#define V_GE _mm_cmpge_ps
#define V_LT _mm_cmplt_ps
#define V_LE _mm_cmple_ps
#define V_MASK _mm_movemask_ps
#ifdef __AVX__
#define V_NEQ(a, b) _mm_cmp_ps(a, b, _CMP_NEQ_OQ)
#endif
#endif
#endif

#if defined(SIMD_REAL) && !defined(__AVX__)
/* a < b or a > b: SSE2 has no ordered not-equal of its own */
static inline vreal simd_neq_(vreal a, vreal b)
{
    return V_OR(V_LT(a, b), V_GT(a, b));
}
#define V_NEQ simd_neq_
#endif

/* The widest vectors: AVX where the compiler targets it, else SSE2's. */
#ifdef SIMD_REAL
#ifdef __AVX__
#ifdef SVET_DOUBLE
typedef __m256d vwreal;
#define VWLANES 4
#define VW_SET1 _mm256_set1_pd
#define VW_LOAD _mm256_loadu_pd
#define VW_ADD _mm256_add_pd
#define VW_SUB _mm256_sub_pd
#define VW_MUL _mm256_mul_pd
#define VW_DIV _mm256_div_pd
#define VW_MAX _mm256_max_pd
#define VW_AND _mm256_and_pd
#define VW_ANDNOT _mm256_andnot_pd
#define VW_OR _mm256_or_pd
#define VW_XOR _mm256_xor_pd
#define VW_GT(a, b) _mm256_cmp_pd(a, b, _CMP_GT_OQ)
#define VW_GE(a, b) _mm256_cmp_pd(a, b, _CMP_GE_OQ)
#define VW_LT(a, b) _mm256_cmp_pd(a, b, _CMP_LT_OQ)
#define VW_LE(a, b) _mm256_cmp_pd(a, b, _CMP_LE_OQ)
#define VW_MASK _mm256_movemask_pd
#define VW_NEQ(a, b) _mm256_cmp_pd(a, b, _CMP_NEQ_OQ)
#define VW_LOAD2(lo, hi) _mm256_loadu2_m128d(hi, lo)
#else
typedef __m256 vwreal;
#define VWLANES 8
#define VW_SET1 _mm256_set1_ps
#define VW_LOAD _mm256_loadu_ps
#define VW_ADD _mm256_add_ps
#define VW_SUB _mm256_sub_ps
#define VW_MUL _mm256_mul_ps
#define VW_DIV _mm256_div_ps
#define VW_MAX _mm256_max_ps
#define VW_AND _mm256_and_ps
#define VW_ANDNOT _mm256_andnot_ps
#define VW_OR _mm256_or_ps
#define VW_XOR _mm256_xor_ps
#define VW_GT(a, b) _mm256_cmp_ps(a, b, _CMP_GT_OQ)
#define VW_GE(a, b) _mm256_cmp_ps(a, b, _CMP_GE_OQ)
#define VW_LT(a, b) _mm256_cmp_ps(a, b, _CMP_LT_OQ)
#define VW_LE(a, b) _mm256_cmp_ps(a, b, _CMP_LE_OQ)
#define VW_MASK _mm256_movemask_ps
#define VW_NEQ(a, b) _mm256_cmp_ps(a, b, _CMP_NEQ_OQ)
#define VW_LOAD2(lo, hi) _mm256_loadu2_m128(hi, lo)
#endif
#else
typedef vreal vwreal;
#define VWLANES VLANES
#define VW_SET1 V_SET1
#define VW_LOAD V_LOAD
#define VW_ADD V_ADD
#define VW_SUB V_SUB
#define VW_MUL V_MUL
#define VW_DIV V_DIV
#define VW_MAX V_MAX
#define VW_AND V_AND
#define VW_ANDNOT V_ANDNOT
#define VW_OR V_OR
#define VW_XOR V_XOR
#define VW_GT V_GT
#define VW_GE V_GE
#define VW_LT V_LT
#define VW_LE V_LE
#define VW_MASK V_MASK
#define VW_NEQ V_NEQ
#endif
#endif

#endif
