/* cc -std=c11 -O2 -fopenmp -Iinclude chapters/ch05/ch05_cases.c src/render/render.c src/render/tracer.c src/render/integrator.c src/render/light.c src/render/camera.c src/render/scene.c src/render/scenefile.c src/materials/material.c src/materials/brdf.c src/core/sample.c src/core/rng.c src/materials/cobject.c src/geometry/shape.c src/geometry/sphere.c src/geometry/plane.c src/geometry/disk.c src/geometry/parallelogram.c src/geometry/triangle.c src/geometry/box.c src/geometry/cylinder.c src/geometry/cone.c src/geometry/quadric.c src/geometry/xform.c src/core/bbox.c src/core/ray.c src/core/frame.c src/core/vec.c src/colour/colour.c src/io/image.c src/stats/imgcompare.c src/stats/converge.c src/io/netpbm.c src/colour/tonemap.c src/io/fileio.c src/core/error.c -lm -o ch05 */
/*
 * ch05_cases.c - chapter 5, solving the rendering equation: the section's
 * cases (a point isotropic source, an extended source, a mirror, diffuse,
 * glossy and mixed surfaces, and glass) each rendered with every strategy
 * of the integrator - BSDF sampling alone, light sampling alone (next-event
 * estimation, Shirley et al. 1996), both joined by multiple importance
 * sampling with the power heuristic (Veach 1997, sec. 9.2), and direct
 * lighting - at EQUAL TIME, and judged against a reference rendered by
 * `path` for many times longer. Writes the images (PFM, PPM), one
 * side-by-side picture per case and a table of error and efficiency
 * (table.md, and table.csv drawn by table.gp beside this file: `make
 * figures`).
 * The integrator: src/render/integrator.c (tests: tests/render/test_integrator.c).
 *
 * usage: ch05 [OUTDIR] [--budget S] [--ref-factor K] [--scale F] [--spp N]
 *             [--threads N] [--clock cpu|wall] [--cases a,b,...]
 * (default out/ch05; run from the top directory, where scenes/ is)
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L /* sysconf */
#endif
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "../chapter.h"
#include "../chapter_image.h"
#include "stats/converge.h"
#include "io/fileio.h"
#include "stats/imgcompare.h"
#include "io/netpbm.h"
#include "render/render.h"
#include "render/scenefile.h"
#include "colour/tonemap.h"

/* The reference has its own seed, so that its noise is independent of the
 * images it judges (the strategies use the scene's seed, 0): with the same
 * seed `path` would repeat the reference's first samples exactly and its
 * error would come out too small. */
#define REF_SEED UINT64_C(0x5EED0C05)

/* The reference must be much better than what it judges: its own relative
 * variance above this fraction of the smallest relMSE it judged is
 * reported as a warning with the table. */
#define REF_MAX_RATIO 0.2

/* --- the strategies ------------------------------------------------------- */

enum { ST_BSDF, ST_NEE, ST_PATH, ST_DIRECT, ST_COUNT };

static const struct {
    const char *name;
    scene_integrator mode;
} STRATEGY[ST_COUNT] = {
    { "bsdf", SCENE_INTEGRATOR_BSDF },    /* BSDF sampling only */
    { "nee", SCENE_INTEGRATOR_NEE },      /* light sampling only, no MIS */
    { "path", SCENE_INTEGRATOR_PATH },    /* both, joined by MIS */
    { "direct", SCENE_INTEGRATOR_DIRECT } /* path cut after one bounce */
};

#define ALL3 ((1u << ST_BSDF) | (1u << ST_NEE) | (1u << ST_PATH))
#define ALL4 (ALL3 | (1u << ST_DIRECT))

/* --- the cases of sec. 5 ---------------------------------------------------- */

typedef struct {
    const char *name;     /* the case, as --cases names it */
    const char *scene;    /* relative to the top directory */
    unsigned strategies;  /* bit i: STRATEGY[i] */
} case_t;

