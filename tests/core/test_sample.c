/*
 * test_sample.c - the samplers of ch. 4 (src/core/sample.c) and the harness that
 * tests them (tests/chi2.c): chi-square fits of every direction sampler to
 * its pdf, KS and chi-square tests of the point samplers, the harness
 * rejecting wrong pdfs, pdfs integrating to 1, no NaN/Inf over a dense
 * sweep of u, jittered strata, the estimators, tests/vectors/sample_*.csv.
 */
#include "testutil.h"
#include "chi2.h"
#include "core/frame.h"
#include "core/sample.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Every hypothesis test of this suite (chi-square and KS) is held to the
 * Sidak-corrected level 1 - (1 - 0.01)^(1/N_STAT_TESTS), so that the whole
 * suite wrongly fails a correct sampler with probability 0.01 at most
 * (for the fixed seeds below it either passes or fails every time). Keep
 * these counts equal to the number of calls of expect_fit / expect_ks /
 * expect_counts_fit that expect a pass. */
#define N_CHI2_DIRECTIONS 22 /* expect_fit in direction_samplers_fit_... */
#define N_CHI2_POINTS 4      /* expect_counts_fit: disk, triangle, ... */
#define N_KS 12              /* expect_ks: 6 lobes, 6 point marginals */
#ifdef SVET_DOUBLE
#define N_DOUBLE_ONLY 1      /* Ward alpha = 1e-4 by chi-square */
#else
#define N_DOUBLE_ONLY 0
#endif
#define N_STAT_TESTS (N_CHI2_DIRECTIONS + N_CHI2_POINTS + N_KS + N_DOUBLE_ONLY)
#define ALPHA 0.01

#define PI_D 3.14159265358979323846

/* --- direction samplers behind one interface ----------------------------- */

typedef enum {
    D_SPHERE, D_HEMISPHERE, D_COSINE, D_CONE, D_PHONG, D_WARD, D_SPHERE_SA
} dkind;

typedef struct {
    dkind kind;
    real a, b;           /* cos_theta_max | e | alpha_x, alpha_y */
    VECTOR3 x, c;        /* D_SPHERE_SA: viewpoint, sphere centre ... */
    real r;              /* ... and radius */
} dspec;

/* A sampler and the pdf it is checked against (the same spec, or a wrong
 * one on purpose). Sphere directions are tested in a frame whose +z points
 * from x to the centre, so the cone is a cap about +z. */
typedef struct {
    dspec s, p;
    VECTOR3 fu, fv, fn;
} dpair;

static dspec spec(dkind kind, double a, double b)
{
    dspec d;
    memset(&d, 0, sizeof d);
    d.kind = kind;
    d.a = (real)a;
    d.b = (real)b;
    return d;
}

/* 1 - cos(theta) of the cone of a sphere seen from x: s^2 / (1 + cos). */
static double sphere_cone_height(const dspec *d)
{
    double dist = (double)vec_distance(d->x, d->c), s = (double)d->r / dist;
    return s * s / (1 + sqrt(fmax(0.0, 1 - s * s)));
}

static dspec sphere_spec(double dist, double r, double theta, double phi)
{
    dspec d = spec(D_SPHERE_SA, 0, 0);
    vec_set(d.c, (real)0.25, (real)-0.5, (real)2);
    vec_set(d.x, d.c[X] + (real)(dist * sin(theta) * cos(phi)),
            d.c[Y] + (real)(dist * sin(theta) * sin(phi)),
            d.c[Z] + (real)(dist * cos(theta)));
    d.r = (real)r;
    return d;
}

static void direction_sample(const dspec *d, const real u[2], VECTOR3 w)
{
    switch (d->kind) {
    case D_SPHERE: sample_uniform_sphere(w, u); break;
    case D_HEMISPHERE: sample_uniform_hemisphere(w, u); break;
    case D_COSINE: sample_cosine_hemisphere(w, u); break;
    case D_CONE: sample_uniform_cone(w, u, d->a); break;
    case D_PHONG: sample_phong_lobe(w, u, d->a); break;
    case D_WARD: sample_ward_half(w, u, d->a, d->b); break;
    case D_SPHERE_SA: (void)sample_sphere_solid_angle(w, d->x, d->c, d->r, u);
        break;
    }
}

static double direction_pdf(const dspec *d, const VECTOR3 w)
{
    switch (d->kind) {
    case D_SPHERE: return (double)sample_uniform_sphere_pdf();
    case D_HEMISPHERE:
        return w[Z] >= 0 ? (double)sample_uniform_hemisphere_pdf() : 0;
    case D_COSINE: return (double)sample_cosine_hemisphere_pdf(w[Z]);
    case D_CONE:
        return w[Z] >= d->a ? (double)sample_uniform_cone_pdf(d->a) : 0;
    case D_PHONG: return (double)sample_phong_lobe_pdf(w[Z], d->a);
    case D_WARD: return (double)sample_ward_half_pdf(w, d->a, d->b);
    case D_SPHERE_SA:
        return (double)sample_sphere_solid_angle_pdf(w, d->x, d->c, d->r);
    }
    return 0;
}

static bool pair_sample(void *ctx, const real u[2], VECTOR3 w)
{
    dpair *p = ctx;
    direction_sample(&p->s, u, w);
    if (p->s.kind == D_SPHERE_SA)
        frame_to_local(w, w, p->fu, p->fv, p->fn);
    return true;
}

static double pair_pdf(void *ctx, const VECTOR3 w)
{
    dpair *p = ctx;
    if (p->p.kind == D_SPHERE_SA) {
        VECTOR3 ww;
        frame_to_world(ww, w, p->fu, p->fv, p->fn);
        return direction_pdf(&p->p, ww);
    }
    return direction_pdf(&p->p, w);
}

static dpair make_pair(dspec s, dspec p)
{
    dpair q;
    memset(&q, 0, sizeof q);
    q.s = s;
    q.p = p;
    if (s.kind == D_SPHERE_SA) {
        vec_sub(q.fn, s.c, s.x);
        if (vec_normalize(q.fn, q.fn) == 0) /* x at the centre */
            vec_set(q.fn, 0, 0, 1);
        frame_from_normal(q.fu, q.fv, q.fn);
    }
    return q;
}

/* Run the chi-square test of sampler s against pdf p with theta x phi bins
 * over the cap of height `cap` (0: the whole sphere). */
static chi2_result run_fit(const char *name, dspec s, dspec p, double cap,
                           int theta_bins, int phi_bins, uint64_t seed)
{
    dpair q = make_pair(s, p);
    chi2_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.theta_bins = theta_bins;
    cfg.phi_bins = phi_bins;
    cfg.significance = ALPHA;
    cfg.tests = N_STAT_TESTS;
    cfg.seed = seed;
    cfg.cap_height = cap;
    chi2_result r = chi2_test(&cfg, pair_sample, pair_pdf, &q);
    chi2_config_defaults(&cfg);
    printf("  %s: %s; pdf integral %.7f\n", name, r.message, r.pdf_integral);
    test_report_cases(name, cfg.samples);
    return r;
}

