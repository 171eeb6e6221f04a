/*
 * photon.c - the photon map method of ch. 8 as a part of the renderer:
 * the `photonmap` statement, photon emission and tracing (Jensen 2001,
 * ch. 5), the radiance estimate (Jensen 1996, eq. 9), and the methods
 * `photon` (direct light by ch. 5's light sampling, caustics from the
 * caustic map, indirect diffuse light by final gathering from the global
 * map, optionally from irradiance precomputed at a subset of its photons,
 * Christensen 1999; Jensen 2001, ch. 9) and `ppm` (Knaus & Zwicker 2011);
 * photon's maps saved to a file and read back for split renders.
 * Tests: tests/photon/test_photon.c; the saved maps:
 * tests/cmd/test_merge.sh
 */
#include "photon/photon.h"

#ifdef _OPENMP
#include <omp.h>
#endif
#include <stdlib.h>
#include <string.h>

#include "core/frame.h"
#include "core/sample.h"
#include "photon/photonsave.h"
#include "render/integrator.h"
#include "render/light.h"
#include "render/render.h"

/* --- settings: the `photonmap` statement -------------------------------- */

void photon_settings_default(photon_settings_t *s)
{
    s->global = 100000;
    s->caustic = 100000;
    s->k = 50;
    s->max_radius = REAL_C(0.1);
    s->filter = PHOTONMAP_FILTER_NONE;
    s->gather = 64;
    s->alpha = REAL_C(0.7);
    s->radius = REAL_C(0.05);
    s->precompute = 0;
}

void photon_settings_of(const scene_t *s, photon_settings_t *out)
{
    const photon_settings_t *p = scene_part_data(s, "photon");
    if (p)
        *out = *p;
    else
        photon_settings_default(out);
}

static const char *const filters[] = { "none", "cone", "gaussian", NULL };
enum { P_GLOBAL, P_CAUSTIC, P_K, P_MAXR, P_FILTER, P_GATHER, P_ALPHA,
       P_RADIUS, P_PRECOMPUTE, P_N };
static const spec_t photon_spec[P_N] = {
    [P_GLOBAL] = { "global", V_U64, 0, 0, 0, NULL },
    [P_CAUSTIC] = { "caustic", V_U64, 0, 0, 0, NULL },
    [P_K] = { "k", V_INT, 0, 1, PHOTON_MAX_K, NULL },
    [P_MAXR] = { "max_radius", V_NUM, F_POSITIVE, 0, 0, NULL },
    [P_FILTER] = { "filter", V_WORD, 0, 0, 0, filters },
    [P_GATHER] = { "gather", V_INT, 0, 0, 65536, NULL },
    [P_ALPHA] = { "alpha", V_NUM, F_POSITIVE, 0, 0, NULL },
    [P_RADIUS] = { "radius", V_NUM, F_POSITIVE, 0, 0, NULL },
    [P_PRECOMPUTE] = { "precompute", V_INT, 0, 0, 1 << 20, NULL },
};

/* a photon count: at least 1, and a map of that many must fit in memory
 * (checked before anything is allocated) */
static svet_status check_count(scenefile_ctx *c, const val_t *v,
                               const char *key)
{
    if (v->u == 0)
        return scenefile_fail(c, v->col, SVET_ERR_RANGE,
                              "'%s' must be at least 1 photon", key);
    svet_error e;
    svet_status st = photonmap_check_count(v->u > SIZE_MAX ? SIZE_MAX
                                                           : (size_t)v->u, &e);
    if (st != SVET_OK)
        return scenefile_fail(c, v->col, st, "'%s': %s", key, e.msg);
    return SVET_OK;
}

static svet_status photon_statement(scenefile_ctx *c)
{
    val_t v[P_N];
    svet_status st = scenefile_keys(c, "photonmap", photon_spec, P_N, v,
                                    false);
    if (st)
        return st;
    if (v[P_GLOBAL].set && (st = check_count(c, &v[P_GLOBAL], "global")))
        return st;
    if (v[P_CAUSTIC].set && (st = check_count(c, &v[P_CAUSTIC], "caustic")))
        return st;
    if (v[P_ALPHA].set && !(v[P_ALPHA].v[0] < 1))
        return scenefile_fail(c, v[P_ALPHA].col, SVET_ERR_RANGE,
                              "'alpha' = %g: must lie in (0, 1)",
                              (double)v[P_ALPHA].v[0]);
    /* the line updates the settings: `--set photonmap.k=20` reruns it */
    scene_t *s = scenefile_scene(c);
    bool fresh;
    photon_settings_t *p = scene_part_data_new(s, "photon", sizeof *p, free, &fresh);
    if (!p)
        return scenefile_fail(c, scenefile_stmt_col(c), SVET_ERR_NOMEM,
                              "out of memory");
    if (fresh)
        photon_settings_default(p);
    if (v[P_GLOBAL].set)
        p->global = v[P_GLOBAL].u;
    if (v[P_CAUSTIC].set)
        p->caustic = v[P_CAUSTIC].u;
    if (v[P_K].set)
        p->k = (int)v[P_K].i;
    if (v[P_MAXR].set)
        p->max_radius = v[P_MAXR].v[0];
    if (v[P_FILTER].set)
        p->filter = (photonmap_filter_t)v[P_FILTER].i;
    if (v[P_GATHER].set)
        p->gather = (int)v[P_GATHER].i;
    if (v[P_ALPHA].set)
        p->alpha = v[P_ALPHA].v[0];
    if (v[P_RADIUS].set)
        p->radius = v[P_RADIUS].v[0];
    if (v[P_PRECOMPUTE].set)
        p->precompute = (int)v[P_PRECOMPUTE].i;
    return SVET_OK;
}

