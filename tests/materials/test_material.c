/*
 * test_material.c - the book's mixed surface (material.h): validation of
 * the parameters; chi-square fits of material_sample to material_pdf for
 * mixed materials (delta components included), grazing and inside
 * directions; a wrong pdf that must fail; reciprocity; albedo <= 1 by
 * Monte Carlo, = 1 for the lossless mixes; component choice frequencies;
 * no NaN or Inf; tests/vectors/materials.csv read back; the shortcut for
 * a single Lambert lobe gives the general answers bit for bit.
 */
#include "testutil.h"
#include "chi2.h"
#include "materials/material.h"
#include "core/rng.h"
#include "core/sample.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define LEN(a) ((int)(sizeof(a) / sizeof *(a)))
#define EPS ((double)REAL_EPSILON)

static void dir(VECTOR3 w, real c, real phi)
{
    real s = sqrt(fmax(REAL_C(0.0), (1 - c) * (1 + c)));
    vec_set(w, s * cos(phi), s * sin(phi), c);
}

static void random_dir(VECTOR3 w, pcg32_t *g)
{
    real u[2] = { pcg32_real(g), pcg32_real(g) };
    sample_uniform_sphere(w, u);
}

static bool finite_nonneg(RADIANCE c)
{
    return rad_is_finite(c) && c.r >= 0 && c.g >= 0 && c.b >= 0;
}

/* --- a gallery of materials ----------------------------------------------- */

typedef struct {
    const char *name;
    material_params p;
} named_params;

static RADIANCE rgb(double r, double g, double b)
{
    return rad_make((real)r, (real)g, (real)b);
}

/* Mixed surfaces of every kind; those marked lossless have a sum of
 * reflectances of 1 in every channel. */
static int gallery(named_params *out)
{
    int n = 0;
    material_params p;
#define ADD(nm) do { out[n].name = nm; out[n].p = p; n++; } while (0)
    material_params_default(&p);
    p.rho_d = rgb(0.8, 0.5, 0.2);
    ADD("lambert");
    material_params_default(&p);
    p.rho_d = rgb(0.5, 0.3, 0.2);
    p.rho_g = rgb(0.4, 0.4, 0.4);
    p.e = 20;
    ADD("plastic phong e=20");
    material_params_default(&p);
    p.rho_d = rgb(0.1, 0.1, 0.1);
    p.rho_g = rgb(0.9, 0.9, 0.9);
    p.e = 1;
    ADD("phong e=1");
    material_params_default(&p);
    p.rho_d = rgb(0.3, 0.2, 0.1);
    p.rho_g = rgb(0.6, 0.6, 0.6);
    p.gloss = MATERIAL_GLOSS_WARD_BOUNDED;
    p.alpha_x = p.alpha_y = REAL_C(0.15);
    ADD("plastic ward bounded");
    material_params_default(&p);
    p.rho_d = rgb(0.2, 0.2, 0.2);
    p.rho_g = rgb(0.7, 0.5, 0.3);
    p.gloss = MATERIAL_GLOSS_WARD;
    p.alpha_x = REAL_C(0.3);
    p.alpha_y = REAL_C(0.06);
    ADD("brushed ward (book)");
    material_params_default(&p);
    p.rho_d = rgb(0.5, 0.5, 0.5);
    p.rho_s = rgb(0.5, 0.5, 0.5);
    ADD("coated diffuse, lossless");
    material_params_default(&p);
    p.rho_s = rgb(0.04, 0.04, 0.04);
    p.rho_t = rgb(0.96, 0.96, 0.96);
    p.eta = REAL_C(1.5);
    ADD("glass, lossless");
    material_params_default(&p);
    p.rho_s = rgb(0.05, 0.05, 0.05);
    p.rho_t = rgb(0.6, 0.5, 0.4);
    p.rho_d = rgb(0.1, 0.1, 0.1);
    p.rho_dt = rgb(0.1, 0.2, 0.3);
    p.eta = REAL_C(1.33);
    ADD("every component");
    material_params_default(&p);
    p.rho_g = rgb(0.3, 0.3, 0.3);
    p.e = 50;
    p.rho_t = rgb(0.6, 0.6, 0.6);
    p.rho_dt = rgb(0.05, 0.05, 0.05);
    p.eta = REAL_C(1.5);
    ADD("frosted glass");
    material_params_default(&p);
    p.rho_d = rgb(0.3, 0.3, 0.3);
    p.rho_dt = rgb(0.6, 0.6, 0.6);
    ADD("paper");
    material_params_default(&p);
    p.rho_s = rgb(0.9, 0.6, 0.3);
    ADD("copper mirror");
#undef ADD
    return n;
}

#define GALLERY_MAX 24

static material_t build(const material_params *p)
{
    material_t m;
    svet_error err;
    svet_status st = material_init(&m, p, &err);
    ck_assert_msg(st == SVET_OK, "%s", err.msg);
    return m;
}

/* --- validation ------------------------------------------------------------- */

