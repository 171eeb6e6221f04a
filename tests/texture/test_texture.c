/*
 * test_texture.c - texture.h: Blinn's bump on a plane with the height
 * h = a s tilts the normal by exactly atan(a), and a zero gradient leaves
 * the hit untouched bit for bit; image heights' central differences are
 * exact for a linear image; a solid's height derivatives are its
 * gradient along dP/ds and dP/dt (central differences agree); the 2D
 * checker alternates; every primitive's (s, t) moves by (h, 0) and (0, h)
 * when the point moves by h dP/ds and h dP/dt (texture coordinates and
 * tangents agree, the box and the disk included).
 */
#include "testutil.h"

#include <math.h>
#include <string.h>

#include "geometry/box.h"
#include "geometry/cone.h"
#include "geometry/cylinder.h"
#include "geometry/disk.h"
#include "geometry/parallelogram.h"
#include "geometry/plane.h"
#include "geometry/sphere.h"
#include "geometry/triangle.h"
#include "geometry/xform.h"
#include "texture/texture.h"

/* The hit of a ray straight down onto the plane z = 0 (normal +z) at
 * (x, y): its PATHPOINT, filled by the plane's own surface(). */
static void plane_hit(COBJECT **obj, PATHPOINT *pp, real x, real y)
{
    VECTOR3 p0 = { 0, 0, 0 }, n = { 0, 0, 1 };
    svet_error e;
    *obj = plane_new(p0, n, &e);
    ck_assert_ptr_nonnull(*obj);
    ray_t r;
    VECTOR3 o = { x, y, 2 }, d = { REAL_C(0.3), REAL_C(-0.2), -1 };
    vec_copy(r.o, o);
    vec_copy(r.d, d);
    hit_t h;
    ck_assert((*obj)->ops->intersect(*obj, 0, &r, 0, (real)INFINITY, &h));
    cobject_fill(*obj, &r, &h, pp);
}

START_TEST(a_bump_of_height_a_s_on_a_plane_tilts_the_normal_by_atan_a)
{
    static const double slopes[] = { 0.01, 0.1, 0.5, 1, 3, -2 };
    for (size_t i = 0; i < sizeof slopes / sizeof slopes[0]; i++) {
        COBJECT *obj;
        PATHPOINT pp;
        plane_hit(&obj, &pp, REAL_C(0.25), REAL_C(-0.5));
        /* the plane's dP/ds is a unit tangent: h = a s is a slope a
         * along it, whatever its direction */
        VECTOR3 n0;
        vec_copy(n0, pp.n);
        const real a = (real)slopes[i];
        ck_assert(texture_bump(&pp, a, 0));
        double c = (double)SVECTOR3(pp.n, n0);
        double angle = acos(fmin(c, 1.0));
        /* the tilt is atan(|a|) to the rounding of a few products and a
         * normalisation: 8 ulps of real in the cosine, i.e. a few 1e-7
         * radians in float at the smallest slope */
        double tol = 8 * (double)REAL_EPSILON / fmax(sin(atan(fabs(slopes[i]))),
                                                    1e-3);
        ck_assert_near(angle, atan(fabs(slopes[i])), tol);
        /* it tilts against the slope: toward -dP/ds for a > 0 */
        double along = (double)SVECTOR3(pp.n, pp.dpds);
        ck_assert(slopes[i] > 0 ? along < 0 : along > 0);
        /* the frame stays right-handed and unit */
        VECTOR3 uxv;
        VVECTOR3(uxv, pp.u, pp.v);
        for (int k = 0; k < 3; k++)
            ck_assert_near(uxv[k], pp.n[k], 1e-5);
        ck_assert_near(vec_length(pp.n), 1, 1e-6);
        cobject_free(obj);
    }
}
END_TEST

/* texture_bump(dhds, dhdt) at a plane's hit moves nothing, bit for bit. */
static void bump_leaves_the_hit(real dhds, real dhdt)
{
    COBJECT *obj;
    PATHPOINT pp, before;
    plane_hit(&obj, &pp, 1, 2);
    memcpy(&before, &pp, sizeof pp);
    ck_assert(!texture_bump(&pp, dhds, dhdt));
    ck_assert(memcmp(&before, &pp, sizeof pp) == 0);
    cobject_free(obj);
}

START_TEST(a_zero_bump_leaves_the_hit_bit_for_bit)
{
    bump_leaves_the_hit(0, 0);
}
END_TEST

START_TEST(a_bump_that_hides_the_viewer_keeps_the_geometric_frame)
{
    /* out = (-0.3, 0.2, 1)/|.|: a slope of -1e3 along +x turns the normal
     * to almost +x, where out is behind it */
    bump_leaves_the_hit(-1000, 0);
}
END_TEST

