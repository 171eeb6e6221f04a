/*
 * bench_grid.c - ch. 7's benchmark: build time, memory and rays per second
 * of brute force (small scenes only), the uniform grid and the
 * hierarchical grid, for coherent camera rays and incoherent random rays
 * (origins uniform in the scene's box, directions uniform on the sphere),
 * at 1 and 2 threads, on 5 x 5 x 5 UV spheres of 1e3 ... 1e6 triangles, the
 * teapot in a stadium, and any OBJ file given; then how each cost grows
 * with N. Markdown on stdout (bench/results/grid.md).
 *   make bench-grid                       the tables
 *   make bench-grid BENCH_ARGS=file.obj   the same for an OBJ file
 *   make bench-grid BENCH_ARGS=--tune     the sweep that chose k
 *   make bench-grid BENCH_ARGS=--quick    a smoke run
 *   make bench-grid BENCH_ARGS="--only 1000000"   one sphere size only
 *   make bench-grid BENCH_ARGS="--only stadium"   the teapot in a stadium
 *   make bench-grid BENCH_ARGS=--render   the renderer on the 1e6
 *       spheres (render.h; --only SIZE for another size): camera rays in
 *       packets against one at a time, for three integrators, and whether
 *       the images are the same
 *   bench_grid --trace camera|packets4|packets8|incoherent [--passes N]
 *       one kind of ray at 1e6 through grid.h alone, N passes (best
 *       reported): the figures of `make count-grid` (tools/count-grid.sh
 *       counts trace_pass() under callgrind) and of back-to-back timings
 * Camera rays are traced one at a time through accel.h (as the renderer
 * traces them), and in packets of 4 x 4 and 8 x 8 pixels through
 * grid_intersect_packet() (grid.h) on a grid built over the same scene.
 */
#include "accel/accel.h"
#include "bench.h"
#include "render/camera.h"
#include "accel/grid.h"
#include "mesh/mesh.h"
#include "mesh/meshgen.h"
#include "mesh/obj.h"
#include "render/allparts.h"
#include "materials/material.h"
#include "accel/primset.h"
#include "render/render.h"
#include "core/rng.h"

#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int g_cam = 512;    /* camera image side */
static long g_rays = 1L << 18; /* incoherent rays */

/* --- rays ------------------------------------------------------------------ */

/* The rays of camera.h's pinhole camera at eye looking at target (up +z,
 * horizontal field of view fov degrees) through the n x n pixel centres,
 * tile by tile (16 x 16 pixels, the renderer's order: render.h
 * RENDER_TILE), rows within a tile. */
static ray_t *camera_rays(const VECTOR3 eye, const VECTOR3 target, double fov,
                          int n)
{
    ray_t *r = malloc((size_t)n * n * sizeof *r);
    camera_t cam;
    VECTOR3 up = { 0, 0, 1 };
    svet_error e;
    if (!r || camera_init(&cam, eye, target, up, (real)fov, CAMERA_FOV_X, n,
                          n, &e) != SVET_OK) {
        fprintf(stderr, "camera: %s\n", r ? e.msg : "out of memory");
        exit(1);
    }
    size_t k = 0;
    for (int ty = 0; ty < n; ty += 16)
        for (int tx = 0; tx < n; tx += 16)
            for (int j = ty; j < ty + 16 && j < n; j++)
                for (int i = tx; i < tx + 16 && i < n; i++)
                    camera_ray(&cam, (real)i + REAL_C(0.5),
                               (real)j + REAL_C(0.5), &r[k++]);
    return r;
}

static ray_t *random_rays(const bbox_t *b, long n, uint64_t seed)
{
    ray_t *r = malloc((size_t)n * sizeof *r);
    pcg32_t g;
    pcg32_seed(&g, seed, 99);
    for (long i = 0; i < n; i++) {
        for (int k = 0; k < 3; k++)
            r[i].o[k] = b->min[k] + (b->max[k] - b->min[k]) * pcg32_real(&g);
        real z = 1 - 2 * pcg32_real(&g), phi = 2 * REAL_PI * pcg32_real(&g);
        real s = sqrt(fmax(REAL_C(0.0), 1 - z * z));
        vec_set(r[i].d, s * cos(phi), s * sin(phi), z);
    }
    return r;
}

/* --- measuring ----------------------------------------------------------- */

typedef struct {
    double wall, cpu; /* seconds */
    long rays, hits;  /* rays traced (a time budget may stop early) */
} run_t;

/* Seconds one measurement may take: a structure that is hopeless for a
 * scene (the uniform grid's teapot) is timed on the rays it got through. */
#define TRACE_BUDGET 2.0

/* Seconds of passes one measurement aims at, and the most passes: a pass
 * over the rays (a camera image at 1e6 takes 0.05 s) is repeated until
 * that much time has passed, and the median pass is reported, so that one
 * slow pass (the first, colder; a moment of another job's) does not
 * decide the figure. */
#define TRACE_REPEAT 1.0
#define TRACE_PASSES 15

/* Run chunk(ctx, from, to, threads) over [0, n) in chunks of 8192 rays
 * until done or out of the time budget; chunk returns its hits. */
