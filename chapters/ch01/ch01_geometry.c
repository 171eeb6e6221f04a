/* cc -std=c11 -O2 -Iinclude chapters/ch01/ch01_geometry.c src/core/vec.c src/core/frame.c src/core/ray.c src/core/bbox.c src/materials/cobject.c src/core/error.c src/geometry/shape.c src/geometry/quadric.c src/geometry/sphere.c src/geometry/plane.c src/geometry/disk.c src/geometry/parallelogram.c src/geometry/triangle.c src/geometry/box.c src/geometry/cylinder.c src/geometry/cone.c src/geometry/xform.c src/render/camera.c -lm -o ch01_geometry */
/*
 * ch01_geometry.c - the geometric part of chapter 1 and appendices A-D:
 * VECTOR3 with VVECTOR3 and SVECTOR3 (app. B), a ray meeting a sphere and
 * the PATHPOINT it fills (the book's structure, field by field), the mirror
 * direction (1.4), refraction (1.11)-(1.12) on both sides of the critical
 * angle, the local frame (app. A), rotation about an axis (app. C), and a
 * picture of every primitive of app. D shaded by its normal.
 *
 * usage: ch01_geometry [OUTDIR]   (default out/ch01; writes primitives.ppm;
 * --help)
 */
#include <stdio.h>
#include <stdlib.h>

#include "../chapter.h"

#include "geometry/box.h"
#include "render/camera.h"
#include "geometry/cone.h"
#include "geometry/cylinder.h"
#include "geometry/disk.h"
#include "core/frame.h"
#include "geometry/parallelogram.h"
#include "geometry/plane.h"
#include "geometry/sphere.h"
#include "geometry/triangle.h"
#include "geometry/xform.h"

static void print_vec(const char *name, const VECTOR3 a)
{
    printf("  %-12s (%9.5f, %9.5f, %9.5f)\n", name, (double)a[X], (double)a[Y],
           (double)a[Z]);
}

static void vectors(void)
{
    printf("== App. B: VECTOR3, VVECTOR3 (cross) and SVECTOR3 (dot)\n");
    VECTOR3 a = { 1, 2, 3 }, b = { -2, 0, 1 }, c;
    VVECTOR3(c, a, b);
    print_vec("a", a);
    print_vec("b", b);
    print_vec("c = a x b", c);
    printf("  a . b = %g,  c . a = %g,  c . b = %g (c is perpendicular to "
           "both)\n\n", (double)SVECTOR3(a, b), (double)SVECTOR3(c, a),
           (double)SVECTOR3(c, b));
}

static void pathpoint(void)
{
    printf("== Ch. 1: a ray meets a sphere; the PATHPOINT it fills\n");
    VECTOR3 centre = { 0, 0, 0 };
    COBJECT *s = sphere_new(centre, 1, NULL);
    ray_t r = { { REAL_C(0.3), REAL_C(0.4), 5 }, { 0, 0, -1 } };
    hit_t h;
    if (!s || !cobject_intersect(s, &r, 0, (real)INFINITY, &h)) {
        printf("  no hit?\n");
        cobject_free(s);
        return;
    }
    PATHPOINT pp;
    cobject_fill(s, &r, &h, &pp);
    VECTOR3 light = { 0, 1, 0 };
    vec_normalize(light, light);
    pathpoint_set_in(&pp, light); /* Psi_i: toward a light straight above */
    print_vec("cross_point", pp.cross_point);
    print_vec("n", pp.n);
    print_vec("u", pp.u);
    print_vec("v", pp.v);
    print_vec("out (Psi_r)", pp.out);
    print_vec("in (Psi_i)", pp.in);
    printf("  bout = %s, bin = %s (acute angle with n?)\n",
           pp.bout ? "TRUE" : "FALSE", pp.bin ? "TRUE" : "FALSE");
    printf("  r_dist = %g (5 - sqrt(1 - 0.3^2 - 0.4^2) = %g)\n",
           (double)pp.r_dist, 5 - sqrt(1 - 0.09 - 0.16));
    printf("  IntersectObj = the %s; surface parameters (s, t) = (%.4f, %.4f)\n",
           pp.IntersectObj->ops->name, (double)pp.st[0], (double)pp.st[1]);
    printf("  %-12s (%.2g, %.2g, %.2g)\n", "p_error", (double)pp.p_error[X],
           (double)pp.p_error[Y], (double)pp.p_error[Z]);
    printf("  (p_error bounds the rounding error of cross_point: a ray leaving "
           "the surface\n   starts just beyond it, ray_spawn in ray.h)\n\n");
    cobject_free(s);
}