/* `direct` is left out where it adds nothing: the point light's scene
 * already stops after one scattering event (maxdepth 1), so `direct` is
 * `path` there, sample for sample. */
static const case_t CASES[] = {
    { "point", "scenes/point_plane.scn", ALL3 },
    { "area", "scenes/area_light.scn", ALL4 },
    { "mirror", "scenes/mirror.scn", ALL4 },
    { "diffuse", "scenes/cbox.scn", ALL4 },
    { "glossy", "scenes/glossy.scn", ALL4 },
    { "mixed", "scenes/mixed.scn", ALL4 },
    { "glass", "scenes/glass.scn", ALL4 },
};
#define NCASES ((int)(sizeof CASES / sizeof CASES[0]))

/* --- settings ------------------------------------------------------------- */

typedef struct {
    const char *dir;     /* output directory */
    double budget;       /* seconds per image */
    double ref_factor;   /* the reference gets budget x ref_factor */
    double scale;        /* resolution relative to the scene's */
    long spp;            /* > 0: equal samples instead of equal time */
    int threads;         /* 0 = every core */
    bool cpu_clock;      /* process CPU time (all threads) or wall clock */
    unsigned cases;      /* bit i: CASES[i] */
} opts_t;

/* The clock the budget is spent on. On a machine shared with other
 * programs the wall clock says how busy they were; the CPU time of this
 * process (summed over its threads) says what the render cost. */
