/*
 * test_primset.c - the flat primitive list of ch. 7's structures: its
 * numbering (mesh triangles in Morton order, then bounded objects, then
 * unbounded ones; degenerate triangles left out), the corners it copies,
 * the tie-break that makes every structure's answer the same, and the
 * mailbox that tests a primitive once per ray.
 */
#include "testutil.h"
#include "accel/accel.h"
#include "accel/grid.h"
#include "mesh/mesh.h"
#include "mesh/meshgen.h"
#include "geometry/plane.h"
#include "accel/primset.h"
#include "geometry/sphere.h"

#include <stdlib.h>
#include <string.h>

START_TEST(primitives_are_numbered_triangles_bounded_unbounded)
{
    svet_error e;
    COBJECT *objs[5];
    VECTOR3 c = { 0, 0, 0 }, n = { 0, 0, 1 }, p = { 0, 0, -5 };
    objs[0] = sphere_new(c, 1, &e);
    ck_assert(meshgen_uv_sphere(&objs[1], c, 2, 8, 4, &e) == SVET_OK);
    objs[2] = plane_new(p, n, &e);
    ck_assert(meshgen_torus(&objs[3], c, 3, 1, 8, 4, &e) == SVET_OK);
    objs[4] = NULL;
    primset_t ps;
    ck_assert(primset_build(&ps, objs, 5, &e) == SVET_OK);
    uint32_t nt = (uint32_t)(objs[1]->nprims + objs[3]->nprims);
    ck_assert_uint_eq(ps.ntri, nt);
    ck_assert_uint_eq(ps.nbounded, nt + 1);
    ck_assert_uint_eq(ps.nrefs, nt + 2);
    ck_assert_uint_eq(ps.refs[nt].obj, 0);       /* the sphere */
    ck_assert_uint_eq(ps.refs[nt + 1].obj, 2);   /* the plane, last */
    /* each triangle once, with its mesh's corners */
    char *seen = calloc(nt, 1);
    for (uint32_t i = 0; i < nt; i++) {
        primref_t r = ps.refs[i];
        ck_assert(r.obj == 1 || r.obj == 3);
        const mesh_t *m = mesh_get(objs[r.obj]);
        real q[9];
        mesh_triangle_corners(m, (int)r.prim, q);
        ck_assert(memcmp(q, ps.tri[i], sizeof q) == 0);
        uint32_t id = r.obj == 1 ? r.prim : (uint32_t)objs[1]->nprims + r.prim;
        ck_assert(!seen[id]);
        seen[id] = 1;
    }
    free(seen);
    /* Morton order: neighbours in the list are near in space: the mean
     * step between successive centroids is well below the mean distance
     * between scattered pairs (i and 7919 i mod n) */
    double step = 0, scattered = 0;
    for (uint32_t i = 1; i < nt; i++) {
        VECTOR3 ca, cb, cc;
        bbox_centroid(ca, &ps.bounds[i - 1]);
        bbox_centroid(cb, &ps.bounds[i]);
        bbox_centroid(cc, &ps.bounds[(7919 * (uint64_t)i) % nt]);
        step += (double)vec_distance(ca, cb);
        scattered += (double)vec_distance(cb, cc);
    }
    ck_assert_msg(step < 0.4 * scattered, "mean step %g, scattered %g",
                  step / (nt - 1), scattered / (nt - 1));
    ck_assert(ps.pad > 0 && ps.pad < 1e-4);
    primset_free(&ps);
    for (int i = 0; i < 4; i++)
        cobject_free(objs[i]);
}
END_TEST

/* Two meshes with the same triangle, and a mesh holding one triangle
 * twice: the hit is always the first object's, then its first
 * triangle's, whichever structure answers. */
