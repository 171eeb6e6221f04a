/*
 * accel.c - the acceleration interface of ch. 7: brute force through
 * primset.h, the structures a program offers through accel_params_t (the
 * grids of grid.c and the batched brute force of batch.c in the svet
 * command; the grids alone in ch. 7), and the automatic choice between
 * them (the rule in accel.h). It names no structure's functions: only
 * their tables (accel_ops_t).
 * Tests: tests/accel/test_accel.c
 */
#define _POSIX_C_SOURCE 200809L
#include "accel/accel.h"
#include "accel/primset.h"
#include "core/simd.h"

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>


struct accel {
    accel_kind kind;
    primset_t ps;
    const accel_ops_t *ops; /* the structure built; NULL for brute force
                               through primset_test() */
    void *s;                /* and its data */
    double build_seconds;
    char describe[256];
};

void accel_params_default(accel_params_t *p)
{
    memset(p, 0, sizeof *p);
    p->kind = ACCEL_AUTO;
}

svet_status accel_kind_parse(const char *s, accel_kind *k, svet_error *err)
{
    for (int i = ACCEL_AUTO; i <= ACCEL_HGRID; i++)
        if (s && strcmp(s, accel_kind_name((accel_kind)i)) == 0) {
            *k = (accel_kind)i;
            return SVET_OK;
        }
    return svet_error_set(err, SVET_ERR_PARSE,
                          "unknown acceleration structure '%s' (expected "
                          "auto, brute, grid or hgrid)", s ? s : "");
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Build the structure ops over a->ps: a->ops, a->s on success. */
static svet_status build_with(accel_t *a, const accel_ops_t *ops,
                              const accel_params_t *p, svet_error *err)
{
    svet_status st = ops->build(&a->s, &a->ps, p, err);
    if (st == SVET_OK)
        a->ops = ops;
    return st;
}

/* Free what build_with() built. */
static void drop_structure(accel_t *a)
{
    if (a->ops && a->ops->free)
        a->ops->free(a->s);
    a->ops = NULL;
    a->s = NULL;
}

/* Does a's structure answer whole queries (the batched brute force)? */
static inline bool whole(const accel_t *a)
{
    return a->ops && a->ops->tracer_intersect;
}

/* Brute force by the structure of kind ACCEL_BRUTE where p offers one
 * and it takes the scene (the batched brute force takes no mesh
 * triangles); else, or when its memory runs out, by primset_test(),
 * which answers the same. */
static void build_brute(accel_t *a, const accel_params_t *p)
{
    const accel_ops_t *b = accel_offered(p->structures, ACCEL_BRUTE);
    if (b)
        (void)build_with(a, b, p, NULL);
}

/* AUTO's choice (accel.h) over a->ps's n bounded primitives: brute force,
 * or a structure of p->structures, built; why says why. */
static svet_status choose(accel_t *a, const accel_params_t *p, long n,
                          accel_kind *kind, char *why, size_t nwhy,
                          svet_error *err)
{
    long brute_max = p->brute_max > 0 ? p->brute_max : ACCEL_BRUTE_MAX;
    const accel_ops_t *grid = accel_offered(p->structures, ACCEL_GRID);
    const accel_ops_t *hgrid = accel_offered(p->structures, ACCEL_HGRID);
    if (n <= brute_max || (!grid && !hgrid)) {
        *kind = ACCEL_BRUTE;
        if (n <= brute_max)
            snprintf(why, nwhy, " (auto: %ld primitives, at most %ld)", n,
                     brute_max);
        else
            snprintf(why, nwhy, " (auto: %ld primitives; this program "
                     "offers no grid)", n);
        return SVET_OK;
    }
    if (!grid) {
        *kind = ACCEL_HGRID; /* built by the caller */
        snprintf(why, nwhy, " (auto: %ld primitives; no uniform grid "
                 "offered)", n);
        return SVET_OK;
    }
    /* On failure *kind stays AUTO: "fell back from auto". */
    svet_status st = build_with(a, grid, p, err);
    if (st != SVET_OK)
        return st;
    double f = grid->crowded ? grid->crowded(a->s, ACCEL_AUTO_CELL) : 0;
    *kind = f > ACCEL_AUTO_CROWDED && hgrid ? ACCEL_HGRID : ACCEL_GRID;
    snprintf(why, nwhy, " (auto: %.3g%% of the references in cells of "
             "more than %d; %ld primitives)", 100 * f, ACCEL_AUTO_CELL, n);
    if (*kind == ACCEL_HGRID)
        drop_structure(a);
    return SVET_OK;
}

svet_status accel_build(accel_t **out, COBJECT *const *objs, int nobjs,
                        const accel_params_t *p, svet_error *err)
{
    *out = NULL;
    accel_params_t def;
    if (!p) {
        accel_params_default(&def);
        p = &def;
    }
    if (p->kind < ACCEL_AUTO || p->kind > ACCEL_HGRID || p->grid_k < 0 ||
        p->hgrid_k < 0 || p->hgrid_leaf < 0 || p->hgrid_depth < 0 ||
        p->brute_max < 0 || p->hgrid_child_k < 0 || !isfinite(p->grid_k) ||
        !isfinite(p->hgrid_k) || !isfinite(p->hgrid_child_k))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "accel: invalid parameters");
    if (p->kind > ACCEL_BRUTE && !accel_offered(p->structures, p->kind))
        return svet_error_set(err, SVET_ERR_UNSUPPORTED,
                              "accel %s: this program was built without %s",
                              accel_kind_name(p->kind),
                              accel_kind_needs(p->kind));
    double t0 = now();
    accel_t *a = calloc(1, sizeof *a);
    if (!a)
        return svet_error_set(err, SVET_ERR_NOMEM, "accel: out of memory");
    svet_status st = primset_build(&a->ps, objs, nobjs, err);
    if (st != SVET_OK) {
        free(a);
        return st;
    }
    char why[160] = "";
    accel_kind kind = p->kind;
    if (kind == ACCEL_AUTO)
        st = choose(a, p, (long)a->ps.nbounded, &kind, why, sizeof why, err);
    if (st == SVET_OK && kind != ACCEL_BRUTE && kind != ACCEL_AUTO &&
        !a->ops)
        st = build_with(a, accel_offered(p->structures, kind), p, err);
    if (st == SVET_ERR_UNSUPPORTED) {
        snprintf(why, sizeof why, " (fell back from %s: %.96s)",
                 accel_kind_name(kind), err ? err->msg : "unsupported");
        kind = ACCEL_BRUTE;
        st = SVET_OK;
        if (err)
            svet_error_clear(err);
    }
    if (st != SVET_OK) {
        accel_free(a);
        return st;
    }
    primset_drop_bounds(&a->ps);
    if (kind == ACCEL_BRUTE && !p->brute_generic)
        build_brute(a, p);
    a->kind = kind;
    a->build_seconds = now() - t0;
    snprintf(a->describe, sizeof a->describe, "%s%s", accel_kind_name(kind),
             why);
    *out = a;
    return SVET_OK;
}

