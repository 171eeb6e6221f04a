/*
 * test_cylinder.c - the finite cylinder of app. D, open and capped: exact
 * hits and misses, the faces it reports, the open interval (tmin, tmax),
 * rays along the axis and grazing the wall, the error bound of hit points,
 * the surface parameters, area and sampling, the geomcheck harness at every
 * scale, tests/vectors/cylinder.csv, and a sweep for NaN and Inf.
 */
#include "geometry/cylinder.h"
#include "core/frame.h"
#include "quadcheck.h"

#include <math.h>
#include <string.h>

/* Placements (ctx: an int): the axis along z (even) or tilted (odd),
 * open (0, 1) or capped (2, 3); radius = scale, height 2 scale about the
 * centre. */
static const real axes[2][3] = { { 0, 0, 1 },
                                 { REAL_C(0.48), REAL_C(-0.6),
                                   REAL_C(0.64) } };

static void ends(VECTOR3 base, VECTOR3 top, real scale, const VECTOR3 centre,
                 int variant)
{
    vec_add_scaled(base, centre, -scale, axes[variant & 1]);
    vec_add_scaled(top, centre, scale, axes[variant & 1]);
}

static COBJECT *make_cylinder(real scale, const VECTOR3 centre, void *ctx)
{
    int v = ctx ? *(const int *)ctx : 0;
    VECTOR3 base, top;
    ends(base, top, scale, centre, v);
    svet_error err;
    COBJECT *obj = cylinder_new(base, top, scale, v >= 2, &err);
    ck_assert_msg(obj != NULL, "cylinder_new: %s", err.msg);
    return obj;
}

static COBJECT *new_cylinder(real bx, real by, real bz, real tx, real ty,
                             real tz, real radius, bool capped)
{
    VECTOR3 b = { bx, by, bz }, t = { tx, ty, tz };
    svet_error err;
    COBJECT *obj = cylinder_new(b, t, radius, capped, &err);
    ck_assert_msg(obj != NULL, "cylinder_new: %s", err.msg);
    return obj;
}

START_TEST(cylinder_new_rejects_bad_input)
{
    VECTOR3 b = { 1, 2, 3 }, t = { 1, 2, 5 }, bad = { 0, (real)NAN, 0 };
    VECTOR3 inf = { (real)INFINITY, 0, 0 };
    VECTOR3 far = { -REAL_MAX, 0, 0 }, far2 = { REAL_MAX, 0, 0 };
    svet_error err;
    const real radii[] = { 0, -1, (real)NAN, (real)INFINITY, REAL_MAX / 2 };
    for (int i = 0; i < 5; i++) {
        svet_error_clear(&err);
        ck_assert_ptr_null(cylinder_new(b, t, radii[i], true, &err));
        ck_assert_int_eq(err.status, SVET_ERR_RANGE);
        ck_assert_msg(strstr(err.msg, "cylinder") != NULL, "%s", err.msg);
    }
    ck_assert_ptr_null(cylinder_new(b, b, 1, false, &err)); /* zero axis */
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_ptr_null(cylinder_new(bad, t, 1, false, &err));
    ck_assert_ptr_null(cylinder_new(b, inf, 1, false, &err));
    ck_assert_ptr_null(cylinder_new(far, far2, 1, false, &err)); /* overflow */
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_ptr_null(cylinder_new(b, t, -1, false, NULL));
    COBJECT *obj = cylinder_new(b, t, 1, true, &err);
    ck_assert_ptr_nonnull(obj);
    ck_assert_str_eq(obj->ops->name, "cylinder");
    ck_assert_int_eq(obj->nprims, 1);
    cobject_free(obj);
}
END_TEST

