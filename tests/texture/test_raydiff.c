/*
 * test_raydiff.c - raydiff.h, ray differentials after Igehy 1999: the
 * camera's equal central differences of camera_ray; off a flat mirror
 * they are those of the mirrored camera, to rounding; through a flat
 * glass slab the footprint on a plane behind it is the closed form of
 * Snell's law differentiated; and an end-to-end render of a textured
 * plane seen in a mirror equals, pixel for pixel, the direct view from
 * the mirrored camera, which it does only where the mip map level after
 * the bounce is the one the direct view at the same distance uses.
 */
#include "testutil.h"
#include "imgtest.h"

#include <math.h>
#include <string.h>

#include "geometry/cone.h"
#include "geometry/cylinder.h"
#include "geometry/shape.h"
#include "geometry/sphere.h"
#include "geometry/triangle.h"
#include "geometry/xform.h"
#include "io/pngio.h"
#include "render/allparts.h"
#include "render/render.h"
#include "render/scenefile.h"
#include "texture/raydiff.h"

/* Rounding of a few dozen operations on numbers of order 1. */
#define TOL (REAL_C(256.0) * REAL_EPSILON)

static void camera(camera_t *c, const VECTOR3 eye, const VECTOR3 target,
                   int w, int h)
{
    VECTOR3 up = { 0, 1, 0 };
    svet_error e;
    ck_assert_int_eq(camera_init(c, eye, target, up, 50, CAMERA_FOV_X, w, h,
                                 &e), SVET_OK);
}

/* the normal's change on a flat surface */
static const VECTOR3 flat = { 0, 0, 0 };

static void near3(const VECTOR3 a, const VECTOR3 b, real tol)
{
    for (int k = 0; k < 3; k++)
        ck_assert_msg(fabs(a[k] - b[k]) <= tol, "[%d] %.9g vs %.9g", k,
                      (double)a[k], (double)b[k]);
}

START_TEST(the_camera_differentials_are_camera_rays_differences)
{
    camera_t c;
    VECTOR3 eye = { 0.3, 2, 1.1 }, target = { 0.1, 0, -1 };
    camera(&c, eye, target, 64, 48);
    const real x = REAL_C(17.25), y = REAL_C(29.5);
    /* double the step of a central difference's optimum in float */
    const real h = sizeof(real) == sizeof(float) ? REAL_C(0.05)
                                                 : REAL_C(1e-4);
    ray_t r, xp, xm, yp, ym;
    camera_ray(&c, x, y, &r);
    camera_ray(&c, x + h, y, &xp);
    camera_ray(&c, x - h, y, &xm);
    camera_ray(&c, x, y + h, &yp);
    camera_ray(&c, x, y - h, &ym);
    raydiff_t rd;
    raydiff_camera(&rd, &c, r.d);
    VECTOR3 fx, fy, zero = { 0, 0, 0 };
    for (int k = 0; k < 3; k++) {
        fx[k] = (xp.d[k] - xm.d[k]) / (2 * h);
        fy[k] = (yp.d[k] - ym.d[k]) / (2 * h);
    }
    /* the difference's error: h^2 / 6 times a third derivative of order
     * (2 tan / W)^3, and rounding of 1e-7 / h in float */
    const real tol = sizeof(real) == sizeof(float) ? REAL_C(2e-5)
                                                   : REAL_C(1e-9);
    near3(rd.dddx, fx, tol);
    near3(rd.dddy, fy, tol);
    near3(rd.dpdx, zero, 0);
    near3(rd.dpdy, zero, 0);
}
END_TEST

/* p mirrored in the plane y = 0. */
static void flip(VECTOR3 out, const VECTOR3 p)
{
    vec_set(out, p[X], -p[Y], p[Z]);
}

