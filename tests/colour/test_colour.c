/*
 * test_colour.c - the sRGB transfer curve and matrices against IEC
 * 61966-2-1; Rec. 2020, Adobe RGB and CIE RGB against their standards;
 * white points against the CIE daylight locus; Bradford and von Kries
 * against published matrices; L*a*b*, gamut mapping and photometric lights
 * by their defining properties; the CSV vectors of tests/vectors/colour_*.
 */
#include "testutil.h"
#include "colour/colour.h"
#include "core/rng.h"

#include <math.h>
#include <string.h>

/* Tolerance for a value derived in real arithmetic through a few 3x3
 * products and one inversion of a matrix with condition number < 50:
 * 64 ulp of 1, plus the 10 digits of the COLOUR_SRGB_* literals. */
#define DERIVED_TOL (64 * (double)REAL_EPSILON + 1e-9)

static void assert_mat_near(const colour_mat3_t *a, const double b[3][3],
                            double tol)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            ck_assert_msg(fabs((double)a->m[i][j] - b[i][j]) <= tol,
                          "[%d][%d]: %.9g vs %.9g (tol %.3g)", i, j,
                          (double)a->m[i][j], b[i][j], tol);
}

static void assert_mat_equal(const colour_mat3_t *a, const colour_mat3_t *b,
                             double tol)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            ck_assert_msg(fabs((double)(a->m[i][j] - b->m[i][j])) <= tol,
                          "[%d][%d]: %.9g vs %.9g (tol %.3g)", i, j,
                          (double)a->m[i][j], (double)b->m[i][j], tol);
}

/* --- the transfer curve ---------------------------------------------------- */

START_TEST(srgb_curve_matches_iec_61966_2_1)
{
    /* IEC 61966-2-1: the two pieces meet at linear 0.0031308 = code
     * 0.04045; 1 maps to 1; 0.18 (mid grey) to 0.46135 (1.055 * 0.18^(1/2.4)
     * - 0.055 evaluated to 30 digits). */
    ck_assert_near(colour_srgb_encode(0), 0, 0);
    ck_assert_near(colour_srgb_encode(1), 1, 4 * REAL_EPSILON);
    ck_assert_near(colour_srgb_encode(REAL_C(0.0031308)), 0.0404499075, 1e-6);
    ck_assert_near(colour_srgb_encode(REAL_C(0.18)), 0.461356129, 1e-6);
    ck_assert_near(colour_srgb_decode(REAL_C(0.5)), 0.214041140, 1e-6);
    ck_assert_near(colour_srgb_decode(-REAL_C(0.5)), -0.214041140, 1e-6);
    ck_assert_int_eq(colour_srgb_encode_byte(REAL_C(0.18)), 118);
    ck_assert_int_eq(colour_srgb_encode_byte(-1), 0);
    ck_assert_int_eq(colour_srgb_encode_byte(NAN), 0);
    ck_assert_int_eq(colour_srgb_encode_byte(2), 255);
    ck_assert(isnan(colour_srgb_encode(NAN)));
}
END_TEST

START_TEST(srgb_curve_round_trips_every_byte)
{
    for (int i = 0; i < 256; i++)
        ck_assert_int_eq(colour_srgb_encode_byte(colour_srgb_decode_byte(
                             (uint8_t)i)), i);
    /* and the real curve, across the junction and out of gamut */
    long n = 0;
    for (real v = REAL_C(-2.0); v <= 2; v += REAL_C(0.001), n++)
        ck_assert_near(colour_srgb_decode(colour_srgb_encode(v)), v,
                       8 * (double)REAL_EPSILON * fmax(1, (double)fabs(v)));
    test_report_cases("srgb_curve_round_trips_every_byte", 256 + n);
}
END_TEST

/* --- sRGB and the other RGB spaces ---------------------------------------- */

