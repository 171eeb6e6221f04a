/*
 * accel.h - what the renderer calls to find where a ray meets the scene
 * (ch. 7): one interface over brute force, the uniform grid and the
 * hierarchical grid (grid.h), chosen by the scene or automatically from
 * it. Queries are thread-safe (any number of threads on one accel_t) and
 * every kind gives the same answer, bit for bit.
 * Tests: tests/test_accel.c; benchmark: bench/bench_grid.c
 */
#ifndef SVET_ACCEL_H
#define SVET_ACCEL_H

#include <stdbool.h>
#include <stddef.h>
#include "cobject.h"
#include "error.h"

/* The values of scene.h's scene_accel, so one casts to the other. */
typedef enum {
    ACCEL_AUTO = 0,  /* chosen from the scene (the rule: accel_build) */
    ACCEL_BRUTE = 1, /* test every primitive */
    ACCEL_GRID = 2,  /* uniform grid */
    ACCEL_HGRID = 3  /* hierarchical grid */
} accel_kind;

typedef struct {
    accel_kind kind;
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
                           without the fast path over analytic primitives
                           (accel.c): the same answers, for tests */
} accel_params_t;

/* AUTO's rule (measured by bench/bench_grid.c; chapters/ch07/README.md):
 *  - at most ACCEL_BRUTE_MAX primitives: brute force (a grid's walk costs
 *    more than testing them all);
 *  - else a uniform grid is built, and when more than ACCEL_AUTO_CROWDED
 *    of its primitive references sit in cells holding more than
 *    ACCEL_AUTO_CELL of them (the distribution is far from uniform: a
 *    dense mesh in a few cells of a large scene), it is replaced by the
 *    hierarchical grid; otherwise it is kept. On evenly spread meshes the
 *    two run within 25% of each other; on the teapot in a stadium the
 *    uniform grid is hundreds of times slower. */
#define ACCEL_BRUTE_MAX 16
#define ACCEL_AUTO_CELL 64
#define ACCEL_AUTO_CROWDED 0.05

/* Defaults: AUTO and every number 0 (= its default). */
void accel_params_default(accel_params_t *p);

typedef struct accel accel_t;

/* Build a structure over objs[0 .. nobjs) (not copied: they must outlive
 * it; NULL entries are skipped; nobjs may be 0, an empty scene). Objects
 * whose bounds are not finite are tested for every ray. Fails with
 * SVET_ERR_RANGE (more than 2^31 - 1 primitives, a bad parameter),
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
 * skip[0], skip[1] (either may be NULL) name the object a ray spawned by
 * ray_spawn() leaves, traced from tmin = 0, or, for a shadow ray made by
 * ray_spawn_to() and traced over (0, its returned tmax), the objects of
 * both of its ends. Only planar primitives are ever skipped (brute
 * force's parallelograms; accel.c gives the argument): a ray can meet a
 * curved or closed surface it leaves again. The answers are those of the
 * queries without skip, bit for bit (tests/test_accel.c compares them on
 * spawned rays). This function can't fail. */
bool accel_intersect_skip(const accel_t *a, const ray_t *r, real tmin,
                          real tmax, const COBJECT *const skip[2],
                          accel_hit_t *h);
bool accel_occluded_skip(const accel_t *a, const ray_t *r, real tmin,
                         real tmax, const COBJECT *const skip[2]);

/* Work done by one query, for the heat maps of ch. 7. */
typedef struct {
    long cells; /* grid cells visited, at every level */
    long tests; /* primitive tests */
} accel_counters_t;

/* accel_intersect() that also adds its work to *c. */
bool accel_intersect_counted(const accel_t *a, const ray_t *r, real tmin,
                             real tmax, accel_hit_t *h, accel_counters_t *c);

typedef struct {
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

/* "auto", "brute", "grid", "hgrid". */
const char *accel_kind_name(accel_kind k);

/* The kind named s (as accel_kind_name spells it). Fails with
 * SVET_ERR_PARSE naming the valid choices. */
svet_status accel_kind_parse(const char *s, accel_kind *k, svet_error *err);

#endif
