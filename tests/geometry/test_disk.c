/*
 * test_disk.c - the disk of app. D: exact hits from both sides, misses,
 * the open interval (tmin, tmax), rays parallel to the disk, the error
 * bound of hit points, the surface parameters, area and sampling, the
 * geomcheck harness at every scale, tests/vectors/disk.csv, and a sweep
 * for NaN and Inf.
 */
#include "geometry/disk.h"
#include "core/frame.h"
#include "quadcheck.h"

#include <math.h>
#include <string.h>

/* The normals of the two placements: along z, and tilted. */
static const real normals[2][3] = { { 0, 0, 1 },
                                    { REAL_C(0.48), REAL_C(-0.6),
                                      REAL_C(0.64) } };

/* ctx: an int, the placement (0 or 1). */
static COBJECT *make_disk(real scale, const VECTOR3 centre, void *ctx)
{
    int variant = ctx ? *(const int *)ctx : 0;
    svet_error err;
    COBJECT *obj = disk_new(centre, normals[variant], scale, &err);
    ck_assert_msg(obj != NULL, "disk_new: %s", err.msg);
    return obj;
}

static COBJECT *new_disk(real cx, real cy, real cz, real nx, real ny,
                         real nz, real radius)
{
    VECTOR3 c = { cx, cy, cz }, n = { nx, ny, nz };
    svet_error err;
    COBJECT *obj = disk_new(c, n, radius, &err);
    ck_assert_msg(obj != NULL, "disk_new: %s", err.msg);
    return obj;
}

