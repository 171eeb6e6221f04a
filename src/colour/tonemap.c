/*
 * tonemap.c - ch. 6, output to the screen: tone-mapping operators, the
 * histogram adjustment with its linear ceiling, gamut handling and the
 * display transfer curve. Sources: Reinhard, Stark, Shirley, Ferwerda,
 * "Photographic tone reproduction for digital images", SIGGRAPH 2002;
 * Drago, Myszkowski, Annen, Chiba, "Adaptive logarithmic mapping for
 * displaying high contrast scenes", Eurographics 2003; Ward Larson,
 * Rushmeier, Piatko, "A visibility matching tone reproduction operator for
 * high dynamic range scenes", IEEE TVCG 3(4), 1997. See tonemap.h.
 * Tests: tests/colour/test_tonemap.c
 */
#include "colour/tonemap.h"
#include "colour/colour.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

/* Rec. 709 luminance weights (IEC 61966-2-1), as rad_luminance(). */
static const double W_R = 0.2126, W_G = 0.7152, W_B = 0.0722;

static const char *const op_names[TONEMAP_OP_COUNT] = {
    "linear", "exponential", "reinhard", "drago", "histogram"
};

void tonemap_defaults(tonemap_params_t *p, tonemap_op_t op)
{
    memset(p, 0, sizeof *p);
    p->op = op;
    p->stops = 0;
    p->delta = 1e-4;
    p->key = 0.18;
    p->white = 0; /* automatic: the largest scaled luminance */
    p->bias = 0.85;
    p->ld_max = 100;
    p->ld_min = 1;
    p->bins = 100;
    p->fovea = 1;
    p->tolerance = 0.025;
    p->curve = TONEMAP_CURVE_SRGB;
    p->gamma = 2.2;
    p->gamut = TONEMAP_GAMUT_DESATURATE;
    p->flag_nonfinite = false;
}

const char *tonemap_op_name(tonemap_op_t op)
{
    return (unsigned)op < TONEMAP_OP_COUNT ? op_names[op] : "unknown";
}

int tonemap_op_from_name(const char *name)
{
    for (int i = 0; i < TONEMAP_OP_COUNT; i++)
        if (name && strcmp(name, op_names[i]) == 0)
            return i;
    return -1;
}

/* --- the curves ------------------------------------------------------------ */

double tonemap_exponential(double L, double L_av)
{
    return L > 0 ? 1 - exp(-L / L_av) : 0;
}

double tonemap_reinhard(double Lw, double Lav, double key, double L_white)
{
    double L = key * (Lw / Lav); /* Reinhard's eq. 2 */
    if (!(L > 0))
        return 0;
    /* eq. 4, L (1 + L / Lwhite^2) / (1 + L), divided through by L so that
     * neither L^2 nor 1 + L can overflow (an infinite white is eq. 3): */
    double q = isinf(L_white) ? 0 : (L / L_white) / L_white;
    return (1 + q) / (1 / L + 1);
}

double tonemap_drago(double Lw, double Lw_max, double bias, double ld_max)
{
    if (!(Lw > 0) || !(Lw_max > 0))
        return 0;
    double p = log(bias) / log(0.5); /* the bias power of Perlin and Hoffert */
    return (ld_max * 0.01 / log10(Lw_max + 1)) * log1p(Lw) /
           log(2 + 8 * pow(Lw / Lw_max, p));
}

double tonemap_encode(double v, const tonemap_params_t *p)
{
    switch (p->curve) {
    case TONEMAP_CURVE_SRGB:
        return (double)colour_srgb_encode((real)v);
    case TONEMAP_CURVE_GAMMA:
        return v > 0 ? pow(v, 1 / p->gamma) : 0;
    case TONEMAP_CURVE_NONE:
        break;
    }
    return v;
}

/* --- the histogram adjustment ---------------------------------------------- */

/* The largest c > 0 with sum_i min(f_i, c) = K c: the fixed point that the
 * paper's trimming loop converges to, or 0 if there is none (then the scene
 * fits the display and a linear map is used). phi(c) = sum min(f_i, c) - K c
 * is concave and piecewise linear with phi(0) = 0; walking its pieces from
 * the top down, the first one whose lower end has phi >= 0 holds the root. */