START_TEST(srgb_matrices_match_iec_61966_2_1)
{
    /* IEC 61966-2-1:1999 eqs. (5.6) and (5.7), printed to 4 decimals. The
     * RGB -> XYZ matrix is the exact one rounded (tol: half a unit of the
     * 4th decimal). The printed XYZ -> RGB was inverted from the rounded
     * forward matrix, so it differs from the exact inverse by up to 3.7e-4
     * (3.2406 vs 3.24097): tol 4e-4. */
    static const double iec_fwd[3][3] = { { 0.4124, 0.3576, 0.1805 },
                                          { 0.2126, 0.7152, 0.0722 },
                                          { 0.0193, 0.1192, 0.9505 } };
    static const double iec_inv[3][3] = { { 3.2406, -1.5372, -0.4986 },
                                          { -0.9689, 1.8758, 0.0415 },
                                          { 0.0557, -0.2040, 1.0570 } };
    const colour_mat3_t fwd = COLOUR_SRGB_TO_XYZ, inv = COLOUR_XYZ_TO_SRGB;
    assert_mat_near(&fwd, iec_fwd, 5e-5 + 1e-7);
    assert_mat_near(&inv, iec_inv, 4e-4);
    /* The constants are the run-time derivation from the primaries. */
    colour_space_t s;
    colour_space_standard(&s, COLOUR_SPACE_SRGB);
    assert_mat_equal(&s.rgb_to_xyz, &fwd, DERIVED_TOL);
    assert_mat_equal(&s.xyz_to_rgb, &inv, 4 * DERIVED_TOL);
    /* and they are inverses of each other */
    colour_mat3_t id = colour_mat3_mul(&fwd, &inv);
    static const double one[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
    assert_mat_near(&id, one, DERIVED_TOL);
    /* colour_luminance is the middle row; rad_luminance its 4 decimals */
    RADIANCE c = rad_make(REAL_C(0.3), REAL_C(0.5), REAL_C(0.9));
    ck_assert_near(colour_luminance(c), colour_rgb_to_xyz(c).Y, 4 * REAL_EPSILON);
    ck_assert_near(colour_luminance(c), rad_luminance(c), 1e-4);
}
END_TEST

START_TEST(other_rgb_spaces_match_their_standards)
{
    colour_space_t s;
    /* Adobe RGB (1998) Color Image Encoding (2005): the normalised
     * RGB -> XYZ matrix, printed to 5 decimals. */
    static const double adobe[3][3] = { { 0.57667, 0.18556, 0.18823 },
                                        { 0.29734, 0.62736, 0.07529 },
                                        { 0.02703, 0.07069, 0.99134 } };
    colour_space_standard(&s, COLOUR_SPACE_ADOBE_RGB);
    assert_mat_near(&s.rgb_to_xyz, adobe, 5e-6 + DERIVED_TOL);
    /* ITU-R BT.2020-2 Table 4: luminance Y = 0.2627 R + 0.6780 G + 0.0593 B */
    colour_space_standard(&s, COLOUR_SPACE_REC2020);
    ck_assert_near(s.rgb_to_xyz.m[1][0], 0.2627, 5e-5 + DERIVED_TOL);
    ck_assert_near(s.rgb_to_xyz.m[1][1], 0.6780, 5e-5 + DERIVED_TOL);
    ck_assert_near(s.rgb_to_xyz.m[1][2], 0.0593, 5e-5 + DERIVED_TOL);
    /* ITU-R BT.2087-0 (2015) eq. (4): linear Rec. 709 -> Rec. 2020, same
     * white, 4 decimals. */
    static const double bt2087[3][3] = { { 0.6274, 0.3293, 0.0433 },
                                         { 0.0691, 0.9195, 0.0114 },
                                         { 0.0164, 0.0880, 0.8956 } };
    colour_space_t srgb;
    colour_space_standard(&srgb, COLOUR_SPACE_SRGB);
    colour_mat3_t m = colour_space_conversion(&srgb, &s, COLOUR_ADAPT_BRADFORD);
    assert_mat_near(&m, bt2087, 5e-5 + DERIVED_TOL);
    /* CIE 1931 RGB -> XYZ with white E (CIE 1931; e.g. Wyszecki & Stiles,
     * Color Science, 2nd ed., eq. 3.3.3(10)), without the 1/0.17697 that
     * makes Y = R for the red primary. Our primaries are the spectral
     * locus at 700, 546.1, 435.8 nm of the 1-nm table, which the 1931
     * 5-digit coefficients reproduce to 1.9e-4. */
    static const double cie[3][3] = { { 0.49, 0.31, 0.20 },
                                      { 0.17697, 0.81240, 0.01063 },
                                      { 0.00, 0.01, 0.99 } };
    colour_space_standard(&s, COLOUR_SPACE_CIE_RGB);
    assert_mat_near(&s.rgb_to_xyz, cie, 2.5e-4);
}
END_TEST

START_TEST(every_space_maps_rgb_white_to_its_white_point)
{
    long n = 0;
    for (int id = 0; id < COLOUR_SPACE_COUNT; id++, n++) {
        colour_space_t s;
        colour_space_standard(&s, (colour_space_id)id);
        colour_xyz_t ww = colour_mat3_apply(&s.rgb_to_xyz, (colour_xyz_t){ 1, 1, 1 });
        ck_assert_near(ww.X, s.white.X, DERIVED_TOL);
        ck_assert_near(ww.Y, 1, DERIVED_TOL);
        ck_assert_near(ww.Z, s.white.Z, DERIVED_TOL);
        /* each primary has its chromaticity */
        const colour_xy_t *p[3] = { &s.red, &s.green, &s.blue };
        for (int k = 0; k < 3; k++) {
            colour_xyz_t e = { k == 0, k == 1, k == 2 };
            colour_xy_t c = colour_xyz_to_xy(colour_mat3_apply(&s.rgb_to_xyz, e));
            ck_assert_near(c.x, p[k]->x, DERIVED_TOL);
            ck_assert_near(c.y, p[k]->y, DERIVED_TOL);
        }
    }
    test_report_cases("every_space_maps_rgb_white_to_its_white_point", n);
}
END_TEST

START_TEST(bad_primaries_are_rejected)
{
    colour_space_t s;
    svet_error err;
    colour_xy_t r = { REAL_C(0.64), REAL_C(0.33) }, g = { REAL_C(0.3), REAL_C(0.6) };
    colour_xy_t b = { REAL_C(0.15), REAL_C(0.06) }, w = { REAL_C(0.3127), REAL_C(0.329) };
    colour_xy_t mid = { (r.x + g.x) / 2, (r.y + g.y) / 2 };
    colour_xy_t zero = { REAL_C(0.2), 0 }, bad = { NAN, REAL_C(0.3) };
    ck_assert_int_eq(colour_space_init(&s, "ok", r, g, b, w, &err), SVET_OK);
    ck_assert_int_eq(colour_space_init(&s, "collinear", r, g, mid, w, &err),
                     SVET_ERR_RANGE);
    ck_assert(strstr(err.msg, "collinear") != NULL);
    ck_assert_int_eq(colour_space_init(&s, "y0", r, g, zero, w, &err), SVET_ERR_RANGE);
    ck_assert_int_eq(colour_space_init(&s, "nan", r, bad, b, w, &err), SVET_ERR_RANGE);
    ck_assert_int_eq(colour_space_init(&s, "white", r, g, b, zero, NULL), SVET_ERR_RANGE);
    colour_mat3_t sing = { { { 1, 2, 3 }, { 2, 4, 6 }, { 0, 1, 0 } } }, inv;
    ck_assert(!colour_mat3_invert(&sing, &inv));
    ck_assert(inv.m[0][0] == 1 && inv.m[0][1] == 0);
}
END_TEST

/* --- white points ------------------------------------------------------------- */

START_TEST(white_points_lie_on_the_published_loci)
{
    /* D65 and D50 against the CIE daylight locus at 6504 K and 5003 K
     * (CIE 15:2004 eqs. 3.3-3.4); the tabulated D spectra sit up to 1.3e-4
     * off the formula (D65: (0.31272, 0.32903) from the table vs 0.32913). */
    colour_xy_t d65 = colour_white_xy(COLOUR_WHITE_D65);
    colour_xy_t d50 = colour_white_xy(COLOUR_WHITE_D50);
    colour_xy_t l65 = colour_daylight_xy(REAL_C(6500.0) * REAL_C(1.4388) / REAL_C(1.4380));
    colour_xy_t l50 = colour_daylight_xy(REAL_C(5000.0) * REAL_C(1.4388) / REAL_C(1.4380));
    ck_assert_near(d65.x, l65.x, 5e-5);
    ck_assert_near(d65.y, l65.y, 1.5e-4);
    ck_assert_near(d50.x, l50.x, 5e-5);
    ck_assert_near(d50.y, l50.y, 1.5e-4);
    /* the published values themselves (IEC 61966-2-1; ICC.1:2010 D50;
     * CIE 15:2004 Table T.3 for A; E by definition) */
    ck_assert_near(d65.x, 0.3127, 1e-7);
    ck_assert_near(d65.y, 0.3290, 1e-7);
    ck_assert_near(d50.x, 0.3457, 1e-7);
    ck_assert_near(d50.y, 0.3585, 1e-7);
    colour_xy_t a = colour_white_xy(COLOUR_WHITE_A), e = colour_white_xy(COLOUR_WHITE_E);
    ck_assert_near(a.x, 0.44757, 1e-7);
    ck_assert_near(a.y, 0.40745, 1e-7);
    ck_assert_near(e.x, 1.0 / 3, 1e-7);
    ck_assert_near(e.y, 1.0 / 3, 1e-7);
    /* XYZ of D65 at Y = 1 against the ASTM E308 table value (0.95047, 1,
     * 1.08883), which comes from the 5-nm D65 spectrum, not the 4-digit xy */
    colour_xyz_t w = colour_white_xyz(COLOUR_WHITE_D65);
    ck_assert_near(w.X, 0.95047, 5e-5);
    ck_assert_near(w.Y, 1, 0);
    ck_assert_near(w.Z, 1.08883, 2.5e-4);
    colour_xyz_t ew = colour_white_xyz(COLOUR_WHITE_E);
    ck_assert(ew.X == 1 && ew.Y == 1 && ew.Z == 1);
}
END_TEST

START_TEST(whites_are_found_by_name)
{
    colour_xyz_t w;
    svet_error err;
    ck_assert_int_eq(colour_white_by_name("d65", &w, &err), SVET_OK);
    ck_assert_near(w.X, colour_white_xyz(COLOUR_WHITE_D65).X, 0);
    ck_assert_int_eq(colour_white_by_name("A", &w, &err), SVET_OK);
    ck_assert_near(w.X, colour_white_xyz(COLOUR_WHITE_A).X, 0);
    ck_assert_int_eq(colour_white_by_name("D66", &w, &err), SVET_ERR_PARSE);
    ck_assert(strstr(err.msg, "D66") != NULL);
    ck_assert_int_eq(colour_white_by_name("D6", &w, &err), SVET_ERR_PARSE);
    ck_assert_int_eq(colour_white_by_name("", &w, &err), SVET_ERR_PARSE);
    ck_assert_int_eq(colour_white_by_name(NULL, &w, NULL), SVET_ERR_PARSE);
}
END_TEST

/* --- chromatic adaptation (app. J) ------------------------------------------ */

START_TEST(bradford_matches_the_published_d65_to_d50_matrix)
{
    /* Lam (1985) cone matrix as printed everywhere (ICC.1:2010 Annex E,
     * brucelindbloom.com "Chromatic Adaptation") */
    static const double lam[3][3] = { { 0.8951, 0.2664, -0.1614 },
                                      { -0.7502, 1.7135, 0.0367 },
                                      { 0.0389, -0.0685, 1.0296 } };
    colour_mat3_t c = colour_adaptation_cone_matrix(COLOUR_ADAPT_BRADFORD);
    assert_mat_near(&c, lam, 1e-7);
    /* The D65 -> D50 Bradford matrix of brucelindbloom.com, for his whites
     * D65 = (0.95047, 1, 1.08883), D50 = (0.96422, 1, 0.82521), 7 decimals */
    static const double d65_d50[3][3] = { { 1.0478112, 0.0228866, -0.0501270 },
                                          { 0.0295424, 0.9904844, -0.0170491 },
                                          { -0.0092345, 0.0150436, 0.7521316 } };
    colour_xyz_t s = { REAL_C(0.95047), 1, REAL_C(1.08883) };
    colour_xyz_t d = { REAL_C(0.96422), 1, REAL_C(0.82521) };
    colour_mat3_t m;
    ck_assert(colour_adaptation_matrix(&m, COLOUR_ADAPT_BRADFORD, s, d));
    assert_mat_near(&m, d65_d50, 5e-8 + DERIVED_TOL);
}
END_TEST

START_TEST(von_kries_does_not_depend_on_the_cone_normalisation)
{
    /* The HPE matrix normalised to D65 (brucelindbloom.com) instead of E
     * (CIECAM02): the adaptation matrix must be the same but for the
     * 5-digit rounding of the two published versions (1.5e-6). The
     * expected values below were computed from the D65-normalised matrix,
     * independently of the code. */
    static const double vk[3][3] = { { 1.0160803, 0.0552297, -0.0521326 },
                                     { 0.0060666, 0.9955661, -0.0012235 },
                                     { 0.0, 0.0, 0.7578869 } };
    colour_xyz_t s = { REAL_C(0.95047), 1, REAL_C(1.08883) };
    colour_xyz_t d = { REAL_C(0.96422), 1, REAL_C(0.82521) };
    colour_mat3_t m;
    ck_assert(colour_adaptation_matrix(&m, COLOUR_ADAPT_VON_KRIES, s, d));
    assert_mat_near(&m, vk, 2.5e-6 + DERIVED_TOL);
    /* XYZ scaling is diagonal */
    ck_assert(colour_adaptation_matrix(&m, COLOUR_ADAPT_XYZ_SCALING, s, d));
    ck_assert_near(m.m[0][0], 0.96422 / 0.95047, DERIVED_TOL);
    ck_assert_near(m.m[2][2], 0.82521 / 1.08883, DERIVED_TOL);
    ck_assert_near(m.m[0][1], 0, 0);
}
END_TEST

START_TEST(an_adapted_white_lands_on_the_target_white)
{
    /* All pairs of named whites and 2000 random pairs of whites with
     * chromaticities in [0.25, 0.45]^2 (z >= 0.1, so every cone response
     * of every method is positive), for all three methods: M src = dst
     * (to rounding) and the reverse transform undoes M. */
    pcg32_t g;
    pcg32_seed(&g, 4, 2);
    long n = 0;
    const colour_adaptation methods[3] = { COLOUR_ADAPT_XYZ_SCALING,
                                           COLOUR_ADAPT_VON_KRIES,
                                           COLOUR_ADAPT_BRADFORD };
    for (int k = 0; k < 2000 + COLOUR_WHITE_COUNT * COLOUR_WHITE_COUNT; k++) {
        colour_xyz_t s, d;
        if (k < COLOUR_WHITE_COUNT * COLOUR_WHITE_COUNT) {
            s = colour_white_xyz((colour_white_id)(k / COLOUR_WHITE_COUNT));
            d = colour_white_xyz((colour_white_id)(k % COLOUR_WHITE_COUNT));
        } else {
            colour_xy_t a = { REAL_C(0.25) + REAL_C(0.2) * pcg32_real(&g),
                              REAL_C(0.25) + REAL_C(0.2) * pcg32_real(&g) };
            colour_xy_t b = { REAL_C(0.25) + REAL_C(0.2) * pcg32_real(&g),
                              REAL_C(0.25) + REAL_C(0.2) * pcg32_real(&g) };
            s = colour_xy_to_white(a);
            d = colour_xy_to_white(b);
            s.X *= 3; s.Y *= 3; s.Z *= 3; /* whites need not have Y = 1 */
        }
        for (int j = 0; j < 3; j++, n++) {
            colour_mat3_t m, back, id;
            ck_assert(colour_adaptation_matrix(&m, methods[j], s, d));
            ck_assert(colour_adaptation_matrix(&back, methods[j], d, s));
            colour_xyz_t r = colour_mat3_apply(&m, s);
            double tol = 32 * (double)REAL_EPSILON * (double)fmax(d.X, fmax(d.Y, d.Z));
            ck_assert_near(r.X, d.X, tol);
            ck_assert_near(r.Y, d.Y, tol);
            ck_assert_near(r.Z, d.Z, tol);
            id = colour_mat3_mul(&back, &m);
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++)
                    ck_assert_near(id.m[a][b], a == b, 64 * REAL_EPSILON);
        }
    }
    test_report_cases("an_adapted_white_lands_on_the_target_white", n);
}
END_TEST

