/*
 * test_brdf.c - the components of ch. 1 (brdf.h): chi-square fits of each
 * lobe's sampling to its pdf (grazing directions included) and a wrong pdf
 * that must fail; Helmholtz reciprocity; albedo by Monte Carlo against the
 * values (1.5)-(1.8), (1.13) give; sample weights against evaluation;
 * extremes of every parameter and direction without NaN or Inf.
 */
#include "testutil.h"
#include "materials/brdf.h"
#include "chi2.h"
#include "core/frame.h"
#include "core/rng.h"
#include "core/sample.h"

#include <math.h>
#include <stdlib.h>

#define LEN(a) ((int)(sizeof(a) / sizeof *(a)))
#define EPS ((double)REAL_EPSILON)

/* --- what the tests share ------------------------------------------------ */

/* The unit direction at cos(theta) = c (sign = side) and azimuth phi. */
static void dir(VECTOR3 w, real c, real phi)
{
    real s = sqrt(fmax(REAL_C(0.0), (1 - c) * (1 + c)));
    vec_set(w, s * cos(phi), s * sin(phi), c);
}

static brdf_t make(brdf_kind kind, real p1, real p2)
{
    brdf_t b;
    svet_error err;
    RADIANCE rho = rad_grey(REAL_C(0.8));
    svet_status st = SVET_OK;
    switch (kind) {
    case BRDF_LAMBERT: st = brdf_lambert(&b, rho, &err); break;
    case BRDF_DIFFUSE_TRANSMISSION:
        st = brdf_diffuse_transmission(&b, rho, &err); break;
    case BRDF_PHONG: st = brdf_phong(&b, rho, p1, &err); break;
    case BRDF_WARD: st = brdf_ward(&b, rho, p1, p2, false, &err); break;
    case BRDF_WARD_BOUNDED: st = brdf_ward(&b, rho, p1, p2, true, &err); break;
    case BRDF_MIRROR: st = brdf_mirror(&b, rad_grey(REAL_C(0.04)), p1, &err);
        break;
    case BRDF_SPECULAR_TRANSMISSION:
        st = brdf_specular_transmission(&b, rho, p1, &err); break;
    default: ck_abort_msg("no such kind");
    }
    ck_assert_msg(st == SVET_OK, "%s", err.msg);
    return b;
}

static bool finite_nonneg(RADIANCE c)
{
    return rad_is_finite(c) && c.r >= 0 && c.g >= 0 && c.b >= 0;
}

/* --- chi-square fits ----------------------------------------------------- */

/* The chi-square harness bins directions about +z; a lobe about another
 * axis (Phong's mirror direction) is rotated so that its axis is +z, where
 * chi2_config.cap_height can zoom in on it. */
typedef struct {
    const brdf_t *b;
    VECTOR3 wo;
    VECTOR3 tu, tv, axis; /* the binning frame, axis = its +z */
    const brdf_t *pdf_of; /* the pdf tested: b's own, or a wrong one */
} fit_ctx;

static bool fit_sample(void *p, const real u[2], VECTOR3 w)
{
    fit_ctx *c = p;
    brdf_sample_t s;
    if (!brdf_sample(c->b, c->wo, u, &s))
        return false;
    frame_to_local(w, s.wi, c->tu, c->tv, c->axis);
    return true;
}

static double fit_pdf(void *p, const VECTOR3 w)
{
    fit_ctx *c = p;
    VECTOR3 wi;
    frame_to_world(wi, w, c->tu, c->tv, c->axis);
    return (double)brdf_pdf(c->pdf_of, wi, c->wo);
}

/* The lobes fitted, with the cap the binning zooms to (0 = whole sphere). */
static const struct {
    const char *name;
    brdf_kind kind;
    real p1, p2;
    double cap;
} fit_lobes[] = {
    { "lambert", BRDF_LAMBERT, 0, 0, 0 },
    { "diffuse transmission", BRDF_DIFFUSE_TRANSMISSION, 0, 0, 0 },
    { "phong e=1", BRDF_PHONG, 1, 0, 0 },
    { "phong e=10", BRDF_PHONG, 10, 0, 1.0 },
    { "phong e=100", BRDF_PHONG, 100, 0, 0.1 },
    { "ward a=0.1", BRDF_WARD, REAL_C(0.1), REAL_C(0.1), 0.4 },
    { "ward a=0.4", BRDF_WARD, REAL_C(0.4), REAL_C(0.4), 0 },
    { "ward ax=0.3 ay=0.03", BRDF_WARD, REAL_C(0.3), REAL_C(0.03), 0 },
    { "ward ax=0.05 ay=0.25", BRDF_WARD_BOUNDED, REAL_C(0.05), REAL_C(0.25),
      0 },
};
/* cos(theta_o) of the incoming directions: normal, oblique, grazing, and
 * one from below (the two-sided lobes reflect on the side of wo) */
static const real fit_cos[] = { 1, REAL_C(0.5), REAL_C(1e-3), REAL_C(1e-5),
                                REAL_C(-0.6) };
/* Every chi-square test of this suite, for the Sidak correction: the fits
 * above plus the three deliberately wrong pdfs. */
#define CHI2_TESTS (LEN(fit_lobes) * LEN(fit_cos) + 3)

static void fit_frame(fit_ctx *c, bool about_mirror)
{
    if (about_mirror)
        vec_set(c->axis, -c->wo[X], -c->wo[Y], c->wo[Z]);
    else
        vec_set(c->axis, 0, 0, c->wo[Z] < 0 ? -1 : 1);
    frame_from_normal(c->tu, c->tv, c->axis);
}

/* SVET_VERBOSE=1 in the environment prints every statistic and p-value. */
static chi2_result fit(fit_ctx *c, double cap, uint64_t seed)
{
    chi2_config cfg = { 0 };
    cfg.tests = CHI2_TESTS;
    cfg.seed = seed;
    cfg.cap_height = cap;
    cfg.samples = 100000;
    return chi2_test(&cfg, fit_sample, fit_pdf, c);
}

