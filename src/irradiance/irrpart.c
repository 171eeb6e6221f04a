/*
 * irrpart.c - the irradiance cache of ch. 9 as a part of the renderer: the
 * `irradiance` statement, the coarse-to-fine pre-pass that fills the cache
 * (Ward, Rubinstein, Clear 1988, sec. 3; its order made deterministic),
 * the record's gather with app. E's gradients (Ward & Heckbert 1992), and
 * the method `irradiance`: direct light by ch. 5's light sampling,
 * mirrors and glass followed as the path tracer does, and the indirect
 * light of a Lambert surface from the cache, E rho_d / pi.
 * Tests: tests/irradiance/test_irrpart.c
 */
#include "irradiance/irrpart.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/frame.h"
#include "irradiance/gradients.h"
#include "materials/material.h"
#include "render/integrator.h"
#include "render/light.h"
#include "render/render.h"

/* the pre-pass's random numbers: a stream of its own beside the camera's */
#define IRR_SEED_SALT UINT64_C(0x1AAD1A4CEC0FFEE5)

/* --- settings: the `irradiance` statement ------------------------------- */

void irr_settings_default(irr_settings_t *s)
{
    s->a = REAL_C(0.15);
    s->m = 8;
    s->n = 32;
    s->min_r = 1;
    s->max_r = 20;
    s->bounces = 1;
    s->gradients = true;
    s->clamp = true;
}

void irr_settings_of(const scene_t *s, irr_settings_t *out)
{
    const irr_settings_t *p = scene_part_data(s, "irradiance");
    if (p)
        *out = *p;
    else
        irr_settings_default(out);
}

enum { I_A, I_M, I_N, I_MINR, I_MAXR, I_BOUNCES, I_GRAD, I_CLAMP, I_N_ };
static const spec_t irr_spec[I_N_] = {
    [I_A] = { "a", V_NUM, F_POSITIVE, 0, 0, NULL },
    [I_M] = { "m", V_INT, 0, 1, 1024, NULL },
    [I_N] = { "n", V_INT, 0, 1, 4096, NULL },
    [I_MINR] = { "min_r", V_NUM, F_POSITIVE, 0, 0, NULL },
    [I_MAXR] = { "max_r", V_NUM, F_POSITIVE, 0, 0, NULL },
    [I_BOUNCES] = { "bounces", V_INT, 0, 1, 64, NULL },
    [I_GRAD] = { "gradients", V_ONOFF, 0, 0, 0, NULL },
    [I_CLAMP] = { "clamp", V_ONOFF, 0, 0, 0, NULL },
};

static svet_status irr_statement(scenefile_ctx *c)
{
    val_t v[I_N_];
    svet_status st = scenefile_keys(c, "irradiance", irr_spec, I_N_, v,
                                    false);
    if (st)
        return st;
    if (v[I_A].set && !(v[I_A].v[0] <= 1))
        return scenefile_fail(c, v[I_A].col, SVET_ERR_RANGE,
                              "'a' = %g: must lie in (0, 1]",
                              (double)v[I_A].v[0]);
    scene_t *s = scenefile_scene(c);
    bool fresh;
    irr_settings_t *p = scene_part_data_new(s, "irradiance", sizeof *p, free, &fresh);
    if (!p)
        return scenefile_fail(c, scenefile_stmt_col(c), SVET_ERR_NOMEM,
                              "out of memory");
    if (fresh)
        irr_settings_default(p);
    /* the line updates the settings: `--set irradiance.a=0.1` reruns it;
     * the gather's size and the range of R are checked against what the
     * line leaves */
    long m = v[I_M].set ? v[I_M].i : p->m, n = v[I_N].set ? v[I_N].i : p->n;
    if (m * n > 65536) {
        int col = v[I_N].set ? v[I_N].col : v[I_M].col;
        return scenefile_fail(c, col, SVET_ERR_RANGE,
                              "'m' x 'n' = %ld: at most 65536 gather rays",
                              m * n);
    }
    real min_r = v[I_MINR].set ? v[I_MINR].v[0] : p->min_r;
    real max_r = v[I_MAXR].set ? v[I_MAXR].v[0] : p->max_r;
    if (!(min_r <= max_r)) {
        int col = v[I_MAXR].set ? v[I_MAXR].col : v[I_MINR].col;
        return scenefile_fail(c, col, SVET_ERR_RANGE,
                              "'min_r' = %g exceeds 'max_r' = %g",
                              (double)min_r, (double)max_r);
    }
    if (v[I_A].set)
        p->a = v[I_A].v[0];
    if (v[I_M].set)
        p->m = (int)v[I_M].i;
    if (v[I_N].set)
        p->n = (int)v[I_N].i;
    p->min_r = min_r;
    p->max_r = max_r;
    if (v[I_BOUNCES].set)
        p->bounces = (int)v[I_BOUNCES].i;
    if (v[I_GRAD].set)
        p->gradients = v[I_GRAD].on;
    if (v[I_CLAMP].set)
        p->clamp = v[I_CLAMP].on;
    return SVET_OK;
}