START_TEST(impossible_whites_give_the_identity)
{
    colour_mat3_t m;
    colour_xyz_t ok = colour_white_xyz(COLOUR_WHITE_D65);
    colour_xyz_t black = { 0, 0, 0 }, nan3 = { NAN, 1, 1 }, neg = { -1, 1, 1 };
    ck_assert(!colour_adaptation_matrix(&m, COLOUR_ADAPT_BRADFORD, black, ok));
    ck_assert(m.m[0][0] == 1 && m.m[1][0] == 0);
    ck_assert(!colour_adaptation_matrix(&m, COLOUR_ADAPT_VON_KRIES, ok, nan3));
    ck_assert(!colour_adaptation_matrix(&m, COLOUR_ADAPT_XYZ_SCALING, neg, ok));
}
END_TEST

START_TEST(space_conversion_adapts_the_white)
{
    /* CIE RGB (white E) -> sRGB (white D65): RGB (1,1,1) must become (1,1,1)
     * with adaptation, and must not without it (XYZ scaling still maps
     * white to white: every method does). */
    colour_space_t cie, srgb;
    colour_space_standard(&cie, COLOUR_SPACE_CIE_RGB);
    colour_space_standard(&srgb, COLOUR_SPACE_SRGB);
    for (int k = 0; k < 3; k++) {
        colour_mat3_t m = colour_space_conversion(&cie, &srgb, (colour_adaptation)k);
        RADIANCE w = colour_mat3_apply_rgb(&m, rad_grey(1));
        ck_assert_near(w.r, 1, 4 * DERIVED_TOL);
        ck_assert_near(w.g, 1, 4 * DERIVED_TOL);
        ck_assert_near(w.b, 1, 4 * DERIVED_TOL);
    }
    colour_mat3_t same = colour_space_conversion(&srgb, &srgb, COLOUR_ADAPT_BRADFORD);
    static const double one[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
    assert_mat_near(&same, one, DERIVED_TOL);
}
END_TEST

/* --- xyY, L*a*b* -------------------------------------------------------------- */

START_TEST(xyY_and_lab_round_trip)
{
    pcg32_t g;
    pcg32_seed(&g, 7, 7);
    colour_xyz_t white = colour_white_xyz(COLOUR_WHITE_D65);
    long n = 0;
    for (int k = 0; k < 10000; k++, n++) {
        colour_xyz_t c = { 2 * pcg32_real(&g), 2 * pcg32_real(&g), 2 * pcg32_real(&g) };
        colour_xyz_t r = colour_xyY_to_xyz(colour_xyz_to_xyY(c));
        double tol = 16 * (double)REAL_EPSILON * (1 + (double)(c.X + c.Y + c.Z) /
                                                          fmax((double)c.Y, 1e-3));
        ck_assert_near(r.X, c.X, tol);
        ck_assert_near(r.Y, c.Y, 0);
        ck_assert_near(r.Z, c.Z, tol);
        colour_xyz_t l = colour_lab_to_xyz(colour_xyz_to_lab(c, white), white);
        ck_assert_near(l.X, c.X, 64 * REAL_EPSILON);
        ck_assert_near(l.Y, c.Y, 64 * REAL_EPSILON);
        ck_assert_near(l.Z, c.Z, 64 * REAL_EPSILON);
    }
    test_report_cases("xyY_and_lab_round_trip", n);
    /* black and the bottom of the diagram */
    colour_xyY_t b = colour_xyz_to_xyY((colour_xyz_t){ 0, 0, 0 });
    ck_assert_near(b.x, 1.0 / 3, 1e-7);
    ck_assert_near(b.Y, 0, 0);
    colour_xyz_t z = colour_xyY_to_xyz((colour_xyY_t){ REAL_C(0.2), 0, 1 });
    ck_assert(z.X == 0 && z.Y == 0 && z.Z == 0);
}
END_TEST

START_TEST(lab_has_its_defining_values)
{
    /* CIE 15:2004 sec. 8.2.1: the white is L* = 100, a* = b* = 0; a grey
     * of Y = 0.18 has L* = 116 * 0.18^(1/3) - 16 = 49.49611 (30 digits);
     * with the exact epsilon and kappa the two pieces meet: f is
     * continuous at Y/Yn = 216/24389. */
    colour_xyz_t white = colour_white_xyz(COLOUR_WHITE_D50);
    colour_lab_t w = colour_xyz_to_lab(white, white);
    ck_assert_near(w.L, 100, 1e-4);
    ck_assert_near(w.a, 0, 1e-4);
    ck_assert_near(w.b, 0, 1e-4);
    colour_xyz_t grey = { REAL_C(0.18) * white.X, REAL_C(0.18), REAL_C(0.18) * white.Z };
    colour_lab_t g = colour_xyz_to_lab(grey, white);
    ck_assert_near(g.L, 49.4961104, 1e-4);
    real eps = REAL_C(216.0) / REAL_C(24389.0);
    colour_xyz_t lo = { 0, eps * (1 - REAL_EPSILON), 0 }, hi = { 0, eps * (1 + REAL_EPSILON), 0 };
    ck_assert_near(colour_xyz_to_lab(lo, white).L, colour_xyz_to_lab(hi, white).L, 1e-4);
    ck_assert_near(colour_xyz_to_lab(hi, white).L, 8, 1e-4); /* 116 * 6/29 - 16 */
    ck_assert_near(colour_delta_e76(w, g), sqrt(pow(100 - 49.4961104, 2)), 1e-3);
}
END_TEST

/* --- gamut and photometry ----------------------------------------------------- */

START_TEST(desaturation_keeps_luminance_and_hue_line)
{
    pcg32_t g;
    pcg32_seed(&g, 11, 3);
    long n = 0;
    for (int k = 0; k < 10000; k++, n++) {
        RADIANCE c = rad_make(4 * pcg32_real(&g) - 1, 4 * pcg32_real(&g) - 1,
                              4 * pcg32_real(&g) - 1);
        RADIANCE d = colour_rgb_desaturate_into_gamut(c);
        real Y = colour_luminance(c);
        ck_assert(d.r >= 0 && d.g >= 0 && d.b >= 0);
        if (c.r >= 0 && c.g >= 0 && c.b >= 0) {
            ck_assert(d.r == c.r && d.g == c.g && d.b == c.b);
            continue;
        }
        if (Y <= 0) {
            ck_assert(rad_is_black(d));
            continue;
        }
        real mag = fabs(c.r) + fabs(c.g) + fabs(c.b);
        ck_assert_near(colour_luminance(d), Y, 16 * REAL_EPSILON * mag);
        ck_assert_near(fmin(d.r, fmin(d.g, d.b)), 0, 64 * REAL_EPSILON * (1 + rad_max(c)));
        /* c - w and d - w are parallel, w the grey of luminance Y: their
         * cross product vanishes */
        const colour_mat3_t m = COLOUR_SRGB_TO_XYZ;
        real w = Y / (m.m[1][0] + m.m[1][1] + m.m[1][2]);
        real a1 = c.r - w, a2 = c.g - w, a3 = c.b - w;
        real b1 = d.r - w, b2 = d.g - w, b3 = d.b - w;
        real scale = (fabs(a1) + fabs(a2) + fabs(a3)) * (fabs(b1) + fabs(b2) + fabs(b3));
        ck_assert_near(a2 * b3 - a3 * b2, 0, 64 * REAL_EPSILON * (1 + scale));
        ck_assert_near(a3 * b1 - a1 * b3, 0, 64 * REAL_EPSILON * (1 + scale));
    }
    test_report_cases("desaturation_keeps_luminance_and_hue_line", n);
}
END_TEST

START_TEST(lights_convert_between_watts_lumens_and_candela)
{
    /* eq. (1.2) and I = Phi / (4 pi) for an isotropic source */
    ck_assert_near(colour_point_candela(1000, COLOUR_UNIT_LUMEN, 0),
                   1000 / (4 * 3.14159265358979), 1e-4);
    ck_assert_near(colour_point_candela(50, COLOUR_UNIT_CANDELA, 0), 50, 0);
    /* 10 W of 555-nm light: 6830 lm */
    ck_assert_near(colour_point_candela(10, COLOUR_UNIT_WATT, 683),
                   6830 / (4 * 3.14159265358979), 1e-3);
    ck_assert_near(colour_point_candela(-1, COLOUR_UNIT_LUMEN, 0), 0, 0);
    ck_assert_near(colour_point_candela(NAN, COLOUR_UNIT_LUMEN, 0), 0, 0);
    ck_assert_near(colour_point_candela(1, COLOUR_UNIT_WATT, NAN), 0, 0);
    /* the book's 100 W incandescent lamp radiates 3 W */
    ck_assert_near(colour_radiant_watts_from_electric(100, COLOUR_EFFICIENCY_INCANDESCENT),
                   3, 1e-5);
    /* the RADIANCE of a 1000-lm warm light: luminance cd / 683, colour kept */
    RADIANCE warm = rad_make(1, REAL_C(0.6), REAL_C(0.3));
    RADIANCE in = colour_point_intensity(warm, 1000, COLOUR_UNIT_LUMEN, 0);
    ck_assert_near(colour_luminance(in) * COLOUR_KM, 1000 / (4 * 3.14159265358979), 1e-3);
    ck_assert_near(in.g / in.r, 0.6, 1e-6);
    ck_assert_near(in.b / in.r, 0.3, 1e-6);
    RADIANCE grey = colour_with_luminance(rad_grey(0), 2);
    ck_assert(grey.r == 2 && grey.g == 2 && grey.b == 2);
}
END_TEST

/* --- the CSV vectors --------------------------------------------------------- */

#ifdef SVET_DOUBLE
#define TOL "tol_double"
#else
#define TOL "tol_float"
#endif

START_TEST(matrices_match_the_vectors)
{
    /* tests/vectors/colour_matrices.csv: RGB <-> XYZ of each space and the
     * adaptation matrices between the named whites, in long double by
     * tools/vectors_colour.c (Gauss-Jordan, not our adjugate) */
    testcsv_t c;
    long n = 0;
    testcsv_open(&c, "colour_matrices.csv");
    while (testcsv_next(&c)) {
        const char *what = testcsv_str(&c, "matrix");
        colour_mat3_t m;
        colour_space_t s;
        colour_space_standard(&s, (colour_space_id)testcsv_num(&c, "space"));
        if (strcmp(what, "rgb_to_xyz") == 0) {
            m = s.rgb_to_xyz;
        } else if (strcmp(what, "xyz_to_rgb") == 0) {
            m = s.xyz_to_rgb;
        } else {
            colour_white_id from = (colour_white_id)testcsv_num(&c, "from");
            colour_white_id to = (colour_white_id)testcsv_num(&c, "to");
            colour_adaptation method = strcmp(what, "bradford") == 0
                                           ? COLOUR_ADAPT_BRADFORD
                                       : strcmp(what, "von_kries") == 0
                                           ? COLOUR_ADAPT_VON_KRIES
                                           : COLOUR_ADAPT_XYZ_SCALING;
            ck_assert(colour_adaptation_matrix(&m, method, colour_white_xyz(from),
                                               colour_white_xyz(to)));
        }
        double tol = testcsv_num(&c, TOL);
        char col[32];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                snprintf(col, sizeof col, "m%d%d", i, j);
                ck_assert_near(m.m[i][j], testcsv_num(&c, col), tol);
            }
        n++;
    }
    testcsv_close(&c);
    ck_assert_int_eq(n, 8 + 3 * 12);
    test_report_cases("matrices_match_the_vectors", n);
}
END_TEST

