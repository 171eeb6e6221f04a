/*
 * test_medium.c - the media of ch. 11: Beer-Lambert per channel; ratio
 * tracking unbiased through a grid whose optical depth has a closed form
 * (a linear ramp); distance sampling, exact (homogeneous) and by delta
 * tracking (the ramp), giving each channel's probabilities of passing and
 * of scattering before any distance in expectation; bad coefficients;
 * media made of components: two homogeneous ones are exactly the medium
 * of their summed coefficients, two gridded ones scatter and transmit as
 * their sum does, and the scattering component is picked in proportion
 * to its sigma_s (a chi-square test); the emitted radiance along a
 * segment, exact when homogeneous and by ratio tracking with emission
 * through the ramp, against its closed form.
 * Statistical checks: fixed seeds, four standard errors of the sample.
 */
#include "testutil.h"
#include "chi2.h"
#include "medium/medium.h"

#include <math.h>
#include <string.h>

START_TEST(beer_lambert_per_channel)
{
    medium_t m = medium_homogeneous(rad_make(REAL_C(0.1), REAL_C(0.5), 2),
                                    rad_make(REAL_C(0.2), 0, 1));
    for (int i = 0; i <= 20; i++) {
        real d = (real)i * REAL_C(0.37);
        RADIANCE tr = medium_tr_homogeneous(&m, d);
        ck_assert_near(tr.r, expl(-0.3L * (long double)d), 4 * REAL_EPSILON);
        ck_assert_near(tr.g, expl(-0.5L * (long double)d), 4 * REAL_EPSILON);
        ck_assert_near(tr.b, expl(-3.0L * (long double)d), 4 * REAL_EPSILON);
        VECTOR3 o = { 0, 0, 0 }, dir = { 1, 0, 0 };
        RADIANCE t2 = medium_tr(&m, o, dir, d, NULL);
        ck_assert(t2.r == tr.r && t2.g == tr.g && t2.b == tr.b);
    }
}
END_TEST

/* a ramp of density 0.2 + 0.3 x over x in [0, 8] (its cell centres),
 * constant in y and z */
static volgrid_t ramp;

static void make_ramp(void)
{
    const float lo[3] = { 0, 0, 0 }, hi[3] = { 8, 1, 1 };
    ck_assert_int_eq(volgrid_alloc(&ramp, 8, 1, 1, 1, lo, hi, 100, NULL),
                     SVET_OK);
    for (int x = 0; x < 8; x++)
        ramp.plane[0][x] = (float)(0.2 + 0.3 * (x + 0.5));
    ramp.max[0] = ramp.plane[0][7];
}

/* the optical depth factor int_1^(1+t) rho dx, the ray from x = 1 */
static double depth(double t)
{
    return 0.2 * t + 0.15 * ((1 + t) * (1 + t) - 1);
}

typedef struct {
    double sum[3], sum2[3];
    long n;
} stat3_t;

static void add(stat3_t *s, RADIANCE v)
{
    double c[3] = { (double)v.r, (double)v.g, (double)v.b };
    for (int k = 0; k < 3; k++) {
        s->sum[k] += c[k];
        s->sum2[k] += c[k] * c[k];
    }
    s->n++;
}

static void expect_mean(const stat3_t *s, const double e[3], const char *what)
{
    for (int k = 0; k < 3; k++) {
        double mean = s->sum[k] / (double)s->n;
        double var = s->sum2[k] / (double)s->n - mean * mean;
        double se = sqrt(fmax(var, 0) / (double)s->n);
        ck_assert_msg(fabs(mean - e[k]) <= 4 * se + 1e-6,
                      "%s channel %d: mean %g, expected %g (se %g)", what, k,
                      mean, e[k], se);
    }
}

