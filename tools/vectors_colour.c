/*
 * vectors_colour.c - writes the test vectors of colour (ch. 2, app. J, K)
 * into DIR/colour_*.csv: the sRGB transfer curve, RGB <-> XYZ matrices of
 * the standard spaces, adaptation matrices and adapted colours, CMF samples
 * and the analytic fit, and blackbody values. Expected values are computed
 * in long double by code of this file (not src/colour/colour.c or src/colour/spectrum.c)
 * from the published definitions, or are published numbers. The blackbody
 * integrals read the CIE 1931 table through spectrum_cmf_data() (the
 * published data in double, whatever real is; the suite checks it against
 * CIE's checksums). Usage: vectors_colour DIR
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "colour/spectrum.h"
#include "vectors.h"

typedef long double ld;
typedef struct {
    ld m[3][3];
} mat;

static FILE *open_csv(const char *dir, const char *name, const char *what,
                      const char *header)
{
    FILE *f = vectors_open(dir, name);
    fprintf(f, "# %s\n# Written by tools/vectors_colour.c (make vectors); "
               "expected values in long double unless the source column "
               "says otherwise.\n%s\n", what, header);
    return f;
}

/* --- long double 3x3 algebra, independent of colour.c ----------------- */

static mat mul(mat a, mat b)
{
    mat r;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            r.m[i][j] = 0;
            for (int k = 0; k < 3; k++)
                r.m[i][j] += a.m[i][k] * b.m[k][j];
        }
    return r;
}

/* Gauss-Jordan with partial pivoting (a different method from the
 * adjugate of colour.c) */
static mat inverse(mat a)
{
    mat r = { { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } } };
    for (int c = 0; c < 3; c++) {
        int p = c;
        for (int i = c + 1; i < 3; i++)
            if (fabsl(a.m[i][c]) > fabsl(a.m[p][c]))
                p = i;
        for (int j = 0; j < 3; j++) {
            ld t = a.m[c][j]; a.m[c][j] = a.m[p][j]; a.m[p][j] = t;
            t = r.m[c][j]; r.m[c][j] = r.m[p][j]; r.m[p][j] = t;
        }
        ld d = a.m[c][c];
        for (int j = 0; j < 3; j++) {
            a.m[c][j] /= d;
            r.m[c][j] /= d;
        }
        for (int i = 0; i < 3; i++)
            if (i != c) {
                ld f = a.m[i][c];
                for (int j = 0; j < 3; j++) {
                    a.m[i][j] -= f * a.m[c][j];
                    r.m[i][j] -= f * r.m[c][j];
                }
            }
    }
    return r;
}

static void apply(mat m, const ld v[3], ld out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = m.m[i][0] * v[0] + m.m[i][1] * v[1] + m.m[i][2] * v[2];
}

/* the white of chromaticity (x, y) at Y = 1 */
static void white(ld x, ld y, ld w[3])
{
    w[0] = x / y;
    w[1] = 1;
    w[2] = (1 - x - y) / y;
}

/* The published definitions: primaries and whites (decimal literals read
 * as long double; the CIE RGB ones are the spectral locus of the 1-nm
 * table at 700, 546.1, 435.8 nm, as in src/colour/colour.c). Index = the
 * colour_space_id and colour_white_id enums. */
static const ld PRIM[4][6] = {
    { 0.64L, 0.33L, 0.30L, 0.60L, 0.15L, 0.06L },        /* IEC 61966-2-1 */
    { 0.708L, 0.292L, 0.170L, 0.797L, 0.131L, 0.046L },  /* BT.2020 */
    { 0.64L, 0.33L, 0.21L, 0.71L, 0.15L, 0.06L },        /* Adobe RGB */
    { 0.7346900233L, 0.2653099767L, 0.2736826753L, 0.7174214263L,
      0.1665346669L, 0.008883964460L }                   /* CIE RGB */
};
static const int SPACE_WHITE[4] = { 0, 0, 0, 3 };
static const char *const SPACE_NAME[4] = { "sRGB", "Rec2020", "AdobeRGB", "CIERGB" };
static const ld WHITE[4][2] = { { 0.3127L, 0.3290L }, { 0.3457L, 0.3585L },
                                { 0.44757L, 0.40745L }, { 1.0L / 3, 1.0L / 3 } };
