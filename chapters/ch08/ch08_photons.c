/* cc -std=c11 -O2 -fopenmp -Iinclude chapters/ch08/ch08_photons.c src/photon/photon.c src/photon/photonmap.c src/photon/photonsave.c src/render/render.c src/render/tracer.c src/render/integrator.c src/render/light.c src/render/camera.c src/render/scene.c src/render/scenefile.c src/materials/material.c src/materials/brdf.c src/core/sample.c src/core/rng.c src/materials/cobject.c src/geometry/shape.c src/geometry/sphere.c src/geometry/plane.c src/geometry/disk.c src/geometry/parallelogram.c src/geometry/triangle.c src/geometry/box.c src/geometry/cylinder.c src/geometry/cone.c src/geometry/quadric.c src/geometry/xform.c src/core/bbox.c src/core/ray.c src/core/frame.c src/core/vec.c src/colour/colour.c src/io/image.c src/io/netpbm.c src/colour/tonemap.c src/io/fileio.c src/core/error.c -lm -o ch08 */
/*
 * ch08_photons.c - chapter 8, the photon map method (Jensen 1996, 2001):
 * the photons of scenes/caustic.scn drawn as dots over the scene (global
 * map blue, caustic map orange), the radiance estimate seen directly from
 * the global map at several k, the image with final gathering, and a
 * table of the estimate's bias and standard deviation against k and the
 * photon count on a plane under a point light, where the irradiance is
 * known exactly (E = I h / d^3). Writes PFM and PPM images and
 * bias.csv (drawn by bias.gp beside this file: `make figures`).
 * The method: src/photon/photon.c (tests: tests/photon/test_photon.c).
 *
 * usage: ch08 [OUTDIR] [--scale F] [--spp N] [--threads N] [--maps R]
 * (default out/ch08; run from the top directory, where scenes/ is)
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../chapter.h"
#include "../chapter_image.h"
#include "../chapter_scene.h"
#include "photon/photon.h"
#include "render/render.h"
#include "render/scenefile.h"

/* the one part this program offers: the photon maps */
static const scene_part_t *const parts[] = { &photon_part, NULL };
static const scene_features_t features = { .parts = parts };
static const chapter_scene_t caustic = { "scenes/caustic.scn", NULL, NULL,
                                         &features, 8, 6 };

/* Render the scene with settings `set` (NULL-terminated) and write it. */
static svet_status render_to(const char *dir, const char *stem, double scale,
                             long spp, int threads, const char *const *set,
                             svet_error *e)
{
    scene_t s;
    svet_status st = chapter_scene_load(&s, &caustic, scale, threads, set, e);
    if (st != SVET_OK)
        return st;
    render_t r;
    st = render_init(&r, &s, e);
    if (st == SVET_OK) {
        st = render_pass(&r, spp, threads, NULL, NULL);
        image_t img = { 0 };
        if (st != SVET_OK)
            *e = r.error;
        else
            st = render_image(&r, &img, e);
        if (st == SVET_OK)
            st = chapter_write_pair(dir, stem, &img, NULL, NULL, e);
        image_free(&img);
        render_free(&r);
        printf("  %s: %ld samples per pixel\n", stem, spp);
    }
    scene_free(&s);
    return st;
}

/* The photons as dots: every photon of both maps that the camera sees
 * (projected; not tested for visibility), global blue, caustic orange. */
