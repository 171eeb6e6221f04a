/*
 * test_accel.c - ch. 7: the uniform and the hierarchical grid answer
 * exactly what brute force answers (the same object, sub-primitive and t,
 * bit for bit, or both miss) on random scenes of meshes and analytic
 * primitives, for rays of every awkward kind: starting inside, exactly on
 * cell boundaries, parallel to an axis, lying in a cell plane, aimed at
 * mesh vertices, from far away, with long and short and exact tmax; shadow
 * queries agree with nearest-hit queries; empty and degenerate scenes;
 * queries from two threads; the automatic choice. Brute force's fast path
 * over analytic primitives answers what primset_test() answers, to the
 * last bit of the hit, on random scenes, the Cornell box and path-like
 * rays.
 */
#include "testutil.h"
#include "accel/accel.h"
#include "accel/batch.h"
#include "accel/grid.h"
#include "geometry/box.h"
#include "geometry/cone.h"
#include "geometry/cylinder.h"
#include "geometry/disk.h"
#include "geomcheck.h"
#include "mesh/mesh.h"
#include "mesh/meshgen.h"
#include "geometry/parallelogram.h"
#include "geometry/plane.h"
#include "geometry/sphere.h"
#include "geometry/triangle.h"
#include "geometry/xform.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NKIND 7
/* The structures compared with brute force through primset_test() alone
 * (kind 0): the defaults, grids made coarse, fine and deep so that every
 * path of the build and the walk runs (few and many primitives per cell,
 * nested child grids), and the batched brute force over analytic
 * primitives (kind 6; batch.h). */
/* Every structure, as the svet command offers them (allparts.c). */
static const accel_ops_t *const all_accels[] = {
#ifdef SVET_SIMD
    &batch_accel, /* a speed layer: not in the plain build */
#endif
    &grid_uniform_accel, &grid_hierarchical_accel, NULL
};

static void kind_params(int k, accel_params_t *p)
{
    accel_params_default(p);
    p->structures = all_accels;
    switch (k) {
    case 0: p->kind = ACCEL_BRUTE; p->brute_generic = true; break;
    case 6: p->kind = ACCEL_BRUTE; break;
    case 1: p->kind = ACCEL_GRID; break;
    case 2: p->kind = ACCEL_HGRID; break;
    case 3: p->kind = ACCEL_GRID; p->grid_k = 0.4; break;
    case 4: p->kind = ACCEL_GRID; p->grid_k = 5; break;
    default:
        p->kind = ACCEL_HGRID; p->hgrid_k = 0.3; p->hgrid_leaf = 2;
        p->hgrid_depth = 4; p->hgrid_child_k = 1.5;
        break;
    }
}

typedef struct {
    COBJECT **objs;
    int n, cap;
} scene_t_;

static void add(scene_t_ *s, COBJECT *o)
{
    ck_assert_ptr_nonnull(o);
    if (s->n == s->cap) {
        s->cap = s->cap ? 2 * s->cap : 16;
        s->objs = realloc(s->objs, (size_t)s->cap * sizeof *s->objs);
    }
    s->objs[s->n++] = o;
}

static void free_scene(scene_t_ *s)
{
    for (int i = 0; i < s->n; i++)
        cobject_free(s->objs[i]);
    free(s->objs);
    memset(s, 0, sizeof *s);
}

static real uni(pcg32_t *g, real lo, real hi)
{
    return lo + (hi - lo) * pcg32_real(g);
}

static void rand_point(VECTOR3 p, pcg32_t *g, real lo, real hi)
{
    vec_set(p, uni(g, lo, hi), uni(g, lo, hi), uni(g, lo, hi));
}

/* A random scene in [-10, 10]^3 of n objects: meshes (spheres, tori,
 * terrain patches, thin sliver triangles) and every analytic primitive
 * there is, some under transforms, one infinite plane now and then. */
static void random_scene(scene_t_ *s, pcg32_t *g, int n, bool with_plane)
{
    svet_error e;
    for (int i = 0; i < n; i++) {
        VECTOR3 c, d;
        rand_point(c, g, -9, 9);
        real r = uni(g, REAL_C(0.2), REAL_C(2.5));
        COBJECT *o = NULL;
        switch (pcg32_bounded(g, 11)) {
        case 0:
            ck_assert(meshgen_uv_sphere(&o, c, r, 6 + (int)pcg32_bounded(g, 12),
                                        3 + (int)pcg32_bounded(g, 6),
                                        &e) == SVET_OK);
            break;
        case 1:
            ck_assert(meshgen_torus(&o, c, r, r / 3, 8 + (int)pcg32_bounded(g, 8),
                                    4 + (int)pcg32_bounded(g, 4),
                                    &e) == SVET_OK);
            break;
        case 2:
            ck_assert(meshgen_terrain(&o, c, 2 * r, r / 2,
                                      2 + (int)pcg32_bounded(g, 6),
                                      pcg32_next(g), &e) == SVET_OK);
            break;
        case 3:
            o = sphere_new(c, r, &e);
            break;
        case 4:
            vec_set(d, r, r / 2, r / 3);
            vec_add(d, c, d);
            o = box_new(c, d, &e);
            break;
        case 5: {
            VECTOR3 c1 = { c[X] + r, c[Y], c[Z] }, c3 = { c[X], c[Y] + r, c[Z] + r };
            o = parallelogram_new(c, c1, c3, &e);
            break;
        }
        case 6:
            geomcheck_random_dir(d, g);
            o = disk_new(c, d, r, &e);
            break;
        case 7:
            geomcheck_random_dir(d, g);
            vec_add_scaled(d, c, 2 * r, d);
            o = pcg32_bounded(g, 2) ? cylinder_new(c, d, r / 2, true, &e)
                                    : cone_new(c, d, r / 2, true, &e);
            break;
        case 8: {
            VECTOR3 p1, p2;
            rand_point(p1, g, -1, 1);
            rand_point(p2, g, -REAL_C(0.01), REAL_C(0.01));
            vec_add_scaled(p1, c, 3 * r, p1);
            vec_add(p2, p2, c);
            o = triangle_new(c, p1, p2, &e); /* a sliver, not a mesh */
            break;
        }
        case 9: {
            VECTOR3 lo = { -1, -1, -1 }, hi = { 1, 1, 1 }, ax, sc = { r, r / 2, r };
            geomcheck_random_dir(ax, g);
            xform_t x = xform_compose(
                xform_compose(xform_scale(sc),
                              xform_rotate(ax, uni(g, 0, 360))),
                xform_translate(c));
            o = xform_new(pcg32_bounded(g, 2) ? box_new(lo, hi, &e)
                                              : sphere_new(lo, 1, &e),
                          &x, &e);
            break;
        }
        default: {
            /* a mesh with degenerate and sliver triangles among good ones */
            mesh_t m = { 0 };
            m.nverts = 5;
            m.ntris = 4;
            m.p = malloc(5 * sizeof *m.p);
            m.tri = malloc(4 * sizeof *m.tri);
            for (int k = 0; k < 4; k++)
                rand_point(m.p[k], g, -r, r), vec_add(m.p[k], m.p[k], c);
            vec_copy(m.p[4], m.p[0]);
            int32_t t[4][3] = { { 0, 1, 2 }, { 0, 4, 3 }, { 1, 2, 3 },
                                { 2, 2, 3 } };
            memcpy(m.tri, t, sizeof t);
            ck_assert(mesh_new(&o, &m, &e) == SVET_OK);
            break;
        }
        }
        ck_assert_msg(o != NULL, "%s", e.msg);
        add(s, o);
    }
    if (with_plane) {
        VECTOR3 p = { 0, -9, 0 }, nrm = { 0, 1, REAL_C(0.1) };
        add(s, plane_new(p, nrm, &e));
    }
}