/* --- what goes through the cache ---------------------------------------- */

/* A material whose non-delta part is Lambert alone (a wall, a varnished
 * wall): its indirect light is rho_d / pi E, E from the cache. Any other
 * non-delta part (glossy, diffuse transmission) is path traced. */
static bool cacheable(const material_t *m)
{
    bool lambert = false;
    for (int i = 0; i < m->ncomp; i++) {
        brdf_kind k = m->comp[i].kind;
        if (k == BRDF_LAMBERT)
            lambert = true;
        else if (k != BRDF_MIRROR && k != BRDF_SPECULAR_TRANSMISSION)
            return false;
    }
    return lambert;
}

/* The shading normal on the side pp is seen from: the hemisphere the
 * cache integrates over. */
static void facing_normal(const PATHPOINT *pp, VECTOR3 n)
{
    vec_copy(n, pp->n);
    if (SVECTOR3(pp->out, pp->n) < 0)
        vec_scale(n, n, -1);
}

/* The radiance arriving along a gather ray: what it hits reflects the
 * direct light found by light sampling there (ch. 5's integrator_direct),
 * and, while `bounces` diffuse vertices are not used up, what its BSDF
 * sample brings (path tracing). Emitters are counted only after delta
 * bounces: seen straight from the record they are the record's direct
 * light, which light sampling computes. *dist is the distance to the
 * first hit (INFINITY: none), for R. */
static RADIANCE gather_ray(const render_t *r, ray_t ray, const COBJECT *from,
                           int bounces, pcg32_t *g, integrator_stats_t *st,
                           real *dist)
{
    const scene_t *sc = r->scene;
    RADIANCE L = rad_grey(0), beta = rad_grey(1);
    const COBJECT *skip[2] = { from, NULL };
    bool after_delta = false;
    *dist = (real)INFINITY;
    for (int depth = 0; depth <= sc->render.max_depth; depth++) {
        hit_t h;
        const COBJECT *obj = NULL;
        st->rays++;
        if (!r->tracer.intersect(r->tracer.ctx, &ray, 0, (real)INFINITY, skip,
                                 &h, &obj)) {
            if (after_delta && sc->has_environment)
                L = rad_add(L, rad_mul(beta, sc->environment));
            break;
        }
        PATHPOINT pp;
        cobject_fill(obj, &ray, &h, &pp);
        if (depth == 0)
            *dist = pp.r_dist;
        if (obj->light && after_delta)
            L = rad_add(L, rad_mul(beta, light_emitted(obj->light, &pp)));
        const material_t *m = obj->material;
        VECTOR3 wo, wi;
        frame_to_local(wo, pp.out, pp.u, pp.v, pp.n);
        if (!material_is_specular(m) && m->ncomp > 0) {
            L = rad_add(L, rad_mul(beta, integrator_direct(&r->integrator,
                                                           &pp, m, wo, false,
                                                           g, st)));
            if (--bounces == 0)
                break;
        }
        real u[3] = { pcg32_real(g), pcg32_real(g), pcg32_real(g) };
        brdf_sample_t bs;
        if (!material_sample(m, wo, u, &bs))
            break;
        beta = rad_mul(beta, bs.weight);
        if (rad_is_black(beta))
            break;
        after_delta = bs.delta;
        frame_to_world(wi, bs.wi, pp.u, pp.v, pp.n);
        ray_spawn(&ray, pp.cross_point, pp.p_error, pp.ng, wi);
        skip[0] = obj;
    }
    return L;
}

/* A record at pp (normal n facing the viewer): the stratified M x N
 * gather of app. E, its irradiance, gradients (turned from the local frame
 * to the world's) and R. Returns false when out of memory. */
