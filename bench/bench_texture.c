/*
 * bench_texture.c - `make bench-texture`: millions of evaluations a second,
 * on one thread, of Perlin's improved noise (ch. 10; texture/noise.h) with
 * and without its gradient and as a 6-octave fractal sum, and of app. L's
 * lookups in a 64^3 grid (texture/interp.h), and of lookups in a
 * 1024 x 1024 RGB mip map by each filter (texture/mipmap.h). The points are drawn before
 * timing; each figure is the best of several runs of at least 0.2 s.
 * Then the renderer's cost of textures: one scene rendered untextured,
 * with a marble rho, and with the marble and a bump map (texpart.c), in
 * camera samples per CPU-second of one thread, the best of several; and an
 * image texture on the plane seen directly and in a mirror sphere, whose
 * lookups take their footprint from the ray differentials carried
 * through the mirror (raydiff.c).
 * Prints a Markdown table, also written to bench/results/texture.md (or
 * the path given as argv[1]).
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "bench.h"

#include "core/rng.h"
#include "render/allparts.h"
#include "render/render.h"
#include "render/scenefile.h"
#include "texture/interp.h"
#include "texture/mipmap.h"
#include "texture/noise.h"

#include <string.h>

#define NPTS 65536
#define GRID 64

static VECTOR3 pts[NPTS];
static float grid_v[GRID * GRID * GRID];
static interp_grid_t grid = { GRID, GRID, GRID, grid_v };
static volatile double sink;
static mipmap_t mip;
static real footprint[NPTS];

typedef double (*kernel_fn)(void);

/* the render rows' image: the shipped 64 x 64 grid, repeated 4 times over
 * the plane's unit (s, t) square; read from the top directory */
#define IMAGE_TEXTURE                                                       \
    "texture g image file scenes/textures/grid.png filter trilinear scale 4"

static double k_noise(void)
{
    real s = 0;
    for (int i = 0; i < NPTS; i++)
        s += noise_perlin(pts[i]);
    return (double)s;
}

static double k_noise_grad(void)
{
    real s = 0;
    for (int i = 0; i < NPTS; i++) {
        VECTOR3 g;
        s += noise_perlin_grad(pts[i], g) + g[X];
    }
    return (double)s;
}

static double k_fractal(void)
{
    noise_octaves_t o = noise_octaves_default();
    real s = 0;
    for (int i = 0; i < NPTS; i++)
        s += noise_fractal(pts[i], &o, NULL);
    return (double)s;
}

#define INTERP_KERNEL(name, fn)                                             \
    static double name(void)                                                \
    {                                                                       \
        real s = 0;                                                         \
        for (int i = 0; i < NPTS; i++)                                      \
            s += fn(&grid, pts[i]);                                         \
        return (double)s;                                                   \
    }
INTERP_KERNEL(k_nearest, interp_nearest)
INTERP_KERNEL(k_trilinear, interp_trilinear)
INTERP_KERNEL(k_parabolic, interp_parabolic)
INTERP_KERNEL(k_blend, interp_parabolic_blend)

#define MIP_KERNEL(name, filter)                                            \
    static double name(void)                                                \
    {                                                                       \
        real s = 0, c[3];                                                   \
        for (int i = 0; i < NPTS; i++) {                                    \
            mipmap_lookup(&mip, filter, pts[i][X] / GRID, pts[i][Y] / GRID, \
                          footprint[i], c);                                 \
            s += c[0];                                                      \
        }                                                                   \
        return (double)s;                                                   \
    }
MIP_KERNEL(k_mip_nearest, MIPMAP_NEAREST)
MIP_KERNEL(k_mip_bilinear, MIPMAP_BILINEAR)
MIP_KERNEL(k_mip_trilinear, MIPMAP_TRILINEAR)

/* millions of calls per CPU-second of this thread (a shared machine
 * disturbs that less than the wall clock): best of runs of >= 0.2 s */