static double fixed_ceiling(const double *f, int n, double K, double *scratch)
{
    double *g = scratch, *below = scratch + n; /* n and n + 1 values */
    double c = 0;
    memcpy(g, f, sizeof *g * (size_t)n);
    /* insertion sort: n is the bin count, ~100 */
    for (int i = 1; i < n; i++) {
        double v = g[i];
        int j = i - 1;
        while (j >= 0 && g[j] > v) {
            g[j + 1] = g[j];
            j--;
        }
        g[j + 1] = v;
    }
    below[0] = 0; /* below[j]: sum of the j smallest counts */
    for (int j = 0; j < n; j++)
        below[j + 1] = below[j] + g[j];
    for (int j = n; j >= 0; j--) {
        /* on [g[j-1], g[j]], phi(c) = below[j] + (n - j) c - K c */
        double lo = j > 0 ? g[j - 1] : 0;
        double phi_lo = below[j] + ((double)(n - j) - K) * lo;
        if (phi_lo >= 0) {
            double slope = (double)(n - j) - K;
            if (phi_lo > 0 && slope < 0)
                c = lo - phi_lo / slope;
            else
                c = lo;
            break;
        }
    }
    return c;
}

static double block_luminance(const image_t *img, int x0, int y0, int side,
                              double k)
{
    double sum = 0;
    int n = 0;
    for (int y = y0; y < y0 + side && y < img->height; y++)
        for (int x = x0; x < x0 + side && x < img->width; x++) {
            const float *p = image_at(img, x, y);
            if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
                continue;
            sum += W_R * fmax((double)p[0], 0) + W_G * fmax((double)p[1], 0) +
                   W_B * fmax((double)p[2], 0);
            n++;
        }
    return n ? k * sum / n : 0;
}

