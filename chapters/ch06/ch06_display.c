/* cc -std=c11 -O2 -Iinclude chapters/ch06/ch06_display.c src/colour/tonemap.c src/io/image.c src/io/netpbm.c src/io/fileio.c src/colour/colour.c src/core/error.c -lm -o ch06 */
/*
 * ch06_display.c - chapter 6, output to the screen: one high-dynamic-range
 * image (a room lit by a window with the sun in it and a lamp: about 10^7
 * from the darkest corner to the sun), shown by every operator of
 * tonemap.h side by side, and the tone reproduction curve of the histogram
 * adjustment (Ward Larson, Rushmeier, Piatko 1997) plotted against the
 * naive histogram equalisation it improves on.
 *
 *   ch06_scene.pfm            the HDR image (linear radiance, PFM)
 *   ch06_<operator>.ppm       each operator's picture (sRGB, 8 bits)
 *   ch06_operators.ppm        all five side by side, in the order linear,
 *                             exponential, reinhard, drago, histogram
 *   ch06_trc.ppm              the tone reproduction curves and the
 *                             histogram (see README.md)
 *   ch06_trc_bins.csv         the histogram before and after the ceiling
 *   ch06_trc_curve.csv        Ld(Lw) of the adjustment and of the naive
 *                             equalisation, with their log-log slopes
 *   ch06_display.md           the table printed below
 *
 * The CSV files are drawn by trc.gp beside this
 * file (`make figures`).
 * usage: ch06 [OUTDIR]   (default out/; --help)
 */
#include "../chapter.h"
#include "colour/colour.h"
#include "io/fileio.h"
#include "io/image.h"
#include "io/netpbm.h"
#include "colour/tonemap.h"

#define W 320 /* size of the scene */
#define H 200
#define SS 4  /* supersamples per pixel side: the sun's edge */

/* --- the scene ------------------------------------------------------------- */

typedef struct {
    double r, g, b;
} rgb_t;

static rgb_t mk(double r, double g, double b)
{
    rgb_t c = { r, g, b };
    return c;
}

static rgb_t scale(rgb_t c, double s)
{
    return mk(c.r * s, c.g * s, c.b * s);
}

static rgb_t add(rgb_t a, rgb_t b)
{
    return mk(a.r + b.r, a.g + b.g, a.b + b.b);
}

static double sq(double x)
{
    return x * x;
}

/* Radiance seen at (u, v) in [0,1]^2, v down. Values are W/(m^2 sr),
 * chosen so that the ratios are those of a real room: sun 5e4, sky 5-10,
 * sunlit floor ~3, walls 0.05-0.5, the dark corner 1e-3. */
static rgb_t scene(double u, double v)
{
    const double sun_u = 0.74, sun_v = 0.27, sun_r = 0.012;
    bool in_window = u > 0.55 && u < 0.85 && v > 0.12 && v < 0.60;
    if (in_window) {
        double wu = (u - 0.55) / 0.30, wv = (v - 0.12) / 0.48;
        /* window bars: dark silhouettes */
        if (fabs(wu - 0.5) < 0.02 || fabs(wv - 0.45) < 0.025)
            return mk(0.02, 0.018, 0.015);
        if (wv > 0.8) /* ground outside, lit by the sun */
            return mk(1.2, 1.6, 0.7);
        double r = sqrt(sq(u - sun_u) + sq((v - sun_v) * H / W));
        if (r < sun_r)
            return mk(5e4, 4.8e4, 4.3e4);
        rgb_t sky = scale(mk(0.45, 0.65, 1.0), 4 + 6 * wv);
        return add(sky, scale(mk(1, 0.9, 0.7), 40 / (1 + sq(r / 0.015))));
    }
    /* the lamp: a small bright bulb on the left wall */
    double lr = sqrt(sq(u - 0.18) + sq((v - 0.33) * H / W));
    if (lr < 0.014)
        return mk(400, 300, 150);
    /* irradiance on the room's surfaces: from the window, the lamp, and
     * a little ambient, falling to almost nothing in the corner */
    double e_win = 0.5 / (1 + (sq(u - 0.7) + sq(v - 0.4)) / 0.04);
    double e_lamp = 0.6 / (1 + sq(lr / 0.08));
    double corner = fmin(1, sq(u / 0.15) + sq((1 - v) / 0.3));
    double e = (e_win + e_lamp + 0.01) * (0.01 + 0.99 * corner);
    if (v > 0.75) { /* floor: a checker, and the sun's patch */
        bool dark = ((int)floor(u * 16 + (v - 0.75) * 40) +
                     (int)floor((v - 0.75) * 40)) % 2;
        double albedo = dark ? 0.15 : 0.5;
        bool patch = v > 0.80 && v < 0.95 && u > 0.30 + (v - 0.8) * 0.7 &&
                     u < 0.55 + (v - 0.8) * 0.7;
        rgb_t light = scale(mk(1, 0.95, 0.85), patch ? 6 + e : e);
        return scale(light, albedo);
    }
    return scale(mk(0.8, 0.7, 0.6), e); /* the warm wall */
}