START_TEST(ratio_tracking_is_unbiased_through_a_ramp)
{
    make_ramp();
    medium_t m = medium_homogeneous(rad_make(REAL_C(0.05), REAL_C(0.3), 0),
                                    rad_make(REAL_C(0.05), 0, REAL_C(0.5)));
    m.grid = &ramp;
    ck_assert_int_eq(medium_check(&m, NULL), SVET_OK);
    VECTOR3 o = { 1, REAL_C(0.5), REAL_C(0.5) }, dir = { 1, 0, 0 };
    pcg32_t g;
    pcg32_seed(&g, 80, 1);
    stat3_t s = { { 0 }, { 0 }, 0 };
    for (int i = 0; i < 200000; i++)
        add(&s, medium_tr(&m, o, dir, 5, &g));
    const double st[3] = { 0.1, 0.3, 0.5 };
    double e[3];
    for (int k = 0; k < 3; k++)
        e[k] = exp(-st[k] * depth(5));
    expect_mean(&s, e, "ratio tracking");
    volgrid_free(&ramp);
}
END_TEST

/* E[w 1{scatter before t0}] and E[w 1{pass}] of medium_sample, against
 * sigma_s int_0^t0 rho(t) T(t) dt and T(tmax) */
static void check_sampling(const medium_t *m, const VECTOR3 o,
                           double (*dep)(double), double (*rho)(double),
                           double tmax, uint64_t seed)
{
    RADIANCE ss = medium_sigma_s(m), st = medium_sigma_t(m);
    const double sig_s[3] = { (double)ss.r, (double)ss.g, (double)ss.b };
    const double sig_t[3] = { (double)st.r, (double)st.g, (double)st.b };
    const double t0s[3] = { 0.5, 2, tmax };
    stat3_t before[3], pass = { { 0 }, { 0 }, 0 };
    memset(before, 0, sizeof before);
    VECTOR3 dir = { 1, 0, 0 };
    pcg32_t g;
    pcg32_seed(&g, 80, seed);
    for (int i = 0; i < 300000; i++) {
        real t;
        RADIANCE w;
        bool hit = medium_sample(m, o, dir, (real)tmax, &g, &t, &w);
        add(&pass, hit ? rad_grey(0) : w);
        for (int j = 0; j < 3; j++)
            add(&before[j], hit && (double)t < t0s[j] ? w : rad_grey(0));
    }
    double e[3];
    for (int k = 0; k < 3; k++)
        e[k] = exp(-sig_t[k] * dep(tmax));
    expect_mean(&pass, e, "passing");
    for (int j = 0; j < 3; j++) {
        /* the integral by the midpoint rule, 20000 steps */
        for (int k = 0; k < 3; k++) {
            double sum = 0, h = t0s[j] / 20000;
            for (int q = 0; q < 20000; q++) {
                double t = (q + 0.5) * h;
                sum += sig_s[k] * rho(t) * exp(-sig_t[k] * dep(t)) * h;
            }
            e[k] = sum;
        }
        expect_mean(&before[j], e, "scattering");
    }
}

static double unit_depth(double t) { return t; }
static double unit_rho(double t) { (void)t; return 1; }
static double ramp_rho(double t) { return 0.2 + 0.3 * (1 + t); }

START_TEST(distance_sampling_homogeneous_and_by_delta_tracking)
{
    /* extinction differing per channel, one channel without scattering */
    medium_t m = medium_homogeneous(rad_make(REAL_C(0.1), REAL_C(0.2), 0),
                                    rad_make(REAL_C(0.4), 0, REAL_C(0.9)));
    VECTOR3 o = { 1, REAL_C(0.5), REAL_C(0.5) };
    check_sampling(&m, o, unit_depth, unit_rho, 3, 2);
    make_ramp();
    medium_t r = medium_homogeneous(rad_make(REAL_C(0.05), REAL_C(0.1), 0),
                                    rad_make(REAL_C(0.1), REAL_C(0.05), REAL_C(0.3)));
    r.grid = &ramp;
    check_sampling(&r, o, depth, ramp_rho, 5, 3);
    volgrid_free(&ramp);
}
END_TEST