static bool gather(const render_t *r, const irr_settings_t *set,
                   const PATHPOINT *pp, const VECTOR3 n, pcg32_t *g,
                   integrator_stats_t *st, irr_record_t *rec)
{
    int cells = set->m * set->n;
    RADIANCE *l = malloc((size_t)cells * sizeof *l);
    real *dist = malloc((size_t)cells * sizeof *dist);
    if (!l || !dist) {
        free(l);
        free(dist);
        return false;
    }
    VECTOR3 t1, t2;
    frame_from_normal(t1, t2, n);
    for (int j = 0; j < set->m; j++)
        for (int k = 0; k < set->n; k++) {
            real u[2] = { pcg32_real(g), pcg32_real(g) };
            VECTOR3 wl, w;
            gradients_direction(set->m, set->n, j, k, u, wl);
            frame_to_world(w, wl, t1, t2, n);
            ray_t ray;
            ray_spawn(&ray, pp->cross_point, pp->p_error, pp->ng, w);
            l[j * set->n + k] = gather_ray(r, ray, pp->IntersectObj,
                                           set->bounces, g, st,
                                           &dist[j * set->n + k]);
        }
    gradients_samples_t s = { set->m, set->n, l, dist };
    VECTOR3 gr[3], gt[3];
    memset(rec, 0, sizeof *rec);
    gradients_compute(&s, &rec->e, gr, gt, &rec->r);
    for (int c = 0; c < 3; c++) {
        frame_to_world(rec->grad_r[c], gr[c], t1, t2, n);
        frame_to_world(rec->grad_t[c], gt[c], t1, t2, n);
    }
    vec_copy(rec->p, pp->cross_point);
    vec_copy(rec->n, n);
    free(l);
    free(dist);
    return true;
}

/* The first hit of the camera ray through film position (fx, fy) with a
 * non-delta part, through delta bounces chosen with g; false when the ray
 * leaves, or dies at a delta surface. *foot is the width of a pixel at
 * the hit, measured along the path: the unit of the clamp of R. */
static bool first_hit(const render_t *r, real fx, real fy, pcg32_t *g,
                      integrator_stats_t *st, PATHPOINT *pp,
                      const material_t **mat, real *foot)
{
    ray_t ray, side;
    camera_ray(&r->camera, fx, fy, &ray);
    camera_ray(&r->camera, fx + 1, fy, &side);
    VECTOR3 dd;
    vec_sub(dd, side.d, ray.d);
    real spread = vec_length(dd), travelled = 0;
    const COBJECT *skip[2] = { NULL, NULL };
    for (int depth = 0; depth <= r->scene->render.max_depth; depth++) {
        hit_t h;
        const COBJECT *obj = NULL;
        st->rays++;
        if (!r->tracer.intersect(r->tracer.ctx, &ray, 0, (real)INFINITY, skip,
                                 &h, &obj))
            return false;
        cobject_fill(obj, &ray, &h, pp);
        travelled += pp->r_dist;
        const material_t *m = obj->material;
        if (!material_is_specular(m) && m->ncomp > 0) {
            *mat = m;
            *foot = travelled * spread;
            return true;
        }
        VECTOR3 wo, wi;
        frame_to_local(wo, pp->out, pp->u, pp->v, pp->n);
        real u[3] = { pcg32_real(g), pcg32_real(g), pcg32_real(g) };
        brdf_sample_t bs;
        if (!material_sample(m, wo, u, &bs))
            return false;
        frame_to_world(wi, bs.wi, pp->u, pp->v, pp->n);
        ray_spawn(&ray, pp->cross_point, pp->p_error, pp->ng, wi);
        skip[0] = obj;
    }
    return false;
}

/* --- the pre-pass --------------------------------------------------------- */

typedef struct {
    bool valid, failed;
    irr_record_t rec;
} candidate_t;

/* The pixel steps of the pre-pass, coarse to fine. */
static const int levels[] = { 16, 8, 4, 2, 1 };