START_TEST(each_lobe_samples_wi_with_its_pdf)
{
    int n = 0;
    for (int i = 0; i < LEN(fit_lobes); i++)
        for (int j = 0; j < LEN(fit_cos); j++) {
            brdf_t b = make(fit_lobes[i].kind, fit_lobes[i].p1,
                            fit_lobes[i].p2);
            fit_ctx c = { .b = &b, .pdf_of = &b };
            dir(c.wo, fit_cos[j], REAL_C(0.7));
            bool glossy = b.kind == BRDF_PHONG || b.kind == BRDF_WARD ||
                          b.kind == BRDF_WARD_BOUNDED;
            fit_frame(&c, glossy);
            chi2_result r = fit(&c, fit_lobes[i].cap, 1000 + (uint64_t)n);
            if (getenv("SVET_VERBOSE"))
                printf("    %s, cos %g: %s\n", fit_lobes[i].name,
                       (double)fit_cos[j], r.message);
            ck_assert_msg(r.passed, "%s, cos theta_o = %g: %s",
                          fit_lobes[i].name, (double)fit_cos[j], r.message);
            n++;
        }
    test_report_cases("each_lobe_samples_wi_with_its_pdf", n);
}
END_TEST

START_TEST(a_wrong_pdf_fails_the_chi2_test)
{
    /* The harness must be able to say no: sample one lobe, test against a
     * slightly different one. Each must fail at the same Sidak-corrected
     * threshold the fits above pass. */
    const struct { brdf_kind kind; real p, wrong; real cos_o; } cases[] = {
        { BRDF_PHONG, 10, 12, REAL_C(0.8) },          /* exponent off by 2 */
        { BRDF_WARD, REAL_C(0.2), REAL_C(0.23), REAL_C(0.5) }, /* alpha +15% */
        { BRDF_PHONG, 1, 0, REAL_C(1e-3) },           /* grazing, e 1 vs 0 */
    };
    for (int i = 0; i < LEN(cases); i++) {
        brdf_t b = make(cases[i].kind, cases[i].p, cases[i].p);
        brdf_t w = make(cases[i].kind, cases[i].wrong, cases[i].wrong);
        fit_ctx c = { .b = &b, .pdf_of = &w };
        dir(c.wo, cases[i].cos_o, REAL_C(0.3));
        fit_frame(&c, true);
        chi2_result r = fit(&c, 0, 77 + (uint64_t)i);
        if (getenv("SVET_VERBOSE"))
            printf("    wrong pdf %d: %s\n", i, r.message);
        ck_assert_msg(!r.passed, "case %d: a wrong pdf passed: %s", i,
                      r.message);
    }
    test_report_cases("a_wrong_pdf_fails_the_chi2_test", LEN(cases));
}
END_TEST

/* --- reciprocity ---------------------------------------------------------- */

/* Every non-delta lobe in its parameter extremes. */
static const struct {
    brdf_kind kind;
    real p1, p2;
} lobes[] = {
    { BRDF_LAMBERT, 0, 0 },
    { BRDF_DIFFUSE_TRANSMISSION, 0, 0 },
    { BRDF_PHONG, 0, 0 },
    { BRDF_PHONG, 1, 0 },
    { BRDF_PHONG, 10, 0 },
    { BRDF_PHONG, 1e3, 0 },
    { BRDF_PHONG, 1e5, 0 },
    { BRDF_WARD, REAL_C(1e-4), REAL_C(1e-4) },
    { BRDF_WARD, REAL_C(0.01), REAL_C(0.01) },
    { BRDF_WARD, 1, 1 },
    { BRDF_WARD, 1, REAL_C(0.01) },
    { BRDF_WARD, REAL_C(1e-4), REAL_C(0.01) },
    { BRDF_WARD_BOUNDED, REAL_C(1e-4), REAL_C(1e-4) },
    { BRDF_WARD_BOUNDED, REAL_C(0.01), REAL_C(0.01) },
    { BRDF_WARD_BOUNDED, 1, 1 },
    { BRDF_WARD_BOUNDED, 1, REAL_C(0.01) },
    { BRDF_WARD_BOUNDED, REAL_C(0.01), 1 },
};

static void random_dir(VECTOR3 w, pcg32_t *g)
{
    real u[2] = { pcg32_real(g), pcg32_real(g) };
    sample_uniform_sphere(w, u);
}

START_TEST(lobes_are_reciprocal)
{
    /* Helmholtz: f(wi, wo) = f(wo, wi). Every formula here is symmetric in
     * its arithmetic too (h = wi + wo, |wi - r(wo)| = |wo - r(wi)|,
     * sqrt(cos_i cos_o)), so the two evaluations agree to the last bit. */
    pcg32_t g;
    pcg32_seed(&g, 5, 6);
    long n = 0;
    for (int i = 0; i < LEN(lobes); i++) {
        brdf_t b = make(lobes[i].kind, lobes[i].p1, lobes[i].p2);
        for (int k = 0; k < 20000; k++, n++) {
            VECTOR3 wi, wo;
            random_dir(wo, &g);
            if (k % 2) { /* near the mirror direction, where lobes peak */
                brdf_sample_t s;
                real u[2] = { pcg32_real(&g), pcg32_real(&g) };
                if (!brdf_sample(&b, wo, u, &s))
                    continue;
                vec_copy(wi, s.wi);
            } else {
                random_dir(wi, &g);
            }
            RADIANCE a = brdf_eval(&b, wi, wo), c = brdf_eval(&b, wo, wi);
            ck_assert_msg(a.r == c.r && a.g == c.g && a.b == c.b,
                          "%s: f(wi,wo) = %.9g, f(wo,wi) = %.9g",
                          brdf_kind_name(b.kind), (double)a.r, (double)c.r);
        }
    }
    test_report_cases("lobes_are_reciprocal", n);
}
END_TEST

START_TEST(specular_transmission_weight_is_the_same_both_ways)
{
    /* The stated exception to reciprocity: across a surface with eta != 1
     * the radiance L changes by (n_t/n_i)^2, so a BTDF for L is not
     * symmetric. svet transports L/n^2 (brdf.c), for which the BTDF is
     * symmetric: refracting wo gives wi, refracting wi gives wo back, and
     * both carry the same rho_t(theta). */
    const real etas[] = { 1, REAL_C(1.5), REAL_C(1) / REAL_C(1.5), REAL_C(2.4) };
    pcg32_t g;
    pcg32_seed(&g, 7, 8);
    long n = 0;
    for (int e = 0; e < LEN(etas); e++) {
        brdf_t b = make(BRDF_SPECULAR_TRANSMISSION, etas[e], 0);
        for (int k = 0; k < 20000; k++) {
            VECTOR3 wo;
            random_dir(wo, &g);
            real u[2] = { 0, 0 };
            brdf_sample_t s, back;
            if (!brdf_sample(&b, wo, u, &s))
                continue; /* total internal reflection */
            n++;
            ck_assert(s.delta && s.pdf == 1);
            /* Near the critical angle the cosine in the thinner medium is
             * c = sqrt(small difference): an absolute rounding of 2 eps
             * in its square is eps / c in c, and rho_t(theta) has slope
             * 5 rho_t(0) (1 - c)^4 <= 4; so 16 eps / c bounds both the
             * direction and the weight. */
            double c = fmin(fabs((double)wo[Z]), fabs((double)s.wi[Z]));
            double tol = fmin(16 * EPS / c, 1e-2);
            if (!brdf_sample(&b, s.wi, u, &back)) {
                /* rounding put the way back just past the critical angle,
                 * where rho_t vanishes continuously */
                ck_assert_near(s.weight.r, 0, tol);
                continue;
            }
            for (int a = 0; a < 3; a++)
                ck_assert_near(back.wi[a], wo[a], tol);
            ck_assert_near(back.weight.r, s.weight.r, tol);
        }
    }
    ck_assert(n > 40000);
    test_report_cases("specular_transmission_weight_is_the_same_both_ways", n);
}
END_TEST

