/*
 * colour.c - colour of ch. 2 and app. J, K: the sRGB transfer curve, XYZ,
 * xyY, L*a*b*, RGB spaces from primaries (SMPTE RP 177), chromatic
 * adaptation (von Kries, Bradford) and photometric lights (eq. (1.2)).
 * Tests: tests/colour/test_colour.c
 */
#include "colour/colour.h"

#include <assert.h>
#include <ctype.h>
#include <string.h>

/* --- the sRGB transfer curve (IEC 61966-2-1:1999) --------------------------- */

real colour_srgb_encode(real v)
{
    if (v < 0)
        return -colour_srgb_encode(-v);
    /* The linear toe below 0.0031308 avoids the infinite slope of a pure
     * power law at 0 (IEC 61966-2-1, sec. 5.2). */
    if (v <= REAL_C(0.0031308))
        return REAL_C(12.92) * v;
    return REAL_C(1.055) * pow(v, REAL_C(1.0) / REAL_C(2.4)) - REAL_C(0.055);
}

real colour_srgb_decode(real e)
{
    if (e < 0)
        return -colour_srgb_decode(-e);
    if (e <= REAL_C(0.04045))
        return e / REAL_C(12.92);
    return pow((e + REAL_C(0.055)) / REAL_C(1.055), REAL_C(2.4));
}

uint8_t colour_srgb_encode_byte(real v)
{
    if (!(v > 0)) /* also NaN */
        return 0;
    if (v >= 1)
        return 255;
    return (uint8_t)(colour_srgb_encode(v) * 255 + REAL_C(0.5));
}

real colour_srgb_decode_byte(uint8_t code)
{
    return colour_srgb_decode((real)code / 255);
}

/* --- XYZ, xyY, L*a*b* -------------------------------------------------------- */

colour_xyY_t colour_xyz_to_xyY(colour_xyz_t c)
{
    real s = c.X + c.Y + c.Z;
    colour_xyY_t r;
    if (s == 0 || !isfinite(s)) {
        r.x = REAL_C(1.0) / 3;
        r.y = REAL_C(1.0) / 3;
        r.Y = s == 0 ? 0 : c.Y;
        return r;
    }
    r.x = c.X / s;
    r.y = c.Y / s;
    r.Y = c.Y;
    return r;
}

colour_xyz_t colour_xyY_to_xyz(colour_xyY_t c)
{
    colour_xyz_t r = { 0, 0, 0 };
    if (!(c.y > 0))
        return r;
    r.X = c.x * c.Y / c.y;
    r.Y = c.Y;
    r.Z = (1 - c.x - c.y) * c.Y / c.y;
    return r;
}

colour_xy_t colour_xyz_to_xy(colour_xyz_t c)
{
    colour_xyY_t t = colour_xyz_to_xyY(c);
    colour_xy_t r = { t.x, t.y };
    return r;
}

colour_xyz_t colour_xy_to_white(colour_xy_t w)
{
    colour_xyY_t t = { w.x, w.y, 1 };
    return colour_xyY_to_xyz(t);
}

/* CIE 15:2004 eq. 8.3-8.5 with the exact constants epsilon = (6/29)^3 =
 * 216/24389 and kappa = 24389/27 (the rounded 0.008856 and 903.3 of older
 * texts leave a small jump at the junction of the two pieces). */
#define LAB_EPSILON (REAL_C(216.0) / REAL_C(24389.0))
#define LAB_KAPPA (REAL_C(24389.0) / REAL_C(27.0))

static real lab_f(real t)
{
    return t > LAB_EPSILON ? cbrt(t) : (LAB_KAPPA * t + 16) / 116;
}

static real lab_f_inv(real f)
{
    real f3 = f * f * f;
    return f3 > LAB_EPSILON ? f3 : (116 * f - 16) / LAB_KAPPA;
}

colour_lab_t colour_xyz_to_lab(colour_xyz_t c, colour_xyz_t white)
{
    real fx = lab_f(c.X / white.X);
    real fy = lab_f(c.Y / white.Y);
    real fz = lab_f(c.Z / white.Z);
    colour_lab_t r = { 116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz) };
    return r;
}