static void expect_fit(const char *name, dspec s, double cap, int theta_bins,
                       int phi_bins, uint64_t seed)
{
    chi2_result r = run_fit(name, s, s, cap, theta_bins, phi_bins, seed);
    ck_assert_msg(r.passed, "%s: %s", name, r.message);
    /* A sampler that never fails has a pdf of total mass 1; the bound is
     * the quadrature's tolerance (1e-7 absolute + 1e-4 relative in float,
     * chi2.c) with room for the float pdf's rounding. */
    ck_assert_msg(fabs(r.pdf_integral - 1) < 1e-3, "%s: pdf integral %.9g",
                  name, r.pdf_integral);
}

static void expect_reject(const char *name, dspec s, dspec p, double cap,
                          uint64_t seed)
{
    chi2_result r = run_fit(name, s, p, cap, 10, 20, seed);
    ck_assert_msg(!r.passed, "%s: a wrong pdf was accepted: %s", name,
                  r.message);
}

/* --- the harness itself ---------------------------------------------------- */

START_TEST(gamma_q_matches_closed_forms_and_tables)
{
    /* Q(1, x) = exp(-x); Q(1/2, x) = erfc(sqrt x); for integer n,
     * Q(n, x) = exp(-x) sum_{k<n} x^k / k! (Abramowitz & Stegun 6.5.13). */
    long n = 0;
    for (double x = 0.0; x < 60; x += 0.37, n += 3) {
        ck_assert_rel(chi2_gamma_q(1, x), exp(-x), 1e-13, 1e-300);
        ck_assert_rel(chi2_gamma_q(0.5, x), erfc(sqrt(x)), 1e-12, 1e-300);
        long double term = 1, sum = 0;
        for (int k = 0; k < 30; k++) {
            sum += term;
            term *= (long double)x / (k + 1);
        }
        ck_assert_rel(chi2_gamma_q(30, x), (double)(expl(-(long double)x) * sum),
                      1e-11, 1e-300);
    }
    /* Upper 1% points of chi-square (NIST/SEMATECH e-Handbook, table
     * 1.3.6.7.4): P(chi2_10 >= 23.209) = P(chi2_100 >= 135.807) = 0.01. */
    ck_assert_near(chi2_gamma_q(5, 23.209 / 2), 0.01, 2e-6);
    ck_assert_near(chi2_gamma_q(50, 135.807 / 2), 0.01, 2e-6);
    ck_assert(chi2_gamma_q(3, 0) == 1);
    ck_assert(isnan(chi2_gamma_q(0, 1)) && isnan(chi2_gamma_q(1, -1)));
    ck_assert(chi2_gamma_q(2, (double)INFINITY) == 0);
    test_report_cases("gamma_q_matches_closed_forms_and_tables", n + 6);
}
END_TEST

START_TEST(sidak_and_ks_match_published_values)
{
    ck_assert_rel(chi2_sidak(0.01, 1), 0.01, 1e-15, 0);
    /* 1 - 0.99^(1/40) = 1 - exp(ln(0.99)/40) = 2.512268e-4 */
    ck_assert_rel(chi2_sidak(0.01, 40), 2.512268e-4, 1e-6, 0);
    /* The asymptotic Kolmogorov distribution: Q_KS(1.3581) = 0.05,
     * Q_KS(1.6276) = 0.01 (Smirnov's table; Massey 1951). With n huge the
     * small-sample correction vanishes. */
    long big = 100000000L;
    ck_assert_near(chi2_ks_pvalue(1.3581 / sqrt((double)big), big), 0.05, 2e-4);
    ck_assert_near(chi2_ks_pvalue(1.6276 / sqrt((double)big), big), 0.01, 1e-4);
    ck_assert_near(chi2_ks_pvalue(0, 10), 1, 1e-12);
}
END_TEST

START_TEST(counts_are_pooled_as_mitsuba_does)
{
    /* Sorted expectations 1, 2, 3 pool into one cell (6 >= 5), then 10, 20:
     * chi2 = (7-6)^2/6 + (12-10)^2/10 + (16-20)^2/20 on 3 - 1 = 2 dof, and
     * Q(1, chi2/2) = exp(-chi2/2). */
    double obs[5] = { 12, 1, 16, 2, 4 }, expc[5] = { 10, 2, 20, 1, 3 };
    chi2_config cfg = { 0 };
    chi2_result r = chi2_from_counts(obs, expc, 5, &cfg);
    double chsq = 1.0 / 6 + 0.4 + 0.8;
    ck_assert_rel(r.statistic, chsq, 1e-14, 0);
    ck_assert_int_eq(r.dof, 2);
    ck_assert_int_eq(r.pooled_in, 3);
    ck_assert_int_eq(r.pooled_out, 1);
    ck_assert_rel(r.p_value, exp(-chsq / 2), 1e-13, 0);
    ck_assert(r.passed);
    /* Samples in a cell the pdf says is empty: rejected outright. */
    double obs2[3] = { 50, 50, 1 }, exp2[3] = { 50, 51, 0 };
    r = chi2_from_counts(obs2, exp2, 3, &cfg);
    ck_assert_msg(!r.passed, "%s", r.message);
    /* Too few cells left after pooling: rejected. */
    double obs3[2] = { 1, 2 }, exp3[2] = { 1.5, 1.5 };
    r = chi2_from_counts(obs3, exp3, 2, &cfg);
    ck_assert(!r.passed);
}
END_TEST

static bool nan_sampler(void *ctx, const real u[2], VECTOR3 w)
{
    (void)ctx;
    sample_uniform_sphere(w, u);
    if (u[0] < REAL_C(0.001))
        w[X] = (real)NAN;
    return true;
}

static double sphere_pdf(void *ctx, const VECTOR3 w)
{
    (void)ctx;
    (void)w;
    return (double)sample_uniform_sphere_pdf();
}

START_TEST(harness_rejects_wrong_pdfs)
{
    /* Each of these must fail: the harness can tell. Cosine-distributed
     * samples against the uniform hemisphere's pdf; a Phong lobe of
     * exponent 10 against the pdf of 11 (a 5% change in width); uniform
     * sphere samples against the hemisphere's pdf (samples where the pdf
     * is 0); Ward alpha 0.1 against 0.11; a cone of cos 0.5 against
     * cos 0.45; a cosine sampler checked with a pdf missing 1/pi (the
     * integral exceeds 1); a sampler that emits NaN. */
    expect_reject("cosine_against_uniform", spec(D_COSINE, 0, 0),
                  spec(D_HEMISPHERE, 0, 0), 0, 11);
    expect_reject("phong_10_against_11", spec(D_PHONG, 10, 0),
                  spec(D_PHONG, 11, 0), 0, 12);
    expect_reject("sphere_against_hemisphere", spec(D_SPHERE, 0, 0),
                  spec(D_HEMISPHERE, 0, 0), 0, 13);
    expect_reject("ward_0.1_against_0.11", spec(D_WARD, 0.1, 0.1),
                  spec(D_WARD, 0.11, 0.11), 0.2, 14);
    expect_reject("cone_0.5_against_0.45", spec(D_CONE, 0.5, 0),
                  spec(D_CONE, 0.45, 0), 0, 15);
    expect_reject("ward_aniso_swapped_axes", spec(D_WARD, 0.3, 0.1),
                  spec(D_WARD, 0.1, 0.3), 0, 16);
    chi2_config cfg = { 0 };
    cfg.seed = 17;
    chi2_result r = chi2_test(&cfg, nan_sampler, sphere_pdf, NULL);
    printf("  nan_sampler: %s\n", r.message);
    ck_assert(!r.passed && r.invalid > 0);
    test_report_cases("harness_rejects_wrong_pdfs", 7 * 200000L);
}
END_TEST

