/*
 * test_tonemap.c - ch. 6 (tonemap.h): the operators against values worked
 * out by hand (python3 float arithmetic, quoted), chromaticity kept, the
 * histogram adjustment's linear ceiling as a property over random scenes,
 * and the extremes: an all-black image, a pixel of 1e30, NaN and Inf.
 */
#include "testutil.h"
#include "colour/tonemap.h"
#include "colour/colour.h"
#include "core/rng.h"

#include <string.h>

/* An image from a list of grey levels (one row). */
static void grey_row(image_t *img, const float *v, int n)
{
    svet_error err;
    ck_assert_int_eq(image_alloc(img, n, 1, 3, &err), SVET_OK);
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            image_at(img, i, 0)[c] = v[i];
}

static tonemap_params_t params(tonemap_op_t op, tonemap_curve_t curve)
{
    tonemap_params_t p;
    tonemap_defaults(&p, op);
    p.curve = curve;
    return p;
}

START_TEST(reinhard_matches_values_worked_by_hand)
{
    /* Lw = Lav: L = a = 0.18. eq. 4 with L_white = 2:
     * 0.18 (1 + 0.18 / 4) / 1.18 = 0.15940677966101696; eq. 3 (white
     * infinite): 0.18 / 1.18 = 0.15254237288135594. L_white = 1 gives L. */
    ck_assert_rel(tonemap_reinhard(1, 1, 0.18, 2), 0.15940677966101696,
                  1e-15, 0);
    ck_assert_rel(tonemap_reinhard(3, 3, 0.18, (double)INFINITY),
                  0.15254237288135594, 1e-15, 0);
    ck_assert_rel(tonemap_reinhard(2, 4, 0.5, 1), 0.25, 1e-15, 0);
    /* no overflow for the largest inputs: white everything */
    ck_assert_rel(tonemap_reinhard(1e300, 1e-300, 0.18, (double)INFINITY), 1,
                  1e-15, 0);
    ck_assert(tonemap_reinhard(0, 1, 0.18, 2) == 0);

    /* On an image of grey 1 and 4 with delta 1e-4 (eq. 1):
     * Lav = exp((ln 1.0001 + ln 4.0001) / 2) = 2.000124998593838, the
     * automatic white 0.18 * 4 / Lav = 0.35997750165923964, and pixel 1
     * maps to 0.1399038186383085, pixel 4 to exactly 1 (it is the white). */
    image_t img, out;
    const float v[2] = { 1, 4 };
    grey_row(&img, v, 2);
    tonemap_params_t p = params(TONEMAP_REINHARD, TONEMAP_CURVE_NONE);
    tonemap_result_t r;
    svet_error err;
    ck_assert_int_eq(tonemap_apply(&img, &out, &p, &r, &err), SVET_OK);
    ck_assert_rel(r.l_logavg, 2.000124998593838, 1e-12, 0);
    ck_assert_rel(r.white, 0.35997750165923964, 1e-12, 0);
    for (int c = 0; c < 3; c++) {
        ck_assert_rel(image_at(&out, 0, 0)[c], 0.1399038186383085, 1e-6, 0);
        ck_assert_rel(image_at(&out, 1, 0)[c], 1.0, 1e-6, 0);
    }
    ck_assert_uint_eq(r.clipped, 0);
    image_free(&out);
    image_free(&img);
}
END_TEST

START_TEST(exponential_drago_and_curves_match_values_worked_by_hand)
{
    /* 1 - exp(-1) = 0.6321205588285577 */
    ck_assert_rel(tonemap_exponential(2.5, 2.5), 0.6321205588285577, 1e-15,
                  0);
    ck_assert(tonemap_exponential(0, 1) == 0);
    ck_assert(tonemap_exponential((double)INFINITY, 1) == 1);
    /* Drago, b = 0.85 (power ln 0.85 / ln 0.5 = 0.23446525363702297):
     * Lw = 0.5, Lw_max = 10 -> (1 / log10 11) ln 1.5 /
     * ln(2 + 8 (0.05)^0.2345) = 0.2180488955832139; at Lw_max, exactly
     * ld_max / 100. */
    ck_assert_rel(tonemap_drago(0.5, 10, 0.85, 100), 0.2180488955832139,
                  1e-14, 0);
    ck_assert_rel(tonemap_drago(10, 10, 0.85, 100), 1, 1e-15, 0);
    ck_assert_rel(tonemap_drago(10, 10, 0.85, 80), 0.8, 1e-15, 0);
    ck_assert(tonemap_drago(0, 10, 0.85, 100) == 0);
    /* the curves: sRGB 1.055 0.5^(1/2.4) - 0.055 = 0.7353569830524495,
     * gamma 2.2: 0.5^(1/2.2) = 0.7297400528407231 */
    tonemap_params_t p = params(TONEMAP_LINEAR, TONEMAP_CURVE_SRGB);
    ck_assert_rel(tonemap_encode(0.5, &p), 0.7353569830524495,
                  4 * REAL_EPSILON, 0);
    p.curve = TONEMAP_CURVE_GAMMA;
    ck_assert_rel(tonemap_encode(0.5, &p), 0.7297400528407231, 1e-15, 0);
    p.curve = TONEMAP_CURVE_NONE;
    ck_assert(tonemap_encode(0.5, &p) == 0.5);
}
END_TEST

