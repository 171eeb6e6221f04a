/*
 * volpath.c - volumetric path tracing (ch. 11): `render integrator
 * volpath`. The volume rendering equation (pbrt-v3 sec. 15.1, eq. 15.1)
 *   L(x, w) = Tr(x, y) L(y, w)
 *           + int_0^t Tr(x, x_s) sigma_s(x_s) int p(w, w') L(x_s, w') dw' ds
 * is estimated by a random walk that samples, along each segment in a
 * medium, the distance to the next scattering event (medium_sample: exact
 * in homogeneous media, delta tracking in grids; pbrt-v3 sec. 15.2.1 and
 * 15.2.2). At every scattering event and at every non-specular surface a
 * light is sampled, its shadow ray weighted by the transmittance (ratio
 * tracking, Novak et al. 2014), and combined with phase or BSDF sampling
 * by the power heuristic (Veach 1997, sec. 9.2) exactly as ch. 5's path
 * tracer combines light and BSDF sampling at surfaces (integrator.c);
 * where the scene has no medium the two estimate the same image.
 * Boundaries follow pbrt-v3's medium interface (medpart.h); an invisible
 * boundary only changes the medium of the rays that cross it.
 * Tests: tests/medium/test_medpart.c
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/frame.h"
#include "materials/material.h"
#include "medpart_data.h"
#include "render/integrator.h"
#include "render/render.h"

/* Where a segment to infinity ends in a medium: any positive extinction
 * makes exp(-sigma_t VOLPATH_FAR) 0, and a zero one gives 1 where an
 * infinite length would give exp(-0 inf), NaN. */
#define VOLPATH_FAR REAL_C(1e30)

/* The most invisible boundaries one segment may cross before the path
 * is given up (a ray caught between coincident surfaces). */
#define VOLPATH_MAX_CROSSINGS 256

typedef struct {
    const medium_t *global; /* the camera's medium: the scene's, or NULL */
    bool invisible;         /* some boundary is invisible: shadow rays
                               must find where they cross it */
} state_t;

static svet_status prepare(void **out, const render_t *r, int threads,
                           svet_error *err)
{
    (void)threads;
    state_t *s = calloc(1, sizeof *s);
    if (!s)
        return svet_error_set(err, SVET_ERR_NOMEM, "volpath: out of memory");
    s->global = medpart_global(r->scene);
    const medpart_data_t *d = scene_part_data(r->scene, "medium");
    for (int i = 0; d && i < d->nsides; i++)
        s->invisible |= d->sides[i]->rec.invisible;
    *out = s;
    return SVET_OK;
}

static void state_free(void *p)
{
    free(p);
}

/* The medium a ray leaving a surface of obj (normal ng) in direction w
 * is in: the side's for a boundary, else the medium it was in. */
static const medium_t *medium_after(const COBJECT *obj, const VECTOR3 ng,
                                    const VECTOR3 w, const medium_t *med)
{
    if (!obj->inside)
        return med;
    return SVECTOR3(w, ng) < 0 ? obj->inside->m : obj->outside->m;
}

/* Transmittance over t in [0, len] of ray r (unit dir) in med. Only a
 * homogeneous medium (the global medium is one) reaches infinity; a ray
 * in a bounded medium that finds no exit has slipped past its boundary by
 * rounding (started within the intersection's epsilon of it), and is
 * taken to be outside: tracking to infinity under a grid's clamped
 * border density would not end. */
static RADIANCE segment_tr(const medium_t *med, const ray_t *r,
                           const VECTOR3 dir, real len, pcg32_t *g)
{
    if (!med || !(len < VOLPATH_FAR || medium_is_homogeneous(med)))
        return rad_grey(1);
    return medium_tr(med, r->o, dir, len < VOLPATH_FAR ? len : VOLPATH_FAR,
                     g);
}

