/*
 * test_mipmap.c - the mip map of ch. 10 (Williams 1983): the pyramid's
 * sizes and means, texel centres returned exactly, bilinear lookups
 * exact on linear images, trilinear as app. L's blend of two levels
 * chosen by the footprint, the three wrap modes, and bad sizes.
 */
#include "testutil.h"
#include "core/rng.h"
#include "texture/mipmap.h"

#include <math.h>
#include <stdlib.h>

/* An image of w x h texels, c channels, channel k of texel (x, y) being
 * a + b x + d y + k: linear in x and y, and integer (exact in float). */
static float *linear_image(int w, int h, int c, double a, double b, double d)
{
    float *px = malloc(sizeof *px * (size_t)w * (size_t)h * (size_t)c);
    ck_assert_ptr_nonnull(px);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int k = 0; k < c; k++)
                px[((size_t)y * w + x) * c + k] = (float)(a + b * x + d * y + k);
    return px;
}

START_TEST(the_pyramid_halves_down_to_one_texel_and_keeps_the_mean)
{
    static const int sizes[][2] = { { 1, 1 }, { 2, 1 }, { 8, 8 }, { 64, 16 },
                                    { 5, 3 }, { 1, 100 }, { 37, 91 } };
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        int w = sizes[i][0], h = sizes[i][1];
        float *px = linear_image(w, h, 2, 3, 2, -1);
        mipmap_t m;
        svet_error e;
        ck_assert_int_eq(mipmap_build(&m, px, w, h, 2, MIPMAP_CLAMP, &e),
                         SVET_OK);
        int side = w > h ? w : h, expect = 1;
        while ((1 << (expect - 1)) < side)
            expect++;
        /* 1 + ceil(log2(side)) levels, the last one 1 x 1 */
        ck_assert_int_eq(m.levels, expect);
        ck_assert_int_eq(m.level[m.levels - 1].width, 1);
        ck_assert_int_eq(m.level[m.levels - 1].height, 1);
        for (int l = 1; l < m.levels; l++) {
            ck_assert_int_eq(m.level[l].width, (m.level[l - 1].width + 1) / 2);
            ck_assert_int_eq(m.level[l].height,
                             (m.level[l - 1].height + 1) / 2);
        }
        /* on a power of two the box filter keeps the mean exactly */
        if ((w & (w - 1)) == 0 && (h & (h - 1)) == 0) {
            double mean = 3 + 2 * (w - 1) / 2.0 - (h - 1) / 2.0;
            real top[2];
            mipmap_texel(&m, m.levels - 1, 0, 0, top);
            ck_assert_near(top[0], mean, 1e-5 * fabs(mean) + 1e-6);
            ck_assert_near(top[1], mean + 1, 1e-5 * fabs(mean) + 1e-6);
        }
        mipmap_free(&m);
        mipmap_free(&m); /* harmless twice */
        free(px);
    }
}
END_TEST

START_TEST(texel_centres_return_the_texel_exactly)
{
    /* sizes whose texel centres (x + 0.5) / w are exact in binary */
    const int w = 16, h = 8, c = 3;
    float *px = linear_image(w, h, c, 1, 5, 11);
    px[0] = 1e30f; /* and not only linear values */
    mipmap_t m;
    ck_assert_int_eq(mipmap_build(&m, px, w, h, c, MIPMAP_REPEAT, NULL),
                     SVET_OK);
    long n = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            real s = ((real)x + REAL_C(0.5)) / (real)w;
            real t = ((real)y + REAL_C(0.5)) / (real)h;
            for (int f = 0; f < 3; f++, n++) {
                real out[3];
                /* a footprint of a tenth of a texel: level 0 */
                mipmap_lookup(&m, (mipmap_filter_t)f, s, t,
                              REAL_C(0.1) / (real)w, out);
                for (int k = 0; k < c; k++)
                    ck_assert(out[k] == (real)px[((size_t)y * w + x) * c + k]);
            }
        }
    mipmap_free(&m);
    free(px);
    test_report_cases("texel_centres_return_the_texel_exactly", n);
}
END_TEST

