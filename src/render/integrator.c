/*
 * integrator.c - the path tracer of ch. 5 and its reduced variants.
 *
 * The rendering equation (ch. 3) at a surface point x seen along wo,
 *   L(x, wo) = L_e(x, wo) + int f(x, wi, wo) L(x', -wi) |cos theta_i| dwi,
 * is estimated by a random walk: at each vertex the emitted light is
 * added, the direct light is estimated by sampling a light (next-event
 * estimation), and the walk continues in a direction sampled from the
 * BSDF. Light reaching a vertex directly is thus found twice - by the light
 * sample and by the BSDF sample happening to hit the light - and the two
 * are weighted by the power heuristic (Veach 1997, sec. 9.2.3) so that each
 * counts where it is the better strategy. Delta components (mirror, glass)
 * and point lights can be reached by only one strategy, which then gets
 * weight 1.
 * `render light indirect` keeps the indirect diffuse light alone: at the
 * first non-specular vertex neither the light sample nor the emitter its
 * BSDF sample hits counts (nor what the camera saw before it), so what
 * remains is that vertex's reflection of light that has bounced at least
 * once more - the part the irradiance cache of ch. 9 computes.
 * Tests: tests/render/test_integrator.c
 */
#include "render/integrator.h"

#include <string.h>

#include "core/frame.h"
#include "materials/material.h"
#include "core/sample.h"

void integrator_init(integrator_t *it, const scene_t *s,
                     const lightset_t *lights, tracer_t tracer)
{
    memset(it, 0, sizeof *it);
    it->scene = s;
    it->lights = lights && lights->n > 0 ? lights : NULL;
    it->env = it->lights ? lightset_environment(it->lights) : -1;
    it->tracer = tracer;
    it->mode = s->render.integrator;
    it->max_depth = s->render.max_depth;
    it->roulette = s->render.roulette;
    it->roulette_depth = s->render.roulette_depth;
    it->ao_distance = s->render.ao_distance;
    it->indirect = s->render.light == SCENE_LIGHT_INDIRECT;
}

real integrator_mis_weight(real a, real b)
{
    if (!(a > 0))
        return 0;
    real r = b / a; /* a^2/(a^2+b^2) = 1/(1 + (b/a)^2) never overflows */
    return 1 / (1 + r * r);
}

static void draw2(real u[2], pcg32_t *g)
{
    u[0] = pcg32_real(g);
    u[1] = pcg32_real(g);
}

/* Next-event estimation at pp (integrator.h, integrator_nee): one light,
 * chosen by power, sampled once, weighted against the point's own
 * sampling by the power heuristic (unless the light is a point or that
 * sampling's hits are not counted). Returns the contribution before the
 * path throughput. Always draws 3 numbers (and then what shadow draws),
 * so the numbers of later bounces do not depend on what happened here. */