typedef long (*chunk_fn)(const void *ctx, long from, long to, int threads);

static run_t one_pass(long n, int threads, chunk_fn chunk, const void *ctx)
{
    run_t out;
    long hits = 0, done = 0;
    double t0 = bench_now(), c0 = bench_cpu_now();
    while (done < n) {
        long m = n - done < 8192 ? n - done : 8192;
        hits += chunk(ctx, done, done + m, threads);
        done += m;
        if (bench_now() - t0 > TRACE_BUDGET)
            break;
    }
    out.wall = bench_now() - t0;
    out.cpu = bench_cpu_now() - c0;
    out.rays = done;
    out.hits = hits;
    return out;
}

static int by_rate(const void *a, const void *b)
{
    const run_t *x = a, *y = b;
    double rx = (double)x->rays / x->wall, ry = (double)y->rays / y->wall;
    return (rx > ry) - (rx < ry);
}

/* Passes of one_pass() for about TRACE_REPEAT seconds (one, when a pass
 * does not finish within the budget): the median pass by wall clock (of
 * an even number, the slower middle one), whose CPU time goes with it. */
static run_t timed(long n, int threads, chunk_fn chunk, const void *ctx)
{
    run_t runs[TRACE_PASSES];
    int k = 0;
    double t0 = bench_now();
    do
        runs[k++] = one_pass(n, threads, chunk, ctx);
    while (k < TRACE_PASSES && runs[k - 1].rays == n &&
           bench_now() - t0 < TRACE_REPEAT);
    qsort(runs, (size_t)k, sizeof *runs, by_rate);
    return runs[(k - 1) / 2];
}

typedef struct {
    const accel_t *a;
    const ray_t *r;
} single_t;

static long single_chunk(const void *ctx, long from, long to, int threads)
{
    const single_t *c = ctx;
    long hits = 0;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 256) \
    reduction(+ : hits)
    for (long i = from; i < to; i++) {
        accel_hit_t h;
        hits += accel_intersect(c->a, &c->r[i], 0, (real)INFINITY, &h);
    }
    return hits;
}

static run_t trace(const accel_t *a, const ray_t *r, long n, int threads)
{
    single_t c = { a, r };
    return timed(n, threads, single_chunk, &c);
}

/* The camera rays' numbers in packets of pw x ph pixels, packet after
 * packet, within the 16 x 16 tiles of camera_rays() (rows of 16 within a
 * tile): n must be a whole number of tiles. */
static long *packet_order(long n, int pw, int ph)
{
    long *ix = malloc((size_t)n * sizeof *ix), k = 0;
    if (!ix) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    for (long t = 0; t < n; t += 256)
        for (int py = 0; py < 16; py += ph)
            for (int px = 0; px < 16; px += pw)
                for (int j = py; j < py + ph; j++)
                    for (int i = px; i < px + pw; i++)
                        ix[k++] = t + 16 * j + i;
    return ix;
}

typedef struct {
    const grid_t *g;
    const ray_t *r;
    const long *ix;
    int m;
} packets_t;

/* Packets of m rays (the rays r[ix[..]]): from and to are multiples of
 * m, as 8192 is. */
static long packet_chunk(const void *ctx, long from, long to, int threads)
{
    const packets_t *c = ctx;
    long hits = 0;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 4) \
    reduction(+ : hits)
    for (long i = from; i < to; i += c->m) {
        primset_query_t q[GRID_PACKET_MAX];
        int k = (int)(to - i < c->m ? to - i : c->m);
        for (int j = 0; j < k; j++)
            primset_query_init(&q[j], &c->r[c->ix[i + j]], 0,
                               (real)INFINITY);
        grid_intersect_packet(c->g, q, k);
        for (int j = 0; j < k; j++)
            hits += primset_query_finish(c->g->ps, &q[j]) != NULL;
    }
    return hits;
}

/* trace() for packets of m rays (the rays r[ix[..]]) through
 * grid_intersect_packet(). */
static run_t trace_packets(const grid_t *g, const ray_t *r, const long *ix,
                           long n, int m, int threads)
{
    packets_t c = { g, r, ix, m };
    return timed(n, threads, packet_chunk, &c);
}

static void per_ray(const accel_t *a, const ray_t *r, long n, double *cells,
                    double *tests)
{
    accel_counters_t c = { 0, 0 };
    long m = n < 20000 ? n : 20000, i;
    double t0 = bench_now();
    for (i = 0; i < m && (i % 256 || bench_now() - t0 < TRACE_BUDGET); i++) {
        accel_hit_t h;
        accel_intersect_counted(a, &r[i * (n / m)], 0, (real)INFINITY, &h, &c);
    }
    m = i;
    *cells = (double)c.cells / (double)m;
    *tests = (double)c.tests / (double)m;
}

typedef struct {
    const char *scene;
    long tris;
    accel_kind kind;
    double build, mb;
    double cells_cam, cells_inc, tests_inc;
    double cam[2], inc[2];  /* Mrays/s by wall clock, 1 and 2 threads */
    double cam_cpu, inc_cpu; /* Mrays per CPU second at 1 thread */
    double pk[2][2];         /* camera rays in packets of 4 x 4 and 8 x 8
                                pixels, Mrays/s by wall clock, 1 and 2
                                threads */
    double pk_cpu[2];        /* per CPU second at 1 thread: 4x4, 8x8 */
} row_t;

