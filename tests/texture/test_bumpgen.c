/*
 * test_bumpgen.c - app. G's generated bump textures: heights in [0, 1],
 * their partial derivatives against central differences where smooth,
 * the patterns' own facts (the waves' period and direction, the ripples'
 * centre, mortar sunk to 0 on the joints, bricks offset by half a brick
 * every other row), and the image written from the same heights.
 */
#include "testutil.h"
#include "core/rng.h"
#include "texture/bumpgen.h"

#include <math.h>
#include <stdlib.h>

static const bumpgen_kind_t kinds[] = { BUMPGEN_WAVES, BUMPGEN_RIPPLES,
                                        BUMPGEN_BRICKS, BUMPGEN_ORANGE_PEEL,
                                        BUMPGEN_DENTS };
#define NKINDS (int)(sizeof kinds / sizeof kinds[0])

#ifdef SVET_DOUBLE
#define H REAL_C(1e-7)
#define TOL 1e-4
#else
#define H REAL_C(1e-3)
#define TOL 0.05
#endif

START_TEST(heights_in_0_1_with_derivatives_equal_to_differences)
{
    pcg32_t g;
    pcg32_seed(&g, 50, 1);
    long n = 0;
    for (int k = 0; k < NKINDS; k++) {
        bumpgen_t b = bumpgen_default(kinds[k]);
        b.angle = REAL_C(0.4);
        /* a bevel wide enough for float's step to resolve */
        b.mortar = REAL_C(0.04);
        int checked = 0;
        double lo = 1, hi = 0;
        for (int i = 0; i < 5000; i++) {
            real u = pcg32_real(&g), v = pcg32_real(&g), du, dv;
            real h = bumpgen_height(&b, u, v, &du, &dv);
            ck_assert(h >= 0 && h <= 1);
            lo = fmin(lo, (double)h);
            hi = fmax(hi, (double)h);
            real a = bumpgen_height(&b, u + H, v, NULL, NULL);
            real c = bumpgen_height(&b, u - H, v, NULL, NULL);
            real d = bumpgen_height(&b, u, v + H, NULL, NULL);
            real e = bumpgen_height(&b, u, v - H, NULL, NULL);
            /* skip the flats' edges and the joints, where h has kinks:
             * one-sided slopes differ there */
            if (fabs((double)(a - 2 * h + c)) > 0.1 * fabs((double)(a - c)) + 1e-6 ||
                fabs((double)(d - 2 * h + e)) > 0.1 * fabs((double)(d - e)) + 1e-6)
                continue;
            real gu = (a - c) / (2 * H), gv = (d - e) / (2 * H);
            ck_assert_msg(fabs((double)(du - gu)) <= TOL * (1 + fabs((double)gu)) &&
                              fabs((double)(dv - gv)) <= TOL * (1 + fabs((double)gv)),
                          "kind %d at (%g, %g): (%g, %g) against (%g, %g)", k,
                          (double)u, (double)v, (double)du, (double)dv,
                          (double)gu, (double)gv);
            checked++;
            n++;
        }
        ck_assert_msg(checked > 1000, "kind %d: %d checked", k, checked);
        ck_assert_msg(hi - lo > 0.5, "kind %d spans %g..%g", k, lo, hi);
    }
    test_report_cases("heights_in_0_1_with_derivatives_equal_to_differences",
                      n);
}
END_TEST

START_TEST(waves_ripples_and_bricks_keep_their_geometry)
{
    /* waves along u: period 1 / frequency, constant along v */
    bumpgen_t w = bumpgen_default(BUMPGEN_WAVES);
    for (int i = 0; i < 100; i++) {
        real u = (real)i / 100;
        ck_assert_near(bumpgen_height(&w, u, 0, NULL, NULL),
                       bumpgen_height(&w, u + REAL_C(0.125), REAL_C(0.7), NULL,
                                      NULL), 1e-5);
    }
    /* ripples: the top at the centre, the same at equal radii */
    bumpgen_t r = bumpgen_default(BUMPGEN_RIPPLES);
    real du, dv;
    ck_assert(bumpgen_height(&r, REAL_C(0.5), REAL_C(0.5), &du, &dv) == 1);
    ck_assert(du == 0 && dv == 0);
    ck_assert_near(bumpgen_height(&r, REAL_C(0.8), REAL_C(0.5), NULL, NULL),
                   bumpgen_height(&r, REAL_C(0.5), REAL_C(0.2), NULL, NULL),
                   1e-5);
    /* bricks: 0 on a joint's centre line, 1 on a brick's middle; the next
     * row's vertical joint is half a brick along */
    bumpgen_t b = bumpgen_default(BUMPGEN_BRICKS);
    ck_assert(bumpgen_height(&b, REAL_C(0.125), REAL_C(0.05), NULL, NULL) == 1);
    ck_assert(bumpgen_height(&b, REAL_C(0.25), REAL_C(0.05), NULL, NULL) == 0);
    ck_assert(bumpgen_height(&b, REAL_C(0.125), REAL_C(0.1), NULL, NULL) == 0);
    ck_assert(bumpgen_height(&b, REAL_C(0.125), REAL_C(0.15), NULL, NULL) == 0);
    ck_assert(bumpgen_height(&b, REAL_C(0.25), REAL_C(0.15), NULL, NULL) == 1);
}
END_TEST

START_TEST(the_image_holds_the_heights_at_texel_centres)
{
    for (int k = 0; k < NKINDS; k++) {
        bumpgen_t b = bumpgen_default(kinds[k]);
        float *px;
        svet_error e;
        ck_assert_int_eq(bumpgen_image(&b, 33, 17, &px, &e), SVET_OK);
        for (int y = 0; y < 17; y++)
            for (int x = 0; x < 33; x++)
                ck_assert(px[y * 33 + x] ==
                          (float)bumpgen_height(&b, ((real)x + REAL_C(0.5)) / 33,
                                                ((real)y + REAL_C(0.5)) / 17,
                                                NULL, NULL));
        free(px);
    }
    bumpgen_t b = bumpgen_default(BUMPGEN_WAVES);
    float *px = (float *)&b;
    svet_error e;
    ck_assert_int_eq(bumpgen_image(&b, 0, 5, &px, &e), SVET_ERR_RANGE);
    ck_assert_ptr_null(px);
    ck_assert_ptr_nonnull(strstr(e.msg, "0 x 5"));
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("bumpgen (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, heights_in_0_1_with_derivatives_equal_to_differences);
    tcase_add_test(tc, waves_ripples_and_bricks_keep_their_geometry);
    tcase_add_test(tc, the_image_holds_the_heights_at_texel_centres);
    suite_add_tcase(s, tc);
    return s;
}
