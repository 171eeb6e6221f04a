/*
 * chi2.h - chi-square goodness-of-fit test of a direction sampler against
 * its pdf, as pbrt-v3 (src/tests/bsdfs.cpp) and Mitsuba 3
 * (mitsuba.chi2.ChiSquareTest) do: draw N directions, histogram them in
 * (cos theta, phi) bins, integrate the pdf over each bin for the expected
 * counts, pool bins expected to hold fewer than 5, and compare with the
 * chi-square distribution at a Sidak-corrected significance. Also the
 * Kolmogorov-Smirnov test for 1D samples (ch. 4's point samplers).
 * Implementation: tests/chi2.c; its own tests: tests/core/test_sample.c.
 */
#ifndef SVET_CHI2_H
#define SVET_CHI2_H

#include <math.h>
#include <stdbool.h>
#include "core/rng.h"
#include "core/vec.h"

/* Draw one direction: return false if the sampler produced no direction
 * (an absorbed sample); such draws count toward N but toward no bin. They
 * form one extra cell whose expected count is N (1 - pdf integral). */
typedef bool (*chi2_sample_fn)(void *ctx, const real u[2], VECTOR3 w);
/* pdf per unit solid angle of w (0 where the sampler never goes). */
typedef double (*chi2_pdf_fn)(void *ctx, const VECTOR3 w);

typedef struct {
    int theta_bins;     /* bins in cos(theta) over [-1, 1]; default 10 */
    int phi_bins;       /* bins in phi over [0, 2 pi); default 2 * theta */
    long samples;       /* N; default 1000 * bins */
    double significance;/* alpha before the Sidak correction; default 0.01 */
    int tests;          /* number of chi-square tests in the whole suite,
                           for the Sidak correction 1 - (1 - alpha)^(1/tests);
                           default 1 */
    uint64_t seed;
    double cap_height;  /* zoom: the cos(theta) bins cover only the cap
                           [1 - cap_height, 1] about +z; every direction
                           below it falls into one extra cell, integrated
                           likewise. 0 (the default) means 2: the whole
                           sphere. Use it to resolve a sharp lobe about +z,
                           e.g. cap_height = 10 / e for a Phong lobe of
                           exponent e, 20 alpha^2 for Ward's half vector. */
} chi2_config;

typedef struct {
    bool passed;
    double statistic;   /* the chi-square statistic */
    int dof;            /* degrees of freedom after pooling */
    double p_value;     /* P(X >= statistic) for X ~ chi2(dof) */
    double threshold;   /* Sidak-corrected significance it was compared to */
    double pdf_integral;/* integral of the pdf over the sphere: 1 for a
                           normalised sampler that is never absorbed */
    char message[256];
    /* --- added fields: diagnostics ----------------------------------- */
    double quad_error;  /* estimated absolute error of pdf_integral (sum
                           of the adaptive quadrature's error estimates) */
    long absorbed;      /* draws for which the sampler returned false */
    long invalid;       /* draws that returned a NaN/Inf or non-unit w */
    long bad_pdf;       /* pdf evaluations that were negative or NaN/Inf */
    int pooled_in;      /* low-expectation cells pooled ... */
    int pooled_out;     /* ... into this many cells */
} chi2_result;

/* Fill defaults for every zero field of cfg. This function can't fail. */
void chi2_config_defaults(chi2_config *cfg);

