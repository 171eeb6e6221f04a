/*
 * volphoton.c - the volume photon map of ch. 11 (medium/volphoton.h):
 * Jensen & Christensen, "Efficient Simulation of Light Transport in
 * Scenes with Participating Media using Photon Maps", SIGGRAPH 1998, and
 * Jensen, "Realistic Image Synthesis Using Photon Mapping", 2001, ch. 10.
 * The first pass traces photons from the lights (photon/photon.h's
 * emission) and from the media that emit through the media and stores
 * them where they scatter (a volume map) and where they land on surfaces
 * (a surface map), in the left-balanced kd-tree of ch. 8
 * (photon/photonmap.h). The second pass,
 * `render integrator volphoton`, marches each camera segment in a medium
 * as Jensen 2001, sec. 10.5 does: at points t_i = (i + u) h (u uniform
 * in [0, 1), one per segment: a randomly shifted rectangle rule, as
 * volsingle.c's) it adds, weighted by the transmittance from the
 * segment's start and by h, the single scattering by light sampling
 * (next-event estimation with the shadow ray's transmittance,
 * volpath_direct) and the multiple scattering from the volume map
 * (volphoton_radiance). The volume map holds only light's photons that
 * have scattered or bounced before, so the two terms do not overlap, and
 * the photons an emitting medium sends from their first event on (the
 * march adds the emission seen directly, and no light sampling covers
 * emitted light scattered). At the
 * first surface with a non-delta part the light is the direct light by
 * light sampling plus the surface map's radiance estimate (photon.h's
 * photon_radiance with the `photonmap` statement's k, max_radius and
 * filter), delta bounces followed as the photon method follows them: the
 * photon method's preview without final gathering, direct light aside.
 * Tests: tests/medium/test_volphoton.c
 */
#include "medium/volphoton.h"

#ifdef _OPENMP
#include <omp.h>
#endif
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/bbox.h"
#include "core/frame.h"
#include "core/sample.h"
#include "materials/material.h"
#include "medpart_data.h"
#include "photon/photon.h"
#include "render/integrator.h"
#include "render/render.h"

/* --- settings: the `volphoton` statement ---------------------------------- */

void volphoton_settings_default(volphoton_settings_t *s)
{
    s->photons = 200000;
    s->k = 50;
    s->max_radius = REAL_C(0.2);
    s->step = REAL_C(0.05);
}

void volphoton_settings_of(const scene_t *s, volphoton_settings_t *out)
{
    const volphoton_settings_t *p = scene_part_data(s, "volphoton");
    if (p)
        *out = *p;
    else
        volphoton_settings_default(out);
}

enum { VP_PHOTONS, VP_K, VP_MAXR, VP_STEP, VP_N };
static const spec_t volphoton_spec[VP_N] = {
    [VP_PHOTONS] = { "photons", V_U64, 0, 0, 0, NULL },
    [VP_K] = { "k", V_INT, 0, 1, PHOTON_MAX_K, NULL },
    [VP_MAXR] = { "max_radius", V_NUM, F_POSITIVE, 0, 0, NULL },
    [VP_STEP] = { "step", V_NUM, F_POSITIVE, 0, 0, NULL },
};

static svet_status volphoton_statement(scenefile_ctx *c)
{
    val_t v[VP_N];
    svet_status st = scenefile_keys(c, "volphoton", volphoton_spec, VP_N, v,
                                    false);
    if (st)
        return st;
    if (v[VP_PHOTONS].set) {
        if (v[VP_PHOTONS].u == 0)
            return scenefile_fail(c, v[VP_PHOTONS].col, SVET_ERR_RANGE,
                                  "'photons' must be at least 1");
        svet_error e;
        uint64_t n = v[VP_PHOTONS].u;
        st = photonmap_check_count(n > SIZE_MAX ? SIZE_MAX : (size_t)n, &e);
        if (st)
            return scenefile_fail(c, v[VP_PHOTONS].col, st, "'photons': %s",
                                  e.msg);
    }
    for (int k = VP_MAXR; k <= VP_STEP; k++)
        if (v[k].set && !isfinite(v[k].v[0]))
            return scenefile_fail(c, v[k].col, SVET_ERR_RANGE,
                                  "'%s' must be finite", volphoton_spec[k].key);
    /* the line updates the settings: `--set volphoton.k=20` reruns it */
    bool fresh;
    volphoton_settings_t *p = scene_part_data_new(scenefile_scene(c),
                                                  "volphoton", sizeof *p,
                                                  free, &fresh);
    if (!p)
        return scenefile_fail(c, scenefile_stmt_col(c), SVET_ERR_NOMEM,
                              "out of memory");
    if (fresh)
        volphoton_settings_default(p);
    if (v[VP_PHOTONS].set)
        p->photons = v[VP_PHOTONS].u;
    if (v[VP_K].set)
        p->k = (int)v[VP_K].i;
    if (v[VP_MAXR].set)
        p->max_radius = v[VP_MAXR].v[0];
    if (v[VP_STEP].set)
        p->step = v[VP_STEP].v[0];
    return SVET_OK;
}

