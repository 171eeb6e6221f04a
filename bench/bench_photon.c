/*
 * bench_photon.c - `make bench-photon`: the photon map of ch. 8
 * (photon/photonmap.h). For 1e5, 1e6 and 1e7 photons on the six walls of a
 * unit box (photons lie on surfaces, as in a Cornell box): the time to
 * balance the kd-tree on one thread and on all, its memory, and k = 50
 * nearest-photon queries per CPU-second on one thread, the query points
 * in scanline order over a wall (as a renderer's first hits come) and at
 * random. Then photon tracing in scenes/caustic.scn (photon/photon.h):
 * photons emitted per CPU-second on one thread and per second of wall
 * time on all, for the global and the caustic map, and Christensen's
 * precomputation (every 4th global photon, k = 50). Prints Markdown
 * tables, also written to bench/results/photon.md (or the path given as
 * argv[1]); `--quick` stops at 1e6 and traces fewer photons.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "bench.h"

#include <omp.h>

#include "core/rng.h"
#include "photon/photon.h"
#include "photon/photonmap.h"
#include "render/allparts.h"
#include "render/render.h"
#include "render/scenefile.h"

/* a point on the box's walls: face f in 0..5, (a, b) on it */
static void wall_point(int f, real a, real b, VECTOR3 p)
{
    int axis = f / 2;
    p[axis] = (real)(f % 2);
    p[(axis + 1) % 3] = a;
    p[(axis + 2) % 3] = b;
}

static void fill(photonmap_t *m, size_t n)
{
    pcg32_t g;
    pcg32_seed(&g, 8, 1);
    VECTOR3 d = { 0, 0, -1 };
    for (size_t i = 0; i < n; i++) {
        VECTOR3 p;
        wall_point((int)(pcg32_next(&g) % 6), pcg32_real(&g), pcg32_real(&g), p);
        photonmap_store(m, p, rad_grey(1), d, 0);
    }
}

static volatile int sink;

/* queries per CPU-second: nq points, k = 50, rmax 0.1 */
static double query_rate(const photonmap_t *m, VECTOR3 *pts, int nq)
{
    int32_t idx[50];
    real d2[50];
    double best = 0;
    for (int run = 0; run < 3; run++) {
        double t0 = bench_cpu_now();
        int s = 0;
        for (int i = 0; i < nq; i++)
            s += photonmap_nearest(m, pts[i], 50, REAL_C(0.1), idx, d2);
        double dt = bench_cpu_now() - t0;
        sink = s;
        if (nq / dt > best)
            best = nq / dt;
    }
    return best;
}

