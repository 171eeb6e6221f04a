/*
 * test_plane.c - the infinite plane of app. D: exact hits, the open
 * interval, parallel and in-plane rays, bounds, area and sample of an
 * infinite shape, the geomcheck harness over a finite window of the plane,
 * tests/vectors/plane.csv, and a NaN sweep.
 */
#include "testutil.h"
#include "core/frame.h"
#include "geomcheck.h"
#include "geometry/plane.h"
#include "primcheck.h"

#include <stdlib.h>
#include <string.h>

static COBJECT *plane(real px, real py, real pz, real nx, real ny, real nz)
{
    VECTOR3 p = { px, py, pz }, n = { nx, ny, nz };
    svet_error err;
    COBJECT *o = plane_new(p, n, &err);
    ck_assert_msg(o != NULL, "%s", err.msg);
    return o;
}

START_TEST(plane_hit_has_exact_t_point_and_frame)
{
    COBJECT *o = plane(5, 5, 2, 0, 0, 3);
    ray_t r = { { REAL_C(1.25), REAL_C(-0.5), 5 }, { 0, 0, -2 } };
    hit_t h;
    ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
    ck_assert(h.t == REAL_C(1.5));
    PATHPOINT pp;
    cobject_fill(o, &r, &h, &pp);
    ck_assert(pp.cross_point[X] == REAL_C(1.25) &&
              pp.cross_point[Y] == REAL_C(-0.5) && pp.cross_point[Z] == 2);
    ck_assert(pp.ng[X] == 0 && pp.ng[Y] == 0 && pp.ng[Z] == 1);
    VECTOR3 fu, fv;
    frame_from_normal(fu, fv, pp.ng);
    ck_assert(memcmp(fu, pp.u, sizeof fu) == 0 &&
              memcmp(fv, pp.v, sizeof fv) == 0);
    ck_assert(memcmp(fu, pp.dpds, sizeof fu) == 0);
    /* st: plane coordinates (p - point) . u, . v modulo 1 */
    VECTOR3 w;
    vec_sub(w, pp.cross_point, (VECTOR3){ 5, 5, 2 });
    real s = SVECTOR3(w, fu), t = SVECTOR3(w, fv);
    ck_assert_near(pp.st[0], s - floor(s), 8 * REAL_EPSILON);
    ck_assert_near(pp.st[1], t - floor(t), 8 * REAL_EPSILON);
    ck_assert(pp.r_dist == 3 && pp.bout);
    cobject_free(o);
}
END_TEST

START_TEST(plane_tilted_hit_matches_the_plane_equation)
{
    /* the plane x + 2y + 2z = 9 (normal (1,2,2)/3 through (1,2,2)) */
    COBJECT *o = plane(1, 2, 2, 1, 2, 2);
    pcg32_t g;
    pcg32_seed(&g, 1, 2);
    long n = 0;
    for (int i = 0; i < 5000; i++, n++) {
        ray_t r;
        vec_set(r.o, 10 * pcg32_real(&g) - 5, 10 * pcg32_real(&g) - 5,
                10 * pcg32_real(&g) - 5);
        geomcheck_random_dir(r.d, &g);
        long double den = (long double)r.d[X] + 2.0L * r.d[Y] +
                          2.0L * r.d[Z];
        long double num = 9 - (long double)r.o[X] - 2.0L * r.o[Y] -
                          2.0L * r.o[Z];
        long double t = num / den;
        hit_t h;
        bool hit = cobject_intersect(o, &r, 0, (real)INFINITY, &h);
        if (fabsl(den) < 0.05L || fabsl(t) < 1e-3L)
            continue; /* ill-conditioned: skip the comparison */
        ck_assert_msg(hit == (t > 0), "ray %d: hit %d, t = %Lg", i, hit, t);
        if (!hit)
            continue;
        /* the numerator sums terms up to 9 + |o.x| + 2|o.y| + 2|o.z|, a few
         * roundings each (the normal (1,2,2)/3 itself carries one): its
         * error over |den| bounds t's */
        double mag = 9 + fabs((double)r.o[X]) + 2 * fabs((double)r.o[Y]) +
                     2 * fabs((double)r.o[Z]);
        ck_assert_near(h.t, (double)t,
                       16 * (double)REAL_EPSILON * mag / fabs((double)den));
        PATHPOINT pp;
        cobject_fill(o, &r, &h, &pp);
        double on = (double)pp.cross_point[X] + 2 * (double)pp.cross_point[Y] +
                    2 * (double)pp.cross_point[Z] - 9;
        /* the rebuilt point is on the plane within its error bound */
        ck_assert_msg(fabs(on) / 3 <= (double)pp.p_error[X] +
                          (double)pp.p_error[Y] + (double)pp.p_error[Z],
                      "ray %d: point %g off the plane, p_error %g", i,
                      fabs(on) / 3, (double)pp.p_error[X]);
        ck_assert(pp.st[0] >= 0 && pp.st[0] <= 1 && pp.st[1] >= 0 &&
                  pp.st[1] <= 1);
    }
    test_report_cases("plane_tilted_hit_matches_the_plane_equation", n);
    cobject_free(o);
}
END_TEST

