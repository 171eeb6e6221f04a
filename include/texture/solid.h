/*
 * solid.h - the solid textures of ch. 10: functions of the point in space
 * rather than of the surface's (u, v), so that an object looks carved out
 * of the material (Perlin, "An Image Synthesizer", SIGGRAPH 1985; Peachey,
 * "Solid Texturing of Complex Surfaces", the same proceedings). Each is a
 * blend factor f(p) in [0, 1] between two colours, with its gradient for
 * bump mapping: a 3D checker, noise, its fractal sum and turbulence, and
 * Perlin 1985's marble, wood and granite.
 * Tests: tests/texture/test_solid.c
 */
#ifndef SVET_SOLID_H
#define SVET_SOLID_H

#include "materials/radiance.h"
#include "texture/noise.h"

typedef enum {
    SOLID_CHECKER,    /* cells of side 1: f = 0 or 1 by the parity of the cell */
    SOLID_NOISE,      /* f = (1 + noise) / 2 */
    SOLID_FRACTAL,    /* f = (1 + fractal sum) / 2, clamped */
    SOLID_TURBULENCE, /* f = turbulence, clamped */
    SOLID_MARBLE,     /* veins: f = (1 + sin(x + amplitude turbulence)) / 2 */
    SOLID_WOOD,       /* rings about the y axis, perturbed by noise */
    SOLID_GRANITE     /* speckles: high-frequency turbulence, thresholded */
} solid_kind_t;

typedef struct {
    solid_kind_t kind;
    RADIANCE a, b;        /* the colours at f = 0 and f = 1 */
    real scale;           /* p is multiplied by scale first (> 0) */
    noise_octaves_t octaves;
    real amplitude;       /* marble: turbulence's weight in the phase;
                             wood: noise's weight on the ring radius */
    real rings;           /* wood: rings per unit of radius */
} solid_texture_t;

/* A texture of the kind with the defaults each kind is shown with in
 * chapters/ch10 (scale 1, 6 octaves of lacunarity 2 and gain 0.5,
 * amplitude 5 for marble and 0.3 for wood, 4 rings), blending a to b. */
solid_texture_t solid_default(solid_kind_t kind, RADIANCE a, RADIANCE b);

/* The blend factor f(p) in [0, 1], and its gradient d f / dp in grad
 * (which may be NULL): exact where f is smooth, 0 inside a checker cell
 * and where a clamp is active. Can't fail. */
real solid_factor(const solid_texture_t *t, const VECTOR3 p, VECTOR3 grad);

/* The colour (1 - f) a + f b at p. Can't fail. */
RADIANCE solid_eval(const solid_texture_t *t, const VECTOR3 p);

#endif
