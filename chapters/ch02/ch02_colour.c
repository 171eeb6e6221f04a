/* cc -std=c11 -O2 -Iinclude chapters/ch02/ch02_colour.c src/colour/colour.c src/colour/spectrum.c src/core/error.c -lm -o ch02 */
/*
 * ch02_colour.c - chapter 2, colour in computer graphics, and appendices J
 * (chromatic adaptation) and K (colour coordinates), as three pictures and
 * a few printed tables.
 *
 *   ch02_chromaticity.ppm  the CIE 1931 xy diagram: the spectral locus
 *                          filled with its colours, the sRGB gamut, the
 *                          whites D65, D50, A, E and the Planckian locus
 *   ch02_blackbody.ppm     the colour of a blackbody from 1000 K to 12000 K
 *   ch02_white_balance.ppm a colour chart lit by illuminant A, shown as it
 *                          is and corrected to D65 by XYZ scaling, von
 *                          Kries and Bradford, next to a daylight reference
 *
 *   ch02_locus.csv, ch02_planck.csv, ch02_points.csv, ch02_gamut.csv,
 *   ch02_fill.csv          the diagram's curves, points and colours
 *   ch02_blackbody.csv     the ramp's chromaticity and display colour
 *   ch02_white_balance.csv the colour error of each correction
 *
 * Images are PPM (8-bit sRGB, no library); the CSV files are drawn with
 * axes and legends by chromaticity.gp, blackbody.gp and white_balance.gp
 * beside this file (`make figures`). The printed tables: the sRGB
 * matrices derived from the primaries, the luminous efficacy of blackbody
 * light (eq. (1.2)), a lamp given in watts turned into lumens, candela and
 * RADIANCE, and the colour error of each white balance.
 *
 * usage: ch02 [OUTDIR]   (default out/; --help)
 */
#include "../chapter.h"
#include "colour/colour.h"
#include "colour/spectrum.h"

/* --- a linear RGB picture, written as sRGB PPM ------------------------------ */

typedef struct {
    int w, h;
    RADIANCE *px; /* linear sRGB, 1 = display white */
} picture_t;

static picture_t picture_new(int w, int h, RADIANCE background)
{
    picture_t p = { w, h, malloc(sizeof(RADIANCE) * (size_t)w * (size_t)h) };
    if (!p.px) {
        fprintf(stderr, "ch02: out of memory\n");
        exit(1);
    }
    for (int i = 0; i < w * h; i++)
        p.px[i] = background;
    return p;
}

static void put(picture_t *p, int x, int y, RADIANCE c)
{
    if (x >= 0 && y >= 0 && x < p->w && y < p->h)
        p->px[y * p->w + x] = c;
}

/* A filled disc: the pen for lines and markers. */
static void dot(picture_t *p, double cx, double cy, double r, RADIANCE c)
{
    for (int y = (int)floor(cy - r); y <= (int)ceil(cy + r); y++)
        for (int x = (int)floor(cx - r); x <= (int)ceil(cx + r); x++)
            if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r)
                put(p, x, y, c);
}

static void line(picture_t *p, double x0, double y0, double x1, double y1,
                 double r, RADIANCE c)
{
    double len = hypot(x1 - x0, y1 - y0);
    int n = (int)(len * 2) + 1;
    for (int i = 0; i <= n; i++)
        dot(p, x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * i / n, r, c);
}

/* A 3x5 pixel font, enough for the labels: each glyph is five rows of
 * three cells, '#' on. */
static const char *glyph(char ch)
{
    static const char *const digits[10] = {
        "####.##.##.####", ".#.##..#..#.###", "###..#####..###", "###..####..####",
        "#.##.####..#..#", "####..###..####", "####..####.####", "###..#..#.#..#.",
        "####.#####.####", "####.####..####" };
    static const char *const letters[26] = {
        ".#.#.#####.##.#", "##.#.###.#.###.", ".###..#..#...##", "##.#.##.##.###.",
        "####..##.#..###", "####..##.#..#..", ".###..#.##.#.##", "#.##.#####.##.#",
        "###.#..#..#.###", "..#..#..##.#.#.", "#.##.###.#.##.#", "#..#..#..#..###",
        "#.########.##.#", "##.#.##.##.##.#", ".#.#.##.##.#.#.", "##.#.###.#..#..",
        ".#.#.##.###..##", "##.#.###.#.##.#", ".###...#...###.", "###.#..#..#..#.",
        "#.##.##.##.####", "#.##.##.##.#.#.", "#.##.########.#", "#.##.#.#.#.##.#",
        "#.##.#.#..#..#.", "###..#.#.#..###" };
    if (ch >= '0' && ch <= '9')
        return digits[ch - '0'];
    if (ch >= 'A' && ch <= 'Z')
        return letters[ch - 'A'];
    if (ch == '.')
        return "............#..";
    if (ch == '-')
        return "......###......";
    return "...............";
}

