/*
 * test_obj.c - the Wavefront OBJ reader (ch. 7): exact contents of small
 * files (every face form, negative indices, fanning, groups, materials,
 * continuations, \r\n), warnings, and every error message checked for its
 * file:line:col; the fuzzer's crash inputs (tests/data/obj/crash-*) kept
 * as regressions.
 */
#include "testutil.h"
#include "mesh/mesh.h"
#include "mesh/obj.h"

#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const mesh_t *parse_ok(const char *text, obj_t *o)
{
    svet_error e;
    svet_status st = obj_parse("t.obj", text, strlen(text), NULL, o, &e);
    ck_assert_msg(st == SVET_OK, "unexpected error: %s", e.msg);
    const mesh_t *m = mesh_get(o->mesh);
    ck_assert_ptr_nonnull(m);
    return m;
}

/* Position of mesh vertex v equals (x, y, z) exactly. */
static void check_p(const mesh_t *m, int v, real x, real y, real z)
{
    ck_assert_msg(m->p[v][X] == x && m->p[v][Y] == y && m->p[v][Z] == z,
                  "vertex %d = (%g %g %g), want (%g %g %g)", v,
                  (double)m->p[v][X], (double)m->p[v][Y], (double)m->p[v][Z],
                  (double)x, (double)y, (double)z);
}

static void check_tri(const mesh_t *m, int t, int a, int b, int c)
{
    ck_assert_msg(m->tri[t][0] == a && m->tri[t][1] == b && m->tri[t][2] == c,
                  "triangle %d = (%d %d %d), want (%d %d %d)", t,
                  (int)m->tri[t][0], (int)m->tri[t][1], (int)m->tri[t][2], a,
                  b, c);
}

START_TEST(obj_reads_every_face_form_exactly)
{
    obj_t o;
    const mesh_t *m = parse_ok("v 0 0 0\n"
                               "v 1 0 0\n"
                               "v 0 1 0\n"
                               "v 1 1 0.5\n"
                               "vt 0.25 0.75\n"
                               "vt 1\n"
                               "vn 0 0 2\n"
                               "f 1 2 3\n"
                               "f 1/1 2/2 4/1\n"
                               "f 2//1 4//1 3//1\n"
                               "f 4/2/1 3/1/1 2/2/1\n",
                               &o);
    ck_assert_int_eq(m->ntris, 4);
    /* distinct (v, vt, vn) triples, in order of first use */
    ck_assert_int_eq(m->nverts, 3 + 3 + 3 + 3);
    check_p(m, 0, 0, 0, 0);
    check_p(m, 5, 1, 1, REAL_C(0.5));
    check_tri(m, 0, 0, 1, 2);
    check_tri(m, 1, 3, 4, 5);
    check_tri(m, 2, 6, 7, 8);
    check_tri(m, 3, 9, 10, 11);
    ck_assert_ptr_nonnull(m->n);
    ck_assert_ptr_nonnull(m->st);
    /* vertex 3 is "1/1": st (0.25, 0.75), no normal */
    ck_assert(m->st[3][0] == REAL_C(0.25) && m->st[3][1] == REAL_C(0.75));
    ck_assert(m->n[3][X] == 0 && m->n[3][Y] == 0 && m->n[3][Z] == 0);
    /* vertex 4 is "2/2": "vt 1" has t = 0 */
    ck_assert(m->st[4][0] == 1 && m->st[4][1] == 0);
    /* vertex 6 is "2//1": the normal, normalised; st missing = NaN */
    ck_assert(m->n[6][Z] == 1);
    ck_assert(isnan(m->st[6][0]));
    /* vertex 9 is "4/2/1" */
    check_p(m, 9, 1, 1, REAL_C(0.5));
    ck_assert(m->st[9][0] == 1 && m->n[9][Z] == 1);
    ck_assert_ptr_null(m->slot);
    ck_assert_ptr_null(o.tri_group);
    ck_assert_int_eq(o.nwarnings, 0);
    obj_free(&o);
}
END_TEST

START_TEST(obj_counts_negative_indices_back_from_the_last)
{
    obj_t o;
    const mesh_t *m = parse_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"
                               "v 5 5 5\nf -1 -3 -2\n",
                               &o);
    ck_assert_int_eq(m->ntris, 2);
    check_tri(m, 0, 0, 1, 2);
    /* -1 is now vertex 4 (5 5 5), -3 vertex 2, -2 vertex 3 */
    check_p(m, m->tri[1][0], 5, 5, 5);
    check_p(m, m->tri[1][1], 1, 0, 0);
    check_p(m, m->tri[1][2], 0, 1, 0);
    obj_free(&o);
}
END_TEST