static void reflect_refract(void)
{
    printf("== Eq. (1.4): the mirror direction Psi_r = 2 (Psi_i . n) n - Psi_i\n");
    VECTOR3 n = { 0, 0, 1 }, in = { 1, 0, 1 }, r;
    vec_normalize(in, in);
    vec_reflect(r, in, n);
    print_vec("Psi_i", in);
    print_vec("Psi_r", r);
    printf("\n== Eqs. (1.11)-(1.12): refraction, glass (n = 1.5) and air\n");
    printf("  %8s | %-28s | %-28s\n", "theta_i", "air -> glass: theta_t",
           "glass -> air: theta_t");
    double crit = asin(1 / 1.5) * 180 / 3.14159265358979323846;
    const double angles[] = { 0, 15, 30, 40, 41, 41.8, 42, 60, 89 };
    for (int i = 0; i < 9; i++) {
        double th = angles[i] * 3.14159265358979323846 / 180;
        VECTOR3 w = { (real)sin(th), 0, (real)cos(th) }, t;
        char s1[64], s2[64];
        bool ok1 = vec_refract(t, w, n, 1, REAL_C(1.5));
        snprintf(s1, sizeof s1, "%.3f deg", acos(-(double)t[Z]) * 180 / 3.14159265358979323846);
        if (!ok1)
            snprintf(s1, sizeof s1, "total internal reflection");
        bool ok2 = vec_refract(t, w, n, REAL_C(1.5), 1);
        snprintf(s2, sizeof s2, "%.3f deg", acos(-(double)t[Z]) * 180 / 3.14159265358979323846);
        if (!ok2)
            snprintf(s2, sizeof s2, "total internal reflection");
        printf("  %8.1f | %-28s | %-28s\n", angles[i], s1, s2);
    }
    printf("  The critical angle of glass: asin(1/1.5) = %.4f deg; beyond it "
           "c2 > 1 in (1.12).\n\n", crit);
}

static void frames_and_rotation(void)
{
    printf("== App. A: a local frame (u, v, n) from a normal (Duff et al. "
           "2017)\n");
    const real ns[3][3] = { { 0, 0, 1 }, { 0, 0, -1 }, { 1, 1, 1 } };
    for (int i = 0; i < 3; i++) {
        VECTOR3 n = { ns[i][0], ns[i][1], ns[i][2] }, u, v, c;
        vec_normalize(n, n);
        frame_from_normal(u, v, n);
        VVECTOR3(c, u, v);
        printf("  n = (%6.3f %6.3f %6.3f): u = (%6.3f %6.3f %6.3f), v = "
               "(%6.3f %6.3f %6.3f), |u x v - n| = %.1e\n", (double)n[X],
               (double)n[Y], (double)n[Z], (double)u[X], (double)u[Y],
               (double)u[Z], (double)v[X], (double)v[Y], (double)v[Z],
               (double)vec_distance(c, n));
    }
    printf("\n== App. C: rotating (1, 0, 0) about z (Rodrigues)\n");
    VECTOR3 x = { 1, 0, 0 }, z = { 0, 0, 1 }, r;
    for (int deg = 0; deg <= 180; deg += 45) {
        vec_rotate(r, x, z, (real)deg * REAL_PI / 180);
        printf("  %3d deg: (%7.4f, %7.4f, %7.4f)\n", deg, (double)r[X],
               (double)r[Y], (double)r[Z]);
    }
    printf("\n");
}

/* --- app. D: every primitive, shaded by its normal ------------------------ */

#define NPRIM 10