/* --- emission and tracing (Jensen 2001, ch. 5) -------------------------- */

void photon_records_push(photon_records_t *b, const VECTOR3 pos,
                         const VECTOR3 dir, const VECTOR3 n, RADIANCE power)
{
    if (b->failed)
        return;
    if (b->n == b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 1024;
        photon_record_t *r = realloc(b->r, cap * sizeof *r);
        if (!r) {
            b->failed = true;
            return;
        }
        b->r = r;
        b->cap = cap;
    }
    photon_record_t *q = &b->r[b->n++];
    vec_copy(q->pos, pos);
    vec_copy(q->dir, dir);
    vec_copy(q->n, n);
    q->power = power;
}

void photon_records_free(photon_records_t *lists, uint64_t n)
{
    if (!lists)
        return;
    for (uint64_t i = 0; i < n; i++)
        free(lists[i].r);
    free(lists);
}

/* The power light l emits photons with (emit()), luminance of it: a
 * point light 4 pi I, an area light sides pi L_e A, the environment pi R^2
 * (the disc the photons cross) times 4 pi L (the radiance's integral over
 * the sphere, its mean L for a uniform sky): pbrt-v3 sec. 16.1.2,
 * InfiniteAreaLight::Sample_Le, whose weight L / (pdf_pos pdf_dir) is
 * L / ((1 / pi R^2) (1 / 4 pi)). */
static real emitted_power(const light_t *l, real R)
{
    switch (l->kind) {
    case LIGHT_POINT:
        return fmax(REAL_C(0.0), rad_luminance(l->intensity)) * 4 * REAL_PI;
    case LIGHT_AREA: {
        real sides = l->emission->two_sided ? 2 : 1;
        return isfinite(l->area)
                   ? fmax(REAL_C(0.0), rad_luminance(l->emission->radiance)) *
                         sides * REAL_PI * l->area
                   : 0;
    }
    case LIGHT_ENVIRONMENT:
        return fmax(REAL_C(0.0), rad_luminance(l->radiance)) * 4 * REAL_PI *
               REAL_PI * R * R;
    }
    return 0;
}

/* The sphere the environment's photons leave from: it must hold every
 * point a photon should reach. The bounded objects' box, as the light set
 * takes it; an unbounded object (a plane, whose box spans the reals or a
 * clipped stand-in, and whose area is infinite) can't be held, so where
 * one is present the box also takes the ball about the camera's target
 * of radius its distance from the eye: the eye, the target and, for a
 * field of view up to 90 degrees, the width of the view at the target's
 * distance, where the camera looks. A point inside the sphere gets the
 * environment's whole irradiance: every ray toward it crosses the disc
 * of radius R facing the ray's direction. */
static void emitters_sphere(const scene_t *s, VECTOR3 centre, real *radius)
{
    bbox_t all;
    bbox_empty(&all);
    bool unbounded = false;
    for (int i = 0; i < s->nobjects; i++) {
        const COBJECT *o = s->objects[i];
        bbox_t b;
        o->ops->bounds(o, -1, &b);
        if (bbox_is_empty(&b))
            continue;
        if (vec_is_finite(b.min) && vec_is_finite(b.max) &&
            isfinite(o->ops->area(o)))
            bbox_union(&all, &b);
        else
            unbounded = true;
    }
    if (unbounded) {
        const VECTOR3 *e = &s->camera.position, *t = &s->camera.target;
        real d = vec_distance(*e, *t);
        VECTOR3 lo, hi;
        for (int a = 0; a < 3; a++) {
            lo[a] = (*t)[a] - d;
            hi[a] = (*t)[a] + d;
        }
        bbox_add_point(&all, lo);
        bbox_add_point(&all, hi);
    }
    if (bbox_is_empty(&all)) {
        vec_set(centre, 0, 0, 0);
        *radius = 1;
        return;
    }
    bbox_centroid(centre, &all);
    *radius = REAL_C(0.5) * vec_distance(all.max, all.min);
    if (!(*radius > 0))
        *radius = 1;
}

svet_status photon_emitters_build(photon_emitters_t *em, const render_t *r,
                                  svet_error *err)
{
    const lightset_t *ls = &r->lights;
    emitters_sphere(r->scene, em->centre, &em->radius);
    em->n = ls->n;
    em->cdf = malloc(((size_t)ls->n + 1) * sizeof *em->cdf);
    if (!em->cdf)
        return svet_error_set(err, SVET_ERR_NOMEM,
                              "photon tracing: out of memory");
    real total = 0;
    for (int i = 0; i < ls->n; i++)
        total += emitted_power(&ls->lights[i], em->radius);
    em->cdf[0] = 0;
    for (int i = 0; i < ls->n; i++)
        em->cdf[i + 1] = em->cdf[i] +
                         (total > 0 ? emitted_power(&ls->lights[i], em->radius) /
                                          total
                                    : REAL_C(1.0) / (real)ls->n);
    em->cdf[ls->n] = 1;
    return SVET_OK;
}