START_TEST(an_image_height_has_the_exact_slope_of_a_linear_image)
{
    enum { W = 16, H = 8 };
    float px[W * H * 3];
    /* h = 2 x + 0.5 y over texel centres: h(s, t) = 2 (W s - 0.5) + ... */
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int k = 0; k < 3; k++)
                px[(y * W + x) * 3 + k] = (float)(x * 2 + y) / 64;
    texture_t t;
    memset(&t, 0, sizeof t);
    t.kind = TEXTURE_IMAGE;
    t.scale = 1;
    t.filter = MIPMAP_BILINEAR;
    svet_error e;
    ck_assert_int_eq(mipmap_build(&t.mip, px, W, H, 3, MIPMAP_CLAMP, &e),
                     SVET_OK);
    texture_point_t q;
    memset(&q, 0, sizeof q);
    q.s = REAL_C(0.4);
    q.t = REAL_C(0.55);
    real hs, ht;
    real h = texture_height(&t, &q, &hs, &ht);
    /* dh/ds = 2/64 per texel = 2 W / 64 per unit s; dh/dt = H / 64 */
    ck_assert_near(hs, 2.0 * W / 64, 1e-4);
    ck_assert_near(ht, 1.0 * H / 64, 1e-4);
    ck_assert_near(h, (2 * (W * 0.4 - 0.5) + (H * 0.55 - 0.5)) / 64, 1e-6);
    /* a lookup at a texel centre returns the texel */
    q.s = (REAL_C(3.5)) / W;
    q.t = (REAL_C(2.5)) / H;
    RADIANCE c = texture_eval(&t, &q);
    ck_assert_near(c.g, (3 * 2 + 2) / 64.0, 0);
    texture_free(&t);
}
END_TEST

START_TEST(a_solid_height_follows_its_gradient_along_the_tangents)
{
    texture_t t;
    memset(&t, 0, sizeof t);
    t.kind = TEXTURE_SOLID;
    t.scale = 1;
    t.solid = solid_default(SOLID_NOISE, rad_grey(0), rad_grey(1));
    t.solid.scale = 3;
    texture_point_t q;
    memset(&q, 0, sizeof q);
    vec_set(q.p, REAL_C(0.31), REAL_C(0.77), REAL_C(-0.42));
    vec_set(q.dpds, REAL_C(0.6), REAL_C(0.0), REAL_C(0.8));
    vec_set(q.dpdt, REAL_C(0.0), REAL_C(1.0), REAL_C(0.0));
    real hs, ht;
    texture_height(&t, &q, &hs, &ht);
    /* central differences along dP/ds, dP/dt: O(d^2) error, d = 1e-3,
     * against float rounding of the values (1e-7 / 1e-3) */
    const double d = 1e-3;
    double f[2][2];
    for (int a = 0; a < 2; a++)
        for (int sgn = 0; sgn < 2; sgn++) {
            texture_point_t r = q;
            const real *dir = a == 0 ? q.dpds : q.dpdt;
            for (int k = 0; k < 3; k++)
                r.p[k] = q.p[k] + (real)((sgn ? d : -d) * (double)dir[k]);
            f[a][sgn] = (double)texture_height(&t, &r, NULL, NULL);
        }
    ck_assert_near(hs, (f[0][1] - f[0][0]) / (2 * d), 2e-3);
    ck_assert_near(ht, (f[1][1] - f[1][0]) / (2 * d), 2e-3);
    ck_assert(fabs((double)hs) + fabs((double)ht) > 0.01);
}
END_TEST

START_TEST(the_checker_alternates_over_s_and_t)
{
    texture_t t;
    memset(&t, 0, sizeof t);
    t.kind = TEXTURE_CHECKER;
    t.scale = 4;
    t.a = rad_grey(REAL_C(0.25));
    t.b = rad_grey(REAL_C(0.75));
    texture_point_t q;
    memset(&q, 0, sizeof q);
    for (int i = 0; i < 8; i++)
        for (int j = 0; j < 8; j++) {
            q.s = ((real)i + REAL_C(0.5)) / 8;
            q.t = ((real)j + REAL_C(0.5)) / 8;
            int parity = (i / 2 + j / 2) % 2;
            ck_assert_near(texture_eval(&t, &q).r, parity ? 0.75 : 0.25, 0);
            real hs = 1, ht = 1;
            texture_height(&t, &q, &hs, &ht);
            ck_assert(hs == 0 && ht == 0);
        }
}
END_TEST

/* The hit of the ray from o toward a on obj (which it must meet). */
static void hit_toward(const COBJECT *obj, const VECTOR3 o, const VECTOR3 a,
                       PATHPOINT *pp)
{
    ray_t r;
    vec_copy(r.o, o);
    vec_sub(r.d, a, o);
    hit_t h;
    ck_assert(cobject_intersect(obj, &r, 0, (real)INFINITY, &h));
    cobject_fill(obj, &r, &h, pp);
}

