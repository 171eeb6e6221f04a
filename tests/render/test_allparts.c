/*
 * test_allparts.c - the list of every optional part (allparts.h): it
 * offers the acceleration layer of ch. 7 with the batched brute force and
 * both grids, in the order of their kinds, and the OBJ loader, so that a
 * scene read with it may use `mesh` and every `accel`.
 * (Without it: tests/render/test_scenefile.c, test_render.c, test_accel.c.)
 */
#include "testutil.h"
#include "accel/accel.h"
#include "accel/batch.h"
#include "render/allparts.h"
#include "accel/grid.h"
#include "mesh/objmesh.h"
#include "render/render.h"
#include "render/scenefile.h"

#include <string.h>

START_TEST(all_parts_offer_every_structure_and_the_obj_loader)
{
    const scene_features_t *f = scene_features_all();
    ck_assert_ptr_nonnull(f);
    ck_assert(f == scene_features_all());
    ck_assert(f->mesh == objmesh_load);
    ck_assert(f->accel == &accel_layer);
    int n = 0;
    while (f->accels[n])
        n++;
    ck_assert_int_eq(n, 3);
    ck_assert(accel_offered(f->accels, ACCEL_BRUTE) == &batch_accel);
    ck_assert(accel_offered(f->accels, ACCEL_GRID) == &grid_uniform_accel);
    ck_assert(accel_offered(f->accels, ACCEL_HGRID) ==
              &grid_hierarchical_accel);
    ck_assert(accel_offered(NULL, ACCEL_GRID) == NULL);
    /* in the order of their kinds */
    for (int i = 0; i < n; i++)
        ck_assert_int_eq(f->accels[i]->kind, ACCEL_BRUTE + i);
    /* every table is complete: accel.c calls them without checking; a
     * structure answers whole queries or those over the bounded
     * primitives, and AUTO asks the grids how crowded they are */
    for (int i = 0; i < n; i++) {
        const accel_ops_t *o = f->accels[i];
        ck_assert(o->build && o->free && o->stats);
        ck_assert((o->tracer_intersect && o->tracer_occluded) ||
                  (o->intersect && o->occluded));
        if (o->kind != ACCEL_BRUTE)
            ck_assert(o->crowded && o->intersect && o->occluded);
    }
    /* the layer's table is complete */
    const accel_layer_t *L = f->accel;
    ck_assert(L->build == accel_build && L->free == accel_free &&
              L->tracer == accel_tracer && L->has_packets == accel_has_packets &&
              L->intersect_packet == accel_tracer_intersect_packet &&
              L->describe == accel_describe);
}
END_TEST

/* The mesh scene renders with every accel the parts offer, each the same
 * image, and says which structure it used. */
START_TEST(a_mesh_scene_renders_alike_with_every_accel_offered)
{
    static const char *const kinds[] = { "accel=brute", "accel=grid",
                                         "accel=hgrid", "accel=auto" };
    static const char *const said[] = { "brute", "grid", "hgrid",
                                        "brute (auto: 4 primitives" };
    double *first = NULL;
    size_t n = 0;
    for (int k = 0; k < 4; k++) {
        scene_t s;
        svet_error err;
        ck_assert_msg(scenefile_read_with(&s, "tests/data/scene/mesh.scn",
                                          scene_features_all(), &err) ==
                          SVET_OK,
                      "%s", err.msg);
        ck_assert_msg(scenefile_override(&s, kinds[k], &err) == SVET_OK,
                      "%s", err.msg);
        ck_assert_int_eq(scenefile_override(&s, "resolution=24x16", &err),
                         SVET_OK);
        render_t r;
        ck_assert_int_eq(render_init(&r, &s, &err), SVET_OK);
        ck_assert_msg(strncmp(r.accel_choice, said[k], strlen(said[k])) == 0,
                      "%s", r.accel_choice);
        render_pass(&r, 2, 1, NULL, NULL);
        n = 3 * (size_t)s.camera.width * (size_t)s.camera.height;
        if (!first) {
            first = malloc(n * sizeof *first);
            ck_assert_ptr_nonnull(first);
            memcpy(first, r.acc.sum, n * sizeof *first);
        } else {
            ck_assert(memcmp(first, r.acc.sum, n * sizeof *first) == 0);
        }
        render_free(&r);
        scene_free(&s);
    }
    free(first);
    test_report_cases("a_mesh_scene_renders_alike_with_every_accel_offered",
                      4);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("allparts");
    TCase *tc = tcase_create("allparts");
    tcase_add_test(tc, all_parts_offer_every_structure_and_the_obj_loader);
    tcase_add_test(tc, a_mesh_scene_renders_alike_with_every_accel_offered);
    suite_add_tcase(s, tc);
    return s;
}