/* --- chi-square fits of the direction samplers ----------------------------- */

START_TEST(direction_samplers_fit_their_pdfs)
{
    /* 22 chi-square tests (N_CHI2_DIRECTIONS). Bins: 10 x 20 in
     * (cos theta, phi), 1000 expected samples per bin, as pbrt-v3's
     * bsdfs.cpp. Lobes about +z are zoomed with the cap (see chi2.h): for
     * Phong, mass 1 - (1 - cap)^(e+1) ~ 1 - e^-10 lies in cap = 10/e; for
     * Ward, tan^2 < 20 alpha^2 holds all but e^-20. */
    expect_fit("uniform_sphere", spec(D_SPHERE, 0, 0), 0, 10, 20, 101);
    expect_fit("uniform_hemisphere", spec(D_HEMISPHERE, 0, 0), 0, 10, 20, 102);
    expect_fit("cosine_hemisphere", spec(D_COSINE, 0, 0), 0, 10, 20, 103);
    /* Cones: the bins cover exactly the cone (cap = 1 - cos_theta_max), so
     * the pdf's step lies on a bin edge and the cubature resolves it. */
    static const double cones[4] = { 0.9, 0.0, -0.7, 0.9999 };
    for (int i = 0; i < 4; i++) {
        char name[64];
        snprintf(name, sizeof name, "uniform_cone_cos_%g", cones[i]);
        expect_fit(name, spec(D_CONE, cones[i], 0), 1 - (double)(real)cones[i],
                   10, 20, 110 + (uint64_t)i);
    }
    static const double es[4] = { 0, 1, 10, 1000 };
    for (int i = 0; i < 4; i++) {
        char name[64];
        snprintf(name, sizeof name, "phong_lobe_e_%g", es[i]);
        expect_fit(name, spec(D_PHONG, es[i], 0), es[i] > 10 ? 10 / es[i] : 0,
                   10, 20, 120 + (uint64_t)i);
    }
    static const double alphas[3] = { 1, 0.1, 0.01 };
    for (int i = 0; i < 3; i++) {
        char name[64];
        snprintf(name, sizeof name, "ward_half_alpha_%g", alphas[i]);
        double cap = fmin(2.0, 20 * alphas[i] * alphas[i]);
        expect_fit(name, spec(D_WARD, alphas[i], alphas[i]), cap >= 2 ? 0 : cap,
                   10, 20, 130 + (uint64_t)i);
    }
    /* Anisotropic, alpha_x/alpha_y = 100 and 1/100: a thin ridge along one
     * axis; 40 phi bins to see it. */
    expect_fit("ward_half_alpha_1_0.01", spec(D_WARD, 1, 0.01), 0, 10, 40, 140);
    expect_fit("ward_half_alpha_0.001_0.1", spec(D_WARD, 0.001, 0.1), 0.2, 10,
               40, 141);
    expect_fit("ward_half_alpha_0.1_0.3", spec(D_WARD, 0.1, 0.3), 1.0, 10, 20,
               142);
    /* Sphere by solid angle, from 1.5, 10 and 100 radii (the cone is the
     * cap about the axis x -> c), and from inside it (whole sphere). Farther
     * cones are too narrow for bins in cos(theta) in float (1000 radii:
     * 1 - cos < 5e-7, 8 floats); narrow_lobes_concentrate_where_expected
     * tests 1000 radii by KS. */
    static const double dists[3] = { 1.5, 10, 100 };
    for (int i = 0; i < 3; i++) {
        char name[64];
        snprintf(name, sizeof name, "sphere_solid_angle_from_%g_radii",
                 dists[i]);
        dspec d = sphere_spec(dists[i] * 0.75, 0.75, 1.1, 2.3);
        expect_fit(name, d, sphere_cone_height(&d), 10, 20, 150 + (uint64_t)i);
    }
    expect_fit("sphere_solid_angle_from_inside",
               sphere_spec(0.4, 1, 0.7, -0.4), 0, 10, 20, 155);
    expect_fit("sphere_solid_angle_from_the_centre",
               sphere_spec(0, 1, 0, 0), 0, 10, 20, 156);
}
END_TEST

#ifdef SVET_DOUBLE
START_TEST(ward_half_alpha_1e_4_fits_in_double)
{
    /* In float, cos(delta) near 1 is spaced 6e-8 apart: the cap of height
     * 2e-7 that holds this lobe has 3 floats in it, too few for bins in
     * cos(theta). The float build tests this lobe by KS on tan^2(delta). */
    expect_fit("ward_half_alpha_1e-4", spec(D_WARD, 1e-4, 1e-4), 2e-7, 10, 20,
               160);
}
END_TEST
#endif

/* --- KS tests of 1D marginals ---------------------------------------------- */

typedef struct {
    int kind;
    double p; /* parameter */
} cdf_ctx;

static double cdf(void *ctx, double x)
{
    const cdf_ctx *c = ctx;
    switch (c->kind) {
    case 0: /* uniform on [0, 1] */
        return fmin(1.0, fmax(0.0, x));
    case 1: /* exponential(1) */
        return x <= 0 ? 0 : -expm1(-x);
    case 2: /* sin^2 of a Phong lobe of exponent p:
             * P(sin^2 <= s) = 1 - (1 - s)^((p + 1)/2) */
        return x <= 0 ? 0 : x >= 1 ? 1 : -expm1((c->p + 1) / 2 * log1p(-x));
    case 3: /* 1 - b of a uniform triangle's barycentric b: 1 - (1 - x)^2 */
        return x <= 0 ? 0 : x >= 1 ? 1 : 1 - (1 - x) * (1 - x);
    }
    return 0;
}

static void expect_ks(const char *name, double *x, long n, cdf_ctx c)
{
    double d = chi2_ks_statistic(x, n, cdf, &c);
    double p = chi2_ks_pvalue(d, n);
    double thr = chi2_sidak(ALPHA, N_STAT_TESTS);
    printf("  %s: KS D = %.5g, p = %.4g (threshold %.3g)\n", name, d, p, thr);
    test_report_cases(name, n);
    ck_assert_msg(p >= thr, "%s: KS D = %g, p = %g < %g", name, d, p, thr);
}

