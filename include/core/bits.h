/*
 * bits.h - two questions about the bits of a 64-bit word, asked by the
 * walks over occupancy words and lane masks (accel.c's parallelogram
 * batch, grid.c's blocks and quads; ch. 7): how many bits are set, and
 * which is the lowest. Each is one instruction where the compiler offers
 * it (POPCNT where it targets it, TZCNT/BSF through gcc's and clang's
 * builtins), else the plain code, kept as the *_plain functions that the
 * tests compare with.
 * Tests: tests/core/test_bits.c
 */
#ifndef SVET_BITS_H
#define SVET_BITS_H

#include <stdint.h>

/* The number of bits set in x, by the SWAR sum of Hacker's Delight
 * (Warren, 2nd ed., sec. 5-1). This function can't fail. */
static inline int bits_count_plain(uint64_t x)
{
    x = x - ((x >> 1) & UINT64_C(0x5555555555555555));
    x = (x & UINT64_C(0x3333333333333333)) +
        ((x >> 2) & UINT64_C(0x3333333333333333));
    x = (x + (x >> 4)) & UINT64_C(0x0f0f0f0f0f0f0f0f);
    return (int)((x * UINT64_C(0x0101010101010101)) >> 56);
}

/* The number of bits set in x: POPCNT where the compiler targets it
 * (-march=native on a machine that has it; plain x86-64 does not), else
 * bits_count_plain(). This function can't fail. */
static inline int bits_count(uint64_t x)
{
#if defined(__POPCNT__) && (defined(__GNUC__) || defined(__clang__))
    return __builtin_popcountll(x);
#else
    return bits_count_plain(x);
#endif
}

/* The index (0 to 63) of the lowest set bit of x, by a loop; 64 for
 * x = 0 (which bits_lowest() must not be given). This function can't
 * fail. */
static inline int bits_lowest_plain(uint64_t x)
{
    int j = 0;
    for (; j < 64 && !(x & 1); x >>= 1)
        j++;
    return j;
}

/* The index of the lowest set bit of x (x != 0): TZCNT/BSF through the
 * compiler's builtin where there is one, else bits_lowest_plain(). This
 * function can't fail for x != 0. */
static inline int bits_lowest(uint64_t x)
{
#if defined(__GNUC__) || defined(__clang__)
    return __builtin_ctzll(x);
#else
    return bits_lowest_plain(x);
#endif
}

#endif
