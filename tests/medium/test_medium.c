/*
 * test_medium.c - the media of ch. 11: Beer-Lambert per channel; ratio
 * tracking unbiased through a grid whose optical depth has a closed form
 * (a linear ramp); distance sampling, exact (homogeneous) and by delta
 * tracking (the ramp), giving each channel's probabilities of passing and
 * of scattering before any distance in expectation; bad coefficients.
 * Statistical checks: fixed seeds, four standard errors of the sample.
 */
#include "testutil.h"
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
    RADIANCE ss = m->sigma_s, st = medium_sigma_t(m);
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

Suite *test_suite(void)
{
    Suite *s = suite_create("medium (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, beer_lambert_per_channel);
    tcase_add_test(tc, ratio_tracking_is_unbiased_through_a_ramp);
    tcase_add_test(tc, distance_sampling_homogeneous_and_by_delta_tracking);
    tcase_add_test(tc, bad_coefficients_are_refused);
    suite_add_tcase(s, tc);
    return s;
}
