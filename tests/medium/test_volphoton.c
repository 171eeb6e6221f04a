/*
 * test_volphoton.c - medium/volphoton.h, the volume photon map of ch. 11
 * (Jensen & Christensen 1998; Jensen 2001, ch. 10): the volume estimate
 * on photons spread uniformly through a cube against its exact mean
 * k/(k-1) times the density; the medium furnace (an albedo-1 sphere
 * under an environment of radiance 1 renders 1 in every pixel, within
 * the estimator's bias bound and noise) for g = -0.5, 0 and 0.8; the
 * fixed-radius estimate's bias on photons of a quadratic density against
 * its closed form a R^2 / 5, growing with the radius R; the smoky box
 * and a glowing sphere (photons the medium emits) against volumetric
 * path tracing by region means; maps and
 * images the same bits for 1 and 2 threads; the statement's messages.
 */
#include "testutil.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "core/sample.h"
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

/* A direction uniform over the sphere, from g. */
static void random_direction(pcg32_t *g, VECTOR3 d)
{
    const real u[2] = { pcg32_real(g), pcg32_real(g) };
    sample_uniform_sphere(d, u);
}

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
        VECTOR3 d;
        random_direction(&g, d);
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

/* N photons of power 1/N in the unit cube with density in z proportional
 * to 1 + a (z - 1/2)^2 (its mean over [0, 1] is 1 + a/12), directions
 * uniform over the sphere, isotropic phase: the estimate with r fixed at
 * rmax (k above any count in the ball) averages the density over the
 * ball, so its mean at a point of z = 1/2 is
 *   n0 (1 + a R^2 / 5) / (4 pi),   n0 = N / (1 + a/12)
 * (the mean of (z - 1/2)^2 over a ball of radius R is R^2 / 5): a bias
 * of a R^2 / 5 of the answer n0 / (4 pi) there, growing as the radius
 * squared. The count in a ball is Poisson (N large) with mean c = n0 (4/3)
 * pi R^3 (1 + a R^2 / 5); over M points whose balls are disjoint the
 * mean's relative standard deviation is 1 / sqrt(M c), and the tolerance
 * 4 of those. At the two larger radii the bias is more than 4 of them
 * (checked), so an estimate without it, or with another volume, fails. */
