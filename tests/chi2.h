/*
 * chi2.h - chi-square goodness-of-fit test of a direction sampler against
 * its pdf, as pbrt-v3 (src/tests/bsdfs.cpp) and Mitsuba 3
 * (mitsuba.chi2.ChiSquareTest) do: draw N directions, histogram them in
 * (cos theta, phi) bins, integrate the pdf over each bin for the expected
 * counts, pool bins expected to hold fewer than 5, and compare with the
 * chi-square distribution at a Sidak-corrected significance.
 */
#ifndef SVET_CHI2_H
#define SVET_CHI2_H

#include <stdbool.h>
#include "rng.h"
#include "vec.h"

/* Draw one direction: return false if the sampler produced no direction
 * (an absorbed sample); such draws count toward N but toward no bin. */
typedef bool (*chi2_sample_fn)(void *ctx, const real u[2], VECTOR3 w);
/* pdf per unit solid angle of w (0 where the sampler never goes). */
typedef double (*chi2_pdf_fn)(void *ctx, const VECTOR3 w);

typedef struct {
    int theta_bins;     /* bins in cos(theta) over [-1, 1]; default 10 */
    int phi_bins;       /* bins in phi over [0, 2 pi); default 2 * theta */
    long samples;       /* N; default 1000 * bins */
    double significance;/* alpha before the Sidak correction; default 0.01 */
    int tests;          /* number of chi-square tests in the whole suite,
                           for the Sidak correction 1 - (1 - alpha)^(1/tests) */
    uint64_t seed;
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
} chi2_result;

/* Fill defaults for every zero field of cfg. */
void chi2_config_defaults(chi2_config *cfg);

/* Run the test. The expected count of each bin is N times the pdf
 * integrated over it by adaptive Simpson / fine Gauss-Legendre quadrature
 * in (cos theta, phi). */
chi2_result chi2_test(const chi2_config *cfg, chi2_sample_fn sample,
                      chi2_pdf_fn pdf, void *ctx);

/* Regularised upper incomplete gamma Q(a, x): the chi-square p-value is
 * Q(dof/2, stat/2). (Numerical Recipes 3rd ed., sec. 6.2.) */
double chi2_gamma_q(double a, double x);

#endif