START_TEST(every_primitives_tangents_match_its_texture_coordinates)
{
    svet_error e;
    const double ang = 0.7, c7 = cos(ang), s7 = sin(ang);
    struct {
        const char *name;
        COBJECT *obj;
        VECTOR3 a, off; /* a point on the surface, and the eye's offset */
    } cases[9];
    int n = 0;
#define CASE(nm, o, ax, ay, az, ox, oy, oz)                                  \
    do {                                                                     \
        cases[n].name = nm;                                                  \
        cases[n].obj = o;                                                    \
        ck_assert_msg(cases[n].obj != NULL, "%s: %s", nm, e.msg);            \
        vec_set(cases[n].a, (real)(ax), (real)(ay), (real)(az));             \
        vec_set(cases[n].off, (real)(ox), (real)(oy), (real)(oz));           \
        n++;                                                                 \
    } while (0)
    VECTOR3 zero = { 0, 0, 0 }, ez = { 0, 0, 1 }, top = { 0, 0, 2 };
    VECTOR3 c1 = { 2, 0, 0 }, c3 = { 0, 1, REAL_C(0.5) };
    VECTOR3 p1 = { 1, 0, 0 }, p2 = { 0, 1, REAL_C(0.3) };
    VECTOR3 bmax = { 1, 2, 3 };
    /* each point off the poles and seams of its parametrisation */
    CASE("sphere", sphere_new(zero, 1, &e), 0.48, 0.6, 0.64, 1.0, 1.2, 1.5);
    CASE("disk", disk_new(zero, ez, 1, &e), 0.4 * c7, 0.4 * s7, 0,
         0.1, 0.2, 2);
    CASE("parallelogram", parallelogram_new(zero, c1, c3, &e), 0.7, 0.4, 0.2,
         0.1, 0.2, 2);
    CASE("triangle", triangle_new(zero, p1, p2, &e), 0.3, 0.25, 0.075,
         0.1, 0.1, 2);
    CASE("box", box_new(zero, bmax, &e), 0.3, 0.7, 3, 0.2, 0.1, 2);
    CASE("cylinder", cylinder_new(zero, top, 1, true, &e), c7, s7, 0.8,
         2 * c7, 2 * s7, 0.2);
    CASE("cone", cone_new(zero, top, 1, true, &e), 0.7 * c7, 0.7 * s7, 0.6,
         2 * c7, 2 * s7, 0.6);
    CASE("plane", plane_new(zero, ez, &e), 0.3, 0.4, 0, 0.1, 0.1, 2);
    {
        /* a sphere moved and stretched: the transform carries dP/ds */
        xform_t x = xform_compose(xform_scale((VECTOR3){ 2, 1, 1 }),
                                  xform_translate((VECTOR3){ 0, 0, 1 }));
        CASE("ellipsoid", xform_new(sphere_new(zero, 1, &e), &x, &e),
             2 * 0.48, 0.6, 1.64, 1.0, 1.2, 1.5);
    }
#undef CASE
    const double h = 1e-3;
    for (int i = 0; i < n; i++) {
        VECTOR3 o;
        vec_add(o, cases[i].a, cases[i].off);
        PATHPOINT pp;
        hit_toward(cases[i].obj, o, cases[i].a, &pp);
        for (int axis = 0; axis < 2; axis++) {
            const real *d = axis == 0 ? pp.dpds : pp.dpdt;
            ck_assert_msg(vec_length(d) > 0, "%s: dP/d%c is zero",
                          cases[i].name, axis ? 't' : 's');
            VECTOR3 q;
            for (int k = 0; k < 3; k++)
                q[k] = pp.cross_point[k] + (real)(h * (double)d[k]);
            PATHPOINT pq;
            hit_toward(cases[i].obj, o, q, &pq);
            double ds = (double)pq.st[0] - (double)pp.st[0];
            double dt = (double)pq.st[1] - (double)pp.st[1];
            double want_s = axis == 0 ? h : 0, want_t = axis == 0 ? 0 : h;
            /* the surface bends away from its tangent by O(h^2): a few
             * percent of h, far above float's rounding of st (1e-7) */
            ck_assert_msg(fabs(ds - want_s) < 0.03 * h &&
                              fabs(dt - want_t) < 0.03 * h,
                          "%s, along dP/d%c: (s, t) moved by (%g, %g), not "
                          "(%g, %g)", cases[i].name, axis ? 't' : 's', ds, dt,
                          want_s, want_t);
        }
        cobject_free(cases[i].obj);
    }
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("texture");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, a_bump_of_height_a_s_on_a_plane_tilts_the_normal_by_atan_a);
    tcase_add_test(tc, a_zero_bump_leaves_the_hit_bit_for_bit);
    tcase_add_test(tc, a_bump_that_hides_the_viewer_keeps_the_geometric_frame);
    tcase_add_test(tc, an_image_height_has_the_exact_slope_of_a_linear_image);
    tcase_add_test(tc, a_solid_height_follows_its_gradient_along_the_tangents);
    tcase_add_test(tc, the_checker_alternates_over_s_and_t);
    tcase_add_test(tc, every_primitives_tangents_match_its_texture_coordinates);
    suite_add_tcase(s, tc);
    return s;
}
