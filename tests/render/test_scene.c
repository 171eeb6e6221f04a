/*
 * test_scene.c - the in-memory scene (scene.h): defaults, ownership of
 * what is added (every failure path frees what it was given: run under
 * LeakSanitizer), the checks on emission and lights, camera validation,
 * and the "did you mean" name matcher.
 */
#include "testutil.h"

#include <math.h>
#include <string.h>

#include "materials/material.h"
#include "render/scene.h"
#include "geometry/sphere.h"

static material_t *grey(real rho)
{
    material_t *m = NULL;
    material_params p;
    material_params_default(&p);
    p.rho_d = rad_grey(rho);
    svet_error err;
    ck_assert_int_eq(material_new(&p, &m, &err), SVET_OK);
    return m;
}

static COBJECT *unit_sphere(void)
{
    VECTOR3 c = { 0, 0, 0 };
    svet_error err;
    COBJECT *obj = sphere_new(c, 1, &err);
    ck_assert_ptr_nonnull(obj);
    return obj;
}

START_TEST(init_gives_the_documented_defaults)
{
    scene_t s;
    scene_init(&s);
    ck_assert_near(s.camera.position[Z], 0, 0);
    ck_assert_near(s.camera.target[Z], -1, 0);
    ck_assert_near(s.camera.up[Y], 1, 0);
    ck_assert_near(s.camera.fov, 40, 0);
    ck_assert_int_eq(s.camera.fov_axis, SCENE_FOV_Y);
    ck_assert_int_eq(s.camera.width, 256);
    ck_assert_int_eq(s.camera.height, 256);
    ck_assert_int_eq(s.camera.filter, SCENE_FILTER_BOX);
    ck_assert_near(s.camera.filter_width, 1, 0);
    ck_assert_int_eq(s.render.spp, 16);
    ck_assert_int_eq(s.render.max_depth, 5);
    ck_assert(s.render.roulette);
    ck_assert_int_eq(s.render.roulette_depth, 3);
    ck_assert_uint_eq(s.render.seed, 0);
    ck_assert_int_eq(s.render.integrator, SCENE_INTEGRATOR_PATH);
    ck_assert_int_eq(s.render.threads, 0);
    ck_assert_int_eq(s.render.passes, 1);
    ck_assert(!s.render.checkpoint);
    ck_assert_ptr_null(s.render.output_exr);
    ck_assert_ptr_null(s.render.output_png);
    ck_assert_int_eq(s.render.tonemap.op, SCENE_TONEMAP_LINEAR);
    ck_assert_int_eq(s.render.tonemap.curve, SCENE_CURVE_SRGB);
    ck_assert_int_eq(s.render.accel, SCENE_ACCEL_AUTO);
    ck_assert_int_eq(s.nobjects + s.nmaterials + s.npoint_lights, 0);
    ck_assert(!s.has_environment);
    ck_assert(!scene_has_lights(&s));
    ck_assert_int_eq(scene_validate(&s, NULL), SVET_OK);
    scene_free(&s);
}
END_TEST

START_TEST(free_is_safe_twice_and_on_null)
{
    scene_t s;
    scene_init(&s);
    ck_assert_int_eq(scene_add_material(&s, "m", grey(REAL_C(0.5)), NULL),
                     SVET_OK);
    ck_assert_int_eq(scene_add_object(&s, unit_sphere(),
                                      scene_find_material(&s, "m"), NULL),
                     SVET_OK);
    scene_free(&s);
    scene_free(&s);
    scene_free(NULL);
    ck_assert_int_eq(s.nobjects, 0);
}
END_TEST

START_TEST(materials_are_found_by_name_and_defined_once)
{
    scene_t s;
    svet_error err;
    scene_init(&s);
    material_t *a = grey(REAL_C(0.5));
    ck_assert_int_eq(scene_add_material(&s, "white", a, &err), SVET_OK);
    ck_assert_ptr_eq(scene_find_material(&s, "white"), a);
    ck_assert_ptr_null(scene_find_material(&s, "whit"));
    /* The duplicate is freed by scene_add_material (LSan checks). */
    ck_assert_int_eq(scene_add_material(&s, "white", grey(1), &err),
                     SVET_ERR_PARSE);
    ck_assert_str_eq(err.msg, "material 'white' is already defined");
    ck_assert_int_eq(scene_add_material(&s, "", grey(1), &err),
                     SVET_ERR_RANGE);
    char longname[SCENE_MAX_NAME + 2];
    memset(longname, 'a', sizeof longname - 1);
    longname[sizeof longname - 1] = '\0';
    ck_assert_int_eq(scene_add_material(&s, longname, grey(1), &err),
                     SVET_ERR_RANGE);
    longname[SCENE_MAX_NAME] = '\0';
    ck_assert_int_eq(scene_add_material(&s, longname, grey(1), &err),
                     SVET_OK);
    ck_assert_int_eq(s.nmaterials, 2);
    ck_assert_int_eq(scene_add_anon_material(&s, grey(REAL_C(0.1)), &err),
                     SVET_OK);
    ck_assert_int_eq(s.nanon_materials, 1);
    scene_free(&s);
}
END_TEST