START_TEST(plane_respects_the_open_interval_and_both_sides)
{
    COBJECT *o = plane(0, 0, 2, 0, 0, 1);
    ray_t r = { { 0, 0, 5 }, { 0, 0, -1 } }, back = { { 0, 0, -1 },
                                                      { 0, 0, 1 } };
    hit_t h;
    real inf = (real)INFINITY;
    ck_assert(!cobject_intersect(o, &r, 0, 3, &h));
    ck_assert(cobject_intersect(o, &r, 0, nextafter(REAL_C(3.0), inf), &h));
    ck_assert(!cobject_intersect(o, &r, 3, inf, &h));
    ck_assert(cobject_intersect(o, &r, nextafter(REAL_C(3.0), REAL_C(0.0)),
                                inf, &h));
    ck_assert(cobject_intersect(o, &back, 0, inf, &h) && h.t == 3);
    PATHPOINT pp;
    cobject_fill(o, &back, &h, &pp);
    ck_assert(pp.ng[Z] == 1 && !pp.bout);
    /* pointing away */
    ray_t away = { { 0, 0, 5 }, { 0, REAL_C(0.1), 1 } };
    ck_assert(!cobject_intersect(o, &away, 0, inf, &h));
    cobject_free(o);
}
END_TEST

START_TEST(rays_parallel_to_the_plane_or_in_it_never_hit)
{
    COBJECT *o = plane(0, 0, 2, 0, 0, 1);
    hit_t h;
    real inf = (real)INFINITY;
    ray_t above = { { 0, 0, 3 }, { 1, 1, 0 } }, in = { { 0, 0, 2 },
                                                      { 1, -2, 0 } };
    ck_assert(!cobject_intersect(o, &above, 0, inf, &h));
    ck_assert(!cobject_intersect(o, &in, 0, inf, &h));
    ck_assert(!cobject_intersect(o, &in, -inf, inf, &h));
    cobject_free(o);
    /* a tilted plane and rays whose origin and direction lie in it
     * exactly (small integers): the origin is on the plane, so no hit */
    COBJECT *t = plane(1, 2, 2, 1, 2, 2);
    pcg32_t g;
    pcg32_seed(&g, 3, 4);
    long n = 0;
    for (int i = 0; i < 20000; i++, n++) {
        /* (a, b, c) with a + 2b + 2c = 9, and d with d.x + 2 d.y + 2 d.z = 0 */
        real b = (real)(int)pcg32_bounded(&g, 21) - 10;
        real c = (real)(int)pcg32_bounded(&g, 21) - 10;
        real dy = (real)(int)pcg32_bounded(&g, 21) - 10;
        real dz = (real)(int)pcg32_bounded(&g, 21) - 10;
        if (dy == 0 && dz == 0)
            dy = 1;
        ray_t r = { { 9 - 2 * b - 2 * c, b, c }, { -2 * dy - 2 * dz, dy, dz } };
        ck_assert(!cobject_intersect(t, &r, 0, inf, &h));
    }
    test_report_cases("rays_parallel_to_the_plane_or_in_it_never_hit", n);
    cobject_free(t);
}
END_TEST