/* text with its top-left corner at (x, y), cells of s x s pixels */
static void text(picture_t *p, int x, int y, int s, const char *str, RADIANCE c)
{
    for (; *str; str++, x += 4 * s) {
        const char *g = glyph(*str);
        for (int row = 0; row < 5; row++)
            for (int col = 0; col < 3; col++)
                if (g[row * 3 + col] == '#')
                    for (int dy = 0; dy < s; dy++)
                        for (int dx = 0; dx < s; dx++)
                            put(p, x + col * s + dx, y + row * s + dy, c);
    }
}

/* Write P6 PPM, sRGB-encoded, through a temporary file renamed at the end
 * so that a failed write never leaves half an image under the real name. */
static int picture_write(const picture_t *p, const char *dir, const char *name)
{
    chapter_file_t cf;
    FILE *f = chapter_open(&cf, "ch02", dir, name);
    if (!f)
        return 1;
    fprintf(f, "P6\n%d %d\n255\n", p->w, p->h);
    for (int i = 0; i < p->w * p->h; i++) {
        unsigned char b[3] = { colour_srgb_encode_byte(p->px[i].r),
                               colour_srgb_encode_byte(p->px[i].g),
                               colour_srgb_encode_byte(p->px[i].b) };
        fwrite(b, 1, 3, f);
    }
    return chapter_close(&cf, "ch02");
}

/* A displayable version of any linear colour: out-of-gamut colours mixed
 * with white until no channel is negative (keeping their luminance), then
 * scaled so the largest channel is `peak`. Black stays black. */
static RADIANCE bright(RADIANCE c, real peak)
{
    c = colour_rgb_desaturate_into_gamut(c);
    real m = rad_max(c);
    return m > 0 ? rad_scale(c, peak / m) : c;
}

static const RADIANCE BLACK = { 0, 0, 0 };
static const RADIANCE WHITE = { 1, 1, 1 };

/* --- 1. the chromaticity diagram ------------------------------------------- */

/* The spectral locus, 1 nm apart, as a closed polygon (the line of
 * purples joins 830 nm back to 360 nm). */
static double locus[SPECTRUM_CMF_COUNT][2];

static void locus_init(void)
{
    for (int i = 0; i < SPECTRUM_CMF_COUNT; i++) {
        colour_xy_t c = spectrum_locus_xy((real)(SPECTRUM_LAMBDA_MIN + i));
        locus[i][0] = (double)c.x;
        locus[i][1] = (double)c.y;
    }
}

/* Is (x, y) inside the horseshoe? The even-odd rule over the polygon. */
static int inside_locus(double x, double y)
{
    int in = 0;
    for (int i = 0, j = SPECTRUM_CMF_COUNT - 1; i < SPECTRUM_CMF_COUNT; j = i++) {
        const double *a = locus[j], *b = locus[i];
        if ((b[1] > y) != (a[1] > y) &&
            x < b[0] + (a[0] - b[0]) * (y - b[1]) / (a[1] - b[1]))
            in = !in;
    }
    return in;
}

#define DIAG_SCALE 700.0 /* pixels per unit of x and y */
#define DIAG_LEFT 50
#define DIAG_TOP 20

/* picture coordinates of a chromaticity */
static double px_x(real x) { return DIAG_LEFT + (double)x * DIAG_SCALE; }
static double px_y(real y) { return DIAG_TOP + (0.9 - (double)y) * DIAG_SCALE; }

static void mark_white(picture_t *p, colour_xy_t w, const char *name, int dx, int dy)
{
    dot(p, px_x(w.x), px_y(w.y), 4.5, BLACK);
    dot(p, px_x(w.x), px_y(w.y), 2.5, WHITE);
    text(p, (int)px_x(w.x) + dx, (int)px_y(w.y) + dy, 2, name, BLACK);
}

