/* cc -std=c11 -O2 -Iinclude chapters/ch07/ch07_grids.c src/accel/accel.c src/accel/grid.c src/accel/grid_build.c src/accel/primset.c src/mesh/mesh.c src/mesh/meshgen.c src/geometry/triangle.c src/geometry/shape.c src/core/frame.c src/core/vec.c src/core/bbox.c src/materials/cobject.c src/core/ray.c src/core/rng.c src/core/error.c src/render/camera.c src/io/image.c src/io/netpbm.c src/io/fileio.c -lm -o ch07 */
/*
 * ch07_grids.c - chapter 7, hierarchical grids: where the time of a ray
 * goes. For two procedural scenes (5 x 5 x 5 spheres of 1e5 triangles, and
 * the teapot in a stadium) and both grids, a heat map of the cells each
 * pixel's camera ray visits (Amanatides & Woo's walk, every level of the
 * hierarchy counted), as a PFM of the raw counts (R = cells, G = triangle
 * tests, B = 1 where the ray hit) and a false-colour PPM on one log scale
 * per scene, with the cells counts also as CSV (one row of the image a
 * line) for heatmap.gp beside this file (`make figures`), which draws
 * them with their colour scale; and a table of build time, memory and
 * work per ray.
 * Usage: ch07 [OUTDIR] [--width W]   (default out/, 480 x 360; --help)
 * Benchmark tables: bench/bench_grid.c, chapters/ch07/README.md.
 */
#include "../chapter.h"
#include "accel/accel.h"
#include "accel/grid.h"
#include "render/camera.h"
#include "io/image.h"
#include "mesh/meshgen.h"
#include "io/netpbm.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int W = 480, H = 360; /* --width W: H = 3 W / 4 */

/* A ramp from black through purple, red and yellow to white: a count c of
 * at most cmax maps to t = ln(1 + c) / ln(1 + cmax). */
static void heat_colour(double t, float rgb[3])
{
    static const float ramp[5][3] = { { 0, 0, 0 },
                                      { 0.35f, 0.05f, 0.55f },
                                      { 0.9f, 0.15f, 0.2f },
                                      { 1, 0.8f, 0.1f },
                                      { 1, 1, 1 } };
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    double x = t * 4;
    int i = (int)x < 3 ? (int)x : 3;
    float f = (float)(x - i);
    for (int k = 0; k < 3; k++)
        rgb[k] = ramp[i][k] + f * (ramp[i + 1][k] - ramp[i][k]);
}

typedef struct {
    const char *name;   /* for the files */
    const char *title;  /* for the table */
    meshgen_scene_t s;
    VECTOR3 eye, target;
} scene_t_;

static int write_maps(const char *dir, const scene_t_ *sc, accel_kind kind,
                      const image_t *counts, double cmax)
{
    char path[1024];
    svet_error err;
    snprintf(path, sizeof path, "%s/ch07_%s_%s_cells.pfm", dir, sc->name,
             accel_kind_name(kind));
    if (netpbm_write_pfm(path, counts, &err) != SVET_OK) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    image_t img;
    if (image_alloc(&img, W, H, 3, &err) != SVET_OK) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double c = (double)image_at(counts, x, y)[0];
            heat_colour(log1p(c) / log1p(cmax), image_at(&img, x, y));
        }
    snprintf(path, sizeof path, "%s/ch07_%s_%s_cells.ppm", dir, sc->name,
             accel_kind_name(kind));
    svet_status st = netpbm_write_ppm(path, &img, 8, &err);
    image_free(&img);
    if (st != SVET_OK) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    printf("  wrote %s (and .pfm)\n", path);

    char name[256];
    snprintf(name, sizeof name, "ch07_%s_%s_cells.csv", sc->name,
             accel_kind_name(kind));
    chapter_file_t cf;
    FILE *f = chapter_open(&cf, "ch07", dir, name);
    if (!f)
        return 1;
    fprintf(f, "# ch07: cells visited by the camera ray of each pixel, %s, "
               "%s; %d rows of %d, the top row first; largest count of the "
               "scene %.0f\n", sc->title, accel_kind_name(kind), H, W, cmax);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            fprintf(f, "%.0f%c", (double)image_at(counts, x, y)[0],
                    x + 1 < W ? ',' : '\n');
    return chapter_close(&cf, "ch07");
}

static double seconds(void)
{
    return (double)clock() / CLOCKS_PER_SEC;
}

