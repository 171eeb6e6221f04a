/*
 * test_batch.c - the batched brute force as a structure (batch.h): it
 * takes scenes of analytic primitives and refuses mesh triangles, answers
 * the Cornell box's rays, bad ones included, as brute force through
 * primset_test() does, bit for bit, and says how much memory it holds.
 * (Its answers on random scenes, skips and culling spheres:
 * tests/accel/test_accel.c; against ch. 5's list:
 * tests/render/test_tracer.c.)
 */
#include "testutil.h"
#include "accel/accel.h"
#include "accel/batch.h"
#include "geomcheck.h"
#include "mesh/meshgen.h"
#include "render/scenefile.h"

#include <string.h>

START_TEST(the_batch_refuses_mesh_triangles)
{
    COBJECT *m;
    VECTOR3 c = { 0, 0, 0 };
    ck_assert_int_eq(meshgen_uv_sphere(&m, c, 1, 8, 4, NULL), SVET_OK);
    primset_t ps;
    svet_error e;
    ck_assert_int_eq(primset_build(&ps, &m, 1, &e), SVET_OK);
    void *s = &ps;
    ck_assert_int_eq(batch_accel.build(&s, &ps, NULL, &e),
                     SVET_ERR_UNSUPPORTED);
    ck_assert(s == NULL);
    batch_accel.free(NULL);
    primset_free(&ps);
    cobject_free(m);
    ck_assert_int_eq(batch_accel.kind, ACCEL_BRUTE);
}
END_TEST

START_TEST(the_batch_answers_the_cornell_box_as_primset_test)
{
    scene_t sc;
    svet_error e;
    ck_assert_msg(scenefile_read(&sc, "scenes/cbox.scn", &e) == SVET_OK, "%s",
                  e.msg);
    primset_t ps;
    void *b;
    ck_assert_int_eq(primset_build(&ps, sc.objects, sc.nobjects, &e), SVET_OK);
#ifndef SVET_SIMD
    /* the plain build has no batch, and says so */
    ck_assert_int_eq(batch_accel.build(&b, &ps, NULL, &e),
                     SVET_ERR_UNSUPPORTED);
    ck_assert_ptr_nonnull(strstr(e.msg, "speed layer"));
    primset_free(&ps);
    scene_free(&sc);
    return;
#endif
    ck_assert_int_eq(batch_accel.build(&b, &ps, NULL, &e), SVET_OK);
    accel_stats_t st;
    memset(&st, 0, sizeof st);
    batch_accel.stats(b, &st);
    ck_assert(st.bytes > 0);
    accel_params_t p;
    accel_params_default(&p);
    p.kind = ACCEL_BRUTE;
    accel_t *a;
    ck_assert_int_eq(accel_build(&a, sc.objects, sc.nobjects, &p, &e), SVET_OK);
    pcg32_t g;
    pcg32_seed(&g, 11, 2);
    long hits = 0, n = 20000;
    for (long i = 0; i < n; i++) {
        ray_t r;
        for (int k = 0; k < 3; k++)
            r.o[k] = -REAL_C(1.2) + REAL_C(2.4) * pcg32_real(&g); /* the box spans -1 to 1 */
        geomcheck_random_dir(r.d, &g);
        if (i % 100 == 99)
            r.o[i % 3] = (real)NAN;
        real tmax = i % 3 == 0 ? 2 * pcg32_real(&g) : (real)INFINITY;
        hit_t hb, hg;
        const COBJECT *ob = NULL, *og = NULL;
        memset(&hb, 0x33, sizeof hb);
        memset(&hg, 0x33, sizeof hg);
        bool fb = batch_accel.tracer_intersect(b, &r, 0, tmax, NULL, &hb, &ob);
        bool fg = accel_tracer_intersect(a, &r, 0, tmax, NULL, &hg, &og);
        ck_assert_int_eq(fb, fg);
        ck_assert_int_eq(batch_accel.tracer_occluded(b, &r, 0, tmax, NULL), fg);
        if (fb) {
            ck_assert_ptr_eq(ob, og);
            ck_assert_int_eq(hb.prim, hg.prim);
            ck_assert(memcmp(&hb.t, &hg.t, sizeof hb.t) == 0);
            ck_assert(memcmp(hb.b, hg.b, sizeof hb.b) == 0);
            hits++;
        }
    }
    ck_assert_msg(hits > n / 4, "%ld hits", hits);
    test_report_cases("the_batch_answers_the_cornell_box_as_primset_test", n);
    accel_free(a);
    batch_accel.free(b);
    primset_free(&ps);
    scene_free(&sc);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("batch");
    TCase *tc = tcase_create("batch");
    tcase_add_test(tc, the_batch_refuses_mesh_triangles);
    tcase_add_test(tc, the_batch_answers_the_cornell_box_as_primset_test);
    suite_add_tcase(s, tc);
    return s;
}
