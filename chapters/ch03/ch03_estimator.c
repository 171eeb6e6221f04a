/* cc -std=c11 -O2 -Iinclude chapters/ch03/ch03_estimator.c src/core/vec.c src/core/frame.c src/core/ray.c src/core/bbox.c src/materials/cobject.c src/core/error.c src/core/rng.c src/core/sample.c src/materials/brdf.c src/materials/material.c src/geometry/sphere.c src/geometry/disk.c src/geometry/quadric.c src/geometry/shape.c src/render/camera.c -lm -o ch03 */
/*
 * ch03_estimator.c - chapter 3, the rendering equation, estimated for one
 * pixel and written out step by step.
 *
 * The rendering equation (Kajiya 1986; ch. 3) for the radiance leaving a
 * surface point x in direction wo:
 *
 *   L(x, wo) = Le(x, wo) + int_Omega f(x, wi, wo) L(x', -wi) |cos theta_i| dwi
 *
 * where x' is the first surface seen from x in direction wi. It is
 * recursive: L appears on both sides. The Monte Carlo method of ch. 4
 * replaces the integral by one sample wi drawn with density p(wi):
 *
 *   L(x, wo) ~ Le(x, wo) + f(x, wi, wo) L(x', -wi) |cos theta_i| / p(wi)
 *
 * and the L on the right is estimated the same way at x': a random walk, a
 * "path". The factor beta = prod f |cos| / p carried along the path is the
 * throughput. Russian roulette (ch. 4) ends the walk without bias: continue
 * with probability q, and divide beta by q when continuing.
 *
 * This program builds a small closed scene (a diffuse room that is a sphere
 * seen from inside, a floor, a ball and a spherical lamp), follows the
 * first few paths through the centre pixel printing every step, and then
 * shows the estimate converging as the number of paths N grows, with its
 * standard error sqrt(Var/N). The renderer's integrator (src/render/integrator.c)
 * is the same estimator plus light sampling and MIS (ch. 5).
 *
 * The estimate and its standard error at every power of two go to
 * OUTDIR/ch03_convergence.csv, drawn by convergence.gp beside this file
 * (`make figures`).
 * usage: ch03 [OUTDIR] [--paths N]   (default out/, 262144 paths; --help)
 */
#include <stdio.h>
#include <stdlib.h>

#include "../chapter.h"

#include "render/camera.h"
#include "geometry/disk.h"
#include "core/frame.h"
#include "materials/material.h"
#include "core/sample.h"
#include "geometry/sphere.h"

#define NOBJ 4

typedef struct {
    COBJECT *obj[NOBJ];
    material_t mat[NOBJ];
    RADIANCE Le[NOBJ]; /* emitted radiance of each object */
    const char *name[NOBJ];
} scene3_t;

static void build(scene3_t *s)
{
    VECTOR3 o = { 0, 0, 0 }, floor_c = { 0, -1, 0 }, up = { 0, 1, 0 };
    VECTOR3 ball_c = { REAL_C(0.3), REAL_C(-0.6), 0 }, lamp_c = { 0, REAL_C(1.6), 0 };
    s->obj[0] = sphere_new(o, 3, NULL);           /* the room, seen from inside */
    s->obj[1] = disk_new(floor_c, up, 2, NULL);   /* the floor */
    s->obj[2] = sphere_new(ball_c, REAL_C(0.4), NULL);
    s->obj[3] = sphere_new(lamp_c, REAL_C(0.6), NULL);
    material_lambert(&s->mat[0], rad_grey(REAL_C(0.5)), NULL);
    material_lambert(&s->mat[1], rad_make(0.7, 0.7, 0.6), NULL);
    material_phong(&s->mat[2], rad_make(0.6, 0.1, 0.1), rad_grey(REAL_C(0.3)),
                   20, NULL);
    material_lambert(&s->mat[3], rad_grey(0), NULL);
    for (int i = 0; i < NOBJ; i++)
        s->Le[i] = rad_grey(0);
    s->Le[3] = rad_grey(5); /* the lamp: 5 W/(m^2 sr) */
    const char *names[NOBJ] = { "room", "floor", "ball", "lamp" };
    for (int i = 0; i < NOBJ; i++)
        s->name[i] = names[i];
}

/* The nearest surface along r: index of the object, or -1. */
static int trace(const scene3_t *s, const ray_t *r, hit_t *best)
{
    int who = -1;
    real tmax = (real)INFINITY;
    for (int i = 0; i < NOBJ; i++) {
        hit_t h;
        if (cobject_intersect(s->obj[i], r, 0, tmax, &h)) {
            *best = h;
            tmax = h.t;
            who = i;
        }
    }
    return who;
}

