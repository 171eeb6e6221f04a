/*
 * test_xform.c - affine transforms and primitives under them (app. C, D):
 * compose/invert round trips, exact quarter turns, Rodrigues against
 * vec_rotate, singular transforms, normals under non-uniform scale, the
 * Cornell box's blocks against hand-computed corners, a box's table of
 * world face frames against the general way, exact areas and the
 * ellipsoid's quadrature against a spheroid's closed form, sampling
 * densities, the geomcheck harness on an oriented box, a parallelogram and
 * an ellipsoid, tests/vectors/xform.csv and a NaN sweep; intersect() and
 * surface() (with the speed layer where SIMD=on) against the plain
 * algorithm, field by field.
 */
#include "testutil.h"
#include "geometry/box.h"
#include "geomcheck.h"
#include "geometry/parallelogram.h"
#include "primcheck.h"
#include "core/ray.h"
#include "geometry/shape.h"
#include "geometry/sphere.h"
#include "geometry/triangle.h"
#include "geometry/xform.h"

#include <string.h>

static const VECTOR3 yaxis = { 0, 1, 0 };

/* a random transform: non-uniform scale in [0.2, 5) per axis (a mirror
 * one time in 4), a rotation, a translation in [-10, 10)^3 */
static xform_t random_xform(pcg32_t *g)
{
    VECTOR3 s, a, t;
    for (int k = 0; k < 3; k++) {
        s[k] = REAL_C(0.2) * exp(REAL_C(3.2) * pcg32_real(g));
        t[k] = 20 * pcg32_real(g) - 10;
    }
    if ((pcg32_next(g) & 3) == 0)
        s[X] = -s[X];
    geomcheck_random_dir(a, g);
    return xform_compose(xform_compose(xform_scale(s),
                                       xform_rotate(a, 360 * pcg32_real(g))),
                         xform_translate(t));
}

static real max_abs_diff(real a[3][4], real b[3][4])
{
    real d = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            d = fmax(d, fabs(a[i][j] - b[i][j]));
    return d;
}

START_TEST(compose_and_invert_round_trip)
{
    pcg32_t g;
    pcg32_seed(&g, 41, 42);
    long n = 0;
    xform_t id = xform_identity();
    for (int i = 0; i < 5000; i++, n++) {
        xform_t x = random_xform(&g), y, z, back;
        svet_error err;
        ck_assert(x.valid);
        ck_assert_int_eq(xform_invert(&x, &y, &err), SVET_OK);
        /* x then x^-1 is the identity, both ways; the stored inverse
         * (from the factors) agrees with the computed one. Entries are
         * up to 5 * 10 = 50: tolerance 64 epsilon times that. */
        real tol = 3200 * REAL_EPSILON;
        z = xform_compose(x, y);
        ck_assert_msg(max_abs_diff(z.m, id.m) <= tol, "x then x^-1: %g",
                      (double)max_abs_diff(z.m, id.m));
        z = xform_compose(y, x);
        ck_assert(max_abs_diff(z.m, id.m) <= tol);
        ck_assert(max_abs_diff(y.m, x.inv) <= tol);
        ck_assert_int_eq(xform_invert(&y, &back, &err), SVET_OK);
        ck_assert(max_abs_diff(back.m, x.m) <= tol);
        /* points go there and back */
        VECTOR3 p, q, r;
        vec_set(p, 10 * pcg32_real(&g) - 5, 10 * pcg32_real(&g) - 5,
                10 * pcg32_real(&g) - 5);
        xform_point(&x, q, p);
        xform_point(&y, r, q);
        for (int k = 0; k < 3; k++)
            ck_assert_near(r[k], p[k], tol);
    }
    test_report_cases("compose_and_invert_round_trip", n);
}
END_TEST

START_TEST(compose_applies_first_then_second)
{
    VECTOR3 s = { 2, 2, 2 }, t = { 1, 0, 0 }, p = { 1, 1, 1 }, q;
    xform_t st = xform_compose(xform_scale(s), xform_translate(t));
    xform_point(&st, q, p); /* scaled, then moved: (3, 2, 2) */
    ck_assert(q[X] == 3 && q[Y] == 2 && q[Z] == 2);
    xform_t ts = xform_compose(xform_translate(t), xform_scale(s));
    xform_point(&ts, q, p); /* moved, then scaled: (4, 2, 2) */
    ck_assert(q[X] == 4 && q[Y] == 2 && q[Z] == 2);
    xform_vector(&st, q, p); /* vectors ignore the translation */
    ck_assert(q[X] == 2 && q[Y] == 2 && q[Z] == 2);
}
END_TEST

START_TEST(quarter_turns_are_exact_and_rotation_matches_rodrigues)
{
    VECTOR3 z = { 0, 0, 1 }, x = { 1, 0, 0 }, p;
    xform_t r = xform_rotate(z, 90);
    xform_point(&r, p, x);
    ck_assert(p[X] == 0 && p[Y] == 1 && p[Z] == 0); /* counter-clockwise */
    r = xform_rotate(z, -270);
    xform_point(&r, p, x);
    ck_assert(p[X] == 0 && p[Y] == 1 && p[Z] == 0);
    r = xform_rotate(yaxis, 180);
    xform_point(&r, p, x);
    ck_assert(p[X] == -1 && p[Y] == 0 && p[Z] == 0);
    r = xform_rotate(yaxis, 720);
    xform_point(&r, p, x);
    ck_assert(p[X] == 1 && p[Y] == 0 && p[Z] == 0);
    pcg32_t g;
    pcg32_seed(&g, 43, 44);
    long n = 0;
    for (int i = 0; i < 5000; i++, n++) {
        VECTOR3 k, a, want, got;
        geomcheck_random_dir(k, &g);
        geomcheck_random_dir(a, &g);
        real deg = 720 * pcg32_real(&g) - 360;
        vec_rotate(want, a, k, deg * (REAL_PI / 180));
        VECTOR3 k3;
        vec_scale(k3, k, 3); /* any length of axis */
        r = xform_rotate(k3, deg);
        xform_vector(&r, got, a);
        for (int c = 0; c < 3; c++)
            ck_assert_near(got[c], want[c], 16 * REAL_EPSILON);
    }
    test_report_cases("rotation_matches_vec_rotate", n);
}
END_TEST