static int build_gallery(COBJECT **o)
{
    int n = 0;
    VECTOR3 c, a, b, nrm;
    /* a row of shapes on a floor plane */
    vec_set(c, -3, 0, 0);
    o[n++] = sphere_new(c, REAL_C(0.8), NULL);
    vec_set(c, -1, 0, 0);
    vec_set(nrm, REAL_C(0.3), REAL_C(0.2), 1);
    o[n++] = disk_new(c, nrm, REAL_C(0.8), NULL);
    vec_set(a, REAL_C(0.3), REAL_C(-0.8), 0);
    vec_set(b, REAL_C(1.9), REAL_C(-0.6), REAL_C(-0.3));
    vec_set(c, REAL_C(0.4), REAL_C(0.8), REAL_C(0.2));
    o[n++] = parallelogram_new(a, b, c, NULL);
    vec_set(a, REAL_C(2.3), REAL_C(-0.8), 0);
    vec_set(b, REAL_C(3.8), REAL_C(-0.8), 0);
    vec_set(c, REAL_C(3.0), REAL_C(0.8), REAL_C(-0.4));
    o[n++] = triangle_new(a, b, c, NULL);
    /* second row */
    VECTOR3 lo = { -REAL_C(0.6), -REAL_C(0.6), -REAL_C(0.6) },
            hi = { REAL_C(0.6), REAL_C(0.6), REAL_C(0.6) };
    xform_t m = xform_compose(xform_rotate((VECTOR3){ 1, 1, 0 }, 30),
                              xform_translate((VECTOR3){ -3, REAL_C(-2.2), 0 }));
    o[n++] = xform_new(box_new(lo, hi, NULL), &m, NULL);
    vec_set(a, -1, REAL_C(-2.9), 0);
    vec_set(b, -1, REAL_C(-1.4), REAL_C(-0.5));
    o[n++] = cylinder_new(a, b, REAL_C(0.5), true, NULL);
    vec_set(a, REAL_C(1.0), REAL_C(-2.9), 0);
    vec_set(b, REAL_C(1.0), REAL_C(-1.3), REAL_C(0.3));
    o[n++] = cone_new(a, b, REAL_C(0.6), true, NULL);
    /* an ellipsoid: a unit sphere scaled and rotated, one line */
    xform_t e = xform_compose(xform_compose(xform_scale((VECTOR3){ REAL_C(0.9), REAL_C(0.45), REAL_C(0.5) }),
                                            xform_rotate((VECTOR3){ 0, 0, 1 }, 30)),
                              xform_translate((VECTOR3){ 3, REAL_C(-2.2), 0 }));
    vec_set(c, 0, 0, 0);
    o[n++] = xform_new(sphere_new(c, 1, NULL), &e, NULL);
    vec_set(c, 0, REAL_C(-3.2), 0);
    vec_set(nrm, 0, 1, 0);
    o[n++] = plane_new(c, nrm, NULL);
    for (int i = 0; i < n; i++)
        if (!o[i])
            return -1;
    return n;
}

static int gallery(const char *dir)
{
    COBJECT *o[NPRIM] = { 0 };
    int n = build_gallery(o);
    if (n < 0) {
        fprintf(stderr, "ch01_geometry: could not build the primitives\n");
        return 1;
    }
    camera_t cam;
    VECTOR3 eye = { 0, REAL_C(1.0), 9 }, at = { 0, REAL_C(-1.1), 0 }, up = { 0, 1, 0 };
    const int W = 480, H = 300;
    camera_init(&cam, eye, at, up, 52, CAMERA_FOV_X, W, H, NULL);
    char path[1024];
    snprintf(path, sizeof path, "%s/primitives.ppm", dir);
    FILE *f = fopen(path, "wb");
    if (!f) {
        perror(path);
        return 1;
    }
    fprintf(f, "P6\n%d %d\n255\n", W, H);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            ray_t r;
            camera_ray(&cam, (real)x + REAL_C(0.5), (real)y + REAL_C(0.5), &r);
            hit_t h, best;
            int who = -1;
            real tmax = (real)INFINITY;
            for (int i = 0; i < n; i++)
                if (cobject_intersect(o[i], &r, 0, tmax, &h)) {
                    best = h;
                    tmax = h.t;
                    who = i;
                }
            unsigned char px[3] = { 20, 20, 28 };
            if (who >= 0) {
                PATHPOINT pp;
                cobject_fill(o[who], &r, &best, &pp);
                /* the normal as a colour, (n + 1)/2, dimmed on the back */
                real k = pp.bout ? 1 : REAL_C(0.4);
                for (int c = 0; c < 3; c++)
                    px[c] = (unsigned char)(255 * k * (pp.n[c] + 1) / 2);
            }
            fwrite(px, 1, 3, f);
        }
    int bad = ferror(f);
    fclose(f);
    for (int i = 0; i < n; i++)
        cobject_free(o[i]);
    if (bad) {
        fprintf(stderr, "ch01_geometry: cannot write %s\n", path);
        return 1;
    }
    printf("== App. D: every primitive, coloured by its normal: %s\n", path);
    return 0;
}

int main(int argc, char **argv)
{
    const chapter_cli_t cli = {
        "ch01_geometry",
        "The book's structures at work (VECTOR3, PATHPOINT, reflection, "
        "refraction,\nframes, rotation), printed, and every primitive of "
        "app. D in OUTDIR/primitives.ppm.",
        "out/ch01", NULL, 0
    };
    const char *dir;
    int rc = chapter_begin(&cli, argc, argv, &dir);
    if (rc >= 0)
        return rc;
    vectors();
    pathpoint();
    reflect_refract();
    frames_and_rotation();
    return gallery(dir);
}
