/*
 * test_subsample.c - app. F's subsampling (src/render/subsample.c): a
 * constant image computes only the coarse pixels; a vertical edge is
 * refined down to the pixels beside it and nowhere else, and the image is
 * exact; a linear ramp is interpolated exactly; a step of 1 computes every
 * pixel; bad steps and thresholds are refused. In the renderer (`render
 * subsample`, render.c): step 1 is the plain render bit for bit; on a
 * constant image every pixel is the plain render's and only the coarse
 * ones are computed; an emitter's edge is refined, the image exact; 1 and
 * 2 threads give the same bits; bad keys are refused with file:line:col,
 * and so are split renders and further passes.
 */
#include "testutil.h"
#include "render/allparts.h"
#include "render/render.h"
#include "render/scenefile.h"
#include "render/subsample.h"

#include <stdlib.h>
#include <string.h>

typedef struct {
    int kind; /* 0 constant, 1 edge between x = 10 and 11, 2 ramp */
    long calls;
} fake_t;

static void pixel(void *c, int x, int y, float out[3])
{
    fake_t *s = c;
    s->calls++;
    float v = s->kind == 0 ? 0.5f
            : s->kind == 1 ? (x <= 10 ? 1.0f : 0.2f)
                           : 0.25f + 0.01f * (float)x + 0.02f * (float)y;
    out[0] = out[1] = out[2] = v;
}

static image_t run(int kind, int w, int h, int step, real thr, uint8_t **mask,
                   long *n)
{
    image_t img;
    ck_assert_int_eq(image_alloc(&img, w, h, 3, NULL), SVET_OK);
    *mask = malloc((size_t)(w * h));
    fake_t s = { kind, 0 };
    subsample_params_t p = { step, thr };
    ck_assert_int_eq(subsample_image(&img, &p, pixel, &s, *mask, n, NULL),
                     SVET_OK);
    ck_assert_int_eq(*n, s.calls); /* each pixel computed at most once */
    return img;
}

START_TEST(a_constant_image_computes_only_the_coarse_pixels)
{
    uint8_t *mask;
    long n;
    image_t img = run(0, 33, 17, 8, REAL_C(0.05), &mask, &n);
    ck_assert_int_eq(n, 5 * 3); /* x = 0, 8, ..., 32; y = 0, 8, 16 */
    for (int y = 0; y < 17; y++)
        for (int x = 0; x < 33; x++) {
            ck_assert_int_eq(mask[y * 33 + x], x % 8 == 0 && y % 8 == 0);
            ck_assert(image_at(&img, x, y)[1] == 0.5f);
        }
    free(mask);
    image_free(&img);
}
END_TEST

START_TEST(an_edge_is_refined_beside_it_and_nowhere_else)
{
    uint8_t *mask;
    long n;
    const int w = 41, h = 25;
    image_t img = run(1, w, h, 8, REAL_C(0.05), &mask, &n);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            /* the image is exact: nothing was interpolated across it */
            ck_assert(image_at(&img, x, y)[0] == (x <= 10 ? 1.0f : 0.2f));
            bool coarse = x % 8 == 0 && y % 8 == 0;
            if (x == 10 || x == 11)
                ck_assert_msg(mask[y * w + x], "(%d, %d) beside the edge "
                              "was not computed", x, y);
            else if (x < 8 || x > 16)
                /* blocks that do not hold the edge stay coarse */
                ck_assert_int_eq(mask[y * w + x], coarse);
        }
    ck_assert_int_lt(n, w * h / 3);
    free(mask);
    image_free(&img);
}
END_TEST

START_TEST(a_ramp_is_interpolated_exactly_and_step_1_computes_all)
{
    uint8_t *mask;
    long n;
    image_t img = run(2, 33, 33, 16, REAL_C(0.9), &mask, &n);
    ck_assert_int_eq(n, 9);
    for (int y = 0; y < 33; y++)
        for (int x = 0; x < 33; x++)
            ck_assert_near(image_at(&img, x, y)[2],
                           0.25 + 0.01 * x + 0.02 * y, 1e-6);
    free(mask);
    image_free(&img);
    img = run(2, 7, 5, 1, REAL_C(0.9), &mask, &n);
    ck_assert_int_eq(n, 35);
    free(mask);
    image_free(&img);
    /* one row, one column, one pixel */
    img = run(1, 20, 1, 4, 0, &mask, &n);
    ck_assert(image_at(&img, 10, 0)[0] == 1.0f && image_at(&img, 11, 0)[0] == 0.2f);
    free(mask);
    image_free(&img);
    img = run(0, 1, 1, 4, 0, &mask, &n);
    ck_assert_int_eq(n, 1);
    free(mask);
    image_free(&img);
}
END_TEST