/* Run the test. The expected count of each bin is N times the pdf
 * integrated over it by adaptive Gauss-Legendre cubature in
 * (cos theta, phi): each bin is split at least twice in each direction
 * (4 x 4 cells, 5 x 5 nodes each), then cells whose estimate changes by more
 * than 1e-7 (absolute, shared out by area) + 1e-4 in float, 1e-7 in double
 * (relative: above the rounding of a pdf evaluated at a float direction)
 * when halved are halved again, down to 2^-14 of a bin or 2e5 pdf calls per
 * bin (the message then says "quadrature unresolved": a pdf with a step
 * inside a bin, or float noise; the counts are still good to ~1e-4). Bins
 * touching a pole, and the region below the cap, are cut into bands that
 * shrink geometrically toward the pole / cap edge. Limit: a feature narrower
 * than about 1/20 of a bin, away from the poles, that no node sees at
 * depth 2 is missed; its samples then land in bins expected to be (nearly)
 * empty and the test fails rather than passing wrongly. Put steps of the
 * pdf on bin edges, and zoom with cap_height for lobes about +z.
 * Fails (passed = false, reason in message) on: p-value below the Sidak
 * threshold; a NaN, Inf or non-unit sample; a negative or non-finite pdf;
 * more than 1e-5 N samples in cells of zero expectation (pbrt-v3's
 * allowance for rounding at the edge of the support); fewer than 1 degree
 * of freedom; a pdf integral above 1 + 1e-3. */
chi2_result chi2_test(const chi2_config *cfg, chi2_sample_fn sample,
                      chi2_pdf_fn pdf, void *ctx);

/* The chi-square test of any histogram: observed and expected counts of n
 * cells that each sum to the same N. Cells are sorted by expected count; those
 * below 5 are pooled in that order into groups of expectation >= 5 (Mitsuba
 * 3, mitsuba/core/math.h chi2(); an under-filled last group joins the next
 * cell instead of being dropped). dof = cells after pooling - 1. Uses
 * cfg->significance and cfg->tests (zero fields take their defaults).
 * The arrays are not modified. Fails as chi2_test for zero-expectation cells
 * and low dof. */
chi2_result chi2_from_counts(const double *observed, const double *expected,
                             int n, const chi2_config *cfg);

/* Integral of pdf over the whole sphere by the same adaptive cubature, in
 * bands of cos(theta) halving in width toward both poles (down to 2^-44)
 * and, when cap_height is in (0, 2), toward the cap's edge 1 - cap_height
 * from both sides; 24 cells in phi. *err (if not NULL) receives the error
 * estimate. This function can't fail. */
double chi2_pdf_integral(chi2_pdf_fn pdf, void *ctx, double cap_height,
                         double *err);

/* Assert (check) that pdf integrates to 1 within tol over the sphere. */
#define chi2_assert_pdf_normalised(pdf, ctx, cap_height, tol)                 \
    do {                                                                      \
        double e_, i_ = chi2_pdf_integral(pdf, ctx, cap_height, &e_);         \
        ck_assert_msg(fabs(i_ - 1.0) <= (double)(tol),                        \
                      "pdf integrates to %.9g (quadrature error %.2g), "      \
                      "not 1 within %.2g",                                    \
                      i_, e_, (double)(tol));                                 \
    } while (0)

/* Regularised upper incomplete gamma Q(a, x) for a > 0, x >= 0: the
 * chi-square p-value is Q(dof/2, stat/2). Series for x < a + 1, Lentz's
 * continued fraction otherwise (Numerical Recipes 3rd ed., sec. 6.2).
 * Returns NaN for a <= 0 or x < 0 (or NaN arguments). */
double chi2_gamma_q(double a, double x);

/* --- Kolmogorov-Smirnov, for samples of a known 1D distribution ---------- */

typedef double (*chi2_cdf_fn)(void *ctx, double x);

/* The KS statistic D = sup |F_n(x) - F(x)| of the n values x (sorted in
 * place) against the cdf F. This function can't fail. */
double chi2_ks_statistic(double *x, long n, chi2_cdf_fn cdf, void *ctx);

/* P(D_n >= d) for a true F: the Kolmogorov distribution Q_KS(z) at
 * z = (sqrt(n) + 0.12 + 0.11 / sqrt(n)) d (Stephens 1970; Numerical
 * Recipes 3rd ed., secs. 6.14 and 14.3.3). */
double chi2_ks_pvalue(double d, long n);

/* Sidak-corrected threshold 1 - (1 - alpha)^(1/tests). */
double chi2_sidak(double alpha, int tests);

#endif
