/*
 * test_quadric.c - what the quadrics of app. D share (src/geometry/quadric.c): the
 * stable quadratic against long double, Kahan's 2x2 determinant, exact
 * power-of-two scaling of directions, the defect of the axis frame that
 * QUADRIC_FRAME_DELTA must cover, point error bounds, face picking.
 */
#include "quadcheck.h"
#include "geometry/quadric.h"

#include <math.h>

/* The roots of a t^2 + 2 bh t + c in long double. The textbook formula
 * (-bh +- sqrt(disc)) / a would itself lose the small root's digits to
 * cancellation (for |bh| = 1e6, 12 of long double's 19), so the reference
 * takes the stable form too, with 11 more bits than double. */
static int roots_ld(long double a, long double bh, long double c,
                    long double t[2])
{
    long double disc = bh * bh - a * c;
    if (disc < 0)
        return 0;
    long double q = -(bh + copysignl(sqrtl(disc), bh));
    t[0] = c / q;
    t[1] = q / a;
    if (t[0] > t[1]) {
        long double x = t[0]; t[0] = t[1]; t[1] = x;
    }
    return 2;
}

START_TEST(roots_of_known_quadratics)
{
    real t[2];
    /* t^2 - 3t + 2 = (t - 1)(t - 2) */
    ck_assert_int_eq(quadric_roots(1, REAL_C(-1.5), 2, REAL_C(0.25), t), 2);
    ck_assert_near(t[0], 1, 0);
    ck_assert_near(t[1], 2, 0);
    /* a double root: (t - 3)^2 */
    ck_assert_int_eq(quadric_roots(1, -3, 9, 0, t), 2);
    ck_assert(t[0] == 3 && t[1] == 3);
    /* linear: 2 (2) t - 8 = 0 */
    ck_assert_int_eq(quadric_roots(0, 2, -8, 4, t), 1);
    ck_assert_near(t[0], 2, 0);
    /* no real roots, NaN, nothing left of the equation */
    ck_assert_int_eq(quadric_roots(1, 0, 1, -1, t), 0);
    ck_assert_int_eq(quadric_roots(1, 0, 1, (real)NAN, t), 0);
    ck_assert_int_eq(quadric_roots(0, 0, 0, 0, t), 0);
    /* bh = 0 and disc = 0 (q = 0): t^2 = 0, no 0/0 */
    ck_assert_int_eq(quadric_roots(1, 0, 0, 0, t), 2);
    ck_assert(t[0] == 0 && t[1] == 0);
    ck_assert_int_eq(quadric_roots(1, -(real)0.0, 0, 0, t), 2);
    ck_assert(t[0] == 0 && t[1] == 0);
}
END_TEST

START_TEST(roots_keep_full_precision_where_the_textbook_cancels)
{
    /* t^2 - 2 B t + 1: roots B +- sqrt(B^2 - 1); the small one ~ 1/(2B)
     * is where (-b + sqrt(disc)) / 2a loses every digit. */
    pcg32_t g;
    pcg32_seed(&g, 3, 4);
    long cases = 0;
    for (int i = 0; i < 20000; i++, cases++) {
        real B = pow(REAL_C(10.0), 6 * pcg32_real(&g));
        real a = 1 + pcg32_real(&g), c = 1 + pcg32_real(&g);
        if (i % 2)
            B = -B;
        real disc = quadric_diff_of_products(B, B, a, c);
        real t[2];
        long double e[2];
        int n = quadric_roots(a, B, c, disc, t);
        int m = roots_ld((long double)a, (long double)B, (long double)c, e);
        ck_assert_int_eq(n, m);
        for (int k = 0; k < n; k++)
            ck_assert_msg(fabsl((long double)t[k] - e[k]) <=
                              8 * (long double)REAL_EPSILON * fabsl(e[k]),
                          "root %d of (%g, %g, %g): %.9g vs %.9Lg", k,
                          (double)a, (double)B, (double)c, (double)t[k], e[k]);
    }
    test_report_cases("roots_keep_full_precision_where_the_textbook_cancels",
                      cases);
}
END_TEST