START_TEST(material_rejects_what_is_not_physical)
{
    const real nan = (real)NAN;
    material_params base;
    material_params_default(&base);
    struct { material_params p; const char *word; } bad[16];
    int n = 0;
#define BAD(field, value, w) do { bad[n].p = base; bad[n].p.field = value; \
                                  bad[n].word = w; n++; } while (0)
    BAD(rho_d, rad_make(nan, 0, 0), "rho_d");
    BAD(rho_s, rad_make(0, -REAL_C(0.1), 0), "rho_s");
    BAD(rho_t, rad_make(0, 0, REAL_C(1.5)), "rho_t");
    BAD(rho_dt, rad_make(0, (real)INFINITY, 0), "rho_dt");
    BAD(rho_g, rad_make(REAL_C(-1e-9), 0, 0), "rho_s");
    BAD(eta, 0, "eta");
    BAD(eta, -1, "eta");
    BAD(eta, nan, "eta");
    /* the sum of components above 1 */
    bad[n].p = base;
    bad[n].p.rho_d = rad_grey(REAL_C(0.6));
    bad[n].p.rho_s = rad_make(REAL_C(0.3), REAL_C(0.5), REAL_C(0.3));
    bad[n++].word = "channel g";
    /* a glossy part with a bad exponent or slope */
    bad[n].p = base;
    bad[n].p.rho_g = rad_grey(REAL_C(0.5));
    bad[n].p.e = -1;
    bad[n++].word = "exponent";
    bad[n].p = bad[n - 1].p;
    bad[n].p.e = nan;
    bad[n++].word = "exponent";
    bad[n].p = base;
    bad[n].p.rho_g = rad_grey(REAL_C(0.5));
    bad[n].p.gloss = MATERIAL_GLOSS_WARD;
    bad[n].p.alpha_x = 0;
    bad[n++].word = "alpha_x";
    bad[n].p = bad[n - 1].p;
    bad[n].p.alpha_x = REAL_C(0.1);
    bad[n].p.alpha_y = -REAL_C(0.1);
    bad[n++].word = "alpha_y";
#undef BAD
    for (int i = 0; i < n; i++) {
        material_t m;
        svet_error err;
        svet_error_clear(&err);
        ck_assert_int_eq(material_init(&m, &bad[i].p, &err), SVET_ERR_RANGE);
        ck_assert_int_eq(err.status, SVET_ERR_RANGE);
        ck_assert_msg(strstr(err.msg, bad[i].word) != NULL,
                      "case %d: '%s' does not name '%s'", i, err.msg,
                      bad[i].word);
        /* a rejected material is black, so a careless caller is safe */
        VECTOR3 w = { 0, 0, 1 };
        real u[3] = { REAL_C(0.5), REAL_C(0.5), REAL_C(0.5) };
        brdf_sample_t s;
        ck_assert(m.ncomp == 0 && !material_sample(&m, w, u, &s));
        material_t *mp = (material_t *)&m;
        ck_assert_int_eq(material_new(&bad[i].p, &mp, NULL), SVET_ERR_RANGE);
        ck_assert_ptr_null(mp);
    }
    material_free(NULL);
    test_report_cases("material_rejects_what_is_not_physical", n);
}
END_TEST

START_TEST(material_accepts_a_sum_of_exactly_one)
{
    /* 0.3 + 0.7 and 0.1 + 0.2 + 0.7 may round above 1 by an ulp */
    material_params p;
    material_params_default(&p);
    p.rho_d = rgb(0.3, 0.1, 0.7);
    p.rho_s = rgb(0.7, 0.2, 0.1);
    p.rho_g = rgb(0.0, 0.7, 0.2);
    material_t *m;
    svet_error err;
    ck_assert_int_eq(material_new(&p, &m, &err), SVET_OK);
    ck_assert_int_eq(m->ncomp, 3); /* Lambert, mirror, Phong */
    ck_assert_int_eq(m->comp[0].kind, BRDF_LAMBERT);
    ck_assert_int_eq(m->comp[1].kind, BRDF_MIRROR);
    ck_assert_int_eq(m->comp[2].kind, BRDF_PHONG);
    /* the mirror rises to what Lambert and Phong leave */
    ck_assert_near(m->comp[1].rho90.r, 1 - 0.3 - 0.0, 4 * EPS);
    ck_assert_near(m->comp[1].rho90.g, 1 - 0.1 - 0.7, 4 * EPS);
    material_free(m);
    /* a black glossy part needs no valid exponent */
    material_params_default(&p);
    p.rho_d = rad_grey(REAL_C(0.5));
    p.e = -5;
    material_t m2;
    ck_assert_int_eq(material_init(&m2, &p, &err), SVET_OK);
    ck_assert_int_eq(m2.ncomp, 1);
    ck_assert(!material_is_specular(&m2));
    /* glass and mirror are specular; black is nothing */
    ck_assert_int_eq(material_glass(&m2, rad_grey(REAL_C(0.04)),
                                    rad_grey(REAL_C(0.9)), REAL_C(1.5), &err),
                     SVET_OK);
    ck_assert(material_is_specular(&m2));
    ck_assert_int_eq(material_lambert(&m2, rad_grey(0), &err), SVET_OK);
    ck_assert(m2.ncomp == 0 && !material_is_specular(&m2));
    test_report_cases("material_accepts_a_sum_of_exactly_one", 4);
}
END_TEST

/* --- chi-square fits ---------------------------------------------------------- */

/* The harness gives two numbers; the third (the component choice) comes
 * from a generator of the context, seeded per test. Delta samples have no
 * density: they are reported as absorbed, and material_pdf, which covers
 * the non-delta part only, integrates to 1 - P(delta). */
typedef struct {
    const material_t *m, *pdf_of;
    VECTOR3 wo;
    pcg32_t g;
} mfit_ctx;

static bool mfit_sample(void *p, const real u[2], VECTOR3 w)
{
    mfit_ctx *c = p;
    real u3[3] = { pcg32_real(&c->g), u[0], u[1] };
    brdf_sample_t s;
    if (!material_sample(c->m, c->wo, u3, &s) || s.delta)
        return false;
    vec_copy(w, s.wi);
    return true;
}

static double mfit_pdf(void *p, const VECTOR3 w)
{
    mfit_ctx *c = p;
    return (double)material_pdf(c->pdf_of, w, c->wo);
}