/* --- weights, pdfs and evaluation ---------------------------------------- */

START_TEST(sample_weight_and_pdf_agree_with_evaluation)
{
    /* For a non-delta lobe the weight must be f |cos theta_i| / pdf and
     * the pdf that brdf_pdf gives for the same pair: the renderer mixes
     * them in MIS. The weights are computed in closed form (cos^e and the
     * Gaussian cancel), so they agree only to rounding: relative 2e-3 in
     * float covers the worst case (Ward alpha = 1e-4: the half vector
     * recomputed from wi + wo differs from the sampled one by a few ulps,
     * which the exponent tan^2/alpha^2 amplifies), 1e-9 in double. */
#ifdef SVET_DOUBLE
    const double rel = 1e-9;
#else
    const double rel = 2e-3;
#endif
    pcg32_t g;
    pcg32_seed(&g, 9, 10);
    long n = 0;
    for (int i = 0; i < LEN(lobes); i++) {
        brdf_t b = make(lobes[i].kind, lobes[i].p1, lobes[i].p2);
        for (int k = 0; k < 20000; k++) {
            VECTOR3 wo;
            random_dir(wo, &g);
            real u[2] = { pcg32_real(&g), pcg32_real(&g) };
            brdf_sample_t s;
            if (!brdf_sample(&b, wo, u, &s))
                continue;
            n++;
            ck_assert(!s.delta);
            real pdf = brdf_pdf(&b, s.wi, wo);
            ck_assert_rel(s.pdf, pdf, 1e2 * EPS, 0);
            RADIANCE f = brdf_eval(&b, s.wi, wo);
            double expect = (double)f.r * fabs((double)s.wi[Z]) / (double)pdf;
            ck_assert_msg(fabs((double)s.weight.r - expect) <=
                              rel * fmax((double)s.weight.r, expect) + 1e-30,
                          "%s p=%g: weight %.9g, f cos/pdf %.9g",
                          brdf_kind_name(b.kind), (double)lobes[i].p1,
                          (double)s.weight.r, expect);
        }
    }
    test_report_cases("sample_weight_and_pdf_agree_with_evaluation", n);
}
END_TEST

/* --- albedo by Monte Carlo ------------------------------------------------ */
/*
 * The albedo a(wo) = integral of f(wi, wo) |cos theta_i| d(omega_i) is
 * estimated by the mean of N sample weights W (0 for an absorbed sample):
 * E[W] = a. By the central limit theorem the mean lies within z standard
 * errors s/sqrt(N) of a with probability erf(z/sqrt 2); z = 5 leaves
 * 5.7e-7 per comparison, under 1e-3 for all comparisons of the suite. The
 * seeds are fixed, so a pass is reproducible; the bound says a failure is
 * a bug and not bad luck. The weights are summed in double (estimator_t);
 * rounding of float weights adds at most a relative 1e-6, included.
 */
#define Z_SIGMA 5.0

typedef struct {
    double mean, se;
} mc_t;

/* importance-sampled (uniform = false) or uniform over the sphere */
static mc_t albedo_mc(const brdf_t *b, const VECTOR3 wo, long n, uint64_t seed,
                      bool uniform)
{
    pcg32_t g;
    pcg32_seed(&g, seed, 99);
    estimator_t e;
    estimator_init(&e);
    for (long k = 0; k < n; k++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        double w = 0;
        if (uniform) {
            VECTOR3 wi;
            sample_uniform_sphere(wi, u);
            RADIANCE f = brdf_eval(b, wi, wo);
            w = (double)f.r * fabs((double)wi[Z]) * 4 * 3.14159265358979323846;
        } else {
            brdf_sample_t s;
            if (brdf_sample(b, wo, u, &s))
                w = (double)s.weight.r;
        }
        estimator_add(&e, w);
    }
    mc_t r = { estimator_mean(&e), estimator_stderr(&e) };
    return r;
}

static double tol_of(mc_t m)
{
    return Z_SIGMA * m.se + 1e-6 * fabs(m.mean);
}

START_TEST(lambert_albedo_is_rho_d)
{
    brdf_t b = make(BRDF_LAMBERT, 0, 0);
    const real cs[] = { 1, REAL_C(0.5), REAL_C(1e-3), REAL_C(1e-7),
                        REAL_C(-0.3) };
    for (int i = 0; i < LEN(cs); i++) {
        VECTOR3 wo;
        dir(wo, cs[i], 1);
        /* cosine sampling: every weight is rho_d exactly, variance 0 */
        mc_t is = albedo_mc(&b, wo, 10000, 1, false);
        ck_assert_near(is.mean, 0.8, 1e-6);
        ck_assert_near(is.se, 0, 1e-6);
        /* uniform sampling: an independent estimate of the same integral */
        mc_t un = albedo_mc(&b, wo, 200000, 2, true);
        ck_assert_near(un.mean, 0.8, tol_of(un));
    }
    test_report_cases("lambert_albedo_is_rho_d", 2 * LEN(cs));
}
END_TEST

START_TEST(diffuse_transmission_albedo_is_rho)
{
    brdf_t b = make(BRDF_DIFFUSE_TRANSMISSION, 0, 0);
    const real cs[] = { 1, REAL_C(0.2), REAL_C(-1e-5) };
    for (int i = 0; i < LEN(cs); i++) {
        VECTOR3 wo;
        dir(wo, cs[i], 2);
        mc_t is = albedo_mc(&b, wo, 10000, 3, false);
        ck_assert_near(is.mean, 0.8, 1e-6);
        mc_t un = albedo_mc(&b, wo, 200000, 4, true);
        ck_assert_near(un.mean, 0.8, tol_of(un));
    }
    test_report_cases("diffuse_transmission_albedo_is_rho", 2 * LEN(cs));
}
END_TEST