START_TEST(adapted_colours_match_the_vectors)
{
    testcsv_t c;
    long n = 0;
    testcsv_open(&c, "colour_adapt.csv");
    while (testcsv_next(&c)) {
        colour_mat3_t m;
        ck_assert(colour_adaptation_matrix(
            &m, (colour_adaptation)testcsv_num(&c, "method"),
            colour_white_xyz((colour_white_id)testcsv_num(&c, "from")),
            colour_white_xyz((colour_white_id)testcsv_num(&c, "to"))));
        colour_xyz_t in = { (real)testcsv_num(&c, "X"), (real)testcsv_num(&c, "Y"),
                            (real)testcsv_num(&c, "Z") };
        colour_xyz_t out = colour_mat3_apply(&m, in);
        double tol = testcsv_num(&c, TOL);
        ck_assert_near(out.X, testcsv_num(&c, "eX"), tol);
        ck_assert_near(out.Y, testcsv_num(&c, "eY"), tol);
        ck_assert_near(out.Z, testcsv_num(&c, "eZ"), tol);
        n++;
    }
    testcsv_close(&c);
    ck_assert(n > 100);
    test_report_cases("adapted_colours_match_the_vectors", n);
}
END_TEST

START_TEST(srgb_curve_matches_the_vectors)
{
    testcsv_t c;
    long n = 0;
    testcsv_open(&c, "colour_srgb.csv");
    while (testcsv_next(&c)) {
        real v = (real)testcsv_num(&c, "linear");
        ck_assert_near(colour_srgb_encode(v), testcsv_num(&c, "encoded"),
                       testcsv_num(&c, TOL));
        ck_assert_int_eq(colour_srgb_encode_byte(v), (int)testcsv_num(&c, "byte"));
        n++;
    }
    testcsv_close(&c);
    ck_assert(n > 100);
    test_report_cases("srgb_curve_matches_the_vectors", n);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("colour");
    TCase *tc = tcase_create("transfer");
    tcase_add_test(tc, srgb_curve_matches_iec_61966_2_1);
    tcase_add_test(tc, srgb_curve_round_trips_every_byte);
    tcase_add_test(tc, srgb_curve_matches_the_vectors);
    suite_add_tcase(s, tc);
    tc = tcase_create("spaces");
    tcase_add_test(tc, srgb_matrices_match_iec_61966_2_1);
    tcase_add_test(tc, other_rgb_spaces_match_their_standards);
    tcase_add_test(tc, every_space_maps_rgb_white_to_its_white_point);
    tcase_add_test(tc, bad_primaries_are_rejected);
    tcase_add_test(tc, matrices_match_the_vectors);
    suite_add_tcase(s, tc);
    tc = tcase_create("adaptation");
    tcase_add_test(tc, white_points_lie_on_the_published_loci);
    tcase_add_test(tc, whites_are_found_by_name);
    tcase_add_test(tc, bradford_matches_the_published_d65_to_d50_matrix);
    tcase_add_test(tc, von_kries_does_not_depend_on_the_cone_normalisation);
    tcase_add_test(tc, an_adapted_white_lands_on_the_target_white);
    tcase_add_test(tc, impossible_whites_give_the_identity);
    tcase_add_test(tc, space_conversion_adapts_the_white);
    tcase_add_test(tc, adapted_colours_match_the_vectors);
    suite_add_tcase(s, tc);
    tc = tcase_create("coordinates");
    tcase_add_test(tc, xyY_and_lab_round_trip);
    tcase_add_test(tc, lab_has_its_defining_values);
    tcase_add_test(tc, desaturation_keeps_luminance_and_hue_line);
    tcase_add_test(tc, lights_convert_between_watts_lumens_and_candela);
    suite_add_tcase(s, tc);
    return s;
}