static const real fit_cos[] = { 1, REAL_C(0.5), REAL_C(1e-3), REAL_C(-0.5) };
/* the gallery's materials fitted: every one with a non-delta part */
static const int fit_which[] = { 1, 2, 3, 4, 7, 8, 9 };
#define CHI2_TESTS (LEN(fit_which) * LEN(fit_cos) + 1)

static chi2_result mfit(mfit_ctx *c, uint64_t seed)
{
    chi2_config cfg = { 0 };
    cfg.tests = CHI2_TESTS;
    cfg.seed = seed;
    cfg.samples = 100000;
    pcg32_seed(&c->g, seed, 3);
    return chi2_test(&cfg, mfit_sample, mfit_pdf, c);
}

START_TEST(mixed_materials_sample_wi_with_their_pdf)
{
    named_params gal[GALLERY_MAX];
    gallery(gal);
    int n = 0;
    for (int i = 0; i < LEN(fit_which); i++)
        for (int j = 0; j < LEN(fit_cos); j++, n++) {
            material_t m = build(&gal[fit_which[i]].p);
            mfit_ctx c = { .m = &m, .pdf_of = &m };
            dir(c.wo, fit_cos[j], REAL_C(0.9));
            chi2_result r = mfit(&c, 500 + (uint64_t)n);
            if (getenv("SVET_VERBOSE"))
                printf("    %s, cos %g: %s\n", gal[fit_which[i]].name,
                       (double)fit_cos[j], r.message);
            ck_assert_msg(r.passed, "%s, cos theta_o = %g: %s",
                          gal[fit_which[i]].name, (double)fit_cos[j],
                          r.message);
        }
    test_report_cases("mixed_materials_sample_wi_with_their_pdf", n);
}
END_TEST

START_TEST(a_wrong_mixture_pdf_fails_the_chi2_test)
{
    /* plastic sampled, tested against the pdf of the same lobes mixed in
     * other proportions (0.45 : 0.45 in place of 0.5 : 0.4 by rho) */
    named_params gal[GALLERY_MAX];
    gallery(gal);
    material_t m = build(&gal[1].p);
    material_params q = gal[1].p;
    q.rho_d = rad_grey(REAL_C(0.45));
    q.rho_g = rad_grey(REAL_C(0.45));
    material_t w = build(&q);
    mfit_ctx c = { .m = &m, .pdf_of = &w };
    dir(c.wo, REAL_C(0.7), 0);
    chi2_result r = mfit(&c, 999);
    if (getenv("SVET_VERBOSE"))
        printf("    wrong mixture: %s\n", r.message);
    ck_assert_msg(!r.passed, "a wrong pdf passed: %s", r.message);
    test_report_cases("a_wrong_mixture_pdf_fails_the_chi2_test", 1);
}
END_TEST

/* --- consistency of sample, pdf and eval -------------------------------------- */

START_TEST(sample_weight_and_pdf_agree_with_evaluation)
{
    named_params gal[GALLERY_MAX];
    int ng = gallery(gal);
    pcg32_t g;
    pcg32_seed(&g, 21, 22);
    long n = 0, deltas = 0;
    for (int i = 0; i < ng; i++) {
        material_t m = build(&gal[i].p);
        for (int k = 0; k < 20000; k++) {
            VECTOR3 wo;
            random_dir(wo, &g);
            real u[3] = { pcg32_real(&g), pcg32_real(&g), pcg32_real(&g) };
            brdf_sample_t s;
            if (!material_sample(&m, wo, u, &s))
                continue;
            n++;
            ck_assert(s.component >= 0 && s.component < m.ncomp);
            const brdf_t *b = &m.comp[s.component];
            ck_assert(s.delta == brdf_is_delta(b));
            if (s.delta) {
                /* weight = rho_k(theta) / P_k, P_k = s.pdf */
                deltas++;
                RADIANCE rho = brdf_nominal(b, wo);
                ck_assert(s.pdf > 0 && s.pdf <= 1);
                ck_assert_rel(s.weight.g * s.pdf, rho.g, 64 * EPS, 1e-30);
                continue;
            }
            real pdf = material_pdf(&m, s.wi, wo);
            ck_assert_rel(s.pdf, pdf, 16 * EPS, 0);
            RADIANCE f = material_eval(&m, s.wi, wo);
            double expect = (double)f.b * fabs((double)s.wi[Z]) / (double)pdf;
            ck_assert_rel(s.weight.b, expect, 64 * EPS, 1e-30);
        }
    }
    ck_assert(deltas > 1000);
    test_report_cases("sample_weight_and_pdf_agree_with_evaluation", n);
}
END_TEST

START_TEST(material_eval_is_reciprocal)
{
    named_params gal[GALLERY_MAX];
    int ng = gallery(gal);
    pcg32_t g;
    pcg32_seed(&g, 23, 24);
    long n = 0;
    for (int i = 0; i < ng; i++) {
        material_t m = build(&gal[i].p);
        for (int k = 0; k < 20000; k++, n++) {
            VECTOR3 wi, wo;
            random_dir(wo, &g);
            random_dir(wi, &g);
            RADIANCE a = material_eval(&m, wi, wo), b = material_eval(&m, wo, wi);
            ck_assert(a.r == b.r && a.g == b.g && a.b == b.b);
        }
    }
    test_report_cases("material_eval_is_reciprocal", n);
}
END_TEST