/* The diagram's data for chromaticity.gp: the spectral locus, the
 * Planckian locus, the marked points, and a grid of the colours that
 * fill the horseshoe (white outside it), as the picture shows them. */
static int diagram_csv(const char *dir)
{
    chapter_file_t cf;
    FILE *f = chapter_open(&cf, "ch02", dir, "ch02_locus.csv");
    if (!f)
        return 1;
    fprintf(f, "# ch02: the spectral locus of the CIE 1931 observer, 1 nm "
               "apart\nlambda_nm,x,y\n");
    for (int i = 0; i < SPECTRUM_CMF_COUNT; i++)
        fprintf(f, "%d,%.6f,%.6f\n", SPECTRUM_LAMBDA_MIN + i, locus[i][0],
                locus[i][1]);
    int rc = chapter_close(&cf, "ch02");

    if (!(f = chapter_open(&cf, "ch02", dir, "ch02_planck.csv")))
        return 1;
    fprintf(f, "# ch02: the Planckian locus, the chromaticity of a "
               "blackbody at T kelvin\nT_K,x,y\n");
    for (double T = 1000; T < 25001; T *= 1.01) {
        colour_xy_t c = spectrum_blackbody_xy((real)T);
        fprintf(f, "%.1f,%.6f,%.6f\n", T, (double)c.x, (double)c.y);
    }
    rc |= chapter_close(&cf, "ch02");

    if (!(f = chapter_open(&cf, "ch02", dir, "ch02_points.csv")))
        return 1;
    colour_space_t s;
    colour_space_standard(&s, COLOUR_SPACE_SRGB);
    const struct {
        const char *name;
        colour_xy_t c;
    } pts[] = { { "sRGB red", s.red }, { "sRGB green", s.green },
                { "sRGB blue", s.blue },
                { "D65", colour_white_xy(COLOUR_WHITE_D65) },
                { "D50", colour_white_xy(COLOUR_WHITE_D50) },
                { "A", colour_white_xy(COLOUR_WHITE_A) },
                { "E", colour_white_xy(COLOUR_WHITE_E) } };
    fprintf(f, "# ch02: the sRGB primaries and the white points of app. "
               "J\nname,x,y\n");
    for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++)
        fprintf(f, "%s,%.6f,%.6f\n", pts[i].name, (double)pts[i].c.x,
                (double)pts[i].c.y);
    rc |= chapter_close(&cf, "ch02");

    if (!(f = chapter_open(&cf, "ch02", dir, "ch02_gamut.csv")))
        return 1;
    fprintf(f, "# ch02: the sRGB gamut, the triangle of its primaries, "
               "closed\ncorner,x,y\n");
    for (int i = 0; i < 4; i++)
        fprintf(f, "%s,%.6f,%.6f\n", pts[i % 3].name, (double)pts[i % 3].c.x,
                (double)pts[i % 3].c.y);
    rc |= chapter_close(&cf, "ch02");

    if (!(f = chapter_open(&cf, "ch02", dir, "ch02_fill.csv")))
        return 1;
    fprintf(f, "# ch02: the colour of each chromaticity at luminance 1, "
               "brought into the sRGB gamut (sRGB codes 0-255; white outside "
               "the locus)\nx,y,r,g,b\n");
    for (int j = 0; j <= 180; j++)
        for (int i = 0; i <= 160; i++) {
            double x = i * 0.005, y = j * 0.005;
            RADIANCE c = WHITE;
            if (y > 0 && inside_locus(x, y)) {
                colour_xyY_t q = { (real)x, (real)y, 1 };
                c = bright(colour_xyz_to_rgb(colour_xyY_to_xyz(q)), REAL_C(0.9));
            }
            fprintf(f, "%.3f,%.3f,%d,%d,%d\n", x, y,
                    colour_srgb_encode_byte(c.r), colour_srgb_encode_byte(c.g),
                    colour_srgb_encode_byte(c.b));
        }
    return rc | chapter_close(&cf, "ch02");
}

