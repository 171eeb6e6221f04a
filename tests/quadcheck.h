/*
 * quadcheck.h - checks that the suites of the quadric primitives of app. D
 * (test_sphere.c, test_disk.c, test_cylinder.c, test_cone.c) share beside
 * primcheck.h: a Kolmogorov-Smirnov test of a sampled coordinate, the
 * reading of tests/vectors/<m>.csv, and checks of a whole PATHPOINT.
 */
#ifndef SVET_QUADCHECK_H
#define SVET_QUADCHECK_H

#include "materials/cobject.h"
#include "geomcheck.h"
#include "primcheck.h"
#include "testutil.h"

/* pi in double (M_PI is not C11). */
#define QUADCHECK_PI 3.14159265358979323846

/* A coordinate of a sample, mapped through its known CDF to [0, 1]. */
typedef double (*quadcheck_cdf_fn)(const cobject_sample_t *s, void *ctx);

/* Draw n samples of obj from a seeded PCG32 and compare the CDF values
 * cdf(sample) with U(0,1) by the Kolmogorov-Smirnov distance D_n. By the
 * Dvoretzky-Kiefer-Wolfowitz inequality with Massart's constant (Ann.
 * Probab. 18, 1990), P(D_n > eps) <= 2 exp(-2 n eps^2) for every n, so
 * eps = sqrt(ln(2 / alpha) / (2 n)) is a threshold that a correct sampler
 * exceeds with probability at most alpha; alpha = 1e-6 here. Reports n
 * cases under `test`. */
void quadcheck_ks(const COBJECT *obj, int n, uint64_t seed,
                  quadcheck_cdf_fn cdf, void *ctx, const char *test);

/* Distance in long double from p to the exact surface of the shape that
 * make(scale, centre, ctx) builds. */
typedef long double (*quadcheck_dist_fn)(const VECTOR3 p, real scale,
                                         const VECTOR3 centre, void *ctx);

/* Distance in long double from p to a surface of revolution about the
 * segment from a to b, given by its meridian: n segments
 * (rho0, h0) - (rho1, h1) in the half-plane of the distance rho from the
 * axis and the height h = (p - a) . (b - a) / |b - a|. A cylinder of
 * radius R and height H has the segments (R, 0)-(R, H), and (0, 0)-(R, 0),
 * (0, H)-(R, H) for its caps. */
long double quadcheck_meridian_distance(const VECTOR3 p, const VECTOR3 a,
                                        const VECTOR3 b,
                                        const long double seg[][4], int n);

/* The exact surface passes through the error box of every hit point and
 * every sampled point: dist(p) <= sum_i |n_i| p_error_i, the half-width of
 * the box along the normal n, which is what ray_offset_origin moves past.
 * n rays per shape at every scale, centred at the origin and 10 scale
 * away; prints the largest dist / bound seen. Returns the points checked. */
long quadcheck_error_bound(primcheck_make_fn make, quadcheck_dist_fn dist,
                           void *ctx, int n, uint64_t seed);

/* primcheck_over_scales on each placement v = 0 .. n-1 of make (called
 * with ctx = &v), of kind kinds[v]; PRIMCHECK_SHADOW runs on the CONVEX
 * placements only. Returns the cases tried. */
long quadcheck_harness(primcheck_make_fn make, int n,
                       const geomcheck_kind kinds[], primcheck_test test,
                       uint64_t seed);

/* A quadric's placements for the harness tests that every quadric suite
 * runs alike (quadcheck_add_harness). */
typedef struct {
    const char *name;            /* "sphere": names the cases reported */
    primcheck_make_fn make;      /* placement v built with ctx = &v */
    int n;                       /* placements v = 0 .. n-1 */
    const geomcheck_kind *kinds; /* kinds[v]: the kind of placement v */
    uint64_t seed[PRIMCHECK_AREA + 1]; /* the seed of each primcheck_test */
    int sweep_rays;              /* rays per scale and centre of the sweep */
    uint64_t sweep_seed;         /* placement v sweeps from sweep_seed + v */
} quadcheck_shape_t;

/* Add to tc the tests of the harness on shape (copied): spawned rays never
 * rehit, sampled points are hit, shadow rays between points miss (when a
 * placement is CONVEX), hits are finite, sampling matches the area (each
 * quadcheck_harness), and no routine returns NaN or Inf (quadcheck_sweep
 * on each placement). One shape per suite. */
void quadcheck_add_harness(TCase *tc, const quadcheck_shape_t *shape);

/* primcheck_sweep_finite (n rays) on make(scale, centre, ctx) at every
 * scale of primcheck_scales, centred at the origin and 10 scale away.
 * Returns the rays traced. */
long quadcheck_sweep(primcheck_make_fn make, void *ctx, int n, uint64_t seed);

/* Check every row of tests/vectors/<file>: build the shape from the row
 * with make_row, trace the row's ray over (0, inf), and compare hit, t,
 * point and normal with the row's tolerances for this build (tol_float or
 * tol_double for t |d| and the point, ntol_float or ntol_double for the
 * normal). Reports the rows under `test`. */
void quadcheck_vectors(const char *file, COBJECT *(*make_row)(testcsv_t *c),
                       const char *test);

/* The ray o + t d. This function can't fail. */
static inline ray_t quadcheck_ray(real ox, real oy, real oz, real dx, real dy,
                                  real dz)
{
    ray_t r = { { ox, oy, oz }, { dx, dy, dz } };
    return r;
}

/* Trace r over (0, inf) and expect a hit at parametric t (to 8 eps t) on
 * face `face` (PATHPOINT.prim) with the normal ng = n (to 8 eps), and a
 * finite PATHPOINT (quadcheck_assert_finite). */
void quadcheck_expect_hit(const COBJECT *c, const ray_t *r, real t, int face,
                          real nx, real ny, real nz);

/* Fill pp for the first hit of r over (tmin, tmax); false on a miss. */
bool quadcheck_trace(const COBJECT *obj, const ray_t *r, real tmin, real tmax,
                     PATHPOINT *pp);

/* The whole PATHPOINT is finite: point, error, normals, frame, st in
 * [0, 1], dP/ds, dP/dt. */
void quadcheck_assert_finite(const PATHPOINT *pp, const char *what);

#endif
