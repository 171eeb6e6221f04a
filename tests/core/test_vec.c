/*
 * test_vec.c - VECTOR3 algebra (app. B), reflection (1.4), refraction
 * (1.11-1.12) and Rodrigues' rotation (app. C), against exact values, the
 * laws the operations obey, and tests/vectors/vec_*.csv.
 */
#include "testutil.h"
#include "core/rng.h"
#include "core/vec.h"

#include <math.h>
#include <string.h>

static void random_unit(VECTOR3 w, pcg32_t *g)
{
    /* uniform on the sphere: z uniform in [-1,1], phi uniform (Archimedes) */
    real z = 1 - 2 * pcg32_real(g), phi = 2 * REAL_PI * pcg32_real(g);
    real r = sqrt(fmax(REAL_C(0.0), 1 - z * z));
    vec_set(w, r * cos(phi), r * sin(phi), z);
}

START_TEST(cross_and_dot_of_the_axes)
{
    VECTOR3 x = { 1, 0, 0 }, y = { 0, 1, 0 }, c;
    VVECTOR3(c, x, y);
    ck_assert(c[X] == 0 && c[Y] == 0 && c[Z] == 1);
    ck_assert(SVECTOR3(x, y) == 0);
    ck_assert(SVECTOR3(c, c) == 1);
    /* aliasing: c = c x x */
    VVECTOR3(c, c, x);
    ck_assert(c[X] == 0 && c[Y] == 1 && c[Z] == 0);
}
END_TEST

START_TEST(cross_is_orthogonal_and_anticommutative)
{
    pcg32_t g;
    pcg32_seed(&g, 1, 2);
    long n = 0;
    for (int i = 0; i < 10000; i++, n++) {
        VECTOR3 a, b, ab, ba;
        random_unit(a, &g);
        random_unit(b, &g);
        VVECTOR3(ab, a, b);
        VVECTOR3(ba, b, a);
        for (int k = 0; k < 3; k++)
            ck_assert(ab[k] == -ba[k]);
        ck_assert_near(SVECTOR3(ab, a), 0, 8 * REAL_EPSILON);
        ck_assert_near(SVECTOR3(ab, b), 0, 8 * REAL_EPSILON);
        /* Lagrange: |a x b|^2 + (a.b)^2 = |a|^2 |b|^2 = 1 */
        real d = SVECTOR3(a, b);
        ck_assert_near(vec_length2(ab) + d * d, 1, 16 * REAL_EPSILON);
    }
    test_report_cases("cross_is_orthogonal_and_anticommutative", n);
}
END_TEST

START_TEST(normalize_handles_zero_nan_and_extremes)
{
    VECTOR3 z = { 0, 0, 0 }, c = { 7, 7, 7 };
    ck_assert(vec_normalize(c, z) == 0);
    ck_assert(c[X] == 0 && c[Y] == 0 && c[Z] == 0);
    VECTOR3 bad = { (real)NAN, 1, 0 };
    ck_assert(vec_normalize(c, bad) == 0);
    ck_assert(vec_is_finite(c));
    VECTOR3 inf = { (real)INFINITY, 0, 0 };
    ck_assert(vec_normalize(c, inf) == 0);
    /* components near the extremes of the type do not overflow/underflow */
    VECTOR3 big = { REAL_MAX / 2, REAL_MAX / 2, 0 };
    ck_assert(vec_normalize(c, big) > 0);
    ck_assert_near(vec_length(c), 1, 2 * REAL_EPSILON);
    VECTOR3 tiny = { REAL_MIN, REAL_MIN, REAL_MIN };
    ck_assert(vec_normalize(c, tiny) > 0);
    ck_assert_near(c[X], 1 / sqrt(REAL_C(3.0)), 2 * REAL_EPSILON);
    /* aliasing; an axis stays exactly an axis */
    VECTOR3 a = { 0, -5, 0 };
    ck_assert(vec_normalize(a, a) == 5);
    ck_assert(a[X] == 0 && a[Y] == -1 && a[Z] == 0);
}
END_TEST

START_TEST(reflection_obeys_eq_1_4)
{
    /* 45 degrees onto the xy plane */
    VECTOR3 n = { 0, 0, 1 }, in, r;
    vec_set(in, 1, 0, 1);
    vec_normalize(in, in);
    vec_reflect(r, in, n);
    ck_assert_near(r[X], -in[X], REAL_EPSILON);
    ck_assert_near(r[Z], in[Z], REAL_EPSILON);
    pcg32_t g;
    pcg32_seed(&g, 3, 4);
    long cases = 0;
    for (int i = 0; i < 10000; i++, cases++) {
        VECTOR3 w, m, rr, back, sum, c;
        random_unit(w, &g);
        random_unit(m, &g);
        vec_reflect(rr, w, m);
        /* angle of incidence = angle of reflection, unit length, coplanar,
         * and reflecting twice gives back the start */
        ck_assert_near(SVECTOR3(rr, m), SVECTOR3(w, m), 8 * REAL_EPSILON);
        ck_assert_near(vec_length(rr), 1, 8 * REAL_EPSILON);
        vec_add(sum, rr, w);
        VVECTOR3(c, sum, m);
        ck_assert_near(vec_length(c), 0, 16 * REAL_EPSILON);
        vec_reflect(back, rr, m);
        for (int k = 0; k < 3; k++)
            ck_assert_near(back[k], w[k], 16 * REAL_EPSILON);
    }
    test_report_cases("reflection_obeys_eq_1_4", cases);
}
END_TEST

