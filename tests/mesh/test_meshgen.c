/*
 * test_meshgen.c - the procedural meshes of ch. 7: triangle counts, closed
 * surfaces (every edge met by exactly two triangles in opposite
 * directions, compared by the bits of the positions), outward winding
 * (the enclosed volume by the divergence theorem is positive and near the
 * solid's), and watertightness: rays from inside always hit.
 */
#include "testutil.h"
#include "geomcheck.h"
#include "mesh/mesh.h"
#include "mesh/meshgen.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static COBJECT *sphere(int nu, int nv)
{
    COBJECT *o;
    svet_error e;
    VECTOR3 c = { 1, 2, 3 };
    ck_assert_msg(meshgen_uv_sphere(&o, c, 2, nu, nv, &e) == SVET_OK, "%s",
                  e.msg);
    return o;
}

static COBJECT *torus(int nu, int nv)
{
    COBJECT *o;
    svet_error e;
    VECTOR3 c = { -1, 0, REAL_C(0.5) };
    ck_assert_msg(meshgen_torus(&o, c, 3, 1, nu, nv, &e) == SVET_OK, "%s",
                  e.msg);
    return o;
}

/* A directed edge between two positions, by their bits. */
typedef struct {
    real a[3], b[3];
} edge_t;

static int cmp_edge(const void *x, const void *y)
{
    return memcmp(x, y, sizeof(edge_t));
}

/* Closed and consistently wound: the multiset of directed edges a->b
 * equals that of the reversed edges b->a. */
static void check_closed(const COBJECT *o)
{
    const mesh_t *m = mesh_get(o);
    size_t n = 3 * (size_t)m->ntris;
    edge_t *fwd = calloc(n, sizeof *fwd), *rev = calloc(n, sizeof *rev);
    for (int t = 0; t < m->ntris; t++)
        for (int k = 0; k < 3; k++) {
            const real *a = m->p[m->tri[t][k]], *b = m->p[m->tri[t][(k + 1) % 3]];
            size_t i = 3 * (size_t)t + (size_t)k;
            memcpy(fwd[i].a, a, sizeof fwd[i].a);
            memcpy(fwd[i].b, b, sizeof fwd[i].b);
            memcpy(rev[i].a, b, sizeof rev[i].a);
            memcpy(rev[i].b, a, sizeof rev[i].b);
        }
    qsort(fwd, n, sizeof *fwd, cmp_edge);
    qsort(rev, n, sizeof *rev, cmp_edge);
    ck_assert_msg(memcmp(fwd, rev, n * sizeof *fwd) == 0,
                  "%s: an edge is not matched by its reverse", o->ops->name);
    free(fwd);
    free(rev);
}

/* Volume = sum over triangles of p0 . (p1 x p2) / 6 (divergence theorem),
 * in double about the first vertex. */
static double volume(const COBJECT *o)
{
    const mesh_t *m = mesh_get(o);
    double v = 0;
    const real *c = m->p[0];
    for (int t = 0; t < m->ntris; t++) {
        double p[3][3];
        for (int k = 0; k < 3; k++)
            for (int a = 0; a < 3; a++)
                p[k][a] = (double)m->p[m->tri[t][k]][a] - (double)c[a];
        v += (p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) +
              p[0][1] * (p[1][2] * p[2][0] - p[1][0] * p[2][2]) +
              p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0])) / 6;
    }
    return v;
}

START_TEST(generators_make_the_triangle_counts_they_promise)
{
    COBJECT *s = sphere(16, 8), *t = torus(12, 6), *h;
    ck_assert_int_eq(s->nprims, 2 * 16 * 7);
    ck_assert_int_eq(t->nprims, 2 * 12 * 6);
    svet_error e;
    VECTOR3 c = { 0, 0, 0 };
    ck_assert(meshgen_terrain(&h, c, 10, 1, 20, 7, &e) == SVET_OK);
    ck_assert_int_eq(h->nprims, 2 * 20 * 20);
    /* terrain heights stay within +-height, over the square */
    bbox_t b;
    h->ops->bounds(h, -1, &b);
    ck_assert(b.min[Z] >= -1 && b.max[Z] <= 1);
    ck_assert_near(b.max[X] - b.min[X], 10, 1e-5);
    cobject_free(h);
    long asked[] = { 12, 100, 1000, 8000, 80000 };
    for (int i = 0; i < 5; i++) {
        int nu, nv;
        meshgen_sphere_segments(asked[i], &nu, &nv);
        long got = 2L * nu * (nv - 1);
        /* the nearest of the counts 4 v (v - 1): within 4 v of the ask */
        ck_assert_msg(labs(got - asked[i]) <= 4L * nv + 12,
                      "asked %ld, got %ld", asked[i], got);
    }
    meshgen_scene_t sc;
    ck_assert(meshgen_sphere_grid(&sc, 5, 100000, &e) == SVET_OK);
    ck_assert_int_eq(sc.nobjs, 125);
    /* 800 per sphere: the nearest 4 v (v - 1) is 840 (v = 15) */
    ck_assert_int_eq(sc.ntris, 125 * 840);
    meshgen_free_objects(&sc);
    ck_assert(meshgen_teapot_stadium(&sc, 10000, &e) == SVET_OK);
    ck_assert_int_eq(sc.nobjs, 3);
    ck_assert_int_eq(sc.objs[1]->nprims, 2);
    ck_assert_int_eq(sc.objs[2]->nprims, 512);
    meshgen_free_objects(&sc);
    cobject_free(s);
    cobject_free(t);
}
END_TEST