static double rate(kernel_fn k)
{
    double start = bench_cpu_now(), best = 1e300;
    int runs = 0;
    while (runs < 3 || bench_cpu_now() - start < 1) {
        double t0 = bench_cpu_now();
        long reps = 0;
        do {
            sink = k();
            reps++;
        } while (bench_cpu_now() - t0 < 0.2);
        double per = (bench_cpu_now() - t0) / (double)reps;
        best = per < best ? per : best;
        runs++;
    }
    return NPTS / best / 1e6;
}

/* The scene of the render rows: a sphere on a plane under a point light;
 * `mat` is the plane's material and the sphere's, unless `sphere` gives
 * the sphere one of its own. */
static const char *scene_with(const char *textures, const char *mat,
                              const char *sphere)
{
    static char text[2048];
    snprintf(text, sizeof text,
             "camera position 0 1 4 target 0 0 0 width 160 height 120\n"
             "render spp 8 maxdepth 4 seed 1 threads 1\n"
             "light point position 2 3 3 intensity 20\n"
             "%s\nmaterial m %s\nmaterial s %s\n"
             "sphere centre 0 0 0 radius 1 material s\n"
             "plane point 0 -1 0 normal 0 1 0 material m\n",
             textures, mat, sphere ? sphere : mat);
    return text;
}

/* Camera samples per CPU-second of one thread: the best of at least five
 * renders and 2 CPU-seconds of them, so that a render slowed by the other
 * jobs of a shared machine (their cache traffic) is outrun by another. */
static double render_rate(const char *text)
{
    scene_t s;
    svet_error e;
    if (scenefile_parse_with(&s, text, strlen(text), "bench.scn", NULL,
                             scene_features_all(), &e) != SVET_OK) {
        fprintf(stderr, "bench_texture: %s\n", e.msg);
        return 0;
    }
    double best = 1e300, start = bench_cpu_now();
    for (int run = 0; run < 5 || bench_cpu_now() - start < 2; run++) {
        render_t r;
        if (render_init(&r, &s, &e) != SVET_OK) {
            fprintf(stderr, "bench_texture: %s\n", e.msg);
            break;
        }
        double t0 = bench_cpu_now();
        render_pass(&r, s.render.spp, 1, NULL, NULL);
        double t = bench_cpu_now() - t0;
        best = t < best ? t : best;
        render_free(&r);
    }
    double n = (double)s.camera.width * (double)s.camera.height *
               (double)s.render.spp;
    scene_free(&s);
    return best < 1e300 ? n / best : 0;
}