colour_xyz_t colour_lab_to_xyz(colour_lab_t c, colour_xyz_t white)
{
    real fy = (c.L + 16) / 116;
    real fx = fy + c.a / 500;
    real fz = fy - c.b / 200;
    colour_xyz_t r = { white.X * lab_f_inv(fx), white.Y * lab_f_inv(fy),
                       white.Z * lab_f_inv(fz) };
    return r;
}

real colour_delta_e76(colour_lab_t a, colour_lab_t b)
{
    real dl = a.L - b.L, da = a.a - b.a, db = a.b - b.b;
    return sqrt(dl * dl + da * da + db * db);
}

/* --- 3x3 matrices ------------------------------------------------------------ */

static const colour_mat3_t IDENTITY = { { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } } };

colour_mat3_t colour_mat3_mul(const colour_mat3_t *a, const colour_mat3_t *b)
{
    colour_mat3_t r;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r.m[i][j] = a->m[i][0] * b->m[0][j] + a->m[i][1] * b->m[1][j] +
                        a->m[i][2] * b->m[2][j];
    return r;
}

bool colour_mat3_invert(const colour_mat3_t *a, colour_mat3_t *inv)
{
    /* The adjugate over the determinant: exact enough for the
     * well-conditioned matrices of colour spaces (condition numbers < 50),
     * and short enough to read against any linear-algebra text. */
    const real (*m)[3] = a->m;
    real c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    real c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    real c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    real det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    real scale = 1;
    for (int i = 0; i < 3; i++)
        scale *= sqrt(m[i][0] * m[i][0] + m[i][1] * m[i][1] + m[i][2] * m[i][2]);
    if (!isfinite(det) || !isfinite(scale) || !(fabs(det) > 16 * REAL_EPSILON * scale)) {
        *inv = IDENTITY;
        return false;
    }
    colour_mat3_t r;
    r.m[0][0] = c00 / det;
    r.m[1][0] = c01 / det;
    r.m[2][0] = c02 / det;
    r.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
    r.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
    r.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
    r.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
    r.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
    r.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
    *inv = r;
    return true;
}

colour_xyz_t colour_mat3_apply(const colour_mat3_t *m, colour_xyz_t v)
{
    colour_xyz_t r;
    r.X = m->m[0][0] * v.X + m->m[0][1] * v.Y + m->m[0][2] * v.Z;
    r.Y = m->m[1][0] * v.X + m->m[1][1] * v.Y + m->m[1][2] * v.Z;
    r.Z = m->m[2][0] * v.X + m->m[2][1] * v.Y + m->m[2][2] * v.Z;
    return r;
}

RADIANCE colour_mat3_apply_rgb(const colour_mat3_t *m, RADIANCE v)
{
    colour_xyz_t t = { v.r, v.g, v.b };
    t = colour_mat3_apply(m, t);
    return rad_make(t.X, t.Y, t.Z);
}

/* --- linear sRGB -------------------------------------------------------------- */

static const colour_mat3_t SRGB_TO_XYZ = COLOUR_SRGB_TO_XYZ;
static const colour_mat3_t XYZ_TO_SRGB = COLOUR_XYZ_TO_SRGB;

RADIANCE colour_xyz_to_rgb(colour_xyz_t c)
{
    colour_xyz_t t = colour_mat3_apply(&XYZ_TO_SRGB, c);
    return rad_make(t.X, t.Y, t.Z);
}

colour_xyz_t colour_rgb_to_xyz(RADIANCE c)
{
    colour_xyz_t t = { c.r, c.g, c.b };
    return colour_mat3_apply(&SRGB_TO_XYZ, t);
}

real colour_luminance(RADIANCE c)
{
    return SRGB_TO_XYZ.m[1][0] * c.r + SRGB_TO_XYZ.m[1][1] * c.g +
           SRGB_TO_XYZ.m[1][2] * c.b;
}