static void make_scene(image_t *img)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            rgb_t sum = mk(0, 0, 0);
            for (int j = 0; j < SS; j++)
                for (int i = 0; i < SS; i++)
                    sum = add(sum, scene((x + (i + 0.5) / SS) / W,
                                         (y + (j + 0.5) / SS) / H));
            float *p = image_at(img, x, y);
            p[0] = (float)(sum.r / (SS * SS));
            p[1] = (float)(sum.g / (SS * SS));
            p[2] = (float)(sum.b / (SS * SS));
        }
}

/* --- drawing: the plot of the curve ---------------------------------------- */

/* A 3 x 5 font for tick labels: digits and minus. */
static const unsigned char glyph[11][5] = {
    { 7, 5, 5, 5, 7 }, { 2, 6, 2, 2, 7 }, { 7, 1, 7, 4, 7 }, { 7, 1, 7, 1, 7 },
    { 5, 5, 7, 1, 1 }, { 7, 4, 7, 1, 7 }, { 7, 4, 7, 5, 7 }, { 7, 1, 1, 1, 1 },
    { 7, 5, 7, 5, 7 }, { 7, 5, 7, 1, 7 }, { 0, 0, 7, 0, 0 },
};

static void dot(image_t *c, int x, int y, rgb_t col)
{
    if (x < 0 || y < 0 || x >= c->width || y >= c->height)
        return;
    float *p = image_at(c, x, y);
    p[0] = (float)col.r;
    p[1] = (float)col.g;
    p[2] = (float)col.b;
}

static void text(image_t *c, int x, int y, const char *s, rgb_t col)
{
    for (; *s; s++, x += 8) {
        int g = *s == '-' ? 10 : *s - '0';
        if (g < 0 || g > 10)
            continue;
        for (int j = 0; j < 5; j++)
            for (int i = 0; i < 3; i++)
                if (glyph[g][j] >> (2 - i) & 1)
                    for (int k = 0; k < 4; k++) /* 2x scale */
                        dot(c, x + 2 * i + k % 2, y + 2 * j + k / 2, col);
    }
}

static void line(image_t *c, double x0, double y0, double x1, double y1,
                 rgb_t col, int dash)
{
    int n = (int)(fmax(fabs(x1 - x0), fabs(y1 - y0)) * 2) + 1;
    for (int i = 0; i <= n; i++) {
        if (dash && (i / dash) % 2)
            continue;
        double t = (double)i / n;
        dot(c, (int)lround(x0 + t * (x1 - x0)), (int)lround(y0 + t * (y1 - y0)),
            col);
    }
}

