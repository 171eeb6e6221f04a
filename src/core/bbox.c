/*
 * bbox.c - axis-aligned bounding boxes and the robust slab test
 * (Kay & Kajiya 1986; pbrt-v3 sec. 3.9.2 for the error bound).
 * Tests: tests/core/test_bbox.c
 */
#include "core/bbox.h"

void bbox_empty(bbox_t *b)
{
    vec_set(b->min, REAL_MAX, REAL_MAX, REAL_MAX);
    vec_set(b->max, -REAL_MAX, -REAL_MAX, -REAL_MAX);
}

bool bbox_is_empty(const bbox_t *b)
{
    return b->min[X] > b->max[X] || b->min[Y] > b->max[Y] ||
           b->min[Z] > b->max[Z];
}

void bbox_add_point(bbox_t *b, const VECTOR3 p)
{
    vec_min(b->min, b->min, p);
    vec_max(b->max, b->max, p);
}

void bbox_union(bbox_t *b, const bbox_t *a)
{
    vec_min(b->min, b->min, a->min);
    vec_max(b->max, b->max, a->max);
}

void bbox_pad(bbox_t *b, real pad)
{
    for (int i = 0; i < 3; i++) {
        b->min[i] -= pad;
        b->max[i] += pad;
    }
}

bool bbox_contains(const bbox_t *b, const VECTOR3 p)
{
    for (int i = 0; i < 3; i++)
        if (!(p[i] >= b->min[i] && p[i] <= b->max[i]))
            return false;
    return true;
}

void bbox_centroid(VECTOR3 c, const bbox_t *b)
{
    for (int i = 0; i < 3; i++)
        c[i] = REAL_C(0.5) * b->min[i] + REAL_C(0.5) * b->max[i];
}

real bbox_surface_area(const bbox_t *b)
{
    if (bbox_is_empty(b))
        return 0;
    VECTOR3 d;
    vec_sub(d, b->max, b->min);
    return 2 * (d[X] * d[Y] + d[Y] * d[Z] + d[Z] * d[X]);
}

bool bbox_intersect(const bbox_t *b, const ray_t *r, real tmin, real tmax,
                    real *t0, real *t1)
{
    real lo = tmin, hi = tmax;
    for (int i = 0; i < 3; i++) {
        real inv = 1 / r->d[i];
        real tn = (b->min[i] - r->o[i]) * inv;
        real tf = (b->max[i] - r->o[i]) * inv;
        if (tn > tf) {
            real s = tn; tn = tf; tf = s;
        }
        /* 0 * inf = NaN when the origin lies on a slab plane and the ray
         * runs inside it: the ray is then in the slab for every t. */
        if (tn != tn)
            tn = -(real)INFINITY;
        if (tf != tf)
            tf = (real)INFINITY;
        tf *= 1 + 2 * ray_gamma(3);
        lo = tn > lo ? tn : lo;
        hi = tf < hi ? tf : hi;
        if (lo > hi)
            return false;
    }
    if (t0)
        *t0 = lo;
    if (t1)
        *t1 = hi;
    return true;
}
