/*
 * volsingle.c - single scattering by ray marching (ch. 11): `render
 * integrator volsingle`. Along each segment of a path inside a medium
 * the single-scattering term of the volume rendering equation (pbrt-v3
 * sec. 15.1, eq. 15.1; the book's ray marching, ch. 11),
 *   L_ss = int_0^len Tr(0, t) sigma_s(t) int p(w, w') L_d(x_t, w') dw' dt,
 * is estimated by marching with step h from a jittered start u h (u
 * uniform in [0, 1)), t_i = (i + u) h for t_i < len, each point weighted
 * by h (a randomly shifted rectangle rule: unbiased for any h, its error
 * falling as h). At each point one light is sampled (the path tracer's
 * next-event estimation, integrator_nee) with its shadow ray's
 * transmittance by ratio tracking (Novak et al. 2014; exact in
 * homogeneous media), and the transmittance from the segment's start is
 * accumulated step by step: exact in a homogeneous medium, the trapezoid
 * rule on the optical depth otherwise (an error of order h^2). Light is
 * scattered in a medium at most once: the path continues only at
 * surfaces, as the path tracer's does (volpath.c's walk with the march
 * in place of distance sampling), each segment's throughput multiplied by
 * its transmittance. The volume photon map's camera rays are marched by
 * the same function, its volume estimate added at each point
 * (volpath_state_t.inscatter).
 * Tests: tests/medium/test_volsingle.c
 */
#include "medium/volsingle.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "medpart_data.h"
#include "render/render.h"

/* The most points one segment is marched at: a longer segment is marched
 * with a longer step, so that a tiny step cannot stall a render. */
#define VOLSINGLE_MAX_STEPS 65536

/* A ray that leaves the scene in the global medium is marched until its
 * transmittance has fallen to this in every channel that has extinction:
 * what lies beyond adds less than this share of the light scattered
 * before it. */
#define VOLSINGLE_CUT 1e-6

static svet_status prepare(void **out, const render_t *r, int threads,
                           svet_error *err)
{
    svet_status st = volpath_prepare(out, r, threads, err);
    if (st)
        return st;
    volpath_state_t *s = *out;
    const medpart_data_t *d = scene_part_data(r->scene, "medium");
    s->step = d && d->step > 0 ? d->step : MEDPART_DEFAULT_STEP;
    return SVET_OK;
}

