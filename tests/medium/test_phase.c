/*
 * test_phase.c - the phase functions of ch. 11 and 12: each integrates to
 * 1 over the sphere, its sampler passes the chi-square test against its
 * pdf (HG at g = -0.9, -0.6, 0, 0.6, 0.9; Rayleigh; isotropic) about a
 * tilted incident direction, the returned pdf equals the phase function,
 * HG's mean cosine is g, and a wrong sampler fails.
 */
#include "testutil.h"
#include "chi2.h"
#include "core/frame.h"
#include "medium/phase.h"

#include <math.h>

#define M_PI_LOCAL 3.14159265358979323846

typedef struct {
    phase_t p;
    VECTOR3 wi;
    bool wrong; /* sample HG with g / 2: the test must see it */
} ctx_t;

static bool sample_fn(void *c, const real u[2], VECTOR3 w)
{
    ctx_t *x = c;
    phase_t p = x->p;
    if (x->wrong)
        p.g /= 2;
    real pdf = phase_sample(&p, x->wi, u, w);
    return pdf > 0;
}

static double pdf_fn(void *c, const VECTOR3 w)
{
    ctx_t *x = c;
    return (double)phase_eval(&x->p, SVECTOR3(x->wi, w));
}

#define NCASES 7
static const phase_t cases[NCASES] = {
    { PHASE_HG, REAL_C(-0.9) }, { PHASE_HG, REAL_C(-0.6) }, { PHASE_HG, 0 },
    { PHASE_HG, REAL_C(0.6) },  { PHASE_HG, REAL_C(0.9) },
    { PHASE_RAYLEIGH, 0 },      { PHASE_ISOTROPIC, 0 }
};

START_TEST(samplers_pass_the_chi_square_test)
{
    for (int i = 0; i < NCASES; i++) {
        ctx_t c = { cases[i], { 0, 0, 1 }, false };
        /* along +z, where the bins resolve the lobe, and tilted */
        for (int tilt = 0; tilt < 2; tilt++) {
            if (tilt) {
                vec_set(c.wi, REAL_C(0.36), REAL_C(0.48), REAL_C(0.8));
            }
            chi2_config cfg = { 0 };
            cfg.theta_bins = 20;
            cfg.samples = 400000;
            cfg.seed = 70 + (uint64_t)(i * 2 + tilt);
            cfg.tests = 2 * NCASES + 1;
            chi2_config_defaults(&cfg);
            chi2_result r = chi2_test(&cfg, sample_fn, pdf_fn, &c);
            ck_assert_msg(r.passed, "case %d tilt %d: %s", i, tilt, r.message);
            chi2_assert_pdf_normalised(pdf_fn, &c, 0, 1e-4);
        }
    }
    /* HG at 0.6 sampled as if g were 0.3 fails */
    ctx_t c = { cases[3], { 0, 0, 1 }, true };
    chi2_config cfg = { 0 };
    cfg.samples = 100000;
    cfg.seed = 99;
    cfg.tests = 2 * NCASES + 1;
    chi2_config_defaults(&cfg);
    ck_assert(!chi2_test(&cfg, sample_fn, pdf_fn, &c).passed);
}
END_TEST

START_TEST(the_pdf_returned_is_the_phase_function)
{
    pcg32_t g;
    pcg32_seed(&g, 71, 1);
    for (int i = 0; i < NCASES; i++)
        for (int k = 0; k < 2000; k++) {
            VECTOR3 wi = { 1 - 2 * pcg32_real(&g), 1 - 2 * pcg32_real(&g),
                           1 - 2 * pcg32_real(&g) }, wo;
            vec_normalize(wi, wi);
            real u[2] = { pcg32_real(&g), pcg32_real(&g) };
            real pdf = phase_sample(&cases[i], wi, u, wo);
            ck_assert_near(SVECTOR3(wo, wo), 1, 16 * REAL_EPSILON);
            ck_assert_near(pdf, phase_eval(&cases[i], SVECTOR3(wi, wo)),
                           1e-3 * (double)pdf + 1e-6);
            /* the cosine alone is the same draw */
            ck_assert_near(SVECTOR3(wi, wo), phase_sample_cos(&cases[i], u[0]),
                           32 * REAL_EPSILON);
        }
}
END_TEST

START_TEST(hg_mean_cosine_is_g_and_the_ends_of_the_inverse)
{
    for (int i = 0; i < NCASES; i++) {
        const phase_t *p = &cases[i];
        /* the mean cosine by the midpoint rule over u: E[cos] = int c(u) du */
        double mean = 0;
        const int n = 200000;
        for (int k = 0; k < n; k++)
            mean += (double)phase_sample_cos(p, (real)((k + 0.5) / n));
        mean /= n;
        double g = p->kind == PHASE_HG ? (double)p->g : 0;
        ck_assert_msg(fabs(mean - g) < 2e-4, "case %d: mean cos %g, not %g",
                      i, mean, g);
        /* u = 0 and u -> 1 reach the ends of [-1, 1] */
        double a = (double)phase_sample_cos(p, 0);
        double b = (double)phase_sample_cos(p, 1 - REAL_EPSILON / 2);
        ck_assert(fabs(fabs(a) - 1) < 1e-3 && fabs(fabs(b) - 1) < 1e-3 &&
                  a * b < 0);
    }
    /* Rayleigh: forward and backward alike, p(0) = 3 / (16 pi) */
    phase_t r = { PHASE_RAYLEIGH, 0 };
    ck_assert_near(phase_eval(&r, 0), 3 / (16 * M_PI_LOCAL), 1e-6);
    ck_assert(phase_eval(&r, REAL_C(0.3)) == phase_eval(&r, REAL_C(-0.3)));
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("phase (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, samplers_pass_the_chi_square_test);
    tcase_add_test(tc, the_pdf_returned_is_the_phase_function);
    tcase_add_test(tc, hg_mean_cosine_is_g_and_the_ends_of_the_inverse);
    suite_add_tcase(s, tc);
    return s;
}
