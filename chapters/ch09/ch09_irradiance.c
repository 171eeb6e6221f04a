/* cc -std=c11 -O2 -fopenmp -Iinclude chapters/ch09/ch09_irradiance.c src/irradiance/irrpart.c src/irradiance/irrcache.c src/irradiance/gradients.c src/render/render.c src/render/subsample.c src/render/tracer.c src/render/integrator.c src/render/light.c src/render/camera.c src/render/scene.c src/render/scenefile.c src/materials/material.c src/materials/brdf.c src/core/sample.c src/core/rng.c src/materials/cobject.c src/geometry/shape.c src/geometry/sphere.c src/geometry/plane.c src/geometry/disk.c src/geometry/parallelogram.c src/geometry/triangle.c src/geometry/box.c src/geometry/cylinder.c src/geometry/cone.c src/geometry/quadric.c src/geometry/xform.c src/core/bbox.c src/core/ray.c src/core/frame.c src/core/vec.c src/colour/colour.c src/io/image.c src/io/netpbm.c src/colour/tonemap.c src/io/fileio.c src/core/error.c -lm -o ch09 */
/*
 * ch09_irradiance.c - chapter 9, the irradiance gradient method (Ward,
 * Rubinstein, Clear 1988; Ward & Heckbert 1992): the Cornell box of
 * scenes/cbox-irradiance.scn by the cache, with and without app. E's
 * gradients, beside the path tracer; the cache's records drawn over the
 * image (a dot at each, a circle of its radius R); a row of the images
 * side by side; the cache's image subsampled by app. F and its mask of
 * computed and interpolated pixels; and the error against a converged
 * path-traced render as Ward's accuracy a falls, with and without
 * gradients, with the records it took. Writes PFM and PPM images, row.csv
 * and error.csv (drawn by row.gp and error.gp beside this file: `make
 * figures`).
 * The method: src/irradiance/irrpart.c, irrcache.c, gradients.c (tests:
 * tests/irradiance/).
 *
 * usage: ch09 [OUTDIR] [--scale F] [--spp N] [--ref-spp N] [--threads N]
 * (default out/ch09; run from the top directory, where scenes/ is)
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
#include "irradiance/irrpart.h"
#include "render/render.h"
#include "render/scenefile.h"
#include "render/subsample.h"

/* the one part this program offers: the irradiance cache; and app. F's
 * subsampling */
static const scene_part_t *const parts[] = { &irr_part, NULL };
static const scene_features_t features = { .parts = parts,
                                           .subsample = &subsample_ops };
static const chapter_scene_t cbox = { "scenes/cbox-irradiance.scn", NULL,
                                      NULL, &features, 8, 8 };

/* App. F's mask of a subsampled render r: white where the pixel was
 * computed, the image dimmed to a quarter where it was interpolated, so
 * that the refined edges stand out against the smooth walls; the count of
 * computed pixels in *computed. */
static svet_status draw_mask(const render_t *r, const image_t *img,
                             image_t *mask, long *computed, svet_error *e)
{
    svet_status st = image_alloc(mask, img->width, img->height, 3, e);
    if (st != SVET_OK)
        return st;
    *computed = 0;
    for (int y = 0; y < img->height; y++)
        for (int x = 0; x < img->width; x++) {
            size_t i = (size_t)y * (size_t)img->width + (size_t)x;
            float *p = image_at(mask, x, y);
            const float *q = image_at(img, x, y);
            bool on = r->sub_mask && r->sub_mask[i];
            for (int c = 0; c < 3; c++)
                p[c] = on ? 1 : 0.25f * fminf(q[c], 1);
            *computed += on;
        }
    return SVET_OK;
}

/* A render of the scene with settings `set`: its image, and with
 * `records` its cache's record count (0 for the path tracer). With
 * `dots`, the records drawn over a copy of the image into *dots; with
 * `mask` (the scene subsampled), app. F's mask into *mask and the pixels
 * computed into *computed. */
