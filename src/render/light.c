/*
 * light.c - sampling the lights of ch. 5 for next-event estimation, and
 * their densities for MIS (Veach 1997, sec. 9.2). Area lights are sampled
 * by area and converted to solid angle, p_w = p_A d^2 / |cos theta_l|
 * (pbrt-v3 sec. 14.2); the environment by a cosine-weighted hemisphere
 * about the shading normal, so a diffuse surface under a uniform sky is
 * estimated with zero variance.
 * Tests: tests/render/test_light.c
 */
#include "render/light.h"

#include <stdlib.h>
#include <string.h>

#include "core/frame.h"
#include "core/sample.h"

static real luminance_power(RADIANCE c, real scale)
{
    return fmax(REAL_C(0.0), rad_luminance(c)) * scale;
}

svet_status lightset_build(lightset_t *ls, const scene_t *s, svet_error *err)
{
    memset(ls, 0, sizeof *ls);
    int n = s->npoint_lights + s->nemitters + (s->has_environment ? 1 : 0);
    if (n == 0)
        return SVET_OK;
    ls->lights = calloc((size_t)n, sizeof *ls->lights);
    ls->cdf = calloc((size_t)n + 1, sizeof *ls->cdf);
    if (!ls->lights || !ls->cdf) {
        lightset_free(ls);
        return svet_error_set(err, SVET_ERR_NOMEM, "lights: out of memory");
    }
    /* The scene's bounding sphere, for the environment's power. An
     * object of infinite area (a plane, whose bounds span the reals) is
     * left out: with it the power would overflow, and the environment
     * would take every light sample from the other lights. */
    bbox_t all;
    bbox_empty(&all);
    for (int i = 0; i < s->nobjects; i++) {
        const COBJECT *o = s->objects[i];
        bbox_t b;
        o->ops->bounds(o, -1, &b);
        if (!bbox_is_empty(&b) && vec_is_finite(b.min) &&
            vec_is_finite(b.max) && isfinite(o->ops->area(o)))
            bbox_union(&all, &b);
    }
    if (bbox_is_empty(&all)) {
        vec_set(ls->centre, 0, 0, 0);
        ls->radius = 1;
    } else {
        bbox_centroid(ls->centre, &all);
        ls->radius = REAL_C(0.5) * vec_distance(all.max, all.min);
    }
    int k = 0;
    for (int i = 0; i < s->npoint_lights; i++, k++) {
        light_t *l = &ls->lights[k];
        l->kind = LIGHT_POINT;
        vec_copy(l->position, s->point_lights[i].position);
        l->intensity = s->point_lights[i].intensity;
        l->power = luminance_power(l->intensity, 4 * REAL_PI); /* Phi = 4 pi I */
    }
    for (int i = 0; i < s->nemitters; i++, k++) {
        light_t *l = &ls->lights[k];
        l->kind = LIGHT_AREA;
        l->emission = s->emitters[i];
        const COBJECT *o = l->emission->obj;
        /* Lambertian emitter: Phi = pi L A per emitting side */
        real sides = l->emission->two_sided ? 2 : 1;
        real area = o->ops->area(o);
        l->area = area;
        l->power = isfinite(area)
                       ? luminance_power(l->emission->radiance,
                                         sides * REAL_PI * area)
                       : 0;
    }
    if (s->has_environment) {
        light_t *l = &ls->lights[k++];
        l->kind = LIGHT_ENVIRONMENT;
        l->radiance = s->environment;
        l->power = luminance_power(l->radiance, REAL_PI * REAL_PI *
                                                    ls->radius * ls->radius);
    }
    ls->n = n;
    real total = 0;
    for (int i = 0; i < n; i++)
        total += ls->lights[i].power;
    ls->cdf[0] = 0;
    for (int i = 0; i < n; i++)
        ls->cdf[i + 1] = ls->cdf[i] + (total > 0 ? ls->lights[i].power / total
                                                 : REAL_C(1.0) / (real)n);
    ls->cdf[n] = 1;
    return SVET_OK;
}

