/*
 * converge.c - `svet converge`: how the error of a render falls with time
 * (ch. 4's 1/sqrt(N), measured). Renders a scene progressively, measuring
 * the image against a converged reference after each of a series of sample
 * counts or time budgets (the series costs one render of its largest
 * count), writes the series as CSV (include/stats/converge.h) and plots it with
 * gnuplot when gnuplot is installed. `svet converge --report` compares
 * several series in one Markdown table (make tradeoffs, docs/tradeoffs.md).
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <spawn.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cmd.h"
#include "cmdutil.h"
#include "stats/converge.h"
#include "io/exrio.h"
#include "io/fileio.h"
#include "render/render.h"
#include "render/scenefile.h"
#include "render/scenepart.h"
#include "stats/ztest.h"

extern char **environ;

#define MAX_POINTS CMD_CONVERGE_MAX_POINTS
#define DEFAULT_SCRIPT "tools/plot-converge.gp"

void cmd_converge_help(FILE *f)
{
    fprintf(f,
"usage: svet converge SCENE --ref REF.exr [options]\n"
"       svet converge --report [--metric rel|abs] [--time T] [--error E]\n"
"                     SERIES.csv ...\n"
"       svet converge --ztest IMAGE.exr --spp N --ref REF.exr [--var V.exr]\n"
"                     [--ref-var RV.exr] [--ref-spp M] [--pvalue P.exr]\n"
"\n"
"Render SCENE progressively and measure it against the converged reference\n"
"REF.exr after each sample count of --spp-list (or each time budget of\n"
"--time-list): the samples already taken are kept, so the whole series costs\n"
"one render of its largest count. Writes DIR/LABEL.csv with one row per\n"
"point (columns: include/stats/converge.h): samples per pixel, seconds, rays, RMSE,\n"
"PSNR (peak 1); the MSE, the render's own variance of the mean\n"
"(render_variance, averaged over the pixels), the reference's, the error\n"
"with the reference's noise taken out, the bias^2 estimate MSE - both\n"
"variances, and the efficiency 1 / (variance x seconds), which stays\n"
"constant along an unbiased series and puts methods on one number (larger\n"
"is better); then all of these again relative, each value divided by\n"
"b^2 + 0.01 (relMSE), where the noisy edge of a bright emitter no longer\n"
"outweighs the rest of the image.\n"
"\n"
"options:\n"
"  --ref FILE.exr        the converged reference (required); its size sets\n"
"                        the render's resolution when the aspect ratio agrees\n"
"  --ref-var FILE.exr    the reference's variance image (default: REF-var.exr\n"
"                        beside it, if it exists); its noise is then taken\n"
"                        out of the error\n"
"  --spp-list A,B,...    increasing sample counts (default 1,2,4,... up to\n"
"                        the scene's spp)\n"
"  --time-list S,T,...   increasing time budgets in seconds, instead\n"
"  --out DIR             where the CSV and the plot go (default out/converge)\n"
"  --label NAME          the method's name: file names and the CSV's method\n"
"                        column (default: the scene's name and the --set\n"
"                        options, e.g. cbox-maxdepth=1)\n"
"  --set KEY=VALUE       a scene setting (maxdepth, integrator, roulette,\n"
"                        accel, ...: scenefile_override), repeatable\n"
"  --strict              refuse a scene that reading warns about (exit 2)\n"
"  --threads N           render threads (0 = every core)\n"
"  --clock wall|cpu      what the seconds and --time-list count: wall, the\n"
"                        time waited (default); cpu, the process's CPU time,\n"
"                        all its threads together, which other jobs on the\n"
"                        machine hardly change (a budget of 2 s at 2\n"
"                        threads is 1 s of wall on a quiet machine). The\n"
"                        CSV's seconds column is then cpu_seconds\n"
"  --seed N              seed of the random numbers (use one other than the\n"
"                        reference's, so that the errors are independent)\n"
"  --max-pixels N        read images of up to N pixels (default 67108864,\n"
"                        8192 x 8192, or the environment's SVET_MAX_PIXELS)\n"
"  --no-plot             write the CSV only\n"
"  --plot-script FILE    the gnuplot script (default " DEFAULT_SCRIPT ",\n"
"                        relative to the current directory)\n"
"  -q, --quiet           no progress lines\n"
"  -h, --help            this text\n"
"\n");
    fprintf(f,
"--report reads the CSV files, the first being the baseline, and prints a\n"
"Markdown table: each method's error at time T (default: the shortest of\n"
"the series' longest times), the time it needs to reach error E (default:\n"
"the baseline's error at T), its efficiency, its rays per second, and\n"
"whether it is biased (at its last point the squared bias exceeds the noise\n"
"variance: the error stops falling). --metric chooses the relative (rel,\n"
"the default) or absolute (abs) error and variance. Values outside a series\n"
"are extrapolated by MSE = bias^2 + c / t and marked ~.\n"
"\n"
"--ztest compares IMAGE.exr, the mean of N samples per pixel with its\n"
"variance image (--var; default IMAGE-var.exr, as svet render --variance\n"
"writes it), with the reference REF.exr (variance --ref-var, default\n"
"REF-var.exr; spp --ref-spp, default the `spp = ` line of REF.txt) by the\n"
"Z-test of the regression test (include/stats/ztest.h; tests/reference/README.md):\n"
"per pixel and on blocks of 4, 16, ... pixels, Sidak-corrected at alpha\n"
"0.01, each level passing when 99.5%% of its cells pass. Prints one line per\n"
"level, then pass or FAIL; --pvalue writes the per-pixel p-values. Exit 0\n"
"when it passes, 5 when it fails, 2 when a file holds a value that is not\n"
"finite or is negative. This is how a port checks its images.\n"
"\n"
"The plot: when the script exists and gnuplot is on PATH, svet converge runs\n"
"`gnuplot -e \"files=...; out=...\" SCRIPT` (posix_spawnp) and writes\n"
"DIR/LABEL.png, the relative RMSE against time on log-log axes; otherwise it\n"
"says so and prints the command to run later.\n"
"Timings are of the render set-up (the photon tracing included) and the\n"
"passes, not the measurements, on the clock of --clock. --report reads the\n"
"clock from the CSV's seconds column (seconds or cpu_seconds), refuses to\n"
"compare series of different clocks and gives times as s or CPU-s.\n"
"\n"
"exit codes: 0 done; 1 bad command line; 2 the scene, the reference or a CSV\n"
"is missing or malformed, or they do not fit together; 3 an output could\n"
"not be written; 5 --ztest: the image fails the test.\n");
}

/* Parse "a,b,c" into increasing positive numbers; false on anything else. */
static bool parse_list(const char *s, double *v, int *n, bool integers)
{
    *n = 0;
    const char *p = s;
    while (*p) {
        char *end;
        errno = 0;
        double x = strtod(p, &end);
        if (end == p || errno || !(x > 0) || x > 1e9 || *n == MAX_POINTS ||
            (integers && x != floor(x)) || (*n > 0 && !(x > v[*n - 1])))
            return false;
        v[(*n)++] = x;
        if (*end == ',' && end[1])
            end++;
        else if (*end)
            return false;
        p = end;
    }
    return *n > 0;
}