static RADIANCE direct_light(const integrator_t *it, const PATHPOINT *pp,
                             const integrator_scatter_t *sc, bool mis,
                             integrator_shadow_fn shadow,
                             const void *shadow_ctx, pcg32_t *g,
                             integrator_stats_t *st)
{
    real upick = pcg32_real(g), u[2];
    draw2(u, g);
    real pmf;
    const light_t *l = lightset_pick(it->lights, upick, &pmf);
    if (!l || !(pmf > 0))
        return rad_grey(0);
    light_sample_t ls;
    if (!light_sample(l, pp, sc->two, u, &ls))
        return rad_grey(0);
    /* the MIS weight needs the pdf pb of the point's own sampling of wi:
     * not for a point light (a delta, weight 1) nor when those samples'
     * hits are not counted, and then it is not made (NULL) */
    const bool weigh = !ls.delta && mis;
    real pb = 0, cosine = 1;
    RADIANCE f;
    if (sc->m) {
        VECTOR3 wi;
        frame_to_local(wi, ls.wi, pp->u, pp->v, pp->n);
        f = material_eval_pdf(sc->m, wi, sc->wo, weigh ? &pb : NULL);
        cosine = fabs(wi[Z]);
    } else {
        f = sc->eval(sc->ctx, ls.wi, weigh ? &pb : NULL);
    }
    if (rad_is_black(f) || rad_is_black(ls.Li))
        return rad_grey(0);
    /* visibility: a shadow ray between the two points, each offset off its
     * surface by its error bound (ray.h) */
    ray_t sr;
    real tmax;
    if (ls.infinite) {
        ray_spawn(&sr, pp->cross_point, pp->p_error, pp->ng, ls.wi);
        tmax = (real)INFINITY;
    } else {
        tmax = ray_spawn_to(&sr, pp->cross_point, pp->p_error, pp->ng, ls.p,
                            ls.p_error, ls.n);
    }
    /* the surfaces at its two ends cannot be met (accel.h) */
    const COBJECT *skip[2] = {
        pp->IntersectObj, ls.infinite || !l->emission ? NULL : l->emission->obj
    };
    RADIANCE tr = rad_grey(1);
    if (shadow) {
        tr = shadow(shadow_ctx, it, pp, &sr, tmax, skip, &ls, g, st);
        if (rad_is_black(tr))
            return rad_grey(0);
    } else {
        st->rays++;
        if (it->tracer.occluded(it->tracer.ctx, &sr, 0, tmax, skip))
            return rad_grey(0);
    }
    real w = 1;
    if (weigh) {
        real pl = pmf * ls.pdf_mis; /* light_pdf(l, pp, two, ls.wi, ls.p, ls.n) */
        w = integrator_mis_weight(pl, pb);
    }
    /* f L |cos| / p, with p = pmf * pdf (the point light's pdf is 1) */
    real scale = w * cosine / (pmf * ls.pdf);
    RADIANCE c = rad_scale(rad_mul(f, ls.Li), scale);
    return shadow ? rad_mul(c, tr) : c;
}

RADIANCE integrator_nee(const integrator_t *it, const PATHPOINT *pp,
                        const integrator_scatter_t *sc, bool mis,
                        integrator_shadow_fn shadow, const void *shadow_ctx,
                        pcg32_t *g, integrator_stats_t *st)
{
    if (!it->lights) {
        (void)pcg32_real(g); (void)pcg32_real(g); (void)pcg32_real(g);
        return rad_grey(0);
    }
    return direct_light(it, pp, sc, mis, shadow, shadow_ctx, g, st);
}

RADIANCE integrator_direct(const integrator_t *it, const PATHPOINT *pp,
                           const struct material *m, const VECTOR3 wo,
                           bool mis, pcg32_t *g, integrator_stats_t *st)
{
    if (!it->lights) {
        (void)pcg32_real(g); (void)pcg32_real(g); (void)pcg32_real(g);
        return rad_grey(0);
    }
    const integrator_scatter_t sc = { m, wo, m->transmits, NULL, NULL };
    return direct_light(it, pp, &sc, mis, NULL, NULL, g, st);
}

/* The camera ray's first hit, as the caller found it
 * (integrator_li_hit()). */
typedef struct {
    bool found;
    hit_t hit;
    const COBJECT *obj;
} first_t;

/* The camera ray's first hit: *first when the caller traced it (NULL:
 * traced here), so that both ways give the same bits. */
static bool first_hit(const integrator_t *it, const ray_t *r,
                      const first_t *first, hit_t *h,
                      const COBJECT **obj)
{
    if (!first)
        return it->tracer.intersect(it->tracer.ctx, r, 0, (real)INFINITY,
                                    NULL, h, obj);
    if (first->found) {
        *h = first->hit;
        *obj = first->obj;
    }
    return first->found;
}

static RADIANCE ambient_occlusion(const integrator_t *it, const ray_t *r,
                                  const first_t *first,
                                  pcg32_t *g, integrator_stats_t *st)
{
    hit_t h;
    const COBJECT *obj;
    real u[2];
    draw2(u, g);
    st->rays++;
    if (!first_hit(it, r, first, &h, &obj))
        return rad_grey(0);
    PATHPOINT pp;
    cobject_fill(obj, r, &h, &pp);
    /* cosine-weighted on the side the camera sees: the estimate of
     * (1/pi) int V cos dw is the fraction of unoccluded samples */
    VECTOR3 local, w;
    sample_cosine_hemisphere(local, u);
    if (SVECTOR3(pp.out, pp.n) < 0)
        local[Z] = -local[Z];
    frame_to_world(w, local, pp.u, pp.v, pp.n);
    ray_t s;
    ray_spawn(&s, pp.cross_point, pp.p_error, pp.ng, w);
    real tmax = it->ao_distance > 0 ? it->ao_distance : (real)INFINITY;
    const COBJECT *skip[2] = { obj, NULL }; /* the surface it leaves */
    st->rays++;
    return rad_grey(it->tracer.occluded(it->tracer.ctx, &s, 0, tmax, skip) ? 0
                                                                           : 1);
}