START_TEST(components_are_chosen_in_proportion_to_their_luminance)
{
    /* The count of component k in N samples is binomial(N, P_k): within
     * 5 sqrt(N P (1 - P)) of N P_k but for a probability of 6e-7. Only
     * draws that return a direction count, so the materials here never
     * absorb: Lambert, mirror, diffuse transmission. */
    material_params p;
    material_params_default(&p);
    p.rho_d = rgb(0.2, 0.3, 0.1);
    p.rho_s = rgb(0.1, 0.1, 0.3);
    p.rho_dt = rgb(0.4, 0.2, 0.2);
    material_t m = build(&p);
    ck_assert_int_eq(m.ncomp, 3);
    const real cs[] = { 1, REAL_C(0.3), REAL_C(-0.05) };
    const long N = 200000;
    for (int j = 0; j < LEN(cs); j++) {
        VECTOR3 wo;
        dir(wo, cs[j], 1);
        long count[3] = { 0, 0, 0 };
        pcg32_t g;
        pcg32_seed(&g, 25, (uint64_t)j);
        for (long k = 0; k < N; k++) {
            real u[3] = { pcg32_real(&g), pcg32_real(&g), pcg32_real(&g) };
            brdf_sample_t s;
            ck_assert(material_sample(&m, wo, u, &s));
            count[s.component]++;
        }
        double y[3], sum = 0;
        for (int k = 0; k < 3; k++)
            sum += y[k] = (double)rad_luminance(brdf_nominal(&m.comp[k], wo));
        for (int k = 0; k < 3; k++) {
            double P = y[k] / sum;
            ck_assert_near((double)count[k], N * P,
                           5 * sqrt(N * P * (1 - P)));
        }
    }
    /* u[0] = 0 and the largest real below 1 choose the first and last */
    VECTOR3 wo = { 0, 0, 1 };
    real u0[3] = { 0, REAL_C(0.5), REAL_C(0.5) };
    real u1[3] = { 1 - REAL_EPSILON / 2, REAL_C(0.5), REAL_C(0.5) };
    brdf_sample_t s;
    ck_assert(material_sample(&m, wo, u0, &s) && s.component == 0);
    ck_assert(material_sample(&m, wo, u1, &s) && s.component == 2);
    test_report_cases("components_are_chosen_in_proportion_to_their_luminance",
                      3 * N + 2);
}
END_TEST

/* --- albedo -------------------------------------------------------------------- */
/*
 * a(wo) = integral of f |cos| over the sphere plus the delta terms, the
 * mean of the weights of material_sample (0 when it returns false). The
 * tolerance is 5 standard errors of that mean (a false failure has
 * probability 5.7e-7 per comparison, by the central limit theorem) plus a
 * relative 1e-6 for float rounding of the weights (summed in double).
 */
typedef struct {
    double mean[3], se[3];
} mc3_t;

static mc3_t albedo_mc(const material_t *m, const VECTOR3 wo, long n,
                       uint64_t seed)
{
    pcg32_t g;
    pcg32_seed(&g, seed, 41);
    estimator_t e[3];
    for (int c = 0; c < 3; c++)
        estimator_init(&e[c]);
    for (long k = 0; k < n; k++) {
        real u[3] = { pcg32_real(&g), pcg32_real(&g), pcg32_real(&g) };
        brdf_sample_t s;
        material_sample(m, wo, u, &s); /* weight black when false */
        estimator_add(&e[0], (double)s.weight.r);
        estimator_add(&e[1], (double)s.weight.g);
        estimator_add(&e[2], (double)s.weight.b);
    }
    mc3_t r;
    for (int c = 0; c < 3; c++) {
        r.mean[c] = estimator_mean(&e[c]);
        r.se[c] = estimator_stderr(&e[c]);
    }
    return r;
}

static double tol3(const mc3_t *a, int c)
{
    return 5 * a->se[c] + 1e-6 * fabs(a->mean[c]);
}

static const real albedo_cos[] = { 1, REAL_C(0.7), REAL_C(0.3), REAL_C(0.05),
                                   REAL_C(1e-3), REAL_C(1e-7), REAL_C(-0.9),
                                   REAL_C(-0.7), REAL_C(-0.3), REAL_C(-1e-4) };

START_TEST(material_albedo_never_exceeds_one)
{
    named_params gal[GALLERY_MAX];
    int ng = gallery(gal);
    long n = 0;
    for (int i = 0; i < ng; i++) {
        /* the book's Ward is excluded: its albedo exceeds 1 at grazing
         * angles by design (brdf.c; test_brdf.c shows it) */
        if (gal[i].p.gloss == MATERIAL_GLOSS_WARD && !rad_is_black(gal[i].p.rho_g))
            continue;
        material_t m = build(&gal[i].p);
        for (int j = 0; j < LEN(albedo_cos); j++, n++) {
            VECTOR3 wo;
            dir(wo, albedo_cos[j], REAL_C(2.2));
            mc3_t a = albedo_mc(&m, wo, 40000, 600 + (uint64_t)n);
            for (int c = 0; c < 3; c++)
                ck_assert_msg(a.mean[c] <= 1 + tol3(&a, c),
                              "%s, cos %g: albedo %.6f", gal[i].name,
                              (double)albedo_cos[j], a.mean[c]);
        }
    }
    test_report_cases("material_albedo_never_exceeds_one", n);
}
END_TEST