static const real phong_e[] = { 0, 1, 10, 1e3, 1e5 };

START_TEST(phong_albedo_is_rho_s_at_normal_incidence)
{
    /* With wo along n the lobe axis is n and (1.8) integrates to rho_s
     * exactly: (e+2)/(2 pi) * 2 pi / (e + 2). */
    VECTOR3 wo = { 0, 0, 1 };
    for (int i = 0; i < LEN(phong_e); i++) {
        brdf_t b = make(BRDF_PHONG, phong_e[i], 0);
        mc_t is = albedo_mc(&b, wo, 200000, 5, false);
        ck_assert_near(is.mean, 0.8, tol_of(is));
        if (phong_e[i] <= 10) { /* uniform sampling resolves wide lobes */
            mc_t un = albedo_mc(&b, wo, 400000, 6, true);
            ck_assert_near(un.mean, 0.8, tol_of(un));
        }
    }
    test_report_cases("phong_albedo_is_rho_s_at_normal_incidence",
                      LEN(phong_e));
}
END_TEST

/* cos(theta_o) from the normal to the grazing extreme */
static const real albedo_cos[] = { 1, REAL_C(0.9), REAL_C(0.7), REAL_C(0.4),
                                   REAL_C(0.1), REAL_C(1e-3), REAL_C(1e-5),
                                   REAL_C(1e-7) };

START_TEST(phong_albedo_never_exceeds_rho_s)
{
    long n = 0;
    double prev = 2;
    for (int i = 0; i < LEN(phong_e); i++) {
        brdf_t b = make(BRDF_PHONG, phong_e[i], 0);
        prev = 2;
        for (int j = 0; j < LEN(albedo_cos); j++, n++) {
            VECTOR3 wo;
            dir(wo, albedo_cos[j], REAL_C(0.4));
            mc_t is = albedo_mc(&b, wo, 100000, 7 + (uint64_t)n, false);
            ck_assert_msg(is.mean <= 0.8 + tol_of(is),
                          "e = %g, cos = %g: albedo %.6f > rho_s 0.8",
                          (double)phong_e[i], (double)albedo_cos[j], is.mean);
            /* and it falls as the lobe tilts toward the horizon */
            ck_assert(is.mean <= prev + tol_of(is));
            prev = is.mean;
        }
    }
    test_report_cases("phong_albedo_never_exceeds_rho_s", n);
}
END_TEST

static const real ward_alpha[][2] = {
    { REAL_C(1e-4), REAL_C(1e-4) }, { REAL_C(0.01), REAL_C(0.01) },
    { REAL_C(0.2), REAL_C(0.2) },   { 1, 1 },
    { 1, REAL_C(0.01) },            { REAL_C(0.01), REAL_C(1e-4) },
};

START_TEST(bounded_ward_albedo_never_exceeds_rho_s)
{
    long n = 0;
    for (int i = 0; i < LEN(ward_alpha); i++) {
        brdf_t b = make(BRDF_WARD_BOUNDED, ward_alpha[i][0], ward_alpha[i][1]);
        for (int j = 0; j < LEN(albedo_cos); j++, n++) {
            VECTOR3 wo;
            dir(wo, albedo_cos[j], REAL_C(0.4));
            mc_t is = albedo_mc(&b, wo, 100000, 100 + (uint64_t)n, false);
            ck_assert_msg(is.mean <= 0.8 + tol_of(is),
                          "alpha (%g, %g), cos = %g: albedo %.6f > 0.8",
                          (double)ward_alpha[i][0], (double)ward_alpha[i][1],
                          (double)albedo_cos[j], is.mean);
        }
    }
    test_report_cases("bounded_ward_albedo_never_exceeds_rho_s", n);
}
END_TEST

START_TEST(book_ward_albedo_is_rho_cos_for_small_alpha)
{
    /* What brdf.c says of (1.9): for a narrow lobe the albedo is
     * rho_s cos(theta_o), not rho_s. Exact as alpha -> 0; at alpha = 0.01
     * the relative difference is of order alpha^2. */
    brdf_t b = make(BRDF_WARD, REAL_C(0.01), REAL_C(0.01));
    const real cs[] = { 1, REAL_C(0.8), REAL_C(0.5), REAL_C(0.2) };
    for (int i = 0; i < LEN(cs); i++) {
        VECTOR3 wo;
        dir(wo, cs[i], 0);
        mc_t is = albedo_mc(&b, wo, 100000, 200 + (uint64_t)i, false);
        ck_assert_near(is.mean, 0.8 * (double)cs[i], tol_of(is) + 1e-3);
    }
    test_report_cases("book_ward_albedo_is_rho_cos_for_small_alpha", LEN(cs));
}
END_TEST

START_TEST(book_ward_albedo_exceeds_one_at_grazing)
{
    /* ... and for a rough surface seen at grazing angles it reflects more
     * than it receives, growing like 1/sqrt(cos theta_o) (Duer 2006): the
     * reason BRDF_WARD_BOUNDED exists. Uniform sampling, an estimator
     * independent of Ward's sampling. */
    brdf_t b = make(BRDF_WARD, 1, 1);
    VECTOR3 wo;
    dir(wo, REAL_C(1e-4), 0);
    mc_t un = albedo_mc(&b, wo, 400000, 300, true);
    ck_assert_msg(un.mean - tol_of(un) > 1,
                  "albedo at cos 1e-4: %.4f +- %.4f", un.mean, un.se);
    test_report_cases("book_ward_albedo_exceeds_one_at_grazing", 1);
}
END_TEST

/* long double reference of Schlick (1.7) with the book's rho90 = 1, at
 * the cosine in the thinner medium by Snell's law (independent of
 * brdf_fresnel_cos). */
static long double schlick_ref(long double rho0, long double cos_o,
                               long double eta)
{
    long double n_from = cos_o > 0 ? 1 : eta, n_to = cos_o > 0 ? eta : 1;
    long double c = fabsl(cos_o);
    if (n_from > n_to) {
        long double sin_t = n_from / n_to * sqrtl(1 - c * c);
        if (sin_t >= 1)
            return 1;
        c = sqrtl(1 - sin_t * sin_t);
    }
    return rho0 + (1 - rho0) * powl(1 - c, 5);
}