/* --- the photon pass ------------------------------------------------------ */

/* A photon's walk from ray (power, in med) through media and off
 * surfaces, drawing from g, its records into out[0] (the volume map's)
 * and out[1] (the surface map's). `events` counts its scatterings and
 * bounces; it is stored from the `first`-th on: 1 for a light's photon,
 * whose first event the camera's light sampling covers, 0 for one a
 * medium emits, which nothing else carries. */
static void walk(const render_t *r, pcg32_t *g, ray_t ray, RADIANCE power,
                 const medium_t *med, const COBJECT *from, int first,
                 photon_records_t *out)
{
    static const VECTOR3 no_normal = { 0, 0, 0 };
    const COBJECT *skip[2] = { from, NULL };
    const int max_depth = r->scene->render.max_depth;
    int events = 0, crossings = 0;
    for (;;) {
        hit_t h;
        const COBJECT *obj = NULL;
        bool hit = r->tracer.intersect(r->tracer.ctx, &ray, 0,
                                       (real)INFINITY, skip, &h, &obj);
        VECTOR3 dir;
        real len = vec_normalize(dir, ray.d);
        if (med && !hit && !medium_is_homogeneous(med))
            med = NULL; /* slipped out of its medium (volpath_segment_tr) */
        if (med) {
            real t;
            RADIANCE w;
            bool scattered = medium_sample(med, ray.o, dir,
                                           hit ? h.t * len : VOLPATH_FAR, g,
                                           &t, &w);
            if (scattered) {
                if (events >= max_depth)
                    return;
                /* Russian roulette by the weight sigma_s Tr / pdf: in a
                 * grey medium the albedo, the power unchanged (Jensen
                 * 2001, sec. 10.3) */
                real q = real_min(rad_max(w), REAL_C(1.0));
                real urr = pcg32_real(g);
                if (!(urr < q))
                    return;
                power = rad_scale(rad_mul(power, w), 1 / q);
                VECTOR3 x;
                vec_add_scaled(x, ray.o, t, dir);
                if (events >= first)
                    photon_records_push(&out[0], x, dir, no_normal, power);
                const phase_t *ph = &med->phase;
                if (med->ncomponents > 0) {
                    RADIANCE wc;
                    ph = &medium_scatterer(med, x, pcg32_real(g), &wc)->phase;
                    power = rad_mul(power, wc);
                }
                real u[2] = { pcg32_real(g), pcg32_real(g) };
                VECTOR3 wo;
                phase_sample(ph, dir, u, wo); /* exact: weight 1 */
                vec_copy(ray.o, x);
                vec_copy(ray.d, wo);
                skip[0] = NULL;
                events++;
                crossings = 0;
                continue;
            }
            power = rad_mul(power, w);
            if (rad_is_black(power))
                return;
        }
        if (!hit)
            return;
        PATHPOINT pp;
        cobject_fill(obj, &ray, &h, &pp);
        if (obj->inside && obj->inside->invisible) {
            if (++crossings > VOLPATH_MAX_CROSSINGS)
                return;
            med = volpath_medium_after(obj, pp.ng, dir, med);
            ray_spawn(&ray, pp.cross_point, pp.p_error, pp.ng, dir);
            skip[0] = obj;
            continue;
        }
        crossings = 0;
        const material_t *m = obj->material;
        if (!material_is_specular(m) && m->ncomp > 0 &&
            events >= first) {
            VECTOR3 n; /* the side it arrived from, as photon.c's */
            vec_scale(n, pp.n, SVECTOR3(pp.n, dir) > 0 ? -1 : 1);
            photon_records_push(&out[1], pp.cross_point, dir, n, power);
        }
        if (events >= max_depth)
            return;
        /* the adjoint bounce and roulette of photon tracing; the ray
         * leaves in ray.d, which decides the medium past a boundary */
        if (!photon_bounce(m, &pp, g, &power, &ray, NULL))
            return;
        med = volpath_medium_after(obj, pp.ng, ray.d, med);
        skip[0] = obj;
        events++;
    }
}