START_TEST(obj_fans_polygons_into_triangles)
{
    obj_t o;
    const mesh_t *m = parse_ok("v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\n"
                               "f 1 2 3 4 5\nf 1 2 3 4\n",
                               &o);
    ck_assert_int_eq(m->ntris, 5);
    check_tri(m, 0, 0, 1, 2);
    check_tri(m, 1, 0, 2, 3);
    check_tri(m, 2, 0, 3, 4);
    check_tri(m, 3, 0, 1, 2);
    check_tri(m, 4, 0, 2, 3);
    obj_free(&o);
}
END_TEST

/* The cube file: groups and usemtl per triangle, mtllib and s skipped. */
START_TEST(obj_records_groups_and_materials_per_triangle)
{
    obj_t o;
    svet_error e;
    ck_assert_msg(obj_read("tests/data/obj/cube.obj", NULL, &o, &e) ==
                      SVET_OK, "%s", e.msg);
    const mesh_t *m = mesh_get(o.mesh);
    ck_assert_int_eq(m->ntris, 12);
    ck_assert_int_eq(o.nmaterials, 2);
    ck_assert_str_eq(o.materials[0], "white");
    ck_assert_str_eq(o.materials[1], "red");
    ck_assert_int_eq(o.ngroups, 3);
    ck_assert_str_eq(o.groups[0], "cube");
    ck_assert_str_eq(o.groups[1], "bottom top");
    ck_assert_str_eq(o.groups[2], "sides");
    for (int t = 0; t < 12; t++) {
        ck_assert_int_eq(m->slot[t], t < 4 ? 0 : 1);
        ck_assert_int_eq(o.tri_group[t], t < 4 ? 1 : 2);
    }
    ck_assert_int_eq(o.nwarnings, 0);
    ck_assert_near(o.mesh->ops->area(o.mesh), 6, 1e-6);
    /* 6 faces x 4 corners, each a distinct (v, vt, vn) */
    ck_assert_int_eq(m->nverts, 24);
    obj_free(&o);
}
END_TEST

START_TEST(obj_reads_comments_crlf_and_continuations)
{
    obj_t o;
    const mesh_t *m = parse_ok("# comment\r\n"
                               "\r\n"
                               "   \t\r\n"
                               "v 1 2 3 # trailing comment\r\n"
                               "v 4 \\\r\n"
                               "  5 6\r\n"
                               "v 7 8 9 1.0\n"
                               "mtllib x.mtl\n"
                               "s 1\n"
                               "f 1 2 \\\n"
                               "3",
                               &o);
    ck_assert_int_eq(m->ntris, 1);
    check_p(m, m->tri[0][1], 4, 5, 6);
    check_p(m, m->tri[0][2], 7, 8, 9);
    obj_free(&o);
    svet_error e;
    ck_assert(obj_read("tests/data/obj/crlf.obj", NULL, &o, &e) == SVET_OK);
    ck_assert_int_eq(o.mesh->nprims, 1);
    obj_free(&o);
}
END_TEST

START_TEST(obj_warns_about_what_it_skips)
{
    obj_t o;
    parse_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\n"
             "l 1 2\n"
             "p 3\n"
             "  curv 0 1 2\n"
             "f 1 2 3\n",
             &o);
    ck_assert_int_eq(o.nwarnings, 3);
    ck_assert_str_eq(o.warnings[0], "t.obj:4:1: warning: 'l' skipped: lines "
                                    "and points have no surface");
    ck_assert_str_eq(o.warnings[1], "t.obj:5:1: warning: 'p' skipped: lines "
                                    "and points have no surface");
    ck_assert_str_eq(o.warnings[2], "t.obj:6:3: warning: unknown statement "
                                    "'curv' skipped");
    obj_free(&o);
}
END_TEST

START_TEST(obj_skips_a_byte_order_mark)
{
    /* Without the skip "\xEF\xBB\xBFv" was an unknown statement and the
     * first vertex was lost: "f 1 2 3" took the wrong corners. */
    obj_t o;
    const mesh_t *m = parse_ok("\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                               "v 0 0 1\nf 1 2 3\n", &o);
    ck_assert_int_eq(o.nwarnings, 0);
    ck_assert_int_eq(m->ntris, 1);
    check_p(m, 0, 0, 0, 0);
    check_p(m, 1, 1, 0, 0);
    check_p(m, 2, 0, 1, 0);
    obj_free(&o);
    /* columns of the first line count from the byte after it */
    svet_error e;
    const char *bad1 = "\xEF\xBB\xBFv 1 2\n";
    ck_assert_int_eq(obj_parse("t.obj", bad1, strlen(bad1), NULL, &o, &e),
                     SVET_ERR_PARSE);
    ck_assert_str_eq(e.msg, "t.obj:1:1: 'v' needs 3 numbers, got 2");
    /* only at the start: later it is a byte like any other */
    parse_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\n\xEF\xBB\xBFv 0 0 1\nf 1 2 3\n",
             &o);
    ck_assert_int_eq(o.nwarnings, 1);
    obj_free(&o);
}
END_TEST

