/*
 * test_volsingle.c - `render integrator volsingle` (src/medium/volsingle.c),
 * single scattering by ray marching: a thin homogeneous slab lit by a
 * far light against the closed form of its singly scattered radiance,
 * lit from the front and from behind; the error of the jittered march
 * falls as the step h (its order), with the constant its leading term
 * predicts; where the density varies, the marched transmittance is the
 * trapezoid rule's, its error of order h^2; one thread and two give the
 * same bits; the `volsingle`
 * statement and its override; a mix of an isotropic and a forward HG
 * component scatters by each one's phase, weighted by its sigma_s.
 */
#include "testutil.h"
#include "scenecheck.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "medium/medpart.h"
#include "medium/volsingle.h"
#include "render/allparts.h"
#include "render/render.h"
#include "render/scenefile.h"

static const double PI = 3.14159265358979323846;

/* The slab: z in [-1, 0] (thickness d = 1) of homogeneous medium behind
 * an invisible boundary, wide enough that every shadow ray leaves it
 * through a face z = 0 or z = -1; the camera on the z axis looks along
 * -z with a field of view of 0.1 degree (its rays are straight on within
 * 1e-6 in cos). The light is a point at distance D = 1e4 in direction
 * (sin a, 0, +-cos a), of intensity D^2: across the slab its rays are
 * parallel within 1e-4 and its irradiance is E = 1 within 2 d / D =
 * 2e-4 (the ratio of squared distances), a distant light to well below
 * the tolerances here. Nothing else: no environment, no surface seen. */
static char *slab_scene(const char *sigma_a, const char *sigma_s,
                        const char *phase, double a, bool front, double h)
{
    const double D = 1e4;
    static char buf[1024];
    snprintf(buf, sizeof buf,
             "camera position 0 0 5 target 0 0 0 fov 0.1 width 1 height 1\n"
             "render spp 1 maxdepth 1 integrator volsingle seed 11\n"
             "volsingle step %.17g\n"
             "material black lambert rho 0\n"
             "medium slab homogeneous sigma_a %s sigma_s %s %s\n"
             "light point position %.17g 0 %.17g intensity %.17g\n"
             "box min -100 -100 -1 max 100 100 0 material black medium slab "
             "invisible\n",
             h, sigma_a, sigma_s, phase, D * sin(a),
             (front ? 1 : -1) * D * cos(a), D * D);
    return buf;
}

/* The singly scattered radiance leaving the slab toward the camera, one
 * channel. A point at depth s (0..d) along the camera ray is reached
 * with transmittance exp(-st s); the light, at angle a to the normal
 * (mu = cos a), crosses s / mu of medium from the front, (d - s) / mu
 * from behind; its direction of travel turns by the angle whose cosine
 * is -mu (front: back toward the camera) or mu (behind). Then
 *   L = int_0^d E ss p exp(-st s) Tl(s) ds
 *     = E ss p (1 - exp(-st d (1 + 1/mu))) / (st (1 + 1/mu))     (front)
 *     = E ss p (exp(-st d) - exp(-st d / mu)) / (st (1/mu - 1))  (behind,
 *       mu < 1).
 * Its integrand at the two ends, f(0) and f(d), for the march's error. */
typedef struct {
    double L, f0, fd;
} slab_t;

static slab_t slab_closed_form(double sa, double ss, double p, double mu,
                               bool front)
{
    const double st = sa + ss, d = 1, E = 1;
    slab_t r;
    if (front) {
        double k = st * (1 + 1 / mu);
        r.L = E * ss * p * (1 - exp(-k * d)) / k;
        r.f0 = E * ss * p;
        r.fd = E * ss * p * exp(-k * d);
    } else {
        r.L = E * ss * p * (exp(-st * d) - exp(-st * d / mu)) /
              (st * (1 / mu - 1));
        r.f0 = E * ss * p * exp(-st * d / mu);
        r.fd = E * ss * p * exp(-st * d);
    }
    return r;
}

static double hg(double g, double c)
{
    return (1 - g * g) / (4 * PI * pow(1 + g * g - 2 * g * c, 1.5));
}