static int run_scene(const char *dir, scene_t_ *sc)
{
    svet_error err;
    camera_t cam = { 0 }; /* gcc -flto takes it for unset after a failed init */
    VECTOR3 up = { 0, 0, 1 };
    if (camera_init(&cam, sc->eye, sc->target, up, 40, CAMERA_FOV_X, W, H,
                    &err) != SVET_OK) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    image_t counts[2];
    double cmax = 1;
    printf("\n%s: %ld triangles in %d objects\n\n", sc->title, sc->s.ntris,
           sc->s.nobjs);
    printf("| structure | build s | MB | cells | mean cells/ray | max | "
           "mean tests/ray | rays/s (1 thread) |\n");
    printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
    for (int k = 0; k < 2; k++) {
        accel_params_t p;
        accel_params_default(&p);
        p.structures = grid_accels;
        p.kind = k == 0 ? ACCEL_GRID : ACCEL_HGRID;
        accel_t *a;
        if (accel_build(&a, sc->s.objs, sc->s.nobjs, &p, &err) != SVET_OK ||
            image_alloc(&counts[k], W, H, 3, &err) != SVET_OK) {
            fprintf(stderr, "%s\n", err.msg);
            return 1;
        }
        accel_stats_t st;
        accel_get_stats(a, &st);
        double cells = 0, tests = 0, maxc = 0, t0 = seconds();
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                ray_t r;
                camera_ray(&cam, (real)x + REAL_C(0.5), (real)y + REAL_C(0.5),
                           &r);
                accel_counters_t c = { 0, 0 };
                accel_hit_t h;
                bool hit = accel_intersect_counted(a, &r, 0, (real)INFINITY,
                                                   &h, &c);
                float *px = image_at(&counts[k], x, y);
                px[0] = (float)c.cells;
                px[1] = (float)c.tests;
                px[2] = hit ? 1.0f : 0.0f;
                cells += (double)c.cells;
                tests += (double)c.tests;
                maxc = (double)c.cells > maxc ? (double)c.cells : maxc;
            }
        double dt = seconds() - t0;
        cmax = maxc > cmax ? maxc : cmax;
        printf("| %s | %.3f | %.1f | %ld | %.1f | %.0f | %.1f | %.0f |\n",
               accel_describe(a), st.build_seconds,
               (double)st.bytes / 1048576.0, st.cells, cells / (W * H), maxc,
               tests / (W * H), dt > 0 ? W * H / dt : 0.0);
        accel_free(a);
    }
    /* one scale for both maps of a scene, so they compare */
    int bad = 0;
    for (int k = 0; k < 2; k++) {
        bad |= write_maps(dir, sc, k == 0 ? ACCEL_GRID : ACCEL_HGRID,
                          &counts[k], cmax);
        image_free(&counts[k]);
    }
    return bad;
}

int main(int argc, char **argv)
{
    double width = W;
    const chapter_opt_t opts[] = {
        { "--width", "W", "image width; the height is 3 W / 4", &width, 4,
          4096 },
    };
    const chapter_cli_t cli = {
        "ch07",
        "Chapter 7: heat maps of the cells each camera ray visits in the "
        "uniform and the\nhierarchical grid, for two scenes of 1e5 "
        "triangles (PFM, PPM and CSV), and a\ntable of build time, memory "
        "and work per ray.",
        "out", opts, 1
    };
    const char *dir;
    int rc = chapter_begin(&cli, argc, argv, &dir);
    if (rc >= 0)
        return rc;
    W = (int)width;
    H = 3 * W / 4;
    svet_error err;
    scene_t_ sc[2];
    memset(sc, 0, sizeof sc);
    sc[0].name = "spheres";
    sc[0].title = "5 x 5 x 5 UV spheres";
    if (meshgen_sphere_grid(&sc[0].s, 5, 100000, &err) != SVET_OK) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    vec_set(sc[0].eye, 22, -16, 20);
    vec_set(sc[0].target, 6, 6, 6);
    sc[1].name = "stadium";
    sc[1].title = "the teapot in a stadium";
    if (meshgen_teapot_stadium(&sc[1].s, 100000, &err) != SVET_OK) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    vec_set(sc[1].eye, 4, -6, 3);
    vec_set(sc[1].target, 0, 0, 1);
    printf("ch07: cells visited per camera ray, %d x %d, uniform grid "
           "(grid) and hierarchical grid (hgrid)\n", W, H);
    int bad = 0;
    for (int i = 0; i < 2 && !bad; i++)
        bad = run_scene(dir, &sc[i]);
    for (int i = 0; i < 2; i++)
        meshgen_free_objects(&sc[i].s);
    return bad;
}
