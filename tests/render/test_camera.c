/*
 * test_camera.c - the pinhole camera: the centre ray looks at the target,
 * the edge rays span the field of view on the chosen axis, project() inverts
 * ray(), and bad set-ups are refused with a message.
 */
#include "testutil.h"
#include "render/camera.h"

#include <math.h>
#include <string.h>

static real angle_between(const VECTOR3 a, const VECTOR3 b)
{
    VECTOR3 c;
    VVECTOR3(c, a, b);
    return atan2(vec_length(c), SVECTOR3(a, b));
}

START_TEST(cornell_box_camera_spans_its_field_of_view)
{
    /* the Cornell box (scenes/cbox.scn): eye (0,0,3.9), target 0, up +y,
     * 39.3077 deg */
    camera_t c;
    VECTOR3 eye = { 0, 0, REAL_C(3.9) }, at = { 0, 0, 0 }, up = { 0, 1, 0 };
    ck_assert_int_eq(camera_init(&c, eye, at, up, REAL_C(39.3077), CAMERA_FOV_X,
                                 256, 256, NULL), SVET_OK);
    ray_t mid, left, right, top;
    camera_ray(&c, 128, 128, &mid);
    ck_assert_near(mid.d[Z], -1, 4 * REAL_EPSILON);
    camera_ray(&c, 0, 128, &left);
    camera_ray(&c, 256, 128, &right);
    camera_ray(&c, 128, 0, &top);
    real fov = angle_between(left.d, right.d) * 180 / REAL_PI;
    ck_assert_near(fov, 39.3077, 1e-4);
    ck_assert(left.d[X] < 0 && right.d[X] > 0 && top.d[Y] > 0);
    /* square image: the vertical angle equals the horizontal one */
    ck_assert_near(angle_between(top.d, mid.d) * 2 * 180 / REAL_PI, 39.3077, 1e-4);
    /* at z = -1 (the back wall) the view is 2 * 4.9 * tan(19.65 deg) wide */
    real half = REAL_C(4.9) * tan(REAL_C(39.3077) / 2 * REAL_PI / 180);
    ck_assert_near(-left.d[X] / -left.d[Z] * REAL_C(4.9), half, 1e-5);
}
END_TEST

START_TEST(fov_axes_and_aspect)
{
    camera_t c;
    VECTOR3 eye = { 1, 2, 3 }, at = { 1, 2, -7 }, up = { 0, 5, 0 };
    /* 200 x 100, 90 degrees along y: tan_y = 1, tan_x = 2 */
    ck_assert_int_eq(camera_init(&c, eye, at, up, 90, CAMERA_FOV_Y, 200, 100,
                                 NULL), SVET_OK);
    ck_assert_near(c.tan_y, 1, 4 * REAL_EPSILON);
    ck_assert_near(c.tan_x, 2, 8 * REAL_EPSILON);
    ck_assert_int_eq(camera_init(&c, eye, at, up, 90, CAMERA_FOV_DIAGONAL, 300,
                                 400, NULL), SVET_OK);
    ck_assert_near(c.tan_x, 0.6, 8 * REAL_EPSILON);
    ck_assert_near(c.tan_y, 0.8, 8 * REAL_EPSILON);
}
END_TEST

START_TEST(project_inverts_ray)
{
    camera_t c;
    VECTOR3 eye = { 3, -1, 2 }, at = { 0, 0, 0 }, up = { 0, 0, 1 };
    ck_assert_int_eq(camera_init(&c, eye, at, up, 50, CAMERA_FOV_X, 64, 48,
                                 NULL), SVET_OK);
    long n = 0;
    for (int j = 0; j <= 48; j += 3)
        for (int i = 0; i <= 64; i += 4, n++) {
            ray_t r;
            real x = (real)i + REAL_C(0.25), y = (real)j + REAL_C(0.5);
            camera_ray(&c, x, y, &r);
            VECTOR3 p;
            ray_at(p, &r, 7);
            real px, py;
            ck_assert(camera_project(&c, p, &px, &py));
            ck_assert_near(px, x, 64 * 64 * REAL_EPSILON);
            ck_assert_near(py, y, 64 * 64 * REAL_EPSILON);
        }
    VECTOR3 behind = { 6, -2, 4 };
    real px, py;
    ck_assert(!camera_project(&c, behind, &px, &py));
    test_report_cases("project_inverts_ray", n);
}
END_TEST

START_TEST(bad_setups_are_refused_with_a_message)
{
    camera_t c;
    svet_error e;
    VECTOR3 eye = { 0, 0, 1 }, at = { 0, 0, 0 }, up = { 0, 1, 0 };
    VECTOR3 upz = { 0, 0, 2 }, nan3 = { (real)NAN, 0, 0 };
    ck_assert_int_eq(camera_init(&c, eye, eye, up, 40, CAMERA_FOV_X, 8, 8, &e),
                     SVET_ERR_RANGE);
    ck_assert(strstr(e.msg, "coincide"));
    ck_assert_int_eq(camera_init(&c, eye, at, upz, 40, CAMERA_FOV_X, 8, 8, &e),
                     SVET_ERR_RANGE);
    ck_assert(strstr(e.msg, "parallel"));
    ck_assert_int_eq(camera_init(&c, eye, at, up, 180, CAMERA_FOV_X, 8, 8, &e),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(camera_init(&c, eye, at, up, (real)NAN, CAMERA_FOV_X, 8, 8,
                                 &e), SVET_ERR_RANGE);
    ck_assert_int_eq(camera_init(&c, eye, at, up, 40, CAMERA_FOV_X, 0, 8, &e),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(camera_init(&c, nan3, at, up, 40, CAMERA_FOV_X, 8, 8, &e),
                     SVET_ERR_RANGE);
    /* apart, but by more than a real holds: not "coincide" */
    VECTOR3 far0 = { -REAL_MAX, 0, 0 }, far1 = { REAL_MAX, 0, 0 };
    ck_assert_int_eq(camera_init(&c, far0, far1, up, 40, CAMERA_FOV_X, 8, 8,
                                 &e), SVET_ERR_RANGE);
    ck_assert_str_eq(e.msg, "camera: position - target overflows " REAL_NAME);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("camera (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, cornell_box_camera_spans_its_field_of_view);
    tcase_add_test(tc, fov_axes_and_aspect);
    tcase_add_test(tc, project_inverts_ray);
    tcase_add_test(tc, bad_setups_are_refused_with_a_message);
    suite_add_tcase(s, tc);
    return s;
}
