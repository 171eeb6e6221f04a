/*
 * imgcompare.h - how far an image is from a reference: the error measures
 * a renderer is judged by (convergence plots, regression tests, ports
 * checked against reference output), and an error image to see where.
 * `svet diff` (cmd/svet.c) prints them for two files.
 * Tests: tests/stats/test_imgcompare.c
 */
#ifndef SVET_IMGCOMPARE_H
#define SVET_IMGCOMPARE_H

#include <stdint.h>
#include "core/error.h"
#include "io/image.h"

/* The default epsilon of the relative MSE. */
#define IMGCOMPARE_EPS 1e-2

/* Measures over every channel value a of R, G, B of the image and b of the
 * reference at the same place (alpha is not compared), N pairs:
 *   MSE     = sum (a - b)^2 / N,      RMSE = sqrt(MSE)
 *   relMSE  = sum (a - b)^2 / (b^2 + eps) / N
 *             (the form of Rousselle, Knaus, Zwicker 2011, "Adaptive
 *             sampling and reconstruction using greedy error
 *             minimization"; eps = 0.01 by default, IMGCOMPARE_EPS, keeps
 *             black reference pixels from dividing by zero; pbrt-v4's MRSE
 *             divides by (b + 0.01)^2 instead, so its figures differ)
 *   MAE     = sum |a - b| / N
 *   PSNR    = 10 log10(peak^2 / MSE) dB, +Inf for identical images; peak
 *             is the largest possible value: 1 for display images, the
 *             reference's maximum (or a chosen value) for HDR ones
 *   max     = max |a - b|, and where.
 * A pair in which either value is NaN or infinite is not summed; it is
 * counted in `nonfinite` (N counts only the others). Sums are in double,
 * in pixel order, so the same images give the same bits. */
typedef struct {
    uint64_t n;         /* value pairs compared */
    uint64_t nonfinite; /* value pairs skipped: NaN or Inf on either side */
    double mse, rmse, relmse, mae, psnr;
    double max_abs;     /* the largest |a - b| */
    int max_x, max_y, max_c; /* where it is (channel 0 R, 1 G, 2 B) */
    double peak;        /* the peak used for PSNR */
    double eps;         /* the epsilon used for relMSE */
} imgcompare_t;

typedef enum {
    IMGCOMPARE_ABS,     /* |a - b| per channel */
    IMGCOMPARE_REL,     /* |a - b| / sqrt(b^2 + eps): its square averages
                           to relMSE */
    IMGCOMPARE_SQUARED  /* (a - b)^2 */
} imgcompare_kind_t;

/* Compare image a with reference b. peak > 0 for PSNR (<= 0: the largest
 * finite value of b's R, G, B, or 1 if that is not positive); eps > 0 for
 * relMSE. Fails with SVET_ERR_RANGE if the sizes differ or eps <= 0. */
svet_status imgcompare(const image_t *a, const image_t *b, double peak,
                       double eps, imgcompare_t *out, svet_error *err);

/* The error image of a against reference b (3 channels, allocated here):
 * per channel the error of `kind`; a pair with NaN or Inf gives NaN so it
 * shows. Fails with SVET_ERR_RANGE if the sizes differ or eps <= 0,
 * SVET_ERR_NOMEM. */
svet_status imgcompare_error_image(const image_t *a, const image_t *b,
                                   imgcompare_kind_t kind, double eps,
                                   image_t *out, svet_error *err);

#endif