START_TEST(plane_bounds_area_and_sample_of_an_infinite_shape)
{
    COBJECT *o = plane(1, 2, 3, 0, -4, 0);
    bbox_t b;
    o->ops->bounds(o, -1, &b);
    ck_assert(b.min[Y] == 2 && b.max[Y] == 2);
    ck_assert(b.min[X] == -REAL_MAX && b.max[X] == REAL_MAX);
    ck_assert(b.min[Z] == -REAL_MAX && b.max[Z] == REAL_MAX);
    ck_assert(isinf(o->ops->area(o)));
    real u[2] = { REAL_C(0.5), REAL_C(0.5) };
    cobject_sample_t s;
    o->ops->sample(o, u, &s);
    ck_assert(s.pdf == 0 && s.p[X] == 1 && s.p[Y] == 2 && s.p[Z] == 3);
    ck_assert(s.n[Y] == -1);
    cobject_free(o);
    COBJECT *t = plane(0, 0, 0, 1, 1, 0);
    t->ops->bounds(t, -1, &b);
    for (int k = 0; k < 3; k++)
        ck_assert(b.min[k] == -REAL_MAX && b.max[k] == REAL_MAX);
    cobject_free(t);
}
END_TEST

START_TEST(plane_rejects_bad_input)
{
    VECTOR3 p = { 0, 0, 0 }, n = { 0, 0, 1 }, z = { 0, 0, 0 },
            nan = { (real)NAN, 0, 0 }, inf = { 0, (real)INFINITY, 0 };
    svet_error err;
    ck_assert_ptr_null(plane_new(p, z, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_msg(strstr(err.msg, "zero") != NULL, "%s", err.msg);
    ck_assert_ptr_null(plane_new(nan, n, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_ptr_null(plane_new(p, inf, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_ptr_null(plane_new(p, z, NULL));
}
END_TEST

/* --- the harness on a finite window of the plane --------------------------- *
 * geomcheck needs finite bounds and a uniform sampler; the window wraps a
 * plane, passes intersect and surface through to it, and gives bounds and
 * samples of the square [-half, half]^2 in the plane's frame. Spawned
 * rays must miss the whole (infinite) plane, not only the window. */
typedef struct {
    COBJECT *plane;
    VECTOR3 p0, n, u, v;
    real half;
} window_t;

static bool win_intersect(const COBJECT *obj, int prim, const ray_t *r,
                          real tmin, real tmax, hit_t *hit)
{
    const window_t *w = obj->shape;
    return w->plane->ops->intersect(w->plane, prim, r, tmin, tmax, hit);
}

static void win_surface(const COBJECT *obj, const ray_t *r, const hit_t *hit,
                        PATHPOINT *pp)
{
    const window_t *w = obj->shape;
    w->plane->ops->surface(w->plane, r, hit, pp);
}

static void win_bounds(const COBJECT *obj, int prim, bbox_t *b)
{
    (void)prim;
    const window_t *w = obj->shape;
    for (int k = 0; k < 3; k++) {
        real e = w->half * (fabs(w->u[k]) + fabs(w->v[k]));
        b->min[k] = w->p0[k] - e;
        b->max[k] = w->p0[k] + e;
    }
}

static real win_area(const COBJECT *obj)
{
    const window_t *w = obj->shape;
    return 4 * w->half * w->half;
}

static void win_sample(const COBJECT *obj, const real u[2],
                       cobject_sample_t *s)
{
    const window_t *w = obj->shape;
    real a = (2 * u[0] - 1) * w->half, b = (2 * u[1] - 1) * w->half;
    for (int k = 0; k < 3; k++) {
        real au = a * w->u[k], bv = b * w->v[k];
        s->p[k] = w->p0[k] + au + bv;
        /* as plane.c: gamma(3) of the terms, plus the frame's tilt off
         * the plane, at most a few units of roundoff times |a| + |b| */
        s->p_error[k] = ray_gamma(3) * (fabs(w->p0[k]) + fabs(au) + fabs(bv))
                        + 4 * REAL_EPSILON * (fabs(a) + fabs(b));
    }
    vec_copy(s->n, w->n);
    s->pdf = 1 / win_area(obj);
}

static void win_destroy(COBJECT *obj)
{
    window_t *w = obj->shape;
    cobject_free(w->plane);
    free(w);
}

static const cobject_ops window_ops = { "plane", win_intersect, win_surface,
                                        win_bounds, win_area, win_sample,
                                        win_destroy, NULL };

static COBJECT *make_window(real s, const VECTOR3 c, void *ctx)
{
    (void)ctx;
    window_t *w = malloc(sizeof *w);
    COBJECT *o = malloc(sizeof *o);
    ck_assert(w && o);
    VECTOR3 n = { REAL_C(0.36), REAL_C(-0.48), REAL_C(0.8) };
    w->plane = plane(c[X], c[Y], c[Z], n[X], n[Y], n[Z]);
    vec_copy(w->p0, c);
    vec_normalize(w->n, n);
    frame_from_normal(w->u, w->v, w->n);
    w->half = s;
    cobject_init(o, &window_ops, w);
    return o;
}

START_TEST(plane_spawned_rays_never_rehit_at_any_scale)
{
    test_report_cases("plane_spawned_rays_never_rehit_at_any_scale",
                      primcheck_over_scales(make_window, NULL, PRIMCHECK_SPAWN,
                                            GEOMCHECK_FLAT, true, 100));
}
END_TEST

START_TEST(plane_points_aimed_at_are_hit_at_any_scale)
{
    test_report_cases("plane_points_aimed_at_are_hit_at_any_scale",
                      primcheck_over_scales(make_window, NULL,
                                            PRIMCHECK_SAMPLED, GEOMCHECK_FLAT,
                                            true, 200));
}
END_TEST

START_TEST(plane_hits_are_finite_at_any_scale)
{
    test_report_cases("plane_hits_are_finite_at_any_scale",
                      primcheck_over_scales(make_window, NULL,
                                            PRIMCHECK_FINITE, GEOMCHECK_FLAT,
                                            true, 300));
}
END_TEST

START_TEST(plane_matches_the_reference_vectors)
{
    testcsv_t c;
    testcsv_open(&c, "plane.csv");
    long n = 0;
    for (; testcsv_next(&c); n++) {
        VECTOR3 p, nn;
        primcheck_csv_vec(&c, "p", p);
        primcheck_csv_vec(&c, "n", nn);
        COBJECT *o = plane(p[X], p[Y], p[Z], nn[X], nn[Y], nn[Z]);
        PATHPOINT pp;
        primcheck_csv_hit(&c, o, "q", "e", &pp);
        cobject_free(o);
    }
    testcsv_close(&c);
    ck_assert_int_gt(n, 0);
    test_report_cases("plane_matches_the_reference_vectors", n);
}
END_TEST

START_TEST(plane_sweep_never_returns_nan_or_inf)
{
    pcg32_t g;
    pcg32_seed(&g, 14, 15);
    long n = 0;
    for (int i = 0; i < 100; i++) {
        real s = ldexp(REAL_C(1.0), (int)pcg32_bounded(&g, 100) - 50);
        VECTOR3 p, nn;
        for (int k = 0; k < 3; k++)
            p[k] = s * (2 * pcg32_real(&g) - 1);
        geomcheck_random_dir(nn, &g);
        if (i % 3 == 0)
            vec_set(nn, 0, 0, i % 2 ? 1 : -1);
        COBJECT *o = plane(p[X], p[Y], p[Z], nn[X], nn[Y], nn[Z]);
        n += primcheck_sweep_finite(o, 2000, (uint64_t)i);
        cobject_free(o);
    }
    test_report_cases("plane_sweep_never_returns_nan_or_inf", n);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("plane");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, plane_hit_has_exact_t_point_and_frame);
    tcase_add_test(tc, plane_tilted_hit_matches_the_plane_equation);
    tcase_add_test(tc, plane_respects_the_open_interval_and_both_sides);
    tcase_add_test(tc, rays_parallel_to_the_plane_or_in_it_never_hit);
    tcase_add_test(tc, plane_bounds_area_and_sample_of_an_infinite_shape);
    tcase_add_test(tc, plane_rejects_bad_input);
    tcase_add_test(tc, plane_spawned_rays_never_rehit_at_any_scale);
    tcase_add_test(tc, plane_points_aimed_at_are_hit_at_any_scale);
    tcase_add_test(tc, plane_hits_are_finite_at_any_scale);
    tcase_add_test(tc, plane_matches_the_reference_vectors);
    tcase_add_test(tc, plane_sweep_never_returns_nan_or_inf);
    suite_add_tcase(s, tc);
    return s;
}
