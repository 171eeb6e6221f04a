/*
 * spectrum.h - light as a function of wavelength (ch. 2): the CIE 1931
 * 2-degree colour-matching functions (the 1-nm table, and the analytic fit
 * of Wyman, Sloan, Shirley 2013), spectrum -> XYZ, v(lambda) and the
 * 683 lm/W of eq. (1.2), Planck's blackbody and the colour and luminous
 * efficacy of a blackbody. XYZ, RGB and adaptation are in colour.h.
 * Tests: tests/colour/test_spectrum.c; vectors: tests/vectors/colour_*.csv
 */
#ifndef SVET_SPECTRUM_H
#define SVET_SPECTRUM_H

#include "core/real.h"
#include "materials/radiance.h"
#include "colour/colour.h"
#include "core/error.h"

/* The CIE 1931 table spans 360-830 nm at 1 nm: 471 rows. */
#define SPECTRUM_LAMBDA_MIN 360
#define SPECTRUM_LAMBDA_MAX 830
#define SPECTRUM_CMF_COUNT (SPECTRUM_LAMBDA_MAX - SPECTRUM_LAMBDA_MIN + 1)

/* Planck's radiation constants from CODATA 2018, exact since the 2019 SI
 * fixed h, c and k: c1L = 2 h c^2 = 1.191042972...e-16 W m^2 / sr (the
 * constant of spectral radiance) and c2 = h c / k = 1.438776877...e-2 m K.
 * Below they are in nanometres: c1L in W nm^4 / (m^2 sr), c2 in nm K. */
#define SPECTRUM_C1L_NM 1.1910429723971884e20
#define SPECTRUM_C2_NM 1.4387768775039337e7
/* Wien's displacement constant b = c2 / 4.965114231744276... (the root of
 * x = 5 (1 - e^-x)): lambda_max T = 2.897771955e-3 m K (CODATA 2018). */
#define SPECTRUM_WIEN_B_NM 2.8977719551851727e6
/* Stefan-Boltzmann sigma = 2 pi^5 k^4 / (15 h^3 c^2) (CODATA 2018). */
#define SPECTRUM_SIGMA 5.6703744191844294e-8

/* CIE illuminant A is Planck's law with the old c2 = 1.435e-2 m K at
 * 2848 K (CIE 15:2004 sec. 3.1); with today's c2 that is 2855.50 K. */
#define SPECTRUM_ILLUMINANT_A_T (2848.0 * SPECTRUM_C2_NM / 1.435e7)

/* --- the CIE 1931 standard observer ------------------------------------- */

/* xbar, ybar, zbar at lambda (nm) from the CIE 1931 2-degree table at 1 nm
 * (CIE 018:2019, dataset DOI 10.25039/CIE.DS.xvudnb9b), interpolated
 * linearly; 0 outside 360-830 nm and for NaN. This function can't fail. */
colour_xyz_t spectrum_cmf(real lambda);

/* Row i (0..470, lambda = 360 + i nm) of the table, exactly as published.
 * An i out of range gives zeros. This function can't fail. */
colour_xyz_t spectrum_cmf_row(int i);

/* The whole table as published, in double whatever real is: 471 rows of
 * xbar, ybar, zbar (row i at 360 + i nm), for tools and for ports that
 * want the data itself. This function can't fail. */
const double *spectrum_cmf_data(void);

/* The multi-lobe piecewise-Gaussian fit of Wyman, Sloan, Shirley, "Simple
 * Analytic Approximations to the CIE XYZ Color Matching Functions", JCGT
 * 2(2), 2013, eqs. (2)-(4). Its largest error against the table over
 * 360-830 nm, measured in tests/colour/test_spectrum.c: 0.024 in zbar (at 425 nm),
 * 0.015 in xbar (631 nm), 0.008 in ybar (528 nm); integrated over a
 * blackbody of 2000-6500 K it moves the chromaticity by up to 2.4e-3.
 * Defined for every lambda (it never quite reaches 0). Can't fail. */
colour_xyz_t spectrum_cmf_wyman(real lambda);
#define SPECTRUM_WYMAN_MAX_ERROR 0.025

/* The book's v(lambda) (fig. 1.2), the photopic luminous efficiency
 * function: ybar of the table. This function can't fail. */
real spectrum_v(real lambda);

/* The chromaticity of monochromatic light of wavelength lambda: a point of
 * the spectral locus. Outside 360-830 nm gives the end points of the table.
 * This function can't fail. */
colour_xy_t spectrum_locus_xy(real lambda);

/* --- spectra and their colour ---------------------------------------------- */

/* A spectrum: a value for each wavelength in nm (radiance per nm, or a
 * reflectance), ctx is passed through. */
