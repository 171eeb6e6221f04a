/*
 * vectors_rng.c - writes the test vectors of the random numbers of ch. 4
 * (include/core/rng.h) into DIR/rng_pcg32.csv and DIR/rng_sample.csv: raw PCG32
 * outputs for several (initstate, initseq), and the first draws of
 * rng_for_sample(seed, pixel, sample) as 32-bit integers and as
 * pcg32_real in float and in double. Expected values come from a second
 * implementation written here from the PCG paper (O'Neill 2014) and
 * SplitMix64 (Steele, Lea, Flood 2014) with 32-bit limb arithmetic, checked
 * against the published first outputs of seeds 42/54 and against
 * src/core/rng.c (any disagreement aborts). Usage: vectors_rng DIR
 */
#include <inttypes.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include "core/rng.h"
#include "vectors.h"

/* --- the independent implementation --------------------------------------- */

/* a * b mod 2^64 from 32-bit halves (no reliance on 64-bit multiply). */
static uint64_t mul64(uint64_t a, uint64_t b)
{
    uint64_t a_lo = a & 0xffffffffu, a_hi = a >> 32;
    uint64_t b_lo = b & 0xffffffffu, b_hi = b >> 32;
    uint64_t lo = a_lo * b_lo;                        /* < 2^64 */
    uint64_t cross = (a_hi * b_lo + a_lo * b_hi) << 32; /* mod 2^64 */
    return lo + cross;
}

typedef struct {
    uint64_t s, inc;
} ref_pcg;

/* PCG-XSH-RR 64/32: output from the old state, then LCG step. */
static uint32_t ref_next(ref_pcg *g)
{
    uint64_t old = g->s;
    g->s = mul64(old, UINT64_C(6364136223846793005)) + g->inc;
    uint32_t x = (uint32_t)(((old >> 18) ^ old) >> 27);
    unsigned rot = (unsigned)(old >> 59);
    for (unsigned i = 0; i < rot; i++) /* rotate right one bit at a time */
        x = (x >> 1) | (x << 31);
    return x;
}

static void ref_seed(ref_pcg *g, uint64_t initstate, uint64_t initseq)
{
    g->s = 0;
    g->inc = (initseq << 1) | 1u;
    (void)ref_next(g);
    g->s += initstate;
    (void)ref_next(g);
}

static uint64_t ref_splitmix(uint64_t x)
{
    uint64_t z = x + UINT64_C(0x9e3779b97f4a7c15);
    z = mul64(z ^ (z >> 30), UINT64_C(0xbf58476d1ce4e5b9));
    z = mul64(z ^ (z >> 27), UINT64_C(0x94d049bb133111eb));
    return z ^ (z >> 31);
}

static void ref_for_sample(ref_pcg *g, uint64_t seed, uint64_t pixel,
                           uint64_t sample)
{
    uint64_t state = ref_splitmix(seed ^ ref_splitmix(pixel));
    uint64_t stream = ref_splitmix(sample ^
                                   ref_splitmix(pixel ^ UINT64_C(0x9e3779b97f4a7c15)));
    ref_seed(g, state, stream);
}

/* --- files ------------------------------------------------------------------ */

static void fail(const char *what)
{
    fprintf(stderr, "vectors_rng: %s\n", what);
    exit(1);
}