static int chromaticity_diagram(const char *dir)
{
    const int W = DIAG_LEFT + (int)(0.8 * DIAG_SCALE) + 20;
    const int H = DIAG_TOP + (int)(0.9 * DIAG_SCALE) + 40;
    RADIANCE grey = rad_grey(REAL_C(0.02));
    picture_t p = picture_new(W, H, grey);
    locus_init();

    /* Fill the horseshoe: each xy at luminance 1 (XYZ = (x/y, 1, z/y)),
     * brought into the sRGB gamut and shown at full brightness. Only the
     * triangle of the sRGB primaries is shown truly; outside it every
     * colour is the nearest one the display can make. */
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double x = (i - DIAG_LEFT) / DIAG_SCALE;
            double y = 0.9 - (j - DIAG_TOP) / DIAG_SCALE;
            if (y <= 0 || !inside_locus(x, y))
                continue;
            colour_xyY_t c = { (real)x, (real)y, 1 };
            put(&p, i, j, bright(colour_xyz_to_rgb(colour_xyY_to_xyz(c)), REAL_C(0.9)));
        }

    /* axes with ticks every 0.1 */
    line(&p, px_x(0), px_y(0), px_x(REAL_C(0.8)), px_y(0), 0.6, WHITE);
    line(&p, px_x(0), px_y(0), px_x(0), px_y(REAL_C(0.9)), 0.6, WHITE);
    for (int k = 0; k <= 8; k++) {
        char lab[16];
        snprintf(lab, sizeof lab, "0.%d", k);
        line(&p, px_x((real)k / 10), px_y(0), px_x((real)k / 10), px_y(0) + 6, 0.6, WHITE);
        line(&p, px_x(0), px_y((real)k / 10), px_x(0) - 6, px_y((real)k / 10), 0.6, WHITE);
        text(&p, (int)px_x((real)k / 10) - 10, (int)px_y(0) + 10, 2, lab, WHITE);
        text(&p, 8, (int)px_y((real)k / 10) - 5, 2, lab, WHITE);
    }
    text(&p, (int)px_x(REAL_C(0.8)) - 8, (int)px_y(0) + 24, 2, "X", WHITE);
    text(&p, 14, DIAG_TOP - 14, 2, "Y", WHITE);

    /* the spectral locus, with wavelength marks */
    for (int l = 380; l < 700; l++) {
        colour_xy_t a = spectrum_locus_xy((real)l), b = spectrum_locus_xy((real)(l + 1));
        line(&p, px_x(a.x), px_y(a.y), px_x(b.x), px_y(b.y), 1.0, WHITE);
    }
    colour_xy_t violet = spectrum_locus_xy(380), red = spectrum_locus_xy(700);
    line(&p, px_x(violet.x), px_y(violet.y), px_x(red.x), px_y(red.y), 0.5, WHITE);
    static const int marks[] = { 460, 470, 480, 490, 500, 510, 520, 530, 540,
                                 550, 560, 570, 580, 590, 600, 620, 700 };
    for (size_t k = 0; k < sizeof marks / sizeof marks[0]; k++) {
        colour_xy_t c = spectrum_locus_xy((real)marks[k]);
        /* label outward from the white point E */
        double dx = (double)c.x - 1.0 / 3, dy = (double)c.y - 1.0 / 3, n = hypot(dx, dy);
        char lab[16];
        snprintf(lab, sizeof lab, "%d", marks[k]);
        dot(&p, px_x(c.x), px_y(c.y), 3, WHITE);
        text(&p, (int)(px_x(c.x) + 18 * dx / n) - 10, (int)(px_y(c.y) - 18 * dy / n) - 5,
             2, lab, WHITE);
    }

    /* the sRGB gamut: the triangle of its primaries */
    colour_space_t s;
    colour_space_standard(&s, COLOUR_SPACE_SRGB);
    const colour_xy_t tri[4] = { s.red, s.green, s.blue, s.red };
    for (int k = 0; k < 3; k++)
        line(&p, px_x(tri[k].x), px_y(tri[k].y), px_x(tri[k + 1].x),
             px_y(tri[k + 1].y), 1.0, BLACK);
    text(&p, (int)px_x(s.green.x) + 8, (int)px_y(s.green.y) - 4, 2, "SRGB", BLACK);

    /* the Planckian locus, 1000 K to 25000 K, with temperature marks */
    for (double T = 1000; T < 25000; T *= 1.01) {
        colour_xy_t a = spectrum_blackbody_xy((real)T);
        colour_xy_t b = spectrum_blackbody_xy((real)(T * 1.01));
        line(&p, px_x(a.x), px_y(a.y), px_x(b.x), px_y(b.y), 1.0, BLACK);
    }
    static const int temps[] = { 1000, 1500, 2000, 3000, 4000, 6000, 10000 };
    for (size_t k = 0; k < sizeof temps / sizeof temps[0]; k++) {
        colour_xy_t c = spectrum_blackbody_xy((real)temps[k]);
        char lab[16];
        snprintf(lab, sizeof lab, "%dK", temps[k]);
        line(&p, px_x(c.x), px_y(c.y), px_x(c.x) + 5, px_y(c.y) + 9, 0.8, BLACK);
        if (temps[k] <= 3000 || temps[k] == 10000)
            text(&p, (int)px_x(c.x) - 8, (int)px_y(c.y) + 12, 2, lab, BLACK);
    }

    /* the white points of app. J */
    mark_white(&p, colour_white_xy(COLOUR_WHITE_D65), "D65", -34, -16);
    mark_white(&p, colour_white_xy(COLOUR_WHITE_D50), "D50", 8, -16);
    mark_white(&p, colour_white_xy(COLOUR_WHITE_A), "A", 8, -16);
    mark_white(&p, colour_white_xy(COLOUR_WHITE_E), "E", -8, -18);

    int rc = picture_write(&p, dir, "ch02_chromaticity.ppm");
    free(p.px);
    return rc | diagram_csv(dir);
}

