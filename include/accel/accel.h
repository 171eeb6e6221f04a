/*
 * accel.h - what the renderer calls to find where a ray meets the scene
 * (ch. 7): one interface over brute force and the structures a program
 * links and offers through accel_params_t.structures (the uniform and the
 * hierarchical grid: grid.h's grid_accels; the batched brute force of
 * batch.h), chosen by the scene or automatically from it. Brute force
 * through primset.h is always there. The renderer reaches this file only
 * through scene_features_t.accel (accel_layer below), so that a program
 * of ch. 5 links none of it and traces with tracer.h's list of objects.
 * Queries are thread-safe (any number of threads on one accel_t) and every
 * kind gives the same answer, bit for bit.
 * Tests: tests/accel/test_accel.c; benchmark: bench/bench_grid.c
 */
#ifndef SVET_ACCEL_H
#define SVET_ACCEL_H

#include <stdbool.h>
#include <stddef.h>
#include "materials/cobject.h"
#include "core/error.h"
#include "accel/primset.h"
#include "render/tracer.h"

/* The values of scene.h's scene_accel, so one casts to the other. */
typedef enum {
    ACCEL_AUTO = 0,  /* chosen from the scene (the rule: accel_build) */
    ACCEL_BRUTE = 1, /* test every primitive */
    ACCEL_GRID = 2,  /* uniform grid */
    ACCEL_HGRID = 3  /* hierarchical grid */
} accel_kind;

typedef struct accel_ops accel_ops_t;

typedef struct {
    accel_kind kind;
    const accel_ops_t *const *structures; /* what the program offers
                           besides brute force through primset.h,
                           NULL-terminated (grid.h's grid_accels, or
                           allparts.h's list, which has batch.h's batched
                           brute force too); NULL or empty: that brute
                           force only */
    double grid_k;      /* uniform grid: k of k N^(1/3) cells per axis;
                           0 = GRID_K_DEFAULT */
    double hgrid_k;     /* hierarchical grid: top level's k; 0 =
                           HGRID_K_DEFAULT */
    int hgrid_leaf;     /* a cell with more primitives gets a child grid;
                           0 = HGRID_LEAF_DEFAULT */
    int hgrid_depth;    /* levels below the top; 0 = HGRID_DEPTH_DEFAULT */
    double hgrid_child_k; /* child grids' k; 0 = HGRID_CHILD_K_DEFAULT */
    int brute_max;      /* AUTO: brute force up to this many primitives;
                           0 = ACCEL_BRUTE_MAX */
    bool brute_generic; /* brute force through primset_test() alone,
                           even where the batched brute force (batch.h) is
                           offered: the same answers, for tests */
} accel_params_t;

/* AUTO's rule (bench/results/grid.md shows both grids on both kinds of
 * scene):
 *  - at most ACCEL_BRUTE_MAX primitives, or no structure offered: brute
 *    force (a grid's walk costs more than testing them all);
 *  - else a uniform grid is built (when offered; else the hierarchical
 *    one), and when more than ACCEL_AUTO_CROWDED
 *    of its primitive references sit in cells holding more than
 *    ACCEL_AUTO_CELL of them (the distribution is far from uniform: a
 *    dense mesh in a few cells of a large scene), it is replaced by the
 *    hierarchical grid; otherwise it is kept. On evenly spread meshes the
 *    two run alike and the children would only cost build time and
 *    memory; where a dense mesh crowds a few cells the uniform grid is
 *    far slower. */
#define ACCEL_BRUTE_MAX 16
#define ACCEL_AUTO_CELL 64
#define ACCEL_AUTO_CROWDED 0.05

/* An acceleration structure a program may link and offer (accel_params_t
 * .structures). It indexes the primset accel_build() makes; accel.c tests
 * the unbounded primitives itself and asks the structure for the rest,
 * unless the structure answers whole queries (tracer_intersect below).
 * Part II's structures (a kd-tree, say) slot in as one more table. */