/* Photon `index` of a light (photon_walk_fn, ctx the global medium,
 * where it leaves its light). */
static void trace_one(const render_t *r, const photon_emitters_t *em,
                      uint64_t count, uint64_t index, void *ctx,
                      photon_records_t *out)
{
    pcg32_t g;
    rng_for_sample(&g, r->scene->render.seed ^ VOLPHOTON_SEED_SALT, 0, index);
    ray_t ray;
    RADIANCE power;
    const COBJECT *from = NULL;
    if (photon_emit(r, em, count, &g, &ray, &power, &from))
        walk(r, &g, ray, power, ctx, from, 1, out);
}

/* --- photons the media emit ----------------------------------------------- */

/* Where the emitting media are: the box around every boundary with an
 * emitting medium on a side other than the global one (whose emission
 * fills all space: the march sees it, no photon carries it), its
 * volume, and the global medium. */
typedef struct {
    bbox_t box;
    real volume;
    const medium_t *global;
} emitting_t;

static bool emitting_of(const render_t *r, emitting_t *e)
{
    const scene_t *s = r->scene;
    e->global = medpart_global(s);
    bbox_empty(&e->box);
    bool any = false;
    for (int i = 0; i < s->nobjects; i++) {
        const COBJECT *o = s->objects[i];
        const struct medium *side[2] = { o->inside, o->outside };
        for (int k = 0; k < 2; k++)
            if (side[k] && side[k]->m && side[k]->m != e->global &&
                medium_emits(side[k]->m)) {
                bbox_t b;
                o->ops->bounds(o, -1, &b);
                bbox_union(&e->box, &b);
                any = true;
            }
    }
    e->volume = 1;
    for (int a = 0; a < 3; a++)
        e->volume *= e->box.max[a] - e->box.min[a];
    return any && e->volume > 0 && isfinite(e->volume);
}

/* The medium at x: a ray from x along +z, through surfaces that are no
 * boundary, to the first boundary, whose side it left (medpart.h's
 * rule); no boundary: the global medium. NULL when caught between
 * coincident surfaces. */
static const medium_t *medium_at(const render_t *r, const VECTOR3 x,
                                 const medium_t *global)
{
    ray_t ray;
    memset(&ray, 0, sizeof ray);
    vec_copy(ray.o, x);
    ray.d[Z] = 1;
    const COBJECT *skip[2] = { NULL, NULL };
    for (int k = 0; k < VOLPATH_MAX_CROSSINGS; k++) {
        hit_t h;
        const COBJECT *obj = NULL;
        if (!r->tracer.intersect(r->tracer.ctx, &ray, 0, (real)INFINITY,
                                 skip, &h, &obj))
            return global;
        PATHPOINT pp;
        cobject_fill(obj, &ray, &h, &pp);
        if (obj->inside)
            return SVECTOR3(ray.d, pp.ng) > 0 ? obj->inside->m
                                              : obj->outside->m;
        VECTOR3 d = { 0, 0, 1 };
        ray_spawn(&ray, pp.cross_point, pp.p_error, pp.ng, d);
        skip[0] = obj;
    }
    return NULL;
}

/* Emitted photon `index` of `count`: a point x uniform in e's box, kept
 * where its medium emits, leaving in a direction uniform over the sphere
 * with the power 4 pi sigma_a(x) L_e V / count (V the box's volume; the
 * source term's integral over volume and directions, each photon its
 * share by the two uniform densities); stored from its first event. */
