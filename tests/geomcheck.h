/*
 * geomcheck.h - robustness tests that apply to every primitive of app. D,
 * after pbrt-v3's src/tests/shapes.cpp (the "Reintersect" tests) and
 * Mitsuba's ray-offset tests:
 *  - a ray spawned at a hit point, leaving the surface on the outside of a
 *    convex shape (either side of a flat one), never hits the shape again;
 *  - a ray aimed at a sampled surface point from outside hits it, at a
 *    point within the error bound;
 *  - a shadow ray between two sampled points of a convex shape hits nothing.
 * Each returns the number of cases it tried; failures are check failures.
 */
#ifndef SVET_GEOMCHECK_H
#define SVET_GEOMCHECK_H

#include "materials/cobject.h"
#include "core/rng.h"

/* How the surface bounds space: decides which spawned rays must miss. */
typedef enum {
    GEOMCHECK_CONVEX,  /* closed convex solid (sphere, box, capped cylinder
                          and cone): rays leaving on the +ng side miss */
    GEOMCHECK_FLAT,    /* one plane (plane, disk, parallelogram, triangle):
                          rays leaving on either side miss */
    GEOMCHECK_OPEN     /* neither (open cylinder/cone, meshes): spawned rays
                          may legitimately hit the far side; only the
                          leaving-outward test for +ng at the hit applies
                          where the shape says so */
} geomcheck_kind;

/* Rays from random origins at distance ~ `scale` around the object's bound
 * toward random points of its bound; at every hit, n_spawn rays in random
 * directions on the allowed side(s) are spawned with ray_spawn() and must
 * not hit obj. Returns the number of spawned rays tested. */
long geomcheck_spawn_never_rehits(const COBJECT *obj, geomcheck_kind kind,
                                  int n_rays, int n_spawn, uint64_t seed);

/* Sample n points with obj->ops->sample; from an origin on the +n side of
 * each (random direction in that hemisphere, distance up to `scale`), a ray
 * aimed at the point must hit obj with hit point within a tolerance of
 * 64 * the sample's p_error + 1e-5 relative to the distance (1e-12 in
 * double); returns n. For GEOMCHECK_OPEN shapes the origin is taken close
 * to the point so other parts of the surface cannot be in the way. */
long geomcheck_sampled_points_are_hit(const COBJECT *obj, geomcheck_kind kind,
                                      int n, real scale, uint64_t seed);

/* For convex shapes: ray_spawn_to() between two sampled points, traced over
 * (0, tmax), must hit nothing. Returns the number of pairs. */
long geomcheck_shadow_rays_between_points_miss(const COBJECT *obj, int n,
                                               uint64_t seed);

/* Every finite ray gives a finite PATHPOINT: no NaN or Inf in cross_point,
 * frame, st or p_error, unit n and ng. Random rays from all around (origin
 * at up to `scale` from the bound's centre, random directions, some aimed
 * at the bound); returns the number of hits checked. */
long geomcheck_hits_are_finite(const COBJECT *obj, int n_rays, real scale,
                               uint64_t seed);

/* Sampling is consistent with area: the pdf of uniform samples is 1/area
 * (checked for every sample when `uniform`), sampled points lie in the
 * bound (padded by their error), and normals are unit. Returns n. */
long geomcheck_sampling_matches_area(const COBJECT *obj, int n, bool uniform,
                                     uint64_t seed);

/* For the tests: a uniform random unit vector; a uniform direction in
 * the hemisphere around n. */
void geomcheck_random_dir(VECTOR3 w, pcg32_t *g);
void geomcheck_random_hemisphere(VECTOR3 w, const VECTOR3 n, pcg32_t *g);

/* A coordinate of every class, for the tests that compare a plain
 * algorithm with its speed layer: a quarter of the draws zeros of both
 * signs, subnormals, the extremes, infinities, NaN or +-1; the rest
 * ordinary numbers of either sign from 2^-30 to 2^31. */
real geomcheck_any_class(pcg32_t *g);

/* A ray whose coordinates are of every class (geomcheck_any_class()),
 * over (0, inf) or an interval whose ends are of every class too. */
void geomcheck_any_ray(ray_t *r, real *tmin, real *tmax, pcg32_t *g);

#endif
