/*
 * test_cone.c - the finite cone of app. D, open and capped: exact hits and
 * misses, the apex and the upper nappe, a ray parallel to a generator,
 * the open interval (tmin, tmax), the error bound of hit points, the
 * surface parameters, area and sampling, the geomcheck harness at every
 * scale, tests/vectors/cone.csv, and a sweep for NaN and Inf.
 */
#include "geometry/cone.h"
#include "core/frame.h"
#include "quadcheck.h"

#include <math.h>
#include <string.h>

/* Placements (ctx: an int): the axis along z (even) or tilted (odd),
 * open (0, 1) or capped (2, 3); base radius = scale, the base at
 * centre - scale axis, the apex at centre + scale axis (H = 2 scale). */
static const real axes[2][3] = { { 0, 0, 1 },
                                 { REAL_C(0.48), REAL_C(-0.6),
                                   REAL_C(0.64) } };

static void ends(VECTOR3 base, VECTOR3 apex, real scale,
                 const VECTOR3 centre, int variant)
{
    vec_add_scaled(base, centre, -scale, axes[variant & 1]);
    vec_add_scaled(apex, centre, scale, axes[variant & 1]);
}

static COBJECT *make_cone(real scale, const VECTOR3 centre, void *ctx)
{
    int v = ctx ? *(const int *)ctx : 0;
    VECTOR3 base, apex;
    ends(base, apex, scale, centre, v);
    svet_error err;
    COBJECT *obj = cone_new(base, apex, scale, v >= 2, &err);
    ck_assert_msg(obj != NULL, "cone_new: %s", err.msg);
    return obj;
}

/* The cone with base (0, 0, 0), apex (0, 0, 2), base radius 1. */
static COBJECT *unit_cone(bool capped)
{
    VECTOR3 b = { 0, 0, 0 }, a = { 0, 0, 2 };
    svet_error err;
    COBJECT *obj = cone_new(b, a, 1, capped, &err);
    ck_assert_msg(obj != NULL, "cone_new: %s", err.msg);
    return obj;
}