static row_t rows[64];
static int nrows;

static void print_header(void)
{
    printf("| scene | triangles | structure | build CPU s | MB | cells/ray "
           "(cam, inc) | tests/ray inc | camera Mrays/s 1T | 2T | "
           "incoherent Mrays/s 1T | 2T | 1T per CPU-s (cam, inc) | "
           "camera, packets of 16 (4x4) Mrays/s 1T | 2T | packets of 64 "
           "(8x8) 1T | 2T | packets 1T per CPU-s (16, 64) |\n");
    printf("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
           "---:|---:|---:|---:|\n");
}

static void print_row(const row_t *r)
{
    printf("| %s | %ld | %s | %.3f | %.1f | %.1f, %.1f | %.1f | %.3f | %.3f "
           "| %.3f | %.3f | %.3f, %.3f |",
           r->scene, r->tris, accel_kind_name(r->kind), r->build, r->mb,
           r->cells_cam, r->cells_inc, r->tests_inc, r->cam[0], r->cam[1],
           r->inc[0], r->inc[1], r->cam_cpu, r->inc_cpu);
    if (r->kind == ACCEL_BRUTE)
        printf(" - | - | - | - | - |\n");
    else
        printf(" %.3f | %.3f | %.3f | %.3f | %.3f, %.3f |\n", r->pk[0][0],
               r->pk[0][1], r->pk[1][0], r->pk[1][1], r->pk_cpu[0],
               r->pk_cpu[1]);
    fflush(stdout);
}

/* The packets' columns of r: a grid of kind (the parameters accel_build
 * gives it) over the same scene, traced by grid_intersect_packet(). */
static void bench_packets(row_t *r, COBJECT **objs, int n, accel_kind kind,
                          const accel_params_t *over, const ray_t *cam,
                          long ncam)
{
    primset_t ps;
    grid_params_t gp;
    grid_t *g;
    svet_error e;
    if (kind == ACCEL_HGRID)
        grid_params_hierarchical(&gp);
    else
        grid_params_uniform(&gp);
    if (over && kind == ACCEL_GRID && over->grid_k > 0)
        gp.k = over->grid_k;
    if (primset_build(&ps, objs, n, &e) != SVET_OK ||
        grid_build(&g, &ps, &gp, &e) != SVET_OK) {
        fprintf(stderr, "packets: %s\n", e.msg);
        exit(1);
    }
    const int side[2] = { 4, 8 };
    for (int s = 0; s < 2; s++) {
        long *ix = packet_order(ncam, side[s], side[s]);
        for (int t = 0; t < 2; t++) {
            run_t c = trace_packets(g, cam, ix, ncam, side[s] * side[s],
                                    t + 1);
            r->pk[s][t] = (double)c.rays / c.wall * 1e-6;
            if (t == 0)
                r->pk_cpu[s] = (double)c.rays / c.cpu * 1e-6;
        }
        free(ix);
    }
    grid_free(g);
    primset_free(&ps);
}

/* Benchmark one structure on one scene; brute force traces a sample. */
static void bench_one(const char *name, COBJECT **objs, int n, long tris,
                      accel_kind kind, const accel_params_t *over,
                      const ray_t *cam, long ncam, const ray_t *inc,
                      long ninc)
{
    accel_params_t p;
    if (over)
        p = *over;
    else
        accel_params_default(&p);
    p.structures = grid_accels;
    p.kind = kind;
    accel_t *a;
    svet_error e;
    double c0 = bench_cpu_now();
    if (accel_build(&a, objs, n, &p, &e) != SVET_OK) {
        fprintf(stderr, "%s: %s\n", name, e.msg);
        exit(1);
    }
    double build_cpu = bench_cpu_now() - c0;
    accel_stats_t st;
    accel_get_stats(a, &st);
    row_t *r = &rows[nrows < 63 ? nrows++ : 63];
    memset(r, 0, sizeof *r);
    r->scene = name;
    r->tris = tris;
    r->kind = kind;
    r->build = build_cpu; /* one thread: CPU time is the work */
    r->mb = (double)st.bytes / 1048576.0;
    if (kind == ACCEL_BRUTE) { /* a sample: every ray costs N tests */
        long cap = 20000000 / (tris > 0 ? tris : 1) + 64;
        ncam = ncam < cap ? ncam : cap;
        ninc = ninc < cap ? ninc : cap;
    }
    per_ray(a, cam, ncam, &r->cells_cam, &r->tests_inc);
    per_ray(a, inc, ninc, &r->cells_inc, &r->tests_inc);
    for (int t = 0; t < 2; t++) {
        run_t c = trace(a, cam, ncam, t + 1), i = trace(a, inc, ninc, t + 1);
        r->cam[t] = (double)c.rays / c.wall * 1e-6;
        r->inc[t] = (double)i.rays / i.wall * 1e-6;
        if (t == 0) {
            r->cam_cpu = (double)c.rays / c.cpu * 1e-6;
            r->inc_cpu = (double)i.rays / i.cpu * 1e-6;
        }
    }
    accel_free(a);
    if (kind != ACCEL_BRUTE)
        bench_packets(r, objs, n, kind, over, cam, ncam);
    print_row(r);
}