/* the light for u in [0, 1): the first i with cdf[i+1] > u, so a light of
 * no power is never chosen; *pmf its chance */
static int emitters_pick(const photon_emitters_t *em, real u, real *pmf)
{
    int lo = 0, hi = em->n - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (em->cdf[mid + 1] > u)
            hi = mid;
        else
            lo = mid + 1;
    }
    *pmf = em->cdf[lo + 1] - em->cdf[lo];
    return lo;
}

/* The photon's first ray and power from the light l chosen with chance
 * pmf: a point light emits isotropically, Phi = 4 pi I; an area light
 * from a point uniform by area, cosine-weighted about its normal (on a
 * side chosen at random when it emits on both), Phi = sides pi L_e A
 * (Jensen 2001, sec. 5.1.1); the environment along a direction uniform
 * over the sphere from a point uniform on the disc of the emitters'
 * sphere (centre c, radius R) facing it, the disc's plane R behind c:
 * every ray that can reach the sphere crosses that disc, and Phi = pi R^2
 * times the radiance's integral over the sphere, 4 pi L (pbrt-v3 sec.
 * 16.1.2, InfiniteAreaLight::Sample_Le, whose weight is L / (pdf_pos
 * pdf_dir); Jensen 2001, sec. 5.1.1). Returns false for a degenerate
 * sample. */
static bool emit(const photon_emitters_t *em, const light_t *l, real pmf,
                 uint64_t count, pcg32_t *g, ray_t *ray, RADIANCE *power,
                 const COBJECT **from)
{
    real u[2] = { pcg32_real(g), pcg32_real(g) };
    real us = pcg32_real(g), ud[2] = { pcg32_real(g), pcg32_real(g) };
    real share = 1 / (pmf * (real)count);
    *from = NULL;
    if (l->kind == LIGHT_POINT) {
        VECTOR3 d;
        sample_uniform_sphere(d, u);
        vec_copy(ray->o, l->position);
        vec_copy(ray->d, d);
        *power = rad_scale(l->intensity, 4 * REAL_PI * share);
        return true;
    }
    if (l->kind == LIGHT_ENVIRONMENT) {
        VECTOR3 d, t1, t2, disc;
        real R = em->radius;
        sample_uniform_sphere(d, u);
        frame_from_normal(t1, t2, d);
        real rr = R * sqrt(ud[0]), phi = 2 * REAL_PI * ud[1];
        vec_set(disc, rr * cos(phi), rr * sin(phi), 0);
        frame_to_world(ray->o, disc, t1, t2, d);
        for (int a = 0; a < 3; a++)
            ray->o[a] += em->centre[a] - R * d[a];
        vec_copy(ray->d, d);
        *power = rad_scale(l->radiance, 4 * REAL_PI * REAL_PI * R * R * share);
        return true;
    }
    if (l->kind != LIGHT_AREA)
        return false;
    const COBJECT *obj = l->emission->obj;
    cobject_sample_t cs;
    obj->ops->sample(obj, u, &cs);
    if (!(cs.pdf > 0))
        return false;
    VECTOR3 n, t1, t2, local, d;
    vec_copy(n, cs.n);
    real sides = 1;
    if (l->emission->two_sided) {
        sides = 2;
        if (us < REAL_C(0.5))
            vec_scale(n, n, -1);
    }
    frame_from_normal(t1, t2, n);
    sample_cosine_hemisphere(local, ud);
    frame_to_world(d, local, t1, t2, n);
    ray_spawn(ray, cs.p, cs.p_error, cs.n, d);
    *power = rad_scale(light_emitted_at_sample(l->emission, &cs),
                       sides * REAL_PI / cs.pdf * share);
    *from = obj;
    return true;
}

void photon_emitters_free(photon_emitters_t *em)
{
    free(em->cdf);
    em->cdf = NULL;
}

bool photon_emit(const render_t *r, const photon_emitters_t *em,
                 uint64_t count, pcg32_t *g, ray_t *ray, RADIANCE *power,
                 const COBJECT **from)
{
    real pmf;
    const light_t *l = &r->lights.lights[emitters_pick(em, pcg32_real(g),
                                                       &pmf)];
    *from = NULL;
    return pmf > 0 && emit(em, l, pmf, count, g, ray, power, from);
}

/* The bounce of photon_bounce (photon.h). The material samples wi for a
 * given wo; a photon needs the adjoint, a new direction for the one it
 * came from. By reciprocity f(wi, wo) = f(wo, wi), so sampling with wo =
 * the photon's incoming direction gives the outgoing one with the weight
 * f |cos| / pdf the flux needs. Refraction's radiance scaling (eta^2) is
 * not the flux's: svet transports basic radiance L / n^2 (brdf.c), in
 * which the BTDF is symmetric and rho_t(theta) is the same both ways, so
 * the photon's power is multiplied by rho_t(theta) alone, as flux is
 * conserved across the interface (Veach 1997, sec. 5.2). Russian roulette
 * by the weight's largest channel keeps the powers equal (Jensen 2001,
 * sec. 5.2). */