RADIANCE colour_rgb_desaturate_into_gamut(RADIANCE c)
{
    real lo = fmin(c.r, fmin(c.g, c.b));
    if (lo >= 0)
        return c;
    real Y = colour_luminance(c);
    if (!(Y > 0))
        return rad_grey(0);
    /* the grey of luminance Y (the row sums to 1 but for its 10th digit) */
    real g = Y / (SRGB_TO_XYZ.m[1][0] + SRGB_TO_XYZ.m[1][1] + SRGB_TO_XYZ.m[1][2]);
    /* c' = g + t (c - g) keeps the luminance Y for any t; min(c') = 0 at: */
    real t = g / (g - lo);
    RADIANCE r = rad_make(g + t * (c.r - g), g + t * (c.g - g), g + t * (c.b - g));
    /* rounding may leave -1 ulp */
    r.r = fmax(r.r, REAL_C(0.0));
    r.g = fmax(r.g, REAL_C(0.0));
    r.b = fmax(r.b, REAL_C(0.0));
    return r;
}

/* --- RGB spaces ----------------------------------------------------------------- */

static bool xy_valid(colour_xy_t c)
{
    return isfinite(c.x) && isfinite(c.y) && c.y > 0;
}

svet_status colour_space_init(colour_space_t *s, const char *name,
                              colour_xy_t red, colour_xy_t green,
                              colour_xy_t blue, colour_xy_t white,
                              svet_error *err)
{
    if (!xy_valid(red) || !xy_valid(green) || !xy_valid(blue) || !xy_valid(white))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "colour space '%s': a chromaticity is not finite "
                              "or has y <= 0", name ? name : "");
    /* SMPTE RP 177-1993 sec. 3.3: the columns of P are the primaries at
     * Y = 1; the scale S of each makes R = G = B = 1 the white. */
    colour_xyz_t p[3] = { colour_xy_to_white(red), colour_xy_to_white(green),
                          colour_xy_to_white(blue) };
    colour_mat3_t P, Pinv;
    for (int j = 0; j < 3; j++) {
        P.m[0][j] = p[j].X;
        P.m[1][j] = p[j].Y;
        P.m[2][j] = p[j].Z;
    }
    if (!colour_mat3_invert(&P, &Pinv))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "colour space '%s': the primaries are collinear",
                              name ? name : "");
    colour_xyz_t W = colour_xy_to_white(white);
    colour_xyz_t S = colour_mat3_apply(&Pinv, W);
    real sv[3] = { S.X, S.Y, S.Z };
    s->name = name;
    s->red = red;
    s->green = green;
    s->blue = blue;
    s->white_xy = white;
    s->white = W;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            s->rgb_to_xyz.m[i][j] = P.m[i][j] * sv[j];
    if (!colour_mat3_invert(&s->rgb_to_xyz, &s->xyz_to_rgb))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "colour space '%s': the white lies on a side of "
                              "the primaries' triangle", name ? name : "");
    return SVET_OK;
}

static colour_xy_t xy(real x, real y)
{
    colour_xy_t c = { x, y };
    return c;
}

void colour_space_standard(colour_space_t *s, colour_space_id id)
{
    colour_xy_t d65 = colour_white_xy(COLOUR_WHITE_D65);
    svet_status st;
    switch (id) {
    case COLOUR_SPACE_REC2020: /* ITU-R BT.2020-2, Table 3 */
        st = colour_space_init(s, "Rec. 2020", xy(REAL_C(0.708), REAL_C(0.292)),
                               xy(REAL_C(0.170), REAL_C(0.797)),
                               xy(REAL_C(0.131), REAL_C(0.046)), d65, NULL);
        break;
    case COLOUR_SPACE_ADOBE_RGB: /* Adobe RGB (1998) Color Image Encoding,
                                    version 2005-05, sec. 4.3.1 */
        st = colour_space_init(s, "Adobe RGB (1998)", xy(REAL_C(0.64), REAL_C(0.33)),
                               xy(REAL_C(0.21), REAL_C(0.71)),
                               xy(REAL_C(0.15), REAL_C(0.06)), d65, NULL);
        break;
    case COLOUR_SPACE_CIE_RGB:
        /* CIE 1931 RGB: monochromatic primaries at 700, 546.1 and 435.8 nm
         * (Wright and Guild's mercury lines), equal-energy white. Their
         * chromaticities are read off the CIE 1931 1-nm table (linear
         * interpolation at 546.1 and 435.8 nm); tests/colour/test_spectrum.c
         * checks them against spectrum_locus_xy(). */
        st = colour_space_init(s, "CIE RGB", xy(REAL_C(0.7346900233), REAL_C(0.2653099767)),
                               xy(REAL_C(0.2736826753), REAL_C(0.7174214263)),
                               xy(REAL_C(0.1665346669), REAL_C(0.008883964460)),
                               colour_white_xy(COLOUR_WHITE_E), NULL);
        break;
    case COLOUR_SPACE_SRGB: /* IEC 61966-2-1:1999 sec. 5.1 = ITU-R BT.709 */
    default:
        st = colour_space_init(s, "sRGB", xy(REAL_C(0.64), REAL_C(0.33)),
                               xy(REAL_C(0.30), REAL_C(0.60)),
                               xy(REAL_C(0.15), REAL_C(0.06)), d65, NULL);
        break;
    }
    (void)st;
    assert(st == SVET_OK);
}