/* --- 2. the blackbody ramp ---------------------------------------------------- */

static int blackbody_ramp(const char *dir)
{
    /* one column per 10 K from 1000 to 12000 K. Top band: the colour at
     * full brightness (chromaticity only). Bottom band: the same colours
     * seen with the eye adapted to D65, at equal luminance, so that only
     * hue and saturation change. */
    const int W = 1101 + 40, H = 150;
    picture_t p = picture_new(W, H, rad_grey(REAL_C(0.02)));
    for (int i = 0; i <= 1100; i++) {
        real T = (real)(1000 + 10 * i);
        RADIANCE c = spectrum_blackbody_rgb(T); /* luminance 1 */
        RADIANCE top = bright(c, 1);
        RADIANCE bottom = rad_scale(colour_rgb_desaturate_into_gamut(c), REAL_C(0.45));
        for (int y = 10; y < 70; y++)
            put(&p, 20 + i, y, top);
        for (int y = 74; y < 114; y++)
            put(&p, 20 + i, y, bottom);
    }
    for (int T = 1000; T <= 12000; T += 1000) {
        int x = 20 + (T - 1000) / 10;
        char lab[16];
        line(&p, x, 114, x, 120, 0.5, WHITE);
        snprintf(lab, sizeof lab, "%d", T);
        text(&p, x - (int)strlen(lab) * 4, 124, 2, lab, WHITE);
    }
    /* where the locus leaves the sRGB gamut (blue < 0 below it) */
    int x1900 = 20 + (1900 - 1000) / 10;
    line(&p, x1900, 2, x1900, 8, 0.5, WHITE);
    int rc = picture_write(&p, dir, "ch02_blackbody.ppm");
    free(p.px);

    chapter_file_t cf;
    FILE *f = chapter_open(&cf, "ch02", dir, "ch02_blackbody.csv");
    if (!f)
        return 1;
    fprintf(f, "# ch02: a blackbody's chromaticity and its colour at full "
               "brightness (sRGB codes 0-255, the top band of "
               "ch02_blackbody.ppm)\nT_K,x,y,r,g,b\n");
    for (int T = 1000; T <= 12000; T += 50) {
        colour_xy_t c = spectrum_blackbody_xy((real)T);
        RADIANCE top = bright(spectrum_blackbody_rgb((real)T), 1);
        fprintf(f, "%d,%.6f,%.6f,%d,%d,%d\n", T, (double)c.x, (double)c.y,
                colour_srgb_encode_byte(top.r), colour_srgb_encode_byte(top.g),
                colour_srgb_encode_byte(top.b));
    }
    return rc | chapter_close(&cf, "ch02");
}

/* --- 3. white balance ----------------------------------------------------------- */