START_TEST(lossless_mixtures_conserve_energy_exactly)
{
    /* A white furnace for one surface: where the reflectances sum to 1 and
     * nothing depends on the lobe shape (diffuse under a Schlick mirror,
     * clear glass), every angle reflects and transmits exactly 1 (the
     * Fresnel coupling of material.h), total internal reflection included;
     * a lone Lambert gives rho_d. The weights of these materials are
     * exact per component, so the tolerance is 5 standard errors of the
     * component choice. */
    named_params gal[GALLERY_MAX];
    gallery(gal);
    const int lossless[] = { 5, 6 };
    long n = 0;
    for (int i = 0; i < LEN(lossless); i++) {
        material_t m = build(&gal[lossless[i]].p);
        for (int j = 0; j < LEN(albedo_cos); j++, n++) {
            VECTOR3 wo;
            dir(wo, albedo_cos[j], REAL_C(0.3));
            mc3_t a = albedo_mc(&m, wo, 40000, 700 + (uint64_t)n);
            for (int c = 0; c < 3; c++)
                ck_assert_msg(fabs(a.mean[c] - 1) <= tol3(&a, c) + 1e-5,
                              "%s, cos %g: albedo %.6f +- %.2g",
                              gal[lossless[i]].name, (double)albedo_cos[j],
                              a.mean[c], a.se[c]);
        }
    }
    material_t m = build(&gal[0].p);
    for (int j = 0; j < LEN(albedo_cos); j++, n++) {
        VECTOR3 wo;
        dir(wo, albedo_cos[j], REAL_C(0.3));
        mc3_t a = albedo_mc(&m, wo, 1000, 800);
        ck_assert_near(a.mean[0], 0.8, 1e-6);
        ck_assert_near(a.mean[2], 0.2, 1e-6);
    }
    test_report_cases("lossless_mixtures_conserve_energy_exactly", n);
}
END_TEST

/* --- no NaN, no Inf --------------------------------------------------------------- */

START_TEST(no_nan_or_inf_over_a_dense_sweep)
{
    named_params gal[GALLERY_MAX];
    int ng = gallery(gal);
    /* plus the extremes of every parameter */
    material_params p;
    const real es[] = { 0, 1e5, BRDF_PHONG_E_MAX };
    for (int k = 0; k < LEN(es); k++) {
        material_params_default(&p);
        p.rho_d = rad_grey(REAL_C(0.2));
        p.rho_g = rad_grey(REAL_C(0.3));
        p.rho_s = rad_grey(REAL_C(0.1));
        p.e = es[k];
        gal[ng].name = "phong extreme";
        gal[ng++].p = p;
    }
    const real as[][2] = { { REAL_C(1e-4), REAL_C(1e-4) },
                           { 1, REAL_C(0.01) },
                           { BRDF_WARD_ALPHA_MIN, BRDF_WARD_ALPHA_MAX } };
    for (int k = 0; k < LEN(as); k++) {
        material_params_default(&p);
        p.rho_g = rad_grey(REAL_C(0.5));
        p.rho_t = rad_grey(REAL_C(0.5));
        p.eta = k == 0 ? REAL_C(1e3) : REAL_C(1e-3);
        p.gloss = k == 1 ? MATERIAL_GLOSS_WARD : MATERIAL_GLOSS_WARD_BOUNDED;
        p.alpha_x = as[k][0];
        p.alpha_y = as[k][1];
        gal[ng].name = "ward extreme";
        gal[ng++].p = p;
    }
    const real one_minus = 1 - REAL_EPSILON / 2;
    const real cs[] = { 1, one_minus, REAL_C(0.5), REAL_C(1e-3), REAL_C(1e-7),
                        REAL_C(1e-12), 0, -REAL_C(1e-7), -REAL_C(0.5), -1 };
    const real us[] = { 0, REAL_C(1e-7), REAL_C(0.5), one_minus };
    pcg32_t g;
    pcg32_seed(&g, 31, 32);
    long n = 0;
    for (int i = 0; i < ng; i++) {
        material_t m = build(&gal[i].p);
        for (int c = 0; c < LEN(cs); c++) {
            VECTOR3 wo, wx;
            dir(wo, cs[c], REAL_C(0.6));
            for (int a = 0; a < LEN(us); a++)
                for (int b = 0; b < LEN(us); b++)
                    for (int d = 0; d < LEN(us); d++, n++) {
                        real u[3] = { us[a], us[b], us[d] };
                        brdf_sample_t s;
                        bool ok = material_sample(&m, wo, u, &s);
                        ck_assert(finite_nonneg(s.weight) &&
                                  isfinite(s.pdf) && s.pdf >= 0);
                        if (ok)
                            ck_assert(fabs((double)vec_length(s.wi) - 1) <=
                                          1e-4 && s.pdf > 0);
                        random_dir(wx, &g);
                        ck_assert(finite_nonneg(material_eval(&m, wx, wo)));
                        real pdf = material_pdf(&m, wx, wo);
                        ck_assert(isfinite(pdf) && pdf >= 0);
                    }
        }
    }
    test_report_cases("no_nan_or_inf_over_a_dense_sweep", n);
}
END_TEST

/* --- the test vectors ---------------------------------------------------------- */

static RADIANCE csv_rgb(testcsv_t *c, const char *prefix)
{
    char n[3][48];
    snprintf(n[0], sizeof n[0], "%s_r", prefix);
    snprintf(n[1], sizeof n[1], "%s_g", prefix);
    snprintf(n[2], sizeof n[2], "%s_b", prefix);
    return rad_make((real)testcsv_num(c, n[0]), (real)testcsv_num(c, n[1]),
                    (real)testcsv_num(c, n[2]));
}

static const brdf_t *find_kind(const material_t *m, brdf_kind kind)
{
    for (int k = 0; k < m->ncomp; k++)
        if (m->comp[k].kind == kind)
            return &m->comp[k];
    return NULL;
}

static void near3(RADIANCE got, RADIANCE want, double tol, const char *what,
                  int line)
{
    ck_assert_msg(fabs((double)got.r - (double)want.r) <= tol &&
                      fabs((double)got.g - (double)want.g) <= tol &&
                      fabs((double)got.b - (double)want.b) <= tol,
                  "materials.csv:%d: %s = (%.9g, %.9g, %.9g), expected "
                  "(%.9g, %.9g, %.9g) within %.3g", line, what,
                  (double)got.r, (double)got.g, (double)got.b,
                  (double)want.r, (double)want.g, (double)want.b, tol);
}