bool photon_bounce(const material_t *m, const PATHPOINT *pp, pcg32_t *g,
                   RADIANCE *power, ray_t *ray, bool *delta)
{
    VECTOR3 wo, wi;
    frame_to_local(wo, pp->out, pp->u, pp->v, pp->n);
    real u[3] = { pcg32_real(g), pcg32_real(g), pcg32_real(g) };
    real urr = pcg32_real(g);
    brdf_sample_t bs;
    if (!material_sample(m, wo, u, &bs))
        return false;
    if (delta)
        *delta = bs.delta;
    real q = real_min(rad_max(bs.weight), REAL_C(1.0));
    if (!(urr < q))
        return false;
    *power = rad_scale(rad_mul(*power, bs.weight), 1 / q);
    frame_to_world(wi, bs.wi, pp->u, pp->v, pp->n);
    ray_spawn(ray, pp->cross_point, pp->p_error, pp->ng, wi);
    return true;
}

/* what trace_one stores, and the stream it draws from */
typedef struct {
    photon_kind_t kind;
    uint64_t stream;
} walk_t;

/* Trace photon `index`: bounce by the materials' own sampling
 * (photon_bounce), store where the kind asks. */
static void trace_one(const render_t *r, const photon_emitters_t *em,
                      uint64_t count, uint64_t index, void *ctx,
                      photon_records_t *out)
{
    const walk_t *w = ctx;
    const photon_kind_t kind = w->kind;
    pcg32_t g;
    rng_for_sample(&g, r->scene->render.seed ^ PHOTON_SEED_SALT, w->stream,
                   index);
    ray_t ray;
    RADIANCE power;
    const COBJECT *skip[2] = { NULL, NULL };
    if (!photon_emit(r, em, count, &g, &ray, &power, &skip[0]))
        return;
    bool diffuse_seen = false;
    const int max_depth = r->scene->render.max_depth;
    for (int depth = 0; depth <= max_depth; depth++) {
        hit_t h;
        const COBJECT *obj = NULL;
        if (!r->tracer.intersect(r->tracer.ctx, &ray, 0, (real)INFINITY, skip,
                                 &h, &obj))
            return;
        PATHPOINT pp;
        cobject_fill(obj, &ray, &h, &pp);
        /* a part's per-hit shading (a texture: scene.h), as the camera's
         * paths see it, so a textured reflectance colours the photon; a
         * photon's ray has no pixel footprint: depth + 1 reads the finest
         * level, as a camera path's later bounces do */
        const material_t *m = obj->material;
        material_t shaded;
        if (obj->texture)
            m = r->scene->shade(r->scene, obj, &ray, depth + 1, &pp, NULL,
                                &shaded);
        VECTOR3 dir;
        vec_normalize(dir, ray.d);
        if (!material_is_specular(m) && m->ncomp > 0) {
            bool store = kind == PHOTON_GLOBAL ||
                         (kind == PHOTON_INDIRECT && depth > 0) ||
                         (kind == PHOTON_CAUSTIC && depth > 0 && !diffuse_seen);
            if (store) {
                VECTOR3 n;
                vec_scale(n, pp.n, SVECTOR3(pp.n, dir) > 0 ? -1 : 1);
                photon_records_push(out, pp.cross_point, dir, n, power);
            }
        }
        if (depth == max_depth)
            return;
        bool delta = true;
        if (!photon_bounce(m, &pp, &g, &power, &ray, &delta))
            return;
        if (!delta) {
            diffuse_seen = true;
            if (kind == PHOTON_CAUSTIC)
                return; /* it can no longer make a caustic */
        }
        skip[0] = obj;
    }
}

svet_status photon_trace_records(const render_t *r, uint64_t count,
                                 int threads, int nlists, photon_walk_fn walk,
                                 void *ctx, const char *what,
                                 photon_records_t **lists, uint64_t *nchunks,
                                 svet_error *err)
{
    *lists = NULL;
    *nchunks = 0;
    if (count == 0 || r->lights.n == 0)
        return SVET_OK;
    uint64_t nc = (count + PHOTON_CHUNK - 1) / PHOTON_CHUNK;
    if (nc > SIZE_MAX / ((size_t)nlists * sizeof(photon_records_t)))
        return svet_error_set(err, SVET_ERR_NOMEM, "%s: %llu photons are too "
                              "many", what, (unsigned long long)count);
    photon_emitters_t em;
    svet_status st = photon_emitters_build(&em, r, err);
    if (st != SVET_OK)
        return st;
    photon_records_t *l = calloc((size_t)nc * (size_t)nlists, sizeof *l);
    if (!l) {
        photon_emitters_free(&em);
        return svet_error_set(err, SVET_ERR_NOMEM, "%s: out of memory", what);
    }
#ifdef _OPENMP
    int nt = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
#else
    (void)threads;
#endif
    for (long long c = 0; c < (long long)nc; c++) {
        photon_records_t out[PHOTON_MAX_LISTS];
        memset(out, 0, sizeof out);
        uint64_t i0 = (uint64_t)c * PHOTON_CHUNK;
        uint64_t i1 = i0 + PHOTON_CHUNK < count ? i0 + PHOTON_CHUNK : count;
        for (uint64_t i = i0; i < i1; i++)
            walk(r, &em, count, i, ctx, out);
        for (int j = 0; j < nlists; j++)
            l[(uint64_t)j * nc + (uint64_t)c] = out[j];
    }
    photon_emitters_free(&em);
    *lists = l;
    *nchunks = nc;
    return SVET_OK;
}