static void scene_box(COBJECT **objs, int n, bbox_t *b)
{
    bbox_empty(b);
    for (int i = 0; i < n; i++) {
        bbox_t o;
        objs[i]->ops->bounds(objs[i], -1, &o);
        bbox_union(b, &o);
    }
}

/* Camera from the (1, -1.6, 1.2) side at 1.3 diagonals, 40 degrees. */
static void default_view(const bbox_t *b, VECTOR3 eye, VECTOR3 target)
{
    bbox_centroid(target, b);
    VECTOR3 d, dir = { 1, REAL_C(-1.6), REAL_C(1.2) };
    vec_sub(d, b->max, b->min);
    vec_normalize(dir, dir);
    vec_add_scaled(eye, target, REAL_C(1.3) * vec_length(d), dir);
}

static void bench_scene(const char *name, COBJECT **objs, int n, long tris,
                        bool brute, const VECTOR3 eye, const VECTOR3 target,
                        double fov)
{
    bbox_t b;
    scene_box(objs, n, &b);
    ray_t *cam = camera_rays(eye, target, fov, g_cam);
    ray_t *inc = random_rays(&b, g_rays, 7);
    long ncam = (long)g_cam * g_cam;
    if (brute)
        bench_one(name, objs, n, tris, ACCEL_BRUTE, NULL, cam, ncam, inc,
                  g_rays);
    bench_one(name, objs, n, tris, ACCEL_GRID, NULL, cam, ncam, inc, g_rays);
    bench_one(name, objs, n, tris, ACCEL_HGRID, NULL, cam, ncam, inc, g_rays);
    free(cam);
    free(inc);
}

/* The title, the machine, its load and the command. */
static void machine_head(int argc, char **argv)
{
    char load[160];
    printf("# Grid benchmark (ch. 7)\n\n- ");
    bench_print_machine(stdout);
    printf(", real = %s\n- at the start, %s\n", REAL_NAME,
           bench_load_words(load, sizeof load));
    printf("- command:");
    for (int i = 0; i < argc; i++)
        printf(" %s", argv[i]);
    printf("\n");
}

static void machine(int argc, char **argv)
{
    machine_head(argc, argv);
    printf("- rays: camera %d x %d (pinhole, 40 degrees, pixel centres, "
           "in 16 x 16 tiles as the renderer traces them), "
           "incoherent %ld (origins uniform in the scene's box, "
           "directions uniform on the sphere); brute force traces a "
           "sample\n",
           g_cam, g_cam, g_rays);
    printf("- Mrays/s by wall clock at 1 and 2 threads (OpenMP); \"per "
           "CPU-s\" divides by the process's CPU time instead, which a "
           "busy machine disturbs less; a measurement repeats its pass "
           "over the rays for about %g s (at most %d passes) and reports "
           "the median pass; a pass stops after %g s and counts the rays "
           "traced by then\n", TRACE_REPEAT, TRACE_PASSES, TRACE_BUDGET);
    printf("- camera rays in packets: the same rays, 4 x 4 or 8 x 8 pixels "
           "of a tile at a time, through grid_intersect_packet() on a grid "
           "of the same kind built over the same scene (grid.h directly: "
           "without accel.c's checks, which the single rays go through)\n");
    printf("- tests/ray counts the primitives the mailbox let through; "
           "%s\n\n",
           GRID_QUADS ? "where a grid has quads (grid.h: from "
                        "GRID_QUAD_MIN_DEFAULT mesh triangles on), only the "
                        "triangles their sign test (four lanes, eight "
                        "with AVX) kept"
                      : "this build has no quads");
}

/* How a cost grows with N: the exponent of a power law through the
 * 1e3 and 1e6 rows (cost ~ N^e). */
static void growth(void)
{
    printf("\n## How the costs grow with N (sphere grids, 1e3 to 1e6 "
           "triangles): cost ~ N^e, time per ray by CPU time at 1 "
           "thread\n\n");
    printf("| structure | build time e | memory e | incoherent time/ray e "
           "| camera time/ray e |\n|---|---:|---:|---:|---:|\n");
    for (int k = ACCEL_BRUTE; k <= ACCEL_HGRID; k++) {
        const row_t *lo = NULL, *hi = NULL;
        for (int i = 0; i < nrows; i++) {
            if (rows[i].kind != (accel_kind)k ||
                strncmp(rows[i].scene, "spheres", 7) != 0)
                continue;
            if (!lo || rows[i].tris < lo->tris)
                lo = &rows[i];
            if (!hi || rows[i].tris > hi->tris)
                hi = &rows[i];
        }
        if (!lo || !hi || lo == hi)
            continue;
        double l = log((double)hi->tris / (double)lo->tris);
        printf("| %s | %.2f | %.2f | %.2f | %.2f |\n",
               accel_kind_name((accel_kind)k),
               log(fmax(hi->build, 1e-6) / fmax(lo->build, 1e-6)) / l,
               log(hi->mb / lo->mb) / l,
               log(lo->inc_cpu / hi->inc_cpu) / l,
               log(lo->cam_cpu / hi->cam_cpu) / l);
    }
}

