/*
 * converge.h - how fast a render's error falls with time (ch. 4: the error
 * of a Monte Carlo estimate falls as 1/sqrt(N)), measured against a
 * converged reference: the error of one image with the renderer's own
 * variance estimate, the efficiency 1 / (variance x time) that puts two
 * methods on one number, the error reached at a given time and the time
 * needed for a given error (read off the log-log line), and bias told from
 * noise (an error that stops falling). Points are kept as CSV files.
 * Tests: tests/stats/test_converge.c. Used by `svet converge` (cmd/cmd_converge.c).
 */
#ifndef SVET_CONVERGE_H
#define SVET_CONVERGE_H

#include <stdbool.h>
#include <stddef.h>
#include "core/error.h"
#include "io/image.h"

/* PSNR is computed against a peak of 1, the display's white, whatever the
 * image's range, so every scene and method uses the same scale. */
#define CONVERGE_PSNR_PEAK 1.0

/* Which error a series is read by.
 *  ABS: the mean squared error (a - b)^2, in radiance units squared.
 *  REL: the relative MSE, each value's (a - b)^2 divided by b^2 + 0.01
 *       (imgcompare.h), and each variance likewise. An emitter seen
 *       directly is 10-100 times brighter than what it lights, and the
 *       noise of the pixels on its edge (part light, part ceiling) then
 *       makes most of the absolute MSE; relative to b^2 every pixel counts
 *       by how visible its error is. svet's tables use REL. */
typedef enum {
    CONVERGE_ABS,
    CONVERGE_REL
} converge_metric;

/* The clock a series' seconds come from.
 *  WALL: the monotonic clock, the time one waits for the render.
 *  CPU: the process's CPU time (CLOCK_PROCESS_CPUTIME_ID), the work of all
 *       its threads: on a machine shared with other jobs it counts the
 *       work done rather than the waiting, so series measured at different
 *       loads stay comparable. One CPU-second is a wall-second of one
 *       core. */
typedef enum {
    CONVERGE_WALL,
    CONVERGE_CPU
} converge_clock;

/* "wall" or "cpu"; the CSV's name of the seconds column ("seconds" or
 * "cpu_seconds"). These functions can't fail. */
const char *converge_clock_name(converge_clock c);
const char *converge_clock_column(converge_clock c);

/* One point of a series: a render after `spp` samples per pixel. The error
 * measures are means over every R, G, B value of the image. */
typedef struct {
    long spp;            /* samples per pixel so far */
    double seconds;      /* render time so far on the series' clock
                            (set-up included, measurement excluded) */
    double rays;         /* rays traced so far; 0 if unknown */
    double rmse, psnr;   /* imgcompare's, reference noise included; PSNR
                            in dB with peak CONVERGE_PSNR_PEAK */
    /* [CONVERGE_ABS] and [CONVERGE_REL]: */
    double mse[2];          /* against the reference, its noise included */
    double variance[2];     /* the render's variance of the mean
                               (render_variance), averaged over values */
    double ref_variance[2]; /* the same for the reference; 0 without one */
} converge_point_t;

/* Fill the image-derived fields of *pt (rmse, psnr, mse, variance,
 * ref_variance) from the render img, its variance image var (NULL: 0), the
 * reference ref and its variance image ref_var (NULL: 0); spp, seconds and
 * rays are left to the caller. Values that are NaN or infinite on either
 * side are skipped (imgcompare.h). Fails with SVET_ERR_RANGE when the sizes
 * differ. */
svet_status converge_measure(const image_t *img, const image_t *var,
                             const image_t *ref, const image_t *ref_var,
                             converge_point_t *pt, svet_error *err);

/* The render's own error, the reference's noise taken out: E(a - b)^2 =
 * var_a + var_b + bias^2, so mse - ref_variance estimates the render's MSE
 * against the exact image. Returns sqrt(max(0, mse - ref_variance)). */
double converge_error(const converge_point_t *p, converge_metric m);

/* mse - variance - ref_variance: an estimate of the squared bias (may come
 * out negative by chance). */
