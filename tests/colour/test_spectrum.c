/*
 * test_spectrum.c - the CIE 1931 table against CIE's checksums and
 * published rows, the spectral locus against CIE's chromaticity table, the
 * error of the Wyman-Sloan-Shirley fit, Planck's law against Wien's and
 * Stefan-Boltzmann's laws, illuminant A, the Planckian locus of Kim et al.,
 * the published luminous efficacy of blackbody radiation, and the CSV
 * vectors of tests/vectors/colour_cmf.csv and colour_blackbody.csv.
 */
#include "testutil.h"
#include "colour/spectrum.h"

#include <math.h>
#include <string.h>

#ifdef SVET_DOUBLE
#define TOL "tol_double"
#define SUFFIX "double"
#else
#define TOL "tol_float"
#define SUFFIX "float"
#endif

static real constant_one(real lambda, const void *ctx)
{
    (void)lambda;
    (void)ctx;
    return 1;
}

/* Planck's law at the temperature *ctx (a real), for spectrum_fn */
static real blackbody(real lambda, const void *ctx)
{
    return spectrum_planck(lambda, *(const real *)ctx);
}

/* --- the table ------------------------------------------------------------ */

START_TEST(table_sums_match_cie_checksums)
{
    /* CIE 15:2004 sec. 7.2 / CIE 018:2019 give the sums of the 1-nm columns
     * 360-830 nm: 106.865469489595, 106.856917101172, 106.892251278636.
     * Tolerance: each of 471 values rounded to real (half an ulp of at most
     * 1.78), summed in double. */
    double s[3] = { 0, 0, 0 };
    for (int i = 0; i < SPECTRUM_CMF_COUNT; i++) {
        colour_xyz_t c = spectrum_cmf_row(i);
        s[0] += (double)c.X;
        s[1] += (double)c.Y;
        s[2] += (double)c.Z;
    }
    double tol = 471 * 1.78 * (double)REAL_UNIT_ROUNDOFF + 1e-11;
    ck_assert_near(s[0], 106.865469489595, tol);
    ck_assert_near(s[1], 106.856917101172, tol);
    ck_assert_near(s[2], 106.892251278636, tol);
    colour_xyz_t out = spectrum_cmf_row(SPECTRUM_CMF_COUNT);
    ck_assert(out.X == 0 && out.Y == 0 && out.Z == 0);
    out = spectrum_cmf_row(-1);
    ck_assert(out.X == 0 && out.Y == 0 && out.Z == 0);
}
END_TEST

START_TEST(table_matches_published_rows_and_the_fit_its_formula)
{
    testcsv_t c;
    long n = 0;
    testcsv_open(&c, "colour_cmf.csv");
    while (testcsv_next(&c)) {
        real lambda = (real)testcsv_num(&c, "lambda");
        double tol = testcsv_num(&c, TOL);
        colour_xyz_t t = spectrum_cmf(lambda);
        ck_assert_near(t.X, testcsv_num(&c, "xbar"), tol);
        ck_assert_near(t.Y, testcsv_num(&c, "ybar"), tol);
        ck_assert_near(t.Z, testcsv_num(&c, "zbar"), tol);
        colour_xyz_t w = spectrum_cmf_wyman(lambda);
        ck_assert_near(w.X, testcsv_num(&c, "wx"), tol);
        ck_assert_near(w.Y, testcsv_num(&c, "wy"), tol);
        ck_assert_near(w.Z, testcsv_num(&c, "wz"), tol);
        n++;
    }
    testcsv_close(&c);
    ck_assert(n >= 20);
    test_report_cases("table_matches_published_rows_and_the_fit_its_formula", n);
}
END_TEST