START_TEST(narrow_lobes_concentrate_where_expected)
{
    /* 6 KS tests. For lobes too narrow for cos(theta) bins in float:
     * Phong e = 1e3, 1e5 by sin^2(alpha) = x^2 + y^2 (accurate in float,
     * unlike 1 - z); Ward by tan^2(delta)(cos^2/ax^2 + sin^2/ay^2) =
     * ((hx/ax)^2 + (hy/ay)^2)/hz^2, which is exponential(1) (Walter 2005). */
    enum { N = 20000 };
    double *x = malloc(N * sizeof *x);
    pcg32_t g;
    static const double es[2] = { 1e3, 1e5 };
    for (int i = 0; i < 2; i++) {
        pcg32_seed(&g, 200 + (uint64_t)i, 1);
        for (int k = 0; k < N; k++) {
            real u[2] = { pcg32_real(&g), pcg32_real(&g) };
            VECTOR3 w;
            sample_phong_lobe(w, u, (real)es[i]);
            x[k] = (double)w[X] * (double)w[X] + (double)w[Y] * (double)w[Y];
        }
        char name[64];
        snprintf(name, sizeof name, "phong_e_%g_sin2_ks", es[i]);
        expect_ks(name, x, N, (cdf_ctx){ 2, es[i] });
    }
    static const double ward[3][2] = { { 1e-4, 1e-4 }, { 1e-2, 1e-4 },
                                       { 1e-4, 1e-2 } };
    for (int i = 0; i < 3; i++) {
        pcg32_seed(&g, 210 + (uint64_t)i, 1);
        for (int k = 0; k < N; k++) {
            real u[2] = { pcg32_real(&g), pcg32_real(&g) };
            VECTOR3 h;
            sample_ward_half(h, u, (real)ward[i][0], (real)ward[i][1]);
            double qx = (double)h[X] / ward[i][0], qy = (double)h[Y] / ward[i][1];
            x[k] = (qx * qx + qy * qy) / ((double)h[Z] * (double)h[Z]);
        }
        char name[64];
        snprintf(name, sizeof name, "ward_%g_%g_exponent_ks", ward[i][0],
                 ward[i][1]);
        expect_ks(name, x, N, (cdf_ctx){ 1, 0 });
    }
    /* The cone toward a sphere 1000 radii away: 1 - cos(theta) about the
     * axis is uniform on [0, h], computed as |w - axis|^2 / 2 with the axis
     * in double. */
    dspec sd = sphere_spec(1000, 1, 2.2, -0.3);
    double axis[3], dist = 0, h = sphere_cone_height(&sd);
    for (int k = 0; k < 3; k++) {
        axis[k] = (double)sd.c[k] - (double)sd.x[k];
        dist += axis[k] * axis[k];
    }
    dist = sqrt(dist);
    pcg32_seed(&g, 220, 1);
    for (int k = 0; k < N; k++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        VECTOR3 w;
        (void)sample_sphere_solid_angle(w, sd.x, sd.c, sd.r, u);
        double d2 = 0;
        for (int c = 0; c < 3; c++) {
            double dc = (double)w[c] - axis[c] / dist;
            d2 += dc * dc;
        }
        x[k] = d2 / 2 / h;
    }
    expect_ks("sphere_solid_angle_1000_radii_ks", x, N, (cdf_ctx){ 0, 0 });
    free(x);
}
END_TEST

/* --- point samplers --------------------------------------------------------- */

/* Chi-square of an nb x nb histogram of two coordinates that are
 * independent and uniform on [0, 1) for a correct sampler. */
static void expect_counts_fit(const char *name, const double *obs, int nb,
                              long n)
{
    double *expc = malloc((size_t)(nb * nb) * sizeof *expc);
    for (int i = 0; i < nb * nb; i++)
        expc[i] = (double)n / (nb * nb);
    chi2_config cfg = { 0 };
    cfg.significance = ALPHA;
    cfg.tests = N_STAT_TESTS;
    chi2_result r = chi2_from_counts(obs, expc, nb * nb, &cfg);
    free(expc);
    printf("  %s: %s\n", name, r.message);
    test_report_cases(name, n);
    ck_assert_msg(r.passed, "%s: %s", name, r.message);
}

static int bin_of(double t, int nb)
{
    int i = (int)floor(t * nb);
    return i < 0 ? 0 : i >= nb ? nb - 1 : i;
}

START_TEST(point_samplers_have_their_distributions)
{
    /* 4 chi-square (N_CHI2_POINTS) and 7 KS tests. Each maps the sample to
     * two coordinates that are independent uniforms exactly when the
     * sample is uniform:
     *   disk:          r^2 and phi / 2 pi (area of a disk of radius r is
     *                  proportional to r^2);
     *   triangle:      (1 - b0)^2 and b1 / (1 - b0) (the area beyond the
     *                  line b0 = t is (1 - t)^2 of the whole; on that line
     *                  the point is uniform);
     *   parallelogram: its two affine coordinates, solved back from p in
     *                  long double;
     *   sphere area:   (z + 1)/2 and phi / 2 pi (Archimedes). */
    enum { N = 100000, NB = 10 };
    double *obs = calloc(NB * NB, sizeof *obs);
    double *m[2] = { malloc(N * sizeof(double)), malloc(N * sizeof(double)) };
    double *b2 = malloc(N * sizeof(double));
    pcg32_t g;

    pcg32_seed(&g, 300, 1);
    for (int k = 0; k < N; k++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) }, d[2];
        sample_concentric_disk(d, u);
        double r2 = (double)d[0] * (double)d[0] + (double)d[1] * (double)d[1];
        double phi = atan2((double)d[1], (double)d[0]);
        phi = phi < 0 ? phi + 2 * PI_D : phi;
        ck_assert(r2 <= 1 + 4 * (double)REAL_EPSILON);
        obs[bin_of(r2, NB) * NB + bin_of(phi / (2 * PI_D), NB)] += 1;
        m[0][k] = r2;
    }
    expect_counts_fit("concentric_disk_r2_phi", obs, NB, N);
    expect_ks("concentric_disk_r2_ks", m[0], N, (cdf_ctx){ 0, 0 });

    memset(obs, 0, NB * NB * sizeof *obs);
    pcg32_seed(&g, 301, 1);
    for (int k = 0; k < N; k++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) }, b[2];
        sample_triangle(b, u);
        ck_assert(b[0] >= 0 && b[1] >= 0 && b[0] + b[1] <= 1);
        double s = 1 - (double)b[0];
        obs[bin_of(s * s, NB) * NB + bin_of(s > 0 ? (double)b[1] / s : 0, NB)] += 1;
        m[0][k] = (double)b[0];
        m[1][k] = (double)b[1];
        b2[k] = 1 - (double)b[0] - (double)b[1];
    }
    expect_counts_fit("triangle_area_and_edge_coordinates", obs, NB, N);
    /* Each barycentric coordinate has the marginal 1 - (1 - x)^2. */
    expect_ks("triangle_b0_ks", m[0], N, (cdf_ctx){ 3, 0 });
    expect_ks("triangle_b1_ks", m[1], N, (cdf_ctx){ 3, 0 });
    expect_ks("triangle_b2_ks", b2, N, (cdf_ctx){ 3, 0 });

    memset(obs, 0, NB * NB * sizeof *obs);
    pcg32_seed(&g, 302, 1);
    VECTOR3 p0 = { 1, -2, 0.5 }, e1 = { 3, 0.5, -1 }, e2 = { -0.7, 2, 1.5 };
    /* Gram matrix of (e1, e2) for the least-squares solve of
     * p - p0 = s e1 + t e2 (exact for points of the plane). */
    long double g11 = 0, g12 = 0, g22 = 0;
    for (int c = 0; c < 3; c++) {
        long double a = (long double)e1[c], b = (long double)e2[c];
        g11 += a * a;
        g12 += a * b;
        g22 += b * b;
    }
    long double det = g11 * g22 - g12 * g12;
    for (int k = 0; k < N; k++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        VECTOR3 p;
        sample_parallelogram(p, p0, e1, e2, u);
        long double r1 = 0, r2 = 0;
        for (int c = 0; c < 3; c++) {
            long double dp = (long double)p[c] - (long double)p0[c];
            r1 += dp * (long double)e1[c];
            r2 += dp * (long double)e2[c];
        }
        double s = (double)((g22 * r1 - g12 * r2) / det);
        double t = (double)((g11 * r2 - g12 * r1) / det);
        obs[bin_of(s, NB) * NB + bin_of(t, NB)] += 1;
        m[0][k] = s;
    }
    expect_counts_fit("parallelogram_affine_coordinates", obs, NB, N);
    expect_ks("parallelogram_s_ks", m[0], N, (cdf_ctx){ 0, 0 });

    memset(obs, 0, NB * NB * sizeof *obs);
    pcg32_seed(&g, 303, 1);
    VECTOR3 c = { 10, -3, 0.25 };
    real rad = REAL_C(2.5);
    for (int k = 0; k < N; k++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        VECTOR3 p, n, q;
        sample_sphere_area(p, n, c, rad, u);
        vec_sub(q, p, c);
        ck_assert_near(vec_length(q), rad, 32 * REAL_EPSILON * 10);
        ck_assert_near(vec_length(n), 1, 4 * REAL_EPSILON);
        double z = (double)n[Z], phi = atan2((double)n[Y], (double)n[X]);
        phi = phi < 0 ? phi + 2 * PI_D : phi;
        obs[bin_of((z + 1) / 2, NB) * NB + bin_of(phi / (2 * PI_D), NB)] += 1;
        m[0][k] = (z + 1) / 2;
    }
    expect_counts_fit("sphere_area_height_and_azimuth", obs, NB, N);
    expect_ks("sphere_area_height_ks", m[0], N, (cdf_ctx){ 0, 0 });
    free(obs);
    free(m[0]);
    free(m[1]);
    free(b2);
}
END_TEST