START_TEST(linear_exposure_doubles_per_stop_and_quantises_as_srgb_bytes)
{
    image_t img, out;
    const float v[3] = { 0.01f, 0.1f, 0.3f };
    grey_row(&img, v, 3);
    tonemap_params_t p = params(TONEMAP_LINEAR, TONEMAP_CURVE_NONE);
    p.stops = 1;
    svet_error err;
    ck_assert_int_eq(tonemap_apply(&img, &out, &p, NULL, &err), SVET_OK);
    for (int i = 0; i < 3; i++)
        ck_assert_rel(image_at(&out, i, 0)[1], 2 * v[i], 1e-6, 0);
    image_free(&out);
    /* With the sRGB curve, the codes written (image_quantize) are those of
     * the colour module's own 8-bit encoder, for a ramp of linear values. */
    p = params(TONEMAP_LINEAR, TONEMAP_CURVE_SRGB);
    image_free(&img);
    ck_assert_int_eq(image_alloc(&img, 1001, 1, 3, &err), SVET_OK);
    for (int i = 0; i <= 1000; i++)
        for (int c = 0; c < 3; c++)
            image_at(&img, i, 0)[c] = (float)i / 1000.0f;
    ck_assert_int_eq(tonemap_apply(&img, &out, &p, NULL, &err), SVET_OK);
    for (int i = 0; i <= 1000; i++)
        ck_assert_uint_eq(image_quantize(image_at(&out, i, 0)[0], 255),
                          colour_srgb_encode_byte((real)i / 1000));
    image_free(&out);
    image_free(&img);
    test_report_cases("linear_exposure_doubles_per_stop_and_quantises_as_"
                      "srgb_bytes", 1004);
}
END_TEST

/* A random HDR scene as real ones are: most pixels (85%) in a band of
 * about two stops (an interior), the rest spread uniformly over
 * +-spread_stops (windows, lamps, shadows); random chromaticity. */
static void random_scene(image_t *img, int w, int h, uint64_t seed,
                         double spread_stops)
{
    svet_error err;
    ck_assert_int_eq(image_alloc(img, w, h, 3, &err), SVET_OK);
    pcg32_t g;
    pcg32_seed(&g, seed, 11);
    for (int i = 0; i < w * h; i++) {
        double z = (double)pcg32_real(&g) + (double)pcg32_real(&g) - 1;
        if (pcg32_real(&g) < REAL_C(0.15))
            z = spread_stops * (2 * (double)pcg32_real(&g) - 1);
        double L = exp2(z);
        for (int c = 0; c < 3; c++)
            img->px[3 * i + c] = (float)(L * (0.2 + (double)pcg32_real(&g)));
    }
}

START_TEST(operators_keep_chromaticity_where_nothing_clips)
{
    long cases = 0;
    for (int op = 0; op < TONEMAP_OP_COUNT; op++) {
        image_t img, out;
        random_scene(&img, 32, 32, 100 + (uint64_t)op, 3);
        tonemap_params_t p = params((tonemap_op_t)op, TONEMAP_CURVE_NONE);
        if (op == TONEMAP_LINEAR)
            p.stops = -6; /* keep the linear map below white */
        svet_error err;
        ck_assert_int_eq(tonemap_apply(&img, &out, &p, NULL, &err), SVET_OK);
        for (int i = 0; i < 32 * 32; i++) {
            const float *a = img.px + 3 * i, *b = out.px + 3 * i;
            if (fmaxf(b[0], fmaxf(b[1], b[2])) >= 1.0f)
                continue; /* desaturated: chromaticity moves by design */
            /* scaling by Ld / Lw keeps the ratios r : g : b */
            ck_assert_rel((double)b[0] * (double)a[1], (double)b[1] * (double)a[0],
                          1e-5, 0);
            ck_assert_rel((double)b[2] * (double)a[1], (double)b[1] * (double)a[2],
                          1e-5, 0);
            cases++;
        }
        image_free(&img);
        image_free(&out);
    }
    ck_assert(cases > 3000);
    test_report_cases("operators_keep_chromaticity_where_nothing_clips",
                      cases);
}
END_TEST