START_TEST(lookup_interpolates_linearly_and_is_zero_outside)
{
    colour_xyz_t a = spectrum_cmf_row(195), b = spectrum_cmf_row(196); /* 555, 556 */
    colour_xyz_t m = spectrum_cmf(REAL_C(555.25));
    ck_assert_near(m.X, REAL_C(0.75) * a.X + REAL_C(0.25) * b.X, 4 * REAL_EPSILON);
    ck_assert_near(m.Z, REAL_C(0.75) * a.Z + REAL_C(0.25) * b.Z, 4 * REAL_EPSILON);
    colour_xyz_t end = spectrum_cmf(830), last = spectrum_cmf_row(470);
    ck_assert(end.X == last.X && end.Y == last.Y);
    const real outside[4] = { REAL_C(359.999), REAL_C(830.001), -1, NAN };
    for (int k = 0; k < 4; k++) {
        colour_xyz_t o = spectrum_cmf(outside[k]);
        ck_assert(o.X == 0 && o.Y == 0 && o.Z == 0);
    }
    /* v(lambda) of eq. (1.2) is ybar: 1 at 555 nm, its maximum */
    ck_assert_near(spectrum_v(555), 1, 0);
    for (int i = 0; i < SPECTRUM_CMF_COUNT; i++)
        ck_assert(spectrum_cmf_row(i).Y <= 1);
}
END_TEST

START_TEST(wyman_fit_error_is_as_stated)
{
    /* The largest |fit - table| over the 471 rows, per function. The
     * header promises SPECTRUM_WYMAN_MAX_ERROR; we also require the bound
     * to be tight (the error really reaches 80% of it), so the stated
     * figure stays honest. Then what it does to colour: the chromaticity
     * of blackbodies integrated with the fit instead of the table. */
    double e[3] = { 0, 0, 0 };
    int at[3] = { 0, 0, 0 };
    for (int i = 0; i < SPECTRUM_CMF_COUNT; i++) {
        colour_xyz_t t = spectrum_cmf_row(i);
        colour_xyz_t w = spectrum_cmf_wyman((real)(SPECTRUM_LAMBDA_MIN + i));
        double d[3] = { fabs((double)(w.X - t.X)), fabs((double)(w.Y - t.Y)),
                        fabs((double)(w.Z - t.Z)) };
        for (int k = 0; k < 3; k++)
            if (d[k] > e[k]) {
                e[k] = d[k];
                at[k] = SPECTRUM_LAMBDA_MIN + i;
            }
    }
    printf("  wyman fit max |error|: xbar %.4f at %d nm, ybar %.4f at %d nm, "
           "zbar %.4f at %d nm\n", e[0], at[0], e[1], at[1], e[2], at[2]);
    double emax = fmax(e[0], fmax(e[1], e[2]));
    ck_assert(emax <= SPECTRUM_WYMAN_MAX_ERROR);
    ck_assert(emax >= 0.8 * SPECTRUM_WYMAN_MAX_ERROR);
    const real temps[3] = { 2000, REAL_C(2855.5), 6500 };
    double worst = 0;
    for (int k = 0; k < 3; k++) {
        double s[3] = { 0, 0, 0 }, f[3] = { 0, 0, 0 };
        for (int i = 0; i < SPECTRUM_CMF_COUNT; i++) {
            real lambda = (real)(SPECTRUM_LAMBDA_MIN + i);
            double L = (double)spectrum_planck(lambda, temps[k]);
            colour_xyz_t t = spectrum_cmf_row(i), w = spectrum_cmf_wyman(lambda);
            s[0] += L * (double)t.X; s[1] += L * (double)t.Y; s[2] += L * (double)t.Z;
            f[0] += L * (double)w.X; f[1] += L * (double)w.Y; f[2] += L * (double)w.Z;
        }
        double dx = s[0] / (s[0] + s[1] + s[2]) - f[0] / (f[0] + f[1] + f[2]);
        double dy = s[1] / (s[0] + s[1] + s[2]) - f[1] / (f[0] + f[1] + f[2]);
        worst = fmax(worst, fmax(fabs(dx), fabs(dy)));
    }
    printf("  wyman fit: blackbody chromaticity error up to %.1e (2000-6500 K)\n", worst);
    ck_assert(worst < 3e-3);
}
END_TEST

