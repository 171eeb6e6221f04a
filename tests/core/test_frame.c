/*
 * test_frame.c - the orthonormal frame of app. A (Duff et al. 2017):
 * orthonormal and right-handed for every normal, the poles and -0.0
 * included, and world <-> local round trips.
 */
#include "testutil.h"
#include "core/frame.h"
#include "core/rng.h"

#include <math.h>

static void check_frame(const VECTOR3 n)
{
    VECTOR3 u, v, c;
    frame_from_normal(u, v, n);
    ck_assert(vec_is_finite(u) && vec_is_finite(v));
    ck_assert_near(vec_length(u), 1, 4 * REAL_EPSILON);
    ck_assert_near(vec_length(v), 1, 4 * REAL_EPSILON);
    ck_assert_near(SVECTOR3(u, v), 0, 4 * REAL_EPSILON);
    ck_assert_near(SVECTOR3(u, n), 0, 4 * REAL_EPSILON);
    ck_assert_near(SVECTOR3(v, n), 0, 4 * REAL_EPSILON);
    VVECTOR3(c, u, v); /* right-handed: u x v = n */
    for (int k = 0; k < 3; k++)
        ck_assert_near(c[k], n[k], 8 * REAL_EPSILON);
}

START_TEST(frame_is_orthonormal_at_the_poles_and_axes)
{
    const real axes[][3] = { { 0, 0, 1 }, { 0, 0, -1 }, { 1, 0, 0 },
                             { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 },
                             { 1, 0, -0.0 }, { 0, 1, -0.0 } };
    for (int i = 0; i < 8; i++)
        check_frame(axes[i]);
    /* nearly (0,0,-1): where the frame of Frisvad 2012 loses orthogonality */
    VECTOR3 n = { REAL_C(1e-4), REAL_C(1e-4), -1 };
    vec_normalize(n, n);
    check_frame(n);
    VECTOR3 m = { REAL_C(-1e-19), REAL_C(3e-20), -1 };
    vec_normalize(m, m);
    check_frame(m);
}
END_TEST

START_TEST(frame_is_orthonormal_for_random_normals)
{
    pcg32_t g;
    pcg32_seed(&g, 11, 12);
    long cases = 0;
    for (int i = 0; i < 100000; i++, cases++) {
        real z = 1 - 2 * pcg32_real(&g), phi = 2 * REAL_PI * pcg32_real(&g);
        if (i % 4 == 0) /* crowd the southern pole */
            z = -1 + REAL_C(1e-6) * pcg32_real(&g);
        real r = sqrt(fmax(REAL_C(0.0), 1 - z * z));
        VECTOR3 n = { r * cos(phi), r * sin(phi), z };
        vec_normalize(n, n);
        check_frame(n);
    }
    test_report_cases("frame_is_orthonormal_for_random_normals", cases);
}
END_TEST

START_TEST(local_and_world_coordinates_round_trip)
{
    pcg32_t g;
    pcg32_seed(&g, 13, 14);
    long cases = 0;
    for (int i = 0; i < 10000; i++, cases++) {
        VECTOR3 n = { pcg32_real(&g) - REAL_C(0.5), pcg32_real(&g) - REAL_C(0.5),
                      pcg32_real(&g) - REAL_C(0.5) };
        if (vec_normalize(n, n) == 0)
            continue;
        VECTOR3 u, v, a = { pcg32_real(&g), pcg32_real(&g), -pcg32_real(&g) };
        VECTOR3 l, w;
        frame_from_normal(u, v, n);
        frame_to_local(l, a, u, v, n);
        ck_assert_near(l[Z], SVECTOR3(a, n), 0);
        frame_to_world(w, l, u, v, n);
        for (int k = 0; k < 3; k++)
            ck_assert_near(w[k], a[k], 16 * REAL_EPSILON);
    }
    /* the normal itself is (0,0,1) locally */
    VECTOR3 n = { 0, 0, -1 }, u, v, l;
    frame_from_normal(u, v, n);
    frame_to_local(l, n, u, v, n);
    ck_assert(l[X] == 0 && l[Y] == 0 && l[Z] == 1);
    test_report_cases("local_and_world_coordinates_round_trip", cases);
}
END_TEST

START_TEST(frames_match_the_vectors)
{
#ifdef SVET_DOUBLE
    const char *tolname = "tol_double";
#else
    const char *tolname = "tol_float";
#endif
    testcsv_t c;
    long cases = 0;
    testcsv_open(&c, "frame.csv");
    while (testcsv_next(&c)) {
        VECTOR3 n = { (real)testcsv_num(&c, "nx"), (real)testcsv_num(&c, "ny"),
                      (real)testcsv_num(&c, "nz") };
        VECTOR3 u, v;
        frame_from_normal(u, v, n);
        const char *uc[3] = { "ux", "uy", "uz" }, *vc[3] = { "vx", "vy", "vz" };
        for (int k = 0; k < 3; k++) {
            ck_assert_near(u[k], testcsv_num(&c, uc[k]), testcsv_num(&c, tolname));
            ck_assert_near(v[k], testcsv_num(&c, vc[k]), testcsv_num(&c, tolname));
        }
        cases++;
    }
    testcsv_close(&c);
    test_report_cases("frames_match_the_vectors", cases);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("frame (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, frame_is_orthonormal_at_the_poles_and_axes);
    tcase_add_test(tc, frame_is_orthonormal_for_random_normals);
    tcase_add_test(tc, local_and_world_coordinates_round_trip);
    tcase_add_test(tc, frames_match_the_vectors);
    suite_add_tcase(s, tc);
    return s;
}