START_TEST(bilinear_is_exact_on_a_linear_image)
{
    const int w = 32, h = 20;
    float *px = linear_image(w, h, 1, -7, 3, 2);
    mipmap_t m;
    ck_assert_int_eq(mipmap_build(&m, px, w, h, 1, MIPMAP_CLAMP, NULL),
                     SVET_OK);
    pcg32_t g;
    pcg32_seed(&g, 30, 1);
    for (int i = 0; i < 5000; i++) {
        /* inside the texel centres' hull, where no wrap is read */
        real x = REAL_C(0.5) + (real)(w - 1) * pcg32_real(&g);
        real y = REAL_C(0.5) + (real)(h - 1) * pcg32_real(&g);
        real out;
        mipmap_lookup(&m, MIPMAP_BILINEAR, x / (real)w, y / (real)h, 0, &out);
        double e = -7 + 3 * ((double)x - 0.5) + 2 * ((double)y - 0.5);
        ck_assert_near(out, e, 200 * (double)REAL_EPSILON);
    }
    mipmap_free(&m);
    free(px);
}
END_TEST

START_TEST(trilinear_blends_the_two_levels_of_the_footprint)
{
    const int w = 64, h = 64;
    pcg32_t g;
    pcg32_seed(&g, 30, 2);
    float *px = malloc(sizeof *px * w * h);
    for (int i = 0; i < w * h; i++)
        px[i] = (float)pcg32_real(&g);
    mipmap_t m, one;
    ck_assert_int_eq(mipmap_build(&m, px, w, h, 1, MIPMAP_REPEAT, NULL),
                     SVET_OK);
    ck_assert_int_eq(m.levels, 7);
    for (int i = 0; i < 2000; i++) {
        real s = pcg32_real(&g), t = pcg32_real(&g);
        /* a footprint of 2^lambda texels of level 0 */
        real lambda = 7 * pcg32_real(&g) - REAL_C(0.5);
        real width = exp2(lambda) / (real)w, out;
        mipmap_lookup(&m, MIPMAP_TRILINEAR, s, t, width, &out);
        /* by hand: the bilinear lookups of the two levels, blended */
        real lam = lambda < 0 ? 0 : lambda;
        int l0 = (int)floor(lam);
        double e;
        if (l0 >= 6) {
            e = (double)m.level[6].px[0];
        } else {
            double f = (double)(lam - (real)l0), v[2];
            for (int k = 0; k < 2; k++) {
                const mipmap_level_t *lv = &m.level[l0 + k];
                double x = (double)s * lv->width - 0.5;
                double y = (double)t * lv->height - 0.5;
                int x0 = (int)floor(x), y0 = (int)floor(y);
                double tx = x - x0, ty = y - y0;
#define T(a, b) (double)lv->px[(((b) + lv->height) % lv->height) * lv->width + \
                               (((a) + lv->width) % lv->width)]
                v[k] = (1 - ty) * ((1 - tx) * T(x0, y0) + tx * T(x0 + 1, y0)) +
                       ty * ((1 - tx) * T(x0, y0 + 1) + tx * T(x0 + 1, y0 + 1));
#undef T
            }
            e = (1 - f) * v[0] + f * v[1];
        }
        ck_assert_near(out, e, 1e-4);
    }
    /* a one-texel map is its texel for every filter and footprint */
    float c1 = 0.25f;
    ck_assert_int_eq(mipmap_build(&one, &c1, 1, 1, 1, MIPMAP_MIRROR, NULL),
                     SVET_OK);
    for (int f = 0; f < 3; f++) {
        real out;
        mipmap_lookup(&one, (mipmap_filter_t)f, REAL_C(0.3), REAL_C(7.9), 10,
                      &out);
        ck_assert(out == REAL_C(0.25));
    }
    mipmap_free(&m);
    mipmap_free(&one);
    free(px);
}
END_TEST