START_TEST(singular_and_invalid_transforms_are_refused)
{
    VECTOR3 zero = { 0, 0, 0 }, flat = { 1, 0, 1 }, nan = { 1, (real)NAN, 1 };
    svet_error err;
    xform_t out;
    ck_assert(!xform_scale(flat).valid);
    ck_assert(!xform_scale(nan).valid);
    ck_assert(!xform_rotate(zero, 30).valid);
    ck_assert(!xform_rotate(yaxis, (real)INFINITY).valid);
    ck_assert(!xform_translate(nan).valid);
    ck_assert(!xform_compose(xform_identity(), xform_scale(flat)).valid);
    xform_t bad = xform_scale(flat);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            ck_assert(isfinite(bad.m[i][j]) && isfinite(bad.inv[i][j]));
    ck_assert_int_eq(xform_invert(&bad, &out, &err), SVET_ERR_RANGE);
    /* a matrix with two nearly parallel columns */
    real m[12] = { 1, 1, 0, 0, 0, 4 * REAL_EPSILON, 0, 0, 0, 0, 1, 0 };
    ck_assert_int_eq(xform_from_matrix(m, &out, &err), SVET_ERR_RANGE);
    ck_assert_msg(strstr(err.msg, "singular") != NULL, "%s", err.msg);
    m[5] = 1;
    ck_assert_int_eq(xform_from_matrix(m, &out, &err), SVET_OK);
    /* a shear and its inverse: (x + y, y, z) */
    VECTOR3 p = { 1, 2, 3 }, q;
    xform_point(&out, q, p);
    ck_assert(q[X] == 3 && q[Y] == 2 && q[Z] == 3);
    VECTOR3 lo = { -1, -1, -1 }, hi = { 1, 1, 1 };
    ck_assert_ptr_null(xform_new(box_new(lo, hi, &err), &bad, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    /* an inverse that is not one */
    xform_t wrong = xform_identity();
    wrong.inv[0][0] = 2;
    ck_assert_ptr_null(xform_new(box_new(lo, hi, &err), &wrong, &err));
    ck_assert_msg(strstr(err.msg, "not the inverse") != NULL, "%s", err.msg);
    /* a failed inner constructor passes through with its own message */
    xform_t id = xform_identity();
    ck_assert_ptr_null(xform_new(box_new(hi, lo, &err), &id, &err));
    ck_assert_msg(strstr(err.msg, "box: min") != NULL, "%s", err.msg);
    ck_assert_ptr_null(xform_of(NULL));
}
END_TEST

START_TEST(normals_stay_perpendicular_under_non_uniform_scale)
{
    pcg32_t g;
    pcg32_seed(&g, 45, 46);
    long n = 0;
    for (int i = 0; i < 10000; i++, n++) {
        xform_t x = random_xform(&g);
        VECTOR3 nn, t, tw, nw, a;
        geomcheck_random_dir(nn, &g);
        geomcheck_random_dir(a, &g);
        VVECTOR3(t, nn, a); /* a tangent: t . n = 0 */
        xform_vector(&x, tw, t);
        xform_normal(&x, nw, nn);
        /* |tw . nw| against the sizes involved */
        double tol = 64 * (double)REAL_EPSILON * (double)vec_length(tw) *
                     (double)vec_length(nw) * 25;
        ck_assert_near(SVECTOR3(tw, nw), 0, tol);
    }
    test_report_cases("normals_stay_perpendicular_under_non_uniform_scale", n);
}
END_TEST

/* the Cornell box's blocks, as the common reference scene places them
 * (scenes/cbox.scn) */
static xform_t block(real sx, real sy, real sz, real deg, real tx, real ty,
                     real tz)
{
    return xform_compose(xform_compose(xform_scale((VECTOR3){ sx, sy, sz }),
                                       xform_rotate(yaxis, deg)),
                         xform_translate((VECTOR3){ tx, ty, tz }));
}

START_TEST(cornell_box_blocks_have_the_hand_computed_corners)
{
    /* The cube [-1,1]^3 scaled by s, turned by a about y (x' = x cos a +
     * z sin a, z' = -x sin a + z cos a), moved by t. Small block: s = 0.3,
     * a = -17 deg, cos = 0.95630475596303544, sin = -0.29237170472273677;
     * e.g. corner (1,1,1): x = 0.335 + 0.3 (cos a + sin a) = 0.534179915,
     * z = 0.38 + 0.3 (cos a - sin a) = 0.754602938. Large block:
     * s = (0.3, 0.61, 0.3), a = 18.25 deg, t = (-0.33, -0.4, -0.28). */
    const double small[8][3] = {
        { 0.13582008462791045, -1, 0.0053970617942683541 },
        { -0.03960293820573163, -1, 0.57917991537208957 },
        { 0.13582008462791045, -0.4, 0.0053970617942683541 },
        { -0.03960293820573163, -0.4, 0.57917991537208957 },
        { 0.70960293820573161, -1, 0.18082008462791044 },
        { 0.53417991537208964, -1, 0.75460293820573165 },
        { 0.70960293820573161, -0.4, 0.18082008462791044 },
        { 0.53417991537208964, -0.4, 0.75460293820573165 } };
    const double large[8][3] = {
        { -0.70885887980568807, -1.01, -0.47096059591543826 },
        { -0.52096059591543831, -1.01, 0.098858879805687971 },
        { -0.70885887980568807, 0.21, -0.47096059591543826 },
        { -0.52096059591543831, 0.21, 0.098858879805687971 },
        { -0.13903940408456175, -1.01, -0.65885887980568802 },
        { 0.048858879805687983, -1.01, -0.089039404084561763 },
        { -0.13903940408456175, 0.21, -0.65885887980568802 },
        { 0.048858879805687983, 0.21, -0.089039404084561763 } };
    xform_t xs = block(REAL_C(0.3), REAL_C(0.3), REAL_C(0.3), -17,
                       REAL_C(0.335), REAL_C(-0.7), REAL_C(0.38));
    xform_t xl = block(REAL_C(0.3), REAL_C(0.61), REAL_C(0.3), REAL_C(18.25),
                       REAL_C(-0.33), REAL_C(-0.4), REAL_C(-0.28));
    for (int c = 0; c < 8; c++) {
        VECTOR3 p = { c & 4 ? 1 : -1, c & 2 ? 1 : -1, c & 1 ? 1 : -1 }, q;
        xform_point(&xs, q, p);
        for (int k = 0; k < 3; k++)
            ck_assert_near(q[k], small[c][k], 8 * REAL_EPSILON);
        xform_point(&xl, q, p);
        for (int k = 0; k < 3; k++)
            ck_assert_near(q[k], large[c][k], 8 * REAL_EPSILON);
    }
    /* the oriented box: its area is that of the scaled cube, and a ray
     * straight down onto its top hits at y = -0.4 */
    VECTOR3 lo = { -1, -1, -1 }, hi = { 1, 1, 1 };
    svet_error err;
    COBJECT *o = xform_new(box_new(lo, hi, &err), &xs, &err);
    ck_assert_msg(o != NULL, "%s", err.msg);
    ck_assert_near(o->ops->area(o), 6 * 0.36, 16 * REAL_EPSILON);
    ray_t r = { { REAL_C(0.335), 1, REAL_C(0.38) }, { 0, -1, 0 } };
    hit_t h;
    ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
    PATHPOINT pp;
    cobject_fill(o, &r, &h, &pp);
    ck_assert_near(pp.cross_point[Y], -0.4, 8 * REAL_EPSILON);
    ck_assert_near(pp.ng[Y], 1, 8 * REAL_EPSILON);
    ck_assert_int_eq(pp.prim, BOX_YMAX);
    bbox_t b;
    o->ops->bounds(o, -1, &b);
    ck_assert((double)b.min[X] <= -0.0396029382 &&
              (double)b.max[X] >= 0.7096029382 && b.min[Y] <= -1 &&
              (double)b.max[Z] >= 0.7546029382);
    ck_assert_near(b.min[X], -0.03960293820573163, 1e-5);
    cobject_free(o);
}
END_TEST

START_TEST(flat_shapes_and_boxes_keep_exact_areas_under_any_map)
{
    pcg32_t g;
    pcg32_seed(&g, 47, 48);
    long n = 0;
    for (int i = 0; i < 300; i++, n++) {
        xform_t x = random_xform(&g);
        svet_error err;
        /* triangle: area |M e1 x M e2| / 2 */
        VECTOR3 p0 = { 0, 0, 0 }, p1 = { 2, 0, 1 }, p2 = { -1, 3, 0 };
        VECTOR3 q0, q1, q2, e1, e2, c;
        xform_point(&x, q0, p0);
        xform_point(&x, q1, p1);
        xform_point(&x, q2, p2);
        vec_sub(e1, q1, q0);
        vec_sub(e2, q2, q0);
        VVECTOR3(c, e1, e2);
        COBJECT *t = xform_new(triangle_new(p0, p1, p2, &err), &x, &err);
        ck_assert_msg(t != NULL, "%s", err.msg);
        ck_assert_rel(t->ops->area(t), vec_length(c) / 2, 64 * REAL_EPSILON,
                      0);
        /* box: six faces, each |M a x M b| */
        VECTOR3 lo = { -1, 0, 2 }, hi = { 1, REAL_C(0.5), 5 };
        COBJECT *bx = xform_new(box_new(lo, hi, &err), &x, &err);
        ck_assert_msg(bx != NULL, "%s", err.msg);
        double want = 0;
        VECTOR3 ext = { 2, REAL_C(0.5), 3 };
        for (int k = 0; k < 3; k++) {
            VECTOR3 a = { 0, 0, 0 }, b = { 0, 0, 0 }, ma, mb;
            a[(k + 1) % 3] = ext[(k + 1) % 3];
            b[(k + 2) % 3] = ext[(k + 2) % 3];
            xform_vector(&x, ma, a);
            xform_vector(&x, mb, b);
            VVECTOR3(c, ma, mb);
            want += 2 * (double)vec_length(c);
        }
        ck_assert_rel(bx->ops->area(bx), want, 64 * REAL_EPSILON, 0);
        cobject_free(t);
        cobject_free(bx);
    }
    test_report_cases("flat_shapes_and_boxes_keep_exact_areas_under_any_map",
                      n);
}
END_TEST

/* Surface area of a spheroid with equatorial radius a and polar c:
 * prolate (c > a): 2 pi a^2 (1 + c / (a e) asin e), e^2 = 1 - a^2/c^2;
 * oblate (c < a): 2 pi a^2 (1 + (1 - e^2) / e atanh e), e^2 = 1 - c^2/a^2
 * (e.g. Beyer, CRC Standard Mathematical Tables). */
static double spheroid_area(double a, double c)
{
    const double pi = 3.14159265358979323846;
    if (c > a) {
        double e = sqrt(1 - a * a / (c * c));
        return 2 * pi * a * a * (1 + c / (a * e) * asin(e));
    }
    double e = sqrt(1 - c * c / (a * a));
    return 2 * pi * a * a * (1 + (1 - e * e) / e * atanh(e));
}

START_TEST(ellipsoid_area_matches_the_spheroid_closed_form)
{
    const double cases[4][2] = { { 1, 2 }, { 2, 1 }, { 1, 5 }, { 3, 0.5 } };
    for (int i = 0; i < 4; i++) {
        VECTOR3 c = { 0, 0, 0 }, s = { (real)cases[i][0], (real)cases[i][0],
                                       (real)cases[i][1] };
        svet_error err;
        xform_t x = xform_compose(xform_scale(s),
                                  xform_translate((VECTOR3){ 3, -2, 7 }));
        COBJECT *o = xform_new(sphere_new(c, 1, &err), &x, &err);
        ck_assert_msg(o != NULL, "%s", err.msg);
        /* the quadrature's own error is far below rounding for the
         * sphere's smooth map; in float each term carries a few epsilon */
        ck_assert_rel(o->ops->area(o), spheroid_area(cases[i][0], cases[i][1]),
                      fmax(64 * (double)REAL_EPSILON, 1e-9), 0);
        cobject_free(o);
    }
    /* a similarity: exact, 4 pi r^2 */
    VECTOR3 c = { 1, 1, 1 }, s = { 3, 3, 3 };
    svet_error err;
    xform_t x = xform_compose(xform_scale(s), xform_rotate(yaxis, 33));
    COBJECT *o = xform_new(sphere_new(c, 2, &err), &x, &err);
    ck_assert_rel(o->ops->area(o), 4 * 3.14159265358979323846 * 36,
                  16 * REAL_EPSILON, 0);
    cobject_free(o);
}
END_TEST

/* Area of the zone z1 <= z <= z2 of the spheroid x^2/a^2 + y^2/a^2 +
 * z^2/c^2 = 1: dA = 2 pi x sqrt(1 + x'^2) dz = 2 pi a sqrt(1 - k^2 z^2) dz,
 * k^2 = (c^2 - a^2) / c^4 (c > a), which integrates to
 * pi a [z sqrt(1 - k^2 z^2) + asin(k z) / k] from z1 to z2. */
static double zone_area(double a, double c, double z1, double z2)
{
    const double pi = 3.14159265358979323846;
    double k = sqrt(c * c - a * a) / (c * c);
    double f2 = z2 * sqrt(1 - k * k * z2 * z2) + asin(k * z2) / k;
    double f1 = z1 * sqrt(1 - k * k * z1 * z1) + asin(k * z1) / k;
    return pi * a * (f2 - f1);
}

/* Monte Carlo of the surface integral of [z > z0] by the object's own
 * sampler, E[[z > z0] / pdf], and of 1, E[1 / pdf]; with standard errors
 * from the sample variance. Checks that every sample lies on the
 * ellipsoid with semi-axes s. */
static void mc_areas(const COBJECT *o, const VECTOR3 s, double z0, int n,
                     double m[2], double se[2], pcg32_t *g)
{
    double sum[2] = { 0, 0 }, sum2[2] = { 0, 0 };
    for (int i = 0; i < n; i++) {
        real u[2] = { pcg32_real(g), pcg32_real(g) };
        cobject_sample_t sm;
        o->ops->sample(o, u, &sm);
        ck_assert(sm.pdf > 0 && isfinite(sm.pdf));
        double px = (double)sm.p[X] / (double)s[X],
               py = (double)sm.p[Y] / (double)s[Y],
               pz = (double)sm.p[Z] / (double)s[Z];
        ck_assert_near(px * px + py * py + pz * pz, 1, 64 * REAL_EPSILON);
        double w = 1 / (double)sm.pdf, v[2] = { w, (double)sm.p[Z] > z0 ? w : 0 };
        for (int k = 0; k < 2; k++) {
            sum[k] += v[k];
            sum2[k] += v[k] * v[k];
        }
    }
    for (int k = 0; k < 2; k++) {
        m[k] = sum[k] / n;
        se[k] = sqrt(fmax(sum2[k] / n - m[k] * m[k], 0.0) / n);
    }
}

START_TEST(ellipsoid_samples_carry_their_exact_density)
{
    /* The sampler is uniform on the sphere, so on the ellipsoid its
     * density is 1 / (4 pi J): if that pdf is right, the mean of
     * indicator / pdf is the area of the region (5 standard errors). */
    pcg32_t g;
    pcg32_seed(&g, 49, 50);
    const int N = 40000;
    VECTOR3 c = { 0, 0, 0 }, s = { 1, 1, 4 }, s3 = { 1, 2, 4 };
    svet_error err;
    xform_t x = xform_scale(s);
    COBJECT *o = xform_new(sphere_new(c, 1, &err), &x, &err);
    ck_assert_msg(o != NULL, "%s", err.msg);
    double m[2], se[2];
    mc_areas(o, s, 2, N, m, se, &g);
    ck_assert_near(m[0], spheroid_area(1, 4), 5 * se[0]);
    ck_assert_near(m[1], zone_area(1, 4, 2, 4), 5 * se[1]);
    cobject_free(o);
    /* tri-axial: against the quadrature area */
    x = xform_scale(s3);
    o = xform_new(sphere_new(c, 1, &err), &x, &err);
    mc_areas(o, s3, 2, N, m, se, &g);
    ck_assert_near(m[0], o->ops->area(o), 5 * se[0]);
    cobject_free(o);
    test_report_cases("ellipsoid_samples_carry_their_exact_density", 2 * N);
}
END_TEST

START_TEST(nested_transforms_merge_into_one)
{
    VECTOR3 lo = { -1, -1, -1 }, hi = { 1, 1, 1 }, s = { 2, 1, 1 },
            t = { 0, 5, 0 };
    svet_error err;
    xform_t a = xform_scale(s), b = xform_translate(t);
    COBJECT *o = xform_new(xform_new(box_new(lo, hi, &err), &a, &err), &b,
                           &err);
    ck_assert_msg(o != NULL, "%s", err.msg);
    const xform_t *x = xform_of(o);
    ck_assert_ptr_nonnull(x);
    ck_assert(x->m[0][0] == 2 && x->m[1][3] == 5 && x->inv[0][0] == REAL_C(0.5));
    ray_t r = { { 0, 10, 0 }, { 0, -1, 0 } };
    hit_t h;
    ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
    ck_assert_near(h.t, 4, 8 * REAL_EPSILON);
    cobject_free(o);
}
END_TEST

START_TEST(a_mirrored_box_keeps_outward_normals)
{
    VECTOR3 lo = { 0, 0, 0 }, hi = { 1, 2, 3 }, s = { -1, 1, 1 };
    svet_error err;
    xform_t x = xform_scale(s);
    COBJECT *o = xform_new(box_new(lo, hi, &err), &x, &err);
    ck_assert_msg(o != NULL, "%s", err.msg);
    pcg32_t g;
    pcg32_seed(&g, 51, 52);
    long n = 0;
    for (int i = 0; i < 5000; i++) {
        /* from far outside toward the box: the normal faces the ray */
        ray_t r;
        VECTOR3 dir, target = { REAL_C(-0.5), 1, REAL_C(1.5) };
        geomcheck_random_dir(dir, &g);
        vec_add_scaled(r.o, target, 10, dir);
        vec_neg(r.d, dir);
        hit_t h;
        ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
        PATHPOINT pp;
        cobject_fill(o, &r, &h, &pp);
        ck_assert(SVECTOR3(pp.ng, r.d) < 0 && pp.bout);
        VECTOR3 c;
        VVECTOR3(c, pp.u, pp.v);
        for (int k = 0; k < 3; k++)
            ck_assert_near(c[k], pp.n[k], 8 * REAL_EPSILON);
        n++;
    }
    test_report_cases("a_mirrored_box_keeps_outward_normals", n);
    cobject_free(o);
}
END_TEST

/* A transformed box, and a box to test the same ray in object space by
 * hand: the reference without xform's culling sphere. */
START_TEST(the_culling_sphere_never_turns_away_a_hit)
{
    /* xform_intersect first tests a padded sphere about a transformed box
     * (fast/xform_cull.c). Against the box hit by hand in object space - the ray
     * mapped by the same matrix, then box_intersect - the answers must be
     * the same bits. The rays that come nearest to the sphere's boundary
     * while hitting the box are those through its corners (on the
     * sphere) and along its edges, and along the edges through a corner;
     * origins from 2^-4 to 2^20 away, and on the box itself leaving it. */
    pcg32_t g;
    pcg32_seed(&g, 61, 62);
    long n = 0, hits = 0;
    for (int i = 0; i < 400; i++) {
        VECTOR3 lo, hi;
        for (int k = 0; k < 3; k++) {
            lo[k] = 4 * pcg32_real(&g) - 2;
            hi[k] = lo[k] + REAL_C(0.01) + 2 * pcg32_real(&g);
        }
        /* every other box a slab: its short edges are nearly tangent to
         * the sphere through its corners */
        if (i % 2)
            hi[i % 3] = lo[i % 3] + ldexp(REAL_C(1.0), -(int)pcg32_bounded(&g, 16));
        xform_t x = random_xform(&g);
        svet_error err;
        COBJECT *box = box_new(lo, hi, &err);
        COBJECT *o = xform_new(box_new(lo, hi, &err), &x, &err);
        ck_assert_msg(box && o, "%s", err.msg);
        const xform_t *xf = xform_of(o);
        xform_t inv = *xf;
        memcpy(inv.m, xf->inv, sizeof inv.m);
        for (int j = 0; j < 100; j++) {
            /* a corner, the middle of an edge, or a point of a face, moved
             * off by up to 2^-20 of the box */
            VECTOR3 q;
            int kind = j % 3;
            for (int k = 0; k < 3; k++) {
                real f = kind == 0 ? (real)pcg32_bounded(&g, 2)
                                   : pcg32_real(&g);
                if (kind == 1 && k == j % 9 / 3)
                    f = REAL_C(0.5);
                q[k] = lo[k] + f * (hi[k] - lo[k]) +
                       ldexp(2 * pcg32_real(&g) - 1, -20);
            }
            VECTOR3 target, dir;
            xform_point(xf, target, q);
            geomcheck_random_dir(dir, &g);
            if (j % 4 == 3) {
                /* along an edge through a corner, tilted by 2^-k: the
                 * grazing hits; along a thin box's short edge they pass
                 * the centre at nearly the sphere's radius */
                VECTOR3 e = { 0, 0, 0 }, ew;
                for (int k = 0; k < 3; k++)
                    q[k] = pcg32_bounded(&g, 2) ? hi[k] : lo[k];
                e[j % 12 / 4] = 1;
                xform_point(xf, target, q);
                xform_vector(xf, ew, e);
                vec_normalize(ew, ew);
                real tilt = ldexp(REAL_C(1.0), -(int)pcg32_bounded(&g, 30));
                vec_add_scaled(dir, ew, tilt, dir);
                vec_normalize(dir, dir);
            }
            ray_t r;
            bool leaving = pcg32_bounded(&g, 4) == 0;
            real dist = leaving ? 0
                                : ldexp(REAL_C(1.0),
                                        (int)pcg32_bounded(&g, 25) - 4);
            vec_add_scaled(r.o, target, dist, dir);
            if (leaving)
                vec_copy(r.d, dir); /* from the surface, either way */
            else
                vec_neg(r.d, dir);
            ray_t ro;
            xform_point(&inv, ro.o, r.o);
            xform_vector(&inv, ro.d, r.d);
            real m = fmax(fabs(r.d[X]), fmax(fabs(r.d[Y]), fabs(r.d[Z])));
            ck_assert(m >= REAL_C(0x1p-16) && m < REAL_C(0x1p17));
            hit_t h1 = { 0, 0, { 0, 0, 0 } }, h2 = h1;
            bool a = box->ops->intersect(box, 0, &ro, 0, (real)INFINITY, &h1);
            bool b = o->ops->intersect(o, 0, &r, 0, (real)INFINITY, &h2);
            ck_assert_msg(a == b, "box %d ray %d: %d vs %d", i, j, (int)a,
                          (int)b);
            if (a) {
                hits++;
                ck_assert(memcmp(&h1.t, &h2.t, sizeof h1.t) == 0);
                ck_assert(h1.b[0] == h2.b[0]);
            }
            n++;
        }
        cobject_free(box);
        cobject_free(o);
    }
    ck_assert(hits > n / 3);
    test_report_cases("the_culling_sphere_never_turns_away_a_hit", n);
}
END_TEST

/* Box i of a random series: corners in [-2, 2]^3, extents 0.01 to 2.01,
 * every third one thin along one axis (2^-15 to 1), and a scale s3 of
 * 2^-20 to 2^20 per axis for the map. */
static void random_box(pcg32_t *g, int i, VECTOR3 lo, VECTOR3 hi, VECTOR3 s3)
{
    for (int k = 0; k < 3; k++) {
        lo[k] = 4 * pcg32_real(g) - 2;
        hi[k] = lo[k] + REAL_C(0.01) + 2 * pcg32_real(g);
        s3[k] = ldexp(REAL_C(1.0), (int)pcg32_bounded(g, 41) - 20);
    }
    if (i % 3 == 1)
        hi[i % 3] = lo[i % 3] + ldexp(REAL_C(1.0), -(int)pcg32_bounded(g, 16));
}

/* o's surface() of hit h on r, in *p1, checked byte for byte against
 * xform_surface_generic(). */
static void surface_as_generic(const COBJECT *o, const ray_t *r,
                               const hit_t *h, PATHPOINT *p1)
{
    PATHPOINT p2;
    memset(p1, 0, sizeof *p1);
    memset(&p2, 0, sizeof p2);
    p1->prim = p2.prim = h->prim;
    o->ops->surface(o, r, h, p1);
    xform_surface_generic(o, r, h, &p2);
    ck_assert(memcmp(p1, &p2, sizeof p2) == 0);
}

/* The fields of two hits, bit for bit (not the padding). */
static bool same_hit_fields(const hit_t *a, const hit_t *b)
{
    return memcmp(&a->t, &b->t, sizeof a->t) == 0 && a->prim == b->prim &&
           memcmp(a->b, b->b, sizeof a->b) == 0;
}

START_TEST(xform_plain_and_fast_agree_field_by_field)
{
    /* intersect() of the build (the culling sphere, the box's slabs and
     * SSE rows where SIMD=on) against xform_intersect_plain(), and
     * surface() against xform_surface_generic(), byte for byte: boxes,
     * spheres and parallelograms under random maps (mirrors included)
     * scaled by 2^-20 to 2^20 per axis; rays of every class (NaN,
     * infinite and zero directions, directions far from unit length),
     * rays aimed at the object from near and far, grazing ones, and rays
     * spawned from its hits in and out, over (0, inf), a short segment
     * and intervals of every class. */
    pcg32_t g;
    pcg32_seed(&g, 81, 82);
    long n = 0, hits = 0;
    for (int i = 0; i < 300; i++) {
        VECTOR3 lo, hi, s3, zero = { 0, 0, 0 }, a = { 1, 0, 0 },
                                  b = { 0, 1, 0 };
        random_box(&g, i, lo, hi, s3);
        xform_t x = random_xform(&g);
        if (i % 2)
            x = xform_compose(x, xform_scale(s3));
        svet_error err;
        COBJECT *in = i % 3 == 0   ? box_new(lo, hi, &err)
                      : i % 3 == 1 ? sphere_new(zero, 1, &err)
                                   : parallelogram_new(zero, a, b, &err);
        COBJECT *o = xform_new(in, &x, &err);
        if (!o)
            continue; /* a map singular to working precision */
        const xform_t *xf = xform_of(o);
        for (int j = 0; j < 300; j++, n++) {
            ray_t r;
            real tmin = 0, tmax = (real)INFINITY;
            if (j % 4 == 0) {
                geomcheck_any_ray(&r, &tmin, &tmax, &g);
            } else {
                VECTOR3 q, target, dir;
                for (int k = 0; k < 3; k++)
                    q[k] = i % 3 == 0 ? lo[k] + pcg32_real(&g) * (hi[k] - lo[k])
                                      : 2 * pcg32_real(&g) - 1;
                xform_point(xf, target, q);
                geomcheck_random_dir(dir, &g);
                real dist = ldexp(shape_max_abs(target) + 1,
                                  (int)pcg32_bounded(&g, 24) - 20);
                vec_add_scaled(r.o, target, dist, dir);
                vec_neg(r.d, dir);
                if (j % 4 == 2)
                    vec_scale(r.d, r.d, ldexp(REAL_C(1.0),
                                              (int)pcg32_bounded(&g, 61) - 30));
                if (j % 8 == 3)
                    tmax = dist * REAL_C(0.5);
            }
            hit_t h1 = { 0, 0, { 0, 0, 0 } }, h2 = h1;
            bool a1 = o->ops->intersect(o, 0, &r, tmin, tmax, &h1);
            bool a2 = xform_intersect_plain(o, 0, &r, tmin, tmax, &h2);
            ck_assert_msg(a1 == a2 && (!a1 || same_hit_fields(&h1, &h2)),
                          "object %d ray %d: o (%a %a %a) d (%a %a %a) (%a, "
                          "%a): %d, plain %d", i, j, (double)r.o[X],
                          (double)r.o[Y], (double)r.o[Z], (double)r.d[X],
                          (double)r.d[Y], (double)r.d[Z], (double)tmin,
                          (double)tmax, (int)a1, (int)a2);
            if (!a1 || !(tmin >= 0) || !vec_is_finite(r.o) ||
                !vec_is_finite(r.d))
                continue;
            hits++;
            PATHPOINT p1;
            surface_as_generic(o, &r, &h1, &p1);
            /* rays spawned from the hit, out along the normal and back in */
            for (int side = 0; side < 2; side++, n++) {
                ray_t s;
                VECTOR3 w;
                geomcheck_random_dir(w, &g);
                if ((SVECTOR3(w, p1.ng) < 0) != (side == 1))
                    vec_neg(w, w);
                ray_spawn(&s, p1.cross_point, p1.p_error, p1.ng, w);
                hit_t k1 = { 0, 0, { 0, 0, 0 } }, k2 = k1;
                bool b1 = o->ops->intersect(o, 0, &s, 0, (real)INFINITY, &k1);
                bool b2 = xform_intersect_plain(o, 0, &s, 0, (real)INFINITY,
                                                &k2);
                ck_assert(b1 == b2 && (!b1 || same_hit_fields(&k1, &k2)));
            }
        }
        cobject_free(o);
    }
    ck_assert(hits > n / 10);
    test_report_cases("xform_plain_and_fast_agree_field_by_field", n);
}
END_TEST

START_TEST(box_face_table_completes_hits_as_the_general_way_bit_for_bit)
{
    /* A transformed box's surface() takes the world normals, derivatives
     * and frame of a hit from a table made once per face (fast/xform_cull.c); the
     * general way maps them at every hit (and its world point and bound
     * come from the plain rows, the table's way from SSE lanes in
     * float). The same bytes, PATHPOINT for
     * PATHPOINT, on hits from outside and from rays leaving a face, for
     * random maps (mirrors included), thin boxes and scales 2^-20 to
     * 2^20; and for an ellipsoid, which has no table. */
    pcg32_t g;
    pcg32_seed(&g, 71, 72);
    long n = 0;
    for (int i = 0; i < 300; i++) {
        VECTOR3 lo, hi, s3;
        random_box(&g, i, lo, hi, s3);
        xform_t x = random_xform(&g);
        if (i % 2)
            x = xform_compose(x, xform_scale(s3));
        svet_error err;
        VECTOR3 centre = { 0, 0, 0 };
        COBJECT *o = i % 10 == 9
                         ? xform_new(sphere_new(centre, 1, &err), &x, &err)
                         : xform_new(box_new(lo, hi, &err), &x, &err);
        if (!o)
            continue; /* a map singular to working precision */
        const xform_t *xf = xform_of(o);
        for (int j = 0; j < 200; j++) {
            VECTOR3 q, target, dir;
            for (int k = 0; k < 3; k++)
                q[k] = i % 10 == 9 ? 2 * pcg32_real(&g) - 1
                                   : lo[k] + pcg32_real(&g) * (hi[k] - lo[k]);
            xform_point(xf, target, q);
            geomcheck_random_dir(dir, &g);
            ray_t r;
            real dist = 4 * shape_max_abs(target) + 1;
            vec_add_scaled(r.o, target, dist, dir);
            vec_neg(r.d, dir);
            hit_t h = { 0, 0, { 0, 0, 0 } };
            if (!o->ops->intersect(o, 0, &r, 0, (real)INFINITY, &h))
                continue;
            for (int pass = 0; pass < 2; pass++) {
                PATHPOINT p1;
                surface_as_generic(o, &r, &h, &p1);
                n++;
                /* then a ray leaving that point, and its hit on the far
                 * side */
                ray_spawn(&r, p1.cross_point, p1.p_error, p1.ng, r.d);
                h = (hit_t){ 0, 0, { 0, 0, 0 } };
                if (!o->ops->intersect(o, 0, &r, 0, (real)INFINITY, &h))
                    break;
            }
        }
        cobject_free(o);
    }
    ck_assert(n > 50000);
    test_report_cases("box_face_table_completes_hits_as_the_general_way_bit_"
                      "for_bit", n);
}
END_TEST

/* One ray r over (tmin, tmax) of the slab test below, on the transformed
 * box o (inner: the same box untransformed): xform_intersect_unculled()
 * and xform_intersect_unseparated() give the same answer and hit bytes;
 * where d needs no rescaling, the answer is also the box's own on the
 * ray mapped to object space by the plain rows (xform_point() and
 * xform_vector() with the inverse; fast/xform_cull.c maps it with SSE in float).
 * Adds 1 to *turned on a miss; returns whether the mapped check ran. */
static bool as_plain_rows(const COBJECT *o, const COBJECT *inner,
                          const ray_t *r, real tmin, real tmax, long *turned)
{
    hit_t h1, h2;
    memset(&h1, 0x5a, sizeof h1);
    memset(&h2, 0x5a, sizeof h2);
    bool a = xform_intersect_unculled(o, 0, r, tmin, tmax, &h1);
    bool b = xform_intersect_unseparated(o, 0, r, tmin, tmax, &h2);
    ck_assert_msg(a == b, "o (%a %a %a) d (%a %a %a) (%a, %a): %d, "
                  "unseparated %d", (double)r->o[X], (double)r->o[Y],
                  (double)r->o[Z], (double)r->d[X], (double)r->d[Y],
                  (double)r->d[Z], (double)tmin, (double)tmax, (int)a, (int)b);
    ck_assert(memcmp(&h1, &h2, sizeof h1) == 0);
    *turned += !a;
    real dm = real_max(fabs(r->d[X]), real_max(fabs(r->d[Y]), fabs(r->d[Z])));
    if (!(dm >= REAL_C(0x1p-16) && dm < REAL_C(0x1p17)))
        return false;
    const xform_t *xf = xform_of(o);
    xform_t back = *xf;
    memcpy(back.m, xf->inv, sizeof back.m);
    ray_t ro;
    xform_point(&back, ro.o, r->o);
    xform_vector(&back, ro.d, r->d);
    hit_t h3 = { 0, 0, { 0, 0, 0 } };
    bool c = vec_is_finite(ro.o) && vec_is_finite(ro.d) &&
             (ro.d[X] != 0 || ro.d[Y] != 0 || ro.d[Z] != 0) &&
             inner->ops->intersect(inner, 0, &ro, tmin, tmax, &h3) &&
             h3.t > tmin && h3.t < tmax;
    ck_assert_msg(c == b, "o (%a %a %a) d (%a %a %a): %d, plain rows %d",
                  (double)r->o[X], (double)r->o[Y], (double)r->o[Z],
                  (double)r->d[X], (double)r->d[Y], (double)r->d[Z], (int)b,
                  (int)c);
    ck_assert(!c || (memcmp(&h3.t, &h2.t, sizeof h3.t) == 0 &&
                     h3.prim == h2.prim &&
                     memcmp(h3.b, h2.b, sizeof h3.b) == 0));
    return true;
}

START_TEST(leaving_a_box_slab_answers_as_the_full_test_bit_for_bit)
{
    /* xform_intersect_unculled() turns away, for a transformed box, a ray
     * whose object-space origin lies beyond a slab and whose direction
     * does not point back (leaves_box() in fast/xform_cull.c); the full slab test
     * (xform_intersect_unseparated) must give the same answer and the
     * same hit bytes. Rays: through random points of the box from far
     * away, spawned from the hits outward (cosine-weighted and grazing,
     * as the integrator spawns them) and inward, from random points in
     * and around the box, world directions along the axes (zero object
     * components under quarter turns), tmin 0, -1 or tiny, tmax infinite
     * or short; random maps (mirrors included), thin boxes, scales 2^-20
     * to 2^20. Where d needs no rescaling, the answer is also the box's
     * own on the ray mapped to object space by the plain rows (the SSE
     * object-space ray of xform.c against them). A quarter of the rays
     * again with a NaN, an infinity, REAL_MAX or 2^120 in o or d (their
     * object-space images overflow under the smaller scales): the same
     * answers as the plain rows give. */
    pcg32_t g;
    pcg32_seed(&g, 91, 92);
    long n = 0, turned = 0, mapped = 0, extreme = 0, extreme_missed = 0;
    for (int i = 0; i < 300; i++) {
        VECTOR3 lo, hi, s3;
        random_box(&g, i, lo, hi, s3);
        VECTOR3 ax = { 0, 0, 1 };
        xform_t x = i % 4 == 3 ? xform_rotate(ax, 90) : random_xform(&g);
        if (i % 2)
            x = xform_compose(x, xform_scale(s3));
        svet_error err;
        COBJECT *o = xform_new(box_new(lo, hi, &err), &x, &err);
        if (!o)
            continue; /* a map singular to working precision */
        const xform_t *xf = xform_of(o);
        COBJECT *inner = box_new(lo, hi, &err);
        ck_assert(inner != NULL);
        for (int j = 0; j < 1000; j++) {
            VECTOR3 q, p, dir;
            for (int k = 0; k < 3; k++)
                q[k] = lo[k] + (3 * pcg32_real(&g) - 1) * (hi[k] - lo[k]);
            xform_point(xf, p, q);
            geomcheck_random_dir(dir, &g);
            if (j % 7 == 0) { /* along a world axis */
                int a = (int)pcg32_bounded(&g, 3);
                vec_set(dir, 0, 0, 0);
                dir[a] = pcg32_next(&g) % 2 ? 1 : -1;
            }
            ray_t r;
            if (j % 2) { /* from far away through p */
                real dist = 4 * shape_max_abs(p) + 1;
                vec_add_scaled(r.o, p, dist, dir);
                vec_neg(r.d, dir);
            } else { /* from p itself */
                vec_copy(r.o, p);
                vec_copy(r.d, dir);
            }
            for (int pass = 0; pass < 3; pass++) {
                const real tmins[3] = { 0, -1, REAL_C(1e-6) };
                real tmin = tmins[pcg32_bounded(&g, 3)];
                real tmax = pcg32_next(&g) % 4 ? (real)INFINITY
                                               : 4 * pcg32_real(&g);
                n++;
                mapped += as_plain_rows(o, inner, &r, tmin, tmax, &turned);
                if (j % 4 == 0) {
                    /* a NaN, an infinity, or a number whose image in
                     * object space may overflow, in o or d */
                    const real bad[6] = { (real)NAN, (real)INFINITY,
                                          -(real)INFINITY, REAL_MAX,
                                          -REAL_MAX, REAL_C(0x1p120) };
                    ray_t e = r;
                    real *c = pcg32_next(&g) % 2 ? e.o : e.d;
                    c[pcg32_bounded(&g, 3)] = bad[pcg32_bounded(&g, 6)];
                    extreme++;
                    mapped += as_plain_rows(o, inner, &e, tmin, tmax,
                                            &extreme_missed);
                }
                /* then a ray spawned from the hit, outward or inward */
                hit_t h = { 0, 0, { 0, 0, 0 } };
                if (!o->ops->intersect(o, 0, &r, 0, (real)INFINITY, &h))
                    break;
                PATHPOINT pp;
                memset(&pp, 0, sizeof pp);
                cobject_fill(o, &r, &h, &pp);
                VECTOR3 w;
                if (pcg32_next(&g) % 3 == 0) {
                    /* grazing: nearly in the face's plane */
                    vec_add_scaled(w, pp.u, ldexp(REAL_C(1.0),
                                                  -(int)pcg32_bounded(&g, 20)),
                                   pp.ng);
                } else {
                    geomcheck_random_hemisphere(w, pp.ng, &g);
                }
                if (pcg32_next(&g) % 4 == 0)
                    vec_neg(w, w); /* into the box */
                ray_spawn(&r, pp.cross_point, pp.p_error, pp.ng, w);
            }
        }
        cobject_free(o);
        cobject_free(inner);
    }
    ck_assert(n > 200000);
    ck_assert(turned > n / 10);
    ck_assert(mapped > n / 2);
    ck_assert(extreme > n / 8 && extreme_missed > extreme / 2);
    test_report_cases("leaving_a_box_slab_answers_as_the_full_test_bit_for_bit",
                      n + extreme);
}
END_TEST

/* --- the geomcheck harness -------------------------------------------------- */

enum { INNER_BOX, INNER_PARA, INNER_SPHERE };

static COBJECT *make_placed(real s, const VECTOR3 c, void *ctx)
{
    int kind = *(const int *)ctx;
    svet_error err;
    VECTOR3 lo = { REAL_C(-0.5), REAL_C(-0.5), REAL_C(-0.5) },
            hi = { REAL_C(0.5), REAL_C(0.5), REAL_C(0.5) }, zero = { 0, 0, 0 };
    VECTOR3 c1 = { 1, 0, 0 }, c3 = { REAL_C(0.3), 1, 0 };
    COBJECT *in = kind == INNER_BOX    ? box_new(lo, hi, &err)
                  : kind == INNER_PARA ? parallelogram_new(zero, c1, c3, &err)
                                       : sphere_new(zero, REAL_C(0.5), &err);
    VECTOR3 sc = { s, REAL_C(0.6) * s, REAL_C(1.7) * s }, ax = { 1, 2, 3 };
    xform_t x = xform_compose(xform_compose(xform_scale(sc),
                                            xform_rotate(ax, 37)),
                              xform_translate(c));
    COBJECT *o = xform_new(in, &x, &err);
    ck_assert_msg(o != NULL, "%s", err.msg);
    return o;
}

static long harness(int kind, primcheck_test test, uint64_t seed)
{
    geomcheck_kind k = kind == INNER_PARA ? GEOMCHECK_FLAT : GEOMCHECK_CONVEX;
    return primcheck_over_scales(make_placed, &kind, test, k,
                                 kind == INNER_PARA, seed);
}

/* the test on a transformed box, parallelogram and sphere */
static long harness_all(primcheck_test test, uint64_t seed)
{
    long n = 0;
    for (int kind = 0; kind < 3; kind++)
        n += harness(kind, test, seed + (uint64_t)kind);
    return n;
}

START_TEST(transformed_spawned_rays_never_rehit_at_any_scale)
{
    test_report_cases("transformed_spawned_rays_never_rehit_at_any_scale", harness_all(PRIMCHECK_SPAWN, 100));
}
END_TEST

START_TEST(transformed_sampled_points_are_hit_at_any_scale)
{
    test_report_cases("transformed_sampled_points_are_hit_at_any_scale", harness_all(PRIMCHECK_SAMPLED, 200));
}
END_TEST

START_TEST(transformed_shadow_rays_between_points_miss_at_any_scale)
{
    long n = harness(INNER_BOX, PRIMCHECK_SHADOW, 300) +
             harness(INNER_SPHERE, PRIMCHECK_SHADOW, 301);
    test_report_cases("transformed_shadow_rays_between_points_miss_at_any_scale",
                      n);
}
END_TEST

START_TEST(transformed_hits_are_finite_at_any_scale)
{
    test_report_cases("transformed_hits_are_finite_at_any_scale", harness_all(PRIMCHECK_FINITE, 400));
}
END_TEST

START_TEST(transformed_sampling_matches_area_at_any_scale)
{
    test_report_cases("transformed_sampling_matches_area_at_any_scale", harness_all(PRIMCHECK_AREA, 500));
}
END_TEST

/* --- reference vectors ------------------------------------------------------ */

START_TEST(xform_matches_the_reference_vectors)
{
    testcsv_t c;
    testcsv_open(&c, "xform.csv");
    long n = 0;
    for (; testcsv_next(&c); n++) {
        VECTOR3 a, b, s, k, t, zero = { 0, 0, 0 };
        primcheck_csv_vec(&c, "a", a);
        primcheck_csv_vec(&c, "b", b);
        primcheck_csv_vec(&c, "s", s);
        primcheck_csv_vec(&c, "k", k);
        primcheck_csv_vec(&c, "t", t);
        svet_error err;
        COBJECT *in = strcmp(testcsv_str(&c, "inner"), "box") == 0
                          ? box_new(a, b, &err)
                          : parallelogram_new(zero, a, b, &err);
        real deg = (real)testcsv_num(&c, "deg");
        xform_t x = xform_compose(xform_compose(xform_scale(s),
                                                xform_rotate(k, deg)),
                                  xform_translate(t));
        COBJECT *o = xform_new(in, &x, &err);
        ck_assert_msg(o != NULL, "%s", err.msg);
        ck_assert_rel(o->ops->area(o), testcsv_num(&c, "area"),
                      primcheck_csv_tol(&c), 0);
        PATHPOINT pp;
        primcheck_csv_hit(&c, o, "p", "n", &pp);
        cobject_free(o);
    }
    testcsv_close(&c);
    ck_assert_int_gt(n, 0);
    test_report_cases("xform_matches_the_reference_vectors", n);
}
END_TEST

START_TEST(xform_sweep_never_returns_nan_or_inf)
{
    pcg32_t g;
    pcg32_seed(&g, 53, 54);
    long n = 0;
    for (int i = 0; i < 60; i++) {
        real s = ldexp(REAL_C(1.0), (int)pcg32_bounded(&g, 60) - 30);
        VECTOR3 sc, a, t, lo = { -1, -1, -1 }, hi = { 1, 1, 1 },
                zero = { 0, 0, 0 };
        for (int k = 0; k < 3; k++) {
            sc[k] = s * exp(4 * pcg32_real(&g) - 2);
            t[k] = s * (20 * pcg32_real(&g) - 10);
        }
        geomcheck_random_dir(a, &g);
        xform_t x = xform_compose(xform_compose(xform_scale(sc),
                                                xform_rotate(a, 90 * pcg32_real(&g))),
                                  xform_translate(t));
        svet_error err;
        COBJECT *in = i % 3 == 0   ? box_new(lo, hi, &err)
                      : i % 3 == 1 ? sphere_new(zero, 1, &err)
                                   : parallelogram_new(zero, a, t, &err);
        COBJECT *o = xform_new(in, &x, &err);
        if (!o)
            continue;
        n += primcheck_sweep_finite(o, 2000, (uint64_t)i);
        cobject_free(o);
    }
    test_report_cases("xform_sweep_never_returns_nan_or_inf", n);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("xform");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 180);
    tcase_add_test(tc, compose_and_invert_round_trip);
    tcase_add_test(tc, compose_applies_first_then_second);
    tcase_add_test(tc, quarter_turns_are_exact_and_rotation_matches_rodrigues);
    tcase_add_test(tc, singular_and_invalid_transforms_are_refused);
    tcase_add_test(tc, normals_stay_perpendicular_under_non_uniform_scale);
    tcase_add_test(tc, cornell_box_blocks_have_the_hand_computed_corners);
    tcase_add_test(tc, flat_shapes_and_boxes_keep_exact_areas_under_any_map);
    tcase_add_test(tc, ellipsoid_area_matches_the_spheroid_closed_form);
    tcase_add_test(tc, ellipsoid_samples_carry_their_exact_density);
    tcase_add_test(tc, nested_transforms_merge_into_one);
    tcase_add_test(tc, a_mirrored_box_keeps_outward_normals);
    tcase_add_test(tc, the_culling_sphere_never_turns_away_a_hit);
    tcase_add_test(tc,
                   box_face_table_completes_hits_as_the_general_way_bit_for_bit);
    tcase_add_test(tc, leaving_a_box_slab_answers_as_the_full_test_bit_for_bit);
    tcase_add_test(tc, xform_plain_and_fast_agree_field_by_field);
    tcase_add_test(tc, transformed_spawned_rays_never_rehit_at_any_scale);
    tcase_add_test(tc, transformed_sampled_points_are_hit_at_any_scale);
    tcase_add_test(tc, transformed_shadow_rays_between_points_miss_at_any_scale);
    tcase_add_test(tc, transformed_hits_are_finite_at_any_scale);
    tcase_add_test(tc, transformed_sampling_matches_area_at_any_scale);
    tcase_add_test(tc, xform_matches_the_reference_vectors);
    tcase_add_test(tc, xform_sweep_never_returns_nan_or_inf);
    suite_add_tcase(s, tc);
    return s;
}