START_TEST(mirror_albedo_is_the_schlick_value)
{
    const real etas[] = { 1, REAL_C(1.5) };
    const real cs[] = { 1, REAL_C(0.5), REAL_C(0.1), REAL_C(1e-3),
                        REAL_C(1e-7), REAL_C(-0.9), REAL_C(-0.75),
                        REAL_C(-0.5) };
    long n = 0;
    for (int e = 0; e < LEN(etas); e++)
        for (int i = 0; i < LEN(cs); i++, n++) {
            brdf_t b = make(BRDF_MIRROR, etas[e], 0);
            VECTOR3 wo;
            dir(wo, cs[i], REAL_C(0.5));
            real u[2] = { REAL_C(0.3), REAL_C(0.6) };
            brdf_sample_t s;
            ck_assert(brdf_sample(&b, wo, u, &s));
            ck_assert(s.delta && s.pdf == 1);
            /* the mirror direction (1.4) */
            ck_assert(s.wi[X] == -wo[X] && s.wi[Y] == -wo[Y] &&
                      s.wi[Z] == wo[Z]);
            long double ref = schlick_ref(0.04L, (long double)wo[Z],
                                          (long double)etas[e]);
            ck_assert_rel(s.weight.r, ref, 64 * REAL_EPSILON, 0);
            /* f itself is a delta: zero for every pair */
            RADIANCE f = brdf_eval(&b, s.wi, wo);
            ck_assert(rad_is_black(f) && brdf_pdf(&b, s.wi, wo) == 0);
        }
    test_report_cases("mirror_albedo_is_the_schlick_value", n);
}
END_TEST

START_TEST(specular_transmission_albedo_is_the_books_rho_t)
{
    /* rho_t(theta) = rho_t(0) (1 - (1 - cos theta)^5), cos theta in the
     * thinner medium; zero beyond the critical angle. */
    const real etas[] = { 1, REAL_C(1.5), REAL_C(0.5) };
    pcg32_t g;
    pcg32_seed(&g, 11, 12);
    long n = 0;
    for (int e = 0; e < LEN(etas); e++) {
        brdf_t b = make(BRDF_SPECULAR_TRANSMISSION, etas[e], 0);
        for (int k = 0; k < 5000; k++, n++) {
            VECTOR3 wo;
            random_dir(wo, &g);
            real u[2] = { 0, 0 };
            brdf_sample_t s;
            bool ok = brdf_sample(&b, wo, u, &s);
            long double r = schlick_ref(0, (long double)wo[Z],
                                        (long double)etas[e]);
            long double rho_t = 0.8L * (1 - r); /* r = (1 - c)^5 here */
            if (!ok) {
                /* only total internal reflection (or a vanishing rho_t) */
                ck_assert_msg(rho_t < 1e-5L, "no transmission where rho_t = "
                              "%Lg", rho_t);
                continue;
            }
            ck_assert(s.wi[Z] * wo[Z] < 0);
            /* Snell: n_o sin(theta_o) = n_i sin(theta_i) */
            long double eta = (long double)etas[e];
            long double n_o = wo[Z] > 0 ? 1 : eta, n_i = wo[Z] > 0 ? eta : 1;
            long double so = hypotl((long double)wo[X], (long double)wo[Y]);
            long double si = hypotl((long double)s.wi[X], (long double)s.wi[Y]);
            ck_assert_near(n_o * so, n_i * si, 1e2 * EPS);
            /* the absolute rounding of the cosine near the critical angle
             * is amplified by 5 (1 - c)^4 <= 5 */
            ck_assert_near(s.weight.r, rho_t, 1e3 * EPS);
        }
    }
    test_report_cases("specular_transmission_albedo_is_the_books_rho_t", n);
}
END_TEST

/* --- interfaces at their limits ----------------------------------------- */

START_TEST(index_match_transmits_straight_through)
{
    /* n1 = n2: no refraction; wi = -wo and rho_t(theta) of the book */
    brdf_t b = make(BRDF_SPECULAR_TRANSMISSION, 1, 0);
    const real cs[] = { 1, REAL_C(0.5), REAL_C(1e-3), REAL_C(1e-7),
                        REAL_C(-0.5), REAL_C(-1e-7) };
    for (int i = 0; i < LEN(cs); i++) {
        VECTOR3 wo;
        dir(wo, cs[i], REAL_C(2.0));
        real u[2] = { REAL_C(0.5), REAL_C(0.5) };
        brdf_sample_t s;
        ck_assert(brdf_sample(&b, wo, u, &s));
        for (int a = 0; a < 3; a++)
            ck_assert_near(s.wi[a], -wo[a], 4 * REAL_EPSILON);
        long double f5 = powl(1 - fabsl((long double)wo[Z]), 5);
        ck_assert_near(s.weight.r, 0.8L * (1 - f5), 16 * REAL_EPSILON);
    }
    test_report_cases("index_match_transmits_straight_through", LEN(cs));
}
END_TEST

START_TEST(total_internal_reflection_starts_at_the_critical_angle)
{
    /* Inside glass (eta = 1.5) at sin(theta) = 1/eta transmission stops
     * and the mirror reflects rho90: both continuously (rho_t -> 0 and
     * rho_s -> 1 as the cosine in air -> 0). */
    const real eta = REAL_C(1.5);
    brdf_t t = make(BRDF_SPECULAR_TRANSMISSION, eta, 0);
    brdf_t m = make(BRDF_MIRROR, eta, 0);
    real sin_c = 1 / eta;
    real u[2] = { 0, 0 };
    long n = 0;
    /* approach the critical angle from below: the transmitted weight
     * falls to 0 without a jump and the mirror's rises to 1 */
    double prev_t = 1;
    for (int k = 1; k <= 40; k++, n++) {
        real s = sin_c * (1 - (real)pow(2.0, -k));
        real c = -sqrt((1 - s) * (1 + s));
        VECTOR3 wo = { s, 0, c };
        brdf_sample_t st, sm;
        bool ok = brdf_sample(&t, wo, u, &st);
        ck_assert(brdf_sample(&m, wo, u, &sm));
        ck_assert(rad_is_finite(st.weight) && rad_is_finite(sm.weight));
        if (ok) {
            ck_assert((double)st.weight.r <= prev_t + 1e-6);
            prev_t = (double)st.weight.r;
        }
        /* rho_s + rho_t <= 1 on the way */
        ck_assert((double)sm.weight.r + (double)(ok ? st.weight.r : 0) <=
                  1 + 1e-6);
    }
    ck_assert(prev_t < 1e-2);
    /* exactly at the critical angle, and beyond it */
    for (int k = 0; k < 3; k++, n++) {
        real s = k == 0 ? sin_c : k == 1 ? REAL_C(0.8) : 1;
        real c = -sqrt(fmax(REAL_C(0.0), (1 - s) * (1 + s)));
        VECTOR3 wo = { s, 0, c };
        brdf_sample_t st, sm;
        bool ok = brdf_sample(&t, wo, u, &st);
        if (ok) /* rounding put it a hair inside: rho_t is then ~0 */
            ck_assert_near(st.weight.r, 0, 1e-2);
        ck_assert(rad_is_finite(st.weight));
        if (fabs(c) >= BRDF_COS_MIN) {
            ck_assert(brdf_sample(&m, wo, u, &sm));
            ck_assert_near(sm.weight.r, 1, ok ? 1e-2 : 0);
        }
        ck_assert_near(brdf_fresnel_cos(c, eta), 0, ok ? 1e-2 : 0);
    }
    test_report_cases("total_internal_reflection_starts_at_the_critical_angle",
                      n);
}
END_TEST