int main(int argc, char **argv)
{
    const char *out = argc > 1 ? argv[1] : "bench/results/texture.md";
    pcg32_t g;
    pcg32_seed(&g, 7, 7);
    for (int i = 0; i < NPTS; i++)
        for (int k = 0; k < 3; k++)
            pts[i][k] = (GRID - 1) * pcg32_real(&g);
    for (int i = 0; i < GRID * GRID * GRID; i++)
        grid_v[i] = (float)pcg32_real(&g);
    /* footprints of 1/4 to 64 texels, as camera rays over a plane */
    for (int i = 0; i < NPTS; i++)
        footprint[i] = exp2(8 * pcg32_real(&g) - 2) / 1024;
    float *tex = malloc(sizeof *tex * 1024 * 1024 * 3);
    if (!tex)
        return 1;
    for (int i = 0; i < 1024 * 1024 * 3; i++)
        tex[i] = (float)pcg32_real(&g);
    svet_error e;
    if (mipmap_build(&mip, tex, 1024, 1024, 3, MIPMAP_REPEAT, &e) != SVET_OK) {
        fprintf(stderr, "bench_texture: %s\n", e.msg);
        return 1;
    }
    free(tex);

    static const struct {
        const char *what;
        kernel_fn k;
    } rows[] = {
        { "improved noise (Perlin 2002)", k_noise },
        { "improved noise and its gradient", k_noise_grad },
        { "fractal sum, 6 octaves", k_fractal },
        { "grid lookup, nearest sample", k_nearest },
        { "grid lookup, trilinear (app. L)", k_trilinear },
        { "grid lookup, parabolic (app. L)", k_parabolic },
        { "grid lookup, parabolic blending (Overhauser)", k_blend },
        { "mip map lookup, nearest texel, RGB", k_mip_nearest },
        { "mip map lookup, bilinear, RGB", k_mip_bilinear },
        { "mip map lookup, trilinear, RGB", k_mip_trilinear },
    };
    char path[1100], load[160];
    snprintf(path, sizeof path, "%s.tmp", out);
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        return 1;
    }
    time_t now = time(NULL);
    char date[32];
    strftime(date, sizeof date, "%Y-%m-%d", gmtime(&now));
    fprintf(f, "# Textures: noise and grid lookups\n\n"
               "`make bench-texture` (bench/bench_texture.c), one thread, per "
               "CPU-second, "
               "real = " REAL_NAME ", %s.\n", date);
    bench_print_machine(f);
    fprintf(f, "; %s.\n\n| what | million calls per CPU-second |\n|---|---:|\n",
            bench_load_words(load, sizeof load));
    double noise_rate = 0;
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        double r = rate(rows[i].k);
        if (i == 0)
            noise_rate = r;
        fprintf(f, "| %s | %.1f |\n", rows[i].what, r);
        printf("%-46s %8.1f M/s\n", rows[i].what, r);
        fflush(stdout);
    }
    static const struct {
        const char *what, *textures, *mat, *sphere;
    } renders[] = {
        { "untextured: lambert rho 0.5 + phong rho 0.3 e 20", "",
          "lambert rho 0.5 + phong rho 0.3 e 20", NULL },
        { "marble rho (a per-hit material)", "texture t marble",
          "lambert rho t + phong rho 0.3 e 20", NULL },
        { "marble rho and a bump of waves", "texture t marble\n"
          "texture w waves", "lambert rho t + phong rho 0.3 e 20 + "
          "bump w strength 0.02", NULL },
        { "a bump of fBm noise alone (its analytic gradient)",
          "texture w fbm scale 4", "lambert rho 0.5 + phong rho 0.3 e 20 + "
          "bump w strength 0.05", NULL },
        { "an image rho, trilinear (the camera's ray differentials)",
          IMAGE_TEXTURE, "lambert rho g + phong rho 0.3 e 20", NULL },
        { "untextured plane, a mirror sphere (rho 0.9)", "",
          "lambert rho 0.5 + phong rho 0.3 e 20", "mirror rho 0.9" },
        { "the image on the plane, a mirror sphere (differentials through "
          "the mirror)", IMAGE_TEXTURE, "lambert rho g + phong rho 0.3 e 20",
          "mirror rho 0.9" },
    };
    fprintf(f, "\nImproved noise: %.1f million values per CPU-second of "
               "one core, %s 30 million (on a shared machine the rate falls "
               "with the load).\n", noise_rate,
            noise_rate >= 30 ? "above" : "below");
    fprintf(f, "\nThe renderer: a sphere on a plane, 160 x 120, 8 spp, up to "
               "4 bounces, one thread, the best of at least five renders and 2 "
               "CPU-s; the image is "
               "scenes/textures/grid.png.\n\n"
               "| scene | camera samples per CPU-second | against untextured "
               "|\n|---|---:|---:|\n");
    double base = 0;
    for (size_t i = 0; i < sizeof renders / sizeof renders[0]; i++) {
        double r = render_rate(scene_with(renders[i].textures,
                                          renders[i].mat, renders[i].sphere));
        if (i == 0)
            base = r;
        fprintf(f, "| %s | %.3g | %.2f |\n", renders[i].what, r,
                base > 0 ? r / base : 0);
        printf("%-52s %10.3g samples/s\n", renders[i].what, r);
        fflush(stdout);
    }
    if (fclose(f) != 0 || rename(path, out) != 0) {
        perror(out);
        return 1;
    }
    mipmap_free(&mip);
    printf("written to %s\n", out);
    return 0;
}
