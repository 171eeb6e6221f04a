/*
 * test_reference.c - the image regression test of the shipped scenes: each
 * converged reference of tests/reference/ (make reference) against a fresh
 * render at a low sample count, by the Z-test of ztest.h (per pixel as in
 * Mitsuba 3's test_renders.py, and on blocks up to the whole image); the
 * test must fail on a biased render (max depth 1; the image scaled by 1.05);
 * and what docs/determinism.md promises: the same bits for a repeated run
 * and for any thread count and pass split, and through an EXR file.
 * On a failure the render, its error and its p-values go to
 * out/test_reference/ (never into the tree).
 */
#include "testutil.h"
#include "io/exrio.h"
#include "stats/imgcompare.h"
#include "render/render.h"
#include "render/scenefile.h"
#include "stats/ztest.h"
#include "imgtest.h"

#include <dirent.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define OUT_DIR "out/test_reference"
#define MAX_REFS 64

/* Camera samples per scene for the test render: 2^18, 16 spp on a
 * 128 x 128 reference; about 0.1-0.4 s on one core of an x86-64 at -O2.
 * Enough for the whole-image level to see a 5 % bias: its z is
 * 0.05 mean / (sigma / sqrt(2^18)), about 10 for a per-sample relative
 * deviation sigma / mean of 2.5 (the Cornell box's is below 2). */
#define TEST_SAMPLES (1L << 18)

/* Where the references are: tests/reference, or $SVET_REFERENCE_DIR (to
 * check another set, e.g. one made by a port). */
static const char *ref_dir(void)
{
    const char *d = getenv("SVET_REFERENCE_DIR");
    return d && *d ? d : "tests/reference";
}

/* The references found, by name (cbox for tests/reference/cbox.txt). */
static char refs[MAX_REFS][64];
static int nrefs;

static int cmp_names(const void *a, const void *b)
{
    return strcmp(a, b);
}

static void find_references(void)
{
    DIR *d = opendir(ref_dir());
    if (!d)
        return;
    struct dirent *e;
    while ((e = readdir(d)) != NULL && nrefs < MAX_REFS) {
        size_t n = strlen(e->d_name);
        if (n > 4 && n < sizeof refs[0] + 4 &&
            strcmp(e->d_name + n - 4, ".txt") == 0) {
            memcpy(refs[nrefs], e->d_name, n - 4);
            refs[nrefs][n - 4] = '\0';
            nrefs++;
        }
    }
    closedir(d);
    qsort(refs, (size_t)nrefs, sizeof refs[0], cmp_names);
}

/* What NAME.txt says (tools/reference.sh writes it). */
typedef struct {
    char name[64];
    char scene[512];
    long spp;
    unsigned long long seed;
    image_t mean, var;
} reference_t;

/* Radiance and variance are finite and never negative. A file that holds
 * other values is corrupt: OpenEXR 3.1's ZIP writer stores a chunk whose
 * deflated size equals its raw size without marking it (fixed upstream in
 * 2026, openexr issue 2306), and such a chunk reads back as noise. */
static void check_values(const image_t *img, const char *what,
                         const char *name)
{
    for (int y = 0; y < img->height; y++)
        for (int x = 0; x < img->width; x++)
            for (int c = 0; c < 3; c++) {
                float v = image_at(img, x, y)[c];
                ck_assert_msg(isfinite(v) && v >= 0, "%s/%s%s.exr: value %g "
                              "at (%d, %d): the file is corrupt (make "
                              "reference)", ref_dir(), name, what,
                              (double)v, x, y);
            }
}

