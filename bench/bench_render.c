/*
 * bench_render.c - `make bench-render`: the Cornell box (scenes/cbox.scn) at
 * 256 x 256 in camera samples per second and rays per second at 1 and 2
 * threads, and its RMSE at 16, 64 and 256 spp against a converged render
 * (ch. 5). The converged render is tests/reference/cbox.exr when it exists
 * (make reference; the RMSE series is then rendered at its resolution),
 * else one rendered here at REF_SPP samples per pixel and kept in
 * out/bench/cbox-ref.exr for the next run. Beside wall-clock rates it
 * prints samples per CPU-second (process CPU time, all threads), which a
 * machine shared with other work disturbs much less. Each speed row is
 * the median of five runs.
 * usage: bench_render [scene] [ref_spp]
 */
#include "bench.h"
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "io/exrio.h"
#include "stats/imgcompare.h"
#include "render/render.h"
#include "render/allparts.h"
#include "render/scenefile.h"

static void die(const char *what, const svet_error *e)
{
    fprintf(stderr, "bench_render: %s: %s\n", what, e->msg);
    exit(1);
}

/* Render s at spp with threads; the image in *img (if not NULL); wall
 * and CPU seconds. */
static void run_cpu(const scene_t *s, long spp, int threads, image_t *img,
                    double *secs, double *cpu, double *rays)
{
    svet_error e;
    render_t r;
    if (render_init(&r, s, &e) != SVET_OK)
        die("render_init", &e);
    double t0 = bench_now(), c0 = bench_cpu_now();
    render_pass(&r, spp, threads, NULL, NULL);
    *secs = bench_now() - t0;
    *cpu = bench_cpu_now() - c0;
    *rays = (double)r.stats.rays;
    if (img && render_image(&r, img, &e) != SVET_OK)
        die("render_image", &e);
    render_free(&r);
}

static void run(const scene_t *s, long spp, int threads, image_t *img,
                double *secs, double *rays)
{
    double cpu;
    run_cpu(s, spp, threads, img, secs, &cpu, rays);
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "scenes/cbox.scn";
    long ref_spp = 4096;
    if (argc > 2) {
        char *end;
        errno = 0;
        ref_spp = strtol(argv[2], &end, 10);
        if (errno || end == argv[2] || *end || ref_spp < 1)
            ref_spp = 0;
    }
    if (argc > 3 || ref_spp < 1) {
        fprintf(stderr, "usage: bench_render [scene] [ref_spp >= 1]\n");
        return 2;
    }
    svet_error e;
    scene_t s;
    scene_init(&s);
    if (scenefile_read_with(&s, path, scene_features_all(), &e) != SVET_OK)
        die(path, &e);
    char cpu[256], date[64];
    bench_cpu_model(cpu, sizeof cpu);
    long px = (long)s.camera.width * s.camera.height;

    printf("## Rendering: %s (%dx%d, max depth %d, %s)\n\n", path,
           s.camera.width, s.camera.height, s.render.max_depth, REAL_NAME);
    printf("Machine: %s, %d cores; compiler %s; command `make bench-render`; "
           "date %s.\n\n", cpu, (int)sysconf(_SC_NPROCESSORS_ONLN),
           __VERSION__, bench_date(date, sizeof date));
    printf("| threads | spp | seconds | camera samples/s | rays/s | "
           "CPU seconds | samples per CPU-second |\n");
    printf("|---:|---:|---:|---:|---:|---:|---:|\n");
    /* Each speed row is the median of SPEED_RUNS runs by wall clock (one
     * run of 16 spp takes half a second, short enough for the machine's
     * other work to show); the range of all runs follows the table. */
    const long spp_speed = 16;
    enum { SPEED_RUNS = 5 };
    double lo[3], hi[3];
    for (int t = 1; t <= 2; t++) {
        double secs[SPEED_RUNS], cpu_secs[SPEED_RUNS], rays[SPEED_RUNS];
        int order[SPEED_RUNS];
        for (int k = 0; k < SPEED_RUNS; k++) {
            run_cpu(&s, spp_speed, t, NULL, &secs[k], &cpu_secs[k], &rays[k]);
            /* insertion by wall-clock seconds */
            int j = k;
            while (j > 0 && secs[order[j - 1]] > secs[k]) {
                order[j] = order[j - 1];
                j--;
            }
            order[j] = k;
        }
        int m = order[SPEED_RUNS / 2];
        lo[t] = (double)(px * spp_speed) / secs[order[SPEED_RUNS - 1]];
        hi[t] = (double)(px * spp_speed) / secs[order[0]];
        printf("| %d | %ld | %.2f | %.3g | %.3g | %.2f | %.3g |\n", t,
               spp_speed, secs[m], (double)(px * spp_speed) / secs[m],
               rays[m] / secs[m], cpu_secs[m],
               (double)(px * spp_speed) / cpu_secs[m]);
        fflush(stdout);
    }
    printf("\nEach row: the median of %d runs by wall clock; camera samples "
           "per second over all runs: 1 thread %.3g to %.3g, 2 threads %.3g "
           "to %.3g.\n", SPEED_RUNS, lo[1], hi[1], lo[2], hi[2]);

    /* the converged reference */
    image_t ref;
    const char *refpath = "tests/reference/cbox.exr";
    char cached[] = "out/bench/cbox-ref.exr";
    double ref_secs = 0;
    if (strcmp(path, "scenes/cbox.scn") == 0 && exrio_read(refpath, &ref, &e) == SVET_OK) {
        printf("\nReference: %s (%dx%d).\n", refpath, ref.width,
               ref.height);
        if (ref.width != s.camera.width || ref.height != s.camera.height) {
            /* the same view at the reference's resolution */
            s.camera.width = ref.width;
            s.camera.height = ref.height;
            printf("The RMSE series below is rendered at %dx%d to match "
                   "it.\n", ref.width, ref.height);
        }
    } else if (exrio_read(cached, &ref, &e) == SVET_OK) {
        printf("\nReference: %s (from an earlier run).\n", cached);
    } else {
        double rays;
        run(&s, ref_spp, 0, &ref, &ref_secs, &rays);
        mkdir("out", 0777);
        mkdir("out/bench", 0777);
        if (exrio_write(cached, &ref, EXRIO_FLOAT, EXRIO_ZIP, &e) != SVET_OK)
            fprintf(stderr, "bench_render: %s\n", e.msg);
        printf("\nReference: %ld spp rendered here in %.1f s (kept in %s).\n",
               ref_spp, ref_secs, cached);
    }
    printf("\n| spp | seconds (2 threads) | RMSE | relMSE | RMSE x sqrt(spp) |\n");
    printf("|---:|---:|---:|---:|---:|\n");
    const long spps[3] = { 16, 64, 256 };
    for (int i = 0; i < 3; i++) {
        image_t img;
        double secs, rays;
        /* a seed other than the reference's, so the errors are independent */
        s.render.seed += 1000;
        run(&s, spps[i], 2, &img, &secs, &rays);
        imgcompare_t c;
        if (imgcompare(&img, &ref, 0, IMGCOMPARE_EPS, &c, &e) != SVET_OK)
            die("imgcompare", &e);
        printf("| %ld | %.2f | %.5f | %.5f | %.4f |\n", spps[i], secs, c.rmse,
               c.relmse, c.rmse * sqrt((double)spps[i]));
        fflush(stdout);
        image_free(&img);
    }
    printf("\nRMSE x sqrt(spp) stays constant when the error falls as "
           "1/sqrt(spp) (no bias).\n");
    image_free(&ref);
    scene_free(&s);
    return 0;
}