START_TEST(ties_go_to_the_first_object_and_primitive)
{
    svet_error e;
    COBJECT *objs[3];
    for (int i = 0; i < 3; i++) {
        mesh_t m = { 0 };
        m.nverts = 3;
        m.ntris = 2;
        m.p = calloc(3, sizeof *m.p);
        m.tri = calloc(2, sizeof *m.tri);
        vec_set(m.p[1], 1, 0, 0);
        vec_set(m.p[2], 0, 1, 0);
        for (int t = 0; t < 2; t++)
            for (int k = 0; k < 3; k++)
                m.tri[t][k] = k;
        ck_assert(mesh_new(&objs[i], &m, &e) == SVET_OK);
    }
    /* and many small spheres so that the grids have cells to walk */
    ray_t r = { { REAL_C(0.25), REAL_C(0.25), 3 }, { 0, 0, -1 } };
    for (int k = ACCEL_BRUTE; k <= ACCEL_HGRID; k++) {
        accel_params_t p;
        accel_params_default(&p);
        p.structures = grid_accels;
        p.kind = (accel_kind)k;
        accel_t *a;
        ck_assert(accel_build(&a, objs + 1, 2, &p, &e) == SVET_OK);
        accel_hit_t h;
        ck_assert(accel_intersect(a, &r, 0, (real)INFINITY, &h));
        ck_assert_ptr_eq(h.obj, objs[1]);
        ck_assert_int_eq(h.hit.prim, 0);
        accel_free(a);
        /* the other order: objs[0] first now */
        COBJECT *rev[2] = { objs[2], objs[0] };
        ck_assert(accel_build(&a, rev, 2, &p, &e) == SVET_OK);
        ck_assert(accel_intersect(a, &r, 0, (real)INFINITY, &h));
        ck_assert_ptr_eq(h.obj, objs[2]);
        ck_assert_int_eq(h.hit.prim, 0);
        accel_free(a);
    }
    for (int i = 0; i < 3; i++)
        cobject_free(objs[i]);
}
END_TEST

/* A triangle spanning many cells along a grazing ray is tested once. */
START_TEST(a_primitive_is_tested_once_per_ray)
{
    svet_error e;
    mesh_t m = { 0 };
    m.nverts = 3;
    m.ntris = 1;
    m.p = calloc(3, sizeof *m.p);
    m.tri = calloc(1, sizeof *m.tri);
    /* in the plane z = 0; the ray runs just above it, in its cells */
    vec_set(m.p[0], 0, 0, 0);
    vec_set(m.p[1], 100, 0, 0);
    vec_set(m.p[2], 0, 100, 0);
    for (int k = 0; k < 3; k++)
        m.tri[0][k] = k;
    COBJECT *objs[41];
    ck_assert(mesh_new(&objs[0], &m, &e) == SVET_OK);
    for (int i = 1; i <= 40; i++) { /* small things to make cells */
        VECTOR3 c = { (real)(2 * i), (real)(i % 7), 10 };
        objs[i] = sphere_new(c, REAL_C(0.5), &e);
    }
    accel_params_t p;
    accel_params_default(&p);
    p.structures = grid_accels;
    p.kind = ACCEL_GRID;
    p.grid_k = 4;
    accel_t *a;
    ck_assert(accel_build(&a, objs, 41, &p, &e) == SVET_OK);
    ray_t r = { { -1, REAL_C(0.5), REAL_C(0.0001) }, { 1, 0, 0 } };
    accel_counters_t cnt = { 0, 0 };
    accel_hit_t h;
    accel_intersect_counted(a, &r, 0, (real)INFINITY, &h, &cnt);
    ck_assert_int_gt(cnt.cells, 20);
    ck_assert_int_eq(cnt.tests, 1);
    accel_free(a);
    for (int i = 0; i <= 40; i++)
        cobject_free(objs[i]);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("primset");
    TCase *tc = tcase_create("primset");
    tcase_add_test(tc, primitives_are_numbered_triangles_bounded_unbounded);
    tcase_add_test(tc, ties_go_to_the_first_object_and_primitive);
    tcase_add_test(tc, a_primitive_is_tested_once_per_ray);
    suite_add_tcase(s, tc);
    return s;
}