double converge_bias2(const converge_point_t *p, converge_metric m);

/* 1 / (variance x seconds): constant along a series whose variance falls
 * as 1/N (an unbiased Monte Carlo estimate); the larger the better. 0 when
 * the variance or the time is 0 or unknown. */
double converge_efficiency(const converge_point_t *p, converge_metric m);

/* 1 / ((mse - ref_variance) x seconds): the same with the measured error,
 * so that bias counts against a method. 0 when not positive. */
double converge_efficiency_mse(const converge_point_t *p, converge_metric m);

/* How a value read off a series was obtained. */
typedef enum {
    CONVERGE_MEASURED,     /* between two measured points (log-log) */
    CONVERGE_EXTRAPOLATED, /* outside them, by MSE = bias^2 + c / t */
    CONVERGE_NEVER,        /* the error asked for is below the bias */
    CONVERGE_UNKNOWN       /* no points */
} converge_how;

/* Is the series biased? At its last point the squared bias estimate
 * exceeds the noise variance (variance + ref_variance): the MSE is more
 * than twice what noise explains, so from there on it falls at most by
 * half, however long the render runs. *bias (may be NULL) receives
 * sqrt(max(0, bias2)) of the last point. False for n = 0 and when the last
 * point has spp 1 (no variance estimate; spp 0 means unknown and counts). */
bool converge_biased(const converge_point_t *p, int n, converge_metric m,
                     double *bias);

/* converge_error() of series p[0..n) (in increasing time) at time t:
 * interpolated linearly in log(error) against log(time) between the
 * points around t, else extrapolated from the nearest end by
 * MSE(t) = b^2 + (MSE_end - b^2) t_end / t, with b the bias
 * (converge_biased; 0 when unbiased). NaN with CONVERGE_UNKNOWN for n = 0
 * or t <= 0. how may be NULL. This function can't fail. */
double converge_error_at(const converge_point_t *p, int n, converge_metric m,
                         double t, converge_how *how);

/* The time at which converge_error() of the series first falls to e, read
 * as converge_error_at reads errors; (double)INFINITY with CONVERGE_NEVER
 * when e is at or below the bias. how may be NULL. This function can't
 * fail. */
double converge_time_to(const converge_point_t *p, int n, converge_metric m,
                        double e, converge_how *how);

/* Write series p[0..n) of method `method` (no commas, quotes or line
 * breaks), timed by clock, to path as CSV: the lines of `comment` (may be
 * NULL) each after "# ", then the header row and one row per point:
 *   method, spp, seconds (cpu_seconds for CONVERGE_CPU), rays,
 *   rmse, psnr                  (imgcompare's)
 *   mse, variance, ref_variance, rmse_noref, bias2, efficiency
 *   relmse, relvariance, ref_relvariance, relrmse_noref, relbias2,
 *   relefficiency               (the same, CONVERGE_REL)
 * where rmse_noref is converge_error(), bias2 converge_bias2() and
 * efficiency converge_efficiency(). Through fileio.h: the old file is
 * replaced only when the new one is complete. Fails with SVET_ERR_RANGE on
 * a bad method name, SVET_ERR_IO, SVET_ERR_NOMEM. */
svet_status converge_csv_write(const char *path, const char *method,
                               const char *comment, converge_clock clock,
                               const converge_point_t *p, int n,
                               svet_error *err);

/* Read a file written by converge_csv_write: '#' lines are skipped,
 * columns found by name (the derived ones, rmse_noref, bias2, efficiency
 * and their rel forms, are not read). The method of the first row goes to
 * method (truncated to method_len), the clock the seconds column names to
 * *clock (may be NULL). *p is malloc'ed (free it), *n its length (0 for a
 * file without rows). Fails with SVET_ERR_IO, SVET_ERR_PARSE (path:line:
 * what is wrong, e.g. both seconds columns or neither), SVET_ERR_NOMEM. */
svet_status converge_csv_read(const char *path, char *method,
                              size_t method_len, converge_clock *clock,
                              converge_point_t **p, int *n, svet_error *err);

#endif
