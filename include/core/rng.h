/*
 * rng.h - the random numbers of ch. 4: PCG32 (O'Neill 2014, "PCG: A Family
 * of Simple Fast Space-Efficient Statistically Good Algorithms for Random
 * Number Generation"; the XSH-RR 64/32 generator of pcg-c-basic), seeded per
 * sample so that a render does not depend on the thread count or order.
 *
 * The numbers of one camera sample are a function of (seed, pixel, sample
 * index) only: rng_for_sample() hashes the three with SplitMix64 into the
 * generator's state and stream, and dimension k of that sample is its k-th
 * draw (rng_dimension() jumps straight to it). A port that reproduces
 * pcg32_next, splitmix64 and rng_for_sample reproduces every image.
 * Tests: tests/core/test_rng.c; vectors: tests/vectors/rng_*.csv
 */
#ifndef SVET_RNG_H
#define SVET_RNG_H

#include <stdint.h>
#include "core/real.h"

typedef struct {
    uint64_t state; /* the LCG state */
    uint64_t inc;   /* stream selector, always odd */
} pcg32_t;

/* pcg32_srandom_r of pcg-c-basic: initstate and a stream number initseq
 * (2^63 streams). Seeds (42, 54) give 0xa15c02b7 0x7b47f409 ... */
void pcg32_seed(pcg32_t *g, uint64_t initstate, uint64_t initseq);

/* Next 32 random bits. */
static inline uint32_t pcg32_next(pcg32_t *g)
{
    uint64_t old = g->state;
    g->state = old * UINT64_C(6364136223846793005) + g->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18) ^ old) >> 27);
    uint32_t rot = (uint32_t)(old >> 59);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
}

/* Move the generator delta steps ahead (or back, modulo 2^64) in O(log
 * delta): Brown, "Random Number Generation with Arbitrary Strides", 1994. */
void pcg32_advance(pcg32_t *g, uint64_t delta);

/* Uniform in [0, bound) without modulo bias (pcg32_boundedrand_r). bound
 * must be > 0. */
uint32_t pcg32_bounded(pcg32_t *g, uint32_t bound);

/* Uniform real in [0, 1), never 1: in float, the top 24 bits times 2^-24,
 * so the largest value is the largest float below 1 (1 - 2^-24); in double,
 * all 32 bits times 2^-32. Both are exact: no rounding ever reaches 1. */
static inline real pcg32_real(pcg32_t *g)
{
#ifdef SVET_DOUBLE
    return (real)pcg32_next(g) * REAL_C(0x1p-32);
#else
    return (real)(pcg32_next(g) >> 8) * REAL_C(0x1p-24);
#endif
}

/* SplitMix64 (Steele, Lea, Flood 2014; the finaliser of java.util's
 * SplittableRandom): a 64-bit mix, one step of the sequence x += golden
 * ratio. splitmix64(0) = 0xe220a8397b1dcdaf. */
uint64_t splitmix64(uint64_t x);

/* The generator of camera sample `sample` of pixel `pixel` (y * width + x)
 * in a render with seed `seed`:
 *   state  = splitmix64(seed ^ splitmix64(pixel)),
 *   stream = splitmix64(sample ^ splitmix64(pixel ^ 0x9e3779b97f4a7c15)),
 * passed to pcg32_seed(g, state, stream). */
void rng_for_sample(pcg32_t *g, uint64_t seed, uint64_t pixel,
                    uint64_t sample);

/* Dimension k (0-based) of that sample without drawing 0..k-1. */
real rng_dimension(uint64_t seed, uint64_t pixel, uint64_t sample,
                   uint64_t k);

#endif