/* irr_fill(), the records each level added in added[] (may be NULL) */
static svet_status fill(irrcache_t *c, const render_t *r, int threads,
                        long *added, svet_error *err)
{
    irr_settings_t set;
    irr_settings_of(r->scene, &set);
    const int w = r->camera.width, h = r->camera.height;
    /* R is clamped per record, in pixels of its own footprint; the cache's
     * clamp, the bound of its octree's search, is the widest and narrowest
     * footprint over every 4th pixel of every 4th row (a record beyond
     * them is clamped to them), and its box the hits' bounds */
    VECTOR3 lo, hi;
    vec_copy(lo, r->camera.eye);
    vec_copy(hi, r->camera.eye);
    real fmin = (real)INFINITY, fmax = 0;
    for (int y = 0; y < h; y += 4)
        for (int x = 0; x < w; x += 4) {
            pcg32_t g;
            rng_for_sample(&g, r->scene->render.seed ^ IRR_SEED_SALT,
                           (uint64_t)y * (uint64_t)w + (uint64_t)x, 98);
            integrator_stats_t ist = { 0, 0 };
            PATHPOINT pp;
            const material_t *m;
            real foot;
            if (!first_hit(r, (real)x + REAL_C(0.5), (real)y + REAL_C(0.5),
                           &g, &ist, &pp, &m, &foot) || !(foot > 0) ||
                !isfinite(foot))
                continue;
            fmin = real_min(fmin, foot);
            fmax = real_max(fmax, foot);
            for (int k = 0; k < 3; k++) {
                lo[k] = real_min(lo[k], pp.cross_point[k]);
                hi[k] = real_max(hi[k], pp.cross_point[k]);
            }
        }
    if (!(fmax > 0)) /* nothing diffuse in sight: an empty cache */
        fmin = fmax = 1;
    svet_status st = irrcache_init(c, set.a, set.min_r * fmin,
                                   set.max_r * fmax, lo, hi, err);
    if (st)
        return st;
    c->gradients = set.gradients;
    c->clamp_neighbours = set.clamp;
    int nt = threads > 0 ? threads : omp_get_max_threads();
    for (int lv = 0; lv < (int)(sizeof levels / sizeof *levels); lv++) {
        int step = levels[lv];
        int cw = (w + step - 1) / step, ch = (h + step - 1) / step;
        long count = (long)cw * ch;
        candidate_t *cand = calloc((size_t)count, sizeof *cand);
        if (!cand) {
            irrcache_free(c);
            return svet_error_set(err, SVET_ERR_NOMEM,
                                  "irradiance: out of memory");
        }
        /* the pixels of this level not on the coarser one's grid, each
         * with random numbers of its own: the candidates do not depend on
         * which thread computed them, nor when (the cache is only read) */
#pragma omp parallel for schedule(dynamic, 4) num_threads(nt)
        for (long i = 0; i < count; i++) {
            int x = (int)(i % cw) * step, y = (int)(i / cw) * step;
            if (lv > 0 && x % (2 * step) == 0 && y % (2 * step) == 0)
                continue;
            pcg32_t g;
            rng_for_sample(&g, r->scene->render.seed ^ IRR_SEED_SALT,
                           (uint64_t)y * (uint64_t)w + (uint64_t)x,
                           (uint64_t)lv);
            integrator_stats_t ist = { 0, 0 };
            PATHPOINT pp;
            const material_t *m;
            real foot;
            if (!first_hit(r, (real)x + REAL_C(0.5), (real)y + REAL_C(0.5),
                           &g, &ist, &pp, &m, &foot) || !cacheable(m))
                continue;
            VECTOR3 n;
            facing_normal(&pp, n);
            RADIANCE e;
            if (irrcache_lookup(c, pp.cross_point, n, &e) > 0)
                continue;
            if (!gather(r, &set, &pp, n, &g, &ist, &cand[i].rec)) {
                cand[i].failed = true;
                continue;
            }
            real rr = cand[i].rec.r;
            rr = real_max(rr, set.min_r * foot);
            cand[i].rec.r = real_min(rr, set.max_r * foot);
            cand[i].valid = true;
        }
        /* joined in pixel order, each skipped where a record added before
         * it in this order now covers it */
        for (long i = 0; i < count && st == SVET_OK; i++) {
            if (cand[i].failed)
                st = svet_error_set(err, SVET_ERR_NOMEM,
                                    "irradiance: out of memory");
            if (!cand[i].valid)
                continue;
            RADIANCE e;
            if (irrcache_lookup(c, cand[i].rec.p, cand[i].rec.n, &e) > 0)
                continue;
            st = irrcache_add(c, &cand[i].rec, err);
            if (st == SVET_OK && added)
                added[lv]++;
        }
        free(cand);
        if (st) {
            irrcache_free(c);
            return st;
        }
    }
    return SVET_OK;
}