/* One path: the estimate of L along the camera ray, printed when verbose. */
static real estimate(const scene3_t *s, ray_t r, pcg32_t *g, bool verbose)
{
    RADIANCE L = rad_grey(0), beta = rad_grey(1);
    for (int depth = 0; depth < 64; depth++) {
        hit_t h;
        int i = trace(s, &r, &h);
        if (i < 0) { /* the room is closed: cannot happen */
            if (verbose)
                printf("    the ray escapes\n");
            break;
        }
        PATHPOINT pp; /* ch. 1's structure: frame, point, in/out, ... */
        cobject_fill(s->obj[i], &r, &h, &pp);
        /* L += beta Le(x, wo): light emitted toward the previous vertex */
        L = rad_add(L, rad_mul(beta, s->Le[i]));
        if (verbose)
            printf("    %d: hits the %-5s at (%6.3f %6.3f %6.3f), r_dist "
                   "%.3f; Le = %.1f; L so far %.4f\n", depth, s->name[i],
                   (double)pp.cross_point[X], (double)pp.cross_point[Y],
                   (double)pp.cross_point[Z], (double)pp.r_dist,
                   (double)s->Le[i].g, (double)L.g);
        /* sample wi from f |cos| (material_sample, ch. 1 and 4) */
        VECTOR3 wo, wi;
        frame_to_local(wo, pp.out, pp.u, pp.v, pp.n);
        real u[3] = { pcg32_real(g), pcg32_real(g), pcg32_real(g) };
        brdf_sample_t bs;
        if (!material_sample(&s->mat[i], wo, u, &bs)) {
            if (verbose)
                printf("       absorbed (black surface or no direction)\n");
            break;
        }
        /* beta *= f |cos theta_i| / p(wi) */
        beta = rad_mul(beta, bs.weight);
        if (verbose)
            printf("       sampled wi with p = %.4f, f cos / p = %.4f: "
                   "throughput beta = %.4f\n", (double)bs.pdf,
                   (double)bs.weight.g, (double)beta.g);
        /* Russian roulette: continue with probability q */
        real q = fmin(REAL_C(1.0), fmax(REAL_C(0.05), rad_max(beta)));
        if (depth >= 2) {
            if (pcg32_real(g) >= q) {
                if (verbose)
                    printf("       Russian roulette ends the path "
                           "(q = %.3f)\n", (double)q);
                break;
            }
            beta = rad_scale(beta, 1 / q);
            if (verbose)
                printf("       survives Russian roulette (q = %.3f): beta /= q "
                       "= %.4f\n", (double)q, (double)beta.g);
        }
        frame_to_world(wi, bs.wi, pp.u, pp.v, pp.n);
        pathpoint_set_in(&pp, wi);
        ray_spawn(&r, pp.cross_point, pp.p_error, pp.ng, wi);
    }
    return L.g; /* the green channel, for the table */
}

int main(int argc, char **argv)
{
    double paths = 262144;
    const chapter_opt_t opts[] = {
        { "--paths", "N", "paths through the pixel", &paths, 1, 1e9 },
    };
    const chapter_cli_t cli = {
        "ch03",
        "Chapter 3: the rendering equation's estimator for one pixel, the "
        "first paths\nprinted step by step, and its convergence (printed, "
        "and in OUTDIR/ch03_convergence.csv).",
        "out", opts, 1
    };
    const char *dir;
    int rc = chapter_begin(&cli, argc, argv, &dir);
    if (rc >= 0)
        return rc;
    long nmax = (long)paths;
    chapter_file_t cf;
    FILE *csv = chapter_open(&cf, cli.prog, dir, "ch03_convergence.csv");
    if (!csv)
        return 1;
    fprintf(csv, "# ch03: the estimate of L (green, W/(m^2 sr)) at the centre "
                 "pixel after N paths, its standard error sqrt(Var/N) and "
                 "sqrt(Var)\nN,mean,stderr,sqrt_var\n");
    scene3_t s;
    build(&s);
    for (int i = 0; i < NOBJ; i++)
        if (!s.obj[i]) {
            fprintf(stderr, "ch03: could not build the scene\n");
            fclose(csv);
            remove(cf.tmp);
            return 1;
        }
    camera_t cam;
    VECTOR3 eye = { 0, 0, REAL_C(2.5) }, at = { 0, REAL_C(-0.5), 0 }, up = { 0, 1, 0 };
    camera_init(&cam, eye, at, up, 50, CAMERA_FOV_Y, 64, 64, NULL);

    printf("Chapter 3: the rendering equation, one pixel (32, 32) of 64 x 64.\n"
           "Estimator: L = Le + f L cos / p, recursively; green channel.\n\n");
    estimator_t e;
    estimator_init(&e);
    long next = 1;
    bool lit_shown = false;
    for (long n = 0; n < nmax; n++) {
        /* path n uses the numbers of sample n of this pixel (rng.h), so it
         * can be followed again with the same numbers */
        pcg32_t g, again;
        rng_for_sample(&g, 3, 32 * 64 + 32, (uint64_t)n);
        ray_t r;
        camera_ray(&cam, 32 + pcg32_real(&g), 32 + pcg32_real(&g), &r);
        again = g;
        bool verbose = n < 3;
        if (verbose)
            printf("path %ld:\n", n);
        real L = estimate(&s, r, &g, verbose);
        if (verbose)
            printf("  estimate %.4f\n\n", (double)L);
        if (!verbose && L > 0 && !lit_shown) {
            printf("path %ld, the first to reach the lamp, once more:\n", n);
            estimate(&s, r, &again, true);
            printf("  estimate %.4f\n\n", (double)L);
            lit_shown = true;
        }
        estimator_add(&e, (double)L);
        if (((n + 1) & n) == 0 || n + 1 == nmax) /* a power of two, or the last */
            fprintf(csv, "%ld,%.9g,%.9g,%.9g\n", n + 1, estimator_mean(&e),
                    estimator_stderr(&e), sqrt(estimator_variance(&e)));
        if (n + 1 == next || n + 1 == nmax) {
            if (next == 1)
                printf("%10s %12s %12s %12s\n", "N", "mean L", "std. error",
                       "sqrt(Var)");
            printf("%10ld %12.5f %12.5f %12.5f\n", n + 1, estimator_mean(&e),
                   estimator_stderr(&e), sqrt(estimator_variance(&e)));
            next *= 4;
        }
    }
    printf("\nThe standard error falls as 1/sqrt(N): 4 times the paths, half "
           "the error.\n");
    for (int i = 0; i < NOBJ; i++)
        cobject_free(s.obj[i]);
    return chapter_close(&cf, cli.prog);
}