/* Compare every kind with brute force on one ray, through accel_*() and
 * the tracer's entries; count hits. */
typedef struct {
    accel_t *a[NKIND];
    long rays, hits, mismatches;
} bench_t;

/* Two hits the same to the last bit: object, sub-primitive, t and the
 * barycentrics (field by field: a copy of a hit_t need not copy its
 * padding, which double has). */
static bool same_hit(const COBJECT *oa, const hit_t *a, const COBJECT *ob,
                     const hit_t *b)
{
    return oa == ob && a->prim == b->prim &&
           memcmp(&a->t, &b->t, sizeof a->t) == 0 &&
           memcmp(a->b, b->b, sizeof a->b) == 0;
}

/* The tracer's entries (render.c calls them through tracer_t) on kind
 * k: the answers of accel_intersect() and accel_occluded(), found and h,
 * to the last bit, with and without an empty skip; on a miss the
 * caller's hit and object keep what they held (a pattern of 0xa5 bytes
 * and a pointer to the bench). */
static void tracer_agrees(const bench_t *b, int k, const ray_t *r, real tmin,
                          real tmax, bool found, const accel_hit_t *h)
{
    const COBJECT *const none[2] = { NULL, NULL };
    for (int pass = 0; pass < 2; pass++) {
        const COBJECT *const *skip = pass ? none : NULL;
        hit_t th, mark;
        memset(&mark, 0xa5, sizeof mark);
        th = mark;
        const COBJECT *obj = (const COBJECT *)(const void *)b;
        bool f = accel_tracer_intersect(b->a[k], r, tmin, tmax, skip, &th,
                                        &obj);
        ck_assert_msg(f == found, "kind %d: the tracer found %d, "
                      "accel_intersect %d", k, f, found);
        if (f)
            ck_assert(same_hit(obj, &th, h->obj, &h->hit));
        else
            ck_assert_msg(obj == (const COBJECT *)(const void *)b &&
                          memcmp(&th, &mark, sizeof th) == 0,
                          "kind %d: a miss wrote the caller's hit", k);
        ck_assert(accel_tracer_occluded(b->a[k], r, tmin, tmax, skip) ==
                  found);
    }
}

static void compare(bench_t *b, const ray_t *r, real tmin, real tmax)
{
    accel_hit_t h[NKIND];
    bool found[NKIND];
    for (int k = 0; k < NKIND; k++) {
        found[k] = accel_intersect(b->a[k], r, tmin, tmax, &h[k]);
        bool occ = accel_occluded(b->a[k], r, tmin, tmax);
        ck_assert_msg(occ == found[k],
                      "kind %d: occluded %d but nearest found %d", k, occ,
                      found[k]);
        tracer_agrees(b, k, r, tmin, tmax, found[k], &h[k]);
    }
    for (int k = 1; k < NKIND; k++) {
        bool same = found[k] == found[0];
        /* b is each primitive's own scratch: compared for meshes (ours),
         * whose surface() reads all three barycentrics, and for brute
         * force's fast path, which claims the very same bytes */
        if (same && found[0])
            same = h[k].obj == h[0].obj && h[k].hit.prim == h[0].hit.prim &&
                   memcmp(&h[k].hit.t, &h[0].hit.t, sizeof(real)) == 0 &&
                   ((!mesh_get(h[0].obj) && k != 6) ||
                    memcmp(h[k].hit.b, h[0].hit.b, sizeof h[0].hit.b) == 0);
        ck_assert_msg(same,
                      "kind %d disagrees with brute force: found %d/%d, t %.9g "
                      "/ %.9g, prim %d / %d; ray o (%a %a %a) d (%a %a %a) "
                      "tmin %g tmax %g",
                      k, found[k], found[0], (double)h[k].hit.t,
                      (double)h[0].hit.t, h[k].hit.prim, h[0].hit.prim,
                      (double)r->o[X], (double)r->o[Y], (double)r->o[Z],
                      (double)r->d[X], (double)r->d[Y], (double)r->d[Z],
                      (double)tmin, (double)tmax);
    }
    b->rays++;
    b->hits += found[0];
}

static void build_all(bench_t *b, COBJECT **objs, int n)
{
    memset(b, 0, sizeof *b);
    for (int k = 0; k < NKIND; k++) {
        accel_params_t p;
        kind_params(k, &p);
        svet_error e;
        ck_assert_msg(accel_build(&b->a[k], objs, n, &p, &e) == SVET_OK, "%s",
                      e.msg);
    }
}

static void free_all(bench_t *b)
{
    for (int k = 0; k < NKIND; k++)
        accel_free(b->a[k]);
}

/* A cell boundary coordinate of kind k's top grid on axis a. */
static real boundary(const accel_t *a, int axis, pcg32_t *g)
{
    accel_stats_t s;
    accel_get_stats(a, &s);
    int i = (int)pcg32_bounded(g, (uint32_t)s.res[axis] + 1);
    double w = (s.box_max[axis] - s.box_min[axis]) / s.res[axis];
    return (real)(s.box_min[axis] + i * w);
}

/* Rays of every kind through one scene. */
static void rays_of_every_kind(bench_t *b, const COBJECT *const *objs, int n,
                               pcg32_t *g, int count)
{
    for (int i = 0; i < count; i++) {
        ray_t r;
        int kind = i % 10;
        rand_point(r.o, g, -12, 12);
        geomcheck_random_dir(r.d, g);
        real tmin = 0, tmax = (real)INFINITY;
        switch (kind) {
        case 0: /* from outside, toward the scene */
            geomcheck_random_dir(r.o, g);
            vec_scale(r.o, r.o, 30);
            {
                VECTOR3 t;
                rand_point(t, g, -8, 8);
                vec_sub(r.d, t, r.o);
            }
            break;
        case 1: /* parallel to an axis */
            vec_set(r.d, 0, 0, 0);
            r.d[pcg32_bounded(g, 3)] = pcg32_bounded(g, 2) ? 1 : -1;
            break;
        case 2: /* origin on a cell boundary (of a grid), on 1 to 3 axes */
            for (int a = 0; a < 3; a++)
                if (a == 0 || pcg32_bounded(g, 2))
                    r.o[a] = boundary(b->a[1 + (int)pcg32_bounded(g, 5)], a, g);
            break;
        case 3: { /* in a cell plane: on a boundary, no motion across it */
            int a = (int)pcg32_bounded(g, 3);
            r.o[a] = boundary(b->a[1 + (int)pcg32_bounded(g, 5)], a, g);
            r.d[a] = 0;
            if (pcg32_bounded(g, 2)) /* and along an axis within it */
                r.d[(a + 1) % 3] = 0;
            break;
        }
        case 4: { /* at a mesh vertex or a primitive's sampled point */
            const COBJECT *o = objs[pcg32_bounded(g, (uint32_t)n)];
            const mesh_t *m = mesh_get(o);
            VECTOR3 t;
            if (m) {
                vec_copy(t, m->p[pcg32_bounded(g, (uint32_t)m->nverts)]);
            } else {
                real u[2] = { pcg32_real(g), pcg32_real(g) };
                cobject_sample_t sm;
                o->ops->sample(o, u, &sm);
                vec_copy(t, sm.p);
            }
            vec_sub(r.d, t, r.o);
            break;
        }
        case 5: /* short and long tmax */
            tmax = pcg32_bounded(g, 2) ? uni(g, 0, 3) : REAL_C(1e30);
            break;
        case 6: /* tmin > 0 */
            tmin = uni(g, 0, 5);
            break;
        case 7: /* very far away, aimed at the scene */
            geomcheck_random_dir(r.o, g);
            vec_scale(r.o, r.o, REAL_C(2e4));
            {
                VECTOR3 t;
                rand_point(t, g, -8, 8);
                vec_sub(r.d, t, r.o);
            }
            break;
        case 8: /* tiny and huge direction lengths */
            vec_scale(r.d, r.d, pcg32_bounded(g, 2) ? REAL_C(1e-20) : REAL_C(1e15));
            break;
        default: /* from inside the scene box, as incoherent rays start */
            rand_point(r.o, g, -9, 9);
            break;
        }
        if (vec_length2(r.d) == 0)
            continue;
        compare(b, &r, tmin, tmax);
        /* the nearest hit's t as tmax excludes it (open interval), and
         * as tmin finds what lies beyond */
        accel_hit_t h;
        if (i % 3 == 0 && accel_intersect(b->a[0], &r, tmin, tmax, &h)) {
            compare(b, &r, tmin, h.hit.t);
            compare(b, &r, h.hit.t, tmax);
        }
    }
}

