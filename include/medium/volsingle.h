/*
 * volsingle.h - the ray march of ch. 11's single scattering (`render
 * integrator volsingle`, src/medium/volsingle.c), which the volume photon
 * map (volphoton.c) marches its camera rays with too: along a segment in
 * a medium, points t_i = (i + u) h from a jittered start, each adding the
 * light sampled there, the medium's emission and, for the photon map,
 * the multiply scattered light of its volume estimate, weighted by the
 * transmittance from the segment's start.
 * Tests: tests/medium/test_volsingle.c
 */
#ifndef SVET_VOLSINGLE_H
#define SVET_VOLSINGLE_H

#include <stdbool.h>

#include "core/rng.h"
#include "core/ray.h"
#include "medium/medium.h"
#include "render/integrator.h"

/* Where a segment to infinity ends in a medium: any positive extinction
 * makes exp(-sigma_t VOLPATH_FAR) 0, and a zero one gives 1 where an
 * infinite length would give exp(-0 inf), NaN. */
#define VOLPATH_FAR REAL_C(1e30)

/* What the march adds at a point x of med besides the light sampled
 * there, per unit length: sigma_s(x) L_i(x, -dir) of the light scattered
 * more than once (the volume photon map's estimate). */
typedef RADIANCE (*volsingle_inscatter_fn)(const void *ctx,
                                           const medium_t *med,
                                           const VECTOR3 x, const VECTOR3 dir);

/* What the media's methods prepare (volpath_prepare): the camera's
 * medium, whether shadow rays must look for invisible boundaries, the
 * march's step and what it adds at each point. */
typedef struct {
    const medium_t *global; /* the camera's medium: the scene's, or NULL */
    bool invisible;         /* some boundary is invisible: shadow rays
                               must find where they cross it */
    real step;              /* > 0: the march step; 0: volpath */
    volsingle_inscatter_fn inscatter; /* NULL: single scattering only */
    const void *inscatter_ctx;
} volpath_state_t;

/* The light scattered toward the ray's origin along ray (unit dir) over
 * [0, len] in med (len VOLPATH_FAR: to infinity, homogeneous media
 * only), marched with step s->step: at each point the medium's emission,
 * s->inscatter's term (when not NULL) and, when nee, a light sampled
 * (integrator_nee with shadow rays through the scene's boundaries); *tr
 * the segment's transmittance, exact in a homogeneous medium, the
 * trapezoid rule on the optical depth at the march's points otherwise.
 * Draws from g, its first number the jittered start. Can't fail. */
RADIANCE volsingle_march(const volpath_state_t *s, const integrator_t *it,
                         const medium_t *med, const ray_t *ray,
                         const VECTOR3 dir, real len, bool nee, pcg32_t *g,
                         integrator_stats_t *st, RADIANCE *tr);

#endif