/* --- no NaN, no Inf ------------------------------------------------------ */

static brdf_t sweep_brdf(int i, int *count)
{
    /* all components with every extreme parameter */
    static const struct { brdf_kind kind; real p1, p2; } all[] = {
        { BRDF_LAMBERT, 0, 0 }, { BRDF_DIFFUSE_TRANSMISSION, 0, 0 },
        { BRDF_PHONG, 0, 0 }, { BRDF_PHONG, 1, 0 }, { BRDF_PHONG, 10, 0 },
        { BRDF_PHONG, 1e3, 0 }, { BRDF_PHONG, 1e5, 0 },
        { BRDF_PHONG, BRDF_PHONG_E_MAX, 0 },
        { BRDF_WARD, REAL_C(1e-4), REAL_C(1e-4) },
        { BRDF_WARD, REAL_C(0.01), REAL_C(0.01) }, { BRDF_WARD, 1, 1 },
        { BRDF_WARD, 1, REAL_C(0.01) }, { BRDF_WARD, REAL_C(0.01), REAL_C(1e-4) },
        { BRDF_WARD, BRDF_WARD_ALPHA_MIN, BRDF_WARD_ALPHA_MIN },
        { BRDF_WARD, BRDF_WARD_ALPHA_MAX, BRDF_WARD_ALPHA_MIN },
        { BRDF_WARD_BOUNDED, REAL_C(1e-4), REAL_C(1e-4) },
        { BRDF_WARD_BOUNDED, REAL_C(0.01), REAL_C(0.01) },
        { BRDF_WARD_BOUNDED, 1, 1 }, { BRDF_WARD_BOUNDED, 1, REAL_C(0.01) },
        { BRDF_WARD_BOUNDED, REAL_C(0.01), REAL_C(1e-4) },
        { BRDF_WARD_BOUNDED, BRDF_WARD_ALPHA_MIN, BRDF_WARD_ALPHA_MIN },
        { BRDF_WARD_BOUNDED, BRDF_WARD_ALPHA_MAX, BRDF_WARD_ALPHA_MAX },
        { BRDF_MIRROR, 1, 0 }, { BRDF_MIRROR, REAL_C(1.5), 0 },
        { BRDF_MIRROR, REAL_C(1e-3), 0 },
        { BRDF_SPECULAR_TRANSMISSION, 1, 0 },
        { BRDF_SPECULAR_TRANSMISSION, REAL_C(1.5), 0 },
        { BRDF_SPECULAR_TRANSMISSION, REAL_C(1) / REAL_C(1.5), 0 },
        { BRDF_SPECULAR_TRANSMISSION, REAL_C(1e3), 0 },
        { BRDF_SPECULAR_TRANSMISSION, REAL_C(1e-3), 0 },
    };
    *count = LEN(all);
    return make(all[i].kind, all[i].p1, all[i].p2);
}

static void check_all(const brdf_t *b, const VECTOR3 wo, const real u[2],
                      const VECTOR3 wx)
{
    brdf_sample_t s;
    bool ok = brdf_sample(b, wo, u, &s);
    ck_assert(finite_nonneg(s.weight) && isfinite(s.pdf) && s.pdf >= 0);
    if (ok) {
        ck_assert_msg(fabs((double)vec_length(s.wi) - 1) <= 1e-4 && s.pdf > 0,
                      "%s: |wi| = %g, pdf %g", brdf_kind_name(b->kind),
                      (double)vec_length(s.wi), (double)s.pdf);
        ck_assert(finite_nonneg(brdf_eval(b, s.wi, wo)));
        real p = brdf_pdf(b, s.wi, wo);
        ck_assert(isfinite(p) && p >= 0);
    } else {
        ck_assert(rad_is_black(s.weight) && s.pdf == 0);
    }
    /* and an unrelated direction */
    RADIANCE f = brdf_eval(b, wx, wo);
    real p = brdf_pdf(b, wx, wo);
    ck_assert_msg(finite_nonneg(f) && isfinite(p) && p >= 0,
                  "%s: f %g pdf %g", brdf_kind_name(b->kind), (double)f.r,
                  (double)p);
    ck_assert(finite_nonneg(brdf_nominal(b, wo)));
}