struct accel_stats;
struct accel_ops {
    accel_kind kind;     /* what it is (the scene's `accel` word) */
    /* Build over ps (its bounds still there; ps outlives it) with the
     * numbers of p. Fails with SVET_ERR_NOMEM, or SVET_ERR_UNSUPPORTED
     * when it cannot index this scene (accel_build then falls back to
     * brute force and says so). */
    svet_status (*build)(void **out, const primset_t *ps,
                         const accel_params_t *p, svet_error *err);
    /* Nearest hit (q->found) and any hit over the bounded primitives,
     * as grid_intersect() and grid_occluded() of grid.h. */
    bool (*intersect)(const void *s, primset_query_t *q);
    bool (*occluded)(const void *s, primset_query_t *q);
    void (*free)(void *s); /* NULL is allowed */
    /* Fill the structure's part of accel_stats_t: bytes (its own),
     * nodes, cells, items, empty_cells, max_cell, depth, res, box. */
    void (*stats)(const void *s, struct accel_stats *st);
    /* AUTO's measure (NULL when it has none): the fraction of its
     * primitive references in cells of more than `crowd` of them. */
    double (*crowded)(const void *s, long crowd);
    /* Nearest hits of n <= ACCEL_PACKET_MAX queries at once, each left
     * exactly as intersect() leaves it (grid_intersect_packet() of
     * grid.h); NULL when the structure has no faster way than intersect()
     * ray by ray. */
    void (*intersect_packet)(const void *s, primset_query_t *q, int n);
    /* A structure that answers whole queries itself, over every
     * primitive of the primset (the unbounded ones and skip included),
     * sets these two, in the shape of tracer.h's tracer_t on its own data
     * s, rays that accel_ray_ok() refuses included; intersect and
     * occluded above may then be NULL (accel.c asks primset_test() for
     * the work counted by accel_intersect_counted()). The batched brute
     * force of batch.h, of kind ACCEL_BRUTE, is one; NULL for the grids,
     * which index the bounded primitives only. */
    bool (*tracer_intersect)(const void *s, const ray_t *r, real tmin,
                             real tmax, const COBJECT *const skip[2],
                             hit_t *hit, const COBJECT **obj);
    bool (*tracer_occluded)(const void *s, const ray_t *r, real tmin,
                            real tmax, const COBJECT *const skip[2]);
};

/* The most queries an accel_ops_t.intersect_packet takes at once. */
#define ACCEL_PACKET_MAX 64

/* The structure of kind k in list (NULL-terminated; may be NULL), or NULL
 * when the program offers none. Inline, so that the scene file's checks
 * link nothing. This function can't fail. */
static inline const accel_ops_t *accel_offered(const accel_ops_t *const *list,
                                               accel_kind k)
{
    for (int i = 0; list && list[i]; i++)
        if (list[i]->kind == k)
            return list[i];
    return NULL;
}

/* What to link for kind k, for messages: "the grids of ch. 7 (grid.c)";
 * "" for AUTO and brute force, which are always there. This function
 * can't fail. */
static inline const char *accel_kind_needs(accel_kind k)
{
    return k == ACCEL_GRID || k == ACCEL_HGRID ? "the grids of ch. 7 (grid.c)"
                                               : "";
}

/* "auto", "brute", "grid", "hgrid". Inline, so that the renderer's
 * messages link nothing. This function can't fail. */
static inline const char *accel_kind_name(accel_kind k)
{
    switch (k) {
    case ACCEL_AUTO: return "auto";
    case ACCEL_BRUTE: return "brute";
    case ACCEL_GRID: return "grid";
    case ACCEL_HGRID: return "hgrid";
    }
    return "?";
}

/* Defaults: AUTO, no structures (brute force only) and every number 0
 * (= its default). */
void accel_params_default(accel_params_t *p);

typedef struct accel accel_t;

/* Build a structure over objs[0 .. nobjs) (not copied: they must outlive
 * it; NULL entries are skipped; nobjs may be 0, an empty scene). Objects
 * whose bounds are not finite are tested for every ray. Fails with
 * SVET_ERR_RANGE (more than 2^31 - 1 primitives, a bad parameter),
 * SVET_ERR_UNSUPPORTED (p asks for a kind p->structures does not offer:
 * "this program was built without the grids of ch. 7 (grid.c)"),
 * SVET_ERR_NOMEM. A grid that cannot be built over a scene whose extent
 * overflows a double falls back to brute force, and says so in
 * accel_describe(). */
