/*
 * noise.h - the solid noise of ch. 10: Perlin's improved noise (Perlin,
 * "Improving Noise", SIGGRAPH 2002) with its analytic gradient, and the
 * sums of octaves built on it: the fractal sum and turbulence of Perlin,
 * "An Image Synthesizer", SIGGRAPH 1985.
 * Tests: tests/texture/test_noise.c; vectors: tests/vectors/noise_perlin.csv
 * (written by Perlin's algorithm in Java, tools/perlin/PerlinVectors.java).
 */
#ifndef SVET_NOISE_H
#define SVET_NOISE_H

#include "core/vec.h"

/* Improved noise at p: the same value, to rounding, as Perlin's Java
 * reference ImprovedNoise.noise(x, y, z), with its permutation, its fade
 * curve 6t^5 - 15t^4 + 10t^3 and its sixteen gradients. Zero at every
 * lattice point (integer x, y, z); C2 across cells; periodic with period
 * 256 in each coordinate; |noise| < 2 always (a convex blend of gradient
 * dot products, each below 2), and about 1.04 at the most in practice.
 * A coordinate that is not finite gives 0. This function can't fail. */
real noise_perlin(const VECTOR3 p);

/* noise_perlin(p), and its gradient d noise / dp in grad, differentiated
 * exactly (the fade curve's derivative 30 t^2 (t - 1)^2 times the cell's
 * trilinear blend, plus the blend of the corner gradients). The value
 * equals noise_perlin(p) bit for bit. This function can't fail. */
real noise_perlin_grad(const VECTOR3 p, VECTOR3 grad);

/* The octaves of a fractal sum: octave i is scaled in space by
 * lacunarity^i and in value by gain^i (Perlin 1985; Musgrave's fBm in
 * Ebert et al., "Texturing and Modeling", ch. 16). */
typedef struct {
    int octaves;      /* 1 or more; at most NOISE_MAX_OCTAVES */
    real lacunarity;  /* spatial frequency ratio between octaves, e.g. 2 */
    real gain;        /* amplitude ratio between octaves, e.g. 0.5 */
} noise_octaves_t;

#define NOISE_MAX_OCTAVES 32

/* The default octaves: 6 of them, lacunarity 2, gain 0.5. */
noise_octaves_t noise_octaves_default(void);

/* The fractal sum sum_i gain^i noise(lacunarity^i p), and its gradient in
 * grad (which may be NULL). o->octaves is clamped to [1,
 * NOISE_MAX_OCTAVES]. This function can't fail. */
real noise_fractal(const VECTOR3 p, const noise_octaves_t *o, VECTOR3 grad);

/* Perlin 1985's turbulence, sum_i gain^i |noise(lacunarity^i p)|, and its
 * gradient (where each octave is not zero; an octave's kink at zero gets
 * the gradient of +noise) in grad (which may be NULL). This function can't
 * fail. */
real noise_turbulence(const VECTOR3 p, const noise_octaves_t *o,
                      VECTOR3 grad);

#endif