RADIANCE volsingle_march(const volpath_state_t *s, const integrator_t *it,
                         const medium_t *med, const ray_t *ray,
                         const VECTOR3 dir, real len, bool nee, pcg32_t *g,
                         integrator_stats_t *st, RADIANCE *tr)
{
    const real u = pcg32_real(g); /* the jittered start */
    const RADIANCE sigma_t = medium_sigma_t(med);
    /* the components marched: a one-component medium is its own */
    const int nc = med->ncomponents > 0 ? med->ncomponents : 1;
    const medium_t *comp = med->ncomponents > 0 ? med->components : med;
    const bool mix = med->ncomponents > 0;
    const bool emits = medium_emits(med);
    bool cut = false;
    if (len >= VOLPATH_FAR) {
        /* to infinity (the global medium, homogeneous): Tr is exactly 0
         * where sigma_t > 0 and 1 where it is 0; no scattering where it
         * is 0 (sigma_s <= sigma_t), so the march stops where Tr has
         * fallen to VOLSINGLE_CUT in the least extinct channel */
        *tr = medium_tr_homogeneous(med, VOLPATH_FAR);
        real smin = (real)INFINITY;
        const real c[3] = { sigma_t.r, sigma_t.g, sigma_t.b };
        for (int k = 0; k < 3; k++)
            if (c[k] > 0 && c[k] < smin)
                smin = c[k];
        if (!(smin < (real)INFINITY))
            return rad_grey(0);
        len = (real)-log(VOLSINGLE_CUT) / smin;
        cut = true;
    }
    real h = s->step;
    if (len / h > VOLSINGLE_MAX_STEPS)
        h = len / VOLSINGLE_MAX_STEPS;
    RADIANCE L = rad_grey(0);
    /* tau[i]: component i's optical depth at density 1 from the
     * segment's start, exact where it is homogeneous, by the trapezoid
     * rule on its density otherwise; d[i] its density at the point */
    real tau[MEDIUM_MAX_COMPONENTS], d_prev[MEDIUM_MAX_COMPONENTS];
    real d[MEDIUM_MAX_COMPONENTS];
    bool flat[MEDIUM_MAX_COMPONENTS];
    for (int k = 0; k < nc; k++) {
        flat[k] = medium_is_homogeneous(&comp[k]);
        tau[k] = 0;
        d_prev[k] = flat[k] ? 1 : medium_density(&comp[k], ray->o);
    }
    real t_prev = 0;
    for (int i = 0;; i++) {
        const real t = ((real)i + u) * h;
        if (!(t < len))
            break;
        VECTOR3 x;
        vec_add_scaled(x, ray->o, t, dir);
        bool any = false;
        for (int k = 0; k < nc; k++) {
            d[k] = 1;
            if (flat[k]) {
                tau[k] = t;
            } else {
                d[k] = medium_density(&comp[k], x);
                tau[k] += (d_prev[k] + d[k]) / 2 * (t - t_prev);
            }
            d_prev[k] = d[k];
            any |= d[k] > 0;
        }
        t_prev = t;
        if (!any || (!nee && !emits && !s->inscatter))
            continue;
        /* Tr from the segment's start: exp of minus the sum of the
         * components' optical depths */
        RADIANCE depth = rad_grey(0);
        for (int k = 0; k < nc; k++)
            depth = rad_add(depth, rad_scale(medium_sigma_t(&comp[k]),
                                             tau[k]));
        const RADIANCE T = rad_make(exp(-depth.r), exp(-depth.g),
                                    exp(-depth.b));
        if (emits) {
            /* the emission of pbrt-v4 sec. 11.1.2, sigma_a L_e, by the
             * same shifted rectangle rule */
            RADIANCE S = rad_grey(0);
            for (int k = 0; k < nc; k++)
                S = rad_add(S, rad_scale(rad_mul(comp[k].sigma_a,
                                                 comp[k].emission),
                                         d[k]));
            L = rad_add(L, rad_mul(T, rad_scale(S, h)));
        }
        if (s->inscatter)
            L = rad_add(L, rad_mul(T, rad_scale(s->inscatter(
                                                    s->inscatter_ctx, med, x,
                                                    dir),
                                                h)));
        if (!nee)
            continue;
        PATHPOINT pp;
        volpath_medium_point(&pp, ray, dir, t);
        volpath_at_t at = { s, med, NULL, { dir[X], dir[Y], dir[Z] },
                            NULL, mix, { x[X], x[Y], x[Z] } };
        /* no phase sampling follows: the light sample takes it all; a
         * mix's phase comes weighted by each component's sigma_s at x
         * (phase_toward in volpath.c) */
        RADIANCE Ld = volpath_direct(&at, it, &pp, NULL, NULL, false, g, st);
        if (rad_is_black(Ld))
            continue;
        const RADIANCE ss = mix ? rad_grey(h)
                                : rad_scale(med->sigma_s, d[0] * h);
        L = rad_add(L, rad_mul(rad_mul(T, ss), Ld));
    }
    if (!cut) {
        RADIANCE depth = rad_grey(0);
        VECTOR3 x;
        vec_add_scaled(x, ray->o, len, dir);
        for (int k = 0; k < nc; k++) {
            if (flat[k]) {
                tau[k] = len;
            } else {
                real dk = medium_density(&comp[k], x);
                tau[k] += (d_prev[k] + dk) / 2 * (len - t_prev);
            }
            depth = rad_add(depth, rad_scale(medium_sigma_t(&comp[k]),
                                             tau[k]));
        }
        *tr = rad_make(exp(-depth.r), exp(-depth.g), exp(-depth.b));
    }
    return L;
}

const render_method_t volsingle_method = {
    .name = "volsingle",
    .describe = "single scattering by ray marching (ch. 11): light sampled "
                "at each step, ratio-tracked shadow rays",
    .prepare = prepare,
    .begin_pass = NULL,
    .li = volpath_li,
    .free = volpath_free,
};