START_TEST(grids_answer_exactly_what_brute_force_answers)
{
    pcg32_t g;
    pcg32_seed(&g, 2024, 7);
    long rays = 0, hits = 0;
    for (int sc = 0; sc < 24; sc++) {
        scene_t_ s = { 0 };
        random_scene(&s, &g, 4 + (int)pcg32_bounded(&g, 60), sc % 4 == 0);
        bench_t b;
        build_all(&b, s.objs, s.n);
        rays_of_every_kind(&b, (const COBJECT *const *)s.objs, s.n, &g, 2000);
        rays += b.rays;
        hits += b.hits;
        free_all(&b);
        free_scene(&s);
    }
    ck_assert(hits > rays / 5);
    test_report_cases("grids_answer_exactly_what_brute_force_answers (rays x "
                      "5 structures)", rays);
}
END_TEST

/* A dense mesh inside a sparse one: hierarchy at work, rays at the
 * teapot, parallel to axes and from inside it. */
START_TEST(grids_agree_on_the_teapot_in_a_stadium)
{
    meshgen_scene_t s;
    svet_error e;
    ck_assert(meshgen_teapot_stadium(&s, 8000, &e) == SVET_OK);
    bench_t b;
    build_all(&b, s.objs, s.nobjs);
    accel_stats_t st;
    accel_get_stats(b.a[2], &st);
    ck_assert_msg(st.depth >= 1 && st.nodes > 1, "hgrid not refined: depth %d",
                  st.depth);
    pcg32_t g;
    pcg32_seed(&g, 5, 6);
    for (int i = 0; i < 3000; i++) {
        ray_t r;
        VECTOR3 t = { uni(&g, -1, 1), uni(&g, -1, 1), uni(&g, 0, 2) };
        if (i % 3 == 0) {
            rand_point(r.o, &g, -5, 5);
            r.o[Z] += 5;
        } else if (i % 3 == 1) {
            rand_point(r.o, &g, -REAL_C(0.5), REAL_C(0.5));
            r.o[Z] += 1;
        } else {
            rand_point(r.o, &g, -500, 500);
            r.o[Z] = fabs(r.o[Z]);
        }
        vec_sub(r.d, t, r.o);
        if (i % 5 == 0)
            geomcheck_random_dir(r.d, &g);
        if (i % 7 == 0) {
            vec_set(r.d, 0, 0, 0);
            r.d[i % 3] = i % 2 ? 1 : -1;
        }
        compare(&b, &r, 0, (real)INFINITY);
    }
    test_report_cases("grids_agree_on_the_teapot_in_a_stadium", b.rays);
    free_all(&b);
    meshgen_free_objects(&s);
}
END_TEST

START_TEST(empty_and_degenerate_scenes_never_hit)
{
    bench_t b;
    pcg32_t g;
    pcg32_seed(&g, 1, 1);
    /* no objects at all, and NULL entries */
    COBJECT *none[3] = { NULL, NULL, NULL };
    build_all(&b, none, 0);
    ray_t r = { { 0, 0, 0 }, { 1, 0, 0 } };
    for (int k = 0; k < NKIND; k++) {
        accel_hit_t h;
        ck_assert(!accel_intersect(b.a[k], &r, 0, (real)INFINITY, &h));
        ck_assert(!accel_occluded(b.a[k], &r, 0, (real)INFINITY));
    }
    free_all(&b);
    build_all(&b, none, 3);
    free_all(&b);
    /* only degenerate triangles: nothing to index */
    mesh_t m = { 0 };
    m.nverts = 3;
    m.ntris = 2;
    m.p = calloc(3, sizeof *m.p);
    m.tri = calloc(2, sizeof *m.tri);
    m.p[1][X] = 1;
    m.p[2][X] = 2; /* collinear */
    m.tri[0][1] = 1;
    m.tri[0][2] = 2;
    COBJECT *o;
    svet_error e;
    ck_assert(mesh_new(&o, &m, &e) == SVET_OK);
    build_all(&b, &o, 1);
    accel_stats_t st;
    accel_get_stats(b.a[1], &st);
    ck_assert_int_eq(st.prims, 0);
    ray_t down = { { 1, 0, 1 }, { 0, 0, -1 } };
    compare(&b, &down, 0, (real)INFINITY);
    free_all(&b);
    cobject_free(o);
}
END_TEST

/* One triangle far larger than anything: it spans every cell. */
START_TEST(a_single_huge_triangle_is_found_from_everywhere)
{
    VECTOR3 p0 = { -1e4, -1e4, 0 }, p1 = { 1e4, -1e4, REAL_C(0.5) },
            p2 = { 0, 1e4, -REAL_C(0.5) };
    svet_error e;
    scene_t_ s = { 0 };
    add(&s, triangle_new(p0, p1, p2, &e));
    mesh_t m = { 0 };
    m.nverts = 3;
    m.ntris = 1;
    m.p = malloc(3 * sizeof *m.p);
    m.tri = calloc(1, sizeof *m.tri);
    vec_copy(m.p[0], p0);
    vec_copy(m.p[1], p1);
    vec_copy(m.p[2], p2);
    m.p[0][Z] += 3;
    m.tri[0][1] = 1;
    m.tri[0][2] = 2;
    COBJECT *o;
    ck_assert(mesh_new(&o, &m, &e) == SVET_OK);
    add(&s, o);
    pcg32_t g;
    pcg32_seed(&g, 9, 9);
    for (int j = 0; j < 20; j++) { /* and small things near it */
        VECTOR3 c;
        rand_point(c, &g, -3, 3);
        add(&s, sphere_new(c, REAL_C(0.3), &e));
    }
    bench_t b;
    build_all(&b, s.objs, s.n);
    for (int i = 0; i < 5000; i++) {
        ray_t r;
        rand_point(r.o, &g, -2e4, 2e4);
        if (i % 2)
            rand_point(r.o, &g, -3, 3);
        geomcheck_random_dir(r.d, &g);
        compare(&b, &r, 0, (real)INFINITY);
    }
    ck_assert(b.hits > 1000);
    test_report_cases("a_single_huge_triangle_is_found_from_everywhere", b.rays);
    free_all(&b);
    free_scene(&s);
}
END_TEST