START_TEST(desaturation_keeps_luminance_and_caps_at_white)
{
    image_t img, out;
    svet_error err;
    ck_assert_int_eq(image_alloc(&img, 2, 1, 3, &err), SVET_OK);
    float *a = image_at(&img, 0, 0);
    a[0] = 4.0f, a[1] = 0.1f, a[2] = 0.1f; /* Y = 0.93930: fits, red does not */
    float *b = image_at(&img, 1, 0);
    b[0] = 9.0f, b[1] = 9.0f, b[2] = 0.0f; /* Y > 1: white */
    tonemap_params_t p = params(TONEMAP_LINEAR, TONEMAP_CURVE_NONE);
    tonemap_result_t r;
    ck_assert_int_eq(tonemap_apply(&img, &out, &p, &r, &err), SVET_OK);
    const float *o = image_at(&out, 0, 0);
    double Y = 0.2126 * (double)o[0] + 0.7152 * (double)o[1] +
               0.0722 * (double)o[2];
    ck_assert_rel(Y, 0.2126 * 4 + 0.7152 * 0.1 + 0.0722 * 0.1, 1e-6, 0);
    ck_assert_rel(o[0], 1, 1e-6, 0);
    ck_assert(o[1] == o[2] && o[1] < o[0]); /* still reddish */
    for (int c = 0; c < 3; c++)
        ck_assert(image_at(&out, 1, 0)[c] == 1.0f);
    ck_assert_uint_eq(r.clipped, 2);
    image_free(&out);
    /* clipping instead: channel by channel */
    p.gamut = TONEMAP_GAMUT_CLIP;
    ck_assert_int_eq(tonemap_apply(&img, &out, &p, &r, &err), SVET_OK);
    ck_assert(image_at(&out, 0, 0)[0] == 1.0f);
    ck_assert_rel(image_at(&out, 0, 0)[1], 0.1, 1e-6, 0);
    image_free(&out);
    image_free(&img);
}
END_TEST

/* d ln Ld / d ln Lw over a fine grid of the curve, by finite differences
 * (independent of the code's own max_slope). */
static double measured_max_slope(const tonemap_histogram_t *h)
{
    double s = 0, b0 = h->bw_min - 0.5, b1 = h->bw_max + 0.5;
    const int n = 20000;
    double prev = log(tonemap_histogram_eval(h, exp(b0)));
    for (int i = 1; i <= n; i++) {
        double b = b0 + (b1 - b0) * i / n;
        double ld = log(tonemap_histogram_eval(h, exp(b)));
        ck_assert_msg(ld >= prev - 1e-12, "the curve goes down at %g", b);
        s = fmax(s, (ld - prev) / ((b1 - b0) / n));
        prev = ld;
    }
    return s;
}

