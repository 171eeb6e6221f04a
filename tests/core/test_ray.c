/*
 * test_ray.c - rounding-error bounds and spawned rays (pbrt-v3 sec. 3.9):
 * gamma(n), the origin offset clears the error box on the requested side,
 * and shadow rays aimed at a point stop short of it; the offset point is
 * nextafter() of the rounded sum, bit for bit, on every class of input,
 * and the vector form of its last step (SIMD=on) is the plain one's bits.
 */
#include "testutil.h"
#include "geomcheck.h"
#include "core/ray.h"

#include <math.h>

START_TEST(gamma_matches_its_definition)
{
    /* gamma(n) = n u / (1 - n u), u = eps/2 (Higham 2002, lemma 3.1) */
    double u = (double)REAL_EPSILON / 2;
    for (int n = 1; n <= 10; n++)
        ck_assert_rel(ray_gamma(n), n * u / (1 - n * u), 4 * REAL_EPSILON, 0);
    ck_assert(ray_gamma(3) > 3 * REAL_UNIT_ROUNDOFF);
}
END_TEST

START_TEST(offset_origin_clears_the_error_box_on_the_side_of_w)
{
    pcg32_t g;
    pcg32_seed(&g, 21, 22);
    long cases = 0;
    for (int i = 0; i < 20000; i++, cases++) {
        VECTOR3 p, err, n, w, po, d;
        real scale = pow(REAL_C(10.0), (real)(pcg32_real(&g) * 8 - 3));
        geomcheck_random_dir(p, &g);
        vec_scale(p, p, scale);
        for (int k = 0; k < 3; k++)
            err[k] = fabs(p[k]) * 8 * REAL_EPSILON * pcg32_real(&g);
        geomcheck_random_dir(n, &g);
        geomcheck_random_dir(w, &g);
        ray_offset_origin(po, p, err, n, w);
        vec_sub(d, po, p);
        /* the offset lies on the side of w ... */
        real side = SVECTOR3(d, n) * (SVECTOR3(w, n) < 0 ? -1 : 1);
        ck_assert(side >= 0);
        /* ... and each moved component went at least as far as asked:
         * |po_k - p_k| >= |n_k| (|n| . err), no rounding back. */
        real dist = fabs(n[X]) * err[X] + fabs(n[Y]) * err[Y] +
                    fabs(n[Z]) * err[Z];
        for (int k = 0; k < 3; k++)
            ck_assert(fabs(d[k]) >= fabs(n[k]) * dist * (1 - 4 * REAL_EPSILON));
    }
    test_report_cases("offset_origin_clears_the_error_box_on_the_side_of_w",
                      cases);
}
END_TEST

START_TEST(zero_error_still_moves_one_ulp)
{
    /* With p_error = 0 the offset is zero and the point is unchanged. */
    VECTOR3 p = { 1, 2, 3 }, e = { 0, 0, 0 }, n = { 0, 0, 1 }, w = { 0, 0, 1 };
    VECTOR3 po;
    ray_offset_origin(po, p, e, n, w);
    ck_assert(po[X] == 1 && po[Y] == 2 && po[Z] == 3);
    /* A tiny error moves z up by at least one ulp, never x or y. */
    vec_set(e, 0, 0, REAL_C(1e-30));
    ray_offset_origin(po, p, e, n, w);
    ck_assert(po[X] == 1 && po[Y] == 2);
    ck_assert(po[Z] > 3);
    vec_set(w, 0, 0, -1);
    ray_offset_origin(po, p, e, n, w);
    ck_assert(po[Z] < 3);
}
END_TEST

/* A value of every class the offset's arithmetic distinguishes: zeros of
 * both signs, subnormals, the extremes of the normal range, infinities,
 * NaN, and ordinary numbers of both signs over a wide range of scales. */
