/*
 * batch.c - the batched brute force (batch.h): what primset_test() over
 * every primitive answers, with each primitive's culling test made here,
 * on vectors where SSE2 is there, instead of behind a call per primitive.
 * Tests: tests/accel/test_batch.c (and tests/accel/test_accel.c)
 */
#include "accel/batch.h"
#include "core/bits.h"
#include "geometry/parallelogram.h"
#include "accel/primset.h"
#include "core/simd.h"
#include "geometry/xform.h"

#include <stddef.h>
#include <stdlib.h>

/* Every reference of the primset, each taken the fastest way to the
 * answer its intersect() gives (brute_run): a parallelogram by its early
 * rejections from the batch, then its watertight test on a ray prepared
 * once; a transformed box by its culling sphere here; any other through
 * intersect(). */
typedef struct {
    const COBJECT *obj;
    int prim;
} brute_item_t;

typedef struct {
    const primset_t *ps; /* what it was built over (it outlives this) */
    brute_item_t *items; /* refs[0 .. nrefs) of the primset */
    uint32_t n;
    parallelogram_batch_t *batch;
    uint32_t para[PARALLELOGRAM_BATCH_MAX]; /* the item of each bit */
    /* The batch's bits of each object, found by its index in the scene
     * (COBJECT.id) when objs_by_id[id] is that object: 0 for an object
     * that is no parallelogram of the batch. An object without such an
     * index (one made outside a scene, as tests make them) is looked for
     * among the batch's items instead. */
    const COBJECT **objs_by_id;
    uint64_t *bits_by_id;
    int nid;
    int npara;
    uint32_t *others;    /* the items neither in the batch nor in spheres,
                            in order */
    uint32_t nothers;
    xform_sphere_t *spheres; /* the transformed objects' culling spheres */
    uint32_t *sphere_item;   /* the item of each sphere */
    uint32_t nspheres;
    /* the spheres' fields side by side (structure of arrays), nspheres
     * rounded up to whole vectors, zero past nspheres: sphere_misses() */
    real *sph; /* SPH_FIELDS arrays of nsph_pad */
    uint32_t nsph_pad;
} brute_t;

/* The fields of sph: centre x, y, z, radius, pad0, pad_o, pad_oc. */
enum { SPH_CX, SPH_CY, SPH_CZ, SPH_R, SPH_P0, SPH_PO, SPH_POC, SPH_FIELDS };

static void brute_free(brute_t *b)
{
    if (!b)
        return;
    free(b->items);
    free(b->others);
    parallelogram_batch_free(b->batch);
    free(b->spheres);
    free(b->sphere_item);
    free(b->sph);
    free(b->objs_by_id);
    free(b->bits_by_id);
    free(b);
}

/* The batch's bits of obj (more than one if it is listed more than
 * once), or 0 when obj is none of its parallelograms (NULL included): a
 * lookup by the object's index in its scene, which every object of a
 * rendered scene has, else a look at each parallelogram of the batch. */
static uint64_t batch_bits(const brute_t *b, const COBJECT *obj)
{
    if (!obj)
        return 0;
    if (obj->id >= 0 && obj->id < b->nid && b->objs_by_id[obj->id] == obj)
        return b->bits_by_id[obj->id];
    uint64_t m = 0;
    for (int k = 0; k < b->npara; k++)
        if (b->items[b->para[k]].obj == obj)
            m |= (uint64_t)1 << k;
    return m;
}

/* Fill objs_by_id and bits_by_id from the items (brute_new()); false
 * when memory runs out. */
static bool index_by_id(brute_t *b, const primset_t *ps)
{
    b->nid = ps->nobjs;
    b->objs_by_id = calloc((size_t)b->nid + 1, sizeof *b->objs_by_id);
    b->bits_by_id = calloc((size_t)b->nid + 1, sizeof *b->bits_by_id);
    if (!b->objs_by_id || !b->bits_by_id)
        return false;
    for (int i = 0; i < ps->nobjs; i++) {
        const COBJECT *o = ps->objs[i];
        if (o && o->id >= 0 && o->id < b->nid && !b->objs_by_id[o->id])
            b->objs_by_id[o->id] = o;
    }
    for (int k = 0; k < b->npara; k++) {
        const COBJECT *o = b->items[b->para[k]].obj;
        if (o->id >= 0 && o->id < b->nid && b->objs_by_id[o->id] == o)
            b->bits_by_id[o->id] |= (uint64_t)1 << k;
    }
    return true;
}