svet_status irr_fill(irrcache_t *c, const render_t *r, int threads,
                     svet_error *err)
{
    return fill(c, r, threads, NULL, err);
}

/* --- the method ----------------------------------------------------------- */

enum { NLEVELS = sizeof levels / sizeof *levels };

/* What the final pass counts, from every thread (atomically): the same
 * totals for any thread count, as every camera path is. */
typedef struct {
    uint64_t lookups, gathers;
} counts_t;

typedef struct {
    irr_settings_t set;
    irrcache_t cache;
    long added[NLEVELS]; /* records each level of the pre-pass added */
    counts_t *counts;    /* written while li reads the rest */
} state_t;

static void state_free(void *p)
{
    state_t *s = p;
    if (!s)
        return;
    irrcache_free(&s->cache);
    free(s->counts);
    free(s);
}

/* The log's line: records per level, lookups and the gathers where no
 * record covered the point */
static void report(const void *state, char *buf, size_t size)
{
    const state_t *s = state;
    int k = snprintf(buf, size, "irradiance cache: %zu records (",
                     s->cache.n);
    for (int lv = 0; lv < NLEVELS && k >= 0 && (size_t)k < size; lv++)
        k += snprintf(buf + k, size - (size_t)k, "%s%ld at step %d",
                      lv ? ", " : "", s->added[lv], levels[lv]);
    if (k >= 0 && (size_t)k < size)
        snprintf(buf + k, size - (size_t)k,
                 "); %llu lookups, %llu of them fell back to a gather of "
                 "their own (%.3g %%); records per lookup %.3g %%",
                 (unsigned long long)s->counts->lookups,
                 (unsigned long long)s->counts->gathers,
                 s->counts->lookups ? 100.0 * (double)s->counts->gathers /
                                          (double)s->counts->lookups
                                    : 0.0,
                 s->counts->lookups ? 100.0 * (double)s->cache.n /
                                          (double)s->counts->lookups
                                    : 0.0);
}

static svet_status prepare(void **out, const render_t *r, int threads,
                           svet_error *err)
{
    state_t *s = calloc(1, sizeof *s);
    if (!s)
        return svet_error_set(err, SVET_ERR_NOMEM,
                              "irradiance: out of memory");
    irr_settings_of(r->scene, &s->set);
    s->counts = calloc(1, sizeof *s->counts);
    if (!s->counts) {
        free(s);
        return svet_error_set(err, SVET_ERR_NOMEM,
                              "irradiance: out of memory");
    }
    svet_status st = fill(&s->cache, r, threads, s->added, err);
    if (st) {
        free(s->counts);
        free(s);
        return st;
    }
    *out = s;
    return SVET_OK;
}

const irrcache_t *irr_state_cache(const void *state)
{
    return &((const state_t *)state)->cache;
}

/* The indirect irradiance at pp from the cache; where no record covers
 * the point, a gather of its own, with the camera sample's numbers, that
 * is not stored (the final pass only reads the cache). */
static RADIANCE indirect(const state_t *s, const render_t *r,
                         const PATHPOINT *pp, pcg32_t *g,
                         integrator_stats_t *st)
{
    VECTOR3 n;
    facing_normal(pp, n);
    RADIANCE e;
#pragma omp atomic
    s->counts->lookups++;
    if (irrcache_lookup(&s->cache, pp->cross_point, n, &e) > 0)
        return e;
#pragma omp atomic
    s->counts->gathers++;
    irr_record_t rec;
    if (!gather(r, &s->set, pp, n, g, st, &rec))
        return rad_grey(0);
    return rec.e;
}

bool irr_pixel_irradiance(const void *state, const render_t *r, int x,
                          int y, uint64_t stream, RADIANCE *cached,
                          bool *found, RADIANCE *gathered)
{
    const state_t *s = state;
    pcg32_t g;
    rng_for_sample(&g, r->scene->render.seed ^ IRR_SEED_SALT ^ stream,
                   (uint64_t)y * (uint64_t)r->camera.width + (uint64_t)x, 99);
    integrator_stats_t ist = { 0, 0 };
    PATHPOINT pp;
    const material_t *m;
    real foot;
    if (!first_hit(r, (real)x + REAL_C(0.5), (real)y + REAL_C(0.5), &g, &ist,
                   &pp, &m, &foot) || !cacheable(m))
        return false;
    VECTOR3 n;
    facing_normal(&pp, n);
    if (cached) {
        int k = irrcache_lookup(&s->cache, pp.cross_point, n, cached);
        if (found)
            *found = k > 0;
    }
    if (gathered) {
        irr_record_t rec;
        *gathered = gather(r, &s->set, &pp, n, &g, &ist, &rec) ? rec.e
                                                             : rad_grey(0);
    }
    return true;
}

