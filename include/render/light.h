/*
 * light.h - the light sources of ch. 5 at render time: a point isotropic
 * source, an area light (an emitting COBJECT) and a uniform environment.
 * For next-event estimation each can be sampled from a shading point, and
 * for multiple importance sampling (Veach 1997, ch. 9) each gives the
 * density with which it would have produced a given direction.
 * The set of lights, with the choice of one light in proportion to its
 * power, is built only when the scene has lights.
 * Tests: tests/render/test_light.c
 */
#ifndef SVET_LIGHT_H
#define SVET_LIGHT_H

#include "materials/cobject.h"
#include "core/error.h"
#include "materials/radiance.h"
#include "render/scene.h"

typedef enum {
    LIGHT_POINT,       /* delta position: reached only by sampling it */
    LIGHT_AREA,        /* an emitting surface, L_e constant (Lambertian) */
    LIGHT_ENVIRONMENT  /* radiance L_env from every direction at infinity */
} light_kind;

typedef struct {
    light_kind kind;
    VECTOR3 position;      /* point light */
    RADIANCE intensity;    /* point light, W/sr */
    const scene_emission_t *emission; /* area light: radiance, sidedness,
                                         the emitting object */
    real area;             /* area light: its object's area(), asked once
                              by lightset_build for light_pdf() */
    RADIANCE radiance;     /* environment */
    real power;            /* luminance of the emitted power (W), used to
                              choose among lights */
} light_t;

/* What light_sample() returns. */
typedef struct {
    VECTOR3 wi;        /* unit direction from the shading point to the light */
    RADIANCE Li;       /* radiance arriving along -wi, before visibility;
                          for a point light, I / d^2 (irradiance per unit
                          projected area, the delta's integral) */
    real pdf;          /* density of wi per unit solid angle; for a point
                          light 1 (a delta: no MIS) */
    real pdf_mis;      /* light_pdf(l, pp, two_sided, wi, p, n), the
                          density the MIS weights use, bit for bit (0 for
                          a point light), made from the numbers the sample
                          already has */
    bool delta;        /* point light */
    bool infinite;     /* environment: the shadow ray runs to infinity */
    VECTOR3 p;         /* the point on the light (not for the environment) */
    VECTOR3 n;         /* its normal (area light) */
    VECTOR3 p_error;   /* its error bound (area light) */
} light_sample_t;

/* The lights of a scene, and a discrete distribution over them. */
typedef struct {
    light_t *lights;
    int n;
    real *cdf;          /* n + 1 entries, cdf[0] = 0, cdf[n] = 1 */
    VECTOR3 centre;     /* bounding sphere of the scene, for the power of */
    real radius;        /* the environment (pi L pi r^2, pbrt-v3 14.2.4) */
} lightset_t;

/* Collect the point lights, emitting objects and environment of s into ls.
 * A scene without lights gives an empty set (n = 0) and allocates nothing.
 * Returns SVET_ERR_NOMEM on allocation failure. */
svet_status lightset_build(lightset_t *ls, const scene_t *s, svet_error *err);
void lightset_free(lightset_t *ls);

/* The probability lightset_pick gives the light at index i (0 for an
 * index out of range). Inline, as lightset_pick: the integrator picks a
 * light at every vertex. This function can't fail. */
static inline real lightset_pmf(const lightset_t *ls, int i)
{
    if (i < 0 || i >= ls->n)
        return 0;
    return ls->cdf[i + 1] - ls->cdf[i];
}

/* Choose a light with probability proportional to its power (uniformly if
 * all powers are 0) using u in [0,1); *pmf receives that probability.
 * NULL for an empty set. This function can't fail. */
static inline const light_t *lightset_pick(const lightset_t *ls, real u,
                                           real *pmf)
{
    if (ls->n == 0) {
        *pmf = 0;
        return NULL;
    }
    /* the first i with cdf[i+1] > u, skipping lights of zero probability */
    int lo = 0, hi = ls->n - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (ls->cdf[mid + 1] > u)
            hi = mid;
        else
            lo = mid + 1;
    }
    *pmf = lightset_pmf(ls, lo);
    return &ls->lights[lo];
}
/* The index of the area light of emitting object obj, or -1. */
int lightset_find_area(const lightset_t *ls, const COBJECT *obj);
/* The index of the environment light, or -1. */
int lightset_environment(const lightset_t *ls);

/* Sample light l as seen from the shading point pp (its cross_point,
 * frame, and `out` side). `two_sided` says whether the material at pp can
 * scatter light arriving from behind (transmission): an environment is
 * then sampled over the whole sphere, else over the hemisphere of pp.out.
 * Returns false when the sample carries nothing (the back of a one-sided
 * emitter, a degenerate configuration); *s is then unspecified. On true
 * every field of *s is set (p, n and p_error zero where they mean
 * nothing). This function can't fail. */
bool light_sample(const light_t *l, const PATHPOINT *pp, bool two_sided,
                  const real u[2], light_sample_t *s);

/* The solid-angle density of direction wi, reaching the light at point p
 * with geometric normal ng (ignored for the environment), for the MIS
 * weights: exact for point-free lights and for area lights whose sample()
 * is uniform by area (every primitive of app. D), p_A = 1/A. The integrator
 * uses this one function (or light_sample_t.pdf_mis, its value for the
 * sampled direction bit for bit) on both sides of the power heuristic, so
 * the weights of a path sum to 1 and the estimate stays unbiased even where
 * a transformed curved emitter samples non-uniformly. 0 for point lights. */
real light_pdf(const light_t *l, const PATHPOINT *pp, bool two_sided,
               const VECTOR3 wi, const VECTOR3 p, const VECTOR3 ng);

/* Radiance emitted by the area light record e at the surface point `on`
 * toward the direction on->out: e->radiance (or, for a textured emitter,
 * e->radiance_at there) on an emitting side, else black. This function
 * can't fail. */
RADIANCE light_emitted(const scene_emission_t *e, const PATHPOINT *on);

/* Radiance emitted at the point cs that e's object's sample() drew, on
 * the side its normal faces: e->radiance, or for a textured emitter
 * e->radiance_at at the PATHPOINT a ray coming down onto cs->p along
 * -cs->n finds (the object's own surface(), so the texture is read at the
 * (s, t) a camera ray meeting that point reads; where that ray misses,
 * numerically, at cs->p with (s, t) = (0, 0)). Light sampling and photon
 * emission read it. This function can't fail. */
RADIANCE light_emitted_at_sample(const scene_emission_t *e,
                                 const cobject_sample_t *cs);

#endif
