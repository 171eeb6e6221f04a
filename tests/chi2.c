/*
 * chi2.c - the goodness-of-fit harness of chi2.h: chi-square test of a
 * direction sampler against its pdf (after pbrt-v3 src/tests/bsdfs.cpp and
 * Mitsuba 3 mitsuba/python/chi2.py), adaptive cubature of the pdf, the
 * incomplete gamma function and the Kolmogorov-Smirnov distribution
 * (Numerical Recipes 3rd ed., secs. 6.2 and 6.14).
 * Tests: tests/core/test_sample.c
 */
#include "chi2.h"

#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI_D 3.14159265358979323846
#define MIN_EXPECTED 5.0   /* Cochran's rule: pool cells expected below 5 */
#define QUAD_ABS 1e-7      /* total absolute tolerance of the pdf mass */
/* Relative tolerance per cell. It must lie above the rounding noise of the
 * pdf, which is evaluated at a direction rounded to `real`: a lobe cos^e
 * turns the 6e-8 rounding of a float cos(theta) into e * 6e-8 (6e-5 at
 * e = 1e3); and far below the statistical noise 1/sqrt(count) of a bin
 * (>= 3e-3 for counts <= 1e5), which 1e-4 is. */
#ifdef SVET_DOUBLE
#define QUAD_REL 1e-7
#else
#define QUAD_REL 1e-4
#endif
#define QUAD_MIN_DEPTH 2   /* always split a bin into >= 4 x 4 cells */
#define QUAD_MAX_DEPTH 14  /* never below 2^-14 of a bin per side */
#define QUAD_CELL_BUDGET 200000L /* pdf evaluations per top-level cell */

void chi2_config_defaults(chi2_config *cfg)
{
    if (cfg->theta_bins <= 0)
        cfg->theta_bins = 10;
    if (cfg->phi_bins <= 0)
        cfg->phi_bins = 2 * cfg->theta_bins;
    if (cfg->samples <= 0)
        cfg->samples = 1000L * cfg->theta_bins * cfg->phi_bins;
    if (cfg->significance <= 0)
        cfg->significance = 0.01;
    if (cfg->tests <= 0)
        cfg->tests = 1;
    if (!(cfg->cap_height > 0 && cfg->cap_height < 2))
        cfg->cap_height = 2;
}

double chi2_sidak(double alpha, int tests)
{
    /* 1 - (1 - alpha)^(1/m), written with log1p/expm1 so that a tiny
     * alpha / m keeps its digits. */
    return -expm1(log1p(-alpha) / (double)(tests > 0 ? tests : 1));
}

/* --- the incomplete gamma function (NR3 sec. 6.2) ------------------------- */

/* P(a, x) by its series, for x < a + 1 (NR3 eq. 6.2.5). */
static double gamma_p_series(double a, double x, double gln)
{
    double ap = a, del = 1.0 / a, sum = del;
    for (int n = 0; n < 1000000; n++) {
        ap += 1.0;
        del *= x / ap;
        sum += del;
        if (fabs(del) < fabs(sum) * DBL_EPSILON)
            break;
    }
    return sum * exp(-x + a * log(x) - gln);
}

/* Q(a, x) by its continued fraction, for x >= a + 1 (NR3 eq. 6.2.7),
 * evaluated by the modified Lentz method. */
static double gamma_q_fraction(double a, double x, double gln)
{
    const double tiny = DBL_MIN / DBL_EPSILON;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 1000000; i++) {
        double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (fabs(d) < tiny)
            d = tiny;
        c = b + an / c;
        if (fabs(c) < tiny)
            c = tiny;
        d = 1.0 / d;
        double del = d * c;
        h *= del;
        if (fabs(del - 1.0) <= DBL_EPSILON)
            break;
    }
    return exp(-x + a * log(x) - gln) * h;
}

double chi2_gamma_q(double a, double x)
{
    if (!(a > 0) || !(x >= 0) || isinf(a))
        return (double)NAN;
    if (x == 0)
        return 1.0;
    if (isinf(x))
        return 0.0;
    double gln = lgamma(a);
    if (x < a + 1.0)
        return 1.0 - gamma_p_series(a, x, gln);
    return gamma_q_fraction(a, x, gln);
}

/* --- chi-square of a histogram, with pooling ----------------------------- */

typedef struct {
    double obs, exp;
} cell_t;