START_TEST(repeat_clamp_and_mirror)
{
    const int w = 8, h = 4;
    float *px = linear_image(w, h, 1, 0, 1, 10);
    mipmap_t r, c, mi;
    ck_assert_int_eq(mipmap_build(&r, px, w, h, 1, MIPMAP_REPEAT, NULL), 0);
    ck_assert_int_eq(mipmap_build(&c, px, w, h, 1, MIPMAP_CLAMP, NULL), 0);
    ck_assert_int_eq(mipmap_build(&mi, px, w, h, 1, MIPMAP_MIRROR, NULL), 0);
    real a, b;
    for (int x = -20; x < 20; x++)
        for (int y = -9; y < 9; y++) {
            mipmap_texel(&r, 0, x, y, &a);
            ck_assert(a == (real)px[((y % h + h) % h) * w + (x % w + w) % w]);
            mipmap_texel(&c, 0, x, y, &a);
            int cx = x < 0 ? 0 : x >= w ? w - 1 : x;
            int cy = y < 0 ? 0 : y >= h ? h - 1 : y;
            ck_assert(a == (real)px[cy * w + cx]);
            /* mirror: texel -1 is texel 0, texel w is texel w - 1 */
            mipmap_texel(&mi, 0, x, y, &a);
            mipmap_texel(&mi, 0, -1 - x, y, &b);
            ck_assert(a == b);
            mipmap_texel(&mi, 0, 2 * w - 1 - x, y, &b);
            ck_assert(a == b);
        }
    /* lookups: repeat is periodic in 1; dyadic s stays exact */
    for (int i = 0; i < 64; i++) {
        real s = (real)i / 64, t = (real)(i % 8) / 8;
        for (int f = 0; f < 3; f++) {
            mipmap_lookup(&r, (mipmap_filter_t)f, s, t, REAL_C(0.01), &a);
            mipmap_lookup(&r, (mipmap_filter_t)f, s + 3, t - 2, REAL_C(0.01),
                          &b);
            ck_assert(a == b);
            mipmap_lookup(&mi, (mipmap_filter_t)f, s, t, REAL_C(0.01), &a);
            mipmap_lookup(&mi, (mipmap_filter_t)f, -s, t, REAL_C(0.01), &b);
            if (f != MIPMAP_NEAREST) /* nearest at -0 vs +0 picks 2 texels */
                ck_assert(a == b);
        }
    }
    /* far outside, NaN and infinities: defined values, no overflow */
    real big[] = { (real)1e30, -(real)1e30, (real)NAN, (real)INFINITY };
    for (int i = 0; i < 4; i++)
        for (int f = 0; f < 3; f++) {
            mipmap_lookup(&r, (mipmap_filter_t)f, big[i], big[3 - i], big[i],
                          &a);
            ck_assert(isfinite(a));
            mipmap_lookup(&c, (mipmap_filter_t)f, big[i], 0, big[i], &a);
            ck_assert(isfinite(a));
        }
    mipmap_lookup(&c, MIPMAP_NEAREST, (real)1e30, 0, 0, &a);
    ck_assert(a == (real)px[w - 1]);
    mipmap_free(&r);
    mipmap_free(&c);
    mipmap_free(&mi);
    free(px);
}
END_TEST