START_TEST(no_nan_or_inf_over_a_dense_sweep)
{
    /* cos(theta) from 1 down to 1e-7 and below (tangent), both sides;
     * u = 0 and the largest real below 1 */
    const real one_minus = 1 - REAL_EPSILON / 2;
    const real cs[] = { 1, one_minus, REAL_C(0.5), REAL_C(0.1), REAL_C(1e-3),
                        REAL_C(1e-5), REAL_C(1e-7), REAL_C(1e-12),
                        REAL_C(1e-20), 0 };
    const real us[] = { 0, REAL_MIN, REAL_C(1e-7), REAL_C(0.25), REAL_C(0.5),
                        one_minus };
    const real phis[] = { 0, REAL_C(0.8), REAL_C(1.5707963), REAL_C(3.0) };
    int nb;
    sweep_brdf(0, &nb);
    pcg32_t g;
    pcg32_seed(&g, 13, 14);
    long n = 0;
    for (int i = 0; i < nb; i++) {
        brdf_t b = sweep_brdf(i, &nb);
        for (int side = -1; side <= 1; side += 2)
            for (int c = 0; c < LEN(cs); c++)
                for (int p = 0; p < LEN(phis); p++) {
                    VECTOR3 wo, wx;
                    dir(wo, side * cs[c], phis[p]);
                    for (int a = 0; a < LEN(us); a++)
                        for (int d = 0; d < LEN(us); d++, n++) {
                            real u[2] = { us[a], us[d] };
                            dir(wx, -side * cs[(a + d) % LEN(cs)],
                                phis[(p + a) % LEN(phis)]);
                            check_all(&b, wo, u, wx);
                            /* wx near wo's mirror direction too */
                            vec_set(wx, -wo[X], -wo[Y], wo[Z]);
                            check_all(&b, wo, u, wx);
                        }
                    for (int k = 0; k < 32; k++, n++) {
                        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
                        random_dir(wx, &g);
                        check_all(&b, wo, u, wx);
                    }
                }
    }
    test_report_cases("no_nan_or_inf_over_a_dense_sweep", n);
}
END_TEST

/* --- constructors --------------------------------------------------------- */

START_TEST(constructors_reject_what_is_not_physical)
{
    brdf_t b;
    svet_error err;
    const real nan = (real)NAN, inf = (real)INFINITY;
    const RADIANCE bad_rho[] = { rad_make(nan, 0, 0), rad_make(0, -REAL_C(0.1), 0),
                                 rad_make(0, 0, REAL_C(1.01)),
                                 rad_make(inf, 0, 0) };
    int n = 0;
    for (int i = 0; i < LEN(bad_rho); i++, n += 6) {
        ck_assert(brdf_lambert(&b, bad_rho[i], &err) == SVET_ERR_RANGE);
        ck_assert(err.msg[0] != '\0');
        ck_assert(brdf_mirror(&b, bad_rho[i], 1, &err) == SVET_ERR_RANGE);
        ck_assert(brdf_phong(&b, bad_rho[i], 10, &err) == SVET_ERR_RANGE);
        ck_assert(brdf_ward(&b, bad_rho[i], REAL_C(0.1), REAL_C(0.1), false,
                            &err) == SVET_ERR_RANGE);
        ck_assert(brdf_specular_transmission(&b, bad_rho[i], REAL_C(1.5),
                                             &err) == SVET_ERR_RANGE);
        ck_assert(brdf_diffuse_transmission(&b, bad_rho[i], &err) ==
                  SVET_ERR_RANGE);
    }
    RADIANCE ok = rad_grey(REAL_C(0.5));
    const real bad_e[] = { -1, nan, inf, BRDF_PHONG_E_MAX * 2 };
    for (int i = 0; i < LEN(bad_e); i++, n++)
        ck_assert(brdf_phong(&b, ok, bad_e[i], &err) == SVET_ERR_RANGE);
    const real bad_alpha[] = { 0, -REAL_C(0.1), nan, inf,
                               BRDF_WARD_ALPHA_MIN / 2 };
    for (int i = 0; i < LEN(bad_alpha); i++, n += 2) {
        ck_assert(brdf_ward(&b, ok, bad_alpha[i], REAL_C(0.1), true, &err) ==
                  SVET_ERR_RANGE);
        ck_assert(brdf_ward(&b, ok, REAL_C(0.1), bad_alpha[i], false, &err) ==
                  SVET_ERR_RANGE);
    }
    const real bad_eta[] = { 0, -1, nan, inf };
    for (int i = 0; i < LEN(bad_eta); i++, n += 2) {
        ck_assert(brdf_specular_transmission(&b, ok, bad_eta[i], &err) ==
                  SVET_ERR_RANGE);
        ck_assert(brdf_mirror(&b, ok, bad_eta[i], &err) == SVET_ERR_RANGE);
    }
    /* a rejected component is black: harmless if used anyway */
    VECTOR3 w = { 0, 0, 1 };
    ck_assert(rad_is_black(brdf_eval(&b, w, w)));
    /* and the limits themselves are accepted */
    ck_assert(brdf_phong(&b, ok, 0, &err) == SVET_OK);
    ck_assert(brdf_phong(&b, ok, BRDF_PHONG_E_MAX, &err) == SVET_OK);
    ck_assert(brdf_ward(&b, ok, BRDF_WARD_ALPHA_MIN, BRDF_WARD_ALPHA_MAX,
                        false, &err) == SVET_OK);
    ck_assert(brdf_lambert(&b, rad_grey(1), &err) == SVET_OK);
    ck_assert(brdf_lambert(&b, rad_grey(0), NULL) == SVET_OK);
    ck_assert(brdf_lambert(&b, rad_grey(-1), NULL) == SVET_ERR_RANGE);
    test_report_cases("constructors_reject_what_is_not_physical", n + 6);
}
END_TEST

/* --- Fresnel's exact reflectance ------------------------------------------ */

/* The unpolarised reflectance in the form of Cook & Torrance 1982, eq. (7),
 * from the thinner side at cos c into index n: with g^2 = n^2 - 1 + c^2,
 * F = (g-c)^2 / (2 (g+c)^2) (1 + ((c(g+c) - 1) / (c(g-c) + 1))^2): a
 * closed form written differently from brdf.c's r_s and r_p, in long
 * double. */
static long double cook_torrance_f(long double c, long double n)
{
    long double g = sqrtl(n * n - 1 + c * c);
    long double a = (g - c) / (g + c), b = (c * (g + c) - 1) / (c * (g - c) + 1);
    return 0.5L * a * a * (1 + b * b);
}