static void emit_one(const render_t *r, const emitting_t *e, uint64_t count,
                     uint64_t index, photon_records_t *out)
{
    pcg32_t g;
    rng_for_sample(&g, r->scene->render.seed ^ VOLPHOTON_SEED_SALT, 1, index);
    VECTOR3 x;
    for (int a = 0; a < 3; a++)
        x[a] = e->box.min[a] +
               pcg32_real(&g) * (e->box.max[a] - e->box.min[a]);
    real u[2] = { pcg32_real(&g), pcg32_real(&g) };
    const medium_t *med = medium_at(r, x, e->global);
    if (!med || med == e->global || !medium_emits(med))
        return;
    RADIANCE power = rad_scale(medium_source_at(med, x),
                               4 * REAL_PI * e->volume / (real)count);
    if (rad_is_black(power))
        return;
    ray_t ray;
    memset(&ray, 0, sizeof ray);
    vec_copy(ray.o, x);
    sample_uniform_sphere(ray.d, u);
    walk(r, &g, ray, power, med, NULL, 0, out);
}

/* The emitted photons' records, as photon_trace_records lays out the
 * lights': list j of chunk c at (*lists)[j * *nchunks + c], each chunk
 * walked by one thread, so that joined in chunk order they do not
 * depend on the thread count. No emitting medium: *lists NULL. */
static svet_status emission_records(const render_t *r, uint64_t count,
                                    int threads, const char *what,
                                    photon_records_t **lists,
                                    uint64_t *nchunks, svet_error *err)
{
    *lists = NULL;
    *nchunks = 0;
    emitting_t e;
    if (count == 0 || !emitting_of(r, &e))
        return SVET_OK;
    uint64_t nc = (count + PHOTON_CHUNK - 1) / PHOTON_CHUNK;
    if (nc > SIZE_MAX / (2 * sizeof(photon_records_t)))
        return svet_error_set(err, SVET_ERR_NOMEM, "%s: %llu photons are too "
                              "many", what, (unsigned long long)count);
    photon_records_t *l = calloc((size_t)(2 * nc), sizeof *l);
    if (!l)
        return svet_error_set(err, SVET_ERR_NOMEM, "%s: out of memory", what);
#ifdef _OPENMP
    int nt = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
#else
    (void)threads;
#endif
    for (long long c = 0; c < (long long)nc; c++) {
        photon_records_t out[2];
        memset(out, 0, sizeof out);
        uint64_t i0 = (uint64_t)c * PHOTON_CHUNK;
        uint64_t i1 = i0 + PHOTON_CHUNK < count ? i0 + PHOTON_CHUNK : count;
        for (uint64_t i = i0; i < i1; i++)
            emit_one(r, &e, count, i, out);
        l[c] = out[0];
        l[nc + (uint64_t)c] = out[1];
    }
    *lists = l;
    *nchunks = nc;
    return SVET_OK;
}

/* Store list `j` (0: volume, 1: surface) of the lights' records and then
 * the media's into m. */
static svet_status store(const photon_records_t *lights, uint64_t nl,
                         const photon_records_t *media, uint64_t nm, int j,
                         const char *what, photonmap_t *m, svet_error *err)
{
    if (nm == 0)
        return photon_records_store(lights + j * nl, nl, 0, what, m, err);
    photon_records_t *all = malloc((size_t)(nl + nm) * sizeof *all);
    if (!all)
        return svet_error_set(err, SVET_ERR_NOMEM, "%s: out of memory", what);
    for (uint64_t c = 0; c < nl; c++)
        all[c] = lights[j * nl + c];
    for (uint64_t c = 0; c < nm; c++)
        all[nl + c] = media[j * nm + c];
    svet_status st = photon_records_store(all, nl + nm, 0, what, m, err);
    free(all); /* the records themselves stay with their lists */
    return st;
}

svet_status volphoton_trace(const render_t *r, uint64_t count, int threads,
                            photonmap_t *vol, photonmap_t *surf,
                            svet_error *err)
{
    static const char what[] = "volume photon tracing";
    memset(vol, 0, sizeof *vol);
    memset(surf, 0, sizeof *surf);
    vol->balanced = surf->balanced = true; /* empty maps find nothing */
    /* the chunked walk of photon.h: list 0 of every chunk the volume
     * map's records, list 1 the surface map's, each joined in chunk
     * order, so the maps do not depend on the thread count; then the
     * photons the media emit, in the same layout */
    photon_records_t *lists = NULL, *emitted = NULL;
    uint64_t nchunks = 0, nemitted = 0;
    svet_status st = photon_trace_records(r, count, threads, 2, trace_one,
                                          (void *)medpart_global(r->scene),
                                          what, &lists, &nchunks, err);
    if (st == SVET_OK)
        st = emission_records(r, count, threads, what, &emitted, &nemitted,
                              err);
    if (st == SVET_OK)
        st = store(lists, nchunks, emitted, nemitted, 0, what, vol, err);
    if (st == SVET_OK)
        st = store(lists, nchunks, emitted, nemitted, 1, what, surf, err);
    photon_records_free(lists, 2 * nchunks);
    photon_records_free(emitted, 2 * nemitted);
    if (st != SVET_OK) {
        photonmap_free(vol);
        photonmap_free(surf);
        vol->balanced = surf->balanced = true;
    }
    return st;
}