/* A synthetic colour chart: 18 colours and 6 greys, each a smooth
 * reflectance spectrum built from a base level, a step (logistic, centre
 * mu, width w: up if w > 0, down if w < 0) and a bump (Gaussian). */
typedef struct {
    double base, step, step_mu, step_w, bump, bump_mu, bump_sigma;
} patch_t;

static const patch_t CHART[24] = {
    { 0.10, 0.25, 600, 40, 0.10, 460, 30 },  /* dark skin */
    { 0.20, 0.45, 590, 35, 0.08, 450, 30 },  /* light skin */
    { 0.10, 0.00, 0, 1, 0.25, 460, 45 },     /* blue sky */
    { 0.05, 0.12, 690, 20, 0.12, 545, 35 },  /* foliage */
    { 0.20, 0.15, 650, 30, 0.35, 450, 40 },  /* blue flower */
    { 0.10, 0.00, 0, 1, 0.55, 510, 45 },     /* bluish green */
    { 0.05, 0.80, 580, 15, 0.00, 0, 1 },     /* orange */
    { 0.08, 0.00, 0, 1, 0.35, 440, 35 },     /* purplish blue */
    { 0.08, 0.65, 595, 12, 0.08, 430, 30 },  /* moderate red */
    { 0.06, 0.20, 660, 25, 0.14, 420, 30 },  /* purple */
    { 0.06, 0.70, 520, 18, 0.00, 0, 1 },     /* yellow green */
    { 0.05, 0.85, 560, 15, 0.00, 0, 1 },     /* orange yellow */
    { 0.04, 0.00, 0, 1, 0.40, 445, 25 },     /* blue */
    { 0.04, 0.00, 0, 1, 0.40, 535, 30 },     /* green */
    { 0.04, 0.65, 610, 10, 0.00, 0, 1 },     /* red */
    { 0.05, 0.85, 505, 12, 0.00, 0, 1 },     /* yellow */
    { 0.55, -0.45, 500, 15, 0.00, 0, 1 },   /* magenta: reflects both ends */
    { 0.05, 0.00, 0, 1, 0.45, 485, 40 },     /* cyan */
    { 0.90, 0.00, 0, 1, 0.00, 0, 1 },        /* white */
    { 0.59, 0.00, 0, 1, 0.00, 0, 1 },        /* neutral 8 */
    { 0.36, 0.00, 0, 1, 0.00, 0, 1 },        /* neutral 6.5 */
    { 0.19, 0.00, 0, 1, 0.00, 0, 1 },        /* neutral 5 */
    { 0.09, 0.00, 0, 1, 0.00, 0, 1 },        /* neutral 3.5 */
    { 0.03, 0.00, 0, 1, 0.00, 0, 1 }         /* black */
};

static double reflectance(const patch_t *q, double lambda)
{
    double r = q->base;
    if (q->step != 0)
        r += q->step / (1 + exp(-(lambda - q->step_mu) / q->step_w));
    if (q->bump != 0) {
        double t = (lambda - q->bump_mu) / q->bump_sigma;
        r += q->bump * exp(-0.5 * t * t);
    }
    if (q->step < 0) /* a notch: the step falls, then rises again at 600 nm */
        r -= q->step / (1 + exp(-(lambda - 600) / 15.0));
    return fmin(fmax(r, 0.0), 1.0);
}

/* light reflected by a patch under a blackbody of temperature T */
typedef struct {
    const patch_t *patch;
    real T;
} lit_t;

static real lit_spectrum(real lambda, const void *ctx)
{
    const lit_t *l = ctx;
    double r = l->patch ? reflectance(l->patch, (double)lambda) : 1;
    return (real)(r * (double)spectrum_planck(lambda, l->T));
}

/* XYZ of each patch under a blackbody of temperature T, with the white
 * of the light at Y = 1 (CIE 15 sec. 7.1: Y of a perfect reflector = 1). */
static void chart_xyz(real T, colour_xyz_t out[24], colour_xyz_t *white)
{
    lit_t l = { NULL, T };
    *white = spectrum_to_xyz(lit_spectrum, &l);
    real k = 1 / white->Y;
    white->X *= k; white->Y = 1; white->Z *= k;
    for (int i = 0; i < 24; i++) {
        l.patch = &CHART[i];
        colour_xyz_t c = spectrum_to_xyz(lit_spectrum, &l);
        out[i].X = c.X * k; out[i].Y = c.Y * k; out[i].Z = c.Z * k;
    }
}