/* Plot area and the mapping from (log10 Lw, log10 Ld) to pixels. */
typedef struct {
    int x0, y0, x1, y1;    /* plot rectangle in pixels */
    double lw0, lw1;       /* log10 Lw at its left and right */
    double ld0, ld1;       /* log10 Ld at its bottom and top */
} axes_t;

static double px_x(const axes_t *a, double lw)
{
    return a->x0 + (lw - a->lw0) / (a->lw1 - a->lw0) * (a->x1 - a->x0);
}

static double px_y(const axes_t *a, double ld)
{
    return a->y1 - (ld - a->ld0) / (a->ld1 - a->ld0) * (a->y1 - a->y0);
}

/* The naive equalisation: the cumulative of the raw histogram, no
 * ceiling (the curve the paper starts from). */
static double naive_ld(const tonemap_histogram_t *h, const double *cum,
                       double Lw)
{
    double b = log(Lw), P;
    if (b <= h->bw_min)
        P = 0;
    else if (b >= h->bw_max)
        P = 1;
    else {
        double t = (b - h->bw_min) / (h->bw_max - h->bw_min) * h->bins;
        int i = (int)t < h->bins ? (int)t : h->bins - 1;
        P = cum[i] + (t - i) * (cum[i + 1] - cum[i]);
    }
    return exp(h->bd_min + (h->bd_max - h->bd_min) * P);
}

/* The canvas: above, the curves Ld(Lw) in log-log axes; below, on the
 * same Lw axis, the histogram before (dim) and after (bright) the
 * ceiling, whose height is the dashed line. */