START_TEST(materials_match_the_vectors)
{
    /* f, the delta components and the refracted direction against the
     * long double values within the file's tolerances; the albedo by
     * Monte Carlo (material_sample, 20000 samples) against the quadrature
     * within 5 standard errors (as material_albedo_never_exceeds_one)
     * plus the quadrature's own tolerance. */
#ifdef SVET_DOUBLE
    const char *tf = "tol_f_double", *ts = "tol_spec_double";
#else
    const char *tf = "tol_f_float", *ts = "tol_spec_float";
#endif
    testcsv_t c;
    testcsv_open(&c, "materials.csv");
    long rows = 0, albedos = 0;
    char last[256] = "";
    while (testcsv_next(&c)) {
        rows++;
        material_params p;
        material_params_default(&p);
        p.rho_d = csv_rgb(&c, "rho_d");
        p.rho_s = csv_rgb(&c, "rho_s");
        p.rho_g = csv_rgb(&c, "rho_g");
        p.rho_t = csv_rgb(&c, "rho_t");
        p.rho_dt = csv_rgb(&c, "rho_dt");
        const char *gl = testcsv_str(&c, "gloss");
        p.gloss = strcmp(gl, "phong") == 0  ? MATERIAL_GLOSS_PHONG
                  : strcmp(gl, "ward") == 0 ? MATERIAL_GLOSS_WARD
                                            : MATERIAL_GLOSS_WARD_BOUNDED;
        p.e = (real)testcsv_num(&c, "e");
        p.alpha_x = (real)testcsv_num(&c, "alpha_x");
        p.alpha_y = (real)testcsv_num(&c, "alpha_y");
        p.eta = (real)testcsv_num(&c, "eta");
        material_t m = build(&p);
        VECTOR3 wo = { (real)testcsv_num(&c, "wo_x"), (real)testcsv_num(&c, "wo_y"),
                       (real)testcsv_num(&c, "wo_z") };
        VECTOR3 wi = { (real)testcsv_num(&c, "wi_x"), (real)testcsv_num(&c, "wi_y"),
                       (real)testcsv_num(&c, "wi_z") };
        vec_normalize(wo, wo);
        vec_normalize(wi, wi);

        near3(material_eval(&m, wi, wo), csv_rgb(&c, "f"),
              testcsv_num(&c, tf), "f", c.line);

        double tol_s = testcsv_num(&c, ts);
        const brdf_t *mir = find_kind(&m, BRDF_MIRROR);
        const brdf_t *tr = find_kind(&m, BRDF_SPECULAR_TRANSMISSION);
        RADIANCE black = rad_grey(0);
        near3(mir ? brdf_nominal(mir, wo) : black, csv_rgb(&c, "spec_r"),
              tol_s, "spec_r", c.line);
        RADIANCE st = csv_rgb(&c, "spec_t");
        near3(tr ? brdf_nominal(tr, wo) : black, st, tol_s, "spec_t", c.line);
        if (tr) {
            real u[2] = { 0, 0 };
            brdf_sample_t s;
            if (brdf_sample(tr, wo, u, &s)) {
                RADIANCE t = rad_make(s.wi[X], s.wi[Y], s.wi[Z]);
                RADIANCE want = rad_make((real)testcsv_num(&c, "t_x"),
                                         (real)testcsv_num(&c, "t_y"),
                                         (real)testcsv_num(&c, "t_z"));
                near3(t, want, tol_s, "t", c.line);
            } else {
                ck_assert_msg((double)rad_max(st) <= tol_s,
                              "materials.csv:%d: no refraction, but "
                              "spec_t = %g", c.line, (double)st.r);
            }
        }

        char key[256];
        snprintf(key, sizeof key, "%s %s %s %s", testcsv_str(&c, "material"),
                 testcsv_str(&c, "wo_x"), testcsv_str(&c, "wo_y"),
                 testcsv_str(&c, "wo_z"));
        if (strcmp(key, last) != 0) {
            snprintf(last, sizeof last, "%s", key);
            albedos++;
            mc3_t a = albedo_mc(&m, wo, 20000, 900 + (uint64_t)albedos);
            RADIANCE want = csv_rgb(&c, "albedo");
            double tq = testcsv_num(&c, "tol_albedo");
            const double w[3] = { (double)want.r, (double)want.g,
                                  (double)want.b };
            for (int k = 0; k < 3; k++)
                ck_assert_msg(fabs(a.mean[k] - w[k]) <= tol3(&a, k) + tq,
                              "materials.csv:%d: %s albedo[%d] by Monte "
                              "Carlo %.6f +- %.2g, quadrature %.6f", c.line,
                              key, k, a.mean[k], a.se[k], w[k]);
        }
    }
    testcsv_close(&c);
    ck_assert(rows >= 700);
    test_report_cases("materials_match_the_vectors", rows + albedos);
}
END_TEST

/* Bit for bit, field by field. */
static bool same_bits(const void *a, const void *b, size_t n)
{
    return memcmp(a, b, n) == 0;
}

static bool same_rad(RADIANCE a, RADIANCE b)
{
    return same_bits(&a.r, &b.r, sizeof a.r) &&
           same_bits(&a.g, &b.g, sizeof a.g) &&
           same_bits(&a.b, &b.b, sizeof a.b);
}