#ifdef SIMD_REAL
#define SPH_LANES VLANES
#else
#define SPH_LANES 1
#endif

/* Fill b->sph from b->spheres (brute_new()); false when memory runs
 * out. */
static bool sphere_arrays(brute_t *b)
{
    uint32_t n = (b->nspheres + SPH_LANES - 1) / SPH_LANES * SPH_LANES;
    b->nsph_pad = n;
    b->sph = calloc((size_t)SPH_FIELDS * n + 1, sizeof *b->sph);
    if (!b->sph)
        return false;
    for (uint32_t k = 0; k < b->nspheres; k++) {
        const xform_sphere_t *sp = &b->spheres[k];
        const real f[SPH_FIELDS] = { sp->centre[X], sp->centre[Y],
                                     sp->centre[Z], sp->radius, sp->pad0,
                                     sp->pad_o, sp->pad_oc };
        for (int j = 0; j < SPH_FIELDS; j++)
            b->sph[(size_t)j * n + k] = f[j];
    }
    return true;
}

/* The batched brute force over ps, or NULL when ps has mesh triangles (they
 * keep primset_test's inline test) or memory runs out (primset_test then
 * serves, with the same answers). Parallelograms past the batch's 64 are
 * tested through intersect(). */
static brute_t *brute_new(const primset_t *ps)
{
    if (ps->ntri != 0)
        return NULL;
    brute_t *b = calloc(1, sizeof *b);
    size_t n = (size_t)ps->nrefs + 1;
    const COBJECT *para[PARALLELOGRAM_BATCH_MAX]; /* the batch's objects */
    int npara = 0, nsph = 0;
    if (b) {
        b->items = malloc(n * sizeof *b->items);
        b->others = malloc(n * sizeof *b->others);
        b->spheres = malloc(n * sizeof *b->spheres);
        b->sphere_item = malloc(n * sizeof *b->sphere_item);
    }
    if (!b || !b->items || !b->others || !b->spheres || !b->sphere_item) {
        brute_free(b);
        return NULL;
    }
    b->ps = ps;
    b->n = ps->nrefs;
    for (uint32_t i = 0; i < ps->nrefs; i++) {
        brute_item_t *it = &b->items[i];
        it->obj = ps->objs[ps->refs[i].obj];
        it->prim = (int)ps->refs[i].prim;
        if (parallelogram_is(it->obj) && npara < PARALLELOGRAM_BATCH_MAX) {
            b->para[npara] = i;
            para[npara++] = it->obj;
            continue;
        }
        if (xform_culling_sphere(it->obj, &b->spheres[nsph])) {
            b->sphere_item[nsph++] = i;
            continue;
        }
        b->others[b->nothers++] = i;
    }
    b->nspheres = (uint32_t)nsph;
    if (!sphere_arrays(b)) {
        brute_free(b);
        return NULL;
    }
    b->npara = npara;
    b->batch = parallelogram_batch_new(para, npara);
    if (!b->batch || !index_by_id(b, ps)) {
        brute_free(b);
        return NULL;
    }
    return b;
}

/* The search of the batched brute force: the primitives' nearest-hit rule
 * of primset_test(), the same arguments to each intersect(). */
typedef struct {
    real tmin, tmax, tmax_tie;
    bool shadow, found;
    uint32_t best;  /* the item of the nearest hit so far */
    hit_t *hit;     /* its hit, written straight into the caller's (which
                       is left untouched until a hit is found); NULL for a
                       shadow ray, which never reaches brute_found()'s copy */
    const COBJECT *skip[2]; /* parallelograms the ray cannot meet */
} brute_search_t;

/* A hit hh of item i: is the search over (a shadow ray's first hit)? */
static inline bool brute_found(brute_search_t *q, const primset_t *ps,
                               uint32_t i, const hit_t *hh)
{
    if (q->shadow)
        return true;
    if (q->found && !(hh->t < q->tmax || primset_before(ps, i, q->best)))
        return false;
    q->found = true;
    q->best = i;
    *q->hit = *hh;
    q->tmax = hh->t;
    q->tmax_tie = real_next_up(hh->t); /* as primset_test() */
    return false;
}

