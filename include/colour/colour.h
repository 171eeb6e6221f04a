/*
 * colour.h - colour of ch. 2 and app. J, K: the sRGB transfer curve, CIE XYZ,
 * xyY and L*a*b*, RGB spaces built from their primaries and white point
 * (sRGB / Rec. 709, Rec. 2020, Adobe RGB (1998), CIE RGB), chromatic
 * adaptation (von Kries, Bradford; app. J) and lights given in watts, lumens
 * or candela (eq. (1.2)). Spectra, the CIE 1931 observer and Planck's law
 * are in spectrum.h; this module needs no spectra, so a program that only
 * encodes pixels links colour.c alone (with error.c).
 * Tests: tests/colour/test_colour.c; vectors: tests/vectors/colour_*.csv
 */
#ifndef SVET_COLOUR_H
#define SVET_COLOUR_H

#include <stdbool.h>
#include <stdint.h>
#include "core/real.h"
#include "materials/radiance.h"
#include "core/error.h"

/*
 * Units. RADIANCE (radiance.h) is linear Rec. 709 RGB in W/(m^2 sr) per
 * channel, in this sense: a spectral radiance L(lambda) in W/(m^2 sr nm) has
 *     X = int L xbar dlambda,  Y = int L ybar dlambda,  Z = int L zbar dlambda
 * (the CIE 1931 functions, ybar = v(lambda) of the book, peak 1 at 555 nm),
 * and its RADIANCE is COLOUR_XYZ_TO_SRGB applied to (X, Y, Z). So the
 * luminance of a RADIANCE is COLOUR_KM * Y cd/m^2 (eq. (1.2)): Y is the
 * radiance of the 555-nm light that looks as bright. The same holds for
 * intensities (W/sr -> cd) and fluxes (W -> lm).
 */

/* eq. (1.2): 683 lm/W, the luminous efficacy of 555-nm light (CIE: K_m =
 * 683.002 lm/W at the peak of v; the SI defines 683 lm/W at 540 THz). */
#define COLOUR_KM REAL_C(683.0)

/* CIE XYZ tristimulus values. X, Y, Z are also the axis indices of vec.h;
 * as struct members they live in their own name space, so both coexist. */
typedef struct {
    real X, Y, Z;
} colour_xyz_t;

/* Chromaticity x = X / (X + Y + Z), y = Y / (X + Y + Z). */
typedef struct {
    real x, y;
} colour_xy_t;

/* Chromaticity with luminance: the coordinates of the CIE 1931 diagram. */
typedef struct {
    real x, y, Y;
} colour_xyY_t;

/* CIE 1976 L*a*b*. */
typedef struct {
    real L, a, b;
} colour_lab_t;

/* A 3x3 matrix acting on column vectors: out[i] = sum_j m[i][j] in[j]. */
typedef struct {
    real m[3][3];
} colour_mat3_t;

/* --- the sRGB transfer curve (IEC 61966-2-1:1999, sec. 5.2) --------------- */

/* Encode one linear value v (1 = display white) with the sRGB curve:
 *   12.92 v                    for v <= 0.0031308,
 *   1.055 v^(1/2.4) - 0.055    otherwise.
 * Values outside [0, 1] are not clamped: negative v gives -encode(-v), so
 * out-of-gamut colours survive a round trip. NaN stays NaN.
 * This function can't fail. */
real colour_srgb_encode(real v);

/* The inverse curve: e / 12.92 for e <= 0.04045, ((e + 0.055) / 1.055)^2.4
 * otherwise; odd-symmetric like colour_srgb_encode. This function can't fail. */
real colour_srgb_decode(real e);

/* Linear value -> 8-bit sRGB code 0..255: clamp to [0, 1], encode, round to
 * nearest. NaN gives 0. This function can't fail. */
uint8_t colour_srgb_encode_byte(real v);

/* 8-bit sRGB code -> linear value, exact to the rounding of real.
 * This function can't fail. */
real colour_srgb_decode_byte(uint8_t code);

/* --- XYZ, xyY, L*a*b* (app. K) --------------------------------------------- */