static void load_reference(reference_t *r, const char *name)
{
    memset(r, 0, sizeof *r);
    snprintf(r->name, sizeof r->name, "%s", name);
    char path[512];
    snprintf(path, sizeof path, "%s/%s.txt", ref_dir(), name);
    FILE *f = fopen(path, "r");
    ck_assert_msg(f != NULL, "cannot open %s (run from the top directory)",
                  path);
    char line[2048];
    r->spp = -1;
    bool have_seed = false;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = '\0';
        char *eq = strstr(line, " = ");
        if (line[0] == '#' || !eq)
            continue;
        *eq = '\0';
        const char *v = eq + 3;
        if (!strcmp(line, "scene"))
            snprintf(r->scene, sizeof r->scene, "%s", v);
        else if (!strcmp(line, "spp"))
            r->spp = strtol(v, NULL, 10);
        else if (!strcmp(line, "seed"))
            r->seed = strtoull(v, NULL, 10), have_seed = true;
    }
    fclose(f);
    ck_assert_msg(r->scene[0] && r->spp > 0 && have_seed,
                  "%s: needs 'scene', 'spp' and 'seed' lines", path);
    svet_error err;
    snprintf(path, sizeof path, "%s/%s.exr", ref_dir(), name);
    ck_assert_msg(exrio_read(path, &r->mean, &err) == SVET_OK, "%s", err.msg);
    snprintf(path, sizeof path, "%s/%s-var.exr", ref_dir(), name);
    ck_assert_msg(exrio_read(path, &r->var, &err) == SVET_OK, "%s", err.msg);
    check_values(&r->mean, "", name);
    check_values(&r->var, "-var", name);
}

static void free_reference(reference_t *r)
{
    image_free(&r->mean);
    image_free(&r->var);
}

/* The reference's scene at the reference's size, with a seed other than
 * the reference's: the test's samples must be independent of it. */
static void load_scene(scene_t *s, const reference_t *r, int width,
                       int height)
{
    svet_error err;
    scene_init(s);
    ck_assert_msg(scenefile_read(s, r->scene, &err) == SVET_OK, "%s",
                  err.msg);
    s->camera.width = width;
    s->camera.height = height;
    s->render.seed = r->seed + 1;
    s->render.threads = 0;
}

typedef struct {
    image_t mean, var;
    long spp;
} rendered_t;

static void render_scene(const scene_t *s, long spp, rendered_t *out)
{
    render_t r;
    svet_error err;
    ck_assert_msg(render_init(&r, s, &err) == SVET_OK, "%s", err.msg);
    render_pass(&r, spp, 0, NULL, NULL);
    ck_assert_int_eq(render_image(&r, &out->mean, &err), SVET_OK);
    ck_assert_int_eq(render_variance(&r, &out->var, &err), SVET_OK);
    out->spp = spp;
    render_free(&r);
}

static void free_rendered(rendered_t *x)
{
    image_free(&x->mean);
    image_free(&x->var);
}

static long test_spp(const reference_t *r)
{
    long px = (long)r->mean.width * r->mean.height;
    long spp = TEST_SAMPLES / px;
    return spp < 4 ? 4 : spp;
}

static void make_dir(const char *path)
{
    if (mkdir(path, 0777) != 0 && errno != EEXIST)
        ck_abort_msg("cannot make %s: %s", path, strerror(errno));
}

/* Write what a failing comparison shows: the render, |render - reference|
 * and the per-pixel p-values, as OUT_DIR/<tag>-{render,error,pvalue}.exr.
 * Returns the path prefix. */
static const char *write_failure(const char *tag, const rendered_t *x,
                                 const reference_t *r, const image_t *pv)
{
    static char prefix[512];
    make_dir("out");
    make_dir(OUT_DIR);
    snprintf(prefix, sizeof prefix, OUT_DIR "/%s", tag);
    char path[600];
    svet_error err;
    image_t e;
    snprintf(path, sizeof path, "%s-render.exr", prefix);
    ck_assert_msg(exrio_write(path, &x->mean, EXRIO_FLOAT, EXRIO_ZIP, &err) ==
                  SVET_OK, "%s", err.msg);
    ck_assert_int_eq(imgcompare_error_image(&x->mean, &r->mean,
                                            IMGCOMPARE_ABS, IMGCOMPARE_EPS,
                                            &e, &err), SVET_OK);
    snprintf(path, sizeof path, "%s-error.exr", prefix);
    ck_assert_msg(exrio_write(path, &e, EXRIO_FLOAT, EXRIO_ZIP, &err) ==
                  SVET_OK, "%s", err.msg);
    image_free(&e);
    snprintf(path, sizeof path, "%s-pvalue.exr", prefix);
    ck_assert_msg(exrio_write(path, pv, EXRIO_FLOAT, EXRIO_ZIP, &err) ==
                  SVET_OK, "%s", err.msg);
    return prefix;
}