/* "scenes/cbox.scn" -> "cbox" (malloc'ed) */
static char *scene_stem(const char *path)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    size_t n = strcspn(base, ".");
    char *s = malloc(n + 1);
    if (s) {
        memcpy(s, base, n);
        s[n] = '\0';
    }
    return s;
}

/* A byte allowed in a label: [A-Za-z0-9._=+-], so that it is a file name
 * and a CSV field. */
static bool label_char(char c)
{
    return ('a' <= c && c <= 'z') || ('A' <= c && c <= 'Z') ||
           ('0' <= c && c <= '9') || (c && strchr("._=+-", c));
}

static bool label_ok(const char *s)
{
    if (!*s || *s == '.' || strlen(s) > 200)
        return false;
    for (; *s; s++)
        if (!label_char(*s))
            return false;
    return true;
}

/* The default label: the scene's stem and the --set options, every other
 * byte made '_'. */
static void make_label(char *out, size_t n, const char *stem,
                       const char *const *sets, int nsets)
{
    snprintf(out, n, "%s", stem);
    for (int i = 0; i < nsets; i++) {
        size_t len = strlen(out);
        snprintf(out + len, n - len, "-%s", sets[i]);
    }
    for (char *c = out; *c; c++)
        if (!label_char(*c))
            *c = '_';
}

/* Make dir and its parents (as mkdir -p); errors are left to the writer. */
static void make_dirs(const char *dir)
{
    char buf[4096];
    snprintf(buf, sizeof buf, "%s", dir);
    for (char *p = buf + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            mkdir(buf, 0777);
            *p = '/';
        }
    mkdir(buf, 0777);
}

static bool file_exists(const char *path)
{
    return access(path, R_OK) == 0;
}

/* Run gnuplot on script with the -e assignments; true when it ran and
 * exited 0. *missing is set when gnuplot was not found. */