START_TEST(lambert_shortcut_answers_as_the_general_way_bit_for_bit)
{
    /* material.c answers eval, pdf and sample of a single Lambert lobe by
     * a shortcut; with m.lambert cleared the general code (component
     * weights, one-sample MIS) runs; material_eval_pdf() answers as
     * material_eval() and material_pdf(). Reflectances of every kind (black,
     * -0 channels, tiny, up to 1), directions on both sides, grazing and
     * in the tangent plane, random numbers up to the last below 1. */
    pcg32_t g;
    pcg32_seed(&g, 61, 62);
    long n = 0;
    /* REAL_TRUE_MIN: a lobe whose luminance rounds to 0 (no pdf) */
    const real special[7] = { 0, -REAL_C(0.0), REAL_MIN, REAL_C(1e-30), 1,
                              REAL_C(0.5), REAL_TRUE_MIN };
    material_t two_lobes;
    ck_assert(material_phong(&two_lobes, rad_grey(REAL_C(0.5)),
                             rad_grey(REAL_C(0.3)), 10, NULL) == SVET_OK);
    for (int i = 0; i < 400; i++) {
        real c[3];
        for (int k = 0; k < 3; k++)
            c[k] = pcg32_bounded(&g, 3) == 0 ? special[pcg32_bounded(&g, 7)]
                                             : pcg32_real(&g);
        material_t fast, general;
        ck_assert(material_lambert(&fast, rad_make(c[0], c[1], c[2]), NULL) ==
                  SVET_OK);
        /* a black one has no lobe at all (checked below) */
        ck_assert(fast.lambert == (c[0] != 0 || c[1] != 0 || c[2] != 0));
        if (!fast.lambert)
            continue;
        general = fast;
        general.lambert = false;
        for (int j = 0; j < 250; j++, n++) {
            VECTOR3 wi, wo;
            random_dir(wi, &g);
            random_dir(wo, &g);
            if (j % 5 == 0)
                wo[Z] = j % 10 == 0 ? 0 : REAL_C(1e-13) * (wo[Z] > 0 ? 1 : -1);
            if (j % 7 == 0)
                wi[Z] = 0;
            real u[3] = { pcg32_real(&g), pcg32_real(&g), pcg32_real(&g) };
            if (j % 11 == 0)
                u[1] = u[2] = 1 - REAL_EPSILON / 2; /* the last below 1 */
            ck_assert(same_rad(material_eval(&fast, wi, wo),
                               material_eval(&general, wi, wo)));
            real p1 = material_pdf(&fast, wi, wo),
                 p2 = material_pdf(&general, wi, wo);
            ck_assert(same_bits(&p1, &p2, sizeof p1));
            /* material_eval_pdf(): both answers in one call, on the
             * shortcut, the general way and a material of two lobes */
            real pe;
            ck_assert(same_rad(material_eval_pdf(&fast, wi, wo, &pe),
                               material_eval(&general, wi, wo)) &&
                      same_bits(&pe, &p2, sizeof pe));
            ck_assert(same_rad(material_eval_pdf(&general, wi, wo, &pe),
                               material_eval(&general, wi, wo)) &&
                      same_bits(&pe, &p2, sizeof pe));
            real pm = material_pdf(&two_lobes, wi, wo);
            ck_assert(same_rad(material_eval_pdf(&two_lobes, wi, wo, &pe),
                               material_eval(&two_lobes, wi, wo)) &&
                      same_bits(&pe, &pm, sizeof pe));
            brdf_sample_t s1, s2;
            bool a = material_sample(&fast, wo, u, &s1);
            bool b = material_sample(&general, wo, u, &s2);
            ck_assert(a == b);
            ck_assert(same_bits(s1.wi, s2.wi, sizeof s1.wi) &&
                      same_rad(s1.weight, s2.weight) &&
                      same_bits(&s1.pdf, &s2.pdf, sizeof s1.pdf) &&
                      s1.delta == s2.delta && s1.component == s2.component);
        }
    }
    /* only a lone Lambert lobe takes the shortcut */
    material_t m;
    ck_assert(material_phong(&m, rad_grey(REAL_C(0.5)), rad_grey(REAL_C(0.3)),
                             10, NULL) == SVET_OK && !m.lambert);
    ck_assert(material_mirror(&m, rad_grey(REAL_C(0.9)), NULL) == SVET_OK &&
              !m.lambert);
    ck_assert(material_lambert(&m, rad_grey(0), NULL) == SVET_OK &&
              !m.lambert); /* black: no component at all */
    test_report_cases("lambert_shortcut_answers_as_the_general_way_bit_for_bit",
                      n);
}
END_TEST