svet_status accel_build(accel_t **out, COBJECT *const *objs, int nobjs,
                        const accel_params_t *p, svet_error *err);

/* NULL is allowed. */
void accel_free(accel_t *a);

/* A hit: the object, and the hit_t to complete with
 * cobject_fill(obj, ray, &hit, &pathpoint). */
typedef struct {
    const COBJECT *obj;
    hit_t hit;
} accel_hit_t;

/* Nearest hit of r in the open interval (tmin, tmax). Returns false (h
 * untouched) on a miss, or when r has a zero, NaN or infinite direction
 * or origin, or tmin, tmax are NaN. Of hits at exactly the same t, the
 * first object in objs wins (then its first sub-primitive), whatever the
 * structure. This function can't fail. */
bool accel_intersect(const accel_t *a, const ray_t *r, real tmin, real tmax,
                     accel_hit_t *h);

/* Is there any hit in (tmin, tmax)? Stops at the first one found (shadow
 * rays). Same answer as accel_intersect() != false. This function can't
 * fail. */
bool accel_occluded(const accel_t *a, const ray_t *r, real tmin, real tmax);

/* accel_intersect() and accel_occluded() told which surfaces the ray
 * cannot meet in (tmin, tmax), so that they may skip their exact tests:
 * skip[0], skip[1] (either may be NULL; skip itself may be NULL, the same
 * as { NULL, NULL }: nothing skipped) name the object a ray spawned by
 * ray_spawn() leaves, traced from tmin = 0, or, for a shadow ray made by
 * ray_spawn_to() and traced over (0, its returned tmax), the objects of
 * both of its ends. Only planar primitives are ever skipped (the
 * batched brute force's parallelograms; batch.c gives the argument): a ray can meet a
 * curved or closed surface it leaves again. The answers are those of the
 * queries without skip, bit for bit (tests/accel/test_accel.c compares them on
 * spawned rays). The renderer reaches these queries as accel_tracer_*()
 * below, through tracer_t's untyped context; these two stay public as
 * the typed ones for a program that holds an accel_t, and state the
 * contract of skip once, here. This function can't fail. */
bool accel_intersect_skip(const accel_t *a, const ray_t *r, real tmin,
                          real tmax, const COBJECT *const skip[2],
                          accel_hit_t *h);
bool accel_occluded_skip(const accel_t *a, const ray_t *r, real tmin,
                         real tmax, const COBJECT *const skip[2]);

/* accel_intersect_skip() and accel_occluded_skip() in the shape of
 * tracer.h's tracer_t.intersect and .occluded, so that render.c's
 * tracer calls them with no function in between: a is the accel_t (as
 * tracer_t's ctx). accel_tracer_intersect() answers into the caller's hit
 * and object directly, with no accel_hit_t in between; *hit and *obj are
 * untouched on a miss. The same answers, bit for bit. These functions
 * can't fail. */
bool accel_tracer_intersect(const void *a, const ray_t *r, real tmin,
                            real tmax, const COBJECT *const skip[2],
                            hit_t *hit, const COBJECT **obj);
bool accel_tracer_occluded(const void *a, const ray_t *r, real tmin,
                           real tmax, const COBJECT *const skip[2]);

/* Whether a's structure traces coherent rays faster in packets than one
 * at a time (the grids: accel_ops_t.intersect_packet), so that a caller
 * holding such rays (a pinhole camera's, a tile of pixels) should give
 * them to accel_tracer_intersect_packet(). This function can't fail. */
bool accel_has_packets(const accel_t *a);

/* The nearest hits of the n rays r[0 .. n) over (tmin, tmax), at once:
 * found[i] = accel_tracer_intersect(a, &r[i], tmin, tmax, NULL, &hit[i],
 * &obj[i]), bit for bit, hit[i] and obj[i] untouched on a miss. The rays
 * may be anything (any origins, any n >= 0); they go fastest with one
 * origin and nearly one direction (a pinhole camera's rays over 8 x 8
 * pixels: grid.h's grid_intersect_packet() walks them together). A
 * structure without packets answers ray by ray. render.c calls it as
 * accel_layer_t.intersect_packet (a: the accel_t). This function can't
 * fail. */