#define PATCH 40
#define GAP 4
#define PANEL_W (6 * (PATCH + GAP) + GAP)
#define PANEL_H (4 * (PATCH + GAP) + GAP)

static void draw_panel(picture_t *p, int x0, int y0, const colour_xyz_t xyz[24],
                       real exposure, const char *label)
{
    text(p, x0 + GAP, y0, 2, label, WHITE);
    y0 += 16;
    for (int i = 0; i < 24; i++) {
        RADIANCE c = rad_scale(colour_xyz_to_rgb(xyz[i]), exposure);
        c = colour_rgb_desaturate_into_gamut(c);
        int px = x0 + GAP + (i % 6) * (PATCH + GAP), py = y0 + GAP + (i / 6) * (PATCH + GAP);
        for (int y = 0; y < PATCH; y++)
            for (int x = 0; x < PATCH; x++)
                put(p, px + x, py + y, c);
    }
}

/* mean and largest Delta E*ab of a panel against the reference, both seen
 * with the D65 white */
static void delta_e(FILE *csv, const char *name, const colour_xyz_t a[24],
                    const colour_xyz_t ref[24])
{
    colour_xyz_t d65 = colour_white_xyz(COLOUR_WHITE_D65);
    double sum = 0, worst = 0;
    for (int i = 0; i < 24; i++) {
        double e = (double)colour_delta_e76(colour_xyz_to_lab(a[i], d65),
                                            colour_xyz_to_lab(ref[i], d65));
        sum += e;
        worst = fmax(worst, e);
    }
    printf("  %-28s mean %6.2f   max %6.2f\n", name, sum / 24, worst);
    if (csv)
        fprintf(csv, "%s,%.4f,%.4f\n", name, sum / 24, worst);
}

static int white_balance(const char *dir)
{
    colour_xyz_t under_a[24], ref[24], wa, wref;
    real T_a = (real)SPECTRUM_ILLUMINANT_A_T;
    chart_xyz(T_a, under_a, &wa);
    /* The reference: the chart under a 6504 K blackbody (near D65; D65 is a
     * tabulated daylight spectrum, not Planck's) adapted by Bradford from
     * that light's white to D65: a small step. */
    chart_xyz(6504, ref, &wref);
    colour_xyz_t d65 = colour_white_xyz(COLOUR_WHITE_D65);
    colour_mat3_t m;
    colour_adaptation_matrix(&m, COLOUR_ADAPT_BRADFORD, wref, d65);
    for (int i = 0; i < 24; i++)
        ref[i] = colour_mat3_apply(&m, ref[i]);

    /* app. J: the same chart seen with the eye (or camera) adapted to A,
     * carried to D65 by each method */
    static const struct {
        colour_adaptation method;
        const char *label, *name;
    } methods[3] = { { COLOUR_ADAPT_XYZ_SCALING, "XYZ SCALING", "XYZ scaling" },
                     { COLOUR_ADAPT_VON_KRIES, "VON KRIES", "von Kries (HPE cones)" },
                     { COLOUR_ADAPT_BRADFORD, "BRADFORD", "Bradford" } };
    colour_xyz_t fixed[3][24];
    for (int k = 0; k < 3; k++) {
        colour_adaptation_matrix(&m, methods[k].method, wa, d65);
        for (int i = 0; i < 24; i++)
            fixed[k][i] = colour_mat3_apply(&m, under_a[i]);
    }

    picture_t p = picture_new(5 * PANEL_W + 6 * GAP, PANEL_H + 24, rad_grey(REAL_C(0.02)));
    /* Uncorrected, the A white is far outside the display's white: its red
     * channel is 1.85 times its luminance. Expose it so that its white
     * patch peaks where the others' do. */
    RADIANCE wa_rgb = colour_xyz_to_rgb(wa);
    draw_panel(&p, GAP, 2, under_a, 1 / rad_max(wa_rgb), "ILLUMINANT A");
    for (int k = 0; k < 3; k++)
        draw_panel(&p, GAP + (k + 1) * (PANEL_W + GAP), 2, fixed[k], 1, methods[k].label);
    draw_panel(&p, GAP + 4 * (PANEL_W + GAP), 2, ref, 1, "DAYLIGHT");

    printf("\nWhite balance: a chart lit by illuminant A (%.1f K), corrected to D65.\n"
           "Delta E*ab (CIE 1976, D65 white) against the chart under 6504 K light:\n",
           (double)T_a);
    chapter_file_t cf;
    FILE *csv = chapter_open(&cf, "ch02", dir, "ch02_white_balance.csv");
    if (csv)
        fprintf(csv, "# ch02: a chart lit by illuminant A, corrected to D65; "
                     "Delta E*ab (CIE 1976) against the chart under 6504 K "
                     "light\nmethod,mean_delta_e,max_delta_e\n");
    delta_e(csv, "uncorrected", under_a, ref);
    for (int k = 0; k < 3; k++)
        delta_e(csv, methods[k].name, fixed[k], ref);
    int rc = chapter_close(&cf, "ch02");
    rc |= picture_write(&p, dir, "ch02_white_balance.ppm");
    free(p.px);
    return rc;
}