/* Bad rays are misses, never a crash or a hang. */
START_TEST(bad_rays_are_misses)
{
    meshgen_scene_t s;
    svet_error e;
    ck_assert(meshgen_sphere_grid(&s, 2, 2000, &e) == SVET_OK);
    bench_t b;
    build_all(&b, s.objs, s.nobjs);
    const real nan = (real)NAN, inf = (real)INFINITY;
    ray_t rays[] = { { { 0, 0, 0 }, { 0, 0, 0 } },
                     { { nan, 0, 0 }, { 1, 0, 0 } },
                     { { 0, 0, 0 }, { inf, 1, 0 } },
                     { { inf, 0, 0 }, { -1, 0, 0 } },
                     { { 1, 1, 1 }, { nan, nan, nan } } };
    for (int k = 0; k < NKIND; k++)
        for (int i = 0; i < 5; i++) {
            accel_hit_t h;
            ck_assert(!accel_intersect(b.a[k], &rays[i], 0, inf, &h));
            ck_assert(!accel_occluded(b.a[k], &rays[i], 0, inf));
        }
    ray_t ok = { { -5, 0, 0 }, { 1, 0, 0 } };
    for (int k = 0; k < NKIND; k++) {
        accel_hit_t h;
        ck_assert(!accel_intersect(b.a[k], &ok, nan, inf, &h));
        ck_assert(!accel_intersect(b.a[k], &ok, 0, nan, &h));
        ck_assert(!accel_intersect(b.a[k], &ok, 5, 5, &h));
        ck_assert(accel_intersect(b.a[k], &ok, 0, inf, &h));
    }
    free_all(&b);
    meshgen_free_objects(&s);
}
END_TEST

/* Queries share nothing mutable: two threads get what one gets. */
START_TEST(queries_from_two_threads_match_one)
{
    meshgen_scene_t s;
    svet_error e;
    ck_assert(meshgen_sphere_grid(&s, 3, 20000, &e) == SVET_OK);
    accel_t *a;
    accel_params_t p;
    accel_params_default(&p);
    p.structures = grid_accels;
    p.kind = ACCEL_HGRID;
    ck_assert(accel_build(&a, s.objs, s.nobjs, &p, &e) == SVET_OK);
    enum { N = 20000 };
    ray_t *r = malloc(N * sizeof *r);
    real *t1 = malloc(N * sizeof *t1), *t2 = malloc(N * sizeof *t2);
    pcg32_t g;
    pcg32_seed(&g, 3, 3);
    for (int i = 0; i < N; i++) {
        rand_point(r[i].o, &g, -1, 7);
        geomcheck_random_dir(r[i].d, &g);
        accel_hit_t h;
        t1[i] = accel_intersect(a, &r[i], 0, (real)INFINITY, &h) ? h.hit.t : -1;
    }
#pragma omp parallel for num_threads(2) schedule(dynamic, 64)
    for (int i = 0; i < N; i++) {
        accel_hit_t h;
        t2[i] = accel_intersect(a, &r[i], 0, (real)INFINITY, &h) ? h.hit.t : -1;
    }
    ck_assert(memcmp(t1, t2, N * sizeof *t1) == 0);
    test_report_cases("queries_from_two_threads_match_one", N);
    free(r);
    free(t1);
    free(t2);
    accel_free(a);
    meshgen_free_objects(&s);
}
END_TEST

START_TEST(auto_picks_from_the_scene_and_says_why)
{
    svet_error e;
    accel_t *a;
    accel_stats_t st;
    /* the grids offered, as the svet command offers them */
    accel_params_t grids;
    accel_params_default(&grids);
    grids.structures = grid_accels;
    /* a handful of objects: brute force */
    scene_t_ few = { 0 };
    VECTOR3 c = { 0, 0, 0 };
    for (int i = 0; i < 5; i++)
        add(&few, sphere_new(c, 1 + (real)i, &e));
    ck_assert(accel_build(&a, few.objs, few.n, NULL, &e) == SVET_OK);
    accel_get_stats(a, &st);
    ck_assert_int_eq(st.kind, ACCEL_BRUTE);
    ck_assert(strncmp(accel_describe(a), "brute (auto: 5 primitives", 25) == 0);
    accel_free(a);
    free_scene(&few);
    /* spheres spread evenly: the uniform grid */
    meshgen_scene_t s;
    ck_assert(meshgen_sphere_grid(&s, 5, 20000, &e) == SVET_OK);
    ck_assert(accel_build(&a, s.objs, s.nobjs, &grids, &e) == SVET_OK);
    accel_get_stats(a, &st);
    ck_assert_msg(st.kind == ACCEL_GRID, "%s", accel_describe(a));
    ck_assert(strncmp(accel_describe(a), "grid (auto: ", 12) == 0);
    accel_free(a);
    meshgen_free_objects(&s);
    /* the teapot in a stadium: the hierarchical grid */
    ck_assert(meshgen_teapot_stadium(&s, 20000, &e) == SVET_OK);
    ck_assert(accel_build(&a, s.objs, s.nobjs, &grids, &e) == SVET_OK);
    accel_get_stats(a, &st);
    ck_assert_msg(st.kind == ACCEL_HGRID, "%s", accel_describe(a));
    ck_assert(st.bytes > 0 && st.build_seconds >= 0);
    accel_free(a);
    meshgen_free_objects(&s);
    /* names */
    accel_kind k;
    ck_assert(accel_kind_parse("hgrid", &k, &e) == SVET_OK && k == ACCEL_HGRID);
    ck_assert(accel_kind_parse("octree", &k, &e) == SVET_ERR_PARSE);
    ck_assert_str_eq(e.msg, "unknown acceleration structure 'octree' "
                            "(expected auto, brute, grid or hgrid)");
    accel_params_t p;
    accel_params_default(&p);
    p.structures = grid_accels;
    p.grid_k = -1;
    ck_assert(accel_build(&a, NULL, 0, &p, &e) == SVET_ERR_RANGE);
}
END_TEST

/* A program of ch. 5 offers no structure: AUTO is brute force whatever
 * the scene, with the same answers as the grid's, and a grid asked for is
 * refused with what to link. */
