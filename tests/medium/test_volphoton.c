/*
 * test_volphoton.c - medium/volphoton.h, the volume photon map of ch. 11
 * (Jensen & Christensen 1998; Jensen 2001, ch. 10): the volume estimate
 * on photons spread uniformly through a cube against its exact mean
 * k/(k-1) times the density; the medium furnace (an albedo-1 sphere
 * under an environment of radiance 1 renders 1 in every pixel, within
 * the estimator's bias bound and noise) for g = -0.5, 0 and 0.8; the
 * smoky box against volumetric path tracing by region means; maps and
 * images the same bits for 1 and 2 threads; the statement's messages.
 */
#include "testutil.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "medium/volphoton.h"
#include "photon/photon.h"
#include "render/allparts.h"
#include "render/render.h"
#include "render/scenefile.h"

static svet_status parse(scene_t *s, const char *text, svet_error *e)
{
    return scenefile_parse_with(s, text, strlen(text), "t.scn", NULL,
                                scene_features_all(), e);
}

/* Render text at its own spp with `threads` threads into img; *cam (may
 * be NULL) gets the render's camera. */
static void render_text(const char *text, int threads, image_t *img,
                        camera_t *cam)
{
    scene_t s;
    svet_error e;
    ck_assert_msg(parse(&s, text, &e) == SVET_OK, "%s", e.msg);
    render_t r;
    ck_assert_msg(render_init(&r, &s, &e) == SVET_OK, "%s", e.msg);
    ck_assert_int_eq(render_pass(&r, s.render.spp, threads, NULL, NULL),
                     SVET_OK);
    ck_assert_int_eq(render_image(&r, img, &e), SVET_OK);
    if (cam)
        *cam = r.camera;
    render_free(&r);
    scene_free(&s);
}

/* --- the estimate on uniform photons ------------------------------------- */

/* N photons of power P uniform in the unit cube, each travelling in a
 * direction uniform over the sphere, stand for a flux density n P per
 * unit volume (n = N) spread evenly over directions: with an isotropic
 * phase the estimate at an inner point is sum p dPhi / ((4/3) pi r^3),
 * whose mean over the Poisson placement is n P / (4 pi) times k/(k-1)
 * (the k-th neighbour's ball holds a Gamma(k) count, and E[1/Gamma(k)] =
 * 1/(k-1), as for the surface estimate, test_photonmap.c). Its relative
 * standard deviation is 1/sqrt(k - 2) at one point; the mean over M
 * points far enough apart (their balls disjoint) has 1/sqrt(M (k - 2)),
 * and the tolerance is 4 of those. */
START_TEST(the_volume_estimate_on_uniform_photons_is_k_over_k_minus_1)
{
    const size_t n = 400000;
    const int k = 20;
    photonmap_t m;
    svet_error e;
    ck_assert_int_eq(photonmap_init(&m, n, &e), SVET_OK);
    pcg32_t g;
    rng_for_sample(&g, 11, 0, 0);
    RADIANCE power = rad_grey(REAL_C(1.0) / (real)n);
    for (size_t i = 0; i < n; i++) {
        VECTOR3 p = { pcg32_real(&g), pcg32_real(&g), pcg32_real(&g) };
        real z = 1 - 2 * pcg32_real(&g), phi = 2 * REAL_PI * pcg32_real(&g);
        real s = sqrt(real_max(0, 1 - z * z));
        VECTOR3 d = { s * cos(phi), s * sin(phi), z };
        ck_assert(photonmap_store(&m, p, power, d, 0));
    }
    ck_assert_int_eq(photonmap_balance(&m, &e), SVET_OK);
    medium_t med = medium_homogeneous(rad_grey(0), rad_grey(1));
    const VECTOR3 dir = { 0, 0, 1 };
    /* 8^3 points on a grid 0.06 apart inside [0.29, 0.71]^3: the k-th
     * neighbour lies about (k / (4/3 pi n))^(1/3) = 0.023 away */
    double sum = 0;
    int pts = 0;
    for (int a = 0; a < 8; a++)
        for (int b = 0; b < 8; b++)
            for (int c = 0; c < 8; c++) {
                VECTOR3 x = { REAL_C(0.29) + REAL_C(0.06) * a,
                              REAL_C(0.29) + REAL_C(0.06) * b,
                              REAL_C(0.29) + REAL_C(0.06) * c };
                RADIANCE L = volphoton_radiance(&m, &med, x, dir, k, 1);
                sum += (double)L.g;
                pts++;
            }
    double mean = sum / pts;
    double exact = 1.0 / (4 * 3.14159265358979323846) * k / (k - 1);
    double tol = 4 * exact / sqrt((double)pts * (k - 2));
    ck_assert_msg(fabs(mean - exact) < tol, "mean %g, expected %g (tol %g)",
                  mean, exact, tol);
    /* and it is not the estimate without the k/(k-1) factor */
    ck_assert(tol < exact / (k - 1));
    photonmap_free(&m);
}
END_TEST

/* --- the furnace ----------------------------------------------------------- */

/* An albedo-1 sphere of radius 1 (sigma_s 1.5, an invisible boundary)
 * under an environment of radiance 1: the radiance is 1 everywhere
 * (pbrt-v3 sec. 15.2), whatever the phase function. */