START_TEST(fresnel_exact_matches_its_closed_forms)
{
    const real etas[] = { REAL_C(1.33), REAL_C(1.5), REAL_C(2.4) };
    long n = 0;
    for (int e = 0; e < LEN(etas); e++) {
        long double eta = etas[e];
        /* normal incidence: ((n - 1) / (n + 1))^2 from both sides, both
         * polarisations */
        long double f0 = (eta - 1) / (eta + 1);
        f0 *= f0;
        real rs, rp;
        ck_assert_rel(brdf_fresnel_dielectric(1, etas[e], &rs, &rp), f0,
                      16 * EPS, 0);
        ck_assert_rel(rs, f0, 16 * EPS, 0);
        ck_assert_rel(rp, f0, 16 * EPS, 0);
        ck_assert_rel(brdf_fresnel_dielectric(-1, etas[e], NULL, NULL), f0,
                      16 * EPS, 0);
        /* the whole curve from outside against Cook & Torrance's form */
        for (int i = 1; i <= 100; i++, n++) {
            real c = (real)i / 100;
            ck_assert_rel(brdf_fresnel_dielectric(c, etas[e], NULL, NULL),
                          cook_torrance_f(c, eta), 256 * EPS, 8 * EPS);
        }
        /* Brewster's angle tan theta_B = n: the p component vanishes,
         * the s one is sin^2(theta_i - theta_t) / sin^2(theta_i + theta_t) */
        long double tb = atanl(eta), tt = atanl(1 / eta);
        brdf_fresnel_dielectric((real)cosl(tb), etas[e], &rs, &rp);
        ck_assert_msg((double)rp < 64 * EPS * EPS + 1e-12, "r_p^2 %g",
                      (double)rp);
        long double s_ref = powl(sinl(tb - tt), 2);
        ck_assert_rel(rs, s_ref, 1e4 * EPS, 0);
        /* and from inside at its own Brewster angle, tan = 1/n */
        brdf_fresnel_dielectric(-(real)cosl(tt), etas[e], &rs, &rp);
        ck_assert((double)rp < 1e-6);
        /* total internal reflection beyond the critical angle, sin = 1/n,
         * from inside; just inside it, less than 1 */
        long double cc = sqrtl(1 - 1 / (eta * eta));
        for (int i = 1; i <= 50; i++, n++) {
            real c = (real)(cc * (long double)i / 51);
            ck_assert(brdf_fresnel_dielectric(-c, etas[e], &rs, &rp) == 1);
            ck_assert(rs == 1 && rp == 1);
        }
        ck_assert(brdf_fresnel_dielectric(-(real)(cc + 0.01L), etas[e], NULL,
                                          NULL) < 1);
        n += 6;
    }
    test_report_cases("fresnel_exact_matches_its_closed_forms", n);
}
END_TEST

START_TEST(fresnel_exact_glass_reflects_and_transmits_all)
{
    /* glass of rho_s(0) = F(0), rho_t(0) = 1 - F(0) with the exact curve:
     * rho_s(theta) = F and rho_s(theta) + rho_t(theta) = 1 at every angle
     * from both sides (energy), F under total internal reflection */
    const real eta = REAL_C(1.5);
    real f0 = (eta - 1) / (eta + 1);
    f0 *= f0;
    brdf_t m, t;
    ck_assert_int_eq(brdf_mirror(&m, rad_grey(f0), eta, NULL), SVET_OK);
    ck_assert_int_eq(brdf_specular_transmission(&t, rad_grey(1 - f0), eta,
                                                NULL), SVET_OK);
    m.exact = t.exact = true;
    long n = 0;
    for (int i = -99; i <= 99; i++, n++) {
        if (i == 0)
            continue;
        VECTOR3 wo;
        dir(wo, (real)i / 100, REAL_C(0.3));
        RADIANCE r = brdf_nominal(&m, wo), tr = brdf_nominal(&t, wo);
        ck_assert_rel(r.r + tr.r, 1, 64 * EPS, 0);
        real f = brdf_fresnel_dielectric(wo[Z], eta, NULL, NULL);
        ck_assert_rel(r.r, f, 256 * EPS, 8 * EPS);
    }
    /* the default stays Schlick's: a different number at 60 degrees */
    VECTOR3 wo;
    dir(wo, REAL_C(0.5), 0);
    m.exact = false;
    real schlick = brdf_nominal(&m, wo).r;
    ck_assert_rel(schlick, f0 + (1 - f0) / 32, 16 * EPS, 0);
    m.exact = true;
    ck_assert(fabs((double)(brdf_nominal(&m, wo).r - schlick)) > 1e-3);
    /* a metal mirror (eta = 1) follows the dielectric of its rho_s(0):
     * rho_s(0) at normal incidence, 1 at grazing */
    brdf_t metal;
    ck_assert_int_eq(brdf_mirror(&metal, rad_make(REAL_C(0.9), REAL_C(0.5),
                                                  0), 1, NULL), SVET_OK);
    metal.exact = true;
    dir(wo, 1, 0);
    RADIANCE r0 = brdf_nominal(&metal, wo);
    ck_assert_rel(r0.r, 0.9, 16 * EPS, 0);
    ck_assert_rel(r0.g, 0.5, 16 * EPS, 0);
    ck_assert(r0.b == 0);
    dir(wo, REAL_C(1e-6), 0);
    RADIANCE r90 = brdf_nominal(&metal, wo);
    ck_assert((double)r90.r > 0.999 && (double)r90.g > 0.99 && r90.b == 0);
    test_report_cases("fresnel_exact_glass_reflects_and_transmits_all", n + 6);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("brdf (" REAL_NAME ")");
    TCase *t = tcase_create("core");
    tcase_set_timeout(t, 600);
    tcase_add_test(t, constructors_reject_what_is_not_physical);
    tcase_add_test(t, lobes_are_reciprocal);
    tcase_add_test(t, specular_transmission_weight_is_the_same_both_ways);
    tcase_add_test(t, sample_weight_and_pdf_agree_with_evaluation);
    tcase_add_test(t, lambert_albedo_is_rho_d);
    tcase_add_test(t, diffuse_transmission_albedo_is_rho);
    tcase_add_test(t, phong_albedo_is_rho_s_at_normal_incidence);
    tcase_add_test(t, phong_albedo_never_exceeds_rho_s);
    tcase_add_test(t, bounded_ward_albedo_never_exceeds_rho_s);
    tcase_add_test(t, book_ward_albedo_is_rho_cos_for_small_alpha);
    tcase_add_test(t, book_ward_albedo_exceeds_one_at_grazing);
    tcase_add_test(t, mirror_albedo_is_the_schlick_value);
    tcase_add_test(t, specular_transmission_albedo_is_the_books_rho_t);
    tcase_add_test(t, index_match_transmits_straight_through);
    tcase_add_test(t, total_internal_reflection_starts_at_the_critical_angle);
    tcase_add_test(t, no_nan_or_inf_over_a_dense_sweep);
    tcase_add_test(t, each_lobe_samples_wi_with_its_pdf);
    tcase_add_test(t, a_wrong_pdf_fails_the_chi2_test);
    tcase_add_test(t, fresnel_exact_matches_its_closed_forms);
    tcase_add_test(t, fresnel_exact_glass_reflects_and_transmits_all);
    suite_add_tcase(s, t);
    return s;
}