/* --- white points and chromatic adaptation ------------------------------------ */

colour_xy_t colour_white_xy(colour_white_id id)
{
    switch (id) {
    case COLOUR_WHITE_D50: return xy(REAL_C(0.3457), REAL_C(0.3585));
    case COLOUR_WHITE_A: return xy(REAL_C(0.44757), REAL_C(0.40745));
    case COLOUR_WHITE_E: return xy(REAL_C(1.0) / 3, REAL_C(1.0) / 3);
    case COLOUR_WHITE_D65:
    default: return xy(REAL_C(0.3127), REAL_C(0.3290));
    }
}

colour_xyz_t colour_white_xyz(colour_white_id id)
{
    if (id == COLOUR_WHITE_E) { /* exactly (1, 1, 1), not 3 roundings of 1/3 */
        colour_xyz_t e = { 1, 1, 1 };
        return e;
    }
    return colour_xy_to_white(colour_white_xy(id));
}

colour_xy_t colour_daylight_xy(real T)
{
    if (!(T >= 4000)) /* also NaN */
        T = 4000;
    if (T > 25000)
        T = 25000;
    real t = 1000 / T; /* the formula in powers of 10^3 / T */
    real x;
    if (T <= 7000)
        x = REAL_C(0.244063) + t * (REAL_C(0.09911) + t * (REAL_C(2.9678) - t * REAL_C(4.6070)));
    else
        x = REAL_C(0.237040) + t * (REAL_C(0.24748) + t * (REAL_C(1.9018) - t * REAL_C(2.0064)));
    return xy(x, REAL_C(-3.0) * x * x + REAL_C(2.870) * x - REAL_C(0.275));
}

svet_status colour_white_by_name(const char *name, colour_xyz_t *white,
                                 svet_error *err)
{
    static const char *const names[COLOUR_WHITE_COUNT] = { "D65", "D50", "A", "E" };
    for (int i = 0; name && i < COLOUR_WHITE_COUNT; i++) {
        const char *a = name, *b = names[i];
        while (*a && *b && toupper((unsigned char)*a) == *b) {
            a++;
            b++;
        }
        if (*a == '\0' && *b == '\0') {
            *white = colour_white_xyz((colour_white_id)i);
            return SVET_OK;
        }
    }
    return svet_error_set(err, SVET_ERR_PARSE,
                          "unknown white point '%s' (D65, D50, A, E)",
                          name ? name : "(null)");
}