void lightset_free(lightset_t *ls)
{
    free(ls->lights);
    free(ls->cdf);
    memset(ls, 0, sizeof *ls);
}

int lightset_find_area(const lightset_t *ls, const COBJECT *obj)
{
    for (int i = 0; i < ls->n; i++)
        if (ls->lights[i].kind == LIGHT_AREA && ls->lights[i].emission->obj == obj)
            return i;
    return -1;
}

int lightset_environment(const lightset_t *ls)
{
    for (int i = 0; i < ls->n; i++)
        if (ls->lights[i].kind == LIGHT_ENVIRONMENT)
            return i;
    return -1;
}

RADIANCE light_emitted(const scene_emission_t *e, const PATHPOINT *on)
{
    if (e->two_sided || SVECTOR3(on->out, on->ng) > 0)
        return e->radiance_at ? e->radiance_at(e, on) : e->radiance;
    return rad_grey(0);
}

RADIANCE light_emitted_at_sample(const scene_emission_t *e,
                                 const cobject_sample_t *cs)
{
    if (!e->radiance_at)
        return e->radiance;
    const COBJECT *o = e->obj;
    /* the ray starts a small height above the point: well clear of the
     * point's error bound, and a ten-thousandth of the object's size, so
     * that no other fold of the object lies between it and the point */
    bbox_t b;
    o->ops->bounds(o, -1, &b);
    real size = bbox_is_empty(&b) ? 1 : vec_distance(b.max, b.min);
    real err = real_max(real_max(fabs(cs->p_error[X]), fabs(cs->p_error[Y])),
                        fabs(cs->p_error[Z]));
    real h = real_max(REAL_C(1e-4) * (isfinite(size) ? size : 1), 64 * err);
    ray_t r;
    for (int k = 0; k < 3; k++) {
        r.o[k] = cs->p[k] + h * cs->n[k];
        r.d[k] = -cs->n[k];
    }
    hit_t hit;
    PATHPOINT pp;
    if (cobject_intersect(o, &r, 0, 2 * h, &hit)) {
        cobject_fill(o, &r, &hit, &pp);
    } else {
        memset(&pp, 0, sizeof pp);
        vec_copy(pp.cross_point, cs->p);
        vec_copy(pp.ng, cs->n);
        vec_copy(pp.n, cs->n);
        vec_copy(pp.out, cs->n);
        pp.IntersectObj = o;
    }
    return e->radiance_at(e, &pp);
}

/* The environment is sampled cosine-weighted about the shading normal, on
 * the side of `out` (or on both sides, each with probability 1/2, when the
 * material transmits): the density |cos| / pi, halved when two-sided. */
static real env_pdf(const PATHPOINT *pp, bool two_sided, const VECTOR3 wi)
{
    real c = SVECTOR3(wi, pp->n);
    real side = SVECTOR3(pp->out, pp->n) >= 0 ? 1 : -1;
    if (two_sided)
        return fabs(c) * REAL_INV_PI * REAL_C(0.5);
    return c * side > 0 ? c * side * REAL_INV_PI : 0;
}

/* An area light's solid-angle density for MIS, p_A d^2 / cos_l with
 * uniform area sampling, p_A = 1/A (every app. D primitive): d2 the
 * squared distance, cos_l > 0 the cosine at the light. light_sample()'s
 * pdf_mis and light_pdf() both make it here, so that they agree bit for
 * bit (the MIS weights of a path sum to 1 only then). */
static inline real area_pdf(const light_t *l, real d2, real cos_l)
{
    real area = l->area; /* o->ops->area(o), as lightset_build asked */
    if (!(cos_l > 0) || !(area > 0) || !isfinite(area))
        return 0;
    return d2 / (area * cos_l);
}