static double clock_now(bool cpu)
{
    if (cpu)
        return (double)clock() / (double)CLOCKS_PER_SEC;
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* One finished render: the mean image, its variance of the mean
 * (render_variance), and what it cost. */
typedef struct {
    image_t img, var;
    long spp;
    double seconds;
} run_t;

static void run_free(run_t *r)
{
    image_free(&r->img);
    image_free(&r->var);
}

/* Render s with `mode` and `seed` in passes of one sample per pixel until
 * `seconds` of the clock are spent (or, if spp > 0, spp samples are in). */
static svet_status render_for(scene_t *s, scene_integrator mode,
                              uint64_t seed, double seconds, long spp,
                              const opts_t *o, run_t *out, svet_error *err)
{
    memset(out, 0, sizeof *out);
    s->render.integrator = mode;
    s->render.seed = seed;
    render_t r;
    svet_status st = render_init(&r, s, err);
    if (st != SVET_OK)
        return st;
    double t0 = clock_now(o->cpu_clock), t = 0;
    do {
        render_pass(&r, r.spp_done + 1, o->threads, NULL, NULL);
        t = clock_now(o->cpu_clock) - t0;
    } while ((spp > 0 ? r.spp_done < spp : t < seconds) &&
             r.spp_done < SCENE_MAX_SPP);
    out->spp = r.spp_done;
    out->seconds = t;
    st = render_image(&r, &out->img, err);
    if (st == SVET_OK)
        st = render_variance(&r, &out->var, err);
    render_free(&r);
    if (st != SVET_OK)
        run_free(out);
    return st;
}

/* --- output ----------------------------------------------------------------- */

static FILE *table_md; /* table.md while it is written, else NULL */

/* printf to stdout and to table.md */
#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
static void out(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    if (table_md) {
        va_start(ap, fmt);
        vfprintf(table_md, fmt, ap);
        va_end(ap);
    }
}

/* Every panel of a case is shown with the same fixed mapping - the scene's
 * exposure, a linear operator, its display curve - so that a pixel means
 * the same radiance in each and only the noise differs. (An adaptive
 * operator would scale each noisy image by its own statistics.) */
static void display_params(const scene_t *s, tonemap_params_t *tp)
{
    tonemap_defaults(tp, TONEMAP_LINEAR);
    tp->stops = (double)s->render.tonemap.exposure;
    tp->curve = (tonemap_curve_t)s->render.tonemap.curve;
    tp->gamma = (double)s->render.tonemap.gamma;
}

/* The relative error image |a - b| / sqrt(b^2 + eps) of img against ref
 * (imgcompare.h: its square averages to relMSE) into *rel or, for the
 * reference (img NULL), its own standard error sqrt(var / (b^2 + eps)):
 * the error it is expected to have. *shown gets it display-linear,
 * sRGB-encoded: white is a relative error of 1 (100 %) or more. */
static svet_status error_panel(const image_t *img, const run_t *ref,
                               image_t *rel, image_t *shown, svet_error *err)
{
    svet_status st;
    if (img) {
        st = imgcompare_error_image(img, &ref->img, IMGCOMPARE_REL,
                                    IMGCOMPARE_EPS, rel, err);
    } else {
        st = image_copy(rel, &ref->var, err);
        if (st == SVET_OK)
            for (size_t i = 0; i < (size_t)rel->width * (size_t)rel->height * 3;
                 i++) {
                double b = (double)ref->img.px[i];
                rel->px[i] = (float)sqrt((double)rel->px[i] /
                                         (b * b + IMGCOMPARE_EPS));
            }
    }
    if (st != SVET_OK)
        return st;
    tonemap_params_t tp;
    tonemap_defaults(&tp, TONEMAP_LINEAR);
    tp.gamut = TONEMAP_GAMUT_CLIP;
    return tonemap_apply(rel, shown, &tp, NULL, err);
}

/* Which of BSDF sampling and light sampling has the smaller error where.
 * One pixel's error at a few dozen samples is mostly chance, and a sum of
 * squared errors over a window is ruled by its one firefly; so each pixel
 * counts a vote: t = the fraction of the pixels in the WIN x WIN window
 * around it where BSDF sampling's relative error (error_panel, summed
 * over R, G, B) is the smaller. The pixel is red where BSDF sampling is
 * better (t near 1), blue where light sampling is, purple where they tie;
 * pixels where both are exact (e.g. black background) vote for neither,
 * and a window of those is black. */
#define WIN 7
static svet_status write_winner(const char *path, const image_t *e_bsdf,
                                const image_t *e_light, svet_error *err)
{
    const int w = e_bsdf->width, h = e_bsdf->height, r = WIN / 2;
    image_t map;
    svet_status st = image_alloc(&map, w, h, 3, err);
    if (st != SVET_OK)
        return st;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int votes = 0, bsdf_wins = 0;
            for (int v = y - r; v <= y + r; v++)
                for (int u = x - r; u <= x + r; u++) {
                    if (u < 0 || v < 0 || u >= w || v >= h)
                        continue;
                    double eb = 0, el = 0;
                    for (int c = 0; c < 3; c++) {
                        eb += (double)image_at(e_bsdf, u, v)[c];
                        el += (double)image_at(e_light, u, v)[c];
                    }
                    if (!(eb > 0 || el > 0)) /* both exact (or NaN) */
                        continue;
                    votes++;
                    bsdf_wins += eb < el;
                }
            float *p = image_at(&map, x, y);
            if (votes > 0) {
                p[0] = (float)bsdf_wins / (float)votes;
                p[2] = 1 - p[0];
            }
        }
    st = netpbm_write_ppm(path, &map, 8, err);
    image_free(&map);
    return st;
}

#define GAP 4 /* pixels of grey between panels */

/* The side-by-side picture: the n images on top, left to right, their
 * error images below. */
static svet_status write_side(const char *path, const image_t *top,
                              const image_t *bottom, int n, svet_error *err)
{
    const int w = top[0].width, h = top[0].height;
    image_t all;
    svet_status st = image_alloc(&all, n * w + (n - 1) * GAP, 2 * h + GAP, 3,
                                 err);
    if (st != SVET_OK)
        return st;
    for (size_t i = 0; i < (size_t)all.width * (size_t)all.height * 3; i++)
        all.px[i] = 0.5f;
    for (int k = 0; k < n; k++)
        for (int row = 0; row < 2; row++) {
            const image_t *p = row ? &bottom[k] : &top[k];
            for (int y = 0; y < h; y++)
                memcpy(image_at(&all, k * (w + GAP), row * (h + GAP) + y),
                       image_at(p, 0, y), (size_t)w * 3 * sizeof(float));
        }
    st = netpbm_write_ppm(path, &all, 8, err);
    image_free(&all);
    return st;
}