START_TEST(cone_new_rejects_bad_input)
{
    VECTOR3 b = { 1, 2, 3 }, a = { 1, 2, 5 }, bad = { 0, 0, (real)NAN };
    VECTOR3 far = { -REAL_MAX, 0, 0 }, far2 = { REAL_MAX, 0, 0 };
    svet_error err;
    const real radii[] = { 0, -1, (real)NAN, (real)INFINITY, REAL_MAX / 2 };
    for (int i = 0; i < 5; i++) {
        svet_error_clear(&err);
        ck_assert_ptr_null(cone_new(b, a, radii[i], true, &err));
        ck_assert_int_eq(err.status, SVET_ERR_RANGE);
        ck_assert_msg(strstr(err.msg, "cone") != NULL, "%s", err.msg);
    }
    ck_assert_ptr_null(cone_new(b, b, 1, false, &err)); /* zero axis */
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_ptr_null(cone_new(bad, a, 1, false, &err));
    ck_assert_ptr_null(cone_new(b, bad, 1, false, &err));
    ck_assert_ptr_null(cone_new(far, far2, 1, true, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_ptr_null(cone_new(b, a, 0, false, NULL));
    COBJECT *obj = cone_new(b, a, 1, true, &err);
    ck_assert_ptr_nonnull(obj);
    ck_assert_str_eq(obj->ops->name, "cone");
    ck_assert_int_eq(obj->nprims, 1);
    cobject_free(obj);
}
END_TEST

START_TEST(exact_hits_report_their_face)
{
    COBJECT *c = unit_cone(true), *o = unit_cone(false);
    /* radius 1 - z/2: at z = 1 the wall is at x = -0.5; the outward
     * normal is (-1, 0, 1/2) / sqrt(5/4) */
    ray_t r = quadcheck_ray(-5, 0, 1, 1, 0, 0);
    const real n1 = 1 / sqrt(REAL_C(1.25)), n2 = REAL_C(0.5) * n1;
    quadcheck_expect_hit(c, &r, REAL_C(4.5), CONE_LATERAL, -n1, 0, n2);
    r = quadcheck_ray(REAL_C(0.25), 0, -3, 0, 0, 1); /* up, under the base */
    quadcheck_expect_hit(c, &r, 3, CONE_BASE, 0, 0, -1);
    /* open: through the base onto the inner wall at z = 1.5 */
    quadcheck_expect_hit(o, &r, REAL_C(4.5), CONE_LATERAL, n1, 0, n2);
    /* over the apex: the double cone's upper nappe must not count */
    r = quadcheck_ray(-5, 0, REAL_C(2.5), 1, 0, 0);
    hit_t h;
    ck_assert(!cobject_intersect(c, &r, 0, (real)INFINITY, &h));
    r = quadcheck_ray(0, 0, 5, 1, 0, 0);
    ck_assert(!cobject_intersect(c, &r, 0, (real)INFINITY, &h));
    /* parallel to the generator from (1,0,0) to the apex: the quadratic's
     * leading coefficient is exactly 0; it meets the other generator at
     * (-0.5, 0, 1), t = 1 */
    r = quadcheck_ray(REAL_C(0.5), 0, -1, -1, 0, 2);
    quadcheck_expect_hit(o, &r, 1, CONE_LATERAL, -n1, 0, n2);
    cobject_free(c);
    cobject_free(o);
}
END_TEST

START_TEST(rays_through_the_apex_give_no_nan)
{
    COBJECT *c = unit_cone(true);
    /* down the axis: the apex at t = 3, where the normal is the axis */
    ray_t r = quadcheck_ray(0, 0, 5, 0, 0, -1);
    quadcheck_expect_hit(c, &r, 3, CONE_LATERAL, 0, 0, 1);
    /* through the apex from every direction: a hit there, or (outside
     * the solid's cone of directions) possibly a miss; never NaN */
    pcg32_t g;
    pcg32_seed(&g, 91, 92);
    long cases = 0;
    VECTOR3 apex = { 0, 0, 2 };
    for (int i = 0; i < 20000; i++, cases++) {
        VECTOR3 w;
        geomcheck_random_dir(w, &g);
        ray_t s;
        vec_add_scaled(s.o, apex, 3, w);
        vec_neg(s.d, w);
        PATHPOINT pp;
        if (!quadcheck_trace(c, &s, 0, (real)INFINITY, &pp))
            continue;
        quadcheck_assert_finite(&pp, "through the apex");
        /* directions into the solid, within its half-angle atan(1/2) of
         * the downward axis, hit at the apex, t = 3 */
        if (-s.d[Z] > REAL_C(0.9))
            ck_assert_near(pp.r_dist, 3, 64 * REAL_EPSILON);
    }
    cobject_free(c);
    test_report_cases("rays_through_the_apex_give_no_nan", cases);
}
END_TEST

START_TEST(tmin_and_tmax_bound_the_hit)
{
    COBJECT *c = unit_cone(true);
    ray_t r = quadcheck_ray(-5, 0, 1, 1, 0, 0); /* t = 4.5 and 5.5 */
    hit_t h;
    ck_assert(!cobject_intersect(c, &r, 0, REAL_C(4.5), &h));
    ck_assert(cobject_intersect(c, &r, 0,
                                nextafter(REAL_C(4.5), REAL_C(5.0)), &h));
    ck_assert(cobject_intersect(c, &r, REAL_C(4.5), 100, &h));
    ck_assert_near(h.t, 5.5, 0);
    ck_assert(!cobject_intersect(c, &r, REAL_C(5.5), 100, &h));
    /* from inside: the far side only */
    r = quadcheck_ray(0, 0, REAL_C(0.5), 1, 0, 0);
    PATHPOINT pp;
    ck_assert(quadcheck_trace(c, &r, 0, (real)INFINITY, &pp));
    ck_assert_near(pp.r_dist, 0.75, 2 * REAL_EPSILON);
    ck_assert(!pp.bout);
    cobject_free(c);
}
END_TEST

static long double cone_distance(const VECTOR3 p, real scale,
                                 const VECTOR3 centre, void *ctx)
{
    int v = ctx ? *(const int *)ctx : 0;
    VECTOR3 base, apex;
    ends(base, apex, scale, centre, v);
    long double R = (long double)scale, h2 = 0;
    for (int k = 0; k < 3; k++) {
        long double d = (long double)apex[k] - (long double)base[k];
        h2 += d * d;
    }
    long double H = sqrtl(h2);
    /* meridian from the apex: the generator (0, 0)-(R, H), the base
     * (0, H)-(R, H) */
    const long double seg[2][4] = { { 0, 0, R, H }, { 0, H, R, H } };
    return quadcheck_meridian_distance(p, apex, base, seg, v >= 2 ? 2 : 1);
}

START_TEST(hit_and_sampled_points_are_within_their_error_bound)
{
    long cases = 0;
    for (int v = 0; v < 4; v++)
        cases += quadcheck_error_bound(make_cone, cone_distance, &v, 1000,
                                       (uint64_t)(101 + v));
    test_report_cases("hit_and_sampled_points_are_within_their_error_bound",
                      cases);
}
END_TEST

START_TEST(surface_parameters_and_frame_follow_the_documented_map)
{
    VECTOR3 centre = { REAL_C(0.5), -1, 2 }, base, apex, w, e1, e2;
    const real R = REAL_C(1.5);
    int v = 3;
    ends(base, apex, R, centre, v);
    COBJECT *c = make_cone(R, centre, &v);
    real H = vec_normalize(w, axes[1]) * 2 * R;
    frame_from_normal(e1, e2, w);
    pcg32_t g;
    pcg32_seed(&g, 111, 112);
    long cases = 0;
    int faces[2] = { 0, 0 };
    for (int k = 0; k < 5000; k++, cases++) {
        ray_t r;
        VECTOR3 dir;
        geomcheck_random_dir(dir, &g);
        vec_add_scaled(r.o, centre, 4 * R, dir);
        geomcheck_random_dir(dir, &g);
        vec_add_scaled(dir, centre, R * pcg32_real(&g), dir);
        vec_sub(r.d, dir, r.o);
        PATHPOINT pp;
        if (!quadcheck_trace(c, &r, 0, (real)INFINITY, &pp))
            continue;
        faces[pp.prim]++;
        const double pi = QUADCHECK_PI, Rd = (double)R, Hd = (double)H;
        double phi = 2 * pi * (double)pp.st[0], t = (double)pp.st[1];
        for (int i = 0; i < 3; i++) {
            double a = (double)e1[i], b = (double)e2[i], z = (double)w[i];
            double radial = cos(phi) * a + sin(phi) * b;
            double tangent = -sin(phi) * a + cos(phi) * b;
            double P, dPds, dPdt;
            if (pp.prim == CONE_LATERAL) {
                /* cone.h: P(s, t) = base + R (1 - t) radial(phi) + t H w */
                P = (double)base[i] + Rd * (1 - t) * radial + t * Hd * z;
                dPds = 2 * pi * Rd * (1 - t) * tangent;
                dPdt = -Rd * radial + Hd * z;
            } else {
                P = (double)base[i] + t * Rd * radial;
                dPds = 2 * pi * t * Rd * tangent;
                dPdt = Rd * radial;
            }
            double tol = 256 * (double)REAL_EPSILON * (Rd + Hd);
            ck_assert_near(pp.cross_point[i], P, tol);
            ck_assert_near(pp.dpds[i], dPds, 2 * pi * tol);
            ck_assert_near(pp.dpdt[i], dPdt, tol);
        }
        VECTOR3 uxv;
        VVECTOR3(uxv, pp.u, pp.v);
        for (int i = 0; i < 3; i++)
            ck_assert_near(uxv[i], pp.n[i], 16 * REAL_EPSILON);
        real ls = vec_length(pp.dpds);
        if (ls > REAL_C(1e-3) * R)
            ck_assert_near(SVECTOR3(pp.u, pp.dpds), ls, 64 * REAL_EPSILON * R);
        /* the normal is perpendicular to both tangents */
        ck_assert_near(SVECTOR3(pp.ng, pp.dpdt), 0, 64 * REAL_EPSILON * H);
    }
    ck_assert(faces[0] > 0 && faces[1] > 0);
    cobject_free(c);
    test_report_cases("surface_parameters_and_frame_follow_the_documented_map",
                      cases);
}
END_TEST

START_TEST(bounds_are_tight_and_area_is_exact)
{
    VECTOR3 b = { 1, 2, 3 }, a = { 1, 2, 7 };
    COBJECT *c = cone_new(b, a, 3, true, NULL);
    bbox_t box;
    c->ops->bounds(c, -1, &box);
    const real lo[] = { -2, -1, 3 }, hi[] = { 4, 5, 7 };
    for (int k = 0; k < 3; k++) {
        ck_assert(box.min[k] <= lo[k] &&
                  box.min[k] >= lo[k] - 64 * REAL_EPSILON);
        ck_assert(box.max[k] >= hi[k] &&
                  box.max[k] <= hi[k] + 64 * REAL_EPSILON);
    }
    /* pi R sqrt(R^2 + H^2) + pi R^2 = 15 pi + 9 pi (a 3-4-5 cone) */
    ck_assert_rel(c->ops->area(c), 24 * QUADCHECK_PI, 4 * REAL_EPSILON, 0);
    cobject_free(c);
    c = cone_new(b, a, 3, false, NULL);
    ck_assert_rel(c->ops->area(c), 15 * QUADCHECK_PI, 4 * REAL_EPSILON, 0);
    cobject_free(c);
}
END_TEST

typedef struct {
    VECTOR3 apex, e1, e2, w; /* w from the base toward the apex */
    double R, H, p_lat;      /* p_lat: the share of the lateral face */
} cone_ctx;

/* Distance below the apex along the axis, azimuth, distance from the axis. */
static void local_coords(const cone_ctx *k, const cobject_sample_t *s,
                         double *depth, double *phi, double *rho)
{
    double x = 0, y = 0, z = 0;
    for (int i = 0; i < 3; i++) {
        double q = (double)s->p[i] - (double)k->apex[i];
        x += q * (double)k->e1[i];
        y += q * (double)k->e2[i];
        z += q * (double)k->w[i];
    }
    *depth = -z;
    *phi = atan2(y, x);
    *rho = sqrt(x * x + y * y);
}

/* U(0,1) exactly when faces are drawn in proportion to their areas and
 * each uniformly: the lateral area within depth h of the apex grows as
 * h^2, so (h / H)^2, scaled into [0, p_lat); on the base (rho / R)^2,
 * scaled into [p_lat, 1). */
static double stacked_cdf(const cobject_sample_t *s, void *ctx)
{
    const cone_ctx *k = ctx;
    double h, phi, rho;
    local_coords(k, s, &h, &phi, &rho);
    if (h > (1 - 1e-4) * k->H && rho < (1 - 1e-3) * k->R)
        return k->p_lat + (1 - k->p_lat) * rho * rho / (k->R * k->R);
    return k->p_lat * fmin(h * h / (k->H * k->H), 1);
}

static double phi_cdf(const cobject_sample_t *s, void *ctx)
{
    double h, phi, rho;
    local_coords(ctx, s, &h, &phi, &rho);
    return phi / (2 * QUADCHECK_PI) + 0.5;
}

START_TEST(sampled_faces_depths_and_radii_are_uniform_by_area)
{
    for (int v = 0; v < 4; v++) {
        cone_ctx k;
        VECTOR3 centre = { 1, 2, -3 }, base;
        ends(base, k.apex, 1, centre, v);
        vec_normalize(k.w, axes[v & 1]);
        frame_from_normal(k.e1, k.e2, k.w);
        k.R = 1;
        k.H = 2;
        /* pi R L / (pi R L + pi R^2) with L = sqrt(5) */
        k.p_lat = v >= 2 ? sqrt(5.0) / (sqrt(5.0) + 1) : 1;
        COBJECT *c = make_cone(1, centre, &v);
        quadcheck_ks(c, 200000, (uint64_t)(31 + v), stacked_cdf, &k,
                     "sampled_face_depth_radius_is_uniform");
        quadcheck_ks(c, 200000, (uint64_t)(41 + v), phi_cdf, &k,
                     "sampled_phi_is_uniform");
        cobject_free(c);
    }
}
END_TEST

/* The harness on all four placements: OPEN when open, CONVEX capped. */
static const geomcheck_kind kinds[4] = { GEOMCHECK_OPEN, GEOMCHECK_OPEN,
                                         GEOMCHECK_CONVEX, GEOMCHECK_CONVEX };

static const quadcheck_shape_t harness = {
    .name = "cone", .make = make_cone, .n = 4, .kinds = kinds,
    .seed = { [PRIMCHECK_SPAWN] = 1, [PRIMCHECK_SAMPLED] = 5,
              [PRIMCHECK_SHADOW] = 9, [PRIMCHECK_FINITE] = 13,
              [PRIMCHECK_AREA] = 17 },
    .sweep_rays = 5000, .sweep_seed = 19
};

static COBJECT *cone_row(testcsv_t *c)
{
    VECTOR3 b, a;
    primcheck_csv_vec(c, "b", b);
    primcheck_csv_vec(c, "a", a);
    return cone_new(b, a, (real)testcsv_num(c, "radius"),
                    testcsv_num(c, "capped") != 0, NULL);
}

START_TEST(hits_match_the_long_double_vectors)
{
    quadcheck_vectors("cone.csv", cone_row,
                      "hits_match_the_long_double_vectors");
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("cone (" REAL_NAME ")");
    TCase *tc = tcase_create("exact");
    tcase_add_test(tc, cone_new_rejects_bad_input);
    tcase_add_test(tc, exact_hits_report_their_face);
    tcase_add_test(tc, rays_through_the_apex_give_no_nan);
    tcase_add_test(tc, tmin_and_tmax_bound_the_hit);
    tcase_add_test(tc, bounds_are_tight_and_area_is_exact);
    tcase_add_test(tc, hits_match_the_long_double_vectors);
    suite_add_tcase(s, tc);
    TCase *tr = tcase_create("random");
    tcase_set_timeout(tr, 120);
    tcase_add_test(tr, hit_and_sampled_points_are_within_their_error_bound);
    tcase_add_test(tr, surface_parameters_and_frame_follow_the_documented_map);
    tcase_add_test(tr, sampled_faces_depths_and_radii_are_uniform_by_area);
    quadcheck_add_harness(tr, &harness);
    suite_add_tcase(s, tr);
    return s;
}