/* The parallelograms in q->skip are left out (accel_intersect_skip()).
 * Why their exact test would answer "no hit" anyway (pbrt-v3 sec. 3.9.5's
 * argument, with its test made exact by the triangle test's bound dt):
 * - A ray spawned from a point p of a plane (ray_spawn) starts at p moved
 *   past p's error box along the normal, to the side its direction
 *   points, so the whole ray (t > 0) lies on that side of the plane: it
 *   can meet the plane only at t <= 0, and the watertight test rejects
 *   every candidate whose t is not certainly > 0 when tmin >= 0
 *   (triangle.c, dt).
 * - A shadow ray from ray_spawn_to() runs from o, off the first surface
 *   toward the second point p1, to q1, p1 moved off the second surface
 *   toward o; it is traced over t < 1 - RAY_SHADOW_EPSILON < 1, part of
 *   the segment o q1. Both ends lie on one side of the second surface's
 *   plane (q1 was moved to o's side), and of the first's (o was moved to
 *   p1's side, and q1 is p1 moved by no more than its own error), and a
 *   segment whose ends lie on one side of a plane never crosses it.
 * A curved or closed surface can be met again, so only the batch's
 * parallelograms are skipped. The sides are those of the computed
 * normal; that they are the true plane's too is pbrt's argument, not a
 * proof: tests/accel/test_accel.c checks on spawned rays, grazing ones
 * included, that the skipped parallelogram's own test never reports a
 * hit and that the answers are those of the query without skip. */

/* The exact test of sphere k's object (its sphere let the ray through),
 * with brute_found()'s answer. */
static inline bool sphere_item_test(const brute_t *b, const primset_t *ps,
                                    const ray_t *r, brute_search_t *q,
                                    uint32_t k)
{
    uint32_t i = b->sphere_item[k];
    hit_t hh = { 0, 0, { 0, 0, 0 } }; /* zeroed, as primset_test */
    return xform_intersect_unculled(b->items[i].obj, b->items[i].prim, r,
                                    q->tmin, q->tmax_tie, &hh) &&
           brute_found(q, ps, i, &hh);
}

/* Bit j set when the ray passes sphere k0 + j (of SPH_LANES from k0):
 * !xform_sphere_misses_ray(). With SSE2, lane j of each vector is sphere
 * k0 + j, and every lane gets the IEEE operations of
 * xform_sphere_misses_ray() in its order (no fused multiply-add;
 * comparisons false on NaN as C's, so a NaN lets the ray through as
 * there): the same answers bit for bit (tests/accel/test_accel.c's brute
 * force test compares the whole query with the generic one, whose
 * transformed objects make the sphere test themselves). Lanes past
 * nspheres hold a sphere of radius 0 at the origin; the caller drops
 * them. */
static inline unsigned spheres_passed(const brute_t *b, uint32_t k0,
                                      const ray_t *r,
                                      const xform_sphere_ray_t *rs)
{
#ifdef SIMD_REAL
    const real u = REAL_UNIT_ROUNDOFF;
    const real *f = b->sph + k0;
    const size_t n = b->nsph_pad;
    const vreal sign = V_SET1(-REAL_C(0.0));
    const vreal ocx = V_SUB(V_LOAD(f + SPH_CX * n), V_SET1(r->o[X])),
                ocy = V_SUB(V_LOAD(f + SPH_CY * n), V_SET1(r->o[Y])),
                ocz = V_SUB(V_LOAD(f + SPH_CZ * n), V_SET1(r->o[Z]));
    const vreal oc1 = V_ADD(V_ADD(V_ANDNOT(sign, ocx), V_ANDNOT(sign, ocy)),
                            V_ANDNOT(sign, ocz));
    const vreal rho = V_ADD(
        V_LOAD(f + SPH_R * n),
        V_ADD(V_ADD(V_LOAD(f + SPH_P0 * n),
                    V_MUL(V_LOAD(f + SPH_PO * n), V_SET1(rs->o_max))),
              V_MUL(V_LOAD(f + SPH_POC * n), oc1)));
    const vreal rho2 = V_MUL(rho, rho);
    const vreal c2 = V_ADD(V_ADD(V_MUL(ocx, ocx), V_MUL(ocy, ocy)),
                           V_MUL(ocz, ocz));
    const vreal bb = V_ADD(V_ADD(V_MUL(ocx, V_SET1(r->d[X])),
                                 V_MUL(ocy, V_SET1(r->d[Y]))),
                           V_MUL(ocz, V_SET1(r->d[Z])));
    const vreal dd = V_SET1(rs->dd);
    const vreal apart = V_GT(V_SUB(V_MUL(c2, dd), V_MUL(bb, bb)),
                             V_MUL(V_ADD(rho2, V_MUL(V_SET1(32 * u), c2)),
                                   dd));
    const vreal away = V_AND(
        V_LE(V_ADD(bb, V_MUL(V_MUL(V_SET1(4 * u), oc1), V_SET1(rs->d_max))),
             V_SET1(0)),
        V_GT(c2, V_MUL(rho2, V_SET1(1 + 8 * u))));
    return ~(unsigned)V_MASK(V_OR(apart, away)) & ((1u << VLANES) - 1);
#else
    (void)k0;
    return !xform_sphere_misses_ray(&b->spheres[k0], r, rs);
#endif
}

