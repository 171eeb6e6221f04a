/*
 * primset.h - the flat list of every sub-primitive of a scene (each
 * triangle of a mesh, each analytic object), which all the acceleration
 * structures of ch. 7 index by number, and the test of one of them against
 * a ray: the inner loop of brute force and of both grids.
 * Tests: tests/accel/test_primset.c (and tests/accel/test_accel.c through accel.h)
 */
#ifndef SVET_PRIMSET_H
#define SVET_PRIMSET_H

#include <stdbool.h>
#include <stdint.h>
#include <string.h>
#include "materials/cobject.h"
#include "core/error.h"
#include "mesh/mesh.h"

/* Primitive numbers fit in 31 bits: the grids use the top bit of an item
 * to mark a child grid. */
#define PRIMSET_MAX_REFS ((1u << 31) - 1)

/* One sub-primitive: object objs[obj], sub-primitive prim. */
typedef struct {
    uint32_t obj;
    uint32_t prim;
} primref_t;

/* The numbering: refs[0 .. ntri) are the triangles of every mesh, sorted
 * along a Morton (Z-order) curve through their centroids, so that the
 * triangles of one grid cell lie side by side in memory;
 * refs[ntri .. nbounded) the other primitives with finite bounds, in the
 * order of the objects; refs[nbounded .. nrefs) those without (infinite
 * planes, say: bounds beyond +-REAL_MAX / 16 count as infinite), which
 * are tested for every ray. Degenerate mesh triangles
 * are left out: they are never hit. */
typedef struct {
    COBJECT *const *objs;   /* the scene's objects (borrowed) */
    int nobjs;
    primref_t *refs;        /* object and sub-primitive of each number */
    uint32_t nrefs, nbounded, ntri;
    real (*tri)[9];         /* corners of refs[0 .. ntri), side by side:
                               the compact layout the inner loop reads
                               (36 B per triangle in float; one or two
                               cache lines per test, where indices and
                               vertices would cost four fetches) */
    bbox_t *bounds;         /* bounds of refs[0 .. nbounded), for building;
                               NULL after primset_drop_bounds() */
    bbox_t box;             /* union of those bounds; empty if none */
    double pad;             /* how far a grid pads every primitive's bounds
                               (see grid.c): 2^-20 of the box's diagonal
                               plus 8 ulps of its largest coordinate */
} primset_t;

/* List the sub-primitives of objs[0..nobjs) (NULL entries and objects
 * with nprims <= 0 are skipped) and their bounds. Fails with
 * SVET_ERR_RANGE when there are more than PRIMSET_MAX_REFS, SVET_ERR_NOMEM.
 * On failure ps holds nothing. */
svet_status primset_build(primset_t *ps, COBJECT *const *objs, int nobjs,
                          svet_error *err);

/* Free the bounds once the structure is built. */
void primset_drop_bounds(primset_t *ps);

void primset_free(primset_t *ps);

/* Bytes held (without the objects). */
size_t primset_bytes(const primset_t *ps);

/* --- one query ------------------------------------------------------------ */

/* A small per-ray cache of the primitives already tested (mailboxing,
 * Amanatides & Woo 1987 sec. 4, made thread-safe by living on the caller's
 * stack instead of in the primitives): a primitive that spans several
 * cells is tested once per ray, not once per cell. Direct-mapped on the
 * low bits of the number; a primitive evicted by another is merely
 * tested again, which gives the same answer. */
#define PRIMSET_MAILBOX 16

/* The state of one ray's query. */
typedef struct {
    const ray_t *r;
    mesh_ray_t mr;      /* the ray prepared for the inline triangle test */
    real tmin, tmax;    /* the open interval still searched: tmax falls to
                           the nearest hit so far */
    real tmax_tie;      /* nextafter(tmax, +inf) once a hit is found */
    bool found;
    uint32_t ref;       /* the primitive of the nearest hit */
    hit_t hit;          /* and that hit */
    long tests;         /* primitive tests made (for statistics) */
    long cells;         /* grid cells visited (for statistics) */
    uint32_t mailbox[PRIMSET_MAILBOX];
} primset_query_t;

/* Start a query of r over (tmin, tmax). This function can't fail. */
static inline void primset_query_init(primset_query_t *q, const ray_t *r,
                                      real tmin, real tmax)
{
    q->r = r;
    mesh_ray_prepare(&q->mr, r);
    q->tmin = tmin;
    q->tmax = tmax;
    q->tmax_tie = tmax;
    q->found = false;
    q->ref = 0;
    q->tests = 0;
    q->cells = 0;
    memset(q->mailbox, 0xff, sizeof q->mailbox);
}