/* n samples of the one pixel: their mean and variance per channel. */
static void sample_slab(const char *text, int n, double mean[3],
                        double var[3])
{
    scene_t s;
    svet_error e;
    ck_assert_msg(scenecheck_parse(&s, text, &e) == SVET_OK, "%s", e.msg);
    render_t r;
    ck_assert_msg(render_init(&r, &s, &e) == SVET_OK, "%s", e.msg);
    double sum[3] = { 0, 0, 0 }, sum2[3] = { 0, 0, 0 };
    for (long i = 0; i < n; i++) {
        integrator_stats_t st = { 0, 0 };
        RADIANCE v = render_sample(&r, 0, 0, i, &st);
        const double c[3] = { (double)v.r, (double)v.g, (double)v.b };
        for (int k = 0; k < 3; k++) {
            sum[k] += c[k];
            sum2[k] += c[k] * c[k];
        }
    }
    for (int k = 0; k < 3; k++) {
        mean[k] = sum[k] / n;
        var[k] = (sum2[k] / n - mean[k] * mean[k]) * n / (n - 1);
    }
    render_free(&r);
    scene_free(&s);
}

/* The march t_i = (i + u) h, i = 0 .. n - 1, over the slab's length
 * d = n h, is a randomly shifted rectangle rule: its expectation over u
 * is the integral, so the mean of many samples matches the closed form
 * within its standard error at any step. Per channel, 4 standard errors
 * of the sample mean, plus 3e-4 L for the far light not being distant. */
START_TEST(front_and_back_lit_slab_matches_the_closed_form)
{
    const double sa[3] = { 0.2, 0.5, 0.1 }, ss[3] = { 0.6, 0.3, 0.9 };
    const double a = PI / 3, mu = cos(a), g = 0.3;
    for (int front = 0; front < 2; front++) {
        double mean[3], var[3];
        sample_slab(slab_scene("0.2 0.5 0.1", "0.6 0.3 0.9", "phase hg g 0.3",
                               a, front, 0.25),
                    4096, mean, var);
        for (int k = 0; k < 3; k++) {
            slab_t c = slab_closed_form(sa[k], ss[k],
                                        hg(g, front ? -mu : mu), mu, front);
            double se = sqrt(var[k] / 4096);
            ck_assert_msg(fabs(mean[k] - c.L) < 4 * se + 3e-4 * c.L,
                          "%s, channel %d: %g, closed form %g (se %g)",
                          front ? "front" : "behind", k, mean[k], c.L, se);
            /* and the test can see a 2% error */
            ck_assert_msg(4 * se < 0.02 * c.L, "se %g of %g", se, c.L);
        }
    }
}
END_TEST

/* The order of the march. With d = n h and u uniform, the error of the
 * shifted rectangle rule is, by the Euler-Maclaurin formula for shifted
 * points (B_k the Bernoulli polynomials),
 *   e(u) = h B1(u) (f(d) - f(0)) + h^2 B2(u) / 2 (f'(d) - f'(0)) + ...,
 * with B1(u) = u - 1/2 of variance 1/12 and uncorrelated with B2(u)
 * (odd and even about 1/2), so the standard deviation of one sample is
 *   sigma(h) = h |f(d) - f(0)| / sqrt(12) (1 + O(h^2)):
 * first order, halving with the step. The relative O(h^2) term is
 * h^2 (k^2 / 60) for f = f0 exp(-k s), here k = 2.4: 0.4% at h = 1/4.
 * The only randomness is u (a point light, one light, homogeneous
 * shadow rays: exact), so the samples' spread is the march's error. The
 * sample variance of n samples of a uniform variable has relative
 * standard error sqrt((kurtosis - 1) / n) = sqrt(0.8 / n), 2% for n =
 * 2048, so the standard deviation 1%; the ratio of two of them 1.4%.
 * Asserted: each sigma within 5% of the prediction (4 standard errors
 * and the O(h^2) term), each ratio sigma(h) / sigma(h/2) within 6% of
 * 2 (4 standard errors), at h = 1/4, 1/8, 1/16, and each mean within 4
 * standard errors of the closed form. */
START_TEST(the_march_error_falls_as_the_step)
{
    const double sa = 0.2, ss = 0.6, a = PI / 3, mu = cos(a), g = 0.3;
    const int n = 2048;
    slab_t c = slab_closed_form(sa, ss, hg(g, -mu), mu, true);
    double prev = 0;
    for (int i = 0; i < 3; i++) {
        double h = 0.25 / (1 << i), mean[3], var[3];
        sample_slab(slab_scene("0.2", "0.6", "phase hg g 0.3", a, true, h), n,
                    mean, var);
        double sigma = sqrt(var[0]);
        double want = h * fabs(c.fd - c.f0) / sqrt(12.0);
        ck_assert_msg(fabs(sigma / want - 1) < 0.05,
                      "h = %g: sigma %g, predicted %g", h, sigma, want);
        ck_assert_msg(fabs(mean[0] - c.L) < 4 * sqrt(var[0] / n) + 3e-4 * c.L,
                      "h = %g: mean %g, closed form %g", h, mean[0], c.L);
        if (i > 0)
            ck_assert_msg(fabs(prev / sigma / 2 - 1) < 0.06,
                          "sigma(%g) / sigma(%g) = %g, order 1 gives 2",
                          2 * h, h, prev / sigma);
        prev = sigma;
    }
}
END_TEST