svet_status tonemap_histogram_build(tonemap_histogram_t *h, const image_t *img,
                                    const tonemap_params_t *p,
                                    svet_error *err)
{
    memset(h, 0, sizeof *h);
    if (p->bins < 2 || p->bins > 100000)
        return svet_error_set(err, SVET_ERR_RANGE, "histogram: %d bins (2 to "
                              "100000)", p->bins);
    if (!(p->ld_min > 0) || !(p->ld_max > p->ld_min) || !isfinite(p->ld_max))
        return svet_error_set(err, SVET_ERR_RANGE, "histogram: display range "
                              "Ld_min %g, Ld_max %g: need 0 < Ld_min < Ld_max",
                              p->ld_min, p->ld_max);
    if (!(p->tolerance >= 0 && p->tolerance < 1))
        return svet_error_set(err, SVET_ERR_RANGE, "histogram: tolerance %g "
                              "(0 to 1)", p->tolerance);
    int side = p->fovea > 1 ? p->fovea : 1;
    int nbx = (img->width + side - 1) / side, nby = (img->height + side - 1) /
                                                    side;
    int n = p->bins;
    double k = exp2(p->stops);
    /* one luminance per block; reused as the scratch of fixed_ceiling */
    size_t nlum = (size_t)nbx * (size_t)nby;
    if (nlum < 2 * (size_t)n + 1)
        nlum = 2 * (size_t)n + 1;
    double *lum = malloc(sizeof *lum * nlum);
    h->raw = calloc((size_t)n, sizeof *h->raw);
    h->trimmed = calloc((size_t)n, sizeof *h->trimmed);
    h->cum = calloc((size_t)n + 1, sizeof *h->cum);
    if (!lum || !h->raw || !h->trimmed || !h->cum) {
        free(lum);
        tonemap_histogram_free(h);
        return svet_error_set(err, SVET_ERR_NOMEM, "histogram: out of memory");
    }
    h->bins = n;
    h->bd_min = log(p->ld_min);
    h->bd_max = log(p->ld_max);
    h->bd_lo = h->bd_min;
    /* World luminance of each foveal block; the range of the positive
     * ones. Black blocks have no brightness (ln 0) and stay out. */
    double lmin = DBL_MAX, lmax = 0;
    size_t nb = 0;
    for (int by = 0; by < nby; by++)
        for (int bx = 0; bx < nbx; bx++) {
            double L = block_luminance(img, bx * side, by * side, side, k);
            if (L > 0 && isfinite(L)) {
                lum[nb++] = L;
                lmin = fmin(lmin, L);
                lmax = fmax(lmax, L);
            }
        }
    if (nb == 0) {
        h->empty = true;
        free(lum);
        return SVET_OK;
    }
    h->bw_min = log(lmin);
    h->bw_max = log(lmax);
    h->scale = p->ld_max / lmax;
    const double range_d = h->bd_max - h->bd_min;
    const double range_w = h->bw_max - h->bw_min;
    if (range_w <= 0) {
        /* one luminance only: any map is the linear one */
        h->linear = true;
        h->raw[0] = h->trimmed[0] = (double)nb;
        free(lum);
        return SVET_OK;
    }
    const double db = range_w / n;
    for (size_t i = 0; i < nb; i++) {
        int b = (int)((log(lum[i]) - h->bw_min) / db);
        h->raw[b < 0 ? 0 : b >= n ? n - 1 : b] += 1;
    }
    memcpy(h->trimmed, h->raw, sizeof *h->raw * (size_t)n);

    /* The paper's loop: cut every bin to the linear ceiling
     * T db / (ln Ld_max - ln Ld_min) of the current total T, and repeat
     * (cutting lowers T, hence the ceiling) until a pass trims less than
     * `tolerance` of the original total. A total falling below that
     * tolerance means that no curve spanning the whole display keeps the
     * contrast below linear everywhere. */
    double tol = p->tolerance * (double)nb, trimmings = 0;
    bool failed = false;
    do {
        double T = 0;
        for (int i = 0; i < n; i++)
            T += h->trimmed[i];
        if (T < tol || T <= 0) {
            failed = true;
            break;
        }
        double ceiling = T * db / range_d;
        trimmings = 0;
        for (int i = 0; i < n; i++)
            if (h->trimmed[i] > ceiling) {
                trimmings += h->trimmed[i] - ceiling;
                h->trimmed[i] = ceiling;
            }
        h->iterations++;
    } while (trimmings > tol && h->iterations < 10000);
    /* Where the loop stops, its last pass may have left bins up to the
     * tolerance above the ceiling of the final total. Finish at the exact
     * fixed point of the same iteration (the limit the loop approaches),
     * so that the slope never exceeds the linear one at all. */
    if (!failed) {
        h->ceiling = fixed_ceiling(h->trimmed, n, range_d / db, lum);
        failed = !(h->ceiling > 0);
    }
    free(lum);
    h->bd_lo = h->bd_min;
    if (failed && range_w <= range_d) {
        /* The scene's range fits the display's: the paper maps linearly. */
        h->linear = true;
        h->ceiling = 0;
        return SVET_OK;
    }
    if (failed) {
        /* Departure from the paper, which maps linearly whenever the
         * trimming fails. It also fails for a scene wider than the display
         * whose histogram is sparse (a normal image plus one pixel of
         * 1e30: a few full bins, a long empty gap), and a linear map
         * anchored at its maximum would turn everything else black. So
         * every occupied bin gets the linear slope, the empty ones none,
         * and the curve ends at Ld_max but starts above Ld_min. */
        int occupied = 0;
        for (int i = 0; i < n; i++) {
            h->trimmed[i] = h->raw[i] > 0 ? 1 : 0;
            occupied += h->raw[i] > 0;
        }
        h->sparse = true;
        h->ceiling = 1;
        h->bd_lo = h->bd_max - occupied * db; /* > bd_min, as failed */
    }
    double T = 0;
    for (int i = 0; i < n; i++) {
        h->trimmed[i] = fmin(h->trimmed[i], h->ceiling);
        T += h->trimmed[i];
    }
    h->cum[0] = 0;
    for (int i = 0; i < n; i++)
        h->cum[i + 1] = h->cum[i] + h->trimmed[i] / T;
    h->cum[n] = 1;
    return SVET_OK;
}