START_TEST(bad_coefficients_are_refused)
{
    svet_error e;
    medium_t m = medium_homogeneous(rad_make(-1, 0, 0), rad_grey(1));
    ck_assert_int_eq(medium_check(&m, &e), SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(e.msg, "sigma_a"));
    m = medium_homogeneous(rad_grey(0), rad_make(0, (real)NAN, 0));
    ck_assert_int_eq(medium_check(&m, &e), SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(e.msg, "sigma_s"));
    m = medium_homogeneous(rad_grey(0), rad_grey(1));
    m.phase.kind = PHASE_HG;
    m.phase.g = 1;
    ck_assert_int_eq(medium_check(&m, &e), SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(e.msg, "g = 1"));
    m.phase.g = REAL_C(-0.5);
    ck_assert_int_eq(medium_check(&m, &e), SVET_OK);
    make_ramp();
    ramp.plane[0][3] = -0.5f;
    m.grid = &ramp;
    ck_assert_int_eq(medium_check(&m, &e), SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(e.msg, "-0.5"));
    volgrid_free(&ramp);
}
END_TEST

/* Two homogeneous components of the same phase against the one medium of
 * their summed coefficients. The values are dyadic, so every sum is exact
 * and the two must agree to the bit: transmittance, and every distance
 * and weight sampled from the same stream. */
START_TEST(homogeneous_components_are_their_sum_exactly)
{
    medium_t c[2] = {
        medium_homogeneous(rad_make(REAL_C(0.25), REAL_C(0.5), REAL_C(0.125)),
                           rad_make(REAL_C(0.5), REAL_C(0.25), 1)),
        medium_homogeneous(rad_make(REAL_C(0.125), REAL_C(0.25), REAL_C(0.5)),
                           rad_make(1, REAL_C(0.5), REAL_C(0.25))),
    };
    medium_t mix = medium_mix(c, 2);
    medium_t one = medium_homogeneous(
        rad_make(REAL_C(0.375), REAL_C(0.75), REAL_C(0.625)),
        rad_make(REAL_C(1.5), REAL_C(0.75), REAL_C(1.25)));
    ck_assert_int_eq(medium_check(&mix, NULL), SVET_OK);
    ck_assert(medium_is_homogeneous(&mix));
    VECTOR3 o = { 0, 0, 0 }, dir = { 0, 0, 1 };
    pcg32_t g1, g2;
    pcg32_seed(&g1, 81, 1);
    pcg32_seed(&g2, 81, 1);
    for (int i = 0; i <= 40; i++) {
        real d = (real)i * REAL_C(0.23);
        RADIANCE a = medium_tr(&mix, o, dir, d, &g1),
                 b = medium_tr(&one, o, dir, d, &g2);
        ck_assert(a.r == b.r && a.g == b.g && a.b == b.b);
    }
    for (int i = 0; i < 10000; i++) {
        real t1, t2;
        RADIANCE w1, w2;
        bool h1 = medium_sample(&mix, o, dir, 2, &g1, &t1, &w1);
        bool h2 = medium_sample(&one, o, dir, 2, &g2, &t2, &w2);
        ck_assert(h1 == h2 && t1 == t2);
        ck_assert(w1.r == w2.r && w1.g == w2.g && w1.b == w2.b);
    }
    test_report_cases("homogeneous_components_are_their_sum_exactly", 10041);
}
END_TEST

/* Two components on the ramp grid, of different coefficients: delta
 * tracking (under the sum of their majorants) and ratio tracking must
 * give the closed forms of their summed coefficients (check_sampling
 * reads the sums through medium_sigma_t and medium_sigma_s). */
START_TEST(gridded_components_scatter_and_transmit_as_their_sum)
{
    make_ramp();
    medium_t c[2] = {
        medium_homogeneous(rad_make(REAL_C(0.05), REAL_C(0.02), 0),
                           rad_make(REAL_C(0.05), REAL_C(0.03), REAL_C(0.2))),
        medium_homogeneous(rad_make(0, REAL_C(0.03), 0),
                           rad_make(REAL_C(0.05), REAL_C(0.02), REAL_C(0.1))),
    };
    c[0].grid = c[1].grid = &ramp;
    medium_t mix = medium_mix(c, 2);
    ck_assert_int_eq(medium_check(&mix, NULL), SVET_OK);
    ck_assert(!medium_is_homogeneous(&mix));
    VECTOR3 o = { 1, REAL_C(0.5), REAL_C(0.5) }, dir = { 1, 0, 0 };
    check_sampling(&mix, o, depth, ramp_rho, 5, 4);
    pcg32_t g;
    pcg32_seed(&g, 82, 1);
    stat3_t s = { { 0 }, { 0 }, 0 };
    for (int i = 0; i < 200000; i++)
        add(&s, medium_tr(&mix, o, dir, 5, &g));
    const double st[3] = { 0.15, 0.1, 0.3 };
    double e[3];
    for (int k = 0; k < 3; k++)
        e[k] = exp(-st[k] * depth(5));
    expect_mean(&s, e, "ratio tracking of the sum");
    volgrid_free(&ramp);
}
END_TEST

