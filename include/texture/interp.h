/*
 * interp.h - app. L: reading a value between the samples of a regular 3D
 * grid, by nearest sample, trilinear and parabolic (quadratic)
 * interpolation. Textures blend mip-map levels with it (ch. 10); gridded
 * media and the smoke solver's fields are sampled with it (ch. 11, 13).
 * Tests: tests/texture/test_interp.c
 */
#ifndef SVET_INTERP_H
#define SVET_INTERP_H

#include "core/vec.h"

/* A grid of nx x ny x nz samples, x fastest: sample (i, j, k) is
 * v[(k * ny + j) * nx + i] and stands at the point (i, j, k) of grid
 * coordinates. Each n is 1 or more (a 2D image is nz = 1). Samples are
 * float whatever the build's real, as grids of densities are stored. */
typedef struct {
    int nx, ny, nz;
    const float *v;
} interp_grid_t;

/* Grid coordinates outside [0, n - 1] are clamped to it on every axis
 * (the grid's border value continues outward), and a NaN coordinate is
 * read as 0. */

/* The sample nearest p (ties at half-way go up). Can't fail. */
real interp_nearest(const interp_grid_t *g, const VECTOR3 p);

/* Trilinear interpolation (app. L): linear along x between the eight
 * samples around p, then along y, then along z. Exact, to rounding, for
 * every function a + b x + c y + d z + e xy + f xz + g yz + h xyz sampled
 * on the grid; continuous, with kinks at the sample planes. Can't fail. */
real interp_trilinear(const interp_grid_t *g, const VECTOR3 p);

/* Parabolic interpolation (app. L): along each axis the parabola through
 * the sample nearest p and its two neighbours (the three nearest at a
 * border), over the 27 samples around p. Exact for every quadratic in
 * each coordinate (x^2 y^2 z^2 included); smoother than trilinear within
 * a cell, but it jumps, by about an eighth of the third difference, where
 * the nearest sample changes, half-way between samples. An axis with 2
 * samples is linear, with 1 constant. Can't fail. */
real interp_parabolic(const interp_grid_t *g, const VECTOR3 p);

/* Overhauser's parabolic blending (Overhauser 1968; Brewer & Anderson
 * 1977): between samples i and i + 1, the parabolas through (i - 1, i,
 * i + 1) and (i, i + 1, i + 2) blended linearly, which is the Catmull-Rom
 * cubic. Exact for quadratics like interp_parabolic, and continuous with a
 * continuous first derivative everywhere; 64 samples. At a border the one
 * parabola that exists is used. Can't fail. */
real interp_parabolic_blend(const interp_grid_t *g, const VECTOR3 p);

/* The 1D kernels. interp_lerp: a + t (b - a). interp_parabola: the value
 * at t (0 at f0, -1 at fm, +1 at fp) of the parabola through the three. */
static inline real interp_lerp(real t, real a, real b)
{
    return a + t * (b - a);
}

static inline real interp_parabola(real t, real fm, real f0, real fp)
{
    /* Newton's form about the centre: f0 + t (fp - fm) / 2
     * + t^2 (fp - 2 f0 + fm) / 2 */
    return f0 + t * ((fp - fm) * REAL_C(0.5) +
                     t * ((fp + fm) * REAL_C(0.5) - f0));
}

#endif