/* --- the printed tables --------------------------------------------------------- */

static void tables(void)
{
    colour_space_t s;
    colour_space_standard(&s, COLOUR_SPACE_SRGB);
    printf("sRGB -> XYZ, derived from the primaries and D65 (IEC 61966-2-1 prints\n"
           "0.4124 0.3576 0.1805 / 0.2126 0.7152 0.0722 / 0.0193 0.1192 0.9505):\n");
    for (int i = 0; i < 3; i++)
        printf("  %9.6f %9.6f %9.6f\n", (double)s.rgb_to_xyz.m[i][0],
               (double)s.rgb_to_xyz.m[i][1], (double)s.rgb_to_xyz.m[i][2]);

    printf("\nBlackbody light (Planck), eq. (1.2): efficacy K = 683 int v L / int L\n"
           "  T (K)     x       y     K all (lm/W)  K 360-830 nm (lm/W)\n");
    static const int temps[] = { 1000, 1500, 2000, 2700, 2856, 3500, 5000, 6500, 6600, 10000 };
    for (size_t k = 0; k < sizeof temps / sizeof temps[0]; k++) {
        real T = (real)temps[k];
        colour_xy_t c = spectrum_blackbody_xy(T);
        printf("  %5d  %.4f  %.4f  %10.2f  %12.2f\n", temps[k], (double)c.x, (double)c.y,
               (double)spectrum_blackbody_efficacy(T),
               (double)spectrum_blackbody_efficacy_band(T));
    }

    /* A lamp in the book's terms (ch. 1): 100 W electrical, efficiency 0.03 */
    real T = (real)SPECTRUM_ILLUMINANT_A_T;
    real watts = colour_radiant_watts_from_electric(100, COLOUR_EFFICIENCY_INCANDESCENT);
    real K = spectrum_blackbody_efficacy_band(T);
    real cd = colour_point_candela(watts, COLOUR_UNIT_WATT, K);
    RADIANCE I = colour_point_intensity(spectrum_blackbody_rgb(T), watts, COLOUR_UNIT_WATT, K);
    printf("\nA 100 W incandescent lamp (ch. 1: radiant flux = 0.03 x electrical power):\n"
           "  %.1f W radiated (360-830 nm), as a %.1f K blackbody: K = %.1f lm/W,\n"
           "  %.0f lm, isotropic: %.1f cd, RADIANCE intensity (W/sr per channel)\n"
           "  (%.4f, %.4f, %.4f) with luminance %.4f = %.1f cd / 683.\n",
           (double)watts, (double)T, (double)K, (double)(watts * K), (double)cd,
           (double)I.r, (double)I.g, (double)I.b, (double)colour_luminance(I), (double)cd);
}

int main(int argc, char **argv)
{
    const chapter_cli_t cli = {
        "ch02",
        "Chapter 2 and appendices J, K: the chromaticity diagram, a blackbody "
        "ramp and a\nwhite balance, as PPM pictures and CSV files (for "
        "`make figures`), and printed\ntables.",
        "out", NULL, 0
    };
    const char *dir;
    int rc = chapter_begin(&cli, argc, argv, &dir);
    if (rc >= 0)
        return rc;
    tables();
    rc = white_balance(dir);
    putchar('\n');
    rc |= chromaticity_diagram(dir);
    rc |= blackbody_ramp(dir);
    return rc;
}