START_TEST(a_flat_mirror_gives_the_mirrored_cameras_differentials)
{
    camera_t c, m;
    VECTOR3 eye = { 0.3, 2, 1.1 }, target = { 0.1, 0, -1 };
    camera(&c, eye, target, 64, 48);
    /* the mirrored camera: eye and frame flipped (a left-handed frame,
     * which the differentials do not mind) */
    m = c;
    flip(m.eye, c.eye);
    flip(m.u, c.u);
    flip(m.v, c.v);
    flip(m.w, c.w);
    const VECTOR3 n = { 0, 1, 0 }, wall = { 0, 0, 1 };
    const real px[3][2] = { { 17.25, 29.5 }, { 0.5, 47.5 }, { 63, 40 } };
    for (int i = 0; i < 3; i++) {
        ray_t r;
        camera_ray(&c, px[i][0], px[i][1], &r);
        ck_assert(r.d[Y] < 0); /* every one meets the mirror */
        raydiff_t a, b;
        raydiff_camera(&a, &c, r.d);
        VECTOR3 d2;
        flip(d2, r.d);
        raydiff_camera(&b, &m, d2);
        /* to the mirror, and the reflection: the mirrored camera's ray
         * meets the mirror at the same point, at the same distance */
        real t = -eye[Y] / r.d[Y];
        ck_assert(raydiff_transfer(&a, r.d, t, n));
        raydiff_reflect(&a, r.d, n, flat, flat);
        ck_assert(raydiff_transfer(&b, d2, t, n));
        near3(a.dpdx, b.dpdx, TOL);
        near3(a.dpdy, b.dpdy, TOL);
        near3(a.dddx, b.dddx, TOL);
        near3(a.dddy, b.dddy, TOL);
        /* and on to a wall z = -3, which both rays meet together */
        VECTOR3 hit;
        for (int k = 0; k < 3; k++)
            hit[k] = eye[k] + t * r.d[k];
        real t2 = (-3 - hit[Z]) / d2[Z];
        ck_assert(raydiff_transfer(&a, d2, t2, wall));
        ck_assert(raydiff_transfer(&b, d2, t2, wall));
        near3(a.dpdx, b.dpdx, 8 * TOL);
        near3(a.dpdy, b.dpdy, 8 * TOL);
    }
}
END_TEST

/* The refracted unit direction of unit d through unit normal n (facing
 * d's side or not), index ratio eta = n_from / n_to: Snell's law in
 * vector form (Glassner 1989), independent of raydiff.c. */
static void snell(VECTOR3 t, const VECTOR3 d, const VECTOR3 n, real eta)
{
    real c = SVECTOR3(d, n);
    real k = 1 - eta * eta * (1 - c * c);
    real s = c < 0 ? -1 : 1;
    for (int i = 0; i < 3; i++)
        t[i] = eta * d[i] + (s * sqrt(k) - eta * c) * n[i];
}