START_TEST(disk_new_rejects_bad_input)
{
    VECTOR3 c = { 1, 2, 3 }, n = { 0, 0, 2 }, zero = { 0, 0, 0 };
    VECTOR3 bad = { (real)NAN, 0, 1 }, inf = { 0, -(real)INFINITY, 0 };
    svet_error err;
    const real radii[] = { 0, -2, (real)NAN, (real)INFINITY, REAL_MAX / 2,
                           REAL_MIN / 4 };
    for (int i = 0; i < 6; i++) {
        svet_error_clear(&err);
        ck_assert_ptr_null(disk_new(c, n, radii[i], &err));
        ck_assert_int_eq(err.status, SVET_ERR_RANGE);
        ck_assert_msg(strstr(err.msg, "disk") != NULL, "%s", err.msg);
    }
    ck_assert_ptr_null(disk_new(c, zero, 1, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_ptr_null(disk_new(c, bad, 1, &err));
    ck_assert_ptr_null(disk_new(bad, n, 1, &err));
    ck_assert_ptr_null(disk_new(inf, n, 1, &err));
    ck_assert_ptr_null(disk_new(c, inf, 1, NULL));
    COBJECT *obj = disk_new(c, n, 1, &err);
    ck_assert_ptr_nonnull(obj);
    ck_assert_str_eq(obj->ops->name, "disk");
    ck_assert_int_eq(obj->nprims, 1);
    cobject_free(obj);
}
END_TEST

START_TEST(rays_along_the_normal_hit_at_the_known_t_from_either_side)
{
    COBJECT *d = new_disk(0, 0, 1, 0, 0, 3, 2);
    PATHPOINT pp;
    ray_t r = quadcheck_ray(REAL_C(0.5), REAL_C(0.5), 5, 0, 0, -1);
    ck_assert(quadcheck_trace(d, &r, 0, (real)INFINITY, &pp));
    ck_assert_near(pp.r_dist, 4, 0);
    ck_assert_near(pp.cross_point[X], 0.5, 0);
    ck_assert_near(pp.cross_point[Y], 0.5, 0);
    ck_assert_near(pp.cross_point[Z], 1, 0);
    ck_assert(pp.ng[X] == 0 && pp.ng[Y] == 0 && pp.ng[Z] == 1);
    ck_assert(pp.bout);
    /* from below, direction of length 2: t = 2, the normal unchanged */
    r = quadcheck_ray(REAL_C(0.5), REAL_C(0.5), -3, 0, 0, 2);
    hit_t h;
    ck_assert(cobject_intersect(d, &r, 0, (real)INFINITY, &h));
    ck_assert_near(h.t, 2, 0);
    ck_assert(quadcheck_trace(d, &r, 0, (real)INFINITY, &pp));
    ck_assert(pp.ng[Z] == 1 && !pp.bout);
    /* the rim is part of the disk; just outside it is not */
    r = quadcheck_ray(2, 0, 5, 0, 0, -1);
    ck_assert(cobject_intersect(d, &r, 0, (real)INFINITY, &h));
    r = quadcheck_ray(nextafter(REAL_C(2.0), REAL_C(3.0)), 0, 5, 0, 0, -1);
    ck_assert(!cobject_intersect(d, &r, 0, (real)INFINITY, &h));
    /* pointing away */
    r = quadcheck_ray(0, 0, 5, 0, 0, 1);
    ck_assert(!cobject_intersect(d, &r, 0, (real)INFINITY, &h));
    cobject_free(d);
    /* tilted: normal (1, 1, 0), centre (1, -1, 2): from (4, 2, 2) along
     * (-1, -1, 0) the plane is reached at t = 3, at the centre */
    d = new_disk(1, -1, 2, 1, 1, 0, REAL_C(1.5));
    r = quadcheck_ray(4, 2, 2, -1, -1, 0);
    ck_assert(quadcheck_trace(d, &r, 0, (real)INFINITY, &pp));
    ck_assert_near(pp.r_dist / vec_length(r.d), 3, 4 * REAL_EPSILON);
    ck_assert_near(pp.cross_point[X], 1, 8 * REAL_EPSILON);
    ck_assert_near(pp.ng[X], sqrt(0.5), 2 * REAL_EPSILON);
    cobject_free(d);
}
END_TEST

START_TEST(tmin_and_tmax_bound_the_hit)
{
    COBJECT *d = new_disk(0, 0, 0, 0, 1, 0, 1);
    ray_t r = quadcheck_ray(0, -4, 0, 0, 1, 0); /* hit at t = 4 */
    hit_t h;
    ck_assert(!cobject_intersect(d, &r, 0, 4, &h));
    ck_assert(cobject_intersect(d, &r, 0, nextafter(REAL_C(4.0), REAL_C(5.0)),
                                &h));
    ck_assert(!cobject_intersect(d, &r, 4, 10, &h));
    ck_assert(cobject_intersect(d, &r, nextafter(REAL_C(4.0), REAL_C(0.0)),
                                10, &h));
    ck_assert_near(h.t, 4, 0);
    /* from the disk itself: t = 0 is not in (0, inf) */
    r = quadcheck_ray(0, 0, 0, 0, 1, 0);
    ck_assert(!cobject_intersect(d, &r, 0, (real)INFINITY, &h));
    cobject_free(d);
}
END_TEST

START_TEST(rays_parallel_to_the_disk_miss_without_nan)
{
    COBJECT *d = new_disk(0, 0, 1, 0, 0, 1, 2);
    const real heights[] = { 1, nextafter(REAL_C(1.0), REAL_C(2.0)),
                             nextafter(REAL_C(1.0), REAL_C(0.0)), 3 };
    hit_t h;
    for (int i = 0; i < 4; i++) {
        ray_t r = quadcheck_ray(-5, 0, heights[i], 1, 0, 0);
        ck_assert(!cobject_intersect(d, &r, 0, (real)INFINITY, &h));
        ck_assert(!cobject_intersect(d, &r, -(real)INFINITY, (real)INFINITY,
                                     &h));
    }
    /* nearly parallel: a hit far along the ray, finite, on the disk */
    long cases = 0;
    for (int e = 4; e < 60; e++, cases++) {
        real dz = -ldexp(REAL_C(1.0), -e);
        ray_t r = quadcheck_ray(-1, 0, 1 - dz, 1, 0, dz);
        PATHPOINT pp;
        if (quadcheck_trace(d, &r, 0, (real)INFINITY, &pp)) {
            quadcheck_assert_finite(&pp, "grazing");
            ck_assert_near(pp.cross_point[Z], 1, 4 * REAL_EPSILON);
            ck_assert_near(pp.cross_point[X], 0, 8 * REAL_EPSILON);
        }
    }
    test_report_cases("rays_parallel_to_the_disk_miss_without_nan", cases);
    cobject_free(d);
}
END_TEST

/* Distance in long double from p to the disk of make_disk. */
static long double disk_distance(const VECTOR3 p, real radius,
                                 const VECTOR3 c, void *ctx)
{
    const real *nr = normals[ctx ? *(const int *)ctx : 0];
    long double n[3], nl = 0, q[3], h = 0, rho2 = 0;
    for (int k = 0; k < 3; k++) {
        n[k] = (long double)nr[k];
        nl += n[k] * n[k];
    }
    nl = sqrtl(nl);
    for (int k = 0; k < 3; k++) {
        q[k] = (long double)p[k] - (long double)c[k];
        h += q[k] * n[k] / nl;
    }
    for (int k = 0; k < 3; k++) {
        long double t = q[k] - h * n[k] / nl;
        rho2 += t * t;
    }
    long double out = fmaxl(sqrtl(rho2) - (long double)radius, 0);
    return sqrtl(h * h + out * out);
}

START_TEST(hit_and_sampled_points_are_within_their_error_bound)
{
    long cases = 0;
    for (int v = 0; v < 2; v++)
        cases += quadcheck_error_bound(make_disk, disk_distance, &v, 2000,
                                       (uint64_t)(51 + v));
    test_report_cases("hit_and_sampled_points_are_within_their_error_bound",
                      cases);
}
END_TEST

START_TEST(surface_parameters_and_frame_follow_the_documented_map)
{
    VECTOR3 c = { REAL_C(0.5), -1, 2 };
    const real R = REAL_C(1.5);
    int v = 1;
    COBJECT *d = make_disk(R, c, &v);
    VECTOR3 n, e1, e2;
    vec_normalize(n, normals[1]);
    frame_from_normal(e1, e2, n);
    pcg32_t g;
    pcg32_seed(&g, 61, 62);
    long cases = 0;
    for (int k = 0; k < 5000; k++, cases++) {
        ray_t r;
        VECTOR3 dir;
        geomcheck_random_hemisphere(dir, n, &g);
        vec_add_scaled(r.o, c, 3 * R, dir);
        real rho = R * sqrt(pcg32_real(&g)), a = 2 * REAL_PI * pcg32_real(&g);
        VECTOR3 target;
        vec_add_scaled(target, c, rho * cos(a), e1);
        vec_add_scaled(target, target, rho * sin(a), e2);
        if (k == 0)
            vec_copy(target, c);
        vec_sub(r.d, target, r.o);
        PATHPOINT pp;
        ck_assert(quadcheck_trace(d, &r, 0, (real)INFINITY, &pp));
        /* disk.h: P(s, t) = c + t R (cos 2 pi s e1 + sin 2 pi s e2) */
        const double pi = QUADCHECK_PI, Rd = (double)R;
        double phi = 2 * pi * (double)pp.st[0], t = (double)pp.st[1];
        for (int i = 0; i < 3; i++) {
            double ei = (double)e1[i], fi = (double)e2[i];
            double P = (double)c[i] + t * Rd * (cos(phi) * ei + sin(phi) * fi);
            double dPds = 2 * pi * t * Rd * (-sin(phi) * ei + cos(phi) * fi);
            double dPdt = Rd * (cos(phi) * ei + sin(phi) * fi);
            double tol = 256 * (double)REAL_EPSILON * Rd;
            ck_assert_near(pp.cross_point[i], P, tol);
            ck_assert_near(pp.dpds[i], dPds, 2 * tol);
            ck_assert_near(pp.dpdt[i], dPdt, tol);
            ck_assert(pp.ng[i] == n[i] && pp.n[i] == n[i]);
        }
        VECTOR3 uxv;
        VVECTOR3(uxv, pp.u, pp.v);
        for (int i = 0; i < 3; i++)
            ck_assert_near(uxv[i], pp.n[i], 16 * REAL_EPSILON);
        real ls = vec_length(pp.dpds);
        if (ls > REAL_C(1e-3) * R)
            ck_assert_near(SVECTOR3(pp.u, pp.dpds), ls, 64 * REAL_EPSILON * R);
    }
    cobject_free(d);
    test_report_cases("surface_parameters_and_frame_follow_the_documented_map",
                      cases);
}
END_TEST

START_TEST(bounds_are_tight_and_area_is_pi_r_squared)
{
    COBJECT *d = new_disk(1, -2, 3, 0, 0, -1, REAL_C(0.5));
    bbox_t b;
    d->ops->bounds(d, -1, &b);
    const real lo[] = { REAL_C(0.5), REAL_C(-2.5), 3 };
    const real hi[] = { REAL_C(1.5), REAL_C(-1.5), 3 };
    for (int k = 0; k < 3; k++) {
        ck_assert(b.min[k] <= lo[k] && b.min[k] >= lo[k] - 8 * REAL_EPSILON);
        ck_assert(b.max[k] >= hi[k] && b.max[k] <= hi[k] + 8 * REAL_EPSILON);
    }
    ck_assert_rel(d->ops->area(d), QUADCHECK_PI / 4, 2 * REAL_EPSILON, 0);
    cobject_free(d);
    /* tilted by 45 degrees about y: x extends R cos 45 either side */
    d = new_disk(0, 0, 0, 1, 0, 1, 2);
    d->ops->bounds(d, -1, &b);
    ck_assert_near(b.max[X], sqrt(2.0), 16 * REAL_EPSILON);
    ck_assert_near(b.max[Y], 2, 16 * REAL_EPSILON);
    ck_assert_near(b.max[Z], sqrt(2.0), 16 * REAL_EPSILON);
    cobject_free(d);
}
END_TEST

typedef struct {
    VECTOR3 c;
    real R;
} disk_ctx;

/* A uniform point of the disk has P(rho <= x) = x^2 / R^2, so
 * (rho / R)^2 is U(0,1); its azimuth is uniform too. */
static double rho2_cdf(const cobject_sample_t *s, void *ctx)
{
    const disk_ctx *k = ctx;
    double d2 = 0;
    for (int i = 0; i < 3; i++) {
        double d = (double)s->p[i] - (double)k->c[i];
        d2 += d * d;
    }
    return fmin(d2 / ((double)k->R * (double)k->R), 1.0);
}

static double phi_cdf(const cobject_sample_t *s, void *ctx)
{
    const disk_ctx *k = ctx;
    return atan2((double)s->p[Y] - (double)k->c[Y],
                 (double)s->p[X] - (double)k->c[X]) / (2 * QUADCHECK_PI) +
           0.5;
}

START_TEST(sampled_radius_squared_and_azimuth_are_uniform)
{
    disk_ctx k = { { 1, 2, -3 }, 2 };
    COBJECT *d = make_disk(k.R, k.c, NULL);
    quadcheck_ks(d, 200000, 8, rho2_cdf, &k, "sampled_rho2_is_uniform");
    quadcheck_ks(d, 200000, 9, phi_cdf, &k, "sampled_phi_is_uniform");
    cobject_free(d);
    int v = 1;
    d = make_disk(k.R, k.c, &v);
    quadcheck_ks(d, 200000, 10, rho2_cdf, &k, "tilted_rho2_is_uniform");
    cobject_free(d);
}
END_TEST

/* The harness on both placements: kind FLAT (rays leave on either side). */
static const geomcheck_kind kinds[2] = { GEOMCHECK_FLAT, GEOMCHECK_FLAT };

static const quadcheck_shape_t harness = {
    .name = "disk", .make = make_disk, .n = 2, .kinds = kinds,
    .seed = { [PRIMCHECK_SPAWN] = 1, [PRIMCHECK_SAMPLED] = 3,
              [PRIMCHECK_FINITE] = 5, [PRIMCHECK_AREA] = 7 },
    .sweep_rays = 10000, .sweep_seed = 9
};

static COBJECT *disk_row(testcsv_t *c)
{
    VECTOR3 centre, n;
    primcheck_csv_vec(c, "c", centre);
    primcheck_csv_vec(c, "a", n);
    return disk_new(centre, n, (real)testcsv_num(c, "radius"), NULL);
}

START_TEST(hits_match_the_long_double_vectors)
{
    quadcheck_vectors("disk.csv", disk_row,
                      "hits_match_the_long_double_vectors");
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("disk (" REAL_NAME ")");
    TCase *tc = tcase_create("exact");
    tcase_add_test(tc, disk_new_rejects_bad_input);
    tcase_add_test(tc,
                   rays_along_the_normal_hit_at_the_known_t_from_either_side);
    tcase_add_test(tc, tmin_and_tmax_bound_the_hit);
    tcase_add_test(tc, rays_parallel_to_the_disk_miss_without_nan);
    tcase_add_test(tc, bounds_are_tight_and_area_is_pi_r_squared);
    tcase_add_test(tc, hits_match_the_long_double_vectors);
    suite_add_tcase(s, tc);
    TCase *tr = tcase_create("random");
    tcase_set_timeout(tr, 120);
    tcase_add_test(tr, hit_and_sampled_points_are_within_their_error_bound);
    tcase_add_test(tr, surface_parameters_and_frame_follow_the_documented_map);
    tcase_add_test(tr, sampled_radius_squared_and_azimuth_are_uniform);
    quadcheck_add_harness(tr, &harness);
    suite_add_tcase(s, tr);
    return s;
}
