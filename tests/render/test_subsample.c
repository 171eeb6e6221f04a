/*
 * test_subsample.c - app. F's subsampling: a constant image computes only
 * the coarse pixels; a vertical edge is refined down to the pixels beside
 * it and nowhere else, and the image is exact; a linear ramp is
 * interpolated exactly; a step of 1 computes every pixel; bad steps and
 * thresholds are refused.
 */
#include "testutil.h"
#include "render/subsample.h"

#include <stdlib.h>
#include <string.h>

typedef struct {
    int kind; /* 0 constant, 1 edge between x = 10 and 11, 2 ramp */
    long calls;
} scene_t;

static void pixel(void *c, int x, int y, float out[3])
{
    scene_t *s = c;
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
    scene_t s = { kind, 0 };
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
    scene_t s = { 0, 0 };
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

Suite *test_suite(void)
{
    Suite *s = suite_create("subsample (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, a_constant_image_computes_only_the_coarse_pixels);
    tcase_add_test(tc, an_edge_is_refined_beside_it_and_nowhere_else);
    tcase_add_test(tc, a_ramp_is_interpolated_exactly_and_step_1_computes_all);
    tcase_add_test(tc, bad_parameters_are_refused);
    suite_add_tcase(s, tc);
    return s;
}