void accel_free(accel_t *a)
{
    if (!a)
        return;
    drop_structure(a);
    primset_free(&a->ps);
    free(a);
}

#ifdef SIMD_REAL
/* tracer_ray_ok()'s answer with SSE2 (every query makes this test), on the six coordinates read as vectors
 * (o and d are adjacent in ray_t): the lanes of x - x are 0 where x is
 * finite and NaN elsewhere, and 0 <= lane fails only for NaN; a finite d
 * is nonzero exactly when some |d_i| > 0. */
_Static_assert(offsetof(ray_t, d) == 3 * sizeof(real) &&
               sizeof(ray_t) == 6 * sizeof(real),
               "ray_t: d follows o without padding");
static inline bool ray_ok(const ray_t *r, real tmin, real tmax)
{
    /* o[0..2], then d[0..2], copied as six reals (reading d through o's
     * pointer would index past o's array); gcc makes it plain loads */
    real c[6];
    memcpy(c, r, sizeof c);
    const vreal zero = V_SET1(0), sign = V_SET1(-REAL_C(0.0));
#ifdef SVET_DOUBLE
    vreal a = V_LOAD(c), b = V_LOAD(c + 2), e = V_LOAD(c + 4); /* o0 o1, o2 d0, d1 d2 */
    vreal f = V_ADD(V_ADD(V_SUB(a, a), V_SUB(b, b)), V_SUB(e, e));
    bool finite = V_MASK(V_LE(f, zero)) == 3;
    bool nonzero = ((V_MASK(V_GT(V_ANDNOT(sign, b), zero)) & 2) |
                    V_MASK(V_GT(V_ANDNOT(sign, e), zero))) != 0;
#else
    vreal a = V_LOAD(c), b = V_LOAD(c + 2); /* o0 o1 o2 d0, o2 d0 d1 d2 */
    vreal f = V_ADD(V_SUB(a, a), V_SUB(b, b));
    bool finite = V_MASK(V_LE(f, zero)) == 15;
    bool nonzero = (V_MASK(V_GT(V_ANDNOT(sign, b), zero)) & 14) != 0;
#endif
    return finite && nonzero && tmin < tmax;
}
#else
static inline bool ray_ok(const ray_t *r, real tmin, real tmax)
{
    return tracer_ray_ok(r, tmin, tmax);
}
#endif