static void pcg32_file(const char *dir)
{
    static const uint32_t published[6] = { 0xa15c02b7, 0x7b47f409, 0xba1d3330,
                                           0x83d2f293, 0xbfa4784b, 0xcbed606e };
    static const uint64_t seeds[][2] = {
        { 42, 54 }, { 0, 0 }, { 1, 1 }, { 12345, 0 },
        { UINT64_C(0xdeadbeefcafef00d), UINT64_C(0x0123456789abcdef) },
        { UINT64_MAX, UINT64_MAX }, { UINT64_C(1) << 63, 7 },
    };
    FILE *f = vectors_open(dir, "rng_pcg32.csv");
    fprintf(f, "# PCG32 (XSH-RR 64/32, pcg32_srandom_r seeding) raw outputs: "
               "output number `index` (0-based) after pcg32_seed(initstate, "
               "initseq).\n"
               "# Seeds 42/54 indices 0-5: published (pcg-random.org, "
               "pcg32-demo). All rows: a second implementation in "
               "tools/vectors_rng.c (32-bit limb multiply), equal to src/core/rng.c.\n"
               "# Seeds are unsigned 64-bit decimal: parse as integers, not "
               "floats. output is exact (tol 0).\n"
               "initstate,initseq,index,output,output_hex,tol,source\n");
    for (size_t s = 0; s < sizeof seeds / sizeof seeds[0]; s++) {
        ref_pcg r;
        pcg32_t g;
        ref_seed(&r, seeds[s][0], seeds[s][1]);
        pcg32_seed(&g, seeds[s][0], seeds[s][1]);
        for (int i = 0; i < 12; i++) {
            uint32_t x = ref_next(&r);
            if (x != pcg32_next(&g))
                fail("src/core/rng.c disagrees with the reference PCG32");
            bool pub = s == 0 && i < 6;
            if (pub && x != published[i])
                fail("reference PCG32 disagrees with the published outputs");
            fprintf(f, "%" PRIu64 ",%" PRIu64 ",%d,%" PRIu32 ",0x%08" PRIx32
                       ",0,%s\n",
                    seeds[s][0], seeds[s][1], i, x, x,
                    pub ? "published pcg32-demo" : "reference implementation");
        }
    }
    vectors_close(f, dir, "rng_pcg32.csv");
}

static void sample_file(const char *dir)
{
    static const uint64_t seeds[] = { 0, 1, 42, UINT64_MAX };
    static const uint64_t pixels[] = { 0, 1, 640 * 480 - 1, UINT64_C(1) << 40 };
    static const uint64_t samples[] = { 0, 1, 1023 };
    static const uint64_t dims[] = { 0, 1, 2, 3, 100 };
    FILE *f = vectors_open(dir, "rng_sample.csv");
    fprintf(f, "# rng_for_sample(seed, pixel, sample): draw number k "
               "(0-based; rng_dimension(seed, pixel, sample, k)) as the raw "
               "32 bits u32 and as pcg32_real: real_float = (u32 >> 8) * "
               "2^-24, real_double = u32 * 2^-32 (exact; printed with 17 "
               "digits, which round-trip).\n"
               "# Expected from a second implementation of SplitMix64 and "
               "PCG32 in tools/vectors_rng.c, equal to src/core/rng.c. Integers "
               "are unsigned 64-bit decimal. Exact: tol 0.\n"
               "seed,pixel,sample,k,u32,real_float,real_double,tol,source\n");
    for (size_t a = 0; a < sizeof seeds / sizeof seeds[0]; a++)
        for (size_t b = 0; b < sizeof pixels / sizeof pixels[0]; b++)
            for (size_t c = 0; c < sizeof samples / sizeof samples[0]; c++)
                for (size_t d = 0; d < sizeof dims / sizeof dims[0]; d++) {
                    ref_pcg r;
                    ref_for_sample(&r, seeds[a], pixels[b], samples[c]);
                    uint32_t x = 0;
                    for (uint64_t k = 0; k <= dims[d]; k++)
                        x = ref_next(&r);
                    pcg32_t g;
                    rng_for_sample(&g, seeds[a], pixels[b], samples[c]);
                    pcg32_advance(&g, dims[d]);
                    if (pcg32_next(&g) != x)
                        fail("src/core/rng.c disagrees with the reference "
                             "rng_for_sample");
                    double rf = (double)(x >> 8) * 0x1p-24;
                    double rd = (double)x * 0x1p-32;
                    fprintf(f, "%" PRIu64 ",%" PRIu64 ",%" PRIu64 ",%" PRIu64
                               ",%" PRIu32 ",%.17g,%.17g,0,reference "
                               "implementation\n",
                            seeds[a], pixels[b], samples[c], dims[d], x, rf, rd);
                }
    vectors_close(f, dir, "rng_sample.csv");
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s DIR\n", argv[0]);
        return 2;
    }
    pcg32_file(argv[1]);
    sample_file(argv[1]);
    return 0;
}