START_TEST(histogram_adjustment_never_exceeds_the_linear_ceiling)
{
    /* Random scenes of 6 to 20 stops of spread (and one with a 1e30 pixel):
     * the naive equalisation (the raw histogram's cumulative) would have
     * slopes far above 1 in the crowded bins; after the ceiling, no part
     * of the curve may be steeper than a linear map (slope 1 in log-log),
     * and the curve still spans Ld_min..Ld_max. */
    long cases = 0;
    int naive_steep = 0;
    for (int t = 0; t < 12; t++) {
        image_t img;
        random_scene(&img, 48, 40, 500 + (uint64_t)t, 6 + 14 * t / 11.0);
        if (t == 11)
            img.px[7] = img.px[8] = img.px[9] = 1e30f;
        tonemap_params_t p = params(TONEMAP_HISTOGRAM, TONEMAP_CURVE_NONE);
        p.fovea = 1 + t % 3;
        tonemap_histogram_t h;
        svet_error err;
        ck_assert_int_eq(tonemap_histogram_build(&h, &img, &p, &err), SVET_OK);
        ck_assert(!h.linear && !h.empty);
        double T = 0, T0 = 0, raw_max = 0;
        for (int i = 0; i < h.bins; i++) {
            T += h.trimmed[i];
            T0 += h.raw[i];
            raw_max = fmax(raw_max, h.raw[i]);
            ck_assert(h.trimmed[i] <= h.ceiling && h.trimmed[i] <= h.raw[i]);
        }
        double K = (h.bd_max - h.bd_min) / ((h.bw_max - h.bw_min) / h.bins);
        naive_steep += raw_max * K / T0 > 1.5;
        /* the ceiling is the fixed point: T = K ceiling (a sparse
         * histogram has none: its occupied bins all sit at slope 1) */
        if (!h.sparse)
            ck_assert_rel(T, K * h.ceiling, 1e-12, 0);
        ck_assert(tonemap_histogram_max_slope(&h) <= 1 + 1e-12);
        ck_assert_msg(measured_max_slope(&h) <= 1 + 1e-6,
                      "scene %d: slope %g", t, measured_max_slope(&h));
        ck_assert_rel(tonemap_histogram_eval(&h, exp(h.bw_min)),
                      h.sparse ? exp(h.bd_lo) : p.ld_min, 1e-12, 0);
        ck_assert(h.bd_lo >= h.bd_min);
        ck_assert_rel(tonemap_histogram_eval(&h, exp(h.bw_max)), p.ld_max,
                      1e-12, 0);
        ck_assert(h.iterations >= 1);
        tonemap_histogram_free(&h);
        image_free(&img);
        cases++;
    }
    ck_assert_int_ge(naive_steep, 10); /* the ceiling had work to do */
    test_report_cases("histogram_adjustment_never_exceeds_the_linear_ceiling",
                      cases);
}
END_TEST

START_TEST(histogram_of_a_scene_that_fits_the_display_is_linear)
{
    /* luminance 1..10 on a display of 1..100 cd/m^2: nothing to compress,
     * the paper maps linearly (Ld proportional to Lw, brightest at Ld_max) */
    image_t img, out;
    const float v[4] = { 1, 2, 5, 10 };
    grey_row(&img, v, 4);
    tonemap_params_t p = params(TONEMAP_HISTOGRAM, TONEMAP_CURVE_NONE);
    tonemap_result_t r;
    svet_error err;
    ck_assert_int_eq(tonemap_apply(&img, &out, &p, &r, &err), SVET_OK);
    ck_assert(r.hist_linear);
    for (int i = 0; i < 4; i++)
        ck_assert_rel(image_at(&out, i, 0)[0], (double)v[i] / 10, 1e-6, 0);
    image_free(&out);
    image_free(&img);
}
END_TEST

START_TEST(an_all_black_image_stays_black_under_every_operator)
{
    image_t img, out;
    svet_error err;
    ck_assert_int_eq(image_alloc(&img, 8, 8, 4, &err), SVET_OK);
    for (int op = 0; op < TONEMAP_OP_COUNT; op++) {
        tonemap_params_t p = params((tonemap_op_t)op, TONEMAP_CURVE_SRGB);
        tonemap_result_t r;
        ck_assert_int_eq(tonemap_apply(&img, &out, &p, &r, &err), SVET_OK);
        for (int i = 0; i < 8 * 8 * 4; i++)
            ck_assert(out.px[i] == 0.0f);
        ck_assert_uint_eq(r.nonfinite, 0);
        ck_assert(r.l_max == 0 && r.l_min == 0);
        image_free(&out);
    }
    image_free(&img);
    test_report_cases("an_all_black_image_stays_black_under_every_operator",
                      TONEMAP_OP_COUNT);
}
END_TEST