START_TEST(exact_hits_report_their_face)
{
    COBJECT *c = new_cylinder(0, 0, 0, 0, 0, 4, 1, true);
    COBJECT *o = new_cylinder(0, 0, 0, 0, 0, 4, 1, false);
    ray_t r = quadcheck_ray(-5, 0, 2, 1, 0, 0);
    quadcheck_expect_hit(c, &r, 4, CYLINDER_LATERAL, -1, 0, 0);
    quadcheck_expect_hit(o, &r, 4, CYLINDER_LATERAL, -1, 0, 0);
    r = quadcheck_ray(REAL_C(0.5), 0, -2, 0, 0, 1); /* up the axis, inside */
    quadcheck_expect_hit(c, &r, 2, CYLINDER_BASE, 0, 0, -1);
    hit_t h;
    ck_assert(!cobject_intersect(o, &r, 0, (real)INFINITY, &h));
    r = quadcheck_ray(0, REAL_C(0.5), 10, 0, 0, -2); /* down, |d| = 2 */
    quadcheck_expect_hit(c, &r, 3, CYLINDER_TOP, 0, 0, 1);
    r = quadcheck_ray(0, 0, 2, 0, 1, 0); /* from inside: the far wall */
    quadcheck_expect_hit(c, &r, 1, CYLINDER_LATERAL, 0, 1, 0);
    quadcheck_expect_hit(o, &r, 1, CYLINDER_LATERAL, 0, 1, 0);
    r = quadcheck_ray(0, 0, 2, 0, 0, 1); /* from inside along the axis */
    quadcheck_expect_hit(c, &r, 2, CYLINDER_TOP, 0, 0, 1);
    ck_assert(!cobject_intersect(o, &r, 0, (real)INFINITY, &h));
    /* into the open end, onto the inner wall: ng still points out */
    r = quadcheck_ray(0, 0, REAL_C(4.5), 1, 0, -1);
    quadcheck_expect_hit(o, &r, 1, CYLINDER_LATERAL, 1, 0, 0);
    r = quadcheck_ray(-5, 0, REAL_C(4.5), 1, 0, 0); /* over the top */
    ck_assert(!cobject_intersect(c, &r, 0, (real)INFINITY, &h));
    r = quadcheck_ray(-5, REAL_C(1.01), 2, 1, 0, 0); /* beside */
    ck_assert(!cobject_intersect(c, &r, 0, (real)INFINITY, &h));
    cobject_free(c);
    cobject_free(o);
    /* a horizontal cylinder along (1, 1, 0): hit from below at t = 4 */
    c = new_cylinder(1, 1, 1, 3, 3, 1, 1, true);
    r = quadcheck_ray(2, 2, -4, 0, 0, 1);
    quadcheck_expect_hit(c, &r, 4, CYLINDER_LATERAL, 0, 0, -1);
    cobject_free(c);
}
END_TEST

START_TEST(tmin_and_tmax_bound_the_hit)
{
    COBJECT *c = new_cylinder(0, 0, 0, 0, 0, 4, 1, true);
    ray_t r = quadcheck_ray(-5, 0, 2, 1, 0, 0); /* t = 4 and 6 */
    hit_t h;
    ck_assert(!cobject_intersect(c, &r, 0, 4, &h));
    ck_assert(cobject_intersect(c, &r, 0, nextafter(REAL_C(4.0), REAL_C(5.0)),
                                &h));
    ck_assert(cobject_intersect(c, &r, 4, 100, &h));
    ck_assert_near(h.t, 6, 0);
    ck_assert(!cobject_intersect(c, &r, 6, 100, &h));
    r = quadcheck_ray(0, 0, -1, 0, 0, 1); /* caps at t = 1 and 5 */
    ck_assert(cobject_intersect(c, &r, 1, 100, &h));
    ck_assert_near(h.t, 5, 0);
    ck_assert(!cobject_intersect(c, &r, 0, 1, &h));
    cobject_free(c);
}
END_TEST