START_TEST(kahan_difference_of_products_is_within_two_ulps)
{
    pcg32_t g;
    pcg32_seed(&g, 5, 6);
    long cases = 0;
    for (int i = 0; i < 100000; i++, cases++) {
        /* a, b, d of 24 bits and c = a + a 14-bit nudge of 2^-16 (at most
         * 32 bits): every product fits long double's 64-bit significand,
         * so the reference is a b - c d rounded once */
        real a = ldexp(floor(ldexp(pcg32_real(&g), 24)), -22) - 2;
        real b = ldexp(floor(ldexp(pcg32_real(&g), 24)), -22) - 2;
        real c = a + ldexp(floor(ldexp(pcg32_real(&g), 14)), -30);
        real d = b; /* a b - c d nearly cancels */
        long double e = (long double)a * (long double)b -
                        (long double)c * (long double)d;
        real r = quadric_diff_of_products(a, b, c, d);
        /* Jeannerod et al. 2013: |error| <= 2 u |result| */
        ck_assert_msg(fabsl((long double)r - e) <=
                          (long double)REAL_EPSILON * fabsl(e),
                      "%.9g vs %.9Lg", (double)r, e);
    }
    test_report_cases("kahan_difference_of_products_is_within_two_ulps",
                      cases);
}
END_TEST

START_TEST(direction_scaling_is_exact_for_every_length)
{
    VECTOR3 ds;
    VECTOR3 d = { 3 * REAL_C(0x1p40), -REAL_C(0x1p38), 0 };
    int k = quadric_scale_dir(ds, d);
    ck_assert_int_eq(k, 41);
    ck_assert(ds[X] == REAL_C(1.5) && ds[Y] == REAL_C(-0.125) && ds[Z] == 0);
    ck_assert(quadric_unscale_t(REAL_C(4.0), k) == REAL_C(0x1p-39));
    /* moderate lengths are left as they are */
    vec_set(d, 3, REAL_C(-0.5), 0);
    ck_assert_int_eq(quadric_scale_dir(ds, d), 0);
    ck_assert(ds[X] == 3 && ds[Y] == REAL_C(-0.5) && ds[Z] == 0);
    VECTOR3 zero = { 0, 0, 0 };
    ck_assert_int_eq(quadric_scale_dir(ds, zero), 0);
    pcg32_t g;
    pcg32_seed(&g, 7, 8);
    long cases = 0;
    for (int i = 0; i < 10000; i++, cases++) {
        int e = (int)pcg32_bounded(&g, 200) - 100;
        VECTOR3 v = { pcg32_real(&g) - REAL_C(0.5), pcg32_real(&g),
                      -pcg32_real(&g) };
        vec_scale(v, v, scalbn(REAL_C(1.0), e));
        real m0 = fmax(fabs(v[X]), fmax(fabs(v[Y]), fabs(v[Z])));
        k = quadric_scale_dir(ds, v);
        real m = fmax(fabs(ds[X]), fmax(fabs(ds[Y]), fabs(ds[Z])));
        if (m == 0)
            continue;
        if (m0 >= REAL_C(0x1p-32) && m0 <= REAL_C(0x1p32))
            ck_assert(k == 0 && m == m0);
        else
            ck_assert(m >= 1 && m < 2);
        for (int j = 0; j < 3; j++) /* exact: scaling back gives v */
            ck_assert(scalbn(ds[j], k) == v[j]);
    }
    test_report_cases("direction_scaling_is_exact_for_every_length", cases);
}
END_TEST

START_TEST(projection_reaches_the_length_for_tiny_and_huge_vectors)
{
    /* a hit computed at the sphere's very centre gave (0, 5e-43, 0):
     * r / |q| overflowed before the scaling by a power of two */
    const real lens[] = { REAL_C(1e-4), 1, REAL_C(1e6) };
    const real mags[] = { REAL_MIN / 64, REAL_C(1e-30), 1, REAL_C(1e30),
                          REAL_MAX / 4 };
    long cases = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 5; j++, cases++) {
            VECTOR3 q = { 0, mags[j], -mags[j] / 3 };
            ck_assert(quadric_project(q, lens[i]));
            ck_assert(vec_is_finite(q));
            /* within gamma(6) per component of a vector exactly len long */
            ck_assert_rel(vec_length(q), lens[i], 8 * REAL_EPSILON, 0);
            ck_assert(q[X] == 0 && q[Y] > 0 && q[Z] < 0);
        }
    VECTOR3 zero = { 0, 0, 0 }, bad = { (real)NAN, 0, 1 };
    ck_assert(!quadric_project(zero, 1));
    ck_assert(!quadric_project(bad, 1));
    test_report_cases(
        "projection_reaches_the_length_for_tiny_and_huge_vectors", cases);
}
END_TEST