START_TEST(spectral_locus_matches_cie_chromaticities)
{
    /* CIE 018:2019 "CIE 1931 chromaticity coordinates of spectrum loci,
     * 2 degree observer" (DOI 10.25039/CIE.DS.mifmy4x4), 6 decimals */
    static const struct {
        real lambda;
        double x, y;
    } pts[] = { { 360, 0.175560, 0.005294 }, { 380, 0.174112, 0.004964 },
                { 520, 0.074302, 0.833803 }, { 780, 0.734690, 0.265310 },
                { 830, 0.734690, 0.265310 } };
    for (size_t k = 0; k < sizeof pts / sizeof pts[0]; k++) {
        colour_xy_t c = spectrum_locus_xy(pts[k].lambda);
        ck_assert_near(c.x, pts[k].x, 5e-7 + 4 * (double)REAL_EPSILON);
        ck_assert_near(c.y, pts[k].y, 5e-7 + 4 * (double)REAL_EPSILON);
    }
    /* beyond the table: its end points */
    colour_xy_t lo = spectrum_locus_xy(100), hi = spectrum_locus_xy(2000);
    ck_assert_near(lo.x, 0.175560, 1e-6);
    ck_assert_near(hi.x, 0.734690, 1e-6);
    /* the CIE RGB primaries of colour.c are the locus at 700, 546.1 and
     * 435.8 nm */
    colour_space_t s;
    colour_space_standard(&s, COLOUR_SPACE_CIE_RGB);
    const real lam[3] = { 700, REAL_C(546.1), REAL_C(435.8) };
    const colour_xy_t p[3] = { s.red, s.green, s.blue };
    for (int k = 0; k < 3; k++) {
        colour_xy_t c = spectrum_locus_xy(lam[k]);
        ck_assert_near(c.x, p[k].x, 1e-9 + 8 * (double)REAL_EPSILON);
        ck_assert_near(c.y, p[k].y, 1e-9 + 8 * (double)REAL_EPSILON);
    }
}
END_TEST

/* --- spectra -> XYZ ------------------------------------------------------- */

START_TEST(constant_spectrum_is_white_e)
{
    /* S = 1: Y = 1 by the normalisation; x, y differ from 1/3 by the
     * difference of the table's column sums (CIE checksums above, less
     * half the end rows for the trapezoid rule):
     * x = 106.86540 / 320.61427 = 0.3333146, y = 0.3332881. */
    colour_xyz_t r = spectrum_to_xyz_relative(constant_one, NULL);
    ck_assert_near(r.Y, 1, 4 * REAL_EPSILON);
    colour_xy_t c = colour_xyz_to_xy(r);
    ck_assert_near(c.x, 1.0 / 3, 1e-4);
    ck_assert_near(c.y, 1.0 / 3, 1e-4);
    ck_assert_near(c.x, 0.3333146, 1e-6);
    ck_assert_near(c.y, 0.3332881, 1e-6);
    /* absolute: int ybar = 106.857 nm, so 1 W/(m^2 sr nm) is 683 * 106.857
     * cd/m^2 (eq. (1.2)); over 470 nm of radiant power that is an efficacy
     * of 683 * 106.857 / 470 = 155.28 lm/W */
    ck_assert_near(spectrum_to_xyz_luminous(constant_one, NULL).Y,
                   683 * 106.856917101172, 1e-2);
    ck_assert_near(spectrum_integral(constant_one, NULL), 470, 1e-4);
    ck_assert_near(spectrum_efficacy(constant_one, NULL), 155.2836, 1e-3);
}
END_TEST