static svet_status dots(const char *dir, double scale, int threads,
                        svet_error *e)
{
    scene_t s;
    svet_status st = chapter_scene_load(&s, &caustic, scale, threads, NULL, e);
    if (st != SVET_OK)
        return st;
    render_t r;
    st = render_init(&r, &s, e);
    photon_settings_t set;
    photon_settings_of(&s, &set);
    photonmap_t g = { 0 }, c = { 0 };
    if (st == SVET_OK)
        st = photon_trace(&r, set.global / 10, PHOTON_GLOBAL, 0, threads, &g,
                          e);
    if (st == SVET_OK)
        st = photon_trace(&r, set.caustic / 10, PHOTON_CAUSTIC, 1, threads,
                          &c, e);
    image_t img = { 0 };
    if (st == SVET_OK)
        st = image_alloc(&img, s.camera.width, s.camera.height, 3, e);
    for (int map = 0; st == SVET_OK && map < 2; map++) {
        const photonmap_t *m = map ? &c : &g;
        const float col[2][3] = { { 0.25f, 0.5f, 1 }, { 1, 0.6f, 0.1f } };
        for (size_t i = 1; i <= m->n; i++) {
            VECTOR3 p = { (real)m->ph[i].pos[0], (real)m->ph[i].pos[1],
                          (real)m->ph[i].pos[2] };
            real x, y;
            if (!camera_project(&r.camera, p, &x, &y) || x < 0 || y < 0 ||
                x >= (real)img.width || y >= (real)img.height)
                continue;
            float *px = image_at(&img, (int)x, (int)y);
            for (int k = 0; k < 3; k++)
                px[k] = col[map][k];
        }
    }
    if (st == SVET_OK) {
        st = chapter_write_pair(dir, "ch08_photons", &img, NULL, NULL, e);
        printf("  ch08_photons: %zu global and %zu caustic photons (a tenth "
               "of the scene's counts)\n", g.n, c.n);
    }
    image_free(&img);
    photonmap_free(&g);
    photonmap_free(&c);
    render_free(&r);
    scene_free(&s);
    return st;
}

/* The bias table: a diffuse plane z = 0 under a point light of intensity
 * I = 1 at height h = 1; the photons land once (maxdepth 0) and the
 * irradiance at (x, y) is exactly E = I h / d^3. For each photon count N
 * and k, R maps of independent streams give at each of 16 points along a
 * line the estimate's mean (its relative bias: blur and k/(k-1)) and
 * standard deviation over the maps, averaged over the points. */
static svet_status bias_table(const char *dir, int threads, int maps,
                              svet_error *e)
{
    static const char text[] =
        "camera position 0 0 3 target 0 0 0 up 0 1 0 width 8 height 8\n"
        "render maxdepth 0\n"
        "material grey lambert rho 0.5\n"
        "parallelogram c0 -4 -4 0 c1 4 -4 0 c3 -4 4 0 material grey\n"
        "light point position 0 0 1 intensity 1\n";
    scene_t s;
    svet_status st = scenefile_parse_with(&s, text, strlen(text), "plane",
                                          NULL, &features, e);
    if (st != SVET_OK)
        return st;
    render_t r;
    st = render_init(&r, &s, e);
    if (st != SVET_OK) {
        scene_free(&s);
        return st;
    }
    chapter_file_t cf;
    FILE *f = chapter_open(&cf, "ch08_photons", dir, "bias.csv");
    if (!f) {
        render_free(&r);
        scene_free(&s);
        return svet_error_set(e, SVET_ERR_IO, "cannot write bias.csv");
    }
    fprintf(f, "# ch08_photons: the irradiance estimate on a plane under a "
               "point light, against E = I h / d^3, over %d maps\n", maps);
    fprintf(f, "photons,k,rel_bias,rel_sd,rel_rmse\n");
    printf("  %9s %5s %10s %10s %10s\n", "photons", "k", "bias", "sd",
           "rmse");
    const uint64_t counts[] = { 10000, 100000, 1000000 };
    const int ks[] = { 5, 10, 25, 50, 100, 200, 400 };
    enum { NP = 16 };
    for (int a = 0; st == SVET_OK && a < 3; a++)
        for (int b = 0; st == SVET_OK && b < 7; b++) {
            double sum[NP] = { 0 }, sum2[NP] = { 0 }, exact[NP];
            for (int m = 0; st == SVET_OK && m < maps; m++) {
                photonmap_t pm;
                st = photon_trace(&r, counts[a], PHOTON_GLOBAL, 100 + m,
                                  threads, &pm, e);
                photonmap_query_t q = { ks[b], 1, PHOTONMAP_FILTER_NONE,
                                        REAL_C(1.1), 0 };
                for (int i = 0; st == SVET_OK && i < NP; i++) {
                    VECTOR3 x = { (real)(0.1 * i), 0, 0 }, n = { 0, 0, 1 };
                    double d = sqrt(1 + 0.01 * i * i);
                    exact[i] = 1 / (d * d * d);
                    double v = (double)photonmap_irradiance(&pm, x, n, &q).g /
                               exact[i];
                    sum[i] += v;
                    sum2[i] += v * v;
                }
                photonmap_free(&pm);
            }
            double bias = 0, var = 0;
            for (int i = 0; i < NP; i++) {
                double mean = sum[i] / maps;
                bias += (mean - 1) / NP;
                var += (sum2[i] / maps - mean * mean) * maps / (maps - 1) / NP;
            }
            double sd = sqrt(fmax(var, 0));
            fprintf(f, "%llu,%d,%.6g,%.6g,%.6g\n",
                    (unsigned long long)counts[a], ks[b], bias, sd,
                    sqrt(bias * bias + var));
            printf("  %9llu %5d %+10.4f %10.4f %10.4f\n",
                   (unsigned long long)counts[a], ks[b], bias, sd,
                   sqrt(bias * bias + var));
        }
    if (chapter_close(&cf, "ch08_photons") != 0 && st == SVET_OK)
        st = svet_error_set(e, SVET_ERR_IO, "cannot write bias.csv");
    render_free(&r);
    scene_free(&s);
    return st;
}