START_TEST(bad_parameters_are_refused)
{
    image_t img;
    ck_assert_int_eq(image_alloc(&img, 4, 4, 3, NULL), SVET_OK);
    fake_t s = { 0, 0 };
    svet_error e;
    subsample_params_t p = { 6, REAL_C(0.1) };
    ck_assert_int_eq(subsample_image(&img, &p, pixel, &s, NULL, NULL, &e),
                     SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(e.msg, "power of 2"));
    p.step = 4;
    p.threshold = 1;
    ck_assert_int_eq(subsample_image(&img, &p, pixel, &s, NULL, NULL, &e),
                     SVET_ERR_RANGE);
    p.threshold = (real)NAN;
    ck_assert_int_eq(subsample_image(&img, &p, pixel, &s, NULL, NULL, &e),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(s.calls, 0);
    image_free(&img);
}
END_TEST

/* the same pixel function, from two threads: the mask and the image of
 * one thread */
START_TEST(two_threads_give_one_threads_image_and_mask)
{
    const int w = 37, h = 29;
    image_t a, b;
    ck_assert_int_eq(image_alloc(&a, w, h, 3, NULL), SVET_OK);
    ck_assert_int_eq(image_alloc(&b, w, h, 3, NULL), SVET_OK);
    uint8_t *ma = malloc((size_t)(w * h)), *mb = malloc((size_t)(w * h));
    fake_t s = { 1, 0 };
    subsample_params_t p = { 8, REAL_C(0.05) };
    long na, nb;
    bool stopped = true;
    ck_assert_int_eq(subsample_image_threads(&a, &p, pixel, &s, ma, &na, 1,
                                             NULL, &stopped, NULL), SVET_OK);
    ck_assert(!stopped);
    /* calls counted without a lock: only the results are compared */
    fake_t s2 = { 1, 0 };
    ck_assert_int_eq(subsample_image_threads(&b, &p, pixel, &s2, mb, &nb, 2,
                                             NULL, NULL, NULL), SVET_OK);
    ck_assert_int_eq(na, nb);
    ck_assert(memcmp(ma, mb, (size_t)(w * h)) == 0);
    ck_assert(memcmp(a.px, b.px, 3 * (size_t)(w * h) * sizeof *a.px) == 0);
    free(ma);
    free(mb);
    image_free(&a);
    image_free(&b);
}
END_TEST

/* --- in the renderer ------------------------------------------------------ */

/* a --set on a parsed scene */
static void set(scene_t *s, const char *setting)
{
    svet_error e;
    ck_assert_msg(scenefile_override(s, setting, &e) == SVET_OK, "%s",
                  e.msg);
}

static void parse(scene_t *s, const char *text)
{
    svet_error e;
    svet_status st = scenefile_parse_with(s, text, strlen(text), "t.scn",
                                          NULL, scene_features_all(), &e);
    ck_assert_msg(st == SVET_OK, "%s", e.msg);
}

/* Render s with `threads` threads in one pass of spp samples. */
static void render_all(const scene_t *s, int threads, render_t *r,
                       image_t *img)
{
    svet_error e;
    ck_assert_msg(render_init(r, s, &e) == SVET_OK, "%s", e.msg);
    ck_assert_msg(render_pass(r, s->render.spp, threads, NULL, NULL) ==
                      SVET_OK, "%s", r->error.msg);
    ck_assert_int_eq(render_image(r, img, NULL), SVET_OK);
}

static bool same_pixels(const image_t *a, const image_t *b)
{
    return a->width == b->width && a->height == b->height &&
           memcmp(a->px, b->px, 3 * (size_t)a->width * (size_t)a->height *
                                    sizeof *a->px) == 0;
}

/* a lit sphere on a floor: noise and edges everywhere */
static const char *sphere_scene =
    "camera position 0 1 5 target 0 0 0 width 40 height 30\n"
    "render spp 4 maxdepth 3 seed 5\n"
    "material w lambert rho 0.7 0.5 0.3\n"
    "sphere centre 0 0 0 radius 1 material w\n"
    "parallelogram c0 -5 -1 5  c1 5 -1 5  c2 5 -1 -5  c3 -5 -1 -5 "
    "material w\n"
    "light point position 2 2 2 intensity 3\n";

START_TEST(step_1_is_the_plain_render_bit_for_bit)
{
    scene_t s;
    parse(&s, sphere_scene);
    render_t a, b;
    image_t ia, ib;
    render_all(&s, 2, &a, &ia);
    s.render.subsample_step = 1;
    s.render.subsample_threshold = REAL_C(0.5);
    render_all(&s, 2, &b, &ib);
    ck_assert_int_eq(b.sub_computed, 40 * 30);
    ck_assert(same_pixels(&ia, &ib));
    size_t n = 40 * 30;
    ck_assert(memcmp(a.acc.sum, b.acc.sum, 3 * n * sizeof *a.acc.sum) == 0);
    ck_assert(memcmp(a.sum2, b.sum2, 3 * n * sizeof *a.sum2) == 0);
    ck_assert(a.stats.rays == b.stats.rays && a.stats.rays > 0);
    image_free(&ia);
    image_free(&ib);
    render_free(&a);
    render_free(&b);
    scene_free(&s);
}
END_TEST

START_TEST(a_constant_render_is_the_plain_one_from_the_coarse_pixels)
{
    /* a sphere around the camera, emitting on both sides: every sample
     * sees the same radiance */
    scene_t s;
    parse(&s, "camera position 0 0 0 target 0 0 -1 width 33 height 17\n"
              "render spp 3 maxdepth 0\n"
              "material w lambert rho 0\n"
              "sphere centre 0 0 0 radius 10 material w "
              "emit 0.3 0.7 0.123456 twosided\n");
    render_t a, b;
    image_t ia, ib;
    render_all(&s, 2, &a, &ia);
    ck_assert_msg(image_at(&ia, 7, 9)[2] > 0, "the emitter is not seen");
    set(&s, "subsample.step=8");
    set(&s, "subsample.threshold=0.01");
    ck_assert_int_eq(s.render.subsample_step, 8);
    render_all(&s, 2, &b, &ib);
    ck_assert_int_eq(b.sub_computed, 5 * 3);
    for (int y = 0; y < 17; y++)
        for (int x = 0; x < 33; x++)
            ck_assert_int_eq(b.sub_mask[y * 33 + x],
                             x % 8 == 0 && y % 8 == 0);
    ck_assert(same_pixels(&ia, &ib));
    image_free(&ia);
    image_free(&ib);
    render_free(&a);
    render_free(&b);
    scene_free(&s);
}
END_TEST

/* The contrast of two pixels, as subsample.c measures it. */
static double pixel_contrast(const float *a, const float *b)
{
    double worst = 0;
    for (int c = 0; c < 3; c++) {
        double sum = fabs((double)a[c]) + fabs((double)b[c]);
        double d = sum > 0 ? fabs((double)a[c] - (double)b[c]) / sum : 0;
        worst = d > worst ? d : worst;
    }
    return worst;
}

START_TEST(an_emitters_edge_is_refined_and_the_image_exact)
{
    /* an emitter covering the left of the view, black beyond its edge;
     * the pixels the edge crosses are partly covered */
    const int W = 48, H = 24;
    scene_t s;
    parse(&s, "camera position 0 0 5 target 0 0 0 width 48 height 24\n"
              "render spp 8 maxdepth 0\n"
              "material w lambert rho 0\n"
              "parallelogram c0 -20 -20 0  c1 0.37 -20 0  c2 0.37 20 0 "
              "c3 -20 20 0 material w emit 1 2 3\n");
    render_t a, b;
    image_t ia, ib;
    render_all(&s, 2, &a, &ia);
    const real T = REAL_C(0.05);
    set(&s, "subsample.step=8");
    set(&s, "subsample.threshold=0.05");
    render_all(&s, 2, &b, &ib);
    ck_assert(same_pixels(&ia, &ib)); /* nothing interpolated across it */
    int edges = 0, first = W, last = -1;
    for (int y = 0; y < H; y++)
        for (int x = 0; x + 1 < W; x++) {
            const float *p = image_at(&ia, x, y), *q = image_at(&ia, x + 1, y);
            if (pixel_contrast(p, q) > (double)T) {
                edges++;
                first = x < first ? x : first;
                last = x + 1 > last ? x + 1 : last;
                ck_assert_msg(b.sub_mask[y * W + x] &&
                                  b.sub_mask[y * W + x + 1],
                              "(%d, %d) and (%d, %d) beside the edge were "
                              "not both computed", x, y, x + 1, y);
            }
        }
    ck_assert_int_ge(edges, H);
    /* the coarse blocks away from the edge are not refined */
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            if (x < first / 8 * 8 || x > (last + 7) / 8 * 8)
                ck_assert_msg(b.sub_mask[y * W + x] ==
                                  ((x % 8 == 0 || x == W - 1) &&
                                   (y % 8 == 0 || y == H - 1)),
                              "(%d, %d) away from the edge (%d..%d)", x, y,
                              first, last);
    ck_assert_int_lt(b.sub_computed, W * H / 3);
    image_free(&ia);
    image_free(&ib);
    render_free(&a);
    render_free(&b);
    scene_free(&s);
}
END_TEST

START_TEST(a_subsampled_render_is_the_same_on_1_and_2_threads)
{
    scene_t s;
    parse(&s, sphere_scene);
    set(&s, "subsample.step=4");
    set(&s, "subsample.threshold=0.2");
    render_t a, b;
    image_t ia, ib;
    render_all(&s, 1, &a, &ia);
    render_all(&s, 2, &b, &ib);
    ck_assert(same_pixels(&ia, &ib));
    ck_assert(memcmp(a.sub_mask, b.sub_mask, 40 * 30) == 0);
    ck_assert_int_eq(a.sub_computed, b.sub_computed);
    ck_assert(a.sub_computed < 40 * 30 && a.sub_computed > 8 * 11);
    ck_assert(a.stats.rays == b.stats.rays);
    image_free(&ia);
    image_free(&ib);
    render_free(&a);
    render_free(&b);
    scene_free(&s);
}
END_TEST

static void refused(const char *text, const scene_features_t *f,
                    svet_status want, const char *msg)
{
    scene_t s;
    svet_error e;
    svet_status st = scenefile_parse_with(&s, text, strlen(text), "t.scn",
                                          NULL, f, &e);
    ck_assert_msg(st == want, "%s: status %d, %s", text, st, e.msg);
    ck_assert_msg(strstr(e.msg, msg), "%s: '%s' lacks '%s'", text, e.msg,
                  msg);
    scene_free(&s);
}

START_TEST(bad_subsample_keys_are_refused_with_file_and_line)
{
    const scene_features_t *all = scene_features_all();
    refused("render spp 4\nrender subsample step 3\n", all, SVET_ERR_RANGE,
            "t.scn:2:18: 'step' = 3: must be 0 (off) or a power of 2");
    refused("render subsample step 512\n", all, SVET_ERR_RANGE, "t.scn:1:");
    refused("render subsample step -2\n", all, SVET_ERR_RANGE, "t.scn:1:");
    refused("\nrender subsample threshold 1\n", all, SVET_ERR_RANGE,
            "t.scn:2:18: 'threshold' = 1: must lie in [0, 1)");
    refused("render subsample threshold -0.1\n", all, SVET_ERR_RANGE,
            "t.scn:1:");
    refused("render subsample stepp 4\n", all, SVET_ERR_PARSE,
            "t.scn:1:18: unknown parameter of render subsample 'stepp' "
            "(did you mean 'step'?)");
    refused("render subsample step 4 step 8\n", all, SVET_ERR_PARSE,
            "t.scn:1:");
    /* a program built without it (ch. 5) */
    refused("render subsample step 4\n", NULL, SVET_ERR_UNSUPPORTED,
            "t.scn:1:8: 'render subsample': this program was built without "
            "the subsampling of app. F");
    /* --set, and what a failed one leaves */
    scene_t s;
    parse(&s, sphere_scene);
    set(&s, "subsample.step=2");
    set(&s, "subsample.threshold=0.3");
    svet_error e;
    ck_assert_int_eq(scenefile_override(&s, "subsample.step=16", &e),
                     SVET_OK);
    ck_assert_int_eq(scenefile_override(&s, "subsample.threshold=0.125", &e),
                     SVET_OK);
    ck_assert_int_eq(s.render.subsample_step, 16);
    ck_assert(s.render.subsample_threshold == REAL_C(0.125));
    ck_assert_int_eq(scenefile_override(&s, "subsample.step=6", &e),
                     SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(e.msg, "override 'subsample.step=6'"));
    ck_assert_int_eq(s.render.subsample_step, 16);
    ck_assert_int_eq(scenefile_override(&s, "subsample.step=0", &e), SVET_OK);
    ck_assert_int_eq(s.render.subsample_step, 0);
    scene_free(&s);
}
END_TEST

START_TEST(split_renders_and_further_passes_are_refused)
{
    scene_t s;
    parse(&s, sphere_scene);
    set(&s, "subsample.step=4");
    set(&s, "subsample.threshold=0.2");
    render_t r;
    ck_assert_int_eq(render_init(&r, &s, NULL), SVET_OK);
    r.crop_x0 = 0, r.crop_x1 = 20, r.crop_y0 = 0, r.crop_y1 = 30;
    ck_assert_int_eq(render_pass(&r, 4, 2, NULL, NULL), SVET_ERR_UNSUPPORTED);
    ck_assert_ptr_nonnull(strstr(r.error.msg, "crop"));
    r.crop_x1 = 0;
    r.spp_done = 2; /* --samples 2:4 */
    ck_assert_int_eq(render_pass(&r, 4, 2, NULL, NULL), SVET_ERR_UNSUPPORTED);
    ck_assert_ptr_nonnull(strstr(r.error.msg, "from sample 2"));
    r.spp_done = 0;
    ck_assert_int_eq(render_pass(&r, 2, 2, NULL, NULL), SVET_OK);
    ck_assert_int_eq(render_pass(&r, 4, 2, NULL, NULL), SVET_ERR_UNSUPPORTED);
    ck_assert_int_eq(r.spp_done, 2);
    /* an interrupted pass is undone: no image, no samples */
    render_t q;
    ck_assert_int_eq(render_init(&q, &s, NULL), SVET_OK);
    volatile sig_atomic_t stop = 1;
    bool abandoned = false;
    svet_error e;
    ck_assert_int_eq(render_pass_until(&q, 4, 2, NULL, NULL, &stop,
                                       &abandoned, &e), SVET_OK);
    ck_assert(abandoned && q.spp_done == 0 && !q.sub.px);
    ck_assert(image_accum_samples(&q.acc) == 0);
    render_free(&q);
    render_free(&r);
    scene_free(&s);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("subsample (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, a_constant_image_computes_only_the_coarse_pixels);
    tcase_add_test(tc, an_edge_is_refined_beside_it_and_nowhere_else);
    tcase_add_test(tc, a_ramp_is_interpolated_exactly_and_step_1_computes_all);
    tcase_add_test(tc, bad_parameters_are_refused);
    tcase_add_test(tc, two_threads_give_one_threads_image_and_mask);
    suite_add_tcase(s, tc);
    TCase *tr = tcase_create("render");
    tcase_set_timeout(tr, 60);
    tcase_add_test(tr, step_1_is_the_plain_render_bit_for_bit);
    tcase_add_test(tr, a_constant_render_is_the_plain_one_from_the_coarse_pixels);
    tcase_add_test(tr, an_emitters_edge_is_refined_and_the_image_exact);
    tcase_add_test(tr, a_subsampled_render_is_the_same_on_1_and_2_threads);
    tcase_add_test(tr, bad_subsample_keys_are_refused_with_file_and_line);
    tcase_add_test(tr, split_renders_and_further_passes_are_refused);
    suite_add_tcase(s, tr);
    return s;
}