static bool run_gnuplot(const char *script, const char *assign, bool *missing)
{
    char *argv[] = { "gnuplot", "-e", (char *)assign, (char *)script, NULL };
    pid_t pid;
    *missing = false;
    int rc = posix_spawnp(&pid, "gnuplot", NULL, NULL, argv, environ);
    if (rc != 0) {
        *missing = rc == ENOENT;
        return false;
    }
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return false;
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

/* Plot csv, timed by clock, to png with the script, or say how to. */
static void plot(const char *script, const char *csv, const char *png,
                 const char *title, converge_clock clock, bool quiet)
{
    char assign[8192];
    if (strchr(csv, '\'') || strchr(png, '\'') || strchr(title, '\'')) {
        fprintf(stderr, "svet converge: no plot: a file name holds a quote\n");
        return;
    }
    snprintf(assign, sizeof assign, "files='%s'; out='%s'; ttl='%s'; "
             "clock='%s'", csv, png, title, converge_clock_name(clock));
    if (!file_exists(script)) {
        fprintf(stderr, "svet converge: no plot: the gnuplot script %s is "
                        "not here (run from svet's top directory, or give "
                        "--plot-script); wrote the CSV only\n", script);
        return;
    }
    bool missing;
    if (run_gnuplot(script, assign, &missing)) {
        if (!quiet)
            fprintf(stderr, "svet converge: plotted %s (gnuplot)\n", png);
        return;
    }
    fprintf(stderr, "svet converge: no plot: %s; wrote the CSV only. To plot "
                    "it later:\n  gnuplot -e \"%s\" %s\n",
            missing ? "gnuplot is not installed" : "gnuplot failed", assign,
            script);
}

/* ------------------------------------------------------------------------ */

static const char *how_mark(converge_how h)
{
    return h == CONVERGE_EXTRAPOLATED ? "~" : "";
}

static void fmt_time(char *out, size_t n, double t, converge_how h,
                     const char *unit)
{
    if (h == CONVERGE_NEVER)
        snprintf(out, n, "never (bias)");
    else if (h == CONVERGE_UNKNOWN || !isfinite(t))
        snprintf(out, n, "-");
    else
        snprintf(out, n, "%s%.3g %s", how_mark(h), t, unit);
}

static int report(int nfiles, const char *const *files, converge_metric m, double T,
                  double E)
{
    typedef struct {
        char method[128];
        converge_point_t *p;
        int n;
    } series_t;
    series_t *s = calloc((size_t)nfiles, sizeof *s);
    if (!s) {
        fprintf(stderr, "svet converge: out of memory\n");
        return SVET_EXIT_INPUT;
    }
    int rc = SVET_EXIT_OK;
    svet_error err;
    converge_clock clock0 = CONVERGE_WALL;
    for (int i = 0; i < nfiles; i++) {
        converge_clock clock;
        svet_error_clear(&err);
        if (converge_csv_read(files[i], s[i].method, sizeof s[i].method,
                              &clock, &s[i].p, &s[i].n, &err) != SVET_OK ||
            s[i].n == 0) {
            if (err.status == SVET_OK)
                fprintf(stderr, "svet converge: %s: a series without "
                                "points\n", files[i]);
            else
                fprintf(stderr, "svet converge: %s\n", err.msg);
            rc = SVET_EXIT_INPUT;
            goto done;
        }
        if (i == 0)
            clock0 = clock;
        else if (clock != clock0) {
            /* a CPU-second is not a wall-second: no common time axis */
            fprintf(stderr, "svet converge: %s is timed by the %s clock, %s "
                            "by the %s clock: times on different clocks do "
                            "not compare\n", files[i],
                    converge_clock_name(clock), files[0],
                    converge_clock_name(clock0));
            rc = SVET_EXIT_INPUT;
            goto done;
        }
    }
    const char *unit = clock0 == CONVERGE_CPU ? "CPU-s" : "s";
    if (!(T > 0)) {
        T = s[0].p[s[0].n - 1].seconds;
        for (int i = 1; i < nfiles; i++)
            T = fmin(T, s[i].p[s[i].n - 1].seconds);
    }
    if (!(E > 0))
        E = converge_error_at(s[0].p, s[0].n, m, T, NULL);
    double eff0 = converge_efficiency(&s[0].p[s[0].n - 1], m);
    double t0 = converge_time_to(s[0].p, s[0].n, m, E, NULL);
    const char *what = m == CONVERGE_REL ? "relative RMSE" : "RMSE";
    printf("Times on the %s clock%s. Error at %.3g %s, and time to reach the "
           "%s of %.3g that the baseline (%s) reaches at %.3g %s; the "
           "reference's noise removed; efficiency 1/(variance x time) with "
           "the %s variance. ~ marks a value extrapolated by MSE = bias^2 + "
           "c/t; <= a method whose first point already reaches the error "
           "(its time to it is at most that point's).\n\n", converge_clock_name(clock0),
           clock0 == CONVERGE_CPU ? " (CPU-seconds, all threads together)"
                                  : "",
           T, unit, what, E, s[0].method, T, unit,
           m == CONVERGE_REL ? "relative" : "absolute");
    printf("| method | spp | %s at %.3g %s | time to %.3g | speed-up | "
           "efficiency | x baseline | rays/%s | biased? |\n", what, T, unit,
           E, unit);
    printf("|---|---:|---:|---:|---:|---:|---:|---:|---|\n");
    for (int i = 0; i < nfiles; i++) {
        const converge_point_t *p = s[i].p, *last = &p[s[i].n - 1];
        converge_how he, ht;
        double e = converge_error_at(p, s[i].n, m, T, &he);
        double t = converge_time_to(p, s[i].n, m, E, &ht);
        double bias, eff = converge_efficiency(last, m);
        bool biased = converge_biased(p, s[i].n, m, &bias);
        char ts[64], sp[64], bs[64];
        /* reached at the first point already: the 1/t law read backwards
         * would leave out a method's fixed cost (a pre-pass), so the
         * report says only that the first point reaches the error */
        bool first = ht == CONVERGE_EXTRAPOLATED && t < p[0].seconds;
        if (first && t >= p[0].seconds * (1 - 1e-9)) {
            first = false; /* the first point itself, up to rounding */
            t = p[0].seconds;
            ht = CONVERGE_MEASURED;
        }
        if (first) {
            t = p[0].seconds;
            snprintf(ts, sizeof ts, "<= %.3g %s", t, unit);
        } else {
            fmt_time(ts, sizeof ts, t, ht, unit);
        }
        if (isfinite(t) && t > 0 && isfinite(t0))
            snprintf(sp, sizeof sp, "%s%.2f", first ? ">= " : "", t0 / t);
        else
            snprintf(sp, sizeof sp, "-");
        if (biased)
            snprintf(bs, sizeof bs, "**yes**, ~%.3g", bias);
        else
            snprintf(bs, sizeof bs, "no");
        printf("| %s | %ld | %s%.3g | %s | %s | %.3g | %.2f | %.3g | %s |\n",
               s[i].method, last->spp, how_mark(he), e, ts, sp, eff,
               eff0 > 0 ? eff / eff0 : 0.0,
               last->seconds > 0 ? last->rays / last->seconds : 0.0, bs);
    }
done:
    for (int i = 0; i < nfiles; i++)
        free(s[i].p);
    free(s);
    return rc;
}

/* ------------------------------------------------------------------------ */

/* The spp recorded in a reference's description "<REF>.txt" (the
 * "spp = N" line of tools/reference.sh), or 0. */
static double spp_from_description(const char *ref)
{
    char *path = cmd_replace_ext(ref, ".txt");
    FILE *f = NULL;
    svet_error err;
    if (path && fileio_open_read(path, &f, &err) != SVET_OK)
        f = NULL; /* no description (or not a regular file): no spp */
    free(path);
    if (!f)
        return 0;
    char line[1024];
    double spp = 0;
    while (fgets(line, sizeof line, f))
        if (strncmp(line, "spp = ", 6) == 0)
            spp = strtod(line + 6, NULL);
    fclose(f);
    return spp > 0 ? spp : 0;
}

/* Radiance images and their variances are finite and never negative; a
 * file holding other values is corrupt (OpenEXR 3.1's ZIP writer stores a
 * chunk whose deflated size equals its raw size without marking it, and
 * such a chunk reads back as noise: openexr issue 2306). False, with a
 * message, at the first bad value. */
static bool values_ok(const image_t *img, const char *path)
{
    for (int y = 0; y < img->height; y++)
        for (int x = 0; x < img->width; x++)
            for (int c = 0; c < 3; c++) {
                float v = image_at(img, x, y)[c];
                if (!isfinite(v) || v < 0) {
                    fprintf(stderr, "svet converge: %s: value %g at (%d, %d) "
                                    "channel %d: a radiance or variance is "
                                    "finite and >= 0; the file is corrupt\n",
                            path, (double)v, x, y, c);
                    return false;
                }
            }
    return true;
}

/* --ztest: the test of tests/render/test_reference.c on two image files. */
static int ztest_files(const char *img_path, const char *var_path,
                       double spp, const char *ref_path,
                       const char *ref_var_path, double ref_spp,
                       const char *pvalue_path,
                       const image_read_limits_t *lim)
{
    image_t img, var, ref, rvar, pv;
    memset(&img, 0, sizeof img);
    memset(&var, 0, sizeof var);
    memset(&ref, 0, sizeof ref);
    memset(&rvar, 0, sizeof rvar);
    memset(&pv, 0, sizeof pv);
    char *vdef = var_path ? NULL : cmd_replace_ext(img_path, "-var.exr");
    char *rdef = ref_var_path ? NULL : cmd_replace_ext(ref_path, "-var.exr");
    var_path = var_path ? var_path : vdef;
    ref_var_path = ref_var_path ? ref_var_path : rdef;
    if (!(ref_spp > 0))
        ref_spp = spp_from_description(ref_path);
    int rc = SVET_EXIT_OK;
    svet_error err;
    if (!var_path || !ref_var_path) {
        fprintf(stderr, "svet converge: out of memory\n");
        rc = SVET_EXIT_INPUT;
        goto done;
    }
    const cmd_file_t outs[] = { { pvalue_path, "the p-value image" } };
    const cmd_file_t ins[] = { { img_path, "the image" },
                               { var_path, "its variance" },
                               { ref_path, "the reference" },
                               { ref_var_path, "the reference's variance" } };
    rc = cmd_check_outputs("converge", outs, 1, ins, 4);
    if (rc != SVET_EXIT_OK)
        goto done;
    if (exrio_read_with(img_path, &img, lim, &err) != SVET_OK ||
        exrio_read_with(var_path, &var, lim, &err) != SVET_OK ||
        exrio_read_with(ref_path, &ref, lim, &err) != SVET_OK ||
        exrio_read_with(ref_var_path, &rvar, lim, &err) != SVET_OK) {
        fprintf(stderr, "svet converge: %s\n", err.msg);
        rc = SVET_EXIT_INPUT;
        goto done;
    }
    if (!values_ok(&img, img_path) || !values_ok(&var, var_path) ||
        !values_ok(&ref, ref_path) || !values_ok(&rvar, ref_var_path)) {
        rc = SVET_EXIT_INPUT;
        goto done;
    }
    ztest_image_t A = { &img, &var, spp }, B = { &ref, &rvar, ref_spp };
    ztest_params_t p;
    ztest_params_default(&p);
    ztest_result_t res;
    if (ztest_run(&A, &B, &p, &res, pvalue_path ? &pv : NULL, &err) !=
        SVET_OK) {
        fprintf(stderr, "svet converge: %s\n", err.msg);
        rc = SVET_EXIT_INPUT;
        goto done;
    }
    printf("# z-test of %s (%g spp) against %s (%g spp): alpha %g over "
           "%ld values, per-value significance %.3g; a level passes when "
           "%g%% of its cells pass\n", img_path, spp, ref_path, ref_spp,
           p.alpha, res.values, res.threshold, 100 * p.min_pass);
    if (!(spp > 0) || !(ref_spp > 0))
        printf("# (an spp is unknown: no variance floor)\n");
    printf("block cells failed min_p worst_z pass\n");
    for (int l = 0; l < res.nlevels; l++) {
        const ztest_level_t *L = &res.level[l];
        printf("%d %ld %ld %.4g %+.4g %s\n", L->block, L->cells, L->failed,
               L->min_p, L->worst_z, L->pass ? "yes" : "NO");
    }
    printf("%s\n", res.pass ? "pass" : "FAIL");
    if (pvalue_path && exrio_write(pvalue_path, &pv, EXRIO_FLOAT, EXRIO_ZIP,
                                   &err) != SVET_OK) {
        fprintf(stderr, "svet converge: %s\n", err.msg);
        rc = SVET_EXIT_OUTPUT;
        goto done;
    }
    if (!res.pass)
        rc = SVET_EXIT_DIFFERENT;
done:
    image_free(&img);
    image_free(&var);
    image_free(&ref);
    image_free(&rvar);
    image_free(&pv);
    free(vdef);
    free(rdef);
    return rc;
}

/* ------------------------------------------------------------------------ */

typedef struct {
    render_t *r;
    const image_t *ref, *ref_var;
    converge_point_t *pts;
    int n;
    double render_secs;   /* set-up + passes so far, on `clock` */
    converge_clock clock;
    int threads;
    bool quiet;
} run_t;

static double clock_now(converge_clock c)
{
    return c == CONVERGE_CPU ? cmd_cpu_now() : cmd_now();
}

/* Render up to spp_end samples and add them to the render clock. */
static void render_to(run_t *u, long spp_end)
{
    double t = clock_now(u->clock);
    render_pass(u->r, spp_end, u->threads, NULL, NULL);
    u->render_secs += clock_now(u->clock) - t;
}

/* Measure the image as it is, append a point and rewrite the CSV (so an
 * interrupted series keeps its points). */
static svet_status measure(run_t *u, const char *csv, const char *method,
                           const char *comment, svet_error *err)
{
    image_t img, var;
    svet_status st = render_image(u->r, &img, err);
    if (st != SVET_OK)
        return st;
    st = render_variance(u->r, &var, err);
    if (st != SVET_OK) {
        image_free(&img);
        return st;
    }
    converge_point_t *p = &u->pts[u->n];
    memset(p, 0, sizeof *p);
    p->spp = u->r->spp_done;
    p->seconds = u->render_secs;
    p->rays = (double)u->r->stats.rays;
    st = converge_measure(&img, &var, u->ref, u->ref_var, p, err);
    image_free(&img);
    image_free(&var);
    if (st != SVET_OK)
        return st;
    u->n++;
    if (!u->quiet)
        fprintf(stderr, "  %6ld spp  %8.3f %s  RMSE %.4g  relative RMSE "
                        "%.4g  (noise removed)  efficiency %.3g\n",
                p->spp, p->seconds,
                u->clock == CONVERGE_CPU ? "CPU-s" : "s",
                converge_error(p, CONVERGE_ABS),
                converge_error(p, CONVERGE_REL),
                converge_efficiency(p, CONVERGE_REL));
    return converge_csv_write(csv, method, comment, u->clock, u->pts, u->n,
                              err);
}

/* The time-budget series: passes sized from the measured rate so that
 * each ends near the next budget, growing at most twofold (the first
 * pass may have been slow to start). The first pass takes 2 samples, the
 * fewest with a variance estimate. */
static svet_status run_times(run_t *u, const double *budget, int nb,
                             const char *csv, const char *method,
                             const char *comment, svet_error *err)
{
    for (int k = 0; k < nb; k++) {
        while (u->render_secs < budget[k] && u->r->spp_done < SCENE_MAX_SPP) {
            long done = u->r->spp_done, step = 2;
            if (done > 0) {
                double rate = (double)done / u->render_secs;
                double want = (budget[k] - u->render_secs) * rate;
                step = want < 1 ? 1 : want > (double)done ? done : (long)want;
            }
            if (step > SCENE_MAX_SPP - done)
                step = SCENE_MAX_SPP - done;
            render_to(u, done + step);
        }
        svet_status st = measure(u, csv, method, comment, err);
        if (st != SVET_OK)
            return st;
    }
    return SVET_OK;
}

static svet_status run_spps(run_t *u, const double *spp, int ns,
                            const char *csv, const char *method,
                            const char *comment, svet_error *err)
{
    for (int k = 0; k < ns; k++) {
        render_to(u, (long)spp[k]);
        svet_status st = measure(u, csv, method, comment, err);
        if (st != SVET_OK)
            return st;
    }
    return SVET_OK;
}

/* The name `render integrator NAME` gives: a part's method (volpath,
 * volsingle, photon, ...) or the core's integrator. */
static const char *integrator_name(const scene_render_t *rs)
{
    if (rs->method)
        return rs->method->name;
    switch (rs->integrator) {
    case SCENE_INTEGRATOR_PATH: return "path";
    case SCENE_INTEGRATOR_DIRECT: return "direct";
    case SCENE_INTEGRATOR_BSDF: return "bsdf";
    case SCENE_INTEGRATOR_AO: return "ao";
    case SCENE_INTEGRATOR_NEE: return "nee";
    }
    return "?";
}

static int opt_label(void *args, const char *cmd, const char *opt,
                     const char *v)
{
    (void)cmd, (void)opt;
    if (!label_ok(v)) {
        fprintf(stderr, "svet converge: --label '%s': use letters, digits "
                        "and . _ = + - only\n", v);
        return SVET_EXIT_USAGE;
    }
    ((cmd_converge_args_t *)args)->label = v;
    return SVET_EXIT_OK;
}

/* --spp-list and --time-list, one of them once */
static int opt_list(void *args, const char *cmd, const char *opt,
                    const char *v)
{
    (void)cmd;
    cmd_converge_args_t *o = args;
    o->time_mode = !strcmp(opt, "--time-list");
    if (o->have_list) {
        fprintf(stderr, "svet converge: give one of --spp-list and "
                        "--time-list, once\n");
        return SVET_EXIT_USAGE;
    }
    if (!parse_list(v, o->list, &o->nlist, !o->time_mode) ||
        (!o->time_mode && o->list[o->nlist - 1] > (double)SCENE_MAX_SPP)) {
        fprintf(stderr, "svet converge: %s '%s': expected at most %d "
                        "increasing positive %s, separated by commas\n", opt,
                v, MAX_POINTS, o->time_mode ? "numbers" : "whole numbers");
        return SVET_EXIT_USAGE;
    }
    o->have_list = true;
    return SVET_EXIT_OK;
}

/* --time and --error: a positive number */
static int opt_budget(void *args, const char *cmd, const char *opt,
                      const char *v)
{
    cmd_converge_args_t *o = args;
    double x;
    if (!cmd_parse_double(v, &x) || !(x > 0))
        return cmd_bad_value(cmd, opt, v);
    *(!strcmp(opt, "--time") ? &o->T : &o->E) = x;
    return SVET_EXIT_OK;
}

/* --spp and --ref-spp: a positive count, at most 1e12 */
static int opt_count(void *args, const char *cmd, const char *opt,
                     const char *v)
{
    cmd_converge_args_t *o = args;
    double x;
    if (!cmd_parse_double(v, &x) || !(x > 0) || x > 1e12)
        return cmd_bad_value(cmd, opt, v);
    *(!strcmp(opt, "--spp") ? &o->zspp : &o->ref_spp) = x;
    return SVET_EXIT_OK;
}

static int opt_metric(void *args, const char *cmd, const char *opt,
                      const char *v)
{
    cmd_converge_args_t *o = args;
    if (!strcmp(v, "rel"))
        o->metric = CONVERGE_REL;
    else if (!strcmp(v, "abs"))
        o->metric = CONVERGE_ABS;
    else
        return cmd_bad_value(cmd, opt, v);
    return SVET_EXIT_OK;
}

static int opt_clock(void *args, const char *cmd, const char *opt,
                     const char *v)
{
    cmd_converge_args_t *o = args;
    if (!strcmp(v, "wall"))
        o->clock = CONVERGE_WALL;
    else if (!strcmp(v, "cpu"))
        o->clock = CONVERGE_CPU;
    else
        return cmd_bad_value(cmd, opt, v);
    return SVET_EXIT_OK;
}

static int file_arg(void *args, const char *cmd, const char *a)
{
    (void)cmd;
    cmd_converge_args_t *o = args;
    if (o->nfiles == CMD_CONVERGE_MAX_FILES) {
        fprintf(stderr, "svet converge: at most %d files\n",
                CMD_CONVERGE_MAX_FILES);
        return SVET_EXIT_USAGE;
    }
    o->files[o->nfiles++] = a;
    return SVET_EXIT_OK;
}

#define AT(f) offsetof(cmd_converge_args_t, f)
static const cmd_option_t options[] = {
    { "--no-plot", NULL, false, CMD_SET_TRUE, AT(no_plot), NULL },
    { "--quiet", "-q", false, CMD_SET_TRUE, AT(quiet), NULL },
    { "--report", NULL, false, CMD_SET_TRUE, AT(report), NULL },
    { "--ref", NULL, true, CMD_SET_FILE, AT(ref), NULL },
    { "--ref-var", NULL, true, CMD_SET_FILE, AT(ref_var), NULL },
    { "--out", NULL, true, CMD_SET_FILE, AT(out_dir), NULL },
    { "--label", NULL, true, CMD_CALL, 0, opt_label },
    { "--plot-script", NULL, true, CMD_SET_FILE, AT(script), NULL },
    { "--spp-list", NULL, true, CMD_CALL, 0, opt_list },
    { "--time-list", NULL, true, CMD_CALL, 0, opt_list },
    { "--time", NULL, true, CMD_CALL, 0, opt_budget },
    { "--error", NULL, true, CMD_CALL, 0, opt_budget },
    { "--ztest", NULL, true, CMD_SET_FILE, AT(ztest_img), NULL },
    { "--var", NULL, true, CMD_SET_FILE, AT(ztest_var), NULL },
    { "--pvalue", NULL, true, CMD_SET_FILE, AT(pvalue), NULL },
    { "--spp", NULL, true, CMD_CALL, 0, opt_count },
    { "--ref-spp", NULL, true, CMD_CALL, 0, opt_count },
    { "--max-pixels", NULL, true, CMD_SET_TEXT, AT(max_pixels), NULL },
    { "--metric", NULL, true, CMD_CALL, 0, opt_metric },
    { "--clock", NULL, true, CMD_CALL, 0, opt_clock },
    { NULL, NULL, false, CMD_SET_TRUE, 0, NULL }
};
#undef AT

int cmd_converge_parse(int argc, char **argv, cmd_converge_args_t *o)
{
    memset(o, 0, sizeof *o);
    o->out_dir = "out/converge";
    o->script = DEFAULT_SCRIPT;
    o->metric = CONVERGE_REL;
    o->clock = CONVERGE_WALL;
    cmd_scene_opts_init(&o->so);
    const cmd_parser_t p = { "converge", options, o, file_arg,
                             cmd_converge_help, &o->so, false, NULL };
    int rc = cmd_parse_options(&p, argc, argv);
    if (rc != CMD_RUN)
        return rc;
    if (o->ztest_img) {
        if (!o->ref || !(o->zspp > 0) || o->nfiles) {
            fprintf(stderr, "svet converge: --ztest IMAGE.exr needs --spp N "
                            "and --ref REF.exr, and no other files\n");
            return SVET_EXIT_USAGE;
        }
    } else if (o->report) {
        if (o->nfiles == 0) {
            fprintf(stderr, "svet converge: --report needs CSV files\n");
            return SVET_EXIT_USAGE;
        }
    } else if (o->nfiles != 1) {
        fprintf(stderr, "svet converge: %s (svet converge --help)\n",
                o->nfiles ? "one scene at a time (--report reads CSV files)"
                          : "no scene file");
        return SVET_EXIT_USAGE;
    } else if (!o->ref) {
        fprintf(stderr, "svet converge: --ref REF.exr is required\n");
        return SVET_EXIT_USAGE;
    }
    return CMD_RUN;
}

int cmd_converge(int argc, char **argv)
{
    cmd_converge_args_t o;
    int rc = cmd_converge_parse(argc, argv, &o);
    if (rc != CMD_RUN)
        return rc;
    image_read_limits_t lim;
    if (cmd_read_limits("converge", o.max_pixels, &lim) != SVET_EXIT_OK)
        return SVET_EXIT_USAGE;
    if (o.ztest_img)
        return ztest_files(o.ztest_img, o.ztest_var, o.zspp, o.ref,
                           o.ref_var, o.ref_spp, o.pvalue, &lim);
    if (o.report)
        return report(o.nfiles, o.files, o.metric, o.T, o.E);
    const char *scene_path = o.files[0], *ref_path = o.ref,
               *ref_var_path = o.ref_var, *out_dir = o.out_dir;
    const bool quiet = o.quiet;
    double *list = o.list;
    int nlist = o.nlist;

    svet_error err;
    svet_error_clear(&err);
    scene_t scene;
    image_t ref, ref_var;
    memset(&ref, 0, sizeof ref);
    memset(&ref_var, 0, sizeof ref_var);
    bool have_var = false, r_live = false;
    render_t r;
    char *stem = NULL, *var_default = NULL, *csv = NULL, *png = NULL,
         *comment = NULL;
    converge_point_t pts[MAX_POINTS];
    char method[256];

    rc = cmd_scene_load("converge", &scene, scene_path, &o.so);
    if (rc != SVET_EXIT_OK)
        goto done;
    if (!ref_var_path) {
        var_default = cmd_replace_ext(ref_path, "-var.exr");
        if (var_default && file_exists(var_default))
            ref_var_path = var_default;
    }
    stem = scene_stem(scene_path);
    if (!stem) {
        rc = SVET_EXIT_OUTPUT;
        goto done;
    }
    if (o.label)
        snprintf(method, sizeof method, "%s", o.label);
    else
        make_label(method, sizeof method, stem, o.so.sets, o.so.nsets);
    size_t dn = strlen(out_dir) + strlen(method) + 8;
    csv = malloc(dn);
    png = malloc(dn);
    comment = malloc(8192);
    if (!csv || !png || !comment) {
        fprintf(stderr, "svet converge: out of memory\n");
        rc = SVET_EXIT_OUTPUT;
        goto done;
    }
    snprintf(csv, dn, "%s/%s.csv", out_dir, method);
    snprintf(png, dn, "%s/%s.png", out_dir, method);
    const cmd_file_t outs[] = { { csv, "the CSV output" },
                                { o.no_plot ? NULL : png, "the plot" } };
    const cmd_file_t ins[] = { { scene_path, "the scene file" },
                               { ref_path, "the reference" },
                               { ref_var_path, "the reference's variance" },
                               { o.script, "the gnuplot script" } };
    rc = cmd_check_outputs("converge", outs, 2, ins, o.no_plot ? 3 : 4);
    if (rc != SVET_EXIT_OK)
        goto done;
    if (exrio_read_with(ref_path, &ref, &lim, &err) != SVET_OK) {
        fprintf(stderr, "svet converge: %s\n", err.msg);
        rc = SVET_EXIT_INPUT;
        goto done;
    }
    if (ref_var_path) {
        if (exrio_read_with(ref_var_path, &ref_var, &lim, &err) != SVET_OK) {
            fprintf(stderr, "svet converge: %s\n", err.msg);
            rc = SVET_EXIT_INPUT;
            goto done;
        }
        have_var = true;
    }
    /* the reference's size, when the view is the same */
    scene_camera_t *cam = &scene.camera;
    if (cam->width != ref.width || cam->height != ref.height) {
        if ((long)cam->width * ref.height != (long)cam->height * ref.width) {
            fprintf(stderr, "svet converge: the reference %s is %d x %d, the "
                            "scene %d x %d: another aspect ratio\n", ref_path,
                    ref.width, ref.height, cam->width, cam->height);
            rc = SVET_EXIT_INPUT;
            goto done;
        }
        if (!quiet)
            fprintf(stderr, "svet converge: rendering at the reference's "
                            "%d x %d (the scene says %d x %d)\n", ref.width,
                    ref.height, cam->width, cam->height);
        cam->width = ref.width;
        cam->height = ref.height;
    }
    if (!o.have_list) {
        for (long s = 1; s <= scene.render.spp && nlist < MAX_POINTS; s *= 2)
            list[nlist++] = (double)s;
    }
    make_dirs(out_dir);

    double t0 = clock_now(o.clock);
    if (scene_validate(&scene, &err) != SVET_OK ||
        render_init(&r, &scene, &err) != SVET_OK) {
        fprintf(stderr, "svet converge: %s: %s\n", scene_path, err.msg);
        rc = SVET_EXIT_INPUT;
        goto done;
    }
    r_live = true;
    run_t u = { &r, &ref, have_var ? &ref_var : NULL, pts, 0,
                clock_now(o.clock) - t0, o.clock, scene.render.threads,
                quiet };

    int len = snprintf(comment, 8192,
        "svet converge %s --ref %s%s%s: %s\n"
        "method %s: seed %llu, %d x %d, integrator %s, maxdepth %d, "
        "roulette %s, %s build "
        "(%s)\n"
        "accel: %s\n"
        "threads %d (0 = every core); %s = %s render set-up "
        "and passes, measurements excluded\n"
        "rmse_noref = sqrt(mse - ref_variance); bias2 = mse - variance - "
        "ref_variance; efficiency = 1/(variance x seconds); PSNR peak %g",
        scene_path, ref_path, ref_var_path ? " --ref-var " : "",
        ref_var_path ? ref_var_path : "",
        o.time_mode ? "time budgets" : "sample counts", method,
        (unsigned long long)scene.render.seed, cam->width, cam->height,
        integrator_name(&scene.render),
        scene.render.max_depth, scene.render.roulette ? "on" : "off",
        REAL_NAME, __VERSION__, r.accel_choice, scene.render.threads,
        converge_clock_column(o.clock),
        o.clock == CONVERGE_CPU ? "CPU time (all threads) of the"
                                : "wall-clock",
        CONVERGE_PSNR_PEAK);
    for (int i = 0; i < o.so.nsets && len > 0 && len < 8000; i++)
        len += snprintf(comment + len, 8192 - (size_t)len, "%s--set %s",
                        i ? " " : "\nsettings: ", o.so.sets[i]);

    if (!quiet)
        fprintf(stderr, "svet converge: %s (%s) against %s\n", scene_path,
                method, ref_path);
    svet_status st = o.time_mode
        ? run_times(&u, list, nlist, csv, method, comment, &err)
        : run_spps(&u, list, nlist, csv, method, comment, &err);
    if (st != SVET_OK) {
        fprintf(stderr, "svet converge: %s\n", err.msg);
        rc = st == SVET_ERR_IO || st == SVET_ERR_NOMEM ? SVET_EXIT_OUTPUT
                                                       : SVET_EXIT_INPUT;
        goto done;
    }
    const converge_point_t *last = &pts[u.n - 1];
    double bias;
    bool biased = converge_biased(pts, u.n, CONVERGE_REL, &bias);
    printf("%s: %d points, %ld spp in %.3g %s; with the reference's noise "
           "removed: RMSE %.4g, relative RMSE %.4g; efficiency "
           "1/(variance x time) %.4g (relative variance); %s; wrote %s\n",
           method, u.n, last->spp, last->seconds,
           o.clock == CONVERGE_CPU ? "CPU-s" : "s",
           converge_error(last, CONVERGE_ABS),
           converge_error(last, CONVERGE_REL),
           converge_efficiency(last, CONVERGE_REL),
           biased ? "BIASED: the error stops falling" : "no bias seen", csv);
    if (biased)
        printf("%s: estimated relative bias %.4g (the floor of the relative "
               "RMSE)\n", method, bias);
    if (!o.no_plot)
        plot(o.script, csv, png, method, o.clock, quiet);
done:
    if (r_live)
        render_free(&r);
    image_free(&ref);
    image_free(&ref_var);
    scene_free(&scene);
    free(stem);
    free(var_default);
    free(csv);
    free(png);
    free(comment);
    return rc;
}