START_TEST(a_glass_slab_gives_the_closed_form_footprint)
{
    /* camera at the origin looking down -z; a slab of index nn between
     * z = -a and z = -a - h; a screen at z = -L. For a ray at angle th
     * from the axis in the x-z plane, refracted to th' (sin th = nn sin
     * th'), the screen is met at X = (L - h) tan th + h tan th', so
     * dX/dth = (L - h) / cos^2 th + h cos th / (nn cos^3 th'), and one
     * pixel is dth = (2 tan_x / W) cos^2 th. Across it, in y at the
     * centre row, Y = (L - h) D_y / |D_z| + h T_y / |T_z| with T_y =
     * D_y / nn, and one pixel is dD_y = -(2 tan_y / H) / |D'| for the
     * unnormalised D' = (sx tan_x, 0, -1). */
    const double a = 2, h = 0.5, L = 5, nn = 1.5;
    camera_t c;
    VECTOR3 eye = { 0, 0, 0 }, target = { 0, 0, -1 };
    camera(&c, eye, target, 100, 80);
    const real xs[3] = { 80.5, 50.25, 3 };
    for (int i = 0; i < 3; i++) {
        ray_t r;
        camera_ray(&c, xs[i], 40, &r); /* the centre row: sy = 0 */
        ck_assert(r.d[Y] == 0);
        raydiff_t rd;
        raydiff_camera(&rd, &c, r.d);
        const VECTOR3 n = { 0, 0, 1 };
        VECTOR3 t1, t2;
        snell(t1, r.d, n, (real)(1 / nn));
        snell(t2, t1, n, (real)nn);
        ck_assert(raydiff_transfer(&rd, r.d, (real)(a / -(double)r.d[Z]), n));
        ck_assert(raydiff_refract(&rd, r.d, n, flat, flat, (real)(1 / nn), t1));
        ck_assert(raydiff_transfer(&rd, t1, (real)(h / -(double)t1[Z]), n));
        ck_assert(raydiff_refract(&rd, t1, n, flat, flat, (real)nn, t2));
        ck_assert(raydiff_transfer(&rd, t2, (real)((L - a - h) / -(double)t2[Z]),
                                   n));
        double dx = (double)r.d[X], dz = -(double)r.d[Z];
        double th = atan2(dx, dz), thp = asin(sin(th) / nn);
        double X_ = ((L - h) / (cos(th) * cos(th)) +
                     h * cos(th) / (nn * pow(cos(thp), 3))) *
                    (2 * (double)c.tan_x / 100) * cos(th) * cos(th);
        double sx = 2 * (double)xs[i] / 100 - 1;
        double tx = (double)c.tan_x;
        double len = sqrt(1 + sx * sx * tx * tx);
        double tz = sqrt(1 - dx * dx / (nn * nn));
        double Y_ = ((L - h) / dz + h / (nn * tz)) *
                    (-2 * (double)c.tan_y / 80) / len;
        const double rel = sizeof(real) == sizeof(float) ? 1e-5 : 1e-12;
        ck_assert_msg(fabs((double)rd.dpdx[X] - X_) <= rel * fabs(X_),
                      "dX/dx %.9g, closed form %.9g", (double)rd.dpdx[X], X_);
        ck_assert_msg(fabs((double)rd.dpdy[Y] - Y_) <= rel * fabs(Y_),
                      "dY/dy %.9g, closed form %.9g", (double)rd.dpdy[Y], Y_);
        /* the footprint over a screen of (s, t) = (x, y) units */
        const VECTOR3 ds = { 1, 0, 0 }, dt = { 0, 1, 0 };
        double w = (double)raydiff_footprint(&rd, ds, dt);
        double want = fmax(fabs(X_), fabs(Y_));
        ck_assert_msg(fabs(w - want) <= 2 * rel * want + 1e-7 * want,
                      "footprint %.9g, closed form %.9g", w, want);
        /* and without the slab it is (L / cos^2 th) dth: the slab makes
         * it smaller, as a lens of flat glass brings the screen nearer */
        ck_assert(fabs(X_) < L * (2 * (double)c.tan_x / 100));
    }
}
END_TEST

/* --- curved mirrors and glass: the real neighbouring rays --------------- */

/* The ray of pixel (x, y) of camera c through `bounces` delta events on
 * obj: a mirror's reflection d - 2 (d . n) n where eta is 0, else
 * Snell's refraction (snell(), index ratio 1 / eta entering, eta
 * leaving). The point of the last hit and the direction leaving it go to
 * p and out. With rd, the differentials are carried along too, with the
 * normal's change of the primitive when curved, 0 when not. */
