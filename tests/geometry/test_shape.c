/*
 * test_shape.c - what the primitives of app. D share (shape.c): one-block
 * allocation, input checks, the scale-safe unit cross product and the
 * PATHPOINT frame (app. A).
 */
#include "testutil.h"
#include "core/frame.h"
#include "geomcheck.h"
#include "geometry/shape.h"

#include <stdalign.h>
#include <stdint.h>
#include <string.h>

static const cobject_ops dummy_ops = { "dummy", NULL, NULL, NULL, NULL, NULL,
                                       NULL, NULL };

START_TEST(shape_alloc_gives_zeroed_aligned_data_freed_with_the_object)
{
    svet_error err;
    COBJECT *o = shape_alloc(&dummy_ops, 3 * sizeof(double), &err);
    ck_assert_ptr_nonnull(o);
    ck_assert(o->ops == &dummy_ops && o->nprims == 1 && o->id == -1);
    ck_assert_ptr_nonnull(o->shape);
    ck_assert((uintptr_t)o->shape % alignof(max_align_t) == 0);
    const double *d = o->shape;
    ck_assert(d[0] == 0 && d[1] == 0 && d[2] == 0);
    cobject_free(o); /* the sanitizer build checks that nothing leaks */
    COBJECT *e = shape_alloc(&dummy_ops, 0, &err);
    ck_assert_ptr_nonnull(e);
    ck_assert_ptr_null(e->shape);
    cobject_free(e);
    ck_assert_ptr_null(shape_alloc(&dummy_ops, (size_t)-1, &err));
    ck_assert_int_eq(err.status, SVET_ERR_NOMEM);
}
END_TEST

START_TEST(shape_check_finite_names_the_bad_input)
{
    svet_error err;
    svet_error_clear(&err);
    VECTOR3 ok = { 1, 2, 3 }, bad = { 1, (real)NAN, 3 };
    ck_assert_int_eq(shape_check_finite("box", "min", ok, &err), SVET_OK);
    ck_assert_int_eq(shape_check_finite("box", "min", bad, &err),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_msg(strstr(err.msg, "box: min") != NULL, "%s", err.msg);
    bad[Y] = (real)INFINITY;
    ck_assert_int_eq(shape_check_finite("box", "max", bad, NULL),
                     SVET_ERR_RANGE);
}
END_TEST

START_TEST(unit_cross_is_exact_for_axes_at_any_scale)
{
    /* from the smallest subnormal-adjacent scales to the largest: the
     * plain cross product would underflow to 0 or overflow to inf */
    const real s[] = { REAL_MIN, REAL_C(1e-30), REAL_C(1.0), REAL_C(1e30),
                       REAL_MAX / 2 };
    for (int i = 0; i < 5; i++) {
        VECTOR3 a = { s[i], 0, 0 }, b = { 0, s[i], 0 }, n;
        ck_assert(shape_unit_cross(n, a, b));
        ck_assert(n[X] == 0 && n[Y] == 0 && n[Z] == 1);
        VECTOR3 c = { 0, 0, s[i] + s[i] / 2 };
        ck_assert(shape_unit_cross(n, c, a)); /* z x x = y */
        ck_assert(n[X] == 0 && n[Y] == 1 && n[Z] == 0);
    }
    VECTOR3 a = { 1, 2, 3 }, b = { 2, 4, 6 }, z = { 0, 0, 0 }, n;
    ck_assert(!shape_unit_cross(n, a, b));
    ck_assert(n[X] == 0 && n[Y] == 0 && n[Z] == 0);
    ck_assert(!shape_unit_cross(n, a, z));
    VECTOR3 nan = { (real)NAN, 0, 1 };
    ck_assert(!shape_unit_cross(n, a, nan));
    ck_assert(vec_is_finite(n));
}
END_TEST

START_TEST(cross_length_overflows_only_when_the_area_does)
{
    VECTOR3 a = { REAL_C(0x1p60), 0, 0 }, b = { 0, REAL_C(0x1p60), 0 };
    ck_assert(shape_cross_length(a, b) == REAL_C(0x1p120));
    VECTOR3 t = { REAL_C(0x1p-60), 0, 0 }, u = { 0, REAL_C(0x1p-60), 0 };
    ck_assert(shape_cross_length(t, u) == REAL_C(0x1p-120));
    VECTOR3 big = { REAL_MAX, 0, 0 };
    ck_assert(isinf(shape_cross_length(big, b)));
    /* 3-4-5: |(3,0,0) x (0,4,0)| ... and a skew pair with an exact answer */
    VECTOR3 p = { 3, 0, 0 }, q = { 3, 4, 0 };
    ck_assert(shape_cross_length(p, q) == 12);
}
END_TEST

START_TEST(shape_frame_is_right_handed_orthonormal_and_follows_dpds)
{
    pcg32_t g;
    pcg32_seed(&g, 7, 11);
    long n = 0;
    for (int i = 0; i < 20000; i++, n++) {
        VECTOR3 nn, d, u, v, c;
        geomcheck_random_dir(nn, &g);
        geomcheck_random_dir(d, &g);
        /* dpds of wildly different lengths, sometimes nearly along n */
        real len = ldexp(REAL_C(1.0), (int)pcg32_bounded(&g, 200) - 100);
        if (i % 7 == 0)
            vec_add_scaled(d, nn, REAL_C(1e-3), d);
        vec_scale(d, d, len);
        shape_frame(u, v, nn, d);
        ck_assert_near(vec_length(u), 1, 8 * REAL_EPSILON);
        ck_assert_near(vec_length(v), 1, 8 * REAL_EPSILON);
        ck_assert_near(SVECTOR3(u, nn), 0, 8 * REAL_EPSILON);
        ck_assert_near(SVECTOR3(v, nn), 0, 8 * REAL_EPSILON);
        ck_assert_near(SVECTOR3(u, v), 0, 8 * REAL_EPSILON);
        VVECTOR3(c, u, v);
        for (int k = 0; k < 3; k++)
            ck_assert_near(c[k], nn[k], 16 * REAL_EPSILON);
        /* u is the direction of dpds's part perpendicular to n */
        VECTOR3 t;
        vec_add_scaled(t, d, -SVECTOR3(d, nn), nn);
        vec_normalize(t, t);
        ck_assert_near(SVECTOR3(u, t), 1, 1e-3);
    }
    /* degenerate tangents fall back to frame_from_normal */
    VECTOR3 nn = { 0, 0, -1 }, zero = { 0, 0, 0 }, along = { 0, 0, 5 };
    VECTOR3 u, v, fu, fv;
    frame_from_normal(fu, fv, nn);
    shape_frame(u, v, nn, zero);
    ck_assert(memcmp(u, fu, sizeof u) == 0 && memcmp(v, fv, sizeof v) == 0);
    shape_frame(u, v, nn, along);
    ck_assert(memcmp(u, fu, sizeof u) == 0 && memcmp(v, fv, sizeof v) == 0);
    test_report_cases("shape_frame_is_right_handed_orthonormal", n);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("shape");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, shape_alloc_gives_zeroed_aligned_data_freed_with_the_object);
    tcase_add_test(tc, shape_check_finite_names_the_bad_input);
    tcase_add_test(tc, unit_cross_is_exact_for_axes_at_any_scale);
    tcase_add_test(tc, cross_length_overflows_only_when_the_area_does);
    tcase_add_test(tc, shape_frame_is_right_handed_orthonormal_and_follows_dpds);
    suite_add_tcase(s, tc);
    return s;
}