static real any_class(pcg32_t *g)
{
    static const real special[] = {
        0, -REAL_C(0.0), REAL_TRUE_MIN, -REAL_TRUE_MIN, 4 * REAL_TRUE_MIN,
        REAL_MIN, -REAL_MIN, REAL_MAX, -REAL_MAX, (real)INFINITY,
        -(real)INFINITY, (real)NAN, 1, -1, REAL_C(0.5), 3, -3,
    };
    const int nspecial = (int)(sizeof special / sizeof special[0]);
    uint32_t k = pcg32_next(g) % 3;
    if (k == 0)
        return special[pcg32_next(g) % (uint32_t)nspecial];
    real x = pow(REAL_C(2.0), (real)((int)(pcg32_next(g) % 60) - 30)) *
             (1 + pcg32_real(g));
    return k == 1 ? x : -x;
}

/* The offset written out from its definition (ray.h) with libm's
 * nextafter for the extra ulp: an independent reference for both the
 * branching way of ray.c and the vector way of fast/ray_simd.c. */
static void offset_reference(VECTOR3 po, const VECTOR3 p, const VECTOR3 e,
                             const VECTOR3 n, const VECTOR3 w)
{
    real d = fabs(n[X]) * e[X] + fabs(n[Y]) * e[Y] + fabs(n[Z]) * e[Z];
    if (SVECTOR3(w, n) < 0)
        d = -d;
    for (int k = 0; k < 3; k++) {
        real off = n[k] * d, q = p[k] + off;
        po[k] = off > 0   ? nextafter(q, (real)INFINITY)
                : off < 0 ? nextafter(q, -(real)INFINITY)
                          : q;
    }
}

START_TEST(offset_origin_is_nextafter_on_every_class)
{
    /* Bits compared (NaN with NaN): zeros, subnormals, infinities and NaN
     * in the point, the error, the normal and the direction, mixed with
     * ordinary values and the axis-aligned normals of a box's walls. */
    pcg32_t g;
    pcg32_seed(&g, 23, 24);
    long cases = 0;
    for (int i = 0; i < 100000; i++, cases++) {
        VECTOR3 p, e, n, w, po, ref;
        for (int k = 0; k < 3; k++) {
            p[k] = any_class(&g);
            e[k] = fabs(any_class(&g));
            n[k] = any_class(&g);
            w[k] = any_class(&g);
        }
        if (i % 4 == 0) { /* a wall's normal: one axis, +-1, the rest +-0 */
            int a = (int)(pcg32_next(&g) % 3);
            for (int k = 0; k < 3; k++)
                n[k] = pcg32_next(&g) % 2 ? REAL_C(0.0) : -REAL_C(0.0);
            n[a] = pcg32_next(&g) % 2 ? 1 : -1;
        }
        ray_offset_origin(po, p, e, n, w);
        offset_reference(ref, p, e, n, w);
        for (int k = 0; k < 3; k++) {
            if (isnan(ref[k])) {
                ck_assert(isnan(po[k]));
                continue;
            }
            real_union_t a = { .x = po[k] }, b = { .x = ref[k] };
            ck_assert_msg(a.u == b.u, "case %d coordinate %d", i, k);
        }
    }
    test_report_cases("offset_origin_is_nextafter_on_every_class", cases);
}
END_TEST

/* Bits equal, a NaN equal to any NaN. */
static bool same_coords(const VECTOR3 a, const VECTOR3 b)
{
    for (int k = 0; k < 3; k++) {
        if (isnan(a[k]) || isnan(b[k])) {
            if (!(isnan(a[k]) && isnan(b[k])))
                return false;
            continue;
        }
        real_union_t x = { .x = a[k] }, y = { .x = b[k] };
        if (x.u != y.u)
            return false;
    }
    return true;
}

/* An input of ray_offset_along(): every class in p, n and d, the normals
 * of a box's walls, and offsets far below and far above p's ulp. */