static COBJECT **sphere_scene(long n, meshgen_scene_t *s)
{
    svet_error e;
    if (meshgen_sphere_grid(s, 5, n, &e) != SVET_OK) {
        fprintf(stderr, "%s\n", e.msg);
        exit(1);
    }
    return s->objs;
}

/* The defaults with both grids offered, asking for one kind. */
static accel_params_t grid_params(accel_kind kind)
{
    accel_params_t p;
    accel_params_default(&p);
    p.structures = grid_accels;
    p.kind = kind;
    return p;
}

/* One row of the sweep: build with p, trace at one thread. */
static void tune_row(const meshgen_scene_t *s, const accel_params_t *p,
                     const ray_t *cam, long ncam, const ray_t *inc, long ninc)
{
    accel_t *a;
    svet_error e;
    if (accel_build(&a, s->objs, s->nobjs, p, &e) != SVET_OK) {
        fprintf(stderr, "%s\n", e.msg);
        exit(1);
    }
    accel_stats_t st;
    accel_get_stats(a, &st);
    run_t c = trace(a, cam, ncam, 1), n = trace(a, inc, ninc, 1);
    ncam = c.rays;
    ninc = n.rays;
    if (p->kind == ACCEL_GRID)
        printf("| %ld | grid | %g | | ", s->ntris, p->grid_k);
    else
        printf("| %ld | hgrid | %g | %g | %d ", s->ntris, p->hgrid_k,
               p->hgrid_child_k, p->hgrid_leaf);
    printf("| %.3f | %.1f | %.3f | %.3f |\n", st.build_seconds,
           (double)st.bytes / 1048576, (double)ncam / c.cpu * 1e-6,
           (double)ninc / n.cpu * 1e-6);
    fflush(stdout);
    accel_free(a);
}

/* The sweep behind GRID_K_DEFAULT and the hgrid defaults: camera and
 * incoherent rays at one thread, by CPU time, for several k. */
static void tune(void)
{
    printf("## Tuning k (1 thread, Mrays per CPU-second)\n\n");
    printf("| triangles | structure | k | child k | leaf | build s | MB | "
           "camera | incoherent |\n|---:|---|---:|---:|---:|---:|---:|---:|"
           "---:|\n");
    long sizes[] = { 10000, 100000, 1000000 };
    for (int si = 0; si < 3; si++) {
        meshgen_scene_t s;
        sphere_scene(sizes[si], &s);
        bbox_t b;
        scene_box(s.objs, s.nobjs, &b);
        VECTOR3 eye, target;
        default_view(&b, eye, target);
        ray_t *cam = camera_rays(eye, target, 40, 256);
        ray_t *inc = random_rays(&b, 1L << 16, 7);
        double ks[] = { 1, 1.5, 2, 2.5, 3, 4 };
        for (int i = 0; i < 6; i++) {
            accel_params_t p = grid_params(ACCEL_GRID);
            p.grid_k = ks[i];
            tune_row(&s, &p, cam, 256 * 256, inc, 1L << 16);
        }
        double hk[] = { 1, 2, 2.5 }, ck[] = { 1.5, 2 };
        int leaf[] = { 12, 32 };
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 2; j++)
                for (int l = 0; l < 2; l++) {
                    accel_params_t p = grid_params(ACCEL_HGRID);
                    p.hgrid_k = hk[i];
                    p.hgrid_child_k = ck[j];
                    p.hgrid_leaf = leaf[l];
                    tune_row(&s, &p, cam, 256 * 256, inc, 1L << 16);
                }
        free(cam);
        free(inc);
        meshgen_free_objects(&s);
    }
}

/* --- one kind of ray, for counting and back-to-back timing -------------- */

static int usage(const char *why, const char *arg);

/* One pass of `kind` over the n rays r (packets of m = side^2 rays in the
 * order ix when m > 1), as a caller of grid.h traces them: each query set
 * up, traced and finished. Kept out of line so that callgrind can count
 * it alone (tools/count-grid.sh). Returns the hits. */
#if defined(__GNUC__) || defined(__clang__)
__attribute__((noinline))
#endif
static long trace_pass(const grid_t *g, const ray_t *r, const long *ix,
                       long n, int m)
{
    long hits = 0;
    if (m <= 1) {
        for (long i = 0; i < n; i++) {
            primset_query_t q;
            primset_query_init(&q, &r[i], 0, (real)INFINITY);
            grid_intersect(g, &q);
            hits += primset_query_finish(g->ps, &q) != NULL;
        }
        return hits;
    }
    for (long i = 0; i < n; i += m) {
        primset_query_t q[GRID_PACKET_MAX];
        for (int j = 0; j < m; j++)
            primset_query_init(&q[j], &r[ix[i + j]], 0, (real)INFINITY);
        grid_intersect_packet(g, q, m);
        for (int j = 0; j < m; j++)
            hits += primset_query_finish(g->ps, &q[j]) != NULL;
    }
    return hits;
}

