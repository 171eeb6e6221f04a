/* cc -std=c11 -O2 -fopenmp -Iinclude chapters/ch11/ch11_media.c src/medium/medpart.c src/medium/volpath.c src/medium/volsingle.c src/medium/medium.c src/medium/phase.c src/medium/volgrid.c src/texture/interp.c src/render/render.c src/render/tracer.c src/render/integrator.c src/render/light.c src/render/camera.c src/render/scene.c src/render/scenefile.c src/materials/material.c src/materials/brdf.c src/core/sample.c src/core/rng.c src/materials/cobject.c src/geometry/shape.c src/geometry/sphere.c src/geometry/plane.c src/geometry/disk.c src/geometry/parallelogram.c src/geometry/triangle.c src/geometry/box.c src/geometry/cylinder.c src/geometry/cone.c src/geometry/quadric.c src/geometry/xform.c src/core/bbox.c src/core/ray.c src/core/frame.c src/core/vec.c src/colour/colour.c src/io/image.c src/io/netpbm.c src/colour/tonemap.c src/io/fileio.c src/core/error.c -lm -o ch11 */
/*
 * ch11_media.c - chapter 11, participating media: the Beer-Lambert law
 * per channel beside ratio tracking's estimate of it (Novak et al. 2014)
 * under a majorant twice the extinction; the Henyey-Greenstein lobes for
 * g = -0.6, 0, 0.3, 0.8, the exact pdf beside a histogram of the exact
 * sampler; and one smoky scene rendered by single scattering with ray
 * marching (`volsingle`) and by volumetric path tracing (`volpath`) in
 * equal time, each against a long volpath reference. Writes beer.csv,
 * hg.csv, equal_time.csv (drawn by beer.gp, hg.gp beside this file:
 * `make figures`) and PFM and PPM images.
 * The methods: src/medium/ (tests: tests/medium/).
 *
 * usage: ch11 [OUTDIR] [--scale F] [--seconds S] [--ref N] [--threads N]
 * (default out/ch11)
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../chapter.h"
#include "../chapter_image.h"
#include "../chapter_scene.h"
#include "medium/medium.h"
#include "medium/medpart.h"
#include "medium/phase.h"
#include "render/render.h"
#include "render/scenefile.h"

/* the one part this program offers: the media */
static const scene_part_t *const parts[] = { &medium_part, NULL };
static const scene_features_t features = { .parts = parts };

static const double PI = 3.14159265358979323846;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* --- Beer-Lambert and ratio tracking ---------------------------------- */

/* a density of 1 everywhere, given as a function so that the medium is
 * not taken for homogeneous and its transmittance is ratio-tracked */
static real one(const void *ctx, const VECTOR3 p)
{
    (void)ctx;
    (void)p;
    return 1;
}

static int beer(const char *dir)
{
    chapter_file_t cf;
    FILE *f = chapter_open(&cf, "ch11_media", dir, "beer.csv");
    if (!f)
        return CHAPTER_EXIT_FAIL;
    medium_t m = medium_homogeneous(rad_make(REAL_C(0.5), 1, 2), rad_grey(0));
    medium_t rt = m;
    rt.fn = one;
    rt.fn_max = 2; /* a majorant twice sigma_t: half the collisions null */
    const int n = 1000;
    fprintf(f, "# transmittance through sigma_t = (0.5, 1, 2): exact "
               "exp(-sigma_t d), and the mean of %d ratio-tracking "
               "estimates with its standard error\n", n);
    fprintf(f, "d,exact_r,exact_g,exact_b,rt_r,rt_g,rt_b,se_r,se_g,se_b\n");
    const VECTOR3 o = { 0, 0, 0 }, dir_z = { 0, 0, 1 };
    for (int i = 0; i <= 40; i++) {
        real d = (real)i / 10;
        RADIANCE ex = medium_tr_homogeneous(&m, d);
        double s[3] = { 0, 0, 0 }, s2[3] = { 0, 0, 0 };
        pcg32_t g;
        pcg32_seed(&g, 11, (uint64_t)i);
        for (int k = 0; k < n; k++) {
            RADIANCE t = medium_tr(&rt, o, dir_z, d, &g);
            const double c[3] = { (double)t.r, (double)t.g, (double)t.b };
            for (int ch = 0; ch < 3; ch++) {
                s[ch] += c[ch];
                s2[ch] += c[ch] * c[ch];
            }
        }
        double mean[3], se[3];
        for (int ch = 0; ch < 3; ch++) {
            mean[ch] = s[ch] / n;
            double var = (s2[ch] / n - mean[ch] * mean[ch]) * n / (n - 1);
            se[ch] = sqrt(var > 0 ? var / n : 0);
        }
        fprintf(f, "%g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.4g,%.4g,%.4g\n",
                (double)d, (double)ex.r, (double)ex.g, (double)ex.b, mean[0],
                mean[1], mean[2], se[0], se[1], se[2]);
    }
    return chapter_close(&cf, "ch11_media") ? CHAPTER_EXIT_FAIL : 0;
}