static svet_status render_one(double scale, long spp, int threads,
                              const char *const *set, image_t *img,
                              size_t *records, image_t *dots, image_t *mask,
                              long *computed, svet_error *e)
{
    scene_t s;
    svet_status st = chapter_scene_load(&s, &cbox, scale, threads, set, e);
    if (st != SVET_OK)
        return st;
    render_t r;
    st = render_init(&r, &s, e);
    if (st != SVET_OK) {
        scene_free(&s);
        return st;
    }
    st = render_pass(&r, spp, threads, NULL, NULL);
    if (st != SVET_OK)
        *e = r.error;
    if (st == SVET_OK)
        st = render_image(&r, img, e);
    const irrcache_t *c = r.method == &irr_method && r.method_state
                              ? irr_state_cache(r.method_state) : NULL;
    if (records)
        *records = c ? c->n : 0;
    if (st == SVET_OK && mask)
        st = draw_mask(&r, img, mask, computed, e);
    if (st == SVET_OK && dots && c) {
        st = image_alloc(dots, img->width, img->height, 3, e);
        if (st == SVET_OK) {
            /* the image, dimmed, then each record: its radius R as seen
             * from the camera (across the view, at the record's
             * distance), a circle of it, and a dot at its centre */
            size_t n = (size_t)img->width * (size_t)img->height * 3;
            for (size_t i = 0; i < n; i++)
                dots->px[i] = 0.5f * img->px[i];
            for (size_t i = 0; i < c->n; i++) {
                const irr_record_t *rec = &c->rec[i];
                real x, y, x2, y2;
                VECTOR3 q;
                vec_copy(q, rec->p);
                for (int k = 0; k < 3; k++)
                    q[k] += rec->r * r.camera.u[k];
                if (!camera_project(&r.camera, rec->p, &x, &y) ||
                    !camera_project(&r.camera, q, &x2, &y2))
                    continue;
                double rad = hypot((double)(x2 - x), (double)(y2 - y));
                int steps = 8 + (int)(8 * rad);
                for (int k = 0; k <= steps; k++) {
                    double a = 2 * 3.14159265358979323846 * k / steps;
                    int px = (int)floor((double)x + rad * cos(a));
                    int py = (int)floor((double)y + rad * sin(a));
                    if (px >= 0 && py >= 0 && px < img->width &&
                        py < img->height) {
                        float *p = image_at(dots, px, py);
                        p[0] = 0.25f, p[1] = 0.5f, p[2] = 1;
                    }
                }
                int px = (int)floor((double)x), py = (int)floor((double)y);
                if (px >= 0 && py >= 0 && px < img->width && py < img->height) {
                    float *p = image_at(dots, px, py);
                    p[0] = 1, p[1] = 0.6f, p[2] = 0.1f;
                }
            }
        }
    }
    render_free(&r);
    scene_free(&s);
    return st;
}

/* The root mean square difference of a and the reference b over the
 * pixels that do not see the light (b below 1 in every channel), relative
 * to b's mean there */
static double rel_rmse(const image_t *a, const image_t *b)
{
    size_t n = (size_t)a->width * (size_t)a->height;
    double s = 0, m = 0;
    long used = 0;
    for (size_t i = 0; i < n; i++) {
        const float *p = b->px + 3 * i, *q = a->px + 3 * i;
        if (p[0] >= 1 || p[1] >= 1 || p[2] >= 1)
            continue;
        for (int c = 0; c < 3; c++) {
            double d = (double)q[c] - (double)p[c];
            s += d * d;
            m += (double)p[c];
        }
        used += 3;
    }
    return used > 0 && m > 0 ? sqrt(s / used) / (m / used) : 0;
}