static const char *const WHITE_NAME[4] = { "D65", "D50", "A", "E" };

static void white_of(int id, ld w[3])
{
    if (id == 3) { /* E is exactly (1, 1, 1) */
        w[0] = w[1] = w[2] = 1;
        return;
    }
    white(WHITE[id][0], WHITE[id][1], w);
}

static mat rgb_to_xyz(int space)
{
    mat P;
    for (int j = 0; j < 3; j++) {
        ld c[3];
        white(PRIM[space][2 * j], PRIM[space][2 * j + 1], c);
        for (int i = 0; i < 3; i++)
            P.m[i][j] = c[i];
    }
    ld w[3], s[3];
    white_of(SPACE_WHITE[space], w);
    apply(inverse(P), w, s);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            P.m[i][j] *= s[j];
    return P;
}

/* cone matrices: identity, Hunt-Pointer-Estevez (E), Bradford (Lam 1985) */
static const mat CONES[3] = {
    { { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } } },
    { { { 0.38971L, 0.68898L, -0.07868L }, { -0.22981L, 1.18340L, 0.04641L },
        { 0, 0, 1 } } },
    { { { 0.8951L, 0.2664L, -0.1614L }, { -0.7502L, 1.7135L, 0.0367L },
        { 0.0389L, -0.0685L, 1.0296L } } }
};
static const char *const METHOD_NAME[3] = { "xyz_scaling", "von_kries", "bradford" };

static mat adaptation(int method, int from, int to)
{
    ld s[3], d[3], cs[3], cd[3];
    white_of(from, s);
    white_of(to, d);
    apply(CONES[method], s, cs);
    apply(CONES[method], d, cd);
    mat D = { { { cd[0] / cs[0], 0, 0 }, { 0, cd[1] / cs[1], 0 }, { 0, 0, cd[2] / cs[2] } } };
    return mul(inverse(CONES[method]), mul(D, CONES[method]));
}

static void print_mat(FILE *f, mat m)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            fprintf(f, ",%.17Lg", m.m[i][j]);
}

static void matrices(const char *dir)
{
    FILE *f = open_csv(dir, "colour_matrices.csv",
        "RGB <-> XYZ matrices of the RGB spaces (space = colour_space_id: 0 sRGB,\n"
        "# 1 Rec. 2020, 2 Adobe RGB (1998), 3 CIE RGB) built from their primaries\n"
        "# and white (SMPTE RP 177), and chromatic adaptation matrices between the\n"
        "# whites (from, to = colour_white_id: 0 D65, 1 D50, 2 A, 3 E) by XYZ\n"
        "# scaling, von Kries (HPE cones) and Bradford; m<i><j> = row i, column j.\n"
        "# Tolerances: 64 ulp of 1 times the magnitude (~4) for a derivation in\n"
        "# float or double arithmetic.",
        "matrix,space,from,to,m00,m01,m02,m10,m11,m12,m20,m21,m22,tol_float,tol_double,source");
    const char *ftol = "3e-05", *dtol = "5e-14";
    for (int s = 0; s < 4; s++) {
        mat m = rgb_to_xyz(s);
        fprintf(f, "rgb_to_xyz,%d,-1,-1", s);
        print_mat(f, m);
        fprintf(f, ",%s,%s,%s primaries + white (SMPTE RP 177) long double\n", ftol, dtol,
                SPACE_NAME[s]);
        fprintf(f, "xyz_to_rgb,%d,-1,-1", s);
        print_mat(f, inverse(m));
        fprintf(f, ",%s,%s,%s inverse by Gauss-Jordan long double\n", ftol, dtol,
                SPACE_NAME[s]);
    }
    for (int method = 0; method < 3; method++)
        for (int from = 0; from < 4; from++)
            for (int to = 0; to < 4; to++) {
                if (from == to)
                    continue;
                fprintf(f, "%s,-1,%d,%d", METHOD_NAME[method], from, to);
                print_mat(f, adaptation(method, from, to));
                fprintf(f, ",%s,%s,%s %s->%s long double\n", ftol, dtol,
                        METHOD_NAME[method], WHITE_NAME[from], WHITE_NAME[to]);
            }
    vectors_close(f, dir, "colour_matrices.csv");
}