/* The Z-test of x against r: prints one line per level, writes the images
 * when it fails. */
static bool compare(const char *tag, const rendered_t *x,
                    const reference_t *r, ztest_result_t *res)
{
    ztest_image_t A = { &x->mean, &x->var, (double)x->spp };
    ztest_image_t B = { &r->mean, &r->var, (double)r->spp };
    ztest_params_t p;
    ztest_params_default(&p);
    image_t pv;
    svet_error err;
    ck_assert_msg(ztest_run(&A, &B, &p, res, &pv, &err) == SVET_OK, "%s",
                  err.msg);
    printf("  %s: %dx%d, %ld spp against %ld; per-value significance %.2g\n",
           tag, r->mean.width, r->mean.height, x->spp, r->spp,
           res->threshold);
    for (int l = 0; l < res->nlevels; l++) {
        const ztest_level_t *L = &res->level[l];
        printf("    blocks of %3d: %6ld cells, %4ld failed (%5.2f%%), "
               "min p %.3g (z %+.3g)%s\n", L->block, L->cells, L->failed,
               100.0 * (double)L->failed / (double)L->cells, L->min_p,
               L->worst_z, L->pass ? "" : "  FAIL");
    }
    if (!res->pass)
        printf("    failed: wrote %s-{render,error,pvalue}.exr\n",
               write_failure(tag, x, r, &pv));
    fflush(stdout);
    image_free(&pv);
    return res->pass;
}

START_TEST(references_exist)
{
    ck_assert_msg(nrefs > 0, "no references in %s (make reference)",
                  ref_dir());
    test_report_cases("references_exist", nrefs);
}
END_TEST

START_TEST(render_agrees_with_its_reference)
{
    reference_t r;
    load_reference(&r, refs[_i]);
    scene_t s;
    load_scene(&s, &r, r.mean.width, r.mean.height);
    rendered_t x;
    render_scene(&s, test_spp(&r), &x);
    ztest_result_t res;
    bool ok = compare(r.name, &x, &r, &res);
    ck_assert_msg(ok, "%s: the render differs from %s/%s.exr beyond its "
                  "noise (see " OUT_DIR "/%s-*.exr; was the scene or the "
                  "renderer changed since make reference?)", r.name,
                  ref_dir(), r.name, r.name);
    free_rendered(&x);
    scene_free(&s);
    free_reference(&r);
}
END_TEST

/* The reference the bias tests use: the Cornell box when it is there. */
static const char *bias_reference(void)
{
    for (int i = 0; i < nrefs; i++)
        if (strcmp(refs[i], "cbox") == 0)
            return refs[i];
    ck_assert_msg(nrefs > 0, "no references (make reference)");
    return refs[0];
}

START_TEST(render_without_indirect_light_fails)
{
    /* Max depth 1 is direct light only: the ceiling of the Cornell box,
     * which the light (facing down) cannot reach, goes black. */
    reference_t r;
    load_reference(&r, bias_reference());
    scene_t s;
    load_scene(&s, &r, r.mean.width, r.mean.height);
    s.render.max_depth = 1;
    rendered_t x;
    render_scene(&s, test_spp(&r), &x);
    char tag[96];
    snprintf(tag, sizeof tag, "%s-maxdepth1", r.name);
    ztest_result_t res;
    ck_assert_msg(!compare(tag, &x, &r, &res),
                  "a direct-light render of %s passed as the full one",
                  r.name);
    /* the failure wrote its images */
    char path[256];
    snprintf(path, sizeof path, OUT_DIR "/%s-pvalue.exr", tag);
    image_t pv;
    ck_assert_msg(exrio_read(path, &pv, NULL) == SVET_OK, "no %s", path);
    ck_assert(pv.width == r.mean.width && pv.height == r.mean.height);
    image_free(&pv);
    free_rendered(&x);
    scene_free(&s);
    free_reference(&r);
}
END_TEST