svet_status photon_records_store(const photon_records_t *lists, uint64_t n,
                                 uint8_t flags, const char *what,
                                 photonmap_t *m, svet_error *err)
{
    size_t total = 0;
    for (uint64_t c = 0; c < n; c++) {
        if (lists[c].failed)
            return svet_error_set(err, SVET_ERR_NOMEM, "%s: out of memory",
                                  what);
        total += lists[c].n;
    }
    if (total == 0)
        return SVET_OK;
    svet_status st = photonmap_init(m, total, err);
    if (st != SVET_OK)
        return st;
    for (uint64_t c = 0; c < n; c++)
        for (size_t i = 0; i < lists[c].n; i++) {
            const photon_record_t *rec = &lists[c].r[i];
            photonmap_store(m, rec->pos, rec->power, rec->dir, flags);
        }
    return photonmap_balance(m, err);
}

/* photon_trace and photon_trace_precomputed: irr, when not NULL, gets the
 * irradiance at every `every`-th stored photon in record order */
static svet_status trace(const render_t *r, uint64_t count,
                         photon_kind_t kind, uint64_t stream, int threads,
                         photonmap_t *m, size_t every,
                         const photonmap_query_t *q, photonmap_t *irr,
                         svet_error *err)
{
    memset(m, 0, sizeof *m);
    m->balanced = true; /* an empty map answers every query with nothing */
    if (irr) {
        memset(irr, 0, sizeof *irr);
        irr->balanced = true;
    }
    walk_t w = { kind, stream };
    photon_records_t *lists;
    uint64_t nchunks;
    svet_status st = photon_trace_records(r, count, threads, 1, trace_one, &w,
                                          "photon tracing", &lists, &nchunks,
                                          err);
    if (st == SVET_OK)
        st = photon_records_store(lists, nchunks, (uint8_t)kind,
                                  "photon tracing", m, err);
    /* the precomputation's points: every `every`-th record */
    size_t npts = st == SVET_OK && irr && every > 0 && m->n > 0
                      ? (m->n - 1) / every + 1 : 0;
    float (*pts)[3] = NULL, (*nrm)[3] = NULL;
    if (npts > 0) {
        pts = malloc(npts * sizeof *pts);
        nrm = malloc(npts * sizeof *nrm);
        if (!pts || !nrm)
            st = svet_error_set(err, SVET_ERR_NOMEM,
                                "photon tracing: out of memory");
    }
    size_t at = 0;
    for (uint64_t c = 0; st == SVET_OK && npts > 0 && c < nchunks; c++)
        for (size_t i = 0; i < lists[c].n; i++, at++)
            if (at % every == 0)
                for (int a = 0; a < 3; a++) {
                    pts[at / every][a] = (float)lists[c].r[i].pos[a];
                    nrm[at / every][a] = (float)lists[c].r[i].n[a];
                }
    photon_records_free(lists, nchunks);
    if (st == SVET_OK && npts > 0)
        st = photonmap_precompute(m, q, (const float (*)[3])pts,
                                  (const float (*)[3])nrm, npts, threads, irr,
                                  err);
    free(pts);
    free(nrm);
    if (st != SVET_OK) {
        photonmap_free(m);
        m->balanced = true;
    }
    return st;
}

svet_status photon_trace(const render_t *r, uint64_t count,
                         photon_kind_t kind, uint64_t stream, int threads,
                         photonmap_t *m, svet_error *err)
{
    return trace(r, count, kind, stream, threads, m, 0, NULL, NULL, err);
}

svet_status photon_trace_precomputed(const render_t *r, uint64_t count,
                                     photon_kind_t kind, uint64_t stream,
                                     int threads, size_t every,
                                     const photonmap_query_t *q,
                                     photonmap_t *m, photonmap_t *irr,
                                     svet_error *err)
{
    return trace(r, count, kind, stream, threads, m, every, q, irr, err);
}

/* --- the radiance estimate ---------------------------------------------- */