/* --- the sRGB curve ------------------------------------------------------- */

static void srgb(const char *dir)
{
    FILE *f = open_csv(dir, "colour_srgb.csv",
        "The sRGB transfer curve of IEC 61966-2-1 sec. 5.2: linear -> encoded and\n"
        "# the 8-bit code (clamp, encode, round half up). Inputs are floats\n"
        "# (exact decimal). tol: 4 ulp of 1 in float / double.",
        "linear,encoded,byte,tol_float,tol_double,source");
    for (int k = -4; k <= 260; k++) {
        float v;
        if (k < 0)
            v = -(float)(k * k) * 0.01f; /* out of gamut: odd symmetry */
        else if (k <= 60)
            v = (float)k * 0.0001f; /* the toe and the junction at 0.0031308 */
        else
            v = (float)(k - 60) * 0.006f; /* up to 1.2 */
        ld x = v, e;
        ld a = fabsl(x);
        e = a <= 0.0031308L ? 12.92L * a : 1.055L * powl(a, 1 / 2.4L) - 0.055L;
        if (x < 0)
            e = -e;
        int byte = v <= 0 ? 0 : v >= 1 ? 255 : (int)(e * 255 + 0.5L);
        fprintf(f, "%.17g,%.17Lg,%d,5e-07,1e-15,IEC 61966-2-1 long double\n",
                (double)v, e, byte);
    }
    vectors_close(f, dir, "colour_srgb.csv");
}

/* --- adapted colours ------------------------------------------------------- */

static void adapted(const char *dir)
{
    FILE *f = open_csv(dir, "colour_adapt.csv",
        "Colours adapted between whites (app. J): input XYZ (floats, exact decimal)\n"
        "# under white `from`, output XYZ under white `to` by each method\n"
        "# (colour_white_id 0 D65, 1 D50, 2 A, 3 E). tol: 64 ulp of the largest\n"
        "# value.",
        "method,from,to,X,Y,Z,eX,eY,eZ,tol_float,tol_double,source");
    static const float in[6][3] = { { 0.2f, 0.3f, 0.4f }, { 0.9f, 0.5f, 0.1f },
                                    { 0.05f, 0.06f, 0.3f }, { 1.0f, 1.0f, 1.0f },
                                    { 0.412390799f, 0.212639006f, 0.019330819f },
                                    { 0.01f, 0.02f, 0.005f } };
    for (int method = 0; method < 3; method++)
        for (int from = 0; from < 4; from++)
            for (int to = 0; to < 4; to++) {
                if (from == to)
                    continue;
                mat m = adaptation(method, from, to);
                for (int k = 0; k < 6; k++) {
                    ld v[3] = { in[k][0], in[k][1], in[k][2] }, o[3];
                    apply(m, v, o);
                    fprintf(f, "%d,%d,%d,%.17g,%.17g,%.17g,%.17Lg,%.17Lg,%.17Lg,"
                               "2e-05,4e-14,%s long double\n",
                            method, from, to, (double)in[k][0], (double)in[k][1],
                            (double)in[k][2], o[0], o[1], o[2], METHOD_NAME[method]);
                }
            }
    vectors_close(f, dir, "colour_adapt.csv");
}

/* --- colour-matching functions ---------------------------------------------- */

