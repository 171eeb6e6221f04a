/*
 * sample.h - the samplers of ch. 4: maps from uniform numbers u in [0,1)^2
 * to points and directions with known densities, for importance sampling.
 * Directions are in a local frame whose z axis is the normal (or the lobe
 * axis); frame_to_world() takes them to the scene. Every sampler comes with
 * its pdf; pdfs over directions are per unit solid angle, pdfs over points
 * per unit area. No sampler returns NaN or Inf for u in [0,1)^2, including
 * u = 0 and the largest real below 1; every direction returned is unit to
 * within a few ulps. None of these functions can fail.
 * Tests: tests/core/test_sample.c (chi-square fits, tests/chi2.h);
 * vectors: tests/vectors/sample_*.csv
 */
#ifndef SVET_SAMPLE_H
#define SVET_SAMPLE_H

#include <stdint.h>
#include "core/rng.h"
#include "core/vec.h"

/* --- directions --------------------------------------------------------- */

/* Uniform on the unit sphere; pdf 1/(4 pi). */
void sample_uniform_sphere(VECTOR3 w, const real u[2]);
real sample_uniform_sphere_pdf(void);

/* Uniform on the hemisphere z >= 0; pdf 1/(2 pi). */
void sample_uniform_hemisphere(VECTOR3 w, const real u[2]);
real sample_uniform_hemisphere_pdf(void);

/* Cosine-weighted hemisphere z > 0 (Malley's method: a concentric disk
 * sample lifted to the hemisphere); pdf cos(theta)/pi (0 for cos <= 0).
 * The sample's z is at least 2^-12: u within 2^-26 of the square's edge
 * (u0 = 0 or u1 = 0) would map to the horizon, where the pdf is 0. */
void sample_cosine_hemisphere(VECTOR3 w, const real u[2]);
real sample_cosine_hemisphere_pdf(real cos_theta);

/* Uniform in the cone of directions within theta_max of +z, given
 * cos(theta_max) in [-1, 1); pdf 1/(2 pi (1 - cos_theta_max)). Values
 * outside [-1, 1] are clamped; at cos_theta_max = 1 (a single direction)
 * w = +z and the pdf is the finite 1/(2 pi REAL_MIN). */
void sample_uniform_cone(VECTOR3 w, const real u[2], real cos_theta_max);
real sample_uniform_cone_pdf(real cos_theta_max);

/* Phong lobe about +z: pdf (e + 1)/(2 pi) cos^e(alpha) for the angle alpha
 * to +z, zero below the z = 0 plane; e >= 0 (e = 0 is uniform over the
 * hemisphere; a negative or NaN e is taken as 0). Used by the modified Phong
 * BRDF (1.8) with the lobe axis along the mirror direction. The sample
 * never lies on the horizon: its pdf is >= (e + 1)/(2 pi) (1 - u0) > 0.
 * The pdf takes cos(alpha) (clamped to <= 1; 0 for cos_alpha < 0). */
void sample_phong_lobe(VECTOR3 w, const real u[2], real e);
real sample_phong_lobe_pdf(real cos_alpha, real e);

/* Ward's half vector h about +z (eq. (1.10), Walter 2005, "Notes on the
 * Ward BRDF", eqs. (6)-(7)): the density of h per solid angle is
 *   p(h) = exp(-tan^2(delta) (cos^2 phi/ax^2 + sin^2 phi/ay^2))
 *          / (pi ax ay cos^3(delta)),
 * delta the polar angle of h, phi its azimuth. Isotropic when ax == ay.
 * u0 = 0 gives h = +z. The alphas are clamped to [1e-7, 1e7] (so that
 * the peak pdf 1/(pi ax ay) stays finite in float). The pdf is 0 for
 * h.z <= 0 and never above REAL_MAX. To get the density of the reflected
 * direction wo = 2 (wi.h) h - wi divide by 4 (wi.h) (Walter 2005 eq. 9). */