/* --- pdfs integrate to 1 --------------------------------------------------- */

static double spec_pdf(void *ctx, const VECTOR3 w)
{
    return pair_pdf(ctx, w);
}

START_TEST(every_pdf_integrates_to_one)
{
    /* Over the sphere by the adaptive cubature of chi2.c (bands shrinking
     * toward the poles and the cap edge). Tolerance 1e-5: the cubature's
     * own tolerance is 1e-7 absolute + 1e-4 (float) / 1e-7 (double)
     * relative per cell, which in float leaves room for the pdf's rounding
     * at a direction rounded to float (relative e * 6e-8 for Phong); the
     * narrowest lobes (Phong 1e5, Ward 1e-4) get 1e-3 in float. */
    struct {
        dspec s;
        double cap, tol_float;
    } cases[] = {
        { spec(D_SPHERE, 0, 0), 0, 1e-5 },
        { spec(D_HEMISPHERE, 0, 0), 0, 1e-5 },
        { spec(D_COSINE, 0, 0), 0, 1e-5 },
        { spec(D_CONE, 0.5, 0), 0.5, 1e-5 },
        { spec(D_CONE, -0.99, 0), 1.99, 1e-5 },
        /* The cubature's nodes just outside the cone round, as float
         * directions, onto its edge: in float a step of height 1/(2 pi h)
         * gains a band ~ulp(1)/2 wide, 2 pi 3e-8 / (2 pi h) = 3e-5 here. */
        { spec(D_CONE, 1 - 1.0 / 1024, 0), 1.0 / 1024, 1e-4 },
        { spec(D_PHONG, 0, 0), 0, 1e-5 },
        { spec(D_PHONG, 1, 0), 0, 1e-5 },
        { spec(D_PHONG, 10, 0), 0, 1e-5 },
        { spec(D_PHONG, 1e3, 0), 0, 1e-4 },
        { spec(D_PHONG, 1e5, 0), 0, 1e-3 },
        { spec(D_WARD, 1, 1), 0, 1e-5 },
        { spec(D_WARD, 0.01, 0.01), 0, 1e-5 },
        { spec(D_WARD, 1e-4, 1e-4), 0, 1e-3 },
        { spec(D_WARD, 1, 0.01), 0, 1e-4 },
        { spec(D_WARD, 0.01, 1e-4), 0, 1e-3 },
        { sphere_spec(1.5, 1, 0.3, 0.2), -1, 1e-5 },
        /* pdf() accepts directions up to 4 eps sqrt(2h) outside the cone
         * (src/core/sample.c: the rounding of float directions), which at 1000
         * radii (h = 5e-7) widens it by ~1e-3 of its solid angle. */
        { sphere_spec(1000, 1, 2.0, 1.0), -1, 2e-3 },
        { sphere_spec(0.5, 1, 2.0, 1.0), 0, 1e-5 },
    };
    int n = (int)(sizeof cases / sizeof cases[0]);
    for (int i = 0; i < n; i++) {
        dpair q = make_pair(cases[i].s, cases[i].s);
        double cap = cases[i].cap < 0 ? sphere_cone_height(&cases[i].s)
                                      : cases[i].cap;
#ifdef SVET_DOUBLE
        double tol = 1e-5;
#else
        double tol = cases[i].tol_float;
#endif
        double err, integral = chi2_pdf_integral(spec_pdf, &q, cap, &err);
        ck_assert_msg(fabs(integral - 1) <= tol,
                      "case %d (kind %d, %g, %g): integral %.9g (err %.2g)", i,
                      (int)cases[i].s.kind, (double)cases[i].s.a,
                      (double)cases[i].s.b, integral, err);
    }
    /* And chi2.h's assertion on one of them. */
    dpair q = make_pair(spec(D_COSINE, 0, 0), spec(D_COSINE, 0, 0));
    chi2_assert_pdf_normalised(spec_pdf, &q, 0, 1e-6);
    test_report_cases("every_pdf_integrates_to_one", n + 1);
}
END_TEST

/* --- robustness: a dense sweep of u ---------------------------------------- */

/* u values: a uniform grid plus the extremes the contract names and their
 * neighbours. */