START_TEST(eval_pdf_answers_as_eval_and_pdf_on_every_kind_of_material)
{
    /* material_eval_pdf() outside the Lambert shortcut: on glass (delta
     * lobes only: f black, pdf 0), Ward under a diffuse base (bounded
     * and the book's), Phong with diffuse transmission, and a black
     * material (no component), f and the pdf are material_eval()'s and
     * material_pdf()'s bit for bit, and with a NULL pdf f alone is the
     * same. Directions on both sides, grazing and in the tangent plane. */
    material_t m[6];
    material_params p;
    ck_assert(material_glass(&m[0], rad_grey(REAL_C(0.1)), rad_grey(REAL_C(0.9)),
                             REAL_C(1.5), NULL) == SVET_OK);
    ck_assert(material_ward(&m[1], rad_grey(REAL_C(0.4)), rad_grey(REAL_C(0.5)),
                            REAL_C(0.05), REAL_C(0.3), NULL) == SVET_OK);
    material_params_default(&p);
    p.rho_d = rad_make(REAL_C(0.2), REAL_C(0.3), REAL_C(0.1));
    p.rho_g = rad_grey(REAL_C(0.6));
    p.gloss = MATERIAL_GLOSS_WARD;
    p.alpha_x = p.alpha_y = REAL_C(0.2);
    ck_assert(material_init(&m[2], &p, NULL) == SVET_OK);
    material_params_default(&p);
    ck_assert(material_init(&m[3], &p, NULL) == SVET_OK); /* black */
    material_params_default(&p);
    p.rho_d = rad_grey(REAL_C(0.3));
    p.rho_g = rad_grey(REAL_C(0.3));
    p.rho_dt = rad_grey(REAL_C(0.3));
    ck_assert(material_init(&m[4], &p, NULL) == SVET_OK);
    material_params_default(&p); /* glass with a diffuse part */
    p.rho_d = rad_grey(REAL_C(0.2));
    p.rho_s = rad_grey(REAL_C(0.1));
    p.rho_t = rad_grey(REAL_C(0.6));
    p.eta = REAL_C(1.33);
    ck_assert(material_init(&m[5], &p, NULL) == SVET_OK);
    ck_assert(m[3].ncomp == 0 && !m[1].lambert && !m[2].lambert);
    pcg32_t g;
    pcg32_seed(&g, 71, 72);
    long n = 0, nonzero = 0;
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 20000; j++, n++) {
            VECTOR3 wi, wo;
            random_dir(wi, &g);
            random_dir(wo, &g);
            if (j % 7 == 0)
                wi[Z] = j % 14 == 0 ? 0 : REAL_C(1e-13);
            if (j % 11 == 0) /* the mirror direction */
                vec_set(wi, -wo[X], -wo[Y], wo[Z]);
            real pe, pd = material_pdf(&m[i], wi, wo);
            RADIANCE f = material_eval(&m[i], wi, wo);
            ck_assert_msg(same_rad(material_eval_pdf(&m[i], wi, wo, &pe), f) &&
                          same_bits(&pe, &pd, sizeof pe),
                          "material %d, case %d", i, j);
            ck_assert(same_rad(material_eval_pdf(&m[i], wi, wo, NULL), f));
            nonzero += pd > 0;
        }
    ck_assert(nonzero > n / 4);
    test_report_cases("eval_pdf_answers_as_eval_and_pdf_on_every_kind_of_"
                      "material", n);
}
END_TEST

START_TEST(transmits_and_specular_flags_say_what_the_material_holds)
{
    /* material_t.transmits and .specular, set once by material_init,
     * stand in for what the integrator asked at every vertex. transmits
     * (rho_t or rho_dt not black) is checked channel by channel (x != 0,
     * so -0 is black) on materials built from channels 0, -0, the
     * smallest subnormal, tiny and ordinary values, with and without a
     * diffuse and a mirror part; a material that fails to build is black
     * and does not transmit. */
    pcg32_t g;
    pcg32_seed(&g, 4242, 17);
    const real pick[] = { 0, REAL_C(-0.0), REAL_TRUE_MIN, REAL_C(1e-30),
                          REAL_C(0.1), REAL_C(0.3) };
    long cases = 0, specular = 0;
    for (int i = 0; i < 50000; i++, cases++) {
        material_params p;
        material_params_default(&p);
        real *ch[6] = { &p.rho_t.r, &p.rho_t.g, &p.rho_t.b,
                        &p.rho_dt.r, &p.rho_dt.g, &p.rho_dt.b };
        bool any = false;
        for (int k = 0; k < 6; k++) {
            /* mostly zeros, so that one nonzero channel is common */
            *ch[k] = pcg32_next(&g) % 3 ? 0 : pick[pcg32_bounded(&g, 6)];
            any = any || *ch[k] != 0;
        }
        if (pcg32_next(&g) % 2)
            p.rho_d = rad_make(REAL_C(0.2), REAL_C(0.3), REAL_C(0.1));
        if (pcg32_next(&g) % 2)
            p.rho_s = rad_make(REAL_C(0.3), 0, REAL_C(0.2));
        if (pcg32_next(&g) % 4 == 0)
            p.eta = REAL_C(1.5);
        material_t m;
        if (material_init(&m, &p, NULL) == SVET_OK)
            ck_assert(m.transmits == any);
        else
            ck_assert(!m.transmits);
        /* material_is_specular(), found once by material_init, against
         * its definition: at least one component, every one a delta */
        bool all = m.ncomp > 0;
        for (int k = 0; k < m.ncomp; k++)
            all = all && brdf_is_delta(&m.comp[k]);
        ck_assert(material_is_specular(&m) == all);
        specular += all;
    }
    ck_assert(specular > 100 && specular < cases - 100);
    test_report_cases(
        "transmits_and_specular_flags_say_what_the_material_holds",
        cases);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("material (" REAL_NAME ")");
    TCase *t = tcase_create("core");
    tcase_set_timeout(t, 600);
    tcase_add_test(t, material_rejects_what_is_not_physical);
    tcase_add_test(t, material_accepts_a_sum_of_exactly_one);
    tcase_add_test(t, sample_weight_and_pdf_agree_with_evaluation);
    tcase_add_test(t, material_eval_is_reciprocal);
    tcase_add_test(t, components_are_chosen_in_proportion_to_their_luminance);
    tcase_add_test(t, material_albedo_never_exceeds_one);
    tcase_add_test(t, lossless_mixtures_conserve_energy_exactly);
    tcase_add_test(t, no_nan_or_inf_over_a_dense_sweep);
    tcase_add_test(t, materials_match_the_vectors);
    tcase_add_test(t, mixed_materials_sample_wi_with_their_pdf);
    tcase_add_test(t, a_wrong_mixture_pdf_fails_the_chi2_test);
    tcase_add_test(t, lambert_shortcut_answers_as_the_general_way_bit_for_bit);
    tcase_add_test(t, eval_pdf_answers_as_eval_and_pdf_on_every_kind_of_material);
    tcase_add_test(t, transmits_and_specular_flags_say_what_the_material_holds);
    suite_add_tcase(s, t);
    return s;
}