/* The camera path: emitters seen directly or through delta bounces; at a
 * surface with a non-delta part, direct light by light sampling; on a
 * cacheable one (Lambert and delta parts) the cache's E rho_d / pi, its
 * delta parts followed; on any other the path continues by BSDF sampling,
 * its emitters then not counted (light sampling has them).
 * With `render light indirect` (scene.h) only the indirect diffuse light
 * stays: nothing before the first surface with a non-delta part, and
 * there no direct light; on a cacheable one the cache's E rho_d / pi and
 * nothing else, on any other what its non-delta BSDF sample brings back
 * but the emitter that sample hits (as the path tracer's
 * integrator.c does). */
static RADIANCE li(const void *state, const render_t *r, const ray_t *camera,
                   long sample, pcg32_t *g, integrator_stats_t *st)
{
    (void)sample;
    const state_t *s = state;
    const scene_t *sc = r->scene;
    st->paths++;
    RADIANCE L = rad_grey(0), beta = rad_grey(1);
    ray_t ray = *camera;
    const COBJECT *skip[2] = { NULL, NULL };
    const bool indirect_only = sc->render.light == SCENE_LIGHT_INDIRECT;
    bool count_emitted = !indirect_only;
    bool first = indirect_only; /* the first non-delta surface is ahead */
    for (int depth = 0;; depth++) {
        hit_t h;
        const COBJECT *obj = NULL;
        st->rays++;
        if (!r->tracer.intersect(r->tracer.ctx, &ray, 0, (real)INFINITY, skip,
                                 &h, &obj)) {
            if (count_emitted && sc->has_environment)
                L = rad_add(L, rad_mul(beta, sc->environment));
            break;
        }
        PATHPOINT pp;
        cobject_fill(obj, &ray, &h, &pp);
        if (obj->light && count_emitted)
            L = rad_add(L, rad_mul(beta, light_emitted(obj->light, &pp)));
        if (depth >= sc->render.max_depth)
            break;
        const material_t *m = obj->material;
        VECTOR3 wo, wi;
        frame_to_local(wo, pp.out, pp.u, pp.v, pp.n);
        bool surface = !material_is_specular(m) && m->ncomp > 0;
        bool cached = surface && cacheable(m);
        const bool first_surface = first && surface;
        if (surface && !first_surface)
            L = rad_add(L, rad_mul(beta, integrator_direct(&r->integrator,
                                                           &pp, m, wo, false,
                                                           g, st)));
        if (cached) {
            RADIANCE e = indirect(s, r, &pp, g, st);
            L = rad_add(L, rad_mul(beta, rad_scale(rad_mul(m->params.rho_d, e),
                                                   1 / REAL_PI)));
            if (first_surface)
                break;
        }
        real u[3] = { pcg32_real(g), pcg32_real(g), pcg32_real(g) };
        brdf_sample_t bs;
        if (!material_sample(m, wo, u, &bs) || (cached && !bs.delta) ||
            (first_surface && bs.delta))
            break;
        beta = rad_mul(beta, bs.weight);
        if (rad_is_black(beta))
            break;
        count_emitted = bs.delta && !first;
        if (first_surface)
            first = false;
        frame_to_world(wi, bs.wi, pp.u, pp.v, pp.n);
        ray_spawn(&ray, pp.cross_point, pp.p_error, pp.ng, wi);
        skip[0] = obj;
    }
    return L;
}

const render_method_t irr_method = {
    "irradiance", "irradiance cache (ch. 9): Ward's records with gradients",
    prepare, NULL, li, state_free, report, NULL, NULL, true
};

static const render_method_t *const methods[] = { &irr_method, NULL };
static const scene_statement_t statements[] = {
    { "irradiance", irr_statement }, { NULL, NULL }
};
const scene_part_t irr_part = { .name = "irradiance",
                                .statements = statements,
                                .methods = methods };