static int sweep_values(real *v)
{
    int n = 0;
    for (int i = 0; i < 64; i++)
        v[n++] = (real)i / 64;
    real one_below = nextafter(REAL_C(1.0), REAL_C(0.0));
    v[n++] = one_below;
    v[n++] = nextafter(one_below, REAL_C(0.0));
    v[n++] = REAL_C(1.0) - REAL_C(0x1p-24); /* largest pcg32_real in float */
    v[n++] = REAL_MIN;
    v[n++] = REAL_C(0x1p-24);
    v[n++] = REAL_C(0x1p-32);
    v[n++] = REAL_C(1e-30);
    v[n++] = nextafter(REAL_C(0.5), REAL_C(0.0));
    v[n++] = nextafter(REAL_C(0.5), REAL_C(1.0));
    v[n++] = nextafter(REAL_C(0.25), REAL_C(0.0));
    v[n++] = nextafter(REAL_C(0.75), REAL_C(1.0));
    return n;
}

static bool finite2(const real a[2])
{
    return isfinite(a[0]) && isfinite(a[1]);
}

START_TEST(no_sampler_returns_nan_or_inf_over_a_dense_sweep)
{
    real v[96];
    int nv = sweep_values(v);
    /* Every direction is unit: its length is within a few roundings of 1
     * (sqrt and the products of sin/cos: 16 eps). Every direction drawn
     * has a positive finite pdf, and the pdf the sampler returns is the
     * pdf function's. */
    const real unit_tol = 16 * REAL_EPSILON;
    dspec dirs[] = {
        spec(D_SPHERE, 0, 0), spec(D_HEMISPHERE, 0, 0), spec(D_COSINE, 0, 0),
        spec(D_CONE, -1, 0), spec(D_CONE, 0, 0), spec(D_CONE, 0.5, 0),
        spec(D_CONE, 1 - 1e-7, 0), spec(D_CONE, 1, 0),
        spec(D_PHONG, 0, 0), spec(D_PHONG, 1, 0), spec(D_PHONG, 10, 0),
        spec(D_PHONG, 1e3, 0), spec(D_PHONG, 1e5, 0),
        spec(D_WARD, 1e-4, 1e-4), spec(D_WARD, 0.01, 0.01), spec(D_WARD, 1, 1),
        spec(D_WARD, 1, 0.01), spec(D_WARD, 0.01, 1), spec(D_WARD, 1e-2, 1e-4),
        spec(D_WARD, 10, 10),
        sphere_spec(0, 1, 0, 0), sphere_spec(0.5, 1, 1, 2),
        sphere_spec(1, 1, 1, 2), sphere_spec(1.0001, 1, 1, 2),
        sphere_spec(10, 1, 2, 1), sphere_spec(1e6, 1, 0.5, 0.5),
        sphere_spec(1e-3, 1e-3, 0.5, 0.5), sphere_spec(2e-3, 1e-3, 2.5, 4),
        sphere_spec(1e4, 1e3, 3, 0.1),
    };
    int nd = (int)(sizeof dirs / sizeof dirs[0]);
    long cases = 0;
    for (int d = 0; d < nd; d++)
        for (int i = 0; i < nv; i++)
            for (int j = 0; j < nv; j++, cases++) {
                real u[2] = { v[i], v[j] };
                /* NaN until a sampler writes it: one that does not fails
                 * the first assertion below */
                VECTOR3 w = { (real)NAN, (real)NAN, (real)NAN };
                real pdf_s = 0;
                if (dirs[d].kind == D_SPHERE_SA)
                    pdf_s = sample_sphere_solid_angle(w, dirs[d].x, dirs[d].c,
                                                      dirs[d].r, u);
                else
                    direction_sample(&dirs[d], u, w);
                ck_assert_msg(vec_is_finite(w), "spec %d u = (%a, %a)", d,
                              (double)u[0], (double)u[1]);
                ck_assert_msg(fabs(vec_length(w) - 1) <= unit_tol,
                              "spec %d u = (%a, %a): |w| - 1 = %g", d,
                              (double)u[0], (double)u[1],
                              (double)(vec_length(w) - 1));
                double pdf = direction_pdf(&dirs[d], w);
                ck_assert_msg(isfinite(pdf) && pdf > 0,
                              "spec %d u = (%a, %a): pdf %g at w = (%g %g %g)",
                              d, (double)u[0], (double)u[1], pdf, (double)w[X],
                              (double)w[Y], (double)w[Z]);
                if (dirs[d].kind == D_SPHERE_SA)
                    ck_assert_msg((double)pdf_s == pdf, "spec %d: %g vs %g", d,
                                  (double)pdf_s, pdf);
            }
    /* Points. */
    VECTOR3 p0 = { 1, 2, 3 }, e1 = { 1e-3, 0, 0 }, e2 = { 0, 1e3, 0 };
    VECTOR3 c = { 1e3, -1e3, 5 };
    for (int i = 0; i < nv; i++)
        for (int j = 0; j < nv; j++) {
            real u[2] = { v[i], v[j] }, d[2], b[2];
            sample_concentric_disk(d, u);
            ck_assert(finite2(d) && d[0] * d[0] + d[1] * d[1] <= 1 + 4 * REAL_EPSILON);
            sample_triangle(b, u);
            ck_assert(finite2(b) && b[0] >= 0 && b[1] >= 0 && b[0] + b[1] <= 1);
            VECTOR3 p, n;
            sample_parallelogram(p, p0, e1, e2, u);
            ck_assert(vec_is_finite(p));
            sample_sphere_area(p, n, c, REAL_C(1e-3), u);
            ck_assert(vec_is_finite(p) && vec_is_finite(n));
            ck_assert_near(vec_length(n), 1, unit_tol);
            cases += 4;
        }
    /* pdfs at the edges of their domains. */
    ck_assert(sample_phong_lobe_pdf(0, 0) > 0);
    ck_assert(sample_phong_lobe_pdf(0, 5) == 0);
    ck_assert(sample_phong_lobe_pdf(REAL_C(-1e-7), 0) == 0);
    ck_assert(isfinite(sample_phong_lobe_pdf(1, REAL_C(1e30))));
    ck_assert(sample_cosine_hemisphere_pdf(0) == 0);
    VECTOR3 grazing = { 1, 0, 0 }, tiny = { 1, 0, REAL_MIN }, up = { 0, 0, 1 };
    ck_assert(sample_ward_half_pdf(grazing, REAL_C(0.1), REAL_C(0.1)) == 0);
    ck_assert(sample_ward_half_pdf(tiny, REAL_C(0.1), REAL_C(0.1)) == 0);
    ck_assert(isfinite(sample_ward_half_pdf(up, 0, 0)));
    ck_assert(isfinite(sample_uniform_cone_pdf(1)));
    test_report_cases("no_sampler_returns_nan_or_inf_over_a_dense_sweep", cases);
}
END_TEST