START_TEST(one_pixel_of_1e30_neither_breaks_nor_blackens_the_image)
{
    long cases = 0;
    for (int op = 0; op < TONEMAP_OP_COUNT; op++) {
        image_t img, out;
        random_scene(&img, 30, 20, 77, 2);
        float *hot = image_at(&img, 13, 7);
        hot[0] = hot[1] = hot[2] = 1e30f;
        tonemap_params_t p = params((tonemap_op_t)op, TONEMAP_CURVE_SRGB);
        tonemap_result_t r;
        svet_error err;
        ck_assert_int_eq(tonemap_apply(&img, &out, &p, &r, &err), SVET_OK);
        double mean = 0;
        for (int i = 0; i < 30 * 20 * 3; i++) {
            ck_assert(isfinite(out.px[i]) && out.px[i] >= 0 &&
                      out.px[i] <= 1);
            mean += (double)out.px[i] / (30 * 20 * 3);
        }
        for (int c = 0; c < 3; c++)
            ck_assert_rel(image_at(&out, 13, 7)[c], 1, 1e-6, 0);
        /* the rest stays visible, except under Drago, whose maximum is
         * the 1e30 pixel by design (log10(1e30) compresses all else) */
        if (op != TONEMAP_DRAGO)
            ck_assert_msg(mean > 0.2, "%s: mean code %g",
                          tonemap_op_name((tonemap_op_t)op), mean);
        if (op == TONEMAP_HISTOGRAM) /* a few full bins, then a long gap */
            ck_assert(r.hist_sparse && r.hist_slope <= 1 + 1e-12);
        ck_assert(isfinite(r.l_logavg) && r.l_logavg < 10);
        image_free(&out);
        image_free(&img);
        cases++;
    }
    test_report_cases("one_pixel_of_1e30_neither_breaks_nor_blackens_the_"
                      "image", cases);
}
END_TEST

START_TEST(nan_and_inf_pixels_are_counted_black_and_kept_out_of_statistics)
{
    image_t img, clean, out;
    const float v[5] = { 1, NAN, 4, INFINITY, -INFINITY };
    const float w[2] = { 1, 4 };
    grey_row(&img, v, 5);
    grey_row(&clean, w, 2);
    image_at(&img, 0, 0)[1] = 1.0f; /* a pixel with one NaN channel */
    image_at(&img, 0, 0)[2] = 1.0f;
    image_at(&img, 1, 0)[0] = 0.5f;
    for (int op = 0; op < TONEMAP_OP_COUNT; op++) {
        tonemap_params_t p = params((tonemap_op_t)op, TONEMAP_CURVE_SRGB);
        tonemap_result_t r, rc;
        svet_error err;
        ck_assert_int_eq(tonemap_apply(&clean, &out, &p, &rc, &err), SVET_OK);
        image_free(&out);
        ck_assert_int_eq(tonemap_apply(&img, &out, &p, &r, &err), SVET_OK);
        ck_assert_uint_eq(r.nonfinite, 3);
        ck_assert_uint_eq(r.pixels, 5);
        /* the statistics are those of the clean pixels alone */
        ck_assert(r.l_logavg == rc.l_logavg && r.l_max == rc.l_max);
        for (int c = 0; c < 3; c++) {
            ck_assert(image_at(&out, 1, 0)[c] == 0.0f);
            ck_assert(image_at(&out, 3, 0)[c] == 0.0f);
            ck_assert(image_at(&out, 4, 0)[c] == 0.0f);
            ck_assert(isfinite(image_at(&out, 2, 0)[c]));
        }
        image_free(&out);
        p.flag_nonfinite = true;
        ck_assert_int_eq(tonemap_apply(&img, &out, &p, &r, &err), SVET_OK);
        const float *m = image_at(&out, 3, 0);
        ck_assert(m[0] == 1.0f && m[1] == 0.0f && m[2] == 1.0f);
        image_free(&out);
    }
    image_free(&img);
    image_free(&clean);
}
END_TEST

START_TEST(negative_channels_are_clamped_and_counted)
{
    image_t img, out;
    const float v[2] = { 0.5f, 0.25f };
    grey_row(&img, v, 2);
    image_at(&img, 1, 0)[2] = -3.0f;
    tonemap_params_t p = params(TONEMAP_LINEAR, TONEMAP_CURVE_NONE);
    tonemap_result_t r;
    svet_error err;
    ck_assert_int_eq(tonemap_apply(&img, &out, &p, &r, &err), SVET_OK);
    ck_assert_uint_eq(r.negative, 1);
    ck_assert(image_at(&out, 1, 0)[2] == 0.0f);
    ck_assert_rel(image_at(&out, 1, 0)[0], 0.25, 1e-6, 0);
    image_free(&out);
    image_free(&img);
}
END_TEST