static int plot_histogram(const tonemap_histogram_t *h, const double *cum,
                          const char *dir)
{
    enum { CW = 640, CH = 520 };
    image_t c;
    svet_error err;
    if (image_alloc(&c, CW, CH, 3, &err) != SVET_OK) {
        fprintf(stderr, "ch06: %s\n", err.msg);
        return 1;
    }
    for (size_t i = 0; i < (size_t)CW * CH * 3; i++)
        c.px[i] = 0.08f;
    const double LN10 = log(10.0);
    axes_t a = { 50, 20, 620, 330, floor(h->bw_min / LN10),
                 ceil(h->bw_max / LN10), h->bd_min / LN10 - 0.25,
                 h->bd_max / LN10 + 0.25 };
    const int hist_top = 360, hist_bottom = 480;
    const rgb_t grid = mk(0.2, 0.2, 0.2), label = mk(0.8, 0.8, 0.8);
    /* decade grid and labels: log10 Lw across, log10 Ld up */
    for (int d = (int)a.lw0; d <= (int)a.lw1; d++) {
        line(&c, px_x(&a, d), a.y0, px_x(&a, d), hist_bottom, grid, 0);
        char s[8];
        snprintf(s, sizeof s, "%d", d);
        text(&c, (int)px_x(&a, d) - 4, hist_bottom + 10, s, label);
    }
    for (int d = (int)ceil(a.ld0); d <= (int)floor(a.ld1); d++) {
        line(&c, a.x0, px_y(&a, d), a.x1, px_y(&a, d), grid, 0);
        char s[8];
        snprintf(s, sizeof s, "%d", d);
        text(&c, a.x0 - 24, (int)px_y(&a, d) - 5, s, label);
    }
    /* the histogram */
    double top = 0;
    for (int i = 0; i < h->bins; i++)
        top = fmax(top, h->raw[i]);
    double db = (h->bw_max - h->bw_min) / h->bins / LN10;
    for (int i = 0; i < h->bins; i++) {
        double xl = px_x(&a, h->bw_min / LN10 + i * db);
        double xr = px_x(&a, h->bw_min / LN10 + (i + 1) * db);
        for (int k = 0; k < 2; k++) {
            double count = k ? h->trimmed[i] : h->raw[i];
            double yt = hist_bottom - count / top * (hist_bottom - hist_top);
            rgb_t col = k ? mk(0.2, 0.4, 0.9) : mk(0.12, 0.18, 0.35);
            for (int x = (int)xl; x < (int)xr; x++)
                line(&c, x, hist_bottom, x, yt, col, 0);
        }
    }
    if (h->ceiling > 0 && !h->sparse) {
        double yc = hist_bottom - h->ceiling / top * (hist_bottom - hist_top);
        line(&c, a.x0, yc, a.x1, yc, mk(0.5, 0.6, 1.0), 6);
    }
    /* a linear map (slope 1, dashed) through the middle of the display
     * range, where the adjusted curve is steepest: the curve may touch it
     * but never be steeper; then the naive equalisation (red) and the
     * adjustment (white) */
    double ld_mid = (h->bd_min + h->bd_max) / 2, lw_mid = h->bw_min;
    for (int i = 0; i <= 1000; i++) {
        double b = h->bw_min + (h->bw_max - h->bw_min) * i / 1000;
        if (log(tonemap_histogram_eval(h, exp(b))) <= ld_mid)
            lw_mid = b;
    }
    double shift = lw_mid / LN10 - ld_mid / LN10; /* lw = ld + shift */
    line(&c, px_x(&a, a.ld0 + shift), px_y(&a, a.ld0),
         px_x(&a, a.ld1 + shift), px_y(&a, a.ld1), mk(0.7, 0.7, 0.2), 4);
    double prev_n = 0, prev_h = 0, prev_x = 0;
    for (int i = 0; i <= 1000; i++) {
        double lw = a.lw0 + (a.lw1 - a.lw0) * i / 1000;
        double x = px_x(&a, lw);
        double yn = px_y(&a, log10(naive_ld(h, cum, pow(10, lw))));
        double yh = px_y(&a, log10(tonemap_histogram_eval(h, pow(10, lw))));
        if (i) {
            line(&c, prev_x, prev_n, x, yn, mk(0.9, 0.25, 0.2), 0);
            line(&c, prev_x, prev_h, x, yh, mk(1, 1, 1), 0);
        }
        prev_x = x, prev_n = yn, prev_h = yh;
    }
    /* the grid and the lines may run off the plot: clear its margins */
    for (int y = 0; y < CH; y++)
        for (int x = 0; x < CW; x++)
            if ((y < a.y0 || (y > a.y1 && y < hist_top - 8)) &&
                x >= a.x0 - 2)
                dot(&c, x, y, mk(0.08, 0.08, 0.08));
    for (size_t i = 0; i < (size_t)CW * CH * 3; i++) /* codes, not radiance */
        c.px[i] = (float)colour_srgb_encode((real)c.px[i]);
    char path[1024];
    snprintf(path, sizeof path, "%s/ch06_trc.ppm", dir);
    int rc = netpbm_write_ppm(path, &c, 8, &err) == SVET_OK ? 0 : 1;
    if (rc)
        fprintf(stderr, "ch06: %s\n", err.msg);
    image_free(&c);
    return rc;
}

/* --- the CSV files ---------------------------------------------------------- */