START_TEST(samplers_reach_their_extremes)
{
    /* u = 0 gives the axis (+z) for Phong and Ward, the pole for the
     * sphere; the cone's edge is reached as u0 -> 1. */
    real u0[2] = { 0, 0 };
    VECTOR3 w;
    sample_phong_lobe(w, u0, REAL_C(1e5));
    ck_assert(w[Z] == 1 && w[X] == 0 && w[Y] == 0);
    sample_ward_half(w, u0, REAL_C(0.3), REAL_C(0.01));
    ck_assert(w[Z] == 1);
    sample_uniform_sphere(w, u0);
    ck_assert(w[Z] == 1);
    real top[2] = { nextafter(REAL_C(1.0), REAL_C(0.0)), 0 };
    sample_uniform_cone(w, top, REAL_C(0.5));
    ck_assert_near(w[Z], 0.5, 4 * REAL_EPSILON);
    sample_uniform_sphere(w, top);
    ck_assert_near(w[Z], -1, 4 * REAL_EPSILON);
    /* A sphere 1e6 radii away: the cone is 1e-6 wide, not lost to
     * rounding 1 - cos. */
    dspec d = sphere_spec(1e6, 1, 0.4, 0.4);
    real pdf = sample_sphere_solid_angle(w, d.x, d.c, d.r, top);
    ck_assert_rel(pdf, 1 / (PI_D * 1e-12), 1e-4, 0);
}
END_TEST

/* --- strata ------------------------------------------------------------------ */

START_TEST(stratified_points_fall_one_per_cell)
{
    static const int sizes[][2] = { { 1, 1 }, { 7, 3 }, { 3, 7 }, { 16, 16 },
                                    { 64, 64 }, { 1, 100 } };
    pcg32_t g;
    pcg32_seed(&g, 400, 1);
    long cases = 0;
    for (int s = 0; s < 6; s++) {
        int nx = sizes[s][0], ny = sizes[s][1];
        real *pts = malloc((size_t)(2 * nx * ny) * sizeof *pts);
        sample_stratified_2d(pts, nx, ny, &g);
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++, cases++) {
                real x = pts[2 * (j * nx + i)], y = pts[2 * (j * nx + i) + 1];
                ck_assert(x >= (real)i / (real)nx && x < (real)(i + 1) / (real)nx);
                ck_assert(y >= (real)j / (real)ny && y < (real)(j + 1) / (real)ny);
            }
        free(pts);
    }
    /* The largest draw in the last cell must not round onto 1: put the
     * generator in the state whose next output is 0xffffffff (bits 41..58
     * set: the xorshift of pcg32 then gives all ones, rotation 0), moved
     * back so that it is the x draw of cell (2, 0) of a 3 x 1 grid. */
    pcg32_t top = { (UINT64_C(1) << 59) - (UINT64_C(1) << 41), 1 };
    pcg32_t probe = top;
    ck_assert_uint_eq(pcg32_next(&probe), 0xffffffffu);
    pcg32_advance(&top, (uint64_t)-4);
    real pts[6];
    sample_stratified_2d(pts, 3, 1, &top);
    ck_assert_msg(pts[4] < 1 && pts[4] >= REAL_C(2.0) / 3, "x = %a",
                  (double)pts[4]);
    test_report_cases("stratified_points_fall_one_per_cell", cases + 1);
}
END_TEST

/* --- estimators -------------------------------------------------------------- */

static void two_pass(const double *x, int n, long double *mean,
                     long double *var)
{
    long double s = 0, ss = 0;
    for (int i = 0; i < n; i++)
        s += (long double)x[i];
    *mean = s / n;
    for (int i = 0; i < n; i++) {
        long double d = (long double)x[i] - *mean;
        ss += d * d;
    }
    *var = n > 1 ? ss / (n - 1) : 0;
}

START_TEST(estimator_matches_exact_and_two_pass_values)
{
    /* x_k = 1e9 + k, k = 1..n: mean 1e9 + (n+1)/2, variance n(n+1)/12
     * exactly. The offset 1e9 defeats the naive sum-of-squares formula
     * (cancellation of 1e18-sized terms in double); Welford's update keeps
     * the variance to ~1e-9 relative. */
    enum { N = 1000 };
    double *x = malloc(N * sizeof *x);
    estimator_t e;
    estimator_init(&e);
    ck_assert(estimator_variance(&e) == 0 && estimator_stderr(&e) == 0);
    for (int k = 1; k <= N; k++) {
        x[k - 1] = 1e9 + k;
        estimator_add(&e, x[k - 1]);
    }
    ck_assert_rel(estimator_mean(&e), 1e9 + (N + 1) / 2.0, 1e-15, 0);
    ck_assert_rel(estimator_variance(&e), N * (N + 1) / 12.0, 1e-9, 0);
    ck_assert_rel(estimator_stderr(&e), sqrt(N * (N + 1) / 12.0 / N), 1e-9, 0);
    /* Random data against the two-pass formulas in long double. */
    pcg32_t g;
    pcg32_seed(&g, 500, 1);
    estimator_init(&e);
    for (int k = 0; k < N; k++) {
        x[k] = exp(4 * (double)pcg32_real(&g)) - 3;
        estimator_add(&e, x[k]);
    }
    long double m, v;
    two_pass(x, N, &m, &v);
    ck_assert_rel(estimator_mean(&e), (double)m, 1e-13, 1e-15);
    ck_assert_rel(estimator_variance(&e), (double)v, 1e-12, 0);
    /* n = 1: mean is the value, variance 0. */
    estimator_init(&e);
    estimator_add(&e, 42.5);
    ck_assert(estimator_mean(&e) == 42.5 && estimator_variance(&e) == 0);
    free(x);
    test_report_cases("estimator_matches_exact_and_two_pass_values", 2 * N + 1);
}
END_TEST

START_TEST(merged_estimators_equal_the_sequential_one)
{
    enum { N = 10007 };
    pcg32_t g;
    pcg32_seed(&g, 501, 1);
    double *x = malloc(N * sizeof *x);
    for (int k = 0; k < N; k++)
        x[k] = 1e6 + 1e3 * (double)pcg32_real(&g);
    estimator_t seq;
    estimator_init(&seq);
    for (int k = 0; k < N; k++)
        estimator_add(&seq, x[k]);
    /* Split into 1, 2, 7, 64 and N parts of uneven sizes; merge. The
     * merged mean and variance agree with the sequential ones to rounding
     * (Chan et al. 1983 is exact in exact arithmetic). */
    static const int parts[] = { 1, 2, 7, 64, N };
    long cases = 0;
    for (int p = 0; p < 5; p++) {
        estimator_t total;
        estimator_init(&total);
        int start = 0;
        for (int q = 0; q < parts[p]; q++) {
            int end = (int)((long)N * (q + 1) * (q + 1) /
                            ((long)parts[p] * parts[p]));
            estimator_t part;
            estimator_init(&part);
            for (int k = start; k < end; k++)
                estimator_add(&part, x[k]);
            estimator_merge(&total, &part);
            start = end;
        }
        ck_assert(total.n == N);
        ck_assert_rel(estimator_mean(&total), estimator_mean(&seq), 1e-14, 0);
        ck_assert_rel(estimator_variance(&total), estimator_variance(&seq),
                      1e-9, 0);
        cases++;
    }
    /* Merging an empty estimator changes nothing, either way round. */
    estimator_t empty, copy = seq;
    estimator_init(&empty);
    estimator_merge(&copy, &empty);
    ck_assert(copy.n == seq.n && copy.mean == seq.mean && copy.m2 == seq.m2);
    estimator_merge(&empty, &seq);
    ck_assert(empty.n == seq.n && empty.mean == seq.mean && empty.m2 == seq.m2);
    free(x);
    test_report_cases("merged_estimators_equal_the_sequential_one", cases + 2);
}
END_TEST

