/*
 * gradients.h - app. E: the irradiance at a point of a diffuse surface
 * from a stratified, cosine-weighted hemisphere of M x N samples, with its
 * rotational and translational gradients from the same samples (Ward &
 * Heckbert, "Irradiance Gradients", EGWR 1992, sec. 3; in the notation of
 * Krivanek et al., "Practical Global Illumination with Irradiance
 * Caching", SIGGRAPH 2008 course, ch. 2), and the harmonic mean distance
 * R the cache weighs records by (Ward et al. 1988).
 * Tests: tests/irradiance/test_gradients.c
 */
#ifndef SVET_GRADIENTS_H
#define SVET_GRADIENTS_H

#include "core/vec.h"
#include "materials/radiance.h"

/* The direction of cell (j, k) of the stratified hemisphere in the local
 * frame (z the normal): theta_j = asin(sqrt((j + u0) / M)) and
 * phi_k = 2 pi (k + u1) / N, cosine-weighted, for j < M, k < N and u in
 * [0, 1)^2 the cell's jitter. Can't fail. */
void gradients_direction(int m, int n, int j, int k, const real u[2],
                         VECTOR3 w);

/* What the hemisphere saw: for cell (j, k), stored at [j * n + k], the
 * radiance arriving along its direction and the distance to what it hit
 * (INFINITY for the sky). */
typedef struct {
    int m, n;
    const RADIANCE *l;
    const real *dist;
} gradients_samples_t;

/* E = pi / (M N) sum L_jk, and from the same samples, per channel, in the
 * local frame (x, y tangent, z the normal; the z components are 0):
 * - the rotational gradient pi / (M N) sum_k v_k sum_j t_j L_jk (Ward &
 *   Heckbert 1992, eq. 7), v_k the tangent vector at angle phi_k + pi / 2
 *   and t_j the mean of tan theta over stratum j under the cosine-weighted
 *   measure; E(n) = E + (n_i x n) . grad_r for a normal turned from n_i
 *   to n (the sign follows from d cos theta = w . (omega x n));
 * - the translational gradient (Ward & Heckbert 1992, sec. 3.2): each
 *   edge between strata moves as the point does, and the radiance
 *   difference across it is weighed by the cosine-weighted solid angle it
 *   sweeps over the nearer distance: for the theta edge of strata
 *   (j - 1, j), (2 pi / N) sin theta cos^2 theta at the edge along u_k
 *   (the stratum's centre direction); for the phi edge of strata (k - 1,
 *   k), the integral of cos theta over the edge, sin theta_j+ -
 *   sin theta_j-, along v_k- (perpendicular to the edge at 2 pi k / N);
 * - R, the harmonic mean M N / sum 1 / r_jk, infinite when nothing was
 *   hit.
 * Both gradients converge to the exact ones as the strata are refined
 * (tests/irradiance/test_gradients.c). Can't fail. */
void gradients_compute(const gradients_samples_t *s, RADIANCE *e,
                       VECTOR3 grad_r[3], VECTOR3 grad_t[3], real *r_mean);

#endif
