/*
 * test_sphere.c - the sphere of app. D: exact hits and misses, the open
 * interval (tmin, tmax), tangent rays, the error bound of hit points, the
 * surface parameters, area and sampling, the geomcheck harness at every
 * scale, tests/vectors/sphere.csv, and a sweep for NaN and Inf.
 */
#include "quadcheck.h"
#include "geometry/sphere.h"

#include <math.h>
#include <string.h>

static COBJECT *make_sphere(real scale, const VECTOR3 centre, void *ctx)
{
    (void)ctx;
    svet_error err;
    COBJECT *obj = sphere_new(centre, scale, &err);
    ck_assert_msg(obj != NULL, "sphere_new: %s", err.msg);
    return obj;
}

static COBJECT *new_sphere(real cx, real cy, real cz, real r)
{
    VECTOR3 c = { cx, cy, cz };
    return make_sphere(r, c, NULL);
}

START_TEST(sphere_new_rejects_bad_input)
{
    VECTOR3 c = { 1, 2, 3 }, bad = { 1, (real)NAN, 3 };
    VECTOR3 inf = { 0, 0, (real)INFINITY };
    const real radii[] = { 0, -1, (real)NAN, (real)INFINITY, -(real)INFINITY,
                           REAL_MAX / 2, REAL_MIN / 4 };
    svet_error err;
    for (int i = 0; i < 7; i++) {
        svet_error_clear(&err);
        ck_assert_ptr_null(sphere_new(c, radii[i], &err));
        ck_assert_int_eq(err.status, SVET_ERR_RANGE);
        ck_assert_msg(strstr(err.msg, "sphere") != NULL, "%s", err.msg);
    }
    ck_assert_ptr_null(sphere_new(bad, 1, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_ptr_null(sphere_new(inf, 1, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_ptr_null(sphere_new(c, -1, NULL)); /* err may be NULL */
    COBJECT *obj = sphere_new(c, 2, &err);
    ck_assert_ptr_nonnull(obj);
    ck_assert_int_eq(obj->nprims, 1);
    ck_assert_str_eq(obj->ops->name, "sphere");
    cobject_free(obj);
}
END_TEST

START_TEST(ray_along_an_axis_hits_at_the_known_t)
{
    COBJECT *s = new_sphere(1, 2, 3, 2);
    PATHPOINT pp;
    /* from x = -9 toward +x: the surface is at x = -1, t = 8 */
    ray_t r = quadcheck_ray(-9, 2, 3, 1, 0, 0);
    ck_assert(quadcheck_trace(s, &r, 0, (real)INFINITY, &pp));
    ck_assert_near(pp.r_dist, 8, 8 * REAL_EPSILON * 8);
    ck_assert_near(pp.cross_point[X], -1, 0);
    ck_assert_near(pp.cross_point[Y], 2, 0);
    ck_assert_near(pp.cross_point[Z], 3, 0);
    ck_assert_near(pp.ng[X], -1, 0);
    ck_assert(pp.bout);
    /* a direction of length 4: t is parametric, 2; r_dist stays 8 */
    r = quadcheck_ray(-9, 2, 3, 4, 0, 0);
    hit_t h;
    ck_assert(cobject_intersect(s, &r, 0, (real)INFINITY, &h));
    ck_assert_near(h.t, 2, 4 * REAL_EPSILON);
    /* down the z axis onto the north pole: t = 10 - 5 = 5 */
    r = quadcheck_ray(1, 2, 10, 0, 0, -1);
    ck_assert(quadcheck_trace(s, &r, 0, (real)INFINITY, &pp));
    ck_assert_near(pp.r_dist, 5, 8 * REAL_EPSILON * 5);
    ck_assert_near(pp.ng[Z], 1, 0);
    ck_assert_near(pp.st[1], 0, 0); /* t = theta / pi = 0 at the pole */
    /* misses: beside the sphere, and pointing away from it */
    r = quadcheck_ray(-9, 2 + REAL_C(2.01), 3, 1, 0, 0);
    ck_assert(!cobject_intersect(s, &r, 0, (real)INFINITY, &h));
    r = quadcheck_ray(-9, 2, 3, -1, 0, 0);
    ck_assert(!cobject_intersect(s, &r, 0, (real)INFINITY, &h));
    cobject_free(s);
}
END_TEST

START_TEST(tmin_and_tmax_bound_the_hit_and_inside_gives_the_far_hit)
{
    COBJECT *s = new_sphere(0, 0, 0, 2);
    ray_t r = quadcheck_ray(-10, 0, 0, 1, 0, 0); /* hits at t = 8 and 12 */
    hit_t h;
    ck_assert(!cobject_intersect(s, &r, 0, 8, &h)); /* t == tmax: open */
    ck_assert(cobject_intersect(s, &r, 0, nextafter(REAL_C(8.0), REAL_C(9.0)),
                                &h));
    ck_assert_near(h.t, 8, 0);
    ck_assert(cobject_intersect(s, &r, 8, 100, &h)); /* t == tmin: open */
    ck_assert_near(h.t, 12, 0);
    ck_assert(!cobject_intersect(s, &r, 12, 100, &h));
    ck_assert(!cobject_intersect(s, &r, 13, 100, &h));
    ck_assert(!cobject_intersect(s, &r, 0, 5, &h));
    /* from the centre: only the far side, whose normal faces the ray */
    r = quadcheck_ray(0, 0, 0, 0, 1, 0);
    PATHPOINT pp;
    ck_assert(quadcheck_trace(s, &r, 0, (real)INFINITY, &pp));
    ck_assert_near(pp.r_dist, 2, 0);
    ck_assert_near(pp.ng[Y], 1, 0);
    ck_assert(!pp.bout);
    /* from inside but off centre, backwards */
    r = quadcheck_ray(1, 0, 0, -1, 0, 0);
    ck_assert(quadcheck_trace(s, &r, 0, (real)INFINITY, &pp));
    ck_assert_near(pp.r_dist, 3, 0);
    cobject_free(s);
}
END_TEST

/* A ray along +x at height y past a sphere of radius r at the origin:
 * exactly tangent when y = r. */
static void check_tangent(COBJECT *s, real r, real y, bool must_hit,
                          bool must_miss)
{
    ray_t ray = quadcheck_ray(-10 * r, y, 0, 1, 0, 0);
    PATHPOINT pp;
    bool hit = quadcheck_trace(s, &ray, 0, (real)INFINITY, &pp);
    ck_assert_msg(!(must_hit && !hit), "tangent y = %.9g: no hit", (double)y);
    ck_assert_msg(!(must_miss && hit), "tangent y = %.9g: hit", (double)y);
    if (!hit)
        return;
    quadcheck_assert_finite(&pp, "tangent");
    /* The near root is 10 r - sqrt(r^2 - y^2); the discriminant r^2 - y^2
     * is known to a few ulps of r^2, which moves the root by up to
     * sqrt(4 eps) r about the tangent. The normal there is within the
     * same angle of +y. */
    double rd = (double)r, yd = (double)y;
    double w = sqrt(fmax(0.0, rd * rd - yd * yd));
    double slack = 2 * sqrt((double)REAL_EPSILON) * rd;
    ck_assert_near(pp.r_dist, 10 * rd - w, slack);
    ck_assert_near(pp.ng[Y], 1, (w + slack) / rd);
    ck_assert_near(vec_length(pp.cross_point), r, 8 * REAL_EPSILON * r);
}

START_TEST(rays_tangent_to_the_sphere_give_no_nan)
{
    const real radii[] = { 1, REAL_C(0.75), 3, REAL_C(1e-3), REAL_C(1e4) };
    for (int i = 0; i < 5; i++) {
        real r = radii[i];
        COBJECT *s = new_sphere(0, 0, 0, r);
        /* exactly tangent: the double root t = 10 r (r = 1, 0.75 and 3
         * make r^2 and y^2 exact, so the discriminant is exactly 0) */
        check_tangent(s, r, r, i < 3, false);
        check_tangent(s, r, nextafter(r, REAL_C(0.0)), i < 3, false);
        check_tangent(s, r, nextafter(r, 2 * r), false, i < 3);
        check_tangent(s, r, r * (1 + 64 * REAL_EPSILON), false, true);
        check_tangent(s, r, r * (1 - 64 * REAL_EPSILON), true, false);
        cobject_free(s);
    }
    /* tangent from the tangent point itself, and from the surface with
     * the direction in the tangent plane */
    COBJECT *s = new_sphere(0, 0, 0, 1);
    ray_t r = quadcheck_ray(0, 1, 0, 1, 0, 0);
    hit_t h;
    ck_assert(!cobject_intersect(s, &r, 0, (real)INFINITY, &h));
    ck_assert(!cobject_intersect(s, &r, -1, (real)INFINITY, &h) ||
              isfinite(h.t));
    cobject_free(s);
}
END_TEST

/* Distance of p from the exact sphere of make_sphere, in long double. */
static long double sphere_distance(const VECTOR3 p, real r,
                                   const VECTOR3 c, void *ctx)
{
    (void)ctx;
    long double d2 = 0;
    for (int k = 0; k < 3; k++) {
        long double d = (long double)p[k] - (long double)c[k];
        d2 += d * d;
    }
    return fabsl(sqrtl(d2) - (long double)r);
}

START_TEST(hit_and_sampled_points_are_within_their_error_bound)
{
    test_report_cases("hit_and_sampled_points_are_within_their_error_bound",
                      quadcheck_error_bound(make_sphere, sphere_distance,
                                            NULL, 2000, 31));
}
END_TEST

START_TEST(surface_parameters_and_frame_follow_the_documented_map)
{
    VECTOR3 c = { REAL_C(0.5), -1, 2 };
    const real r = REAL_C(1.5);
    COBJECT *s = make_sphere(r, c, NULL);
    pcg32_t g;
    pcg32_seed(&g, 41, 42);
    long cases = 0;
    for (int k = 0; k < 5000; k++, cases++) {
        ray_t ray;
        VECTOR3 dir;
        geomcheck_random_dir(dir, &g);
        vec_add_scaled(ray.o, c, 5 * r, dir);
        vec_sub(ray.d, c, ray.o);
        geomcheck_random_dir(dir, &g);
        vec_add_scaled(ray.d, ray.d, r * pcg32_real(&g), dir);
        PATHPOINT pp;
        if (k == 0) /* straight onto the north pole */
            ray = quadcheck_ray(c[X], c[Y], c[Z] + 5, 0, 0, -1);
        ck_assert(quadcheck_trace(s, &ray, 0, (real)INFINITY, &pp));
        /* P(s, t) = c + r (sin theta cos phi, sin theta sin phi, cos theta)
         * with phi = 2 pi s, theta = pi t (sphere.h), in double */
        const double pi = QUADCHECK_PI, rd = (double)r;
        double phi = 2 * pi * (double)pp.st[0], th = pi * (double)pp.st[1];
        double P[3] = { (double)c[X] + rd * sin(th) * cos(phi),
                        (double)c[Y] + rd * sin(th) * sin(phi),
                        (double)c[Z] + rd * cos(th) };
        double dPds[3] = { -2 * pi * rd * sin(th) * sin(phi),
                           2 * pi * rd * sin(th) * cos(phi), 0 };
        double dPdt[3] = { pi * rd * cos(th) * cos(phi),
                           pi * rd * cos(th) * sin(phi), -pi * rd * sin(th) };
        for (int i = 0; i < 3; i++) {
            ck_assert_near(pp.cross_point[i], P[i], 64 * REAL_EPSILON * r);
            ck_assert_near(pp.dpds[i], dPds[i], 64 * REAL_EPSILON * r);
            ck_assert_near(pp.dpdt[i], dPdt[i], 64 * REAL_EPSILON * r);
        }
        /* u along dP/ds (where it does not vanish), u x v = n = ng */
        VECTOR3 uxv;
        VVECTOR3(uxv, pp.u, pp.v);
        for (int i = 0; i < 3; i++) {
            ck_assert_near(uxv[i], pp.n[i], 16 * REAL_EPSILON);
            ck_assert_near(pp.n[i], pp.ng[i], 0);
        }
        real ls = vec_length(pp.dpds);
        if (ls > REAL_C(1e-3) * r)
            ck_assert_near(SVECTOR3(pp.u, pp.dpds), ls, 64 * REAL_EPSILON * r);
        ck_assert_near(SVECTOR3(pp.u, pp.n), 0, 16 * REAL_EPSILON);
    }
    cobject_free(s);
    test_report_cases("surface_parameters_and_frame_follow_the_documented_map",
                      cases);
}
END_TEST

START_TEST(bounds_are_tight_and_area_is_4_pi_r_squared)
{
    COBJECT *s = new_sphere(1, -2, 3, REAL_C(0.5));
    bbox_t b;
    s->ops->bounds(s, -1, &b);
    const real lo[] = { REAL_C(0.5), REAL_C(-2.5), REAL_C(2.5) };
    const real hi[] = { REAL_C(1.5), REAL_C(-1.5), REAL_C(3.5) };
    for (int k = 0; k < 3; k++) {
        ck_assert(b.min[k] <= lo[k] && b.min[k] >= lo[k] - 4 * REAL_EPSILON);
        ck_assert(b.max[k] >= hi[k] && b.max[k] <= hi[k] + 4 * REAL_EPSILON);
    }
    ck_assert_rel(s->ops->area(s), QUADCHECK_PI, 2 * REAL_EPSILON, 0);
    cobject_free(s);
    s = new_sphere(0, 0, 0, 3);
    ck_assert_rel(s->ops->area(s), 36 * QUADCHECK_PI, 2 * REAL_EPSILON, 0);
    cobject_free(s);
}
END_TEST

typedef struct {
    VECTOR3 c;
    real r;
    int axis;
} coord_ctx;

/* Archimedes (On the Sphere and Cylinder I, 33-34): the area of a zone of
 * the sphere is 2 pi r h, so a uniform point has z uniform in [-r, r] and
 * (z + r) / 2r is U(0,1); so is every axis, by symmetry. */
static double z_cdf(const cobject_sample_t *s, void *ctx)
{
    const coord_ctx *k = ctx;
    return ((double)s->p[k->axis] - (double)k->c[k->axis] + (double)k->r) /
           (2 * (double)k->r);
}

static double phi_cdf(const cobject_sample_t *s, void *ctx)
{
    const coord_ctx *k = ctx;
    return atan2((double)s->p[Y] - (double)k->c[Y],
                 (double)s->p[X] - (double)k->c[X]) / (2 * QUADCHECK_PI) + 0.5;
}

START_TEST(sampled_coordinates_are_uniform_as_archimedes_says)
{
    coord_ctx k = { { 1, 2, -3 }, 2, Z };
    COBJECT *s = make_sphere(k.r, k.c, NULL);
    quadcheck_ks(s, 200000, 5, z_cdf, &k, "sampled_z_is_uniform");
    k.axis = X;
    quadcheck_ks(s, 200000, 6, z_cdf, &k, "sampled_x_is_uniform");
    quadcheck_ks(s, 200000, 7, phi_cdf, &k, "sampled_phi_is_uniform");
    cobject_free(s);
}
END_TEST

/* The harness: a sphere is CONVEX. */
static const geomcheck_kind kinds[1] = { GEOMCHECK_CONVEX };

static const quadcheck_shape_t harness = {
    .name = "sphere", .make = make_sphere, .n = 1, .kinds = kinds,
    .seed = { [PRIMCHECK_SPAWN] = 1, [PRIMCHECK_SAMPLED] = 2,
              [PRIMCHECK_SHADOW] = 3, [PRIMCHECK_FINITE] = 4,
              [PRIMCHECK_AREA] = 5 },
    .sweep_rays = 20000, .sweep_seed = 6
};

static COBJECT *sphere_row(testcsv_t *c)
{
    VECTOR3 centre;
    primcheck_csv_vec(c, "c", centre);
    return sphere_new(centre, (real)testcsv_num(c, "radius"), NULL);
}

START_TEST(hits_match_the_long_double_vectors)
{
    quadcheck_vectors("sphere.csv", sphere_row,
                      "hits_match_the_long_double_vectors");
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("sphere (" REAL_NAME ")");
    TCase *tc = tcase_create("exact");
    tcase_add_test(tc, sphere_new_rejects_bad_input);
    tcase_add_test(tc, ray_along_an_axis_hits_at_the_known_t);
    tcase_add_test(tc,
                   tmin_and_tmax_bound_the_hit_and_inside_gives_the_far_hit);
    tcase_add_test(tc, rays_tangent_to_the_sphere_give_no_nan);
    tcase_add_test(tc, bounds_are_tight_and_area_is_4_pi_r_squared);
    tcase_add_test(tc, hits_match_the_long_double_vectors);
    suite_add_tcase(s, tc);
    TCase *tr = tcase_create("random");
    tcase_set_timeout(tr, 120);
    tcase_add_test(tr, hit_and_sampled_points_are_within_their_error_bound);
    tcase_add_test(tr, surface_parameters_and_frame_follow_the_documented_map);
    tcase_add_test(tr, sampled_coordinates_are_uniform_as_archimedes_says);
    quadcheck_add_harness(tr, &harness);
    suite_add_tcase(s, tr);
    return s;
}
