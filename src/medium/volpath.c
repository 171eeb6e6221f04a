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
 * A medium's emission, the source term sigma_a L_e of pbrt-v4 (sec.
 * 11.1.2), is added along each segment before the distance is sampled.
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

svet_status volpath_prepare(void **out, const render_t *r, int threads,
                            svet_error *err)
{
    (void)threads;
    volpath_state_t *s = calloc(1, sizeof *s);
    if (!s)
        return svet_error_set(err, SVET_ERR_NOMEM, "volpath: out of memory");
    s->global = medpart_global(r->scene);
    const medpart_data_t *d = scene_part_data(r->scene, "medium");
    for (int i = 0; d && i < d->nsides; i++)
        s->invisible |= d->sides[i]->rec.invisible;
    *out = s;
    return SVET_OK;
}

void volpath_free(void *p)
{
    free(p);
}

/* The medium a ray leaving a surface of obj (normal ng) in direction w
 * is in: the side's for a boundary, else the medium it was in. */
const medium_t *volpath_medium_after(const COBJECT *obj, const VECTOR3 ng,
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
RADIANCE volpath_segment_tr(const medium_t *med, const ray_t *r,
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
static RADIANCE shadow(const volpath_state_t *s, const integrator_t *it,
                       ray_t sr, real tmax, const COBJECT *const ends[2],
                       const light_sample_t *ls, const medium_t *med,
                       pcg32_t *g, integrator_stats_t *st)
{
    const COBJECT *skip[2] = { ends[0], ends[1] };
    VECTOR3 dir;
    if (!s->invisible) {
        /* no boundary to cross: one medium all along */
        st->rays++;
        if (it->tracer.occluded(it->tracer.ctx, &sr, 0, tmax, skip))
            return rad_grey(0);
        real len = vec_normalize(dir, sr.d);
        return volpath_segment_tr(med, &sr, dir, tmax * len, g);
    }
    RADIANCE tr = rad_grey(1);
    for (int k = 0; k < VOLPATH_MAX_CROSSINGS; k++) {
        hit_t h;
        const COBJECT *obj = NULL;
        st->rays++;
        bool hit = it->tracer.intersect(it->tracer.ctx, &sr, 0, tmax, skip,
                                        &h, &obj);
        real len = vec_normalize(dir, sr.d);
        tr = rad_mul(tr, volpath_segment_tr(med, &sr, dir, (hit ? h.t : tmax) * len,
                                    g));
        if (!hit)
            return tr;
        if (rad_is_black(tr) || !(obj->inside && obj->inside->invisible))
            return rad_grey(0);
        PATHPOINT pp;
        cobject_fill(obj, &sr, &h, &pp);
        med = volpath_medium_after(obj, pp.ng, sr.d, med);
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

RADIANCE volpath_shadow(const void *ctx, const integrator_t *it,
                        const PATHPOINT *pp, const ray_t *sr, real tmax,
                        const COBJECT *const skip[2],
                        const light_sample_t *ls, pcg32_t *g,
                        integrator_stats_t *st)
{
    const volpath_at_t *at = ctx;
    const medium_t *med = at->obj ? volpath_medium_after(at->obj, pp->ng, ls->wi,
                                                 at->med)
                                  : at->med;
    return shadow(at->s, it, *sr, tmax, skip, ls, med, g, st);
}

/* The phase function as what scatters toward a light (integrator_nee):
 * light travels along -wi, then along -dir, so cos = wi . dir; the phase
 * is sampled exactly, so its pdf is its value. */
static RADIANCE phase_toward(const void *ctx, const VECTOR3 wi, real *pdf)
{
    const volpath_at_t *at = ctx;
    const real c = SVECTOR3(wi, at->dir);
    if (at->mix) {
        /* the mix's components scatter together: sum_i sigma_s_i(x)
         * p_i(c) per channel (medium.h); as a density of directions,
         * the mixture of the p_i by the means of their sigma_s */
        const medium_t *m = at->med;
        RADIANCE f = rad_grey(0);
        real wsum = 0, psum = 0;
        for (int i = 0; i < m->ncomponents; i++) {
            RADIANCE st, ss;
            medium_coeffs_at(&m->components[i], at->x, &st, &ss);
            real p = phase_eval(&m->components[i].phase, c);
            f = rad_add(f, rad_scale(ss, p));
            real w = (ss.r + ss.g + ss.b) / 3;
            wsum += w;
            psum += w * p;
        }
        if (pdf)
            *pdf = wsum > 0 ? psum / wsum : 0;
        return f;
    }
    real p = phase_eval(at->ph ? at->ph : &at->med->phase, c);
    if (pdf)
        *pdf = p;
    return rad_grey(p);
}

RADIANCE volpath_direct(const volpath_at_t *at, const integrator_t *it,
                        const PATHPOINT *pp, const material_t *m,
                        const VECTOR3 wo, bool mis, pcg32_t *g,
                        integrator_stats_t *st)
{
    integrator_scatter_t sc = { m, wo, true, phase_toward, at };
    if (m) {
        sc.two = m->transmits;
        sc.eval = NULL;
        sc.ctx = NULL;
    }
    return integrator_nee(it, pp, &sc, mis, volpath_shadow, at, g, st);
}

void volpath_medium_point(PATHPOINT *pp, const ray_t *r, const VECTOR3 dir,
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

RADIANCE volpath_li(const void *state, const render_t *r,
                    const ray_t *camera, long sample, pcg32_t *g,
                    integrator_stats_t *st)
{
    (void)sample;
    const volpath_state_t *s = state;
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
            med = NULL; /* slipped out of its medium (volpath_segment_tr) */
        if (med && s->step > 0) {
            /* volsingle: the light scattered once along this segment,
             * and on with its transmittance */
            RADIANCE tr = rad_grey(1);
            L = rad_add(L, rad_mul(beta, volsingle_march(
                                             s, it, med, &ray, dir,
                                             hit ? h.t * len : VOLPATH_FAR,
                                             nee && depth < it->max_depth, g,
                                             st, &tr)));
            beta = rad_mul(beta, tr);
            if (rad_is_black(beta))
                break;
        } else if (med) {
            /* the light the medium emits along the whole segment, exact
             * or tracked (medium_emitted); then the walk samples where
             * it scatters, which estimates the rest of the equation */
            if (medium_emits(med))
                L = rad_add(L, rad_mul(beta, medium_emitted(
                                                 med, ray.o, dir,
                                                 hit ? h.t * len : VOLPATH_FAR,
                                                 g)));
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
                volpath_medium_point(pp, &ray, dir, t);
                /* the component that scatters, by its sigma_s (medium.h);
                 * a one-component medium draws nothing for it */
                const phase_t *ph = &med->phase;
                if (med->ncomponents > 0) {
                    RADIANCE wc;
                    ph = &medium_scatterer(med, pp->cross_point,
                                           pcg32_real(g), &wc)->phase;
                    beta = rad_mul(beta, wc);
                }
                if (nee) {
                    volpath_at_t at = { s, med, NULL, { dir[X], dir[Y],
                                                        dir[Z] }, ph, false,
                                        { 0, 0, 0 } };
                    L = rad_add(L, rad_mul(beta, volpath_direct(&at, it, pp,
                                                                NULL, NULL,
                                                                true, g, st)));
                }
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
            med = volpath_medium_after(obj, pp->ng, dir, med);
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
            m = sc->shade(sc, obj, &ray, depth, pp, NULL, &shaded);
        VECTOR3 wo;
        frame_to_local(wo, pp->out, pp->u, pp->v, pp->n);
        if (nee && !material_is_specular(m)) {
            volpath_at_t at = { s, med, obj, { dir[X], dir[Y], dir[Z] },
                                NULL, false, { 0, 0, 0 } };
            L = rad_add(L, rad_mul(beta, volpath_direct(&at, it, pp, m, wo,
                                                        true, g, st)));
        }
        real u[3] = { pcg32_real(g), pcg32_real(g), pcg32_real(g) };
        brdf_sample_t bs;
        if (!material_sample(m, wo, u, &bs))
            break;
        beta = rad_mul(beta, bs.weight);
        VECTOR3 wi;
        frame_to_world(wi, bs.wi, pp->u, pp->v, pp->n);
        med = volpath_medium_after(obj, pp->ng, wi, med);
        cur = prev;
        prev = pp;
        prev_delta = bs.delta;
        prev_pdf = bs.pdf;
        prev_two = m->transmits;
        ray_spawn(&ray, pp->cross_point, pp->p_error, pp->ng, wi);
        skip[0] = obj;
    bounce:
        depth++;
        /* Russian roulette as ch. 5's path tracer's, the scattering
         * events in media counted with the surfaces' */
        if (!integrator_roulette(it, depth, g, &beta))
            break;
        if (rad_is_black(beta))
            break;
    }
    return L;
}

const render_method_t volpath_method = {
    .name = "volpath",
    .describe = "volumetric path tracing (ch. 11): distance sampling, "
                "ratio tracking, light sampling with MIS",
    .prepare = volpath_prepare,
    .begin_pass = NULL,
    .li = volpath_li,
    .free = volpath_free,
};