/* --- the volume radiance estimate ----------------------------------------- */

/* The phase function at x of light deflected by cos: the medium's, or in
 * a sum the components' weighted by the mean of their sigma_s at x (the
 * chance medium_scatterer gives each). */
static real phase_at(const medium_t *med, const VECTOR3 x, real cos_theta)
{
    if (med->ncomponents == 0)
        return phase_eval(&med->phase, cos_theta);
    real sum = 0, wsum = 0;
    for (int i = 0; i < med->ncomponents; i++) {
        RADIANCE st, ss;
        medium_coeffs_at(&med->components[i], x, &st, &ss);
        real w = (ss.r + ss.g + ss.b) / 3;
        sum += w * phase_eval(&med->components[i].phase, cos_theta);
        wsum += w;
    }
    return wsum > 0 ? sum / wsum : 0;
}

RADIANCE volphoton_radiance(const photonmap_t *vol, const medium_t *med,
                            const VECTOR3 x, const VECTOR3 dir, int k,
                            real rmax)
{
    int32_t idx[PHOTON_MAX_K];
    real d2[PHOTON_MAX_K];
    if (k > PHOTON_MAX_K)
        k = PHOTON_MAX_K;
    RADIANCE L = rad_grey(0);
    int found = photonmap_nearest(vol, x, k, rmax, idx, d2);
    real r2 = found == k ? d2[found - 1] : rmax * rmax;
    if (found == 0 || !(r2 > 0))
        return L;
    for (int i = 0; i < found; i++) {
        const photon_t *p = &vol->ph[idx[i]];
        VECTOR3 d;
        photonmap_direction(p, d);
        /* light travelled along d, then leaves toward -dir */
        real ph = phase_at(med, x, -SVECTOR3(d, dir));
        L = rad_add(L, rad_scale(rad_make((real)p->power[0],
                                          (real)p->power[1],
                                          (real)p->power[2]), ph));
    }
    /* Jensen & Christensen 1998, sec. 3.2: the photons' flux in the
     * sphere of radius r, per its volume (4/3) pi r^3 */
    return rad_scale(L, 1 / (REAL_C(4.0) / 3 * REAL_PI * r2 * sqrt(r2)));
}

/* --- the method ------------------------------------------------------------ */

typedef struct {
    volpath_state_t vp;        /* the camera's medium, invisible boundaries */
    volphoton_settings_t set;
    photonmap_query_t surfq;   /* the surface map's estimate (photonmap) */
    photonmap_t vol, surf;
} state_t;

static void state_free(void *p)
{
    state_t *s = p;
    if (!s)
        return;
    photonmap_free(&s->vol);
    photonmap_free(&s->surf);
    free(s);
}

/* The march's term beyond the light sampled at a point
 * (volsingle_inscatter_fn): the volume map's multiple scattering. */
static RADIANCE map_inscatter(const void *ctx, const medium_t *med,
                              const VECTOR3 x, const VECTOR3 dir)
{
    const state_t *s = ctx;
    return volphoton_radiance(&s->vol, med, x, dir, s->set.k,
                              s->set.max_radius);
}

static svet_status prepare(void **out, const render_t *r, int threads,
                           svet_error *err)
{
    state_t *s = calloc(1, sizeof *s);
    if (!s)
        return svet_error_set(err, SVET_ERR_NOMEM,
                              "volphoton: out of memory");
    void *vp;
    svet_status st = volpath_prepare(&vp, r, threads, err);
    if (st) {
        free(s);
        return st;
    }
    s->vp = *(const volpath_state_t *)vp;
    volpath_free(vp);
    volphoton_settings_of(r->scene, &s->set);
    s->vp.step = s->set.step;
    s->vp.inscatter = map_inscatter;
    s->vp.inscatter_ctx = s;
    photon_settings_t ps;
    photon_settings_of(r->scene, &ps);
    photonmap_query_t q = { ps.k, ps.max_radius, ps.filter, REAL_C(1.1),
                            REAL_C(0.25) };
    s->surfq = q;
    st = volphoton_trace(r, s->set.photons, threads, &s->vol, &s->surf, err);
    if (st) {
        state_free(s);
        return st;
    }
    *out = s;
    return SVET_OK;
}