/* xyY of an XYZ. Black (X + Y + Z = 0) has no chromaticity; it gets that of
 * the equal-energy white E, (1/3, 1/3), and Y = 0. This function can't fail. */
colour_xyY_t colour_xyz_to_xyY(colour_xyz_t c);

/* XYZ of an xyY: X = x Y / y, Z = (1 - x - y) Y / y. y <= 0 (the bottom of
 * the diagram, where no light lives) gives black. This function can't fail. */
colour_xyz_t colour_xyY_to_xyz(colour_xyY_t c);

/* The chromaticity of an XYZ (black gives E's, as above). Can't fail. */
colour_xy_t colour_xyz_to_xy(colour_xyz_t c);

/* The white of chromaticity w scaled to Y = 1. Can't fail (y <= 0: black). */
colour_xyz_t colour_xy_to_white(colour_xy_t w);

/* CIE 1976 L*a*b* relative to the white `white` (CIE 15:2004 sec. 8.2.1,
 * with its exact constants 216/24389 and 24389/27). Can't fail. */
colour_lab_t colour_xyz_to_lab(colour_xyz_t c, colour_xyz_t white);
colour_xyz_t colour_lab_to_xyz(colour_lab_t c, colour_xyz_t white);

/* The CIE 1976 colour difference Delta E*_ab: Euclidean distance in L*a*b*;
 * about 2 is just noticeable side by side. Can't fail. */
real colour_delta_e76(colour_lab_t a, colour_lab_t b);

/* --- 3x3 matrices ------------------------------------------------------------ */

/* a b. Can't fail. */
colour_mat3_t colour_mat3_mul(const colour_mat3_t *a, const colour_mat3_t *b);

/* The inverse of a into *inv (which may be a). Returns false, and sets *inv
 * to the identity, if a is singular to working precision (|det| below 16
 * REAL_EPSILON times the product of its row norms) or not finite. */
bool colour_mat3_invert(const colour_mat3_t *a, colour_mat3_t *inv);

/* m v for XYZ triples and for RADIANCE. Can't fail. */
colour_xyz_t colour_mat3_apply(const colour_mat3_t *m, colour_xyz_t v);
RADIANCE colour_mat3_apply_rgb(const colour_mat3_t *m, RADIANCE v);

/* --- linear sRGB (Rec. 709 primaries, D65) ---------------------------------- */

/* The matrices of IEC 61966-2-1 derived from its primaries R (0.64, 0.33),
 * G (0.30, 0.60), B (0.15, 0.06) and white D65 (0.3127, 0.3290) in exact
 * rational arithmetic and given to 10 digits; the standard prints the same
 * matrices rounded to 4 decimals (its XYZ -> RGB differs from the exact
 * inverse by up to 4e-4 in the 4th decimal because it was inverted from the
 * rounded matrix). tests/colour/test_colour.c checks them against both. */
#define COLOUR_SRGB_TO_XYZ                                                     \
    { { { REAL_C(0.4123907993), REAL_C(0.3575843394), REAL_C(0.1804807884) },  \
        { REAL_C(0.2126390059), REAL_C(0.7151686788), REAL_C(0.07219231536) }, \
        { REAL_C(0.01933081872), REAL_C(0.1191947798), REAL_C(0.9505321522) } } }
#define COLOUR_XYZ_TO_SRGB                                                     \
    { { { REAL_C(3.240969942), REAL_C(-1.537383178), REAL_C(-0.4986107603) },  \
        { REAL_C(-0.9692436363), REAL_C(1.875967502), REAL_C(0.04155505741) }, \
        { REAL_C(0.0556300797), REAL_C(-0.2039769589), REAL_C(1.056971514) } } }

/* XYZ -> linear sRGB RADIANCE (may be negative outside the gamut), and back.
 * These functions can't fail. */
RADIANCE colour_xyz_to_rgb(colour_xyz_t c);
colour_xyz_t colour_rgb_to_xyz(RADIANCE c);

/* Luminance Y of a linear sRGB RADIANCE with the full-precision middle row
 * of COLOUR_SRGB_TO_XYZ (rad_luminance uses the standard's 4 decimals).
 * Can't fail. */
real colour_luminance(RADIANCE c);