static void trace(const camera_t *c, const COBJECT *obj, real x, real y,
                  real eta, int bounces, bool curved, VECTOR3 p, VECTOR3 out,
                  raydiff_t *rd)
{
    ray_t r;
    camera_ray(c, x, y, &r);
    vec_normalize(r.d, r.d);
    if (rd)
        raydiff_camera(rd, c, r.d);
    real tmin = 0;
    for (int b = 0; b < bounces; b++) {
        hit_t h;
        PATHPOINT pp;
        ck_assert(cobject_intersect(obj, &r, tmin, (real)INFINITY, &h));
        cobject_fill(obj, &r, &h, &pp);
        real dn = SVECTOR3(r.d, pp.n), ratio = dn < 0 ? 1 / eta : eta;
        VECTOR3 o;
        if (eta == 0)
            for (int i = 0; i < 3; i++)
                o[i] = r.d[i] - 2 * dn * pp.n[i];
        else
            snell(o, r.d, pp.n, ratio);
        if (rd) {
            VECTOR3 nx = { 0, 0, 0 }, ny = { 0, 0, 0 };
            ck_assert(raydiff_transfer(rd, r.d, pp.r_dist, pp.ng));
            if (curved) {
                cobject_normal_change(obj, &pp, rd->dpdx, nx);
                cobject_normal_change(obj, &pp, rd->dpdy, ny);
            }
            if (eta == 0)
                raydiff_reflect(rd, r.d, pp.n, nx, ny);
            else
                ck_assert(raydiff_refract(rd, r.d, pp.n, nx, ny, ratio, o));
        }
        vec_copy(r.o, pp.cross_point);
        vec_copy(r.d, o);
        vec_copy(p, pp.cross_point);
        tmin = REAL_C(1e-2); /* past the surface just left */
    }
    vec_copy(out, r.d);
}

/* The largest component of |a - b|. */
static real maxdiff(const VECTOR3 a, const VECTOR3 b)
{
    return shape_max_abs((VECTOR3){ a[X] - b[X], a[Y] - b[Y], a[Z] - b[Z] });
}

/* Central differences of trace()'s p and out along x (dx = 1) or y, over
 * step h. */
static void central(const camera_t *c, const COBJECT *obj, real x, real y,
                    real eta, int bounces, int dx, real h, VECTOR3 fp,
                    VECTOR3 fd)
{
    VECTOR3 pa, da, pb, db;
    real ex = dx ? h : 0, ey = dx ? 0 : h;
    trace(c, obj, x + ex, y + ey, eta, bounces, false, pa, da, NULL);
    trace(c, obj, x - ex, y - ey, eta, bounces, false, pb, db, NULL);
    for (int k = 0; k < 3; k++) {
        fp[k] = (pa[k] - pb[k]) / (2 * h);
        fd[k] = (da[k] - db[k]) / (2 * h);
    }
}