START_TEST(refraction_obeys_snell_and_reports_tir)
{
    pcg32_t g;
    pcg32_seed(&g, 5, 6);
    long cases = 0, tir = 0;
    const real etas[][2] = { { 1, 1.5 }, { 1.5, 1 }, { 1, 1 }, { 1, 2.42 },
                             { 1.33, 1 } };
    for (int e = 0; e < 5; e++) {
        real n1 = etas[e][0], n2 = etas[e][1];
        for (int i = 0; i < 4000; i++, cases++) {
            VECTOR3 w, m, t;
            random_unit(w, &g);
            random_unit(m, &g);
            real ci = SVECTOR3(w, m);
            real si = sqrt(fmax(REAL_C(0.0), 1 - ci * ci));
            bool ok = vec_refract(t, w, m, n1, n2);
            ck_assert(vec_is_finite(t));
            if (!ok) {
                tir++;
                ck_assert_msg(n1 / n2 * si >= 1 - 16 * REAL_EPSILON,
                              "TIR reported below the critical angle");
                continue;
            }
            real ct = SVECTOR3(t, m);
            /* other side of the surface, unit, Snell n1 sin_i = n2 sin_t;
             * sines from |w x m| (accurate near normal incidence, where
             * sqrt(1 - cos^2) is not) */
            ck_assert(ci * ct <= 0);
            ck_assert_near(vec_length(t), 1, 16 * REAL_EPSILON);
            VECTOR3 tm, wm0;
            VVECTOR3(tm, t, m);
            VVECTOR3(wm0, w, m);
            ck_assert_near(n1 * vec_length(wm0), n2 * vec_length(tm),
                           32 * REAL_EPSILON * fmax(n1, n2));
            /* coplanar with w and m */
            VECTOR3 wm;
            VVECTOR3(wm, w, m);
            ck_assert_near(SVECTOR3(wm, t), 0, 32 * REAL_EPSILON);
        }
    }
    ck_assert(tir > 0);
    test_report_cases("refraction_obeys_snell_and_reports_tir", cases);
}
END_TEST

START_TEST(refraction_at_the_critical_angle_and_normal_incidence)
{
    VECTOR3 n = { 0, 0, 1 }, w, t;
    /* glass to air, normal incidence: straight through */
    vec_set(w, 0, 0, 1);
    ck_assert(vec_refract(t, w, n, 1.5, 1));
    ck_assert(t[X] == 0 && t[Y] == 0 && t[Z] == -1);
    /* from below the surface (n . w < 0): the plus sign of (1.11) */
    vec_set(w, 0, 0, -1);
    ck_assert(vec_refract(t, w, n, 1, 1.5));
    ck_assert(t[Z] == 1);
    /* n1 = n2: the ray goes on undeviated, t = -w */
    vec_set(w, REAL_C(0.6), 0, REAL_C(0.8));
    ck_assert(vec_refract(t, w, n, 1.5, 1.5));
    for (int k = 0; k < 3; k++)
        ck_assert_near(t[k], -w[k], 2 * REAL_EPSILON);
    /* just inside and just beyond the critical angle asin(1/1.5) */
    double crit = asin(1 / 1.5);
    double d = 1e-3;
    vec_set(w, (real)sin(crit - d), 0, (real)cos(crit - d));
    ck_assert(vec_refract(t, w, n, 1.5, 1));
    ck_assert(t[Z] < 0 && t[Z] > REAL_C(-0.1));
    vec_set(w, (real)sin(crit + d), 0, (real)cos(crit + d));
    ck_assert(!vec_refract(t, w, n, 1.5, 1));
    ck_assert_near(t[X], -w[X], 2 * REAL_EPSILON); /* mirror direction */
    /* grazing incidence from air: leaves at the critical angle */
    vec_set(w, 1, 0, REAL_C(1e-7));
    ck_assert(vec_refract(t, w, n, 1, 1.5));
    ck_assert_near(-t[X], 1 / 1.5, 1e-5);
}
END_TEST

START_TEST(rodrigues_rotation_of_app_c)
{
    VECTOR3 x = { 1, 0, 0 }, z = { 0, 0, 1 }, r;
    vec_rotate(r, x, z, REAL_PI / 2);
    ck_assert_near(r[X], 0, 2 * REAL_EPSILON);
    ck_assert_near(r[Y], 1, 2 * REAL_EPSILON);
    pcg32_t g;
    pcg32_seed(&g, 7, 8);
    long cases = 0;
    for (int i = 0; i < 10000; i++, cases++) {
        VECTOR3 a, k, ra, back;
        random_unit(a, &g);
        random_unit(k, &g);
        real ang = (pcg32_real(&g) - REAL_C(0.5)) * 4 * REAL_PI;
        vec_rotate(ra, a, k, ang);
        /* length and the component along the axis are kept; rotating back
         * gives the start */
        ck_assert_near(vec_length(ra), 1, 16 * REAL_EPSILON);
        ck_assert_near(SVECTOR3(ra, k), SVECTOR3(a, k), 16 * REAL_EPSILON);
        vec_rotate(back, ra, k, -ang);
        for (int c = 0; c < 3; c++)
            ck_assert_near(back[c], a[c], 64 * REAL_EPSILON);
    }
    test_report_cases("rodrigues_rotation_of_app_c", cases);
}
END_TEST