START_TEST(objects_get_their_material_and_index)
{
    scene_t s;
    svet_error err;
    scene_init(&s);
    material_t *m = grey(REAL_C(0.5));
    ck_assert_int_eq(scene_add_material(&s, "m", m, &err), SVET_OK);
    for (int i = 0; i < 20; i++)
        ck_assert_int_eq(scene_add_object(&s, unit_sphere(), m, &err),
                         SVET_OK);
    ck_assert_int_eq(s.nobjects, 20);
    for (int i = 0; i < 20; i++) {
        ck_assert_int_eq(s.objects[i]->id, i);
        ck_assert_ptr_eq(s.objects[i]->material, m);
        ck_assert_ptr_null(s.objects[i]->light);
    }
    /* No material: refused, and the object is freed (LSan checks). */
    ck_assert_int_eq(scene_add_object(&s, unit_sphere(), NULL, &err),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(s.nobjects, 20);
    scene_free(&s);
}
END_TEST

START_TEST(emission_is_checked_and_recorded)
{
    scene_t s;
    svet_error err;
    scene_init(&s);
    material_t *m = grey(REAL_C(0.5));
    ck_assert_int_eq(scene_add_material(&s, "m", m, &err), SVET_OK);
    ck_assert_int_eq(scene_add_object(&s, unit_sphere(), m, &err), SVET_OK);
    COBJECT *obj = s.objects[0];
    const RADIANCE bad[] = { rad_make(-1, 0, 0), rad_make(0, (real)NAN, 0),
                             rad_make(0, 0, (real)INFINITY) };
    for (int i = 0; i < 3; i++)
        ck_assert_int_eq(scene_set_emission(&s, obj, bad[i], false, &err),
                         SVET_ERR_RANGE);
    ck_assert_ptr_null(obj->light);
    ck_assert_int_eq(scene_set_emission(&s, obj, rad_make(1, 2, 3), true,
                                        &err),
                     SVET_OK);
    ck_assert_ptr_nonnull(obj->light);
    ck_assert_ptr_eq(obj->light, s.emitters[0]);
    ck_assert_ptr_eq(s.emitters[0]->obj, obj);
    ck_assert(s.emitters[0]->two_sided);
    ck_assert_near(s.emitters[0]->radiance.b, 3, 0);
    ck_assert_int_eq(scene_set_emission(&s, obj, rad_grey(1), false, &err),
                     SVET_ERR_RANGE);
    ck_assert_str_eq(err.msg, "the object already emits");
    ck_assert(scene_has_lights(&s));
    scene_free(&s);
}
END_TEST

START_TEST(point_lights_and_environment_are_lights)
{
    scene_t s;
    svet_error err;
    scene_init(&s);
    VECTOR3 p = { 1, 2, 3 }, nanp = { 0, (real)NAN, 0 };
    ck_assert_int_eq(scene_add_point_light(&s, nanp, rad_grey(1), &err),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(scene_add_point_light(&s, p, rad_grey(-1), &err),
                     SVET_ERR_RANGE);
    ck_assert(!scene_has_lights(&s));
    ck_assert_int_eq(scene_add_point_light(&s, p, rad_make(1, 2, 3), &err),
                     SVET_OK);
    ck_assert_int_eq(s.npoint_lights, 1);
    ck_assert_near(s.point_lights[0].position[Z], 3, 0);
    ck_assert_near(s.point_lights[0].intensity.g, 2, 0);
    ck_assert(scene_has_lights(&s));
    scene_free(&s);
    /* A black environment lights nothing; a bright one does. */
    s.has_environment = true;
    s.environment = rad_grey(0);
    ck_assert(!scene_has_lights(&s));
    s.environment = rad_grey(1);
    ck_assert(scene_has_lights(&s));
    scene_free(&s);
}
END_TEST

START_TEST(validate_rejects_a_camera_that_cannot_see)
{
    scene_t s;
    svet_error err;
    scene_init(&s);
    vec_set(s.camera.target, 0, 0, 0);
    ck_assert_int_eq(scene_validate(&s, &err), SVET_ERR_RANGE);
    ck_assert_str_eq(err.msg, "camera target must differ from its position");
    vec_set(s.camera.target, 0, 5, 0);
    ck_assert_int_eq(scene_validate(&s, &err), SVET_ERR_RANGE);
    ck_assert_str_eq(err.msg,
                     "camera up must not be along the view direction");
    vec_set(s.camera.up, 0, 0, 0);
    ck_assert_int_eq(scene_validate(&s, &err), SVET_ERR_RANGE);
    ck_assert_str_eq(err.msg, "camera up must be a nonzero vector");
    vec_set(s.camera.up, 1, 1, 0);
    ck_assert_int_eq(scene_validate(&s, &err), SVET_OK);
    /* finite and different, but the difference overflows: in a component,
     * or only in the length */
    vec_set(s.camera.up, 0, 1, 0);
    vec_set(s.camera.position, -REAL_MAX, 0, 0);
    vec_set(s.camera.target, REAL_MAX, 0, 0);
    ck_assert_int_eq(scene_validate(&s, &err), SVET_ERR_RANGE);
    ck_assert_str_eq(err.msg, "camera target - position overflows " REAL_NAME
                              ": bring them closer");
    real h = REAL_C(0.75) * REAL_MAX;
    vec_set(s.camera.position, 0, 0, 0);
    vec_set(s.camera.target, h, 0, h);
    ck_assert_int_eq(scene_validate(&s, &err), SVET_ERR_RANGE);
    ck_assert_str_eq(err.msg, "camera target - position overflows " REAL_NAME
                              ": bring them closer");
    scene_free(&s);
}
END_TEST

START_TEST(many_materials_are_all_found)
{
    /* The name index is a hash table; this fills it through several
     * doublings and checks every name, and names never defined. */
    scene_t s;
    scene_init(&s);
    const int n = 3000;
    char name[32];
    for (int i = 0; i < n; i++) {
        snprintf(name, sizeof name, "m%d", i);
        ck_assert_int_eq(scene_add_material(&s, name, grey(REAL_C(0.5)),
                                            NULL),
                         SVET_OK);
    }
    for (int i = 0; i < n; i++) {
        snprintf(name, sizeof name, "m%d", i);
        ck_assert_ptr_eq(scene_find_material(&s, name),
                         s.materials[i].material);
        snprintf(name, sizeof name, "x%d", i);
        ck_assert_ptr_null(scene_find_material(&s, name));
    }
    ck_assert_int_eq(scene_add_material(&s, "m17", grey(1), NULL),
                     SVET_ERR_PARSE);
    test_report_cases("many_materials_are_all_found", 2L * n);
    scene_free(&s);
}
END_TEST

START_TEST(nearest_name_suggests_only_likely_typos)
{
    static const char *const names[] = { "sphere", "plane", "disk", "box",
                                         "cone", "camera", "material" };
    const int n = 7;
    ck_assert_str_eq(scene_nearest_name("sphear", names, n), "sphere");
    ck_assert_str_eq(scene_nearest_name("spher", names, n), "sphere");
    ck_assert_str_eq(scene_nearest_name("camrea", names, n), "camera");
    ck_assert_str_eq(scene_nearest_name("materail", names, n), "material");
    ck_assert_str_eq(scene_nearest_name("dsik", names, n), "disk");
    ck_assert_str_eq(scene_nearest_name("bx", names, n), "box");
    /* Too far from anything: no suggestion rather than a silly one. */
    ck_assert_ptr_null(scene_nearest_name("x", names, n));
    ck_assert_ptr_null(scene_nearest_name("teapot", names, n));
    ck_assert_ptr_null(scene_nearest_name("", names, n));
    /* A very long word is compared on its first 63 bytes and is far. */
    char longword[300];
    memset(longword, 'q', sizeof longword - 1);
    longword[sizeof longword - 1] = '\0';
    ck_assert_ptr_null(scene_nearest_name(longword, names, n));
    ck_assert_ptr_null(scene_nearest_name("sphere", names, 0));
}
END_TEST

START_TEST(suggest_material_finds_the_nearest_defined_name)
{
    scene_t s;
    scene_init(&s);
    ck_assert_ptr_null(scene_suggest_material(&s, "white"));
    scene_add_material(&s, "white", grey(REAL_C(0.5)), NULL);
    scene_add_material(&s, "green", grey(REAL_C(0.5)), NULL);
    ck_assert_str_eq(scene_suggest_material(&s, "whte"), "white");
    ck_assert_str_eq(scene_suggest_material(&s, "gren"), "green");
    ck_assert_ptr_null(scene_suggest_material(&s, "glass"));
    scene_free(&s);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("scene");
    TCase *tc = tcase_create("scene");
    tcase_add_test(tc, init_gives_the_documented_defaults);
    tcase_add_test(tc, free_is_safe_twice_and_on_null);
    tcase_add_test(tc, materials_are_found_by_name_and_defined_once);
    tcase_add_test(tc, objects_get_their_material_and_index);
    tcase_add_test(tc, emission_is_checked_and_recorded);
    tcase_add_test(tc, point_lights_and_environment_are_lights);
    tcase_add_test(tc, validate_rejects_a_camera_that_cannot_see);
    tcase_add_test(tc, many_materials_are_all_found);
    tcase_add_test(tc, nearest_name_suggests_only_likely_typos);
    tcase_add_test(tc, suggest_material_finds_the_nearest_defined_name);
    suite_add_tcase(s, tc);
    return s;
}