START_TEST(spheres_and_tori_are_closed_and_wound_outward)
{
    for (int k = 0; k < 3; k++) {
        COBJECT *s = sphere(6 + 10 * k, 3 + 5 * k);
        COBJECT *t = torus(5 + 12 * k, 3 + 4 * k);
        check_closed(s);
        check_closed(t);
        /* polyhedra inscribed in the solids: smaller, but positive and
         * approaching 4/3 pi r^3 and 2 pi^2 R r^2 (an inscribed n-gon
         * keeps n sin(2 pi/n) / (2 pi) of a circle's area: 0.95 for the
         * torus's 11-gon tube, 0.99 for its 29 segments) */
        double vs = volume(s), vt = volume(t);
        const double pi = 3.14159265358979323846;
        double Vs = 4.0 / 3.0 * pi * 8, Vt = 2 * pi * pi * 3;
        ck_assert(vs > 0 && vs < Vs && vt > 0 && vt < Vt);
        if (k == 2) {
            ck_assert_msg(vs > 0.97 * Vs, "sphere volume %g of %g", vs, Vs);
            ck_assert_msg(vt > 0.93 * Vt, "torus volume %g of %g", vt, Vt);
        }
        cobject_free(s);
        cobject_free(t);
    }
}
END_TEST

/* The watertight test lets no ray out of a closed mesh: from points
 * inside, every direction hits, including rays aimed exactly at
 * vertices (where up to 2 nu triangles meet, at the poles) and at edge
 * midpoints. */
START_TEST(rays_from_inside_closed_meshes_always_hit)
{
    COBJECT *objs[2] = { sphere(40, 20), torus(48, 24) };
    pcg32_t g;
    pcg32_seed(&g, 21, 22);
    long cases = 0;
    for (int j = 0; j < 2; j++) {
        const COBJECT *o = objs[j];
        const mesh_t *m = mesh_get(o);
        for (int i = 0; i < 20000; i++) {
            ray_t r;
            /* inside: the sphere's centre region; the torus's tube core */
            if (j == 0) {
                VECTOR3 c = { 1, 2, 3 };
                geomcheck_random_dir(r.o, &g);
                vec_add_scaled(r.o, c, REAL_C(1.5) * pcg32_real(&g), r.o);
            } else {
                real phi = 2 * REAL_PI * pcg32_real(&g);
                VECTOR3 q = { 3 * cos(phi) - 1, 3 * sin(phi), REAL_C(0.5) };
                VECTOR3 w;
                geomcheck_random_dir(w, &g);
                vec_add_scaled(r.o, q, REAL_C(0.5) * pcg32_real(&g), w);
            }
            int v = (int)pcg32_bounded(&g, (uint32_t)m->nverts);
            if (i % 3 == 0) {
                vec_sub(r.d, m->p[v], r.o); /* at a vertex */
            } else if (i % 3 == 1) {
                int t = (int)pcg32_bounded(&g, (uint32_t)m->ntris);
                VECTOR3 mid;
                vec_add(mid, m->p[m->tri[t][0]], m->p[m->tri[t][1]]);
                vec_scale(mid, mid, REAL_C(0.5));
                vec_sub(r.d, mid, r.o); /* at an edge */
            } else {
                geomcheck_random_dir(r.d, &g);
            }
            hit_t h;
            ck_assert_msg(cobject_intersect(o, &r, 0, (real)INFINITY, &h),
                          "%s: ray %d from inside escapes", j ? "torus"
                                                               : "sphere", i);
            cases++;
        }
    }
    test_report_cases("rays_from_inside_closed_meshes_always_hit", cases);
    cobject_free(objs[0]);
    cobject_free(objs[1]);
}
END_TEST

START_TEST(generators_reject_bad_sizes)
{
    COBJECT *o;
    svet_error e;
    VECTOR3 c = { 0, 0, 0 }, bad = { (real)NAN, 0, 0 };
    ck_assert_int_eq(meshgen_uv_sphere(&o, c, 0, 8, 4, &e), SVET_ERR_RANGE);
    ck_assert_int_eq(meshgen_uv_sphere(&o, c, 1, 2, 4, &e), SVET_ERR_RANGE);
    ck_assert_int_eq(meshgen_uv_sphere(&o, bad, 1, 8, 4, &e), SVET_ERR_RANGE);
    ck_assert_int_eq(meshgen_torus(&o, c, 1, 2, 8, 8, &e), SVET_ERR_RANGE);
    ck_assert_int_eq(meshgen_terrain(&o, c, -1, 1, 8, 1, &e), SVET_ERR_RANGE);
    ck_assert_int_eq(meshgen_terrain(&o, c, 1, (real)INFINITY, 8, 1, &e),
                     SVET_ERR_RANGE);
    meshgen_scene_t s;
    ck_assert_int_eq(meshgen_sphere_grid(&s, 0, 100, &e), SVET_ERR_RANGE);
    ck_assert_ptr_null(s.objs);
    ck_assert(strstr(e.msg, "meshgen_sphere_grid") != NULL);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("meshgen");
    TCase *tc = tcase_create("meshgen");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, generators_make_the_triangle_counts_they_promise);
    tcase_add_test(tc, spheres_and_tori_are_closed_and_wound_outward);
    tcase_add_test(tc, rays_from_inside_closed_meshes_always_hit);
    tcase_add_test(tc, generators_reject_bad_sizes);
    suite_add_tcase(s, tc);
    return s;
}