START_TEST(light_at_555_nm_gives_683_lumens_per_watt)
{
    /* eq. (1.2): a 1-nm-wide triangle of area 1 W/nm at 555 nm */
    static const real tri[3] = { 0, 1, 0 };
    spectrum_sampled_t s = { 554, 1, 3, tri };
    ck_assert_near(spectrum_integral(spectrum_sampled, &s), 1, 1e-6);
    ck_assert_near(spectrum_to_xyz_luminous(spectrum_sampled, &s).Y, 683, 1e-3);
    ck_assert_near(spectrum_efficacy(spectrum_sampled, &s), 683, 1e-3);
    /* the sampled spectrum interpolates and is 0 outside */
    ck_assert_near(spectrum_sampled(REAL_C(554.5), &s), 0.5, 1e-6);
    ck_assert_near(spectrum_sampled(553, &s), 0, 0);
    ck_assert_near(spectrum_sampled(557, &s), 0, 0);
    ck_assert_near(spectrum_sampled(NAN, &s), 0, 0);
    spectrum_sampled_t bad = { 554, 0, 3, tri };
    ck_assert_near(spectrum_sampled(555, &bad), 0, 0);
    /* its RGB: the colour of 555-nm light, luminance 1 */
    RADIANCE c = spectrum_to_rgb(spectrum_sampled, &s);
    ck_assert_near(colour_luminance(c), 1, 1e-5);
}
END_TEST

/* --- Planck ------------------------------------------------------------------ */

START_TEST(planck_peaks_where_wien_says)
{
    /* CODATA 2018: b = 2.897771955e-3 m K */
    ck_assert_rel(spectrum_wien_peak(1), 2.897771955e6, 1e-9 + (double)REAL_EPSILON, 0);
    /* golden-section search for the maximum of spectrum_planck. Its flat
     * top limits the argmax to about sqrt(epsilon) relative. */
    const real temps[6] = { 300, 1000, 2856, 5778, 10000, 30000 };
    for (int k = 0; k < 6; k++) {
        double T = (double)temps[k], lo = 0.5e6 / T, hi = 6e6 / T;
        const double g = 0.6180339887498949;
        for (int it = 0; it < 200; it++) {
            double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
            if (spectrum_planck((real)a, temps[k]) < spectrum_planck((real)b, temps[k]))
                lo = a;
            else
                hi = b;
        }
        double peak = 0.5 * (lo + hi);
        ck_assert_rel(peak, spectrum_wien_peak(temps[k]),
                      4 * sqrt((double)REAL_EPSILON), 0);
        ck_assert_near(spectrum_planck_normalised((real)peak, temps[k]), 1,
                       16 * REAL_EPSILON);
    }
    test_report_cases("planck_peaks_where_wien_says", 6);
}
END_TEST

START_TEST(planck_integrates_to_stefan_boltzmann)
{
    /* int_0^inf L dlambda = sigma T^4 / pi: c1 and c2 against sigma (all
     * from CODATA 2018). Simpson's rule in u = ln(lambda) from 10 nm to
     * 1e7 nm (the tails beyond hold < 1e-9 of the total at these T):
     * 20000 panels, error far below the 1e-7 asked. */
    const real temps[3] = { 1000, 5778, 20000 };
    for (int k = 0; k < 3; k++) {
        const int n = 20000;
        double a = log(10.0), b = log(1e7), h = (b - a) / n, s = 0;
        for (int i = 0; i <= n; i++) {
            double lambda = exp(a + i * h);
            double f = (double)spectrum_planck((real)lambda, temps[k]) * lambda;
            s += f * (i == 0 || i == n ? 1 : i % 2 ? 4 : 2);
        }
        s *= h / 3;
        ck_assert_rel(s, spectrum_blackbody_radiance(temps[k]), 1e-6, 0);
    }
}
END_TEST