int main(int argc, char **argv)
{
    bool quick = argc > 1 && !strcmp(argv[1], "--quick");
    const char *out = argc > 1 && !quick ? argv[1] : "bench/results/photon.md";
    static const size_t sizes[] = { 100000, 1000000, 10000000 };
    int nsizes = quick ? 2 : 3, nthreads = omp_get_max_threads();

    enum { NQ = 200000 };
    VECTOR3 *scan = malloc(sizeof *scan * NQ), *rnd = malloc(sizeof *rnd * NQ);
    if (!scan || !rnd)
        return 1;
    pcg32_t g;
    pcg32_seed(&g, 8, 2);
    for (int i = 0; i < NQ; i++) {
        /* 400 x 500 raster over the floor, then random points on walls */
        wall_point(2, (real)(i % 400) / 400, (real)(i / 400) / 500, scan[i]);
        wall_point((int)(pcg32_next(&g) % 6), pcg32_real(&g), pcg32_real(&g),
                   rnd[i]);
    }

    char path[1100], load[160], date[32];
    snprintf(path, sizeof path, "%s.tmp", out);
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        return 1;
    }
    time_t now = time(NULL);
    strftime(date, sizeof date, "%Y-%m-%d", gmtime(&now));
    fprintf(f, "# Photon maps: balancing and queries\n\n`make bench-photon` "
               "(bench/bench_photon.c), real = " REAL_NAME ", %s. ", date);
    bench_print_machine(f);
    fprintf(f, "; %s.\n\nPhotons on the six walls of a unit box; k = 50 "
               "nearest within 0.1; query rates per CPU-second of one "
               "thread.\n\n| photons | memory (MB) | balance, 1 thread (s) | "
               "balance, %d threads (s, wall) | queries/s, scanline | "
               "queries/s, random |\n|---:|---:|---:|---:|---:|---:|\n",
            bench_load_words(load, sizeof load), nthreads);
    for (int s = 0; s < nsizes; s++) {
        size_t n = sizes[s];
        double t1 = 0, tn = 0;
        photonmap_t m;
        svet_error e;
        for (int threads = 1; threads <= 2; threads++) {
            if (photonmap_init(&m, n, &e) != SVET_OK) {
                fprintf(stderr, "bench_photon: %s\n", e.msg);
                return 1;
            }
            fill(&m, n);
            omp_set_num_threads(threads == 1 ? 1 : nthreads);
            double c0 = bench_cpu_now(), w0 = bench_now();
            if (photonmap_balance(&m, &e) != SVET_OK) {
                fprintf(stderr, "bench_photon: %s\n", e.msg);
                return 1;
            }
            if (threads == 1)
                t1 = bench_cpu_now() - c0;
            else
                tn = bench_now() - w0;
            if (threads == 1)
                photonmap_free(&m);
        }
        omp_set_num_threads(1);
        double qs = query_rate(&m, scan, NQ), qr = query_rate(&m, rnd, NQ);
        fprintf(f, "| %zu | %.0f | %.3f | %.3f | %.0f | %.0f |\n", n,
                (double)photonmap_bytes(n) / 1e6, t1, tn, qs, qr);
        printf("%9zu photons: balance %.3f s (1T CPU), %.3f s (%dT wall); "
               "queries %.0f/s scanline, %.0f/s random\n", n, t1, tn,
               nthreads, qs, qr);
        fflush(stdout);
        photonmap_free(&m);
    }
    free(scan);
    free(rnd);

    /* photon tracing in the caustic scene */
    scene_t sc;
    render_t r;
    svet_error e;
    if (scenefile_read_with(&sc, "scenes/caustic.scn", scene_features_all(),
                            &e) != SVET_OK ||
        render_init(&r, &sc, &e) != SVET_OK) {
        fprintf(stderr, "bench_photon: %s\n", e.msg);
        return 1;
    }
    const uint64_t count = quick ? 100000 : 1000000;
    fprintf(f, "\nPhoton tracing in scenes/caustic.scn, %llu photons emitted "
               "(the map built included): photons per CPU-second on one "
               "thread, per wall second on %d; and the irradiance "
               "precomputed at every 4th global photon (k = 50, max_radius "
               "0.08, Christensen 1999), points per CPU-second on one "
               "thread.\n\n| map | stored | photons/s, 1 thread (CPU) | "
               "photons/s, %d threads (wall) | precomputed points/s, 1 "
               "thread |\n|---|---:|---:|---:|---:|\n",
            (unsigned long long)count, nthreads, nthreads);
    photonmap_query_t q = { 50, REAL_C(0.08), PHOTONMAP_FILTER_CONE,
                            REAL_C(1.1), REAL_C(0.25) };
    for (int kind = 0; kind < 2; kind++) {
        photon_kind_t pk = kind == 0 ? PHOTON_GLOBAL : PHOTON_CAUSTIC;
        photonmap_t m, irr;
        omp_set_num_threads(1);
        double c0 = bench_cpu_now();
        if (photon_trace(&r, count, pk, 0, 1, &m, &e) != SVET_OK) {
            fprintf(stderr, "bench_photon: %s\n", e.msg);
            return 1;
        }
        double t1 = bench_cpu_now() - c0;
        size_t stored = m.n;
        photonmap_free(&m);
        omp_set_num_threads(nthreads);
        double w0 = bench_now();
        if (photon_trace(&r, count, pk, 0, nthreads, &m, &e) != SVET_OK) {
            fprintf(stderr, "bench_photon: %s\n", e.msg);
            return 1;
        }
        double tn = bench_now() - w0;
        photonmap_free(&m);
        char pre[64] = "-";
        if (pk == PHOTON_GLOBAL) {
            /* the precomputation's CPU time: the traced map's and the
             * precomputed one's, less the tracing's alone */
            omp_set_num_threads(1);
            c0 = bench_cpu_now();
            if (photon_trace_precomputed(&r, count, pk, 0, 1, 4, &q, &m, &irr,
                                         &e) != SVET_OK) {
                fprintf(stderr, "bench_photon: %s\n", e.msg);
                return 1;
            }
            double tp = bench_cpu_now() - c0 - t1;
            snprintf(pre, sizeof pre, "%.0f",
                     tp > 0 ? (double)irr.n / tp : 0.0);
            photonmap_free(&m);
            photonmap_free(&irr);
        }
        fprintf(f, "| %s | %zu | %.0f | %.0f | %s |\n",
                kind == 0 ? "global" : "caustic", stored, (double)count / t1,
                (double)count / tn, pre);
        printf("photon tracing, %s map: %zu stored; %.0f photons/s (1T CPU), "
               "%.0f/s (%dT wall); precomputed %s points/s\n",
               kind == 0 ? "global" : "caustic", stored, (double)count / t1,
               (double)count / tn, nthreads, pre);
        fflush(stdout);
    }
    render_free(&r);
    scene_free(&sc);
    if (fclose(f) != 0 || rename(path, out) != 0) {
        perror(out);
        return 1;
    }
    printf("written to %s\n", out);
    return 0;
}