START_TEST(curved_mirrors_and_glass_follow_the_neighbouring_rays)
{
    svet_error e;
    camera_t c;
    VECTOR3 eye = { 0.2, 0.3, 5 }, target = { 0, 0, 0 };
    camera(&c, eye, target, 64, 48);
    VECTOR3 o = { 0, 0, 0 };
    COBJECT *obj[5];
    obj[0] = sphere_new(o, 1, &e);
    obj[1] = cylinder_new((VECTOR3){ 0, -2, 0 }, (VECTOR3){ 0, 2, 0 }, 1,
                          false, &e);
    obj[2] = cone_new((VECTOR3){ 0, -1.5, 0 }, (VECTOR3){ 0, 1.5, 0 }, 1.2,
                      false, &e);
    /* an ellipsoid turned about an oblique axis */
    xform_t x = xform_compose(xform_scale((VECTOR3){ 1.4, 0.9, 0.8 }),
                              xform_rotate((VECTOR3){ 1, 2, 0.5 }, 35));
    obj[3] = xform_new(sphere_new(o, 1, &e), &x, &e);
    /* a flat triangle with splayed vertex normals */
    obj[4] = triangle_new((VECTOR3){ -2, -2, 0 }, (VECTOR3){ 2, -2, 0 },
                          (VECTOR3){ 0, 2, 0 }, &e);
    for (int i = 0; i < 5; i++)
        ck_assert_msg(obj[i] != NULL, "%s", e.msg);
    ck_assert_int_eq(triangle_set_normals(obj[4], (VECTOR3){ -0.4, -0.3, 1 },
                                          (VECTOR3){ 0.5, -0.2, 1 },
                                          (VECTOR3){ 0, 0.6, 1 }, &e),
                     SVET_OK);
    /* a step of a good fraction of a pixel in float (rounding of 1e-7 in
     * a coordinate of order 5 over 2 h), far less in double */
    const bool f = sizeof(real) == sizeof(float);
    const real h = f ? REAL_C(0.25) : REAL_C(1e-3);
    const real px[2][2] = { { 36.3, 20.7 }, { 27.6, 27.2 } };
    /* mirror, glass entered, glass through (the closed ones) */
    const struct { real eta; int bounces; } ev[3] = { { 0, 1 }, { 1.5, 1 },
                                                      { 1.5, 2 } };
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 3; j++) {
            if (ev[j].bounces == 2 && i != 0 && i != 3)
                continue;
            for (int k = 0; k < 2; k++) {
                real miss = 0;
                for (int a = 0; a < 2; a++) {
                    VECTOR3 p, d, fp, fd, fp2, fd2;
                    raydiff_t rd, flat_rd;
                    trace(&c, obj[i], px[k][0], px[k][1], ev[j].eta,
                          ev[j].bounces, true, p, d, &rd);
                    trace(&c, obj[i], px[k][0], px[k][1], ev[j].eta,
                          ev[j].bounces, false, p, d, &flat_rd);
                    central(&c, obj[i], px[k][0], px[k][1], ev[j].eta,
                            ev[j].bounces, a == 0, h, fp, fd);
                    central(&c, obj[i], px[k][0], px[k][1], ev[j].eta,
                            ev[j].bounces, a == 0, 2 * h, fp2, fd2);
                    /* the difference's error is c h^2 and 4 c h^2 at 2 h,
                     * so at most a third of their gap (Richardson); twice
                     * that, and the rounding of about 64 ulp of
                     * coordinates of order 5 over 2 h */
                    real round = 64 * REAL_EPSILON * 5 / (2 * h);
                    real tp = 2 * maxdiff(fp, fp2) + round;
                    real td = 2 * maxdiff(fd, fd2) + round;
                    const real *gp = a == 0 ? rd.dpdx : rd.dpdy;
                    const real *gd = a == 0 ? rd.dddx : rd.dddy;
                    const real *nd = a == 0 ? flat_rd.dddx : flat_rd.dddy;
                    ck_assert_msg(maxdiff(gp, fp) <= tp,
                                  "%s ev %d px %d axis %d: dP off by %g, "
                                  "tolerance %g", obj[i]->ops->name, j, k, a,
                                  (double)maxdiff(gp, fp), (double)tp);
                    ck_assert_msg(maxdiff(gd, fd) <= td,
                                  "%s ev %d px %d axis %d: dD off by %g, "
                                  "tolerance %g", obj[i]->ops->name, j, k, a,
                                  (double)maxdiff(gd, fd), (double)td);
                    miss = fmax(miss, maxdiff(nd, fd) / td);
                }
                /* and the flat surface's dN = 0 misses by far along one
                 * axis at least (a cylinder is straight along the other) */
                ck_assert_msg(miss > 20, "%s ev %d px %d: dN = 0 off by "
                              "only %g tolerances", obj[i]->ops->name, j, k,
                              (double)miss);
            }
        }
    for (int i = 0; i < 5; i++)
        cobject_free(obj[i]);
}
END_TEST

/* --- a textured plane seen in a mirror ------------------------------------ */

static void render_text(const char *text, image_t *img)
{
    scene_t s;
    svet_error e;
    ck_assert_msg(scenefile_parse_with(&s, text, strlen(text), "t.scn", NULL,
                                       scene_features_all(), &e) == SVET_OK,
                  "%s", e.msg);
    render_t r;
    ck_assert_int_eq(render_init(&r, &s, &e), SVET_OK);
    ck_assert_int_eq(render_pass(&r, s.render.spp, 1, NULL, NULL), SVET_OK);
    ck_assert_int_eq(render_image(&r, img, &e), SVET_OK);
    render_free(&r);
    scene_free(&s);
}