START_TEST(planck_survives_extreme_input)
{
    ck_assert_near(spectrum_planck(500, 0), 0, 0);
    ck_assert_near(spectrum_planck(500, -5), 0, 0);
    ck_assert_near(spectrum_planck(0, 5000), 0, 0);
    ck_assert_near(spectrum_planck(NAN, 5000), 0, 0);
    ck_assert(spectrum_planck(360, 1) == 0); /* underflows to 0, no NaN */
    ck_assert(isfinite(spectrum_planck(830, REAL_C(1e9))));
    const real temps[6] = { REAL_C(1e-3), 1, 50, 200, REAL_C(1e8), REAL_MAX };
    for (int k = 0; k < 6; k++) {
        colour_xy_t c = spectrum_blackbody_xy(temps[k]);
        ck_assert(isfinite(c.x) && isfinite(c.y));
        ck_assert(c.x > REAL_C(0.2) && c.x < REAL_C(0.75));
        real K = spectrum_blackbody_efficacy_band(temps[k]);
        ck_assert(isfinite(K) && K >= 0 && K < 683);
    }
    /* T -> 0: the red end of the table; T -> inf: Rayleigh-Jeans, L ~
     * lambda^-4, which sits at (0.2399, 0.2342) */
    colour_xy_t cold = spectrum_blackbody_xy(1), hot = spectrum_blackbody_xy(REAL_C(1e9));
    ck_assert_near(cold.x, 0.734690, 1e-5);
    ck_assert_near(hot.x, 0.2399, 2e-4);
    ck_assert_near(hot.y, 0.2342, 2e-4);
    colour_xyz_t black = spectrum_blackbody_xyz(NAN);
    ck_assert(black.Y == 0);
    ck_assert(spectrum_blackbody_efficacy(0) == 0);
    ck_assert(isinf(spectrum_wien_peak(0)) && isinf(spectrum_wien_peak(-3)));
    ck_assert(spectrum_planck_normalised(500, -1) == 0);
}
END_TEST

START_TEST(illuminant_a_is_planck_at_2856_k)
{
    /* CIE 15:2004 Table T.3: A = (0.44757, 0.40745). A is Planck's law with
     * c2 = 1.435e-2 at 2848 K; our 1-nm, 360-830 nm integration gives
     * (0.447574, 0.407439): within 1.5e-5 of the 5-decimal figure. */
    colour_xy_t a = spectrum_blackbody_xy((real)SPECTRUM_ILLUMINANT_A_T);
    ck_assert_near(a.x, 0.44757, 1.5e-5);
    ck_assert_near(a.y, 0.40745, 1.5e-5);
    ck_assert_near(SPECTRUM_ILLUMINANT_A_T, 2855.50, 0.01);
    /* and the named white A of colour.h agrees */
    colour_xy_t w = colour_white_xy(COLOUR_WHITE_A);
    ck_assert_near(a.x, w.x, 1.5e-5);
    ck_assert_near(a.y, w.y, 1.5e-5);
}
END_TEST

START_TEST(planckian_locus_matches_kim_et_al)
{
    /* Kim et al. (2002; US patent 7,024,034): cubic splines for the
     * Planckian locus, 1667-25000 K. An independent script (Planck and the
     * CIE table in Python) puts the fit within 5.6e-4 of the exact locus
     * (at 2612 K); 1e-3 leaves room without hiding a real error, which
     * would be a shift along the locus of ~100 K. */
    long n = 0;
    for (double T = 1667; T <= 25000; T *= 1.01, n++) {
        double t = 1e3 / T, x, y;
        if (T <= 4000)
            x = ((-0.2661239 * t - 0.2343589) * t + 0.8776956) * t + 0.179910;
        else
            x = ((-3.0258469 * t + 2.1070379) * t + 0.2226347) * t + 0.240390;
        if (T <= 2222)
            y = ((-1.1063814 * x - 1.34811020) * x + 2.18555832) * x - 0.20219683;
        else if (T <= 4000)
            y = ((-0.9549476 * x - 1.37418593) * x + 2.09137015) * x - 0.16748867;
        else
            y = ((3.0817580 * x - 5.87338670) * x + 3.75112997) * x - 0.37001483;
        colour_xy_t c = spectrum_blackbody_xy((real)T);
        ck_assert_near(c.x, x, 1e-3);
        ck_assert_near(c.y, y, 1e-3);
    }
    test_report_cases("planckian_locus_matches_kim_et_al", n);
}
END_TEST