/* The transmittance of the shadow ray sr over (0, tmax) toward the light
 * sample ls, starting in med: 0 when a surface blocks it; through
 * invisible boundaries, changing medium at each. */
static RADIANCE shadow(const state_t *s, const integrator_t *it, ray_t sr,
                       real tmax, const COBJECT *from, const COBJECT *to,
                       const light_sample_t *ls, const medium_t *med,
                       pcg32_t *g, integrator_stats_t *st)
{
    const COBJECT *skip[2] = { from, to };
    VECTOR3 dir;
    if (!s->invisible) {
        /* no boundary to cross: one medium all along */
        st->rays++;
        if (it->tracer.occluded(it->tracer.ctx, &sr, 0, tmax, skip))
            return rad_grey(0);
        real len = vec_normalize(dir, sr.d);
        return segment_tr(med, &sr, dir, tmax * len, g);
    }
    RADIANCE tr = rad_grey(1);
    for (int k = 0; k < VOLPATH_MAX_CROSSINGS; k++) {
        hit_t h;
        const COBJECT *obj = NULL;
        st->rays++;
        bool hit = it->tracer.intersect(it->tracer.ctx, &sr, 0, tmax, skip,
                                        &h, &obj);
        real len = vec_normalize(dir, sr.d);
        tr = rad_mul(tr, segment_tr(med, &sr, dir, (hit ? h.t : tmax) * len,
                                    g));
        if (!hit)
            return tr;
        if (rad_is_black(tr) || !(obj->inside && obj->inside->invisible))
            return rad_grey(0);
        PATHPOINT pp;
        cobject_fill(obj, &sr, &h, &pp);
        med = medium_after(obj, pp.ng, sr.d, med);
        if (ls->infinite) {
            ray_spawn(&sr, pp.cross_point, pp.p_error, pp.ng, ls->wi);
            tmax = (real)INFINITY;
        } else {
            tmax = ray_spawn_to(&sr, pp.cross_point, pp.p_error, pp.ng, ls->p,
                                ls->p_error, ls->n);
        }
        skip[0] = obj;
    }
    return rad_grey(0);
}

/* Next-event estimation at pp: at a surface of material m (obj not NULL;
 * wo in the local frame) or at a scattering event of a medium of phase ph
 * reached along dir (obj NULL). One light chosen by power, sampled once,
 * its shadow ray's transmittance, and the power heuristic against BSDF or
 * phase sampling. Returns the contribution before the path throughput. */
static RADIANCE direct(const state_t *s, const integrator_t *it,
                       const PATHPOINT *pp, const COBJECT *obj,
                       const material_t *m, const VECTOR3 wo,
                       const phase_t *ph, const VECTOR3 dir,
                       const medium_t *med, pcg32_t *g,
                       integrator_stats_t *st)
{
    real upick = pcg32_real(g), u[2];
    u[0] = pcg32_real(g);
    u[1] = pcg32_real(g);
    real pmf;
    const light_t *l = lightset_pick(it->lights, upick, &pmf);
    if (!l || !(pmf > 0))
        return rad_grey(0);
    const bool two = obj ? m->transmits : true;
    light_sample_t ls;
    if (!light_sample(l, pp, two, u, &ls))
        return rad_grey(0);
    real pb = 0;
    RADIANCE f;
    if (obj) {
        VECTOR3 wi;
        frame_to_local(wi, ls.wi, pp->u, pp->v, pp->n);
        f = rad_scale(material_eval_pdf(m, wi, wo, ls.delta ? NULL : &pb),
                      fabs(wi[Z]));
        med = medium_after(obj, pp->ng, ls.wi, med);
    } else {
        /* light travels along -wi, then along -dir: cos = wi . dir */
        pb = phase_eval(ph, SVECTOR3(ls.wi, dir));
        f = rad_grey(pb);
    }
    if (rad_is_black(f) || rad_is_black(ls.Li))
        return rad_grey(0);
    ray_t sr;
    real tmax;
    if (ls.infinite) {
        ray_spawn(&sr, pp->cross_point, pp->p_error, pp->ng, ls.wi);
        tmax = (real)INFINITY;
    } else {
        tmax = ray_spawn_to(&sr, pp->cross_point, pp->p_error, pp->ng, ls.p,
                            ls.p_error, ls.n);
    }
    const COBJECT *to = ls.infinite || !l->emission ? NULL : l->emission->obj;
    RADIANCE tr = shadow(s, it, sr, tmax, obj, to, &ls, med, g, st);
    if (rad_is_black(tr))
        return rad_grey(0);
    real w = ls.delta ? 1 : integrator_mis_weight(pmf * ls.pdf_mis, pb);
    return rad_mul(rad_mul(f, rad_mul(ls.Li, tr)),
                   rad_grey(w / (pmf * ls.pdf)));
}