/* The camera path: the march along every segment in a medium, emitters
 * seen directly or through delta bounces, invisible boundaries crossed,
 * delta bounces followed, and at the first surface with a non-delta part
 * its direct light by light sampling and the surface map's estimate. */
static RADIANCE li(const void *state, const render_t *r, const ray_t *camera,
                   long sample, pcg32_t *g, integrator_stats_t *st)
{
    (void)sample;
    const state_t *s = state;
    const scene_t *sc = r->scene;
    const integrator_t *it = &r->integrator;
    const bool nee = it->lights != NULL;
    st->paths++;
    RADIANCE L = rad_grey(0), beta = rad_grey(1);
    ray_t ray = *camera;
    const medium_t *med = s->vp.global;
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
        if (med) {
            RADIANCE tr = rad_grey(1);
            L = rad_add(L, rad_mul(beta, volsingle_march(
                                             &s->vp, it, med, &ray, dir,
                                             hit ? h.t * len : VOLPATH_FAR,
                                             nee, g, st, &tr)));
            beta = rad_mul(beta, tr);
            if (rad_is_black(beta))
                break;
        }
        if (!hit) {
            if (sc->has_environment)
                L = rad_add(L, rad_mul(beta, sc->environment));
            break;
        }
        PATHPOINT pp;
        cobject_fill(obj, &ray, &h, &pp);
        if (obj->inside && obj->inside->invisible) {
            if (++crossings > VOLPATH_MAX_CROSSINGS)
                break;
            med = volpath_medium_after(obj, pp.ng, dir, med);
            ray_spawn(&ray, pp.cross_point, pp.p_error, pp.ng, dir);
            skip[0] = obj;
            continue;
        }
        crossings = 0;
        if (obj->light)
            L = rad_add(L, rad_mul(beta, light_emitted(obj->light, &pp)));
        if (depth >= sc->render.max_depth)
            break;
        const material_t *m = obj->material;
        material_t shaded;
        if (obj->texture)
            m = sc->shade(sc, obj, &ray, depth, &pp, NULL, &shaded);
        VECTOR3 wo, wi;
        frame_to_local(wo, pp.out, pp.u, pp.v, pp.n);
        bool diffuse = !material_is_specular(m) && m->ncomp > 0;
        if (diffuse) {
            RADIANCE Ls = photon_radiance(&s->surf, &pp, m, wo, &s->surfq);
            if (nee) {
                volpath_at_t at = { &s->vp, med, obj,
                                    { dir[X], dir[Y], dir[Z] }, NULL, false,
                                    { 0, 0, 0 } };
                Ls = rad_add(Ls, volpath_direct(&at, it, &pp, m, wo, false, g,
                                                st));
            }
            L = rad_add(L, rad_mul(beta, Ls));
        }
        real u[3] = { pcg32_real(g), pcg32_real(g), pcg32_real(g) };
        brdf_sample_t bs;
        if (!material_sample(m, wo, u, &bs) || (diffuse && !bs.delta))
            break;
        beta = rad_mul(beta, bs.weight);
        if (rad_is_black(beta))
            break;
        frame_to_world(wi, bs.wi, pp.u, pp.v, pp.n);
        med = volpath_medium_after(obj, pp.ng, wi, med);
        ray_spawn(&ray, pp.cross_point, pp.p_error, pp.ng, wi);
        skip[0] = obj;
        depth++;
    }
    return L;
}

const render_method_t volphoton_method = {
    .name = "volphoton",
    .describe = "the volume photon map (ch. 11, Jensen & Christensen 1998): "
                "ray marching, multiple scattering from the map",
    .prepare = prepare,
    .begin_pass = NULL,
    .li = li,
    .free = state_free,
};

static const render_method_t *const methods[] = { &volphoton_method, NULL };
static const scene_statement_t statements[] = {
    { "volphoton", volphoton_statement }, { NULL, NULL }
};
const scene_part_t volphoton_part = { .name = "volphoton",
                                      .statements = statements,
                                      .methods = methods };