/* `bench_grid --trace KIND [--passes N]`: the 1e6 spheres' uniform grid
 * (grid.h directly, without accel.c), the benchmark's camera or
 * incoherent rays, N passes of one thread; prints the best pass. */
static int trace_only(const char *kind, int passes)
{
    int side = strcmp(kind, "camera") == 0       ? 1
               : strcmp(kind, "packets4") == 0   ? 4
               : strcmp(kind, "packets8") == 0   ? 8
               : strcmp(kind, "incoherent") == 0 ? 0
                                                 : -1;
    if (side < 0)
        return usage("--trace takes camera, packets4, packets8 or "
                     "incoherent", kind);
    meshgen_scene_t s;
    sphere_scene(1000000, &s);
    bbox_t b;
    scene_box(s.objs, s.nobjs, &b);
    VECTOR3 eye, target;
    default_view(&b, eye, target);
    long n = (long)g_cam * g_cam;
    ray_t *r = side ? camera_rays(eye, target, 40, g_cam)
                    : random_rays(&b, n, 7);
    long *ix = side > 1 ? packet_order(n, side, side) : NULL;
    primset_t ps;
    grid_params_t gp;
    grid_t *g;
    svet_error e;
    grid_params_uniform(&gp);
    if (primset_build(&ps, s.objs, s.nobjs, &e) != SVET_OK ||
        grid_build(&g, &ps, &gp, &e) != SVET_OK) {
        fprintf(stderr, "bench_grid: %s\n", e.msg);
        return 1;
    }
    double best = 0;
    long hits = 0;
    for (int p = 0; p < passes; p++) {
        double t0 = bench_now();
        hits = trace_pass(g, r, ix, n, side * side);
        double rate = (double)n / (bench_now() - t0) * 1e-6;
        best = rate > best ? rate : best;
    }
    printf("%s: %ld rays, %ld hits, best of %d passes %.3f Mrays/s\n", kind,
           n, hits, passes, best);
    grid_free(g);
    primset_free(&ps);
    free(ix);
    free(r);
    meshgen_free_objects(&s);
    return 0;
}

/* --- the renderer on the spheres (--render) ----------------------------- */

/* Passes of one sample per pixel each measurement takes (the median is
 * reported); the same number for packets and single rays, so that their
 * images can be compared at the end. */
#define RENDER_PASSES 3

/* The 5 x 5 x 5 spheres of ntris triangles as a scene for render.h: grey
 * diffuse (albedo 0.6), under a uniform sky of radiance 1, seen as the
 * camera rays of the tables see them (default_view, 40 degrees, g_cam
 * pixels a side); the integrator as asked. */
static long render_scene(scene_t *sc, long ntris, scene_integrator mode,
                         int max_depth)
{
    svet_error e;
    meshgen_scene_t m;
    sphere_scene(ntris, &m);
    scene_init(sc);
    sc->features = scene_features_all();
    material_params p;
    material_params_default(&p);
    p.rho_d = rad_grey(REAL_C(0.6));
    material_t *mat;
    if (material_new(&p, &mat, &e) != SVET_OK ||
        scene_add_anon_material(sc, mat, &e) != SVET_OK) {
        fprintf(stderr, "%s\n", e.msg);
        exit(1);
    }
    bbox_t b;
    scene_box(m.objs, m.nobjs, &b);
    for (int i = 0; i < m.nobjs; i++)
        if (scene_add_object(sc, m.objs[i], mat, &e) != SVET_OK) {
            fprintf(stderr, "%s\n", e.msg);
            exit(1);
        }
    free(m.objs); /* the objects are the scene's now */
    sc->has_environment = true;
    sc->environment = rad_grey(1);
    default_view(&b, sc->camera.position, sc->camera.target);
    vec_set(sc->camera.up, 0, 0, 1);
    sc->camera.fov = 40;
    sc->camera.width = sc->camera.height = g_cam;
    sc->render.integrator = mode;
    sc->render.max_depth = max_depth;
    sc->render.accel = SCENE_ACCEL_GRID;
    return m.ntris;
}

typedef struct {
    double wall[2], cpu[2]; /* median pass at 1 and 2 threads */
    double rays_per_sample;
} render_run_t;

/* RENDER_PASSES passes of one sample per pixel of each of the two renders
 * r[0], r[1], at 1, then 2 threads, alternating which goes first, so
 * that a drift of the machine's speed falls on both alike; each reports
 * its median pass by wall clock with that pass's CPU time, as timed()
 * does. */
static void render_runs(render_t *const r[2], render_run_t out[2])
{
    const long px = (long)g_cam * g_cam;
    for (int t = 0; t < 2; t++) {
        run_t runs[2][RENDER_PASSES];
        for (int k = 0; k < RENDER_PASSES; k++)
            for (int i = 0; i < 2; i++) {
                int j = (k + t) % 2 ? 1 - i : i;
                double t0 = bench_now(), c0 = bench_cpu_now();
                render_pass(r[j], r[j]->spp_done + 1, t + 1, NULL, NULL);
                runs[j][k].wall = bench_now() - t0;
                runs[j][k].cpu = bench_cpu_now() - c0;
                runs[j][k].rays = px; /* samples, for by_rate() */
                runs[j][k].hits = 0;
            }
        for (int j = 0; j < 2; j++) {
            qsort(runs[j], RENDER_PASSES, sizeof runs[j][0], by_rate);
            out[j].wall[t] = runs[j][(RENDER_PASSES - 1) / 2].wall;
            out[j].cpu[t] = runs[j][(RENDER_PASSES - 1) / 2].cpu;
        }
    }
    for (int j = 0; j < 2; j++)
        out[j].rays_per_sample = (double)r[j]->stats.rays /
                                 ((double)r[j]->spp_done * g_cam * g_cam);
}