/* The PATHPOINT of a scattering event at distance t along r (unit dir):
 * a point with no surface, its frame around dir. */
static void medium_point(PATHPOINT *pp, const ray_t *r, const VECTOR3 dir,
                         real t)
{
    memset(pp, 0, sizeof *pp);
    vec_add_scaled(pp->cross_point, r->o, t, dir);
    vec_copy(pp->n, dir);
    vec_copy(pp->ng, dir);
    frame_from_normal(pp->u, pp->v, pp->n);
    vec_scale(pp->out, dir, -1);
    pp->r_dist = t;
}

static RADIANCE li(const void *state, const render_t *r, const ray_t *camera,
                   long sample, pcg32_t *g, integrator_stats_t *st)
{
    (void)sample;
    const state_t *s = state;
    const integrator_t *it = &r->integrator;
    const scene_t *sc = r->scene;
    st->paths++;
    const bool nee = it->lights != NULL;
    const int env = it->env;
    RADIANCE L = rad_grey(0), beta = rad_grey(1);
    ray_t ray = *camera;
    const medium_t *med = s->global;
    bool prev_delta = true;
    real prev_pdf = 0;
    bool prev_two = false;
    PATHPOINT buf[2];
    PATHPOINT *cur = &buf[0], *prev = &buf[1];
    const COBJECT *skip[2] = { NULL, NULL };
    int crossings = 0;

    for (int depth = 0;;) {
        hit_t h;
        const COBJECT *obj = NULL;
        st->rays++;
        bool hit = it->tracer.intersect(it->tracer.ctx, &ray, 0,
                                        (real)INFINITY, skip, &h, &obj);
        VECTOR3 dir;
        real len = vec_normalize(dir, ray.d);
        if (med && !hit && !medium_is_homogeneous(med))
            med = NULL; /* slipped out of a bounded medium (segment_tr) */
        if (med) {
            real t;
            RADIANCE w;
            bool scattered = medium_sample(med, ray.o, dir,
                                           hit ? h.t * len : VOLPATH_FAR,
                                           g, &t, &w);
            beta = rad_mul(beta, w);
            if (rad_is_black(beta))
                break;
            if (scattered) {
                if (depth >= it->max_depth)
                    break;
                PATHPOINT *pp = cur;
                medium_point(pp, &ray, dir, t);
                /* the component that scatters, by its sigma_s (medium.h);
                 * a one-component medium draws nothing for it */
                const phase_t *ph = &med->phase;
                if (med->ncomponents > 0) {
                    RADIANCE wc;
                    ph = &medium_scatterer(med, pp->cross_point,
                                           pcg32_real(g), &wc)->phase;
                    beta = rad_mul(beta, wc);
                }
                if (nee)
                    L = rad_add(L, rad_mul(beta, direct(s, it, pp, NULL, NULL,
                                                        NULL, ph, dir, med, g,
                                                        st)));
                real u[2] = { pcg32_real(g), pcg32_real(g) };
                VECTOR3 wo;
                real pdf = phase_sample(ph, dir, u, wo);
                /* the phase is sampled exactly: the weight p / pdf is 1 */
                cur = prev;
                prev = pp;
                prev_delta = false;
                prev_pdf = pdf;
                prev_two = true;
                vec_copy(ray.o, pp->cross_point);
                vec_copy(ray.d, wo);
                skip[0] = NULL;
                crossings = 0;
                goto bounce;
            }
        }
        if (!hit) {
            if (sc->has_environment) {
                real w = 1;
                if (!prev_delta && nee && env >= 0) {
                    real pl = lightset_pmf(it->lights, env) *
                              light_pdf(&it->lights->lights[env], prev,
                                        prev_two, dir, dir, dir);
                    w = integrator_mis_weight(prev_pdf, pl);
                }
                L = rad_add(L, rad_scale(rad_mul(beta, sc->environment), w));
            }
            break;
        }
        PATHPOINT *pp = cur;
        cobject_fill(obj, &ray, &h, pp);
        if (obj->inside && obj->inside->invisible) {
            /* no surface: the ray goes straight on, into the other side */
            if (++crossings > VOLPATH_MAX_CROSSINGS)
                break;
            med = medium_after(obj, pp->ng, dir, med);
            ray_spawn(&ray, pp->cross_point, pp->p_error, pp->ng, dir);
            skip[0] = obj;
            continue;
        }
        crossings = 0;
        if (obj->light) {
            RADIANCE Le = light_emitted(obj->light, pp);
            if (!rad_is_black(Le)) {
                real w = 1;
                if (!prev_delta && nee) {
                    int k = lightset_find_area(it->lights, obj);
                    real pl = lightset_pmf(it->lights, k) *
                              light_pdf(&it->lights->lights[k], prev, prev_two,
                                        dir, pp->cross_point, pp->ng);
                    w = integrator_mis_weight(prev_pdf, pl);
                }
                L = rad_add(L, rad_scale(rad_mul(beta, Le), w));
            }
        }
        if (depth >= it->max_depth)
            break;
        const material_t *m = obj->material;
        material_t shaded;
        if (obj->texture)
            m = sc->shade(sc, obj, &ray, depth, pp, &shaded);
        VECTOR3 wo;
        frame_to_local(wo, pp->out, pp->u, pp->v, pp->n);
        if (nee && !material_is_specular(m))
            L = rad_add(L, rad_mul(beta, direct(s, it, pp, obj, m, wo, NULL,
                                                dir, med, g, st)));
        real u[3] = { pcg32_real(g), pcg32_real(g), pcg32_real(g) };
        brdf_sample_t bs;
        if (!material_sample(m, wo, u, &bs))
            break;
        beta = rad_mul(beta, bs.weight);
        VECTOR3 wi;
        frame_to_world(wi, bs.wi, pp->u, pp->v, pp->n);
        med = medium_after(obj, pp->ng, wi, med);
        cur = prev;
        prev = pp;
        prev_delta = bs.delta;
        prev_pdf = bs.pdf;
        prev_two = m->transmits;
        ray_spawn(&ray, pp->cross_point, pp->p_error, pp->ng, wi);
        skip[0] = obj;
    bounce:
        depth++;
        {
            /* Russian roulette as ch. 5's path tracer */
            real urr = pcg32_real(g);
            if (it->roulette && depth >= it->roulette_depth) {
                real q = real_min(real_max(rad_max(beta), REAL_C(0.05)),
                                  REAL_C(1.0));
                if (urr >= q)
                    break;
                beta = rad_scale(beta, 1 / q);
            }
        }
        if (rad_is_black(beta))
            break;
    }
    return L;
}

const render_method_t volpath_method = {
    .name = "volpath",
    .describe = "volumetric path tracing (ch. 11): distance sampling, "
                "ratio tracking, light sampling with MIS",
    .prepare = prepare,
    .begin_pass = NULL,
    .li = li,
    .free = state_free,
};