/* Each malformed input: the status and the exact message. */
static const struct {
    const char *text;
    svet_status st;
    const char *msg;
} bad[] = {
    { "v 1 2\n", SVET_ERR_PARSE, "t.obj:1:1: 'v' needs 3 numbers, got 2" },
    { "v 1 2 3 4 5 6 7 8\n", SVET_ERR_PARSE,
      "t.obj:1:17: 'v' takes at most 7 numbers" },
    { "v 1 2 x\n", SVET_ERR_PARSE, "t.obj:1:7: expected a number, found 'x'" },
    { "v 1 2 nan\n", SVET_ERR_PARSE,
      "t.obj:1:7: expected a number, found 'nan'" },
    { "v 1 inf 2\n", SVET_ERR_PARSE,
      "t.obj:1:5: expected a number, found 'inf'" },
    { "v 1 2 0x1p3\n", SVET_ERR_PARSE,
      "t.obj:1:7: expected a number, found '0x1p3'" },
    { "v 1 2 1.5e\n", SVET_ERR_PARSE,
      "t.obj:1:7: expected a number, found '1.5e'" },
    { "\n\nv 1 2 1e999\n", SVET_ERR_RANGE,
      "t.obj:3:7: number '1e999' is out of range" },
    { "vn 1 2\n", SVET_ERR_PARSE, "t.obj:1:1: 'vn' needs 3 numbers, got 2" },
    { "vt\n", SVET_ERR_PARSE, "t.obj:1:1: 'vt' needs 1 numbers, got 0" },
    { "vt 1 2 3 4\n", SVET_ERR_PARSE,
      "t.obj:1:10: 'vt' takes at most 3 numbers" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", SVET_ERR_RANGE,
      "t.obj:4:7: vertex index 0 (OBJ indices start at 1)" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", SVET_ERR_RANGE,
      "t.obj:4:7: vertex index 4 out of range: 3 defined so far" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n", SVET_ERR_RANGE,
      "t.obj:4:3: vertex index -4 out of range: 3 defined so far" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", SVET_ERR_PARSE,
      "t.obj:4:1: a face needs at least 3 vertices, got 2" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/ 2 3\n", SVET_ERR_PARSE,
      "t.obj:4:5: malformed face vertex: nothing after '/'" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2/3/4 2 3\n", SVET_ERR_PARSE,
      "t.obj:4:8: malformed face vertex: more than two '/'" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1// 2 3\n", SVET_ERR_PARSE,
      "t.obj:4:6: malformed face vertex: no normal index after '/'" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2 3\n", SVET_ERR_RANGE,
      "t.obj:4:5: texture index 1 out of range: 0 defined so far" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//-1 2 3\n", SVET_ERR_RANGE,
      "t.obj:4:6: normal index -1 out of range: 0 defined so far" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2x 3\n", SVET_ERR_PARSE,
      "t.obj:4:6: malformed vertex index: unexpected 'x'" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf /1 2 3\n", SVET_ERR_PARSE,
      "t.obj:4:3: expected a vertex index" },
    { "usemtl\n", SVET_ERR_PARSE, "t.obj:1:1: 'usemtl' needs a name" },
    { "v 0 0 0\n", SVET_ERR_PARSE, "t.obj: no faces" },
    { "", SVET_ERR_PARSE, "t.obj: no faces" },
    /* a continued line reports the physical line of the token */
    { "v 1 \\\n 2 x\n", SVET_ERR_PARSE,
      "t.obj:2:4: expected a number, found 'x'" },
    { "v 1 2 3\r\nv 1 y 3\r\n", SVET_ERR_PARSE,
      "t.obj:2:5: expected a number, found 'y'" },
};