/* Published rows of the CIE 1931 table (CIE 018:2019; CIE 15:2004 Table
 * T.4 for 380-780 nm), every 10 nm: typed here from the standard,
 * independently of src/colour/spectrum.c's table. */
static const struct {
    int lambda;
    double x, y, z;
} CIE_ROWS[] = {
    { 360, 0.0001299, 0.000003917, 0.0006061 },
    { 380, 0.001368, 0.000039, 0.006450001 },
    { 400, 0.01431, 0.000396, 0.06785001 },
    { 420, 0.13438, 0.004, 0.6456 },
    { 440, 0.34828, 0.023, 1.74706 },
    { 460, 0.2908, 0.06, 1.6692 },
    { 480, 0.09564, 0.13902, 0.8129501 },
    { 500, 0.0049, 0.323, 0.272 },
    { 520, 0.06327, 0.71, 0.07824999 },
    { 540, 0.2904, 0.954, 0.0203 },
    { 555, 0.5120501, 1.0, 0.005749999 },
    { 560, 0.5945, 0.995, 0.0039 },
    { 580, 0.9163, 0.87, 0.001650001 },
    { 600, 1.0622, 0.631, 0.0008 },
    { 620, 0.8544499, 0.381, 0.00019 },
    { 640, 0.4479, 0.175, 0.00002 },
    { 660, 0.1649, 0.061, 0 },
    { 680, 0.04677, 0.017, 0 },
    { 700, 0.01135916, 0.004102, 0 },
    { 720, 0.002899327, 0.001047, 0 },
    { 740, 0.0006900786, 0.0002492, 0 },
    { 760, 0.0001661505, 0.00006, 0 },
    { 780, 0.00004150994, 0.00001499, 0 },
    { 830, 0.000001251141, 0.00000045181, 0 },
};

static ld lobe(ld l, ld mu, ld s1, ld s2)
{
    ld t = (l - mu) / (l < mu ? s1 : s2);
    return expl(-0.5L * t * t);
}

static void cmf(const char *dir)
{
    FILE *f = open_csv(dir, "colour_cmf.csv",
        "CIE 1931 2-degree colour-matching functions: published rows (xbar,\n"
        "# ybar, zbar; CIE 018:2019, DOI 10.25039/CIE.DS.xvudnb9b) and the\n"
        "# multi-lobe fit of Wyman, Sloan, Shirley, JCGT 2(2) 2013, eqs. (2)-(4)\n"
        "# (wx, wy, wz) in long double. tol: float rounding of the published\n"
        "# values (6e-8 relative) / of the fit (2 ulp of 1).",
        "lambda,xbar,ybar,zbar,wx,wy,wz,tol_float,tol_double,source");
    for (size_t k = 0; k < sizeof CIE_ROWS / sizeof CIE_ROWS[0]; k++) {
        ld l = CIE_ROWS[k].lambda;
        ld wx = 1.056L * lobe(l, 599.8L, 37.9L, 31.0L) +
                0.362L * lobe(l, 442.0L, 16.0L, 26.7L) -
                0.065L * lobe(l, 501.1L, 20.4L, 26.2L);
        ld wy = 0.821L * lobe(l, 568.8L, 46.9L, 40.5L) +
                0.286L * lobe(l, 530.9L, 16.3L, 31.1L);
        ld wz = 1.217L * lobe(l, 437.0L, 11.8L, 36.0L) +
                0.681L * lobe(l, 459.0L, 26.0L, 13.8L);
        fprintf(f, "%d,%.10g,%.10g,%.10g,%.17Lg,%.17Lg,%.17Lg,4e-07,4e-15,"
                   "CIE 018:2019 table; Wyman 2013 long double\n",
                CIE_ROWS[k].lambda, CIE_ROWS[k].x, CIE_ROWS[k].y, CIE_ROWS[k].z,
                wx, wy, wz);
    }
    vectors_close(f, dir, "colour_cmf.csv");
}

