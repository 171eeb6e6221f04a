/*
 * simd.h - vectors of real for the culling tests of brute force
 * (parallelogram.c's batch): SSE2's 4 floats or 2 doubles, where the
 * compiler targets SSE2 (every x86-64 does). Each V_ macro is one IEEE
 * operation, so code written with them computes in every lane the bits
 * that the same expressions give in plain C, as long as it keeps their
 * order (SSE2 has no fused multiply-add); V_MAX(a, b) is a > b ? a : b,
 * real_max's answer, NaN included. Without SSE2, SIMD_REAL is undefined
 * and the callers run their plain loops.
 * Tests: tests/test_parallelogram.c (the vector loop against its plain
 * loop)
 */
#ifndef SVET_SIMD_H
#define SVET_SIMD_H

#include "real.h"

#ifdef __SSE2__
#define SIMD_REAL 1
#include <emmintrin.h>
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
#endif
#endif

#endif