START_TEST(no_structures_means_brute_force_and_refused_grids)
{
    svet_error e;
    meshgen_scene_t s;
    ck_assert(meshgen_sphere_grid(&s, 3, 2000, &e) == SVET_OK);
    accel_t *brute, *grid;
    ck_assert(accel_build(&brute, s.objs, s.nobjs, NULL, &e) == SVET_OK);
    accel_stats_t st;
    accel_get_stats(brute, &st);
    ck_assert_int_eq(st.kind, ACCEL_BRUTE);
    ck_assert_int_eq(st.cells, 0);
    ck_assert_msg(strstr(accel_describe(brute), "brute (auto: ") ==
                      accel_describe(brute) &&
                      strstr(accel_describe(brute), "offers no grid"),
                  "%s", accel_describe(brute));
    accel_params_t p;
    accel_params_default(&p);
    ck_assert(p.structures == NULL);
    const accel_kind refused[2] = { ACCEL_GRID, ACCEL_HGRID };
    for (int i = 0; i < 2; i++) {
        p.kind = refused[i];
        accel_t *a = NULL;
        ck_assert_int_eq(accel_build(&a, s.objs, s.nobjs, &p, &e),
                         SVET_ERR_UNSUPPORTED);
        ck_assert(a == NULL);
        ck_assert_msg(strstr(e.msg, "this program was built without the "
                                    "grids of ch. 7 (grid.c)"),
                      "%s", e.msg);
    }
    /* an empty list is no list */
    const accel_ops_t *none[1] = { NULL };
    p.structures = none;
    p.kind = ACCEL_GRID;
    accel_t *a = NULL;
    ck_assert_int_eq(accel_build(&a, s.objs, s.nobjs, &p, &e),
                     SVET_ERR_UNSUPPORTED);
    /* the same answers as the grid the svet command would build */
    p.structures = grid_accels;
    ck_assert(accel_build(&grid, s.objs, s.nobjs, &p, &e) == SVET_OK);
    pcg32_t g;
    pcg32_seed(&g, 41, 7);
    long n = 0;
    for (int i = 0; i < 2000; i++) {
        ray_t r;
        rand_point(r.o, &g, -3, 9); /* the spheres' centres: 0, 3, 6 */
        rand_point(r.d, &g, -1, 1);
        accel_hit_t hb, hg;
        bool b = accel_intersect(brute, &r, 0, (real)INFINITY, &hb);
        bool gr = accel_intersect(grid, &r, 0, (real)INFINITY, &hg);
        ck_assert(b == gr);
        ck_assert(accel_occluded(brute, &r, 0, (real)INFINITY) == b);
        if (b) {
            ck_assert(hb.obj == hg.obj && hb.hit.prim == hg.hit.prim);
            ck_assert(memcmp(&hb.hit.t, &hg.hit.t, sizeof hb.hit.t) == 0);
        }
        n++;
    }
    test_report_cases("no_structures_means_brute_force", n);
    accel_free(brute);
    accel_free(grid);
    meshgen_free_objects(&s);
}
END_TEST

/* The Cornell box of scenes/cbox.scn (walls, light, two transformed
 * boxes), with ties added: a second floor on the first, and an infinite
 * plane through the back wall listed before everything (the unbounded go
 * last in primset's order but win ties by the order of the objects). */
static void cornell_box(scene_t_ *s, bool ties)
{
    svet_error e;
    static const real q[7][4][3] = {
        { { -1, -1, 1 }, { 1, -1, 1 }, { 1, -1, -1 }, { -1, -1, -1 } },
        { { -1, 1, -1 }, { 1, 1, -1 }, { 1, 1, 1 }, { -1, 1, 1 } },
        { { -1, -1, -1 }, { 1, -1, -1 }, { 1, 1, -1 }, { -1, 1, -1 } },
        { { 1, -1, -1 }, { 1, -1, 1 }, { 1, 1, 1 }, { 1, 1, -1 } },
        { { -1, -1, 1 }, { -1, -1, -1 }, { -1, 1, -1 }, { -1, 1, 1 } },
        { { -0.23, 0.99, -0.18 }, { 0.23, 0.99, -0.18 }, { 0.23, 0.99, 0.2 },
          { -0.23, 0.99, 0.2 } },
        { { -1, -1, 1 }, { 1, -1, 1 }, { 1, -1, -1 }, { -1, -1, -1 } } };
    if (ties) {
        VECTOR3 p = { 0, 0, -1 }, n = { 0, 0, 1 };
        add(s, plane_new(p, n, &e));
    }
    for (int i = 0; i < (ties ? 7 : 6); i++)
        add(s, parallelogram_new4(q[i][0], q[i][1], q[i][2], q[i][3], &e));
    VECTOR3 lo = { -1, -1, -1 }, hi = { 1, 1, 1 }, y = { 0, 1, 0 };
    VECTOR3 s1 = { 0.3, 0.3, 0.3 }, t1 = { 0.335, -0.7, 0.38 };
    VECTOR3 s2 = { 0.3, 0.61, 0.3 }, t2 = { -0.33, -0.4, -0.28 };
    xform_t x1 = xform_compose(xform_compose(xform_scale(s1),
                                             xform_rotate(y, -17)),
                               xform_translate(t1));
    xform_t x2 = xform_compose(xform_compose(xform_scale(s2),
                                             xform_rotate(y, 18.25)),
                               xform_translate(t2));
    add(s, xform_new(box_new(lo, hi, &e), &x1, &e));
    add(s, xform_new(box_new(lo, hi, &e), &x2, &e));
}

/* Rays as a path tracer makes them: leaving a sampled surface point along
 * a random direction (ray_spawn, tmin 0), and shadow rays from one
 * sampled point to another (ray_spawn_to), grazing ones included. */
static void path_rays(bench_t *b, const COBJECT *const *objs, int n,
                      pcg32_t *g, int count)
{
    for (int i = 0; i < count; i++) {
        const COBJECT *o = objs[pcg32_bounded(g, (uint32_t)n)];
        const COBJECT *o2 = objs[pcg32_bounded(g, (uint32_t)n)];
        real u[2] = { pcg32_real(g), pcg32_real(g) };
        cobject_sample_t a, c;
        o->ops->sample(o, u, &a);
        u[0] = pcg32_real(g);
        u[1] = pcg32_real(g);
        o2->ops->sample(o2, u, &c);
        if (!vec_is_finite(a.p) || !vec_is_finite(c.p))
            continue;
        ray_t r;
        VECTOR3 w;
        geomcheck_random_dir(w, g);
        if (i % 4 == 0) /* grazing: nearly in the tangent plane */
            vec_add_scaled(w, w, -SVECTOR3(w, a.n) * REAL_C(0.999), a.n);
        if (vec_length2(w) == 0)
            continue;
        ray_spawn(&r, a.p, a.p_error, a.n, w);
        compare(b, &r, 0, (real)INFINITY);
        real tmax = ray_spawn_to(&r, a.p, a.p_error, a.n, c.p, c.p_error,
                                 c.n);
        if (vec_length2(r.d) > 0)
            compare(b, &r, 0, tmax);
    }
}

/* Every structure on scene s: n1 rays of every kind and n2 path-like
 * rays; then s is freed. Returns the rays compared, their hits in *hits. */
static long compare_on(scene_t_ *s, pcg32_t *g, int n1, int n2, long *hits)
{
    bench_t b;
    build_all(&b, s->objs, s->n);
    rays_of_every_kind(&b, (const COBJECT *const *)s->objs, s->n, g, n1);
    path_rays(&b, (const COBJECT *const *)s->objs, s->n, g, n2);
    free_all(&b);
    free_scene(s);
    *hits = b.hits;
    return b.rays;
}

/* A parallelogram with c0 in [-spread, spread]^3, its edges in
 * [-2, 2]^3, all scaled by scale (1 leaves them as drawn); NULL when
 * degenerate. */
static COBJECT *random_parallelogram(pcg32_t *g, real spread, real scale)
{
    VECTOR3 c0, c1, c3;
    svet_error e;
    rand_point(c0, g, -spread, spread);
    rand_point(c1, g, -2, 2);
    rand_point(c3, g, -2, 2);
    vec_add(c1, c1, c0);
    vec_add(c3, c3, c0);
    vec_scale(c0, c0, scale);
    vec_scale(c1, c1, scale);
    vec_scale(c3, c3, scale);
    return parallelogram_new(c0, c1, c3, &e);
}