/* --- blackbody -------------------------------------------------------------- */

/* c1L, c2 and sigma from h, c, k (exact in the 2019 SI), in long double */
static const ld H = 6.62607015e-34L, C = 299792458.0L, KB = 1.380649e-23L;

static ld planck(ld lambda_nm, ld T)
{
    ld c1 = 2 * H * C * C, c2 = H * C / KB, l = lambda_nm * 1e-9L;
    return c1 / (l * l * l * l * l) / expm1l(c2 / (l * T)) * 1e-9L; /* per nm */
}

static void blackbody(const char *dir)
{
    FILE *f = open_csv(dir, "colour_blackbody.csv",
        "Blackbody (Planck) values: chromaticity x, y of the CIE 1931 observer\n"
        "# (1-nm table, trapezoid rule 360-830 nm); luminance (cd/m^2) = 683 int\n"
        "# v L; efficacy = luminance pi / (sigma T^4) (lm/W of all radiation);\n"
        "# efficacy_band = 683 int v L / int L over 360-830 nm; the Wien peak\n"
        "# lambda_max (nm) and L there (W/(m^2 sr nm)), with c1L = 2hc^2,\n"
        "# c2 = hc/k, sigma from the exact SI h, c, k. Tolerances: relative\n"
        "# (tol_rel_*) except tol_xy_* (absolute); float: the final rounding of\n"
        "# a result summed in double (the C code sums in double in both builds).",
        "T,x,y,luminance,efficacy,efficacy_band,lambda_max,L_max,"
        "tol_xy_float,tol_xy_double,tol_rel_float,tol_rel_double,source");
    static const double temps[] = { 500, 800, 1000, 1500, 1900, 2000, 2700,
                                    2855.4958516593747, 3000, 4000, 5000, 5778,
                                    6500, 6630, 7500, 10000, 12000, 20000, 1e5, 1e6 };
    ld sigma = 2 * powl(3.14159265358979323846264L, 5) * powl(KB, 4) /
               (15 * H * H * H * C * C);
    ld b_nm = 0;
    {
        /* Wien: lambda_max T = h c / (k x), x = 5 (1 - e^-x), by iteration */
        ld x = 5;
        for (int i = 0; i < 100; i++)
            x = 5 * (1 - expl(-x));
        b_nm = H * C / (KB * x) * 1e9L;
    }
    for (size_t k = 0; k < sizeof temps / sizeof temps[0]; k++) {
        ld T = temps[k], s[4] = { 0, 0, 0, 0 };
        const double *cmf = spectrum_cmf_data();
        for (int i = 0; i < SPECTRUM_CMF_COUNT; i++) {
            ld w = (i == 0 || i == SPECTRUM_CMF_COUNT - 1) ? 0.5L : 1;
            ld L = w * planck(360 + i, T);
            s[0] += L * cmf[3 * i];
            s[1] += L * cmf[3 * i + 1];
            s[2] += L * cmf[3 * i + 2];
            s[3] += L;
        }
        ld sum = s[0] + s[1] + s[2];
        ld lum = 683 * s[1];
        ld eff = lum * 3.14159265358979323846264L / (sigma * T * T * T * T);
        ld lmax = b_nm / T;
        fprintf(f, "%.17Lg,%.17Lg,%.17Lg,%.17Lg,%.17Lg,%.17Lg,%.17Lg,%.17Lg,"
                   "1e-06,1e-12,1e-06,1e-12,Planck + CIE 1931 table long double\n",
                T, s[0] / sum, s[1] / sum, lum, eff, 683 * s[1] / s[3], lmax,
                planck(lmax, T));
    }
    vectors_close(f, dir, "colour_blackbody.csv");
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s DIR\n", argv[0]);
        return 2;
    }
    matrices(argv[1]);
    srgb(argv[1]);
    adapted(argv[1]);
    cmf(argv[1]);
    blackbody(argv[1]);
    return 0;
}
