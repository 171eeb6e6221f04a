/*
 * integrator.h - the estimators of the rendering equation (ch. 3, eq. of
 * Kajiya 1986) by the Monte Carlo method of ch. 4, in the cases ch. 5 walks
 * through: a path tracer with next-event estimation (light sampling) and
 * BSDF sampling combined by multiple importance sampling with the power
 * heuristic (Veach 1997, sec. 9.2), Russian roulette, and the reduced
 * strategies ch. 5 compares: direct lighting only, BSDF sampling only, and
 * ambient occlusion.
 * Tests: tests/render/test_integrator.c (analytic scenes with exact answers)
 */
#ifndef SVET_INTEGRATOR_H
#define SVET_INTEGRATOR_H

#include <stdint.h>
#include "materials/cobject.h"
#include "render/light.h"
#include "materials/radiance.h"
#include "core/rng.h"
#include "render/scene.h"
#include "render/tracer.h"

typedef struct {
    const scene_t *scene;
    const lightset_t *lights;   /* NULL or empty when the scene has none */
    int env;                    /* lightset_environment(lights), found once
                                   by integrator_init (-1: none) */
    tracer_t tracer;
    scene_integrator mode;      /* path, direct, bsdf, ao */
    int max_depth;              /* scattering events (scene.h) */
    bool roulette;
    int roulette_depth;
    real ao_distance;           /* 0 = unlimited */
    bool indirect;              /* `render light indirect` (scene.h): the
                                   indirect diffuse light alone */
} integrator_t;

/* Per-thread counters. */
typedef struct integrator_stats {
    uint64_t rays;        /* every ray traced: camera, bounce and shadow */
    uint64_t paths;
} integrator_stats_t;

/* Set up from a scene's render settings. `lights` may be NULL when the
 * scene has none; it must not change while `it` is in use (its
 * environment light is looked up here once). This function can't fail. */
void integrator_init(integrator_t *it, const scene_t *s,
                     const lightset_t *lights, tracer_t tracer);

/* The radiance arriving at the camera along -r.d, estimated from one path
 * whose random numbers are drawn from g in a fixed order. Never negative;
 * may be NaN only if the scene's data is (the caller counts those). */
RADIANCE integrator_li(const integrator_t *it, const ray_t *r, pcg32_t *g,
                       integrator_stats_t *st);

/* integrator_li() of a camera ray r whose nearest hit over (0, inf) the
 * caller has found already: found, and then *hit and obj as
 * tracer_t.intersect leaves them (read only when found). The same
 * estimate, bit for bit, and the same random numbers, without tracing r
 * again (it is still counted in st->rays). This function can't fail. */
RADIANCE integrator_li_hit(const integrator_t *it, const ray_t *r, bool found,
                           const hit_t *hit, const COBJECT *obj, pcg32_t *g,
                           integrator_stats_t *st);

/* The path tracer's next-event estimation at a surface point pp of
 * material m, seen along wo (local frame): one light chosen by power,
 * sampled once, its shadow ray traced, weighted against BSDF sampling by
 * the power heuristic when mis (else weight 1: light sampling alone, for
 * a method that does not count emitters its BSDF samples hit; the photon
 * maps of ch. 8). Draws 3 numbers from g; black without lights. This
 * function can't fail. */
RADIANCE integrator_direct(const integrator_t *it, const PATHPOINT *pp,
                           const struct material *m, const VECTOR3 wo,
                           bool mis, pcg32_t *g, integrator_stats_t *st);

/* What scatters light at the point of a light sample (integrator_nee): a
 * surface's material m, seen along wo (pp's local frame), or, when m is
 * NULL, the caller's eval: f per unit solid angle toward wi (world, unit;
 * any cosine included) and, when pdf is not NULL, the pdf of the caller's
 * own sampling of wi there (a medium's phase function, ch. 11). two: light
 * from both sides counts (a surface that transmits; a medium). */
typedef struct {
    const struct material *m;
    const real *wo;
    bool two;
    RADIANCE (*eval)(const void *ctx, const VECTOR3 wi, real *pdf);
    const void *ctx;
} integrator_scatter_t;

/* The transmittance of the shadow ray *sr over (0, tmax) from pp toward
 * the light sample ls, skip its two end surfaces: black when blocked,
 * less than 1 through a medium (ch. 11). It may draw from g and counts
 * the rays it traces in st. */
typedef RADIANCE (*integrator_shadow_fn)(const void *ctx,
                                         const integrator_t *it,
                                         const PATHPOINT *pp, const ray_t *sr,
                                         real tmax,
                                         const COBJECT *const skip[2],
                                         const light_sample_t *ls, pcg32_t *g,
                                         integrator_stats_t *st);

/* Next-event estimation at pp, the one the path tracer makes at surfaces
 * (integrator_direct) and ch. 11's estimators at surfaces and points of
 * a medium: one light chosen by power, sampled once, f from sc, the
 * shadow ray's transmittance from shadow (NULL: the tracer's occlusion
 * test, 0 or 1), weighted against sc's own sampling by the power
 * heuristic when mis (else weight 1). Draws 3 numbers from g, then what
 * shadow draws; black without lights. This function can't fail. */
RADIANCE integrator_nee(const integrator_t *it, const PATHPOINT *pp,
                        const integrator_scatter_t *sc, bool mis,
                        integrator_shadow_fn shadow, const void *shadow_ctx,
                        pcg32_t *g, integrator_stats_t *st);

/* The power heuristic with beta = 2 for two strategies with densities a
 * (the one used) and b: a^2 / (a^2 + b^2), computed without overflow;
 * 0 when a is 0. */
real integrator_mis_weight(real a, real b);

/* Russian roulette (ch. 4) after a path's events-th scattering event
 * (surface or medium): draws one number from g whether or not roulette
 * is on, so the stream does not depend on it; when it->roulette and
 * events >= it->roulette_depth the path goes on with probability q =
 * min(1, max(0.05, max channel of *beta)), *beta divided by q (unbiased).
 * Returns false when the path ends. The path tracer and volpath's walk
 * share it. */
bool integrator_roulette(const integrator_t *it, int events, pcg32_t *g,
                         RADIANCE *beta);

#endif