/* Bring a colour with a negative channel into the gamut by mixing it with
 * the grey of the same luminance (the sRGB white, D65) just enough that its
 * smallest channel becomes 0: luminance is kept and the chromaticity moves
 * straight toward the white point. In-gamut colours are returned unchanged;
 * a colour with luminance <= 0 becomes black. Can't fail. */
RADIANCE colour_rgb_desaturate_into_gamut(RADIANCE c);

/* --- RGB spaces from primaries and white point (app. K) -------------------- */

typedef struct {
    const char *name;
    colour_xy_t red, green, blue; /* chromaticities of the primaries */
    colour_xy_t white_xy;         /* chromaticity of the white R = G = B */
    colour_xyz_t white;           /* that white with Y = 1 */
    colour_mat3_t rgb_to_xyz;     /* white (1, 1, 1) -> white, Y = 1 */
    colour_mat3_t xyz_to_rgb;
} colour_space_t;

typedef enum {
    COLOUR_SPACE_SRGB,      /* IEC 61966-2-1 = ITU-R BT.709, white D65 */
    COLOUR_SPACE_REC2020,   /* ITU-R BT.2020, white D65 */
    COLOUR_SPACE_ADOBE_RGB, /* Adobe RGB (1998), white D65 */
    COLOUR_SPACE_CIE_RGB,   /* CIE 1931 RGB: 700, 546.1, 435.8 nm, white E */
    COLOUR_SPACE_COUNT
} colour_space_id;

/* Build an RGB space from its primaries and white (SMPTE RP 177-1993): with
 * P the matrix whose columns are the XYZ of the primaries at Y = 1, solve
 * P S = W for the white W and set rgb_to_xyz = P diag(S). Fails with
 * SVET_ERR_RANGE if a chromaticity is not finite or has y <= 0, or the
 * primaries are collinear. `name` is kept as given (not copied). */
svet_status colour_space_init(colour_space_t *s, const char *name,
                              colour_xy_t red, colour_xy_t green,
                              colour_xy_t blue, colour_xy_t white,
                              svet_error *err);

/* One of the standard spaces above, built at run time from its published
 * primaries and white. An id out of range gives sRGB. Can't fail. */
void colour_space_standard(colour_space_t *s, colour_space_id id);

/* --- white points and chromatic adaptation (app. J) ------------------------ */

typedef enum {
    COLOUR_WHITE_D65, /* (0.3127, 0.3290): noon daylight; sRGB, Rec. 709 */
    COLOUR_WHITE_D50, /* (0.3457, 0.3585): horizon light; ICC, printing */
    COLOUR_WHITE_A,   /* (0.44757, 0.40745): incandescent, ~2856 K */
    COLOUR_WHITE_E,   /* (1/3, 1/3): equal energy */
    COLOUR_WHITE_COUNT
} colour_white_id;

/* Chromaticity of a standard white (an id out of range gives D65) and its
 * XYZ with Y = 1. Values: IEC 61966-2-1 (D65), ISO 3664 / ICC (D50),
 * CIE 15:2004 Table T.3 (A), and 1/3 (E). Can't fail. */
colour_xy_t colour_white_xy(colour_white_id id);
colour_xyz_t colour_white_xyz(colour_white_id id);

/* A white by its name: "D65", "D50", "A" or "E" (case-insensitive). Fails
 * with SVET_ERR_PARSE on any other name; spectrum_white_parse() also takes
 * blackbody temperatures ("3200K"). */
svet_status colour_white_by_name(const char *name, colour_xyz_t *white,
                                 svet_error *err);

/* The CIE daylight locus (CIE 15:2004 eqs. 3.3-3.4): the chromaticity of
 * the daylight illuminant D of correlated colour temperature T, defined for
 * 4000 K <= T <= 25000 K (T is clamped to that range). D65 is T = 6504 K
 * (6500 K times 1.4388/1.4380, the change of c2 in 1968), D50 5003 K; their
 * tabulated spectra give chromaticities within 1.3e-4 of this formula.
 * Can't fail. */
colour_xy_t colour_daylight_xy(real T);

