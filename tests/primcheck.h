/*
 * primcheck.h - runs the robustness harness of geomcheck.h over the scales
 * every primitive must survive (1e-4 to 1e6 in float, 1e-8 to 1e8 in
 * double), with the object at the origin and moved away from it, and a
 * dense sweep of extreme rays through any COBJECT checking that nothing
 * comes back NaN or infinite. Used by the primitives' suites.
 */
#ifndef SVET_PRIMCHECK_H
#define SVET_PRIMCHECK_H

#include "materials/cobject.h"
#include "geomcheck.h"
#include "testutil.h"

/* Build the object under test with characteristic size `scale`, centred
 * near `centre`; return NULL to skip that placement. ctx is passed on. */
typedef COBJECT *(*primcheck_make_fn)(real scale, const VECTOR3 centre,
                                      void *ctx);

typedef enum {
    PRIMCHECK_SPAWN,   /* geomcheck_spawn_never_rehits */
    PRIMCHECK_SAMPLED, /* geomcheck_sampled_points_are_hit */
    PRIMCHECK_SHADOW,  /* geomcheck_shadow_rays_between_points_miss */
    PRIMCHECK_FINITE,  /* geomcheck_hits_are_finite */
    PRIMCHECK_AREA     /* geomcheck_sampling_matches_area */
} primcheck_test;

/* The scales of the current build: sets *n and returns the array. */
const real *primcheck_scales(int *n);

/* Run one geomcheck test on make(scale, centre) for every scale and for
 * centres at 0, 5 scale and 1000 scale from the origin (three directions);
 * `uniform` is passed to geomcheck_sampling_matches_area. Returns the
 * total number of cases the harness tried. */
long primcheck_over_scales(primcheck_make_fn make, void *ctx,
                           primcheck_test test, geomcheck_kind kind,
                           bool uniform, uint64_t seed);

/* n rays with origins and directions of magnitudes spread log-uniformly
 * over the whole range of real (some components zero, some directions a
 * single ulp long, some origins on the object's bound), traced over random
 * (tmin, tmax); on every hit t, the PATHPOINT and the frame must be finite
 * and n, ng unit; bounds, area and sample (u in [0,1), the ends included)
 * must be free of NaN. Returns the number of rays traced. */
long primcheck_sweep_finite(const COBJECT *obj, int n, uint64_t seed);

/* --- the reference vectors (tests/vectors/README.md) --------------------- */

/* The vector in the columns <prefix>x, <prefix>y, <prefix>z of the row. */
void primcheck_csv_vec(testcsv_t *c, const char *prefix, VECTOR3 v);

/* The row's tolerance for this build: tol_float or tol_double. */
double primcheck_csv_tol(testcsv_t *c);

/* Trace the row's ray (ox oy oz dx dy dz) at obj over (0, inf) and check
 * it against the row: `hit`, then for a hit `t` (relative), the point in
 * columns <p>x.. (relative to `scale`) and the unit normal ng in <n>x..
 * (absolute), within the row's tolerance. Returns whether it hit, with
 * the PATHPOINT in *pp for further checks. */
bool primcheck_csv_hit(testcsv_t *c, const COBJECT *obj, const char *p,
                       const char *n, PATHPOINT *pp);

#endif