bool light_sample(const light_t *l, const PATHPOINT *pp, bool two_sided,
                  const real u[2], light_sample_t *s)
{
    /* every field is set on a true return below (what a memset of *s
     * first gave, without writing the fields twice) */
    switch (l->kind) {
    case LIGHT_POINT: {
        VECTOR3 d;
        vec_sub(d, l->position, pp->cross_point);
        real d2 = vec_length2(d);
        if (!(d2 > 0) || vec_normalize(s->wi, d) == 0)
            return false;
        s->Li = rad_scale(l->intensity, 1 / d2); /* inverse-square law */
        s->pdf = 1;
        s->pdf_mis = 0;
        s->delta = true;
        s->infinite = false;
        vec_copy(s->p, l->position);
        vec_copy(s->n, s->wi); /* any normal: p has no error to offset */
        vec_set(s->p_error, 0, 0, 0);
        return true;
    }
    case LIGHT_AREA: {
        const COBJECT *o = l->emission->obj;
        cobject_sample_t cs;
        o->ops->sample(o, u, &cs);
        VECTOR3 d;
        vec_sub(d, cs.p, pp->cross_point);
        real d2 = vec_length2(d);
        if (!(d2 > 0) || !(cs.pdf > 0) || vec_normalize(s->wi, d) == 0)
            return false;
        real cos_l = -SVECTOR3(s->wi, cs.n);
        if (!l->emission->two_sided && cos_l <= 0)
            return false; /* the back of a one-sided emitter */
        cos_l = fabs(cos_l);
        if (!(cos_l > 0))
            return false;
        s->pdf = cs.pdf * d2 / cos_l; /* area to solid angle */
        if (!isfinite(s->pdf))
            return false;
        /* light_pdf() on (wi, p, n) = (s->wi, cs.p, cs.n) makes this
         * cos_l, d and d2 again by the same operations on the same
         * numbers */
        s->pdf_mis = area_pdf(l, d2, cos_l);
        s->Li = light_emitted_at_sample(l->emission, &cs);
        s->delta = false;
        s->infinite = false;
        vec_copy(s->p, cs.p);
        vec_copy(s->n, cs.n);
        vec_copy(s->p_error, cs.p_error);
        return true;
    }
    case LIGHT_ENVIRONMENT: {
        VECTOR3 local;
        real side = SVECTOR3(pp->out, pp->n) >= 0 ? 1 : -1;
        real v[2] = { u[0], u[1] };
        if (two_sided) {
            /* u[0] < 1/2 keeps the side of `out`, else the other side; u[0]
             * is stretched back to [0,1) for the hemisphere */
            if (u[0] >= REAL_C(0.5))
                side = -side;
            v[0] = u[0] < REAL_C(0.5) ? 2 * u[0] : 2 * u[0] - 1;
        }
        sample_cosine_hemisphere(local, v);
        local[Z] *= side;
        frame_to_world(s->wi, local, pp->u, pp->v, pp->n);
        s->pdf = env_pdf(pp, two_sided, s->wi);
        if (!(s->pdf > 0))
            return false;
        s->pdf_mis = s->pdf; /* light_pdf() is env_pdf() on the same wi */
        s->Li = l->radiance;
        s->delta = false;
        s->infinite = true;
        vec_set(s->p, 0, 0, 0);
        vec_set(s->n, 0, 0, 0);
        vec_set(s->p_error, 0, 0, 0);
        return true;
    }
    }
    return false;
}

real light_pdf(const light_t *l, const PATHPOINT *pp, bool two_sided,
               const VECTOR3 wi, const VECTOR3 p, const VECTOR3 ng)
{
    switch (l->kind) {
    case LIGHT_POINT:
        return 0;
    case LIGHT_AREA: {
        real cos_l = -SVECTOR3(wi, ng);
        if (!l->emission->two_sided && cos_l <= 0)
            return 0;
        cos_l = fabs(cos_l);
        VECTOR3 d;
        vec_sub(d, p, pp->cross_point);
        return area_pdf(l, vec_length2(d), cos_l);
    }
    case LIGHT_ENVIRONMENT:
        return env_pdf(pp, two_sided, wi);
    }
    return 0;
}