static void render_row(const char *what, const char *how,
                       const render_run_t *u, const char *same)
{
    double n = (double)g_cam * g_cam / 1e6;
    printf("| %s | %s | %.2f | %.3f | %.3f | %.3f | %.3f | %s |\n", what, how,
           u->rays_per_sample, n / u->wall[0], n / u->wall[1],
           n / u->cpu[0], n * u->rays_per_sample / u->wall[0], same);
}

static int render_bench(bool quick, const char *only)
{
    const long ntris = only ? atol(only) : quick ? 10000 : 1000000;
    const struct {
        const char *name;
        scene_integrator mode;
        int depth;
    } modes[3] = {
        { "camera rays only (path, maxdepth 0)", SCENE_INTEGRATOR_PATH, 0 },
        { "ambient occlusion (one shadow ray)", SCENE_INTEGRATOR_AO, 0 },
        { "path tracing (maxdepth 3, sky light)", SCENE_INTEGRATOR_PATH, 3 },
    };
    bool head = false;
    int rc = 0;
    for (int m = 0; m < 3; m++) {
        scene_t sc;
        long tris = render_scene(&sc, ntris, modes[m].mode, modes[m].depth);
        if (!head) {
            printf("The renderer (render.h) on the 5 x 5 x 5 spheres of %ld "
                   "triangles, uniform grid, %d x %d pixels, one sample a "
                   "pixel a pass, the median of %d passes at each thread "
                   "count, the two renders' passes alternating; samples "
                   "in millions a second; \"same image\": the accumulated "
                   "sums, counts and rays of the %d samples a pixel "
                   "compared byte for byte with the render one ray at a "
                   "time\n\n",
                   tris, g_cam, g_cam, RENDER_PASSES, 2 * RENDER_PASSES);
            printf("| integrator | camera rays | rays/sample | Msamples/s 1T "
                   "| 2T | 1T per CPU-s | Mrays/s 1T | same image |\n"
                   "|---|---|---:|---:|---:|---:|---:|---|\n");
            head = true;
        }
        render_t one, pk;
        svet_error e;
        if (render_init(&one, &sc, &e) != SVET_OK) {
            fprintf(stderr, "%s\n", e.msg);
            scene_free(&sc);
            return 1;
        }
        if (render_init(&pk, &sc, &e) != SVET_OK) {
            fprintf(stderr, "%s\n", e.msg);
            render_free(&one);
            scene_free(&sc);
            return 1;
        }
        one.packets = false;
        render_t *const both[2] = { &one, &pk };
        render_run_t u[2];
        render_runs(both, u);
        render_run_t *u1 = &u[0], *u2 = &u[1];
        size_t n = (size_t)g_cam * (size_t)g_cam;
        bool same = pk.packets &&
                    memcmp(one.acc.sum, pk.acc.sum, 3 * n * sizeof(image_fixed_t)) == 0 &&
                    memcmp(one.acc.count, pk.acc.count, n * sizeof(uint64_t)) == 0 &&
                    memcmp(one.sum2, pk.sum2, 3 * n * sizeof(image_fixed_t)) == 0 &&
                    one.stats.rays == pk.stats.rays &&
                    one.stats.paths == pk.stats.paths;
        render_row(modes[m].name, "one at a time", u1, "");
        render_row(modes[m].name, "packets of 8 x 8", u2,
                   same ? "yes" : "NO");
        if (!same)
            rc = 1;
        if (m == 0)
            fprintf(stderr, "bench_grid: %s\n", pk.accel_choice);
        render_free(&one);
        render_free(&pk);
        scene_free(&sc);
    }
    return rc;
}

static int usage(const char *why, const char *arg)
{
    fprintf(stderr,
            "bench_grid: %s%s%s\nusage: bench_grid [--quick] [--only "
            "1000|10000|100000|1000000|stadium] [FILE.obj]\n"
            "       bench_grid --tune\n"
            "       bench_grid --render [--quick] [--only SIZE]\n"
            "       bench_grid --trace camera|packets4|packets8|incoherent "
            "[--passes N]\n",
            why, arg ? ": " : "", arg ? arg : "");
    return 2;
}

/* --only's argument: one of the sphere sizes, or "stadium". */
static bool only_ok(const char *a, const long *sizes, int n)
{
    if (strcmp(a, "stadium") == 0)
        return true;
    char *end;
    long v = strtol(a, &end, 10);
    for (int i = 0; *a && !*end && i < n; i++)
        if (v == sizes[i])
            return true;
    return false;
}

