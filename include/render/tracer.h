/*
 * tracer.h - how rays find surfaces (ch. 5): the two queries the
 * integrator asks (the nearest hit, and any hit for a shadow ray) as a
 * table of functions, and ch. 5's own answer to them, the book's method:
 * every object of the scene asked in turn for its nearest hit. Chapter 7's
 * acceleration structures answer the same queries faster (accel.h), bit
 * for bit, and reach the renderer through scene_features_t (scene.h).
 * Tests: tests/render/test_tracer.c
 */
#ifndef SVET_TRACER_H
#define SVET_TRACER_H

#include <stdbool.h>
#include "materials/cobject.h"
#include "render/scene.h"

/* The queries of a ray r over the open interval (tmin, tmax). */
typedef struct tracer {
    /* Nearest hit in (tmin, tmax): fills *hit and *obj (both untouched
     * on a miss). Of hits at exactly the same t, the first object of the
     * scene wins, then its first sub-primitive. skip: the objects the ray
     * cannot meet, which the tracer may leave out (accel.h's
     * accel_intersect_skip(); each entry may be NULL, and skip itself:
     * nothing skipped). */
    bool (*intersect)(const void *ctx, const ray_t *r, real tmin, real tmax,
                      const COBJECT *const skip[2], hit_t *hit,
                      const COBJECT **obj);
    /* Any hit in (tmin, tmax) (shadow rays); skip as for intersect. */
    bool (*occluded)(const void *ctx, const ray_t *r, real tmin, real tmax,
                     const COBJECT *const skip[2]);
    const void *ctx;
} tracer_t;

/* Whether a query takes ray r over (tmin, tmax) at all: all six
 * coordinates finite, d nonzero, tmin < tmax; every tracer answers "no
 * hit" otherwise. x - x is 0 for a finite x and NaN for an infinity or a
 * NaN, so the sum below is 0 exactly when all six are finite; a finite d
 * is nonzero exactly when the sum of |d_i| is positive; a NaN tmin or
 * tmax makes tmin < tmax false. This function can't fail. */
static inline bool tracer_ray_ok(const ray_t *r, real tmin, real tmax)
{
    real f = ((r->o[X] - r->o[X]) + (r->o[Y] - r->o[Y])) +
             ((r->o[Z] - r->o[Z]) + (r->d[X] - r->d[X])) +
             ((r->d[Y] - r->d[Y]) + (r->d[Z] - r->d[Z]));
    return f == 0 && fabs(r->d[X]) + fabs(r->d[Y]) + fabs(r->d[Z]) > 0 &&
           tmin < tmax;
}

/* The tracer of ch. 5 over the objects of s (s is its ctx and must
 * outlive it): each object, in the scene's order, asked for the nearest
 * hit of each of its sub-primitives over (tmin, the nearest so far).
 * skip is ignored. The answers are those of every acceleration structure
 * of accel.h, bit for bit. This function can't fail. */
tracer_t tracer_brute(const scene_t *s);

#endif