#ifdef SVET_DOUBLE
#define TOL "tol_double"
#else
#define TOL "tol_float"
#endif

static void read3(testcsv_t *c, const char *p, VECTOR3 v)
{
    char name[16];
    const char *xyz[3] = { "x", "y", "z" };
    for (int k = 0; k < 3; k++) {
        snprintf(name, sizeof name, "%s%s", p, xyz[k]);
        v[k] = (real)testcsv_num(c, name);
    }
}

START_TEST(operations_match_the_vectors)
{
    testcsv_t c;
    long n = 0;
    testcsv_open(&c, "vec_ops.csv");
    while (testcsv_next(&c)) {
        VECTOR3 a, b, e, r;
        read3(&c, "a", a);
        read3(&c, "b", b);
        read3(&c, "e", e);
        double tol = testcsv_num(&c, TOL);
        const char *op = testcsv_str(&c, "op");
        if (strcmp(op, "cross") == 0) {
            VVECTOR3(r, a, b);
        } else if (strcmp(op, "dot") == 0) {
            vec_set(r, SVECTOR3(a, b), 0, 0);
        } else if (strcmp(op, "length") == 0) {
            vec_set(r, vec_length(a), 0, 0);
        } else {
            vec_normalize(r, a);
        }
        for (int k = 0; k < 3; k++)
            ck_assert_msg(fabs((double)r[k] - (double)e[k]) <= tol,
                          "vec_ops.csv:%d: %s component %d: %.9g vs %.9g",
                          c.line, op, k, (double)r[k], (double)e[k]);
        n++;
    }
    testcsv_close(&c);
    test_report_cases("operations_match_the_vectors", n);
}
END_TEST

START_TEST(reflection_refraction_rotation_match_the_vectors)
{
    testcsv_t c;
    long n = 0;
    testcsv_open(&c, "vec_reflect.csv");
    while (testcsv_next(&c)) {
        VECTOR3 w, m, e, r;
        read3(&c, "w", w);
        read3(&c, "n", m);
        read3(&c, "r", e);
        vec_reflect(r, w, m);
        for (int k = 0; k < 3; k++)
            ck_assert_near(r[k], e[k], testcsv_num(&c, TOL));
        n++;
    }
    testcsv_close(&c);
    testcsv_open(&c, "vec_refract.csv");
    while (testcsv_next(&c)) {
        VECTOR3 w, m, e, t;
        read3(&c, "w", w);
        read3(&c, "n", m);
        read3(&c, "t", e);
        bool ok = vec_refract(t, w, m, (real)testcsv_num(&c, "n1"),
                              (real)testcsv_num(&c, "n2"));
        ck_assert_msg(ok == (testcsv_num(&c, "tir") == 0),
                      "vec_refract.csv:%d: TIR disagrees", c.line);
        for (int k = 0; k < 3; k++)
            ck_assert_msg(fabs((double)t[k] - (double)e[k]) <=
                              testcsv_num(&c, TOL),
                          "vec_refract.csv:%d: component %d: %.9g vs %.9g",
                          c.line, k, (double)t[k], (double)e[k]);
        n++;
    }
    testcsv_close(&c);
    testcsv_open(&c, "vec_rotate.csv");
    while (testcsv_next(&c)) {
        VECTOR3 a, k, e, r;
        read3(&c, "a", a);
        read3(&c, "k", k);
        read3(&c, "r", e);
        vec_rotate(r, a, k, (real)testcsv_num(&c, "angle"));
        for (int j = 0; j < 3; j++)
            ck_assert_near(r[j], e[j], testcsv_num(&c, TOL));
        n++;
    }
    testcsv_close(&c);
    test_report_cases("reflection_refraction_rotation_match_the_vectors", n);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("vec (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, cross_and_dot_of_the_axes);
    tcase_add_test(tc, cross_is_orthogonal_and_anticommutative);
    tcase_add_test(tc, normalize_handles_zero_nan_and_extremes);
    tcase_add_test(tc, reflection_obeys_eq_1_4);
    tcase_add_test(tc, refraction_obeys_snell_and_reports_tir);
    tcase_add_test(tc, refraction_at_the_critical_angle_and_normal_incidence);
    tcase_add_test(tc, rodrigues_rotation_of_app_c);
    tcase_add_test(tc, operations_match_the_vectors);
    tcase_add_test(tc, reflection_refraction_rotation_match_the_vectors);
    suite_add_tcase(s, tc);
    return s;
}