START_TEST(the_volume_estimates_bias_grows_as_the_radius_squared)
{
    const size_t n = 240000;
    const double a = 48, PI_D = 3.14159265358979323846;
    photonmap_t m;
    svet_error e;
    ck_assert_int_eq(photonmap_init(&m, n, &e), SVET_OK);
    pcg32_t g;
    rng_for_sample(&g, 12, 0, 0);
    RADIANCE power = rad_grey(REAL_C(1.0) / (real)n);
    for (size_t i = 0; i < n; i++) {
        /* z by rejection under the density's largest value, 1 + a/4 */
        real z;
        do
            z = pcg32_real(&g);
        while (!((double)pcg32_real(&g) * (1 + a / 4) <
                 1 + a * (double)((z - REAL_C(0.5)) * (z - REAL_C(0.5)))));
        VECTOR3 p = { pcg32_real(&g), pcg32_real(&g), z };
        VECTOR3 d;
        random_direction(&g, d);
        ck_assert(photonmap_store(&m, p, power, d, 0));
    }
    ck_assert_int_eq(photonmap_balance(&m, &e), SVET_OK);
    medium_t med = medium_homogeneous(rad_grey(0), rad_grey(1));
    const VECTOR3 dir = { 0, 0, 1 };
    /* the flux density n0 P / (4 pi), P = 1 / N the photons' power */
    const double n0 = (double)n / (1 + a / 12);
    const double answer = n0 / (double)n / (4 * PI_D);
    static const double radii[3] = { 0.05, 0.1, 0.15 };
    double measured[3];
    for (int ri = 0; ri < 3; ri++) {
        const double R = radii[ri];
        /* points 2R apart on z = 1/2, their balls inside the cube */
        double sum = 0;
        int pts = 0;
        for (double x = R; x <= 1 - R + 1e-9; x += 2 * R)
            for (double y = R; y <= 1 - R + 1e-9; y += 2 * R) {
                VECTOR3 q = { (real)x, (real)y, REAL_C(0.5) };
                RADIANCE L = volphoton_radiance(&m, &med, q, dir,
                                                PHOTON_MAX_K, (real)R);
                sum += (double)L.g;
                pts++;
            }
        double bias = a * R * R / 5;
        double count = n0 * 4.0 / 3 * PI_D * R * R * R * (1 + bias);
        ck_assert(count < 0.85 * PHOTON_MAX_K); /* r stays rmax */
        double rel_sd = 1 / sqrt(pts * count);
        measured[ri] = sum / pts / answer - 1;
        ck_assert_msg(fabs(measured[ri] - bias) < 4 * rel_sd,
                      "R = %g: relative bias %g, expected a R^2 / 5 = %g "
                      "(tol %g, %d points)", R, measured[ri], bias,
                      4 * rel_sd, pts);
        if (ri > 0)
            ck_assert(bias > 4 * rel_sd);
    }
    /* and it falls as the radius shrinks */
    ck_assert(measured[2] > measured[1] && measured[1] > measured[0]);
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

/* --- against volumetric path tracing ----------------------------------------- */

/* The smoky Cornell box of scenes/smoky-cbox.scn, small. */
#define SMOKY(method, spp, seed, keys) \
    "camera position 0 0 3.9 target 0 0 0 up 0 1 0\n" \
    "camera fov 39.3077 fov_axis y width 16 height 16 filter box\n" \
    "render spp " spp " maxdepth 7 roulette on roulette_depth 3 seed " seed \
    "\nrender integrator " method "\n" \
    "material white lambert rho 0.885809 0.698859 0.666422\n" \
    "material green lambert rho 0.105421 0.37798 0.076425\n" \
    "material red   lambert rho 0.570068 0.0430135 0.0443706\n" \
    "parallelogram c0 -1 -1 1   c1 1 -1 1   c2 1 -1 -1  c3 -1 -1 -1  " \
    "material white\n" \
    "parallelogram c0 -1 1 -1   c1 1 1 -1   c2 1 1 1    c3 -1 1 1    " \
    "material white\n" \
    "parallelogram c0 -1 -1 -1  c1 1 -1 -1  c2 1 1 -1   c3 -1 1 -1   " \
    "material white\n" \
    "parallelogram c0 1 -1 -1   c1 1 -1 1   c2 1 1 1    c3 1 1 -1    " \
    "material green\n" \
    "parallelogram c0 -1 -1 1   c1 -1 -1 -1 c2 -1 1 -1  c3 -1 1 1    " \
    "material red\n" \
    "parallelogram c0 -0.23 0.99 -0.18  c1 0.23 0.99 -0.18  " \
    "c2 0.23 0.99 0.2  c3 -0.23 0.99 0.2  material white  " \
    "emit 18.387 13.9873 6.75357\n" \
    "box min -1 -1 -1 max 1 1 1  scale 0.3 rotate y -17 " \
    "translate 0.335 -0.7 0.38 material white\n" \
    "box min -1 -1 -1 max 1 1 1  scale 0.3 0.61 0.3 rotate y 18.25 " \
    "translate -0.33 -0.4 -0.28 material white\n" \
    "medium smoke homogeneous sigma_a 0.05 sigma_s 0.5 phase hg g 0.3\n" \
    "box min -0.999 -0.999 -0.999 max 0.999 0.98 0.999 material white " \
    "medium smoke invisible\n" keys

#define REGION 4
#define NREGION 16

/* The means of the 4 x 4 regions of the mean of a and b, two renders of
 * independent seeds, and the variances of those means: of a region's
 * mean in one render the larger of two estimates, the sum of its pixels'
 * variances (a_p - b_p)^2 / 2 over the pixels squared (pixels
 * independent) and (A - B)^2 / 2 of the regions' means A and B (what the
 * map's noise shares between the pixels), halved for the mean of two. */
static void region_means(const image_t *a, const image_t *b, int ch,
                         double *mean, double *var)
{
    int nr = a->width / REGION;
    for (int ry = 0; ry < nr; ry++)
        for (int rx = 0; rx < nr; rx++) {
            double sa = 0, sb = 0, sp = 0;
            for (int y = ry * REGION; y < (ry + 1) * REGION; y++)
                for (int x = rx * REGION; x < (rx + 1) * REGION; x++) {
                    double va = (double)image_at(a, x, y)[ch];
                    double vb = (double)image_at(b, x, y)[ch];
                    sa += va;
                    sb += vb;
                    sp += (va - vb) * (va - vb) / 2;
                }
            const double n = REGION * REGION;
            double A = sa / n, B = sb / n;
            double vpix = sp / (n * n), vreg = (A - B) * (A - B) / 2;
            mean[ry * nr + rx] = (A + B) / 2;
            var[ry * nr + rx] = (vpix > vreg ? vpix : vreg) / 2;
        }
}

/* Two volphoton renders a, b against two volpath renders r1, r2 (other
 * seeds) by region means: every region within 4 standard deviations of
 * the difference in every channel, and at least min_tight of the
 * region-channels tight (standard deviation below `tight` of the mean),
 * so that the agreement says something. */
static void agrees_with_volpath(const image_t *r1, const image_t *r2,
                                const image_t *a, const image_t *b,
                                double tight, int min_tight)
{
    ck_assert_int_eq(a->width / REGION * (a->height / REGION), NREGION);
    int n_tight = 0;
    for (int ch = 0; ch < 3; ch++) {
        double mr[NREGION], vr[NREGION], mp[NREGION], vp[NREGION];
        region_means(r1, r2, ch, mr, vr);
        region_means(a, b, ch, mp, vp);
        for (int i = 0; i < NREGION; i++) {
            double sd = sqrt(vr[i] + vp[i]);
            ck_assert_msg(fabs(mp[i] - mr[i]) < 4 * sd,
                          "channel %d, region %d: volphoton %g, volpath %g "
                          "(sd %g)", ch, i, mp[i], mr[i], sd);
            n_tight += sd < tight * mr[i];
        }
    }
    ck_assert_int_ge(n_tight, min_tight);
}

/* Volumetric path tracing is unbiased; the volume photon map's bias (the
 * blur of its estimates, k/(k-1), the surface map's) is below its noise
 * at 400 000 photons and these radii. Each region's mean of the two
 * must agree within 4 standard deviations of their difference, and that
 * deviation must be small against the mean (10 per cent) where the
 * region is not the light's, for the test to see an error of that size
 * in the multiply scattered light. */
#define SMOKY_VP "volphoton photons 400000 k 50 max_radius 0.1 step 0.05\n"
START_TEST(the_smoky_box_agrees_with_volpath)
{
    image_t r1, r2, a, b;
    render_text(SMOKY("volpath", "512", "1", ""), 0, &r1, NULL);
    render_text(SMOKY("volpath", "512", "2", ""), 0, &r2, NULL);
    render_text(SMOKY("volphoton", "16", "1", SMOKY_VP), 0, &a, NULL);
    render_text(SMOKY("volphoton", "16", "2", SMOKY_VP), 0, &b, NULL);
    /* all but the two regions of the light in the three channels */
    agrees_with_volpath(&r1, &r2, &a, &b, 0.1, 3 * (NREGION - 2));
    image_free(&r1);
    image_free(&r2);
    image_free(&a);
    image_free(&b);
}
END_TEST

/* A glowing sphere (sigma_a 0.5, sigma_s 1.5, emission L_e per channel,
 * HG g 0.3) with no light: the radiance seen is its emission along the
 * camera ray plus that emission scattered once or more, which only the
 * photons the medium emits carry. Against volumetric path tracing by
 * region means, as the smoky box; the sphere's regions must be tight
 * (standard deviation below 5 per cent of the mean) for the test to see
 * the scattered part, about half of the radiance at the centre. */
#define GLOW(method, spp, seed) \
    "camera position 0 0 4 target 0 0 0 fov 32 width 16 height 16\n" \
    "render spp " spp " maxdepth 100 integrator " method " seed " seed "\n" \
    "material black lambert rho 0\n" \
    "medium glow homogeneous sigma_a 0.5 sigma_s 1.5 emission 1 0.5 2 " \
    "phase hg g 0.3\n" \
    "sphere centre 0 0 0 radius 1 material black medium glow invisible\n" \
    "volphoton photons 400000 k 50 max_radius 0.06 step 0.05\n"
START_TEST(an_emitting_medium_agrees_with_volpath)
{
    image_t r1, r2, a, b;
    render_text(GLOW("volpath", "256", "1"), 0, &r1, NULL);
    render_text(GLOW("volpath", "256", "2"), 0, &r2, NULL);
    render_text(GLOW("volphoton", "16", "1"), 0, &a, NULL);
    render_text(GLOW("volphoton", "16", "2"), 0, &b, NULL);
    /* the four central regions at least, in every channel */
    agrees_with_volpath(&r1, &r2, &a, &b, 0.05, 3 * 4);
    image_free(&r1);
    image_free(&r2);
    image_free(&a);
    image_free(&b);
}
END_TEST

/* --- determinism and the statement ----------------------------------------- */

/* Photon i draws from its own stream and the chunks join in order; the
 * camera samples from theirs: one thread and two give the same bits. */
START_TEST(one_thread_and_two_give_the_same_bits)
{
    static const char scene[] =
        "camera position 0 0 4 target 0 0 0 fov 40 width 8 height 8\n"
        "render spp 2 maxdepth 50 integrator volphoton seed 3\n"
        "material grey lambert rho 0.5\n"
        "light point position 0 2.5 0 intensity 4\n"
        "medium fog homogeneous sigma_a 0.2 sigma_s 1 phase hg g 0.4\n"
        "sphere centre 0 0 0 radius 1 material grey medium fog invisible\n"
        "plane point 0 -1.2 0 normal 0 1 0 material grey\n"
        "volphoton photons 20000 k 20 max_radius 0.3 step 0.1\n";
    image_t a, b;
    render_text(scene, 1, &a, NULL);
    render_text(scene, 2, &b, NULL);
    ck_assert_int_eq(a.width, b.width);
    double sum = 0;
    for (int y = 0; y < a.height; y++)
        for (int x = 0; x < a.width; x++) {
            ck_assert(memcmp(image_at(&a, x, y), image_at(&b, x, y),
                             3 * sizeof *image_at(&a, x, y)) == 0);
            sum += (double)image_at(&a, x, y)[1];
        }
    ck_assert(sum > 0); /* not the same bits of a black image */
    image_free(&a);
    image_free(&b);
}
END_TEST

/* Parse text, expect failure with a message that starts with `where` and
 * holds `what`. */
static void refused(const char *text, const char *where, const char *what)
{
    scene_t s;
    svet_error e;
    ck_assert_int_ne(parse(&s, text, &e), SVET_OK);
    ck_assert_msg(strncmp(e.msg, where, strlen(where)) == 0 &&
                      strstr(e.msg, what),
                  "expected '%s ... %s', got '%s'", where, what, e.msg);
}

#define HEAD "camera position 0 0 3 target 0 0 0 width 8 height 6\n"

START_TEST(bad_volphoton_keys_name_file_and_line)
{
    refused(HEAD "volphoton photons 0\n", "t.scn:2:", "at least 1");
    refused(HEAD "volphoton k 0\n", "t.scn:2:", "k");
    refused(HEAD "volphoton k 5000\n", "t.scn:2:", "k");
    refused(HEAD "volphoton max_radius -1\n", "t.scn:2:", "max_radius");
    refused(HEAD "volphoton step 0\n", "t.scn:2:", "step");
    refused(HEAD "volphoton step nan\n", "t.scn:2:", "step");
    refused(HEAD "volphoton photons 100000000000000000\n", "t.scn:2:",
            "photons");
    refused(HEAD "volphoton radius 1\n", "t.scn:2:", "radius");
    /* and --set reruns the line, keeping what it does not name */
    scene_t s;
    svet_error e;
    ck_assert_msg(parse(&s, HEAD "volphoton photons 1000 k 7\n", &e) ==
                      SVET_OK, "%s", e.msg);
    ck_assert_msg(scenefile_override(&s, "volphoton.step=0.02", &e) ==
                      SVET_OK, "%s", e.msg);
    volphoton_settings_t v;
    volphoton_settings_of(&s, &v);
    ck_assert_int_eq(v.k, 7);
    ck_assert_uint_eq(v.photons, 1000);
    ck_assert(fabs((double)v.step - 0.02) < 1e-6);
    ck_assert_int_ne(scenefile_override(&s, "volphoton.k=0", &e), SVET_OK);
    scene_free(&s);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("volphoton");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc,
                   the_volume_estimate_on_uniform_photons_is_k_over_k_minus_1);
    tcase_add_test(tc, the_volume_estimates_bias_grows_as_the_radius_squared);
    tcase_add_test(tc, a_scattering_sphere_in_a_furnace_renders_one);
    tcase_add_test(tc, the_smoky_box_agrees_with_volpath);
    tcase_add_test(tc, an_emitting_medium_agrees_with_volpath);
    tcase_add_test(tc, one_thread_and_two_give_the_same_bits);
    tcase_add_test(tc, bad_volphoton_keys_name_file_and_line);
    suite_add_tcase(s, tc);
    return s;
}