START_TEST(render_five_percent_too_bright_fails)
{
    /* The same render scaled by 1.05 (its variance by 1.05^2): a bias far
     * below one pixel's noise at this sample count, which the block levels
     * must find (TEST_SAMPLES says why they can). */
    reference_t r;
    load_reference(&r, bias_reference());
    scene_t s;
    load_scene(&s, &r, r.mean.width, r.mean.height);
    rendered_t x;
    render_scene(&s, test_spp(&r), &x);
    size_t n = 3 * (size_t)r.mean.width * (size_t)r.mean.height;
    for (size_t i = 0; i < n; i++) {
        x.mean.px[i] *= 1.05f;
        x.var.px[i] *= 1.05f * 1.05f;
    }
    char tag[96];
    snprintf(tag, sizeof tag, "%s-scaled1.05", r.name);
    ztest_result_t res;
    ck_assert_msg(!compare(tag, &x, &r, &res),
                  "%s scaled by 1.05 passed", r.name);
    free_rendered(&x);
    scene_free(&s);
    free_reference(&r);
}
END_TEST

START_TEST(render_is_the_same_bits_for_any_threads_passes_and_runs)
{
    /* docs/determinism.md: sample s of pixel p depends only on (seed, p,
     * s) and each pixel adds its samples in order, so a render of a
     * shipped scene (through the scene file, the tracer the renderer
     * chooses, the EXR writer) is the same bits run twice, on 1 or 2
     * threads, in one pass or three. */
    reference_t r;
    load_reference(&r, bias_reference());
    scene_t s;
    /* a quarter of the reference's size a side keeps the view */
    int w = r.mean.width / 4 > 0 ? r.mean.width / 4 : 1;
    int h = r.mean.height / 4 > 0 ? r.mean.height / 4 : 1;
    load_scene(&s, &r, w, h);
    render_t a, b, c;
    svet_error err;
    ck_assert_int_eq(render_init(&a, &s, &err), SVET_OK);
    ck_assert_int_eq(render_init(&b, &s, &err), SVET_OK);
    ck_assert_int_eq(render_init(&c, &s, &err), SVET_OK);
    render_pass(&a, 6, 1, NULL, NULL);
    render_pass(&b, 6, 1, NULL, NULL);
    render_pass(&c, 1, 2, NULL, NULL);
    render_pass(&c, 4, 2, NULL, NULL);
    render_pass(&c, 6, 2, NULL, NULL);
    size_t n = (size_t)w * (size_t)h;
    const render_t *other[2] = { &b, &c };
    for (int k = 0; k < 2; k++) {
        ck_assert(memcmp(a.acc.sum, other[k]->acc.sum, 3 * n * sizeof(image_fixed_t))
                  == 0);
        ck_assert(memcmp(a.acc.count, other[k]->acc.count,
                         n * sizeof(uint64_t)) == 0);
        ck_assert(memcmp(a.sum2, other[k]->sum2, 3 * n * sizeof(image_fixed_t)) == 0);
    }
    /* the written file holds the image's bits */
    image_t img, back;
    ck_assert_int_eq(render_image(&a, &img, &err), SVET_OK);
    const char *path = imgtest_path("determinism.exr");
    ck_assert_int_eq(exrio_write(path, &img, EXRIO_FLOAT, EXRIO_ZIP, &err),
                     SVET_OK);
    ck_assert_int_eq(exrio_read(path, &back, &err), SVET_OK);
    ck_assert(back.width == w && back.height == h && back.channels == 3);
    ck_assert(memcmp(img.px, back.px, 3 * n * sizeof(float)) == 0);
    test_report_cases("render_is_the_same_bits_for_any_threads_passes_and_runs",
                      (long)n * 6);
    image_free(&img);
    image_free(&back);
    render_free(&a);
    render_free(&b);
    render_free(&c);
    scene_free(&s);
    free_reference(&r);
}
END_TEST

Suite *test_suite(void)
{
    find_references();
    Suite *s = suite_create("reference images (" REAL_NAME ")");
    TCase *tc = tcase_create("reference");
    /* generous for the sanitizer build (about 10x slower); a normal
     * build takes a few seconds in all */
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, references_exist);
    tcase_add_loop_test(tc, render_agrees_with_its_reference, 0, nrefs);
    if (nrefs > 0) {
        tcase_add_test(tc, render_without_indirect_light_fails);
        tcase_add_test(tc, render_five_percent_too_bright_fails);
        tcase_add_test(
            tc, render_is_the_same_bits_for_any_threads_passes_and_runs);
    }
    suite_add_tcase(s, tc);
    return s;
}