static int cell_cmp(const void *pa, const void *pb)
{
    const cell_t *a = pa, *b = pb;
    return (a->exp > b->exp) - (a->exp < b->exp);
}

static void decide(chi2_result *r, const chi2_config *cfg)
{
    r->threshold = chi2_sidak(cfg->significance, cfg->tests);
    if (r->dof < 1) {
        snprintf(r->message, sizeof r->message,
                 "too few degrees of freedom (%d) after pooling", r->dof);
        return;
    }
    r->p_value = chi2_gamma_q(0.5 * r->dof, 0.5 * r->statistic);
    r->passed = isfinite(r->p_value) && r->p_value >= r->threshold;
    snprintf(r->message, sizeof r->message,
             "%s: chi2 = %.6g, dof = %d, p = %.4g %s threshold %.4g "
             "(alpha %.3g, Sidak over %d tests); pooled %d cells into %d",
             r->passed ? "accepted" : "REJECTED", r->statistic, r->dof,
             r->p_value, r->passed ? ">=" : "<", r->threshold,
             cfg->significance, cfg->tests, r->pooled_in, r->pooled_out);
}

chi2_result chi2_from_counts(const double *observed, const double *expected,
                             int n, const chi2_config *cfg_in)
{
    chi2_config cfg = *cfg_in;
    chi2_config_defaults(&cfg);
    chi2_result r;
    memset(&r, 0, sizeof r);
    r.p_value = (double)NAN;
    r.pdf_integral = (double)NAN;

    cell_t *c = malloc((size_t)(n > 0 ? n : 1) * sizeof *c);
    if (!c) {
        snprintf(r.message, sizeof r.message, "out of memory");
        return r;
    }
    double total = 0, zero_obs = 0;
    int m = 0;
    for (int i = 0; i < n; i++) {
        total += observed[i];
        if (!(expected[i] > 0)) {
            zero_obs += observed[i]; /* NaN expectations land here too */
            continue;
        }
        c[m].obs = observed[i];
        c[m].exp = expected[i];
        m++;
    }
    /* Samples where the pdf says none can be. pbrt-v3 lets through 1e-5 N
     * of them: rounding at the edge of the support (a z of -1e-9 from a
     * hemisphere sampler) is no bug. */
    if (zero_obs > 1e-5 * total) {
        free(c);
        snprintf(r.message, sizeof r.message,
                 "REJECTED: %.0f of %.0f samples in cells of expected count 0",
                 zero_obs, total);
        r.threshold = chi2_sidak(cfg.significance, cfg.tests);
        return r;
    }
    qsort(c, (size_t)m, sizeof *c, cell_cmp);

    /* Pool the smallest cells in order into groups of expectation >= 5. */
    double chsq = 0, pool_obs = 0, pool_exp = 0;
    int dof = 0, i = 0;
    while (i < m && c[i].exp < MIN_EXPECTED) {
        pool_obs += c[i].obs;
        pool_exp += c[i].exp;
        r.pooled_in++;
        i++;
        if (pool_exp >= MIN_EXPECTED) {
            chsq += (pool_obs - pool_exp) * (pool_obs - pool_exp) / pool_exp;
            dof++;
            r.pooled_out++;
            pool_obs = pool_exp = 0;
        }
    }
    if (pool_exp > 0) {
        if (i < m) { /* the last, under-filled group joins the next cell */
            c[i].obs += pool_obs;
            c[i].exp += pool_exp;
        } else {     /* nothing left to join: count it as it is */
            chsq += (pool_obs - pool_exp) * (pool_obs - pool_exp) / pool_exp;
            dof++;
        }
        r.pooled_out++;
    }
    for (; i < m; i++) {
        double d = c[i].obs - c[i].exp;
        chsq += d * d / c[i].exp;
        dof++;
    }
    free(c);
    /* All parameters of the distribution are known: only the constraint
     * sum(obs) = sum(exp) = N removes a degree of freedom. */
    r.statistic = chsq;
    r.dof = dof - 1;
    decide(&r, &cfg);
    return r;
}

/* --- adaptive cubature of a pdf over (cos theta, phi) --------------------- */

typedef struct {
    chi2_pdf_fn pdf;
    void *ctx;
    long evals;
    long budget_end; /* stop refining when evals passes this */
    long exhausted;  /* top-level cells that ran out of budget */
    long bad;       /* negative or non-finite pdf values */
    double err;     /* accumulated error estimate */
    double abs_per_area; /* absolute tolerance per unit of (cos, phi) area */
} cubature_t;