/* --- tests/vectors/sample_*.csv --------------------------------------------- */

/* Column <name>_float or <name>_double, for this build's real. */
static double per_real(testcsv_t *c, const char *name)
{
    char col[64];
    snprintf(col, sizeof col, "%s_%s", name, REAL_NAME);
    return testcsv_num(c, col);
}

START_TEST(samplers_match_the_vectors)
{
    /* sample_directions.csv: every direction sampler at a table of u
     * (extremes included), against independent long double closed forms
     * (tools/vectors_sample.c). */
    testcsv_t c;
    long rows = 0;
    testcsv_open(&c, "sample_directions.csv");
    while (testcsv_next(&c)) {
        const char *s = testcsv_str(&c, "sampler");
        real u[2] = { (real)testcsv_num(&c, "u0"), (real)testcsv_num(&c, "u1") };
        real a = (real)testcsv_num(&c, "a"), b = (real)testcsv_num(&c, "b");
        VECTOR3 w;
        real pdf;
        if (strcmp(s, "uniform_sphere") == 0) {
            sample_uniform_sphere(w, u);
            pdf = sample_uniform_sphere_pdf();
        } else if (strcmp(s, "uniform_hemisphere") == 0) {
            sample_uniform_hemisphere(w, u);
            pdf = sample_uniform_hemisphere_pdf();
        } else if (strcmp(s, "cosine_hemisphere") == 0) {
            sample_cosine_hemisphere(w, u);
            pdf = sample_cosine_hemisphere_pdf(w[Z]);
        } else if (strcmp(s, "uniform_cone") == 0) {
            sample_uniform_cone(w, u, a);
            pdf = sample_uniform_cone_pdf(a);
        } else if (strcmp(s, "phong_lobe") == 0) {
            sample_phong_lobe(w, u, a);
            pdf = sample_phong_lobe_pdf(w[Z], a);
        } else if (strcmp(s, "ward_half") == 0) {
            sample_ward_half(w, u, a, b);
            pdf = sample_ward_half_pdf(w, a, b);
        } else {
            ck_abort_msg("%s:%d: unknown sampler %s", c.path, c.line, s);
            return;
        }
        double tol = per_real(&c, "tol");
        ck_assert_msg(fabs((double)w[X] - testcsv_num(&c, "wx")) <= tol &&
                          fabs((double)w[Y] - testcsv_num(&c, "wy")) <= tol &&
                          fabs((double)w[Z] - testcsv_num(&c, "wz")) <= tol,
                      "%s:%d %s: w = (%.9g %.9g %.9g), tol %g", c.path, c.line,
                      s, (double)w[X], (double)w[Y], (double)w[Z], tol);
        double pe = testcsv_num(&c, "pdf");
        double prel = per_real(&c, "pdf_rel");
        ck_assert_msg(fabs((double)pdf - pe) <= prel * pe + 1e-300,
                      "%s:%d %s: pdf %.9g, expected %.9g (rel %g)", c.path,
                      c.line, s, (double)pdf, pe, prel);
        rows++;
    }
    testcsv_close(&c);

    testcsv_open(&c, "sample_points.csv");
    while (testcsv_next(&c)) {
        const char *s = testcsv_str(&c, "sampler");
        real u[2] = { (real)testcsv_num(&c, "u0"), (real)testcsv_num(&c, "u1") };
        real q[2];
        if (strcmp(s, "concentric_disk") == 0)
            sample_concentric_disk(q, u);
        else if (strcmp(s, "triangle") == 0)
            sample_triangle(q, u);
        else {
            ck_abort_msg("%s:%d: unknown sampler %s", c.path, c.line, s);
            return;
        }
        double tol = per_real(&c, "tol");
        ck_assert_msg(fabs((double)q[0] - testcsv_num(&c, "p0")) <= tol &&
                          fabs((double)q[1] - testcsv_num(&c, "p1")) <= tol,
                      "%s:%d %s: (%.9g %.9g)", c.path, c.line, s, (double)q[0],
                      (double)q[1]);
        rows++;
    }
    testcsv_close(&c);

    testcsv_open(&c, "sample_sphere.csv");
    while (testcsv_next(&c)) {
        VECTOR3 x = { (real)testcsv_num(&c, "xx"), (real)testcsv_num(&c, "xy"),
                      (real)testcsv_num(&c, "xz") };
        VECTOR3 cc = { (real)testcsv_num(&c, "cx"), (real)testcsv_num(&c, "cy"),
                       (real)testcsv_num(&c, "cz") };
        real r = (real)testcsv_num(&c, "r");
        real u[2] = { (real)testcsv_num(&c, "u0"), (real)testcsv_num(&c, "u1") };
        VECTOR3 w;
        real pdf = sample_sphere_solid_angle(w, x, cc, r, u);
        double tol = per_real(&c, "tol");
        ck_assert_msg(fabs((double)w[X] - testcsv_num(&c, "wx")) <= tol &&
                          fabs((double)w[Y] - testcsv_num(&c, "wy")) <= tol &&
                          fabs((double)w[Z] - testcsv_num(&c, "wz")) <= tol,
                      "%s:%d: w = (%.9g %.9g %.9g)", c.path, c.line,
                      (double)w[X], (double)w[Y], (double)w[Z]);
        double prel = per_real(&c, "pdf_rel");
        double pe = testcsv_num(&c, "pdf");
        ck_assert_msg(fabs((double)pdf - pe) <= prel * pe, "%s:%d: pdf %.9g vs %.9g",
                      c.path, c.line, (double)pdf, pe);
        rows++;
    }
    testcsv_close(&c);
    test_report_cases("samplers_match_the_vectors", rows);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("sample (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    /* the chi-square fits take a few seconds each in float */
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, gamma_q_matches_closed_forms_and_tables);
    tcase_add_test(tc, sidak_and_ks_match_published_values);
    tcase_add_test(tc, counts_are_pooled_as_mitsuba_does);
    tcase_add_test(tc, harness_rejects_wrong_pdfs);
    tcase_add_test(tc, direction_samplers_fit_their_pdfs);
#ifdef SVET_DOUBLE
    tcase_add_test(tc, ward_half_alpha_1e_4_fits_in_double);
#endif
    tcase_add_test(tc, narrow_lobes_concentrate_where_expected);
    tcase_add_test(tc, point_samplers_have_their_distributions);
    tcase_add_test(tc, every_pdf_integrates_to_one);
    tcase_add_test(tc, no_sampler_returns_nan_or_inf_over_a_dense_sweep);
    tcase_add_test(tc, samplers_reach_their_extremes);
    tcase_add_test(tc, stratified_points_fall_one_per_cell);
    tcase_add_test(tc, estimator_matches_exact_and_two_pass_values);
    tcase_add_test(tc, merged_estimators_equal_the_sequential_one);
    tcase_add_test(tc, samplers_match_the_vectors);
    suite_add_tcase(s, tc);
    return s;
}