/* --- one case ----------------------------------------------------------------- */

typedef struct {
    const char *scene, *strategy;
    long spp;
    double seconds;
    double rmse, relmse, relvar; /* relvar: the image's own, estimated */
    double noise_ratio;          /* relMSE / (relvar + the reference's):
                                    about 1 unless the image is biased */
    double efficiency;           /* 1 / (relMSE x seconds) */
} row_t;

typedef struct {
    const char *scene;
    long spp;
    double seconds;
    double relvar;               /* the reference's own, estimated */
    double min_relmse;           /* the smallest relMSE it judged */
} refrow_t;

static svet_status run_case(const case_t *c, const opts_t *o, row_t *rows,
                            int *nrows, refrow_t *ref_row, svet_error *err)
{
    scene_t s;
    scene_init(&s);
    svet_status st = scenefile_read(&s, c->scene, err);
    if (st != SVET_OK)
        return st;
    int w = (int)((double)s.camera.width * o->scale + 0.5);
    int h = (int)((double)s.camera.height * o->scale + 0.5);
    s.camera.width = w > 0 ? w : 1;
    s.camera.height = h > 0 ? h : 1;
    const uint64_t seed = s.render.seed;
    tonemap_params_t tp;
    display_params(&s, &tp);

    /* the panels of the side-by-side picture, and each strategy's
     * relative error image (error_panel) */
    image_t top[ST_COUNT + 1], bottom[ST_COUNT + 1], rel[ST_COUNT + 1];
    memset(top, 0, sizeof top);
    memset(bottom, 0, sizeof bottom);
    memset(rel, 0, sizeof rel);
    int npanels = 0;
    run_t ref;
    memset(&ref, 0, sizeof ref);

    /* the reference: path at ref_factor times the budget */
    fprintf(stderr, "ch05: %s (%s, %d x %d): reference...\n", c->name,
            c->scene, s.camera.width, s.camera.height);
    st = render_for(&s, SCENE_INTEGRATOR_PATH, REF_SEED,
                    o->budget * o->ref_factor,
                    o->spp > 0 ? (long)((double)o->spp * o->ref_factor) : 0,
                    o, &ref, err);
    ref_row->scene = c->name;
    ref_row->spp = ref.spp;
    ref_row->seconds = ref.seconds;
    ref_row->min_relmse = (double)INFINITY;

    for (int k = 0; k < ST_COUNT && st == SVET_OK; k++) {
        if (!(c->strategies & (1u << k)))
            continue;
        run_t run;
        st = render_for(&s, STRATEGY[k].mode, seed, o->budget, o->spp, o,
                        &run, err);
        if (st != SVET_OK)
            break;
        converge_point_t pt;
        st = converge_measure(&run.img, &run.var, &ref.img, &ref.var, &pt,
                              err);
        char stem[256];
        snprintf(stem, sizeof stem, "%s_%s", c->name, STRATEGY[k].name);
        if (st == SVET_OK)
            st = chapter_write_pair(o->dir, stem, &run.img, &tp,
                                    &top[npanels], err);
        if (st == SVET_OK)
            st = error_panel(&run.img, &ref, &rel[k], &bottom[npanels], err);
        if (st == SVET_OK) {
            npanels++;
            row_t *r = &rows[(*nrows)++];
            r->scene = c->name;
            r->strategy = STRATEGY[k].name;
            r->spp = run.spp;
            r->seconds = run.seconds;
            r->rmse = pt.rmse;
            r->relmse = pt.mse[CONVERGE_REL];
            r->relvar = pt.variance[CONVERGE_REL];
            double noise = r->relvar + pt.ref_variance[CONVERGE_REL];
            r->noise_ratio = noise > 0 ? r->relmse / noise : (double)INFINITY;
            r->efficiency = r->relmse * r->seconds > 0
                                ? 1 / (r->relmse * r->seconds) : 0;
            ref_row->relvar = pt.ref_variance[CONVERGE_REL];
            if (r->relmse < ref_row->min_relmse)
                ref_row->min_relmse = r->relmse;
            fprintf(stderr, "ch05: %s %-6s %5ld spp %6.2f s  relMSE %.3g\n",
                    c->name, r->strategy, r->spp, r->seconds, r->relmse);
        }
        run_free(&run);
    }
    if (st == SVET_OK) {
        char stem[256], path[1200];
        snprintf(stem, sizeof stem, "%s_reference", c->name);
        st = chapter_write_pair(o->dir, stem, &ref.img, &tp, &top[npanels],
                                err);
        if (st == SVET_OK)
            st = error_panel(NULL, &ref, &rel[ST_COUNT], &bottom[npanels],
                             err);
        if (st == SVET_OK) {
            npanels++;
            snprintf(path, sizeof path, "%s/%s_side.ppm", o->dir, c->name);
            st = write_side(path, top, bottom, npanels, err);
        }
        if (st == SVET_OK && rel[ST_BSDF].px && rel[ST_NEE].px) {
            snprintf(path, sizeof path, "%s/%s_winner.ppm", o->dir, c->name);
            st = write_winner(path, &rel[ST_BSDF], &rel[ST_NEE], err);
        }
    }
    for (int k = 0; k <= ST_COUNT; k++) {
        image_free(&top[k]);
        image_free(&bottom[k]);
        image_free(&rel[k]);
    }
    run_free(&ref);
    scene_free(&s);
    return st;
}