static int write_csvs(const tonemap_histogram_t *h, const double *cum,
                      const char *dir)
{
    char path[1024];
    svet_error err;
    fileio_t out;
    snprintf(path, sizeof path, "%s/ch06_trc_bins.csv", dir);
    if (fileio_begin(&out, path, &err) != SVET_OK)
        goto fail;
    fprintf(out.f, "# ch06: histogram of ln Lw (foveal luminance, "
                   "W/(m^2 sr)) before and after the linear ceiling\n"
                   "# ceiling %.9g counts per bin%s\n"
                   "bin,lw_lo,lw_hi,raw,trimmed\n",
            h->ceiling, h->sparse ? " (sparse: occupied bins at slope 1)"
                                  : "");
    double db = (h->bw_max - h->bw_min) / h->bins;
    for (int i = 0; i < h->bins; i++)
        fprintf(out.f, "%d,%.9g,%.9g,%.9g,%.9g\n", i,
                exp(h->bw_min + i * db), exp(h->bw_min + (i + 1) * db),
                h->raw[i], h->trimmed[i]);
    if (fileio_commit(&out, &err) != SVET_OK)
        goto fail;
    snprintf(path, sizeof path, "%s/ch06_trc_curve.csv", dir);
    if (fileio_begin(&out, path, &err) != SVET_OK)
        goto fail;
    fprintf(out.f, "# ch06: display luminance Ld (cd/m^2) for world "
                   "luminance Lw: histogram adjustment with the linear "
                   "ceiling, and naive equalisation; slopes are d ln Ld / "
                   "d ln Lw between neighbouring rows (a linear map has 1)\n"
                   "lw,ld_adjusted,slope_adjusted,ld_naive,slope_naive\n");
    double pa = 0, pn = 0, pb = 0;
    for (int i = 0; i <= 400; i++) {
        double b = h->bw_min + (h->bw_max - h->bw_min) * i / 400;
        double la = tonemap_histogram_eval(h, exp(b));
        double ln = naive_ld(h, cum, exp(b));
        double sa = i ? (log(la) - pa) / (b - pb) : 0;
        double sn = i ? (log(ln) - pn) / (b - pb) : 0;
        fprintf(out.f, "%.9g,%.9g,%.6f,%.9g,%.6f\n", exp(b), la, sa, ln, sn);
        pa = log(la), pn = log(ln), pb = b;
    }
    if (fileio_commit(&out, &err) != SVET_OK)
        goto fail;
    return 0;
fail:
    fprintf(stderr, "ch06: %s\n", err.msg);
    return 1;
}

/* --- main ------------------------------------------------------------------- */