static void along_case(pcg32_t *g, int i, VECTOR3 p, VECTOR3 n, real *d)
{
    for (int k = 0; k < 3; k++) {
        p[k] = any_class(g);
        n[k] = any_class(g);
    }
    *d = any_class(g);
    if (i % 4 == 0) { /* a wall's normal: one axis, +-1, the rest +-0 */
        int a = (int)(pcg32_next(g) % 3);
        for (int k = 0; k < 3; k++)
            n[k] = pcg32_next(g) % 2 ? REAL_C(0.0) : -REAL_C(0.0);
        n[a] = pcg32_next(g) % 2 ? 1 : -1;
    }
    if (i % 8 == 1) /* an offset near p's rounding */
        *d = p[X] * REAL_EPSILON * (pcg32_real(g) - REAL_C(0.5));
}

/* ray_offset_along() from its definition, with libm's nextafter. */
static void along_reference(VECTOR3 po, const VECTOR3 p, const VECTOR3 n,
                            real d)
{
    for (int k = 0; k < 3; k++) {
        real off = n[k] * d, q = p[k] + off;
        po[k] = off > 0   ? nextafter(q, (real)INFINITY)
                : off < 0 ? nextafter(q, -(real)INFINITY)
                          : q;
    }
}

typedef void along_fn(VECTOR3 po, const VECTOR3 p, const VECTOR3 n, real d);

/* f and ref on `cases` inputs of along_case(): the same bits. */
static void same_along(along_fn *f, along_fn *ref, uint64_t seed, int cases,
                       const char *name)
{
    pcg32_t g;
    pcg32_seed(&g, seed, seed + 1);
    for (int i = 0; i < cases; i++) {
        VECTOR3 p, n, a, b;
        real d;
        along_case(&g, i, p, n, &d);
        f(a, p, n, d);
        ref(b, p, n, d);
        ck_assert_msg(same_coords(a, b), "%s, case %d: p (%g %g %g) n (%g "
                      "%g %g) d %g", name, i, (double)p[X], (double)p[Y],
                      (double)p[Z], (double)n[X], (double)n[Y],
                      (double)n[Z], (double)d);
    }
    test_report_cases(name, cases);
}

START_TEST(offset_along_plain_is_nextafter_on_every_class)
{
    same_along(ray_offset_along_plain, along_reference, 25, 100000,
               "offset_along_plain_is_nextafter_on_every_class");
}
END_TEST

#ifdef SVET_SIMD
START_TEST(offset_along_simd_is_the_plain_bits)
{
    same_along(ray_offset_along_simd, ray_offset_along_plain, 27, 200000,
               "offset_along_simd_is_the_plain_bits");
}
END_TEST
#endif

START_TEST(spawn_to_stops_short_of_the_target)
{
    VECTOR3 p0 = { 0, 0, 0 }, p1 = { 0, 0, 10 }, e = { 0, 0, 0 };
    VECTOR3 n0 = { 0, 0, 1 }, n1 = { 0, 0, -1 };
    ray_t r;
    real tmax = ray_spawn_to(&r, p0, e, n0, p1, e, n1);
    VECTOR3 end;
    ray_at(end, &r, tmax);
    ck_assert(end[Z] < 10 && end[Z] > REAL_C(9.99));
    ray_at(end, &r, 1);
    ck_assert_near(end[Z], 10, 0);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("ray (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, gamma_matches_its_definition);
    tcase_add_test(tc, offset_origin_clears_the_error_box_on_the_side_of_w);
    tcase_add_test(tc, zero_error_still_moves_one_ulp);
    tcase_add_test(tc, spawn_to_stops_short_of_the_target);
    tcase_add_test(tc, offset_origin_is_nextafter_on_every_class);
    tcase_add_test(tc, offset_along_plain_is_nextafter_on_every_class);
#ifdef SVET_SIMD
    tcase_add_test(tc, offset_along_simd_is_the_plain_bits);
#endif
    suite_add_tcase(s, tc);
    return s;
}