static RADIANCE li(const integrator_t *it, const ray_t *camera,
                   const first_t *first, pcg32_t *g, integrator_stats_t *st)
{
    st->paths++;
    if (it->mode == SCENE_INTEGRATOR_AO)
        return ambient_occlusion(it, camera, first, g, st);

    /* Light sampling runs in every mode but BSDF-only. The emitters that a
     * BSDF sample hits count, weighted by MIS where light sampling could
     * have found them too - except in the `nee` mode, which shows light
     * sampling alone: there they count only after a delta bounce, which
     * light sampling cannot follow. Direct lighting is the path tracer cut
     * after one scattering event. */
    bool nee = it->lights && it->mode != SCENE_INTEGRATOR_BSDF;
    const bool bsdf_hits = !(nee && it->mode == SCENE_INTEGRATOR_NEE);
    int max_depth = it->mode == SCENE_INTEGRATOR_DIRECT
                        ? (it->max_depth < 1 ? it->max_depth : 1)
                        : it->max_depth;
    const int env = it->env;

    RADIANCE L = rad_grey(0), beta = rad_grey(1);
    ray_t r = *camera;
    /* what the previous vertex needs for the MIS weight of an emitter that
     * the BSDF sample hits */
    bool prev_delta = true; /* the camera ray counts emission in full */
    real prev_pdf = 0;
    bool prev_two = false;
    /* the vertices in two buffers that swap at each bounce (no copy);
     * *prev is read only when prev_delta is false, i.e. after it is set */
    PATHPOINT buf[2];
    PATHPOINT *cur = &buf[0], *prev = &buf[1];
    /* the surface the ray leaves (none for the camera ray) */
    const COBJECT *skip[2] = { NULL, NULL };
    /* the camera ray's differentials, where the scene reads a texture
     * (scene.h): to each hit and through the delta bounces */
    const scene_raydiff_ops_t *dops = it->scene->raydiff;
    raydiff_t rdiff;
    bool diff = dops != NULL;
    if (diff)
        dops->camera(it->scene->raydiff_ctx, &r, &rdiff);
    /* with it->indirect: 0 until the first non-specular vertex, 1 on the
     * ray that leaves it, 2 after; light found counts only at 2 */
    int stage = it->indirect ? 0 : 2;

    for (int depth = 0;; depth++) {
        hit_t h;
        const COBJECT *obj = NULL;
        st->rays++;
        bool hit = depth == 0 ? first_hit(it, &r, first, &h, &obj)
                              : it->tracer.intersect(it->tracer.ctx, &r, 0,
                                                     (real)INFINITY, skip,
                                                     &h, &obj);
        /* Light found by this ray: counted in full from the camera and
         * after a delta bounce; after a sampled bounce weighted against
         * light sampling. */
        bool count = (depth == 0 || prev_delta || bsdf_hits) && stage == 2;
        if (!hit) {
            if (it->scene->has_environment && count) {
                VECTOR3 d;
                vec_normalize(d, r.d);
                real w = 1;
                if (!prev_delta && nee && env >= 0) {
                    real pl = lightset_pmf(it->lights, env) *
                              light_pdf(&it->lights->lights[env], prev,
                                        prev_two, d, d, d);
                    w = integrator_mis_weight(prev_pdf, pl);
                }
                L = rad_add(L, rad_scale(rad_mul(beta, it->scene->environment),
                                         w));
            }
            break;
        }
        PATHPOINT *pp = cur;
        cobject_fill(obj, &r, &h, pp);
        if (diff)
            diff = dops->hit(&rdiff, &r, pp);

        if (obj->light && count) {
            RADIANCE Le = light_emitted(obj->light, pp);
            if (!rad_is_black(Le)) {
                real w = 1;
                if (!prev_delta && nee) {
                    int li = lightset_find_area(it->lights, obj);
                    real pl = lightset_pmf(it->lights, li) *
                              light_pdf(&it->lights->lights[li], prev,
                                        prev_two, r.d, pp->cross_point, pp->ng);
                    w = integrator_mis_weight(prev_pdf, pl);
                }
                L = rad_add(L, rad_scale(rad_mul(beta, Le), w));
            }
        }
        if (stage == 1)
            stage = 2;
        if (depth >= max_depth)
            break;

        const material_t *m = obj->material;
        /* a part's per-hit shading (a texture, a bump map: scene.h) */
        material_t shaded;
        if (obj->texture)
            m = it->scene->shade(it->scene, obj, &r, depth, pp,
                                 diff ? &rdiff : NULL, &shaded);
        /* whether light from behind the surface can scatter toward the
         * viewer (rho_t or rho_dt not black, found by material_init) */
        const bool two = m->transmits;
        VECTOR3 wo;
        frame_to_local(wo, pp->out, pp->u, pp->v, pp->n);
        /* the first non-specular vertex of `light indirect` */
        const bool first_diffuse = stage == 0 && !material_is_specular(m);
        if (nee && !material_is_specular(m) && !first_diffuse) {
            const integrator_scatter_t sc = { m, wo, two, NULL, NULL };
            RADIANCE Ld = direct_light(it, pp, &sc, bsdf_hits, NULL, NULL, g,
                                       st);
            /* with bsdf_hits false the light sample's weight is 1 */
            L = rad_add(L, rad_mul(beta, Ld));
        } else if (nee) {
            /* keep the draw count of a bounce fixed */
            (void)pcg32_real(g); (void)pcg32_real(g); (void)pcg32_real(g);
        }

        /* continue the path by sampling the BSDF */
        real u[3] = { pcg32_real(g), pcg32_real(g), pcg32_real(g) };
        brdf_sample_t bs;
        if (!material_sample(m, wo, u, &bs))
            break;
        if (first_diffuse) {
            /* only its non-delta parts' reflection is the diffuse light */
            if (bs.delta)
                break;
            stage = 1;
        }
        beta = rad_mul(beta, bs.weight);
        VECTOR3 wi;
        frame_to_world(wi, bs.wi, pp->u, pp->v, pp->n);
        if (diff)
            diff = bs.delta && dops->scatter(&rdiff, &r, pp, m, wi);
        cur = prev; /* the next vertex overwrites the one before this */
        prev = pp;
        prev_delta = bs.delta;
        prev_pdf = bs.pdf;
        prev_two = two;
        ray_spawn(&r, pp->cross_point, pp->p_error, pp->ng, wi);
        skip[0] = obj;

        if (!integrator_roulette(it, depth + 1, g, &beta))
            break;
        if (rad_is_black(beta))
            break;
    }
    return L;
}

bool integrator_roulette(const integrator_t *it, int events, pcg32_t *g,
                         RADIANCE *beta)
{
    /* continue with probability q, dividing by q keeps the estimate
     * unbiased; q follows the throughput so that dim paths end early,
     * and is at least 0.05 */
    real urr = pcg32_real(g);
    if (it->roulette && events >= it->roulette_depth) {
        /* as fmin(1, fmax(0.05, .)), a NaN throughput included, without
         * the libm calls */
        real q = real_min(real_max(rad_max(*beta), REAL_C(0.05)),
                          REAL_C(1.0));
        if (urr >= q)
            return false;
        *beta = rad_scale(*beta, 1 / q);
    }
    return true;
}

RADIANCE integrator_li(const integrator_t *it, const ray_t *camera,
                       pcg32_t *g, integrator_stats_t *st)
{
    return li(it, camera, NULL, g, st);
}

RADIANCE integrator_li_hit(const integrator_t *it, const ray_t *camera,
                           bool found, const hit_t *hit, const COBJECT *obj,
                           pcg32_t *g, integrator_stats_t *st)
{
    first_t first = { found, { 0, 0, { 0, 0, 0 } }, obj };
    if (found)
        first.hit = *hit;
    return li(it, camera, &first, g, st);
}