RADIANCE photon_radiance(const photonmap_t *m, const PATHPOINT *pp,
                         const material_t *mat, const VECTOR3 wo,
                         const photonmap_query_t *q)
{
    int32_t idx[PHOTON_MAX_K];
    real d2[PHOTON_MAX_K];
    int k = q->k < PHOTON_MAX_K ? q->k : PHOTON_MAX_K;
    int found = photonmap_nearest(m, pp->cross_point, k, q->rmax, idx, d2);
    real r2 = found == k ? d2[found - 1] : q->rmax * q->rmax;
    RADIANCE L = rad_grey(0);
    if (found == 0 || !(r2 > 0))
        return L;
    real r = sqrt(r2);
    for (int i = 0; i < found; i++) {
        const photon_t *p = &m->ph[idx[i]];
        VECTOR3 d, wi, wl;
        VECTOR3 off = { (real)p->pos[0] - pp->cross_point[X],
                        (real)p->pos[1] - pp->cross_point[Y],
                        (real)p->pos[2] - pp->cross_point[Z] };
        if (q->disc > 0 && fabs(SVECTOR3(off, pp->ng)) > q->disc * r)
            continue; /* off the surface's plane: another surface */
        photonmap_direction(p, d);
        vec_scale(wi, d, -1); /* toward where the photon came from */
        frame_to_local(wl, wi, pp->u, pp->v, pp->n);
        RADIANCE f = material_eval(mat, wl, wo);
        if (rad_is_black(f))
            continue;
        real w = photonmap_filter_weight(q, d2[i], r2);
        RADIANCE phi = rad_make((real)p->power[0], (real)p->power[1],
                                (real)p->power[2]);
        L = rad_add(L, rad_scale(rad_mul(f, phi), w));
    }
    return rad_scale(L, 1 / photonmap_filter_area(q, r2));
}

/* --- the methods ---------------------------------------------------------- */

typedef struct {
    photon_settings_t set;
    bool ppm;
    photonmap_t global, caustic;   /* photon */
    photonmap_t irr;               /* photon: Christensen's precomputed
                                      irradiance at every precompute-th
                                      global photon */
    photonmap_t *maps;             /* ppm: one per sample index in [s0, s1) */
    long s0, nmaps;
} state_t;

static void state_free(void *p)
{
    state_t *s = p;
    if (!s)
        return;
    photonmap_free(&s->global);
    photonmap_free(&s->caustic);
    photonmap_free(&s->irr);
    for (long i = 0; i < s->nmaps; i++)
        photonmap_free(&s->maps[i]);
    free(s->maps);
    free(s);
}

static photonmap_query_t query_of(const photon_settings_t *set, real rmax)
{
    photonmap_query_t q = { set->k, rmax, set->filter, REAL_C(1.1),
                            REAL_C(0.25) };
    return q;
}

static svet_status prepare(void **out, const render_t *r, int threads,
                           bool ppm, svet_error *err)
{
    state_t *s = calloc(1, sizeof *s);
    if (!s)
        return svet_error_set(err, SVET_ERR_NOMEM, "photon: out of memory");
    photon_settings_of(r->scene, &s->set);
    s->ppm = ppm;
    s->global.balanced = s->caustic.balanced = s->irr.balanced = true;
    svet_status st = SVET_OK;
    if (!ppm) {
        photonmap_query_t q = query_of(&s->set, s->set.max_radius);
        /* the preview (gather 0) looks the map up where the camera
         * lands, not by gathering: it does not use the precomputation */
        size_t every = s->set.gather > 0 ? (size_t)s->set.precompute : 0;
        st = photon_trace_precomputed(r, s->set.global, PHOTON_GLOBAL, 0,
                                      threads, every, &q, &s->global,
                                      &s->irr, err);
        if (st == SVET_OK)
            st = photon_trace(r, s->set.caustic, PHOTON_CAUSTIC, 1, threads,
                              &s->caustic, err);
    }
    if (st != SVET_OK) {
        state_free(s);
        return st;
    }
    *out = s;
    return SVET_OK;
}

static svet_status prepare_photon(void **out, const render_t *r, int threads,
                                  svet_error *err)
{
    return prepare(out, r, threads, false, err);
}

static svet_status prepare_ppm(void **out, const render_t *r, int threads,
                               svet_error *err)
{
    return prepare(out, r, threads, true, err);
}

/* photon's pre-pass to a file: the global map, the caustic map and the
 * precomputed irradiance, each as photonsave.h writes a map */
static svet_status save_photon(const void *state, FILE *f, svet_error *err)
{
    const state_t *s = state;
    svet_status st = SVET_OK;
    if (fprintf(f, "photon maps 3\n") < 0)
        return svet_error_set(err, SVET_ERR_IO, "photon: a write failed");
    const photonmap_t *maps[] = { &s->global, &s->caustic, &s->irr };
    for (int k = 0; k < 3 && st == SVET_OK; k++)
        st = photonmap_write(maps[k], f, err);
    return st;
}

/* the state prepare_photon makes, with the maps save_photon wrote */
static svet_status load_photon(void **out, const render_t *r, FILE *f,
                               svet_error *err)
{
    state_t *s = calloc(1, sizeof *s);
    if (!s)
        return svet_error_set(err, SVET_ERR_NOMEM, "photon: out of memory");
    photon_settings_of(r->scene, &s->set);
    s->global.balanced = s->caustic.balanced = s->irr.balanced = true;
    int nmaps = 0;
    svet_status st = SVET_OK;
    if (fscanf(f, "photon maps %d", &nmaps) != 1 || nmaps != 3 ||
        fgetc(f) != '\n')
        st = svet_error_set(err, SVET_ERR_PARSE,
                            "not the pre-pass of integrator photon (no "
                            "'photon maps 3' line)");
    photonmap_t *maps[] = { &s->global, &s->caustic, &s->irr };
    for (int k = 0; k < 3 && st == SVET_OK; k++)
        st = photonmap_read(maps[k], f, err);
    if (st != SVET_OK) {
        state_free(s);
        return st;
    }
    *out = s;
    return SVET_OK;
}