/* --- Henyey-Greenstein lobes ------------------------------------------ */

static int lobes(const char *dir)
{
    enum { NG = 4, NB = 90 };
    const double gs[NG] = { -0.6, 0, 0.3, 0.8 };
    const long n = 1000000;
    static long hist[NG][NB];
    memset(hist, 0, sizeof hist);
    for (int j = 0; j < NG; j++) {
        phase_t p = { PHASE_HG, (real)gs[j] };
        pcg32_t g;
        pcg32_seed(&g, 29, (uint64_t)j);
        for (long k = 0; k < n; k++) {
            double c = (double)phase_sample_cos(&p, pcg32_real(&g));
            double th = acos(c < -1 ? -1 : c > 1 ? 1 : c);
            int b = (int)(th / PI * NB);
            hist[j][b < NB ? b : NB - 1]++;
        }
    }
    chapter_file_t cf;
    FILE *f = chapter_open(&cf, "ch11_media", dir, "hg.csv");
    if (!f)
        return CHAPTER_EXIT_FAIL;
    fprintf(f, "# HG p(theta) per unit solid angle: exact, and %ld exact "
               "samples binned in theta (count / (n 2 pi (cos a - cos b)))\n",
            n);
    fprintf(f, "theta");
    for (int j = 0; j < NG; j++)
        fprintf(f, ",exact_%g,sampled_%g", gs[j], gs[j]);
    fprintf(f, "\n");
    for (int b = 0; b < NB; b++) {
        double a0 = PI * b / NB, a1 = PI * (b + 1) / NB, th = (a0 + a1) / 2;
        fprintf(f, "%.6g", th);
        for (int j = 0; j < NG; j++) {
            phase_t p = { PHASE_HG, (real)gs[j] };
            double ex = (double)phase_eval(&p, (real)cos(th));
            double sa = 2 * PI * (cos(a0) - cos(a1));
            fprintf(f, ",%.6g,%.6g", ex, (double)hist[j][b] / ((double)n * sa));
        }
        fprintf(f, "\n");
    }
    return chapter_close(&cf, "ch11_media") ? CHAPTER_EXIT_FAIL : 0;
}

/* --- the same medium by each estimator, in equal time ------------------ */

/* A sphere of forward-scattering smoke over a floor, before a wall, lit
 * by a square light above it. */
static const char scene_text[] =
    "camera position 0 1 4.5 target 0 0.7 0 fov 40 width 160 height 120\n"
    "render spp 1 maxdepth 32 seed 1\n"
    "volsingle step 0.05\n"
    "material grey lambert rho 0.6\n"
    "material black lambert rho 0\n"
    "medium smoke homogeneous sigma_a 0.1 sigma_s 1.5 phase hg g 0.5\n"
    "parallelogram c0 -0.5 2.5 -0.5 c1 0.5 2.5 -0.5 c3 -0.5 2.5 0.5 "
    "material black emit 12\n"
    "plane point 0 0 0 normal 0 1 0 material grey\n"
    "plane point 0 0 -2 normal 0 0 1 material grey\n"
    "sphere centre 0 0.8 0 radius 0.7 material black medium smoke "
    "invisible\n";

static const chapter_scene_t smoke = { NULL, scene_text, "ch11_media.c",
                                       &features, 8, 6 };

/* Render with `integrator`: spp samples when spp > 0, else one sample
 * per pixel at a time until `seconds` have passed; *spp_done and
 * *secs say how many and how long. */
static svet_status render_for(const char *integrator, double scale, long spp,
                              double seconds, int threads, image_t *img,
                              long *spp_done, double *secs, svet_error *e)
{
    char buf[64];
    snprintf(buf, sizeof buf, "integrator=%s", integrator);
    const char *const set[] = { buf, NULL };
    scene_t s;
    svet_status st = chapter_scene_load(&s, &smoke, scale, threads, set, e);
    if (st != SVET_OK)
        return st;
    render_t r;
    st = render_init(&r, &s, e);
    if (st == SVET_OK) {
        double t0 = now();
        long n = 0;
        while (st == SVET_OK &&
               (spp > 0 ? n < spp : (n == 0 || now() - t0 < seconds))) {
            n++;
            st = render_pass(&r, n, threads, NULL, NULL);
            if (st != SVET_OK)
                *e = r.error;
        }
        *secs = now() - t0;
        *spp_done = n;
        if (st == SVET_OK)
            st = render_image(&r, img, e);
        render_free(&r);
    }
    scene_free(&s);
    return st;
}

