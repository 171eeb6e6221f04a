/*
 * tonemap.h - output to the screen (ch. 6): from the linear radiance of a
 * render to display codes. The "approximation functions" of sec. 6.1
 * (linear with exposure, exponential, Reinhard et al. 2002, Drago et al.
 * 2003) and the optimised tone reproduction curve of sec. 6.2 (the
 * histogram adjustment of Ward Larson, Rushmeier, Piatko 1997), then the
 * display transfer curve (sRGB or a plain gamma) and quantisation.
 * Tests: tests/colour/test_tonemap.c
 *
 * Every operator maps LUMINANCE, Lw -> Ld, and keeps chromaticity: a
 * pixel's RGB is scaled by Ld / Lw. A colour scaled past the display's
 * white in one channel is then desaturated toward grey at the same
 * luminance until its largest channel is 1 (or clipped channel by channel,
 * as an option). Luminance is Y of linear Rec. 709 RGB
 * (0.2126 R + 0.7152 G + 0.0722 B, as rad_luminance()).
 *
 * Statistics (log-average, maximum, histogram) skip pixels with a NaN or
 * infinite channel: they are counted in tonemap_result_t and written black
 * (or magenta, to find them). Negative channels are clamped to 0 and
 * counted. All arithmetic is in double whatever `real` is: a log-average
 * over millions of pixels, or a pixel of 1e30, needs the range.
 */
#ifndef SVET_TONEMAP_H
#define SVET_TONEMAP_H

#include <stdbool.h>
#include <stdint.h>
#include "core/error.h"
#include "io/image.h"

typedef enum {
    TONEMAP_LINEAR,      /* Ld = Lw (after exposure): clips the highlights */
    TONEMAP_EXPONENTIAL, /* Ld = 1 - exp(-Lw / Lav) */
    TONEMAP_REINHARD,    /* Reinhard et al. 2002, global operator, eq. (4) */
    TONEMAP_DRAGO,       /* Drago et al. 2003, adaptive logarithmic */
    TONEMAP_HISTOGRAM,   /* Ward Larson et al. 1997, with linear ceiling */
    TONEMAP_OP_COUNT
} tonemap_op_t;

typedef enum {
    TONEMAP_CURVE_SRGB,  /* IEC 61966-2-1 (colour_srgb_encode) */
    TONEMAP_CURVE_GAMMA, /* v^(1/gamma) */
    TONEMAP_CURVE_NONE   /* display-linear output */
} tonemap_curve_t;

typedef enum {
    TONEMAP_GAMUT_DESATURATE, /* toward grey at the same luminance */
    TONEMAP_GAMUT_CLIP        /* each channel to 1: shifts hue */
} tonemap_gamut_t;

typedef struct {
    tonemap_op_t op;
    double stops;        /* exposure: Lw is multiplied by 2^stops first */
    double delta;        /* the delta of Reinhard's log-average eq. (1),
                            keeping log(0) away: 1e-4, in the image's units */
    double key;          /* Reinhard's key a: 0.18 ("middle grey") */
    double white;        /* Reinhard's L_white in units of the scaled
                            luminance L = a Lw / Lav; <= 0: the largest
                            scaled luminance of the image (the paper's
                            suggestion), so nothing burns out */
    double bias;         /* Drago's b: 0.85 */
    double ld_max;       /* display white, cd/m^2: 100 (Drago, histogram) */
    double ld_min;       /* display black, cd/m^2: 1 (histogram) */
    int bins;            /* histogram: 100 bins over log luminance */
    int fovea;           /* histogram: side in pixels of the blocks whose
                            mean luminance feeds the histogram (the paper's
                            1-degree fovea); 1 = every pixel */
    double tolerance;    /* histogram: stop trimming when less than this
                            fraction of the pixels was cut: 0.025 */
    tonemap_curve_t curve;
    double gamma;        /* for TONEMAP_CURVE_GAMMA: 2.2 */
    tonemap_gamut_t gamut;
    bool flag_nonfinite; /* NaN/Inf pixels magenta (1, 0, 1), not black */
} tonemap_params_t;

/* What an application of an operator found and did. */
typedef struct {
    uint64_t pixels;    /* in the image */
    uint64_t nonfinite; /* with a NaN or Inf channel: skipped, black */
    uint64_t negative;  /* with a negative channel: clamped to 0 */
    uint64_t clipped;   /* mapped beyond display white: desaturated/clipped */
    double l_min;       /* smallest positive finite luminance (after the
                           exposure), 0 if there is none */
    double l_max;       /* largest finite luminance, 0 if none */
    double l_logavg;    /* exp(mean ln(delta + Lw)), Reinhard's eq. (1) */
    double white;       /* Reinhard: the L_white used */
    bool hist_linear;   /* histogram: the scene fitted the display, so
                           the paper's linear mapping was used */
    bool hist_sparse;   /* histogram: occupied bins at slope 1 (see
                           tonemap_histogram_t) */
    int hist_iterations;/* histogram: trimming passes made */
    double hist_slope;  /* histogram: the largest d ln Ld / d ln Lw of the
                           curve; the linear ceiling keeps it <= 1 */
} tonemap_result_t;

/* Default parameters for operator op, as above. This function can't
 * fail. */