START_TEST(rays_along_the_axis_and_grazing_the_wall_give_no_nan)
{
    COBJECT *c = new_cylinder(0, 0, 0, 0, 0, 4, 1, true);
    COBJECT *o = new_cylinder(0, 0, 0, 0, 0, 4, 1, false);
    const real xs[] = { 0, REAL_C(0.5), nextafter(REAL_C(1.0), REAL_C(0.0)),
                        1, nextafter(REAL_C(1.0), REAL_C(2.0)), 2 };
    long cases = 0;
    for (int i = 0; i < 6; i++)
        for (int s = -1; s <= 1; s += 2, cases += 2) {
            ray_t r = quadcheck_ray(xs[i], 0, s > 0 ? -3 : 7, 0, 0, (real)s);
            PATHPOINT pp;
            bool hc = quadcheck_trace(c, &r, 0, (real)INFINITY, &pp);
            if (hc)
                quadcheck_assert_finite(&pp, "axis, capped");
            /* inside the radius the cap is hit at t = 3 */
            if (xs[i] < 1) {
                ck_assert(hc);
                ck_assert_near(pp.r_dist, 3, 0);
                ck_assert_int_eq(pp.prim,
                                 s > 0 ? CYLINDER_BASE : CYLINDER_TOP);
            }
            if (xs[i] > 1)
                ck_assert(!hc);
            if (quadcheck_trace(o, &r, 0, (real)INFINITY, &pp))
                quadcheck_assert_finite(&pp, "axis, open");
        }
    /* rays tangent to the wall, and one ulp either side */
    for (int i = 2; i < 5; i++, cases += 2) {
        ray_t r = quadcheck_ray(-5, xs[i], 2, 1, 0, 0);
        PATHPOINT pp;
        if (quadcheck_trace(c, &r, 0, (real)INFINITY, &pp)) {
            quadcheck_assert_finite(&pp, "tangent");
            ck_assert_near(pp.r_dist, 5, 4 * sqrt(REAL_EPSILON));
        }
        /* tangent from a point */
        r = quadcheck_ray(-5, 0, 2, 1, xs[i] / 5, 0);
        if (quadcheck_trace(c, &r, 0, (real)INFINITY, &pp))
            quadcheck_assert_finite(&pp, "tangent from a point");
    }
    /* nearly parallel to the axis from below, 0.1 inside the wall: it
     * reaches the wall at t = 0.1 2^e, z = t - 1, which is on the open
     * cylinder for e = 4 and 5 only */
    for (int e = 2; e < 60; e++, cases++) {
        ray_t r = quadcheck_ray(REAL_C(0.9), 0, -1, ldexp(REAL_C(1.0), -e), 0,
                                1);
        PATHPOINT pp;
        bool hit = quadcheck_trace(o, &r, 0, (real)INFINITY, &pp);
        ck_assert_msg(hit == (e == 4 || e == 5), "e = %d: hit = %d", e, hit);
        if (hit)
            ck_assert_near(pp.cross_point[X], 1, 4 * REAL_EPSILON);
    }
    cobject_free(c);
    cobject_free(o);
    test_report_cases("rays_along_the_axis_and_grazing_the_wall_give_no_nan",
                      cases);
}
END_TEST

static long double cylinder_distance(const VECTOR3 p, real scale,
                                     const VECTOR3 centre, void *ctx)
{
    int v = ctx ? *(const int *)ctx : 0;
    VECTOR3 base, top;
    ends(base, top, scale, centre, v);
    /* R and H in long double, from the ends as stored */
    long double R = (long double)scale, h2 = 0;
    for (int k = 0; k < 3; k++) {
        long double d = (long double)top[k] - (long double)base[k];
        h2 += d * d;
    }
    long double H = sqrtl(h2);
    const long double seg[3][4] = { { R, 0, R, H }, { 0, 0, R, 0 },
                                    { 0, H, R, H } };
    return quadcheck_meridian_distance(p, base, top, seg, v >= 2 ? 3 : 1);
}

START_TEST(hit_and_sampled_points_are_within_their_error_bound)
{
    long cases = 0;
    for (int v = 0; v < 4; v++)
        cases += quadcheck_error_bound(make_cylinder, cylinder_distance, &v,
                                       1000, (uint64_t)(71 + v));
    test_report_cases("hit_and_sampled_points_are_within_their_error_bound",
                      cases);
}
END_TEST