/* The ceiling y = 3 of stripes one texel wide along x (s), 16 texels a
 * unit, lit from below by a point light at (0, 1, 0); seen from (0, eye,
 * 0) looking along y, with or without a mirror floor at y = 0. Both
 * cameras have image right = +x (up -z looking down, +z looking up), so
 * the mirror flips their images in z only, under which the scene is
 * symmetric: the same pixel of each meets the ceiling at the same
 * point. */
static const char *ceiling(const char *png, const char *filter, int eye,
                           bool mirror)
{
    static char text[2048];
    snprintf(text, sizeof text,
             "camera position 0 %d 0 target 0 0 0 up 0 0 %d fov 40 width 48 "
             "height 48\n"
             "render spp 1 maxdepth %d seed 9\n"
             "light point position 0 1 0 intensity 4\n"
             "texture c image file \"%s\" data filter %s\n"
             "material m lambert rho c\n"
             "material silver mirror rho 1\n"
             "parallelogram c0 -8 3 -8 c1 8 3 -8 c3 -8 3 8 material m\n"
             "%s",
             eye, eye > 0 ? -1 : 1, mirror ? 2 : 1, png, filter,
             mirror ? "plane point 0 0 0 normal 0 1 0 material "
                      "silver\n" : "");
    return text;
}

START_TEST(a_plane_in_a_mirror_reads_the_level_of_the_direct_view)
{
    image_t img;
    ck_assert_int_eq(image_alloc(&img, 256, 256, 3, NULL), SVET_OK);
    for (int y = 0; y < 256; y++)
        for (int x = 0; x < 256; x++) {
            float *p = image_at(&img, x, y);
            p[0] = p[1] = p[2] = x % 2 ? 0.9f : 0.1f;
        }
    const char *png = imgtest_path("stripes.png");
    svet_error e;
    ck_assert_int_eq(pngio_write(png, &img, 16, &e), SVET_OK);
    image_free(&img);
    /* the mirror 2 below the eye, the ceiling 3 above the mirror: the
     * mirrored camera 2 below the mirror sees it at the same distance 5,
     * where a pixel spans about 1.2 texels at the centre (2 tan 20 / 48
     * * 5 * 16): between levels 0 and 1, so that the level shows in
     * every pixel's blend */
    image_t direct, seen, fine;
    render_text(ceiling(png, "trilinear", -2, false), &direct);
    render_text(ceiling(png, "trilinear", 2, true), &seen);
    render_text(ceiling(png, "bilinear", 2, true), &fine);
    double worst = 0, lo = 1e9, hi = 0, off = 0;
    for (int y = 0; y < 48; y++)
        for (int x = 0; x < 48; x++) {
            double a = image_at(&direct, x, y)[0];
            double b = image_at(&seen, x, y)[0];
            double f = image_at(&fine, x, y)[0];
            worst = fmax(worst, fabs(a - b) / a);
            off = fmax(off, fabs(f - a) / a);
            lo = fmin(lo, a);
            hi = fmax(hi, a);
        }
    /* the same image to a ten-thousandth: the hit points differ by
     * rounding only, and the mirror's rho_s is 1 at every angle */
    ck_assert_msg(worst < 1e-4, "mirrored view differs by %g", worst);
    /* which the finest level (the footprint lost at the bounce) misses by
     * far: the stripes alias */
    ck_assert_msg(off > 0.2, "finest level differs by only %g", off);
    ck_assert(hi > lo);
    image_free(&direct);
    image_free(&seen);
    image_free(&fine);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("raydiff");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, the_camera_differentials_are_camera_rays_differences);
    tcase_add_test(tc, a_flat_mirror_gives_the_mirrored_cameras_differentials);
    tcase_add_test(tc, a_glass_slab_gives_the_closed_form_footprint);
    tcase_add_test(tc, curved_mirrors_and_glass_follow_the_neighbouring_rays);
    tcase_add_test(tc, a_plane_in_a_mirror_reads_the_level_of_the_direct_view);
    suite_add_tcase(s, tc);
    return s;
}