void tonemap_defaults(tonemap_params_t *p, tonemap_op_t op);

/* The operator's name ("linear", "exponential", "reinhard", "drago",
 * "histogram"), and back (-1 for an unknown name). Can't fail. */
const char *tonemap_op_name(tonemap_op_t op);
int tonemap_op_from_name(const char *name);

/* Tone-map `in` (linear RGB or RGBA) into `out`, allocated here with the
 * same size and channels: display codes in [0, 1] after p->curve, alpha
 * copied (clamped to [0, 1]). res (may be NULL) receives the statistics.
 * The input may hold anything: black, 1e30, NaN, Inf. Fails with
 * SVET_ERR_RANGE for parameters out of their domain (the message names
 * the parameter), SVET_ERR_NOMEM as image_alloc() does; out is then
 * zeroed. */
svet_status tonemap_apply(const image_t *in, image_t *out,
                          const tonemap_params_t *p, tonemap_result_t *res,
                          svet_error *err);

/* --- the curves, one luminance at a time (for tests and plots) ---------- */

/* 1 - exp(-L / L_av). L_av > 0. Can't fail. */
double tonemap_exponential(double L, double L_av);

/* Reinhard et al. 2002: L = a Lw / Lav (eq. 2), then
 *   Ld = L (1 + L / L_white^2) / (1 + L)          (eq. 4)
 * evaluated so that no intermediate overflows for L up to DBL_MAX;
 * L_white = Inf gives eq. (3), L / (1 + L). Lav > 0. Can't fail. */
double tonemap_reinhard(double Lw, double Lav, double key, double L_white);

/* Drago et al. 2003, "Adaptive logarithmic mapping for displaying high
 * contrast scenes", the mapping of its sec. 3, with Lw and Lw_max already
 * divided by the world adaptation luminance:
 *   Ld = (ld_max / 100) / log10(Lw_max + 1)
 *        * ln(Lw + 1) / ln(2 + 8 (Lw / Lw_max)^(ln b / ln 0.5)),
 * 1 at Lw = Lw_max for ld_max = 100. Lw_max > 0. Can't fail. */
double tonemap_drago(double Lw, double Lw_max, double bias, double ld_max);

/* The display transfer of p (sRGB, gamma, none) of one display-linear
 * value v in [0, 1]. Can't fail. */
double tonemap_encode(double v, const tonemap_params_t *p);

/* --- the histogram adjustment (Ward Larson, Rushmeier, Piatko 1997) ------ */

/* The tone reproduction curve built from an image's histogram of world
 * brightness B = ln Lw: display brightness
 *   Bd(Bw) = ln Ld_min + (ln Ld_max - ln Ld_min) P(Bw)
 * where P is the cumulative of the histogram after the linear ceiling
 * trimmed it: no bin may hold more than
 *   f(b) <= T db / (ln Ld_max - ln Ld_min)
 * (T the total count, db the bin width), which is the condition
 * dLd/dLw <= Ld/Lw: contrast never above that of a linear map. P is
 * piecewise linear in Bw (the histogram is a piecewise-constant density),
 * so the curve is continuous and its log-log slope is f(b) / ceiling. */
typedef struct {
    int bins;
    double bw_min, bw_max;  /* world brightness range, ln cd/m^2 (or ln of
                               the image's units) */
    double bd_min, bd_max;  /* ln Ld_min, ln Ld_max */
    double bd_lo;           /* where the curve starts: bd_min, or above it
                               for a `sparse` histogram */
    double *raw;            /* bins counts before trimming */
    double *trimmed;        /* bins counts after the ceiling */
    double *cum;            /* bins + 1 values: P at each bin edge */
    double ceiling;         /* the final ceiling, counts per bin */
    int iterations;         /* the paper's trimming passes */
    bool linear;            /* the scene fits the display: Ld = scale Lw */
    bool sparse;            /* wider than the display, yet too few occupied
                               bins to span it with slopes <= 1: each
                               occupied bin gets slope 1 (tonemap.c) */
    double scale;           /* for `linear`: Ld_max / Lw_max */
    bool empty;             /* no positive finite luminance at all */
} tonemap_histogram_t;

/* Build the curve from the finite, positive luminances of img (times
 * 2^p->stops), averaged over p->fovea-pixel blocks. h is zeroed first, so
 * tonemap_histogram_free() is always safe. Fails with SVET_ERR_RANGE for
 * bins < 2, ld_min <= 0 or ld_max <= ld_min, SVET_ERR_NOMEM. */
svet_status tonemap_histogram_build(tonemap_histogram_t *h, const image_t *img,
                                    const tonemap_params_t *p,
                                    svet_error *err);

/* Ld in cd/m^2 for world luminance Lw > 0, between Ld_min and Ld_max
 * (from exp(bd_lo) for a sparse histogram; Ld = scale Lw for a linear
 * one); 0 for Lw <= 0. Can't fail. */
double tonemap_histogram_eval(const tonemap_histogram_t *h, double Lw);

/* The largest log-log slope d ln Ld / d ln Lw over the curve. Can't fail. */
double tonemap_histogram_max_slope(const tonemap_histogram_t *h);

void tonemap_histogram_free(tonemap_histogram_t *h);

#endif