colour_mat3_t colour_adaptation_cone_matrix(colour_adaptation method)
{
    /* von Kries (1902) scales the cone responses; the cones here are those
     * of Hunt, Pointer and Estevez normalised to equal energy, as in
     * CIECAM02 (CIE 159:2004). The normalisation of the rows does not
     * change the adaptation matrix. */
    static const colour_mat3_t HPE = { { { REAL_C(0.38971), REAL_C(0.68898), REAL_C(-0.07868) },
                                         { REAL_C(-0.22981), REAL_C(1.18340), REAL_C(0.04641) },
                                         { REAL_C(0.0), REAL_C(0.0), REAL_C(1.0) } } };
    /* Lam (1985), "Metamerism and colour constancy", PhD thesis, Univ. of
     * Bradford: "sharpened" responses. This is the linearised Bradford
     * transform of ICC and of most software; Lam's original also bends the
     * blue response with an exponent, which is dropped here. */
    static const colour_mat3_t BRADFORD = { { { REAL_C(0.8951), REAL_C(0.2664), REAL_C(-0.1614) },
                                              { REAL_C(-0.7502), REAL_C(1.7135), REAL_C(0.0367) },
                                              { REAL_C(0.0389), REAL_C(-0.0685), REAL_C(1.0296) } } };
    switch (method) {
    case COLOUR_ADAPT_VON_KRIES: return HPE;
    case COLOUR_ADAPT_BRADFORD: return BRADFORD;
    case COLOUR_ADAPT_XYZ_SCALING:
    default: return IDENTITY;
    }
}

static bool xyz_finite(colour_xyz_t c)
{
    return isfinite(c.X) && isfinite(c.Y) && isfinite(c.Z);
}

bool colour_adaptation_matrix(colour_mat3_t *m, colour_adaptation method,
                              colour_xyz_t src, colour_xyz_t dst)
{
    colour_mat3_t C = colour_adaptation_cone_matrix(method), Cinv;
    *m = IDENTITY;
    if (!xyz_finite(src) || !xyz_finite(dst) || !colour_mat3_invert(&C, &Cinv))
        return false;
    /* app. J: cone responses of both whites, their ratios scale each cone */
    colour_xyz_t s = colour_mat3_apply(&C, src);
    colour_xyz_t d = colour_mat3_apply(&C, dst);
    if (!(s.X > 0 && s.Y > 0 && s.Z > 0 && d.X > 0 && d.Y > 0 && d.Z > 0))
        return false;
    real g[3] = { d.X / s.X, d.Y / s.Y, d.Z / s.Z };
    colour_mat3_t D = C; /* diag(g) C */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            D.m[i][j] *= g[i];
    *m = colour_mat3_mul(&Cinv, &D);
    return true;
}

colour_mat3_t colour_space_conversion(const colour_space_t *from,
                                      const colour_space_t *to,
                                      colour_adaptation method)
{
    colour_mat3_t A, t;
    if (from->white_xy.x == to->white_xy.x && from->white_xy.y == to->white_xy.y)
        A = IDENTITY;
    else
        (void)colour_adaptation_matrix(&A, method, from->white, to->white);
    t = colour_mat3_mul(&A, &from->rgb_to_xyz);
    return colour_mat3_mul(&to->xyz_to_rgb, &t);
}

/* --- photometry ----------------------------------------------------------------- */

real colour_radiant_watts_from_electric(real electric_watts, real efficiency)
{
    return electric_watts * efficiency;
}

real colour_point_candela(real amount, colour_unit unit, real efficacy)
{
    if (!(amount >= 0) || !isfinite(amount))
        return 0;
    if (unit == COLOUR_UNIT_CANDELA)
        return amount;
    real lumens = amount;
    if (unit == COLOUR_UNIT_WATT) {
        if (!(efficacy >= 0) || !isfinite(efficacy))
            return 0;
        lumens = efficacy * amount; /* eq. (1.2): Phi_v = K Phi */
    }
    /* an isotropic source spreads its flux over 4 pi steradians */
    return lumens / (4 * REAL_PI);
}

RADIANCE colour_with_luminance(RADIANCE colour, real Y)
{
    real y0 = colour_luminance(colour);
    if (!(y0 > 0) || !isfinite(y0))
        return rad_grey(Y);
    return rad_scale(colour, Y / y0);
}

RADIANCE colour_point_intensity(RADIANCE colour, real amount, colour_unit unit,
                                real efficacy)
{
    real cd = colour_point_candela(amount, unit, efficacy);
    return colour_with_luminance(colour, cd / COLOUR_KM);
}