/* The batched brute force: what primset_test() over every ref gives, with
 * each primitive's culling test made here instead of behind a call: a
 * test skipped here is one whose intersect() would have answered "no
 * hit" at its first step. The order differs (the transformed objects
 * with a culling sphere, the rest, then the parallelograms that pass the
 * batch's rejections), which primset.h's
 * nearest-hit rule makes irrelevant: ties go to the earlier primitive
 * whatever the order. So the answer is primset_test's bit for bit
 * (tests/accel/test_accel.c compares them). A shadow ray (q->shadow) stops at
 * the first hit. */
static bool brute_run(const brute_t *b, const primset_t *ps, const ray_t *r,
                      brute_search_t *q)
{
    /* The objects in the room first (in the Cornell box, its two boxes):
     * a hit there shortens tmax, so the batch turns the walls behind it
     * away (stays_before() in parallelogram.c), and a shadow ray they
     * block ends before any wall is looked at. */
    xform_sphere_ray_t rs; /* the spheres' per-ray values, made once */
    xform_sphere_ray(r, &rs);
    /* xf_intersect() culls by its sphere only for tmin >= 0: the two
     * cases as two loops, so that the loop does not test tmin again */
    if (q->tmin >= 0) {
        for (uint32_t k0 = 0; k0 < b->nspheres; k0 += SPH_LANES) {
            /* the spheres the ray passes, lowest first, as the loop over
             * k would take them */
            unsigned pass = spheres_passed(b, k0, r, &rs);
            for (; pass; pass &= pass - 1) {
                uint32_t k = k0 + (uint32_t)bits_lowest(pass);
                if (k < b->nspheres && sphere_item_test(b, ps, r, q, k))
                    return true;
            }
        }
    } else {
        for (uint32_t k = 0; k < b->nspheres; k++)
            if (sphere_item_test(b, ps, r, q, k))
                return true;
    }
    for (uint32_t k = 0; k < b->nothers; k++) {
        uint32_t i = b->others[k];
        const brute_item_t *it = &b->items[i];
        hit_t hh = { 0, 0, { 0, 0, 0 } }; /* zeroed, as primset_test */
        if (it->obj->ops->intersect(it->obj, it->prim, r, q->tmin,
                                    q->tmax_tie, &hh) &&
            brute_found(q, ps, i, &hh))
            return true;
    }
    /* the parallelograms in q->skip are left out of the batch */
    uint64_t want = ~(batch_bits(b, q->skip[0]) | batch_bits(b, q->skip[1]));
    uint64_t maybe = parallelogram_batch_cull(b->batch, r, q->tmin,
                                              q->tmax_tie, want);
    if (maybe) {
        triangle_ray_t pr;
        triangle_ray_prepare(&pr, r);
        for (; maybe; maybe &= maybe - 1) { /* lowest bit first */
            uint32_t i = b->para[bits_lowest(maybe)];
            hit_t hh = { 0, 0, { 0, 0, 0 } };
            if (parallelogram_intersect_prepared(b->items[i].obj,
                                                 b->items[i].prim, &pr,
                                                 q->tmin, q->tmax_tie, &hh) &&
                brute_found(q, ps, i, &hh))
                return true;
        }
    }
    return q->found;
}