double tonemap_histogram_eval(const tonemap_histogram_t *h, double Lw)
{
    if (!(Lw > 0) || h->empty)
        return 0;
    if (h->linear)
        return h->scale * Lw;
    double b = log(Lw), P;
    if (b <= h->bw_min) {
        P = 0;
    } else if (b >= h->bw_max) {
        P = 1;
    } else {
        double t = (b - h->bw_min) / (h->bw_max - h->bw_min) * h->bins;
        int i = (int)t;
        if (i >= h->bins)
            i = h->bins - 1;
        P = h->cum[i] + (t - i) * (h->cum[i + 1] - h->cum[i]);
    }
    return exp(h->bd_lo + (h->bd_max - h->bd_lo) * P);
}

double tonemap_histogram_max_slope(const tonemap_histogram_t *h)
{
    if (h->empty)
        return 0;
    if (h->linear)
        return 1;
    /* in bin i: d Bd / d Bw = (Bd range) (cum[i+1] - cum[i]) / db */
    double db = (h->bw_max - h->bw_min) / h->bins, s = 0;
    for (int i = 0; i < h->bins; i++)
        s = fmax(s, (h->bd_max - h->bd_lo) * (h->cum[i + 1] - h->cum[i]) /
                        db);
    return s;
}

void tonemap_histogram_free(tonemap_histogram_t *h)
{
    if (!h)
        return;
    free(h->raw);
    free(h->trimmed);
    free(h->cum);
    memset(h, 0, sizeof *h);
}

/* --- applying an operator to an image ------------------------------------ */

static svet_status check_params(const tonemap_params_t *p, svet_error *err)
{
    const char *bad = NULL;
    double v = 0;
    if ((unsigned)p->op >= TONEMAP_OP_COUNT)
        return svet_error_set(err, SVET_ERR_RANGE, "tone mapping: unknown "
                              "operator %d", (int)p->op);
    if (!isfinite(p->stops))
        bad = "stops", v = p->stops;
    else if (!(p->delta > 0) || !isfinite(p->delta))
        bad = "delta", v = p->delta;
    else if (!(p->key > 0) || !isfinite(p->key))
        bad = "key", v = p->key;
    else if (isnan(p->white))
        bad = "white", v = p->white;
    else if (!(p->bias > 0 && p->bias <= 1))
        bad = "bias", v = p->bias;
    else if (!(p->ld_max > 0) || !isfinite(p->ld_max))
        bad = "ld_max", v = p->ld_max;
    else if (p->curve == TONEMAP_CURVE_GAMMA &&
             (!(p->gamma > 0) || !isfinite(p->gamma)))
        bad = "gamma", v = p->gamma;
    if (bad)
        return svet_error_set(err, SVET_ERR_RANGE, "tone mapping: %s = %g is "
                              "out of range", bad, v);
    return SVET_OK;
}

/* Scale rgb (luminance Lw) to luminance Ld, then bring it inside the
 * display: returns true if it had to. */
static bool to_display(double rgb[3], double Lw, double Ld,
                       tonemap_gamut_t gamut)
{
    if (!(Lw > 0) || !(Ld > 0)) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        return false;
    }
    double s = Ld / Lw;
    double m = 0;
    for (int c = 0; c < 3; c++) {
        rgb[c] *= s;
        m = fmax(m, rgb[c]);
    }
    if (m <= 1)
        return false;
    if (gamut == TONEMAP_GAMUT_CLIP) {
        for (int c = 0; c < 3; c++)
            rgb[c] = fmin(rgb[c], 1);
    } else if (Ld >= 1) {
        rgb[0] = rgb[1] = rgb[2] = 1; /* brighter than white: white */
    } else {
        /* Mix with grey of the same luminance: Y + t (c - Y) keeps Y
         * (the weights sum to 1) and t makes the largest channel 1. */
        double t = (1 - Ld) / (m - Ld);
        for (int c = 0; c < 3; c++)
            rgb[c] = Ld + t * (rgb[c] - Ld);
    }
    return true;
}