void accel_tracer_intersect_packet(const void *a, const ray_t *r, int n,
                                   real tmin, real tmax, hit_t *hit,
                                   const COBJECT **obj, bool *found);

/* Whether a query takes ray r over (tmin, tmax) at all: all six
 * coordinates finite, d nonzero, tmin < tmax (a query answers "no hit"
 * otherwise). accel_ray_ok_plain is the same test without SIMD
 * (tracer.h's tracer_ray_ok()).
 * Test hooks: tests/accel/test_accel.c checks both against the definition (the
 * queries make the test inline). These functions can't fail. */
bool accel_ray_ok(const ray_t *r, real tmin, real tmax);
bool accel_ray_ok_plain(const ray_t *r, real tmin, real tmax);

/* Work done by one query, for the heat maps of ch. 7. */
typedef struct {
    long cells; /* grid cells visited, at every level */
    long tests; /* primitive tests */
} accel_counters_t;

/* accel_intersect() that also adds its work to *c. */
bool accel_intersect_counted(const accel_t *a, const ray_t *r, real tmin,
                             real tmax, accel_hit_t *h, accel_counters_t *c);

typedef struct accel_stats {
    accel_kind kind;      /* what was built (never AUTO) */
    double build_seconds; /* wall-clock time of accel_build */
    size_t bytes;         /* memory of the structure (not the objects) */
    long prims;           /* primitives indexed (degenerate triangles
                             left out) */
    long unbounded;       /* of which tested for every ray */
    long nodes;           /* grids: 1 for the uniform grid */
    long cells;           /* cells at all levels */
    long items;           /* primitive references in cells */
    long empty_cells;
    long max_cell;        /* most primitives in one cell */
    int depth;            /* deepest level (0: the top only) */
    int res[3];           /* the top level's cells per axis */
    double box_min[3];    /* and its box: cell (i, j, k) starts at */
    double box_max[3];    /* box_min + (i, j, k) (box_max - box_min) / res */
} accel_stats_t;

void accel_get_stats(const accel_t *a, accel_stats_t *s);

/* One line saying what was built and, for AUTO, why: "hgrid (auto: 41% of
 * the references in cells of more than 64; 12345 primitives)". */
const char *accel_describe(const accel_t *a);

/* The kind named s (as accel_kind_name spells it). Fails with
 * SVET_ERR_PARSE naming the valid choices. */
svet_status accel_kind_parse(const char *s, accel_kind *k, svet_error *err);

/* accel.c's functions as one table, which a program hands the renderer
 * in scene_features_t.accel (allparts.h), so that render.c builds its
 * tracer here without naming this file: a program that offers no table
 * (ch. 5) links none of accel.c, primset.c or the structures. */
typedef struct accel_layer {
    svet_status (*build)(accel_t **out, COBJECT *const *objs, int nobjs,
                         const accel_params_t *p, svet_error *err);
    void (*free)(accel_t *a);
    tracer_t (*tracer)(const accel_t *a); /* accel_tracer() */
    bool (*has_packets)(const accel_t *a);
    void (*intersect_packet)(const void *a, const ray_t *r, int n, real tmin,
                             real tmax, hit_t *hit, const COBJECT **obj,
                             bool *found);
    const char *(*describe)(const accel_t *a);
} accel_layer_t;

/* The tracer over a: accel_tracer_intersect() and accel_tracer_occluded()
 * with a as ctx, or, where a's structure answers whole queries (the
 * batched brute force), its own tracer_intersect and tracer_occluded with
 * its data as ctx, which answer the same with no call in between. a must
 * outlive it. This function can't fail. */
tracer_t accel_tracer(const accel_t *a);

/* { accel_build, accel_free, accel_tracer, accel_has_packets,
 * accel_tracer_intersect_packet, accel_describe }. */
extern const accel_layer_t accel_layer;

#endif