START_TEST(surface_parameters_and_frame_follow_the_documented_map)
{
    VECTOR3 centre = { REAL_C(0.5), -1, 2 }, base, top, w, e1, e2;
    const real R = REAL_C(1.5);
    int v = 3;
    ends(base, top, R, centre, v);
    COBJECT *c = make_cylinder(R, centre, &v);
    real H = vec_normalize(w, axes[1]) * 2 * R;
    frame_from_normal(e1, e2, w);
    pcg32_t g;
    pcg32_seed(&g, 81, 82);
    long cases = 0;
    int faces[3] = { 0, 0, 0 };
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
            double P, dPds, dPdt;
            if (pp.prim == CYLINDER_LATERAL) {
                /* cylinder.h: P(s, t) = base + R radial(phi) + t H w */
                P = (double)base[i] + Rd * radial + t * Hd * z;
                dPds = 2 * pi * Rd * (-sin(phi) * a + cos(phi) * b);
                dPdt = Hd * z;
            } else {
                /* the caps are disks about their centres */
                const real *cc = pp.prim == CYLINDER_BASE ? base : top;
                P = (double)cc[i] + t * Rd * radial;
                dPds = 2 * pi * t * Rd * (-sin(phi) * a + cos(phi) * b);
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
        if (pp.prim == CYLINDER_LATERAL) /* v = n x u = w */
            for (int i = 0; i < 3; i++)
                ck_assert_near(pp.v[i], w[i], 16 * REAL_EPSILON);
        real ls = vec_length(pp.dpds);
        if (ls > REAL_C(1e-3) * R)
            ck_assert_near(SVECTOR3(pp.u, pp.dpds), ls, 64 * REAL_EPSILON * R);
    }
    ck_assert(faces[0] > 0 && faces[1] > 0 && faces[2] > 0);
    cobject_free(c);
    test_report_cases("surface_parameters_and_frame_follow_the_documented_map",
                      cases);
}
END_TEST

START_TEST(bounds_are_tight_and_area_is_exact)
{
    COBJECT *c = new_cylinder(1, 2, 3, 1, 2, 7, REAL_C(0.5), true);
    bbox_t b;
    c->ops->bounds(c, -1, &b);
    const real lo[] = { REAL_C(0.5), REAL_C(1.5), 3 };
    const real hi[] = { REAL_C(1.5), REAL_C(2.5), 7 };
    for (int k = 0; k < 3; k++) {
        ck_assert(b.min[k] <= lo[k] && b.min[k] >= lo[k] - 16 * REAL_EPSILON);
        ck_assert(b.max[k] >= hi[k] && b.max[k] <= hi[k] + 16 * REAL_EPSILON);
    }
    /* 2 pi R H + 2 pi R^2 = 4 pi + pi / 2 */
    ck_assert_rel(c->ops->area(c), 4.5 * QUADCHECK_PI, 4 * REAL_EPSILON, 0);
    cobject_free(c);
    c = new_cylinder(1, 2, 3, 1, 2, 7, REAL_C(0.5), false);
    ck_assert_rel(c->ops->area(c), 4 * QUADCHECK_PI, 4 * REAL_EPSILON, 0);
    cobject_free(c);
}
END_TEST

typedef struct {
    VECTOR3 base, e1, e2, w;
    double R, H, p_lat; /* p_lat: the share of the lateral face */
} cyl_ctx;

static void local_coords(const cyl_ctx *k, const cobject_sample_t *s,
                         double *rho, double *phi, double *h)
{
    double q[3], x = 0, y = 0, z = 0;
    for (int i = 0; i < 3; i++) {
        q[i] = (double)s->p[i] - (double)k->base[i];
        x += q[i] * (double)k->e1[i];
        y += q[i] * (double)k->e2[i];
        z += q[i] * (double)k->w[i];
    }
    *rho = sqrt(x * x + y * y);
    *phi = atan2(y, x);
    *h = z;
}

/* One number per sample that is U(0,1) exactly when the faces are drawn
 * in proportion to their areas and each uniformly: on the lateral face
 * h / H, uniform since the face unrolls to a rectangle, scaled into
 * [0, p_lat); on the caps (rho / R)^2, uniform on a disk, scaled into
 * the caps' shares after it. */