/* Where the density varies the march accumulates the optical depth by
 * the trapezoid rule over its points 0, t_0 = u h, t_1, ..., len. For the
 * density z^2 along the z axis from 0 to len = 2 (optical depth 8/3 at
 * density 1) the rule's error on an interval of width D is exactly
 * D^3 f'' / 12 = D^3 / 6 (f'' = 2, constant), so the marched depth is
 * 8/3 + sum D^3 / 6, about len h^2 / 6: second order. The test redraws
 * the march's u (the first number of the same stream), predicts each
 * channel's exp(-sigma_t tau) to float precision, and checks that the
 * error against exp(-sigma_t 8/3) falls by 4 (3 to 5, the end intervals
 * shifting with h) each time h halves. */
static real squared_z(const void *ctx, const VECTOR3 p)
{
    (void)ctx;
    return p[Z] * p[Z];
}

START_TEST(the_marched_transmittance_of_a_varying_density_is_second_order)
{
    medium_t m = medium_homogeneous(rad_make(REAL_C(0.5), 1, REAL_C(0.25)),
                                    rad_grey(0));
    m.fn = squared_z;
    m.fn_max = 4;
    integrator_t it;
    memset(&it, 0, sizeof it);
    ray_t r;
    memset(&r, 0, sizeof r);
    r.d[Z] = 1;
    const double len = 2, exact_tau = 8.0 / 3, sig = 1; /* channel g */
    double prev = 0;
    for (int i = 0; i < 3; i++) {
        double h = 0.1 / (1 << i);
        volpath_state_t s = { .step = (real)h };
        pcg32_t g, g2;
        pcg32_seed(&g, 3, 7);
        g2 = g;
        integrator_stats_t st = { 0, 0 };
        RADIANCE tr;
        RADIANCE L = volsingle_march(&s, &it, &m, &r, r.d, (real)len, false,
                                     &g, &st, &tr);
        ck_assert(rad_is_black(L));
        double u = (double)pcg32_real(&g2), sum = 0, t_prev = 0;
        for (int k = 0;; k++) {
            double t = ((double)k + u) * h;
            if (!(t < len))
                break;
            sum += pow(t - t_prev, 3);
            t_prev = t;
        }
        sum += pow(len - t_prev, 3);
        double tau = exact_tau + sum / 6;
        double want = exp(-sig * tau), got = (double)tr.g;
        ck_assert_msg(fabs(got / want - 1) < 1e-4,
                      "h = %g: Tr %.8g, the trapezoid rule's %.8g", h, got,
                      want);
        double err = fabs(got - exp(-sig * exact_tau));
        if (i > 0)
            ck_assert_msg(prev / err > 3 && prev / err < 5,
                          "error(%g) / error(%g) = %g, order 2 gives 4",
                          2 * h, h, prev / err);
        prev = err;
    }
}
END_TEST

/* A scene with a surface, an area light, a global fog and a sphere of
 * scattering medium: each pixel's march, light samples and ratio-tracked
 * shadow rays draw from the pixel's own stream. */
#define FOGGY \
    "camera position 0 0 4 target 0 0 0 fov 40 width 8 height 8\n" \
    "render spp 8 maxdepth 3 integrator volsingle seed 5\n" \
    "volsingle step 0.2\n" \
    "material grey lambert rho 0.5\n" \
    "material black lambert rho 0\n" \
    "medium fog homogeneous sigma_a 0.02 sigma_s 0.05 global\n" \
    "medium cloud homogeneous sigma_a 0.1 sigma_s 1 phase hg g 0.5\n" \
    "parallelogram c0 -1 2 -1 c1 1 2 -1 c3 -1 2 1 material black emit 5\n" \
    "plane point 0 -1 0 normal 0 1 0 material grey\n" \
    "sphere centre 0 0 0 radius 0.8 material black medium cloud invisible\n"