/* Does primitive a come before b in the order of the objects and of their
 * sub-primitives? The tie-break of primset_test(). */
static inline bool primset_before(const primset_t *ps, uint32_t a, uint32_t b)
{
    primref_t ra = ps->refs[a], rb = ps->refs[b];
    return ra.obj < rb.obj || (ra.obj == rb.obj && ra.prim < rb.prim);
}

/* Has `ref` been tested for this ray already? If not, marks it tested
 * (the mailbox) and counts the test. This function can't fail. */
static inline bool primset_seen(primset_query_t *q, uint32_t ref)
{
    uint32_t *mb = &q->mailbox[ref & (PRIMSET_MAILBOX - 1)];
    if (*mb == ref)
        return true;
    *mb = ref;
    q->tests++;
    return false;
}

/* Keep a hit at t of primitive ref when it beats the best so far (the
 * nearest-hit rule of primset_test()); the caller then fills q->hit's
 * other fields when this returns true. This function can't fail. */
static inline bool primset_keep(const primset_t *ps, primset_query_t *q,
                                uint32_t ref, real t)
{
    if (q->found && !(t < q->tmax || primset_before(ps, ref, q->ref)))
        return false;
    q->found = true;
    q->ref = ref;
    q->tmax = t;
    q->tmax_tie = real_next_up(t); /* nextafter(t, +inf), no libm call */
    return true;
}

/* primset_test() of mesh triangle ref (ref < ps->ntri) without the
 * mailbox (the caller has asked primset_seen()), on the corners c:
 * ps->tri[ref], or a copy of its bits that the caller has at hand (the
 * grid's quads), which gives the same answer. Returns true when ref was
 * hit in (tmin, tmax). This function can't fail. */
static inline bool primset_test_corners(const primset_t *ps,
                                        primset_query_t *q, uint32_t ref,
                                        const real c[9])
{
    real t, b[3];
    if (!mesh_ray_intersect(c, &q->mr, q->tmin, q->tmax_tie, &t, b))
        return false;
    if (primset_keep(ps, q, ref, t)) {
        q->hit.t = t;
        q->hit.prim = -1; /* set from refs by primset_query_finish() */
        q->hit.b[0] = b[0];
        q->hit.b[1] = b[1];
        q->hit.b[2] = b[2];
    }
    return true;
}

/* primset_test_corners() on ps->tri[ref]. This function can't fail. */
static inline bool primset_test_tri(const primset_t *ps, primset_query_t *q,
                                    uint32_t ref)
{
    return primset_test_corners(ps, q, ref, ps->tri[ref]);
}

/* Test primitive `ref`. Nearest-hit rule: a hit replaces the best one
 * when it is nearer, or at exactly the same t and earlier in the order of
 * the objects (then of their sub-primitives), so the answer does not
 * depend on the order in which a structure tests the primitives: every
 * structure gives the hit brute force gives, bit for bit. Returns true
 * when ref was hit in (tmin, tmax) at all (for shadow rays: any hit ends
 * the search). This function can't fail. */
static inline bool primset_test(const primset_t *ps, primset_query_t *q,
                                uint32_t ref)
{
    if (primset_seen(q, ref))
        return false;
    if (ref < ps->ntri)
        return primset_test_tri(ps, q, ref);
    const primref_t pr = ps->refs[ref];
    const COBJECT *o = ps->objs[pr.obj];
    /* zeroed: a primitive may leave part of the scratch b unset, and
     * every structure must return the same bytes */
    hit_t h = { 0, 0, { 0, 0, 0 } };
    if (!o->ops->intersect(o, (int)pr.prim, q->r, q->tmin, q->tmax_tie, &h))
        return false;
    if (primset_keep(ps, q, ref, h.t))
        q->hit = h;
    return true;
}

/* The object of the nearest hit, with q->hit.prim completed; NULL when
 * there is none. This function can't fail. */
static inline const COBJECT *primset_query_finish(const primset_t *ps,
                                                  primset_query_t *q)
{
    if (!q->found)
        return NULL;
    primref_t pr = ps->refs[q->ref];
    q->hit.prim = (int)pr.prim;
    return ps->objs[pr.obj];
}

#endif