START_TEST(fast_brute_force_answers_bit_for_bit_what_primset_test_answers)
{
    pcg32_t g;
    pcg32_seed(&g, 77, 5);
    long rays = 0, hits;
    /* random scenes of analytic primitives (their meshes dropped) */
    for (int sc = 0; sc < 16; sc++) {
        scene_t_ all = { 0 }, s = { 0 };
        random_scene(&all, &g, 4 + (int)pcg32_bounded(&g, 40), sc % 3 == 0);
        for (int i = 0; i < all.n; i++)
            if (mesh_get(all.objs[i]))
                cobject_free(all.objs[i]);
            else
                add(&s, all.objs[i]);
        free(all.objs);
        if (s.n > 0)
            rays += compare_on(&s, &g, 2000, 1000, &hits);
    }
    /* the Cornell box, with and without ties */
    for (int ties = 0; ties < 2; ties++) {
        scene_t_ s = { 0 };
        cornell_box(&s, ties);
        long n = compare_on(&s, &g, 5000, 20000, &hits);
        ck_assert_msg(hits > n / 3, "%ld hits of %ld", hits, n);
        rays += n;
    }
    /* more parallelograms than one batch holds: the rest go through
     * intersect() */
    scene_t_ s = { 0 };
    for (int i = 0; i < PARALLELOGRAM_BATCH_MAX + 9; i++) {
        COBJECT *o = random_parallelogram(&g, 5, 1);
        if (o)
            add(&s, o);
    }
    rays += compare_on(&s, &g, 3000, 2000, &hits);
    test_report_cases("fast_brute_force_answers_bit_for_bit_what_primset_"
                      "test_answers (rays x 6 structures)", rays);
}
END_TEST

/* One ray r over (0, tmax) of the skip test below: the skipped
 * parallelograms' own tests find nothing, and the queries with and
 * without skip agree to the last bit. */
static void skip_agrees(const accel_t *a, const ray_t *r, real tmax,
                        const COBJECT *const skip[2])
{
    for (int k = 0; k < 2; k++)
        if (skip[k]) {
            hit_t h;
            ck_assert_msg(!skip[k]->ops->intersect(skip[k], 0, r, 0, tmax, &h),
                          "a ray meets the surface it leaves or aims at, t "
                          "%.9g of tmax %.9g: o (%a %a %a) d (%a %a %a)",
                          (double)h.t, (double)tmax, (double)r->o[X],
                          (double)r->o[Y], (double)r->o[Z], (double)r->d[X],
                          (double)r->d[Y], (double)r->d[Z]);
        }
    accel_hit_t h0, h1;
    bool f0 = accel_intersect(a, r, 0, tmax, &h0);
    bool f1 = accel_intersect_skip(a, r, 0, tmax, skip, &h1);
    ck_assert(f0 == f1);
    if (f0)
        ck_assert(h0.obj == h1.obj && h0.hit.prim == h1.hit.prim &&
                  memcmp(&h0.hit.t, &h1.hit.t, sizeof h0.hit.t) == 0 &&
                  memcmp(h0.hit.b, h1.hit.b, sizeof h0.hit.b) == 0);
    ck_assert(accel_occluded(a, r, 0, tmax) ==
              accel_occluded_skip(a, r, 0, tmax, skip));
    /* the tracer's entries (render.c): the same answers */
    hit_t h2 = { 0, 0, { 0, 0, 0 } };
    const COBJECT *o2 = NULL;
    ck_assert(accel_tracer_intersect(a, r, 0, tmax, skip, &h2, &o2) == f1);
    ck_assert(!f1 ? o2 == NULL : o2 == h1.obj && h2.prim == h1.hit.prim &&
              memcmp(&h2.t, &h1.hit.t, sizeof h2.t) == 0 &&
              memcmp(h2.b, h1.hit.b, sizeof h2.b) == 0);
    ck_assert(accel_tracer_occluded(a, r, 0, tmax, skip) ==
              accel_occluded_skip(a, r, 0, tmax, skip));
}

/* Rays spawned as the integrator spawns them, from points where random
 * rays (from [-3 scale, 3 scale]^3) hit a parallelogram of s (cobject_fill's point, error and normal):
 * leaving it on either side (reflection, transmission, grazing), and
 * shadow rays to a point sampled on another parallelogram (an area
 * light). Returns the rays tried; s is freed. */
static long skip_rays(scene_t_ *s, pcg32_t *g, int count, real scale)
{
    accel_t *a;
    svet_error e;
    accel_params_t p;
    kind_params(6, &p); /* the batched brute force, which skips */
    ck_assert(accel_build(&a, s->objs, s->n, &p, &e) == SVET_OK);
    long rays = 0;
    for (int i = 0; i < count; i++) {
        ray_t r;
        rand_point(r.o, g, -3 * scale, 3 * scale);
        geomcheck_random_dir(r.d, g);
        accel_hit_t h;
        if (!accel_intersect(a, &r, 0, (real)INFINITY, &h) ||
            strcmp(h.obj->ops->name, "parallelogram") != 0)
            continue;
        PATHPOINT pp;
        cobject_fill(h.obj, &r, &h.hit, &pp);
        VECTOR3 w;
        geomcheck_random_dir(w, g);
        if (i % 3 == 0) /* grazing */
            vec_add_scaled(w, w, -SVECTOR3(w, pp.ng) * REAL_C(0.9999), pp.ng);
        ray_t sr;
        if (vec_length2(w) > 0) {
            const COBJECT *skip[2] = { h.obj, NULL };
            ray_spawn(&sr, pp.cross_point, pp.p_error, pp.ng, w);
            skip_agrees(a, &sr, (real)INFINITY, skip);
            rays++;
        }
        const COBJECT *l = s->objs[pcg32_bounded(g, (uint32_t)s->n)];
        if (l == h.obj || strcmp(l->ops->name, "parallelogram") != 0)
            continue;
        real u[2] = { pcg32_real(g), pcg32_real(g) };
        cobject_sample_t ls;
        l->ops->sample(l, u, &ls);
        real tmax = ray_spawn_to(&sr, pp.cross_point, pp.p_error, pp.ng, ls.p,
                                 ls.p_error, ls.n);
        if (vec_length2(sr.d) > 0) {
            const COBJECT *skip[2] = { h.obj, l };
            skip_agrees(a, &sr, tmax, skip);
            rays++;
        }
    }
    accel_free(a);
    free_scene(s);
    return rays;
}

START_TEST(skipping_the_planes_a_ray_leaves_or_aims_at_changes_no_answer)
{
    pcg32_t g;
    pcg32_seed(&g, 91, 3);
    long rays = 0;
    /* inside the box: once with the objects numbered as a scene numbers
     * them (COBJECT.id, which brute force looks the skipped ones up by),
     * once unnumbered (id -1, looked for in the batch), once with the
     * numbers reversed, so that an object's id names another object */
    for (int pass = 0; pass < 3; pass++) {
        scene_t_ s = { 0 };
        cornell_box(&s, false);
        for (int i = 0; i < s.n; i++)
            s.objs[i]->id = pass == 0 ? i : pass == 1 ? -1 : s.n - 1 - i;
        rays += skip_rays(&s, &g, 70000, REAL_C(0.33));
    }
    /* parallelograms of every orientation and size, at several scales */
    for (int sc = 0; sc < 12; sc++) {
        scene_t_ p = { 0 };
        real scale = (real)ldexp(1, 6 * (sc % 4) - 9);
        for (int i = 0; i < 2 + (int)pcg32_bounded(&g, 10); i++) {
            COBJECT *o = random_parallelogram(&g, 2, scale);
            if (o)
                add(&p, o);
        }
        if (p.n > 0)
            rays += skip_rays(&p, &g, 20000, scale);
        else
            free_scene(&p);
    }
    ck_assert_msg(rays > 50000, "%ld rays", rays);
    test_report_cases("skipping_the_planes_a_ray_leaves_or_aims_at_changes_"
                      "no_answer (spawned rays)", rays);
}
END_TEST

