/*
 * bbox.h - axis-aligned bounding boxes: what every COBJECT reports through
 * its bounds(), and what the grids of ch. 7 are built from.
 * Tests: tests/core/test_bbox.c
 */
#ifndef SVET_BBOX_H
#define SVET_BBOX_H

#include <stdbool.h>
#include "core/ray.h"

typedef struct {
    VECTOR3 min, max; /* empty when min > max on some axis */
} bbox_t;

/* The empty box: min = +huge, max = -huge, so that adding a point gives
 * that point. */
void bbox_empty(bbox_t *b);
bool bbox_is_empty(const bbox_t *b);
void bbox_add_point(bbox_t *b, const VECTOR3 p);
void bbox_union(bbox_t *b, const bbox_t *a);
/* Grow every side by the absolute amount pad (pad >= 0). */
void bbox_pad(bbox_t *b, real pad);
bool bbox_contains(const bbox_t *b, const VECTOR3 p);
void bbox_centroid(VECTOR3 c, const bbox_t *b);
/* 0 for an empty box. */
real bbox_surface_area(const bbox_t *b);

/* Slab test (Kay & Kajiya 1986) over (tmin, tmax). Returns true and the
 * parametric entry and exit t0 <= t1 clipped to that interval if the ray
 * meets the box. Robust as in pbrt-v3 sec. 3.9.2: each exit distance is
 * enlarged by 2 gamma(3) so rounding never drops a grazing hit; division by
 * a zero direction component gives +-infinity, which the comparisons handle
 * (a ray in the plane of a face counts as hitting it). */
bool bbox_intersect(const bbox_t *b, const ray_t *r, real tmin, real tmax,
                    real *t0, real *t1);

#endif