/* 5-point Gauss-Legendre nodes and weights on [-1, 1] (Abramowitz & Stegun
 * table 25.4). */
static const double gl_x[5] = { -0.9061798459386640, -0.5384693101056831, 0.0,
                                0.5384693101056831, 0.9061798459386640 };
static const double gl_w[5] = { 0.2369268850561891, 0.4786286704993665,
                                0.5688888888888889, 0.4786286704993665,
                                0.2369268850561891 };

/* The pdf at cos theta = c, with sin theta = s and the azimuth's cosine
 * and sine given (a cell's nodes share them, see gl_cell). */
static double pdf_at_cs(cubature_t *q, double c, double s, double cp,
                        double sp)
{
    VECTOR3 w;
    vec_set(w, (real)(s * cp), (real)(s * sp), (real)c);
    double p = q->pdf(q->ctx, w);
    q->evals++;
    if (!(p >= 0) || !isfinite(p)) {
        q->bad++;
        return 0;
    }
    return p;
}

static double sin_of_cos(double c)
{
    return sqrt(fmax(0.0, (1.0 - c) * (1.0 + c)));
}

/* Tensor-product Gauss-Legendre over [c0, c1] x [p0, p1]; the solid angle
 * element is dcos(theta) dphi, so no Jacobian. The 5 x 5 nodes take their
 * sines and cosines from 5 values of theta and 5 of phi. */
static double gl_cell(cubature_t *q, double c0, double c1, double p0, double p1)
{
    double hc = 0.5 * (c1 - c0), mc = 0.5 * (c1 + c0);
    double hp = 0.5 * (p1 - p0), mp = 0.5 * (p1 + p0);
    double cp[5], sp[5];
    for (int j = 0; j < 5; j++) {
        double phi = mp + hp * gl_x[j];
        cp[j] = cos(phi);
        sp[j] = sin(phi);
    }
    double sum = 0;
    for (int i = 0; i < 5; i++) {
        double c = mc + hc * gl_x[i], s = sin_of_cos(c);
        for (int j = 0; j < 5; j++)
            sum += gl_w[i] * gl_w[j] * pdf_at_cs(q, c, s, cp[j], sp[j]);
    }
    return sum * hc * hp;
}

/* Split into four; accept the children's sum when it agrees with the
 * parent's estimate `whole` (the parent's error estimate is |sum - whole|,
 * and the children are more accurate than that). */
static double adapt(cubature_t *q, double c0, double c1, double p0, double p1,
                    double whole, int depth)
{
    double cm = 0.5 * (c0 + c1), pm = 0.5 * (p0 + p1);
    double k[4] = { gl_cell(q, c0, cm, p0, pm), gl_cell(q, cm, c1, p0, pm),
                    gl_cell(q, c0, cm, pm, p1), gl_cell(q, cm, c1, pm, p1) };
    double sum = (k[0] + k[1]) + (k[2] + k[3]);
    double diff = fabs(sum - whole);
    double tol = q->abs_per_area * (c1 - c0) * (p1 - p0) + QUAD_REL * fabs(sum);
    if (depth + 1 >= QUAD_MIN_DEPTH &&
        (diff <= tol || depth + 1 >= QUAD_MAX_DEPTH ||
         q->evals > q->budget_end)) {
        q->err += diff;
        return sum;
    }
    return (adapt(q, c0, cm, p0, pm, k[0], depth + 1) +
            adapt(q, cm, c1, p0, pm, k[1], depth + 1)) +
           (adapt(q, c0, cm, pm, p1, k[2], depth + 1) +
            adapt(q, cm, c1, pm, p1, k[3], depth + 1));
}

static double integrate_cell(cubature_t *q, double c0, double c1, double p0,
                             double p1)
{
    q->budget_end = q->evals + QUAD_CELL_BUDGET;
    double sum = adapt(q, c0, c1, p0, p1, gl_cell(q, c0, c1, p0, p1), 0);
    if (q->evals > q->budget_end)
        q->exhausted++;
    return sum;
}

/* Integral over the band cos theta in [c0, c1], phi in [p0, p1], in np
 * cells along phi. */
static double integrate_band(cubature_t *q, double c0, double c1, double p0,
                             double p1, int np)
{
    double sum = 0;
    for (int j = 0; j < np; j++)
        sum += integrate_cell(q, c0, c1, p0 + (p1 - p0) * j / np,
                              j + 1 == np ? p1 : p0 + (p1 - p0) * (j + 1) / np);
    return sum;
}