START_TEST(query_ray_check_accepts_exactly_finite_rays_with_a_direction)
{
    /* Every query first checks its ray (accel_ray_ok: with SSE2 as
     * vectors, else the plain sums): against the definition, coordinate
     * by coordinate with isfinite() and d_i != 0, and against the plain
     * version, on rays whose six coordinates and tmin, tmax are drawn
     * from zeros of both signs, the smallest subnormal, ordinary values,
     * the largest real, infinities and NaN. */
    const real pick[] = { 0, REAL_C(-0.0), REAL_TRUE_MIN, -REAL_TRUE_MIN,
                          1, REAL_C(-2.5), REAL_MAX, -REAL_MAX,
                          (real)INFINITY, -(real)INFINITY, (real)NAN };
    const int np = (int)(sizeof pick / sizeof pick[0]);
    pcg32_t g;
    pcg32_seed(&g, 123, 456);
    long cases = 0, ok = 0;
    for (int i = 0; i < 400000; i++, cases++) {
        ray_t r;
        for (int k = 0; k < 3; k++) {
            /* mostly ordinary coordinates, so that every single special
             * one is met alone */
            r.o[k] = pcg32_next(&g) % 4 ? pcg32_real(&g) - REAL_C(0.5)
                                       : pick[pcg32_bounded(&g, (uint32_t)np)];
            r.d[k] = pcg32_next(&g) % 4 ? pcg32_real(&g) - REAL_C(0.5)
                                       : pick[pcg32_bounded(&g, (uint32_t)np)];
        }
        if (pcg32_next(&g) % 8 == 0)
            vec_set(r.d, 0, 0, 0);
        real tmin = pcg32_next(&g) % 8 ? 0 : pick[pcg32_bounded(&g, (uint32_t)np)];
        real tmax = pcg32_next(&g) % 8 ? (real)INFINITY
                                       : pick[pcg32_bounded(&g, (uint32_t)np)];
        bool finite = true, nonzero = false;
        for (int k = 0; k < 3; k++) {
            finite = finite && isfinite(r.o[k]) && isfinite(r.d[k]);
            nonzero = nonzero || r.d[k] != 0;
        }
        bool want = finite && nonzero && tmin < tmax;
        ck_assert(accel_ray_ok(&r, tmin, tmax) == want);
        ck_assert(accel_ray_ok_plain(&r, tmin, tmax) == want);
        ok += want;
    }
    ck_assert(ok > cases / 10 && ok < cases - cases / 10);
    test_report_cases("query_ray_check_accepts_exactly_finite_rays_with_a_"
                      "direction", cases);
}
END_TEST

/* The culling spheres are the speed layer's (fast/xform_cull.c). */
#ifdef SVET_SIMD
START_TEST(vector_sphere_test_answers_as_each_sphere_bit_for_bit)
{
    /* The batched brute force tests the transformed boxes' culling
     * spheres a vector at a time (batch.c, spheres_passed()); each answer must be
     * xform_sphere_misses_ray()'s for that sphere. Eleven boxes under
     * random maps (more than one vector, a part-filled last one) among
     * other objects; rays whose line passes a sphere's centre at
     * (1 + delta) times its padded radius, delta 0 or +-2^-k (k <= 28),
     * from origins 1 to 2048 radii before or past the nearest point;
     * rays from (1 + delta) padded radii moving away from the centre or
     * along the surface (tilted by +-2^-k, k < 30); random rays; and a
     * tenth of them with a NaN, an infinity or a coordinate whose square
     * overflows (2^70 in float, REAL_MAX in double), where the vector
     * lanes must fail their comparisons as C's do. */
    pcg32_t g;
    pcg32_seed(&g, 777, 3);
    COBJECT *objs[14];
    xform_sphere_t sp[11];
    int n = 0, nsph = 0;
    svet_error e;
    for (int i = 0; i < 11; i++) {
        VECTOR3 lo, hi, axis, sc, tr;
        rand_point(lo, &g, -1, 0);
        rand_point(hi, &g, REAL_C(0.1), 1);
        rand_point(axis, &g, -1, 1);
        rand_point(sc, &g, REAL_C(0.2), 3);
        rand_point(tr, &g, -8, 8);
        xform_t x = xform_compose(
            xform_compose(xform_scale(sc), xform_rotate(axis, uni(&g, -180, 180))),
            xform_translate(tr));
        objs[n] = xform_new(box_new(lo, hi, &e), &x, &e);
        ck_assert(objs[n] != NULL);
        ck_assert(xform_culling_sphere(objs[n], &sp[nsph]));
        n++, nsph++;
        if (i == 3 || i == 7) { /* other objects between them */
            VECTOR3 c = { 1, 2, 3 }, c1 = { 2, 2, 3 }, c3 = { 1, 3, 3 };
            objs[n++] = i == 3 ? sphere_new(c, 1, &e)
                               : parallelogram_new(c, c1, c3, &e);
            ck_assert(objs[n - 1] != NULL);
        }
    }
    ck_assert_int_eq(n, 13);
    primset_t ps;
    void *a;
    ck_assert(primset_build(&ps, objs, n, &e) == SVET_OK);
    ck_assert(batch_accel.build(&a, &ps, NULL, &e) == SVET_OK);
    long cases = 0, passed = 0;
    for (int i = 0; i < 200000; i++) {
        ray_t r;
        const xform_sphere_t *s0 = &sp[pcg32_bounded(&g, (uint32_t)nsph)];
        geomcheck_random_dir(r.d, &g);
        /* delta: 0 or +-2^-k, k up to 28, around the padded radius */
        real delta = i % 5 == 0 ? 0
                                : ldexp(REAL_C(1.0), -(int)pcg32_bounded(&g, 29));
        if (pcg32_next(&g) % 2)
            delta = -delta;
        VECTOR3 w; /* the unit vector from the centre to the origin's side */
        real along = 0;
        if (i % 3 == 0) { /* a line passing at (1 + delta) rho */
            VECTOR3 t;
            geomcheck_random_dir(t, &g);
            VVECTOR3(w, r.d, t);
            vec_normalize(w, w);
            along = s0->radius * ldexp(uni(&g, 1, 2), (int)pcg32_bounded(&g, 11)) *
                    (pcg32_next(&g) % 2 ? 1 : -1);
        } else if (i % 3 == 1) { /* from (1 + delta) rho, moving away */
            geomcheck_random_dir(w, &g);
            if (SVECTOR3(w, r.d) < 0)
                vec_neg(r.d, r.d);
            if (i % 2) { /* nearly along the surface: d = t + eps w */
                VECTOR3 t;
                VVECTOR3(t, w, r.d);
                vec_normalize(t, t);
                real eps = ldexp(REAL_C(1.0), -(int)pcg32_bounded(&g, 30));
                vec_add_scaled(r.d, t, pcg32_next(&g) % 2 ? eps : -eps, w);
            }
        }
        if (i % 3 != 2) {
            /* rho as xform_sphere_misses_ray() pads it, for the origin
             * placed first at the bare radius */
            real rho = s0->radius;
            for (int pass = 0; pass < 2; pass++) {
                for (int k = 0; k < 3; k++)
                    r.o[k] = s0->centre[k] + rho * (1 + delta) * w[k] +
                             along * r.d[k];
                xform_sphere_ray_t rs0;
                xform_sphere_ray(&r, &rs0);
                real oc1 = fabs(s0->centre[X] - r.o[X]) +
                           fabs(s0->centre[Y] - r.o[Y]) +
                           fabs(s0->centre[Z] - r.o[Z]);
                rho = s0->radius + (s0->pad0 + s0->pad_o * rs0.o_max +
                                    s0->pad_oc * oc1);
            }
        } else {
            rand_point(r.o, &g, -12, 12);
        }
        if (i % 7 == 0) /* a direction of any length */
            vec_scale(r.d, r.d, uni(&g, REAL_C(0.01), 100));
        if (i % 10 == 9) { /* a NaN, an infinity or a coordinate whose
                              square overflows, in o or d */
            const real bad[6] = { (real)NAN, (real)INFINITY, -(real)INFINITY,
                                  REAL_MAX, -REAL_MAX,
                                  REAL_C(0x1p70) };
            real *c = pcg32_next(&g) % 2 ? r.o : r.d;
            c[pcg32_bounded(&g, 3)] = bad[pcg32_bounded(&g, 6)];
        }
        xform_sphere_ray_t rs;
        xform_sphere_ray(&r, &rs);
        uint64_t got = batch_spheres_passed(a, &r);
        for (int k = 0; k < nsph; k++, cases++) {
            bool pass = !xform_sphere_misses_ray(&sp[k], &r, &rs);
            ck_assert_msg(((got >> k) & 1) == pass, "ray %d sphere %d", i, k);
            passed += pass;
        }
        ck_assert(got >> nsph == 0);
    }
    ck_assert(passed > cases / 50 && passed < cases - cases / 50);
    test_report_cases("vector_sphere_test_answers_as_each_sphere_bit_for_bit",
                      cases);
    batch_accel.free(a);
    primset_free(&ps);
    for (int i = 0; i < n; i++)
        cobject_free(objs[i]);
}
END_TEST
#endif