START_TEST(blackbody_efficacy_matches_published_values)
{
    /* Wikipedia, "Luminous efficacy", quoting D. L. Klipstein: an ideal
     * thermal radiator is most efficient near 6600 K, at a theoretical
     * 95 lm/W. We find the maximum by scanning 3000-12000 K by 10 K. */
    double best = 0, best_T = 0;
    for (double T = 3000; T <= 12000; T += 10) {
        double K = (double)spectrum_blackbody_efficacy((real)T);
        if (K > best) {
            best = K;
            best_T = T;
        }
    }
    printf("  blackbody efficacy peaks at %.0f K: %.2f lm/W\n", best_T, best);
    ck_assert_near(best, 95, 1);
    ck_assert_near(best_T, 6600, 150);
    /* The same table: "truncated 5800 K blackbody" (400-700 nm only),
     * 251 lm/W. A rounded figure of unstated V(lambda) data: 1%. */
    real T = 5800;
    double v = 0, e = 0;
    for (int l = 400; l <= 700; l++) {
        double w = (l == 400 || l == 700) ? 0.5 : 1;
        double L = w * (double)spectrum_planck((real)l, T);
        v += L * (double)spectrum_v((real)l);
        e += L;
    }
    ck_assert_rel(683 * v / e, 251, 0.01, 0);
    /* incandescent light: 2856 K radiates 16.4 lm/W of its total power
     * (computed by an independent script: Planck, the CIE table, 1 nm) */
    ck_assert_near(spectrum_blackbody_efficacy(REAL_C(2856.0)), 16.45, 0.01);
}
END_TEST

START_TEST(blackbody_matches_the_vectors)
{
    testcsv_t c;
    long n = 0;
    testcsv_open(&c, "colour_blackbody.csv");
    while (testcsv_next(&c)) {
        real T = (real)testcsv_num(&c, "T");
        double txy = testcsv_num(&c, "tol_xy_" SUFFIX);
        double trel = testcsv_num(&c, "tol_rel_" SUFFIX);
        colour_xy_t xy = spectrum_blackbody_xy(T);
        ck_assert_near(xy.x, testcsv_num(&c, "x"), txy);
        ck_assert_near(xy.y, testcsv_num(&c, "y"), txy);
        ck_assert_rel(spectrum_blackbody_luminance(T), testcsv_num(&c, "luminance"), trel, 0);
        ck_assert_rel(spectrum_blackbody_efficacy(T), testcsv_num(&c, "efficacy"), trel, 0);
        ck_assert_rel(spectrum_blackbody_efficacy_band(T),
                      testcsv_num(&c, "efficacy_band"), trel, 0);
        real lmax = spectrum_wien_peak(T);
        ck_assert_rel(lmax, testcsv_num(&c, "lambda_max"), trel, 0);
        ck_assert_rel(spectrum_planck((real)testcsv_num(&c, "lambda_max"), T),
                      testcsv_num(&c, "L_max"), 4 * trel, 0);
        /* the band efficacy is also spectrum_efficacy of Planck's law */
        ck_assert_rel(spectrum_efficacy(blackbody, &T),
                      testcsv_num(&c, "efficacy_band"), 4 * trel, 0);
        n++;
    }
    testcsv_close(&c);
    ck_assert(n >= 15);
    test_report_cases("blackbody_matches_the_vectors", n);
}
END_TEST

START_TEST(blackbody_rgb_is_in_gamut_above_1900_k)
{
    /* The Planckian locus leaves the sRGB triangle through its red-green
     * side near 1900 K (blue < 0 below); everything hotter is inside. */
    for (real T = 1000; T < 1850; T += 50)
        ck_assert(spectrum_blackbody_rgb(T).b < 0);
    long n = 0;
    for (real T = 1950; T <= REAL_C(1e6); T *= REAL_C(1.05), n++) {
        RADIANCE c = spectrum_blackbody_rgb(T);
        ck_assert(c.r > 0 && c.g > 0 && c.b > 0);
        ck_assert_near(colour_luminance(c), 1, 1e-5);
    }
    /* 6504 K is close to the D65 white: all channels within 5% */
    RADIANCE d = spectrum_blackbody_rgb(6504);
    ck_assert_near(d.r, 1, 0.05);
    ck_assert_near(d.b, 1, 0.05);
    test_report_cases("blackbody_rgb_is_in_gamut_above_1900_k", n);
}
END_TEST