/* --- the table ------------------------------------------------------------------ */

static void cpu_model(char *buf, size_t n)
{
    snprintf(buf, n, "unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f)
        return;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        char *colon = strchr(line, ':');
        if (strncmp(line, "model name", 10) == 0 && colon) {
            colon += 2;
            colon[strcspn(colon, "\n")] = '\0';
            snprintf(buf, n, "%s", colon);
            break;
        }
    }
    fclose(f);
}

/* The efficiency of `path` on the same case, 0 if it was not run. */
static double path_efficiency(const row_t *rows, int nrows, const char *scene)
{
    for (int j = 0; j < nrows; j++)
        if (rows[j].scene == scene && strcmp(rows[j].strategy, "path") == 0)
            return rows[j].efficiency;
    return 0;
}

static void print_table(const row_t *rows, int nrows, const refrow_t *refs,
                        int nrefs, const opts_t *o, int argc, char **argv)
{
    char cpu[256];
    cpu_model(cpu, sizeof cpu);
    out("# Chapter 5: the cases at equal %s\n\n", o->spp > 0 ? "samples"
                                                             : "time");
    out("Command:");
    for (int i = 0; i < argc; i++)
        out(" %s", argv[i]);
    out("\n\nMachine: %d processors (%s), compiler %s, real = %s, "
        "threads %d (0 = all).\n", (int)sysconf(_SC_NPROCESSORS_ONLN), cpu, __VERSION__,
        REAL_NAME, o->threads);
    if (o->spp > 0)
        out("Budget: %ld spp per image; references %g x that.\n", o->spp,
            o->ref_factor);
    else
        out("Budget: %g s of %s time per image, in passes of 1 spp; "
            "references %g x that.\n", o->budget,
            o->cpu_clock ? "CPU (all threads summed)" : "wall-clock",
            o->ref_factor);
    out("Resolution: %g x the scene's.\n\n", o->scale);

    out("| scene | strategy | spp | seconds | RMSE | relMSE | own relvar "
        "| relMSE / noise | efficiency vs path |\n");
    out("|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
    for (int i = 0; i < nrows; i++) {
        const row_t *r = &rows[i];
        double eff_path = path_efficiency(rows, nrows, r->scene);
        out("| %s | %s | %ld | %.2f | %.4g | %.4g | %.3g | %.3g | ", r->scene,
            r->strategy, r->spp, r->seconds, r->rmse, r->relmse, r->relvar,
            r->noise_ratio);
        if (eff_path > 0)
            out("%.3g |\n", r->efficiency / eff_path);
        else
            out("- |\n");
    }
    out("\nThe references (path, seed %#llx):\n\n",
        (unsigned long long)REF_SEED);
    out("| scene | spp | seconds | own relvar | smallest relMSE judged | "
        "ratio |\n|---|---:|---:|---:|---:|---:|\n");
    for (int i = 0; i < nrefs; i++) {
        const refrow_t *r = &refs[i];
        out("| %s | %ld | %.2f | %.3g | %.3g | %.3f |\n", r->scene, r->spp,
            r->seconds, r->relvar, r->min_relmse,
            r->min_relmse > 0 ? r->relvar / r->min_relmse : 0);
    }
    for (int i = 0; i < nrefs; i++)
        if (refs[i].relvar > REF_MAX_RATIO * refs[i].min_relmse)
            out("\n**Warning:** the reference of %s is too noisy to judge "
                "by: its own relvar is more than %g of the smallest relMSE "
                "it judged. Give it more time (--ref-factor).\n",
                refs[i].scene, REF_MAX_RATIO);
    out("\nrelMSE: mean over R, G, B of (a - b)^2 / (b^2 + 0.01) against the "
        "reference b (its noise included); own relvar: the same mean of the "
        "image's own variance of the mean (render_variance); relMSE / noise: "
        "relMSE over the sum of the image's and the reference's relvar, "
        "about 1 when noise explains the error, far above 1 for a biased "
        "image (a strategy that misses light); efficiency: "
        "1 / (relMSE x seconds), relative to path's.\n");
}

/* The table as CSV for table.gp: one row per image; efficiency is
 * relative to path's on the same case. */
static svet_status write_csv(const char *dir, const row_t *rows, int nrows,
                             svet_error *err)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/table.csv", dir);
    fileio_t f;
    svet_status st = fileio_begin(&f, path, err);
    if (st != SVET_OK)
        return st;
    fprintf(f.f, "# ch05: each case rendered with each strategy; relMSE "
                 "against the reference, efficiency 1 / (relMSE x seconds) "
                 "relative to path's\ncase,strategy,spp,seconds,rmse,relmse,"
                 "relvar,noise_ratio,efficiency_vs_path\n");
    for (int i = 0; i < nrows; i++) {
        const row_t *r = &rows[i];
        double eff_path = path_efficiency(rows, nrows, r->scene);
        fprintf(f.f, "%s,%s,%ld,%.4f,%.6g,%.6g,%.6g,%.6g,%.6g\n", r->scene,
                r->strategy, r->spp, r->seconds, r->rmse, r->relmse, r->relvar,
                r->noise_ratio, eff_path > 0 ? r->efficiency / eff_path
                                             : (double)NAN);
    }
    return fileio_commit(&f, err);
}