START_TEST(disk_hits_miss_parallel_rays_and_include_the_rim)
{
    real ts, x, y;
    VECTOR3 o = { 0, 0, 1 }, along = { 1, 0, 0 }, down = { 0, 0, -1 };
    ck_assert(!quadric_disk_hit(o, along, 0, 1, &ts, &x, &y));
    VECTOR3 in_plane = { 0, 0, 0 };
    ck_assert(!quadric_disk_hit(in_plane, along, 0, 1, &ts, &x, &y));
    VECTOR3 rim = { 1, 0, 1 }, out = { 0, 0, 1 };
    ck_assert(quadric_disk_hit(rim, down, 0, 1, &ts, &x, &y));
    ck_assert(ts == 1 && x == 1 && y == 0);
    out[X] = nextafter(REAL_C(1.0), REAL_C(2.0));
    ck_assert(!quadric_disk_hit(out, down, 0, 1, &ts, &x, &y));
    /* the bound of a box rounds outward */
    bbox_t b;
    bbox_empty(&b);
    VECTOR3 lo = { REAL_C(0.1), -1, 0 }, hi = { REAL_C(0.3), 1, 0 };
    quadric_bounds_add(&b, lo, hi);
    for (int k = 0; k < 3; k++)
        ck_assert(b.min[k] < lo[k] && b.max[k] > hi[k]);
}
END_TEST

START_TEST(azimuth_lies_in_zero_to_two_pi)
{
    ck_assert_near(quadric_phi(0, 0), 0, 0);
    ck_assert_near(quadric_phi(1, 0), 0, 0);
    ck_assert_near(quadric_phi(0, 1), REAL_PI / 2, 2 * REAL_EPSILON);
    ck_assert_near(quadric_phi(-1, 0), REAL_PI, 2 * REAL_EPSILON);
    ck_assert_near(quadric_phi(0, -1), 3 * REAL_PI / 2, 4 * REAL_EPSILON);
    real phi = quadric_phi(1, -REAL_MIN);
    ck_assert(phi >= 0 && phi <= 2 * REAL_PI);
}
END_TEST

/* The frame's departure from orthonormality and from the exact axis, which
 * QUADRIC_FRAME_DELTA must cover with a margin of four. */
START_TEST(axis_frame_defect_is_a_quarter_of_its_bound)
{
    pcg32_t g;
    pcg32_seed(&g, 9, 10);
    long cases = 0;
    double worst = 0;
    for (int i = 0; i < 100000; i++, cases++) {
        VECTOR3 a, w, zero = { 0, 0, 0 };
        geomcheck_random_dir(a, &g);
        vec_scale(a, a, pow(REAL_C(10.0), 8 * pcg32_real(&g) - 4));
        if (i % 8 == 0) /* near the poles of frame_from_normal */
            vec_set(a, REAL_C(1e-3) * (pcg32_real(&g) - REAL_C(0.5)), 0,
                    -1 - pcg32_real(&g));
        vec_normalize(w, a);
        quadric_frame_t f;
        quadric_frame_init(&f, zero, w);
        long double al = 0;
        for (int p = 0; p < 3; p++)
            al += (long double)a[p] * (long double)a[p];
        al = sqrtl(al);
        const real *e[3] = { f.e1, f.e2, f.w };
        double defect = 0;
        for (int p = 0; p < 3; p++) {
            defect = fmax(defect, fabs(1 - (double)vec_length(e[p])));
            for (int q = p + 1; q < 3; q++)
                defect = fmax(defect, fabs((double)SVECTOR3(e[p], e[q])));
            defect = fmax(defect, (double)fabsl((long double)e[2][p] -
                                                (long double)a[p] / al));
        }
        /* right-handed: e1 x e2 = w */
        VECTOR3 c;
        VVECTOR3(c, f.e1, f.e2);
        for (int p = 0; p < 3; p++)
            defect = fmax(defect, fabs((double)(c[p] - f.w[p])));
        worst = fmax(worst, defect);
        ck_assert_msg(defect <= (double)QUADRIC_FRAME_DELTA / 4, "defect %g",
                      defect);
    }
    printf("  largest defect: %.3g eps\n", worst / (double)REAL_EPSILON);
    test_report_cases("axis_frame_defect_is_a_quarter_of_its_bound", cases);
}
END_TEST