bool accel_ray_ok(const ray_t *r, real tmin, real tmax)
{
    return ray_ok(r, tmin, tmax);
}

bool accel_ray_ok_plain(const ray_t *r, real tmin, real tmax)
{
    return tracer_ray_ok(r, tmin, tmax);
}

/* Brute force, and the unbounded primitives of a structure: refs
 * [from, to). */
static bool test_range(const primset_t *ps, primset_query_t *q, uint32_t from,
                       uint32_t to, bool shadow)
{
    for (uint32_t i = from; i < to; i++)
        if (primset_test(ps, q, i) && shadow)
            return true;
    return q->found;
}

static bool run(const accel_t *a, primset_query_t *q, bool shadow)
{
    if (!a->ops || whole(a))
        return test_range(&a->ps, q, 0, a->ps.nrefs, shadow);
    if (test_range(&a->ps, q, a->ps.nbounded, a->ps.nrefs, shadow) && shadow)
        return true;
    return shadow ? a->ops->occluded(a->s, q) : a->ops->intersect(a->s, q);
}

/* The nearest hit, written into *hit and *obj (untouched on a miss):
 * the one query behind accel_intersect*() and accel_tracer_intersect(). */
static bool nearest(const accel_t *a, const ray_t *r, real tmin, real tmax,
                    const COBJECT *const skip[2], hit_t *hit,
                    const COBJECT **obj, accel_counters_t *c)
{
    if (!a || !ray_ok(r, tmin, tmax))
        return false;
    if (whole(a) && !c)
        return a->ops->tracer_intersect(a->s, r, tmin, tmax, skip, hit, obj);
    primset_query_t q;
    primset_query_init(&q, r, tmin, tmax);
    run(a, &q, false);
    if (c) {
        c->cells += q.cells;
        c->tests += q.tests;
    }
    if (!q.found)
        return false;
    *obj = primset_query_finish(&a->ps, &q);
    *hit = q.hit;
    return true;
}

bool accel_intersect(const accel_t *a, const ray_t *r, real tmin, real tmax,
                     accel_hit_t *h)
{
    return nearest(a, r, tmin, tmax, NULL, &h->hit, &h->obj, NULL);
}

bool accel_intersect_skip(const accel_t *a, const ray_t *r, real tmin,
                          real tmax, const COBJECT *const skip[2],
                          accel_hit_t *h)
{
    return nearest(a, r, tmin, tmax, skip, &h->hit, &h->obj, NULL);
}

bool accel_tracer_intersect(const void *a, const ray_t *r, real tmin,
                            real tmax, const COBJECT *const skip[2],
                            hit_t *hit, const COBJECT **obj)
{
    return nearest(a, r, tmin, tmax, skip, hit, obj, NULL);
}

bool accel_intersect_counted(const accel_t *a, const ray_t *r, real tmin,
                             real tmax, accel_hit_t *h, accel_counters_t *c)
{
    return nearest(a, r, tmin, tmax, NULL, &h->hit, &h->obj, c);
}