/* The scattering component at a point is picked in proportion to the
 * mean of its sigma_s there: a chi-square test of the picks of three
 * components (one gridded, so the proportions depend on the point), and
 * the weight makes each pick's expectation sigma_s_i / sigma_s exactly. */
START_TEST(the_scatterer_is_picked_in_proportion_to_sigma_s)
{
    make_ramp();
    medium_t c[3] = {
        medium_homogeneous(rad_grey(REAL_C(0.1)),
                           rad_make(REAL_C(0.2), REAL_C(0.4), REAL_C(0.6))),
        medium_homogeneous(rad_grey(0), rad_grey(REAL_C(0.5))),
        medium_homogeneous(rad_grey(REAL_C(0.3)), rad_make(REAL_C(0.1), 0, 0)),
    };
    c[1].grid = &ramp;
    c[1].phase.kind = PHASE_HG;
    c[1].phase.g = REAL_C(0.5);
    medium_t mix = medium_mix(c, 3);
    ck_assert_int_eq(medium_check(&mix, NULL), SVET_OK);
    VECTOR3 p = { REAL_C(3.7), REAL_C(0.5), REAL_C(0.5) };
    double rho = 0.2 + 0.3 * 3.7; /* the ramp, linear between its centres */
    double mean[3] = { 0.4, 0.5 * rho, 0.1 / 3 }, sum = 0;
    for (int i = 0; i < 3; i++)
        sum += mean[i];
    enum { N = 60000 };
    double obs[3] = { 0, 0, 0 }, expct[3];
    pcg32_t g;
    pcg32_seed(&g, 83, 1);
    for (int n = 0; n < N; n++) {
        RADIANCE w;
        const medium_t *k = medium_scatterer(&mix, p, pcg32_real(&g), &w);
        int i = (int)(k - c);
        ck_assert(i >= 0 && i < 3);
        obs[i]++;
        /* w P_i = sigma_s_i / sigma_s, channel by channel */
        RADIANCE ss = k->sigma_s;
        double r = i == 1 ? rho : 1, pi = mean[i] / sum;
        double tot[3] = { 0.2 + 0.5 * rho + 0.1, 0.4 + 0.5 * rho,
                          0.6 + 0.5 * rho };
        double want[3] = { (double)ss.r * r / tot[0], (double)ss.g * r / tot[1],
                           (double)ss.b * r / tot[2] };
        double got[3] = { (double)w.r * pi, (double)w.g * pi, (double)w.b * pi };
        for (int ch = 0; ch < 3; ch++)
            ck_assert_msg(fabs(got[ch] - want[ch]) < 1e-4,
                          "component %d channel %d: w P = %g, expected %g", i,
                          ch, got[ch], want[ch]);
    }
    for (int i = 0; i < 3; i++)
        expct[i] = N * mean[i] / sum;
    chi2_config cfg;
    memset(&cfg, 0, sizeof cfg);
    chi2_config_defaults(&cfg);
    chi2_result res = chi2_from_counts(obs, expct, 3, &cfg);
    ck_assert_msg(res.passed, "%s (counts %g %g %g, expected %g %g %g)",
                  res.message, obs[0], obs[1], obs[2], expct[0], expct[1],
                  expct[2]);
    /* one component: itself, weight 1 */
    RADIANCE w;
    ck_assert_ptr_eq(medium_scatterer(&c[0], p, REAL_C(0.7), &w), &c[0]);
    ck_assert(w.r == 1 && w.g == 1 && w.b == 1);
    volgrid_free(&ramp);
}
END_TEST