START_TEST(one_thread_and_two_give_the_same_bits)
{
    image_t a, b;
    scenecheck_render(FOGGY, 1, &a);
    scenecheck_render(FOGGY, 2, &b);
    ck_assert_int_eq(a.width, b.width);
    double sum = 0;
    for (int y = 0; y < a.height; y++)
        for (int x = 0; x < a.width; x++) {
            ck_assert(memcmp(image_at(&a, x, y), image_at(&b, x, y),
                             3 * sizeof *image_at(&a, x, y)) == 0);
            sum += (double)image_at(&a, x, y)[0];
        }
    ck_assert_msg(sum > 0, "the scene is lit");
    image_free(&a);
    image_free(&b);
}
END_TEST

START_TEST(the_step_statement_and_its_override)
{
    scene_t s;
    svet_error e;
    ck_assert_msg(scenecheck_parse(&s, FOGGY, &e) == SVET_OK, "%s", e.msg);
    ck_assert_msg(scenefile_override(&s, "volsingle.step=0.5", &e) ==
                      SVET_OK, "%s", e.msg);
    scene_free(&s);
    const char *bad[][2] = {
        { "volsingle step 0\n", "t.scn:1:" },
        { "volsingle step -1\n", "t.scn:1:" },
        { "volsingle stp 0.1\n", "t.scn:1:" },
        { "volsingle step nan\n", "t.scn:1:" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        ck_assert_int_ne(scenecheck_parse(&s, bad[i][0], &e), SVET_OK);
        ck_assert_msg(strncmp(e.msg, bad[i][1], strlen(bad[i][1])) == 0,
                      "'%s': %s", bad[i][0], e.msg);
    }
}
END_TEST

/* The slab as a mix (`medium NAME mix`) of an isotropic, absorbing
 * component and a forward HG one (g = 0.8), scattering per channel in
 * other proportions: its single scattering is the closed form above with
 * sigma_t and sigma_s summed and the phase sum_i sigma_s_i p_i /
 * sigma_s, each component's phase weighted by its sigma_s. Lit from the
 * front (scattering angle cos -mu) and from behind (cos mu), per
 * channel within 4 standard errors; one phase for both, the isotropic
 * or the HG one, misses by far more. */
static char *mix_slab_scene(double a, bool front, double h)
{
    const double D = 1e4;
    static char buf[1024];
    snprintf(buf, sizeof buf,
             "camera position 0 0 5 target 0 0 0 fov 0.1 width 1 height 1\n"
             "render spp 1 maxdepth 1 integrator volsingle seed 11\n"
             "volsingle step %.17g\n"
             "material black lambert rho 0\n"
             "medium iso homogeneous sigma_a 0.2 0.5 0.1 "
             "sigma_s 0.3 0.1 0.5\n"
             "medium fwd homogeneous sigma_s 0.3 0.2 0.4 phase hg g 0.8\n"
             "medium slab mix iso fwd\n"
             "light point position %.17g 0 %.17g intensity %.17g\n"
             "box min -100 -100 -1 max 100 100 0 material black medium slab "
             "invisible\n",
             h, D * sin(a), (front ? 1 : -1) * D * cos(a), D * D);
    return buf;
}

START_TEST(a_mix_scatters_by_each_components_phase)
{
    const double sa[3] = { 0.2, 0.5, 0.1 }, s1[3] = { 0.3, 0.1, 0.5 };
    const double s2[3] = { 0.3, 0.2, 0.4 };
    const double a = PI / 3, mu = cos(a);
    for (int front = 0; front < 2; front++) {
        double mean[3], var[3];
        sample_slab(mix_slab_scene(a, front, 0.25), 4096, mean, var);
        const double c = front ? -mu : mu;
        for (int k = 0; k < 3; k++) {
            double ss = s1[k] + s2[k];
            double p = (s1[k] / (4 * PI) + s2[k] * hg(0.8, c)) / ss;
            slab_t cf = slab_closed_form(sa[k], ss, p, mu, front);
            double se = sqrt(var[k] / 4096);
            ck_assert_msg(fabs(mean[k] - cf.L) < 4 * se + 3e-4 * cf.L,
                          "%s, channel %d: %g, closed form %g (se %g)",
                          front ? "front" : "behind", k, mean[k], cf.L, se);
            ck_assert_msg(4 * se < 0.02 * cf.L, "se %g of %g", se, cf.L);
        }
    }
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("volsingle");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, front_and_back_lit_slab_matches_the_closed_form);
    tcase_add_test(tc, the_march_error_falls_as_the_step);
    tcase_add_test(tc,
                   the_marched_transmittance_of_a_varying_density_is_second_order);
    tcase_add_test(tc, one_thread_and_two_give_the_same_bits);
    tcase_add_test(tc, the_step_statement_and_its_override);
    tcase_add_test(tc, a_mix_scatters_by_each_components_phase);
    suite_add_tcase(s, tc);
    return s;
}