bool accel_has_packets(const accel_t *a)
{
    return a && a->ops && a->ops->intersect_packet;
}

void accel_tracer_intersect_packet(const void *ctx, const ray_t *r, int n,
                                   real tmin, real tmax, hit_t *hit,
                                   const COBJECT **obj, bool *found)
{
    const accel_t *a = ctx;
    if (!accel_has_packets(a)) {
        for (int i = 0; i < n; i++)
            found[i] = accel_tracer_intersect(a, &r[i], tmin, tmax, NULL,
                                              &hit[i], &obj[i]);
        return;
    }
    for (int i0 = 0; i0 < n; i0 += ACCEL_PACKET_MAX) {
        const int i1 = n - i0 > ACCEL_PACKET_MAX ? i0 + ACCEL_PACKET_MAX : n;
        primset_query_t q[ACCEL_PACKET_MAX];
        int ray_of[ACCEL_PACKET_MAX];
        int m = 0;
        /* nearest()'s steps for each ray, the structure's part for all
         * of them at once: the check, then the unbounded primitives
         * (run()), so that each query reaches the structure as it would
         * alone */
        for (int i = i0; i < i1; i++) {
            found[i] = false;
            if (!ray_ok(&r[i], tmin, tmax))
                continue;
            primset_query_init(&q[m], &r[i], tmin, tmax);
            test_range(&a->ps, &q[m], a->ps.nbounded, a->ps.nrefs, false);
            ray_of[m++] = i;
        }
        a->ops->intersect_packet(a->s, q, m);
        for (int j = 0; j < m; j++) {
            if (!q[j].found)
                continue;
            const int i = ray_of[j];
            obj[i] = primset_query_finish(&a->ps, &q[j]);
            hit[i] = q[j].hit;
            found[i] = true;
        }
    }
}

/* accel_occluded_skip() and accel_tracer_occluded(): the one shadow
 * query (inline in both). */
static inline bool occluded(const accel_t *a, const ray_t *r, real tmin,
                            real tmax, const COBJECT *const skip[2])
{
    if (!a || !ray_ok(r, tmin, tmax))
        return false;
    if (whole(a))
        return a->ops->tracer_occluded(a->s, r, tmin, tmax, skip);
    primset_query_t q;
    primset_query_init(&q, r, tmin, tmax);
    return run(a, &q, true);
}

bool accel_occluded(const accel_t *a, const ray_t *r, real tmin, real tmax)
{
    return occluded(a, r, tmin, tmax, NULL);
}

bool accel_occluded_skip(const accel_t *a, const ray_t *r, real tmin,
                         real tmax, const COBJECT *const skip[2])
{
    return occluded(a, r, tmin, tmax, skip);
}

bool accel_tracer_occluded(const void *a, const ray_t *r, real tmin,
                           real tmax, const COBJECT *const skip[2])
{
    return occluded(a, r, tmin, tmax, skip);
}

void accel_get_stats(const accel_t *a, accel_stats_t *s)
{
    memset(s, 0, sizeof *s);
    if (!a)
        return;
    if (a->ops)
        a->ops->stats(a->s, s);
    s->kind = a->kind;
    s->build_seconds = a->build_seconds;
    s->bytes += sizeof *a + primset_bytes(&a->ps);
    s->prims = (long)a->ps.nrefs;
    s->unbounded = (long)(a->ps.nrefs - a->ps.nbounded);
}

const char *accel_describe(const accel_t *a)
{
    return a ? a->describe : "none";
}

tracer_t accel_tracer(const accel_t *a)
{
    tracer_t t = { accel_tracer_intersect, accel_tracer_occluded, a };
    if (a && whole(a)) {
        t.intersect = a->ops->tracer_intersect;
        t.occluded = a->ops->tracer_occluded;
        t.ctx = a->s;
    }
    return t;
}

const accel_layer_t accel_layer = {
    .build = accel_build,
    .free = accel_free,
    .tracer = accel_tracer,
    .has_packets = accel_has_packets,
    .intersect_packet = accel_tracer_intersect_packet,
    .describe = accel_describe,
};