uint64_t batch_spheres_passed(const void *s, const ray_t *r)
{
    const brute_t *b = s;
    xform_sphere_ray_t rs;
    xform_sphere_ray(r, &rs);
    uint64_t m = 0;
    for (uint32_t k0 = 0; k0 < b->nspheres && k0 < 64; k0 += SPH_LANES)
        m |= (uint64_t)spheres_passed(b, k0, r, &rs) << k0;
    return b->nspheres < 64 ? m & (((uint64_t)1 << b->nspheres) - 1) : m;
}

/* Start a search of (tmin, tmax). */
static void brute_search_init(brute_search_t *q, real tmin, real tmax,
                              hit_t *hit, const COBJECT *const skip[2])
{
    q->hit = hit;
    q->skip[0] = skip ? skip[0] : NULL;
    q->skip[1] = skip ? skip[1] : NULL;
    q->tmin = tmin;
    q->tmax = q->tmax_tie = tmax;
    q->shadow = !hit;
    q->found = false;
    q->best = 0;
}

/* The nearest hit by the batched brute force b of a ray that
 * accel_ray_ok() accepts. */
static inline bool brute_nearest(const brute_t *b, const ray_t *r,
                                 real tmin, real tmax,
                                 const COBJECT *const skip[2], hit_t *hit,
                                 const COBJECT **obj)
{
    brute_search_t q;
    brute_search_init(&q, tmin, tmax, hit, skip);
    if (!brute_run(b, b->ps, r, &q))
        return false;
    *obj = b->items[q.best].obj;
    hit->prim = b->items[q.best].prim;
    return true;
}

/* The memory of the batched brute force, as brute_new() allocates it (its
 * parallelogram batch aside, which says nothing of its size). */
static size_t brute_bytes(const brute_t *b)
{
    size_t n = (size_t)b->n + 1, nid = (size_t)b->nid + 1;
    return sizeof *b +
           n * (sizeof *b->items + sizeof *b->others + sizeof *b->spheres +
                sizeof *b->sphere_item) +
           ((size_t)SPH_FIELDS * b->nsph_pad + 1) * sizeof *b->sph +
           nid * (sizeof *b->objs_by_id + sizeof *b->bits_by_id);
}

static svet_status batch_build(void **out, const primset_t *ps,
                               const accel_params_t *p, svet_error *err)
{
    (void)p;
    *out = NULL;
    if (ps->ntri != 0)
        return svet_error_set(err, SVET_ERR_UNSUPPORTED,
                              "brute: the batch takes no mesh triangles");
#ifndef SVET_SIMD
    /* the batch is made of the speed layers (the parallelograms' early
     * rejections, the culling spheres): the plain build has none, and
     * brute force is primset_test()'s, which answers the same; the
     * batch's code is still compiled, so that it stays correct C */
    (void)ps;
    (void)brute_new;
    return svet_error_set(err, SVET_ERR_UNSUPPORTED,
                          "brute: the batch is a speed layer, and this build "
                          "(SIMD=off) has none");
#else
    brute_t *b = brute_new(ps);
    if (!b)
        return svet_error_set(err, SVET_ERR_NOMEM, "brute: out of memory");
    *out = b;
    return SVET_OK;
#endif
}

static void batch_free(void *s)
{
    brute_free(s);
}

static void batch_stats(const void *s, accel_stats_t *st)
{
    st->bytes = brute_bytes(s);
}

static bool batch_intersect(const void *s, const ray_t *r, real tmin,
                            real tmax, const COBJECT *const skip[2],
                            hit_t *hit, const COBJECT **obj)
{
    return accel_ray_ok(r, tmin, tmax) &&
           brute_nearest(s, r, tmin, tmax, skip, hit, obj);
}

static bool batch_occluded(const void *s, const ray_t *r, real tmin,
                           real tmax, const COBJECT *const skip[2])
{
    const brute_t *b = s;
    if (!accel_ray_ok(r, tmin, tmax))
        return false;
    brute_search_t q;
    brute_search_init(&q, tmin, tmax, NULL, skip);
    return brute_run(b, b->ps, r, &q);
}

const accel_ops_t batch_accel = {
    .kind = ACCEL_BRUTE,
    .build = batch_build,
    .free = batch_free,
    .stats = batch_stats,
    .tracer_intersect = batch_intersect,
    .tracer_occluded = batch_occluded,
};