/* ppm: the maps of sample indices [s0, s1), map i from stream 2 + i, so
 * that sample i sees the same map however the samples are split into
 * passes (render.h) */
static svet_status begin_ppm(void *state, const render_t *r, long s0, long s1,
                             int threads, svet_error *err)
{
    state_t *s = state;
    for (long i = 0; i < s->nmaps; i++)
        photonmap_free(&s->maps[i]);
    free(s->maps);
    s->maps = NULL;
    s->nmaps = 0;
    long n = s1 - s0;
    /* the maps of the pass live at once: refuse before tracing what
     * would not fit (each photon stores at least once on average in a
     * closed scene) */
    size_t total = s->set.global > SIZE_MAX / (size_t)n
                       ? SIZE_MAX : (size_t)n * (size_t)s->set.global;
    svet_error e;
    svet_status st = photonmap_check_count(total, &e);
    if (st != SVET_OK)
        return svet_error_set(err, st, "ppm: %ld maps of %llu photons, one "
                              "for each sample index of the pass: %s (fewer "
                              "samples a pass, `render passes`, or fewer "
                              "photons)", n, (unsigned long long)s->set.global,
                              e.msg);
    s->maps = calloc((size_t)n, sizeof *s->maps);
    if (!s->maps)
        return svet_error_set(err, SVET_ERR_NOMEM, "ppm: out of memory");
    s->s0 = s0;
    s->nmaps = n;
    for (long i = 0; i < n; i++) {
        st = photon_trace(r, s->set.global, PHOTON_INDIRECT,
                          2 + (uint64_t)(s0 + i), threads, &s->maps[i], err);
        if (st != SVET_OK)
            return st;
    }
    return SVET_OK;
}

/* The global map's estimate where a final-gather ray from x lands:
 * through delta bounces (a gather ray that leaves by glass still finds the
 * diffuse light behind it) to the first surface with a non-delta part.
 * Emission there is not counted: direct light is light sampling's, and
 * light through delta bounces is the caustic map's. */
static RADIANCE gather_lookup(const state_t *s, const render_t *r, ray_t ray,
                              const COBJECT *from, pcg32_t *g,
                              integrator_stats_t *st)
{
    RADIANCE beta = rad_grey(1);
    const COBJECT *skip[2] = { from, NULL };
    photonmap_query_t q = query_of(&s->set, s->set.max_radius);
    for (int depth = 0; depth < 16; depth++) {
        hit_t h;
        const COBJECT *obj = NULL;
        st->rays++;
        if (!r->tracer.intersect(r->tracer.ctx, &ray, 0, (real)INFINITY, skip,
                                 &h, &obj))
            return rad_grey(0);
        PATHPOINT pp;
        cobject_fill(obj, &ray, &h, &pp);
        /* the per-hit shading (scene.h); a gather ray is a later bounce */
        const material_t *m = obj->material;
        material_t shaded;
        if (obj->texture)
            m = r->scene->shade(r->scene, obj, &ray, depth + 1, &pp, NULL,
                                &shaded);
        VECTOR3 wo, wi;
        frame_to_local(wo, pp.out, pp.u, pp.v, pp.n);
        if (!material_is_specular(m)) {
            /* Christensen 1999: the nearest precomputed irradiance on
             * this side of the surface, times the reflectance toward wo
             * (f(n, wo): rho / pi on a Lambert surface), else the plain
             * estimate */
            VECTOR3 n, nl;
            RADIANCE e;
            vec_scale(n, pp.n, SVECTOR3(pp.n, pp.out) < 0 ? -1 : 1);
            if (s->irr.n > 0 &&
                photonmap_precomputed(&s->irr, pp.cross_point, n, q.rmax,
                                      &e)) {
                frame_to_local(nl, n, pp.u, pp.v, pp.n);
                return rad_mul(beta, rad_mul(e, material_eval(m, nl, wo)));
            }
            return rad_mul(beta, photon_radiance(&s->global, &pp, m, wo, &q));
        }
        real u[3] = { pcg32_real(g), pcg32_real(g), pcg32_real(g) };
        brdf_sample_t bs;
        if (!material_sample(m, wo, u, &bs))
            return rad_grey(0);
        beta = rad_mul(beta, bs.weight);
        frame_to_world(wi, bs.wi, pp.u, pp.v, pp.n);
        ray_spawn(&ray, pp.cross_point, pp.p_error, pp.ng, wi);
        skip[0] = obj;
    }
    return rad_grey(0);
}

/* The light leaving a surface with a non-delta part toward wo, by the
 * method: photon with gathering: direct by light sampling + caustic map +
 * final gathering from the global map (Jensen 2001, sec. 9.1); photon
 * without: the global map alone; ppm: direct by light sampling + the
 * sample's map of indirect photons at its radius. */