START_TEST(frame_points_are_within_their_rounding_bound)
{
    pcg32_t g;
    pcg32_seed(&g, 11, 12);
    long cases = 0;
    for (int i = 0; i < 20000; i++, cases++) {
        VECTOR3 w, at, p, err;
        geomcheck_random_dir(w, &g);
        geomcheck_random_dir(at, &g);
        vec_scale(at, at, 100 * pcg32_real(&g));
        quadric_frame_t f;
        quadric_frame_init(&f, at, w);
        real x = 10 * pcg32_real(&g) - 5, y = 10 * pcg32_real(&g) - 5,
             z = 10 * pcg32_real(&g) - 5;
        quadric_frame_point(&f, at, x, y, z, 0, p, err);
        /* with the frame as computed, the sum in long double: only the
         * gamma(4) part of the bound is at stake here */
        for (int k = 0; k < 3; k++) {
            long double e = (long double)at[k] +
                            (long double)x * (long double)f.e1[k] +
                            (long double)y * (long double)f.e2[k] +
                            (long double)z * (long double)f.w[k];
            ck_assert(fabsl((long double)p[k] - e) <= (long double)err[k]);
        }
    }
    test_report_cases("frame_points_are_within_their_rounding_bound", cases);
}
END_TEST

START_TEST(faces_are_picked_in_proportion_to_their_area)
{
    const real area[3] = { 2, 1, 1 };
    long count[3] = { 0, 0, 0 };
    const int n = 100000;
    pcg32_t g;
    pcg32_seed(&g, 13, 14);
    for (int i = 0; i < n; i++) {
        real u = pcg32_real(&g);
        int f = quadric_pick_face(&u, area, 3);
        ck_assert(f >= 0 && f < 3 && u >= 0 && u <= 1);
        count[f]++;
    }
    /* Binomial counts: p = 1/2, 1/4, 1/4; 6 standard deviations
     * sqrt(n p (1 - p)) <= 0.5 sqrt(n) allow a false alarm with
     * probability < 1e-8 each. */
    const double p[3] = { 0.5, 0.25, 0.25 };
    for (int f = 0; f < 3; f++)
        ck_assert_near(count[f], n * p[f], 6 * sqrt(n * p[f] * (1 - p[f])));
    /* the ends map to the ends */
    real u = 0;
    ck_assert_int_eq(quadric_pick_face(&u, area, 3), 0);
    ck_assert(u == 0);
    u = nextafter(REAL_C(1.0), REAL_C(0.0));
    ck_assert_int_eq(quadric_pick_face(&u, area, 3), 2);
    ck_assert(u <= 1);
    test_report_cases("faces_are_picked_in_proportion_to_their_area", n);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("quadric (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, roots_of_known_quadratics);
    tcase_add_test(tc, roots_keep_full_precision_where_the_textbook_cancels);
    tcase_add_test(tc, kahan_difference_of_products_is_within_two_ulps);
    tcase_add_test(tc, direction_scaling_is_exact_for_every_length);
    tcase_add_test(tc,
                   projection_reaches_the_length_for_tiny_and_huge_vectors);
    tcase_add_test(tc, disk_hits_miss_parallel_rays_and_include_the_rim);
    tcase_add_test(tc, azimuth_lies_in_zero_to_two_pi);
    tcase_add_test(tc, axis_frame_defect_is_a_quarter_of_its_bound);
    tcase_add_test(tc, frame_points_are_within_their_rounding_bound);
    tcase_add_test(tc, faces_are_picked_in_proportion_to_their_area);
    suite_add_tcase(s, tc);
    return s;
}