START_TEST(bad_sums_are_refused)
{
    svet_error e;
    medium_t c[MEDIUM_MAX_COMPONENTS + 1];
    for (int i = 0; i <= MEDIUM_MAX_COMPONENTS; i++)
        c[i] = medium_homogeneous(rad_grey(0), rad_grey(1));
    medium_t m = medium_mix(c, MEDIUM_MAX_COMPONENTS + 1);
    ck_assert_int_eq(medium_check(&m, &e), SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(e.msg, "components"));
    m = medium_mix(c, MEDIUM_MAX_COMPONENTS);
    ck_assert_int_eq(medium_check(&m, &e), SVET_OK);
    c[1].sigma_s = rad_make(0, -1, 0);
    ck_assert_int_eq(medium_check(&m, &e), SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(e.msg, "sigma_s"));
    c[1] = medium_mix(c + 2, 2); /* nested */
    ck_assert_int_eq(medium_check(&m, &e), SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(e.msg, "of its own"));
}
END_TEST

/* Emission (pbrt-v4 sec. 11.1.2, source sigma_a L_e): where sigma_a and
 * sigma_t share one density, dTr/dt = -sigma_t rho Tr gives
 *   int_0^d Tr sigma_a rho L_e dt = L_e (sigma_a / sigma_t) (1 - Tr(d))
 * per channel. Homogeneous: exact, drawing nothing; through the ramp by
 * ratio tracking with emission, its mean within 4 standard errors. A
 * source of L_e alone, or a dropped density, misses both. */
START_TEST(emission_along_a_segment_has_its_closed_form)
{
    const RADIANCE sa = rad_make(REAL_C(0.05), REAL_C(0.3), REAL_C(0.2));
    const RADIANCE ss = rad_make(REAL_C(0.05), 0, REAL_C(0.3));
    const double Le[3] = { 1, 2, 0.5 }, a[3] = { 0.05, 0.3, 0.2 };
    const double t[3] = { 0.1, 0.3, 0.5 };
    medium_t m = medium_homogeneous(sa, ss);
    m.emission = rad_make(1, 2, REAL_C(0.5));
    ck_assert(medium_emits(&m));
    VECTOR3 o = { 1, REAL_C(0.5), REAL_C(0.5) }, dir = { 1, 0, 0 };
    pcg32_t g, g0;
    pcg32_seed(&g, 81, 1);
    g0 = g;
    RADIANCE L = medium_emitted(&m, o, dir, 5, &g);
    ck_assert(memcmp(&g, &g0, sizeof g) == 0);
    const double got[3] = { (double)L.r, (double)L.g, (double)L.b };
    for (int k = 0; k < 3; k++) {
        double want = Le[k] * a[k] / t[k] * (1 - exp(-t[k] * 5));
        ck_assert_msg(fabs(got[k] / want - 1) < 1e-5,
                      "homogeneous channel %d: %g, closed form %g", k,
                      got[k], want);
    }
    make_ramp();
    m.grid = &ramp;
    stat3_t s = { { 0 }, { 0 }, 0 };
    for (int i = 0; i < 200000; i++)
        add(&s, medium_emitted(&m, o, dir, 5, &g));
    double e[3];
    for (int k = 0; k < 3; k++)
        e[k] = Le[k] * a[k] / t[k] * (1 - exp(-t[k] * depth(5)));
    expect_mean(&s, e, "emission through the ramp");
    /* no absorption, no emission */
    m.sigma_a = rad_grey(0);
    ck_assert(!medium_emits(&m));
    volgrid_free(&ramp);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("medium (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, beer_lambert_per_channel);
    tcase_add_test(tc, ratio_tracking_is_unbiased_through_a_ramp);
    tcase_add_test(tc, distance_sampling_homogeneous_and_by_delta_tracking);
    tcase_add_test(tc, bad_coefficients_are_refused);
    tcase_add_test(tc, homogeneous_components_are_their_sum_exactly);
    tcase_add_test(tc, gridded_components_scatter_and_transmit_as_their_sum);
    tcase_add_test(tc, the_scatterer_is_picked_in_proportion_to_sigma_s);
    tcase_add_test(tc, bad_sums_are_refused);
    tcase_add_test(tc, emission_along_a_segment_has_its_closed_form);
    suite_add_tcase(s, tc);
    return s;
}