START_TEST(bad_sizes_are_refused_with_a_message)
{
    float px[4] = { 0 };
    mipmap_t m;
    svet_error e;
    ck_assert_int_eq(mipmap_build(&m, px, 0, 1, 1, MIPMAP_REPEAT, &e),
                     SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(e.msg, "0 x 1"));
    ck_assert_int_eq(mipmap_build(&m, px, 70000, 1, 1, MIPMAP_REPEAT, &e),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(mipmap_build(&m, px, 1, 1, 5, MIPMAP_REPEAT, &e),
                     SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(e.msg, "5 channels"));
    ck_assert_int_eq(m.levels, 0);
    mipmap_free(&m);
}
END_TEST

/* A checkerboard plane z = 0 seen at a grazing angle by a pinhole camera
 * 1 above it, looking along +y and down 8 degrees: each pixel's hit
 * point and its footprint from the neighbouring pixels' hits (a plane's
 * ray differentials, Igehy 1999, in closed form). */
typedef struct {
    int w, h;
    double tan_half; /* of the vertical field of view */
} view_t;

/* the texture coordinates (u, v) where the ray through film position
 * (fx, fy) in pixels meets the plane; false above the horizon */
static bool plane_hit(const view_t *c, double fx, double fy, double *u,
                      double *v)
{
    const double pitch = -8 * 3.14159265358979323846 / 180;
    double sx = (2 * fx / c->w - 1) * c->tan_half * c->w / c->h;
    double sy = (1 - 2 * fy / c->h) * c->tan_half;
    /* camera frame: right x, up (cos, sin pitch), forward (-sin, cos) */
    double dx = sx;
    double dy = cos(pitch) + sy * -sin(pitch);
    double dz = sin(pitch) + sy * cos(pitch);
    if (dz >= -1e-9)
        return false;
    double t = 1 / -dz;
    *u = t * dx;
    *v = t * dy;
    return true;
}

START_TEST(mip_mapping_beats_nearest_texels_at_grazing_angles)
{
    /* a 256 x 256 checkerboard of 16 x 16 squares, repeated, one texture
     * unit across; the plane's (u, v) are the texture's (s, t) */
    const int tw = 256;
    float *px = malloc(sizeof *px * tw * tw);
    for (int y = 0; y < tw; y++)
        for (int x = 0; x < tw; x++)
            px[y * tw + x] = ((x / 16 + y / 16) % 2) ? 1.0f : 0.0f;
    mipmap_t m;
    ck_assert_int_eq(mipmap_build(&m, px, tw, tw, 1, MIPMAP_REPEAT, NULL),
                     SVET_OK);
    view_t c = { 64, 48, tan(20 * 3.14159265358979323846 / 180) };
    double err[3] = { 0, 0, 0 };
    int pixels = 0;
    pcg32_t g;
    pcg32_seed(&g, 30, 9);
    for (int y = 0; y < c.h; y++)
        for (int x = 0; x < c.w; x++) {
            double u, v, ux, vx, uy, vy;
            if (!plane_hit(&c, x + 0.5, y + 0.5, &u, &v) ||
                !plane_hit(&c, x + 1.5, y + 0.5, &ux, &vx) ||
                !plane_hit(&c, x + 0.5, y + 1.5, &uy, &vy))
                continue;
            /* the reference: the pixel's box, 32 x 32 stratified nearest
             * lookups */
            double ref = 0;
            for (int i = 0; i < 32; i++)
                for (int j = 0; j < 32; j++) {
                    double a, b;
                    real o;
                    if (!plane_hit(&c, x + (i + 0.5) / 32, y + (j + 0.5) / 32,
                                   &a, &b))
                        continue;
                    mipmap_lookup(&m, MIPMAP_NEAREST, (real)a, (real)b, 0, &o);
                    ref += (double)o / 1024;
                }
            /* one lookup at the pixel's centre, footprint the larger of
             * the pixel's two extents on the texture */
            double width = fmax(hypot(ux - u, vx - v), hypot(uy - u, vy - v));
            for (int f = 0; f < 3; f++) {
                real o;
                mipmap_lookup(&m, (mipmap_filter_t)f, (real)u, (real)v,
                              (real)width, &o);
                err[f] += ((double)o - ref) * ((double)o - ref);
            }
            pixels++;
        }
    ck_assert_int_gt(pixels, 1000);
    for (int f = 0; f < 3; f++)
        err[f] = sqrt(err[f] / pixels);
    /* measured: RMS error of nearest, bilinear and trilinear against the
     * supersampled reference; the mip map's is the lowest by far */
    ck_assert_msg(err[MIPMAP_TRILINEAR] < 0.3 * err[MIPMAP_NEAREST],
                  "RMS error: nearest %g, bilinear %g, trilinear %g",
                  err[0], err[1], err[2]);
    mipmap_free(&m);
    free(px);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("mipmap (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, the_pyramid_halves_down_to_one_texel_and_keeps_the_mean);
    tcase_add_test(tc, texel_centres_return_the_texel_exactly);
    tcase_add_test(tc, bilinear_is_exact_on_a_linear_image);
    tcase_add_test(tc, trilinear_blends_the_two_levels_of_the_footprint);
    tcase_add_test(tc, repeat_clamp_and_mirror);
    tcase_add_test(tc, bad_sizes_are_refused_with_a_message);
    tcase_add_test(tc, mip_mapping_beats_nearest_texels_at_grazing_angles);
    suite_add_tcase(s, tc);
    return s;
}