int main(int argc, char **argv)
{
    const char *objfile = NULL;
    const char *only = NULL; /* one sphere size, or "stadium" */
    bool quick = false, tuning = false, rendering = false;
    const char *trace = NULL; /* one kind of ray alone */
    int passes = 5;
    const long sizes[] = { 1000, 10000, 100000, 1000000 };
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--tune") == 0) {
            tuning = true;
        } else if (strcmp(argv[i], "--render") == 0) {
            rendering = true;
        } else if (strcmp(argv[i], "--quick") == 0) {
            quick = true;
            g_cam = 128;
            g_rays = 1L << 14;
        } else if (strcmp(argv[i], "--only") == 0) {
            if (i + 1 == argc)
                return usage("--only needs a size or stadium", NULL);
            only = argv[++i];
            if (!only_ok(only, sizes, 4))
                return usage("--only takes a sphere size or stadium", only);
        } else if (strcmp(argv[i], "--trace") == 0) {
            if (i + 1 == argc)
                return usage("--trace needs a kind of ray", NULL);
            trace = argv[++i];
        } else if (strcmp(argv[i], "--passes") == 0) {
            char *end;
            long v = i + 1 < argc ? strtol(argv[i + 1], &end, 10) : 0;
            if (i + 1 == argc || *end != '\0' || v < 1 || v > 1000)
                return usage("--passes takes a whole number from 1 to 1000",
                             i + 1 < argc ? argv[i + 1] : NULL);
            passes = (int)v;
            i++;
        } else if (argv[i][0] == '-') {
            return usage("unknown option", argv[i]);
        } else if (objfile) {
            return usage("one OBJ file at most", argv[i]);
        } else {
            objfile = argv[i];
        }
    }
    if (trace) {
        if (tuning || quick || only || objfile || rendering)
            return usage("--trace takes only --passes beside it", NULL);
        return trace_only(trace, passes);
    }
    if (rendering) {
        if (tuning || objfile || (only && strcmp(only, "stadium") == 0))
            return usage("--render takes only --quick and --only SIZE "
                         "beside it", NULL);
        machine_head(argc, argv);
        printf("\n");
        return render_bench(quick, only);
    }
    if (tuning) {
        if (argc != 2)
            return usage("--tune takes no other argument", NULL);
        machine(argc, argv);
        tune();
        return 0;
    }
    if (objfile && only)
        return usage("--only is for the built-in scenes, not an OBJ file",
                     NULL);
    if (objfile) {
        /* read first: a file that cannot be read gives its file:line error
         * alone, and no table */
        obj_t o;
        svet_error e;
        if (obj_read(objfile, NULL, &o, &e) != SVET_OK) {
            fprintf(stderr, "%s\n", e.msg);
            return 1;
        }
        for (long i = 0; i < o.nwarnings && i < OBJ_MAX_WARNINGS; i++)
            fprintf(stderr, "%s\n", o.warnings[i]);
        machine(argc, argv);
        print_header();
        bbox_t b;
        scene_box(&o.mesh, 1, &b);
        VECTOR3 eye, target;
        default_view(&b, eye, target);
        bench_scene(objfile, &o.mesh, 1, o.mesh->nprims, o.mesh->nprims <= 20000,
                    eye, target, 40);
        printf("\n(mesh: %.1f MB, %zu bytes per triangle)\n",
               (double)mesh_bytes(o.mesh) / 1048576,
               mesh_bytes(o.mesh) / (size_t)o.mesh->nprims);
        obj_free(&o);
        return 0;
    }
    machine(argc, argv);
    print_header();
    int nsizes = quick && !only ? 2 : 4;
    size_t mesh_mem = 0;
    long mesh_tris = 0;
    for (int i = 0; i < nsizes; i++) {
        if (only && atol(only) != sizes[i])
            continue;
        meshgen_scene_t s;
        sphere_scene(sizes[i], &s);
        char *name = malloc(64);
        snprintf(name, 64, "spheres 5x5x5");
        bbox_t b;
        scene_box(s.objs, s.nobjs, &b);
        VECTOR3 eye, target;
        default_view(&b, eye, target);
        bench_scene(name, s.objs, s.nobjs, s.ntris, sizes[i] <= 10000, eye,
                    target, 40);
        if (i == nsizes - 1) {
            for (int k = 0; k < s.nobjs; k++)
                mesh_mem += mesh_bytes(s.objs[k]);
            mesh_tris = s.ntris;
        }
        meshgen_free_objects(&s);
    }
    if (only && strcmp(only, "stadium") != 0)
        return 0;
    /* the teapot in a stadium, seen from the stands' side */
    meshgen_scene_t s;
    svet_error e;
    if (meshgen_teapot_stadium(&s, quick ? 10000 : 100000, &e) != SVET_OK)
        return 1;
    VECTOR3 eye = { 3, -5, 3 }, target = { 0, 0, 1 };
    bench_scene("teapot in a stadium", s.objs, s.nobjs, s.ntris, false, eye,
                target, 40);
    meshgen_free_objects(&s);
    if (only)
        return 0;
    growth();
    printf("\nMeshes: %zu bytes per triangle at %ld triangles (vertices, "
           "normals, st, indices, alias table; mesh.h).\n",
           mesh_mem / (size_t)mesh_tris, mesh_tris);
    return 0;
}