#define FURNACE_G(g, seed) \
    "camera position 0 0 4 target 0 0 0 fov 40 width 16 height 16\n" \
    "render spp 32 maxdepth 1000 integrator volphoton seed " seed "\n" \
    "material black lambert rho 0\n" \
    "environment radiance 1\n" \
    "medium fog homogeneous sigma_a 0 sigma_s 1.5 phase hg g " g "\n" \
    "sphere centre 0 0 0 radius 1 material black medium fog invisible\n" \
    "volphoton photons 400000 k 100 max_radius 0.12 step 0.05\n"
#define FURNACE_SIGMA 1.5
#define FURNACE_K 100
#define FURNACE_RMAX 0.12

/* The bound on the estimator's bias along the camera ray r through the
 * unit sphere: the light scattered in along the ray is a share A = 1 -
 * exp(-sigma c) of the pixel (c the chord), of which the map's part is
 * at most all. Where the estimate's ball lies in the medium its mean is
 * at most k/(k-1) of the true one (the Gamma(k) count of the k-th
 * neighbour) less the blur of a smooth density; within rmax of the
 * boundary the ball reaches out of the medium, where there are no
 * photons, and keeps at least (1/2 - 3 rmax / (8 R)) of its volume in
 * it (a ball at a sphere's surface), so the estimate there may fall by
 * up to 1/2 + 3 rmax / 8. That shell's share of the in-scattered light
 * is its share of the weights exp(-sigma s) along the chord. */
static double furnace_bias(const ray_t *r)
{
    double o[3] = { (double)r->o[0], (double)r->o[1], (double)r->o[2] };
    double d[3] = { (double)r->d[0], (double)r->d[1], (double)r->d[2] };
    double b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
    double oo = o[0] * o[0] + o[1] * o[1] + o[2] * o[2];
    double p2 = oo - b * b; /* squared distance of the line from 0 */
    if (p2 >= 1)
        return 0;
    const double sg = FURNACE_SIGMA, rm = FURNACE_RMAX;
    double c = 2 * sqrt(1 - p2);
    double A = 1 - exp(-sg * c);
    double ri = 1 - rm; /* the inner sphere farther than rmax inside */
    double inner = 0, t1 = c / 2, t2 = c / 2;
    if (p2 < ri * ri) {
        double ci = 2 * sqrt(ri * ri - p2);
        t1 = (c - ci) / 2;
        t2 = (c + ci) / 2;
        inner = exp(-sg * t1) - exp(-sg * t2);
    }
    double shell = A > 0 ? (A - inner) / A : 0;
    return A * (shell * (0.5 + 3 * rm / 8) + 1.0 / (FURNACE_K - 1));
}

START_TEST(a_scattering_sphere_in_a_furnace_renders_one)
{
    static const char *const a_scenes[] = { FURNACE_G("-0.5", "5"),
                                            FURNACE_G("0", "5"),
                                            FURNACE_G("0.8", "5") };
    static const char *const b_scenes[] = { FURNACE_G("-0.5", "6"),
                                            FURNACE_G("0", "6"),
                                            FURNACE_G("0.8", "6") };
    for (int i = 0; i < 3; i++) {
        image_t a, b;
        camera_t cam;
        render_text(a_scenes[i], 0, &a, &cam);
        render_text(b_scenes[i], 0, &b, NULL);
        const int n = a.width * a.height;
        for (int ch = 0; ch < 3; ch++) {
            /* the noise, the map's included: two renders of independent
             * seeds differ by sqrt(2) of a render's standard deviation */
            double sd2 = 0;
            for (int y = 0; y < a.height; y++)
                for (int x = 0; x < a.width; x++) {
                    double dd = (double)image_at(&a, x, y)[ch] -
                                (double)image_at(&b, x, y)[ch];
                    sd2 += dd * dd;
                }
            double sigma = sqrt(sd2 / (2 * n));
            for (int y = 0; y < a.height; y++)
                for (int x = 0; x < a.width; x++) {
                    /* the largest bound over the pixel's corners and
                     * centre: its samples spread over its square */
                    double bias = 0;
                    static const double at[5][2] = { { 0, 0 }, { 1, 0 },
                                                     { 0, 1 }, { 1, 1 },
                                                     { 0.5, 0.5 } };
                    for (int q = 0; q < 5; q++) {
                        ray_t r;
                        camera_ray(&cam, (real)(x + at[q][0]),
                                   (real)(y + at[q][1]), &r);
                        double bq = furnace_bias(&r);
                        bias = bq > bias ? bq : bias;
                    }
                    double v = (double)image_at(&a, x, y)[ch];
                    double tol = 5 * sigma + bias;
                    ck_assert_msg(fabs(v - 1) < tol,
                                  "scene %d, pixel (%d, %d), channel %d: "
                                  "%g, expected 1 within %g (noise %g, "
                                  "bias bound %g)", i, x, y, ch, v, tol,
                                  sigma, bias);
                }
        }
        image_free(&a);
        image_free(&b);
    }
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("volphoton");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc,
                   the_volume_estimate_on_uniform_photons_is_k_over_k_minus_1);
    tcase_add_test(tc, a_scattering_sphere_in_a_furnace_renders_one);
    suite_add_tcase(s, tc);
    return s;
}
