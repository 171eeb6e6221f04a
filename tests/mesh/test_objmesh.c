/*
 * test_objmesh.c - the `mesh` statement's OBJ loader (objmesh.h): one
 * part per usemtl name with faces, in the file's order, the whole mesh
 * when there is one; vertices moved by the transform and the winding
 * reversed by a mirror; the reader's errors passed on with the OBJ file's
 * line and column. (The statement itself: tests/render/test_scenefile.c.)
 */
#include "testutil.h"
#include "mesh/mesh.h"
#include "mesh/objmesh.h"

#include <string.h>

#define DATA "tests/data/scene/"

START_TEST(parts_follow_the_usemtl_names_in_file_order)
{
    scene_mesh_part_t *p;
    int n;
    svet_error err;
    ck_assert_int_eq(objmesh_load(DATA "tri.obj", NULL, &p, &n, NULL, &err),
                     SVET_OK);
    ck_assert_int_eq(n, 2);
    ck_assert_str_eq(p[0].material, "red");
    ck_assert_str_eq(p[1].material, "blue");
    for (int i = 0; i < 2; i++) {
        ck_assert_ptr_nonnull(mesh_get(p[i].obj));
        ck_assert_int_eq(p[i].obj->nprims, 1);
    }
    scene_mesh_parts_free(p, n);
    /* no usemtl: one part, no name, the whole mesh */
    ck_assert_int_eq(objmesh_load(DATA "quad.obj", NULL, &p, &n, NULL, &err),
                     SVET_OK);
    ck_assert_int_eq(n, 1);
    ck_assert_ptr_null(p[0].material);
    ck_assert_int_eq(p[0].obj->nprims, 2);
    scene_mesh_parts_free(p, n);
    scene_mesh_parts_free(NULL, 0);
}
END_TEST

START_TEST(a_mirror_moves_the_vertices_and_reverses_the_winding)
{
    VECTOR3 f = { -1, 2, 1 };
    xform_t x = xform_scale(f);
    scene_mesh_part_t *p;
    int n;
    svet_error err;
    ck_assert_int_eq(objmesh_load(DATA "tri.obj", &x, &p, &n, NULL, &err),
                     SVET_OK);
    ck_assert_int_eq(n, 2);
    /* f 1 2 3 of (0 0 0) (1 0 0) (0 1 0) becomes (0 0 0) (0 2 0) (-1 0 0) */
    const mesh_t *m = mesh_get(p[0].obj);
    ck_assert_int_eq(m->ntris, 1);
    const real want[3][3] = { { 0, 0, 0 }, { 0, 2, 0 }, { -1, 0, 0 } };
    for (int k = 0; k < 3; k++)
        for (int a = 0; a < 3; a++)
            ck_assert_near(m->p[m->tri[0][k]][a], want[k][a], 0);
    /* the normal (0 0 1) stays (0 0 1) under the mirror in x */
    ck_assert_ptr_nonnull(m->n);
    ck_assert_near(m->n[m->tri[0][0]][Z], 1, 1e-6);
    scene_mesh_parts_free(p, n);
}
END_TEST

START_TEST(reader_errors_name_the_obj_file_line_and_column)
{
    scene_mesh_part_t dummy, *p = &dummy; /* must become NULL */
    int n = 7;
    svet_error err;
    ck_assert_int_eq(objmesh_load(DATA "bad.obj", NULL, &p, &n, NULL, &err),
                     SVET_ERR_RANGE);
    ck_assert_str_eq(err.msg, DATA "bad.obj:5:7: vertex index 9 out of "
                              "range: 3 defined so far");
    ck_assert_ptr_null(p);
    ck_assert_int_eq(n, 0);
    ck_assert_int_eq(objmesh_load(DATA "missing.obj", NULL, &p, &n, NULL,
                                  &err),
                     SVET_ERR_IO);
    ck_assert(strncmp(err.msg, DATA "missing.obj", strlen(DATA) + 11) == 0);
}
END_TEST

START_TEST(reader_warnings_are_handed_to_the_caller_and_counted)
{
    /* Without them a skipped "vv" or "ff" went unseen. */
    scene_mesh_part_t *p;
    int n;
    svet_error err;
    scene_warnings_t w;
    w.n = 0;
    ck_assert_int_eq(objmesh_load(DATA "warn.obj", NULL, &p, &n, &w, &err),
                     SVET_OK);
    scene_mesh_parts_free(p, n);
    /* vv, ff, l and x1 .. x8: OBJ_MAX_WARNINGS kept, every one counted */
    ck_assert_int_eq(w.n, 11);
    ck_assert_str_eq(w.msg[0], DATA "warn.obj:4:1: warning: unknown "
                               "statement 'vv' skipped");
    ck_assert_str_eq(w.msg[1], DATA "warn.obj:7:1: warning: unknown "
                               "statement 'ff' skipped");
    ck_assert_str_eq(w.msg[7], DATA "warn.obj:14:1: warning: unknown "
                               "statement 'x5' skipped");
    /* added to what the caller holds already */
    ck_assert_int_eq(objmesh_load(DATA "warn.obj", NULL, &p, &n, &w, &err),
                     SVET_OK);
    scene_mesh_parts_free(p, n);
    ck_assert_int_eq(w.n, 22);
    /* a file without warnings adds none */
    w.n = 0;
    ck_assert_int_eq(objmesh_load(DATA "tri.obj", NULL, &p, &n, &w, &err),
                     SVET_OK);
    scene_mesh_parts_free(p, n);
    ck_assert_int_eq(w.n, 0);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("objmesh");
    TCase *tc = tcase_create("objmesh");
    tcase_add_test(tc, parts_follow_the_usemtl_names_in_file_order);
    tcase_add_test(tc, a_mirror_moves_the_vertices_and_reverses_the_winding);
    tcase_add_test(tc, reader_errors_name_the_obj_file_line_and_column);
    tcase_add_test(tc, reader_warnings_are_handed_to_the_caller_and_counted);
    suite_add_tcase(s, tc);
    return s;
}