static int cmp_double(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

/* Integral over cos theta in [lo, hi], phi in [p0, p1], in bands that shrink
 * geometrically (by halves, down to 2^-44) toward each of the nfocus values
 * of cos theta in focus[]: there a sharp lobe (about a pole, or cut off by
 * the edge of a cap) has its mass, and bands of fixed width would let it
 * fall between the quadrature nodes. */
static double integrate_focused(cubature_t *q, double lo, double hi,
                                const double *focus, int nfocus, double p0,
                                double p1, int np)
{
    enum { MAXEDGE = 2 + 4 * 2 * 46 };
    double e[MAXEDGE];
    int n = 0;
    e[n++] = lo;
    e[n++] = hi;
    for (int f = 0; f < nfocus && f < 4; f++)
        for (int k = -44; k <= 1; k++)
            for (int sgn = -1; sgn <= 1; sgn += 2) {
                double x = focus[f] + sgn * ldexp(1.0, k);
                if (x > lo && x < hi)
                    e[n++] = x;
            }
    qsort(e, (size_t)n, sizeof *e, cmp_double);
    double sum = 0;
    for (int i = 1; i < n; i++)
        if (e[i] > e[i - 1])
            sum += integrate_band(q, e[i - 1], e[i], p0, p1, np);
    return sum;
}

static void quad_init(cubature_t *q, chi2_pdf_fn pdf, void *ctx)
{
    memset(q, 0, sizeof *q);
    q->pdf = pdf;
    q->ctx = ctx;
    q->abs_per_area = QUAD_ABS / (4 * PI_D);
}

double chi2_pdf_integral(chi2_pdf_fn pdf, void *ctx, double cap_height,
                         double *err)
{
    cubature_t q;
    quad_init(&q, pdf, ctx);
    double focus[3] = { -1, 1, 1 - cap_height };
    int nfocus = cap_height > 0 && cap_height < 2 ? 3 : 2;
    double sum = integrate_focused(&q, -1, 1, focus, nfocus, 0, 2 * PI_D, 24);
    if (err)
        *err = q.err;
    return sum;
}

/* --- the direction test ----------------------------------------------------- */

chi2_result chi2_test(const chi2_config *cfg_in, chi2_sample_fn sample,
                      chi2_pdf_fn pdf, void *ctx)
{
    chi2_config cfg = *cfg_in;
    chi2_config_defaults(&cfg);
    const int nt = cfg.theta_bins, np = cfg.phi_bins;
    const double c_lo = 1 - cfg.cap_height; /* bottom of the binned cap */
    const bool capped = cfg.cap_height < 2;
    /* cells: nt * np bins, then "below the cap", then "absorbed" */
    const int nbins = nt * np, ncell = nbins + 2;
    double *obs = calloc((size_t)ncell, sizeof *obs);
    double *expc = calloc((size_t)ncell, sizeof *expc);
    chi2_result r;
    memset(&r, 0, sizeof r);
    r.p_value = (double)NAN;
    if (!obs || !expc) {
        free(obs);
        free(expc);
        snprintf(r.message, sizeof r.message, "out of memory");
        return r;
    }

    /* Histogram of the samples. */
    pcg32_t g;
    pcg32_seed(&g, cfg.seed, UINT64_C(0x63686932)); /* "chi2" */
    double first_bad[3] = { 0, 0, 0 };
    for (long k = 0; k < cfg.samples; k++) {
        real u[2];
        u[0] = pcg32_real(&g);
        u[1] = pcg32_real(&g);
        VECTOR3 w = { 0, 0, 0 };
        if (!sample(ctx, u, w)) {
            r.absorbed++;
            obs[nbins + 1] += 1;
            continue;
        }
        double x = (double)w[X], y = (double)w[Y], z = (double)w[Z];
        double len = sqrt(x * x + y * y + z * z);
        if (!isfinite(len) || fabs(len - 1) > 1e-4) {
            if (r.invalid++ == 0) {
                first_bad[0] = x; first_bad[1] = y; first_bad[2] = z;
            }
            continue;
        }
        double c = z / len;
        if (capped && c < c_lo) {
            obs[nbins] += 1;
            continue;
        }
        double phi = atan2(y, x);
        if (phi < 0)
            phi += 2 * PI_D;
        int i = (int)((c - c_lo) / cfg.cap_height * nt);
        int j = (int)(phi / (2 * PI_D) * np);
        i = i < 0 ? 0 : i >= nt ? nt - 1 : i;
        j = j < 0 ? 0 : j >= np ? np - 1 : j;
        obs[i * np + j] += 1;
    }

    /* Expected counts: N times the pdf integrated over each cell. */
    cubature_t q;
    quad_init(&q, pdf, ctx);
    double integral = 0;
    for (int i = 0; i < nt; i++)
        for (int j = 0; j < np; j++) {
            double c0 = c_lo + cfg.cap_height * i / nt;
            double c1 = i + 1 == nt ? 1.0 : c_lo + cfg.cap_height * (i + 1) / nt;
            double p0 = 2 * PI_D * j / np, p1 = 2 * PI_D * (j + 1) / np;
            /* Bins at a pole are cut into bands shrinking toward it, where
             * lobes about +z (or -z) put their mass. */
            double pole = i + 1 == nt ? 1.0 : -1.0;
            double m = i + 1 == nt || (i == 0 && !capped)
                           ? integrate_focused(&q, c0, c1, &pole, 1, p0, p1, 1)
                           : integrate_cell(&q, c0, c1, p0, p1);
            integral += m;
            expc[i * np + j] = m * (double)cfg.samples;
        }
    if (capped) {
        double focus[2] = { -1, c_lo };
        double m = integrate_focused(&q, -1, c_lo, focus, 2, 0, 2 * PI_D, np);
        integral += m;
        expc[nbins] = m * (double)cfg.samples;
    }
    expc[nbins + 1] = fmax(0.0, 1.0 - integral) * (double)cfg.samples;

    if (r.invalid > 0 || q.bad > 0 || integral > 1 + 1e-3) {
        r.threshold = chi2_sidak(cfg.significance, cfg.tests);
        if (r.invalid > 0)
            snprintf(r.message, sizeof r.message,
                     "REJECTED: %ld samples NaN, Inf or not unit, the first "
                     "(%.9g, %.9g, %.9g)",
                     r.invalid, first_bad[0], first_bad[1], first_bad[2]);
        else if (q.bad > 0)
            snprintf(r.message, sizeof r.message,
                     "REJECTED: %ld pdf values negative, NaN or Inf", q.bad);
        else
            snprintf(r.message, sizeof r.message,
                     "REJECTED: the pdf integrates to %.9g > 1", integral);
    } else {
        long absorbed = r.absorbed;
        r = chi2_from_counts(obs, expc, ncell, &cfg);
        r.absorbed = absorbed;
    }
    if (q.exhausted > 0) {
        size_t len = strlen(r.message);
        snprintf(r.message + len, sizeof r.message - len,
                 "; quadrature unresolved in %ld cells", q.exhausted);
    }
    r.pdf_integral = integral;
    r.quad_error = q.err;
    r.bad_pdf = q.bad;
    free(obs);
    free(expc);
    return r;
}

/* --- Kolmogorov-Smirnov ------------------------------------------------- */

double chi2_ks_statistic(double *x, long n, chi2_cdf_fn cdf, void *ctx)
{
    qsort(x, (size_t)n, sizeof *x, cmp_double);
    double d = 0;
    for (long i = 0; i < n; i++) {
        double f = cdf(ctx, x[i]);
        double above = (double)(i + 1) / (double)n - f;
        double below = f - (double)i / (double)n;
        d = fmax(d, fmax(above, below));
    }
    return d;
}

/* Q_KS(z) = 1 - P_KS(z), NR3 sec. 6.14: the theta-function series in
 * exp(-(2j-1)^2 pi^2 / (8 z^2)) converges fast for small z, the
 * alternating series 2 sum (-1)^(j-1) exp(-2 j^2 z^2) for large z. */
static double q_ks(double z)
{
    if (z <= 0)
        return 1.0;
    if (z < 1.18) {
        double y = exp(-1.23370055013616983 / (z * z)); /* pi^2 / 8 */
        double p = 2.50662827463100050 / z *            /* sqrt(2 pi) */
                   (y + pow(y, 9) + pow(y, 25) + pow(y, 49));
        return 1.0 - p;
    }
    double x = exp(-2.0 * z * z);
    return 2.0 * (x - pow(x, 4) + pow(x, 9));
}

double chi2_ks_pvalue(double d, long n)
{
    double sn = sqrt((double)n);
    return q_ks((sn + 0.12 + 0.11 / sn) * d);
}
