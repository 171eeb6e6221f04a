/*
 * phase.h - the phase functions of ch. 11 and 12: how a participating
 * medium scatters light, p(cos theta) per unit solid angle, normalised
 * over the sphere: isotropic, Henyey-Greenstein (Henyey & Greenstein,
 * "Diffuse radiation in the galaxy", ApJ 93, 1941) with its exact
 * inverse-CDF sampling for every g in (-1, 1), and Rayleigh's
 * 3 / (16 pi) (1 + cos^2 theta) for the sky of ch. 12, sampled exactly by
 * Cardano's formula (Frisvad, "Importance sampling the Rayleigh phase
 * function", JOSA A 28(12), 2011).
 * Tests: tests/medium/test_phase.c
 */
#ifndef SVET_PHASE_H
#define SVET_PHASE_H

#include "core/vec.h"

typedef enum {
    PHASE_ISOTROPIC,
    PHASE_HG,       /* Henyey-Greenstein with asymmetry g */
    PHASE_RAYLEIGH  /* molecules much smaller than the wavelength */
} phase_kind_t;

typedef struct {
    phase_kind_t kind;
    real g; /* HG: the mean cosine of scattering, in (-1, 1) */
} phase_t;

/* The largest |g| accepted: closer to 1 the lobe is narrower than float's
 * resolution of directions. */
#define PHASE_MAX_G REAL_C(0.999)

/* The phase function of the cosine between the direction light travels
 * before and after scattering (cos = 1: straight on, no deflection).
 * Can't fail. */
real phase_eval(const phase_t *p, real cos_theta);

/* Sample the direction after scattering, wo, of light travelling along
 * wi (unit), from u in [0, 1)^2; returns the pdf of wo, which equals
 * phase_eval (the samplers are exact). Can't fail. */
real phase_sample(const phase_t *p, const VECTOR3 wi, const real u[2],
                  VECTOR3 wo);

/* The cosine of the sampled deflection alone, from u in [0, 1): the
 * inverse of the phase function's CDF in cos theta. Can't fail. */
real phase_sample_cos(const phase_t *p, real u);

#endif