static double stacked_cdf(const cobject_sample_t *s, void *ctx)
{
    const cyl_ctx *k = ctx;
    double rho, phi, h;
    local_coords(k, s, &rho, &phi, &h);
    double cap = (1 - k->p_lat) / 2, r2 = fmin(rho * rho / (k->R * k->R), 1);
    if (h < 1e-4 * k->H)
        return k->p_lat + cap * r2;
    if (h > (1 - 1e-4) * k->H)
        return k->p_lat + cap + cap * r2;
    return k->p_lat * h / k->H;
}

static double phi_cdf(const cobject_sample_t *s, void *ctx)
{
    double rho, phi, h;
    local_coords(ctx, s, &rho, &phi, &h);
    return phi / (2 * QUADCHECK_PI) + 0.5;
}

START_TEST(sampled_faces_heights_and_radii_are_uniform_by_area)
{
    for (int v = 0; v < 4; v++) {
        cyl_ctx k;
        VECTOR3 centre = { 1, 2, -3 }, top;
        ends(k.base, top, 1, centre, v);
        vec_normalize(k.w, axes[v & 1]);
        frame_from_normal(k.e1, k.e2, k.w);
        k.R = 1;
        k.H = 2;
        /* 2 pi R H / (2 pi R H + 2 pi R^2) = H / (H + R) */
        k.p_lat = v >= 2 ? 2.0 / 3 : 1;
        COBJECT *c = make_cylinder(1, centre, &v);
        quadcheck_ks(c, 200000, (uint64_t)(11 + v), stacked_cdf, &k,
                     "sampled_face_height_radius_is_uniform");
        quadcheck_ks(c, 200000, (uint64_t)(21 + v), phi_cdf, &k,
                     "sampled_phi_is_uniform");
        cobject_free(c);
    }
}
END_TEST

/* The harness on all four placements: OPEN when open, CONVEX capped. */
static const geomcheck_kind kinds[4] = { GEOMCHECK_OPEN, GEOMCHECK_OPEN,
                                         GEOMCHECK_CONVEX, GEOMCHECK_CONVEX };

static const quadcheck_shape_t harness = {
    .name = "cylinder", .make = make_cylinder, .n = 4, .kinds = kinds,
    .seed = { [PRIMCHECK_SPAWN] = 1, [PRIMCHECK_SAMPLED] = 5,
              [PRIMCHECK_SHADOW] = 9, [PRIMCHECK_FINITE] = 13,
              [PRIMCHECK_AREA] = 17 },
    .sweep_rays = 5000, .sweep_seed = 9
};

static COBJECT *cylinder_row(testcsv_t *c)
{
    VECTOR3 b, e;
    primcheck_csv_vec(c, "b", b);
    primcheck_csv_vec(c, "e", e);
    return cylinder_new(b, e, (real)testcsv_num(c, "radius"),
                        testcsv_num(c, "capped") != 0, NULL);
}

START_TEST(hits_match_the_long_double_vectors)
{
    quadcheck_vectors("cylinder.csv", cylinder_row,
                      "hits_match_the_long_double_vectors");
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("cylinder (" REAL_NAME ")");
    TCase *tc = tcase_create("exact");
    tcase_add_test(tc, cylinder_new_rejects_bad_input);
    tcase_add_test(tc, exact_hits_report_their_face);
    tcase_add_test(tc, tmin_and_tmax_bound_the_hit);
    tcase_add_test(tc, rays_along_the_axis_and_grazing_the_wall_give_no_nan);
    tcase_add_test(tc, bounds_are_tight_and_area_is_exact);
    tcase_add_test(tc, hits_match_the_long_double_vectors);
    suite_add_tcase(s, tc);
    TCase *tr = tcase_create("random");
    tcase_set_timeout(tr, 120);
    tcase_add_test(tr, hit_and_sampled_points_are_within_their_error_bound);
    tcase_add_test(tr, surface_parameters_and_frame_follow_the_documented_map);
    tcase_add_test(tr, sampled_faces_heights_and_radii_are_uniform_by_area);
    quadcheck_add_harness(tr, &harness);
    suite_add_tcase(s, tr);
    return s;
}