/* accel_tracer_intersect_packet() answers each ray as
 * accel_tracer_intersect() answers it alone, bit for bit, and as brute
 * force (kind 0) does: packets of camera-like rays (one origin, nearly
 * one direction) with the odd ray from elsewhere, in another direction,
 * or unusable (NaN, zero direction), of 1 to 150 rays (more than
 * ACCEL_PACKET_MAX goes in parts), over (0, inf) and shorter intervals,
 * on every kind: the grids walk them together, brute force ray by ray. A
 * miss leaves the caller's hit and object as they were. */
START_TEST(packets_answer_as_each_ray_alone)
{
    pcg32_t g;
    pcg32_seed(&g, 2027, 11);
    long rays = 0, hits = 0;
    enum { M = 150 };
    ray_t r[M];
    hit_t h[M], mark;
    const COBJECT *obj[M];
    bool found[M];
    memset(&mark, 0xa5, sizeof mark);
    const COBJECT *const marker = (const COBJECT *)(const void *)&g;
    for (int sc = 0; sc < 12; sc++) {
        scene_t_ s = { 0 };
        random_scene(&s, &g, 10 + (int)pcg32_bounded(&g, 50), sc % 3 == 0);
        bench_t b;
        build_all(&b, s.objs, s.n);
        for (int k = 0; k < NKIND; k++)
            ck_assert_int_eq(accel_has_packets(b.a[k]), k >= 1 && k <= 5);
        for (int pk = 0; pk < 60; pk++) {
            VECTOR3 o, c;
            rand_point(o, &g, -14, 14);
            VECTOR3 aim;
            rand_point(aim, &g, -6, 6);
            vec_sub(c, aim, o);
            vec_normalize(c, c);
            real spread = pk % 4 == 0 ? REAL_C(0.3) : REAL_C(0.03);
            int n = pk % 7 == 0 ? 1 + (int)pcg32_bounded(&g, M)
                                : 1 + (int)pcg32_bounded(&g, 64);
            for (int i = 0; i < n; i++) {
                vec_copy(r[i].o, o);
                VECTOR3 jit;
                rand_point(jit, &g, -spread, spread);
                vec_add(r[i].d, c, jit);
                uint32_t odd = pcg32_bounded(&g, 40);
                if (odd == 0)
                    rand_point(r[i].o, &g, -14, 14); /* another origin */
                else if (odd == 1)
                    geomcheck_random_dir(r[i].d, &g); /* any direction */
                else if (odd == 2)
                    r[i].d[i % 3] = (real)NAN;
                else if (odd == 3)
                    vec_set(r[i].d, 0, 0, 0);
                else if (odd == 4)
                    r[i].o[Y] = -r[i].o[Y] * 0; /* -0 or +0 for the origin */
            }
            real tmin = 0, tmax = (real)INFINITY;
            if (pk % 5 == 1) {
                tmin = uni(&g, 0, 1);
                tmax = tmin + uni(&g, 0, 30);
            }
            for (int k = 0; k < NKIND; k++) {
                for (int i = 0; i < n; i++) {
                    h[i] = mark;
                    obj[i] = marker;
                }
                accel_tracer_intersect_packet(b.a[k], r, n, tmin, tmax, h,
                                              obj, found);
                for (int i = 0; i < n; i++) {
                    hit_t th = mark;
                    const COBJECT *to = marker;
                    bool f = accel_tracer_intersect(b.a[k], &r[i], tmin, tmax,
                                                    NULL, &th, &to);
                    accel_hit_t bh;
                    bool bf = accel_intersect(b.a[0], &r[i], tmin, tmax, &bh);
                    ck_assert_msg(found[i] == f && f == bf,
                                  "kind %d, packet %d, ray %d of %d: found %d "
                                  "in the packet, %d alone, %d by brute force",
                                  k, pk, i, n, found[i], f, bf);
                    /* on a miss, untouched: the marks, byte for byte */
                    bool same = f ? same_hit(obj[i], &h[i], to, &th)
                                  : obj[i] == marker &&
                                        memcmp(&h[i], &mark, sizeof mark) == 0;
                    ck_assert_msg(same, "kind %d, packet %d, ray %d of %d: "
                                  "the packet's hit differs from the ray's "
                                  "alone", k, pk, i, n);
                    if (f)
                        ck_assert(to == bh.obj && th.prim == bh.hit.prim &&
                                  memcmp(&th.t, &bh.hit.t, sizeof th.t) == 0);
                    rays++;
                    hits += f;
                }
            }
        }
        free_all(&b);
        free_scene(&s);
    }
    ck_assert(hits > rays / 5);
    test_report_cases("packets_answer_as_each_ray_alone (rays x 7 "
                      "structures)", rays);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("accel");
    TCase *tc = tcase_create("accel");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, grids_answer_exactly_what_brute_force_answers);
    tcase_add_test(tc, grids_agree_on_the_teapot_in_a_stadium);
    tcase_add_test(tc, empty_and_degenerate_scenes_never_hit);
    tcase_add_test(tc, a_single_huge_triangle_is_found_from_everywhere);
    tcase_add_test(tc, bad_rays_are_misses);
    tcase_add_test(tc, packets_answer_as_each_ray_alone);
    tcase_add_test(tc, queries_from_two_threads_match_one);
    tcase_add_test(tc, auto_picks_from_the_scene_and_says_why);
    tcase_add_test(tc, no_structures_means_brute_force_and_refused_grids);
    tcase_add_test(tc, query_ray_check_accepts_exactly_finite_rays_with_a_direction);
#ifdef SVET_SIMD
    tcase_add_test(tc, vector_sphere_test_answers_as_each_sphere_bit_for_bit);
#endif
    tcase_add_test(tc,
                   fast_brute_force_answers_bit_for_bit_what_primset_test_answers);
    tcase_add_test(tc,
                   skipping_the_planes_a_ray_leaves_or_aims_at_changes_no_answer);
    suite_add_tcase(s, tc);
    return s;
}
