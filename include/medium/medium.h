/*
 * medium.h - the participating media of ch. 11: absorption sigma_a,
 * scattering sigma_s and extinction sigma_t = sigma_a + sigma_s per unit
 * length (RGB, so that extinction may differ per channel), emission, and
 * a phase function (medium/phase.h), scaled in space by a density: 1
 * everywhere (homogeneous), a grid (medium/volgrid.h, gridded media and
 * ch. 13's smoke), or a function (ch. 12's exponential atmosphere). What a
 * renderer asks of a medium: the transmittance exp(-integral sigma_t)
 * along a segment, exact where the medium is homogeneous and by ratio
 * tracking otherwise (Novak, Selle, Jarosz, "Residual Ratio Tracking",
 * SIGGRAPH 2014), and a distance to the next scattering event, exact in a
 * homogeneous medium (pbrt-v3 sec. 15.2.1) and by delta tracking
 * (Woodcock et al. 1965) under a majorant otherwise.
 * Tests: tests/medium/test_medium.c
 */
#ifndef SVET_MEDIUM_H
#define SVET_MEDIUM_H

#include "core/error.h"
#include "core/rng.h"
#include "materials/radiance.h"
#include "medium/phase.h"
#include "medium/volgrid.h"

/* A density given as a function, with a bound no value exceeds. */
typedef real (*medium_density_fn)(const void *ctx, const VECTOR3 p);

typedef struct {
    RADIANCE sigma_a, sigma_s; /* per unit length at density 1 */
    RADIANCE emission;         /* emitted radiance per unit length at
                                  density 1 (sigma_a times the radiance of
                                  an emitting medium in equilibrium) */
    phase_t phase;
    /* the density: exactly one of these, or none for 1 everywhere */
    const volgrid_t *grid;     /* channel 0 of a grid */
    medium_density_fn fn;
    const void *fn_ctx;
    real fn_max;               /* fn's bound, >= every value of fn */
} medium_t;

/* A homogeneous medium of the given coefficients and isotropic phase. */
medium_t medium_homogeneous(RADIANCE sigma_a, RADIANCE sigma_s);

/* Check the coefficients: finite and >= 0, emission finite and >= 0, HG's
 * g in (-PHASE_MAX_G, PHASE_MAX_G), a density grid's values >= 0 and a
 * function's bound finite and > 0. The message says which value is wrong;
 * the caller adds the file and line. Returns SVET_ERR_RANGE. */
svet_status medium_check(const medium_t *m, svet_error *err);

/* true when the density is 1 everywhere. */
bool medium_is_homogeneous(const medium_t *m);

/* The density at p: 1, the grid's trilinear value, or fn's. */
real medium_density(const medium_t *m, const VECTOR3 p);

/* The largest density anywhere: 1, the grid's largest value, fn_max. */
real medium_density_max(const medium_t *m);

/* sigma_t = sigma_a + sigma_s at density 1. */
RADIANCE medium_sigma_t(const medium_t *m);

/* Transmittance over a distance d of a homogeneous medium: Beer-Lambert,
 * exp(-sigma_t d) per channel. Can't fail. */
RADIANCE medium_tr_homogeneous(const medium_t *m, real d);

/* Transmittance along o + t dir (dir unit) for t in [0, tmax]: exact for
 * a homogeneous medium; otherwise ratio tracking, an unbiased estimate
 * that draws from g (steps under the majorant medium_density_max times
 * the largest channel of sigma_t). Can't fail. */
RADIANCE medium_tr(const medium_t *m, const VECTOR3 o, const VECTOR3 dir,
                   real tmax, pcg32_t *g);

/* Where light travelling from o along dir first interacts within tmax:
 * returns true with *t the distance of a scattering event, false when it
 * passes the segment. *weight is what the path's throughput is multiplied
 * by: sigma_s Tr / pdf at an event, Tr / P(pass) when it passes, per
 * channel. Homogeneous media sample the distance exactly in one channel
 * picked uniformly, the pdf being the channels' average (pbrt-v3 sec.
 * 15.2.1); others by delta tracking on the largest channel's majorant
 * with the per-channel ratio as weight. Draws from g. Can't fail. */
bool medium_sample(const medium_t *m, const VECTOR3 o, const VECTOR3 dir,
                   real tmax, pcg32_t *g, real *t, RADIANCE *weight);

#endif