int main(int argc, char **argv)
{
    double scale = 0.5, spp = 4, threads = 0, maps = 8;
    const chapter_opt_t opts[] = {
        { "--scale", "F", "resolution relative to caustic.scn's", &scale,
          0.05, 4 },
        { "--spp", "N", "samples per pixel of the renders", &spp, 1, 1e5 },
        { "--threads", "N", "threads (0 = every core)", &threads, 0, 1024 },
        { "--maps", "R", "independent maps per row of the bias table", &maps,
          2, 1000 },
    };
    const chapter_cli_t cli = {
        "ch08_photons",
        "Chapter 8: the photons of scenes/caustic.scn as dots, the global "
        "map's estimate at\nseveral k, final gathering, and the estimate's "
        "bias and spread against k and\nthe photon count.",
        "out/ch08", opts, (int)(sizeof opts / sizeof *opts)
    };
    const char *dir;
    int rc = chapter_begin(&cli, argc, argv, &dir);
    if (rc >= 0)
        return rc;
    svet_error e;
    int nt = (int)threads;
    long n = (long)spp;
    printf("ch08: photons as dots\n");
    if (dots(dir, scale, nt, &e) != SVET_OK)
        return chapter_fail("ch08", "dots", &e);
    printf("ch08: the global map seen directly, at several k\n");
    static const char *const kset[3][4] = {
        { "photonmap.gather=0", "photonmap.k=10", "photonmap.max_radius=0.3",
          NULL },
        { "photonmap.gather=0", "photonmap.k=50", "photonmap.max_radius=0.3",
          NULL },
        { "photonmap.gather=0", "photonmap.k=250", "photonmap.max_radius=0.3",
          NULL },
    };
    const char *kstem[3] = { "ch08_global_k10", "ch08_global_k50",
                             "ch08_global_k250" };
    for (int i = 0; i < 3; i++)
        if (render_to(dir, kstem[i], scale, n, nt, kset[i], &e) != SVET_OK)
            return chapter_fail("ch08", kstem[i], &e);
    printf("ch08: final gathering, and the path tracer for comparison\n");
    if (render_to(dir, "ch08_gather", scale, n, nt, NULL, &e) != SVET_OK)
        return chapter_fail("ch08", "gather", &e);
    static const char *const path_set[] = { "integrator=path", NULL };
    if (render_to(dir, "ch08_path", scale, 16 * n, nt, path_set, &e) !=
        SVET_OK)
        return chapter_fail("ch08", "path", &e);
    printf("ch08: the estimate's bias and spread (%s/bias.csv)\n", dir);
    if (bias_table(dir, nt, (int)maps, &e) != SVET_OK)
        return chapter_fail("ch08", "bias table", &e);
    return 0;
}