START_TEST(white_points_parse_by_name_or_temperature)
{
    colour_xyz_t w;
    svet_error err;
    ck_assert_int_eq(spectrum_white_parse("D50", &w, &err), SVET_OK);
    ck_assert_near(w.X, colour_white_xyz(COLOUR_WHITE_D50).X, 0);
    ck_assert_int_eq(spectrum_white_parse("3200K", &w, &err), SVET_OK);
    colour_xyz_t b = spectrum_blackbody_xyz(3200);
    ck_assert_near(w.X, b.X, 0);
    ck_assert_near(w.Y, 1, 0);
    ck_assert_int_eq(spectrum_white_parse("6500", &w, &err), SVET_OK);
    ck_assert_int_eq(spectrum_white_parse("6500 K", &w, &err), SVET_ERR_PARSE);
    ck_assert_int_eq(spectrum_white_parse("hot", &w, &err), SVET_ERR_PARSE);
    ck_assert(strstr(err.msg, "hot") != NULL);
    ck_assert_int_eq(spectrum_white_parse("5K", &w, &err), SVET_ERR_RANGE);
    ck_assert_int_eq(spectrum_white_parse("nanK", &w, &err), SVET_ERR_RANGE);
    ck_assert_int_eq(spectrum_white_parse(NULL, &w, NULL), SVET_ERR_PARSE);
    /* an adaptation from a parsed blackbody white lands on D65 */
    colour_mat3_t m;
    ck_assert_int_eq(spectrum_white_parse("2700K", &w, &err), SVET_OK);
    ck_assert(colour_adaptation_matrix(&m, COLOUR_ADAPT_BRADFORD, w,
                                       colour_white_xyz(COLOUR_WHITE_D65)));
    RADIANCE r = colour_xyz_to_rgb(colour_mat3_apply(&m, w));
    ck_assert_near(r.r, 1, 1e-5);
    ck_assert_near(r.g, 1, 1e-5);
    ck_assert_near(r.b, 1, 1e-5);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("spectrum");
    TCase *tc = tcase_create("observer");
    tcase_add_test(tc, table_sums_match_cie_checksums);
    tcase_add_test(tc, table_matches_published_rows_and_the_fit_its_formula);
    tcase_add_test(tc, lookup_interpolates_linearly_and_is_zero_outside);
    tcase_add_test(tc, wyman_fit_error_is_as_stated);
    tcase_add_test(tc, spectral_locus_matches_cie_chromaticities);
    tcase_add_test(tc, constant_spectrum_is_white_e);
    tcase_add_test(tc, light_at_555_nm_gives_683_lumens_per_watt);
    suite_add_tcase(s, tc);
    tc = tcase_create("planck");
    tcase_add_test(tc, planck_peaks_where_wien_says);
    tcase_add_test(tc, planck_integrates_to_stefan_boltzmann);
    tcase_add_test(tc, planck_survives_extreme_input);
    tcase_add_test(tc, illuminant_a_is_planck_at_2856_k);
    tcase_add_test(tc, planckian_locus_matches_kim_et_al);
    tcase_add_test(tc, blackbody_efficacy_matches_published_values);
    tcase_add_test(tc, blackbody_matches_the_vectors);
    tcase_add_test(tc, blackbody_rgb_is_in_gamut_above_1900_k);
    tcase_add_test(tc, white_points_parse_by_name_or_temperature);
    suite_add_tcase(s, tc);
    return s;
}
