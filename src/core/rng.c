/*
 * rng.c - PCG32 seeding, jump-ahead and bounded draws (O'Neill 2014,
 * pcg-c-basic), SplitMix64, and the per-sample seeding of rng.h (ch. 4).
 * Tests: tests/core/test_rng.c
 */
#include "core/rng.h"

#define PCG32_MULT UINT64_C(6364136223846793005)

void pcg32_seed(pcg32_t *g, uint64_t initstate, uint64_t initseq)
{
    g->state = 0;
    g->inc = (initseq << 1) | 1;
    (void)pcg32_next(g);
    g->state += initstate;
    (void)pcg32_next(g);
}

void pcg32_advance(pcg32_t *g, uint64_t delta)
{
    /* x_{n+delta} = A x_n + C with A = a^delta, C = c (a^delta - 1)/(a - 1),
     * built by repeated squaring. */
    uint64_t cur_mult = PCG32_MULT, cur_plus = g->inc;
    uint64_t acc_mult = 1, acc_plus = 0;
    while (delta > 0) {
        if (delta & 1) {
            acc_mult *= cur_mult;
            acc_plus = acc_plus * cur_mult + cur_plus;
        }
        cur_plus = (cur_mult + 1) * cur_plus;
        cur_mult *= cur_mult;
        delta >>= 1;
    }
    g->state = acc_mult * g->state + acc_plus;
}

uint32_t pcg32_bounded(pcg32_t *g, uint32_t bound)
{
    /* Reject the lowest (2^32 mod bound) values so every residue is equally
     * likely; at most half of all draws are rejected, so this ends. */
    uint32_t threshold = (0u - bound) % bound;
    for (;;) {
        uint32_t r = pcg32_next(g);
        if (r >= threshold)
            return r % bound;
    }
}

uint64_t splitmix64(uint64_t x)
{
    uint64_t z = x + UINT64_C(0x9e3779b97f4a7c15);
    z = (z ^ (z >> 30)) * UINT64_C(0xbf58476d1ce4e5b9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94d049bb133111eb);
    return z ^ (z >> 31);
}

void rng_for_sample(pcg32_t *g, uint64_t seed, uint64_t pixel,
                    uint64_t sample)
{
    uint64_t state = splitmix64(seed ^ splitmix64(pixel));
    uint64_t stream =
        splitmix64(sample ^ splitmix64(pixel ^ UINT64_C(0x9e3779b97f4a7c15)));
    pcg32_seed(g, state, stream);
}

real rng_dimension(uint64_t seed, uint64_t pixel, uint64_t sample, uint64_t k)
{
    pcg32_t g;
    rng_for_sample(&g, seed, pixel, sample);
    pcg32_advance(&g, k);
    return pcg32_real(&g);
}