static RADIANCE at_surface(const state_t *s, const render_t *r,
                           const PATHPOINT *pp, const material_t *m,
                           const VECTOR3 wo, long sample, pcg32_t *g,
                           integrator_stats_t *st)
{
    if (s->ppm) {
        RADIANCE L = integrator_direct(&r->integrator, pp, m, wo, false, g,
                                       st);
        long i = sample - s->s0;
        if (i < 0 || i >= s->nmaps)
            return L;
        /* r_i = r_1 i^((alpha - 1) / 2), i counted from 1 (Knaus &
         * Zwicker 2011, eq. 16 with the exponent of its sec. 4.3) */
        real ri = s->set.radius *
                  pow((real)(sample + 1), (s->set.alpha - 1) / 2);
        photonmap_query_t q = query_of(&s->set, ri);
        return rad_add(L, photon_radiance(&s->maps[i], pp, m, wo, &q));
    }
    photonmap_query_t q = query_of(&s->set, s->set.max_radius);
    if (s->set.gather == 0)
        return photon_radiance(&s->global, pp, m, wo, &q);
    RADIANCE L = integrator_direct(&r->integrator, pp, m, wo, false, g, st);
    L = rad_add(L, photon_radiance(&s->caustic, pp, m, wo, &q));
    RADIANCE ind = rad_grey(0);
    for (int j = 0; j < s->set.gather; j++) {
        real u[3] = { pcg32_real(g), pcg32_real(g), pcg32_real(g) };
        brdf_sample_t bs;
        /* the delta part is followed by the caller */
        if (!material_sample(m, wo, u, &bs) || bs.delta)
            continue;
        VECTOR3 wi;
        frame_to_world(wi, bs.wi, pp->u, pp->v, pp->n);
        ray_t gr;
        ray_spawn(&gr, pp->cross_point, pp->p_error, pp->ng, wi);
        ind = rad_add(ind, rad_mul(bs.weight, gather_lookup(s, r, gr,
                                                            pp->IntersectObj,
                                                            g, st)));
    }
    return rad_add(L, rad_scale(ind, 1 / (real)s->set.gather));
}

/* The camera path: emitters seen directly or through delta bounces, delta
 * bounces followed as the path tracer does (ch. 5), and at the first
 * surface with a non-delta part the estimate of at_surface(); a delta
 * part there (a varnish's mirror) continues the path. */
static RADIANCE li(const void *state, const render_t *r, const ray_t *camera,
                   long sample, pcg32_t *g, integrator_stats_t *st)
{
    const state_t *s = state;
    const scene_t *sc = r->scene;
    st->paths++;
    RADIANCE L = rad_grey(0), beta = rad_grey(1);
    ray_t ray = *camera;
    const COBJECT *skip[2] = { NULL, NULL };
    for (int depth = 0;; depth++) {
        hit_t h;
        const COBJECT *obj = NULL;
        st->rays++;
        if (!r->tracer.intersect(r->tracer.ctx, &ray, 0, (real)INFINITY, skip,
                                 &h, &obj)) {
            if (sc->has_environment)
                L = rad_add(L, rad_mul(beta, sc->environment));
            break;
        }
        PATHPOINT pp;
        cobject_fill(obj, &ray, &h, &pp);
        if (obj->light)
            L = rad_add(L, rad_mul(beta, light_emitted(obj->light, &pp)));
        if (depth >= sc->render.max_depth)
            break;
        /* the per-hit shading (scene.h), as the path tracer's */
        const material_t *m = obj->material;
        material_t shaded;
        if (obj->texture)
            m = sc->shade(sc, obj, &ray, depth, &pp, NULL, &shaded);
        VECTOR3 wo, wi;
        frame_to_local(wo, pp.out, pp.u, pp.v, pp.n);
        bool diffuse = !material_is_specular(m) && m->ncomp > 0;
        if (diffuse)
            L = rad_add(L, rad_mul(beta, at_surface(s, r, &pp, m, wo, sample,
                                                   g, st)));
        real u[3] = { pcg32_real(g), pcg32_real(g), pcg32_real(g) };
        brdf_sample_t bs;
        if (!material_sample(m, wo, u, &bs) || (diffuse && !bs.delta))
            break;
        beta = rad_mul(beta, bs.weight);
        if (rad_is_black(beta))
            break;
        frame_to_world(wi, bs.wi, pp.u, pp.v, pp.n);
        ray_spawn(&ray, pp.cross_point, pp.p_error, pp.ng, wi);
        skip[0] = obj;
    }
    return L;
}

const render_method_t photon_method = {
    "photon", "photon maps (ch. 8): global and caustic maps, final gathering",
    prepare_photon, NULL, li, state_free, NULL, save_photon, load_photon, false
};
const render_method_t photon_ppm_method = {
    "ppm", "progressive photon maps (Knaus & Zwicker 2011): a map per sample",
    prepare_ppm, begin_ppm, li, state_free, NULL, NULL, NULL, false
};

static const render_method_t *const methods[] = { &photon_method,
                                                  &photon_ppm_method, NULL };
static const scene_statement_t statements[] = {
    { "photonmap", photon_statement }, { NULL, NULL }
};
const scene_part_t photon_part = { .name = "photon",
                                   .statements = statements,
                                   .methods = methods };