int main(int argc, char **argv)
{
    double scale = 0.25, spp = 4, ref_spp = 256, threads = 0;
    const chapter_opt_t opts[] = {
        { "--scale", "F", "resolution relative to cbox-irradiance.scn's",
          &scale, 0.03, 4 },
        { "--spp", "N", "samples per pixel of the cache's renders", &spp, 1,
          1e5 },
        { "--ref-spp", "N", "samples per pixel of the path tracer's",
          &ref_spp, 1, 1e6 },
        { "--threads", "N", "threads (0 = every core)", &threads, 0, 1024 },
    };
    const chapter_cli_t cli = {
        "ch09_irradiance",
        "Chapter 9: the Cornell box by the irradiance cache with and without "
        "gradients,\nbeside the path tracer; the records drawn over the "
        "image; the error against a\nconverged render as the accuracy a "
        "falls.",
        "out/ch09", opts, (int)(sizeof opts / sizeof *opts)
    };
    const char *dir;
    int rc = chapter_begin(&cli, argc, argv, &dir);
    if (rc >= 0)
        return rc;
    svet_error e;
    int nt = (int)threads;
    long n = (long)spp;
    image_t ref = { 0 }, grad = { 0 }, flat = { 0 }, dots = { 0 };
    size_t records;

    printf("ch09: the path tracer, %ld samples per pixel\n", (long)ref_spp);
    static const char *const path_set[] = { "integrator=path", NULL };
    if (render_one(scale, (long)ref_spp, nt, path_set, &ref, NULL, NULL,
                   NULL, NULL, &e) != SVET_OK ||
        chapter_write_pair(dir, "ch09_path", &ref, NULL, NULL, &e))
        return chapter_fail("ch09", "path tracer", &e);

    printf("ch09: the cache with gradients, and its records\n");
    if (render_one(scale, n, nt, NULL, &grad, &records, &dots, NULL, NULL,
                   &e) != SVET_OK ||
        chapter_write_pair(dir, "ch09_irradiance", &grad, NULL, NULL, &e) ||
        chapter_write_pair(dir, "ch09_records", &dots, NULL, NULL, &e))
        return chapter_fail("ch09", "cache", &e);
    printf("  %zu records\n", records);
    printf("ch09: the cache without gradients\n");
    static const char *const flat_set[] = { "irradiance.gradients=off",
                                            NULL };
    if (render_one(scale, n, nt, flat_set, &flat, NULL, NULL, NULL, NULL,
                   &e) != SVET_OK ||
        chapter_write_pair(dir, "ch09_no_gradients", &flat, NULL, NULL, &e))
        return chapter_fail("ch09", "cache without gradients", &e);

    printf("ch09: the cache subsampled (app. F), and its mask\n");
    static const char *const sub_set[] = { "subsample.step=4",
                                           "subsample.threshold=0.2",
                                           NULL };
    image_t sub = { 0 }, mask = { 0 };
    long computed = 0;
    if (render_one(scale, n, nt, sub_set, &sub, NULL, NULL, &mask,
                   &computed, &e) != SVET_OK ||
        chapter_write_pair(dir, "ch09_subsampled", &sub, NULL, NULL, &e) ||
        chapter_write_pair(dir, "ch09_sub_mask", &mask, NULL, NULL, &e))
        return chapter_fail("ch09", "subsampling", &e);
    printf("  step 4, threshold 0.2: %ld of %ld pixels computed\n",
           computed, (long)sub.width * sub.height);
    image_free(&sub);
    image_free(&mask);

    /* the row through the middle of the image: the green channel */
    chapter_file_t cf;
    FILE *f = chapter_open(&cf, "ch09_irradiance", dir, "row.csv");
    if (!f)
        return CHAPTER_EXIT_FAIL;
    int row = ref.height / 2;
    fprintf(f, "# ch09_irradiance: row %d of the Cornell box, green "
               "channel: the cache at %ld spp with and without gradients, "
               "the path tracer at %ld spp\n", row, n, (long)ref_spp);
    fprintf(f, "x,gradients,no_gradients,path\n");
    for (int x = 0; x < ref.width; x++)
        fprintf(f, "%d,%.6g,%.6g,%.6g\n", x, (double)image_at(&grad, x, row)[1],
                (double)image_at(&flat, x, row)[1],
                (double)image_at(&ref, x, row)[1]);
    if (chapter_close(&cf, "ch09_irradiance") != 0)
        return CHAPTER_EXIT_FAIL;
    image_free(&grad);
    image_free(&flat);
    image_free(&dots);

    printf("ch09: the error against the path tracer as a falls\n");
    f = chapter_open(&cf, "ch09_irradiance", dir, "error.csv");
    if (!f)
        return CHAPTER_EXIT_FAIL;
    fprintf(f, "# ch09_irradiance: the cache at %ld spp against the path "
               "tracer at %ld spp, the relative RMS difference over the "
               "pixels not seeing the light\n", n, (long)ref_spp);
    fprintf(f, "a,records,rel_rmse,records_no_gradients,"
               "rel_rmse_no_gradients\n");
    printf("  %6s %8s %10s %8s %10s\n", "a", "records", "rmse", "records",
           "rmse (no gradients)");
    const double as[] = { 0.6, 0.4, 0.25, 0.15, 0.1 };
    for (int i = 0; i < (int)(sizeof as / sizeof *as); i++) {
        double err[2];
        size_t rec[2];
        for (int g = 0; g < 2; g++) {
            char a[48];
            snprintf(a, sizeof a, "irradiance.a=%g", as[i]);
            const char *const set[] = { a, g ? "irradiance.gradients=off"
                                             : "irradiance.gradients=on",
                                        NULL };
            image_t img = { 0 };
            if (render_one(scale, n, nt, set, &img, &rec[g], NULL, NULL,
                           NULL, &e) != SVET_OK) {
                chapter_close(&cf, "ch09_irradiance");
                return chapter_fail("ch09", "error against a", &e);
            }
            err[g] = rel_rmse(&img, &ref);
            image_free(&img);
        }
        fprintf(f, "%g,%zu,%.6g,%zu,%.6g\n", as[i], rec[0], err[0], rec[1],
                err[1]);
        printf("  %6g %8zu %10.4f %8zu %10.4f\n", as[i], rec[0], err[0],
               rec[1], err[1]);
    }
    if (chapter_close(&cf, "ch09_irradiance") != 0)
        return CHAPTER_EXIT_FAIL;
    image_free(&ref);
    return 0;
}