/* --- main ----------------------------------------------------------------------- */

static void usage(FILE *f)
{
    fprintf(f,
            "usage: ch05 [OUTDIR] [--budget S] [--ref-factor K] [--scale F]\n"
            "            [--spp N] [--threads N] [--clock cpu|wall]\n"
            "            [--cases a,b,...]\n"
            "Renders each case of chapter 5 with every strategy at equal "
            "time\n(default: 1 s of CPU time per image at half the "
            "resolution, references\n16 x longer) into OUTDIR (out/ch05). "
            "Cases:");
    for (int i = 0; i < NCASES; i++)
        fprintf(f, " %s", CASES[i].name);
    fprintf(f, ".\nRun from the top directory (the scenes are read from "
               "scenes/).\n");
}

static bool parse_cases(const char *list, unsigned *mask)
{
    *mask = 0;
    char buf[256];
    snprintf(buf, sizeof buf, "%s", list);
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        int i = 0;
        while (i < NCASES && strcmp(CASES[i].name, tok) != 0)
            i++;
        if (i == NCASES)
            return false;
        *mask |= 1u << i;
    }
    return *mask != 0;
}

int main(int argc, char **argv)
{
    opts_t o = { "out/ch05", 1.0, 16.0, 0.5, 0, 0, true, (1u << NCASES) - 1 };
    bool have_dir = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        char *end = NULL;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return 0;
        } else if (a[0] != '-') {
            if (have_dir) {
                fprintf(stderr, "ch05: one output directory only: '%s', "
                                "then '%s'\n", o.dir, a);
                return 2;
            }
            o.dir = a;
            have_dir = true;
            continue;
        } else if (!v) {
            fprintf(stderr, "ch05: %s needs a value\n", a);
            return 2;
        } else if (!strcmp(a, "--budget")) {
            o.budget = strtod(v, &end);
            if (!(o.budget > 0 && o.budget < 1e6))
                end = NULL;
        } else if (!strcmp(a, "--ref-factor")) {
            o.ref_factor = strtod(v, &end);
            if (!(o.ref_factor >= 1 && o.ref_factor < 1e6))
                end = NULL;
        } else if (!strcmp(a, "--scale")) {
            o.scale = strtod(v, &end);
            if (!(o.scale > 0 && o.scale <= 16))
                end = NULL;
        } else if (!strcmp(a, "--spp")) {
            o.spp = strtol(v, &end, 10);
            if (o.spp < 1 || o.spp > SCENE_MAX_SPP)
                end = NULL;
        } else if (!strcmp(a, "--threads")) {
            o.threads = (int)strtol(v, &end, 10);
            if (o.threads < 0 || o.threads > SCENE_MAX_THREADS)
                end = NULL;
        } else if (!strcmp(a, "--clock")) {
            o.cpu_clock = !strcmp(v, "cpu");
            end = o.cpu_clock || !strcmp(v, "wall") ? (char *)v + strlen(v)
                                                     : NULL;
        } else if (!strcmp(a, "--cases")) {
            end = parse_cases(v, &o.cases) ? (char *)v + strlen(v) : NULL;
        } else {
            fprintf(stderr, "ch05: unknown option %s\n", a);
            usage(stderr);
            return 2;
        }
        if (!end || *end) {
            fprintf(stderr, "ch05: bad value for %s: '%s'\n", a, v);
            return 2;
        }
        i++;
    }
    if (chapter_make_dir("ch05", o.dir) != 0)
        return 1;

    row_t rows[NCASES * ST_COUNT];
    refrow_t refs[NCASES];
    int nrows = 0, nrefs = 0;
    svet_error err;
    svet_error_clear(&err);
    for (int i = 0; i < NCASES; i++) {
        if (!(o.cases & (1u << i)))
            continue;
        if (run_case(&CASES[i], &o, rows, &nrows, &refs[nrefs++], &err) !=
            SVET_OK) {
            fprintf(stderr, "ch05: %s\n", err.msg);
            return 1;
        }
    }

    char path[1200];
    snprintf(path, sizeof path, "%s/table.md", o.dir);
    fileio_t f;
    if (fileio_begin(&f, path, &err) != SVET_OK) {
        fprintf(stderr, "ch05: %s\n", err.msg);
        return 1;
    }
    table_md = f.f;
    print_table(rows, nrows, refs, nrefs, &o, argc, argv);
    table_md = NULL;
    if (fileio_commit(&f, &err) != SVET_OK ||
        write_csv(o.dir, rows, nrows, &err) != SVET_OK) {
        fprintf(stderr, "ch05: %s\n", err.msg);
        return 1;
    }
    fprintf(stderr, "ch05: wrote %s and the images beside it\n", path);
    return 0;
}