/* root mean square difference over pixels and channels */
static double rmse(const image_t *a, const image_t *b)
{
    double s = 0;
    for (int y = 0; y < a->height; y++)
        for (int x = 0; x < a->width; x++)
            for (int k = 0; k < 3; k++) {
                double d = (double)image_at(a, x, y)[k] -
                           (double)image_at(b, x, y)[k];
                s += d * d;
            }
    return sqrt(s / (3.0 * a->width * a->height));
}

static int equal_time(const char *dir, double scale, double seconds,
                      long ref_spp, int threads)
{
    svet_error e;
    image_t ref = { 0 }, img = { 0 };
    long n;
    double secs;
    printf("ch11: the volpath reference, %ld samples per pixel\n", ref_spp);
    if (render_for("volpath", scale, ref_spp, 0, threads, &ref, &n, &secs,
                   &e) != SVET_OK ||
        chapter_write_pair(dir, "ch11_reference", &ref, NULL, NULL, &e) !=
            SVET_OK)
        return chapter_fail("ch11", "reference", &e);
    chapter_file_t cf;
    FILE *f = chapter_open(&cf, "ch11_media", dir, "equal_time.csv");
    if (!f) {
        image_free(&ref);
        return CHAPTER_EXIT_FAIL;
    }
    fprintf(f, "# the smoky sphere in %g s each against volpath at %ld spp "
               "(%.1f s)\n", seconds, ref_spp, secs);
    fprintf(f, "integrator,spp,seconds,rmse\n");
    static const char *const methods[] = { "volsingle", "volpath" };
    int rc = 0;
    for (int i = 0; i < 2 && rc == 0; i++) {
        char stem[64];
        snprintf(stem, sizeof stem, "ch11_%s", methods[i]);
        if (render_for(methods[i], scale, 0, seconds, threads, &img, &n,
                       &secs, &e) != SVET_OK ||
            chapter_write_pair(dir, stem, &img, NULL, NULL, &e) != SVET_OK) {
            rc = chapter_fail("ch11", methods[i], &e);
            break;
        }
        double err = rmse(&img, &ref);
        fprintf(f, "%s,%ld,%.3f,%.6g\n", methods[i], n, secs, err);
        printf("  %s: %ld samples per pixel in %.2f s, rmse %.4g\n",
               methods[i], n, secs, err);
        image_free(&img);
    }
    image_free(&ref);
    if (chapter_close(&cf, "ch11_media") != 0 && rc == 0)
        rc = CHAPTER_EXIT_FAIL;
    return rc;
}

int main(int argc, char **argv)
{
    double scale = 0.5, seconds = 2, ref = 512, threads = 0;
    const chapter_opt_t opts[] = {
        { "--scale", "F", "resolution relative to 160 x 120", &scale, 0.05,
          8 },
        { "--seconds", "S", "time of each equal-time render", &seconds, 0.01,
          3600 },
        { "--ref", "N", "samples per pixel of the volpath reference", &ref, 1,
          1e6 },
        { "--threads", "N", "threads (0 = every core)", &threads, 0, 1024 },
    };
    const chapter_cli_t cli = {
        "ch11_media",
        "Chapter 11: Beer-Lambert against ratio tracking, the HG lobes exact "
        "and sampled,\nand a smoky sphere by single scattering (ray "
        "marching) and by volumetric\npath tracing in equal time against a "
        "long reference.",
        "out/ch11", opts, (int)(sizeof opts / sizeof *opts)
    };
    const char *dir;
    int rc = chapter_begin(&cli, argc, argv, &dir);
    if (rc >= 0)
        return rc;
    printf("ch11: Beer-Lambert and ratio tracking (%s/beer.csv)\n", dir);
    if ((rc = beer(dir)) != 0)
        return rc;
    printf("ch11: the HG lobes (%s/hg.csv)\n", dir);
    if ((rc = lobes(dir)) != 0)
        return rc;
    return equal_time(dir, scale, seconds, (long)ref, (int)threads);
}