typedef enum {
    COLOUR_ADAPT_XYZ_SCALING, /* scale X, Y, Z directly ("wrong von Kries") */
    COLOUR_ADAPT_VON_KRIES,   /* scale the cone responses L, M, S (HPE) */
    COLOUR_ADAPT_BRADFORD     /* scale Lam's sharpened responses (linear) */
} colour_adaptation;

/* The cone (or sharpened-cone) matrix of a method: Hunt-Pointer-Estevez for
 * von Kries, Lam's for Bradford, the identity for XYZ scaling. Can't fail. */
colour_mat3_t colour_adaptation_cone_matrix(colour_adaptation method);

/* The chromatic adaptation transform from white src to white dst (app. J):
 *     M = C^-1 diag(C dst / C src) C,
 * C the cone matrix of the method; M src = dst exactly (to rounding).
 * Returns false and sets *m to the identity if a white is not finite or
 * gives a cone response <= 0 (no real white does). */
bool colour_adaptation_matrix(colour_mat3_t *m, colour_adaptation method,
                              colour_xyz_t src, colour_xyz_t dst);

/* The matrix that takes linear RGB of space `from` to linear RGB of space
 * `to` (app. K): to.xyz_to_rgb * A * from.rgb_to_xyz, with A the adaptation
 * from from's white to to's white by `method` (A = identity when the whites
 * are equal). Can't fail. */
colour_mat3_t colour_space_conversion(const colour_space_t *from,
                                      const colour_space_t *to,
                                      colour_adaptation method);

/* --- photometry: lights in watts, lumens or candela (eq. (1.2)) ------------ */

/*
 * A point light is given by its colour (any RADIANCE; only its chromaticity
 * matters) and an amount in one of these units. "Watts" are radiant watts
 * emitted between 360 and 830 nm (the span of the CIE tables): they become
 * lumens through the luminous efficacy K of the light's spectrum,
 *     K = 683 int v S dlambda / int S dlambda    (lm/W, eq. (1.2)),
 * which an RGB colour alone does not determine: the caller gives it, e.g.
 * spectrum_blackbody_efficacy_band(T) for a lamp of colour temperature T.
 * The book's way from a lamp's electrical power (ch. 1: radiant flux =
 * electrical power times an efficiency, ~0.03 for incandescent lamps and
 * ~0.15-0.35 for fluorescent ones) is colour_radiant_watts_from_electric().
 */
typedef enum {
    COLOUR_UNIT_WATT,    /* radiant flux, W (360-830 nm) */
    COLOUR_UNIT_LUMEN,   /* luminous flux, lm */
    COLOUR_UNIT_CANDELA  /* luminous intensity, cd = lm/sr */
} colour_unit;

/* The efficiencies of ch. 1 (fraction of electrical power radiated). */
#define COLOUR_EFFICIENCY_INCANDESCENT REAL_C(0.03)
#define COLOUR_EFFICIENCY_FLUORESCENT_LOW REAL_C(0.15)
#define COLOUR_EFFICIENCY_FLUORESCENT_HIGH REAL_C(0.35)

/* ch. 1: radiant flux = electrical power * efficiency. Can't fail. */
real colour_radiant_watts_from_electric(real electric_watts, real efficiency);

/* Luminous intensity (cd) of an isotropic point source: I = Phi_v / (4 pi)
 * for a flux Phi_v in lumens; watts go through the efficacy first
 * (Phi_v = K Phi); candela pass through. A negative or non-finite amount or
 * efficacy gives 0. Can't fail. */
real colour_point_candela(real amount, colour_unit unit, real efficacy);

/* `colour` rescaled so that its luminance (colour_luminance) is Y, keeping
 * its chromaticity; black or negative-luminance colours give the grey of
 * luminance Y. Can't fail. */
RADIANCE colour_with_luminance(RADIANCE colour, real Y);

/* The RADIANCE-unit intensity (W/sr per channel, see Units above) of an
 * isotropic point light of the given colour and amount: luminance
 * candela / 683, the chromaticity of `colour`. Can't fail. */
RADIANCE colour_point_intensity(RADIANCE colour, real amount, colour_unit unit,
                                real efficacy);

#endif