void sample_ward_half(VECTOR3 h, const real u[2], real alpha_x, real alpha_y);
real sample_ward_half_pdf(const VECTOR3 h, real alpha_x, real alpha_y);

/* --- points ------------------------------------------------------------- */

/* Concentric map of the square to the unit disk (Shirley & Chiu 1997), area
 * preserving up to a constant; pdf 1/pi per unit area. */
void sample_concentric_disk(real d[2], const real u[2]);

/* Uniform barycentrics (b0, b1) of a triangle, b2 = 1 - b0 - b1
 * (the square-root parameterisation; pbrt-v3 sec. 13.6.5); pdf 1/area. */
void sample_triangle(real b[2], const real u[2]);

/* Uniform point of the parallelogram p0 + s e1 + t e2: s = u0, t = u1;
 * pdf 1/|e1 x e2|. */
void sample_parallelogram(VECTOR3 p, const VECTOR3 p0, const VECTOR3 e1,
                          const VECTOR3 e2, const real u[2]);

/* Uniform point on the sphere (centre c, radius r) by area; pdf
 * 1/(4 pi r^2) per unit area. Returns the outward unit normal n too
 * (p = c + r n). */
void sample_sphere_area(VECTOR3 p, VECTOR3 n, const VECTOR3 c, real r,
                        const real u[2]);

/* A direction from the point x toward the sphere (c, r), uniform in the cone
 * the sphere subtends (Shirley, Wang, Zimmerman 1996; pbrt-v3 sec. 14.2.2).
 * Returns the pdf per unit solid angle and sets w; if x is inside the
 * sphere (|x - c| < r), falls back to area sampling converted to solid
 * angle and says so by returning the pdf of that (the value
 * sample_sphere_solid_angle_pdf gives for w). The cone is computed from
 * sin^2(theta_max) = r^2/|x - c|^2 without forming 1 - cos, so a sphere
 * 1e6 radii away still has a cone (pdf ~ 1e12, finite). For r <= 0 or a NaN
 * position, returns 0 with w = +z: a caller must test pdf > 0. */
real sample_sphere_solid_angle(VECTOR3 w, const VECTOR3 x, const VECTOR3 c,
                               real r, const real u[2]);
/* The pdf of direction w under sample_sphere_solid_angle (0 if w misses the
 * sphere's cone). */
real sample_sphere_solid_angle_pdf(const VECTOR3 w, const VECTOR3 x,
                                   const VECTOR3 c, real r);

/* --- strata ------------------------------------------------------------- */

/* nx * ny jittered points in [0,1)^2, one uniformly inside each cell,
 * row-major, written to pts[2 * (j * nx + i) + {0,1}]: x in
 * [i/nx, (i+1)/nx) and y in [j/ny, (j+1)/ny), both bounds as computed in
 * `real` (a point that would round onto the upper edge is moved just below
 * it). Draws 2 nx ny numbers from g, x before y, cell by cell. */
void sample_stratified_2d(real *pts, int nx, int ny, pcg32_t *g);

/* --- estimators (ch. 4) -------------------------------------------------- */

/* Running mean and variance, Welford 1962 / Chan et al. 1983, in double so
 * that a million samples of a float estimator keep their digits. */
typedef struct {
    int64_t n;
    double mean;
    double m2; /* sum of squared deviations from the mean */
} estimator_t;

/* None of the estimator functions can fail. */
void estimator_init(estimator_t *e);
void estimator_add(estimator_t *e, double x);
/* Merge b into a (parallel partial sums; Chan, Golub, LeVeque 1983). */
void estimator_merge(estimator_t *a, const estimator_t *b);
double estimator_mean(const estimator_t *e);
/* Unbiased sample variance (n - 1 in the denominator); 0 for n < 2. */
double estimator_variance(const estimator_t *e);
/* Standard error of the mean, sqrt(variance / n); 0 for n < 2. */
double estimator_stderr(const estimator_t *e);

#endif