int main(int argc, char **argv)
{
    const chapter_cli_t cli = {
        "ch06",
        "Chapter 6: one HDR image through every tone-mapping operator, and "
        "the histogram\nadjustment's tone reproduction curve, as PFM/PPM "
        "pictures, CSV files (for\n`make figures`) and a Markdown table.",
        "out", NULL, 0
    };
    const char *dir;
    int rc = chapter_begin(&cli, argc, argv, &dir);
    if (rc >= 0)
        return rc;
    svet_error err;
    image_t hdr, side;
    const int gap = 4;
    if (image_alloc(&hdr, W, H, 3, &err) != SVET_OK ||
        image_alloc(&side, TONEMAP_OP_COUNT * (W + gap) - gap, H, 3, &err) !=
            SVET_OK) {
        fprintf(stderr, "ch06: %s\n", err.msg);
        return 1;
    }
    make_scene(&hdr);
    char path[1024];
    snprintf(path, sizeof path, "%s/ch06_scene.pfm", dir);
    if (netpbm_write_pfm(path, &hdr, &err) != SVET_OK) {
        fprintf(stderr, "ch06: %s\n", err.msg);
        return 1;
    }

    char table[4096];
    int len = snprintf(table, sizeof table,
                       "| operator | log-average Lw | desaturated pixels | "
                       "notes |\n|---|---|---|---|\n");
    for (int op = 0; op < TONEMAP_OP_COUNT; op++) {
        tonemap_params_t p;
        tonemap_defaults(&p, (tonemap_op_t)op);
        if (op == TONEMAP_LINEAR)
            p.stops = 1; /* expose for the walls: the window burns out */
        if (op == TONEMAP_HISTOGRAM)
            p.fovea = 4; /* about 1 degree for a 320-pixel, 80-degree view */
        image_t out;
        tonemap_result_t r;
        if (tonemap_apply(&hdr, &out, &p, &r, &err) != SVET_OK) {
            fprintf(stderr, "ch06: %s\n", err.msg);
            return 1;
        }
        for (int y = 0; y < H; y++)
            memcpy(image_at(&side, op * (W + gap), y), image_at(&out, 0, y),
                   3 * W * sizeof(float));
        snprintf(path, sizeof path, "%s/ch06_%s.ppm", dir,
                 tonemap_op_name((tonemap_op_t)op));
        if (netpbm_write_ppm(path, &out, 8, &err) != SVET_OK) {
            fprintf(stderr, "ch06: %s\n", err.msg);
            return 1;
        }
        char notes[160] = "";
        if (op == TONEMAP_LINEAR)
            snprintf(notes, sizeof notes, "+1 stop");
        else if (op == TONEMAP_REINHARD)
            snprintf(notes, sizeof notes, "key 0.18, L_white %.4g", r.white);
        else if (op == TONEMAP_DRAGO)
            snprintf(notes, sizeof notes, "bias 0.85, Lw_max %.4g", r.l_max);
        else if (op == TONEMAP_HISTOGRAM)
            snprintf(notes, sizeof notes, "%d trimming passes, max slope "
                     "%.4f%s", r.hist_iterations, r.hist_slope,
                     r.hist_linear ? ", linear" : r.hist_sparse ? ", sparse"
                                                                 : "");
        len += snprintf(table + len, sizeof table - (size_t)len,
                        "| %s | %.4g | %llu | %s |\n",
                        tonemap_op_name((tonemap_op_t)op), r.l_logavg,
                        (unsigned long long)r.clipped, notes);
        image_free(&out);
    }
    snprintf(path, sizeof path, "%s/ch06_operators.ppm", dir);
    if (netpbm_write_ppm(path, &side, 8, &err) != SVET_OK) {
        fprintf(stderr, "ch06: %s\n", err.msg);
        return 1;
    }
    double lmin = 1e300, lmax = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) {
        const float *q = hdr.px + 3 * i;
        double L = 0.2126 * (double)q[0] + 0.7152 * (double)q[1] +
                   0.0722 * (double)q[2];
        lmin = fmin(lmin, L);
        lmax = fmax(lmax, L);
    }
    len += snprintf(table + len, sizeof table - (size_t)len,
                    "\nscene: %d x %d, luminance %.3g to %.3g (ratio %.3g)\n",
                    W, H, lmin, lmax, lmax / lmin);

    /* the curve of the histogram adjustment, and the naive one */
    tonemap_params_t p;
    tonemap_defaults(&p, TONEMAP_HISTOGRAM);
    p.fovea = 4;
    tonemap_histogram_t h;
    if (tonemap_histogram_build(&h, &hdr, &p, &err) != SVET_OK) {
        fprintf(stderr, "ch06: %s\n", err.msg);
        return 1;
    }
    double *cum = malloc(sizeof *cum * (size_t)(h.bins + 1));
    if (!cum)
        return 1;
    double T = 0;
    for (int i = 0; i < h.bins; i++)
        T += h.raw[i];
    cum[0] = 0;
    for (int i = 0; i < h.bins; i++)
        cum[i + 1] = cum[i] + h.raw[i] / T;
    double naive_slope = 0;
    for (int i = 0; i < h.bins; i++)
        naive_slope = fmax(naive_slope, (h.bd_max - h.bd_min) * h.raw[i] / T /
                                            ((h.bw_max - h.bw_min) / h.bins));
    len += snprintf(table + len, sizeof table - (size_t)len,
                    "histogram adjustment: largest log-log slope %.3f with "
                    "the ceiling, %.3f for naive equalisation\n",
                    tonemap_histogram_max_slope(&h), naive_slope);
    rc = plot_histogram(&h, cum, dir) | write_csvs(&h, cum, dir);
    fputs(table, stdout);
    snprintf(path, sizeof path, "%s/ch06_display.md", dir);
    if (fileio_write_text(path, table, &err) != SVET_OK) {
        fprintf(stderr, "ch06: %s\n", err.msg);
        rc = 1;
    }
    free(cum);
    tonemap_histogram_free(&h);
    image_free(&hdr);
    image_free(&side);
    return rc;
}