START_TEST(obj_names_file_line_and_column_of_every_error)
{
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        obj_t o;
        svet_error e;
        svet_status st = obj_parse("t.obj", bad[i].text, strlen(bad[i].text),
                                   NULL, &o, &e);
        ck_assert_msg(st == bad[i].st, "case %zu: status %d, want %d (%s)", i,
                      st, bad[i].st, e.msg);
        ck_assert_msg(strcmp(e.msg, bad[i].msg) == 0,
                      "case %zu: message\n  '%s'\nwant\n  '%s'", i, e.msg,
                      bad[i].msg);
        ck_assert_ptr_null(o.mesh);
        obj_free(&o);
    }
    test_report_cases("obj_names_file_line_and_column_of_every_error",
                      (long)(sizeof bad / sizeof bad[0]));
}
END_TEST

START_TEST(obj_reports_files_it_cannot_read_and_limits)
{
    obj_t o;
    svet_error e;
    ck_assert_int_eq(obj_read("tests/data/obj/no-such.obj", NULL, &o, &e),
                     SVET_ERR_IO);
    ck_assert(strncmp(e.msg, "tests/data/obj/no-such.obj: cannot open", 39) ==
              0);
    ck_assert_int_eq(obj_read("tests/data/obj/bad-index.obj", NULL, &o, &e),
                     SVET_ERR_RANGE);
    ck_assert_str_eq(e.msg, "tests/data/obj/bad-index.obj:5:2: vertex index "
                            "4 out of range: 3 defined so far");
    obj_limits_t lim;
    obj_limits_default(&lim);
    lim.max_triangles = 2;
    const char *quad5 = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 2 0\n"
                        "f 1 2 3 4 5\n";
    ck_assert_int_eq(obj_parse("t.obj", quad5, strlen(quad5), &lim, &o, &e),
                     SVET_ERR_RANGE);
    ck_assert_str_eq(e.msg, "t.obj:6:11: more than 2 triangles (the limit)");
    obj_limits_default(&lim);
    lim.max_elements = 4;
    ck_assert_int_eq(obj_parse("t.obj", quad5, strlen(quad5), &lim, &o, &e),
                     SVET_ERR_RANGE);
    ck_assert_str_eq(e.msg, "t.obj:5:1: more than 4 v/vt/vn elements (the "
                            "limit)");
    obj_limits_default(&lim);
    lim.max_vertices = 3;
    ck_assert_int_eq(obj_parse("t.obj", quad5, strlen(quad5), &lim, &o, &e),
                     SVET_ERR_RANGE);
    ck_assert_str_eq(e.msg, "t.obj:6:9: more than 3 distinct face vertices "
                            "(the limit)");
    /* NUL bytes are blanks, not the end of the text */
    const char nul[] = "v 0 0 0\nv 1\0 0 0\nv 0 1 0\nf 1 2 3\n";
    ck_assert_int_eq(obj_parse("t.obj", nul, sizeof nul - 1, NULL, &o, &e),
                     SVET_OK);
    obj_free(&o);
}
END_TEST

/* Every input the fuzzer once crashed on must now parse or fail cleanly. */
START_TEST(obj_survives_every_input_the_fuzzer_found)
{
    DIR *d = opendir("tests/data/obj");
    ck_assert_ptr_nonnull(d);
    struct dirent *de;
    long n = 0;
    while ((de = readdir(d)) != NULL) {
        if (strncmp(de->d_name, "crash-", 6) != 0)
            continue;
        char path[512];
        snprintf(path, sizeof path, "tests/data/obj/%s", de->d_name);
        obj_t o;
        svet_error e;
        svet_status st = obj_read(path, NULL, &o, &e);
        ck_assert(st == SVET_OK || st == SVET_ERR_PARSE ||
                  st == SVET_ERR_RANGE);
        if (st != SVET_OK)
            ck_assert(strncmp(e.msg, path, strlen(path)) == 0);
        obj_free(&o);
        n++;
    }
    closedir(d);
    test_report_cases("obj_survives_every_input_the_fuzzer_found", n);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("obj");
    TCase *tc = tcase_create("obj");
    tcase_add_test(tc, obj_reads_every_face_form_exactly);
    tcase_add_test(tc, obj_skips_a_byte_order_mark);
    tcase_add_test(tc, obj_counts_negative_indices_back_from_the_last);
    tcase_add_test(tc, obj_fans_polygons_into_triangles);
    tcase_add_test(tc, obj_records_groups_and_materials_per_triangle);
    tcase_add_test(tc, obj_reads_comments_crlf_and_continuations);
    tcase_add_test(tc, obj_warns_about_what_it_skips);
    tcase_add_test(tc, obj_names_file_line_and_column_of_every_error);
    tcase_add_test(tc, obj_reports_files_it_cannot_read_and_limits);
    tcase_add_test(tc, obj_survives_every_input_the_fuzzer_found);
    suite_add_tcase(s, tc);
    return s;
}