START_TEST(bad_parameters_are_refused_by_name)
{
    image_t img, out;
    const float v[1] = { 1 };
    grey_row(&img, v, 1);
    svet_error err;
    tonemap_params_t p;
    p = params(TONEMAP_REINHARD, TONEMAP_CURVE_SRGB);
    p.key = -1;
    ck_assert_int_eq(tonemap_apply(&img, &out, &p, NULL, &err),
                     SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(err.msg, "key"));
    ck_assert_ptr_null(out.px);
    p = params(TONEMAP_DRAGO, TONEMAP_CURVE_SRGB);
    p.bias = 1.5;
    ck_assert_int_eq(tonemap_apply(&img, &out, &p, NULL, &err),
                     SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(err.msg, "bias"));
    p = params(TONEMAP_HISTOGRAM, TONEMAP_CURVE_SRGB);
    p.ld_min = 200;
    ck_assert_int_eq(tonemap_apply(&img, &out, &p, NULL, &err),
                     SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(err.msg, "Ld_min"));
    p = params(TONEMAP_LINEAR, TONEMAP_CURVE_GAMMA);
    p.gamma = 0;
    ck_assert_int_eq(tonemap_apply(&img, &out, &p, NULL, &err),
                     SVET_ERR_RANGE);
    p = params(TONEMAP_LINEAR, TONEMAP_CURVE_SRGB);
    p.stops = (double)NAN;
    ck_assert_int_eq(tonemap_apply(&img, &out, &p, NULL, &err),
                     SVET_ERR_RANGE);
    p.op = TONEMAP_OP_COUNT;
    p.stops = 0;
    ck_assert_int_eq(tonemap_apply(&img, &out, &p, NULL, &err),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(tonemap_op_from_name("drago"), TONEMAP_DRAGO);
    ck_assert_int_eq(tonemap_op_from_name("dargo"), -1);
    ck_assert_str_eq(tonemap_op_name(TONEMAP_HISTOGRAM), "histogram");
    image_free(&img);
}
END_TEST

START_TEST(curves_match_the_port_vectors)
{
    /* tests/vectors/tonemap.csv: the papers' formulas in long double
     * (tools/vectors_tonemap.c), not this code */
    testcsv_t c;
    testcsv_open(&c, "tonemap.csv");
    long rows = 0;
    while (testcsv_next(&c)) {
        const char *op = testcsv_str(&c, "op");
        double lw = testcsv_num(&c, "lw"), got;
        if (strcmp(op, "exponential") == 0)
            got = tonemap_exponential(lw, testcsv_num(&c, "lav"));
        else if (strcmp(op, "reinhard") == 0)
            got = tonemap_reinhard(lw, testcsv_num(&c, "lav"),
                                   testcsv_num(&c, "key"),
                                   testcsv_num(&c, "white"));
        else if (strcmp(op, "drago") == 0)
            got = tonemap_drago(lw, testcsv_num(&c, "lw_max"),
                                testcsv_num(&c, "bias"),
                                testcsv_num(&c, "ld_max"));
        else
            ck_abort_msg("tonemap.csv:%d: unknown op %s", c.line, op);
        ck_assert_msg(fabs(got - testcsv_num(&c, "expected")) <=
                          testcsv_num(&c, "tol"),
                      "tonemap.csv:%d: %s(%g) = %.17g, expected %.17g", c.line,
                      op, lw, got, testcsv_num(&c, "expected"));
        rows++;
    }
    testcsv_close(&c);
    ck_assert_int_ge(rows, 150);
    test_report_cases("curves_match_the_port_vectors", rows);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("tonemap");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, reinhard_matches_values_worked_by_hand);
    tcase_add_test(tc, exponential_drago_and_curves_match_values_worked_by_hand);
    tcase_add_test(tc, linear_exposure_doubles_per_stop_and_quantises_as_srgb_bytes);
    tcase_add_test(tc, operators_keep_chromaticity_where_nothing_clips);
    tcase_add_test(tc, desaturation_keeps_luminance_and_caps_at_white);
    tcase_add_test(tc, histogram_adjustment_never_exceeds_the_linear_ceiling);
    tcase_add_test(tc, histogram_of_a_scene_that_fits_the_display_is_linear);
    tcase_add_test(tc, an_all_black_image_stays_black_under_every_operator);
    tcase_add_test(tc, one_pixel_of_1e30_neither_breaks_nor_blackens_the_image);
    tcase_add_test(tc, nan_and_inf_pixels_are_counted_black_and_kept_out_of_statistics);
    tcase_add_test(tc, negative_channels_are_clamped_and_counted);
    tcase_add_test(tc, bad_parameters_are_refused_by_name);
    tcase_add_test(tc, curves_match_the_port_vectors);
    suite_add_tcase(s, tc);
    return s;
}