typedef real (*spectrum_fn)(real lambda, const void *ctx);

/* A spectrum sampled at n points lambda_min + i step, linear in between and
 * 0 outside; spectrum_sampled() is its spectrum_fn (ctx = the struct). */
typedef struct {
    real lambda_min, step; /* nm */
    int n;
    const real *value;
} spectrum_sampled_t;
real spectrum_sampled(real lambda, const void *ctx);

/* int_{360}^{830} S(lambda) {xbar, ybar, zbar} dlambda, summed at the 1-nm
 * rows of the table (CIE 15:2004 sec. 7.1). With S in W/(m^2 sr nm) this is
 * the RADIANCE-unit XYZ of colour.h. Sums run in double whatever real is:
 * 471 terms summed in float would lose up to 3e-5 relative. Can't fail. */
colour_xyz_t spectrum_to_xyz(spectrum_fn s, const void *ctx);

/* The same divided by int ybar dlambda = 106.857 nm, so that S = 1 at every
 * wavelength gives Y = 1 (and X = 1.00008, Z = 1.00033, the table's E):
 * the normalisation for reflectances and relative spectra. Can't fail. */
colour_xyz_t spectrum_to_xyz_relative(spectrum_fn s, const void *ctx);

/* The absolute photometric values, 683 times spectrum_to_xyz (eq. (1.2)):
 * Y in cd/m^2 for a radiance in W/(m^2 sr nm), in lm for a flux in W/nm.
 * Can't fail. */
colour_xyz_t spectrum_to_xyz_luminous(spectrum_fn s, const void *ctx);

/* int_{360}^{830} S dlambda at the same rows (radiant quantity). Can't fail. */
real spectrum_integral(spectrum_fn s, const void *ctx);

/* Luminous efficacy of a spectrum over the table's span:
 * K = 683 int v S / int S (lm/W). 0 if int S <= 0. Can't fail. */
real spectrum_efficacy(spectrum_fn s, const void *ctx);

/* Linear sRGB of a spectrum, in RADIANCE units (see colour.h). Can't fail. */
RADIANCE spectrum_to_rgb(spectrum_fn s, const void *ctx);

/* --- Planck's blackbody ------------------------------------------------------ */

/* Spectral radiance of a blackbody, W/(m^2 sr nm), at wavelength lambda nm
 * and temperature T K:  L = c1L / lambda^5 / (exp(c2 / (lambda T)) - 1).
 * 0 for lambda <= 0, T <= 0 or NaN. This function can't fail. */
real spectrum_planck(real lambda, real T);

/* Planck's law divided by its peak value (at Wien's lambda_max), so the
 * peak is 1. Can't fail. */
real spectrum_planck_normalised(real lambda, real T);

/* Wien's displacement law: the wavelength (nm) of the peak of
 * spectrum_planck(., T), b / T. Can't fail (T <= 0 or NaN gives
 * infinity). */
real spectrum_wien_peak(real T);

/* Total radiance of a blackbody over all wavelengths, sigma T^4 / pi,
 * W/(m^2 sr). Can't fail. */
real spectrum_blackbody_radiance(real T);

/* Luminance of a blackbody, cd/m^2: 683 int v L dlambda. Can't fail. */
real spectrum_blackbody_luminance(real T);

/* Luminous efficacy of blackbody radiation (lm/W): its luminous flux over
 * its radiant flux at all wavelengths, 683 pi int v L / (sigma T^4), the
 * number usually quoted (peak ~95 lm/W near 6600 K) - and over 360-830 nm
 * only (the "radiant watts" of colour.h). 0 for T <= 0. Can't fail. */
real spectrum_blackbody_efficacy(real T);
real spectrum_blackbody_efficacy_band(real T);

/* The colour of a blackbody: XYZ with Y = 1, its chromaticity (a point of
 * the Planckian locus), and linear sRGB with luminance 1. Below about
 * 1900 K the sRGB colour has a negative blue channel (it lies outside the
 * gamut); colour_rgb_desaturate_into_gamut() brings it in for display.
 * T <= 0 gives black. These functions can't fail. */
colour_xyz_t spectrum_blackbody_xyz(real T);
colour_xy_t spectrum_blackbody_xy(real T);
RADIANCE spectrum_blackbody_rgb(real T);

/* A white point by name for colour_adaptation_matrix(): "D65", "D50", "A",
 * "E" (colour_white_by_name) or a blackbody temperature such as "3200K" or
 * "3200" (Kelvin, 100 to 1e6). Y = 1. Fails with SVET_ERR_PARSE on
 * anything else. */
svet_status spectrum_white_parse(const char *text, colour_xyz_t *white,
                                 svet_error *err);

#endif