svet_status tonemap_apply(const image_t *in, image_t *out,
                          const tonemap_params_t *p, tonemap_result_t *res,
                          svet_error *err)
{
    tonemap_result_t r;
    memset(&r, 0, sizeof r);
    memset(out, 0, sizeof *out);
    svet_status st = check_params(p, err);
    if (st != SVET_OK)
        return st;
    tonemap_histogram_t hist;
    memset(&hist, 0, sizeof hist);
    if (p->op == TONEMAP_HISTOGRAM &&
        (st = tonemap_histogram_build(&hist, in, p, err)) != SVET_OK)
        return st;
    if ((st = image_alloc(out, in->width, in->height, in->channels, err)) !=
        SVET_OK) {
        tonemap_histogram_free(&hist);
        return st;
    }

    /* Statistics over the finite pixels, after the exposure k. */
    const double k = exp2(p->stops);
    const size_t n = (size_t)in->width * (size_t)in->height;
    const size_t nc = (size_t)in->channels;
    double logsum = 0;
    uint64_t finite = 0;
    r.pixels = n;
    r.l_min = DBL_MAX;
    for (size_t i = 0; i < n; i++) {
        const float *px = in->px + i * nc;
        if (!isfinite(px[0]) || !isfinite(px[1]) || !isfinite(px[2])) {
            r.nonfinite++;
            continue;
        }
        if (px[0] < 0 || px[1] < 0 || px[2] < 0)
            r.negative++;
        double L = k * (W_R * fmax((double)px[0], 0) +
                        W_G * fmax((double)px[1], 0) +
                        W_B * fmax((double)px[2], 0));
        if (L > 0)
            r.l_min = fmin(r.l_min, L);
        r.l_max = fmax(r.l_max, L);
        logsum += log(p->delta + L); /* Reinhard's eq. 1 */
        finite++;
    }
    if (r.l_min == DBL_MAX)
        r.l_min = 0;
    r.l_logavg = finite ? exp(logsum / (double)finite) : p->delta;
    /* Reinhard's white: by default the largest scaled luminance. */
    r.white = p->white > 0 ? p->white : p->key * (r.l_max / r.l_logavg);
    if (!(r.white > 0))
        r.white = (double)INFINITY;
    if (p->op == TONEMAP_HISTOGRAM) {
        r.hist_linear = hist.linear;
        r.hist_sparse = hist.sparse;
        r.hist_iterations = hist.iterations;
        r.hist_slope = tonemap_histogram_max_slope(&hist);
    }

    for (size_t i = 0; i < n; i++) {
        const float *px = in->px + i * nc;
        float *o = out->px + i * nc;
        if (nc == 4) {
            double a = isfinite(px[3]) ? fmin(fmax((double)px[3], 0), 1) : 0;
            o[3] = (float)a;
        }
        if (!isfinite(px[0]) || !isfinite(px[1]) || !isfinite(px[2])) {
            bool flag = p->flag_nonfinite;
            o[0] = flag ? 1.0f : 0.0f;
            o[1] = 0.0f;
            o[2] = flag ? 1.0f : 0.0f;
            continue;
        }
        double rgb[3];
        for (int c = 0; c < 3; c++)
            rgb[c] = k * fmax((double)px[c], 0);
        double Lw = W_R * rgb[0] + W_G * rgb[1] + W_B * rgb[2], Ld = 0;
        switch (p->op) {
        case TONEMAP_LINEAR:
            Ld = Lw;
            break;
        case TONEMAP_EXPONENTIAL:
            Ld = tonemap_exponential(Lw, r.l_logavg);
            break;
        case TONEMAP_REINHARD:
            Ld = tonemap_reinhard(Lw, r.l_logavg, p->key, r.white);
            break;
        case TONEMAP_DRAGO:
            /* Drago: world luminance over the adaptation luminance */
            Ld = tonemap_drago(Lw / r.l_logavg, r.l_max / r.l_logavg, p->bias,
                               p->ld_max);
            break;
        case TONEMAP_HISTOGRAM:
            Ld = tonemap_histogram_eval(&hist, Lw) / p->ld_max;
            break;
        case TONEMAP_OP_COUNT:
            break;
        }
        if (to_display(rgb, Lw, Ld, p->gamut))
            r.clipped++;
        for (int c = 0; c < 3; c++)
            o[c] = (float)tonemap_encode(rgb[c], p);
    }
    tonemap_histogram_free(&hist);
    if (res)
        *res = r;
    return SVET_OK;
}
